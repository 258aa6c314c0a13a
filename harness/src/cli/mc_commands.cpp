// mc_commands.cpp: `kestrel mc` and `kestrel mc merge` (docs/monte-carlo.md).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/command_util.h"
#include "harness/cli/commands.h"
#include "harness/mc/monte_carlo.h"
#include "harness/mc/mc_journal.h"
#include "harness/drive/run_scenario.h"
#include "harness/output/results_dir.h"
#include "harness/core/run.h"
#include "scenario/json_util.h"
#include "mc/mc_comm.h"
#include "mc/mc_validate.h"

namespace harness {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string mc_manifest_text(const McPlan& plan, const std::string& source, const std::vector<Override>& ov,
                             const json& partition, const std::vector<uint64_t>& only, bool complete,
                             const json& record_hashes, const json& merged_from = nullptr)
{
  json j;
  j["kestrel_mc_manifest"] = kMcManifestFormat;
  j["kestrel_version"] = version();
  j["source"] = source;
  json o = json::array();
  for (const Override& x : ov) o.push_back(x.path + "=" + x.value);
  j["overrides"] = o;
  j["master_seed"] = plan.master_seed;
  j["runs"] = plan.runs;
  j["partition"] = partition;
  j["only"] = only;
  j["complete"] = complete;
  j["runs_done"] = record_hashes.size();
  if (!merged_from.is_null()) j["merged_from"] = merged_from;
  j["scenario"] = scenario_to_json(plan.nominal);
  if (plan.from) {  // kestrel mc --from: every run starts from this checkpoint
    j["from_checkpoint"] = {{"path", plan.from->path}, {"fnv1a64", hex64(plan.from->fnv1a64)}, {"tick", plan.from->info.tick}};
  }
  // what `mc merge` checks a shard against (mc_validate.h)
  j["scenario_fnv1a64"] = mc_scenario_hash(j["scenario"]);
  j["record_fnv1a64"] = record_hashes;  // [index, mc_record_hash] per finished run
  return j.dump(2) + "\n";
}

std::string duration_text(double s)
{
  std::ostringstream o;
  if (!(s >= 0.0) || s > 1e7) return "?";
  const long t = static_cast<long>(s + 0.5);
  if (t >= 3600) o << t / 3600 << "h" << std::setw(2) << std::setfill('0') << (t % 3600) / 60 << "m";
  else if (t >= 60) o << t / 60 << "m" << std::setw(2) << std::setfill('0') << t % 60 << "s";
  else o << t << "s";
  return o.str();
}

// "17,42,100-120" -> indices (sorted, unique); false on a malformed list.
bool parse_only(const std::string& s, uint64_t runs, std::vector<uint64_t>& out, std::string& why)
{
  std::set<uint64_t> got;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const size_t dash = item.find('-');
    auto num = [&](const std::string& t, uint64_t& v) {
      if (t.empty() || t.size() > 12 || t.find_first_not_of("0123456789") != std::string::npos) return false;
      v = std::stoull(t);
      return true;
    };
    uint64_t a = 0, b = 0;
    if (dash == std::string::npos ? !num(item, a) : !(num(item.substr(0, dash), a) && num(item.substr(dash + 1), b))) {
      why = "--only: '" + item + "' is not a run index or a range a-b";
      return false;
    }
    if (dash == std::string::npos) b = a;
    if (b < a || b >= runs) {
      why = "--only: '" + item + "' is outside the campaign's runs 0.." + std::to_string(runs - 1);
      return false;
    }
    if (b - a > 10000000) {
      why = "--only: range too long";
      return false;
    }
    for (uint64_t k = a; k <= b; ++k) got.insert(k);
  }
  if (got.empty()) {
    why = "--only: no run index given";
    return false;
  }
  out.assign(got.begin(), got.end());
  return true;
}

std::string shell_quote(const std::string& s)
{
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

std::string self_exe()
{
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("kestrel") : p.string();
}

template <class R>
int print_outcome(const std::vector<R>& recs, const std::string& dir, double wall, std::ostream& out)
{
  size_t failed = 0, invalid = 0;
  std::vector<uint64_t> bad;
  for (const R& r : recs) {
    if (r.pass) continue;
    ++failed;
    invalid += r.invalid ? 1 : 0;
    bad.push_back(r.index);
  }
  out << recs.size() << " runs in " << std::setprecision(4) << wall << " s: " << recs.size() - failed << " passed, "
      << failed << " failed";
  if (invalid) out << " (" << invalid << " invalid draws)";
  out << "\n";
  if (!bad.empty()) {
    out << "failing runs:";
    for (size_t i = 0; i < bad.size() && i < 20; ++i) out << " " << bad[i];
    if (bad.size() > 20) out << " ... (" << bad.size() - 20 << " more)";
    out << "\n";
  }
  out << "summary: " << (fs::path(dir) / "summary.csv").string() << "\n";
  out << "report: " << (fs::path(dir) / "mc_report.html").string() << "\n";
  return failed ? kExitMcFailures : kExitOk;
}

int write_slurm(const McCommand& c, const McPlan& plan, const std::vector<Override>& ov, std::ostream& out,
                std::ostream& err)
{
  const fs::path target = fs::absolute(c.out_dir);
  const fs::path sdir = fs::path(target.string() + ".slurm");
  std::error_code ec;
  if (fs::exists(sdir, ec) && !c.force) {
    err << "kestrel: " << sdir.string() << " exists; use --force to rewrite the batch scripts\n";
    return kExitRefused;
  }
  fs::create_directories(sdir / "logs", ec);
  if (ec) {
    err << "kestrel: cannot create " << sdir.string() << ": " << ec.message() << "\n";
    return kExitOutput;
  }
  const unsigned n = c.slurm_tasks;
  const std::string exe = self_exe();
  const std::string scen = (sdir / "scenario.json").string();
  try {
    write_text(scen, manifest_text(plan.nominal, ov));
    std::ostringstream a;
    a << "#!/bin/bash\n"
      << "# Kestrel Monte Carlo: " << plan.runs << " runs of " << plan.nominal.name << " (master seed "
      << plan.master_seed << ") as a Slurm array of " << n << " shards.\n"
      << "# Submit with submit.sh (the array, then the merge once every shard succeeded).\n"
      << "#SBATCH --job-name=kestrel-mc-" << plan.nominal.name << "\n"
      << "#SBATCH --array=0-" << n - 1 << "\n"
      << "#SBATCH --ntasks=1\n"
      << "#SBATCH --cpus-per-task=" << c.jobs << "\n"
      << "#SBATCH --output=" << (sdir / "logs" / "shard-%a.out").string() << "\n"
      << "# exit 6 (the shard ran; some runs failed their criteria) is a result, not a job failure\n"
      << shell_quote(exe) << " mc " << shell_quote(scen) << " --runs " << plan.runs << " --seed "
      << plan.master_seed << " -j " << c.jobs << " --force --shard \"${SLURM_ARRAY_TASK_ID}/" << n << "\" -o "
      << shell_quote((sdir / "shards").string()) << "/shard-\"${SLURM_ARRAY_TASK_ID}\"\n"
      << "rc=$?\n[ \"$rc\" -eq 6 ] && exit 0\nexit \"$rc\"\n";
    write_text((sdir / "array.sbatch").string(), a.str());
    std::ostringstream m;
    m << "#!/bin/bash\n"
      << "# Kestrel Monte Carlo: joins the shards of array.sbatch into " << target.string() << "\n"
      << "#SBATCH --job-name=kestrel-mc-merge\n"
      << "#SBATCH --ntasks=1\n"
      << "#SBATCH --output=" << (sdir / "logs" / "merge.out").string() << "\n"
      << "exec " << shell_quote(exe) << " mc merge --force -o " << shell_quote(target.string()) << " "
      << shell_quote((sdir / "shards").string()) << "/shard-*\n";
    write_text((sdir / "merge.sbatch").string(), m.str());
    std::ostringstream s;
    s << "#!/bin/sh\n# Submits the shards, then the merge (after every shard succeeded).\nset -e\n"
      << "cd " << shell_quote(sdir.string()) << "\n"
      << "jid=$(sbatch --parsable array.sbatch)\njid=${jid%%;*}\n"
      << "sbatch --parsable --dependency=afterok:\"$jid\" merge.sbatch\n";
    write_text((sdir / "submit.sh").string(), s.str());
    fs::permissions(sdir / "submit.sh", fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  } catch (const std::exception& e) {
    err << "kestrel: output error: " << e.what() << "\n";
    return kExitOutput;
  }
  out << "Slurm batch scripts for " << plan.runs << " runs in " << n << " shards: " << sdir.string() << "\n"
      << "  submit: " << (sdir / "submit.sh").string() << "   (array.sbatch, then merge.sbatch into "
      << target.string() << ")\n";
  return kExitOk;
}

// The campaign's plan from the command (--set, --seed, --runs); an exit
// code when the scenario is refused.
std::optional<int> load_plan(const McCommand& c, std::vector<Override>& ov, McPlan& plan, std::ostream& rerr)
{
  if (!parse_sets(c.sets, ov, rerr)) return kExitUsage;
  if (!c.from.empty() && (c.shard_count > 1 || c.slurm_tasks > 0 || !c.resume.empty())) {
    rerr << "kestrel: --from runs in one process (threads) or under mpirun; not with --shard, --slurm or --resume\n";
    return kExitUsage;
  }
  try {
    const Scenario sc = load_scenario(c.scenario, ov);
    if (!sc.monte_carlo) {
      rerr << c.scenario << ": no monte_carlo section: nothing to disperse (docs/monte-carlo.md)\n";
      return kExitInvalidScenario;
    }
    plan = make_mc_plan(sc, c.seed ? *c.seed : sc.monte_carlo->seed, c.runs ? *c.runs : sc.monte_carlo->runs);
    if (!c.from.empty()) branch_mc_plan(plan, c.from);
  } catch (const ScenarioError& e) {
    print_issues(e, rerr);
    return kExitInvalidScenario;
  } catch (const CheckpointError& e) {
    rerr << "kestrel: --from: " << e.what() << "\n";
    return kExitInvalidScenario;
  }
  if (plan.runs == 0) {
    rerr << "kestrel: --runs must be at least 1\n";
    return kExitUsage;
  }
  return std::nullopt;
}

// The runs asked for (--only, else all of them).
std::optional<int> select_runs(const McCommand& c, const McPlan& plan, std::vector<uint64_t>& indices, std::ostream& rerr)
{
  if (c.only.empty()) {
    for (uint64_t k = 0; k < plan.runs; ++k) indices.push_back(k);
    return std::nullopt;
  }
  std::string why;
  if (parse_only(c.only, plan.runs, indices, why)) return std::nullopt;
  rerr << "kestrel: " << why << "\n";
  return kExitUsage;
}

// This process's slice: shard i of N, then rank r of P within it.
std::vector<uint64_t> my_runs(const McCommand& c, const McComm& comm, const std::vector<uint64_t>& indices)
{
  const uint64_t slots = static_cast<uint64_t>(c.shard_count) * static_cast<uint64_t>(comm.size());
  const uint64_t slot = static_cast<uint64_t>(c.shard_index) * static_cast<uint64_t>(comm.size()) +
                        static_cast<uint64_t>(comm.rank());
  std::vector<uint64_t> mine;
  for (uint64_t k : indices)
    if (k % slots == slot) mine.push_back(k);
  return mine;
}

// Rank 0 owns the results folder; the others write their runs into its
// working folder (a shared file system, as on any cluster).  Returns the
// working folder on every rank, "" (after a message) when it is refused.
std::string open_campaign_dir(const McComm& comm, const std::string& out_dir, bool force,
                              std::optional<ResultsDir>& rdir, int& code, std::ostream& rerr,
                              const std::function<std::string(ResultsDir&)>& prepare)
{
  std::string work, problem;
  code = kExitOk;
  if (comm.rank() == 0) {
    try {
      rdir.emplace(out_dir, force);
      problem = prepare(*rdir);
      if (problem.empty()) work = rdir->work().string();
      else code = kExitRefused;
    } catch (const ResultsDirRefused& e) {
      problem = e.what();
      code = kExitRefused;
    } catch (const std::exception& e) {
      problem = std::string("output error: ") + e.what();
      code = kExitOutput;
    }
  }
  work = comm.broadcast(problem.empty() ? work : std::string());
  if (work.empty()) {
    rerr << "kestrel: " << problem << "\n";
    if (code == kExitOk) code = kExitOutput;
  }
  return work;
}

// The progress bar of rank 0 (on err, from any worker thread).
std::function<void(const McProgress&)> progress_bar(std::ostream& err, const McComm& comm, std::mutex& pmu)
{
  return [&err, &comm, &pmu](const McProgress& p) {
    std::lock_guard<std::mutex> g(pmu);
    const double f = p.total ? static_cast<double>(p.done) / static_cast<double>(p.total) : 1.0;
    const int w = 30, filled = static_cast<int>(f * w);
    const double eta = p.done ? p.elapsed_s * static_cast<double>(p.total - p.done) / static_cast<double>(p.done) : -1.0;
    err << "\r[" << std::string(static_cast<size_t>(filled), '#') << std::string(static_cast<size_t>(w - filled), ' ')
        << "] " << p.done << "/" << p.total << " runs" << (comm.size() > 1 ? " (rank 0)" : "") << ", " << p.failed
        << " failed, " << duration_text(eta) << " left   " << std::flush;
  };
}

// Every rank's run states (and error, and stop) on rank 0, sorted by index:
// the records themselves are in the shared working folder's journal.  A
// state travels as a line "index flags" (no document per run: rank 0's
// memory stays flat in the number of runs).
std::vector<McRunState> gather_states(const McComm& comm, std::vector<McRunState> states, bool& stopped,
                                      std::string& run_error)
{
  if (!comm.active()) return states;  // one process: its states, sorted by index already
  std::string mine = json({{"error", run_error}, {"stopped", stopped}}).dump() + "\n";
  for (const McRunState& r : states)
    mine += std::to_string(r.index) + " " + std::to_string((r.pass ? 1 : 0) | (r.invalid ? 2 : 0) | (r.full ? 4 : 0)) + "\n";
  states.clear();
  const std::vector<std::string> parts = comm.gather(mine);
  std::vector<McRunState> all;
  for (const std::string& p : parts) {
    std::istringstream in(p);
    std::string head;
    std::getline(in, head);
    const json j = json::parse(head);
    if (!j.at("error").get<std::string>().empty() && run_error.empty()) run_error = j.at("error").get<std::string>();
    stopped = stopped || j.at("stopped").get<bool>();
    McRunState r;
    unsigned flags = 0;
    while (in >> r.index >> flags) {
      r.pass = flags & 1;
      r.invalid = flags & 2;
      r.full = flags & 4;
      all.push_back(r);
    }
  }
  std::sort(all.begin(), all.end(), [](const McRunState& a, const McRunState& b) { return a.index < b.index; });
  return all;
}

json partition_json(const McCommand& c)
{
  return c.shard_count > 1 ? json({{"shard", c.shard_index}, {"shards", c.shard_count}}) : json(nullptr);
}

std::vector<uint64_t> only_list(const McCommand& c, const std::vector<uint64_t>& indices)
{
  return c.only.empty() ? std::vector<uint64_t>{} : indices;
}

std::string run_folder_name(uint64_t k)
{
  char b[32];
  std::snprintf(b, sizeof b, "%06llu", static_cast<unsigned long long>(k));
  return b;
}

// --resume: the folders of earlier attempts at `target`: the target itself
// (a stopped campaign) and the working folders of killed ones.
std::vector<fs::path> resume_sources(const fs::path& target, const fs::path& work)
{
  std::vector<fs::path> out;
  std::error_code ec;
  if (fs::is_regular_file(target / "mc_manifest.json", ec)) out.push_back(target);
  const std::string pre = "." + target.filename().string() + ".kestrel-work-";
  for (const fs::directory_entry& e : fs::directory_iterator(target.parent_path(), ec))
    if (e.path() != work && e.path().filename().string().rfind(pre, 0) == 0 && e.is_directory(ec))
      out.push_back(e.path());
  return out;
}

// "" when the campaign manifest `m` of an earlier attempt is this
// campaign's (`want`), else what differs.
std::string resume_mismatch(const json& m, const json& want)
{
  for (const char* k : {"scenario", "master_seed", "runs", "partition", "only"}) {
    if (!m.contains(k)) return std::string("it has no '") + k + "'";
    if (m.at(k) != want.at(k)) {
      if (std::string(k) == "scenario") return "its scenario differs (another scenario file or --set)";
      return std::string("its ") + k + " is " + m.at(k).dump() + ", this command's is " + want.at(k).dump();
    }
  }
  return "";
}

// Moves the finished runs (record and run folder) of `src` into `work`.
void adopt_runs(const fs::path& src, const fs::path& work)
{
  fs::create_directories(work / "records");
  fs::create_directories(work / "runs");
  for (uint64_t k : mc_journal_indices(src)) {
    std::error_code ec;
    const fs::path run = work / "runs" / run_folder_name(k);
    if (!fs::exists(run, ec)) fs::rename(src / "runs" / run_folder_name(k), run, ec);  // absent: rerun below
    if (!fs::exists(mc_record_path(work, k), ec)) fs::rename(mc_record_path(src, k), mc_record_path(work, k), ec);
    if (ec) throw OutputError("moving run " + std::to_string(k) + " out of " + src.string() + ": " + ec.message());
  }
}

// Every record of the earlier attempts read as `mc merge` reads a shard's
// (mc_validate.h: no link followed, every field typed and sized to the
// campaign) and holding the run its name says, before anything moves.
// Returns a refusal naming the file and the field, or "".
std::string check_journals(const std::vector<fs::path>& dirs, const McRecordShape& shape)
{
  constexpr uint64_t kMaxRecordBytes = uint64_t(1) << 26;  // [B] one record (its thinned series)
  for (const fs::path& d : dirs)
    for (uint64_t k : mc_journal_indices(d)) {
      const fs::path f = mc_record_path(d, k);
      try {
        const std::vector<McRecord> r = read_mc_records(read_shard_file(f, kMaxRecordBytes), f.string(), shape);
        if (r.size() != 1 || r.front().index != k)
          return f.string() + ": holds " + std::to_string(r.size()) + " records, not run " + std::to_string(k) + " alone";
      } catch (const std::exception& e) {
        return e.what();
      }
    }
  return "";
}

// --resume into the new working folder: every earlier attempt checked
// against this campaign, then its finished runs moved in (a record whose run
// folder is missing is dropped: that run runs again).  Returns a refusal.
std::string adopt_earlier(const McCommand& c, const json& want, const McRecordShape& shape, ResultsDir& rdir,
                          std::vector<fs::path>& stale)
{
  const std::vector<fs::path> src = resume_sources(rdir.target(), rdir.work());
  std::vector<fs::path> usable;
  for (const fs::path& d : src) {
    json m;
    try {
      m = json::parse(read_shard_file(d / "mc_manifest.json", uint64_t(1) << 30));  // no link followed
    } catch (const std::exception&) {
      continue;  // a working folder killed before its manifest: no finished run in it
    }
    const std::string why = resume_mismatch(m, want);
    if (!why.empty()) return d.string() + " is not this campaign: " + why + "; not resuming";
    if (d == rdir.target() && m.value("complete", false) && !fs::exists(d / "records"))
      return c.resume + " is a complete campaign: nothing to resume";
    usable.push_back(d);
  }
  if (usable.empty()) return c.resume + ": no interrupted campaign there to resume";
  const std::string bad = check_journals(usable, shape);
  if (!bad.empty()) return bad + "; not resuming";
  for (const fs::path& d : usable) adopt_runs(d, rdir.work());
  for (uint64_t k : mc_journal_indices(rdir.work()))
    if (!fs::exists(rdir.work() / "runs" / run_folder_name(k))) fs::remove(mc_record_path(rdir.work(), k));
  for (const fs::path& d : src)
    if (d != rdir.target()) stale.push_back(d);
  return "";
}

// The campaign's files into its working folder, then the folder committed.
// (The journal, records/, stays in an incomplete campaign, for --resume.)
int write_campaign(const McCommand& c, const McPlan& plan, const std::vector<Override>& ov,
                   const std::vector<uint64_t>& indices, const std::vector<McRunState>& all, McSummaryInfo& info,
                   const std::string& work, ResultsDir& rdir, std::ostream& err)
{
  if (c.shard_count > 1) info.partition = "shard " + std::to_string(c.shard_index) + "/" + std::to_string(c.shard_count);
  try {
    const McJournalRecords records(work, all);
    write_mc_outputs(plan, records, info, work);
    json hashes = json::array();
    for (size_t i = 0; i < records.size(); ++i) {
      const McRecord r = records.record(i);
      hashes.push_back(json::array({r.index, mc_record_hash(r)}));
    }
    write_text((fs::path(work) / "mc_manifest.json").string(),
               mc_manifest_text(plan, c.scenario, ov, partition_json(c), only_list(c, indices), info.complete, hashes));
    if (info.complete) remove_mc_journal(work);
    rdir.commit();
  } catch (const std::exception& e) {
    err << "kestrel: output error: " << e.what() << "\n";
    return kExitOutput;
  }
  return kExitOk;
}

// What rank 0 does once the runs are in: the files, then the outcome.
int finish_campaign(const McCommand& c, const McPlan& plan, const std::vector<Override>& ov,
                    const std::vector<uint64_t>& indices, const std::vector<McRunState>& all, bool stopped, double wall,
                    const std::string& work, std::optional<ResultsDir>& rdir, std::ostream& out, std::ostream& err)
{
  McSummaryInfo info;
  info.source = c.scenario;
  for (const Override& o : ov) info.overrides.push_back(o.path + "=" + o.value);
  uint64_t planned = 0;
  for (uint64_t k : indices)
    if (k % c.shard_count == c.shard_index) ++planned;
  info.complete = !stopped && all.size() == planned;
  info.wall_seconds = wall;
  if (write_campaign(c, plan, ov, indices, all, info, work, *rdir, err) != kExitOk) {
    rdir->keep_work();
    err << "kestrel: nothing was written to " << c.out_dir << " (its previous contents, if any, are unchanged); the "
        << all.size() << " finished runs are kept in " << work << ": --resume " << c.out_dir << " continues\n";
    return kExitOutput;
  }
  if (stopped) {
    err << "kestrel: interrupted after " << all.size() << " of " << planned << " runs; the finished runs are in "
        << c.out_dir << ", marked incomplete: the same command with --resume " << c.out_dir
        << " runs the others\n";
    return kExitInterruptedBase + (c.stop ? c.stop->load() : 0);
  }
  return print_outcome(all, c.out_dir, wall, out);
}

}  // namespace

// --resume: how many of the campaign's runs (this shard's) are done.
void say_resuming(const McCommand& c, const std::string& work, const std::vector<uint64_t>& indices, std::ostream& err)
{
  const std::vector<uint64_t> have = mc_journal_indices(work);
  uint64_t planned = 0, done = 0;
  for (uint64_t k : indices) {
    if (k % c.shard_count != c.shard_index) continue;
    ++planned;
    done += std::binary_search(have.begin(), have.end(), k) ? 1 : 0;
  }
  err << "kestrel: resuming: " << done << " of " << planned << " runs done, " << planned - done << " to run\n";
}

// The campaign's working folder made ready on rank 0: its manifest first
// (marked incomplete: a killed campaign's folder says what it is), then,
// with --resume, the finished runs of the earlier attempts moved in.
std::function<std::string(ResultsDir&)> prepare_work(const McCommand& c, const McPlan& plan,
                                                    const std::vector<Override>& ov,
                                                    const std::vector<uint64_t>& indices,
                                                    std::vector<fs::path>& stale)
{
  return [&c, &plan, &ov, &indices, &stale](ResultsDir& rdir) {
    const std::string m = mc_manifest_text(plan, c.scenario, ov, partition_json(c), only_list(c, indices), false, json::array());
    write_file_durably(rdir.work() / "mc_manifest.json", m);
    return c.resume.empty() ? std::string() : adopt_earlier(c, json::parse(m), mc_record_shape(plan), rdir, stale);
  };
}

int cmd_mc(const McCommand& c0, std::ostream& out, std::ostream& err)
{
  McComm comm;  // MPI when started by mpirun
  const bool root = comm.rank() == 0;
  std::ostringstream sink;
  std::ostream& rerr = root ? err : sink;  // one rank speaks
  std::vector<Override> ov;
  McPlan plan;
  if (const std::optional<int> code = load_plan(c0, ov, plan, rerr)) return *code;
  std::vector<uint64_t> indices;
  if (const std::optional<int> code = select_runs(c0, plan, indices, rerr)) return *code;
  if (c0.slurm_tasks > 0) return root ? write_slurm(c0, plan, ov, out, err) : kExitOk;
  McCommand c = c0;
  auto same_folder = [](const std::string& a, const std::string& b) {
    auto norm = [](const std::string& p) { return (fs::absolute(p) / "").lexically_normal(); };
    return norm(a) == norm(b);
  };
  if (!c.resume.empty() && !c.out_dir.empty() && !same_folder(c.out_dir, c.resume)) {
    rerr << "kestrel: --resume " << c.resume << " continues that folder; -o names another one\n";
    return kExitUsage;
  }
  if (!c.resume.empty()) c.out_dir = c.resume;
  if (c.out_dir.empty()) c.out_dir = (fs::path("runs") / (plan.nominal.name + "_mc")).string();
  std::optional<ResultsDir> rdir;
  std::vector<fs::path> stale;  // --resume: earlier working folders, removed once the campaign is written
  int code = kExitOk;
  const std::string work = open_campaign_dir(comm, c.out_dir, c.force || !c.resume.empty(), rdir, code, rerr,
                                             prepare_work(c, plan, ov, indices, stale));
  if (work.empty()) return code;
  McRunOptions ro;
  ro.jobs = std::max(1u, c.jobs);
  ro.indices = my_runs(c, comm, indices);
  ro.stop = c.stop;
  ro.resume = !c.resume.empty();
  if (ro.resume && root) say_resuming(c, work, indices, rerr);
  std::mutex pmu;
  if (c.progress && root) ro.progress = progress_bar(err, comm, pmu);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<McRunState> states;
  bool stopped = false;
  std::string run_error;
  try {
    states = run_mc_journal(plan, work, ro, stopped);
  } catch (const std::exception& e) {
    run_error = e.what();
  }
  if (c.progress && root) err << "\n";
  const std::vector<McRunState> all = gather_states(comm, std::move(states), stopped, run_error);
  if (!root) return run_error.empty() ? kExitOk : kExitRunFailed;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!run_error.empty()) {
    rdir->keep_work();
    err << "kestrel: campaign failed: " << run_error << "\n";
    err << "kestrel: nothing was written to " << c.out_dir << "; the finished runs are kept in " << work
        << ": --resume " << c.out_dir << " continues once the cause is fixed\n";
    return kExitOutput;
  }
  const int rc = finish_campaign(c, plan, ov, indices, all, stopped, wall, work, rdir, out, err);
  if (rc != kExitOutput) {
    std::error_code ec;
    for (const fs::path& d : stale) fs::remove_all(d, ec);
  }
  return rc;
}

int cmd_mc_program(McCommand c, const std::string& shard, std::ostream& out, std::ostream& err)
{
  if (c.scenario.empty()) {
    err << "kestrel mc: a scenario file is required (or: kestrel mc merge -o DIR SHARD...)\n";
    return kExitUsage;
  }
  if (!shard.empty()) {
    unsigned long long i = 0, n = 0;
    char extra = 0;
    if (std::sscanf(shard.c_str(), "%llu/%llu%c", &i, &n, &extra) != 2 || n < 1 || i >= n || n > 100000) {
      err << "kestrel mc: --shard expects i/N with 0 <= i < N <= 100000, got '" << shard << "'\n";
      return kExitUsage;
    }
    c.shard_index = static_cast<uint32_t>(i);
    c.shard_count = static_cast<uint32_t>(n);
  }
  c.progress = isatty(STDERR_FILENO) != 0;
  c.stop = stop_on_signals();
  return cmd_mc(c, out, err);
}

namespace {

// The merged campaign folder: the shards' runs/ copied (no link followed),
// the manifest and outputs.  Nothing is in place until the commit.
void write_merged(const std::string& out_dir, const std::vector<std::string>& shards, bool force, const McShards& set)
{
  ResultsDir rdir(out_dir, force);
  const fs::path runs_dir = rdir.work() / "runs";
  fs::create_directories(runs_dir);
  for (size_t j = 0; j < shards.size(); ++j) copy_mc_runs(shards[j], set.runs[j], runs_dir);  // the shards stay as they were
  McSummaryInfo info;
  info.source = set.first.source;
  info.complete = true;
  for (const McRecord& r : set.records) info.wall_seconds += r.wall_seconds;
  std::vector<Override> ov;
  for (const std::string& o : set.first.overrides) ov.push_back(parse_override(o));
  json merged = json::array();
  for (const std::string& s : shards) merged.push_back(fs::absolute(s).string());
  write_text((rdir.work() / "mc_manifest.json").string(),
             mc_manifest_text(set.plan, info.source, ov, nullptr, set.only, true, mc_record_hashes(set.records), merged));
  write_mc_outputs(set.plan, set.records, info, rdir.work());
  rdir.commit();
}

}  // namespace

int cmd_mc_merge(const std::string& out_dir, const std::vector<std::string>& shards, bool force, std::ostream& out,
                 std::ostream& err)
{
  if (shards.empty()) {
    err << "kestrel: mc merge: no shard folders given\n";
    return kExitUsage;
  }
  McShards set;
  try {
    set = read_mc_shards(shards);  // every field checked against the campaign (docs/monte-carlo.md)
  } catch (const McShardError& e) {
    err << "kestrel: mc merge: " << e.what() << "\n";
    return kExitUsage;
  } catch (const ScenarioError& e) {
    print_issues(e, err);
    return kExitInvalidScenario;
  }
  try {
    write_merged(out_dir, shards, force, set);
  } catch (const McShardError& e) {  // a shard changed between the check and the copy
    err << "kestrel: mc merge: " << e.what() << "\n";
    return kExitUsage;
  } catch (const ResultsDirRefused& e) {
    err << "kestrel: " << e.what() << "\n";
    return kExitRefused;
  } catch (const std::exception& e) {
    err << "kestrel: output error: " << e.what() << "\n";
    return kExitOutput;
  }
  out << "merged " << shards.size() << " shards: ";
  double cpu = 0.0;
  for (const McRecord& r : set.records) cpu += r.wall_seconds;
  return print_outcome(set.records, out_dir, cpu, out);
}

}  // namespace harness

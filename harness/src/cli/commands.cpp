#include "harness/cli/commands.h"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <optional>
#include <sstream>

#include "cli/command_util.h"
#include "harness/mc/monte_carlo.h"
#include "harness/drive/run_scenario.h"
#include "harness/output/results_dir.h"
#include "harness/core/checkpoint.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

#ifndef KESTREL_SCENARIO_DIR
#define KESTREL_SCENARIO_DIR "scenarios"
#endif
// The installed scenarios, relative to the installed kestrel program's folder.
#ifndef KESTREL_INSTALLED_SCENARIO_DIR
#define KESTREL_INSTALLED_SCENARIO_DIR "../share/kestrel/scenarios"
#endif

namespace harness {

namespace fs = std::filesystem;

bool parse_sets(const std::vector<std::string>& sets, std::vector<Override>& out, std::ostream& err)
{
  for (const std::string& s : sets) {
    try {
      out.push_back(parse_override(s));
    } catch (const std::exception& e) {
      err << "kestrel: " << e.what() << "\n";
      return false;
    }
  }
  return true;
}

void print_issues(const ScenarioError& e, std::ostream& err)
{
  for (const ScenarioIssue& is : e.issues()) err << is.str() << "\n";
  err << "kestrel: scenario rejected (" << e.issues().size() << " problem" << (e.issues().size() == 1 ? "" : "s")
      << "); nothing was run\n";
}


std::string scenario_dir()
{
  if (const char* d = std::getenv("KESTREL_SCENARIO_DIR")) return d;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);  // Linux; elsewhere the next two
  if (!ec) {
    const fs::path installed = exe.parent_path() / KESTREL_INSTALLED_SCENARIO_DIR;
    if (fs::is_directory(installed, ec)) return installed.lexically_normal().string();
  }
  if (fs::is_directory(KESTREL_SCENARIO_DIR, ec)) return KESTREL_SCENARIO_DIR;
  return "scenarios";
}

std::string resolve_scenario(const std::string& arg)
{
  std::error_code ec;
  if (arg.empty() || fs::exists(arg, ec) || arg.find('/') != std::string::npos) return arg;
  const fs::path dir = scenario_dir();
  for (const std::string& name : {arg, arg + ".yaml", arg + ".yml"})
    if (fs::is_regular_file(dir / name, ec)) return (dir / name).string();
  return arg;
}

int cmd_schema(const std::string& out_file, std::ostream& out, std::ostream& err)
{
  const std::string text = scenario_json_schema_text();
  if (out_file.empty()) {
    out << text;
    return kExitOk;
  }
  std::ofstream f(out_file, std::ios::binary | std::ios::trunc);
  f << text;
  f.close();
  if (!f) {
    err << "kestrel: cannot write " << out_file << "\n";
    return kExitOutput;
  }
  return kExitOk;
}

int cmd_validate(const std::string& scenario, const std::vector<std::string>& sets, std::ostream& out,
                 std::ostream& err)
{
  std::vector<Override> ov;
  if (!parse_sets(sets, ov, err)) return kExitUsage;
  try {
    const Scenario sc = load_scenario(scenario, ov);
    check_run_configuration(sc);  // the plant and FSW checks of a run, no run storage
    if (sc.monte_carlo) {           // the campaign's criteria name recorded columns
      const McPlan plan = make_mc_plan(sc, sc.monte_carlo->seed, sc.monte_carlo->runs);
      out << scenario << ": monte_carlo: " << plan.runs << " runs, " << plan.drawn.size() << " drawn values, "
          << sc.monte_carlo->criteria.size() << " criteria\n";
    }
    for (const std::string& w : jitter_step_warnings(sc)) out << scenario << ": warning: " << w << "\n";
    out << scenario << ": ok (" << sc.name << ", " << sc.wheels.size() << " wheels, " << sc.thrusters.size()
        << " thrusters, " << sc.num_ticks() << " steps of " << sc.rates.dt << " s)\n";
    return kExitOk;
  } catch (const ScenarioError& e) {
    print_issues(e, err);
    return kExitInvalidScenario;
  } catch (const std::exception& e) {
    err << scenario << ": internal error: " << e.what() << "\n";
    return kExitRunFailed;
  }
}

int cmd_fsw_config(const std::string& scenario, const std::vector<std::string>& sets, const std::string& out_file,
                   std::ostream& out, std::ostream& err)
{
  std::vector<Override> ov;
  if (!parse_sets(sets, ov, err)) return kExitUsage;
  FswAcsConfig cfg;
  try {
    cfg = fsw_acs_config_of(load_scenario(scenario, ov));
  } catch (const ScenarioError& e) {
    print_issues(e, err);
    return kExitInvalidScenario;
  }
  std::vector<uint8_t> img(fsw_link_config_size());
  size_t len = 0;
  if (fsw_link_config_encode(&cfg, img.data(), img.size(), &len, nullptr) != FSW_OK) {
    err << "kestrel: cannot encode the FSW configuration image\n";
    return kExitRunFailed;
  }
  std::ofstream f(out_file, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(img.data()), static_cast<std::streamsize>(len));
  f.close();
  if (!f) {
    err << "kestrel: cannot write " << out_file << "\n";
    return kExitOutput;
  }
  out << out_file << ": FSW configuration image of " << scenario << " (" << len << " bytes, format "
      << FSW_LINK_CONFIG_VERSION << ")\n";
  return kExitOk;
}

RunOptions run_options_of(const RunCommand& c, const Scenario& sc, const std::vector<Override>& overrides)
{
  RunOptions opt;
  opt.out_dir = c.out_dir.empty() ? (fs::path("runs") / sc.name).string() : c.out_dir;
  opt.overrides = overrides;
  opt.force = c.force;
  opt.stop = c.stop;
  if (c.realtime) opt.realtime_scale = c.rt_scale;
  opt.fsw_link = c.fsw;
  opt.link = c.link;
  opt.control = c.control;
  return opt;
}

namespace {

// The scenario of a run command (--set applied, --csv); an exit code when
// it cannot be loaded.
std::optional<int> load_run_scenario(const RunCommand& c, Scenario& sc, std::vector<Override>& ov, std::ostream& err)
{
  if (!parse_sets(c.sets, ov, err)) return kExitUsage;
  try {
    sc = load_scenario(c.scenario, ov);
  } catch (const ScenarioError& e) {
    print_issues(e, err);
    return kExitInvalidScenario;
  }
  if (c.csv) sc.outputs.csv = true;
  for (const std::string& w : jitter_step_warnings(sc)) err << "kestrel: warning: " << w << "\n";
  return std::nullopt;
}

// Notices while running and the progress bar (on a terminal) on `err`.
void attach_messages(const RunCommand& c, RunOptions& opt, std::ostream& err)
{
  const bool bar = c.progress;
  opt.notice = [&err, bar](const std::string& msg) {
    if (bar) err << "\n";
    err << "kestrel: " << msg << "\n";
  };
  if (!bar) return;
  opt.progress = [&err, last_pct = -1](double f) mutable {
    const int pct = static_cast<int>(f * 100.0);
    if (pct == last_pct) return;
    last_pct = pct;
    const int w = 40, filled = pct * w / 100;
    err << "\r[" << std::string(static_cast<size_t>(filled), '#') << std::string(static_cast<size_t>(w - filled), ' ')
        << "] " << std::setw(3) << pct << "%" << std::flush;
  };
}

// run_scenario (or resume_scenario), its exceptions as exit codes (with
// their message on err).
std::optional<int> run_caught(const std::function<RunResult()>& go, const RunOptions& opt, bool bar, RunResult& r,
                              std::ostream& err)
{
  try {
    r = go();
    if (bar) err << "\n";
    return std::nullopt;
  } catch (const ScenarioError& e) {
    if (bar) err << "\n";
    print_issues(e, err);
    return kExitInvalidScenario;
  } catch (const ResultsDirRefused& e) {
    if (bar) err << "\n";
    err << "kestrel: " << e.what() << "\n";
    return kExitRefused;
  } catch (const CheckpointError& e) {
    if (bar) err << "\n";
    err << "kestrel: " << e.what() << "\n";
    return kExitRefused;
  } catch (const OutputError& e) {
    if (bar) err << "\n";
    err << "kestrel: output error: " << e.what() << "\n";
    err << "kestrel: nothing was written to " << opt.out_dir << " (its previous contents, if any, are unchanged)\n";
    return kExitOutput;
  } catch (const std::exception& e) {
    if (bar) err << "\n";
    err << "kestrel: run failed: " << e.what() << "\n";
    return kExitRunFailed;
  }
}

// The options --checkpoint-every and --resume do not take (a usage error).
std::string checkpoint_option_conflict(const RunCommand& c)
{
  if (c.checkpoint_every <= 0.0 && c.resume.empty()) return c.scenario.empty() ? "a scenario is required (or --resume DIR)" : "";
  const char* opt = c.resume.empty() ? "--checkpoint-every" : "--resume";
  if (!c.fsw.empty())
    return std::string(opt) + ": the flight software runs outside this process (--fsw " + c.fsw +
           "): its state is on the other side of the link, which a checkpoint cannot hold; refused";
  if (c.live.on || c.control) return std::string(opt) + " is not taken with --live";
  if (c.resume.empty()) return "";
  if (!c.out_dir.empty()) return "--resume DIR names the results folder; -o is not taken with it";
  if (c.force) return "--force is not taken with --resume (the run replaces what its first start would have)";
  if (c.scenario.empty() && (!c.sets.empty() || c.csv))
    return "with --resume, --set and --csv only check the checkpoint's scenario: give the scenario too";
  return "";
}

// The figures of a run that went to its end: speed, pacing, link, files.
void print_run(const RunCommand& c, const Scenario& sc, const RunOptions& opt, const RunResult& r, std::ostream& out,
               std::ostream& err)
{
  out << sc.name << ": " << sc.duration << " s simulated in " << std::setprecision(3) << r.wall_seconds
      << " s (real-time factor " << std::setprecision(4) << (r.wall_seconds > 0 ? sc.duration / r.wall_seconds : 0.0)
      << "x); final pointing error " << std::setprecision(4) << r.final_pointing_error_deg << " deg ("
      << describe(r.final_pointing_reference) << ")\n";
  if (r.max_jitter_step > kJitterStepLimit) err << "kestrel: warning: " << jitter_reached_warning(r.max_jitter_step) << "\n";
  if (r.paced)
    out << "paced at " << r.pacing.scale << "x real time: tick lateness p50 " << r.pacing.lateness_p50_s * 1e6
        << " us, p99 " << r.pacing.lateness_p99_s * 1e6 << " us, max " << r.pacing.lateness_max_s * 1e6 << " us, "
        << r.pacing.overruns << " overruns in " << r.pacing.ticks << " ticks, drift at the end "
        << r.pacing.drift_s * 1e6 << " us\n";
  if (r.linked)
    out << "FSW link (" << c.fsw << "): " << r.link.cycles << " cycles, " << r.link.sent << " sensor packets sent, "
        << r.link.lost << " lost, " << r.link.corrupted << " corrupted, " << r.link.missing
        << " cycles without a reply, " << r.link.rejected << " replies rejected; FSW end: " << r.link.fsw.rx_crc
        << " CRC rejections, " << r.link.fsw.rx_stale << " stale, " << r.link.fsw.missed << " missed cycles\n";
  out << "results: " << opt.out_dir << "\n";
  for (const auto& f : r.files)
    if (fs::path(f).filename() == "report.html") out << "report: " << f << "\n";
  for (const auto& f : r.files) out << "  " << f << "\n";
}

}  // namespace

int cmd_run(const RunCommand& c, std::ostream& out, std::ostream& err)
{
  const std::string conflict = checkpoint_option_conflict(c);
  if (!conflict.empty()) {
    err << "kestrel run: " << conflict << "\n";
    return kExitUsage;
  }
  std::vector<Override> ov;
  Scenario sc;
  if (!c.scenario.empty())
    if (const std::optional<int> code = load_run_scenario(c, sc, ov, err)) return *code;
  RunOptions opt = run_options_of(c, sc, ov);
  attach_messages(c, opt, err);
  RunResult r;
  std::function<RunResult()> go = [&] { return run_scenario(sc, opt); };
  if (!c.resume.empty()) {
    opt.out_dir = c.resume;
    go = [&, expected = c.scenario.empty() ? std::optional<Scenario>() : std::optional<Scenario>(sc)] {
      return resume_scenario(opt, expected ? &*expected : nullptr, sc);
    };
  }
  opt.checkpoint_every = c.checkpoint_every;
  if (const std::optional<int> code = run_caught(go, opt, c.progress, r, err)) return *code;
  if (r.stopped_by_signal != 0) {
    err << "kestrel: interrupted by " << r.status.stopped_by << " at t = " << r.status.t_reached << " s of "
        << sc.duration << " s; the results so far are in " << opt.out_dir << ", marked incomplete\n";
    return kExitInterruptedBase + r.stopped_by_signal;
  }
  if (!r.ok) {
    err << "kestrel: run failed: " << r.failure << "\n";
    for (const auto& f : r.files) err << "  partial results: " << f << "\n";
    return kExitRunFailed;
  }
  print_run(c, sc, opt, r, out, err);
  return kExitOk;
}

namespace {

std::atomic<int> g_stop{0};
static_assert(std::atomic<int>::is_always_lock_free, "signal handler needs a lock-free flag");

extern "C" void on_stop_signal(int sig)
{
  g_stop.store(sig);
}

}  // namespace

const std::atomic<int>* stop_on_signals()
{
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sa.sa_flags = SA_RESETHAND;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  return &g_stop;
}

int cmd_list(const std::string& dir, std::ostream& out, std::ostream& err)
{
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    err << "kestrel: no scenario directory '" << dir << "'\n";
    return kExitUsage;
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".yaml" || e.path().extension() == ".yml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& p : files) {
    try {
      const Scenario sc = load_scenario(p.string());
      out << std::left << std::setw(28) << p.filename().string() << " " << sc.description << "\n";
    } catch (const ScenarioError& e) {
      out << std::left << std::setw(28) << p.filename().string() << " (invalid: " << e.issues().size()
          << " problems; run kestrel validate)\n";
    }
  }
  out << "(" << files.size() << " scenarios in " << dir << "; run one by its name: kestrel run NAME)\n";
  return kExitOk;
}

}  // namespace harness

// mc_campaign.cpp: the plan, the per-run metrics and the runs of a Monte
// Carlo campaign (harness/monte_carlo.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include "harness/mc/monte_carlo.h"
#include "harness/mc/mc_journal.h"
#include "harness/drive/run_scenario.h"
#include "harness/drive/run_steps.h"
#include "harness/core/run.h"
#include "scenario/mc_draw.h"

namespace harness {

namespace fs = std::filesystem;

namespace {

// The recorded rows of a run reduced to the plan's metrics and thinned
// series, streaming (memory bounded for any duration).
class McSink : public RecordSink {
 public:
  // a run branched from a checkpoint is handed the rows from the checkpoint's sink_rows on
  explicit McSink(const McPlan& plan)
      : plan_(plan), metrics_(plan.metrics), first_row_(plan.from ? plan.from->info.sink_rows : 0)
  {
  }

  void begin(const RecordLayout& layout, uint64_t expected_rows) override
  {
    metrics_.begin(layout, expected_rows);
    series_cols_.clear();
    for (const std::string& c : plan_.series_columns) {
      const MetricSelection s = select_columns(layout, c);
      series_cols_.push_back(s.cols.empty() ? SIZE_MAX : s.cols.front());
    }
    series_.assign(plan_.series_rows.size() * plan_.series_columns.size(), std::nanf(""));
    ncols_ = layout.columns.size();
    row_ = first_row_;
    next_sample_ = 0;
    while (next_sample_ < plan_.series_rows.size() && plan_.series_rows[next_sample_] < row_) ++next_sample_;
  }

  void write(const double* rows, size_t n) override
  {
    metrics_.write(rows, n);
    for (size_t r = 0; r < n; ++r, ++row_) {
      const double* x = rows + r * ncols_;
      if (next_sample_ < plan_.series_rows.size() && row_ == plan_.series_rows[next_sample_]) {
        for (size_t c = 0; c < series_cols_.size(); ++c)
          if (series_cols_[c] != SIZE_MAX)
            series_[next_sample_ * series_cols_.size() + c] = static_cast<float>(x[series_cols_[c]]);
        ++next_sample_;
      }
    }
  }

  void end(bool) override {}

  std::vector<double> metrics() const { return metrics_.values(); }
  std::vector<float> series() const { return series_; }

 private:
  const McPlan& plan_;
  MetricSink metrics_;
  std::vector<size_t> series_cols_;
  std::vector<float> series_;
  size_t ncols_ = 0;
  const uint64_t first_row_;
  uint64_t row_ = 0;
  size_t next_sample_ = 0;
};

}  // namespace

namespace {

void require_monte_carlo(const Scenario& nominal)
{
  if (nominal.monte_carlo) return;
  ScenarioIssue is;
  is.file = nominal.source_file;
  is.key = "monte_carlo";
  is.message = "the scenario has no monte_carlo section (docs/monte-carlo.md)";
  throw ScenarioError({is});
}

// The metrics every campaign records (those the layout has columns for).
void add_default_metrics(McPlan& p, const RecordLayout& l)
{
  auto add = [&](const std::string& name, const std::string& column, const std::string& stat, const std::string& what) {
    const MetricSelection s = select_columns(l, column);
    if (s.cols.empty()) return;
    McMetric m;
    m.col = {name, stat == "error_count" ? "-" : unit_of(l, s), what};
    m.column = column;
    m.stat = stat;
    p.metrics.push_back(m);
  };
  add("pointing_error_final", "pointing_error_deg", "final", "pointing error at the end");
  add("omega_max", "omega_BN_B", "max", "largest body rate |omega_BN_B|");
  add("wheel_speed_max", "wheel_speed_rpm_*", "max_abs", "largest wheel speed, any wheel");
  add("propellant_used", "propellant_kg", "drop", "propellant used");
  add("fsw_errors", "fsw_status", "error_count", "recorded rows with an FSW error status");
}

// The thinned channels (what the campaign report overlays) and the recorded
// rows they sample.
void add_series(McPlan& p, const RecordLayout& l, uint64_t rows)
{
  auto channel = [&](const std::string& name, const std::string& column) {
    const MetricSelection s = select_columns(l, column);
    if (s.cols.empty()) return;
    std::vector<std::string> cols;
    for (size_t c : s.cols) cols.push_back(l.columns[c].name);
    for (const std::string& c : cols) p.series_columns.push_back(c);
    p.channels.emplace_back(name, cols);
    p.channel_units.push_back(unit_of(l, s));
  };
  channel("pointing_error", "pointing_error_deg");
  channel("omega_BN_B", "omega_BN_B");
  channel("wheel_speed", "wheel_speed_rpm_*");
  channel("thruster_force", "thruster_force_*");
  channel("propellant", "propellant_kg");
  const uint64_t S = std::min<uint64_t>(p.nominal.monte_carlo->retention.thin_samples, rows);
  const double record_dt = p.nominal.rates.dt * p.nominal.rates.record_divisor;
  for (uint64_t j = 0; j < S; ++j) {
    const uint64_t r = S > 1 ? (j * (rows - 1) + (S - 1) / 2) / (S - 1) : 0;
    if (!p.series_rows.empty() && r == p.series_rows.back()) continue;
    p.series_rows.push_back(r);
    p.series_t.push_back(static_cast<double>(r) * record_dt);
  }
}

}  // namespace

McPlan make_mc_plan(const Scenario& nominal, uint64_t master_seed, uint64_t runs)
{
  require_monte_carlo(nominal);
  McPlan p;
  p.nominal = nominal;
  p.master_seed = master_seed;
  p.runs = runs;
  p.bound = std::make_shared<const McBinding>(bind_campaign(nominal));
  p.drawn = p.bound->columns;
  // The recorded layout: the nominal run's (a draw changes values, not columns).
  Scenario probe = nominal;
  probe.monte_carlo.reset();
  RunConfig rc;
  rc.keep_in_memory = false;
  const Run run(probe, std::move(rc));
  const RecordLayout& l = run.recorder().layout();
  add_default_metrics(p, l);
  for (McMetric& m : criterion_metrics(nominal, l)) p.metrics.push_back(std::move(m));
  add_series(p, l, run.recorder().capacity());
  return p;
}

namespace {

// An invalid draw's folder: its manifest only.
void write_draw_manifest(const fs::path& dir, const Scenario& sc)
{
  fs::create_directories(dir);
  write_text((dir / "manifest.json").string(), manifest_text(sc, {}));
}

// A run with full results: run_scenario() into dir, the campaign's sink fed too.
RunResult run_full(const Scenario& sc, const fs::path& dir, McSink& sink, const std::atomic<int>* stop)
{
  RunOptions o;
  o.out_dir = dir.string();
  o.force = true;  // the folder holds at most this run's manifest (a retention rerun)
  o.extra_sinks.push_back(&sink);
  o.stop = stop;
  const RunResult r = run_scenario(sc, o);
  // the run folder's lock file: no other process writes into a campaign's runs/
  std::error_code ec;
  fs::remove(dir.parent_path() / ("." + dir.filename().string() + ".kestrel-lock"), ec);
  return r;
}

// A run without files but its manifest (with how it ended): the same steps
// as run_scenario(), the campaign's sink the only one.
RunResult run_light(const Scenario& sc, const Branch* from, const fs::path& dir, McSink& sink,
                    const std::atomic<int>* stop)
{
  RunOptions o;
  o.stop = stop;
  RunResult r;
  RunOutputs outputs("", false);
  RunPacing pacing;
  RunConfig rc;
  rc.keep_in_memory = false;
  if (from) rc.accept_events = branch_accepts_events(*from);
  Run run(sc, std::move(rc));
  outputs.open(run, {}, {&sink});
  if (from) start_branch(run, *from);
  drive(run, o, pacing, r);
  finish_run(run, nullptr, r);
  fs::create_directories(dir);
  write_text((dir / "manifest.json").string(), manifest_text(sc, {}, &r.status));
  return r;
}

// A drawn run to its metrics: full results (run_scenario) or the light run.
void run_draw(const McPlan& plan, const Scenario& sc, const fs::path& dir, bool full, const std::atomic<int>* stop,
              McRecord& rec)
{
  McSink sink(plan);
  std::string failure;
  try {
    const RunResult r = full ? run_full(sc, dir, sink, stop) : run_light(sc, plan.from.get(), dir, sink, stop);
    rec.interrupted = r.stopped_by_signal != 0;
    failure = r.failure;
    rec.complete = r.status.complete;
    rec.full = full;
  } catch (const ScenarioError& e) {  // a configuration the plant or FSW refuses: an invalid draw
    const ScenarioIssue& is = e.issues().front();
    rec.invalid = true;
    rec.reason = "invalid draw: " + is.key + ": " + is.message;
    write_draw_manifest(dir, sc);
  }
  if (rec.interrupted || rec.invalid) return;
  rec.metrics = sink.metrics();
  rec.series = sink.series();
  if (!rec.complete) rec.reason = "run failed: " + (failure.empty() ? std::string("incomplete") : failure);
}

// The first criterion a run's metrics fail ("" : all pass).
std::string failed_criterion(const McPlan& plan, const std::vector<double>& metrics)
{
  for (size_t m = 0; m < plan.metrics.size(); ++m) {
    if (plan.metrics[m].criterion < 0) continue;
    const std::string f = criterion_failure(plan.metrics[m], metrics[m]);
    if (!f.empty()) return f;
  }
  return "";
}

}  // namespace

McRecord run_mc_one(const McPlan& plan, uint64_t k, const fs::path& dir, bool full, const std::atomic<int>* stop)
{
  const auto t0 = std::chrono::steady_clock::now();
  McRecord rec;
  rec.index = k;
  // the dispersions bound when the campaign was planned (a plan made by hand binds per run)
  McDraw d = plan.bound ? draw_run(plan.nominal, *plan.bound, plan.master_seed, k, false)
                        : draw_run(plan.nominal, plan.master_seed, k, false);
  // A light run builds its plant and FSW once: its Run makes the plant and
  // FSW check (same builders, same order, same first ScenarioError, caught
  // by run_draw as an invalid draw).  A full run or a branched one checks
  // first: run_scenario would have made its folder, branch_draw reads the
  // checked scenario.
  if (d.invalid.empty()) check_drawn_scenario(d, full || plan.from != nullptr);
  rec.seed = d.sc.seed;
  rec.drawn = d.drawn;
  rec.metrics.assign(plan.metrics.size(), NAN);
  rec.series.assign(plan.series_rows.size() * plan.series_columns.size(), std::nanf(""));
  d.sc.source_file = plan.nominal.source_file;
  if (plan.from && d.invalid.empty()) d.invalid = branch_draw(plan, d.sc);  // --from: starts from the checkpoint
  if (!d.invalid.empty()) {
    rec.invalid = true;
    rec.reason = "invalid draw: " + d.invalid;
    write_draw_manifest(dir, d.sc);
  } else {
    run_draw(plan, d.sc, dir, full, stop, rec);
    if (rec.interrupted) return rec;
  }
  if (rec.reason.empty()) rec.reason = failed_criterion(plan, rec.metrics);
  rec.pass = rec.reason.empty();
  rec.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rec;
}

namespace {
std::string run_dir_name(uint64_t k)
{
  char b[32];
  std::snprintf(b, sizeof b, "%06llu", static_cast<unsigned long long>(k));
  return b;
}

bool same_metrics(const McRecord& a, const McRecord& b)
{
  if (a.metrics.size() != b.metrics.size()) return false;
  for (size_t i = 0; i < a.metrics.size(); ++i)
    if (!(a.metrics[i] == b.metrics[i] || (std::isnan(a.metrics[i]) && std::isnan(b.metrics[i])))) return false;
  return true;
}
}  // namespace

namespace {

// The runs of one process: worker threads over a list of slots (positions
// in McRunOptions::indices), each finished run's record written to the
// journal (dir/records) as it finishes, and the retention of full results.
// Only each slot's state is held in memory.
class McRunner {
 public:
  McRunner(const McPlan& plan, const fs::path& dir, const McRunOptions& opt)
      : plan_(plan), ret_(plan.nominal.monte_carlo->retention), dir_(dir), runs_(dir / "runs"), opt_(opt),
        state_(opt.indices.size()), done_(opt.indices.size(), 0), t0_(std::chrono::steady_clock::now()),
        journal_(dir, opt.commit_seconds)
  {
    fs::create_directories(runs_);
    fs::create_directories(dir_ / "records");
    prog_.total = opt.indices.size();
    if (opt.resume)
      load_journal();
    else
      clear_journal();
  }

  // The slots, on opt.jobs threads (the first pass, or the reruns of
  // failing runs for their full results).  Throws a worker's exception.
  void work(bool rerun_pass, const std::vector<size_t>& todo)
  {
    std::atomic<size_t> at{0};
    auto body = [&]() {
      for (;;) {
        if (stop_asked() || failed()) return;
        const size_t j = at.fetch_add(1);
        if (j >= todo.size()) return;
        try {
          if (rerun_pass)
            rerun_full(todo[j]);
          else if (!run_slot(todo[j]))
            return;
        } catch (const std::exception& e) {
          std::lock_guard<std::mutex> g(mu_);
          if (error_.empty()) error_ = "run " + std::to_string(opt_.indices[todo[j]]) + ": " + e.what();
          return;
        }
      }
    };
    const unsigned n = std::max(1u, std::min<unsigned>(opt_.jobs, static_cast<unsigned>(todo.size())));
    std::vector<std::thread> th;
    for (unsigned i = 1; i < n; ++i) th.emplace_back(body);
    body();
    for (std::thread& t : th) t.join();
    journal_.commit();  // the finished runs' records, also when a run ended the campaign
    if (!error_.empty()) throw std::runtime_error(error_);
  }

  // The slots still to run (none done: a fresh campaign; --resume: those
  // without a record).
  std::vector<size_t> pending() const
  {
    std::vector<size_t> todo;
    for (size_t slot = 0; slot < done_.size(); ++slot)
      if (!done_[slot]) todo.push_back(slot);
    return todo;
  }

  // Retention, exact and independent of the threads (and of a campaign's
  // interruptions): the first max_failing failing runs by index keep full
  // results (returns those that have none yet, to rerun), the others keep
  // their manifest only.
  std::vector<size_t> retain(const std::vector<size_t>& order)
  {
    std::vector<size_t> rerun;
    uint32_t n_fail = 0;
    for (size_t slot : order) {
      McRunState& r = state_[slot];
      if (!done_[slot] || r.pass || r.invalid || opt_.indices[slot] < ret_.keep_first) continue;
      if (n_fail++ < ret_.max_failing) {
        if (!r.full) rerun.push_back(slot);
      } else if (r.full) {  // beyond the first max_failing: the manifest only
        McRecord rec = read_mc_record(mc_record_path(dir_, r.index));
        rec.full = false;
        write_mc_record(dir_, rec);
        drop_all_but_manifest(runs_ / run_dir_name(opt_.indices[slot]));
        r.full = false;
      }
    }
    return rerun;
  }

  bool stop_asked() const { return opt_.stop && opt_.stop->load() != 0; }

  // The finished runs' states, in `order`.
  std::vector<McRunState> take(const std::vector<size_t>& order) const
  {
    std::vector<McRunState> res;
    for (size_t slot : order)
      if (done_[slot]) res.push_back(state_[slot]);
    return res;
  }

 private:
  bool failed()
  {
    std::lock_guard<std::mutex> g(mu_);
    return !error_.empty();
  }

  // Not resuming: this process's runs have no record (another process, an
  // MPI rank, may be writing its own into the same folder).
  void clear_journal()
  {
    std::vector<uint64_t> mine = opt_.indices;
    std::sort(mine.begin(), mine.end());
    for (uint64_t k : mc_journal_indices(dir_))
      if (std::binary_search(mine.begin(), mine.end(), k)) fs::remove(mc_record_path(dir_, k));
  }

  // --resume: the runs of this process that have a record already.
  void load_journal()
  {
    const std::vector<uint64_t> have = mc_journal_indices(dir_);
    for (size_t slot = 0; slot < opt_.indices.size(); ++slot) {
      const uint64_t k = opt_.indices[slot];
      if (!std::binary_search(have.begin(), have.end(), k)) continue;
      const McRecord r = read_mc_record(mc_record_path(dir_, k));
      if (r.index != k) throw std::runtime_error(mc_record_path(dir_, k).string() + ": holds run " + std::to_string(r.index));
      state_[slot] = mc_run_state(r);
      done_[slot] = 1;
      ++prog_.done;
      if (!r.pass) ++prog_.failed;
      if (!r.pass && !r.invalid && r.full && k >= ret_.keep_first) failing_full_.fetch_add(1);
    }
  }

  // A finished run's record to the journal (the first pass's committed
  // in groups, a replacement at once), then its state.
  void record(size_t slot, const McRecord& r, bool first_pass)
  {
    if (first_pass)
      journal_.add(r);
    else
      write_mc_record(dir_, r);
    std::lock_guard<std::mutex> g(mu_);
    state_[slot] = mc_run_state(r);
    if (!first_pass) return;
    done_[slot] = 1;
    ++prog_.done;
    if (!r.pass) ++prog_.failed;
    prog_.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    if (opt_.progress) opt_.progress(prog_);
  }

  // First pass of one run; false when it was interrupted (not part of the
  // campaign: no folder).  A failing run gets its full results at once, by
  // the same worker (the selection is made exact by index after the pass).
  bool run_slot(size_t slot)
  {
    const uint64_t k = opt_.indices[slot];
    const McRecord r = run_mc_one(plan_, k, runs_ / run_dir_name(k), k < ret_.keep_first, opt_.stop);
    if (r.interrupted) {
      std::error_code ec;
      fs::remove_all(runs_ / run_dir_name(k), ec);
      return false;
    }
    const bool keep = ret_.keep_failing && !r.pass && !r.invalid && !r.full && failing_full_.load() < ret_.max_failing;
    record(slot, r, true);
    if (keep) {
      failing_full_.fetch_add(1);
      rerun_full(slot);
    }
    return true;
  }

  // A failing run's full results: run k again through run_scenario; its
  // metrics must be the first pass's.
  void rerun_full(size_t slot)
  {
    const uint64_t k = opt_.indices[slot];
    journal_.commit();  // the first pass's record in place before it is read or replaced
    McRecord r = run_mc_one(plan_, k, runs_ / run_dir_name(k), true, opt_.stop);
    McRecord first = read_mc_record(mc_record_path(dir_, k));
    if (r.interrupted) {  // the first pass's record stays; the folder holds a partial rerun, marked incomplete
      if (first.full) {
        first.full = false;
        record(slot, first, false);
      }
      return;
    }
    if (!same_metrics(first, r) || first.pass != r.pass) {
      r.pass = false;
      r.reason = "NOT REPRODUCED: the full-results rerun gave other metrics than the first pass (" + first.reason + ")";
    }
    r.wall_seconds += first.wall_seconds;
    record(slot, r, false);
  }

  static void drop_all_but_manifest(const fs::path& d)
  {
    std::error_code ec;
    std::vector<fs::path> drop;  // listed first, removed after the listing
    for (const fs::directory_entry& e : fs::directory_iterator(d, ec))
      if (e.path().filename() != "manifest.json") drop.push_back(e.path());
    for (const fs::path& f : drop) fs::remove_all(f, ec);
  }

  const McPlan& plan_;
  const RetentionSpec& ret_;
  const fs::path dir_, runs_;
  const McRunOptions& opt_;
  std::vector<McRunState> state_;
  std::vector<char> done_;
  std::mutex mu_;
  McProgress prog_;
  const std::chrono::steady_clock::time_point t0_;
  std::string error_;                     // an exception of a worker (output error): ends the campaign
  std::atomic<uint32_t> failing_full_{0};  // failing runs given full results during the pass
  McJournalWriter journal_;               // the first pass's records, committed in groups
};

}  // namespace

std::vector<McRunState> run_mc_journal(const McPlan& plan, const fs::path& dir, const McRunOptions& opt, bool& stopped)
{
  McRunner runner(plan, dir, opt);
  // the longest-known first would balance better; index order keeps the
  // progress readable and the result does not depend on it
  runner.work(false, runner.pending());
  stopped = runner.stop_asked();
  std::vector<size_t> order(opt.indices.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return opt.indices[a] < opt.indices[b]; });
  if (!stopped && plan.nominal.monte_carlo->retention.keep_failing) {
    runner.work(true, runner.retain(order));
    stopped = runner.stop_asked();
  }
  return runner.take(order);
}

std::vector<McRecord> run_mc_runs(const McPlan& plan, const fs::path& dir, const McRunOptions& opt, bool& stopped)
{
  const std::vector<McRunState> states = run_mc_journal(plan, dir, opt, stopped);
  std::vector<McRecord> out;
  out.reserve(states.size());
  for (const McRunState& s : states) out.push_back(read_mc_record(mc_record_path(dir, s.index)));
  return out;
}

std::vector<size_t> mc_table_order(const McRecordSource& records)
{
  std::vector<size_t> o(records.size());
  for (size_t i = 0; i < o.size(); ++i) o[i] = i;
  auto rank = [&](size_t i) {
    const McRunState& s = records.state(i);
    return s.invalid ? 0 : s.pass ? 2 : 1;
  };
  std::stable_sort(o.begin(), o.end(), [&](size_t a, size_t b) {
    const int ra = rank(a), rb = rank(b);
    if (ra != rb) return ra < rb;
    return records.state(a).index < records.state(b).index;
  });
  return o;
}

std::vector<size_t> mc_table_order(const std::vector<McRecord>& records)
{
  return mc_table_order(McMemoryRecords(records));
}

}  // namespace harness

// run_scenario.cpp: a whole run into a results directory, streamed.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "harness/drive/run_checkpoints.h"
#include "harness/drive/run_scenario.h"
#include "harness/drive/branch.h"
#include "harness/drive/run_steps.h"
#include "harness/core/checkpoint.h"
#include "harness/link/pil.h"
#include "harness/output/results_dir.h"

#ifdef KESTREL_HAVE_REPORT
#include "report/report.hpp"
#endif

namespace harness {

namespace fs = std::filesystem;

namespace {

// A generous estimate of a run's output [bytes]: the HDF5 file uncompressed
// (deflate only makes it smaller), the CSV at ~25 characters a value, the
// report's bounded series twice (JSON and the HTML page), and 1 MiB of small
// files.
uint64_t output_estimate(const Run& run, const Scenario& sc)
{
  const uint64_t rows = run.recorder().capacity();
  const uint64_t cols = run.recorder().num_columns();
  uint64_t b = (1u << 20);
  if (sc.outputs.hdf5) b += rows * (cols + 1) * 8;
  if (sc.outputs.csv) b += rows * cols * 25;
  if (sc.outputs.report_data) {
    const uint64_t shown = std::min<uint64_t>(rows, 2 * ReportSink::kReportBuckets) * cols +
                           std::min<uint64_t>(rows, ReportSink::kSpectrumRows) * 5;
    b += 2 * shown * 25;
  }
  return b;
}

std::string signal_name(int s)
{
  switch (s) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "signal " + std::to_string(s);
  }
}

// The endpoint behind the link, with the options of this run
// (LinkOptions::for_run: the defaulting rules).
std::unique_ptr<FswEndpoint> make_remote_fsw(const Scenario& sc, const RunOptions& opt, RemoteFsw*& remote,
                                             std::function<double()> time_left)
{
  const LinkOptions lo =
      opt.link.for_run(sc.rates.dt * sc.rates.fsw_divisor, opt.realtime_scale, std::move(time_left));
  const FswAcsConfig fcfg = fsw_acs_config_of(sc);
  auto r = std::make_unique<RemoteFsw>(open_fsw_transport(opt.fsw_link, fcfg, lo), fcfg, lo);
  remote = r.get();
  return r;
}

// A threshold as written in a scenario (shortest text that reads back).
std::string fmt_number(double v)
{
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

void add_item(std::vector<SummaryItem>& v, const char* key, double value, const char* unit, const char* what)
{
  v.push_back({key, value, unit, what});
}

void add_pacing_items(std::vector<SummaryItem>& v, const PacingStats& p)
{
  add_item(v, "rt_scale", p.scale, "", "paced at this multiple of real time");
  add_item(v, "rt_lateness_p50", p.lateness_p50_s, "s", "tick wake-up after its deadline, median");
  add_item(v, "rt_lateness_p99", p.lateness_p99_s, "s", "99th percentile");
  add_item(v, "rt_lateness_max", p.lateness_max_s, "s", "maximum");
  add_item(v, "rt_overruns", static_cast<double>(p.overruns), "", "ticks whose work ended after the next deadline");
  add_item(v, "rt_drift", p.drift_s, "s", "last tick's lateness (absolute deadlines: no accumulation)");
  add_item(v, "rt_priority", p.realtime_priority ? 1 : 0, "", "1: SCHED_FIFO and locked memory");
}

void add_link_items(std::vector<SummaryItem>& v, const LinkCounters& l)
{
  const auto n = [](uint64_t x) { return static_cast<double>(x); };
  add_item(v, "link_cycles", n(l.cycles), "", "FSW cycles over the link");
  add_item(v, "link_sent", n(l.sent), "", "sensor packets sent (duplicates included)");
  add_item(v, "link_lost", n(l.lost), "", "dropped by the loss injector");
  add_item(v, "link_corrupted", n(l.corrupted), "", "sent with flipped bits");
  add_item(v, "link_missing", n(l.missing), "", "cycles without a reply (last command held or zero applied)");
  add_item(v, "link_rejected", n(l.rejected), "", "received packets the harness rejected");
  add_item(v, "link_fsw_rx_crc", n(l.fsw.rx_crc), "", "FSW end: packets rejected on CRC");
  add_item(v, "link_fsw_rx_stale", n(l.fsw.rx_stale), "", "FSW end: duplicate, old or out-of-order sensor packets");
  add_item(v, "link_fsw_missed", n(l.fsw.missed), "", "FSW end: control cycles without a sensor packet");
  add_item(v, "link_retransmits", n(l.retransmits), "", "lockstep over UDP: sensor packets sent again without a reply");
}

}  // namespace

// ---- the outputs --------------------------------------------------------

RunOutputs::RunOutputs(const std::string& out_dir, bool force)
{
  if (!out_dir.empty()) {
    dir_.emplace(out_dir, force);
    work_ = dir_->work();
  }
}

RunOutputs::RunOutputs(const std::string& out_dir, const std::string& marker)
{
  dir_.emplace(out_dir, marker);
  dir_->keep_work();  // a resume that fails leaves the folder as it found it, to be resumed again
  work_ = dir_->work();
}

void RunOutputs::write_file(const std::string& name, const std::string& text)
{
  write_text((work_ / name).string(), text);
  written_.push_back(name);
}

void RunOutputs::open(Run& run, const std::vector<Override>& overrides, const std::vector<RecordSink*>& extra)
{
  const auto add = [&run, this](RecordSink& s) {
    run.add_sink(s);
    sinks_.push_back(&s);
  };
  if (files()) {
    const Scenario& sc = run.scenario();
    dir_->require_free_space(output_estimate(run, sc));
    manifest_ = manifest_text(sc, overrides);
    write_file("manifest.json", manifest_);
    if (sc.outputs.hdf5) {
      h5_.emplace((work_ / "results.h5").string(), sc, manifest_);
      h5_->set_events(&run.events_applied());  // with the events added while running
      add(*h5_);
    }
    if (sc.outputs.csv) {
      csv_.emplace((work_ / "telemetry.csv").string());
      add(*csv_);
    }
    if (sc.outputs.report_data) {
      report_.emplace();
      add(*report_);
    }
    if (sc.monte_carlo && !sc.monte_carlo->criteria.empty()) {
      requirements_.emplace(criterion_metrics(sc, run.recorder().layout()));
      add(*requirements_);
    }
  }
  for (RecordSink* s : extra) add(*s);
}

void RunOutputs::write_report(const Run& run, const RunResult& res)
{
  const RunStory story{summary_items(run, res), res.warnings, res.requirements};
  const std::string data = report_data_text(run, *report_, &res.status, res.paced ? &res.pacing : nullptr, &story);
  write_file("report_data.json", data);
#ifdef KESTREL_HAVE_REPORT
  try {
    report::write_html(data, (work_ / "report.html").string());
  } catch (const std::exception& e) {
    throw OutputError(e.what());
  }
  written_.push_back("report.html");
#endif
}

void RunOutputs::write(const Run& run, RunResult& res, const std::vector<Override>& overrides)
{
  if (!files()) return;
  const Scenario& sc = run.scenario();
  if (requirements_) res.requirements = requirement_results(*requirements_);
  if (h5_) written_.push_back("results.h5");
  if (csv_) written_.push_back("telemetry.csv");
  if (report_) write_report(run, res);
  write_file("dataflow.dot", run.dataflow().to_dot(sc.name));
  std::ostringstream health;
  for (const std::string& l : run.fsw_health_lines()) health << l << "\n";
  write_file("fsw_health.txt", health.str());
  write_file("summary.txt", summary_text(res.status, sc.duration, summary_items(run, res), res.warnings));
  // the manifest again, now saying how the run ended
  // (run.scenario(): with the events the live view added, so it replays them)
  write_text((work_ / "manifest.json").string(), manifest_text(sc, overrides, &res.status));
  dir_->commit();
  for (const std::string& n : written_) res.files.push_back((dir_->target() / n).string());
}

// ---- pacing and the loop ------------------------------------------------

void RunPacing::pace_at(const Scenario& sc, double scale, const std::function<void(const std::string&)>& notice,
                       const std::atomic<int>* stop)
{
  if (!pacer_) {
    pacer_.emplace(sc.tick_ns(), scale);
    pacer_->set_stop(stop);
    const std::string w = pacer_->request_realtime();
    if (!w.empty() && notice) notice(w);
  } else {
    pacer_->restart(scale);
  }
  notice_every_ = std::max<uint64_t>(1, static_cast<uint64_t>(1e10 * scale / static_cast<double>(sc.tick_ns())));
}

double RunPacing::time_left() const
{
  return pacer_ ? pacer_->seconds_to(tick_ + 1) : std::numeric_limits<double>::infinity();
}

bool RunPacing::step(Run& run, const std::function<void(const std::string&)>& notice)
{
  const uint64_t k = run.tick();
  if (!pacer_->wait_for(k)) return true;  // stopped: the loop sees the flag
  tick_ = k;
  if (!run.step_ticks(1)) return false;
  pacer_->done(k);
  if ((k + 1) % notice_every_ == 0) {
    const uint64_t late = pacer_->take_new_overruns();
    if (late > 0 && notice)
      notice("cannot keep up: " + std::to_string(late) + " of the last " + std::to_string(notice_every_) +
             " ticks overran their deadline");
  }
  return true;
}

void drive(Run& run, const RunOptions& opt, RunPacing& pacing, RunResult& res, RunCheckpoints* checkpoints)
{
  const Scenario& sc = run.scenario();
  // chunks of at most 1000 ticks: a stop request is seen within milliseconds
  const uint64_t total = run.total_ticks();
  const uint64_t chunk = std::clamp<uint64_t>(total / 200, 1, 1000);
  const auto stop_asked = [&opt] { return opt.stop && opt.stop->load() != 0; };
  if (opt.realtime_scale > 0.0) pacing.pace_at(sc, opt.realtime_scale, opt.notice, opt.stop);
  if (opt.control) opt.control->started(run, opt.realtime_scale, opt.stop);
  const auto t0 = std::chrono::steady_clock::now();
  while (!run.done()) {
    if (stop_asked()) {
      res.stopped_by_signal = opt.stop->load();
      break;
    }
    uint64_t limit = chunk;
    if (opt.control) {  // commands enter here, at a tick boundary; a pause waits here
      double pace = 0.0;
      limit = std::min(chunk, opt.control->boundary(run, pace));
      if (pace > 0.0) pacing.pace_at(sc, pace, opt.notice, opt.stop);
      if (stop_asked()) continue;
    }
    if (checkpoints) limit = std::min(limit, checkpoints->boundary(run));
    if (pacing.on()) {  // one tick at a time, each at its deadline
      if (!pacing.step(run, opt.notice)) break;
      if (opt.progress && run.tick() % chunk == 0)
        opt.progress(static_cast<double>(run.tick()) / static_cast<double>(total));
      continue;
    }
    if (!run.step_ticks(limit)) break;
    if (opt.progress) opt.progress(static_cast<double>(run.tick()) / static_cast<double>(total));
  }
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (pacing.on()) {
    res.paced = true;
    res.pacing = pacing.stats();
  }
}

// ---- the end of a run ---------------------------------------------------

void finish_run(Run& run, const RemoteFsw* remote, RunResult& res)
{
  res.ticks = run.tick();
  res.sim_seconds = run.scenario().duration;
  res.failure = run.failure();
  res.ok = res.failure.empty() && res.stopped_by_signal == 0;
  // Results are written also for a failed or interrupted run (never lose
  // data): the rows recorded up to there are in the files, marked incomplete.
  run.finish();
  if (remote != nullptr) {
    res.linked = true;
    res.link = remote->counters();
  }
  res.final_pointing_error_deg = run.final_pointing_error_deg();
  res.final_pointing_reference = run.final_pointing_reference();
  res.max_jitter_step = run.max_jitter_step();
  if (res.max_jitter_step > kJitterStepLimit) res.warnings.push_back(jitter_reached_warning(res.max_jitter_step));
  RunStatus& st = res.status;
  st.complete = res.ok && run.done();
  st.ticks = run.tick();
  st.t_reached = run.recorder().rows() > 0 ? run.recorder().last_row()[0] : 0.0;
  st.stopped_by = res.stopped_by_signal ? signal_name(res.stopped_by_signal) : res.failure;
  st.events = run.events_applied();
}

std::vector<SummaryItem> summary_items(const Run& run, const RunResult& res)
{
  std::vector<SummaryItem> v;
  add_item(v, "complete", res.status.complete ? 1 : 0, "", "1: the run reached its duration");
  add_item(v, "t_reached", res.status.t_reached, "s", "time of the last recorded row");
  for (const SummaryItem& it : run.summary()) v.push_back(it);
  for (const RequirementResult& r : res.requirements)
    v.push_back({"requirement_" + r.name, r.value, r.unit == "-" ? "" : r.unit,
                 std::string(r.pass ? "PASS: " : "FAIL: ") + r.what + (r.below ? " below " : " above ") +
                     fmt_number(r.threshold)});
  if (res.paced) add_pacing_items(v, res.pacing);
  if (res.linked) add_link_items(v, res.link);
  return v;
}

std::string summary_text(const RunStatus& st, double duration, const std::vector<SummaryItem>& items,
                         const std::vector<std::string>& warnings)
{
  std::ostringstream summ;
  summ << std::setprecision(10);
  if (!st.complete)
    summ << "# INCOMPLETE: stopped" << (st.stopped_by.empty() ? "" : " (" + st.stopped_by + ")") << " at t = "
         << st.t_reached << " s of " << duration << " s\n";
  for (const std::string& w : warnings) summ << "# warning: " << w << "\n";
  for (const SummaryItem& it : items)
    summ << it.key << " = " << it.value << " " << it.unit << "    # " << it.what << "\n";
  return summ.str();
}

// ---- the whole run ------------------------------------------------------

namespace {

// A run into `outputs` (opened already); with `checkpoints`, checkpointed
// or continued from one; with `branch`, started from a campaign's checkpoint.
RunResult run_into(RunOutputs& outputs, const Scenario& sc, const RunOptions& opt, RunCheckpoints* checkpoints,
                   const Branch* branch)
{
  RunResult res;
  if (opt.notice)
    for (const std::string& n : outputs.notes()) opt.notice(n);
  res.warnings = jitter_step_warnings(sc);
  RunOptions o = opt;  // the notices while running are the run's warnings too
  o.notice = [&res, &opt](const std::string& msg) {
    res.warnings.push_back(msg);
    if (opt.notice) opt.notice(msg);
  };
  RunPacing pacing;
  RunConfig cfg;
  cfg.keep_in_memory = false;  // streamed: memory does not grow with the duration
  RemoteFsw* remote = nullptr;
  if (!opt.fsw_link.empty())
    cfg.fsw = make_remote_fsw(sc, opt, remote, [&pacing] { return pacing.time_left(); });
  cfg.accept_events = opt.control != nullptr;  // the live view's commands are events
  if (branch) cfg.accept_events = branch_accepts_events(*branch);
  Run run(sc, std::move(cfg));
  outputs.open(run, opt.overrides, opt.extra_sinks);
  if (opt.control && outputs.files()) opt.control->results_folder(outputs.work().string(), opt.out_dir);
  if (branch) start_branch(run, *branch);
  if (checkpoints) checkpoints->attach(run, outputs.sinks());
  drive(run, o, pacing, res, checkpoints);
  finish_run(run, remote, res);
  if (checkpoints) checkpoints->discard();  // not part of the results
  outputs.write(run, res, opt.overrides);
  if (opt.control) opt.control->ended(run, res);
  return res;
}

}  // namespace

RunResult run_scenario(const Scenario& sc, const RunOptions& opt)
{
  if (sc.from_checkpoint && opt.checkpoint_every > 0.0)
    throw std::invalid_argument("--checkpoint-every: a run started from a campaign's checkpoint (the manifest's "
                                "from_checkpoint) is not checkpointed again; refused");
  // a run that starts from a checkpoint: the file checked before the folder is made
  const std::shared_ptr<const Branch> branch = sc.from_checkpoint ? open_branch(sc) : nullptr;
  RunOutputs outputs(opt.out_dir, opt.force);  // lock, refuse or replace: before anything is simulated
  std::optional<RunCheckpoints> checkpoints;
  if (opt.checkpoint_every > 0.0 && outputs.files())
    checkpoints.emplace(outputs.work(), sc, opt.overrides, opt.checkpoint_every);
  return run_into(outputs, sc, opt, checkpoints ? &*checkpoints : nullptr, branch.get());
}

RunResult resume_scenario(const RunOptions& opt, const Scenario* expected, Scenario& resumed)
{
  RunOutputs outputs(opt.out_dir, std::string(RunCheckpoints::kCheckpointName));  // not the bool overload
  RunCheckpoints checkpoints(outputs.work());
  if (expected) {
    const std::string diff = first_difference(scenario_to_json_text(checkpoints.scenario()), scenario_to_json_text(*expected));
    if (!diff.empty())
      throw CheckpointError(opt.out_dir + ": its checkpoint is of scenario '" + checkpoints.scenario().name +
                            "', not of the one given ('" + expected->name + "'): refused (" + diff + ")");
  }
  resumed = checkpoints.scenario();
  RunOptions o = opt;
  o.overrides = checkpoints.overrides();
  o.checkpoint_every = checkpoints.every_seconds();
  return run_into(outputs, resumed, o, &checkpoints, nullptr);  // its state is the checkpoint's
}

}  // namespace harness

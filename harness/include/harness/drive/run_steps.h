// run_steps: the named steps of a run to files (harness_drive), shared by
// run_scenario() and by a Monte Carlo campaign's runs (mc_campaign.cpp):
//
//   RunOutputs outputs(dir, force);      the results folder, before anything runs
//   RunPacing pacing;                     wall-clock pacing (the link asks it too)
//   Run run(...);
//   outputs.open(run, ...);               manifest first, then the sinks
//   drive(run, opt, pacing, res);         the loop: pacer, run control, stop, progress
//   finish_run(run, remote, res);         Run::finish() and the run's status
//   outputs.write(run, res, overrides);   report data, summary.txt, the manifest again
//
// summary.txt is written from declared items (summary_items()): the run's
// own (Run::summary()), then the pacing and link figures, each a key, a
// value, a unit and a description.
#ifndef HARNESS_DRIVE_RUN_STEPS_H
#define HARNESS_DRIVE_RUN_STEPS_H

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/pacer.h"
#include "harness/core/run.h"
#include "harness/drive/run_scenario.h"
#include "harness/output/outputs.h"
#include "harness/output/results_dir.h"

namespace harness {

// The outputs of one run: its results folder and the sinks the scenario's
// outputs section chooses.
class RunOutputs {
 public:
  // Locks, refuses or replaces the results folder and creates its working
  // folder (results_dir.h): before anything is simulated.  out_dir "": no
  // files (open() then adds the extra sinks only, write() does nothing).
  RunOutputs(const std::string& out_dir, bool force);
  // Continuing a killed run: takes over its working folder, the one holding
  // `marker` (ResultsDir's resume constructor).
  RunOutputs(const std::string& out_dir, const std::string& marker);
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  bool files() const { return dir_.has_value(); }
  // The working folder (results_dir.h): what is written there appears in
  // the results folder when the run ends ("" without files).
  const std::filesystem::path& work() const { return work_; }
  // The sinks open() attached, in order (the extra ones last).
  const std::vector<RecordSink*>& sinks() const { return sinks_; }
  // What killed runs left beside the results folder (ResultsDir::notes()).
  std::vector<std::string> notes() const { return dir_ ? dir_->notes() : std::vector<std::string>(); }
  // Checks the free space for the run's output, writes the input record
  // first (manifest.json: a run killed outright leaves it in the working
  // folder), then adds the HDF5, CSV and report sinks the scenario asks for,
  // then `extra` (caller-owned: a campaign's metrics).
  void open(Run& run, const std::vector<Override>& overrides, const std::vector<RecordSink*>& extra);
  // After finish_run(): report_data.json (and report.html), dataflow.dot,
  // fsw_health.txt, summary.txt, the manifest again with how the run ended;
  // commits the folder and lists the files in res.files.
  void write(const Run& run, RunResult& res, const std::vector<Override>& overrides);

 private:
  void write_file(const std::string& name, const std::string& text);
  void write_report(const Run& run, const RunResult& res);

  std::optional<ResultsDir> dir_;
  std::filesystem::path work_;
  std::string manifest_;             // the input record (written first)
  std::vector<std::string> written_;  // names in the results folder, in order
  std::optional<Hdf5Sink> h5_;
  std::optional<CsvSink> csv_;
  std::optional<ReportSink> report_;
  std::optional<MetricSink> requirements_;  // the scenario's criteria, when it has some
  std::vector<RecordSink*> sinks_;
};

// Wall-clock pacing of a run (pacer.h).  Made before the run: the FSW link
// waits for a reply at most until the deadline of the tick after the one
// being computed (time_left()).
class RunPacing {
 public:
  bool on() const { return pacer_.has_value(); }
  // Starts pacing at `scale` times real time (asking for real-time priority,
  // its warning to `notice`), or restarts the deadlines at that scale.
  // A stop flag ends a wait for a deadline within Pacer::kSlice.
  void pace_at(const Scenario& sc, double scale, const std::function<void(const std::string&)>& notice,
               const std::atomic<int>* stop = nullptr);
  // [s] wall time left until the deadline of the tick after the one being
  // computed (+inf when not paced).
  double time_left() const;
  // One tick at its deadline: waits, steps, marks it done and notices
  // overruns (one notice per ~10 s of wall time at most).  False when the
  // run failed.  A stop flag set during the wait: nothing stepped, true
  // (the loop sees the flag).
  bool step(Run& run, const std::function<void(const std::string&)>& notice);
  PacingStats stats() const { return pacer_->stats(); }

 private:
  std::optional<Pacer> pacer_;
  uint64_t tick_ = 0;          // the tick being computed
  uint64_t notice_every_ = 1;  // ticks per ~10 s of wall time
};

// The loop: chunks of at most 1000 ticks (a stop request is seen within
// milliseconds), or one tick at a time when paced; the run control's
// boundary before each; progress between chunks.  Sets res.wall_seconds,
// res.stopped_by_signal and, when paced, res.paced and res.pacing.
class RunCheckpoints;  // harness/drive/run_checkpoints.h
// `checkpoints`: asked at every boundary (RunCheckpoints::boundary).
void drive(Run& run, const RunOptions& opt, RunPacing& pacing, RunResult& res, RunCheckpoints* checkpoints = nullptr);

// Run::finish() (the rows recorded so far are in the files, marked
// incomplete when the run did not end), then the run's figures and status
// in res; remote: the FSW behind the link (its counters), or null.
void finish_run(Run& run, const RemoteFsw* remote, RunResult& res);

// What summary.txt lists, in order: complete, t_reached, Run::summary(),
// the requirement lines (requirement_<name>: the measured value, PASS or
// FAIL in the description), the pacing figures (rt_*, paced runs) and the
// link figures (link_*, the FSW behind the link).
std::vector<SummaryItem> summary_items(const Run& run, const RunResult& res);
// summary.txt: "# INCOMPLETE..." when the run did not end, "# warning: ..."
// per warning, then one line per item: "key = value unit    # description"
// (10 significant digits).
std::string summary_text(const RunStatus& st, double duration, const std::vector<SummaryItem>& items,
                         const std::vector<std::string>& warnings = {});

}  // namespace harness

#endif  // HARNESS_DRIVE_RUN_STEPS_H

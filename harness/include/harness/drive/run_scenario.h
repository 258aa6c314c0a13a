// run_scenario: a whole run into a results folder (harness_drive): the
// results folder, the sinks, the pacing and the run control around a Run.
#ifndef HARNESS_DRIVE_RUN_SCENARIO_H
#define HARNESS_DRIVE_RUN_SCENARIO_H

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "harness/core/pacer.h"
#include "harness/core/run.h"
#include "harness/link/remote_fsw.h"
#include "harness/output/outputs.h"
#include "harness/scenario/scenario.h"

namespace harness {

struct RunResult;

// Something that steers a run at its tick boundaries while it goes: the live
// view (harness/src/live_*.cpp, docs/live.md).  run_scenario() builds the run
// with RunConfig::accept_events when one is given, calls started() once,
// boundary() before every step (paced: every tick) and ended() once the
// results are written.
class RunControl {
 public:
  virtual ~RunControl() = default;
  // Before started(), when the run writes a results folder: the working
  // folder its files go into (they appear in `target` when the run ends,
  // results_dir.h).  Not called for a run without files.
  virtual void results_folder(const std::string& working, const std::string& target)
  {
    (void)working;
    (void)target;
  }
  // After the run is built, before its first tick; `realtime_scale` 0: not paced.
  virtual void started(Run& run, double realtime_scale, const std::atomic<int>* stop) = 0;
  // At the boundary before tick run.tick(): applies what was asked
  // (Run::add_event), may wait while paused (returns when resumed, stepped
  // or stopped).  Returns the most ticks to run before the next call (>= 1);
  // sets `pace` > 0 to (re)start pacing at that multiple of real time (a new
  // rate, or the deadlines restarted after a pause).
  virtual uint64_t boundary(Run& run, double& pace) = 0;
  // Once, after the results are written (or the run failed).
  virtual void ended(const Run& run, const RunResult& res) = 0;
};

struct RunOptions {
  std::string out_dir;                          // "" : write nothing (see results_dir.h)
  bool force = false;                           // replace an existing results folder whole
  std::vector<Override> overrides;              // echoed into the manifest
  std::function<void(double fraction)> progress;  // optional, called between chunks of ticks
  // Optional stop request (set by a SIGINT/SIGTERM handler to the signal
  // number): the run stops at the next tick boundary (within ~1000 ticks),
  // and what was recorded is written, marked incomplete.
  const std::atomic<int>* stop = nullptr;
  // > 0: pace the ticks to the wall clock at this multiple of real time
  // (1: real time; pacer.h); 0: as fast as possible.
  double realtime_scale = 0.0;
  // Optional: warnings while running (no real-time priority, cannot keep up).
  std::function<void(const std::string&)> notice;
  // "" : the FSW in this process; "udp:HOST:PORT" or "serial:DEVICE:BAUD":
  // the FSW behind the link (remote_fsw.h, docs/hwil.md).
  std::string fsw_link;
  LinkOptions link;
  // Further sinks (caller-owned) fed with the same rows (a Monte Carlo
  // campaign's metrics, mc_campaign.cpp).
  std::vector<RecordSink*> extra_sinks;
  // Optional: steers the run at its tick boundaries (the live view).
  RunControl* control = nullptr;
  // > 0: a checkpoint every this many simulated seconds (rounded to whole
  // ticks) in the results' working folder, so that resume_scenario() can
  // continue the run if it is killed (run_checkpoints.h, docs/checkpoint.md).
  double checkpoint_every = 0.0;
};

struct RunResult {
  bool ok = false;
  std::string failure;
  uint64_t ticks = 0;
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  double final_pointing_error_deg = 0.0;
  // what it measures: the reference in force at the end (Run::final_pointing_reference)
  PointingReference final_pointing_reference = PointingReference::Inertial;
  double max_jitter_step = 0.0;    // [rad] Run::max_jitter_step()
  int stopped_by_signal = 0;       // the signal that stopped the run (0: none)
  bool paced = false;              // realtime_scale > 0: pacing holds the figures
  PacingStats pacing;
  RunStatus status;
  std::vector<std::string> files;  // written, in order (paths in the results folder)
  bool linked = false;             // the FSW ran behind the link (RunOptions::fsw_link)
  LinkCounters link;               // ... and what the link counted
  // Every warning of the run, in order: the scenario's before it started
  // (jitter_step_warnings), the notices while it ran (RunOptions::notice)
  // and its figures' after it ended (jitter_reached_warning).  Written into
  // summary.txt and report_data.json.
  std::vector<std::string> warnings;
  // The scenario's requirement lines (monte_carlo.criteria) evaluated on
  // this run (runs with a results folder; metrics.h).
  std::vector<RequirementResult> requirements;
};

// Runs a scenario to the end, streaming its results into opt.out_dir (memory
// bounded for any duration) through a ResultsDir (results_dir.h): the folder
// appears whole when the run ends (complete, failed or interrupted) and is
// never mixed with another run's files.  Throws ScenarioError (configuration
// rejected), ResultsDirRefused (target exists / in use; nothing ran) or
// OutputError (files; the target is left as it was).
RunResult run_scenario(const Scenario& sc, const RunOptions& opt = {});

// Continues the run of the results folder opt.out_dir that was killed after
// writing a checkpoint (RunOptions::checkpoint_every): the scenario, --set
// lines and checkpoint interval are the checkpoint's (`resumed` is set to
// that scenario); the result files come out as an uninterrupted run's.
// `expected`, when given, must be that scenario.  Throws ResultsDirRefused
// (nothing to resume), CheckpointError (damaged, foreign, another
// scenario) and what run_scenario() throws.
RunResult resume_scenario(const RunOptions& opt, const Scenario* expected, Scenario& resumed);

}  // namespace harness

#endif  // HARNESS_DRIVE_RUN_SCENARIO_H

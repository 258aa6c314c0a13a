// run: one closed-loop run of a scenario.
//
// Tick protocol (plant-dynamics §7.2), tick k at t_k = k * dt:
//   1. every task due at k runs in this fixed order:
//        truth        (every tick)  plant state -> `truth`
//        burn_monitor (every tick, thruster runs) non-gravitational delta-v, burn start/end
//        css          (FSW group, configured CSS) truth -> `css_readings`
//        sensors      (FSW group)   truth (+ css_readings) -> `fsw_sensors` (FswAcsSensorMsg)
//        fsw_acs      (FSW group)   fsw_acs_cycle(): `fsw_sensors` -> `fsw_actuators`, `fsw_health`
//        actuators    (FSW group)   wheel torques latched (zero-order hold); thruster
//                                   on-times (ACS + burn schedule) -> `thr_cmd` -> plant
//        metrics, recorder (record group)
//   2. the plant integrates [t_k, t_k + dt] with the held commands.
// The last tick k = num_ticks only runs step 1 (so t = duration is recorded).
// Setup allocates everything; step_ticks() does not allocate.
#ifndef HARNESS_RUN_H
#define HARNESS_RUN_H

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "harness/messages.h"
#include "harness/recorder.h"
#include "harness/scenario.h"
#include "harness/scheduler.h"

namespace harness {

const char* version();

// One figure of the run summary (summary.txt, report_data.json "summary").
struct SummaryItem {
  std::string key;
  double value = 0.0;  // NaN: not applicable
  std::string unit;
  std::string what;
};

class Run {
 public:
  // Builds the plant, the FSW chain, the data flow and the recorder.  Throws
  // ScenarioError when the plant or an FSW module rejects the configuration.
  explicit Run(const Scenario& sc);
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  // Runs up to n more ticks (fewer at the end).  False once the run has
  // failed (see failure()); true otherwise.
  bool step_ticks(uint64_t n);
  bool done() const;
  uint64_t tick() const;         // next tick to run
  uint64_t total_ticks() const;  // num_ticks + 1 (the final sample)

  const std::string& failure() const;  // "" while ok
  const Scenario& scenario() const;
  const Recorder& recorder() const;
  const DataFlow& dataflow() const;
  const Scheduler& scheduler() const;

  // Geometry for the report.
  std::vector<std::array<double, 3>> wheel_axes_B() const;
  // FSW health: module name -> (calls, errors, last status name)
  std::vector<std::string> fsw_health_lines() const;
  // Figures of the run: final pointing error; with thrusters the burn
  // (propellant vs the rocket equation, delivered delta-v) and the orbit.
  std::vector<SummaryItem> summary() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct RunOptions {
  std::string out_dir;                          // "" : write nothing
  std::vector<Override> overrides;              // echoed into the manifest
  std::function<void(double fraction)> progress;  // optional, called <= ~200 times
};

struct RunResult {
  bool ok = false;
  std::string failure;
  uint64_t ticks = 0;
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  double final_pointing_error_deg = 0.0;
  std::vector<std::string> files;  // written, in order
};

// Runs a scenario to the end and writes its results into opt.out_dir.
// Throws ScenarioError (configuration rejected) or OutputError (files).
RunResult run_scenario(const Scenario& sc, const RunOptions& opt = {});

}  // namespace harness

#endif  // HARNESS_RUN_H

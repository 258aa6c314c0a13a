// run: one closed-loop run of a scenario.
//
// Tick protocol (docs/dynamics.md §7.2), tick k at t_k = k * dt: every task due
// at k runs in the order of the table kTickProtocol (run.cpp):
//   events         (every tick, scenarios with events) the events whose
//                  trigger holds are applied (docs/events.md, event_task.h);
//                  an FSW command is written to `fsw_cmd` (runs that take
//                  FSW commands), which fsw_acs hands to the endpoint and
//                  metrics measures the pointing against
//   truth          (FSW and record ticks; every tick with thrusters) plant state -> `truth`
//   mtq_state      (record group, magnetorquers) the rods' dipoles and power -> `mtq_state`
//   burn_monitor   (every tick, thruster runs) `truth` -> `burn_state`
//   sample_sensors (every tick, sampled sensors) `truth` -> `sensor_samples`
//   magnetometer   (every tick, sensors.magnetometer) field model, rods -> `magnetometer`
//   css            (FSW group, configured CSS) `truth` -> `css_readings`
//   sensors        (FSW group)   `truth`, `sensor_samples`, `css_readings` -> `fsw_sensors`
//   fsw_acs        (FSW group)   FswEndpoint::cycle: `fsw_sensors` (+ a new `fsw_cmd`) -> `fsw_actuators`, `fsw_health`
//                                (+ `sun_heading` in sun-safe runs)
//   actuators      (FSW group)   `fsw_actuators` (+ burn schedule) -> `plant_cmd`
//   plant_input    (FSW group)   `plant_cmd` latched by the plant (zero-order hold)
//   magnetorquers  (FSW group, magnetorquers) `mtq_cmd` -> the rods (dipole or PWM drive)
//   metrics        (record group) `truth`, `burn_state`, `fsw_cmd` -> `metrics`
//   recorder       (record group) one row -> the sinks
// then the plant integrates [t_k, t_k + dt] with the held commands.  The last
// tick k = num_ticks only runs the tasks (so t = duration is recorded).
// Setup allocates; step_ticks() does not (the sinks' own work aside: an HDF5
// sink's library allocates when it writes a chunk).
#ifndef HARNESS_RUN_H
#define HARNESS_RUN_H

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/fsw_endpoint.h"
#include "harness/core/messages.h"
#include "harness/core/recorder.h"
#include "harness/core/scenario_types.h"
#include "harness/core/scheduler.h"
#include "sim/plant.h"
#include "sim/state_io.h"

namespace harness {

const char* version();

// Resolution of wheel-imbalance jitter (docs/performance.md, "Accuracy per
// cost"): a wheel whose imbalance makes jitter (simple_jitter or
// fully_coupled with U_s or U_d > 0) turns by |Omega| h per plant step h =
// dt / rates.plant_substeps.  Above kJitterStepLimit the RK4 step misses
// the jitter amplitude by more than about 1 % (measured by
// bench_jitter_accuracy: 0.6 % at 2 rad, 4.4 % at 3.1 rad; docs/performance.md).
constexpr double kJitterStepLimit = 2.0;  // [rad]
bool wheel_jitters(const sim::ReactionWheelParams& p);
// Before a run: the jittering wheels whose initial speed breaks the limit,
// each as "wheels[i] (name): ..." with the sub-steps that would meet it.
std::vector<std::string> jitter_step_warnings(const Scenario& sc);
// After a run: its largest |Omega| h (Run::max_jitter_step) broke the limit.
std::string jitter_reached_warning(double max_step);
// The sub-steps per tick that keep |Omega| dt / n within the limit.
uint32_t substeps_for(double Omega_abs, double dt);

// What pointing_error_deg measures (docs/harness.md, "Recorded columns"): the
// truth attitude against the reference the flight software is commanded to
// track, from the scenario's fsw.mode and then from each FSW command (mode,
// reference) of an event, the live view or Python:
//   Inertial    principal angle of B from the inertial reference sigma_R0N
//               (fsw.inertial.sigma_R0N, then the last commanded one)
//   SunAxis     Sun-axis angle: fsw.sun_safe.sun_axis_B from the true Sun
//               direction (sun-safe mode)
//   OrbitFrame  principal angle of B from the orbit frame's Bd (nadir mode)
// DETUMBLE measures against the reference of the mode it leaves for.
enum class PointingReference { Inertial, SunAxis, OrbitFrame };
// "principal angle from the inertial reference", "Sun-axis angle", ...
const char* describe(PointingReference r);

// A scenario event as applied during a run (docs/events.md): logged in the
// manifest's result, the HDF5 file and the report.
struct AppliedEvent {
  std::string name;
  uint64_t tick = 0;  // the tick boundary it was applied at
  double t = 0.0;     // [s] t_tick
  std::string what;   // its actions, e.g. "rw2 fail_off; rw2 command_unavailable"
};

// One figure of the run summary (summary.txt, report_data.json "summary").
struct SummaryItem {
  std::string key;
  double value = 0.0;  // NaN: not applicable
  std::string unit;
  std::string what;
};

struct TruthMsg;  // harness/core/loop_messages.h

struct RunConfig {
  // Keep every recorded row in memory (Run::memory()): tests, the C++ API,
  // short runs.  Off for streaming-only runs (memory bounded for any duration).
  bool keep_in_memory = true;
  // Where the FSW runs; null: the fsw_c application in this process,
  // configured from the scenario.
  std::unique_ptr<FswEndpoint> fsw;
  size_t chunk_rows = 1024;  // recorder rows per chunk handed to the sinks
  // Build the events task even when the scenario has no events, so events
  // can be added while the run goes (add_event; the live view).
  bool accept_events = false;
  // Further recorded quantities computed from the truth at every recorded
  // row, after the run's own columns (a Python sensor, docs/python.md):
  // fill(t_ns, truth, out) writes every column of `quantities`; it may throw
  // InLoopError (harness/core/loop_error.h) to fail the run at that tick.
  struct TruthSource {
    std::string group;
    std::vector<Quantity> quantities;
    std::function<void(int64_t, const TruthMsg&, double*)> fill;
  };
  std::vector<TruthSource> truth_sources;
};

// The FSW application configuration a scenario gives (what InProcessFsw is
// built with): an endpoint that runs the same application elsewhere (an FSW
// process, a board under test) is configured with it.  Throws ScenarioError
// like Run.
FswAcsConfig fsw_acs_config_of(const Scenario& sc);

class Run {
 public:
  // Builds the plant, the sensors, the FSW endpoint, the data flow and the
  // recorder from a typed scenario (load_scenario() or built in C++).  Throws
  // ScenarioError when the plant or the FSW rejects the configuration.
  explicit Run(const Scenario& sc, RunConfig cfg = {});
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  // Attaches a sink (caller-owned, alive until finish()); before the first step.
  void add_sink(RecordSink& sink);

  // Runs up to n more ticks (fewer at the end).  False once the run has
  // failed (see failure()); true otherwise.
  bool step_ticks(uint64_t n);
  // Hands the last rows to the sinks and ends them: complete when the run
  // reached its end without failure.  Idempotent.
  void finish();
  bool done() const;
  uint64_t tick() const;         // next tick to run
  uint64_t total_ticks() const;  // num_ticks + 1 (the final sample)

  const std::string& failure() const;  // "" while ok
  const Scenario& scenario() const;
  const Recorder& recorder() const;
  // The rows kept in memory (RunConfig::keep_in_memory; std::logic_error otherwise).
  const MemorySink& memory() const;
  const DataFlow& dataflow() const;
  const Scheduler& scheduler() const;
  // The plant, for changes between steps (sim::Plant's device setters: wheel
  // limits, friction and health, thruster health) and its accessors (docs/dynamics.md §13).
  sim::Plant& plant();
  const sim::Plant& plant() const;

  // Appends an event to the run's scenario (scenario().events) and the
  // events task, between steps: e.g. {t = t of tick(), actions} applies at
  // the next tick, exactly as if the scenario had listed it (so the
  // manifest of scenario() replays it).  Throws ScenarioError when an
  // action does not fit the scenario (check_event_action) and
  // std::logic_error without RunConfig::accept_events; nothing is added then.
  void add_event(const EventSpec& e);
  // RunConfig::accept_events as the run was built (a checkpoint records it).
  bool accepts_events() const;
  // Whether the FSW endpoint takes commands (scenario events on device fsw).
  bool fsw_accepts_commands() const;
  // The mrp_fb gains in force {K [N*m], P [N*m*s]}: the configuration's,
  // then the last gain_K / gain_P an event (or a live command) applied.
  std::array<double, 2> fsw_gains() const;

  // The events applied so far, in order.
  const std::vector<AppliedEvent>& events_applied() const;

  // Pointing error of the last recorded row [deg] (NaN before the first).
  double final_pointing_error_deg() const;
  // What it measured there (the reference in force at the last recorded
  // row), and whether an FSW command changed the reference during the run.
  PointingReference final_pointing_reference() const;
  bool pointing_reference_commanded() const;
  // Geometry for the report.
  std::vector<std::array<double, 3>> wheel_axes_B() const;
  // FSW health: the last health message, then per-module counters when the
  // endpoint can see them.
  std::vector<std::string> fsw_health_lines() const;
  // Figures of the run: final pointing error; with thrusters the burn
  // (propellant vs the rocket equation, delivered delta-v) and the orbit.
  std::vector<SummaryItem> summary() const;
  // [rad] the largest |Omega| h of a jittering wheel seen at the ticks so
  // far (0 without one); above kJitterStepLimit the run's jitter is
  // under-resolved (kestrel run warns, the summary lists it).
  double max_jitter_step() const;

  // Per-tick cost split (`kestrel bench`): with profiling on, every task
  // call and every plant step is timed (steady clock).  profile() lists
  // {name, ns} for each task of the scheduler and "plant", summed so far.
  void set_profiling(bool on);
  std::vector<std::pair<std::string, uint64_t>> profile() const;

  // Checkpoint (docs/checkpoint.md; the file: harness/core/checkpoint.h).
  // Why the run cannot be saved now, "" when it can: it failed or ended, or
  // its FSW runs outside this process.
  std::string checkpoint_refusal() const;
  // Walks the run's whole state between ticks, saving or restoring
  // (sim/state_io.h), part by part in a fixed order: the run's clock, the
  // plant and its effectors, the FSW endpoint, the sensors, every message,
  // the recorder, the stateful tasks.  Restoring needs a run built from the
  // same scenario, its sinks attached, before its first step.
  void state_io(sim::StateIO& io);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace harness

#endif  // HARNESS_RUN_H

// run_impl.h: the parts of a run (Run::Impl), private to the core room.
// run.cpp builds and steps them; run_wiring.cpp wires them (messages,
// tasks, recorder, events); run_state.cpp saves and restores them for a
// checkpoint; run_summary.cpp forms the run's summary from them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/run.h"
#include "core/event_task.h"
#include "core/fsw_config.h"
#include "core/plant_builder.h"
#include "core/sensor_suite.h"
#include "core/tasks.h"

namespace harness {

struct Run::Impl {
  Scenario sc;
  bool accept_events = false;  // RunConfig::accept_events
  EnvEffectors env{};  // filled by build_plant (before plant_owner)
  SettableParts mag{};  // likewise
  SunSource sun;  // the run's Sun (sensors, truth, metrics: one shared)
  std::unique_ptr<sim::Plant> plant_owner;
  sim::Plant& plant;
  FswSetup fsw_setup;
  std::unique_ptr<FswEndpoint> fsw;
  std::unique_ptr<SensorSuite> sensors;
  Scheduler sched;
  DataFlow flow;
  Recorder rec{"telemetry"};
  size_t n_truth_sources = 0;  // callers' truth sources (Python sensors): state outside the run
  std::optional<MemorySink> mem;
  uint64_t tick = 0;
  uint64_t n_ticks = 0;
  std::string failure;
  int64_t substep_ns = 0;           // plant step: dt / rates.plant_substeps
  std::vector<int> jitter_wheels;   // wheels whose imbalance makes jitter
  double max_jitter_Omega = 0.0;    // [rad/s] largest |Omega| of those at a tick
  uint64_t plant_ns = 0;            // [ns] plant steps while profiling (set_profiling)

  // tasks (optional ones absent when the run does not need them)
  std::optional<TruthTask> truth;
  std::optional<BurnMonitor> burn;
  std::optional<SampleSensorsTask> sample;
  std::optional<CssTask> css;
  std::optional<FswInputTask> fsw_input;
  std::optional<FswTask> fsw_task;
  std::optional<ActuatorTask> actuators;
  std::optional<PlantInputTask> plant_input;
  std::optional<MetricsTask> metrics;
  std::optional<EventTask> events;  // scenarios with events only
  std::optional<MagnetometerTask> magnetometer;  // sensors.magnetometer only
  std::optional<MagnetorquerTask> magnetorquers;  // magnetorquers only
  std::optional<MtqStateTask> mtq_state;          // magnetorquers only

  Channel<TruthMsg>* truth_ch = nullptr;
  Channel<FswAcsHealthMsg>* health_ch = nullptr;

  // The messages of the data flow (optional ones null when the run does not
  // need them).
  struct Messages {
    Channel<TruthMsg>* truth = nullptr;
    Channel<FswAcsSensorMsg>* sens = nullptr;
    Channel<FswAcsActuatorMsg>* act = nullptr;
    Channel<FswAcsHealthMsg>* health = nullptr;
    Channel<PlantCmdMsg>* cmd = nullptr;
    Channel<MetricsMsg>* metrics = nullptr;
    Channel<SunHeadingMsg>* sun = nullptr;
    Channel<BurnStateMsg>* burn = nullptr;
    Channel<SensorSampleMsg>* samples = nullptr;
    Channel<CssMsg>* css = nullptr;
    Channel<MtqCmdMsg>* mtq_cmd = nullptr;
    Channel<MtqStateMsg>* mtq_state = nullptr;
    Channel<MagnetometerMsg>* mag = nullptr;
    Channel<FswAcsCmdMsg>* fsw_cmd = nullptr;  // runs that take FSW commands
  };
  Channel<MtqCmdMsg>* mtq_cmd_ch = nullptr;  // events write it (until the FSW commands the rods)
  Channel<FswAcsCmdMsg>* fsw_cmd_ch = nullptr;  // events write it (runs that take FSW commands)

  explicit Impl(const Scenario& s)
      : sc(s), sun(sc), plant_owner(build_plant(s, &env, &mag)), plant(*plant_owner), sched(s.tick_ns())
  {
  }
  void wire(RunConfig& cfg);
  void build_fsw(RunConfig& cfg);
  Messages add_messages(bool fsw_commands);
  FswAcsCmdMsg initial_command() const;
  void add_tasks(const Messages& m);
  void add_magnetic_tasks(const Messages& m);
  void add_recorder(const Messages& m);
  void add_events();
  void schedule(const RateGroup& fsw_group, const RateGroup& rec_group);
  bool step_plant();
};

}  // namespace harness

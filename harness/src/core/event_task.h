// event_task: the scenario's events in the tick protocol (docs/events.md).
// First task of every tick k: each event not yet applied whose trigger
// holds is applied, in the order of the list, before any other task of
// tick k runs, so its actions are in force for the whole tick:
//   t          fires at the first tick with t_k >= t
//   after      fires at the first tick with t_k >= t(applied) + delay (same
//              tick when delay = 0: `after` names an earlier event)
//   when       fires at the first tick after a recorded row whose column
//              is below / above the threshold (the last row of ticks < k)
// Applying allocates nothing (the log is reserved at construction).
#ifndef HARNESS_SRC_EVENT_TASK_H
#define HARNESS_SRC_EVENT_TASK_H

#include <cstdint>
#include <limits>
#include <vector>

#include "core/events.h"
#include "harness/core/fsw_endpoint.h"
#include "harness/core/recorder.h"
#include "harness/core/run.h"
#include "harness/core/scenario_types.h"
#include "core/sensor_suite.h"
#include "harness/core/loop_messages.h"
#include "harness/core/messages.h"
#include "sim/environment_effectors.h"
#include "sim/plant.h"

namespace harness {

class EventTask {
 public:
  // Throws ScenarioError (at the event's key) for what only the run can
  // check: a device or a watched column the run does not have.
  // The FSW commands (mode, actuation, reference, gains) start from
  // `initial` and are written to `cmd` (`fsw_cmd`: the FSW task hands each
  // to `fsw` for its next cycle, the metrics measure against it); unset
  // when the run takes no FSW commands (an fsw event is refused then).
  EventTask(const Scenario& sc, sim::Plant& plant, SensorSuite& sensors, const Recorder& rec, FswEndpoint& fsw,
            const FswAcsCmdMsg& initial, Writer<FswAcsCmdMsg> cmd);
  void operator()(uint64_t k);
  // Takes the scenario's last event (just appended to sc.events, e.g. a
  // command from the live view) into the run; throws like the constructor.
  // Allocates (the live view's commands, not the scenario's own events).
  void add();
  const std::vector<AppliedEvent>& log() const { return log_; }
  // The FSW command as commanded so far (from the configuration's mode,
  // actuation, reference and gains; each FSW action changes its field).
  const FswAcsCmdMsg& command() const { return cmd_; }
  // The run's rods and their command message (runs with magnetorquers):
  // the magnetorquer actions act on them.
  void attach_magnetorquers(sim::MagneticEffector* mag, Writer<MtqCmdMsg> cmd);
  // The run's drag model (runs with environment.drag): the atmosphere
  // actions act on it; `scale` is the scenario's density scale (restore).
  void attach_atmosphere(sim::DragEffector* drag, double scale);
  // For a checkpoint (sim/state_io.h): the commands so far, each event's
  // trigger time and whether it applied, and the log (event index, tick, t).
  // The actions' effects are in the state of what they act on.
  void state_io(sim::StateIO& io);

 private:
  struct Act {
    EventTarget target;
    EventAction action;
    double value;
  };
  struct Ev {
    std::vector<Act> acts;
    uint64_t t_ns = std::numeric_limits<uint64_t>::max();  // time trigger [ns] (after: set when its event applies)
    int after = -1;                                        // index of the event it follows
    uint64_t delay_ns = 0;
    size_t column = 0;  // when
    bool watch = false, below = false;
    double threshold = 0.0;
    bool applied = false;
    AppliedEvent entry;  // built at setup, moved into the log when applied (no allocation)
  };
  void apply(const Act& a, uint64_t t_ns);
  void apply_wheel(const Act& a);
  void apply_thruster(const Act& a);
  void apply_fsw(const Act& a, uint64_t t_ns);
  void apply_sensor(const Act& a, uint64_t t_ns);
  void apply_magnetorquer(const Act& a, uint64_t t_ns);
  void apply_state(const Act& a);
  void attitude_to_short_set();
  Ev make(size_t i) const;  // event i of the scenario, checked

  const Scenario& sc_;
  sim::Plant& plant_;
  SensorSuite& sensors_;
  const Recorder& rec_;
  FswEndpoint& fsw_;
  FswAcsCmdMsg cmd_;  // the mode, actuation, reference and gains commanded so far
  Writer<FswAcsCmdMsg> cmd_out_;
  uint64_t tick_ns_;
  sim::MagneticEffector* mag_ = nullptr;
  sim::DragEffector* drag_ = nullptr;
  double density_scale_ = 1.0;  // the scenario's
  Writer<MtqCmdMsg> mtq_cmd_;
  std::vector<Ev> ev_;
  std::vector<AppliedEvent> log_;
  std::vector<uint32_t> log_index_;  // the event of each log entry
};

}  // namespace harness

#endif  // HARNESS_SRC_EVENT_TASK_H

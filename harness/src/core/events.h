// events: the scenario's `events` (docs/events.md) -- which device an
// action names, which actions each device takes, the columns a `when`
// trigger may watch.  Shared by the reader (scenario_events.cpp, problems at
// the key's line) and the run (event_task.cpp).  Private to the harness.
#ifndef HARNESS_SRC_EVENTS_H
#define HARNESS_SRC_EVENTS_H

#include <string>
#include <vector>

#include "harness/core/scenario_types.h"

namespace harness {

enum class EventDevice { Wheel, Thruster, Gyro, StarTracker, Css, Fsw, Magnetorquer, Magnetometer, Atmosphere, Spacecraft };

enum class EventAction {
  // wheels (the plant's motor, limits, friction; the tachometer; the FSW's availability flag)
  WheelFailOff, WheelStuck, WheelTorqueLimit, WheelFriction, TachNan, TachFrozen, TachBias, TachNoiseScale, CommandUnavailable,
  CommandAvailable,
  // thrusters
  ThrStuckClosed, ThrStuckOpen, ThrThrustFactor,
  // magnetorquer rods (the plant's sim::MagneticEffector; the `mtq_cmd` message)
  MtqFailOff, MtqStuck, MtqScale, MtqDipole,
  // the atmosphere of the drag model (sim::DragEffector)
  AtmDensityScale,
  // sensors (gyro, star tracker, a coarse sun sensor, the magnetometer)
  SensorDropout, SensorFrozen, SensorNoiseScale, SensorBiasX, SensorBiasY, SensorBiasZ, SensorBias,
  // the flight software (a ground/executive command, FswAcsCmdMsg)
  FswModeInertial, FswModeSunSafe, FswActuationWheels, FswActuationThrusters, FswReferenceX, FswReferenceY,
  FswReferenceZ, FswGainK, FswGainP,
  // the plant's state (the spacecraft; a wheel's speed), set at the tick boundary
  ScSigmaX, ScSigmaY, ScSigmaZ, ScOmegaX, ScOmegaY, ScOmegaZ, ScPosX, ScPosY, ScPosZ, ScVelX, ScVelY, ScVelZ,
  ScPropellant, WheelSpeed,
  // every device: back to nominal (a wheel: motor, limits, friction, tachometer)
  Restore
};

// What a value means for an action; Value::None: the action takes none.
enum class EventValue { None, Positive, NonNegative, Finite };

struct EventActionDef {
  const char* word;
  EventAction action;
  EventValue value;
  const char* unit;  // of the value
  const char* what;  // one line for docs and messages
};

struct EventTarget {
  EventDevice device = EventDevice::Wheel;
  int index = 0;  // wheel, thruster, magnetorquer or CSS index; 0 for gyro, star tracker, magnetometer
};

// Resolves a device name (wheel, thruster or magnetorquer name, "gyro",
// "star_tracker", "css<i>", "magnetometer", "fsw", "spacecraft"): "" or the reason it names nothing.
std::string resolve_event_device(const Scenario& sc, const std::string& name, EventTarget& out);
// The actions a device takes.
const std::vector<EventActionDef>& event_actions(EventDevice d);
const char* to_string(EventDevice d);
// The action word for a device: nullptr when the device does not take it.
const EventActionDef* find_event_action(EventDevice d, const std::string& word);
// Checks one action against the scenario: "" or the reason; `key` receives
// the key at fault ("device", "action" or "value").
std::string check_event_action(const Scenario& sc, const EventActionSpec& a, std::string& key);
// The names of the scenario's devices that take actions (wheels, thrusters,
// sensors that are enabled, magnetorquers, magnetometer, atmosphere,
// spacecraft; not "fsw", which depends on the run's flight software).
std::vector<std::string> event_device_names(const Scenario& sc);
// The recorded columns a `when` trigger may watch in this scenario.
std::vector<std::string> event_watch_columns(const Scenario& sc);

}  // namespace harness

#endif  // HARNESS_SRC_EVENTS_H

// events.cpp: the devices and actions of scenario events (events.h).
#include "core/events.h"

#include <cmath>
#include <string>

namespace harness {

namespace {
const std::vector<EventActionDef> kWheelActions = {
    {"fail_off", EventAction::WheelFailOff, EventValue::None, "-", "motor unpowered: no torque (friction still acts)"},
    {"stuck", EventAction::WheelStuck, EventValue::None, "-",
     "rotor held at its present speed relative to the body: no motor or friction torque, its momentum stays"},
    {"torque_limit", EventAction::WheelTorqueLimit, EventValue::Positive, "N*m", "motor torque limit u_max reduced to value"},
    {"friction", EventAction::WheelFriction, EventValue::NonNegative, "-",
     "every friction term (Coulomb, static, viscous) times value"},
    {"tach_nan", EventAction::TachNan, EventValue::None, "-", "its tachometer reads NaN"},
    {"tach_frozen", EventAction::TachFrozen, EventValue::None, "-", "its tachometer holds its last reading"},
    {"tach_bias", EventAction::TachBias, EventValue::Finite, "rad/s", "value added to its tachometer reading"},
    {"tach_noise_scale", EventAction::TachNoiseScale, EventValue::NonNegative, "-",
     "its tachometer's noise 1-sigma times value (draws stay aligned)"},
    {"command_unavailable", EventAction::CommandUnavailable, EventValue::None, "-",
     "the FSW is told the wheel is unavailable (FswAcsSensorMsg.rw_avail = 1)"},
    {"command_available", EventAction::CommandAvailable, EventValue::None, "-",
     "the FSW is told the wheel is available again (rw_avail = 0)"},
    {"speed", EventAction::WheelSpeed, EventValue::Finite, "rad/s",
     "its rotor speed relative to the body set to value (|value| <= its Omega_max when set)"},
    {"restore", EventAction::Restore, EventValue::None, "-",
     "rotor free, motor, torque limit, friction and tachometer back to the scenario's values"},
};
const std::vector<EventActionDef> kThrusterActions = {
    {"stuck_closed", EventAction::ThrStuckClosed, EventValue::None, "-", "valve closed: no thrust, requests ignored"},
    {"stuck_open", EventAction::ThrStuckOpen, EventValue::None, "-", "valve open: full thrust, requests ignored"},
    {"thrust_factor", EventAction::ThrThrustFactor, EventValue::Positive, "-",
     "force, swirl torque and mass flow times value (< 1 degraded; Isp and valve unchanged)"},
    {"command_unavailable", EventAction::CommandUnavailable, EventValue::None, "-",
     "the FSW is told the ACS thruster is unavailable (FswAcsSensorMsg.thr_avail = 1): mapped as absent, kept off"},
    {"command_available", EventAction::CommandAvailable, EventValue::None, "-",
     "the FSW is told the ACS thruster is available again (thr_avail = 0)"},
    {"restore", EventAction::Restore, EventValue::None, "-", "valve follows its commands again, thrust factor 1"},
};
const std::vector<EventActionDef> kSensorActions = {
    {"dropout", EventAction::SensorDropout, EventValue::Positive, "s",
     "no valid output for value seconds (star tracker: att_valid 0; gyro: NaN rates; CSS: unavailable)"},
    {"frozen", EventAction::SensorFrozen, EventValue::None, "-", "the output holds its last value"},
    {"noise_scale", EventAction::SensorNoiseScale, EventValue::NonNegative, "-",
     "the model's random-error 1-sigmas times value (gyro ARW and RRW; star tracker cross and boresight; CSS "
     "sigma)"},
    {"bias_x", EventAction::SensorBiasX, EventValue::Finite, "rad/s or rad",
     "gyro: value added to its x rate; star tracker: the measured attitude turned by value about body x"},
    {"bias_y", EventAction::SensorBiasY, EventValue::Finite, "rad/s or rad", "as bias_x, about y"},
    {"bias_z", EventAction::SensorBiasZ, EventValue::Finite, "rad/s or rad", "as bias_x, about z"},
    {"bias", EventAction::SensorBias, EventValue::Finite, "css units", "coarse sun sensor: value added to its reading"},
    {"restore", EventAction::Restore, EventValue::None, "-", "the output follows the sensor again, noise scale 1, no bias"},
};
const std::vector<EventActionDef> kMagnetorquerActions = {
    {"fail_off", EventAction::MtqFailOff, EventValue::None, "-",
     "coil dead: the remanent dipole of its last command stays, commands ignored"},
    {"stuck", EventAction::MtqStuck, EventValue::None, "-", "dipole held at its present value, commands ignored"},
    {"scale", EventAction::MtqScale, EventValue::NonNegative, "-",
     "its dipole commands times value (then saturation) from the next command"},
    {"dipole", EventAction::MtqDipole, EventValue::Finite, "A*m^2",
     "command its dipole (mtq_cmd), applied at the next control instant (FSW tick)"},
    {"restore", EventAction::Restore, EventValue::None, "-", "commands act again, scale 1 (from the next command)"},
};
const std::vector<EventActionDef> kMagnetometerActions = {
    {"dropout", EventAction::SensorDropout, EventValue::Positive, "s",
     "no valid reading for value seconds (mag_valid 0, NaN field)"},
    {"frozen", EventAction::SensorFrozen, EventValue::None, "-", "the reading holds its present value"},
    {"noise_scale", EventAction::SensorNoiseScale, EventValue::NonNegative, "-", "its noise 1-sigma times value"},
    {"bias_x", EventAction::SensorBiasX, EventValue::Finite, "T",
     "value added to its x reading (sensor axes), from its next sample"},
    {"bias_y", EventAction::SensorBiasY, EventValue::Finite, "T", "as bias_x, its y reading"},
    {"bias_z", EventAction::SensorBiasZ, EventValue::Finite, "T", "as bias_x, its z reading"},
    {"restore", EventAction::Restore, EventValue::None, "-", "the reading follows the sensor again, noise scale 1, no bias"},
};
const std::vector<EventActionDef> kAtmosphereActions = {
    {"density_scale", EventAction::AtmDensityScale, EventValue::NonNegative, "-",
     "the drag model's air density times value instead of environment.drag.density_scale, from the next step "
     "(a geomagnetic storm)"},
    {"restore", EventAction::Restore, EventValue::None, "-", "back to environment.drag.density_scale"},
};
const std::vector<EventActionDef> kSpacecraftActions = {
    {"sigma_BN_x", EventAction::ScSigmaX, EventValue::Finite, "-",
     "attitude MRP sigma_BN component x set to value (the others kept; the shadow set when |sigma_BN| > 1)"},
    {"sigma_BN_y", EventAction::ScSigmaY, EventValue::Finite, "-", "as sigma_BN_x, component y"},
    {"sigma_BN_z", EventAction::ScSigmaZ, EventValue::Finite, "-", "as sigma_BN_x, component z"},
    {"omega_BN_B_x", EventAction::ScOmegaX, EventValue::Finite, "rad/s", "body rate omega_BN_B component x set to value"},
    {"omega_BN_B_y", EventAction::ScOmegaY, EventValue::Finite, "rad/s", "as omega_BN_B_x, component y"},
    {"omega_BN_B_z", EventAction::ScOmegaZ, EventValue::Finite, "rad/s", "as omega_BN_B_x, component z"},
    {"r_N_x", EventAction::ScPosX, EventValue::Finite, "m", "position r_BN_N component x set to value"},
    {"r_N_y", EventAction::ScPosY, EventValue::Finite, "m", "as r_N_x, component y"},
    {"r_N_z", EventAction::ScPosZ, EventValue::Finite, "m", "as r_N_x, component z"},
    {"v_N_x", EventAction::ScVelX, EventValue::Finite, "m/s", "velocity v_BN_N component x set to value"},
    {"v_N_y", EventAction::ScVelY, EventValue::Finite, "m/s", "as v_N_x, component y"},
    {"v_N_z", EventAction::ScVelZ, EventValue::Finite, "m/s", "as v_N_x, component z"},
    {"propellant_mass", EventAction::ScPropellant, EventValue::NonNegative, "kg",
     "the propellant of the first tank set to value (0 <= value <= its capacity)"},
};
const std::vector<EventActionDef> kFswActions = {
    {"mode_inertial", EventAction::FswModeInertial, EventValue::None, "-",
     "command inertial pointing (guid_inertial -> att_track; needs an attitude: star tracker or truth)"},
    {"mode_sun_safe", EventAction::FswModeSunSafe, EventValue::None, "-",
     "command sun-safe pointing (css_sun -> guid_sunsafe; needs the coarse sun sensors)"},
    {"actuation_wheels", EventAction::FswActuationWheels, EventValue::None, "-", "command control by the wheels"},
    {"actuation_thrusters", EventAction::FswActuationThrusters, EventValue::None, "-",
     "command control by the ACS thrusters"},
    {"reference_x", EventAction::FswReferenceX, EventValue::Finite, "-",
     "command a new inertial reference: component x of sigma_R0N (MRP; the others as last set; one event "
     "with reference_x, _y, _z sets all three)"},
    {"reference_y", EventAction::FswReferenceY, EventValue::Finite, "-", "as reference_x, component y"},
    {"reference_z", EventAction::FswReferenceZ, EventValue::Finite, "-", "as reference_x, component z"},
    {"gain_K", EventAction::FswGainK, EventValue::Positive, "N*m", "command mrp_fb's attitude gain K"},
    {"gain_P", EventAction::FswGainP, EventValue::Positive, "N*m*s", "command mrp_fb's rate gain P"},
};
}  // namespace

const char* to_string(EventDevice d)
{
  switch (d) {
    case EventDevice::Wheel: return "wheel";
    case EventDevice::Thruster: return "thruster";
    case EventDevice::Gyro: return "gyro";
    case EventDevice::StarTracker: return "star tracker";
    case EventDevice::Css: return "coarse sun sensor";
    case EventDevice::Fsw: return "flight software";
    case EventDevice::Magnetorquer: return "magnetorquer";
    case EventDevice::Magnetometer: return "magnetometer";
    case EventDevice::Atmosphere: return "atmosphere";
    case EventDevice::Spacecraft: return "spacecraft";
  }
  return "?";
}

const std::vector<EventActionDef>& event_actions(EventDevice d)
{
  switch (d) {
    case EventDevice::Wheel: return kWheelActions;
    case EventDevice::Thruster: return kThrusterActions;
    case EventDevice::Fsw: return kFswActions;
    case EventDevice::Magnetorquer: return kMagnetorquerActions;
    case EventDevice::Magnetometer: return kMagnetometerActions;
    case EventDevice::Atmosphere: return kAtmosphereActions;
    case EventDevice::Spacecraft: return kSpacecraftActions;
    default: return kSensorActions;
  }
}

const EventActionDef* find_event_action(EventDevice d, const std::string& word)
{
  for (const EventActionDef& a : event_actions(d))
    if (word == a.word) return &a;
  return nullptr;
}

std::string resolve_event_device(const Scenario& sc, const std::string& name, EventTarget& out)
{
  for (size_t i = 0; i < sc.wheels.size(); ++i)
    if (sc.wheels[i].name == name) {
      out = {EventDevice::Wheel, static_cast<int>(i)};
      return "";
    }
  for (size_t j = 0; j < sc.thrusters.size(); ++j)
    if (sc.thrusters[j].name == name) {
      out = {EventDevice::Thruster, static_cast<int>(j)};
      return "";
    }
  for (size_t i = 0; i < sc.magnetorquers.size(); ++i)
    if (sc.magnetorquers[i].name == name) {
      out = {EventDevice::Magnetorquer, static_cast<int>(i)};
      return "";
    }
  if (name == "fsw") {
    out = {EventDevice::Fsw, 0};
    return "";
  }
  if (name == "spacecraft") {
    out = {EventDevice::Spacecraft, 0};
    return "";
  }
  if (name == "atmosphere") {
    if (!sc.environment.drag.enabled) return "the drag model is off (environment.drag.enabled: false)";
    out = {EventDevice::Atmosphere, 0};
    return "";
  }
  if (name == "magnetometer") {
    if (!sc.sensors.magnetometer.enabled) return "the magnetometer is not enabled (sensors.magnetometer.enabled: false)";
    out = {EventDevice::Magnetometer, 0};
    return "";
  }
  if (name == "gyro") {
    if (!sc.sensors.gyro.enabled) return "the gyro is not enabled (sensors.gyro.enabled: false)";
    out = {EventDevice::Gyro, 0};
    return "";
  }
  if (name == "star_tracker") {
    if (!sc.sensors.star_tracker.enabled) return "the star tracker is not enabled (sensors.star_tracker.enabled: false)";
    out = {EventDevice::StarTracker, 0};
    return "";
  }
  if (name.size() > 3 && name.compare(0, 3, "css") == 0 && name.size() <= 6) {
    bool digits = true;
    for (size_t c = 3; c < name.size(); ++c) digits = digits && name[c] >= '0' && name[c] <= '9';
    if (digits) {
      const size_t i = static_cast<size_t>(std::stoul(name.substr(3)));
      if (i >= sc.sensors.css.normals_B.size())
        return "no coarse sun sensor " + name + " (sensors.css.normals has " +
               std::to_string(sc.sensors.css.normals_B.size()) + "; css<i> is normals[i])";
      out = {EventDevice::Css, static_cast<int>(i)};
      return "";
    }
  }
  std::string known;
  for (const WheelSpec& w : sc.wheels) known += w.name + ", ";
  for (const ThrusterSpec& t : sc.thrusters) known += t.name + ", ";
  for (const MagnetorquerSpec& m : sc.magnetorquers) known += m.name + ", ";
  known += "gyro, star_tracker, css<i>, magnetometer, atmosphere, fsw, spacecraft";
  return "no device named '" + escape_bytes(name) + "' (devices: " + known + ")";
}

namespace {
// The plant-state actions' limits: a wheel's speed within its Omega_max, the
// propellant within [0, the tank's load].  "" or the reason (`key` set).
std::string check_state_action(const Scenario& sc, const EventTarget& tg, EventAction x, double v, std::string& key)
{
  if (x == EventAction::ScPropellant) {
    const std::optional<TankSpec>& tank = sc.tank ? sc.tank : sc.rcs_tank;
    key = "action";
    if (!tank) return "'propellant_mass' needs a propellant tank (tank or rcs_tank)";
    key = "value";
    if (std::isfinite(v) && v > tank->mass)
      return "'propellant_mass' needs a value <= the tank's load " + std::to_string(tank->mass) + " [kg]";
  }
  if (x == EventAction::WheelSpeed) {
    const double lim = sc.wheels[static_cast<size_t>(tg.index)].params.Omega_max;
    key = "value";
    if (std::isfinite(v) && lim > 0.0 && std::fabs(v) > lim)
      return "'speed' needs |value| <= the wheel's Omega_max " + std::to_string(lim) + " [rad/s]";
  }
  return "";
}
}  // namespace

std::string check_event_action(const Scenario& sc, const EventActionSpec& a, std::string& key)
{
  EventTarget tg;
  key = "device";
  std::string why = resolve_event_device(sc, a.device, tg);
  if (!why.empty()) return why;
  key = "action";
  const EventActionDef* d = find_event_action(tg.device, a.action);
  if (!d) {
    std::string all;
    for (const EventActionDef& x : event_actions(tg.device)) all += (all.empty() ? "" : ", ") + std::string(x.word);
    return "a " + std::string(to_string(tg.device)) + " takes one of {" + all + "}, got '" + escape_bytes(a.action) +
           "'";
  }
  if (tg.device == EventDevice::Wheel && (d->action == EventAction::TachNan || d->action == EventAction::TachFrozen ||
                                          d->action == EventAction::TachBias || d->action == EventAction::TachNoiseScale) &&
      !sc.sensors.tachometer.enabled)
    return "'" + a.action + "' needs the tachometers (sensors.tachometer.enabled: true)";
  if (tg.device == EventDevice::Thruster &&
      (d->action == EventAction::CommandUnavailable || d->action == EventAction::CommandAvailable) &&
      !sc.thrusters[static_cast<size_t>(tg.index)].acs)
    return "'" + a.action + "' flags an ACS thruster for the FSW; '" + a.device +
           "' is not one (acs: false: the FSW does not command it)";
  {
    const EventAction x = d->action;
    const bool axis = x == EventAction::SensorBiasX || x == EventAction::SensorBiasY || x == EventAction::SensorBiasZ;
    if (axis && tg.device == EventDevice::Css)
      return "a coarse sun sensor has one output: its bias step is 'bias', not '" + a.action + "'";
    if (x == EventAction::SensorBias && tg.device != EventDevice::Css)
      return "'bias' is a coarse sun sensor's; the " + std::string(to_string(tg.device)) +
             " takes bias_x, bias_y, bias_z (body axes)";
    if (axis && tg.device == EventDevice::StarTracker && std::fabs(a.value) > 3.141592653589793) {
      key = "value";
      return "a star tracker bias is a rotation angle: |value| <= pi [rad]";
    }
  }
  if ((d->action == EventAction::SensorNoiseScale || d->action == EventAction::TachNoiseScale) && !sc.sensors.noise)
    return "'" + a.action + "' needs sensor noise (sensors.noise: true)";
  if (tg.device == EventDevice::Fsw) {
    const EventAction x = d->action;
    if (x == EventAction::FswModeSunSafe && sc.sensors.css.normals_B.size() < 3)
      return "'mode_sun_safe' needs the coarse sun sensors (sensors.css.normals: at least 3)";
    if (x == EventAction::FswModeSunSafe && sc.environment.sun_position_N.norm() == 0.0)
      return "'mode_sun_safe' needs a Sun position (environment.sun_position_N)";
    if (x == EventAction::FswActuationWheels && sc.wheels.size() < 3)
      return "'actuation_wheels' needs at least 3 wheels";
    const bool acs = sc.has_acs_thrusters();
    if (x == EventAction::FswActuationThrusters && !acs)
      return "'actuation_thrusters' needs ACS thrusters (thrusters with acs: true)";
  }
  {
    const std::string why_state = check_state_action(sc, tg, d->action, a.value, key);
    if (!why_state.empty()) return why_state;
  }
  key = "value";
  const double v = a.value;
  switch (d->value) {
    case EventValue::None:
      if (!std::isnan(v)) return "'" + a.action + "' takes no value";
      return "";
    case EventValue::Positive:
      if (!(v > 0.0) || !std::isfinite(v)) return "'" + a.action + "' needs a value > 0 [" + d->unit + "]";
      return "";
    case EventValue::NonNegative:
      if (!(v >= 0.0) || !std::isfinite(v)) return "'" + a.action + "' needs a value >= 0 [" + d->unit + "]";
      return "";
    case EventValue::Finite:
      if (!std::isfinite(v)) return "'" + a.action + "' needs a finite value [" + d->unit + "]";
      return "";
  }
  return "";
}

std::vector<std::string> event_device_names(const Scenario& sc)
{
  std::vector<std::string> out;
  for (const WheelSpec& w : sc.wheels) out.push_back(w.name);
  for (const ThrusterSpec& t : sc.thrusters) out.push_back(t.name);
  if (sc.sensors.gyro.enabled) out.push_back("gyro");
  if (sc.sensors.star_tracker.enabled) out.push_back("star_tracker");
  for (size_t i = 0; i < sc.sensors.css.normals_B.size(); ++i) out.push_back("css" + std::to_string(i));
  for (const MagnetorquerSpec& r : sc.magnetorquers) out.push_back(r.name);
  if (sc.sensors.magnetometer.enabled) out.push_back("magnetometer");
  if (sc.environment.drag.enabled) out.push_back("atmosphere");
  out.push_back("spacecraft");
  return out;
}

std::vector<std::string> event_watch_columns(const Scenario& sc)
{
  std::vector<std::string> out{"pointing_error_deg"};
  for (size_t i = 0; i < sc.wheels.size(); ++i) {
    out.push_back("wheel_speed_rpm_" + std::to_string(i));
    out.push_back("meas_wheel_speed_rpm_" + std::to_string(i));
  }
  return out;
}

}  // namespace harness

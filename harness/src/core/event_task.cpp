#include "core/event_task.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/build_error.h"

namespace harness {

namespace {
// [ns] a time in seconds as the first whole tick at or after it
uint64_t ceil_to_tick(double t_s, uint64_t tick_ns)
{
  if (!(t_s < 9e9)) return std::numeric_limits<uint64_t>::max();  // beyond any run (kMaxTicks)
  const uint64_t t_ns = static_cast<uint64_t>(std::llround(t_s * 1e9));
  return (t_ns + tick_ns - 1) / tick_ns * tick_ns;
}
}  // namespace

EventTask::EventTask(const Scenario& sc, sim::Plant& plant, SensorSuite& sensors, const Recorder& rec,
                     FswEndpoint& fsw, const FswAcsCmdMsg& initial, Writer<FswAcsCmdMsg> cmd)
    : sc_(sc), plant_(plant), sensors_(sensors), rec_(rec), fsw_(fsw), cmd_(initial), cmd_out_(cmd),
      tick_ns_(sc.tick_ns())
{
  for (size_t i = 0; i < sc.events.size(); ++i) ev_.push_back(make(i));
  log_.reserve(ev_.size());
  log_index_.reserve(ev_.size());
}

void EventTask::add()
{
  ev_.push_back(make(sc_.events.size() - 1));
  log_.reserve(ev_.size());
  log_index_.reserve(ev_.size());
}

void EventTask::state_io(sim::StateIO& io)
{
  uint64_t n_ev = ev_.size(), n_log = log_.size();
  io.value("events.count", n_ev);
  // restoring, the run's scenario may list events after the saved ones: events
  // added since the checkpoint (a branched run's), still to come
  if (n_ev > ev_.size()) throw std::runtime_error("checkpoint: the run has another number of events");
  io.value("events.command", cmd_);
  for (size_t i = 0; i < n_ev; ++i) {
    Ev& e = ev_[i];
    io.value("events.t_ns", e.t_ns);
    io.value("events.applied", e.applied);
    // a time event still to come fires at its time in this run's scenario: the
    // saved one for the scenario that saved it, a dispersed one in a campaign
    // branched from the checkpoint (docs/checkpoint.md, "Branching a campaign")
    if (io.loading() && !e.applied && sc_.events[i].t) e.t_ns = ceil_to_tick(*sc_.events[i].t, tick_ns_);
  }
  io.value("events.log_size", n_log);
  if (io.loading()) {
    log_.clear();
    log_index_.clear();
  }
  for (uint64_t j = 0; j < n_log; ++j) {
    uint32_t idx = io.loading() ? 0 : log_index_[j];
    AppliedEvent a = io.loading() ? AppliedEvent{} : log_[j];
    io.value("events.log_index", idx);
    io.value("events.log_tick", a.tick);
    io.value("events.log_t", a.t);
    if (!io.loading()) continue;
    if (idx >= ev_.size()) throw std::runtime_error("checkpoint: an applied event is not in the run");
    AppliedEvent entry = make(idx).entry;
    entry.tick = a.tick;
    entry.t = a.t;
    log_.push_back(std::move(entry));
    log_index_.push_back(idx);
  }
}

EventTask::Ev EventTask::make(size_t i) const
{
  const EventSpec& e = sc_.events[i];
  const std::string key = "events[" + std::to_string(i) + "]";
  Ev ev;
  if (e.t) ev.t_ns = ceil_to_tick(*e.t, tick_ns_);
  if (!e.after.empty()) {
    for (size_t j = 0; j < i; ++j)
      if (sc_.events[j].name == e.after) ev.after = static_cast<int>(j);
    if (ev.after < 0) throw config_error(sc_, key + ".after", "no earlier event named '" + e.after + "'");
    ev.delay_ns = ceil_to_tick(e.delay, tick_ns_);
  }
  if (!e.when.empty()) {
    try {
      ev.column = rec_.column_index(e.when);
    } catch (const std::out_of_range&) {
      throw config_error(sc_, key + ".when", "this run records no column '" + e.when + "'");
    }
    ev.watch = true;
    ev.below = e.below.has_value();
    ev.threshold = e.below ? *e.below : e.above.value_or(0.0);
  }
  for (size_t j = 0; j < e.actions.size(); ++j) {
    const EventActionSpec& a = e.actions[j];
    std::string k;
    const std::string why = check_event_action(sc_, a, k);
    if (!why.empty()) throw config_error(sc_, key + ".actions[" + std::to_string(j) + "]." + k, why);
    Act act;
    resolve_event_device(sc_, a.device, act.target);
    if (act.target.device == EventDevice::Fsw && (!fsw_.accepts_commands() || !cmd_out_.valid()))
      throw config_error(sc_, key + ".actions[" + std::to_string(j) + "].device",
                         "this run's FSW (" + fsw_.describe() + ") takes no commands yet");
    act.action = find_event_action(act.target.device, a.action)->action;
    act.value = a.value;
    ev.acts.push_back(act);
    ev.entry.what += (j ? "; " : "") + a.device + " " + a.action;
    if (!std::isnan(a.value)) {
      std::ostringstream v;
      v.precision(10);
      v << a.value;
      ev.entry.what += " " + v.str();
    }
  }
  ev.entry.name = e.name;
  return ev;
}

void EventTask::operator()(uint64_t k)
{
  const uint64_t t_ns = k * tick_ns_;
  const double* row = nullptr;
  for (size_t i = 0; i < ev_.size(); ++i) {
    Ev& e = ev_[i];
    if (e.applied) continue;
    bool fire = false;
    if (e.watch) {
      if (!row) row = rec_.last_row();
      if (row) {
        const double x = row[e.column];
        fire = e.below ? x < e.threshold : x > e.threshold;
      }
    } else {
      fire = t_ns >= e.t_ns;
    }
    if (!fire) continue;
    bool attitude = false;
    for (const Act& a : e.acts) {
      apply(a, t_ns);
      attitude = attitude || a.action == EventAction::ScSigmaX || a.action == EventAction::ScSigmaY ||
                 a.action == EventAction::ScSigmaZ;
    }
    if (attitude) attitude_to_short_set();
    e.applied = true;
    e.entry.tick = k;
    e.entry.t = static_cast<double>(t_ns) / 1e9;  // as the recorded t
    log_.push_back(std::move(e.entry));
    log_index_.push_back(static_cast<uint32_t>(i));
    for (Ev& f : ev_)  // events that follow this one: their time is now known
      if (f.after == static_cast<int>(i))
        f.t_ns = f.delay_ns > std::numeric_limits<uint64_t>::max() - t_ns ? std::numeric_limits<uint64_t>::max()
                                                                          : t_ns + f.delay_ns;
  }
}

// One action on the device it names.
void EventTask::apply(const Act& a, uint64_t t_ns)
{
  switch (a.target.device) {
    case EventDevice::Wheel:
      if (a.action == EventAction::WheelSpeed)
        apply_state(a);
      else
        apply_wheel(a);
      break;
    case EventDevice::Spacecraft: apply_state(a); break;
    case EventDevice::Thruster: apply_thruster(a); break;
    case EventDevice::Fsw: apply_fsw(a, t_ns); break;
    case EventDevice::Magnetorquer: apply_magnetorquer(a, t_ns); break;
    case EventDevice::Atmosphere:
      if (drag_) drag_->set_density_scale(a.action == EventAction::AtmDensityScale ? a.value : density_scale_);
      break;
    case EventDevice::Magnetometer:
    case EventDevice::Gyro:
    case EventDevice::StarTracker:
    case EventDevice::Css: apply_sensor(a, t_ns); break;
  }
}

// One component of the plant's state (checked by check_event_action).
void EventTask::apply_state(const Act& a)
{
  const sim::StateLayout& L = plant_.layout();
  int at = 0;
  switch (a.action) {
    case EventAction::ScSigmaX: at = sim::StateLayout::sigma_BN; break;
    case EventAction::ScSigmaY: at = sim::StateLayout::sigma_BN + 1; break;
    case EventAction::ScSigmaZ: at = sim::StateLayout::sigma_BN + 2; break;
    case EventAction::ScOmegaX: at = sim::StateLayout::omega_BN_B; break;
    case EventAction::ScOmegaY: at = sim::StateLayout::omega_BN_B + 1; break;
    case EventAction::ScOmegaZ: at = sim::StateLayout::omega_BN_B + 2; break;
    case EventAction::ScPosX: at = sim::StateLayout::r_BN_N; break;
    case EventAction::ScPosY: at = sim::StateLayout::r_BN_N + 1; break;
    case EventAction::ScPosZ: at = sim::StateLayout::r_BN_N + 2; break;
    case EventAction::ScVelX: at = sim::StateLayout::v_BN_N; break;
    case EventAction::ScVelY: at = sim::StateLayout::v_BN_N + 1; break;
    case EventAction::ScVelZ: at = sim::StateLayout::v_BN_N + 2; break;
    case EventAction::ScPropellant: at = L.m_p(0); break;
    case EventAction::WheelSpeed: at = L.Omega(a.target.index); break;
    default: return;
  }
  sim::StateVector x = plant_.state();
  x[at] = a.value;
  plant_.set_state(x);
}

// After an event's actions: |sigma_BN| > 1 (components set one by one) is
// switched to the shadow set -sigma/|sigma|^2, the same attitude.
void EventTask::attitude_to_short_set()
{
  sim::StateVector x = plant_.state();
  const double s2 = x.segment<3>(sim::StateLayout::sigma_BN).squaredNorm();
  if (!(s2 > 1.0)) return;
  x.segment<3>(sim::StateLayout::sigma_BN) *= -1.0 / s2;
  plant_.set_state(x);
}

// Wheel health, limits and friction (plant); tachometer faults and the
// commanded availability (FSW input).
void EventTask::apply_wheel(const Act& a)
{
  const int i = a.target.index;
  using F = SensorSuite::Fault;
  const sim::ReactionWheelParams& p = sc_.wheels[static_cast<size_t>(i)].params;
  switch (a.action) {
    case EventAction::WheelFailOff: plant_.set_wheel_health(i, sim::WheelHealth::Off); break;
    case EventAction::WheelStuck: plant_.set_wheel_health(i, sim::WheelHealth::Stuck); break;
    case EventAction::WheelTorqueLimit: plant_.set_wheel_u_max(i, a.value); break;
    case EventAction::WheelFriction: {
      sim::WheelFrictionParams f = p.friction;
      f.tau_c *= a.value;
      f.tau_st *= a.value;
      f.c_v *= a.value;
      plant_.set_wheel_friction(i, f);
      break;
    }
    case EventAction::TachNan: sensors_.set_tach_fault(i, F::Nan, 0.0); break;
    case EventAction::TachFrozen: sensors_.set_tach_fault(i, F::Frozen, 0.0); break;
    case EventAction::TachBias: sensors_.set_tach_fault(i, F::Bias, a.value); break;
    case EventAction::TachNoiseScale: sensors_.set_tach_noise_scale(i, a.value); break;
    case EventAction::CommandUnavailable: sensors_.set_rw_commanded_unavailable(i, true); break;
    case EventAction::CommandAvailable: sensors_.set_rw_commanded_unavailable(i, false); break;
    case EventAction::Restore:
      plant_.set_wheel_health(i, sim::WheelHealth::Nominal);
      plant_.set_wheel_u_max(i, p.u_max);
      plant_.set_wheel_friction(i, p.friction);
      sensors_.set_tach_fault(i, F::None, 0.0);
      sensors_.set_tach_noise_scale(i, 1.0);
      break;
    default: break;
  }
}

// Thruster health and thrust scale (plant); the commanded availability (FSW input).
void EventTask::apply_thruster(const Act& a)
{
  const int i = a.target.index;
  switch (a.action) {
    case EventAction::ThrStuckClosed: plant_.set_thruster_health(i, sim::ThrusterHealth::FailedOff); break;
    case EventAction::ThrStuckOpen: plant_.set_thruster_health(i, sim::ThrusterHealth::StuckOn); break;
    case EventAction::ThrThrustFactor: plant_.set_thruster_thrust_scale(i, a.value); break;
    case EventAction::CommandUnavailable:
    case EventAction::CommandAvailable: {
      int j = 0;  // the FSW's index: the ACS thrusters in scenario order
      for (int m = 0; m < i; ++m) j += sc_.thrusters[static_cast<size_t>(m)].acs ? 1 : 0;
      sensors_.set_thr_commanded_unavailable(j, a.action == EventAction::CommandUnavailable);
      break;
    }
    default:  // restore (the availability flag is a command of its own)
      plant_.set_thruster_health(i, sim::ThrusterHealth::Nominal);
      plant_.set_thruster_thrust_scale(i, 1.0);
      break;
  }
}

// Mode, actuation, reference and gains: a command to the FSW.
void EventTask::apply_fsw(const Act& a, uint64_t t_ns)
{
  switch (a.action) {
    case EventAction::FswModeInertial: cmd_.mode = FSW_ACS_MODE_INERTIAL; break;
    case EventAction::FswModeSunSafe: cmd_.mode = FSW_ACS_MODE_SUN_SAFE; break;
    case EventAction::FswActuationWheels: cmd_.actuation = FSW_ACS_ACT_WHEELS; break;
    case EventAction::FswActuationThrusters: cmd_.actuation = FSW_ACS_ACT_THRUSTERS; break;
    case EventAction::FswReferenceX:
    case EventAction::FswReferenceY:
    case EventAction::FswReferenceZ:
      cmd_.set_ref = 1;
      cmd_.sigma_R0N[a.action == EventAction::FswReferenceX ? 0 : a.action == EventAction::FswReferenceY ? 1 : 2] =
          static_cast<fsw_real>(a.value);
      break;
    case EventAction::FswGainK:
      cmd_.set_gains = 1;
      cmd_.K = static_cast<fsw_real>(a.value);
      break;
    case EventAction::FswGainP:
      cmd_.set_gains = 1;
      cmd_.P = static_cast<fsw_real>(a.value);
      break;
    default: break;
  }
  cmd_out_.write(cmd_, t_ns);  // the FSW's from its next cycle (this tick's, when it runs now)
}

// Gyro, star tracker and coarse sun sensor faults, noise scale and bias.
void EventTask::apply_sensor(const Act& a, uint64_t t_ns)
{
  const int i = a.target.index;
  using F = SensorSuite::Fault;
  const F f = a.action == EventAction::SensorDropout ? F::Dropout
              : a.action == EventAction::SensorFrozen ? F::Frozen
                                                      : F::None;
  // a dropout longer than any run (> 9e9 s) lasts to the end
  const uint64_t until = f != F::Dropout ? 0
                         : a.value < 9e9 ? t_ns + static_cast<uint64_t>(std::llround(a.value * 1e9))
                                         : std::numeric_limits<uint64_t>::max();
  const EventAction x = a.action;
  const bool scale = x == EventAction::SensorNoiseScale, restore = x == EventAction::Restore;
  const int axis = x == EventAction::SensorBiasX ? 0 : x == EventAction::SensorBiasY ? 1 : x == EventAction::SensorBiasZ ? 2 : -1;
  const bool fault = !scale && axis < 0 && x != EventAction::SensorBias;  // dropout, frozen, restore
  const double k = scale ? a.value : 1.0;
  if (a.target.device == EventDevice::Gyro) {
    if (fault) sensors_.set_gyro_fault(f, until);
    if (scale || restore) sensors_.set_gyro_noise_scale(k);
    if (axis >= 0) sensors_.set_gyro_bias(axis, a.value);
    for (int b = 0; restore && b < 3; ++b) sensors_.set_gyro_bias(b, 0.0);
  } else if (a.target.device == EventDevice::StarTracker) {
    if (fault) sensors_.set_star_tracker_fault(f, until);
    if (scale || restore) sensors_.set_star_tracker_noise_scale(k);
    if (axis >= 0) sensors_.set_star_tracker_bias(axis, a.value);
    for (int b = 0; restore && b < 3; ++b) sensors_.set_star_tracker_bias(b, 0.0);
  } else if (a.target.device == EventDevice::Magnetometer) {
    if (fault) sensors_.set_magnetometer_fault(f, until);
    if (scale || restore) sensors_.set_magnetometer_noise_scale(k);
    if (axis >= 0) sensors_.set_magnetometer_bias(axis, a.value);
    for (int b = 0; restore && b < 3; ++b) sensors_.set_magnetometer_bias(b, 0.0);
  } else {
    if (fault) sensors_.set_css_fault(i, f, until);
    if (scale || restore) sensors_.set_css_noise_scale(i, k);
    if (x == EventAction::SensorBias || restore) sensors_.set_css_bias(i, restore ? 0.0 : a.value);
  }
}

void EventTask::attach_atmosphere(sim::DragEffector* drag, double scale)
{
  drag_ = drag;
  density_scale_ = scale;
}

void EventTask::attach_magnetorquers(sim::MagneticEffector* mag, Writer<MtqCmdMsg> cmd)
{
  mag_ = mag;
  mtq_cmd_ = cmd;
}

// Rod health and scale (the plant's magnetic effector); a dipole command
// (the `mtq_cmd` message, taken by the rods at the next control instant).
void EventTask::apply_magnetorquer(const Act& a, uint64_t t_ns)
{
  if (!mag_) return;
  const int i = a.target.index;
  switch (a.action) {
    case EventAction::MtqFailOff: mag_->set_rod_health(i, sim::MagnetorquerHealth::FailedOff); break;
    case EventAction::MtqStuck: mag_->set_rod_health(i, sim::MagnetorquerHealth::Stuck); break;
    case EventAction::MtqScale: mag_->set_rod_scale(i, a.value); break;
    case EventAction::MtqDipole: {
      if (!mtq_cmd_.valid()) break;  // the FSW commands the rods (rejected at load: scenario_events.cpp)
      MtqCmdMsg c = mtq_cmd_.channel().value();
      c.m_cmd[i] = a.value;
      mtq_cmd_.write(c, t_ns);
      break;
    }
    default:  // restore
      mag_->set_rod_health(i, sim::MagnetorquerHealth::Nominal);
      mag_->set_rod_scale(i, 1.0);
      break;
  }
}

}  // namespace harness

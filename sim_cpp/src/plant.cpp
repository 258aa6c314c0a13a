// plant: see sim/plant.h.  docs/dynamics.md §1, §4.3, §4.6, §5, §7.
#include "sim/plant.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/attitude.h"
#include "sim/rk4.h"
#include "sim/units.h"
#include "validate_util.h"

namespace sim {

namespace {

using Eigen::Vector3d;

// Events closer than this fraction of the segment to a sub-step end are not
// split points (they would create sub-steps of ~1e-18 s from the rounding of
// t_latch + T_on).  The impulse error this allows is < F * 1e-13 * dt.
constexpr double kEventSnapRel = 1e-13;

SpacecraftModel make_model(SpacecraftParams sc, const PropulsionParams& prop)
{
  const size_t n_tank = prop.tanks.size();
  if (n_tank > static_cast<size_t>(kMaxTanks))
    detail::fail("tanks.size()", static_cast<double>(n_tank), "must be <= sim::kMaxTanks");
  for (size_t k = 0; k < n_tank; ++k) validate(prop.tanks[k], "tanks[" + std::to_string(k) + "]");
  return SpacecraftModel(std::move(sc), static_cast<int>(n_tank));
}

}  // namespace

// ------------------------------------------------------------------ set-up

Plant::Plant(PlantParams params, const InitialConditions& ic)
    : model_(make_model(std::move(params.sc), params.prop)),
      tanks_(std::move(params.prop.tanks)),
      merger_(model_.params().hub, tanks_.data(), static_cast<int>(tanks_.size())),
      thr_(std::move(params.prop.thrusters), static_cast<int>(tanks_.size()), params.prop.command)
{
  extra_.reserve(static_cast<size_t>(kMaxEffectors - 1));
  // Tanks full, then the C-point initial conditions converted with that hub (§1).
  StateVector x(layout().size());
  x.setZero();
  for (int k = 0; k < num_tanks(); ++k) x(layout().m_p(k)) = tanks_[static_cast<size_t>(k)].m_p0;
  x_ = model_.initial_state(ic, hub_with_propellant(x));
  for (int k = 0; k < num_tanks(); ++k) x_(layout().m_p(k)) = x(layout().m_p(k));
  prepare_effectors_now();
}

void Plant::add_effector_impl(std::unique_ptr<ForceTorqueEffector> e)
{
  if (!e) detail::fail("effector", 0.0, "must not be null");
  if (num_effectors() >= kMaxEffectors)
    detail::fail("effectors.size()", num_effectors() + 1, "must be <= sim::kMaxEffectors");
  extra_.push_back(std::move(e));
  extra_.back()->prepare_now(t_ns_);
}

void Plant::prepare_effectors_now()
{
  const int64_t t = t_ns_;
  for_each_effector([t](ForceTorqueEffector& e) { e.prepare_now(t); });
}

void Plant::set_state(const StateVector& x)
{
  if (x.size() != layout().size())
    detail::fail("state.size()", static_cast<double>(x.size()), "must equal 12 + 2*num_rw + num_tanks");
  x_ = x;
}

void Plant::state_io(StateIO& io)
{
  int dim = static_cast<int>(x_.size());
  io.value("plant.state_dim", dim);
  if (dim != layout().size()) throw std::runtime_error("checkpoint: the plant's state has another size");
  io.bytes("plant.x", x_.data(), sizeof(double) * static_cast<size_t>(dim));
  io.value("plant.t_ns", t_ns_);
  io.value("plant.held", held_);
  io.value("plant.wheel_health", wheel_health_);
  io.value("plant.Omega_prev", Omega_prev_);
  io.value("plant.first_step", first_step_);
  io.value("plant.switches", switches_);
  io.value("plant.steps", steps_);
  io.value("plant.split_sub_steps", split_sub_steps_);
  io.value("plant.status", status_);
  for (int i = 0; i < num_rw(); ++i) {  // the wheel parameters settable during a run
    ReactionWheelParams w = wheel_params(i);
    io.value("wheel.u_max", w.u_max);
    io.value("wheel.Omega_max", w.Omega_max);
    io.value("wheel.friction", w.friction);
    if (!io.loading()) continue;
    model_.set_wheel_u_max(i, w.u_max);
    model_.set_wheel_Omega_max(i, w.Omega_max);
    model_.set_wheel_friction(i, w.friction);
  }
  for_each_effector([&io](ForceTorqueEffector& e) { e.state_io(io); });
}

void Plant::check_wheel_index(int i) const
{
  if (i < 0 || i >= num_rw()) detail::fail("wheel index", i, "must be in [0, num_rw)");
}

const ReactionWheelParams& Plant::wheel_params(int i) const
{
  return model_.params().wheels[static_cast<size_t>(i)];
}

// ------------------------------------------------------------------ inputs

void Plant::latch_wheel_commands(const WheelArray& u_cmd) { latch_wheel_commands(u_cmd.data()); }

void Plant::latch_wheel_commands(const double* u_cmd)
{
  const std::vector<ReactionWheelParams>& wheels = model_.params().wheels;
  for (int i = 0; i < num_rw(); ++i) {
    const auto ui = static_cast<size_t>(i);
    held_.wheels.u_s[ui] =
        wheel_health_[ui] != WheelHealth::Nominal ? 0.0 : command_pipeline(wheels[ui], u_cmd[i], Omega(i));
  }
}

void Plant::command_thrusters(const ThrusterArray& T_req) { thr_.command(T_req); }

void Plant::set_external(const Eigen::Vector3d& F_ext_B, const Eigen::Vector3d& L_ext_B)
{
  held_.loads.F_ext_B = F_ext_B;
  held_.loads.L_ext_B = L_ext_B;
}

// ------------------------------------------------------- device parameters

void Plant::set_wheel_u_max(int i, double u_max) { model_.set_wheel_u_max(i, u_max); }

void Plant::set_wheel_Omega_max(int i, double Omega_max) { model_.set_wheel_Omega_max(i, Omega_max); }

void Plant::set_wheel_friction(int i, const WheelFrictionParams& f)
{
  model_.set_wheel_friction(i, f);
  // beta_st <= 0 now: the Stribeck flag cannot stay set (§4.6)
  if (!(f.beta_st > 0.0)) held_.wheels.stribeck[static_cast<size_t>(i)] = false;
}

void Plant::set_wheel_health(int i, WheelHealth h)
{
  check_wheel_index(i);
  const int hv = static_cast<int>(h);
  if (hv < 0 || hv > 2)
    detail::fail("wheels[" + std::to_string(i) + "].health", hv, "must be Nominal, Off or Stuck");
  const auto ui = static_cast<size_t>(i);
  wheel_health_[ui] = h;
  if (h != WheelHealth::Nominal) held_.wheels.u_s[ui] = 0.0;
  held_.wheels.stuck[ui] = h == WheelHealth::Stuck;
  if (h == WheelHealth::Stuck) held_.wheels.stribeck[ui] = false;  // no friction acts while held
}

void Plant::set_thruster_health(int j, ThrusterHealth h) { thr_.set_health(j, h); }
void Plant::set_thruster_thrust_scale(int j, double s) { thr_.set_thrust_scale(j, s); }

// --------------------------------------------------------------- accessors

double Plant::tau_f(int i) const
{
  return model_.friction_torque(i, x_, held_.wheels.stribeck[static_cast<size_t>(i)]);
}

ThrusterCounters Plant::counters() const
{
  ThrusterCounters c = thr_.counters();
  c.split_sub_steps = split_sub_steps_;
  return c;
}

HubParams Plant::hub_with_propellant(const StateVector& x) const
{
  TankArray m_p{};
  for (int k = 0; k < num_tanks(); ++k) m_p[static_cast<size_t>(k)] = x(layout().m_p(k));
  return merger_.merge(m_p);
}

void Plant::fill_sensor_truth(SensorTruth& out, const Eigen::Vector3d& r_SunN_N, double f_illum) const
{
  out.t_ns = t_ns_;
  out.sigma_BN = sigma_BN();
  out.omega_BN_B = omega_BN_B();
  out.r_BN_N = r_BN_N();
  out.r_SunN_N = r_SunN_N;
  out.f_illum = f_illum;
  out.Omega.fill(0.0);
  for (int i = 0; i < num_rw(); ++i) out.Omega[static_cast<size_t>(i)] = Omega(i);
}

const RotorSinCos* Plant::rotor_sin_cos_now() const
{
  if (!model_.needs_rotor_angles()) return nullptr;
  bool same = rotor_now_set_;
  for (int i = 0; i < num_rw(); ++i) {  // the angles' bits (-0 and +0 differ, as their sines do)
    uint64_t b = 0;
    std::memcpy(&b, &x_(layout().theta(i)), sizeof b);
    same = same && b == rotor_now_theta_[static_cast<size_t>(i)];
    rotor_now_theta_[static_cast<size_t>(i)] = b;
  }
  if (!same) {
    model_.rotor_sin_cos(x_, rotor_now_);
    rotor_now_set_ = true;
  }
  return &rotor_now_;
}

SensorTruth Plant::sensor_truth(const Eigen::Vector3d& r_SunN_N, double f_illum) const
{
  SensorTruth t;
  fill_sensor_truth(t, r_SunN_N, f_illum);
  return t;
}

// ------------------------------------------------------------- derivatives

StateVector Plant::derivatives(double t, const StateVector& x, Accelerations* acc) const
{
  // Every force/torque effector adds onto the held external loads, in list
  // order (thrusters first), then the hub and wheels with the stage hub.
  EffectorSums sums;
  sums.F_B = held_.loads.F_ext_B;
  sums.L_B = held_.loads.L_ext_B;
  const EffectorStage stage{t, x, layout()};
  thr_.accumulate(stage, sums);
  for (const auto& e : extra_) e->accumulate(stage, sums);

  ExternalLoads loads;
  loads.F_ext_B = sums.F_B;
  loads.L_ext_B = sums.L_B;
  const RotorSinCos* sc = &x == &x_ ? rotor_sin_cos_now() : nullptr;  // a step's first stage
  StateVector xd = num_tanks() == 0
                       ? model_.derivatives(t, x, held_.wheels, loads, model_.params().hub, acc, sc)
                       : model_.derivatives(t, x, held_.wheels, loads, hub_with_propellant(x), acc, sc);
  for (int k = 0; k < num_tanks(); ++k) xd(layout().m_p(k)) = sums.m_p_dot[static_cast<size_t>(k)];
  return xd;
}

// ---------------------------------------------------------------- the step

bool Plant::integrate_segment(int64_t t0_ns, int64_t t1_ns)
{
  const double H = seconds_from_ns(t1_ns - t0_ns);
  const double snap = kEventSnapRel * H;
  for_each_effector([t0_ns](ForceTorqueEffector& e) { e.begin_segment(t0_ns); });

  double tau = 0.0;
  while (tau < H) {
    double next = H;
    for_each_effector([&](ForceTorqueEffector& e) { next = std::min(next, e.next_event(tau, H, snap)); });
    if (next < H) ++split_sub_steps_;
    for_each_effector([tau, next](ForceTorqueEffector& e) { e.begin_substep(tau, next); });

    StateVector x_next = rk4_step(x_, tau, next - tau,
                                  [this](double t, const StateVector& x) { return derivatives(t, x); });
    if (!x_next.allFinite()) return false;
    const Vector3d sigma = x_next.segment<3>(StateLayout::sigma_BN);
    if (sigma.squaredNorm() > 1.0) {  // §7.4: after every completed (sub-)step
      x_next.segment<3>(StateLayout::sigma_BN) = mrp_shadow(sigma);
      ++switches_;
    }
    for (int k = 0; k < num_tanks(); ++k) {  // §5.6: clamp at 0
      double& m_p = x_next(layout().m_p(k));
      if (m_p < 0.0) m_p = 0.0;
    }
    x_ = x_next;
    for_each_effector([](ForceTorqueEffector& e) { e.end_substep(); });
    tau = next;
  }
  return true;
}

StepStatus Plant::step(int64_t dt_ns)
{
  if (status_ != StepStatus::Ok) return status_;
  if (dt_ns <= 0) detail::fail("step dt_ns", static_cast<double>(dt_ns), "must be > 0");
  for (int i = 0; i < num_rw(); ++i) {  // §4.6, once per step at its start
    const auto ui = static_cast<size_t>(i);
    const double Om = Omega(i);
    const double dOm = first_step_ ? 0.0 : Om - Omega_prev_[ui];
    held_.wheels.stribeck[ui] =
        update_stribeck_mode(wheel_params(i).friction, held_.wheels.stribeck[ui], Om, dOm);
    Omega_prev_[ui] = Om;
  }
  first_step_ = false;

  // Segments: cut where an effector has a discrete action (a thruster latch
  // instant while a message is pending, §5.2); the action runs at the cut.
  const StateVector x_start = x_;
  const int64_t t_end = t_ns_ + dt_ns;
  int64_t t0 = t_ns_;
  while (t0 < t_end) {
    for_each_effector([t0](ForceTorqueEffector& e) { e.at_instant(t0); });
    int64_t t1 = t_end;
    for_each_effector([&](ForceTorqueEffector& e) { t1 = std::min(t1, e.next_cut_ns(t0)); });
    if (!integrate_segment(t0, t1)) {
      x_ = x_start;
      status_ = StepStatus::NonFiniteState;
      prepare_effectors_now();
      return status_;
    }
    t0 = t1;
  }
  t_ns_ = t_end;
  ++steps_;
  prepare_effectors_now();
  return status_;
}

}  // namespace sim

namespace sim {

const Eigen::Matrix3d& EffectorStage::dcm_NB() const
{
  if (!dcm_ready) {
    dcm_NB_cache = dcm_BN_from_sigma(x.segment<3>(StateLayout::sigma_BN)).transpose();
    dcm_ready = true;
  }
  return dcm_NB_cache;
}

}  // namespace sim

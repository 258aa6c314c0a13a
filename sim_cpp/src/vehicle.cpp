// vehicle: see sim/vehicle.h.  Spec plant-dynamics §5, §7.2-§7.3.
#include "sim/vehicle.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "sim/attitude.h"
#include "sim/rk4.h"
#include "validate_util.h"

namespace sim {

namespace {

using Eigen::Vector3d;

// Events closer than this fraction of the segment to a sub-step end are not
// split points (they would create sub-steps of ~1e-18 s from the rounding of
// t_latch + T_on).  The impulse error this allows is < F * 1e-13 * dt.
constexpr double kEventSnapRel = 1e-13;

}  // namespace

VehicleState operator+(const VehicleState& a, const VehicleState& b)
{
  VehicleState r;
  r.sc = a.sc + b.sc;
  r.prop = a.prop + b.prop;
  return r;
}

VehicleState operator*(double s, const VehicleState& a)
{
  VehicleState r;
  r.sc = s * a.sc;
  r.prop = s * a.prop;
  return r;
}

// ---------------------------------------------------------------- the model

VehicleModel::VehicleModel(SpacecraftParams sc, PropulsionParams prop)
    : sc_(std::move(sc)), prop_(std::move(prop))
{
  using namespace detail;
  const size_t n_thr = prop_.thrusters.size();
  const size_t n_tank = prop_.tanks.size();
  if (n_thr > static_cast<size_t>(kMaxThrusters))
    fail("thrusters.size()", static_cast<double>(n_thr), "must be <= sim::kMaxThrusters");
  if (n_tank > static_cast<size_t>(kMaxTanks))
    fail("tanks.size()", static_cast<double>(n_tank), "must be <= sim::kMaxTanks");
  for (size_t k = 0; k < n_tank; ++k) validate(prop_.tanks[k], "tanks[" + std::to_string(k) + "]");
  for (size_t j = 0; j < n_thr; ++j) {
    const std::string name = "thrusters[" + std::to_string(j) + "]";
    validate(prop_.thrusters[j], name);
    if (prop_.thrusters[j].tank >= static_cast<int>(n_tank))
      fail(name + ".tank", prop_.thrusters[j].tank, "must be < tanks.size() (or -1)");
  }
  validate(prop_.command, "command");
  layout_.num_thr = static_cast<int>(n_thr);
  layout_.num_tanks = static_cast<int>(n_tank);
}

HubParams VehicleModel::hub_with_propellant(const VehicleState& x) const
{
  TankArray m_p{};
  for (int k = 0; k < num_tanks(); ++k) m_p[static_cast<size_t>(k)] = x.prop(layout_.m_p(k));
  return merge_tanks_into_hub(sc_.params().hub, prop_.tanks.data(), num_tanks(), m_p);
}

VehicleState VehicleModel::initial_state(const InitialConditions& ic) const
{
  VehicleState x;
  x.prop.setZero(layout_.size());
  for (int k = 0; k < num_tanks(); ++k)
    x.prop(layout_.m_p(k)) = prop_.tanks[static_cast<size_t>(k)].m_p0;
  x.sc = sc_.initial_state(ic, hub_with_propellant(x));
  return x;
}

MassProps VehicleModel::mass_props(const VehicleState& x) const
{
  return sc_.mass_props(x.sc, hub_with_propellant(x));
}

EnergyMomentum VehicleModel::energy_momentum(const VehicleState& x) const
{
  return sc_.energy_momentum(x.sc, hub_with_propellant(x));
}

double VehicleModel::kappa(int j, double t, const VehicleState& x, const SubStepInputs& in) const
{
  const auto uj = static_cast<size_t>(j);
  const ThrusterParams& p = prop_.thrusters[uj];
  if (p.transient == ThrusterTransient::FirstOrder) return x.prop(layout_.kappa(j));
  return scheduled_kappa(p, in.schedule[uj], in.s_at_t0[uj] + t, in.open[uj]);
}

ThrusterEffect VehicleModel::effect(int j, double kappa, const VehicleState& x) const
{
  const ThrusterParams& p = prop_.thrusters[static_cast<size_t>(j)];
  if (p.tank >= 0 && !(x.prop(layout_.m_p(p.tank)) > 0.0)) return ThrusterEffect{};  // §5.6 empty tank
  return thruster_effect(p, kappa);
}

VehicleState VehicleModel::derivatives(double t, const VehicleState& x, const SubStepInputs& in,
                                       Accelerations* acc) const
{
  VehicleState xd;
  xd.prop.setZero(layout_.size());
  HeldInputs held = in.sc;
  for (int j = 0; j < num_thr(); ++j) {
    const auto uj = static_cast<size_t>(j);
    const ThrusterParams& p = prop_.thrusters[uj];
    const double k = kappa(j, t, x, in);
    const ThrusterEffect e = effect(j, k, x);
    held.F_ext_B += e.F_B;
    held.L_ext_B += e.L_B;
    if (p.tank >= 0) xd.prop(layout_.m_p(p.tank)) -= e.mdot;
    if (p.transient == ThrusterTransient::FirstOrder)  // §5.3
      xd.prop(layout_.kappa(j)) = in.open[uj] ? p.omega_on * (1.0 - k) : -p.omega_off * k;
  }
  xd.sc = sc_.derivatives(t, x.sc, held, hub_with_propellant(x), acc);
  return xd;
}

// ------------------------------------------------------------------ the run

Vehicle::Vehicle(SpacecraftParams sc, PropulsionParams prop, const InitialConditions& ic)
    : model_(std::move(sc), std::move(prop)), x_(model_.initial_state(ic))
{
  for (int j = 0; j < model_.num_thr(); ++j)
    in_.schedule[static_cast<size_t>(j)] =
        initial_schedule(model_.propulsion().thrusters[static_cast<size_t>(j)]);
}

void Vehicle::set_state(const VehicleState& x)
{
  if (x.sc.size() != model_.spacecraft().layout().size())
    detail::fail("state.sc.size()", static_cast<double>(x.sc.size()), "must match the wheel count");
  if (x.prop.size() != model_.prop_layout().size())
    detail::fail("state.prop.size()", static_cast<double>(x.prop.size()),
                 "must equal num_thr + num_tanks");
  x_ = x;
}

void Vehicle::latch_wheel_commands(const WheelArray& u_cmd)
{
  const SpacecraftModel& m = model_.spacecraft();
  for (int i = 0; i < m.num_rw(); ++i) {
    const auto ui = static_cast<size_t>(i);
    in_.sc.u_s[ui] = command_pipeline(m.params().wheels[ui], u_cmd[ui], Omega(i));
  }
}

void Vehicle::set_external(const Eigen::Vector3d& F_ext_B, const Eigen::Vector3d& L_ext_B)
{
  in_.sc.F_ext_B = F_ext_B;
  in_.sc.L_ext_B = L_ext_B;
}

void Vehicle::command_thrusters(const ThrusterArray& T_req)
{
  T_req_ = T_req;
  command_pending_ = true;
}

double Vehicle::s_since_latch(int j, int64_t t_ns) const
{
  return static_cast<double>(t_ns - in_.schedule[static_cast<size_t>(j)].t_latch_ns) * 1e-9;
}

double Vehicle::kappa(int j) const
{
  const auto uj = static_cast<size_t>(j);
  const ThrusterParams& p = model_.propulsion().thrusters[uj];
  if (p.transient == ThrusterTransient::FirstOrder) return x_.prop(model_.prop_layout().kappa(j));
  const double s = s_since_latch(j, t_ns_);
  return scheduled_kappa(p, in_.schedule[uj], s, sim::valve_open(in_.schedule[uj], s));
}

bool Vehicle::valve_open(int j) const
{
  return sim::valve_open(in_.schedule[static_cast<size_t>(j)], s_since_latch(j, t_ns_));
}

ThrusterEffect Vehicle::thruster_effect(int j) const
{
  return model_.effect(j, kappa(j), x_);
}

void Vehicle::latch_thrusters(int64_t t_L_ns)
{
  for (int j = 0; j < model_.num_thr(); ++j) {
    const auto uj = static_cast<size_t>(j);
    const ThrusterParams& p = model_.propulsion().thrusters[uj];
    const double s = s_since_latch(j, t_L_ns);
    const double kappa_now =
        p.transient == ThrusterTransient::FirstOrder
            ? x_.prop(model_.prop_layout().kappa(j))
            : scheduled_kappa(p, in_.schedule[uj], s, sim::valve_open(in_.schedule[uj], s));
    const bool firing = valve_firing(in_.schedule[uj], s);
    if (latch_thruster(p, model_.propulsion().command, T_req_[uj], t_L_ns, kappa_now, firing,
                       in_.schedule[uj]) == LatchResult::IgnoredMinOnTime)
      ++counters_.ignored_min_on;
  }
  command_pending_ = false;
  ++counters_.latches;
}

bool Vehicle::integrate_segment(int64_t t0_ns, int64_t t1_ns)
{
  const int n_thr = model_.num_thr();
  const auto& thr = model_.propulsion().thrusters;
  const double H = static_cast<double>(t1_ns - t0_ns) * 1e-9;
  const double snap = kEventSnapRel * H;
  for (int j = 0; j < n_thr; ++j) in_.s_at_t0[static_cast<size_t>(j)] = s_since_latch(j, t0_ns);

  double tau = 0.0;
  while (tau < H) {
    // Next event in (tau + snap, H - snap): valve closings and Table breakpoints.
    double next = H;
    const auto consider = [&](double e) {
      if (e > tau + snap && e < next && e < H - snap) next = e;
    };
    for (int j = 0; j < n_thr; ++j) {
      const auto uj = static_cast<size_t>(j);
      const ValveSchedule& s = in_.schedule[uj];
      const double s0 = in_.s_at_t0[uj];
      consider(s.T_on - s0);  // valve closing (opening happens only at latches)
      if (thr[uj].transient != ThrusterTransient::Table) continue;
      for (const RampPoint& q : thr[uj].on_ramp)  // on-ramp knots, while open
        if (q.t > s.tau_on0 && q.t - s.tau_on0 < s.T_on) consider(q.t - s.tau_on0 - s0);
      for (const RampPoint& q : thr[uj].off_ramp)  // off-ramp knots, after closing
        if (q.t > s.tau_off0) consider(s.T_on + (q.t - s.tau_off0) - s0);
    }
    if (next < H) ++counters_.split_sub_steps;

    const double mid = 0.5 * (tau + next);
    for (int j = 0; j < n_thr; ++j) {
      const auto uj = static_cast<size_t>(j);
      in_.open[uj] = sim::valve_open(in_.schedule[uj], in_.s_at_t0[uj] + mid);
    }
    const VehicleModel& m = model_;
    const SubStepInputs& in = in_;
    VehicleState x_next = rk4_step(x_, tau, next - tau, [&m, &in](double t, const VehicleState& x) {
      return m.derivatives(t, x, in);
    });
    if (!x_next.sc.allFinite() || !x_next.prop.allFinite()) return false;
    const Vector3d sigma = x_next.sc.segment<3>(StateLayout::sigma_BN);
    if (sigma.squaredNorm() > 1.0) {  // §7.4: after every completed (sub-)step
      x_next.sc.segment<3>(StateLayout::sigma_BN) = mrp_shadow(sigma);
      ++switches_;
    }
    for (int k = 0; k < model_.num_tanks(); ++k) {  // §5.6: clamp at 0
      double& m_p = x_next.prop(model_.prop_layout().m_p(k));
      if (m_p < 0.0) m_p = 0.0;
    }
    x_ = x_next;
    tau = next;
  }
  return true;
}

StepStatus Vehicle::step(int64_t dt_ns)
{
  if (status_ != StepStatus::Ok) return status_;
  if (dt_ns <= 0) detail::fail("step dt_ns", static_cast<double>(dt_ns), "must be > 0");
  const SpacecraftModel& scm = model_.spacecraft();
  for (int i = 0; i < scm.num_rw(); ++i) {  // §4.6, once per step at its start
    const auto ui = static_cast<size_t>(i);
    const double Om = Omega(i);
    const double dOm = first_step_ ? 0.0 : Om - Omega_prev_[ui];
    in_.sc.stribeck[ui] =
        update_stribeck_mode(scm.params().wheels[ui].friction, in_.sc.stribeck[ui], Om, dOm);
    Omega_prev_[ui] = Om;
  }
  first_step_ = false;

  // Latch instants k*T_upd (§5.2) cut the step only while a command message
  // is pending (the latch is the only thing that happens there).
  const VehicleState x_start = x_;
  const int64_t T_upd = model_.propulsion().command.T_upd_ns;
  const int64_t t_end = t_ns_ + dt_ns;
  int64_t t0 = t_ns_;
  while (t0 < t_end) {
    if (t0 % T_upd == 0 && command_pending_) latch_thrusters(t0);
    const int64_t t1 = command_pending_ ? std::min(t_end, (t0 / T_upd + 1) * T_upd) : t_end;
    if (!integrate_segment(t0, t1)) {
      x_ = x_start;
      status_ = StepStatus::NonFiniteState;
      return status_;
    }
    t0 = t1;
  }
  t_ns_ = t_end;
  return status_;
}

}  // namespace sim

// thruster_set: see sim/thruster_set.h.  docs/dynamics.md §5.2-§5.4, §7.3.
#include "sim/thruster_set.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "sim/units.h"
#include "validate_util.h"

namespace sim {

namespace {
// A thruster's effect with its force, torque and mass flow times s (exact for s = 1).
ThrusterEffect scaled(ThrusterEffect e, double s)
{
  e.F_B *= s;
  e.L_B *= s;
  e.mdot *= s;
  return e;
}

// RK4's defect in the first moment of e^{-w s} over a sub-step, per unit
// amplitude, z = w h > 0, e_half = e^{-z/2}:
//   (z - 1 + e^{-z}) / z^2 - (1 + 2 e^{-z/2}) / 6
//   = sum_{k>=3} (-z)^k [1/(k+2)! - 1/(3 2^k k!)]  (= -z^3/720 + ...).
// Below z = 1 the series (the closed form's leading terms cancel there, to
// eps/z absolute); its 20 terms leave < 1/24! ~ 2e-24.
constexpr int kMomentTerms = 20;  // k = 3 .. 22
constexpr std::array<double, kMomentTerms> moment_series()
{
  std::array<double, kMomentTerms> c{};
  double fact = 2.0;  // k! at k = 2
  for (int k = 3; k < 3 + kMomentTerms; ++k) {
    fact *= k;
    double pow2 = 1.0;
    for (int i = 0; i < k; ++i) pow2 *= 2.0;
    c[static_cast<size_t>(k - 3)] = 1.0 / (fact * (k + 1) * (k + 2)) - 1.0 / (3.0 * pow2 * fact);
  }
  return c;
}
constexpr std::array<double, kMomentTerms> kMomentSeries = moment_series();

double first_moment_rk4_defect(double z, double e_half)
{
  if (z >= 1.0) return (std::expm1(-z) + z) / (z * z) - (1.0 + 2.0 * e_half) / 6.0;
  double sum = 0.0;
  for (int i = kMomentTerms - 1; i >= 0; --i) sum = sum * (-z) + kMomentSeries[static_cast<size_t>(i)];
  return -z * z * z * sum;
}
}  // namespace

ThrusterSet::ThrusterSet(std::vector<ThrusterParams> thrusters, int num_tanks,
                         ThrusterCommandParams command)
    : p_(std::move(thrusters)), cmd_(command)
{
  using namespace detail;
  scale_.fill(1.0);
  const size_t n_thr = p_.size();
  if (n_thr > static_cast<size_t>(kMaxThrusters))
    fail("thrusters.size()", static_cast<double>(n_thr), "must be <= sim::kMaxThrusters");
  for (size_t j = 0; j < n_thr; ++j) {
    const std::string name = "thrusters[" + std::to_string(j) + "]";
    validate(p_[j], name);
    if (p_[j].tank >= num_tanks) fail(name + ".tank", p_[j].tank, "must be < tanks.size() (or -1)");
  }
  validate(cmd_, "command");
  for (size_t j = 0; j < n_thr; ++j) {
    sched_[j] = initial_schedule(p_[j]);
    refresh_unit(j);
  }
  prepare_now(0);
}

void ThrusterSet::refresh_unit(size_t j) { unit_[j] = scaled(thruster_effect(p_[j], 1.0), scale_[j]); }

void ThrusterSet::command(const ThrusterArray& T_req)
{
  T_req_ = T_req;
  pending_ = true;
}

namespace {

// [s] Open time of schedule s over [t_latch, t_ns]: the valve is open on
// [t_latch, t_latch + T_on).
double open_time_until(const ValveSchedule& s, int64_t t_ns)
{
  const double since = seconds_from_ns(t_ns - s.t_latch_ns);
  return since <= 0.0 ? 0.0 : std::min(since, s.T_on);
}

}  // namespace

double ThrusterSet::s_since_latch(int j, int64_t t_ns) const
{
  return seconds_from_ns(t_ns - sched_[static_cast<size_t>(j)].t_latch_ns);
}

double ThrusterSet::kappa(int j) const
{
  const auto uj = static_cast<size_t>(j);
  const ThrusterParams& p = p_[uj];
  if (health_[uj] == ThrusterHealth::FailedOff) return 0.0;
  if (p.transient == ThrusterTransient::FirstOrder) return kappa_fo_[uj];
  const double s = s_since_latch(j, t0_ns_);
  return scheduled_kappa(p, sched_[uj], s, sim::valve_open(sched_[uj], s));
}

bool ThrusterSet::valve_open(int j) const
{
  return sim::valve_open(sched_[static_cast<size_t>(j)], s_since_latch(j, t0_ns_));
}

ThrusterEffect ThrusterSet::effect(int j, const StateVector& x, const StateLayout& L) const
{
  const auto uj = static_cast<size_t>(j);
  const ThrusterParams& p = p_[uj];
  if (health_[uj] == ThrusterHealth::FailedOff) return ThrusterEffect{};
  if (p.tank >= 0 && !(x(L.m_p(p.tank)) > 0.0)) return ThrusterEffect{};  // §5.6 empty tank
  return scaled(unit_[uj], kappa(j));
}

void ThrusterSet::set_thrust_scale(int j, double s)
{
  if (j < 0 || j >= num_thr()) detail::fail("thruster index", j, "must be in [0, num_thr)");
  if (!(s >= 0.0) || !std::isfinite(s))
    detail::fail("thrusters[" + std::to_string(j) + "].thrust_scale", s, "must be finite and >= 0");
  scale_[static_cast<size_t>(j)] = s;
  refresh_unit(static_cast<size_t>(j));
}

void ThrusterSet::set_health(int j, ThrusterHealth h)
{
  if (j < 0 || j >= num_thr()) detail::fail("thruster index", j, "must be in [0, num_thr)");
  const int hv = static_cast<int>(h);
  if (hv < 0 || hv > 2)
    detail::fail("thrusters[" + std::to_string(j) + "].health", hv, "must be Nominal, FailedOff or StuckOn");
  const auto uj = static_cast<size_t>(j);
  const ThrusterParams& p = p_[uj];
  const double kappa_now = kappa(j);
  ValveSchedule& s = sched_[uj];
  const ThrusterHealth old = health_[uj];
  open_done_[uj] += open_time_until(s, t0_ns_);  // the running schedule is replaced now
  health_[uj] = h;
  switch (h) {
    case ThrusterHealth::FailedOff:  // closed now, no tail
      s = initial_schedule(p);
      s.t_latch_ns = t0_ns_;
      kappa_fo_[uj] = 0.0;
      break;
    case ThrusterHealth::StuckOn:  // open from now on, rising from the present factor
      s.t_latch_ns = t0_ns_;
      s.T_on = std::numeric_limits<double>::infinity();
      if (p.transient == ThrusterTransient::Table) s.tau_on0 = ramp_entry_time(p.on_ramp, kappa_now, true);
      break;
    case ThrusterHealth::Nominal:
      if (old == ThrusterHealth::StuckOn) {  // the valve closes now; commands act again
        s.t_latch_ns = t0_ns_;
        s.T_on = 0.0;
        if (p.transient == ThrusterTransient::Table)
          s.tau_off0 = ramp_entry_time(p.off_ramp, kappa_now, false);
      }
      break;
  }
  prepare_now(t0_ns_);
}

// ------------------------------------------------------------------ physics

double ThrusterSet::first_order_closed_form(size_t j, double t) const
{
  const FirstOrderStage& f = fo_[j];
  const double s = t - stage_t_[0];
  return f.kappa_c + f.d0 * std::exp(-f.w * s) + f.delta + f.slope * s;
}

void ThrusterSet::accumulate(const EffectorStage& stage, EffectorSums& sums) const
{
  if (!substep_formed_) form_substep(0.0, 0.0);  // between steps: the state of now
  if (num_active_ == 0) return;
  // Which RK4 stage time of the current sub-step t is (the same for every
  // FirstOrder thruster), or -1.
  const double t = stage.t;
  const int k = t == stage_t_[0] ? 0 : t == stage_t_[1] ? 1 : t == stage_t_[2] ? 2 : -1;
  // §5.6: a thruster whose tank is empty at this stage gives nothing.
  std::array<bool, kMaxTanks> dry{};
  for (int m = 0; m < stage.layout.num_tanks; ++m)
    dry[static_cast<size_t>(m)] = !(stage.x(stage.layout.m_p(m)) > 0.0);
  // Summed in locals: the same additions in the same order, without a store
  // to sums per term (the compiler cannot rule out that sums aliases unit_).
  Eigen::Vector3d F = sums.F_B, L = sums.L_B;
  TankArray mdot = sums.m_p_dot;
  for (int a = 0; a < num_active_; ++a) {
    const ActiveThruster& at = active_[static_cast<size_t>(a)];
    const auto uj = static_cast<size_t>(at.j);
    const auto tank = static_cast<size_t>(at.tank);
    if (at.tank >= 0 && dry[tank]) continue;
    // FirstOrder: the stage value, or the closed form itself at a time that
    // is not a stage time (a caller evaluating the derivatives elsewhere).
    double kappa;
    if (!at.first_order)
      kappa = scheduled_kappa(p_[uj], sched_[uj], s_at_t0_[uj] + t, open_[uj]);
    else
      kappa = k >= 0 ? fo_[uj].kappa[k] : first_order_closed_form(uj, t);
    if (kappa == 0.0) continue;  // closed and decayed: no force, torque or flow
    const ThrusterEffect& u = unit_[uj];
    F += kappa * u.F_B;
    L += kappa * u.L_B;
    if (at.tank >= 0) mdot[tank] -= kappa * u.mdot;
  }
  sums.F_B = F;
  sums.L_B = L;
  sums.m_p_dot = mdot;
}

// ------------------------------------------------------------ step protocol


double ThrusterSet::valve_open_time(int j) const
{
  const auto uj = static_cast<size_t>(j);
  return open_done_[uj] + open_time_until(sched_[uj], t0_ns_);
}

void ThrusterSet::latch(int64_t t_L_ns)
{
  for (int j = 0; j < num_thr(); ++j) {
    const auto uj = static_cast<size_t>(j);
    if (health_[uj] != ThrusterHealth::Nominal) continue;  // failed valves ignore commands
    const ThrusterParams& p = p_[uj];
    const double s = s_since_latch(j, t_L_ns);
    const double kappa_now =
        p.transient == ThrusterTransient::FirstOrder
            ? kappa_fo_[uj]
            : scheduled_kappa(p, sched_[uj], s, sim::valve_open(sched_[uj], s));
    const bool firing = valve_firing(sched_[uj], s);
    const ValveSchedule before = sched_[uj];
    if (latch_thruster(p, cmd_, T_req_[uj], t_L_ns, kappa_now, firing, sched_[uj]) ==
        LatchResult::IgnoredMinOnTime) {
      ++counters_.ignored_min_on;
    } else {
      open_done_[uj] += open_time_until(before, t_L_ns);  // replaced at t_L
    }
  }
  pending_ = false;
  ++counters_.latches;
}

void ThrusterSet::at_instant(int64_t t_ns)
{
  if (pending_ && t_ns % cmd_.T_upd_ns == 0) latch(t_ns);
}

int64_t ThrusterSet::next_cut_ns(int64_t t_ns) const
{
  // Latch instants k*T_upd cut the step only while a message is pending.
  if (!pending_) return std::numeric_limits<int64_t>::max();
  return (t_ns / cmd_.T_upd_ns + 1) * cmd_.T_upd_ns;
}

void ThrusterSet::begin_segment(int64_t t0_ns)
{
  t0_ns_ = t0_ns;
  for (int j = 0; j < num_thr(); ++j) s_at_t0_[static_cast<size_t>(j)] = s_since_latch(j, t0_ns);
}

double ThrusterSet::next_event(double tau, double H, double snap) const
{
  // Next event in (tau + snap, H - snap): valve closings and Table breakpoints.
  double next = H;
  const auto consider = [&](double e) {
    if (e > tau + snap && e < next && e < H - snap) next = e;
  };
  for (int j = 0; j < num_thr(); ++j) {
    const auto uj = static_cast<size_t>(j);
    const ValveSchedule& s = sched_[uj];
    const double s0 = s_at_t0_[uj];
    consider(s.T_on - s0);  // valve closing (opening happens only at latches)
    if (p_[uj].transient != ThrusterTransient::Table) continue;
    for (const RampPoint& q : p_[uj].on_ramp)  // on-ramp knots, while open
      if (q.t > s.tau_on0 && q.t - s.tau_on0 < s.T_on) consider(q.t - s.tau_on0 - s0);
    for (const RampPoint& q : p_[uj].off_ramp)  // off-ramp knots, after closing
      if (q.t > s.tau_off0) consider(s.T_on + (q.t - s.tau_off0) - s0);
  }
  return next;
}

void ThrusterSet::begin_substep(double tau, double tau_end) { form_substep(tau, tau_end); }

void ThrusterSet::form_substep(double tau, double tau_end) const
{
  substep_formed_ = true;
  const double mid = 0.5 * (tau + tau_end);
  const double h = tau_end - tau;  // as Plant passes it to rk4_step
  stage_t_[0] = tau;               // RK4 stage times, formed exactly as rk4_step forms them
  stage_t_[1] = tau + 0.5 * h;
  stage_t_[2] = tau + h;
  // The exponentials depend on w h alone, and h is the sub-step's: one set
  // per distinct rate (thrusters mostly share omega_on = omega_off).
  struct Decay {
    // per unit d0: the stage corrections at s = 0, h/2 and h (see below)
    double w, e_half, e_full, c0, c_half, c_full;
  };
  std::array<Decay, kMaxThrusters> memo;  // at most one rate per thruster
  size_t n_memo = 0;
  num_active_ = 0;
  for (int j = 0; j < num_thr(); ++j) {
    const auto uj = static_cast<size_t>(j);
    const bool open = sim::valve_open(sched_[uj], s_at_t0_[uj] + mid);
    open_[uj] = open;
    const ThrusterParams& p = p_[uj];
    if (p.transient != ThrusterTransient::FirstOrder) {
      if (health_[uj] != ThrusterHealth::FailedOff) active_[static_cast<size_t>(num_active_++)] = {j, p.tank, false};
      continue;
    }
    // kappa(s) = kappa_c + d0 e^{-w s} on [0, h] (§5.3 in closed form).
    FirstOrderStage& f = fo_[uj];
    const double kappa0 = kappa_fo_[uj];
    f.kappa_c = open ? 1.0 : 0.0;
    f.w = open ? p.omega_on : p.omega_off;
    f.d0 = kappa0 - f.kappa_c;
    // Zero at every stage (closed and decayed) or failed: accumulate skips it.
    if (health_[uj] != ThrusterHealth::FailedOff && !(f.d0 == 0.0 && kappa0 == 0.0))
      active_[static_cast<size_t>(num_active_++)] = {j, p.tank, true};
    if (f.d0 == 0.0 || !(h > 0.0)) {  // at rest (0 closed, 1 open) or no interval
      f.delta = 0.0;
      f.slope = 0.0;
      f.kappa[0] = f.kappa[1] = f.kappa[2] = f.kappa_end = kappa0;
      continue;
    }
    size_t m = 0;
    while (m < n_memo && memo[m].w != f.w) ++m;
    if (m == n_memo) {
      const double wh = f.w * h;
      Decay& d = memo[n_memo++];
      d.w = f.w;
      d.e_half = std::exp(-0.5 * wh);
      d.e_full = std::exp(-wh);
      // For a stage acceleration a(t) that does not depend on the state,
      // RK4 over [0, h] gives (stages a1 at 0, a2 = a3 at h/2, a4 at h)
      //   v(h) = v0 + h (a1 + 2 a2 + 2 a3 + a4) / 6
      //   x(h) = x0 + h v0 + h^2 (a1 + a2 + a3) / 6,
      // where the exact values need the mean of a, (1/h) int a ds, and its
      // first moment, (1/h^2) int (h - s) a ds.  Per unit d0, with z = w h:
      //   e0 = exact mean of e^{-w s} less RK4's (1 + 4 e^{-z/2} + e^{-z}) / 6
      //      = -z^4/2880 + O(z^5),
      //   e1 = exact moment (z - 1 + e^{-z}) / z^2 less (1 + 2 e^{-z/2}) / 6
      //      = -z^3/720 + O(z^4).
      // A correction linear in s, delta(s) = c0 + (c_full - c0) s / h,
      // added to the closed form at every stage meets both:
      //   (c0 + 4 c_half + c_full) / 6 = e0,  (c0 + 2 c_half) / 6 = e1
      // with c0 = 6 e1 - 2 e0, c_half = e0, c_full = 4 e0 - 6 e1.  Then the
      // RK4 sums of kappa (so of F, the torque and mdot, linear in kappa) and
      // of its first moment over the sub-step are exact: impulse, propellant
      // and the sub-step's position and attitude increments from the thrust.
      const double e0 = -std::expm1(-wh) / wh - (1.0 + 4.0 * d.e_half + d.e_full) / 6.0;
      const double e1 = first_moment_rk4_defect(wh, d.e_half);
      d.c0 = 6.0 * e1 - 2.0 * e0;
      d.c_half = e0;
      d.c_full = 4.0 * e0 - 6.0 * e1;
    }
    const Decay& d = memo[m];
    f.delta = f.d0 * d.c0;
    f.slope = f.d0 * (d.c_full - d.c0) / h;
    f.kappa_end = f.kappa_c + f.d0 * d.e_full;
    f.kappa[0] = kappa0 + f.delta;
    f.kappa[1] = f.kappa_c + f.d0 * d.e_half + f.d0 * d.c_half;
    f.kappa[2] = f.kappa_end + f.d0 * d.c_full;
  }
}

void ThrusterSet::end_substep()
{
  for (int j = 0; j < num_thr(); ++j) {
    const auto uj = static_cast<size_t>(j);
    if (p_[uj].transient != ThrusterTransient::FirstOrder) continue;
    double k = fo_[uj].kappa_end;
    if (std::abs(k) < DBL_MIN) k = 0.0;  // a decayed tail: no subnormal arithmetic
    kappa_fo_[uj] = k;
  }
}

void ThrusterSet::state_io(StateIO& io)
{
  io.value("thrusters.T_req", T_req_);
  io.value("thrusters.pending", pending_);
  io.value("thrusters.schedules", sched_);
  io.value("thrusters.health", health_);
  io.value("thrusters.scale", scale_);
  io.value("thrusters.unit", unit_);
  io.value("thrusters.kappa_fo", kappa_fo_);
  io.value("thrusters.t0_ns", t0_ns_);
  io.value("thrusters.s_at_t0", s_at_t0_);
  io.value("thrusters.substep_formed", substep_formed_);
  io.value("thrusters.open", open_);
  io.value("thrusters.first_order", fo_);
  io.value("thrusters.stage_t", stage_t_);
  io.value("thrusters.active", active_);
  io.value("thrusters.num_active", num_active_);
  io.value("thrusters.counters", counters_);
  io.value("thrusters.open_done", open_done_);
}

void ThrusterSet::prepare_now(int64_t t_ns)
{
  begin_segment(t_ns);
  substep_formed_ = false;  // formed by accumulate if a derivative is evaluated before the next step
}

}  // namespace sim

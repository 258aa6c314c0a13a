// thruster: see sim/thruster.h.  docs/dynamics.md §5.1-§5.4.
#include "sim/thruster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "validate_util.h"

namespace sim {

namespace {
// Tolerance on |t_hat_B| - 1 (axes are typed in with ~16 digits).
constexpr double kUnitAxisTol = 1e-9;

void validate_ramp(const std::vector<RampPoint>& r, const std::string& field, bool rising)
{
  using namespace detail;
  if (r.size() < 2) fail(field + ".size()", static_cast<double>(r.size()), "needs >= 2 points");
  const double f_start = rising ? 0.0 : 1.0;
  const double f_end = rising ? 1.0 : 0.0;
  if (r.front().t != 0.0) fail(field + "[0].t", r.front().t, "must be 0");
  if (r.front().f != f_start)
    fail(field + "[0].f", r.front().f, rising ? "on-ramp must start at 0" : "off-ramp must start at 1");
  if (r.back().f != f_end)
    fail(field + ".back().f", r.back().f, rising ? "on-ramp must end at 1" : "off-ramp must end at 0");
  for (size_t i = 1; i < r.size(); ++i) {
    const std::string fi = field + "[" + std::to_string(i) + "]";
    require_finite(fi + ".t", r[i].t);
    require_finite(fi + ".f", r[i].f);
    if (!(r[i].t > r[i - 1].t)) fail(fi + ".t", r[i].t, "times must increase strictly");
    if (r[i].f < 0.0 || r[i].f > 1.0) fail(fi + ".f", r[i].f, "must be in [0, 1]");
    if (rising ? r[i].f < r[i - 1].f : r[i].f > r[i - 1].f)
      fail(fi + ".f", r[i].f, rising ? "on-ramp must be non-decreasing" : "off-ramp must be non-increasing");
  }
}
}  // namespace

const char* to_string(ThrusterTransient m)
{
  switch (m) {
    case ThrusterTransient::Instant: return "Instant";
    case ThrusterTransient::FirstOrder: return "FirstOrder";
    case ThrusterTransient::Table: return "Table";
  }
  return "?";
}

const char* to_string(ThrusterHealth h)
{
  switch (h) {
    case ThrusterHealth::Nominal: return "Nominal";
    case ThrusterHealth::FailedOff: return "FailedOff";
    case ThrusterHealth::StuckOn: return "StuckOn";
  }
  return "?";
}

void validate(const ThrusterParams& p, const std::string& name)
{
  using namespace detail;
  require_finite(name + ".r_TjB_B", p.r_TjB_B);
  require_finite(name + ".t_hat_B", p.t_hat_B);
  if (std::abs(p.t_hat_B.norm() - 1.0) > kUnitAxisTol)
    fail_vec(name + ".t_hat_B", p.t_hat_B, "must be a unit vector");
  require_positive(name + ".F_max", p.F_max);
  require_positive(name + ".Isp", p.Isp);
  require_non_negative(name + ".T_min", p.T_min);
  const int model = static_cast<int>(p.transient);
  if (model < 0 || model > 2) fail(name + ".transient", model, "must be Instant, FirstOrder or Table");
  if (p.transient == ThrusterTransient::FirstOrder) {
    require_positive(name + ".omega_on", p.omega_on);
    require_positive(name + ".omega_off", p.omega_off);
  }
  if (p.transient == ThrusterTransient::Table) {
    validate_ramp(p.on_ramp, name + ".on_ramp", true);
    validate_ramp(p.off_ramp, name + ".off_ramp", false);
  }
  require_finite(name + ".tau_sw", p.tau_sw);
  if (p.tank < -1) fail(name + ".tank", p.tank, "must be >= -1 (-1: no tank)");
  require_finite(name + ".dispersion", p.dispersion);
  if (!(p.dispersion > -1.0)) fail(name + ".dispersion", p.dispersion, "must be > -1");
}

void validate(const ThrusterCommandParams& p, const std::string& name)
{
  using namespace detail;
  if (!(p.T_upd_ns > 0)) fail(name + ".T_upd_ns", static_cast<double>(p.T_upd_ns), "must be > 0");
  if (p.T_sat) {
    if (std::isnan(*p.T_sat) || !(*p.T_sat > 0.0)) fail(name + ".T_sat", *p.T_sat, "must be > 0 (inf: no clip)");
  }
  require_non_negative(name + ".T_q", p.T_q);
  require_non_negative(name + ".kappa_idle", p.kappa_idle);
  if (!(p.kappa_idle < 1.0)) fail(name + ".kappa_idle", p.kappa_idle, "must be < 1");
}

double saturation_time(const ThrusterCommandParams& p)
{
  return p.T_sat ? *p.T_sat : static_cast<double>(p.T_upd_ns) * 1e-9;
}

// ----------------------------------------------------------------- tables

double ramp_value(const std::vector<RampPoint>& r, double tau)
{
  if (tau <= r.front().t) return r.front().f;
  if (tau >= r.back().t) return r.back().f;
  // First knot strictly after tau; tables are short (a few points).
  size_t i = 1;
  while (r[i].t <= tau) ++i;
  const RampPoint& a = r[i - 1];
  const RampPoint& b = r[i];
  return a.f + (b.f - a.f) * ((tau - a.t) / (b.t - a.t));
}

double ramp_entry_time(const std::vector<RampPoint>& r, double f, bool rising)
{
  const auto reached = [rising, f](double v) { return rising ? v >= f : v <= f; };
  if (reached(r.front().f)) return r.front().t;
  for (size_t i = 1; i < r.size(); ++i) {
    if (!reached(r[i].f)) continue;
    const RampPoint& a = r[i - 1];
    const RampPoint& b = r[i];
    // a.f has not reached f, b.f has, so b.f != a.f.
    return a.t + (b.t - a.t) * ((f - a.f) / (b.f - a.f));
  }
  return r.back().t;
}

// ----------------------------------------------------------- valve schedule

ValveSchedule initial_schedule(const ThrusterParams& p)
{
  ValveSchedule s;
  if (p.transient == ThrusterTransient::Table) s.tau_off0 = p.off_ramp.back().t;
  return s;
}

double scheduled_kappa(const ThrusterParams& p, const ValveSchedule& s, double s_since_latch,
                       bool open)
{
  if (p.transient == ThrusterTransient::Instant) return open ? 1.0 : 0.0;
  if (open) return ramp_value(p.on_ramp, s.tau_on0 + s_since_latch);
  return ramp_value(p.off_ramp, s.tau_off0 + (s_since_latch - s.T_on));
}

double first_order_kappa(const ThrusterParams& p, double kappa0, bool open, double t)
{
  const double kappa_c = open ? 1.0 : 0.0;
  const double w = open ? p.omega_on : p.omega_off;
  return kappa_c + (kappa0 - kappa_c) * std::exp(-w * t);
}

double first_order_kappa_integral(const ThrusterParams& p, double kappa0, bool open, double t)
{
  const double kappa_c = open ? 1.0 : 0.0;
  const double w = open ? p.omega_on : p.omega_off;
  // 1 - e^{-w t} = -expm1(-w t): accurate for w t << 1
  return kappa_c * t - (kappa0 - kappa_c) * std::expm1(-w * t) / w;
}

LatchResult latch_thruster(const ThrusterParams& p, const ThrusterCommandParams& c, double T_req,
                           int64_t t_L_ns, double kappa_now, bool firing, ValveSchedule& s)
{
  // 1. Saturation (a NaN or negative request closes the valve).
  double T = (std::isnan(T_req) || T_req < 0.0) ? 0.0 : std::min(T_req, saturation_time(c));
  // 2. Minimum impulse bit: ignored only for an idle thruster.
  const bool idle = !firing && kappa_now <= c.kappa_idle;
  if (T > 0.0 && T < p.T_min && idle) return LatchResult::IgnoredMinOnTime;
  // 4. Valve-timer resolution.
  if (c.T_q > 0.0 && std::isfinite(T)) T = c.T_q * std::floor(T / c.T_q);
  // 3. The new command replaces the running one.
  s.t_latch_ns = t_L_ns;
  s.T_on = T;
  if (p.transient == ThrusterTransient::Table) {
    s.tau_on0 = ramp_entry_time(p.on_ramp, kappa_now, true);
    const double kappa_close = T > 0.0 ? ramp_value(p.on_ramp, s.tau_on0 + T) : kappa_now;
    s.tau_off0 = ramp_entry_time(p.off_ramp, kappa_close, false);
  }
  return LatchResult::Scheduled;
}

// ------------------------------------------------------------------ effect

ThrusterEffect thruster_effect(const ThrusterParams& p, double kappa)
{
  ThrusterEffect e;
  const double F = p.F_max * kappa * (1.0 + p.dispersion);  // [N]
  e.F_B = F * p.t_hat_B;
  e.L_B = p.r_TjB_B.cross(e.F_B) + (kappa * p.tau_sw) * p.t_hat_B;
  e.mdot = F / (kG0 * p.Isp);
  return e;
}

}  // namespace sim

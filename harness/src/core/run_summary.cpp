// run_summary.cpp: the figures of a run's summary (Run::summary), the
// final pointing error, and the burn's figures for runs with a burn.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/run_impl.h"
#include "sim/environment.h"
#include "sim/units.h"

namespace harness {

namespace {

constexpr double kRadToDeg = 180.0 / sim::kPi;

}  // namespace

double Run::final_pointing_error_deg() const
{
  const double* row = impl_->rec.last_row();
  return row ? row[impl_->rec.column_index("pointing_error_deg")] : std::numeric_limits<double>::quiet_NaN();
}

// The burn's figures of the summary: start and end, the delivered delta-v
// against the rocket equation, the orbit at burn start (mu > 0).
static void burn_summary(const BurnMonitor& bm, const Scenario& sc, double mu, int num_tanks, double max_err_burn,
                         std::vector<SummaryItem>& out)
{
  if (bm.burn.engine >= 0 && bm.start.set) {
    const BurnMonitor::Snap& a = bm.start;
    const bool ended = bm.end.set;
    const BurnMonitor::Snap& b = ended ? bm.end : a;
    const ThrusterSpec& eng = sc.thrusters[static_cast<size_t>(bm.burn.engine)];
    out.push_back({"burn_start_s", a.t, "s", "engine open (first command instant at or after burn.start)"});
    out.push_back({"burn_end_s", ended ? b.t : std::numeric_limits<double>::quiet_NaN(), "s",
                   "engine closed and its thrust below 1e-3 F_max"});
    out.push_back({"burn_complete", ended ? 1.0 : 0.0, "-", "1 if the burn ended before the end of the run"});
    out.push_back({"max_pointing_error_burn_deg", max_err_burn * kRadToDeg, "deg",
                   "largest recorded pointing error between burn start and end"});
    if (ended) {
      const double m0 = a.m, m1 = b.m;
      // propellant of the engine's tank (tank 0); with rcs_tank the ACS
      // thrusters draw from tank 1, so tank 0 is the engine's alone
      const double dm_main = a.m_p[0] - b.m_p[0];
      const double dm_rcs = num_tanks > 1 ? a.m_p[1] - b.m_p[1] : 0.0;
      const double dv = (b.dv_ng - a.dv_ng).norm();
      const double ve = sim::kG0 * eng.Isp;
      const double dm_rocket = m0 * (1.0 - std::exp(-dv / ve));
      out.push_back({"mass_before_burn_kg", m0, "kg", "total mass at burn start"});
      out.push_back({"mass_after_burn_kg", m1, "kg", "total mass at burn end"});
      out.push_back({"propellant_engine_kg", dm_main, "kg", "tank 0 propellant used during the burn"});
      out.push_back({"propellant_rcs_burn_kg", dm_rcs, "kg", "rcs_tank propellant used during the burn"});
      out.push_back({"dv_nongrav_mps", dv, "m/s",
                     "|v_C(end) - v_C(start) - integral of gravity|: the delivered (sensed) delta-v"});
      out.push_back({"dv_rocket_mps", ve * std::log(m0 / (m0 - dm_main)), "m/s",
                     "g0 Isp ln(m0 / (m0 - engine propellant)): rocket equation"});
      out.push_back({"propellant_rocket_kg", dm_rocket, "kg", "m0 (1 - exp(-dv_nongrav / (g0 Isp)))"});
      out.push_back({"propellant_vs_rocket_rel", dm_main / dm_rocket - 1.0, "-",
                     "engine propellant / rocket-equation propellant - 1"});
    }
    if (mu > 0.0) {
      const sim::OrbitElements o0 = sim::elements_from_rv(mu, a.r, a.v);
      out.push_back({"orbit_before_e", o0.e, "-", "osculating eccentricity at burn start"});
      out.push_back({"orbit_before_r_p_km", o0.r_p * 1e-3, "km", "periapsis radius at burn start"});
    }
  }
}

std::vector<SummaryItem> Run::summary() const
{
  const Impl& m = *impl_;
  std::vector<SummaryItem> out;
  if (m.rec.rows() > 0)  // after a commanded change, it says which reference it is measured from
    out.push_back({"final_pointing_error_deg", final_pointing_error_deg(), "deg",
                   m.metrics->ref_commanded ? std::string(describe(m.metrics->ref)) +
                                                  " at the end of the run (a command changed the reference during the run)"
                                            : std::string("pointing error at the end of the run")});
  if (!m.jitter_wheels.empty())
    out.push_back({"max_jitter_step_rad", max_jitter_step(), "rad",
                   "largest |Omega| h of a jittering wheel (under-resolved above " +
                       std::to_string(static_cast<int>(kJitterStepLimit)) + ": docs/performance.md)"});
  if (m.plant.num_thr() == 0) return out;
  double used = 0.0;
  for (int k = 0; k < m.plant.num_tanks(); ++k) used += m.plant.tanks()[static_cast<size_t>(k)].m_p0 - m.plant.m_prop(k);
  out.push_back({"propellant_used_kg", used, "kg", "all tanks, whole run"});
  double on_total = 0.0;
  for (int j = 0; j < m.plant.num_thr(); ++j) {
    const double on = m.plant.thrusters().valve_open_time(j);
    on_total += on;
    out.push_back({"on_time_" + m.sc.thrusters[static_cast<size_t>(j)].name + "_s", on, "s",
                   "valve-open time, whole run (every latched pulse, exact)"});
  }
  out.push_back({"on_time_total_s", on_total, "s", "valve-open time of all thrusters, whole run"});
  const double mu = m.sc.environment.mu;
  burn_summary(*m.burn, m.sc, mu, m.plant.num_tanks(), m.metrics->max_err_burn, out);
  if (mu > 0.0) {
    const TruthMsg& t = m.truth_ch->value();  // the last tick run
    const Eigen::Vector3d r(t.r_CN_N[0], t.r_CN_N[1], t.r_CN_N[2]), v(t.v_CN_N[0], t.v_CN_N[1], t.v_CN_N[2]);
    const sim::OrbitElements o = sim::elements_from_rv(mu, r, v);
    out.push_back({"orbit_after_e", o.e, "-", "osculating eccentricity at the end of the run"});
    out.push_back({"orbit_after_r_p_km", o.r_p * 1e-3, "km", "periapsis radius"});
    out.push_back({"orbit_after_r_a_km", o.e < 1.0 ? o.r_a * 1e-3 : std::numeric_limits<double>::quiet_NaN(), "km",
                   "apoapsis radius (NaN: not captured)"});
    out.push_back({"orbit_after_period_h",
                   o.e < 1.0 ? 2.0 * sim::kPi * std::sqrt(o.a * o.a * o.a / mu) / 3600.0
                             : std::numeric_limits<double>::quiet_NaN(),
                   "h", "orbital period (NaN: not captured)"});
    out.push_back({"captured", o.e < 1.0 ? 1.0 : 0.0, "-", "1 if the orbit after the run is an ellipse"});
  }
  return out;
}
}  // namespace harness

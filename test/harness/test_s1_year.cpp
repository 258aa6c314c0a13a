// S1 for a year (scenarios/s1_year_dumps.yaml): Sun pointing on four wheels
// under solar radiation pressure with a 0.3 m centre-of-pressure offset, the
// wheels' momentum dumped by thrusters (fsw.momentum.policy: thrusters).
// 4.5 days of it here (three dumps).  Every expected figure is computed in
// this file from the scenario's numbers (the facet formula by hand, the
// thruster couple's lever arm, the Sun's distance from a low-precision
// almanac written here), never from the run's own outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace {

const std::string kFile = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_year_dumps.yaml";
constexpr double kPi = 3.14159265358979323846;
constexpr double kP1AU = 1361.0 / 299792458.0;  // [N/m^2] solar pressure at 1 AU (TSI 1361 W/m^2 / c)
constexpr double kG0 = 9.80665;                  // [m/s^2]
constexpr double kDays = 4.5;                    // run length [days]: dumps near 0.85, 2.55, 4.25 d

// Sun-Earth distance [AU] t seconds after 2027-04-04T00:00:00Z (the file's
// epoch), from the Astronomical Almanac's low-precision formula
// (R = 1.00014 - 0.01671 cos g - 0.00014 cos 2g, g the mean anomaly,
// ~1e-5 AU).  JD of the epoch: 2461499.5.
double sun_distance_au(double t)
{
  const double n = 2461499.5 + t / 86400.0 - 2451545.0;
  const double g = (357.528 + 0.9856003 * n) * kPi / 180.0;
  return 1.00014 - 0.01671 * std::cos(g) - 0.00014 * std::cos(2.0 * g);
}

// SRP force [N] at 1 AU on the facets, Sun along s (B), each lit facet
// (c = n.s > 0) giving -P A c [(1 - specular) s + 2 (specular c + diffuse/3) n];
// torque about the point c_B.
void srp_by_hand(const std::vector<sim::Facet>& facets, const Eigen::Vector3d& s, const Eigen::Vector3d& c_B,
                 Eigen::Vector3d& F, Eigen::Vector3d& L)
{
  F.setZero();
  L.setZero();
  for (const sim::Facet& f : facets) {
    const double c = f.n_B.dot(s);
    if (c <= 0.0) continue;
    const Eigen::Vector3d Fi =
        -kP1AU * f.area * c * ((1.0 - f.specular) * s + 2.0 * (f.specular * c + f.diffuse / 3.0) * f.n_B);
    F += Fi;
    L += (f.r_B - c_B).cross(Fi);
  }
}

struct Dump {
  size_t start = 0, end = 0;  // first row with phase != 0, first row back at 0
};

std::vector<Dump> find_dumps(const std::vector<double>& phase)
{
  std::vector<Dump> out;
  for (size_t k = 1; k < phase.size(); ++k) {
    if (phase[k - 1] == 0.0 && phase[k] != 0.0) out.push_back({k, 0});
    if (!out.empty() && out.back().end == 0 && phase[k - 1] != 0.0 && phase[k] == 0.0) out.back().end = k;
  }
  return out;
}

}  // namespace

// The file's numbers are those its header derives its predictions from.
TEST(S1Year, FileCarriesTheNumbersOfItsPredictions)
{
  const harness::Scenario sc = harness::load_scenario(kFile);
  EXPECT_EQ(sc.duration, 31557600.0);  // a Julian year
  EXPECT_EQ(sc.rates.dt, 0.5);
  EXPECT_EQ(sc.rates.record_divisor, 120u);  // 60 s
  ASSERT_EQ(sc.spacecraft.facets.size(), 8u);
  Eigen::Vector3d F, L;
  srp_by_hand(sc.spacecraft.facets, Eigen::Vector3d::UnitZ(), sc.spacecraft.r_BcB_B, F, L);
  // the header's hand figures: arrays 2 x 5 m^2 with k = 1 + 0.15 + 2 * 0.05 / 3,
  // bus top 2.25 m^2 with k = 1 + 0.2 + 2 * 0.3 / 3; arm 0.3 m along x
  const double Fz = -kP1AU * (10.0 * (1.0 + 0.15 + 0.1 / 3.0) + 2.25 * 1.4);
  EXPECT_NEAR(Fz, -6.8021e-5, 1e-9);
  EXPECT_NEAR(F.z(), Fz, 1e-15);
  EXPECT_NEAR(F.head<2>().norm(), 0.0, 1e-18);
  EXPECT_NEAR(L.y(), 0.3 * Fz, 1e-15);
  EXPECT_NEAR(L.x(), 0.0, 1e-18);
  EXPECT_NEAR(L.z(), 0.0, 1e-18);
  EXPECT_EQ(sc.fsw.mom_h_upper, 4.0);
  EXPECT_EQ(sc.fsw.mom_h_lower, 1.0);
  EXPECT_EQ(sc.fsw.mom_Isp, 220.0);
  ASSERT_TRUE(sc.tank.has_value());
  EXPECT_EQ((sc.tank->r_TB_B - sc.spacecraft.r_BcB_B).norm(), 0.0);  // the tank at the mass centre
}

// A band of zero width or a dump policy without thrusters is refused.
TEST(S1Year, BadMomentumKeysAreRejected)
{
  EXPECT_THROW(harness::load_scenario(kFile, {{"fsw.momentum.h_lower", "4.0"}}), harness::ScenarioError);
  try {
    harness::load_scenario(kFile, {{"fsw.momentum.h_lower", "5.0"}});
    ADD_FAILURE() << "h_lower above h_upper accepted";
  } catch (const harness::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("h_lower"), std::string::npos) << e.what();
  }
  EXPECT_THROW(harness::load_scenario(kFile, {{"thrusters[0].F_max", "-1"}}), harness::ScenarioError);
}

// 4.5 days: SRP torque, dump interval, propellant per dump (the FSW's
// estimate and the tank's), pointing during the dumps, the wheels back at
// h_lower.  About 10 s in Release; not under the sanitizers (777,600 ticks).
TEST(S1Year, DumpsEveryIntervalWithPredictedPropellantAndPointing)
{
#ifdef KESTREL_TEST_SANITIZE
  GTEST_SKIP() << "4.5 days at 0.5 s: release and clang presets only";
#endif
  const harness::Scenario sc = harness::load_scenario(
      kFile, {{"duration", std::to_string(kDays * 86400.0)},
              {"rates.record_divisor", "10"},  // every 5 s
              {"outputs.hdf5", "false"},
              {"outputs.report_data", "false"}});
  harness::Run run(sc);
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& m = run.memory();
  const auto t = m.column("t");
  const size_t n = t.size();

  // Predictions from the file's numbers.
  const Eigen::Vector3d c_B = sc.spacecraft.r_BcB_B;
  Eigen::Vector3d F1, L1;
  srp_by_hand(sc.spacecraft.facets, Eigen::Vector3d::UnitZ(), c_B, F1, L1);
  const double band = sc.fsw.mom_h_upper - sc.fsw.mom_h_lower;
  auto L_at = [&](double tt) { return L1 / std::pow(sun_distance_au(tt), 2); };
  // Lever arm of the pair a +y_B dump fires (acs1 + acs5): |sum r x F| / sum |F|
  // about the mass centre.
  Eigen::Vector3d Lpair = Eigen::Vector3d::Zero();
  double Fsum = 0.0;
  for (int j : {0, 4}) {
    const auto& th = sc.thrusters[static_cast<size_t>(j)];
    Lpair += (th.r_TjB_B - c_B).cross(th.F_max * th.t_hat_B);
    Fsum += th.F_max;
  }
  ASSERT_NEAR(Lpair.normalized().y(), 1.0, 1e-12);  // a pure +y couple
  const double lever = Lpair.norm() / Fsum;         // 1.7907 m
  EXPECT_NEAR(lever, 1.7907, 1e-12);
  const double Isp = sc.thrusters[0].Isp;
  const double prop_pred = band / (lever * Isp * kG0);  // 7.765e-4 kg
  const double I_yy = sc.spacecraft.inertia(1, 1);
  const double dt = sc.rates.dt * sc.rates.fsw_divisor;
  const double theta_bound = band * dt / (2.0 * I_yy);  // 9.4e-4 rad

  // (1) The pressure torque the plant applied, against the hand formula
  // scaled by (1 AU / d)^2.  Pointing errors (< 0.1 deg) change it by < 1e-5;
  // the craft's 1.5e6 km from the Earth, nearly perpendicular to the Sun
  // line, changes d by < 1e-4.
  for (size_t k = n / 8; k < n; k += n / 8) {
    const Eigen::Vector3d meas(m.column("torque_solar_pressure_x")[k], m.column("torque_solar_pressure_y")[k],
                               m.column("torque_solar_pressure_z")[k]);
    EXPECT_LT((meas - L_at(t[k])).norm(), 2e-3 * L_at(t[k]).norm()) << "t = " << t[k];
  }

  // (2) Three dumps, the intervals between their starts.
  const auto phase = m.column("fsw_dump_phase");
  const std::vector<Dump> dumps = find_dumps(phase);
  ASSERT_EQ(dumps.size(), 3u);
  EXPECT_EQ(m.column("fsw_dumps").back(), 3.0);
  for (size_t i = 1; i < dumps.size(); ++i) {
    const double t0 = t[dumps[i - 1].start], t1 = t[dumps[i].start];
    const double pred = band / L_at(0.5 * (t0 + t1)).norm();
    std::printf("dump interval %zu: %.0f s measured, %.0f s predicted (%.3f %%)\n", i, t1 - t0, pred,
                100.0 * (t1 - t0 - pred) / pred);
    EXPECT_NEAR(t1 - t0, pred, 0.10 * pred);
  }
  // the first from the initial 2.5 N*m*s along -y
  std::printf("first dump at %.0f s (%.0f s predicted)\n", t[dumps[0].start], 1.5 / L_at(0.0).norm());

  // (3) Propellant per dump: the FSW's estimate (fsw_prop_used) and the
  // tank's mass; nothing burns outside the dumps.
  const auto prop_fsw = m.column("fsw_prop_used"), tank = m.column("propellant_kg");
  size_t prev_end = 0;
  for (const Dump& d : dumps) {
    ASSERT_GT(d.end, d.start);
    const size_t a = d.start - 1, b = std::min(d.end + 1, n - 1);
    const double dm_fsw = prop_fsw[b] - prop_fsw[a], dm_tank = tank[a] - tank[b];
    std::printf("dump at %.0f s: %.0f s long, propellant %.4e kg (FSW), %.4e kg (tank), predicted %.4e kg\n", t[d.start],
                t[d.end] - t[d.start], dm_fsw, dm_tank, prop_pred);
    EXPECT_NEAR(dm_fsw, prop_pred, 0.10 * prop_pred);
    EXPECT_NEAR(dm_tank, prop_pred, 0.10 * prop_pred);
    EXPECT_NEAR(dm_tank, dm_fsw, 0.01 * dm_fsw);  // instant valves: the tank pays exactly the on-times
    EXPECT_EQ(tank[a], tank[prev_end]) << "propellant used between dumps";
    prev_end = b;
  }
  EXPECT_EQ(tank[n - 1], tank[prev_end]);

  // (4) Pointing during each dump (its pulses and coasts, and one more
  // coast after it) within the error of the hour before it plus the bound.
  // (5) The wheels back near h_lower: the dump leaves < one minimum pulse
  // (L_dump t_min_pulse) undelivered and the pressure adds |L| t_dump.
  const auto pe = m.column("pointing_error_deg");
  const auto hx = m.column("fsw_h_w_B_x"), hy = m.column("fsw_h_w_B_y"), hz = m.column("fsw_h_w_B_z");
  for (const Dump& d : dumps) {
    double quiet = 0.0, during = 0.0;
    for (size_t k = 0; k < n; ++k) {
      if (t[k] > t[d.start] - 3600.0 && k < d.start) quiet = std::max(quiet, pe[k]);
      if (k >= d.start && t[k] <= t[d.end] + sc.fsw.mom_t_coast) during = std::max(during, pe[k]);
    }
    std::printf("dump at %.0f s: pointing %.4f deg before, %.4f deg during (bound %.4f + %.4f deg)\n", t[d.start], quiet,
                during, quiet, theta_bound * 180.0 / kPi);
    EXPECT_LE(during, quiet + theta_bound * 180.0 / kPi);
    const double h_before = Eigen::Vector3d(hx[d.start - 1], hy[d.start - 1], hz[d.start - 1]).norm();
    const double h_after = Eigen::Vector3d(hx[d.end], hy[d.end], hz[d.end]).norm();
    const double slack = sc.fsw.mom_L_dump * sc.fsw.mom_t_min_pulse + L_at(t[d.start]).norm() * (t[d.end] - t[d.start]);
    std::printf("  |h_w| %.4f -> %.4f N m s (h_lower %.1f, slack %.4f)\n", h_before, h_after, sc.fsw.mom_h_lower, slack);
    // 5 s before the start: within a sample's growth and the tachometer noise
    // (0.1 rpm on each 0.0796 kg m^2 wheel: 8e-4 N m s; 1e-2 is > 5 sigma of |h|)
    EXPECT_NEAR(h_before, sc.fsw.mom_h_upper, 5.0 * L_at(t[d.start]).norm() + 1e-2);
    EXPECT_NEAR(h_after, sc.fsw.mom_h_lower, slack);
  }
}

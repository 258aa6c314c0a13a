// Earth-orbit disturbance models reached from scenario keys (environment.*,
// spacecraft.facets, spacecraft.residual_dipole): the recorded torques, the
// manifest round trip, and that scenarios without them record nothing new.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "harness/core/run.h"
#include "harness/scenario/scenario.h"
#include "rule_cases.h"

namespace {

const std::string kLeo = std::string(KESTREL_SOURCE_DIR) + "/test/harness/data/leo_environment.yaml";
const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

// Every model on, with the facets and the dipole of the file.
const std::vector<harness::Override> kAllOn{{"environment.solar_pressure.enabled", "true"},
                                            {"environment.solar_pressure.period", "0.5"},
                                            {"environment.drag.enabled", "true"},
                                            {"environment.drag.density_scale", "2.5"},
                                            {"environment.magnetic.enabled", "true"},
                                            {"environment.magnetic.igrf_degree", "8"}};

// [BN] of an MRP, formed here (Schaub & Junkins, eq. 3.152):
// [BN] = I + (8 [s~]^2 - 4 (1 - s.s) [s~]) / (1 + s.s)^2.
Eigen::Matrix3d dcm_from_mrp(const Eigen::Vector3d& s)
{
  Eigen::Matrix3d t;
  t << 0.0, -s(2), s(1), s(2), 0.0, -s(0), -s(1), s(0), 0.0;
  const double ss = s.squaredNorm();
  return Eigen::Matrix3d::Identity() + (8.0 * t * t - 4.0 * (1.0 - ss) * t) / ((1.0 + ss) * (1.0 + ss));
}

std::vector<std::string> torque_columns(const harness::MemorySink& m)
{
  std::vector<std::string> out;
  for (const auto& c : m.columns())
    if (c.name.rfind("torque_", 0) == 0) out.push_back(c.name);
  return out;
}

}  // namespace

// Gravity gradient alone at t = 0: L = 3 mu/R^3 r x (I r), r the unit
// position of the mass centre in B.  With balanced wheels (no separate
// rotor) the inertia about the mass centre is the hub's as written, and C is
// the hub's mass centre, whose position the file gives (r_CN_N).
TEST(Environment, GravityGradientTorqueAtStartMatchesTheClosedForm)
{
  const harness::Scenario sc = harness::load_scenario(kLeo);
  harness::Run run(sc);
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& m = run.memory();
  EXPECT_EQ(torque_columns(m),
            (std::vector<std::string>{"torque_gravity_gradient_x", "torque_gravity_gradient_y", "torque_gravity_gradient_z"}));

  const double mu = 3.986004415e14;  // the file's environment.mu
  Eigen::Matrix3d I;                  // the file's spacecraft.inertia
  I << 900.0, 12.0, -30.0, 12.0, 800.0, 25.0, -30.0, 25.0, 600.0;
  const Eigen::Vector3d R_N(7.0e6, 0.0, 0.0);  // spacecraft.initial.r_CN_N
  const Eigen::Vector3d r_B = dcm_from_mrp(Eigen::Vector3d(0.1, 0.2, -0.3)) * R_N.normalized();
  const Eigen::Vector3d L = 3.0 * mu / std::pow(R_N.norm(), 3) * r_B.cross(I * r_B);
  ASSERT_GT(L.cwiseAbs().minCoeff(), 1e-6);  // every component resolved (|L| ~ 1e-4 N*m)
  EXPECT_EQ(m.column("t").front(), 0.0);
  const char* axes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(m.column(std::string("torque_gravity_gradient_") + axes[i]).front(), L(i), 1e-12 * L.norm()) << axes[i];

  // The last row (t = 2 s), from that row's recorded attitude and position
  // of B: the mass centre is at r_B + [NB] c with c the file's com (the
  // inertia about B would differ by m (c.c I - c c^T), ~10 kg*m^2, and miss).
  const uint64_t last = m.rows() - 1;
  auto at = [&m, last](const std::string& stem) {
    return Eigen::Vector3d(m.column(stem + "_x")[last], m.column(stem + "_y")[last], m.column(stem + "_z")[last]);
  };
  const Eigen::Matrix3d BN = dcm_from_mrp(at("sigma_BN"));
  const Eigen::Vector3d c_B(0.05, -0.02, 0.10);
  const Eigen::Vector3d R2_N = at("r_BN_N") + BN.transpose() * c_B;
  const Eigen::Vector3d r2_B = BN * R2_N.normalized();
  const Eigen::Vector3d L2 = 3.0 * mu / std::pow(R2_N.norm(), 3) * r2_B.cross(I * r2_B);
  EXPECT_EQ(m.column("t")[last], 2.0);
  EXPECT_GT((L2 - L).norm(), 1e-3 * L.norm());  // the attitude moved: a different torque
  EXPECT_LT((at("torque_gravity_gradient") - L2).norm(), 1e-10 * L2.norm());
}

// Scenarios without the keys build no effector and record no torque column.
TEST(Environment, OffByDefaultRecordsNoTorque)
{
  harness::Scenario sc = harness::load_scenario(kS1, {{"duration", "1"}});
  EXPECT_FALSE(sc.environment.gravity_gradient.enabled || sc.environment.solar_pressure.enabled ||
               sc.environment.drag.enabled || sc.environment.magnetic.enabled);
  EXPECT_FALSE(sc.environment.j2);
  EXPECT_TRUE(sc.spacecraft.facets.empty());
  const std::string json = harness::scenario_to_json_text(sc);
  for (const char* k : {"epoch", "gravity_gradient", "solar_pressure", "drag", "magnetic", "facets", "residual_dipole", "j2"})
    EXPECT_EQ(json.find(std::string("\"") + k + "\""), std::string::npos) << k;
  harness::Run run(sc);
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  EXPECT_TRUE(torque_columns(run.memory()).empty());
}

// Every model on: one column group per source, each torque finite and
// non-zero at every row (the plates face the flow and the Sun).
TEST(Environment, EveryModelRecordsItsOwnTorque)
{
  const harness::Scenario sc = harness::load_scenario(kLeo, kAllOn);
  harness::Run run(sc);
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& m = run.memory();
  ASSERT_EQ(torque_columns(m).size(), 12u);
  for (const char* src : {"gravity_gradient", "solar_pressure", "drag", "magnetic"}) {
    SCOPED_TRACE(src);
    const std::string p = std::string("torque_") + src + "_";
    const auto x = m.column(p + "x"), y = m.column(p + "y"), z = m.column(p + "z");
    for (size_t k = 0; k < x.size(); ++k) {
      const double n = std::sqrt(x[k] * x[k] + y[k] * y[k] + z[k] * z[k]);
      EXPECT_TRUE(std::isfinite(n));
      EXPECT_GT(n, 0.0);
    }
  }
}

TEST(Environment, ManifestFormReloadsIdentically)
{
  const harness::Scenario a = harness::load_scenario(kLeo, kAllOn);
  const std::string ja = harness::scenario_to_json_text(a);
  const harness::Scenario b = harness::load_scenario_text(ja, "m.json");
  EXPECT_EQ(harness::scenario_to_json_text(b), ja);
  EXPECT_EQ(b.environment.epoch, "2027-03-21T12:00:00Z");
  EXPECT_TRUE(b.environment.gravity_gradient.enabled && b.environment.solar_pressure.enabled &&
              b.environment.drag.enabled && b.environment.magnetic.enabled);
  EXPECT_EQ(b.environment.gravity_gradient.period, 0.0);
  EXPECT_EQ(b.environment.solar_pressure.period, 0.5);
  EXPECT_EQ(b.environment.drag_density_scale, 2.5);
  EXPECT_EQ(b.environment.igrf_degree, 8);
  ASSERT_EQ(b.spacecraft.facets.size(), 2u);
  EXPECT_EQ(b.spacecraft.facets[0].specular, 0.3);
  EXPECT_EQ(b.spacecraft.facets[1].absorbed, 1.0);  // default
  EXPECT_EQ(b.spacecraft.facets[1].n_B, Eigen::Vector3d(-1.0, 0.0, 0.0));
  EXPECT_EQ(b.spacecraft.residual_dipole_B, Eigen::Vector3d(0.5, -0.2, 1.0));
}

// Cross-field rules, each named at its key.
TEST(Environment, RulesNameTheKey)
{
  const std::vector<testutil::RuleCase> cases{
      {{{"environment.epoch", "2027-13-01T00:00:00Z"}}, "environment.epoch", "month"},
      {{{"environment.epoch", "2027-03-21 12:00"}}, "environment.epoch", "YYYY-MM-DDThh:mm:ssZ"},
      {{{"environment.epoch", "2031-01-02T00:00:00Z"}, {"environment.magnetic.enabled", "true"}},
       "environment.epoch", "2020 to 2030"},
      {{{"environment.mu", "4.282837e13"}, {"environment.drag.enabled", "true"}}, "environment.drag", "Earth orbit"},
      {{{"environment.mu", "0"}}, "environment.gravity_gradient", "mu > 0"},
      {{{"environment.mu", "4.282837e13"}, {"environment.j2", "true"}}, "environment.j2", "Earth orbit"},
      {{{"environment.j2", "1.08e-3"}}, "environment.j2", "true or false"},
      {{{"spacecraft.facets", "[]"}, {"environment.solar_pressure.enabled", "true"}},
       "environment.solar_pressure", "facets"},
      {{{"environment.magnetic.igrf_degree", "14"}}, "environment.magnetic.igrf_degree", "13"},
      {{{"environment.gravity_gradient.period", "-1"}}, "environment.gravity_gradient.period", "[0, 86400]"},
      {{{"environment.mu", "0"}}, "environment.epoch", "Earth orbit"},
      {{{"environment.sun_position_N", "[1.0e11, 0.0, 0.0]"}}, "environment.sun_position_N", "from the date"},
  };
  testutil::expect_rules_named(kLeo, cases);
}

// A dated run takes its Sun from the almanac of the epoch and the Earth's
// shadow: the coarse sun sensors of a sun-safe hold see nothing behind the
// Earth and see the almanac Sun on the day side.  At 2027-06-21 12:00 UTC,
// 2.2 h before the June solstice, the Sun stands at right ascension 90 deg
// and declination epsilon = 23.44 deg within 0.1 deg: unit vector
// (0, cos eps, sin eps) in N, 90 deg from the fixed default Sun (+x).  A
// spacecraft 7,000 km from the Earth's centre on the anti-Sun side is deep
// in the umbra (the cone is ~6,300 km wide there); on the Sun side it is lit
// and the parallax is 5e-5 rad.
TEST(Environment, DatedRunTakesTheAlmanacSunAndTheEarthShadow)
{
  const double eps = 23.4393 * M_PI / 180.0;
  const Eigen::Vector3d sun(0.0, std::cos(eps), std::sin(eps));
  const std::vector<harness::Override> sun_safe{
      {"environment.epoch", "2027-06-21T12:00:00Z"},
      {"fsw.mode", "sun_safe"},
      {"fsw.sun_safe.sun_axis_B", "[0.0, 0.0, 1.0]"},
      {"sensors.noise", "false"},
      {"sensors.css.fov_deg", "90"},
      {"sensors.css.normals", "[[1,0,0],[-1,0,0],[0,1,0],[0,-1,0],[0,0,1],[0,0,-1]]"},
      {"duration", "1.0"}};
  for (const double side : {-1.0, 1.0}) {
    SCOPED_TRACE(side);
    std::vector<harness::Override> set = sun_safe;
    const Eigen::Vector3d r = side * 7.0e6 * sun;
    set.push_back({"spacecraft.initial.r_CN_N",
                   "[" + std::to_string(r(0)) + ", " + std::to_string(r(1)) + ", " + std::to_string(r(2)) + "]"});
    set.push_back({"spacecraft.initial.v_CN_N", "[7546.0, 0.0, 0.0]"});
    const harness::Scenario sc = harness::load_scenario(kLeo, set);
    harness::Run run(sc);
    ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
    const harness::MemorySink& m = run.memory();
    const auto lit = m.column("css_num_lit"), valid = m.column("sun_valid");
    const auto bx = m.column("sun_B_x"), by = m.column("sun_B_y"), bz = m.column("sun_B_z");
    const auto s0 = m.column("sigma_BN_x"), s1 = m.column("sigma_BN_y"), s2 = m.column("sigma_BN_z");
    ASSERT_FALSE(lit.empty());
    for (size_t k = 0; k < lit.size(); ++k) {
      if (side < 0.0) {
        EXPECT_EQ(lit[k], 0.0) << k;
        EXPECT_EQ(valid[k], 0.0) << k;
        continue;
      }
      EXPECT_GT(lit[k], 0.0) << k;
      // the estimate against the solstice Sun turned into B by the recorded attitude
      const Eigen::Vector3d d_B = dcm_from_mrp(Eigen::Vector3d(s0[k], s1[k], s2[k])) * sun;
      const double ang = std::acos(std::clamp(d_B.dot(Eigen::Vector3d(bx[k], by[k], bz[k]).normalized()), -1.0, 1.0));
      EXPECT_LT(ang, 3e-3) << k;  // 0.17 deg: the 0.1 deg of the date plus the parallax
    }
  }
}

// environment.j2 reaches the plant's gravity.  The file's orbit starts on the
// equator at r = 7000 km (x axis) with v = (0, 5000, 5500) m/s, where the J2
// acceleration is a_x = -k, k = (3/2) J2 mu R^2 / r^4 = 1.0967390e-2 m/s^2
// (J2 = 1.08262668e-3, R = 6378137 m; by hand in sim_test_environment), and
// a_z = -3 k z / r grows with z = 5500 t.  So after 2 s the runs with and
// without it differ by
//   x: -k t^2 / 2             = -2.1934780e-2 m
//   z: -k v_z t^3 / (2 r)     = -3.4468e-5 m.
// Over the 2 s, |r| changes by ~16 m and 5 z^2/r^2 reaches 1.2e-5, so the
// acceleration changes by ~1e-5 of itself: tolerance 1e-4 on x, 1 % on z.
// The key is written to the manifest when on and reloads.
TEST(Environment, J2KeyReachesThePlantGravity)
{
  harness::Scenario off = harness::load_scenario(kLeo);
  harness::Scenario on = harness::load_scenario(kLeo, {{"environment.j2", "true"}});
  EXPECT_TRUE(on.environment.j2);
  const std::string ja = harness::scenario_to_json_text(on);
  EXPECT_NE(ja.find("\"j2\": true"), std::string::npos);
  EXPECT_TRUE(harness::load_scenario_text(ja, "m.json").environment.j2);
  harness::Run a(off), b(on);
  ASSERT_TRUE(a.step_ticks(a.total_ticks())) << a.failure();
  ASSERT_TRUE(b.step_ticks(b.total_ticks())) << b.failure();
  const uint64_t last = a.memory().rows() - 1;
  ASSERT_EQ(a.memory().column("t")[last], 2.0);
  const double dx = b.memory().column("r_BN_N_x")[last] - a.memory().column("r_BN_N_x")[last];
  const double dz = b.memory().column("r_BN_N_z")[last] - a.memory().column("r_BN_N_z")[last];
  std::printf("environment.j2: x(2 s) with J2 - without = %.7e m (expected -2.1934780e-2), z: %.5e m "
              "(expected -3.4468e-5)\n", dx, dz);
  EXPECT_NEAR(dx, -2.1934780e-2, 1e-4 * 2.1934780e-2);
  EXPECT_NEAR(dz, -3.4468e-5, 1e-2 * 3.4468e-5);
}

// ------------------------------------------------------ recorded momentum

namespace {

const std::string kS3 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s3_leo_smallsat.yaml";
constexpr double kPi = 3.14159265358979323846;
// Under the sanitizers (about 2 ms per tick) the S3 runs step at 0.5 s
// (FSW at 2 Hz) instead of 0.1 s; the assertions are the same.
#ifdef KESTREL_TEST_SANITIZE
const std::vector<harness::Override> kCoarse{{"rates.dt", "0.5"}, {"rates.record_divisor", "10"}};
#else
const std::vector<harness::Override> kCoarse{};
#endif
std::vector<harness::Override> with(std::vector<harness::Override> ov, const std::vector<harness::Override>& more)
{
  ov.insert(ov.end(), more.begin(), more.end());
  return ov;
}
const char* const kSources[] = {"gravity_gradient", "solar_pressure", "drag", "magnetic"};

Eigen::Vector3d row3(const harness::MemorySink& m, const std::string& stem, uint64_t k)
{
  return {m.at(k, m.column_index(stem + "_x")), m.at(k, m.column_index(stem + "_y")),
          m.at(k, m.column_index(stem + "_z"))};
}

}  // namespace

// The momentum balance of a disturbed run (S3 shortened to 1,200 s, every
// source on, held at its default period, closed loop): the sum over the
// sources of H_<source>_N at the last row equals the change of H_C_N, the
// plant's total angular momentum about the mass centre, to 1e-9 of that
// change (measured 2.0e-10).  Each source's share is far above the tolerance.
TEST(Environment, RecordedMomentumOfTheSourcesBalancesTheChangeOfHc)
{
  const harness::Scenario sc = harness::load_scenario(kS3, with({{"duration", "1200"}, {"outputs.hdf5", "false"}}, kCoarse));
  harness::Run run(sc);
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& m = run.memory();
  const uint64_t last = m.rows() - 1;
  const Eigen::Vector3d dH = row3(m, "H_C_N", last) - row3(m, "H_C_N", 0);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const char* s : kSources) {
    const std::string stem = std::string("H_") + s + "_N";
    EXPECT_EQ(row3(m, stem, 0), Eigen::Vector3d::Zero()) << s;  // nothing given yet at t = 0
    const Eigen::Vector3d h = row3(m, stem, last);
    EXPECT_GT(h.norm(), 1e-6 * dH.norm()) << s;
    sum += h;
  }
  const double rel = (sum - dH).norm() / dH.norm();
  std::printf("momentum balance over 1200 s of S3: |dH_C| %.4e N m s, relative error %.2e\n", dH.norm(), rel);
  ASSERT_GT(dH.norm(), 1e-4);  // N*m*s: well resolved
  EXPECT_LT(rel, 1e-9);
}

// The accumulated gravity-gradient momentum is the integral of the recorded
// torque about C rotated to N: Simpson's rule over rows 1 s apart, from the
// recorded torque and attitude, at an attitude far from N (so that a frame
// mix-up would show).  The attitude jitters at the FSW rate under sensor
// noise and the rows sample it at 1 Hz: agreement within 1e-4 (measured 1.1e-7).
TEST(Environment, AccumulatedMomentumIsTheIntegralOfTheTorqueInN)
{
#ifdef KESTREL_TEST_SANITIZE
  const std::vector<harness::Override> rows{{"rates.dt", "0.5"}, {"rates.record_divisor", "2"}};
#else
  const std::vector<harness::Override> rows{{"rates.record_divisor", "10"}};
#endif
  const std::vector<harness::Override> ov{{"duration", "600"},
                                          {"outputs.hdf5", "false"},
                                          {"fsw.inertial.sigma_R0N", "[0.1, 0.2, -0.3]"},
                                          {"spacecraft.initial.sigma_BN", "[0.1, 0.2, -0.3]"}};
  harness::Run run(harness::load_scenario(kS3, with(ov, rows)));
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& m = run.memory();
  auto L_N = [&m](uint64_t k) {
    return Eigen::Vector3d(dcm_from_mrp(row3(m, "sigma_BN", k)).transpose() * row3(m, "torque_gravity_gradient", k));
  };
  const uint64_t last = m.rows() - 1;
  ASSERT_EQ(last % 2, 0u);
  Eigen::Vector3d simpson = Eigen::Vector3d::Zero();
  for (uint64_t k = 0; k + 2 <= last; k += 2) simpson += (1.0 / 3.0) * (L_N(k) + 4.0 * L_N(k + 1) + L_N(k + 2));
  const Eigen::Vector3d acc = row3(m, "H_gravity_gradient_N", last);
  const double rel = (acc - simpson).norm() / simpson.norm();
  std::printf("gravity gradient over 600 s: |H| %.4e N m s, against Simpson on the rows %.2e\n", acc.norm(), rel);
  EXPECT_LT(rel, 1e-4);
}

// Illumination: a circular equatorial orbit of 7,000 km with the Sun (near
// the March equinox, declination 0.3 deg) in the orbit plane, from 100 deg
// of right ascension through the whole shadow.  The spacecraft is behind
// the Earth, illumination below 1/2 (the Sun's centre hidden), while it is
// within asin(R/r) of the anti-Sun direction: the Sun's centre sets where
// the line of sight grazes the Earth (the cylinder of radius R, to the
// parallax r/AU = 5e-5 rad, 0.04 s).  The anti-Sun direction itself moves
// prograde at the Sun's rate in right ascension, 2 pi/365.2422 d x
// cos(obliquity) at the equinox, so the shadow lasts 2 asin(R/r)/(n - that
// rate) (the rate adds 0.36 s to 2,126 s); the 0.3 deg out of plane shortens
// it by a relative 1e-5.  Rows 0.1 s apart: each crossing within 0.1 s, so
// 0.3 s in all.  The penumbra lasts the Sun's apparent diameter (0.533 deg)
// over the orbit rate: 8.6 s at each crossing.
TEST(Environment, IlluminationFollowsTheEarthsShadow)
{
  const double mu = 3.986004415e14, r = 7.0e6, R = 6378136.3;  // R: sim::kRadiusEarth, the shadowing sphere
  const double n = std::sqrt(mu / (r * r * r)), period = 2.0 * kPi / n, v = std::sqrt(mu / r);
  const double u0 = 100.0 * kPi / 180.0;  // [rad] right ascension at t = 0
  auto vec = [](double x, double y) { return "[" + std::to_string(x) + ", " + std::to_string(y) + ", 0]"; };
  const std::vector<harness::Override> ov{{"duration", "2600"},
                                          {"rates.record_divisor", "1"},
                                          {"rates.fsw_divisor", "10"},  // the hold does not matter here
                                          {"spacecraft.initial.r_CN_N", vec(r * std::cos(u0), r * std::sin(u0))},
                                          {"spacecraft.initial.v_CN_N", vec(-v * std::sin(u0), v * std::cos(u0))},
                                          {"spacecraft.com", "[0, 0, 0]"}};
  harness::Run run(harness::load_scenario(kLeo, ov));
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& m = run.memory();
  const auto t = m.column("t"), f = m.column("illumination"), ecl = m.column("eclipse");
  double t_dark = 0.0, t_pen = 0.0, t_in = -1.0, t_out = -1.0;
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_TRUE(f[k] >= 0.0 && f[k] <= 1.0);
    EXPECT_EQ(ecl[k], f[k] < 1.0 ? 1.0 : 0.0);
    if (f[k] < 0.5) t_dark += 0.1;
    if (f[k] > 0.0 && f[k] < 1.0) t_pen += 0.1;
    if (f[k] < 0.5 && t_in < 0.0) t_in = t[k];
    if (f[k] >= 0.5 && t_in >= 0.0 && t_out < 0.0) t_out = t[k];
  }
  EXPECT_EQ(f.front(), 1.0);  // sunlit at both ends: the whole shadow is inside the run
  EXPECT_EQ(f.back(), 1.0);
  const double sun_ra_rate = 2.0 * kPi / (365.2422 * 86400.0) * std::cos(23.4393 * kPi / 180.0);  // [rad/s]
  const double expected = 2.0 * std::asin(R / r) / (n - sun_ra_rate);
  std::printf("shadow: %.1f s (illumination < 1/2) against %.2f s, entry %.1f s, exit %.1f s; penumbra %.1f s\n",
              t_dark, expected, t_in, t_out, t_pen);
  EXPECT_NEAR(t_dark, expected, 0.3);
  // centred on the anti-Sun point, 80 deg of orbit after the start plus the
  // Sun's right ascension (2027-03-21 12:00, the morning after the equinox;
  // ~1 deg/day): between 0 and 1 deg.
  const double mid = 0.5 * (t_in + t_out), t_anti = 80.0 / 360.0 * period;
  EXPECT_GT(mid, t_anti);
  EXPECT_LT(mid, t_anti + period / 360.0);
  const double pen = 2.0 * (0.533 * kPi / 180.0) / n;
  EXPECT_NEAR(t_pen, pen, 0.5);
}

// An Earth-orbit run records illumination with its epoch, the field with
// the magnetic model, one momentum per source that is on and the wheels'
// momentum; S1 records none of them.
TEST(Environment, EarthOrbitColumnsOnlyWhereTheyApply)
{
  auto names = [](const harness::MemorySink& m) {
    std::vector<std::string> out;
    for (const auto& c : m.columns())
      for (const char* p : {"illumination", "eclipse", "field_B_", "H_gravity", "H_solar", "H_drag", "H_magnetic", "H_wheels"})
        if (c.name.rfind(p, 0) == 0) out.push_back(c.name);
    return out;
  };
  harness::Run gg(harness::load_scenario(kLeo));
  ASSERT_TRUE(gg.step_ticks(2));
  EXPECT_EQ(names(gg.memory()),
            (std::vector<std::string>{"illumination", "eclipse", "H_gravity_gradient_N_x", "H_gravity_gradient_N_y",
                                      "H_gravity_gradient_N_z", "H_wheels_N_x", "H_wheels_N_y", "H_wheels_N_z"}));
  harness::Run all(harness::load_scenario(kLeo, kAllOn));
  ASSERT_TRUE(all.step_ticks(2));
  EXPECT_EQ(names(all.memory()).size(), 2u + 3u + 12u + 3u);
  harness::Run s1(harness::load_scenario(kS1, {{"duration", "1"}}));
  ASSERT_TRUE(s1.step_ticks(2));
  EXPECT_TRUE(names(s1.memory()).empty());
}

// The recorded field is the one the magnetic torque acts with:
// torque_magnetic = m x field_B for the file's residual dipole, every row.
TEST(Environment, RecordedFieldGivesTheMagneticTorque)
{
  harness::Run run(harness::load_scenario(kLeo, kAllOn));
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& m = run.memory();
  const Eigen::Vector3d dip(0.5, -0.2, 1.0);  // spacecraft.residual_dipole
  for (uint64_t k = 0; k < m.rows(); ++k) {
    const Eigen::Vector3d B = row3(m, "field_B", k);
    EXPECT_GT(B.norm(), 1.0e-5);  // LEO: 20-50 uT
    EXPECT_LT(B.norm(), 6.0e-5);
    EXPECT_LT((row3(m, "torque_magnetic", k) - dip.cross(B)).norm(), 1e-12 * dip.norm() * B.norm()) << k;
  }
}

// Event device `atmosphere` (drag on): density_scale steps the drag model's
// air density (a storm), restore goes back to environment.drag.density_scale.
// Twin runs of the LEO file (drag on, scale 1): one with the storm, x3 from
// t = 0.5 s and back at 1.2 s; the other without.  Rows before 0.5 s are
// equal; between, the storm run's recorded drag torque is 3 times the
// other's, and after the restore equal again, to 1e-6: the runs part only
// through the storm itself (2 x 3.4e-6 N m extra for 0.7 s on 600-900
// kg m^2 turns the body by ~1e-9 rad, and the FSW answers it), which moves
// the attitude-dependent torque by ~1e-8 of itself (measured 1.5e-8).
TEST(Environment, AtmosphereEventStepsTheDensityScale)
{
  const std::vector<harness::Override> base{{"environment.drag.enabled", "true"}, {"duration", "2.0"}};
  std::vector<harness::Override> storm = base;
  storm.push_back({"events", "[{t: 0.5, actions: [{device: atmosphere, action: density_scale, value: 3.0}]},"
                             " {t: 1.2, actions: [{device: atmosphere, action: restore}]}]"});
  harness::Run a(harness::load_scenario(kLeo, storm)), b(harness::load_scenario(kLeo, base));
  ASSERT_TRUE(a.step_ticks(a.total_ticks())) << a.failure();
  ASSERT_TRUE(b.step_ticks(b.total_ticks())) << b.failure();
  const auto t = a.memory().column("t");
  ASSERT_EQ(a.events_applied().size(), 2u);
  for (size_t k = 0; k < t.size(); ++k) {
    SCOPED_TRACE(t[k]);
    const Eigen::Vector3d La = row3(a.memory(), "torque_drag", k), Lb = row3(b.memory(), "torque_drag", k);
    ASSERT_GT(Lb.norm(), 0.0);
    const double want = (t[k] >= 0.5 - 1e-9 && t[k] < 1.2 - 1e-9) ? 3.0 : 1.0;
    EXPECT_LT((La - want * Lb).norm(), 1e-6 * want * Lb.norm());
  }
  // an atmosphere without drag is refused at the event's key
  try {
    harness::load_scenario(kLeo, {{"events", "[{t: 0.5, actions: [{device: atmosphere, action: density_scale, value: 3.0}]}]"}});
    ADD_FAILURE() << "accepted";
  } catch (const harness::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("drag model is off"), std::string::npos) << e.what();
  }
}

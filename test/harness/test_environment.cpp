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
  struct Case {
    std::vector<harness::Override> set;
    const char* key;
    const char* words;
  };
  const std::vector<Case> cases{
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
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    try {
      harness::load_scenario(kLeo, c.set);
      ADD_FAILURE() << "accepted";
    } catch (const harness::ScenarioError& e) {
      bool found = false;
      for (const auto& is : e.issues())
        found = found || (is.key == c.key && is.message.find(c.words) != std::string::npos);
      EXPECT_TRUE(found) << e.what();
    }
  }
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

// Environment (spec plant-dynamics §0, §6, §9.3, §11): point-mass gravity
// with a configurable mu (Mars for S2) inside the dynamics, two-body
// conservation and Kepler solutions, the S2 approach hyperbola, Sun
// position/direction geometry and the conical-shadow illumination factor
// against an independent ray-casting count.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sim/environment.h"
#include "sim/plant.h"
#include "sim/units.h"
#include "sim/plant.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

sim::SpacecraftParams mars_hub()
{
  sim::SpacecraftParams p;
  p.hub.m_h = 750.0;
  p.hub.I_hBc_B = Vector3d(900.0, 800.0, 600.0).asDiagonal();
  p.hub.r_BcB_B = Vector3d(0.02, -0.01, 0.05);  // B != C: gravity acts at C
  p.mu = sim::mars().mu;
  return p;
}

TEST(Gravity, PointMassLawAndDynamicsAgree)
{
  const Vector3d r(3.9e6, -1.2e6, 0.7e6);
  const Vector3d g = sim::point_mass_gravity(sim::kMuMars, r);
  EXPECT_NEAR(g.norm(), 4.2828314e13 / r.squaredNorm(), 1e-15 * g.norm());
  EXPECT_NEAR((g.normalized() + r.normalized()).norm(), 0.0, 1e-15);
  EXPECT_EQ(sim::point_mass_gravity(0.0, r), Vector3d::Zero());
  // In the dynamics: non-rotating hub, no inputs -> the mass centre
  // accelerates at g(r_C) (B-point acceleration equals C's when omega = 0).
  sim::InitialConditions ic;
  ic.r_CN_N = r;
  ic.sigma_BN = Vector3d(0.1, 0.2, -0.3);
  const sim::SpacecraftModel m(mars_hub());
  const sim::StateVector x = m.initial_state(ic, m.params().hub);
  const sim::StateVector xd = m.derivatives(0.0, x, sim::WheelInputs{}, sim::ExternalLoads{}, m.params().hub);
  const Vector3d a_N = xd.segment<3>(sim::StateLayout::v_BN_N);
  const Vector3d g_test = -4.2828314e13 / std::pow(r.norm(), 3) * r;
  EXPECT_NEAR((a_N - g_test).norm(), 0.0, 1e-14 * g_test.norm());
}

TEST(Gravity, CentralBodyConfigRejected)
{
  EXPECT_THROW(sim::validate(sim::CentralBody{-1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(sim::validate(sim::CentralBody{1.0, NAN}), std::invalid_argument);
  sim::SunParams s;
  s.r_SunN_N0 = Vector3d::Zero();
  try {
    sim::validate(s, "sun");
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sun.r_SunN_N0"), std::string::npos);
  }
}

// Kepler solution checked without any integrator: energy, angular momentum,
// and v = dr/dt by central differences.
TEST(TwoBody, KeplerSolutionIsConsistent)
{
  const double mu = sim::kMuMars;
  for (double e : {0.0, 0.3, 0.9, 1.4, 3.0}) {
    const double r_p = 3896.19e3;
    const double p = r_p * (1.0 + e);
    for (double t : {-5000.0, -300.0, 0.0, 1234.5, 8000.0}) {
      const sim::OrbitState s = sim::conic_state_from_periapsis(mu, r_p, e, t);
      const sim::OrbitElements el = sim::elements_from_rv(mu, s.r_N, s.v_N);
      EXPECT_NEAR(el.e, e, 1e-12) << e << " " << t;
      EXPECT_NEAR(el.r_p, r_p, 1e-9 * r_p);
      EXPECT_NEAR(el.h_N.z(), std::sqrt(mu * p), 1e-12 * std::sqrt(mu * p));
      const double dt = 1e-2;
      const sim::OrbitState a = sim::conic_state_from_periapsis(mu, r_p, e, t - dt);
      const sim::OrbitState b = sim::conic_state_from_periapsis(mu, r_p, e, t + dt);
      EXPECT_LT(((b.r_N - a.r_N) / (2 * dt) - s.v_N).norm(), 1e-7 * s.v_N.norm()) << e << " " << t;
    }
  }
}

// One period of an e = 0.3 Mars orbit with RK4 (dt = 2 s): energy and
// angular momentum conserved, and the trajectory matches Kepler's solution.
// RK4 error scale: (n_max dt)^4 with n_max = v_p/r_p ~ 1.3e-3 /s -> ~5e-11
// per radian of true anomaly; we allow 1e-9 on position.
TEST(TwoBody, EllipticOrbitConservesAndMatchesKepler)
{
  const double mu = sim::kMuMars, r_p = 3896.19e3, e = 0.3;
  const double a = r_p / (1.0 - e);
  const double T = 2.0 * sim::kPi * std::sqrt(a * a * a / mu);
  const sim::OrbitState s0 = sim::conic_state_from_periapsis(mu, r_p, e, 0.0);
  sim::InitialConditions ic;
  ic.r_CN_N = s0.r_N;
  ic.v_CN_N = s0.v_N;
  ic.omega_BN_B = Vector3d(0.001, -0.002, 0.003);
  sim::Plant sc({mars_hub(), {}}, ic);
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  const int n = static_cast<int>(std::floor(T / 2.0));
  double worst = 0.0;
  for (int k = 1; k <= n; ++k) {
    ASSERT_EQ(sc.step(2'000'000'000), sim::StepStatus::Ok);  // 2 s
    if (k % 250 != 0 && k != n) continue;
    const sim::OrbitState s = sim::conic_state_from_periapsis(mu, r_p, e, k * 2.0);
    worst = std::max(worst, (sc.energy_momentum().r_CN_N - s.r_N).norm() / s.r_N.norm());
  }
  EXPECT_LT(worst, 1e-9);
  const sim::EnergyMomentum e1 = sc.energy_momentum();
  EXPECT_LT(std::abs(e1.E_orb - e0.E_orb), 1e-10 * std::abs(e0.E_orb));
  EXPECT_LT((e1.H_orb_N - e0.H_orb_N).norm(), 1e-10 * e0.H_orb_N.norm());
  EXPECT_NEAR(e0.E_orb / 750.0, -mu / (2.0 * a), 1e-12 * mu / a);
}

// Scenario S2 approach: v_inf = 2.5 km/s, periapsis altitude 500 km, start
// 750 s (half of a 1500 s burn) before periapsis; coasting brings the
// vehicle (with a full tank, B != C) to periapsis at v_p = sqrt(v_inf^2 + 2 mu/r_p).
TEST(TwoBody, MarsApproachHyperbolaReachesPeriapsis)
{
  const double mu = sim::kMuMars, v_inf = 2500.0;
  const double r_p = sim::kRadiusMars + 500e3;
  const double e = sim::hyperbolic_eccentricity(mu, r_p, v_inf);
  const sim::OrbitState s0 = sim::conic_state_from_periapsis(mu, r_p, e, -750.0);
  const sim::OrbitElements el = sim::elements_from_rv(mu, s0.r_N, s0.v_N);
  EXPECT_NEAR(el.energy, 0.5 * v_inf * v_inf, 1e-9 * v_inf * v_inf);
  EXPECT_NEAR(el.r_p, r_p, 1e-6);

  sim::PropulsionParams prop;
  prop.tanks.resize(1);
  prop.tanks[0].r_TB_B = Vector3d(0.0, 0.0, 0.2);
  prop.tanks[0].m_p0 = 400.0;
  sim::InitialConditions ic;
  ic.r_CN_N = s0.r_N;
  ic.v_CN_N = s0.v_N;
  sim::Plant v({mars_hub(), prop}, ic);
  for (int k = 0; k < 1500; ++k) ASSERT_EQ(v.step(500'000'000), sim::StepStatus::Ok);  // 0.5 s
  const sim::EnergyMomentum em = v.energy_momentum();
  const double v_p = std::sqrt(v_inf * v_inf + 2.0 * mu / r_p);
  EXPECT_LT((em.r_CN_N - Vector3d(r_p, 0.0, 0.0)).norm(), 1e-8 * r_p);
  EXPECT_LT((em.v_CN_N - Vector3d(0.0, v_p, 0.0)).norm(), 1e-8 * v_p);
}

TEST(Sun, PositionDirectionAndFluxGeometry)
{
  sim::SunParams sun;  // S1: (1 AU, 0, 0), fixed
  EXPECT_EQ(sim::sun_position_N(sun, 1e6), Vector3d(sim::kAU, 0.0, 0.0));
  // Circular heliocentric motion: a quarter period later the Sun is at +y.
  sun.n = std::sqrt(sim::kMuSun / std::pow(sim::kAU, 3));
  const double quarter = 0.5 * sim::kPi / sun.n;
  const Vector3d r_q = sim::sun_position_N(sun, quarter);
  EXPECT_NEAR((r_q - Vector3d(0.0, sim::kAU, 0.0)).norm(), 0.0, 1e-15 * sim::kAU * 10);
  EXPECT_NEAR(2.0 * sim::kPi / sun.n / 86400.0, 365.25, 0.1);  // a year, in days

  // Body yawed +90 deg about z: N's x axis is -y in B.
  const Matrix3d dcm_BN = simtest::rot(Vector3d::UnitZ(), 0.5 * sim::kPi).transpose();
  const Vector3d s_B = sim::sun_direction_B(dcm_BN, Vector3d::Zero(), Vector3d(sim::kAU, 0, 0));
  EXPECT_NEAR((s_B - Vector3d(0.0, -1.0, 0.0)).norm(), 0.0, 1e-15);
  // Spacecraft 1 AU along y: Sun direction (1, -1, 0)/sqrt2, flux halved.
  const Vector3d r_sc(0.0, sim::kAU, 0.0);
  const Vector3d s_N = sim::sun_direction_B(Matrix3d::Identity(), r_sc, Vector3d(sim::kAU, 0, 0));
  EXPECT_NEAR((s_N - Vector3d(1.0, -1.0, 0.0) / std::sqrt(2.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(sim::solar_flux_scale(r_sc, Vector3d(sim::kAU, 0, 0)), 0.5, 1e-15);
  EXPECT_NEAR(sim::solar_flux_scale(Vector3d::Zero(), Vector3d(1.524 * sim::kAU, 0, 0)),
              1.0 / (1.524 * 1.524), 1e-15);
}

// Test-side illumination: cast rays from the spacecraft to a grid of points
// on the solar disk (perpendicular to the line of sight) and count those not
// blocked by the body sphere.
double illumination_by_rays(const Vector3d& r_sc, const Vector3d& r_sun, double R_body, int n)
{
  const Vector3d w = (r_sun - r_sc).normalized();
  const Vector3d u = w.unitOrthogonal();
  const Vector3d v = w.cross(u);
  long total = 0, lit = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -1.0 + (2.0 * i + 1.0) / n, y = -1.0 + (2.0 * j + 1.0) / n;
      if (x * x + y * y > 1.0) continue;
      ++total;
      const Vector3d d = (r_sun + sim::kRadiusSun * (x * u + y * v) - r_sc).normalized();
      const double t_c = -r_sc.dot(d);  // closest approach of the ray to the body centre
      const bool blocked = t_c > 0.0 && (r_sc + t_c * d).norm() < R_body;
      lit += !blocked;
    }
  return static_cast<double>(lit) / static_cast<double>(total);
}

TEST(Sun, IlluminationFactorConicalShadow)
{
  const double R = sim::kRadiusMars;
  const Vector3d r_sun(1.524 * sim::kAU, 0.0, 0.0);
  // Sunlit side, and far outside the shadow cone.
  EXPECT_EQ(sim::illumination_factor(Vector3d(R + 500e3, 0, 0), r_sun, R), 1.0);
  EXPECT_EQ(sim::illumination_factor(Vector3d(0, R + 500e3, 0), r_sun, R), 1.0);
  // Deep umbra behind the planet.
  EXPECT_EQ(sim::illumination_factor(Vector3d(-(R + 500e3), 0, 0), r_sun, R), 0.0);
  EXPECT_EQ(sim::illumination_factor(Vector3d(-(R + 500e3), 0, 0), r_sun, 0.0), 1.0);

  // Walk across the penumbra on the night side at x = -(R + 500 km): the
  // factor rises monotonically from 0 to 1 and matches the ray count.
  double prev = -1.0, worst = 0.0;
  int partial = 0;
  for (int k = 0; k <= 40; ++k) {
    const double y = R - 15e3 + k * 0.75e3;
    const Vector3d r_sc(-(R + 500e3), y, 0.0);
    const double f = sim::illumination_factor(r_sc, r_sun, R);
    EXPECT_GE(f, prev);
    prev = f;
    if (f > 0.0 && f < 1.0) {
      ++partial;
      worst = std::max(worst, std::abs(f - illumination_by_rays(r_sc, r_sun, R, 200)));
    }
  }
  EXPECT_EQ(prev, 1.0);
  EXPECT_GE(partial, 5);
  EXPECT_LT(worst, 6e-3);  // grid of 200 x 200: edge-cell fraction ~ 4/200 * 0.3

  // Annular case (body disk inside the Sun's): 1 - (b/a)^2.
  const double R_small = 1e3;
  const Vector3d r_far(-4e6, 0.0, 0.0);
  const double a = std::asin(sim::kRadiusSun / (r_sun - r_far).norm());
  const double b = std::asin(R_small / 4e6);
  EXPECT_NEAR(sim::illumination_factor(r_far, r_sun, R_small), 1.0 - (b * b) / (a * a), 1e-12);
}

}  // namespace

// Environment (docs/dynamics.md §0, §6, §9.3, §11): point-mass gravity
// with a configurable mu (Mars for S2) inside the dynamics, the Earth's J2
// (by hand, against the potential, nodal regression), two-body
// conservation and Kepler solutions, the S2 approach hyperbola, Sun
// position/direction geometry and the conical-shadow illumination factor
// against an independent ray-casting count.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

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

// ------------------------------------------------------------------ J2

namespace {

// J2 acceleration in spherical components (independent of the Cartesian
// form of sim::j2_acceleration): from U = (mu J2 R^2 / (2 r^3)) (3 sin^2 phi - 1),
//   a_r   = -dU/dr          = -(3/2) mu J2 R^2 / r^4 (1 - 3 sin^2 phi)
//   a_phi = -(1/r) dU/dphi  = -3 mu J2 R^2 / r^4 sin phi cos phi  (northward),
// rotated to N with the local unit vectors at latitude phi, longitude lambda.
Vector3d j2_spherical(double mu, double J2, double R, const Vector3d& r_N)
{
  const double r = r_N.norm();
  const double phi = std::asin(r_N.z() / r), lam = std::atan2(r_N.y(), r_N.x());
  const double k = mu * J2 * R * R / std::pow(r, 4);
  const double a_r = -1.5 * k * (1.0 - 3.0 * std::sin(phi) * std::sin(phi));
  const double a_phi = -3.0 * k * std::sin(phi) * std::cos(phi);
  const Vector3d e_r(std::cos(phi) * std::cos(lam), std::cos(phi) * std::sin(lam), std::sin(phi));
  const Vector3d e_phi(-std::sin(phi) * std::cos(lam), -std::sin(phi) * std::sin(lam), std::cos(phi));
  return a_r * e_r + a_phi * e_phi;
}

sim::SpacecraftParams earth_j2_hub()
{
  sim::SpacecraftParams p;
  p.hub.m_h = 20.0;
  p.hub.I_hBc_B = Vector3d(0.3, 0.4, 0.5).asDiagonal();
  p.mu = sim::kMuEarth;
  p.J2 = sim::kJ2Earth;
  p.R_J2 = sim::kRadiusJ2Earth;
  return p;
}

}  // namespace

// J2 acceleration by hand at r = 7000 km, mu = 3.986004415e14, J2 =
// 1.08262668e-3, R = 6378137 m: k = (3/2) J2 mu R^2 / r^4
//   = 1.62394002e-3 * 3.986004415e14 * 4.0680631591e13 / 2.401e27
//   = 1.0967390e-2 m/s^2.
// Equator (x axis): a = (-k, 0, 0), towards the Earth (the equatorial bulge
// pulls harder).  Pole (z axis): a = (0, 0, +2k), away from it.  Printed to 8
// digits, so 1e-7 relative; against the spherical form at a general point to
// 1e-14, and against -grad U by central differences (step 1 m) to 1e-9.
TEST(Gravity, J2AccelerationByHandAndAgainstThePotential)
{
  const double mu = sim::kMuEarth, J2 = sim::kJ2Earth, R = sim::kRadiusJ2Earth;
  const double k = 1.0967390e-2;
  const Vector3d eq = sim::j2_acceleration(mu, J2, R, Vector3d(7.0e6, 0.0, 0.0));
  EXPECT_NEAR(eq.x(), -k, 1e-7 * k);
  EXPECT_EQ(eq.y(), 0.0);
  EXPECT_EQ(eq.z(), 0.0);
  const Vector3d eq_y = sim::j2_acceleration(mu, J2, R, Vector3d(0.0, -7.0e6, 0.0));
  EXPECT_NEAR(eq_y.y(), k, 1e-7 * k);
  const Vector3d pole = sim::j2_acceleration(mu, J2, R, Vector3d(0.0, 0.0, 7.0e6));
  EXPECT_NEAR(pole.z(), 2.0 * k, 1e-7 * k);
  EXPECT_EQ(pole.x(), 0.0);
  const Vector3d south = sim::j2_acceleration(mu, J2, R, Vector3d(0.0, 0.0, -7.0e6));
  EXPECT_NEAR(south.z(), -2.0 * k, 1e-7 * k);
  for (const Vector3d& r : {Vector3d(4.1e6, -3.3e6, 4.6e6), Vector3d(-6.6e6, 1.0e6, -2.2e6), Vector3d(1e5, 2e5, 7.1e6)}) {
    const Vector3d a = sim::j2_acceleration(mu, J2, R, r);
    EXPECT_LT((a - j2_spherical(mu, J2, R, r)).norm(), 1e-14 * k) << r.transpose();
    Vector3d grad;
    for (int i = 0; i < 3; ++i) {
      const Vector3d d = Vector3d::Unit(i);
      grad(i) = (sim::j2_potential(mu, J2, R, r + d) - sim::j2_potential(mu, J2, R, r - d)) / 2.0;
    }
    EXPECT_LT((a + grad).norm(), 1e-9 * a.norm()) << r.transpose();
  }
  EXPECT_EQ(sim::j2_acceleration(mu, 0.0, R, Vector3d(7e6, 0, 0)), Vector3d::Zero());
  // In the dynamics: a non-rotating hub, B != C: the mass centre accelerates
  // at point-mass plus J2 gravity at C.
  sim::SpacecraftParams p = earth_j2_hub();
  p.hub.r_BcB_B = Vector3d(0.02, -0.01, 0.05);
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(4.1e6, -3.3e6, 4.6e6);
  ic.sigma_BN = Vector3d(0.1, 0.2, -0.3);
  const sim::SpacecraftModel m(p);
  const sim::StateVector x = m.initial_state(ic, m.params().hub);
  const sim::StateVector xd = m.derivatives(0.0, x, sim::WheelInputs{}, sim::ExternalLoads{}, m.params().hub);
  const Vector3d g = -mu / std::pow(ic.r_CN_N.norm(), 3) * ic.r_CN_N + j2_spherical(mu, J2, R, ic.r_CN_N);
  EXPECT_LT((xd.segment<3>(sim::StateLayout::v_BN_N) - g).norm(), 1e-14 * g.norm());
}

TEST(Gravity, J2ConfigRejectedByName)
{
  const auto expect_field = [](sim::SpacecraftParams p, const std::string& field) {
    try {
      const sim::SpacecraftModel m(p);
      ADD_FAILURE() << "accepted " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  sim::SpacecraftParams p = earth_j2_hub();
  p.J2 = -1e-3;
  expect_field(p, "J2");
  p = earth_j2_hub();
  p.J2 = NAN;
  expect_field(p, "J2");
  p = earth_j2_hub();
  p.mu = 0.0;
  expect_field(p, "J2");
  p = earth_j2_hub();
  p.R_J2 = 0.0;
  expect_field(p, "R_J2");
  p = earth_j2_hub();
  p.R_J2 = INFINITY;
  expect_field(p, "R_J2");
}

// Nodal regression of a circular orbit (r = 7000 km, i = 45 deg and 98 deg)
// under J2, integrated by the plant (RK4, dt = 10 s), against the secular
// first-order theory
//   dOmega/dt = -(3/2) n J2 (R/p)^2 cos i,   n = sqrt(mu/a^3), p = a (1 - e^2) ~ a.
// Omega = atan2(h_x, -h_y) of h = r x v, sampled at each ascending-node
// crossing (z from - to +, time and Omega interpolated linearly between the
// steps): the short-period terms of Omega depend on the argument of latitude
// u, which is 0 at every sample, so they cancel in the differences; the rate
// is the slope over 5 nodal periods.
// The theory takes mean elements: here the time averages of the osculating a
// and i over those 5 periods (equal to the mean elements to first order in
// J2).  What it leaves out is of relative order J2 (R/a)^2 = 9.0e-4: the
// second-order secular terms and the difference between the mean motion and
// sqrt(mu/a^3) (1.5 J2 (R/p)^2 (1 - 1.5 sin^2 i): +3e-4 at 45 deg, -6e-4 at
// 98 deg).  Tolerance 2 J2 (R/a)^2 = 1.8e-3; measured 1.25e-3 (45 deg) and
// 8.2e-4 (98 deg).  With the initial osculating a = 7000 km instead (the
// mean a is 4.7 and 9.2 km lower, and the rate goes as a^{-7/2}: 2.4e-3 and
// 4.6e-3 more) the errors are 3.9e-3 and 4.5e-3; tolerance 6 J2 (R/a)^2.
// The orbital energy with the J2 potential (E_orb) stays constant to RK4's
// error, 1.5e-10 (tolerance 1e-9); without the potential it would swing by
// ~ J2 (R/a)^2 ~ 1e-3.
TEST(Gravity, J2NodalRegressionMatchesSecularTheory)
{
  const double mu = sim::kMuEarth, J2 = sim::kJ2Earth, R = sim::kRadiusJ2Earth, a = 7.0e6;
  const double n = std::sqrt(mu / (a * a * a));
  for (double inc_deg : {45.0, 98.0}) {
    const double inc = inc_deg * sim::kPi / 180.0;
    sim::InitialConditions ic;
    ic.r_CN_N = Vector3d(a, 0.0, 0.0);
    ic.v_CN_N = std::sqrt(mu / a) * Vector3d(0.0, std::cos(inc), std::sin(inc));
    sim::Plant sc({earth_j2_hub(), {}}, ic);
    const double E0 = sc.energy_momentum().E_orb;
    const auto node_of = [](const sim::EnergyMomentum& em) {
      const Vector3d h = em.r_CN_N.cross(em.v_CN_N);
      return std::atan2(h.x(), -h.y());
    };
    std::vector<double> t_node, om_node;
    // time averages of the osculating a and i between the first and last node
    double sum_a = 0.0, sum_i = 0.0, sum_w = 0.0;
    const auto osc = [&](const sim::EnergyMomentum& em, double& a_osc, double& i_osc) {
      const sim::OrbitElements el = sim::elements_from_rv(mu, em.r_CN_N, em.v_CN_N);
      a_osc = el.a;
      i_osc = std::acos(el.h_N.z() / el.h_N.norm());
    };
    sim::EnergyMomentum prev = sc.energy_momentum();
    double worst_E = 0.0;
    const double dt = 10.0;
    for (int k = 1; t_node.size() < 6; ++k) {
      ASSERT_EQ(sc.step(10'000'000'000), sim::StepStatus::Ok);
      const sim::EnergyMomentum em = sc.energy_momentum();
      worst_E = std::max(worst_E, std::abs(em.E_orb - E0) / std::abs(E0));
      if (!t_node.empty()) {  // trapezoid over the step
        double a0, i0, a1, i1;
        osc(prev, a0, i0);
        osc(em, a1, i1);
        sum_a += 0.5 * (a0 + a1) * dt;
        sum_i += 0.5 * (i0 + i1) * dt;
        sum_w += dt;
      }
      if (prev.r_CN_N.z() < 0.0 && em.r_CN_N.z() >= 0.0) {
        const double f = -prev.r_CN_N.z() / (em.r_CN_N.z() - prev.r_CN_N.z());
        t_node.push_back((k - 1 + f) * dt);
        om_node.push_back(node_of(prev) + f * (node_of(em) - node_of(prev)));
      }
      prev = em;
      ASSERT_LT(k, 10'000);
    }
    const double rate = (om_node.back() - om_node.front()) / (t_node.back() - t_node.front());
    const double theory = -1.5 * n * J2 * (R / a) * (R / a) * std::cos(inc);
    const double rel = std::abs(rate - theory) / std::abs(theory);
    const double am = sum_a / sum_w, im = sum_i / sum_w;
    const double theory_m = -1.5 * std::sqrt(mu / (am * am * am)) * J2 * (R / am) * (R / am) * std::cos(im);
    const double rel_m = std::abs(rate - theory_m) / std::abs(theory_m);
    std::printf("J2 nodal regression, i = %g deg: measured %.6e rad/s; theory with mean a = %.3f km, "
                "i = %.4f deg: %.6e rad/s (relative %.2e); with the initial a, i: %.6e (relative %.2e); "
                "energy drift %.1e\n", inc_deg, rate, am / 1e3, im * 180.0 / sim::kPi, theory_m, rel_m, theory, rel,
                worst_E);
    EXPECT_LT(rel_m, 2.0 * J2 * (R / a) * (R / a));
    EXPECT_LT(rel, 6.0 * J2 * (R / a) * (R / a));
    EXPECT_LT(worst_E, 1e-9);
  }
}

// ------------------------------------------------------------- eclipses

namespace {

// The exact umbra and penumbra of two spheres (Sun radius R_S at distance D
// along s_hat from the Earth's centre, Earth radius R), as cones about the
// axis -s_hat.  Let s = -P.s_hat be a point's distance behind the Earth's
// centre along the axis and rho its distance from the axis.
//   Umbra: the cone tangent to both spheres on the same side, apex behind
//   the Earth at x_u = R D / (R_S - R) (similar triangles R/x_u =
//   R_S/(x_u + D)), half-angle sin(alpha_u) = (R_S - R)/D; a point is in
//   umbra where rho <= (x_u - s) tan(alpha_u).
//   Penumbra (any part of the Sun hidden): the cone tangent on opposite
//   sides, apex towards the Sun at x_p = R D / (R_S + R), sin(alpha_p) =
//   (R_S + R)/D; the shadow is where rho <= (x_p + s) tan(alpha_p), s > 0.
// On a circular orbit of radius r in a plane at beta angle beta to the Sun
// direction, P = r (cos th e1 + sin th e2) with s_hat = cos(beta) e1 +
// sin(beta) n, so s = -r cos(beta) cos(th) and rho^2 = r^2 - s^2.  On the
// umbra cone r^2 - s^2 = (x_u - s)^2 t^2 (t = tan alpha_u):
//   (1 + t^2) s^2 - 2 x_u t^2 s + t^2 x_u^2 - r^2 = 0,
//   s_u = [x_u t^2 + sqrt(r^2 (1 + t^2) - t^2 x_u^2)] / (1 + t^2)
// (the root behind the Earth); on the penumbra cone, with x_p -> -x_p,
//   s_p = [-x_p t^2 + sqrt(r^2 (1 + t^2) - t^2 x_p^2)] / (1 + t^2).
// The shadow is the arc |th - pi| <= phi, cos(phi) = s_b / (r cos beta).
// This is the geometry sim::illumination_factor resolves: a point is in
// umbra exactly when the Earth's apparent disk covers the Sun's (c <= b - a
// with the apparent radii asin(R/d) of spheres), which happens exactly
// inside the cone tangent to both.
struct ShadowArc {
  double phi_umbra, phi_penumbra;  // [rad] half-arcs about the anti-Sun point
};

ShadowArc shadow_arc(double r, double beta, double R, double R_S, double D)
{
  const double x_u = R * D / (R_S - R), x_p = R * D / (R_S + R);
  const double t_u = std::tan(std::asin((R_S - R) / D)), t_p = std::tan(std::asin((R_S + R) / D));
  const double s_u = (x_u * t_u * t_u + std::sqrt(r * r * (1.0 + t_u * t_u) - t_u * t_u * x_u * x_u)) / (1.0 + t_u * t_u);
  const double s_p = (-x_p * t_p * t_p + std::sqrt(r * r * (1.0 + t_p * t_p) - t_p * t_p * x_p * x_p)) / (1.0 + t_p * t_p);
  return {std::acos(s_u / (r * std::cos(beta))), std::acos(s_p / (r * std::cos(beta)))};
}

}  // namespace

// Umbra and penumbra entry and exit of a circular 7000 km orbit (plant,
// RK4, dt = 1 s, no J2), the Sun fixed at 1 AU at beta = 0, 30 and 60 deg
// from the orbit plane (no umbra above 65.4 deg here).  The times where
// sim::illumination_factor first reaches 0 (umbra) and first drops below 1
// (penumbra), and where it leaves them, are found by bisection to 1 ns
// between the step ends (the plant restarted from the step start with the
// step cut at the trial time), and compared to th / n from the cone geometry
// above (th = pi -+ phi, the orbit starting at th = 0, n = sqrt(mu/r^3)).
// First the geometry itself: the same bisection on Kepler's positions with
// the contact condition c = b -+ a written here (c by atan2, well
// conditioned) reproduces the cones to 1e-9 s (measured ~1e-12 s).
// Tolerance for the plant: 1e-8 s.  The plant's orbit is Kepler's to
// 3e-7 m at these times (4e-11 s at 7.5 km/s), the bisection resolves 1 ns,
// and illumination_factor forms the near-contact factors of its disk
// overlap directly, so the factor keeps ~1e-14 absolute there and the
// contact moves by < 1e-11 rad.  Measured: up to 9e-10 s (printed).  (With
// acos of (c^2 + a^2 - b^2)/(2ac), as before 2026-12-05, an argument
// rounding of 1e-16 near +-1 became 1.5e-8 rad, times b^2 = 1.3 rad^2
// against the Sun's disk pi a^2 = 6.8e-5 rad^2: the factor was off by up to
// ~3e-4 near a contact and the times here by up to 3.8e-4 s.)
// Eclipse duration against the textbook cylinder: a shadow of radius R
// behind the Earth (the Sun at infinity) covers the points with s > 0 and
// rho <= R, i.e.
//   s = r cos(beta) cos(phi) >= sqrt(r^2 - R^2) = sqrt(h^2 + 2 R h),
// so the eclipse arc theta = 2 phi has cos(theta/2) = sqrt(h^2 + 2 R h) /
// (r cos beta), h = r - R.  The Sun's angular radius a = R_S/D = 4.65e-3 rad
// moves the umbra's edge in by ~ s a (13.5 km) and the penumbra's out by as
// much: the cylinder's duration lies between the two, and their mean equals
// it to first order; the second-order rest is ~ s a / s = a of the
// difference (measured 4.6e-3, 4.4e-3, 3.4e-4 of it): bound 2 a.
TEST(Sun, EclipseEntryAndExitMatchConicalGeometry)
{
  const double mu = sim::kMuEarth, R = sim::kRadiusEarth, r = 7.0e6, D = sim::kAU;
  const double n = std::sqrt(mu / (r * r * r));
  const double T = 2.0 * sim::kPi / n;
  sim::SpacecraftParams hub;
  hub.hub.m_h = 20.0;
  hub.hub.I_hBc_B = Vector3d(0.3, 0.4, 0.5).asDiagonal();
  hub.mu = mu;
  for (double beta_deg : {0.0, 30.0, 60.0}) {
    SCOPED_TRACE(beta_deg);
    const double beta = beta_deg * sim::kPi / 180.0;
    const Vector3d r_sun = D * Vector3d(std::cos(beta), 0.0, std::sin(beta));
    const auto illum = [&](const Vector3d& p) { return sim::illumination_factor(p, r_sun, R); };
    sim::InitialConditions ic;
    ic.r_CN_N = Vector3d(r, 0.0, 0.0);
    ic.v_CN_N = Vector3d(0.0, std::sqrt(mu / r), 0.0);
    sim::Plant plant({hub, {}}, ic);
    // f(t) test on the plant state restarted at (r_k, v_k) and stepped tau_ns.
    const auto state_after = [&](const Vector3d& r_k, const Vector3d& v_k, int64_t tau_ns) {
      sim::InitialConditions c;
      c.r_CN_N = r_k;
      c.v_CN_N = v_k;
      sim::Plant p({hub, {}}, c);
      if (tau_ns > 0) {
        EXPECT_EQ(p.step(tau_ns), sim::StepStatus::Ok);
      }
      return p.r_BN_N();
    };
    // Bisection for the first time in (t_k, t_k + 1 s] at which pred holds.
    const auto bisect = [&](const Vector3d& r_k, const Vector3d& v_k, double t_k, auto pred) {
      int64_t lo = 0, hi = 1'000'000'000;
      while (hi - lo > 1) {
        const int64_t mid = (lo + hi) / 2;
        (pred(illum(state_after(r_k, v_k, mid))) ? hi : lo) = mid;
      }
      return t_k + static_cast<double>(hi) * 1e-9;
    };
    double t_pen_in = NAN, t_umb_in = NAN, t_umb_out = NAN, t_pen_out = NAN;
    const int steps = static_cast<int>(T) + 1;
    double f_prev = illum(plant.r_BN_N());
    ASSERT_EQ(f_prev, 1.0);
    for (int k = 0; k < steps; ++k) {
      const Vector3d r_k = plant.r_BN_N(), v_k = plant.v_BN_N();
      ASSERT_EQ(plant.step(1'000'000'000), sim::StepStatus::Ok);
      const double f = illum(plant.r_BN_N());
      const double t_k = k;
      if (f_prev == 1.0 && f < 1.0) t_pen_in = bisect(r_k, v_k, t_k, [](double x) { return x < 1.0; });
      if (f_prev > 0.0 && f == 0.0) t_umb_in = bisect(r_k, v_k, t_k, [](double x) { return x == 0.0; });
      if (f_prev == 0.0 && f > 0.0) t_umb_out = bisect(r_k, v_k, t_k, [](double x) { return x > 0.0; });
      if (f_prev < 1.0 && f == 1.0) t_pen_out = bisect(r_k, v_k, t_k, [](double x) { return x == 1.0; });
      f_prev = f;
    }
    const ShadowArc arc = shadow_arc(r, beta, R, sim::kRadiusSun, D);
    {  // the geometry against the contact condition on Kepler's orbit
      const auto contact = [&](double th, double sign) {  // c - (b + sign a), >0 outside
        const Vector3d p = r * Vector3d(std::cos(th), std::sin(th), 0.0);
        const Vector3d to_sun = r_sun - p, to_body = -p;
        const double c = std::atan2(to_sun.cross(to_body).norm(), to_sun.dot(to_body));
        return c - (std::asin(R / p.norm()) + sign * std::asin(sim::kRadiusSun / to_sun.norm()));
      };
      for (double sign : {-1.0, 1.0}) {
        double lo = 0.5 * sim::kPi, hi = sim::kPi;  // contact < 0 at pi (in shadow)
        for (int it = 0; it < 200; ++it) {
          const double mid = 0.5 * (lo + hi);
          (contact(mid, sign) <= 0.0 ? hi : lo) = mid;
        }
        const double phi = sign < 0.0 ? arc.phi_umbra : arc.phi_penumbra;
        EXPECT_NEAR(hi / n, (sim::kPi - phi) / n, 1e-9) << "sign " << sign;
      }
    }
    const double want[4] = {(sim::kPi - arc.phi_penumbra) / n, (sim::kPi - arc.phi_umbra) / n,
                            (sim::kPi + arc.phi_umbra) / n, (sim::kPi + arc.phi_penumbra) / n};
    const double got[4] = {t_pen_in, t_umb_in, t_umb_out, t_pen_out};
    const char* what[4] = {"penumbra entry", "umbra entry", "umbra exit", "penumbra exit"};
    for (int i = 0; i < 4; ++i) {
      std::printf("beta %2.0f deg: %-14s sim %.9f s, cones %.9f s, difference %.1e s\n", beta_deg, what[i], got[i],
                  want[i], got[i] - want[i]);
      EXPECT_NEAR(got[i], want[i], 1e-8) << what[i];
    }
    // Duration against the textbook cylinder formula.
    const double h = r - R;
    const double theta_cyl = 2.0 * std::acos(std::sqrt(h * h + 2.0 * R * h) / (r * std::cos(beta)));
    const double T_cyl = theta_cyl / n, T_umb = t_umb_out - t_umb_in, T_pen = t_pen_out - t_pen_in;
    std::printf("beta %2.0f deg: eclipse duration: umbra %.3f s, penumbra %.3f s, cylinder %.3f s, "
                "mean of umbra and penumbra - cylinder %.3e s\n", beta_deg, T_umb, T_pen, T_cyl,
                0.5 * (T_umb + T_pen) - T_cyl);
    EXPECT_LT(T_umb, T_cyl);
    EXPECT_GT(T_pen, T_cyl);
    const double a_sun = sim::kRadiusSun / D;
    EXPECT_LT(std::abs(0.5 * (T_umb + T_pen) - T_cyl), 2.0 * a_sun * (T_pen - T_umb));
  }
}

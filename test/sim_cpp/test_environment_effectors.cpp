// The environment effectors of sim::Plant (sim/environment_effectors.h,
// docs/environment.md "In the plant"): gravity-gradient libration, the full
// inertia about the mass centre, the momentum balance of a disturbed run,
// bit-identity with inert effectors, hold, SRP shadow, drag scale, and
// magnetorquer commands and faults.
#include <array>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/environment_effectors.h"
#include "sim/units.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

sim::EarthContext context()
{
  sim::EarthContextParams p;
  p.epoch = {2026, 3, 20, 12, 0, 0.0};
  return sim::EarthContext(p);
}

sim::Facet facet(double area, const Vector3d& n, const Vector3d& r)
{
  sim::Facet f;
  f.area = area;
  f.n_B = n;
  f.r_B = r;
  f.absorbed = 0.6;
  f.specular = 0.3;
  f.diffuse = 0.1;
  return f;
}

// A 1 m box centred at (0.2, -0.1, 0.3) plus a 4 m^2 two-sided panel at
// +y 2 m: centres of pressure away from the mass centre, so that both the
// force and the torque matter.
sim::FacetSet box_and_panel()
{
  sim::FacetSet s;
  const Vector3d o(0.2, -0.1, 0.3);
  for (int a = 0; a < 3; ++a)
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      const Vector3d n = sgn * Vector3d::Unit(a);
      s.facets[static_cast<size_t>(s.count++)] = facet(1.0, n, o + 0.5 * n);
    }
  s.facets[static_cast<size_t>(s.count++)] = facet(4.0, Vector3d::UnitZ(), Vector3d(0.0, 2.0, 0.0));
  s.facets[static_cast<size_t>(s.count++)] = facet(4.0, -Vector3d::UnitZ(), Vector3d(0.0, 2.0, 0.0));
  return s;
}

// Circular orbit of radius R, inclination inc, C at (R, 0, 0).
sim::InitialConditions circular(double R, double inc)
{
  sim::InitialConditions ic;
  const double v = std::sqrt(sim::kMuEarth / R);
  ic.r_CN_N = Vector3d(R, 0.0, 0.0);
  ic.v_CN_N = v * Vector3d(0.0, std::cos(inc), std::sin(inc));
  return ic;
}

// ------------------------------------------------------- gravity gradient

// Small-angle pitch libration in a circular orbit.  Body axes x radial,
// y along-track, z orbit normal; pitch theta about z obeys
// theta'' = -(3 n^2 (I_y - I_x) / I_z) sin(theta) cos(theta).  With
// I = diag(200, 800, 600) (I_y - I_x = I_z, a plate in the x-z plane) the
// small-angle rate is sqrt(3) n; 2 theta is a pendulum angle, so the period
// at amplitude theta0 is 2 pi/(sqrt(3) n) (1 + theta0^2/4 + ...).  The hub
// CoM is off B so that the position of C, not B, has to be used.
TEST(GravityGradientEffector, PitchLibrationPeriod)
{
  const double R = 7000e3, theta0 = 1e-3;
  const double n = std::sqrt(sim::kMuEarth / (R * R * R));
  sim::PlantParams pp;
  pp.sc.hub.m_h = 100.0;
  pp.sc.hub.I_hBc_B = Vector3d(200.0, 800.0, 600.0).asDiagonal();
  pp.sc.hub.r_BcB_B = Vector3d(0.1, -0.2, 0.3);
  pp.sc.mu = sim::kMuEarth;
  sim::InitialConditions ic = circular(R, 0.0);
  ic.sigma_BN = Vector3d(0.0, 0.0, std::tan(theta0 / 4.0));  // pitch theta0 from LVLH (= N at t = 0)
  ic.omega_BN_B = Vector3d(0.0, 0.0, n);
  sim::Plant plant(pp, ic);
  plant.add_effector(std::make_unique<sim::GravityGradientEffector>(plant, context()));

  // theta = angle from the radial to B x, about N z (test-side rotation maths).
  auto pitch = [&plant]() {
    const Matrix3d C_BN = simtest::dcm_BN_via_quaternion(plant.sigma_BN());
    const Vector3d bx = C_BN.row(0).transpose();
    const Vector3d r = plant.energy_momentum().r_CN_N.normalized();
    return std::atan2(r.cross(bx).z(), r.dot(bx));
  };
  const double dt = 1.0;
  const double T_expected = 2.0 * M_PI / (std::sqrt(3.0) * n) * (1.0 + theta0 * theta0 / 4.0);
  std::vector<double> zeros;
  double prev = pitch();
  for (int k = 1; k <= static_cast<int>(5.6 * T_expected / dt); ++k) {
    ASSERT_EQ(plant.step(simtest::ns(dt)), sim::StepStatus::Ok);
    const double th = pitch();
    if ((prev > 0.0) != (th > 0.0)) zeros.push_back((k - 1) * dt + dt * prev / (prev - th));
    prev = th;
  }
  ASSERT_GE(zeros.size(), 10u);
  const double T = 2.0 * (zeros.back() - zeros.front()) / static_cast<double>(zeros.size() - 1);
  const double err = T / T_expected - 1.0;
  std::printf("libration period %.6f s, expected %.6f s, relative error %.2e\n", T, T_expected, err);
  EXPECT_LT(std::abs(err), 1e-7);
  // Without the amplitude term the error is theta0^2/4 = 2.5e-7: resolved.
  EXPECT_GT(std::abs(T * std::sqrt(3.0) * n / (2.0 * M_PI) - 1.0), 2e-7);
}

// The torque uses the full inertia about the mass centre: hub, a fully
// coupled wheel (a separate rotor: balanced, J_t = J_g = J_s/2 by default,
// so its inertia does not depend on the rotor angle) and a point-mass tank,
// with the parallel axes about C written out here.
TEST(GravityGradientEffector, FullInertiaAboutTheMassCentre)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.mu = sim::kMuEarth;
  sim::ReactionWheelParams w;
  w.model = sim::WheelModel::FullyCoupled;
  w.gs_hat_nom_B = Vector3d(1.0, 2.0, 2.0) / 3.0;
  w.r_WB_B = Vector3d(-0.6, 0.3, 1.2);
  w.m_w = 12.0;
  w.J_s = 0.09;
  w.Omega_0 = 150.0;
  pp.sc.wheels = {w};
  sim::TankParams tank;
  tank.r_TB_B = Vector3d(0.4, 0.7, -0.9);
  tank.m_p0 = 80.0;
  pp.prop.tanks = {tank};
  sim::InitialConditions ic = simtest::leo_ic();
  sim::Plant plant(pp, ic);
  auto& gg = plant.add_effector(std::make_unique<sim::GravityGradientEffector>(plant, context()));

  const sim::HubParams& h = pp.sc.hub;
  const double m = h.m_h + w.m_w + tank.m_p0;
  const Vector3d c = (h.m_h * h.r_BcB_B + w.m_w * w.r_WB_B + tank.m_p0 * tank.r_TB_B) / m;
  auto pa = [](double mass, const Vector3d& d) {
    return Matrix3d(mass * (d.dot(d) * Matrix3d::Identity() - d * d.transpose()));
  };
  const Vector3d g = w.gs_hat_nom_B;
  const Matrix3d I_rotor = w.J_s * g * g.transpose() + 0.5 * w.J_s * (Matrix3d::Identity() - g * g.transpose());
  const Matrix3d I_C = h.I_hBc_B + pa(h.m_h, h.r_BcB_B - c) + I_rotor + pa(w.m_w, w.r_WB_B - c) +
                       pa(tank.m_p0, tank.r_TB_B - c);
  const Matrix3d C_BN = simtest::dcm_BN_via_quaternion(plant.sigma_BN());
  const Vector3d R_B = C_BN * plant.r_BN_N() + c;  // position of C, B components
  const Vector3d expected = 3.0 * sim::kMuEarth / std::pow(R_B.norm(), 5) * R_B.cross(I_C * R_B);
  const sim::BodyLoad l = gg.load(0.0, plant.state());
  EXPECT_LT((l.L_B - expected).norm(), 1e-12 * expected.norm());
  EXPECT_EQ(l.F_B, Vector3d::Zero());
}

// No tank and no fully-coupled wheel: the mass centre and the inertia about
// it are formed once, at construction; the torque still follows the state
// (attitude and position after an hour of steps), with I_C and c written
// out here (a Balanced wheel's rotor is inside the hub's inertia).
TEST(GravityGradientEffector, FixedMassPropertiesFollowTheState)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.hub.r_BcB_B = Vector3d(0.05, -0.02, 0.11);
  pp.sc.mu = sim::kMuEarth;
  sim::ReactionWheelParams w;
  w.model = sim::WheelModel::Balanced;
  w.gs_hat_nom_B = Vector3d(1.0, 2.0, 2.0) / 3.0;
  w.m_w = 12.0;
  w.J_s = 0.09;
  w.Omega_0 = 150.0;
  pp.sc.wheels = {w};
  sim::InitialConditions ic = simtest::leo_ic();
  ic.omega_BN_B = Vector3d(0.01, -0.02, 0.015);
  sim::Plant plant(pp, ic);
  auto& gg = plant.add_effector(std::make_unique<sim::GravityGradientEffector>(plant, context()));
  const sim::HubParams& h = pp.sc.hub;
  const Vector3d c = h.r_BcB_B;
  const Matrix3d I_C = h.I_hBc_B;
  for (int k = 0; k < 360; ++k) ASSERT_EQ(plant.step(10000000000LL), sim::StepStatus::Ok);
  const Matrix3d C_BN = simtest::dcm_BN_via_quaternion(plant.sigma_BN());
  const Vector3d R_B = C_BN * plant.r_BN_N() + c;
  const Vector3d expected = 3.0 * sim::kMuEarth / std::pow(R_B.norm(), 5) * R_B.cross(I_C * R_B);
  const sim::BodyLoad l = gg.load(0.0, plant.state());
  EXPECT_GT(expected.norm(), 0.0);
  EXPECT_LT((l.L_B - expected).norm(), 1e-12 * expected.norm());
}

// ------------------------------------------------------ momentum balance

// Two plates whose normals stay within 65 deg of the Sun (B x) and of the
// flow (B y) over the run below: the loads are smooth functions of the
// state (a facet turning edge-on puts a kink max(0, n.s) into the load).
sim::FacetSet two_plates()
{
  sim::FacetSet s;
  s.facets[0] = facet(2.0, Vector3d::UnitX(), Vector3d(0.3, 0.5, -0.2));
  s.facets[1] = facet(1.5, Vector3d::UnitY(), Vector3d(-0.4, 0.2, 0.6));
  s.count = 2;
  return s;
}

struct Balance {
  double err = 0.0;             // |dH - int L_C dt| / |int L_C dt|
  double dH = 0.0;              // [N m s] |dH|
  double min_cos = 1.0;         // smallest n.s, n.v_hat of the two plates (two_plates only)
  std::array<double, 4> part{};  // [N m s] |int L_C dt| of each effector alone
  // The effectors' own accumulators (SampledEnvironmentEffector::momentum_N):
  double err_acc = 0.0;               // |dH - sum of momentum_N| / |dH|
  std::array<double, 4> acc_vs_simpson{};  // |momentum_N - Simpson part| / |Simpson part|, each effector
};

// Gravity gradient + SRP + drag + residual dipole + a commanded rod, four
// spinning wheels, a CoM 12 cm off B, 300 s at 51.6 deg, 400 km: the change
// of H_C,N against the integral of the external torque about C, the sum
// over the effectors of [NB](L_B - c x F_B), integrated here by composite
// Simpson on the step ends (each effector's load(t, x) at the plant state).
Balance momentum_balance(const sim::FacetSet& facets, const Vector3d& sigma, const Vector3d& omega, double dt)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.wheels = simtest::pyramid_wheels(sim::WheelModel::Balanced);
  pp.sc.mu = sim::kMuEarth;
  sim::InitialConditions ic = circular(6778e3, sim::rad_from_deg(51.6));
  ic.sigma_BN = sigma;
  ic.omega_BN_B = omega;
  sim::Plant plant(pp, ic);
  const sim::EarthContext ctx = context();

  std::vector<const sim::SampledEnvironmentEffector*> effs;
  effs.push_back(&plant.add_effector(std::make_unique<sim::GravityGradientEffector>(plant, ctx)));
  sim::SolarPressureParams srp;
  srp.facets = facets;
  srp.period_ns = 0;
  effs.push_back(&plant.add_effector(std::make_unique<sim::SolarPressureEffector>(plant, ctx, srp)));
  sim::DragParams drag;
  drag.facets = facets;
  drag.period_ns = 0;
  effs.push_back(&plant.add_effector(std::make_unique<sim::DragEffector>(plant, ctx, drag)));
  sim::MagneticParams mag;
  mag.m_residual_B = Vector3d(0.5, -0.3, 0.8);
  sim::MagnetorquerParams rod;
  rod.axis_B = Vector3d::UnitY();
  rod.m_max = 10.0;
  mag.rods = {rod};
  mag.period_ns = 0;
  auto& m = plant.add_effector(std::make_unique<sim::MagneticEffector>(plant, ctx, mag));
  m.command_dipoles({6.0});
  effs.push_back(&m);

  Balance b;
  auto torques_C_N = [&](std::array<Vector3d, 4>& L) {
    const double t = sim::seconds_from_ns(plant.t_ns());
    const Vector3d c = plant.mass_centre().c_B;
    const Matrix3d C_NB = simtest::dcm_BN_via_quaternion(plant.sigma_BN()).transpose();
    for (size_t k = 0; k < 4; ++k) {
      const sim::BodyLoad l = effs[k]->load(t, plant.state());
      L[k] = C_NB * (l.L_B - c.cross(l.F_B));
    }
    // Plate 0 against the Sun, plate 1 against the flow (test-side).
    const Matrix3d C_BN = C_NB.transpose();
    const Vector3d s_B = C_BN * (ctx.sun_position_N(t) - plant.r_BN_N()).normalized();
    const Vector3d w_B = C_BN * sim::wind_velocity_N(plant.r_BN_N(), plant.v_BN_N()).normalized();
    b.min_cos = std::min({b.min_cos, s_B.x(), w_B.y()});
  };
  const int pairs = static_cast<int>(std::lround(150.0 / dt));
  const Vector3d H0 = plant.energy_momentum().H_C_N;
  std::array<Vector3d, 4> f0, f1, f2, part;
  part.fill(Vector3d::Zero());
  torques_C_N(f0);
  for (int k = 0; k < pairs; ++k) {
    EXPECT_EQ(plant.step(simtest::ns(dt)), sim::StepStatus::Ok);
    torques_C_N(f1);
    EXPECT_EQ(plant.step(simtest::ns(dt)), sim::StepStatus::Ok);
    torques_C_N(f2);
    for (size_t e = 0; e < 4; ++e) part[e] += (dt / 3.0) * (f0[e] + 4.0 * f1[e] + f2[e]);
    f0 = f2;
  }
  const Vector3d integral = part[0] + part[1] + part[2] + part[3];
  const Vector3d dH = plant.energy_momentum().H_C_N - H0;
  b.err = (dH - integral).norm() / integral.norm();
  b.dH = dH.norm();
  Vector3d acc = Vector3d::Zero();
  for (size_t e = 0; e < 4; ++e) {
    b.part[e] = part[e].norm();
    acc += effs[e]->momentum_N();
    b.acc_vs_simpson[e] = (effs[e]->momentum_N() - part[e]).norm() / part[e].norm();
  }
  b.err_acc = (dH - acc).norm() / dH.norm();
  return b;
}

TEST(EnvironmentEffectors, MomentumBalance)
{
  const Balance b = momentum_balance(two_plates(), Vector3d::Zero(), Vector3d(0.002, -0.001, 0.0015), 0.1);
  std::printf("momentum balance: |dH| %.6e N m s, relative error %.2e; parts GG %.3e SRP %.3e drag %.3e "
              "magnetic %.3e N m s; min cos %.3f\n",
              b.dH, b.err, b.part[0], b.part[1], b.part[2], b.part[3], b.min_cos);
  ASSERT_GT(b.min_cos, 0.1);  // no facet turned edge-on: the loads are smooth
  EXPECT_LT(b.err, 1e-9);
  for (double p : b.part) EXPECT_GT(p, 1e-5 * b.dH);  // each effector far above the tolerance
  // (Summing L_B instead of L_B - c x F_B above misses by 8.7e-2.)

  // The effectors' own accumulators, RK4-weighted stage torques: the sum
  // closes the balance, and each agrees with the test's Simpson integral
  // of that effector's load (two quadratures of the same smooth torque).
  std::printf("accumulated: relative error %.2e; against Simpson GG %.1e SRP %.1e drag %.1e magnetic %.1e\n",
              b.err_acc, b.acc_vs_simpson[0], b.acc_vs_simpson[1], b.acc_vs_simpson[2], b.acc_vs_simpson[3]);
  EXPECT_LT(b.err_acc, 1e-9);
  for (double d : b.acc_vs_simpson) EXPECT_LT(d, 1e-7);
}

// A derivative evaluated outside Plant::step (a caller's query) adds nothing
// to the accumulated momentum; a step does.
TEST(EnvironmentEffectors, AccumulatedMomentumCountsOnlyTheSteps)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.mu = sim::kMuEarth;
  sim::Plant plant(pp, circular(6778e3, 0.9));
  const auto& gg = plant.add_effector(std::make_unique<sim::GravityGradientEffector>(plant, context()));
  (void)plant.derivatives(0.0, plant.state());
  EXPECT_EQ(gg.momentum_N(), Vector3d::Zero());
  ASSERT_EQ(plant.step(simtest::ns(0.1)), sim::StepStatus::Ok);
  const Vector3d after_one = gg.momentum_N();
  EXPECT_GT(after_one.norm(), 0.0);
  (void)plant.derivatives(0.0, plant.state());
  EXPECT_EQ(gg.momentum_N(), after_one);
}

// A tumbling box: facets turn edge-on many times, and at each such kink
// both RK4 and the test's Simpson rule lose their order (local error
// O(h^2)).  The balance then holds to O(h): measured 3.6e-7 at 0.1 s,
// 1.5e-7 at 0.05 s.  The effectors' own accumulators, which weight the
// stage torques as RK4 does, close it far better.
TEST(EnvironmentEffectors, MomentumBalanceThroughFacetKinks)
{
  const Vector3d sigma(0.1, 0.2, -0.3), omega(0.01, -0.02, 0.015);
  const Balance coarse = momentum_balance(box_and_panel(), sigma, omega, 0.1);
  const Balance fine = momentum_balance(box_and_panel(), sigma, omega, 0.05);
  std::printf("through kinks: relative error %.2e at 0.1 s, %.2e at 0.05 s; accumulated %.2e, %.2e\n", coarse.err,
              fine.err, coarse.err_acc, fine.err_acc);
  EXPECT_LT(coarse.err, 1e-6);
  EXPECT_LT(fine.err, 0.6 * coarse.err);
  // The accumulators integrate the very stage torques RK4 used, kinks
  // included: the balance closes to 4.3e-11 and 4.8e-11.
  EXPECT_LT(coarse.err_acc, 1e-9);
  EXPECT_LT(fine.err_acc, 1e-9);
}

// ---------------------------------------------------------- bit identity

// Effectors that contribute nothing (no facets, no dipole), sampled every
// stage or held: the run is bit-identical to the plant without them.
TEST(EnvironmentEffectors, InertEffectorsLeaveTheRunBitIdentical)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.wheels = simtest::pyramid_wheels(sim::WheelModel::Balanced);
  pp.sc.mu = sim::kMuEarth;
  const sim::InitialConditions ic = simtest::leo_ic();
  sim::Plant old_way(pp, ic);
  sim::Plant with(pp, ic);
  const sim::EarthContext ctx = context();
  for (int64_t period : {int64_t{0}, int64_t{300000000}}) {
    sim::SolarPressureParams s;
    s.period_ns = period;
    with.add_effector(std::make_unique<sim::SolarPressureEffector>(with, ctx, s));
    sim::DragParams d;
    d.period_ns = period;
    with.add_effector(std::make_unique<sim::DragEffector>(with, ctx, d));
    sim::MagneticParams m;
    m.period_ns = period;
    with.add_effector(std::make_unique<sim::MagneticEffector>(with, ctx, m));
  }
  const sim::WheelArray cmd{0.01, -0.02, 0.03, 0.04};
  for (int k = 0; k < 500; ++k) {
    old_way.latch_wheel_commands(cmd);
    with.latch_wheel_commands(cmd);
    ASSERT_EQ(old_way.step(simtest::ns(0.1)), sim::StepStatus::Ok);
    ASSERT_EQ(with.step(simtest::ns(0.1)), sim::StepStatus::Ok);
  }
  ASSERT_EQ(old_way.state().size(), with.state().size());
  for (int i = 0; i < old_way.state().size(); ++i) EXPECT_EQ(old_way.state()(i), with.state()(i)) << i;
  EXPECT_EQ(old_way.mrp_switch_count(), with.mrp_switch_count());
}

// ------------------------------------------------------------------ hold

// A held environment is sampled at the first step start at or after each
// k T (the steps are not cut) and kept in N between samples.
TEST(EnvironmentEffectors, HeldEnvironmentIsSampledAtThePeriod)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.mu = sim::kMuEarth;
  sim::Plant plant(pp, circular(6778e3, 0.9));
  sim::DragParams d;
  d.facets = box_and_panel();
  d.period_ns = simtest::ns(1.0);
  auto& drag = plant.add_effector(std::make_unique<sim::DragEffector>(plant, context(), d));
  sim::DragParams d0 = d;
  d0.period_ns = 0;
  const sim::DragEffector exact(plant, context(), d0);
  EXPECT_EQ(drag.last_sample_ns(), 0);
  for (int k = 1; k <= 25; ++k) {
    ASSERT_EQ(plant.step(simtest::ns(0.3)), sim::StepStatus::Ok);  // samples at 1.2, 2.1 s
    const int64_t expected = k < 5 ? 0 : k < 8 ? simtest::ns(1.2) : k < 11 ? simtest::ns(2.1) : -1;
    if (expected >= 0) {
      EXPECT_EQ(drag.last_sample_ns(), expected) << k;
    }
  }
  // Steps start at multiples of 0.3 s: the last sample (7.2 s) is one
  // step old; the held density differs from the exact one by the altitude
  // change over that step.
  const int64_t ts = drag.last_sample_ns();
  EXPECT_EQ(ts % simtest::ns(0.3), 0);
  EXPECT_LE(plant.t_ns() - ts, simtest::ns(1.2));
  sim::StateVector x = plant.state();
  const sim::BodyLoad held = drag.load(0.0, x);
  const sim::BodyLoad now = exact.load(0.0, x);
  EXPECT_NE(held.F_B, now.F_B);                               // held, not exact
  EXPECT_EQ(ts, simtest::ns(7.2));
  EXPECT_LT((held.F_B - now.F_B).norm(), 1e-3 * now.F_B.norm());  // 0.3 s of altitude change
}

// With period_ns > 0 gravity gradient, SRP and drag evaluate their load at
// each sample (the first step start at or after k T) and hold it in B until
// the next sample.  The same run made by hand: a plant without the
// effectors whose held external force and torque are set, at the steps
// where the effectors sampled, to their load at that step's start state
// (sim::Plant::set_external): every step bit-identical.  Both plants pass
// through the same states, so the loads are the same numbers.
TEST(EnvironmentEffectors, HeldLoadIsConstantInBBetweenSamples)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.mu = sim::kMuEarth;
  sim::InitialConditions ic = circular(6778e3, 0.9);
  ic.omega_BN_B = Vector3d(0.02, -0.05, 0.08);  // tumbling: the load moves within a step
  sim::Plant with(pp, ic), by_hand(pp, ic);
  sim::SolarPressureParams sp;
  sp.facets = box_and_panel();
  sp.period_ns = simtest::ns(1.0);
  sim::DragParams dp;
  dp.facets = box_and_panel();
  dp.period_ns = simtest::ns(1.0);
  sim::GravityGradientParams gp;
  gp.period_ns = simtest::ns(1.0);
  std::vector<const sim::SampledEnvironmentEffector*> eff;
  eff.push_back(&with.add_effector(std::make_unique<sim::GravityGradientEffector>(with, context(), gp)));
  eff.push_back(&with.add_effector(std::make_unique<sim::SolarPressureEffector>(with, context(), sp)));
  eff.push_back(&with.add_effector(std::make_unique<sim::DragEffector>(with, context(), dp)));
  Vector3d L_first = Vector3d::Zero(), L_last = Vector3d::Zero();
  int64_t last_sample = -1;
  int resamples = 0;
  for (int k = 0; k < 40; ++k) {
    // the step start; `with` samples its environment there (every 1 s)
    const sim::StateVector x0 = with.state();
    const double t0 = 1e-9 * static_cast<double>(with.t_ns());
    ASSERT_EQ(with.step(simtest::ns(0.25)), sim::StepStatus::Ok);
    if (eff[0]->last_sample_ns() != last_sample) {  // sampled at this step's start
      last_sample = eff[0]->last_sample_ns();
      ASSERT_EQ(last_sample, with.t_ns() - simtest::ns(0.25));
      ++resamples;
      Vector3d F = Vector3d::Zero(), L = Vector3d::Zero();
      for (const auto* e : eff) {
        ASSERT_EQ(e->last_sample_ns(), last_sample);
        const sim::BodyLoad l = e->load(t0, x0);
        F += l.F_B;
        L += l.L_B;
      }
      by_hand.set_external(F, L);
      (k == 0 ? L_first : L_last) = L;
    }
    ASSERT_EQ(by_hand.step(simtest::ns(0.25)), sim::StepStatus::Ok);
    ASSERT_EQ(with.state(), by_hand.state()) << k;
  }
  EXPECT_EQ(resamples, 10);  // at 0, 1, ..., 9 s
  // the load moved from sample to sample: a hold between samples, not through the run
  EXPECT_GT((L_last - L_first).norm(), 0.1 * L_first.norm());
}

// ------------------------------------------------------------------- SRP

TEST(SolarPressureEffector, SunlitPlateAndUmbra)
{
  const sim::EarthContext ctx = context();
  const Vector3d sun = ctx.sun_position_N(0.0);
  const Vector3d s_hat = sun.normalized();
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.mu = sim::kMuEarth;
  sim::SolarPressureParams p;
  p.period_ns = 0;
  sim::Facet f;  // absorbing 2 m^2 plate, normal B x, at (0, 0, 1) m
  f.area = 2.0;
  f.n_B = Vector3d::UnitX();
  f.r_B = Vector3d(0.0, 0.0, 1.0);
  p.facets.facets[0] = f;
  p.facets.count = 1;

  // Sunlit side, B = N rotated so that B x points at the Sun.
  sim::InitialConditions ic = circular(7000e3, 0.0);
  ic.r_CN_N = 7000e3 * s_hat;
  const Vector3d ax = Vector3d::UnitX().cross(s_hat).normalized();
  const double ang = std::acos(Vector3d::UnitX().dot(s_hat));
  ic.sigma_BN = ax * std::tan(ang / 4.0);  // [BN] takes s_hat to B x
  sim::Plant lit(pp, ic);
  auto& e = lit.add_effector(std::make_unique<sim::SolarPressureEffector>(lit, ctx, p));
  const Vector3d s_B = simtest::dcm_BN_via_quaternion(lit.sigma_BN()) * (sun - lit.r_BN_N()).normalized();
  ASSERT_NEAR(s_B.x(), 1.0, 1e-9);
  const double flux = std::pow(sim::kAU / (sun - lit.r_BN_N()).norm(), 2);
  const sim::BodyLoad l = e.load(0.0, lit.state());
  const Vector3d F = -sim::kSolarPressure1AU * 2.0 * flux * s_B;  // absorbed: -P A s
  EXPECT_LT((l.F_B - F).norm(), 1e-12 * F.norm());
  EXPECT_LT((l.L_B - Vector3d(0.0, 0.0, 1.0).cross(F)).norm(), 1e-12 * F.norm());

  // Behind the Earth (anti-Sun side, 7000 km): umbra, nothing.
  ic.r_CN_N = -7000e3 * s_hat;
  sim::Plant dark(pp, ic);
  auto& e2 = dark.add_effector(std::make_unique<sim::SolarPressureEffector>(dark, ctx, p));
  EXPECT_EQ(e2.load(0.0, dark.state()).F_B, Vector3d::Zero());
}

// ------------------------------------------------------------------ drag

TEST(DragEffector, PlateAgainstTheFlowAndDensityScale)
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.hub.r_BcB_B = Vector3d::Zero();  // B = C: the height of B is 400 km exactly
  pp.sc.mu = sim::kMuEarth;
  const double R = sim::kWgs84A + 400e3;
  sim::Plant plant(pp, circular(R, 0.0));  // equatorial: height 400 km, air along N y
  sim::DragParams p;
  p.period_ns = 0;
  sim::Facet f;  // 1.5 m^2 plate facing the flow (normal B y = N y), C_D 2.2
  f.area = 1.5;
  f.n_B = Vector3d::UnitY();
  f.r_B = Vector3d(0.3, 0.0, 0.0);
  p.facets.facets[0] = f;
  p.facets.count = 1;
  auto& e = plant.add_effector(std::make_unique<sim::DragEffector>(plant, context(), p));
  // Vallado Table 8-4, 400 km band: rho0 = 3.725e-12 kg/m^3 at h0 = 400 km.
  const double v_rel = std::sqrt(sim::kMuEarth / R) - sim::kOmegaEarth * R;
  const double Fy = -0.5 * 3.725e-12 * 2.2 * 1.5 * v_rel * v_rel;
  const sim::BodyLoad l = e.load(0.0, plant.state());
  EXPECT_NEAR(l.F_B.y(), Fy, 1e-9 * std::abs(Fy));
  EXPECT_NEAR(l.F_B.x(), 0.0, 1e-20);
  EXPECT_NEAR(l.L_B.z(), 0.3 * Fy, 1e-9 * std::abs(Fy));
  e.set_density_scale(2.5);
  EXPECT_NEAR(e.load(0.0, plant.state()).F_B.y(), 2.5 * Fy, 1e-9 * std::abs(Fy));
  try {
    e.set_density_scale(-1.0);
    FAIL();
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("drag.atmosphere.scale"), std::string::npos);
  }
}

// -------------------------------------------------------- magnetorquers

// The reference hub in LEO about the Earth (the magnetic effector's plant).
sim::PlantParams leo_hub_params()
{
  sim::PlantParams pp;
  pp.sc.hub = simtest::reference_hub();
  pp.sc.mu = sim::kMuEarth;
  return pp;
}

// field_N keeps its last evaluation: the same arguments give it back, and a
// change of either the time or the position evaluates the model again (each
// result equals IGRF-14 formed here).
TEST(MagneticEffector, FieldNIsTheModelAfterARepeatedOrChangedCall)
{
  sim::Plant plant(leo_hub_params(), simtest::leo_ic());
  const sim::EarthContext ctx = context();
  sim::MagneticParams p;
  auto& m = plant.add_effector(std::make_unique<sim::MagneticEffector>(plant, ctx, p));
  const sim::Igrf14 igrf(ctx.decimal_year(), 13);
  auto model = [&](double t, const Vector3d& r) {
    const Matrix3d C_EN = ctx.dcm_EN(t);
    return Vector3d(C_EN.transpose() * igrf.field_E(C_EN * r));
  };
  const Vector3d r1 = plant.r_BN_N(), r2 = r1 + Vector3d(7.5e3, -2.0e3, 1.0e3);  // [m] a second later
  const Vector3d a = m.field_N(10.0, r1);
  const double tol = 1e-18;  // [T] |B| ~ 3e-5 T: ~100 roundings
  EXPECT_LT((a - model(10.0, r1)).norm(), tol);
  EXPECT_EQ(m.field_N(10.0, r1), a);                           // kept
  EXPECT_LT((m.field_N(11.0, r1) - model(11.0, r1)).norm(), tol);  // the time changed
  EXPECT_LT((m.field_N(11.0, r2) - model(11.0, r2)).norm(), tol);  // the position changed
  EXPECT_GT((model(11.0, r2) - model(11.0, r1)).norm(), 1e-8);  // [T] they differ (a change is seen)
  EXPECT_EQ(m.field_N(10.0, r1), a);             // and back
}

TEST(MagneticEffector, CommandsSaturationFaultsAndTorque)
{
  sim::Plant plant(leo_hub_params(), simtest::leo_ic());
  const sim::EarthContext ctx = context();
  sim::MagneticParams p;
  p.m_residual_B = Vector3d(0.1, 0.2, 0.3);
  p.period_ns = 0;
  for (int a = 0; a < 3; ++a) {
    sim::MagnetorquerParams r;
    r.axis_B = Vector3d::Unit(a);
    r.m_max = 10.0;
    r.m_remanent = 0.05;
    p.rods.push_back(r);
  }
  auto& m = plant.add_effector(std::make_unique<sim::MagneticEffector>(plant, ctx, p));
  EXPECT_EQ(m.num_rods(), 3);
  m.command_dipoles({4.0, -25.0, 2.0});  // rod 1 saturates
  EXPECT_LT((m.dipole_B() - Vector3d(4.1, -9.8, 2.3)).norm(), 1e-14);
  EXPECT_TRUE(m.rod(1).saturated());

  // Torque m x B with B from the IGRF at the epoch year, rotated N -> B here.
  const Matrix3d C_EN = ctx.dcm_EN(0.0);
  const sim::Igrf14 igrf(ctx.decimal_year(), 13);
  const Vector3d B_N = C_EN.transpose() * igrf.field_E(C_EN * plant.r_BN_N());
  const Vector3d B_B = simtest::dcm_BN_via_quaternion(plant.sigma_BN()) * B_N;
  const Vector3d L = Vector3d(4.1, -9.8, 2.3).cross(B_B);
  EXPECT_LT((m.load(0.0, plant.state()).L_B - L).norm(), 1e-12 * L.norm());
  EXPECT_GT(B_N.norm(), 1e-6);  // about 10 uT at this radius

  // Faults: scale, stuck (frozen), failed off (remanence of the last sign).
  m.set_rod_scale(0, 0.5);
  m.set_rod_health(1, sim::MagnetorquerHealth::Stuck);
  m.set_rod_health(2, sim::MagnetorquerHealth::FailedOff);
  m.command_dipoles({4.0, 3.0, -7.0});
  EXPECT_EQ(m.rod_dipole(0), 2.0);
  EXPECT_EQ(m.rod_dipole(1), -10.0);
  EXPECT_EQ(m.rod_dipole(2), 0.05);
  m.set_rod_health(1, sim::MagnetorquerHealth::Nominal);
  m.command_dipoles({0.0, 3.0, 0.0});
  EXPECT_EQ(m.rod_dipole(1), 3.0);
  EXPECT_EQ(m.rod_dipole(0), 0.05);  // coil off: remanence, sign of the last command (+)

  // Named fields.
  auto msg = [&](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(msg([&] { m.set_rod_scale(2, -1.0); }).find("magnetic.rods[2].scale"), std::string::npos);
  EXPECT_NE(msg([&] { m.set_rod_health(0, static_cast<sim::MagnetorquerHealth>(7)); }).find("magnetic.rods[0].health"),
            std::string::npos);
  sim::MagneticParams bad = p;
  bad.igrf_degree = 14;
  EXPECT_NE(msg([&] { sim::MagneticEffector e(plant, ctx, bad); }).find("magnetic.igrf_degree"), std::string::npos);
  bad = p;
  bad.period_ns = -1;
  EXPECT_NE(msg([&] { sim::MagneticEffector e(plant, ctx, bad); }).find("magnetic.period_ns"), std::string::npos);
  bad = p;
  bad.rods[1].m_max = 0.0;
  EXPECT_NE(msg([&] { sim::MagneticEffector e(plant, ctx, bad); }).find("magnetic.rods[1].m_max"), std::string::npos);
  sim::SolarPressureParams s;
  s.facets.count = 1;
  s.facets.facets[0].area = 0.0;
  EXPECT_NE(msg([&] { sim::SolarPressureEffector e(plant, ctx, s); }).find("solar_pressure.facets[0].area"),
            std::string::npos);
}

}  // namespace

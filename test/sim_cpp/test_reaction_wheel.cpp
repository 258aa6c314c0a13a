// Reaction wheels (docs/dynamics.md §4): frame convention, command
// pipeline, friction and mode logic, closed-form spin-up and spin-down,
// zero-imbalance equivalences, the fully-coupled back-effect against an
// independent planar Newton-Euler model, mixed models, config rejection.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "kestrel_test_support.h"
#include "sim/attitude.h"
#include "sim/reaction_wheel.h"
#include "sim/plant.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using sim::WheelModel;

// --------------------------------------------------------------- §4.2 frames

void expect_vec_eq(const Vector3d& a, const Vector3d& b, double tol)
{
  EXPECT_LT((a - b).norm(), tol) << "got " << a.transpose() << ", want " << b.transpose();
}

TEST(WheelFrame, SpecExamplesForCoordinateAxes)
{
  struct Case { Vector3d g, w2, w3; };
  const Case cases[] = {
      {Vector3d::UnitX(), Vector3d::UnitZ(), -Vector3d::UnitY()},
      {Vector3d::UnitY(), -Vector3d::UnitZ(), -Vector3d::UnitX()},
      {Vector3d::UnitZ(), Vector3d::UnitY(), -Vector3d::UnitX()},
  };
  for (const Case& c : cases) {
    sim::ReactionWheelParams p;
    p.gs_hat_nom_B = c.g;
    p.J_s = 0.1;
    const sim::ReactionWheelDerived d = sim::derive(p);
    EXPECT_EQ(d.gs_hat_B, c.g);
    expect_vec_eq(d.w2_0_hat_B, c.w2, 1e-15);
    expect_vec_eq(d.w3_0_hat_B, c.w3, 1e-15);
    // theta = 90 deg: w2 -> w3_0, w3 -> -w2_0 (positive rotation about gs)
    const sim::WheelAxes ax = sim::wheel_axes(d, 0.5 * sim::kPi);
    expect_vec_eq(ax.w2_hat_B, c.w3, 1e-15);
    expect_vec_eq(ax.w3_hat_B, -c.w2, 1e-15);
  }
}

TEST(WheelFrame, MisalignmentRotatesAxisAndTransverseAxes)
{
  // g_nom = x, delta = 0.01 rad about y: g = (cos, 0, -sin), w2_0 = R z = (sin, 0, cos), w3_0 = -y.
  sim::ReactionWheelParams p;
  p.gs_hat_nom_B = Vector3d::UnitX();
  p.delta_mis_B = Vector3d(0.0, 0.01, 0.0);
  p.J_s = 0.1;
  const sim::ReactionWheelDerived d = sim::derive(p);
  expect_vec_eq(d.gs_hat_B, Vector3d(std::cos(0.01), 0.0, -std::sin(0.01)), 1e-16);
  expect_vec_eq(d.w2_0_hat_B, Vector3d(std::sin(0.01), 0.0, std::cos(0.01)), 1e-16);
  expect_vec_eq(d.w3_0_hat_B, -Vector3d::UnitY(), 1e-16);
}

TEST(WheelFrame, NearXAxisFallsBackToY)
{
  // |g x x| = sin(0.005) < 0.01 -> w2_0 = unit(g x y)
  sim::ReactionWheelParams p;
  p.gs_hat_nom_B = Vector3d(std::cos(0.005), std::sin(0.005), 0.0);
  p.J_s = 0.1;
  const sim::ReactionWheelDerived d = sim::derive(p);
  expect_vec_eq(d.w2_0_hat_B, Vector3d::UnitZ(), 1e-15);  // g x y ~ x x y = z
  expect_vec_eq(d.w3_0_hat_B, p.gs_hat_nom_B.cross(Vector3d::UnitZ()), 1e-15);
}

TEST(WheelFrame, DerivedValuesAreEchoed)
{
  sim::ReactionWheelParams p;
  p.model = WheelModel::FullyCoupled;
  p.gs_hat_nom_B = Vector3d::UnitZ();
  p.J_s = 0.08;
  p.m_w = 4.0;
  p.U_s = 2.0e-4;
  p.U_d = 3.0e-5;
  const sim::ReactionWheelDerived d = sim::derive(p);
  EXPECT_DOUBLE_EQ(d.d, 5.0e-5);
  EXPECT_EQ(d.J13, 3.0e-5);
  EXPECT_EQ(d.J_t, 0.04);  // default J_s/2
  EXPECT_EQ(d.J_g, 0.04);
  EXPECT_DOUBLE_EQ(d.J_bar, 0.08 + 4.0 * 2.5e-9);
  p.model = WheelModel::SimpleJitter;  // imbalance does not move a simple-jitter rotor
  EXPECT_EQ(sim::derive(p).d, 0.0);
  EXPECT_EQ(sim::derive(p).J_bar, 0.08);
}

// ------------------------------------------------------ §4.3 command pipeline

TEST(WheelCommand, PipelineOrderSaturationDeadbandPowerSpeed)
{
  sim::ReactionWheelParams p;
  p.u_max = 0.2;
  p.u_min = 0.01;
  p.P_max = 1.0;
  p.Omega_max = 100.0;
  struct Case { double u_cmd, Omega, want; const char* why; };
  const Case cases[] = {
      {0.5, 10.0, 0.1, "saturate to 0.2, then |0.2*10| >= 1 W: 1/10"},
      {-0.5, 1.0, -0.2, "saturate only"},
      {0.15, 0.0, 0.15, "pass through at rest"},
      {0.005, 5.0, 0.0, "dead-band"},
      {-0.009, 5.0, 0.0, "dead-band, negative"},
      {0.05, 100.0, 0.0, "power limit to 0.01, then speed limit (accelerating)"},
      {-0.05, 100.0, -0.01, "power limit; slowing torque allowed at max speed"},
      {-0.05, -150.0, 0.0, "speed limit, negative direction"},
      {0.0, 200.0, 0.0, "zero stays zero"},
  };
  for (const Case& c : cases)
    EXPECT_DOUBLE_EQ(sim::command_pipeline(p, c.u_cmd, c.Omega), c.want) << c.why;

  sim::ReactionWheelParams off;  // all limits disabled
  EXPECT_EQ(sim::command_pipeline(off, 3.7, 1e4), 3.7);
}

TEST(WheelCommand, LatchUsesWheelSpeedAtLatchAndHoldsIt)
{
  sim::SpacecraftParams sp;
  sp.hub.m_h = 100.0;
  sp.hub.I_hBc_B = Matrix3d::Identity() * 10.0;
  sim::ReactionWheelParams w;
  w.gs_hat_nom_B = Vector3d::UnitZ();
  w.J_s = 0.1;
  w.P_max = 2.0;
  w.Omega_0 = 40.0;
  sp.wheels.push_back(w);
  sim::Plant sc({sp, {}}, sim::InitialConditions{});
  sim::WheelArray u{};
  u[0] = 1.0;
  sc.latch_wheel_commands(u);
  EXPECT_DOUBLE_EQ(sc.u_s(0), 2.0 / 40.0);  // power limit at the latch speed
  for (int k = 0; k < 10; ++k) sc.step(simtest::ns(0.1));
  EXPECT_GT(sc.Omega(0), 40.0);
  EXPECT_DOUBLE_EQ(sc.u_s(0), 2.0 / 40.0);  // held, not re-limited during the steps
}

// -------------------------------------------------------------- §4.4 friction

sim::WheelFrictionParams friction_params()
{
  sim::WheelFrictionParams f;
  f.tau_c = 0.002;
  f.tau_st = 0.004;
  f.c_v = 1e-5;
  f.beta_st = 0.5;
  f.omega_lc = 0.1;
  return f;
}

TEST(WheelFriction, CoulombViscousHandValues)
{
  const sim::WheelFrictionParams f = friction_params();
  EXPECT_DOUBLE_EQ(sim::friction_torque(f, 10.0, false), -(0.002 + 1e-4));
  EXPECT_DOUBLE_EQ(sim::friction_torque(f, -10.0, false), 0.002 + 1e-4);
  // low-speed band: line through the origin and f(omega_lc) = 0.002 + 1e-6
  EXPECT_DOUBLE_EQ(sim::friction_torque(f, 0.05, false), -0.5 * 0.002001);
  EXPECT_DOUBLE_EQ(sim::friction_torque(f, -0.025, false), 0.25 * 0.002001);
  EXPECT_EQ(sim::friction_torque(f, 0.0, false), 0.0);
  // continuous at the band edge
  EXPECT_NEAR(sim::friction_torque(f, 0.1 * (1 - 1e-12), false),
              sim::friction_torque(f, 0.1 * (1 + 1e-12), false), 1e-14);
}

TEST(WheelFriction, StribeckPeakAndSymmetry)
{
  const sim::WheelFrictionParams f = friction_params();
  // At Omega = beta the hump term is exactly tau_st - tau_c (docs/dynamics.md §4.4).
  const double want = -((0.004 - 0.002) + 0.002 * std::tanh(10.0 * 0.5 / 0.5) + 1e-5 * 0.5);
  EXPECT_NEAR(sim::friction_torque(f, 0.5, true), want, 1e-17);
  // the hump term is the maximum over Omega: breakaway close to tau_st
  double peak = 0.0;
  for (int k = 1; k < 2000; ++k) peak = std::max(peak, -sim::friction_torque(f, k * 1e-3, true));
  EXPECT_NEAR(peak, 0.004, 1e-5);
  for (double Om : {0.03, 0.3, 2.0, 40.0})
    EXPECT_EQ(sim::friction_torque(f, -Om, true), -sim::friction_torque(f, Om, true));
  // beta_st <= 0 disables Stribeck even if the flag is set
  sim::WheelFrictionParams off = f;
  off.beta_st = -1.0;
  EXPECT_EQ(sim::friction_torque(off, 0.5, true), sim::friction_torque(off, 0.5, false));
}

TEST(WheelFriction, StribeckModeLogic)
{
  const sim::WheelFrictionParams f = friction_params();  // 0.1 omega_lc = 0.01
  // §4.6: entered near zero only while the speed moves AWAY from zero.
  EXPECT_TRUE(sim::update_stribeck_mode(f, false, 0.005, 1e-3));    // near zero, speeding up: enter
  EXPECT_TRUE(sim::update_stribeck_mode(f, false, -0.005, -1e-3));
  EXPECT_TRUE(sim::update_stribeck_mode(f, false, 0.0, -1.0));      // at rest: enter
  EXPECT_TRUE(sim::update_stribeck_mode(f, false, 0.005, 0.0));     // first step (dOmega = 0): enter
  EXPECT_FALSE(sim::update_stribeck_mode(f, false, 0.005, -1e-3));  // near zero but slowing: stay out
  EXPECT_FALSE(sim::update_stribeck_mode(f, false, -0.005, 1e-3));
  EXPECT_FALSE(sim::update_stribeck_mode(f, true, 0.005, -1e-3));   // slowing near zero: leave
  EXPECT_TRUE(sim::update_stribeck_mode(f, true, 0.5, 0.01));      // moving away: keep
  EXPECT_TRUE(sim::update_stribeck_mode(f, true, -0.5, -0.01));
  EXPECT_TRUE(sim::update_stribeck_mode(f, true, 0.5, 0.0));       // dOmega zero: keep
  EXPECT_FALSE(sim::update_stribeck_mode(f, true, 0.5, -0.01));    // slowing: leave
  EXPECT_FALSE(sim::update_stribeck_mode(f, false, 0.5, 0.01));    // not entered
  sim::WheelFrictionParams off = f;
  off.beta_st = 0.0;
  EXPECT_FALSE(sim::update_stribeck_mode(off, true, 0.0, 0.0));
}

// ------------------------------------------ one wheel about a principal axis

// Hub with one wheel spinning about z through the CoM, body rate about z only.
// Balanced/Simple: hub total I_zz includes J_s.  FullyCoupled: hub excludes the
// rotor, so the total is I_hz + J_s.  With motor torque u_tot on the rotor:
//   omega_z' = -u/(I_zz - J_s),   Omega' = u I_zz / (J_s (I_zz - J_s)).
struct SingleWheel {
  sim::SpacecraftParams params;
  double I_zz;  // [kg*m^2] total about z through C
  double J_s;
};

SingleWheel single_wheel(WheelModel model)
{
  SingleWheel s;
  s.J_s = 0.05;
  const double I_hz = 8.0;
  sim::SpacecraftParams& p = s.params;
  p.hub.m_h = 100.0;
  p.hub.I_hBc_B = Vector3d(10.0, 12.0, I_hz).asDiagonal();
  sim::ReactionWheelParams w;
  w.model = model;
  w.gs_hat_nom_B = Vector3d::UnitZ();
  w.r_WB_B = Vector3d(0.0, 0.0, 0.2);  // on the axis: keeps z principal for FC
  w.J_s = s.J_s;
  w.m_w = 3.0;
  w.Omega_0 = 20.0;
  p.wheels.push_back(w);
  s.I_zz = model == WheelModel::FullyCoupled ? I_hz + s.J_s : I_hz;
  return s;
}

class SingleWheelAnalytic : public ::testing::TestWithParam<WheelModel> {};

TEST_P(SingleWheelAnalytic, SpinUpWithConstantMotorTorque)
{
  const SingleWheel s = single_wheel(GetParam());
  sim::InitialConditions ic;
  ic.omega_BN_B = Vector3d(0.0, 0.0, 0.3);
  sim::Plant sc({s.params, {}}, ic);
  const double u = 0.03;
  sim::WheelArray cmd{};
  cmd[0] = u;
  sc.latch_wheel_commands(cmd);
  const double wz_dot = -u / (s.I_zz - s.J_s);
  const double Om_dot = u * s.I_zz / (s.J_s * (s.I_zz - s.J_s));
  const double dt = 0.01;
  for (int k = 1; k <= 2000; ++k) {  // 20 s: Omega 20 -> ~32 rad/s, hub turns > 180 deg
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    const double t = k * dt;
    const double wz = 0.3 + wz_dot * t;
    ASSERT_NEAR(sc.Omega(0), 20.0 + Om_dot * t, 1e-10 * 20.0) << "t = " << t;
    ASSERT_NEAR(sc.omega_BN_B().z(), wz, 1e-12);
    EXPECT_LT(sc.omega_BN_B().head<2>().norm(), 1e-14);
    const double angle = 0.3 * t + 0.5 * wz_dot * t * t;
    const Matrix3d dcm_BN_true = simtest::rot(Vector3d::UnitZ(), angle).transpose();
    ASSERT_LT(std::abs(simtest::dcm_angle(sim::dcm_BN_from_sigma(sc.sigma_BN()) *
                                          dcm_BN_true.transpose())), 1e-10);
  }
  EXPECT_GE(sc.mrp_switch_count(), 1u);
}

TEST_P(SingleWheelAnalytic, ViscousSpinDownIsExponential)
{
  SingleWheel s = single_wheel(GetParam());
  s.params.wheels[0].friction.c_v = 2e-3;
  s.params.wheels[0].friction.omega_lc = 1e-4;
  sim::Plant sc({s.params, {}}, sim::InitialConditions{});
  const double k_rate = 2e-3 * s.I_zz / (s.J_s * (s.I_zz - s.J_s));  // [1/s]
  const double dt = 0.005;
  for (int k = 1; k <= 2000; ++k) ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
  const double Om = 20.0 * std::exp(-k_rate * 10.0);
  EXPECT_NEAR(sc.Omega(0), Om, 1e-10 * 20.0);
  // total momentum about z: I_zz w + J_s Omega = J_s Omega_0 (hub starts at rest)
  EXPECT_NEAR(sc.omega_BN_B().z(), s.J_s * (20.0 - Om) / s.I_zz, 1e-13);
  EXPECT_NEAR(sc.tau_f(0), -2e-3 * sc.Omega(0), 1e-15);
}

TEST_P(SingleWheelAnalytic, CoulombSpinDownIsLinear)
{
  SingleWheel s = single_wheel(GetParam());
  s.params.wheels[0].friction.tau_c = 1e-3;
  sim::Plant sc({s.params, {}}, sim::InitialConditions{});
  const double rate = 1e-3 * s.I_zz / (s.J_s * (s.I_zz - s.J_s));
  for (int k = 0; k < 500; ++k) ASSERT_EQ(sc.step(simtest::ns(0.01)), sim::StepStatus::Ok);
  EXPECT_NEAR(sc.Omega(0), 20.0 - rate * 5.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Models, SingleWheelAnalytic,
                         ::testing::Values(WheelModel::Balanced, WheelModel::SimpleJitter,
                                           WheelModel::FullyCoupled),
                         [](const auto& info) { return std::string(sim::to_string(info.param)); });

// Spin-axis misalignment in the dynamics (not only in the frame): a balanced
// wheel whose axis is tilted by delta_mis = 0.02 rad about x, hub and wheel at
// rest, motor torque u on.  At omega = 0 the hub equation is
//   [I - J_s g g^T] omega_dot = -g u,   g = R_x(0.02) z = (0, -sin 0.02, cos 0.02)
// with the TRUE axis g (computed here by hand, not from the code).  Over a
// 1e-4 s step omega = omega_dot dt to O(dt^2) relative.  Using the nominal
// axis instead would put omega_dot_y = 0 and fail.
TEST(WheelMisalignment, HubFeelsTheTrueSpinAxis)
{
  SingleWheel s = single_wheel(WheelModel::Balanced);
  s.params.wheels[0].Omega_0 = 0.0;
  s.params.wheels[0].delta_mis_B = Vector3d(0.02, 0.0, 0.0);
  sim::Plant sc({s.params, {}}, sim::InitialConditions{});
  const double u = 0.05, dt = 1e-4;
  sim::WheelArray cmd{};
  cmd[0] = u;
  sc.latch_wheel_commands(cmd);
  ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
  const Vector3d g(0.0, -std::sin(0.02), std::cos(0.02));
  const Matrix3d I = Vector3d(10.0, 12.0, 8.0).asDiagonal();
  const Vector3d omega_dot = -(I - s.J_s * g * g.transpose()).inverse() * g * u;
  const Vector3d omega = sc.omega_BN_B();
  EXPECT_NEAR((omega - omega_dot * dt).norm() / (omega_dot * dt).norm(), 0.0, 1e-6);
  // g_y = -sin(0.02) < 0, so the hub turns about +y: omega_y / |omega_z| = sin(0.02) (7.95/12) = 0.013
  EXPECT_GT(omega.y(), 1e-2 * std::abs(omega.z()));
}

// Conservation holds with misaligned axes too (fully coupled pyramid,
// every wheel tilted differently), motors off and no friction.
TEST(WheelMisalignment, FullyCoupledPyramidStillConserves)
{
  sim::SpacecraftParams p;
  p.hub = simtest::reference_hub();
  p.wheels = simtest::pyramid_wheels(WheelModel::FullyCoupled);
  for (size_t i = 0; i < p.wheels.size(); ++i)
    p.wheels[i].delta_mis_B = Vector3d(0.01 * (i + 1), -0.005 * i, 0.002);
  sim::Plant sc({p, {}}, sim::InitialConditions{});
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  double dH = 0.0, dE = 0.0;
  for (int k = 0; k < 5000; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(1e-4)), sim::StepStatus::Ok);
    const sim::EnergyMomentum e = sc.energy_momentum();
    dH = std::max(dH, (e.H_C_N - e0.H_C_N).norm() / e0.H_C_N.norm());
    dE = std::max(dE, std::abs(e.E_rot - e0.E_rot) / e0.E_rot);
  }
  EXPECT_LT(dH, 1e-12);
  EXPECT_LT(dE, 1e-12);
}

// Stribeck flag through the step protocol: entered at rest, kept while
// spinning up, dropped once the wheel decelerates.
TEST(WheelFriction, ModeFollowsStepProtocol)
{
  SingleWheel s = single_wheel(WheelModel::Balanced);
  s.params.wheels[0].Omega_0 = 0.0;
  s.params.wheels[0].friction = friction_params();
  sim::Plant sc({s.params, {}}, sim::InitialConditions{});
  sim::WheelArray cmd{};
  cmd[0] = 0.01;
  sc.latch_wheel_commands(cmd);
  sc.step(simtest::ns(0.01));
  EXPECT_TRUE(sc.stribeck_mode(0));
  for (int k = 0; k < 50; ++k) sc.step(simtest::ns(0.01));
  EXPECT_TRUE(sc.stribeck_mode(0));
  EXPECT_GT(sc.Omega(0), 0.0);
  cmd[0] = -0.02;
  sc.latch_wheel_commands(cmd);
  sc.step(simtest::ns(0.01));  // flag uses the speed change over the previous step: still accelerating
  sc.step(simtest::ns(0.01));
  EXPECT_FALSE(sc.stribeck_mode(0));
}

// §4.6 regression: a wheel braked by friction toward rest must not enter the
// Stribeck regime (it is slowing down, not breaking away).  Viscous friction
// with Coulomb off and a stiction hump configured (tau_st > 0, beta_st > 0):
// the Coulomb/viscous law is exactly -c_v Omega at every speed, so
//   Omega(t) = Omega_0 exp(-k t),  k = c_v I_zz / (J_s (I_zz - J_s))
// (single-axis coupling as in SingleWheelAnalytic).  Entering the regime
// below 0.1 omega_lc would add the hump slope and leave the exponential.
TEST(WheelFriction, ViscousCoastToRestFollowsTheExponentialAndNeverEntersStribeck)
{
  SingleWheel s = single_wheel(WheelModel::Balanced);
  sim::WheelFrictionParams& f = s.params.wheels[0].friction;
  f.tau_c = 0.0;
  f.c_v = 1e-3;
  f.tau_st = 1e-3;
  f.beta_st = 0.5;
  f.omega_lc = 1e-4;
  sim::Plant sc({s.params, {}}, sim::InitialConditions{});
  const double k_rate = 1e-3 * s.I_zz / (s.J_s * (s.I_zz - s.J_s));  // [1/s] ~0.0201
  const double dt = 0.1;                                            // k dt = 2e-3
  double worst_rel = 0.0;
  for (int k = 1; k <= 20000; ++k) {  // 2000 s = 40 time constants
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    ASSERT_FALSE(sc.stribeck_mode(0)) << "t = " << k * dt;
    const double truth = 20.0 * std::exp(-k_rate * k * dt);
    worst_rel = std::max(worst_rel, std::abs(sc.Omega(0) - truth) / truth);
  }
  EXPECT_LT(worst_rel, 1e-9);
  EXPECT_LT(std::abs(sc.Omega(0)), 1e-12);  // analytic: 20 e^-40.3 = 6e-17
}

// The case the old reading got badly wrong: Coulomb + viscous friction with
// Stribeck configured, coasting to rest.  Below omega_lc the law is the
// straight line f(omega_lc) Omega / omega_lc, i.e. an exponential with
//   k = (tau_c / omega_lc + c_v) I_zz / (J_s (I_zz - J_s)).
// Entering the Stribeck regime at 0.1 omega_lc (old behaviour) replaced that
// slope with tau_c tanh(10 omega_lc/beta)/omega_lc + ..., ~400x weaker, and
// the wheel crept at ~1e-7 rad/s for minutes.
TEST(WheelFriction, CoulombCoastToRestDecaysAtTheLowSpeedBandRate)
{
  SingleWheel s = single_wheel(WheelModel::Balanced);
  s.params.wheels[0].Omega_0 = 0.05;
  sim::WheelFrictionParams& f = s.params.wheels[0].friction;
  f.tau_c = 1e-4;
  f.c_v = 1e-5;
  f.tau_st = 2e-4;
  f.beta_st = 0.5;
  f.omega_lc = 1e-4;
  sim::Plant sc({s.params, {}}, sim::InitialConditions{});
  const double coupling = s.I_zz / (s.J_s * (s.I_zz - s.J_s));
  const double k_band = (1e-4 / 1e-4 + 1e-5) * coupling;  // [1/s] ~20: stiff, RK4 needs k dt < 2.7
  const double dt = 0.01;
  // Enter the band (Coulomb ramp takes ~ 0.05 / (1e-4 * coupling) = 25 s).
  int k = 0;
  while (std::abs(sc.Omega(0)) >= 1e-4 && k < 5000) {
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    ++k;
  }
  ASSERT_LT(k, 5000);
  const double Om_band = sc.Omega(0);
  ASSERT_GT(Om_band, 0.0);
  // RK4 amplification for the linear decay, per step: R(z) = 1 - z + z^2/2 - z^3/6 + z^4/24.
  const double z = k_band * dt;
  const double R = 1.0 - z + z * z / 2.0 - z * z * z / 6.0 + z * z * z * z / 24.0;
  double Om_rk4 = Om_band;
  for (int n = 1; n <= 200; ++n) {  // 2 s = 40 band time constants
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    EXPECT_FALSE(sc.stribeck_mode(0));
    Om_rk4 *= R;
    EXPECT_NEAR(sc.Omega(0), Om_rk4, 1e-9 * Om_band + 1e-300) << "n = " << n;
  }
  // RK4 and the analytic exponential agree to (z^5/120) per step here.
  EXPECT_NEAR(sc.Omega(0), Om_band * std::exp(-k_band * 2.0), 1e-3 * Om_band * std::exp(-k_band * 2.0));
  EXPECT_LT(std::abs(sc.Omega(0)), 1e-12);
}

// ... and a wheel accelerating away from zero does enter it: start slightly
// negative, a small positive motor torque drives Omega through zero.  Flags:
// first step in (dOmega = 0), out while approaching zero, in again once past
// zero and below 0.1 omega_lc, kept while the speed keeps growing.
TEST(WheelFriction, AcceleratingAwayFromZeroEntersStribeck)
{
  SingleWheel s = single_wheel(WheelModel::Balanced);
  s.params.wheels[0].Omega_0 = -5e-6;
  sim::WheelFrictionParams& f = s.params.wheels[0].friction;
  f.tau_c = 0.0;
  f.c_v = 1e-9;
  f.tau_st = 1e-9;
  f.beta_st = 0.5;
  f.omega_lc = 1e-4;  // 0.1 omega_lc = 1e-5
  sim::Plant sc({s.params, {}}, sim::InitialConditions{});
  sim::WheelArray cmd{};
  cmd[0] = 1e-6;  // Omega_dot ~ 2e-5 rad/s^2: 2e-7 rad/s per 0.01 s step
  sc.latch_wheel_commands(cmd);
  ASSERT_EQ(sc.step(simtest::ns(0.01)), sim::StepStatus::Ok);
  EXPECT_TRUE(sc.stribeck_mode(0));  // first step: dOmega = 0
  ASSERT_EQ(sc.step(simtest::ns(0.01)), sim::StepStatus::Ok);
  EXPECT_FALSE(sc.stribeck_mode(0));  // Omega < 0 growing toward zero
  int k = 0;
  while (sc.Omega(0) <= 0.0 && k < 1000) {
    ASSERT_EQ(sc.step(simtest::ns(0.01)), sim::StepStatus::Ok);
    ++k;
  }
  ASSERT_LT(k, 1000);
  ASSERT_EQ(sc.step(simtest::ns(0.01)), sim::StepStatus::Ok);  // this step starts with Omega in (0, 1e-5)
  EXPECT_TRUE(sc.stribeck_mode(0));
  for (int n = 0; n < 200; ++n) ASSERT_EQ(sc.step(simtest::ns(0.01)), sim::StepStatus::Ok);
  EXPECT_GT(sc.Omega(0), 1e-5);      // well past the entry band ...
  EXPECT_TRUE(sc.stribeck_mode(0));  // ... and still breaking away
}

// ------------------------------------------------ zero-imbalance equivalences

sim::SpacecraftParams pyramid_vehicle(WheelModel model)
{
  sim::SpacecraftParams p;
  p.hub = simtest::reference_hub();
  p.wheels = simtest::pyramid_wheels(model);
  p.mu = sim::kMuEarth;
  return p;
}

TEST(WheelImbalance, SimpleJitterWithZeroImbalanceIsBitwiseBalanced)
{
  sim::SpacecraftParams pb = pyramid_vehicle(WheelModel::Balanced);
  sim::SpacecraftParams ps = pyramid_vehicle(WheelModel::SimpleJitter);
  for (auto& w : ps.wheels) w.U_s = w.U_d = 0.0;
  sim::Plant b({pb, {}}, simtest::leo_ic());
  sim::Plant s({ps, {}}, simtest::leo_ic());
  sim::WheelArray cmd{0.01, -0.02, 0.015, 0.005};
  b.latch_wheel_commands(cmd);
  s.latch_wheel_commands(cmd);
  for (int k = 0; k < 1000; ++k) {
    b.step(simtest::ns(1e-3));
    s.step(simtest::ns(1e-3));
  }
  EXPECT_EQ(b.state(), s.state());
  // and the imbalance does change the answer, so the comparison has teeth
  sim::Plant j({pyramid_vehicle(WheelModel::SimpleJitter), {}}, simtest::leo_ic());
  j.latch_wheel_commands(cmd);
  for (int k = 0; k < 1000; ++k) j.step(simtest::ns(1e-3));
  EXPECT_GT((j.omega_BN_B() - b.omega_BN_B()).norm(), 1e-9);
}

// FC rotors with no imbalance and J_t = J_g are axisymmetric rigid bodies:
// folding their mass and inertia into the hub (parallel-axis theorem, done
// here by hand) must give the Balanced answer.
TEST(WheelImbalance, FullyCoupledWithZeroImbalanceEqualsBalancedWithFoldedHub)
{
  sim::SpacecraftParams pf = pyramid_vehicle(WheelModel::FullyCoupled);
  pf.hub.m_h = 714.0;  // 750 kg total with four 9 kg rotors
  for (auto& w : pf.wheels) {
    w.U_s = w.U_d = 0.0;
    w.J_t.reset();
    w.J_g.reset();
  }
  sim::SpacecraftParams pb = pyramid_vehicle(WheelModel::Balanced);
  const double m = pf.hub.m_h + 4 * 9.0;
  Vector3d first = pf.hub.m_h * pf.hub.r_BcB_B;
  for (const auto& w : pf.wheels) first += w.m_w * w.r_WB_B;
  const Vector3d c = first / m;
  auto P = [](const Vector3d& r) { return Matrix3d(r.squaredNorm() * Matrix3d::Identity() - r * r.transpose()); };
  Matrix3d I_C = pf.hub.I_hBc_B + pf.hub.m_h * P(pf.hub.r_BcB_B - c);
  for (const auto& w : pf.wheels) {
    const Vector3d g = w.gs_hat_nom_B;
    I_C += w.J_s * g * g.transpose() + 0.5 * w.J_s * (Matrix3d::Identity() - g * g.transpose()) +
           w.m_w * P(w.r_WB_B - c);
  }
  pb.hub.m_h = m;
  pb.hub.r_BcB_B = c;
  pb.hub.I_hBc_B = 0.5 * (I_C + I_C.transpose());

  sim::Plant f({pf, {}}, simtest::leo_ic());
  sim::Plant b({pb, {}}, simtest::leo_ic());
  sim::WheelArray cmd{0.01, -0.02, 0.015, 0.005};
  f.latch_wheel_commands(cmd);
  b.latch_wheel_commands(cmd);
  for (int k = 0; k < 1000; ++k) {
    f.step(simtest::ns(1e-3));
    b.step(simtest::ns(1e-3));
  }
  EXPECT_LT(simtest::rel_err(f.omega_BN_B(), b.omega_BN_B()), 1e-12);
  EXPECT_LT((f.sigma_BN() - b.sigma_BN()).norm(), 1e-13);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(f.Omega(i), b.Omega(i), 1e-12 * std::abs(b.Omega(i)));
  EXPECT_LT((f.energy_momentum().r_CN_N - b.energy_momentum().r_CN_N).norm(), 1e-7);  // of 1e7 m
  EXPECT_LT(simtest::rel_err(f.energy_momentum().H_C_N, b.energy_momentum().H_C_N), 1e-12);
}

// ------------------------------------- fully-coupled back-effect (planar case)

// Independent planar model: hub (m_h, I_h about its CoM) and a rotor (m_w,
// J_s about its CoM) pinned at hub-fixed point a, rotor CoM at distance d from
// the pin.  Newton-Euler with the pin force f as an unknown:
//   rotor  m_w a_w = f,          J_s phi''  = (-d e(phi)) x f + u
//   hub    m_h a_h = -f,         I_h psi''  = (R(psi) a) x (-f) - u
//   a_w = a_h + psi'' J R a - psi'^2 R a + d phi'' e'(phi) - d phi'^2 e(phi)
// q = (x, y, psi, phi, x', y', psi', phi').
struct Planar {
  double m_h, I_h, m_w, J_s, d, u;
  Eigen::Vector2d a;

  Eigen::Matrix<double, 8, 1> f(const Eigen::Matrix<double, 8, 1>& q) const
  {
    const double psi = q(2), phi = q(3), psi_d = q(6), phi_d = q(7);
    const Eigen::Vector2d Ra(std::cos(psi) * a.x() - std::sin(psi) * a.y(),
                             std::sin(psi) * a.x() + std::cos(psi) * a.y());
    const Eigen::Vector2d JRa(-Ra.y(), Ra.x());
    const Eigen::Vector2d e(std::cos(phi), std::sin(phi));
    const Eigen::Vector2d ep(-std::sin(phi), std::cos(phi));
    // unknowns z = (ax, ay, psi'', phi'', fx, fy)
    Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs;
    for (int r = 0; r < 2; ++r) {
      M(r, r) = m_w;
      M(r, 2) = m_w * JRa(r);
      M(r, 3) = m_w * d * ep(r);
      M(r, 4 + r) = -1.0;
      rhs(r) = m_w * (psi_d * psi_d * Ra(r) + d * phi_d * phi_d * e(r));
      M(3 + r, r) = m_h;
      M(3 + r, 4 + r) = 1.0;
      rhs(3 + r) = 0.0;
    }
    M(2, 3) = J_s;
    M(2, 4) = -d * e.y();
    M(2, 5) = d * e.x();
    rhs(2) = u;
    M(5, 2) = I_h;
    M(5, 4) = -Ra.y();
    M(5, 5) = Ra.x();
    rhs(5) = -u;
    const Eigen::Matrix<double, 6, 1> z = M.fullPivLu().solve(rhs);
    Eigen::Matrix<double, 8, 1> qd;
    qd << q.segment<4>(4), z.head<4>();
    return qd;
  }
};

class FullyCoupledBackEffect : public ::testing::TestWithParam<double> {};

TEST_P(FullyCoupledBackEffect, WheelSpeedMatchesIndependentPlanarModel)
{
  const double u = GetParam();  // motor torque [N*m]
  Planar pl{50.0, 2.0, 5.0, 0.05, 0.01, u, Eigen::Vector2d(0.5, 0.2)};
  const double omega0 = 0.2, Omega0 = 50.0;

  sim::SpacecraftParams p;
  p.hub.m_h = pl.m_h;
  p.hub.I_hBc_B = Vector3d(3.0, 3.5, pl.I_h).asDiagonal();
  sim::ReactionWheelParams w;
  w.model = WheelModel::FullyCoupled;
  w.gs_hat_nom_B = Vector3d::UnitZ();  // w2_0 = y, w3_0 = -x (§4.2)
  w.r_WB_B = Vector3d(pl.a.x(), pl.a.y(), 0.0);
  w.m_w = pl.m_w;
  w.J_s = pl.J_s;
  w.J_t = 0.03;  // out-of-plane inertias play no role in planar motion
  w.J_g = 0.02;
  w.U_s = pl.m_w * pl.d;
  w.Omega_0 = Omega0;
  p.wheels.push_back(w);
  sim::InitialConditions ic;  // system CoM at rest at the origin
  ic.omega_BN_B = Vector3d(0.0, 0.0, omega0);
  sim::Plant sc({p, {}}, ic);
  sim::WheelArray cmd{u};
  sc.latch_wheel_commands(cmd);

  // Same initial state for the planar model: rotor CoM direction w2 = e(psi + pi/2 + theta).
  const double m = pl.m_h + pl.m_w;
  const double phi0 = 0.5 * sim::kPi;
  const Eigen::Vector2d e0(std::cos(phi0), std::sin(phi0)), ep0(-std::sin(phi0), std::cos(phi0));
  const Eigen::Vector2d p_h = -(pl.m_w / m) * (pl.a + pl.d * e0);
  const Eigen::Vector2d v_h = -(pl.m_w / m) * (omega0 * Eigen::Vector2d(-pl.a.y(), pl.a.x()) +
                                                pl.d * (omega0 + Omega0) * ep0);
  Eigen::Matrix<double, 8, 1> q;
  q << p_h, 0.0, phi0, v_h, omega0, omega0 + Omega0;

  const double dt = 2e-4;
  double Om_min = 1e9, Om_max = -1e9, worst_Om = 0.0, worst_w = 0.0, worst_r = 0.0;
  for (int k = 1; k <= 2500; ++k) {  // 0.5 s, ~4 wheel revolutions
    const auto k1 = pl.f(q);
    const auto k2 = pl.f(q + 0.5 * dt * k1);
    const auto k3 = pl.f(q + 0.5 * dt * k2);
    const auto k4 = pl.f(q + dt * k3);
    q += dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    const double Om_ref = q(7) - q(6);
    Om_min = std::min(Om_min, sc.Omega(0));
    Om_max = std::max(Om_max, sc.Omega(0));
    worst_Om = std::max(worst_Om, std::abs(sc.Omega(0) - Om_ref));
    worst_w = std::max(worst_w, std::abs(sc.omega_BN_B().z() - q(6)));
    worst_r = std::max(worst_r, (sc.r_BN_N().head<2>() - q.head<2>()).norm());
  }
  EXPECT_LT(worst_Om, 1e-9 * Omega0);
  EXPECT_LT(worst_w, 1e-11);
  EXPECT_LT(worst_r, 1e-12);
  EXPECT_LT(sc.omega_BN_B().head<2>().norm(), 1e-12);  // stays planar
  // The back-effect: with no motor torque the wheel speed still oscillates,
  // driven by its own imbalance through the hub motion.
  if (u == 0.0) {
    EXPECT_GT(Om_max - Om_min, 1e-3);
  }
  // psi from the plant attitude (sigma = tan(psi/4) z, modulo shadow set)
  const double psi_sim = 4.0 * std::atan(sc.sigma_BN().z());
  EXPECT_NEAR(std::remainder(psi_sim - q(2), 2.0 * sim::kPi), 0.0, 1e-11);
}

INSTANTIATE_TEST_SUITE_P(MotorTorque, FullyCoupledBackEffect, ::testing::Values(0.0, 0.2),
                         [](const auto& info) { return info.param == 0.0 ? "Off" : "On"; });

// ------------------------------------------------------------------ mixed sets

TEST(WheelMixed, BalancedWheelThetaDoesNotChangeThePhysics)
{
  sim::SpacecraftParams p = pyramid_vehicle(WheelModel::FullyCoupled);
  p.wheels[0].model = WheelModel::Balanced;
  p.wheels[1].model = WheelModel::SimpleJitter;
  p.hub.I_hBc_B += p.wheels[0].J_s * p.wheels[0].gs_hat_nom_B * p.wheels[0].gs_hat_nom_B.transpose();
  sim::Plant a({p, {}}, simtest::leo_ic());
  sim::Plant b({p, {}}, simtest::leo_ic());
  sim::StateVector x = b.state();
  x(b.model().layout().theta(0)) = 1.234;  // balanced wheel: theta is output only
  b.set_state(x);
  for (int k = 0; k < 500; ++k) {
    a.step(simtest::ns(1e-3));
    b.step(simtest::ns(1e-3));
  }
  sim::StateVector xa = a.state(), xb = b.state();
  EXPECT_NEAR(xb(b.model().layout().theta(0)) - xa(a.model().layout().theta(0)), 1.234, 1e-13);
  xa(a.model().layout().theta(0)) = xb(b.model().layout().theta(0)) = 0.0;
  EXPECT_EQ(xa, xb);
  // the jitter wheels' angles do matter
  sim::Plant c({p, {}}, simtest::leo_ic());
  x = c.state();
  x(c.model().layout().theta(2)) = 1.234;
  c.set_state(x);
  for (int k = 0; k < 500; ++k) c.step(simtest::ns(1e-3));
  EXPECT_GT((c.omega_BN_B() - a.omega_BN_B()).norm(), 1e-10);
}

// ---------------------------------------------------------- config rejection

struct BadWheel {
  const char* why;
  void (*spoil)(sim::ReactionWheelParams&);
  const char* field;
  const char* value;
};

const BadWheel kBadWheels[] = {
    {"axis not unit", [](sim::ReactionWheelParams& w) { w.gs_hat_nom_B = Vector3d(1, 1, 0); },
     "wheels[1].gs_hat_nom_B", "[1, 1, 0]"},
    {"axis NaN", [](sim::ReactionWheelParams& w) { w.gs_hat_nom_B.y() = std::nan(""); },
     "wheels[1].gs_hat_nom_B", "nan"},
    {"misalignment inf",
     [](sim::ReactionWheelParams& w) { w.delta_mis_B.z() = std::numeric_limits<double>::infinity(); },
     "wheels[1].delta_mis_B", "inf"},
    {"zero spin inertia", [](sim::ReactionWheelParams& w) { w.J_s = 0.0; }, "wheels[1].J_s", "= 0"},
    {"negative J_t", [](sim::ReactionWheelParams& w) { w.J_t = -0.1; }, "wheels[1].J_t", "= -0.1"},
    {"zero J_g", [](sim::ReactionWheelParams& w) { w.J_g = 0.0; }, "wheels[1].J_g", "= 0"},
    {"negative U_s", [](sim::ReactionWheelParams& w) { w.U_s = -1e-6; }, "wheels[1].U_s", "= -9.9999"},
    {"negative U_d", [](sim::ReactionWheelParams& w) { w.U_d = -2e-7; }, "wheels[1].U_d", "= -1.9999"},
    {"FC rotor without mass", [](sim::ReactionWheelParams& w) { w.m_w = 0.0; }, "wheels[1].m_w", "= 0"},
    {"FC rotor inertia indefinite", [](sim::ReactionWheelParams& w) { w.U_d = 0.5; },
     "wheels[1].U_d", "= 0.5"},
    {"negative dead-band", [](sim::ReactionWheelParams& w) { w.u_min = -0.25; }, "wheels[1].u_min", "= -0.25"},
    {"NaN initial speed", [](sim::ReactionWheelParams& w) { w.Omega_0 = std::nan(""); },
     "wheels[1].Omega_0", "nan"},
    {"negative Coulomb", [](sim::ReactionWheelParams& w) { w.friction.tau_c = -0.5; },
     "wheels[1].friction.tau_c", "= -0.5"},
    {"negative viscous", [](sim::ReactionWheelParams& w) { w.friction.c_v = -0.5; },
     "wheels[1].friction.c_v", "= -0.5"},
    {"zero low-speed band", [](sim::ReactionWheelParams& w) { w.friction.omega_lc = 0.0; },
     "wheels[1].friction.omega_lc", "= 0"},
    {"breakaway below Coulomb",
     [](sim::ReactionWheelParams& w) {
       w.friction.beta_st = 0.5;
       w.friction.tau_c = 0.002;
       w.friction.tau_st = 0.001;
     },
     "wheels[1].friction.tau_st", "= 0.001"},
};

TEST(WheelConfig, InvalidWheelIsRejectedNamingFieldAndValue)
{
  sim::SpacecraftParams good = pyramid_vehicle(WheelModel::FullyCoupled);
  EXPECT_NO_THROW(sim::SpacecraftModel{good});
  for (const BadWheel& b : kBadWheels) {
    sim::SpacecraftParams p = good;
    b.spoil(p.wheels[1]);
    try {
      sim::SpacecraftModel m(p);
      ADD_FAILURE() << b.why << ": accepted";
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(b.field), std::string::npos) << b.why << ": " << msg;
      EXPECT_NE(msg.find(b.value), std::string::npos) << b.why << ": " << msg;
    }
  }
}

}  // namespace

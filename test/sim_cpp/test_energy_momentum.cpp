// Energy and momentum (docs/dynamics.md §8): conservation per wheel model,
// work done by the motors, friction dissipation, and the simple-jitter model's
// non-conservation accounted for exactly by its pseudo-external loads.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/attitude.h"
#include "sim/plant.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using sim::WheelModel;

sim::SpacecraftParams vehicle(WheelModel model)
{
  sim::SpacecraftParams p;
  p.hub = simtest::reference_hub();
  p.wheels = simtest::pyramid_wheels(model);
  p.mu = sim::kMuEarth;
  return p;
}

// Largest relative deviation of each quantity from its initial value over a run.
struct Drift {
  double H_C = 0.0, E_rot = 0.0, H_orb = 0.0, E_orb = 0.0;
};

void track(Drift& d, const sim::EnergyMomentum& e0, const sim::EnergyMomentum& e)
{
  d.H_C = std::max(d.H_C, (e.H_C_N - e0.H_C_N).norm() / e0.H_C_N.norm());
  d.E_rot = std::max(d.E_rot, std::abs(e.E_rot - e0.E_rot) / std::abs(e0.E_rot));
  d.H_orb = std::max(d.H_orb, (e.H_orb_N - e0.H_orb_N).norm() / e0.H_orb_N.norm());
  d.E_orb = std::max(d.E_orb, std::abs(e.E_orb - e0.E_orb) / std::abs(e0.E_orb));
}

struct ConservationCase {
  WheelModel model;
  double dt;     // [s]
  int steps;
  double tol;    // relative
};

class Conservation : public ::testing::TestWithParam<ConservationCase> {};

// Motor torque off, no friction, point-mass gravity at C: H_C, E_rot, H_orb
// and E_orb are constants of motion (§8 table).  Checked at every step.
TEST_P(Conservation, TorqueOffNoFriction)
{
  const ConservationCase c = GetParam();
  sim::Plant sc({vehicle(c.model), {}}, simtest::leo_ic());
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  Drift d;
  for (int k = 0; k < c.steps; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(c.dt)), sim::StepStatus::Ok);
    track(d, e0, sc.energy_momentum());
  }
  EXPECT_LT(d.H_C, c.tol);
  EXPECT_LT(d.E_rot, c.tol);
  EXPECT_LT(d.H_orb, c.tol);
  EXPECT_LT(d.E_orb, c.tol);
}

// Basilisk-style run: motor torques on for the first half, off for the second.
// H_C and the orbital quantities are conserved over the whole run (motor
// torque is internal); E_rot changes by exactly the motor work sum(u Omega)
// while the torque is on and is conserved after the cut.
TEST_P(Conservation, TorqueOnThenOff)
{
  const ConservationCase c = GetParam();
  sim::Plant sc({vehicle(c.model), {}}, simtest::leo_ic());
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  const sim::WheelArray cmd{0.05, -0.04, 0.03, -0.02};
  sc.latch_wheel_commands(cmd);
  const int half = c.steps / 2;  // even number of steps per half for Simpson
  ASSERT_EQ(half % 2, 0);
  auto power = [&sc, &cmd]() {
    double P = 0.0;
    for (int i = 0; i < 4; ++i) P += cmd[static_cast<size_t>(i)] * sc.Omega(i);
    return P;
  };
  Drift d;
  double work = power();  // Simpson weights 1,4,2,...,4,1 (times dt/3)
  for (int k = 1; k <= half; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(c.dt)), sim::StepStatus::Ok);
    track(d, e0, sc.energy_momentum());
    work += (k == half ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0)) * power();
  }
  work *= c.dt / 3.0;
  const sim::EnergyMomentum e_cut = sc.energy_momentum();
  const double dE = e_cut.E_rot - e0.E_rot;
  EXPECT_GT(std::abs(dE), 1e-4 * std::abs(e0.E_rot));  // the motors did real work
  EXPECT_NEAR(dE, work, 1e-9 * std::abs(dE));

  sc.latch_wheel_commands(sim::WheelArray{});
  Drift after;
  for (int k = 0; k < c.steps - half; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(c.dt)), sim::StepStatus::Ok);
    const sim::EnergyMomentum e = sc.energy_momentum();
    track(d, e0, e);
    track(after, e_cut, e);
  }
  EXPECT_LT(d.H_C, c.tol);
  EXPECT_LT(d.H_orb, c.tol);
  EXPECT_LT(d.E_orb, c.tol);
  EXPECT_LT(after.E_rot, c.tol);
}

// Friction (Coulomb + viscous + Stribeck) is internal: H_C is conserved and
// E_rot only decreases.
TEST_P(Conservation, FrictionDissipatesEnergyButKeepsMomentum)
{
  const ConservationCase c = GetParam();
  sim::SpacecraftParams p = vehicle(c.model);
  for (auto& w : p.wheels) {
    w.friction.tau_c = 5e-3;
    w.friction.c_v = 1e-4;
    w.friction.tau_st = 8e-3;
    w.friction.beta_st = 0.5;
  }
  sim::Plant sc({p, {}}, simtest::leo_ic());
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  Drift d;
  double E_prev = e0.E_rot;
  int increases = 0;
  for (int k = 0; k < c.steps; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(c.dt)), sim::StepStatus::Ok);
    const sim::EnergyMomentum e = sc.energy_momentum();
    track(d, e0, e);
    if (e.E_rot > E_prev) ++increases;
    E_prev = e.E_rot;
  }
  EXPECT_LT(d.H_C, c.tol);
  EXPECT_EQ(increases, 0);
  EXPECT_LT(sc.energy_momentum().E_rot, e0.E_rot * (1.0 - 1e-6));
}

INSTANTIATE_TEST_SUITE_P(
    Models, Conservation,
    // runs long enough for many wheel revolutions and a visible orbit arc:
    // 20 s balanced, 2 s (>= 20 revolutions of the 400 rpm wheel) fully coupled
    ::testing::Values(ConservationCase{WheelModel::Balanced, 1e-3, 20000, 1e-12},
                      ConservationCase{WheelModel::FullyCoupled, 1e-4, 20000, 1e-12},
                      // docs/dynamics.md §8: 1e-8 for fully coupled at the coarse step
                      ConservationCase{WheelModel::FullyCoupled, 1e-3, 2000, 1e-8}),
    [](const auto& info) {
      return std::string(sim::to_string(info.param.model)) +
             (info.param.dt < 5e-4 ? "_dt1e4" : "_dt1e3");
    });

// Wheels of different models in one spacecraft (issue 6): two balanced and
// two fully-coupled wheels, motors off, no friction: the constants of motion
// of §8 hold as for a single model.
TEST(Conservation, MixedBalancedAndFullyCoupledWheels)
{
  sim::SpacecraftParams p = vehicle(WheelModel::FullyCoupled);
  p.wheels[0].model = WheelModel::Balanced;
  p.wheels[2].model = WheelModel::Balanced;
  sim::Plant sc({p, {}}, simtest::leo_ic());
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  Drift d;
  for (int k = 0; k < 10000; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(1e-4)), sim::StepStatus::Ok);
    track(d, e0, sc.energy_momentum());
  }
  EXPECT_LT(d.H_C, 1e-12);
  EXPECT_LT(d.E_rot, 1e-12);
  EXPECT_LT(d.H_orb, 1e-12);
  EXPECT_LT(d.E_orb, 1e-12);
}

// A wheel stuck at its speed (WheelHealth::Stuck): the bearing torque that
// holds Omega' = 0 is internal, so H_C stays a constant of motion (1e-12 as
// the other cases), while the rotor's relative speed stays exactly what it
// was.  The other wheels coast (motors off); the vehicle tumbles, so a free
// rotor's Omega would move (Omega' = -g . omega' for a balanced wheel): by
// at least 1e-6 rad/s here.  Per model: balanced, fully coupled.
TEST(Conservation, StuckWheelKeepsItsSpeedAndTheMomentum)
{
  for (WheelModel model : {WheelModel::Balanced, WheelModel::FullyCoupled}) {
    sim::Plant sc({vehicle(model), {}}, simtest::leo_ic());
    sim::Plant free_sc({vehicle(model), {}}, simtest::leo_ic());
    sc.set_wheel_health(1, sim::WheelHealth::Stuck);
    EXPECT_EQ(sc.wheel_health(1), sim::WheelHealth::Stuck);
    const double Om1 = sc.Omega(1);
    const sim::EnergyMomentum e0 = sc.energy_momentum();
    Drift d;
    const double dt = model == WheelModel::Balanced ? 1e-3 : 1e-4;
    for (int k = 0; k < 10000; ++k) {
      ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
      ASSERT_EQ(free_sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
      ASSERT_EQ(sc.Omega(1), Om1) << k;
      track(d, e0, sc.energy_momentum());
    }
    EXPECT_LT(d.H_C, 1e-12) << sim::to_string(model);
    EXPECT_LT(d.H_orb, 1e-12) << sim::to_string(model);
    EXPECT_GT(std::abs(free_sc.Omega(1) - Om1), 1e-6) << sim::to_string(model);
    // freed again: the wheel equation is back (its speed moves from here)
    sc.set_wheel_health(1, sim::WheelHealth::Nominal);
    for (int k = 0; k < 1000; ++k) ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    EXPECT_NE(sc.Omega(1), Om1) << sim::to_string(model);
  }
}

// SimpleJitter with zero imbalance is exactly Balanced, so it conserves too.
TEST(Conservation, SimpleJitterWithoutImbalanceConserves)
{
  sim::SpacecraftParams p = vehicle(WheelModel::SimpleJitter);
  for (auto& w : p.wheels) w.U_s = w.U_d = 0.0;
  sim::Plant sc({p, {}}, simtest::leo_ic());
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  Drift d;
  for (int k = 0; k < 2000; ++k) {
    sc.step(simtest::ns(1e-3));
    track(d, e0, sc.energy_momentum());
  }
  EXPECT_LT(d.H_C, 1e-12);
  EXPECT_LT(d.E_rot, 1e-12);
}

// The simple model does NOT conserve momentum or energy (§4.7): its imbalance
// loads are pseudo-external.  The change of H_C,N must equal the time integral
// of their moment about C, and the change of E_rot the integral of their
// power omega . L_C -- i.e. the pseudo-loads are the only source of drift.
TEST(Conservation, SimpleJitterDoesNotConserveAndDriftEqualsPseudoLoads)
{
  const sim::SpacecraftParams p = vehicle(WheelModel::SimpleJitter);
  sim::Plant sc({p, {}}, simtest::leo_ic());
  const sim::SpacecraftModel& m = sc.model();
  const Vector3d c = p.hub.r_BcB_B;  // no FC wheels: C is fixed in B

  // moment of the pseudo-loads about C, N components, and their power
  auto loads = [&](Vector3d& L_C_N, double& power) {
    Vector3d L_C_B = Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      const auto& w = p.wheels[static_cast<size_t>(i)];
      const sim::WheelAxes ax = sim::wheel_axes(m.wheel_derived(i), sc.theta(i));
      const double Om2 = sc.Omega(i) * sc.Omega(i);
      const Vector3d F = w.U_s * Om2 * ax.w2_hat_B;
      L_C_B += (w.r_WB_B - c).cross(F) + w.U_d * Om2 * ax.w2_hat_B;
    }
    L_C_N = sim::dcm_BN_from_sigma(sc.sigma_BN()).transpose() * L_C_B;
    power = sc.omega_BN_B().dot(L_C_B);
  };

  const double dt = 2e-4;
  const int steps = 5000;  // 1 s
  const sim::EnergyMomentum e0 = sc.energy_momentum();
  Vector3d L;
  double P;
  loads(L, P);
  Vector3d dH = L;
  double dE = P;
  double max_dH = 0.0;
  for (int k = 1; k <= steps; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    loads(L, P);
    const double wgt = (k == steps ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0));
    dH += wgt * L;
    dE += wgt * P;
    max_dH = std::max(max_dH, (sc.energy_momentum().H_C_N - e0.H_C_N).norm());
  }
  dH *= dt / 3.0;
  dE *= dt / 3.0;
  const sim::EnergyMomentum e1 = sc.energy_momentum();
  // not conserved: far outside the 1e-12 bound that the other models meet
  EXPECT_GT(max_dH / e0.H_C_N.norm(), 1e-7);
  EXPECT_GT(std::abs(e1.E_rot - e0.E_rot) / e0.E_rot, 1e-9);
  EXPECT_GT((e1.H_orb_N - e0.H_orb_N).norm() / e0.H_orb_N.norm(), 1e-12);
  // ...and the drift is exactly the pseudo-loads' impulse and work
  EXPECT_LT((e1.H_C_N - e0.H_C_N - dH).norm(), 1e-6 * max_dH);
  EXPECT_NEAR(e1.E_rot - e0.E_rot, dE, 1e-6 * std::abs(dE));
}

// §8 formulas against hand calculation: hub with one balanced wheel.
// H_C = I_C w + J_s Omega g ; E = 1/2 w.I_C w + 1/2 J_s Omega^2 + J_s Omega (g.w)
TEST(EnergyMomentum, BalancedHandCalculation)
{
  sim::SpacecraftParams p;
  p.hub.m_h = 100.0;
  p.hub.I_hBc_B = Vector3d(10.0, 12.0, 8.0).asDiagonal();
  p.hub.r_BcB_B = Vector3d(1.0, 0.0, 0.0);
  sim::ReactionWheelParams w;
  w.gs_hat_nom_B = Vector3d::UnitZ();
  w.J_s = 0.5;
  w.Omega_0 = 4.0;
  p.wheels.push_back(w);
  sim::InitialConditions ic;
  ic.omega_BN_B = Vector3d(0.1, 0.2, 0.3);
  ic.v_CN_N = Vector3d(1.0, 0.0, 0.0);
  sim::Plant sc({p, {}}, ic);
  const sim::EnergyMomentum e = sc.energy_momentum();
  // H = (1, 2.4, 2.4) + (0, 0, 2) ; E = 0.5*(0.1+0.48+0.72) + 0.5*0.5*16 + 0.5*4*0.3
  EXPECT_LT((e.H_C_B - Vector3d(1.0, 2.4, 4.4)).norm(), 1e-14);
  EXPECT_NEAR(e.E_rot, 0.65 + 4.0 + 0.6, 1e-14);
  EXPECT_LT((e.v_CN_N - ic.v_CN_N).norm(), 1e-15);
  EXPECT_NEAR(e.E_orb, 0.5 * 100.0 * 1.0, 1e-13);  // mu = 0: kinetic only
}

// FC rotor with a static imbalance, hub at rest, wheel spinning about z at B:
// rotor CoM at d w2 moves with speed d Omega, so
//   E_rot = 1/2 J_s Omega^2 + 1/2 m_w (d Omega)^2 - 1/2 m_sc |c_dot|^2,
//   H_C   = (J_s Omega + m_w d^2 Omega) z - m_sc c x c_dot,  c = m_w d w2 / m_sc.
TEST(EnergyMomentum, FullyCoupledHandCalculation)
{
  sim::SpacecraftParams p;
  p.hub.m_h = 20.0;
  p.hub.I_hBc_B = Matrix3d::Identity();
  sim::ReactionWheelParams w;
  w.model = WheelModel::FullyCoupled;
  w.gs_hat_nom_B = Vector3d::UnitZ();
  w.m_w = 5.0;
  w.J_s = 0.1;
  w.U_s = 0.05;  // d = 0.01 m
  w.Omega_0 = 10.0;
  p.wheels.push_back(w);
  sim::SpacecraftModel model(p);
  sim::StateVector x(model.layout().size());
  x.setZero();
  x(model.layout().Omega(0)) = 10.0;
  const sim::EnergyMomentum e = model.energy_momentum(x, model.params().hub);
  const double d = 0.01, m = 25.0;
  const Vector3d w2 = Vector3d::UnitY();       // theta = 0
  const Vector3d c = 5.0 * d * w2 / m;           // (0, 0.002, 0)
  const Vector3d c_dot = 5.0 * d * 10.0 * -Vector3d::UnitX() / m;  // w3 = -x
  const double E = 0.5 * 0.1 * 100.0 + 0.5 * 5.0 * (d * 10.0) * (d * 10.0) - 0.5 * m * c_dot.squaredNorm();
  const Vector3d H = (0.1 * 10.0 + 5.0 * d * d * 10.0) * Vector3d::UnitZ() - m * c.cross(c_dot);
  EXPECT_NEAR(e.E_rot, E, 1e-15);
  EXPECT_LT((e.H_C_B - H).norm(), 1e-15);
  const sim::MassProps mp = model.mass_props(x, model.params().hub);
  EXPECT_LT((mp.c_B - c).norm(), 1e-17);
  EXPECT_LT((mp.c_prime_B - c_dot).norm(), 1e-16);
}

}  // namespace

// sim::Plant, the one run class (docs/dynamics.md "The plant"): state layout,
// device parameters changed between steps (wheel limits, friction, health;
// thruster health) with validation, the force/torque effector list, the §13
// accessors and the sensor-truth filler.
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/plant.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using sim::WheelModel;

constexpr int64_t kMs = 1'000'000;  // [ns]

// One Balanced wheel about z through the CoM (as test_reaction_wheel's
// SingleWheel): Omega' = u_tot I_zz / (J_s (I_zz - J_s)).
struct OneWheel {
  sim::SpacecraftParams sc;
  double I_zz = 8.0;
  double J_s = 0.05;
  double coupling() const { return I_zz / (J_s * (I_zz - J_s)); }
};

OneWheel one_wheel()
{
  OneWheel s;
  s.sc.hub.m_h = 100.0;
  s.sc.hub.I_hBc_B = Vector3d(10.0, 12.0, s.I_zz).asDiagonal();
  sim::ReactionWheelParams w;
  w.gs_hat_nom_B = Vector3d::UnitZ();
  w.J_s = s.J_s;
  w.Omega_0 = 20.0;
  w.u_max = 0.2;
  s.sc.wheels.push_back(w);
  return s;
}

sim::ThrusterParams axial_thruster(sim::ThrusterTransient m)
{
  sim::ThrusterParams t;
  t.r_TjB_B = Vector3d(0.0, 0.0, -1.5);
  t.t_hat_B = Vector3d::UnitZ();
  t.F_max = 10.0;
  t.Isp = 220.0;
  t.T_min = 0.0;
  t.transient = m;
  t.tank = -1;
  return t;
}

sim::PlantParams thruster_plant(sim::ThrusterTransient m)
{
  sim::PlantParams p;
  p.sc.hub.m_h = 500.0;
  p.sc.hub.I_hBc_B = Vector3d(100.0, 120.0, 80.0).asDiagonal();
  p.prop.thrusters = {axial_thruster(m)};
  p.prop.command.T_sat = std::numeric_limits<double>::infinity();
  return p;
}

sim::ThrusterArray req(double T)
{
  sim::ThrusterArray a{};
  a[0] = T;
  return a;
}

void expect_invalid(const std::function<void()>& f, const std::string& field)
{
  try {
    f();
    ADD_FAILURE() << "accepted bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------ layout

TEST(PlantLayout, OneStateVectorHubWheelsTanks)
{
  sim::PlantParams p;
  p.sc.hub = simtest::reference_hub();
  p.sc.hub.I_hBc_B += 0.5 * Matrix3d::Identity();
  p.sc.wheels = simtest::pyramid_wheels(WheelModel::Balanced);
  p.prop.tanks.resize(2);
  p.prop.tanks[0].m_p0 = 30.0;
  p.prop.tanks[1].m_p0 = 12.5;
  p.prop.thrusters = {axial_thruster(sim::ThrusterTransient::FirstOrder)};
  const sim::Plant plant(p, sim::InitialConditions{});
  const sim::StateLayout& L = plant.layout();
  EXPECT_EQ(L.size(), 12 + 2 * 4 + 2);  // kappa is not an integrated state
  EXPECT_EQ(L.Omega(0), 12);
  EXPECT_EQ(L.theta(0), 16);
  EXPECT_EQ(L.m_p(1), 21);
  EXPECT_EQ(plant.state()(L.m_p(1)), 12.5);
  EXPECT_EQ(plant.m_prop(0), 30.0);
  EXPECT_EQ(plant.num_effectors(), 1);  // the thruster set
  EXPECT_EQ(plant.t_ns(), 0);
  // A plant without thrusters or tanks is the hub-and-wheels spacecraft.
  sim::PlantParams q;
  q.sc = p.sc;
  EXPECT_EQ(sim::Plant(q, sim::InitialConditions{}).layout().size(), 20);
}

TEST(PlantLayout, CapacitiesAreEnforcedAtConstruction)
{
  sim::PlantParams p = thruster_plant(sim::ThrusterTransient::Instant);
  p.prop.thrusters.assign(sim::kMaxThrusters, axial_thruster(sim::ThrusterTransient::Instant));
  EXPECT_NO_THROW(sim::Plant(p, sim::InitialConditions{}));
  p.prop.thrusters.push_back(p.prop.thrusters[0]);
  expect_invalid([&] { sim::Plant(p, sim::InitialConditions{}); }, "thrusters.size()");
}

// ------------------------------------------------- wheel device parameters

// The latch from a message's own array: the first num_rw entries through the
// command pipeline (here the saturation at u_max, by hand), as the WheelArray
// form; a wheel Off latches 0.
TEST(PlantSetters, LatchFromAPlainArrayReadsTheRunsWheels)
{
  OneWheel s = one_wheel();
  s.sc.wheels[0].u_max = 0.1;
  sim::Plant plant({s.sc, {}}, sim::InitialConditions{});
  const double over[1] = {0.5};  // one entry: the plant has one wheel
  plant.latch_wheel_commands(over);
  EXPECT_EQ(plant.u_s(0), 0.1);
  const double under[1] = {-0.05};
  plant.latch_wheel_commands(under);
  EXPECT_EQ(plant.u_s(0), -0.05);
  sim::WheelArray cmd{};
  cmd[0] = 0.5;
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), 0.1);
  plant.set_wheel_health(0, sim::WheelHealth::Off);
  plant.latch_wheel_commands(under);
  EXPECT_EQ(plant.u_s(0), 0.0);
}

// A wheel set Off stops responding to commands (u_s = 0 at once and at every
// latch) and spins down under Coulomb friction at the analytic rate
// tau_c I_zz / (J_s (I_zz - J_s)) (friction still acts).
TEST(PlantSetters, WheelOffIgnoresCommandsAndSpinsDownUnderFriction)
{
  OneWheel s = one_wheel();
  s.sc.wheels[0].friction.tau_c = 1e-3;
  sim::Plant plant({s.sc, {}}, sim::InitialConditions{});
  sim::WheelArray cmd{};
  cmd[0] = 0.05;
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), 0.05);
  for (int k = 0; k < 100; ++k) ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  const double Om1 = plant.Omega(0);
  EXPECT_GT(Om1, 20.0);  // spun up

  plant.set_wheel_health(0, sim::WheelHealth::Off);
  EXPECT_EQ(plant.wheel_health(0), sim::WheelHealth::Off);
  EXPECT_EQ(plant.u_s(0), 0.0);  // at once
  const double rate = 1e-3 * s.coupling();
  for (int k = 1; k <= 500; ++k) {  // 5 s, re-commanded every step
    plant.latch_wheel_commands(cmd);
    EXPECT_EQ(plant.u_s(0), 0.0);
    ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
    ASSERT_NEAR(plant.Omega(0), Om1 - rate * k * 0.01, 1e-12 * Om1);
  }
  EXPECT_EQ(plant.tau_f(0), -1e-3);
  // Back to Nominal: the next latch applies the command again.
  plant.set_wheel_health(0, sim::WheelHealth::Nominal);
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), 0.05);
}

// A stuck balanced wheel turns with the hub: the vehicle is then a gyrostat
// with the constant rotor momentum h = J_s Omega g and the full inertia I
// (hub plus the rotor's J_s about g):  I omega' = -omega x (I omega + h).
// Integrated here by the test's own RK4 at the plant's step, the body rate
// agrees with the plant's to 1e-12 after 10 s; the gyrostat's 1/2 omega.I
// omega is conserved (omega . (omega x ...) = 0); commands are ignored.
TEST(PlantSetters, StuckWheelMakesTheVehicleAGyrostat)
{
  OneWheel s = one_wheel();
  s.sc.wheels[0].friction.tau_c = 1e-3;  // friction acts no more while held
  sim::InitialConditions ic;
  ic.omega_BN_B = Vector3d(0.05, -0.03, 0.02);
  sim::Plant plant({s.sc, {}}, ic);
  plant.set_wheel_health(0, sim::WheelHealth::Stuck);
  sim::WheelArray cmd{};
  cmd[0] = 0.05;
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), 0.0);
  const Matrix3d I = Vector3d(10.0, 12.0, s.I_zz).asDiagonal();  // hub I_hBc_B: it holds the rotor's J_s
  const Vector3d h = s.J_s * 20.0 * Vector3d::UnitZ();
  const auto f = [&](const Vector3d& w) -> Vector3d { return I.inverse() * (-w.cross(I * w + h)); };
  Vector3d w = ic.omega_BN_B;
  const double T0 = 0.5 * w.dot(I * w), dt = 0.01;
  for (int k = 0; k < 1000; ++k) {
    const Vector3d k1 = f(w), k2 = f(w + 0.5 * dt * k1), k3 = f(w + 0.5 * dt * k2), k4 = f(w + dt * k3);
    w += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  }
  EXPECT_EQ(plant.Omega(0), 20.0);
  EXPECT_LT((plant.omega_BN_B() - w).norm(), 1e-12);
  EXPECT_GT((w - ic.omega_BN_B).norm(), 1e-3);  // the gyrostat did move
  const Vector3d wp = plant.omega_BN_B();
  EXPECT_NEAR(0.5 * wp.dot(I * wp), T0, 1e-12 * T0);
}

// Lowering u_max keeps the held torque (zero-order hold) and clips the next latch.
TEST(PlantSetters, LoweringUMaxClipsTheNextLatch)
{
  OneWheel s = one_wheel();
  sim::Plant plant({s.sc, {}}, sim::InitialConditions{});
  sim::WheelArray cmd{};
  cmd[0] = 0.15;
  plant.latch_wheel_commands(cmd);
  ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  const sim::StateVector x_before = plant.state();
  plant.set_wheel_u_max(0, 0.04);
  EXPECT_EQ(plant.wheel_params(0).u_max, 0.04);
  EXPECT_EQ(plant.u_s(0), 0.15);        // held until the next latch
  EXPECT_EQ(plant.state(), x_before);   // state untouched
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), 0.04);
  cmd[0] = -1.0;
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), -0.04);
  // and the wheel accelerates at the clipped torque
  const double Om0 = plant.Omega(0);
  ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  EXPECT_NEAR(plant.Omega(0), Om0 - 0.04 * s.coupling() * 0.01, 1e-13 * Om0);
}

// Omega_max: a wheel at or above the new limit refuses torque that speeds it up.
TEST(PlantSetters, LoweringOmegaMaxStopsFurtherSpinUp)
{
  OneWheel s = one_wheel();  // Omega_0 = 20 rad/s
  sim::Plant plant({s.sc, {}}, sim::InitialConditions{});
  plant.set_wheel_Omega_max(0, 15.0);
  sim::WheelArray cmd{};
  cmd[0] = 0.1;
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), 0.0);
  cmd[0] = -0.1;  // slowing torque is always allowed (§4.3 step 4)
  plant.latch_wheel_commands(cmd);
  EXPECT_EQ(plant.u_s(0), -0.1);
}

// New friction parameters act from the next derivative evaluation; the state is kept.
TEST(PlantSetters, FrictionChangeActsAtOnceAndKeepsState)
{
  OneWheel s = one_wheel();
  sim::Plant plant({s.sc, {}}, sim::InitialConditions{});
  ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  EXPECT_EQ(plant.tau_f(0), 0.0);
  const sim::StateVector x = plant.state();
  sim::WheelFrictionParams f;
  f.c_v = 2e-3;
  plant.set_wheel_friction(0, f);
  EXPECT_EQ(plant.state(), x);
  EXPECT_NEAR(plant.tau_f(0), -2e-3 * plant.Omega(0), 1e-18);
  const double Om0 = plant.Omega(0);
  const double k_rate = 2e-3 * s.coupling();
  for (int k = 0; k < 100; ++k) ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  EXPECT_NEAR(plant.Omega(0), Om0 * std::exp(-k_rate * 1.0), 1e-10 * Om0);
}

TEST(PlantSetters, InvalidValuesAreRejectedNamingTheField)
{
  OneWheel s = one_wheel();
  sim::PlantParams p;
  p.sc = s.sc;
  p.prop.thrusters = {axial_thruster(sim::ThrusterTransient::Instant)};
  sim::Plant plant(p, sim::InitialConditions{});
  const double inf = std::numeric_limits<double>::infinity();
  expect_invalid([&] { plant.set_wheel_u_max(0, std::nan("")); }, "wheels[0].u_max");
  expect_invalid([&] { plant.set_wheel_Omega_max(0, inf); }, "wheels[0].Omega_max");
  sim::WheelFrictionParams f;
  f.c_v = -1.0;
  expect_invalid([&] { plant.set_wheel_friction(0, f); }, "wheels[0].friction.c_v");
  f = {};
  f.omega_lc = 0.0;
  expect_invalid([&] { plant.set_wheel_friction(0, f); }, "wheels[0].friction.omega_lc");
  f = {};
  f.beta_st = 0.5;
  f.tau_c = 2e-3;
  f.tau_st = 1e-3;
  expect_invalid([&] { plant.set_wheel_friction(0, f); }, "wheels[0].friction.tau_st");
  expect_invalid([&] { plant.set_wheel_health(0, static_cast<sim::WheelHealth>(7)); }, "wheels[0].health");
  expect_invalid([&] { plant.set_wheel_u_max(1, 0.1); }, "wheel index");
  expect_invalid([&] { plant.set_thruster_health(0, static_cast<sim::ThrusterHealth>(9)); },
                 "thrusters[0].health");
  expect_invalid([&] { plant.set_thruster_health(3, sim::ThrusterHealth::FailedOff); }, "thruster index");
  // a rejected value leaves the old one in place
  EXPECT_EQ(plant.wheel_params(0).u_max, 0.2);
  EXPECT_EQ(plant.wheel_params(0).friction.c_v, 0.0);
}

// ----------------------------------------------- thruster device parameters

// FailedOff: no force, no impulse, no propellant; requests ignored; set while
// firing, the factor drops to 0 at once (no tail).
TEST(PlantSetters, ThrusterFailedOffProducesNoForceOrImpulse)
{
  for (auto m : {sim::ThrusterTransient::Instant, sim::ThrusterTransient::FirstOrder}) {
    sim::PlantParams p = thruster_plant(m);
    p.prop.thrusters[0].tank = 0;
    p.prop.tanks.resize(1);
    p.prop.tanks[0].m_p0 = 20.0;
    sim::Plant plant(p, sim::InitialConditions{});
    plant.command_thrusters(req(1.0));
    for (int k = 0; k < 20; ++k) ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
    ASSERT_GT(plant.kappa(0), 0.5);
    plant.set_thruster_health(0, sim::ThrusterHealth::FailedOff);
    EXPECT_EQ(plant.kappa(0), 0.0);
    EXPECT_FALSE(plant.valve_open(0));
    EXPECT_EQ(plant.thruster_effect(0).F_B, Vector3d::Zero());
    const Vector3d v = plant.v_BN_N();
    const double m_p = plant.m_prop(0);
    for (int k = 0; k < 100; ++k) {
      if (k % 10 == 0) plant.command_thrusters(req(0.05));
      ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
    }
    EXPECT_EQ(plant.v_BN_N(), v) << sim::to_string(m);
    EXPECT_EQ(plant.m_prop(0), m_p);
    EXPECT_EQ(plant.kappa(0), 0.0);
    EXPECT_EQ(plant.thruster_health(0), sim::ThrusterHealth::FailedOff);
  }
}

// StuckOn: the valve opens now and stays open whatever is commanded; an
// Instant thruster then delivers F_max per second.  Nominal again closes it.
TEST(PlantSetters, ThrusterStuckOnFiresUntilRestored)
{
  sim::Plant plant(thruster_plant(sim::ThrusterTransient::Instant), sim::InitialConditions{});
  for (int k = 0; k < 5; ++k) ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  plant.set_thruster_health(0, sim::ThrusterHealth::StuckOn);
  EXPECT_TRUE(plant.valve_open(0));
  for (int k = 0; k < 100; ++k) {
    if (k % 10 == 0) plant.command_thrusters(req(0.0));  // closing requests are ignored
    ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  }
  EXPECT_NEAR(500.0 * plant.v_BN_N().z(), 10.0 * 1.0, 1e-12 * 10.0);
  plant.set_thruster_health(0, sim::ThrusterHealth::Nominal);
  EXPECT_FALSE(plant.valve_open(0));
  for (int k = 0; k < 10; ++k) ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  EXPECT_NEAR(500.0 * plant.v_BN_N().z(), 10.0, 1e-12 * 10.0);
}

// ------------------------------------------------------- the effector list

// A test effector: a constant body torque and force (a stand-in for a
// magnetorquer), added without touching the thrusters.
class ConstantLoad final : public sim::ForceTorqueEffector {
 public:
  ConstantLoad(const Vector3d& F, const Vector3d& L) : F_(F), L_(L) {}
  const char* kind() const override { return "constant_load"; }
  void accumulate(const sim::EffectorStage&, sim::EffectorSums& sums) const override
  {
    sums.F_B += F_;
    sums.L_B += L_;
  }
  void state_io(sim::StateIO& io) override
  {
    io.value("constant_load.F", F_);
    io.value("constant_load.L", L_);
  }
  void set(const Vector3d& F, const Vector3d& L)
  {
    F_ = F;
    L_ = L;
  }

 private:
  Vector3d F_, L_;
};

TEST(PlantEffectors, AddedEffectorIsSummedLikeTheHeldExternalLoad)
{
  sim::PlantParams p;
  p.sc.hub = simtest::reference_hub();
  p.sc.hub.I_hBc_B += 0.5 * Matrix3d::Identity();
  p.sc.wheels = simtest::pyramid_wheels(WheelModel::Balanced);
  p.sc.mu = sim::kMuEarth;
  const Vector3d F(0.3, -0.1, 0.2), L(0.01, 0.02, -0.03);
  sim::Plant a(p, simtest::leo_ic());
  sim::Plant b(p, simtest::leo_ic());
  a.set_external(F, L);
  ConstantLoad& load = b.add_effector(std::make_unique<ConstantLoad>(F, L));
  EXPECT_EQ(b.num_effectors(), 2);
  for (int k = 0; k < 200; ++k) {
    ASSERT_EQ(a.step(10 * kMs), sim::StepStatus::Ok);
    ASSERT_EQ(b.step(10 * kMs), sim::StepStatus::Ok);
  }
  EXPECT_EQ(a.state(), b.state());  // 0 + F is F: bit for bit
  load.set(Vector3d::Zero(), Vector3d::Zero());
  a.set_external(Vector3d::Zero(), Vector3d::Zero());
  for (int k = 0; k < 50; ++k) {
    ASSERT_EQ(a.step(10 * kMs), sim::StepStatus::Ok);
    ASSERT_EQ(b.step(10 * kMs), sim::StepStatus::Ok);
  }
  EXPECT_EQ(a.state(), b.state());
  // capacity
  for (int k = b.num_effectors(); k < sim::kMaxEffectors; ++k)
    b.add_effector(std::make_unique<ConstantLoad>(Vector3d::Zero(), Vector3d::Zero()));
  expect_invalid([&] { b.add_effector(std::make_unique<ConstantLoad>(F, L)); }, "effectors.size()");
}

// ----------------------------------------------------------- §13 accessors

TEST(PlantAccessors, SensorTruthAndHeldInputsComeFromThePlant)
{
  sim::PlantParams p;
  p.sc.hub = simtest::reference_hub();
  p.sc.hub.I_hBc_B += 0.5 * Matrix3d::Identity();
  p.sc.wheels = simtest::pyramid_wheels(WheelModel::Balanced);
  for (auto& w : p.sc.wheels) w.friction.tau_c = 1e-3;
  sim::Plant plant(p, simtest::leo_ic());
  const sim::WheelArray cmd{0.01, -0.02, 0.03, 0.5};
  plant.latch_wheel_commands(cmd);
  for (int k = 0; k < 7; ++k) ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
  const Vector3d r_sun(1.4e11, 2e10, -3e9);
  const sim::SensorTruth t = plant.sensor_truth(r_sun, 0.75);
  EXPECT_EQ(t.t_ns, 70 * kMs);
  EXPECT_EQ(t.sigma_BN, plant.sigma_BN());
  EXPECT_EQ(t.omega_BN_B, plant.omega_BN_B());
  EXPECT_EQ(t.r_BN_N, plant.r_BN_N());
  EXPECT_EQ(t.r_SunN_N, r_sun);
  EXPECT_EQ(t.f_illum, 0.75);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(t.Omega[static_cast<size_t>(i)], plant.Omega(i));
  EXPECT_EQ(t.Omega[4], 0.0);
  // held wheel torques after the §4.3 pipeline (wheel 3 clipped by u_max = 0 -> unlimited here)
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(plant.u_s(i), cmd[static_cast<size_t>(i)]);
    EXPECT_EQ(plant.held_inputs().wheels.u_s[static_cast<size_t>(i)], plant.u_s(i));
    EXPECT_EQ(plant.tau_f(i), -1e-3 * (plant.Omega(i) > 0.0 ? 1.0 : -1.0));
  }
  EXPECT_EQ(plant.steps_taken(), 7u);
  EXPECT_EQ(plant.mass_props().m_sc, 750.0);
  EXPECT_LT((plant.energy_momentum().r_CN_N - plant.r_BN_N() -
             sim::dcm_BN_from_sigma(plant.sigma_BN()).transpose() * plant.mass_props().c_B).norm(), 1e-6);
}

// The cos and sin of the rotor angles are formed once per state (the
// truth's mass centre and a step's first derivative share them): the mass
// centre and the derivative at the plant's state are those the model forms
// from a copy of it, bit for bit, after steps and after set_state.
TEST(PlantAccessors, SharedRotorAnglesGiveTheModelsOwnBits)
{
  sim::PlantParams p;
  p.sc.hub = simtest::reference_hub();
  p.sc.wheels = simtest::pyramid_wheels(WheelModel::FullyCoupled);
  sim::Plant plant(p, simtest::leo_ic());
  plant.latch_wheel_commands(sim::WheelArray{0.01, -0.02, 0.03, 0.05});
  const auto expect_model_bits = [&plant](const char* when) {
    SCOPED_TRACE(when);
    const sim::StateVector x = plant.state();  // a copy: the model forms its own cos and sin
    const sim::MassCentre own = plant.model().mass_centre(x, plant.hub_with_propellant(x));
    const sim::MassCentre shared = plant.mass_centre();
    EXPECT_EQ(shared.m_sc, own.m_sc);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(shared.c_B(i), own.c_B(i));
    const sim::StateVector d_own = plant.derivatives(0.0, x);
    const sim::StateVector d_shared = plant.derivatives(0.0, plant.state());
    ASSERT_EQ(d_own.size(), d_shared.size());
    for (Eigen::Index i = 0; i < d_own.size(); ++i) EXPECT_EQ(d_shared(i), d_own(i)) << "entry " << i;
  };
  expect_model_bits("at start");
  for (int k = 0; k < 5; ++k) {
    ASSERT_EQ(plant.step(10 * kMs), sim::StepStatus::Ok);
    expect_model_bits("after a step");
  }
  sim::StateVector x = plant.state();
  for (int i = 0; i < plant.num_rw(); ++i) x(plant.layout().theta(i)) += 0.5 * (i + 1);
  plant.set_state(x);  // the angles the shared values were of change
  expect_model_bits("after set_state");
}

}  // namespace

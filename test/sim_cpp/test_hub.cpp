// Rigid hub at point B (docs/dynamics.md §1-§3, §7): closed-form torque-free
// and constant-torque motion, circular orbit, hand-derived accelerations of
// the B-point formulation, C->B initial conditions and config rejection.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "kestrel_test_support.h"
#include "sim/attitude.h"
#include "sim/plant.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using simtest::dcm_angle;
using simtest::rot;

sim::SpacecraftParams hub_only(const Matrix3d& I, const Vector3d& r_BcB_B, double mu = 0.0)
{
  sim::SpacecraftParams p;
  p.hub.m_h = 500.0;
  p.hub.I_hBc_B = I;
  p.hub.r_BcB_B = r_BcB_B;
  p.mu = mu;
  return p;
}

// Axisymmetric torque-free body: [NB](t) = R(h_N, w_p t) [NB](0) R(e3, w_r t),
// w_p = |H|/I1, w_r = w3 (1 - I3/I1) (Euler-Poinsot closed form).  B is offset
// from the CoM so the general B-point path is exercised; the run passes
// several MRP switches.
TEST(Hub, TorqueFreeAxisymmetricMatchesClosedFormThroughMrpSwitches)
{
  const double I1 = 100.0, I3 = 60.0;
  const Matrix3d I = Vector3d(I1, I1, I3).asDiagonal();
  const Vector3d c(0.3, -0.2, 0.1);
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(10.0, -5.0, 2.0);
  ic.sigma_BN = Vector3d(0.2, -0.1, 0.3);
  ic.omega_BN_B = Vector3d(0.3, 0.1, 0.5);
  sim::Plant sc({hub_only(I, c), {}}, ic);

  const Matrix3d dcm_NB0 = sim::dcm_BN_from_sigma(ic.sigma_BN).transpose();
  const Vector3d H_N = dcm_NB0 * (I * ic.omega_BN_B);
  const double w_p = H_N.norm() / I1;
  const double w_r = ic.omega_BN_B.z() * (1.0 - I3 / I1);
  const Vector3d h_hat_N = H_N.normalized();

  const double dt = 0.005;
  const int steps = 8000;  // 40 s, ~3.5 revolutions about H
  double worst_att = 0.0, worst_rate = 0.0, worst_rC = 0.0;
  for (int k = 1; k <= steps; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    if (k % 100 != 0) continue;
    const double t = k * dt;
    const Matrix3d dcm_NB_true = rot(h_hat_N, w_p * t) * dcm_NB0 * rot(Vector3d::UnitZ(), w_r * t);
    const Matrix3d dcm_BN_sim = sim::dcm_BN_from_sigma(sc.sigma_BN());
    worst_att = std::max(worst_att, std::abs(dcm_angle(dcm_BN_sim * dcm_NB_true)));
    const Vector3d omega_true = dcm_NB_true.transpose() * (w_p * h_hat_N) + w_r * Vector3d::UnitZ();
    worst_rate = std::max(worst_rate, (sc.omega_BN_B() - omega_true).norm() / omega_true.norm());
    worst_rC = std::max(worst_rC, (sc.energy_momentum().r_CN_N - ic.r_CN_N).norm());
    EXPECT_LE(sc.sigma_BN().norm(), 1.0);
  }
  EXPECT_GE(sc.mrp_switch_count(), 3u);
  EXPECT_LT(worst_att, 1e-10);
  EXPECT_LT(worst_rate, 1e-10);
  EXPECT_LT(worst_rC, 1e-9);  // C stays put while B circles around it
}

// Constant torque about a principal axis from rest: omega = (L/I) t,
// angle = L t^2 / (2 I), sigma = tan(angle/4) z (mod shadow).  Past 180 deg.
TEST(Hub, ConstantPrincipalTorqueFromRest)
{
  const Matrix3d I = Vector3d(80.0, 90.0, 50.0).asDiagonal();
  sim::Plant sc({hub_only(I, Vector3d::Zero()), {}}, sim::InitialConditions{});
  const double L = 5.0;  // [N*m] about z
  sc.set_external(Vector3d::Zero(), Vector3d(0.0, 0.0, L));
  const double dt = 0.01;
  for (int k = 1; k <= 1000; ++k) {
    ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
    const double t = k * dt;
    const double angle = 0.5 * L / 50.0 * t * t;
    EXPECT_NEAR(sc.omega_BN_B().z(), L / 50.0 * t, 1e-13);
    const Matrix3d dcm_BN_true = rot(Vector3d::UnitZ(), angle).transpose();
    ASSERT_LT(std::abs(dcm_angle(sim::dcm_BN_from_sigma(sc.sigma_BN()) * dcm_BN_true.transpose())),
              1e-10) << "t = " << t;
  }
  EXPECT_EQ(sc.omega_BN_B().x(), 0.0);
  EXPECT_EQ(sc.omega_BN_B().y(), 0.0);
  EXPECT_EQ(sc.mrp_switch_count(), 1u);  // angle reaches 5 rad: one crossing of pi
}

// Circular orbit of C with a tumbling, offset hub: gravity acts at C only, so
// r_C(t) = R (cos nt, sin nt, 0) regardless of the attitude motion.
TEST(Hub, CircularOrbitOfMassCentre)
{
  const double mu = sim::kMuEarth;
  const double R = 7.0e6;
  const double n = std::sqrt(mu / (R * R * R));
  const Matrix3d I = (Matrix3d() << 120, 5, -3, 5, 100, 2, -3, 2, 80).finished();
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(R, 0.0, 0.0);
  ic.v_CN_N = Vector3d(0.0, n * R, 0.0);
  ic.omega_BN_B = Vector3d(0.02, -0.05, 0.03);
  sim::Plant sc({hub_only(I, Vector3d(0.4, 0.1, -0.3), mu), {}}, ic);
  const double dt = 0.25;
  const int steps = 2400;  // 600 s
  for (int k = 0; k < steps; ++k) ASSERT_EQ(sc.step(simtest::ns(dt)), sim::StepStatus::Ok);
  const double t = steps * dt;
  const Vector3d r_true(R * std::cos(n * t), R * std::sin(n * t), 0.0);
  EXPECT_LT((sc.energy_momentum().r_CN_N - r_true).norm(), 1e-6);  // [m] of 7e6 m
  EXPECT_GT((sc.r_BN_N() - r_true).norm(), 0.1);  // B really is a different point
}

// One derivative evaluation against the textbook equations written about C and
// moved to B by hand: I_C w' = L_B - c x F - w x I_C w ;
// r''_B = F/m + g - w' x c - w x (w x c).  Hub only, so I_C = I_hBc.
TEST(Hub, DerivativesMatchHandDerivedBPointEquations)
{
  kt::Rng rng(21);
  const Matrix3d I = (Matrix3d() << 120, 5, -3, 5, 100, 2, -3, 2, 80).finished();
  const Vector3d c(0.4, 0.1, -0.3);
  sim::SpacecraftModel model(hub_only(I, c, sim::kMuEarth));
  for (int k = 0; k < 20; ++k) {
    sim::InitialConditions ic;
    ic.r_CN_N = Vector3d(rng.uniform(6.8e6, 7.2e6), rng.uniform(-1e6, 1e6), rng.uniform(-1e6, 1e6));
    ic.sigma_BN = Vector3d(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5));
    ic.omega_BN_B = Vector3d(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2));
    const sim::StateVector x = model.initial_state(ic, model.params().hub);
    sim::ExternalLoads in;
    in.F_ext_B = Vector3d(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5));
    in.L_ext_B = Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    sim::Accelerations acc;
    const sim::StateVector xd = model.derivatives(0.0, x, sim::WheelInputs{}, in, model.params().hub, &acc);

    const double m = 500.0;
    const Vector3d& w = ic.omega_BN_B;
    const Matrix3d dcm_BN = simtest::dcm_BN_via_quaternion(ic.sigma_BN);
    const Vector3d g_B = dcm_BN * (-sim::kMuEarth / std::pow(ic.r_CN_N.norm(), 3) * ic.r_CN_N);
    const Vector3d w_dot = I.inverse() * (in.L_ext_B - c.cross(in.F_ext_B) - w.cross(I * w));
    const Vector3d r_ddot_B = in.F_ext_B / m + g_B - w_dot.cross(c) - w.cross(w.cross(c));
    EXPECT_LT((acc.omega_dot_BN_B - w_dot).norm(), 1e-14 * (1.0 + w_dot.norm()));
    EXPECT_LT((acc.r_ddot_BN_B - r_ddot_B).norm(), 1e-13 * r_ddot_B.norm());
    EXPECT_LT((xd.segment<3>(3) - dcm_BN.transpose() * r_ddot_B).norm(), 1e-13 * r_ddot_B.norm());
    EXPECT_EQ(xd.segment<3>(0), x.segment<3>(3));
  }
}

// §1: r_B = r_C - [NB] c and v_B = v_C - [NB](w x c); §8 gives C back.
TEST(Hub, InitialConditionsAreConvertedFromCToB)
{
  const Vector3d c(0.4, 0.1, -0.3);
  sim::SpacecraftModel model(hub_only(Matrix3d::Identity() * 10.0, c));
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(1.0, 2.0, 3.0);
  ic.v_CN_N = Vector3d(-0.1, 0.2, 0.05);
  ic.sigma_BN = Vector3d(0.0, 0.0, std::sqrt(2.0) - 1.0);  // +90 deg about z
  ic.omega_BN_B = Vector3d(0.0, 0.0, 0.5);
  const sim::StateVector x = model.initial_state(ic, model.params().hub);
  // [NB] c = rot_z(90) c = (-0.1, 0.4, -0.3); w x c = (-0.05, 0.2, 0) -> N: (-0.2, -0.05, 0)
  EXPECT_LT((x.segment<3>(0) - Vector3d(1.1, 1.6, 3.3)).norm(), 1e-15);
  EXPECT_LT((x.segment<3>(3) - Vector3d(0.1, 0.25, 0.05)).norm(), 1e-15);
  const sim::EnergyMomentum em = model.energy_momentum(x, model.params().hub);
  EXPECT_LT((em.r_CN_N - ic.r_CN_N).norm(), 1e-15);
  EXPECT_LT((em.v_CN_N - ic.v_CN_N).norm(), 1e-15);
}

// Mass properties of a hub alone: m, c = r_BcB, I_B = I_Bc + m [r~][r~]^T.
TEST(Hub, MassPropertiesParallelAxis)
{
  const Vector3d r(1.0, 2.0, 0.0);
  sim::SpacecraftModel model(hub_only(Vector3d(10.0, 20.0, 30.0).asDiagonal(), r));
  const sim::MassProps mp =
      model.mass_props(model.initial_state(sim::InitialConditions{}, model.params().hub), model.params().hub);
  EXPECT_EQ(mp.m_sc, 500.0);
  EXPECT_EQ(mp.c_B, r);
  EXPECT_EQ(mp.c_prime_B, Vector3d::Zero());
  Matrix3d I_B;  // by hand: m(|r|^2 I - r r^T) = 500 [[4,-2,0],[-2,1,0],[0,0,5]]
  I_B << 10 + 2000, -1000, 0, -1000, 20 + 500, 0, 0, 0, 30 + 2500;
  EXPECT_LT((mp.I_sc_B - I_B).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(mp.I_sc_prime_B, Matrix3d::Zero());
}

TEST(Hub, NonFiniteStateHaltsTheRun)
{
  sim::Plant sc({hub_only(Matrix3d::Identity(), Vector3d::Zero()), {}}, sim::InitialConditions{});
  sc.set_external(Vector3d::Zero(), Vector3d(std::nan(""), 0.0, 0.0));
  const sim::StateVector before = sc.state();
  EXPECT_EQ(sc.step(simtest::ns(0.1)), sim::StepStatus::NonFiniteState);
  EXPECT_EQ(sc.state(), before);  // not committed
  sc.set_external(Vector3d::Zero(), Vector3d::Zero());
  EXPECT_EQ(sc.step(simtest::ns(0.1)), sim::StepStatus::NonFiniteState);  // stays halted
  EXPECT_EQ(sc.steps_taken(), 0u);
}

// ----------------------------------------------------------- config rejection

struct BadHub {
  const char* why;
  void (*spoil)(sim::SpacecraftParams&);
  const char* field;
  const char* value;
};

sim::SpacecraftParams good_params()
{
  return hub_only(Vector3d(10.0, 20.0, 30.0).asDiagonal(), Vector3d::Zero());
}

const BadHub kBadHubs[] = {
    {"zero mass", [](sim::SpacecraftParams& p) { p.hub.m_h = 0.0; }, "hub.m_h", "= 0"},
    {"negative mass", [](sim::SpacecraftParams& p) { p.hub.m_h = -3.5; }, "hub.m_h", "= -3.5"},
    {"NaN mass", [](sim::SpacecraftParams& p) { p.hub.m_h = std::nan(""); }, "hub.m_h", "nan"},
    {"asymmetric inertia", [](sim::SpacecraftParams& p) { p.hub.I_hBc_B(0, 1) = 0.25; },
     "hub.I_hBc_B (max |I - I^T|)", "= 0.25"},
    {"indefinite inertia", [](sim::SpacecraftParams& p) { p.hub.I_hBc_B(2, 2) = -4.0; },
     "hub.I_hBc_B (min eigenvalue)", "= -4"},
    {"infinite CoM offset",
     [](sim::SpacecraftParams& p) { p.hub.r_BcB_B.x() = std::numeric_limits<double>::infinity(); },
     "hub.r_BcB_B", "inf"},
    {"negative mu", [](sim::SpacecraftParams& p) { p.mu = -1.0; }, "mu", "= -1"},
    {"too many wheels",
     [](sim::SpacecraftParams& p) {
       sim::ReactionWheelParams w;
       w.gs_hat_nom_B = Vector3d::UnitX();
       w.J_s = 0.01;
       p.wheels.assign(sim::kMaxWheels + 1, w);
     },
     "wheels.size()", "= 37"},  // kMaxWheels + 1
    {"hub inertia without the wheel spin inertia",
     [](sim::SpacecraftParams& p) {
       sim::ReactionWheelParams w;
       w.gs_hat_nom_B = Vector3d::UnitX();
       w.J_s = 12.0;  // more than the hub's 10 about x
       p.wheels.push_back(w);
     },
     "hub.I_hBc_B - sum(J_s gs gs^T) (min eigenvalue)", "= -2"},
};

TEST(Hub, InvalidConfigurationIsRejectedNamingFieldAndValue)
{
  EXPECT_NO_THROW(sim::SpacecraftModel{good_params()});
  for (const BadHub& b : kBadHubs) {
    sim::SpacecraftParams p = good_params();
    b.spoil(p);
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

// rk4_step (docs/dynamics.md §7.1): exactness on cubics, fourth-order
// convergence (error ratio ~16 when dt halves) on a scalar ODE with a known
// solution, on a torque-free rigid body against its closed form, and on the
// full plant with fully-coupled wheels against a fine-step reference.
#include <cmath>

#include <gtest/gtest.h>

#include "sim/attitude.h"
#include "sim/rk4.h"
#include "sim/plant.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Classic RK4 integrates x' = f(t) with Simpson's rule: exact for cubics.
TEST(Rk4, ExactForCubicQuadrature)
{
  const auto f = [](double t, double) { return 4.0 * t * t * t - 3.0 * t * t + 1.0; };
  const double x1 = sim::rk4_step(0.0, 0.5, 1.5, f);  // int_0.5^2 = [t^4 - t^3 + t]
  const double want = (16.0 - 8.0 + 2.0) - (0.0625 - 0.125 + 0.5);
  EXPECT_NEAR(x1, want, 1e-14);
}

// One step of y' = y from y = 1 is the Taylor polynomial of e^h to order 4.
TEST(Rk4, OneStepIsFourthOrderTaylor)
{
  const double h = 0.1;
  const double y = sim::rk4_step(1.0, 0.0, h, [](double, double x) { return x; });
  EXPECT_NEAR(y, 1.0 + h + h * h / 2 + h * h * h / 6 + h * h * h * h / 24, 1e-16);
}

double exp_error(double dt)
{
  double y = 1.0;
  const int n = static_cast<int>(std::lround(2.0 / dt));
  for (int k = 0; k < n; ++k) y = sim::rk4_step(y, k * dt, dt, [](double t, double x) { return -x * std::cos(t); });
  return std::abs(y - std::exp(-std::sin(2.0)));
}

TEST(Rk4, ConvergenceRatioScalar)
{
  const double e1 = exp_error(0.1), e2 = exp_error(0.05), e3 = exp_error(0.025);
  EXPECT_NEAR(e1 / e2, 16.0, 1.0);
  EXPECT_NEAR(e2 / e3, 16.0, 0.5);
}

// Torque-free axisymmetric hub against the Euler-Poinsot closed form (see
// test_hub): attitude error angle at t = 20 s for dt and dt/2.
double rigid_body_error(double dt)
{
  const double I1 = 100.0, I3 = 60.0;
  sim::SpacecraftParams p;
  p.hub.m_h = 10.0;
  p.hub.I_hBc_B = Vector3d(I1, I1, I3).asDiagonal();
  sim::InitialConditions ic;
  ic.sigma_BN = Vector3d(0.2, -0.1, 0.3);
  ic.omega_BN_B = Vector3d(0.3, 0.1, 0.5);
  sim::Plant sc({p, {}}, ic);
  const int n = static_cast<int>(std::lround(20.0 / dt));
  for (int k = 0; k < n; ++k) sc.step(simtest::ns(dt));
  const Matrix3d dcm_NB0 = sim::dcm_BN_from_sigma(ic.sigma_BN).transpose();
  const Vector3d H_N = dcm_NB0 * (p.hub.I_hBc_B * ic.omega_BN_B);
  const double t = n * dt;
  const Matrix3d dcm_NB = simtest::rot(H_N.normalized(), H_N.norm() / I1 * t) * dcm_NB0 *
                          simtest::rot(Vector3d::UnitZ(), ic.omega_BN_B.z() * (1 - I3 / I1) * t);
  return std::abs(simtest::dcm_angle(sim::dcm_BN_from_sigma(sc.sigma_BN()) * dcm_NB));
}

TEST(Rk4, ConvergenceRatioTorqueFreeRigidBody)
{
  const double e1 = rigid_body_error(0.2), e2 = rigid_body_error(0.1);
  EXPECT_GT(e2, 1e-11);  // well above round-off, so the ratio means something
  EXPECT_NEAR(e1 / e2, 16.0, 1.0);
}

// Full plant: hub + 4 fully-coupled wheels in LEO with motor torques, final
// state (attitude, rates, wheel speeds and angles) against a dt/16 reference.
// dt = 0.01 s turns the fastest wheel by 0.42 rad per step: still asymptotic.
sim::StateVector plant_run(double dt)
{
  sim::SpacecraftParams p;
  p.hub = simtest::reference_hub();
  p.wheels = simtest::pyramid_wheels(sim::WheelModel::FullyCoupled);
  p.mu = sim::kMuEarth;
  sim::Plant sc({p, {}}, simtest::leo_ic());
  sc.latch_wheel_commands(sim::WheelArray{0.05, -0.04, 0.03, -0.02});
  const int n = static_cast<int>(std::lround(0.4 / dt));
  for (int k = 0; k < n; ++k) sc.step(simtest::ns(dt));
  return sc.state();
}

TEST(Rk4, ConvergenceRatioFullyCoupledPlant)
{
  const sim::StateVector ref = plant_run(0.01 / 16);
  auto err = [&ref](const sim::StateVector& x) {
    return (x.segment(6, x.size() - 6) - ref.segment(6, ref.size() - 6)).norm();
  };
  const double e1 = err(plant_run(0.01)), e2 = err(plant_run(0.005));
  EXPECT_GT(e2, 1e-11);  // well above round-off (the reference error is ~e2/256)
  EXPECT_NEAR(e1 / e2, 16.0, 1.0);
}

}  // namespace

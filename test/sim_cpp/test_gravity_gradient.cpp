// Gravity-gradient torque (docs/environment.md): a hand calculation; the
// exact torque of point masses in inverse-square gravity (an independent
// model of the same body, summed in the test) at a general attitude; zero
// with the principal axes on the orbit frame; and the pitch libration
// period of a gravity-gradient-stable body in a circular orbit, integrated
// with the model's torque, against 2 pi / (n sqrt(3 (Ix - Iz) / Iy)) and
// against the exact pendulum period (complete elliptic integral).
#include <cmath>

#include <gtest/gtest.h>

#include "sim/gravity_gradient.h"
#include "sim/units.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kMu = 3.986004415e14;

TEST(GravityGradient, HandCalculation)
{
  // I = diag(10, 20, 30), R_B = R (1, 1, 0)/sqrt 2:
  // R x I R = R^2/2 (1,1,0) x (10,20,0) = (0, 0, 5 R^2)  ->  L = (0, 0, 15 mu / R^3).
  const double R = 7.0e6;
  const Vector3d L = sim::gravity_gradient_torque(kMu, R * Vector3d(1.0, 1.0, 0.0) / std::sqrt(2.0),
                                                  Vector3d(10.0, 20.0, 30.0).asDiagonal());
  const double expect = 15.0 * kMu / (R * R * R);
  EXPECT_NEAR(L.x(), 0.0, 1e-15 * expect);
  EXPECT_NEAR(L.y(), 0.0, 1e-15 * expect);
  EXPECT_NEAR(L.z(), expect, 1e-14 * expect);
  EXPECT_EQ(sim::gravity_gradient_torque(0.0, Vector3d(R, 0.0, 0.0), Matrix3d::Identity()), Vector3d::Zero());
}

// Six point masses in pairs at +-d_k along the axes of a principal frame P
// turned by C_BP: mass centre at the origin, I_P = diag(2 m (d2^2 + d3^2), ...).
// The exact torque is sum r_i x m g(R + r_i) with g the inverse-square law;
// the model is its first-order term, so they agree to O((d/R)^2) (pairs
// cancel the odd order): ~1e-13 here, far below the tolerance, which is set
// by the cancellation in the sum (1e-9 .. 5e-9 relative found; 2e-8 allowed).
TEST(GravityGradient, MatchesPointMassesAtAGeneralAttitude)
{
  const Matrix3d C_BP = simtest::rot(Vector3d(0.3, -0.5, 0.8).normalized(), 1.1);
  const double m = 5.0;
  const Vector3d d(1.0, 1.7, 0.6);  // [m]
  const Matrix3d I_P = Vector3d(2 * m * (d(1) * d(1) + d(2) * d(2)), 2 * m * (d(0) * d(0) + d(2) * d(2)),
                                2 * m * (d(0) * d(0) + d(1) * d(1))).asDiagonal();
  const Matrix3d I_B = C_BP * I_P * C_BP.transpose();
  for (const Vector3d& R_B : {Vector3d(6.9e6, 1.0e6, -2.0e6), Vector3d(-1.0e6, 4.2e7, 3.0e5),
                              Vector3d(3.0e6, -3.0e6, 5.5e6)}) {
    Vector3d L_exact = Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      for (double s : {-1.0, 1.0}) {
        const Vector3d r_i = C_BP.col(k) * (s * d(k));
        const Vector3d p = R_B + r_i;
        L_exact += r_i.cross(m * (-kMu / std::pow(p.norm(), 3)) * p);
      }
    }
    const Vector3d L = sim::gravity_gradient_torque(kMu, R_B, I_B);
    EXPECT_LT((L - L_exact).norm(), 2e-8 * L_exact.norm()) << R_B.transpose();
    EXPECT_GT(L_exact.norm(), 0.0);
  }
}

TEST(GravityGradient, ZeroWithPrincipalAxesOnTheOrbitFrame)
{
  // Body axes = LVLH (x along track, y opposite the orbit normal, z nadir):
  // R_B = (0, 0, -R) lies along a principal axis whatever the moments.
  const Matrix3d I = Vector3d(120.0, 95.0, 40.0).asDiagonal();
  EXPECT_EQ(sim::gravity_gradient_torque(kMu, Vector3d(0.0, 0.0, -7.0e6), I), Vector3d::Zero());
  // Also with a principal frame turned about z only (R still on a principal axis).
  const Matrix3d C = simtest::rot(Vector3d::UnitZ(), 0.7);
  const Vector3d L = sim::gravity_gradient_torque(kMu, Vector3d(0.0, 0.0, 7.0e6), C * I * C.transpose());
  EXPECT_LT(L.norm(), 1e-25);
}

// Complete elliptic integral of the first kind by the arithmetic-geometric mean.
double ellip_k(double k)
{
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 30; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return sim::kPi / (2.0 * a);
}

// Planar pitch motion about the orbit normal (a principal axis) in a circular
// orbit: the body's inertial rate is n + theta', n constant, so
// Iy theta'' = L_y(theta) exactly.  Body = LVLH turned by theta about y:
// R_B = R (sin theta, 0, -cos theta).  Theory: L_y = -3 n^2 (Ix - Iz) sin theta cos theta,
// small-angle frequency n sqrt(3 (Ix - Iz) / Iy) (sqrt 3 n for a rod, Iz -> 0).
// Returns the mean period over the crossings of theta = 0 (RK4, 2000 steps per period).
double libration_period(const Matrix3d& I, double theta0, double R)
{
  const double n = std::sqrt(kMu / (R * R * R));
  const double Iy = I(1, 1);
  const auto acc = [&](double th) {
    const Vector3d R_B = R * Vector3d(std::sin(th), 0.0, -std::cos(th));
    return sim::gravity_gradient_torque(kMu, R_B, I).y() / Iy;
  };
  const double T_guess = 2.0 * sim::kPi / (n * std::sqrt(3.0 * (I(0, 0) - I(2, 2)) / Iy));
  const double h = T_guess / 2000.0;
  double th = theta0, w = 0.0, t = 0.0;
  double first = -1.0, last = -1.0;
  int crossings = 0;
  while (crossings < 9) {
    const double k1t = w, k1w = acc(th);
    const double k2t = w + 0.5 * h * k1w, k2w = acc(th + 0.5 * h * k1t);
    const double k3t = w + 0.5 * h * k2w, k3w = acc(th + 0.5 * h * k2t);
    const double k4t = w + h * k3w, k4w = acc(th + h * k3t);
    const double th1 = th + h / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    const double w1 = w + h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    if ((th > 0.0) != (th1 > 0.0)) {  // linear interpolation of the zero crossing
      const double tc = t + h * th / (th - th1);
      if (first < 0.0) first = tc;
      last = tc;
      ++crossings;
    }
    th = th1;
    w = w1;
    t += h;
  }
  return (last - first) / 4.0;  // 9 crossings = 4 full periods
}

TEST(GravityGradient, PitchLibrationPeriodOfARod)
{
  // Rod along the local vertical: Ix = Iy = 100, Iz = 0 -> 2 pi / (sqrt 3 n).
  const double R = 7.0e6;
  const double n = std::sqrt(kMu / (R * R * R));
  const Matrix3d I = Vector3d(100.0, 100.0, 0.0).asDiagonal();
  const double T_theory = 2.0 * sim::kPi / (std::sqrt(3.0) * n);
  // 0.01 rad: the finite-amplitude lengthening is (2 theta0)^2 / 16 = 2.5e-5
  // (next term O(theta0^4) ~ 1e-9): within 5e-5 of theory, and within 1e-7 of
  // theory with the lengthening.
  const double ratio = libration_period(I, 0.01, R) / T_theory;
  EXPECT_NEAR(ratio, 1.0, 5e-5);
  EXPECT_NEAR(ratio, 1.0 + 0.02 * 0.02 / 16.0, 1e-7);
}

TEST(GravityGradient, PitchLibrationPeriodGeneralAndLargeAmplitude)
{
  const double R = 4.2164e7;  // geostationary radius
  const double n = std::sqrt(kMu / (R * R * R));
  const Matrix3d I = Vector3d(900.0, 1000.0, 300.0).asDiagonal();
  const double w0 = n * std::sqrt(3.0 * (900.0 - 300.0) / 1000.0);
  EXPECT_NEAR(libration_period(I, 0.005, R) / (2.0 * sim::kPi / w0), 1.0 + 0.01 * 0.01 / 16.0, 1e-7);
  // theta'' = -(w0^2 / 2) sin 2 theta: a pendulum in phi = 2 theta, amplitude
  // 2 theta0, period 4 K(sin theta0) / w0.
  const double theta0 = 0.6;
  const double T_exact = 4.0 * ellip_k(std::sin(theta0)) / w0;
  EXPECT_NEAR(libration_period(I, theta0, R) / T_exact, 1.0, 1e-6);
  EXPECT_GT(T_exact / (2.0 * sim::kPi / w0), 1.09);  // visibly longer than the small-angle period
}

}  // namespace

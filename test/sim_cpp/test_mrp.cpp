// MRP kinematics (docs/dynamics.md §7.4) against an independent route
// through Euler parameters, hand cases and finite differences.
#include <cmath>

#include <gtest/gtest.h>

#include "kestrel_test_support.h"
#include "sim/attitude.h"
#include "sim_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Vector3d random_vec(kt::Rng& rng, double lo, double hi)
{
  return Vector3d(rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi));
}

TEST(Mrp, NinetyDegreesAboutZHandCase)
{
  // B is N rotated +90 deg about z: sigma = tan(90deg/4) z = (sqrt(2) - 1) z.
  // Then x_N = -y_B... i.e. [BN] rows are N's basis seen in B: [[0,1,0],[-1,0,0],[0,0,1]].
  const Vector3d sigma(0.0, 0.0, std::sqrt(2.0) - 1.0);
  Matrix3d expect;
  expect << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  EXPECT_LT((sim::dcm_BN_from_sigma(sigma) - expect).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Mrp, DcmMatchesEulerParameterRouteAndIsOrthonormal)
{
  kt::Rng rng(7);
  for (int k = 0; k < 200; ++k) {
    const Vector3d s = random_vec(rng, -1.0, 1.0);
    const Matrix3d C = sim::dcm_BN_from_sigma(s);
    EXPECT_LT((C - simtest::dcm_BN_via_quaternion(s)).cwiseAbs().maxCoeff(), 2e-15);
    EXPECT_LT((C * C.transpose() - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 2e-15);
    EXPECT_NEAR(C.determinant(), 1.0, 2e-15);
  }
}

TEST(Mrp, ShadowSetIsTheSameAttitude)
{
  kt::Rng rng(11);
  for (int k = 0; k < 100; ++k) {
    const Vector3d s = random_vec(rng, -1.0, 1.0);
    const Vector3d ss = sim::mrp_shadow(s);
    EXPECT_NEAR(ss.norm() * s.norm(), 1.0, 1e-14);
    EXPECT_LT((sim::dcm_BN_from_sigma(ss) - sim::dcm_BN_from_sigma(s)).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(Mrp, KinematicsMatchDcmDifferentialEquation)
{
  // d/dt [BN] = -[omega~][BN]; compare a central difference along sigma_dot.
  kt::Rng rng(3);
  const double h = 1e-6;
  for (int k = 0; k < 50; ++k) {
    const Vector3d s = random_vec(rng, -0.8, 0.8);
    const Vector3d w = random_vec(rng, -1.0, 1.0);
    const Vector3d sd = sim::sigma_dot_from_omega(s, w);
    const Matrix3d dC = (simtest::dcm_BN_via_quaternion(s + h * sd) -
                         simtest::dcm_BN_via_quaternion(s - h * sd)) / (2.0 * h);
    const Matrix3d expect = -sim::skew(w) * simtest::dcm_BN_via_quaternion(s);
    EXPECT_LT((dC - expect).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(Mrp, RotationFromVectorIsRodrigues)
{
  kt::Rng rng(5);
  for (int k = 0; k < 50; ++k) {
    const Vector3d d = random_vec(rng, -2.0, 2.0);
    EXPECT_LT((sim::rotation_from_vector(d) - simtest::rot(d.normalized(), d.norm()))
                  .cwiseAbs().maxCoeff(), 1e-15);
  }
  EXPECT_EQ(sim::rotation_from_vector(Vector3d::Zero()), Matrix3d::Identity());
}

TEST(Mrp, SkewIsCrossProduct)
{
  const Vector3d a(1.0, -2.0, 3.0);
  const Vector3d b(0.5, 4.0, -1.0);
  EXPECT_EQ(sim::skew(a) * b, a.cross(b));
}

}  // namespace

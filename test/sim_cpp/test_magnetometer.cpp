// Magnetometer (docs/environment.md): ideal transfer = [SB] B; bias, scale
// factor and the magnetorquers' interference as the formula; quantisation and
// saturation; noise statistics against sigma; named, reproducible streams;
// sampling period.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sim/sensors.h"
#include "sim_test_util.h"
#include "field_check.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

const Vector3d kB(21000e-9, -4000e-9, 38000e-9);  // [T] a LEO-like field, B

sim::MagnetometerParams mag()
{
  sim::MagnetometerParams p;
  p.dcm_SB = simtest::rot(Vector3d(0.2, -0.4, 0.9).normalized(), 0.8);
  p.period_ns = 100'000'000;
  return p;
}

TEST(Magnetometer, IdealReadsTheRotatedField)
{
  sim::Magnetometer m(mag(), sim::SensorContext{1, true});
  ASSERT_TRUE(m.update(0, kB, sim::MagnetorquerArray{}));
  EXPECT_LT((m.output().B_S - mag().dcm_SB * kB).norm(), 1e-20);
  EXPECT_TRUE(m.output().valid);
  EXPECT_FALSE(m.output().saturated);
  // Off-period instants hold the last sample.
  EXPECT_FALSE(m.update(50'000'000, 2.0 * kB, sim::MagnetorquerArray{}));
  EXPECT_EQ(m.output().t_ns, 0);
  EXPECT_TRUE(m.update(100'000'000, 2.0 * kB, sim::MagnetorquerArray{}));
  EXPECT_LT((m.output().B_S - 2.0 * mag().dcm_SB * kB).norm(), 1e-20);
}

// b = (1 + e) .* [SB](B + D m) + bias, worked out component by component.
TEST(Magnetometer, BiasScaleAndInterference)
{
  sim::MagnetometerParams p = mag();
  p.dcm_SB = Matrix3d::Identity();
  p.bias = Vector3d(100e-9, -50e-9, 20e-9);
  p.scale_error = Vector3d(0.01, -0.02, 0.0);
  p.interference_B(0, 1) = 2e-8;  // rod 1 (of y): 20 nT per A m^2 on x
  p.interference_B(2, 0) = -1e-8;  // rod 0: -10 nT per A m^2 on z
  sim::Magnetometer m(p, sim::SensorContext{1, true});
  sim::MagnetorquerArray dip{};
  dip[0] = 5.0;
  dip[1] = -3.0;
  ASSERT_TRUE(m.update(0, kB, dip));
  const Vector3d want((21000e-9 + 2e-8 * -3.0) * 1.01 + 100e-9, -4000e-9 * 0.98 - 50e-9,
                      (38000e-9 - 1e-8 * 5.0) + 20e-9);
  EXPECT_LT((m.output().B_S - want).norm(), 1e-20);
  // Noise off: no bias, no scale error; interference stays (it is physics).
  sim::Magnetometer ideal(p, sim::SensorContext{1, false});
  ASSERT_TRUE(ideal.update(0, kB, dip));
  EXPECT_LT((ideal.output().B_S - Vector3d(21000e-9 - 6e-8, -4000e-9, 38000e-9 - 5e-8)).norm(), 1e-20);
}

TEST(Magnetometer, QuantisationAndSaturation)
{
  sim::MagnetometerParams p = mag();
  p.dcm_SB = Matrix3d::Identity();
  p.lsb = 13e-9;
  p.range = 30000e-9;
  sim::Magnetometer m(p, sim::SensorContext{1, false});
  ASSERT_TRUE(m.update(0, kB, sim::MagnetorquerArray{}));
  // 21000/13 = 1615.38 -> 1615 LSB; -4000/13 = -307.7 -> -307 LSB (towards zero); z clipped.
  EXPECT_NEAR(m.output().B_S.x(), 1615 * 13e-9, 1e-20);
  EXPECT_NEAR(m.output().B_S.y(), -307 * 13e-9, 1e-20);
  EXPECT_EQ(m.output().B_S.z(), 30000e-9);
  EXPECT_TRUE(m.output().saturated);
}

TEST(Magnetometer, NoiseHasItsSigmaAndStreamsAreNamed)
{
  sim::MagnetometerParams p = mag();
  p.sigma = 50e-9;
  p.bias = Vector3d(30e-9, 0.0, -30e-9);
  const int N = 20000;
  sim::Magnetometer m(p, sim::SensorContext{7, true});
  Vector3d sum = Vector3d::Zero(), sum2 = Vector3d::Zero();
  const Vector3d truth = p.dcm_SB * kB + p.bias;
  for (int k = 0; k < N; ++k) {
    ASSERT_TRUE(m.update(int64_t(k) * p.period_ns, kB, sim::MagnetorquerArray{}));
    const Vector3d e = m.output().B_S - truth;
    sum += e;
    sum2 += e.cwiseProduct(e);
  }
  const Vector3d mean = sum / N;
  const Vector3d sd = (sum2 / N - mean.cwiseProduct(mean)).cwiseSqrt();
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(mean(i)), 5.0 * 50e-9 / std::sqrt(double(N)));  // 5 sigma of the mean
    EXPECT_NEAR(sd(i) / 50e-9, 1.0, 0.03);  // sd of the sd ~ 1/sqrt(2N) = 0.5 %
  }
  // Same seed and name: same numbers; another name: others.
  sim::Magnetometer a(p, sim::SensorContext{7, true}), b(p, sim::SensorContext{7, true});
  p.name = "mag2";
  sim::Magnetometer c(p, sim::SensorContext{7, true});
  a.update(0, kB, {});
  b.update(0, kB, {});
  c.update(0, kB, {});
  EXPECT_EQ(a.output().B_S, b.output().B_S);
  EXPECT_NE(a.output().B_S, c.output().B_S);
  // A noise scale of 0 leaves bias only.
  a.set_noise_scale(0.0);
  a.update(p.period_ns, kB, {});
  EXPECT_LT((a.output().B_S - truth).norm(), 1e-20);
}

TEST(Magnetometer, RejectedFieldsAreNamed)
{
  const auto expect_field = [](const sim::MagnetometerParams& p, const char* field) {
    simtest::expect_rejects_field([&] { sim::Magnetometer(p, sim::SensorContext{}); }, field);
  };
  sim::MagnetometerParams p = mag();
  p.dcm_SB(0, 0) = 2.0;
  expect_field(p, "magnetometer(mag).dcm_SB");
  p = mag();
  p.sigma = -1.0;
  expect_field(p, "magnetometer(mag).sigma");
  p = mag();
  p.scale_error.y() = -1.0;
  expect_field(p, "magnetometer(mag).scale_error");
  p = mag();
  p.interference_B(1, 2) = NAN;
  expect_field(p, "magnetometer(mag).interference_B");
  p = mag();
  p.period_ns = 0;
  expect_field(p, "magnetometer(mag).period_ns");
  p = mag();
  p.range = -1.0;
  expect_field(p, "magnetometer(mag).range");
}

}  // namespace

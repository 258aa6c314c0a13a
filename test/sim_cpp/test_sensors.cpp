// Sensors (docs/dynamics.md §9): config rejection, the single noise-off
// switch giving exact truth (plus quantisation when configured), gyro
// white noise, angle and rate random walks growing as sqrt(t), bias/scale/
// quantisation/saturation, star-tracker cross/boresight noise and rate, CSS
// cosine/FOV/Kelly/distance/eclipse response and noise, tachometers, and
// per-sensor stream determinism.  Statistical checks use bounds computed
// from the sample count (stats_test_util.h, 4.5 standard errors).
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/attitude.h"
#include "sim/environment.h"
#include "sim/sensors.h"
#include "sim/units.h"
#include "sim_test_util.h"
#include "stats_test_util.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::Vector4d;

constexpr int64_t kMs = 1'000'000;
constexpr double kArcsec = sim::kPi / (180.0 * 3600.0);

sim::SensorTruth truth_at(int64_t t_ns)
{
  sim::SensorTruth t;
  t.t_ns = t_ns;
  t.sigma_BN = Vector3d(0.1, 0.2, -0.3);
  t.omega_BN_B = Vector3d(0.001, -0.01, 0.03);
  t.Omega[0] = 100.0;
  t.Omega[1] = -250.5;
  t.Omega[2] = 0.123456;
  return t;
}

void expect_rejects(const std::function<void()>& make, const std::string& field)
{
  try {
    make();
    ADD_FAILURE() << "accepted bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(SensorConfig, RejectsEachBadFieldByName)
{
  const sim::SensorContext ctx;
  expect_rejects([&] { sim::GyroParams p; p.period_ns = 0; sim::Gyro g(p, ctx); }, "gyro(gyro).period_ns");
  expect_rejects([&] { sim::GyroParams p; p.sigma_ARW = -1; sim::Gyro g(p, ctx); }, "gyro(gyro).sigma_ARW");
  expect_rejects([&] { sim::GyroParams p; p.dcm_PB(0, 1) = 0.1; sim::Gyro g(p, ctx); }, "gyro(gyro).dcm_PB");
  expect_rejects([&] { sim::GyroParams p; p.dcm_PB = -Matrix3d::Identity(); sim::Gyro g(p, ctx); }, "dcm_PB (det)");
  expect_rejects([&] { sim::GyroParams p; p.name = ""; sim::Gyro g(p, ctx); }, "gyro().name");
  expect_rejects([&] { sim::GyroParams p; p.scale_error.x() = -1.0; sim::Gyro g(p, ctx); }, "scale_error");
  expect_rejects([&] { sim::StarTrackerParams p; p.sigma_bore = NAN; sim::StarTracker s(p, ctx); }, "star_tracker(st).sigma_bore");
  expect_rejects([&] { sim::CssParams p; p.n_hat_B = Vector3d(1, 1, 0); sim::CoarseSunSensor c(p, ctx); }, "css(css).n_hat_B");
  expect_rejects([&] { sim::CssParams p; p.fov_half = 2.0; sim::CoarseSunSensor c(p, ctx); }, "css(css).fov_half");
  expect_rejects([&] { sim::CssParams p; p.y_max = -1.0; sim::CoarseSunSensor c(p, ctx); }, "css(css).y_max");
  expect_rejects([&] { sim::TachParams p; p.num_rw = sim::kMaxWheels + 1; sim::WheelTachometers w(p, ctx); }, "tach(tach).num_rw");
  expect_rejects([&] { sim::TachParams p; p.lsb = -1e-3; sim::WheelTachometers w(p, ctx); }, "tach(tach).lsb");
}

// --------------------------------------------------------------- noise off

TEST(SensorNoiseOff, OneSwitchGivesExactTruth)
{
  sim::SensorContext ctx;
  ctx.run_seed = 77;
  ctx.noise = false;
  sim::GyroParams gp;
  gp.sigma_ARW = 1e-5;
  gp.sigma_RRW = 1e-8;
  gp.b0 = Vector3d(1e-4, -2e-4, 3e-4);
  gp.scale_error = Vector3d(1e-3, 0.0, -1e-3);
  gp.dcm_PB = simtest::rot(Vector3d(1, 2, 3).normalized(), 0.7);
  sim::Gyro gyro(gp, ctx);
  sim::StarTrackerParams sp;
  sp.sigma_cross = 20 * kArcsec;
  sp.sigma_bore = 100 * kArcsec;
  sp.dcm_CB = simtest::rot(Vector3d::UnitX(), 0.5 * sim::kPi);
  sim::StarTracker st(sp, ctx);
  sim::CssParams cp;
  cp.n_hat_B = Vector3d(0.0, 0.707107, 0.707107).normalized();
  cp.sigma = 0.01;
  cp.bias = 0.02;
  cp.fov_half = sim::rad_from_deg(80.0);
  cp.period_ns = 250 * kMs;
  sim::CoarseSunSensor css(cp, ctx);
  sim::TachParams tp;
  tp.num_rw = 3;
  tp.sigma = 0.1;
  tp.period_ns = 250 * kMs;
  sim::WheelTachometers tach(tp, ctx);

  for (int k = 0; k < 20; ++k) {
    sim::SensorTruth t = truth_at(k * 250 * kMs);
    t.sigma_BN = Vector3d(0.1, 0.2, -0.3) * (1.0 + 0.1 * k);  // crosses |sigma| = 1
    t.omega_BN_B *= 1.0 + k;
    ASSERT_TRUE(gyro.update(t) && st.update(t) && css.update(t) && tach.update(t));
    EXPECT_EQ(gyro.output().omega_PN_P, Vector3d(gp.dcm_PB * t.omega_BN_B));
    // Star tracker against the test-side quaternion route.
    const Matrix3d CN_true = sp.dcm_CB * simtest::dcm_BN_via_quaternion(t.sigma_BN);
    const Matrix3d CN_meas = simtest::dcm_BN_via_quaternion(st.output().sigma_CN);
    EXPECT_LT(simtest::dcm_angle(CN_meas * CN_true.transpose()), 1e-14);
    EXPECT_GE(st.output().q_CN(0), 0.0);
    EXPECT_LE(st.output().sigma_CN.norm(), 1.0);
    // CSS: scale * cosine (Sun at +x of N, 1 AU, full illumination).
    const Vector3d s_B = simtest::dcm_BN_via_quaternion(t.sigma_BN).col(0);
    const double c = cp.n_hat_B.dot(s_B);
    EXPECT_NEAR(css.output().y, c >= std::cos(cp.fov_half) ? c : 0.0, 1e-15);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(tach.output().Omega[static_cast<size_t>(i)], t.Omega[static_cast<size_t>(i)]);
  }
  EXPECT_EQ(gyro.bias_walk(), Vector3d::Zero());
}

TEST(SensorNoiseOff, QuantisationAndSaturationRemain)
{
  sim::SensorContext ctx;
  ctx.noise = false;
  sim::GyroParams gp;
  gp.sigma_ARW = 1e-3;
  gp.lsb = 1e-3;
  gp.omega_max = 5.0;
  sim::Gyro gyro(gp, ctx);
  sim::SensorTruth t = truth_at(0);
  t.omega_BN_B = Vector3d(10.0, -0.0123456, 0.0009);
  ASSERT_TRUE(gyro.update(t));
  // q(x) = sign(x) LSB floor(|x|/LSB): toward zero; then clip to +-5.
  EXPECT_EQ(gyro.output().omega_PN_P.x(), 5.0);
  EXPECT_DOUBLE_EQ(gyro.output().omega_PN_P.y(), -0.012);
  EXPECT_EQ(gyro.output().omega_PN_P.z(), 0.0);
  EXPECT_TRUE(gyro.output().saturated);
  sim::TachParams tp;
  tp.num_rw = 3;
  tp.lsb = 0.5;
  sim::WheelTachometers tach(tp, ctx);
  ASSERT_TRUE(tach.update(t));
  EXPECT_EQ(tach.output().Omega[0], 100.0);
  EXPECT_EQ(tach.output().Omega[1], -250.5);
  EXPECT_EQ(tach.output().Omega[2], 0.0);
}

// --------------------------------------------------------------------- gyro

TEST(Gyro, SamplesOnlyAtItsRateWithTimeTags)
{
  sim::GyroParams gp;
  gp.period_ns = 20 * kMs;
  sim::Gyro g(gp, sim::SensorContext{});
  EXPECT_TRUE(g.update(truth_at(0)));
  EXPECT_FALSE(g.update(truth_at(10 * kMs)));
  EXPECT_EQ(g.output().t_ns, 0);
  EXPECT_TRUE(g.update(truth_at(40 * kMs)));
  EXPECT_EQ(g.output().t_ns, 40 * kMs);
}

TEST(Gyro, ConstantBiasAndScaleFactorByHand)
{
  sim::GyroParams gp;
  gp.b0 = Vector3d(1e-4, -2e-4, 3e-4);
  gp.scale_error = Vector3d(1e-3, 0.0, -2e-3);
  sim::Gyro g(gp, sim::SensorContext{});
  ASSERT_TRUE(g.update(truth_at(0)));
  const Vector3d w(0.001, -0.01, 0.03);
  const Vector3d expect((w.x() + 1e-4) * 1.001, (w.y() - 2e-4), (w.z() + 3e-4) * 0.998);
  EXPECT_LT((g.output().omega_PN_P - expect).norm(), 1e-18);
}

// White rate noise sigma_ARW / sqrt(dt) per axis, zero mean, axes uncorrelated.
TEST(Gyro, AngleRandomWalkWhiteNoiseStatistics)
{
  sim::GyroParams gp;
  gp.sigma_ARW = 1e-5;  // S1
  gp.period_ns = 100 * kMs;
  sim::SensorContext ctx;
  ctx.run_seed = 11;
  sim::Gyro g(gp, ctx);
  const int n = 20000;
  const double sd = 1e-5 / std::sqrt(0.1);
  std::vector<double> e[3];
  double xy = 0.0;
  for (int k = 0; k < n; ++k) {
    sim::SensorTruth t = truth_at(k * 100 * kMs);
    ASSERT_TRUE(g.update(t));
    const Vector3d err = g.output().omega_PN_P - t.omega_BN_B;
    for (int i = 0; i < 3; ++i) e[i].push_back(err(i));
    xy += err.x() * err.y();
  }
  for (int i = 0; i < 3; ++i) {
    const stats::Moments m = stats::moments(e[i]);
    EXPECT_TRUE(stats::mean_consistent(m.mean, 0.0, sd, n)) << i << " " << m.mean;
    EXPECT_TRUE(stats::variance_consistent(m.var, sd * sd, n)) << i << " " << m.var / (sd * sd);
  }
  EXPECT_LT(std::abs(xy / n), stats::kZ * sd * sd / std::sqrt(n));
}

// Integrated rate error (angle) over M seeded runs: Var = sigma_ARW^2 t, so
// the spread grows as sqrt(t).  With zero mean, sum(theta^2)/Var ~ chi2(M).
TEST(Gyro, IntegratedAngleGrowsAsSqrtTime)
{
  sim::GyroParams gp;
  gp.sigma_ARW = 1e-5;
  gp.period_ns = 100 * kMs;
  const int M = 400, K1 = 25, K2 = 400;  // 2.5 s and 40 s
  double ss1 = 0.0, ss2 = 0.0;
  for (int r = 0; r < M; ++r) {
    sim::SensorContext ctx;
    ctx.run_seed = 1000 + static_cast<uint64_t>(r);
    sim::Gyro g(gp, ctx);
    double theta = 0.0;
    for (int k = 0; k < K2; ++k) {
      sim::SensorTruth t = truth_at(k * 100 * kMs);
      g.update(t);
      theta += (g.output().omega_PN_P.x() - t.omega_BN_B.x()) * 0.1;
      if (k + 1 == K1) ss1 += theta * theta;
    }
    ss2 += theta * theta;
  }
  const double v1 = 1e-10 * K1 * 0.1, v2 = 1e-10 * K2 * 0.1;
  EXPECT_GT(ss1 / v1, stats::chi2_quantile(M, -stats::kZ));
  EXPECT_LT(ss1 / v1, stats::chi2_quantile(M, stats::kZ));
  EXPECT_GT(ss2 / v2, stats::chi2_quantile(M, -stats::kZ));
  EXPECT_LT(ss2 / v2, stats::chi2_quantile(M, stats::kZ));
}

// Bias random walk: b_k = sum of k steps sigma_RRW sqrt(dt) nu, so
// Var(b_k) = sigma_RRW^2 k dt (sqrt(t) growth of the spread).
TEST(Gyro, RateRandomWalkGrowsAsSqrtTime)
{
  sim::GyroParams gp;
  gp.sigma_RRW = 1e-8;  // S1
  gp.period_ns = 100 * kMs;
  const int M = 400, K1 = 100, K2 = 1600;
  double ss1[3] = {0, 0, 0}, ss2[3] = {0, 0, 0};
  for (int r = 0; r < M; ++r) {
    sim::SensorContext ctx;
    ctx.run_seed = 5000 + static_cast<uint64_t>(r);
    sim::Gyro g(gp, ctx);
    for (int k = 0; k <= K2; ++k) {
      sim::SensorTruth t = truth_at(k * 100 * kMs);
      g.update(t);  // sample k carries b_k
      const Vector3d b = g.output().omega_PN_P - t.omega_BN_B;
      for (int i = 0; i < 3; ++i) {
        if (k == K1) ss1[i] += b(i) * b(i);
        if (k == K2) ss2[i] += b(i) * b(i);
      }
    }
  }
  const double v1 = 1e-16 * K1 * 0.1, v2 = 1e-16 * K2 * 0.1;
  // Pooled over the three axes: 3M degrees of freedom.
  const double q1 = (ss1[0] + ss1[1] + ss1[2]) / v1, q2 = (ss2[0] + ss2[1] + ss2[2]) / v2;
  EXPECT_GT(q1, stats::chi2_quantile(3 * M, -stats::kZ)) << q1;
  EXPECT_LT(q1, stats::chi2_quantile(3 * M, stats::kZ)) << q1;
  EXPECT_GT(q2, stats::chi2_quantile(3 * M, -stats::kZ)) << q2;
  EXPECT_LT(q2, stats::chi2_quantile(3 * M, stats::kZ)) << q2;
}

TEST(Gyro, StreamDependsOnSeedAndNameOnly)
{
  sim::GyroParams gp;
  gp.sigma_ARW = 1e-5;
  sim::SensorContext ctx;
  ctx.run_seed = 3;
  sim::Gyro a(gp, ctx), b(gp, ctx);
  gp.name = "gyro2";
  sim::Gyro c(gp, ctx);
  int same_ac = 0;
  for (int k = 0; k < 100; ++k) {
    const sim::SensorTruth t = truth_at(k * 10 * kMs);
    a.update(t);
    b.update(t);
    c.update(t);
    EXPECT_EQ(a.output().omega_PN_P, b.output().omega_PN_P);
    same_ac += a.output().omega_PN_P == c.output().omega_PN_P;
  }
  EXPECT_EQ(same_ac, 0);
}

// ------------------------------------------------------------ star tracker

// Error rotation recovered through the test-side quaternion route:
// [CN]_meas [CN]^T = exp(-[delta~]); its axis-angle vector is -delta.
TEST(StarTracker, CrossAndBoresightNoiseStatistics)
{
  sim::StarTrackerParams sp;
  sp.sigma_cross = 20 * kArcsec;  // S1
  sp.sigma_bore = 100 * kArcsec;
  sp.dcm_CB = simtest::rot(Vector3d(0.3, -0.5, 0.8).normalized(), 1.1);
  sim::SensorContext ctx;
  ctx.run_seed = 21;
  sim::StarTracker st(sp, ctx);
  const int n = 8000;
  std::vector<double> d[3];
  const sim::SensorTruth base = truth_at(0);
  const Matrix3d CN_true = sp.dcm_CB * simtest::dcm_BN_via_quaternion(base.sigma_BN);
  for (int k = 0; k < n; ++k) {
    sim::SensorTruth t = base;
    t.t_ns = k * 250 * kMs;
    ASSERT_TRUE(st.update(t));
    const Matrix3d E = simtest::dcm_BN_via_quaternion(st.output().sigma_CN) * CN_true.transpose();
    const Vector3d v(E(2, 1) - E(1, 2), E(0, 2) - E(2, 0), E(1, 0) - E(0, 1));
    const double ang = simtest::dcm_angle(E);
    const Vector3d delta = -(ang / (0.5 * v.norm())) * 0.5 * v;  // axis * angle
    for (int i = 0; i < 3; ++i) d[i].push_back(delta(i));
  }
  const double sig[3] = {sp.sigma_cross, sp.sigma_cross, sp.sigma_bore};
  for (int i = 0; i < 3; ++i) {
    const stats::Moments m = stats::moments(d[i]);
    EXPECT_TRUE(stats::mean_consistent(m.mean, 0.0, sig[i], n)) << i;
    EXPECT_TRUE(stats::variance_consistent(m.var, sig[i] * sig[i], n)) << i << " " << m.var / (sig[i] * sig[i]);
  }
}

TEST(StarTracker, UpdateRateQuaternionBranchAndSunExclusion)
{
  sim::StarTrackerParams sp;
  sp.sun_exclusion = sim::rad_from_deg(30.0);
  sim::StarTracker st(sp, sim::SensorContext{});
  int samples = 0;
  for (int k = 0; k <= 100; ++k) samples += st.update(truth_at(k * 10 * kMs));  // 0..1 s at 4 Hz
  EXPECT_EQ(samples, 5);
  EXPECT_EQ(st.output().t_ns, 1000 * kMs);
  // Near-180 deg attitudes: scalar part >= 0 and |sigma| <= 1.
  for (double ang : {3.1, 3.14159, -3.1}) {
    sim::SensorTruth t = truth_at(0);
    const Vector3d axis = Vector3d(0.2, -0.6, 0.77).normalized();
    t.sigma_BN = std::tan(ang / 4.0) * axis;
    ASSERT_TRUE(st.update(t));
    EXPECT_GE(st.output().q_CN(0), 0.0);
    EXPECT_LE(st.output().sigma_CN.norm(), 1.0 + 1e-15);
    EXPECT_NEAR(st.output().q_CN.norm(), 1.0, 1e-15);
  }
  // Case z (= body z) pointed 10 deg from the Sun (at N +x): invalid; 40 deg: valid.
  for (double off_deg : {10.0, 29.99, 30.01, 40.0}) {
    sim::SensorTruth t = truth_at(0);
    // [BN] = rotation taking N x to B z-ish: rotate body about y by -(90 - off) deg
    const Matrix3d dcm_NB = simtest::rot(Vector3d::UnitY(), sim::rad_from_deg(90.0 - off_deg));
    const Vector4d q = sim::quaternion_from_dcm(dcm_NB.transpose());
    t.sigma_BN = sim::sigma_from_quaternion(q);
    ASSERT_TRUE(st.update(t));
    EXPECT_EQ(st.output().valid, off_deg > 30.0) << off_deg;
  }
}

// ------------------------------------------------------- coarse sun sensor

sim::SensorTruth sun_at_angle_from_z(double theta)  // Sun direction in B: (sin, 0, cos)
{
  sim::SensorTruth t = truth_at(0);
  t.sigma_BN = Vector3d::Zero();
  t.r_SunN_N = sim::kAU * Vector3d(std::sin(theta), 0.0, std::cos(theta));
  return t;
}

TEST(CoarseSunSensor, CosineFovKellyDistanceEclipseAndLimits)
{
  sim::CssParams cp;
  cp.scale = 2.0;
  cp.fov_half = sim::rad_from_deg(80.0);
  cp.albedo = 0.01;
  sim::SensorContext ctx;
  ctx.noise = false;
  sim::CoarseSunSensor c(cp, ctx);
  c.update(sun_at_angle_from_z(sim::rad_from_deg(60.0)));
  EXPECT_NEAR(c.output().y, 2.0 * (0.5 + 0.01), 1e-15);
  c.update(sun_at_angle_from_z(sim::rad_from_deg(79.0)));
  EXPECT_NEAR(c.output().y, 2.0 * (std::cos(sim::rad_from_deg(79.0)) + 0.01), 1e-15);
  c.update(sun_at_angle_from_z(sim::rad_from_deg(81.0)));
  EXPECT_NEAR(c.output().y, 2.0 * 0.01, 1e-17);  // albedo added outside the FOV
  // Distance 2 AU and half illumination: factor 1/4 * 1/2.
  sim::SensorTruth t = sun_at_angle_from_z(0.0);
  t.r_BN_N = -sim::kAU * Vector3d::UnitZ();
  t.f_illum = 0.5;
  c.update(t);
  EXPECT_NEAR(c.output().y, 2.0 * (0.125 + 0.01), 1e-15);
  // Kelly factor: gamma (1 - exp(-gamma^2 / k)) with gamma = cos 70 deg, k = 0.1.
  cp.k_kelly = 0.1;
  cp.albedo = 0.0;
  cp.y_max = 0.5;
  sim::CoarseSunSensor ck(cp, ctx);
  const double g = std::cos(sim::rad_from_deg(70.0));
  ck.update(sun_at_angle_from_z(sim::rad_from_deg(70.0)));
  EXPECT_NEAR(ck.output().y, 2.0 * g * (1.0 - std::exp(-g * g / 0.1)), 1e-15);
  ck.update(sun_at_angle_from_z(0.0));
  EXPECT_EQ(ck.output().y, 0.5);  // upper limit
}

// The set's Sun geometry computed once per instant (SensorSuite::read_css)
// gives each sensor the reading, bit for bit, that it computes alone from
// the truth, noise draws included; and it is the geometry by hand.
TEST(CoarseSunSensor, SharedSunGeometryGivesTheSameReadings)
{
  sim::SensorContext ctx;
  ctx.run_seed = 99;
  std::vector<sim::CoarseSunSensor> alone, shared;
  for (int i = 0; i < 6; ++i) {
    sim::CssParams cp;
    cp.name = "css" + std::to_string(i);
    cp.n_hat_B = Vector3d(i % 3 == 0, i % 3 == 1, i % 3 == 2) * (i < 3 ? 1.0 : -1.0);
    cp.fov_half = sim::rad_from_deg(60.0 + 5.0 * i);
    cp.k_kelly = i % 2 ? 0.05 : 0.0;
    cp.sigma = 0.01;
    cp.y_max = 2.0;
    alone.emplace_back(cp, ctx);
    shared.emplace_back(cp, ctx);
  }
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    sim::SensorTruth t = truth_at(k * 100 * kMs);
    t.sigma_BN = Vector3d(u(g), u(g), u(g)) * 0.5;
    t.r_BN_N = 1e7 * Vector3d(u(g), u(g), u(g));
    t.f_illum = 0.5 * (1.0 + u(g));
    const sim::SunGeometry sun = sim::sun_geometry(t);
    const Vector3d d = t.r_SunN_N - t.r_BN_N;
    ASSERT_NEAR((sun.s_B - sim::dcm_BN_from_sigma(t.sigma_BN) * d / d.norm()).norm(), 0.0, 1e-15);
    ASSERT_NEAR(sun.flux, t.f_illum * (sim::kAU / d.norm()) * (sim::kAU / d.norm()), 1e-15);
    for (size_t i = 0; i < alone.size(); ++i) {
      ASSERT_EQ(alone[i].update(t), shared[i].update(t, sun));
      ASSERT_EQ(alone[i].output().y, shared[i].output().y) << k << " " << i;
      ASSERT_EQ(alone[i].output().gamma, shared[i].output().gamma) << k << " " << i;
    }
  }
}

TEST(CoarseSunSensor, NoiseAndBiasStatisticsAndIndependentStreams)
{
  sim::CssParams cp;
  cp.sigma = 0.01;
  cp.bias = 0.003;
  cp.scale = 2.0;
  sim::SensorContext ctx;
  ctx.run_seed = 8;
  cp.name = "css0";
  sim::CoarseSunSensor c0(cp, ctx);
  cp.name = "css1";
  sim::CoarseSunSensor c1(cp, ctx);
  const int n = 20000;
  const sim::SensorTruth t = sun_at_angle_from_z(sim::rad_from_deg(45.0));
  const double ideal = 2.0 * std::cos(sim::rad_from_deg(45.0));
  std::vector<double> e0, e1;
  double cross = 0.0;
  for (int k = 0; k < n; ++k) {
    sim::SensorTruth tk = t;
    tk.t_ns = k * 100 * kMs;
    c0.update(tk);
    c1.update(tk);
    e0.push_back(c0.output().y - ideal);
    e1.push_back(c1.output().y - ideal);
    cross += (e0.back() - 0.006) * (e1.back() - 0.006);
  }
  const double sd = 2.0 * 0.01;
  for (const auto* e : {&e0, &e1}) {
    const stats::Moments m = stats::moments(*e);
    EXPECT_TRUE(stats::mean_consistent(m.mean, 2.0 * 0.003, sd, n)) << m.mean;
    EXPECT_TRUE(stats::variance_consistent(m.var, sd * sd, n)) << m.var / (sd * sd);
  }
  EXPECT_LT(std::abs(cross / n), stats::kZ * sd * sd / std::sqrt(n));  // streams independent
}

// -------------------------------------------------------------- tachometer

TEST(WheelTachometers, NoiseStatisticsPerWheel)
{
  sim::TachParams tp;
  tp.num_rw = 4;
  tp.sigma = 0.05;
  sim::SensorContext ctx;
  ctx.run_seed = 31;
  sim::WheelTachometers tach(tp, ctx);
  const int n = 20000;
  std::vector<double> e[4];
  for (int k = 0; k < n; ++k) {
    sim::SensorTruth t = truth_at(k * 100 * kMs);
    t.Omega[3] = 600.0;
    ASSERT_TRUE(tach.update(t));
    for (int i = 0; i < 4; ++i) e[i].push_back(tach.output().Omega[static_cast<size_t>(i)] - t.Omega[static_cast<size_t>(i)]);
  }
  for (int i = 0; i < 4; ++i) {
    const stats::Moments m = stats::moments(e[i]);
    EXPECT_TRUE(stats::mean_consistent(m.mean, 0.0, 0.05, n)) << i;
    EXPECT_TRUE(stats::variance_consistent(m.var, 0.05 * 0.05, n)) << i;
  }
}

}  // namespace

// Noise scale (the fault event noise_scale): twins on the same seed and name
// draw the same normals, so a twin at scale k has k times the random error of
// the nominal one, sample by sample: gyro (ARW and the bias walk it drives,
// b0 = 0, no scale error or quantisation: e = b_k + sigma_ARW/sqrt(dt) eta,
// both linear in k), star tracker (rotation angle k |delta|), CSS (y - s(gamma
// + b) = s k sigma eta, inside the limits).  Scale 0 mid-run: the gyro error
// is then its frozen bias walk, constant.  Bad scales are refused by name.
TEST(SensorNoiseScale, TwinsDifferByTheScaleSampleBySample)
{
  sim::SensorContext ctx;
  ctx.run_seed = 5;
  sim::GyroParams gp;
  gp.sigma_ARW = 1e-5;
  gp.sigma_RRW = 1e-6;
  gp.period_ns = 100 * kMs;
  sim::Gyro g1(gp, ctx), g2(gp, ctx);
  g2.set_noise_scale(2.5);
  EXPECT_EQ(g2.noise_scale(), 2.5);
  Vector3d frozen = Vector3d::Zero();
  for (int k = 0; k < 400; ++k) {
    const sim::SensorTruth t = truth_at(k * 100 * kMs);
    ASSERT_TRUE(g1.update(t));
    ASSERT_TRUE(g2.update(t));
    const Vector3d e1 = g1.output().omega_PN_P - t.omega_BN_B, e2 = g2.output().omega_PN_P - t.omega_BN_B;
    if (k < 200) {
      EXPECT_LT((e2 - 2.5 * e1).norm(), 1e-9 * e1.norm() + 1e-18) << k;
      if (k == 199) g2.set_noise_scale(0.0);
    } else {
      if (k == 200) frozen = e2;  // b_ as left by the last scaled sample
      EXPECT_LT((e2 - frozen).norm(), 1e-15) << k;
    }
  }
  EXPECT_GT(frozen.norm(), 1e-7);  // the bias walk had moved: a constant, not zero

  sim::StarTrackerParams sp;
  sp.sigma_cross = 20 * kArcsec;
  sp.sigma_bore = 100 * kArcsec;
  sim::StarTracker s1(sp, ctx), s2(sp, ctx);
  s2.set_noise_scale(2.5);
  sim::CssParams cp;
  cp.sigma = 0.01;
  cp.bias = 0.003;
  cp.scale = 2.0;
  sim::CoarseSunSensor c1(cp, ctx), c2(cp, ctx);
  c2.set_noise_scale(2.5);
  const sim::SensorTruth base = sun_at_angle_from_z(sim::rad_from_deg(45.0));
  const Matrix3d CN_true = sp.dcm_CB * simtest::dcm_BN_via_quaternion(base.sigma_BN);
  const double gb = 2.0 * (std::cos(sim::rad_from_deg(45.0)) + 0.003);  // s (gamma + b)
  for (int k = 0; k < 100; ++k) {
    sim::SensorTruth t = base;
    t.t_ns = k * 1000 * kMs;
    ASSERT_TRUE(s1.update(t));
    ASSERT_TRUE(s2.update(t));
    const double a1 = simtest::dcm_angle(simtest::dcm_BN_via_quaternion(s1.output().sigma_CN) * CN_true.transpose());
    const double a2 = simtest::dcm_angle(simtest::dcm_BN_via_quaternion(s2.output().sigma_CN) * CN_true.transpose());
    EXPECT_NEAR(a2, 2.5 * a1, 1e-6 * a1 + 1e-12) << k;
    c1.update(t);
    c2.update(t);
    EXPECT_NEAR(c2.output().y - gb, 2.5 * (c1.output().y - gb), 1e-12) << k;
  }
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      c2.set_noise_scale(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("css.noise_scale"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(c2.noise_scale(), 2.5);

  // tachometers: per wheel; wheel 1 at scale 3, wheels 0 and 2 untouched
  // (bit for bit the nominal twin): Omega - truth = k sigma eta
  sim::TachParams tp;
  tp.num_rw = 3;
  tp.sigma = 0.01;
  tp.period_ns = 100 * kMs;
  sim::WheelTachometers w1(tp, ctx), w2(tp, ctx);
  w2.set_noise_scale(1, 3.0);
  EXPECT_EQ(w2.noise_scale(1), 3.0);
  EXPECT_EQ(w2.noise_scale(0), 1.0);
  for (int k = 0; k < 100; ++k) {
    sim::SensorTruth t = truth_at(k * 100 * kMs);
    for (size_t i = 0; i < 3; ++i) t.Omega[i] = 100.0 * static_cast<double>(i + 1);
    ASSERT_TRUE(w1.update(t));
    ASSERT_TRUE(w2.update(t));
    EXPECT_EQ(w2.output().Omega[0], w1.output().Omega[0]) << k;
    EXPECT_EQ(w2.output().Omega[2], w1.output().Omega[2]) << k;
    EXPECT_NEAR(w2.output().Omega[1] - 200.0, 3.0 * (w1.output().Omega[1] - 200.0), 1e-12) << k;
  }
  EXPECT_THROW(w2.set_noise_scale(3, 1.0), std::out_of_range);
  EXPECT_THROW(w2.set_noise_scale(0, -1.0), std::invalid_argument);
}

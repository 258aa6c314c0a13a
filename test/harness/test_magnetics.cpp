// Magnetorquers and the magnetometer in a run (scenario keys magnetorquers,
// magnetorquer_drive, sensors.magnetometer; events on devices magnetorquer and
// magnetometer; columns mtq_dipole_<i>, mtq_power_<i>, mag_B_S_*, mag_valid).
// Expected values: the field from sim's IGRF-14 evaluated here at the recorded
// position, time and attitude (the model's own accuracy is tested in
// test/sim_cpp/test_magnetic_field.cpp), the torque m x B, saturation,
// remanence, the interference matrix and the duty cycle formed here by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "harness/core/run.h"
#include "harness/scenario/scenario.h"
#include "rule_cases.h"
#include "scenario/mc_draw.h"
#include "sim/earth_context.h"
#include "sim/magnetic_field.h"

namespace {

const std::string kFile = std::string(KESTREL_SOURCE_DIR) + "/test/harness/data/leo_magnetics.yaml";

const Eigen::Vector3d kAxisA(0.6, 0.8, 0.0);  // mtq_a's axis (the file)
const Eigen::Vector3d kAxisZ(0.0, 0.0, 1.0);  // mtq_z's axis
const double kMaxA = 10.0, kRemA = 0.2, kPowA = 2.0;  // mtq_a: m_max [A*m^2], m_remanent, power_max [W]

// [BN] of an MRP (Schaub & Junkins, eq. 3.152), formed here.
Eigen::Matrix3d dcm_from_mrp(const Eigen::Vector3d& s)
{
  Eigen::Matrix3d t;
  t << 0.0, -s(2), s(1), s(2), 0.0, -s(0), -s(1), s(0), 0.0;
  const double ss = s.squaredNorm();
  return Eigen::Matrix3d::Identity() + (8.0 * t * t - 4.0 * (1.0 - ss) * t) / ((1.0 + ss) * (1.0 + ss));
}

// The magnetometer's dcm_SB of the file: turned 90 deg about z.
Eigen::Matrix3d sensor_from_body()
{
  Eigen::Matrix3d SB;
  SB << 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0;
  return SB;
}

// The geomagnetic field [T] in N at plant time t [s] and position r_N [m]
// for the file's epoch and degree 13.
struct Field {
  sim::EarthContext ctx{[] {
    sim::EarthContextParams p;
    p.epoch = {2027, 3, 21, 12, 0, 0.0};
    return p;
  }()};
  sim::Igrf14 igrf{ctx.decimal_year(), 13};
  Eigen::Vector3d N(double t, const Eigen::Vector3d& r_N) const
  {
    const Eigen::Matrix3d EN = ctx.dcm_EN(t);
    return EN.transpose() * igrf.field_E(EN * r_N);
  }
};

struct Rows {
  const harness::MemorySink& m;
  double at(const std::string& c, size_t k) const { return m.column(c)[k]; }
  Eigen::Vector3d v(const std::string& stem, size_t k) const { return {at(stem + "_x", k), at(stem + "_y", k), at(stem + "_z", k)}; }
  double t(size_t k) const { return at("t", k); }
  // The field in B at row k, from the recorded time, position and attitude.
  Eigen::Vector3d B_B(const Field& f, size_t k) const
  {
    return dcm_from_mrp(v("sigma_BN", k)) * f.N(t(k), v("r_BN_N", k));
  }
};

// Events as YAML for an override: {t, device, action[, value]} each.
struct Ev {
  double t;
  const char* device;
  const char* action;
  double value = std::numeric_limits<double>::quiet_NaN();
};
std::string events_yaml(const std::vector<Ev>& evs)
{
  std::string s = "[";
  for (const Ev& e : evs) {
    s += std::string(s.size() > 1 ? ", " : "") + "{t: " + std::to_string(e.t) + ", actions: [{device: " + e.device +
         ", action: " + e.action;
    if (!std::isnan(e.value)) s += ", value: " + std::to_string(e.value);
    s += "}]}";
  }
  return s + "]";
}

harness::Run& run_to_end(harness::Run& r)
{
  EXPECT_TRUE(r.step_ticks(r.total_ticks())) << r.failure();
  return r;
}

}  // namespace

// One rod commanded to 4 A*m^2, then to 25 (saturates at 10): the recorded
// dipole and power, and torque_magnetic = m a x B_B with B from IGRF-14 at the
// recorded state (no residual dipole, the other rod off: the torque is the rod's).
TEST(Magnetics, RodTorqueIsDipoleCrossFieldAndSaturates)
{
  const harness::Scenario sc =
      harness::load_scenario(kFile, {{"events", events_yaml({{0.0, "mtq_a", "dipole", 4.0}, {1.0, "mtq_a", "dipole", 25.0}})}});
  harness::Run run(sc);
  run_to_end(run);
  const Rows r{run.memory()};
  const Field f;
  ASSERT_EQ(r.m.rows(), 21u);
  // row k shows the rods as they acted over the step before t_k (before tick k's commands)
  EXPECT_EQ(r.at("mtq_dipole_0", 0), 0.0);
  double worst = 0.0;
  for (size_t k = 1; k < r.m.rows(); ++k) {
    const double m = r.t(k) <= 1.0 + 1e-9 ? 4.0 : kMaxA;
    EXPECT_EQ(r.at("mtq_dipole_0", k), m) << r.t(k);
    EXPECT_EQ(r.at("mtq_dipole_1", k), 0.0);
    EXPECT_NEAR(r.at("mtq_power_0", k), kPowA * (m / kMaxA) * (m / kMaxA), 1e-15) << r.t(k);
    const Eigen::Vector3d L = (m * kAxisA).cross(r.B_B(f, k));
    worst = std::max(worst, (r.v("torque_magnetic", k) - L).norm() / L.norm());
  }
  EXPECT_LT(worst, 1e-9);  // |L| ~ 1e-4 N*m
  std::printf("torque_magnetic vs m a x B: worst relative difference %.2e\n", worst);
}

// Fail off, stuck, scale and restore (docs/events.md, magnetorquer).
TEST(Magnetics, RodFaultsStuckScaleRestoreFailOff)
{
  const harness::Scenario sc = harness::load_scenario(
      kFile, {{"events", events_yaml({{0.0, "mtq_a", "dipole", 6.0},
                                      {0.5, "mtq_a", "stuck"},
                                      {0.7, "mtq_a", "dipole", -3.0},   // ignored while stuck
                                      {1.0, "mtq_a", "restore"},        // -3 acts from tick 1.0's command
                                      {1.3, "mtq_a", "scale", 0.5},     // -1.5 from tick 1.3's command
                                      {1.5, "mtq_a", "fail_off"}})}});  // at once: remanence, sign of -1.5
  harness::Run run(sc);
  run_to_end(run);
  const Rows r{run.memory()};
  const Field f;
  for (size_t k = 1; k < r.m.rows(); ++k) {
    const double t = r.t(k);
    const double m = t < 1.05 ? 6.0 : t < 1.35 ? -3.0 : t < 1.45 ? -1.5 : -kRemA;
    const double p = t < 1.45 ? kPowA * (m / kMaxA) * (m / kMaxA) : 0.0;
    EXPECT_EQ(r.at("mtq_dipole_0", k), m) << t;
    EXPECT_NEAR(r.at("mtq_power_0", k), p, 1e-15) << t;
    const Eigen::Vector3d L = (m * kAxisA).cross(r.B_B(f, k));
    EXPECT_LT((r.v("torque_magnetic", k) - L).norm(), 1e-9 * L.norm()) << t;
  }
}

// The magnetometer reads [SB] (B_B + D m): the field formed here, the
// interference matrix of the file times the commanded dipoles; sampled every
// 0.2 s and held in between.
TEST(Magnetics, MagnetometerReadsFieldPlusInterference)
{
  const harness::Scenario sc = harness::load_scenario(
      kFile, {{"events", events_yaml({{0.0, "mtq_a", "dipole", 4.0}, {0.0, "mtq_z", "dipole", -2.0}})}});
  harness::Run run(sc);
  run_to_end(run);
  const Rows r{run.memory()};
  const Field f;
  const Eigen::Matrix3d SB = sensor_from_body();
  Eigen::Matrix<double, 3, 2> D;
  D << 1.0e-6, 0.0, 0.0, 2.0e-6, 5.0e-7, -1.0e-6;
  double largest_interference = 0.0;
  for (size_t k = 0; k < r.m.rows(); k += 2) {  // the sample rows
    const Eigen::Vector2d m = k == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(4.0, -2.0);
    const Eigen::Vector3d b = SB * (r.B_B(f, k) + D * m);
    EXPECT_LT((r.v("mag_B_S", k) - b).norm(), 1e-15) << r.t(k);  // |b| ~ 3e-5 T
    EXPECT_EQ(r.at("mag_valid", k), 1.0);
    largest_interference = std::max(largest_interference, (D * m).norm());
    if (k + 1 < r.m.rows()) {
      EXPECT_EQ(r.v("mag_B_S", k + 1), r.v("mag_B_S", k));  // held
    }
  }
  EXPECT_GT(largest_interference, 5e-6);  // seen: 1/6 of the field
}

// sensors.magnetometer.field_period T = 1 s (samples every 0.2 s, rods off,
// 60 s of a 7000 km orbit): at t = j T the reading is the exact field (the
// model evaluated there); before the second evaluation it holds the first;
// after it, the field in N is B_j + s (B_j - B_(j-1)), s = (t - t_j) / T,
// formed here from the exact field at the two sample times.  Its error from
// the exact field: Taylor's theorem gives e = tau (tau + T) / 2 B'' (tau = t
// - t_j < T), so |e| <= T^2 max|B''|.  For the dipole on a circular orbit of
// rate w, B = B0 (3 (m.r) r - m) has harmonics 0, w and 2 w of the orbit
// angle, with |B''| <= 4 w^2 (3/2) B0 = 6 w^2 B0 <= 6 w^2 |B| (|B| >= B0);
// with the Earth turning the dipole, w -> w + w_E.  The bound taken: twice
// that, 12 (w + w_E)^2 T^2 |B| (the higher degrees, ~15 % of the field at
// 7000 km but with harmonics up to (n + 1) w).  The field held instead would
// be off by up to |B'| T ~ 2 w T |B|: far outside it (the check discriminates).
TEST(Magnetics, MagnetometerFieldPeriodExtrapolatesWithinTheBound)
{
  const double T = 1.0;
  const harness::Scenario sc = harness::load_scenario(
      kFile, {{"duration", "60.0"}, {"sensors.magnetometer.field_period", "1.0"}});
  harness::Run run(sc);
  run_to_end(run);
  const Rows r{run.memory()};
  const Field f;
  const Eigen::Matrix3d SB = sensor_from_body();
  const Eigen::Vector3d r0(7.0e6, 0.0, 0.0), v0(0.0, 5000.0, 5500.0);  // the file's initial orbit
  const double w = v0.norm() / r0.norm() + 7.292115e-5;                 // [rad/s] orbit rate + w_E
  const double bound = 12.0 * w * w * T * T;                             // [-] relative to |B|
  auto field_at = [&](size_t k) { return f.N(r.t(k), r.v("r_BN_N", k)); };
  double worst = 0.0, worst_held = 0.0;
  size_t j1 = 0, j0 = 0;  // rows of the last two field samples
  int n_fields = 0;
  for (size_t k = 0; k < r.m.rows(); k += 2) {  // the magnetometer's sample rows (0.2 s)
    const Eigen::Vector3d B_exact_N = field_at(k);
    const bool field_sample = std::fmod(r.t(k) + 1e-9, T) < 1e-6;
    Eigen::Vector3d B_N;
    if (field_sample) {
      j0 = j1;
      j1 = k;
      ++n_fields;
      B_N = B_exact_N;
    } else if (n_fields < 2) {
      B_N = field_at(j1);  // held
    } else {
      const double s = (r.t(k) - r.t(j1)) / (r.t(j1) - r.t(j0));
      B_N = field_at(j1) + s * (field_at(j1) - field_at(j0));
    }
    const Eigen::Matrix3d BN = dcm_from_mrp(r.v("sigma_BN", k));
    EXPECT_LT((r.v("mag_B_S", k) - SB * BN * B_N).norm(), 1e-16) << r.t(k);  // |b| ~ 3e-5 T
    if (n_fields >= 2) {
      const Eigen::Vector3d b = SB * BN * B_exact_N, m = r.v("mag_B_S", k);
      worst = std::max(worst, std::atan2(b.cross(m).norm(), b.dot(m)));
      const Eigen::Vector3d h = SB * BN * field_at(j1);
      worst_held = std::max(worst_held, std::atan2(b.cross(h).norm(), b.dot(h)));
    }
  }
  EXPECT_EQ(n_fields, 61);
  std::printf("field period 1 s: largest angle error %.3g rad, bound %.3g, held %.3g\n", worst, bound, worst_held);
  EXPECT_LT(worst, bound);
  EXPECT_GT(worst_held, 10.0 * bound);
}

// Dropout, frozen, restore and a bias step on the magnetometer.
TEST(Magnetics, MagnetometerDropoutFrozenBias)
{
  std::vector<Ev> evs{{0.4, "magnetometer", "dropout", 0.3},
                      {1.0, "magnetometer", "frozen"},
                      {1.4, "magnetometer", "restore"},
                      {1.4, "magnetometer", "bias_y", 2e-6}};
  const harness::Scenario sc = harness::load_scenario(kFile, {{"events", events_yaml(evs)}});
  harness::Run run(sc);
  run_to_end(run);
  const Rows r{run.memory()};
  const Field f;
  const Eigen::Matrix3d SB = sensor_from_body();
  auto ideal = [&](size_t k) { return Eigen::Vector3d(SB * r.B_B(f, k)); };
  for (size_t k = 4; k <= 7; ++k) {  // 0.4 .. 0.7 s: dropped (0.7: no sample since, the dropout held)
    EXPECT_EQ(r.at("mag_valid", k), 0.0) << r.t(k);
    EXPECT_TRUE(std::isnan(r.at("mag_B_S_x", k)));
  }
  EXPECT_EQ(r.at("mag_valid", 8), 1.0);
  EXPECT_LT((r.v("mag_B_S", 8) - ideal(8)).norm(), 1e-15);
  for (size_t k = 10; k <= 13; ++k) EXPECT_EQ(r.v("mag_B_S", k), r.v("mag_B_S", 8)) << r.t(k);  // frozen at 0.8's
  EXPECT_GT((ideal(12) - ideal(8)).norm(), 1e-11);  // the field moved meanwhile (1e-9 T per 0.4 s)
  for (size_t k = 14; k <= 20; k += 2)
    EXPECT_LT((r.v("mag_B_S", k) - ideal(k) - Eigen::Vector3d(0.0, 2e-6, 0.0)).norm(), 1e-15) << r.t(k);
}

// PWM: FSW period 1 s = the PWM period; 3.33 A*m^2 of 10 is a duty of 0.333,
// on for 0.333 s, which is not a whole number of 0.1 s steps.  The momentum
// change over the first cycle equals m_max a_N x (integral of B_N over the
// on-time) (Simpson's rule here); with the switch quantised to the step it
// would be off by 10 %.  Remanence 0: the average dipole is duty x m_max.
TEST(Magnetics, PwmAverageDipoleIsDutyTimesMax)
{
  const harness::Scenario sc =
      harness::load_scenario(kFile, {{"rates.fsw_divisor", "10"},
                                     {"magnetorquers[0].m_remanent", "0"},
                                     {"magnetorquer_drive", "{mode: pwm}"},
                                     {"events", events_yaml({{0.0, "mtq_a", "dipole", 3.33}})}});
  harness::Run run(sc);
  run_to_end(run);
  const Rows r{run.memory()};
  const Field f;
  const double on = 0.333;  // [s] duty x period
  // the attitude at t: the recorded MRPs interpolated linearly between rows
  // (the body turns by ~1e-3 rad over the on-time; the interpolation error is ~1e-8 rad)
  auto NB = [&r](double t) {
    const size_t k = static_cast<size_t>(t / 0.1);
    const double w = t / 0.1 - static_cast<double>(k);
    return Eigen::Matrix3d(dcm_from_mrp((1.0 - w) * r.v("sigma_BN", k) + w * r.v("sigma_BN", k + 1)).transpose());
  };
  const Eigen::Vector3d r0 = r.v("r_BN_N", 0), v0 = r.v("v_BN_N", 0);  // r(t) = r0 + v0 t within 0.5 m
  Eigen::Vector3d L_int = Eigen::Vector3d::Zero();  // integral of (m_max a_N) x B_N over the on-time
  const int n = 40;
  for (int i = 0; i <= n; ++i) {
    const double t = on * i / n, w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    L_int += w * (kMaxA * NB(t) * kAxisA).cross(f.N(t, r0 + v0 * t));
  }
  L_int *= on / (3.0 * n);
  const Eigen::Vector3d dH_expected = L_int;
  const Eigen::Vector3d dH = r.v("H_C_N", 10) - r.v("H_C_N", 0);
  EXPECT_LT((dH - dH_expected).norm(), 1e-5 * dH_expected.norm()) << dH.transpose() << " vs " << dH_expected.transpose();
  std::printf("PWM: |dH - expected| / |expected| = %.2e over the first cycle (|dH| = %.3e N*m*s)\n",
              (dH - dH_expected).norm() / dH_expected.norm(), dH_expected.norm());
  // the same as the average dipole over the period: |dH| / (P |a_N x B_mean|)
  const Eigen::Vector3d B_mid = f.N(0.5 * on, r0 + v0 * 0.5 * on);
  EXPECT_NEAR(dH.norm() / (1.0 * (NB(0.5 * on) * kAxisA).cross(B_mid).norm()), 3.33, 3.33 * 1e-3);
  // recorded at the ticks (the left limit): on at 0.1 .. 0.3 s, off from 0.4 s
  for (size_t k = 1; k <= 10; ++k) {
    EXPECT_EQ(r.at("mtq_dipole_0", k), k <= 3 ? kMaxA : 0.0) << r.t(k);
    EXPECT_EQ(r.at("mtq_power_0", k), k <= 3 ? kPowA : 0.0) << r.t(k);
  }
}

// Scenarios without the keys record no magnetic column; the keys round-trip
// through the manifest.
TEST(Magnetics, OffByDefaultAndManifestRoundTrip)
{
  const harness::Scenario s1 = harness::load_scenario(std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml",
                                                      {{"duration", "1"}});
  const std::string j1 = harness::scenario_to_json_text(s1);
  for (const char* k : {"magnetorquers", "magnetorquer_drive", "magnetometer"})
    EXPECT_EQ(j1.find(std::string("\"") + k + "\""), std::string::npos) << k;
  harness::Run run1(s1);
  run_to_end(run1);
  for (const auto& c : run1.memory().columns())
    EXPECT_TRUE(c.name.rfind("mtq_", 0) != 0 && c.name.rfind("mag_", 0) != 0) << c.name;

  const harness::Scenario a = harness::load_scenario(kFile, {{"magnetorquer_drive", "{mode: pwm, pwm_period: 0.05}"}});
  const std::string ja = harness::scenario_to_json_text(a);
  const harness::Scenario b = harness::load_scenario_text(ja, "m.json");
  EXPECT_EQ(harness::scenario_to_json_text(b), ja);
  ASSERT_EQ(b.magnetorquers.size(), 2u);
  EXPECT_EQ(b.magnetorquers[0].name, "mtq_a");
  EXPECT_EQ(b.magnetorquers[0].axis_B, kAxisA);
  EXPECT_EQ(b.magnetorquers[1].m_remanent, 0.1);
  EXPECT_EQ(b.magnetorquer_drive.mode, harness::MtqDriveMode::Pwm);
  EXPECT_EQ(b.magnetorquer_drive.pwm_period, 0.05);
  EXPECT_TRUE(b.sensors.magnetometer.enabled);
  EXPECT_EQ(b.sensors.magnetometer.dcm_SB(1, 0), -1.0);
  ASSERT_EQ(b.sensors.magnetometer.interference.cols(), 2);
  EXPECT_EQ(b.sensors.magnetometer.interference(2, 1), -1.0e-6);
}

// Cross-field rules, each named at its key.
TEST(Magnetics, RulesNameTheKey)
{
  const std::vector<testutil::RuleCase> cases{
      {{{"magnetorquers[0].axis", "[0.6, 0.80001, 0.0]"}}, "magnetorquers[0].axis", "within 1e-06"},
      {{{"magnetorquers[0].m_remanent", "10"}}, "magnetorquers[0].m_remanent", "< m_max"},
      {{{"magnetorquers[0].m_max", "0"}}, "magnetorquers[0].m_max", "> 0"},
      {{{"magnetorquers[1].name", "mtq_a"}}, "magnetorquers[1].name", "duplicate"},
      {{{"environment.magnetic.enabled", "false"}}, "magnetorquers", "environment.magnetic.enabled"},
      {{{"environment.magnetic.enabled", "false"}}, "sensors.magnetometer.enabled", "environment.magnetic.enabled"},
      {{{"sensors.magnetometer.interference", "[[1, 2, 3], [1, 2, 3], [1, 2, 3]]"}},
       "sensors.magnetometer.interference", "one column per magnetorquer (2)"},
      {{{"sensors.magnetometer.dcm_SB", "[[1, 0, 0], [0, 1, 0], [0, 0, -1]]"}}, "sensors.magnetometer.dcm_SB", "det"},
      {{{"sensors.magnetometer.dcm_SB", "[[1, 0.01, 0], [0, 1, 0], [0, 0, 1]]"}}, "sensors.magnetometer.dcm_SB",
       "orthonormal"},
      {{{"sensors.magnetometer.period", "0.15"}}, "sensors.magnetometer.period", "whole number of steps"},
      {{{"sensors.magnetometer.field_period", "0.3"}}, "sensors.magnetometer.field_period",
       "whole number of the magnetometer's sample period (0.2 s)"},
      {{{"sensors.magnetometer.field_period", "0.1"}}, "sensors.magnetometer.field_period", "whole number"},
      {{{"sensors.magnetometer.field_period", "-1"}}, "sensors.magnetometer.field_period", ">= 0"},
      {{{"sensors.magnetometer.scale_error", "[0, -1, 0]"}}, "sensors.magnetometer.scale_error", "> -1"},
      {{{"sensors.magnetometer.sigma", "-1e-9"}}, "sensors.magnetometer.sigma", ">= 0"},
      {{{"magnetorquer_drive", "{mode: pwm, pwm_period: 0.03}"}}, "magnetorquer_drive.pwm_period", "whole number"},
      {{{"events", "[{t: 0, actions: [{device: mtq_a, action: dipole}]}]"}}, "events[0].actions[0].action", "needs a finite value"},
      {{{"events", "[{t: 0, actions: [{device: magnetometer, action: bias}]}]"}}, "events[0].actions[0].action",
       "takes one of"},
  };
  testutil::expect_rules_named(kFile, cases);
}

// Monte Carlo: residual_dipole, the magnetometer's bias and the drag density
// scale are dispersible; each run's draws reach the run (its scenario, and
// the recorded torque and reading: bias = reading - [SB] B_B, torque =
// m_res x B_B with the rods off).
TEST(Magnetics, MonteCarloDispersesResidualDipoleAndMagnetometerBias)
{
  std::string text;
  {
    std::ifstream in(kFile);
    std::stringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  auto replace = [&text](const std::string& a, const std::string& b) {
    const size_t at = text.find(a);
    ASSERT_NE(at, std::string::npos) << a;
    text.replace(at, a.size(), b);
  };
  replace("duration: 2.0", "duration: 0.4");
  replace("igrf_degree: 13}\n", "igrf_degree: 13}\n  drag: {enabled: true}\n");  // drag on plate: density_scale applies
  replace("  com: [0.05, -0.02, 0.10]\n",
          "  com: [0.05, -0.02, 0.10]\n  facets:\n    - {area: 1.0, normal: [1.0, 0.0, 0.0], centre_of_pressure: [0.1, 0.0, 0.0]}\n");
  text += R"(monte_carlo:
  runs: 3
  seed: 5
  dispersions:
    - {key: spacecraft.residual_dipole, dist: normal_vector, std: [0.5, 0.5, 0.5]}
    - {key: sensors.magnetometer.bias, dist: normal_vector, std: [1.0e-6, 1.0e-6, 1.0e-6]}
    - {key: environment.drag.density_scale, dist: uniform, min: 0.5, max: 2.0}
)";
  const harness::Scenario nominal = harness::load_scenario_text(text, "mc_magnetics.yaml");
  const harness::McBinding bound = harness::bind_campaign(nominal);
  const Eigen::Matrix3d SB = sensor_from_body();
  const Field f;
  for (uint64_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    const harness::McDraw d = harness::draw_run(nominal, bound, 5, k);
    ASSERT_TRUE(d.invalid.empty()) << d.invalid;
    const Eigen::Vector3d m_res = d.sc.spacecraft.residual_dipole_B, bias = d.sc.sensors.magnetometer.bias;
    EXPECT_GT(m_res.norm(), 0.0);
    EXPECT_GT(bias.norm(), 0.0);
    EXPECT_GE(d.sc.environment.drag_density_scale, 0.5);
    EXPECT_LE(d.sc.environment.drag_density_scale, 2.0);
    ASSERT_EQ(d.drawn.size(), 7u);  // 3 + 3 + 1 columns
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(d.drawn[static_cast<size_t>(a)], m_res(a));
      EXPECT_EQ(d.drawn[static_cast<size_t>(3 + a)], bias(a));
    }
    EXPECT_EQ(d.drawn[6], d.sc.environment.drag_density_scale);
    harness::Run run(d.sc);
    run_to_end(run);
    const Rows r{run.memory()};
    const Eigen::Vector3d B = r.B_B(f, 0);
    EXPECT_LT((r.v("mag_B_S", 0) - SB * B - bias).norm(), 1e-15);
    const Eigen::Vector3d L = m_res.cross(B);
    EXPECT_LT((r.v("torque_magnetic", 0) - L).norm(), 1e-9 * L.norm());
  }
}

// noise_scale on the magnetometer: twin runs with sigma 1e-7 T, one scaled by
// 3 from 1.0 s: before, the readings are equal; after, its error (reading
// minus the ideal [SB] B_B) is 3 times the twin's, sample by sample.
TEST(Magnetics, MagnetometerNoiseScaleTwins)
{
  const std::vector<harness::Override> base{{"sensors.magnetometer.sigma", "1e-7"}};
  std::vector<harness::Override> scaled = base;
  scaled.push_back({"events", events_yaml({{1.0, "magnetometer", "noise_scale", 3.0}})});
  harness::Run a(harness::load_scenario(kFile, base)), b(harness::load_scenario(kFile, scaled));
  run_to_end(a);
  run_to_end(b);
  const Rows ra{a.memory()}, rb{b.memory()};
  const Field f;
  const Eigen::Matrix3d SB = sensor_from_body();
  for (size_t k = 0; k < ra.m.rows(); k += 2) {
    const Eigen::Vector3d ideal = SB * ra.B_B(f, k);
    const Eigen::Vector3d ea = ra.v("mag_B_S", k) - ideal, eb = rb.v("mag_B_S", k) - ideal;
    EXPECT_GT(ea.norm(), 1e-9) << ra.t(k);  // the noise is there (3 sigma ~ 1.7e-7 T)
    const double k_scale = ra.t(k) < 0.95 ? 1.0 : 3.0;
    EXPECT_LT((eb - k_scale * ea).norm(), 1e-15) << ra.t(k);
  }
}

// PWM and a stuck rod: stuck during the on-phase of the first cycle, the rod
// stays at +m_max (and its power) for the rest of the run.
TEST(Magnetics, PwmRodStuckHoldsItsLevel)
{
  const harness::Scenario sc = harness::load_scenario(
      kFile, {{"rates.fsw_divisor", "10"},
              {"magnetorquer_drive", "{mode: pwm}"},
              {"events", events_yaml({{0.0, "mtq_a", "dipole", 3.33}, {0.2, "mtq_a", "stuck"}})}});
  harness::Run run(sc);
  run_to_end(run);
  const Rows r{run.memory()};
  for (size_t k = 1; k < r.m.rows(); ++k) {
    EXPECT_EQ(r.at("mtq_dipole_0", k), kMaxA) << r.t(k);
    EXPECT_EQ(r.at("mtq_power_0", k), kPowA) << r.t(k);
  }
}

// trq_lpf: control-torque low-pass filter (docs/fsw/trq_lpf.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/trq_lpf.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

struct Fixture {
  FswTrqLpfConfig cfg{};
  FswTrqLpfState st{};
  FswTrqLpfIn in{};
  FswTrqLpfOut out{};
  Fixture(double h = 0.1, double wc = 2.0)
  {
    cfg.h = static_cast<fsw_real>(h);
    cfg.omega_c = static_cast<fsw_real>(wc);
    EXPECT_EQ(fsw_trq_lpf_init(&st, &cfg), FSW_OK);
  }
  FswStatus step(uint64_t t_ns, double x, double y, double z)
  {
    in.t_ns = t_ns;
    in.Lr_B[0] = static_cast<fsw_real>(x);
    in.Lr_B[1] = static_cast<fsw_real>(y);
    in.Lr_B[2] = static_cast<fsw_real>(z);
    return fsw_trq_lpf_update(&st, &cfg, &in, &out);
  }
};

constexpr uint64_t kH = 100000000u;  // 0.1 s in ns

}  // namespace

// Verifies: REQ-LPF-001
TEST(TrqLpfConfig, RejectsBadConfigurationsTableDriven)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const struct {
    const char* why;
    double h, wc;
  } rows[] = {
      {"h zero", 0.0, 1.0},          {"h negative", -0.1, 1.0},     {"h NaN", nan, 1.0},
      {"omega_c zero", 0.1, 0.0},    {"omega_c negative", 0.1, -2}, {"omega_c Inf", 0.1, INFINITY},
      {"omega_c h = pi", 0.1, 10 * 3.14159265358979323846}, {"omega_c h > pi", 1.0, 4.0},
  };
  for (const auto& r : rows) {
    FswTrqLpfConfig cfg{static_cast<fsw_real>(r.h), static_cast<fsw_real>(r.wc)};
    FswTrqLpfState st{};
    EXPECT_EQ(fsw_trq_lpf_check(&cfg), FSW_E_CONFIG) << r.why;
    EXPECT_EQ(fsw_trq_lpf_init(&st, &cfg), FSW_E_CONFIG) << r.why;
    FswTrqLpfIn in{};
    FswTrqLpfOut out{{1, 1, 1}};
    EXPECT_EQ(fsw_trq_lpf_update(&st, &cfg, &in, &out), FSW_E_NOT_INIT);
    for (int k = 0; k < 3; k++) EXPECT_EQ(out.LrF_B[k], 0.0);
  }
}

// h = 0.1 s, omega_c = 2 rad/s: hw = 2 tan(0.1), a0 = 2 + hw, a1 = 2 - hw.
// Call 1 (Lr_prev = Lr, LrF_prev = 0): LrF1 = 2 hw Lr / a0.
// Call 2 (same Lr): LrF2 = (2 hw Lr + a1 LrF1) / a0.
// Verifies: REQ-LPF-002
TEST(TrqLpfNominal, FirstTwoStepsByHand)
{
  Fixture f;
  const double hw = 2.0 * std::tan(0.1), a0 = 2.0 + hw, a1 = 2.0 - hw;
  ASSERT_EQ(f.step(0, 1.0, -2.0, 0.5), FSW_OK);  // first call at t = 0 is legal
  const double L[3] = {1.0, -2.0, 0.5};
  double F1[3];
  for (int k = 0; k < 3; k++) {
    F1[k] = 2 * hw * L[k] / a0;
    EXPECT_NEAR(f.out.LrF_B[k], F1[k], kt::tol(1e-15, 1e-6));
  }
  ASSERT_EQ(f.step(kH, 1.0, -2.0, 0.5), FSW_OK);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(f.out.LrF_B[k], (2 * hw * L[k] + a1 * F1[k]) / a0, kt::tol(1e-15, 1e-6));
}

// DC gain 1: a constant input is reached; the error decays by a1/a0 per step.
// Verifies: REQ-LPF-002
TEST(TrqLpfNominal, UnitDcGain)
{
  Fixture f;
  for (uint64_t k = 0; k < 400; k++) ASSERT_EQ(f.step(k * kH, 0.3, -0.2, 0.1), FSW_OK);
  EXPECT_NEAR(f.out.LrF_B[0], 0.3, kt::tol(1e-14, 1e-6));
  EXPECT_NEAR(f.out.LrF_B[1], -0.2, kt::tol(1e-14, 1e-6));
  EXPECT_NEAR(f.out.LrF_B[2], 0.1, kt::tol(1e-14, 1e-6));
}

// Pre-warped Tustin: the gain at omega_c is exactly 1/sqrt(2).  Drive a
// sinusoid at omega_c and compare the steady amplitude.
// Verifies: REQ-LPF-002
TEST(TrqLpfNominal, HalfPowerAtCutoff)
{
  Fixture f(0.01, 5.0);
  double amp = 0;
  for (uint64_t k = 0; k < 20000; k++) {
    ASSERT_EQ(f.step(k * 10000000u, std::sin(5.0 * 0.01 * double(k)), 0, 0), FSW_OK);
    if (k > 15000) amp = std::fmax(amp, std::fabs(double(f.out.LrF_B[0])));
  }
  EXPECT_NEAR(amp, 1 / std::sqrt(2.0), 2e-3);  // sampled peak: within 0.3 %
}

// Verifies: REQ-LPF-003
TEST(TrqLpfTiming, RateWarningAndTimeErrors)
{
  Fixture f;
  ASSERT_EQ(f.step(5 * kH, 1, 1, 1), FSW_OK);
  EXPECT_EQ(f.step(6 * kH + kH / 200, 1, 1, 1), FSW_OK);  // 0.5 % off: fine
  const FswTrqLpfState before = f.st;
  EXPECT_EQ(f.step(6 * kH + kH / 200, 1, 1, 1), FSW_E_TIME);  // same time
  for (int k = 0; k < 3; k++) EXPECT_EQ(f.out.LrF_B[k], 0.0);
  EXPECT_EQ(f.step(kH, 1, 1, 1), FSW_E_TIME);  // earlier
  EXPECT_EQ(f.st.LrF_prev[0], before.LrF_prev[0]);
  EXPECT_EQ(f.st.clock.t_prev_ns, before.clock.t_prev_ns);
  EXPECT_EQ(f.st.health.bad_time, 2u);
  // the 1 % threshold of docs/fsw/trq_lpf.md: a period 0.9 % long is fine, 1.5 % long warns
  uint64_t t = 6 * kH + kH / 200;
  t += kH + kH * 9 / 1000;
  EXPECT_EQ(f.step(t, 1, 1, 1), FSW_OK);
  t += kH + kH * 15 / 1000;
  EXPECT_EQ(f.step(t, 1, 1, 1), FSW_W_RATE);
  EXPECT_EQ(f.st.health.rate, 1u);
  t += 3 * kH;
  EXPECT_EQ(f.step(t, 1, 1, 1), FSW_W_RATE);  // 0.3 s instead of 0.1 s
  EXPECT_NE(f.out.LrF_B[0], 0.0);                 // still filtered with h
  EXPECT_EQ(f.st.health.rate, 2u);
}

// Verifies: REQ-LPF-004
TEST(TrqLpfBadInput, NonFiniteGivesZerosAndNoStateChange)
{
  Fixture f, g;
  ASSERT_EQ(f.step(0, 1, 2, 3), FSW_OK);
  ASSERT_EQ(g.step(0, 1, 2, 3), FSW_OK);
  EXPECT_EQ(f.step(kH, 1, std::numeric_limits<double>::quiet_NaN(), 3), FSW_E_BAD_INPUT);
  for (int k = 0; k < 3; k++) EXPECT_EQ(f.out.LrF_B[k], 0.0);
  EXPECT_EQ(f.step(kH, 1, INFINITY, 3), FSW_E_BAD_INPUT);
  EXPECT_EQ(f.st.health.bad_input, 2u);
  // the rejected calls left nothing behind: f and g agree from here on
  ASSERT_EQ(f.step(kH, 0.5, 0.5, 0.5), FSW_OK);
  ASSERT_EQ(g.step(kH, 0.5, 0.5, 0.5), FSW_OK);
  for (int k = 0; k < 3; k++) EXPECT_EQ(f.out.LrF_B[k], g.out.LrF_B[k]);
  kestrel_assert_reset();
  EXPECT_EQ(fsw_trq_lpf_update(&f.st, &f.cfg, nullptr, &f.out), FSW_E_NULL_ARG);
  EXPECT_EQ(kestrel_assert_count(), 1u);
  kestrel_assert_reset();
}

// Verifies: REQ-LPF-005
TEST(TrqLpfRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  Fixture f;
  fsw_real first[20][3];
  for (int pass = 0; pass < 2; pass++) {
    kt::Rng r(3);
    for (int k = 0; k < 20; k++) {
      ASSERT_EQ(f.step(uint64_t(k) * kH + 7u, r.normal(), r.normal(), r.normal()), FSW_OK);
      for (int j = 0; j < 3; j++) {
        if (pass == 0)
          first[k][j] = f.out.LrF_B[j];
        else
          EXPECT_EQ(f.out.LrF_B[j], first[k][j]);
      }
    }
    fsw_trq_lpf_reset(&f.st);
    EXPECT_EQ(f.st.clock.has_prev, 0);
  }
}

// Finding 4 (issue 13): 0.1, then a finite torque so large that the filter
// overflows, then 0.1.  Before the fix the output became inf, then NaN on
// every later call under OK (poisoned memory).  Now the huge input is bad
// input with the safe output and the state byte-identical, and a good retry
// at the same time stamp gives what a run without the glitch gives.
// Verifies: REQ-LPF-004
TEST(TrqLpfIssue13, OverflowIsBadInputAndDoesNotPoisonTheMemory)
{
  const double big = 0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  constexpr uint64_t kHalf = 500000000u;  // h = 0.5 s
  Fixture f(0.5, 4.0), clean(0.5, 4.0);
  ASSERT_EQ(FSW_OK, f.step(kHalf, 0.1, 0.1, 0.1));
  ASSERT_EQ(FSW_OK, clean.step(kHalf, 0.1, 0.1, 0.1));
  const FswTrqLpfState before = f.st;
  EXPECT_EQ(FSW_E_BAD_INPUT, f.step(2 * kHalf, big, 0.1, 0.1));
  for (int k = 0; k < 3; k++) EXPECT_EQ(0.0, f.out.LrF_B[k]);
  FswTrqLpfState after = f.st;
  after.health = before.health;
  EXPECT_EQ(0, std::memcmp(&before, &after, sizeof before));
  EXPECT_EQ(FSW_OK, f.step(2 * kHalf, 0.1, 0.1, 0.1));  // retry, same time
  EXPECT_EQ(FSW_OK, clean.step(2 * kHalf, 0.1, 0.1, 0.1));
  for (int k = 0; k < 3; k++) {
    EXPECT_TRUE(std::isfinite(f.out.LrF_B[k]));
    EXPECT_EQ(clean.out.LrF_B[k], f.out.LrF_B[k]);
  }
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(TrqLpfIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("trq_lpf", fsw_trq_lpf_check, fsw_trq_lpf_init, fsw_trq_lpf_reset, fsw_trq_lpf_update);
}

// Issue 21 (mutation survivor of seed 2112): init starts from a cleared
// memory, also on a state that has run: a re-initialised filter repeats a
// fresh filter's outputs bit for bit.
// Verifies: REQ-LPF-005
TEST(TrqLpfIssue21, InitClearsTheMemoryOfAUsedState)
{
  Fixture used, fresh;
  for (int k = 0; k < 5; k++) ASSERT_EQ(used.step(uint64_t(k) * kH, 1.0, -2.0, 0.5), FSW_OK);
  ASSERT_EQ(fsw_trq_lpf_init(&used.st, &used.cfg), FSW_OK);
  for (int k = 0; k < 3; k++) {
    const FswStatus a = used.step(uint64_t(k) * kH, 0.3, 0.1, -0.2);
    const FswStatus b = fresh.step(uint64_t(k) * kH, 0.3, 0.1, -0.2);
    EXPECT_EQ(a, b) << k;
    for (int j = 0; j < 3; j++) EXPECT_EQ(fresh.out.LrF_B[j], used.out.LrF_B[j]) << k << "," << j;
  }
}

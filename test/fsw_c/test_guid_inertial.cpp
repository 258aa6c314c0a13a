// guid_inertial: inertial three-axis pointing (docs/fsw/guid_inertial.md).
// Expected values are the configuration itself (the reference is constant)
// or its shadow set computed by hand; the rotation is compared with an
// independent principal-rotation DCM (gnc_test_ref.h).
#include <gtest/gtest.h>

#include <cmath>

#include "fsw/guid_inertial.h"
#include "gnc_test_ref.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

const double kTol = kt::tol(1e-15, 1e-7);

class GuidInertial : public ::testing::Test {
 protected:
  void SetUp() override { kestrel_assert_reset(); }
  void TearDown() override { EXPECT_EQ(0ul, kestrel_assert_count() - expected_asserts_); }
  FswGuidInertialConfig cfg_{};
  FswGuidInertialState st_{};
  FswGuidInertialOut out_{};
  unsigned long expected_asserts_ = 0;
};

void fill_garbage(FswGuidInertialOut& o)
{
  for (int i = 0; i < 3; i++) o.sigma_RN[i] = o.omega_RN_N[i] = o.omega_dot_RN_N[i] = FSW_R(7.0);
}

// Verifies: REQ-GINER-001
TEST_F(GuidInertial, OutputsConfiguredAttitudeWithZeroRates)
{
  gref::set3(cfg_.sigma_R0N, 0.1, 0.2, -0.3);  // |s|^2 = 0.14 <= 1: used as is
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_init(&st_, &cfg_));
  EXPECT_EQ(1, st_.ready);
  fill_garbage(out_);
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_update(&st_, &cfg_, &out_));
  EXPECT_V3_NEAR(gref::rr(0.1), gref::rr(0.2), gref::rr(-0.3), out_.sigma_RN, 0.0);  // exact copy
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.omega_RN_N, 0.0);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.omega_dot_RN_N, 0.0);
  EXPECT_EQ(1u, st_.health.calls);
  EXPECT_EQ(FSW_OK, st_.health.last);
}

// Verifies: REQ-GINER-001
TEST_F(GuidInertial, LongMrpIsShadowSwitchedAtInit)
{
  // s = (1, 1, 0.5): |s|^2 = 2.25 > 1, shadow = -s/2.25 = (-4/9, -4/9, -2/9).
  gref::set3(cfg_.sigma_R0N, 1.0, 1.0, 0.5);
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_init(&st_, &cfg_));
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_update(&st_, &cfg_, &out_));
  EXPECT_V3_NEAR(-4.0 / 9.0, -4.0 / 9.0, -2.0 / 9.0, out_.sigma_RN, kTol);
  // same rotation as the configured (long) MRP
  double C_cfg[3][3], C_out[3][3];
  gref::dcm_of_mrp(C_cfg, cfg_.sigma_R0N);
  gref::dcm_of_mrp(C_out, out_.sigma_RN);
  EXPECT_LT(gref::max_abs_diff(C_cfg, C_out), kt::tol(1e-14, 1e-6));
}

// Verifies: REQ-GINER-001
TEST_F(GuidInertial, UnitMrpIsNotSwitched)
{
  // |s| = 1 exactly (180 deg about z): the switch is strict (> 1), keep it.
  gref::set3(cfg_.sigma_R0N, 0.0, 0.0, 1.0);
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_init(&st_, &cfg_));
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_update(&st_, &cfg_, &out_));
  EXPECT_V3_NEAR(0.0, 0.0, 1.0, out_.sigma_RN, 0.0);
}

// Verifies: REQ-GINER-002
TEST_F(GuidInertial, RejectsNonFiniteConfig)
{
  struct Case {
    const char* name;
    double s[3];
  };
  const Case cases[] = {
      {"nan x", {gref::nan(), 0.0, 0.0}},
      {"nan z", {0.0, 0.0, gref::nan()}},
      {"+inf y", {0.0, gref::inf(), 0.0}},
      {"-inf x", {-gref::inf(), 0.0, 0.0}},
      {"|s|^2 overflows", {kt::kFloat ? 1e30 : 1e200, 0.0, 0.0}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    FswGuidInertialConfig bad{};
    gref::to_real(bad.sigma_R0N, c.s);
    EXPECT_EQ(FSW_E_CONFIG, fsw_guid_inertial_check(&bad));
    FswGuidInertialState st{};
    st.ready = 1;
    EXPECT_EQ(FSW_E_CONFIG, fsw_guid_inertial_init(&st, &bad));
    EXPECT_EQ(0, st.ready);
    fill_garbage(out_);
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_guid_inertial_update(&st, &bad, &out_));
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.sigma_RN, 0.0);  // safe output: R = N
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.omega_RN_N, 0.0);
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.omega_dot_RN_N, 0.0);
    EXPECT_EQ(1u, st.health.other_error);
  }
}

// Verifies: REQ-GINER-002
TEST_F(GuidInertial, NeverInitialisedStateGivesSafeOutput)
{
  fill_garbage(out_);
  EXPECT_EQ(FSW_E_NOT_INIT, fsw_guid_inertial_update(&st_, &cfg_, &out_));
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.sigma_RN, 0.0);
}

// Verifies: REQ-GEN-007
TEST_F(GuidInertial, NullPointersAssertAndReturnNullArg)
{
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_init(&st_, &cfg_));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_guid_inertial_update(&st_, &cfg_, nullptr));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_guid_inertial_update(nullptr, &cfg_, &out_));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_guid_inertial_update(&st_, nullptr, &out_));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_guid_inertial_check(nullptr));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_guid_inertial_init(nullptr, &cfg_));
  expected_asserts_ = 5;
  EXPECT_EQ(5ul, kestrel_assert_count());
  EXPECT_EQ(2u, st_.health.bad_input);  // the two calls that had a state
}

// Verifies: REQ-GINER-003
TEST_F(GuidInertial, RepeatableAfterReset)
{
  gref::set3(cfg_.sigma_R0N, -0.2, 0.5, 0.7);
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_init(&st_, &cfg_));
  FswGuidInertialOut a{}, b{};
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_update(&st_, &cfg_, &a));
  fsw_guid_inertial_reset(&st_);
  ASSERT_EQ(FSW_OK, fsw_guid_inertial_update(&st_, &cfg_, &b));
  for (int i = 0; i < 3; i++) {
    EXPECT_EQ(a.sigma_RN[i], b.sigma_RN[i]);
    EXPECT_EQ(a.omega_RN_N[i], b.omega_RN_N[i]);
  }
  EXPECT_EQ(2u, st_.health.calls);  // reset keeps the counters
}

}  // namespace

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h); the module has no In struct.
// Verifies: REQ-GEN-007
TEST(GuidInertialIssue21, EveryNullArgumentAssertsAndReturns)
{
  FswGuidInertialConfig cfg{};
  FswGuidInertialState st{};
  FswGuidInertialOut out{};
  kt::each_null("guid_inertial_check", fsw_guid_inertial_check, &cfg);
  kt::each_null("guid_inertial_init", fsw_guid_inertial_init, &st, &cfg);
  kt::each_null("guid_inertial_reset", fsw_guid_inertial_reset, &st);
  kt::each_null("guid_inertial_update", fsw_guid_inertial_update, &st, &cfg, &out);
}

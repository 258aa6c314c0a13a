// att_track: attitude tracking error (docs/fsw/att_track.md).
// Hand cases use rotations about one axis, where MRPs compose as angles:
// sigma = tan(theta/4) e, so B at theta_B and R at theta_R about e give
// sigma_BR = tan((theta_B - theta_R)/4) e.  The general case is checked
// against an independent DCM: [BR] = [BN][RN]^T (gnc_test_ref.h).
#include <gtest/gtest.h>

#include <cmath>

#include "fsw/att_track.h"
#include "gnc_test_ref.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

const double kTol = kt::tol(1e-14, 2e-6);
const double kDeg = gref::kPi / 180.0;

class AttTrack : public ::testing::Test {
 protected:
  void SetUp() override
  {
    kestrel_assert_reset();
    ASSERT_EQ(FSW_OK, fsw_att_track_init(&st_, &cfg_));
  }
  FswAttTrackConfig cfg_{};
  FswAttTrackState st_{};
  FswAttTrackIn in_{};
  FswAttTrackOut out_{};
};

fsw_real* input_field(FswAttTrackIn& in, int f)
{
  switch (f) {
  case 0: return in.sigma_BN;
  case 1: return in.omega_BN_B;
  case 2: return in.ref.sigma_RN;
  case 3: return in.ref.omega_RN_N;
  default: return in.ref.omega_dot_RN_N;
  }
}

void expect_zero_guid(const FswAttGuid& g)
{
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, g.sigma_BR, 0.0);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, g.omega_BR_B, 0.0);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, g.omega_RN_B, 0.0);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, g.omega_dot_RN_B, 0.0);
}

// Verifies: REQ-ATTTRK-001
TEST_F(AttTrack, SameAxisRotationsSubtractAngles)
{
  // B at 60 deg, R at 20 deg about z: sigma_BR = tan(40 deg / 4) z = tan(10 deg) z.
  gref::set3(in_.sigma_BN, 0, 0, std::tan(60 * kDeg / 4));
  gref::set3(in_.ref.sigma_RN, 0, 0, std::tan(20 * kDeg / 4));
  ASSERT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &out_));
  EXPECT_V3_NEAR(0.0, 0.0, std::tan(10 * kDeg), out_.sigma_BR, kTol);
}

// Verifies: REQ-ATTTRK-001
TEST_F(AttTrack, RatesAreExpressedInBody)
{
  // sigma_BN = tan(90deg/4) z: [BN] = M3(90 deg) = [[0,1,0],[-1,0,0],[0,0,1]].
  // omega_RN_N = (0.1, 0, 0.02)  ->  omega_RN_B = (0, -0.1, 0.02)
  // omega_dot_RN_N = (0, 0.003, 0) -> omega_dot_RN_B = (0.003, 0, 0)
  // omega_BN_B = (0.01, 0.02, 0.03) -> omega_BR_B = (0.01, 0.12, 0.01)
  gref::set3(in_.sigma_BN, 0, 0, std::tan(90 * kDeg / 4));
  gref::set3(in_.omega_BN_B, 0.01, 0.02, 0.03);
  gref::set3(in_.ref.omega_RN_N, 0.1, 0.0, 0.02);
  gref::set3(in_.ref.omega_dot_RN_N, 0.0, 0.003, 0.0);
  ASSERT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &out_));
  EXPECT_V3_NEAR(0.0, -0.1, 0.02, out_.omega_RN_B, kTol);
  EXPECT_V3_NEAR(0.003, 0.0, 0.0, out_.omega_dot_RN_B, kTol);
  EXPECT_V3_NEAR(0.01, 0.12, 0.01, out_.omega_BR_B, kTol);
  // sigma_RN = 0, so sigma_BR = sigma_BN
  EXPECT_V3_NEAR(0.0, 0.0, std::tan(90 * kDeg / 4), out_.sigma_BR, kTol);
}

// Verifies: REQ-ATTTRK-001
TEST_F(AttTrack, ReferenceOffsetShiftsTheReference)
{
  // All about x: B at 50, R at 30, R0 relative to R at 15 deg.
  // sigma_RN' = addMRP(sigma_RN, -sigma_R0R): 30 - 15 = 15 deg;
  // sigma_BR = 50 - 15 = 35 deg.  The offset does not enter the rates.
  gref::set3(cfg_.sigma_R0R, std::tan(15 * kDeg / 4), 0, 0);
  ASSERT_EQ(FSW_OK, fsw_att_track_init(&st_, &cfg_));
  gref::set3(in_.sigma_BN, std::tan(50 * kDeg / 4), 0, 0);
  gref::set3(in_.ref.sigma_RN, std::tan(30 * kDeg / 4), 0, 0);
  gref::set3(in_.omega_BN_B, 0.0, 0.0, 0.04);
  ASSERT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &out_));
  EXPECT_V3_NEAR(std::tan(35 * kDeg / 4), 0.0, 0.0, out_.sigma_BR, kTol);
  EXPECT_V3_NEAR(0.0, 0.0, 0.04, out_.omega_BR_B, kTol);
}

// Verifies: REQ-ATTTRK-001
TEST_F(AttTrack, ErrorNear360DegreesIsTheShortRotation)
{
  // B at +179 deg, R at -179 deg about y: B rel. R is 358 deg = -2 deg about y.
  gref::set3(in_.sigma_BN, 0, std::tan(179 * kDeg / 4), 0);
  gref::set3(in_.ref.sigma_RN, 0, std::tan(-179 * kDeg / 4), 0);
  ASSERT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &out_));
  EXPECT_V3_NEAR(0.0, std::tan(-2 * kDeg / 4), 0.0, out_.sigma_BR, kt::tol(1e-13, 1e-5));
}

// Verifies: REQ-ATTTRK-001
TEST_F(AttTrack, MatchesIndependentDcmCompositionOnRandomAttitudes)
{
  // Property: DCM(sigma_BR) = DCM(sigma_BN) DCM(sigma_RN')^T with
  // DCM(sigma_RN') = DCM(-sigma_R0R) DCM(sigma_RN) ([R R0][R0 N]);
  // |sigma_BR| <= 1; omega_BR = omega_BN - [BN] omega_RN_N.
  kt::Rng rng(0x5eed0001u);
  for (int trial = 0; trial < 200; trial++) {
    double sBN[3], sRN[3], sR0R[3], wBN[3], wRN[3], dwRN[3];
    gref::random_mrp(rng, sBN);
    gref::random_mrp(rng, sRN);
    gref::random_mrp(rng, sR0R, trial % 2 ? 2.0 * gref::kPi : 0.0);  // half with no offset
    for (int i = 0; i < 3; i++) {
      wBN[i] = rng.uniform(-0.1, 0.1);
      wRN[i] = rng.uniform(-0.1, 0.1);
      dwRN[i] = rng.uniform(-0.01, 0.01);
    }
    FswAttTrackConfig cfg{};
    gref::to_real(cfg.sigma_R0R, sR0R);
    FswAttTrackState st{};
    ASSERT_EQ(FSW_OK, fsw_att_track_init(&st, &cfg));
    FswAttTrackIn in{};
    gref::to_real(in.sigma_BN, sBN);
    gref::to_real(in.ref.sigma_RN, sRN);
    gref::to_real(in.omega_BN_B, wBN);
    gref::to_real(in.ref.omega_RN_N, wRN);
    gref::to_real(in.ref.omega_dot_RN_N, dwRN);
    FswAttTrackOut out{};
    ASSERT_EQ(FSW_OK, fsw_att_track_update(&st, &cfg, &in, &out));

    double C_BN[3][3], C_RN[3][3], C_RR0[3][3], C_RpN[3][3], C_RpN_T[3][3], want[3][3], got[3][3];
    const double mR0R[3] = {-sR0R[0], -sR0R[1], -sR0R[2]};
    gref::dcm_of_mrp(C_BN, in.sigma_BN);
    gref::dcm_of_mrp(C_RN, in.ref.sigma_RN);
    fsw_real mR0R_r[3];
    gref::to_real(mR0R_r, mR0R);
    gref::dcm_of_mrp(C_RR0, mR0R_r);
    gref::matmul(C_RpN, C_RR0, C_RN);
    gref::transpose(C_RpN_T, C_RpN);
    gref::matmul(want, C_BN, C_RpN_T);
    gref::dcm_of_mrp(got, out.sigma_BR);
    EXPECT_LT(gref::max_abs_diff(want, got), kt::tol(1e-12, 2e-5)) << "trial " << trial;
    double s_out[3];
    gref::to_double(s_out, out.sigma_BR);
    EXPECT_LE(gref::norm(s_out), 1.0 + kt::tol(1e-15, 1e-6));

    double wRN_B[3], dwRN_B[3], wRN_d[3], dwRN_d[3];
    gref::to_double(wRN_d, in.ref.omega_RN_N);
    gref::to_double(dwRN_d, in.ref.omega_dot_RN_N);
    gref::matvec(wRN_B, C_BN, wRN_d);
    gref::matvec(dwRN_B, C_BN, dwRN_d);
    const double tol = kt::tol(1e-15, 1e-7);
    for (int i = 0; i < 3; i++) {
      EXPECT_NEAR(wRN_B[i], out.omega_RN_B[i], tol);
      EXPECT_NEAR(dwRN_B[i], out.omega_dot_RN_B[i], tol * 0.1);
      EXPECT_NEAR(static_cast<double>(in.omega_BN_B[i]) - wRN_B[i], out.omega_BR_B[i], tol);
    }
  }
}

// Verifies: REQ-ATTTRK-002
TEST_F(AttTrack, RejectsNonFiniteConfig)
{
  const double bad_values[] = {gref::nan(), gref::inf(), -gref::inf()};
  for (int k = 0; k < 3; k++) {
    for (double v : bad_values) {
      FswAttTrackConfig cfg{};
      cfg.sigma_R0R[k] = static_cast<fsw_real>(v);
      EXPECT_EQ(FSW_E_CONFIG, fsw_att_track_check(&cfg));
      FswAttTrackState st{};
      EXPECT_EQ(FSW_E_CONFIG, fsw_att_track_init(&st, &cfg));
      EXPECT_EQ(0, st.ready);
      EXPECT_EQ(FSW_E_NOT_INIT, fsw_att_track_update(&st, &cfg, &in_, &out_));
      expect_zero_guid(out_);
    }
  }
}

// Verifies: REQ-ATTTRK-003
TEST_F(AttTrack, NonFiniteInputGivesZeroErrors)
{
  // Every component of every input field, NaN and Inf: status, zero
  // guidance, counter.
  const double bad_values[] = {gref::nan(), gref::inf()};
  uint32_t n_bad = 0;
  for (int f = 0; f < 5; f++) {
    for (int k = 0; k < 3; k++) {
      for (double v : bad_values) {
        FswAttTrackIn in{};
        gref::set3(in.sigma_BN, 0.1, 0.2, 0.3);
        gref::set3(in.omega_BN_B, 0.01, 0.0, 0.0);
        input_field(in, f)[k] = static_cast<fsw_real>(v);
        for (int i = 0; i < 3; i++) out_.sigma_BR[i] = out_.omega_BR_B[i] = FSW_R(9.0);
        EXPECT_EQ(FSW_E_BAD_INPUT, fsw_att_track_update(&st_, &cfg_, &in, &out_));
        expect_zero_guid(out_);
        n_bad++;
      }
    }
  }
  // finite but huge reference rate: [BN] omega_RN_N overflows -> safe output
  {
    FswAttTrackIn in{};
    gref::set3(in.sigma_BN, 0.1, 0.2, 0.3);
    const double big = kt::kFloat ? 3e38 : 1.7e308;
    gref::set3(in.ref.omega_RN_N, big, big, big);
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_att_track_update(&st_, &cfg_, &in, &out_));
    expect_zero_guid(out_);
    n_bad++;
  }
  EXPECT_EQ(n_bad, st_.health.bad_input);
  // the next good call recovers
  gref::set3(in_.sigma_BN, 0.1, 0.0, 0.0);
  EXPECT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &out_));
  EXPECT_V3_NEAR(0.1, 0.0, 0.0, out_.sigma_BR, kTol);
}

// Verifies: REQ-GEN-007
TEST_F(AttTrack, NullPointersAssert)
{
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_att_track_update(&st_, &cfg_, nullptr, &out_));
  EXPECT_EQ(1ul, kestrel_assert_count());
  expect_zero_guid(out_);
}

// Verifies: REQ-ATTTRK-004
TEST_F(AttTrack, RepeatableAfterReset)
{
  gref::set3(in_.sigma_BN, 0.3, -0.2, 0.1);
  gref::set3(in_.ref.sigma_RN, -0.1, 0.4, 0.2);
  gref::set3(in_.omega_BN_B, 0.01, -0.02, 0.03);
  gref::set3(in_.ref.omega_RN_N, 0.001, 0.002, -0.003);
  FswAttTrackOut a{}, b{};
  ASSERT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &a));
  fsw_att_track_reset(&st_);
  ASSERT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &b));
  for (int i = 0; i < 3; i++) {
    EXPECT_EQ(a.sigma_BR[i], b.sigma_BR[i]);
    EXPECT_EQ(a.omega_BR_B[i], b.omega_BR_B[i]);
    EXPECT_EQ(a.omega_RN_B[i], b.omega_RN_B[i]);
  }
}

}  // namespace

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(AttTrackIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("att_track", fsw_att_track_check, fsw_att_track_init, fsw_att_track_reset, fsw_att_track_update);
}

// Issue 21: finite values that overflow.  An MRP whose |sigma|^2 overflows
// (2 sqrt(max) in one component: |sigma|^2 = 4 max) cannot be switched to
// its shadow set: a config offset like that is refused, an input like that
// is bad input.  Rates: omega_BN = max and omega_RN_N = -max at [BN] = I
// give omega_BR = 2 max = inf.  Accelerations: (max, max, 0) in N seen from
// B turned 45 deg about z (sigma = (0, 0, tan(pi/16))) has one component of
// length sqrt(2) max = inf.  Each: bad input, zero guidance.
// Verifies: REQ-ATTTRK-003
TEST_F(AttTrack, Issue21FiniteInputsThatOverflow)
{
  const fsw_real mx = std::numeric_limits<fsw_real>::max();
  const fsw_real huge = 2 * std::sqrt(mx);
  FswAttTrackConfig cfg{};
  cfg.sigma_R0R[1] = huge;
  EXPECT_EQ(FSW_E_CONFIG, fsw_att_track_check(&cfg));
  for (int f : {0, 2}) {  // sigma_BN, ref.sigma_RN
    FswAttTrackIn in{};
    input_field(in, f)[2] = huge;
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_att_track_update(&st_, &cfg_, &in, &out_)) << f;
    expect_zero_guid(out_);
  }
  {
    FswAttTrackIn in{};
    in.omega_BN_B[0] = mx;
    in.ref.omega_RN_N[0] = -mx;
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_att_track_update(&st_, &cfg_, &in, &out_));
    expect_zero_guid(out_);
  }
  {
    FswAttTrackIn in{};
    gref::set3(in.sigma_BN, 0.0, 0.0, std::tan(gref::kPi / 16.0));  // 45 deg about z
    in.ref.omega_dot_RN_N[0] = mx;
    in.ref.omega_dot_RN_N[1] = mx;
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_att_track_update(&st_, &cfg_, &in, &out_));
    expect_zero_guid(out_);
  }
  in_ = FswAttTrackIn{};
  EXPECT_EQ(FSW_OK, fsw_att_track_update(&st_, &cfg_, &in_, &out_));  // recovers
}

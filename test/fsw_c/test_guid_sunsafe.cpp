// guid_sunsafe: sun-safe pointing (docs/fsw/guid_sunsafe.md).
// Hand cases: s_cmd = +x and the Sun on +y is a -90 deg rotation of B
// relative to R about z (R's first axis must coincide with the Sun, i.e.
// R = B turned +90 deg about z), so sigma_BR = tan(-90deg/4) z.
// Property (any geometry): [BR]^T s_hat_B = s_cmd_hat, i.e. in R components
// the commanded body axis points at the Sun, checked with an independent DCM.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/fsw_vec.h"
#include "fsw/guid_sunsafe.h"
#include "guid_sunsafe_internal.h"
#include "gnc_test_ref.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

const double kTol = kt::tol(1e-15, 2e-7);
const double kDeg = gref::kPi / 180.0;

class GuidSunsafe : public ::testing::Test {
 protected:
  void SetUp() override
  {
    kestrel_assert_reset();
    gref::set3(cfg_.s_cmd_B, 1.0, 0.0, 0.0);
    cfg_.min_unit_mag = FSW_R(0.1);
    cfg_.small_angle = static_cast<fsw_real>(0.01 * kDeg);
    gref::set3(cfg_.omega_search_B, 0.0, 0.0, 0.02);
    cfg_.sun_axis_spin_rate = FSW_R(0.0);
    ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
  }
  FswStatus run() { return fsw_guid_sunsafe_update(&st_, &cfg_, &in_, &out_); }
  FswGuidSunsafeConfig cfg_{};
  FswGuidSunsafeState st_{};
  FswGuidSunsafeIn in_{};
  FswGuidSunsafeOut out_{};
};

// Verifies: REQ-GSUN-001
TEST_F(GuidSunsafe, QuarterTurnHandCase)
{
  // Sun on +y with |s| = 2 (not unit): theta = 90 deg,
  // e = unit(s x s_cmd) = unit(y x x) = -z, sigma_BR = tan(22.5 deg) (-z).
  gref::set3(in_.sun_B, 0.0, 2.0, 0.0);
  gref::set3(in_.omega_BN_B, 0.01, 0.02, 0.03);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_V3_NEAR(0.0, 0.0, -std::tan(22.5 * kDeg), out_.guid.sigma_BR, kTol);
  EXPECT_NEAR(90 * kDeg, out_.sun_angle_err, kTol);
  EXPECT_EQ(1, out_.sun_valid);
  // no spin about the Sun axis: omega_RN = 0, omega_BR = omega_BN
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.omega_RN_B, 0.0);
  EXPECT_V3_NEAR(gref::rr(0.01), gref::rr(0.02), gref::rr(0.03), out_.guid.omega_BR_B, 0.0);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.omega_dot_RN_B, 0.0);
}

// Verifies: REQ-GSUN-001
TEST_F(GuidSunsafe, SpinAboutSunAxis)
{
  // omega_RN_B = (rate/|s|) s = (0.05/2) (0, 2, 0) = (0, 0.05, 0);
  // omega_BR = (0.01, 0.02, 0.03) - (0, 0.05, 0) = (0.01, -0.03, 0.03).
  cfg_.sun_axis_spin_rate = FSW_R(0.05);
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
  gref::set3(in_.sun_B, 0.0, 2.0, 0.0);
  gref::set3(in_.omega_BN_B, 0.01, 0.02, 0.03);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_V3_NEAR(0.0, 0.05, 0.0, out_.guid.omega_RN_B, kTol);
  EXPECT_V3_NEAR(0.01, -0.03, 0.03, out_.guid.omega_BR_B, kTol);
}

// Verifies: REQ-GSUN-002
TEST_F(GuidSunsafe, InsideDeadBandNoAttitudeError)
{
  // Sun 0.005 deg off +x in the x-y plane, dead band 0.01 deg: sigma_BR = 0,
  // theta still reported, rates still formed.
  const double a = 0.005 * kDeg;
  gref::set3(in_.sun_B, std::cos(a), std::sin(a), 0.0);
  gref::set3(in_.omega_BN_B, 0.001, 0.0, 0.0);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.sigma_BR, 0.0);
  EXPECT_NEAR(a, out_.sun_angle_err, kt::tol(1e-9, 3e-4));  // acos near 1 loses digits
  EXPECT_V3_NEAR(gref::rr(0.001), 0.0, 0.0, out_.guid.omega_BR_B, 0.0);
  EXPECT_EQ(1, out_.sun_valid);
}

// Verifies: REQ-GSUN-002
TEST_F(GuidSunsafe, AntiparallelUsesE180)
{
  // s_cmd = +x: |x cross x| = 0 < 0.1, so e180 = unit(x cross y) = +z.
  // Sun on -x: theta = pi, sigma_BR = tan(pi/4) z = z (|sigma| = 1, no switch).
  EXPECT_V3_NEAR(0.0, 0.0, 1.0, st_.e180_hat_B, 0.0);
  gref::set3(in_.sun_B, -3.0, 0.0, 0.0);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_V3_NEAR(0.0, 0.0, 1.0, out_.guid.sigma_BR, kTol);
  EXPECT_NEAR(gref::kPi, out_.sun_angle_err, kTol);
}

// Verifies: REQ-GSUN-002
TEST_F(GuidSunsafe, NearlyAntiparallelWithinDeadBandUsesE180)
{
  // Sun 0.005 deg from -x (pi - theta < small_angle): axis e180 = +z,
  // angle theta, sigma_BR = tan(theta/4) z.
  const double a = 0.005 * kDeg;
  gref::set3(in_.sun_B, -std::cos(a), 0.0, std::sin(a));
  ASSERT_EQ(FSW_OK, run());
  const double theta = gref::kPi - a;
  EXPECT_V3_NEAR(0.0, 0.0, std::tan(theta / 4), out_.guid.sigma_BR, kt::tol(1e-9, 2e-4));
}

// Verifies: REQ-GSUN-002
TEST_F(GuidSunsafe, ExactAntiparallelWithZeroDeadBandIsGuarded)
{
  // small_angle = 0: the e180 branch (pi - theta < 0) is never taken, the
  // cross product is exactly 0 and the library guard must use e180.
  // s_cmd = +z: |z x x| = 1 >= 0.1, e180 = unit(z x x) = +y.
  gref::set3(cfg_.s_cmd_B, 0.0, 0.0, 5.0);
  cfg_.small_angle = FSW_R(0.0);
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
  EXPECT_V3_NEAR(0.0, 0.0, 1.0, st_.s_cmd_hat_B, 0.0);
  EXPECT_V3_NEAR(0.0, 1.0, 0.0, st_.e180_hat_B, 0.0);
  gref::set3(in_.sun_B, 0.0, 0.0, -1.0);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_V3_NEAR(0.0, 1.0, 0.0, out_.guid.sigma_BR, kTol);
  for (int i = 0; i < 3; i++) EXPECT_TRUE(std::isfinite(static_cast<double>(out_.guid.sigma_BR[i])));
}

// Issue 21 (seed 9001): the Sun exactly on (or opposite) the commanded axis.
// c = s_cmd_hat . s / |s| is then +-1 up to rounding, and rounding puts it
// outside [-1, 1] for some directions; acos would return NaN there.  Over a
// grid of 400 directions the cycle must succeed with theta within
// acos(1 - 4 eps) ~ sqrt(8 eps) of 0 (resp. pi); where the computed c is
// beyond +-1 (counted with the library's own dot and norm, the same
// operations in the same order), the clamp makes theta exactly 0 (resp. pi).
// Verifies: REQ-GSUN-006
TEST_F(GuidSunsafe, Issue21SunOnTheCommandedAxisRoundsToAValidAngle)
{
  const double eps = static_cast<double>(std::numeric_limits<fsw_real>::epsilon());
  const double bound = std::sqrt(8.0 * eps);  // acos(1 - d) = sqrt(2 d) + O(d^1.5), d <= 4 eps
  int above = 0, below = 0;
  for (int a = 0; a < 20; a++) {
    for (int b = 0; b < 20; b++) {
      const double az = 2.0 * gref::kPi * (a + 0.37) / 20.0, el = gref::kPi * ((b + 0.5) / 20.0 - 0.5);
      gref::set3(cfg_.s_cmd_B, std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el));
      ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
      for (const double sign : {1.0, -1.0}) {
        for (int k = 0; k < 3; k++) in_.sun_B[k] = static_cast<fsw_real>(sign * static_cast<double>(cfg_.s_cmd_B[k]));
        const double c = static_cast<double>(fsw_v3_dot(st_.s_cmd_hat_B, in_.sun_B) / fsw_v3_norm(in_.sun_B));
        ASSERT_EQ(FSW_OK, run()) << a << " " << b << " " << sign;
        const double theta = static_cast<double>(out_.sun_angle_err);
        if (sign > 0) {
          EXPECT_LE(theta, bound) << a << " " << b;
          if (c > 1.0) {
            above++;
            EXPECT_EQ(0.0, theta);
          }
        } else {
          EXPECT_GE(theta, gref::kPi - bound) << a << " " << b;
          if (c < -1.0) {
            below++;
            EXPECT_NEAR(gref::kPi, theta, kTol);  // acos(-1) = pi, rounded to the real type
          }
        }
        for (int k = 0; k < 3; k++) EXPECT_TRUE(std::isfinite(static_cast<double>(out_.guid.sigma_BR[k])));
      }
    }
  }
  // the grid reaches both clamps (else the test would not test them)
  EXPECT_GT(above, 0);
  EXPECT_GT(below, 0);
}

// Verifies: REQ-GSUN-003
TEST_F(GuidSunsafe, NoValidSunSearchSpin)
{
  // |s| = 0.05 <= min_unit_mag = 0.1: sigma_BR = 0, omega_RN = omega_search,
  // omega_BR = omega_BN - omega_search = (0.01, 0, 0.03 - 0.02).
  gref::set3(in_.sun_B, 0.05, 0.0, 0.0);
  gref::set3(in_.omega_BN_B, 0.01, 0.0, 0.03);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.sigma_BR, 0.0);
  EXPECT_V3_NEAR(0.0, 0.0, gref::rr(0.02), out_.guid.omega_RN_B, 0.0);
  EXPECT_V3_NEAR(0.01, 0.0, 0.03 - 0.02, out_.guid.omega_BR_B, kTol);
  EXPECT_EQ(0, out_.sun_valid);
  EXPECT_EQ(0.0, out_.sun_angle_err);
  // the boundary |s| = min_unit_mag is "no Sun" (spec: valid only if |s| > minUnitMag)
  gref::set3(in_.sun_B, 0.1, 0.0, 0.0);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_EQ(0, out_.sun_valid);
  gref::set3(in_.sun_B, 0.1001, 0.0, 0.0);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_EQ(1, out_.sun_valid);
  // exactly zero heading with min_unit_mag = 0 is also "no Sun" (no 0/0)
  cfg_.min_unit_mag = FSW_R(0.0);
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
  gref::set3(in_.sun_B, 0.0, 0.0, 0.0);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_EQ(0, out_.sun_valid);
  EXPECT_V3_NEAR(0.01, 0.0, 0.03 - 0.02, out_.guid.omega_BR_B, kTol);
}

// Verifies: REQ-GSUN-001
TEST_F(GuidSunsafe, RandomGeometryPointsCommandedAxisAtSun)
{
  kt::Rng rng(0x5eed0002u);
  for (int trial = 0; trial < 300; trial++) {
    double scmd[3], sun[3];
    rng.unit3(scmd);
    rng.unit3(sun);
    const double mag = rng.uniform(0.5, 3.0);
    FswGuidSunsafeConfig cfg = cfg_;
    gref::to_real(cfg.s_cmd_B, scmd);
    FswGuidSunsafeState st{};
    ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st, &cfg));
    FswGuidSunsafeIn in{};
    gref::set3(in.sun_B, mag * sun[0], mag * sun[1], mag * sun[2]);
    FswGuidSunsafeOut out{};
    ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_update(&st, &cfg, &in, &out));
    const double theta = std::acos(std::fmax(-1.0, std::fmin(1.0, gref::dot(scmd, sun))));
    EXPECT_NEAR(theta, out.sun_angle_err, kt::tol(1e-12, 1e-3));
    if (theta < 0.01 * kDeg || gref::kPi - theta < 0.01 * kDeg) continue;  // dead bands
    double C_BR[3][3], C_RB[3][3], s_R[3];
    gref::dcm_of_mrp(C_BR, out.guid.sigma_BR);
    gref::transpose(C_RB, C_BR);
    gref::matvec(s_R, C_RB, sun);
    for (int i = 0; i < 3; i++) EXPECT_NEAR(scmd[i], s_R[i], kt::tol(1e-12, 2e-5)) << trial;
    // minimal rotation: sigma_BR is perpendicular to both vectors, |sigma| = tan(theta/4)
    double s_out[3];
    gref::to_double(s_out, out.guid.sigma_BR);
    EXPECT_NEAR(std::tan(theta / 4), gref::norm(s_out), kt::tol(1e-12, 2e-5));
    EXPECT_NEAR(0.0, gref::dot(s_out, sun), kt::tol(1e-12, 2e-5));
  }
}

// Verifies: REQ-GSUN-004
TEST_F(GuidSunsafe, RejectsBadConfig)
{
  struct Case {
    const char* name;
    void (*edit)(FswGuidSunsafeConfig&);
  };
  const Case cases[] = {
      {"s_cmd too short", [](FswGuidSunsafeConfig& c) { gref::set3(c.s_cmd_B, 0.05, 0.05, 0.0); }},
      {"s_cmd zero", [](FswGuidSunsafeConfig& c) { gref::set3(c.s_cmd_B, 0, 0, 0); }},
      {"s_cmd nan", [](FswGuidSunsafeConfig& c) { c.s_cmd_B[1] = static_cast<fsw_real>(gref::nan()); }},
      {"min_unit_mag < 0", [](FswGuidSunsafeConfig& c) { c.min_unit_mag = FSW_R(-0.1); }},
      {"min_unit_mag inf", [](FswGuidSunsafeConfig& c) { c.min_unit_mag = static_cast<fsw_real>(gref::inf()); }},
      {"small_angle < 0", [](FswGuidSunsafeConfig& c) { c.small_angle = FSW_R(-1e-3); }},
      {"small_angle = pi/2", [](FswGuidSunsafeConfig& c) { c.small_angle = static_cast<fsw_real>(gref::kPi / 2); }},
      {"small_angle nan", [](FswGuidSunsafeConfig& c) { c.small_angle = static_cast<fsw_real>(gref::nan()); }},
      {"omega_search inf", [](FswGuidSunsafeConfig& c) { c.omega_search_B[2] = static_cast<fsw_real>(gref::inf()); }},
      {"omega_search above FSW_GUID_SUNSAFE_RATE_MAX (issue 21)",
       [](FswGuidSunsafeConfig& c) { c.omega_search_B[0] = 2 * FSW_GUID_SUNSAFE_RATE_MAX; }},
      {"spin rate nan", [](FswGuidSunsafeConfig& c) { c.sun_axis_spin_rate = static_cast<fsw_real>(gref::nan()); }},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    FswGuidSunsafeConfig cfg = cfg_;
    k.edit(cfg);
    EXPECT_EQ(FSW_E_CONFIG, fsw_guid_sunsafe_check(&cfg));
    FswGuidSunsafeState st{};
    EXPECT_EQ(FSW_E_CONFIG, fsw_guid_sunsafe_init(&st, &cfg));
    EXPECT_EQ(0, st.ready);
    gref::set3(in_.sun_B, 0.0, 1.0, 0.0);
    out_.sun_valid = 5;
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_guid_sunsafe_update(&st, &cfg, &in_, &out_));
    EXPECT_EQ(0, out_.sun_valid);
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.sigma_BR, 0.0);
  }
  // boundary values that are legal
  FswGuidSunsafeConfig ok = cfg_;
  gref::set3(ok.s_cmd_B, 0.1, 0.0, 0.0);  // |s_cmd| = 0.1 exactly
  ok.min_unit_mag = FSW_R(0.0);
  ok.small_angle = FSW_R(0.0);
  EXPECT_EQ(FSW_OK, fsw_guid_sunsafe_check(&ok));
}

// Verifies: REQ-GSUN-005
TEST_F(GuidSunsafe, NonFiniteInputGivesZeroErrors)
{
  const double bad_values[] = {gref::nan(), gref::inf(), -gref::inf()};
  uint32_t n = 0;
  for (int f = 0; f < 2; f++) {
    for (int k = 0; k < 3; k++) {
      for (double v : bad_values) {
        FswGuidSunsafeIn in{};
        gref::set3(in.sun_B, 0.0, 1.0, 0.0);
        gref::set3(in.omega_BN_B, 0.01, 0.02, 0.03);
        (f == 0 ? in.sun_B : in.omega_BN_B)[k] = static_cast<fsw_real>(v);
        for (int i = 0; i < 3; i++) out_.guid.omega_BR_B[i] = out_.guid.sigma_BR[i] = FSW_R(4.0);
        EXPECT_EQ(FSW_E_BAD_INPUT, fsw_guid_sunsafe_update(&st_, &cfg_, &in, &out_));
        EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.sigma_BR, 0.0);
        EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.omega_BR_B, 0.0);
        EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.guid.omega_RN_B, 0.0);
        EXPECT_EQ(0, out_.sun_valid);
        n++;
      }
    }
  }
  // finite but huge rates: check bounds the configured rates (issue 13),
  // so the rate outputs cannot overflow; a huge body rate stays finite
  {
    const double big = kt::kFloat ? 3e38 : 1.7e308;
    cfg_.sun_axis_spin_rate = static_cast<fsw_real>(big);
    EXPECT_EQ(FSW_E_CONFIG, fsw_guid_sunsafe_init(&st_, &cfg_));
    cfg_.sun_axis_spin_rate = FSW_R(-10.0);
    ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
    FswGuidSunsafeIn in{};
    gref::set3(in.sun_B, -1.0, 0.0, 0.0);
    gref::set3(in.omega_BN_B, big, 0.0, 0.0);
    EXPECT_EQ(FSW_OK, fsw_guid_sunsafe_update(&st_, &cfg_, &in, &out_));
    for (int i = 0; i < 3; i++) EXPECT_TRUE(std::isfinite(out_.guid.omega_BR_B[i]));
  }
  EXPECT_EQ(0ul, kestrel_assert_count());
}

// Verifies: REQ-GEN-007
TEST_F(GuidSunsafe, NullPointersAssert)
{
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_guid_sunsafe_update(&st_, &cfg_, nullptr, &out_));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_guid_sunsafe_check(nullptr));
  EXPECT_EQ(2ul, kestrel_assert_count());
}

// Verifies: REQ-GSUN-007
TEST_F(GuidSunsafe, RepeatableAfterReset)
{
  cfg_.sun_axis_spin_rate = FSW_R(0.01);
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
  gref::set3(in_.sun_B, 0.3, -0.5, 0.8);
  gref::set3(in_.omega_BN_B, 0.01, 0.02, -0.01);
  FswGuidSunsafeOut a{}, b{};
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_update(&st_, &cfg_, &in_, &a));
  fsw_guid_sunsafe_reset(&st_);
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_update(&st_, &cfg_, &in_, &b));
  for (int i = 0; i < 3; i++) {
    EXPECT_EQ(a.guid.sigma_BR[i], b.guid.sigma_BR[i]);
    EXPECT_EQ(a.guid.omega_BR_B[i], b.guid.omega_BR_B[i]);
  }
  EXPECT_EQ(a.sun_angle_err, b.sun_angle_err);
}

}  // namespace

// ---- issue 13: the contract for every input -------------------------------

// Finding 5: s_cmd = (0, 1, 1) with sun_B = (0, big, big) gave sigma_BR =
// NaN under OK (|sun_B| overflowed).  sun_B is used by direction only now:
// aligned, so sigma_BR = 0 and the angle 0, all finite.
// Verifies: REQ-GSUN-006
TEST_F(GuidSunsafe, Issue13HugeSunVectorIsUsedByDirection)
{
  const double big = 0.85 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  gref::set3(cfg_.s_cmd_B, 0.0, 1.0, 1.0);
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
  gref::set3(in_.sun_B, 0.0, big, big);
  gref::set3(in_.omega_BN_B, 0.0, 0.0, 0.0);
  EXPECT_EQ(FSW_OK, run());
  for (int i = 0; i < 3; i++) {
    EXPECT_TRUE(std::isfinite(out_.guid.sigma_BR[i]));
    EXPECT_NEAR(0.0, out_.guid.sigma_BR[i], kt::tol(1e-15, 1e-6));
  }
  EXPECT_TRUE(std::isfinite(out_.sun_angle_err));
  // and at 90 degrees: the same guidance as for the unit heading
  gref::set3(in_.sun_B, big, 0.0, 0.0);
  EXPECT_EQ(FSW_OK, run());
  const FswGuidSunsafeOut huge = out_;
  gref::set3(in_.sun_B, 1.0, 0.0, 0.0);
  EXPECT_EQ(FSW_OK, run());
  for (int i = 0; i < 3; i++) EXPECT_EQ(out_.guid.sigma_BR[i], huge.guid.sigma_BR[i]);
  EXPECT_NEAR(gref::kPi / 2, huge.sun_angle_err, kt::tol(1e-15, 1e-6));
}

// Finding 5: check accepted s_cmd = (big, big, 0), whose norm overflows, and
// init stored a zero axis (sigma_BR = 0 under OK with the Sun at 90 deg).
// Now |s_cmd_B| is bounded by FSW_GUID_SUNSAFE_S_CMD_MAX.
// Verifies: REQ-GSUN-004
TEST_F(GuidSunsafe, Issue13CommandedAxisIsBounded)
{
  const double big = 0.85 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  gref::set3(cfg_.s_cmd_B, big, big, 0.0);
  EXPECT_EQ(FSW_E_CONFIG, fsw_guid_sunsafe_check(&cfg_));
  EXPECT_EQ(FSW_E_CONFIG, fsw_guid_sunsafe_init(&st_, &cfg_));
  gref::set3(cfg_.s_cmd_B, 7.0, 7.0, 0.0);  // |s_cmd| = 9.9: accepted, unit axis
  ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_, &cfg_));
  EXPECT_NEAR(1.0, fsw_v3_norm(st_.s_cmd_hat_B), kt::tol(1e-15, 1e-6));
  gref::set3(in_.sun_B, 0.0, 0.0, 1.0);  // 90 degrees
  EXPECT_EQ(FSW_OK, run());
  EXPECT_NEAR(std::tan(gref::kPi / 8), fsw_v3_norm(out_.guid.sigma_BR), kt::tol(1e-15, 1e-6));
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(GuidSunsafeIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("guid_sunsafe", fsw_guid_sunsafe_check, fsw_guid_sunsafe_init, fsw_guid_sunsafe_reset, fsw_guid_sunsafe_update);
}

// fsw_acs calls the guidance without the update's input checks (its Sun
// heading is the sensor estimate's, finite, and its body rate is checked
// before any stage runs): for every finite input the output, the status and
// the health record are the update's, bit for bit, over seeded headings of
// every size (0, below min_unit_mag, tiny, unit, huge), headings inside the
// dead band and near the antiparallel, and body rates up to the largest
// finite real.
// Verifies: REQ-GSUN-001
TEST(GuidSunsafePoint, PointOfACheckedInputIsTheUpdate)
{
  kt::Rng rng(0x5eed0045u);
  const double big = kt::kFloat ? 3.4e38 : 1.79e308;
  const double mags[] = {0.0, 0.05, 1e-30, 1.0, 1.0, 1.0, 3.0, 1e30, big};
  int seen_valid = 0, seen_search = 0, seen_band = 0, seen_e180 = 0;
  for (int cset = 0; cset < 4; cset++) {
    FswGuidSunsafeConfig c{};
    double s_cmd[3];
    rng.unit3(s_cmd);
    gref::set3(c.s_cmd_B, s_cmd[0] * (1.0 + cset), s_cmd[1] * (1.0 + cset), s_cmd[2] * (1.0 + cset));
    c.min_unit_mag = static_cast<fsw_real>(cset == 3 ? 0.0 : 0.1);
    c.small_angle = static_cast<fsw_real>(cset * 0.2);
    gref::set3(c.omega_search_B, 0.01, -0.02, 0.03 * cset);
    c.sun_axis_spin_rate = static_cast<fsw_real>(cset == 2 ? -10.0 : 0.05 * cset);
    FswGuidSunsafeState st_u{}, st_p{};
    ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_u, &c));
    ASSERT_EQ(FSW_OK, fsw_guid_sunsafe_init(&st_p, &c));
    for (int t = 0; t < 1500; t++) {
      FswGuidSunsafeIn in{};
      double u[3];
      rng.unit3(u);
      if (t % 7 == 3) {  // about the commanded axis or its opposite (dead band, e180)
        const double sgn = (t % 2 == 0) ? 1.0 : -1.0;
        for (int i = 0; i < 3; i++) u[i] = sgn * s_cmd[i] + rng.uniform(-1e-3, 1e-3) * (t % 3);
      }
      const double m = mags[rng.uniform_int(0, 8)];
      gref::set3(in.sun_B, u[0] * m, u[1] * m, u[2] * m);
      const double w = (t % 11 == 0) ? big : 0.1;
      gref::set3(in.omega_BN_B, rng.uniform(-w, w), rng.uniform(-w, w), rng.uniform(-w, w));
      FswGuidSunsafeOut out_u{}, out_p{};
      const FswStatus su = fsw_guid_sunsafe_update(&st_u, &c, &in, &out_u);
      const FswStatus sp = fsw_guid_sunsafe_point(&st_p, &c, &in, &out_p);
      ASSERT_EQ(su, sp) << cset << " " << t;
      ASSERT_EQ(0, std::memcmp(&out_u, &out_p, sizeof out_u)) << cset << " " << t;
      ASSERT_EQ(0, std::memcmp(&st_u, &st_p, sizeof st_u)) << cset << " " << t;
      seen_valid += out_u.sun_valid;
      seen_search += (out_u.sun_valid == 0);
      seen_band += (out_u.sun_valid && out_u.guid.sigma_BR[0] == FSW_R(0.0) &&
                    out_u.guid.sigma_BR[1] == FSW_R(0.0) && out_u.guid.sigma_BR[2] == FSW_R(0.0));
      seen_e180 += (out_u.sun_valid && out_u.sun_angle_err > 3.0);
    }
  }
  EXPECT_GT(seen_valid, 1000);
  EXPECT_GT(seen_search, 100);
  EXPECT_GT(seen_band, 10);
  EXPECT_GT(seen_e180, 10);
  // a state that is not ready: FSW_E_NOT_INIT and the safe output, as the update
  FswGuidSunsafeConfig c{};
  gref::set3(c.s_cmd_B, 1.0, 0.0, 0.0);
  FswGuidSunsafeState idle{};
  FswGuidSunsafeIn in{};
  FswGuidSunsafeOut out{};
  out.sun_valid = 1;
  EXPECT_EQ(FSW_E_NOT_INIT, fsw_guid_sunsafe_point(&idle, &c, &in, &out));
  EXPECT_EQ(0, out.sun_valid);
  EXPECT_EQ(1u, idle.health.calls);
}

// rw_sat: wheel torque saturation (docs/fsw/rw_sat.md).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fsw/rw_sat.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {
struct Fixture {
  std::unique_ptr<FswRwSatConfig> cfg = rwt::make0<FswRwSatConfig>();
  std::unique_ptr<FswRwSatState> st = rwt::make0<FswRwSatState>();
  std::unique_ptr<FswRwSatIn> in = rwt::make0<FswRwSatIn>();
  std::unique_ptr<FswRwSatOut> out = rwt::make0<FswRwSatOut>();
  explicit Fixture(int n = 4, int mode = FSW_RW_SAT_SCALE)
  {
    cfg->num_rw = n;
    cfg->mode = mode;
    for (int i = 0; i < n; i++) cfg->u_max[i] = FSW_R(0.1);
    EXPECT_EQ(fsw_rw_sat_init(st.get(), cfg.get()), FSW_OK);
  }
  FswStatus update() { return fsw_rw_sat_update(st.get(), cfg.get(), in.get(), out.get()); }
  void set(const double* u, int n)
  {
    for (int i = 0; i < n; i++) in->u_s[i] = static_cast<fsw_real>(u[i]);
  }
};
}  // namespace

// Verifies: REQ-RWSAT-001
TEST(RwSatConfig, RejectsBadConfigurationsTableDriven)
{
  const struct {
    const char* why;
    void (*spoil)(FswRwSatConfig*);
    FswStatus want;
  } rows[] = {
      {"no wheels", [](FswRwSatConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many", [](FswRwSatConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"limit zero", [](FswRwSatConfig* c) { c->u_max[2] = 0; }, FSW_E_CONFIG},
      {"limit NaN", [](FswRwSatConfig* c) { c->u_max[0] = std::numeric_limits<fsw_real>::quiet_NaN(); }, FSW_E_CONFIG},
      {"limit Inf", [](FswRwSatConfig* c) { c->u_max[1] = std::numeric_limits<fsw_real>::infinity(); }, FSW_E_CONFIG},
      {"mode 2", [](FswRwSatConfig* c) { c->mode = 2; }, FSW_E_CONFIG},
  };
  for (const auto& r : rows) {
    Fixture f;
    r.spoil(f.cfg.get());
    EXPECT_EQ(fsw_rw_sat_check(f.cfg.get()), r.want) << r.why;
    EXPECT_EQ(fsw_rw_sat_init(f.st.get(), f.cfg.get()), r.want) << r.why;
    f.in->u_s[0] = 1;
    EXPECT_EQ(f.update(), FSW_E_NOT_INIT);
    EXPECT_EQ(f.out->u_s[0], 0.0);
  }
}

// u = (0.2, -0.05, 0.1, 0), u_max = 0.1: s = max |u|/u_max = 2.
// SCALE: u/2 = (0.1, -0.025, 0.05, 0).  CLIP: (0.1, -0.05, 0.1, 0).
// Verifies: REQ-RWSAT-002
TEST(RwSatNominal, ScaleAndClipByHand)
{
  const double u[4] = {0.2, -0.05, 0.1, 0};
  Fixture s(4, FSW_RW_SAT_SCALE), c(4, FSW_RW_SAT_CLIP);
  s.set(u, 4);
  c.set(u, 4);
  EXPECT_EQ(s.update(), FSW_W_SAT);
  EXPECT_EQ(c.update(), FSW_W_SAT);
  const double ws[4] = {0.1, -0.025, 0.05, 0}, wc[4] = {0.1, -0.05, 0.1, 0};
  for (int i = 0; i < 4; i++) {
    EXPECT_NEAR(s.out->u_s[i], ws[i], kt::tol(1e-17, 1e-8)) << i;
    EXPECT_NEAR(c.out->u_s[i], wc[i], kt::tol(1e-17, 1e-8)) << i;
  }
  EXPECT_EQ(s.st->health.saturated, 1u);
  // inside the limits: unchanged, OK
  const double v[4] = {0.1, -0.1, 0.03, 0};
  s.set(v, 4);
  EXPECT_EQ(s.update(), FSW_OK);
  for (int i = 0; i < 4; i++) EXPECT_EQ(s.out->u_s[i], s.in->u_s[i]);
}

// An unavailable wheel is 0 and does not set the scale.
// Verifies: REQ-RWSAT-003
TEST(RwSatNominal, UnavailableWheelIsZeroAndIgnored)
{
  const double u[4] = {0.05, 5.0, -0.02, 0.01};
  Fixture f;
  f.set(u, 4);
  f.in->avail[1] = FSW_UNAVAILABLE;
  for (int i = 0; i < FSW_MAX_RW; i++) f.out->u_s[i] = 9;
  EXPECT_EQ(f.update(), FSW_OK);
  EXPECT_EQ(f.out->u_s[1], 0.0);
  EXPECT_EQ(f.out->u_s[0], f.in->u_s[0]);
  for (int i = 4; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->u_s[i], 0.0);
}

// Verifies: REQ-RWSAT-004
TEST(RwSatBadInput, NonFiniteOrBadMaskGivesZeros)
{
  for (int row = 0; row < 3; row++) {
    Fixture f;
    f.in->u_s[0] = FSW_R(0.05);
    if (row == 0) f.in->u_s[2] = std::numeric_limits<fsw_real>::quiet_NaN();
    if (row == 1) f.in->u_s[3] = -std::numeric_limits<fsw_real>::infinity();
    if (row == 2) f.in->avail[1] = 2;
    EXPECT_EQ(f.update(), FSW_E_BAD_INPUT);
    for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->u_s[i], 0.0);
    EXPECT_EQ(f.st->health.bad_input, 1u);
  }
  Fixture f;
  kestrel_assert_reset();
  EXPECT_EQ(fsw_rw_sat_update(f.st.get(), nullptr, f.in.get(), f.out.get()), FSW_E_NULL_ARG);
  EXPECT_EQ(kestrel_assert_count(), 1u);
  kestrel_assert_reset();
}

// Verifies: REQ-RWSAT-005
TEST(RwSatRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  Fixture f;
  fsw_real first[4];
  for (int pass = 0; pass < 2; pass++) {
    const double u[4] = {0.3, -0.1, 0.2, 0.05};
    f.set(u, 4);
    (void)f.update();
    for (int i = 0; i < 4; i++) {
      if (pass == 0) first[i] = f.out->u_s[i];
      else EXPECT_EQ(f.out->u_s[i], first[i]);
    }
    fsw_rw_sat_reset(f.st.get());
  }
}

// Properties (3, 4, 6, 36 wheels, random limits and torques): every output
// within its limit; SCALE keeps the direction (u_out = u / s, with s from an
// independent max); CLIP changes only the entries beyond their limit.
class RwSatProperties : public ::testing::TestWithParam<int> {};
// Verifies: REQ-RWSAT-002, REQ-RWSAT-006
TEST_P(RwSatProperties, LimitsDirectionAndClip)
{
  const int n = GetParam();
  kt::Rng rng(5000u + uint64_t(n));
  for (int trial = 0; trial < 40; trial++) {
    Fixture s(n, FSW_RW_SAT_SCALE), c(n, FSW_RW_SAT_CLIP);
    double smax = 0;
    for (int i = 0; i < n; i++) {
      s.cfg->u_max[i] = c.cfg->u_max[i] = static_cast<fsw_real>(rng.uniform(0.01, 0.5));
      s.in->u_s[i] = c.in->u_s[i] = static_cast<fsw_real>(rng.normal() * 0.3);
      smax = std::fmax(smax, std::fabs(double(s.in->u_s[i])) / double(s.cfg->u_max[i]));
    }
    ASSERT_EQ(fsw_rw_sat_init(s.st.get(), s.cfg.get()), FSW_OK);
    ASSERT_EQ(fsw_rw_sat_init(c.st.get(), c.cfg.get()), FSW_OK);
    EXPECT_EQ(s.update(), smax > 1 ? FSW_W_SAT : FSW_OK);
    EXPECT_EQ(c.update(), smax > 1 ? FSW_W_SAT : FSW_OK);
    for (int i = 0; i < n; i++) {
      const double u = double(s.in->u_s[i]), um = double(s.cfg->u_max[i]);
      EXPECT_LE(std::fabs(s.out->u_s[i]), s.cfg->u_max[i]);
      EXPECT_LE(std::fabs(c.out->u_s[i]), c.cfg->u_max[i]);
      EXPECT_NEAR(s.out->u_s[i], smax > 1 ? u / smax : u, kt::tol(1e-15, 1e-6) * std::fabs(u) + 1e-300);
      EXPECT_EQ(double(c.out->u_s[i]), std::fabs(u) > um ? std::copysign(um, u) : u);
    }
  }
}
INSTANTIATE_TEST_SUITE_P(Wheels, RwSatProperties, ::testing::ValuesIn(rwt::kCounts));

// The bound holds in IEEE arithmetic, not only for real numbers (docs/eva.md,
// "WP proofs"): a torque one ulp above its limit gives a rounded ratio above
// 1 (FSW_W_SAT, scaled or clipped to within the limit, the sign kept); a
// torque at its limit, a ratio of exactly 1 (FSW_OK, unchanged).  Limits just
// below a power of two (where a ratio of neighbours is closest to 1), 1, 0.1,
// a subnormal and a huge one, in both modes and both signs.
// Verifies: REQ-RWSAT-006
TEST(RwSatBound, OneUlpAboveTheLimitIsLimitedAtTheLimitIsNot)
{
  using lim = std::numeric_limits<fsw_real>;
  const fsw_real limits[] = {FSW_R(0.1), FSW_R(1.0), std::nextafter(FSW_R(1.0), FSW_R(0.0)),
                             std::nextafter(FSW_R(2.0), FSW_R(0.0)), lim::denorm_min() * 3,
                             lim::max() / 2};
  for (int mode : {FSW_RW_SAT_SCALE, FSW_RW_SAT_CLIP}) {
    for (fsw_real um : limits) {
      for (fsw_real sign : {FSW_R(1.0), FSW_R(-1.0)}) {
        Fixture f(1, mode);
        f.cfg->u_max[0] = um;
        f.in->u_s[0] = sign * um;
        EXPECT_EQ(f.update(), FSW_OK) << um;
        EXPECT_EQ(f.out->u_s[0], sign * um) << um;
        f.in->u_s[0] = sign * std::nextafter(um, lim::infinity());
        EXPECT_EQ(f.update(), FSW_W_SAT) << um;
        EXPECT_LE(std::fabs(f.out->u_s[0]), um) << um;
        EXPECT_GT(sign * f.out->u_s[0], FSW_R(0.0)) << um;
      }
    }
  }
}

// Issue 21: one wheel is a legal configuration (num_rw >= 1).  u = 0.25,
// u_max = 0.1: s = 2.5, SCALE and CLIP both give 0.1 (a single wheel has no
// direction to keep); u = -0.04 is inside: unchanged, OK.
// Verifies: REQ-RWSAT-001, REQ-RWSAT-002
TEST(RwSatIssue21, SingleWheelIsAcceptedAndLimited)
{
  for (int mode : {FSW_RW_SAT_SCALE, FSW_RW_SAT_CLIP}) {
    Fixture f(1, mode);
    EXPECT_EQ(fsw_rw_sat_check(f.cfg.get()), FSW_OK) << mode;
    ASSERT_EQ(f.st->ready, 1) << mode;
    const double u[1] = {0.25};
    f.set(u, 1);
    EXPECT_EQ(f.update(), FSW_W_SAT) << mode;
    EXPECT_NEAR(f.out->u_s[0], 0.1, kt::tol(1e-17, 1e-8)) << mode;
    for (int i = 1; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->u_s[i], 0.0);
    const double v[1] = {-0.04};
    f.set(v, 1);
    EXPECT_EQ(f.update(), FSW_OK) << mode;
    EXPECT_EQ(f.out->u_s[0], f.in->u_s[0]) << mode;
  }
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(RwSatIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("rw_sat", fsw_rw_sat_check, fsw_rw_sat_init, fsw_rw_sat_reset, fsw_rw_sat_update);
}

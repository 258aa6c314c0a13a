// rw_volt: motor torque -> voltage with speed loop (docs/fsw/rw_volt.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/rw_volt.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {
constexpr uint64_t kDt = 100000000u;  // 0.1 s

struct Fixture {
  std::unique_ptr<FswRwVoltConfig> cfg = rwt::make0<FswRwVoltConfig>();
  std::unique_ptr<FswRwVoltState> st = rwt::make0<FswRwVoltState>();
  std::unique_ptr<FswRwVoltIn> in = rwt::make0<FswRwVoltIn>();
  std::unique_ptr<FswRwVoltOut> out = rwt::make0<FswRwVoltOut>();
  // V_min = 0.5 V, V_max = 10 V, u_max = 0.2 N*m, J_s = 0.01 kg m^2, K_V = 0.5
  explicit Fixture(int n = 4)
  {
    cfg->num_rw = n;
    cfg->V_min = FSW_R(0.5);
    cfg->V_max = FSW_R(10.0);
    cfg->K_V = FSW_R(0.5);
    for (int i = 0; i < n; i++) {
      cfg->u_max[i] = FSW_R(0.2);
      cfg->J_s[i] = FSW_R(0.01);
      cfg->Omega_dot_max[i] = FSW_R(20.0);
    }
    EXPECT_EQ(init(), FSW_OK);
  }
  FswStatus init() { return fsw_rw_volt_init(st.get(), cfg.get()); }
  FswStatus update(uint64_t t) {
    in->t_ns = t;
    return fsw_rw_volt_update(st.get(), cfg.get(), in.get(), out.get());
  }
};
// (V_max - V_min)/u_max = 47.5 V/(N*m)
double ff(double u) { return u > 0 ? 47.5 * u + 0.5 : (u < 0 ? 47.5 * u - 0.5 : 0.0); }
}  // namespace

// Verifies: REQ-RWVOLT-001
TEST(RwVoltConfig, RejectsBadConfigurationsTableDriven)
{
  const struct {
    const char* why;
    void (*spoil)(FswRwVoltConfig*);
    FswStatus want;
  } rows[] = {
      {"no wheels", [](FswRwVoltConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many", [](FswRwVoltConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"V_min negative", [](FswRwVoltConfig* c) { c->V_min = -1; }, FSW_E_CONFIG},
      // issue 21: each clause of the range checks
      {"V_min NaN", [](FswRwVoltConfig* c) { c->V_min = std::numeric_limits<fsw_real>::quiet_NaN(); }, FSW_E_CONFIG},
      {"V_max below V_min", [](FswRwVoltConfig* c) { c->V_max = c->V_min - 1; }, FSW_E_CONFIG},
      {"V_max above FSW_RW_V_MAX_MAX", [](FswRwVoltConfig* c) { c->V_max = 2 * FSW_RW_V_MAX_MAX; }, FSW_E_CONFIG},
      {"K_V NaN", [](FswRwVoltConfig* c) { c->K_V = std::numeric_limits<fsw_real>::quiet_NaN(); }, FSW_E_CONFIG},
      {"K_V above FSW_RW_GAIN_MAX", [](FswRwVoltConfig* c) { c->K_V = 2 * FSW_RW_GAIN_MAX; }, FSW_E_CONFIG},
      {"V_max = V_min", [](FswRwVoltConfig* c) { c->V_max = c->V_min; }, FSW_E_CONFIG},
      {"V_max NaN", [](FswRwVoltConfig* c) { c->V_max = std::numeric_limits<fsw_real>::quiet_NaN(); }, FSW_E_CONFIG},
      {"K_V negative", [](FswRwVoltConfig* c) { c->K_V = -1; }, FSW_E_CONFIG},
      {"K_V Inf", [](FswRwVoltConfig* c) { c->K_V = std::numeric_limits<fsw_real>::infinity(); }, FSW_E_CONFIG},
      {"u_max zero", [](FswRwVoltConfig* c) { c->u_max[3] = 0; }, FSW_E_CONFIG},
      {"J_s negative", [](FswRwVoltConfig* c) { c->J_s[0] = -1; }, FSW_E_CONFIG},
      {"gate flag 3", [](FswRwVoltConfig* c) { c->gate_rate = 3; }, FSW_E_CONFIG},
      {"gate with zero limit",
       [](FswRwVoltConfig* c) {
         c->gate_rate = 1;
         c->Omega_dot_max[2] = 0;
       },
       FSW_E_CONFIG},
  };
  for (const auto& r : rows) {
    Fixture f;
    r.spoil(f.cfg.get());
    EXPECT_EQ(fsw_rw_volt_check(f.cfg.get()), r.want) << r.why;
    EXPECT_EQ(f.init(), r.want) << r.why;
    f.in->u_s[0] = FSW_R(0.1);
    EXPECT_EQ(f.update(0), FSW_E_NOT_INIT);
    EXPECT_EQ(f.out->V[0], 0.0);
  }
}

// Feed-forward: V = 47.5 u +/- 0.5, exact 0 stays 0, clip at 10 V,
// unavailable wheel 0 V.
// Verifies: REQ-RWVOLT-002
TEST(RwVoltNominal, FeedForwardByHand)
{
  Fixture f(5);
  const double u[5] = {0.1, -0.02, 0.0, 0.5, 0.1};
  for (int i = 0; i < 5; i++) f.in->u_s[i] = static_cast<fsw_real>(u[i]);
  f.in->avail[4] = FSW_UNAVAILABLE;
  EXPECT_EQ(f.update(0), FSW_W_SAT);  // wheel 4 clipped
  EXPECT_NEAR(f.out->V[0], 5.25, kt::tol(1e-14, 1e-5));
  EXPECT_NEAR(f.out->V[1], -1.45, kt::tol(1e-14, 1e-5));
  EXPECT_EQ(f.out->V[2], 0.0);
  EXPECT_EQ(f.out->V[3], 10.0);
  EXPECT_EQ(f.out->V[4], 0.0);
  for (int i = 5; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->V[i], 0.0);
}

// Speed loop, u = 0.1, Omega = 100, 100, 100.5 rad/s at 0, 0.1, 0.2 s:
// call 1: p 0 -> 1; call 2: stores Omega, p -> 2; call 3: Omega_dot = 5,
// J Omega_dot = 0.05, u' = 0.1 - 0.5 (0.05 - 0.1) = 0.125, V = 47.5*0.125 + 0.5.
// Verifies: REQ-RWVOLT-003
TEST(RwVoltNominal, SpeedLoopWarmUpAndCorrection)
{
  Fixture f(1);
  f.in->u_s[0] = FSW_R(0.1);
  f.in->has_Omega = 1;
  f.in->Omega[0] = FSW_R(100.0);
  ASSERT_EQ(f.update(0), FSW_OK);
  EXPECT_NEAR(f.out->V[0], ff(0.1), kt::tol(1e-14, 1e-5));
  EXPECT_EQ(f.st->phase, 1);
  ASSERT_EQ(f.update(kDt), FSW_OK);
  EXPECT_NEAR(f.out->V[0], ff(0.1), kt::tol(1e-14, 1e-5));
  EXPECT_EQ(f.st->phase, 2);
  f.in->Omega[0] = FSW_R(100.5);
  ASSERT_EQ(f.update(2 * kDt), FSW_OK);
  EXPECT_NEAR(f.out->V[0], ff(0.125), kt::tol(1e-12, 1e-4));
  // a call without speeds restarts the warm-up
  f.in->has_Omega = 0;
  ASSERT_EQ(f.update(3 * kDt), FSW_OK);
  EXPECT_EQ(f.st->phase, 0);
  EXPECT_NEAR(f.out->V[0], ff(0.1), kt::tol(1e-14, 1e-5));
}

// Gate at 20 rad/s^2: a jump of 10 rad/s in 0.1 s (100 rad/s^2) is not used,
// bit 0 of fault is set, the feed-forward alone remains; Omega_prev still moves.
// Verifies: REQ-RWVOLT-004
TEST(RwVoltNominal, OutlierGateSkipsCorrection)
{
  Fixture f(2);
  f.cfg->gate_rate = 1;
  ASSERT_EQ(f.init(), FSW_OK);
  f.in->has_Omega = 1;
  f.in->u_s[0] = f.in->u_s[1] = FSW_R(0.1);
  f.in->Omega[0] = f.in->Omega[1] = FSW_R(100.0);
  ASSERT_EQ(f.update(0), FSW_OK);
  ASSERT_EQ(f.update(kDt), FSW_OK);
  f.in->Omega[0] = FSW_R(110.0);
  f.in->Omega[1] = FSW_R(100.5);
  ASSERT_EQ(f.update(2 * kDt), FSW_OK);
  EXPECT_EQ(f.out->fault, 1u);
  EXPECT_NEAR(f.out->V[0], ff(0.1), kt::tol(1e-14, 1e-5));
  EXPECT_NEAR(f.out->V[1], ff(0.125), kt::tol(1e-12, 1e-4));
  EXPECT_EQ(f.st->Omega_prev[0], FSW_R(110.0));
}

// docs/fsw/rw_volt.md: Omega_prev is stored for EVERY wheel.  Wheel 1 is unavailable for
// one call while its speed moves 100 -> 101 rad/s; back in service at
// 102 rad/s, its rate is (102 - 101)/0.1 = 10 rad/s^2 (from the sample taken
// while unavailable, not the 100 of before): u = 0.1 - 0.5 (0.01*10 - 0.1) = 0.1.
// With a stale 100 it would be 20 rad/s^2 and u = 0.05.  A NaN sample taken
// while unavailable (failed tachometer) is not read and skips one correction.
// Verifies: REQ-RWVOLT-003
TEST(RwVoltNominal, StoredSpeedOfUnavailableWheelIsUsedOnReturn)
{
  Fixture f(2);
  f.in->has_Omega = 1;
  f.in->u_s[0] = f.in->u_s[1] = FSW_R(0.1);
  f.in->Omega[0] = f.in->Omega[1] = FSW_R(100.0);
  ASSERT_EQ(f.update(0), FSW_OK);
  ASSERT_EQ(f.update(kDt), FSW_OK);
  f.in->avail[1] = FSW_UNAVAILABLE;
  f.in->Omega[1] = FSW_R(101.0);
  ASSERT_EQ(f.update(2 * kDt), FSW_OK);
  EXPECT_EQ(f.out->V[1], 0.0);
  f.in->avail[1] = FSW_AVAILABLE;
  f.in->Omega[1] = FSW_R(102.0);
  ASSERT_EQ(f.update(3 * kDt), FSW_OK);
  EXPECT_NEAR(f.out->V[1], ff(0.1), kt::tol(1e-12, 1e-4));
  // failed tachometer while unavailable: accepted, and no NaN on return
  f.in->avail[1] = FSW_UNAVAILABLE;
  f.in->Omega[1] = std::numeric_limits<fsw_real>::quiet_NaN();
  ASSERT_EQ(f.update(4 * kDt), FSW_OK);
  f.in->avail[1] = FSW_AVAILABLE;
  f.in->Omega[1] = FSW_R(50.0);
  ASSERT_EQ(f.update(5 * kDt), FSW_OK);
  EXPECT_NEAR(f.out->V[1], ff(0.1), kt::tol(1e-14, 1e-5));  // correction skipped once
  f.in->Omega[1] = FSW_R(50.5);                              // 5 rad/s^2 -> u = 0.1 - 0.5 (0.05 - 0.1)
  ASSERT_EQ(f.update(6 * kDt), FSW_OK);
  EXPECT_NEAR(f.out->V[1], ff(0.125), kt::tol(1e-12, 1e-4));
}

// Verifies: REQ-RWVOLT-006
TEST(RwVoltBadInput, NonFiniteBadFlagsAndTime)
{
  for (int row = 0; row < 4; row++) {
    Fixture f;
    f.in->u_s[0] = FSW_R(0.1);
    f.in->has_Omega = 1;
    if (row == 0) f.in->u_s[1] = std::numeric_limits<fsw_real>::quiet_NaN();
    if (row == 1) f.in->Omega[2] = std::numeric_limits<fsw_real>::infinity();
    if (row == 2) f.in->has_Omega = 2;
    if (row == 3) f.in->avail[0] = 7;
    EXPECT_EQ(f.update(0), FSW_E_BAD_INPUT) << row;
    for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->V[i], 0.0);
    EXPECT_EQ(f.st->phase, 0);
    EXPECT_EQ(f.st->clock.has_prev, 0);
    EXPECT_EQ(f.st->health.bad_input, 1u) << row;
  }
  // mid-loop (phase 2, speeds stored): a bad call changes no state at all
  {
    Fixture f(2);
    f.in->has_Omega = 1;
    f.in->u_s[0] = FSW_R(0.1);
    f.in->Omega[0] = FSW_R(100.0);
    f.in->Omega[1] = FSW_R(-50.0);
    ASSERT_EQ(f.update(0), FSW_OK);
    ASSERT_EQ(f.update(kDt), FSW_OK);
    ASSERT_EQ(f.st->phase, 2);
    f.in->Omega[1] = std::numeric_limits<fsw_real>::quiet_NaN();
    EXPECT_EQ(f.update(2 * kDt), FSW_E_BAD_INPUT);
    EXPECT_EQ(f.st->phase, 2);
    EXPECT_EQ(f.st->Omega_prev[0], FSW_R(100.0));
    EXPECT_EQ(f.st->Omega_prev[1], FSW_R(-50.0));
    EXPECT_EQ(f.st->clock.t_prev_ns, kDt);
    EXPECT_EQ(f.st->health.bad_input, 1u);
    for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->V[i], 0.0);
  }
  // NaN speeds are ignored when not supplied
  Fixture g;
  g.in->Omega[0] = std::numeric_limits<fsw_real>::quiet_NaN();
  EXPECT_EQ(g.update(0), FSW_OK);
  // time must increase
  Fixture h;
  h.in->has_Omega = 1;
  ASSERT_EQ(h.update(5 * kDt), FSW_OK);
  h.in->u_s[0] = FSW_R(0.1);
  EXPECT_EQ(h.update(5 * kDt), FSW_E_TIME);
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(h.out->V[i], 0.0);
  EXPECT_EQ(h.update(4 * kDt), FSW_E_TIME);
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(h.out->V[i], 0.0);
  EXPECT_EQ(h.st->phase, 1);
  EXPECT_EQ(h.st->clock.t_prev_ns, 5 * kDt);
  EXPECT_EQ(h.st->health.bad_time, 2u);
}

// Verifies: REQ-GEN-007
TEST(RwVoltBadInput, NullArgumentsAssertAndReturn)
{
  Fixture f;
  kestrel_assert_reset();
  EXPECT_EQ(fsw_rw_volt_update(f.st.get(), f.cfg.get(), nullptr, f.out.get()), FSW_E_NULL_ARG);
  EXPECT_EQ(f.out->V[0], 0.0);
  EXPECT_EQ(kestrel_assert_count(), 1u);
  kestrel_assert_reset();
}

// Verifies: REQ-RWVOLT-007
TEST(RwVoltRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  Fixture f;
  fsw_real first[8][4];
  for (int pass = 0; pass < 2; pass++) {
    kt::Rng r(21);
    f.in->has_Omega = 1;
    for (int k = 0; k < 8; k++) {
      for (int i = 0; i < 4; i++) {
        f.in->u_s[i] = static_cast<fsw_real>(r.uniform(-0.2, 0.2));
        f.in->Omega[i] = static_cast<fsw_real>(r.uniform(-100, 100));
      }
      ASSERT_GE(f.update(uint64_t(k) * kDt), FSW_OK);
      for (int i = 0; i < 4; i++) {
        if (pass == 0) first[k][i] = f.out->V[i];
        else EXPECT_EQ(f.out->V[i], first[k][i]);
      }
    }
    fsw_rw_volt_reset(f.st.get());
  }
}

// Properties, 3/4/6/36 wheels: |V| <= V_max, sign(V) = sign(u) without the
// loop, |V| >= V_min for u != 0, unavailable wheels exactly 0.
class RwVoltProperties : public ::testing::TestWithParam<int> {};
// Verifies: REQ-RWVOLT-005, REQ-RWVOLT-002
TEST_P(RwVoltProperties, BoundsSignAndAvailability)
{
  const int n = GetParam();
  kt::Rng rng(6000u + uint64_t(n));
  Fixture f(n);
  for (int k = 0; k < 30; k++) {
    for (int i = 0; i < n; i++) {
      f.in->u_s[i] = static_cast<fsw_real>(rng.normal() * 0.2);
      f.in->avail[i] = rng.uniform() < 0.2 ? FSW_UNAVAILABLE : FSW_AVAILABLE;
    }
    ASSERT_GE(f.update(uint64_t(k) * kDt), FSW_OK);
    for (int i = 0; i < n; i++) {
      const double V = f.out->V[i], u = f.in->u_s[i];
      EXPECT_LE(std::fabs(V), 10.0);
      if (f.in->avail[i]) {
        EXPECT_EQ(V, 0.0);
      } else {
        EXPECT_EQ(V > 0, u > 0);
        EXPECT_GE(std::fabs(V), 0.5);
        EXPECT_NEAR(V, std::fmax(-10.0, std::fmin(10.0, ff(u))), kt::tol(1e-13, 1e-4));
      }
    }
  }
}
INSTANTIATE_TEST_SUITE_P(Wheels, RwVoltProperties, ::testing::ValuesIn(rwt::kCounts));

// ---- issue 13: the contract for every input -------------------------------

// Finding 3: a one-cycle speed glitch of ~ -max then 10 rad/s made the rate
// (and the correction) overflow: V = NaN under OK.  Now that wheel is an
// outlier (fault bit, no correction) and every voltage stays finite; the
// next call runs the loop normally.  Also with K_V = 0 (0 * inf).
// Verifies: REQ-RWVOLT-004
TEST(RwVoltIssue13, SpeedGlitchOverflowIsAnOutlierNotNaN)
{
  const double big = 0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  for (double kv : {0.5, 0.0}) {
    Fixture f(1);
    f.cfg->K_V = static_cast<fsw_real>(kv);
    ASSERT_EQ(FSW_OK, f.init());
    f.in->has_Omega = 1;
    f.in->u_s[0] = FSW_R(0.05);
    f.in->Omega[0] = FSW_R(0.0);
    EXPECT_FALSE(fsw_status_is_error(f.update(kDt)));
    f.in->Omega[0] = static_cast<fsw_real>(-big);
    EXPECT_FALSE(fsw_status_is_error(f.update(2 * kDt)));
    f.in->Omega[0] = FSW_R(10.0);
    const FswStatus s = f.update(3 * kDt);
    EXPECT_FALSE(fsw_status_is_error(s));
    EXPECT_TRUE(std::isfinite(f.out->V[0])) << kv;
    EXPECT_LE(std::fabs(f.out->V[0]), 10.0);
    EXPECT_EQ(1u, f.out->fault & 1u);
    EXPECT_EQ(static_cast<fsw_real>(ff(0.05)), f.out->V[0]);  // no correction
    EXPECT_FALSE(fsw_status_is_error(f.update(4 * kDt)));   // loop goes on
    EXPECT_EQ(0u, f.out->fault);
    EXPECT_TRUE(std::isfinite(f.out->V[0]));
  }
}

// Finding 3: J_s ~ max and u_max ~ min (accepted before, NaN with ordinary
// speeds or with u = 0) are outside the physical ranges: refused by check.
// Verifies: REQ-RWVOLT-001
TEST(RwVoltIssue13, ConfigRangesKeepProductsFinite)
{
  Fixture f(2);
  f.cfg->J_s[1] = static_cast<fsw_real>(0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  EXPECT_EQ(FSW_E_CONFIG, fsw_rw_volt_check(f.cfg.get()));
  f.cfg->J_s[1] = FSW_R(0.01);
  f.cfg->u_max[0] = std::numeric_limits<fsw_real>::min();
  EXPECT_EQ(FSW_E_CONFIG, fsw_rw_volt_check(f.cfg.get()));
  f.cfg->u_max[0] = FSW_RW_U_MAX_MIN;
  ASSERT_EQ(FSW_OK, f.init());
  f.in->u_s[0] = FSW_R(0.0);
  f.in->u_s[1] = FSW_R(0.1);
  EXPECT_FALSE(fsw_status_is_error(f.update(kDt)));
  EXPECT_EQ(0.0, f.out->V[0]);
  EXPECT_TRUE(std::isfinite(f.out->V[1]));
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(RwVoltIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("rw_volt", fsw_rw_volt_check, fsw_rw_volt_init, fsw_rw_volt_reset, fsw_rw_volt_update);
}

// Issue 21: the V_max range is inclusive (rw_volt.h: "> V_min, <=
// FSW_RW_V_MAX_MAX"): V_max equal to FSW_RW_V_MAX_MAX is accepted and a
// command of u_max then gives exactly that voltage, (V_max - V_min)/u_max *
// u_max + V_min = V_max (to rounding); the next representable value above
// is refused.
// Verifies: REQ-RWVOLT-001
TEST(RwVoltIssue21, VMaxEqualToTheLargestIsAccepted)
{
  Fixture f(2);
  f.cfg->V_max = FSW_RW_V_MAX_MAX;
  EXPECT_EQ(FSW_OK, fsw_rw_volt_check(f.cfg.get()));
  ASSERT_EQ(FSW_OK, f.init());
  f.in->u_s[0] = FSW_R(0.2);  // u_max
  f.in->u_s[1] = FSW_R(-0.1);  // half of -u_max: -(1e4 - 0.5)/2 - 0.5
  f.in->avail[0] = FSW_AVAILABLE;
  f.in->avail[1] = FSW_AVAILABLE;
  EXPECT_FALSE(fsw_status_is_error(f.update(0)));  // first call: feed-forward only
  const double V_max = static_cast<double>(FSW_RW_V_MAX_MAX);
  EXPECT_NEAR(V_max, f.out->V[0], V_max * kt::tol(1e-12, 1e-6));
  EXPECT_LE(f.out->V[0], FSW_RW_V_MAX_MAX);
  EXPECT_NEAR(-(V_max - 0.5) / 2 - 0.5, f.out->V[1], V_max * kt::tol(1e-12, 1e-6));
  f.cfg->V_max = std::nextafter(FSW_RW_V_MAX_MAX, 2 * FSW_RW_V_MAX_MAX);
  EXPECT_EQ(FSW_E_CONFIG, fsw_rw_volt_check(f.cfg.get()));
}

// rw_speed_filter: tachometer outlier rejection (library design, see
// docs/fsw/rw_speed_filter.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/rw_speed_filter.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {
constexpr uint64_t kDt = 100000000u;  // 0.1 s
const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();

// u_max/J_s = 0.2/0.02 = 10 rad/s^2, noise 0.5 rad/s: bound over 0.1 s = 1.5 rad/s.
struct Fixture {
  std::unique_ptr<FswRwSpeedFilterConfig> cfg = rwt::make0<FswRwSpeedFilterConfig>();
  std::unique_ptr<FswRwSpeedFilterState> st = rwt::make0<FswRwSpeedFilterState>();
  std::unique_ptr<FswRwSpeedFilterIn> in = rwt::make0<FswRwSpeedFilterIn>();
  std::unique_ptr<FswRwSpeedFilterOut> out = rwt::make0<FswRwSpeedFilterOut>();
  explicit Fixture(int n = 1)
  {
    cfg->num_rw = n;
    for (int i = 0; i < n; i++) {
      cfg->u_max[i] = FSW_R(0.2);
      cfg->J_s[i] = FSW_R(0.02);
      cfg->noise[i] = FSW_R(0.5);
    }
    cfg->k_reject = 3;
    cfg->n_recover = 3;
    EXPECT_EQ(init(), FSW_OK);
  }
  FswStatus init() { return fsw_rw_speed_filter_init(st.get(), cfg.get()); }
  FswStatus step(uint64_t t, double w0)
  {
    in->t_ns = t;
    in->Omega_meas[0] = static_cast<fsw_real>(w0);
    return fsw_rw_speed_filter_update(st.get(), cfg.get(), in.get(), out.get());
  }
};
}  // namespace

// Verifies: REQ-RWSF-001
TEST(RwSpeedFilterConfig, RejectsBadConfigurationsTableDriven)
{
  const struct {
    const char* why;
    void (*spoil)(FswRwSpeedFilterConfig*);
    FswStatus want;
  } rows[] = {
      {"no wheels", [](FswRwSpeedFilterConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many", [](FswRwSpeedFilterConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"u_max zero", [](FswRwSpeedFilterConfig* c) { c->u_max[0] = 0; }, FSW_E_CONFIG},
      {"J_s NaN", [](FswRwSpeedFilterConfig* c) { c->J_s[0] = kNaN; }, FSW_E_CONFIG},
      {"noise negative", [](FswRwSpeedFilterConfig* c) { c->noise[0] = -1; }, FSW_E_CONFIG},
      {"noise Inf", [](FswRwSpeedFilterConfig* c) { c->noise[0] = std::numeric_limits<fsw_real>::infinity(); }, FSW_E_CONFIG},
      {"k_reject zero", [](FswRwSpeedFilterConfig* c) { c->k_reject = 0; }, FSW_E_CONFIG},
      {"n_recover zero", [](FswRwSpeedFilterConfig* c) { c->n_recover = 0; }, FSW_E_CONFIG},
  };
  for (const auto& r : rows) {
    Fixture f;
    r.spoil(f.cfg.get());
    EXPECT_EQ(fsw_rw_speed_filter_check(f.cfg.get()), r.want) << r.why;
    EXPECT_EQ(f.init(), r.want) << r.why;
    EXPECT_EQ(f.step(0, 100.0), FSW_E_NOT_INIT);
    EXPECT_EQ(f.out->Omega[0], 0.0);
  }
  Fixture f;
  f.cfg->noise[0] = 0;  // zero margin is allowed
  EXPECT_EQ(f.init(), FSW_OK);
}

// Bound over 0.1 s is 1.5 rad/s.  100 -> 101 -> 102.4 accepted; 150 rejected
// (held at 102.4); 104.0 at 0.4 s: bound since the last good (0.2 s) is
// 10*0.2 + 0.5 = 2.5 >= 1.6, accepted.
// Verifies: REQ-RWSF-002
TEST(RwSpeedFilterNominal, RejectHoldAndWideningBound)
{
  Fixture f;
  EXPECT_EQ(f.step(0, 100.0), FSW_OK);  // first sample: no reference, accepted
  EXPECT_EQ(f.step(kDt, 101.0), FSW_OK);
  EXPECT_EQ(f.step(2 * kDt, 102.4), FSW_OK);
  EXPECT_EQ(f.out->rejected, 0u);
  EXPECT_EQ(f.step(3 * kDt, 150.0), FSW_OK);
  EXPECT_EQ(f.out->rejected, 1u);
  EXPECT_EQ(f.out->Omega[0], FSW_R(102.4));
  EXPECT_EQ(f.out->avail[0], FSW_AVAILABLE);
  EXPECT_EQ(f.st->rejections[0], 1u);
  EXPECT_EQ(f.step(4 * kDt, 104.0), FSW_OK);
  EXPECT_EQ(f.out->rejected, 0u);
  EXPECT_EQ(f.out->Omega[0], FSW_R(104.0));
  // 1.6 rad/s in 0.1 s would have been rejected without the widening
  EXPECT_EQ(f.step(5 * kDt, 105.6), FSW_OK);
  EXPECT_EQ(f.out->rejected, 1u);
}

// Issue 45: a finite sample beyond +-FSW_RW_OMEGA_MAX (1e4 rad/s) is no
// speed.  As the first sample it is rejected (output 0, no reference);
// 1e4 itself is accepted.  A failed wheel does not recover on such samples,
// however consistent with each other: three equal 2e4 samples leave it
// failed, three in range bring it back.
// Verifies: REQ-RWSF-002
TEST(RwSpeedFilterNominal, Issue45SamplesBeyondTheSpeedRangeAreOutliers)
{
  {
    Fixture f;
    EXPECT_EQ(f.step(0, 10000.5), FSW_OK);
    EXPECT_EQ(f.out->rejected, 1u);
    EXPECT_EQ(f.out->Omega[0], FSW_R(0.0));
    EXPECT_EQ(f.step(kDt, -1e300), FSW_OK);
    EXPECT_EQ(f.out->rejected, 1u);
    EXPECT_EQ(f.out->Omega[0], FSW_R(0.0));
  }
  {
    Fixture f;
    EXPECT_EQ(f.step(0, -1e4), FSW_OK);
    EXPECT_EQ(f.out->rejected, 0u);
    EXPECT_EQ(f.out->Omega[0], FSW_R(-1e4));
  }
  Fixture f;
  ASSERT_EQ(f.step(0, 100.0), FSW_OK);
  for (int k = 1; k <= 3; k++) ASSERT_EQ(f.step(uint64_t(k) * kDt, 300.0 + k), FSW_OK);
  ASSERT_EQ(f.out->failed, 1u);
  for (int k = 4; k <= 6; k++) {
    ASSERT_EQ(f.step(uint64_t(k) * kDt, 20000.0), FSW_OK);
    EXPECT_EQ(f.out->failed, 1u) << k;
    EXPECT_EQ(f.out->Omega[0], FSW_R(100.0)) << k;  // held
  }
  for (int k = 7; k <= 9; k++) ASSERT_EQ(f.step(uint64_t(k) * kDt, 200.0 + 0.1 * (k - 7)), FSW_OK);
  EXPECT_EQ(f.out->failed, 0u);
  EXPECT_EQ(f.out->Omega[0], static_cast<fsw_real>(200.2));
}

// Issue 21 (seed 9001): a recovered wheel's reference is the recovery
// sample, at the recovery time.  Fail at 0.3 s (k_reject = 3), recover with
// 200, 200.5, 201 at 0.4-0.6 s (n_recover = 3).  At 0.7 s the bound is
// 10 rad/s^2 * 0.1 s + 0.5 = 1.5 rad/s from 201: 202.4 is accepted, 202.7
// rejected.  Measured from the last good sample before the failure (100 at
// 0 s, 0.7 s earlier) the bound would be 7.5 rad/s and 202.7 would pass.
// Verifies: REQ-RWSF-002
TEST(RwSpeedFilterNominal, Issue21RecoveryRestartsTheBoundAtTheRecoveryTime)
{
  for (const double next : {202.4, 202.7}) {
    Fixture f;
    ASSERT_EQ(f.step(0, 100.0), FSW_OK);
    ASSERT_EQ(f.step(kDt, 300.0), FSW_OK);
    ASSERT_EQ(f.step(2 * kDt, 300.0), FSW_OK);
    ASSERT_EQ(f.step(3 * kDt, 300.0), FSW_OK);
    ASSERT_EQ(f.out->failed, 1u);
    const double seq[3] = {200.0, 200.5, 201.0};
    for (int k = 0; k < 3; k++) ASSERT_EQ(f.step(uint64_t(4 + k) * kDt, seq[k]), FSW_OK);
    ASSERT_EQ(f.out->failed, 0u);
    ASSERT_EQ(f.out->Omega[0], FSW_R(201.0));
    ASSERT_EQ(f.step(7 * kDt, next), FSW_OK);
    if (next < 202.5) {
      EXPECT_EQ(f.out->rejected, 0u) << next;
      EXPECT_EQ(f.out->Omega[0], static_cast<fsw_real>(next));
    } else {
      EXPECT_EQ(f.out->rejected, 1u) << next;
      EXPECT_EQ(f.out->Omega[0], FSW_R(201.0));  // held
    }
  }
}

// k_reject = 3: three consecutive rejections (a NaN counts) mark the wheel
// unavailable; three mutually consistent samples bring it back at the latest.
// Verifies: REQ-RWSF-003
TEST(RwSpeedFilterNominal, FailAfterKAndRecoverAfterN)
{
  Fixture f;
  ASSERT_EQ(f.step(0, 100.0), FSW_OK);
  ASSERT_EQ(f.step(kDt, 300.0), FSW_OK);
  ASSERT_EQ(f.step(2 * kDt, kNaN), FSW_OK);
  EXPECT_EQ(f.out->avail[0], FSW_AVAILABLE);
  ASSERT_EQ(f.step(3 * kDt, -300.0), FSW_OK);
  EXPECT_EQ(f.out->avail[0], FSW_UNAVAILABLE);
  EXPECT_EQ(f.out->failed, 1u);
  EXPECT_EQ(f.out->Omega[0], FSW_R(100.0));
  EXPECT_EQ(f.st->rejections[0], 3u);
  // recovery chain: 200 (1), 200.5 (2), NaN breaks it, 201 (1), 201.5 (2), 202 (3)
  const double seq[6] = {200.0, 200.5, std::nan(""), 201.0, 201.5, 202.0};
  for (int k = 0; k < 6; k++) {
    ASSERT_EQ(f.step(uint64_t(4 + k) * kDt, seq[k]), FSW_OK);
    EXPECT_EQ(f.out->avail[0], k < 5 ? FSW_UNAVAILABLE : FSW_AVAILABLE) << k;
  }
  EXPECT_EQ(f.out->Omega[0], FSW_R(202.0));
  EXPECT_EQ(f.out->failed, 0u);
  EXPECT_EQ(f.st->rejections[0], 3u);  // samples while failed are not counted
  // an inconsistent sample while failed restarts the chain at 1
  Fixture g;
  g.cfg->k_reject = 1;
  g.cfg->n_recover = 2;
  ASSERT_EQ(g.init(), FSW_OK);
  ASSERT_EQ(g.step(0, 0.0), FSW_OK);
  ASSERT_EQ(g.step(kDt, 50.0), FSW_OK);
  EXPECT_EQ(g.out->failed, 1u);
  ASSERT_EQ(g.step(2 * kDt, 60.0), FSW_OK);  // chain 1
  ASSERT_EQ(g.step(3 * kDt, 80.0), FSW_OK);  // inconsistent: chain 1 again
  EXPECT_EQ(g.out->failed, 1u);
  ASSERT_EQ(g.step(4 * kDt, 80.5), FSW_OK);  // chain 2: back
  EXPECT_EQ(g.out->failed, 0u);
  EXPECT_EQ(g.out->Omega[0], FSW_R(80.5));
}

// Verifies: REQ-RWSF-004
TEST(RwSpeedFilterNominal, UpstreamMaskIsCombined)
{
  Fixture f(3);
  f.in->avail[1] = FSW_UNAVAILABLE;
  f.in->Omega_meas[1] = FSW_R(7.0);
  ASSERT_EQ(f.step(0, 1.0), FSW_OK);
  EXPECT_EQ(f.out->avail[0], FSW_AVAILABLE);
  EXPECT_EQ(f.out->avail[1], FSW_UNAVAILABLE);
  EXPECT_EQ(f.out->Omega[1], FSW_R(7.0));  // still screened and passed on
  for (int i = 3; i < FSW_MAX_RW; i++) {
    EXPECT_EQ(f.out->Omega[i], 0.0);
    EXPECT_EQ(f.out->avail[i], 0);
  }
}

// Verifies: REQ-RWSF-007
TEST(RwSpeedFilterBadInput, BadMaskAndTimeAdvanceNothing)
{
  Fixture f(2);
  ASSERT_EQ(f.step(kDt, 100.0), FSW_OK);
  f.in->avail[1] = 4;
  EXPECT_EQ(f.step(2 * kDt, 300.0), FSW_E_BAD_INPUT);
  EXPECT_EQ(f.out->Omega[0], FSW_R(100.0));  // held
  EXPECT_EQ(f.out->avail[0], FSW_UNAVAILABLE);
  EXPECT_EQ(f.out->avail[1], FSW_UNAVAILABLE);
  EXPECT_EQ(f.st->rejections[0], 0u);
  f.in->avail[1] = 0;
  EXPECT_EQ(f.step(kDt, 300.0), FSW_E_TIME);
  EXPECT_EQ(f.step(kDt / 2, 300.0), FSW_E_TIME);
  EXPECT_EQ(f.st->clock.t_prev_ns, kDt);
  EXPECT_EQ(f.st->reject_run[0], 0u);
  EXPECT_EQ(f.st->health.bad_time, 2u);
  EXPECT_EQ(f.st->health.bad_input, 1u);
  kestrel_assert_reset();
  EXPECT_EQ(fsw_rw_speed_filter_update(f.st.get(), f.cfg.get(), nullptr, f.out.get()), FSW_E_NULL_ARG);
  EXPECT_EQ(kestrel_assert_count(), 1u);
  kestrel_assert_reset();
}

// docs/fsw-conventions.md, "Reset and the output" "reset zeroes the output", read for a caller-owned
// output (docs/fsw-conventions.md): this module's safe output holds the last
// good speeds, but reset forgets them, so a bad input right after reset
// gives 0 speeds (all unavailable), not the values from before the reset.
// Verifies: REQ-RWSF-007
TEST(RwSpeedFilterBadInput, ResetThenBadInputGivesTheSafeOutputNotStaleValues)
{
  Fixture f(2);
  ASSERT_EQ(f.step(kDt, 100.0), FSW_OK);
  f.in->avail[1] = 4;
  ASSERT_EQ(f.step(2 * kDt, 100.0), FSW_E_BAD_INPUT);
  EXPECT_EQ(f.out->Omega[0], FSW_R(100.0));  // before reset: held (documented)
  fsw_rw_speed_filter_reset(f.st.get());
  EXPECT_EQ(f.step(3 * kDt, 100.0), FSW_E_BAD_INPUT);
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->Omega[i], FSW_R(0.0)) << i;
  EXPECT_EQ(f.out->avail[0], FSW_UNAVAILABLE);
  EXPECT_EQ(f.out->avail[1], FSW_UNAVAILABLE);
  EXPECT_EQ(f.out->rejected, 0u);
  EXPECT_EQ(f.st->clock.has_prev, 0);
}

// Verifies: REQ-RWSF-008
TEST(RwSpeedFilterRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  Fixture f(4);
  fsw_real first[30][4];
  uint64_t rej[30];
  for (int pass = 0; pass < 2; pass++) {
    kt::Rng r(77);
    for (int k = 0; k < 30; k++) {
      for (int i = 0; i < 4; i++)
        f.in->Omega_meas[i] = static_cast<fsw_real>(r.uniform() < 0.2 ? r.uniform(-500, 500) : 100 + 0.1 * k);
      f.in->t_ns = uint64_t(k) * kDt;
      ASSERT_EQ(fsw_rw_speed_filter_update(f.st.get(), f.cfg.get(), f.in.get(), f.out.get()), FSW_OK);
      if (pass == 0) rej[k] = f.out->rejected;
      else EXPECT_EQ(f.out->rejected, rej[k]);
      for (int i = 0; i < 4; i++) {
        if (pass == 0) first[k][i] = f.out->Omega[i];
        else EXPECT_EQ(f.out->Omega[i], first[k][i]);
      }
    }
    fsw_rw_speed_filter_reset(f.st.get());
  }
}

// Properties, 3/4/6/36 wheels: a speed history whose steps stay within the
// torque bound (random accelerations up to 90 % of u_max/J_s, noise within
// the margin) is never rejected; isolated spikes beyond bound + 1 rad/s are
// always rejected and the held value is the previous true sample.
class RwSpeedFilterProperties : public ::testing::TestWithParam<int> {};
// Verifies: REQ-RWSF-008
TEST_P(RwSpeedFilterProperties, PhysicalHistoriesPassAndSpikesAreCaught)
{
  const int n = GetParam();
  kt::Rng rng(7000u + uint64_t(n));
  Fixture f(n);
  f.cfg->k_reject = 2;
  for (int i = 0; i < n; i++) {
    f.cfg->u_max[i] = static_cast<fsw_real>(rng.uniform(0.05, 0.3));
    f.cfg->J_s[i] = static_cast<fsw_real>(rng.uniform(0.01, 0.1));
    f.cfg->noise[i] = static_cast<fsw_real>(rng.uniform(0.2, 1.0));
  }
  ASSERT_EQ(f.init(), FSW_OK);
  double w[FSW_MAX_RW];
  for (int i = 0; i < n; i++) w[i] = rng.uniform(-300, 300);
  for (int k = 0; k < 60; k++) {
    const bool spike_step = k % 5 == 4;
    const int spiked = rng.uniform_int(0, n - 1);
    for (int i = 0; i < n; i++) {
      const double amax = double(f.cfg->u_max[i]) / double(f.cfg->J_s[i]);
      const double noise = double(f.cfg->noise[i]);
      if (k > 0) w[i] += 0.9 * amax * 0.1 * rng.uniform(-1, 1);
      double meas = w[i] + 0.45 * noise * rng.uniform(-1, 1);
      if (spike_step && i == spiked) meas = w[i] + (rng.uniform() < 0.5 ? -1 : 1) * (amax * 0.2 + noise + 1.0);
      f.in->Omega_meas[i] = static_cast<fsw_real>(meas);
    }
    f.in->t_ns = uint64_t(k) * kDt;
    ASSERT_EQ(fsw_rw_speed_filter_update(f.st.get(), f.cfg.get(), f.in.get(), f.out.get()), FSW_OK);
    const uint64_t want = spike_step ? (uint64_t(1) << spiked) : 0u;
    EXPECT_EQ(f.out->rejected, want) << "n=" << n << " k=" << k;
    EXPECT_EQ(f.out->failed, 0u);
    for (int i = 0; i < n; i++) EXPECT_EQ(f.out->avail[i], FSW_AVAILABLE);
  }
}
INSTANTIATE_TEST_SUITE_P(Wheels, RwSpeedFilterProperties, ::testing::ValuesIn(rwt::kCounts));

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(RwSpeedFilterIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("rw_speed_filter", fsw_rw_speed_filter_check, fsw_rw_speed_filter_init, fsw_rw_speed_filter_reset, fsw_rw_speed_filter_update);
}

// ---- issue 14: the latched stale and torque-consistency tests ------------

// Verifies: REQ-RWSF-001
TEST(RwSpeedFilterConfig, TorqueToleranceIsCheckedOnlyWhenTheWindowIsOn)
{
  Fixture f(2);
  f.cfg->resid_tol[1] = kNaN;  // torque test off: not read
  EXPECT_EQ(fsw_rw_speed_filter_check(f.cfg.get()), FSW_OK);
  f.cfg->n_window = 5;
  EXPECT_EQ(fsw_rw_speed_filter_check(f.cfg.get()), FSW_E_CONFIG);
  f.cfg->resid_tol[1] = FSW_R(-0.1);
  EXPECT_EQ(fsw_rw_speed_filter_check(f.cfg.get()), FSW_E_CONFIG);
  f.cfg->resid_tol[1] = std::numeric_limits<fsw_real>::infinity();
  EXPECT_EQ(fsw_rw_speed_filter_check(f.cfg.get()), FSW_E_CONFIG);
  f.cfg->resid_tol[1] = FSW_R(0.0);  // zero tolerance is allowed
  EXPECT_EQ(fsw_rw_speed_filter_check(f.cfg.get()), FSW_OK);
}

// With the torque test on, the applied torques are inputs: not finite or
// beyond 2 u_max (0.4 N*m) is bad input with no state change; u_valid must
// be 0/1.  With the test off they are not read.
// Verifies: REQ-RWSF-007
TEST(RwSpeedFilterBadInput, AppliedTorqueOutOfRangeIsRejectedWithNoStateChange)
{
  Fixture f(2);
  f.in->u_applied[1] = kNaN;
  f.in->u_valid = 1;
  ASSERT_EQ(f.step(0, 100.0), FSW_OK);  // n_window = 0: not read
  f.cfg->n_window = 4;
  f.cfg->resid_tol[0] = f.cfg->resid_tol[1] = FSW_R(0.3);
  ASSERT_EQ(f.init(), FSW_OK);
  f.in->u_applied[1] = FSW_R(0.0);
  ASSERT_EQ(f.step(0, 100.0), FSW_OK);
  const FswRwSpeedFilterState before = *f.st;
  const fsw_real bad[] = {kNaN, FSW_R(0.41), FSW_R(-0.41), std::numeric_limits<fsw_real>::infinity()};
  for (fsw_real u : bad) {
    f.in->u_applied[1] = u;
    EXPECT_EQ(f.step(kDt, 100.0), FSW_E_BAD_INPUT) << u;
    EXPECT_EQ(f.out->avail[0], FSW_UNAVAILABLE);
    EXPECT_EQ(0, std::memcmp(&before.win_exp, &f.st->win_exp, sizeof before.win_exp));
    EXPECT_EQ(before.clock.t_prev_ns, f.st->clock.t_prev_ns);
  }
  f.in->u_applied[1] = FSW_R(0.4);  // 2 u_max exactly: allowed
  EXPECT_EQ(f.step(kDt, 100.0), FSW_OK);
  f.in->u_valid = 2;
  EXPECT_EQ(f.step(2 * kDt, 100.0), FSW_E_BAD_INPUT);
  f.in->u_applied[1] = kNaN;
  f.in->u_valid = 0;  // not known: not read
  EXPECT_EQ(f.step(2 * kDt, 100.0), FSW_OK);
}

// n_stale = 3: the fourth bit-identical sample in a row (three repeats)
// fails and latches the wheel; the outlier rule's recovery (n_recover = 3
// consistent samples) does not bring it back; reset does.  A tachometer
// that reads 100.5 twice and then moves is not stale.
// Verifies: REQ-RWSF-005
TEST(RwSpeedFilterStale, ThreeRepeatsLatchAFrozenTachometerUntilReset)
{
  Fixture f(2);
  f.cfg->n_stale = 3;
  ASSERT_EQ(f.init(), FSW_OK);
  const double w0[] = {100.0, 100.5, 100.5, 100.5, 100.6, 100.6, 100.6};
  for (int k = 0; k < 7; k++) {
    f.in->Omega_meas[1] = static_cast<fsw_real>(50.0 + 0.1 * k);
    ASSERT_EQ(f.step(uint64_t(k) * kDt, w0[k]), FSW_OK);
    EXPECT_EQ(f.out->latched, 0u) << k;
  }
  ASSERT_EQ(f.step(7 * kDt, 100.6), FSW_OK);  // third repeat of 100.6
  EXPECT_EQ(f.out->latched, 1u);
  EXPECT_EQ(f.out->failed, 1u);
  EXPECT_EQ(f.out->avail[0], FSW_UNAVAILABLE);
  EXPECT_EQ(f.out->avail[1], FSW_AVAILABLE);
  EXPECT_EQ(f.out->Omega[0], FSW_R(100.6));
  for (int k = 8; k < 20; k++) {  // live, mutually consistent samples again
    f.in->Omega_meas[1] = static_cast<fsw_real>(50.0 + 0.1 * k);
    ASSERT_EQ(f.step(uint64_t(k) * kDt, 100.6 + 0.1 * (k - 7)), FSW_OK);
    EXPECT_EQ(f.out->latched, 1u) << k;
    EXPECT_EQ(f.out->avail[0], FSW_UNAVAILABLE) << k;
    EXPECT_EQ(f.out->Omega[0], FSW_R(100.6)) << k;  // held
  }
  fsw_rw_speed_filter_reset(f.st.get());
  ASSERT_EQ(f.step(20 * kDt, 102.0), FSW_OK);
  EXPECT_EQ(f.out->latched, 0u);
  EXPECT_EQ(f.out->avail[0], FSW_AVAILABLE);
  EXPECT_EQ(f.out->Omega[0], FSW_R(102.0));
}

// Issue 39: the stale test compares bit for bit, as documented.  A zero
// reading that flips its sign every call (+0.0, -0.0, +0.0, ...) is equal
// under == but never repeats its bits: not stale, however long it lasts.
// The same zero with one sign repeated three times is (n_stale = 3).
// Verifies: REQ-RWSF-005
TEST(RwSpeedFilterStale, Issue39ASignFlippingZeroIsNotARepeat)
{
  Fixture f(2);
  f.cfg->n_stale = 3;
  ASSERT_EQ(f.init(), FSW_OK);
  int k = 0;
  for (; k < 10; k++) {
    f.in->Omega_meas[1] = static_cast<fsw_real>(50.0 + 0.1 * k);  // wheel 1 live
    ASSERT_EQ(f.step(uint64_t(k) * kDt, (k % 2) ? -0.0 : 0.0), FSW_OK);
    EXPECT_EQ(f.out->latched, 0u) << k;
    EXPECT_EQ(f.out->avail[0], FSW_AVAILABLE) << k;
  }
  EXPECT_EQ(f.st->stale_run[0], 0u);
  for (int rep = 0; rep < 3; rep++, k++) {  // -0.0 four times in a row: three repeats
    f.in->Omega_meas[1] = static_cast<fsw_real>(50.0 + 0.1 * k);
    ASSERT_EQ(f.step(uint64_t(k) * kDt, -0.0), FSW_OK);
  }
  EXPECT_EQ(f.out->latched, 1u);
  EXPECT_EQ(f.out->failed, 1u);
}

namespace {
// Torque test by hand: J_s = 0.02 kg*m^2, u = 0.1 N*m applied, calls every
// 0.1 s: the speed rises 0.1/0.02*0.1 = 0.5 rad/s per call.  n_window = 5
// calls, resid_tol = 0.3 rad/s.  The window opens on the first sample (k = 0)
// and closes clean at k = 5, 10, ...
struct TorqueFixture : Fixture {
  TorqueFixture() : Fixture(2)
  {
    cfg->n_window = 5;
    cfg->resid_tol[0] = cfg->resid_tol[1] = FSW_R(0.3);
    EXPECT_EQ(init(), FSW_OK);
    in->u_applied[0] = FSW_R(0.1);
    in->u_applied[1] = FSW_R(0.0);
    in->u_valid = 1;
  }
  FswStatus at(int k, double w0)
  {
    in->Omega_meas[1] = FSW_R(-30.0) + static_cast<fsw_real>(k % 2) * FSW_R(0.1);  // idle, noisy
    return step(uint64_t(k) * kDt, w0);
  }
};
}  // namespace

// Verifies: REQ-RWSF-006
TEST(RwSpeedFilterTorque, ASpeedThatFollowsTheTorqueWithinToleranceIsNeverLatched)
{
  TorqueFixture f;
  for (int k = 0; k < 100; k++) {  // +-0.1 rad/s alternating noise: residual <= 0.2 < 0.3
    ASSERT_EQ(f.at(k, 100.0 + 0.5 * k + ((k % 2) ? 0.1 : -0.1)), FSW_OK);
    ASSERT_EQ(f.out->latched, 0u) << k;
    ASSERT_EQ(f.out->avail[0], FSW_AVAILABLE) << k;
  }
}

// Frozen at 102.5 from k = 5 on: the window opened at k = 5 closes at k = 10
// with a measured change of 0 against 5 * 0.5 = 2.5 explained: latched at
// k = 10, not before.  (A motor that does not deliver reads the same way.)
// Verifies: REQ-RWSF-006
TEST(RwSpeedFilterTorque, AFrozenReadingUnderTorqueLatchesAtTheWindowsEnd)
{
  TorqueFixture f;
  for (int k = 0; k <= 10; k++) {
    ASSERT_EQ(f.at(k, k <= 5 ? 100.0 + 0.5 * k : 102.5), FSW_OK);
    EXPECT_EQ(f.out->latched, k == 10 ? 1u : 0u) << k;
  }
  EXPECT_EQ(f.out->failed, 1u);
  EXPECT_EQ(f.out->avail[0], FSW_UNAVAILABLE);
  EXPECT_EQ(f.out->rejected, 0u);  // the outlier gate alone never sees it
  EXPECT_EQ(f.out->Omega[0], FSW_R(102.5));
}

// An interval with u_valid = 0 (k = 7) restarts the window there: the
// frozen reading is latched five calls later, at k = 12.
// Verifies: REQ-RWSF-006
TEST(RwSpeedFilterTorque, AnUnknownTorqueRestartsTheWindow)
{
  TorqueFixture f;
  for (int k = 0; k <= 12; k++) {
    f.in->u_valid = (k == 7) ? 0u : 1u;
    ASSERT_EQ(f.at(k, k <= 5 ? 100.0 + 0.5 * k : 102.5), FSW_OK);
    EXPECT_EQ(f.out->latched, k == 12 ? 1u : 0u) << k;
  }
}

// The residual is signed both ways: a tachometer that runs ahead of the
// torque (bias ramp, or a motor delivering twice its command) is caught too.
// Verifies: REQ-RWSF-006
TEST(RwSpeedFilterTorque, ASpeedRisingTwiceAsFastAsTheTorqueExplainsIsLatched)
{
  TorqueFixture f;
  int latched_at = -1;
  for (int k = 0; k <= 10 && latched_at < 0; k++) {
    ASSERT_EQ(f.at(k, 100.0 + 1.0 * k), FSW_OK);  // 1.0 rad/s per call, within the outlier bound
    EXPECT_EQ(f.out->rejected, 0u);
    if (f.out->latched) latched_at = k;
  }
  EXPECT_EQ(latched_at, 5);  // residual 5.0 - 2.5 = 2.5 > 0.3 at the first window's end
}

// A window whose closing sample is an outlier (k = 5 reads 150, rejected)
// waits for the next accepted one: at k = 6 the speed 103.0 has moved
// 3.0 rad/s from the window's start, as the six intervals of torque explain
// (6 x 0.5): clean, no latch.  A wheel failed by outliers (three NaN, k_reject
// = 3) takes no part in the torque test: its window closes, nothing latches,
// and after recovery (n_recover = 3 consistent samples) it runs again: a
// reading frozen from then on is latched one window later.
// Verifies: REQ-RWSF-006
TEST(RwSpeedFilterTorque, OutliersAndOutlierFailuresPauseTheWindow)
{
  TorqueFixture f;
  for (int k = 0; k <= 6; k++) {
    ASSERT_EQ(f.at(k, k == 5 ? 150.0 : 100.0 + 0.5 * k), FSW_OK);
    EXPECT_EQ(f.out->rejected, k == 5 ? 1u : 0u) << k;
    EXPECT_EQ(f.out->latched, 0u) << k;
  }
  for (int k = 7; k <= 9; k++) {  // NaN: failed at k = 9
    ASSERT_EQ(f.at(k, std::nan("")), FSW_OK);
    EXPECT_EQ(f.out->latched, 0u) << k;
  }
  EXPECT_EQ(f.out->failed, 1u);
  int k = 10;
  for (; k <= 12; k++) ASSERT_EQ(f.at(k, 100.0 + 0.5 * k), FSW_OK);  // three consistent: back at k = 12
  EXPECT_EQ(f.out->failed, 0u);
  EXPECT_EQ(f.out->latched, 0u);
  int latched_at = -1;
  for (; k <= 20 && latched_at < 0; k++) {  // frozen at 106 from k = 12 on
    ASSERT_EQ(f.at(k, 106.0), FSW_OK);
    if (f.out->latched) latched_at = k;
  }
  EXPECT_EQ(latched_at, 18);  // the window opened at k = 13 (the first accepted sample after recovery) closes at 18
}

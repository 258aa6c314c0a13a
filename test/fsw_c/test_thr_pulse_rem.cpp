// thr_pulse_rem: remainder-tracking thruster pulsing (docs/fsw/thr_pulse_rem.md).
// Hand-computed sequences, boundary equalities, first-call and timing
// rules, config rejection, bad input, repeatability and the impulse
// tracking property over many cycles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/thr_pulse_rem.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

using R = fsw_real;
const double kTol = kt::tol(1e-12, 1e-6);
const uint64_t kSec = 1000000000ull;

// The period as docs/fsw-conventions.md, "Timing" defines it: (real)(ns) * 1e-9.
R dt_of(uint64_t ns) { return static_cast<R>(ns) * static_cast<R>(1e-9); }

FswThrPulseRemConfig cfg2()
{
  FswThrPulseRemConfig c;
  std::memset(&c, 0, sizeof c);
  c.common.num_thr = 2;
  c.common.F_max[0] = 1;
  c.common.F_max[1] = 2;
  c.common.t_min = static_cast<R>(0.1);
  c.common.base_thrust_state = 0;
  c.common.init_off_pulse_on_time = 2;
  return c;
}

struct Pulser {
  FswThrPulseRemConfig c;
  FswThrPulseRemState st;
  FswThrPulseRemOut out;
  explicit Pulser(const FswThrPulseRemConfig& cfg) : c(cfg) { EXPECT_EQ(FSW_OK, fsw_thr_pulse_rem_init(&st, &c)); }
  FswStatus step(uint64_t t_ns, double f0, double f1 = 0)
  {
    FswThrPulseRemIn in;
    std::memset(&in, 0, sizeof in);
    in.t_ns = t_ns;
    in.F[0] = static_cast<R>(f0);
    in.F[1] = static_cast<R>(f1);
    return fsw_thr_pulse_rem_update(&st, &c, &in, &out);
  }
};

void expect_rest_zero(const FswThrPulseRemOut& o, int n)
{
  for (int i = n; i < FSW_MAX_THR; i++) EXPECT_EQ(0, o.t_on[i]) << "entry " << i;
}

struct BadCfg {
  const char* why;
  void (*spoil)(FswThrPulseRemConfig*);
  FswStatus want;
};
const BadCfg kBadConfigs[] = {
    {"zero thrusters", [](FswThrPulseRemConfig* c) { c->common.num_thr = 0; }, FSW_E_CONFIG},
    {"more than FSW_MAX_THR", [](FswThrPulseRemConfig* c) { c->common.num_thr = FSW_MAX_THR + 1; }, FSW_E_CAPACITY},
    {"F_max zero", [](FswThrPulseRemConfig* c) { c->common.F_max[1] = 0; }, FSW_E_CONFIG},
    {"F_max negative", [](FswThrPulseRemConfig* c) { c->common.F_max[0] = -1; }, FSW_E_CONFIG},
    {"F_max Inf", [](FswThrPulseRemConfig* c) { c->common.F_max[0] = std::numeric_limits<R>::infinity(); }, FSW_E_CONFIG},
    {"t_min zero", [](FswThrPulseRemConfig* c) { c->common.t_min = 0; }, FSW_E_CONFIG},
    {"t_min negative", [](FswThrPulseRemConfig* c) { c->common.t_min = -0.1f; }, FSW_E_CONFIG},
    {"t_min NaN", [](FswThrPulseRemConfig* c) { c->common.t_min = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"base state 2", [](FswThrPulseRemConfig* c) { c->common.base_thrust_state = 2; }, FSW_E_CONFIG},
    {"base state -1", [](FswThrPulseRemConfig* c) { c->common.base_thrust_state = -1; }, FSW_E_CONFIG},
    {"init on-time negative", [](FswThrPulseRemConfig* c) { c->common.init_off_pulse_on_time = -1; }, FSW_E_CONFIG},
    {"init on-time NaN", [](FswThrPulseRemConfig* c) { c->common.init_off_pulse_on_time = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
};

// Verifies: REQ-PREM-001
TEST(ThrPulseRem, ConfigRejectionTable)
{
  {
    FswThrPulseRemConfig good = cfg2();
    ASSERT_EQ(FSW_OK, fsw_thr_pulse_rem_check(&good));
  }
  for (const BadCfg& row : kBadConfigs) {
    FswThrPulseRemConfig c = cfg2();
    row.spoil(&c);
    EXPECT_EQ(row.want, fsw_thr_pulse_rem_check(&c)) << row.why;
    FswThrPulseRemState st;
    std::memset(&st, 0x33, sizeof st);
    EXPECT_EQ(row.want, fsw_thr_pulse_rem_init(&st, &c)) << row.why;
    EXPECT_EQ(0, st.common.ready);
    FswThrPulseRemIn in;
    std::memset(&in, 0, sizeof in);
    FswThrPulseRemOut out;
    for (R& t : out.t_on) t = 5;
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_thr_pulse_rem_update(&st, &c, &in, &out)) << row.why;
    for (R t : out.t_on) EXPECT_EQ(0, t) << row.why;
  }
}

// Verifies: REQ-PREM-002
TEST(ThrPulseRem, HandSequenceWithRemainder)
{
  // F_max = 1, t_min = 0.1, period 1 s.  A 0.04 N request is 0.04 s: below
  // t_min, so it is carried (rho = 0.4), then 0.04 + 0.04 = 0.08 (rho 0.8),
  // then 0.04 + 0.08 = 0.12 s >= t_min fires and clears the remainder.
  Pulser p(cfg2());
  const R dt = dt_of(kSec);
  EXPECT_EQ(FSW_OK, p.step(0, 0.04));  // first call at t = 0 is legal
  EXPECT_EQ(0, p.out.t_on[0]);
  EXPECT_EQ(FSW_OK, p.step(1 * kSec, 0.04));
  EXPECT_EQ(0, p.out.t_on[0]);
  EXPECT_NEAR(0.4, p.st.rem[0], kTol);
  EXPECT_EQ(FSW_OK, p.step(2 * kSec, 0.04));
  EXPECT_EQ(0, p.out.t_on[0]);
  EXPECT_NEAR(0.8, p.st.rem[0], kTol);
  EXPECT_EQ(FSW_OK, p.step(3 * kSec, 0.04));
  EXPECT_NEAR(0.12, p.out.t_on[0], kTol);
  EXPECT_EQ(0, p.st.rem[0]);
  // saturation: 1.5 N for 1 s -> t = 1.5 >= dt: on for 1.1 dt, excess lost
  EXPECT_EQ(FSW_W_SAT, p.step(4 * kSec, 1.5));
  EXPECT_NEAR(1.1 * dt, p.out.t_on[0], kTol);
  EXPECT_EQ(0, p.st.rem[0]);
  EXPECT_EQ(1u, p.st.common.health.saturated);
  // negative force is clipped to 0; a plain request passes through
  EXPECT_EQ(FSW_OK, p.step(5 * kSec, -0.3, 1.0));  // thruster 1: 1 N of 2 N -> 0.5 s
  EXPECT_EQ(0, p.out.t_on[0]);
  EXPECT_EQ(0, p.st.rem[0]);  // clipped before the remainder: no negative on-time is carried (seed 20261203)
  EXPECT_NEAR(0.5, p.out.t_on[1], kTol);
  expect_rest_zero(p.out, 2);
}

// Verifies: REQ-PREM-002
TEST(ThrPulseRem, OnTimeEqualToMinimumFires)
{
  // t = (f / F_max) dt equal to t_min exactly is not "< t_min": it fires.
  FswThrPulseRemConfig c = cfg2();
  const uint64_t step = 500000000ull;
  c.common.t_min = (static_cast<R>(0.25) / c.common.F_max[0]) * dt_of(step);
  Pulser p(c);
  p.step(0, 0);
  EXPECT_EQ(FSW_OK, p.step(step, 0.25));
  EXPECT_EQ(c.common.t_min, p.out.t_on[0]);
  EXPECT_EQ(0, p.st.rem[0]);
  // and a request exactly equal to the period saturates without a warning
  EXPECT_EQ(FSW_OK, p.step(2 * step, 1.0));
  EXPECT_EQ(static_cast<R>(1.1) * dt_of(step), p.out.t_on[0]);
}

// Verifies: REQ-PREM-003
TEST(ThrPulseRem, OffPulsingFirstCallAndNominalFullOn)
{
  FswThrPulseRemConfig c = cfg2();
  c.common.base_thrust_state = 1;
  Pulser p(c);
  // first call: b * initOffPulseOnTime = 2.0 s for every thruster
  EXPECT_EQ(FSW_OK, p.step(7 * kSec, -0.5, -1.0));
  EXPECT_EQ(2, p.out.t_on[0]);
  EXPECT_EQ(2, p.out.t_on[1]);
  expect_rest_zero(p.out, 2);
  // F = 0 is full thrust: t = dt -> on through the period (no warning)
  EXPECT_EQ(FSW_OK, p.step(8 * kSec, 0, 0));
  EXPECT_NEAR(1.1, p.out.t_on[0], kTol);
  // F = -F_max/2 -> half the period; F = -0.96 F_max -> 0.04 s, carried
  EXPECT_EQ(FSW_OK, p.step(9 * kSec, -0.5, -1.92));
  EXPECT_NEAR(0.5, p.out.t_on[0], kTol);
  EXPECT_EQ(0, p.out.t_on[1]);
  EXPECT_NEAR(0.4, p.st.rem[1], kt::tol(1e-12, 1e-5));
  // positive F in off-pulsing (more than full thrust) saturates
  EXPECT_EQ(FSW_W_SAT, p.step(10 * kSec, 0.2, 0));
}

// Verifies: REQ-PREM-004
TEST(ThrPulseRem, TimeMustIncreaseAndNothingAdvances)
{
  Pulser p(cfg2());
  p.step(0, 0);
  p.step(kSec, 0.03);  // rho = 0.3
  FswThrPulseRemState before = p.st;
  for (uint64_t t : {kSec, kSec - 1, uint64_t(0)}) {
    for (R& x : p.out.t_on) x = 4;
    EXPECT_EQ(FSW_E_TIME, p.step(t, 0.5, 0.5));
    for (R x : p.out.t_on) EXPECT_EQ(0, x);
    EXPECT_EQ(0, std::memcmp(before.rem, p.st.rem, sizeof before.rem));
    EXPECT_EQ(before.common.clock.t_prev_ns, p.st.common.clock.t_prev_ns);
  }
  EXPECT_EQ(3u, p.st.common.health.bad_time);
  // the remainder survived the rejected calls: 0.03 + 0.3 * 0.1 = 0.06
  p.step(2 * kSec, 0.03);
  EXPECT_NEAR(0.6, p.st.rem[0], kTol);
}

// Verifies: REQ-PREM-004
TEST(ThrPulseRem, BadInputGivesSafeOutput)
{
  Pulser p(cfg2());
  p.step(0, 0);
  p.step(kSec, 0.05);  // rho = 0.5
  const R bad[] = {std::numeric_limits<R>::quiet_NaN(), std::numeric_limits<R>::infinity(),
                   -std::numeric_limits<R>::infinity()};
  uint32_t k = 0;
  for (R b : bad) {
    FswThrPulseRemIn in;
    std::memset(&in, 0, sizeof in);
    in.t_ns = 2 * kSec;
    in.F[1] = b;
    for (R& x : p.out.t_on) x = 4;
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_thr_pulse_rem_update(&p.st, &p.c, &in, &p.out));
    for (R x : p.out.t_on) EXPECT_EQ(0, x);
    EXPECT_EQ(++k, p.st.common.health.bad_input);
    EXPECT_EQ(kSec, p.st.common.clock.t_prev_ns);  // time not advanced
    EXPECT_NEAR(0.5, p.st.rem[0], kTol);
  }
  // entries beyond num_thr are not inputs: NaN there is ignored
  FswThrPulseRemIn in;
  std::memset(&in, 0, sizeof in);
  in.t_ns = 2 * kSec;
  in.F[5] = std::numeric_limits<R>::quiet_NaN();
  EXPECT_EQ(FSW_OK, fsw_thr_pulse_rem_update(&p.st, &p.c, &in, &p.out));
  expect_rest_zero(p.out, 2);
  kestrel_assert_reset();
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_thr_pulse_rem_update(&p.st, &p.c, &in, nullptr));
  EXPECT_EQ(1u, kestrel_assert_count());
  kestrel_assert_reset();
}

// Verifies: REQ-PREM-005
TEST(ThrPulseRem, RepeatableAfterReset)
{
  FswThrPulseRemConfig c = cfg2();
  Pulser p(c);
  kt::Rng rng(3);
  double f[40][2];
  R first[40][2];
  for (auto& row : f)
    for (double& x : row) x = rng.uniform(-0.2, 2.5);
  for (int k = 0; k < 40; k++) {
    p.step(uint64_t(k) * 100000000ull, f[k][0], f[k][1]);
    first[k][0] = p.out.t_on[0];
    first[k][1] = p.out.t_on[1];
  }
  fsw_thr_pulse_rem_reset(&p.st);
  EXPECT_EQ(0, p.st.common.clock.has_prev);
  for (int k = 0; k < 40; k++) {
    p.step(uint64_t(k) * 100000000ull, f[k][0], f[k][1]);
    EXPECT_EQ(first[k][0], p.out.t_on[0]) << k;
    EXPECT_EQ(first[k][1], p.out.t_on[1]) << k;
  }
}

// Verifies: REQ-PREM-002
TEST(ThrPulseRem, ImpulseTracksRequestWithinOneMinimumBit)
{
  // Over many cycles of unsaturated requests (many below t_min), the
  // impulse delivered by each thruster (F_max * t_on) lags the impulse
  // requested (F * dt) by the carried remainder only: 0 <= lag < F_max t_min.
  const int n = 6;
  FswThrPulseRemConfig c;
  std::memset(&c, 0, sizeof c);
  c.common.num_thr = n;
  c.common.t_min = static_cast<R>(0.02);
  c.common.init_off_pulse_on_time = 2;
  kt::Rng rng(99);
  for (int i = 0; i < n; i++) c.common.F_max[i] = static_cast<R>(rng.uniform(0.5, 5));
  FswThrPulseRemState st;
  ASSERT_EQ(FSW_OK, fsw_thr_pulse_rem_init(&st, &c));
  FswThrPulseRemIn in;
  FswThrPulseRemOut out;
  std::memset(&in, 0, sizeof in);
  const uint64_t step = 100000000ull;  // 0.1 s
  const R dt = dt_of(step);
  fsw_thr_pulse_rem_update(&st, &c, &in, &out);  // first call
  double req[n] = {}, del[n] = {};
  for (int k = 1; k <= 3000; k++) {
    in.t_ns = uint64_t(k) * step;
    for (int i = 0; i < n; i++) {
      // mostly tiny requests (below t_min = 20 % of the period), some larger;
      // at most 75 % so that request + remainder stays below the period
      double frac = rng.uniform_int(0, 4) == 0 ? rng.uniform(0, 0.75) : rng.uniform(0, 0.15);
      in.F[i] = static_cast<R>(frac * c.common.F_max[i]);
    }
    ASSERT_EQ(FSW_OK, fsw_thr_pulse_rem_update(&st, &c, &in, &out));
    for (int i = 0; i < n; i++) {
      req[i] += double(in.F[i]) * double(dt);
      del[i] += double(c.common.F_max[i]) * double(out.t_on[i]);
      const double bit = double(c.common.F_max[i]) * double(c.common.t_min);
      const double lag = req[i] - del[i];
      ASSERT_GE(lag, -kt::tol(1e-9, 1e-2) * bit) << "step " << k << " thr " << i;
      ASSERT_LT(lag, bit * (1 + kt::tol(1e-9, 1e-2))) << "step " << k << " thr " << i;
      // every on-time is 0 or in [t_min, dt)
      ASSERT_TRUE(out.t_on[i] == 0 || (out.t_on[i] >= c.common.t_min && out.t_on[i] < dt));
    }
  }
}

}  // namespace

// docs/fsw-conventions.md, "Reset and the output" "reset zeroes the output", read for a caller-owned
// output (docs/fsw-conventions.md): after reset, a bad input gives the
// documented safe output (every thruster off), neither the on-times the
// caller's buffer still holds nor the first-call output of the module.
// Verifies: REQ-PREM-004
TEST(ThrPulseRem, ResetThenBadInputGivesTheSafeOutputNotStaleValues)
{
  FswThrPulseRemConfig c = cfg2();
  c.common.base_thrust_state = 1;  // off-pulsing: the first-call output is 2 s, not 0
  Pulser p(c);
  ASSERT_EQ(FSW_OK, p.step(kSec, -0.5, -1.0));
  EXPECT_EQ(R(2), p.out.t_on[0]);  // first call: b * init_off_pulse_on_time
  ASSERT_FALSE(fsw_status_is_error(p.step(2 * kSec, -0.5, -1.0)));
  ASSERT_NE(0, p.out.t_on[0]);
  fsw_thr_pulse_rem_reset(&p.st);
  EXPECT_EQ(FSW_E_BAD_INPUT, p.step(3 * kSec, std::numeric_limits<double>::quiet_NaN(), -1.0));
  for (int i = 0; i < FSW_MAX_THR; i++) EXPECT_EQ(0, p.out.t_on[i]) << i;
  EXPECT_EQ(0, p.st.common.clock.has_prev);  // nothing advanced
  // the next good call is the first after reset again
  ASSERT_EQ(FSW_OK, p.step(kSec, -0.5, -1.0));
  EXPECT_EQ(R(2), p.out.t_on[0]);
  EXPECT_EQ(R(2), p.out.t_on[1]);
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(ThrPulseRemIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("thr_pulse_rem", fsw_thr_pulse_rem_check, fsw_thr_pulse_rem_init, fsw_thr_pulse_rem_reset, fsw_thr_pulse_rem_update);
}

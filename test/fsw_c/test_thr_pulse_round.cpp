// thr_pulse_round: rounding thruster pulser (docs/fsw/thr_pulse_round.md) and the
// carryResidual extension.  Round-half-to-even cases on an exactly
// representable resolution, t_min, clipping, config rejection, bad input,
// repeatability and the sigma-delta tracking property.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/thr_pulse_round.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

using R = fsw_real;
const double kTol = kt::tol(1e-12, 1e-6);

FswThrPulseRoundConfig basilisk_defaults(int n = 36)
{
  // Basilisk thrFiringRound defaults: T = 1 s, q = 0.01 s, t_min = 0,
  // F_max = 1 N (scalar: every entry), 36 thrusters.
  FswThrPulseRoundConfig c;
  std::memset(&c, 0, sizeof c);
  c.num_thr = n;
  for (int i = 0; i < n; i++) c.F_max[i] = 1;
  c.period = 1;
  c.resolution = static_cast<R>(0.01);
  c.t_min = 0;
  return c;
}

// One thruster in carry mode (T = 1, q = 0.25, F_max = 1, t_min = 0,
// carry_residual = 1), initialised, with a zeroed input.
struct Carry {
  FswThrPulseRoundConfig c = basilisk_defaults(1);
  FswThrPulseRoundState st;
  FswThrPulseRoundIn in;
  FswThrPulseRoundOut out;
  Carry()
  {
    c.resolution = static_cast<R>(0.25);
    c.carry_residual = 1;
    EXPECT_EQ(FSW_OK, fsw_thr_pulse_round_init(&st, &c));
    std::memset(&in, 0, sizeof in);
  }
};

// Runs one update on a fresh state with forces f (rest 0).
FswStatus run(const FswThrPulseRoundConfig& c, std::initializer_list<double> f, FswThrPulseRoundOut* out,
              uint64_t t_ns = 0)
{
  FswThrPulseRoundState st;
  EXPECT_EQ(FSW_OK, fsw_thr_pulse_round_init(&st, &c));
  FswThrPulseRoundIn in;
  std::memset(&in, 0, sizeof in);
  in.t_ns = t_ns;
  int i = 0;
  for (double x : f) in.F[i++] = static_cast<R>(x);
  return fsw_thr_pulse_round_update(&st, &c, &in, out);
}

struct BadCfg {
  const char* why;
  void (*spoil)(FswThrPulseRoundConfig*);
  FswStatus want;
};
const BadCfg kBadConfigs[] = {
    {"zero thrusters", [](FswThrPulseRoundConfig* c) { c->num_thr = 0; }, FSW_E_CONFIG},
    {"more than FSW_MAX_THR", [](FswThrPulseRoundConfig* c) { c->num_thr = FSW_MAX_THR + 1; }, FSW_E_CAPACITY},
    {"F_max zero", [](FswThrPulseRoundConfig* c) { c->F_max[3] = 0; }, FSW_E_CONFIG},
    {"F_max NaN", [](FswThrPulseRoundConfig* c) { c->F_max[0] = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"period zero", [](FswThrPulseRoundConfig* c) { c->period = 0; }, FSW_E_CONFIG},
    {"period negative", [](FswThrPulseRoundConfig* c) { c->period = -1; }, FSW_E_CONFIG},
    {"period Inf", [](FswThrPulseRoundConfig* c) { c->period = std::numeric_limits<R>::infinity(); }, FSW_E_CONFIG},
    {"resolution zero", [](FswThrPulseRoundConfig* c) { c->resolution = 0; }, FSW_E_CONFIG},
    {"resolution NaN", [](FswThrPulseRoundConfig* c) { c->resolution = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"t_min negative", [](FswThrPulseRoundConfig* c) { c->t_min = -0.01f; }, FSW_E_CONFIG},
    {"t_min NaN (issue 21)", [](FswThrPulseRoundConfig* c) { c->t_min = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"carry_residual 2", [](FswThrPulseRoundConfig* c) { c->carry_residual = 2; }, FSW_E_CONFIG},
};

// Verifies: REQ-PROUND-001
TEST(ThrPulseRound, ConfigRejectionTable)
{
  {
    FswThrPulseRoundConfig good = basilisk_defaults();
    ASSERT_EQ(FSW_OK, fsw_thr_pulse_round_check(&good));
  }
  for (const BadCfg& row : kBadConfigs) {
    FswThrPulseRoundConfig c = basilisk_defaults();
    row.spoil(&c);
    EXPECT_EQ(row.want, fsw_thr_pulse_round_check(&c)) << row.why;
    FswThrPulseRoundState st;
    EXPECT_EQ(row.want, fsw_thr_pulse_round_init(&st, &c)) << row.why;
    EXPECT_EQ(0, st.common.ready);
    FswThrPulseRoundIn in;
    std::memset(&in, 0, sizeof in);
    FswThrPulseRoundOut out;
    for (R& t : out.t_on) t = 5;
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_thr_pulse_round_update(&st, &c, &in, &out)) << row.why;
    for (R t : out.t_on) EXPECT_EQ(0, t);
  }
}

// Verifies: REQ-PROUND-002
TEST(ThrPulseRound, RoundHalfToEven)
{
  // q = 0.25 s and T = 1 s are exact, so t/q lands exactly on .5:
  // 0.125/0.25 = 0.5 -> 0; 0.375 -> 1.5 -> 2; 0.625 -> 2.5 -> 2 (round()
  // would give 3 = 0.75 s); 0.875 -> 3.5 -> 4; 0.3 -> 1.2 -> 1.
  FswThrPulseRoundConfig c = basilisk_defaults(5);
  c.resolution = static_cast<R>(0.25);
  FswThrPulseRoundOut out;
  EXPECT_EQ(FSW_OK, run(c, {0.125, 0.375, 0.625, 0.875, 0.3}, &out));
  EXPECT_EQ(0.0, out.t_on[0]);
  EXPECT_EQ(0.5, out.t_on[1]);
  EXPECT_EQ(0.5, out.t_on[2]);
  EXPECT_EQ(1.0, out.t_on[3]);
  EXPECT_EQ(0.25, out.t_on[4]);
  for (int i = 5; i < FSW_MAX_THR; i++) EXPECT_EQ(0, out.t_on[i]);
}

// Verifies: REQ-PROUND-002
TEST(ThrPulseRound, BasiliskDefaultsNominal)
{
  // T f / F_max rounded to 0.01 s: 0.123 -> 0.12, 0.5 -> 0.5, -0.2 -> 0,
  // 1.7 -> clamp to T = 1 (warning), 0.996 -> 1.00.
  FswThrPulseRoundConfig c = basilisk_defaults();
  FswThrPulseRoundOut out;
  EXPECT_EQ(FSW_W_SAT, run(c, {0.123, 0.5, -0.2, 1.7, 0.996}, &out));
  EXPECT_NEAR(0.12, out.t_on[0], kTol);
  EXPECT_NEAR(0.5, out.t_on[1], kTol);
  EXPECT_EQ(0, out.t_on[2]);
  EXPECT_EQ(1, out.t_on[3]);
  EXPECT_NEAR(1.0, out.t_on[4], kTol);
  EXPECT_LE(out.t_on[4], 1);
}

// Verifies: REQ-PROUND-002
TEST(ThrPulseRound, PeriodForceLimitAndMinimumOnTime)
{
  // T = 2 s, F_max = 4 N, q = 0.25, t_min = 0.5: t = 2 F / 4.
  // F = 0.6 -> 0.3 s -> 1.2 -> 0.25 < t_min -> 0;  F = 1 -> 0.5 s (= t_min,
  // kept);  F = 3 -> 1.5 s;  F = 3.9 -> 1.95 -> 7.8 -> 8 -> 2.0 s.
  FswThrPulseRoundConfig c = basilisk_defaults(4);
  c.period = 2;
  c.resolution = static_cast<R>(0.25);
  c.t_min = static_cast<R>(0.5);
  for (int i = 0; i < 4; i++) c.F_max[i] = 4;
  FswThrPulseRoundOut out;
  EXPECT_EQ(FSW_OK, run(c, {0.6, 1.0, 3.0, 3.9}, &out));
  EXPECT_EQ(0, out.t_on[0]);
  EXPECT_EQ(0.5, out.t_on[1]);
  EXPECT_EQ(1.5, out.t_on[2]);
  EXPECT_EQ(2.0, out.t_on[3]);
}

// Verifies: REQ-PROUND-002
TEST(ThrPulseRound, RoundingAboveThePeriodIsClipped)
{
  // q = 0.75 does not divide T = 1: t = 1 -> 1.33 -> 1 -> 0.75; t = 0.9 ->
  // 1.2 -> 0.75; with q = 0.6: t = 1 -> 1.67 -> 2 -> 1.2 -> clipped to 1,
  // t = 0.95 -> 1.58 -> 2 -> clipped to 1.
  FswThrPulseRoundConfig c = basilisk_defaults(2);
  c.resolution = static_cast<R>(0.75);
  FswThrPulseRoundOut out;
  run(c, {1.0, 0.9}, &out);
  EXPECT_EQ(0.75, out.t_on[0]);
  EXPECT_EQ(0.75, out.t_on[1]);
  c.resolution = static_cast<R>(0.6);
  run(c, {1.0, 0.95}, &out);
  EXPECT_EQ(1, out.t_on[0]);
  EXPECT_EQ(1, out.t_on[1]);
}

// Verifies: REQ-PROUND-004
TEST(ThrPulseRound, BadInputAndStatelessTiming)
{
  FswThrPulseRoundConfig c = basilisk_defaults(3);
  FswThrPulseRoundState st;
  ASSERT_EQ(FSW_OK, fsw_thr_pulse_round_init(&st, &c));
  FswThrPulseRoundIn in;
  std::memset(&in, 0, sizeof in);
  FswThrPulseRoundOut out;
  in.F[0] = static_cast<R>(0.5);
  in.F[1] = std::numeric_limits<R>::quiet_NaN();
  for (R& t : out.t_on) t = 5;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_thr_pulse_round_update(&st, &c, &in, &out));
  for (R t : out.t_on) EXPECT_EQ(0, t);
  EXPECT_EQ(1u, st.common.health.bad_input);
  // inputs beyond num_thr are ignored
  in.F[1] = 0;
  in.F[3] = std::numeric_limits<R>::infinity();
  EXPECT_EQ(FSW_OK, fsw_thr_pulse_round_update(&st, &c, &in, &out));
  EXPECT_EQ(0, out.t_on[3]);
  // stateless mode ignores the time stamp: the same t_ns again is fine
  EXPECT_EQ(FSW_OK, fsw_thr_pulse_round_update(&st, &c, &in, &out));
  EXPECT_NEAR(0.5, out.t_on[0], kTol);
}

// Verifies: REQ-PROUND-003
TEST(ThrPulseRound, CarryResidualHandSequence)
{
  // T = 1, q = 0.25, F = 0.1 N of 1 N each period (t = 0.1 s):
  //  t' = 0.1  -> rint(0.4) = 0 -> 0,    r = 0.1
  //  t' = 0.2  -> rint(0.8) = 1 -> 0.25, r = -0.05
  //  t' = 0.05 -> 0 -> 0,                r = 0.05
  //  t' = 0.15 -> rint(0.6) = 1 -> 0.25, r = -0.1
  //  t' = 0.0  -> 0,                     r = 0   (four periods: 0.5 s of 0.4 s + ...)
  Carry f;
  const FswThrPulseRoundConfig& c = f.c;
  FswThrPulseRoundState& st = f.st;
  FswThrPulseRoundIn& in = f.in;
  FswThrPulseRoundOut& out = f.out;
  in.F[0] = static_cast<R>(0.1);
  const double want_on[] = {0, 0.25, 0, 0.25, 0};
  const double want_r[] = {0.1, -0.05, 0.05, -0.1, 0.0};
  for (int k = 0; k < 5; k++) {
    in.t_ns = uint64_t(k) * 1000000000ull;  // first call at t = 0 is legal
    EXPECT_EQ(FSW_OK, fsw_thr_pulse_round_update(&st, &c, &in, &out)) << k;
    EXPECT_EQ(want_on[k], out.t_on[0]) << k;
    EXPECT_NEAR(want_r[k], st.resid[0], kt::tol(1e-12, 1e-6)) << k;
  }
  // carry mode follows the timing model: a repeated time stamp is refused
  R r_before = st.resid[0];
  EXPECT_EQ(FSW_E_TIME, fsw_thr_pulse_round_update(&st, &c, &in, &out));
  EXPECT_EQ(r_before, st.resid[0]);
  for (R t : out.t_on) EXPECT_EQ(0, t);
  // reset clears the residual and the time
  fsw_thr_pulse_round_reset(&st);
  EXPECT_EQ(0, st.resid[0]);
  EXPECT_EQ(0, st.common.clock.has_prev);
}

// Verifies: REQ-PROUND-003
TEST(ThrPulseRound, CarryResidualDeliversSubResolutionRequestsOnAverage)
{
  // Unsaturated random requests: the carried residual stays within half a
  // resolution step (t_min = 0) or t_min (t_min > q/2), so the total
  // on-time tracks the total request within that bound forever.
  kt::Rng rng(17);
  for (double t_min : {0.0, 0.1}) {
    FswThrPulseRoundConfig c = basilisk_defaults(4);
    c.resolution = static_cast<R>(0.05);
    c.t_min = static_cast<R>(t_min);
    c.carry_residual = 1;
    FswThrPulseRoundState st;
    ASSERT_EQ(FSW_OK, fsw_thr_pulse_round_init(&st, &c));
    FswThrPulseRoundIn in;
    std::memset(&in, 0, sizeof in);
    FswThrPulseRoundOut out;
    double req[4] = {}, del[4] = {};
    const double bound = std::fmax(0.5 * double(c.resolution), t_min + 0.5 * double(c.resolution));
    for (int k = 0; k < 2000; k++) {
      in.t_ns = uint64_t(k + 1) * 1000000ull;
      for (int i = 0; i < 4; i++) in.F[i] = static_cast<R>(rng.uniform(0, 0.12));
      ASSERT_EQ(FSW_OK, fsw_thr_pulse_round_update(&st, &c, &in, &out));
      for (int i = 0; i < 4; i++) {
        req[i] += double(c.period) * double(in.F[i]) / double(c.F_max[i]);
        del[i] += double(out.t_on[i]);
        ASSERT_LE(std::fabs(req[i] - del[i]), bound + kt::tol(1e-9, 1e-3)) << "step " << k;
      }
    }
    // and the plain (stateless) pulser would have delivered nothing at all
    // for requests below half a step: 0.02 s -> rint(0.4) = 0
    FswThrPulseRoundConfig plain = c;
    plain.carry_residual = 0;
    FswThrPulseRoundOut o2;
    run(plain, {0.02}, &o2);
    EXPECT_EQ(0, o2.t_on[0]);
  }
}

// Verifies: REQ-PROUND-005
TEST(ThrPulseRound, RepeatableAfterReset)
{
  FswThrPulseRoundConfig c = basilisk_defaults(3);
  c.carry_residual = 1;
  FswThrPulseRoundState st;
  ASSERT_EQ(FSW_OK, fsw_thr_pulse_round_init(&st, &c));
  kt::Rng rng(1);
  FswThrPulseRoundIn in[30];
  FswThrPulseRoundOut first[30], again;
  for (int k = 0; k < 30; k++) {
    std::memset(&in[k], 0, sizeof in[k]);
    in[k].t_ns = uint64_t(k) * 1000ull;
    for (int i = 0; i < 3; i++) in[k].F[i] = static_cast<R>(rng.uniform(-0.2, 1.2));
    fsw_thr_pulse_round_update(&st, &c, &in[k], &first[k]);
  }
  fsw_thr_pulse_round_reset(&st);
  for (int k = 0; k < 30; k++) {
    fsw_thr_pulse_round_update(&st, &c, &in[k], &again);
    EXPECT_EQ(0, std::memcmp(&first[k], &again, sizeof again)) << k;
  }
}

// Verifies: REQ-GEN-007
TEST(ThrPulseRound, NullArgumentsReachTheAssertHook)
{
  FswThrPulseRoundConfig c = basilisk_defaults(2);
  FswThrPulseRoundState st;
  ASSERT_EQ(FSW_OK, fsw_thr_pulse_round_init(&st, &c));
  FswThrPulseRoundIn in;
  std::memset(&in, 0, sizeof in);
  FswThrPulseRoundOut out;
  for (R& t : out.t_on) t = 5;
  kestrel_assert_reset();
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_thr_pulse_round_update(&st, &c, nullptr, &out));
  for (R t : out.t_on) EXPECT_EQ(0, t);
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_thr_pulse_round_check(nullptr));
  EXPECT_EQ(2u, kestrel_assert_count());
  EXPECT_EQ(1u, st.common.health.bad_input);
  kestrel_assert_reset();
}

}  // namespace

// Finding 8 (issue 13): period 0.1 s, resolution 0.15 s, t_min = 0.12 s and
// F = F_max gave t_on = 0.1 s < t_min under OK.  A minimum on-time longer
// than the period cannot be honoured: check refuses it; t_min = period is
// accepted and then every non-zero on-time is >= t_min.
// Verifies: REQ-PROUND-001
TEST(ThrPulseRound, Issue13MinimumOnTimeLongerThanPeriodIsRefused)
{
  FswThrPulseRoundConfig c = basilisk_defaults(1);
  c.period = static_cast<R>(0.1);
  c.resolution = static_cast<R>(0.15);
  c.t_min = static_cast<R>(0.12);
  EXPECT_EQ(FSW_E_CONFIG, fsw_thr_pulse_round_check(&c));
  c.t_min = c.period;
  ASSERT_EQ(FSW_OK, fsw_thr_pulse_round_check(&c));
  FswThrPulseRoundOut out;
  for (double f : {0.3, 0.7, 1.0, 2.0}) {
    EXPECT_FALSE(fsw_status_is_error(run(c, {f}, &out)));
    EXPECT_TRUE(out.t_on[0] == 0 || out.t_on[0] >= c.t_min) << f;
    EXPECT_LE(out.t_on[0], c.period);
  }
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(ThrPulseRoundIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("thr_pulse_round", fsw_thr_pulse_round_check, fsw_thr_pulse_round_init, fsw_thr_pulse_round_reset, fsw_thr_pulse_round_update);
}


namespace {
// One carry-mode step: request F, expected status, on-time and residual.
struct CarryStep {
  double F;
  FswStatus s;
  double on, r;
};
// Runs the steps, one per period of 1 s, on a fresh state of one thruster
// (T = 1, q = 0.25, F_max = 1, t_min = 0, carry_residual = 1).  The on-time
// must be exactly the expected value and never -0.
void expect_carry_sequence(std::initializer_list<CarryStep> steps)
{
  Carry f;
  const FswThrPulseRoundConfig& c = f.c;
  FswThrPulseRoundState& st = f.st;
  FswThrPulseRoundIn& in = f.in;
  FswThrPulseRoundOut& out = f.out;
  int k = 0;
  for (const CarryStep& step : steps) {
    in.t_ns = uint64_t(k) * 1000000000ull;
    in.F[0] = static_cast<R>(step.F);
    EXPECT_EQ(step.s, fsw_thr_pulse_round_update(&st, &c, &in, &out)) << k;
    EXPECT_EQ(step.on, out.t_on[0]) << k;
    EXPECT_FALSE(std::signbit(out.t_on[0])) << "on-time -0 at step " << k;
    EXPECT_NEAR(step.r, st.resid[0], kt::tol(1e-12, 1e-6)) << k;
    k++;
  }
}
}  // namespace

// Issue 21: in carry mode a negative residual makes t = T f / F_max + r
// negative when the request drops to 0; the first clamp of the equations
// (docs/fsw/thr_pulse_round.md: "t = clamp(t, 0, T)" before rounding) turns
// it into +0, so the on-time is exactly +0.0 -- not -0.0, which rint(-0.2)
// would give and which would go out as a different binary64 on the link and
// in the bitwise host/target comparisons -- and the residual is carried on.
// T = 1, q = 0.25, t_min = 0:
//   F = 0.2: t' = 0.2   -> rint(0.8) = 1 -> 0.25, r = -0.05
//   F = 0:   t' = -0.05 -> clamp 0 -> 0,          r = -0.05
//   F = 0.3: t' = 0.25  -> rint(1) = 1  -> 0.25,  r = 0
// Verifies: REQ-PROUND-003
TEST(ThrPulseRoundIssue21, NegativeCarriedRequestGivesPlusZero)
{
  expect_carry_sequence({{0.2, FSW_OK, 0.25, -0.05},
                         {0.0, FSW_OK, 0.0, -0.05},
                         {0.0, FSW_OK, 0.0, -0.05},
                         {0.3, FSW_OK, 0.25, 0.0}});
}

// Issue 21: the carried residual is limited to one period
// (docs/fsw/thr_pulse_round.md: "r_i = clamp(t' - t, -T, T)"), so a
// saturated request does not build up a backlog that keeps firing after it
// ends.  T = 1, q = 0.25, F_max = 1:
//   F = 3: t' = 3 -> clamp 1 -> 1 (W_SAT), r = clamp(2) = 1
//   F = 0: t' = 1 -> 1,                    r = 0
//   F = 0: t' = 0 -> 0,                    r = 0   (unclamped: 1, 1, then 0)
// Verifies: REQ-PROUND-003
TEST(ThrPulseRoundIssue21, CarriedResidualIsLimitedToOnePeriod)
{
  expect_carry_sequence({{3.0, FSW_W_SAT, 1.0, 1.0}, {0.0, FSW_OK, 1.0, 0.0}, {0.0, FSW_OK, 0.0, 0.0}});
}

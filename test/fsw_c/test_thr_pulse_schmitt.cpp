// thr_pulse_schmitt: Schmitt-trigger thruster pulsing (docs/fsw/thr_pulse_schmitt.md).
// Hand-computed sequence through the hysteresis band, inclusive level
// boundaries, first call and timing, config rejection, bad input,
// repeatability and the no-chatter property.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/thr_pulse_schmitt.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

using R = fsw_real;
const double kTol = kt::tol(1e-12, 1e-6);
const uint64_t kSec = 1000000000ull;

R dt_of(uint64_t ns) { return static_cast<R>(ns) * static_cast<R>(1e-9); }

FswThrPulseSchmittConfig cfg1(int n = 1)
{
  FswThrPulseSchmittConfig c;
  std::memset(&c, 0, sizeof c);
  c.common.num_thr = n;
  for (int i = 0; i < n; i++) c.common.F_max[i] = 1;
  c.common.t_min = static_cast<R>(0.1);
  c.level_on = static_cast<R>(0.75);
  c.level_off = static_cast<R>(0.25);
  c.common.init_off_pulse_on_time = 2;
  return c;
}

struct Pulser {
  FswThrPulseSchmittConfig c;
  FswThrPulseSchmittState st;
  FswThrPulseSchmittOut out;
  explicit Pulser(const FswThrPulseSchmittConfig& cfg) : c(cfg)
  {
    EXPECT_EQ(FSW_OK, fsw_thr_pulse_schmitt_init(&st, &c));
  }
  FswStatus step(uint64_t t_ns, double f0)
  {
    FswThrPulseSchmittIn in;
    std::memset(&in, 0, sizeof in);
    in.t_ns = t_ns;
    in.F[0] = static_cast<R>(f0);
    return fsw_thr_pulse_schmitt_update(&st, &c, &in, &out);
  }
};

struct BadCfg {
  const char* why;
  void (*spoil)(FswThrPulseSchmittConfig*);
  FswStatus want;
};
const BadCfg kBadConfigs[] = {
    {"zero thrusters", [](FswThrPulseSchmittConfig* c) { c->common.num_thr = 0; }, FSW_E_CONFIG},
    {"more than FSW_MAX_THR", [](FswThrPulseSchmittConfig* c) { c->common.num_thr = FSW_MAX_THR + 1; }, FSW_E_CAPACITY},
    {"F_max zero", [](FswThrPulseSchmittConfig* c) { c->common.F_max[0] = 0; }, FSW_E_CONFIG},
    {"t_min zero", [](FswThrPulseSchmittConfig* c) { c->common.t_min = 0; }, FSW_E_CONFIG},
    {"t_min Inf", [](FswThrPulseSchmittConfig* c) { c->common.t_min = std::numeric_limits<R>::infinity(); }, FSW_E_CONFIG},
    {"level_off negative", [](FswThrPulseSchmittConfig* c) { c->level_off = -0.1f; }, FSW_E_CONFIG},
    {"level_off == level_on", [](FswThrPulseSchmittConfig* c) { c->level_off = c->level_on; }, FSW_E_CONFIG},
    {"level_off > level_on", [](FswThrPulseSchmittConfig* c) { c->level_off = 0.8f; }, FSW_E_CONFIG},
    {"level_on > 1", [](FswThrPulseSchmittConfig* c) { c->level_on = 1.01f; }, FSW_E_CONFIG},
    {"level_on NaN", [](FswThrPulseSchmittConfig* c) { c->level_on = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"level_off NaN (issue 21)", [](FswThrPulseSchmittConfig* c) { c->level_off = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"base state 3", [](FswThrPulseSchmittConfig* c) { c->common.base_thrust_state = 3; }, FSW_E_CONFIG},
    {"init on-time negative", [](FswThrPulseSchmittConfig* c) { c->common.init_off_pulse_on_time = -2; }, FSW_E_CONFIG},
};

// Verifies: REQ-PSCHM-001
TEST(ThrPulseSchmitt, ConfigRejectionTable)
{
  {
    FswThrPulseSchmittConfig good = cfg1();
    ASSERT_EQ(FSW_OK, fsw_thr_pulse_schmitt_check(&good));
    good.level_off = 0;  // the closed ends of the ranges are legal
    good.level_on = 1;
    ASSERT_EQ(FSW_OK, fsw_thr_pulse_schmitt_check(&good));
  }
  for (const BadCfg& row : kBadConfigs) {
    FswThrPulseSchmittConfig c = cfg1();
    row.spoil(&c);
    EXPECT_EQ(row.want, fsw_thr_pulse_schmitt_check(&c)) << row.why;
    FswThrPulseSchmittState st;
    EXPECT_EQ(row.want, fsw_thr_pulse_schmitt_init(&st, &c)) << row.why;
    EXPECT_EQ(0, st.common.ready);
    FswThrPulseSchmittIn in;
    std::memset(&in, 0, sizeof in);
    FswThrPulseSchmittOut out;
    for (R& t : out.t_on) t = 5;
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_thr_pulse_schmitt_update(&st, &c, &in, &out)) << row.why;
    for (R t : out.t_on) EXPECT_EQ(0, t);
  }
}

// Verifies: REQ-PSCHM-002
TEST(ThrPulseSchmitt, HandSequenceThroughTheBand)
{
  // F_max 1, period 1 s, t_min 0.1: level l = F / 0.1 for F < 0.1.
  // levels on 0.75, off 0.25.
  Pulser p(cfg1());
  const R dt = dt_of(kSec);
  const R t_min = p.c.common.t_min;
  struct Row { double F; double want; const char* why; } rows[] = {
      {0.05, 0, "l = 0.5 in the band, memory off -> off"},
      {0.08, -1, "l = 0.8 >= 0.75 -> fires t_min"},
      {0.05, -1, "l = 0.5 in the band, memory on -> t_min"},
      {0.02, 0, "l = 0.2 <= 0.25 -> off"},
      {0.05, 0, "band, memory off"},
      {0.5, 0.5, "t = 0.5 s in [t_min, dt) -> passes, memory on"},
      {0.05, -1, "band after a normal pulse: memory on -> t_min"},
      {-1.0, 0, "negative force clipped to 0 -> l = 0 -> off"},
      {2.0, -2, "t = 2 >= dt -> 1.1 dt"},
      {0.05, -1, "band after saturation: memory on"},
  };
  EXPECT_EQ(FSW_OK, p.step(0, 0.3));
  EXPECT_EQ(0, p.out.t_on[0]) << "first call, on-pulsing: off";
  uint64_t t = 0;
  for (const Row& r : rows) {
    t += kSec;
    FswStatus s = p.step(t, r.F);
    double want = r.want == -1 ? double(t_min) : r.want == -2 ? 1.1 * double(dt) : r.want;
    EXPECT_NEAR(want, p.out.t_on[0], kTol) << r.why;
    EXPECT_EQ(r.F > 1.0 ? FSW_W_SAT : FSW_OK, s) << r.why;
    for (int i = 1; i < FSW_MAX_THR; i++) EXPECT_EQ(0, p.out.t_on[i]);
  }
}

// Verifies: REQ-PSCHM-002
TEST(ThrPulseSchmitt, LevelBoundariesAreInclusive)
{
  // Levels computed with the page's own expression l = ((F/F_max) dt)/t_min
  // so the comparisons see exact equality.
  FswThrPulseSchmittConfig c = cfg1();
  c.common.t_min = static_cast<R>(0.5);
  const uint64_t step = kSec;
  const R dt = dt_of(step);
  const R F_on = static_cast<R>(0.375), F_off = static_cast<R>(0.125);
  c.level_on = ((F_on / c.common.F_max[0]) * dt) / c.common.t_min;
  c.level_off = ((F_off / c.common.F_max[0]) * dt) / c.common.t_min;
  Pulser p(c);
  p.step(0, 0);
  p.step(step, F_on);  // l == level_on -> on
  EXPECT_EQ(c.common.t_min, p.out.t_on[0]);
  p.step(2 * step, F_off);  // l == level_off -> off (not held)
  EXPECT_EQ(0, p.out.t_on[0]);
  EXPECT_EQ(0, p.st.last_on[0]);
}

// Verifies: REQ-PSCHM-003
TEST(ThrPulseSchmitt, OffPulsingFirstCall)
{
  FswThrPulseSchmittConfig c = cfg1(3);
  c.common.base_thrust_state = 1;
  Pulser p(c);
  EXPECT_EQ(FSW_OK, p.step(123, -0.5));
  for (int i = 0; i < 3; i++) EXPECT_EQ(2, p.out.t_on[i]);
  for (int i = 3; i < FSW_MAX_THR; i++) EXPECT_EQ(0, p.out.t_on[i]);
  // F = -F_max/2 off-pulsing: f = 0.5 N -> 0.5 s of a 1 s period
  EXPECT_EQ(FSW_OK, p.step(123 + kSec, -0.5));
  EXPECT_NEAR(0.5, p.out.t_on[0], kTol);
  EXPECT_NEAR(1.1, p.out.t_on[1], kTol);  // F = 0: full thrust
}

// Verifies: REQ-PSCHM-004
TEST(ThrPulseSchmitt, TimeAndBadInputAdvanceNothing)
{
  Pulser p(cfg1());
  p.step(0, 0);
  p.step(kSec, 0.08);  // memory on
  FswThrPulseSchmittState before = p.st;
  EXPECT_EQ(FSW_E_TIME, p.step(kSec, 0.0));
  EXPECT_EQ(FSW_E_TIME, p.step(0, 0.0));
  EXPECT_EQ(FSW_E_BAD_INPUT, p.step(2 * kSec, std::nan("")));
  for (R x : p.out.t_on) EXPECT_EQ(0, x);
  EXPECT_EQ(before.last_on[0], p.st.last_on[0]);
  EXPECT_EQ(before.common.clock.t_prev_ns, p.st.common.clock.t_prev_ns);
  EXPECT_EQ(2u, p.st.common.health.bad_time);
  EXPECT_EQ(1u, p.st.common.health.bad_input);
  // memory still on: a band request fires t_min
  p.step(2 * kSec, 0.05);
  EXPECT_NEAR(0.1, p.out.t_on[0], kTol);
}

// Verifies: REQ-PSCHM-005
TEST(ThrPulseSchmitt, RepeatableAfterReset)
{
  Pulser p(cfg1());
  kt::Rng rng(8);
  double f[50];
  R first[50];
  for (double& x : f) x = rng.uniform(-0.05, 0.2);
  for (int k = 0; k < 50; k++) {
    p.step(uint64_t(k) * kSec, f[k]);
    first[k] = p.out.t_on[0];
  }
  fsw_thr_pulse_schmitt_reset(&p.st);
  EXPECT_EQ(0, p.st.last_on[0]);
  for (int k = 0; k < 50; k++) {
    p.step(uint64_t(k) * kSec, f[k]);
    EXPECT_EQ(first[k], p.out.t_on[0]) << k;
  }
}

// Verifies: REQ-PSCHM-002
TEST(ThrPulseSchmitt, RequestHeldBetweenLevelsNeverChatters)
{
  // After a random history, each thruster's request is held at a level
  // strictly inside (level_off, level_on): its on-time never changes.
  const int n = 8;
  kt::Rng rng(4242);
  for (int trial = 0; trial < 20; trial++) {
    FswThrPulseSchmittConfig c = cfg1(n);
    c.level_off = static_cast<R>(rng.uniform(0.0, 0.5));
    c.level_on = static_cast<R>(rng.uniform(double(c.level_off) + 0.05, 1.0));
    for (int i = 0; i < n; i++) c.common.F_max[i] = static_cast<R>(rng.uniform(0.5, 3));
    FswThrPulseSchmittState st;
    ASSERT_EQ(FSW_OK, fsw_thr_pulse_schmitt_init(&st, &c));
    FswThrPulseSchmittIn in;
    FswThrPulseSchmittOut out;
    std::memset(&in, 0, sizeof in);
    const R dt = dt_of(kSec);
    uint64_t t = 0;
    for (int k = 0; k < 10; k++, t += kSec) {  // random history
      in.t_ns = t;
      for (int i = 0; i < n; i++) in.F[i] = static_cast<R>(rng.uniform(0, 0.2) * c.common.F_max[i]);
      fsw_thr_pulse_schmitt_update(&st, &c, &in, &out);
    }
    for (int i = 0; i < n; i++) {
      double lvl = rng.uniform(double(c.level_off), double(c.level_on));
      lvl = std::fmin(std::fmax(lvl, double(c.level_off) + 1e-3), double(c.level_on) - 1e-3);
      in.F[i] = static_cast<R>(lvl * double(c.common.t_min) / double(dt) * double(c.common.F_max[i]));
    }
    R held[FSW_MAX_THR];
    for (int k = 0; k < 100; k++, t += kSec) {
      in.t_ns = t;
      ASSERT_EQ(FSW_OK, fsw_thr_pulse_schmitt_update(&st, &c, &in, &out));
      for (int i = 0; i < n; i++) {
        ASSERT_TRUE(out.t_on[i] == 0 || out.t_on[i] == c.common.t_min);
        if (k == 0) held[i] = out.t_on[i];
        ASSERT_EQ(held[i], out.t_on[i]) << "trial " << trial << " thr " << i << " step " << k;
      }
    }
  }
}

// Verifies: REQ-GEN-007
TEST(ThrPulseSchmitt, NullArgumentsReachTheAssertHook)
{
  FswThrPulseSchmittConfig c = cfg1();
  FswThrPulseSchmittState st;
  ASSERT_EQ(FSW_OK, fsw_thr_pulse_schmitt_init(&st, &c));
  FswThrPulseSchmittIn in;
  std::memset(&in, 0, sizeof in);
  FswThrPulseSchmittOut out;
  for (R& t : out.t_on) t = 5;
  kestrel_assert_reset();
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_thr_pulse_schmitt_update(&st, &c, nullptr, &out));
  for (R t : out.t_on) EXPECT_EQ(0, t);
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_thr_pulse_schmitt_check(nullptr));
  EXPECT_EQ(2u, kestrel_assert_count());
  EXPECT_EQ(1u, st.common.health.bad_input);
  kestrel_assert_reset();
}

}  // namespace

// Finding 8 (issue 13): t_min = 0.02 s and a 16 ms call period gave
// t_on = 0.02 s, longer than the period.  The minimum pulse is now
// min(t_min, period): it fills the period.
// Verifies: REQ-PSCHM-003
TEST(ThrPulseSchmitt, Issue13MinimumPulseNeverExceedsThePeriod)
{
  FswThrPulseSchmittConfig c = cfg1();
  c.common.t_min = static_cast<R>(0.02);
  Pulser p(c);
  const uint64_t kT = 16000000ull;  // 16 ms
  ASSERT_EQ(FSW_OK, p.step(kT, 0.0));  // first call
  for (int k = 2; k < 6; k++) {
    EXPECT_FALSE(fsw_status_is_error(p.step(k * kT, 1.0)));  // t = 16 ms < t_min
    EXPECT_GT(p.out.t_on[0], 0.0);
    EXPECT_LE(p.out.t_on[0], static_cast<R>(0.016));
    EXPECT_NEAR(0.016, p.out.t_on[0], kTol);
  }
}

// Issue 21: saturation with a period other than 1 s.  Period 0.5 s, F_max 1:
// t = F / F_max * dt.  F = 1.5 -> t = 0.75 s > dt: on for 1.1 dt = 0.55 s and
// W_SAT; F = 1 -> t = dt exactly: 0.55 s, not saturated (t > dt is false).
// Verifies: REQ-PSCHM-003
TEST(ThrPulseSchmitt, Issue21SaturationScalesWithThePeriod)
{
  Pulser p(cfg1());
  const uint64_t half = kSec / 2;
  ASSERT_EQ(FSW_OK, p.step(0, 0.0));
  EXPECT_EQ(FSW_W_SAT, p.step(half, 1.5));
  EXPECT_NEAR(0.55, p.out.t_on[0], kTol);
  EXPECT_EQ(FSW_OK, p.step(2 * half, 1.0));
  EXPECT_NEAR(0.55, p.out.t_on[0], kTol);
  EXPECT_EQ(1u, p.st.common.health.saturated);
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(ThrPulseSchmittIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("thr_pulse_schmitt", fsw_thr_pulse_schmitt_check, fsw_thr_pulse_schmitt_init, fsw_thr_pulse_schmitt_reset, fsw_thr_pulse_schmitt_update);
}

// Issue 21 (mutation survivor of seed 2112): init clears the hysteresis
// memory, also on a state that has fired: after re-init a request in the
// band (level 0.5, between level_off 0.25 and level_on 0.75) is off, as for
// a fresh pulser.
// Verifies: REQ-PSCHM-004
TEST(ThrPulseSchmitt, Issue21InitClearsTheMemoryOfAUsedState)
{
  Pulser p(cfg1());
  ASSERT_EQ(FSW_OK, p.step(0, 0.0));
  ASSERT_EQ(FSW_OK, p.step(kSec, 0.08));  // level 0.8: fires, memory on
  ASSERT_NEAR(0.1, p.out.t_on[0], kTol);
  ASSERT_EQ(FSW_OK, fsw_thr_pulse_schmitt_init(&p.st, &p.c));
  ASSERT_EQ(FSW_OK, p.step(0, 0.0));
  EXPECT_EQ(FSW_OK, p.step(kSec, 0.05));  // level 0.5: in the band
  EXPECT_EQ(0, p.out.t_on[0]);
}

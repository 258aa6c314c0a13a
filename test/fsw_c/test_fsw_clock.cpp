// fsw_clock: the shared timing step of docs/fsw-conventions.md, "Timing".  Hand values,
// the first call at any time stamp (no sentinel), rejection of equal and
// earlier stamps without any change, dt from the integer difference (no
// accumulated round-off), reset, and NULL arguments.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "fsw/fsw_clock.h"
#include "kestrel_test_support.h"

namespace {

using R = fsw_real;
constexpr uint64_t kSec = 1000000000ull;

FswClock fresh()
{
  FswClock c;
  std::memset(&c, 0xA5, sizeof c);  // garbage: reset must define every field
  fsw_clock_reset(&c);
  return c;
}

}  // namespace

// Verifies: REQ-CLOCK-004
TEST(FswClock, ResetClearsBothFields)
{
  const FswClock c = fresh();
  EXPECT_EQ(0, c.has_prev);
  EXPECT_EQ(0u, c.t_prev_ns);
}

// Verifies: REQ-CLOCK-001
TEST(FswClock, FirstCallIsLegalAtAnyTimeIncludingZero)
{
  const uint64_t stamps[] = {0u, 1u, 5 * kSec, UINT64_MAX};
  for (uint64_t t : stamps) {
    const FswClock c = fresh();
    R dt = static_cast<R>(-1);
    EXPECT_EQ(FSW_OK, fsw_clock_dt(&c, t, &dt)) << t;
    EXPECT_EQ(0, dt) << t;
    EXPECT_EQ(0, c.has_prev);  // dt changes nothing
  }
}

// Verifies: REQ-CLOCK-003
TEST(FswClock, HandValues)
{
  FswClock c = fresh();
  fsw_clock_commit(&c, 2 * kSec);
  EXPECT_EQ(1, c.has_prev);
  EXPECT_EQ(2 * kSec, c.t_prev_ns);
  R dt = 0;
  // 0.5 s, 1 ns and 10 s after the previous call
  EXPECT_EQ(FSW_OK, fsw_clock_dt(&c, 2 * kSec + kSec / 2, &dt));
  EXPECT_EQ(static_cast<R>(kSec / 2) * static_cast<R>(1e-9), dt);
  EXPECT_NEAR(0.5, double(dt), kt::tol(1e-15, 1e-7));
  EXPECT_EQ(FSW_OK, fsw_clock_dt(&c, 2 * kSec + 1, &dt));
  EXPECT_EQ(static_cast<R>(1) * static_cast<R>(1e-9), dt);
  EXPECT_EQ(FSW_OK, fsw_clock_dt(&c, 12 * kSec, &dt));
  EXPECT_NEAR(10.0, double(dt), kt::tol(1e-14, 1e-5));
  // nothing was committed by dt
  EXPECT_EQ(2 * kSec, c.t_prev_ns);
}

// Verifies: REQ-CLOCK-002
TEST(FswClock, EqualOrEarlierStampIsRejectedAndChangesNothing)
{
  FswClock c = fresh();
  fsw_clock_commit(&c, 7 * kSec);
  const FswClock before = c;
  const uint64_t stamps[] = {7 * kSec, 7 * kSec - 1, 0u};
  for (uint64_t t : stamps) {
    R dt = static_cast<R>(3);
    EXPECT_EQ(FSW_E_TIME, fsw_clock_dt(&c, t, &dt)) << t;
    EXPECT_EQ(0, dt) << t;
    EXPECT_EQ(0, std::memcmp(&before, &c, sizeof c));
  }
}

// Verifies: REQ-CLOCK-003
TEST(FswClock, DtFromTheIntegerDifferenceHasNoAccumulatedRoundOff)
{
  // 10^5 steps of 0.1 s: the stamp grows exactly, so the last dt is the
  // same number as the first (a summed real clock would drift).
  FswClock c = fresh();
  const uint64_t h = kSec / 10;
  R first = 0, dt = 0;
  fsw_clock_commit(&c, 0);
  for (uint64_t k = 1; k <= 100000u; ++k) {
    ASSERT_EQ(FSW_OK, fsw_clock_dt(&c, k * h, &dt));
    if (k == 1) first = dt;
    ASSERT_EQ(first, dt) << k;
    fsw_clock_commit(&c, k * h);
  }
}

// Verifies: REQ-CLOCK-004
TEST(FswClock, ResetForgetsThePreviousCall)
{
  FswClock c = fresh();
  fsw_clock_commit(&c, 9 * kSec);
  fsw_clock_reset(&c);
  R dt = static_cast<R>(1);
  EXPECT_EQ(FSW_OK, fsw_clock_dt(&c, 1 * kSec, &dt));  // earlier stamp is fine again
  EXPECT_EQ(0, dt);
}

// Verifies: REQ-GEN-007
TEST(FswClock, NullArguments)
{
  kestrel_assert_reset();
  FswClock c = fresh();
  R dt = static_cast<R>(4);
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_clock_dt(nullptr, 1, &dt));
  EXPECT_EQ(0, dt);
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_clock_dt(&c, 1, nullptr));
  fsw_clock_commit(nullptr, 1);
  fsw_clock_reset(nullptr);
  EXPECT_EQ(4u, kestrel_assert_count());
  kestrel_assert_reset();
}

// fsw_clock_ns_to_s gives the bits of (fsw_real)d * 1e-9 (the compiler's own
// conversion, correctly rounded) for every kind of difference: below 2^32,
// at and around the powers of two where the float path starts shifting,
// exact ties of the 24-bit rounding with and without lower bits below them
// (round to even, round up), the largest value, and a deterministic spread
// of 64-bit values (a 64-bit LCG, shifted so every bit length occurs).
// Verifies: REQ-CLOCK-003
TEST(FswClock, NsToSecondsRoundsAsTheDirectConversion)
{
  std::vector<uint64_t> d = {0u, 1u, 100000000u, 0xffffffffu, 0x100000000u, 0x100000001u,
                             0x1ffffffffu, ~0ull, 1ull << 63, (1ull << 63) + 1u};
  for (int e = 33; e < 64; e++) {
    const uint64_t top = 1ull << e, half = 1ull << (e - 24);  // half an ulp at 2^e
    d.push_back(top + half);                 // tie: to even (down)
    d.push_back(top + 3 * half);             // tie: to even (up)
    d.push_back(top + half + 1u);            // just above the tie: up
    d.push_back(top + half - 1u);            // just below: down
    d.push_back(top - 1u);                   // rounds up to 2^e
  }
  uint64_t x = 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < 4000; i++) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    d.push_back(x >> (i % 64));
  }
  for (uint64_t v : d) {
    const R want = static_cast<R>(v) * FSW_R(1e-9);
    EXPECT_EQ(want, fsw_clock_ns_to_s(v)) << v;
  }
}

// MC/DC closures (docs/coverage.md): each test shows one condition of a
// decision in fsw_c/src acting on its own, the other conditions of the
// decision held at the values that let it decide.  Expected values: the
// documented safe outputs of the headers (0 for the planning helpers,
// FSW_E_BAD_INPUT with FSW_LINK_E_SPACE for a too small buffer) and, next
// to each rejected case, a neighbouring accepted case with its closed-form
// value, so that a guard that rejected everything would fail too.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

extern "C" {
#include "fsw/bdot.h"
#include "fsw/fsw_link_sec.h"
#include "fsw/thr_momentum.h"
}

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
const fsw_real kInf = std::numeric_limits<fsw_real>::infinity();
const fsw_real kMax = std::numeric_limits<fsw_real>::max();
const fsw_real kTiny = std::numeric_limits<fsw_real>::denorm_min();

}  // namespace

// bdot.c fsw_bdot_gain: !isfinite(n) || !isfinite(J_min) || !isfinite(incl)
// Verifies: REQ-BDOT-011
TEST(McdcBdotGain, NonFiniteInertiaAloneGivesZero)
{
  // accepted neighbour: k = 2 n (1 + sin 0) J = 2 * 0.001 * 1 * 10 = 0.02
  EXPECT_NEAR(fsw_bdot_gain(FSW_R(0.001), FSW_R(10.0), FSW_R(0.0)), 0.02, 1e-7);
  EXPECT_EQ(fsw_bdot_gain(FSW_R(0.001), kNaN, FSW_R(0.0)), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_gain(FSW_R(0.001), kInf, FSW_R(0.0)), FSW_R(0.0));
}

// bdot.c fsw_bdot_decay_time: the four conditions on k and J, the two on
// B_rms (normalize 0) and the two on k_eff = k B_rms^2.
// Verifies: REQ-BDOT-011
TEST(McdcBdotDecayTime, EachInvalidArgumentAloneGivesZero)
{
  // accepted neighbours: T = 1.5 J / k (normalize 1), 1.5 J / (k B^2) (normalize 0)
  EXPECT_NEAR(fsw_bdot_decay_time(FSW_R(2.0), FSW_R(3.0), FSW_R(0.5), 1), 2.25, 1e-6);
  EXPECT_NEAR(fsw_bdot_decay_time(FSW_R(2.0), FSW_R(3.0), FSW_R(0.5), 0), 9.0, 1e-5);
  // k, J
  EXPECT_EQ(fsw_bdot_decay_time(kNaN, FSW_R(3.0), FSW_R(0.5), 1), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_decay_time(kInf, FSW_R(3.0), FSW_R(0.5), 1), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_decay_time(FSW_R(2.0), kNaN, FSW_R(0.5), 1), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_decay_time(FSW_R(2.0), -kInf, FSW_R(0.5), 1), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_decay_time(FSW_R(2.0), FSW_R(-3.0), FSW_R(0.5), 1), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_decay_time(FSW_R(2.0), FSW_R(0.0), FSW_R(0.5), 1), FSW_R(0.0));
  // B_rms (normalize 0 only: normalize 1 ignores it)
  EXPECT_EQ(fsw_bdot_decay_time(FSW_R(2.0), FSW_R(3.0), kInf, 0), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_decay_time(FSW_R(2.0), FSW_R(3.0), kNaN, 0), FSW_R(0.0));
  EXPECT_NEAR(fsw_bdot_decay_time(FSW_R(2.0), FSW_R(3.0), kInf, 1), 2.25, 1e-6);
  // k_eff = k B^2 underflows to 0 (the time would be infinite) or overflows
  EXPECT_EQ(fsw_bdot_decay_time(kTiny, FSW_R(3.0), FSW_R(0.5), 0), FSW_R(0.0));
  EXPECT_EQ(fsw_bdot_decay_time(kMax, FSW_R(3.0), FSW_R(2.0), 0), FSW_R(0.0));
}

// thr_momentum.c: the finiteness conditions of the two planning helpers
// Verifies: REQ-THRMOM-009
TEST(McdcThrMomentumPlanning, EachNonFiniteArgumentAloneGivesZero)
{
  // accepted neighbours: T = (h_u - h_l) / |L| = (3 - 1) / 0.5 = 4 s;
  // m = |dH| / r / (Isp g0) = 2 / 0.5 / (200 * 9.80665) kg
  EXPECT_NEAR(fsw_thr_momentum_dump_interval(FSW_R(3.0), FSW_R(1.0), FSW_R(0.5)), 4.0, 1e-6);
  EXPECT_NEAR(fsw_thr_momentum_prop_per_dump(FSW_R(2.0), FSW_R(0.5), FSW_R(200.0)), 4.0 / (200.0 * 9.80665),
              1e-8);
  EXPECT_EQ(fsw_thr_momentum_dump_interval(FSW_R(3.0), kNaN, FSW_R(0.5)), FSW_R(0.0));
  EXPECT_EQ(fsw_thr_momentum_dump_interval(FSW_R(3.0), kInf, FSW_R(0.5)), FSW_R(0.0));
  EXPECT_EQ(fsw_thr_momentum_prop_per_dump(FSW_R(2.0), kNaN, FSW_R(200.0)), FSW_R(0.0));
  EXPECT_EQ(fsw_thr_momentum_prop_per_dump(FSW_R(2.0), kInf, FSW_R(200.0)), FSW_R(0.0));
  EXPECT_EQ(fsw_thr_momentum_prop_per_dump(FSW_R(2.0), FSW_R(0.5), kNaN), FSW_R(0.0));
  EXPECT_EQ(fsw_thr_momentum_prop_per_dump(FSW_R(2.0), FSW_R(0.5), kInf), FSW_R(0.0));
}

// fsw_link_sec.c fsw_link_sec_protect: cap < trailer || n > cap - trailer.
// A buffer that holds the trailer but not the packet and its trailer is
// refused before anything is written; one byte more and the packet goes.
// Verifies: REQ-LSEC-003
TEST(McdcLinkSec, BufferHoldingTheTrailerButNotThePacketIsRefused)
{
  const uint8_t key[32] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16,
                           17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32};
  uint8_t pkt[10];
  for (size_t i = 0; i < sizeof pkt; ++i) pkt[i] = static_cast<uint8_t>(0xA0u + i);
  const size_t fits = sizeof pkt + FSW_LINK_SEC_TRAILER_SIZE;  // 10 + 4 + 16 = 30 bytes
  ASSERT_EQ(fits, 30u);
  FswLinkSec s;
  ASSERT_EQ(fsw_link_sec_init(&s, key, sizeof key), FSW_OK);
  std::vector<uint8_t> out(fits, 0x5Au);
  size_t len = 99u;
  FswLinkError err = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_sec_protect(&s, pkt, sizeof pkt, out.data(), fits - 1u, &len, &err), FSW_E_BAD_INPUT);
  EXPECT_EQ(err, FSW_LINK_E_SPACE);
  EXPECT_EQ(len, 99u);
  for (uint8_t b : out) EXPECT_EQ(b, 0x5Au);
  EXPECT_EQ(s.tx_seq, 1u);  // no number used
  err = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_sec_protect(&s, pkt, sizeof pkt, out.data(), fits, &len, &err), FSW_OK);
  EXPECT_EQ(len, fits);
  EXPECT_EQ(0, std::memcmp(out.data(), pkt, sizeof pkt));
  EXPECT_EQ(s.tx_seq, 2u);
}

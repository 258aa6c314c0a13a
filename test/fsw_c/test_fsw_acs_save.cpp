// fsw_acs_save: the application's state image (fsw/fsw_acs_save.h).  A state
// restored from an image continues exactly as the original: the same
// actuator and health outputs, bit for bit, cycle after cycle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "acs_fixture.hpp"
#include "fsw/fsw_acs.h"
#include "fsw/fsw_acs_save.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

FswAcsConfig g_cfg;
FswAcsState g_a, g_b;

// A tumbling vehicle seen by every sensor, varying with the cycle c.
void sensors(FswAcsSensorMsg& m, uint64_t c)
{
  std::memset(&m, 0, sizeof m);
  m.t_ns = 100000000ull * (c + 1);
  m.att_valid = 1;
  for (int i = 0; i < 3; i++) {
    m.sigma_BN[i] = acsfix::R(0.1 * std::sin(0.01 * double(c) + i));
    m.omega_BN_B[i] = acsfix::R(0.01 * std::cos(0.02 * double(c) + i));
  }
  const double s = 1.0 / std::sqrt(3.0);
  m.css[0] = acsfix::R(s);
  m.css[2] = acsfix::R(s);
  m.css[4] = acsfix::R(s);
}

void cycle(FswAcsState& st, uint64_t c, FswAcsActuatorMsg& act, FswAcsHealthMsg& h)
{
  FswAcsSensorMsg in;
  sensors(in, c);
  std::memset(&act, 0, sizeof act);
  std::memset(&h, 0, sizeof h);
  (void)fsw_acs_cycle(&st, &g_cfg, &in, nullptr, &act, &h);
}

}  // namespace

// Verifies: REQ-ACS-017
TEST(FswAcsSave, TagAndSize)
{
  EXPECT_EQ(16u + sizeof(FswAcsState), fsw_acs_save_size());
  std::vector<uint8_t> buf(fsw_acs_save_size());
  size_t len = 0;
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_a, &g_cfg, nullptr));
  ASSERT_EQ(FSW_OK, fsw_acs_save(&g_a, buf.data(), buf.size(), &len));
  EXPECT_EQ(buf.size(), len);
  // the tag, little-endian: "KFSW", version 2, the state's and the real's sizes
  EXPECT_EQ(0, std::memcmp(buf.data(), "KFSW", 4));
  EXPECT_EQ(2u, buf[4] | buf[5] << 8 | buf[6] << 16 | unsigned(buf[7]) << 24);
  EXPECT_EQ(sizeof(FswAcsState), size_t(buf[8] | buf[9] << 8 | buf[10] << 16 | unsigned(buf[11]) << 24));
  EXPECT_EQ(sizeof(fsw_real), size_t(buf[12]));
  EXPECT_EQ(0, std::memcmp(buf.data() + 16, &g_a, sizeof g_a));
}

// Verifies: REQ-ACS-017
TEST(FswAcsSave, RestoredStateContinuesBitForBit)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_a, &g_cfg, nullptr));
  FswAcsActuatorMsg act_a, act_b;
  FswAcsHealthMsg h_a, h_b;
  for (uint64_t c = 0; c < 50; c++) cycle(g_a, c, act_a, h_a);
  std::vector<uint8_t> buf(fsw_acs_save_size());
  size_t len = 0;
  ASSERT_EQ(FSW_OK, fsw_acs_save(&g_a, buf.data(), buf.size(), &len));
  std::memset(&g_b, 0x5A, sizeof g_b);  // anything: restore replaces it whole
  ASSERT_EQ(FSW_OK, fsw_acs_restore(&g_b, buf.data(), len));
  double moved = 0.0;
  for (uint64_t c = 50; c < 150; c++) {
    cycle(g_a, c, act_a, h_a);
    cycle(g_b, c, act_b, h_b);
    ASSERT_EQ(0, std::memcmp(&act_a, &act_b, sizeof act_a)) << c;
    ASSERT_EQ(0, std::memcmp(&h_a, &h_b, sizeof h_a)) << c;
    for (int i = 0; i < FSW_MAX_RW; i++) moved += std::fabs(double(act_a.u_s[i]));
  }
  EXPECT_GT(moved, 0.0);  // the controller acted: the comparison saw live outputs
  EXPECT_EQ(0, std::memcmp(&g_a, &g_b, sizeof g_a));
}

// Verifies: REQ-ACS-017
TEST(FswAcsSave, RefusesAWrongImageAndLeavesTheStateAlone)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_a, &g_cfg, nullptr));
  std::vector<uint8_t> buf(fsw_acs_save_size());
  size_t len = 0;
  ASSERT_EQ(FSW_OK, fsw_acs_save(&g_a, buf.data(), buf.size(), &len));
  std::memset(&g_b, 0x33, sizeof g_b);
  const FswAcsState before = g_b;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_restore(&g_b, buf.data(), len - 1));  // length
  for (size_t byte : {0u, 4u, 8u, 12u}) {  // each field of the tag
    std::vector<uint8_t> bad = buf;
    bad[byte] ^= 0x01u;
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_restore(&g_b, bad.data(), bad.size())) << byte;
  }
  EXPECT_EQ(0, std::memcmp(&before, &g_b, sizeof g_b));
  // too small a buffer: nothing written, length 0
  std::vector<uint8_t> small(fsw_acs_save_size() - 1, 0xEE);
  len = 99;
  EXPECT_EQ(FSW_E_CAPACITY, fsw_acs_save(&g_a, small.data(), small.size(), &len));
  EXPECT_EQ(0u, len);
  for (uint8_t v : small) ASSERT_EQ(0xEE, v);
}

// Verifies: REQ-ACS-017, REQ-GEN-007
TEST(FswAcsSave, NullArguments)
{
  std::vector<uint8_t> buf(fsw_acs_save_size());
  size_t len = 0;
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_a, &g_cfg, nullptr));
  kt::each_null("fsw_acs_save", [](const FswAcsState* s, uint8_t* b, size_t* l) {
    return fsw_acs_save(s, b, fsw_acs_save_size(), l);
  }, static_cast<const FswAcsState*>(&g_a), buf.data(), &len);
  ASSERT_EQ(FSW_OK, fsw_acs_save(&g_a, buf.data(), buf.size(), &len));
  kt::each_null("fsw_acs_restore", [](FswAcsState* s, const uint8_t* b) {
    return fsw_acs_restore(s, b, fsw_acs_save_size());
  }, &g_b, static_cast<const uint8_t*>(buf.data()));
}

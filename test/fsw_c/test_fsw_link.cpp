// fsw_link: the wire codec of the FSW link (docs/icd.md).  The CRC against
// its published check value and an independent table-driven CRC written
// here; a command packet compared byte for byte with one assembled by hand
// from the ICD; reals as big-endian binary64 whatever the host (this test
// runs on the big-endian s390x and the little-endian targets alike); round
// trips of every packet at zero and full capacity; every single-bit error
// and every truncation rejected; counts, flags, lengths and APIDs checked;
// no message written on failure; no byte written past an encoder's buffer;
// and the stream deframer recovering after garbage and a corrupted packet.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fsw/fsw_link.h"
#include "kestrel_test_support.h"

namespace {

using R = fsw_real;
using Bytes = std::vector<uint8_t>;

// CRC-16/CCITT-FALSE, table-driven (an implementation independent of the
// library's bitwise one).
// CRC-16/CCITT-FALSE by its definition: each bit, MSB first, shifted
// through the register with the polynomial 0x1021 (the flight code uses a
// byte table; this is the independent reference).
uint16_t crc_ref(const uint8_t* p, size_t n, uint16_t crc = 0xFFFF)
{
  for (size_t i = 0; i < n; ++i) {
    for (int b = 7; b >= 0; --b) {
      const bool in = ((p[i] >> b) & 1) != 0;
      const bool top = (crc & 0x8000) != 0;
      crc = static_cast<uint16_t>(crc << 1);
      if (in != top) crc = static_cast<uint16_t>(crc ^ 0x1021);
    }
  }
  return crc;
}

// A sensor message with distinct values in every field (exact in float).
FswAcsSensorMsg sensor_msg(uint8_t nrw, uint8_t ncss)
{
  FswAcsSensorMsg m;
  std::memset(&m, 0, sizeof m);
  m.t_ns = 0x0123456789ABCDEFull;
  m.att_valid = 1;
  for (int i = 0; i < 3; ++i) {
    m.sigma_BN[i] = R(0.125) * R(i + 1);
    m.omega_BN_B[i] = R(-0.5) * R(i + 1);
    m.r_CoM_B[i] = R(0.25) + R(i);
  }
  for (uint8_t i = 0; i < nrw; ++i) {
    m.Omega[i] = R(100.5) - R(i);
    m.rw_avail[i] = static_cast<uint8_t>(i % 2);
  }
  for (uint8_t i = 0; i < ncss; ++i) {
    m.css[i] = R(0.0625) * R(i);
    m.css_avail[i] = static_cast<uint8_t>((i + 1) % 2);
  }
  m.thr_avail[0] = 1;  // bits 0 and FSW_MAX_THR - 1: both ends of the mask travel
  m.thr_avail[FSW_MAX_THR - 1] = 1;
  for (int i = 0; i < 3; ++i) {
    m.B_B[i] = R(2.5e-5) * R(i - 1) + R(1e-6);  // [T]
    m.r_N[i] = R(6.9e6) - R(1.5e6) * R(i);     // [m]
    m.v_N[i] = R(-7.5e3) + R(2e3) * R(i);      // [m/s]
  }
  m.mag_valid = 1;
  m.orbit_valid = 1;
  return m;
}

FswAcsActuatorMsg actuator_msg(uint8_t nrw, uint8_t nthr, uint8_t nmtq = 0)
{
  FswAcsActuatorMsg m;
  std::memset(&m, 0, sizeof m);
  m.wheels_active = 1;
  m.thrusters_active = 0;
  m.mtq_active = nmtq > 0 ? 1 : 0;
  for (uint8_t i = 0; i < nmtq; ++i) m.m_cmd[i] = R(-0.75) + R(0.25) * R(i);  // [A m^2]
  for (int i = 0; i < 3; ++i) m.Lr_B[i] = R(-0.01) * R(i + 1);
  for (uint8_t i = 0; i < nrw; ++i) {
    m.u_s[i] = R(0.001) * R(i);
    m.V[i] = R(-2.5) * R(i);
  }
  for (uint8_t i = 0; i < nthr; ++i) {
    m.F[i] = R(1.5) * R(i);
    m.t_on[i] = R(0.0125) * R(i);
  }
  return m;
}

FswAcsHealthMsg health_msg()
{
  FswAcsHealthMsg m;
  std::memset(&m, 0, sizeof m);
  m.status = FSW_W_SAT;
  m.mode = FSW_ACS_MODE_INERTIAL;
  m.actuation = FSW_ACS_ACT_THRUSTERS;
  m.safe_output = 1;
  m.cycles = 4000000000u;
  m.mode_changes = 3;
  for (int i = 0; i < FSW_ACS_NUM_STAGES; ++i) m.stage_status[i] = static_cast<FswStatus>(i % 2 ? -(i % 9) : (i % 4));
  for (int i = 0; i < 3; ++i) {
    m.sigma_BR[i] = R(0.01) * R(i);
    m.omega_BR_B[i] = R(-1e-3) * R(i);
    m.sun_hat_B[i] = R(i == 2);
  }
  m.att_err_angle = R(0.5);
  m.sun_angle_err = R(-0.25);
  m.sun_valid = 1;
  m.num_lit = 5;
  m.rw_failed = 0x8000000000000005ull;  // bit 63: all 64 bits travel
  m.rw_latched = 0x4ull;
  m.health.bad_input = 1;
  m.health.bad_time = 2;
  m.health.saturated = 3;
  m.health.singular = 4;
  m.health.rate = 5;
  m.health.other_error = 6;
  m.health.calls = 70000;
  m.health.last = FSW_E_TIME;
  m.policy = FSW_ACS_MOM_MAGNETORQUERS;
  m.detumbled = 1;
  m.dump_phase = 2;
  for (int i = 0; i < 3; ++i) {
    m.h_w_B[i] = R(0.125) * R(i + 1) - R(0.3);  // [N m s]
    m.tau_mtq_B[i] = R(-3e-6) * R(i + 1);       // [N m]
  }
  m.rate_est = R(0.0375);
  m.dumps = 3000000000u;
  m.prop_used = R(0.0625);
  return m;
}

Bytes encode_sensor(const FswAcsSensorMsg& m, uint8_t nrw, uint8_t ncss, uint16_t seq = 7)
{
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  FswLinkError e = FSW_LINK_E_SPACE;
  EXPECT_EQ(fsw_link_encode_sensor(&m, nrw, ncss, seq, b.data(), b.size(), &len, &e), FSW_OK);
  EXPECT_EQ(e, FSW_LINK_OK);
  b.resize(len);
  return b;
}

void fix_crc(Bytes& b)
{
  const uint16_t c = crc_ref(b.data(), b.size() - 2);
  b[b.size() - 2] = static_cast<uint8_t>(c >> 8);
  b[b.size() - 1] = static_cast<uint8_t>(c);
}

}  // namespace

// Verifies: REQ-LINK-001
TEST(FswLink, CrcMatchesTheCheckValueAndTheBitwiseDefinition)
{
  const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(fsw_link_crc16(check, sizeof check, 0xFFFF), 0x29B1);  // CRC-16/CCITT-FALSE check value
  EXPECT_EQ(fsw_link_crc16(check, 0, 0xFFFF), 0xFFFF);
  // continuing a CRC over a split buffer gives the same result
  EXPECT_EQ(fsw_link_crc16(check + 4, 5, fsw_link_crc16(check, 4, 0xFFFF)), 0x29B1);
  uint32_t x = 12345;
  Bytes data(1000);
  for (auto& v : data) {
    x = x * 1103515245u + 12345u;
    v = static_cast<uint8_t>(x >> 16);
  }
  for (size_t n : {1u, 2u, 17u, 255u, 1000u}) EXPECT_EQ(fsw_link_crc16(data.data(), n, 0xFFFF), crc_ref(data.data(), n)) << n;
  // every byte value from registers with each high byte: every table entry
  for (unsigned hi = 0; hi < 256; hi += 51) {
    for (unsigned v = 0; v < 256; ++v) {
      const uint8_t byte = static_cast<uint8_t>(v);
      const uint16_t init = static_cast<uint16_t>((hi << 8) | (v ^ 0x5A));
      ASSERT_EQ(fsw_link_crc16(&byte, 1, init), crc_ref(&byte, 1, init)) << hi << " " << v;
    }
  }
}

// A command packet assembled by hand from the ICD's byte table.
// Verifies: REQ-LINK-002
TEST(FswLink, CommandPacketBytesAreTheIcdsBytes)
{
  FswAcsCmdMsg cmd{};
  cmd.mode = FSW_ACS_MODE_INERTIAL;
  cmd.actuation = FSW_ACS_ACT_WHEELS;
  cmd.set_gains = 1;
  cmd.sigma_R0N[1] = R(-2.5);  // sent although set_ref = 0 (the receiver ignores it)
  cmd.K = R(0.5);
  cmd.P = R(30.0);
  cmd.set_policy = 1;
  cmd.policy = FSW_ACS_MOM_THRUSTERS;
  uint8_t buf[96];
  size_t len = 0;
  ASSERT_EQ(fsw_link_encode_cmd(&cmd, 0x0102030405060708ull, 16389 /* wraps to 5 */, buf, sizeof buf, &len, nullptr),
            FSW_OK);
  Bytes want = {0x19, 0x02,  // version 0, type 1 (TC), sec. header 1, APID 0x102
                0xC0, 0x05,  // unsegmented, sequence count 5
                0x00, 0x37,  // data length 8 + 46 + 2 - 1 = 55
                0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08,  // t_ns
                0x01, 0x00, 0x00, 0x01,                          // mode, actuation, set_ref, set_gains
                0, 0, 0, 0, 0, 0, 0, 0,                          // sigma_R0N[0] = 0
                0xC0, 0x04, 0, 0, 0, 0, 0, 0,                    // sigma_R0N[1] = -2.5
                0, 0, 0, 0, 0, 0, 0, 0,                          // sigma_R0N[2] = 0
                0x3F, 0xE0, 0, 0, 0, 0, 0, 0,                    // K = 0.5
                0x40, 0x3E, 0, 0, 0, 0, 0, 0,                    // P = 30
                0x01, 0x01,                                      // set_policy, policy (thrusters)
                0x00, 0x00};                                     // CRC
  fix_crc(want);
  ASSERT_EQ(len, want.size());
  EXPECT_EQ(Bytes(buf, buf + len), want);
  FswLinkPacket p;
  ASSERT_EQ(fsw_link_parse(buf, len, &p, nullptr), FSW_OK);
  EXPECT_EQ(p.apid, FSW_LINK_APID_CMD);
  EXPECT_EQ(p.type, 1);
  EXPECT_EQ(p.seq, 5);
  EXPECT_EQ(p.t_ns, 0x0102030405060708ull);
  FswAcsCmdMsg back = {-1, -1};
  ASSERT_EQ(fsw_link_decode_cmd(&p, &back, nullptr), FSW_OK);
  EXPECT_EQ(back.mode, FSW_ACS_MODE_INERTIAL);
  EXPECT_EQ(back.actuation, FSW_ACS_ACT_WHEELS);
  EXPECT_EQ(back.set_ref, 0);
  EXPECT_EQ(back.set_gains, 1);
  EXPECT_EQ(back.sigma_R0N[1], R(-2.5));
  EXPECT_EQ(back.K, R(0.5));
  EXPECT_EQ(back.P, R(30.0));
  EXPECT_EQ(back.set_policy, 1);
  EXPECT_EQ(back.policy, FSW_ACS_MOM_THRUSTERS);
  // a flag other than 0/1 is refused both ways, and the message is not written
  Bytes b(buf, buf + len);
  b[FSW_LINK_HEADER_SIZE + 2] = 2;  // set_ref
  fix_crc(b);
  ASSERT_EQ(fsw_link_parse(b.data(), b.size(), &p, nullptr), FSW_OK);
  FswAcsCmdMsg untouched = {-7, -7};
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_decode_cmd(&p, &untouched, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  EXPECT_EQ(untouched.mode, -7);
  cmd.set_gains = 3;
  EXPECT_EQ(fsw_link_encode_cmd(&cmd, 0, 0, buf, sizeof buf, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  cmd.set_gains = 0;
  cmd.set_ref = 2;
  EXPECT_EQ(fsw_link_encode_cmd(&cmd, 0, 0, buf, sizeof buf, &len, &e), FSW_E_BAD_INPUT);
  cmd.set_ref = 0;
  cmd.set_policy = 2;
  EXPECT_EQ(fsw_link_encode_cmd(&cmd, 0, 0, buf, sizeof buf, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  Bytes good(want);
  good[FSW_LINK_HEADER_SIZE + 44] = 2;  // set_policy not 0/1 on the wire
  fix_crc(good);
  ASSERT_EQ(fsw_link_parse(good.data(), good.size(), &p, nullptr), FSW_OK);
  EXPECT_EQ(fsw_link_decode_cmd(&p, &untouched, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  EXPECT_EQ(untouched.mode, -7);
  for (const int bad_policy : {-1, 256}) {
    cmd.set_policy = 1;
    cmd.policy = bad_policy;
    EXPECT_EQ(fsw_link_encode_cmd(&cmd, 0, 0, buf, sizeof buf, &len, &e), FSW_E_BAD_INPUT) << bad_policy;
    EXPECT_EQ(e, FSW_LINK_E_COUNT);
  }
}

// Reals are IEEE-754 binary64, big-endian, on every host.
// Verifies: REQ-LINK-002
TEST(FswLink, RealsAreBigEndianBinary64)
{
  FswAcsSensorMsg m = sensor_msg(0, 0);
  m.sigma_BN[0] = R(1.0);    // 3FF0 0000 0000 0000
  m.sigma_BN[1] = R(-2.5);   // C004 0000 0000 0000
  m.sigma_BN[2] = R(0.1);    // 3FB9 9999 9999 999A in double; the float 0.1 widened in float builds
  const Bytes b = encode_sensor(m, 0, 0);
  ASSERT_EQ(b.size(), FSW_LINK_HEADER_SIZE + 158u + 2u);
  const size_t s = FSW_LINK_HEADER_SIZE + 4;  // sigma_BN[0]
  EXPECT_EQ(Bytes(b.begin() + s, b.begin() + s + 8), (Bytes{0x3F, 0xF0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(Bytes(b.begin() + s + 8, b.begin() + s + 16), (Bytes{0xC0, 0x04, 0, 0, 0, 0, 0, 0}));
  if (sizeof(R) == 8)
    EXPECT_EQ(Bytes(b.begin() + s + 16, b.begin() + s + 24), (Bytes{0x3F, 0xB9, 0x99, 0x99, 0x99, 0x99, 0x99, 0x9A}));
  else  // the float nearest 0.1 (0x3DCCCCCD), widened exactly
    EXPECT_EQ(Bytes(b.begin() + s + 16, b.begin() + s + 24), (Bytes{0x3F, 0xB9, 0x99, 0x99, 0xA0, 0, 0, 0}));
  // the time stamp is in the secondary header, big-endian
  EXPECT_EQ(Bytes(b.begin() + 6, b.begin() + 14), (Bytes{0x01, 0x23, 0x45, 0x67, 0x89, 0xAB, 0xCD, 0xEF}));
}

// Verifies: REQ-LINK-003
TEST(FswLink, EveryPacketRoundTripsAtZeroAndFullCapacity)
{
  for (const auto& n : std::vector<std::pair<uint8_t, uint8_t>>{{0, 0}, {4, 8}, {FSW_MAX_RW, FSW_MAX_CSS}}) {
    const FswAcsSensorMsg m = sensor_msg(n.first, n.second);
    const Bytes b = encode_sensor(m, n.first, n.second, 16383);
    EXPECT_EQ(b.size(), FSW_LINK_HEADER_SIZE + FSW_LINK_SENSOR_PAYLOAD(n.first, n.second) + 2u);
    FswLinkPacket p;
    ASSERT_EQ(fsw_link_parse(b.data(), b.size(), &p, nullptr), FSW_OK);
    EXPECT_EQ(p.seq, 16383);
    FswAcsSensorMsg back;
    std::memset(&back, 0x5A, sizeof back);
    uint8_t nrw = 99, ncss = 99;
    ASSERT_EQ(fsw_link_decode_sensor(&p, &back, &nrw, &ncss, nullptr), FSW_OK);
    EXPECT_EQ(nrw, n.first);
    EXPECT_EQ(ncss, n.second);
    EXPECT_EQ(std::memcmp(&back, &m, sizeof m), 0) << "sensor " << int(n.first) << "/" << int(n.second);
  }
  struct Counts {
    uint8_t rw, thr, mtq;
  };
  for (const Counts n : {Counts{0, 0, 0}, Counts{4, 9, 3}, Counts{0, 0, FSW_MAX_MTQ},
                         Counts{FSW_MAX_RW, FSW_MAX_THR, FSW_MAX_MTQ}}) {
    const FswAcsActuatorMsg m = actuator_msg(n.rw, n.thr, n.mtq);
    Bytes b(FSW_LINK_MAX_PACKET);
    size_t len = 0;
    ASSERT_EQ(fsw_link_encode_actuator(&m, n.rw, n.thr, n.mtq, 42, 9, b.data(), b.size(), &len, nullptr), FSW_OK);
    EXPECT_EQ(len, FSW_LINK_HEADER_SIZE + FSW_LINK_ACTUATOR_PAYLOAD(n.rw, n.thr, n.mtq) + 2u);
    FswLinkPacket p;
    ASSERT_EQ(fsw_link_parse(b.data(), len, &p, nullptr), FSW_OK);
    EXPECT_EQ(p.type, 0);
    EXPECT_EQ(p.t_ns, 42u);
    FswAcsActuatorMsg back;
    std::memset(&back, 0x5A, sizeof back);
    uint8_t nrw = 0, nthr = 0, nmtq = 99;
    ASSERT_EQ(fsw_link_decode_actuator(&p, &back, &nrw, &nthr, &nmtq, nullptr), FSW_OK);
    EXPECT_EQ(std::memcmp(&back, &m, sizeof m), 0);
    EXPECT_EQ(nrw, n.rw);
    EXPECT_EQ(nthr, n.thr);
    EXPECT_EQ(nmtq, n.mtq);
  }
  const FswAcsHealthMsg h = health_msg();
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  ASSERT_EQ(fsw_link_encode_health(&h, 77, 1, b.data(), b.size(), &len, nullptr), FSW_OK);
  EXPECT_EQ(len, FSW_LINK_HEADER_SIZE + FSW_LINK_HEALTH_PAYLOAD + 2u);
  FswLinkPacket p;
  ASSERT_EQ(fsw_link_parse(b.data(), len, &p, nullptr), FSW_OK);
  FswAcsHealthMsg back;
  std::memset(&back, 0x5A, sizeof back);
  ASSERT_EQ(fsw_link_decode_health(&p, &back, nullptr), FSW_OK);
  EXPECT_EQ(std::memcmp(&back, &h, sizeof h), 0);
}

// CRC-16 detects every single-bit error; every truncation is short.
// Verifies: REQ-LINK-004
TEST(FswLink, EverySingleBitErrorAndTruncationIsRejected)
{
  // the full sensor and actuator packets (the largest of this build) and the health packet
  std::vector<Bytes> packets = {encode_sensor(sensor_msg(4, 6), 4, 6),
                                encode_sensor(sensor_msg(FSW_MAX_RW, FSW_MAX_CSS), FSW_MAX_RW, FSW_MAX_CSS)};
  for (int k = 0; k < 2; ++k) {
    Bytes b(FSW_LINK_MAX_PACKET);
    size_t len = 0;
    if (k == 0) {
      const FswAcsActuatorMsg a = actuator_msg(FSW_MAX_RW, FSW_MAX_THR, FSW_MAX_MTQ);
      ASSERT_EQ(fsw_link_encode_actuator(&a, FSW_MAX_RW, FSW_MAX_THR, FSW_MAX_MTQ, 1, 2, b.data(), b.size(), &len,
                                         nullptr),
                FSW_OK);
    } else {
      const FswAcsHealthMsg h = health_msg();
      ASSERT_EQ(fsw_link_encode_health(&h, 1, 2, b.data(), b.size(), &len, nullptr), FSW_OK);
    }
    b.resize(len);
    packets.push_back(b);
  }
  EXPECT_EQ(std::max({packets[1].size(), packets[2].size(), packets[3].size()}), FSW_LINK_MAX_PACKET);
  for (const Bytes& good : packets) {
    FswLinkPacket p;
    std::memset(&p, 0x33, sizeof p);
    const FswLinkPacket untouched = p;
    for (size_t bit = 0; bit < good.size() * 8; ++bit) {
      Bytes b = good;
      b[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      FswLinkError e = FSW_LINK_OK;
      ASSERT_EQ(fsw_link_parse(b.data(), b.size(), &p, &e), FSW_E_BAD_INPUT) << "bit " << bit;
      EXPECT_NE(e, FSW_LINK_OK);
    }
    for (size_t n = 0; n < good.size(); ++n) {
      FswLinkError e = FSW_LINK_OK;
      ASSERT_EQ(fsw_link_parse(good.data(), n, &p, &e), FSW_E_BAD_INPUT) << n;
      EXPECT_EQ(e, FSW_LINK_E_SHORT) << n;
    }
    EXPECT_EQ(std::memcmp(&p, &untouched, sizeof p), 0);  // never written on failure
  }
}

// Verifies: REQ-LINK-004
TEST(FswLink, DecodersCheckApidLengthCountsAndFlags)
{
  const Bytes good = encode_sensor(sensor_msg(4, 6), 4, 6);
  FswAcsSensorMsg m;
  std::memset(&m, 0x77, sizeof m);
  unsigned char before[sizeof m];
  std::memcpy(before, &m, sizeof m);
  uint8_t nrw = 0, ncss = 0;
  auto decode = [&](Bytes b) {
    fix_crc(b);
    FswLinkPacket p;
    FswLinkError e = FSW_LINK_OK;
    if (fsw_link_parse(b.data(), b.size(), &p, &e) != FSW_OK) return e;
    const FswStatus st = fsw_link_decode_sensor(&p, &m, &nrw, &ncss, &e);
    EXPECT_EQ(st, e == FSW_LINK_OK ? FSW_OK : FSW_E_BAD_INPUT);
    return e;
  };
  const size_t pay = FSW_LINK_HEADER_SIZE;
  Bytes b = good;
  b[pay + 0] = FSW_MAX_RW + 1;  // a count beyond the capacity
  EXPECT_EQ(decode(b), FSW_LINK_E_COUNT);
  b = good;
  b[pay + 0] = 5;  // a count that does not match the length
  EXPECT_EQ(decode(b), FSW_LINK_E_LENGTH);
  b = good;
  b[pay + 2] = 2;  // att_valid not 0/1
  EXPECT_EQ(decode(b), FSW_LINK_E_COUNT);
  b = good;
  b[pay + 3] = 1;  // reserved byte
  EXPECT_EQ(decode(b), FSW_LINK_E_COUNT);
  b = good;
  b[b.size() - 2 - 74 - 8 - 1] = 7;  // the last css_avail flag (before the u64 thruster mask, 72 bytes
                                     // of B_B, r_N, v_N and the two flags)
  EXPECT_EQ(decode(b), FSW_LINK_E_COUNT);
  b = good;
  b[1] = 0x81;  // APID 0x181: an actuator packet's
  b[0] = 0x09;  // with the telemetry type
  EXPECT_EQ(decode(b), FSW_LINK_E_APID);
  b = good;
  b[0] |= 0x20;  // version 1
  EXPECT_EQ(decode(b), FSW_LINK_E_HEADER);
  b = good;
  b[0] &= static_cast<uint8_t>(~0x08);  // no secondary header
  EXPECT_EQ(decode(b), FSW_LINK_E_HEADER);
  b = good;
  b[2] &= 0x3F;  // segmented
  EXPECT_EQ(decode(b), FSW_LINK_E_HEADER);
  EXPECT_EQ(std::memcmp(before, &m, sizeof m), 0);  // the message was never written
  EXPECT_EQ(decode(good), FSW_LINK_OK);
}

// Verifies: REQ-LINK-005
TEST(FswLink, EncodersNeverWritePastTheirBufferAndRejectBadCounts)
{
  const FswAcsSensorMsg m = sensor_msg(4, 4);
  const size_t need = FSW_LINK_HEADER_SIZE + FSW_LINK_SENSOR_PAYLOAD(4, 4) + 2;
  for (size_t cap = 0; cap < need; ++cap) {
    Bytes b(cap + 8, 0xEE);
    size_t len = 12345;
    FswLinkError e = FSW_LINK_OK;
    ASSERT_EQ(fsw_link_encode_sensor(&m, 4, 4, 0, b.data(), cap, &len, &e), FSW_E_BAD_INPUT) << cap;
    EXPECT_EQ(e, FSW_LINK_E_SPACE);
    for (size_t i = cap; i < b.size(); ++i) ASSERT_EQ(b[i], 0xEE) << cap;
  }
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_encode_sensor(&m, FSW_MAX_RW + 1, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  const FswAcsCmdMsg bad = {300, 0};
  EXPECT_EQ(fsw_link_encode_cmd(&bad, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(fsw_link_encode_sensor(nullptr, 0, 0, 0, b.data(), b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_parse(nullptr, 10, nullptr, &e), FSW_E_NULL_ARG);
}

// A byte stream with garbage, a corrupted packet and packets split anywhere.
// Verifies: REQ-LINK-006
TEST(FswLink, DeframerRecoversAfterGarbageAndCorruption)
{
  std::vector<Bytes> pkts;
  for (uint16_t k = 0; k < 5; ++k) {
    FswAcsSensorMsg m = sensor_msg(4, 3);
    m.t_ns = 1000u * k;
    pkts.push_back(encode_sensor(m, 4, 3, k));
  }
  Bytes stream = {0x00, 0x1A, 0xCF, 0x55, 0x1A};  // garbage with marker prefixes
  for (size_t k = 0; k < pkts.size(); ++k) {
    Bytes f(pkts[k].size() + FSW_LINK_ASM_SIZE);
    size_t len = 0;
    ASSERT_EQ(fsw_link_frame(pkts[k].data(), pkts[k].size(), f.data(), f.size(), &len), FSW_OK);
    ASSERT_EQ(len, f.size());
    EXPECT_EQ(Bytes(f.begin(), f.begin() + 4), (Bytes{0x1A, 0xCF, 0xFC, 0x1D}));
    if (k == 2) f[30] ^= 0x10;  // corrupt packet 2
    if (k == 3) stream.push_back(0xFF);  // a stray byte before packet 3
    stream.insert(stream.end(), f.begin(), f.end());
  }
  // feed in pieces of every size from 1 byte to all at once: the same packets
  for (size_t piece : {size_t{1}, size_t{3}, size_t{64}, stream.size()}) {
    FswLinkDeframer d;
    fsw_link_deframer_init(&d);
    std::vector<uint16_t> got;
    size_t at = 0;
    while (at < stream.size()) {
      const size_t n = std::min(piece, stream.size() - at);
      size_t off = 0;
      while (off < n) {
        const uint8_t* pkt = nullptr;
        size_t pl = 0;
        off += fsw_link_deframer_push(&d, stream.data() + at + off, n - off, &pkt, &pl);
        if (pkt) {
          FswLinkPacket p;
          ASSERT_EQ(fsw_link_parse(pkt, pl, &p, nullptr), FSW_OK);
          got.push_back(p.seq);
        } else {
          break;
        }
      }
      at += n;
    }
    EXPECT_EQ(got, (std::vector<uint16_t>{0, 1, 3, 4})) << "piece " << piece;
    EXPECT_EQ(d.packets, 4u);
    EXPECT_GE(d.rejected, 1u);
    EXPECT_GE(d.sync_slips, 6u);
  }
}

// Issue 21 (seed 2112): the deframer's buffer holds a prefix of the marker,
// or the marker and more, whenever a push returns: a byte that cannot start
// the marker is skipped (and counted) in the call that brought it, even when
// it is the last byte of the input, and a byte that can is kept.
// Verifies: REQ-LINK-006
TEST(FswLink, Issue21DeframerKeepsOnlyAMarkerPrefixBetweenPushes)
{
  const uint8_t marker[4] = {0x1A, 0xCF, 0xFC, 0x1D};
  const Bytes stream = {0x55, 0x1A, 0xCF, 0x00, 0x1A, 0x1A, 0xCF, 0xFC, 0x77};
  for (size_t piece : {size_t{1}, size_t{2}, stream.size()}) {
    FswLinkDeframer d;
    fsw_link_deframer_init(&d);
    size_t at = 0;
    while (at < stream.size()) {
      const uint8_t* pkt = nullptr;
      size_t pl = 0;
      const size_t n = std::min(piece, stream.size() - at);
      EXPECT_EQ(fsw_link_deframer_push(&d, stream.data() + at, n, &pkt, &pl), n);  // no packet: all taken
      EXPECT_EQ(pkt, nullptr);
      at += n;
      ASSERT_LE(d.have, sizeof marker) << "piece " << piece << " at " << at;
      for (size_t i = 0; i < d.have; i++) EXPECT_EQ(d.buf[i], marker[i]) << "piece " << piece << " at " << at;
    }
    // the hunt: 0x55 skipped; 1A CF then 00 breaks it: 1A, CF, 00 skipped;
    // 1A then 1A: the first 1A skipped; 1A CF FC then 77: all four skipped.
    EXPECT_EQ(d.sync_slips, 1u + 3u + 1u + 4u) << "piece " << piece;
    EXPECT_EQ(d.have, 0u) << "piece " << piece;
    EXPECT_EQ(d.packets, 0u);
  }
  // a lone first byte of the marker is kept for the next push
  FswLinkDeframer d;
  fsw_link_deframer_init(&d);
  const uint8_t* pkt = nullptr;
  size_t pl = 0;
  EXPECT_EQ(fsw_link_deframer_push(&d, marker, 1, &pkt, &pl), 1u);
  EXPECT_EQ(d.have, 1u);
  EXPECT_EQ(d.sync_slips, 0u);
}

// Every argument and range check of the encoders, the parser, the decoders,
// the framer and the deframer, one condition at a time (branch coverage of
// fsw_link.c: each operand of each || decides once).
// Verifies: REQ-LINK-004
TEST(FswLink, EveryArgumentAndRangeCheckRejectsAlone)
{
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  FswLinkError e = FSW_LINK_OK;
  const FswAcsSensorMsg s = sensor_msg(2, 2);
  const FswAcsActuatorMsg a = actuator_msg(2, 2, 1);
  const FswAcsHealthMsg h = health_msg();
  const FswAcsCmdMsg c = {1, 1};
  // CRC of a null buffer: the running value unchanged
  EXPECT_EQ(fsw_link_crc16(nullptr, 5, 0x1234), 0x1234);
  // encoders: each null, each count, each mode range, each short buffer
  EXPECT_EQ(fsw_link_encode_sensor(&s, 2, 2, 0, nullptr, b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_sensor(&s, 2, 2, 0, b.data(), b.size(), nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_sensor(&s, 2, FSW_MAX_CSS + 1, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  EXPECT_EQ(fsw_link_encode_cmd(nullptr, 0, 0, b.data(), b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_cmd(&c, 0, 0, nullptr, b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_cmd(&c, 0, 0, b.data(), b.size(), nullptr, &e), FSW_E_NULL_ARG);
  for (const FswAcsCmdMsg bad : {FswAcsCmdMsg{-1, 0}, FswAcsCmdMsg{256, 0}, FswAcsCmdMsg{0, -1}, FswAcsCmdMsg{0, 256}}) {
    EXPECT_EQ(fsw_link_encode_cmd(&bad, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
    EXPECT_EQ(e, FSW_LINK_E_COUNT);
    FswAcsHealthMsg hb = h;
    hb.mode = bad.mode;
    hb.actuation = bad.actuation;
    EXPECT_EQ(fsw_link_encode_health(&hb, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
    EXPECT_EQ(e, FSW_LINK_E_COUNT);
  }
  for (const int bad_policy : {-1, 256}) {  // the momentum policy travels as a u8
    FswAcsCmdMsg cb = c;
    cb.policy = bad_policy;
    EXPECT_EQ(fsw_link_encode_cmd(&cb, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
    EXPECT_EQ(e, FSW_LINK_E_COUNT);
    FswAcsHealthMsg hb = h;
    hb.policy = bad_policy;
    EXPECT_EQ(fsw_link_encode_health(&hb, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
    EXPECT_EQ(e, FSW_LINK_E_COUNT);
  }
  EXPECT_EQ(fsw_link_encode_cmd(&c, 0, 0, b.data(), 14 + 4 + 1, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_SPACE);
  EXPECT_EQ(fsw_link_encode_actuator(nullptr, 2, 2, 1, 0, 0, b.data(), b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_actuator(&a, 2, 2, 1, 0, 0, nullptr, b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_actuator(&a, 2, 2, 1, 0, 0, b.data(), b.size(), nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_actuator(&a, FSW_MAX_RW + 1, 2, 1, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(fsw_link_encode_actuator(&a, 2, FSW_MAX_THR + 1, 1, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_encode_actuator(&a, 2, 2, FSW_MAX_MTQ + 1, 0, 0, b.data(), b.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  EXPECT_EQ(fsw_link_encode_actuator(&a, 2, 2, 1, 0, 0, b.data(), 20, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_SPACE);
  EXPECT_EQ(fsw_link_encode_health(nullptr, 0, 0, b.data(), b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_health(&h, 0, 0, nullptr, b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_health(&h, 0, 0, b.data(), b.size(), nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_health(&h, 0, 0, b.data(), 100, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_SPACE);
  // thrusters_active and mtq_active travel as flags (ICD: actuator offsets 4 and 5)
  FswAcsActuatorMsg at = a;
  at.thrusters_active = 7;
  at.mtq_active = 200;
  ASSERT_EQ(fsw_link_encode_actuator(&at, 2, 2, 1, 0, 0, b.data(), b.size(), &len, &e), FSW_OK);
  EXPECT_EQ(b[FSW_LINK_HEADER_SIZE + 4], 1u);
  EXPECT_EQ(b[FSW_LINK_HEADER_SIZE + 5], 1u);

  // parser: null packet pointer; a data length too small for the headers
  FswLinkPacket p;
  Bytes pk = encode_sensor(s, 2, 2);
  EXPECT_EQ(fsw_link_parse(pk.data(), pk.size(), nullptr, &e), FSW_E_NULL_ARG);
  Bytes tiny = pk;
  tiny[4] = 0;
  tiny[5] = 8;  // 9 bytes after the primary header: less than 8 + CRC ... + 1
  fix_crc(tiny);
  EXPECT_EQ(fsw_link_parse(tiny.data(), tiny.size(), &p, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_HEADER);

  // decoders: each null; the right APID with the wrong type; short payloads
  ASSERT_EQ(fsw_link_parse(pk.data(), pk.size(), &p, &e), FSW_OK);
  FswAcsSensorMsg ms;
  FswAcsCmdMsg mc;
  FswAcsActuatorMsg ma;
  FswAcsHealthMsg mh;
  uint8_t n1 = 0, n2 = 0, n3 = 0;
  EXPECT_EQ(fsw_link_decode_sensor(nullptr, &ms, &n1, &n2, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_sensor(&p, nullptr, &n1, &n2, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_sensor(&p, &ms, nullptr, &n2, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_sensor(&p, &ms, &n1, nullptr, &e), FSW_E_NULL_ARG);
  FswLinkPacket np = p;
  np.payload = nullptr;
  EXPECT_EQ(fsw_link_decode_sensor(&np, &ms, &n1, &n2, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_cmd(nullptr, &mc, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_cmd(&p, nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_cmd(&np, &mc, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_actuator(nullptr, &ma, &n1, &n2, &n3, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_actuator(&p, nullptr, &n1, &n2, &n3, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_actuator(&p, &ma, nullptr, &n2, &n3, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_actuator(&p, &ma, &n1, nullptr, &n3, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_actuator(&p, &ma, &n1, &n2, nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_actuator(&np, &ma, &n1, &n2, &n3, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_health(nullptr, &mh, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_health(&p, nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_health(&np, &mh, &e), FSW_E_NULL_ARG);
  FswLinkPacket wrong_type = p;
  wrong_type.type = 0;  // APID 0x101 as telemetry
  EXPECT_EQ(fsw_link_decode_sensor(&wrong_type, &ms, &n1, &n2, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_APID);
  // synthetic payloads of given lengths under a packet of the given APID
  auto with = [&](uint16_t apid, uint8_t type, const Bytes& payload) {
    FswLinkPacket q;
    q.apid = apid;
    q.type = type;
    q.seq = 0;
    q.t_ns = 0;
    q.payload = payload.data();
    q.payload_len = payload.size();
    q.packet_len = payload.size() + 16;
    return q;
  };
  const Bytes short3(3, 0);
  FswLinkPacket q = with(FSW_LINK_APID_SENSOR, 1, short3);
  EXPECT_EQ(fsw_link_decode_sensor(&q, &ms, &n1, &n2, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_LENGTH);
  Bytes cnt(FSW_LINK_SENSOR_PAYLOAD(0, 0), 0);
  cnt[1] = FSW_MAX_CSS + 1;
  q = with(FSW_LINK_APID_SENSOR, 1, cnt);
  EXPECT_EQ(fsw_link_decode_sensor(&q, &ms, &n1, &n2, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
  q = with(FSW_LINK_APID_CMD, 1, short3);
  EXPECT_EQ(fsw_link_decode_cmd(&q, &mc, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_LENGTH);
  for (const size_t at : {size_t{3}, size_t{44}}) {  // set_gains, set_policy not 0/1
    Bytes cmd_flag(FSW_LINK_CMD_PAYLOAD, 0);
    cmd_flag[at] = 2;
    q = with(FSW_LINK_APID_CMD, 1, cmd_flag);
    EXPECT_EQ(fsw_link_decode_cmd(&q, &mc, &e), FSW_E_BAD_INPUT) << at;
    EXPECT_EQ(e, FSW_LINK_E_COUNT) << at;
  }
  q = with(FSW_LINK_APID_ACTUATOR, 1, Bytes(FSW_LINK_ACTUATOR_PAYLOAD(0, 0, 0), 0));
  EXPECT_EQ(fsw_link_decode_actuator(&q, &ma, &n1, &n2, &n3, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_APID);
  q = with(FSW_LINK_APID_ACTUATOR, 0, short3);
  EXPECT_EQ(fsw_link_decode_actuator(&q, &ma, &n1, &n2, &n3, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_LENGTH);
  for (int which = 0; which < 10; ++which) {  // ICD offsets: counts 0..2, flags 3..5, reserved 6..7
    Bytes pa(FSW_LINK_ACTUATOR_PAYLOAD(0, 0, 0), 0);
    if (which == 0) pa[0] = FSW_MAX_RW + 1;
    if (which == 1) pa[1] = FSW_MAX_THR + 1;
    if (which == 2) pa[2] = FSW_MAX_MTQ + 1;
    if (which == 3) pa[0] = 1;  // one wheel declared, none in the payload
    if (which == 4) pa[2] = 1;  // one rod declared, none in the payload
    if (which == 5) pa[3] = 2;  // wheels_active
    if (which == 6) pa[4] = 2;  // thrusters_active
    if (which == 7) pa[5] = 2;  // mtq_active
    if (which == 8) pa[6] = 1;  // reserved
    if (which == 9) pa[7] = 0x80;
    q = with(FSW_LINK_APID_ACTUATOR, 0, pa);
    n1 = n2 = n3 = 77;
    EXPECT_EQ(fsw_link_decode_actuator(&q, &ma, &n1, &n2, &n3, &e), FSW_E_BAD_INPUT) << which;
    EXPECT_EQ(e, which == 3 || which == 4 ? FSW_LINK_E_LENGTH : FSW_LINK_E_COUNT) << which;
    EXPECT_EQ(n3, 77) << which;
  }
  q = with(FSW_LINK_APID_HEALTH, 1, Bytes(FSW_LINK_HEALTH_PAYLOAD, 0));
  EXPECT_EQ(fsw_link_decode_health(&q, &mh, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_APID);
  q = with(FSW_LINK_APID_HEALTH, 0, short3);
  EXPECT_EQ(fsw_link_decode_health(&q, &mh, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_LENGTH);
  for (int which = 0; which < 5; ++which) {
    Bytes ph(FSW_LINK_HEALTH_PAYLOAD, 0);
    ph[7] = FSW_ACS_NUM_STAGES;
    if (which == 0) ph[4] = 2;  // safe_output
    if (which == 1) ph[5] = 2;  // sun_valid
    if (which == 2) ph[7] = FSW_ACS_NUM_STAGES + 1;
    if (which == 3) ph[183] = 2;  // detumbled (ICD offset 183)
    if (which == 4) ph[185] = 1;  // reserved (ICD offset 185)
    q = with(FSW_LINK_APID_HEALTH, 0, ph);
    EXPECT_EQ(fsw_link_decode_health(&q, &mh, &e), FSW_E_BAD_INPUT) << which;
    EXPECT_EQ(e, FSW_LINK_E_COUNT) << which;
  }

  // framer and deframer arguments
  EXPECT_EQ(fsw_link_frame(nullptr, 4, b.data(), b.size(), &len), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_frame(pk.data(), pk.size(), nullptr, b.size(), &len), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_frame(pk.data(), pk.size(), b.data(), b.size(), nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_frame(pk.data(), pk.size(), b.data(), pk.size() + 3, &len), FSW_E_BAD_INPUT);
  FswLinkDeframer d;
  fsw_link_deframer_init(&d);
  const uint8_t* out = nullptr;
  size_t out_len = 0;
  EXPECT_EQ(fsw_link_deframer_push(nullptr, pk.data(), pk.size(), &out, &out_len), 0u);
  EXPECT_EQ(fsw_link_deframer_push(&d, nullptr, pk.size(), &out, &out_len), 0u);
  EXPECT_EQ(fsw_link_deframer_push(&d, pk.data(), pk.size(), nullptr, &out_len), 0u);
  EXPECT_EQ(fsw_link_deframer_push(&d, pk.data(), pk.size(), &out, nullptr), 0u);
  // a marker followed by a length field below the smallest packet, then a
  // good packet: the short candidate is rejected, the good one delivered
  Bytes stream = {0x1A, 0xCF, 0xFC, 0x1D, 0x19, 0x01, 0xC0, 0x00, 0x00, 0x02};
  Bytes framed(pk.size() + 4);
  ASSERT_EQ(fsw_link_frame(pk.data(), pk.size(), framed.data(), framed.size(), &len), FSW_OK);
  stream.insert(stream.end(), framed.begin(), framed.end());
  size_t pos = 0;
  int got = 0;
  while (pos < stream.size()) {
    pos += fsw_link_deframer_push(&d, stream.data() + pos, stream.size() - pos, &out, &out_len);
    if (out != nullptr) ++got;
  }
  EXPECT_EQ(got, 1);
  EXPECT_GE(d.rejected, 1u);
}

// Issue 21 (branch coverage of fsw_link.c): att_valid travels as a flag
// (docs/icd.md, sensor offset 2: 0 or 1): 0 stays 0, any non-zero value is
// sent as 1, and the decoder gives back what was sent.
// Verifies: REQ-LINK-002
TEST(FswLink, Issue21AttValidTravelsAsAFlag)
{
  const size_t att = FSW_LINK_HEADER_SIZE + 2;  // ICD: payload offset 2
  for (const auto& c : std::vector<std::pair<uint8_t, uint8_t>>{{0, 0}, {1, 1}, {7, 1}, {255, 1}}) {
    FswAcsSensorMsg m = sensor_msg(2, 3);
    m.att_valid = c.first;
    const Bytes b = encode_sensor(m, 2, 3);
    ASSERT_EQ(b.size(), FSW_LINK_HEADER_SIZE + 158u + 9u * 2u + 9u * 3u + 2u);
    EXPECT_EQ(b[att], c.second) << int(c.first);
    FswLinkPacket p;
    ASSERT_EQ(fsw_link_parse(b.data(), b.size(), &p, nullptr), FSW_OK);
    FswAcsSensorMsg back;
    std::memset(&back, 0x5A, sizeof back);
    uint8_t nrw = 0, ncss = 0;
    FswLinkError e = FSW_LINK_E_SPACE;
    ASSERT_EQ(fsw_link_decode_sensor(&p, &back, &nrw, &ncss, &e), FSW_OK);
    EXPECT_EQ(e, FSW_LINK_OK);
    EXPECT_EQ(back.att_valid, c.second) << int(c.first);
  }
}

// Issue 21 (branch coverage of fsw_link.c): every rw_avail byte is a flag
// (docs/icd.md, sensor offset 76 + 8 n_rw, n_rw bytes): a value other than
// 0 or 1 in any of them is refused with FSW_LINK_E_COUNT (the CRC made
// right, so the flag is the only fault) and the message is not written; a
// flag changed from 0 to 1 is accepted and decoded.
// Verifies: REQ-LINK-002
TEST(FswLink, Issue21WheelAvailabilityFlagsAreZeroOrOne)
{
  const uint8_t nrw = 4, ncss = 6;
  const Bytes good = encode_sensor(sensor_msg(nrw, ncss), nrw, ncss);
  const size_t avail = FSW_LINK_HEADER_SIZE + 76u + 8u * nrw;  // ICD offset of rw_avail[0]
  // sensor_msg sets rw_avail[i] = i % 2
  EXPECT_EQ(Bytes(good.begin() + avail, good.begin() + avail + nrw), (Bytes{0, 1, 0, 1}));
  auto decode = [&](const Bytes& b, FswAcsSensorMsg* m) {
    FswLinkPacket p;
    FswLinkError e = FSW_LINK_OK;
    EXPECT_EQ(fsw_link_parse(b.data(), b.size(), &p, &e), FSW_OK);
    uint8_t n1 = 99, n2 = 99;
    const FswStatus st = fsw_link_decode_sensor(&p, m, &n1, &n2, &e);
    EXPECT_EQ(st, e == FSW_LINK_OK ? FSW_OK : FSW_E_BAD_INPUT);
    if (st != FSW_OK) {
      EXPECT_EQ(n1, 99);  // counts are not written on failure either
      EXPECT_EQ(n2, 99);
    }
    return e;
  };
  for (size_t i = 0; i < nrw; ++i) {
    for (const uint8_t v : {uint8_t{2}, uint8_t{0x80}, uint8_t{0xFF}}) {
      Bytes b = good;
      b[avail + i] = v;
      fix_crc(b);
      FswAcsSensorMsg m;
      std::memset(&m, 0x77, sizeof m);
      unsigned char before[sizeof m];
      std::memcpy(before, &m, sizeof m);
      EXPECT_EQ(decode(b, &m), FSW_LINK_E_COUNT) << "wheel " << i << " value " << int(v);
      EXPECT_EQ(std::memcmp(before, &m, sizeof m), 0) << "wheel " << i;
    }
  }
  Bytes b = good;
  b[avail] = 1;  // wheel 0 unavailable
  fix_crc(b);
  FswAcsSensorMsg m;
  ASSERT_EQ(decode(b, &m), FSW_LINK_OK);
  EXPECT_EQ(m.rw_avail[0], 1u);
  EXPECT_EQ(m.rw_avail[1], 1u);
  EXPECT_EQ(m.rw_avail[2], 0u);
}

// Issue 21 (branch coverage of fsw_link.c): init of a NULL deframer returns
// without touching memory (the header's "void ... init" with the module's
// NULL checks; a dereference would crash this test).
// Verifies: REQ-GEN-007
TEST(FswLink, Issue21DeframerInitOfNullDoesNothing)
{
  fsw_link_deframer_init(nullptr);
  FswLinkDeframer d;
  std::memset(&d, 0xA5, sizeof d);
  fsw_link_deframer_init(&d);
  EXPECT_EQ(d.have, 0u);
  EXPECT_EQ(d.packets, 0u);
  EXPECT_EQ(d.sync_slips, 0u);
  EXPECT_EQ(d.rejected, 0u);
}

namespace {

// A packet of `total` bytes (header, zero payload, right CRC) that parses:
// the parser judges header and CRC, not the APID's payload (docs/icd.md,
// "Receiving rules").  Primary header 19 01 C0 00: version 0, TC, secondary
// header, APID 0x101, unsegmented, count 0; data length total - 6 - 1.
Bytes packet_of_size(size_t total)
{
  Bytes b(total, 0);
  b[0] = 0x19;
  b[1] = 0x01;
  b[2] = 0xC0;
  b[3] = 0x00;
  b[4] = static_cast<uint8_t>((total - 7) >> 8);
  b[5] = static_cast<uint8_t>((total - 7) & 0xFF);
  fix_crc(b);
  return b;
}

// The attached sync marker 1A CF FC 1D and the packet (docs/icd.md).
Bytes framed(const Bytes& pkt)
{
  Bytes f(FSW_LINK_ASM_SIZE + pkt.size());
  f[0] = 0x1A;
  f[1] = 0xCF;
  f[2] = 0xFC;
  f[3] = 0x1D;
  for (size_t i = 0; i < pkt.size(); ++i) f[FSW_LINK_ASM_SIZE + i] = pkt[i];
  return f;
}

}  // namespace

// Issue 21 (branch coverage of fsw_link.c): the deframer takes the length
// from the primary header and refuses a length beyond the largest packet
// of this build's capacities (FSW_LINK_MAX_PACKET; docs/icd.md, "Byte
// streams") as soon as the header is in, without waiting for (or buffering)
// the bytes it announces; a candidate of exactly that size is collected and
// delivered.  After the refusal the hunt goes on and the next packet is
// delivered.
// Verifies: REQ-LINK-006
TEST(FswLink, Issue21DeframerRefusesALengthBeyondTheLargestPacket)
{
  // the longest packet the buffer holds: delivered whole, byte for byte
  {
    const Bytes longest = packet_of_size(FSW_LINK_MAX_PACKET);
    FswLinkPacket p;
    ASSERT_EQ(fsw_link_parse(longest.data(), longest.size(), &p, nullptr), FSW_OK);  // a valid packet
    const Bytes f = framed(longest);
    FswLinkDeframer d;
    fsw_link_deframer_init(&d);
    const uint8_t* pkt = nullptr;
    size_t pl = 0;
    EXPECT_EQ(fsw_link_deframer_push(&d, f.data(), f.size(), &pkt, &pl), f.size());
    ASSERT_NE(pkt, nullptr);
    ASSERT_EQ(pl, longest.size());
    EXPECT_EQ(Bytes(pkt, pkt + pl), longest);
    EXPECT_EQ(d.packets, 1u);
    EXPECT_EQ(d.rejected, 0u);
    EXPECT_EQ(d.sync_slips, 0u);
  }
  // one byte longer (also a valid packet, CRC right): refused at its header
  const Bytes too_long = packet_of_size(FSW_LINK_MAX_PACKET + 1u);
  FswAcsSensorMsg m = sensor_msg(2, 2);
  const Bytes next = encode_sensor(m, 2, 2, 321);
  Bytes stream = framed(too_long);
  const Bytes f2 = framed(next);
  stream.insert(stream.end(), f2.begin(), f2.end());
  FswLinkDeframer d;
  fsw_link_deframer_init(&d);
  const uint8_t* pkt = nullptr;
  size_t pl = 0;
  const size_t head = FSW_LINK_ASM_SIZE + FSW_LINK_PRIMARY_SIZE;  // marker and primary header
  EXPECT_EQ(fsw_link_deframer_push(&d, stream.data(), head, &pkt, &pl), head);
  EXPECT_EQ(pkt, nullptr);
  EXPECT_EQ(d.rejected, 1u);  // refused on the header alone
  EXPECT_LT(d.have, head);    // and nothing of its announced length buffered
  std::vector<uint16_t> got;
  size_t at = head;
  while (at < stream.size()) {
    at += fsw_link_deframer_push(&d, stream.data() + at, stream.size() - at, &pkt, &pl);
    if (pkt != nullptr) {
      FswLinkPacket p;
      ASSERT_EQ(fsw_link_parse(pkt, pl, &p, nullptr), FSW_OK);
      got.push_back(p.seq);
    }
  }
  EXPECT_EQ(got, (std::vector<uint16_t>{321}));
  EXPECT_EQ(d.packets, 1u);
  EXPECT_EQ(d.rejected, 1u);
  // every byte of the refused frame but the marker byte dropped by the
  // rejection itself is skipped by the hunt: 4 + (MAX + 1) - 1 bytes
  // (no four of them read 1A CF FC 1D: the payload is zero and the CRC is two bytes)
  EXPECT_EQ(d.sync_slips, FSW_LINK_MAX_PACKET + 4u);
}

// Issue 21: link_safe is a flag on the wire (docs/icd.md, link status
// payload offset 38, u8): 0 goes out as 0 and any non-zero value as 1; the
// decoder gives the same flag back.  Byte positions from the ICD table, not
// from the encoder.
// Verifies: REQ-LINK-002
TEST(FswLink, Issue21LinkSafeTravelsAsAFlag)
{
  const size_t safe_at = FSW_LINK_HEADER_SIZE + 38u;  // ICD: payload offset 38
  for (const auto& c : std::vector<std::pair<uint8_t, uint8_t>>{{0, 0}, {1, 1}, {9, 1}, {255, 1}}) {
    FswLinkStatusMsg m;
    std::memset(&m, 0, sizeof m);
    m.rx_packets = 12;
    m.cycles = 34;
    m.last_seq = 56;
    m.link_safe = c.first;
    Bytes b(FSW_LINK_MAX_PACKET);
    size_t len = 0;
    ASSERT_EQ(fsw_link_encode_status(&m, 789u, 3u, b.data(), b.size(), &len, nullptr), FSW_OK);
    ASSERT_EQ(len, FSW_LINK_HEADER_SIZE + 40u + FSW_LINK_CRC_SIZE);  // ICD: 40-byte payload
    EXPECT_EQ(b[safe_at], c.second) << int(c.first);
    EXPECT_EQ(b[safe_at + 1u], 2u) << "ICD version, offset 39";
    FswLinkPacket p;
    ASSERT_EQ(fsw_link_parse(b.data(), len, &p, nullptr), FSW_OK);
    FswLinkStatusMsg back;
    std::memset(&back, 0x5A, sizeof back);
    FswLinkError e = FSW_LINK_E_SPACE;
    ASSERT_EQ(fsw_link_decode_status(&p, &back, &e), FSW_OK);
    EXPECT_EQ(e, FSW_LINK_OK);
    EXPECT_EQ(back.link_safe, c.second) << int(c.first);
    EXPECT_EQ(back.last_seq, 56u);
  }
}

// Issue 14: the thruster flags travel as a big-endian u64 after css_avail
// (docs/icd.md, offset 76 + 9 n_rw + 9 n_css): bit i = thruster i
// unavailable.  sensor_msg flags thrusters 0 and FSW_MAX_THR - 1.  A bit at
// or above FSW_MAX_THR is refused (FSW_LINK_E_COUNT); an encoder refuses a
// flag other than 0/1 (it could not travel as a bit).
// Verifies: REQ-LINK-002
TEST(FswLink, ThrusterAvailabilityTravelsAsABitMask)
{
  const uint8_t nrw = 2, ncss = 3;
  FswAcsSensorMsg m = sensor_msg(nrw, ncss);
  const Bytes good = encode_sensor(m, nrw, ncss);
  const size_t at = FSW_LINK_HEADER_SIZE + 76u + 9u * nrw + 9u * ncss;
  uint64_t want = 1u | (uint64_t(1) << (FSW_MAX_THR - 1));
  Bytes be(8);
  for (int k = 0; k < 8; ++k) be[size_t(k)] = static_cast<uint8_t>(want >> (8 * (7 - k)));
  EXPECT_EQ(Bytes(good.begin() + static_cast<long>(at), good.begin() + static_cast<long>(at) + 8), be);
  FswLinkPacket p;
  ASSERT_EQ(fsw_link_parse(good.data(), good.size(), &p, nullptr), FSW_OK);
  FswAcsSensorMsg back;
  uint8_t n1 = 0, n2 = 0;
  ASSERT_EQ(fsw_link_decode_sensor(&p, &back, &n1, &n2, nullptr), FSW_OK);
  EXPECT_EQ(std::memcmp(back.thr_avail, m.thr_avail, sizeof m.thr_avail), 0);
  if (FSW_MAX_THR < 64) {
    Bytes b = good;
    b[at] |= 0x80u;  // bit 63
    fix_crc(b);
    ASSERT_EQ(fsw_link_parse(b.data(), b.size(), &p, nullptr), FSW_OK);
    FswLinkError e = FSW_LINK_OK;
    EXPECT_EQ(fsw_link_decode_sensor(&p, &back, &n1, &n2, &e), FSW_E_BAD_INPUT);
    EXPECT_EQ(e, FSW_LINK_E_COUNT);
  }
  m.thr_avail[3] = 2;
  Bytes buf(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_encode_sensor(&m, nrw, ncss, 1, buf.data(), buf.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
}

namespace {

// The big-endian binary64 at b[at], read without the library.
double f64_at(const Bytes& b, size_t at)
{
  uint64_t bits = 0;
  for (size_t k = 0; k < 8; ++k) bits = (bits << 8) | b[at + k];
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

uint64_t u_at(const Bytes& b, size_t at, size_t n)
{
  uint64_t v = 0;
  for (size_t k = 0; k < n; ++k) v = (v << 8) | b[at + k];
  return v;
}

Bytes encode_actuator(const FswAcsActuatorMsg& m, uint8_t nrw, uint8_t nthr, uint8_t nmtq)
{
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  EXPECT_EQ(fsw_link_encode_actuator(&m, nrw, nthr, nmtq, 5, 6, b.data(), b.size(), &len, nullptr), FSW_OK);
  b.resize(len);
  return b;
}

Bytes encode_health(const FswAcsHealthMsg& m)
{
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  EXPECT_EQ(fsw_link_encode_health(&m, 5, 6, b.data(), b.size(), &len, nullptr), FSW_OK);
  b.resize(len);
  return b;
}

}  // namespace

// ICD version 2: every payload size is the sum of its table's rows
// (docs/icd.md), added up here row by row, for several counts: the
// macros, the encoders and the largest packet agree with the tables.
// Verifies: REQ-LINK-002
TEST(FswLink, Icd2PayloadSizesAreTheSumsOfTheTables)
{
  EXPECT_EQ(FSW_LINK_ICD_VERSION, 2u);
  for (const auto& n : std::vector<std::pair<size_t, size_t>>{{0, 0}, {3, 5}, {FSW_MAX_RW, FSW_MAX_CSS}}) {
    // n_rw, n_css, att_valid, reserved; sigma_BN, omega_BN_B, r_CoM_B; Omega; rw_avail; css; css_avail;
    // thr_avail; B_B, r_N, v_N; mag_valid, orbit_valid
    const size_t p = 4 * 1 + 3 * 3 * 8 + 8 * n.first + n.first + 8 * n.second + n.second + 8 + 3 * 3 * 8 + 2;
    EXPECT_EQ(FSW_LINK_SENSOR_PAYLOAD(n.first, n.second), p);
    EXPECT_EQ(encode_sensor(sensor_msg(uint8_t(n.first), uint8_t(n.second)), uint8_t(n.first), uint8_t(n.second)).size(),
              14u + p + 2u);
  }
  // mode, actuation, set_ref, set_gains; sigma_R0N; K; P; set_policy, policy
  EXPECT_EQ(FSW_LINK_CMD_PAYLOAD, 4u + 24u + 8u + 8u + 2u);
  size_t largest_actuator = 0;
  for (const auto& c : std::vector<std::array<size_t, 3>>{{0, 0, 0}, {2, 3, 4}, {FSW_MAX_RW, FSW_MAX_THR, FSW_MAX_MTQ}}) {
    // n_rw, n_thr, n_mtq, three flags, reserved u16; Lr_B; u_s, V; F, t_on; m_cmd
    const size_t p = 6 + 2 + 24 + 16 * c[0] + 16 * c[1] + 8 * c[2];
    EXPECT_EQ(FSW_LINK_ACTUATOR_PAYLOAD(c[0], c[1], c[2]), p);
    const auto m = actuator_msg(uint8_t(c[0]), uint8_t(c[1]), uint8_t(c[2]));
    EXPECT_EQ(encode_actuator(m, uint8_t(c[0]), uint8_t(c[1]), uint8_t(c[2])).size(), 14u + p + 2u);
    largest_actuator = p;
  }
  // status..number of stages (8 bytes), cycles, mode_changes; 16 stages; sigma_BR, omega_BR_B, two angles,
  // sun_hat_B; 7 counters, last; rw_failed, rw_latched; policy, detumbled, dump_phase, reserved, dumps;
  // h_w_B, rate_est, tau_mtq_B, prop_used
  const size_t health = 8 + 4 + 4 + 16 * 2 + (3 + 3 + 2 + 3) * 8 + 7 * 4 + 2 + 2 * 8 + 4 + 4 + (3 + 1 + 3 + 1) * 8;
  EXPECT_EQ(health, 254u);
  EXPECT_EQ(FSW_ACS_NUM_STAGES, 16);
  EXPECT_EQ(FSW_LINK_HEALTH_PAYLOAD, health);
  EXPECT_EQ(encode_health(health_msg()).size(), 14u + health + 2u);
  const size_t largest_sensor = FSW_LINK_SENSOR_PAYLOAD(FSW_MAX_RW, FSW_MAX_CSS);
  EXPECT_EQ(FSW_LINK_MAX_PACKET, 16u + std::max({largest_sensor, largest_actuator, health}));
  if (FSW_MAX_RW == 36 && FSW_MAX_CSS == 32 && FSW_MAX_THR == 36 && FSW_MAX_MTQ == 8) {  // the defaults
    EXPECT_EQ(largest_sensor, 770u);
    EXPECT_EQ(largest_actuator, 1248u);
    EXPECT_EQ(FSW_LINK_MAX_PACKET, 1264u);
  }
}

// The fields of ICD version 2 at their table offsets, read back without the
// library; their flags travel as 0/1 and a flag other than 0/1 on the wire
// is refused (FSW_LINK_E_COUNT) without writing the message.
// Verifies: REQ-LINK-002
TEST(FswLink, Icd2NewFieldsSitAtTheirTableOffsets)
{
  const uint8_t nrw = 2, ncss = 3;
  FswAcsSensorMsg s = sensor_msg(nrw, ncss);
  s.mag_valid = 9;  // non-zero: sent as 1
  s.orbit_valid = 0;
  Bytes b = encode_sensor(s, nrw, ncss);
  const size_t t = 14 + 76 + 9 * nrw + 9 * ncss;  // thr_avail
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(f64_at(b, t + 8 + 8 * i), double(s.B_B[i])) << i;
    EXPECT_EQ(f64_at(b, t + 32 + 8 * i), double(s.r_N[i])) << i;
    EXPECT_EQ(f64_at(b, t + 56 + 8 * i), double(s.v_N[i])) << i;
  }
  EXPECT_EQ(b[t + 80], 1u);  // mag_valid
  EXPECT_EQ(b[t + 81], 0u);  // orbit_valid
  EXPECT_EQ(t + 82 + 2, b.size());
  for (const size_t at : {t + 80, t + 81}) {
    for (const uint8_t v : {uint8_t{2}, uint8_t{0xFF}}) {
      Bytes bad = b;
      bad[at] = v;
      fix_crc(bad);
      FswLinkPacket p;
      ASSERT_EQ(fsw_link_parse(bad.data(), bad.size(), &p, nullptr), FSW_OK);
      FswAcsSensorMsg m;
      std::memset(&m, 0x77, sizeof m);
      uint8_t n1 = 99, n2 = 99;
      FswLinkError e = FSW_LINK_OK;
      EXPECT_EQ(fsw_link_decode_sensor(&p, &m, &n1, &n2, &e), FSW_E_BAD_INPUT) << at;
      EXPECT_EQ(e, FSW_LINK_E_COUNT) << at;
      EXPECT_EQ(m.mag_valid, 0x77u);
      EXPECT_EQ(n1, 99u);
    }
  }

  const uint8_t nthr = 3, nmtq = 4;
  FswAcsActuatorMsg a = actuator_msg(nrw, nthr, nmtq);
  b = encode_actuator(a, nrw, nthr, nmtq);
  EXPECT_EQ(Bytes(b.begin() + 14, b.begin() + 22), (Bytes{nrw, nthr, nmtq, 1, 0, 1, 0, 0}));
  EXPECT_EQ(f64_at(b, 14 + 8), double(a.Lr_B[0]));
  EXPECT_EQ(f64_at(b, 14 + 32 + 8 * nrw), double(a.V[0]));
  EXPECT_EQ(f64_at(b, 14 + 32 + 16 * nrw + 8 * nthr + 8), double(a.t_on[1]));
  for (size_t i = 0; i < nmtq; ++i)
    EXPECT_EQ(f64_at(b, 14 + 32 + 16 * nrw + 16 * nthr + 8 * i), -0.75 + 0.25 * double(i)) << i;
  EXPECT_EQ(14 + 32 + 16 * nrw + 16 * nthr + 8 * nmtq + 2, b.size());

  const FswAcsHealthMsg h = health_msg();
  b = encode_health(h);
  const size_t p0 = 14;
  EXPECT_EQ(b[p0 + 7], 16u);                                      // number of stages
  EXPECT_EQ(u_at(b, p0 + 16 + 2 * 15, 2), uint64_t(uint16_t(h.stage_status[15])));  // rw_bias, the last
  EXPECT_EQ(u_at(b, p0 + 174, 8), 0x4u);                          // rw_latched
  EXPECT_EQ(b[p0 + 182], 2u);                                     // policy: magnetorquers
  EXPECT_EQ(b[p0 + 183], 1u);                                     // detumbled
  EXPECT_EQ(b[p0 + 184], 2u);                                     // dump_phase
  EXPECT_EQ(b[p0 + 185], 0u);                                     // reserved
  EXPECT_EQ(u_at(b, p0 + 186, 4), 3000000000u);                  // dumps
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(f64_at(b, p0 + 190 + 8 * i), double(h.h_w_B[i])) << i;
    EXPECT_EQ(f64_at(b, p0 + 222 + 8 * i), double(h.tau_mtq_B[i])) << i;
  }
  EXPECT_EQ(f64_at(b, p0 + 214), double(h.rate_est));                                          // rate_est
  EXPECT_EQ(f64_at(b, p0 + 246), 0.0625);                                                      // prop_used
  FswAcsHealthMsg hd = h;
  hd.detumbled = 5;  // non-zero: sent as 1
  EXPECT_EQ(encode_health(hd)[p0 + 183], 1u);
}

// A peer of ICD version 1 (packets before the version-2 fields; layouts of
// that version written here by hand) is refused: its sensor, command,
// actuator and health packets fail on their length (FSW_LINK_E_LENGTH, for
// any counts: 84 + 9k never equals 158 + 9j, 28 + 16k never equals
// 32 + 16j + 8m), its link status on the version byte (FSW_LINK_E_HEADER).
// Verifies: REQ-LINK-007
TEST(FswLink, Icd1PeerIsRejected)
{
  auto packet = [](uint16_t apid, uint8_t type, const Bytes& payload) {
    Bytes b(14 + payload.size() + 2, 0);
    b[0] = static_cast<uint8_t>((type << 4) | 0x08 | (apid >> 8));  // version 0, type, sec. header, APID
    b[1] = static_cast<uint8_t>(apid & 0xFF);
    b[2] = 0xC0;  // unsegmented, count 1
    b[3] = 0x01;
    b[4] = static_cast<uint8_t>((8 + payload.size() + 1) >> 8);  // data length 8 + P + 2 - 1
    b[5] = static_cast<uint8_t>((8 + payload.size() + 1) & 0xFF);
    b[13] = 9;  // t_ns
    for (size_t i = 0; i < payload.size(); ++i) b[14 + i] = payload[i];
    fix_crc(b);
    return b;
  };
  auto why = [](const Bytes& b, int kind) {
    FswLinkPacket p;
    FswLinkError e = FSW_LINK_OK;
    EXPECT_EQ(fsw_link_parse(b.data(), b.size(), &p, &e), FSW_OK);
    FswAcsSensorMsg s;
    FswAcsCmdMsg c;
    FswAcsActuatorMsg a;
    FswAcsHealthMsg h;
    FswLinkStatusMsg st;
    uint8_t n1, n2, n3;
    FswStatus r = FSW_OK;
    if (kind == 0) r = fsw_link_decode_sensor(&p, &s, &n1, &n2, &e);
    if (kind == 1) r = fsw_link_decode_cmd(&p, &c, &e);
    if (kind == 2) r = fsw_link_decode_actuator(&p, &a, &n1, &n2, &n3, &e);
    if (kind == 3) r = fsw_link_decode_health(&p, &h, &e);
    if (kind == 4) r = fsw_link_decode_status(&p, &st, &e);
    EXPECT_EQ(r, FSW_E_BAD_INPUT);
    return e;
  };
  for (uint8_t nrw = 0; nrw <= 4; ++nrw) {
    for (uint8_t n2 = 0; n2 <= 4; ++n2) {
      // v1 sensor: n_rw, n_css, att_valid, reserved, 9 f64, Omega, rw_avail, css, css_avail, u64 thr_avail
      Bytes s = {nrw, n2, 1, 0};
      s.resize(84 + 9 * nrw + 9 * n2, 0);
      EXPECT_EQ(why(packet(0x101, 1, s), 0), FSW_LINK_E_LENGTH) << int(nrw) << "/" << int(n2);
      // v1 actuator: n_rw, n_thr, wheels_active, thrusters_active, Lr_B (-0.01: first byte 0xBF), u_s, V, F, t_on
      Bytes a = {nrw, n2, 1, 1, 0xBF, 0x84, 0x7A, 0xE1, 0x47, 0xAE, 0x14, 0x7B};
      a.resize(28 + 16 * nrw + 16 * n2, 0);
      EXPECT_EQ(why(packet(0x181, 0, a), 2), FSW_LINK_E_LENGTH) << int(nrw) << "/" << int(n2);
    }
  }
  EXPECT_EQ(why(packet(0x102, 1, Bytes(44, 0)), 1), FSW_LINK_E_LENGTH);  // v1 command: 44 bytes
  Bytes h(172, 0);                                                       // v1 health: 11 stages
  h[7] = 11;
  EXPECT_EQ(why(packet(0x182, 0, h), 3), FSW_LINK_E_LENGTH);
  Bytes st(40, 0);  // v1 link status: byte 39 reserved (0)
  EXPECT_EQ(why(packet(0x183, 0, st), 4), FSW_LINK_E_HEADER);
  st[39] = 2;  // this version's: accepted
  const Bytes ok = packet(0x183, 0, st);
  FswLinkPacket p;
  ASSERT_EQ(fsw_link_parse(ok.data(), ok.size(), &p, nullptr), FSW_OK);
  FswLinkStatusMsg m;
  ASSERT_EQ(fsw_link_decode_status(&p, &m, nullptr), FSW_OK);
  EXPECT_EQ(m.icd_version, 2u);
  st[39] = 3;  // a later version
  EXPECT_EQ(why(packet(0x183, 0, st), 4), FSW_LINK_E_HEADER);
}

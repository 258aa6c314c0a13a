// The configuration image (fsw_link_config_*) and the FSW end of the link
// (fsw_link_node).  Image: header bytes as docs/icd.md gives them, a body
// length computed here from the struct definitions by hand (not from the
// table), every byte of every field carried (a struct filled with a byte
// pattern comes back with exactly the padding bytes differing), round trips
// of the fixture's wheel and thruster configs that fsw_acs_check accepts,
// every single-bit error, truncation and extension rejected, nothing written
// on failure.  Node: its replies equal fsw_acs_cycle run directly on the same
// inputs; stale, duplicate, damaged and foreign packets counted and answered
// by the link status alone; sequence gaps counted as missed cycles; commands applied from the
// next cycle; the watchdog entering link-safe after max_missed periods with
// the safe output, and the next sensor packet recovering; the messages the
// node hands its application equal the encoded ones bit for bit (the
// decoders' contract of the Eva envelope analysis of the node).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "acs_fixture.hpp"
#include "fsw/fsw_link.h"
#include "fsw/fsw_link_node.h"
#include "kestrel_test_support.h"

namespace {

using Bytes = std::vector<uint8_t>;
using acsfix::R;

// Counted by hand from the struct definitions in fsw_acs.h and the module
// headers (C = FSW_MAX_CSS, W = FSW_MAX_RW, T = FSW_MAX_THR, M = FSW_MAX_MTQ):
//   int fields: initial_mode, initial_actuation, css.num_css,
//     mrp_fb.{control_law_type, num_rw}, use_lpf, has_wheels,
//     rw_map.{num_rw, num_axes, mode}, use_null, rw_null.{num_rw,
//     scale_to_fit}, rw_sat.{num_rw, mode}, use_volt, rw_volt.{num_rw,
//     gate_rate}, has_thrusters, thr_map.{num_thr, thr_force_sign,
//     use_2nd_loop, mode}, pulser, 2 x pulser common {num_thr,
//     base_thrust_state}                                              = 28
//   version 2: has_mtq, mtq_map.num_mtq, bdot.{variant, normalize,
//     max_missed}, detumble_exit_mode, has_orbit, orbit.variant,
//     initial_policy, use_thr_mom, thr_mom.{num_rw, num_thr},
//     use_mtq_desat, mtq_desat.num_rw, use_bias, rw_bias.num_rw       + 16
//   reals: css 4C+1, sunsafe 9, inertial 3, track 3, mrp_fb 16+4W, lpf 2,
//     rw_map 10+3W, rw_null 1+4W, Omega_des W, rw_sat W, rw_volt 3+3W,
//     thr_map 11+7T, pulse_rem T+2, pulse_schmitt T+4
//                                              = 65 + 4C + 16W + 9T
//   version 2: mtq_map 4M+1, bdot 8, orbit 4, thr_mom 8+4W+T,
//     mtq_desat 6+4W, rw_bias 2+4W             + 29 + 4M + 12W + T
constexpr size_t kInts = 28 + 16;
constexpr size_t kReals = 65 + 4 * FSW_MAX_CSS + 16 * FSW_MAX_RW + 9 * FSW_MAX_THR + 29 + 4 * FSW_MAX_MTQ +
                          12 * FSW_MAX_RW + FSW_MAX_THR;

Bytes image_of(const FswAcsConfig& c)
{
  Bytes b(fsw_link_config_size());
  size_t len = 0;
  FswLinkError e = FSW_LINK_E_SHORT;
  EXPECT_EQ(fsw_link_config_encode(&c, b.data(), b.size(), &len, &e), FSW_OK);
  EXPECT_EQ(e, FSW_LINK_OK);
  EXPECT_EQ(len, b.size());
  return b;
}

void put_crc(Bytes& b)
{
  const uint16_t crc = fsw_link_crc16(b.data(), b.size() - 2, 0xFFFF);
  b[b.size() - 2] = static_cast<uint8_t>(crc >> 8);
  b[b.size() - 1] = static_cast<uint8_t>(crc & 0xFF);
}

}  // namespace

// Verifies: REQ-LINK-002, REQ-LINK-008
TEST(FswLinkConfig, HeaderAndSizeAreTheIcds)
{
  auto c_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& c = *c_p;
  acsfix::wheel_config(c);
  const Bytes b = image_of(c);
  ASSERT_EQ(b.size(), 20u + 4u * kInts + 8u * kReals + 2u);
  EXPECT_EQ(b[0], 'K');
  EXPECT_EQ(b[1], 'C');
  EXPECT_EQ(b[2], 'F');
  EXPECT_EQ(b[3], 'G');
  EXPECT_EQ(b[4], 0u);
  EXPECT_EQ(b[5], FSW_LINK_CONFIG_VERSION);
  EXPECT_EQ(b[10], FSW_MAX_RW);
  EXPECT_EQ(b[11], FSW_MAX_CSS);
  EXPECT_EQ(b[12], FSW_MAX_THR);
  EXPECT_EQ(b[13], FSW_MAX_MTQ);
  EXPECT_EQ(b[14], 0u);
  EXPECT_EQ(b[15], 0u);
  const uint32_t body = (uint32_t(b[16]) << 24) | (uint32_t(b[17]) << 16) | (uint32_t(b[18]) << 8) | b[19];
  EXPECT_EQ(body, 4u * kInts + 8u * kReals);
  // the first body fields: initial_mode, initial_actuation as big-endian i32
  EXPECT_EQ(b[20 + 3], uint8_t(c.initial_mode));
  EXPECT_EQ(b[24 + 3], uint8_t(c.initial_actuation));
  // css.num_css, then n_hat_B[0][0] as big-endian binary64 (1.0 = 3FF0...)
  EXPECT_EQ(b[28 + 3], uint8_t(c.css.num_css));
  EXPECT_EQ(b[32], 0x3F);
  EXPECT_EQ(b[33], 0xF0);
}

// Verifies: REQ-LINK-008
TEST(FswLinkConfig, EveryFieldByteIsCarried)
{
  // Every byte 0x41: ints 0x41414141, reals finite (2.3e6 in double, 12.1 in
  // float).  Decoded, exactly the bytes of no field (padding) differ, and
  // there are sizeof - kInts ints - kReals reals of them: a field missing from
  // the table would add its bytes to the difference.
  auto a_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& a = *a_p;
  auto d_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& d = *d_p;
  std::memset(&a, 0x41, sizeof a);
  const Bytes b = image_of(a);
  ASSERT_EQ(fsw_link_config_decode(b.data(), b.size(), &d, nullptr), FSW_OK);
  const auto* pa = reinterpret_cast<const uint8_t*>(&a);
  const auto* pd = reinterpret_cast<const uint8_t*>(&d);
  size_t differing = 0;
  for (size_t i = 0; i < sizeof a; ++i) {
    if (pa[i] != pd[i]) {
      ++differing;
      EXPECT_EQ(pd[i], 0u) << "byte " << i;  // padding: zeroed by the decoder
    }
  }
  EXPECT_EQ(differing, sizeof a - kInts * sizeof(int) - kReals * sizeof(fsw_real));
}

// Verifies: REQ-LINK-008
TEST(FswLinkConfig, FixtureConfigsRoundTripAndPassTheCheck)
{
  for (int which = 0; which < 3; ++which) {
    auto c_p = std::make_unique<FswAcsConfig>();
    FswAcsConfig& c = *c_p;
    auto d_p = std::make_unique<FswAcsConfig>();
    FswAcsConfig& d = *d_p;
    if (which == 0) acsfix::wheel_config(c);
    if (which == 1) acsfix::thruster_config(c);
    if (which == 2) acsfix::thruster_config(c, FSW_ACS_PULSE_SCHMITT);
    const Bytes b = image_of(c);
    std::memset(&d, 0x77, sizeof d);
    FswLinkError e = FSW_LINK_E_SHORT;
    ASSERT_EQ(fsw_link_config_decode(b.data(), b.size(), &d, &e), FSW_OK);
    EXPECT_EQ(e, FSW_LINK_OK);
    EXPECT_EQ(image_of(d), b);  // same bytes again
    const char* bad = "x";
    EXPECT_EQ(fsw_acs_check(&d, &bad), FSW_OK);
    EXPECT_EQ(bad, nullptr);
    EXPECT_EQ(d.mrp_fb.K, c.mrp_fb.K);
    EXPECT_EQ(d.mrp_fb.I_B[2][2], c.mrp_fb.I_B[2][2]);
    EXPECT_EQ(d.thr_map.num_thr, c.thr_map.num_thr);
    EXPECT_EQ(d.thr_map.thr_force_sign, c.thr_map.thr_force_sign);
    EXPECT_EQ(d.pulse_schmitt.level_off, c.pulse_schmitt.level_off);
    EXPECT_EQ(d.rw_map.gs_hat_B[3][2], c.rw_map.gs_hat_B[3][2]);
  }
  // negative ints survive (two's complement i32)
  auto c_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& c = *c_p;
  auto d_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& d = *d_p;
  acsfix::thruster_config(c);
  c.thr_map.thr_force_sign = -1;
  const Bytes b = image_of(c);
  ASSERT_EQ(fsw_link_config_decode(b.data(), b.size(), &d, nullptr), FSW_OK);
  EXPECT_EQ(d.thr_map.thr_force_sign, -1);
}

// Verifies: REQ-LINK-008
TEST(FswLinkConfig, DamagedImagesAreRejectedAndWriteNothing)
{
  auto c_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& c = *c_p;
  auto d_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& d = *d_p;
  auto untouched_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& untouched = *untouched_p;
  acsfix::wheel_config(c);
  const Bytes good = image_of(c);
  std::memset(&untouched, 0x5A, sizeof untouched);
  auto rejects = [&](const Bytes& b, FswLinkError want) {
    std::memcpy(&d, &untouched, sizeof d);
    FswLinkError e = FSW_LINK_OK;
    EXPECT_EQ(fsw_link_config_decode(b.data(), b.size(), &d, &e), FSW_E_BAD_INPUT);
    EXPECT_EQ(e, want);
    EXPECT_EQ(std::memcmp(&d, &untouched, sizeof d), 0);
  };
  // single-bit errors: every bit of the header, of the first 64 body bytes
  // and of the CRC, and every 37th bit elsewhere (a CRC-16 detects every
  // single-bit error at any position; the sample keeps the test short under
  // a target's emulator).  Header bits change the header (or the length),
  // body and CRC bits fail the CRC.
  Bytes b = good;
  for (size_t bit = 0; bit < good.size() * 8; ++bit) {
    const size_t byte = bit / 8;
    if (byte >= 20 + 64 && byte < good.size() - 2 && bit % 37 != 0) continue;
    b[byte] = static_cast<uint8_t>(b[byte] ^ (1u << (bit % 8)));
    std::memcpy(&d, &untouched, sizeof d);
    FswLinkError e = FSW_LINK_OK;
    ASSERT_EQ(fsw_link_config_decode(b.data(), b.size(), &d, &e), FSW_E_BAD_INPUT) << "bit " << bit;
    b[byte] = good[byte];
    if (byte < 16) {
      EXPECT_EQ(e, FSW_LINK_E_HEADER);
    } else if (byte < 20) {
      EXPECT_TRUE(e == FSW_LINK_E_SHORT || e == FSW_LINK_E_LENGTH) << "bit " << bit;
    } else {
      EXPECT_EQ(e, FSW_LINK_E_CRC) << "bit " << bit;
    }
    EXPECT_EQ(std::memcmp(&d, &untouched, sizeof d), 0);
  }
  rejects(Bytes(good.begin(), good.begin() + 19), FSW_LINK_E_SHORT);
  rejects(Bytes(good.begin(), good.end() - 1), FSW_LINK_E_SHORT);
  Bytes longer = good;
  longer.push_back(0);
  rejects(longer, FSW_LINK_E_LENGTH);
  // another build's capacity, with a valid CRC: refused by the header
  Bytes other = good;
  other[10] = static_cast<uint8_t>(other[10] + 1);
  put_crc(other);
  rejects(other, FSW_LINK_E_HEADER);
  Bytes rods = good;  // another rod capacity
  rods[13] = static_cast<uint8_t>(rods[13] + 1);
  put_crc(rods);
  rejects(rods, FSW_LINK_E_HEADER);
  // another format version (the one before)
  Bytes version = good;
  version[5] = static_cast<uint8_t>(FSW_LINK_CONFIG_VERSION - 1u);
  put_crc(version);
  rejects(version, FSW_LINK_E_HEADER);
}

// Verifies: REQ-LINK-008
TEST(FswLinkConfig, NullArgumentsAndShortBuffers)
{
  auto c_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& c = *c_p;
  acsfix::wheel_config(c);
  Bytes b(fsw_link_config_size());
  size_t len = 0;
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_config_encode(nullptr, b.data(), b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_config_encode(&c, nullptr, b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_config_encode(&c, b.data(), b.size(), nullptr, &e), FSW_E_NULL_ARG);
  const Bytes before = b;
  EXPECT_EQ(fsw_link_config_encode(&c, b.data(), b.size() - 1, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_SPACE);
  EXPECT_EQ(b, before);
  EXPECT_EQ(fsw_link_config_encode(&c, b.data(), b.size(), &len, nullptr), FSW_OK);
  EXPECT_EQ(fsw_link_config_decode(nullptr, b.size(), &c, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_config_decode(b.data(), b.size(), nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_config_decode(b.data(), b.size(), &c, nullptr), FSW_OK);
}

// ---- link status packet ---------------------------------------------------

// Verifies: REQ-LINK-003, REQ-LINK-004
TEST(FswLinkStatus, RoundTripsAndChecksItsFields)
{
  FswLinkStatusMsg m{}, d{};
  m.rx_packets = 0x01020304u;
  m.rx_crc = 5;
  m.rx_rejected = 6;
  m.rx_stale = 7;
  m.missed = 8;
  m.safe_entries = 9;
  m.safe_cycles = 10;
  m.recoveries = 11;
  m.cycles = 0xFFFFFFFFu;
  m.last_seq = 16383;
  m.link_safe = 1;
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  ASSERT_EQ(fsw_link_encode_status(&m, 42, 7, b.data(), b.size(), &len, nullptr), FSW_OK);
  ASSERT_EQ(len, 14u + FSW_LINK_STATUS_PAYLOAD + 2u);
  EXPECT_EQ(b[14], 0x01);  // rx_packets, big-endian, first in the payload
  EXPECT_EQ(b[17], 0x04);
  FswLinkPacket p;
  ASSERT_EQ(fsw_link_parse(b.data(), len, &p, nullptr), FSW_OK);
  EXPECT_EQ(p.apid, FSW_LINK_APID_LINK);
  EXPECT_EQ(p.type, 0u);
  FswLinkError e = FSW_LINK_E_CRC;
  ASSERT_EQ(fsw_link_decode_status(&p, &d, &e), FSW_OK);
  EXPECT_EQ(e, FSW_LINK_OK);
  EXPECT_EQ(b[14 + 39], 2u);        // the ICD version (2), whatever m.icd_version says (0 here)
  EXPECT_EQ(d.icd_version, 2u);
  d.icd_version = m.icd_version;
  EXPECT_EQ(std::memcmp(&m, &d, sizeof m), 0);

  auto reject = [&](size_t at, uint8_t v, FswLinkError want) {
    Bytes x(b.begin(), b.begin() + static_cast<long>(len));
    x[at] = v;
    put_crc(x);
    FswLinkPacket q;
    ASSERT_EQ(fsw_link_parse(x.data(), x.size(), &q, nullptr), FSW_OK);
    FswLinkStatusMsg out;
    std::memset(&out, 0x33, sizeof out);
    const FswLinkStatusMsg before = out;
    FswLinkError why = FSW_LINK_OK;
    EXPECT_EQ(fsw_link_decode_status(&q, &out, &why), FSW_E_BAD_INPUT);
    EXPECT_EQ(why, want);
    EXPECT_EQ(std::memcmp(&out, &before, sizeof out), 0);
  };
  reject(14 + 38, 2, FSW_LINK_E_COUNT);      // link_safe flag 2
  reject(14 + 39, 1, FSW_LINK_E_HEADER);     // ICD version 1 (byte 39 was reserved, 0, in version 1)
  reject(14 + 39, 0, FSW_LINK_E_HEADER);
  reject(14 + 36, 0x40, FSW_LINK_E_COUNT);   // last_seq 16384 + ...
  reject(1, 0x82, FSW_LINK_E_APID);          // APID 0x182 (health)
  // wrong length: a health packet's APID changed to 0x183 has 254 bytes
  FswAcsHealthMsg h{};
  ASSERT_EQ(fsw_link_encode_health(&h, 1, 1, b.data(), b.size(), &len, nullptr), FSW_OK);
  b[1] = 0x83;
  Bytes y(b.begin(), b.begin() + static_cast<long>(len));
  put_crc(y);
  ASSERT_EQ(fsw_link_parse(y.data(), y.size(), &p, nullptr), FSW_OK);
  EXPECT_EQ(fsw_link_decode_status(&p, &d, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_LENGTH);
  // nulls and space
  EXPECT_EQ(fsw_link_decode_status(nullptr, &d, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_decode_status(&p, nullptr, &e), FSW_E_NULL_ARG);
  FswLinkPacket np = p;
  np.payload = nullptr;
  EXPECT_EQ(fsw_link_decode_status(&np, &d, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_status(nullptr, 0, 0, b.data(), b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_status(&m, 0, 0, nullptr, b.size(), &len, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_status(&m, 0, 0, b.data(), b.size(), nullptr, &e), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_encode_status(&m, 0, 0, b.data(), 14 + FSW_LINK_STATUS_PAYLOAD + 1, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_SPACE);
}

// ---- the node ---------------------------------------------------------------

namespace {

constexpr uint8_t kRw = 4, kCss = 6;

// A sensor message of cycle k: a slow tumble with the Sun along +x, the
// wheels at growing speeds.
FswAcsSensorMsg sensors(int k)
{
  FswAcsSensorMsg s;
  std::memset(&s, 0, sizeof s);
  s.t_ns = static_cast<uint64_t>(k) * acsfix::kPeriodNs;
  s.att_valid = 1;
  s.sigma_BN[0] = R(0.01 * k);
  s.omega_BN_B[0] = R(0.01);
  s.omega_BN_B[1] = R(-0.02);
  s.omega_BN_B[2] = R(0.005 * k);
  for (int i = 0; i < kRw; ++i) s.Omega[i] = R(10.0 * i + k);
  s.css[0] = R(0.9);
  s.css[2] = R(0.3);
  return s;
}

Bytes sensor_packet(const FswAcsSensorMsg& s, uint16_t seq)
{
  Bytes b(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  EXPECT_EQ(fsw_link_encode_sensor(&s, kRw, kCss, seq, b.data(), b.size(), &len, nullptr), FSW_OK);
  b.resize(len);
  return b;
}

struct Node {  // always on the heap (make_unique): large for a target's test stack
  FswAcsConfig cfg;
  FswLinkNode n;
  explicit Node(uint32_t max_missed = 3)
  {
    acsfix::wheel_config(cfg);
    const char* bad = "x";
    EXPECT_EQ(fsw_link_node_init(&n, &cfg, max_missed, &bad), FSW_OK);
    EXPECT_EQ(bad, nullptr);
  }
  int feed(const Bytes& b) { return fsw_link_node_receive(&n, &cfg, b.data(), b.size()); }
  FswLinkPacket reply(int i) const
  {
    FswLinkPacket p;
    EXPECT_EQ(fsw_link_parse(n.out[i], n.out_len[i], &p, nullptr), FSW_OK);
    return p;
  }
  // The link status in reply 0, decoded; its time stamp in t_ns.
  FswLinkStatusMsg status(uint64_t& t_ns) const
  {
    const FswLinkPacket p = reply(0);
    FswLinkStatusMsg ls;
    std::memset(&ls, 0, sizeof ls);
    EXPECT_EQ(fsw_link_decode_status(&p, &ls, nullptr), FSW_OK);
    t_ns = p.t_ns;
    return ls;
  }
};

}  // namespace

// Verifies: REQ-NODE-001
TEST(FswLinkNode, RepliesEqualTheApplicationRunDirectly)
{
  // heap: the node and the state are large for a target's test stack
  auto nodep = std::make_unique<Node>();
  Node& node = *nodep;
  auto stp = std::make_unique<FswAcsState>();
  FswAcsState& st = *stp;
  ASSERT_EQ(fsw_acs_init(&st, &node.cfg, nullptr), FSW_OK);
  for (int k = 0; k < 20; ++k) {
    const FswAcsSensorMsg s = sensors(k);
    ASSERT_EQ(node.feed(sensor_packet(s, static_cast<uint16_t>(k))), 3);
    FswAcsActuatorMsg act, ract;
    FswAcsHealthMsg h, rh;
    fsw_acs_cycle(&st, &node.cfg, &s, nullptr, &act, &h);
    uint8_t nrw = 0, nthr = 9, nmtq = 9;
    const FswLinkPacket pa = node.reply(0), ph = node.reply(1), pl = node.reply(2);
    ASSERT_EQ(fsw_link_decode_actuator(&pa, &ract, &nrw, &nthr, &nmtq, nullptr), FSW_OK);
    EXPECT_EQ(nmtq, 0u);  // the configuration has no rods yet
    ASSERT_EQ(fsw_link_decode_health(&ph, &rh, nullptr), FSW_OK);
    EXPECT_EQ(pa.t_ns, s.t_ns);
    EXPECT_EQ(ph.t_ns, s.t_ns);
    EXPECT_EQ(pl.t_ns, s.t_ns);
    EXPECT_EQ(pa.seq, k);
    EXPECT_EQ(nrw, kRw);
    EXPECT_EQ(nthr, 0u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(ract.Lr_B[i], act.Lr_B[i]);
    for (int i = 0; i < kRw; ++i) {
      EXPECT_EQ(ract.u_s[i], act.u_s[i]);
      EXPECT_EQ(ract.V[i], act.V[i]);
    }
    EXPECT_EQ(ract.wheels_active, act.wheels_active);
    EXPECT_EQ(rh.status, h.status);
    EXPECT_EQ(rh.cycles, h.cycles);
    EXPECT_EQ(rh.att_err_angle, h.att_err_angle);
    EXPECT_EQ(rh.sun_angle_err, h.sun_angle_err);
    FswLinkStatusMsg ls;
    ASSERT_EQ(fsw_link_decode_status(&pl, &ls, nullptr), FSW_OK);
    EXPECT_EQ(ls.cycles, static_cast<uint32_t>(k + 1));
    EXPECT_EQ(ls.rx_packets, static_cast<uint32_t>(k + 1));
    EXPECT_EQ(ls.last_seq, k);
  }
  EXPECT_EQ(node.n.link.missed, 0u);
  EXPECT_EQ(node.n.link.rx_stale + node.n.link.rx_crc + node.n.link.rx_rejected, 0u);
}

// Verifies: REQ-NODE-002
TEST(FswLinkNode, StaleDamagedAndForeignPacketsAreCountedAndAnsweredByTheStatus)
{
  auto nodep = std::make_unique<Node>();
  Node& node = *nodep;
  ASSERT_EQ(node.feed(sensor_packet(sensors(5), 100)), 3);
  EXPECT_EQ(node.feed(sensor_packet(sensors(5), 100)), 3);  // duplicate: the replies again (below)
  EXPECT_EQ(node.feed(sensor_packet(sensors(6), 99)), 1);   // older sequence count
  EXPECT_EQ(node.feed(sensor_packet(sensors(4), 101)), 1);  // newer count, older time
  EXPECT_EQ(node.feed(sensor_packet(sensors(5), 101)), 1);  // newer count, same time
  EXPECT_EQ(node.feed(sensor_packet(sensors(6), uint16_t(100 + 8192))), 1);  // half the circle: behind
  EXPECT_EQ(node.n.link.rx_stale, 5u);
  {  // the status answer: the counters so far, the last accepted time stamp
    uint64_t t = 0;
    const FswLinkStatusMsg ls = node.status(t);
    EXPECT_EQ(t, sensors(5).t_ns);
    EXPECT_EQ(ls.rx_stale, 5u);
    EXPECT_EQ(ls.rx_packets, 6u);
    EXPECT_EQ(ls.cycles, 1u);
  }
  EXPECT_EQ(node.n.acs.cycles, 1u);  // none of them ran a cycle
  Bytes bad = sensor_packet(sensors(6), 101);
  bad[20] ^= 0x10;
  EXPECT_EQ(node.feed(bad), 1);
  EXPECT_EQ(node.n.link.rx_crc, 1u);
  EXPECT_EQ(node.feed(Bytes(bad.begin(), bad.begin() + 10)), 1);  // short
  // an actuator packet is not for the FSW; nor is a sensor packet whose
  // declared counts do not match its length
  FswAcsActuatorMsg a{};
  Bytes ab(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  ASSERT_EQ(fsw_link_encode_actuator(&a, 0, 0, 0, 1, 0, ab.data(), ab.size(), &len, nullptr), FSW_OK);
  ab.resize(len);
  EXPECT_EQ(node.feed(ab), 1);
  Bytes wrong = sensor_packet(sensors(6), 101);
  wrong[14] = kRw + 1;  // n_rw
  put_crc(wrong);
  EXPECT_EQ(node.feed(wrong), 1);
  EXPECT_EQ(node.n.link.rx_rejected, 3u);
  EXPECT_EQ(node.n.link.rx_packets, 10u);
  // a gap: sequence 100 -> 104 misses 3 cycles, and is answered
  EXPECT_EQ(node.feed(sensor_packet(sensors(9), 104)), 3);
  EXPECT_EQ(node.n.link.missed, 3u);
  // wrap-around: 16383 -> 0 is one ahead
  auto wp = std::make_unique<Node>();
  Node& w = *wp;
  ASSERT_EQ(w.feed(sensor_packet(sensors(1), 16383)), 3);
  EXPECT_EQ(w.feed(sensor_packet(sensors(2), 0)), 3);
  EXPECT_EQ(w.n.link.missed, 0u);
}

// Verifies: REQ-NODE-003
TEST(FswLinkNode, CommandsApplyFromTheNextCycle)
{
  auto nodep = std::make_unique<Node>();
  Node& node = *nodep;
  FswAcsCmdMsg c{FSW_ACS_MODE_INERTIAL, FSW_ACS_ACT_WHEELS};
  Bytes cb(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  ASSERT_EQ(node.feed(sensor_packet(sensors(1), 1)), 3);
  FswAcsHealthMsg h;
  FswLinkPacket ph = node.reply(1);
  ASSERT_EQ(fsw_link_decode_health(&ph, &h, nullptr), FSW_OK);
  EXPECT_EQ(h.mode, FSW_ACS_MODE_SUN_SAFE);
  ASSERT_EQ(fsw_link_encode_cmd(&c, 0, 0, cb.data(), cb.size(), &len, nullptr), FSW_OK);
  cb.resize(len);
  EXPECT_EQ(node.feed(cb), 1);
  ASSERT_EQ(node.feed(sensor_packet(sensors(2), 2)), 3);
  ph = node.reply(1);
  ASSERT_EQ(fsw_link_decode_health(&ph, &h, nullptr), FSW_OK);
  EXPECT_EQ(h.mode, FSW_ACS_MODE_INERTIAL);
  EXPECT_EQ(h.mode_changes, 1u);
}

// Verifies: REQ-NODE-004
TEST(FswLinkNode, WatchdogEntersLinkSafeAndDataRecovers)
{
  auto nodep = std::make_unique<Node>(3);
  Node& node = *nodep;
  ASSERT_EQ(node.feed(sensor_packet(sensors(1), 1)), 3);
  EXPECT_EQ(fsw_link_node_watchdog(&node.n, 7), 0);
  EXPECT_EQ(fsw_link_node_watchdog(&node.n, 7), 0);
  EXPECT_EQ(node.n.link.link_safe, 0u);
  ASSERT_EQ(fsw_link_node_watchdog(&node.n, 7), 2);  // the third missed period
  FswAcsActuatorMsg a;
  uint8_t nrw = 0, nthr = 0, nmtq = 0;
  FswLinkPacket pa = node.reply(0), pl = node.reply(1);
  ASSERT_EQ(fsw_link_decode_actuator(&pa, &a, &nrw, &nthr, &nmtq, nullptr), FSW_OK);
  EXPECT_EQ(pa.t_ns, 7u);
  EXPECT_EQ(a.wheels_active, 0u);
  EXPECT_EQ(a.thrusters_active, 0u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a.Lr_B[i], R(0));
  for (int i = 0; i < kRw; ++i) EXPECT_EQ(a.u_s[i], R(0));
  FswLinkStatusMsg ls;
  ASSERT_EQ(fsw_link_decode_status(&pl, &ls, nullptr), FSW_OK);
  EXPECT_EQ(ls.link_safe, 1u);
  EXPECT_EQ(ls.safe_entries, 1u);
  EXPECT_EQ(ls.safe_cycles, 1u);
  EXPECT_EQ(ls.missed, 3u);
  ASSERT_EQ(fsw_link_node_watchdog(&node.n, 8), 2);  // still safe: one entry, two safe outputs
  EXPECT_EQ(node.n.link.safe_entries, 1u);
  EXPECT_EQ(node.n.link.safe_cycles, 2u);
  ASSERT_EQ(node.feed(sensor_packet(sensors(2), 2)), 3);  // data returns
  EXPECT_EQ(node.n.link.link_safe, 0u);
  EXPECT_EQ(node.n.link.recoveries, 1u);
  EXPECT_EQ(node.n.consec_missed, 0u);
  // the count starts again: two more periods do not trip it
  EXPECT_EQ(fsw_link_node_watchdog(&node.n, 9), 0);
  EXPECT_EQ(fsw_link_node_watchdog(&node.n, 9), 0);
}

// Verifies: REQ-NODE-006
TEST(FswLinkNode, InitChecksItsArguments)
{
  auto cfg_p = std::make_unique<FswAcsConfig>();
  FswAcsConfig& cfg = *cfg_p;
  acsfix::wheel_config(cfg);
  auto np = std::make_unique<FswLinkNode>();
  FswLinkNode& n = *np;
  const char* bad = nullptr;
  EXPECT_EQ(fsw_link_node_init(&n, &cfg, 0, &bad), FSW_E_CONFIG);
  EXPECT_STREQ(bad, "max_missed");
  EXPECT_EQ(fsw_link_node_init(&n, &cfg, 0, nullptr), FSW_E_CONFIG);
  EXPECT_EQ(fsw_link_node_init(nullptr, &cfg, 1, &bad), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_node_init(&n, nullptr, 1, nullptr), FSW_E_NULL_ARG);
  cfg.initial_mode = 7;
  EXPECT_NE(fsw_link_node_init(&n, &cfg, 1, &bad), FSW_OK);
  EXPECT_STREQ(bad, "initial_mode");
  // a thruster config: actuator packets carry the thrusters
  acsfix::thruster_config(cfg);
  ASSERT_EQ(fsw_link_node_init(&n, &cfg, 1, nullptr), FSW_OK);
  EXPECT_EQ(n.num_rw, 0u);
  EXPECT_EQ(n.num_thr, 8u);
  uint8_t b[4] = {0, 0, 0, 0};
  EXPECT_EQ(fsw_link_node_receive(nullptr, &cfg, b, 4), 0);
  EXPECT_EQ(fsw_link_node_receive(&n, nullptr, b, 4), 0);
  EXPECT_EQ(fsw_link_node_receive(&n, &cfg, nullptr, 4), 0);
  EXPECT_EQ(fsw_link_node_watchdog(nullptr, 0), 0);
}

// A retransmitted sensor packet (the same bytes again: the sender lost the
// reply) is answered by the last cycle's three replies, byte for byte, and
// runs no second cycle; it is counted stale and resent.  The same sequence
// count and time with another payload (another CRC) is not a retransmission:
// stale, the link status alone.  After link-safe entry the old replies are
// no longer offered.
// Verifies: REQ-NODE-005
TEST(FswLinkNode, ARetransmittedSensorPacketIsAnsweredAgainWithoutASecondCycle)
{
  auto nodep = std::make_unique<Node>();
  Node& node = *nodep;
  const Bytes first = sensor_packet(sensors(5), 100);
  ASSERT_EQ(node.feed(first), 3);
  std::vector<Bytes> replies;
  for (int i = 0; i < 3; ++i) replies.emplace_back(node.n.out[i], node.n.out[i] + node.n.out_len[i]);
  ASSERT_EQ(node.feed(first), 3);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(Bytes(node.n.out[i], node.n.out[i] + node.n.out_len[i]), replies[size_t(i)]) << "reply " << i;
  EXPECT_EQ(node.n.acs.cycles, 1u);
  EXPECT_EQ(node.n.link.cycles, 1u);
  EXPECT_EQ(node.n.link.rx_stale, 1u);
  EXPECT_EQ(node.n.resent, 1u);
  FswAcsSensorMsg other = sensors(5);
  other.omega_BN_B[0] = R(0.03);  // same count and time, other bytes
  EXPECT_EQ(node.feed(sensor_packet(other, 100)), 1);
  EXPECT_EQ(node.n.link.rx_stale, 2u);
  EXPECT_EQ(node.n.resent, 1u);
  // three missed periods: link-safe; the old packet is now plain stale
  for (int i = 0; i < 3; ++i) (void)fsw_link_node_watchdog(&node.n, 7);
  ASSERT_EQ(node.n.link.link_safe, 1u);
  EXPECT_EQ(node.feed(first), 1);
  EXPECT_EQ(node.n.resent, 1u);
  EXPECT_EQ(node.n.acs.cycles, 1u);
}

// MC/DC of the retransmission test (fsw_link_node.c: have_last &&
// have_replies && seq == last && t == last_t && crc == last_crc): the last
// packet's sequence count with another time (one period later, the other
// fields unchanged) is not a retransmission: it is stale (the count did not
// advance), answered by the link status alone, and runs no cycle; the exact
// retransmission right after it is still answered with the three replies.
// Verifies: REQ-NODE-002, REQ-NODE-005
TEST(FswLinkNode, McdcTheSameCountWithAnotherTimeIsStaleNotARetransmission)
{
  auto nodep = std::make_unique<Node>();
  Node& node = *nodep;
  const Bytes first = sensor_packet(sensors(5), 100);
  ASSERT_EQ(node.feed(first), 3);
  FswAcsSensorMsg later = sensors(5);
  later.t_ns += acsfix::kPeriodNs;
  EXPECT_EQ(node.feed(sensor_packet(later, 100)), 1);
  EXPECT_EQ(node.n.link.rx_stale, 1u);
  EXPECT_EQ(node.n.resent, 0u);
  EXPECT_EQ(node.n.acs.cycles, 1u);
  uint64_t t = 0;
  const FswLinkStatusMsg ls = node.status(t);  // stamped with the last accepted time
  EXPECT_EQ(t, sensors(5).t_ns);
  EXPECT_EQ(ls.rx_stale, 1u);
  EXPECT_EQ(ls.cycles, 1u);
  ASSERT_EQ(node.feed(first), 3);
  EXPECT_EQ(node.n.resent, 1u);
  EXPECT_EQ(node.n.link.rx_stale, 2u);
  EXPECT_EQ(node.n.acs.cycles, 1u);
}

// The messages the node hands its application are the messages the sender
// encoded, bit for bit: the contract by which the Eva envelope analysis of
// the node takes the two decoders (test/proofs/eva/fsw_link_node.c), over
// its domain: sensor packets with the configured counts (entries beyond
// them 0), every flag 0 or 1, and command packets with every mode,
// actuation and policy, the set flags 0 or 1; the reals +-1e6, +-1e-6,
// both zeros, the smallest subnormal and normal numbers and pseudo-random
// bit patterns of every finite value within 1e6.  The node decodes before
// it judges a packet, so the cycle's own verdicts (refused inputs) do not
// matter here.
// Verifies: REQ-LINK-003
TEST(FswLinkNode, TheApplicationGetsTheEncodedMessagesBitForBit)
{
  auto nodep = std::make_unique<Node>();
  Node& node = *nodep;
  const fsw_real special[] = {R(1e6), R(-1e6), R(1e-6), R(-1e-6), R(0.0), -R(0.0),
                              std::numeric_limits<fsw_real>::denorm_min(), -std::numeric_limits<fsw_real>::min(),
                              R(0.1)};
  const size_t n_special = sizeof special / sizeof special[0];
  uint64_t x = 0x9E3779B97F4A7C15ull;  // xorshift64 state
  size_t next_special = 0;
  auto bits = [&x]() {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  auto real = [&]() {
    if (next_special < n_special) return special[next_special++];
    for (;;) {  // a random finite bit pattern within the envelope
      const uint64_t b = bits();
      double d;
      std::memcpy(&d, &b, sizeof d);
      if (std::isfinite(d) && std::fabs(d) <= 1e6) return static_cast<fsw_real>(d);
    }
  };
  auto flag = [&bits]() { return static_cast<uint8_t>(bits() & 1u); };
  for (int k = 0; k < 200; ++k) {
    FswAcsSensorMsg m;
    std::memset(&m, 0, sizeof m);
    m.t_ns = static_cast<uint64_t>(k + 1) * acsfix::kPeriodNs;
    m.att_valid = flag();
    m.mag_valid = flag();
    m.orbit_valid = flag();
    for (int i = 0; i < 3; ++i) {
      m.sigma_BN[i] = real();
      m.omega_BN_B[i] = real();
      m.r_CoM_B[i] = real();
      m.B_B[i] = real();
      m.r_N[i] = real();
      m.v_N[i] = real();
    }
    for (int i = 0; i < kRw; ++i) {
      m.Omega[i] = real();
      m.rw_avail[i] = flag();
    }
    for (int i = 0; i < kCss; ++i) {
      m.css[i] = real();
      m.css_avail[i] = flag();
    }
    for (int i = 0; i < FSW_MAX_THR; ++i) m.thr_avail[i] = flag();
    node.feed(sensor_packet(m, static_cast<uint16_t>(k)));
    ASSERT_EQ(std::memcmp(&node.n.sens, &m, sizeof m), 0) << "sensor packet " << k;

    FswAcsCmdMsg c;
    std::memset(&c, 0, sizeof c);
    c.mode = k % 4;
    c.actuation = (k / 4) % 2;
    c.set_ref = flag();
    c.set_gains = flag();
    c.set_policy = flag();
    c.policy = (k / 8) % 3;
    for (int i = 0; i < 3; ++i) c.sigma_R0N[i] = real();
    c.K = real();
    c.P = real();
    Bytes cb(FSW_LINK_MAX_PACKET);
    size_t len = 0;
    ASSERT_EQ(fsw_link_encode_cmd(&c, m.t_ns, static_cast<uint16_t>(k), cb.data(), cb.size(), &len, nullptr), FSW_OK);
    cb.resize(len);
    EXPECT_EQ(node.feed(cb), 1);
    ASSERT_EQ(std::memcmp(&node.n.cmd, &c, sizeof c), 0) << "command packet " << k;
    EXPECT_EQ(node.n.have_cmd, 1u);
  }
  EXPECT_EQ(node.n.link.rx_rejected + node.n.link.rx_crc, 0u);
}

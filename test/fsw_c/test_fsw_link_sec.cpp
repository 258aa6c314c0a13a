// fsw_link_sec: SHA-256 against the FIPS 180-2 examples, HMAC-SHA-256
// against the seven test cases of RFC 4231 (published values, typed in from
// the RFC), and the security trailer: a round trip, every single-bit flip
// of a protected packet refused, a wrong key refused, replays and numbers
// older than the 64-wide window refused, out-of-order numbers inside the
// window accepted once, key lengths outside 16 ... 64 bytes refused.
#include <gtest/gtest.h>

#include <string>
#include <vector>

extern "C" {
#include "fsw/fsw_link_sec.h"
}

namespace {

using Bytes = std::vector<uint8_t>;

std::string hex(const uint8_t* p, size_t n)
{
  static const char* d = "0123456789abcdef";
  std::string s;
  for (size_t i = 0; i < n; ++i) {
    s += d[p[i] >> 4];
    s += d[p[i] & 15];
  }
  return s;
}

Bytes str(const std::string& s) { return Bytes(s.begin(), s.end()); }

std::string sha256(const Bytes& m)
{
  FswSha256 c;
  uint8_t out[32];
  fsw_sha256_init(&c);
  fsw_sha256_update(&c, m.data(), m.size());
  fsw_sha256_final(&c, out);
  return hex(out, 32);
}

std::string hmac(const Bytes& key, const Bytes& msg)
{
  uint8_t out[32];
  fsw_hmac_sha256(key.data(), key.size(), msg.data(), msg.size(), nullptr, 0, out);
  return hex(out, 32);
}

// A packet-like byte string (the trailer does not parse the packet).
Bytes packet(uint8_t fill, size_t n = 40)
{
  Bytes b(n);
  for (size_t i = 0; i < n; ++i) b[i] = static_cast<uint8_t>(fill + 7 * i);
  return b;
}

const Bytes kKey = str("0123456789abcdef0123456789abcdef");  // 32 bytes

}  // namespace

// Verifies: REQ-LSEC-001
TEST(FswSha256, FipsExamples)
{
  EXPECT_EQ(sha256(str("abc")), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256(str("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256({}), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  // fed in pieces of every size: the same digest
  const Bytes m = str("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq");
  for (size_t piece = 1; piece < m.size(); ++piece) {
    FswSha256 c;
    uint8_t out[32];
    fsw_sha256_init(&c);
    for (size_t i = 0; i < m.size(); i += piece) fsw_sha256_update(&c, m.data() + i, std::min(piece, m.size() - i));
    fsw_sha256_final(&c, out);
    EXPECT_EQ(hex(out, 32), "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1") << piece;
  }
}

// Verifies: REQ-LSEC-001
TEST(FswHmacSha256, Rfc4231TestCases)
{
  Bytes k4;
  for (uint8_t i = 1; i <= 25; ++i) k4.push_back(i);
  EXPECT_EQ(hmac(Bytes(20, 0x0b), str("Hi There")), "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
  EXPECT_EQ(hmac(str("Jefe"), str("what do ya want for nothing?")),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
  EXPECT_EQ(hmac(Bytes(20, 0xaa), Bytes(50, 0xdd)), "773ea91e36800e46854db8ebd09181a72959098b3ef8c122d9635514ced565fe");
  EXPECT_EQ(hmac(k4, Bytes(50, 0xcd)), "82558a389a443c0ea4cc819899f2083a85f0faa3e578f8077a2e3ff46729665b");
  EXPECT_EQ(hmac(Bytes(20, 0x0c), str("Test With Truncation")).substr(0, 32), "a3b6167473100ee06e0c796c2955552b");
  EXPECT_EQ(hmac(Bytes(131, 0xaa), str("Test Using Larger Than Block-Size Key - Hash Key First")),
            "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
  EXPECT_EQ(hmac(Bytes(131, 0xaa), str("This is a test using a larger than block-size key and a larger than block-size "
                                       "data. The key needs to be hashed before being used by the HMAC algorithm.")),
            "9b09ffa71b942fcb27635fbcd5b0e944bfdc63644f0713938a7f51535c3a35e2");
  // a || b is the concatenation
  uint8_t out[32];
  const Bytes d = str("what do ya want for nothing?");
  fsw_hmac_sha256(reinterpret_cast<const uint8_t*>("Jefe"), 4, d.data(), 9, d.data() + 9, d.size() - 9, out);
  EXPECT_EQ(hex(out, 32), "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

// Verifies: REQ-LSEC-002
TEST(FswLinkSec, RoundTripAndTheTrailerLayout)
{
  FswLinkSec tx, rx;
  ASSERT_EQ(fsw_link_sec_init(&tx, kKey.data(), kKey.size()), FSW_OK);
  ASSERT_EQ(fsw_link_sec_init(&rx, kKey.data(), kKey.size()), FSW_OK);
  for (uint32_t k = 1; k <= 3; ++k) {
    const Bytes p = packet(static_cast<uint8_t>(k));
    Bytes w(p.size() + FSW_LINK_SEC_TRAILER_SIZE);
    size_t len = 0;
    ASSERT_EQ(fsw_link_sec_protect(&tx, p.data(), p.size(), w.data(), w.size(), &len, nullptr), FSW_OK);
    ASSERT_EQ(len, p.size() + 20u);
    EXPECT_EQ(Bytes(w.begin(), w.begin() + 40), p);
    EXPECT_EQ(Bytes(w.begin() + 40, w.begin() + 44), (Bytes{0, 0, 0, static_cast<uint8_t>(k)}));  // big-endian number
    // the MAC: HMAC-SHA-256 of packet || number, first 16 bytes
    EXPECT_EQ(hex(w.data() + 44, 16), hmac(kKey, Bytes(w.begin(), w.begin() + 44)).substr(0, 32));
    size_t plen = 0;
    FswLinkError e = FSW_LINK_E_SHORT;
    ASSERT_EQ(fsw_link_sec_verify(&rx, w.data(), w.size(), &plen, &e), FSW_OK);
    EXPECT_EQ(e, FSW_LINK_OK);
    EXPECT_EQ(plen, p.size());
  }
  EXPECT_EQ(rx.rx_ok, 3u);
  Bytes small(30);
  size_t len = 0;
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_sec_protect(&tx, small.data(), 11, small.data() + 11, 19, &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_SPACE);
}

// Verifies: REQ-LSEC-003
TEST(FswLinkSec, EveryBitFlipAWrongKeyAndAMissingTrailerAreRefused)
{
  FswLinkSec tx, rx, other;
  ASSERT_EQ(fsw_link_sec_init(&tx, kKey.data(), kKey.size()), FSW_OK);
  const Bytes p = packet(9);
  Bytes w(p.size() + 20);
  size_t len = 0;
  ASSERT_EQ(fsw_link_sec_protect(&tx, p.data(), p.size(), w.data(), w.size(), &len, nullptr), FSW_OK);
  for (size_t bit = 0; bit < w.size() * 8; ++bit) {
    ASSERT_EQ(fsw_link_sec_init(&rx, kKey.data(), kKey.size()), FSW_OK);
    Bytes bad = w;
    bad[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    size_t plen = 0;
    FswLinkError e = FSW_LINK_OK;
    EXPECT_EQ(fsw_link_sec_verify(&rx, bad.data(), bad.size(), &plen, &e), FSW_E_BAD_INPUT) << bit;
    EXPECT_EQ(e, FSW_LINK_E_AUTH) << bit;
    EXPECT_EQ(rx.rx_high, 0u);  // a refused packet moves nothing
  }
  Bytes k2 = kKey;
  k2[31] ^= 1;
  ASSERT_EQ(fsw_link_sec_init(&other, k2.data(), k2.size()), FSW_OK);
  size_t plen = 0;
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_sec_verify(&other, w.data(), w.size(), &plen, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_AUTH);
  EXPECT_EQ(other.rx_auth_failed, 1u);
  // the bare packet (no trailer): its last 20 bytes are no MAC
  EXPECT_EQ(fsw_link_sec_verify(&other, p.data(), p.size(), &plen, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_AUTH);
  EXPECT_EQ(fsw_link_sec_verify(&other, p.data(), 20, &plen, &e), FSW_E_BAD_INPUT);  // too short for one
  EXPECT_EQ(other.rx_auth_failed, 3u);
}

// Verifies: REQ-LSEC-004
TEST(FswLinkSec, ReplaysAndNumbersOlderThanTheWindowAreRefused)
{
  FswLinkSec tx, rx;
  ASSERT_EQ(fsw_link_sec_init(&tx, kKey.data(), kKey.size()), FSW_OK);
  ASSERT_EQ(fsw_link_sec_init(&rx, kKey.data(), kKey.size()), FSW_OK);
  std::vector<Bytes> sent;  // numbers 1 ... 100
  for (int k = 0; k < 100; ++k) {
    const Bytes p = packet(static_cast<uint8_t>(k));
    Bytes w(p.size() + 20);
    size_t len = 0;
    ASSERT_EQ(fsw_link_sec_protect(&tx, p.data(), p.size(), w.data(), w.size(), &len, nullptr), FSW_OK);
    sent.push_back(w);
  }
  const auto verify = [&](int number) {
    size_t plen = 0;
    FswLinkError e = FSW_LINK_OK;
    const Bytes& w = sent[size_t(number - 1)];
    return fsw_link_sec_verify(&rx, w.data(), w.size(), &plen, &e) == FSW_OK ? FSW_LINK_OK : e;
  };
  EXPECT_EQ(verify(10), FSW_LINK_OK);
  EXPECT_EQ(verify(10), FSW_LINK_E_REPLAY);  // the same packet again
  EXPECT_EQ(verify(5), FSW_LINK_OK);          // late but inside the window, not seen
  EXPECT_EQ(verify(5), FSW_LINK_E_REPLAY);
  EXPECT_EQ(verify(100), FSW_LINK_OK);        // the highest is now 100: the window is 37 ... 100
  EXPECT_EQ(verify(37), FSW_LINK_OK);
  EXPECT_EQ(verify(36), FSW_LINK_E_REPLAY);   // 64 below the highest: out of the window
  EXPECT_EQ(verify(10), FSW_LINK_E_REPLAY);
  EXPECT_EQ(verify(99), FSW_LINK_OK);
  EXPECT_EQ(verify(99), FSW_LINK_E_REPLAY);
  EXPECT_EQ(rx.rx_ok, 5u);
  EXPECT_EQ(rx.rx_replayed, 5u);
  EXPECT_EQ(rx.rx_auth_failed, 0u);
}

// Verifies: REQ-LSEC-005
TEST(FswLinkSec, KeyLengthsOutsideTheRangeAreRefused)
{
  FswLinkSec s;
  const Bytes k(65, 1);
  EXPECT_EQ(fsw_link_sec_init(&s, k.data(), 15), FSW_E_CONFIG);
  EXPECT_EQ(fsw_link_sec_init(&s, k.data(), 65), FSW_E_CONFIG);
  EXPECT_EQ(fsw_link_sec_init(&s, k.data(), 16), FSW_OK);
  EXPECT_EQ(fsw_link_sec_init(&s, k.data(), 64), FSW_OK);
  EXPECT_EQ(fsw_link_sec_init(nullptr, k.data(), 16), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_sec_init(&s, nullptr, 16), FSW_E_NULL_ARG);
  // a sender whose numbers are used up stops
  ASSERT_EQ(fsw_link_sec_init(&s, k.data(), 32), FSW_OK);
  s.tx_seq = 0xFFFFFFFFu;
  const Bytes p = packet(1);
  Bytes w(p.size() + 20);
  size_t len = 0;
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_sec_protect(&s, p.data(), p.size(), w.data(), w.size(), &len, &e), FSW_OK);
  EXPECT_EQ(fsw_link_sec_protect(&s, p.data(), p.size(), w.data(), w.size(), &len, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_COUNT);
}

// HMAC-SHA-256 with an empty key and an empty message: the value published
// with the HMAC examples of the algorithm (the key is all zero padding).
// Verifies: REQ-LSEC-001
TEST(FswHmacSha256, EmptyKeyAndMessage)
{
  EXPECT_EQ(hmac(Bytes(), Bytes()), "b613679a0814d9ec772f95d778c35fc5ff1697c493715653c6c712144292c5ad");
}

// Missing pointers are refused with FSW_E_NULL_ARG (no write through them);
// the hashing functions ignore a missing context or data and leave the
// digest of what came before unchanged; the error out-pointer is optional.
// Verifies: REQ-LSEC-006
TEST(FswLinkSec, MissingPointersAndAnOmittedErrorCode)
{
  fsw_sha256_init(nullptr);
  fsw_sha256_update(nullptr, nullptr, 3);
  FswSha256 c;
  fsw_sha256_init(&c);
  fsw_sha256_update(&c, reinterpret_cast<const uint8_t*>("abc"), 3);
  fsw_sha256_update(&c, nullptr, 5);  // refused: nothing added
  uint8_t out[32];
  fsw_sha256_final(&c, out);
  EXPECT_EQ(hex(out, 32), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");  // FIPS "abc"

  FswLinkSec s;
  ASSERT_EQ(fsw_link_sec_init(&s, kKey.data(), kKey.size()), FSW_OK);
  const Bytes p = packet(3);
  Bytes w(p.size() + 20);
  size_t len = 0, plen = 0;
  EXPECT_EQ(fsw_link_sec_protect(nullptr, p.data(), p.size(), w.data(), w.size(), &len, nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_sec_protect(&s, nullptr, p.size(), w.data(), w.size(), &len, nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_sec_protect(&s, p.data(), p.size(), nullptr, w.size(), &len, nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_sec_protect(&s, p.data(), p.size(), w.data(), w.size(), nullptr, nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_sec_protect(&s, p.data(), p.size(), w.data(), 19, &len, nullptr), FSW_E_BAD_INPUT);  // no room
  EXPECT_EQ(s.tx_seq, 1u);
  ASSERT_EQ(fsw_link_sec_protect(&s, p.data(), p.size(), w.data(), w.size(), &len, nullptr), FSW_OK);
  FswLinkSec rx;
  ASSERT_EQ(fsw_link_sec_init(&rx, kKey.data(), kKey.size()), FSW_OK);
  EXPECT_EQ(fsw_link_sec_verify(nullptr, w.data(), w.size(), &plen, nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_sec_verify(&rx, nullptr, w.size(), &plen, nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_link_sec_verify(&rx, w.data(), w.size(), nullptr, nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(rx.rx_auth_failed + rx.rx_ok + rx.rx_replayed, 0u);
  EXPECT_EQ(fsw_link_sec_verify(&rx, w.data(), w.size(), &plen, nullptr), FSW_OK);
  EXPECT_EQ(plen, p.size());
  EXPECT_EQ(fsw_link_sec_verify(&rx, w.data(), w.size(), &plen, nullptr), FSW_E_BAD_INPUT);  // a replay
  EXPECT_EQ(rx.rx_replayed, 1u);
}

// Number 0 is never sent (a sender starts at 1): a packet carrying it, even
// with a good MAC, is a replay.
// Verifies: REQ-LSEC-004
TEST(FswLinkSec, NumberZeroWithAGoodMacIsRefused)
{
  Bytes w = packet(5);
  const size_t n = w.size();
  w.insert(w.end(), {0, 0, 0, 0});
  uint8_t mac[32];
  fsw_hmac_sha256(kKey.data(), kKey.size(), w.data(), w.size(), nullptr, 0, mac);
  w.insert(w.end(), mac, mac + 16);
  FswLinkSec rx;
  ASSERT_EQ(fsw_link_sec_init(&rx, kKey.data(), kKey.size()), FSW_OK);
  size_t plen = 0;
  FswLinkError e = FSW_LINK_OK;
  EXPECT_EQ(fsw_link_sec_verify(&rx, w.data(), w.size(), &plen, &e), FSW_E_BAD_INPUT);
  EXPECT_EQ(e, FSW_LINK_E_REPLAY);
  EXPECT_EQ(rx.rx_replayed, 1u);
  EXPECT_EQ(rx.rx_high, 0u);
  // the same packet numbered 1 (its MAC recomputed) is accepted
  w[n + 3] = 1;
  fsw_hmac_sha256(kKey.data(), kKey.size(), w.data(), n + 4, nullptr, 0, mac);
  std::copy(mac, mac + 16, w.begin() + long(n + 4));
  EXPECT_EQ(fsw_link_sec_verify(&rx, w.data(), w.size(), &plen, &e), FSW_OK);
}

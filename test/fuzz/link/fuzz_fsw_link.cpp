// libFuzzer harness of the FSW link codec (fsw_link.h, docs/icd.md): any
// bytes through the parser, every decoder and the stream deframer.
// Asserts: no crash or out-of-bounds access (ASan); a parsed packet lies
// inside the input; a decoder writes its message only on success; and a
// packet that decodes re-encodes to exactly its own bytes (the encoding is
// canonical: one byte string per message), in the double build.  The same
// bytes also go through the configuration-image decoder (same contract).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fsw/fsw_link.h"
#include "fsw/fsw_link_sec.h"

namespace {

[[noreturn]] void violation(const char* what)
{
  std::fprintf(stderr, "fsw_link contract violation: %s\n", what);
  std::abort();
}

template <class T>
bool untouched(const T& v)
{
  const unsigned char* p = reinterpret_cast<const unsigned char*>(&v);
  for (size_t i = 0; i < sizeof v; ++i)
    if (p[i] != 0xA5) return false;
  return true;
}

void same_bytes(const uint8_t* a, size_t na, const std::vector<uint8_t>& b, size_t nb, const char* what)
{
  if (na != nb || std::memcmp(a, b.data(), na) != 0) violation(what);
}

void check_packet(const uint8_t* data, size_t size)
{
  FswLinkPacket p;
  FswLinkError e = FSW_LINK_OK;
  if (fsw_link_parse(data, size, &p, &e) != FSW_OK) {
    if (e == FSW_LINK_OK) violation("parse failed without a reason");
    return;
  }
  if (p.packet_len > size || p.payload < data || p.payload + p.payload_len > data + size)
    violation("parsed packet outside the input");
  std::vector<uint8_t> out(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  const bool exact = sizeof(fsw_real) == sizeof(double);
  {
    FswAcsSensorMsg m;
    std::memset(&m, 0xA5, sizeof m);
    uint8_t nrw = 0, ncss = 0;
    if (fsw_link_decode_sensor(&p, &m, &nrw, &ncss, &e) == FSW_OK) {
      if (fsw_link_encode_sensor(&m, nrw, ncss, p.seq, out.data(), out.size(), &len, nullptr) != FSW_OK)
        violation("a decoded sensor message does not encode");
      if (exact) same_bytes(data, p.packet_len, out, len, "sensor packet does not re-encode to its bytes");
    } else if (!untouched(m)) {
      violation("sensor decoder wrote on failure");
    }
  }
  {
    FswAcsCmdMsg m;
    std::memset(&m, 0xA5, sizeof m);
    if (fsw_link_decode_cmd(&p, &m, &e) == FSW_OK) {
      if (fsw_link_encode_cmd(&m, p.t_ns, p.seq, out.data(), out.size(), &len, nullptr) != FSW_OK)
        violation("a decoded command does not encode");
      if (exact) same_bytes(data, p.packet_len, out, len, "command packet does not re-encode to its bytes");
    } else if (!untouched(m)) {
      violation("command decoder wrote on failure");
    }
  }
  {
    FswAcsActuatorMsg m;
    std::memset(&m, 0xA5, sizeof m);
    uint8_t nrw = 0, nthr = 0, nmtq = 0;
    if (fsw_link_decode_actuator(&p, &m, &nrw, &nthr, &nmtq, &e) == FSW_OK) {
      if (fsw_link_encode_actuator(&m, nrw, nthr, nmtq, p.t_ns, p.seq, out.data(), out.size(), &len, nullptr) !=
          FSW_OK)
        violation("a decoded actuator message does not encode");
      if (exact) same_bytes(data, p.packet_len, out, len, "actuator packet does not re-encode to its bytes");
    } else if (!untouched(m)) {
      violation("actuator decoder wrote on failure");
    }
  }
  {
    FswAcsHealthMsg m;
    std::memset(&m, 0xA5, sizeof m);
    if (fsw_link_decode_health(&p, &m, &e) == FSW_OK) {
      if (fsw_link_encode_health(&m, p.t_ns, p.seq, out.data(), out.size(), &len, nullptr) != FSW_OK)
        violation("a decoded health message does not encode");
      if (exact) same_bytes(data, p.packet_len, out, len, "health packet does not re-encode to its bytes");
    } else if (!untouched(m)) {
      violation("health decoder wrote on failure");
    }
  }
  {
    FswLinkStatusMsg m;
    std::memset(&m, 0xA5, sizeof m);
    if (fsw_link_decode_status(&p, &m, &e) == FSW_OK) {
      if (fsw_link_encode_status(&m, p.t_ns, p.seq, out.data(), out.size(), &len, nullptr) != FSW_OK)
        violation("a decoded link status does not encode");
      same_bytes(data, p.packet_len, out, len, "link status packet does not re-encode to its bytes");
    } else if (!untouched(m)) {
      violation("link status decoder wrote on failure");
    }
  }
}

// The bytes as a configuration image: written only on success, and an image
// that decodes re-encodes to its own bytes (double build).
void check_config(const uint8_t* data, size_t size)
{
  static FswAcsConfig c;
  std::memset(&c, 0xA5, sizeof c);
  FswLinkError e = FSW_LINK_OK;
  if (fsw_link_config_decode(data, size, &c, &e) != FSW_OK) {
    if (!untouched(c)) violation("config decoder wrote on failure");
    return;
  }
  std::vector<uint8_t> out(fsw_link_config_size());
  size_t len = 0;
  if (fsw_link_config_encode(&c, out.data(), out.size(), &len, nullptr) != FSW_OK)
    violation("a decoded configuration does not encode");
  if (sizeof(fsw_real) == sizeof(double)) same_bytes(data, size, out, len, "config image does not re-encode");
}

}  // namespace

// fsw_link_sec_verify on arbitrary bytes: refused (auth or replay) without
// moving the window, or accepted with the packet length n - 20; a packet
// protected under the key verifies once and is a replay the second time.
static void check_sec(const uint8_t* data, size_t size)
{
  static const uint8_t key[32] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16,
                                  17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32};
  FswLinkSec s;
  if (fsw_link_sec_init(&s, key, sizeof key) != FSW_OK) violation("fsw_link_sec_init refused a 32-byte key");
  size_t plen = 0;
  FswLinkError e = FSW_LINK_OK;
  const FswStatus st = fsw_link_sec_verify(&s, data, size, &plen, &e);
  if (st == FSW_OK && plen + FSW_LINK_SEC_TRAILER_SIZE != size) violation("verify: wrong packet length");
  if (st != FSW_OK && (st != FSW_E_BAD_INPUT || (e != FSW_LINK_E_AUTH && e != FSW_LINK_E_REPLAY) || s.rx_high != 0))
    violation("verify: a refusal not as documented");
  if (size > 2048) return;
  std::vector<uint8_t> w(size + FSW_LINK_SEC_TRAILER_SIZE);
  size_t len = 0;
  FswLinkSec tx;
  (void)fsw_link_sec_init(&tx, key, sizeof key);
  (void)fsw_link_sec_init(&s, key, sizeof key);
  if (fsw_link_sec_protect(&tx, data, size, w.data(), w.size(), &len, nullptr) != FSW_OK || len != w.size())
    violation("protect failed with room");
  if (size + FSW_LINK_SEC_TRAILER_SIZE < FSW_LINK_SEC_TRAILER_SIZE + FSW_LINK_HEADER_SIZE + FSW_LINK_CRC_SIZE) return;
  if (fsw_link_sec_verify(&s, w.data(), w.size(), &plen, &e) != FSW_OK || plen != size)
    violation("a protected packet did not verify");
  if (fsw_link_sec_verify(&s, w.data(), w.size(), &plen, &e) != FSW_E_BAD_INPUT || e != FSW_LINK_E_REPLAY)
    violation("a replayed packet was not refused as a replay");
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  check_packet(data, size);
  check_sec(data, size);
  check_config(data, size);
  // the same bytes as a stream, in two pieces: every packet the deframer
  // delivers parses, and it never consumes more than it was given
  FswLinkDeframer d;
  fsw_link_deframer_init(&d);
  const size_t half = size / 2;
  for (int piece = 0; piece < 2; ++piece) {
    const uint8_t* at = data + (piece ? half : 0);
    size_t left = piece ? size - half : half;
    while (left > 0) {
      const uint8_t* pkt = nullptr;
      size_t pl = 0;
      const size_t used = fsw_link_deframer_push(&d, at, left, &pkt, &pl);
      if (used > left) violation("deframer consumed more than it was given");
      at += used;
      left -= used;
      if (pkt) {
        FswLinkPacket p;
        if (fsw_link_parse(pkt, pl, &p, nullptr) != FSW_OK || p.packet_len != pl)
          violation("deframer delivered a packet that does not parse");
        check_packet(pkt, pl);
      } else if (left > 0) {
        violation("deframer stopped with input left and no packet");
      }
    }
  }
  return 0;
}

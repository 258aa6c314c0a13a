// Encodes link packets of every APID with the flight codec (fsw_link_encode_*)
// for several counts and random field values, and prints one JSON object per
// packet: the bytes and the values the test put in, named as docs/icd.md
// names them (written here by hand from the message structs, not read from
// the packet table).  test/icd/test_icd_dictionary.py decodes the bytes with a
// decoder that reads only the generated dictionary and compares every field.
//
// Usage: icd_codec_dump SEED   (prints to stdout; exit 1 if an encoder fails)
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "fsw/fsw_link.h"

namespace {

std::mt19937_64 rng;

// A random finite binary64 of any sign and magnitude (random bits, the
// exponent kept below all-ones), sometimes a special value.
double any_double()
{
  switch (rng() % 8u) {
    case 0: return 0.0;
    case 1: return -0.0;
    case 2: return static_cast<double>(static_cast<int64_t>(rng() % 2001u) - 1000) / 7.0;
    default: break;
  }
  uint64_t b = rng();
  if (((b >> 52) & 0x7FFu) == 0x7FFu) b &= ~(uint64_t{1} << 62);
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
}

uint8_t flag() { return static_cast<uint8_t>(rng() & 1u); }

class Json {
 public:
  void num(const char* k, uint64_t v) { add(k, std::to_string(v)); }
  void inum(const char* k, int64_t v) { add(k, std::to_string(v)); }
  void real(const char* k, fsw_real x) { add(k, bits(x)); }
  void reals(const char* k, const fsw_real* x, size_t n)
  {
    std::string s = "[";
    for (size_t i = 0; i < n; ++i) s += (i ? "," : "") + bits(x[i]);
    add(k, s + "]");
  }
  template <typename T>
  void ints(const char* k, const T* x, size_t n)
  {
    std::string s = "[";
    for (size_t i = 0; i < n; ++i) s += (i ? "," : "") + std::to_string(static_cast<int64_t>(x[i]));
    add(k, s + "]");
  }
  std::string str() const { return "{" + body_ + "}"; }

 private:
  static std::string bits(fsw_real x)
  {
    const double d = static_cast<double>(x);  // what travels: binary64
    uint64_t b;
    std::memcpy(&b, &d, sizeof b);
    char buf[32];
    std::snprintf(buf, sizeof buf, "\"0x%016" PRIx64 "\"", b);
    return buf;
  }
  void add(const char* k, const std::string& v) { body_ += (body_.empty() ? "\"" : ",\"") + std::string(k) + "\":" + v; }
  std::string body_;
};

// The expected values of a packet start with its header's.
Json header(uint16_t seq, uint64_t t_ns)
{
  Json j;
  j.num("seq_count", seq % 16384u);
  j.num("t_ns", t_ns);
  return j;
}

void emit(const char* name, const uint8_t* buf, size_t len, const Json& j)
{
  std::string hex;
  char b[3];
  for (size_t i = 0; i < len; ++i) {
    std::snprintf(b, sizeof b, "%02x", buf[i]);
    hex += b;
  }
  std::printf("{\"packet\":\"%s\",\"hex\":\"%s\",\"fields\":%s}\n", name, hex.c_str(), j.str().c_str());
}

bool sensor(uint8_t nrw, uint8_t ncss, uint16_t seq)
{
  FswAcsSensorMsg m;
  std::memset(&m, 0, sizeof m);
  m.t_ns = rng();
  m.att_valid = flag();
  for (auto& x : m.sigma_BN) x = any_double();
  for (auto& x : m.omega_BN_B) x = any_double();
  for (auto& x : m.r_CoM_B) x = any_double();
  for (size_t i = 0; i < nrw; ++i) m.Omega[i] = any_double(), m.rw_avail[i] = flag();
  for (size_t i = 0; i < ncss; ++i) m.css[i] = any_double(), m.css_avail[i] = flag();
  uint64_t thr_bits = 0;
  for (size_t i = 0; i < FSW_MAX_THR; ++i) {
    m.thr_avail[i] = flag();
    if (m.thr_avail[i]) thr_bits |= uint64_t{1} << i;
  }
  for (auto& x : m.B_B) x = any_double();
  for (auto& x : m.r_N) x = any_double();
  for (auto& x : m.v_N) x = any_double();
  m.mag_valid = flag();
  m.orbit_valid = flag();
  uint8_t buf[FSW_LINK_MAX_PACKET];
  size_t len = 0;
  if (fsw_link_encode_sensor(&m, nrw, ncss, seq, buf, sizeof buf, &len, nullptr) != FSW_OK) return false;
  Json j = header(seq, m.t_ns);
  j.num("n_rw", nrw);
  j.num("n_css", ncss);
  j.num("att_valid", m.att_valid);
  j.num("reserved", 0);
  j.reals("sigma_BN", m.sigma_BN, 3);
  j.reals("omega_BN_B", m.omega_BN_B, 3);
  j.reals("r_CoM_B", m.r_CoM_B, 3);
  j.reals("Omega", m.Omega, nrw);
  j.ints("rw_avail", m.rw_avail, nrw);
  j.reals("css", m.css, ncss);
  j.ints("css_avail", m.css_avail, ncss);
  j.num("thr_avail", thr_bits);
  j.reals("B_B", m.B_B, 3);
  j.reals("r_N", m.r_N, 3);
  j.reals("v_N", m.v_N, 3);
  j.num("mag_valid", m.mag_valid);
  j.num("orbit_valid", m.orbit_valid);
  emit("sensor", buf, len, j);
  return true;
}

bool command(uint16_t seq)
{
  FswAcsCmdMsg m;
  std::memset(&m, 0, sizeof m);
  m.mode = static_cast<int>(rng() % 256u);
  m.actuation = static_cast<int>(rng() % 256u);
  m.set_ref = flag();
  m.set_gains = flag();
  for (auto& x : m.sigma_R0N) x = any_double();
  m.K = any_double();
  m.P = any_double();
  m.set_policy = flag();
  m.policy = static_cast<int>(rng() % 256u);
  const uint64_t t_ns = rng();
  uint8_t buf[FSW_LINK_MAX_PACKET];
  size_t len = 0;
  if (fsw_link_encode_cmd(&m, t_ns, seq, buf, sizeof buf, &len, nullptr) != FSW_OK) return false;
  Json j = header(seq, t_ns);
  j.num("mode", static_cast<uint64_t>(m.mode));
  j.num("actuation", static_cast<uint64_t>(m.actuation));
  j.num("set_ref", m.set_ref);
  j.num("set_gains", m.set_gains);
  j.reals("sigma_R0N", m.sigma_R0N, 3);
  j.real("K", m.K);
  j.real("P", m.P);
  j.num("set_policy", m.set_policy);
  j.num("policy", static_cast<uint64_t>(m.policy));
  emit("command", buf, len, j);
  return true;
}

bool actuator(uint8_t nrw, uint8_t nthr, uint8_t nmtq, uint16_t seq)
{
  FswAcsActuatorMsg m;
  std::memset(&m, 0, sizeof m);
  for (auto& x : m.Lr_B) x = any_double();
  for (size_t i = 0; i < nrw; ++i) m.u_s[i] = any_double(), m.V[i] = any_double();
  for (size_t i = 0; i < nthr; ++i) m.F[i] = any_double(), m.t_on[i] = any_double();
  for (size_t i = 0; i < nmtq; ++i) m.m_cmd[i] = any_double();
  m.wheels_active = flag();
  m.thrusters_active = flag();
  m.mtq_active = flag();
  const uint64_t t_ns = rng();
  uint8_t buf[FSW_LINK_MAX_PACKET];
  size_t len = 0;
  if (fsw_link_encode_actuator(&m, nrw, nthr, nmtq, t_ns, seq, buf, sizeof buf, &len, nullptr) != FSW_OK)
    return false;
  Json j = header(seq, t_ns);
  j.num("n_rw", nrw);
  j.num("n_thr", nthr);
  j.num("n_mtq", nmtq);
  j.num("wheels_active", m.wheels_active);
  j.num("thrusters_active", m.thrusters_active);
  j.num("mtq_active", m.mtq_active);
  j.num("reserved", 0);
  j.reals("Lr_B", m.Lr_B, 3);
  j.reals("u_s", m.u_s, nrw);
  j.reals("V", m.V, nrw);
  j.reals("F", m.F, nthr);
  j.reals("t_on", m.t_on, nthr);
  j.reals("m_cmd", m.m_cmd, nmtq);
  emit("actuator", buf, len, j);
  return true;
}

FswStatus any_status() { return static_cast<FswStatus>(static_cast<int>(rng() % 12u) - 8); }

bool health(uint16_t seq)
{
  FswAcsHealthMsg m;
  std::memset(&m, 0, sizeof m);
  m.status = any_status();
  m.mode = static_cast<int>(rng() % 256u);
  m.actuation = static_cast<int>(rng() % 256u);
  m.safe_output = flag();
  m.sun_valid = flag();
  m.num_lit = static_cast<uint8_t>(rng());
  m.cycles = static_cast<uint32_t>(rng());
  m.mode_changes = static_cast<uint32_t>(rng());
  for (auto& s : m.stage_status) s = any_status();
  for (auto& x : m.sigma_BR) x = any_double();
  for (auto& x : m.omega_BR_B) x = any_double();
  m.att_err_angle = any_double();
  m.sun_angle_err = any_double();
  for (auto& x : m.sun_hat_B) x = any_double();
  m.health.bad_input = static_cast<uint32_t>(rng());
  m.health.bad_time = static_cast<uint32_t>(rng());
  m.health.saturated = static_cast<uint32_t>(rng());
  m.health.singular = static_cast<uint32_t>(rng());
  m.health.rate = static_cast<uint32_t>(rng());
  m.health.other_error = static_cast<uint32_t>(rng());
  m.health.calls = static_cast<uint32_t>(rng());
  m.health.last = any_status();
  m.rw_failed = rng();
  m.rw_latched = rng();
  m.policy = static_cast<int>(rng() % 256u);
  m.detumbled = flag();
  m.dump_phase = static_cast<uint8_t>(rng());
  m.dumps = static_cast<uint32_t>(rng());
  for (auto& x : m.h_w_B) x = any_double();
  m.rate_est = any_double();
  for (auto& x : m.tau_mtq_B) x = any_double();
  m.prop_used = any_double();
  const uint64_t t_ns = rng();
  uint8_t buf[FSW_LINK_MAX_PACKET];
  size_t len = 0;
  if (fsw_link_encode_health(&m, t_ns, seq, buf, sizeof buf, &len, nullptr) != FSW_OK) return false;
  Json j = header(seq, t_ns);
  j.inum("status", m.status);
  j.num("mode", static_cast<uint64_t>(m.mode));
  j.num("actuation", static_cast<uint64_t>(m.actuation));
  j.num("safe_output", m.safe_output);
  j.num("sun_valid", m.sun_valid);
  j.num("num_lit", m.num_lit);
  j.num("num_stages", FSW_ACS_NUM_STAGES);
  j.num("cycles", m.cycles);
  j.num("mode_changes", m.mode_changes);
  j.ints("stage_status", m.stage_status, FSW_ACS_NUM_STAGES);
  j.reals("sigma_BR", m.sigma_BR, 3);
  j.reals("omega_BR_B", m.omega_BR_B, 3);
  j.real("att_err_angle", m.att_err_angle);
  j.real("sun_angle_err", m.sun_angle_err);
  j.reals("sun_hat_B", m.sun_hat_B, 3);
  j.num("bad_input", m.health.bad_input);
  j.num("bad_time", m.health.bad_time);
  j.num("saturated", m.health.saturated);
  j.num("singular", m.health.singular);
  j.num("rate", m.health.rate);
  j.num("other_error", m.health.other_error);
  j.num("calls", m.health.calls);
  j.inum("last", m.health.last);
  j.num("rw_failed", m.rw_failed);
  j.num("rw_latched", m.rw_latched);
  j.num("policy", static_cast<uint64_t>(m.policy));
  j.num("detumbled", m.detumbled);
  j.num("dump_phase", m.dump_phase);
  j.num("reserved", 0);
  j.num("dumps", m.dumps);
  j.reals("h_w_B", m.h_w_B, 3);
  j.real("rate_est", m.rate_est);
  j.reals("tau_mtq_B", m.tau_mtq_B, 3);
  j.real("prop_used", m.prop_used);
  emit("health", buf, len, j);
  return true;
}

bool link_status(uint16_t seq)
{
  FswLinkStatusMsg m;
  std::memset(&m, 0, sizeof m);
  uint32_t* c[] = {&m.rx_packets, &m.rx_crc,     &m.rx_rejected, &m.rx_stale, &m.missed,
                   &m.safe_entries, &m.safe_cycles, &m.recoveries, &m.cycles};
  for (uint32_t* p : c) *p = static_cast<uint32_t>(rng());
  m.last_seq = static_cast<uint16_t>(rng() % 16384u);
  m.link_safe = flag();
  const uint64_t t_ns = rng();
  uint8_t buf[FSW_LINK_MAX_PACKET];
  size_t len = 0;
  if (fsw_link_encode_status(&m, t_ns, seq, buf, sizeof buf, &len, nullptr) != FSW_OK) return false;
  Json j = header(seq, t_ns);
  j.num("rx_packets", m.rx_packets);
  j.num("rx_crc", m.rx_crc);
  j.num("rx_rejected", m.rx_rejected);
  j.num("rx_stale", m.rx_stale);
  j.num("missed", m.missed);
  j.num("safe_entries", m.safe_entries);
  j.num("safe_cycles", m.safe_cycles);
  j.num("recoveries", m.recoveries);
  j.num("cycles", m.cycles);
  j.num("last_seq", m.last_seq);
  j.num("link_safe", m.link_safe);
  j.num("icd_version", 2);
  emit("link_status", buf, len, j);
  return true;
}

}  // namespace

int main(int argc, char** argv)
{
  if (argc != 2) {
    std::fprintf(stderr, "usage: icd_codec_dump SEED\n");
    return 2;
  }
  rng.seed(std::strtoull(argv[1], nullptr, 10));
  bool ok = true;
  // counts: none, one, S1-like, odd, full capacity
  const uint8_t rw[] = {0, 1, 4, 3, FSW_MAX_RW};
  const uint8_t css[] = {0, 1, 8, 5, FSW_MAX_CSS};
  const uint8_t thr[] = {0, 1, 0, 8, FSW_MAX_THR};
  const uint8_t mtq[] = {0, 1, 0, 3, FSW_MAX_MTQ};
  for (int rep = 0; rep < 4; ++rep) {
    for (size_t k = 0; k < sizeof rw; ++k) {
      const uint16_t seq = static_cast<uint16_t>(rng() % 65536u);  // the encoder keeps it modulo 16384
      ok = sensor(rw[k], css[k], seq) && ok;
      ok = actuator(rw[k], thr[k], mtq[k], seq) && ok;
    }
    ok = command(static_cast<uint16_t>(rng() % 16384u)) && ok;
    ok = health(static_cast<uint16_t>(rng() % 16384u)) && ok;
    ok = link_status(static_cast<uint16_t>(rng() % 16384u)) && ok;
  }
  if (!ok) std::fprintf(stderr, "icd_codec_dump: an encoder refused a packet\n");
  return ok ? 0 : 1;
}

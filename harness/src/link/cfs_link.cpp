#include "harness/link/cfs_link.h"

#include "icd/generated/kestrel_icd.h" // the packet table's constants (icd/packets.yaml, tools/icd_gen.py)

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace harness {

namespace {

using Clock = std::chrono::steady_clock;

// cFS message ids (cFS v1 message id = the CCSDS stream id, the first two
// bytes of a message) and header sizes: KESTREL_ACS's from the packet table,
// to_lab's from its own build.
constexpr uint16_t kCfsAcsLinkMid = KESTREL_ICD_CFS_LINK_MID;
constexpr uint16_t kCfsAcsSendHkMid = KESTREL_ICD_CFS_SEND_HK_MID;
constexpr uint16_t kCfsAcsHkMid = KESTREL_ICD_CFS_HK_TLM_MID;
constexpr uint16_t kCfsAcsActuatorMid = KESTREL_ICD_CFS_ACTUATOR_TLM_MID;
constexpr uint16_t kCfsAcsHealthMid = KESTREL_ICD_CFS_HEALTH_TLM_MID;
constexpr size_t kCfsCmdHeader = KESTREL_ICD_CFS_CMD_HEADER_SIZE;
constexpr size_t kCfsTlmHeader = KESTREL_ICD_CFS_TLM_HEADER_SIZE;
constexpr uint16_t kCfsToLabCmdMid = 0x1880; // to_lab's commands
constexpr uint8_t kCfsToLabAddPktCc = 2;
constexpr uint8_t kCfsToLabOutputEnableCc = 6;

uint16_t be16(const uint8_t* p) { return static_cast<uint16_t>(p[0] << 8 | p[1]); }
uint32_t be32(const uint8_t* p)
{
  return static_cast<uint32_t>(p[0]) << 24 | static_cast<uint32_t>(p[1]) << 16 | static_cast<uint32_t>(p[2]) << 8 |
         p[3];
}

// The stream id of a whole cFS message (its CCSDS length agrees with n);
// 0 when it is not one.
uint16_t cfs_mid(const uint8_t* msg, size_t n)
{
  if (n < kCfsTlmHeader || static_cast<size_t>(be16(msg + 4)) + 7u != n) return 0;
  return be16(msg);
}

struct CfsSpec {
  std::string host;
  int port = 1234, tlm_port = 1235;
};

int parse_port(const std::string& s, const std::string& spec)
{
  char* end = nullptr;
  const long v = s.empty() ? -1 : std::strtol(s.c_str(), &end, 10);
  if (v < 1 || v > 65535 || *end != '\0')
    throw FswEndpointError("FSW link: bad cFS address 'cfs:" + spec +
                           "' (expected cfs:HOST[:PORT[:TLMPORT]], ports in 1..65535)");
  return static_cast<int>(v);
}

CfsSpec parse_cfs_spec(const std::string& spec)
{
  CfsSpec c;
  const size_t a = spec.find(':');
  c.host = spec.substr(0, a);
  in_addr ip{};
  if (inet_pton(AF_INET, c.host.c_str(), &ip) != 1)
    throw FswEndpointError("FSW link: bad cFS address 'cfs:" + spec +
                           "' (expected cfs:HOST[:PORT[:TLMPORT]] with an IPv4 HOST, e.g. cfs:127.0.0.1:1234)");
  if (a == std::string::npos) return c;  // the lab apps' ports
  const size_t b = spec.find(':', a + 1);
  c.port = parse_port(spec.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1), spec);
  if (b != std::string::npos) c.tlm_port = parse_port(spec.substr(b + 1), spec);
  return c;
}

// This machine's IPv4 address on the route to host:port (127.0.0.1 for the
// loopback): where to_lab is told to send its telemetry.
std::string local_address_towards(const CfsSpec& c)
{
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(c.port));
  inet_pton(AF_INET, c.host.c_str(), &to.sin_addr);
  sockaddr_in me{};
  socklen_t len = sizeof me;
  char text[INET_ADDRSTRLEN] = "";
  const bool ok = fd >= 0 && connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) == 0 &&
                  getsockname(fd, reinterpret_cast<sockaddr*>(&me), &len) == 0 &&
                  inet_ntop(AF_INET, &me.sin_addr, text, sizeof text) != nullptr;
  if (fd >= 0) close(fd);
  if (!ok) throw FswEndpointError("FSW link: no route to the cFS host " + c.host);
  return text;
}

// The transport: ICD packets out as 0x18F1 commands to ci_lab, ICD packets
// in from to_lab's 0x08F1/0x08F2 telemetry (cfs_link.h).
class CfsTransport : public LinkTransport {
 public:
  CfsTransport(const CfsSpec& c, const std::string& me)
      : up_(open_link_transport("udp:" + c.host + ":" + std::to_string(c.port))),
        down_(bind_udp_transport(me + ":" + std::to_string(c.tlm_port))),
        me_(me),
        tlm_port_(c.tlm_port),
        desc_("cfs: ci_lab at " + c.host + ":" + std::to_string(c.port) + ", to_lab to " + me + ":" +
              std::to_string(c.tlm_port))
  {
  }
  std::string describe() const override { return desc_; }
  bool sends_link_status() const override { return false; }
  // Every 64th packet also asks for the application's housekeeping (kept
  // for fsw_health.txt; it changes nothing in the FSW).
  void send(const uint8_t* p, size_t n) override
  {
    command(kCfsAcsLinkMid, 0, p, n);
    if (++sent_ % 64u == 0) command(kCfsAcsSendHkMid, 0, nullptr, 0);
  }
  bool recv(std::vector<uint8_t>& pkt, double timeout_s) override;
  std::string diagnose() const override;
  std::string far_end_status() const override;
  void start(double timeout_s);

 private:
  void command(uint16_t mid, uint8_t cc, const uint8_t* payload, size_t n)
  {
    const std::vector<uint8_t> m = cfs_command(mid, cc, seq_, payload, n);
    seq_ = static_cast<uint16_t>((seq_ + 1u) & 0x3FFFu);
    up_->send(m.data(), m.size());
  }
  void enable_output();
  // One datagram from to_lab: true (and the ICD packet in pkt) for the
  // application's actuator or health message.
  bool classify(std::vector<uint8_t>& pkt);

  std::unique_ptr<LinkTransport> up_, down_;
  std::string me_;
  int tlm_port_;
  std::string desc_;
  uint16_t seq_ = 0;
  std::vector<uint8_t> rx_;
  CfsAcsHk hk_;
  uint64_t datagrams_ = 0, hk_count_ = 0, other_ = 0, sent_ = 0;
};

std::string hk_text(const CfsAcsHk& hk)
{
  return "commands=" + std::to_string(hk.command_count) + " command_errors=" + std::to_string(hk.command_error_count) +
         " mode=" + std::to_string(hk.mode) + " config_loaded=" + std::to_string(hk.config_loaded) +
         " cycles=" + std::to_string(hk.cycles) + " cycle_errors=" + std::to_string(hk.cycle_errors) +
         " link_rejected=" + std::to_string(hk.link_rejected) + " last_status=" + std::to_string(hk.last_status) +
         " table_rejects=" + std::to_string(hk.table_rejects);
}

void CfsTransport::enable_output()
{
  std::array<uint8_t, 16> ip{};  // TO_LAB_EnableOutput_Payload_t: char dest_IP[16]
  std::memcpy(ip.data(), me_.data(), std::min(me_.size(), ip.size() - 1));
  command(kCfsToLabCmdMid, kCfsToLabOutputEnableCc, ip.data(), ip.size());
  for (uint16_t mid = kCfsAcsHkMid; mid <= kCfsAcsHealthMid; ++mid) {
    // TO_LAB_AddPacket_Payload_t in the target's byte order (little-endian
    // here): CFE_SB_MsgId_t (u32), CFE_SB_Qos_t (2 x u8), u8 BufLimit, pad
    const std::array<uint8_t, 8> add{static_cast<uint8_t>(mid & 0xFFu), static_cast<uint8_t>(mid >> 8), 0, 0, 0, 0, 4,
                                     0};
    command(kCfsToLabCmdMid, kCfsToLabAddPktCc, add.data(), add.size());
  }
}

bool CfsTransport::classify(std::vector<uint8_t>& pkt)
{
  ++datagrams_;
  const uint16_t mid = cfs_mid(rx_.data(), rx_.size());
  if (mid == kCfsAcsHkMid && cfs_decode_hk(rx_.data(), rx_.size(), hk_)) {
    ++hk_count_;
    return false;
  }
  if (mid != kCfsAcsActuatorMid && mid != kCfsAcsHealthMid) {
    ++other_;
    return false;
  }
  // the ICD packet, as long as its own CCSDS header says (else the rest:
  // the parser refuses it and the link counts it)
  const uint8_t* inner = rx_.data() + kCfsTlmHeader;
  const size_t avail = rx_.size() - kCfsTlmHeader;
  const size_t len = avail >= 6 ? std::min<size_t>(avail, static_cast<size_t>(be16(inner + 4)) + 7u) : avail;
  pkt.assign(inner, inner + len);
  return true;
}

bool CfsTransport::recv(std::vector<uint8_t>& pkt, double timeout_s)
{
  const auto end = Clock::now() + std::chrono::duration<double>(std::max(0.0, timeout_s));
  for (;;) {
    const double left = std::chrono::duration<double>(end - Clock::now()).count();
    if (!down_->recv(rx_, std::max(0.0, left))) return false;
    if (classify(pkt)) return true;
  }
}

std::string CfsTransport::diagnose() const
{
  std::string s = "to_lab sent " + std::to_string(datagrams_) + " datagrams to port " + std::to_string(tlm_port_) +
                  ", " + std::to_string(hk_count_) + " of them KESTREL_ACS housekeeping";
  if (hk_count_ > 0) s += " (the last: " + hk_text(hk_) + ")";
  return s + "; is core-cpu1 still running with KESTREL_ACS and the same configuration table?";
}

std::string CfsTransport::far_end_status() const
{
  return "KESTREL_ACS in cFS, no link status packets; its housekeeping when last received: " + hk_text(hk_) +
         "; to_lab datagrams: " + std::to_string(datagrams_) + " received, " +
         std::to_string(datagrams_ - hk_count_ - other_) + " passed on (actuator, health), " +
         std::to_string(other_) + " others dropped";
}

// Enables to_lab's output (again every 2 s until to_lab is heard: a command
// sent before ci_lab listened is lost) and asks for KESTREL_ACS's
// housekeeping every 0.5 s until it comes.
void CfsTransport::start(double timeout_s)
{
  const auto t0 = Clock::now();
  const auto end = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  auto next_enable = t0, next_hk = t0;
  std::vector<uint8_t> ignored;
  for (;;) {
    const auto now = Clock::now();
    if (datagrams_ == 0 && now >= next_enable) {
      enable_output();
      next_enable = now + std::chrono::seconds(2);
    }
    if (now >= next_hk) {
      command(kCfsAcsSendHkMid, 0, nullptr, 0);
      next_hk = now + std::chrono::milliseconds(500);
    }
    if (now >= end) break;
    const auto until = std::min({end, next_hk, datagrams_ == 0 ? next_enable : end});
    if (!down_->recv(rx_, std::chrono::duration<double>(until - now).count())) continue;
    classify(ignored);
    if (hk_count_ == 0) continue;
    if (!hk_.config_loaded)
      throw FswEndpointError("FSW link: KESTREL_ACS runs without a valid configuration table (" +
                             std::to_string(hk_.table_rejects) +
                             " table loads refused: see core-cpu1's events for the field)");
    return;
  }
  const std::string n = std::to_string(tlm_port_);
  if (datagrams_ == 0)
    throw FswEndpointError("FSW link: no telemetry from to_lab on port " + n +
                           ": is core-cpu1 running with KESTREL_ACS and to_lab? (" + desc_ + ")");
  throw FswEndpointError("FSW link: to_lab sends to port " + n + " but KESTREL_ACS sent no housekeeping (0x08F0) within " +
                         std::to_string(timeout_s) + " s: is KESTREL_ACS in core-cpu1's startup script? (" + desc_ +
                         ")");
}

}  // namespace

std::vector<uint8_t> cfs_command(uint16_t mid, uint8_t cc, uint16_t seq, const uint8_t* payload, size_t n)
{
  std::vector<uint8_t> m(kCfsCmdHeader + n);
  const size_t len = m.size() - 7u;  // CCSDS: total length - 7
  const uint16_t sq = static_cast<uint16_t>(0xC000u | (seq & 0x3FFFu));
  m[0] = static_cast<uint8_t>(mid >> 8);
  m[1] = static_cast<uint8_t>(mid);
  m[2] = static_cast<uint8_t>(sq >> 8);
  m[3] = static_cast<uint8_t>(sq);
  m[4] = static_cast<uint8_t>(len >> 8);
  m[5] = static_cast<uint8_t>(len);
  m[6] = static_cast<uint8_t>(cc & 0x7Fu);
  if (n > 0) std::memcpy(m.data() + kCfsCmdHeader, payload, n);
  uint8_t x = 0xFF;
  for (const uint8_t b : m) x = static_cast<uint8_t>(x ^ b);
  m[7] = x;  // with it, the XOR of all bytes and 0xFF is 0
  return m;
}

bool cfs_decode_hk(const uint8_t* msg, size_t n, CfsAcsHk& hk)
{
  if (cfs_mid(msg, n) != kCfsAcsHkMid || n < kCfsTlmHeader + 24u) return false;
  const uint8_t* p = msg + kCfsTlmHeader;
  hk.command_count = p[0];
  hk.command_error_count = p[1];
  hk.mode = p[2];
  hk.config_loaded = p[3];
  hk.cycles = be32(p + 4);
  hk.cycle_errors = be32(p + 8);
  hk.link_rejected = be32(p + 12);
  hk.last_status = be32(p + 16);
  hk.table_rejects = be32(p + 20);
  return true;
}

std::unique_ptr<LinkTransport> open_cfs_transport(const std::string& spec, double timeout_s)
{
  const CfsSpec c = parse_cfs_spec(spec);
  auto t = std::make_unique<CfsTransport>(c, local_address_towards(c));
  t->start(timeout_s);
  return t;
}

}  // namespace harness

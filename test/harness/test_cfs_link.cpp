// The FSW link's cFS profile (harness/src/link/cfs_link.cpp, docs/hwil.md
// "cFS") against a stand-in for cFS written here: one UDP socket plays
// ci_lab (it checks every command's header and checksum by cFE's rule and
// records to_lab's commands), the FSW runs in process behind it, and its
// replies go out as to_lab telemetry (16-byte header) to the harness's port,
// with other telemetry in between.  No cFS needed: the closed loop through a
// real core-cpu1 is harness_cfs_closed_loop (cfs_closed_loop_test.py).
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "harness/core/fsw_endpoint.h"
#include "harness/core/run.h"
#include "harness/link/cfs_link.h"
#include "harness/scenario/scenario.h"

namespace {

const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

uint16_t be16(const uint8_t* p) { return static_cast<uint16_t>(p[0] << 8 | p[1]); }

int udp_socket(uint16_t port, uint16_t* bound)
{
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  *bound = ntohs(a.sin_port);
  return fd;
}

// A free UDP port on the loopback (bound, read, released).
uint16_t free_port()
{
  uint16_t p = 0;
  close(udp_socket(0, &p));
  return p;
}

// ci_lab + KESTREL_ACS + to_lab, in one thread.
class FakeCfs {
 public:
  FakeCfs(const FswAcsConfig& cfg, uint8_t config_loaded, uint16_t tlm_port)
      : fsw_(cfg), config_loaded_(config_loaded), tlm_port_(tlm_port)
  {
    fd_ = udp_socket(0, &port_);
    th_ = std::thread([this] { serve(); });
  }
  ~FakeCfs()
  {
    stop_ = true;
    th_.join();
    close(fd_);
  }
  uint16_t port() const { return port_; }
  std::string dest_ip;               // from OUTPUT_ENABLE
  std::vector<uint32_t> added;       // ADD_PKT message ids
  std::atomic<int> bad_commands{0};  // header or checksum wrong
  std::atomic<int> cycles{0};
  std::atomic<int> hk_requests{0};

 private:
  void tlm(uint16_t mid, const uint8_t* payload, size_t n)
  {
    if (dest_ip.empty()) return;  // to_lab sends nothing before it is enabled
    std::vector<uint8_t> m(16 + n, 0);
    m[0] = static_cast<uint8_t>(mid >> 8);
    m[1] = static_cast<uint8_t>(mid);
    m[2] = 0xC0;
    m[4] = static_cast<uint8_t>((m.size() - 7) >> 8);
    m[5] = static_cast<uint8_t>(m.size() - 7);
    std::memcpy(m.data() + 16, payload, n);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(tlm_port_);
    inet_pton(AF_INET, dest_ip.c_str(), &to.sin_addr);
    sendto(fd_, m.data(), m.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  }
  void link_packet(const uint8_t* p, size_t n)
  {
    FswLinkPacket pkt;
    ASSERT_EQ(fsw_link_parse(p, n, &pkt, nullptr), FSW_OK);
    if (pkt.apid == FSW_LINK_APID_CMD) {
      FswAcsCmdMsg c;
      ASSERT_EQ(fsw_link_decode_cmd(&pkt, &c, nullptr), FSW_OK);
      fsw_.command(c);
      return;
    }
    FswAcsSensorMsg in;
    uint8_t nrw = 0, ncss = 0;
    ASSERT_EQ(fsw_link_decode_sensor(&pkt, &in, &nrw, &ncss, nullptr), FSW_OK);
    FswAcsActuatorMsg out{};
    FswAcsHealthMsg h{};
    fsw_.cycle(in, out, h);
    std::vector<uint8_t> buf(FSW_LINK_MAX_PACKET);
    size_t len = 0;
    const uint8_t hk_other[24] = {};
    tlm(0x0800, hk_other, sizeof hk_other);  // another app's housekeeping in between: dropped
    ASSERT_EQ(fsw_link_encode_actuator(&out, FSW_MAX_RW, FSW_MAX_THR, FSW_MAX_MTQ, pkt.t_ns, seq_, buf.data(),
                                       buf.size(), &len, nullptr),
              FSW_OK);
    tlm(0x08F1, buf.data(), len);
    ASSERT_EQ(fsw_link_encode_health(&h, pkt.t_ns, seq_, buf.data(), buf.size(), &len, nullptr), FSW_OK);
    ++seq_;
    ++cycles;  // before the cycle's last reply leaves: the run may end, and the test read it, at once
    tlm(0x08F2, buf.data(), len);
  }
  void command(const uint8_t* m, size_t n)
  {
    uint8_t x = 0xFF;  // CFE_MSG_ValidateChecksum: 0xFF XOR every byte is 0
    for (size_t i = 0; i < n; ++i) x = static_cast<uint8_t>(x ^ m[i]);
    if (n < 8 || be16(m + 4) + 7u != n || (be16(m + 2) & 0xC000u) != 0xC000u || x != 0) {
      ++bad_commands;
      return;
    }
    const uint16_t mid = be16(m);
    const uint8_t cc = m[6];
    if (mid == 0x1880 && cc == 6 && n == 8 + 16) dest_ip.assign(reinterpret_cast<const char*>(m + 8));
    if (mid == 0x1880 && cc == 2 && n == 8 + 8)
      added.push_back(static_cast<uint32_t>(m[8] | m[9] << 8 | m[10] << 16 | m[11] << 24));  // little-endian
    if (mid == 0x18F2 && n == 8) {
      ++hk_requests;
      uint8_t hk[24] = {0, 0, 0, config_loaded_};
      hk[23] = config_loaded_ ? 0 : 1;  // table_rejects
      tlm(0x08F0, hk, sizeof hk);
    }
    if (mid == 0x18F1 && cc == 0) link_packet(m + 8, n - 8);
  }
  void serve()
  {
    std::vector<uint8_t> rx(65536);
    while (!stop_) {
      pollfd p{fd_, POLLIN, 0};
      if (poll(&p, 1, 20) <= 0) continue;
      const ssize_t n = recv(fd_, rx.data(), rx.size(), 0);
      if (n > 0) command(rx.data(), static_cast<size_t>(n));
    }
  }

  harness::InProcessFsw fsw_;
  uint8_t config_loaded_;
  uint16_t tlm_port_, port_ = 0;
  uint16_t seq_ = 0;
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  std::thread th_;
};

uint64_t bits(double x)
{
  uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

std::string spec(uint16_t ci, uint16_t tlm) { return "127.0.0.1:" + std::to_string(ci) + ":" + std::to_string(tlm); }

// The command header, byte by byte (CCSDS primary header: version 0, type
// 1, secondary header 1, APID 0x0F1; sequence flags 3; length = total - 7;
// then function code and checksum).
TEST(CfsLink, CommandHeaderAndChecksum)
{
  const uint8_t pay[3] = {0x01, 0x02, 0x80};
  const std::vector<uint8_t> m = harness::cfs_command(0x18F1, 5, 0x4003, pay, sizeof pay);
  ASSERT_EQ(m.size(), 11u);
  EXPECT_EQ(m[0], 0x18);
  EXPECT_EQ(m[1], 0xF1);
  EXPECT_EQ(m[2], 0xC0);  // sequence count 0x4003 wraps to its 14 bits: 3
  EXPECT_EQ(m[3], 0x03);
  EXPECT_EQ(m[4], 0x00);
  EXPECT_EQ(m[5], 4);
  EXPECT_EQ(m[6], 5);
  // by hand: FF^18 = E7, ^F1 = 16, ^C0 = D6, ^03 = D5, ^00, ^04 = D1, ^05 = D4,
  // ^01 = D5, ^02 = D7, ^80 = 57; cFE validates it as 0xFF XOR every byte = 0
  EXPECT_EQ(m[7], 0x57);
  uint8_t x = 0xFF;
  for (const uint8_t b : m) x = static_cast<uint8_t>(x ^ b);
  EXPECT_EQ(x, 0);
  const std::vector<uint8_t> hk = harness::cfs_command(0x18F2, 0, 0, nullptr, 0);
  EXPECT_EQ(hk.size(), 8u);
  EXPECT_EQ(hk[5], 1);
}

TEST(CfsLink, HousekeepingDecodes)
{
  std::vector<uint8_t> m(16 + 24, 0);
  m[0] = 0x08;
  m[1] = 0xF0;
  m[5] = static_cast<uint8_t>(m.size() - 7);
  const uint8_t pay[24] = {3, 1, 2, 1, 0, 0, 1, 0, 0, 0, 0, 7, 0, 0, 0, 9, 0xFF, 0xFF, 0xFF, 0xFE, 0, 0, 0, 2};
  std::memcpy(m.data() + 16, pay, sizeof pay);
  harness::CfsAcsHk hk;
  ASSERT_TRUE(harness::cfs_decode_hk(m.data(), m.size(), hk));
  EXPECT_EQ(hk.command_count, 3);
  EXPECT_EQ(hk.command_error_count, 1);
  EXPECT_EQ(hk.mode, 2);
  EXPECT_EQ(hk.config_loaded, 1);
  EXPECT_EQ(hk.cycles, 256u);
  EXPECT_EQ(hk.cycle_errors, 7u);
  EXPECT_EQ(hk.link_rejected, 9u);
  EXPECT_EQ(hk.last_status, 0xFFFFFFFEu);
  EXPECT_EQ(hk.table_rejects, 2u);
  m[1] = 0xF1;  // another message id
  EXPECT_FALSE(harness::cfs_decode_hk(m.data(), m.size(), hk));
  m[1] = 0xF0;
  EXPECT_FALSE(harness::cfs_decode_hk(m.data(), m.size() - 1, hk));  // length disagrees with the header
}

// S1 for 20 s through the stand-in equals the in-process run in every
// telemetry column; to_lab was enabled towards 127.0.0.1 and subscribed to
// 0x08F0..0x08F2; every command passed cFE's checks.
TEST(CfsLink, LockstepS1EqualsInProcess)
{
  harness::Scenario sc = harness::load_scenario(kS1, {{"duration", "20"}});
  harness::Run local(sc);
  ASSERT_TRUE(local.step_ticks(local.total_ticks())) << local.failure();
  const uint16_t tlm = free_port();
  FakeCfs cfs(harness::fsw_acs_config_of(sc), 1, tlm);
  harness::LinkOptions lo;
  lo.timeout_s = 30.0;
  harness::RunConfig cfg;
  auto t = harness::open_cfs_transport(spec(cfs.port(), tlm), 30.0);
  const int start_requests = cfs.hk_requests;  // at link start: until one is answered
  EXPECT_GE(start_requests, 1);
  auto r = std::make_unique<harness::RemoteFsw>(std::move(t), harness::fsw_acs_config_of(sc), lo);
  harness::RemoteFsw* link = r.get();
  cfg.fsw = std::move(r);
  harness::Run linked(sc, std::move(cfg));
  ASSERT_TRUE(linked.step_ticks(linked.total_ticks())) << linked.failure();
  const harness::MemorySink &a = local.memory(), &b = linked.memory();
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.num_columns(), b.num_columns());
  size_t differing = 0;
  for (uint64_t row = 0; row < a.rows(); ++row)
    for (size_t c = 0; c < a.num_columns(); ++c)
      if (bits(a.at(row, c)) != bits(b.at(row, c))) ++differing;
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(link->counters().cycles, 201u);
  EXPECT_EQ(link->counters().replies, 201u);
  EXPECT_EQ(link->counters().rejected + link->counters().stale + link->counters().missing, 0u);
  EXPECT_EQ(cfs.cycles, 201);
  EXPECT_EQ(cfs.bad_commands, 0);
  // with packets 64, 128 and 192 (one more when a start-up request was still
  // on its way as the first answer came: a stalled machine)
  EXPECT_GE(cfs.hk_requests - start_requests, 3);
  EXPECT_LE(cfs.hk_requests - start_requests, 4);
  EXPECT_EQ(cfs.dest_ip, "127.0.0.1");
  EXPECT_EQ(cfs.added, (std::vector<uint32_t>{0x08F0, 0x08F1, 0x08F2}));
  const std::vector<std::string> lines = link->module_health_lines();
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[1].find("config_loaded=1"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("402 passed on (actuator, health), 201 others dropped"), std::string::npos) << lines[1];
}

std::string start_error(const std::string& s, double timeout)
{
  try {
    harness::open_cfs_transport(s, timeout);
  } catch (const harness::FswEndpointError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(CfsLink, NothingListeningSaysSo)
{
  const uint16_t tlm = free_port();
  const std::string e = start_error(spec(free_port(), tlm), 0.6);
  EXPECT_NE(e.find("no telemetry from to_lab on port " + std::to_string(tlm) +
                   ": is core-cpu1 running with KESTREL_ACS and to_lab?"),
            std::string::npos)
      << e;
}

TEST(CfsLink, ApplicationWithoutTableIsRefused)
{
  harness::Scenario sc = harness::load_scenario(kS1, {});
  const uint16_t tlm = free_port();
  FakeCfs cfs(harness::fsw_acs_config_of(sc), 0, tlm);
  const std::string e = start_error(spec(cfs.port(), tlm), 10.0);
  EXPECT_NE(e.find("KESTREL_ACS runs without a valid configuration table (1 table loads refused"), std::string::npos)
      << e;
}

TEST(CfsLink, BadAddressesAreRefused)
{
  for (const char* s : {"localhost:1234", "127.0.0.1:", "127.0.0.1:0", "127.0.0.1:1234:70000", "127.0.0.1:12x"}) {
    const std::string e = start_error(s, 0.1);
    EXPECT_NE(e.find("bad cFS address 'cfs:" + std::string(s) + "'"), std::string::npos) << e;
  }
}

}  // namespace

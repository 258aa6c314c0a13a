#include "harness/link/remote_fsw.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>

namespace harness {

namespace {

using Clock = std::chrono::steady_clock;

std::string errno_text() { return std::strerror(errno); }

// Splits "A:B" at the last colon.
bool split_last(const std::string& s, std::string& a, std::string& b)
{
  const auto c = s.rfind(':');
  if (c == std::string::npos || c == 0 || c + 1 == s.size()) return false;
  a = s.substr(0, c);
  b = s.substr(c + 1);
  return true;
}

// Waits for fd to be readable for at most timeout_s; false on timeout.
bool wait_readable(int fd, double timeout_s)
{
  const auto end = Clock::now() + std::chrono::duration<double>(std::max(0.0, timeout_s));
  for (;;) {
    const double left = std::chrono::duration<double>(end - Clock::now()).count();
    pollfd p{fd, POLLIN, 0};
    const int ms = left <= 0 ? 0 : static_cast<int>(left * 1000.0) + 1;
    const int rc = ::poll(&p, 1, ms);
    if (rc > 0) return true;
    if (rc == 0) return false;
    if (errno != EINTR) throw FswEndpointError("FSW link: poll failed: " + errno_text());
  }
}

class UdpTransport : public LinkTransport {
 public:
  explicit UdpTransport(const std::string& spec)
  {
    std::string host, port;
    if (!split_last(spec, host, port))
      throw FswEndpointError("FSW link: bad UDP address '" + spec + "' (expected udp:HOST:PORT)");
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    hints.ai_flags = AI_NUMERICSERV;
    addrinfo* res = nullptr;
    const int rc = ::getaddrinfo(host.c_str(), port.c_str(), &hints, &res);
    if (rc != 0) throw FswEndpointError("FSW link: cannot resolve '" + spec + "': " + ::gai_strerror(rc));
    fd_ = ::socket(res->ai_family, SOCK_DGRAM, 0);
    if (fd_ < 0 || ::connect(fd_, res->ai_addr, res->ai_addrlen) != 0) {
      const std::string why = errno_text();
      ::freeaddrinfo(res);
      if (fd_ >= 0) ::close(fd_);
      throw FswEndpointError("FSW link: cannot open UDP to " + spec + ": " + why);
    }
    ::freeaddrinfo(res);
    desc_ = "udp " + spec;
  }
  ~UdpTransport() override { ::close(fd_); }
  std::string describe() const override { return desc_; }
  void send(const uint8_t* p, size_t n) override
  {
    // a refused datagram (no process on the port yet) is a lost packet
    (void)::send(fd_, p, n, 0);
  }
  bool recv(std::vector<uint8_t>& pkt, double timeout_s) override
  {
    for (;;) {
      if (!wait_readable(fd_, timeout_s)) return false;
      pkt.resize(65536);
      const ssize_t n = ::recv(fd_, pkt.data(), pkt.size(), 0);
      if (n >= 0) {
        pkt.resize(static_cast<size_t>(n));
        return true;
      }
      if (errno != EINTR && errno != ECONNREFUSED) throw FswEndpointError("FSW link: receive failed: " + errno_text());
      timeout_s = 0.0;  // ICMP refusal seen: look once more, then report a timeout
    }
  }

 private:
  int fd_ = -1;
  std::string desc_;
};

speed_t baud_of(long b)
{
  switch (b) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return 0;
  }
}

// A byte stream (serial line, socket): packets framed by the attached sync
// marker, deframed by the flight code's FswLinkDeframer.  Owns fd.
class StreamTransport : public LinkTransport {
 public:
  StreamTransport(int fd, std::string desc) : fd_(fd), desc_(std::move(desc))
  {
    int type = 0;
    socklen_t tl = sizeof type;
    socket_ = ::getsockopt(fd_, SOL_SOCKET, SO_TYPE, &type, &tl) == 0;
    fsw_link_deframer_init(&d_);
  }
  ~StreamTransport() override { ::close(fd_); }
  std::string describe() const override { return desc_; }
  void send(const uint8_t* p, size_t n) override
  {
    std::vector<uint8_t> f(n + FSW_LINK_ASM_SIZE);
    size_t len = 0;
    if (fsw_link_frame(p, n, f.data(), f.size(), &len) != FSW_OK) return;
    size_t done = 0;
    while (done < len) {
      // a socket whose peer has gone must not raise SIGPIPE
      const ssize_t w = socket_ ? ::send(fd_, f.data() + done, len - done, MSG_NOSIGNAL)
                                : ::write(fd_, f.data() + done, len - done);
      if (w < 0) {
        if (errno == EINTR || errno == EAGAIN) continue;
        throw FswEndpointError("FSW link: write failed: " + errno_text());
      }
      done += static_cast<size_t>(w);
    }
  }
  bool recv(std::vector<uint8_t>& pkt, double timeout_s) override
  {
    const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      while (used_ < have_) {
        const uint8_t* p = nullptr;
        size_t plen = 0;
        used_ += fsw_link_deframer_push(&d_, buf_ + used_, have_ - used_, &p, &plen);
        if (p != nullptr) {
          pkt.assign(p, p + plen);
          return true;
        }
      }
      const double left = std::chrono::duration<double>(end - Clock::now()).count();
      if (!wait_readable(fd_, left)) return false;
      const ssize_t n = ::read(fd_, buf_, sizeof buf_);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw FswEndpointError("FSW link: the " + std::string(socket_ ? "socket" : "serial line") + " closed");
      have_ = static_cast<size_t>(n);
      used_ = 0;
    }
  }

 private:
  int fd_ = -1;
  bool socket_ = false;
  std::string desc_;
  FswLinkDeframer d_;
  uint8_t buf_[4096];
  size_t have_ = 0, used_ = 0;
};

// A serial line: a terminal set raw at the given baud rate.
int open_serial_line(const std::string& spec, std::string& desc)
{
  std::string dev, baud;
  if (!split_last(spec, dev, baud))
    throw FswEndpointError("FSW link: bad serial line '" + spec + "' (expected serial:DEVICE:BAUD)");
  char* end = nullptr;
  const long b = std::strtol(baud.c_str(), &end, 10);
  const speed_t sp = baud_of(b);
  if (*end != '\0' || sp == 0)
    throw FswEndpointError("FSW link: unsupported baud rate '" + baud + "' (9600 ... 921600)");
  const int fd = ::open(dev.c_str(), O_RDWR | O_NOCTTY);
  if (fd < 0) throw FswEndpointError("FSW link: cannot open " + dev + ": " + errno_text());
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    ::close(fd);
    throw FswEndpointError("FSW link: " + dev + " is not a terminal");
  }
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(CSTOPB | CRTSCTS);
  tio.c_cc[VMIN] = 1;
  tio.c_cc[VTIME] = 0;
  ::cfsetispeed(&tio, sp);
  ::cfsetospeed(&tio, sp);
  ::tcsetattr(fd, TCSANOW, &tio);
  desc = "serial " + dev + " " + baud + " baud";
  return fd;
}

uint8_t clamp_count(int n, int cap) { return static_cast<uint8_t>(std::clamp(n, 0, cap)); }

}  // namespace

std::unique_ptr<LinkTransport> make_stream_transport(int fd, const std::string& desc)
{
  return std::make_unique<StreamTransport>(fd, desc);
}

std::unique_ptr<LinkTransport> open_link_transport(const std::string& spec)
{
  if (spec.rfind("udp:", 0) == 0) return std::make_unique<UdpTransport>(spec.substr(4));
  if (spec.rfind("serial:", 0) == 0) {
    std::string desc;
    const int fd = open_serial_line(spec.substr(7), desc);
    return std::make_unique<StreamTransport>(fd, desc);
  }
  throw FswEndpointError("FSW link: unknown transport '" + spec + "' (expected udp:HOST:PORT or serial:DEVICE:BAUD)");
}

RemoteFsw::RemoteFsw(std::unique_ptr<LinkTransport> t, const FswAcsConfig& cfg, LinkOptions opt)
    : t_(std::move(t)), opt_(opt), rng_(opt.seed)
{
  missing_ = opt_.on_missing;
  if (!opt_.on_missing_set && opt_.any_fault()) missing_ = LinkOptions::Missing::kHold;
  // Wheel speeds the FSW can read: the largest wheel count of its modules.
  const int nrw = std::max({cfg.mrp_fb.num_rw, cfg.rw_map.num_rw, cfg.rw_null.num_rw, cfg.rw_sat.num_rw,
                            cfg.rw_volt.num_rw});
  num_rw_ = clamp_count(nrw, FSW_MAX_RW);
  num_css_ = clamp_count(cfg.css.num_css, FSW_MAX_CSS);
  std::memset(&last_act_, 0, sizeof last_act_);
  std::memset(&last_health_, 0, sizeof last_health_);
  rx_.reserve(65536);
}

std::string RemoteFsw::describe() const { return "fsw_c application behind the FSW link (" + t_->describe() + ")"; }

void RemoteFsw::put(std::vector<uint8_t> pkt)
{
  t_->send(pkt.data(), pkt.size());
  ++c_.sent;
}

void RemoteFsw::flush_due()
{
  for (auto it = held_.begin(); it != held_.end();) {
    if (it->due <= c_.cycles) {
      put(std::move(it->pkt));
      it = held_.erase(it);
    } else {
      ++it;
    }
  }
}

bool RemoteFsw::await_reply(uint64_t t_ns, FswAcsActuatorMsg& out, FswAcsHealthMsg& health)
{
  const bool lockstep_fail = missing_ == LinkOptions::Missing::kFail;
  double limit = lockstep_fail ? opt_.timeout_s : opt_.reply_timeout_s;
  if (opt_.time_left) limit = std::min(limit, opt_.time_left());
  const auto end = Clock::now() + std::chrono::duration<double>(limit);
  bool have_act = false;
  // nothing sent this cycle, and the FSW's last status covers all that was:
  // no reply can come
  if (!lockstep_fail && c_.fsw.rx_packets >= c_.sent) return false;
  for (;;) {
    const double left = std::chrono::duration<double>(end - Clock::now()).count();
    if (left <= 0 || !t_->recv(rx_, left)) {
      ++c_.timeouts;
      return false;
    }
    FswLinkPacket p;
    if (fsw_link_parse(rx_.data(), rx_.size(), &p, nullptr) != FSW_OK) {
      ++c_.rejected;
      continue;
    }
    if (p.apid == FSW_LINK_APID_LINK) {
      if (fsw_link_decode_status(&p, &c_.fsw, nullptr) != FSW_OK) {
        ++c_.rejected;
        continue;
      }
      // the FSW has processed all we sent and did not answer this cycle
      if (!have_act && c_.fsw.rx_packets >= c_.sent && !lockstep_fail) return false;
      continue;
    }
    if (p.t_ns != t_ns) {
      ++c_.stale;
      continue;
    }
    if (p.apid == FSW_LINK_APID_ACTUATOR) {
      uint8_t nrw = 0, nthr = 0;
      if (fsw_link_decode_actuator(&p, &out, &nrw, &nthr, nullptr) != FSW_OK) {
        ++c_.rejected;
        continue;
      }
      have_act = true;
    } else if (p.apid == FSW_LINK_APID_HEALTH && have_act) {
      if (fsw_link_decode_health(&p, &health, nullptr) != FSW_OK) {
        ++c_.rejected;
        continue;
      }
      return true;
    } else {
      ++c_.rejected;
    }
  }
}

void RemoteFsw::cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& health)
{
  std::vector<uint8_t> pkt(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  if (have_cmd_) {  // a ground command goes out first, so that this cycle applies it
    if (fsw_link_encode_cmd(&cmd_, in.t_ns, cmd_seq_, pkt.data(), pkt.size(), &len, nullptr) != FSW_OK)
      throw FswEndpointError("FSW link: cannot encode the command");
    cmd_seq_ = static_cast<uint16_t>((cmd_seq_ + 1u) % FSW_LINK_SEQ_MODULO);
    put(std::vector<uint8_t>(pkt.begin(), pkt.begin() + static_cast<std::ptrdiff_t>(len)));
    have_cmd_ = false;
  }
  if (fsw_link_encode_sensor(&in, num_rw_, num_css_, seq_, pkt.data(), pkt.size(), &len, nullptr) != FSW_OK)
    throw FswEndpointError("FSW link: cannot encode the sensor message");
  pkt.resize(len);
  seq_ = static_cast<uint16_t>((seq_ + 1u) % FSW_LINK_SEQ_MODULO);
  ++c_.cycles;
  // faults, each decided by its own draw so that one probability does not
  // shift the others' sequences
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double d_loss = u(rng_), d_corrupt = u(rng_), d_dup = u(rng_), d_reorder = u(rng_), d_delay = u(rng_);
  const uint64_t bits = rng_();
  if (d_corrupt < opt_.corrupt) {
    ++c_.corrupted;
    const int nflip = 1 + static_cast<int>(bits % 3u);
    for (int i = 0; i < nflip; ++i) {
      const uint64_t b = (bits >> (8 + 20 * i)) % (pkt.size() * 8u);
      pkt[b / 8u] = static_cast<uint8_t>(pkt[b / 8u] ^ (1u << (b % 8u)));
    }
  }
  if (d_loss < opt_.loss) {
    ++c_.lost;
  } else if (d_delay < opt_.delay) {
    ++c_.delayed;
    held_.push_back({c_.cycles + static_cast<uint64_t>(std::max(1, opt_.delay_cycles)), pkt});
  } else if (d_reorder < opt_.reorder) {
    ++c_.reordered;
    held_.push_back({c_.cycles + 1u, pkt});  // goes out after the next cycle's packet
    flush_due();
  } else {
    put(pkt);
    if (d_dup < opt_.duplicate) {
      ++c_.duplicated;
      put(pkt);
    }
  }
  if (d_reorder >= opt_.reorder) flush_due();
  if (await_reply(in.t_ns, out, health)) {
    ++c_.replies;
    last_act_ = out;
    last_health_ = health;
    return;
  }
  if (missing_ == LinkOptions::Missing::kFail) {
    std::ostringstream os;
    os << "FSW link: no reply to the sensor packet of t = " << in.t_ns * 1e-9 << " s within " << opt_.timeout_s
       << " s (" << t_->describe();
    const std::string why = t_->diagnose();
    if (why.empty())
      os << "; is kestrel-fsw running with the same configuration?)";
    else
      os << "; " << why << ")";
    throw FswEndpointError(os.str());
  }
  ++c_.missing;
  if (missing_ == LinkOptions::Missing::kHold) {
    out = last_act_;
  } else {
    std::memset(&out, 0, sizeof out);
  }
  health = last_health_;
  health.safe_output = missing_ == LinkOptions::Missing::kZero ? 1u : last_health_.safe_output;
}

std::vector<std::string> RemoteFsw::module_health_lines() const
{
  std::ostringstream h, f;
  h << "link (harness end, " << t_->describe() << "): cycles=" << c_.cycles << " sent=" << c_.sent
    << " lost=" << c_.lost << " corrupted=" << c_.corrupted << " duplicated=" << c_.duplicated
    << " reordered=" << c_.reordered << " delayed=" << c_.delayed << " replies=" << c_.replies
    << " missing=" << c_.missing << " timeouts=" << c_.timeouts << " rejected=" << c_.rejected << " stale=" << c_.stale << " on_missing="
    << (missing_ == LinkOptions::Missing::kFail ? "fail" : missing_ == LinkOptions::Missing::kHold ? "hold" : "zero");
  f << "link (FSW end, last status): rx_packets=" << c_.fsw.rx_packets << " rx_crc=" << c_.fsw.rx_crc
    << " rx_rejected=" << c_.fsw.rx_rejected << " rx_stale=" << c_.fsw.rx_stale << " missed=" << c_.fsw.missed
    << " safe_entries=" << c_.fsw.safe_entries << " safe_cycles=" << c_.fsw.safe_cycles
    << " recoveries=" << c_.fsw.recoveries << " cycles=" << c_.fsw.cycles;
  return {h.str(), f.str()};
}

}  // namespace harness

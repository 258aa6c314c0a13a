#include "harness/link/remote_fsw.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>

#include "transport/fsw_transport.h"

namespace harness {

namespace {

using Clock = std::chrono::steady_clock;

std::string errno_text() { return std::strerror(errno); }

// The harness's side of the link: an RAII owner of the C transport
// (flight/posix/fsw_transport.c, which kestrel-fsw runs too): opening,
// framing on byte streams, receiving with a timeout, sending and closing
// are all there; this class turns its results into packets and exceptions.
class CTransport : public LinkTransport {
 public:
  enum class Kind { kUdp, kUdpBound, kSerial };
  // a connected UDP socket ("HOST:PORT"), a bound one (receives only), or a
  // serial line ("DEVICE:BAUD")
  CTransport(Kind kind, const std::string& spec) : t_(std::make_unique<FswTransport>())
  {
    char err[256] = "";
    const int rc = kind == Kind::kUdp        ? fsw_transport_connect_udp(t_.get(), spec.c_str(), err, sizeof err)
                   : kind == Kind::kUdpBound ? fsw_transport_open_udp(t_.get(), spec.c_str(), err, sizeof err)
                                             : fsw_transport_open_serial(t_.get(), spec.c_str(), err, sizeof err);
    if (rc != 0) throw FswEndpointError(std::string("FSW link: ") + err);
  }
  // a byte stream already open; owns fd
  CTransport(int fd, const std::string& desc) : t_(std::make_unique<FswTransport>())
  {
    fsw_transport_open_stream(t_.get(), fd, desc.c_str());
  }
  // a stream socket connected to a unix socket; *listening false: nothing
  // accepts there yet (no transport)
  CTransport(const std::string& path, const std::string& desc, bool* listening)
      : t_(std::make_unique<FswTransport>())
  {
    char err[256] = "";
    const int rc = fsw_transport_connect_unix(t_.get(), path.c_str(), desc.c_str(), err, sizeof err);
    if (rc == -1) throw FswEndpointError(std::string("PIL (harness side): ") + err);
    *listening = rc == 0;
  }
  ~CTransport() override { fsw_transport_close(t_.get()); }
  CTransport(const CTransport&) = delete;
  CTransport& operator=(const CTransport&) = delete;

  std::string describe() const override { return t_->desc; }
  bool datagram() const override { return !t_->stream; }
  // packet authentication with the shared key in key_file (UDP only)
  void set_key(const std::string& key_file)
  {
    std::array<uint8_t, FSW_LINK_SEC_KEY_MAX> key{};
    size_t n = 0;
    char err[320] = "";
    sec_ = std::make_unique<FswLinkSec>();
    int rc = fsw_transport_load_key(key_file.c_str(), key.data(), key.size(), &n, err, sizeof err);
    if (rc == 0 && fsw_link_sec_init(sec_.get(), key.data(), n) != FSW_OK) rc = -1;
    key.fill(0);
    if (rc == 0) rc = fsw_transport_set_key(t_.get(), sec_.get(), err, sizeof err);
    if (rc != 0) throw FswEndpointError(std::string("FSW link: --link-key: ") + err);
  }
  std::string diagnose() const override
  {
    if (!sec_ || sec_->rx_auth_failed + sec_->rx_replayed == 0) return "";
    return std::to_string(sec_->rx_auth_failed) + " datagrams from the FSW end failed authentication and " +
           std::to_string(sec_->rx_replayed) + " were replays: is kestrel-fsw using the same key (--key)?";
  }
  void send(const uint8_t* p, size_t n) override
  {
    if (fsw_transport_send(t_.get(), p, n) != 0 && errno != EMSGSIZE)  // a packet too long to frame: not sent
      throw FswEndpointError("FSW link: write failed: " + errno_text());
  }
  bool recv(std::vector<uint8_t>& pkt, double timeout_s) override
  {
    const auto end = Clock::now() + std::chrono::duration<double>(std::max(0.0, timeout_s));
    for (;;) {
      const double left = std::chrono::duration<double>(end - Clock::now()).count();
      const int ms = left <= 0 ? 0 : static_cast<int>(std::min(left, 2.0e6) * 1000.0) + 1;
      const uint8_t* p = nullptr;
      size_t len = 0;
      const int rc = fsw_transport_recv(t_.get(), &p, &len, ms);
      if (rc == FSW_TRANSPORT_PACKET) {
        pkt.assign(p, p + len);
        return true;
      }
      if (rc == FSW_TRANSPORT_TIMEOUT) return false;
      if (rc == FSW_TRANSPORT_REFUSED) continue;  // unauthenticated: dropped (counted in sec_)
      if (rc == FSW_TRANSPORT_ERROR && errno == EINTR) continue;
      if (t_->stream)
        throw FswEndpointError("FSW link: the " + std::string(t_->is_socket ? "socket" : "serial line") + " closed");
      throw FswEndpointError("FSW link: receive failed: " + errno_text());
    }
  }

 private:
  std::unique_ptr<FswTransport> t_;  // 67 kB of buffers: not on the stack
  std::unique_ptr<FswLinkSec> sec_;  // with a key
};

uint8_t clamp_count(int n, int cap) { return static_cast<uint8_t>(std::clamp(n, 0, cap)); }

}  // namespace

std::unique_ptr<LinkTransport> make_stream_transport(int fd, const std::string& desc)
{
  return std::make_unique<CTransport>(fd, desc);
}

std::unique_ptr<LinkTransport> connect_unix_transport(const std::string& path, const std::string& desc)
{
  bool listening = false;
  auto t = std::make_unique<CTransport>(path, desc, &listening);
  if (!listening) return nullptr;
  return t;
}

std::unique_ptr<LinkTransport> open_link_transport(const std::string& spec, const std::string& key_file)
{
  if (spec.rfind("udp:", 0) == 0) {
    auto t = std::make_unique<CTransport>(CTransport::Kind::kUdp, spec.substr(4));
    if (!key_file.empty()) t->set_key(key_file);
    return t;
  }
  if (!key_file.empty())
    throw FswEndpointError("FSW link: --link-key: packet authentication needs a UDP link (udp:HOST:PORT)");
  if (spec.rfind("serial:", 0) == 0) return std::make_unique<CTransport>(CTransport::Kind::kSerial, spec.substr(7));
  throw FswEndpointError("FSW link: unknown transport '" + spec + "' (expected udp:HOST:PORT or serial:DEVICE:BAUD)");
}

std::unique_ptr<LinkTransport> bind_udp_transport(const std::string& spec)
{
  return std::make_unique<CTransport>(CTransport::Kind::kUdpBound, spec);
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

// One received packet of the cycle stamped t_ns: the actuator, the health
// and the link status that ends it, in this order.  kDone: the status of
// this cycle came (its counters are the FSW end's final ones for the cycle);
// kProcessed: a status says the FSW end has processed everything sent and
// not answered this cycle (hold/zero only).
RemoteFsw::Got RemoteFsw::take(uint64_t t_ns, Reply& r)
{
  FswLinkPacket p;
  if (fsw_link_parse(rx_.data(), rx_.size(), &p, nullptr) != FSW_OK) {
    ++c_.rejected;
    return Got::kNothing;
  }
  if (p.apid == FSW_LINK_APID_LINK) {
    FswLinkStatusMsg st;
    if (fsw_link_decode_status(&p, &st, nullptr) != FSW_OK) {
      ++c_.rejected;
      return Got::kNothing;
    }
    c_.fsw = st;
    if (r.have_health && p.t_ns == t_ns) return Got::kDone;
    // the FSW has processed all we sent and did not answer this cycle
    const bool lockstep_fail = missing_ == LinkOptions::Missing::kFail;
    if (!r.have_act && c_.fsw.rx_packets >= c_.sent && !lockstep_fail) return Got::kProcessed;
    return Got::kNothing;
  }
  if (p.t_ns != t_ns) {
    ++c_.stale;
    return Got::kNothing;
  }
  uint8_t nrw = 0, nthr = 0, nmtq = 0;
  if (p.apid == FSW_LINK_APID_ACTUATOR && !r.have_act) {
    if (fsw_link_decode_actuator(&p, &r.act, &nrw, &nthr, &nmtq, nullptr) != FSW_OK) {
      ++c_.rejected;
      return Got::kNothing;
    }
    r.have_act = true;
  } else if (p.apid == FSW_LINK_APID_HEALTH && r.have_act && !r.have_health) {
    if (fsw_link_decode_health(&p, &r.health, nullptr) != FSW_OK) {
      ++c_.rejected;
      return Got::kNothing;
    }
    r.have_health = true;
    if (!t_->sends_link_status()) return Got::kDone;  // the health packet ends the cycle
  } else if (p.apid == FSW_LINK_APID_ACTUATOR || p.apid == FSW_LINK_APID_HEALTH) {
    ++c_.stale;  // this cycle's reply again (an answered retransmission)
  } else {
    ++c_.rejected;
  }
  return Got::kNothing;
}

bool RemoteFsw::retransmitting() const
{
  return missing_ == LinkOptions::Missing::kFail && t_->datagram() && opt_.retransmits > 0;
}

// Lockstep over UDP: a command packet lost on the way would let the cycle
// run without it, silently; so the harness waits for the link status that
// answers it (a count of received packets above `before`, the count of the
// last status) and sends it again after retransmit_s, as for the sensor
// packet.  A command applied twice is harmless (fsw_acs_msgs.h).
void RemoteFsw::await_command_ack(const std::vector<uint8_t>& cmd, uint32_t before, uint64_t t_ns)
{
  const auto end = Clock::now() + std::chrono::duration<double>(opt_.timeout_s);
  int retx_left = opt_.retransmits;
  auto next_retx = Clock::now() + std::chrono::duration<double>(opt_.retransmit_s);
  for (;;) {
    const auto until = retx_left > 0 ? std::min(end, next_retx) : end;
    const double left = std::chrono::duration<double>(until - Clock::now()).count();
    if (left <= 0 || !t_->recv(rx_, left)) {
      if (retx_left == 0 || Clock::now() >= end)
        throw FswEndpointError("FSW link: the command packet before the sensor packet of t = " +
                               std::to_string(t_ns * 1e-9) + " s was not acknowledged within " +
                               std::to_string(opt_.timeout_s) + " s (" + t_->describe() + ")");
      t_->send(cmd.data(), cmd.size());
      ++c_.retransmits;
      --retx_left;
      next_retx = Clock::now() + std::chrono::duration<double>(opt_.retransmit_s);
      continue;
    }
    FswLinkPacket p;
    FswLinkStatusMsg st;
    if (fsw_link_parse(rx_.data(), rx_.size(), &p, nullptr) != FSW_OK) {
      ++c_.rejected;
    } else if (p.apid != FSW_LINK_APID_LINK) {
      ++c_.stale;  // a reply of an earlier cycle (an answered retransmission)
    } else if (fsw_link_decode_status(&p, &st, nullptr) != FSW_OK) {
      ++c_.rejected;
    } else {
      c_.fsw = st;
      if (st.rx_packets > before) return;
    }
  }
}

// Lockstep over a datagram link retransmits the sensor packet (the same
// bytes) after retransmit_s without the whole reply, at most retransmits
// times a cycle; the FSW end answers a packet it has already run with its
// replies again and runs no second cycle (fsw_link_node.h).
bool RemoteFsw::await_reply(uint64_t t_ns, FswAcsActuatorMsg& out, FswAcsHealthMsg& health)
{
  const bool lockstep_fail = missing_ == LinkOptions::Missing::kFail;
  double limit = lockstep_fail ? opt_.timeout_s : opt_.reply_timeout_s;
  if (opt_.time_left) limit = std::min(limit, opt_.time_left());
  const auto end = Clock::now() + std::chrono::duration<double>(limit);
  const bool retransmit = retransmitting() && !last_pkt_.empty();
  int retx_left = retransmit ? opt_.retransmits : 0;
  auto next_retx = Clock::now() + std::chrono::duration<double>(opt_.retransmit_s);
  Reply r;
  // nothing sent this cycle, and the FSW's last status covers all that was:
  // no reply can come
  if (!lockstep_fail && c_.fsw.rx_packets >= c_.sent) return false;
  for (;;) {
    const auto until = retx_left > 0 ? std::min(end, next_retx) : end;
    const double left = std::chrono::duration<double>(until - Clock::now()).count();
    if (left <= 0 || !t_->recv(rx_, left)) {
      if (retx_left > 0 && Clock::now() < end) {  // the retransmission's turn
        t_->send(last_pkt_.data(), last_pkt_.size());
        ++c_.retransmits;
        --retx_left;
        next_retx = Clock::now() + std::chrono::duration<double>(opt_.retransmit_s);
        continue;
      }
      if (!r.have_health) ++c_.timeouts;
      break;  // a whole reply without its status still counts (the status is late)
    }
    const Got g = take(t_ns, r);
    if (g == Got::kDone) break;
    if (g == Got::kProcessed) return false;
  }
  if (!r.have_health) return false;
  out = r.act;
  health = r.health;
  return true;
}

void RemoteFsw::cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& health)
{
  std::vector<uint8_t> pkt(FSW_LINK_MAX_PACKET);
  size_t len = 0;
  if (have_cmd_) {  // a ground command goes out first, so that this cycle applies it
    if (fsw_link_encode_cmd(&cmd_, in.t_ns, cmd_seq_, pkt.data(), pkt.size(), &len, nullptr) != FSW_OK)
      throw FswEndpointError("FSW link: cannot encode the command");
    cmd_seq_ = static_cast<uint16_t>((cmd_seq_ + 1u) % FSW_LINK_SEQ_MODULO);
    const uint32_t before = c_.fsw.rx_packets;
    const std::vector<uint8_t> cmd(pkt.begin(), pkt.begin() + static_cast<std::ptrdiff_t>(len));
    put(cmd);
    have_cmd_ = false;
    if (retransmitting()) await_command_ack(cmd, before, in.t_ns);
  }
  if (fsw_link_encode_sensor(&in, num_rw_, num_css_, seq_, pkt.data(), pkt.size(), &len, nullptr) != FSW_OK)
    throw FswEndpointError("FSW link: cannot encode the sensor message");
  pkt.resize(len);
  last_pkt_ = pkt;  // as encoded: what a retransmission sends again
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
      os << "; is kestrel-fsw running with the same configuration" << (opt_.key_file.empty() ? "" : " and key")
         << "?)";
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
    << " missing=" << c_.missing << " timeouts=" << c_.timeouts << " retransmits=" << c_.retransmits
    << " rejected=" << c_.rejected << " stale=" << c_.stale << " on_missing="
    << (missing_ == LinkOptions::Missing::kFail ? "fail" : missing_ == LinkOptions::Missing::kHold ? "hold" : "zero");
  if (!t_->sends_link_status()) return {h.str(), "link (FSW end): " + t_->far_end_status()};
  f << "link (FSW end, status of the last cycle): rx_packets=" << c_.fsw.rx_packets << " rx_crc=" << c_.fsw.rx_crc
    << " rx_rejected=" << c_.fsw.rx_rejected << " rx_stale=" << c_.fsw.rx_stale << " missed=" << c_.fsw.missed
    << " safe_entries=" << c_.fsw.safe_entries << " safe_cycles=" << c_.fsw.safe_cycles
    << " recoveries=" << c_.fsw.recoveries << " cycles=" << c_.fsw.cycles;
  return {h.str(), f.str()};
}

}  // namespace harness

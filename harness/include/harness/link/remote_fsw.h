// remote_fsw: the FSW endpoint behind the FSW link (docs/hwil.md, docs/icd.md):
// kestrel-fsw on this machine or another, or a flight computer, over UDP or a
// serial line.  Each cycle sends one sensor packet (APID 0x101) and waits for
// the actuator (0x181) and health (0x182) packets stamped with its t_ns; the
// link status packet (0x183) that follows carries the FSW end's counters.
//
// Lockstep (the default): the harness waits for cycle k's reply (actuator,
// health and the link status that ends the cycle, so the FSW end's counters
// it keeps are final); over UDP it sends the sensor packet again after
// LinkOptions::retransmit_s without a whole reply (bounded, counted), and
// waits for the link status that acknowledges a command packet (sent again
// likewise) before the sensor packet goes out; no reply within
// LinkOptions::timeout_s is a FswEndpointError.  With --realtime, or
// with injected faults, or with on_missing set, a cycle whose reply does not
// come holds the last command (hold) or applies the safe output (zero), and
// is counted.  A cycle is given up as soon as the FSW's link status shows it
// has processed every packet sent without answering this one (a rejected
// packet), else after reply_timeout_s.
//
// Faults (uplink, sensor packets; seeded, repeatable): loss, corruption
// (1..3 flipped bits), duplication, reordering (swapped with the next
// packet), delay (sent delay_cycles cycles late).
#ifndef HARNESS_REMOTE_FSW_H
#define HARNESS_REMOTE_FSW_H

#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "harness/core/fsw_endpoint.h"

extern "C" {
#include "fsw/fsw_link.h"
}

namespace harness {

struct LinkOptions {
  enum class Missing { kFail, kHold, kZero };
  Missing on_missing = Missing::kFail;  // what a cycle without a reply applies
  bool on_missing_set = false;          // given explicitly (else: fail, or hold with faults/real time)
  double timeout_s = 10.0;              // lockstep: no reply within this fails the run
  double reply_timeout_s = 0.5;         // hold/zero: give a cycle up after this [s wall]
  // Lockstep over UDP: the sensor packet goes out again when its whole
  // reply has not come within retransmit_s, at most `retransmits` times a
  // cycle (a datagram the kernel dropped under load is not fatal); 0: never.
  double retransmit_s = 0.25;
  int retransmits = 8;
  // faults, probabilities per sensor packet in [0, 1]
  double loss = 0.0, corrupt = 0.0, duplicate = 0.0, reorder = 0.0, delay = 0.0;
  int delay_cycles = 2;                 // how late a delayed packet goes out
  uint64_t seed = 1;
  // Optional (paced runs): wall time [s] left until the deadline of the
  // tick being computed; a wait for a reply never goes past it.
  std::function<double()> time_left;
  // Processor in the loop (--fsw pil:TARGET, docs/pil.md): the FSW program
  // to run instead of the build's cross-built one, and the emulator command
  // instead of the target's QEMU ("" : defaults).  The start-up of the
  // emulated FSW is bounded by timeout_s.
  std::string pil_bin;
  // Packet authentication (--link-key FILE, docs/hwil.md): the shared key's
  // file, given to both ends ("" : none).
  std::string key_file;
  std::string pil_emulator;
  bool any_fault() const { return loss > 0 || corrupt > 0 || duplicate > 0 || reorder > 0 || delay > 0; }
  // The options a run uses, from these as given (the `kestrel run` flags,
  // RunCommand::link): the defaulting rules in one place.
  //   - on_missing not given: fail (lockstep), but hold the last command
  //     with injected faults or with real-time pacing;
  //   - paced (realtime_scale > 0): a cycle waits for its reply at most one
  //     FSW period of wall time (fsw_period_s / realtime_scale), and never
  //     past `deadline` (the time left until the next tick's deadline).
  LinkOptions for_run(double fsw_period_s, double realtime_scale, std::function<double()> deadline) const
  {
    LinkOptions lo = *this;
    if (!lo.on_missing_set && (lo.any_fault() || realtime_scale > 0)) lo.on_missing = Missing::kHold;
    lo.on_missing_set = lo.on_missing_set || lo.any_fault() || realtime_scale > 0;
    if (realtime_scale > 0) {
      lo.reply_timeout_s = fsw_period_s / realtime_scale;
      lo.time_left = std::move(deadline);
    }
    return lo;
  }
};

// Moves whole packets.  recv() returns false on timeout.
class LinkTransport {
 public:
  virtual ~LinkTransport() = default;
  virtual std::string describe() const = 0;
  virtual void send(const uint8_t* p, size_t n) = 0;
  virtual bool recv(std::vector<uint8_t>& pkt, double timeout_s) = 0;
  // Datagrams (UDP: a packet can be lost whole) rather than a byte stream.
  virtual bool datagram() const { return false; }
  // Which side failed when a reply does not come ("" : unknown, the far
  // end is not ours to inspect).
  virtual std::string diagnose() const { return ""; }
  // The far end ends each cycle's reply with a link status packet (0x183,
  // kestrel-fsw); false: the health packet ends it (the cFS application).
  virtual bool sends_link_status() const { return true; }
  // Without link status packets: what the transport knows of the far end
  // (a line of fsw_health.txt).
  virtual std::string far_end_status() const { return ""; }
};

// The transports below are RAII wrappers over the C transport module that
// kestrel-fsw runs too (flight/posix/include/transport/fsw_transport.h):
// opening, framing on byte streams, receiving with a timeout, sending and
// closing are written once, there.

// A byte stream already open (a serial line, a connected socket): packets
// framed by the attached sync marker.  Takes ownership of fd.
std::unique_ptr<LinkTransport> make_stream_transport(int fd, const std::string& desc);

// A stream socket connected to the unix socket at path (an emulator's UART),
// framed as above; nullptr while nothing accepts there.  Throws
// FswEndpointError when no socket can be made.
std::unique_ptr<LinkTransport> connect_unix_transport(const std::string& path, const std::string& desc);

// "udp:HOST:PORT" or "serial:DEVICE:BAUD"; throws FswEndpointError with the
// reason (bad address, cannot open).  key_file: packet authentication with
// the shared key in it (fsw_link_sec.h; UDP only; the file must be mode
// 0600 or stricter, and its key is never printed); "" : none.
std::unique_ptr<LinkTransport> open_link_transport(const std::string& spec, const std::string& key_file = "");

// A UDP socket bound to "HOST:PORT" that receives every datagram sent there
// (whatever its content) and sends nothing; throws FswEndpointError (the
// port is taken, a bad address).
std::unique_ptr<LinkTransport> bind_udp_transport(const std::string& spec);

// What the harness end counted.
struct LinkCounters {
  uint64_t cycles = 0;          // cycles asked of the endpoint
  uint64_t sent = 0;            // sensor packets put on the wire (duplicates included)
  uint64_t lost = 0;            // dropped by the loss injector
  uint64_t corrupted = 0;       // sent with flipped bits
  uint64_t duplicated = 0, reordered = 0, delayed = 0;
  uint64_t replies = 0;         // cycles answered in time
  uint64_t missing = 0;         // cycles without a reply (hold/zero applied)
  uint64_t timeouts = 0;        // ... of which given up after the reply timeout
  uint64_t retransmits = 0;     // sensor packets sent again (lockstep over UDP, no reply yet)
  uint64_t rejected = 0;        // received packets that failed to parse or decode
  uint64_t stale = 0;           // replies of another cycle (late, duplicated)
  FswLinkStatusMsg fsw{};       // the last link status of the FSW end
};

class RemoteFsw : public FswEndpoint {
 public:
  // cfg: the configuration the FSW end runs (for the packet counts and the
  // safe output's sizes), fsw_acs_config_of(scenario).
  RemoteFsw(std::unique_ptr<LinkTransport> t, const FswAcsConfig& cfg, LinkOptions opt);
  std::string describe() const override;
  void cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& health) override;
  std::vector<std::string> module_health_lines() const override;
  const LinkCounters& counters() const { return c_; }
  // Sent as a command packet (APID 0x102) just before the next cycle's
  // sensor packet, outside the fault injection: the FSW end holds it and
  // applies it from that cycle (docs/hwil.md).
  bool accepts_commands() const override { return true; }
  void command(const FswAcsCmdMsg& cmd) override
  {
    cmd_ = cmd;
    have_cmd_ = true;
  }

 private:
  void put(std::vector<uint8_t> pkt);
  void flush_due();
  bool await_reply(uint64_t t_ns, FswAcsActuatorMsg& out, FswAcsHealthMsg& health);
  struct Reply {
    FswAcsActuatorMsg act{};
    FswAcsHealthMsg health{};
    bool have_act = false, have_health = false;
  };
  enum class Got { kNothing, kDone, kProcessed };
  Got take(uint64_t t_ns, Reply& r);
  bool retransmitting() const;
  void await_command_ack(const std::vector<uint8_t>& cmd, uint32_t before, uint64_t t_ns);

  std::unique_ptr<LinkTransport> t_;
  LinkOptions opt_;
  LinkOptions::Missing missing_;
  uint8_t num_rw_, num_css_;
  uint16_t seq_ = 0;
  std::mt19937_64 rng_;
  struct Held {
    uint64_t due;
    std::vector<uint8_t> pkt;
  };
  std::vector<Held> held_;
  LinkCounters c_;
  FswAcsActuatorMsg last_act_{};
  FswAcsHealthMsg last_health_{};
  std::vector<uint8_t> rx_;
  std::vector<uint8_t> last_pkt_;  // the last sensor packet, as encoded
  FswAcsCmdMsg cmd_{};
  bool have_cmd_ = false;
  uint16_t cmd_seq_ = 0;
};

}  // namespace harness

#endif  // HARNESS_REMOTE_FSW_H

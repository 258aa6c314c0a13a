// live_server: `kestrel run SCENARIO --live` (docs/live.md).  A local HTTP
// server (cpp-httplib, its own threads) that serves the live page and its
// API while the run goes, and a RunControl that the run calls at its tick
// boundaries.
//
// The simulation never waits for the page:
//   telemetry  boundary() copies the last recorded row into a ring of
//              kRingFrames preallocated frames under a try_lock: when a page
//              request holds the lock the frame is dropped and counted
//              (`dropped_busy`); a frame overwritten before any page read it
//              is counted too (`dropped_unread`, once a page has connected).
//              At most one frame per kPublishPeriod of wall time.
//   push       GET /api/stream (server-sent events, live_stream.cpp) sends
//              what was published since its last message; the sim thread
//              only bumps a counter, a slow client loses frames, never
//              delays the run.
//   commands   the server validates a command when it arrives (the token;
//              an event action with check_event_action(), the scenario
//              event validation) and refuses it with a message, or queues
//              it (bounded, kMaxQueued); boundary() drains the queue before
//              the tick it is called for: an event action becomes a scenario
//              event {name live<n>, t = t_k, actions} added with
//              Run::add_event(), so the manifest replays it; a save
//              writes a checkpoint (checkpoint.h) into the results folder
//              there, between two ticks.
// Not in the library the fuzzers link (kestrel::harness_live, linked by the
// kestrel program only).
#ifndef HARNESS_SRC_LIVE_SERVER_H
#define HARNESS_SRC_LIVE_SERVER_H

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "harness/drive/run_scenario.h"

namespace harness {

struct LiveOptions {
  std::string host = "127.0.0.1";  // address to bind
  int port = 0;                    // 0: any free port
  std::string token;               // "" : 128 random bits, hex
  bool start_paused = false;       // the run waits after tick 0 (t = 0 recorded) for resume or step
  // [s] otherwise the run waits after tick 0 until a page connects (its
  // stream or a /api/frames request) or a command comes, at most this long
  // (0: no wait); kestrel run: --live-wait, by default kDefaultPageWait for
  // an unpaced run (it would be over before a page opened) and 0 paced
  double wait_unpaced = 0.0;
  double wait_paced = 0.0;
};

struct LiveCounters {
  uint64_t published = 0;         // frames put in the ring
  uint64_t dropped_busy = 0;      // not published: a page request held the ring
  uint64_t dropped_unread = 0;    // overwritten before a page read them (a page connected)
  uint64_t commands_applied = 0;  // entered the run
  uint64_t commands_refused = 0;  // refused with a message (device, action, value, state, queue full)
  uint64_t requests_unauthorised = 0;  // refused before their body was read: no or a wrong token (403)
  uint64_t requests_refused = 0;       // refused before their body was read: too large, compressed, chunked
  uint64_t connections = 0;            // accepted
  uint64_t connections_closed = 0;     // by the server: idle, header too slow or too large, evicted at the limit
  double paused_s = 0.0;          // [s] wall time the run waited, paused
  double waited_s = 0.0;          // [s] wall time the run waited at t = 0 for a page
};

class LiveServer : public RunControl {
 public:
  static constexpr size_t kRingFrames = 256;
  static constexpr size_t kMaxQueued = 64;
  static constexpr size_t kLogKept = 1000;  // commands the log keeps (older ones are forgotten)
  static constexpr size_t kLogPage = 64;    // commands per answer (/api/frames: the last ones)
  static constexpr double kPublishPeriod = 0.02;  // [s] wall time: at most 50 frames/s
  static constexpr double kPushPeriod = 0.05;     // [s] a stream's messages: at most 20/s (frames batched)
  static constexpr size_t kMaxStreams = 2;        // pushed streams at once (each holds one of the gate's workers)
  static constexpr double kDefaultPageWait = 60.0;  // [s] kestrel run --live, unpaced: wait for a page

  // Binds and starts serving (the page answers "starting" until the run
  // starts).  Throws std::runtime_error when the address cannot be bound.
  explicit LiveServer(LiveOptions opt);
  ~LiveServer() override;  // stops the server and joins its thread
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const;
  const std::string& token() const;
  std::string url() const;  // http://HOST:PORT/?token=...

  void results_folder(const std::string& working, const std::string& target) override;
  void started(Run& run, double realtime_scale, const std::atomic<int>* stop) override;
  uint64_t boundary(Run& run, double& pace) override;
  void ended(const Run& run, const RunResult& res) override;
  // Keeps serving (the final frame, the report) for `seconds` or until *stop.
  void linger(double seconds, const std::atomic<int>* stop);
  LiveCounters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace harness

#endif  // HARNESS_SRC_LIVE_SERVER_H

// live_gate: the live view's connection handling (docs/live.md, "Access").
// A cpp-httplib server whose connections are held by a gate instead of the
// library's thread pool, so that no client can hold the server by sending
// slowly or nothing at all:
//   - one poller thread holds every connection that waits for a request
//     (new, or kept alive between requests) and reads its header without
//     blocking; a connection is handed to a worker only once its whole
//     header is in (at most header_max bytes, within header_timeout of its
//     first byte; idle ones are closed after idle_timeout);
//   - a few workers answer complete requests: cpp-httplib parses the header
//     from memory and reads the body (at most body_max bytes from the
//     socket per request, each read within io_timeout);
//   - at most max_connections are open: a new one at the limit closes the
//     connection that has waited longest without a complete request (or,
//     when every one is being answered, is answered 503 and closed).
// The request's handlers (the pre-routing check: token, size, encoding)
// run before the body is read; close_after_answer() closes the connection
// after a refusal, so a body that was never read is never parsed.
#ifndef HARNESS_SRC_LIVE_GATE_H
#define HARNESS_SRC_LIVE_GATE_H

#include <httplib.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace harness {

struct GateLimits {
  size_t max_connections = 64;   // open at once (waiting and being answered)
  size_t workers = 4;            // threads answering complete requests
  size_t header_max = 16384;     // [bytes] request line and headers
  size_t body_max = 65536;       // [bytes] read from the socket per request
  double header_timeout = 2.0;   // [s] from a request's first byte to its header's end
  double idle_timeout = 5.0;     // [s] waiting for a request (new or kept-alive connection)
  double io_timeout = 5.0;       // [s] each read of a body, each write of an answer
  size_t keep_alive_max = 1000;  // requests per connection
};

struct GateCounters {
  uint64_t connections = 0;    // accepted
  uint64_t idle_closed = 0;    // no request within idle_timeout
  uint64_t slow_closed = 0;    // header not complete within header_timeout (408)
  uint64_t large_closed = 0;   // header over header_max (431)
  uint64_t evicted = 0;        // closed waiting, to let a new connection in at the limit
  uint64_t busy_refused = 0;   // 503: every connection was being answered
};

class GatedServer : public httplib::Server {
 public:
  explicit GatedServer(GateLimits lim = GateLimits());
  ~GatedServer() override;
  GatedServer(const GatedServer&) = delete;
  GatedServer& operator=(const GatedServer&) = delete;

  // Binds (port 0: any free port) and listens with a backlog of kBacklog
  // (cpp-httplib's own is 5: a burst of connections then waits a second
  // for the kernel's retry); the port, or -1.
  static constexpr int kBacklog = 128;
  int bind_gated(const std::string& host, int port);
  // Stops the poller and the workers and closes every connection (after
  // stop() and the listening thread's end).
  void stop_gate();
  GateCounters gate_counters() const;
  const GateLimits& limits() const;
  // From a handler: the connection of the request being answered closes
  // after the answer (its unread body is never read).
  static void close_after_answer();
  // From the pre-routing handler, for a request it admits: its connection
  // may stay open for the next request.  Without it (a request cpp-httplib
  // could not parse and answered 400 itself, or one refused) the connection
  // closes after the answer, and nothing left of that request is read as
  // the next one.
  static void keep_connection_open();

 protected:
  bool process_and_close_socket(socket_t sock) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace harness

#endif  // HARNESS_SRC_LIVE_GATE_H

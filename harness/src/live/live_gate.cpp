// live_gate.cpp: the live view's connection gate (live_gate.h).
#include "live/live_gate.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace harness {

namespace {

using Clock = std::chrono::steady_clock;

double since_s(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Conn {
  int fd = -1;
  std::string buf;  // read, not yet consumed (from `pos`)
  size_t pos = 0;
  Clock::time_point since = Clock::now();    // waiting since (idle), or the request's first byte
  Clock::time_point entered = Clock::now();  // joined the poller's connections
  bool started = false;                    // a request's first byte is in
  size_t served = 0;
  bool close_after = false;
};

thread_local Conn* t_current = nullptr;

// Runs the accepted connection's task at once on the accepting thread: the
// gate's process_and_close_socket only hands the socket to the poller.
struct InlineQueue : httplib::TaskQueue {
  void enqueue(std::function<void()> fn) override { fn(); }
  void shutdown() override {}
};

// the blank line that ends a header: CRLF, or bare LF (which cpp-httplib
// then answers 400 at once, rather than the gate holding it until 408)
bool header_complete(const Conn& c)
{
  return c.buf.find("\r\n\r\n", c.pos) != std::string::npos || c.buf.find("\n\n", c.pos) != std::string::npos;
}

void send_status_and_close(int fd, int status, const char* what)
{
  std::string r = "HTTP/1.1 " + std::to_string(status) + " " + what +
                  "\r\nConnection: close\r\nContent-Type: text/plain\r\nContent-Length: " +
                  std::to_string(std::strlen(what) + 1) + "\r\n\r\n" + what + "\n";
  (void)!::send(fd, r.data(), r.size(), MSG_NOSIGNAL | MSG_DONTWAIT);  // best effort: never waits
  ::shutdown(fd, SHUT_WR);
  ::close(fd);
}

// poll() for `ev` on fd for up to `seconds`, in slices so that a stopping
// gate is not held; > 0 ready, 0 timed out or stopping, < 0 error
int wait_for(int fd, short ev, double seconds, const std::atomic<bool>& stopping)
{
  const Clock::time_point t0 = Clock::now();
  for (;;) {
    const double left = seconds - since_s(t0);
    if (left <= 0.0 || stopping.load()) return 0;
    pollfd p{fd, ev, 0};
    const int ms = static_cast<int>(std::min(left, 0.1) * 1000.0) + 1;
    const int r = ::poll(&p, 1, ms);
    if (r > 0) return (p.revents & (ev | POLLHUP | POLLERR)) ? 1 : -1;
    if (r < 0 && errno != EINTR) return -1;
  }
}

// cpp-httplib's view of a gated connection: the header from memory, the
// body from the socket within a budget, each wait bounded.
class GateStream : public httplib::Stream {
 public:
  GateStream(Conn& c, const GateLimits& lim, const std::atomic<bool>& stopping)
      : c_(c), lim_(lim), stopping_(stopping), budget_(lim.body_max)
  {
  }
  bool failed = false;

  bool is_readable() const override
  {
    return c_.pos < c_.buf.size() || wait_for(c_.fd, POLLIN, lim_.io_timeout, stopping_) > 0;
  }
  bool is_writable() const override { return wait_for(c_.fd, POLLOUT, lim_.io_timeout, stopping_) > 0; }
  ssize_t read(char* ptr, size_t size) override
  {
    if (c_.pos < c_.buf.size()) {
      const size_t n = std::min(size, c_.buf.size() - c_.pos);
      std::memcpy(ptr, c_.buf.data() + c_.pos, n);
      c_.pos += n;
      if (c_.pos == c_.buf.size()) {
        c_.buf.clear();
        c_.pos = 0;
      }
      return static_cast<ssize_t>(n);
    }
    if (budget_ == 0 || wait_for(c_.fd, POLLIN, lim_.io_timeout, stopping_) <= 0) {
      failed = true;
      return -1;
    }
    const ssize_t n = ::recv(c_.fd, ptr, std::min(size, budget_), 0);
    if (n > 0) budget_ -= static_cast<size_t>(n);
    if (n <= 0) failed = true;
    return n;
  }
  ssize_t write(const char* ptr, size_t size) override
  {
    size_t done = 0;
    while (done < size) {
      if (wait_for(c_.fd, POLLOUT, lim_.io_timeout, stopping_) <= 0) {
        failed = true;
        return -1;
      }
      const ssize_t n = ::send(c_.fd, ptr + done, size - done, MSG_NOSIGNAL);
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) continue;
      if (n <= 0) {
        failed = true;
        return -1;
      }
      done += static_cast<size_t>(n);
    }
    return static_cast<ssize_t>(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(true, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(false, ip, port); }
  socket_t socket() const override { return c_.fd; }

 private:
  void address(bool peer, std::string& ip, int& port) const
  {
    sockaddr_storage a{};
    socklen_t n = sizeof(a);
    const int r = peer ? ::getpeername(c_.fd, reinterpret_cast<sockaddr*>(&a), &n)
                       : ::getsockname(c_.fd, reinterpret_cast<sockaddr*>(&a), &n);
    ip.clear();
    port = 0;
    if (r != 0) return;
    char s[INET6_ADDRSTRLEN] = {0};
    if (a.ss_family == AF_INET) {
      const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
      ::inet_ntop(AF_INET, &v4->sin_addr, s, sizeof(s));
      port = ntohs(v4->sin_port);
    } else if (a.ss_family == AF_INET6) {
      const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
      ::inet_ntop(AF_INET6, &v6->sin6_addr, s, sizeof(s));
      port = ntohs(v6->sin6_port);
    }
    ip = s;
  }
  Conn& c_;
  const GateLimits& lim_;
  const std::atomic<bool>& stopping_;
  size_t budget_;
};

}  // namespace

struct GatedServer::Impl {
  GatedServer* owner = nullptr;
  GateLimits lim;
  std::atomic<bool> stopping{false};
  int wake[2] = {-1, -1};  // the poller's self-pipe
  int listen_fd = -1;

  mutable std::mutex mu;
  std::condition_variable ready_cv;
  std::vector<Conn*> incoming;  // new or returned by a worker (under mu)
  std::deque<Conn*> ready;      // complete header, for a worker (under mu)
  size_t open = 0;              // connections open (under mu)
  std::vector<Conn*> waiting;   // the poller's own
  GateCounters n;               // under mu

  std::thread poller;
  std::vector<std::thread> workers;

  void poke() { (void)!::write(wake[1], "x", 1); }
  // closes (when not yet) and forgets a connection
  void drop(Conn* c)
  {
    if (c->fd >= 0) ::close(c->fd);
    delete c;
    std::lock_guard<std::mutex> lk(mu);
    --open;
  }
  void hand(Conn* c)
  {
    std::lock_guard<std::mutex> lk(mu);
    ready.push_back(c);
    ready_cv.notify_one();
  }
  enum class Read { Keep, Ready, Drop };
  void poll_loop();
  void take_incoming();
  Read read_header(Conn* c);
  void expire();
  void work_loop();
};

void GatedServer::Impl::take_incoming()
{
  std::vector<Conn*> in;
  {
    std::lock_guard<std::mutex> lk(mu);
    in.swap(incoming);
  }
  for (Conn* c : in) {
    if (c->served == 0 && c->buf.empty()) {  // a new connection
      size_t now_open = 0;
      {
        std::lock_guard<std::mutex> lk(mu);
        now_open = open;
      }
      if (now_open > lim.max_connections) {
        if (waiting.empty()) {  // every other one is being answered
          {
            std::lock_guard<std::mutex> lk(mu);
            ++n.busy_refused;
          }
          send_status_and_close(c->fd, 503, "Service Unavailable");
          c->fd = -1;
          drop(c);
          continue;
        }
        // the one that has waited longest without a complete request
        auto oldest = std::min_element(waiting.begin(), waiting.end(),
                                       [](const Conn* a, const Conn* b) { return a->entered < b->entered; });
        Conn* o = *oldest;
        waiting.erase(oldest);
        {
          std::lock_guard<std::mutex> lk(mu);
          ++n.evicted;
        }
        drop(o);
      }
    }
    if (header_complete(*c)) {  // a kept-alive connection's next request came with the last
      hand(c);
      continue;
    }
    c->started = c->pos < c->buf.size();
    c->since = c->entered = Clock::now();
    waiting.push_back(c);
  }
}

GatedServer::Impl::Read GatedServer::Impl::read_header(Conn* c)
{
  char tmp[4096];
  for (;;) {
    const size_t room = lim.header_max - std::min(lim.header_max, c->buf.size() - c->pos);
    if (room == 0) {
      {
        std::lock_guard<std::mutex> lk(mu);
        ++n.large_closed;
      }
      send_status_and_close(c->fd, 431, "Request Header Fields Too Large");
      c->fd = -1;
      return Read::Drop;
    }
    const ssize_t r = ::recv(c->fd, tmp, std::min(room, sizeof(tmp)), MSG_DONTWAIT);
    if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return Read::Keep;
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return Read::Drop;  // closed by the peer, or an error
    if (!c->started) {
      c->started = true;
      c->since = Clock::now();
    }
    c->buf.append(tmp, static_cast<size_t>(r));
    if (header_complete(*c)) return Read::Ready;
  }
}

void GatedServer::Impl::expire()
{
  std::vector<Conn*> keep;
  for (Conn* c : waiting) {
    const double w = since_s(c->since);
    if (!c->started && w > lim.idle_timeout) {
      {
        std::lock_guard<std::mutex> lk(mu);
        ++n.idle_closed;
      }
      drop(c);
    } else if (c->started && w > lim.header_timeout) {
      {
        std::lock_guard<std::mutex> lk(mu);
        ++n.slow_closed;
      }
      send_status_and_close(c->fd, 408, "Request Timeout");
      c->fd = -1;
      drop(c);
    } else {
      keep.push_back(c);
    }
  }
  waiting.swap(keep);
}

void GatedServer::Impl::poll_loop()
{
  std::vector<pollfd> fds;
  while (!stopping.load()) {
    take_incoming();
    fds.assign(1, pollfd{wake[0], POLLIN, 0});
    for (Conn* c : waiting) fds.push_back(pollfd{c->fd, POLLIN, 0});
    const int r = ::poll(fds.data(), fds.size(), 50);
    if (r < 0 && errno != EINTR) break;
    if (fds[0].revents & POLLIN) {
      char b[64];
      while (::read(wake[0], b, sizeof(b)) > 0) {
      }
    }
    std::vector<Conn*> keep;
    for (size_t i = 0; i < waiting.size(); ++i) {
      Conn* c = waiting[i];
      const Read what = fds[i + 1].revents == 0 ? Read::Keep : read_header(c);
      if (what == Read::Keep) keep.push_back(c);
      if (what == Read::Ready) hand(c);
      if (what == Read::Drop) drop(c);
    }
    waiting.swap(keep);
    expire();
  }
}

void GatedServer::Impl::work_loop()
{
  for (;;) {
    Conn* c = nullptr;
    {
      std::unique_lock<std::mutex> lk(mu);
      ready_cv.wait(lk, [this] { return stopping.load() || !ready.empty(); });
      if (stopping.load()) return;
      c = ready.front();
      ready.pop_front();
    }
    GateStream strm(*c, lim, stopping);
    bool closed = false;
    const bool last = c->served + 1 >= lim.keep_alive_max;
    c->close_after = true;  // unless the request is admitted (keep_connection_open)
    t_current = c;
    const bool ok = owner->process_request(strm, last, closed, [](httplib::Request&) {});
    t_current = nullptr;
    ++c->served;
    if (!ok || closed || last || c->close_after || strm.failed || stopping.load()) {
      ::shutdown(c->fd, SHUT_WR);
      drop(c);
      continue;
    }
    {
      std::lock_guard<std::mutex> lk(mu);
      incoming.push_back(c);
    }
    poke();
  }
}

GatedServer::GatedServer(GateLimits lim) : impl_(std::make_unique<Impl>())
{
  Impl& m = *impl_;
  m.owner = this;
  m.lim = lim;
  if (::pipe(m.wake) != 0) throw std::runtime_error("live view: cannot create a pipe");
  ::fcntl(m.wake[0], F_SETFL, O_NONBLOCK);
  ::fcntl(m.wake[1], F_SETFL, O_NONBLOCK);
  new_task_queue = [] { return new InlineQueue; };
  // the listening socket: SO_REUSEADDR (not cpp-httplib's SO_REUSEPORT,
  // which lets another process of the user bind the same port), and kept
  // to widen its backlog after bind
  set_socket_options([&m](socket_t s) {
    const int yes = 1;
    ::setsockopt(s, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    m.listen_fd = s;
  });
  set_payload_max_length(lim.body_max);
  m.poller = std::thread([&m] { m.poll_loop(); });
  for (size_t i = 0; i < std::max<size_t>(1, lim.workers); ++i) m.workers.emplace_back([&m] { m.work_loop(); });
}

GatedServer::~GatedServer() { stop_gate(); }

int GatedServer::bind_gated(const std::string& host, int port)
{
  int p = -1;
  if (port == 0) {
    p = bind_to_any_port(host);
  } else if (bind_to_port(host, port)) {
    p = port;
  }
  if (p > 0 && impl_->listen_fd >= 0) ::listen(impl_->listen_fd, kBacklog);  // on a listening socket: its new backlog
  return p > 0 ? p : -1;
}

void GatedServer::stop_gate()
{
  Impl& m = *impl_;
  if (m.stopping.exchange(true)) return;
  m.poke();
  {
    std::lock_guard<std::mutex> lk(m.mu);
    m.ready_cv.notify_all();
  }
  if (m.poller.joinable()) m.poller.join();
  for (std::thread& t : m.workers)
    if (t.joinable()) t.join();
  std::lock_guard<std::mutex> lk(m.mu);
  for (Conn* c : m.waiting) {
    ::close(c->fd);
    delete c;
  }
  for (Conn* c : m.incoming) {
    ::close(c->fd);
    delete c;
  }
  for (Conn* c : m.ready) {
    ::close(c->fd);
    delete c;
  }
  m.waiting.clear();
  m.incoming.clear();
  m.ready.clear();
  ::close(m.wake[0]);
  ::close(m.wake[1]);
}

bool GatedServer::process_and_close_socket(socket_t sock)
{
  // on the accepting thread: hand the socket to the poller (which keeps
  // max_connections: it closes the longest-waiting one, or answers 503)
  Impl& m = *impl_;
  if (m.stopping.load()) {
    ::close(sock);
    return false;
  }
  ::fcntl(sock, F_SETFL, ::fcntl(sock, F_GETFL) | O_NONBLOCK);
  auto* c = new Conn;
  c->fd = sock;
  {
    std::lock_guard<std::mutex> lk(m.mu);
    ++m.n.connections;
    ++m.open;
    m.incoming.push_back(c);
  }
  m.poke();
  return true;
}

void GatedServer::close_after_answer()
{
  if (t_current) t_current->close_after = true;
}

void GatedServer::keep_connection_open()
{
  if (t_current) t_current->close_after = false;
}

GateCounters GatedServer::gate_counters() const
{
  std::lock_guard<std::mutex> lk(impl_->mu);
  return impl_->n;
}

const GateLimits& GatedServer::limits() const { return impl_->lim; }

}  // namespace harness

// The live view (docs/live.md): commands enter a run at tick boundaries as
// scenario events and the manifest replays them bit for bit; the server
// refuses bad commands (the scenario event validation) and requests without
// the access token, and applies nothing then.
#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "harness/drive/run_scenario.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"
#include "live_test_util.h"

using namespace live_test;

namespace {

std::string text_of(const fs::path& p)
{
  std::ifstream in(p);
  std::ostringstream o;
  o << in.rdbuf();
  return o.str();
}

// A scripted controller: at given ticks it adds an action as the live view
// does (an event {t = t_k, actions}), without a server.
class Scripted : public harness::RunControl {
 public:
  struct At {
    uint64_t tick;
    harness::EventActionSpec action;
  };
  explicit Scripted(std::vector<At> plan) : plan_(std::move(plan)) {}
  void started(harness::Run&, double, const std::atomic<int>*) override {}
  uint64_t boundary(harness::Run& run, double&) override
  {
    const uint64_t k = run.tick();
    for (const At& a : plan_)
      if (a.tick == k) {
        harness::EventSpec e;
        e.name = "live" + std::to_string(++n_);
        e.t = static_cast<double>(k * run.scenario().tick_ns()) / 1e9;
        e.actions.push_back(a.action);
        run.add_event(e);
      }
    // the next boundary at the next planned tick (tests the chunking too)
    uint64_t next = run.total_ticks();
    for (const At& a : plan_)
      if (a.tick > k && a.tick < next) next = a.tick;
    return next - k;
  }
  void ended(const harness::Run&, const harness::RunResult&) override { ended_ = true; }
  bool ended_ = false;

 private:
  std::vector<At> plan_;
  int n_ = 0;
};

bool same(const std::vector<double>& a, const std::vector<double>& b)
{
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  return true;
}

}  // namespace

// rw2 failed at tick 30 (t = 7.5 s) and flagged unavailable at tick 31 by the
// controller: its torque is zero in the row of tick 30 and after (fail_off
// zeroes u_s at once, docs/events.md) and not in the row before; the manifest
// lists both as scenario events (t = 7.5 exactly: 30 * 0.25e9 ns / 1e9, where
// * 1e-9 would give 7.500000000000001) and reruns bit for bit.
TEST(LiveControl, CommandsAtTickBoundariesReplayFromTheManifest)
{
  const fs::path dir = temp_dir("replay");
  const harness::Scenario sc = harness::load_scenario(kS1, fast());
  ASSERT_TRUE(sc.events.empty());
  Scripted ctl({{30, {"rw2", "fail_off"}}, {31, {"rw2", "command_unavailable"}}});
  harness::RunOptions opt;
  opt.out_dir = (dir / "live").string();
  opt.control = &ctl;
  const harness::RunResult a = harness::run_scenario(sc, opt);
  ASSERT_TRUE(a.ok) << a.failure;
  EXPECT_TRUE(ctl.ended_);
  const harness::Hdf5Table h = harness::read_hdf5((dir / "live" / "results.h5").string());
  ASSERT_EQ(h.events.size(), 2u);
  EXPECT_EQ(h.events[0].tick, 30u);
  EXPECT_EQ(h.events[0].t, 7.5);
  EXPECT_EQ(h.events[1].tick, 31u);
  EXPECT_EQ(h.events[0].what, "rw2 fail_off");
  // rw2 = wheel 1: torque zero from the row of tick 30 on, not before
  size_t ct = 0, cw = 0;
  for (size_t c = 0; c < h.names.size(); ++c) {
    if (h.names[c] == "t") ct = c;
    if (h.names[c] == "wheel_torque_1") cw = c;
  }
  ASSERT_GT(cw, 0u);
  const size_t nc = h.names.size();
  ASSERT_EQ(h.rows, 241u);  // 60 s at 4 Hz, both ends
  EXPECT_EQ(h.data[30 * nc + ct], 7.5);
  EXPECT_NE(h.data[29 * nc + cw], 0.0);  // the PD loop is acquiring at 7.25 s
  for (uint64_t r = 30; r < h.rows; ++r) ASSERT_EQ(h.data[r * nc + cw], 0.0) << "row " << r;
  // the manifest: the scenario with both events, as a scenario file lists them
  const json man = json::parse(text_of(dir / "live" / "manifest.json"));
  ASSERT_EQ(man["scenario"]["events"].size(), 2u);
  EXPECT_EQ(man["scenario"]["events"][0]["t"].get<double>(), 7.5);
  EXPECT_EQ(man["result"]["events_applied"].size(), 2u);
  // rerun from the manifest (no controller): bit for bit
  harness::RunOptions opt2;
  opt2.out_dir = (dir / "replay").string();
  const harness::Scenario again = harness::load_scenario((dir / "live" / "manifest.json").string());
  ASSERT_EQ(again.events.size(), 2u);
  const harness::RunResult b = harness::run_scenario(again, opt2);
  ASSERT_TRUE(b.ok) << b.failure;
  const harness::Hdf5Table h2 = harness::read_hdf5((dir / "replay" / "results.h5").string());
  EXPECT_TRUE(same(h.data, h2.data));
  ASSERT_EQ(h2.events.size(), 2u);
  EXPECT_EQ(h2.events[1].tick, 31u);
  // and a controller that adds nothing changes nothing: the run without one
  Scripted idle({});
  harness::RunOptions opt3;
  opt3.out_dir = (dir / "idle").string();
  opt3.control = &idle;
  ASSERT_TRUE(harness::run_scenario(sc, opt3).ok);
  harness::RunOptions opt4;
  opt4.out_dir = (dir / "plain").string();
  ASSERT_TRUE(harness::run_scenario(sc, opt4).ok);
  EXPECT_TRUE(same(harness::read_hdf5((dir / "idle" / "results.h5").string()).data,
                   harness::read_hdf5((dir / "plain" / "results.h5").string()).data));
  fs::remove_all(dir);
}

// An action the scenario cannot take is refused by Run::add_event (the
// scenario event validation) and nothing is added.
TEST(LiveControl, AddEventRefusesWhatTheScenarioCannotTake)
{
  const harness::Scenario sc = harness::load_scenario(kS1, fast());
  harness::RunConfig cfg;
  cfg.accept_events = true;
  harness::Run run(sc, std::move(cfg));
  harness::EventSpec e;
  e.name = "x";
  e.t = 0.0;
  e.actions.push_back({"rw9", "fail_off"});
  EXPECT_THROW(run.add_event(e), harness::ScenarioError);
  e.actions[0] = {"rw2", "stuck_open"};
  EXPECT_THROW(run.add_event(e), harness::ScenarioError);
  EXPECT_TRUE(run.scenario().events.empty());
  harness::Run plain(sc);  // without accept_events
  e.actions[0] = {"rw2", "fail_off"};
  EXPECT_THROW(plain.add_event(e), std::logic_error);
}

TEST(LiveServer, TokenBadCommandsRefusedNothingApplied)
{
  const fs::path dir = temp_dir("server");
  harness::LiveOptions lo;
  lo.start_paused = true;  // the run waits at the boundary after tick 0
  Served s(lo);
  ASSERT_GT(s.srv.port(), 0);
  EXPECT_EQ(s.srv.token().size(), 32u);  // 128 bits, hex
  EXPECT_NE(s.srv.url().find("http://127.0.0.1:" + std::to_string(s.srv.port()) + "/?token=" + s.srv.token()),
            std::string::npos);
  harness::RunResult res;
  std::thread sim = s.start_run(dir / "run", res);
  ASSERT_TRUE(s.started());

  // the token: missing or wrong -> 403, for the page and the API
  EXPECT_EQ(s.cli.Get("/")->status, 403);
  EXPECT_EQ(s.cli.Get("/?token=" + std::string(32, '0'))->status, 403);
  EXPECT_EQ(s.cli.Get("/?token=" + s.srv.token())->status, 200);
  EXPECT_EQ(s.cli.Get("/api/info")->status, 403);
  EXPECT_EQ(s.cli.Get("/api/frames", s.auth("nope"))->status, 403);
  const json fail2 = {{"op", "event"}, {"device", "rw2"}, {"action", "fail_off"}};
  EXPECT_EQ(s.post(fail2, "")->status, 403);
  EXPECT_EQ(s.post(fail2, s.srv.token().substr(1) + "x")->status, 403);

  // bad commands: the scenario event validation's messages (events.cpp)
  auto r = s.post_ok({{"op", "event"}, {"device", "rw9"}, {"action", "fail_off"}});
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(error_of(r).find("device: no device named 'rw9' (devices: rw1, rw2, rw3, rw4"), std::string::npos)
      << error_of(r);
  // a name with a right-to-left override (U+202E) is quoted escaped
  r = s.post_ok({{"op", "event"}, {"device", "rw\xe2\x80\xae" "9"}, {"action", "fail_off"}});
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(error_of(r).find("no device named 'rw\\u202E9'"), std::string::npos) << error_of(r);
  r = s.post_ok({{"op", "event"}, {"device", "rw2"}, {"action", "stuck_open"}});
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(error_of(r).find("action: a wheel takes one of {fail_off"), std::string::npos) << error_of(r);
  r = s.post_ok({{"op", "event"}, {"device", "rw2"}, {"action", "torque_limit"}});
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(error_of(r).find("needs a value > 0"), std::string::npos) << error_of(r);
  r = s.post_ok({{"op", "event"}, {"device", "rw2"}, {"action", "fail_off"}, {"value", 3}});
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(error_of(r).find("takes no value"), std::string::npos) << error_of(r);
  r = s.post_ok({{"op", "event"}, {"device", "gyro"}, {"action", "dropout"}, {"value", -1}});
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(s.post_ok({{"op", "explode"}})->status, 400);
  EXPECT_EQ(s.post_ok({{"op", "rate"}, {"value", -1}})->status, 400);
  // a rate outside [1e-6, 1e6] (the pacer's range: 1e-300 used to overflow its deadlines)
  for (double bad : {1e-300, 9.9e-7, 1.01e6}) {
    r = s.post_ok({{"op", "rate"}, {"value", bad}});
    EXPECT_EQ(r->status, 400) << bad;
    EXPECT_NE(error_of(r).find("rate: value: a real-time scale is in [1e-6, 1e6]"), std::string::npos) << error_of(r);
  }
  EXPECT_EQ(s.post_ok({{"op", "step"}, {"ticks", 0}})->status, 400);
  EXPECT_EQ(s.cli.Post("/api/command", s.auth(s.srv.token()), "not json", "application/json")->status, 400);

  // step 29 ticks while paused: the run is at the boundary before tick 30, paused
  EXPECT_EQ(s.post_ok({{"op", "step"}, {"ticks", 29}})->status, 202);
  ASSERT_TRUE(wait_for([&] {
    const json f = s.frames();
    return !f.is_null() && f["state"] == "paused" && !f["frames"].empty() && f["frames"].back()["tick"] == 30;
  }));
  // a good command enters at the next boundary (tick 30), then resume
  r = s.post_ok(fail2);
  EXPECT_EQ(r->status, 202);
  // a rate turns pacing on in this unpaced run: the rest (ticks 30..240) at
  // 1000x real time, 0.25 ms of wall time a tick after the first, which is
  // due at once (Pacer::restart)
  EXPECT_EQ(s.post_ok({{"op", "rate"}, {"value", 1000}})->status, 202);
  EXPECT_EQ(s.post_ok({{"op", "resume"}})->status, 202);
  sim.join();
  ASSERT_TRUE(res.ok) << res.failure;
  EXPECT_TRUE(res.paced);
  EXPECT_EQ(res.pacing.scale, 1000.0);
  EXPECT_EQ(res.pacing.ticks, 211u);
  // the running wall time (the pauses taken off) covers the deadlines
  EXPECT_GE(res.wall_seconds - s.srv.counters().paused_s, 210 * 0.25e-3);
  EXPECT_EQ(s.post_ok({{"op", "pause"}})->status, 409);  // ended

  // exactly one event: the good one, at tick 30 (t = 7.5 s exactly: k tick_ns / 1e9)
  const json man = json::parse(text_of(dir / "run" / "manifest.json"));
  ASSERT_EQ(man["scenario"]["events"].size(), 1u);
  EXPECT_EQ(man["scenario"]["events"][0]["t"].get<double>(), 7.5);
  ASSERT_EQ(man["result"]["events_applied"].size(), 1u);
  EXPECT_EQ(man["result"]["events_applied"][0]["tick"].get<uint64_t>(), 30u);
  EXPECT_EQ(man["result"]["events_applied"][0]["actions"], "rw2 fail_off");
  const harness::LiveCounters n = s.srv.counters();
  EXPECT_EQ(n.commands_applied, 4u);  // step, the event, rate, resume
  EXPECT_EQ(n.commands_refused, 13u + 1u);  // 13 bad commands, 1 after the end
  EXPECT_EQ(n.requests_unauthorised, 6u);     // apart: refused before their body was read
  EXPECT_EQ(n.requests_refused, 0u);
  const json f = s.frames();
  EXPECT_EQ(f["state"], "ended");
  EXPECT_EQ(f["report"], "/report");
  fs::remove_all(dir);
}

// ---- before authentication: the body, the connections ------------------------

namespace {

double since_s(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int connect_to(int port)
{
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
    if (fd >= 0) ::close(fd);
    return -1;
  }
  return fd;
}

bool send_all(int fd, const std::string& s)
{
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::send(fd, s.data() + done, s.size() - done, MSG_NOSIGNAL);
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

// What the server sends until it closes the connection (or `limit_s`).
std::string read_until_closed(int fd, double limit_s, bool* closed = nullptr)
{
  std::string got;
  const auto t0 = std::chrono::steady_clock::now();
  char b[4096];
  if (closed) *closed = false;
  while (since_s(t0) < limit_s) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) continue;
    const ssize_t n = ::recv(fd, b, sizeof(b), 0);
    if (n <= 0) {
      if (closed) *closed = true;
      break;
    }
    got.append(b, static_cast<size_t>(n));
  }
  return got;
}

int status_of(const std::string& answer)
{
  return answer.size() >= 12 && answer.compare(0, 9, "HTTP/1.1 ") == 0 ? std::stoi(answer.substr(9, 3)) : -1;
}

long rss_kb()
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

}  // namespace

// A body is never read before the token and its size and encoding are
// checked from the header: a request claiming 200 MB is answered at once
// (403 without the token, 413 with it) and its connection closed, so the
// 200 MB cannot be sent (the server reads none of it: memory stays flat);
// a compressed or chunked body is refused; `Expect: 100-continue` without
// the token gets 403, never "100 Continue".  Counted apart from commands.
TEST(LiveServer, RefusesBeforeReadingTheBody)
{
  harness::LiveOptions lo;
  harness::LiveServer srv(lo);
  const std::string tok = srv.token();
  const long rss0 = rss_kb();
  const std::string big = "POST /api/command HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
                          "Content-Length: 209715200\r\n";
  const std::string chunk(1 << 20, 'x');
  for (const std::string& who : {std::string(""), "X-Kestrel-Token: " + tok + "\r\n"}) {
    const int fd = connect_to(srv.port());
    ASSERT_GE(fd, 0);
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_TRUE(send_all(fd, big + who + "\r\n"));
    bool closed = false;
    const std::string ans = read_until_closed(fd, 5.0, &closed);
    const double dt = since_s(t0);
    EXPECT_EQ(status_of(ans), who.empty() ? 403 : 413) << ans;
    EXPECT_TRUE(closed) << "the connection stays open after refusing a 200 MB body";
    EXPECT_LT(dt, 2.0);
    std::printf("200 MB body %s: %d in %.1f ms, connection closed\n", who.empty() ? "without the token" : "with it",
                status_of(ans), dt * 1e3);
    // the body can no longer be sent: the server closed before reading it
    size_t sent = 0;
    while (sent < (200u << 20) && send_all(fd, chunk)) sent += chunk.size();
    EXPECT_LT(sent, 200u << 20);
    std::printf("  then %zu MB of the body were accepted by the sockets before the send failed\n", sent >> 20);
    ::close(fd);
  }
  const long rss1 = rss_kb();
  std::printf("resident memory: %ld kB before, %ld kB after\n", rss0, rss1);
  EXPECT_LT(rss1 - rss0, 32 * 1024);  // not the 200 MB (nor the 1.1 GB once measured)

  auto one = [&](const std::string& req) {
    const int fd = connect_to(srv.port());
    EXPECT_GE(fd, 0);
    EXPECT_TRUE(send_all(fd, req));
    bool closed = false;
    const std::string ans = read_until_closed(fd, 5.0, &closed);
    EXPECT_TRUE(closed) << req;
    ::close(fd);
    return ans;
  };
  const std::string post = "POST /api/command HTTP/1.1\r\nHost: x\r\nX-Kestrel-Token: " + tok + "\r\n";
  // gzip (a 509 kB gzip body once expanded to 512 MB): refused, whatever it holds
  std::string a = one(post + "Content-Encoding: gzip\r\nContent-Length: 20\r\n\r\n" + std::string(20, '\0'));
  EXPECT_EQ(status_of(a), 415) << a;
  EXPECT_NE(a.find("compressed request bodies are refused (Content-Encoding: gzip)"), std::string::npos) << a;
  a = one(post + "Content-Encoding: deflate\r\nContent-Length: 2\r\n\r\n{}");
  EXPECT_EQ(status_of(a), 415) << a;
  a = one(post + "Transfer-Encoding: chunked\r\n\r\n2\r\n{}\r\n0\r\n\r\n");
  EXPECT_EQ(status_of(a), 411) << a;
  a = one(post + "Content-Length: 99999999999999999999999\r\n\r\n");
  EXPECT_EQ(status_of(a), 413) << a;
  a = one("POST /api/command HTTP/1.1\r\nHost: x\r\nExpect: 100-continue\r\nContent-Length: 209715200\r\n\r\n");
  EXPECT_EQ(status_of(a), 403) << a;
  EXPECT_EQ(a.find("100 Continue"), std::string::npos) << a;
  // a header ended by bare line feeds is answered at once (cpp-httplib
  // reads CRLF lines only: 400), not held until the 2 s header time (408)
  const auto tb = std::chrono::steady_clock::now();
  a = one("GET /?token=" + tok + " HTTP/1.1\nHost: x\nConnection: close\n\n");
  EXPECT_EQ(status_of(a), 400) << a;
  EXPECT_LT(since_s(tb), 1.0);
  // a body within the cap, with the token, is read (the run has not started: 409)
  httplib::Client cli("127.0.0.1", srv.port());
  auto r = cli.Post("/api/command", {{"X-Kestrel-Token", tok}}, std::string("{\"op\":\"pause\"}"), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
  const harness::LiveCounters n = srv.counters();
  EXPECT_EQ(n.requests_unauthorised, 2u);
  EXPECT_EQ(n.requests_refused, 4u + 1u);  // 413 twice, 415 twice, 411 (gzip, deflate, chunked, two sizes)
  EXPECT_EQ(n.commands_refused, 1u);       // the 409 only
}

// No number of idle or slow clients holds the page: 200 idle connections
// (the server keeps at most 64 and closes the longest-waiting one for a new
// one) and 30 that send their header a byte every 100 ms (each is read by
// the poller, never by a worker, and closed 2 s after its first byte) while
// the page and the API answer; a header over 16 kB is refused (431).
TEST(LiveServer, IdleAndSlowConnectionsDoNotHoldThePage)
{
  harness::LiveOptions lo;
  harness::LiveServer srv(lo);
  const std::string page = "/?token=" + srv.token();
  std::vector<int> idle;
  const auto tc = std::chrono::steady_clock::now();
  for (int i = 0; i < 200; ++i) {
    const int fd = connect_to(srv.port());
    ASSERT_GE(fd, 0) << i;
    idle.push_back(fd);
  }
  std::printf("200 idle connections opened in %.1f ms\n", since_s(tc) * 1e3);
  httplib::Client cli("127.0.0.1", srv.port());
  cli.set_connection_timeout(5);
  cli.set_read_timeout(5);
  auto t0 = std::chrono::steady_clock::now();
  auto r = cli.Get(page.c_str());
  const double t_idle = since_s(t0);
  ASSERT_TRUE(r) << "no answer with 200 idle connections open";
  EXPECT_EQ(r->status, 200);
  EXPECT_LT(t_idle, 2.0);
  std::printf("page answered in %.1f ms with 200 idle connections open\n", t_idle * 1e3);

  // slowloris: 30 connections, a header byte each every 100 ms
  std::atomic<bool> done{false};
  std::vector<int> slow;
  for (int i = 0; i < 30; ++i) slow.push_back(connect_to(srv.port()));
  std::thread drip([&] {
    const std::string hdr = "GET / HTTP/1.1\r\nHost: x\r\nX-Padding: " + std::string(1000, 'a');
    for (size_t k = 0; k < hdr.size() && !done.load(); ++k) {
      for (int fd : slow) (void)!::send(fd, &hdr[k], 1, MSG_NOSIGNAL | MSG_DONTWAIT);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  double worst = 0.0;
  for (int i = 0; i < 10; ++i) {
    httplib::Client c2("127.0.0.1", srv.port());
    c2.set_read_timeout(5);
    t0 = std::chrono::steady_clock::now();
    auto r2 = c2.Get("/api/frames", {{"X-Kestrel-Token", srv.token()}});
    worst = std::max(worst, since_s(t0));
    ASSERT_TRUE(r2) << "no answer during the slow headers";
    EXPECT_EQ(r2->status, 200);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_LT(worst, 2.0);
  std::printf("during 30 slow headers: 10 requests, the slowest answered in %.1f ms\n", worst * 1e3);
  // the slow ones are closed 2 s after their first byte (408)
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  done.store(true);
  drip.join();
  int got408 = 0;
  for (int fd : slow) {
    const std::string a = read_until_closed(fd, 1.0);
    got408 += status_of(a) == 408;
    ::close(fd);
  }
  EXPECT_EQ(got408, 30);
  std::printf("slow connections answered 408 and closed (%.1f s into the test)\n", since_s(tc));

  // a header that never ends within 16 kB
  const int fd = connect_to(srv.port());
  ASSERT_GE(fd, 0);
  send_all(fd, "GET / HTTP/1.1\r\nX-Big: " + std::string(20000, 'b'));
  EXPECT_EQ(status_of(read_until_closed(fd, 3.0)), 431);
  ::close(fd);
  for (int f : idle) ::close(f);
  const harness::LiveCounters n = srv.counters();
  EXPECT_GE(n.connections, 200u + 1 + 30 + 10 + 1);
  EXPECT_GE(n.connections_closed, 200u - 64u + 30u + 1u);  // evicted, slow, too large
  EXPECT_EQ(n.requests_unauthorised, 0u);
}

// The command log keeps the last 1000 commands; /api/frames carries the
// last 64 (every queued one: at most 64 wait) and /api/commands pages back
// through the rest, 64 at most per answer.
TEST(LiveServer, CommandLogIsBoundedAndPages)
{
  const fs::path dir = temp_dir("log");
  Served s(paused_options());
  harness::RunResult res;
  std::thread sim = s.start_run(dir / "run", res);
  ASSERT_TRUE(s.started());
  // 1100 pauses: each applied at once by the paused run (a 429 when the
  // queue is full is retried)
  for (int i = 0; i < 1100;) {
    auto r = s.post_ok({{"op", "pause"}});
    ASSERT_TRUE(r);
    if (r->status == 429) continue;
    ASSERT_EQ(r->status, 202);
    ++i;
  }
  const json f = s.frames();
  EXPECT_EQ(f["commands_total"], 1100u);
  ASSERT_EQ(f["commands"].size(), 64u);
  EXPECT_EQ(f["commands"].front()["id"], 1037u);
  EXPECT_EQ(f["commands"].back()["id"], 1100u);
  auto page = [&](const std::string& q) {
    auto r = s.cli.Get(("/api/commands" + q).c_str(), s.auth(s.srv.token()));
    return r && r->status == 200 ? json::parse(r->body) : json();
  };
  json p = page("?before=1037");
  ASSERT_EQ(p["commands"].size(), 64u);
  EXPECT_EQ(p["commands"].front()["id"], 973u);
  EXPECT_EQ(p["commands"].back()["id"], 1036u);
  EXPECT_EQ(p["more"], true);
  EXPECT_EQ(p["first_kept"], 101u);  // 1100 - 1000 + 1: the first 100 are forgotten
  p = page("?before=150&limit=10");
  ASSERT_EQ(p["commands"].size(), 10u);
  EXPECT_EQ(p["commands"].front()["id"], 140u);
  p = page("?before=120");
  ASSERT_EQ(p["commands"].size(), 19u);  // 101..119
  EXPECT_EQ(p["more"], false);
  EXPECT_TRUE(page("?before=50")["commands"].empty());
  EXPECT_EQ(page("")["commands"].back()["id"], 1100u);
  for (const char* bad : {"?limit=0", "?limit=65", "?before=x", "?before=-1"}) {
    auto r = s.cli.Get((std::string("/api/commands") + bad).c_str(), s.auth(s.srv.token()));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << bad;
  }
  EXPECT_EQ(s.post_ok({{"op", "resume"}})->status, 202);
  sim.join();
  ASSERT_TRUE(res.ok) << res.failure;
  EXPECT_EQ(s.srv.counters().commands_applied, 1101u);
  fs::remove_all(dir);
}

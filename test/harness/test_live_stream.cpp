// The live view's push (docs/live.md, "Push"): GET /api/stream sends the
// frames as server-sent events, with the access token only; an unpaced run
// waits at t = 0 for a page (its simulated time does not advance before),
// and not forever; the gains in force follow a gain command.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "live_test_util.h"

using namespace live_test;

namespace {

// The messages of an event stream: each `id: N\ndata: JSON\n\n` (comment
// lines, the keep-alives, are skipped).
std::vector<json> messages_of(const std::string& text)
{
  std::vector<json> out;
  size_t at = 0;
  for (size_t end; (end = text.find("\n\n", at)) != std::string::npos; at = end + 2) {
    const std::string m = text.substr(at, end - at);
    const size_t d = m.find("data: ");
    if (d != std::string::npos) out.push_back(json::parse(m.substr(d + 6)));
  }
  return out;
}

// GET /api/stream until a message says the run ended, or (with `hold`)
// until *hold is false
struct Streamed {
  int status = 0;
  std::string type, text;
};
Streamed stream(int port, const std::string& token, const std::atomic<bool>* hold = nullptr)
{
  httplib::Client cli("127.0.0.1", port);
  cli.set_read_timeout(20, 0);
  Streamed s;
  auto r = cli.Get(("/api/stream?token=" + token).c_str(), [&](const char* d, size_t n) {
    s.text.append(d, n);
    return hold ? hold->load() : true;  // without: to the stream's end (after the run's)
  });
  if (r) {
    s.status = r->status;
    s.type = r->get_header_value("Content-Type");
  }
  return s;
}

}  // namespace

TEST(LiveStream, UnpacedRunWaitsForThePageThenPushesEveryFrameOnce)
{
  const fs::path dir = temp_dir("stream");
  harness::LiveOptions lo;
  lo.wait_unpaced = 30.0;
  Served s(lo);
  harness::RunResult res;
  std::atomic<bool> done{false};
  std::thread sim = s.start_run(dir / "run", res, &done);  // unpaced
  ASSERT_TRUE(s.started());  // /api/info is not a page
  // without the token: 403, and the run still waits (240 ticks unpaced take
  // milliseconds: after 0.4 s it would long be over)
  auto no = s.cli.Get("/api/stream");
  ASSERT_TRUE(no);
  EXPECT_EQ(no->status, 403);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  EXPECT_FALSE(done.load()) << "the unpaced run did not wait for a page";

  const Streamed st = stream(s.srv.port(), s.srv.token());
  sim.join();
  ASSERT_TRUE(res.ok) << res.failure;
  EXPECT_EQ(st.status, 200);
  EXPECT_EQ(st.type, "text/event-stream");
  const std::vector<json> m = messages_of(st.text);
  ASSERT_GE(m.size(), 2u) << st.text.substr(0, 400);
  // every frame once, in order, to the end: ticks 0..240 (t = 0..60 s at 0.25 s)
  std::vector<json> frames;
  for (const json& j : m)
    for (const json& f : j["frames"]) {
      if (!frames.empty()) {
        EXPECT_GT(f["seq"].get<uint64_t>(), frames.back()["seq"].get<uint64_t>());
      }
      frames.push_back(f);
    }
  const uint64_t n = frames.size();
  ASSERT_GE(n, 2u);
  // the first frame: the boundary after tick 0, t = 0, published when the
  // wait began; the next one only after the wait (about 0.4 s of wall time later)
  EXPECT_EQ(frames[0]["tick"], 1u);
  EXPECT_EQ(frames[0]["row"][0], 0.0);
  EXPECT_GE(frames[1]["wall"].get<double>() - frames[0]["wall"].get<double>(), 0.3);
  EXPECT_EQ(m.back()["state"], "ended");
  EXPECT_EQ(frames.back()["tick"], 241u);
  EXPECT_EQ(frames.back()["row"][0], 60.0);
  EXPECT_EQ(n, s.srv.counters().published);  // none missed
  const double waited = s.srv.counters().waited_s;
  EXPECT_GE(waited, 0.3);  // from after tick 0: a little less than the 0.4 s sleep on a loaded machine
  EXPECT_LT(waited, 20.0);
  std::printf("waited %.2f s for the page; %zu messages, %llu frames pushed\n", waited, m.size(),
              static_cast<unsigned long long>(n));
  fs::remove_all(dir);
}

TEST(LiveStream, WithoutAPageTheWaitEnds)
{
  const fs::path dir = temp_dir("nopage");
  harness::LiveOptions lo;
  lo.wait_unpaced = 0.3;
  Served s(lo);
  harness::RunResult res;
  std::thread sim = s.start_run(dir / "run", res);
  sim.join();
  ASSERT_TRUE(res.ok) << res.failure;
  EXPECT_GE(s.srv.counters().waited_s, 0.3);
  EXPECT_LT(s.srv.counters().waited_s, 5.0);
  fs::remove_all(dir);
}

// The gains in force: the scenario's mrp_fb gains, then a gain_K command's
// value once it applied (P unchanged); at most two streams at once.
TEST(LiveStream, GainsInForceAndStreamsBounded)
{
  const fs::path dir = temp_dir("gains");
  Served s(paused_options());
  harness::RunResult res;
  std::thread sim = s.start_run(dir / "run", res);
  ASSERT_TRUE(s.started());
  const harness::Scenario sc = harness::load_scenario(kS1, fast());
  const double K0 = sc.fsw.mrp_fb.K, P0 = sc.fsw.mrp_fb.P;
  ASSERT_TRUE(wait_for([&] { return s.frames()["state"] == "paused"; }));
  json f = s.frames();
  EXPECT_EQ(f["gains"]["K"], K0);
  EXPECT_EQ(f["gains"]["P"], P0);
  json info = json::parse(s.cli.Get("/api/info", s.auth(s.srv.token()))->body);
  EXPECT_EQ(info["gains"]["K"], K0);

  // two streams open (each holds a worker); a third is refused 503
  std::atomic<int> opened{0};
  std::atomic<bool> hold{true};
  std::vector<std::thread> open;
  for (int i = 0; i < 2; ++i)
    open.emplace_back([&] {
      const Streamed st = stream(s.srv.port(), s.srv.token(), &hold);
      if (!messages_of(st.text).empty() && st.text.find("\"gains\"") != std::string::npos) ++opened;
    });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto third = s.cli.Get(("/api/stream?token=" + s.srv.token()).c_str());
  hold = false;  // the two end at their next message or keep-alive (1 s)
  for (std::thread& t : open) t.join();
  EXPECT_EQ(opened.load(), 2);
  ASSERT_TRUE(third);
  EXPECT_EQ(third->status, 503);

  const double K1 = 0.5 * K0;
  ASSERT_EQ(s.post_ok({{"op", "event"}, {"device", "fsw"}, {"action", "gain_K"}, {"value", K1}})->status, 202);
  ASSERT_EQ(s.post_ok({{"op", "step"}, {"ticks", 1}})->status, 202);
  ASSERT_TRUE(wait_for([&] { return s.frames()["gains"]["K"] == K1; }));
  f = s.frames();
  EXPECT_EQ(f["gains"]["P"], P0);
  EXPECT_EQ(s.post_ok({{"op", "resume"}})->status, 202);
  sim.join();
  ASSERT_TRUE(res.ok) << res.failure;
  fs::remove_all(dir);
}

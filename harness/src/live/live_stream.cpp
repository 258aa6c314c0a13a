// live_stream.cpp: the live view's pushed telemetry (GET /api/stream,
// server-sent events) and an unpaced run's wait for a page (docs/live.md,
// "Push").
//
// A stream is one worker of the gate writing a chunked answer: each message
// is the JSON of /api/frames with every frame published since the last
// message (`id:` its last frame's seq, so a reconnecting browser resumes
// with Last-Event-ID).  It waits for something new (a frame, a command's
// state, the run's state), at most one message per kPushPeriod, a comment
// line every second of nothing new.  The sim thread only bumps a counter:
// it never waits for a stream.  A client that reads slowly holds its own
// worker (each write at most GateLimits::io_timeout, then the stream is
// closed); the frames it did not take in time are overwritten in the ring
// and reported as `missed` in its next message (coalesced, never queued).
#include <memory>
#include <string>

#include "live/live_impl.h"

namespace harness {

namespace {

struct StreamState {
  uint64_t since = 0;         // the last frame sent
  uint64_t version = ~0ull;   // Impl::version at the last message
  std::chrono::steady_clock::time_point sent{};
  bool ended = false;         // the run's end was sent: the stream closes
};

}  // namespace

void LiveServer::Impl::stream(const httplib::Request& req, httplib::Response& res)
{
  if (streams.fetch_add(1) >= static_cast<int>(kMaxStreams)) {
    streams.fetch_sub(1);
    res.status = 503;
    res.set_content(json{{"ok", false},
                         {"error", "at most " + std::to_string(kMaxStreams) +
                                       " pushed streams at once: poll /api/frames instead"}}
                        .dump(),
                    "application/json");
    return;
  }
  // released with the last copy of the provider: the stream's slot
  std::shared_ptr<void> slot(nullptr, [this](void*) { streams.fetch_sub(1); });
  auto st = std::make_shared<StreamState>();
  const std::string resume = req.get_header_value("Last-Event-ID");
  if (!resume.empty() && resume.size() <= 19 && resume.find_first_not_of("0123456789") == std::string::npos)
    st->since = std::stoull(resume);
  res.set_header("Cache-Control", "no-store");
  res.set_chunked_content_provider("text/event-stream", [this, st, slot](size_t, httplib::DataSink& sink) {
    using namespace std::chrono;
    if (st->ended || closing.load()) {
      sink.done();
      return true;
    }
    // at most one message per kPushPeriod; something new, or a keep-alive
    // comment after a second (a closed client shows as a failed write)
    const auto due = st->sent + duration_cast<steady_clock::duration>(duration<double>(kPushPeriod));
    while (steady_clock::now() < due && !closing.load()) std::this_thread::sleep_for(milliseconds(5));
    const auto t0 = steady_clock::now();
    while (version.load() == st->version && !closing.load() && steady_clock::now() - t0 < seconds(1))
      std::this_thread::sleep_for(milliseconds(5));
    if (closing.load()) {
      sink.done();
      return true;
    }
    if (version.load() == st->version) return sink.write(": keep-alive\n\n", 14);
    st->version = version.load();  // before reading: a change meanwhile is sent next time
    st->sent = steady_clock::now();
    uint64_t last = st->since;
    const std::string body = frames_text(st->since, &last);
    st->since = last;
    st->ended = state.load() == 3;
    const std::string msg = "id: " + std::to_string(last) + "\ndata: " + body + "\n\n";
    return sink.write(msg.data(), msg.size());
  });
}

void LiveServer::Impl::wait_for_page(Run& run, double& pace)
{
  set_state(4);
  publish(run, true);  // the page shows t = 0 when it comes
  const auto t0 = std::chrono::steady_clock::now();
  while (!page_seen.load() && !has_cmd.load() && seconds_since(t0) < wait_s) {
    if (stop && stop->load() != 0) break;
    std::unique_lock<std::mutex> lk(cmd_mu);
    cmd_cv.wait_for(lk, std::chrono::milliseconds(100), [this] { return page_seen.load() || has_cmd.load(); });
  }
  waited_s.store(seconds_since(t0));
  wait_s = 0.0;  // once
  if (has_cmd.load()) drain(run, pace);
  if (paced && !paused) pace = rate;  // deadlines restart from now
  set_state(paused ? 2 : 1);
}

}  // namespace harness

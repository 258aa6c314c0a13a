// live_server.cpp: the live view's server and run control (live_server.h):
// the routes, the frames ring, the run's boundaries.  Commands:
// live_commands.cpp; the pushed stream: live_stream.cpp.
#include "live/live_impl.h"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "scenario/scenario_limits.h"
#include "harness/core/pacer.h"

#ifdef KESTREL_HAVE_REPORT
#include "report/report.hpp"
#endif

namespace harness {

namespace {

std::string random_token()
{
  std::random_device rd;
  std::ostringstream o;
  for (int i = 0; i < 4; ++i) {
    const uint32_t w = rd();
    const char* hex = "0123456789abcdef";
    for (int b = 7; b >= 0; --b) o << hex[(w >> (4 * b)) & 0xfu];
  }
  return o.str();
}

// compares without stopping at the first difference
bool same_token(const std::string& a, const std::string& b)
{
  if (a.size() != b.size() || a.empty()) return false;
  unsigned d = 0;
  for (size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned>(a[i] ^ b[i]);
  return d == 0;
}

const char* value_kind(EventValue v)
{
  switch (v) {
    case EventValue::None: return "none";
    case EventValue::Positive: return "positive";
    case EventValue::NonNegative: return "non_negative";
    case EventValue::Finite: return "finite";
  }
  return "none";
}

// The device panel: every device of the scenario, under the name the
// scenario gives it (the names its events use), and the actions it takes
// here (an action check_event_action refuses in this scenario is left out).
json devices_json(const Run& run)
{
  const Scenario& sc = run.scenario();
  // the device panel: every device of the scenario and the actions it takes
  // here (an action check_event_action refuses in this scenario is left out)
  json devices = json::array();
  auto add_device = [&](const std::string& name) {
    EventTarget tg;
    if (!resolve_event_device(sc, name, tg).empty()) return;
    json acts = json::array();
    for (const EventActionDef& d : event_actions(tg.device)) {
      EventActionSpec probe{name, d.word, d.value == EventValue::None ? std::numeric_limits<double>::quiet_NaN() : 1.0};
      std::string key;
      if (!check_event_action(sc, probe, key).empty()) continue;
      acts.push_back({{"action", d.word}, {"value", value_kind(d.value)}, {"unit", d.unit}, {"what", d.what}});
    }
    devices.push_back({{"name", name}, {"kind", to_string(tg.device)}, {"index", tg.index}, {"actions", acts}});
  };
  for (const std::string& name : event_device_names(sc)) add_device(name);
  if (run.fsw_accepts_commands()) add_device("fsw");  // mode and actuation commands
  return devices;
}

#ifndef KESTREL_HAVE_REPORT
const char* kNoPage =
    "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Kestrel live view</title></head><body>"
    "<h1>Kestrel live view</h1><p>This build has no bundled page (Node.js/npm were missing at build time). "
    "The API answers at /api/info, /api/frames and /api/command.</p></body></html>";
#endif

}  // namespace

bool LiveServer::Impl::admit(const httplib::Request& req, httplib::Response& res)
{
  std::string given = req.get_header_value("X-Kestrel-Token");
  if (given.empty() && req.has_param("token")) given = req.get_param_value("token");
  if (!same_token(given, token)) {
    ++unauthorised;
    refuse_request(res, 403, given.empty() ? "no access token: open the URL kestrel printed (it carries ?token=...)"
                                           : "wrong access token: open the URL kestrel printed");
    if (req.path == "/")
      res.set_content(
          "Kestrel live view: this page needs the access token. Open the URL `kestrel run --live` printed.\n",
          "text/plain");
    return false;
  }
  const std::string enc = req.get_header_value("Content-Encoding");
  if (!enc.empty() && enc != "identity") {
    ++requests_refused;
    refuse_request(res, 415, "compressed request bodies are refused (Content-Encoding: " + escape_bytes(enc) + ")");
    return false;
  }
  if (req.has_header("Transfer-Encoding")) {
    ++requests_refused;
    refuse_request(res, 411, "a request body needs a Content-Length (chunked bodies are refused)");
    return false;
  }
  if (req.has_header("Content-Length")) {
    const std::string v = req.get_header_value("Content-Length");
    const size_t cap = srv.limits().body_max;
    bool digits = !v.empty() && v.size() <= 19;
    for (char ch : v) digits = digits && ch >= '0' && ch <= '9';
    if (!digits || std::stoull(v) > cap) {
      ++requests_refused;
      refuse_request(res, 413, "a request body is at most " + std::to_string(cap) + " bytes");
      return false;
    }
  }
  GatedServer::keep_connection_open();
  return true;
}

void LiveServer::Impl::serve()
{
  // every request passes admit() before its body is read (with
  // `Expect: 100-continue`, before the client sends it)
  srv.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    return admit(req, res) ? httplib::Server::HandlerResponse::Unhandled : httplib::Server::HandlerResponse::Handled;
  });
  srv.set_expect_100_continue_handler(
      [this](const httplib::Request& req, httplib::Response& res) { return admit(req, res) ? 100 : res.status; });
  srv.Get("/", [](const httplib::Request&, httplib::Response& res) {
#ifdef KESTREL_HAVE_REPORT
    res.set_content(report::live_page(), "text/html; charset=utf-8");
#else
    res.set_content(kNoPage, "text/html; charset=utf-8");
#endif
  });
  srv.Get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
    std::lock_guard<std::mutex> lk(info_mu);
    if (!info_ready) {
      res.status = 503;
      res.set_content(json{{"state", "starting"}}.dump(), "application/json");
      return;
    }
    res.set_content(info_text, "application/json");
  });
  srv.Get("/api/frames", [this](const httplib::Request& req, httplib::Response& res) {
    uint64_t since = 0;
    if (req.has_param("since")) {
      try {
        since = std::stoull(req.get_param_value("since"));
      } catch (const std::exception&) {
        refuse(res, 400, "since: expected a frame number");
        return;
      }
    }
    res.set_content(frames_text(since), "application/json");
  });
  srv.Get("/api/stream", [this](const httplib::Request& req, httplib::Response& res) { stream(req, res); });
  srv.Get("/api/commands", [this](const httplib::Request& req, httplib::Response& res) {
    const std::string text = commands_text(req);
    if (text.empty()) {
      refuse(res, 400, "before: expected a command id; limit: expected a count in [1, " + std::to_string(kLogPage) + "]");
      return;
    }
    res.set_content(text, "application/json");
  });
  srv.Post("/api/command", [this](const httplib::Request& req, httplib::Response& res) { post_command(req, res); });
  srv.Get("/report", [this](const httplib::Request&, httplib::Response& res) {
    std::string path;
    {
      std::lock_guard<std::mutex> lk(info_mu);
      path = report_path;
    }
    std::ifstream f(path, std::ios::binary);
    if (path.empty() || !f) {
      res.status = 404;
      res.set_content("no report (yet): the run writes it when it ends\n", "text/plain");
      return;
    }
    std::ostringstream o;
    o << f.rdbuf();
    res.set_content(o.str(), "text/html; charset=utf-8");
  });
}

std::string LiveServer::Impl::frames_text(uint64_t since, uint64_t* last_out)
{
  if (!page_seen.exchange(true)) cmd_cv.notify_all();  // a run waiting for a page goes on
  uint64_t last = 0, missed = 0;
  std::array<double, 2> g{};
  std::vector<Frame> copy;  // copied under the lock (memcpy), the JSON is written after it
  copy.reserve(kRingFrames);
  {
    std::lock_guard<std::mutex> lk(ring_mu);
    last = seq;
    g = gains;
    const uint64_t oldest = seq >= kRingFrames ? seq - kRingFrames + 1 : 1;
    const uint64_t from = since + 1 < oldest ? oldest : since + 1;
    if (from > since + 1) missed = from - since - 1;
    for (uint64_t s = from; s <= seq; ++s) copy.push_back(ring[static_cast<size_t>(s % kRingFrames)]);
  }
  json frames = json::array();
  for (const Frame& f : copy) {
    json row = json::array();
    for (double v : f.row) row.push_back(std::isfinite(v) ? json(v) : json(nullptr));
    frames.push_back({{"seq", f.seq}, {"tick", f.tick}, {"wall", f.wall}, {"rate", f.rate}, {"paused", f.paused},
                      {"row", std::move(row)}});
  }
  uint64_t prev = max_read.load();
  while (last > prev && !max_read.compare_exchange_weak(prev, last)) {
  }
  json cmds = json::array();  // the last kLogPage (older ones: /api/commands)
  uint64_t total = 0;
  {
    std::lock_guard<std::mutex> lk(cmd_mu);
    total = next_id - 1;
    for (size_t i = log.size() > kLogPage ? log.size() - kLogPage : 0; i < log.size(); ++i)
      cmds.push_back(log_json(log[i]));
  }
  if (last_out) *last_out = last;
  static const char* kStates[] = {"starting", "running", "paused", "ended", "waiting"};
  json j = {{"state", kStates[state.load()]},
            {"last", last},
            {"missed", missed},
            {"dropped_busy", dropped_busy.load()},
            {"dropped_unread", dropped_unread.load()},
            {"wall", seconds_since(t_start)},
            {"rate", rate_shown.load()},
            {"frames", std::move(frames)},
            {"commands", std::move(cmds)},
            {"commands_total", total}};
  if (has_gains) j["gains"] = {{"K", g[0]}, {"P", g[1]}};
  if (state.load() == 3) {
    std::lock_guard<std::mutex> lk(info_mu);
    j["end"] = end_text;
    if (!report_path.empty()) j["report"] = "/report";
  }
  return j.dump();
}

void LiveServer::Impl::publish(const Run& run, bool force)
{
  const double now = seconds_since(t_start);
  if (!force && now - last_publish < kPublishPeriod) return;
  const double* row = run.recorder().last_row();
  if (!row) return;
  if (!ring_mu.try_lock()) {  // a page request is copying: drop this frame, never wait
    ++dropped_busy;
    return;
  }
  last_publish = now;
  const uint64_t s = ++seq;
  Frame& f = ring[static_cast<size_t>(s % kRingFrames)];
  if (f.seq != 0 && f.seq > max_read.load() && page_seen.load()) ++dropped_unread;
  f.seq = s;
  f.tick = run.tick();
  f.wall = now;
  f.rate = rate;
  f.paused = paused;
  std::copy(row, row + ncols, f.row.begin());
  if (has_gains) gains = run.fsw_gains();
  ring_mu.unlock();
  bump();
}

LiveServer::LiveServer(LiveOptions opt) : impl_(std::make_unique<Impl>())
{
  Impl& m = *impl_;
  m.opt = std::move(opt);
  m.token = m.opt.token.empty() ? random_token() : m.opt.token;
  m.ring.resize(kRingFrames);
  m.serve();
  m.port = m.srv.bind_gated(m.opt.host, m.opt.port);
  if (m.port <= 0 && m.opt.port == 0) throw std::runtime_error("live view: cannot bind " + m.opt.host + " to a free port");
  if (m.port <= 0)
    throw std::runtime_error("live view: cannot bind " + m.opt.host + ":" + std::to_string(m.opt.port) +
                             " (in use, or not an address of this host)");
  m.thread = std::thread([&m] { m.srv.listen_after_bind(); });
}

LiveServer::~LiveServer()
{
  impl_->closing.store(true);  // pushed streams end (their workers return)
  impl_->srv.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
  impl_->srv.stop_gate();  // its workers call into Impl: stopped before Impl's members go
}

int LiveServer::port() const { return impl_->port; }
const std::string& LiveServer::token() const { return impl_->token; }
std::string LiveServer::url() const
{
  const std::string& h = impl_->opt.host;
  const bool v6 = h.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + h + "]" : h) + ":" + std::to_string(impl_->port) + "/?token=" + impl_->token;
}

void LiveServer::results_folder(const std::string& working, const std::string& target)
{
  std::lock_guard<std::mutex> lk(impl_->info_mu);
  impl_->save_dir = working;
  impl_->save_target = target;
}

void LiveServer::started(Run& run, double realtime_scale, const std::atomic<int>* stop)
{
  Impl& m = *impl_;
  const Scenario& sc = run.scenario();
  const Recorder& rec = run.recorder();
  m.stop = stop;
  m.paused = m.opt.start_paused;
  // an unpaced run would be over before a page opened: it waits after tick
  // 0 for one (wait_for_page), unless paused anyway
  m.wait_s = m.opt.start_paused ? 0.0 : realtime_scale > 0.0 ? m.opt.wait_paced : m.opt.wait_unpaced;
  m.has_gains = run.fsw_accepts_commands();
  m.gains = run.fsw_gains();
  m.step_until = m.opt.start_paused ? 1 : 0;  // tick 0 runs, so the page shows the state at t = 0
  m.paced = realtime_scale > 0.0;
  m.rate = realtime_scale;
  m.rate_shown.store(realtime_scale);
  m.ncols = rec.num_columns();
  m.total_ticks = run.total_ticks();
  m.tick_ns = sc.tick_ns();
  for (auto& f : m.ring) f.row.assign(m.ncols, 0.0);
  json cols = json::array(), units = json::array();
  for (const Column& c : rec.columns()) {
    cols.push_back(c.name);
    units.push_back(c.unit);
  }
  const json devices = devices_json(run);
  json wheels = json::array();
  for (const WheelSpec& w : sc.wheels) wheels.push_back({{"name", w.name}, {"Omega_max", w.params.Omega_max}});
  json info = {{"scenario", sc.name},
               {"gains", m.has_gains ? json{{"K", m.gains[0]}, {"P", m.gains[1]}} : json(nullptr)},
               {"description", sc.description},
               {"version", version()},
               {"dt", sc.rates.dt},
               {"duration", sc.duration},
               {"ticks", m.total_ticks},
               {"fsw_mode", to_string(sc.fsw.mode)},
               {"paced", m.paced},
               {"rate", m.rate},
               {"columns", cols},
               {"units", units},
               {"devices", devices},
               {"wheels", wheels},
               {"geometry", json::parse(geometry_json_text(run))},
               {"publish_period", kPublishPeriod},
               {"wait_for_page", m.wait_s},
               {"save_refused", m.save_dir.empty() ? "the run writes no results folder (-o)" : run.checkpoint_refusal()},
               {"ring_frames", kRingFrames}};
  std::lock_guard<std::mutex> lk(m.info_mu);
  m.sc = sc;
  m.save_refusal = run.checkpoint_refusal();  // FSW or sensors outside the harness: no save at all
  m.max_live_events = kMaxScenarioEvents > sc.events.size() ? kMaxScenarioEvents - sc.events.size() : 0;
  m.info_text = info.dump();
  m.info_ready = true;
  m.set_state(1);
}

uint64_t LiveServer::boundary(Run& run, double& pace)
{
  Impl& m = *impl_;
  if (m.has_cmd.load(std::memory_order_relaxed)) m.drain(run, pace);
  if (m.wait_s > 0.0 && run.tick() >= 1) m.wait_for_page(run, pace);  // tick 0 ran: the page shows t = 0
  if (!m.paused) {
    m.publish(run, false);
    return 1;
  }
  if (run.tick() < m.step_until) {  // stepping while paused
    m.publish(run, false);
    return m.step_until - run.tick();
  }
  // paused: show it, then wait for a command (or a stop request)
  m.set_state(2);
  m.publish(run, true);
  const auto wait0 = std::chrono::steady_clock::now();
  while (m.paused && run.tick() >= m.step_until) {
    if (m.stop && m.stop->load() != 0) return 1;
    {
      std::unique_lock<std::mutex> lk(m.cmd_mu);
      m.cmd_cv.wait_for(lk, std::chrono::milliseconds(100), [&m] { return m.has_cmd.load(); });
    }
    if (m.has_cmd.load()) m.drain(run, pace);
  }
  m.paused_s.store(m.paused_s.load() + seconds_since(wait0));
  if (!m.paused) m.set_state(1);
  m.publish(run, true);
  return m.paused ? m.step_until - run.tick() : 1;
}

void LiveServer::ended(const Run& run, const RunResult& res)
{
  Impl& m = *impl_;
  m.paused = false;
  m.publish(run, true);
  std::ostringstream o;
  o << (res.ok ? "complete" : res.stopped_by_signal ? "interrupted" : "failed: " + res.failure) << " at t = "
    << res.status.t_reached << " s";
  std::lock_guard<std::mutex> lk(m.info_mu);
  for (const std::string& f : res.files)
    if (f.size() >= 11 && f.compare(f.size() - 11, 11, "report.html") == 0) m.report_path = f;
  m.end_text = o.str();
  m.set_state(3);
  // commands still queued will never apply
  std::lock_guard<std::mutex> lc(m.cmd_mu);
  for (const Impl::Command& c : m.queue) {
    ++m.refused;
    if (c.id < m.log_base) continue;
    m.log[static_cast<size_t>(c.id - m.log_base)].status = "refused";
    m.log[static_cast<size_t>(c.id - m.log_base)].detail = "the run ended first";
  }
  m.queue.clear();
  m.bump();
}

void LiveServer::linger(double seconds, const std::atomic<int>* stop)
{
  const auto t0 = std::chrono::steady_clock::now();
  while (seconds_since(t0) < seconds && !(stop && stop->load() != 0))
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

LiveCounters LiveServer::counters() const
{
  const Impl& m = *impl_;
  LiveCounters c;
  c.published = m.seq;
  c.dropped_busy = m.dropped_busy.load();
  c.dropped_unread = m.dropped_unread.load();
  c.commands_applied = m.applied.load();
  c.commands_refused = m.refused.load();
  c.requests_unauthorised = m.unauthorised.load();
  c.requests_refused = m.requests_refused.load();
  const GateCounters g = m.srv.gate_counters();
  c.connections = g.connections;
  c.connections_closed = g.idle_closed + g.slow_closed + g.large_closed + g.evicted + g.busy_refused;
  c.paused_s = m.paused_s.load();
  c.waited_s = m.waited_s.load();
  return c;
}

}  // namespace harness

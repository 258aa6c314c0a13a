// live_server.cpp: the live view's server and run control (live_server.h).
#include "live/live_server.h"

#include "live/live_gate.h"

// after Eigen (through live_server.h): <resolv.h> defines the macro _res,
// a parameter name in Eigen's templates
#include <httplib.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/events.h"
#include "scenario/scenario_limits.h"
#include "harness/core/pacer.h"
#include "harness/core/run.h"

#ifdef KESTREL_HAVE_REPORT
#include "report/report.hpp"
#endif

namespace harness {

using json = nlohmann::json;

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

double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

#ifndef KESTREL_HAVE_REPORT
const char* kNoPage =
    "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Kestrel live view</title></head><body>"
    "<h1>Kestrel live view</h1><p>This build has no bundled page (Node.js/npm were missing at build time). "
    "The API answers at /api/info, /api/frames and /api/command.</p></body></html>";
#endif

}  // namespace

struct LiveServer::Impl {
  LiveOptions opt;
  std::string token;
  int port = 0;
  GatedServer srv;
  std::thread thread;
  const std::chrono::steady_clock::time_point t_start = std::chrono::steady_clock::now();

  // ---- set once at started() (read by the server after `info_ready`) --------
  std::mutex info_mu;
  bool info_ready = false;
  Scenario sc;               // the scenario as started: what commands are checked against
  std::string info_text;     // /api/info
  size_t ncols = 0;
  uint64_t total_ticks = 0;
  uint64_t tick_ns = 1;
  size_t max_live_events = 0;  // kMaxScenarioEvents - the scenario's own
  const std::atomic<int>* stop = nullptr;

  // ---- frames: the ring (producer: the sim thread, try_lock only) --------------
  struct Frame {
    uint64_t seq = 0, tick = 0;
    double wall = 0.0, rate = 0.0;
    bool paused = false;
    std::vector<double> row;
  };
  std::mutex ring_mu;
  std::vector<Frame> ring;
  uint64_t seq = 0;  // frames published (the last one's seq)
  std::atomic<uint64_t> max_read{0};
  std::atomic<bool> page_seen{false};
  std::atomic<uint64_t> dropped_busy{0}, dropped_unread{0};
  double last_publish = -1.0;

  // ---- commands ------------------------------------------------------------------
  struct Command {
    uint64_t id = 0;
    std::string op;  // pause, resume, step, rate, event
    uint64_t ticks = 0;
    double value = 0.0;
    EventActionSpec action;
  };
  struct LogEntry {
    uint64_t id = 0;
    std::string text, status;  // status: queued, applied, refused
    std::string detail;
    uint64_t tick = 0;
    double t = 0.0;
  };
  std::mutex cmd_mu;
  std::condition_variable cmd_cv;
  std::deque<Command> queue;
  std::atomic<bool> has_cmd{false};
  std::deque<LogEntry> log;  // the last kLogKept commands, ids log_base.. (under cmd_mu)
  uint64_t log_base = 1;
  uint64_t next_id = 1;
  size_t live_events = 0;  // event commands accepted (under cmd_mu)
  std::atomic<uint64_t> applied{0}, refused{0};
  std::atomic<uint64_t> unauthorised{0}, requests_refused{0};  // refused before the body was read
  std::atomic<double> paused_s{0.0};

  // ---- run state (sim thread; mirrored for the server) -----------------------
  std::atomic<int> state{0};  // 0 starting, 1 running, 2 paused, 3 ended
  bool paced = false;
  double rate = 0.0;          // pacing scale (0: as fast as possible)
  std::atomic<double> rate_shown{0.0};
  bool paused = false;
  uint64_t step_until = 0;  // paused: run up to this tick (step)
  std::string report_path;    // after ended()
  std::string end_text;

  void serve();
  // Before the body is read (from the request line and headers): the token,
  // then the body's size and encoding.  false after refusing (the
  // connection closes after the answer: the body is never read).
  bool admit(const httplib::Request& req, httplib::Response& res);
  void refuse_request(httplib::Response& res, int status, const std::string& msg)
  {
    res.status = status;
    res.set_content(json{{"ok", false}, {"error", msg}}.dump(), "application/json");
    GatedServer::close_after_answer();
  }
  json log_json(const LogEntry& e) const
  {
    return {{"id", e.id}, {"command", e.text}, {"status", e.status}, {"detail", e.detail}, {"tick", e.tick}, {"t", e.t}};
  }
  std::string commands_text(const httplib::Request& req);
  void refuse(httplib::Response& res, int status, const std::string& msg)
  {
    ++refused;
    res.status = status;
    res.set_content(json{{"ok", false}, {"error", msg}}.dump(), "application/json");
  }
  void post_command(const httplib::Request& req, httplib::Response& res);
  // A command's JSON into c and the text of its log entry; "" or why it is
  // refused (400).
  std::string read_command(const json& j, Command& c, std::string& text);
  std::string read_event(const json& j, Command& c, std::string& text);
  // Queues c (its id set); false after refusing it (too many waiting, or
  // the most events a scenario may have).
  bool enqueue(Command& c, const std::string& text, httplib::Response& res);
  std::string frames_text(uint64_t since);
  void publish(const Run& run, bool force);
  // the sim thread: applies what is queued at the boundary before tick k
  void drain(Run& run, double& pace);
  void set_log(uint64_t id, const std::string& status, const std::string& detail, uint64_t tick, double t)
  {
    std::lock_guard<std::mutex> lk(cmd_mu);
    if (id < log_base) return;  // forgotten (kLogKept newer ones since)
    LogEntry& e = log[static_cast<size_t>(id - log_base)];
    e.status = status;
    e.detail = detail;
    e.tick = tick;
    e.t = t;
  }
};

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

std::string LiveServer::Impl::read_event(const json& j, Command& c, std::string& text)
{
  if (!j.contains("device") || !j["device"].is_string() || !j.contains("action") || !j["action"].is_string())
    return "event: needs \"device\" and \"action\" (strings) and, when the action takes one, \"value\"";
  c.action.device = j["device"].get<std::string>();
  c.action.action = j["action"].get<std::string>();
  if (j.contains("value") && !j["value"].is_null()) {
    if (!j["value"].is_number()) return "event: value must be a number";
    c.action.value = j["value"].get<double>();
  }
  // the scenario event validation (events.cpp), as for a scenario file
  std::string key;
  const std::string why = check_event_action(sc, c.action, key);
  if (!why.empty()) return key + ": " + why;
  text = c.action.device + " " + c.action.action;
  if (!std::isnan(c.action.value)) {
    std::ostringstream o;
    o.precision(10);
    o << c.action.value;
    text += " " + o.str();
  }
  return "";
}

std::string LiveServer::Impl::read_command(const json& j, Command& c, std::string& text)
{
  c.op = j["op"].get<std::string>();
  text = c.op;
  if (c.op == "pause" || c.op == "resume") return "";
  if (c.op == "step") {
    const json n = j.value("ticks", json(1));
    if (!n.is_number_integer() || n.get<int64_t>() < 1 || n.get<int64_t>() > 1000000)
      return "step: ticks must be an integer in [1, 1000000]";
    c.ticks = n.get<uint64_t>();
    text += " " + std::to_string(c.ticks) + " tick" + (c.ticks == 1 ? "" : "s");
    return "";
  }
  if (c.op == "rate") {
    const json v = j.value("value", json());
    if (!v.is_number()) return "rate: value must be a number (a multiple of real time)";
    const std::string why = Pacer::check_scale(v.get<double>());
    if (!why.empty()) return "rate: value: " + why;
    c.value = v.get<double>();
    std::ostringstream o;
    o << "rate " << c.value << "x";
    text = o.str();
    return "";
  }
  if (c.op == "event") return read_event(j, c, text);
  return "unknown command '" + escape_bytes(c.op) + "' (pause, resume, step, rate, event)";
}

bool LiveServer::Impl::enqueue(Command& c, const std::string& text, httplib::Response& res)
{
  std::lock_guard<std::mutex> lk(cmd_mu);
  if (queue.size() >= kMaxQueued) {
    ++refused;
    res.status = 429;
    res.set_content(json{{"ok", false}, {"error", "too many commands waiting for the run"}}.dump(), "application/json");
    return false;
  }
  if (c.op == "event") {
    if (live_events >= max_live_events) {
      ++refused;
      res.status = 409;
      res.set_content(json{{"ok", false},
                           {"error", "the run holds the most events a scenario may have (" +
                                         std::to_string(kMaxScenarioEvents) + ")"}}
                          .dump(),
                      "application/json");
      return false;
    }
    ++live_events;
  }
  c.id = next_id++;
  log.push_back({c.id, text, "queued", "", 0, 0.0});
  while (log.size() > kLogKept) {
    log.pop_front();
    ++log_base;
  }
  queue.push_back(c);
  has_cmd.store(true);
  return true;
}

void LiveServer::Impl::post_command(const httplib::Request& req, httplib::Response& res)
{
  json j;
  try {
    j = json::parse(req.body);
  } catch (const std::exception&) {
    refuse(res, 400, "the command is not JSON");
    return;
  }
  if (!j.is_object() || !j.contains("op") || !j["op"].is_string()) {
    refuse(res, 400, "a command is {\"op\": pause|resume|step|rate|event, ...}");
    return;
  }
  {
    std::lock_guard<std::mutex> lk(info_mu);
    if (!info_ready) {
      refuse(res, 409, "the run has not started yet");
      return;
    }
  }
  if (state.load() == 3) {
    refuse(res, 409, "the run has ended: nothing can be applied");
    return;
  }
  Command c;
  std::string text;
  const std::string why = read_command(j, c, text);
  if (!why.empty()) {
    refuse(res, 400, why);
    return;
  }
  if (!enqueue(c, text, res)) return;
  cmd_cv.notify_all();
  res.status = 202;
  res.set_content(json{{"ok", true}, {"id", c.id}, {"command", text}}.dump(), "application/json");
}

std::string LiveServer::Impl::commands_text(const httplib::Request& req)
{
  auto number = [&req](const char* key, uint64_t dflt, uint64_t& out) {
    if (!req.has_param(key)) {
      out = dflt;
      return true;
    }
    const std::string v = req.get_param_value(key);
    if (v.empty() || v.size() > 19 || v.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::stoull(v);
    return true;
  };
  uint64_t before = 0, limit = 0;
  if (!number("before", UINT64_MAX, before) || !number("limit", kLogPage, limit) || limit < 1 || limit > kLogPage)
    return "";
  json cmds = json::array();
  std::lock_guard<std::mutex> lk(cmd_mu);
  size_t end = log.size();  // entries with id < before
  if (before < log_base + log.size()) end = before > log_base ? static_cast<size_t>(before - log_base) : 0;
  const size_t begin = end > limit ? end - static_cast<size_t>(limit) : 0;
  for (size_t i = begin; i < end; ++i) cmds.push_back(log_json(log[i]));
  return json{{"commands", std::move(cmds)},
              {"more", begin > 0},
              {"first_kept", log_base},
              {"total", next_id - 1}}
      .dump();
}

std::string LiveServer::Impl::frames_text(uint64_t since)
{
  page_seen.store(true);
  uint64_t last = 0, missed = 0;
  std::vector<Frame> copy;  // copied under the lock (memcpy), the JSON is written after it
  copy.reserve(kRingFrames);
  {
    std::lock_guard<std::mutex> lk(ring_mu);
    last = seq;
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
  static const char* kStates[] = {"starting", "running", "paused", "ended"};
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
  ring_mu.unlock();
}

void LiveServer::Impl::drain(Run& run, double& pace)
{
  std::deque<Command> cmds;
  {
    std::lock_guard<std::mutex> lk(cmd_mu);
    cmds.swap(queue);
    has_cmd.store(false);
  }
  const uint64_t k = run.tick();
  const double t_k = static_cast<double>(k * tick_ns) / 1e9;  // as the recorded t (correctly rounded: k dt)
  for (const Command& c : cmds) {
    if (c.op == "pause") {
      paused = true;
      step_until = 0;  // a step under way ends here
    } else if (c.op == "resume") {
      if (paused && paced) pace = rate;  // deadlines restart from now
      paused = false;
    } else if (c.op == "step") {
      paused = true;  // from a running run: pause after the steps
      step_until = (step_until > k ? step_until : k) + c.ticks;
      if (paced) pace = rate;
    } else if (c.op == "rate") {
      rate = c.value;
      paced = true;
      rate_shown.store(rate);
      if (!paused) pace = rate;
    } else if (c.op == "event") {
      if (k + 1 >= total_ticks) {  // t_k would be the run's end: the manifest would not take it
        ++refused;
        set_log(c.id, "refused", "the run is at its last tick", k, t_k);
        continue;
      }
      EventSpec e;
      e.name = "live" + std::to_string(c.id);
      for (bool taken = true; taken;) {  // unique among the scenario's names
        taken = false;
        for (const EventSpec& x : run.scenario().events) taken = taken || x.name == e.name;
        if (taken) e.name += "_";
      }
      e.t = t_k;
      e.actions.push_back(c.action);
      try {
        run.add_event(e);
      } catch (const std::exception& ex) {
        ++refused;
        set_log(c.id, "refused", ex.what(), k, t_k);
        continue;
      }
      ++applied;
      set_log(c.id, "applied", "event " + e.name, k, t_k);
      continue;
    }
    ++applied;
    set_log(c.id, "applied", "", k, t_k);
  }
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

void LiveServer::started(Run& run, double realtime_scale, const std::atomic<int>* stop)
{
  Impl& m = *impl_;
  const Scenario& sc = run.scenario();
  const Recorder& rec = run.recorder();
  m.stop = stop;
  m.paused = m.opt.start_paused;
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
  for (const WheelSpec& w : sc.wheels) add_device(w.name);
  for (const ThrusterSpec& t : sc.thrusters) add_device(t.name);
  if (sc.sensors.gyro.enabled) add_device("gyro");
  if (sc.sensors.star_tracker.enabled) add_device("star_tracker");
  for (size_t i = 0; i < sc.sensors.css.normals_B.size(); ++i) add_device("css" + std::to_string(i));
  for (const MagnetorquerSpec& r : sc.magnetorquers) add_device(r.name);
  if (sc.sensors.magnetometer.enabled) add_device("magnetometer");
  if (sc.environment.drag.enabled) add_device("atmosphere");
  if (run.fsw_accepts_commands()) add_device("fsw");  // mode and actuation commands
  json wheels = json::array();
  for (const WheelSpec& w : sc.wheels) wheels.push_back({{"name", w.name}, {"Omega_max", w.params.Omega_max}});
  json info = {{"scenario", sc.name},
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
               {"ring_frames", kRingFrames}};
  std::lock_guard<std::mutex> lk(m.info_mu);
  m.sc = sc;
  m.max_live_events = kMaxScenarioEvents > sc.events.size() ? kMaxScenarioEvents - sc.events.size() : 0;
  m.info_text = info.dump();
  m.info_ready = true;
  m.state.store(1);
}

uint64_t LiveServer::boundary(Run& run, double& pace)
{
  Impl& m = *impl_;
  if (m.has_cmd.load(std::memory_order_relaxed)) m.drain(run, pace);
  if (!m.paused) {
    m.publish(run, false);
    return 1;
  }
  if (run.tick() < m.step_until) {  // stepping while paused
    m.publish(run, false);
    return m.step_until - run.tick();
  }
  // paused: show it, then wait for a command (or a stop request)
  m.state.store(2);
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
  if (!m.paused) m.state.store(1);
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
  m.state.store(3);
  // commands still queued will never apply
  std::lock_guard<std::mutex> lc(m.cmd_mu);
  for (const Impl::Command& c : m.queue) {
    ++m.refused;
    if (c.id < m.log_base) continue;
    m.log[static_cast<size_t>(c.id - m.log_base)].status = "refused";
    m.log[static_cast<size_t>(c.id - m.log_base)].detail = "the run ended first";
  }
  m.queue.clear();
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
  return c;
}

}  // namespace harness

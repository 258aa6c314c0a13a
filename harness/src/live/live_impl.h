// live_impl.h: the live view server's state (live_server.h), shared by its
// files: live_server.cpp (the server, the frames, the run's boundaries),
// live_commands.cpp (commands and their log), live_stream.cpp (the pushed
// stream, waiting for a page).  Internal to kestrel::harness_live.
#ifndef HARNESS_SRC_LIVE_IMPL_H
#define HARNESS_SRC_LIVE_IMPL_H

#include "live/live_server.h"

#include "live/live_gate.h"

// after Eigen (through live_server.h): <resolv.h> defines the macro _res,
// a parameter name in Eigen's templates
#include <httplib.h>

#include <array>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "core/events.h"
#include "harness/core/run.h"

namespace harness {

using json = nlohmann::json;

inline double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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
  std::array<double, 2> gains{{0.0, 0.0}};  // mrp_fb K, P in force at the last frame (under ring_mu)
  bool has_gains = false;                   // the FSW takes gain commands (set at started())
  std::mutex ring_mu;
  std::vector<Frame> ring;
  uint64_t seq = 0;  // frames published (the last one's seq)
  std::atomic<uint64_t> max_read{0};
  std::atomic<bool> page_seen{false};
  std::atomic<uint64_t> dropped_busy{0}, dropped_unread{0};
  double last_publish = -1.0;
  // bumped by every new frame, command log change and state change: what a
  // pushed stream waits for (live_stream.cpp)
  std::atomic<uint64_t> version{0};
  void bump() { version.fetch_add(1, std::memory_order_relaxed); }
  std::atomic<int> streams{0};          // pushed streams open
  std::atomic<bool> closing{false};     // the server is stopping: streams end

  // ---- commands ------------------------------------------------------------------
  struct Command {
    uint64_t id = 0;
    std::string op;  // pause, resume, step, rate, event, save
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
    std::string file;  // save: the checkpoint's name in the results folder
    uint64_t bytes = 0;  // ... and its size
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
  std::atomic<int> state{0};  // 0 starting, 1 running, 2 paused, 3 ended, 4 waiting for a page
  void set_state(int s)
  {
    state.store(s);
    bump();
  }
  double wait_s = 0.0;               // [s] the run waits at t = 0 for a page this long at most (0: no wait)
  std::atomic<double> waited_s{0.0}; // [s] wall time it waited
  bool paced = false;
  double rate = 0.0;          // pacing scale (0: as fast as possible)
  std::atomic<double> rate_shown{0.0};
  bool paused = false;
  uint64_t step_until = 0;  // paused: run up to this tick (step)
  std::string report_path;    // after ended()
  std::string end_text;
  // save: the results folder's working folder the checkpoints go into and
  // the folder they appear in (RunControl::results_folder, before
  // started()); why this run cannot be saved at all (set at started():
  // its FSW or sensors outside the harness)
  std::string save_dir, save_target, save_refusal;

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
    json j = {{"id", e.id}, {"command", e.text}, {"status", e.status}, {"detail", e.detail}, {"tick", e.tick}, {"t", e.t}};
    if (!e.file.empty()) j["file"] = {{"name", e.file}, {"bytes", e.bytes}};
    return j;
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
  // /api/frames and each pushed message: the frames after `since` (the
  // ring's, at most kRingFrames), run state, gains, commands; `last` is set
  // to the last frame's seq.  A page asking is a page seen.
  std::string frames_text(uint64_t since, uint64_t* last = nullptr);
  // GET /api/stream: server-sent events (live_stream.cpp)
  void stream(const httplib::Request& req, httplib::Response& res);
  // the sim thread after tick 0: waits until a page is seen, at most wait_s
  void wait_for_page(Run& run, double& pace);
  void publish(const Run& run, bool force);
  // the sim thread: applies what is queued at the boundary before tick k
  void drain(Run& run, double& pace);
  // the sim thread, at the boundary before tick k: a checkpoint of the run
  // into the results folder (checkpoint-<k>.kckp), logged as applied with
  // its name and size, or refused with why
  void save_state(Run& run, uint64_t id, uint64_t k, double t_k);
  // a save command that cannot apply whatever the tick: why ("" when it can)
  std::string save_refused_now();
  void set_log(uint64_t id, const std::string& status, const std::string& detail, uint64_t tick, double t,
               const std::string& file = "", uint64_t bytes = 0)
  {
    std::lock_guard<std::mutex> lk(cmd_mu);
    if (id < log_base) return;  // forgotten (kLogKept newer ones since)
    LogEntry& e = log[static_cast<size_t>(id - log_base)];
    e.status = status;
    e.detail = detail;
    e.tick = tick;
    e.t = t;
    e.file = file;
    e.bytes = bytes;
    bump();
  }
};

}  // namespace harness

#endif  // HARNESS_SRC_LIVE_IMPL_H

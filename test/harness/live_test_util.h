// live_test_util.h: what the live view's tests share (test_live.cpp,
// test_live_stream.cpp): the fast S1, a server with a client, waiting.
#ifndef TEST_HARNESS_LIVE_TEST_UTIL_H
#define TEST_HARNESS_LIVE_TEST_UTIL_H

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "harness/drive/run_scenario.h"
#include "harness/scenario/scenario.h"
#include "live/live_server.h"

// after Eigen (through the harness headers): <resolv.h> defines the macro
// _res, a parameter name in Eigen's templates
#include <httplib.h>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace live_test {

inline const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

// The closed-loop tests' fast S1 (test_closed_loop.cpp): 4 Hz plant and FSW,
// balanced wheels, 60 s.
inline std::vector<harness::Override> fast()
{
  return {{"rates.dt", "0.25"},
          {"rates.fsw_divisor", "1"},
          {"rates.record_divisor", "1"},
          {"wheel_defaults.model", "balanced"},
          {"duration", "60"}};
}

inline fs::path temp_dir(const std::string& what)
{
  const fs::path d = fs::temp_directory_path() / ("kestrel_live_" + what + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

// A server whose run waits at the boundary after tick 0 for resume or step.
inline harness::LiveOptions paused_options()
{
  harness::LiveOptions lo;
  lo.start_paused = true;
  return lo;
}

struct Served {
  harness::LiveServer srv;
  httplib::Client cli;
  explicit Served(harness::LiveOptions o) : srv(std::move(o)), cli("127.0.0.1", srv.port()) {}
  httplib::Headers auth(const std::string& tok) const { return {{"X-Kestrel-Token", tok}}; }
  httplib::Result post(const json& j, const std::string& tok)
  {
    return cli.Post("/api/command", auth(tok), j.dump(), "application/json");
  }
  httplib::Result post_ok(const json& j) { return post(j, srv.token()); }
  // The fast S1 into `out` under this server's control, on its own thread.
  // (unpaced); *done set when it returned
  std::thread start_run(const fs::path& out, harness::RunResult& res, std::atomic<bool>* done = nullptr)
  {
    harness::RunOptions opt;
    opt.out_dir = out.string();
    opt.control = &srv;
    return std::thread([opt, &res, done] {
      res = harness::run_scenario(harness::load_scenario(kS1, fast()), opt);
      if (done) *done = true;
    });
  }
  // the run has started: /api/info answers (waits up to 20 s)
  bool started();
  json frames()
  {
    auto r = cli.Get("/api/frames", auth(srv.token()));
    return r && r->status == 200 ? json::parse(r->body) : json();
  }
};

// waits up to 20 s for `cond` (the run is short; the bound only ends a hung test)
template <class F>
inline bool wait_for(F cond)
{
  for (int i = 0; i < 2000; ++i) {
    if (cond()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

inline bool Served::started()
{
  return wait_for([this] {
    auto r = cli.Get("/api/info", auth(srv.token()));
    return r && r->status == 200;
  });
}

inline std::string error_of(const httplib::Result& r) { return r ? json::parse(r->body).value("error", "") : ""; }

}  // namespace live_test

#endif  // TEST_HARNESS_LIVE_TEST_UTIL_H

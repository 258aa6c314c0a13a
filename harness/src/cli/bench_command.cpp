// `kestrel bench`: real-time factors of the reference cases and where a
// tick's time goes (docs/performance.md).
//
// Each case runs kRepeats times as fast as it can, without output sinks
// (the recorder fills its rows; no file is written), and its speed is the
// process CPU time (min / median / max of the repeats).  One more run with
// the scheduler's profiling on times every task call and every plant step
// (steady clock) and gives the split per tick: plant, sensors, FSW,
// recording and other.  The timer's own cost is measured and printed; it
// is in the split's figures, not in the real-time factors.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <map>
#include <string>
#include <vector>

#include "cli/command_util.h"
#include "harness/cli/commands.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace harness {

namespace {

namespace fs = std::filesystem;

constexpr int kRepeats = 5;

double cpu_seconds()
{
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// [ns] one steady_clock reading pair, as the profiler takes around each call
double timer_pair_ns()
{
  constexpr int n = 200000;
  const auto t0 = std::chrono::steady_clock::now();
  volatile int64_t sink = 0;  // keeps the readings
  for (int i = 0; i < n; ++i) {
    const auto a = std::chrono::steady_clock::now();
    sink = sink + (std::chrono::steady_clock::now() - a).count();
  }
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / n;
}

// The category of a task of kTickProtocol (run.cpp) in the split.
const char* category(const std::string& task)
{
  static const std::map<std::string, const char*> m{
      {"plant", "plant"},          {"sample_sensors", "sensors"}, {"css", "sensors"},  {"sensors", "sensors"},
      {"fsw_acs", "fsw"},          {"metrics", "recording"},      {"recorder", "recording"},
  };
  const auto it = m.find(task);
  return it == m.end() ? "other" : it->second;
}

struct Case {
  std::string id;  // --case name
  std::string label;
  std::string file;
  std::vector<Override> ov;
  bool fully_coupled = false;
  bool extra = false;  // run only when named with --case
};

Scenario load_case(const Case& c)
{
  Scenario sc = load_scenario(c.file, c.ov);
  if (c.fully_coupled)
    for (auto& w : sc.wheels) w.params.model = sim::WheelModel::FullyCoupled;
  return sc;
}

RunConfig bench_config()
{
  RunConfig cfg;
  cfg.keep_in_memory = false;
  return cfg;
}

// The reference cases: S1 fully coupled at dt = 0.01 s and 0.1 s, S1 with
// plant sub-steps, S2 as shipped; and the extra cases, run when named
// (S1 with the FSW every step, S1 in LEO with the environment on and off).
std::vector<Case> reference_cases(const std::string& dir)
{
  const std::string s1 = (fs::path(dir) / "s1_sun_pointing.yaml").string();
  const std::string s2 = (fs::path(dir) / "s2_mars_orbit_insertion.yaml").string();
  std::vector<Case> cases;
  for (const char* dt : {"0.01", "0.1"}) {
    const bool fine = std::string(dt) == "0.01";
    Case c{fine ? "s1-0.01" : "s1-0.1", fine ? "S1 fully-coupled, dt = 0.01 s" : "S1 fully-coupled, dt = 0.1 s", s1,
           {}, true};
    c.ov = {{"rates.dt", dt},
            {"rates.fsw_divisor", fine ? "10" : "1"},
            {"rates.fsw_offset", "0"},
            {"rates.record_divisor", fine ? "100" : "10"},
            {"wheel_defaults.model", "fully_coupled"}};
    cases.push_back(c);
  }
  {
    Case c = cases[0];
    c.id = "s1-substeps";
    c.label = "S1, dt = 0.01 s, 2 plant sub-steps";
    c.ov.push_back({"rates.plant_substeps", "2"});
    cases.push_back(c);
  }
  cases.push_back({"s2", "S2 Mars orbit insertion, as shipped", s2, {}, false});
  // Extra: S1's dt = 0.01 s case with the FSW every step (100 Hz, the
  // plant's rate), where the FSW cycle is a large part of a tick.
  {
    Case c = cases[0];
    c.id = "s1-fsw-every-step";
    c.label = "S1 fully-coupled, FSW every 0.01 s step";
    c.extra = true;
    for (Override& o : c.ov)
      if (o.path == "rates.fsw_divisor") o.value = "1";
    cases.push_back(c);
  }
  // Extra: S1's dt = 0.01 s case flown in LEO with every disturbance model
  // on, and the same orbit with every model off (the environment's cost).
  const std::string leo = (fs::path(dir) / "s1_leo_environment.yaml").string();
  Case env{"s1-leo-env", "S1 in LEO, every disturbance model on", leo, cases[0].ov, true, true};
  Case off{"s1-leo-off", "S1 in LEO, every disturbance model off", leo, cases[0].ov, true, true};
  for (const char* m : {"gravity_gradient", "solar_pressure", "drag", "magnetic"})
    off.ov.push_back({std::string("environment.") + m + ".enabled", "false"});
  cases.push_back(env);
  cases.push_back(off);
  return cases;
}

// --case: the named cases only, in the usual order; false (after a
// message) on an unknown name.
bool select_cases(const std::vector<std::string>& only, std::vector<Case>& cases, std::ostream& err)
{
  for (const std::string& name : only) {
    if (std::none_of(cases.begin(), cases.end(), [&name](const Case& c) { return c.id == name; })) {
      err << "kestrel bench: no case '" << name << "'; the cases are:";
      for (const Case& c : cases) err << " " << c.id;
      err << "\n";
      return false;
    }
  }
  if (only.empty())
    cases.erase(std::remove_if(cases.begin(), cases.end(), [](const Case& c) { return c.extra; }), cases.end());
  else
    cases.erase(std::remove_if(cases.begin(), cases.end(),
                               [&only](const Case& c) { return std::find(only.begin(), only.end(), c.id) == only.end(); }),
                cases.end());
  return true;
}

// The real-time factors of kRepeats runs, sorted; empty (after a message)
// when a run failed.
std::vector<double> speeds(const Case& c, const Scenario& sc, std::ostream& err)
{
  std::vector<double> rtf;
  for (int r = 0; r < kRepeats; ++r) {
    Run run(sc, bench_config());
    const double c0 = cpu_seconds();
    run.step_ticks(run.total_ticks());
    const double cpu = cpu_seconds() - c0;
    if (!run.failure().empty()) {
      err << c.label << ": run failed: " << run.failure() << "\n";
      return {};
    }
    rtf.push_back(sc.duration / cpu);
  }
  std::sort(rtf.begin(), rtf.end());
  return rtf;
}

// Where a tick's time goes, from one profiled run [ns in all]: plant,
// sensors, fsw, recording, other; `calls`: the timed calls.
std::map<std::string, double> split_of(const Scenario& sc, double& calls)
{
  Run run(sc, bench_config());
  run.set_profiling(true);
  const auto w0 = std::chrono::steady_clock::now();
  run.step_ticks(run.total_ticks());
  const double wall_ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - w0).count();
  std::map<std::string, double> split{{"plant", 0}, {"sensors", 0}, {"fsw", 0}, {"recording", 0}, {"other", 0}};
  double timed = 0.0;
  calls = 0.0;
  const auto prof = run.profile();
  for (const auto& [name, ns] : prof) {
    split[category(name)] += static_cast<double>(ns);
    timed += static_cast<double>(ns);
  }
  for (size_t i = 0; i < run.scheduler().num_tasks(); ++i) calls += static_cast<double>(run.scheduler().run_count(i));
  calls += static_cast<double>(sc.num_ticks());  // the plant's
  split["other"] += wall_ns - timed;             // the loop itself: between the timed calls
  return split;
}

// One case's two lines; false when a run failed.
bool bench_case(const Case& c, double pair_ns, std::ostream& out, std::ostream& err)
{
  const Scenario sc = load_case(c);
  const std::vector<double> rtf = speeds(c, sc, err);
  if (rtf.empty()) return false;
  const double ticks = static_cast<double>(sc.num_ticks() + 1);
  const double us_tick = sc.duration / rtf[kRepeats / 2] / ticks * 1e6;
  double calls = 0.0;
  std::map<std::string, double> split = split_of(sc, calls);
  const auto us = [ticks](double ns) { return ns / ticks / 1e3; };  // [us per tick]
  out << "  " << std::left << std::setw(38) << c.label << std::right << std::fixed << std::setprecision(0)
      << std::setw(8) << rtf[kRepeats / 2] << "x real time (" << rtf[0] << " / " << rtf[kRepeats / 2] << " / "
      << rtf[kRepeats - 1] << ")  " << std::setprecision(2) << us_tick << " us per tick\n"
      << "      split [us per tick]: plant " << us(split["plant"]) << ", sensors " << us(split["sensors"])
      << ", FSW " << us(split["fsw"]) << ", recording " << us(split["recording"]) << ", other "
      << us(split["other"]) << "  (timer cost in these: " << us(pair_ns * calls) << ")\n";
  out.unsetf(std::ios::fixed);
  return true;
}

}  // namespace

int cmd_bench(const std::string& dir, const std::vector<std::string>& only, std::ostream& out, std::ostream& err)
{
  std::vector<Case> cases = reference_cases(dir);
  if (!select_cases(only, cases, err)) return kExitUsage;
  const double pair_ns = timer_pair_ns();
  out << "kestrel bench (" << version() << "): one core, FSW at 10 Hz (unless the case says otherwise), recording at 1 Hz (S2 as shipped), no files;\n"
      << "speed = simulated s per process-CPU s over " << kRepeats
      << " runs (min / median / max); split = one timed run, us per tick\n";
  for (const Case& c : cases) {
    try {
      if (!bench_case(c, pair_ns, out, err)) return kExitRunFailed;
    } catch (const ScenarioError& e) {
      print_issues(e, err);
      return kExitInvalidScenario;
    }
  }
  return kExitOk;
}

}  // namespace harness

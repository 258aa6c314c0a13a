// `kestrel bench`: real-time factors of the reference cases and where a
// tick's time goes (docs/performance.md).
//
// Each case runs kRepeats times as fast as it can, without output sinks
// (the recorder fills its rows; no file is written), and its speed is the
// process CPU time (min / median / max of the repeats).  One more run with
// the scheduler's profiling on times every task call and every plant step
// (steady clock) and gives the split per tick: plant, sensors, FSW,
// recording and other.  The timer's own cost is measured and printed; it
// is in the split's figures, not in the real-time factors.  The Monte
// Carlo case times a small campaign (`kestrel mc`, one thread) against the
// same number of bare runs.  With --callgrind, each case runs once more in
// a child process under valgrind's callgrind, counting the instructions of
// Run::step_ticks.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "cli/command_util.h"
#include "harness/cli/commands.h"
#include "harness/core/run.h"
#include "harness/mc/mc_journal.h"
#include "harness/mc/monte_carlo.h"
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
      {"plant", "plant"},         {"truth", "truth"},          {"sample_sensors", "sensors"},
      {"css", "sensors"},         {"sensors", "sensors"},      {"magnetometer", "sensors"},
      {"fsw_acs", "fsw"},         {"metrics", "recording"},    {"recorder", "recording"},
      {"mtq_state", "recording"}, {"events", "events"},        {"burn_monitor", "events"},
      {"actuators", "actuators"}, {"plant_input", "actuators"}, {"magnetorquers", "actuators"},
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
  uint64_t mc_runs = 0;  // > 0: a Monte Carlo campaign of this many runs (bench_mc)
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

// Extra S3 cases (docs/performance.md, "S3"): the detumble-and-hold
// scenario's first 2,000 s (B-dot on the rods, then the hold) with every
// environment model on and the magnetorquers driven, FSW at 10 Hz,
// dt = 0.1 s: fully-coupled wheels (a 0.13 kg rotor with a small wheel's
// imbalance, values of the class, assumed) at the
// 1 % jitter sub-step (16 sub-steps: the 3,000 rpm wheel starts at
// |Omega| h = 1.96 rad; over a day the wheels reach 2.16 rad, about 1 % on
// the jitter amplitude, docs/performance.md), and balanced wheels; and a Monte Carlo
// campaign of 20 short runs of the S3 campaign on one thread (--mc-runs,
// --mc-duration).
void s3_cases(const std::string& dir, std::vector<Case>& cases)
{
  const std::string hold = (fs::path(dir) / "s3_detumble_hold.yaml").string();
  const std::vector<Override> s3{{"duration", "2000"}};
  Case coupled{"s3-env", "S3 every environment model, fully coupled", hold, s3, true, true};
  for (const Override& o : std::vector<Override>{{"wheel_defaults.model", "fully_coupled"},
                                                 {"wheel_defaults.m_w", "0.13"},
                                                 {"wheel_defaults.U_s", "1.0e-7"},
                                                 {"wheel_defaults.U_d", "5.0e-9"},
                                                 {"rates.plant_substeps", "16"}})
    coupled.ov.push_back(o);
  cases.push_back(coupled);
  cases.push_back({"s3-env-balanced", "S3 every environment model, balanced", hold, s3, false, true});
  Case mc{"s3-mc", "S3 Monte Carlo", (fs::path(dir) / "s3_monte_carlo.yaml").string(), {{"duration", "300"}}, false, true};
  mc.mc_runs = 20;
  cases.push_back(mc);
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
  // Extra: S1's campaign as shipped (a wheel failure at a random time), 20 runs of 600 s.
  Case mc{"s1-mc", "S1 Monte Carlo", (fs::path(dir) / "s1_monte_carlo.yaml").string(), {}, false, true};
  mc.mc_runs = 20;
  cases.push_back(mc);
  s3_cases(dir, cases);
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

// Where a tick's time goes, from one profiled run [ns in all], by the
// categories of category() and "other"; `calls`: the timed calls.
std::map<std::string, double> split_of(const Scenario& sc, double& calls)
{
  Run run(sc, bench_config());
  run.set_profiling(true);
  const auto w0 = std::chrono::steady_clock::now();
  run.step_ticks(run.total_ticks());
  const double wall_ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - w0).count();
  std::map<std::string, double> split{{"plant", 0},  {"truth", 0},     {"sensors", 0},   {"fsw", 0},
                                      {"actuators", 0}, {"recording", 0}, {"events", 0}, {"other", 0}};
  double timed = 0.0;
  calls = 0.0;
  for (const auto& [name, ns] : run.profile()) {
    split[category(name)] += static_cast<double>(ns);
    timed += static_cast<double>(ns);
  }
  for (size_t i = 0; i < run.scheduler().num_tasks(); ++i) calls += static_cast<double>(run.scheduler().run_count(i));
  calls += static_cast<double>(sc.num_ticks());  // the plant's
  split["other"] += wall_ns - timed;             // the loop itself: between the timed calls
  return split;
}

// valgrind on PATH ("" when absent).
std::string find_valgrind()
{
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string d;
  while (std::getline(dirs, d, ':')) {
    const fs::path v = fs::path(d.empty() ? "." : d) / "valgrind";
    std::error_code ec;
    if (fs::is_regular_file(v, ec)) return v.string();
  }
  return "";
}

// Instructions of Run::step_ticks in one run of the case (`kestrel bench
// --case ID --once` under callgrind, in a child process); < 0 when the
// count failed.
double callgrind_instructions(const std::string& valgrind, const Case& c)
{
  const fs::path out = fs::temp_directory_path() / ("kestrel_bench_" + c.id + "_" + std::to_string(::getpid()) + ".cg");
  std::error_code ec;
  const std::string self = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) return -1.0;
  const std::string cmd = "'" + valgrind + "' --tool=callgrind --callgrind-out-file='" + out.string() +
                          "' --toggle-collect='harness::Run::step_ticks*' '" + self + "' bench --once --case " + c.id +
                          " >/dev/null 2>&1";
  double ir = -1.0;
  if (std::system(cmd.c_str()) == 0) {
    std::ifstream f(out);
    std::string line;
    while (std::getline(f, line))
      if (line.rfind("summary:", 0) == 0 || line.rfind("totals:", 0) == 0) ir = std::stod(line.substr(line.find(':') + 1));
  }
  fs::remove(out, ec);
  return ir;
}

// The split line of a case.
void print_split(std::map<std::string, double>& split, double ticks, double timer_ns, std::ostream& out)
{
  const auto us = [ticks](double ns) { return ns / ticks / 1e3; };  // [us per tick]
  out << std::fixed << std::setprecision(2) << "      split [us per tick]: plant " << us(split["plant"]) << ", truth "
      << us(split["truth"]) << ", sensors " << us(split["sensors"]) << ", FSW " << us(split["fsw"]) << ", actuators "
      << us(split["actuators"]) << ", recording " << us(split["recording"]) << ", events " << us(split["events"])
      << ", other " << us(split["other"]) << "  (timer cost in these: " << us(timer_ns) << ")\n";
  out.unsetf(std::ios::fixed);
}

// One case's lines; false when a run failed.
bool bench_case(const Case& c, const BenchOptions& o, double pair_ns, std::ostream& out, std::ostream& err)
{
  const Scenario sc = load_case(c);
  if (o.once) {  // the child of --callgrind: one plain run
    Run run(sc, bench_config());
    run.step_ticks(run.total_ticks());
    return run.failure().empty();
  }
  const std::vector<double> rtf = speeds(c, sc, err);
  if (rtf.empty()) return false;
  const double ticks = static_cast<double>(sc.num_ticks() + 1);
  const double us_tick = sc.duration / rtf[kRepeats / 2] / ticks * 1e6;
  double calls = 0.0;
  std::map<std::string, double> split = split_of(sc, calls);
  out << "  " << std::left << std::setw(38) << c.label << std::right << std::fixed << std::setprecision(0)
      << std::setw(8) << rtf[kRepeats / 2] << "x real time (" << rtf[0] << " / " << rtf[kRepeats / 2] << " / "
      << rtf[kRepeats - 1] << ")  " << std::setprecision(2) << us_tick << " us per tick";
  if (sc.rates.plant_substeps > 1) out << " (" << sc.rates.plant_substeps << " plant sub-steps)";
  out << "\n";
  out.unsetf(std::ios::fixed);
  print_split(split, ticks, pair_ns * calls, out);
  if (!o.valgrind.empty()) {
    const double ir = callgrind_instructions(o.valgrind, c);
    if (ir < 0) out << "      instructions per tick: (callgrind failed)\n";
    else out << "      instructions per tick (callgrind, Run::step_ticks): " << std::fixed << std::setprecision(0)
             << ir / ticks << "\n";
    out.unsetf(std::ios::fixed);
  }
  return true;
}

// The Monte Carlo cases: a campaign of c.mc_runs runs on one thread into a
// temporary folder (plan, runs with their manifests and the journal of
// records, the retained runs' full results, the summary files written from
// the journal: what `kestrel mc` does), against as many bare runs of the
// nominal scenario (built and run, no files): process CPU per run of each.
// Failing runs are not rerun for their full results: the short runs fail
// the campaigns' criteria by design, and those reruns are the retention's
// price.
double campaign_cpu(const Case& c, Scenario sc)
{
  sc.monte_carlo->retention.keep_failing = false;
  const McPlan plan = make_mc_plan(sc, sc.monte_carlo->seed, c.mc_runs);
  McRunOptions ro;
  for (uint64_t k = 0; k < c.mc_runs; ++k) ro.indices.push_back(k);
  const fs::path dir = fs::temp_directory_path() / ("kestrel_bench_mc_" + std::to_string(::getpid()));
  const double c0 = cpu_seconds();
  bool stopped = false;
  const std::vector<McRunState> states = run_mc_journal(plan, dir, ro, stopped);
  McSummaryInfo info;
  info.source = c.file;
  write_mc_outputs(plan, McJournalRecords(dir, states), info, dir);
  const double cpu = cpu_seconds() - c0;
  std::error_code ec;
  fs::remove_all(dir, ec);
  return cpu;
}

// The bare runs' process CPU per run.
double bare_cpu(const Case& c, const Scenario& sc)
{
  const double b0 = cpu_seconds();
  for (uint64_t k = 0; k < c.mc_runs; ++k) {
    Run run(sc, bench_config());
    run.step_ticks(run.total_ticks());
  }
  return (cpu_seconds() - b0) / static_cast<double>(c.mc_runs);
}

// part "both": the two halves one after the other and the overhead; "campaign"
// or "bare": that half alone, so that two processes can be timed in turn
// (interleaved pairs are steadier than two halves of one process on a machine
// whose speed drifts).
bool bench_mc(const Case& c, const std::string& part, std::ostream& out)
{
  const Scenario sc = load_case(c);
  std::ostringstream label;
  label << c.label << ", " << c.mc_runs << " runs of " << sc.duration << " s";
  out << "  " << std::left << std::setw(38) << label.str() << std::right << std::fixed << std::setprecision(2);
  if (part == "bare") {
    out << " bare run " << bare_cpu(c, sc) * 1e3 << " ms CPU per run\n";
  } else if (part == "campaign") {
    out << " campaign " << campaign_cpu(c, sc) / static_cast<double>(c.mc_runs) * 1e3 << " ms CPU per run\n";
  } else {
    const double bare = bare_cpu(c, sc);
    const double per_run = campaign_cpu(c, sc) / static_cast<double>(c.mc_runs);
    out << " campaign " << per_run * 1e3 << " ms CPU per run, bare run " << bare * 1e3 << " ms: overhead "
        << std::setprecision(1) << 100.0 * (per_run / bare - 1.0) << " %; " << std::setprecision(0)
        << sc.duration / bare << "x real time bare\n";
  }
  out.unsetf(std::ios::fixed);
  return true;
}

// --mc-runs, --mc-duration: the Monte Carlo cases' size.
void size_mc_cases(const BenchOptions& o, std::vector<Case>& cases)
{
  for (Case& c : cases) {
    if (c.mc_runs == 0) continue;
    if (o.mc_runs > 0) c.mc_runs = o.mc_runs;
    if (o.mc_duration <= 0.0) continue;
    c.ov.erase(std::remove_if(c.ov.begin(), c.ov.end(), [](const Override& ov) { return ov.path == "duration"; }),
               c.ov.end());
    c.ov.push_back({"duration", std::to_string(o.mc_duration)});
  }
}

}  // namespace

int cmd_bench(const std::string& dir, BenchOptions o, std::ostream& out, std::ostream& err)
{
  std::vector<Case> cases = reference_cases(dir);
  if (!select_cases(o.only, cases, err)) return kExitUsage;
  size_mc_cases(o, cases);
  if (o.callgrind && !o.once) {
    o.valgrind = find_valgrind();
    if (o.valgrind.empty()) out << "kestrel bench: --callgrind: no valgrind on PATH; instruction counts skipped\n";
  }
  const double pair_ns = o.once ? 0.0 : timer_pair_ns();
  if (!o.once)
    out << "kestrel bench (" << version() << "): one core, FSW at 10 Hz (unless the case says otherwise), recording at 1 Hz (S2 as shipped), no files;\n"
        << "speed = simulated s per process-CPU s over " << kRepeats
        << " runs (min / median / max); split = one timed run, us per tick\n";
  for (const Case& c : cases) {
    try {
      const bool ok = c.mc_runs > 0 ? (o.once || bench_mc(c, o.mc_part, out)) : bench_case(c, o, pair_ns, out, err);
      if (!ok) return kExitRunFailed;
    } catch (const ScenarioError& e) {
      print_issues(e, err);
      return kExitInvalidScenario;
    }
  }
  return kExitOk;
}

}  // namespace harness

// Results are all or nothing and never mixed (results_dir.h), and an
// interrupt keeps what was computed.  Most cases run the real `kestrel`
// executable in a child process, as a user would: re-runs, --force, a
// concurrent run on the same folder, SIGINT and SIGTERM, an unwritable
// parent, a file system that fills up (RLIMIT_FSIZE: the kernel fails the
// write exactly as on a full disk) and /dev/full.
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/drive/run_scenario.h"
#include "harness/output/results_dir.h"
#include "harness/scenario/scenario.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

fs::path fresh_dir(const std::string& name)
{
  const fs::path d = fs::temp_directory_path() / ("kestrel_rdir_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p)
{
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Files of `dir` whose name contains `part` (leftover working folders).
std::vector<std::string> entries_with(const fs::path& dir, const std::string& part)
{
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(part) != std::string::npos) out.push_back(e.path().filename().string());
  return out;
}

struct Child {
  pid_t pid = -1;
  fs::path err_file;
};

// Starts `kestrel run S1 -o out args...` with stderr to a file.  With
// fsize_limit > 0 the child's largest writable file size is limited
// (SIGXFSZ ignored, so writes fail with EFBIG like a full disk).
Child start_run(const fs::path& out, std::vector<std::string> args, const fs::path& err_file,
                rlim_t fsize_limit = 0)
{
  std::vector<std::string> argv = {KESTREL_EXE, "run", kS1, "-o", out.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  Child c;
  c.err_file = err_file;
  c.pid = fork();
  if (c.pid == 0) {
    if (fsize_limit > 0) {
      struct rlimit rl {fsize_limit, fsize_limit};
      setrlimit(RLIMIT_FSIZE, &rl);
      signal(SIGXFSZ, SIG_IGN);
    }
    FILE* e = std::freopen(err_file.c_str(), "w", stderr);
    FILE* o = std::freopen("/dev/null", "w", stdout);
    (void)e;
    (void)o;
    std::vector<char*> a;
    for (std::string& s : argv) a.push_back(s.data());
    a.push_back(nullptr);
    execv(KESTREL_EXE, a.data());
    _exit(127);
  }
  return c;
}

// Exit code (or 1000 + signal) of a child, killing it after `limit_s`.
int wait_exit(const Child& c, double limit_s = 120.0)
{
  const auto t0 = std::chrono::steady_clock::now();
  int status = 0;
  while (waitpid(c.pid, &status, WNOHANG) == 0) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > limit_s) {
      kill(c.pid, SIGKILL);
      waitpid(c.pid, &status, 0);
      ADD_FAILURE() << "kestrel did not end within " << limit_s << " s";
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 1000 + WTERMSIG(status);
}

int run_kestrel(const fs::path& out, const std::vector<std::string>& args, std::string* err = nullptr,
                rlim_t fsize_limit = 0)
{
  const fs::path ef = fs::temp_directory_path() / ("kestrel_rdir_stderr_" + std::to_string(getpid()) + ".txt");
  const int rc = wait_exit(start_run(out, args, ef, fsize_limit));
  if (err) *err = slurp(ef);
  return rc;
}

// Waits until a run has its working folder (it holds the lock and simulates).
bool wait_for_working_folder(const fs::path& parent, double limit_s = 30.0)
{
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < limit_s) {
    if (!entries_with(parent, ".kestrel-work-").empty()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

const std::vector<std::string> kShort = {"--set", "duration=10", "--set", "rates.dt=0.05", "--set",
                                         "rates.fsw_divisor=2"};
const std::vector<std::string> kLong = {"--set", "duration=200000", "--set", "rates.dt=0.05", "--set",
                                        "rates.fsw_divisor=2"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& more)
{
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// Checks an interrupted run's folder: every file present, marked incomplete
// with the time reached (the last row of results.h5), readable.
void expect_partial_results(const fs::path& out, const std::string& signal_name)
{
  const harness::Hdf5Table t = harness::read_hdf5((out / "results.h5").string());
  EXPECT_FALSE(t.complete);
  ASSERT_GT(t.rows, 10u);
  const double t_last = t.data[(t.rows - 1) * t.names.size() + 0];
  EXPECT_EQ(t.names[0], "t");
  EXPECT_LT(t_last, 200000.0);
  const json m = json::parse(slurp(out / "manifest.json"));
  EXPECT_EQ(m["result"]["complete"], false);
  EXPECT_EQ(m["result"]["stopped_by"], signal_name);
  EXPECT_DOUBLE_EQ(m["result"]["t_reached"].get<double>(), t_last);
  const std::string summary = slurp(out / "summary.txt");
  EXPECT_EQ(summary.rfind("# INCOMPLETE: stopped (" + signal_name + ")", 0), 0u) << summary;
  EXPECT_NE(summary.find("complete = 0"), std::string::npos);
  const json rd = json::parse(slurp(out / "report_data.json"));
  EXPECT_EQ(rd["meta"]["complete"], false);
  EXPECT_EQ(rd["meta"]["stopped_by"], signal_name);
  EXPECT_DOUBLE_EQ(rd["meta"]["t_reached"].get<double>(), t_last);
  EXPECT_EQ(rd["meta"]["rows"].get<uint64_t>(), t.rows);
#ifdef KESTREL_TEST_HAVE_REPORT
  EXPECT_TRUE(fs::exists(out / "report.html"));
#endif
  // and an analyst's usual reader opens it (Debian python3-h5py, installed by scripts/install-deps.sh)
  const std::string cmd = "/usr/bin/python3 -c \"import h5py,sys; f=h5py.File(sys.argv[1],'r'); "
                          "assert f.attrs['complete']==0; assert f['t'].shape[0]==" +
                          std::to_string(t.rows) + "\" " + (out / "results.h5").string();
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "h5py could not read " << out / "results.h5";
}

}  // namespace

TEST(ResultsDir, RunAppearsWholeAndLeavesNoWorkingFolder)
{
  const fs::path dir = fresh_dir("whole");
  const fs::path out = dir / "s1";
  ASSERT_EQ(run_kestrel(out, kShort), 0);
  for (const char* f : {"manifest.json", "results.h5", "report_data.json", "summary.txt", "fsw_health.txt"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_TRUE(entries_with(dir, ".kestrel-work-").empty());
  const json m = json::parse(slurp(out / "manifest.json"));
  EXPECT_EQ(m["result"]["complete"], true);
  EXPECT_EQ(m["result"]["ticks"], 201);
  EXPECT_DOUBLE_EQ(m["result"]["t_reached"].get<double>(), 10.0);
  EXPECT_TRUE(harness::read_hdf5((out / "results.h5").string()).complete);
}

TEST(ResultsDir, ExistingResultsAreRefusedUnlessForcedAndThenReplacedWhole)
{
  const fs::path dir = fresh_dir("rerun");
  const fs::path out = dir / "s1";
  ASSERT_EQ(run_kestrel(out, with(kShort, {"--csv"})), 0);
  ASSERT_TRUE(fs::exists(out / "telemetry.csv"));
  const std::string manifest1 = slurp(out / "manifest.json");
  const std::string h5_1 = slurp(out / "results.h5");
  std::string err;
  // refused: nothing run, nothing touched
  EXPECT_EQ(run_kestrel(out, with(kShort, {"--set", "seed=7"}), &err), 5);
  EXPECT_NE(err.find("already holds the results"), std::string::npos) << err;
  EXPECT_NE(err.find("--force"), std::string::npos) << err;
  EXPECT_EQ(slurp(out / "manifest.json"), manifest1);
  EXPECT_EQ(slurp(out / "results.h5"), h5_1);
  // --force: the new run replaces the old whole (no stale telemetry.csv)
  ASSERT_EQ(run_kestrel(out, with(kShort, {"--set", "seed=7", "--force"}), &err), 0) << err;
  EXPECT_FALSE(fs::exists(out / "telemetry.csv"));
  const json m = json::parse(slurp(out / "manifest.json"));
  EXPECT_EQ(m["scenario"]["seed"], 7);
  EXPECT_EQ(harness::read_hdf5((out / "results.h5").string()).seed, 7u);
  EXPECT_TRUE(entries_with(dir, ".kestrel-old-").empty());
  EXPECT_TRUE(entries_with(dir, ".kestrel-work-").empty());
}

TEST(ResultsDir, ForceNeverReplacesAFolderWithForeignFiles)
{
  const fs::path dir = fresh_dir("foreign");
  const fs::path out = dir / "mine";
  fs::create_directories(out);
  { std::ofstream(out / "notes.txt") << "my thesis\n"; }
  std::string err;
  EXPECT_EQ(run_kestrel(out, with(kShort, {"--force"}), &err), 5);
  EXPECT_NE(err.find("notes.txt"), std::string::npos) << err;
  EXPECT_EQ(slurp(out / "notes.txt"), "my thesis\n");
  EXPECT_FALSE(fs::exists(out / "manifest.json"));
  // a file (not a folder) as the target is refused too
  { std::ofstream(dir / "afile") << "x"; }
  EXPECT_EQ(run_kestrel(dir / "afile", with(kShort, {"--force"}), &err), 5);
  EXPECT_EQ(slurp(dir / "afile"), "x");
}

TEST(ResultsDir, ConcurrentRunIsRefusedAndSigintKeepsPartialResults)
{
  const fs::path dir = fresh_dir("sigint");
  const fs::path out = dir / "s1";
  const Child a = start_run(out, kLong, dir / "a_err.txt");
  ASSERT_TRUE(wait_for_working_folder(dir));
  std::string err;
  EXPECT_EQ(run_kestrel(out, kShort, &err), 5);  // the second run on the same folder
  EXPECT_NE(err.find("another kestrel run (pid " + std::to_string(a.pid) + ")"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out)) << "the refused run wrote into the folder";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(a.pid, SIGINT);
  EXPECT_EQ(wait_exit(a), 130);
  const std::string a_err = slurp(dir / "a_err.txt");
  EXPECT_NE(a_err.find("interrupted by SIGINT at t = "), std::string::npos) << a_err;
  EXPECT_NE(a_err.find("marked incomplete"), std::string::npos) << a_err;
  expect_partial_results(out, "SIGINT");
  EXPECT_TRUE(entries_with(dir, ".kestrel-work-").empty());
}

// The case that used to leave an unopenable results.h5 beside the older
// run's report: interrupting a forced re-run gives a folder holding only
// the new, partial run.
TEST(ResultsDir, SigtermDuringForcedRerunReplacesTheOldRunWhole)
{
  const fs::path dir = fresh_dir("sigterm");
  const fs::path out = dir / "s1";
  ASSERT_EQ(run_kestrel(out, with(kShort, {"--csv"})), 0);
  const Child a = start_run(out, with(kLong, {"--force"}), dir / "a_err.txt");
  ASSERT_TRUE(wait_for_working_folder(dir));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  // until the swap the older run is there, whole
  EXPECT_TRUE(fs::exists(out / "telemetry.csv"));
  kill(a.pid, SIGTERM);
  EXPECT_EQ(wait_exit(a), 143);
  expect_partial_results(out, "SIGTERM");
  EXPECT_FALSE(fs::exists(out / "telemetry.csv"));
  EXPECT_TRUE(entries_with(dir, ".kestrel-").size() == 1u);  // only the lock file
}

TEST(ResultsDir, UnwritableParentIsFoundBeforeSimulating)
{
  const fs::path dir = fresh_dir("unwritable");
  { std::ofstream(dir / "plainfile") << "x"; }
  std::string err;
  // a parent that is a file: exit 4 at once, even for a year-long run
  EXPECT_EQ(run_kestrel(dir / "plainfile" / "s1", {"--set", "duration=31536000"}, &err), 4);
  EXPECT_NE(err.find("cannot create its parent folder"), std::string::npos) << err;
  if (geteuid() != 0) {  // permission bits do not stop root
    fs::create_directories(dir / "ro");
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_EQ(run_kestrel(dir / "ro" / "s1", {"--set", "duration=31536000"}, &err), 4);
    EXPECT_NE(err.find("cannot write in"), std::string::npos) << err;
    fs::permissions(dir / "ro", fs::perms::owner_all);
  }
}

TEST(ResultsDir, FullDiskLosesNothingOfThePreviousResults)
{
  const fs::path dir = fresh_dir("full");
  const fs::path out = dir / "s1";
  ASSERT_EQ(run_kestrel(out, kShort), 0);
  const std::string manifest1 = slurp(out / "manifest.json");
  // 256 KiB per file: the 2,000 s run's results.h5 cannot fit
  std::string err;
  const int rc = run_kestrel(out, {"--force", "--set", "duration=2000"}, &err, 256 * 1024);
  EXPECT_EQ(rc, 4) << err;
  EXPECT_NE(err.find("output error"), std::string::npos) << err;
  EXPECT_NE(err.find("previous contents"), std::string::npos) << err;
  EXPECT_EQ(slurp(out / "manifest.json"), manifest1);
  EXPECT_TRUE(harness::read_hdf5((out / "results.h5").string()).complete);
  EXPECT_TRUE(entries_with(dir, ".kestrel-work-").empty());
  EXPECT_TRUE(entries_with(dir, ".kestrel-old-").empty());
}

TEST(ResultsDir, DevFullWritesAreErrors)
{
  EXPECT_THROW(harness::write_text("/dev/full", std::string(1 << 16, 'x')), harness::OutputError);
  harness::CsvSink csv("/dev/full");
  harness::RecordLayout layout;
  layout.columns.push_back({});
  layout.columns.back().name = "t";
  const std::vector<double> rows(8192, 1.0);
  bool threw = false;
  try {
    csv.begin(layout, rows.size());
    csv.write(rows.data(), rows.size());
    csv.end(true);
  } catch (const harness::OutputError&) {
    threw = true;
  }
  EXPECT_TRUE(threw);
}

TEST(ResultsDir, FreeSpaceIsCheckedBeforeSimulating)
{
  const fs::path dir = fresh_dir("space");
  EXPECT_GT(harness::free_bytes(dir), 0u);
  {
    harness::ResultsDir rd((dir / "s1").string(), false);
    EXPECT_TRUE(fs::is_directory(rd.work()));
    EXPECT_THROW(rd.require_free_space(std::numeric_limits<uint64_t>::max() / 2), harness::OutputError);
    EXPECT_NO_THROW(rd.require_free_space(1));
  }
  // not committed: the working folder is gone, the target never appeared
  EXPECT_TRUE(entries_with(dir, ".kestrel-work-").empty());
  EXPECT_FALSE(fs::exists(dir / "s1"));
}

// In the library: a stop request is honoured at the next chunk boundary and
// the rows up to it are written.
TEST(ResultsDir, StopRequestEndsAtATickBoundary)
{
  const fs::path dir = fresh_dir("stop");
  const harness::Scenario sc = harness::load_scenario(
      kS1, {{"duration", "100"}, {"rates.dt", "0.01"}, {"rates.record_divisor", "1"}});
  std::atomic<int> stop{0};
  harness::RunOptions opt;
  opt.out_dir = (dir / "s1").string();
  opt.stop = &stop;
  opt.progress = [&stop](double) { stop.store(SIGINT); };  // after the first chunk
  const harness::RunResult r = harness::run_scenario(sc, opt);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.stopped_by_signal, SIGINT);
  // 10,001 ticks: chunks of 10,001 / 200 = 50 ticks
  EXPECT_EQ(r.ticks, 50u);
  EXPECT_FALSE(r.status.complete);
  EXPECT_DOUBLE_EQ(r.status.t_reached, 0.49);
  const harness::Hdf5Table t = harness::read_hdf5((dir / "s1" / "results.h5").string());
  EXPECT_EQ(t.rows, 50u);
  EXPECT_FALSE(t.complete);
}

// A signal ends a paced run within the pacer's slice (50 ms) whatever the
// pacing: at --rt-scale 0.001 a tick of S1 (dt 0.01 s) is due every 10 s of
// wall time and at 1e-6 every 10,000 s; SIGINT took 8.7 s there and SIGTERM
// was ignored for 36 minutes at 1e-9.  The results of the tick done are
// kept, marked interrupted.  (The bound is 2 s so that a loaded machine
// does not fail it; the figure is printed.)
TEST(ResultsDir, SignalsEndASlowlyPacedRunPromptly)
{
  struct Case {
    int sig;
    const char* name;
    const char* scale;
    int code;
  };
  for (const Case& k : {Case{SIGINT, "SIGINT", "0.001", 130}, Case{SIGTERM, "SIGTERM", "1e-6", 143}}) {
    const fs::path dir = fresh_dir(std::string("paced_") + k.name);
    const fs::path out = dir / "s1";
    const Child a = start_run(out, {"--set", "duration=60", "--realtime", "--rt-scale", k.scale}, dir / "err.txt");
    ASSERT_TRUE(wait_for_working_folder(dir));
    std::this_thread::sleep_for(std::chrono::milliseconds(800));  // in the wait for tick 1
    const auto t0 = std::chrono::steady_clock::now();
    kill(a.pid, k.sig);
    const int rc = wait_exit(a, 60.0);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(rc, k.code) << slurp(dir / "err.txt");
    EXPECT_LT(dt, 2.0) << k.name;
    std::printf("%s at --rt-scale %s: kestrel ended %.0f ms after the signal\n", k.name, k.scale, dt * 1e3);
    std::fflush(stdout);  // before the next fork
    const json m = json::parse(slurp(out / "manifest.json"));
    EXPECT_EQ(m["result"]["complete"], false);
    EXPECT_EQ(m["result"]["stopped_by"], k.name);
    const harness::Hdf5Table t = harness::read_hdf5((out / "results.h5").string());
    EXPECT_FALSE(t.complete);
    EXPECT_GE(t.rows, 1u);  // tick 0, due at once
    EXPECT_EQ(slurp(out / "summary.txt").rfind(std::string("# INCOMPLETE: stopped (") + k.name + ")", 0), 0u);
  }
}

// A run killed outright (SIGKILL: nothing can clean up) leaves its working
// folder beside the results.  The next run of the same results says so,
// naming the folder and the pid, and prints the command that removes it
// (it removes nothing itself: the folder may hold the only copy of
// something); the command works, and then nothing is said.
TEST(ResultsDir, RerunNamesAKilledRunsLeftoverFolder)
{
  const fs::path dir = fresh_dir("leftover");
  const fs::path out = dir / "s1";
  const Child a = start_run(out, kLong, dir / "a_err.txt");
  ASSERT_TRUE(wait_for_working_folder(dir));
  kill(a.pid, SIGKILL);
  EXPECT_EQ(wait_exit(a), 1000 + SIGKILL);
  const fs::path left = dir / (".s1.kestrel-work-" + std::to_string(a.pid));
  ASSERT_TRUE(fs::is_directory(left));
  std::string err;
  ASSERT_EQ(run_kestrel(out, kShort, &err), 0) << err;
  EXPECT_NE(err.find(left.string() + " was left by an earlier run of s1 that was killed (pid " +
                     std::to_string(a.pid) + ", its unfinished results); nothing uses it: remove it with  rm -rf -- '" +
                     left.string() + "'"),
            std::string::npos)
      << err;
  EXPECT_TRUE(fs::is_directory(left));  // not removed by kestrel
  const size_t at = err.find("rm -rf -- ");
  ASSERT_NE(at, std::string::npos);
  const std::string cmd = err.substr(at, err.find('\n', at) - at);
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_FALSE(fs::exists(left));
  ASSERT_EQ(run_kestrel(out, with(kShort, {"--force"}), &err), 0) << err;
  EXPECT_EQ(err.find("was left by"), std::string::npos) << err;
}

// A campaign folder may hold records/ (an interrupted campaign's journal):
// --force replaces it whole; outside a campaign folder it is foreign.  A
// working folder told to stay (keep_work: a campaign's finished runs for
// --resume) outlives its ResultsDir; otherwise it is removed.
TEST(ResultsDir, CampaignJournalIsACampaignPartAndAKeptWorkingFolderStays)
{
  const fs::path dir = fresh_dir("journal");
  const fs::path camp = dir / "camp", run = dir / "run";
  fs::create_directories(camp / "records");
  { std::ofstream(camp / "mc_manifest.json") << "{}"; }
  { std::ofstream(camp / "records" / "000000.json") << "{}"; }
  {
    harness::ResultsDir r(camp.string(), true);
    r.commit();
  }
  EXPECT_FALSE(fs::exists(camp / "records"));
  fs::create_directories(run / "records");
  { std::ofstream(run / "manifest.json") << "{}"; }
  try {
    harness::ResultsDir r(run.string(), true);
    ADD_FAILURE() << "a run folder holding records/ was replaced";
  } catch (const harness::ResultsDirRefused& e) {
    EXPECT_NE(std::string(e.what()).find("records"), std::string::npos) << e.what();
  }
  fs::path kept, dropped;
  {
    harness::ResultsDir r((dir / "a").string(), false);
    kept = r.work();
    r.keep_work();
  }
  {
    harness::ResultsDir r((dir / "b").string(), false);
    dropped = r.work();
  }
  EXPECT_TRUE(fs::is_directory(kept));
  EXPECT_FALSE(fs::exists(dropped));
  fs::remove_all(dir);
}

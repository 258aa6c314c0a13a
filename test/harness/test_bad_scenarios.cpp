// The malformed-scenario corpus (bad_scenarios/*.yaml): the real `kestrel
// validate` program must reject every case with exit code 3 (invalid
// scenario; `# exit: N` for another code in 1..127), never crash, and print
// every "# expect:" fragment of the file (file name with the line number of
// the spoiled key, the key path and the reason; for a --set mistake the
// override's name).  Each case runs in a child process and must finish
// within 1 s and 200 MB peak RSS (measured with wait4's rusage; an address
// space limit stops a runaway early).  The fragments were written by hand.
//
// Directives in a case file (comment lines at its top):
//   # expect: <fragment>      printed somewhere in the output
//   # set: <key=value>        passed as --set <key=value>
//   # target: <path>          validate this path (relative to the source
//                             tree) instead of the case file itself
//   # exit: <code>            expected exit code (default 3)
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "harness/cli/commands.h"
#include "harness/scenario/scenario.h"

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> corpus()
{
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(KESTREL_TEST_BAD_DIR))
    if (e.path().extension() == ".yaml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The values of every "# <name>: " line of a case file.
std::vector<std::string> directive(const fs::path& p, const std::string& name)
{
  std::ifstream in(p, std::ios::binary);
  std::vector<std::string> out;
  std::string line;
  const std::string tag = "# " + name + ": ";
  while (std::getline(in, line))
    if (line.rfind(tag, 0) == 0) out.push_back(line.substr(tag.size()));
  return out;
}

std::vector<std::string> expected_fragments(const fs::path& p) { return directive(p, "expect"); }

#ifdef KESTREL_TEST_SANITIZE
constexpr double kMaxSeconds = 10.0;  // [s] ASan and UBSan slow everything down
constexpr long kMaxRssKb = 0;         // peak memory means nothing under ASan: not checked
#else
constexpr double kMaxSeconds = 1.0;       // [s]
constexpr long kMaxRssKb = 200L * 1024L;  // [KiB] 200 MB
#endif
constexpr double kKillSeconds = 20.0;  // [s] a hang is killed (and fails) after this

// One run of the kestrel program: exit status, output, wall time, peak RSS.
struct Child {
  int status = -1;
  std::string output;
  double seconds = 0.0;
  long max_rss_kb = 0;
  bool killed = false;
};

// `scenario_dir`: non-empty, the child's $KESTREL_SCENARIO_DIR (what `list` shows).
Child run_child(const std::vector<std::string>& args, const std::string& scenario_dir = "")
{
  Child r;
  int fds[2];
  if (pipe(fds) != 0) return r;
  std::vector<char*> argv;
  std::vector<std::string> all{KESTREL_EXE};
  all.insert(all.end(), args.begin(), args.end());
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
#ifndef KESTREL_TEST_SANITIZE
    // 1 GiB of address space: a runaway allocation fails fast in the child
    // instead of swapping the machine (the 200 MB RSS bound is checked below).
    const rlimit as{1L << 30, 1L << 30};
    setrlimit(RLIMIT_AS, &as);
#endif
    if (!scenario_dir.empty()) setenv("KESTREL_SCENARIO_DIR", scenario_dir.c_str(), 1);
    dup2(fds[1], 1);
    dup2(fds[1], 2);
    close(fds[0]);
    close(fds[1]);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(fds[1]);
  char buf[4096];
  for (;;) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (el > kKillSeconds && !r.killed) {
      kill(pid, SIGKILL);
      r.killed = true;
    }
    pollfd pfd{fds[0], POLLIN, 0};
    if (poll(&pfd, 1, 100) <= 0) continue;
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n <= 0) break;
    r.output.append(buf, static_cast<size_t>(n));
  }
  close(fds[0]);
  rusage ru{};
  wait4(pid, &r.status, 0, &ru);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.max_rss_kb = ru.ru_maxrss;
  return r;
}

// Bounded: within kMaxSeconds and kMaxRssKb, not killed.
void expect_bounded(const Child& c)
{
  EXPECT_FALSE(c.killed) << "killed after " << kKillSeconds << " s";
  EXPECT_LT(c.seconds, kMaxSeconds) << "took " << c.seconds << " s";
  if (kMaxRssKb > 0) {
    EXPECT_LT(c.max_rss_kb, kMaxRssKb) << "peak RSS " << c.max_rss_kb << " KiB";
  }
}

// The arguments of `kestrel validate` for a case file.
std::vector<std::string> validate_args(const fs::path& f)
{
  std::vector<std::string> args{"validate"};
  const std::vector<std::string> target = directive(f, "target");
  if (target.empty()) args.push_back(f.string());
  else if (fs::path(target.front()).is_absolute()) args.push_back(target.front());
  else args.push_back((fs::path(KESTREL_SOURCE_DIR) / target.front()).string());
  for (const std::string& s : directive(f, "set")) {
    args.push_back("--set");
    args.push_back(s);
  }
  return args;
}

struct Proc {
  int status = -1;
  std::string output;
};

Proc run_exe(const std::string& args)
{
  Proc r;
  const std::string cmd = std::string("\"") + KESTREL_EXE + "\" " + args + " 2>&1";
  FILE* f = popen(cmd.c_str(), "r");
  if (!f) return r;
  char buf[4096];
  size_t n = 0;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0) r.output.append(buf, n);
  r.status = pclose(f);
  return r;
}

}  // namespace

TEST(BadScenarios, CorpusHasAtLeastAHundredCasesEachWithExpectations)
{
  const auto files = corpus();
  EXPECT_GE(files.size(), 100u);
  for (const auto& f : files) EXPECT_GE(expected_fragments(f).size(), 2u) << f;
}

TEST(BadScenarios, KestrelValidateRejectsEachWithAPreciseMessageInBoundedTimeAndMemory)
{
  for (const fs::path& f : corpus()) {
    SCOPED_TRACE(f.filename().string());
    const Child p = run_child(validate_args(f));
    ASSERT_TRUE(WIFEXITED(p.status)) << "crashed or killed: status " << p.status << "\n" << p.output;
    const std::vector<std::string> want = directive(f, "exit");
    const int code = want.empty() ? harness::kExitInvalidScenario : std::stoi(want.front());
    EXPECT_GE(code, 1);
    EXPECT_LE(code, 127);
    EXPECT_EQ(WEXITSTATUS(p.status), code) << p.output;
    for (const std::string& frag : expected_fragments(f))
      EXPECT_NE(p.output.find(frag), std::string::npos) << "missing '" << frag << "' in:\n" << p.output;
    if (code == harness::kExitInvalidScenario) {
      EXPECT_NE(p.output.find("nothing was run"), std::string::npos) << p.output;
    }
    // every problem line has a place: file:line:col or the --set it came from
    size_t start = 0;
    for (size_t nl; (nl = p.output.find('\n', start)) != std::string::npos; start = nl + 1) {
      const std::string line = p.output.substr(start, nl - start);
      if (line.rfind("kestrel:", 0) == 0) continue;
      const bool placed = line.find(": --set ") != std::string::npos ||
                          line.find(".yaml:") != std::string::npos || line.find(".json:") != std::string::npos;
      const bool file_level = line.find(": (file): ") != std::string::npos;
      EXPECT_TRUE(placed || file_level) << "no place in: " << line;
    }
    expect_bounded(p);
  }
}

TEST(BadScenarios, ListOfTheWholeCorpusIsBounded)
{
  // `kestrel list` reads every file of a folder: the alias bombs, deep
  // nesting and huge durations of the corpus must not slow it down.
  const Child p = run_child({"list"}, KESTREL_TEST_BAD_DIR);
  ASSERT_TRUE(WIFEXITED(p.status)) << p.output;
  EXPECT_EQ(WEXITSTATUS(p.status), 0) << p.output;
  EXPECT_NE(p.output.find("invalid"), std::string::npos) << p.output;
  EXPECT_FALSE(p.killed);
  EXPECT_LT(p.seconds, 5.0 * kMaxSeconds) << "took " << p.seconds << " s";
  if (kMaxRssKb > 0) {
    EXPECT_LT(p.max_rss_kb, kMaxRssKb) << "peak RSS " << p.max_rss_kb << " KiB";
  }
}

TEST(BadScenarios, ValidateOfALongRunAllocatesNoRunStorage)
{
  // 6e5 s at dt = 0.01 s is 6e7 steps: validation must not size anything by it.
  const std::string s1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";
  const Child p = run_child({"validate", s1, "--set", "duration=600000"});
  ASSERT_TRUE(WIFEXITED(p.status)) << p.output;
  EXPECT_EQ(WEXITSTATUS(p.status), 0) << p.output;
  expect_bounded(p);
  const Child q = run_child({"validate", s1, "--set", "duration=6e8"});
  ASSERT_TRUE(WIFEXITED(q.status)) << q.output;
  EXPECT_EQ(WEXITSTATUS(q.status), 0) << q.output;
  expect_bounded(q);
}

TEST(BadScenarios, RunRefusesToStartAndWritesNothing)
{
  const fs::path out = fs::temp_directory_path() / "kestrel_bad_run_out";
  fs::remove_all(out);
  const fs::path f = corpus().front();
  const Proc p = run_exe("run \"" + f.string() + "\" -o \"" + out.string() + "\"");
  ASSERT_TRUE(WIFEXITED(p.status));
  EXPECT_EQ(WEXITSTATUS(p.status), harness::kExitInvalidScenario);
  EXPECT_FALSE(fs::exists(out));
}

TEST(BadScenarios, LibraryLoaderGivesTheSameIssues)
{
  for (const fs::path& f : corpus()) {
    SCOPED_TRACE(f.filename().string());
    try {
      harness::load_scenario(f.string());
      // some problems are found only by the plant/FSW checks (validate runs them)
    } catch (const harness::ScenarioError& e) {
      ASSERT_FALSE(e.issues().empty());
      for (const auto& is : e.issues()) {
        EXPECT_FALSE(is.key.empty());
        EXPECT_FALSE(is.message.empty());
      }
    }
  }
}

TEST(BadScenarios, MissingFileAndBadSet)
{
  Proc p = run_exe("validate /nonexistent/kestrel.yaml");
  ASSERT_TRUE(WIFEXITED(p.status));
  EXPECT_EQ(WEXITSTATUS(p.status), harness::kExitInvalidScenario);
  EXPECT_NE(p.output.find("/nonexistent/kestrel.yaml"), std::string::npos);
  EXPECT_NE(p.output.find("cannot open"), std::string::npos);

  const std::string s1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";
  p = run_exe("validate \"" + s1 + "\" --set fsw.mrp_fb.K=-2");
  ASSERT_TRUE(WIFEXITED(p.status));
  EXPECT_EQ(WEXITSTATUS(p.status), harness::kExitInvalidScenario);
  EXPECT_NE(p.output.find("--set fsw.mrp_fb.K"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("must be > 0"), std::string::npos) << p.output;

  p = run_exe("validate \"" + s1 + "\" --set nonsense");
  ASSERT_TRUE(WIFEXITED(p.status));
  EXPECT_EQ(WEXITSTATUS(p.status), harness::kExitUsage);
}

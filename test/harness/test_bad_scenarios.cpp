// The malformed-scenario corpus (bad_scenarios/*.yaml): the real `kestrel
// validate` program must reject every file with exit code 3 (invalid
// scenario), never crash, and print every "# expect:" fragment of the file
// (file name with the line number of the spoiled key, the key path and the
// reason).  The fragments were written by hand from the file contents.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "harness/commands.h"
#include "harness/scenario.h"

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

std::vector<std::string> expected_fragments(const fs::path& p)
{
  std::ifstream in(p);
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("# expect: ", 0) == 0) out.push_back(line.substr(10));
  return out;
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

TEST(BadScenarios, CorpusHasAtLeastTwentyFilesEachWithExpectations)
{
  const auto files = corpus();
  EXPECT_GE(files.size(), 20u);
  for (const auto& f : files) EXPECT_GE(expected_fragments(f).size(), 2u) << f;
}

TEST(BadScenarios, KestrelValidateRejectsEachWithAPreciseMessage)
{
  for (const fs::path& f : corpus()) {
    SCOPED_TRACE(f.filename().string());
    const Proc p = run_exe("validate \"" + f.string() + "\"");
    ASSERT_TRUE(WIFEXITED(p.status)) << "crashed or killed: status " << p.status << "\n" << p.output;
    EXPECT_EQ(WEXITSTATUS(p.status), harness::kExitInvalidScenario) << p.output;
    for (const std::string& frag : expected_fragments(f))
      EXPECT_NE(p.output.find(frag), std::string::npos) << "missing '" << frag << "' in:\n" << p.output;
    EXPECT_NE(p.output.find("nothing was run"), std::string::npos) << p.output;
  }
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

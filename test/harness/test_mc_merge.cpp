// `kestrel mc merge` reads shards it did not write (docs/monte-carlo.md,
// "What merge checks"): every field of a shard's mc_manifest.json and
// mc_runs.json is checked against the campaign before anything is written,
// links inside a shard are never followed, and a refusal names the shard's
// file and the field.  The shards here are two real shards of a 6-run
// campaign of the S1 campaign shortened to 20 s runs (data/mc_short.yaml;
// the gain cut tenfold, so runs fail their `settled` criterion), tampered
// with one field at a time.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/cli/commands.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const uint64_t kRuns = 6;

// The test's scratch folder, removed when the program ends.
struct Scratch {
  fs::path root = fs::temp_directory_path() / ("kestrel-mc-merge-test-" + std::to_string(getpid()));
  Scratch()
  {
    fs::remove_all(root);
    fs::create_directories(root);
  }
  ~Scratch()
  {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
};

fs::path scratch_root()
{
  static const Scratch s;
  return s.root;
}

// Shards 0/2 and 1/2 of the campaign, made once per test program.
const fs::path& pristine()
{
  static const fs::path dir = [] {
    const fs::path d = scratch_root() / "pristine";
    for (uint32_t i = 0; i < 2; ++i) {
      harness::McCommand c;
      // the shipped S1 campaign shortened to 20 s runs (test/harness/data/
      // mc_short.yaml), so that it is short in every preset, the sanitizers'
      // included; the gain cut tenfold fails `settled` in every run
      c.scenario = std::string(KESTREL_SOURCE_DIR) + "/test/harness/data/mc_short.yaml";
      c.sets = {"fsw.mrp_fb.K=0.01"};
      c.runs = kRuns;
      c.seed = 7;
      c.shard_index = i;
      c.shard_count = 2;
      c.out_dir = (d / ("s" + std::to_string(i))).string();
      std::ostringstream out, err;
      const int rc = harness::cmd_mc(c, out, err);
      if (rc != harness::kExitOk && rc != harness::kExitMcFailures) {
        ADD_FAILURE() << "making shard " << i << ": exit " << rc << ": " << err.str();
      }
    }
    return d;
  }();
  return dir;
}

json load(const fs::path& p)
{
  std::ifstream in(p);
  return json::parse(in);
}

void save(const fs::path& p, const json& j)
{
  std::ofstream o(p, std::ios::trunc);
  o << j.dump(2) << "\n";
}

struct Merged {
  int rc = -1;
  std::string out, err;
  fs::path dir;
};

class McMerge : public ::testing::Test {
 protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = scratch_root() / info->name();
    fs::remove_all(work_);
    fs::create_directories(work_);
    for (const char* s : {"s0", "s1"}) fs::copy(pristine() / s, work_ / s, fs::copy_options::recursive);
  }

  fs::path shard(int i) const { return work_ / ("s" + std::to_string(i)); }
  fs::path manifest(int i) const { return shard(i) / "mc_manifest.json"; }
  fs::path runs_json(int i) const { return shard(i) / "mc_runs.json"; }

  Merged merge() const
  {
    Merged m;
    m.dir = work_ / "merged";
    std::ostringstream out, err;
    m.rc = harness::cmd_mc_merge(m.dir.string(), {shard(0).string(), shard(1).string()}, false, out, err);
    m.out = out.str();
    m.err = err.str();
    return m;
  }

  // Refused: exit 2, a message naming the shard's file and the field, and
  // nothing written where the merged campaign would go.
  static void expect_refused(const Merged& m, const fs::path& file, const std::string& field)
  {
    EXPECT_EQ(m.rc, harness::kExitUsage) << m.err;
    EXPECT_NE(m.err.find(file.string()), std::string::npos) << "the message names " << file << ": " << m.err;
    EXPECT_NE(m.err.find(field), std::string::npos) << "the message names the field " << field << ": " << m.err;
    EXPECT_FALSE(fs::exists(m.dir)) << "a refused merge wrote " << m.dir;
  }

  fs::path work_;
};

TEST_F(McMerge, UntouchedShardsMerge)
{
  const Merged m = merge();
  ASSERT_EQ(m.rc, harness::kExitMcFailures) << m.err;  // every run fails `settled`, as made
  const json recs = load(m.dir / "mc_runs.json");
  ASSERT_EQ(recs.at("records").size(), kRuns);
  for (uint64_t k = 0; k < kRuns; ++k) EXPECT_EQ(recs["records"][k]["index"].get<uint64_t>(), k);
  EXPECT_TRUE(fs::exists(m.dir / "summary.h5"));
  EXPECT_TRUE(fs::exists(m.dir / "runs" / "000005" / "manifest.json"));
}

TEST_F(McMerge, EmptySeriesRefused)
{
  json r = load(runs_json(1));
  r["records"][0]["series"] = json::array();
  save(runs_json(1), r);
  expect_refused(merge(), runs_json(1), "records[0].series");
}

TEST_F(McMerge, ShortDrawnRefused)
{
  json r = load(runs_json(0));
  json& d = r["records"][1]["drawn"];
  ASSERT_GT(d.size(), 1u);
  d.erase(d.size() - 1);
  save(runs_json(0), r);
  expect_refused(merge(), runs_json(0), "records[1].drawn");
}

TEST_F(McMerge, EmptyMetricsRefused)
{
  json r = load(runs_json(0));
  r["records"][2]["metrics"] = json::array();
  save(runs_json(0), r);
  expect_refused(merge(), runs_json(0), "records[2].metrics");
}

TEST_F(McMerge, ManifestWithoutScenarioRefused)
{
  for (int i : {0, 1}) {
    json m = load(manifest(i));
    m.erase("scenario");
    save(manifest(i), m);
  }
  expect_refused(merge(), manifest(0), "scenario");
}

TEST_F(McMerge, SecondManifestWithoutScenarioRefused)
{
  json m = load(manifest(1));
  m.erase("scenario");
  save(manifest(1), m);
  expect_refused(merge(), manifest(1), "scenario");
}

TEST_F(McMerge, CompleteOfWrongTypeRefused)
{
  json m = load(manifest(1));
  m["complete"] = "yes";
  save(manifest(1), m);
  expect_refused(merge(), manifest(1), "complete");
}

TEST_F(McMerge, MasterSeedOfWrongTypeRefused)
{
  for (int i : {0, 1}) {
    json m = load(manifest(i));
    m["master_seed"] = "7";
    save(manifest(i), m);
  }
  expect_refused(merge(), manifest(0), "master_seed");
}

TEST_F(McMerge, NegativeMasterSeedRefused)
{
  for (int i : {0, 1}) {
    json m = load(manifest(i));
    m["master_seed"] = -1;
    save(manifest(i), m);
  }
  expect_refused(merge(), manifest(0), "master_seed");
}

TEST_F(McMerge, OverrideNotKeyValueRefused)
{
  for (int i : {0, 1}) {
    json m = load(manifest(i));
    m["overrides"] = json::array({"duration"});
    save(manifest(i), m);
  }
  expect_refused(merge(), manifest(0), "overrides[0]");
}

TEST_F(McMerge, TrillionRunsRefused)
{
  for (int i : {0, 1}) {
    json m = load(manifest(i));
    m["runs"] = 1000000000000ULL;
    save(manifest(i), m);
  }
  expect_refused(merge(), manifest(0), "runs");
}

TEST_F(McMerge, RecordsAllSetToPassRefused)
{
  for (int i : {0, 1}) {
    json r = load(runs_json(i));
    for (json& x : r["records"]) {
      x["pass"] = true;
      x["reason"] = "";
    }
    save(runs_json(i), r);
  }
  expect_refused(merge(), runs_json(0), "records[0].pass");
}

TEST_F(McMerge, IndexBeyondTheCampaignRefused)
{
  json r = load(runs_json(1));
  r["records"][0]["index"] = 99999;
  save(runs_json(1), r);
  expect_refused(merge(), runs_json(1), "records[0].index");
}

TEST_F(McMerge, IndexOfAnotherShardRefused)
{
  // shard 0 of 2 holds the even runs; run 1 moved into it (and out of shard 1)
  // (the manifests' counts and hashes moved along: only the partition tells)
  json r0 = load(runs_json(0)), r1 = load(runs_json(1)), m0 = load(manifest(0)), m1 = load(manifest(1));
  r0["records"].push_back(r1["records"][0]);
  r1["records"].erase(0);
  m0["record_fnv1a64"].push_back(m1["record_fnv1a64"][0]);
  m1["record_fnv1a64"].erase(0);
  m0["runs_done"] = 4;
  m1["runs_done"] = 2;
  save(runs_json(0), r0);
  save(runs_json(1), r1);
  save(manifest(0), m0);
  save(manifest(1), m1);
  expect_refused(merge(), runs_json(0), "records[3].index");
}

TEST_F(McMerge, SeedNotTheDrawnOneRefused)
{
  json r = load(runs_json(0));
  r["records"][1]["seed"] = r["records"][1]["seed"].get<uint64_t>() + 1;
  save(runs_json(0), r);
  expect_refused(merge(), runs_json(0), "records[1].seed");
}

TEST_F(McMerge, DrawnValueNotTheDrawnOneRefused)
{
  json r = load(runs_json(1));
  json& v = r["records"][2]["drawn"][0];
  v = v.get<double>() * 1.5 + 1.0;
  save(runs_json(1), r);
  expect_refused(merge(), runs_json(1), "records[2].drawn[0]");
}

TEST_F(McMerge, EditedMetricRefusedByItsHash)
{
  // a metric changed, the record still consistent (failing): only the
  // manifest's hash of the record tells
  json r = load(runs_json(0));
  json& v = r["records"][0]["metrics"][0];
  ASSERT_TRUE(v.is_number());
  v = v.get<double>() + 1.0;
  save(runs_json(0), r);
  expect_refused(merge(), runs_json(0), "records[0]");
  const Merged m = merge();
  EXPECT_NE(m.err.find("hash"), std::string::npos) << m.err;
}

TEST_F(McMerge, EditedScenarioRefusedByItsHash)
{
  for (int i : {0, 1}) {
    json m = load(manifest(i));
    m["scenario"]["duration"] = 900.0;
    save(manifest(i), m);
  }
  expect_refused(merge(), manifest(0), "scenario");
}

TEST_F(McMerge, RunsDoneNotTheRecordsRefused)
{
  json m = load(manifest(1));
  m["runs_done"] = 2;
  save(manifest(1), m);
  expect_refused(merge(), manifest(1), "runs_done");
}

TEST_F(McMerge, SymlinkInRunsRefusedAndNotFollowed)
{
  const fs::path secret = work_ / "secret.txt";
  {
    std::ofstream(secret) << "not part of any campaign\n";
  }
  fs::create_symlink(secret, shard(0) / "runs" / "000000" / "notes.txt");
  const Merged m = merge();
  expect_refused(m, shard(0) / "runs" / "000000" / "notes.txt", "link");
}

TEST_F(McMerge, SymlinkedRunFolderRefused)
{
  fs::remove_all(shard(1) / "runs" / "000003");
  fs::create_directory_symlink(shard(0) / "runs" / "000000", shard(1) / "runs" / "000003");
  expect_refused(merge(), shard(1) / "runs" / "000003", "link");
}

TEST_F(McMerge, SymlinkedRecordsFileRefused)
{
  fs::rename(runs_json(1), work_ / "elsewhere.json");
  fs::create_symlink(work_ / "elsewhere.json", runs_json(1));
  expect_refused(merge(), runs_json(1), "link");
}

TEST_F(McMerge, StrayFolderInRunsRefused)
{
  fs::create_directories(shard(0) / "runs" / "000001");  // an odd run in the even shard, without a record
  expect_refused(merge(), shard(0) / "runs" / "000001", "runs/");
}

// `--only ""` runs nothing rather than everything: refused with a message.
TEST(McOnly, EmptyListRefused)
{
  const fs::path out = scratch_root() / "only-empty";
  const std::string cmd = std::string(KESTREL_EXE) + " mc " + KESTREL_SOURCE_DIR +
                          "/scenarios/s1_monte_carlo.yaml --runs 2 --only '' -o " + out.string() + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string text;
  char buf[256];
  while (fgets(buf, sizeof buf, p)) text += buf;
  const int st = pclose(p);
  ASSERT_TRUE(WIFEXITED(st)) << text;
  EXPECT_EQ(WEXITSTATUS(st), harness::kExitUsage) << text;
  EXPECT_NE(text.find("--only"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(out)) << "an empty --only ran the campaign";
}

}  // namespace

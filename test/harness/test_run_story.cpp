// The run's own story in report_data.json and summary.txt (one source):
// exact thruster valve-open times, every warning, the requirement lines.
// Expected values come from the scenario (a burn's duration), from the
// recorded commands summed independently here, or from the recorded rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/drive/run_scenario.h"
#include "harness/scenario/scenario.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kDir = std::string(KESTREL_SOURCE_DIR) + "/scenarios/";

struct Tmp {
  fs::path p;
  explicit Tmp(const std::string& name) : p(fs::temp_directory_path() / ("kestrel_story_" + name + "_" + std::to_string(::getpid())))
  {
    fs::remove_all(p);
  }
  ~Tmp() { fs::remove_all(p); }
};

std::string slurp(const fs::path& f)
{
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Story {
  json data;
  std::string summary;
  harness::MemorySink rows;
  harness::RunResult res;
};

// Runs sc into dir with every row kept in memory too.
void run_into(const harness::Scenario& sc, const fs::path& dir, Story& s)
{
  harness::RunOptions o;
  o.out_dir = dir.string();
  o.extra_sinks.push_back(&s.rows);
  s.res = harness::run_scenario(sc, o);
  ASSERT_TRUE(s.res.ok) << s.res.failure;
  s.data = json::parse(slurp(dir / "report_data.json"));
  s.summary = slurp(dir / "summary.txt");
}

double item(const json& d, const std::string& key)
{
  EXPECT_TRUE(d["summary"].contains(key)) << key;
  return d["summary"].contains(key) ? d["summary"][key]["value"].get<double>() : NAN;
}

}  // namespace

// S2 with a 7.3 s burn, the plant at the thruster command period (0.1 s),
// every FSW cycle recorded, the ACS thrusters' minimum on-time off: the
// engine's valve-open time is the burn's duration, and each ACS thruster's
// is the sum of its commanded on-times clipped to [0, T_upd], every command
// but the last tick's (latched at its own tick; the last is never stepped).
TEST(RunStory, ThrusterOnTimesAreExact)
{
  std::vector<harness::Override> ov = {{"duration", "20"},      {"burn.start", "5"},         {"burn.duration", "7.3"},
                                       {"rates.dt", "0.1"},     {"rates.fsw_divisor", "1"},  {"rates.record_divisor", "1"}};
  for (int j = 1; j <= 8; ++j) ov.push_back({"thrusters[" + std::to_string(j) + "].T_min", "0"});
  const harness::Scenario sc = harness::load_scenario(kDir + "s2_mars_orbit_insertion.yaml", ov);
  Tmp tmp("s2");
  Story s;
  run_into(sc, tmp.p, s);
  EXPECT_NEAR(item(s.data, "on_time_main_s"), 7.3, 1e-9);
  double total = item(s.data, "on_time_main_s"), acs_sum = 0.0;
  const uint64_t n = s.rows.rows();
  for (int j = 1; j <= 8; ++j) {
    const size_t c = s.rows.column_index("thruster_on_time_" + std::to_string(j));
    double want = 0.0;
    for (uint64_t r = 0; r + 1 < n; ++r) want += std::min(std::max(s.rows.at(r, c), 0.0), 0.1);
    const double got = item(s.data, "on_time_" + sc.thrusters[static_cast<size_t>(j)].name + "_s");
    EXPECT_NEAR(got, want, 1e-9) << sc.thrusters[static_cast<size_t>(j)].name;
    total += got;
    acs_sum += want;
  }
  EXPECT_GT(acs_sum, 0.05);  // the ACS thrusters did fire (holding the burn's torque)
  EXPECT_NEAR(item(s.data, "on_time_total_s"), total, 1e-9);
  // one source: summary.txt lists the same items in the same order
  std::vector<std::string> keys;
  std::istringstream in(s.summary);
  for (std::string l; std::getline(in, l);)
    if (!l.empty() && l[0] != '#') keys.push_back(l.substr(0, l.find(" = ")));
  ASSERT_TRUE(s.data.contains("summary_order"));
  EXPECT_EQ(keys, s.data["summary_order"].get<std::vector<std::string>>());
  EXPECT_NE(s.summary.find("on_time_main_s = 7.3 s"), std::string::npos) << s.summary;
  EXPECT_TRUE(s.data["warnings"].empty());
  EXPECT_TRUE(s.data["requirements"].empty());  // S2 has no criteria
}

// A jittering wheel at 5000 rpm with one plant step of 0.01 s per tick
// turns 5.2 rad per step (> 2): the warning before the run and the one
// after it are in summary.txt and report_data.json, word for word.
TEST(RunStory, WarningsReachSummaryAndReport)
{
  const harness::Scenario sc =
      harness::load_scenario(kDir + "s1_sun_pointing.yaml", {{"duration", "1"}, {"rates.plant_substeps", "1"},
                                                             {"wheels[0].Omega_0_rpm", "5000"}});
  Tmp tmp("jitter");
  Story s;
  run_into(sc, tmp.p, s);
  const auto w = s.data["warnings"].get<std::vector<std::string>>();
  ASSERT_GE(w.size(), 2u);
  EXPECT_EQ(w[0].rfind("wheels[0] (", 0), 0u) << w[0];
  EXPECT_NE(w[0].find("under-resolved"), std::string::npos);
  bool after = false;
  for (const std::string& x : w) {
    after = after || x.rfind("a jittering wheel reached |Omega| h = ", 0) == 0;
    EXPECT_NE(s.summary.find("# warning: " + x + "\n"), std::string::npos) << x;
  }
  EXPECT_TRUE(after);
  EXPECT_EQ(w, s.res.warnings);
}

// The demonstration campaign's scenario run alone with a low and a high
// gain: its criteria are the run's requirement lines, PASS/FAIL with the
// measured value, which is the max of the recorded pointing error over
// t >= 30 s computed here.
TEST(RunStory, RequirementLinesPassAndFail)
{
  for (const char* K : {"0.7", "4.5"}) {
    const harness::Scenario sc = harness::load_scenario(kDir + "mc_demo_drivers.yaml", {{"fsw.mrp_fb.K", K}});
    Tmp tmp(std::string("req") + K);
    Story s;
    run_into(sc, tmp.p, s);
    const auto t = s.rows.column("t"), e = s.rows.column("pointing_error_deg");
    double mx = -INFINITY;
    for (size_t i = 0; i < t.size(); ++i)
      if (t[i] >= 30.0) mx = std::max(mx, e[i]);
    const bool want_pass = mx < 2.0;
    EXPECT_EQ(want_pass, std::string(K) == "4.5") << "the scenario no longer separates the gains: " << mx;
    const json& req = s.data["requirements"];
    ASSERT_EQ(req.size(), 2u);
    EXPECT_EQ(req[0]["name"], "settled");
    EXPECT_EQ(req[0]["value"].get<double>(), mx);
    EXPECT_EQ(req[0]["threshold"].get<double>(), 2.0);
    EXPECT_EQ(req[0]["pass"].get<bool>(), want_pass);
    EXPECT_EQ(req[1]["name"], "no_fsw_error");
    EXPECT_TRUE(req[1]["pass"].get<bool>());
    EXPECT_NE(s.summary.find(std::string("requirement_settled = ")), std::string::npos);
    EXPECT_NE(s.summary.find(want_pass ? "# PASS: max of pointing_error_deg for t >= 30 s below 2"
                                       : "# FAIL: max of pointing_error_deg for t >= 30 s below 2"),
              std::string::npos)
        << s.summary;
  }
}

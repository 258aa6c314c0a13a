// Regression against the pre-change results: S1 (60 s, as shipped: fully
// coupled wheels, sensor noise on) and S2 (40 s with a 20 s burn) recorded
// with the harness of commit c4b044e (test/harness/data/README.md) must be
// reproduced by today's harness, column by column.  The reshaping of the
// harness (tasks, sinks, endpoint) changes no number; where a later physics
// change does, the columns it changes are named here with the bound it keeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "harness/run.h"
#include "harness/scenario.h"

namespace {

struct Csv {
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
};

Csv read_csv(const std::string& path)
{
  Csv c;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return c;
  std::stringstream hs(line);
  std::string h;
  while (std::getline(hs, h, ',')) c.names.push_back(h.substr(0, h.find(" [")));
  c.cols.resize(c.names.size());
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::string v;
    for (size_t k = 0; std::getline(ls, v, ',') && k < c.cols.size(); ++k) c.cols[k].push_back(std::stod(v));
  }
  return c;
}

// Columns allowed to differ from the baseline, with the largest difference
// allowed relative to the column's largest magnitude (empty: none).
using Allowed = std::map<std::string, double>;

void compare(const std::string& baseline, const harness::Scenario& sc, const Allowed& allowed)
{
  const Csv base = read_csv(std::string(KESTREL_SOURCE_DIR) + "/test/harness/data/" + baseline);
  ASSERT_GT(base.names.size(), 40u);
  harness::Run run(sc);
  ASSERT_TRUE(run.step_ticks(run.total_ticks())) << run.failure();
  const harness::MemorySink& now = run.memory();
  ASSERT_EQ(now.rows(), base.cols[0].size());
  size_t identical = 0;
  for (size_t k = 0; k < base.names.size(); ++k) {
    const std::string& name = base.names[k];
    SCOPED_TRACE(name);
    const std::vector<double> v = now.column(name);  // throws if the column is gone
    double scale = 0.0, worst = 0.0;
    for (size_t r = 0; r < v.size(); ++r) {
      scale = std::max(scale, std::fabs(base.cols[k][r]));
      worst = std::max(worst, std::fabs(v[r] - base.cols[k][r]));
    }
    const auto it = allowed.find(name);
    if (it == allowed.end()) {
      EXPECT_EQ(v, base.cols[k]) << "max |diff| " << worst;
    } else {
      EXPECT_LE(worst, it->second * std::max(scale, 1e-300)) << "max |diff| " << worst << " of " << scale;
    }
    if (worst == 0.0) ++identical;
  }
  ::testing::Test::RecordProperty("identical_columns", static_cast<int>(identical));
}

}  // namespace

TEST(Regression, S1SixtySecondsAsBefore)
{
  const harness::Scenario sc = harness::load_scenario(std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml",
                                                      {{"duration", "60"}, {"rates.record_divisor", "100"}});
  compare("baseline_s1_60s.csv", sc, {});
}

TEST(Regression, S2BurnAsBefore)
{
  const harness::Scenario sc = harness::load_scenario(
      std::string(KESTREL_SOURCE_DIR) + "/scenarios/s2_mars_orbit_insertion.yaml",
      {{"duration", "40"}, {"burn.start", "10"}, {"burn.duration", "20"}, {"rates.record_divisor", "20"}});
  compare("baseline_s2_40s.csv", sc, {});
}

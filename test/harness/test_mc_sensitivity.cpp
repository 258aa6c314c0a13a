// What drives a campaign's failures (mc_sensitivity.h): the rank statistics
// against independent brute-force calculations written here (pair counting
// for the AUC, rank counting for Spearman's rho), a synthetic campaign
// where one drawn value decides the failures and the others are noise, and
// the shipped demonstration campaign, where the dispersed gain K ranks first.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/mc/mc_sensitivity.h"

namespace fs = std::filesystem;

namespace {

// P(x_fail > x_pass) + 1/2 P(equal) over every (failing, passing) pair.
double auc_by_pairs(const std::vector<double>& x, const std::vector<char>& fail)
{
  double wins = 0.0, pairs = 0.0;
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = 0; j < x.size(); ++j)
      if (fail[i] && !fail[j]) {
        pairs += 1.0;
        wins += x[i] > x[j] ? 1.0 : x[i] == x[j] ? 0.5 : 0.0;
      }
  return wins / pairs;
}

// rank of x[i]: 1 + (values below) + (other values equal) / 2
std::vector<double> ranks_by_count(const std::vector<double>& x)
{
  std::vector<double> r(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    double below = 0.0, equal = 0.0;
    for (size_t j = 0; j < x.size(); ++j) {
      if (x[j] < x[i]) below += 1.0;
      if (j != i && x[j] == x[i]) equal += 1.0;
    }
    r[i] = 1.0 + below + equal / 2.0;
  }
  return r;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b)
{
  double ma = 0.0, mb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    ma += a[i] / static_cast<double>(a.size());
    mb += b[i] / static_cast<double>(b.size());
  }
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// a fixed pseudo-random sequence in [0, 1) (64-bit LCG, top 53 bits)
struct Lcg {
  uint64_t s;
  double next()
  {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) * 0x1.0p-53;
  }
};

}  // namespace

TEST(McSensitivity, MidRanksShareTies)
{
  EXPECT_EQ(harness::mid_ranks({3.0, 1.0, 3.0, 2.0}), (std::vector<double>{3.5, 1.0, 3.5, 2.0}));
  EXPECT_EQ(harness::mid_ranks({5.0, 5.0, 5.0}), (std::vector<double>{2.0, 2.0, 2.0}));
}

TEST(McSensitivity, StatisticsMatchBruteForce)
{
  Lcg g{7};
  std::vector<double> x, y;
  std::vector<char> f;
  for (int i = 0; i < 57; ++i) {
    x.push_back(std::round(g.next() * 20.0));  // ties on purpose
    y.push_back(x.back() + 8.0 * g.next());
    f.push_back(g.next() < 0.3 + 0.02 * x.back() ? 1 : 0);
  }
  EXPECT_NEAR(harness::mann_whitney_auc(x, f), auc_by_pairs(x, f), 1e-12);
  EXPECT_NEAR(harness::spearman_rho(x, y), pearson(ranks_by_count(x), ranks_by_count(y)), 1e-12);
  // without ties: z = (U - nf np / 2) / sqrt(nf np (n + 1) / 12), p = erfc(|z| / sqrt 2)
  std::vector<double> u;
  for (int i = 0; i < 57; ++i) u.push_back(g.next());
  double nf = 0.0;
  for (char c : f) nf += c;
  const double np = 57.0 - nf, U = auc_by_pairs(u, f) * nf * np;
  const double z = (U - nf * np / 2.0) / std::sqrt(nf * np * 58.0 / 12.0);
  EXPECT_NEAR(harness::mann_whitney_p(u, f), std::erfc(std::fabs(z) / std::sqrt(2.0)), 1e-12);
  // degenerate groups
  EXPECT_TRUE(std::isnan(harness::mann_whitney_auc(x, std::vector<char>(x.size(), 0))));
  EXPECT_TRUE(std::isnan(harness::spearman_rho({1.0, 2.0}, {1.0, 2.0})));
  EXPECT_TRUE(std::isnan(harness::spearman_rho({1.0, 1.0, 1.0}, {1.0, 2.0, 3.0})));
}

// 200 runs, three drawn values; a run fails when drawn value 1 is above
// 0.7 (30 % of the runs): value 1 ranks first with delta = +1 exactly, the
// noise values have |delta| below 0.25 (their standard deviation is about
// 0.09 at these group sizes), and an invalid draw is left out.
TEST(McSensitivity, SyntheticDriverRanksFirst)
{
  harness::McPlan plan;
  plan.drawn = {{"noise_a", "m"}, {"driver", "s"}, {"noise_b", "-"}};
  harness::McMetric m;
  m.col = {"limit", "-", "max of x"};
  m.criterion = 0;
  m.below = true;
  m.threshold = 0.7;
  plan.metrics = {harness::McMetric{}, m};
  std::vector<harness::McRecord> recs;
  Lcg g{2026};
  size_t failing = 0;
  for (uint64_t k = 0; k < 201; ++k) {
    harness::McRecord r;
    r.index = k;
    r.drawn = {g.next(), g.next(), g.next()};
    r.invalid = k == 100;
    r.metrics = {0.0, r.drawn[1]};
    r.pass = !r.invalid && r.drawn[1] < 0.7;
    failing += !r.invalid && !r.pass;
    recs.push_back(r);
  }
  const auto d = harness::mc_sensitivity(plan, harness::McMemoryRecords(recs));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].metric, 1u);
  EXPECT_EQ(d[0].runs, 200u);
  EXPECT_EQ(d[0].failed, failing);
  ASSERT_EQ(d[0].ranked.size(), 3u);
  EXPECT_EQ(d[0].ranked[0].drawn, 1u);
  EXPECT_EQ(d[0].ranked[0].delta, 1.0);
  EXPECT_EQ(d[0].ranked[0].rho, 1.0);  // the metric is the driver itself
  EXPECT_LT(d[0].ranked[0].p, 1e-20);
  for (size_t i = 1; i < 3; ++i) {
    EXPECT_LT(std::fabs(d[0].ranked[i].delta), 0.25) << plan.drawn[d[0].ranked[i].drawn].name;
    EXPECT_GT(d[0].ranked[i].p, 1e-3);
  }
  for (uint64_t k : d[0].failing) EXPECT_GT(recs[k].drawn[1], 0.7);
}

// The shipped demonstration campaign: some runs fail `settled` because of
// the dispersed gain K (low K: slow), and the report data say so.
TEST(McSensitivity, DemonstrationCampaignRanksTheGainFirst)
{
#ifdef KESTREL_TEST_SKIP_CAMPAIGN
  GTEST_SKIP() << "40 runs: host-release preset only (test/harness/CMakeLists.txt)";
#endif
  const harness::Scenario sc = harness::load_scenario(std::string(KESTREL_SOURCE_DIR) + "/scenarios/mc_demo_drivers.yaml");
  const harness::McPlan plan = harness::make_mc_plan(sc, sc.monte_carlo->seed, sc.monte_carlo->runs);
  const fs::path dir = fs::temp_directory_path() / ("kestrel_mc_demo_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  harness::McRunOptions opt;
  opt.jobs = 2;
  for (uint64_t k = 0; k < plan.runs; ++k) opt.indices.push_back(k);
  bool stopped = false;
  const std::vector<harness::McRecord> recs = harness::run_mc_runs(plan, dir, opt, stopped);
  ASSERT_EQ(recs.size(), 40u);
  harness::write_mc_outputs(plan, recs, {}, dir);
  std::ifstream in(dir / "mc_report_data.json");
  std::stringstream ss;
  ss << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(ss.str());
  fs::remove_all(dir);
  ASSERT_EQ(j["drivers"].size(), 2u);
  const nlohmann::json& c = j["drivers"][0];
  EXPECT_EQ(c["criterion"], "settled");
  const size_t failed = c["failed"].get<size_t>();
  EXPECT_GT(failed, 3u);
  EXPECT_LT(failed, 37u);
  EXPECT_EQ(c["ranked_by"], "delta");
  EXPECT_EQ(c["ranked"][0]["drawn"], "fsw.mrp_fb.K");
  EXPECT_LT(c["ranked"][0]["delta"].get<double>(), -0.8);  // the failing runs drew the low gains
  // the failing runs listed are the records that failed `settled`
  std::vector<uint64_t> want;
  for (const harness::McRecord& r : recs)
    if (!(r.metrics[plan.metrics.size() - 2] < 2.0)) want.push_back(r.index);
  EXPECT_EQ(c["failing"].get<std::vector<uint64_t>>(), want);
  EXPECT_EQ(j["drivers"][1]["failed"], 0);
}

// Deterministic named random streams (docs/dynamics.md §9,
// §13): hash and mixer against published reference values, stream
// determinism and separation, thread-count independence, and the uniform
// and normal samplers against confidence bounds from the sample count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "sim/rng.h"
#include "stats_test_util.h"

namespace {

// Reference vectors of the FNV authors' test suite and of SplitMix64 (Vigna).
TEST(Rng, HashAndMixerMatchReferenceValues)
{
  EXPECT_EQ(sim::fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(sim::fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(sim::fnv1a64("foobar"), 0x85944171f73967e8ull);
  // SplitMix64 from state 0: outputs 1 and 2.
  EXPECT_EQ(sim::splitmix64(0), 0xe220a8397b1dcdafull);
  EXPECT_EQ(sim::splitmix64(0x9E3779B97F4A7C15ull), 0x6e789e6aa1b965f4ull);
}

std::vector<uint64_t> draw(uint64_t seed, const std::string& name, int n)
{
  sim::Rng r(seed, name);
  std::vector<uint64_t> out;
  for (int i = 0; i < n; ++i) {
    const double g = r.normal();  // mix the two kinds of draw
    uint64_t bits;
    static_assert(sizeof bits == sizeof g, "double is 64 bits");
    std::memcpy(&bits, &g, sizeof bits);
    out.push_back(bits ^ r.next_u64());
  }
  return out;
}

TEST(Rng, SameSeedAndNameGiveBitIdenticalStreams)
{
  EXPECT_EQ(draw(42, "gyro", 1000), draw(42, "gyro", 1000));
  EXPECT_EQ(sim::derive_seed(42, "gyro"), sim::derive_seed(42, std::string("gy") + "ro"));
}

TEST(Rng, DifferentNamesOrSeedsGiveDifferentStreams)
{
  const std::vector<std::string> names = {"gyro", "st", "css0", "css1", "css2", "tach", "Gyro", ""};
  std::vector<uint64_t> seeds;
  for (const auto& n : names) seeds.push_back(sim::derive_seed(7, n));
  for (const auto& n : names) seeds.push_back(sim::derive_seed(8, n));
  std::sort(seeds.begin(), seeds.end());
  EXPECT_EQ(std::adjacent_find(seeds.begin(), seeds.end()), seeds.end());
  // Streams differ from the first draw on, and are uncorrelated: matching
  // 64-bit words between two streams would be a ~2^-64 event.
  const auto a = draw(7, "css0", 500), b = draw(7, "css1", 500), c = draw(8, "css0", 500);
  int same_ab = 0, same_ac = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    same_ab += a[i] == b[i];
    same_ac += a[i] == c[i];
  }
  EXPECT_EQ(same_ab, 0);
  EXPECT_EQ(same_ac, 0);
}

// Monte Carlo runs derive streams from (run_seed, name) only, so the numbers
// do not depend on how many threads run them or in which order.
TEST(Rng, StreamsIndependentOfThreadCountAndOrder)
{
  const std::vector<std::string> names = {"gyro", "st", "css0", "css1", "css2", "css3",
                                          "css4", "css5", "css6", "css7", "tach"};
  std::vector<std::vector<uint64_t>> serial;
  for (const auto& n : names) serial.push_back(draw(1234, n, 2000));
  for (int n_threads : {1, 2, 4}) {
    std::vector<std::vector<uint64_t>> par(names.size());
    std::vector<std::thread> pool;
    for (int t = 0; t < n_threads; ++t)
      pool.emplace_back([&, t] {
        for (int i = static_cast<int>(names.size()) - 1 - t; i >= 0; i -= n_threads)
          par[static_cast<size_t>(i)] = draw(1234, names[static_cast<size_t>(i)], 2000);
      });
    for (auto& th : pool) th.join();
    EXPECT_EQ(par, serial) << n_threads << " threads";
  }
}

TEST(Rng, UniformMomentsAndRange)
{
  sim::Rng r(99, "uniform");
  const int n = 200000;
  std::vector<double> x(n);
  for (double& v : x) {
    v = r.uniform();
    ASSERT_GE(v, 0.0);
    ASSERT_LT(v, 1.0);
  }
  const stats::Moments m = stats::moments(x);
  EXPECT_TRUE(stats::mean_consistent(m.mean, 0.5, std::sqrt(1.0 / 12.0), n)) << m.mean;
  // Var of s^2 for U(0,1): (mu4 - sigma^4)/n = (1/80 - 1/144)/n.
  EXPECT_LT(std::abs(m.var - 1.0 / 12.0), stats::kZ * std::sqrt((1.0 / 80 - 1.0 / 144) / n));
}

TEST(Rng, NormalMomentsTailsAndKolmogorovSmirnov)
{
  const int n = 200000;
  std::vector<double> x(n);
  sim::Rng r(2024, "normal");
  for (double& v : x) v = r.normal();
  const stats::Moments m = stats::moments(x);
  EXPECT_TRUE(stats::mean_consistent(m.mean, 0.0, 1.0, n)) << m.mean;
  EXPECT_TRUE(stats::variance_consistent(m.var, 1.0, n)) << m.var;
  double m3 = 0.0, m4 = 0.0;
  long tail2 = 0;
  for (double v : x) {
    m3 += v * v * v;
    m4 += v * v * v * v;
    tail2 += std::abs(v) > 2.0;
  }
  m3 /= n;
  m4 /= n;
  EXPECT_LT(std::abs(m3), stats::kZ * std::sqrt(15.0 / n));        // Var(x^3) = 15
  EXPECT_LT(std::abs(m4 - 3.0), stats::kZ * std::sqrt(96.0 / n));  // Var(x^4) = 105 - 9
  const double p2 = std::erfc(2.0 / std::sqrt(2.0));               // P(|x| > 2) = 0.0455
  EXPECT_LT(std::abs(static_cast<double>(tail2) / n - p2), stats::kZ * std::sqrt(p2 * (1 - p2) / n));
  // Kolmogorov-Smirnov distance; 1.95/sqrt(n) is the alpha = 0.001 critical value.
  std::sort(x.begin(), x.end());
  double d = 0.0;
  for (int i = 0; i < n; ++i) {
    const double F = 0.5 * std::erfc(-x[static_cast<size_t>(i)] / std::sqrt(2.0));
    d = std::max({d, std::abs(F - static_cast<double>(i) / n), std::abs(F - static_cast<double>(i + 1) / n)});
  }
  EXPECT_LT(d, 1.95 / std::sqrt(static_cast<double>(n)));
}

// Consecutive normals (including the polar pair) are uncorrelated.
TEST(Rng, NormalLagOneCorrelationIsZero)
{
  const int n = 100000;
  sim::Rng r(5, "lag");
  double prev = r.normal(), sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v = r.normal();
    sum += prev * v;
    prev = v;
  }
  EXPECT_LT(std::abs(sum / n), stats::kZ / std::sqrt(static_cast<double>(n)));
}

}  // namespace

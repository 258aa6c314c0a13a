// Paced runs (pacer.h): pacing changes when ticks run, never what they
// compute; the wall time is at least what the deadlines impose; the figures
// are consistent.  (Lateness itself depends on the machine's load: it is a
// benchmark figure, bench/pacing.sh, not a test threshold.)
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "harness/drive/run_scenario.h"
#include "harness/core/pacer.h"
#include "harness/scenario/scenario.h"

namespace fs = std::filesystem;

namespace {
const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

harness::RunResult run_to(const fs::path& dir, double scale)
{
  const harness::Scenario sc = harness::load_scenario(kS1, {{"duration", "2"}, {"rates.dt", "0.01"}, {"rates.record_divisor", "1"}});
  harness::RunOptions opt;
  fs::remove_all(dir);
  opt.out_dir = dir.string();
  opt.realtime_scale = scale;
  return harness::run_scenario(sc, opt);
}
}  // namespace

TEST(Pacing, PacedRunComputesExactlyWhatTheUnpacedRunComputes)
{
  const fs::path base = fs::temp_directory_path() / "kestrel_pacing";
  const harness::RunResult fast = run_to(base / "fast", 0.0);
  const harness::RunResult paced = run_to(base / "paced", 20.0);  // 2 s simulated in >= 0.1 s
  ASSERT_TRUE(fast.ok);
  ASSERT_TRUE(paced.ok);
  EXPECT_FALSE(fast.paced);
  ASSERT_TRUE(paced.paced);
  const harness::Hdf5Table a = harness::read_hdf5((base / "fast" / "results.h5").string());
  const harness::Hdf5Table b = harness::read_hdf5((base / "paced" / "results.h5").string());
  ASSERT_EQ(a.rows, 201u);
  EXPECT_TRUE(a.data == b.data);  // bit for bit
  // 200 tick intervals of 10 ms / 20 after the first tick: at least 0.1 s
  EXPECT_GE(paced.wall_seconds, 0.1);
  const harness::PacingStats& p = paced.pacing;
  EXPECT_EQ(p.ticks, 201u);
  EXPECT_EQ(p.scale, 20.0);
  EXPECT_LE(p.lateness_p50_s, p.lateness_p99_s);
  EXPECT_LE(p.lateness_p99_s, p.lateness_max_s);
  EXPECT_GE(p.lateness_max_s, 0.0);
  EXPECT_LE(p.overruns, p.ticks);
  EXPECT_LE(p.drift_s, p.lateness_max_s);
  // the figures are in summary.txt
  std::ifstream in(base / "paced" / "summary.txt");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* key : {"rt_scale = 20", "rt_lateness_p50 = ", "rt_lateness_p99 = ", "rt_lateness_max = ",
                          "rt_overruns = ", "rt_drift = ", "rt_priority = "})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  fs::remove_all(base);
}

TEST(Pacing, HistogramBinsAreTenPerDecade)
{
  EXPECT_DOUBLE_EQ(harness::pacer_bin_edge(0), 1e-7);
  EXPECT_NEAR(harness::pacer_bin_edge(10), 1e-6, 1e-18);
  EXPECT_NEAR(harness::pacer_bin_edge(1) / harness::pacer_bin_edge(0), std::pow(10.0, 0.1), 1e-12);
  EXPECT_NEAR(harness::pacer_bin_edge(harness::Pacer::kBins - 2), 100.0 / std::pow(10.0, 0.1), 1e-9);
  EXPECT_TRUE(std::isinf(harness::pacer_bin_edge(harness::Pacer::kBins - 1)));
}

TEST(Pacing, BadScaleIsRejected)
{
  EXPECT_THROW(harness::Pacer(10000000, 0.0), std::invalid_argument);
  EXPECT_THROW(harness::Pacer(10000000, -1.0), std::invalid_argument);
  EXPECT_THROW(harness::Pacer(0, 1.0), std::invalid_argument);
}

// The documented range [1e-6, 1e6]: 1e-300 (which overflowed the deadline
// arithmetic: the run went unpaced with 56,000 overrun lines) and the
// values just outside are refused naming the range; the bounds are taken.
// restart() checks the same.  At the slowest scale a far tick's deadline is
// held at 1e18 ns (k dt / scale would be 1e24 ns here), never overflowing.
TEST(Pacing, ScaleOutsideItsRangeIsRefused)
{
  for (double bad : {1e-300, 9.99e-7, 1.000001e6, 1e300, std::nan(""), HUGE_VAL}) {
    try {
      harness::Pacer p(10000000, bad);
      ADD_FAILURE() << bad << " taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("[1e-6, 1e6]"), std::string::npos) << e.what();
    }
  }
  harness::Pacer slow(10000000, 1e-6);
  harness::Pacer fast(10000000, 1e6);
  EXPECT_THROW(fast.restart(1e-300), std::invalid_argument);
  EXPECT_EQ(harness::Pacer::check_scale(1.0), "");
  EXPECT_NE(harness::Pacer::check_scale(0.0), "");
  std::atomic<int> stop{0};
  slow.set_stop(&stop);
  stop.store(15);
  ASSERT_FALSE(slow.wait_for(0) && slow.wait_for(100000000000ULL));  // the first is due at once
  const double left = slow.seconds_to(100000000000ULL);  // 1e11 ticks of 10 ms at 1e-6: 1e18 s, held at 1e9 s
  EXPECT_GT(left, 0.99e9);
  EXPECT_LT(left, 1.01e9);
}

// A stop flag ends the wait for a deadline within the slice, whatever the
// scale: tick 1 is due 10,000 s after tick 0 at 1e-6; the flag is set
// after 100 ms and the wait returns false (nothing measured) at once.
TEST(Pacing, StopFlagEndsTheWaitWithinASlice)
{
  harness::Pacer p(10000000, 1e-6);
  std::atomic<int> stop{0};
  p.set_stop(&stop);
  ASSERT_TRUE(p.wait_for(0));
  std::thread t([&stop] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    stop.store(2);
  });
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(p.wait_for(1));
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t.join();
  EXPECT_LT(dt, 0.1 + 2.0);  // 0.1 s + a slice; 2 s so that load cannot fail it
  std::printf("the wait for a 10,000 s deadline ended %.0f ms after the stop flag\n", (dt - 0.1) * 1e3);
  EXPECT_EQ(p.stats().ticks, 1u);  // tick 1 not counted
}

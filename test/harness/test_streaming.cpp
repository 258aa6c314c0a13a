// Results that stream: the HDF5 layout analysts read (one dataset per
// quantity, grouped by message, units and frames in attributes), HDF5 and
// the in-memory table agreeing sample for sample, a stopped run's file
// marked incomplete, the report's bounded reduction (extremes kept, full
// rate for the spectrum window), and peak memory that does not grow with the
// duration of a real `kestrel run` (the proxy for the one-year run).
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <hdf5.h>
#include <nlohmann/json.hpp>

#include "harness/drive/run_scenario.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace fs = std::filesystem;

namespace {

const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

fs::path fresh_dir(const std::string& name)
{
  const fs::path d = fs::temp_directory_path() / ("kestrel_stream_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

harness::Scenario short_s1()
{
  return harness::load_scenario(kS1, {{"duration", "30"},
                                      {"rates.dt", "0.05"},
                                      {"rates.fsw_divisor", "2"},
                                      {"rates.record_divisor", "4"},
                                      {"wheel_defaults.model", "balanced"}});
}

std::string attr_text(hid_t obj, const char* name)
{
  const hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  if (a < 0) return "<missing>";
  const hid_t t = H5Aget_type(a);
  std::string s(H5Tget_size(t), '\0');
  H5Aread(a, t, &s[0]);
  H5Tclose(t);
  H5Aclose(a);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

// Dataset dims and values.
std::vector<double> read_dataset(hid_t file, const char* path, hsize_t dims[2])
{
  const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  EXPECT_GE(ds, 0) << path;
  if (ds < 0) return {};
  const hid_t sp = H5Dget_space(ds);
  EXPECT_EQ(H5Sget_simple_extent_ndims(sp), 2) << path;
  H5Sget_simple_extent_dims(sp, dims, nullptr);
  std::vector<double> v(static_cast<size_t>(dims[0] * dims[1]));
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(sp);
  H5Dclose(ds);
  return v;
}

}  // namespace

TEST(Streaming, Hdf5HasOneDatasetPerQuantityGroupedByMessage)
{
  const fs::path dir = fresh_dir("layout");
  harness::RunOptions opt;
  opt.out_dir = dir.string();
  ASSERT_TRUE(harness::run_scenario(short_s1(), opt).ok);
  harness::Run mem(short_s1());  // the same run, kept in memory
  ASSERT_TRUE(mem.step_ticks(mem.total_ticks()));
  const harness::MemorySink& m = mem.memory();
  ASSERT_EQ(m.rows(), 151u);

  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen((dir / "results.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hsize_t d[2] = {0, 0};
  const auto w = read_dataset(f, "/truth/omega_BN_B", d);
  EXPECT_EQ(d[0], 151u);
  EXPECT_EQ(d[1], 3u);
  const auto wx = m.column("omega_BN_B_x"), wz = m.column("omega_BN_B_z");
  for (size_t r = 0; r < 151; ++r) {
    ASSERT_EQ(w[r * 3 + 0], wx[r]) << r;
    ASSERT_EQ(w[r * 3 + 2], wz[r]) << r;
  }
  {
    const hid_t ds = H5Dopen2(f, "/truth/omega_BN_B", H5P_DEFAULT);
    EXPECT_EQ(attr_text(ds, "unit"), "rad/s");
    EXPECT_EQ(attr_text(ds, "frame"), "B");
    H5Dclose(ds);
  }
  const auto t = read_dataset(f, "/t", d);
  EXPECT_EQ(d[1], 1u);
  EXPECT_EQ(t.back(), 30.0);
  const auto ws = read_dataset(f, "/truth/wheel_speed", d);
  EXPECT_EQ(d[1], 4u);  // one component per wheel
  EXPECT_NEAR(ws[0], 100.0, 1e-9);  // rw1 starts at 100 rpm
  {
    const hid_t ds = H5Dopen2(f, "/truth/wheel_speed", H5P_DEFAULT);
    EXPECT_EQ(attr_text(ds, "unit"), "rpm");
    H5Dclose(ds);
  }
  read_dataset(f, "/fsw_health/stage_status", d);
  EXPECT_EQ(d[1], static_cast<hsize_t>(FSW_ACS_NUM_STAGES));
  read_dataset(f, "/fsw_sensors/omega_BN_B", d);  // measured next to truth, same quantity name
  EXPECT_EQ(d[1], 3u);
  read_dataset(f, "/metrics/pointing_error", d);
  EXPECT_EQ(d[1], 1u);
  H5Fclose(f);

  // the flat table read back equals the in-memory table, bit for bit
  const harness::Hdf5Table tab = harness::read_hdf5((dir / "results.h5").string());
  EXPECT_TRUE(tab.complete);
  ASSERT_EQ(tab.names.size(), m.num_columns());
  ASSERT_EQ(tab.rows, m.rows());
  for (size_t c = 0; c < m.num_columns(); ++c) EXPECT_EQ(tab.names[c], m.columns()[c].name);
  EXPECT_TRUE(std::equal(tab.data.begin(), tab.data.end(), m.data()));
}

TEST(Streaming, AStoppedRunKeepsItsRowsMarkedIncomplete)
{
  const fs::path dir = fresh_dir("stopped");
  const harness::Scenario sc = short_s1();
  harness::RunConfig cfg;
  cfg.keep_in_memory = false;
  cfg.chunk_rows = 16;
  harness::Run run(sc, std::move(cfg));
  harness::Hdf5Sink h5((dir / "results.h5").string(), sc, "{}");
  run.add_sink(h5);
  ASSERT_TRUE(run.step_ticks(200));  // 10 s of 30: rows at t = 0, 0.2, ..., 9.8
  run.finish();
  EXPECT_FALSE(run.done());
  const harness::Hdf5Table tab = harness::read_hdf5((dir / "results.h5").string());
  EXPECT_FALSE(tab.complete);
  ASSERT_EQ(tab.rows, 50u);
  EXPECT_NEAR(tab.data[49 * tab.names.size()], 9.8, 1e-12);
}

// The report's reduction on a signal with known extremes: a slow sine with
// single-sample spikes; every spike survives, the global extremes are
// exact, the display size is bounded, the spectrum keeps the last rows.
TEST(Streaming, ReportSinkKeepsExtremesAndIsBounded)
{
  harness::Recorder rec("r");
  uint64_t i = 0;
  auto sig = [](uint64_t k) {
    double v = std::sin(1e-4 * static_cast<double>(k));
    if (k % 9973 == 17) v += 5.0 + static_cast<double>(k % 7);  // spikes
    if (k == 123457) v = -42.0;
    return v;
  };
  rec.add_source("", {{"t", "s", "", {"t"}}}, [&i](double* o) { o[0] = 0.1 * static_cast<double>(i); });
  rec.add_source("truth", {{"omega_BN_B", "rad/s", "B", {"omega_BN_B_x", "omega_BN_B_y", "omega_BN_B_z"}}},
                 [&i, &sig](double* o) {
                   o[0] = sig(i);
                   o[1] = static_cast<double>(i);
                   o[2] = -static_cast<double>(i);
                 });
  const uint64_t n = 300001;
  rec.allocate(n);
  harness::ReportSink rep;
  rec.add_sink(rep);
  for (i = 0; i < n; ++i) rec.sample();
  rec.finish(true);
  ASSERT_TRUE(rep.decimated());
  const auto j = nlohmann::json::parse("{" + rep.series_json() + "}");
  const auto& x = j["series"]["omega_BN_B_x"];
  const auto& t = j["series"]["t"];
  ASSERT_EQ(x.size(), t.size());
  EXPECT_LE(x.size(), 2 * harness::ReportSink::kReportBuckets + 2);
  double lo = 1e300, hi = -1e300;
  size_t spikes = 0;
  for (size_t p = 0; p < x.size(); ++p) {
    lo = std::min(lo, x[p].get<double>());
    hi = std::max(hi, x[p].get<double>());
    if (x[p].get<double>() > 4.0) ++spikes;
    if (p) {
      EXPECT_GE(t[p].get<double>(), t[p - 1].get<double>());
    }
  }
  size_t true_spikes = 0;
  double true_hi = -1e300;
  for (uint64_t k = 0; k < n; ++k) {
    if (sig(k) > 4.0) ++true_spikes;
    true_hi = std::max(true_hi, sig(k));
  }
  EXPECT_EQ(lo, -42.0);
  EXPECT_EQ(hi, true_hi);
  EXPECT_EQ(spikes, true_spikes);  // buckets (75 rows) are narrower than the spike spacing
  // a monotonic column keeps its first and last values exactly
  EXPECT_EQ(j["series"]["omega_BN_B_y"].front().get<double>(), 0.0);
  EXPECT_EQ(j["series"]["omega_BN_B_y"].back().get<double>(), static_cast<double>(n - 1));
  EXPECT_EQ(t.back().get<double>(), 0.1 * static_cast<double>(n - 1));
  // the spectrum window: the last kSpectrumRows rows at full rate
  const auto& sx = j["spectrum"]["omega_BN_B_x"];
  ASSERT_EQ(sx.size(), harness::ReportSink::kSpectrumRows);
  for (size_t k = 0; k < sx.size(); ++k)
    ASSERT_EQ(sx[k].get<double>(), sig(n - harness::ReportSink::kSpectrumRows + k)) << k;
  EXPECT_EQ(j["decimation"]["rows"], n);
}

TEST(Streaming, ReportSinkKeepsShortRunsWhole)
{
  harness::Recorder rec("r");
  int i = 0;
  rec.add_source({{"t", "s"}, {"y", "-"}}, [&i](double* o) {
    o[0] = i;
    o[1] = i * i;
  });
  rec.allocate(2 * harness::ReportSink::kReportBuckets);
  harness::ReportSink rep;
  rec.add_sink(rep);
  for (i = 0; i < static_cast<int>(2 * harness::ReportSink::kReportBuckets); ++i) rec.sample();
  rec.finish(true);
  EXPECT_FALSE(rep.decimated());
  const auto j = nlohmann::json::parse("{" + rep.series_json() + "}");
  ASSERT_EQ(j["series"]["y"].size(), 2 * harness::ReportSink::kReportBuckets);
  EXPECT_EQ(j["series"]["y"][77].get<double>(), 77.0 * 77.0);
  EXPECT_FALSE(j.contains("spectrum"));
}

#ifndef KESTREL_TEST_SANITIZE
namespace {
// Peak resident set [MiB] of `kestrel run` for a duration (S1, balanced
// wheels, dt = 0.1 s, every tick recorded).
double peak_mib_of_run(const std::string& duration, const fs::path& out)
{
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string d = "duration=" + duration;
    execl(KESTREL_EXE, KESTREL_EXE, "run", kS1.c_str(), "-o", out.c_str(), "--set", d.c_str(), "--set",
          "rates.dt=0.1", "--set", "rates.fsw_divisor=1", "--set", "rates.record_divisor=1", "--set",
          "wheel_defaults.model=balanced", static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  struct rusage ru {};
  wait4(pid, &status, 0, &ru);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << duration;
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}
}  // namespace

// Five times the rows, the same peak: nothing grows with the duration.  Both
// runs are long enough to fill every bounded buffer (the report's buckets
// and its full-rate spectrum window); the extra 160,000 rows would be
// ~90 MiB in an in-memory table.
TEST(Streaming, PeakMemoryDoesNotGrowWithDuration)
{
  const fs::path dir = fresh_dir("peak");
  const double short_mib = peak_mib_of_run("4000", dir / "short");   // 40,001 rows
  const double long_mib = peak_mib_of_run("20000", dir / "long");    // 200,001 rows
  RecordProperty("peak_short_mib", std::to_string(short_mib));
  RecordProperty("peak_long_mib", std::to_string(long_mib));
  std::printf("peak RSS: 4,000 s run %.1f MiB, 20,000 s run %.1f MiB\n", short_mib, long_mib);
  EXPECT_LT(long_mib - short_mib, 10.0);
  EXPECT_LT(fs::file_size(dir / "long" / "report_data.json"), 25u * 1024u * 1024u);
  fs::remove_all(dir);
}
#endif

// Results: HDF5 round trip (columns, units, attributes, chunking, deflate),
// CSV, report_data.json schema, and reproducibility from the manifest.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/cli/commands.h"
#include "harness/drive/run_scenario.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace fs = std::filesystem;

namespace {

const std::string kS1 = std::string(KESTREL_SOURCE_DIR) + "/scenarios/s1_sun_pointing.yaml";

fs::path fresh_dir(const std::string& name)
{
  const fs::path d = fs::temp_directory_path() / ("kestrel_test_" + name);
  fs::remove_all(d);
  return d;
}

std::string slurp(const fs::path& p)
{
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A short S1: 30 s, balanced wheels, 0.05 s steps.
harness::Scenario short_s1(uint64_t seed = 11)
{
  return harness::load_scenario(kS1, {{"duration", "30"},
                                      {"rates.dt", "0.05"},
                                      {"rates.fsw_divisor", "2"},
                                      {"rates.record_divisor", "4"},
                                      {"wheel_defaults.model", "balanced"},
                                      {"outputs.csv", "true"},
                                      {"seed", std::to_string(seed)}});
}

}  // namespace

TEST(Outputs, Hdf5RoundTrip)
{
  const fs::path dir = fresh_dir("h5");
  const harness::Scenario sc = short_s1();
  harness::RunOptions opt;
  opt.out_dir = dir.string();
  const harness::RunResult r = harness::run_scenario(sc, opt);
  ASSERT_TRUE(r.ok) << r.failure;

  // the same table in memory, for comparison
  harness::Run run(sc);
  run.step_ticks(run.total_ticks());
  const harness::MemorySink& rec = run.memory();
  // 30 s at 0.05 s = 600 steps, ticks 0..600, every 4th: 0,4,...,600 -> 151 rows
  ASSERT_EQ(rec.rows(), 151u);

  const harness::Hdf5Table t = harness::read_hdf5((dir / "results.h5").string());
  EXPECT_EQ(t.rows, 151u);
  ASSERT_EQ(t.names.size(), rec.num_columns());
  ASSERT_EQ(t.units.size(), rec.num_columns());
  for (size_t c = 0; c < rec.num_columns(); ++c) {
    EXPECT_EQ(t.names[c], rec.columns()[c].name);
    EXPECT_EQ(t.units[c], rec.columns()[c].unit);
  }
  EXPECT_EQ(t.names[0], "t");
  EXPECT_EQ(t.units[0], "s");
  for (uint64_t row = 0; row < t.rows; ++row)
    for (size_t c = 0; c < rec.num_columns(); ++c)
      ASSERT_EQ(t.data[row * rec.num_columns() + c], rec.at(row, c)) << row << " " << t.names[c];
  EXPECT_EQ(t.data[150 * rec.num_columns()], 30.0);  // last t
  EXPECT_EQ(t.seed, 11u);
  EXPECT_EQ(t.version, std::string(harness::version()));
  EXPECT_EQ(t.scenario, "s1_sun_pointing");
  EXPECT_EQ(t.dt, 0.05);
  EXPECT_EQ(t.duration, 30.0);
  EXPECT_TRUE(t.chunked);
  EXPECT_TRUE(t.deflate);
  // the file embeds the manifest as the run began; manifest.json adds how it ended
  nlohmann::json m = nlohmann::json::parse(slurp(dir / "manifest.json"));
  EXPECT_EQ(m["result"]["complete"], true);
  m.erase("result");
  EXPECT_EQ(nlohmann::json::parse(t.manifest), m);
}

TEST(Outputs, CsvHeaderAndValues)
{
  const fs::path dir = fresh_dir("csv");
  harness::RunOptions opt;
  opt.out_dir = dir.string();
  ASSERT_TRUE(harness::run_scenario(short_s1(), opt).ok);
  std::ifstream in(dir / "telemetry.csv");
  std::string header, row0;
  std::getline(in, header);
  std::getline(in, row0);
  EXPECT_EQ(header.rfind("t [s],pointing_error_deg [deg],sigma_BN_x [-]", 0), 0u) << header;
  EXPECT_EQ(row0.rfind("0,", 0), 0u);
  size_t lines = 2;
  std::string l;
  while (std::getline(in, l)) ++lines;
  EXPECT_EQ(lines, 152u);  // header + 151 rows
}

TEST(Outputs, ReportDataSchema)
{
  const fs::path dir = fresh_dir("report");
  harness::RunOptions opt;
  opt.out_dir = dir.string();
  ASSERT_TRUE(harness::run_scenario(short_s1(), opt).ok);
  const auto j = nlohmann::json::parse(slurp(dir / "report_data.json"));
  for (const char* k : {"meta", "series", "units", "attitude", "geometry", "dataflow_dot"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["meta"]["scenario"], "s1_sun_pointing");
  EXPECT_EQ(j["meta"]["seed"], 11);
  EXPECT_EQ(j["meta"]["dt"], 0.05);
  EXPECT_EQ(j["meta"]["duration"], 30.0);
  const auto& s = j["series"];
  for (const char* k : {"t", "pointing_error_deg", "omega_BN_B_x", "omega_BN_B_y", "omega_BN_B_z",
                        "wheel_speed_rpm_0", "wheel_speed_rpm_3", "wheel_torque_0", "wheel_torque_3"}) {
    ASSERT_TRUE(s.contains(k)) << k;
    EXPECT_EQ(s[k].size(), 151u) << k;
    EXPECT_TRUE(j["units"].contains(k)) << k;
  }
  EXPECT_EQ(j["units"]["wheel_speed_rpm_0"], "rpm");
  EXPECT_EQ(j["units"]["pointing_error_deg"], "deg");
  // first recorded wheel speed is the configured 100 rpm
  EXPECT_NEAR(s["wheel_speed_rpm_0"][0].get<double>(), 100.0, 1e-9);
  ASSERT_EQ(j["attitude"]["q_BN"].size(), 151u);
  const auto& q0 = j["attitude"]["q_BN"][0];
  // sigma = (0.1, 0.2, -0.3): s2 = 0.14, beta0 = 0.86/1.14, beta_v = 2 sigma / 1.14
  EXPECT_NEAR(q0[0].get<double>(), 0.86 / 1.14, 1e-15);
  EXPECT_NEAR(q0[1].get<double>(), 0.2 / 1.14, 1e-15);
  EXPECT_NEAR(q0[3].get<double>(), -0.6 / 1.14, 1e-15);
  ASSERT_EQ(j["geometry"]["wheel_axes_B"].size(), 4u);
  EXPECT_NEAR(j["geometry"]["wheel_axes_B"][0][2].get<double>(), std::sin(40.0 * M_PI / 180.0), 1e-6);
  EXPECT_TRUE(j["geometry"]["thrusters"].is_array());
  // what the 3D view draws, as s1_sun_pointing.yaml gives it: the wheels'
  // names, 8 sun sensors of 80 deg half angle, the star tracker on +z_B, the
  // Sun fixed at 1 AU along x (no epoch: one sample), no central body (mu 0)
  const auto& g = j["geometry"];
  EXPECT_EQ(g["wheel_names"], nlohmann::json::array({"rw1", "rw2", "rw3", "rw4"}));
  ASSERT_EQ(g["sensors"]["css"]["normals_B"].size(), 8u);
  EXPECT_NEAR(g["sensors"]["css"]["fov_deg"].get<double>(), 80.0, 1e-12);
  EXPECT_NEAR(g["sensors"]["css"]["normals_B"][4][1].get<double>(), -0.965926, 1e-6);
  EXPECT_EQ(g["sensors"]["star_tracker"]["boresight_B"], nlohmann::json::array({0.0, 0.0, 1.0}));
  ASSERT_EQ(g["sun"]["t"].size(), 1u);
  EXPECT_EQ(g["sun"]["r_N"][0], nlohmann::json::array({1.495978707e11, 0.0, 0.0}));
  EXPECT_FALSE(g.contains("central_body"));
  EXPECT_FALSE(g.contains("burn"));
  const std::string dot = j["dataflow_dot"];
  EXPECT_EQ(dot.rfind("digraph", 0), 0u);
  // the FSW is one component, the application fsw_acs, between its messages
  EXPECT_NE(dot.find("\"m:fsw_sensors\" -> \"c:fsw_acs\""), std::string::npos);
  EXPECT_NE(dot.find("\"c:fsw_acs\" -> \"m:fsw_actuators\""), std::string::npos);
  EXPECT_NE(dot.find("\"c:fsw_acs\" -> \"m:fsw_health\""), std::string::npos);
  EXPECT_EQ(slurp(dir / "dataflow.dot"), dot);
#ifdef KESTREL_TEST_HAVE_REPORT
  // with the report writer in the build, the run also has its HTML page
  const std::string html = slurp(dir / "report.html");
  EXPECT_NE(html.find("<html"), std::string::npos);
  EXPECT_NE(html.find("s1_sun_pointing"), std::string::npos);
#endif
}

// S2 (2 s of it): Mars as the central body (equatorial radius 3396.19 km),
// the main-engine burn of the scenario, the thrusters' names; S3 (dated):
// the Sun sampled 65 times over the run, about 1 AU away (0.983 to 1.017 AU
// over a year).
TEST(Outputs, ReportDataSceneGeometry)
{
  const std::string src = std::string(KESTREL_SOURCE_DIR) + "/scenarios/";
  const fs::path dir = fresh_dir("report_scene");
  harness::RunOptions opt;
  opt.out_dir = dir.string();
  ASSERT_TRUE(harness::run_scenario(harness::load_scenario(src + "s2_mars_orbit_insertion.yaml", {{"duration", "2"}}), opt).ok);
  auto g = nlohmann::json::parse(slurp(dir / "report_data.json"))["geometry"];
  EXPECT_EQ(g["central_body"]["name"], "Mars");
  EXPECT_NEAR(g["central_body"]["radius"].get<double>(), 3396.19e3, 1e-6);
  EXPECT_EQ(g["burn"], nlohmann::json({{"thruster", "main"}, {"start", 360.0}, {"duration", 480.0}}));
  EXPECT_EQ(g["thrusters"][0]["name"], "main");
  EXPECT_EQ(g["thrusters"][8]["name"], "acs8");
  EXPECT_EQ(g["sun"]["r_N"][0], nlohmann::json::array({0.0, 2.279e11, 0.0}));
  EXPECT_FALSE(g["sensors"].contains("css"));
  fs::remove_all(dir);
  ASSERT_TRUE(harness::run_scenario(harness::load_scenario(src + "s3_leo_smallsat.yaml", {{"duration", "60"}}), opt).ok);
  g = nlohmann::json::parse(slurp(dir / "report_data.json"))["geometry"];
  EXPECT_EQ(g["central_body"]["name"], "Earth");
  ASSERT_EQ(g["sun"]["t"].size(), 65u);
  EXPECT_EQ(g["sun"]["t"][64], 60.0);
  for (const auto& r : g["sun"]["r_N"]) {
    const double au = std::hypot(r[0].get<double>(), r[1].get<double>(), r[2].get<double>()) / 1.495978707e11;
    EXPECT_GT(au, 0.98);
    EXPECT_LT(au, 1.02);
  }
  EXPECT_EQ(g["magnetorquer_names"], nlohmann::json::array({"mtq_x", "mtq_y", "mtq_z"}));
}

TEST(Outputs, RunFromManifestReproducesResults)
{
  const fs::path d1 = fresh_dir("repro1"), d2 = fresh_dir("repro2");
  std::ostringstream out, err;
  harness::RunCommand c;
  c.scenario = kS1;
  c.out_dir = d1.string();
  c.sets = {"duration=20", "rates.dt=0.05", "rates.fsw_divisor=2", "wheel_defaults.model=fully_coupled",
            "fsw.mrp_fb.K=4.0", "seed=1234"};
  ASSERT_EQ(harness::cmd_run(c, out, err), harness::kExitOk) << err.str();
  harness::RunCommand c2;
  c2.scenario = (d1 / "manifest.json").string();
  c2.out_dir = d2.string();
  ASSERT_EQ(harness::cmd_run(c2, out, err), harness::kExitOk) << err.str();
  const harness::Hdf5Table a = harness::read_hdf5((d1 / "results.h5").string());
  const harness::Hdf5Table b = harness::read_hdf5((d2 / "results.h5").string());
  EXPECT_EQ(a.seed, 1234u);
  EXPECT_EQ(b.seed, 1234u);
  EXPECT_EQ(a.names, b.names);
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_TRUE(a.data == b.data);  // bit-identical
  EXPECT_EQ(slurp(d1 / "report_data.json"), slurp(d2 / "report_data.json"));
  // the manifest of the rerun describes the same scenario
  const auto m1 = nlohmann::json::parse(slurp(d1 / "manifest.json"));
  const auto m2 = nlohmann::json::parse(slurp(d2 / "manifest.json"));
  EXPECT_EQ(m1["scenario"], m2["scenario"]);
  EXPECT_EQ(m1["scenario"]["fsw"]["mrp_fb"]["K"], 4.0);
  EXPECT_EQ(m1["overrides"].size(), 6u);
}

TEST(Outputs, UnwritableDirectoryIsAnOutputError)
{
  std::ostringstream out, err;
  harness::RunCommand c;
  c.scenario = kS1;
  c.out_dir = "/proc/kestrel_cannot_write_here";
  c.sets = {"duration=1"};
  EXPECT_EQ(harness::cmd_run(c, out, err), harness::kExitOutput) << err.str();
  EXPECT_NE(err.str().find("kestrel_cannot_write_here"), std::string::npos);
}

TEST(Outputs, ListShowsShippedScenarios)
{
  std::ostringstream out, err;
  EXPECT_EQ(harness::cmd_list(std::string(KESTREL_SOURCE_DIR) + "/scenarios", out, err), harness::kExitOk);
  EXPECT_NE(out.str().find("s1_sun_pointing.yaml"), std::string::npos);
}

// The run command holds the link's options (what the --on-missing, --link-*,
// --reply-timeout and --pil-* flags set) and hands them to the run unchanged.
TEST(Outputs, RunCommandPassesItsLinkOptionsUnchanged)
{
  harness::RunCommand c;
  c.scenario = kS1;
  c.fsw = "udp:127.0.0.1:4711";
  c.realtime = true;
  c.rt_scale = 3.0;
  c.link.on_missing = harness::LinkOptions::Missing::kZero;
  c.link.on_missing_set = true;
  c.link.timeout_s = 7.5;
  c.link.reply_timeout_s = 0.25;
  c.link.loss = 0.1;
  c.link.corrupt = 0.02;
  c.link.duplicate = 0.03;
  c.link.reorder = 0.04;
  c.link.delay = 0.05;
  c.link.delay_cycles = 9;
  c.link.seed = 1234567;
  c.link.pil_bin = "/opt/fsw.elf";
  c.link.pil_emulator = "qemu-arm -cpu cortex-a7";
  c.link.retransmit_s = 0.125;
  c.link.retransmits = 3;
  c.link.key_file = "/etc/kestrel/link.key";
  const harness::Scenario sc = harness::load_scenario(kS1);
  const harness::RunOptions o = harness::run_options_of(c, sc, {});
  EXPECT_EQ(o.fsw_link, c.fsw);
  EXPECT_EQ(o.realtime_scale, 3.0);
  EXPECT_EQ(o.out_dir, (fs::path("runs") / sc.name).string());
  const harness::LinkOptions& l = o.link;
  EXPECT_EQ(l.on_missing, c.link.on_missing);
  EXPECT_EQ(l.on_missing_set, c.link.on_missing_set);
  EXPECT_EQ(l.timeout_s, c.link.timeout_s);
  EXPECT_EQ(l.reply_timeout_s, c.link.reply_timeout_s);
  EXPECT_EQ(l.loss, c.link.loss);
  EXPECT_EQ(l.corrupt, c.link.corrupt);
  EXPECT_EQ(l.duplicate, c.link.duplicate);
  EXPECT_EQ(l.reorder, c.link.reorder);
  EXPECT_EQ(l.delay, c.link.delay);
  EXPECT_EQ(l.delay_cycles, c.link.delay_cycles);
  EXPECT_EQ(l.seed, c.link.seed);
  EXPECT_EQ(l.pil_bin, c.link.pil_bin);
  EXPECT_EQ(l.pil_emulator, c.link.pil_emulator);
  EXPECT_EQ(l.retransmit_s, c.link.retransmit_s);
  EXPECT_EQ(l.retransmits, c.link.retransmits);
  EXPECT_EQ(l.key_file, c.link.key_file);
}

// The defaulting rules of a run's link options (LinkOptions::for_run).
TEST(Outputs, LinkOptionsForARun)
{
  using M = harness::LinkOptions::Missing;
  harness::LinkOptions given;  // lockstep: a missing reply fails the run
  harness::LinkOptions lo = given.for_run(0.1, 0.0, nullptr);
  EXPECT_EQ(lo.on_missing, M::kFail);
  EXPECT_FALSE(lo.on_missing_set);
  EXPECT_EQ(lo.reply_timeout_s, 0.5);
  EXPECT_FALSE(lo.time_left);
  given.loss = 0.01;  // faults: hold
  lo = given.for_run(0.1, 0.0, nullptr);
  EXPECT_EQ(lo.on_missing, M::kHold);
  EXPECT_TRUE(lo.on_missing_set);
  given.loss = 0.0;  // paced: hold, one FSW period of wall time, the deadline
  lo = given.for_run(0.1, 4.0, [] { return 0.5; });
  EXPECT_EQ(lo.on_missing, M::kHold);
  EXPECT_EQ(lo.reply_timeout_s, 0.1 / 4.0);
  ASSERT_TRUE(lo.time_left);
  EXPECT_EQ(lo.time_left(), 0.5);
  given.on_missing = M::kZero;  // given: kept
  given.on_missing_set = true;
  given.loss = 0.2;
  EXPECT_EQ(given.for_run(0.1, 4.0, nullptr).on_missing, M::kZero);
  EXPECT_EQ(given.for_run(0.1, 0.0, nullptr).on_missing, M::kZero);
}

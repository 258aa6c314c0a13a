// A Monte Carlo campaign branched from a checkpoint (kestrel mc --from;
// docs/checkpoint.md, "Branching a campaign"): every run starts from the
// checkpoint's state.  Run k's records equal an independent restore of the
// checkpoint with run k's draws applied through the Run API; each run's
// manifest replays it bit for bit; threads change nothing; a dispersion of
// a key fixed before the checkpoint, a foreign, damaged, changed or missing
// checkpoint are refused with a message naming the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "harness/cli/commands.h"
#include "harness/core/checkpoint.h"
#include "harness/core/run.h"
#include "harness/drive/run_scenario.h"
#include "harness/mc/monte_carlo.h"
#include "harness/output/metrics.h"
#include "harness/scenario/scenario.h"
#include "scenario/mc_draw.h"

namespace {

namespace fs = std::filesystem;
using namespace harness;

const std::string kYaml = std::string(KESTREL_SOURCE_DIR) + "/test/harness/data/mc_from.yaml";
constexpr uint64_t kSaveTick = 800;  // t = 8 s at dt = 0.01 s

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::string read_text(const fs::path& p)
{
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class McBranch : public ::testing::Test {
 protected:
  static void SetUpTestSuite()
  {
    dir_ = fs::temp_directory_path() / ("kestrel_mc_branch_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    nominal_ = new Scenario(load_scenario(kYaml));
    ckpt_ = (dir_ / "s.ckpt").string();
    save_at(*nominal_, ckpt_, kSaveTick);
  }
  static void TearDownTestSuite()
  {
    delete nominal_;
    fs::remove_all(dir_);
  }

  // A checkpoint of sc saved before tick `tick`, from a run that accepts events.
  static void save_at(const Scenario& sc, const std::string& path, uint64_t tick, size_t chunk_rows = 1024,
                      bool accept_events = true)
  {
    RunConfig c;
    c.chunk_rows = chunk_rows;
    c.accept_events = accept_events;
    c.keep_in_memory = false;
    harness::Run a(sc, std::move(c));
    ASSERT_TRUE(a.step_ticks(tick));
    save_checkpoint(a, path, scenario_to_json_text(sc));
  }

  static McPlan plan()
  {
    McPlan p = make_mc_plan(*nominal_, nominal_->monte_carlo->seed, nominal_->monte_carlo->runs);
    branch_mc_plan(p, ckpt_);
    return p;
  }

  static std::vector<McRecord> campaign(const McPlan& p, const fs::path& d, unsigned jobs)
  {
    McRunOptions o;
    o.jobs = jobs;
    for (uint64_t k = 0; k < p.runs; ++k) o.indices.push_back(k);
    bool stopped = false;
    std::vector<McRecord> r = run_mc_runs(p, d, o, stopped);
    EXPECT_FALSE(stopped);
    return r;
  }

  static int mc_cli(const std::string& yaml, const std::string& from, const std::string& out, std::string& err)
  {
    McCommand c;
    c.scenario = yaml;
    c.from = from;
    c.out_dir = out;
    c.force = true;
    std::ostringstream o, e;
    const int rc = cmd_mc(c, o, e);
    err = e.str();
    return rc;
  }

  static fs::path dir_;
  static Scenario* nominal_;
  static std::string ckpt_;
};

fs::path McBranch::dir_;
Scenario* McBranch::nominal_ = nullptr;
std::string McBranch::ckpt_;

// The independent path: the checkpoint restored into a run of the nominal
// scenario with run k's seed and event time, the drawn gain and torque limit
// applied through Run::add_event at the checkpoint's tick; the campaign's
// metrics computed from its rows by a MetricSink of the plan's metrics.
std::vector<double> by_hand(const McPlan& p, const Scenario& nominal, const std::string& ckpt, uint64_t k,
                            std::vector<AppliedEvent>& applied)
{
  const McDraw d = draw_run(nominal, p.master_seed, k);  // the values: events[0].t, K, wheels[0].u_max
  Scenario sc = nominal;
  sc.monte_carlo.reset();
  sc.seed = mc_run_seed(p.master_seed, k);
  sc.events[0].t = d.drawn[0];
  RunConfig c;
  c.accept_events = true;
  c.keep_in_memory = false;
  harness::Run r(sc, std::move(c));
  MetricSink m(p.metrics);
  r.add_sink(m);
  std::vector<uint8_t> state;
  const CheckpointInfo info = decode_checkpoint(read_checkpoint_file(ckpt), state, ckpt);
  restore_branch_state(r, state);
  EventSpec e;
  e.name = "by_hand";
  e.t = static_cast<double>(info.tick * sc.tick_ns()) / 1e9;
  e.actions = {{"fsw", "gain_K", d.drawn[1]}, {sc.wheels[0].name, "torque_limit", d.drawn[2]}};
  r.add_event(e);
  EXPECT_TRUE(r.step_ticks(r.total_ticks())) << r.failure();
  r.finish();
  applied = r.events_applied();
  return m.values();
}

TEST_F(McBranch, RunsEqualAnIndependentRestoreAndReplayFromTheirManifests)
{
  const McPlan p = plan();
  ASSERT_TRUE(p.from);
  EXPECT_EQ(p.from->info.tick, kSaveTick);
  const fs::path d = dir_ / "campaign";
  const std::vector<McRecord> recs = campaign(p, d, 2);
  ASSERT_EQ(recs.size(), 4u);
  std::set<double> finals;
  for (const McRecord& rec : recs) {
    SCOPED_TRACE("run " + std::to_string(rec.index));
    ASSERT_FALSE(rec.invalid) << rec.reason;
    ASSERT_TRUE(rec.complete) << rec.reason;
    EXPECT_EQ(rec.seed, mc_run_seed(p.master_seed, rec.index));
    // (a) the independent restore with run k's draws
    std::vector<AppliedEvent> applied;
    const std::vector<double> mine = by_hand(p, *nominal_, ckpt_, rec.index, applied);
    ASSERT_EQ(mine.size(), rec.metrics.size());
    for (size_t i = 0; i < mine.size(); ++i)
      EXPECT_TRUE(same_bits(mine[i], rec.metrics[i])) << p.metrics[i].col.name << ": " << mine[i] << " vs "
                                                      << rec.metrics[i];
    finals.insert(rec.metrics[0]);
    // the failure fires at its drawn time, after the checkpoint
    bool failed = false;
    for (const AppliedEvent& e : applied)
      if (e.name == "rw2_fails") {
        failed = true;
        EXPECT_GE(e.tick, kSaveTick);
        EXPECT_EQ(e.tick, static_cast<uint64_t>(std::ceil(rec.drawn[0] / 0.01 - 1e-9)));
      }
    EXPECT_TRUE(failed);
    // (b) its manifest replayed alone: the same metrics, bit for bit
    const fs::path run_dir = d / "runs" / (std::string(6 - std::to_string(rec.index).size(), '0') + std::to_string(rec.index));
    const Scenario again = load_scenario((run_dir / "manifest.json").string());
    ASSERT_TRUE(again.from_checkpoint);
    EXPECT_EQ(again.from_checkpoint->tick, kSaveTick);
    MetricSink m(p.metrics);
    RunOptions o;
    o.out_dir = (dir_ / ("replay" + std::to_string(rec.index))).string();
    o.force = true;
    o.extra_sinks.push_back(&m);
    const RunResult rr = run_scenario(again, o);
    ASSERT_TRUE(rr.status.complete);
    const std::vector<double> replay = m.values();
    for (size_t i = 0; i < replay.size(); ++i)
      EXPECT_TRUE(same_bits(replay[i], rec.metrics[i])) << p.metrics[i].col.name;
    if (rec.full) {  // a run kept with full results: the replay's summary is its own, byte for byte
      const std::string s0 = read_text(run_dir / "summary.txt");
      EXPECT_NE(s0.find("pointing_error"), std::string::npos) << s0;
      EXPECT_EQ(s0, read_text(fs::path(o.out_dir) / "summary.txt"));
    }
  }
  EXPECT_TRUE(recs[0].full);
  EXPECT_EQ(finals.size(), recs.size()) << "each run's draws and noise should give its own outcome";
  // one thread: the same records
  const std::vector<McRecord> one = campaign(p, dir_ / "campaign_j1", 1);
  ASSERT_EQ(one.size(), recs.size());
  for (size_t k = 0; k < one.size(); ++k) {
    EXPECT_EQ(one[k].reason, recs[k].reason);
    for (size_t i = 0; i < one[k].metrics.size(); ++i) EXPECT_TRUE(same_bits(one[k].metrics[i], recs[k].metrics[i]));
    for (size_t i = 0; i < one[k].series.size(); ++i)
      EXPECT_TRUE(std::memcmp(&one[k].series[i], &recs[k].series[i], sizeof(float)) == 0);
  }
}

TEST_F(McBranch, TheSensorNoiseStartsFromEachRunsSeed)
{
  // two runs branched with the same seed are one run; another seed, other noise
  Scenario sc = *nominal_;
  sc.monte_carlo.reset();
  std::vector<uint8_t> state;
  decode_checkpoint(read_checkpoint_file(ckpt_), state, ckpt_);
  auto final_meas = [&](uint64_t seed) {
    sc.seed = seed;
    RunConfig c;
    c.accept_events = true;
    harness::Run r(sc, std::move(c));
    restore_branch_state(r, state);
    EXPECT_TRUE(r.step_ticks(200));
    // the state after 2 s: its bytes hold every sensor's noise stream and output
    return save_run_state(r);
  };
  EXPECT_TRUE(final_meas(5) == final_meas(5));
  EXPECT_TRUE(final_meas(5) != final_meas(6));
  // and the streams are those a fresh run of that seed starts with: a run
  // restored in full (restore_run_state) then continued with the nominal's
  // streams differs from the branched one of the nominal's own seed
  sc.seed = nominal_->seed;
  RunConfig c;
  c.accept_events = true;
  harness::Run full(sc, std::move(c));
  restore_run_state(full, state);
  ASSERT_TRUE(full.step_ticks(200));
  EXPECT_TRUE(save_run_state(full) != final_meas(nominal_->seed));
}

TEST_F(McBranch, FixedKeysAndBadCheckpointsAreRefusedBeforeAnyRun)
{
  const std::string text = read_text(kYaml);
  auto variant = [&](const std::string& extra, const std::string& name) {
    std::string t = text;
    const std::string at = "    - {key: \"wheels[0].u_max\", dist: uniform, min: 0.1, max: 0.2}\n";
    t.replace(t.find(at), at.size(), at + extra);
    const fs::path p = dir_ / name;
    std::ofstream(p) << t;
    return p.string();
  };
  std::string err;
  // (c) a key fixed before the checkpoint, named
  const std::string mass = variant("    - {key: spacecraft.mass, dist: uniform, min: 700, max: 800}\n", "mass.yaml");
  EXPECT_EQ(mc_cli(mass, ckpt_, (dir_ / "c1").string(), err), 3);
  EXPECT_NE(err.find("monte_carlo.dispersions[3].key: spacecraft.mass: fixed before the checkpoint (t = 8 s)"),
            std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "c1"));
  const std::string att =
      variant("    - {key: spacecraft.initial.sigma_BN, dist: attitude, angle_max_deg: 5}\n", "att.yaml");
  EXPECT_EQ(mc_cli(att, ckpt_, (dir_ / "c1").string(), err), 3);
  EXPECT_NE(err.find("spacecraft.initial.sigma_BN: fixed before the checkpoint"), std::string::npos) << err;
  // an event that is not a time event (after ...) is fixed too
  const std::string delay = variant("    - {key: \"events[1].delay\", dist: uniform, min: 0.1, max: 0.5}\n", "d.yaml");
  EXPECT_EQ(mc_cli(delay, ckpt_, (dir_ / "c1").string(), err), 3);
  EXPECT_NE(err.find("events[1].delay: the event fires before the checkpoint"), std::string::npos) << err;
  // an event time drawn before the checkpoint: that run is an invalid draw, the others run
  std::string t = text;
  const std::string at = "min: 8.5, max: 15}";
  t.replace(t.find(at), at.size(), "min: 2, max: 15}");
  const fs::path early = dir_ / "early.yaml";
  std::ofstream(early) << t;
  EXPECT_EQ(mc_cli(early.string(), ckpt_, (dir_ / "c2").string(), err), 6) << err;
  const std::string summary = read_text(dir_ / "c2" / "summary.csv");
  EXPECT_NE(summary.find("invalid draw: events[0].t: drawn "), std::string::npos) << summary;
  EXPECT_NE(summary.find(" s, before the checkpoint (t = 8 s)"), std::string::npos) << summary;
  EXPECT_NE(summary.find(",pass,"), std::string::npos) << summary;
  // a settable key needs a checkpoint of a run that accepts events (the state's layout)
  const std::string closed = (dir_ / "closed.ckpt").string();
  save_at(*nominal_, closed, kSaveTick, 1024, false);
  EXPECT_EQ(mc_cli(kYaml, closed, (dir_ / "c1").string(), err), 3);
  EXPECT_NE(err.find("monte_carlo.dispersions[1].key: fsw.mrp_fb.K: set by an event action at the checkpoint, but "
                     "the checkpoint's run was built without RunConfig::accept_events"),
            std::string::npos) << err;
  // (d) a checkpoint of another scenario
  Scenario other = *nominal_;
  set_parameter(other, "fsw.mrp_fb.P", 31.0);
  const std::string foreign = (dir_ / "other.ckpt").string();
  save_at(other, foreign, kSaveTick);
  EXPECT_EQ(mc_cli(kYaml, foreign, (dir_ / "c1").string(), err), 3);
  EXPECT_NE(err.find("not of this campaign's nominal scenario"), std::string::npos) << err;
  EXPECT_NE(err.find("P"), std::string::npos) << err;
  // a damaged one (one byte changed), a missing one
  std::vector<uint8_t> bytes = read_checkpoint_file(ckpt_);
  bytes[bytes.size() / 2] ^= 0x40;
  const std::string bad = (dir_ / "bad.ckpt").string();
  write_checkpoint_file(bad, bytes);
  EXPECT_EQ(mc_cli(kYaml, bad, (dir_ / "c1").string(), err), 3);
  EXPECT_NE(err.find("checksum mismatch"), std::string::npos) << err;
  EXPECT_EQ(mc_cli(kYaml, (dir_ / "none.ckpt").string(), (dir_ / "c1").string(), err), 3);
  EXPECT_NE(err.find("no such checkpoint file"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "c1"));
}

TEST_F(McBranch, TheCommandWritesTheCampaignAndRecordsTheCheckpoint)
{
  McCommand c;
  c.scenario = kYaml;
  c.from = ckpt_;
  c.out_dir = (dir_ / "cli").string();
  c.jobs = 2;
  std::ostringstream o, e;
  const int rc = cmd_mc(c, o, e);
  EXPECT_TRUE(rc == 0 || rc == 6) << rc << ": " << e.str();
  for (const char* f : {"summary.csv", "summary.h5", "mc_runs.json", "mc_report_data.json", "mc_manifest.json"})
    EXPECT_TRUE(fs::exists(dir_ / "cli" / f)) << f;
  const std::string m = read_text(dir_ / "cli" / "mc_manifest.json");
  EXPECT_NE(m.find("\"from_checkpoint\""), std::string::npos);
  EXPECT_NE(m.find(fs::path(ckpt_).lexically_normal().string()), std::string::npos);
  // the records are those of the library's campaign (the same plan)
  const std::string runs = read_text(dir_ / "cli" / "runs" / "000002" / "manifest.json");
  EXPECT_NE(runs.find("\"from_checkpoint\""), std::string::npos);
  EXPECT_NE(runs.find("\"tick\": 800"), std::string::npos);
  // --shard, --slurm and --resume are refused with --from
  c.shard_count = 2;
  std::ostringstream e2;
  EXPECT_EQ(cmd_mc(c, o, e2), 2);
  EXPECT_NE(e2.str().find("not with --shard, --slurm or --resume"), std::string::npos) << e2.str();
}

TEST_F(McBranch, AChoiceOfFswModeAndAReferenceBecomeCommandsAtTheCheckpoint)
{
  std::string t = read_text(kYaml);
  const std::string at = "    - {key: \"wheels[0].u_max\", dist: uniform, min: 0.1, max: 0.2}\n";
  t.replace(t.find(at), at.size(),
            at + "    - {key: fsw.mode, dist: choice, values: [sun_safe, inertial]}\n"
                 "    - {key: fsw.inertial.sigma_R0N, dist: attitude, angle_max_deg: 10}\n");
  const fs::path y = dir_ / "mode.yaml";
  std::ofstream(y) << t;
  std::string err;
  const int rc = mc_cli(y.string(), ckpt_, (dir_ / "mode").string(), err);
  EXPECT_TRUE(rc == 0 || rc == 6) << err;
  int inertial = 0;
  for (int k = 0; k < 4; ++k) {
    const std::string m = read_text(dir_ / "mode" / "runs" / ("00000" + std::to_string(k)) / "manifest.json");
    EXPECT_EQ(m.find("invalid"), std::string::npos) << m.substr(0, 400);
    // the nominal mode stays in the scenario; the drawn one is a command at t = 8 s
    EXPECT_NE(m.find("\"actions\": \"fsw gain_K"), std::string::npos);
    EXPECT_NE(m.find("fsw reference_x"), std::string::npos);
    if (m.find("fsw mode_inertial") != std::string::npos) ++inertial;
    const Scenario sc = load_scenario((dir_ / "mode" / "runs" / ("00000" + std::to_string(k)) / "manifest.json").string());
    EXPECT_EQ(sc.fsw.mode, nominal_->fsw.mode);
  }
  EXPECT_GT(inertial, 0);
  EXPECT_LT(inertial, 4);
  // run 0 (kept with full results) replayed from its manifest: the same summary, byte for byte
  RunCommand rc0;
  rc0.scenario = (dir_ / "mode" / "runs" / "000000" / "manifest.json").string();
  rc0.out_dir = (dir_ / "mode_r0").string();
  std::ostringstream o, e;
  ASSERT_EQ(cmd_run(rc0, o, e), 0) << e.str();
  const std::string s0 = read_text(dir_ / "mode" / "runs" / "000000" / "summary.txt");
  EXPECT_NE(s0.find("pointing_error"), std::string::npos) << s0;
  EXPECT_EQ(s0, read_text(dir_ / "mode_r0" / "summary.txt"));
}

TEST_F(McBranch, ACheckpointOfRowByRowRecordingBranchesTheSame)
{
  // a Python run's checkpoint hands on every row (chunk of 1): the restored
  // recorder takes that chunk size; the physics is the same, so the final
  // values and the windowed criteria are those of the campaign from the
  // default chunk, and the rows handed on start at the checkpoint's tick
  const std::string one = (dir_ / "rowwise.ckpt").string();
  save_at(*nominal_, one, kSaveTick, 1);
  McPlan p1 = make_mc_plan(*nominal_, nominal_->monte_carlo->seed, 2);
  branch_mc_plan(p1, one);
  EXPECT_EQ(p1.from->info.sink_rows, kSaveTick / 10);  // every row recorded before tick 800 (t = 0 ... 7.9 s)
  McPlan p = make_mc_plan(*nominal_, nominal_->monte_carlo->seed, 2);
  branch_mc_plan(p, ckpt_);
  const std::vector<McRecord> a = campaign(p1, dir_ / "rowwise", 1), b = campaign(p, dir_ / "chunked", 1);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    ASSERT_TRUE(a[k].complete) << a[k].reason;
    for (size_t i = 0; i < p.metrics.size(); ++i)
      if (p.metrics[i].stat == "final" || p.metrics[i].criterion >= 0)
        EXPECT_TRUE(same_bits(a[k].metrics[i], b[k].metrics[i])) << p.metrics[i].col.name;
  }
}

TEST_F(McBranch, AManifestWhoseCheckpointChangedOrWentIsRefused)
{
  // a one-run campaign from a copy of the checkpoint, then the copy re-saved at another tick
  const std::string copy = (dir_ / "copy.ckpt").string();
  fs::copy_file(ckpt_, copy, fs::copy_options::overwrite_existing);
  McPlan p = make_mc_plan(*nominal_, nominal_->monte_carlo->seed, 1);
  branch_mc_plan(p, copy);
  const fs::path d = dir_ / "one";
  ASSERT_EQ(campaign(p, d, 1).size(), 1u);
  const std::string manifest = (d / "runs" / "000000" / "manifest.json").string();
  RunCommand rc;
  rc.scenario = manifest;
  rc.out_dir = (dir_ / "r").string();
  rc.force = true;
  std::ostringstream out, err;
  EXPECT_EQ(cmd_run(rc, out, err), 0) << err.str();
  save_at(*nominal_, copy, kSaveTick + 1);
  std::ostringstream err2;
  EXPECT_NE(cmd_run(rc, out, err2), 0);
  EXPECT_NE(err2.str().find("the checkpoint has changed since; refused"), std::string::npos) << err2.str();
  fs::remove(copy);
  std::ostringstream err3;
  EXPECT_NE(cmd_run(rc, out, err3), 0);
  EXPECT_NE(err3.str().find("no such checkpoint file"), std::string::npos) << err3.str();
}

}  // namespace

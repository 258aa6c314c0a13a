// Checkpoint and restore of a run (docs/checkpoint.md): a run restored from
// a checkpoint continues exactly as the run it was saved from would have,
// every recorded value bit for bit; a damaged, foreign or mismatched
// checkpoint is refused with a message naming the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "harness/core/checkpoint.h"
#include "harness/core/run.h"
#include "harness/scenario/scenario.h"

namespace {

using harness::CheckpointError;
using harness::Override;
using harness::RunConfig;
using harness::Scenario;

std::string scen(const char* f) { return std::string(KESTREL_SOURCE_DIR) + "/scenarios/" + f; }

RunConfig small_chunks()
{
  RunConfig c;
  c.chunk_rows = 37;  // several chunks, and checkpoints in the middle of one
  return c;
}

// Bitwise equality of two doubles (NaN equal to the same NaN).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_story(const harness::Run& x, const harness::Run& y)
{
  const auto sx = x.summary(), sy = y.summary();
  ASSERT_EQ(sx.size(), sy.size());
  for (size_t i = 0; i < sx.size(); ++i) {
    EXPECT_EQ(sx[i].key, sy[i].key);
    EXPECT_TRUE(same_bits(sx[i].value, sy[i].value)) << sx[i].key << ": " << sx[i].value << " vs " << sy[i].value;
  }
  ASSERT_EQ(x.events_applied().size(), y.events_applied().size());
  for (size_t i = 0; i < x.events_applied().size(); ++i) {
    EXPECT_EQ(x.events_applied()[i].name, y.events_applied()[i].name);
    EXPECT_EQ(x.events_applied()[i].tick, y.events_applied()[i].tick);
    EXPECT_EQ(x.events_applied()[i].what, y.events_applied()[i].what);
  }
  EXPECT_EQ(x.fsw_health_lines(), y.fsw_health_lines());
  EXPECT_TRUE(same_bits(x.max_jitter_step(), y.max_jitter_step()));
}

// Runs `sc` whole; again to `save_tick`, saved, continued; and a third run
// restored from that state and continued.  Every row the restored run
// records equals the uninterrupted run's, bit for bit.
void check_resume(const Scenario& sc, uint64_t save_tick)
{
  harness::Run full(sc, small_chunks());
  ASSERT_TRUE(full.step_ticks(full.total_ticks())) << full.failure();
  ASSERT_LT(save_tick, full.total_ticks());

  harness::Run a(sc, small_chunks());
  ASSERT_TRUE(a.step_ticks(save_tick));
  const std::vector<uint8_t> state = harness::save_run_state(a);
  const uint64_t sink_rows = a.recorder().sink_rows();
  EXPECT_GT(a.recorder().rows(), sink_rows) << "the checkpoint should fall inside a chunk";
  ASSERT_TRUE(a.step_ticks(a.total_ticks()));  // saving changes nothing

  harness::Run b(sc, small_chunks());
  harness::restore_run_state(b, state);
  EXPECT_EQ(save_tick, b.tick());
  EXPECT_EQ(state, harness::save_run_state(b));  // the round trip keeps every byte
  ASSERT_TRUE(b.step_ticks(b.total_ticks())) << b.failure();
  ASSERT_TRUE(b.done());

  const harness::MemorySink &mf = full.memory(), &ma = a.memory(), &mb = b.memory();
  const size_t nc = mf.num_columns();
  ASSERT_EQ(mf.rows(), ma.rows());
  EXPECT_EQ(0, std::memcmp(mf.data(), ma.data(), sizeof(double) * nc * mf.rows()));
  ASSERT_EQ(mf.rows() - sink_rows, mb.rows());
  for (uint64_t r = 0; r < mb.rows(); ++r)
    ASSERT_EQ(0, std::memcmp(mf.data() + (sink_rows + r) * nc, mb.data() + r * nc, sizeof(double) * nc))
        << "row " << sink_rows + r;
  EXPECT_TRUE(mb.complete());
  expect_same_story(full, a);
  expect_same_story(full, b);
}

}  // namespace

TEST(Checkpoint, S1ContinuesBitForBit)
{
  // S1: fully coupled wheels (jitter), gyro, star tracker, tachometers and
  // CSS noise streams; saved between two FSW ticks
  check_resume(harness::load_scenario(scen("s1_sun_pointing.yaml"), {{"duration", "30"}}), 1234);
}

TEST(Checkpoint, EventScenarioContinuesBitForBit)
{
  // saved between an event and the one that follows it 0.1 s later: the
  // follower's trigger time, the log and the wheel's failure carry over
  const Scenario sc =
      harness::load_scenario(scen("s1_wheel_failure.yaml"), {{"duration", "12"}, {"events.0.t", "5"}});
  check_resume(sc, 505);
}

TEST(Checkpoint, S2ContinuesBitForBitAcrossTheBurnAndAStuckThruster)
{
  const std::vector<Override> ov = {{"rates.dt", "0.1"},       {"rates.fsw_divisor", "1"},
                                    {"rates.record_divisor", "5"}, {"duration", "560"},
                                    {"burn.start", "380"},     {"events.0.t", "420"}};
  const Scenario sc = harness::load_scenario(scen("s2_thruster_stuck.yaml"), ov);
  check_resume(sc, 3903);  // mid-burn, before the thruster sticks
  check_resume(sc, 4301);  // after
}

TEST(Checkpoint, EnvironmentAndMagnetorquersContinueBitForBit)
{
  // gravity gradient, solar pressure, drag, IGRF field, PWM rods, magnetometer
  check_resume(harness::load_scenario(scen("s3_detumble_hold.yaml"), {{"duration", "200"}}), 1017);
  check_resume(harness::load_scenario(scen("s3_leo_smallsat.yaml"), {{"duration", "200"}}), 777);
}

namespace {

struct Files {
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("kestrel_ckpt_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                               "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  Files() { std::filesystem::create_directories(dir); }
  ~Files() { std::filesystem::remove_all(dir); }
  std::string operator()(const char* name) const { return (dir / name).string(); }
};

std::string message_of(const std::function<void()>& f)
{
  try {
    f();
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "(no CheckpointError)";
}

Scenario s1_short(const char* duration = "5") { return harness::load_scenario(scen("s1_sun_pointing.yaml"), {{"duration", duration}}); }

}  // namespace

TEST(Checkpoint, FileRoundTripAndAtomicReplacement)
{
  Files f;
  const Scenario sc = s1_short();
  const std::string text = harness::scenario_to_json_text(sc);
  harness::Run a(sc);
  ASSERT_TRUE(a.step_ticks(150));
  harness::save_checkpoint(a, f("c.ckpt"), text);
  ASSERT_TRUE(a.step_ticks(50));
  harness::save_checkpoint(a, f("c.ckpt"), text);  // replaces the first whole
  EXPECT_FALSE(std::filesystem::exists(f("c.ckpt.tmp")));
  harness::Run b(sc);
  const harness::CheckpointInfo info = harness::restore_checkpoint(b, f("c.ckpt"), text);
  EXPECT_EQ(200u, info.tick);
  EXPECT_EQ(200u, b.tick());
  EXPECT_EQ(a.total_ticks(), info.total_ticks);
  EXPECT_EQ(a.recorder().sink_rows(), info.sink_rows);
  EXPECT_EQ("s1_sun_pointing", info.scenario_name);
  EXPECT_EQ(text, info.scenario_text);
  EXPECT_EQ(std::string(harness::version()), info.kestrel_version);
  // the layout's fixed header (docs/checkpoint.md): magic, format, flags, tick
  const std::vector<uint8_t> bytes = harness::read_checkpoint_file(f("c.ckpt"));
  EXPECT_EQ(0, std::memcmp(bytes.data(), "KSTRLCKP", 8));
  EXPECT_EQ(2u, bytes[8]);
  uint64_t tick = 0;
  for (int i = 0; i < 8; ++i) tick |= uint64_t(bytes[16 + size_t(i)]) << (8 * i);
  EXPECT_EQ(200u, tick);
  // a checkpoint cannot be written where no folder is: the message says so
  EXPECT_NE(std::string::npos, message_of([&] {
              harness::save_checkpoint(a, f("no_such_dir/c.ckpt"), text);
            }).find("cannot create"));
}

TEST(Checkpoint, DamagedFilesAreRefused)
{
  Files f;
  const Scenario sc = s1_short();
  const std::string text = harness::scenario_to_json_text(sc);
  harness::Run a(sc);
  ASSERT_TRUE(a.step_ticks(100));
  harness::save_checkpoint(a, f("c.ckpt"), text);
  const std::vector<uint8_t> good = harness::read_checkpoint_file(f("c.ckpt"));
  auto restore_bytes = [&](const std::vector<uint8_t>& b) {
    std::ofstream(f("bad.ckpt"), std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
    harness::Run r(sc);
    return message_of([&] { harness::restore_checkpoint(r, f("bad.ckpt"), text); });
  };
  for (size_t at : {size_t(20), good.size() / 2, good.size() - 9, good.size() - 1}) {  // one flipped bit anywhere
    std::vector<uint8_t> b = good;
    b[at] ^= 0x10;
    EXPECT_NE(std::string::npos, restore_bytes(b).find("checksum mismatch")) << at;
  }
  std::vector<uint8_t> cut(good.begin(), good.begin() + std::ptrdiff_t(good.size() / 3));
  EXPECT_NE(std::string::npos, restore_bytes(cut).find("checksum mismatch"));
  EXPECT_NE(std::string::npos, restore_bytes({'h', 'e', 'l', 'l', 'o'}).find("not a Kestrel checkpoint"));
  std::vector<uint8_t> v2 = good;
  v2[8] = 3;  // another format version: named before the checksum is looked at
  EXPECT_NE(std::string::npos, restore_bytes(v2).find("checkpoint format 3; this kestrel reads format 2"));
  // the file on disk is never touched by a refused restore
  EXPECT_EQ(good, harness::read_checkpoint_file(f("c.ckpt")));
}

// Format 2 added the `outputs` text after the scenario; a format-1 file
// (the same bytes without that field, version 1, its own checksum: made
// here by hand from the layout in docs/checkpoint.md) is still read.
TEST(Checkpoint, OutputsTextRoundTripsAndFormatOneIsStillRead)
{
  const Scenario sc = s1_short();
  harness::Run a(sc);
  ASSERT_TRUE(a.step_ticks(50));
  harness::CheckpointInfo info;
  info.tick = 50;
  info.total_ticks = a.total_ticks();
  info.kestrel_version = "v";
  info.scenario_name = sc.name;
  info.scenario_text = harness::scenario_to_json_text(sc);
  info.outputs = "{\"x\":1}";
  const std::vector<uint8_t> state = harness::save_run_state(a);
  std::vector<uint8_t> back;
  const std::vector<uint8_t> v2 = harness::encode_checkpoint(info, state);
  EXPECT_EQ("{\"x\":1}", harness::decode_checkpoint(v2, back).outputs);
  EXPECT_EQ(state, back);
  // format 1: drop the outputs field (u64 length + 7 bytes), version 1, new FNV-1a 64
  const size_t at = 40 + (8 + info.kestrel_version.size()) + (8 + info.scenario_name.size()) +
                    (8 + info.scenario_text.size());
  std::vector<uint8_t> v1(v2.begin(), v2.end() - 8);
  v1.erase(v1.begin() + std::ptrdiff_t(at), v1.begin() + std::ptrdiff_t(at + 8 + info.outputs.size()));
  v1[8] = 1;
  uint64_t h = 0xcbf29ce484222325ull;
  for (uint8_t b : v1) h = (h ^ b) * 0x100000001b3ull;
  for (int i = 0; i < 8; ++i) v1.push_back(uint8_t(h >> (8 * i)));
  const harness::CheckpointInfo old = harness::decode_checkpoint(v1, back);
  EXPECT_EQ("", old.outputs);
  EXPECT_EQ(info.scenario_text, old.scenario_text);
  EXPECT_EQ(state, back);
}

TEST(Checkpoint, AForeignScenarioIsRefusedWithTheDifference)
{
  Files f;
  const Scenario s1 = s1_short();
  harness::Run a(s1);
  ASSERT_TRUE(a.step_ticks(100));
  harness::save_checkpoint(a, f("c.ckpt"), harness::scenario_to_json_text(s1));
  const Scenario longer = s1_short("6");
  harness::Run b(longer);
  const std::string m =
      message_of([&] { harness::restore_checkpoint(b, f("c.ckpt"), harness::scenario_to_json_text(longer)); });
  EXPECT_NE(std::string::npos, m.find("a checkpoint of scenario 's1_sun_pointing'")) << m;
  EXPECT_NE(std::string::npos, m.find("\"duration\": 5")) << m;
  EXPECT_NE(std::string::npos, m.find("\"duration\": 6")) << m;
  EXPECT_EQ(0u, b.tick());
  const Scenario s2 = harness::load_scenario(scen("s2_thruster_stuck.yaml"), {{"rates.dt", "0.1"}});
  harness::Run c(s2);
  const std::string m2 =
      message_of([&] { harness::restore_checkpoint(c, f("c.ckpt"), harness::scenario_to_json_text(s2)); });
  EXPECT_NE(std::string::npos, m2.find("not of this run's ('s2_thruster_stuck')")) << m2;
}

TEST(Checkpoint, StateOfAnotherRunDoesNotFit)
{
  // the state bytes alone, into a run of another configuration: the first
  // part whose size differs is named
  harness::Run a(s1_short());
  ASSERT_TRUE(a.step_ticks(10));
  const std::vector<uint8_t> state = harness::save_run_state(a);
  harness::Run c(harness::load_scenario(scen("s2_thruster_stuck.yaml"), {{"rates.dt", "0.1"}}));
  const std::string m = message_of([&] { harness::restore_run_state(c, state); });
  EXPECT_NE(std::string::npos, m.find("checkpoint")) << m;
  EXPECT_NE(m, "(no CheckpointError)");
  // restoring into a run that has started is a programming error
  harness::Run d(s1_short());
  ASSERT_TRUE(d.step_ticks(1));
  EXPECT_THROW(harness::restore_run_state(d, state), std::logic_error);
}

namespace {
// An FSW that runs elsewhere (as a link to a process or a board would).
class Elsewhere : public harness::FswEndpoint {
 public:
  std::string describe() const override { return "FSW on a test board"; }
  void cycle(const FswAcsSensorMsg&, FswAcsActuatorMsg& out, FswAcsHealthMsg& h) override
  {
    out = FswAcsActuatorMsg{};
    h = FswAcsHealthMsg{};
  }
};
}  // namespace

TEST(Checkpoint, ARunWhoseFswRunsElsewhereCannotBeSaved)
{
  RunConfig cfg;
  cfg.fsw = std::make_unique<Elsewhere>();
  harness::Run r(s1_short(), std::move(cfg));
  ASSERT_TRUE(r.step_ticks(10));
  EXPECT_NE(std::string::npos, r.checkpoint_refusal().find("FSW on a test board")) << r.checkpoint_refusal();
  EXPECT_THROW(harness::save_run_state(r), std::logic_error);
  harness::Run done(s1_short("0.1"));
  ASSERT_TRUE(done.step_ticks(done.total_ticks()));
  EXPECT_EQ("the run has ended", done.checkpoint_refusal());
}

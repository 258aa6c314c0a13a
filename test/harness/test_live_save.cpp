// The live view's "save state" (docs/live.md, docs/checkpoint.md): POST
// {op: save} writes a checkpoint of the run at a tick boundary into its
// results folder (checkpoint-<tick>.kckp), the command log gives its name
// and size; the checkpoint holds the scenario with the events the page
// added, and a Run built from that scenario and restored from it records
// what the uninterrupted run recorded, bit for bit.  Refused with a
// message when the run has no results folder or has ended.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>
#include <utility>

#include "harness/core/checkpoint.h"
#include "harness/core/run.h"
#include "harness/drive/run_scenario.h"
#include "harness/output/outputs.h"
#include "harness/output/results_dir.h"
#include "harness/scenario/scenario.h"
#include "live_test_util.h"

using namespace live_test;

namespace {

// the command log's entry for command `id` (the last kLogPage are in /api/frames)
json log_entry(Served& s, uint64_t id)
{
  const json f = s.frames();
  if (f.is_null()) return json();
  for (const json& c : f["commands"])
    if (c["id"].get<uint64_t>() == id) return c;
  return json();
}

// waits until command `id` is applied or refused; its log entry
json settled(Served& s, uint64_t id)
{
  json e;
  wait_for([&] {
    e = log_entry(s, id);
    return !e.is_null() && e["status"] != "queued";
  });
  return e;
}

}  // namespace

// Paused after tick 0: rw2 failed from the page (applies at tick 1), 29
// steps, then "save state" at the boundary before tick 30 (t = 7.5 s).
TEST(LiveSave, CheckpointAtATickBoundaryRestoresBitForBit)
{
  const fs::path dir = temp_dir("save");
  Served s(paused_options());
  harness::RunResult res;
  std::thread sim = s.start_run(dir / "run", res);
  ASSERT_TRUE(s.started());
  const json info = json::parse(s.cli.Get("/api/info", s.auth(s.srv.token()))->body);
  EXPECT_EQ(info["save_refused"], "");  // an in-process FSW, a results folder: it can be saved

  EXPECT_EQ(s.post_ok({{"op", "event"}, {"device", "rw2"}, {"action", "fail_off"}})->status, 202);
  EXPECT_EQ(s.post_ok({{"op", "step"}, {"ticks", 29}})->status, 202);
  ASSERT_TRUE(wait_for([&] {
    const json f = s.frames();
    return !f.is_null() && f["state"] == "paused" && !f["frames"].empty() && f["frames"].back()["tick"] == 30;
  }));
  auto r = s.post_ok({{"op", "save"}});
  ASSERT_EQ(r->status, 202);
  const json q = json::parse(r->body);
  EXPECT_EQ(q["command"], "save state");
  const json e = settled(s, q["id"].get<uint64_t>());
  ASSERT_EQ(e["status"], "applied") << e.dump();
  EXPECT_EQ(e["tick"], 30);
  EXPECT_EQ(e["t"].get<double>(), 7.5);
  ASSERT_EQ(e["file"]["name"], "checkpoint-30.kckp");
  EXPECT_NE(e["detail"].get<std::string>().find("saved checkpoint-30.kckp"), std::string::npos) << e.dump();
  EXPECT_EQ(s.post_ok({{"op", "resume"}})->status, 202);
  sim.join();
  ASSERT_TRUE(res.ok) << res.failure;
  r = s.post_ok({{"op", "save"}});  // the run has ended
  EXPECT_EQ(r->status, 409);
  EXPECT_NE(error_of(r).find("the run has ended"), std::string::npos) << error_of(r);

  // the file is in the results folder, whole (no .tmp), of the size the log gave
  const fs::path ck = dir / "run" / "checkpoint-30.kckp";
  ASSERT_TRUE(fs::exists(ck));
  EXPECT_FALSE(fs::exists(dir / "run" / "checkpoint-30.kckp.tmp"));
  EXPECT_EQ(fs::file_size(ck), e["file"]["bytes"].get<uint64_t>());
  EXPECT_TRUE(harness::ResultsDir::is_result_file_name("checkpoint-30.kckp"));  // --force may replace the folder

  // its header and scenario: tick 30, with the event the page added
  std::vector<uint8_t> state;
  const harness::CheckpointInfo ci =
      harness::decode_checkpoint(harness::read_checkpoint_file(ck.string()), state, ck.string());
  EXPECT_EQ(ci.tick, 30u);
  EXPECT_EQ(ci.total_ticks, 241u);
  const harness::Scenario sc = harness::load_scenario_text(ci.scenario_text, "checkpoint-30.kckp");
  ASSERT_EQ(sc.events.size(), 1u);
  EXPECT_EQ(sc.events[0].t, 0.25);
  ASSERT_EQ(sc.events[0].actions.size(), 1u);
  EXPECT_EQ(sc.events[0].actions[0].device, "rw2");

  // restored into a run built from that scenario as the live run was
  // (RunConfig::accept_events: the FSW command message exists) and
  // continued: every row from sink_rows on is the live run's (its
  // results.h5), bit for bit.  Built without it, the run has one message
  // fewer: refused.
  harness::Run without(sc);
  EXPECT_THROW(harness::restore_checkpoint(without, ck.string(), ci.scenario_text), harness::CheckpointError);
  harness::RunConfig cfg;
  cfg.accept_events = true;
  harness::Run b(sc, std::move(cfg));
  const harness::CheckpointInfo bi = harness::restore_checkpoint(b, ck.string(), ci.scenario_text);
  EXPECT_EQ(b.tick(), 30u);
  ASSERT_TRUE(b.step_ticks(b.total_ticks())) << b.failure();
  ASSERT_TRUE(b.done());
  const harness::Hdf5Table h = harness::read_hdf5((dir / "run" / "results.h5").string());
  const harness::MemorySink& mb = b.memory();
  const size_t nc = h.names.size();
  ASSERT_EQ(mb.num_columns(), nc);
  ASSERT_EQ(h.rows, 241u);
  ASSERT_EQ(mb.rows(), h.rows - bi.sink_rows);
  for (uint64_t row = 0; row < mb.rows(); ++row)
    ASSERT_EQ(0, std::memcmp(h.data.data() + (bi.sink_rows + row) * nc, mb.data() + row * nc, sizeof(double) * nc))
        << "row " << bi.sink_rows + row;

  // and the save changed nothing: the checkpoint's scenario run whole, no page
  harness::RunOptions plain;
  plain.out_dir = (dir / "plain").string();
  ASSERT_TRUE(harness::run_scenario(sc, plain).ok);
  const harness::Hdf5Table hp = harness::read_hdf5((dir / "plain" / "results.h5").string());
  ASSERT_EQ(hp.data.size(), h.data.size());
  EXPECT_EQ(0, std::memcmp(hp.data.data(), h.data.data(), sizeof(double) * h.data.size()));
  fs::remove_all(dir);
}

// A run without a results folder has nowhere to save: refused at once (409)
// with the reason, nothing queued; the page's info says so too.
TEST(LiveSave, RefusedWithoutAResultsFolder)
{
  Served s(paused_options());
  harness::RunResult res;
  std::thread sim = s.start_run(fs::path(), res);  // out_dir "": no files
  ASSERT_TRUE(s.started());
  const json info = json::parse(s.cli.Get("/api/info", s.auth(s.srv.token()))->body);
  EXPECT_NE(info["save_refused"].get<std::string>().find("no results folder"), std::string::npos) << info["save_refused"];
  const auto r = s.post_ok({{"op", "save"}});
  EXPECT_EQ(r->status, 409);
  EXPECT_EQ(error_of(r), "save: the run writes no results folder (-o): there is nowhere to save its state");
  EXPECT_EQ(s.post_ok({{"op", "resume"}})->status, 202);
  sim.join();
  ASSERT_TRUE(res.ok) << res.failure;
  const harness::LiveCounters n = s.srv.counters();
  EXPECT_EQ(n.commands_refused, 1u);
  EXPECT_EQ(n.commands_applied, 1u);  // resume
}

// The names a results folder may hold: checkpoint-<tick>.kckp, nothing like it.
TEST(LiveSave, CheckpointFileNames)
{
  using harness::ResultsDir;
  EXPECT_TRUE(ResultsDir::is_live_checkpoint_name("checkpoint-0.kckp"));
  EXPECT_TRUE(ResultsDir::is_live_checkpoint_name("checkpoint-18446744073709551615.kckp"));
  for (const char* bad : {"checkpoint-.kckp", "checkpoint-1.kckp.tmp", "checkpoint-x.kckp", "checkpoint-1.ckpt",
                          "xcheckpoint-1.kckp", "checkpoint--1.kckp", "checkpoint-1/.kckp"})
    EXPECT_FALSE(ResultsDir::is_live_checkpoint_name(bad)) << bad;
}

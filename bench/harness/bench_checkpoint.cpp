// The cost of a checkpoint of S1 (scenarios/s1_sun_pointing.yaml) at
// t = 300 s (docs/checkpoint.md, "Cost").  Prints microseconds per
// checkpoint and the size in the counters; not a pass/fail test.
//
//   BM_SaveState        the run's state as bytes (save_run_state)
//   BM_SaveFile         the whole checkpoint: state, encoding with the
//                       scenario and checksum, written atomically (temporary
//                       file, fsync, rename, fsync of the folder) in /tmp
//   BM_Encode           the same without the file system (state, encoding, checksum)
//   BM_RestoreState     the state back into a fresh run (its build excluded)
//
// Run: build/host-release/bench/harness/bench_checkpoint --benchmark_repetitions=9
//      --benchmark_report_aggregates_only=true   (quote the medians)
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "harness/core/checkpoint.h"
#include "harness/scenario/scenario.h"

namespace {

const harness::Scenario& s1()
{
  static const harness::Scenario sc = harness::load_scenario(KESTREL_SOURCE_DIR "/scenarios/s1_sun_pointing.yaml");
  return sc;
}

harness::Run& run_at_300s()
{
  static std::unique_ptr<harness::Run> r = [] {
    harness::RunConfig cfg;
    cfg.keep_in_memory = false;  // as `kestrel run` streams
    auto run = std::make_unique<harness::Run>(s1(), std::move(cfg));
    run->step_ticks(30000);
    return run;
  }();
  return *r;
}

void BM_SaveState(benchmark::State& state)
{
  harness::Run& run = run_at_300s();
  size_t bytes = 0;
  for (auto _ : state) {
    const std::vector<uint8_t> s = harness::save_run_state(run);
    bytes = s.size();
    benchmark::DoNotOptimize(s.data());
  }
  state.counters["state_bytes"] = static_cast<double>(bytes);
  // most of it: the rows waiting in the recorder's chunk (8 bytes a value)
  state.counters["rows_waiting"] = static_cast<double>(run.recorder().rows() - run.recorder().sink_rows());
  state.counters["columns"] = static_cast<double>(run.recorder().num_columns());
}
BENCHMARK(BM_SaveState)->Unit(benchmark::kMicrosecond);

void BM_SaveFile(benchmark::State& state)
{
  harness::Run& run = run_at_300s();
  const std::string text = harness::scenario_to_json_text(s1());
  const std::string path = (std::filesystem::temp_directory_path() / "kestrel_bench.ckpt").string();
  for (auto _ : state) harness::save_checkpoint(run, path, text);
  state.counters["file_bytes"] = static_cast<double>(std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_SaveFile)->Unit(benchmark::kMicrosecond);

void BM_Encode(benchmark::State& state)  // BM_SaveFile without the file system
{
  harness::Run& run = run_at_300s();
  const std::string text = harness::scenario_to_json_text(s1());
  harness::CheckpointInfo info;
  info.scenario_text = text;
  for (auto _ : state) {
    const std::vector<uint8_t> b = harness::encode_checkpoint(info, harness::save_run_state(run));
    benchmark::DoNotOptimize(b.data());
  }
}
BENCHMARK(BM_Encode)->Unit(benchmark::kMicrosecond);

void BM_RestoreState(benchmark::State& state)
{
  const std::vector<uint8_t> saved = harness::save_run_state(run_at_300s());
  for (auto _ : state) {
    state.PauseTiming();
    harness::RunConfig cfg;
    cfg.keep_in_memory = false;
    harness::Run fresh(s1(), std::move(cfg));
    state.ResumeTiming();
    harness::restore_run_state(fresh, saved);
  }
}
BENCHMARK(BM_RestoreState)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

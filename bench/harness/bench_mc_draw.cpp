// The per-run planning cost of a Monte Carlo campaign: drawing run k of the
// shipped campaign scenarios/s1_monte_carlo.yaml (5 dispersions, 8 drawn
// keys), k = 0, 1, ... 99 in turn.  Prints microseconds per run; not a
// pass/fail test.
//
//   BM_DrawRun/check:0/bound:1  the draws only (draw_run with check = false),
//                               the dispersions bound once (as a campaign's plan
//                               does: bind_campaign)
//   BM_DrawRun/check:0/bound:0  the same, the dispersions bound for each run
//   BM_DrawRun/check:1/...      the draws and the checks of the drawn scenario
//                               (what a campaign does before each run: reload,
//                               plant and FSW checks)
//
// Run: build/host-release/bench/harness/bench_mc_draw --benchmark_repetitions=9
//      --benchmark_report_aggregates_only=true   (quote the medians)
#include <benchmark/benchmark.h>

#include <cstdint>

#include "harness/scenario/scenario.h"
#include "scenario/mc_draw.h"

namespace {

const harness::Scenario& campaign()
{
  static const harness::Scenario sc = harness::load_scenario(KESTREL_SOURCE_DIR "/scenarios/s1_monte_carlo.yaml");
  return sc;
}

void BM_DrawRun(benchmark::State& state)
{
  const harness::Scenario& sc = campaign();
  const bool check = state.range(0) != 0, bind_once = state.range(1) != 0;
  const harness::McBinding bound = harness::bind_campaign(sc);
  const uint64_t master = sc.monte_carlo->seed, runs = sc.monte_carlo->runs;
  uint64_t k = 0;
  for (auto _ : state) {
    harness::McDraw d = bind_once ? harness::draw_run(sc, bound, master, k, check)
                                  : harness::draw_run(sc, master, k, check);
    benchmark::DoNotOptimize(d.drawn.data());
    k = (k + 1) % runs;
  }
}
BENCHMARK(BM_DrawRun)->ArgNames({"check", "bound"})->ArgsProduct({{0, 1}, {1, 0}})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

// The per-run planning cost of a Monte Carlo campaign: drawing run k of the
// shipped campaign scenarios/s1_monte_carlo.yaml (5 dispersions, 8 drawn
// keys), k = 0, 1, ... 99 in turn.  Prints microseconds per run; not a
// pass/fail test.
//
//   BM_DrawRun/0       the draws only (draw_run with check = false), the
//                      dispersions bound once (as the campaign's plan does)
//   BM_DrawRun/1       the draws and the checks of the drawn scenario (what a
//                      campaign does before each run: reload, plant and FSW checks)
//   BM_BindAndDraw/0   the draws only, the dispersions bound for each run
//   BM_BindAndDraw/1   the same with the checks
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
  const harness::McBinding bound = harness::bind_campaign(sc);
  const bool check = state.range(0) != 0;
  const uint64_t master = sc.monte_carlo->seed, runs = sc.monte_carlo->runs;
  uint64_t k = 0;
  for (auto _ : state) {
    harness::McDraw d = harness::draw_run(sc, bound, master, k, check);
    benchmark::DoNotOptimize(d.drawn.data());
    k = (k + 1) % runs;
  }
}
BENCHMARK(BM_DrawRun)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_BindAndDraw(benchmark::State& state)
{
  const harness::Scenario& sc = campaign();
  const bool check = state.range(0) != 0;
  const uint64_t master = sc.monte_carlo->seed, runs = sc.monte_carlo->runs;
  uint64_t k = 0;
  for (auto _ : state) {
    harness::McDraw d = harness::draw_run(sc, master, k, check);
    benchmark::DoNotOptimize(d.drawn.data());
    k = (k + 1) % runs;
  }
}
BENCHMARK(BM_BindAndDraw)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

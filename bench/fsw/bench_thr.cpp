// Google Benchmark: cost of one update of each thruster module (thr_map in
// both modes, thr_pulse_rem, thr_pulse_schmitt, thr_pulse_round) for 8 and
// 36 thrusters.  Geometry and requests are fixed, representative values;
// the pulsers advance their time stamp every iteration as in flight.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "fsw/thr_map.h"
#include "fsw/thr_pulse_rem.h"
#include "fsw/thr_pulse_round.h"
#include "fsw/thr_pulse_schmitt.h"

// The integrator's assert hook (fsw_status.h): nothing to do in a benchmark.
extern "C" void fsw_assert_failed(const char*, int) {}

namespace {

using R = fsw_real;

// n thrusters on a ring of radius 1 m, alternately at z = +-0.5 m, pushing
// tangentially (alternating sense) with a small axial tilt: full rank.
void ring_geometry(FswThrMapConfig* c, int n, int mode)
{
  std::memset(c, 0, sizeof *c);
  c->control_axes_B[0][0] = 1;
  c->control_axes_B[1][1] = 1;
  c->control_axes_B[2][2] = 1;
  c->num_thr = n;
  c->thr_force_sign = 1;
  c->mode = mode;
  for (int i = 0; i < n; i++) {
    double a = 6.283185307179586 * i / n, s = (i % 2) ? -1.0 : 1.0;
    double g[3] = {-s * std::sin(a), s * std::cos(a), 0.3};
    double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    c->r_thr_B[i][0] = static_cast<R>(std::cos(a));
    c->r_thr_B[i][1] = static_cast<R>(std::sin(a));
    c->r_thr_B[i][2] = static_cast<R>((i / 2) % 2 ? -0.5 : 0.5);
    for (int k = 0; k < 3; k++) c->gt_hat_B[i][k] = static_cast<R>(g[k] / gn);
    c->F_max[i] = 1;
  }
}

void thr_map_bench(benchmark::State& state, int mode)
{
  const int n = static_cast<int>(state.range(0));
  static FswThrMapConfig cfg;  // large structs off the benchmark's stack
  static FswThrMapState st;
  ring_geometry(&cfg, n, mode);
  if (fsw_thr_map_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  FswThrMapIn in{};
  in.Lr_B[0] = static_cast<R>(0.12);
  in.Lr_B[1] = static_cast<R>(-0.05);
  in.Lr_B[2] = static_cast<R>(0.08);
  in.r_CoM_B[0] = static_cast<R>(0.01);
  FswThrMapOut out{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(fsw_thr_map_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
  state.counters["nnls_iter"] = st.nnls_iter;
}
void BM_ThrMapMinNorm(benchmark::State& state) { thr_map_bench(state, FSW_THR_MAP_MIN_NORM); }
void BM_ThrMapNnls(benchmark::State& state) { thr_map_bench(state, FSW_THR_MAP_NNLS); }
BENCHMARK(BM_ThrMapMinNorm)->Arg(8)->Arg(36);
BENCHMARK(BM_ThrMapNnls)->Arg(8)->Arg(36);

// mixed requests: sub-minimum, in range and saturated
template <class In>
void fill_forces(In* in, int n)
{
  for (int i = 0; i < n; i++) in->F[i] = static_cast<R>(0.013 * (i % 7) + 0.11 * (i % 3) + (i % 11 == 0 ? 1.2 : 0.0));
}

void BM_ThrPulseRem(benchmark::State& state)
{
  const int n = static_cast<int>(state.range(0));
  FswThrPulseRemConfig cfg{};
  cfg.common.num_thr = n;
  for (int i = 0; i < n; i++) cfg.common.F_max[i] = 1;
  cfg.common.t_min = static_cast<R>(0.02);
  cfg.common.init_off_pulse_on_time = 2;
  FswThrPulseRemState st{};
  if (fsw_thr_pulse_rem_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  FswThrPulseRemIn in{};
  fill_forces(&in, n);
  FswThrPulseRemOut out{};
  for (auto _ : state) {
    in.t_ns += 100000000ull;
    benchmark::DoNotOptimize(fsw_thr_pulse_rem_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ThrPulseRem)->Arg(8)->Arg(36);

void BM_ThrPulseSchmitt(benchmark::State& state)
{
  const int n = static_cast<int>(state.range(0));
  FswThrPulseSchmittConfig cfg{};
  cfg.common.num_thr = n;
  for (int i = 0; i < n; i++) cfg.common.F_max[i] = 1;
  cfg.common.t_min = static_cast<R>(0.02);
  cfg.level_on = static_cast<R>(0.75);
  cfg.level_off = static_cast<R>(0.25);
  cfg.common.init_off_pulse_on_time = 2;
  FswThrPulseSchmittState st{};
  if (fsw_thr_pulse_schmitt_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  FswThrPulseSchmittIn in{};
  fill_forces(&in, n);
  FswThrPulseSchmittOut out{};
  for (auto _ : state) {
    in.t_ns += 100000000ull;
    benchmark::DoNotOptimize(fsw_thr_pulse_schmitt_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ThrPulseSchmitt)->Arg(8)->Arg(36);

void BM_ThrPulseRound(benchmark::State& state)
{
  const int n = static_cast<int>(state.range(0));
  FswThrPulseRoundConfig cfg{};
  cfg.num_thr = n;
  for (int i = 0; i < n; i++) cfg.F_max[i] = 1;
  cfg.period = 1;
  cfg.resolution = static_cast<R>(0.01);
  cfg.carry_residual = 1;
  FswThrPulseRoundState st{};
  if (fsw_thr_pulse_round_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  FswThrPulseRoundIn in{};
  fill_forces(&in, n);
  FswThrPulseRoundOut out{};
  for (auto _ : state) {
    in.t_ns += 1000000000ull;
    benchmark::DoNotOptimize(fsw_thr_pulse_round_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ThrPulseRound)->Arg(8)->Arg(36);

}  // namespace

BENCHMARK_MAIN();

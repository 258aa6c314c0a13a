// Cost of one update of each reaction-wheel module for 4 and 36 wheels
// (host only; prints figures, not a pass/fail test).  Geometries: the
// 4-wheel pyramid of the docs and 36 deterministic pseudo-random axes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <memory>

#include "fsw/rw_map.h"
#include "fsw/rw_null.h"
#include "fsw/rw_null_regen.h"
#include "fsw/rw_sat.h"
#include "fsw/rw_speed_filter.h"
#include "fsw/rw_volt.h"
#include "fsw/trq_lpf.h"

extern "C" void fsw_assert_failed(const char*, int) {}

namespace {

// n unit axes: the pyramid for n = 4, a golden-angle spiral otherwise.
void axes(fsw_real g[][3], int n)
{
  for (int i = 0; i < n; i++) {
    double x, y, z;
    if (n == 4) {
      const double s = 1.0 / std::sqrt(3.0);
      x = (i == 0 || i == 3) ? s : -s;
      y = (i < 2) ? s : -s;
      z = s;
    } else {
      z = 1.0 - (2.0 * i + 1.0) / n;
      const double r = std::sqrt(1.0 - z * z), a = 2.399963229728653 * i;
      x = r * std::cos(a);
      y = r * std::sin(a);
    }
    g[i][0] = static_cast<fsw_real>(x);
    g[i][1] = static_cast<fsw_real>(y);
    g[i][2] = static_cast<fsw_real>(z);
  }
}

template <class T>
std::unique_ptr<T> z()
{
  return std::unique_ptr<T>(new T());
}

void speeds(fsw_real* w, int n)
{
  for (int i = 0; i < n; i++) w[i] = static_cast<fsw_real>(100.0 + 37.0 * i - 9.0 * (i % 5));
}

void BM_rw_map(benchmark::State& s, int mode)
{
  const int n = static_cast<int>(s.range(0));
  auto c = z<FswRwMapConfig>();
  auto st = z<FswRwMapState>();
  auto in = z<FswRwMapIn>();
  auto out = z<FswRwMapOut>();
  c->num_rw = n;
  axes(c->gs_hat_B, n);
  c->num_axes = 3;
  for (int j = 0; j < 3; j++) c->ctrl_axes_B[j][j] = FSW_R(1.0);
  c->mode = mode;
  c->eps_P = FSW_RW_MAP_EPS_P_DEFAULT;
  fsw_rw_map_init(st.get(), c.get());
  speeds(in->Omega, n);
  in->Lr_B[0] = FSW_R(0.01);
  in->Lr_B[1] = FSW_R(-0.02);
  in->Lr_B[2] = FSW_R(0.03);
  for (auto _ : s) {
    benchmark::DoNotOptimize(fsw_rw_map_update(st.get(), c.get(), in.get(), out.get()));
    benchmark::ClobberMemory();
  }
}
void BM_rw_map_min_norm(benchmark::State& s) { BM_rw_map(s, FSW_RW_MAP_MIN_NORM); }
void BM_rw_map_power(benchmark::State& s) { BM_rw_map(s, FSW_RW_MAP_POWER); }

void BM_rw_null(benchmark::State& s)
{
  const int n = static_cast<int>(s.range(0));
  auto c = z<FswRwNullConfig>();
  auto st = z<FswRwNullState>();
  auto in = z<FswRwNullIn>();
  auto out = z<FswRwNullOut>();
  c->num_rw = n;
  axes(c->gs_hat_B, n);
  c->k_null = FSW_R(1e-3);
  c->scale_to_fit = 1;
  for (int i = 0; i < n; i++) c->u_max[i] = FSW_R(0.2);
  fsw_rw_null_init(st.get(), c.get());
  speeds(in->Omega, n);
  for (auto _ : s) {
    benchmark::DoNotOptimize(fsw_rw_null_update(st.get(), c.get(), in.get(), out.get()));
    benchmark::ClobberMemory();
  }
}

// Worst case of rw_null: the mask changes on every call (projector recomputed).
void BM_rw_null_mask_change(benchmark::State& s)
{
  const int n = static_cast<int>(s.range(0));
  auto c = z<FswRwNullConfig>();
  auto st = z<FswRwNullState>();
  auto in = z<FswRwNullIn>();
  auto out = z<FswRwNullOut>();
  c->num_rw = n;
  axes(c->gs_hat_B, n);
  c->k_null = FSW_R(1e-3);
  fsw_rw_null_init(st.get(), c.get());
  speeds(in->Omega, n);
  for (auto _ : s) {
    in->avail[0] = static_cast<uint8_t>(1 - in->avail[0]);
    benchmark::DoNotOptimize(fsw_rw_null_update(st.get(), c.get(), in.get(), out.get()));
    benchmark::ClobberMemory();
  }
}

void BM_rw_null_regen(benchmark::State& s, int mode)
{
  const int n = static_cast<int>(s.range(0));
  auto c = z<FswRwNullRegenConfig>();
  auto st = z<FswRwNullRegenState>();
  auto in = z<FswRwNullRegenIn>();
  auto out = z<FswRwNullRegenOut>();
  c->num_rw = n;
  axes(c->gs_hat_B, n);
  c->mode = mode;
  c->k_P = FSW_R(1e-4);
  for (int i = 0; i < n; i++) c->u_max[i] = FSW_R(0.2);
  fsw_rw_null_regen_init(st.get(), c.get());
  speeds(in->Omega, n);
  if (mode == FSW_RW_REGEN_OPTIMUM)  // nullity 1: four available wheels
    for (int i = 4; i < n; i++) in->avail[i] = FSW_UNAVAILABLE;
  for (auto _ : s) {
    benchmark::DoNotOptimize(fsw_rw_null_regen_update(st.get(), c.get(), in.get(), out.get()));
    benchmark::ClobberMemory();
  }
}
void BM_rw_null_regen_gradient(benchmark::State& s) { BM_rw_null_regen(s, FSW_RW_REGEN_GRADIENT); }
void BM_rw_null_regen_optimum(benchmark::State& s) { BM_rw_null_regen(s, FSW_RW_REGEN_OPTIMUM); }

void BM_trq_lpf(benchmark::State& s)
{
  FswTrqLpfConfig c{FSW_R(0.1), FSW_R(2.0)};
  FswTrqLpfState st{};
  FswTrqLpfIn in{{FSW_R(0.01), FSW_R(0.02), FSW_R(0.03)}, 0u};
  FswTrqLpfOut out{};
  fsw_trq_lpf_init(&st, &c);
  for (auto _ : s) {
    in.t_ns += 100000000u;
    benchmark::DoNotOptimize(fsw_trq_lpf_update(&st, &c, &in, &out));
    benchmark::ClobberMemory();
  }
}

void BM_rw_sat(benchmark::State& s)
{
  const int n = static_cast<int>(s.range(0));
  auto c = z<FswRwSatConfig>();
  auto st = z<FswRwSatState>();
  auto in = z<FswRwSatIn>();
  auto out = z<FswRwSatOut>();
  c->num_rw = n;
  for (int i = 0; i < n; i++) {
    c->u_max[i] = FSW_R(0.1);
    in->u_s[i] = static_cast<fsw_real>(0.05 * (i % 5));
  }
  fsw_rw_sat_init(st.get(), c.get());
  for (auto _ : s) {
    benchmark::DoNotOptimize(fsw_rw_sat_update(st.get(), c.get(), in.get(), out.get()));
    benchmark::ClobberMemory();
  }
}

void BM_rw_volt(benchmark::State& s)
{
  const int n = static_cast<int>(s.range(0));
  auto c = z<FswRwVoltConfig>();
  auto st = z<FswRwVoltState>();
  auto in = z<FswRwVoltIn>();
  auto out = z<FswRwVoltOut>();
  c->num_rw = n;
  c->V_min = FSW_R(0.5);
  c->V_max = FSW_R(10.0);
  c->K_V = FSW_R(0.5);
  c->gate_rate = 1;
  for (int i = 0; i < n; i++) {
    c->u_max[i] = FSW_R(0.2);
    c->J_s[i] = FSW_R(0.01);
    c->Omega_dot_max[i] = FSW_R(50.0);
    in->u_s[i] = static_cast<fsw_real>(0.01 * (i % 7) - 0.03);
  }
  fsw_rw_volt_init(st.get(), c.get());
  speeds(in->Omega, n);
  in->has_Omega = 1;
  for (auto _ : s) {
    in->t_ns += 100000000u;
    benchmark::DoNotOptimize(fsw_rw_volt_update(st.get(), c.get(), in.get(), out.get()));
    benchmark::ClobberMemory();
  }
}

void BM_rw_speed_filter(benchmark::State& s)
{
  const int n = static_cast<int>(s.range(0));
  auto c = z<FswRwSpeedFilterConfig>();
  auto st = z<FswRwSpeedFilterState>();
  auto in = z<FswRwSpeedFilterIn>();
  auto out = z<FswRwSpeedFilterOut>();
  c->num_rw = n;
  c->k_reject = 3;
  c->n_recover = 3;
  for (int i = 0; i < n; i++) {
    c->u_max[i] = FSW_R(0.2);
    c->J_s[i] = FSW_R(0.02);
    c->noise[i] = FSW_R(0.5);
  }
  fsw_rw_speed_filter_init(st.get(), c.get());
  speeds(in->Omega_meas, n);
  for (auto _ : s) {
    in->t_ns += 100000000u;
    benchmark::DoNotOptimize(fsw_rw_speed_filter_update(st.get(), c.get(), in.get(), out.get()));
    benchmark::ClobberMemory();
  }
}

}  // namespace

BENCHMARK(BM_rw_map_min_norm)->Arg(4)->Arg(36);
BENCHMARK(BM_rw_map_power)->Arg(4)->Arg(36);
BENCHMARK(BM_rw_null)->Arg(4)->Arg(36);
BENCHMARK(BM_rw_null_mask_change)->Arg(4)->Arg(36);
BENCHMARK(BM_rw_null_regen_gradient)->Arg(4)->Arg(36);
BENCHMARK(BM_rw_null_regen_optimum)->Arg(4)->Arg(36);
BENCHMARK(BM_trq_lpf);
BENCHMARK(BM_rw_sat)->Arg(4)->Arg(36);
BENCHMARK(BM_rw_volt)->Arg(4)->Arg(36);
BENCHMARK(BM_rw_speed_filter)->Arg(4)->Arg(36);
BENCHMARK_MAIN();

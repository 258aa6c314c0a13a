// Cost of one fsw_acs cycle: 4-wheel configuration (sun-safe and inertial,
// with and without null motion/filter/voltages) and 8-thruster
// configuration (remainder and Schmitt pulsing).  Inputs come from the
// fixture plant so every stage does real work.
#include <benchmark/benchmark.h>

#include "acs_fixture.hpp"

extern "C" void fsw_assert_failed(const char*, int) {}

namespace {

FswAcsConfig g_cfg;
FswAcsState g_st;

void run(benchmark::State& state, int which)
{
  if (which < 3) {
    acsfix::wheel_config(g_cfg);
    if (which >= 1) g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
    if (which == 2) g_cfg.use_null = g_cfg.use_lpf = g_cfg.use_volt = 1;
  } else {
    acsfix::thruster_config(g_cfg, which == 3 ? FSW_ACS_PULSE_REMAINDER : FSW_ACS_PULSE_SCHMITT);
  }
  fsw_acs_init(&g_st, &g_cfg, nullptr);
  acsfix::Plant p;
  p.omega[0] = 0.003;
  p.sigma[1] = 0.05;
  p.Omega[2] = 30;
  FswAcsSensorMsg m;
  FswAcsActuatorMsg a;
  FswAcsHealthMsg h;
  uint64_t k = 0;
  p.sense(0, m);
  for (auto _ : state) {
    m.t_ns = (k++) * acsfix::kPeriodNs;
    benchmark::DoNotOptimize(fsw_acs_cycle(&g_st, &g_cfg, &m, nullptr, &a, &h));
    benchmark::ClobberMemory();
  }
}

void BM_acs_4rw_sunsafe(benchmark::State& s) { run(s, 0); }
void BM_acs_4rw_inertial(benchmark::State& s) { run(s, 1); }
void BM_acs_4rw_inertial_null_lpf_volt(benchmark::State& s) { run(s, 2); }
void BM_acs_8thr_remainder(benchmark::State& s) { run(s, 3); }
void BM_acs_8thr_schmitt(benchmark::State& s) { run(s, 4); }

BENCHMARK(BM_acs_4rw_sunsafe);
BENCHMARK(BM_acs_4rw_inertial);
BENCHMARK(BM_acs_4rw_inertial_null_lpf_volt);
BENCHMARK(BM_acs_8thr_remainder);
BENCHMARK(BM_acs_8thr_schmitt);

}  // namespace

BENCHMARK_MAIN();

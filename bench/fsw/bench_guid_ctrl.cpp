// Google Benchmark: cost of one update of each guidance / estimation /
// control module (guid_inertial, guid_sunsafe, att_track, css_sun, mrp_fb).
// Inputs are fixed, representative values; mrp_fb advances its time stamp
// every iteration so the integral branch runs as in flight.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include "fsw/att_track.h"
#include "fsw/css_sun.h"
#include "fsw/guid_inertial.h"
#include "fsw/guid_sunsafe.h"
#include "fsw/mrp_fb.h"

// The integrator's assert hook (fsw_status.h): nothing to do in a benchmark.
extern "C" void fsw_assert_failed(const char*, int) {}

namespace {

void set3(fsw_real v[3], double x, double y, double z)
{
  v[0] = static_cast<fsw_real>(x);
  v[1] = static_cast<fsw_real>(y);
  v[2] = static_cast<fsw_real>(z);
}

void BM_GuidInertial(benchmark::State& state)
{
  FswGuidInertialConfig cfg{};
  set3(cfg.sigma_R0N, 0.1, 0.2, -0.3);
  FswGuidInertialState st{};
  if (fsw_guid_inertial_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  FswGuidInertialOut out{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(fsw_guid_inertial_update(&st, &cfg, &out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_GuidInertial);

void BM_GuidSunsafe(benchmark::State& state)
{
  FswGuidSunsafeConfig cfg{};
  set3(cfg.s_cmd_B, 1.0, 0.0, 0.0);
  cfg.min_unit_mag = static_cast<fsw_real>(0.1);
  cfg.small_angle = static_cast<fsw_real>(1e-4);
  cfg.sun_axis_spin_rate = static_cast<fsw_real>(0.01);
  FswGuidSunsafeState st{};
  if (fsw_guid_sunsafe_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  FswGuidSunsafeIn in{};
  set3(in.sun_B, 0.3, -0.5, 0.8);
  set3(in.omega_BN_B, 0.01, 0.02, -0.01);
  FswGuidSunsafeOut out{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(fsw_guid_sunsafe_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_GuidSunsafe);

void BM_AttTrack(benchmark::State& state)
{
  FswAttTrackConfig cfg{};
  set3(cfg.sigma_R0R, 0.01, 0.0, 0.0);
  FswAttTrackState st{};
  if (fsw_att_track_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  FswAttTrackIn in{};
  set3(in.sigma_BN, 0.3, -0.2, 0.1);
  set3(in.omega_BN_B, 0.01, -0.02, 0.03);
  set3(in.ref.sigma_RN, -0.1, 0.4, 0.2);
  set3(in.ref.omega_RN_N, 0.001, 0.002, -0.003);
  set3(in.ref.omega_dot_RN_N, 1e-5, 0.0, 2e-5);
  FswAttTrackOut out{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(fsw_att_track_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_AttTrack);

// 14 sensors (6 cube faces + 8 corners), Sun lighting 7 of them: WLS path.
void BM_CssSun(benchmark::State& state)
{
  static FswCssSunConfig cfg{};  // large structs off the benchmark stack
  cfg.num_css = 14;
  const double f[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  int k = 0;
  for (int i = 0; i < 6; i++, k++) set3(cfg.n_hat_B[k], f[i][0], f[i][1], f[i][2]);
  const double r3 = 1.0 / std::sqrt(3.0);
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      for (int sz = -1; sz <= 1; sz += 2, k++) set3(cfg.n_hat_B[k], sx * r3, sy * r3, sz * r3);
  for (int i = 0; i < 14; i++) cfg.scale[i] = static_cast<fsw_real>(1.0);
  cfg.lit_threshold = static_cast<fsw_real>(0.1);
  FswCssSunState st{};
  if (fsw_css_sun_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  static FswCssSunIn in{};
  const double s[3] = {0.48, 0.6, 0.64};
  for (int i = 0; i < 14; i++) {
    const double c = cfg.n_hat_B[i][0] * s[0] + cfg.n_hat_B[i][1] * s[1] + cfg.n_hat_B[i][2] * s[2];
    in.reading[i] = static_cast<fsw_real>(c > 0.0 ? c : 0.0);
  }
  FswCssSunOut out{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(fsw_css_sun_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
  if (out.mode != FSW_CSS_SUN_WLS) state.SkipWithError("expected the WLS path");
}
BENCHMARK(BM_CssSun);

// Four pyramid wheels, integral on, law 0.
void BM_MrpFb(benchmark::State& state)
{
  static FswMrpFbConfig cfg{};
  cfg.K = static_cast<fsw_real>(0.15);
  cfg.P = static_cast<fsw_real>(150.0);
  cfg.K_i = static_cast<fsw_real>(0.01);
  cfg.integral_limit = static_cast<fsw_real>(20.0);
  set3(cfg.known_torque_B, 1.0, 1.0, 1.0);
  set3(cfg.I_B[0], 1000, 0, 0);
  set3(cfg.I_B[1], 0, 800, 0);
  set3(cfg.I_B[2], 0, 0, 800);
  cfg.num_rw = 4;
  const double c = 1.0 / std::sqrt(3.0);
  const double sx[4] = {1, -1, -1, 1}, sy[4] = {1, 1, -1, -1};
  for (int i = 0; i < 4; i++) {
    set3(cfg.gs_hat_B[i], sx[i] * c, sy[i] * c, c);
    cfg.J_s[i] = static_cast<fsw_real>(0.1);
  }
  FswMrpFbState st{};
  if (fsw_mrp_fb_init(&st, &cfg) != FSW_OK) state.SkipWithError("init");
  static FswMrpFbIn in{};
  set3(in.guid.sigma_BR, 0.3, -0.5, 0.7);
  set3(in.guid.omega_BR_B, 0.01, -0.02, 0.015);
  set3(in.guid.omega_RN_B, -0.02, -0.01, 0.005);
  set3(in.guid.omega_dot_RN_B, 2e-4, 3e-4, 1e-4);
  for (int i = 0; i < 4; i++) in.Omega[i] = static_cast<fsw_real>(10.0 * (i + 1));
  FswMrpFbOut out{};
  uint64_t t = 0;
  for (auto _ : state) {
    in.t_ns = t;
    t += 100000000ull;  // 10 Hz
    benchmark::DoNotOptimize(fsw_mrp_fb_update(&st, &cfg, &in, &out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_MrpFb);

}  // namespace

BENCHMARK_MAIN();

// fsw_thr_pulse_round_update: thruster count, limits, period, resolution,
// t_min and carry_residual; a sequence of force commands and time stamps
// (any order when stateless).  OK/W_SAT: 0 <= t_on <= period, non-zero
// on-times at least t_min, residuals finite within [-T, T], nothing beyond
// num_thr; errors: all off and no state change.
#include "fsw/thr_pulse_round.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswThrPulseRoundConfig cfg{};
  cfg.carry_residual = in.flag(in.u8() % 2);
  cfg.num_thr = in.count(8, FSW_MAX_THR);
  const int n = fuzz_clamp_count(cfg.num_thr, FSW_MAX_THR);
  in.reals(cfg.F_max, n, nullptr, 1.0);
  cfg.period = static_cast<fsw_real>(in.real(0.1));
  cfg.resolution = static_cast<fsw_real>(in.real(0.01));
  cfg.t_min = static_cast<fsw_real>(in.real(0.02));
  fuzz_trace("period resolution t_min", &cfg.period, 3);
  static FswThrPulseRoundState st;
  FswThrPulseRoundIn x{};
  FswThrPulseRoundOut out;
  const auto step = [&]() {
    return fuzz_call("thr_pulse_round", st, out, {FSW_OK, FSW_W_SAT, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_thr_pulse_round_update(&st, &cfg, &x, &out); },
                     fuzz_mask_common_health<FswThrPulseRoundState>,
                     [](const FswThrPulseRoundOut &o, int) { return fuzz_nonzero_from(o.t_on, 0, FSW_MAX_THR) < 0; });
  };
  if (!fuzz_init("thr_pulse_round", st, cfg, fsw_thr_pulse_round_check, fsw_thr_pulse_round_init,
                 [](const FswThrPulseRoundState &s) { return s.common.ready; }, step))
    return 0;
  uint64_t t = 0;
  const uint64_t period = std::isfinite(cfg.period) && cfg.period > 0 && cfg.period < 1e3
                              ? static_cast<uint64_t>(cfg.period * 1e9) : 100000000ull;
  for (int k = 0, steps = in.steps(8, 32); k < steps; k++) {
    if (in.op()) fsw_thr_pulse_round_reset(&st);
    for (int i = 0; i < n; i++) x.F[i] = static_cast<fsw_real>(in.real(0.1 * (1 + (i + 3 * k) % 11) * cfg.F_max[i]));
    x.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, period);
    fuzz_trace("F", x.F, n);
    if (step() < 0) continue;
    fuzz_check_on_times("thr_pulse_round", out.t_on, n, 0, 0.0, cfg.period, cfg.period, cfg.t_min, false);
    for (int i = 0; i < n; i++)
      FUZZ_REQUIRE(std::isfinite(st.resid[i]) && std::fabs(st.resid[i]) <= cfg.period,
                   "thr_pulse_round: residual[%d] = %.17g", i, st.resid[i]);
  }
  return 0;
}

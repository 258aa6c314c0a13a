// fsw_thr_pulse_rem_update: thruster count, limits, t_min, base thrust
// state and first-call on-time; a sequence of force commands and time
// stamps.  OK/W_SAT: on the first call after reset t_on = b * init on-time,
// then 0 <= t_on <= 1.1 dt, non-zero on-times at least t_min unless
// saturated, finite remainders, nothing beyond num_thr; errors: all off and
// no state change.
#include "fsw/thr_pulse_rem.h"
#include "fuzz_pulse.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswThrPulseRemConfig cfg{};
  const FswThrPulseCommon &c = cfg.common;
  const int n = fuzz_pulse_common(in, cfg.common);
  const uint64_t period = fuzz_period_ns(in.u8());
  static FswThrPulseRemState st;
  FswThrPulseRemIn x{};
  FswThrPulseRemOut out;
  const auto step = [&]() {
    return fuzz_call("thr_pulse_rem", st, out, {FSW_OK, FSW_W_SAT, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_thr_pulse_rem_update(&st, &cfg, &x, &out); },
                     fuzz_mask_common_health<FswThrPulseRemState>,
                     [](const FswThrPulseRemOut &o, int) { return fuzz_nonzero_from(o.t_on, 0, FSW_MAX_THR) < 0; });
  };
  if (!fuzz_init("thr_pulse_rem", st, cfg, fsw_thr_pulse_rem_check, fsw_thr_pulse_rem_init,
                 [](const FswThrPulseRemState &s) { return s.common.ready; }, step))
    return 0;
  uint64_t t = 0;
  for (int k = 0, steps = in.steps(8, 32); k < steps; k++) {
    if (in.op()) fsw_thr_pulse_rem_reset(&st);
    int first;
    double dt;
    fuzz_pulse_input(in, c, st.common.clock, k, 0.01, period, &t, x.F, &first, &dt);
    x.t_ns = t;
    if (step() < 0) continue;
    fuzz_check_on_times("thr_pulse_rem", out.t_on, n, first, c.base_thrust_state * c.init_off_pulse_on_time, dt,
                        1.1 * dt, c.t_min, true);
    FUZZ_REQUIRE(fuzz_finite(st.rem, FSW_MAX_THR), "thr_pulse_rem: non-finite remainder after an accepted call");
  }
  return 0;
}

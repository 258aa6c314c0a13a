// fsw_thr_pulse_schmitt_update: thruster count, limits, t_min, levels, base
// thrust state and first-call on-time; a sequence of force commands and
// time stamps.  OK/W_SAT: first call after reset t_on = b * init on-time,
// then 0 <= t_on <= 1.1 dt, non-zero on-times at least min(t_min, dt)
// unless saturated, memory 0/1, nothing beyond num_thr; errors: all off and
// no state change.
#include "fsw/thr_pulse_schmitt.h"
#include "fuzz_pulse.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswThrPulseSchmittConfig cfg{};
  const FswThrPulseCommon &c = cfg.common;
  const int n = fuzz_pulse_common(in, cfg.common);
  cfg.level_on = static_cast<fsw_real>(in.real(0.75));
  cfg.level_off = static_cast<fsw_real>(in.real(0.25));
  const uint64_t period = fuzz_period_ns(in.u8());
  fuzz_trace("level_on level_off", &cfg.level_on, 2);
  static FswThrPulseSchmittState st;
  FswThrPulseSchmittIn x{};
  FswThrPulseSchmittOut out;
  const auto is_off = [](const FswThrPulseSchmittOut &o, int) { return fuzz_nonzero_from(o.t_on, 0, FSW_MAX_THR) < 0; };
  const auto step = [&]() {
    return fuzz_call("thr_pulse_schmitt", st, out, {FSW_OK, FSW_W_SAT, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_thr_pulse_schmitt_update(&st, &cfg, &x, &out); },
                     fuzz_mask_common_health<FswThrPulseSchmittState>, is_off);
  };
  if (!fuzz_init("thr_pulse_schmitt", st, cfg, fsw_thr_pulse_schmitt_check, fsw_thr_pulse_schmitt_init,
                 [](const FswThrPulseSchmittState &s) { return s.common.ready; }, step))
    return 0;
  uint64_t t = 0;
  for (int k = 0, steps = in.steps(8, 32); k < steps; k++) {
    if (in.op()) fsw_thr_pulse_schmitt_reset(&st);
    int first;
    double dt;
    fuzz_pulse_input(in, c, st.common.clock, 2 * k, 0.15, period, &t, x.F, &first, &dt);
    x.t_ns = t;
    if (step() < 0) continue;
    // the minimum pulse is min(t_min, period) (a period shorter than t_min cannot hold a t_min pulse)
    fuzz_check_on_times("thr_pulse_schmitt", out.t_on, n, first, c.base_thrust_state * c.init_off_pulse_on_time,
                        dt, 1.1 * dt, c.t_min < dt ? c.t_min : dt, true);
    for (int i = 0; i < FSW_MAX_THR; i++)
      FUZZ_REQUIRE(st.last_on[i] <= 1 && (i < n || st.last_on[i] == 0), "thr_pulse_schmitt: memory[%d] = %d", i,
                   st.last_on[i]);
  }
  return 0;
}

// Shared part of the remainder and Schmitt pulser harnesses: the decoded
// common configuration (FswThrPulseCommon) and one call's force commands and
// time stamp with the period the pulser will measure.
#ifndef KESTREL_FUZZ_FSW_PULSE_H
#define KESTREL_FUZZ_FSW_PULSE_H

#include "fsw/thr_pulse_common.h"
#include "fuzz_input.h"

// Decode the common config (nominal: 8 thrusters of 1 N, t_min 20 ms,
// first-call on-time 2 s, base thrust state from the variant byte).
// Returns the number of thrusters to fill.
inline int fuzz_pulse_common(FuzzIn &in, FswThrPulseCommon &c)
{
  c.base_thrust_state = in.flag(in.u8() % 2);
  c.num_thr = in.count(8, FSW_MAX_THR);
  const int n = fuzz_clamp_count(c.num_thr, FSW_MAX_THR);
  in.reals(c.F_max, n, nullptr, 1.0);
  c.t_min = static_cast<fsw_real>(in.real(0.02));
  c.init_off_pulse_on_time = static_cast<fsw_real>(in.real(2.0));
  fuzz_trace("F_max", c.F_max, n);
  fuzz_trace("t_min", &c.t_min, 1);
  return n;
}

// One call's input: forces near level * F_max (negative when off-pulsing)
// and the next time stamp.  Sets *first (first call after reset) and *dt
// (the period the pulser measures, 0 on the first call) from the clock.
inline void fuzz_pulse_input(FuzzIn &in, const FswThrPulseCommon &c, const FswClock &clk, int k, double level,
                             uint64_t period, uint64_t *t, fsw_real *F, int *first, double *dt)
{
  const int n = fuzz_clamp_count(c.num_thr, FSW_MAX_THR);
  const double sgn = c.base_thrust_state ? -1.0 : 1.0;
  for (int i = 0; i < n; i++) F[i] = static_cast<fsw_real>(in.real(sgn * level * (1 + (i + k) % 9) * c.F_max[i]));
  *t = (k == 0) ? in.next_time(0, 0) : in.next_time(*t, period);
  *first = !clk.has_prev;
  *dt = *first ? 0.0 : static_cast<double>(*t - clk.t_prev_ns) * 1e-9;
  fuzz_trace("F", F, n);
  fuzz_trace_int("t_ns", static_cast<long long>(*t));
}

#endif  // KESTREL_FUZZ_FSW_PULSE_H

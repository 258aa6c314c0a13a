/* thr_pulse_common: shared pieces of the thruster pulsing modules. */
#include "thr_pulse_common.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

FswStatus fsw_thr_pulse_check_common(int num_thr, fsw_real t_min, int t_min_positive,
                                 const fsw_real *F_max)
{
  int i;
  if (num_thr > FSW_MAX_THR) return FSW_E_CAPACITY;
  if (num_thr < 1) return FSW_E_CONFIG;
  if (!isfinite(t_min) || t_min < FSW_R(0.0)) return FSW_E_CONFIG;
  if (t_min_positive && !(t_min > FSW_R(0.0))) return FSW_E_CONFIG;
  for (i = 0; i < num_thr; i++)
    if (!isfinite(F_max[i]) || !(F_max[i] > FSW_R(0.0))) return FSW_E_CONFIG;
  return FSW_OK;
}

FswStatus fsw_thr_pulse_check_base(int base_thrust_state, fsw_real init_off_pulse_on_time)
{
  if (base_thrust_state != THR_PULSE_ON_PULSING && base_thrust_state != THR_PULSE_OFF_PULSING)
    return FSW_E_CONFIG;
  if (!isfinite(init_off_pulse_on_time) || init_off_pulse_on_time < FSW_R(0.0))
    return FSW_E_CONFIG;
  return FSW_OK;
}

FswStatus fsw_thr_pulse_timing(int has_prev, uint64_t t_prev_ns, uint64_t t_ns,
                           ThrPulseTiming *timing, fsw_real *dt)
{
  *dt = FSW_R(0.0);
  if (!has_prev) {
    *timing = THR_PULSE_FIRST;
    return FSW_OK;
  }
  *timing = THR_PULSE_STEP;
  if (t_ns <= t_prev_ns) return FSW_E_TIME;
  /* fsw-algorithms.md 0.3: dt = (double)(t_ns - t_prev_ns) * 1e-9 */
  *dt = (fsw_real)(t_ns - t_prev_ns) * FSW_R(1e-9);
  return FSW_OK;
}

FswStatus fsw_thr_pulse_begin(int ready, FswHealth *health, const fsw_real *F, int n, int use_time,
                              int has_prev, uint64_t t_prev_ns, uint64_t t_ns,
                              ThrPulseTiming *timing, fsw_real *dt)
{
  FswStatus s = FSW_OK;
  *timing = THR_PULSE_FIRST;
  *dt = FSW_R(0.0);
  if (!ready) return fsw_health_record(health, FSW_E_NOT_INIT);
  if (!fsw_vn_is_finite(F, n)) return fsw_health_record(health, FSW_E_BAD_INPUT);
  if (use_time) s = fsw_thr_pulse_timing(has_prev, t_prev_ns, t_ns, timing, dt);
  if (s != FSW_OK) return fsw_health_record(health, s);
  return FSW_OK;
}

void fsw_thr_pulse_safe_output(fsw_real t_on[FSW_MAX_THR]) { fsw_vn_zero(t_on, FSW_MAX_THR); }

void fsw_thr_pulse_first_output(fsw_real t_on[FSW_MAX_THR], int n, int base_thrust_state,
                            fsw_real init_off_pulse_on_time)
{
  int i;
  for (i = 0; i < n; i++) t_on[i] = (fsw_real)base_thrust_state * init_off_pulse_on_time;
}

fsw_real fsw_thr_pulse_on_time(fsw_real F, fsw_real F_max, int base_thrust_state, fsw_real dt)
{
  fsw_real f = F;
  if (base_thrust_state == THR_PULSE_OFF_PULSING) f = f + F_max;
  if (f < FSW_R(0.0)) f = FSW_R(0.0);
  return (f / F_max) * dt;
}

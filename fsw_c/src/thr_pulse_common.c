/* thr_pulse_common: shared pieces of the thruster pulsing modules. */
#include "thr_pulse_internal.h"

#include <stddef.h>

#include "fsw/fsw_clock.h"
#include "fsw/fsw_vec.h"

FswStatus fsw_thr_pulse_check_thrusters(int num_thr, const fsw_real *F_max)
{
  int i;
  if (num_thr > FSW_MAX_THR) { return FSW_E_CAPACITY; }
  if (num_thr < 1) { return FSW_E_CONFIG; }
  for (i = 0; i < num_thr; i++) {
    if (!isfinite(F_max[i]) || !(F_max[i] > FSW_R(0.0))) { return FSW_E_CONFIG; } }
  return FSW_OK;
}

FswStatus fsw_thr_pulse_check_common(const FswThrPulseCommon *c)
{
  const FswStatus s = fsw_thr_pulse_check_thrusters(c->num_thr, c->F_max);
  if (s != FSW_OK) { return s; }
  if (!isfinite(c->t_min) || !(c->t_min > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (c->base_thrust_state != THR_PULSE_ON_PULSING && c->base_thrust_state != THR_PULSE_OFF_PULSING) {
    return FSW_E_CONFIG; }
  if (!isfinite(c->init_off_pulse_on_time) || c->init_off_pulse_on_time < FSW_R(0.0)) {
    return FSW_E_CONFIG; }
  return FSW_OK;
}

void fsw_thr_pulse_init_common(FswThrPulseCommonState *cs)
{
  cs->ready = 0;
  fsw_health_clear(&cs->health);
  fsw_clock_reset(&cs->clock);
}

FswStatus fsw_thr_pulse_begin(FswThrPulseCommonState *cs, const fsw_real *F, int n, int use_time,
                              uint64_t t_ns, fsw_real *dt)
{
  FswStatus s = FSW_OK;
  *dt = FSW_R(0.0);
  if (!cs->ready) { return fsw_health_record(&cs->health, FSW_E_NOT_INIT); }
  if (!fsw_vn_is_finite(F, n)) { return fsw_health_record(&cs->health, FSW_E_BAD_INPUT); }
  if (use_time) { s = fsw_clock_dt(&cs->clock, t_ns, dt); }
  if (s != FSW_OK) { return fsw_health_record(&cs->health, s); }
  return FSW_OK;
}

FswStatus fsw_thr_pulse_end(FswThrPulseCommonState *cs, int use_time, uint64_t t_ns, int saturated)
{
  if (use_time) { fsw_clock_commit(&cs->clock, t_ns); }
  return fsw_health_record(&cs->health, saturated ? FSW_W_SAT : FSW_OK);
}

void fsw_thr_pulse_safe_output(fsw_real t_on[FSW_MAX_THR]) { fsw_vn_zero(t_on, FSW_MAX_THR); }

void fsw_thr_pulse_first_output(fsw_real t_on[FSW_MAX_THR], const FswThrPulseCommon *c)
{
  int i;
  for (i = 0; i < c->num_thr; i++) {
    t_on[i] = (fsw_real)c->base_thrust_state * c->init_off_pulse_on_time; }
}

fsw_real fsw_thr_pulse_on_time(fsw_real F, fsw_real F_max, int base_thrust_state, fsw_real dt)
{
  fsw_real f = F;
  if (base_thrust_state == THR_PULSE_OFF_PULSING) { f = f + F_max; }
  if (f < FSW_R(0.0)) { f = FSW_R(0.0); }
  return (f / F_max) * dt;
}

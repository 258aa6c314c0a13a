/* thr_pulse_rem: remainder-tracking thruster pulsing, fsw-algorithms.md 9. */
#include "fsw/thr_pulse_rem.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"
#include "thr_pulse_common.h"

FswStatus fsw_thr_pulse_rem_check(const FswThrPulseRemConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) return FSW_E_NULL_ARG;
  s = fsw_thr_pulse_check_common(cfg->num_thr, cfg->t_min, 1, cfg->F_max);
  if (s != FSW_OK) return s;
  return fsw_thr_pulse_check_base(cfg->base_thrust_state, cfg->init_off_pulse_on_time);
}

void fsw_thr_pulse_rem_reset(FswThrPulseRemState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) return;
  fsw_vn_zero(st->rem, FSW_MAX_THR);
  st->has_prev = 0;
  st->t_prev_ns = 0u;
}

FswStatus fsw_thr_pulse_rem_init(FswThrPulseRemState *st, const FswThrPulseRemConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) return FSW_E_NULL_ARG;
  st->ready = 0;
  fsw_health_clear(&st->health);
  fsw_thr_pulse_rem_reset(st);
  s = fsw_thr_pulse_rem_check(cfg);
  if (s != FSW_OK) return s;
  st->ready = 1;
  return FSW_OK;
}

FswStatus fsw_thr_pulse_rem_update(FswThrPulseRemState *st, const FswThrPulseRemConfig *cfg,
                                   const FswThrPulseRemIn *in, FswThrPulseRemOut *out)
{
  ThrPulseTiming timing;
  fsw_real dt;
  FswStatus s;
  int i, n, saturated = 0;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) fsw_thr_pulse_safe_output(out->t_on);
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    if (st != NULL) (void)fsw_health_record(&st->health, FSW_E_NULL_ARG);
    return FSW_E_NULL_ARG;
  }
  n = cfg->num_thr;
  s = fsw_thr_pulse_begin(st->ready, &st->health, in->F, n, 1, st->has_prev, st->t_prev_ns,
                          in->t_ns, &timing, &dt);
  if (s != FSW_OK) return s;

  if (timing == THR_PULSE_FIRST) {
    fsw_thr_pulse_first_output(out->t_on, n, cfg->base_thrust_state,
                               cfg->init_off_pulse_on_time);
  } else {
    for (i = 0; i < n; i++) {
      /* 9 steps 1-3, in the order written */
      fsw_real t = fsw_thr_pulse_on_time(in->F[i], cfg->F_max[i], cfg->base_thrust_state, dt);
      t = t + st->rem[i] * cfg->t_min;
      st->rem[i] = FSW_R(0.0);
      if (t < cfg->t_min) {
        st->rem[i] = t / cfg->t_min;
        out->t_on[i] = FSW_R(0.0);
      } else if (t >= dt) {
        if (t > dt) saturated = 1;
        out->t_on[i] = THR_PULSE_SAT_FACTOR * dt;
      } else {
        out->t_on[i] = t;
      }
    }
  }
  st->has_prev = 1;
  st->t_prev_ns = in->t_ns;
  return fsw_health_record(&st->health, saturated ? FSW_W_SAT : FSW_OK);
}

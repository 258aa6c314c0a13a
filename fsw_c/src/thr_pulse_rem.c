/* thr_pulse_rem: remainder-tracking thruster pulsing, docs/fsw/thr_pulse_rem.md. */
#include "fsw/thr_pulse_rem.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"
#include "thr_pulse_internal.h"

FswStatus fsw_thr_pulse_rem_check(const FswThrPulseRemConfig *cfg)
{
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  return fsw_thr_pulse_check_common(&cfg->common);
}

void fsw_thr_pulse_rem_reset(FswThrPulseRemState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  fsw_vn_zero(st->rem, FSW_MAX_THR);
  fsw_clock_reset(&st->common.clock);
}

FswStatus fsw_thr_pulse_rem_init(FswThrPulseRemState *st, const FswThrPulseRemConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  fsw_thr_pulse_init_common(&st->common);
  fsw_thr_pulse_rem_reset(st);
  s = fsw_thr_pulse_rem_check(cfg);
  if (s != FSW_OK) { return s; }
  st->common.ready = 1;
  return FSW_OK;
}

FswStatus fsw_thr_pulse_rem_update(FswThrPulseRemState *st, const FswThrPulseRemConfig *cfg,
                                   const FswThrPulseRemIn *in, FswThrPulseRemOut *out)
{
  const FswThrPulseCommon *c;
  fsw_real dt;
  FswStatus s;
  int i, saturated = 0;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { fsw_thr_pulse_safe_output(out->t_on); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    if (st != NULL) { (void)fsw_health_record(&st->common.health, FSW_E_NULL_ARG); }
    return FSW_E_NULL_ARG;
  }
  c = &cfg->common;
  s = fsw_thr_pulse_begin(&st->common, in->F, c->num_thr, 1, in->t_ns, &dt);
  if (s != FSW_OK) { return s; }

  if (!st->common.clock.has_prev) {
    fsw_thr_pulse_first_output(out->t_on, c);
  } else {
    for (i = 0; i < c->num_thr; i++) {
      /* 9 steps 1-3, in the order written */
      fsw_real t = fsw_thr_pulse_on_time(in->F[i], c->F_max[i], c->base_thrust_state, dt);
      t = t + st->rem[i] * c->t_min;
      st->rem[i] = FSW_R(0.0);
      if (t < c->t_min) {
        st->rem[i] = t / c->t_min;
        out->t_on[i] = FSW_R(0.0);
      } else if (t >= dt) {
        if (t > dt) { saturated = 1; }
        out->t_on[i] = THR_PULSE_SAT_FACTOR * dt;
      } else {
        out->t_on[i] = t;
      }
    }
  }
  return fsw_thr_pulse_end(&st->common, 1, in->t_ns, saturated);
}

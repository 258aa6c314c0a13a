/* thr_pulse_schmitt: Schmitt-trigger thruster pulsing, docs/fsw/thr_pulse_schmitt.md. */
#include "fsw/thr_pulse_schmitt.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_vec.h"
#include "thr_pulse_internal.h"

FswStatus fsw_thr_pulse_schmitt_check(const FswThrPulseSchmittConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_thr_pulse_check_common(&cfg->common);
  if (s != FSW_OK) { return s; }
  if (!isfinite(cfg->level_on) || !isfinite(cfg->level_off)) { return FSW_E_CONFIG; }
  if (!(cfg->level_off >= FSW_R(0.0) && cfg->level_off < cfg->level_on &&
        cfg->level_on <= FSW_R(1.0))) {
    return FSW_E_CONFIG; }
  return FSW_OK;
}

void fsw_thr_pulse_schmitt_reset(FswThrPulseSchmittState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  (void)memset(st->last_on, 0, sizeof st->last_on);
  fsw_clock_reset(&st->common.clock);
}

FswStatus fsw_thr_pulse_schmitt_init(FswThrPulseSchmittState *st,
                                     const FswThrPulseSchmittConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  fsw_thr_pulse_init_common(&st->common);
  fsw_thr_pulse_schmitt_reset(st);
  s = fsw_thr_pulse_schmitt_check(cfg);
  if (s != FSW_OK) { return s; }
  st->common.ready = 1;
  return FSW_OK;
}

FswStatus fsw_thr_pulse_schmitt_update(FswThrPulseSchmittState *st,
                                       const FswThrPulseSchmittConfig *cfg,
                                       const FswThrPulseSchmittIn *in,
                                       FswThrPulseSchmittOut *out)
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
      fsw_real t = fsw_thr_pulse_on_time(in->F[i], c->F_max[i], c->base_thrust_state, dt);
      if (t < c->t_min) {
        fsw_real level = t / c->t_min;
        /* the minimum pulse, but never longer than the call period (a
         * period shorter than t_min cannot hold a t_min pulse) */
        const fsw_real t_pulse = (c->t_min < dt) ? c->t_min : dt;
        /* both comparisons inclusive */
        if (level >= cfg->level_on) {
          st->last_on[i] = 1u;
          out->t_on[i] = t_pulse;
        } else if (level <= cfg->level_off) {
          st->last_on[i] = 0u;
          out->t_on[i] = FSW_R(0.0);
        } else {
          out->t_on[i] = st->last_on[i] ? t_pulse : FSW_R(0.0);
        }
      } else if (t >= dt) {
        if (t > dt) { saturated = 1; }
        st->last_on[i] = 1u;
        out->t_on[i] = THR_PULSE_SAT_FACTOR * dt;
      } else {
        st->last_on[i] = 1u;
        out->t_on[i] = t;
      }
    }
  }
  return fsw_thr_pulse_end(&st->common, 1, in->t_ns, saturated);
}

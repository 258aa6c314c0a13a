/* thr_pulse_schmitt: Schmitt-trigger thruster pulsing, fsw-algorithms.md 10. */
#include "fsw/thr_pulse_schmitt.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_vec.h"
#include "thr_pulse_common.h"

FswStatus fsw_thr_pulse_schmitt_check(const FswThrPulseSchmittConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) return FSW_E_NULL_ARG;
  s = fsw_thr_pulse_check_common(cfg->num_thr, cfg->t_min, 1, cfg->F_max);
  if (s != FSW_OK) return s;
  if (!isfinite(cfg->level_on) || !isfinite(cfg->level_off)) return FSW_E_CONFIG;
  if (!(cfg->level_off >= FSW_R(0.0) && cfg->level_off < cfg->level_on &&
        cfg->level_on <= FSW_R(1.0)))
    return FSW_E_CONFIG;
  return fsw_thr_pulse_check_base(cfg->base_thrust_state, cfg->init_off_pulse_on_time);
}

void fsw_thr_pulse_schmitt_reset(FswThrPulseSchmittState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) return;
  memset(st->last_on, 0, sizeof st->last_on);
  st->has_prev = 0;
  st->t_prev_ns = 0u;
}

FswStatus fsw_thr_pulse_schmitt_init(FswThrPulseSchmittState *st,
                                     const FswThrPulseSchmittConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) return FSW_E_NULL_ARG;
  st->ready = 0;
  fsw_health_clear(&st->health);
  fsw_thr_pulse_schmitt_reset(st);
  s = fsw_thr_pulse_schmitt_check(cfg);
  if (s != FSW_OK) return s;
  st->ready = 1;
  return FSW_OK;
}

FswStatus fsw_thr_pulse_schmitt_update(FswThrPulseSchmittState *st,
                                       const FswThrPulseSchmittConfig *cfg,
                                       const FswThrPulseSchmittIn *in,
                                       FswThrPulseSchmittOut *out)
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
      fsw_real t = fsw_thr_pulse_on_time(in->F[i], cfg->F_max[i], cfg->base_thrust_state, dt);
      if (t < cfg->t_min) {
        fsw_real level = t / cfg->t_min;
        /* both comparisons inclusive (10) */
        if (level >= cfg->level_on) {
          st->last_on[i] = 1u;
          out->t_on[i] = cfg->t_min;
        } else if (level <= cfg->level_off) {
          st->last_on[i] = 0u;
          out->t_on[i] = FSW_R(0.0);
        } else {
          out->t_on[i] = st->last_on[i] ? cfg->t_min : FSW_R(0.0);
        }
      } else if (t >= dt) {
        if (t > dt) saturated = 1;
        st->last_on[i] = 1u;
        out->t_on[i] = THR_PULSE_SAT_FACTOR * dt;
      } else {
        st->last_on[i] = 1u;
        out->t_on[i] = t;
      }
    }
  }
  st->has_prev = 1;
  st->t_prev_ns = in->t_ns;
  return fsw_health_record(&st->health, saturated ? FSW_W_SAT : FSW_OK);
}

/* thr_pulse_round: rounding thruster pulser, docs/fsw/thr_pulse_round.md. */
#include "fsw/thr_pulse_round.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"
#include "thr_pulse_internal.h"

FswStatus fsw_thr_pulse_round_check(const FswThrPulseRoundConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_thr_pulse_check_thrusters(cfg->num_thr, cfg->F_max);
  if (s != FSW_OK) { return s; }
  if (!isfinite(cfg->t_min) || cfg->t_min < FSW_R(0.0)) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->period) || !(cfg->period > FSW_R(0.0))) { return FSW_E_CONFIG; }
  /* a minimum on-time longer than the period cannot be honoured: the final
   * clamp to the period would command an on-time below t_min */
  if (cfg->t_min > cfg->period) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->resolution) || !(cfg->resolution > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (cfg->carry_residual != 0 && cfg->carry_residual != 1) { return FSW_E_CONFIG; }
  return FSW_OK;
}

void fsw_thr_pulse_round_reset(FswThrPulseRoundState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  fsw_vn_zero(st->resid, FSW_MAX_THR);
  fsw_clock_reset(&st->common.clock);
}

FswStatus fsw_thr_pulse_round_init(FswThrPulseRoundState *st, const FswThrPulseRoundConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  fsw_thr_pulse_init_common(&st->common);
  fsw_thr_pulse_round_reset(st);
  s = fsw_thr_pulse_round_check(cfg);
  if (s != FSW_OK) { return s; }
  st->common.ready = 1;
  return FSW_OK;
}

static fsw_real clamp(fsw_real x, fsw_real lo, fsw_real hi)
{
  if (x < lo) { return lo; }
  if (x > hi) { return hi; }
  return x;
}

FswStatus fsw_thr_pulse_round_update(FswThrPulseRoundState *st, const FswThrPulseRoundConfig *cfg,
                                     const FswThrPulseRoundIn *in, FswThrPulseRoundOut *out)
{
  const fsw_real T = (cfg != NULL) ? cfg->period : FSW_R(0.0);
  fsw_real dt;
  FswStatus s;
  int i, n, saturated = 0;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { fsw_thr_pulse_safe_output(out->t_on); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    if (st != NULL) { (void)fsw_health_record(&st->common.health, FSW_E_NULL_ARG); }
    return FSW_E_NULL_ARG;
  }
  n = cfg->num_thr;
  /* time stamps matter only to the carried residual (the default mode is
   * stateless like Basilisk's) */
  s = fsw_thr_pulse_begin(&st->common, in->F, n, cfg->carry_residual, in->t_ns, &dt);
  if (s != FSW_OK) { return s; }

  /* WP (docs/eva.md, "WP proofs"): every on-time within [0, T], proven from
   * this loop invariant and test/proofs/wp/thr_pulse_round_bound.h. */
  /*@ loop invariant 0 <= i <= n;
      loop invariant \forall integer k; 0 <= k < i ==> 0 <= out->t_on[k] <= T;
      loop invariant \forall integer k; i <= k < FSW_MAX_THR ==> 0 <= out->t_on[k] <= 0;
      loop invariant \forall integer k; 0 <= k < n ==> -T <= st->resid[k] <= T;
      loop assigns i, saturated, out->t_on[0 .. n - 1], st->resid[0 .. n - 1];
      loop variant n - i; */
  for (i = 0; i < n; i++) {
    fsw_real f = (in->F[i] > FSW_R(0.0)) ? in->F[i] : FSW_R(0.0);
    fsw_real t = T * f / cfg->F_max[i];
    fsw_real t_req;
    if (cfg->carry_residual) { t = t + st->resid[i]; }
    t_req = t;
    if (t > T) { saturated = 1; }
    t = clamp(t, FSW_R(0.0), T);
    /* round half to even: rint in the default rounding mode, not round() */
    t = FSW_RINT(t / cfg->resolution) * cfg->resolution;
    if (t < cfg->t_min) { t = FSW_R(0.0); }
    t = clamp(t, FSW_R(0.0), T);
    out->t_on[i] = t;
    if (cfg->carry_residual) { st->resid[i] = clamp(t_req - t, -T, T); }
  }
  return fsw_thr_pulse_end(&st->common, cfg->carry_residual, in->t_ns, saturated);
}

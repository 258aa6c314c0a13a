/* rw_volt: torque -> voltage with speed loop and outlier gate (docs/fsw/rw_volt.md). */
#include "fsw/rw_volt.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"
#include "fsw/rw_common.h"

FswStatus fsw_rw_volt_check(const FswRwVoltConfig *cfg)
{
  int n;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  n = cfg->num_rw;
  if (n < 1 || n > FSW_MAX_RW || n > 64) { return FSW_E_CAPACITY; }
  if (!isfinite(cfg->V_min) || cfg->V_min < FSW_R(0.0)) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->V_max) || !(cfg->V_max > cfg->V_min) || cfg->V_max > FSW_RW_V_MAX_MAX) {
    return FSW_E_CONFIG; }
  if (!isfinite(cfg->K_V) || cfg->K_V < FSW_R(0.0) || cfg->K_V > FSW_RW_GAIN_MAX) {
    return FSW_E_CONFIG; }
  if (!fsw_rw_all_in_range(cfg->u_max, n, FSW_RW_U_MAX_MIN, FSW_RW_U_MAX_MAX) ||
      !fsw_rw_all_in_range(cfg->J_s, n, FSW_R(0.0), FSW_RW_J_S_MAX)) {
    return FSW_E_CONFIG; }
  if (cfg->gate_rate != 0 && cfg->gate_rate != 1) { return FSW_E_CONFIG; }
  if (cfg->gate_rate && !fsw_rw_all_positive(cfg->Omega_dot_max, n)) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_rw_volt_init(FswRwVoltState *st, const FswRwVoltConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_rw_volt_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_rw_volt_reset(st);
  return FSW_OK;
}

void fsw_rw_volt_reset(FswRwVoltState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  fsw_rw_zero(st->Omega_prev);
  {
    int i;
    for (i = 0; i < FSW_MAX_RW; i++) { st->prev_ok[i] = 0u; }
  }
  st->phase = 0;
  fsw_clock_reset(&st->clock);
}

FswStatus fsw_rw_volt_update(FswRwVoltState *st, const FswRwVoltConfig *cfg,
                             const FswRwVoltIn *in, FswRwVoltOut *out)
{
  fsw_real dt = FSW_R(0.0);
  fsw_real Omega_prev[FSW_MAX_RW]; /* [rad/s] candidate state, committed at the end */
  uint8_t prev_ok[FSW_MAX_RW];
  int n, i, clipped = 0, phase;
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { /* safe output */
    fsw_rw_zero(out->V);
    out->fault = 0u;
  }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_rw;
  if (!fsw_rw_avail_valid(in->avail, n) || !fsw_vn_is_finite(in->u_s, n) ||
      (in->has_Omega != 0 && in->has_Omega != 1) ||
      (in->has_Omega && !fsw_rw_avail_finite(in->Omega, in->avail, n))) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  {
    const FswStatus s = fsw_clock_dt(&st->clock, in->t_ns, &dt); /* FSW_OK or FSW_E_TIME */
    if (s != FSW_OK) { return fsw_health_record(&st->health, s); }
  }

  for (i = 0; i < n; i++) { out->V[i] = (in->avail[i] == FSW_AVAILABLE) ? in->u_s[i] : FSW_R(0.0); }

  /* speed loop (out->V holds the torque until the feed-forward below); the
   * new speed memory is built in locals and committed only on success */
  for (i = 0; i < FSW_MAX_RW; i++) {
    Omega_prev[i] = st->Omega_prev[i];
    prev_ok[i] = st->prev_ok[i];
  }
  phase = st->phase;
  if (!in->has_Omega) {
    phase = 0;
  } else if (st->phase == 0) {
    phase = 1;
  } else {
    for (i = 0; i < n; i++) {
      /* a wheel whose previous speed was not a number (unavailable with a
       * failed tachometer) skips one correction after it comes back */
      if (st->phase == 2 && in->avail[i] == FSW_AVAILABLE && st->prev_ok[i]) {
        const fsw_real Omega_dot = (in->Omega[i] - st->Omega_prev[i]) / dt;
        const fsw_real dV = cfg->K_V * (cfg->J_s[i] * Omega_dot - out->V[i]);
        /* a rate or correction that overflows (a speed glitch of ~1e308)
         * is an outlier whether or not the gate is on: no correction */
        if ((cfg->gate_rate && FSW_FABS(Omega_dot) > cfg->Omega_dot_max[i]) || !isfinite(dV)) {
          out->fault |= (uint64_t)1u << i;
        } else {
          out->V[i] -= dV; }
      }
      /* docs/fsw/rw_volt.md: Omega_prev = Omega for every wheel (available or not) */
      prev_ok[i] = (uint8_t)(isfinite(in->Omega[i]) ? 1 : 0);
      Omega_prev[i] = prev_ok[i] ? in->Omega[i] : FSW_R(0.0);
    }
    phase = 2;
  }

  /* feed-forward with dead-band jump and clip */
  for (i = 0; i < n; i++) {
    fsw_real V;
    if (in->avail[i] != FSW_AVAILABLE) { continue; } /* stays exactly 0 */
    V = (cfg->V_max - cfg->V_min) / cfg->u_max[i] * out->V[i];
    if (V > FSW_R(0.0)) {
      V += cfg->V_min;
    } else if (V < FSW_R(0.0)) {
      V -= cfg->V_min; }
    if (V > cfg->V_max) {
      V = cfg->V_max;
      clipped = 1;
    } else if (V < -cfg->V_max) {
      V = -cfg->V_max;
      clipped = 1;
    }
    out->V[i] = V;
  }
  if (!fsw_vn_is_finite(out->V, n)) { /* not reached with a checked config */
    fsw_rw_zero(out->V);
    out->fault = 0u;
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  for (i = 0; i < FSW_MAX_RW; i++) {
    st->Omega_prev[i] = Omega_prev[i];
    st->prev_ok[i] = prev_ok[i];
  }
  st->phase = phase;
  fsw_clock_commit(&st->clock, in->t_ns);
  return fsw_health_record(&st->health, clipped ? FSW_W_SAT : FSW_OK);
}

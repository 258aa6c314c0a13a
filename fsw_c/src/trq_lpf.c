/* trq_lpf: first-order Tustin low-pass of the control torque (docs/fsw/trq_lpf.md). */
#include "fsw/trq_lpf.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

#define TRQ_LPF_PI FSW_R(3.14159265358979323846)

FswStatus fsw_trq_lpf_check(const FswTrqLpfConfig *cfg)
{
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (!isfinite(cfg->h) || !(cfg->h > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->omega_c) || !(cfg->omega_c > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (!(cfg->omega_c * cfg->h < TRQ_LPF_PI)) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_trq_lpf_init(FswTrqLpfState *st, const FswTrqLpfConfig *cfg)
{
  FswStatus s;
  fsw_real hw;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_trq_lpf_check(cfg);
  if (s != FSW_OK) { return s; }
  hw = FSW_R(2.0) * FSW_TAN(cfg->omega_c * cfg->h / FSW_R(2.0));
  st->a0 = FSW_R(2.0) + hw;
  st->a1 = FSW_R(2.0) - hw;
  st->b0 = hw;
  st->ready = 1;
  fsw_trq_lpf_reset(st);
  return FSW_OK;
}

void fsw_trq_lpf_reset(FswTrqLpfState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  fsw_v3_zero(st->Lr_prev);
  fsw_v3_zero(st->LrF_prev);
  fsw_clock_reset(&st->clock);
}

FswStatus fsw_trq_lpf_update(FswTrqLpfState *st, const FswTrqLpfConfig *cfg,
                             const FswTrqLpfIn *in, FswTrqLpfOut *out)
{
  FswStatus s = FSW_OK;
  fsw_real dt; /* [s] */
  fsw_real Lr_prev[3], LrF[3]; /* candidate memory, committed on success */
  int k;
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { fsw_v3_zero(out->LrF_B); } /* safe output */
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (!fsw_v3_is_finite(in->Lr_B)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  s = fsw_clock_dt(&st->clock, in->t_ns, &dt); /* FSW_OK or FSW_E_TIME */
  if (s != FSW_OK) { return fsw_health_record(&st->health, s); }
  if (st->clock.has_prev) {
    if (FSW_FABS(dt - cfg->h) > FSW_TRQ_LPF_RATE_TOL * cfg->h) { s = FSW_W_RATE; }
    fsw_v3_copy(Lr_prev, st->Lr_prev);
    fsw_v3_copy(LrF, st->LrF_prev);
  } else {
    fsw_v3_copy(Lr_prev, in->Lr_B);
    fsw_v3_zero(LrF);
  }
  for (k = 0; k < 3; k++) {
    LrF[k] = (st->b0 * in->Lr_B[k] + st->b0 * Lr_prev[k] + st->a1 * LrF[k]) / st->a0; }
  /* a finite but huge torque overflows the filter: bad input, memory kept */
  if (!fsw_v3_is_finite(LrF)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  fsw_v3_copy(out->LrF_B, LrF);
  fsw_v3_copy(st->Lr_prev, in->Lr_B);
  fsw_v3_copy(st->LrF_prev, LrF);
  fsw_clock_commit(&st->clock, in->t_ns);
  return fsw_health_record(&st->health, s);
}

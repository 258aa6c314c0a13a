/* mtq_desat: wheel momentum desaturation by magnetorquers (cross-product law). */
#include "fsw/mtq_desat.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"
#include "fsw/mtq_map.h"
#include "fsw/rw_common.h"

FswStatus fsw_mtq_desat_check(const FswMtqDesatConfig *cfg)
{
  FswStatus s;
  int k;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_rw_check_axes(cfg->gs_hat_B, cfg->num_rw, 1);
  if (s != FSW_OK) { return s; }
  if (!fsw_rw_all_in_range(cfg->J_s, cfg->num_rw, FSW_R(0.0), FSW_RW_J_S_MAX)) { return FSW_E_CONFIG; }
  if (!fsw_rw_all_in_range(&cfg->k_desat, 1, FSW_R(0.0), FSW_MTQ_DESAT_K_MAX)) { return FSW_E_CONFIG; }
  if (!fsw_rw_all_in_range(&cfg->tau_max, 1, FSW_MTQ_DESAT_TAU_MIN, FSW_MTQ_DESAT_TAU_MAX)) {
    return FSW_E_CONFIG; }
  for (k = 0; k < 3; k++) {
    if (!(FSW_FABS(cfg->h_target_B[k]) <= FSW_MTQ_DESAT_H_MAX)) { return FSW_E_CONFIG; } }
  if (!(cfg->h_deadband >= FSW_R(0.0) && cfg->h_deadband <= FSW_MTQ_DESAT_H_MAX)) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_mtq_desat_init(FswMtqDesatState *st, const FswMtqDesatConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_mtq_desat_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_mtq_desat_reset(st);
  return FSW_OK;
}

void fsw_mtq_desat_reset(FswMtqDesatState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* no time-varying state */
}

static void desat_safe_output(FswMtqDesatOut *out)
{
  fsw_v3_zero(out->tau_req_B);
  fsw_v3_zero(out->m_B);
  fsw_v3_zero(out->h_w_B);
  fsw_v3_zero(out->h_err_B);
  out->h_err_norm = FSW_R(0.0);
  out->scale = FSW_R(0.0);
}

FswStatus fsw_mtq_desat_update(FswMtqDesatState *st, const FswMtqDesatConfig *cfg,
                               const FswMtqDesatIn *in, FswMtqDesatOut *out)
{
  fsw_real b_hat[3], Bn; /* [-], [T] field direction and size */
  fsw_real t, s;
  FswStatus fs;
  int n;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { desat_safe_output(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_rw;
  if (!fsw_rw_avail_valid(in->avail, n) || !fsw_rw_avail_speed_ok(in->Omega, in->avail, n)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  fs = fsw_mtq_field(b_hat, &Bn, in->B_B, in->B_valid);
  if (fs < 0) { return fsw_health_record(&st->health, fs); }

  /* h_w = sum J_s Omega gs_hat over the available wheels (<= 36 x 1e8) */
  fsw_rw_momentum(out->h_w_B, cfg->gs_hat_B, cfg->J_s, in->Omega, in->avail, n);
  fsw_v3_sub(out->h_err_B, out->h_w_B, cfg->h_target_B);
  out->h_err_norm = fsw_v3_norm(out->h_err_B);
  if (fs != FSW_OK) { return fsw_health_record(&st->health, fs); } /* no field: no request */
  if (out->h_err_norm <= cfg->h_deadband) { return fsw_health_record(&st->health, FSW_OK); }

  /* tau_req = -k (h - (h . b) b) = k (h x b) x b; m = (k/|B|) (h x b) */
  fsw_v3_cross(out->m_B, out->h_err_B, b_hat);
  fsw_v3_cross(out->tau_req_B, out->m_B, b_hat);
  fsw_v3_scale(out->tau_req_B, cfg->k_desat, out->tau_req_B);
  fsw_v3_scale(out->m_B, cfg->k_desat / Bn, out->m_B);
  t = fsw_v3_norm(out->tau_req_B);
  s = t > cfg->tau_max ? cfg->tau_max / t : FSW_R(1.0);
  if (s < FSW_R(1.0)) {
    fsw_v3_scale(out->tau_req_B, s, out->tau_req_B);
    fsw_v3_scale(out->m_B, s, out->m_B);
  }
  out->scale = s;
  return fsw_health_record(&st->health, s < FSW_R(1.0) ? FSW_W_SAT : FSW_OK);
}

/* rw_null: wheel-speed null motion (docs/fsw/rw_null.md). */
#include "fsw/rw_null.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

FswStatus fsw_rw_null_check(const FswRwNullConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_rw_check_axes(cfg->gs_hat_B, cfg->num_rw, 1);
  if (s != FSW_OK) { return s; }
  if (!fsw_rw_all_in_range(&cfg->k_null, 1, FSW_R(0.0), FSW_RW_GAIN_MAX)) { return FSW_E_CONFIG; }
  if (cfg->scale_to_fit != 0 && cfg->scale_to_fit != 1) { return FSW_E_CONFIG; }
  if (cfg->scale_to_fit &&
      !fsw_rw_all_in_range(cfg->u_max, cfg->num_rw, FSW_RW_U_MAX_MIN, FSW_RW_U_MAX_MAX)) {
    return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_rw_null_init(FswRwNullState *st, const FswRwNullConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_rw_null_check(cfg);
  if (s != FSW_OK) { return s; }
  fsw_rw_proj_init(&st->proj, cfg->gs_hat_B, cfg->num_rw);
  st->ready = 1;
  fsw_rw_null_reset(st);
  return FSW_OK;
}

void fsw_rw_null_reset(FswRwNullState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* no time-varying state; the projector is derived data */
}

FswStatus fsw_rw_null_update(FswRwNullState *st, const FswRwNullConfig *cfg,
                             const FswRwNullIn *in, FswRwNullOut *out)
{
  fsw_real d[FSW_MAX_RW];  /* [N*m] -K (Omega - Omega_des) */
  fsw_real du[FSW_MAX_RW]; /* [N*m] [tau] d (projected twice, see rw_common.h) */
  fsw_real uc[FSW_MAX_RW]; /* [N*m] u_c with unavailable wheels at 0 */
  uint8_t avail_prev[FSW_MAX_RW]; /* projector mask before this call */
  int n, i;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) {
    fsw_rw_zero(out->u_s); /* safe output */
    out->kappa = FSW_R(0.0);
  }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_rw;
  if (!fsw_rw_avail_valid(in->avail, n) || !fsw_vn_is_finite(in->u_s, n) ||
      !fsw_rw_avail_speed_ok(in->Omega, in->avail, n) ||
      !fsw_rw_avail_speed_ok(in->Omega_des, in->avail, n)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }

  for (i = 0; i < FSW_MAX_RW; i++) { avail_prev[i] = st->proj.avail[i]; }
  (void)fsw_rw_proj_refresh(&st->proj, in->avail);
  for (i = 0; i < n; i++) {
    const int a = in->avail[i] == FSW_AVAILABLE;
    /* unavailable wheels: their speeds are not read (0 * NaN would leak) */
    d[i] = a ? -cfg->k_null * (in->Omega[i] - in->Omega_des[i]) : FSW_R(0.0);
    uc[i] = a ? in->u_s[i] : FSW_R(0.0);
  }
  fsw_rw_proj_apply(du, &st->proj, d);
  /* finite but huge speed errors overflow d or [tau] d: bad input */
  if (!fsw_vn_is_finite(du, n)) {
    (void)fsw_rw_proj_refresh(&st->proj, avail_prev); /* untouched on error */
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  out->kappa = fsw_rw_add_scaled_to_fit(out->u_s, uc, du, cfg->scale_to_fit ? cfg->u_max : NULL, n);
  if (!fsw_vn_is_finite(out->u_s, n) || !isfinite(out->kappa)) {
    fsw_rw_zero(out->u_s);
    out->kappa = FSW_R(0.0);
    (void)fsw_rw_proj_refresh(&st->proj, avail_prev); /* untouched on error */
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  if (!fsw_rw_null_change_ok(&st->proj, out->u_s, uc, n)) {
    /* the step is not in the null space to working precision: drop it */
    fsw_vn_copy(out->u_s, uc, n);
    out->kappa = FSW_R(0.0);
    return fsw_health_record(&st->health, FSW_W_SINGULAR);
  }
  return fsw_health_record(&st->health, out->kappa < FSW_R(1.0) ? FSW_W_SAT : FSW_OK);
}

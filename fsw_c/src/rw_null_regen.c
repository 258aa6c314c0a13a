/* rw_null_regen: regenerative power-optimal null motion (docs/fsw/rw_null_regen.md). */
#include "fsw/rw_null_regen.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

/* |Omega^T n| below this fraction of |Omega| counts as 0 (alpha = 0). */
#if FSW_USE_FLOAT
#define REGEN_TIE_TOL FSW_R(1e-6)
#else
#define REGEN_TIE_TOL 1e-12
#endif

FswStatus fsw_rw_null_regen_check(const FswRwNullRegenConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_rw_check_axes(cfg->gs_hat_B, cfg->num_rw, 1);
  if (s != FSW_OK) { return s; }
  if (cfg->mode == FSW_RW_REGEN_GRADIENT) {
    if (!fsw_rw_all_in_range(&cfg->k_P, 1, FSW_R(0.0), FSW_RW_GAIN_MAX)) { return FSW_E_CONFIG; }
  } else if (cfg->mode != FSW_RW_REGEN_OPTIMUM) {
    return FSW_E_CONFIG;
  }
  if (!fsw_rw_all_in_range(cfg->u_max, cfg->num_rw, FSW_RW_U_MAX_MIN, FSW_RW_U_MAX_MAX)) {
    return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_rw_null_regen_init(FswRwNullRegenState *st, const FswRwNullRegenConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_rw_null_regen_check(cfg);
  if (s != FSW_OK) { return s; }
  fsw_rw_proj_init(&st->proj, cfg->gs_hat_B, cfg->num_rw);
  st->ready = 1;
  fsw_rw_null_regen_reset(st);
  return FSW_OK;
}

void fsw_rw_null_regen_reset(FswRwNullRegenState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* no time-varying state; the projector is derived data */
}

/* Nullity-1 optimum.  n = tau[:,k]/sqrt(tau_kk), k = largest diagonal
 * (lowest index on ties), sign so the first non-zero entry is > 0;
 * [alpha_lo, alpha_hi] = intersection over wheels of
 * {alpha : -u_max <= u0 + alpha n <= u_max}. */
static FswStatus regen_optimum(fsw_real *u, const FswRwNullProj *p, const fsw_real *u0,
                               const fsw_real *Omega, const fsw_real *u_max)
{
  fsw_real nv[FSW_MAX_RW];
  fsw_real tmax = FSW_R(0.0), sg = FSW_R(0.0), lo = -FSW_R(1.0), hi = FSW_R(1.0);
  fsw_real om_n, om_norm, alpha;
  int n = p->num_rw, i, k = 0, have = 0;

  for (i = 0; i < n; i++) {
    if (p->tau[i][i] > tmax) {
      tmax = p->tau[i][i];
      k = i;
    } }
  for (i = 0; i < n; i++) {
    nv[i] = p->tau[i][k] / FSW_SQRT(tmax);
    if (sg == FSW_R(0.0) && nv[i] != FSW_R(0.0)) { sg = (nv[i] > FSW_R(0.0)) ? FSW_R(1.0) : -FSW_R(1.0); }
  }
  for (i = 0; i < n; i++) { nv[i] *= sg; }

  for (i = 0; i < n; i++) {
    fsw_real a, b;
    if (nv[i] == FSW_R(0.0)) {
      if (FSW_FABS(u0[i]) > u_max[i]) { return FSW_W_SAT; } /* no alpha helps */
      continue;
    }
    a = (-u_max[i] - u0[i]) / nv[i];
    b = (u_max[i] - u0[i]) / nv[i];
    if (a > b) {
      fsw_real t = a;
      a = b;
      b = t;
    }
    if (!have || a > lo) { lo = a; }
    if (!have || b < hi) { hi = b; }
    have = 1;
  }
  if (lo > hi) { return FSW_W_SAT; }

  om_n = fsw_vn_dot(Omega, nv, n);
  om_norm = fsw_vn_norm(Omega, n);
  if (om_n > REGEN_TIE_TOL * om_norm) {
    alpha = lo;
  } else if (om_n < -REGEN_TIE_TOL * om_norm) {
    alpha = hi;
  } else {
    alpha = FSW_R(0.0); }
  for (i = 0; i < n; i++) {
    u[i] = u0[i] + alpha * nv[i];
    if (u[i] > u_max[i]) { u[i] = u_max[i]; } /* last-ulp rounding only */
    if (u[i] < -u_max[i]) { u[i] = -u_max[i]; }
  }
  return FSW_OK;
}

FswStatus fsw_rw_null_regen_update(FswRwNullRegenState *st, const FswRwNullRegenConfig *cfg,
                                   const FswRwNullRegenIn *in, FswRwNullRegenOut *out)
{
  fsw_real u0[FSW_MAX_RW], om[FSW_MAX_RW], d[FSW_MAX_RW], du[FSW_MAX_RW];
  uint8_t avail_prev[FSW_MAX_RW]; /* projector mask before this call */
  FswStatus s = FSW_OK;
  int n, i, nullity;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) {
    fsw_rw_zero(out->u_s); /* safe output */
    out->power = FSW_R(0.0);
  }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_rw;
  if (!fsw_rw_avail_valid(in->avail, n) || !fsw_vn_is_finite(in->u_s, n) ||
      !fsw_rw_avail_speed_ok(in->Omega, in->avail, n)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }

  for (i = 0; i < FSW_MAX_RW; i++) { avail_prev[i] = st->proj.avail[i]; }
  (void)fsw_rw_proj_refresh(&st->proj, in->avail);
  for (i = 0; i < n; i++) {
    const int a = in->avail[i] == FSW_AVAILABLE;
    u0[i] = a ? in->u_s[i] : FSW_R(0.0);
    om[i] = a ? in->Omega[i] : FSW_R(0.0);
  }
  fsw_vn_copy(out->u_s, u0, n); /* u0 unless a better u is found */
  nullity = st->proj.num_avail - st->proj.rank;

  if (cfg->mode == FSW_RW_REGEN_GRADIENT) {
    /* steepest descent of P in the null space: -k_P [tau] Omega */
    fsw_vn_scale(d, -cfg->k_P, om, n);
    fsw_rw_proj_apply(du, &st->proj, d);
    if (fsw_rw_add_scaled_to_fit(out->u_s, u0, du, cfg->u_max, n) < FSW_R(1.0)) { s = FSW_W_SAT; }
  } else if (nullity == 1) {
    s = regen_optimum(out->u_s, &st->proj, u0, om, cfg->u_max);
  } else if (nullity > 1) {
    s = FSW_E_UNSUPPORTED;
    (void)fsw_rw_proj_refresh(&st->proj, avail_prev); /* an error changes no state */
  }
  out->power = fsw_vn_dot(om, out->u_s, n);
  /* finite but huge speeds overflow the step or the power: bad input */
  if (!fsw_vn_is_finite(out->u_s, n) || !isfinite(out->power)) {
    fsw_rw_zero(out->u_s);
    out->power = FSW_R(0.0);
    (void)fsw_rw_proj_refresh(&st->proj, avail_prev); /* untouched on error */
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  if (s >= 0 && !fsw_rw_null_change_ok(&st->proj, out->u_s, u0, n)) {
    /* the step is not in the null space to working precision: drop it */
    fsw_vn_copy(out->u_s, u0, n);
    out->power = fsw_vn_dot(om, out->u_s, n);
    s = FSW_W_SINGULAR;
  }
  return fsw_health_record(&st->health, s);
}

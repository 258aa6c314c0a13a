/* thr_map: thruster force mapping, docs/fsw/thr_map.md (Basilisk
 * thrForceMapping) with the opt-in exact bounded mode of 8.6. */
#include "fsw/thr_map.h"

#include <stddef.h>

#include "fsw/fsw_linalg.h"
#include "fsw/fsw_vec.h"

/* Saturation angle below which the torque angle error is treated as 0: the
 * angle of two parallel vectors computed in floating point is ~1e-8 rad in
 * double (docs/fsw/thr_map.md, defect b: 1e-6 rad).  In single precision
 * acos(1 - k eps) is already sqrt(2 k eps) ~ 5e-4 rad for k = 1, so the
 * float build uses 2e-3 rad.  [rad] */
#if FSW_USE_FLOAT
#define THR_MAP_ANGLE_ROUNDOFF FSW_R(2e-3)
#else
#define THR_MAP_ANGLE_ROUNDOFF FSW_R(1e-6)
#endif

/* Tolerance of a unit force direction: | |gt_hat| - 1 | must not exceed it. */
#if FSW_USE_FLOAT
#define THR_MAP_UNIT_TOL FSW_R(1e-5)
#else
#define THR_MAP_UNIT_TOL FSW_R(1e-9)
#endif

/* Relative torque error above which the NNLS result reports FSW_W_SAT. */
#define THR_NNLS_SAT_TOL (FSW_R(10000.0) * FSW_REAL_EPS)

/* Count the control axes (rows up to the first with norm <= epsilon) and
 * write them normalised into C.  Returns the count (0..3), or -1 for a
 * counted row so short that 1/|row| overflows (a norm below the inverse of
 * the largest real, possible with epsilon 0): its normalised row would be
 * infinite, so check refuses it. */
static int count_axes(fsw_real C[3][3], const FswThrMapConfig *cfg)
{
  int nc = 0, j;
  fsw_m33_zero(C);
  for (j = 0; j < 3; j++) {
    fsw_real n = fsw_v3_norm(cfg->control_axes_B[j]);
    fsw_real inv;
    if (!(n > cfg->epsilon) || !isfinite(n)) { break; }
    inv = FSW_R(1.0) / n;
    if (!isfinite(inv)) { return -1; }
    fsw_v3_scale(C[j], inv, cfg->control_axes_B[j]);
    nc++;
  }
  return nc;
}

FswStatus fsw_thr_map_check(const FswThrMapConfig *cfg)
{
  fsw_real C[3][3], L[3][3];
  int i, j, nc;

  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (cfg->num_thr > FSW_MAX_THR) { return FSW_E_CAPACITY; }
  if (cfg->num_thr < 1) { return FSW_E_CONFIG; }
  if (cfg->thr_force_sign != 1 && cfg->thr_force_sign != -1) { return FSW_E_CONFIG; }
  if (cfg->use_2nd_loop != 0 && cfg->use_2nd_loop != 1) { return FSW_E_CONFIG; }
  if (cfg->mode != FSW_THR_MAP_MIN_NORM && cfg->mode != FSW_THR_MAP_NNLS) { return FSW_E_CONFIG; }
#if !FSW_CFG_THR_NNLS
  if (cfg->mode == FSW_THR_MAP_NNLS) { return FSW_E_UNSUPPORTED; } /* built without it (fsw_config.h) */
#endif
  if (!isfinite(cfg->epsilon) || cfg->epsilon < FSW_R(0.0)) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->ang_err_thresh) || cfg->ang_err_thresh < FSW_R(0.0)) { return FSW_E_CONFIG; }
  for (j = 0; j < 3; j++) {
    if (!fsw_v3_is_finite(cfg->control_axes_B[j]) ||
        fsw_vn_max_abs(cfg->control_axes_B[j], 3) > FSW_THR_MAP_AXIS_MAX) {
      return FSW_E_CONFIG; } }
  for (i = 0; i < cfg->num_thr; i++) {
    if (!fsw_v3_is_finite(cfg->r_thr_B[i]) || !fsw_v3_is_finite(cfg->gt_hat_B[i])) {
      return FSW_E_CONFIG; }
    if (fsw_vn_max_abs(cfg->r_thr_B[i], 3) > FSW_THR_MAP_R_MAX) { return FSW_E_CONFIG; }
    if (cfg->F_max[i] > FSW_THR_MAP_F_MAX) { return FSW_E_CONFIG; }
    if (FSW_FABS(fsw_v3_norm(cfg->gt_hat_B[i]) - FSW_R(1.0)) > THR_MAP_UNIT_TOL) {
      return FSW_E_CONFIG; }
    if (!isfinite(cfg->F_max[i]) || !(cfg->F_max[i] > FSW_R(0.0))) { return FSW_E_CONFIG; }
  }
  nc = count_axes(C, cfg);
  if (nc <= 0) { return FSW_E_CONFIG; } /* no counted row, or one too short to normalise */
  /* The counted (unit) axes must be independent: the K1 rank rule applied
   * to [C]: Cholesky of [C][C]^T, fail if a pivot <= FSW_RANK_TOL * max diag
   * (max diag = 1 for unit rows). */
  for (j = 0; j < nc; j++) {
    for (i = 0; i < j; i++) {
      fsw_real v = fsw_v3_dot(C[j], C[i]);
      int k;
      for (k = 0; k < i; k++) { v -= L[j][k] * L[i][k]; }
      L[j][i] = v / L[i][i];
    }
    {
      fsw_real d = fsw_v3_dot(C[j], C[j]);
      int k;
      for (k = 0; k < j; k++) { d -= L[j][k] * L[j][k]; }
      if (!(d > FSW_RANK_TOL)) { return FSW_E_SINGULAR; }
      L[j][j] = FSW_SQRT(d);
    }
  }
  return FSW_OK;
}

void fsw_thr_map_reset(FswThrMapState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  st->ang_err = FSW_R(0.0);
  st->nnls_iter = 0;
}

FswStatus fsw_thr_map_init(FswThrMapState *st, const FswThrMapConfig *cfg)
{
  FswStatus s;
  int i;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  st->num_axes = 0;
  fsw_m33_zero(st->C);
  fsw_vn_zero(st->gt_norm, FSW_MAX_THR);
  fsw_health_clear(&st->health);
  fsw_thr_map_reset(st);
  s = fsw_thr_map_check(cfg);
  if (s != FSW_OK) { return s; }
  st->num_axes = count_axes(st->C, cfg);
  for (i = 0; i < cfg->num_thr; i++) { st->gt_norm[i] = fsw_v3_norm(cfg->gt_hat_B[i]); }
  st->ready = 1;
  return FSW_OK;
}

/* F <- F - min(0, min_i F_i): shift so the most negative becomes 0. */
static void shift_min(fsw_real *F, int n)
{
  fsw_real fmin = FSW_R(0.0);
  int i;
  for (i = 0; i < n; i++) {
    if (F[i] < fmin) { fmin = F[i]; } }
  for (i = 0; i < n; i++) { F[i] = F[i] - fmin; }
}

/* ---- Minimum-norm mode (docs/fsw/thr_map.md) ----------------------------- */

/* Torque angle error of 8.5 (library variant: compares with [C]^T Lbar). */
static fsw_real torque_angle_error(const FswThrMapState *st, const FswThrMapConfig *cfg,
                                   const fsw_real Lbar[3], const fsw_real *F)
{
  fsw_real Lb_B[3], tau_B[3], c;
  int i, j, k, nc = st->num_axes;
  if (!(fsw_vn_norm(Lbar, nc) > cfg->epsilon)) { return FSW_R(0.0); }
  fsw_v3_zero(Lb_B);
  for (j = 0; j < nc; j++) { fsw_v3_axpy(Lb_B, Lb_B, Lbar[j], st->C[j]); }
  fsw_v3_zero(tau_B);
  for (i = 0; i < cfg->num_thr; i++) {
    fsw_real f = F[i];
    if (!(FSW_FABS(f) < cfg->F_max[i])) { f = (f < FSW_R(0.0)) ? -cfg->F_max[i] : cfg->F_max[i]; }
    for (k = 0; k < 3; k++) { tau_B[k] += f * st->work.D_B[k][i]; }
  }
  (void)fsw_v3_normalize(Lb_B, Lb_B);
  (void)fsw_v3_normalize(tau_B, tau_B);
  c = fsw_v3_dot(Lb_B, tau_B);
  if (!(c < FSW_R(1.0))) { return FSW_R(0.0); }
  if (c < FSW_R(-1.0)) { c = FSW_R(-1.0); }
  c = FSW_ACOS(c);
  return (c < THR_MAP_ANGLE_ROUNDOFF) ? FSW_R(0.0) : c;
}

static FswStatus map_min_norm(FswThrMapState *st, const FswThrMapConfig *cfg,
                              const fsw_real Lbar[3], const uint8_t *avail, fsw_real F[FSW_MAX_EFF])
{
  fsw_real *Fbar = st->work.Fbar;
  const int n = cfg->num_thr, nc = st->num_axes, sF = cfg->thr_force_sign;
  int singular = 0, scaled = 0, i, j;
  FswStatus ks; /* K1 status */

  /* 8.3 first pass over all thrusters.  K1 judges rank by its pivot floor
   * and the delivered residual; FSW_E_BAD_INPUT: F would overflow. */
  ks = fsw_minnorm_solve(F, FSW_CM3N(st->work.CD), Lbar, nc, n);
  if (ks == FSW_E_BAD_INPUT) { return ks; }
  if (ks != FSW_OK) { singular = 1; }
  if (sF > 0) { shift_min(F, n); }
  /* an unavailable thruster (zero column: 0 from the solve) is not shifted on */
  for (i = 0; i < n; i++) {
    if (avail[i] != FSW_AVAILABLE) { F[i] = FSW_R(0.0); } }

  /* 8.4 second pass over S = {i : sF F_i > 0} */
  if (sF < 0 || cfg->use_2nd_loop) {
    int ns = 0, c = 0;
    for (i = 0; i < n; i++) {
      if ((fsw_real)sF * F[i] > FSW_R(0.0)) {
        for (j = 0; j < nc; j++) { st->work.CD_S[j][ns] = st->work.CD[j][i]; }
        ns++;
      }
    }
    /* An empty S (zero request) gives F = 0 without a singular warning. */
    if (ns == 0) {
      fsw_vn_zero(Fbar, FSW_MAX_EFF);
    } else {
      ks = fsw_minnorm_solve(Fbar, FSW_CM3N(st->work.CD_S), Lbar, nc, ns);
      if (ks == FSW_E_BAD_INPUT) { return ks; }
      if (ks != FSW_OK) { singular = 1; }
    }
    if (sF > 0) { shift_min(Fbar, ns); }
    for (i = 0; i < n; i++) {
      if ((fsw_real)sF * F[i] > FSW_R(0.0)) {
        F[i] = Fbar[c];
        c++;
      } else {
        F[i] = FSW_R(0.0);
      }
    }
  }

  /* 8.5 saturation scaling */
  st->ang_err = torque_angle_error(st, cfg, Lbar, F);
  if (st->ang_err > cfg->ang_err_thresh) {
    fsw_real s = FSW_R(0.0);
    for (i = 0; i < n; i++) {
      fsw_real u = FSW_FABS(F[i]) / cfg->F_max[i];
      if (u > s) { s = u; }
    }
    if (s > FSW_R(1.0)) {
      for (i = 0; i < n; i++) { F[i] = F[i] / s; }
      st->ang_err = torque_angle_error(st, cfg, Lbar, F);
      scaled = 1;
    }
  }
  if (singular) { return FSW_W_SINGULAR; }
  return scaled ? FSW_W_SAT : FSW_OK;
}

/* ---- Exact bounded mode (docs/fsw/thr_map.md, NNLS mode) ----------------- */
#if FSW_CFG_THR_NNLS

static FswStatus map_nnls(FswThrMapState *st, const FswThrMapConfig *cfg,
                          const fsw_real Lbar[3], const uint8_t *avail, fsw_real F[FSW_MAX_EFF])
{
  fsw_real *lo = st->work.lo, *hi = st->work.hi, r[3];
  const int n = cfg->num_thr, nc = st->num_axes;
  int i, k;
  for (i = 0; i < n; i++) {
    lo[i] = (cfg->thr_force_sign > 0) ? FSW_R(0.0) : -cfg->F_max[i];
    hi[i] = (cfg->thr_force_sign > 0) ? cfg->F_max[i] : FSW_R(0.0);
    if (avail[i] != FSW_AVAILABLE) { lo[i] = hi[i] = FSW_R(0.0); } /* absent */
  }
  /* K4; its input checks cannot fail here: [C][D] and Lbar were checked
   * finite by the caller and the bounds come from a checked config */
  (void)fsw_bounded_minnorm_solve(F, FSW_CM3N(st->work.CD), Lbar, nc, n, lo,
                                  hi, &st->nnls_iter);
  st->ang_err = FSW_R(0.0);
  for (k = 0; k < nc; k++) {
    fsw_real v = Lbar[k];
    for (i = 0; i < n; i++) { v -= st->work.CD[k][i] * F[i]; }
    r[k] = v;
  }
  /* OK only when the delivered torque is the request: a rank-deficient
   * [C][D] (reduced-axis set) gets the least-squares torque and FSW_W_SAT
   * unless the request lies in its range. */
  if (!(fsw_vn_norm(r, nc) <= THR_NNLS_SAT_TOL * fsw_vn_norm(Lbar, nc))) { return FSW_W_SAT; }
  return FSW_OK;
}
#endif /* FSW_CFG_THR_NNLS */

/* ---- update --------------------------------------------------------------- */

FswStatus fsw_thr_map_update(FswThrMapState *st, const FswThrMapConfig *cfg,
                             const FswThrMapIn *in, FswThrMapOut *out)
{
  fsw_real *F, Lr_B[3], Lbar[3], ang_err_prev, geo[3] = {FSW_R(0.0), FSW_R(0.0), FSW_R(0.0)};
  FswStatus s;
  int i, j, k, n, nc, nnls_iter_prev;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { fsw_vn_zero(out->F, FSW_MAX_THR); } /* safe output */
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    if (st != NULL) { (void)fsw_health_record(&st->health, FSW_E_NULL_ARG); }
    return FSW_E_NULL_ARG;
  }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
#if !FSW_CFG_THR_NNLS
  /* init refused the mode; a configuration changed to it since is refused here */
  if (cfg->mode == FSW_THR_MAP_NNLS) { return fsw_health_record(&st->health, FSW_E_UNSUPPORTED); }
#endif
  n = cfg->num_thr;
  if (!fsw_v3_is_finite(in->Lr_B) || !fsw_v3_is_finite(in->r_CoM_B) ||
      fsw_vn_max_abs(in->r_CoM_B, 3) > FSW_THR_MAP_R_MAX) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  for (i = 0; i < n; i++) {
    if (in->avail[i] > FSW_UNAVAILABLE) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); } }
  nc = st->num_axes;

  /* 8.2: d_i = (r_i - r_CoM) x gt_i; off-pulsing removes the all-on torque */
  fsw_v3_copy(Lr_B, in->Lr_B);
  {
    fsw_real Lr_offset[3];
    fsw_v3_zero(Lr_offset);
    for (i = 0; i < n; i++) {
      fsw_real rel[3], d[3];
      fsw_v3_sub(rel, cfg->r_thr_B[i], in->r_CoM_B);
      fsw_v3_cross(d, rel, cfg->gt_hat_B[i]);
      if (in->avail[i] != FSW_AVAILABLE) { fsw_v3_zero(d); } /* absent: no torque arm, not on */
      for (k = 0; k < 3; k++) { st->work.D_B[k][i] = d[k]; }
      /* [C][D] */
      for (j = 0; j < nc; j++) { st->work.CD[j][i] = fsw_v3_dot(st->C[j], d); }
      {
        /* the geometry on its own scale: c_j . (rel x g) / (|rel| |g|),
         * at most 1 in size (unit rows c_j); row sums of squares in geo */
        const fsw_real len = fsw_v3_norm(rel) * st->gt_norm[i];
        if (len > FSW_R(0.0)) {
          for (j = 0; j < nc; j++) {
            const fsw_real e = st->work.CD[j][i] / len;
            geo[j] += e * e;
          } }
      }
      if (cfg->thr_force_sign < 0) {
        fsw_real Ld[3];
        fsw_v3_scale(Ld, cfg->F_max[i], d);
        fsw_v3_sub(Lr_offset, Lr_offset, Ld);
      }
    }
    fsw_v3_add(Lr_B, Lr_offset, Lr_B);
  }
  /* Lbar = [C] Lr */
  for (j = 0; j < 3; j++) { Lbar[j] = FSW_R(0.0); }
  for (j = 0; j < nc; j++) { Lbar[j] = fsw_v3_dot(st->C[j], Lr_B); }
  if (!fsw_vn_is_finite(Lbar, nc)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }

  F = st->work.F;
  fsw_vn_zero(F, FSW_MAX_EFF);
  ang_err_prev = st->ang_err;
  nnls_iter_prev = st->nnls_iter;
  st->nnls_iter = 0;
  if (!(fsw_vn_max_abs(geo, nc) > FSW_RANK_TOL)) {
    /* Every torque arm is normal to every control axis or passes through
     * the CoM, to within rounding: the entries of [C][D] are noise that
     * K1's scale-invariant test (and K4's residual) would take as a
     * full-rank geometry (docs/fsw-conventions.md "Rank test"). */
    s = FSW_W_SINGULAR; /* F = 0; the diagnostics as each mode sets them */
    st->ang_err = (cfg->mode == FSW_THR_MAP_NNLS) ? FSW_R(0.0) : torque_angle_error(st, cfg, Lbar, F);
#if FSW_CFG_THR_NNLS
  } else if (cfg->mode == FSW_THR_MAP_NNLS) {
    s = map_nnls(st, cfg, Lbar, in->avail, F);
#endif
  } else {
    s = map_min_norm(st, cfg, Lbar, in->avail, F); }
  /* overflow of a finite request is bad input; no NaN/Inf leaves */
  if (fsw_status_is_error(s) || !fsw_vn_is_finite(F, n) || !isfinite(st->ang_err)) {
    st->ang_err = ang_err_prev; /* an error changes no diagnostics either */
    st->nnls_iter = nnls_iter_prev;
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  for (i = 0; i < n; i++) /* an unavailable thruster is commanded off */ {
    if (in->avail[i] != FSW_AVAILABLE) { F[i] = (cfg->thr_force_sign > 0) ? FSW_R(0.0) : -cfg->F_max[i]; } }
  fsw_vn_copy(out->F, F, n);
  return fsw_health_record(&st->health, s);
}

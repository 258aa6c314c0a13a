/* rw_map: minimum-norm and L2 power-optimal (docs/fsw/rw_map.md) wheel
 * torque mapping.  Both are one weighted minimum-norm problem
 *   min sum_k u_k^2 / y_k   s.t.  A u = b,  A = [C][Gs_a],  b = -[C] Lr,
 * with y_k = 1 (min-norm) or y_k = 1/(Omega_k^2 + eps_P) (power), solved as
 * in 5.3: columns scaled by sqrt(y), K1, then scaled back.
 * K1 works on the normal equations, whose rounding grows with cond(A)^2; one
 * step of iterative refinement (r = b - A x, x += K1(A, r)) brings the torque
 * residual back to ~eps * |A| |x| (docs/fsw/rw_map.md asks for 1e-12
 * relative, which badly conditioned 3-wheel sets miss without it).  The
 * correction lies in the row space of A, so x stays the minimum-norm
 * solution. */
#include "fsw/rw_map.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_linalg.h"
#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"
#include "fsw_status_inline.h"
#include "fsw/rw_common.h"
#include "rw_map_internal.h"

FswStatus fsw_rw_map_check(const FswRwMapConfig *cfg)
{
  FswStatus s;
  int j, k;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_rw_check_axes(cfg->gs_hat_B, cfg->num_rw, 1);
  if (s != FSW_OK) { return s; }
  if (cfg->num_axes < 0 || cfg->num_axes > 3) { return FSW_E_CONFIG; }
  for (j = 0; j < cfg->num_axes; j++) {
    if (!fsw_v3_is_finite(cfg->ctrl_axes_B[j])) { return FSW_E_CONFIG; }
    if (FSW_FABS(fsw_v3_norm(cfg->ctrl_axes_B[j]) - FSW_R(1.0)) > FSW_RW_UNIT_TOL) {
      return FSW_E_CONFIG; }
    for (k = 0; k < j; k++) {
      if (FSW_FABS(fsw_v3_dot(cfg->ctrl_axes_B[j], cfg->ctrl_axes_B[k])) > FSW_RW_ORTHO_TOL) {
        return FSW_E_CONFIG; } }
  }
  if (cfg->mode == FSW_RW_MAP_POWER) {
    if (!fsw_rw_all_positive(&cfg->eps_P, 1) || cfg->eps_P < FSW_RW_MAP_EPS_P_MIN ||
        cfg->eps_P > FSW_RW_MAP_EPS_P_MAX) {
      return FSW_E_CONFIG; }
  } else if (cfg->mode != FSW_RW_MAP_MIN_NORM) {
    return FSW_E_CONFIG;
  }
  return FSW_OK;
}

FswStatus fsw_rw_map_init(FswRwMapState *st, const FswRwMapConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  st->work.mn_valid = 0;
  fsw_health_clear(&st->health);
  s = fsw_rw_map_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_rw_map_reset(st);
  return FSW_OK;
}

void fsw_rw_map_reset(FswRwMapState *st)
{
  FSW_ASSERT(st != NULL);
  /* stateless: nothing time-varying to clear; the MIN_NORM factor kept for
   * the last mask (FswRwMapWork) is formed anew at the next update */
  if (st != NULL) { st->work.mn_valid = 0; }
}

/* A = [C][Gs_a] diag(sqrt(y)) over the available wheels, with idx, sy and
 * the count na, and the geometric verdict: FSW_W_SINGULAR when fewer than
 * nc wheels are available or no control axis is reachable (the floor
 * below), else FSW_OK with K1's factor of A in w->k1. */
static FswStatus form_map(FswRwMapWork *w, const FswRwMapConfig *cfg, const fsw_real *Omega, const uint8_t *avail,
                          int *na_out)
{
  fsw_real d, d_max = FSW_R(0.0);
  const int n = cfg->num_rw, nc = cfg->num_axes;
  int na = 0, i, j, k;
  for (i = 0; i < n; i++) {
    if (avail[i] != FSW_AVAILABLE) { continue; }
    w->idx[na] = i;
    /* y = 1/W, W = Omega^2 + eps_P; Omega^2 overflowing gives y = 0 */
    w->sy[na] = (cfg->mode == FSW_RW_MAP_POWER)
                    ? FSW_SQRT(FSW_R(1.0) / (Omega[i] * Omega[i] + cfg->eps_P))
                    : FSW_R(1.0);
    na++;
  }
  *na_out = na;
  if (na < nc) { return FSW_W_SINGULAR; }
  for (j = 0; j < nc; j++) {
    d = FSW_R(0.0);
    for (k = 0; k < na; k++) {
      const fsw_real m = fsw_v3_dot(cfg->ctrl_axes_B[j], cfg->gs_hat_B[w->idx[k]]);
      d += m * m;
      w->A[j][k] = m;
    }
    if (d > d_max) { d_max = d; }
  }
  /* POWER: the columns scaled by sqrt(y).  The weights scale them against
   * each other without bound (a speed whose square overflows weighs 0), so
   * a wheel that reaches no control axis beyond rounding (its column's sum
   * of squares <= FSW_RANK_TOL, the floor below taken wheel by wheel) could
   * outweigh the wheels that do and carry the torque: its column is 0. */
  if (cfg->mode == FSW_RW_MAP_POWER) {
    for (k = 0; k < na; k++) {
      d = FSW_R(0.0);
      for (j = 0; j < nc; j++) { d += w->A[j][k] * w->A[j][k]; }
      for (j = 0; j < nc; j++) { w->A[j][k] = (d > FSW_RANK_TOL) ? (w->A[j][k] * w->sy[k]) : FSW_R(0.0); }
    }
  }
  /* The geometry [C][Gs_a] is dimensionless (unit rows and columns, so
   * each entry is at most 1 in size): when every entry is at the rounding
   * level of such products (sum of squares of the largest row <=
   * FSW_RANK_TOL), no control axis can be reached, however the entries'
   * rounding noise makes K1's scale-invariant test see a full-rank A
   * (a single wheel at 90 deg to a single control axis: c . g ~ 1e-17). */
  if (!(d_max > FSW_RANK_TOL)) { return FSW_W_SINGULAR; }
  (void)fsw_minnorm_factor(&w->k1, FSW_CM3N(w->A), nc, na);
  return FSW_OK;
}

FswStatus fsw_rw_map_update(FswRwMapState *st, const FswRwMapConfig *cfg,
                            const FswRwMapIn *in, FswRwMapOut *out)
{
  int n;
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { fsw_rw_zero(out->u_s); } /* safe output */
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_rw;
  if (!fsw_v3_is_finite(in->Lr_B) || !fsw_rw_avail_valid(in->avail, n) ||
      (cfg->mode == FSW_RW_MAP_POWER && !fsw_rw_avail_finite(in->Omega, in->avail, n))) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  return fsw_rw_map_torques(st, cfg, in->Lr_B, in->Omega, in->avail, out);
}

FswStatus fsw_rw_map_torques(FswRwMapState *st, const FswRwMapConfig *cfg, const fsw_real Lr_B[3],
                             const fsw_real Omega[FSW_MAX_RW], const uint8_t avail[FSW_MAX_RW],
                             FswRwMapOut *out)
{
  fsw_real b[3], r[3];
  FswRwMapWork *w;
  int n, nc, na, i, j, k, refine;
  FswStatus s;

  fsw_rw_zero(out->u_s); /* safe output */
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  w = &st->work;
  n = cfg->num_rw;
  nc = cfg->num_axes;
  /* Lr is checked here too: the application's Lr is the control law's
   * torque less a momentum dump's, a difference that can overflow */
  if (!fsw_v3_is_finite(Lr_B)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  if (nc == 0) { return fsw_health_record_ok_i(&st->health); }

  if (cfg->mode == FSW_RW_MAP_MIN_NORM && w->mn_valid) {
    if (memcmp(w->mn_avail, avail, (size_t)n) != 0) { w->mn_valid = 0; } /* another mask */
  }
  if (cfg->mode == FSW_RW_MAP_MIN_NORM && w->mn_valid) {
    na = w->mn_na; /* A, idx, sy and k1 as formed for this mask */
    s = w->mn_geo;
  } else {
    s = form_map(w, cfg, Omega, avail, &na);
    if (cfg->mode == FSW_RW_MAP_MIN_NORM) {
      for (i = 0; i < n; i++) { w->mn_avail[i] = avail[i]; }
      w->mn_na = na;
      w->mn_geo = s;
      w->mn_valid = 1;
    }
  }
  if (s != FSW_OK) { return fsw_health_record(&st->health, s); }

  for (j = 0; j < nc; j++) { b[j] = -fsw_v3_dot(cfg->ctrl_axes_B[j], Lr_B); }
  /* K1 judges rank by its pivot floor and by the delivered residual
   * (fsw_linalg.h); FSW_E_BAD_INPUT from it means b = -[C] Lr or the
   * solution overflows the real type (finite but huge Lr). */
  s = fsw_minnorm_solve_factored(w->x, &w->k1, FSW_CM3N(w->A), b);
  if (s == FSW_E_SINGULAR) { return fsw_health_record(&st->health, FSW_W_SINGULAR); }
  if (s != FSW_OK) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  for (j = 0; j < nc; j++) { r[j] = b[j] - fsw_vn_dot(w->A[j], w->x, na); }
  /* the correction, when its solve succeeds, added in the output pass */
  refine = 0;
  if (fsw_minnorm_solve_factored(w->dx, &w->k1, FSW_CM3N(w->A), r) == FSW_OK) { refine = 1; }
  for (k = 0; k < na; k++) {
    fsw_real xk = w->x[k];
    fsw_real u;
    if (refine != 0) { xk += w->dx[k]; }
    u = xk * w->sy[k];
    if (!isfinite(u)) { /* overflow of a finite request: bad input, u = 0 */
      fsw_rw_zero(out->u_s);
      return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
    }
    out->u_s[w->idx[k]] = u;
  }
  return fsw_health_record_ok_i(&st->health);
}

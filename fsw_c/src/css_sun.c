/* css_sun: Sun heading from coarse sun sensors (docs/fsw/css_sun.md). */
#include "fsw/css_sun.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"
#include "fsw_status_inline.h"
#include "css_sun_internal.h"

static void write_safe(FswCssSunOut *out)
{
  fsw_v3_zero(out->sun_hat_B);
  out->sun_mag = FSW_R(0.0);
  out->sun_valid = 0;
  out->num_lit = 0;
  out->mode = FSW_CSS_SUN_NONE;
}

FswStatus fsw_css_sun_check(const FswCssSunConfig *cfg)
{
  int i;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (cfg->num_css < 1) { return FSW_E_CONFIG; }
  if (cfg->num_css > FSW_MAX_CSS) { return FSW_E_CAPACITY; }
  if (!isfinite(cfg->lit_threshold) || cfg->lit_threshold < FSW_R(0.0) ||
      !(cfg->lit_threshold < FSW_R(1.0))) {
    return FSW_E_CONFIG;
  }
  for (i = 0; i < cfg->num_css; i++) {
    if (!fsw_v3_is_finite(cfg->n_hat_B[i])) { return FSW_E_CONFIG; }
    if (!(FSW_FABS(fsw_v3_norm(cfg->n_hat_B[i]) - FSW_R(1.0)) <= FSW_CSS_SUN_UNIT_TOL)) {
      return FSW_E_CONFIG;
    }
    if (!isfinite(cfg->scale[i]) || !(cfg->scale[i] > FSW_R(0.0))) { return FSW_E_CONFIG; }
  }
  return FSW_OK;
}

FswStatus fsw_css_sun_init(FswCssSunState *st, const FswCssSunConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  (void)memset(st, 0, sizeof *st);
  fsw_health_clear(&st->health);
  s = fsw_css_sun_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_css_sun_reset(st);
  return FSW_OK;
}

void fsw_css_sun_reset(FswCssSunState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* stateless */
}

/* Solve M x = c for symmetric M by Cholesky in fixed order (k = 0, 1, 2).
 * Returns 0 (x = 0) when a pivot is <= FSW_CSS_SUN_RANK_TOL * max_j M_jj or
 * max_j M_jj is not positive: the same scale-invariant test as kernel K1. */
static int chol3_solve(fsw_real x[3], const fsw_real M[3][3], const fsw_real c[3])
{
  fsw_real L[3][3];
  fsw_real y[3];
  fsw_real dmax = M[0][0];
  fsw_real tol;
  int i, j, k;
  if (M[1][1] > dmax) { dmax = M[1][1]; }
  if (M[2][2] > dmax) { dmax = M[2][2]; }
  fsw_v3_zero(x);
  if (!(dmax > FSW_R(0.0))) { return 0; }
  tol = FSW_CSS_SUN_RANK_TOL * dmax;
  for (k = 0; k < 3; k++) {
    fsw_real p = M[k][k];
    for (j = 0; j < k; j++) { p -= L[k][j] * L[k][j]; }
    if (!(p > tol)) { return 0; }
    L[k][k] = FSW_SQRT(p);
    for (i = k + 1; i < 3; i++) {
      fsw_real s = M[i][k];
      for (j = 0; j < k; j++) { s -= L[i][j] * L[k][j]; }
      L[i][k] = s / L[k][k];
    }
  }
  for (i = 0; i < 3; i++) { /* L y = c */
    fsw_real s = c[i];
    for (j = 0; j < i; j++) { s -= L[i][j] * y[j]; }
    y[i] = s / L[i][i];
  }
  for (i = 2; i >= 0; i--) { /* L^T x = y */
    fsw_real s = y[i];
    for (j = i + 1; j < 3; j++) { s -= L[j][i] * x[j]; }
    x[i] = s / L[i][i];
  }
  return 1;
}

static int in_ok(const FswCssSunConfig *cfg, const FswCssSunIn *in)
{
  int i;
  for (i = 0; i < cfg->num_css; i++) {
    if (in->avail[i] == FSW_AVAILABLE) {
      if (!isfinite(in->reading[i])) { return 0; }
    } else if (in->avail[i] != FSW_UNAVAILABLE) {
      return 0;
    }
  }
  return 1;
}

FswStatus fsw_css_sun_update(FswCssSunState *st, const FswCssSunConfig *cfg,
                             const FswCssSunIn *in, FswCssSunOut *out)
{
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { write_safe(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    return fsw_health_record(st != NULL ? &st->health : NULL, FSW_E_NULL_ARG);
  }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (!in_ok(cfg, in)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  return fsw_css_sun_estimate(st, cfg, in->reading, in->avail, out);
}

FswStatus fsw_css_sun_estimate(FswCssSunState *st, const FswCssSunConfig *cfg,
                               const fsw_real reading[FSW_MAX_CSS], const uint8_t avail[FSW_MAX_CSS],
                               FswCssSunOut *out)
{
  fsw_real y[FSW_MAX_CSS];     /* [-] normalised readings (cosines) */
  uint8_t lit[FSW_MAX_CSS];    /* [-] 1 if lit */
  fsw_real M[3][3];            /* [-] sum w n n^T, lower triangle (all chol3_solve reads) */
  fsw_real c[3];               /* [-] sum w y n   */
  fsw_real x[3];               /* [-] unnormalised estimate */
  fsw_real x_norm;
  int num_lit = 0;
  int a = -1, b = -1;          /* brightest lit sensor, brightest non-parallel partner */
  int i, j, k;

  write_safe(out);
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }

  /* lit set and weighted normal equations */
  fsw_m33_zero(M);
  fsw_v3_zero(c);
  for (i = 0; i < cfg->num_css; i++) {
    lit[i] = 0u;
    y[i] = FSW_R(0.0);
    if (avail[i] != FSW_AVAILABLE) { continue; }
    y[i] = reading[i] / cfg->scale[i];
    if (!isfinite(y[i])) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); } /* overflow */
    if (!(y[i] > cfg->lit_threshold)) { continue; }
    lit[i] = 1u;
    num_lit++;
    if (a < 0 || y[i] > y[a]) { a = i; }
    for (j = 0; j < 3; j++) {
      for (k = 0; k <= j; k++) { M[j][k] += y[i] * cfg->n_hat_B[i][j] * cfg->n_hat_B[i][k]; }
      c[j] += y[i] * y[i] * cfg->n_hat_B[i][j];
    }
  }
  /* Overflow of huge readings.  c is finite only if M is: a lit y_i whose
   * square overflows makes the term y_i^2 n_ij infinite (or NaN) for the
   * j where n_ij != 0, and c_j with it; while every y_i^2 is finite,
   * y_i <= sqrt(max real) (times 1 + eps), and the at most FSW_MAX_CSS
   * terms y_i n_ij n_ik of an entry of M, each at most y_i (1 + tol)^2, sum
   * to far below the largest real.  So testing c decides as testing M and
   * c did. */
  if (!fsw_v3_is_finite(c)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  out->num_lit = num_lit;

  if (num_lit >= 3 && chol3_solve(x, FSW_CM33(M), c)) {
    if (fsw_v3_norm_normalize(out->sun_hat_B, &x_norm, x)) {
      out->sun_mag = x_norm;
      out->sun_valid = 1;
      out->mode = FSW_CSS_SUN_WLS;
      return fsw_health_record_ok_i(&st->health);
    }
  }
  if (a < 0) { return fsw_health_record(&st->health, FSW_W_SINGULAR); } /* NONE */

  /* brightest partner of a whose normal is not parallel to n_a */
  for (i = 0; i < cfg->num_css; i++) {
    fsw_real cab;
    if (!lit[i] || i == a) { continue; }
    cab = fsw_v3_dot(cfg->n_hat_B[a], cfg->n_hat_B[i]);
    if (!(FSW_R(1.0) - cab * cab > FSW_CSS_SUN_RANK_TOL)) { continue; }
    if (b < 0 || y[i] > y[b]) { b = i; }
  }
  if (b >= 0) {
    /* x = alpha n_a + beta n_b with [1 cab; cab 1][alpha; beta] = [y_a; y_b] */
    const fsw_real cab = fsw_v3_dot(cfg->n_hat_B[a], cfg->n_hat_B[b]);
    const fsw_real det = FSW_R(1.0) - cab * cab;
    const fsw_real alpha = (y[a] - cab * y[b]) / det;
    const fsw_real beta = (y[b] - cab * y[a]) / det;
    fsw_v3_scale(x, alpha, cfg->n_hat_B[a]);
    fsw_v3_axpy(x, x, beta, cfg->n_hat_B[b]);
    if (fsw_v3_norm_normalize(out->sun_hat_B, &x_norm, x)) {
      out->sun_mag = x_norm;
      out->sun_valid = 1;
      out->mode = FSW_CSS_SUN_TWO;
      return fsw_health_record(&st->health, FSW_W_SINGULAR);
    }
  }
  fsw_v3_copy(out->sun_hat_B, cfg->n_hat_B[a]);
  out->sun_mag = y[a];
  out->sun_valid = 1;
  out->mode = FSW_CSS_SUN_ONE;
  return fsw_health_record(&st->health, FSW_W_SINGULAR);
}

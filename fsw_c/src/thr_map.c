/* thr_map: thruster force mapping, fsw-algorithms.md 8 (Basilisk
 * thrForceMapping) with the opt-in exact bounded mode of 8.6. */
#include "fsw/thr_map.h"

#include <stddef.h>

#include "fsw/fsw_linalg.h"
#include "fsw/fsw_vec.h"

/* Saturation angle below which the torque angle error is treated as 0: the
 * angle of two parallel vectors computed in floating point is ~1e-8 rad in
 * double (fsw-algorithms.md 8.5, defect b: 1e-6 rad).  In single precision
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

/* Relative round-off tolerance of the active-set method (NNLS mode): a
 * residual, gradient or step below THR_NNLS_TOL times its natural scale is
 * zero. */
#define THR_NNLS_TOL (FSW_R(1000.0) * FSW_REAL_EPS)
/* Relative torque error above which the NNLS result reports FSW_W_SAT. */
#define THR_NNLS_SAT_TOL (FSW_R(10000.0) * FSW_REAL_EPS)
/* Fixed iteration budget of the active-set method: THR_NNLS_ITER_PER_THR
 * times the thruster count (both phases together). */
#define THR_NNLS_ITER_PER_THR 3

/* Variable status of the active-set method. */
#define THR_NNLS_FREE 0
#define THR_NNLS_AT_LO 1
#define THR_NNLS_AT_HI 2

/* Count the control axes (rows up to the first with norm <= epsilon) and
 * write them normalised into C.  Returns the count (0..3). */
static int count_axes(fsw_real C[3][3], const FswThrMapConfig *cfg)
{
  int nc = 0, j;
  fsw_m33_zero(C);
  for (j = 0; j < 3; j++) {
    fsw_real n = fsw_v3_norm(cfg->control_axes_B[j]);
    if (!(n > cfg->epsilon) || !isfinite(n)) break;
    fsw_v3_scale(C[j], FSW_R(1.0) / n, cfg->control_axes_B[j]);
    nc++;
  }
  return nc;
}

FswStatus fsw_thr_map_check(const FswThrMapConfig *cfg)
{
  fsw_real C[3][3], L[3][3];
  int i, j, nc;

  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) return FSW_E_NULL_ARG;
  if (cfg->num_thr > FSW_MAX_THR) return FSW_E_CAPACITY;
  if (cfg->num_thr < 1) return FSW_E_CONFIG;
  if (cfg->thr_force_sign != 1 && cfg->thr_force_sign != -1) return FSW_E_CONFIG;
  if (cfg->use_2nd_loop != 0 && cfg->use_2nd_loop != 1) return FSW_E_CONFIG;
  if (cfg->mode != FSW_THR_MAP_MIN_NORM && cfg->mode != FSW_THR_MAP_NNLS) return FSW_E_CONFIG;
  if (!isfinite(cfg->epsilon) || cfg->epsilon < FSW_R(0.0)) return FSW_E_CONFIG;
  if (!isfinite(cfg->ang_err_thresh) || cfg->ang_err_thresh < FSW_R(0.0)) return FSW_E_CONFIG;
  for (j = 0; j < 3; j++)
    if (!fsw_v3_is_finite(cfg->control_axes_B[j])) return FSW_E_CONFIG;
  for (i = 0; i < cfg->num_thr; i++) {
    if (!fsw_v3_is_finite(cfg->r_thr_B[i]) || !fsw_v3_is_finite(cfg->gt_hat_B[i]))
      return FSW_E_CONFIG;
    if (FSW_FABS(fsw_v3_norm(cfg->gt_hat_B[i]) - FSW_R(1.0)) > THR_MAP_UNIT_TOL)
      return FSW_E_CONFIG;
    if (!isfinite(cfg->F_max[i]) || !(cfg->F_max[i] > FSW_R(0.0))) return FSW_E_CONFIG;
  }
  nc = count_axes(C, cfg);
  if (nc == 0) return FSW_E_CONFIG;
  /* The counted (unit) axes must be independent: the K1 rank rule applied
   * to [C]: Cholesky of [C][C]^T, fail if a pivot <= FSW_RANK_TOL * max diag
   * (max diag = 1 for unit rows). */
  for (j = 0; j < nc; j++) {
    for (i = 0; i < j; i++) {
      fsw_real v = fsw_v3_dot(C[j], C[i]);
      int k;
      for (k = 0; k < i; k++) v -= L[j][k] * L[i][k];
      L[j][i] = v / L[i][i];
    }
    {
      fsw_real d = fsw_v3_dot(C[j], C[j]);
      int k;
      for (k = 0; k < j; k++) d -= L[j][k] * L[j][k];
      if (!(d > FSW_RANK_TOL)) return FSW_E_SINGULAR;
      L[j][j] = FSW_SQRT(d);
    }
  }
  return FSW_OK;
}

void fsw_thr_map_reset(FswThrMapState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) return;
  st->ang_err = FSW_R(0.0);
  st->nnls_iter = 0;
}

FswStatus fsw_thr_map_init(FswThrMapState *st, const FswThrMapConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) return FSW_E_NULL_ARG;
  st->ready = 0;
  st->num_axes = 0;
  fsw_m33_zero(st->C);
  fsw_health_clear(&st->health);
  fsw_thr_map_reset(st);
  s = fsw_thr_map_check(cfg);
  if (s != FSW_OK) return s;
  st->num_axes = count_axes(st->C, cfg);
  st->ready = 1;
  return FSW_OK;
}

/* F <- F - min(0, min_i F_i) (8.3): shift so the most negative becomes 0. */
static void shift_min(fsw_real *F, int n)
{
  fsw_real fmin = FSW_R(0.0);
  int i;
  for (i = 0; i < n; i++)
    if (F[i] < fmin) fmin = F[i];
  for (i = 0; i < n; i++) F[i] = F[i] - fmin;
}

/* ---- Minimum-norm mode (8.3-8.5) ---------------------------------------- */

/* Torque angle error of 8.5 (library variant: compares with [C]^T Lbar). */
static fsw_real torque_angle_error(const FswThrMapState *st, const FswThrMapConfig *cfg,
                                   const fsw_real Lbar[3], const fsw_real *F)
{
  fsw_real Lb_B[3], tau_B[3], c;
  int i, j, k, nc = st->num_axes;
  if (!(fsw_vn_norm(Lbar, nc) > cfg->epsilon)) return FSW_R(0.0);
  fsw_v3_zero(Lb_B);
  for (j = 0; j < nc; j++) fsw_v3_axpy(Lb_B, Lb_B, Lbar[j], st->C[j]);
  fsw_v3_zero(tau_B);
  for (i = 0; i < cfg->num_thr; i++) {
    fsw_real f = F[i];
    if (!(FSW_FABS(f) < cfg->F_max[i])) f = (f < FSW_R(0.0)) ? -cfg->F_max[i] : cfg->F_max[i];
    for (k = 0; k < 3; k++) tau_B[k] += f * st->work.D_B[k][i];
  }
  (void)fsw_v3_normalize(Lb_B, Lb_B);
  (void)fsw_v3_normalize(tau_B, tau_B);
  c = fsw_v3_dot(Lb_B, tau_B);
  if (!(c < FSW_R(1.0))) return FSW_R(0.0);
  if (c < FSW_R(-1.0)) c = FSW_R(-1.0);
  c = FSW_ACOS(c);
  return (c < THR_MAP_ANGLE_ROUNDOFF) ? FSW_R(0.0) : c;
}

static FswStatus map_min_norm(FswThrMapState *st, const FswThrMapConfig *cfg,
                              const fsw_real Lbar[3], fsw_real F[FSW_MAX_EFF])
{
  fsw_real *Fbar = st->work.Fbar;
  const int n = cfg->num_thr, nc = st->num_axes, sF = cfg->thr_force_sign;
  int singular = 0, scaled = 0, i, j;

  /* 8.3 first pass over all thrusters */
  if (fsw_minnorm_solve(F, FSW_CM3N(st->work.CD), Lbar, nc, n) != FSW_OK) singular = 1;
  if (sF > 0) shift_min(F, n);

  /* 8.4 second pass over S = {i : sF F_i > 0} */
  if (sF < 0 || cfg->use_2nd_loop) {
    int ns = 0, c = 0;
    for (i = 0; i < n; i++) {
      if ((fsw_real)sF * F[i] > FSW_R(0.0)) {
        for (j = 0; j < nc; j++) st->work.CD_S[j][ns] = st->work.CD[j][i];
        ns++;
      }
    }
    /* An empty S (zero request) gives F = 0 without a singular warning. */
    if (ns == 0)
      fsw_vn_zero(Fbar, FSW_MAX_EFF);
    else if (fsw_minnorm_solve(Fbar, FSW_CM3N(st->work.CD_S), Lbar, nc, ns) != FSW_OK)
      singular = 1;
    if (sF > 0) shift_min(Fbar, ns);
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
      if (u > s) s = u;
    }
    if (s > FSW_R(1.0)) {
      for (i = 0; i < n; i++) F[i] = F[i] / s;
      st->ang_err = torque_angle_error(st, cfg, Lbar, F);
      scaled = 1;
    }
  }
  if (singular) return FSW_W_SINGULAR;
  return scaled ? FSW_W_SAT : FSW_OK;
}

/* ---- Exact bounded mode (8.6) -------------------------------------------- */

/* Solve M x = rhs for a symmetric positive semi-definite m x m matrix M by
 * LDL^T in fixed order.  A pivot <= FSW_RANK_TOL * max diag is dropped (its
 * component of the solution is 0), so a consistent rhs is solved exactly
 * even when M is singular. */
static void psd_solve(fsw_real x[3], const fsw_real M[3][3], const fsw_real rhs[3], int m)
{
  fsw_real L[3][3], d[3], y[3], dmax = FSW_R(0.0);
  int keep[3], i, j, k;
  for (k = 0; k < m; k++)
    if (M[k][k] > dmax) dmax = M[k][k];
  for (k = 0; k < m; k++) {
    fsw_real v = M[k][k];
    for (j = 0; j < k; j++) v -= L[k][j] * L[k][j] * d[j];
    keep[k] = (dmax > FSW_R(0.0) && v > FSW_RANK_TOL * dmax);
    d[k] = keep[k] ? v : FSW_R(0.0);
    L[k][k] = FSW_R(1.0);
    for (i = k + 1; i < m; i++) {
      fsw_real w = M[i][k];
      for (j = 0; j < k; j++) w -= L[i][j] * L[k][j] * d[j];
      L[i][k] = keep[k] ? w / d[k] : FSW_R(0.0);
    }
  }
  for (k = 0; k < m; k++) {
    fsw_real v = rhs[k];
    for (j = 0; j < k; j++) v -= L[k][j] * y[j];
    y[k] = v;
  }
  for (k = m - 1; k >= 0; k--) {
    fsw_real v = keep[k] ? y[k] / d[k] : FSW_R(0.0);
    for (i = k + 1; i < m; i++) v -= L[i][k] * x[i];
    x[k] = v;
  }
  for (k = m; k < 3; k++) x[k] = FSW_R(0.0);
}

/* Column i of A dotted with an m-vector. */
static fsw_real col_dot(const fsw_real A[3][FSW_MAX_EFF], int i, const fsw_real v[3], int m)
{
  fsw_real s = FSW_R(0.0);
  int k;
  for (k = 0; k < m; k++) s += A[k][i] * v[k];
  return s;
}

/* Bounded least squares then least norm:
 *   phase 1 (Lawson-Hanson / BVLS style): minimise |A F - b| subject to
 *     lo <= F <= hi, starting from F = 0 (0 must be lo_i or hi_i); the free
 *     set keeps at most m independent columns;
 *   phase 2 (primal active set): keeping A F fixed at the phase-1 value,
 *     minimise |F| subject to the bounds; steps in the null space of the
 *     free columns, so the delivered torque never changes.
 * At most THR_NNLS_ITER_PER_THR * n subproblem solves; ties go to the
 * lowest index.  F always stays within [lo, hi].  Returns the iteration
 * count. */
static int nnls_solve(fsw_real F[FSW_MAX_EFF], const fsw_real A[3][FSW_MAX_EFF],
                      const fsw_real b[3], int m, int n, const fsw_real lo[FSW_MAX_EFF],
                      const fsw_real hi[FSW_MAX_EFF])
{
  signed char stat[FSW_MAX_EFF];
  int P[3], np = 0, it = 0, i, j, k, q;
  const int budget = THR_NNLS_ITER_PER_THR * n;
  fsw_real bnorm = fsw_vn_norm(b, m), fscale = FSW_R(0.0);

  for (i = 0; i < n; i++) {
    F[i] = FSW_R(0.0);
    stat[i] = (lo[i] == FSW_R(0.0)) ? THR_NNLS_AT_LO : THR_NNLS_AT_HI;
    if (hi[i] - lo[i] > fscale) fscale = hi[i] - lo[i];
  }

  /* ---- phase 1 ---- */
  while (it < budget && np < m) {
    fsw_real r[3], gbest = FSW_R(0.0);
    int best = -1, first = 1;
    for (k = 0; k < m; k++) {
      fsw_real v = b[k];
      for (i = 0; i < n; i++) v -= A[k][i] * F[i];
      r[k] = v;
    }
    if (fsw_vn_norm(r, m) <= THR_NNLS_TOL * bnorm) break;
    for (i = 0; i < n; i++) {
      fsw_real g, an2 = FSW_R(0.0);
      if (stat[i] == THR_NNLS_FREE) continue;
      for (k = 0; k < m; k++) an2 += A[k][i] * A[k][i];
      g = col_dot(A, i, r, m);
      if (stat[i] == THR_NNLS_AT_HI) g = -g;
      if (g > THR_NNLS_TOL * bnorm * FSW_SQRT(an2) && g > gbest) {
        gbest = g;
        best = i;
      }
    }
    if (best < 0) break;
    /* insert into P keeping index order */
    for (q = np; q > 0 && P[q - 1] > best; q--) P[q] = P[q - 1];
    P[q] = best;
    np++;
    {
      const int entering_at_lo = (stat[best] == THR_NNLS_AT_LO);
      int stop = 0;
      stat[best] = THR_NNLS_FREE;
      while (it < budget) {
        fsw_real G[3][3], rhs[3], r0[3], z[3], alpha = FSW_R(1.0);
        int blk = -1;
        it++;
        /* r0 = b - sum over fixed columns; LS on the free columns */
        for (k = 0; k < m; k++) {
          fsw_real v = b[k];
          for (i = 0; i < n; i++)
            if (stat[i] != THR_NNLS_FREE) v -= A[k][i] * F[i];
          r0[k] = v;
        }
        for (q = 0; q < np; q++) {
          for (j = 0; j < np; j++) {
            fsw_real v = FSW_R(0.0);
            for (k = 0; k < m; k++) v += A[k][P[q]] * A[k][P[j]];
            G[q][j] = v;
          }
          rhs[q] = col_dot(A, P[q], r0, m);
        }
        psd_solve(z, FSW_CM33(G), rhs, np);
        if (first) {
          /* The entering variable must move into the box (exact arithmetic
           * guarantees it; round-off may not).  Otherwise undo and stop. */
          for (q = 0; q < np && P[q] != best; q++) {
          }
          if (entering_at_lo ? !(z[q] > lo[best]) : !(z[q] < hi[best])) {
            stat[best] = entering_at_lo ? THR_NNLS_AT_LO : THR_NNLS_AT_HI;
            for (; q + 1 < np; q++) P[q] = P[q + 1];
            np--;
            stop = 1;
            break;
          }
          first = 0;
        }
        for (q = 0; q < np; q++) {
          i = P[q];
          if (z[q] <= lo[i] || z[q] >= hi[i]) {
            fsw_real bound = (z[q] <= lo[i]) ? lo[i] : hi[i];
            fsw_real a = (bound - F[i]) / (z[q] - F[i]);
            if (!(a > FSW_R(0.0))) a = FSW_R(0.0);
            if (blk < 0 || a < alpha) {
              alpha = a;
              blk = q;
            }
          }
        }
        if (blk < 0) {
          for (q = 0; q < np; q++) F[P[q]] = z[q];
          break;
        }
        if (alpha > FSW_R(1.0)) alpha = FSW_R(1.0);
        for (q = 0; q < np; q++) F[P[q]] = F[P[q]] + alpha * (z[q] - F[P[q]]);
        /* fix the blocking variable and any other that reached a bound */
        {
          const int ib = P[blk];
          const int ib_lo = (z[blk] <= lo[ib]);
          F[ib] = ib_lo ? lo[ib] : hi[ib];
          stat[ib] = ib_lo ? THR_NNLS_AT_LO : THR_NNLS_AT_HI;
          for (q = 0; q < np; q++) {
            i = P[q];
            if (stat[i] != THR_NNLS_FREE) continue;
            if (F[i] <= lo[i]) {
              F[i] = lo[i];
              stat[i] = THR_NNLS_AT_LO;
            } else if (F[i] >= hi[i]) {
              F[i] = hi[i];
              stat[i] = THR_NNLS_AT_HI;
            }
          }
          for (j = 0, q = 0; q < np; q++)
            if (stat[P[q]] == THR_NNLS_FREE) P[j++] = P[q];
          np = j;
        }
      }
      if (stop) break;
    }
  }

  /* ---- phase 2 ---- */
  while (it < budget) {
    fsw_real M[3][3], c[3], lam[3], alpha = FSW_R(1.0), pmax = FSW_R(0.0), vbest;
    int blk = -1, best = -1, blk_lo = 0;
    it++;
    for (k = 0; k < m; k++) {
      for (j = 0; j <= k; j++) {
        fsw_real v = FSW_R(0.0);
        for (i = 0; i < n; i++)
          if (stat[i] == THR_NNLS_FREE) v += A[k][i] * A[j][i];
        M[k][j] = v;
        M[j][k] = v;
      }
      {
        fsw_real v = FSW_R(0.0);
        for (i = 0; i < n; i++)
          if (stat[i] == THR_NNLS_FREE) v += A[k][i] * F[i];
        c[k] = v;
      }
    }
    psd_solve(lam, FSW_CM33(M), c, m);
    for (i = 0; i < n; i++) {
      fsw_real p;
      if (stat[i] != THR_NNLS_FREE) continue;
      p = col_dot(A, i, lam, m) - F[i];
      if (FSW_FABS(p) > pmax) pmax = FSW_FABS(p);
    }
    if (pmax > THR_NNLS_TOL * fscale) {
      /* step toward the minimum-norm point of the free set, ratio test */
      for (i = 0; i < n; i++) {
        fsw_real z;
        if (stat[i] != THR_NNLS_FREE) continue;
        z = col_dot(A, i, lam, m);
        if (z < lo[i] || z > hi[i]) {
          fsw_real bound = (z < lo[i]) ? lo[i] : hi[i];
          fsw_real a = (bound - F[i]) / (z - F[i]);
          if (!(a > FSW_R(0.0))) a = FSW_R(0.0);
          if (blk < 0 || a < alpha) {
            alpha = a;
            blk = i;
            blk_lo = (z < lo[i]);
          }
        }
      }
      if (alpha > FSW_R(1.0)) alpha = FSW_R(1.0);
      for (i = 0; i < n; i++) {
        fsw_real z;
        if (stat[i] != THR_NNLS_FREE) continue;
        z = col_dot(A, i, lam, m);
        F[i] = F[i] + alpha * (z - F[i]);
        if (F[i] < lo[i]) F[i] = lo[i];
        if (F[i] > hi[i]) F[i] = hi[i];
      }
      if (blk >= 0) {
        F[blk] = blk_lo ? lo[blk] : hi[blk];
        stat[blk] = blk_lo ? THR_NNLS_AT_LO : THR_NNLS_AT_HI;
        continue;
      }
      /* full step: F is now the minimiser on the free set and lam its
       * multiplier, so the optimality test below needs no new solve */
    }
    /* stationary on the free set: release the bound with the largest
     * multiplier of the wrong sign */
    vbest = THR_NNLS_TOL * fscale;
    for (i = 0; i < n; i++) {
      fsw_real g, v;
      if (stat[i] == THR_NNLS_FREE) continue;
      g = col_dot(A, i, lam, m);
      v = (stat[i] == THR_NNLS_AT_LO) ? g - lo[i] : hi[i] - g;
      if (v > vbest) {
        vbest = v;
        best = i;
      }
    }
    if (best < 0) break;
    stat[best] = THR_NNLS_FREE;
  }
  return it;
}

static FswStatus map_nnls(FswThrMapState *st, const FswThrMapConfig *cfg,
                          const fsw_real Lbar[3], fsw_real F[FSW_MAX_EFF])
{
  fsw_real *lo = st->work.lo, *hi = st->work.hi, r[3];
  const int n = cfg->num_thr, nc = st->num_axes;
  int i, k;
  for (i = 0; i < n; i++) {
    lo[i] = (cfg->thr_force_sign > 0) ? FSW_R(0.0) : -cfg->F_max[i];
    hi[i] = (cfg->thr_force_sign > 0) ? cfg->F_max[i] : FSW_R(0.0);
  }
  st->nnls_iter = nnls_solve(F, FSW_CM3N(st->work.CD), Lbar, nc, n, lo, hi);
  st->ang_err = FSW_R(0.0);
  for (k = 0; k < nc; k++) {
    fsw_real v = Lbar[k];
    for (i = 0; i < n; i++) v -= st->work.CD[k][i] * F[i];
    r[k] = v;
  }
  if (fsw_vn_norm(r, nc) > THR_NNLS_SAT_TOL * fsw_vn_norm(Lbar, nc)) return FSW_W_SAT;
  return FSW_OK;
}

/* ---- update --------------------------------------------------------------- */

FswStatus fsw_thr_map_update(FswThrMapState *st, const FswThrMapConfig *cfg,
                             const FswThrMapIn *in, FswThrMapOut *out)
{
  fsw_real *F, Lr_B[3], Lbar[3];
  FswStatus s;
  int i, j, k, n, nc;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) fsw_vn_zero(out->F, FSW_MAX_THR); /* safe output */
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    if (st != NULL) (void)fsw_health_record(&st->health, FSW_E_NULL_ARG);
    return FSW_E_NULL_ARG;
  }
  if (!st->ready) return fsw_health_record(&st->health, FSW_E_NOT_INIT);
  if (!fsw_v3_is_finite(in->Lr_B) || !fsw_v3_is_finite(in->r_CoM_B))
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  n = cfg->num_thr;
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
      for (k = 0; k < 3; k++) st->work.D_B[k][i] = d[k];
      if (cfg->thr_force_sign < 0) {
        fsw_real Ld[3];
        fsw_v3_scale(Ld, cfg->F_max[i], d);
        fsw_v3_sub(Lr_offset, Lr_offset, Ld);
      }
    }
    fsw_v3_add(Lr_B, Lr_offset, Lr_B);
  }
  /* Lbar = [C] Lr; [C][D] */
  for (j = 0; j < 3; j++) Lbar[j] = FSW_R(0.0);
  for (j = 0; j < nc; j++) {
    Lbar[j] = fsw_v3_dot(st->C[j], Lr_B);
    for (i = 0; i < n; i++) {
      fsw_real d[3];
      for (k = 0; k < 3; k++) d[k] = st->work.D_B[k][i];
      st->work.CD[j][i] = fsw_v3_dot(st->C[j], d);
    }
  }
  if (!fsw_vn_is_finite(Lbar, nc)) return fsw_health_record(&st->health, FSW_E_BAD_INPUT);

  F = st->work.F;
  fsw_vn_zero(F, FSW_MAX_EFF);
  st->nnls_iter = 0;
  if (cfg->mode == FSW_THR_MAP_NNLS)
    s = map_nnls(st, cfg, Lbar, F);
  else
    s = map_min_norm(st, cfg, Lbar, F);
  fsw_vn_copy(out->F, F, n);
  return fsw_health_record(&st->health, s);
}

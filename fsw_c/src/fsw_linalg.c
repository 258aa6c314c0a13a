/* fsw_linalg: kernels K1 (minimum-norm solve) and K2 (null-space projector)
 * of docs/fsw/core.md, "Kernels", and K4 (bounded minimum-norm solve, the exact
 * mode of thr_map, docs/fsw/thr_map.md, "NNLS mode"). */
#include "fsw/fsw_linalg.h"

#include <float.h>
#include <stddef.h>

#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"

#if FSW_USE_FLOAT
#define K1_MAX_EXP FLT_MAX_EXP
#define K1_MIN_NORMAL FLT_MIN
#else
#define K1_MAX_EXP DBL_MAX_EXP
#define K1_MIN_NORMAL DBL_MIN
#endif

/* e with 2^(e-1) <= m < 2^e (0 for m <= 0), clamped so that 2^-e is
 * finite: b 2^-e is then an exact scaling into [1/2, 1). */
static int pow2_exp(fsw_real m)
{
  int e = 0;
  if (!(m > FSW_R(0.0)) || !isfinite(m)) { return 0; }
  if (m >= K1_MIN_NORMAL) {
    e = fsw_frexp_exp_normal(m); /* frexp's e; >= MIN_EXP, no clamp needed */
  } else {
    (void)FSW_FREXP(m, &e);
  }
  if (-e > K1_MAX_EXP - 1) { e = -(K1_MAX_EXP - 1); }
  return e;
}

/* Cholesky solve L L^T z = rhs (m x m, L from the factorisation above). */
static void chol_solve(fsw_real z[3], const fsw_real L[3][3], const fsw_real rhs[3], int m)
{
  fsw_real y[3];
  int i, j;
  if (m == 3) { /* the loops below for m = 3, written out (the same order) */
    const fsw_real y0 = rhs[0] / L[0][0];
    const fsw_real y1 = (rhs[1] - (L[1][0] * y0)) / L[1][1];
    const fsw_real y2 = ((rhs[2] - (L[2][0] * y0)) - (L[2][1] * y1)) / L[2][2];
    const fsw_real z2 = y2 / L[2][2];
    const fsw_real z1 = (y1 - (L[2][1] * z2)) / L[1][1];
    const fsw_real z0 = ((y0 - (L[1][0] * z1)) - (L[2][0] * z2)) / L[0][0];
    fsw_v3_set(z, z0, z1, z2);
  } else {
    for (i = 0; i < m; i++) {
      fsw_real v = rhs[i];
      for (j = 0; j < i; j++) { v -= L[i][j] * y[j]; }
      y[i] = v / L[i][i];
    }
    for (i = m - 1; i >= 0; i--) {
      fsw_real v = y[i];
      for (j = i + 1; j < m; j++) { v -= L[j][i] * z[j]; }
      z[i] = v / L[i][i];
    }
  }
}

/* x = As^T z and r = bs - As x (As = s A formed on the fly).  Three rows
 * (the wheel and thruster mappings' usual case) with the sum over the rows
 * written out: the same terms added in the same order from 0. */
static void k1_apply(fsw_real x[FSW_MAX_EFF], fsw_real r[3], const fsw_real A[3][FSW_MAX_EFF],
                     fsw_real s, const fsw_real z[3], const fsw_real bs[3], int m, int n)
{
  int i, j;
  if (m == 3) {
    const fsw_real z0 = z[0];
    const fsw_real z1 = z[1];
    const fsw_real z2 = z[2];
    fsw_real r0 = bs[0];
    fsw_real r1 = bs[1];
    fsw_real r2 = bs[2];
    for (j = 0; j < n; j++) {
      fsw_real v = FSW_R(0.0);
      v += (A[0][j] * s) * z0;
      v += (A[1][j] * s) * z1;
      v += (A[2][j] * s) * z2;
      x[j] = v;
    }
    for (j = 0; j < n; j++) {
      const fsw_real xj = x[j];
      r0 -= (A[0][j] * s) * xj;
      r1 -= (A[1][j] * s) * xj;
      r2 -= (A[2][j] * s) * xj;
    }
    fsw_v3_set(r, r0, r1, r2);
  } else {
    for (j = 0; j < n; j++) {
      fsw_real v = FSW_R(0.0);
      for (i = 0; i < m; i++) { v += (A[i][j] * s) * z[i]; }
      x[j] = v;
    }
    for (i = 0; i < m; i++) {
      fsw_real v = bs[i];
      for (j = 0; j < n; j++) { v -= (A[i][j] * s) * x[j]; }
      r[i] = v;
    }
  }
}

/* The delivered-residual test |r| <= FSW_RESID_TOL |bs|, decided as the
 * overflow-safe norms (fsw_vn_norm) decide it.  A plain sum of squares
 * settles it first when the answer is clear by a wide margin: with
 * rr = sum r_i^2 and bb = sum bs_i^2 (each within a few rounding units of
 * |r|^2 and |bs|^2, bb finite and >= K1_FAST_BB_MIN, so that squares of
 * r_i lost to underflow are far below the margin), rr <= RESID_TOL^2 bb / 4
 * means |r| <= ~RESID_TOL |bs| / 2, which the scaled norms (each within a
 * few rounding units) also pass.  Otherwise (near the threshold, rank
 * deficient, bb out of range, NaN) the scaled norms decide. */
#if FSW_USE_FLOAT
#define K1_FAST_BB_MIN FSW_R(1e-20)
#define K1_FAST_BB_MAX FSW_R(1e30)
#else
#define K1_FAST_BB_MIN FSW_R(1e-200)
#define K1_FAST_BB_MAX FSW_R(1e300)
#endif
static int k1_resid_ok(const fsw_real r[3], const fsw_real bs[3], int m)
{
  fsw_real rr = FSW_R(0.0);
  fsw_real bb = FSW_R(0.0);
  int ok = 0;
  int i;
  for (i = 0; i < m; i++) {
    rr += r[i] * r[i];
    bb += bs[i] * bs[i];
  }
  if ((bb >= K1_FAST_BB_MIN) && (bb <= K1_FAST_BB_MAX) &&
      (rr <= ((FSW_R(0.25) * FSW_RESID_TOL * FSW_RESID_TOL) * bb))) {
    ok = 1;
  } else if (fsw_vn_norm(r, m) <= (FSW_RESID_TOL * fsw_vn_norm(bs, m))) {
    ok = 1;
  } else {
    ok = 0;
  }
  return ok;
}

FswStatus fsw_minnorm_factor(FswMinnormFactor *f, const fsw_real A[3][FSW_MAX_EFF], int m, int n)
{
  fsw_real M[3][3], amax = FSW_R(0.0), s, dmax;
  int i, j, k;

  FSW_ASSERT(f != NULL && A != NULL);
  if (f == NULL) { return FSW_E_NULL_ARG; }
  f->m = m;
  f->n = n;
  f->s = FSW_R(0.0);
  fsw_m33_zero(f->L);
  f->status = FSW_E_NULL_ARG;
  if (A == NULL) { return f->status; }
  f->status = FSW_E_CAPACITY;
  if (m < 1 || m > 3 || n < 0 || n > FSW_MAX_EFF) { return f->status; }

  f->status = FSW_E_BAD_INPUT;
  for (i = 0; i < m; i++) {
    fsw_real v;
    if (!fsw_vni_is_finite(A[i], n)) { return f->status; }
    v = fsw_vn_max_abs(A[i], n);
    if (v > amax) { amax = v; }
  }
  f->status = FSW_E_SINGULAR;
  if (n < m || amax == FSW_R(0.0)) { return f->status; }
  /* a matrix whose largest entry is subnormal cannot be scaled exactly and
   * its solution overflows for any ordinary b: bad input */
  f->status = FSW_E_BAD_INPUT;
  if (amax < K1_MIN_NORMAL) { return f->status; }

  /* As = s A with s a power of two, formed on the fly (no copy of A: the
   * products (s A_ik)(s A_jk) are exact scalings of A_ik A_jk). */
  s = fsw_pow2_scale(amax);

  /* M = As As^T (lower triangle used) */
  dmax = FSW_R(0.0);
  for (i = 0; i < m; i++) {
    for (j = 0; j <= i; j++) {
      fsw_real v = FSW_R(0.0);
      for (k = 0; k < n; k++) { v += (A[i][k] * s) * (A[j][k] * s); }
      M[i][j] = v;
    }
    if (M[i][i] > dmax) { dmax = M[i][i]; }
  }
  f->status = FSW_E_SINGULAR;
  if (!(dmax > FSW_R(0.0))) { return f->status; }

  /* Cholesky M = L L^T in fixed order; pivot test relative to max diag. */
  for (k = 0; k < m; k++) {
    fsw_real d = M[k][k];
    for (j = 0; j < k; j++) { d -= f->L[k][j] * f->L[k][j]; }
    if (d <= FSW_RANK_TOL * dmax) {
      fsw_m33_zero(f->L);
      return f->status;
    }
    f->L[k][k] = FSW_SQRT(d);
    for (i = k + 1; i < m; i++) {
      fsw_real v = M[i][k];
      for (j = 0; j < k; j++) { v -= f->L[i][j] * f->L[k][j]; }
      f->L[i][k] = v / f->L[k][k];
    }
  }
  f->s = s;
  f->status = FSW_OK;
  return f->status;
}

FswStatus fsw_minnorm_solve_factored(fsw_real x[FSW_MAX_EFF], const FswMinnormFactor *f,
                                     const fsw_real A[3][FSW_MAX_EFF], const fsw_real b[3])
{
  fsw_real bs[3] = {FSW_R(0.0), FSW_R(0.0), FSW_R(0.0)}; /* entries m.. unused */
  fsw_real r[3], dz[3], z[3];
  fsw_real s, t, mb;
  int i, j, eb, m, n, nz, fin;

  FSW_ASSERT(x != NULL && f != NULL && A != NULL && b != NULL);
  if (x == NULL || f == NULL || A == NULL || b == NULL) { return FSW_E_NULL_ARG; }
  m = f->m;
  n = f->n;
  /* the safe output x = 0 on each early return below (a solve that goes on
   * writes every x[j], j < n, in k1_apply) */
  nz = (n < 0) ? 0 : ((n > FSW_MAX_EFF) ? FSW_MAX_EFF : n);
  if (f->status == FSW_E_CAPACITY || f->status == FSW_E_NULL_ARG) {
    fsw_vn_zero(x, nz);
    return f->status;
  }
  /* max |b_i| is finite exactly when every b_i is (fsw_vn_max_abs gives NaN
   * for a NaN entry, infinity for an infinite one): one pass for the
   * finiteness test and the scale below */
  mb = fsw_vn_max_abs(b, m);
  if (!isfinite(mb)) {
    fsw_vn_zero(x, nz);
    return FSW_E_BAD_INPUT;
  }
  if (f->status != FSW_OK) {
    fsw_vn_zero(x, nz);
    return f->status;
  }

  /* b is scaled by s and by a power of two t = 2^-eb that brings max |b|
   * into [1/2, 1): the solve cannot overflow, and x = (solution) 2^eb at the
   * end (exact scalings: the digits are those of the unscaled solve). */
  s = f->s;
  eb = pow2_exp(mb);
  t = (fsw_pow2i_normal(-eb) != 0) ? fsw_pow2i(-eb) : FSW_LDEXP(FSW_R(1.0), -eb);
  for (i = 0; i < m; i++) { bs[i] = (b[i] * t) * s; }

  /* L L^T z = bs; x = As^T z (the two scale factors s cancel:
   * As^T (As As^T)^-1 bs = A^T (A A^T)^-1 b t) */
  chol_solve(z, FSW_CM33(f->L), bs, m);
  k1_apply(x, r, A, s, z, bs, m, n);
  /* Delivered-residual rank test (docs/fsw-conventions.md "Rank test"):
   * a pivot above the floor can still be rounding noise; then A x is far
   * from b.  One refinement step first (a full-rank A that passes the
   * pivot floor always meets FSW_RESID_TOL after it), then reject. */
  if (!k1_resid_ok(r, bs, m)) {
    chol_solve(dz, FSW_CM33(f->L), r, m);
    for (i = 0; i < m; i++) { z[i] += dz[i]; }
    k1_apply(x, r, A, s, z, bs, m, n);
    if (!k1_resid_ok(r, bs, m)) {
      fsw_vn_zero(x, n);
      return isfinite(fsw_vn_norm(r, m)) ? FSW_E_SINGULAR : FSW_E_BAD_INPUT;
    }
  }
  /* undo the scaling of b; a solution beyond the real's range is bad input.
   * When 2^eb is a finite real (always but for max |b| >= 2^(MAX_EXP-1)),
   * x * 2^eb is the exact product rounded once, as ldexp(x, eb) is: the
   * same bits for every x, with one ldexp per call instead of one per
   * entry. */
  fin = 1; /* 0 when an entry is not finite: tested in the same pass */
  if (eb < K1_MAX_EXP) {
    const fsw_real u = (fsw_pow2i_normal(eb) != 0) ? fsw_pow2i(eb) : FSW_LDEXP(FSW_R(1.0), eb);
    for (j = 0; j < n; j++) {
      x[j] *= u;
      if (!isfinite(x[j])) { fin = 0; }
    }
  } else {
    for (j = 0; j < n; j++) {
      x[j] = FSW_LDEXP(x[j], eb);
      if (!isfinite(x[j])) { fin = 0; }
    }
  }
  if (fin == 0) {
    fsw_vn_zero(x, n);
    return FSW_E_BAD_INPUT;
  }
  return FSW_OK;
}

FswStatus fsw_minnorm_solve(fsw_real x[FSW_MAX_EFF], const fsw_real A[3][FSW_MAX_EFF],
                            const fsw_real b[3], int m, int n)
{
  FswMinnormFactor f;
  FSW_ASSERT(x != NULL && A != NULL && b != NULL);
  if (x == NULL || A == NULL || b == NULL) { return FSW_E_NULL_ARG; }
  (void)fsw_minnorm_factor(&f, A, m, n);
  return fsw_minnorm_solve_factored(x, &f, A, b);
}

FswStatus fsw_null_projector(fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF],
                             const fsw_real G[3][FSW_MAX_EFF], int n,
                             const uint8_t *avail, int *rank)
{
  fsw_real Q[3][FSW_MAX_EFF];
  int nq = 0, r, i, j, k, pass;

  FSW_ASSERT(tau != NULL && G != NULL);
  if (rank != NULL) { *rank = 0; }
  if (tau == NULL || G == NULL) { return FSW_E_NULL_ARG; }
  if (n < 0 || n > FSW_MAX_EFF) {
    for (i = 0; i < FSW_MAX_EFF; i++) { fsw_vn_zero(tau[i], FSW_MAX_EFF); }
    return FSW_E_CAPACITY;
  }
  for (i = 0; i < n; i++) { fsw_vn_zero(tau[i], n); }
  for (r = 0; r < 3; r++) {
    if (!fsw_vni_is_finite(G[r], n)) { return FSW_E_BAD_INPUT; } }

  for (r = 0; r < 3; r++) {
    fsw_real *v = Q[nq];
    fsw_real n0, res, s;
    for (j = 0; j < n; j++) {
      v[j] = (avail != NULL && avail[j] != FSW_AVAILABLE) ? FSW_R(0.0) : G[r][j]; }
    s = fsw_pow2_scale(fsw_vn_max_abs(v, n));
    fsw_vn_scale(v, s, v, n);
    n0 = fsw_vn_norm(v, n);
    if (!(n0 > FSW_R(0.0))) { continue; }
    /* modified Gram-Schmidt, then one re-orthogonalisation pass */
    for (pass = 0; pass < 2; pass++) {
      for (k = 0; k < nq; k++) {
        fsw_real c = fsw_vn_dot(Q[k], v, n);
        for (j = 0; j < n; j++) { v[j] -= c * Q[k][j]; }
      }
      if (pass == 0) {
        res = fsw_vn_norm(v, n);
        if (res <= FSW_NULL_TOL * n0) { break; }
      }
    }
    if (pass == 0) { continue; } /* dropped: dependent on earlier rows */
    res = fsw_vn_norm(v, n);
    fsw_vn_scale(v, FSW_R(1.0) / res, v, n);
    nq++;
  }

  for (i = 0; i < n; i++) {
    int ai = (avail == NULL || avail[i] == FSW_AVAILABLE);
    for (j = 0; j < n; j++) {
      int aj = (avail == NULL || avail[j] == FSW_AVAILABLE);
      fsw_real v = (i == j) ? FSW_R(1.0) : FSW_R(0.0);
      if (!ai || !aj) {
        tau[i][j] = FSW_R(0.0);
        continue;
      }
      for (k = 0; k < nq; k++) { v -= Q[k][i] * Q[k][j]; }
      tau[i][j] = v;
    }
  }
  if (rank != NULL) { *rank = nq; }
  return FSW_OK;
}

/* ---- K4: bounded least squares, then least norm ------------------------- */

/* Relative round-off tolerance of the active-set method: a residual,
 * gradient or step below K4_TOL times its natural scale is zero. */
#define K4_TOL (FSW_R(1000.0) * FSW_REAL_EPS)
/* Fixed iteration budget: K4_ITER_PER_COL times the column count (both
 * phases together). */
#define K4_ITER_PER_COL 3

/* Variable status of the active-set method. */
#define K4_FREE 0
#define K4_AT_LO 1
#define K4_AT_HI 2

/* Solve M x = rhs for a symmetric positive semi-definite m x m matrix M by
 * LDL^T in fixed order.  A pivot <= FSW_RANK_TOL * max diag is dropped (its
 * component of the solution is 0), so a consistent rhs is solved exactly
 * even when M is singular. */
static void psd_solve(fsw_real x[3], const fsw_real M[3][3], const fsw_real rhs[3], int m)
{
  fsw_real L[3][3], d[3], y[3], dmax = FSW_R(0.0);
  int keep[3], i, j, k;
  for (k = 0; k < m; k++) {
    if (M[k][k] > dmax) { dmax = M[k][k]; } }
  for (k = 0; k < m; k++) {
    fsw_real v = M[k][k];
    for (j = 0; j < k; j++) { v -= L[k][j] * L[k][j] * d[j]; }
    keep[k] = (dmax > FSW_R(0.0) && v > FSW_RANK_TOL * dmax);
    d[k] = keep[k] ? v : FSW_R(0.0);
    L[k][k] = FSW_R(1.0);
    for (i = k + 1; i < m; i++) {
      fsw_real w = M[i][k];
      for (j = 0; j < k; j++) { w -= L[i][j] * L[k][j] * d[j]; }
      L[i][k] = keep[k] ? w / d[k] : FSW_R(0.0);
    }
  }
  for (k = 0; k < m; k++) {
    fsw_real v = rhs[k];
    for (j = 0; j < k; j++) { v -= L[k][j] * y[j]; }
    y[k] = v;
  }
  for (k = m - 1; k >= 0; k--) {
    fsw_real v = keep[k] ? y[k] / d[k] : FSW_R(0.0);
    for (i = k + 1; i < m; i++) { v -= L[i][k] * x[i]; }
    x[k] = v;
  }
  for (k = m; k < 3; k++) { x[k] = FSW_R(0.0); }
}

/* Column i of A dotted with an m-vector. */
static fsw_real col_dot(const fsw_real A[3][FSW_MAX_EFF], int i, const fsw_real v[3], int m)
{
  fsw_real s = FSW_R(0.0);
  int k;
  for (k = 0; k < m; k++) { s += A[k][i] * v[k]; }
  return s;
}

/* K4 body (inputs already checked).  See fsw_linalg.h for the method:
 * phase 1 (Lawson-Hanson / BVLS style) minimises |A F - b| within the box
 * from F = 0, keeping at most m independent free columns; phase 2 (primal
 * active set) keeps A F fixed and minimises |F|, stepping in the null space
 * of the free columns.  Ties go to the lowest index; F never leaves
 * [lo, hi].  Returns the iteration count.
 * Every sum runs over ascending column index.  The loops over the fixed
 * columns in phase 1 and the unbounded ones in phase 2 walk an index list
 * formed once per iteration, and the per-column quantities that do not change
 * within a call (the gradient floor K4_TOL |b| |a_i|) or within an
 * iteration (a_i . lam) are formed once: the same operations on the same
 * operands as testing each column's status inside every sum. */
static int bounded_minnorm(fsw_real F[FSW_MAX_EFF], const fsw_real A[3][FSW_MAX_EFF],
                           const fsw_real b[3], int m, int n, const fsw_real lo[FSW_MAX_EFF],
                           const fsw_real hi[FSW_MAX_EFF])
{
  signed char stat[FSW_MAX_EFF];
  fsw_real gfloor[FSW_MAX_EFF]; /* phase 1: K4_TOL |b| |a_i| */
  fsw_real za[FSW_MAX_EFF];     /* phase 2: a_i . lam of the listed free columns */
  int idx[FSW_MAX_EFF];         /* the columns a loop walks, ascending */
  int P[3], np = 0, it = 0, ni, i, j, k, q;
  const int budget = K4_ITER_PER_COL * n;
  const fsw_real bnorm = fsw_vn_norm(b, m);
  const fsw_real btol = K4_TOL * bnorm;
  fsw_real fscale = FSW_R(0.0);

  for (i = 0; i < n; i++) {
    fsw_real an2 = FSW_R(0.0);
    F[i] = FSW_R(0.0);
    stat[i] = (lo[i] == FSW_R(0.0)) ? K4_AT_LO : K4_AT_HI;
    if (hi[i] - lo[i] > fscale) { fscale = hi[i] - lo[i]; }
    for (k = 0; k < m; k++) { an2 += A[k][i] * A[k][i]; }
    gfloor[i] = btol * FSW_SQRT(an2);
  }

  /* ---- phase 1 ---- */
  while (it < budget && np < m) {
    fsw_real r[3], gbest = FSW_R(0.0);
    int best = -1, first = 1;
    for (k = 0; k < m; k++) {
      fsw_real v = b[k];
      for (i = 0; i < n; i++) { v -= A[k][i] * F[i]; }
      r[k] = v;
    }
    if (fsw_vn_norm(r, m) <= btol) { break; }
    for (i = 0; i < n; i++) {
      fsw_real g;
      if (stat[i] == K4_FREE) { continue; }
      g = col_dot(A, i, r, m);
      if (stat[i] == K4_AT_HI) { g = -g; }
      if (g > gfloor[i] && g > gbest) {
        gbest = g;
        best = i;
      }
    }
    if (best < 0) { break; }
    /* insert into P keeping index order */
    for (q = np; q > 0 && P[q - 1] > best; q--) { P[q] = P[q - 1]; }
    P[q] = best;
    np++;
    {
      const int entering_at_lo = (stat[best] == K4_AT_LO);
      int stop = 0;
      stat[best] = K4_FREE;
      while (it < budget) {
        fsw_real G[3][3], rhs[3], r0[3], z[3], alpha = FSW_R(1.0);
        int blk = -1;
        it++;
        /* r0 = b - sum over fixed columns; LS on the free columns */
        ni = 0; for (i = 0; i < n; i++) {
          if (stat[i] != K4_FREE) { idx[ni++] = i; } }
        for (k = 0; k < m; k++) {
          fsw_real v = b[k];
          for (q = 0; q < ni; q++) { v -= A[k][idx[q]] * F[idx[q]]; }
          r0[k] = v;
        }
        for (q = 0; q < np; q++) {
          for (j = 0; j < np; j++) {
            fsw_real v = FSW_R(0.0);
            for (k = 0; k < m; k++) { v += A[k][P[q]] * A[k][P[j]]; }
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
            stat[best] = entering_at_lo ? K4_AT_LO : K4_AT_HI;
            for (; q + 1 < np; q++) { P[q] = P[q + 1]; }
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
            if (!(a > FSW_R(0.0))) { a = FSW_R(0.0); }
            if (blk < 0 || a < alpha) {
              alpha = a;
              blk = q;
            }
          }
        }
        if (blk < 0) {
          for (q = 0; q < np; q++) { F[P[q]] = z[q]; }
          break;
        }
        if (alpha > FSW_R(1.0)) { alpha = FSW_R(1.0); }
        for (q = 0; q < np; q++) { F[P[q]] = F[P[q]] + alpha * (z[q] - F[P[q]]); }
        /* fix the blocking variable and any other that reached a bound */
        {
          const int ib = P[blk];
          const int ib_lo = (z[blk] <= lo[ib]);
          F[ib] = ib_lo ? lo[ib] : hi[ib];
          stat[ib] = ib_lo ? K4_AT_LO : K4_AT_HI;
          for (q = 0; q < np; q++) {
            i = P[q];
            if (stat[i] != K4_FREE) { continue; }
            if (F[i] <= lo[i]) {
              F[i] = lo[i];
              stat[i] = K4_AT_LO;
            } else if (F[i] >= hi[i]) {
              F[i] = hi[i];
              stat[i] = K4_AT_HI;
            }
          }
          j = 0; for (q = 0; q < np; q++) {
            if (stat[P[q]] == K4_FREE) { P[j++] = P[q]; } }
          np = j;
        }
      }
      if (stop) { break; }
    }
  }

  /* ---- phase 2 ---- */
  while (it < budget) {
    fsw_real M[3][3], c[3], lam[3], alpha = FSW_R(1.0), pmax = FSW_R(0.0), vbest;
    int blk = -1, best = -1, blk_lo = 0;
    it++;
    ni = 0; for (i = 0; i < n; i++) {
      if (stat[i] == K4_FREE) { idx[ni++] = i; } }
    for (k = 0; k < m; k++) {
      for (j = 0; j <= k; j++) {
        fsw_real v = FSW_R(0.0);
        for (q = 0; q < ni; q++) { v += A[k][idx[q]] * A[j][idx[q]]; }
        M[k][j] = v;
        M[j][k] = v;
      }
      {
        fsw_real v = FSW_R(0.0);
        for (q = 0; q < ni; q++) { v += A[k][idx[q]] * F[idx[q]]; }
        c[k] = v;
      }
    }
    psd_solve(lam, FSW_CM33(M), c, m);
    for (q = 0; q < ni; q++) {
      fsw_real p;
      i = idx[q];
      za[q] = col_dot(A, i, lam, m);
      p = za[q] - F[i];
      if (FSW_FABS(p) > pmax) { pmax = FSW_FABS(p); }
    }
    if (pmax > K4_TOL * fscale) {
      /* step toward the minimum-norm point of the free set, ratio test */
      for (q = 0; q < ni; q++) {
        const fsw_real z = za[q];
        i = idx[q];
        if (z < lo[i] || z > hi[i]) {
          fsw_real bound = (z < lo[i]) ? lo[i] : hi[i];
          fsw_real a = (bound - F[i]) / (z - F[i]);
          if (!(a > FSW_R(0.0))) { a = FSW_R(0.0); }
          if (blk < 0 || a < alpha) {
            alpha = a;
            blk = i;
            blk_lo = (z < lo[i]);
          }
        }
      }
      if (alpha > FSW_R(1.0)) { alpha = FSW_R(1.0); }
      for (q = 0; q < ni; q++) {
        i = idx[q];
        F[i] = F[i] + alpha * (za[q] - F[i]);
        if (F[i] < lo[i]) { F[i] = lo[i]; }
        if (F[i] > hi[i]) { F[i] = hi[i]; }
      }
      if (blk >= 0) {
        F[blk] = blk_lo ? lo[blk] : hi[blk];
        stat[blk] = blk_lo ? K4_AT_LO : K4_AT_HI;
        continue;
      }
      /* full step: F is now the minimiser on the free set and lam its
       * multiplier, so the optimality test below needs no new solve */
    }
    /* stationary on the free set: release the bound with the largest
     * multiplier of the wrong sign */
    vbest = K4_TOL * fscale;
    for (i = 0; i < n; i++) {
      fsw_real g, v;
      if (stat[i] == K4_FREE) { continue; }
      g = col_dot(A, i, lam, m);
      v = (stat[i] == K4_AT_LO) ? g - lo[i] : hi[i] - g;
      if (v > vbest) {
        vbest = v;
        best = i;
      }
    }
    if (best < 0) { break; }
    stat[best] = K4_FREE;
  }
  return it;
}

FswStatus fsw_bounded_minnorm_solve(fsw_real x[FSW_MAX_EFF], const fsw_real A[3][FSW_MAX_EFF],
                                    const fsw_real b[3], int m, int n,
                                    const fsw_real lo[FSW_MAX_EFF], const fsw_real hi[FSW_MAX_EFF],
                                    int *iterations)
{
  int i;
  FSW_ASSERT(x != NULL && A != NULL && b != NULL && lo != NULL && hi != NULL);
  if (iterations != NULL) { *iterations = 0; }
  if (x == NULL || A == NULL || b == NULL || lo == NULL || hi == NULL) { return FSW_E_NULL_ARG; }
  fsw_vn_zero(x, n < 0 ? 0 : (n > FSW_MAX_EFF ? FSW_MAX_EFF : n)); /* safe output */
  if (m < 1 || m > 3 || n < 0 || n > FSW_MAX_EFF) { return FSW_E_CAPACITY; }
  for (i = 0; i < m; i++) {
    if (!fsw_vni_is_finite(A[i], n) || !isfinite(b[i])) { return FSW_E_BAD_INPUT; } }
  for (i = 0; i < n; i++) {
    if (!isfinite(lo[i]) || !isfinite(hi[i]) || !(lo[i] <= hi[i])) { return FSW_E_BAD_INPUT; }
    if (lo[i] != FSW_R(0.0) && hi[i] != FSW_R(0.0)) { return FSW_E_BAD_INPUT; }
  }
  i = bounded_minnorm(x, A, b, m, n, lo, hi);
  if (iterations != NULL) { *iterations = i; }
  return FSW_OK;
}

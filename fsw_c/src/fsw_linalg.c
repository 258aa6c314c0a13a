/* fsw_linalg: kernels K1 (minimum-norm solve) and K2 (null-space projector)
 * of fsw-algorithms.md 0.4. */
#include "fsw/fsw_linalg.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

/* Power of two 2^-e with 2^(e-1) <= m < 2^e: multiplying by it is exact
 * (barring subnormals), so pre-scaling changes no rounding, only the range. */
static fsw_real pow2_scale_for(fsw_real m)
{
  int e = 0;
  if (!(m > FSW_R(0.0))) return FSW_R(1.0);
  (void)FSW_FREXP(m, &e);
  return FSW_LDEXP(FSW_R(1.0), -e);
}

FswStatus fsw_minnorm_solve(fsw_real x[FSW_MAX_EFF], const fsw_real A[3][FSW_MAX_EFF],
                            const fsw_real b[3], int m, int n)
{
  fsw_real bs[3];
  fsw_real M[3][3], L[3][3], y[3], z[3];
  fsw_real amax = FSW_R(0.0), s, dmax;
  int i, j, k;

  FSW_ASSERT(x != NULL && A != NULL && b != NULL);
  if (x == NULL || A == NULL || b == NULL) return FSW_E_NULL_ARG;
  fsw_vn_zero(x, n < 0 ? 0 : (n > FSW_MAX_EFF ? FSW_MAX_EFF : n)); /* safe output */
  if (m < 1 || m > 3 || n < 0 || n > FSW_MAX_EFF) return FSW_E_CAPACITY;

  for (i = 0; i < m; i++) {
    if (!fsw_vn_is_finite(A[i], n) || !isfinite(b[i])) return FSW_E_BAD_INPUT;
    {
      fsw_real r = fsw_vn_max_abs(A[i], n);
      if (r > amax) amax = r;
    }
  }
  if (n < m || amax == FSW_R(0.0)) return FSW_E_SINGULAR;

  /* As = s A with s a power of two, formed on the fly (no copy of A: the
   * products (s A_ik)(s A_jk) are exact scalings of A_ik A_jk). */
  s = pow2_scale_for(amax);
  for (i = 0; i < m; i++) bs[i] = b[i] * s;

  /* M = As As^T (lower triangle used) */
  dmax = FSW_R(0.0);
  for (i = 0; i < m; i++) {
    for (j = 0; j <= i; j++) {
      fsw_real v = FSW_R(0.0);
      for (k = 0; k < n; k++) v += (A[i][k] * s) * (A[j][k] * s);
      M[i][j] = v;
    }
    if (M[i][i] > dmax) dmax = M[i][i];
  }
  if (!(dmax > FSW_R(0.0))) return FSW_E_SINGULAR;

  /* Cholesky M = L L^T in fixed order; pivot test relative to max diag. */
  for (k = 0; k < m; k++) {
    fsw_real d = M[k][k];
    for (j = 0; j < k; j++) d -= L[k][j] * L[k][j];
    if (d <= FSW_RANK_TOL * dmax) return FSW_E_SINGULAR;
    L[k][k] = FSW_SQRT(d);
    for (i = k + 1; i < m; i++) {
      fsw_real v = M[i][k];
      for (j = 0; j < k; j++) v -= L[i][j] * L[k][j];
      L[i][k] = v / L[k][k];
    }
  }
  /* L y = bs; L^T z = y */
  for (i = 0; i < m; i++) {
    fsw_real v = bs[i];
    for (j = 0; j < i; j++) v -= L[i][j] * y[j];
    y[i] = v / L[i][i];
  }
  for (i = m - 1; i >= 0; i--) {
    fsw_real v = y[i];
    for (j = i + 1; j < m; j++) v -= L[j][i] * z[j];
    z[i] = v / L[i][i];
  }
  /* x = As^T z  (the two scale factors cancel: As^T (As As^T)^-1 bs = x) */
  for (j = 0; j < n; j++) {
    fsw_real v = FSW_R(0.0);
    for (i = 0; i < m; i++) v += (A[i][j] * s) * z[i];
    x[j] = v;
  }
  return FSW_OK;
}

FswStatus fsw_null_projector(fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF],
                             const fsw_real G[3][FSW_MAX_EFF], int n,
                             const uint8_t avail[FSW_MAX_EFF], int *rank)
{
  fsw_real Q[3][FSW_MAX_EFF];
  int nq = 0, r, i, j, k, pass;

  FSW_ASSERT(tau != NULL && G != NULL);
  if (rank != NULL) *rank = 0;
  if (tau == NULL || G == NULL) return FSW_E_NULL_ARG;
  if (n < 0 || n > FSW_MAX_EFF) {
    for (i = 0; i < FSW_MAX_EFF; i++) fsw_vn_zero(tau[i], FSW_MAX_EFF);
    return FSW_E_CAPACITY;
  }
  for (i = 0; i < n; i++) fsw_vn_zero(tau[i], n);
  for (r = 0; r < 3; r++)
    if (!fsw_vn_is_finite(G[r], n)) return FSW_E_BAD_INPUT;

  for (r = 0; r < 3; r++) {
    fsw_real *v = Q[nq];
    fsw_real n0, res, s;
    for (j = 0; j < n; j++)
      v[j] = (avail != NULL && avail[j] != FSW_AVAILABLE) ? FSW_R(0.0) : G[r][j];
    s = pow2_scale_for(fsw_vn_max_abs(v, n));
    fsw_vn_scale(v, s, v, n);
    n0 = fsw_vn_norm(v, n);
    if (!(n0 > FSW_R(0.0))) continue;
    /* modified Gram-Schmidt, then one re-orthogonalisation pass */
    for (pass = 0; pass < 2; pass++) {
      for (k = 0; k < nq; k++) {
        fsw_real c = fsw_vn_dot(Q[k], v, n);
        for (j = 0; j < n; j++) v[j] -= c * Q[k][j];
      }
      if (pass == 0) {
        res = fsw_vn_norm(v, n);
        if (res <= FSW_NULL_TOL * n0) break;
      }
    }
    if (pass == 0) continue; /* dropped: dependent on earlier rows */
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
      for (k = 0; k < nq; k++) v -= Q[k][i] * Q[k][j];
      tau[i][j] = v;
    }
  }
  if (rank != NULL) *rank = nq;
  return FSW_OK;
}

/* fsw_vec: small vector and 3x3 matrix operations (alias-safe). */
#include "fsw/fsw_vec.h"

#include <float.h>

#define FSW_VEC_INLINE_NO_ALIASES
#include "fsw_vec_inline.h"

void fsw_v3_set(fsw_real out[3], fsw_real x, fsw_real y, fsw_real z)
{
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

void fsw_v3_copy(fsw_real out[3], const fsw_real a[3])
{
  fsw_real t0 = a[0], t1 = a[1], t2 = a[2];
  out[0] = t0;
  out[1] = t1;
  out[2] = t2;
}

void fsw_v3_zero(fsw_real out[3]) { fsw_v3_set(out, FSW_R(0.0), FSW_R(0.0), FSW_R(0.0)); }

void fsw_v3_add(fsw_real out[3], const fsw_real a[3], const fsw_real b[3])
{
  fsw_v3_set(out, a[0] + b[0], a[1] + b[1], a[2] + b[2]);
}

void fsw_v3_sub(fsw_real out[3], const fsw_real a[3], const fsw_real b[3])
{
  fsw_v3_set(out, a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

void fsw_v3_scale(fsw_real out[3], fsw_real s, const fsw_real a[3])
{
  fsw_v3_set(out, s * a[0], s * a[1], s * a[2]);
}

void fsw_v3_axpy(fsw_real out[3], const fsw_real a[3], fsw_real s, const fsw_real b[3])
{
  fsw_v3_set(out, a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]);
}

fsw_real fsw_v3_dot(const fsw_real a[3], const fsw_real b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void fsw_v3_cross(fsw_real out[3], const fsw_real a[3], const fsw_real b[3])
{
  fsw_v3_set(out, a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
             a[0] * b[1] - a[1] * b[0]);
}

fsw_real fsw_v3_norm2(const fsw_real a[3]) { return fsw_v3_dot(a, a); }

fsw_real fsw_v3_norm(const fsw_real a[3]) { return fsw_vn_norm(a, 3); }

#if FSW_USE_FLOAT
#define FSW_REAL_MAX_EXP FLT_MAX_EXP
#else
#define FSW_REAL_MAX_EXP DBL_MAX_EXP
#endif

fsw_real fsw_pow2_scale(fsw_real m)
{
  int e = 0;
  if (!(m > FSW_R(0.0)) || !isfinite(m)) { return FSW_R(1.0); }
  if (m >= FSW_RB_MIN_NORMAL) {
    e = fsw_frexp_exp_normal(m); /* frexp's e, from the exponent field */
  } else {
    (void)FSW_FREXP(m, &e);
    /* subnormal m: 2^-e would overflow; the largest finite power of two
     * still brings m * scale into the normal range */
    if (-e > FSW_REAL_MAX_EXP - 1) { e = -(FSW_REAL_MAX_EXP - 1); }
  }
  /* 2^-e is a normal number but for m at or above 2^(MAX_EXP-2), where it
   * is subnormal (ldexp) */
  return (fsw_pow2i_normal(-e) != 0) ? fsw_pow2i(-e) : FSW_LDEXP(FSW_R(1.0), -e);
}

int fsw_v3_norm_normalize(fsw_real out[3], fsw_real *norm, const fsw_real a[3])
{
  /* Pre-scaled by a power of two (exact): the same bits as a/|a| in the
   * normal range, and a unit vector also for entries near the real's
   * maximum (|a| would overflow) or subnormal (|a| would lose digits).  The
   * largest entry is searched and the scaled sum of squares formed once for
   * |a| and the direction (fsw_v3i_scaled_root). */
  const fsw_real m = fsw_vni_max_abs(a, 3);
  fsw_real b[3], p, r, n;
  /* m is finite only if every entry is: fsw_vn_max_abs returns NaN for a
   * NaN entry and infinity for an infinite one. */
  if (!(m > FSW_R(0.0)) || !isfinite(m)) {
    *norm = m; /* fsw_vn_norm's value: 0, NaN or infinity */
    fsw_v3_zero(out);
    return 0;
  }
  r = fsw_v3i_scaled_root(a, m);
  *norm = m * r;
  p = fsw_pow2_scale(m);
  fsw_v3_scale(b, p, a);
  n = (m * p) * r; /* = fsw_v3_norm(b) */
  fsw_v3_set(out, b[0] / n, b[1] / n, b[2] / n);
  return 1;
}

int fsw_v3_normalize(fsw_real out[3], const fsw_real a[3])
{
  fsw_real norm;
  return fsw_v3_norm_normalize(out, &norm, a);
}

int fsw_v3_is_finite(const fsw_real a[3]) { return fsw_vn_is_finite(a, 3); }

void fsw_vn_copy(fsw_real *out, const fsw_real *a, int n)
{
  int i;
  if (out == a) { return; }
  for (i = 0; i < n; i++) { out[i] = a[i]; }
}

void fsw_vn_zero(fsw_real *out, int n)
{
  int i;
  for (i = 0; i < n; i++) { out[i] = FSW_R(0.0); }
}

void fsw_vn_scale(fsw_real *out, fsw_real s, const fsw_real *a, int n)
{
  int i;
  for (i = 0; i < n; i++) { out[i] = s * a[i]; }
}

void fsw_vn_add(fsw_real *out, const fsw_real *a, const fsw_real *b, int n)
{
  int i;
  for (i = 0; i < n; i++) { out[i] = a[i] + b[i]; }
}

void fsw_vn_sub(fsw_real *out, const fsw_real *a, const fsw_real *b, int n)
{
  int i;
  for (i = 0; i < n; i++) { out[i] = a[i] - b[i]; }
}

fsw_real fsw_vn_dot(const fsw_real *a, const fsw_real *b, int n)
{
  fsw_real s = FSW_R(0.0);
  int i;
  for (i = 0; i < n; i++) { s += a[i] * b[i]; }
  return s;
}

fsw_real fsw_vn_max_abs(const fsw_real *a, int n) { return fsw_vni_max_abs(a, n); }

fsw_real fsw_vn_norm(const fsw_real *a, int n)
{
  /* Scaled sum of squares: no overflow for entries near the real's maximum
   * and no underflow to zero for tiny ones. */
  fsw_real m = fsw_vni_max_abs(a, n);
  fsw_real s = FSW_R(0.0);
  int i;
  if (m == FSW_R(0.0) || !isfinite(m)) { return m; }
  for (i = 0; i < n; i++) {
    fsw_real t = a[i] / m;
    s += t * t;
  }
  return m * FSW_SQRT(s);
}

int fsw_vn_is_finite(const fsw_real *a, int n) { return fsw_vni_is_finite(a, n); }

void fsw_m33_zero(fsw_real out[3][3])
{
  int i, j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { out[i][j] = FSW_R(0.0); } }
}

void fsw_m33_identity(fsw_real out[3][3])
{
  int i;
  fsw_m33_zero(out);
  for (i = 0; i < 3; i++) { out[i][i] = FSW_R(1.0); }
}

void fsw_m33_copy(fsw_real out[3][3], const fsw_real a[3][3])
{
  int i, j;
  if ((const fsw_real *)out == &a[0][0]) { return; }
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { out[i][j] = a[i][j]; } }
}

void fsw_m33_transpose(fsw_real out[3][3], const fsw_real a[3][3])
{
  fsw_real t[3][3];
  int i, j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { t[i][j] = a[j][i]; } }
  fsw_m33_copy(out, FSW_CM33(t));
}

void fsw_m33_add(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3])
{
  int i, j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { out[i][j] = a[i][j] + b[i][j]; } }
}

void fsw_m33_sub(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3])
{
  int i, j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { out[i][j] = a[i][j] - b[i][j]; } }
}

void fsw_m33_scale(fsw_real out[3][3], fsw_real s, const fsw_real a[3][3])
{
  int i, j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { out[i][j] = s * a[i][j]; } }
}

void fsw_m33_mult(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3])
{
  fsw_real t[3][3];
  int i, j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { t[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j]; } }
  fsw_m33_copy(out, FSW_CM33(t));
}

void fsw_m33_mult_t(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3])
{
  fsw_real t[3][3];
  int i, j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { t[i][j] = a[i][0] * b[j][0] + a[i][1] * b[j][1] + a[i][2] * b[j][2]; } }
  fsw_m33_copy(out, FSW_CM33(t));
}

void fsw_m33_mult_v3(fsw_real out[3], const fsw_real a[3][3], const fsw_real v[3])
{
  fsw_v3_set(out, fsw_v3_dot(a[0], v), fsw_v3_dot(a[1], v), fsw_v3_dot(a[2], v));
}

void fsw_m33_tmult_v3(fsw_real out[3], const fsw_real a[3][3], const fsw_real v[3])
{
  fsw_v3_set(out, a[0][0] * v[0] + a[1][0] * v[1] + a[2][0] * v[2],
             a[0][1] * v[0] + a[1][1] * v[1] + a[2][1] * v[2],
             a[0][2] * v[0] + a[1][2] * v[1] + a[2][2] * v[2]);
}

fsw_real fsw_m33_det(const fsw_real a[3][3])
{
  fsw_real c[3];
  fsw_v3_cross(c, a[1], a[2]);
  return fsw_v3_dot(a[0], c);
}

fsw_real fsw_m33_trace(const fsw_real a[3][3]) { return a[0][0] + a[1][1] + a[2][2]; }

int fsw_m33_is_finite(const fsw_real a[3][3])
{
  return fsw_v3_is_finite(a[0]) && fsw_v3_is_finite(a[1]) && fsw_v3_is_finite(a[2]);
}

int fsw_m33_inverse(fsw_real out[3][3], const fsw_real a[3][3], fsw_real rel_tol)
{
  /* Columns of the inverse are the cross products of the rows / det. */
  fsw_real c0[3], c1[3], c2[3];
  fsw_real det, scale;
  int i;
  if (!fsw_m33_is_finite(a)) {
    fsw_m33_zero(out);
    return 0;
  }
  fsw_v3_cross(c0, a[1], a[2]);
  fsw_v3_cross(c1, a[2], a[0]);
  fsw_v3_cross(c2, a[0], a[1]);
  det = fsw_v3_dot(a[0], c0);
  scale = fsw_v3_norm(a[0]) * fsw_v3_norm(a[1]) * fsw_v3_norm(a[2]);
  if (!(FSW_FABS(det) > rel_tol * scale) || !(scale > FSW_R(0.0))) {
    fsw_m33_zero(out);
    return 0;
  }
  for (i = 0; i < 3; i++) {
    out[i][0] = c0[i] / det;
    out[i][1] = c1[i] / det;
    out[i][2] = c2[i] / det;
  }
  return 1;
}

/* fsw_vec: small vector and 3x3 matrix operations.
 * Output argument first.  Every function is alias-safe: an output may be the
 * same array as an input.  3x3 matrices are row-major fsw_real[3][3]; pass a
 * non-const matrix to a const parameter through FSW_CM33() (C only). */
#ifndef FSW_VEC_H
#define FSW_VEC_H

#include "fsw/fsw_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- 3-vectors ---- */
void fsw_v3_set(fsw_real out[3], fsw_real x, fsw_real y, fsw_real z);
void fsw_v3_copy(fsw_real out[3], const fsw_real a[3]);
void fsw_v3_zero(fsw_real out[3]);
void fsw_v3_add(fsw_real out[3], const fsw_real a[3], const fsw_real b[3]);
void fsw_v3_sub(fsw_real out[3], const fsw_real a[3], const fsw_real b[3]);
void fsw_v3_scale(fsw_real out[3], fsw_real s, const fsw_real a[3]);
/* out = a + s*b */
void fsw_v3_axpy(fsw_real out[3], const fsw_real a[3], fsw_real s, const fsw_real b[3]);
fsw_real fsw_v3_dot(const fsw_real a[3], const fsw_real b[3]);
void fsw_v3_cross(fsw_real out[3], const fsw_real a[3], const fsw_real b[3]);
fsw_real fsw_v3_norm2(const fsw_real a[3]); /* squared norm */
fsw_real fsw_v3_norm(const fsw_real a[3]);  /* overflow-safe Euclidean norm */
/* out = a/|a|.  Returns 0 and writes zeros when a is zero or not finite,
 * 1 on success (also for finite a whose norm would overflow or underflow:
 * a is pre-scaled by a power of two, which changes no digit otherwise). */
int fsw_v3_normalize(fsw_real out[3], const fsw_real a[3]);
/* fsw_v3_normalize(out, a) and *norm = fsw_v3_norm(a), the same bits as the
 * two calls (also for a zero or non-finite a: *norm is then 0, NaN or
 * infinity), with one search for the largest entry and one sum.  out may be
 * a. */
int fsw_v3_norm_normalize(fsw_real out[3], fsw_real *norm, const fsw_real a[3]);
int fsw_v3_is_finite(const fsw_real a[3]); /* 1 if all entries are finite */
/* 2^-e with 2^(e-1) <= m < 2^e (1 for m <= 0 or non-finite; for subnormal
 * m the largest finite power of two): multiplying by it is exact barring
 * subnormals, so it changes the range, not digits. */
fsw_real fsw_pow2_scale(fsw_real m);

/* ---- n-vectors (0 <= n; n <= 0 is an empty vector) ---- */
void fsw_vn_copy(fsw_real *out, const fsw_real *a, int n);
void fsw_vn_zero(fsw_real *out, int n);
void fsw_vn_scale(fsw_real *out, fsw_real s, const fsw_real *a, int n);
void fsw_vn_add(fsw_real *out, const fsw_real *a, const fsw_real *b, int n);
void fsw_vn_sub(fsw_real *out, const fsw_real *a, const fsw_real *b, int n);
fsw_real fsw_vn_dot(const fsw_real *a, const fsw_real *b, int n);
fsw_real fsw_vn_norm(const fsw_real *a, int n); /* overflow-safe */
fsw_real fsw_vn_max_abs(const fsw_real *a, int n);
int fsw_vn_is_finite(const fsw_real *a, int n); /* 1 if all entries finite */

/* ---- 3x3 matrices ---- */
void fsw_m33_zero(fsw_real out[3][3]);
void fsw_m33_identity(fsw_real out[3][3]);
void fsw_m33_copy(fsw_real out[3][3], const fsw_real a[3][3]);
void fsw_m33_transpose(fsw_real out[3][3], const fsw_real a[3][3]);
void fsw_m33_add(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3]);
void fsw_m33_sub(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3]);
void fsw_m33_scale(fsw_real out[3][3], fsw_real s, const fsw_real a[3][3]);
void fsw_m33_mult(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3]);
/* out = a * b^T */
void fsw_m33_mult_t(fsw_real out[3][3], const fsw_real a[3][3], const fsw_real b[3][3]);
/* out = a * v */
void fsw_m33_mult_v3(fsw_real out[3], const fsw_real a[3][3], const fsw_real v[3]);
/* out = a^T * v */
void fsw_m33_tmult_v3(fsw_real out[3], const fsw_real a[3][3], const fsw_real v[3]);
fsw_real fsw_m33_det(const fsw_real a[3][3]);
fsw_real fsw_m33_trace(const fsw_real a[3][3]);
int fsw_m33_is_finite(const fsw_real a[3][3]);
/* Inverse by adjugate with a scale-invariant singularity test: fails (returns
 * 0, out = 0) when |det| <= rel_tol * prod(row norms), i.e. when the rows are
 * nearly dependent whatever their units.  Returns 1 on success. */
int fsw_m33_inverse(fsw_real out[3][3], const fsw_real a[3][3], fsw_real rel_tol);

#ifdef __cplusplus
}
#endif

#endif /* FSW_VEC_H */

/* fsw_vec_inline: the one-line vector helpers of fsw/fsw_vec.h as static
 * inline functions, for the modules of the flight cycle.  Not a public
 * header.  Each body is the expression of the out-of-line function in
 * fsw_vec.c, evaluated in the same order (the library is compiled with
 * -ffp-contract=off), so a module that includes this header computes the
 * same bits as one that calls fsw_vec.c; the call and its argument passing
 * are gone.  The public functions stay in fsw_vec.c with the same names and
 * signatures (the library's API and ABI do not change).
 *
 * Include after fsw/fsw_vec.h: the macros at the end make the module's calls
 * of those names use the inline bodies. */
#ifndef FSW_VEC_INLINE_H
#define FSW_VEC_INLINE_H

#include <float.h>
#include <stdint.h>
#include <string.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_vec.h"

static inline void fsw_v3i_set(fsw_real out[3], fsw_real x, fsw_real y, fsw_real z)
{
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

static inline void fsw_v3i_copy(fsw_real out[3], const fsw_real a[3])
{
  fsw_real t0 = a[0], t1 = a[1], t2 = a[2];
  out[0] = t0;
  out[1] = t1;
  out[2] = t2;
}

static inline void fsw_v3i_zero(fsw_real out[3])
{
  fsw_v3i_set(out, FSW_R(0.0), FSW_R(0.0), FSW_R(0.0));
}

static inline void fsw_v3i_add(fsw_real out[3], const fsw_real a[3], const fsw_real b[3])
{
  fsw_v3i_set(out, a[0] + b[0], a[1] + b[1], a[2] + b[2]);
}

static inline void fsw_v3i_sub(fsw_real out[3], const fsw_real a[3], const fsw_real b[3])
{
  fsw_v3i_set(out, a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

static inline void fsw_v3i_scale(fsw_real out[3], fsw_real s, const fsw_real a[3])
{
  fsw_v3i_set(out, s * a[0], s * a[1], s * a[2]);
}

static inline void fsw_v3i_axpy(fsw_real out[3], const fsw_real a[3], fsw_real s,
                                const fsw_real b[3])
{
  fsw_v3i_set(out, a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]);
}

static inline fsw_real fsw_v3i_dot(const fsw_real a[3], const fsw_real b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void fsw_v3i_cross(fsw_real out[3], const fsw_real a[3], const fsw_real b[3])
{
  fsw_v3i_set(out, a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
              a[0] * b[1] - a[1] * b[0]);
}

static inline fsw_real fsw_v3i_norm2(const fsw_real a[3]) { return fsw_v3i_dot(a, a); }

/* 1 if all entries are finite; evaluated without branches (every entry is
 * tested), the same result as fsw_vn_is_finite(a, 3). */
static inline int fsw_v3i_is_finite(const fsw_real a[3])
{
  return (isfinite(a[0]) != 0) & (isfinite(a[1]) != 0) & (isfinite(a[2]) != 0);
}

/* fsw_vn_is_finite(a, n): 1 if all n entries are finite. */
static inline int fsw_vni_is_finite(const fsw_real *a, int n)
{
  int i;
  for (i = 0; i < n; i++) {
    if (!isfinite(a[i])) { return 0; } }
  return 1;
}

/* fsw_vn_copy and fsw_vn_zero of n entries.  The copy runs through the
 * entries also when out == a (each entry is written with its own value, the
 * same result as fsw_vn_copy's early return). */
static inline void fsw_vni_copy(fsw_real *out, const fsw_real *a, int n)
{
  int i;
  for (i = 0; i < n; i++) { out[i] = a[i]; }
}

static inline void fsw_vni_zero(fsw_real *out, int n)
{
  int i;
  for (i = 0; i < n; i++) { out[i] = FSW_R(0.0); }
}

static inline fsw_real fsw_vni_dot(const fsw_real *a, const fsw_real *b, int n)
{
  fsw_real s = FSW_R(0.0);
  int i;
  for (i = 0; i < n; i++) { s += a[i] * b[i]; }
  return s;
}

static inline void fsw_m33i_mult_v3(fsw_real out[3], const fsw_real a[3][3], const fsw_real v[3])
{
  fsw_v3i_set(out, fsw_v3i_dot(a[0], v), fsw_v3i_dot(a[1], v), fsw_v3i_dot(a[2], v));
}

static inline void fsw_m33i_tmult_v3(fsw_real out[3], const fsw_real a[3][3], const fsw_real v[3])
{
  fsw_v3i_set(out, a[0][0] * v[0] + a[1][0] * v[1] + a[2][0] * v[2],
              a[0][1] * v[0] + a[1][1] * v[1] + a[2][1] * v[2],
              a[0][2] * v[0] + a[1][2] * v[1] + a[2][2] * v[2]);
}

/* fsw_vn_max_abs(a, n): max |a_i| (0 for n <= 0); a NaN entry gives NaN
 * (and keeps it: no later entry compares above NaN), so the result is
 * finite exactly when every entry is. */
static inline fsw_real fsw_vni_max_abs(const fsw_real *a, int n)
{
  fsw_real m = FSW_R(0.0);
  int i;
  for (i = 0; i < n; i++) {
    fsw_real v = FSW_FABS(a[i]);
    if (v > m || v != v) { m = v; } /* NaN propagates */
  }
  return m;
}

/* sqrt(sum (a_i / m)^2) for m = fsw_vn_max_abs(a, 3) > 0 and finite: the
 * root fsw_vn_norm forms, so fsw_v3_norm(a) is m times it, bit for bit.  For
 * b = p a with p = fsw_pow2_scale(m) it is also the root fsw_vn_norm forms
 * for b, so fsw_v3_norm(b) is (m p) times it without searching b again:
 * max |b_i| is m p exactly (|a_k| = m gives the same product; every other
 * |b_i| is a rounded |a_i| p <= m p), and b_i / (m p) is the exact quotient
 * a_i / m rounded once; p a_i is rounded only where it is subnormal with
 * p < 1, where m p is in [1/2, 1), so both quotients are below 2^MIN_EXP
 * and both squares round to 0. */
static inline fsw_real fsw_v3i_scaled_root(const fsw_real a[3], fsw_real m)
{
  fsw_real s = FSW_R(0.0);
  fsw_real t;
  t = a[0] / m;
  s += t * t;
  t = a[1] / m;
  s += t * t;
  t = a[2] / m;
  s += t * t;
  return FSW_SQRT(s);
}

/* Powers of two from the bits of the real type (IEEE 754 binary64, or
 * binary32 when fsw_real is float: the same bit layout as the link's wire
 * encoding assumes).  They give the bits frexp and ldexp give, for normal
 * numbers only (the callers keep frexp and ldexp for the rest), without a
 * call into the math library. */
#if FSW_USE_FLOAT
typedef uint32_t fsw_real_bits;
#define FSW_RB_MANT 23
#define FSW_RB_BIAS 127
#define FSW_RB_EMASK 0xFFu
#define FSW_RB_MIN_EXP FLT_MIN_EXP
#define FSW_RB_MAX_EXP FLT_MAX_EXP
#define FSW_RB_MIN_NORMAL FLT_MIN
#else
typedef uint64_t fsw_real_bits;
#define FSW_RB_MANT 52
#define FSW_RB_BIAS 1023
#define FSW_RB_EMASK 0x7FFu
#define FSW_RB_MIN_EXP DBL_MIN_EXP
#define FSW_RB_MAX_EXP DBL_MAX_EXP
#define FSW_RB_MIN_NORMAL DBL_MIN
#endif

/* 1 if 2^k is a normal number of the real type. */
static inline int fsw_pow2i_normal(int k)
{
  return (k >= (FSW_RB_MIN_EXP - 1)) && (k <= (FSW_RB_MAX_EXP - 1));
}

/* 2^k for a k with fsw_pow2i_normal(k): exactly ldexp(1, k). */
static inline fsw_real fsw_pow2i(int k)
{
  const int biased = k + FSW_RB_BIAS; /* 1 .. 2 MAX_EXP - 2 */
  fsw_real_bits bits = (fsw_real_bits)biased;
  fsw_real v;
  bits <<= FSW_RB_MANT;
  (void)memcpy(&v, &bits, sizeof v);
  return v;
}

/* The exponent e of frexp(m, &e) (m = f 2^e, 1/2 <= f < 1) for a normal,
 * finite m: the biased exponent field less (bias - 1). */
static inline int fsw_frexp_exp_normal(fsw_real m)
{
  fsw_real_bits bits;
  int field;
  (void)memcpy(&bits, &m, sizeof bits);
  bits >>= FSW_RB_MANT;
  bits &= FSW_RB_EMASK;
  field = (int)bits;
  return field - (FSW_RB_BIAS - 1);
}

/* fsw_vec.c includes this header for the functions above only.  A build
 * optimised for size (-Os, __OPTIMIZE_SIZE__) keeps the calls of fsw_vec.c:
 * the same bits, one copy of each helper instead of one per module. */
#ifndef FSW_VEC_INLINE_NO_ALIASES
#ifndef __OPTIMIZE_SIZE__
#define fsw_v3_set fsw_v3i_set
#define fsw_v3_copy fsw_v3i_copy
#define fsw_v3_zero fsw_v3i_zero
#define fsw_v3_add fsw_v3i_add
#define fsw_v3_sub fsw_v3i_sub
#define fsw_v3_scale fsw_v3i_scale
#define fsw_v3_axpy fsw_v3i_axpy
#define fsw_v3_dot fsw_v3i_dot
#define fsw_v3_cross fsw_v3i_cross
#define fsw_v3_norm2 fsw_v3i_norm2
#define fsw_v3_is_finite fsw_v3i_is_finite
#define fsw_vn_copy fsw_vni_copy
#define fsw_vn_zero fsw_vni_zero
#define fsw_vn_dot fsw_vni_dot
#define fsw_vn_max_abs fsw_vni_max_abs
#define fsw_m33_mult_v3 fsw_m33i_mult_v3
#define fsw_m33_tmult_v3 fsw_m33i_tmult_v3
#endif
#endif

#endif /* FSW_VEC_INLINE_H */

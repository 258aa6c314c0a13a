// Vector and 3x3 matrix operations: closed-form values, aliasing, and
// properties over seeded random inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fsw/fsw_vec.h"
#include "kestrel_test_support.h"

namespace {

const double kTol = kt::tol(1e-14, 1e-6);

void rnd3(kt::Rng& r, fsw_real v[3], double lo = -10.0, double hi = 10.0)
{
  for (int i = 0; i < 3; i++) v[i] = static_cast<fsw_real>(r.uniform(lo, hi));
}
void rnd33(kt::Rng& r, fsw_real m[3][3])
{
  for (int i = 0; i < 3; i++) rnd3(r, m[i]);
}

// Verifies: REQ-VEC-001
TEST(FswV3, ClosedFormValues)
{
  fsw_real a[3] = {1, 2, 3}, b[3] = {4, -5, 6}, c[3];
  fsw_v3_add(c, a, b);
  EXPECT_EQ(5, c[0]); EXPECT_EQ(-3, c[1]); EXPECT_EQ(9, c[2]);
  fsw_v3_sub(c, a, b);
  EXPECT_EQ(-3, c[0]); EXPECT_EQ(7, c[1]); EXPECT_EQ(-3, c[2]);
  fsw_v3_scale(c, FSW_R(2.0), a);
  EXPECT_EQ(2, c[0]); EXPECT_EQ(4, c[1]); EXPECT_EQ(6, c[2]);
  fsw_v3_axpy(c, a, FSW_R(-1.0), b);
  EXPECT_EQ(-3, c[0]); EXPECT_EQ(7, c[1]); EXPECT_EQ(-3, c[2]);
  EXPECT_EQ(4 - 10 + 18, fsw_v3_dot(a, b));
  // (1,2,3) x (4,-5,6) = (2*6 - 3*(-5), 3*4 - 1*6, 1*(-5) - 2*4) = (27, 6, -13)
  fsw_v3_cross(c, a, b);
  EXPECT_EQ(27, c[0]); EXPECT_EQ(6, c[1]); EXPECT_EQ(-13, c[2]);
  EXPECT_EQ(14, fsw_v3_norm2(a));
  fsw_real p[3] = {3, 4, 12};
  EXPECT_NEAR(13.0, fsw_v3_norm(p), kTol * 13);
  fsw_v3_zero(c);
  EXPECT_EQ(0, c[0] + c[1] + c[2]);
}

// Verifies: REQ-VEC-001
TEST(FswV3, CrossIsAliasSafeAndOrthogonal)
{
  kt::Rng r(11);
  for (int k = 0; k < 200; k++) {
    fsw_real a[3], b[3], c[3], a2[3];
    rnd3(r, a);
    rnd3(r, b);
    fsw_v3_cross(c, a, b);
    fsw_v3_copy(a2, a);
    fsw_v3_cross(a2, a2, b);  // output aliases first input
    for (int i = 0; i < 3; i++) EXPECT_EQ(c[i], a2[i]);
    const double scale = fsw_v3_norm(a) * fsw_v3_norm(b) * fsw_v3_norm(c) + 1e-300;
    EXPECT_NEAR(0.0, fsw_v3_dot(c, a) / scale, kTol * 10);
    EXPECT_NEAR(0.0, fsw_v3_dot(c, b) / scale, kTol * 10);
  }
}

// Verifies: REQ-VEC-002
TEST(FswV3, NormalizeHandlesZeroAndNonFinite)
{
  fsw_real v[3] = {0, 0, 0}, out[3] = {9, 9, 9};
  EXPECT_EQ(0, fsw_v3_normalize(out, v));
  EXPECT_EQ(0, out[0]); EXPECT_EQ(0, out[1]); EXPECT_EQ(0, out[2]);
  v[0] = std::numeric_limits<fsw_real>::quiet_NaN();
  EXPECT_EQ(0, fsw_v3_normalize(out, v));
  EXPECT_EQ(0, out[0]);
  v[0] = std::numeric_limits<fsw_real>::infinity();
  EXPECT_EQ(0, fsw_v3_normalize(out, v));
  fsw_real w[3] = {0, -2, 0};
  EXPECT_EQ(1, fsw_v3_normalize(w, w));
  EXPECT_EQ(0, w[0]); EXPECT_EQ(-1, w[1]); EXPECT_EQ(0, w[2]);
  EXPECT_FALSE(fsw_v3_is_finite(v));
  EXPECT_TRUE(fsw_v3_is_finite(w));
}

// fsw_v3_norm_normalize gives fsw_vn_norm's |a| and the direction the
// scaled normalisation gives, bit for bit, from one search and one sum.  The
// direction's reference is written here: m = max |a_i|, 2^-e from frexp and
// ldexp (e clamped for a subnormal m), b = 2^-e a, n = (m 2^-e) sqrt(sum
// (b_i / (m 2^-e))^2), out = b / n.  Entries span the whole exponent range
// with mixed scales, so that 2^-e a_i is subnormal for some entries.
// Verifies: REQ-VEC-002, REQ-VEC-003
TEST(FswV3, NormNormalizeIsTheNormAndTheScaledDirection)
{
  using L = std::numeric_limits<fsw_real>;
  kt::Rng r(20261206);
  auto same = [](fsw_real x, fsw_real y) {
    return (std::isnan(x) && std::isnan(y)) || (x == y && std::signbit(x) == std::signbit(y));
  };
  for (int k = 0; k < 20000; k++) {
    fsw_real a[3];
    for (int i = 0; i < 3; i++) {
      const int e = r.uniform_int(L::min_exponent - L::digits, L::max_exponent - 1);
      a[i] = std::ldexp(static_cast<fsw_real>(r.uniform(0.5, 1.0)), e);
      if (r.uniform() < 0.5) a[i] = -a[i];
      if (r.uniform() < 0.05) a[i] = 0;
    }
    fsw_real out[3], norm = -1;
    const int ok = fsw_v3_norm_normalize(out, &norm, a);
    ASSERT_TRUE(same(fsw_vn_norm(a, 3), norm)) << k;
    fsw_real m = 0;
    for (int i = 0; i < 3; i++) m = std::max(m, std::fabs(a[i]));
    if (m == 0) {
      EXPECT_EQ(0, ok);
      continue;
    }
    int e = 0;
    (void)std::frexp(m, &e);
    if (-e > L::max_exponent - 1) e = -(L::max_exponent - 1);
    const fsw_real p = std::ldexp(FSW_R(1.0), -e);
    const fsw_real b[3] = {p * a[0], p * a[1], p * a[2]};
    const fsw_real mb = m * p;
    fsw_real sum = 0;
    for (int i = 0; i < 3; i++) {
      const fsw_real t = b[i] / mb;
      sum += t * t;
    }
    const fsw_real n = mb * std::sqrt(sum);
    ASSERT_EQ(1, ok) << k;
    for (int i = 0; i < 3; i++) ASSERT_TRUE(same(b[i] / n, out[i])) << k << " " << i;
    fsw_real again[3] = {a[0], a[1], a[2]}, norm2 = -1;  // out may be a
    ASSERT_EQ(1, fsw_v3_norm_normalize(again, &norm2, again));
    for (int i = 0; i < 3; i++) ASSERT_TRUE(same(out[i], again[i])) << k;
    ASSERT_TRUE(same(norm, norm2));
  }
  // zero, NaN and infinite a: 0 returned, out = 0, *norm = fsw_vn_norm's 0, NaN, infinity
  fsw_real z[3] = {0, 0, 0}, out[3] = {9, 9, 9}, norm = -1;
  EXPECT_EQ(0, fsw_v3_norm_normalize(out, &norm, z));
  EXPECT_EQ(0, norm);
  EXPECT_EQ(0, out[0]); EXPECT_EQ(0, out[1]); EXPECT_EQ(0, out[2]);
  fsw_real v[3] = {1, L::quiet_NaN(), 2};
  out[1] = 9;
  EXPECT_EQ(0, fsw_v3_norm_normalize(out, &norm, v));
  EXPECT_TRUE(std::isnan(norm));
  EXPECT_EQ(0, out[1]);
  v[1] = -L::infinity();
  out[2] = 9;
  EXPECT_EQ(0, fsw_v3_norm_normalize(out, &norm, v));
  EXPECT_EQ(L::infinity(), norm);
  EXPECT_EQ(0, out[2]);
}

// Verifies: REQ-VEC-003
TEST(FswVn, NormIsOverflowAndUnderflowSafe)
{
  const fsw_real big = std::numeric_limits<fsw_real>::max() / 4;
  fsw_real v[2] = {big, big};
  // |(b, b)| = b sqrt(2): the naive sum of squares overflows to Inf.
  EXPECT_NEAR(1.0, fsw_vn_norm(v, 2) / (static_cast<double>(big) * std::sqrt(2.0)), kTol * 10);
  const fsw_real tiny = std::numeric_limits<fsw_real>::min() * 8;
  fsw_real t[2] = {tiny * 3, tiny * 4};  // squares underflow; the norm is 5 tiny
  EXPECT_NEAR(1.0, fsw_vn_norm(t, 2) / (5.0 * static_cast<double>(tiny)), kTol * 10);
  fsw_real z[4] = {0, 0, 0, 0};
  EXPECT_EQ(0, fsw_vn_norm(z, 4));
  EXPECT_EQ(0, fsw_vn_norm(z, 0));
}

// Verifies: REQ-VEC-001
TEST(FswVn, BasicOpsAndFiniteness)
{
  fsw_real a[5] = {1, -2, 3, -4, 5}, b[5] = {5, 4, 3, 2, 1}, c[5];
  EXPECT_EQ(5 - 8 + 9 - 8 + 5, fsw_vn_dot(a, b, 5));
  fsw_vn_add(c, a, b, 5);
  EXPECT_EQ(6, c[0]); EXPECT_EQ(6, c[4]);
  fsw_vn_sub(c, a, b, 5);
  EXPECT_EQ(-4, c[0]); EXPECT_EQ(4, c[4]);
  fsw_vn_scale(c, FSW_R(-2.0), a, 5);
  EXPECT_EQ(-2, c[0]); EXPECT_EQ(8, c[3]);
  EXPECT_EQ(5, fsw_vn_max_abs(a, 5));
  fsw_vn_copy(c, a, 5);
  for (int i = 0; i < 5; i++) EXPECT_EQ(a[i], c[i]);
  fsw_vn_zero(c, 5);
  for (int i = 0; i < 5; i++) EXPECT_EQ(0, c[i]);
  EXPECT_TRUE(fsw_vn_is_finite(a, 5));
  a[4] = std::numeric_limits<fsw_real>::quiet_NaN();
  EXPECT_FALSE(fsw_vn_is_finite(a, 5));
  EXPECT_TRUE(fsw_vn_is_finite(a, 4));  // only n entries are read
  EXPECT_TRUE(std::isnan(fsw_vn_max_abs(a, 5)));  // NaN propagates
}

// Verifies: REQ-VEC-001
TEST(FswM33, ClosedFormValues)
{
  const fsw_real A[3][3] = {{2, 0, 1}, {1, 3, 2}, {1, 1, 1}};
  // det = 2(3*1 - 2*1) - 0 + 1(1*1 - 3*1) = 2 - 2 = 0 -> use another one
  const fsw_real B[3][3] = {{4, 7, 2}, {3, 6, 1}, {2, 5, 3}};
  // det(B) = 4(18-5) - 7(9-2) + 2(15-12) = 52 - 49 + 6 = 9
  EXPECT_NEAR(0.0, fsw_m33_det(A), kTol);
  EXPECT_NEAR(9.0, fsw_m33_det(B), kTol * 9);
  EXPECT_EQ(13, fsw_m33_trace(B));
  fsw_real Binv[3][3];
  ASSERT_EQ(1, fsw_m33_inverse(Binv, B, FSW_R(1e-9)));
  // adj(B)/9: cofactors computed by hand
  const double want[3][3] = {{13.0 / 9, -11.0 / 9, -5.0 / 9},
                             {-7.0 / 9, 8.0 / 9, 2.0 / 9},
                             {3.0 / 9, -6.0 / 9, 3.0 / 9}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_NEAR(want[i][j], Binv[i][j], kTol * 10);
  fsw_real Ainv[3][3];
  EXPECT_EQ(0, fsw_m33_inverse(Ainv, A, FSW_R(1e-9)));
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_EQ(0, Ainv[i][j]);

  fsw_real v[3] = {1, 2, 3}, out[3];
  fsw_m33_mult_v3(out, B, v);  // (4+14+6, 3+12+3, 2+10+9)
  EXPECT_EQ(24, out[0]); EXPECT_EQ(18, out[1]); EXPECT_EQ(21, out[2]);
  fsw_m33_tmult_v3(out, B, v);  // (4+6+6, 7+12+15, 2+2+9)
  EXPECT_EQ(16, out[0]); EXPECT_EQ(34, out[1]); EXPECT_EQ(13, out[2]);
}

// Verifies: REQ-VEC-004
TEST(FswM33, InverseSingularityTestIsScaleInvariant)
{
  // The same nearly singular shape, expressed in tiny and in huge units,
  // gets the same decision; an absolute determinant threshold would not.
  kt::Rng r(5);
  for (int k = 0; k < 50; k++) {
    fsw_real M[3][3];
    rnd33(r, M);
    const fsw_real scales[] = {FSW_R(1e-6), FSW_R(1.0), FSW_R(1e6)};
    int decisions[3];
    for (int s = 0; s < 3; s++) {
      fsw_real S[3][3], inv[3][3];
      fsw_m33_scale(S, scales[s], FSW_CM33(M));
      decisions[s] = fsw_m33_inverse(inv, FSW_CM33(S), FSW_R(1e-3));
    }
    EXPECT_EQ(decisions[0], decisions[1]);
    EXPECT_EQ(decisions[1], decisions[2]);
  }
}

// Verifies: REQ-VEC-001
TEST(FswM33, PropertiesOverRandomMatrices)
{
  kt::Rng r(7);
  for (int k = 0; k < 200; k++) {
    fsw_real A[3][3], B[3][3], AB[3][3], ABt[3][3], Bt[3][3], At[3][3], T[3][3];
    rnd33(r, A);
    rnd33(r, B);
    fsw_m33_mult(AB, FSW_CM33(A), FSW_CM33(B));
    // det(AB) = det(A) det(B)
    const double dA = fsw_m33_det(FSW_CM33(A)), dB = fsw_m33_det(FSW_CM33(B));
    EXPECT_NEAR(dA * dB, fsw_m33_det(FSW_CM33(AB)), kTol * 1e4 * (1 + std::fabs(dA * dB)));
    // A B^T two ways
    fsw_m33_transpose(Bt, FSW_CM33(B));
    fsw_m33_mult(T, FSW_CM33(A), FSW_CM33(Bt));
    fsw_m33_mult_t(ABt, FSW_CM33(A), FSW_CM33(B));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_NEAR(T[i][j], ABt[i][j], kTol * 1e3);
    // in-place transpose twice is the identity map
    fsw_m33_copy(At, FSW_CM33(A));
    fsw_m33_transpose(At, FSW_CM33(At));
    fsw_m33_transpose(At, FSW_CM33(At));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_EQ(A[i][j], At[i][j]);
    // in-place multiply: A <- A B
    fsw_m33_copy(T, FSW_CM33(A));
    fsw_m33_mult(T, FSW_CM33(T), FSW_CM33(B));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_EQ(AB[i][j], T[i][j]);
    // A A^-1 = I when well conditioned
    fsw_real inv[3][3], P[3][3];
    if (fsw_m33_inverse(inv, FSW_CM33(A), FSW_R(1e-2))) {
      fsw_m33_mult(P, FSW_CM33(A), FSW_CM33(inv));
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) EXPECT_NEAR(i == j ? 1.0 : 0.0, P[i][j], kTol * 1e4);
    }
    // add/sub/scale
    fsw_real S[3][3], D[3][3];
    fsw_m33_add(S, FSW_CM33(A), FSW_CM33(B));
    fsw_m33_sub(D, FSW_CM33(S), FSW_CM33(B));
    fsw_m33_scale(T, FSW_R(2.0), FSW_CM33(A));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        EXPECT_NEAR(A[i][j], D[i][j], kTol * 1e2);
        EXPECT_EQ(2 * A[i][j], T[i][j]);
      }
  }
}

// Verifies: REQ-VEC-001
TEST(FswM33, IdentityZeroAndFiniteness)
{
  fsw_real I[3][3], Z[3][3];
  fsw_m33_identity(I);
  fsw_m33_zero(Z);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      EXPECT_EQ(i == j ? 1 : 0, I[i][j]);
      EXPECT_EQ(0, Z[i][j]);
    }
  EXPECT_TRUE(fsw_m33_is_finite(FSW_CM33(I)));
  I[2][1] = std::numeric_limits<fsw_real>::infinity();
  EXPECT_FALSE(fsw_m33_is_finite(FSW_CM33(I)));
  fsw_real inv[3][3];
  EXPECT_EQ(0, fsw_m33_inverse(inv, FSW_CM33(I), FSW_R(1e-9)));
}

}  // namespace

// Issue 21: non-finite and aliased arguments of the helpers.  A zero, NaN or
// infinite magnitude has no power-of-two scale (1 is returned); a vector
// with an Inf has no direction (0, return 0) and its norm is Inf; a NaN
// anywhere in a matrix makes it non-finite; copying onto itself is a no-op.
// Verifies: REQ-VEC-001, REQ-VEC-002
TEST(FswVecIssue21, NonFiniteAndAliasedArguments)
{
  const fsw_real inf = std::numeric_limits<fsw_real>::infinity();
  const fsw_real nan = std::numeric_limits<fsw_real>::quiet_NaN();
  EXPECT_EQ(1.0, fsw_pow2_scale(0));
  EXPECT_EQ(1.0, fsw_pow2_scale(inf));
  EXPECT_EQ(1.0, fsw_pow2_scale(nan));
  EXPECT_EQ(0.25, fsw_pow2_scale(3));  // 3 = 0.75 * 2^2 -> 2^-2
  const fsw_real a[3] = {inf, 1, 0};
  fsw_real u[3] = {9, 9, 9};
  EXPECT_EQ(0, fsw_v3_normalize(u, a));
  for (int i = 0; i < 3; i++) EXPECT_EQ(0.0, u[i]);
  EXPECT_EQ(inf, fsw_vn_norm(a, 3));
  for (int r = 0; r < 3; r++) {
    fsw_real m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    EXPECT_EQ(1, fsw_m33_is_finite(m));
    m[r][2] = nan;
    EXPECT_EQ(0, fsw_m33_is_finite(m)) << "row " << r;
  }
  fsw_real v[3] = {1, 2, 3};
  fsw_vn_copy(v, v, 3);
  EXPECT_EQ(2.0, v[1]);
  fsw_real m[3][3] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  fsw_m33_copy(m, m);
  EXPECT_EQ(6.0, m[1][2]);
}

// fsw_pow2_scale(m) = 2^-e with m = f 2^e, 1/2 <= f < 1, over the whole
// range of the real type: m = 2^j and m = 1.5 2^j give 2^-(j+1) (std::ldexp
// as the reference), so m p is exactly 1/2 and 3/4; where 2^-(j+1) is not
// a normal number (m >= 2^(MAX_EXP-2)) it is the subnormal power of two;
// a subnormal m gives the largest finite power of two, 2^(MAX_EXP-1).
// Verifies: REQ-VEC-001
TEST(FswVec, Pow2ScaleOverTheWholeRange)
{
  using L = std::numeric_limits<fsw_real>;
  for (int j = L::min_exponent - 1; j < L::max_exponent; j++) {
    const fsw_real p = std::ldexp(FSW_R(1.0), -(j + 1));
    EXPECT_EQ(p, fsw_pow2_scale(std::ldexp(FSW_R(1.0), j))) << j;
    EXPECT_EQ(p, fsw_pow2_scale(std::ldexp(FSW_R(1.5), j))) << j;
    if (j + 1 <= L::max_exponent - 1) {
      EXPECT_EQ(FSW_R(0.5), std::ldexp(FSW_R(1.0), j) * fsw_pow2_scale(std::ldexp(FSW_R(1.0), j))) << j;
      EXPECT_EQ(FSW_R(0.75), std::ldexp(FSW_R(1.5), j) * fsw_pow2_scale(std::ldexp(FSW_R(1.5), j))) << j;
    }
  }
  const fsw_real big = std::ldexp(FSW_R(1.0), L::max_exponent - 1);
  EXPECT_EQ(big, fsw_pow2_scale(L::denorm_min()));
  EXPECT_EQ(big, fsw_pow2_scale(L::min() / 4));
  EXPECT_EQ(big / 2, fsw_pow2_scale(L::min() / 2));
  EXPECT_EQ(std::ldexp(FSW_R(1.0), -L::max_exponent), fsw_pow2_scale(L::max()));
}

// Mutation seed 31337 (fsw_vec.c:277): the singularity test is relative to
// the product of all three row norms.  diag(s, 1, 1) with s = 1e-9 has
// |det| = s and |a0| |a1| |a2| = s, so |det| / scale = 1 > rel_tol = 1e-6:
// invertible, inverse diag(1/s, 1, 1), however small row 0 is.  A scale
// that left row 0 out (|a1|^2 |a2| = 1) would call it singular (1e-9 < 1e-6).
// Verifies: REQ-VEC-004
TEST(FswM33Seed31337, SingularityScaleUsesEveryRowNorm)
{
  const fsw_real s = FSW_R(1e-9);
  const fsw_real A[3][3] = {{s, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  fsw_real inv[3][3];
  ASSERT_EQ(1, fsw_m33_inverse(inv, A, FSW_R(1e-6)));
  const double want00 = 1.0 / static_cast<double>(s);
  EXPECT_NEAR(want00, inv[0][0], kTol * want00);
  EXPECT_EQ(1, inv[1][1]);  // 1*1 / 1, exact
  EXPECT_EQ(1, inv[2][2]);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      if (i != j) EXPECT_EQ(0, inv[i][j]) << i << "," << j;
}

// Mutation seed 31337 (fsw_vec.c:278): when the product of the row norms
// underflows to 0 the relative test has no scale and the matrix is refused
// (return 0, out = 0), even though the adjugate's determinant did not
// underflow.  diag(x, x, 1/x) with x = 2^-600 (float: 2^-80): the scale is
// (x * x) * (1/x) and x * x = 2^-1200 (float 2^-160) is below the smallest
// subnormal, so it is 0; det = x * (x * (1/x)) = x is not 0 and passes
// |det| > rel_tol * 0.  Only the 'scale > 0' guard refuses it.
// Verifies: REQ-VEC-004
TEST(FswM33Seed31337, UnderflowedScaleIsRefused)
{
  const int e = kt::kFloat ? 80 : 600;
  const fsw_real x = static_cast<fsw_real>(std::ldexp(1.0, -e));
  const fsw_real y = static_cast<fsw_real>(std::ldexp(1.0, e));
  ASSERT_EQ(0, x * x);  // the premise: the norm product underflows
  ASSERT_NE(0, x * (x * y));
  const fsw_real A[3][3] = {{x, 0, 0}, {0, x, 0}, {0, 0, y}};
  fsw_real inv[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) inv[i][j] = 7;
  EXPECT_EQ(0, fsw_m33_inverse(inv, A, FSW_R(1e-6)));
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_EQ(0, inv[i][j]) << i << "," << j;
}

// Kernels K1 (scale-invariant minimum-norm solve) and K2 (rank-robust
// null-space projector) of docs/fsw/core.md, "Kernels".  Closed-form cases, an
// independent normal-equation solver written here, and properties over
// seeded random geometries with 3..FSW_MAX_EFF columns.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

#include "fsw/fsw_linalg.h"
#include "fsw/fsw_vec.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

const double kTol = kt::tol(1e-12, 2e-5);
const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();

struct Mat3N {
  fsw_real a[3][FSW_MAX_EFF];
};

Mat3N random_matrix(kt::Rng& r, int m, int n, double scale = 1.0)
{
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  for (int i = 0; i < m; i++)
    for (int j = 0; j < n; j++) A.a[i][j] = static_cast<fsw_real>(scale * r.uniform(-1, 1));
  return A;
}

/* Hadamard ratio det(A A^T) / prod(diag(A A^T)) in (0, 1]: 1 for orthogonal
 * rows, 0 for dependent ones.  Used to keep random draws well conditioned
 * where a test is about accuracy, not about the rank decision. */
double hadamard_ratio(const Mat3N& A, int m, int n)
{
  double M[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < m; i++)
    for (int j = 0; j < m; j++) {
      double s = 0;
      for (int k = 0; k < n; k++) s += static_cast<double>(A.a[i][k]) * A.a[j][k];
      M[i][j] = s;
    }
  const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                     M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
  return det / (M[0][0] * M[1][1] * M[2][2]);
}

Mat3N random_well_conditioned(kt::Rng& r, int m, int n)
{
  Mat3N A = random_matrix(r, m, n);
  while (hadamard_ratio(A, m, n) < 1e-2) A = random_matrix(r, m, n);
  return A;
}

/* Independent reference: x = A^T (A A^T)^-1 b by Gauss-Jordan with partial
 * pivoting in double (a different algorithm from the library's Cholesky). */
void ref_minnorm(double* x, const Mat3N& A, const double* b, int m, int n)
{
  double M[3][4];
  for (int i = 0; i < m; i++) {
    for (int j = 0; j < m; j++) {
      double s = 0;
      for (int k = 0; k < n; k++) s += static_cast<double>(A.a[i][k]) * A.a[j][k];
      M[i][j] = s;
    }
    M[i][m] = b[i];
  }
  for (int c = 0; c < m; c++) {
    int p = c;
    for (int i = c + 1; i < m; i++)
      if (std::fabs(M[i][c]) > std::fabs(M[p][c])) p = i;
    for (int j = 0; j <= m; j++) std::swap(M[c][j], M[p][j]);
    for (int i = 0; i < m; i++) {
      if (i == c) continue;
      const double f = M[i][c] / M[c][c];
      for (int j = 0; j <= m; j++) M[i][j] -= f * M[c][j];
    }
  }
  double y[3];
  for (int i = 0; i < m; i++) y[i] = M[i][m] / M[i][i];
  for (int k = 0; k < n; k++) {
    x[k] = 0;
    for (int i = 0; i < m; i++) x[k] += static_cast<double>(A.a[i][k]) * y[i];
  }
}

// Verifies: REQ-LINALG-001
TEST(FswMinNorm, ClosedFormCases)
{
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  fsw_real x[FSW_MAX_EFF], b[3] = {2, 0, 0};
  // one row [1 1]: the minimum-norm split of 2 is (1, 1)
  A.a[0][0] = 1;
  A.a[0][1] = 1;
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, 1, 2));
  EXPECT_NEAR(1.0, x[0], kTol);
  EXPECT_NEAR(1.0, x[1], kTol);
  // 3 x 4 pyramid-like [I | 1]: A A^T = I + 1 1^T, (I + 11^T)^-1 = I - 11^T/4,
  // so for b = (1,0,0): y = (3/4, -1/4, -1/4), x = A^T y = (3/4, -1/4, -1/4, 1/4).
  std::memset(&A, 0, sizeof A);
  for (int i = 0; i < 3; i++) {
    A.a[i][i] = 1;
    A.a[i][3] = 1;
  }
  fsw_real b1[3] = {1, 0, 0};
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b1, 3, 4));
  EXPECT_NEAR(0.75, x[0], kTol);
  EXPECT_NEAR(-0.25, x[1], kTol);
  EXPECT_NEAR(-0.25, x[2], kTol);
  EXPECT_NEAR(0.25, x[3], kTol);
  // square, invertible: x = A^-1 b exactly
  std::memset(&A, 0, sizeof A);
  A.a[0][0] = 2;
  A.a[1][1] = 4;
  A.a[2][2] = FSW_R(0.5);
  fsw_real b2[3] = {1, 1, 1};
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b2, 3, 3));
  EXPECT_NEAR(0.5, x[0], kTol);
  EXPECT_NEAR(0.25, x[1], kTol);
  EXPECT_NEAR(2.0, x[2], kTol);
}

// Issue 21: the forward substitution L y = b must subtract row 0's term
// L_10 y_0 from b_1.  A = [1 0; 1 d] (square, nearly parallel rows) with
// d = 2^-19 in double, 2^-8 in float (d^2 = 3.6e-12 > FSW_RANK_TOL = 1e-12,
// 1.5e-5 > 1e-5: full rank).  With the power-of-two scalings every number is
// exact: A A^T = [1 1; 1 1 + d^2], L = [1 0; 1 d], and b = (0.3, 0.3) gives
// y = (0.3, (0.3 - 1 * 0.3) / d) = (0.3, 0), z = (0.3, 0), x = A^T z =
// (0.3, 0) = A^-1 b (x0 = b0, x1 = (b1 - b0) / d): exact, residual 0.  Were
// the coupling dropped, y_1 = 0.3 / d and z_1 = 0.3 / d^2 (2^38 or 2^16 times
// b): x_0 = z_0 + z_1 cancels 38 (16) bits, an error of ~2^-15 (2^-8)
// relative, that the one refinement step does not remove (the residual
// test then refuses it: FSW_E_SINGULAR).
// Verifies: REQ-LINALG-001
TEST(FswMinNorm, Issue21ForwardSubstitutionUsesTheCouplingToRowZero)
{
  const fsw_real d = static_cast<fsw_real>(kt::tol(std::ldexp(1.0, -19), std::ldexp(1.0, -8)));
  ASSERT_GT(double(d) * double(d), double(FSW_RANK_TOL));  // full rank by the pivot test
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  A.a[0][0] = 1;
  A.a[1][0] = 1;
  A.a[1][1] = d;
  fsw_real x[FSW_MAX_EFF], b[3] = {FSW_R(0.3), FSW_R(0.3), 0};
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, 2, 2));
  EXPECT_NEAR(double(b[0]), double(x[0]), kTol);
  EXPECT_NEAR(0.0, double(x[1]), kTol);
  // the same with a third row coupled to row 0 only: A = [1 0 0; 1 d 0; 1 0 d],
  // b = (0.3, 0.3, 0.3) -> x = (0.3, 0, 0) (L_20 = 1 couples row 2 to row 0)
  A.a[2][0] = 1;
  A.a[2][2] = d;
  b[2] = FSW_R(0.3);
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, 3, 3));
  EXPECT_NEAR(double(b[0]), double(x[0]), kTol);
  EXPECT_NEAR(0.0, double(x[1]), kTol);
  EXPECT_NEAR(0.0, double(x[2]), kTol);
}

// Verifies: REQ-LINALG-001
TEST(FswMinNorm, MatchesIndependentSolverAndIsMinimumNorm)
{
  kt::Rng r(201);
  const int sizes[] = {3, 4, 6, 8, 12, FSW_MAX_EFF};
  for (int n : sizes) {
    for (int m = 1; m <= 3; m++) {
      for (int k = 0; k < 20; k++) {
        Mat3N A = random_well_conditioned(r, m, n);
        fsw_real b[3] = {0, 0, 0}, x[FSW_MAX_EFF];
        double bd[3] = {0, 0, 0}, xr[FSW_MAX_EFF];
        for (int i = 0; i < m; i++) bd[i] = b[i] = static_cast<fsw_real>(r.uniform(-1, 1));
        ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, m, n)) << "n=" << n << " m=" << m;
        ref_minnorm(xr, A, bd, m, n);
        const double xn = fsw_vn_norm(x, n) + 1e-300;
        for (int j = 0; j < n; j++) EXPECT_NEAR(xr[j], x[j], kTol * 100 * xn);
        // A x = b
        for (int i = 0; i < m; i++) EXPECT_NEAR(b[i], fsw_vn_dot(A.a[i], x, n), kTol * 100 * (1 + xn));
        // minimum norm: adding any null-space vector z (A z = 0) increases |x|.
        // Build z by projecting a random vector with the K2 projector.
        if (n > m) {
          static fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF];
          ASSERT_EQ(FSW_OK, fsw_null_projector(tau, A.a, n, nullptr, nullptr));
          fsw_real v[FSW_MAX_EFF], z[FSW_MAX_EFF], xz[FSW_MAX_EFF];
          for (int j = 0; j < n; j++) v[j] = static_cast<fsw_real>(r.uniform(-1, 1));
          for (int j = 0; j < n; j++) z[j] = fsw_vn_dot(tau[j], v, n);
          EXPECT_NEAR(0.0, fsw_vn_dot(x, z, n) / (xn * (fsw_vn_norm(z, n) + 1e-30)), kTol * 100);
          fsw_vn_add(xz, x, z, n);
          EXPECT_GE(fsw_vn_norm(xz, n), fsw_vn_norm(x, n) * (1 - kTol));
        }
      }
    }
  }
}

// Verifies: REQ-LINALG-002
TEST(FswMinNorm, RankDecisionIsScaleInvariant)
{
  // A small spacecraft (lever arms in mm) and a large one (km) with the same
  // shape get the same decision, and x scales as 1/c.  An absolute
  // determinant threshold (Basilisk) would call the small one singular.
  kt::Rng r(202);
  const double scales[] = {1e-9, 1e-3, 1.0, 1e3, 1e9};
  for (int k = 0; k < 50; k++) {
    const int n = 4 + k % 8;
    Mat3N A = random_well_conditioned(r, 3, n);
    if (k % 5 == 0) {  // every fifth geometry: exactly coplanar columns
      for (int j = 0; j < n; j++) A.a[2][j] = A.a[0][j] + A.a[1][j];
    }
    fsw_real b[3] = {FSW_R(0.3), FSW_R(-0.2), FSW_R(0.1)}, x1[FSW_MAX_EFF];
    const FswStatus s1 = fsw_minnorm_solve(x1, A.a, b, 3, n);
    EXPECT_EQ(k % 5 == 0 ? FSW_E_SINGULAR : FSW_OK, s1);
    for (double c : scales) {
      Mat3N Ac = A;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < n; j++) Ac.a[i][j] = static_cast<fsw_real>(c * A.a[i][j]);
      fsw_real xc[FSW_MAX_EFF];
      EXPECT_EQ(s1, fsw_minnorm_solve(xc, Ac.a, b, 3, n)) << "scale " << c;
      if (s1 == FSW_OK)
        for (int j = 0; j < n; j++) EXPECT_NEAR(x1[j], c * xc[j], kTol * 100 * (1 + std::fabs(x1[j])));
    }
  }
}

// Verifies: REQ-LINALG-002
TEST(FswMinNorm, RankDeficientGivesZeroAndStatus)
{
  Mat3N A;
  fsw_real x[FSW_MAX_EFF], b[3] = {1, 2, 3};
  // coplanar wheel axes: all columns in the x-y plane
  std::memset(&A, 0, sizeof A);
  for (int j = 0; j < 5; j++) {
    A.a[0][j] = static_cast<fsw_real>(std::cos(0.3 * j));
    A.a[1][j] = static_cast<fsw_real>(std::sin(0.3 * j));
  }
  for (int j = 0; j < FSW_MAX_EFF; j++) x[j] = 99;
  EXPECT_EQ(FSW_E_SINGULAR, fsw_minnorm_solve(x, A.a, b, 3, 5));
  for (int j = 0; j < 5; j++) EXPECT_EQ(0, x[j]);
  // fewer columns than rows
  EXPECT_EQ(FSW_E_SINGULAR, fsw_minnorm_solve(x, A.a, b, 3, 2));
  // all zero
  std::memset(&A, 0, sizeof A);
  EXPECT_EQ(FSW_E_SINGULAR, fsw_minnorm_solve(x, A.a, b, 2, 4));
  // n = 0 with m >= 1
  EXPECT_EQ(FSW_E_SINGULAR, fsw_minnorm_solve(x, A.a, b, 1, 0));
  // nearly dependent rows: threshold behaviour.  Row 2 = row 1 + d * e.
  // The second Cholesky pivot is about d^2 |e_perp|^2 relative to |row1|^2.
  kt::Rng r(203);
  Mat3N B = random_matrix(r, 2, 6);
  Mat3N Bd = B, Bc = B;
  const double d_dep = kt::tol(1e-8, 1e-4), d_ok = kt::tol(1e-4, 1e-1);
  for (int j = 0; j < 6; j++) {
    const double e = r.uniform(-1, 1);
    Bd.a[1][j] = static_cast<fsw_real>(B.a[0][j] + d_dep * e);
    Bc.a[1][j] = static_cast<fsw_real>(B.a[0][j] + d_ok * e);
  }
  EXPECT_EQ(FSW_E_SINGULAR, fsw_minnorm_solve(x, Bd.a, b, 2, 6));
  EXPECT_EQ(FSW_OK, fsw_minnorm_solve(x, Bc.a, b, 2, 6));
}

// Verifies: REQ-LINALG-004
TEST(FswMinNorm, NonFiniteAndCapacity)
{
  kt::Rng r(204);
  Mat3N A = random_matrix(r, 3, 6);
  fsw_real x[FSW_MAX_EFF], b[3] = {1, 2, 3};
  Mat3N An = A;
  An.a[1][4] = kNaN;
  for (int j = 0; j < FSW_MAX_EFF; j++) x[j] = 7;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_minnorm_solve(x, An.a, b, 3, 6));
  for (int j = 0; j < 6; j++) EXPECT_EQ(0, x[j]);
  // a NaN beyond the used block is not read
  EXPECT_EQ(FSW_OK, fsw_minnorm_solve(x, An.a, b, 1, 6));
  fsw_real bi[3] = {1, std::numeric_limits<fsw_real>::infinity(), 0};
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_minnorm_solve(x, A.a, bi, 3, 6));
  EXPECT_EQ(FSW_E_CAPACITY, fsw_minnorm_solve(x, A.a, b, 0, 6));
  EXPECT_EQ(FSW_E_CAPACITY, fsw_minnorm_solve(x, A.a, b, 4, 6));
  EXPECT_EQ(FSW_E_CAPACITY, fsw_minnorm_solve(x, A.a, b, 3, -1));
  EXPECT_EQ(FSW_E_CAPACITY, fsw_minnorm_solve(x, A.a, b, 3, FSW_MAX_EFF + 1));
  for (int j = 0; j < FSW_MAX_EFF; j++) EXPECT_EQ(0, x[j]);  // clamped safe output
  kestrel_assert_reset();
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_solve(nullptr, A.a, b, 3, 6));
  EXPECT_EQ(1ul, kestrel_assert_count());
  kestrel_assert_reset();
}

// Verifies: REQ-LINALG-004
TEST(FswMinNorm, HugeAndTinyEntriesDoNotOverflow)
{
  // Power-of-two pre-scaling keeps A A^T finite near the real's range ends.
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  const fsw_real big = std::numeric_limits<fsw_real>::max() / 8;
  A.a[0][0] = big;
  A.a[0][1] = big;
  fsw_real x[FSW_MAX_EFF], b[3] = {big, 0, 0};
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, 1, 2));
  EXPECT_NEAR(0.5, x[0], kTol);
  EXPECT_NEAR(0.5, x[1], kTol);
}

// Verifies: REQ-LINALG-007
TEST(FswMinNorm, Repeatable)
{
  kt::Rng r(205);
  Mat3N A = random_matrix(r, 3, 9);
  fsw_real b[3] = {1, -1, FSW_R(0.5)}, x1[FSW_MAX_EFF], x2[FSW_MAX_EFF];
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x1, A.a, b, 3, 9));
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x2, A.a, b, 3, 9));
  EXPECT_EQ(0, std::memcmp(x1, x2, 9 * sizeof(fsw_real)));
}

// Verifies: REQ-LINALG-001, REQ-LINALG-007
TEST(FswMinNormFactor, FactorThenSolveIsTheOneCallSolveBitForBit)
{
  // fsw_minnorm_solve is factor + solve_factored; this checks the split
  // against the one-call solve over shapes and every status the solve
  // returns: well and badly conditioned, rank deficient, zero, non-finite
  // A or b, subnormal A, out of range m and n, and several b per factor.
  kt::Rng r(206);
  const fsw_real inf = std::numeric_limits<fsw_real>::infinity();
  int seen[8] = {0};
  for (int trial = 0; trial < 3000; trial++) {
    const int m = 1 + trial % 3, n = (trial / 3) % 10;
    Mat3N A = random_matrix(r, 3, FSW_MAX_EFF);
    switch (trial % 11) {
      case 1: for (int k = 0; k < n; k++) A.a[m - 1][k] = A.a[0][k]; break;  // dependent rows
      case 2: std::memset(&A, 0, sizeof A); break;
      case 3: A.a[0][n > 0 ? n - 1 : 0] = kNaN; break;
      case 4: for (int i = 0; i < 3; i++) for (int k = 0; k < FSW_MAX_EFF; k++) A.a[i][k] *= std::numeric_limits<fsw_real>::denorm_min(); break;
      case 5: A.a[0][0] = inf; break;
      case 6: for (int k = 0; k < n; k++) A.a[m - 1][k] = A.a[0][k] * (1 + 8 * std::numeric_limits<fsw_real>::epsilon()); break;
      default: break;
    }
    const int mm = (trial % 97 == 0) ? 4 : m, nn = (trial % 89 == 0) ? FSW_MAX_EFF + 1 : n;
    FswMinnormFactor f;
    const FswStatus fs = fsw_minnorm_factor(&f, A.a, mm, nn);
    for (int q = 0; q < 3; q++) {
      fsw_real b[3] = {static_cast<fsw_real>(r.uniform(-1, 1)), static_cast<fsw_real>(r.uniform(-1e3, 1e3)),
                       static_cast<fsw_real>(r.uniform(-1e-3, 1e-3))};
      if (trial % 13 == 0 && q == 1) b[m - 1] = kNaN;
      if (trial % 17 == 0 && q == 2) b[0] = std::numeric_limits<fsw_real>::max();
      fsw_real x1[FSW_MAX_EFF], x2[FSW_MAX_EFF];
      for (int k = 0; k < FSW_MAX_EFF; k++) x1[k] = x2[k] = 7;
      const FswStatus s1 = fsw_minnorm_solve(x1, A.a, b, mm, nn);
      const FswStatus s2 = fsw_minnorm_solve_factored(x2, &f, A.a, b);
      ASSERT_EQ(s1, s2) << "trial " << trial;
      ASSERT_EQ(0, std::memcmp(x1, x2, sizeof x1)) << "trial " << trial;
      // a factor that is not OK is the answer for every finite b (an OK
      // factor can still end SINGULAR by the delivered-residual test)
      if (fs != FSW_OK && std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2])) EXPECT_EQ(fs, s1);
      seen[s1 == FSW_OK ? 0 : s1 == FSW_E_SINGULAR ? 1 : s1 == FSW_E_BAD_INPUT ? 2 : s1 == FSW_E_CAPACITY ? 3 : 4]++;
    }
  }
  EXPECT_GT(seen[0], 100);
  EXPECT_GT(seen[1], 100);
  EXPECT_GT(seen[2], 100);
  EXPECT_GT(seen[3], 10);
  EXPECT_EQ(0, seen[4]);
}

// Verifies: REQ-LINALG-001, REQ-GEN-007
TEST(FswMinNormFactor, ClosedFormAndNullArguments)
{
  // A = [2 0; 0 4] (m = n = 2): s = 2^-e with 2^(e-1) <= 4 < 2^e, so
  // 1/8 (the largest entry to 1/2); (sA)(sA)^T = diag(1/16, 1/4),
  // L = diag(1/4, 1/2); x = A^-1 b.
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  A.a[0][0] = 2;
  A.a[1][1] = 4;
  FswMinnormFactor f;
  ASSERT_EQ(FSW_OK, fsw_minnorm_factor(&f, A.a, 2, 2));
  EXPECT_EQ(FSW_R(0.125), f.s);
  EXPECT_EQ(FSW_R(0.25), f.L[0][0]);
  EXPECT_EQ(FSW_R(0.5), f.L[1][1]);
  EXPECT_EQ(FSW_R(0.0), f.L[1][0]);
  fsw_real b[3] = {1, 1, 0}, x[FSW_MAX_EFF];
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve_factored(x, &f, A.a, b));
  EXPECT_EQ(FSW_R(0.5), x[0]);
  EXPECT_EQ(FSW_R(0.25), x[1]);
  kestrel_assert_reset();
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_factor(nullptr, A.a, 2, 2));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_factor(&f, nullptr, 2, 2));
  EXPECT_EQ(FSW_E_NULL_ARG, f.status);
  for (int k = 0; k < FSW_MAX_EFF; k++) x[k] = 7;
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_solve_factored(x, &f, A.a, b));  // a factor of nothing
  for (int k = 0; k < 2; k++) EXPECT_EQ(0, x[k]);
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_solve_factored(nullptr, &f, A.a, b));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_solve_factored(x, nullptr, A.a, b));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_solve_factored(x, &f, nullptr, b));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_solve_factored(x, &f, A.a, nullptr));
  EXPECT_EQ(6ul, kestrel_assert_count());
  kestrel_assert_reset();
}

/* ---- K2 ---- */

fsw_real g_tau[FSW_MAX_EFF][FSW_MAX_EFF];
fsw_real g_tau2[FSW_MAX_EFF][FSW_MAX_EFF];

void expect_projector(const fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF], const Mat3N& G, int n, int rank,
                      double tol)
{
  // symmetric, idempotent, [G][tau] = 0, trace = n - rank
  double tr = 0;
  for (int i = 0; i < n; i++) {
    tr += tau[i][i];
    for (int j = 0; j < n; j++) {
      EXPECT_EQ(tau[i][j], tau[j][i]);
      double tt = 0;
      for (int k = 0; k < n; k++) tt += static_cast<double>(tau[i][k]) * tau[k][j];
      EXPECT_NEAR(tau[i][j], tt, tol);
    }
  }
  EXPECT_NEAR(n - rank, tr, tol * n);
  double gmax = 0;
  for (int r = 0; r < 3; r++) gmax = std::fmax(gmax, fsw_vn_max_abs(G.a[r], n));
  for (int r = 0; r < 3; r++)
    for (int j = 0; j < n; j++) {
      double s = 0;
      for (int k = 0; k < n; k++) s += static_cast<double>(G.a[r][k]) * tau[k][j];
      EXPECT_NEAR(0.0, s, tol * (1 + gmax) * n);
    }
}

// Verifies: REQ-LINALG-005
TEST(FswNullProjector, FullRankEqualsClosedForm)
{
  // [tau] = I - G^T (G G^T)^-1 G; column j of G^T (G G^T)^-1 G is the
  // minimum-norm solution of G x = G e_j, so the reference uses ref_minnorm.
  kt::Rng r(301);
  const int sizes[] = {4, 5, 6, 12, FSW_MAX_EFF};
  for (int n : sizes) {
    Mat3N G = random_matrix(r, 3, n);
    int rank = -1;
    ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau, G.a, n, nullptr, &rank));
    EXPECT_EQ(3, rank);
    for (int j = 0; j < n; j++) {
      double b[3], col[FSW_MAX_EFF];
      for (int i = 0; i < 3; i++) b[i] = G.a[i][j];
      ref_minnorm(col, G, b, 3, n);
      for (int i = 0; i < n; i++) EXPECT_NEAR((i == j ? 1.0 : 0.0) - col[i], g_tau[i][j], kTol * 100);
    }
    expect_projector(g_tau, G, n, 3, kTol * 100);
  }
}

// Verifies: REQ-LINALG-005
TEST(FswNullProjector, ThreeIndependentWheelsHaveNoNullSpace)
{
  kt::Rng r(302);
  Mat3N G = random_well_conditioned(r, 3, 3);
  int rank = 0;
  ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau, G.a, 3, nullptr, &rank));
  EXPECT_EQ(3, rank);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_NEAR(0.0, g_tau[i][j], kTol * 10);
}

// Verifies: REQ-LINALG-005
TEST(FswNullProjector, RankDeficientSetsStillGiveTrueProjector)
{
  kt::Rng r(303);
  for (int k = 0; k < 30; k++) {
    const int n = 3 + k % 10;
    Mat3N G = random_matrix(r, 3, n);
    int want_rank = 3;
    if (k % 3 == 0) {  // coplanar: rank 2
      for (int j = 0; j < n; j++) G.a[2][j] = FSW_R(0.5) * G.a[0][j] - FSW_R(2.0) * G.a[1][j];
      want_rank = 2;
    } else if (k % 3 == 1) {  // collinear: rank 1
      for (int j = 0; j < n; j++) {
        G.a[1][j] = FSW_R(3.0) * G.a[0][j];
        G.a[2][j] = FSW_R(-1.0) * G.a[0][j];
      }
      want_rank = 1;
    }
    int rank = -1;
    ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau, G.a, n, nullptr, &rank));
    EXPECT_EQ(want_rank, rank);
    expect_projector(g_tau, G, n, want_rank, kTol * 100);
  }
  // all-zero geometry: nothing to avoid, tau = I, rank 0
  Mat3N Z;
  std::memset(&Z, 0, sizeof Z);
  int rank = -1;
  ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau, Z.a, 4, nullptr, &rank));
  EXPECT_EQ(0, rank);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) EXPECT_EQ(i == j ? 1 : 0, g_tau[i][j]);
}

// Verifies: REQ-LINALG-005
TEST(FswNullProjector, AvailabilityMaskRemovesWheels)
{
  kt::Rng r(304);
  const int n = 6;
  Mat3N G = random_matrix(r, 3, n);
  uint8_t avail[FSW_MAX_EFF] = {0};
  avail[1] = FSW_UNAVAILABLE;
  avail[4] = FSW_UNAVAILABLE;
  ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau, G.a, n, avail, nullptr));
  // reference: projector of the 4 remaining columns, embedded
  Mat3N Gr;
  std::memset(&Gr, 0, sizeof Gr);
  const int keep[] = {0, 2, 3, 5};
  for (int i = 0; i < 3; i++)
    for (int c = 0; c < 4; c++) Gr.a[i][c] = G.a[i][keep[c]];
  ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau2, Gr.a, 4, nullptr, nullptr));
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      if (avail[i] || avail[j]) {
        EXPECT_EQ(0, g_tau[i][j]);
      }
    }
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 4; b++) EXPECT_NEAR(g_tau2[a][b], g_tau[keep[a]][keep[b]], kTol * 10);
  // body torque of any null command is zero with the full G too
  expect_projector(g_tau, G, n, 3 + 2 /* masked rows count as removed */, kTol * 100);
}

// Verifies: REQ-LINALG-005
TEST(FswNullProjector, ScaleInvariantAndNonFinite)
{
  kt::Rng r(305);
  Mat3N G = random_matrix(r, 3, 7);
  ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau, G.a, 7, nullptr, nullptr));
  Mat3N Gs = G;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 7; j++) Gs.a[i][j] = G.a[i][j] * FSW_R(1e-7);
  ASSERT_EQ(FSW_OK, fsw_null_projector(g_tau2, Gs.a, 7, nullptr, nullptr));
  for (int i = 0; i < 7; i++)
    for (int j = 0; j < 7; j++) EXPECT_NEAR(g_tau[i][j], g_tau2[i][j], kTol * 10);

  G.a[2][3] = kNaN;
  int rank = 9;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_null_projector(g_tau, G.a, 7, nullptr, &rank));
  EXPECT_EQ(0, rank);
  for (int i = 0; i < 7; i++)
    for (int j = 0; j < 7; j++) EXPECT_EQ(0, g_tau[i][j]);
  EXPECT_EQ(FSW_E_CAPACITY, fsw_null_projector(g_tau, G.a, FSW_MAX_EFF + 1, nullptr, nullptr));
  EXPECT_EQ(FSW_E_CAPACITY, fsw_null_projector(g_tau, G.a, -2, nullptr, nullptr));
}

}  // namespace

// ---- K4 fsw_bounded_minnorm_solve ------------------------------------------

namespace {

struct Box {
  fsw_real lo[FSW_MAX_EFF];
  fsw_real hi[FSW_MAX_EFF];
};

Box box(int n, double lo, double hi)
{
  Box B;
  std::memset(&B, 0, sizeof B);
  for (int i = 0; i < n; i++) {
    B.lo[i] = static_cast<fsw_real>(lo);
    B.hi[i] = static_cast<fsw_real>(hi);
  }
  return B;
}

// (arrays by reference, not std::initializer_list by value: the latter
// draws an ABI note from GCC on 32-bit Arm)
template <size_t N>
Mat3N mat(int m, int n, const double (&rows)[N])
{
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  size_t k = 0;
  for (int i = 0; i < m; i++)
    for (int j = 0; j < n && k < N; j++) A.a[i][j] = static_cast<fsw_real>(rows[k++]);
  return A;
}

struct K4Run {
  FswStatus s;
  int iter;
  fsw_real x[FSW_MAX_EFF];
};

template <size_t N>
K4Run k4(const Mat3N& A, const double (&bl)[N], int m, int n, const Box& B)
{
  static_assert(N <= 3, "b has at most 3 entries");
  K4Run r;
  fsw_real b[3] = {0, 0, 0};
  for (size_t i = 0; i < N; i++) b[i] = static_cast<fsw_real>(bl[i]);
  for (int j = 0; j < FSW_MAX_EFF; j++) r.x[j] = 99;
  r.iter = -1;
  r.s = fsw_bounded_minnorm_solve(r.x, A.a, b, m, n, B.lo, B.hi, &r.iter);
  return r;
}

template <size_t N>
void expect_x(const K4Run& r, const double (&want)[N], const char* why)
{
  for (size_t j = 0; j < N; j++) EXPECT_NEAR(want[j], double(r.x[j]), kTol) << why << ", entry " << j;
}

}  // namespace

// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, InteriorSolutionIsTheNormalEquationSolution)
{
  // A = [1 0 1; 0 1 1], b = (2, 2): (A A^T)^-1 b = (2/3, 2/3), x = A^T y =
  // (2/3, 2/3, 4/3), inside [0, 10]^3, so the bounds change nothing.
  const Mat3N A = mat(2, 3, {1, 0, 1, 0, 1, 1});
  const K4Run r = k4(A, {2, 2}, 2, 3, box(3, 0, 10));
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {2.0 / 3, 2.0 / 3, 4.0 / 3}, "interior");
  EXPECT_GE(r.iter, 1);
  EXPECT_LE(r.iter, 3 * 3);
  // ... and equal to K1 (the normal equations) on the same problem
  fsw_real x1[FSW_MAX_EFF], b[3] = {2, 2, 0};
  ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x1, A.a, b, 2, 3));
  for (int j = 0; j < 3; j++) EXPECT_NEAR(double(x1[j]), double(r.x[j]), kTol);
  // square and diagonal: x = b ./ diag
  const K4Run d = k4(mat(2, 2, {2, 0, 0, 4}), {2, 2}, 2, 2, box(2, 0, 10));
  EXPECT_EQ(FSW_OK, d.s);
  expect_x(d, {1.0, 0.5}, "diagonal");
  // an off-pulsing box [-F, 0]: x1 + x2 = -1 -> (-1/2, -1/2)
  const K4Run neg = k4(mat(1, 2, {1, 1}), {-1}, 1, 2, box(2, -1, 0));
  EXPECT_EQ(FSW_OK, neg.s);
  expect_x(neg, {-0.5, -0.5}, "negative box");
}

// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, ActiveBounds)
{
  // x1 + x2 = 3 with x1 <= 1: the unconstrained (3/2, 3/2) is cut to (1, 2),
  // the smallest-norm point of the line inside the box.
  Box B = box(2, 0, 10);
  B.hi[0] = 1;
  const K4Run up = k4(mat(1, 2, {1, 1}), {3}, 1, 2, B);
  EXPECT_EQ(FSW_OK, up.s);
  expect_x(up, {1.0, 2.0}, "upper bound active");
  // x1 - x2 = 1 with x >= 0: unconstrained (1/2, -1/2) -> (1, 0)
  const K4Run lo = k4(mat(1, 2, {1, -1}), {1}, 1, 2, box(2, 0, 10));
  EXPECT_EQ(FSW_OK, lo.s);
  expect_x(lo, {1.0, 0.0}, "lower bound active");
  // out of reach: x1 + x2 = 5 with x <= 1: least squares, both at the top
  const K4Run far = k4(mat(1, 2, {1, 1}), {5}, 1, 2, box(2, 0, 1));
  EXPECT_EQ(FSW_OK, far.s);
  expect_x(far, {1.0, 1.0}, "out of reach");
  // a column fixed at zero (lo = hi = 0, a removed thruster) is never used
  Box Z = box(3, 0, 10);
  Z.hi[1] = 0;
  const K4Run z = k4(mat(1, 3, {1, 1, 1}), {2}, 1, 3, Z);
  EXPECT_EQ(FSW_OK, z.s);
  expect_x(z, {1.0, 0.0, 1.0}, "fixed column");
}

// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, RankDeficient)
{
  // rows (1 1) and (2 2): rank 1.  Consistent b = (1, 2): x1 + x2 = 1 ->
  // (1/2, 1/2).  Inconsistent b = (1, 0): least squares in s = x1 + x2,
  // (s - 1)^2 + (2 s)^2 minimal at s = 1/5 -> (1/10, 1/10).
  const Mat3N A = mat(2, 2, {1, 1, 2, 2});
  const K4Run c = k4(A, {1, 2}, 2, 2, box(2, 0, 10));
  EXPECT_EQ(FSW_OK, c.s);
  expect_x(c, {0.5, 0.5}, "consistent");
  const K4Run i = k4(A, {1, 0}, 2, 2, box(2, 0, 10));
  EXPECT_EQ(FSW_OK, i.s);
  expect_x(i, {0.1, 0.1}, "inconsistent");
  // duplicated columns in a 2 x 3 system: x1 + x2 = 2, x3 = 1 -> (1, 1, 1)
  const K4Run d = k4(mat(2, 3, {1, 1, 0, 0, 0, 1}), {2, 1}, 2, 3, box(3, 0, 10));
  EXPECT_EQ(FSW_OK, d.s);
  expect_x(d, {1.0, 1.0, 1.0}, "duplicated columns");
  // all-zero A: nothing to do, x = 0
  const K4Run zero = k4(mat(3, 4, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), {1, 2, 3}, 3, 4,
                        box(4, 0, 1));
  EXPECT_EQ(FSW_OK, zero.s);
  expect_x(zero, {0, 0, 0, 0}, "zero matrix");
}

// Verifies: REQ-LINALG-004
TEST(FswBoundedMinNorm, BadInput)
{
  const Mat3N A = mat(1, 2, {1, 1});
  const fsw_real inf = std::numeric_limits<fsw_real>::infinity();
  struct Row {
    const char* why;
    void (*spoil)(Mat3N&, Box&);
    int m, n;
    FswStatus want;
  };
  const Row rows[] = {
      {"NaN in A", [](Mat3N& a, Box&) { a.a[0][1] = kNaN; }, 1, 2, FSW_E_BAD_INPUT},
      {"NaN lower bound", [](Mat3N&, Box& b) { b.lo[0] = kNaN; }, 1, 2, FSW_E_BAD_INPUT},
      {"lo > hi", [](Mat3N&, Box& b) { b.lo[1] = 0; b.hi[1] = -1; }, 1, 2, FSW_E_BAD_INPUT},
      {"Inf upper bound (issue 21)", [](Mat3N&, Box& b) { b.hi[0] = std::numeric_limits<fsw_real>::infinity(); }, 1, 2,
       FSW_E_BAD_INPUT},
      {"0 not a bound", [](Mat3N&, Box& b) { b.lo[0] = -1; }, 1, 2, FSW_E_BAD_INPUT},
      {"m = 0", [](Mat3N&, Box&) {}, 0, 2, FSW_E_CAPACITY},
      {"m = 4", [](Mat3N&, Box&) {}, 4, 2, FSW_E_CAPACITY},
      {"n < 0", [](Mat3N&, Box&) {}, 1, -1, FSW_E_CAPACITY},
      {"n > FSW_MAX_EFF", [](Mat3N&, Box&) {}, 1, FSW_MAX_EFF + 1, FSW_E_CAPACITY},
  };
  for (const Row& r : rows) {
    Mat3N a = A;
    Box b = box(2, 0, 1);
    r.spoil(a, b);
    const K4Run run = k4(a, {1}, r.m, r.n, b);
    EXPECT_EQ(r.want, run.s) << r.why;
    EXPECT_EQ(0, run.iter) << r.why;
    const int nz = r.n < 0 ? 0 : (r.n > FSW_MAX_EFF ? FSW_MAX_EFF : r.n);
    for (int j = 0; j < nz; j++) EXPECT_EQ(0, run.x[j]) << r.why << " entry " << j;
  }
  // infinite right-hand side
  {
    fsw_real x[FSW_MAX_EFF], b[3] = {inf, 0, 0};
    const Box B = box(2, 0, 1);
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_bounded_minnorm_solve(x, A.a, b, 1, 2, B.lo, B.hi, nullptr));
  }
  // NULL pointers (iterations may be NULL)
  kestrel_assert_reset();
  {
    fsw_real x[FSW_MAX_EFF], b[3] = {1, 0, 0};
    const Box B = box(2, 0, 1);
    EXPECT_EQ(FSW_OK, fsw_bounded_minnorm_solve(x, A.a, b, 1, 2, B.lo, B.hi, nullptr));
    EXPECT_EQ(0ul, kestrel_assert_count());
    EXPECT_EQ(FSW_E_NULL_ARG, fsw_bounded_minnorm_solve(x, A.a, b, 1, 2, nullptr, B.hi, nullptr));
    EXPECT_EQ(1ul, kestrel_assert_count());
  }
  kestrel_assert_reset();
}

// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, RandomBoxesAgreeWithK1WhenInteriorAndStayInTheBox)
{
  kt::Rng r(404);
  int interior = 0;
  for (int trial = 0; trial < 400; trial++) {
    const int m = 1 + trial % 3, n = m + 1 + r.uniform_int(0, 6);
    const Mat3N A = random_well_conditioned(r, m, n);
    fsw_real b[3] = {0, 0, 0};
    for (int i = 0; i < m; i++) b[i] = static_cast<fsw_real>(r.uniform(-1, 1));
    const Box B = box(n, 0, r.uniform(0.1, 3));
    fsw_real x[FSW_MAX_EFF], x1[FSW_MAX_EFF];
    int it = -1;
    ASSERT_EQ(FSW_OK, fsw_bounded_minnorm_solve(x, A.a, b, m, n, B.lo, B.hi, &it));
    ASSERT_LE(it, 3 * n);
    for (int j = 0; j < n; j++) {
      ASSERT_GE(x[j], B.lo[j]);
      ASSERT_LE(x[j], B.hi[j]);
    }
    ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x1, A.a, b, m, n));
    bool inside = true;
    for (int j = 0; j < n; j++) inside = inside && x1[j] > B.lo[j] + 1e-3 && x1[j] < B.hi[j] - 1e-3;
    if (!inside) continue;
    ++interior;
    for (int j = 0; j < n; j++) EXPECT_NEAR(double(x1[j]), double(x[j]), kt::tol(1e-11, 1e-4)) << trial;
  }
  EXPECT_GT(interior, 10);  // the property was exercised
}

// ---- issue 13: K1 rank by delivered residual; overflow is bad input -------

// Nearly dependent rows (row 3 = mix of rows 1, 2 plus 1e-8..1e-3 noise,
// 1e-4..1e-1 in float) at
// scales 1e-3..1e3: OK always means |A x - b| <= FSW_RESID_TOL |b| (checked
// in double); otherwise FSW_E_SINGULAR with x = 0.  Before the fix a pivot
// of rounding noise just above the floor returned OK with a residual of
// the order of |b|.
// Verifies: REQ-LINALG-003
TEST(FswMinNorm, Issue13OkAlwaysDeliversTheRequest)
{
  kt::Rng r(1313);
  int ok = 0, singular = 0;
  for (int trial = 0; trial < 5000; trial++) {
    const int n = r.uniform_int(3, 8);
    const double scale = std::pow(10.0, r.uniform(-3, 3));
    Mat3N A = random_matrix(r, 3, n, scale);
    const double c0 = r.uniform(-1, 1), c1 = r.uniform(-1, 1);
    // float: the pivot floor (1e-5) needs a larger tilt for OK cases
    const double noise = kt::kFloat ? std::pow(10.0, r.uniform(-4, -1)) : std::pow(10.0, r.uniform(-8, -3));
    for (int j = 0; j < n; j++)
      A.a[2][j] = static_cast<fsw_real>(c0 * A.a[0][j] + c1 * A.a[1][j] +
                                        noise * scale * r.uniform(-1, 1));
    fsw_real b[3], x[FSW_MAX_EFF];
    for (int i = 0; i < 3; i++) b[i] = static_cast<fsw_real>(r.uniform(-1, 1));
    const FswStatus s = fsw_minnorm_solve(x, A.a, b, 3, n);
    if (s == FSW_OK) {
      ok++;
      double rn = 0, bn = 0;
      for (int i = 0; i < 3; i++) {
        double v = b[i];
        for (int j = 0; j < n; j++) v -= static_cast<double>(A.a[i][j]) * x[j];
        rn += v * v;
        bn += static_cast<double>(b[i]) * b[i];
      }
      ASSERT_LE(std::sqrt(rn), 2.0 * FSW_RESID_TOL * std::sqrt(bn)) << "trial " << trial;
    } else {
      ASSERT_EQ(FSW_E_SINGULAR, s) << "trial " << trial;
      singular++;
      for (int j = 0; j < n; j++) ASSERT_EQ(0, x[j]);
    }
  }
  EXPECT_GT(ok, 0);
  EXPECT_GT(singular, 0);
}

// A finite b whose solution is beyond the real's range: FSW_E_BAD_INPUT,
// x = 0 (was inf under OK).  A huge b with a representable solution is
// fine (b is pre-scaled by a power of two).
// Verifies: REQ-LINALG-004
TEST(FswMinNorm, Issue13OverflowingSolutionIsBadInput)
{
  const double big = 0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  fsw_real x[FSW_MAX_EFF], b[3] = {static_cast<fsw_real>(big), 0, 0};
  A.a[0][0] = FSW_R(0.5);
  for (int j = 0; j < FSW_MAX_EFF; j++) x[j] = 99;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_minnorm_solve(x, A.a, b, 1, 1));
  EXPECT_EQ(0, x[0]);
  A.a[0][0] = FSW_R(4.0);
  EXPECT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, 1, 1));
  EXPECT_EQ(static_cast<fsw_real>(big) / FSW_R(4.0), x[0]);
  A.a[0][0] = std::numeric_limits<fsw_real>::denorm_min();  // subnormal A
  b[0] = 1;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_minnorm_solve(x, A.a, b, 1, 1));
  EXPECT_EQ(0, x[0]);
}

// Issue 21: phase 1's guard for an entering column that does not move into
// the box.  a1 = (1, 0), a2 = (1/2)(1, d), b = (1, 1), box [0, 10]^2.
// a1 has the larger gradient (1 against (1 + d)/2) and enters: x1 = 1,
// r = (0, 1).  Then a2's gradient a2.r = d/2 passes the entry test
// (> 1000 eps |b| |a2|: d >~ 3e-13 in double, 1.7e-4 in float), but the
// Schur pivot of the 2 x 2 normal matrix is |a2|^2 - (a1.a2)^2/|a1|^2 = d^2/4
// <= FSW_RANK_TOL (d = 1e-9: 2.5e-19 in double, rounded to 0; d = 1e-3:
// 2.5e-7 in float), so the pivot is dropped, z2 = 0 does not enter the box,
// and the entry is undone (phase 1 ends at x = (1, 0)).  Phase 2 then
// minimises |x| at the same A x with the same rank test, which sees a2 as
// a1 / 2: the minimum-norm point of x1 + x2 / 2 = 1 is (1, 1/2) / (1 + 1/4)
// = (0.8, 0.4).  Its residual |(0, 1 - 0.2 d)| = 1 - 0.2 d is within 0.8 d of
// the exact optimum (x = (0, 2), residual 1 - d), below FSW_RESID_TOL: a2 is
// numerically parallel to a1 at this rank tolerance.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21EnteringColumnDroppedByTheRankTestIsUndone)
{
  const double d = kt::tol(1e-9, 1e-3);
  const Mat3N A = mat(2, 2, {1.0, 0.5, 0.0, 0.5 * d});
  const K4Run r = k4(A, {1, 1}, 2, 2, box(2, 0, 10));
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {0.8, 0.4}, "entry undone, then least norm");
  EXPECT_LE(r.iter, 3 * 2);
  const double res = std::hypot(1.0 - (double(r.x[0]) + 0.5 * double(r.x[1])), 1.0 - 0.5 * d * double(r.x[1]));
  EXPECT_LE(res - (1.0 - d), double(FSW_RESID_TOL));
  EXPECT_GE(res - (1.0 - d), 0.0);  // nothing beats the optimum
  // mirrored into an off-pulsing box [-10, 0] with -b: the same numbers,
  // negated (the entry is undone from the upper bound)
  const K4Run rn = k4(A, {-1, -1}, 2, 2, box(2, -10, 0));
  EXPECT_EQ(FSW_OK, rn.s);
  expect_x(rn, {-0.8, -0.4}, "off-pulsing box");
  // the entering column first in the free set: a0 = e (0, 1) tiny
  // (e^2 <= FSW_RANK_TOL: e = 1e-7 in double, 1e-3 in float), a1 = (1, 0),
  // b = (1, 1), box [0, 2]^2.  a1 enters (gradient 1 > e): x1 = 1 < 2 stays
  // free, r = (0, 1); a0's gradient e passes the entry test (it scales with
  // |a0|), but its pivot e^2 <= FSW_RANK_TOL * 1 is dropped, z0 = 0: undone,
  // with a1 moved down in the free set.  x = (0, 1); the exact optimum
  // x = (2, 1) has residual 1 - 2 e, better by 2 e < FSW_RESID_TOL only.
  const double e = kt::tol(1e-7, 1e-3);
  const K4Run rt = k4(mat(2, 2, {0.0, 1.0, e, 0.0}), {1, 1}, 2, 2, box(2, 0, 2));
  EXPECT_EQ(FSW_OK, rt.s);
  expect_x(rt, {0.0, 1.0}, "tiny entering column first");
}

// Issue 21: two free variables that reach their bounds at the same step
// length (phase 1 fixes the blocking one and every other one at a bound).
// a1 = (1, 0), a2 = (-1/2, 1/2), b = (1, 2), box [0, 2]^2.  Gradients at 0:
// a1.b = 1 > a2.b = 1/2, so a1 enters alone: x1 = a1.b / |a1|^2 = 1, r = (0, 2);
// then a2.r = 1 > 0 enters and the free least squares is A^-1 b = (3, 4)
// (3 a1 + 4 a2 = (1, 2)).  Step lengths to the bounds: (2 - 1)/(3 - 1) = 1/2
// and (2 - 0)/(4 - 0) = 1/2, equal and exact in binary: both stop at 2.  At
// (2, 2) the gradient A^T (A x - b) = A^T (0, -1) = (0, -1/2) does not point
// into the box, so it is the bounded optimum; A is invertible, so phase 2
// keeps it.  The mirror problem (b -> -b, box [-2, 0]) ends at (-2, -2)
// through the lower bounds.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21TwoVariablesReachTheirBoundsTogether)
{
  const Mat3N A = mat(2, 2, {1.0, -0.5, 0.0, 0.5});
  const K4Run up = k4(A, {1, 2}, 2, 2, box(2, 0, 2));
  EXPECT_EQ(FSW_OK, up.s);
  expect_x(up, {2.0, 2.0}, "upper bounds together");
  const K4Run dn = k4(A, {-1, -2}, 2, 2, box(2, -2, 0));
  EXPECT_EQ(FSW_OK, dn.s);
  expect_x(dn, {-2.0, -2.0}, "lower bounds together");
}

// Issue 21: a free variable that reaches its bound in the same phase-1 step
// as the blocking one is set exactly onto the bound (fsw_linalg.h: F never
// leaves [lo, hi]); the step F + alpha (z - F) lands there only up to
// round-off.  A = [0 -1.5 0 1; 0.5 -1.5 0.5 1], b = (-1/3, 4/3), box [0, 1]^4
// (a geometry found by a search over small grids for such a tie; the step
// lengths are ratios of thirds, not exact in binary, and x3 would be left at
// -2^-55 in double).  Expected by hand: with u = x3 - 1.5 x1 and
// w = (x0 + x2) / 2, A x = (u, w + u).  The exact fit needs w = 5/3 > 1, so
// w = 1 (x0 = x2 = 1) and u minimises (u + 1/3)^2 + (u - 1/3)^2: u = 0; the
// gradient in w, 2 (w + u - 4/3) < 0, keeps w at its top.  The least norm of
// x1^2 + x3^2 with x3 = 1.5 x1 is x1 = x3 = 0: x = (1, 0, 1, 0).  Mirrored
// (-b, box [-1, 0]): x = (-1, 0, -1, 0), the tie at the upper bound 0.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21VariableReachingItsBoundInTheSameStepIsSetOntoIt)
{
  const Mat3N A = mat(2, 4, {0.0, -1.5, 0.0, 1.0, 0.5, -1.5, 0.5, 1.0});
  const double third = 1.0 / 3.0;
  const Box up = box(4, 0, 1);
  const K4Run r = k4(A, {-third, 4 * third}, 2, 4, up);
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {1.0, 0.0, 1.0, 0.0}, "tie at the lower bounds");
  for (int j = 0; j < 4; j++) {  // exactly inside the box, not by round-off
    EXPECT_GE(r.x[j], up.lo[j]) << j;
    EXPECT_LE(r.x[j], up.hi[j]) << j;
  }
  const Box dn = box(4, -1, 0);
  const K4Run rn = k4(A, {third, -4 * third}, 2, 4, dn);
  EXPECT_EQ(FSW_OK, rn.s);
  expect_x(rn, {-1.0, 0.0, -1.0, 0.0}, "tie at the upper bounds");
  for (int j = 0; j < 4; j++) {
    EXPECT_GE(rn.x[j], dn.lo[j]) << j;
    EXPECT_LE(rn.x[j], dn.hi[j]) << j;
  }
}

// Issue 21: phase 2's step F + alpha (z - F) of a free variable that is not
// the blocking one but reaches its bound too is clamped into [lo, hi]
// (round-off would leave x4 at -2^-56 below 0, or +2^-56 above 0 mirrored).
// A = [-0.5 1 1.5 1.5 1; -0.5 0 -1.5 -1.5 0; 0 -1 -1 0 1.5], b = (-1, -5/3, 0),
// box [0, 3]^5 (found by a search over small grids for such a tie).
// Expected by hand: x = (8/3, 0, 0, 2/9, 0) fits exactly (rows:
// -4/3 + 1/3 = -1, -4/3 - 1/3 = -5/3, 0) and is the least-norm point of the
// box: with lam = (-70/27, -74/27, l2), a0.lam = 8/3 = x0 and a3.lam = 2/9 =
// x3 (free), while a1.lam = -70/27 - l2, a2.lam = 2/9 - l2 and a4.lam =
// -70/27 + 1.5 l2 are all <= 0 (at the lower bound 0) for l2 in
// [2/9, 140/81]: the KKT conditions of min |x|^2 / 2 hold.  Mirrored (-b,
// box [-3, 0]): -x.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21PhaseTwoStepIsClampedIntoTheBox)
{
  const Mat3N A = mat(3, 5, {-0.5, 1.0, 1.5, 1.5, 1.0, -0.5, 0.0, -1.5, -1.5, 0.0, 0.0, -1.0, -1.0, 0.0, 1.5});
  const Box up = box(5, 0, 3);
  const K4Run r = k4(A, {-1.0, -5.0 / 3, 0.0}, 3, 5, up);
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {8.0 / 3, 0.0, 0.0, 2.0 / 9, 0.0}, "box [0, 3]");
  const Box dn = box(5, -3, 0);
  const K4Run rn = k4(A, {1.0, 5.0 / 3, 0.0}, 3, 5, dn);
  EXPECT_EQ(FSW_OK, rn.s);
  expect_x(rn, {-8.0 / 3, 0.0, 0.0, -2.0 / 9, 0.0}, "box [-3, 0]");
  for (int j = 0; j < 5; j++) {  // exactly inside the box, not by round-off
    EXPECT_GE(r.x[j], up.lo[j]) << j;
    EXPECT_LE(r.x[j], up.hi[j]) << j;
    EXPECT_GE(rn.x[j], dn.lo[j]) << j;
    EXPECT_LE(rn.x[j], dn.hi[j]) << j;
  }
}

// Issue 21: the variable that stops a phase-2 step is fixed on its bound
// exactly (a thruster held at its 0 bound is off, not at 1e-17 N); the step
// itself lands there only up to round-off.  A = [0.5 1 0.5; -1.5 0.5 1.5],
// b = (-1/3, -2/3), box [-1, 0]^3 (found by a search over small grids for a
// step that stops 2^-56 short of the bound).  By hand: A A^T = [1.5 0.5;
// 0.5 4.75], the unconstrained least-norm x = A^T (A A^T)^-1 b has x0 =
// 1/11 > 0, so x0 goes to its bound 0; then [1 0.5; 0.5 1.5] (x1, x2) = b
// gives x1 = -2/15, x2 = -2/5, inside the box; the multipliers lam = (0,
// -4/15) of that solve give a0.lam = 2/5 >= 0, so x0 rightly stays at its
// upper bound: x = (0, -2/15, -2/5).  Mirrored (-b, box [0, 1]): -x, x0 at
// its lower bound 0.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21PhaseTwoBlockingVariableIsExactlyOnItsBound)
{
  const Mat3N A = mat(2, 3, {0.5, 1.0, 0.5, -1.5, 0.5, 1.5});
  const K4Run r = k4(A, {-1.0 / 3, -2.0 / 3}, 2, 3, box(3, -1, 0));
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {0.0, -2.0 / 15, -2.0 / 5}, "box [-1, 0]");
  EXPECT_EQ(fsw_real(0), r.x[0]);  // on the bound, not near it
  const K4Run rn = k4(A, {1.0 / 3, 2.0 / 3}, 2, 3, box(3, 0, 1));
  EXPECT_EQ(FSW_OK, rn.s);
  expect_x(rn, {0.0, 2.0 / 15, 2.0 / 5}, "box [0, 1]");
  EXPECT_EQ(fsw_real(0), rn.x[0]);
}

// Issue 21: every required pointer of K1, K2 and K4 NULL in turn (null_args.h);
// K2's avail and rank and K4's iterations may be NULL by contract.
// Verifies: REQ-GEN-007
TEST(FswLinalgIssue21, EveryNullArgumentAssertsAndReturns)
{
  static Mat3N A;
  static fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF];
  fsw_real x[FSW_MAX_EFF], b[3] = {1, 0, 0};
  const Box B = box(2, 0, 1);
  A = mat(1, 2, {1, 1});
  kt::each_null("K1", [](fsw_real* xx, const Mat3N* a, const fsw_real* bb) {
    return fsw_minnorm_solve(xx, a != nullptr ? a->a : nullptr, bb, 1, 2);
  }, x, &A, b);
  kt::each_null("K2", [](fsw_real (*t)[FSW_MAX_EFF], const Mat3N* a) {
    return fsw_null_projector(t, a != nullptr ? a->a : nullptr, 2, nullptr, nullptr);
  }, tau, &A);
  kt::each_null("K4", [](fsw_real* xx, const Mat3N* a, const fsw_real* bb, const fsw_real* lo, const fsw_real* hi) {
    return fsw_bounded_minnorm_solve(xx, a != nullptr ? a->a : nullptr, bb, 1, 2, lo, hi, nullptr);
  }, x, &A, b, B.lo, B.hi);
}

// Issue 21: a right-hand side whose largest entry is subnormal.  K1 scales b
// by 2^-e to [1/2, 1); for the smallest subnormal 2^-e is not finite, so the
// scale is clamped to the largest finite power of two.  A = [1]: x = b
// exactly either way (the scaling is by powers of two and undone).
// Verifies: REQ-LINALG-004
TEST(FswMinNorm, Issue21SubnormalRightHandSide)
{
  static Mat3N A;
  A = mat(1, 1, {1.0});
  fsw_real x[FSW_MAX_EFF], b[3] = {std::numeric_limits<fsw_real>::denorm_min(), 0, 0};
  EXPECT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, 1, 1));
  EXPECT_EQ(b[0], x[0]);
}

// K1's digits do not depend on the scale of A: A is scaled by a power of two
// s (exact) and b by 2^-e, so A 2^k gives exactly x 2^-k.  Scales far from 1
// (2^600 and 2^-600 in double, 2^60 and 2^-60 in float) put the sum of
// squares of the scaled b out of the range where the residual test is first
// decided by plain sums of squares (it underflows or overflows), so the
// overflow-safe norms decide; the result is the same bits as at scale 1.
// Verifies: REQ-LINALG-001
TEST(FswMinNorm, ScaleOfAFarFromOneGivesTheScaledSolutionBitForBit)
{
  const int k = sizeof(fsw_real) == 4 ? 60 : 600;
  kt::Rng r(4501);
  for (int trial = 0; trial < 50; trial++) {
    const int m = 1 + trial % 3, n = m + trial % 4;
    static Mat3N A, As;
    A = random_well_conditioned(r, m, n);
    fsw_real b[3] = {0, 0, 0}, x[FSW_MAX_EFF], xs[FSW_MAX_EFF];
    for (int i = 0; i < m; i++) b[i] = static_cast<fsw_real>(r.uniform(-5, 5));
    ASSERT_EQ(FSW_OK, fsw_minnorm_solve(x, A.a, b, m, n)) << trial;
    for (const int sgn : {1, -1}) {
      As = A;
      for (int i = 0; i < m; i++)
        for (int j = 0; j < n; j++) As.a[i][j] = std::ldexp(A.a[i][j], sgn * k);
      ASSERT_EQ(FSW_OK, fsw_minnorm_solve(xs, As.a, b, m, n)) << trial << " " << sgn;
      for (int j = 0; j < n; j++) EXPECT_EQ(std::ldexp(x[j], -sgn * k), xs[j]) << trial << " " << sgn << " " << j;
    }
  }
}

// Issue 21 (mutation survivors of seed 2112): K2's row-drop test is relative
// to the row's own norm, |residual| <= FSW_NULL_TOL |row|.  16 columns,
// row 0 = (1, ..., 1), row 1 = row 0 + rho (1, -1, 1, -1, ...): the part of
// row 1 not in row 0 is rho (1, -1, ...), of norm 4 rho against |row 1| ~ 4,
// so the relative residual is rho.  rho = FSW_NULL_TOL / 2: dropped (rank 1);
// rho = 2 FSW_NULL_TOL: kept (rank 2).  (Both rows are scaled by 1/2 before
// the test, so a threshold that is not relative to |row| = 2 would move by
// a factor of 4 and swap the two answers.)
// Verifies: REQ-LINALG-005
TEST(FswNullProjector, Issue21RowDropIsRelativeToTheRowNorm)
{
  static Mat3N G;
  static fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF];
  for (const double f : {0.5, 2.0}) {
    const double rho = f * static_cast<double>(FSW_NULL_TOL);
    std::memset(&G, 0, sizeof G);
    for (int j = 0; j < 16; j++) {
      G.a[0][j] = 1;
      G.a[1][j] = static_cast<fsw_real>(1.0 + rho * (j % 2 ? -1.0 : 1.0));
    }
    int rank = -1;
    ASSERT_EQ(FSW_OK, fsw_null_projector(tau, G.a, 16, nullptr, &rank));
    EXPECT_EQ(f < 1 ? 1 : 2, rank) << "rho = " << rho;
  }
}

// Issue 21 (mutation survivors of seed 2112): K4's phase-1 stop test is
// relative to |b|.  The interior problem of
// InteriorSolutionIsTheNormalEquationSolution with b scaled by k = 1e-7:
// A x = b exactly (a stop test that is not relative to |b| would end phase 1
// at x = 0), and in double x = k (2/3, 2/3, 4/3), the minimum-norm solution.
// FINDING (single precision, not fixed here, docs/design/coverage.md): phase 2's
// stationarity test is absolute, K4_TOL x the box size (1.2e-4 x 10 here), so
// for |b| below ~1e-3 of the box it stops at the phase-1 point x = k (0, 0, 2):
// the torque is exact but |x| is 2 k instead of 1.63 k.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21SmallRightHandSideIsScaledNotIgnored)
{
  const double k = 1e-7;
  const K4Run r = k4(mat(2, 3, {1, 0, 1, 0, 1, 1}), {2 * k, 2 * k}, 2, 3, box(3, 0, 10));
  EXPECT_EQ(FSW_OK, r.s);
  const double x0 = double(r.x[0]) / k, x1 = double(r.x[1]) / k, x2 = double(r.x[2]) / k;
  EXPECT_NEAR(2.0, x0 + x2, kTol);  // A x = b, relative to k
  EXPECT_NEAR(2.0, x1 + x2, kTol);
  if (!kt::kFloat) {
    EXPECT_NEAR(2.0 / 3, x0, kTol);
    EXPECT_NEAR(2.0 / 3, x1, kTol);
    EXPECT_NEAR(4.0 / 3, x2, kTol);
  }
}

// Issue 21 (mutation survivors of seed 2112): the free set is kept in index
// order, so the LDL^T of phase 1 meets the columns in index order and ties
// of the rank test go to the lower index.  a0 = (1/2)(1, d), a1 = (1, 0),
// b = (1, 1), box [0, 10]^2 (d as in EnteringColumnDroppedByTheRankTest...).
// a1 enters first (gradient 1 > (1 + d)/2): x1 = 1.  a0 enters; in index
// order its pivot comes first and is kept, a1's (d^2-small) is dropped, so
// z = (2 (1 + d)/(1 + d^2), 0): x1 is blocked at 0 and x0 takes over.
// Phase 2 then gives the minimum-norm point of the numerically rank-1
// system x0 / 2 + x1 = (1 + d)/(1 + d^2): (0.4, 0.8) (1 + d)/(1 + d^2).
// (In the other order a0's pivot would be the one dropped: x = (0, 1).)
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21FreeSetInIndexOrder)
{
  const double d = kt::tol(1e-9, 1e-3);
  const K4Run r = k4(mat(2, 2, {0.5, 1.0, 0.5 * d, 0.0}), {1, 1}, 2, 2, box(2, 0, 10));
  EXPECT_EQ(FSW_OK, r.s);
  const double c = (1 + d) / (1 + d * d);
  expect_x(r, {0.4 * c, 0.8 * c}, "index order");
}

// Issue 21 (seed 9001, fsw_linalg.c:436): phase 2's ratio test keeps the
// smallest step of all blocking variables, variable 0 included.
// A = [3 -1 2; 1 1 -3], b = (1, -2), box [0,2] x [0,1] x [0,2].  A x = b is
// the line (0, 1, 1) + t (1, 11, 4) (the null vector is row 1 x row 2);
// x0 >= 0 needs t >= 0 and x1 <= 1 needs t <= 0, so (0, 1, 1) is the only
// admissible solution, and K4 delivers A x = b whenever one exists.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21OnlyAdmissibleSolutionIsFound)
{
  Box B = box(3, 0, 2);
  B.hi[1] = 1;
  const K4Run r = k4(mat(2, 3, {3, -1, 2, 1, 1, -3}), {1, -2}, 2, 3, B);
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {0.0, 1.0, 1.0}, "unique admissible solution");
  EXPECT_LE(r.iter, 3 * 3);
}

// Issue 21 (seed 2112, fsw_linalg.c:371): phase 1 steps only as far as the
// first bound (ratio test), not to the unconstrained point.
// A = [-1 3 1; 2 -1 -1], b = (1, -3), box [0,3] x [0,1] x [0,4].  A x = b
// is the line (0, -1, 4) + t (-2, 1, -5): x0 >= 0 needs t <= 0, x1 >= 0
// needs t >= 1, so no admissible solution; least squares instead.  At
// x = (0, 0, 2): r = b - A x = (-1, -1), the gradient of |r|^2 / 2 is
// -A^T r = (1, 2, 0): x0 and x1 sit at their lower bound with a positive
// gradient, x2 is inside with a zero one, the KKT conditions of this convex
// problem.  The minimiser is unique: A x = (2, -2) along the null line
// needs x0 = -2t >= 0 and x1 = t >= 0, t = 0.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21PhaseOneStopsAtTheFirstBound)
{
  Box B = box(3, 0, 3);
  B.hi[1] = 1;
  B.hi[2] = 4;
  const K4Run r = k4(mat(2, 3, {-1, 3, 1, 2, -1, -1}), {1, -3}, 2, 3, B);
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {0.0, 0.0, 2.0}, "least squares in the box");
}

// Issue 21 (seed 9001, fsw_linalg.c:304): a column enters phase 1 only when
// its gradient beats the round-off floor scaled by its own norm.
// A = [1 -2 2; -3 3 -3; -1 2 -2] (row 3 = -row 1, rank 2), b = (-4, -3, 1),
// box [0,2] x [0,1] x [-3,0].  With s = row1 . x and u = x1 - x2 (>= 0):
// |A x - b|^2 = 2 (s + 5/2)^2 + 9 (x0 - u - 1)^2 + const, s = x0 - 2 u.
// Unconstrained: u = 7/2, x0 = 9/2 > 2, so x0 = 2 (its partial derivative
// at the optimum below is -90/17 < 0: it presses on the upper bound), and
// d/du [2 (9/2 - 2u)^2 + 9 (1 - u)^2] = 34 u - 54 = 0 gives u = 27/17.  The
// least-squares set is x0 = 2, x1 - x2 = 27/17; its minimum norm point is
// x1 = -x2 = 27/34, inside the box.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21RankTwoLeastSquaresWithMinimumNorm)
{
  Box B = box(3, 0, 2);
  B.hi[1] = 1;
  B.lo[2] = -3;
  B.hi[2] = 0;
  const K4Run r = k4(mat(3, 3, {1, -2, 2, -3, 3, -3, -1, 2, -2}), {-4, -3, 1}, 3, 3, B);
  EXPECT_EQ(FSW_OK, r.s);
  expect_x(r, {2.0, 27.0 / 34, -27.0 / 34}, "minimum-norm least squares");
}

// Issue 21 (an exhaustive mutation pass over K4): scaling A and b by a power
// of two changes nothing.  Every test of K4 is relative (residual against
// K4_TOL |b|, gradient against K4_TOL |b| |a_i|, LDL^T pivot against
// FSW_RANK_TOL times the largest diagonal, steps against the box), and
// products by 2^k are exact, so x and the iteration count must be
// bit-identical at 2^-20 and 2^20 (|A| ~ 1e-6 .. 1e6: no underflow or
// overflow in float either).  The problems are the three above (a unique
// admissible solution, a least-squares case, a rank-2 A).
// Verifies: REQ-LINALG-006, REQ-LINALG-002
TEST(FswBoundedMinNorm, Issue21ScalingAAndBByAPowerOfTwoChangesNothing)
{
  struct Problem {
    Mat3N A;
    fsw_real b[3];
    int m;
    Box B;
  };
  Problem ps[3];
  ps[0] = {mat(2, 3, {3, -1, 2, 1, 1, -3}), {1, -2, 0}, 2, box(3, 0, 2)};
  ps[0].B.hi[1] = 1;
  ps[1] = {mat(2, 3, {-1, 3, 1, 2, -1, -1}), {1, -3, 0}, 2, box(3, 0, 3)};
  ps[1].B.hi[1] = 1;
  ps[1].B.hi[2] = 4;
  ps[2] = {mat(3, 3, {1, -2, 2, -3, 3, -3, -1, 2, -2}), {-4, -3, 1}, 3, box(3, 0, 2)};
  ps[2].B.hi[1] = 1;
  ps[2].B.lo[2] = -3;
  ps[2].B.hi[2] = 0;
  for (int k = 0; k < 3; k++) {
    const Problem& p = ps[k];
    fsw_real x1[FSW_MAX_EFF];
    int it1 = -1;
    ASSERT_EQ(FSW_OK, fsw_bounded_minnorm_solve(x1, p.A.a, p.b, p.m, 3, p.B.lo, p.B.hi, &it1));
    for (const int e : {-20, 20}) {
      const fsw_real s = static_cast<fsw_real>(std::ldexp(1.0, e));
      Mat3N As = p.A;
      fsw_real bs[3];
      for (int i = 0; i < 3; i++) {
        bs[i] = p.b[i] * s;
        for (int j = 0; j < 3; j++) As.a[i][j] = p.A.a[i][j] * s;
      }
      fsw_real xs[FSW_MAX_EFF];
      int its = -1;
      ASSERT_EQ(FSW_OK, fsw_bounded_minnorm_solve(xs, As.a, bs, p.m, 3, p.B.lo, p.B.hi, &its));
      for (int j = 0; j < 3; j++) EXPECT_EQ(x1[j], xs[j]) << "problem " << k << ", scale 2^" << e << ", entry " << j;
      EXPECT_EQ(it1, its) << "problem " << k << ", scale 2^" << e;
    }
  }
}

// Issue 21 (an exhaustive mutation pass over K4): x receives exactly n
// entries; the caller's entries past n are not written (the k4 helper
// fills them with 99).  At full capacity (n = FSW_MAX_EFF, where a loop one
// past would leave the arrays) the sum x_1 + ... + x_n = n / 2 in [0, 1]^n
// has the minimum-norm solution x_i = 1/2 (equal entries by symmetry,
// 1/2 each to meet the sum).
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Issue21WritesOnlyTheNEntriesOfX)
{
  const K4Run r = k4(mat(1, 2, {1, 1}), {1}, 1, 2, box(2, 0, 10));
  ASSERT_EQ(FSW_OK, r.s);
  expect_x(r, {0.5, 0.5}, "two entries");
  for (int j = 2; j < FSW_MAX_EFF; j++) EXPECT_EQ(99, r.x[j]) << j;

  const int n = FSW_MAX_EFF;
  Mat3N A;
  std::memset(&A, 0, sizeof A);
  for (int j = 0; j < n; j++) A.a[0][j] = 1;
  const Box B = box(n, 0, 1);
  fsw_real b[3] = {static_cast<fsw_real>(n / 2.0), 0, 0};
  fsw_real x[FSW_MAX_EFF];
  int it = -1;
  ASSERT_EQ(FSW_OK, fsw_bounded_minnorm_solve(x, A.a, b, 1, n, B.lo, B.hi, &it));
  for (int j = 0; j < n; j++) EXPECT_NEAR(0.5, double(x[j]), kTol) << j;
  EXPECT_LE(it, 3 * n);
}

// Mutation seed 31337 (fsw_linalg.c:432): in phase 2 a free variable whose
// minimum-norm value z lands exactly ON its bound does not block the step
// (only z < lo or z > hi does): it stays free at the bound.  A = [1 1],
// b = 2, box [0, 4] x [0, 1]; every number below is exact in binary.
// Hand trace of the iterations (each inner phase-1 solve and each phase-2
// pass counts one):
//  1: phase 1 from x = 0, r = 2, gradients A^T r = (2, 2): the tie goes to
//     index 0; its least-squares value 2 is inside [0, 4]: x = (2, 0);
//     np = m = 1 ends phase 1.
//  2: phase 2, free {0}: lam = 2, z0 = 2 = x0, stationary; x1 at its lower
//     bound has multiplier A1 lam - lo1 = 2 > 0: released.
//  3: free {0, 1}: A A^T = 2, c = A x = 2, lam = 1, z = (1, 1).  z1 = 1 is
//     on hi1 = 1, not beyond: no blocking variable, full step x = (1, 1),
//     nothing bound to release: done after 3 iterations.
// x = (1, 1) is the least-norm solution of x0 + x1 = 2 (x0 = x1), inside the
// box.  Treating z1 = hi1 as blocking would fix x1 at 1 and need a 4th pass
// to find the same x.
// Verifies: REQ-LINALG-006
TEST(FswBoundedMinNorm, Seed31337PhaseTwoValueOnItsBoundDoesNotBlock)
{
  const Mat3N A = mat(1, 2, {1.0, 1.0});
  Box B = box(2, 0, 4);
  B.hi[1] = 1;
  const K4Run r = k4(A, {2.0}, 1, 2, B);
  EXPECT_EQ(FSW_OK, r.s);
  EXPECT_EQ(1, r.x[0]);  // exact: 2 + 1 * (1 - 2)
  EXPECT_EQ(1, r.x[1]);
  EXPECT_EQ(3, r.iter);
}

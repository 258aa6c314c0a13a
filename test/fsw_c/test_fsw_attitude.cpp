// Attitude maths: MRP (with shadow set), MRP add/sub, MRP <-> DCM <->
// quaternion, tilde.  Closed-form cases plus properties over seeded random
// attitudes, checked against independent formulas written in this file.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fsw/fsw_attitude.h"
#include "fsw/fsw_vec.h"
#include "kestrel_test_support.h"

namespace {

const double kTol = kt::tol(1e-13, 2e-6);
const double kPi = 3.14159265358979323846;

/* random MRP with |s| <= smax (uniform axis, uniform angle) */
void random_mrp(kt::Rng& r, fsw_real s[3], double phi_max = 2.0 * kPi)
{
  double e[3];
  r.unit3(e);
  const double phi = r.uniform(0.0, phi_max);
  const double t = std::tan(phi / 4.0);
  for (int i = 0; i < 3; i++) s[i] = static_cast<fsw_real>(t * e[i]);
}

/* Independent DCM: [C] = I + (8 [s~]^2 - 4 (1 - s^2) [s~]) / (1 + s^2)^2
 * (Schaub & Junkins eq. 3.152), in double. */
void ref_dcm(double C[3][3], const fsw_real sr[3])
{
  const double s[3] = {sr[0], sr[1], sr[2]};
  const double s2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
  const double T[3][3] = {{0, -s[2], s[1]}, {s[2], 0, -s[0]}, {-s[1], s[0], 0}};
  double T2[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      T2[i][j] = 0;
      for (int k = 0; k < 3; k++) T2[i][j] += T[i][k] * T[k][j];
    }
  const double d = (1 + s2) * (1 + s2);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) C[i][j] = (i == j ? 1.0 : 0.0) + (8 * T2[i][j] - 4 * (1 - s2) * T[i][j]) / d;
}

void expect_dcm_near(const fsw_real A[3][3], const fsw_real B[3][3], double tol)
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_NEAR(A[i][j], B[i][j], tol) << i << "," << j;
}

// Verifies: REQ-ATT-001
TEST(FswMrp, DcmOfAxis3RotationIsM3)
{
  // sigma = e3 tan(theta/4) gives the passive rotation [M3(theta)].
  const double th = 0.7;
  fsw_real s[3] = {0, 0, static_cast<fsw_real>(std::tan(th / 4))}, C[3][3];
  fsw_mrp_to_dcm(C, s);
  const double c = std::cos(th), sn = std::sin(th);
  const double want[3][3] = {{c, sn, 0}, {-sn, c, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_NEAR(want[i][j], C[i][j], kTol);
  EXPECT_NEAR(th, fsw_mrp_angle(s), kTol);
}

// Verifies: REQ-ATT-001
TEST(FswMrp, DcmMatchesIndependentFormulaAndIsOrthonormal)
{
  kt::Rng r(101);
  for (int k = 0; k < 300; k++) {
    fsw_real s[3], C[3][3], CCt[3][3];
    random_mrp(r, s);
    fsw_mrp_to_dcm(C, s);
    double R[3][3];
    ref_dcm(R, s);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_NEAR(R[i][j], C[i][j], kTol * 10);
    fsw_m33_mult_t(CCt, FSW_CM33(C), FSW_CM33(C));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_NEAR(i == j ? 1.0 : 0.0, CCt[i][j], kTol * 10);
    EXPECT_NEAR(1.0, fsw_m33_det(FSW_CM33(C)), kTol * 10);
  }
}

// Verifies: REQ-ATT-002
TEST(FswMrp, ShadowSetDescribesTheSameAttitude)
{
  kt::Rng r(102);
  for (int k = 0; k < 200; k++) {
    fsw_real s[3], sh[3], C1[3][3], C2[3][3], sw[3];
    random_mrp(r, s, 1.9 * kPi);
    if (fsw_v3_norm(s) < 1e-3) continue;
    fsw_mrp_shadow(sh, s);
    fsw_mrp_to_dcm(C1, s);
    fsw_mrp_to_dcm(C2, sh);
    expect_dcm_near(C1, C2, kTol * 10);
    // |s| |shadow(s)| = 1
    EXPECT_NEAR(1.0, fsw_v3_norm(s) * fsw_v3_norm(sh), kTol * 10);
    fsw_mrp_switch(sw, s);
    EXPECT_LE(fsw_v3_norm2(sw), 1.0 + kTol);
    if (fsw_v3_norm2(s) <= 1) {
      for (int i = 0; i < 3; i++) EXPECT_EQ(s[i], sw[i]);
    }
  }
  fsw_real z[3] = {0, 0, 0}, out[3] = {1, 1, 1};
  fsw_mrp_shadow(out, z);  // no shadow of the identity: documented as 0
  EXPECT_EQ(0, out[0] + out[1] + out[2]);
}

// Verifies: REQ-ATT-001
TEST(FswMrp, RoundTripsThroughDcmAndQuaternion)
{
  kt::Rng r(103);
  for (int k = 0; k < 300; k++) {
    fsw_real s[3], C[3][3], s2[3], q[4], s3[3], C2[3][3], q2[4];
    random_mrp(r, s, kPi * 0.999);  // |s| < 1: the round trip returns s itself
    fsw_mrp_to_dcm(C, s);
    fsw_dcm_to_mrp(s2, FSW_CM33(C));
    for (int i = 0; i < 3; i++) EXPECT_NEAR(s[i], s2[i], kTol * 10);
    fsw_mrp_to_quat(q, s);
    EXPECT_NEAR(1.0, fsw_vn_norm(q, 4), kTol);
    EXPECT_GE(q[0], 0);
    fsw_quat_to_mrp(s3, q);
    for (int i = 0; i < 3; i++) EXPECT_NEAR(s[i], s3[i], kTol * 10);
    fsw_quat_to_dcm(C2, q);
    expect_dcm_near(C, C2, kTol * 10);
    fsw_dcm_to_quat(q2, FSW_CM33(C));
    for (int i = 0; i < 4; i++) EXPECT_NEAR(q[i], q2[i], kTol * 10);
    // -q is the same attitude: quat_to_mrp picks the short rotation
    fsw_real nq[4] = {-q[0], -q[1], -q[2], -q[3]}, s4[3];
    fsw_quat_to_mrp(s4, nq);
    for (int i = 0; i < 3; i++) EXPECT_NEAR(s[i], s4[i], kTol * 10);
  }
}

// Verifies: REQ-ATT-001, REQ-ATT-004
TEST(FswMrp, HalfTurnAndDegenerateQuaternions)
{
  // 180 deg about x: trace = -1, Sheppard must take the b1 branch.
  const fsw_real C[3][3] = {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  fsw_real q[4], s[3];
  fsw_dcm_to_quat(q, C);
  EXPECT_NEAR(0.0, q[0], kTol);
  EXPECT_NEAR(1.0, std::fabs(q[1]), kTol);
  fsw_dcm_to_mrp(s, C);
  EXPECT_NEAR(1.0, fsw_v3_norm(s), kTol);  // |sigma| = tan(180/4) = 1
  EXPECT_NEAR(kPi, fsw_mrp_angle(s), kTol * 10);
  // a zero quaternion is not an attitude: documented as identity
  fsw_real z[4] = {0, 0, 0, 0}, I[3][3];
  fsw_quat_to_dcm(I, z);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_EQ(i == j ? 1 : 0, I[i][j]);
  // a non-unit quaternion is normalised first
  fsw_real q3[4] = {2, 0, 0, 0}, C3[3][3];
  fsw_quat_to_dcm(C3, q3);
  EXPECT_NEAR(1.0, C3[0][0], kTol);
}

// Verifies: REQ-ATT-003
TEST(FswMrp, AddComposesRotations)
{
  // DCM(add(q1, q2)) = DCM(q2) DCM(q1): rotation q1 followed by q2.
  kt::Rng r(104);
  for (int k = 0; k < 400; k++) {
    fsw_real q1[3], q2[3], q[3], C1[3][3], C2[3][3], C21[3][3], C[3][3];
    random_mrp(r, q1);
    random_mrp(r, q2);
    fsw_mrp_add(q, q1, q2);
    EXPECT_LE(fsw_v3_norm2(q), 1.0 + kTol);
    fsw_mrp_to_dcm(C1, q1);
    fsw_mrp_to_dcm(C2, q2);
    fsw_m33_mult(C21, FSW_CM33(C2), FSW_CM33(C1));
    fsw_mrp_to_dcm(C, q);
    expect_dcm_near(C21, C, kTol * 1e3);
  }
}

// Verifies: REQ-ATT-003
TEST(FswMrp, SubGivesRelativeAttitude)
{
  // DCM(sub(q1, q2)) = DCM(q1) DCM(q2)^T: e.g. [BR] = [BN][RN]^T.
  kt::Rng r(105);
  for (int k = 0; k < 400; k++) {
    fsw_real q1[3], q2[3], q[3], C1[3][3], C2[3][3], C12[3][3], C[3][3];
    random_mrp(r, q1);
    random_mrp(r, q2);
    fsw_mrp_sub(q, q1, q2);
    EXPECT_LE(fsw_v3_norm2(q), 1.0 + kTol);
    fsw_mrp_to_dcm(C1, q1);
    fsw_mrp_to_dcm(C2, q2);
    fsw_m33_mult_t(C12, FSW_CM33(C1), FSW_CM33(C2));
    fsw_mrp_to_dcm(C, q);
    expect_dcm_near(C12, C, kTol * 1e3);
  }
}

// Verifies: REQ-ATT-003
TEST(FswMrp, SubOfNearly360DegreeApartSetsUsesTheShadowBranch)
{
  // q1 = -0.999 e1 (-179.885 deg) and q2 = +0.999 e1 (+179.885 deg) are only
  // 0.229 deg apart, but with the plain sets den = 1 + |q1|^2|q2|^2 + 2 q1.q2
  // = (1 - 0.998001)^2 = 4.0e-6.  The 0.1 switch must replace q1 by its
  // shadow so the result is finite and equals the small true rotation.
  const fsw_real q2[3] = {FSW_R(0.999), 0, 0};
  const fsw_real q1[3] = {FSW_R(-0.999), 0, 0};
  fsw_real q[3];
  fsw_mrp_sub(q, q1, q2);
  fsw_real C1[3][3], C2[3][3], C12[3][3], C[3][3];
  fsw_mrp_to_dcm(C1, q1);
  fsw_mrp_to_dcm(C2, q2);
  fsw_m33_mult_t(C12, FSW_CM33(C1), FSW_CM33(C2));
  fsw_mrp_to_dcm(C, q);
  expect_dcm_near(C12, C, kt::tol(1e-9, 1e-4));
  EXPECT_TRUE(fsw_v3_is_finite(q));
  const double want = 8.0 * std::atan(0.999) - 2.0 * kPi;  // 359.77 deg wraps to 0.229 deg
  EXPECT_NEAR(std::fabs(want), fsw_mrp_angle(q), kt::tol(1e-9, 1e-4));
}

// Verifies: REQ-ATT-003
TEST(FswMrp, AddOfIdentityIsIdentityMap)
{
  kt::Rng r(106);
  const fsw_real z[3] = {0, 0, 0};
  for (int k = 0; k < 50; k++) {
    fsw_real s[3], a[3], b[3], d[3];
    random_mrp(r, s, kPi * 0.99);
    fsw_mrp_add(a, s, z);
    fsw_mrp_add(b, z, s);
    fsw_mrp_sub(d, s, s);
    for (int i = 0; i < 3; i++) {
      EXPECT_NEAR(s[i], a[i], kTol);
      EXPECT_NEAR(s[i], b[i], kTol);
      EXPECT_NEAR(0.0, d[i], kTol);
    }
  }
}

// Verifies: REQ-ATT-005
TEST(FswTilde, IsCrossProductMatrix)
{
  kt::Rng r(107);
  for (int k = 0; k < 100; k++) {
    fsw_real a[3], b[3], T[3][3], Tb[3], axb[3];
    for (int i = 0; i < 3; i++) {
      a[i] = static_cast<fsw_real>(r.uniform(-5, 5));
      b[i] = static_cast<fsw_real>(r.uniform(-5, 5));
    }
    fsw_tilde(T, a);
    fsw_m33_mult_v3(Tb, FSW_CM33(T), b);
    fsw_v3_cross(axb, a, b);
    for (int i = 0; i < 3; i++) EXPECT_NEAR(axb[i], Tb[i], kTol * 100);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_EQ(T[i][j], -T[j][i]);
  }
}

// Verifies: REQ-ATT-005
TEST(FswMrp, KinematicsMatrixProperties)
{
  // [B] w = (1 - s^2) w + 2 s x w + 2 s (s.w), and [B][B]^T = (1 + s^2)^2 I.
  kt::Rng r(108);
  for (int k = 0; k < 100; k++) {
    fsw_real s[3], w[3], B[3][3], Bw[3], BBt[3][3];
    random_mrp(r, s, kPi);
    for (int i = 0; i < 3; i++) w[i] = static_cast<fsw_real>(r.uniform(-1, 1));
    fsw_mrp_bmat(B, s);
    fsw_m33_mult_v3(Bw, FSW_CM33(B), w);
    const double s2 = fsw_v3_norm2(s), sw = fsw_v3_dot(s, w);
    fsw_real sxw[3];
    fsw_v3_cross(sxw, s, w);
    for (int i = 0; i < 3; i++) EXPECT_NEAR((1 - s2) * w[i] + 2 * sxw[i] + 2 * s[i] * sw, Bw[i], kTol * 10);
    fsw_m33_mult_t(BBt, FSW_CM33(B), FSW_CM33(B));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_NEAR(i == j ? (1 + s2) * (1 + s2) : 0.0, BBt[i][j], kTol * 10);
  }
}

}  // namespace

// Issue 21: Sheppard's degenerate branch.  The four b_k^2 = (1 + tr)/4,
// (1 + 2 C_kk - tr)/4 sum to exactly 1 for any matrix, so the largest is
// >= 1/4 and f = 4 sqrt(b_k^2) >= 2 for every finite C (the zero matrix gives
// b^2 = (1/4, 1/4, 1/4, 1/4): q = (1/2, 0, 0, 0), normalised to identity).
// f > 0 fails only when the diagonal holds a NaN (every b^2 is NaN) or
// overflows (-1e308 on the diagonal: tr = -inf, b0^2 = -inf, the others
// -inf + inf = NaN): the branch then gives the identity quaternion, finite,
// instead of propagating NaN into the attitude.
// Verifies: REQ-ATT-004
TEST(FswMrp, Issue21DcmToQuatDegenerateInputGivesIdentity)
{
  const fsw_real big = -std::numeric_limits<fsw_real>::max();
  const fsw_real nan = std::numeric_limits<fsw_real>::quiet_NaN();
  const fsw_real Z[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const fsw_real N[3][3] = {{nan, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const fsw_real O[3][3] = {{big, 0, 0}, {0, big, 0}, {0, 0, big}};
  const fsw_real* cases[3] = {&Z[0][0], &N[0][0], &O[0][0]};
  const char* why[3] = {"zero matrix", "NaN on the diagonal", "overflowing trace"};
  for (int c = 0; c < 3; c++) {
    fsw_real C[3][3], q[4] = {9, 9, 9, 9}, s[3] = {9, 9, 9};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) C[i][j] = cases[c][3 * i + j];
    fsw_dcm_to_quat(q, C);
    EXPECT_EQ(1.0, q[0]) << why[c];
    for (int i = 1; i < 4; i++) EXPECT_EQ(0.0, q[i]) << why[c] << " q" << i;
    fsw_dcm_to_mrp(s, C);
    for (int i = 0; i < 3; i++) EXPECT_EQ(0.0, s[i]) << why[c] << " sigma" << i;
  }
}

// Issue 21: a quaternion whose norm is not finite (an Inf entry) is not an
// attitude: like the zero quaternion (HalfTurnAndDegenerateQuaternions) it
// gives the identity DCM rather than NaN.
// Verifies: REQ-ATT-004
TEST(FswMrp, Issue21InfiniteQuaternionGivesIdentity)
{
  const fsw_real q[4] = {0, std::numeric_limits<fsw_real>::infinity(), 0, 0};
  fsw_real C[3][3];
  fsw_quat_to_dcm(C, q);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) EXPECT_EQ(i == j ? 1.0 : 0.0, C[i][j]) << i << "," << j;
}

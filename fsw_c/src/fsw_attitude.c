/* fsw_attitude: MRP / DCM / quaternion maths (docs/fsw/core.md, "Kernels" K3). */
#include "fsw/fsw_attitude.h"

#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"

void fsw_mrp_shadow(fsw_real out[3], const fsw_real s[3])
{
  fsw_real s2 = fsw_v3_norm2(s);
  if (s2 > FSW_R(0.0)) {
    fsw_v3_scale(out, FSW_R(-1.0) / s2, s);
  } else {
    fsw_v3_zero(out);
  }
}

void fsw_mrp_switch(fsw_real out[3], const fsw_real s[3])
{
  if (fsw_v3_norm2(s) > FSW_R(1.0)) {
    fsw_mrp_shadow(out, s);
  } else {
    fsw_v3_copy(out, s);
  }
}

fsw_real fsw_mrp_angle(const fsw_real s[3]) { return FSW_R(4.0) * FSW_ATAN(fsw_v3_norm(s)); }

void fsw_mrp_to_dcm(fsw_real C[3][3], const fsw_real s[3])
{
  const fsw_real s1 = s[0], s2 = s[1], s3 = s[2];
  const fsw_real q = s1 * s1 + s2 * s2 + s3 * s3; /* s^2 */
  const fsw_real S = FSW_R(1.0) - q;
  const fsw_real d = (FSW_R(1.0) + q) * (FSW_R(1.0) + q);
  C[0][0] = (FSW_R(4.0) * (FSW_R(2.0) * s1 * s1 - q) + S * S) / d;
  C[0][1] = (FSW_R(8.0) * s1 * s2 + FSW_R(4.0) * s3 * S) / d;
  C[0][2] = (FSW_R(8.0) * s1 * s3 - FSW_R(4.0) * s2 * S) / d;
  C[1][0] = (FSW_R(8.0) * s2 * s1 - FSW_R(4.0) * s3 * S) / d;
  C[1][1] = (FSW_R(4.0) * (FSW_R(2.0) * s2 * s2 - q) + S * S) / d;
  C[1][2] = (FSW_R(8.0) * s2 * s3 + FSW_R(4.0) * s1 * S) / d;
  C[2][0] = (FSW_R(8.0) * s3 * s1 + FSW_R(4.0) * s2 * S) / d;
  C[2][1] = (FSW_R(8.0) * s3 * s2 - FSW_R(4.0) * s1 * S) / d;
  C[2][2] = (FSW_R(4.0) * (FSW_R(2.0) * s3 * s3 - q) + S * S) / d;
}

static void quat_normalize_pos(fsw_real q[4])
{
  fsw_real n = fsw_vn_norm(q, 4);
  int i;
  if (!(n > FSW_R(0.0)) || !isfinite(n)) {
    q[0] = FSW_R(1.0);
    q[1] = q[2] = q[3] = FSW_R(0.0);
    return;
  }
  if (q[0] < FSW_R(0.0)) { n = -n; }
  for (i = 0; i < 4; i++) { q[i] /= n; }
}

void fsw_dcm_to_quat(fsw_real q[4], const fsw_real C[3][3])
{
  const fsw_real tr = fsw_m33_trace(C);
  fsw_real b2[4];
  int k = 0, i;
  fsw_real bk, f;
  b2[0] = (FSW_R(1.0) + tr) / FSW_R(4.0);
  b2[1] = (FSW_R(1.0) + FSW_R(2.0) * C[0][0] - tr) / FSW_R(4.0);
  b2[2] = (FSW_R(1.0) + FSW_R(2.0) * C[1][1] - tr) / FSW_R(4.0);
  b2[3] = (FSW_R(1.0) + FSW_R(2.0) * C[2][2] - tr) / FSW_R(4.0);
  for (i = 1; i < 4; i++) {
    if (b2[i] > b2[k]) { k = i; } } /* lowest index wins ties */
  bk = FSW_SQRT(b2[k] > FSW_R(0.0) ? b2[k] : FSW_R(0.0));
  f = FSW_R(4.0) * bk;
  if (!(f > FSW_R(0.0))) {
    q[0] = FSW_R(1.0);
    q[1] = q[2] = q[3] = FSW_R(0.0);
    return;
  }
  switch (k) {
  case 0:
    q[0] = bk;
    q[1] = (C[1][2] - C[2][1]) / f;
    q[2] = (C[2][0] - C[0][2]) / f;
    q[3] = (C[0][1] - C[1][0]) / f;
    break;
  case 1:
    q[1] = bk;
    q[0] = (C[1][2] - C[2][1]) / f;
    q[2] = (C[0][1] + C[1][0]) / f;
    q[3] = (C[2][0] + C[0][2]) / f;
    break;
  case 2:
    q[2] = bk;
    q[0] = (C[2][0] - C[0][2]) / f;
    q[1] = (C[0][1] + C[1][0]) / f;
    q[3] = (C[1][2] + C[2][1]) / f;
    break;
  default:
    q[3] = bk;
    q[0] = (C[0][1] - C[1][0]) / f;
    q[1] = (C[2][0] + C[0][2]) / f;
    q[2] = (C[1][2] + C[2][1]) / f;
    break;
  }
  quat_normalize_pos(q);
}

void fsw_quat_to_dcm(fsw_real C[3][3], const fsw_real qin[4])
{
  fsw_real q[4];
  fsw_real b0, b1, b2, b3;
  fsw_vn_copy(q, qin, 4);
  quat_normalize_pos(q);
  b0 = q[0];
  b1 = q[1];
  b2 = q[2];
  b3 = q[3];
  C[0][0] = b0 * b0 + b1 * b1 - b2 * b2 - b3 * b3;
  C[0][1] = FSW_R(2.0) * (b1 * b2 + b0 * b3);
  C[0][2] = FSW_R(2.0) * (b1 * b3 - b0 * b2);
  C[1][0] = FSW_R(2.0) * (b1 * b2 - b0 * b3);
  C[1][1] = b0 * b0 - b1 * b1 + b2 * b2 - b3 * b3;
  C[1][2] = FSW_R(2.0) * (b2 * b3 + b0 * b1);
  C[2][0] = FSW_R(2.0) * (b1 * b3 + b0 * b2);
  C[2][1] = FSW_R(2.0) * (b2 * b3 - b0 * b1);
  C[2][2] = b0 * b0 - b1 * b1 - b2 * b2 + b3 * b3;
}

void fsw_quat_to_mrp(fsw_real s[3], const fsw_real qin[4])
{
  fsw_real q[4];
  fsw_vn_copy(q, qin, 4);
  quat_normalize_pos(q); /* b0 >= 0 so that |s| <= 1 and 1 + b0 >= 1 */
  fsw_v3_scale(s, FSW_R(1.0) / (FSW_R(1.0) + q[0]), &q[1]);
}

void fsw_mrp_to_quat(fsw_real q[4], const fsw_real s[3])
{
  const fsw_real s2 = fsw_v3_norm2(s);
  const fsw_real d = FSW_R(1.0) + s2;
  q[0] = (FSW_R(1.0) - s2) / d;
  q[1] = FSW_R(2.0) * s[0] / d;
  q[2] = FSW_R(2.0) * s[1] / d;
  q[3] = FSW_R(2.0) * s[2] / d;
}

void fsw_dcm_to_mrp(fsw_real out[3], const fsw_real C[3][3])
{
  fsw_real q[4];
  fsw_dcm_to_quat(q, C);
  fsw_quat_to_mrp(out, q);
}

/* Shared body of addMRP / subMRP: sign = +1 for add, -1 for sub. */
static void mrp_compose(fsw_real out[3], const fsw_real q1in[3], const fsw_real q2[3],
                        fsw_real sign)
{
  fsw_real q1[3], c[3], r[3];
  fsw_real n1, n2, den;
  fsw_v3_copy(q1, q1in);
  n1 = fsw_v3_norm2(q1);
  n2 = fsw_v3_norm2(q2);
  den = FSW_R(1.0) + n1 * n2 - sign * FSW_R(2.0) * fsw_v3_dot(q1, q2);
  if (FSW_FABS(den) < FSW_R(0.1)) {
    fsw_mrp_shadow(q1, q1);
    n1 = fsw_v3_norm2(q1);
    den = FSW_R(1.0) + n1 * n2 - sign * FSW_R(2.0) * fsw_v3_dot(q1, q2);
  }
  fsw_v3_cross(c, q1, q2);
  r[0] = (FSW_R(1.0) - n2) * q1[0] + sign * (FSW_R(1.0) - n1) * q2[0] + FSW_R(2.0) * c[0];
  r[1] = (FSW_R(1.0) - n2) * q1[1] + sign * (FSW_R(1.0) - n1) * q2[1] + FSW_R(2.0) * c[1];
  r[2] = (FSW_R(1.0) - n2) * q1[2] + sign * (FSW_R(1.0) - n1) * q2[2] + FSW_R(2.0) * c[2];
  r[0] /= den;
  r[1] /= den;
  r[2] /= den;
  fsw_mrp_switch(out, r);
}

void fsw_mrp_add(fsw_real out[3], const fsw_real q1[3], const fsw_real q2[3])
{
  mrp_compose(out, q1, q2, FSW_R(1.0));
}

void fsw_mrp_sub(fsw_real out[3], const fsw_real q1[3], const fsw_real q2[3])
{
  mrp_compose(out, q1, q2, FSW_R(-1.0));
}

void fsw_mrp_bmat(fsw_real B[3][3], const fsw_real s[3])
{
  const fsw_real s2 = fsw_v3_norm2(s);
  int i, j;
  fsw_tilde(B, s);
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) { B[i][j] = FSW_R(2.0) * B[i][j] + FSW_R(2.0) * s[i] * s[j]; } }
  for (i = 0; i < 3; i++) { B[i][i] += FSW_R(1.0) - s2; }
}

void fsw_tilde(fsw_real out[3][3], const fsw_real v[3])
{
  const fsw_real x = v[0], y = v[1], z = v[2];
  out[0][0] = FSW_R(0.0);
  out[0][1] = -z;
  out[0][2] = y;
  out[1][0] = z;
  out[1][1] = FSW_R(0.0);
  out[1][2] = -x;
  out[2][0] = -y;
  out[2][1] = x;
  out[2][2] = FSW_R(0.0);
}

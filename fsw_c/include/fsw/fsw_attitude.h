/* fsw_attitude: MRP, DCM and quaternion maths (docs/fsw/core.md, "Kernels" K3).
 * Conventions (Schaub & Junkins):
 *   sigma = e_hat * tan(Phi/4), Phi the principal rotation angle;
 *   dcm_BN maps N components to B components: v_B = dcm_BN v_N;
 *   quaternion beta = [b0, b1, b2, b3], scalar FIRST, b0 = cos(Phi/2),
 *   same sense as the MRP and the DCM (passive, frame rotation).
 * The shadow set of sigma is -sigma/|sigma|^2; "switch" means replacing sigma
 * by its shadow when |sigma| > 1 so that |sigma| <= 1 (Phi <= 180 deg). */
#ifndef FSW_ATTITUDE_H
#define FSW_ATTITUDE_H

#include "fsw/fsw_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* out = -s/|s|^2; s = 0 (no shadow) gives out = 0. */
void fsw_mrp_shadow(fsw_real out[3], const fsw_real s[3]);
/* out = shadow(s) if |s|^2 > 1, else s. */
void fsw_mrp_switch(fsw_real out[3], const fsw_real s[3]);
/* Principal rotation angle Phi = 4 atan(|s|) [rad], in [0, 2 pi). */
fsw_real fsw_mrp_angle(const fsw_real s[3]);

/* [C] = MRP2C(s), element-wise (docs/fsw/core.md, "Attitude"). */
void fsw_mrp_to_dcm(fsw_real C[3][3], const fsw_real s[3]);
/* MRP of a proper orthonormal [C], |out| <= 1 (through the quaternion). */
void fsw_dcm_to_mrp(fsw_real out[3], const fsw_real C[3][3]);

/* Quaternion of a DCM by Sheppard's method (largest-component branch),
 * normalised, with b0 >= 0. */
void fsw_dcm_to_quat(fsw_real q[4], const fsw_real C[3][3]);
/* DCM of a quaternion; q is normalised first (q = 0 gives the identity). */
void fsw_quat_to_dcm(fsw_real C[3][3], const fsw_real q[4]);
/* MRP of a quaternion: q normalised, sign chosen so b0 >= 0, s = qv/(1+b0). */
void fsw_quat_to_mrp(fsw_real s[3], const fsw_real q[4]);
/* Quaternion of an MRP: b0 = (1-|s|^2)/(1+|s|^2), bv = 2 s/(1+|s|^2). */
void fsw_mrp_to_quat(fsw_real q[4], const fsw_real s[3]);

/* Rotation q1 followed by q2 (spec addMRP), result switched to |out| <= 1. */
void fsw_mrp_add(fsw_real out[3], const fsw_real q1[3], const fsw_real q2[3]);
/* Attitude q1 relative to q2 (spec subMRP), result switched to |out| <= 1. */
void fsw_mrp_sub(fsw_real out[3], const fsw_real q1[3], const fsw_real q2[3]);

/* MRP kinematics matrix [B(s)]: sigma_dot = 1/4 [B] omega. */
void fsw_mrp_bmat(fsw_real B[3][3], const fsw_real s[3]);

/* Skew-symmetric cross-product matrix: tilde(v) w = v x w. */
void fsw_tilde(fsw_real out[3][3], const fsw_real v[3]);

#ifdef __cplusplus
}
#endif

#endif /* FSW_ATTITUDE_H */

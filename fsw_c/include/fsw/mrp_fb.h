/* mrp_fb: MRP feedback attitude control law (docs/fsw/mrp_fb.md, Basilisk
 * mrpFeedback; Schaub & Junkins ch. 8).
 *   omega = omega_BR + omega_RN
 *   int_sigma += K dt sigma_BR, each component clamped to +-integral_limit
 *   z = int_sigma + [I] omega_BR               (only if K_i > 0, else z = 0)
 *   H = [I] omega + sum_avail J_s,i (gs_i . omega + Omega_i) gs_i
 *   v = omega_RN + K_i z  (law 0)   or   v = omega  (law 1)
 *   Lr = -(K sigma_BR + P omega_BR + P K_i z - v x H
 *          + [I](omega x omega_RN - omega_dot_RN) + L_B)
 * Lr is the external torque the actuators must put onto the body (docs/fsw-conventions.md, "Frames, units and signs");
 * it is not saturated here.  Frames: B body.  Units: SI.
 * Stateful (integral and timing, docs/fsw-conventions.md "Timing").
 * Safe output (bad input, bad time, init failed): torque_B = int_torque_B = 0,
 * no state advanced. */
#ifndef FSW_MRP_FB_H
#define FSW_MRP_FB_H

#include <stdint.h>

#include "fsw/att_track.h" /* FswAttGuid */
#include "fsw/fsw_clock.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FSW_MRP_FB_LAW_0 0 /* v = omega_RN + K_i z (Basilisk default) */
#define FSW_MRP_FB_LAW_1 1 /* v = omega_BN                            */

typedef struct {
  fsw_real K;                  /* [N*m]         attitude gain, finite, > 0          */
  fsw_real P;                  /* [N*m*s]       rate gain, finite, > 0              */
  fsw_real K_i;                /* [1/(kg*m^2)]  integral gain, finite; <= 0 disables
                                                the integral term (recommended -1)  */
  fsw_real integral_limit;     /* [N*m*s]       per-component bound on int_sigma,
                                                finite, >= 0                        */
  int control_law_type;        /* [-]           FSW_MRP_FB_LAW_0 or _1              */
  fsw_real known_torque_B[3];  /* [N*m]         known external torque L_B, finite   */
  fsw_real I_B[3][3];          /* [kg*m^2]      spacecraft inertia about the CoM, B
                                                components; finite, symmetric,
                                                positive definite                   */
  int num_rw;                  /* [-]           wheels in H, 0..FSW_MAX_RW (0 = none)*/
  fsw_real gs_hat_B[FSW_MAX_RW][3]; /* [-]      (num_rw) spin axes, unit within
                                                FSW_MRP_FB_UNIT_TOL                 */
  fsw_real J_s[FSW_MAX_RW];    /* [kg*m^2]      (num_rw) spin inertias, (0, 1e4]   */
} FswMrpFbConfig;

typedef struct {
  int ready;              /* [-]     1 after a successful init                   */
  FswClock clock;         /* [-]     previous accepted call (docs/fsw-conventions.md, "Timing")           */
  fsw_real int_sigma[3];  /* [N*m*s] integral of K sigma_BR dt, clamped          */
  FswHealth health;       /* [-]     call counters                               */
} FswMrpFbState;

typedef struct {
  uint64_t t_ns;                 /* [ns]    time stamp of this control step         */
  FswAttGuid guid;               /* guidance message (att_track / guid_sunsafe)     */
  fsw_real Omega[FSW_MAX_RW];    /* [rad/s] (num_rw) wheel speeds rel. body; read
                                            only for available wheels              */
  uint8_t rw_avail[FSW_MAX_RW];  /* [-]     (num_rw) FSW_AVAILABLE (0) or
                                            FSW_UNAVAILABLE (1); zero = all avail. */
} FswMrpFbIn;

typedef struct {
  fsw_real torque_B[3];     /* [N*m] Lr, control torque request on the body       */
  fsw_real int_torque_B[3]; /* [N*m] integral feedback part, -P K_i z (telemetry) */
} FswMrpFbOut;

/* Unit-vector tolerance for gs_hat_B: | |gs| - 1 | <= tol. */
#if FSW_USE_FLOAT
#define FSW_MRP_FB_UNIT_TOL FSW_R(1e-6)
#else
#define FSW_MRP_FB_UNIT_TOL FSW_R(1e-9)
#endif

/* FSW_OK; FSW_E_CONFIG (non-finite value, K or P <= 0, integral_limit < 0,
 * bad control_law_type, inertia not symmetric positive definite, num_rw < 0,
 * non-unit gs_hat_B, J_s not in (0, FSW_RW_J_S_MAX]); FSW_E_CAPACITY (num_rw > FSW_MAX_RW);
 * FSW_E_NULL_ARG. */
FswStatus fsw_mrp_fb_check(const FswMrpFbConfig *cfg);
/* check; ready = 1; health cleared; reset. */
FswStatus fsw_mrp_fb_init(FswMrpFbState *st, const FswMrpFbConfig *cfg);
/* int_sigma = 0, clock reset.  Keeps ready and health. */
void fsw_mrp_fb_reset(FswMrpFbState *st);
/* FSW_OK; with the safe output and no state change: FSW_E_BAD_INPUT (NaN/Inf
 * in guid or in Omega of an available wheel, rw_avail entry not 0/1, finite
 * inputs so large that Lr overflows),
 * FSW_E_TIME (t_ns <= t_prev_ns after the first call), FSW_E_NOT_INIT,
 * FSW_E_NULL_ARG.  dt = 0 on the first call after reset. */
FswStatus fsw_mrp_fb_update(FswMrpFbState *st, const FswMrpFbConfig *cfg, const FswMrpFbIn *in,
                            FswMrpFbOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_MRP_FB_H */

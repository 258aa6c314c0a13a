/* att_track: attitude tracking error (docs/fsw/att_track.md, Basilisk
 * attTrackingError).
 * From the navigation attitude/rate of B and a reference R (FswAttRef) it
 * forms the guidance message FswAttGuid consumed by the control law mrp_fb:
 *   sigma_RN' = addMRP(sigma_RN, -sigma_R0R)      (corrected reference)
 *   sigma_BR  = subMRP(sigma_BN, sigma_RN')
 *   omega_RN_B = [BN] omega_RN_N,  omega_BR_B = omega_BN_B - omega_RN_B,
 *   omega_dot_RN_B = [BN] omega_dot_RN_N,  [BN] = MRP2C(sigma_BN).
 * Stateless.  Frames: B body, N inertial, R reference.  Units: SI, rad.
 * Safe output (bad input, init failed): all four vectors 0 ("no error"). */
#ifndef FSW_ATT_TRACK_H
#define FSW_ATT_TRACK_H

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/guid_inertial.h" /* FswAttRef */

#ifdef __cplusplus
extern "C" {
#endif

/* Attitude guidance message: tracking errors plus the reference motion in B
 * components.  Output of att_track and guid_sunsafe, input of mrp_fb. */
typedef struct {
  fsw_real sigma_BR[3];       /* [-]       MRP of B relative to R, |sigma| <= 1 */
  fsw_real omega_BR_B[3];     /* [rad/s]   angular velocity of B rel. R, B comp. */
  fsw_real omega_RN_B[3];     /* [rad/s]   angular velocity of R rel. N, B comp. */
  fsw_real omega_dot_RN_B[3]; /* [rad/s^2] inertial derivative of omega_RN, B comp. */
} FswAttGuid;

typedef struct {
  fsw_real sigma_R0R[3]; /* [-] MRP of the nominal reference R0 relative to the
                            corrected reference R (0 = none), finite */
} FswAttTrackConfig;

typedef struct {
  int ready;             /* [-] 1 after a successful init             */
  fsw_real sigma_RR0[3]; /* [-] -sigma_R0R, derived once by init      */
  FswHealth health;      /* [-] call counters                         */
} FswAttTrackState;

typedef struct {
  fsw_real sigma_BN[3];   /* [-]     navigation attitude MRP of B rel. N */
  fsw_real omega_BN_B[3]; /* [rad/s] navigation body rate, B components  */
  FswAttRef ref;          /* reference from a guidance module            */
} FswAttTrackIn;

/* The output is the guidance message itself. */
typedef FswAttGuid FswAttTrackOut;

/* FSW_OK, or FSW_E_CONFIG (non-finite sigma_R0R), FSW_E_NULL_ARG. */
FswStatus fsw_att_track_check(const FswAttTrackConfig *cfg);
FswStatus fsw_att_track_init(FswAttTrackState *st, const FswAttTrackConfig *cfg);
/* No dynamic state: kept for the uniform module shape. */
void fsw_att_track_reset(FswAttTrackState *st);
/* FSW_OK; with the safe output: FSW_E_BAD_INPUT (NaN/Inf anywhere in `in`,
 * or finite inputs so large that an output overflows), FSW_E_NOT_INIT,
 * FSW_E_NULL_ARG. */
FswStatus fsw_att_track_update(FswAttTrackState *st, const FswAttTrackConfig *cfg,
                               const FswAttTrackIn *in, FswAttTrackOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_ATT_TRACK_H */

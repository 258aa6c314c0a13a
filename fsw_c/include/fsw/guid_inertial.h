/* guid_inertial: inertial three-axis pointing guidance
 * (docs/fsw/guid_inertial.md, Basilisk inertial3D).
 * Produces a constant attitude reference R0 fixed in N: sigma_RN = sigma_R0N,
 * omega_RN_N = 0, omega_dot_RN_N = 0.  Stateless, no inputs.
 * Frames: N inertial, R reference.  Units: SI, rad.
 * Safe output (init failed or never ran): sigma_RN = 0 (R = N), rates 0. */
#ifndef FSW_GUID_INERTIAL_H
#define FSW_GUID_INERTIAL_H

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Attitude reference message: the output of every reference generator and
 * the reference input of att_track (docs/fsw/att_track.md). */
typedef struct {
  fsw_real sigma_RN[3];       /* [-]       MRP of R relative to N, |sigma| <= 1 */
  fsw_real omega_RN_N[3];     /* [rad/s]   angular velocity of R rel. N, N comp. */
  fsw_real omega_dot_RN_N[3]; /* [rad/s^2] its inertial derivative, N components */
} FswAttRef;

typedef struct {
  fsw_real sigma_R0N[3]; /* [-] commanded inertial attitude (MRP), finite; any
                            magnitude (shadow-switched to |sigma| <= 1 by init) */
} FswGuidInertialConfig;

typedef struct {
  int ready;            /* [-] 1 after a successful init                     */
  fsw_real sigma_RN[3]; /* [-] sigma_R0N shadow-switched to |sigma| <= 1     */
  FswHealth health;     /* [-] call counters                                 */
} FswGuidInertialState;

/* The output is the reference message itself. */
typedef FswAttRef FswGuidInertialOut;

/* FSW_OK, or FSW_E_CONFIG (non-finite sigma_R0N), FSW_E_NULL_ARG. */
FswStatus fsw_guid_inertial_check(const FswGuidInertialConfig *cfg);
/* check, then store the switched sigma_R0N; ready = 1. */
FswStatus fsw_guid_inertial_init(FswGuidInertialState *st, const FswGuidInertialConfig *cfg);
/* No dynamic state: kept for the uniform module shape. */
void fsw_guid_inertial_reset(FswGuidInertialState *st);
/* Writes the reference.  There are no runtime inputs (docs/fsw/guid_inertial.md), so the
 * module has no In struct.  Returns FSW_OK, FSW_E_NOT_INIT (safe output) or
 * FSW_E_NULL_ARG. */
FswStatus fsw_guid_inertial_update(FswGuidInertialState *st, const FswGuidInertialConfig *cfg,
                                   FswGuidInertialOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_GUID_INERTIAL_H */

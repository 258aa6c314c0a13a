/* guid_sunsafe: sun-safe pointing guidance (docs/fsw/guid_sunsafe.md, Basilisk
 * sunSafePoint).
 * Outputs attitude and rate errors that turn body axis s_cmd toward the Sun
 * heading s_B, or a search spin omega_search_B when no Sun heading is valid
 * (|s_B| <= min_unit_mag).  The output is the guidance message FswAttGuid
 * (att_track.h), so it feeds mrp_fb directly (no att_track in between).
 * Stateless.  Frames: B body.  Units: SI, rad.
 * Safe output (bad input, init failed): guidance all 0, sun_angle_err 0,
 * sun_valid 0. */
#ifndef FSW_GUID_SUNSAFE_H
#define FSW_GUID_SUNSAFE_H

#include "fsw/att_track.h" /* FswAttGuid */
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Physical ranges accepted by check (no product of them can overflow). */
#define FSW_GUID_SUNSAFE_S_CMD_MAX FSW_R(10.0) /* [-]     largest |s_cmd_B|       */
#define FSW_GUID_SUNSAFE_RATE_MAX FSW_R(10.0)  /* [rad/s] largest |component| of
                                                  omega_search_B and |sun_axis_spin_rate| */

typedef struct {
  fsw_real s_cmd_B[3];         /* [-]     body axis to point at the Sun, finite,
                                          0.1 <= |s_cmd_B| <= FSW_GUID_SUNSAFE_S_CMD_MAX
                                          (normalised by init)                  */
  fsw_real min_unit_mag;       /* [-]     |s_B| above which the heading is valid,
                                          finite, >= 0                          */
  fsw_real small_angle;        /* [rad]   dead band on the Sun angle, finite,
                                          0 <= small_angle < pi/2               */
  fsw_real omega_search_B[3];  /* [rad/s] search rate without Sun, finite (0 ok),
                                          |component| <= FSW_GUID_SUNSAFE_RATE_MAX */
  fsw_real sun_axis_spin_rate; /* [rad/s] spin about the Sun heading, finite,
                                          |.| <= FSW_GUID_SUNSAFE_RATE_MAX      */
} FswGuidSunsafeConfig;

typedef struct {
  int ready;                /* [-] 1 after a successful init                   */
  fsw_real s_cmd_hat_B[3];  /* [-] unit(s_cmd_B), by init                      */
  fsw_real e180_hat_B[3];   /* [-] rotation axis used when s_B = -s_cmd, init  */
  FswHealth health;         /* [-] call counters                               */
} FswGuidSunsafeState;

typedef struct {
  fsw_real sun_B[3];      /* [-]     Sun heading, B components, need not be unit
                                     (e.g. css_sun output; 0 = no Sun)        */
  fsw_real omega_BN_B[3]; /* [rad/s] navigation body rate, B components       */
} FswGuidSunsafeIn;

typedef struct {
  FswAttGuid guid;        /* guidance message (omega_dot_RN_B is always 0)    */
  fsw_real sun_angle_err; /* [rad] angle between s_cmd and s_B, telemetry
                             (0 when the heading is not valid)               */
  int sun_valid;          /* [-] 1 if |s_B| > min_unit_mag on this call       */
} FswGuidSunsafeOut;

/* FSW_OK; FSW_E_CONFIG (non-finite field, |s_cmd_B| < 0.1, min_unit_mag < 0,
 * small_angle outside [0, pi/2)); FSW_E_NULL_ARG. */
FswStatus fsw_guid_sunsafe_check(const FswGuidSunsafeConfig *cfg);
/* check; s_cmd_hat = unit(s_cmd); e180 = unit(s_cmd_hat x [1,0,0]), or
 * unit(s_cmd_hat x [0,1,0]) if |s_cmd_hat x [1,0,0]| < 0.1. */
FswStatus fsw_guid_sunsafe_init(FswGuidSunsafeState *st, const FswGuidSunsafeConfig *cfg);
/* No dynamic state: kept for the uniform module shape. */
void fsw_guid_sunsafe_reset(FswGuidSunsafeState *st);
/* FSW_OK (valid heading or search mode; every output finite, |sigma_BR| <= 1;
 * any finite sun_B is used by direction only, so huge or tiny headings give
 * the same guidance as the unit heading); with the safe output:
 * FSW_E_BAD_INPUT (NaN/Inf input, or a rate output that overflows),
 * FSW_E_NOT_INIT, FSW_E_NULL_ARG. */
FswStatus fsw_guid_sunsafe_update(FswGuidSunsafeState *st, const FswGuidSunsafeConfig *cfg,
                                  const FswGuidSunsafeIn *in, FswGuidSunsafeOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_GUID_SUNSAFE_H */

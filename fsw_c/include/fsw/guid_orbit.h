/* guid_orbit: orbit-referenced attitude guidance (nadir or velocity
 * pointing) from the navigation position and velocity.
 * Orbit frame R (rows of [RN] in N components), h = r x v:
 *   NADIR:    R3 = -r_hat, R2 = -h_hat, R1 = R2 x R3 (along-track);
 *   VELOCITY: R1 = v_hat,  R2 = -h_hat, R3 = R1 x R2.
 * Rates, exact for two-body motion (h constant, a = -mu r/r^3):
 *   NADIR:    omega_RN = h/r^2,
 *             omega_dot_RN = -2 (r.v)/r^2 omega_RN;
 *   VELOCITY: omega_RN = (v x a)/v^2 = mu h/(r^3 v^2),
 *             omega_dot_RN = (r.v)/r^2 (2 mu/(r v^2) - 3) omega_RN.
 * The output is the reference of the desired body frame Bd, offset from R by
 * the fixed [BdR] = MRP2C(sigma_BdR): sigma_RN (the message field) holds
 * sigma_BdN of [BdN] = [BdR][RN]; omega and omega_dot are those of R (a
 * fixed offset does not change them), N components.
 * Stateless.  Frames: N inertial, R orbit, Bd desired body.  Units: SI, rad.
 * Safe output (bad input, not initialised): sigma = 0 (Bd = N), rates 0; the
 * application holds its previous reference on an error status instead of
 * tracking it. */
#ifndef FSW_GUID_ORBIT_H
#define FSW_GUID_ORBIT_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/guid_inertial.h" /* FswAttRef */

#ifdef __cplusplus
extern "C" {
#endif

#define FSW_GUID_ORBIT_NADIR 0
#define FSW_GUID_ORBIT_VELOCITY 1

/* Largest gravitational parameter accepted (the Sun is 1.327e20). */
#define FSW_GUID_ORBIT_MU_MAX FSW_R(1e21) /* [m^3/s^2] */
/* Smallest orbit radius accepted at run time. */
#define FSW_GUID_ORBIT_R_MIN FSW_R(1.0) /* [m] */
/* r and v count as parallel (h = 0, the frame undefined) when the sine of
 * the angle between them is at or below this. */
#if FSW_USE_FLOAT
#define FSW_GUID_ORBIT_SIN_MIN FSW_R(1e-4)
#else
#define FSW_GUID_ORBIT_SIN_MIN 1e-8
#endif

typedef struct {
  int variant;           /* [-]         FSW_GUID_ORBIT_NADIR or _VELOCITY            */
  fsw_real sigma_BdR[3]; /* [-]         MRP of the desired body frame relative to R,
                                        finite (any magnitude; 0 = aligned with R)   */
  fsw_real mu;           /* [m^3/s^2]   gravitational parameter, 0 < mu <=
                                        FSW_GUID_ORBIT_MU_MAX (read by VELOCITY)     */
} FswGuidOrbitConfig;

typedef struct {
  int ready;                /* [-] 1 after a successful init                    */
  fsw_real dcm_BdR[3][3];   /* [-] MRP2C(sigma_BdR), derived once by init        */
  FswHealth health;         /* [-] call counters                                */
} FswGuidOrbitState;

typedef struct {
  fsw_real r_N[3]; /* [m]   position of the spacecraft rel. the central body, N */
  fsw_real v_N[3]; /* [m/s] its inertial velocity, N components                  */
  uint8_t valid;   /* [-]   1: r_N, v_N are a valid navigation solution; 0 not   */
} FswGuidOrbitIn;

/* The output is the reference message itself (sigma_RN holds sigma_BdN). */
typedef FswAttRef FswGuidOrbitOut;

/* FSW_OK; FSW_E_CONFIG (variant, non-finite sigma_BdR, mu out of range). */
FswStatus fsw_guid_orbit_check(const FswGuidOrbitConfig *cfg);
FswStatus fsw_guid_orbit_init(FswGuidOrbitState *st, const FswGuidOrbitConfig *cfg);
/* No dynamic state: kept for the uniform module shape. */
void fsw_guid_orbit_reset(FswGuidOrbitState *st);
/* FSW_OK (|sigma| <= 1, rates finite).  With the safe output:
 * FSW_E_BAD_INPUT for valid != 1, non-finite r_N or v_N, |r| <
 * FSW_GUID_ORBIT_R_MIN, v = 0, r parallel to v (sine of their angle <=
 * FSW_GUID_ORBIT_SIN_MIN), or finite inputs whose rates overflow;
 * FSW_E_NOT_INIT; FSW_E_NULL_ARG. */
FswStatus fsw_guid_orbit_update(FswGuidOrbitState *st, const FswGuidOrbitConfig *cfg,
                                const FswGuidOrbitIn *in, FswGuidOrbitOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_GUID_ORBIT_H */

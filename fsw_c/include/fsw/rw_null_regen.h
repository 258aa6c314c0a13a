/* rw_null_regen: regenerative power-optimal null motion
 * (docs/fsw/rw_null_regen.md, after Blenden & Schaub 2012).  Moves the mapped torques u0 along the
 * null space of [Gs_a] to lower the total mechanical power P = Omega^T u
 * (negative P returns energy to the bus) without changing the body torque:
 *   FSW_RW_REGEN_GRADIENT  u = u0 - kappa k_P [tau] Omega   (any wheel count;
 *                          kappa in [0,1] scale-to-fit against u_max, so
 *                          dP = -kappa k_P |[tau] Omega|^2 <= 0)
 *   FSW_RW_REGEN_OPTIMUM   nullity 1 only: u = u0 + alpha n with alpha at the
 *                          end of the admissible interval that minimises P
 *                          (the LP optimum is bang-bang: a wheel sits at
 *                          its limit).  Nullity 0: u = u0.  Nullity > 1:
 *                          FSW_E_UNSUPPORTED with u = u0.
 * Unavailable wheels get exactly 0.  Frames: B.  Units: SI.
 * Safe output: u = 0 for bad input / not initialised; u = u0 (the mapped
 * torques passed through) for FSW_E_UNSUPPORTED and an empty interval. */
#ifndef FSW_RW_NULL_REGEN_H
#define FSW_RW_NULL_REGEN_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/rw_common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  FSW_RW_REGEN_GRADIENT = 0, /* default of a zeroed config */
  FSW_RW_REGEN_OPTIMUM = 1
} FswRwRegenMode;

typedef struct {
  int num_rw;                       /* [-]        1..FSW_MAX_RW                  */
  fsw_real gs_hat_B[FSW_MAX_RW][3]; /* [-]        (num_rw) spin axes, unit, B    */
  int mode;                         /* [-]        FswRwRegenMode                 */
  fsw_real k_P;                     /* [N*m*s/rad] GRADIENT gain, > 0, <=
                                       FSW_RW_GAIN_MAX (unused by OPTIMUM)       */
  fsw_real u_max[FSW_MAX_RW];       /* [N*m]      (num_rw) torque limits,
                                       FSW_RW_U_MAX_MIN..FSW_RW_U_MAX_MAX        */
} FswRwNullRegenConfig;

typedef struct {
  int ready;
  FswRwNullProj proj; /* [Gs], projector, mask (~11 KiB) */
  FswHealth health;
} FswRwNullRegenState;

typedef struct {
  fsw_real u_s[FSW_MAX_RW];   /* [N*m]   (num_rw) u0 from rw_map (4 or 5)        */
  fsw_real Omega[FSW_MAX_RW]; /* [rad/s] (num_rw) wheel speeds relative to body */
  uint8_t avail[FSW_MAX_RW];  /* [-]     (num_rw) 0 available, 1 unavailable     */
} FswRwNullRegenIn;

typedef struct {
  fsw_real u_s[FSW_MAX_RW]; /* [N*m] (num_rw) torques; 0 beyond num_rw     */
  fsw_real power;           /* [W]   Omega^T u of the output (avail. wheels) */
} FswRwNullRegenOut;

FswStatus fsw_rw_null_regen_check(const FswRwNullRegenConfig *cfg);
FswStatus fsw_rw_null_regen_init(FswRwNullRegenState *st, const FswRwNullRegenConfig *cfg);
void fsw_rw_null_regen_reset(FswRwNullRegenState *st);
/* FSW_OK; FSW_W_SAT (GRADIENT: null step reduced to fit the limits; OPTIMUM:
 * no alpha keeps every wheel inside its limit, u = u0); FSW_W_SINGULAR (u =
 * u0) when the step would move the body torque by more than FSW_NULL_TOL of
 * its size (fsw_rw_null_change_ok, rw_common.h); FSW_E_UNSUPPORTED
 * (OPTIMUM with nullity > 1, u = u0, projector untouched); FSW_E_BAD_INPUT
 * (u = 0, power = 0, projector untouched) for non-finite u_s, an Omega of an
 * available wheel beyond +-FSW_RW_OMEGA_MAX (rw_common.h) or not finite, a
 * mask entry other than 0/1, or finite values so large that the step or
 * the power overflows;
 * FSW_E_NOT_INIT.  u and power are finite under every status. */
FswStatus fsw_rw_null_regen_update(FswRwNullRegenState *st, const FswRwNullRegenConfig *cfg,
                                   const FswRwNullRegenIn *in, FswRwNullRegenOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_NULL_REGEN_H */

/* rw_null: reaction-wheel null motion (docs/fsw/rw_null.md, Basilisk
 * rwNullSpace).  Adds wheel torques in the null space of [Gs_a] (available
 * wheels) so the body torque is unchanged while wheel speeds move toward
 * Omega_des:  u = u_c + kappa [tau] d,  d = -K_Omega (Omega - Omega_des).
 * [tau] comes from K2 (true projector for any rank, also for coplanar sets)
 * and is recomputed whenever the availability mask changes.  With
 * scale_to_fit, kappa in [0,1] is the largest step that keeps every
 * |u_i| <= u_max_i (kappa = 0 if u_c already violates a limit); otherwise
 * kappa = 1.  Unavailable wheels get exactly 0.
 * Frames: B.  Units: SI.
 * Safe output (bad input, not initialised): u_s = 0 for every wheel. */
#ifndef FSW_RW_NULL_H
#define FSW_RW_NULL_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/rw_common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  int num_rw;                       /* [-]       1..FSW_MAX_RW                   */
  fsw_real gs_hat_B[FSW_MAX_RW][3]; /* [-]       (num_rw) spin axes, unit, B     */
  fsw_real k_null;                  /* [N*m*s]   K_Omega speed-error gain,
                                       > 0, <= FSW_RW_GAIN_MAX (rw_common.h)   */
  int scale_to_fit;                 /* [-]       0 (Basilisk parity) or 1        */
  fsw_real u_max[FSW_MAX_RW];       /* [N*m]     (num_rw) torque limits,
                                       FSW_RW_U_MAX_MIN..FSW_RW_U_MAX_MAX; read
                                       only when scale_to_fit = 1               */
} FswRwNullConfig;

typedef struct {
  int ready;          /* 1 after a successful init */
  FswRwNullProj proj; /* [Gs], projector and the mask it belongs to (~11 KiB) */
  FswHealth health;
} FswRwNullState;

typedef struct {
  fsw_real u_s[FSW_MAX_RW];       /* [N*m]   (num_rw) torques from rw_map        */
  fsw_real Omega[FSW_MAX_RW];     /* [rad/s] (num_rw) measured speeds rel. body */
  fsw_real Omega_des[FSW_MAX_RW]; /* [rad/s] (num_rw) desired speeds (0 = despin) */
  uint8_t avail[FSW_MAX_RW];      /* [-]     (num_rw) 0 available, 1 unavailable */
} FswRwNullIn;

typedef struct {
  fsw_real u_s[FSW_MAX_RW]; /* [N*m] (num_rw) torques; 0 beyond num_rw */
  fsw_real kappa;           /* [-]   fraction of the null torque applied */
} FswRwNullOut;

/* FSW_OK, FSW_E_CAPACITY (num_rw), FSW_E_CONFIG (axes, gain, limits). */
FswStatus fsw_rw_null_check(const FswRwNullConfig *cfg);
FswStatus fsw_rw_null_init(FswRwNullState *st, const FswRwNullConfig *cfg);
/* Stateless apart from the projector cache, which reset keeps. */
void fsw_rw_null_reset(FswRwNullState *st);
/* FSW_OK (u finite, kappa = 1); FSW_W_SAT when scale_to_fit reduced the
 * null torque (kappa < 1); FSW_W_SINGULAR (u = u_c, kappa = 0) when the
 * null step would move the body torque by more than FSW_NULL_TOL of its size
 * (near-duplicate or near-coplanar axes: fsw_rw_null_change_ok); FSW_E_BAD_INPUT (u = 0, kappa = 0, projector
 * untouched) for non-finite u_s, an Omega or Omega_des of an available
 * wheel beyond +-FSW_RW_OMEGA_MAX (rw_common.h) or not finite, a mask entry
 * other than 0/1, or finite values so large that the null torque overflows;
 * FSW_E_NOT_INIT. */
FswStatus fsw_rw_null_update(FswRwNullState *st, const FswRwNullConfig *cfg,
                             const FswRwNullIn *in, FswRwNullOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_NULL_H */

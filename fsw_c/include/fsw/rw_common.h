/* rw_common: pieces shared by the reaction-wheel modules (rw_map, rw_null,
 * rw_null_regen, rw_sat, rw_volt, rw_speed_filter): wheel-geometry and
 * availability-mask checks, the cached null-space projector of [Gs] over the
 * available wheels (docs/fsw/rw_null.md, K2) and the scale-to-fit rule for a
 * torque increment that must not push a wheel past its limit (6.1, 6.2).
 * Frames: B.  Units: SI.  No module keeps any of this outside its own state. */
#ifndef FSW_RW_COMMON_H
#define FSW_RW_COMMON_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Tolerances of configured axes: |g| = 1 within FSW_RW_UNIT_TOL, control
 * axes orthogonal within FSW_RW_ORTHO_TOL (docs/fsw/rw_map.md: 1e-9 and
 * 1e-6; single precision cannot hold 1e-9, so the float build uses 1e-6 and
 * 1e-5). */
#if FSW_USE_FLOAT
#define FSW_RW_UNIT_TOL FSW_R(1e-6)
#define FSW_RW_ORTHO_TOL FSW_R(1e-5)
#else
#define FSW_RW_UNIT_TOL 1e-9
#define FSW_RW_ORTHO_TOL 1e-6
#endif

/* Validate a wheel set: num_rw in [min_rw, FSW_MAX_RW] (else FSW_E_CAPACITY),
 * every gs_hat_B[i] finite and of unit length within FSW_RW_UNIT_TOL (else
 * FSW_E_CONFIG). */
FswStatus fsw_rw_check_axes(const fsw_real gs_hat_B[FSW_MAX_RW][3], int num_rw, int min_rw);

/* Physical ranges of the wheel configuration values accepted by the
 * modules' check: wide enough for any wheel from CubeSat to CMG, narrow
 * enough that no product or ratio of accepted values overflows either real
 * type (u_max ratios stay <= 1e13, gains times inertias <= 1e10). */
#define FSW_RW_U_MAX_MIN FSW_R(1e-9) /* [N*m]       smallest torque limit */
#define FSW_RW_U_MAX_MAX FSW_R(1e4)  /* [N*m]       largest torque limit  */
#define FSW_RW_J_S_MAX FSW_R(1e4)    /* [kg*m^2]    largest spin inertia  */
#define FSW_RW_GAIN_MAX FSW_R(1e6)   /* [-, N*m*s]  largest gain (k_null, k_P, K_V) */
#define FSW_RW_V_MAX_MAX FSW_R(1e4)  /* [V]         largest V_max         */
/* Largest wheel speed (and desired speed) the null-motion modules accept at
 * run time: 1e4 rad/s (~95,000 rpm, above any flywheel flown).  Beyond it a
 * speed is bad input: a huge finite speed error makes a null step whose
 * round-off alone (eps times the speed error) can exceed the real step and,
 * scaled to the torque limits, leak into body torque. */
#define FSW_RW_OMEGA_MAX FSW_R(1e4) /* [rad/s] */

/* 1 when v[0..n-1] are all finite and > 0. */
int fsw_rw_all_positive(const fsw_real *v, int n);

/* 1 when v[0..n-1] are all finite, > 0 and within [lo, hi]. */
int fsw_rw_all_in_range(const fsw_real *v, int n, fsw_real lo, fsw_real hi);

/* 1 when every avail[0..n-1] is FSW_AVAILABLE or FSW_UNAVAILABLE. */
int fsw_rw_avail_valid(const uint8_t avail[FSW_MAX_RW], int n);
/* 1 if x[i] is finite for every AVAILABLE wheel i < n (entries of
 * unavailable wheels are not read: a failed tachometer on a wheel already
 * taken out of service must not stop the chain).  avail must be valid. */
int fsw_rw_avail_finite(const fsw_real *x, const uint8_t avail[FSW_MAX_RW], int n);

/* 1 if x[i] is finite and |x[i]| <= FSW_RW_OMEGA_MAX for every AVAILABLE
 * wheel i < n (entries of unavailable wheels are not read). */
int fsw_rw_avail_speed_ok(const fsw_real *x, const uint8_t avail[FSW_MAX_RW], int n);

/* h_B = sum over the AVAILABLE wheels i < n of J_s[i] Omega[i] gs_hat_B[i]:
 * the wheels' momentum relative to the body, B [N*m*s] (entries of
 * unavailable wheels are not read).  avail must be valid. */
void fsw_rw_momentum(fsw_real h_B[3], const fsw_real gs_hat_B[FSW_MAX_RW][3], const fsw_real *J_s,
                     const fsw_real *Omega, const uint8_t avail[FSW_MAX_RW], int n);

/* Zero all FSW_MAX_RW entries (the safe torque/voltage output). */
void fsw_rw_zero(fsw_real u[FSW_MAX_RW]);

/* Null-space projector of [Gs] restricted to the available wheels, cached
 * for the mask it was computed with.  ~10.7 KiB in double at FSW_MAX_EFF=36:
 * it lives in the caller-owned module state, never on the stack. */
typedef struct {
  fsw_real G[3][FSW_MAX_EFF];             /* [-] [Gs] = [g_1 ... g_N], 3 x num_rw */
  fsw_real tau[FSW_MAX_EFF][FSW_MAX_EFF]; /* [-] (num_rw x num_rw) projector onto
                                             null([Gs_a]); rows/columns of
                                             unavailable wheels are exactly 0 */
  uint8_t avail[FSW_MAX_RW];              /* [-] mask tau was computed for */
  int num_rw;                             /* [-] wheels in G */
  int num_avail;                          /* [-] available wheels in the mask */
  int rank;                               /* [-] rank of [Gs_a], 0..3 */
} FswRwNullProj;

/* Fill G from the (already checked) axes and compute tau for "all
 * available". */
void fsw_rw_proj_init(FswRwNullProj *p, const fsw_real gs_hat_B[FSW_MAX_RW][3], int num_rw);

/* Recompute tau when `avail` (validated by the caller; NULL = all available)
 * differs from the mask tau was computed for.  Returns 1 if recomputed. */
int fsw_rw_proj_refresh(FswRwNullProj *p, const uint8_t avail[FSW_MAX_RW]);

/* out = [tau]([tau] d) (n = p->num_rw entries).  [tau] is idempotent; the
 * second product removes the round-off of the first (~eps |d|, which leaks
 * into the body torque when d lies mostly in the row space of [Gs]), so the
 * leak is ~eps |out|.  out must not alias d. */
void fsw_rw_proj_apply(fsw_real *out, const FswRwNullProj *p, const fsw_real *d);

/* 1 when the change u - u0 (n wheels) moves the body torque by at most
 * FSW_NULL_TOL times its own size: |[Gs](u - u0)| <= FSW_NULL_TOL *
 * sum_i |u_i - u0_i| (the axes are unit vectors, so the right side bounds
 * the torque a change of that size could make).  A null step that fails
 * this is not in the null space to working precision (near-duplicate or
 * near-coplanar axes make the projector ill-conditioned): the modules then
 * drop it and return FSW_W_SINGULAR with u = u0. */
int fsw_rw_null_change_ok(const FswRwNullProj *p, const fsw_real *u, const fsw_real *u0, int n);

/* out = u_c + kappa * du with the largest kappa in [0, 1] such that
 * |out_i| <= u_max_i for every i < n (docs/fsw/rw_null.md scaleNullToFit):
 * kappa = min(1, min over du_i != 0 of the admissible step); kappa = 0 when
 * u_c already violates a limit.  The result is clamped to the limits to
 * remove the last rounding (a change of a few ulp).  `u_max` NULL means no
 * limits (kappa = 1).  Returns kappa.  out may alias u_c. */
fsw_real fsw_rw_add_scaled_to_fit(fsw_real *out, const fsw_real *u_c, const fsw_real *du,
                                  const fsw_real *u_max, int n);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_COMMON_H */

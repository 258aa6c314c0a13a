/* rw_map: reaction-wheel torque mapping (docs/fsw/rw_map.md).
 * Turns the control torque Lr (the torque the wheels must put on the body)
 * into wheel motor torques u_s with [C][Gs_a] u_s,a = -[C] Lr over the
 * available wheels a, choosing among all solutions either
 *   FSW_RW_MAP_MIN_NORM  the minimum Euclidean norm (Basilisk rwMotorTorque), or
 *   FSW_RW_MAP_POWER     the minimum of sum W_i u_i^2, W_i = Omega_i^2 + eps_P
 *                        (L2 power-optimal, Schaub & Lappas 2009, with the
 *                        library's named regularisation eps_P).
 * No saturation is applied here (rw_sat).  Stateless apart from health.
 * Frames: B.  Units: SI.
 * Safe output: u_s = 0 for every wheel. */
#ifndef FSW_RW_MAP_H
#define FSW_RW_MAP_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_linalg.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  FSW_RW_MAP_MIN_NORM = 0, /* minimum norm (default of a zeroed config) */
  FSW_RW_MAP_POWER = 1     /* L2 power-optimal */
} FswRwMapMode;

/* Default eps_P of docs/fsw/rw_map.md [rad^2/s^2]. */
#define FSW_RW_MAP_EPS_P_DEFAULT FSW_R(1.0)
/* Accepted range of eps_P [rad^2/s^2]: 1/eps_P and Omega^2 + eps_P stay far
 * inside the range of either real type (a denormal eps_P made 1/W infinite
 * and every POWER update a bad input). */
#define FSW_RW_MAP_EPS_P_MIN FSW_R(1e-9)
#define FSW_RW_MAP_EPS_P_MAX FSW_R(1e9)

typedef struct {
  int num_rw;                       /* [-]     1..FSW_MAX_RW                       */
  fsw_real gs_hat_B[FSW_MAX_RW][3]; /* [-]     (num_rw) spin axes, unit, B         */
  int num_axes;                     /* [-]     nc, 0..3 controlled axes (0: u = 0) */
  fsw_real ctrl_axes_B[3][3];       /* [-]     (num_axes) rows c_j: unit within
                                       FSW_RW_UNIT_TOL, mutually orthogonal within
                                       FSW_RW_ORTHO_TOL                           */
  int mode;                         /* [-]     FswRwMapMode                        */
  fsw_real eps_P;                   /* [rad^2/s^2] POWER only: FSW_RW_MAP_EPS_P_MIN
                                       ..FSW_RW_MAP_EPS_P_MAX                       */
} FswRwMapConfig;

typedef struct {
  /* scratch of one update, kept here so that the update's own stack stays
   * small (flight stack budget): [C][Gs_a] diag(sqrt(y)), solutions, the
   * available-wheel indices and their sqrt(y), and K1's factor of A (one
   * factorisation for the solve and its refinement step) */
  fsw_real A[3][FSW_MAX_EFF];
  fsw_real x[FSW_MAX_EFF], dx[FSW_MAX_EFF];
  fsw_real sy[FSW_MAX_RW];
  int idx[FSW_MAX_RW];
  FswMinnormFactor k1;
  /* MIN_NORM only: A depends on the mask alone (sqrt(y) = 1), so A, idx,
   * na, the geometric verdict and k1 are kept for the mask of the last
   * update and reused while the mask is the same.  Never a different
   * output: with mn_valid = 0 or another mask they are formed anew, and
   * they are a function of the config (fixed after init) and the mask
   * alone.  init and reset clear mn_valid. */
  int mn_valid;                 /* [-] 1: the members below hold mn_avail */
  uint8_t mn_avail[FSW_MAX_RW]; /* [-] (num_rw) the mask they were formed for */
  int mn_na;                    /* [-] available wheels of that mask */
  FswStatus mn_geo;             /* FSW_OK, or FSW_W_SINGULAR: too few wheels or
                                   no control axis reachable (the floor) */
} FswRwMapWork;

typedef struct {
  int ready;         /* 1 after a successful init */
  FswRwMapWork work; /* scratch, see above */
  FswHealth health;  /* counters read by the harness */
} FswRwMapState;

typedef struct {
  fsw_real Lr_B[3];           /* [N*m]   torque the wheels must apply to the body */
  fsw_real Omega[FSW_MAX_RW]; /* [rad/s] (num_rw) wheel speeds rel. body (POWER) */
  uint8_t avail[FSW_MAX_RW];  /* [-]     (num_rw) FSW_AVAILABLE (0) / FSW_UNAVAILABLE (1);
                                 all zero = all available                      */
} FswRwMapIn;

typedef struct {
  fsw_real u_s[FSW_MAX_RW]; /* [N*m] (num_rw) motor torques; 0 beyond num_rw */
} FswRwMapOut;

/* FSW_OK, FSW_E_CAPACITY (num_rw), FSW_E_CONFIG (axes, mode, eps_P). */
FswStatus fsw_rw_map_check(const FswRwMapConfig *cfg);
FswStatus fsw_rw_map_init(FswRwMapState *st, const FswRwMapConfig *cfg);
void fsw_rw_map_reset(FswRwMapState *st);
/* FSW_OK: u finite and [C][Gs] u = -[C] Lr within FSW_RESID_TOL relative
 * (in practice ~1e-15); FSW_W_SINGULAR (u = 0) when the available wheels
 * cannot produce torque about every control axis (fewer than nc available;
 * every entry of the dimensionless [C][Gs_a] at rounding level: the largest
 * row's sum of squares <= FSW_RANK_TOL; or [C][Gs_a] rank deficient by the
 * K1 test: pivot floor or delivered residual, fsw_linalg.h); FSW_E_BAD_INPUT (u = 0) for non-finite Lr,
 * non-finite Omega in POWER mode, a mask entry other than 0/1, or a finite
 * Lr so large that -[C] Lr or u overflows; FSW_E_NOT_INIT.  Stateless: no
 * status changes anything but the health counters and the scratch. */
FswStatus fsw_rw_map_update(FswRwMapState *st, const FswRwMapConfig *cfg,
                            const FswRwMapIn *in, FswRwMapOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_MAP_H */

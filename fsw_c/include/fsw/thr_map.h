/* thr_map: thruster force mapping (docs/fsw/thr_map.md, Basilisk
 * thrForceMapping).  Maps the requested control torque Lr onto per-thruster
 * forces for 1-3 control axes.  Frames: B.  Units: SI.
 *
 * Two modes:
 *  - FSW_THR_MAP_MIN_NORM (default, Basilisk parity): minimum-norm solve, the
 *    min-shift of on-pulsing thrusters, the optional second pass and the
 *    saturation scaling (docs/fsw/thr_map.md).  Assumes the thrusters form pure couples;
 *    with a CoM offset or a failed thruster the delivered torque is wrong
 *    (docs/fsw/thr_map.md, "Differences from Basilisk").
 *  - FSW_THR_MAP_NNLS (opt-in, docs/fsw/thr_map.md "NNLS mode"): minimum ||F|| subject to [C][D]F = Lbar
 *    (least squares when no admissible F exists) and the thruster limits,
 *    by a deterministic bounded-variable active-set method.  Delivers the
 *    requested torque whenever the thrusters can.  A build with
 *    FSW_CFG_THR_NNLS = 0 (fsw_config.h) does not have it: check and init
 *    refuse the mode with FSW_E_UNSUPPORTED and update returns
 *    FSW_E_UNSUPPORTED with the safe output for a configuration changed to
 *    it after init.
 *
 * Output F: on-pulsing (thr_force_sign = +1) the commanded force of each
 * thruster, >= 0; off-pulsing (thr_force_sign = -1, DV thrusters nominally
 * on at F_max) the force change from full thrust, <= 0 in normal use.
 *
 * Safe output: F = 0 for every entry (no state is advanced: the module has
 * no dynamic state).  Entries at and beyond num_thr are always exactly 0. */
#ifndef FSW_THR_MAP_H
#define FSW_THR_MAP_H

#include <stdint.h>

#include "fsw/fsw_config.h" /* FSW_MAX_THR, FSW_MAX_EFF, fsw_real */
#include "fsw/fsw_status.h" /* FswStatus, FswHealth */

#ifdef __cplusplus
extern "C" {
#endif

/* Physical ranges accepted by check (and, for r_CoM_B, by update): with
 * them every intermediate of the mapping ([D], [C][D], the off-pulsing
 * offset, K1/K4) stays far inside the range of either real type. */
#define FSW_THR_MAP_R_MAX FSW_R(1e3)    /* [m] |component| of r_thr_B, r_CoM_B   */
#define FSW_THR_MAP_F_MAX FSW_R(1e6)    /* [N] largest F_max                     */
#define FSW_THR_MAP_AXIS_MAX FSW_R(1e3) /* [-] |component| of control_axes_B     */

/* Mapping algorithm (FswThrMapConfig.mode). */
typedef enum {
  FSW_THR_MAP_MIN_NORM = 0, /* Basilisk thrForceMapping, default             */
  FSW_THR_MAP_NNLS = 1      /* exact bounded solve, opt-in                   */
} FswThrMapMode;

typedef struct {
  /* [-] (3 rows) control axes, B components.  Rows are counted in order up
   * to the first whose norm is <= epsilon (0 counted rows is an error) and
   * normalised by init; the counted rows must be linearly independent, and
   * none so short that 1/norm overflows (FSW_E_CONFIG). */
  fsw_real control_axes_B[3][3];
  int num_thr;                         /* [-]   1..FSW_MAX_THR                */
  fsw_real r_thr_B[FSW_MAX_THR][3];    /* [m]   (num_thr) thruster locations,
                                          |component| <= FSW_THR_MAP_R_MAX   */
  fsw_real gt_hat_B[FSW_MAX_THR][3];   /* [-]   (num_thr) unit force axes     */
  fsw_real F_max[FSW_MAX_THR];         /* [N]   (num_thr) max thrust,
                                          0 < F_max <= FSW_THR_MAP_F_MAX     */
  int thr_force_sign;                  /* [-]   +1 on-pulsing RCS, -1 off-pulsing DV */
  fsw_real ang_err_thresh;             /* [rad] >= 0; scaling when the torque angle
                                          error exceeds it; > pi disables scaling */
  fsw_real epsilon;                    /* [N*m] >= 0; |Lbar| <= epsilon counts as
                                          zero request (Basilisk default 0)  */
  int use_2nd_loop;                    /* [-]   0/1: second pass for on-pulsing */
  int mode;                            /* [-]   FswThrMapMode                  */
} FswThrMapConfig;

/* Scratch matrices of one update (kept here, not on the stack, so every
 * public function stays well below the 4 KiB stack budget).  They carry no
 * meaning between calls. */
typedef struct {
  fsw_real D_B[3][FSW_MAX_EFF];  /* [m] torque arms d_i as columns, B     */
  fsw_real CD[3][FSW_MAX_EFF];   /* [m] [C][D], control-axis rows          */
  fsw_real CD_S[3][FSW_MAX_EFF]; /* [m] second-pass columns                */
  fsw_real F[FSW_MAX_EFF];       /* [N] forces being computed              */
  fsw_real Fbar[FSW_MAX_EFF];    /* [N] second-pass forces                 */
  fsw_real lo[FSW_MAX_EFF];      /* [N] NNLS lower bounds                  */
  fsw_real hi[FSW_MAX_EFF];      /* [N] NNLS upper bounds                  */
} FswThrMapWork;

typedef struct {
  int ready;                /* [-] 1 once init accepted the config          */
  int num_axes;             /* [-] counted control axes nc (1..3), by init  */
  fsw_real C[3][3];         /* [-] normalised control axes (nc rows), by init */
  fsw_real gt_norm[FSW_MAX_THR]; /* [-] |gt_hat_B[i]| (num_thr), by init      */
  fsw_real ang_err;         /* [rad] torque angle error of the last update
                               (min-norm mode), 0 otherwise                 */
  int nnls_iter;            /* [-] active-set iterations of the last update */
  FswThrMapWork work;       /* scratch, see above                           */
  FswHealth health;         /* counters read by the harness                 */
} FswThrMapState;

typedef struct {
  fsw_real Lr_B[3];    /* [N*m] requested external control torque, B        */
  fsw_real r_CoM_B[3]; /* [m]   centre of mass location, B, |component| <=
                          FSW_THR_MAP_R_MAX (else FSW_E_BAD_INPUT)          */
  uint8_t avail[FSW_MAX_THR]; /* [-] (num_thr) 0 available, 1 unavailable (a
                          thruster flagged failed: it is mapped as absent,
                          its torque arm taken out of [D] and, off-pulsing,
                          its nominal torque out of the offset; its command
                          is "off": F = 0 on-pulsing, -F_max off-pulsing) */
} FswThrMapIn;

typedef struct {
  fsw_real F[FSW_MAX_THR]; /* [N] (num_thr) force command, see above; rest 0 */
} FswThrMapOut;

/* Validate the configuration.  FSW_E_CAPACITY: num_thr > FSW_MAX_THR;
 * FSW_E_SINGULAR: the counted control axes are linearly dependent;
 * FSW_E_UNSUPPORTED: mode FSW_THR_MAP_NNLS in a build without it
 * (FSW_CFG_THR_NNLS = 0); FSW_E_CONFIG: anything else out of range or
 * non-finite. */
FswStatus fsw_thr_map_check(const FswThrMapConfig *cfg);
/* check, then normalise the control axes, clear health, reset. */
FswStatus fsw_thr_map_init(FswThrMapState *st, const FswThrMapConfig *cfg);
/* No dynamic state: clears the last-update diagnostics only. */
void fsw_thr_map_reset(FswThrMapState *st);
/* Returns FSW_OK (F finite; NNLS: [C][D] F = [C] Lr within 1e4 eps
 * relative; min-norm: the solve met the K1 rank and residual tests);
 * FSW_W_SAT (min-norm: forces were scaled down; NNLS: the request is out of
 * reach, e.g. a reduced-axis (rank-deficient) set, and the least-squares
 * torque is delivered); FSW_W_SINGULAR (either mode: no torque arm reaches
 * any control axis beyond rounding, i.e. the largest over axes c_j of
 * sum_i (c_j . (r_i - r_CoM) x g_i / (|r_i - r_CoM| |g_i|))^2 is
 * <= FSW_RANK_TOL; min-norm also: rank-deficient [C][D] by the K1 test,
 * pivot floor or delivered residual, fsw_linalg.h; F = 0, a thruster
 * flagged unavailable keeping its off command);
 * FSW_E_BAD_INPUT (NaN/Inf input, r_CoM_B out of range, an avail entry not
 * 0/1, or a finite request
 * so large that the forces overflow; F = 0); FSW_E_NOT_INIT;
 * FSW_E_UNSUPPORTED (mode FSW_THR_MAP_NNLS, built without it; F = 0);
 * FSW_E_NULL_ARG.  OK and warnings change the diagnostics (ang_err,
 * nnls_iter); every status may change the scratch and the health counters,
 * nothing else. */
FswStatus fsw_thr_map_update(FswThrMapState *st, const FswThrMapConfig *cfg,
                             const FswThrMapIn *in, FswThrMapOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_THR_MAP_H */

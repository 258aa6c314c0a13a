/* mtq_desat: reaction-wheel momentum desaturation by magnetorquers
 * (cross-product law).
 *
 *   h_w      = sum over available wheels of J_s_i Omega_i gs_hat_i   (B)
 *   h_err    = h_w - h_target
 *   tau_req  = -k_desat h_err_perp,   h_err_perp = h_err - (h_err . b) b,
 *   m_B      = (k_desat / |B|^2) (h_err x B) = (k_desat / |B|) (h_err x b)
 * with b = B/|B|.  m_B x B = -k_desat h_err_perp = tau_req exactly
 * ((h x B) x B = (h . B) B - |B|^2 h), so tau_req is the part of the wanted
 * external torque -k_desat h_err that a dipole can make; the part along B
 * cannot be made this cycle.  When |tau_req| > tau_max both tau_req and m_B
 * are multiplied by scale = tau_max/|tau_req| (direction kept, W_SAT).
 * When |h_err| <= h_deadband there is no request (tau_req = m_B = 0).
 *
 * Use: hand tau_req_B to mtq_map in torque mode (or m_B in dipole mode) and
 * add -tau_ach_B (mtq_map's achieved magnetic torque) to the body torque the
 * wheels are asked for, so the attitude holds while the magnetic torque
 * changes the wheel momentum: d(h_err)/dt = tau_ach = -k_desat h_err_perp
 * (time constant 1/k_desat per axis perpendicular to B; over an orbit B
 * turns, so every axis unloads).  See docs/fsw/mtq_desat.md for tuning.
 * Stateless apart from the health counters.  Frames: B.  Units: SI.
 * Safe output (errors, not initialised): every output 0. */
#ifndef FSW_MTQ_DESAT_H
#define FSW_MTQ_DESAT_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FSW_MTQ_DESAT_K_MAX FSW_R(1e3)   /* [1/s]   largest k_desat                      */
#define FSW_MTQ_DESAT_H_MAX FSW_R(1e8)   /* [N*m*s] largest |h_target_B| component and
                                            h_deadband (J_s max x Omega max, rw_common.h) */
#define FSW_MTQ_DESAT_TAU_MIN FSW_R(1e-9) /* [N*m]  smallest tau_max                     */
#define FSW_MTQ_DESAT_TAU_MAX FSW_R(1e4)  /* [N*m]  largest tau_max                      */

typedef struct {
  int num_rw;                       /* [-]       1..FSW_MAX_RW                          */
  fsw_real gs_hat_B[FSW_MAX_RW][3]; /* [-]       (num_rw) spin axes, unit, B            */
  fsw_real J_s[FSW_MAX_RW];         /* [kg*m^2]  (num_rw) spin inertias, > 0,
                                       <= FSW_RW_J_S_MAX (rw_common.h)                 */
  fsw_real k_desat;                 /* [1/s]     desaturation gain, (0, FSW_MTQ_DESAT_K_MAX] */
  fsw_real h_target_B[3];           /* [N*m*s]   wheel momentum to hold (0 or a bias), B,
                                       components within +-FSW_MTQ_DESAT_H_MAX        */
  fsw_real tau_max;                 /* [N*m]     limit on |tau_req_B|,
                                       FSW_MTQ_DESAT_TAU_MIN..FSW_MTQ_DESAT_TAU_MAX    */
  fsw_real h_deadband;              /* [N*m*s]   no request while |h_err| <= it,
                                       0..FSW_MTQ_DESAT_H_MAX                          */
} FswMtqDesatConfig;

typedef struct {
  int ready; /* 1 after a successful init */
  FswHealth health;
} FswMtqDesatState;

typedef struct {
  fsw_real Omega[FSW_MAX_RW]; /* [rad/s] (num_rw) wheel speeds rel. body; read for
                                 available wheels, within +-FSW_RW_OMEGA_MAX      */
  uint8_t avail[FSW_MAX_RW];  /* [-]     (num_rw) 0 available, 1 unavailable      */
  fsw_real B_B[3];            /* [T]     magnetic field in B; read when B_valid = 1 */
  uint8_t B_valid;            /* [-]     1 B_B is a valid measurement, 0 not      */
} FswMtqDesatIn;

typedef struct {
  fsw_real tau_req_B[3]; /* [N*m]     requested magnetic torque, perpendicular to B,
                            |tau_req_B| <= tau_max (hand to mtq_map, torque mode)  */
  fsw_real m_B[3];       /* [A*m^2]   the dipole with m_B x B_B = tau_req_B          */
  fsw_real h_w_B[3];     /* [N*m*s]   momentum of the available wheels, B            */
  fsw_real h_err_B[3];   /* [N*m*s]   h_w_B - h_target_B                             */
  fsw_real h_err_norm;   /* [N*m*s]   |h_err_B|                                      */
  fsw_real scale;        /* [-]       tau_max limiting factor, (0, 1]; 1 unlimited;
                            0 when there is no request (deadband, no field, errors) */
} FswMtqDesatOut;

/* FSW_OK, FSW_E_CAPACITY (num_rw), FSW_E_CONFIG (axes, J_s, k_desat,
 * h_target_B, tau_max, h_deadband out of range or not finite). */
FswStatus fsw_mtq_desat_check(const FswMtqDesatConfig *cfg);
FswStatus fsw_mtq_desat_init(FswMtqDesatState *st, const FswMtqDesatConfig *cfg);
/* Stateless: nothing to clear (health counters are kept). */
void fsw_mtq_desat_reset(FswMtqDesatState *st);
/* FSW_OK: tau_req_B = -k_desat h_err_perp (or 0 inside the deadband),
 *   scale = 1 (0 inside the deadband).
 * FSW_W_SAT: |-k_desat h_err_perp| > tau_max; tau_req_B and m_B scaled by
 *   scale < 1 so that |tau_req_B| = tau_max.
 * FSW_W_SINGULAR: no usable field (B_valid = 0, or |B_B| < FSW_MTQ_B_MIN,
 *   mtq_map.h): tau_req_B = m_B = 0, scale = 0; h_w_B, h_err_B and
 *   h_err_norm are still reported.
 * FSW_E_BAD_INPUT (safe output): a mask entry or B_valid not 0/1, the speed
 *   of an available wheel not finite or beyond FSW_RW_OMEGA_MAX, B_B not
 *   finite or |B_B| > FSW_MTQ_B_MAX with B_valid = 1.
 * FSW_E_NOT_INIT (safe output). */
FswStatus fsw_mtq_desat_update(FswMtqDesatState *st, const FswMtqDesatConfig *cfg,
                               const FswMtqDesatIn *in, FswMtqDesatOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_MTQ_DESAT_H */

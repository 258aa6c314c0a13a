/* mtq_map: magnetorquer mapping.  Turns a torque request (or a dipole
 * request, e.g. from B-dot) into rod dipole commands.
 *
 * Torque mode (use_dipole = 0): a dipole m in a field B makes the torque
 * m x B, which is always perpendicular to B.  The request is split into
 *   tau_par  = (tau . b) b                      (b = B/|B|, unachievable)
 *   tau_perp = tau - tau_par
 * and the minimum-norm dipole giving m x B = tau_perp is
 *   m_B = (B x tau) / |B|^2 = (b x tau) / |B|.
 * Dipole mode (use_dipole = 1): m_B = m_req_B, tau_par = 0.
 *
 * Rods: c minimises |G c - m_B| and, among those, |c|: c = G^+ m_B with
 * G = [gt_hat of the available rods] (3 x n).  G^+ = G^T (G G^T)^+ where the
 * pseudo-inverse of the 3x3 M = G G^T comes from its eigen-decomposition
 * (cyclic Jacobi, fixed order); eigenvalues <= FSW_RANK_TOL x the largest
 * are treated as 0.  So with three or more independent rods G c = m_B
 * exactly and c has the least norm; with rods spanning a plane (rank 2, e.g.
 * two rods) G c is the projection of m_B onto that plane (least squares)
 * and the out-of-plane part is not delivered (FSW_W_SINGULAR when that
 * part exceeds FSW_RESID_TOL |m_B|); one rod (rank 1) delivers the
 * component of m_B along it.
 *
 * Saturation keeps the direction: lim_i = duty_max m_max_i; when any
 * |c_i| > lim_i every c is multiplied by the one factor
 * scale = min_i lim_i/|c_i| in (0, 1).  Unavailable rods get exactly 0.
 * Outputs: m_ach_B = G c, tau_ach_B = m_ach_B x B, duty_i = |c_i|/m_max_i.
 *
 * duty_max is the fraction of each control period the rods may be on: the
 * rest of the period the rods are off so that the magnetometer samples a
 * field free of the rods' own (sensing/actuation time-sharing).  With a PWM
 * drive a command c maps to the on-time |c|/m_max T from the start of the
 * period, so |c| <= duty_max m_max keeps the rods off for the sample.
 *
 * Field: B_valid = 0 or |B| < FSW_MTQ_B_MIN (1e-9 T, four orders below
 * any Earth-orbit field) leaves no usable field direction: rods off,
 * FSW_W_SINGULAR.  Stateless apart from the health counters.
 * Frames: B.  Units: SI.
 * Safe output (errors, not initialised): every m_cmd and duty 0 (rods off),
 * m_ach_B = tau_ach_B = tau_par_B = 0, scale = 0. */
#ifndef FSW_MTQ_MAP_H
#define FSW_MTQ_MAP_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Accepted configuration and input ranges (chosen so that no product or
 * ratio of accepted values overflows either real type). */
#define FSW_MTQ_M_MAX_MIN FSW_R(1e-6)  /* [A*m^2] smallest rod dipole limit */
#define FSW_MTQ_M_MAX_MAX FSW_R(1e4)   /* [A*m^2] largest rod dipole limit  */
#define FSW_MTQ_DUTY_MIN FSW_R(1e-3)   /* [-]     smallest duty_max (a subnormal one made
                                          every limit 0: fuzz finding, 2026-12-05)        */
#define FSW_MTQ_B_MIN FSW_R(1e-9)      /* [T]     smaller |B|: no usable field (W_SINGULAR) */
#define FSW_MTQ_B_MAX FSW_R(1.0)       /* [T]     larger |B|: a faulty reading (bad input)   */
#define FSW_MTQ_TAU_REQ_MAX FSW_R(1e6) /* [N*m]   largest |tau_B| component accepted         */
#define FSW_MTQ_M_REQ_MAX FSW_R(1e9)   /* [A*m^2] largest |m_req_B| component accepted       */
/* |gt_hat| = 1 within this (as the wheel axes: 1e-9 double, 1e-6 float). */
#if FSW_USE_FLOAT
#define FSW_MTQ_UNIT_TOL FSW_R(1e-6)
#else
#define FSW_MTQ_UNIT_TOL 1e-9
#endif

typedef struct {
  int num_mtq;                       /* [-]      1..FSW_MAX_MTQ                          */
  fsw_real gt_hat_B[FSW_MAX_MTQ][3]; /* [-]      (num_mtq) rod dipole axes, unit, B      */
  fsw_real m_max[FSW_MAX_MTQ];       /* [A*m^2]  (num_mtq) rod dipole at full drive,
                                        FSW_MTQ_M_MAX_MIN..FSW_MTQ_M_MAX_MAX           */
  fsw_real duty_max;                 /* [-]      fraction of the period the rods may
                                        be on, FSW_MTQ_DUTY_MIN..1;
                                        |m_cmd_i| <= duty_max m_max_i                  */
} FswMtqMapConfig;

typedef struct {
  int ready; /* 1 after a successful init */
  FswHealth health;
} FswMtqMapState;

typedef struct {
  fsw_real tau_B[3];          /* [N*m]   desired torque, B (read when use_dipole = 0),
                                 components within +-FSW_MTQ_TAU_REQ_MAX           */
  fsw_real m_req_B[3];        /* [A*m^2] desired dipole, B (read when use_dipole = 1),
                                 components within +-FSW_MTQ_M_REQ_MAX             */
  uint8_t use_dipole;         /* [-]     0 map tau_B, 1 map m_req_B directly         */
  fsw_real B_B[3];            /* [T]     magnetic field in B (magnetometer); read
                                 when B_valid = 1                                   */
  uint8_t B_valid;            /* [-]     1 B_B is a valid measurement, 0 not         */
  uint8_t avail[FSW_MAX_MTQ]; /* [-]     (num_mtq) 0 available, 1 unavailable        */
} FswMtqMapIn;

typedef struct {
  fsw_real m_cmd[FSW_MAX_MTQ]; /* [A*m^2] (num_mtq) rod dipole commands; 0 beyond
                                  num_mtq and for unavailable rods                  */
  fsw_real duty[FSW_MAX_MTQ];  /* [-]     (num_mtq) |m_cmd_i| / m_max_i, <= duty_max  */
  fsw_real m_ach_B[3];         /* [A*m^2] dipole the commands make, G m_cmd, B        */
  fsw_real tau_ach_B[3];       /* [N*m]   torque they make in B_B: m_ach_B x B_B      */
  fsw_real tau_par_B[3];       /* [N*m]   part of tau_B along B (unachievable); 0 in
                                  dipole mode                                       */
  fsw_real scale;              /* [-]     common saturation factor, (0, 1]; 1 when no
                                  rod saturated; 0 under W_SINGULAR for the field
                                  and under errors                                  */
  int rank;                    /* [-]     rank of G over the available rods, 0..3     */
} FswMtqMapOut;

/* The field check shared by the magnetorquer modules (mtq_map, mtq_desat).
 * For a measurement B (read only when valid = 1) returns
 *   FSW_OK          usable: b_hat = B/|B| (unit), *B_norm = |B|;
 *   FSW_W_SINGULAR  no usable direction (valid = 0, or |B| < FSW_MTQ_B_MIN);
 *   FSW_E_BAD_INPUT valid not 0/1, B not finite, or |B| > FSW_MTQ_B_MAX;
 * and b_hat = 0, *B_norm = 0 unless OK. */
FswStatus fsw_mtq_field(fsw_real b_hat[3], fsw_real *B_norm, const fsw_real B[3], uint8_t valid);

/* FSW_OK, FSW_E_CAPACITY (num_mtq), FSW_E_CONFIG (axis not finite or not
 * unit, m_max or duty_max out of range or not finite). */
FswStatus fsw_mtq_map_check(const FswMtqMapConfig *cfg);
FswStatus fsw_mtq_map_init(FswMtqMapState *st, const FswMtqMapConfig *cfg);
/* Stateless: nothing to clear (health counters are kept). */
void fsw_mtq_map_reset(FswMtqMapState *st);
/* FSW_OK: m_B delivered (G m_cmd = m_B within FSW_RESID_TOL |m_B|), no rod
 *   saturated, scale = 1.
 * FSW_W_SAT: the commands were scaled by scale < 1 (direction kept).
 * FSW_W_SINGULAR: (a) B_valid = 0 or |B_B| < FSW_MTQ_B_MIN: rods off, every
 *   output 0 (the safe output), B_B not read when B_valid = 0; (b) the
 *   available rods do not span m_B (rank < 3, or no rod available): the
 *   least-squares commands above, scaled as for W_SAT when needed (scale
 *   tells).
 * FSW_E_BAD_INPUT (safe output): use_dipole or B_valid not 0/1, a mask
 *   entry not 0/1, the request read (tau_B or m_req_B) not finite or beyond
 *   its range, B_B not finite or |B_B| > FSW_MTQ_B_MAX with B_valid = 1.
 * FSW_E_NOT_INIT (safe output). */
FswStatus fsw_mtq_map_update(FswMtqMapState *st, const FswMtqMapConfig *cfg,
                             const FswMtqMapIn *in, FswMtqMapOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_MTQ_MAP_H */

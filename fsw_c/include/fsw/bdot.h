/* bdot: B-dot detumbling with magnetorquers (docs/fsw/bdot.md).
 * Commands a body dipole m_B that removes rotational energy through the
 * magnetic torque tau = m x B:
 *   FSW_BDOT_DERIV (0): m = -g Bdot_f, Bdot_f a low-passed finite difference
 *     of the valid magnetometer samples:
 *       raw = (B_k - B_j) / dt_kj  (j = the last VALID sample, dt from t_ns)
 *       Bdot_f += beta (raw - Bdot_f),  beta = dt_kj / (tau_f + dt_kj)
 *     (backward-Euler form of tau_f d(Bdot_f)/dt = raw - Bdot_f: no overshoot,
 *     unit DC gain, any dt; tau_f = 0 gives beta = 1, no filter).  The first
 *     valid sample after init/reset/drop only primes (m = 0); the first
 *     difference after it sets Bdot_f = raw (no start from 0).
 *   FSW_BDOT_GYRO (1): m = -g Bdot_w with Bdot_w = B x omega (= -omega x B,
 *     the body-frame derivative of an inertially fixed field), i.e.
 *     m = g (omega x B).  Torque power omega.(m x B) = -g |omega x B|^2 <= 0.
 *   g = k_bdot (normalize 0) or k_bdot / |B|^2 (normalize 1).
 * Saturation keeps the direction: m is scaled by one common factor
 * scale = min(1, min_i m_max_B[i] / |m_i|) so every |m_i| <= m_max_B[i].
 * Missed samples (DERIV: B_valid = 0; GYRO: B_valid = 0 or omega_valid = 0):
 * the last commanded dipole (and Bdot) is held for up to max_missed
 * consecutive cycles (FSW_W_RATE, held = 1); the next miss switches the rods
 * off (m = 0, FSW_W_RATE, held = 0) and drops the derivative memory, so the
 * next valid sample primes again.  A valid sample within the hold window is
 * differenced against the last valid one over the true elapsed time.
 * Detumble flag: rate_est = |omega| when omega_valid, else (DERIV only)
 * |Bdot_f| / |B| (= the rate component normal to B for a fixed field: a
 * lower bound of |omega|).  rate_est < omega_done continuously for
 * t_persist seconds sets detumbled = 1; it stays latched until reset or
 * until rate_est > omega_reenter (> omega_done).  A cycle without a rate
 * estimate restarts the persistence time but keeps the latch.
 * Frames: B.  Units: SI.
 * Safe output (bad input, bad time, not initialised): every field 0
 * (m_B = 0, Bdot_B = 0, rate_est = 0, rate_valid = 0, detumbled = 0,
 * t_below = 0, scale = 0, held = 0). */
#ifndef FSW_BDOT_H
#define FSW_BDOT_H

#include <stdint.h>

#include "fsw/fsw_clock.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FSW_BDOT_DERIV 0 /* magnetometer-derivative law */
#define FSW_BDOT_GYRO 1  /* gyro law, m = g (omega x B)  */

/* Ranges (chosen so that no accepted config and in-range input overflows
 * a float: |m_i| before saturation <= (1e12 / 1e-18) * (2e-3 T / 1e-9 s)
 * = 2e36 < 3.4e38). */
#define FSW_BDOT_K_MAX FSW_R(1e12)        /* [A*m^2*s/T or N*m*s] largest k_bdot */
#define FSW_BDOT_TAU_MAX FSW_R(1e6)       /* [s]      largest tau_f                */
#define FSW_BDOT_MISSED_MAX 100000        /* [-]      largest max_missed           */
#define FSW_BDOT_M_MIN FSW_R(1e-6)        /* [A*m^2]  smallest m_max_B[i]          */
#define FSW_BDOT_M_MAX FSW_R(1e4)         /* [A*m^2]  largest m_max_B[i]           */
#define FSW_BDOT_OMEGA_MAX FSW_R(100.0)   /* [rad/s]  largest |omega_i| input and
                                             largest omega_reenter             */
#define FSW_BDOT_T_PERSIST_MAX FSW_R(1e6) /* [s]      largest t_persist; t_below
                                             saturates there                  */
#define FSW_BDOT_B_MAX FSW_R(1e-3)        /* [T]      largest |B_i| input (1 mT)   */
#define FSW_BDOT_B_MIN FSW_R(1e-9)        /* [T]      smallest |B| of a valid
                                             sample (1 nT; LEO fields are
                                             > 1e-5 T)                         */

typedef struct {
  int variant;          /* [-]    FSW_BDOT_DERIV or FSW_BDOT_GYRO                */
  fsw_real k_bdot;      /* [A*m^2*s/T] (normalize 0) or [N*m*s] (normalize 1)
                           gain, > 0, <= FSW_BDOT_K_MAX; see fsw_bdot_gain      */
  int normalize;        /* [-]    0: g = k_bdot; 1: g = k_bdot / |B|^2           */
  fsw_real tau_f;       /* [s]    derivative filter time constant, 0 (no filter)
                           .. FSW_BDOT_TAU_MAX; read by DERIV only             */
  int max_missed;       /* [-]    cycles a dipole is held over missed samples,
                           0..FSW_BDOT_MISSED_MAX                              */
  fsw_real m_max_B[3];  /* [A*m^2] per-B-axis dipole limit,
                           FSW_BDOT_M_MIN..FSW_BDOT_M_MAX                      */
  fsw_real omega_done;  /* [rad/s] detumbled threshold, > 0                    */
  fsw_real omega_reenter; /* [rad/s] re-entry threshold, > omega_done,
                           <= FSW_BDOT_OMEGA_MAX                               */
  fsw_real t_persist;   /* [s]    time below omega_done before detumbled = 1,
                           0..FSW_BDOT_T_PERSIST_MAX                           */
} FswBdotConfig;

/* The dynamic memory, cleared by reset (one struct so that update can
 * compute into a copy and commit it only on the accepted path). */
typedef struct {
  FswClock clock;       /* [-]    previous accepted call                        */
  int primed;           /* [-]    DERIV: B_prev holds a valid sample            */
  uint64_t t_B_ns;      /* [ns]   time stamp of B_prev                          */
  fsw_real B_prev[3];   /* [T]    last valid field sample                       */
  int has_bdot;         /* [-]    DERIV: Bdot_f holds a filtered value          */
  fsw_real Bdot_f[3];   /* [T/s]  filter memory (DERIV); last Bdot_w (GYRO)     */
  fsw_real m_hold[3];   /* [A*m^2] last commanded dipole (after saturation)     */
  fsw_real scale_hold;  /* [-]    its saturation factor                         */
  int missed;           /* [-]    consecutive missed cycles (saturating)        */
  int below;            /* [-]    previous accepted cycle had rate < omega_done */
  fsw_real t_below;     /* [s]    continuous time below omega_done              */
  uint8_t detumbled;    /* [-]    latched detumble flag                         */
} FswBdotMemory;

typedef struct {
  int ready;            /* 1 after a successful init */
  FswBdotMemory mem;
  FswHealth health;
} FswBdotState;

typedef struct {
  uint64_t t_ns;          /* [ns]    time stamp                                  */
  fsw_real B_B[3];        /* [T]     measured field, B (read when B_valid = 1)   */
  uint8_t B_valid;        /* [-]     1 valid sample, 0 missed                    */
  fsw_real omega_BN_B[3]; /* [rad/s] body rate, B (read when omega_valid = 1)    */
  uint8_t omega_valid;    /* [-]     1 valid, 0 not available                    */
} FswBdotIn;

typedef struct {
  fsw_real m_B[3];    /* [A*m^2] commanded dipole, B (|m_i| <= m_max_B[i])       */
  fsw_real Bdot_B[3]; /* [T/s]   Bdot the dipole was formed from (filtered, or
                         B x omega for GYRO); 0 while priming                  */
  fsw_real rate_est;  /* [rad/s] rate used by the detumble test (0 if none)     */
  uint8_t rate_valid; /* [-]     1 when rate_est is a measurement this cycle    */
  uint8_t detumbled;  /* [-]     latched detumble flag, 0/1                     */
  fsw_real t_below;   /* [s]     continuous time below omega_done               */
  fsw_real scale;     /* [-]     saturation factor in (0, 1]; 1 unsaturated     */
  uint8_t held;       /* [-]     1 when m_B is a dipole held over a missed sample */
} FswBdotOut;

/* FSW_OK or FSW_E_CONFIG (any field non-finite or out of its range, a flag
 * or variant not 0/1, omega_reenter <= omega_done). */
FswStatus fsw_bdot_check(const FswBdotConfig *cfg);
FswStatus fsw_bdot_init(FswBdotState *st, const FswBdotConfig *cfg);
/* Clears the memory (clock, derivative, held dipole, detumble latch). */
void fsw_bdot_reset(FswBdotState *st);
/* FSW_OK (dipole within limits, unscaled);
 * FSW_W_SAT (scaled by scale < 1, direction kept);
 * FSW_W_RATE (a missed sample: held dipole, held = 1, for up to max_missed
 *   cycles, then m = 0 and the derivative memory dropped);
 * FSW_E_BAD_INPUT (a flag not 0/1, or a flagged-valid B_B / omega_BN_B that
 *   is non-finite, has a component beyond FSW_BDOT_B_MAX / FSW_BDOT_OMEGA_MAX,
 *   or |B_B| < FSW_BDOT_B_MIN);
 * FSW_E_TIME (t_ns <= previous accepted call); FSW_E_NOT_INIT.
 * Errors write the safe output and change no memory. */
FswStatus fsw_bdot_update(FswBdotState *st, const FswBdotConfig *cfg,
                          const FswBdotIn *in, FswBdotOut *out);

/* Gain of the normalised law (normalize = 1) after Avanzini & Giulietti
 * (2012): k = 2 n (1 + sin xi) J_min [N*m*s], n the orbit rate [rad/s],
 * J_min the smallest principal inertia [kg*m^2], xi the orbit inclination to
 * the geomagnetic equator [rad].  For normalize = 0 divide by a typical
 * |B|^2 (docs/fsw/bdot.md).  Returns 0 for non-finite input, n <= 0 or
 * J_min <= 0. */
fsw_real fsw_bdot_gain(fsw_real n_orbit, fsw_real J_min, fsw_real incl_mag);

/* e-folding time [s] of |omega| estimated by averaging the projector normal
 * to B over directions (<1 - (b.e)^2> = 2/3):  T = 3 J / (2 k_eff),
 * k_eff = k (normalize 1) or k B_rms^2 (normalize 0).  Valid for gains at or
 * below the optimum of fsw_bdot_gain (above it the field's rotation limits
 * the decay and the time grows); J [kg*m^2] the largest principal inertia
 * for a bound.  Returns 0 for non-finite or non-positive k, J (or B_rms with
 * normalize 0) or normalize not 0/1. */
fsw_real fsw_bdot_decay_time(fsw_real k, fsw_real J, fsw_real B_rms, int normalize);

#ifdef __cplusplus
}
#endif

#endif /* FSW_BDOT_H */

/* thr_momentum: thruster momentum management and dumping for a
 * reaction-wheel spacecraft.  Each control cycle:
 *
 *  1. Wheel momentum (B components, relative to the body) over the
 *     AVAILABLE wheels:  h_w_B = sum_i J_s[i] Omega[i] gs_hat_B[i].
 *     The body-rate part of the wheels' momentum, J_s g g^T omega, is not
 *     included (it is J_s |omega| per wheel, 5e-5 N*m*s for 0.05 kg*m^2 at
 *     1 mrad/s: negligible against any dump threshold of a pointed craft).
 *  2. Hysteresis: in IDLE, when |h_w| > h_upper, a dump starts with the
 *     external momentum change that brings the wheels down to h_lower,
 *         Delta_H_B = -h_w_B (1 - h_lower / |h_w|),  |Delta_H| = |h_w| - h_lower,
 *     frozen for the whole dump (one dump removes at most
 *     2 FSW_THR_MOM_CYCLES_MAX L_dump dt_cycle, see there).  No new dump
 *     starts until |h_w| > h_upper again.
 *  3. Dump sequence IDLE -> PULSE -> COAST -> PULSE ... -> COAST -> IDLE.
 *     The remaining impulse I_rem starts at |Delta_H|.  A pulse is given the
 *     impulse I_p = min(I_rem, L_dump t_pulse_max) (>= L_dump t_min_pulse,
 *     see below).  Each PULSE cycle requests the body torque
 *         L_thr_B = u (I_c / dt_cycle),  u = Delta_H / |Delta_H|,
 *         I_c = min(L_dump dt_cycle, impulse left in the pulse),
 *     i.e. L_dump while the pulse has a full cycle's impulse left and the
 *     reduced torque that completes it exactly in its last cycle.  The
 *     request of a cycle acts over the NEXT control period, whose nominal
 *     length is the configured dt_cycle, so the impulse counted for a PULSE
 *     cycle is exactly the commanded I_c = |L_thr| dt_cycle, taken off I_rem
 *     and off the pulse in the cycle that commands it (dH_rem_B is what
 *     remains after this cycle's command is delivered).  A pulse therefore
 *     delivers at most L_dump t_pulse_max: ceil(t_pulse_max / dt_cycle)
 *     cycles, the last one at reduced torque.  A pulse ends when what is
 *     left of it is at most FSW_THR_MOM_CYCLE_TOL of a full cycle's impulse
 *     (that rounding crumb stays in I_rem).
 *     After the pulse's last command the module coasts (L_thr = 0) for
 *     t_coast seconds after the pulse's last period ends: the next
 *     decision is taken at the first cycle with
 *         t_ns - t_last_pulse_cmd >= dt_cycle + t_coast - FSW_THR_MOM_CYCLE_TOL dt_cycle.
 *     Then, if I_rem >= L_dump t_min_pulse, the next pulse starts in that
 *     cycle; otherwise the dump ends (phase IDLE, dumps + 1).  Every pulse
 *     therefore delivers at least the minimum pulse impulse L_dump
 *     t_min_pulse (a shorter pulse is never commanded), and the dump leaves
 *     less than one minimum pulse impulse undelivered.  The cycle that ends
 *     a dump does not start another.
 *  4. The wheels hold the attitude: the application adds -L_thr_B to the
 *     torque request of the wheel chain, so the wheels absorb the thruster
 *     torque and h_w changes by +integral(L_thr) = Delta_H (the module does
 *     not do this).
 *  5. Propellant: each call reports the thruster on-times the application
 *     commanded in the PREVIOUS cycle (t_on_prev).  dm = sum_j F_max[j]
 *     t_on_prev[j] / (Isp g0), g0 = 9.80665 m/s^2, is attributed to the
 *     cycle that commanded it: it is added to prop_dump and prop_total when
 *     the previous accepted call reported PULSE or COAST (so the on-times of
 *     a dump's last cycle, reported in the cycle that ends the dump, count;
 *     the first call after reset and cycles after an IDLE call count
 *     nothing).  Thrusting outside dumps is not attributed.
 *
 * enable = 0: dumping is off: no dump starts (automatic or forced) and a
 * dump in progress is ABORTED in that cycle (L_thr = 0, phase IDLE,
 * aborts + 1; dumps is not counted; t_dump and prop_dump keep the aborted
 * dump's figures).  force_dump = 1 (with enable = 1, in IDLE) starts a dump
 * now when |h_w| > h_lower and |h_w| - h_lower >= L_dump t_min_pulse (a
 * smaller dump cannot be commanded and is ignored); it is ignored during a
 * dump.
 *
 * FSW_W_RATE: the previous accepted call commanded a torque and the
 * measured period differs from dt_cycle by more than FSW_THR_MOM_RATE_TOL
 * (the impulse delivered then differs from the one counted); the output is
 * computed as usual.
 *
 * Frames: B.  Units: SI.
 * Safe output (every error): L_thr_B = 0, h_w_B = 0, h_norm = 0.  For
 * FSW_E_BAD_INPUT and FSW_E_TIME the report fields (phase, dH_B, dH_rem_B,
 * dumps, aborts, pulses, t_dump, prop_dump, prop_total) repeat those of the
 * last accepted call (all 0 after reset); for FSW_E_NOT_INIT and
 * FSW_E_NULL_ARG every field is 0.  No state advances on an error. */
#ifndef FSW_THR_MOMENTUM_H
#define FSW_THR_MOMENTUM_H

#include <stdint.h>

#include "fsw/fsw_clock.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/rw_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Standard gravity for the specific impulse [m/s^2]. */
#define FSW_THR_MOM_G0 FSW_R(9.80665)
/* Ranges accepted by check: wide enough for any craft, narrow enough that
 * no product or ratio of accepted values overflows either real type. */
#define FSW_THR_MOM_H_MAX FSW_R(1e9)     /* [N*m*s] largest h_upper                 */
#define FSW_THR_MOM_L_MIN FSW_R(1e-9)    /* [N*m]   smallest L_dump                 */
#define FSW_THR_MOM_L_MAX FSW_R(1e6)     /* [N*m]   largest L_dump                  */
#define FSW_THR_MOM_T_MIN FSW_R(1e-6)    /* [s]     smallest t_min_pulse, dt_cycle  */
#define FSW_THR_MOM_T_MAX FSW_R(1e6)     /* [s]     largest t_pulse_max, t_coast    */
#define FSW_THR_MOM_DT_MAX FSW_R(1e3)    /* [s]     largest dt_cycle                */
/* Largest number of full-torque control cycles in h_upper (h_upper <=
 * FSW_THR_MOM_CYCLES_MAX L_dump dt_cycle) and in t_pulse_max (<=
 * FSW_THR_MOM_CYCLES_MAX dt_cycle).  One dump removes at most twice that
 * (|Delta_H| <= 2 FSW_THR_MOM_CYCLES_MAX L_dump dt_cycle, so that a cycle's
 * impulse is never lost in the rounding of the remaining impulse, also in
 * single precision); a larger excess (a forced dump or a wheel coming back
 * into service with |h_w| > 2 h_upper) is removed by successive dumps. */
#define FSW_THR_MOM_CYCLES_MAX FSW_R(1e6)
#define FSW_THR_MOM_F_MAX FSW_R(1e6)     /* [N]     largest F_max                   */
#define FSW_THR_MOM_ISP_MIN FSW_R(1.0)   /* [s]     smallest Isp                    */
#define FSW_THR_MOM_ISP_MAX FSW_R(1e5)   /* [s]     largest Isp                     */
/* Largest on-time entry accepted at run time [s]; beyond it: bad input. */
#define FSW_THR_MOM_T_ON_MAX FSW_R(1e4)
/* Timing and impulse crumbs, as a fraction of one control cycle [-]. */
#define FSW_THR_MOM_CYCLE_TOL FSW_R(1e-3)
/* Relative period mismatch above which a cycle after a PULSE gives FSW_W_RATE. */
#define FSW_THR_MOM_RATE_TOL FSW_R(0.01)

typedef enum { FSW_THR_MOM_IDLE = 0, FSW_THR_MOM_PULSE = 1, FSW_THR_MOM_COAST = 2 } FswThrMomPhase;

typedef struct {
  int num_rw;                       /* [-]       1..FSW_MAX_RW                          */
  fsw_real gs_hat_B[FSW_MAX_RW][3]; /* [-]       (num_rw) spin axes, unit, B            */
  fsw_real J_s[FSW_MAX_RW];         /* [kg*m^2]  (num_rw) spin inertias,
                                       (0, FSW_RW_J_S_MAX] (rw_common.h)              */
  fsw_real h_upper;                 /* [N*m*s]   dump start threshold on |h_w|,
                                       (h_lower, FSW_THR_MOM_H_MAX] and
                                       <= FSW_THR_MOM_CYCLES_MAX L_dump dt_cycle      */
  fsw_real h_lower;                 /* [N*m*s]   |h_w| a dump aims at, >= 0; the band
                                       h_upper - h_lower >= L_dump t_min_pulse       */
  fsw_real L_dump;                  /* [N*m]     pulse torque,
                                       [FSW_THR_MOM_L_MIN, FSW_THR_MOM_L_MAX]         */
  fsw_real t_pulse_max;             /* [s]       longest pulse at L_dump,
                                       [t_min_pulse, FSW_THR_MOM_T_MAX] and
                                       <= FSW_THR_MOM_CYCLES_MAX dt_cycle             */
  fsw_real t_min_pulse;             /* [s]       shortest pulse at L_dump,
                                       [FSW_THR_MOM_T_MIN, t_pulse_max]               */
  fsw_real t_coast;                 /* [s]       settling after a pulse,
                                       [0, FSW_THR_MOM_T_MAX]                         */
  fsw_real dt_cycle;                /* [s]       nominal control period,
                                       [FSW_THR_MOM_T_MIN, FSW_THR_MOM_DT_MAX]        */
  int num_thr;                      /* [-]       1..FSW_MAX_THR                         */
  fsw_real F_max[FSW_MAX_THR];      /* [N]       (num_thr) full thrust,
                                       (0, FSW_THR_MOM_F_MAX]                         */
  fsw_real Isp;                     /* [s]       specific impulse,
                                       [FSW_THR_MOM_ISP_MIN, FSW_THR_MOM_ISP_MAX]     */
} FswThrMomentumConfig;

typedef struct {
  int ready;                /* [-]       1 after a successful init                       */
  FswClock clock;           /* [-]       previous accepted call                          */
  int phase;                /* [-]       FswThrMomPhase the next call starts from        */
  int phase_out;            /* [-]       phase reported by the last accepted call        */
  fsw_real u_B[3];          /* [-]       unit direction of Delta_H (during a dump)       */
  fsw_real dH_B[3];         /* [N*m*s]   Delta_H of the current/last dump                */
  fsw_real I_rem;           /* [N*m*s]   remaining impulse |dH_rem| (0 in IDLE)          */
  fsw_real I_pulse;         /* [N*m*s]   impulse left in the current pulse               */
  fsw_real L_prev;          /* [N*m]     |L_thr| commanded by the last accepted call     */
  uint64_t t_start_ns;      /* [ns]      start of the current/last dump                  */
  uint64_t t_cmd_ns;        /* [ns]      last PULSE command                              */
  uint32_t dumps;           /* [-]       dumps completed since reset (saturating)        */
  uint32_t aborts;          /* [-]       dumps aborted by enable = 0 (saturating)        */
  uint32_t pulses;          /* [-]       pulses of the current/last dump                 */
  fsw_real t_dump;          /* [s]       duration of the current/last dump               */
  fsw_real prop_dump;       /* [kg]      propellant of the current/last dump             */
  fsw_real prop_total;      /* [kg]      propellant of every dump since reset            */
  FswHealth health;
} FswThrMomentumState;

typedef struct {
  uint64_t t_ns;                 /* [ns]    time stamp of this call                       */
  fsw_real Omega[FSW_MAX_RW];    /* [rad/s] (num_rw) wheel speeds relative to the body,
                                    |Omega| <= FSW_RW_OMEGA_MAX for available wheels     */
  uint8_t avail[FSW_MAX_RW];     /* [-]     (num_rw) 0 available, 1 unavailable          */
  fsw_real t_on_prev[FSW_MAX_THR]; /* [s]   (num_thr) on-times the application commanded
                                    in the previous cycle, [0, FSW_THR_MOM_T_ON_MAX]     */
  uint8_t enable;                /* [-]     1 dumping on; 0 no dump starts and a dump in
                                    progress is aborted                                  */
  uint8_t force_dump;            /* [-]     1 start a dump now (IDLE, enable = 1) when
                                    |h_w| - h_lower >= L_dump t_min_pulse               */
} FswThrMomentumIn;

typedef struct {
  fsw_real L_thr_B[3];   /* [N*m]   body torque request for the thrusters (B); the
                            wheel chain must be given -L_thr_B                        */
  int phase;             /* [-]     FswThrMomPhase of this cycle's output: PULSE when
                            L_thr is commanded, COAST between pulses, else IDLE      */
  fsw_real dH_rem_B[3];  /* [N*m*s] Delta_H not yet commanded (after this cycle's
                            command); 0 in IDLE                                      */
  fsw_real h_w_B[3];     /* [N*m*s] wheel momentum of the available wheels            */
  fsw_real h_norm;       /* [N*m*s] |h_w_B|                                           */
  uint32_t dumps;        /* [-]     dumps completed since reset                        */
  fsw_real t_dump;       /* [s]     from the start of the current/last dump to now /
                            to the cycle that ended it                               */
  fsw_real prop_dump;    /* [kg]    propellant of the current/last dump               */
  fsw_real prop_total;   /* [kg]    propellant of every dump since reset              */
  fsw_real dH_B[3];      /* [N*m*s] Delta_H of the current/last dump (frozen)         */
  uint32_t aborts;       /* [-]     dumps aborted since reset                          */
  uint32_t pulses;       /* [-]     pulses of the current/last dump                    */
} FswThrMomentumOut;

/* FSW_OK; FSW_E_CAPACITY (num_rw, num_thr); FSW_E_CONFIG (axes not unit,
 * J_s, thresholds, h_lower >= h_upper, band below one minimum pulse
 * impulse, L_dump, t_pulse_max, t_min_pulse > t_pulse_max, t_coast,
 * dt_cycle, F_max, Isp out of range or not finite). */
FswStatus fsw_thr_momentum_check(const FswThrMomentumConfig *cfg);
FswStatus fsw_thr_momentum_init(FswThrMomentumState *st, const FswThrMomentumConfig *cfg);
/* Back to IDLE; forgets the dump in progress, the counters, the propellant
 * totals and the previous call.  Health counters are kept. */
void fsw_thr_momentum_reset(FswThrMomentumState *st);
/* FSW_OK; FSW_W_RATE (see above; output valid); FSW_E_BAD_INPUT (an
 * available wheel's Omega not finite or beyond FSW_RW_OMEGA_MAX, a mask
 * entry not 0/1, a t_on_prev[j < num_thr] not finite, negative or above
 * FSW_THR_MOM_T_ON_MAX, enable or force_dump not 0/1); FSW_E_TIME (t_ns not
 * after the previous accepted call); FSW_E_NOT_INIT; FSW_E_NULL_ARG.
 * Errors give the safe output and advance no state. */
FswStatus fsw_thr_momentum_update(FswThrMomentumState *st, const FswThrMomentumConfig *cfg,
                                  const FswThrMomentumIn *in, FswThrMomentumOut *out);

/* Planning helpers (pure functions).
 *
 * Steady-state interval between dump starts [s] under a constant secular
 * disturbance torque of magnitude |L_dist| [N*m] whose direction is fixed in
 * B: every dump removes h_upper - h_lower and the disturbance brings it back
 * in (h_upper - h_lower) / |L_dist|, whatever the dump's own duration (the
 * wheels keep absorbing the disturbance during the dump).  Returns 0 for
 * invalid arguments (non-finite, h_lower < 0, h_upper <= h_lower,
 * L_dist = 0, or a quotient beyond the real's range). */
fsw_real fsw_thr_momentum_dump_interval(fsw_real h_upper, fsw_real h_lower, fsw_real L_dist);

/* Propellant [kg] of one dump of momentum |dH| [N*m*s] made by thrusters
 * whose torque per newton of total thrust is lever_arm [m] (|L| / sum F):
 * total thrust impulse |dH| / lever_arm, m = |dH| / (lever_arm Isp g0).
 * Returns 0 for invalid arguments (non-finite, lever_arm <= 0, Isp <= 0, or
 * a result beyond the real's range). */
fsw_real fsw_thr_momentum_prop_per_dump(fsw_real dH, fsw_real lever_arm, fsw_real Isp);

#ifdef __cplusplus
}
#endif

#endif /* FSW_THR_MOMENTUM_H */

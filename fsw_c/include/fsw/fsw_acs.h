/* fsw_acs: the FSW application.  One cycle function, called once per control
 * period by the flight executive (or the harness, a HIL process, a target
 * test), wires the modules into
 *   guidance (css_sun -> guid_sunsafe | guid_inertial -> att_track) -> mrp_fb
 *   -> [trq_lpf] -> wheel chain:    rw_map -> [rw_null] -> rw_sat -> [rw_volt]
 * with the tachometers screened first by [rw_speed_filter] (its speeds and
 * availability feed mrp_fb and every wheel stage),
 *                -> thruster chain: thr_map -> thr_pulse_rem | thr_pulse_schmitt
 * over the messages of fsw_acs_msgs.h.  See docs/fsw/fsw_acs.md.
 *
 * Mode transitions (a change of mode or of actuation in FswAcsCmdMsg) take
 * effect at the start of the cycle that requests them and reset:
 *   - mrp_fb (integral term and timing), trq_lpf (filter memory),
 *   - the pulser (remainders / Schmitt memory) and thr_map,
 *   - rw_volt (speed-loop warm-up).
 * Derived data (null-space projector, normalised axes) is never reset.
 *
 * Safe output: all actuator commands 0 (wheel torque and voltage 0,
 * thrusters off, Lr = 0), with wheels_active = thrusters_active = 0.  It is
 * written on every error; the next good cycle recovers with no reset. */
#ifndef FSW_ACS_H
#define FSW_ACS_H

#include <stdint.h>

#include "fsw/att_track.h"
#include "fsw/bdot.h"
#include "fsw/css_sun.h"
#include "fsw/fsw_clock.h"
#include "fsw/fsw_acs_msgs.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/guid_inertial.h"
#include "fsw/guid_orbit.h"
#include "fsw/guid_sunsafe.h"
#include "fsw/mrp_fb.h"
#include "fsw/mtq_desat.h"
#include "fsw/mtq_map.h"
#include "fsw/rw_bias.h"
#include "fsw/rw_map.h"
#include "fsw/rw_null.h"
#include "fsw/rw_sat.h"
#include "fsw/rw_speed_filter.h"
#include "fsw/rw_volt.h"
#include "fsw/thr_map.h"
#include "fsw/thr_momentum.h"
#include "fsw/thr_pulse_rem.h"
#include "fsw/thr_pulse_schmitt.h"
#include "fsw/trq_lpf.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  FSW_ACS_PULSE_REMAINDER = 0, /* thr_pulse_rem (docs/fsw/thr_pulse_rem.md)     */
  FSW_ACS_PULSE_SCHMITT = 1    /* thr_pulse_schmitt (docs/fsw/thr_pulse_schmitt.md) */
} FswAcsPulser;

/* The actuator geometry of the spacecraft, given once.  The modules keep
 * their own copies (each module config is complete on its own, as the
 * module template requires); fsw_acs_config_set_geometry() is the one place
 * that writes them, and fsw_acs_check() cross-checks them as a safety net
 * for configs filled by hand.  Thruster names follow thr_map. */
typedef struct {
  /* reaction wheels */
  int num_rw;                          /* [-]      0..FSW_MAX_RW (0: no wheels)    */
  fsw_real gs_hat_B[FSW_MAX_RW][3];    /* [-]      (num_rw) spin axes, unit, B     */
  fsw_real J_s[FSW_MAX_RW];            /* [kg*m^2] (num_rw) spin inertias, > 0     */
  fsw_real u_max[FSW_MAX_RW];          /* [N*m]    (num_rw) motor torque limits, > 0 */
  /* thrusters (the ones the FSW commands) */
  int num_thr;                         /* [-]      0..FSW_MAX_THR (0: none)        */
  fsw_real r_thr_B[FSW_MAX_THR][3];    /* [m]      (num_thr) locations, B          */
  fsw_real gt_hat_B[FSW_MAX_THR][3];   /* [-]      (num_thr) unit force axes, B    */
  fsw_real F_max[FSW_MAX_THR];         /* [N]      (num_thr) max thrust, > 0       */
  /* magnetorquer rods */
  int num_mtq;                         /* [-]      0..FSW_MAX_MTQ (0: none)        */
  fsw_real mtq_axis_B[FSW_MAX_MTQ][3]; /* [-]      (num_mtq) rod axes, unit, B     */
  fsw_real mtq_m_max[FSW_MAX_MTQ];     /* [A*m^2]  (num_mtq) rod dipole limits, > 0 */
} FswAcsGeometry;

/* All configuration of the application in one struct. */
typedef struct {
  int initial_mode;         /* [-] FswAcsMode after init                          */
  int initial_actuation;    /* [-] FswAcsActuation after init                     */
  /* guidance */
  FswCssSunConfig css;             /* coarse sun sensors (SUN_SAFE)                */
  FswGuidSunsafeConfig sunsafe;    /* sun-safe pointing                            */
  FswGuidInertialConfig inertial;  /* inertial pointing                            */
  FswAttTrackConfig track;         /* tracking error (INERTIAL)                    */
  /* control */
  FswMrpFbConfig mrp_fb;           /* control law (its RW set: the wheel set)     */
  int use_lpf;                     /* [-] 0/1: low-pass filter Lr                  */
  FswTrqLpfConfig lpf;
  /* wheel chain (used when has_wheels = 1) */
  int has_wheels;                  /* [-] 0/1                                       */
  int use_speed_filter;            /* [-] 0/1: screen the tachometers (outliers, NaN,
                                      stale and torque-inconsistent readings fail a
                                      wheel: it is then unavailable to every stage) */
  FswRwSpeedFilterConfig speed_filter;
  FswRwMapConfig rw_map;
  int use_null;                    /* [-] 0/1: null motion toward Omega_des         */
  FswRwNullConfig rw_null;
  fsw_real Omega_des[FSW_MAX_RW];  /* [rad/s] (num_rw) desired wheel speeds         */
  FswRwSatConfig rw_sat;
  int use_volt;                    /* [-] 0/1: also compute motor voltages          */
  FswRwVoltConfig rw_volt;
  /* thruster chain (used when has_thrusters = 1) */
  int has_thrusters;               /* [-] 0/1                                       */
  FswThrMapConfig thr_map;
  int pulser;                      /* [-] FswAcsPulser                              */
  FswThrPulseRemConfig pulse_rem;
  FswThrPulseSchmittConfig pulse_schmitt;
  /* magnetorquers (used when has_mtq = 1): DETUMBLE and the MAGNETORQUERS policy */
  int has_mtq;                     /* [-] 0/1                                       */
  FswMtqMapConfig mtq_map;         /* rods, duty_max (sensing/actuation time-sharing) */
  FswBdotConfig bdot;              /* DETUMBLE's control law                        */
  int detumble_exit_mode;          /* [-] FswAcsMode entered once bdot reports the
                                      body detumbled (SUN_SAFE, INERTIAL or NADIR);
                                      -1: stay in DETUMBLE                          */
  /* orbit-referenced guidance (used when has_orbit = 1): NADIR */
  int has_orbit;                   /* [-] 0/1                                       */
  FswGuidOrbitConfig orbit;
  /* momentum management of the wheels in the pointing modes */
  int initial_policy;              /* [-] FswAcsMomentumPolicy after init           */
  int use_thr_mom;                 /* [-] 0/1: THRUSTERS policy available (needs
                                      wheels and on-pulsing thrusters; the pulser
                                      then runs every cycle of the policy and its
                                      first cycle after a reset starts no dump)     */
  FswThrMomentumConfig thr_mom;
  int use_mtq_desat;               /* [-] 0/1: MAGNETORQUERS policy available (needs
                                      wheels and has_mtq)                           */
  FswMtqDesatConfig mtq_desat;
  int use_bias;                    /* [-] 0/1: rw_bias chooses rw_null's desired
                                      speeds (needs use_null); else Omega_des       */
  FswRwBiasConfig rw_bias;
} FswAcsConfig;

/* Inputs and outputs of the stages, kept in the state so that the cycle
 * function's own stack stays small (see the stack table in docs).  Private
 * by convention: its layout may change; an integrator reads FswAcsHealthMsg
 * (and the module health counters) instead.  Scratch except three members
 * that persist into the next cycle (docs/fsw-conventions.md, "Errors"):
 * u_last and u_last_valid (a record of the wheel torque sent: an error
 * cycle clears u_last_valid) and t_on_last (saved and put back on an error
 * cycle like the state). */
typedef struct {
  FswRwSpeedFilterIn filt_in;
  FswRwSpeedFilterOut filt_out;
  /* The wheel torque the last call wrote and whether it was applied over the
   * whole interval since (a good cycle with wheels active); an error cycle or
   * a thruster cycle clears u_last_valid, so the speed filter's torque window
   * restarts.  A record of outputs, not algorithm state: errors change it. */
  fsw_real u_last[FSW_MAX_RW];
  uint8_t u_last_valid;
  FswCssSunIn css_in;
  FswCssSunOut css_out;
  FswGuidSunsafeIn sunsafe_in;
  FswGuidSunsafeOut sunsafe_out;
  FswGuidInertialOut inertial_out;
  FswAttTrackIn track_in;
  FswAttTrackOut track_out;
  FswMrpFbIn fb_in;
  FswMrpFbOut fb_out;
  FswTrqLpfIn lpf_in;
  FswTrqLpfOut lpf_out;
  FswRwMapIn map_in;
  FswRwMapOut map_out;
  FswRwNullIn null_in;
  FswRwNullOut null_out;
  FswRwSatIn sat_in;
  FswRwSatOut sat_out;
  FswRwVoltIn volt_in;
  FswRwVoltOut volt_out;
  FswThrMapIn thr_in;
  FswThrMapOut thr_out;
  FswThrPulseRemIn rem_in;
  FswThrPulseRemOut rem_out;
  FswThrPulseSchmittIn sch_in;
  FswThrPulseSchmittOut sch_out;
  FswBdotIn bdot_in;
  FswBdotOut bdot_out;
  FswMtqMapIn mtq_in;
  FswMtqMapOut mtq_out;
  FswMtqDesatIn desat_in;
  FswMtqDesatOut desat_out;
  FswThrMomentumIn mom_in;
  FswThrMomentumOut mom_out;
  FswRwBiasIn bias_in;
  FswRwBiasOut bias_out;
  FswGuidOrbitIn orbit_in;
  FswGuidOrbitOut orbit_out;
  /* The thruster on-times the last good cycle commanded (thr_momentum's
   * propellant count); zero after an error or a cycle without thrusters. */
  fsw_real t_on_last[FSW_MAX_THR];
  /* The dynamic state as it was before the stages ran; a cycle that ends
   * in an error puts it back (health counters excepted), so an error cycle
   * advances no state (docs/fsw-conventions.md, "The contract"). */
  struct {
    int mode, actuation;
    uint32_t mode_changes;
    FswMrpFbState mrp_fb;
    FswTrqLpfState lpf;
    FswRwVoltState rw_volt;
    fsw_real thr_ang_err;
    int thr_nnls_iter;
    FswThrPulseRemState pulse_rem;
    FswThrPulseSchmittState pulse_schmitt;
    uint8_t null_avail[FSW_MAX_RW]; /* rw_null projector mask */
    FswRwSpeedFilterState speed_filter;
    fsw_real sigma_R0N[3], K, P;     /* commanded reference and gains */
    FswGuidInertialState inertial;
    int policy, cmd_mode;
    FswBdotState bdot;
    fsw_real B_hold[3];
    uint8_t B_hold_ok;
    FswThrMomentumState thr_mom;
    uint8_t bias_in_band[FSW_MAX_RW]; /* rw_bias hysteresis (its projector and
                                         basis are derived from the mask) */
    FswGuidOrbitState orbit;
    fsw_real t_on_last[FSW_MAX_THR];
  } saved;
} FswAcsWork;

typedef struct {
  int ready;            /* [-]  1 after a successful init                      */
  int mode;             /* [-]  FswAcsMode in force                            */
  int actuation;        /* [-]  FswAcsActuation in force                       */
  FswClock clock;       /* [-]  previous accepted cycle (fsw_clock.h)         */
  uint32_t cycles;      /* [-]  accepted (non-error) cycles since init         */
  uint32_t mode_changes;/* [-]  transitions since init                         */
  FswCssSunState css;
  FswGuidSunsafeState sunsafe;
  FswGuidInertialState inertial;
  FswAttTrackState track;
  FswMrpFbState mrp_fb;
  FswTrqLpfState lpf;
  FswRwMapState rw_map;
  FswRwNullState rw_null;
  FswRwSatState rw_sat;
  FswRwVoltState rw_volt;
  FswRwSpeedFilterState speed_filter;
  /* The configurations in force for guid_inertial and mrp_fb: the
   * configuration's, with the reference and gains of the last set command
   * (FswAcsCmdMsg set_ref, set_gains); reset restores the configuration's. */
  FswGuidInertialConfig inertial_cfg;
  FswMrpFbConfig mrp_cfg;
  FswThrMapState thr_map;
  FswThrPulseRemState pulse_rem;
  FswThrPulseSchmittState pulse_schmitt;
  int policy;           /* [-]  FswAcsMomentumPolicy in force                  */
  int cmd_mode;         /* [-]  the mode last commanded (init: initial_mode): a
                                command acts when its mode differs from it     */
  FswBdotState bdot;
  fsw_real B_hold[3];   /* [T]  last valid field sample (DETUMBLE: the rods map
                                bdot's held dipole over a missed sample)       */
  uint8_t B_hold_ok;    /* [-]  B_hold holds a sample                          */
  FswMtqMapState mtq_map;
  FswMtqDesatState mtq_desat;
  FswThrMomentumState thr_mom;
  FswRwBiasState rw_bias;
  FswGuidOrbitState orbit;
  FswAcsWork work;
  FswHealth health;
} FswAcsState;

/* Writes the geometry into every module config that holds a copy:
 *   wheels:    has_wheels = (num_rw > 0); num_rw, gs_hat_B and J_s of mrp_fb
 *              (the wheels in H); num_rw and gs_hat_B of rw_map; num_rw,
 *              gs_hat_B and u_max of rw_null; num_rw and u_max of rw_sat;
 *              num_rw, u_max and J_s of rw_volt and of speed_filter;
 *   thrusters: has_thrusters = (num_thr > 0); num_thr, r_thr_B, gt_hat_B and
 *              F_max of thr_map and common.num_thr and common.F_max of both
 *              pulsers (pulse_rem, pulse_schmitt).
 * Entries beyond the counts are set to 0.  Nothing else is touched (gains,
 * modes, use_* flags, the pulser's t_min ...).  Values are not checked here:
 * fsw_acs_check() does that.  Returns FSW_OK; FSW_E_CAPACITY (num_rw >
 * FSW_MAX_RW or num_thr > FSW_MAX_THR), FSW_E_CONFIG (a negative count) and
 * FSW_E_NULL_ARG leave cfg unchanged. */
FswStatus fsw_acs_config_set_geometry(FswAcsConfig *cfg, const FswAcsGeometry *geo);

/* Name of a stage (FswAcsStage) for telemetry and logs, e.g. "rw_map";
 * "unknown" for a value outside 0..FSW_ACS_NUM_STAGES-1.  Never NULL; the
 * strings are constant. */
const char *fsw_acs_stage_name(int stage);

/* Validates the whole configuration.  On failure, *bad_field (if not NULL)
 * receives the name of the first bad field, e.g. "initial_mode" or
 * "rw_map" (a module config that its own _check rejected; the status is
 * that module's) or a cross-module field such as "speed_filter.u_max" (with
 * use_speed_filter, each wheel's filter limit must be >= its rw_sat.u_max:
 * the filter refuses an applied torque above 2 of its u_max).  On success
 * *bad_field = NULL. */
FswStatus fsw_acs_check(const FswAcsConfig *cfg, const char **bad_field);

/* check + init of every module used; on failure the state is not ready. */
FswStatus fsw_acs_init(FswAcsState *st, const FswAcsConfig *cfg, const char **bad_field);

/* Back to the post-init mode with all dynamic state cleared. */
void fsw_acs_reset(FswAcsState *st, const FswAcsConfig *cfg);

/* One control cycle.  `cmd` may be NULL (keep the current mode).  Always
 * writes `act` fully and `hlth` fully.  Returns the cycle status (also in
 * hlth->status): FSW_OK or a warning with valid commands; an error with the
 * safe output (FSW_E_BAD_INPUT: non-finite sensor values, an available
 * wheel's speed beyond +-FSW_RW_OMEGA_MAX without the speed filter (with it,
 * such a speed is an outlier of that wheel), or an invalid mode
 * request or set command (a flag not 0/1, a non-finite reference, a gain
 * not finite and > 0), or a stage's error such as an overflow of finite sensor values;
 * FSW_E_TIME: t_ns not after the previous cycle; FSW_E_NOT_INIT).  An error
 * cycle advances no state at all: mode, clock, cycle count, commanded
 * reference and gains and every stage's memory are as before the call (only health counters and the
 * scratch `work` change), so a good retry at the same t_ns is accepted.
 * An error cycle's `hlth` is the safe health message: all 0 except status,
 * safe_output = 1, mode, actuation, policy, counters, rw_failed/rw_latched
 * and health as restored, and stage_status[] (which stage failed). */
FswStatus fsw_acs_cycle(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                        const FswAcsCmdMsg *cmd, FswAcsActuatorMsg *act, FswAcsHealthMsg *hlth);

#ifdef __cplusplus
}
#endif

#endif /* FSW_ACS_H */

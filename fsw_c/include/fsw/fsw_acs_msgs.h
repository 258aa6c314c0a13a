/* fsw_acs_msgs: the messages of the FSW application fsw_acs.
 * Plain C structs, one per direction, shared by the flight executive, the
 * desktop harness, a hardware-in-the-loop process and the target tests:
 *   FswAcsSensorMsg   sensors -> FSW          (one per control cycle)
 *   FswAcsCmdMsg      ground/executive -> FSW (mode requests)
 *   FswAcsActuatorMsg FSW -> actuators        (wheel torques/voltages, thruster on-times)
 *   FswAcsHealthMsg   FSW -> executive/telemetry (everything an integrator
 *                     reads; the state's work area is private by convention)
 * Frames: B body, N inertial.  Units: SI, time in ns. */
#ifndef FSW_ACS_MSGS_H
#define FSW_ACS_MSGS_H

#include <stdint.h>

#include "fsw/css_sun.h" /* FSW_MAX_CSS */
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Pointing modes. */
typedef enum {
  FSW_ACS_MODE_SUN_SAFE = 0, /* point s_cmd at the Sun from the CSS heading (or search spin) */
  FSW_ACS_MODE_INERTIAL = 1, /* hold the configured inertial attitude (needs sigma_BN)     */
  FSW_ACS_MODE_DETUMBLE = 2, /* B-dot with the magnetorquers; no attitude control; leaves
                                for the configured pointing mode once detumbled         */
  FSW_ACS_MODE_NADIR = 3     /* follow the orbit frame (needs sigma_BN and r_N, v_N)       */
} FswAcsMode;

/* Momentum management: who unloads the wheels in the pointing modes. */
typedef enum {
  FSW_ACS_MOM_NONE = 0,         /* nobody                                              */
  FSW_ACS_MOM_THRUSTERS = 1,    /* thr_momentum: hysteresis dumps through thr_map      */
  FSW_ACS_MOM_MAGNETORQUERS = 2 /* mtq_desat -> mtq_map: continuous cross-product law */
} FswAcsMomentumPolicy;

/* Actuation chains. */
typedef enum {
  FSW_ACS_ACT_WHEELS = 0,   /* rw_map -> rw_null -> rw_sat -> rw_volt */
  FSW_ACS_ACT_THRUSTERS = 1 /* thr_map -> pulsing                     */
} FswAcsActuation;

typedef struct {
  uint64_t t_ns;                  /* [ns]    time stamp of this cycle, strictly increasing   */
  fsw_real sigma_BN[3];           /* [-]     navigation attitude (star tracker/estimator)    */
  uint8_t att_valid;              /* [-]     1 if sigma_BN is valid (required by INERTIAL)   */
  fsw_real omega_BN_B[3];         /* [rad/s] body rate (gyro), B components, always required */
  fsw_real css[FSW_MAX_CSS];      /* [css units] (num_css) coarse sun sensor readings        */
  uint8_t css_avail[FSW_MAX_CSS]; /* [-]     (num_css) 0 available, 1 unavailable            */
  fsw_real Omega[FSW_MAX_RW];     /* [rad/s] (num_rw) wheel speeds relative to the body      */
  uint8_t rw_avail[FSW_MAX_RW];   /* [-]     (num_rw) 0 available, 1 unavailable             */
  fsw_real r_CoM_B[3];            /* [m]     centre of mass, B (thruster mapping)            */
  uint8_t thr_avail[FSW_MAX_THR]; /* [-]     (num_thr) 0 available, 1 unavailable: a thruster
                                             flagged failed is mapped as absent and kept off */
  fsw_real B_B[3];                /* [T]     magnetometer field in B (the executive rotates the
                                             sensor's reading into B), read when mag_valid = 1 */
  uint8_t mag_valid;              /* [-]     1 if B_B is a fresh valid sample                 */
  fsw_real r_N[3];                /* [m]     position relative to the central body, N (GNSS or
                                             orbit propagator), read when orbit_valid = 1    */
  fsw_real v_N[3];                /* [m/s]   velocity, N                                      */
  uint8_t orbit_valid;            /* [-]     1 if r_N, v_N are valid (required by NADIR)      */
} FswAcsSensorMsg;

/* A ground/executive command.  Mode and actuation are always requested;
 * the reference and gain fields are "set" commands, applied when their flag
 * is 1 at the start of the cycle that receives them and held until another
 * such command or a reset (fsw_acs_reset: back to the configuration).
 * Sending the same command every cycle is harmless (a link node does). */
typedef struct {
  int mode;              /* [-]     requested FswAcsMode; acts only when it differs
                                    from the mode last commanded (edge-triggered: a
                                    repeated command does not undo DETUMBLE's exit)   */
  int actuation;         /* [-]     requested FswAcsActuation                         */
  uint8_t set_ref;       /* [-]     0/1: the inertial reference becomes sigma_R0N     */
  fsw_real sigma_R0N[3]; /* [-]     new reference R0 relative to N (MRP, finite,
                                    shadow-switched), read when set_ref = 1           */
  uint8_t set_gains;     /* [-]     0/1: mrp_fb's K and P become the two below        */
  fsw_real K;            /* [N*m]   attitude gain, finite, > 0 (set_gains = 1)        */
  fsw_real P;            /* [N*m*s] rate gain, finite, > 0 (set_gains = 1)            */
  uint8_t set_policy;    /* [-]     0/1: the momentum policy becomes `policy`          */
  int policy;            /* [-]     FswAcsMomentumPolicy (set_policy = 1); the actuators
                                    it needs must be configured                      */
} FswAcsCmdMsg;

typedef struct {
  fsw_real Lr_B[3];            /* [N*m] control torque request (after the optional filter)  */
  fsw_real u_s[FSW_MAX_RW];    /* [N*m] (num_rw) wheel motor torques (0 in thruster mode)   */
  fsw_real V[FSW_MAX_RW];      /* [V]   (num_rw) wheel motor voltages (if use_volt, else 0)  */
  fsw_real F[FSW_MAX_THR];     /* [N]   (num_thr) thruster force command (telemetry)         */
  fsw_real t_on[FSW_MAX_THR];  /* [s]   (num_thr) thruster on-times from this cycle's start  */
  uint8_t wheels_active;       /* [-]   1 if u_s/V are to be applied                         */
  uint8_t thrusters_active;    /* [-]   1 if t_on is to be applied                           */
  fsw_real m_cmd[FSW_MAX_MTQ]; /* [A*m^2] (num_mtq) rod dipole commands, the mean over the
                                  period (<= duty_max m_max: PWM on-time |m|/m_max T)     */
  uint8_t mtq_active;          /* [-]   1 if m_cmd is to be applied (0: rods off)             */
} FswAcsActuatorMsg;

/* Stages of the cycle, for per-stage status telemetry.  Their names come
 * from fsw_acs_stage_name() (fsw_acs.h). */
typedef enum {
  FSW_ACS_STAGE_CSS = 0,
  FSW_ACS_STAGE_GUIDANCE,
  FSW_ACS_STAGE_TRACK,
  FSW_ACS_STAGE_CONTROL,
  FSW_ACS_STAGE_LPF,
  FSW_ACS_STAGE_RW_MAP,
  FSW_ACS_STAGE_RW_NULL,
  FSW_ACS_STAGE_RW_SAT,
  FSW_ACS_STAGE_RW_VOLT,
  FSW_ACS_STAGE_THR_MAP,
  FSW_ACS_STAGE_THR_PULSE,
  FSW_ACS_STAGE_BDOT,
  FSW_ACS_STAGE_MTQ_DESAT,
  FSW_ACS_STAGE_MTQ_MAP,
  FSW_ACS_STAGE_THR_MOM,
  FSW_ACS_STAGE_RW_BIAS,
  FSW_ACS_NUM_STAGES
} FswAcsStage;

typedef struct {
  FswStatus status;                         /* [-]   status of the cycle (worst of the stages) */
  int mode;                                 /* [-]   FswAcsMode in force after the cycle        */
  int actuation;                            /* [-]   FswAcsActuation in force after the cycle   */
  uint8_t safe_output;                      /* [-]   1: the actuator message is the safe output */
  uint32_t cycles;                          /* [-]   accepted cycles since init                 */
  uint32_t mode_changes;                    /* [-]   mode/actuation transitions since init      */
  FswStatus stage_status[FSW_ACS_NUM_STAGES]; /* [-] status of each stage this cycle (FSW_OK if not run) */
  fsw_real sigma_BR[3];                     /* [-]     attitude error                            */
  fsw_real omega_BR_B[3];                   /* [rad/s] rate error                                */
  fsw_real att_err_angle;                   /* [rad]   principal angle of sigma_BR               */
  fsw_real sun_angle_err;                   /* [rad]   sun-safe angle error (SUN_SAFE)            */
  fsw_real sun_hat_B[3];                    /* [-]     CSS Sun heading the cycle used, B (unit
                                                       when sun_valid; 0 when not, in INERTIAL
                                                       and on a rejected cycle)                  */
  uint8_t sun_valid;                        /* [-]     CSS heading valid this cycle              */
  uint8_t num_lit;                          /* [-]     lit CSS                                   */
  uint64_t rw_failed;                       /* [-]     bit i: wheel i failed by the FSW's speed
                                                       filter (unavailable to every stage); 0
                                                       without the filter                        */
  uint64_t rw_latched;                      /* [-]     bit i: ... by its stale or torque test
                                                       (held until the application is reset)     */
  int policy;                               /* [-]     FswAcsMomentumPolicy in force             */
  uint8_t detumbled;                        /* [-]     bdot's detumble-complete flag (DETUMBLE)  */
  uint8_t dump_phase;                       /* [-]     FswThrMomPhase of thr_momentum            */
  fsw_real h_w_B[3];                        /* [N*m*s] wheel momentum, B (available wheels)   */
  fsw_real rate_est;                        /* [rad/s] bdot's rate estimate (DETUMBLE)        */
  fsw_real tau_mtq_B[3];                    /* [N*m]   magnetic torque the rods' commands make
                                                       with this cycle's field               */
  uint32_t dumps;                           /* [-]     completed thruster dumps               */
  fsw_real prop_used;                       /* [kg]    propellant of the dumps since init     */
  FswHealth health;                         /* [-]     counters of the application              */
} FswAcsHealthMsg;

#ifdef __cplusplus
}
#endif

#endif /* FSW_ACS_MSGS_H */

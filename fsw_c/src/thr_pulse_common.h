/* thr_pulse_common: internal pieces shared by the thruster pulsing modules
 * (thr_pulse_rem, thr_pulse_schmitt, thr_pulse_round): config checks, the
 * timing model of fsw-algorithms.md 0.3, the first-call output and the
 * force -> on-time conversion of 9 steps 1-2.  Not a public header. */
#ifndef FSW_THR_PULSE_COMMON_H
#define FSW_THR_PULSE_COMMON_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

/* A saturated thruster is commanded on for THR_PULSE_SAT_FACTOR times the
 * control period (Basilisk's 1.1): "on through the whole period"; the plant
 * clips the command at the next command.  [-] */
#define THR_PULSE_SAT_FACTOR FSW_R(1.1)

/* Base thrust state b (9): 0 on-pulsing, 1 off-pulsing. */
#define THR_PULSE_ON_PULSING 0
#define THR_PULSE_OFF_PULSING 1

/* Result of the timing step. */
typedef enum {
  THR_PULSE_FIRST = 0, /* first call after reset: no period yet            */
  THR_PULSE_STEP = 1   /* a later call: *dt holds the period (> 0)        */
} ThrPulseTiming;

/* Common config checks: count (FSW_E_CONFIG below 1, FSW_E_CAPACITY above
 * FSW_MAX_THR), t_min (finite; > 0 if t_min_positive, else >= 0),
 * F_max[0..num_thr-1] finite and > 0.  Returns FSW_OK or the status. */
FswStatus fsw_thr_pulse_check_common(int num_thr, fsw_real t_min, int t_min_positive,
                                 const fsw_real *F_max);

/* Base thrust state b in {0, 1} and initOffPulseOnTime finite and >= 0. */
FswStatus fsw_thr_pulse_check_base(int base_thrust_state, fsw_real init_off_pulse_on_time);

/* Timing model 0.3: on a first call returns THR_PULSE_FIRST (dt = 0);
 * otherwise dt = (t_ns - t_prev_ns) * 1e-9 s and THR_PULSE_STEP, or
 * FSW_E_TIME (returned as a negative status through *status) when t_ns is
 * not after t_prev_ns.  Changes nothing. */
FswStatus fsw_thr_pulse_timing(int has_prev, uint64_t t_prev_ns, uint64_t t_ns,
                           ThrPulseTiming *timing, fsw_real *dt);

/* Safe output: every entry of t_on (FSW_MAX_THR) set to 0. */
void fsw_thr_pulse_safe_output(fsw_real t_on[FSW_MAX_THR]);

/* First-call output of 9/10: t_on,i = b * initOffPulseOnTime for i < n. */
void fsw_thr_pulse_first_output(fsw_real t_on[FSW_MAX_THR], int n, int base_thrust_state,
                            fsw_real init_off_pulse_on_time);

/* 9 steps 1-2 without the remainder: f = F (+ F_max if b = 1), clipped at
 * 0; returns (f / F_max) * dt. */
/* The shared start of every pulser update, after its NULL checks: readiness,
 * finite forces (n entries) and, when use_time, the timing model of
 * fsw-algorithms.md 0.3 (*timing, *dt).  Returns FSW_OK to go on; any other
 * status has already been counted in *health and is for the caller to
 * return with the safe output it wrote.  Changes no module state. */
FswStatus fsw_thr_pulse_begin(int ready, FswHealth *health, const fsw_real *F, int n, int use_time,
                              int has_prev, uint64_t t_prev_ns, uint64_t t_ns,
                              ThrPulseTiming *timing, fsw_real *dt);

fsw_real fsw_thr_pulse_on_time(fsw_real F, fsw_real F_max, int base_thrust_state, fsw_real dt);

#endif /* FSW_THR_PULSE_COMMON_H */

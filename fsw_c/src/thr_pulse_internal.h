/* thr_pulse_internal: internal pieces shared by the thruster pulsing modules
 * (thr_pulse_rem, thr_pulse_schmitt, thr_pulse_round): config checks, the
 * shared start and end of an update (readiness, input check, the timing
 * model of docs/fsw-conventions.md, "Timing" through fsw_clock, health), the first-call
 * output and the force -> on-time conversion of 9 steps 1-2.  Not a public
 * header; the public parts are in fsw/thr_pulse_common.h. */
#ifndef FSW_THR_PULSE_INTERNAL_H
#define FSW_THR_PULSE_INTERNAL_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/thr_pulse_common.h"

/* A saturated thruster is commanded on for THR_PULSE_SAT_FACTOR times the
 * control period (Basilisk's 1.1): "on through the whole period"; the plant
 * clips the command at the next command.  [-] */
#define THR_PULSE_SAT_FACTOR FSW_R(1.1)

/* Base thrust state b (9): 0 on-pulsing, 1 off-pulsing. */
#define THR_PULSE_ON_PULSING 0
#define THR_PULSE_OFF_PULSING 1

/* Thruster count (FSW_E_CONFIG below 1, FSW_E_CAPACITY above FSW_MAX_THR)
 * and F_max[0..num_thr-1] finite and > 0.  Returns FSW_OK or the status. */
FswStatus fsw_thr_pulse_check_thrusters(int num_thr, const fsw_real *F_max);

/* The whole FswThrPulseCommon: count, t_min finite and > 0, F_max, base
 * thrust state b in {0, 1}, init_off_pulse_on_time finite and >= 0. */
FswStatus fsw_thr_pulse_check_common(const FswThrPulseCommon *c);

/* First half of every pulser init: ready = 0, health cleared, clock reset.
 * The module then resets its own memory, checks its config and, on success,
 * sets cs->ready = 1. */
void fsw_thr_pulse_init_common(FswThrPulseCommonState *cs);

/* The shared start of every pulser update, after its NULL checks: readiness,
 * finite forces (n entries) and, when use_time, the timing model of
 * docs/fsw-conventions.md, "Timing" (*dt = 0 on the first call after reset, which the
 * caller recognises by !cs->clock.has_prev).  Returns FSW_OK to go on; any
 * other status has already been counted in cs->health and is for the caller
 * to return with the safe output it wrote.  Changes no module state. */
FswStatus fsw_thr_pulse_begin(FswThrPulseCommonState *cs, const fsw_real *F, int n, int use_time,
                              uint64_t t_ns, fsw_real *dt);

/* The shared end of an accepted update: commits the time stamp when
 * use_time, records FSW_W_SAT (saturated) or FSW_OK and returns it. */
FswStatus fsw_thr_pulse_end(FswThrPulseCommonState *cs, int use_time, uint64_t t_ns, int saturated);

/* Safe output: every entry of t_on (FSW_MAX_THR) set to 0. */
void fsw_thr_pulse_safe_output(fsw_real t_on[FSW_MAX_THR]);

/* First-call output of 9/10: t_on,i = b * initOffPulseOnTime for i < n. */
void fsw_thr_pulse_first_output(fsw_real t_on[FSW_MAX_THR], const FswThrPulseCommon *c);

/* 9 steps 1-2 without the remainder: f = F (+ F_max if b = 1), clipped at
 * 0; returns (f / F_max) * dt. */
fsw_real fsw_thr_pulse_on_time(fsw_real F, fsw_real F_max, int base_thrust_state, fsw_real dt);

#endif /* FSW_THR_PULSE_INTERNAL_H */

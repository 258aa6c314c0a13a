/* thr_pulse_rem: thruster pulsing with remainder tracking
 * (docs/fsw/thr_pulse_rem.md, Basilisk thrFiringRemainder).  Turns per-thruster force commands into
 * on-times for one control period; requests shorter than the minimum
 * on-time are carried over (in units of t_min) and delivered later.
 * Units: SI.
 *
 * First call after reset (no period yet): t_on = b * init_off_pulse_on_time
 * for every thruster; attitude control is skipped for one period.
 * Saturated thrusters (t >= period) get 1.1 * period ("on through the
 * period"; the excess is discarded, not carried).
 * Safe output: every thruster off (t_on = 0), no state advanced.  Entries
 * at and beyond num_thr are always exactly 0. */
#ifndef FSW_THR_PULSE_REM_H
#define FSW_THR_PULSE_REM_H

#include <stdint.h>

#include "fsw/fsw_config.h"       /* FSW_MAX_THR, fsw_real */
#include "fsw/fsw_status.h"       /* FswStatus, FswHealth */
#include "fsw/thr_pulse_common.h" /* FswThrPulseCommon, FswThrPulseCommonState */

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  FswThrPulseCommon common;        /* num_thr, F_max, t_min, b, init on-time    */
} FswThrPulseRemConfig;

typedef struct {
  FswThrPulseCommonState common;   /* ready, clock, health                      */
  fsw_real rem[FSW_MAX_THR];       /* [-] (num_thr) remainder rho_i, in t_min   */
} FswThrPulseRemState;

typedef struct {
  uint64_t t_ns;                   /* [ns] time of this call                    */
  fsw_real F[FSW_MAX_THR];         /* [N] (num_thr) force command from thr_map  */
} FswThrPulseRemIn;

typedef struct {
  fsw_real t_on[FSW_MAX_THR];      /* [s] (num_thr) on-time command; rest 0     */
} FswThrPulseRemOut;

/* FSW_E_CAPACITY: num_thr > FSW_MAX_THR; FSW_E_CONFIG: anything else. */
FswStatus fsw_thr_pulse_rem_check(const FswThrPulseRemConfig *cfg);
FswStatus fsw_thr_pulse_rem_init(FswThrPulseRemState *st, const FswThrPulseRemConfig *cfg);
/* Zero the remainders and forget the previous call. */
void fsw_thr_pulse_rem_reset(FswThrPulseRemState *st);
/* FSW_OK; FSW_W_SAT when a request exceeded the period (excess lost);
 * FSW_E_BAD_INPUT (NaN/Inf force); FSW_E_TIME (t_ns not after the previous
 * call); FSW_E_NOT_INIT; FSW_E_NULL_ARG.  Errors give the safe output. */
FswStatus fsw_thr_pulse_rem_update(FswThrPulseRemState *st, const FswThrPulseRemConfig *cfg,
                                   const FswThrPulseRemIn *in, FswThrPulseRemOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_THR_PULSE_REM_H */

/* thr_pulse_schmitt: thruster pulsing with a Schmitt trigger
 * (docs/fsw/thr_pulse_schmitt.md, Basilisk thrFiringSchmitt).  On-times shorter than
 * the minimum on-time t_min are decided by hysteresis on the duty level
 * l = t / t_min: l >= level_on fires t_min, l <= level_off stays off, in
 * between the thruster keeps its previous decision.  Units: SI.
 *
 * First call after reset: t_on = b * init_off_pulse_on_time (as in thr_pulse_rem).
 * Saturated thrusters (t >= period) get 1.1 * period (they stay on
 * through the period, docs/fsw/thr_pulse_schmitt.md).  The minimum pulse is min(t_min, period): when the
 * call period is shorter than t_min a minimum pulse lasts the period.
 * Safe output: every thruster off (t_on = 0), no state advanced.  Entries
 * at and beyond num_thr are always exactly 0. */
#ifndef FSW_THR_PULSE_SCHMITT_H
#define FSW_THR_PULSE_SCHMITT_H

#include <stdint.h>

#include "fsw/fsw_config.h"       /* FSW_MAX_THR, fsw_real */
#include "fsw/fsw_status.h"       /* FswStatus, FswHealth */
#include "fsw/thr_pulse_common.h" /* FswThrPulseCommon, FswThrPulseCommonState */

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  FswThrPulseCommon common;        /* num_thr, F_max, t_min, b, init on-time    */
  fsw_real level_on;               /* [-] duty level that switches on, <= 1     */
  fsw_real level_off;              /* [-] duty level that switches off,
                                      0 <= level_off < level_on                 */
} FswThrPulseSchmittConfig;

typedef struct {
  FswThrPulseCommonState common;   /* ready, clock, health                      */
  uint8_t last_on[FSW_MAX_THR];    /* [-] (num_thr) hysteresis memory, 0 = off  */
} FswThrPulseSchmittState;

typedef struct {
  uint64_t t_ns;                   /* [ns] time of this call                    */
  fsw_real F[FSW_MAX_THR];         /* [N] (num_thr) force command from thr_map  */
} FswThrPulseSchmittIn;

typedef struct {
  fsw_real t_on[FSW_MAX_THR];      /* [s] (num_thr) on-time command; rest 0     */
} FswThrPulseSchmittOut;

/* FSW_E_CAPACITY: num_thr > FSW_MAX_THR; FSW_E_CONFIG: anything else. */
FswStatus fsw_thr_pulse_schmitt_check(const FswThrPulseSchmittConfig *cfg);
FswStatus fsw_thr_pulse_schmitt_init(FswThrPulseSchmittState *st,
                                     const FswThrPulseSchmittConfig *cfg);
/* Every thruster's memory to off; forget the previous call. */
void fsw_thr_pulse_schmitt_reset(FswThrPulseSchmittState *st);
/* FSW_OK; FSW_W_SAT when a request exceeded the period; FSW_E_BAD_INPUT;
 * FSW_E_TIME; FSW_E_NOT_INIT; FSW_E_NULL_ARG.  Errors: safe output. */
FswStatus fsw_thr_pulse_schmitt_update(FswThrPulseSchmittState *st,
                                       const FswThrPulseSchmittConfig *cfg,
                                       const FswThrPulseSchmittIn *in,
                                       FswThrPulseSchmittOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_THR_PULSE_SCHMITT_H */

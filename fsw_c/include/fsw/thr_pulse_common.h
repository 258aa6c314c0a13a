/* thr_pulse_common: the parts every thruster pulser shares
 * (docs/fsw/thr_pulse_rem.md, thr_pulse_schmitt.md, thr_pulse_round.md).
 *  - FswThrPulseCommon: the configuration of the pulse-width pulsers
 *    thr_pulse_rem and thr_pulse_schmitt, embedded in their configs
 *    as `common`.  thr_pulse_round has no base thrust state and no
 *    first-call on-time and accepts t_min = 0, so it keeps its own fields.
 *  - FswThrPulseCommonState: readiness, the timing step of 0.3 and the health
 *    counters, embedded in the state of all three pulsers as `common`.
 * Units: SI. */
#ifndef FSW_THR_PULSE_COMMON_H
#define FSW_THR_PULSE_COMMON_H

#include "fsw/fsw_clock.h"  /* FswClock */
#include "fsw/fsw_config.h" /* FSW_MAX_THR, fsw_real */
#include "fsw/fsw_status.h" /* FswHealth */

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  int num_thr;                     /* [-] 1..FSW_MAX_THR                        */
  fsw_real F_max[FSW_MAX_THR];     /* [N] (num_thr) max thrust, > 0             */
  fsw_real t_min;                  /* [s] minimum on-time, > 0                  */
  int base_thrust_state;           /* [-] b: 0 on-pulsing, 1 off-pulsing (DV);
                                      must match thr_map: sign -1 <=> b = 1    */
  fsw_real init_off_pulse_on_time; /* [s] first-call on-time when b = 1, >= 0
                                      (Basilisk: 2.0)                          */
} FswThrPulseCommon;

typedef struct {
  int ready;                       /* [-] 1 once init accepted the config       */
  FswClock clock;                  /* [-] previous accepted call (fsw_clock.h)  */
  FswHealth health;                /* counters read by the harness              */
} FswThrPulseCommonState;

#ifdef __cplusplus
}
#endif

#endif /* FSW_THR_PULSE_COMMON_H */

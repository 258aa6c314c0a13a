/* thr_pulse_round: thruster pulsing by rounding (docs/fsw/thr_pulse_round.md,
 * Basilisk thrFiringRound, a Python module).  On-time = control period T
 * times the force fraction, rounded to the on-time resolution q with
 * round-half-to-even, zeroed below t_min and clipped to [0, T].  Units: SI.
 *
 * Stateless by default: the time stamp is not used and any call order is
 * accepted.  With carry_residual = 1 (library extension) the rounding error
 * r_i is carried to the next call (first-order sigma-delta), and the timing
 * model of docs/fsw-conventions.md, "Timing" applies (t_ns must increase).
 * Safe output: every thruster off (t_on = 0), no state advanced.  Entries
 * at and beyond num_thr are always exactly 0.
 * Basilisk's scalar F_max: write the same value into every F_max entry;
 * Basilisk's default count (36 with a scalar F_max) is num_thr = 36. */
#ifndef FSW_THR_PULSE_ROUND_H
#define FSW_THR_PULSE_ROUND_H

#include <stdint.h>

#include "fsw/fsw_config.h"       /* FSW_MAX_THR, fsw_real */
#include "fsw/fsw_status.h"       /* FswStatus, FswHealth */
#include "fsw/thr_pulse_common.h" /* FswThrPulseCommonState */

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  int num_thr;                 /* [-] 1..FSW_MAX_THR                          */
  fsw_real F_max[FSW_MAX_THR]; /* [N] (num_thr) max thrust, > 0 (Basilisk 1) */
  fsw_real period;             /* [s] control period T, > 0 (Basilisk 1)      */
  fsw_real resolution;         /* [s] on-time resolution q, > 0 (Basilisk 0.01) */
  fsw_real t_min;              /* [s] minimum on-time, 0 <= t_min <= period
                                   (Basilisk 0)                              */
  int carry_residual;          /* [-] 0 (Basilisk) or 1: carry rounding error */
} FswThrPulseRoundConfig;

typedef struct {
  FswThrPulseCommonState common; /* ready, clock (carry mode only), health    */
  fsw_real resid[FSW_MAX_THR]; /* [s] (num_thr) carried residual r_i, in [-T, T] */
} FswThrPulseRoundState;

typedef struct {
  uint64_t t_ns;               /* [ns] time of this call (carry mode only)    */
  fsw_real F[FSW_MAX_THR];     /* [N] (num_thr) force command; rest ignored   */
} FswThrPulseRoundIn;

typedef struct {
  fsw_real t_on[FSW_MAX_THR];  /* [s] (num_thr) on-time command; rest 0       */
} FswThrPulseRoundOut;

/* FSW_E_CAPACITY: num_thr > FSW_MAX_THR; FSW_E_CONFIG: anything else. */
FswStatus fsw_thr_pulse_round_check(const FswThrPulseRoundConfig *cfg);
FswStatus fsw_thr_pulse_round_init(FswThrPulseRoundState *st, const FswThrPulseRoundConfig *cfg);
/* Zero the residuals and forget the previous call. */
void fsw_thr_pulse_round_reset(FswThrPulseRoundState *st);
/* FSW_OK; FSW_W_SAT when a request exceeded the period; FSW_E_BAD_INPUT;
 * FSW_E_TIME (carry mode only); FSW_E_NOT_INIT; FSW_E_NULL_ARG.  Errors:
 * safe output. */
FswStatus fsw_thr_pulse_round_update(FswThrPulseRoundState *st, const FswThrPulseRoundConfig *cfg,
                                     const FswThrPulseRoundIn *in, FswThrPulseRoundOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_THR_PULSE_ROUND_H */

/* fsw_clock: the timing step of docs/fsw-conventions.md, "Timing", shared by every
 * stateful module.  A module receives the sample time t_ns in its In struct
 * (it never reads a clock and is never handed dt) and derives dt here:
 *   - the first call after reset is legal at any t_ns, including 0 (an
 *     explicit has_prev flag, no time sentinel), and has dt = 0;
 *   - a later call needs t_ns > t_prev_ns, else FSW_E_TIME;
 *   - dt = (fsw_real)(t_ns - t_prev_ns) * 1e-9 s (the integer difference
 *     first, so dt carries no accumulated round-off; fsw_clock_ns_to_s).
 * Use: fsw_clock_dt() before any state is touched; fsw_clock_commit() once
 * the call is accepted (an error path never commits); fsw_clock_reset() from
 * the module's _reset.  Units: ns in, s out. */
#ifndef FSW_CLOCK_H
#define FSW_CLOCK_H

#include <stdint.h>

#include "fsw/fsw_config.h" /* fsw_real */
#include "fsw/fsw_status.h" /* FswStatus */

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  int has_prev;       /* [-]  a call has been accepted since reset        */
  uint64_t t_prev_ns; /* [ns] time stamp of that call (0 while has_prev = 0) */
} FswClock;

/* The period since the previous accepted call.  FSW_OK with *dt = 0 on the
 * first call after reset; FSW_OK with *dt > 0 when t_ns > t_prev_ns;
 * FSW_E_TIME with *dt = 0 when t_ns <= t_prev_ns; FSW_E_NULL_ARG (dt = 0 if
 * dt is not NULL).  Changes nothing. */
FswStatus fsw_clock_dt(const FswClock *clk, uint64_t t_ns, fsw_real *dt);

/* Record an accepted call at t_ns: has_prev = 1, t_prev_ns = t_ns. */
void fsw_clock_commit(FswClock *clk, uint64_t t_ns);

/* Forget the previous call: has_prev = 0, t_prev_ns = 0. */
void fsw_clock_reset(FswClock *clk);

/* Seconds of a time-stamp difference: (fsw_real)d_ns * 1e-9, the same bits
 * as that expression (the conversion rounds to nearest, ties to even).  In
 * single precision it converts through 32-bit integers, which the
 * Cortex-M4F's FPU converts itself, instead of the 64-bit conversion
 * routine of the compiler's run-time library (540 B of soft-float code). */
fsw_real fsw_clock_ns_to_s(uint64_t d_ns);

#ifdef __cplusplus
}
#endif

#endif /* FSW_CLOCK_H */

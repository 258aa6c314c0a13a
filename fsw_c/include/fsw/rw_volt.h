/* rw_volt: wheel motor torque -> voltage with the optional speed loop
 * (docs/fsw/rw_volt.md, Basilisk rwMotorVoltage).
 * Speed loop (only when has_Omega = 1; phase p = 0 after reset):
 *   p = 0 -> p = 1 (no speeds stored); p = 1 -> Omega_prev = Omega, p = 2;
 *   p = 2 -> for available i: Omega_dot = (Omega - Omega_prev)/dt,
 *            u_i <- u_i - K_V (J_s,i Omega_dot - u_i); Omega_prev = Omega.
 *   A call without speeds returns the loop to p = 0 (stale Omega_prev is
 *   never differenced).
 * Outlier gate (library extension, gate_rate = 1): if |Omega_dot_i| >
 *   Omega_dot_max_i the correction of wheel i is skipped for this call
 *   (Omega_prev is still updated) and bit i of `fault` is set.
 * Feed-forward: V_i = (V_max - V_min)/u_max_i * u_i, then +V_min if V_i > 0,
 *   -V_min if V_i < 0 (exact 0 stays 0), clipped to [-V_max, V_max].
 * Unavailable wheels get exactly 0 V.  Units: SI.
 * Safe output (bad input, bad time, not initialised): V = 0, fault = 0. */
#ifndef FSW_RW_VOLT_H
#define FSW_RW_VOLT_H

#include <stdint.h>

#include "fsw/fsw_clock.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/rw_common.h" /* physical ranges */

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  int num_rw;                         /* [-]       1..FSW_MAX_RW (<= 64)           */
  fsw_real V_min;                     /* [V]       dead-band jump, >= 0            */
  fsw_real V_max;                     /* [V]       > V_min, <= FSW_RW_V_MAX_MAX    */
  fsw_real K_V;                       /* [-]       speed-loop gain, 0..FSW_RW_GAIN_MAX
                                         (Basilisk's header says V/N*m: wrong)     */
  fsw_real u_max[FSW_MAX_RW];         /* [N*m]     (num_rw) torque at V_max,
                                         FSW_RW_U_MAX_MIN..FSW_RW_U_MAX_MAX       */
  fsw_real J_s[FSW_MAX_RW];           /* [kg*m^2]  (num_rw) spin inertia,
                                         > 0, <= FSW_RW_J_S_MAX (rw_common.h)     */
  int gate_rate;                      /* [-]       0 (default) or 1: outlier gate  */
  fsw_real Omega_dot_max[FSW_MAX_RW]; /* [rad/s^2] (num_rw) gate, > 0 if gate_rate */
} FswRwVoltConfig;

typedef struct {
  int ready;
  fsw_real Omega_prev[FSW_MAX_RW]; /* [rad/s] speeds of the previous call */
  uint8_t prev_ok[FSW_MAX_RW];     /* [-] 1 if that speed was a number     */
  int phase;                       /* [-] speed-loop warm-up 0, 1, 2 */
  FswClock clock;                  /* [-] previous accepted call (docs/fsw-conventions.md, "Timing") */
  FswHealth health;
} FswRwVoltState;

typedef struct {
  fsw_real u_s[FSW_MAX_RW];   /* [N*m]   (num_rw) motor torques              */
  fsw_real Omega[FSW_MAX_RW]; /* [rad/s] (num_rw) speeds, read if has_Omega  */
  int has_Omega;              /* [-]     1: speeds supplied (loop enabled)    */
  uint8_t avail[FSW_MAX_RW];  /* [-]     (num_rw) 0 available, 1 unavailable */
  uint64_t t_ns;              /* [ns]    time stamp                           */
} FswRwVoltIn;

typedef struct {
  fsw_real V[FSW_MAX_RW]; /* [V] (num_rw) motor voltages; 0 beyond num_rw   */
  uint64_t fault;         /* [-] bit i: wheel i's speed rate failed the gate,
                             or its correction overflowed (no correction)  */
} FswRwVoltOut;

FswStatus fsw_rw_volt_check(const FswRwVoltConfig *cfg);
FswStatus fsw_rw_volt_init(FswRwVoltState *st, const FswRwVoltConfig *cfg);
void fsw_rw_volt_reset(FswRwVoltState *st);
/* FSW_OK (|V| <= V_max, finite); FSW_W_SAT (a voltage was clipped to
 * V_max); FSW_E_BAD_INPUT (non-finite u or supplied Omega, has_Omega not
 * 0/1, mask entry not 0/1); FSW_E_TIME (t_ns <= previous); FSW_E_NOT_INIT.
 * Errors advance no state (speed memory, phase, clock: all committed only
 * on success).  A speed jump whose rate or correction overflows is an
 * outlier: that wheel gets no correction and its fault bit is set. */
FswStatus fsw_rw_volt_update(FswRwVoltState *st, const FswRwVoltConfig *cfg,
                             const FswRwVoltIn *in, FswRwVoltOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_VOLT_H */

/* rw_speed_filter: wheel-speed (tachometer) outlier rejection.  Library
 * design (docs/fsw/rw_speed_filter.md).
 * Per wheel i, with the last accepted ("good") sample Omega_good at t_good:
 *   bound_i = (u_max_i / J_s,i) (t - t_good) + noise_i
 * A wheel's speed relative to the body changes at most u_max/J_s (the motor
 * torque) plus the body-acceleration term g_s^T omega_dot_BN, which noise_i
 * must cover together with the sensor noise.
 *   accept  |Omega_meas - Omega_good| <= bound_i (finite sample): Omega_good,
 *           t_good <- sample; the run of consecutive rejections restarts.
 *   reject  otherwise, or a NaN/Inf sample or one beyond +-FSW_RW_OMEGA_MAX
 *           (1e4 rad/s, rw_common.h): the output holds Omega_good, the
 *           wheel's rejection counter rises, bit i of `rejected` is set.
 *           Because t_good stays put, the bound widens while rejecting.
 *   fail    after k_reject consecutive rejections the wheel is marked
 *           UNAVAILABLE (bit i of `failed`), and stays so until it recovers.
 *   recover while failed, each finite sample is compared with the previous
 *           finite one (same bound, over their spacing); n_recover samples in
 *           a row that are mutually consistent bring the wheel back, anchored
 *           on the latest sample.  A NaN/Inf sample or an inconsistent one
 *           restarts the count (an inconsistent one counts as its first);
 *           so does a sample beyond +-FSW_RW_OMEGA_MAX.
 * Two latched tests (library extension, issue 14; both off when 0):
 *   stale   n_stale > 0: a wheel whose finite sample equals its previous
 *           finite sample bit for bit n_stale times in a row is failed and
 *           latched (a frozen tachometer: a live one with noise never
 *           repeats; use only with a fresh, noisy sample every call).  Bit
 *           for bit: -0.0 after +0.0 (or the reverse) is not a repeat.
 *   torque  n_window > 0: over a window of n_window calls the accepted speed
 *           change is compared with the change the applied motor torque
 *           explains, sum(u_applied_i dt) / J_s,i; a residual above
 *           resid_tol_i fails and latches the wheel (a frozen or stuck
 *           tachometer, or a motor that does not deliver).  An interval with
 *           u_valid = 0 restarts the window (the torque is not known).
 *   A latched wheel stays failed (output held, UNAVAILABLE) until reset:
 *   the outlier recovery rule does not apply to it.
 * The first finite sample within +-FSW_RW_OMEGA_MAX after reset is accepted
 * as it is (no reference).  Non-finite samples and samples beyond that bound
 * are outliers of one wheel, not bad input of the module: every speed the
 * filter outputs is within +-FSW_RW_OMEGA_MAX.
 * Out.avail = In.avail OR failed.  Units: SI.
 * Safe output (bad time, bad mask, not initialised): Omega = held good values
 * (0 if none, and 0 when not initialised), every wheel UNAVAILABLE. */
#ifndef FSW_RW_SPEED_FILTER_H
#define FSW_RW_SPEED_FILTER_H

#include <stdint.h>

#include "fsw/fsw_clock.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  int num_rw;                 /* [-]        1..FSW_MAX_RW (<= 64)                 */
  fsw_real u_max[FSW_MAX_RW]; /* [N*m]      (num_rw) motor torque limit, > 0      */
  fsw_real J_s[FSW_MAX_RW];   /* [kg*m^2]   (num_rw) spin inertia, > 0            */
  fsw_real noise[FSW_MAX_RW]; /* [rad/s]    (num_rw) margin, finite, >= 0         */
  uint32_t k_reject;          /* [-]        consecutive rejections to fail, >= 1  */
  uint32_t n_recover;         /* [-]        consistent samples to recover, >= 1   */
  uint32_t n_stale;           /* [-]        identical samples in a row to latch;
                                            0: stale test off                      */
  uint32_t n_window;          /* [-]        calls per torque-consistency window;
                                            0: torque test off                     */
  fsw_real resid_tol[FSW_MAX_RW]; /* [rad/s] (num_rw) allowed |measured - explained|
                                            speed change over a window, finite,
                                            >= 0 (checked when n_window > 0)      */
} FswRwSpeedFilterConfig;

typedef struct {
  int ready;
  fsw_real Omega_good[FSW_MAX_RW]; /* [rad/s] last accepted sample           */
  uint64_t t_good_ns[FSW_MAX_RW];  /* [ns]    its time                        */
  fsw_real Omega_cand[FSW_MAX_RW]; /* [rad/s] previous finite sample (failed) */
  uint64_t t_cand_ns[FSW_MAX_RW];  /* [ns]    its time                        */
  uint32_t reject_run[FSW_MAX_RW]; /* [-]     consecutive rejections          */
  uint32_t recover_run[FSW_MAX_RW];/* [-]     consistent samples while failed */
  uint32_t rejections[FSW_MAX_RW]; /* [-]     total rejections (saturating),
                                      kept by reset like the health counters */
  uint8_t has_good[FSW_MAX_RW];    /* [-]     Omega_good valid                */
  uint8_t failed[FSW_MAX_RW];      /* [-]     held UNAVAILABLE by the filter  */
  uint8_t latched[FSW_MAX_RW];     /* [-]     failed by the stale or torque test:
                                      held until reset                      */
  fsw_real last_raw[FSW_MAX_RW];   /* [rad/s] previous finite raw sample      */
  uint8_t has_raw[FSW_MAX_RW];     /* [-]     last_raw valid                   */
  uint32_t stale_run[FSW_MAX_RW];  /* [-]     samples equal to their predecessor */
  uint8_t win_open[FSW_MAX_RW];    /* [-]     a torque window is running      */
  fsw_real win_Omega0[FSW_MAX_RW]; /* [rad/s] accepted sample that opened it  */
  fsw_real win_exp[FSW_MAX_RW];    /* [rad/s] speed change the torque explains */
  uint32_t win_count[FSW_MAX_RW];  /* [-]     intervals in the window         */
  FswClock clock;                  /* [-]     previous accepted call (fsw_clock.h) */
  FswHealth health;
} FswRwSpeedFilterState;

typedef struct {
  fsw_real Omega_meas[FSW_MAX_RW]; /* [rad/s] (num_rw) raw tachometer samples    */
  uint8_t avail[FSW_MAX_RW];       /* [-]     (num_rw) upstream mask, 0/1        */
  uint64_t t_ns;                   /* [ns]    sample time                        */
  fsw_real u_applied[FSW_MAX_RW];  /* [N*m]   (num_rw) motor torque applied since the
                                      previous call, |u| <= 2 u_max (read when
                                      n_window > 0 and u_valid = 1)           */
  uint8_t u_valid;                 /* [-]     1: u_applied held over the whole
                                      interval since the previous call; 0: not
                                      known (every torque window restarts)    */
} FswRwSpeedFilterIn;

typedef struct {
  fsw_real Omega[FSW_MAX_RW]; /* [rad/s] (num_rw) screened speeds; 0 beyond num_rw */
  uint8_t avail[FSW_MAX_RW];  /* [-]     (num_rw) In.avail OR failed; 0 beyond     */
  uint64_t rejected;          /* [-]     bit i: this call's sample i rejected     */
  uint64_t failed;            /* [-]     bit i: wheel i held unavailable          */
  uint64_t latched;           /* [-]     bit i: ... by the stale or torque test  */
} FswRwSpeedFilterOut;

FswStatus fsw_rw_speed_filter_check(const FswRwSpeedFilterConfig *cfg);
FswStatus fsw_rw_speed_filter_init(FswRwSpeedFilterState *st, const FswRwSpeedFilterConfig *cfg);
/* Clears samples, runs, failures (latched ones too), windows and timing;
 * keeps `rejections` and health. */
void fsw_rw_speed_filter_reset(FswRwSpeedFilterState *st);
/* FSW_OK (rejections are reported in Out, not as a status); FSW_E_BAD_INPUT
 * (mask entry not 0/1, u_valid not 0/1, or with n_window > 0 and u_valid = 1
 * an applied torque that is not finite or exceeds 2 u_max); FSW_E_TIME (t_ns <= previous); FSW_E_NOT_INIT.
 * Errors advance no state. */
FswStatus fsw_rw_speed_filter_update(FswRwSpeedFilterState *st, const FswRwSpeedFilterConfig *cfg,
                                     const FswRwSpeedFilterIn *in, FswRwSpeedFilterOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_SPEED_FILTER_H */

/* WP contract of thr_pulse_round.c's fsw_thr_pulse_round_update (docs/eva.md,
 * "WP proofs").
 * wp-target: thr_pulse_round.c fsw_thr_pulse_round_update
 * wp-options: -wp-model Caveat+real
 * The thruster on-time command is within one control period: for a
 * configuration that check accepts, every output on-time is in [0, T]
 * whatever the force command, the carried residuals and the result; the
 * entries beyond num_thr are exactly 0; and the carried residual stays in
 * [-T, T] (its documented range) from one call to the next.  The loop
 * invariant is an ACSL comment in thr_pulse_round.c itself.  clamp's
 * contract is proven on its own (thr_pulse_round_clamp.h); the contracts
 * of the shared pulsing functions below are assumed, not proven here.
 * A zero is written 0 <= x <= 0: WP 25's real model hands x == 0 to Why3
 * with an integer zero, which Why3 refuses. */
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/thr_pulse_round.h"
#include "thr_pulse_round_clamp.h"

/*@ requires \valid(t_on + (0 .. FSW_MAX_THR - 1));
    assigns t_on[0 .. FSW_MAX_THR - 1];
    ensures zero: \forall integer k; 0 <= k < FSW_MAX_THR ==> 0 <= t_on[k] <= 0;
*/
void fsw_thr_pulse_safe_output(fsw_real t_on[FSW_MAX_THR]);

/*@ assigns *cs, *dt; */
FswStatus fsw_thr_pulse_begin(FswThrPulseCommonState *cs, const fsw_real *F, int n, int use_time,
                              uint64_t t_ns, fsw_real *dt);

/*@ assigns *cs; */
FswStatus fsw_thr_pulse_end(FswThrPulseCommonState *cs, int use_time, uint64_t t_ns, int saturated);

/*@ assigns *h; ensures \result == s; */
FswStatus fsw_health_record(FswHealth *h, FswStatus s);

/*@ assigns \nothing; */
void fsw_assert_failed(const char *file, int line);

/*@ requires valid: \valid(st) && \valid_read(cfg) && \valid_read(in) && \valid(out);
    requires separated: \separated(st, cfg, in, out);
    requires checked_count: 1 <= cfg->num_thr <= FSW_MAX_THR;
    requires checked_thrust: \forall integer k; 0 <= k < cfg->num_thr ==> cfg->F_max[k] > 0;
    requires checked_times: cfg->period > 0 && cfg->resolution > 0 &&
               0 <= cfg->t_min <= cfg->period;
    requires resid_range: \forall integer k; 0 <= k < cfg->num_thr ==>
               -cfg->period <= st->resid[k] <= cfg->period;
    assigns out->t_on[0 .. FSW_MAX_THR - 1], st->common, st->resid[0 .. FSW_MAX_THR - 1];
    ensures in_period: \forall integer k; 0 <= k < cfg->num_thr ==>
              0 <= out->t_on[k] <= cfg->period;
    ensures zero_beyond: \forall integer k; cfg->num_thr <= k < FSW_MAX_THR ==>
              0 <= out->t_on[k] <= 0;
    ensures resid_kept: \forall integer k; 0 <= k < cfg->num_thr ==>
              -cfg->period <= st->resid[k] <= cfg->period;
*/
FswStatus fsw_thr_pulse_round_update(FswThrPulseRoundState *st, const FswThrPulseRoundConfig *cfg,
                                     const FswThrPulseRoundIn *in, FswThrPulseRoundOut *out);

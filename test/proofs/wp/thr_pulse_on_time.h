/* WP contract of thr_pulse_common.c's fsw_thr_pulse_on_time (docs/eva.md,
 * "WP proofs").
 * wp-target: thr_pulse_common.c fsw_thr_pulse_on_time
 * The on-time that thr_pulse_rem and thr_pulse_schmitt start from is never
 * negative, whatever the sign of the force command, for either base thrust
 * state. */
#include "fsw/fsw_config.h"

/*@ requires finite_F: \is_finite(F);
    requires positive_F_max: \is_finite(F_max) && F_max > 0;
    requires nonneg_dt: \is_finite(dt) && dt >= 0;
    assigns \nothing;
    ensures nonneg: \result >= 0;
    ensures zero_when_off: base_thrust_state != 1 && F <= 0 ==> \result == 0;
*/
fsw_real fsw_thr_pulse_on_time(fsw_real F, fsw_real F_max, int base_thrust_state, fsw_real dt);

/* WP contract of thr_pulse_round.c's clamp (docs/eva.md, "WP proofs").
 * wp-target: thr_pulse_round.c clamp
 * tools/eva_check.py forces this header into that file's translation unit
 * with -include, so the flight source carries no annotation; the Eva
 * analysis of test/proofs/eva/thr_pulse.c includes it too and so checks the
 * preconditions at every call.  The last step of every thruster's on-time
 * command is clamp(t, 0, T): in_range is the saturation of the command. */
#include "fsw/fsw_config.h"

/*@ requires finite_bounds: \is_finite(lo) && \is_finite(hi);
    requires ordered: lo <= hi;
    requires finite_x: \is_finite(x);
    assigns \nothing;
    ensures in_range: lo <= \result <= hi;
    ensures unchanged_inside: lo <= x <= hi ==> \result == x;
    ensures at_bound: (x < lo ==> \result == lo) && (x > hi ==> \result == hi);
*/
static fsw_real clamp(fsw_real x, fsw_real lo, fsw_real hi);

/* Planted wrong contract (docs/eva.md, "WP proofs"): the WP gate must
 * report it not proven.  The wheel torque bound of rw_sat_bound.h with half
 * the limit, which a command of 0.75 u_max on one wheel violates; the same
 * preconditions (the contract of test/proofs/wp/rw_sat_bound.h, which
 * Frama-C merges with this one) and the same loop invariants of rw_sat.c.
 * Only this goal is tried.
 * wp-target: rw_sat.c fsw_rw_sat_update
 * wp-options: -wp-model Caveat+real -wp-prop half_bound -wp-timeout 5 */
#include "../wp/rw_sat_bound.h"

/*@ ensures half_bound: \forall integer k; 0 <= k < cfg->num_rw ==>
      -cfg->u_max[k] / 2 <= out->u_s[k] <= cfg->u_max[k] / 2;
*/
FswStatus fsw_rw_sat_update(FswRwSatState *st, const FswRwSatConfig *cfg, const FswRwSatIn *in,
                            FswRwSatOut *out);

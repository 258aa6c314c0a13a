/* Planted wrong contract (docs/eva.md, "WP proofs"): the WP gate must
 * report it not proven.  The wheel torque bound of rw_sat_bound.h with half
 * the limit, which a command of 0.75 u_max on one wheel violates; the same
 * preconditions (the contract of test/proofs/wp/rw_sat_bound.h, which
 * Frama-C merges with this one) and the same loop invariants of rw_sat.c.
 * Only this goal is tried.
 * wp-target: rw_sat.c fsw_rw_sat_limit
 * wp-options: -wp-model Typed+real -wp-prop half_bound -wp-timeout 5 */
#include "../wp/rw_sat_bound.h"

/*@ ensures half_bound: \forall integer k; 0 <= k < cfg->num_rw ==>
      -cfg->u_max[k] / 2 <= u_out[k] <= cfg->u_max[k] / 2;
*/
FswStatus fsw_rw_sat_limit(FswRwSatState *st, const FswRwSatConfig *cfg, const fsw_real u_in[FSW_MAX_RW],
                           const uint8_t avail[FSW_MAX_RW], fsw_real u_out[FSW_MAX_RW]);

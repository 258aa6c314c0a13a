/* WP contract of rw_sat.c's fsw_rw_sat_limit, the saturation that
 * fsw_rw_sat_update runs after its checks and the application calls
 * directly (docs/eva.md, "WP proofs").
 * wp-target: rw_sat.c fsw_rw_sat_limit
 * wp-options: -wp-model Typed+real -wp-timeout 60
 * The saturation bound of the wheel torque command: for a configuration
 * that check accepts, every output torque is within [-u_max_i, u_max_i]
 * whatever the input and the result (NaN inputs included), in both modes (SCALE and CLIP);
 * unavailable wheels and the entries beyond num_rw are exactly 0; an
 * unlimited command (FSW_OK) passes every available torque unchanged.  The
 * loop invariants are ACSL comments in rw_sat.c itself (plain comments to a
 * C compiler).  The contracts of the functions it calls, below, are
 * assumed, not proven here: each is a few lines of code (rw_common.c,
 * fsw_vec.c, fsw_status.c) and each is exercised by its module tests. */
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/rw_common.h"
#include "fsw/rw_sat.h"

/*@ requires \valid(u + (0 .. FSW_MAX_RW - 1));
    assigns u[0 .. FSW_MAX_RW - 1];
    ensures zero: \forall integer k; 0 <= k < FSW_MAX_RW ==> 0 <= u[k] <= 0;
*/
void fsw_rw_zero(fsw_real u[FSW_MAX_RW]);

/*@ assigns \nothing; */
int fsw_vn_is_finite(const fsw_real *a, int n);

/*@ assigns \nothing; */
int fsw_rw_avail_valid(const uint8_t avail[FSW_MAX_RW], int n);

/*@ assigns *h;
    ensures \result == s;
*/
FswStatus fsw_health_record(FswHealth *h, FswStatus s);

/*@ assigns \nothing; */
void fsw_assert_failed(const char *file, int line);

/*@ requires valid: \valid(st) && \valid_read(cfg) && \valid(u_out + (0 .. FSW_MAX_RW - 1));
    requires valid_in: \valid_read(u_in + (0 .. cfg->num_rw - 1)) && \valid_read(avail + (0 .. cfg->num_rw - 1));
    requires separated: \separated(st, cfg, u_in + (0 .. cfg->num_rw - 1), avail + (0 .. cfg->num_rw - 1),
                                    u_out + (0 .. FSW_MAX_RW - 1));
    requires checked_count: 1 <= cfg->num_rw <= FSW_MAX_RW;
    requires checked_limits: \forall integer k; 0 <= k < cfg->num_rw ==> cfg->u_max[k] > 0;
    requires checked_mode: cfg->mode == FSW_RW_SAT_SCALE || cfg->mode == FSW_RW_SAT_CLIP;
    assigns u_out[0 .. FSW_MAX_RW - 1], st->health;
    ensures bound: \forall integer k; 0 <= k < cfg->num_rw ==>
              -cfg->u_max[k] <= u_out[k] <= cfg->u_max[k];
    ensures unavailable_zero: \forall integer k; 0 <= k < cfg->num_rw ==>
              avail[k] != FSW_AVAILABLE ==> 0 <= u_out[k] <= 0;
    ensures zero_beyond: \forall integer k; cfg->num_rw <= k < FSW_MAX_RW ==> 0 <= u_out[k] <= 0;
    ensures unlimited_unchanged: \result == FSW_OK ==> \forall integer k; 0 <= k < cfg->num_rw ==>
              avail[k] == FSW_AVAILABLE ==> u_out[k] == u_in[k];
*/
FswStatus fsw_rw_sat_limit(FswRwSatState *st, const FswRwSatConfig *cfg, const fsw_real u_in[FSW_MAX_RW],
                           const uint8_t avail[FSW_MAX_RW], fsw_real u_out[FSW_MAX_RW]);

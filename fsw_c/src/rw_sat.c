/* rw_sat: wheel torque saturation, scale or clip (docs/fsw/rw_sat.md). */
#include "fsw/rw_sat.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"
#include "fsw/rw_common.h"
#include "rw_sat_internal.h"

FswStatus fsw_rw_sat_check(const FswRwSatConfig *cfg)
{
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (cfg->num_rw < 1 || cfg->num_rw > FSW_MAX_RW) { return FSW_E_CAPACITY; }
  if (!fsw_rw_all_positive(cfg->u_max, cfg->num_rw)) { return FSW_E_CONFIG; }
  if (cfg->mode != FSW_RW_SAT_SCALE && cfg->mode != FSW_RW_SAT_CLIP) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_rw_sat_init(FswRwSatState *st, const FswRwSatConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_rw_sat_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_rw_sat_reset(st);
  return FSW_OK;
}

void fsw_rw_sat_reset(FswRwSatState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* stateless */
}

FswStatus fsw_rw_sat_update(FswRwSatState *st, const FswRwSatConfig *cfg, const FswRwSatIn *in,
                            FswRwSatOut *out)
{
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    if (out != NULL) { fsw_rw_zero(out->u_s); } /* safe output */
    return FSW_E_NULL_ARG;
  }
  if (!st->ready) {
    fsw_rw_zero(out->u_s);
    return fsw_health_record(&st->health, FSW_E_NOT_INIT);
  }
  if (!fsw_vn_is_finite(in->u_s, cfg->num_rw) || !fsw_rw_avail_valid(in->avail, cfg->num_rw)) {
    fsw_rw_zero(out->u_s);
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  return fsw_rw_sat_limit(st, cfg, in->u_s, in->avail, out->u_s);
}

FswStatus fsw_rw_sat_limit(FswRwSatState *st, const FswRwSatConfig *cfg, const fsw_real u_in[FSW_MAX_RW],
                           const uint8_t avail[FSW_MAX_RW], fsw_real u_out[FSW_MAX_RW])
{
  fsw_real s = FSW_R(0.0);
  int n, i, limited = 0;
  fsw_rw_zero(u_out);
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_rw;

  /* WP (docs/eva.md, "WP proofs"): the saturation bound, proven from
   * these loop invariants and the contract of test/proofs/wp/rw_sat_bound.h.
   * Each invariant also holds in IEEE arithmetic: a rounded |u|/u_max <= 1
   * implies |u| <= u_max. */
  /*@ loop invariant 0 <= i <= n && 0 <= s;
      loop invariant copied: \forall integer k; 0 <= k < i ==> avail[k] == FSW_AVAILABLE ==>
        u_out[k] == u_in[k];
      loop invariant within: \forall integer k; 0 <= k < i ==> avail[k] == FSW_AVAILABLE ==>
        s > 1 || \abs(u_in[k]) <= cfg->u_max[k];
      loop invariant \forall integer k; 0 <= k < i ==> avail[k] != FSW_AVAILABLE ==>
        0 <= u_out[k] <= 0;
      loop invariant \forall integer k; i <= k < FSW_MAX_RW ==> 0 <= u_out[k] <= 0;
      loop assigns i, s, u_out[0 .. n - 1];
      loop variant n - i; */
  for (i = 0; i < n; i++) {
    fsw_real r;
    if (avail[i] != FSW_AVAILABLE) { continue; }
    u_out[i] = u_in[i];
    r = FSW_FABS(u_in[i]) / cfg->u_max[i];
    if (r > s) { s = r; }
  }
  if (s > FSW_R(1.0)) {
    limited = 1;
    /*@ loop invariant 0 <= i <= n;
        loop invariant \forall integer k; 0 <= k < i ==>
          -cfg->u_max[k] <= u_out[k] <= cfg->u_max[k];
        loop invariant \forall integer k; i <= k < n ==> avail[k] != FSW_AVAILABLE ==>
          0 <= u_out[k] <= 0;
        loop invariant \forall integer k; 0 <= k < i ==> avail[k] != FSW_AVAILABLE ==>
          0 <= u_out[k] <= 0;
        loop assigns i, u_out[0 .. n - 1];
        loop variant n - i; */
    for (i = 0; i < n; i++) {
      if (cfg->mode == FSW_RW_SAT_SCALE) { u_out[i] /= s; }
      /* CLIP, and the last rounding of SCALE */
      if (u_out[i] > cfg->u_max[i]) { u_out[i] = cfg->u_max[i]; }
      if (u_out[i] < -cfg->u_max[i]) { u_out[i] = -cfg->u_max[i]; }
    }
  }
  return fsw_health_record(&st->health, limited ? FSW_W_SAT : FSW_OK);
}

/* guid_sunsafe: sun-safe pointing guidance (docs/fsw/guid_sunsafe.md). */
#include "fsw/guid_sunsafe.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_attitude.h"
#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"
#include "fsw_status_inline.h"
#include "guid_sunsafe_internal.h"

/* Library guard (docs/fsw/guid_sunsafe.md): in the "normal" branch a cross product
 * |s_B x s_cmd| <= tol * |s_B| is treated as antiparallel (use e180).
 * 1e-12 in double as specified; single-precision round-off of a cross
 * product of unit vectors is ~1e-7, so 1e-6 there. */
#if FSW_USE_FLOAT
#define SUNSAFE_PARALLEL_TOL FSW_R(1e-6)
#else
#define SUNSAFE_PARALLEL_TOL FSW_R(1e-12)
#endif

#define SUNSAFE_PI FSW_R(3.14159265358979323846)

static void write_safe(FswGuidSunsafeOut *out)
{
  fsw_v3_zero(out->guid.sigma_BR);
  fsw_v3_zero(out->guid.omega_BR_B);
  fsw_v3_zero(out->guid.omega_RN_B);
  fsw_v3_zero(out->guid.omega_dot_RN_B);
  out->sun_angle_err = FSW_R(0.0);
  out->sun_valid = 0;
}

FswStatus fsw_guid_sunsafe_check(const FswGuidSunsafeConfig *cfg)
{
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (!fsw_v3_is_finite(cfg->s_cmd_B) || !fsw_v3_is_finite(cfg->omega_search_B) ||
      !isfinite(cfg->min_unit_mag) || !isfinite(cfg->small_angle) ||
      !isfinite(cfg->sun_axis_spin_rate)) {
    return FSW_E_CONFIG;
  }
  if (!(fsw_v3_norm(cfg->s_cmd_B) >= FSW_R(0.1)) ||
      !(fsw_v3_norm(cfg->s_cmd_B) <= FSW_GUID_SUNSAFE_S_CMD_MAX)) {
    return FSW_E_CONFIG; }
  if (fsw_vn_max_abs(cfg->omega_search_B, 3) > FSW_GUID_SUNSAFE_RATE_MAX ||
      FSW_FABS(cfg->sun_axis_spin_rate) > FSW_GUID_SUNSAFE_RATE_MAX) {
    return FSW_E_CONFIG; }
  if (cfg->min_unit_mag < FSW_R(0.0)) { return FSW_E_CONFIG; }
  if (cfg->small_angle < FSW_R(0.0) || !(cfg->small_angle < FSW_R(0.5) * SUNSAFE_PI)) {
    return FSW_E_CONFIG;
  }
  return FSW_OK;
}

FswStatus fsw_guid_sunsafe_init(FswGuidSunsafeState *st, const FswGuidSunsafeConfig *cfg)
{
  const fsw_real x_hat[3] = {FSW_R(1.0), FSW_R(0.0), FSW_R(0.0)};
  const fsw_real y_hat[3] = {FSW_R(0.0), FSW_R(1.0), FSW_R(0.0)};
  fsw_real e180[3];
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  (void)memset(st, 0, sizeof *st);
  fsw_health_clear(&st->health);
  s = fsw_guid_sunsafe_check(cfg);
  if (s != FSW_OK) { return s; }
  (void)fsw_v3_normalize(st->s_cmd_hat_B, cfg->s_cmd_B);
  fsw_v3_cross(e180, st->s_cmd_hat_B, x_hat);
  if (fsw_v3_norm(e180) < FSW_R(0.1)) { fsw_v3_cross(e180, st->s_cmd_hat_B, y_hat); }
  (void)fsw_v3_normalize(st->e180_hat_B, e180); /* |e180| >= 0.7 here */
  st->ready = 1;
  fsw_guid_sunsafe_reset(st);
  return FSW_OK;
}

void fsw_guid_sunsafe_reset(FswGuidSunsafeState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* stateless */
}

FswStatus fsw_guid_sunsafe_update(FswGuidSunsafeState *st, const FswGuidSunsafeConfig *cfg,
                                  const FswGuidSunsafeIn *in, FswGuidSunsafeOut *out)
{
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { write_safe(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    return fsw_health_record(st != NULL ? &st->health : NULL, FSW_E_NULL_ARG);
  }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (!fsw_v3_is_finite(in->sun_B) || !fsw_v3_is_finite(in->omega_BN_B)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  return fsw_guid_sunsafe_point(st, cfg, in, out);
}

FswStatus fsw_guid_sunsafe_point(FswGuidSunsafeState *st, const FswGuidSunsafeConfig *cfg,
                                 const FswGuidSunsafeIn *in, FswGuidSunsafeOut *out)
{
  fsw_real s_norm; /* [-] |s_B| */
  fsw_real s_B[3]; /* [-] sun_B scaled by a power of two (direction only) */
  fsw_real m;      /* [-] max |sun_B_i| */
  fsw_real r;      /* [-] the root of sun_B's scaled sum of squares */
  write_safe(out);
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }

  /* |sun_B| as fsw_v3_norm forms it: m times the root of the scaled sum
   * (0 for a zero sun_B; sun_B is finite here, so m is) */
  m = fsw_vn_max_abs(in->sun_B, 3);
  r = (m > FSW_R(0.0)) ? fsw_v3i_scaled_root(in->sun_B, m) : FSW_R(0.0);
  s_norm = m * r;
  if (s_norm > cfg->min_unit_mag && s_norm > FSW_R(0.0)) {
    fsw_real c, theta; /* cos(theta); [rad] */
    fsw_real omega_RN_B[3];
    /* Only the direction of sun_B is used below: scale it by a power of
     * two (exact, same digits) so that |s_B| is in [1/2, 2 sqrt 3) and no
     * product overflows or underflows for any finite sun_B. */
    const fsw_real p = fsw_pow2_scale(m);
    fsw_v3_scale(s_B, p, in->sun_B);
    s_norm = (m * p) * r; /* = fsw_v3_norm(s_B) */
    c = fsw_v3_dot(st->s_cmd_hat_B, s_B) / s_norm;
    if (c > FSW_R(1.0)) { c = FSW_R(1.0); }
    if (c < FSW_R(-1.0)) { c = FSW_R(-1.0); }
    theta = FSW_ACOS(c);
    if (!(theta < cfg->small_angle)) {
      fsw_real e_hat[3];
      fsw_real sigma_BR[3];
      if (SUNSAFE_PI - theta < cfg->small_angle) {
        fsw_v3_copy(e_hat, st->e180_hat_B);
      } else {
        fsw_real e_norm; /* [-] |s_B x s_cmd| */
        int e_unit;      /* 1 if e_hat was normalised */
        fsw_v3_cross(e_hat, s_B, st->s_cmd_hat_B);
        e_unit = fsw_v3_norm_normalize(e_hat, &e_norm, e_hat);
        if (!(e_norm > SUNSAFE_PARALLEL_TOL * s_norm) || !e_unit) {
          fsw_v3_copy(e_hat, st->e180_hat_B);
        }
      }
      fsw_v3_scale(sigma_BR, FSW_TAN(theta / FSW_R(4.0)), e_hat);
      fsw_mrp_switch(out->guid.sigma_BR, sigma_BR); /* never active for theta <= pi */
    }
    /* (sigma_BR stays 0 inside the dead band) */
    fsw_v3_scale(omega_RN_B, cfg->sun_axis_spin_rate / s_norm, s_B);
    fsw_v3_copy(out->guid.omega_RN_B, omega_RN_B);
    fsw_v3_sub(out->guid.omega_BR_B, in->omega_BN_B, omega_RN_B);
    out->sun_angle_err = theta;
    out->sun_valid = 1;
  } else {
    /* no valid Sun heading: search spin, no attitude error */
    fsw_v3_copy(out->guid.omega_RN_B, cfg->omega_search_B);
    fsw_v3_sub(out->guid.omega_BR_B, in->omega_BN_B, cfg->omega_search_B);
  }
  /* finite but huge inputs can overflow: treat like non-finite input */
  if (!fsw_v3_is_finite(out->guid.omega_BR_B) || !fsw_v3_is_finite(out->guid.omega_RN_B) ||
      !fsw_v3_is_finite(out->guid.sigma_BR) || !isfinite(out->sun_angle_err)) {
    write_safe(out);
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  return fsw_health_record_ok_i(&st->health);
}

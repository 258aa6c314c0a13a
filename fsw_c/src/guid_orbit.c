/* guid_orbit: orbit-referenced guidance (nadir / velocity pointing).
 * Equations: guid_orbit.h and docs/fsw/guid_orbit.md. */
#include "fsw/guid_orbit.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_attitude.h"
#include "fsw/fsw_vec.h"

static void write_safe(FswGuidOrbitOut *out)
{
  fsw_v3_zero(out->sigma_RN);
  fsw_v3_zero(out->omega_RN_N);
  fsw_v3_zero(out->omega_dot_RN_N);
}

FswStatus fsw_guid_orbit_check(const FswGuidOrbitConfig *cfg)
{
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (cfg->variant != FSW_GUID_ORBIT_NADIR && cfg->variant != FSW_GUID_ORBIT_VELOCITY) { return FSW_E_CONFIG; }
  if (!fsw_v3_is_finite(cfg->sigma_BdR) || !isfinite(fsw_v3_norm2(cfg->sigma_BdR))) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->mu) || !(cfg->mu > FSW_R(0.0)) || cfg->mu > FSW_GUID_ORBIT_MU_MAX) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_guid_orbit_init(FswGuidOrbitState *st, const FswGuidOrbitConfig *cfg)
{
  FswStatus s;
  fsw_real sw[3];
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  (void)memset(st, 0, sizeof *st);
  fsw_health_clear(&st->health);
  s = fsw_guid_orbit_check(cfg);
  if (s != FSW_OK) { return s; }
  fsw_mrp_switch(sw, cfg->sigma_BdR); /* same rotation, |sigma| <= 1 */
  fsw_mrp_to_dcm(st->dcm_BdR, sw);
  st->ready = 1;
  fsw_guid_orbit_reset(st);
  return FSW_OK;
}

void fsw_guid_orbit_reset(FswGuidOrbitState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* stateless */
}

FswStatus fsw_guid_orbit_update(FswGuidOrbitState *st, const FswGuidOrbitConfig *cfg,
                                const FswGuidOrbitIn *in, FswGuidOrbitOut *out)
{
  fsw_real rh[3], vh[3], hh[3], C[3][3], BdN[3][3], w[3], wd[3];
  fsw_real r, v, sin_rv, rate, rdot_r; /* |r|, |v|, |r_hat x v_hat|, |omega|, (r.v)/r^2 */
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { write_safe(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    return fsw_health_record(st != NULL ? &st->health : NULL, FSW_E_NULL_ARG); }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (in->valid != 1 || !fsw_v3_is_finite(in->r_N) || !fsw_v3_is_finite(in->v_N)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  r = fsw_v3_norm(in->r_N);
  v = fsw_v3_norm(in->v_N);
  if (!(r >= FSW_GUID_ORBIT_R_MIN) || !isfinite(r) || !isfinite(v) || !fsw_v3_normalize(rh, in->r_N) ||
      !fsw_v3_normalize(vh, in->v_N)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  fsw_v3_cross(hh, rh, vh);
  sin_rv = fsw_v3_norm(hh);
  if (!(sin_rv > FSW_GUID_ORBIT_SIN_MIN)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  fsw_v3_scale(hh, FSW_R(1.0) / sin_rv, hh);
  /* (r.v)/r^2 = (r_hat . v_hat) v / r */
  rdot_r = fsw_v3_dot(rh, vh) * (v / r);

  /* rows of [RN]: R1, R2, R3 */
  fsw_v3_scale(C[1], FSW_R(-1.0), hh);
  if (cfg->variant == FSW_GUID_ORBIT_NADIR) {
    fsw_v3_scale(C[2], FSW_R(-1.0), rh);
    fsw_v3_cross(C[0], C[1], C[2]);
    /* |h|/r^2 = sin v / r */
    rate = sin_rv * (v / r);
    fsw_v3_scale(w, rate, hh);
    fsw_v3_scale(wd, FSW_R(-2.0) * rdot_r, w);
  } else {
    fsw_real g; /* mu/(r v^2) */
    fsw_v3_copy(C[0], vh);
    fsw_v3_cross(C[2], C[0], C[1]);
    /* mu |h| /(r^3 v^2) = (mu/(r v^2)) sin / r * v ... written as g * sin * v / r */
    g = (cfg->mu / r) / v / v;
    rate = g * sin_rv * (v / r);
    fsw_v3_scale(w, rate, hh);
    fsw_v3_scale(wd, rdot_r * (FSW_R(2.0) * g - FSW_R(3.0)), w);
  }
  if (!fsw_v3_is_finite(w) || !fsw_v3_is_finite(wd)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }

  fsw_m33_mult(BdN, FSW_CM33(st->dcm_BdR), FSW_CM33(C));
  fsw_dcm_to_mrp(out->sigma_RN, FSW_CM33(BdN));
  fsw_v3_copy(out->omega_RN_N, w);
  fsw_v3_copy(out->omega_dot_RN_N, wd);
  return fsw_health_record(&st->health, FSW_OK);
}

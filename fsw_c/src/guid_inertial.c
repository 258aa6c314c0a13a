/* guid_inertial: inertial three-axis pointing (docs/fsw/guid_inertial.md). */
#include "fsw/guid_inertial.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_attitude.h"
#include "fsw/fsw_vec.h"

static void write_safe(FswGuidInertialOut *out)
{
  fsw_v3_zero(out->sigma_RN);
  fsw_v3_zero(out->omega_RN_N);
  fsw_v3_zero(out->omega_dot_RN_N);
}

FswStatus fsw_guid_inertial_check(const FswGuidInertialConfig *cfg)
{
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (!fsw_v3_is_finite(cfg->sigma_R0N)) { return FSW_E_CONFIG; }
  /* |sigma|^2 must be finite for the shadow switch to be meaningful */
  if (!isfinite(fsw_v3_norm2(cfg->sigma_R0N))) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_guid_inertial_init(FswGuidInertialState *st, const FswGuidInertialConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  (void)memset(st, 0, sizeof *st);
  fsw_health_clear(&st->health);
  s = fsw_guid_inertial_check(cfg);
  if (s != FSW_OK) { return s; }
  fsw_mrp_switch(st->sigma_RN, cfg->sigma_R0N);
  st->ready = 1;
  fsw_guid_inertial_reset(st);
  return FSW_OK;
}

void fsw_guid_inertial_reset(FswGuidInertialState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* stateless */
}

FswStatus fsw_guid_inertial_update(FswGuidInertialState *st, const FswGuidInertialConfig *cfg,
                                   FswGuidInertialOut *out)
{
  FSW_ASSERT(st != NULL && cfg != NULL && out != NULL);
  if (out != NULL) { write_safe(out); }
  if (st == NULL || cfg == NULL || out == NULL) {
    return fsw_health_record(st != NULL ? &st->health : NULL, FSW_E_NULL_ARG);
  }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  fsw_v3_copy(out->sigma_RN, st->sigma_RN);
  return fsw_health_record(&st->health, FSW_OK);
}

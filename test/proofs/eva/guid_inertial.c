/* Eva driver: guid_inertial (docs/fsw/guid_inertial.md, docs/eva.md).
 * eva-sources: guid_inertial.c fsw_attitude.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/guid_inertial.h"

static void run(void)
{
  FswGuidInertialConfig cfg;
  FswGuidInertialState st;
  FswGuidInertialOut out;
  FswStatus s;
  int i;
  /* check accepts any finite sigma_R0N whose |sigma|^2 is finite; any: also
   * NaN and infinities, which check refuses */
  for (i = 0; i < 3; i++) cfg.sigma_R0N[i] = eva_any_mode ? eva_sensor() : eva_real(-EVA_ENV, EVA_ENV);
  EVA_ENTRY(check, fsw_guid_inertial_check(&cfg));
  s = fsw_guid_inertial_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  s = fsw_guid_inertial_update(&st, &cfg, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

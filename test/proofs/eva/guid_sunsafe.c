/* Eva driver: guid_sunsafe (docs/fsw/guid_sunsafe.md, docs/eva.md).
 * eva-sources: guid_sunsafe.c fsw_attitude.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/guid_sunsafe.h"

static void run(void)
{
  FswGuidSunsafeConfig cfg;
  FswGuidSunsafeState st;
  FswGuidSunsafeIn in;
  FswGuidSunsafeOut out;
  FswStatus s;
  /* components of an s_cmd_B with 0.1 <= |s_cmd_B| <= 10 (a superset) */
  eva_reals(cfg.s_cmd_B, 3, -FSW_GUID_SUNSAFE_S_CMD_MAX, FSW_GUID_SUNSAFE_S_CMD_MAX);
  cfg.min_unit_mag = eva_nonneg();
  cfg.small_angle = eva_real(0.0, 1.5707963267948963); /* [0, pi/2) */
  eva_reals(cfg.omega_search_B, 3, -FSW_GUID_SUNSAFE_RATE_MAX, FSW_GUID_SUNSAFE_RATE_MAX);
  cfg.sun_axis_spin_rate = eva_real(-FSW_GUID_SUNSAFE_RATE_MAX, FSW_GUID_SUNSAFE_RATE_MAX);
  EVA_ENTRY(check, fsw_guid_sunsafe_check(&cfg));
  s = fsw_guid_sunsafe_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_sensors(in.sun_B, 3);
  eva_sensors(in.omega_BN_B, 3);
  s = fsw_guid_sunsafe_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

/* Eva driver: guid_orbit (docs/fsw/guid_orbit.md, docs/eva.md).
 * eva-sources: guid_orbit.c fsw_attitude.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/guid_orbit.h"

static void run(void)
{
  FswGuidOrbitConfig cfg;
  FswGuidOrbitState st;
  FswGuidOrbitIn in;
  FswGuidOrbitOut out;
  FswStatus s;
  cfg.variant = eva_int(FSW_GUID_ORBIT_NADIR, FSW_GUID_ORBIT_VELOCITY);
  eva_reals(cfg.sigma_BdR, 3, eva_any_mode ? -EVA_SQ : -EVA_ENV, eva_any_mode ? EVA_SQ : EVA_ENV);
  cfg.mu = eva_positive_to(FSW_GUID_ORBIT_MU_MAX);
  EVA_ENTRY(check, fsw_guid_orbit_check(&cfg));
  s = fsw_guid_orbit_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_sensors(in.r_N, 3);
  eva_sensors(in.v_N, 3);
  if (!eva_any_mode) { /* positions out to 1e12 m (beyond Saturn's orbit radius about the Sun) */
    eva_reals(in.r_N, 3, -1e12, 1e12);
  }
  in.valid = (uint8_t)eva_int(0, 255);
  s = fsw_guid_orbit_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

/* Eva driver: rw_map (docs/fsw/rw_map.md, docs/eva.md).
 * eva-sources: rw_map.c rw_common.c fsw_linalg.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_common.h"
#include "fsw/rw_map.h"

static void run(void)
{
  static FswRwMapState st; /* large scratch: static, as a flight build holds it */
  FswRwMapConfig cfg;
  FswRwMapIn in;
  FswRwMapOut out;
  FswStatus s;
  int k;
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_units(cfg.gs_hat_B, FSW_MAX_RW, FSW_RW_UNIT_TOL);
  cfg.num_axes = eva_int(0, 3);
  eva_units(cfg.ctrl_axes_B, 3, FSW_RW_UNIT_TOL);
  cfg.mode = eva_int(FSW_RW_MAP_MIN_NORM, FSW_RW_MAP_POWER);
  cfg.eps_P = eva_real(FSW_RW_MAP_EPS_P_MIN, FSW_RW_MAP_EPS_P_MAX);
  EVA_ENTRY(check, fsw_rw_map_check(&cfg));
  s = fsw_rw_map_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the kept factorisation read by a second call */
    eva_sensors(in.Lr_B, 3);
    eva_sensors(in.Omega, FSW_MAX_RW);
    eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
    s = fsw_rw_map_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

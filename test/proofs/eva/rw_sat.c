/* Eva driver: rw_sat (docs/fsw/rw_sat.md, docs/eva.md).
 * eva-sources: rw_sat.c rw_common.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_sat.h"

static void run(void)
{
  FswRwSatConfig cfg;
  FswRwSatState st;
  FswRwSatIn in;
  FswRwSatOut out;
  FswStatus s;
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_positives(cfg.u_max, FSW_MAX_RW);
  cfg.mode = eva_int(FSW_RW_SAT_SCALE, FSW_RW_SAT_CLIP);
  EVA_ENTRY(check, fsw_rw_sat_check(&cfg));
  s = fsw_rw_sat_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_sensors(in.u_s, FSW_MAX_RW);
  eva_bytes(in.avail, FSW_MAX_RW, 0, 255); /* 0/1 valid, the rest rejected */
  s = fsw_rw_sat_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

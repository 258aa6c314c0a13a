/* Eva driver: rw_null (docs/fsw/rw_null.md, docs/eva.md).
 * The loops over the wheels (up to FSW_MAX_RW) are not unrolled and the
 * states are not split (-eva-slevel 0; only the three-row loops unroll): with the defaults the
 * N x N projector keeps one state per iteration of every enclosing loop
 * (over 60 s of CPU); this way each analysis takes about 3 s, and the joined
 * iterations give the initialization and counter alarms recorded in
 * alarms.txt (each entry is written below the wheel count before it is read).
 * eva-options: -eva-auto-loop-unroll 3 -eva-slevel 0
 * eva-sources: rw_null.c rw_common.c fsw_linalg.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_common.h"
#include "fsw/rw_null.h"

static void run(void)
{
  static FswRwNullState st; /* large projector: static, as a flight build holds it */
  FswRwNullConfig cfg;
  FswRwNullIn in;
  FswRwNullOut out;
  FswStatus s;
  int k;
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_units(cfg.gs_hat_B, FSW_MAX_RW, FSW_RW_UNIT_TOL);
  cfg.k_null = eva_positive_to(FSW_RW_GAIN_MAX);
  cfg.scale_to_fit = eva_int(0, 1);
  eva_reals(cfg.u_max, FSW_MAX_RW, FSW_RW_U_MAX_MIN, FSW_RW_U_MAX_MAX);
  EVA_ENTRY(check, fsw_rw_null_check(&cfg));
  s = fsw_rw_null_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the kept projector read by a second call */
    eva_sensors(in.u_s, FSW_MAX_RW);
    eva_sensors(in.Omega, FSW_MAX_RW);
    eva_sensors(in.Omega_des, FSW_MAX_RW);
    eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
    s = fsw_rw_null_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

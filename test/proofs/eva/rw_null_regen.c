/* Eva driver: rw_null_regen (docs/fsw/rw_null_regen.md, docs/eva.md).
 * The wheel loops are joined as in rw_null.c (the same projector).
 * eva-options: -eva-auto-loop-unroll 3 -eva-slevel 0
 * eva-sources: rw_null_regen.c rw_common.c fsw_linalg.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_common.h"
#include "fsw/rw_null_regen.h"

static void run(void)
{
  static FswRwNullRegenState st; /* large projector: static, as a flight build holds it */
  FswRwNullRegenConfig cfg;
  FswRwNullRegenIn in;
  FswRwNullRegenOut out;
  FswStatus s;
  int k;
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_units(cfg.gs_hat_B, FSW_MAX_RW, FSW_RW_UNIT_TOL);
  cfg.mode = eva_int(FSW_RW_REGEN_GRADIENT, FSW_RW_REGEN_OPTIMUM);
  cfg.k_P = eva_positive_to(FSW_RW_GAIN_MAX);
  eva_reals(cfg.u_max, FSW_MAX_RW, FSW_RW_U_MAX_MIN, FSW_RW_U_MAX_MAX);
  EVA_ENTRY(check, fsw_rw_null_regen_check(&cfg));
  s = fsw_rw_null_regen_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the kept projector read by a second call */
    eva_sensors(in.u_s, FSW_MAX_RW);
    eva_sensors(in.Omega, FSW_MAX_RW);
    eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
    s = fsw_rw_null_regen_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

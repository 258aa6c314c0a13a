/* Eva driver: rw_bias (docs/fsw/rw_bias.md, docs/eva.md).
 * The wheel loops are joined as in rw_null.c (the same projector); the
 * alarms of both analyses are recorded in alarms.txt (docs/eva.md).
 * eva-options: -eva-auto-loop-unroll 3 -eva-slevel 0
 * eva-sources: rw_bias.c rw_common.c fsw_linalg.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_common.h"
#include "fsw/rw_bias.h"

static void run(void)
{
  static FswRwBiasState st; /* large projector and basis: static, as a flight build holds it */
  FswRwBiasConfig cfg;
  FswRwBiasIn in;
  FswRwBiasOut out;
  FswStatus s;
  int k;
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_units(cfg.gs_hat_B, FSW_MAX_RW, FSW_RW_UNIT_TOL);
  /* signed preferred speeds; check refuses those inside the keep-out band */
  eva_reals(cfg.Omega_bias, FSW_MAX_RW, -FSW_RW_OMEGA_MAX, FSW_RW_OMEGA_MAX);
  cfg.Omega_keepout = eva_positive_to(FSW_RW_OMEGA_MAX / 2);
  cfg.Omega_hyst = eva_real(0.0, FSW_RW_OMEGA_MAX / 2);
  EVA_ENTRY(check, fsw_rw_bias_check(&cfg));
  s = fsw_rw_bias_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the kept basis and hysteresis read by a second call */
    eva_sensors(in.Omega, FSW_MAX_RW);
    eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
    s = fsw_rw_bias_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

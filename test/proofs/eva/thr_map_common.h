/* The thr_map Eva drivers' body (thr_map.c: minimum-norm mode,
 * thr_map_nnls.c: the bounded mode): a configuration in the domain
 * docs/eva.md gives thr_map, with the mode the driver names, then check,
 * init and update.  tools/eva_check.py reads the entries (EVA_ENTRY) here
 * too.  Only Frama-C reads this file. */
#ifndef EVA_THR_MAP_COMMON_H
#define EVA_THR_MAP_COMMON_H

#include "eva_driver.h"

#include "fsw/thr_map.h"

static void thr_map_config(FswThrMapConfig *cfg, FswThrMapMode mode)
{
  int i;
  for (i = 0; i < 3; i++) eva_reals(cfg->control_axes_B[i], 3, -FSW_THR_MAP_AXIS_MAX, FSW_THR_MAP_AXIS_MAX);
  cfg->num_thr = eva_int(1, FSW_MAX_THR);
  /*@ loop unroll 64; */
  for (i = 0; i < FSW_MAX_THR; i++) {
    eva_reals(cfg->r_thr_B[i], 3, -FSW_THR_MAP_R_MAX, FSW_THR_MAP_R_MAX);
    cfg->F_max[i] = eva_positive_to(FSW_THR_MAP_F_MAX);
  }
  eva_units(cfg->gt_hat_B, FSW_MAX_THR, 1e-9); /* thr_map's unit tolerance */
  cfg->thr_force_sign = eva_int(0, 1) ? 1 : -1;
  cfg->ang_err_thresh = eva_nonneg();
  cfg->epsilon = eva_nonneg();
  cfg->use_2nd_loop = eva_int(0, 1);
  cfg->mode = mode;
}

static void thr_map_input(FswThrMapIn *in)
{
  eva_sensors(in->Lr_B, 3);
  eva_sensors(in->r_CoM_B, 3);
  eva_bytes(in->avail, FSW_MAX_THR, 0, 255);
}

static void thr_map_run(FswThrMapMode mode)
{
  static FswThrMapState st; /* large scratch: static, as a flight build holds it */
  FswThrMapConfig cfg;
  FswThrMapIn in;
  FswThrMapOut out;
  FswStatus s;
  thr_map_config(&cfg, mode);
  EVA_ENTRY(check, fsw_thr_map_check(&cfg));
  s = fsw_thr_map_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  thr_map_input(&in);
  s = fsw_thr_map_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

#endif /* EVA_THR_MAP_COMMON_H */

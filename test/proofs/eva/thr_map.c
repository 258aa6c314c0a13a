/* Eva driver: thr_map (docs/fsw/thr_map.md, docs/eva.md).
 * eva-sources: thr_map.c fsw_linalg.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/thr_map.h"

static void run(void)
{
  static FswThrMapState st; /* large scratch: static, as a flight build holds it */
  FswThrMapConfig cfg;
  FswThrMapIn in;
  FswThrMapOut out;
  FswStatus s;
  int i;
  const fsw_real u = 1.0 + 1e-9; /* unit force axes within thr_map's tolerance */
  for (i = 0; i < 3; i++) eva_reals(cfg.control_axes_B[i], 3, -FSW_THR_MAP_AXIS_MAX, FSW_THR_MAP_AXIS_MAX);
  cfg.num_thr = eva_int(1, FSW_MAX_THR);
  /*@ loop unroll 64; */
  for (i = 0; i < FSW_MAX_THR; i++) {
    eva_reals(cfg.r_thr_B[i], 3, -FSW_THR_MAP_R_MAX, FSW_THR_MAP_R_MAX);
    eva_reals(cfg.gt_hat_B[i], 3, -u, u);
    cfg.F_max[i] = eva_real(eva_any_mode ? EVA_TINY : EVA_ENV_MIN, FSW_THR_MAP_F_MAX);
  }
  cfg.thr_force_sign = eva_int(0, 1) ? 1 : -1;
  cfg.ang_err_thresh = eva_nonneg();
  cfg.epsilon = eva_nonneg();
  cfg.use_2nd_loop = eva_int(0, 1);
  cfg.mode = eva_int(FSW_THR_MAP_MIN_NORM, FSW_THR_MAP_NNLS);
  EVA_ENTRY(check, fsw_thr_map_check(&cfg));
  s = fsw_thr_map_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_sensors(in.Lr_B, 3);
  eva_sensors(in.r_CoM_B, 3);
  eva_bytes(in.avail, FSW_MAX_THR, 0, 255);
  s = fsw_thr_map_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

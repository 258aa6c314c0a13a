/* Eva driver: mrp_fb (docs/fsw/mrp_fb.md, docs/eva.md).
 * eva-sources: mrp_fb.c rw_common.c fsw_vec.c fsw_clock.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/mrp_fb.h"

static void run(void)
{
  FswMrpFbConfig cfg;
  FswMrpFbState st;
  FswMrpFbIn in;
  FswMrpFbOut out;
  FswStatus s;
  int i, j, k;
  cfg.K = eva_positive();
  cfg.P = eva_positive();
  cfg.K_i = eva_finite();
  cfg.integral_limit = eva_nonneg();
  cfg.control_law_type = eva_int(FSW_MRP_FB_LAW_0, FSW_MRP_FB_LAW_1);
  for (i = 0; i < 3; i++) cfg.known_torque_B[i] = eva_finite();
  /* a superset of the symmetric positive definite inertias: positive
   * diagonal, symmetric off-diagonal terms */
  for (j = 0; j < 3; j++) {
    cfg.I_B[j][j] = eva_positive();
    for (k = j + 1; k < 3; k++) {
      cfg.I_B[j][k] = eva_finite();
      cfg.I_B[k][j] = cfg.I_B[j][k];
    }
  }
  cfg.num_rw = eva_int(0, FSW_MAX_RW);
  eva_units(cfg.gs_hat_B, FSW_MAX_RW, FSW_MRP_FB_UNIT_TOL);
  eva_positives(cfg.J_s, FSW_MAX_RW);
  EVA_ENTRY(check, fsw_mrp_fb_check(&cfg));
  s = fsw_mrp_fb_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the integral carried to a second call */
    in.t_ns = eva_u64();
    eva_sensors(in.guid.sigma_BR, 3);
    eva_sensors(in.guid.omega_BR_B, 3);
    eva_sensors(in.guid.omega_RN_B, 3);
    eva_sensors(in.guid.omega_dot_RN_B, 3);
    eva_sensors(in.Omega, FSW_MAX_RW);
    eva_bytes(in.rw_avail, FSW_MAX_RW, 0, 255);
    s = fsw_mrp_fb_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

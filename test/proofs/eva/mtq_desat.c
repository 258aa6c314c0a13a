/* Eva driver: mtq_desat (docs/fsw/mtq_desat.md, docs/eva.md).
 * eva-sources: mtq_desat.c mtq_map.c fsw_linalg.c rw_common.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_common.h"
#include "fsw/mtq_desat.h"

static void run(void)
{
  FswMtqDesatConfig cfg;
  FswMtqDesatState st;
  FswMtqDesatIn in;
  FswMtqDesatOut out;
  FswStatus s;
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_units(cfg.gs_hat_B, FSW_MAX_RW, FSW_RW_UNIT_TOL);
  eva_reals(cfg.J_s, FSW_MAX_RW, eva_pos_min(), FSW_RW_J_S_MAX);
  cfg.k_desat = eva_positive_to(FSW_MTQ_DESAT_K_MAX);
  eva_reals(cfg.h_target_B, 3, -FSW_MTQ_DESAT_H_MAX, FSW_MTQ_DESAT_H_MAX);
  cfg.tau_max = eva_real(FSW_MTQ_DESAT_TAU_MIN, FSW_MTQ_DESAT_TAU_MAX);
  cfg.h_deadband = eva_real(0.0, FSW_MTQ_DESAT_H_MAX);
  EVA_ENTRY(check, fsw_mtq_desat_check(&cfg));
  s = fsw_mtq_desat_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  /* Omega: the contract bounds it by FSW_RW_OMEGA_MAX (envelope); any: every value */
  if (eva_any_mode) eva_sensors(in.Omega, FSW_MAX_RW);
  else eva_reals(in.Omega, FSW_MAX_RW, -FSW_RW_OMEGA_MAX, FSW_RW_OMEGA_MAX);
  eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
  eva_sensors(in.B_B, 3);
  in.B_valid = (uint8_t)eva_int(0, 255);
  s = fsw_mtq_desat_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

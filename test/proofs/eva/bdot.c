/* Eva driver: bdot (docs/fsw/bdot.md, docs/eva.md).
 * eva-sources: bdot.c fsw_vec.c fsw_clock.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/bdot.h"

static void run(void)
{
  FswBdotConfig cfg;
  FswBdotState st;
  FswBdotIn in;
  FswBdotOut out;
  FswStatus s;
  int k;
  const fsw_real pmin = eva_pos_min();
  cfg.variant = eva_int(FSW_BDOT_DERIV, FSW_BDOT_GYRO);
  cfg.k_bdot = eva_real(pmin, FSW_BDOT_K_MAX);
  cfg.normalize = eva_int(0, 1);
  cfg.tau_f = eva_real(0.0, FSW_BDOT_TAU_MAX);
  cfg.max_missed = eva_int(0, FSW_BDOT_MISSED_MAX);
  eva_reals(cfg.m_max_B, 3, FSW_BDOT_M_MIN, FSW_BDOT_M_MAX);
  cfg.omega_done = eva_real(pmin, FSW_BDOT_OMEGA_MAX); /* check refuses omega_reenter <= omega_done */
  cfg.omega_reenter = eva_real(pmin, FSW_BDOT_OMEGA_MAX);
  cfg.t_persist = eva_real(0.0, FSW_BDOT_T_PERSIST_MAX);
  EVA_ENTRY(check, fsw_bdot_check(&cfg));
  s = fsw_bdot_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 3; k++) { /* priming, the first derivative, the filter's memory */
    in.t_ns = eva_u64();
    eva_sensors(in.B_B, 3);
    in.B_valid = (uint8_t)eva_int(0, 255);
    eva_sensors(in.omega_BN_B, 3);
    in.omega_valid = (uint8_t)eva_int(0, 255);
    s = fsw_bdot_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

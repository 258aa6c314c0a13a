/* Eva driver: thr_momentum (docs/fsw/thr_momentum.md, docs/eva.md).
 * eva-sources: thr_momentum.c rw_common.c fsw_vec.c fsw_clock.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_common.h"
#include "fsw/thr_momentum.h"

static void run(void)
{
  FswThrMomentumConfig cfg;
  FswThrMomentumState st;
  FswThrMomentumIn in;
  FswThrMomentumOut out;
  FswStatus s;
  int k;
  const fsw_real pmin = eva_pos_min();
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_units(cfg.gs_hat_B, FSW_MAX_RW, FSW_RW_UNIT_TOL);
  eva_reals(cfg.J_s, FSW_MAX_RW, pmin, FSW_RW_J_S_MAX);
  /* intervals of each value; check refuses the combinations the contract excludes */
  cfg.h_upper = eva_real(pmin, FSW_THR_MOM_H_MAX);
  cfg.h_lower = eva_real(0.0, FSW_THR_MOM_H_MAX);
  cfg.L_dump = eva_real(FSW_THR_MOM_L_MIN, FSW_THR_MOM_L_MAX);
  cfg.t_pulse_max = eva_real(FSW_THR_MOM_T_MIN, FSW_THR_MOM_T_MAX);
  cfg.t_min_pulse = eva_real(FSW_THR_MOM_T_MIN, FSW_THR_MOM_T_MAX);
  cfg.t_coast = eva_real(0.0, FSW_THR_MOM_T_MAX);
  cfg.dt_cycle = eva_real(FSW_THR_MOM_T_MIN, FSW_THR_MOM_DT_MAX);
  cfg.num_thr = eva_int(1, FSW_MAX_THR);
  eva_reals(cfg.F_max, FSW_MAX_THR, pmin, FSW_THR_MOM_F_MAX);
  cfg.Isp = eva_real(FSW_THR_MOM_ISP_MIN, FSW_THR_MOM_ISP_MAX);
  EVA_ENTRY(check, fsw_thr_momentum_check(&cfg));
  s = fsw_thr_momentum_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 3; k++) { /* idle to pulse to coast: the dump's phases */
    in.t_ns = eva_u64();
    if (eva_any_mode) eva_sensors(in.Omega, FSW_MAX_RW);
    else eva_reals(in.Omega, FSW_MAX_RW, -FSW_RW_OMEGA_MAX, FSW_RW_OMEGA_MAX);
    eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
    if (eva_any_mode) eva_sensors(in.t_on_prev, FSW_MAX_THR);
    else eva_reals(in.t_on_prev, FSW_MAX_THR, 0.0, FSW_THR_MOM_T_ON_MAX);
    in.enable = (uint8_t)eva_int(0, 255);
    in.force_dump = (uint8_t)eva_int(0, 255);
    s = fsw_thr_momentum_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

/* Eva driver: rw_volt (docs/fsw/rw_volt.md, docs/eva.md).
 * eva-sources: rw_volt.c rw_common.c fsw_vec.c fsw_clock.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_common.h"
#include "fsw/rw_volt.h"

static void run(void)
{
  FswRwVoltConfig cfg;
  FswRwVoltState st;
  FswRwVoltIn in;
  FswRwVoltOut out;
  FswStatus s;
  int k;
  const fsw_real pmin = eva_pos_min();
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  cfg.V_min = eva_real(0.0, FSW_RW_V_MAX_MAX);
  cfg.V_max = eva_real(pmin, FSW_RW_V_MAX_MAX); /* check refuses V_max <= V_min */
  cfg.K_V = eva_real(0.0, FSW_RW_GAIN_MAX);
  eva_reals(cfg.u_max, FSW_MAX_RW, FSW_RW_U_MAX_MIN, FSW_RW_U_MAX_MAX);
  eva_reals(cfg.J_s, FSW_MAX_RW, pmin, FSW_RW_J_S_MAX);
  cfg.gate_rate = eva_int(0, 1);
  eva_positives(cfg.Omega_dot_max, FSW_MAX_RW);
  EVA_ENTRY(check, fsw_rw_volt_check(&cfg));
  s = fsw_rw_volt_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 3; k++) { /* the speed loop's warm-up: phases 0, 1, 2 */
    eva_sensors(in.u_s, FSW_MAX_RW);
    eva_sensors(in.Omega, FSW_MAX_RW);
    in.has_Omega = eva_int(0, 1);
    eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
    in.t_ns = eva_u64();
    s = fsw_rw_volt_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

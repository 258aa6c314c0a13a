/* Eva driver: mtq_map (docs/fsw/mtq_map.md, docs/eva.md).
 * eva-sources: mtq_map.c fsw_linalg.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/mtq_map.h"

static void run(void)
{
  FswMtqMapConfig cfg;
  FswMtqMapState st;
  FswMtqMapIn in;
  FswMtqMapOut out;
  FswStatus s;
  cfg.num_mtq = eva_int(1, FSW_MAX_MTQ);
  eva_units(cfg.gt_hat_B, FSW_MAX_MTQ, FSW_MTQ_UNIT_TOL);
  eva_reals(cfg.m_max, FSW_MAX_MTQ, FSW_MTQ_M_MAX_MIN, FSW_MTQ_M_MAX_MAX);
  cfg.duty_max = eva_real(FSW_MTQ_DUTY_MIN, 1.0);
  EVA_ENTRY(check, fsw_mtq_map_check(&cfg));
  s = fsw_mtq_map_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_sensors(in.tau_B, 3);
  eva_sensors(in.m_req_B, 3);
  in.use_dipole = (uint8_t)eva_int(0, 255);
  eva_sensors(in.B_B, 3);
  in.B_valid = (uint8_t)eva_int(0, 255);
  eva_bytes(in.avail, FSW_MAX_MTQ, 0, 255);
  s = fsw_mtq_map_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

/* Eva driver: rw_speed_filter (docs/fsw/rw_speed_filter.md, docs/eva.md).
 * eva-sources: rw_speed_filter.c rw_common.c fsw_vec.c fsw_clock.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/rw_speed_filter.h"

static void run(void)
{
  FswRwSpeedFilterConfig cfg;
  FswRwSpeedFilterState st;
  FswRwSpeedFilterIn in;
  FswRwSpeedFilterOut out;
  FswStatus s;
  int k;
  cfg.num_rw = eva_int(1, FSW_MAX_RW);
  eva_positives(cfg.u_max, FSW_MAX_RW);
  eva_positives(cfg.J_s, FSW_MAX_RW);
  /*@ loop unroll 64; */
  for (k = 0; k < FSW_MAX_RW; k++) {
    cfg.noise[k] = eva_nonneg();
    cfg.resid_tol[k] = eva_nonneg();
  }
  cfg.k_reject = Frama_C_unsigned_int_interval(1u, UINT32_MAX);
  cfg.n_recover = Frama_C_unsigned_int_interval(1u, UINT32_MAX);
  cfg.n_stale = Frama_C_unsigned_int_interval(0u, UINT32_MAX);
  cfg.n_window = Frama_C_unsigned_int_interval(0u, UINT32_MAX);
  EVA_ENTRY(check, fsw_rw_speed_filter_check(&cfg));
  s = fsw_rw_speed_filter_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 3; k++) { /* first sample, a later one, a third (the windows, the runs) */
    eva_sensors(in.Omega_meas, FSW_MAX_RW);
    eva_bytes(in.avail, FSW_MAX_RW, 0, 255);
    in.t_ns = eva_u64();
    eva_sensors(in.u_applied, FSW_MAX_RW);
    in.u_valid = (uint8_t)eva_int(0, 255);
    s = fsw_rw_speed_filter_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

/* Eva driver: trq_lpf (docs/fsw/trq_lpf.md, docs/eva.md).
 * eva-sources: trq_lpf.c fsw_vec.c fsw_clock.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/trq_lpf.h"

static void run(void)
{
  FswTrqLpfConfig cfg;
  FswTrqLpfState st;
  FswTrqLpfIn in;
  FswTrqLpfOut out;
  FswStatus s;
  int k;
  /* check accepts h > 0, omega_c > 0 (both finite) with omega_c h < pi */
  cfg.h = eva_positive();
  cfg.omega_c = eva_positive();
  EVA_ENTRY(check, fsw_trq_lpf_check(&cfg));
  s = fsw_trq_lpf_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* a first call and a later one: the filter's memory */
    eva_sensors(in.Lr_B, 3);
    in.t_ns = eva_u64();
    s = fsw_trq_lpf_update(&st, &cfg, &in, &out);
    EVA_ENTRY(update, s);
  }
}

EVA_MAINS

/* Eva driver: css_sun (docs/fsw/css_sun.md, docs/eva.md).
 * eva-sources: css_sun.c fsw_linalg.c fsw_vec.c fsw_status.c
 * eva-options: -eva-min-loop-unroll 33 */
#include "eva_driver.h"

#include "fsw/css_sun.h"

static void run(void)
{
  FswCssSunConfig cfg;
  FswCssSunState st;
  FswCssSunIn in;
  FswCssSunOut out;
  FswStatus s;
  cfg.num_css = eva_int(1, FSW_MAX_CSS);
  eva_units(cfg.n_hat_B, FSW_MAX_CSS, FSW_CSS_SUN_UNIT_TOL);
  eva_positives(cfg.scale, FSW_MAX_CSS);
  cfg.lit_threshold = eva_real(0.0, 0.99999999);
  EVA_ENTRY(check, fsw_css_sun_check(&cfg));
  s = fsw_css_sun_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_sensors(in.reading, FSW_MAX_CSS);
  eva_bytes(in.avail, FSW_MAX_CSS, 0, 255);
  s = fsw_css_sun_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

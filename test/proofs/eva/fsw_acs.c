/* Eva driver: fsw_acs, the application cycle (fsw/fsw_acs.h,
 * docs/fsw/fsw_acs.md, docs/eva.md) with the reference wheel configuration
 * of acs_config.h: check and init, then two cycles over any sensor message,
 * the first without a command, the second with any command (a mode or
 * policy change, a new reference or new gains).  One state per program
 * point (-eva-slevel 0) except in the cycle function (its error returns and
 * DETUMBLE's local guidance kept apart from the pointing modes') and in
 * rw_map's update and minimum-norm solve (the number of control axes kept
 * apart, as rw_map.c's analysis does); loops of up to 7 iterations unrolled
 * (css_sun's sensor loop over the 6 configured sensors returns from inside).
 * With the defaults the analysis ran over 77 s of CPU without finishing;
 * this way it takes about 13 s.
 * eva-options: -eva-slevel 0 -eva-min-loop-unroll 7 -eva-slevel-function fsw_acs_cycle:8,fsw_rw_map_update:30,fsw_minnorm_solve_factored:30
 * eva-sources: fsw_acs.c att_track.c bdot.c css_sun.c fsw_attitude.c fsw_clock.c fsw_linalg.c fsw_status.c fsw_vec.c guid_inertial.c guid_orbit.c guid_sunsafe.c mrp_fb.c mtq_desat.c mtq_map.c rw_bias.c rw_common.c rw_map.c rw_null.c rw_sat.c rw_speed_filter.c rw_volt.c thr_map.c thr_momentum.c thr_pulse_common.c thr_pulse_rem.c thr_pulse_schmitt.c trq_lpf.c */
#include "acs_config.h"

static void run(void)
{
  static FswAcsConfig cfg;
  static FswAcsState st;
  static FswAcsSensorMsg sens;
  static FswAcsCmdMsg cmd;
  static FswAcsActuatorMsg act;
  static FswAcsHealthMsg hlth;
  const char *bad;
  FswStatus s;
  eva_acs_config(&cfg);
  EVA_ENTRY(check, fsw_acs_check(&cfg, &bad));
  s = fsw_acs_init(&st, &cfg, &bad);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_acs_sensors(&sens);
  EVA_ENTRY(cycle, fsw_acs_cycle(&st, &cfg, &sens, NULL, &act, &hlth));
  eva_acs_sensors(&sens);
  eva_acs_cmd(&cmd);
  EVA_ENTRY(cycle, fsw_acs_cycle(&st, &cfg, &sens, &cmd, &act, &hlth));
}

EVA_MAINS

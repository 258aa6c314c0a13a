/* Eva driver: att_track (docs/fsw/att_track.md, docs/eva.md).
 * eva-sources: att_track.c fsw_attitude.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/att_track.h"

static void run(void)
{
  FswAttTrackConfig cfg;
  FswAttTrackState st;
  FswAttTrackIn in;
  FswAttTrackOut out;
  FswStatus s;
  int i;
  /* check accepts any finite sigma_R0R whose |sigma|^2 is finite; any: also
   * NaN and infinities, which check refuses */
  for (i = 0; i < 3; i++) cfg.sigma_R0R[i] = eva_any_mode ? eva_sensor() : eva_finite();
  EVA_ENTRY(check, fsw_att_track_check(&cfg));
  s = fsw_att_track_init(&st, &cfg);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  eva_sensors(in.sigma_BN, 3);
  eva_sensors(in.omega_BN_B, 3);
  eva_sensors(in.ref.sigma_RN, 3);
  eva_sensors(in.ref.omega_RN_N, 3);
  eva_sensors(in.ref.omega_dot_RN_N, 3);
  s = fsw_att_track_update(&st, &cfg, &in, &out);
  EVA_ENTRY(update, s);
}

EVA_MAINS

/* One control step of a flight program: attitude error -> mrp_fb -> rw_map
 * (docs/tutorial.md).  A real program runs this every control period with the
 * time stamp, guidance and wheel speeds of that period, and sends u_s to the
 * wheel drives. */
#include <stdio.h>
#include <string.h>

#include "fsw/mrp_fb.h"
#include "fsw/rw_map.h"

/* The library calls this on a programmer error (a NULL pointer). */
void fsw_assert_failed(const char *file, int line)
{
  fprintf(stderr, "fsw assert: %s:%d\n", file, line);
}

int main(void)
{
  static const fsw_real axes[4][3] = {{0.541675220, 0.541675220, 0.642787610},
                                      {-0.541675220, 0.541675220, 0.642787610},
                                      {-0.541675220, -0.541675220, 0.642787610},
                                      {0.541675220, -0.541675220, 0.642787610}};
  static FswMrpFbConfig fb_cfg;
  static FswMrpFbState fb;
  static FswRwMapConfig map_cfg;
  static FswRwMapState map;
  FswMrpFbIn fb_in;
  FswMrpFbOut fb_out;
  FswRwMapIn map_in;
  FswRwMapOut map_out;
  int i;

  fb_cfg.K = 0.5;       /* [N*m]   the gains of my_sat.yaml */
  fb_cfg.P = 6.0;       /* [N*m*s] */
  fb_cfg.K_i = -1.0;    /* integral term off */
  fb_cfg.I_B[0][0] = 60.0;
  fb_cfg.I_B[1][1] = 50.0;
  fb_cfg.I_B[2][2] = 40.0;
  map_cfg.num_rw = 4;
  memcpy(map_cfg.gs_hat_B, axes, sizeof axes);
  map_cfg.num_axes = 3;
  for (i = 0; i < 3; ++i) map_cfg.ctrl_axes_B[i][i] = 1.0;
  map_cfg.mode = FSW_RW_MAP_MIN_NORM;
  if (fsw_mrp_fb_init(&fb, &fb_cfg) != FSW_OK || fsw_rw_map_init(&map, &map_cfg) != FSW_OK) {
    fprintf(stderr, "configuration refused\n");
    return 1;
  }

  memset(&fb_in, 0, sizeof fb_in);
  fb_in.t_ns = 0;
  fb_in.guid.sigma_BR[2] = 0.1;     /* 4 atan(0.1) = 22.8 deg about z from the reference */
  fb_in.guid.omega_BR_B[0] = 0.01;  /* [rad/s] */
  if (fsw_mrp_fb_update(&fb, &fb_cfg, &fb_in, &fb_out) != FSW_OK) return 1;

  memset(&map_in, 0, sizeof map_in);
  memcpy(map_in.Lr_B, fb_out.torque_B, sizeof map_in.Lr_B);
  if (fsw_rw_map_update(&map, &map_cfg, &map_in, &map_out) != FSW_OK) return 1;

  printf("Lr = (%.4f, %.4f, %.4f) N*m\n", (double)fb_out.torque_B[0], (double)fb_out.torque_B[1],
         (double)fb_out.torque_B[2]);
  for (i = 0; i < 4; ++i) printf("wheel %d: u_s = %+.5f N*m\n", i + 1, (double)map_out.u_s[i]);
  return 0;
}

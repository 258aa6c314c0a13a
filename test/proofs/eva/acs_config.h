/* The application configuration of the fsw_acs and fsw_link_node Eva
 * drivers (docs/eva.md): the reference wheel spacecraft of the fsw_acs tests
 * (test/fsw_c/acs_fixture.hpp, wheel_config): a 900/800/600 kg m^2 body, a
 * 4-wheel pyramid (spin axes 40 deg above the x-y plane at azimuths 45 + 90 k
 * deg, J_s 0.1 kg m^2, u_max 0.2 N m), 6 coarse sun sensors on the cube
 * faces, sun-safe guidance pointing +z at the Sun, mrp_fb without the
 * integral term, rw_map MIN_NORM about the body axes, rw_sat SCALE; no
 * filter, null motion, voltages, thrusters, rods or orbit.  Concrete values:
 * the inputs, not the configuration, are what these drivers vary. */
#ifndef EVA_ACS_CONFIG_H
#define EVA_ACS_CONFIG_H

#include <string.h>

#include "eva_driver.h"

#include "fsw/fsw_acs.h"

/* cos(40 deg) cos(45 deg + 90 k deg), cos(40 deg) sin(...), sin(40 deg) */
#define EVA_PYR_XY 0.5416752204197018
#define EVA_PYR_Z 0.6427876096865393

static void eva_acs_config(FswAcsConfig *c)
{
  static FswAcsGeometry g;
  static const fsw_real sx[4] = {1.0, -1.0, -1.0, 1.0}, sy[4] = {1.0, 1.0, -1.0, -1.0};
  int i;
  (void)memset(c, 0, sizeof *c);
  (void)memset(&g, 0, sizeof g);
  c->initial_mode = FSW_ACS_MODE_SUN_SAFE;
  c->initial_actuation = FSW_ACS_ACT_WHEELS;
  c->css.num_css = 6;
  for (i = 0; i < 6; i++) {
    c->css.n_hat_B[i][i / 2] = (i % 2 == 0) ? 1.0 : -1.0;
    c->css.scale[i] = 1.0;
  }
  c->css.lit_threshold = 0.01;
  c->sunsafe.s_cmd_B[2] = 1.0;
  c->sunsafe.min_unit_mag = 0.1;
  c->sunsafe.small_angle = 1e-4;
  c->sunsafe.omega_search_B[2] = 0.005;
  c->inertial.sigma_R0N[0] = 0.1;
  c->inertial.sigma_R0N[1] = -0.05;
  c->inertial.sigma_R0N[2] = 0.2;
  c->mrp_fb.K = 1.44;
  c->mrp_fb.P = 36.0;
  c->mrp_fb.K_i = -1.0;
  c->mrp_fb.integral_limit = 0.0;
  c->mrp_fb.I_B[0][0] = 900.0;
  c->mrp_fb.I_B[1][1] = 800.0;
  c->mrp_fb.I_B[2][2] = 600.0;
  c->lpf.h = 0.5;
  c->lpf.omega_c = 1.0;
  g.num_rw = 4;
  for (i = 0; i < 4; i++) {
    g.gs_hat_B[i][0] = sx[i] * EVA_PYR_XY;
    g.gs_hat_B[i][1] = sy[i] * EVA_PYR_XY;
    g.gs_hat_B[i][2] = EVA_PYR_Z;
    g.J_s[i] = 0.1;
    g.u_max[i] = 0.2;
  }
  (void)fsw_acs_config_set_geometry(c, &g);
  c->rw_map.num_axes = 3;
  for (i = 0; i < 3; i++) c->rw_map.ctrl_axes_B[i][i] = 1.0;
  c->rw_map.mode = FSW_RW_MAP_MIN_NORM;
  c->rw_map.eps_P = 1.0;
  c->rw_null.k_null = 0.002;
  c->rw_null.scale_to_fit = 1;
  c->rw_sat.mode = FSW_RW_SAT_SCALE;
  c->rw_volt.V_min = 0.0;
  c->rw_volt.V_max = 10.0;
  c->rw_volt.K_V = 0.0;
}

/* A sensor message over the contract's domains: every real a sensor input
 * (eva_sensor: the envelope, or any finite, NaN or infinite), every flag and
 * availability byte 0..255, any time stamp; every entry of every array, not
 * only the configured ones. */
static void eva_acs_sensors(FswAcsSensorMsg *m)
{
  m->t_ns = eva_u64();
  eva_sensors(m->sigma_BN, 3);
  m->att_valid = (uint8_t)eva_int(0, 255);
  eva_sensors(m->omega_BN_B, 3);
  eva_sensors(m->css, FSW_MAX_CSS);
  eva_bytes(m->css_avail, FSW_MAX_CSS, 0, 255);
  eva_sensors(m->Omega, FSW_MAX_RW);
  eva_bytes(m->rw_avail, FSW_MAX_RW, 0, 255);
  eva_sensors(m->r_CoM_B, 3);
  eva_bytes(m->thr_avail, FSW_MAX_THR, 0, 255);
  eva_sensors(m->B_B, 3);
  m->mag_valid = (uint8_t)eva_int(0, 255);
  eva_sensors(m->r_N, 3);
  eva_sensors(m->v_N, 3);
  m->orbit_valid = (uint8_t)eva_int(0, 255);
}

/* A command over its domain: any of the four modes and two actuations (the
 * ones not configured are refused), every flag 0..255, the reference and
 * gains sensor inputs, any of the three policies. */
static void eva_acs_cmd(FswAcsCmdMsg *m)
{
  m->mode = eva_int(FSW_ACS_MODE_SUN_SAFE, FSW_ACS_MODE_NADIR);
  m->actuation = eva_int(FSW_ACS_ACT_WHEELS, FSW_ACS_ACT_THRUSTERS);
  m->set_ref = (uint8_t)eva_int(0, 255);
  eva_sensors(m->sigma_R0N, 3);
  m->set_gains = (uint8_t)eva_int(0, 255);
  m->K = eva_sensor();
  m->P = eva_sensor();
  m->set_policy = (uint8_t)eva_int(0, 255);
  m->policy = eva_int(FSW_ACS_MOM_NONE, FSW_ACS_MOM_MAGNETORQUERS);
}

#endif /* EVA_ACS_CONFIG_H */

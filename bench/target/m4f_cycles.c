/* Instructions per fsw_acs_cycle and per module update on the Cortex-M4F
 * (QEMU mps2-an386, -icount shift=0; docs/performance.md, "Flight cycle on
 * the target").  A benchmark: it prints, it asserts nothing.
 *
 * Replays the golden sequences of test/fsw_c/data/fsw_acs_golden.inc (the
 * inputs recorded from the closed loop of test/fsw_c/acs_fixture.hpp) with
 * their configurations, ported here to C:
 *   scenario 0: 4-wheel pyramid (S1's spacecraft and wheel geometry), 6 CSS,
 *               rw_null, trq_lpf and rw_volt on; 40 cycles SUN_SAFE, then
 *               40 cycles INERTIAL;
 *   scenario 1: 8 thrusters, INERTIAL, remainder pulser, 40 cycles;
 *   scenario 2: the same with the Schmitt pulser.
 * Each cycle is counted whole (m4f_count around fsw_acs_cycle), then every
 * module the cycle ran is counted alone: its state as it was before the
 * cycle, the inputs the cycle gave it (the work area), its configuration.
 * A module count includes its call's argument set-up (a few instructions).
 * Prints min / median (lower middle) / max per mode and item.
 * Application code: C99, static storage, no heap. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "data/fsw_acs_golden.h"
#include "fsw/fsw_acs.h"
#include "m4f_counter.h"

void fsw_assert_failed(const char *file, int line);
void fsw_assert_failed(const char *file, int line) { printf("m4f_cycles: FSW assertion failed at %s:%d\n", file, line); }

static const FswAcsGoldenCycle kGolden[] = {
#include "data/fsw_acs_golden.inc"
};
#define NUM_GOLDEN (sizeof kGolden / sizeof kGolden[0])

/* ---- the configurations of acs_fixture.hpp's golden_config() ---------- */
#define PI 3.14159265358979323846
static fsw_real R(double x) { return (fsw_real)x; }

static void base_config(FswAcsConfig *c)
{
  int i;
  memset(c, 0, sizeof *c);
  c->initial_mode = FSW_ACS_MODE_SUN_SAFE;
  c->initial_actuation = FSW_ACS_ACT_WHEELS;
  c->css.num_css = 6;
  for (i = 0; i < 6; i++) {
    c->css.n_hat_B[i][i / 2] = R(i % 2 == 0 ? 1.0 : -1.0);
    c->css.scale[i] = R(1.0);
  }
  c->css.lit_threshold = R(0.01);
  c->sunsafe.s_cmd_B[2] = R(1.0);
  c->sunsafe.min_unit_mag = R(0.1);
  c->sunsafe.small_angle = R(1e-4);
  c->sunsafe.omega_search_B[2] = R(0.005);
  c->inertial.sigma_R0N[0] = R(0.1);
  c->inertial.sigma_R0N[1] = R(-0.05);
  c->inertial.sigma_R0N[2] = R(0.2);
  c->mrp_fb.K = R(1.44);
  c->mrp_fb.P = R(36.0);
  c->mrp_fb.K_i = R(-1.0);
  c->mrp_fb.integral_limit = R(0.0);
  c->mrp_fb.I_B[0][0] = R(900.0);
  c->mrp_fb.I_B[1][1] = R(800.0);
  c->mrp_fb.I_B[2][2] = R(600.0);
  c->lpf.h = R(0.5);
  c->lpf.omega_c = R(1.0);
}

static int wheel_config(FswAcsConfig *c)
{
  static FswAcsGeometry g;
  int i, k;
  base_config(c);
  memset(&g, 0, sizeof g);
  g.num_rw = 4;
  for (i = 0; i < 4; i++) {
    const double el = 40.0 * PI / 180.0, az = (45.0 + 90.0 * i) * PI / 180.0;
    g.gs_hat_B[i][0] = R(cos(el) * cos(az));
    g.gs_hat_B[i][1] = R(cos(el) * sin(az));
    g.gs_hat_B[i][2] = R(sin(el));
    g.J_s[i] = R(0.1);
    g.u_max[i] = R(0.2);
  }
  if (fsw_acs_config_set_geometry(c, &g) != FSW_OK) return -1;
  c->rw_map.num_axes = 3;
  for (k = 0; k < 3; k++) c->rw_map.ctrl_axes_B[k][k] = R(1.0);
  c->rw_map.mode = FSW_RW_MAP_MIN_NORM;
  c->rw_map.eps_P = R(1.0);
  c->rw_null.k_null = R(0.002);
  c->rw_null.scale_to_fit = 1;
  c->rw_sat.mode = FSW_RW_SAT_SCALE;
  c->rw_volt.V_min = R(0.0);
  c->rw_volt.V_max = R(10.0);
  c->rw_volt.K_V = R(0.0);
  c->use_null = 1;
  c->use_lpf = 1;
  c->use_volt = 1;
  c->Omega_des[0] = R(20.0);
  return 0;
}

static int thruster_config(FswAcsConfig *c, int pulser)
{
  static const double r[8][3] = {{-0.86360, -0.82550, 1.79070},  {-0.82550, -0.86360, 1.79070},
                                 {0.82550, 0.86360, 1.79070},    {0.86360, 0.82550, 1.79070},
                                 {-0.86360, -0.82550, -1.79070}, {-0.82550, -0.86360, -1.79070},
                                 {0.82550, 0.86360, -1.79070},   {0.86360, 0.82550, -1.79070}};
  static const double gt[8][3] = {{1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {-1, 0, 0},
                                  {-1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {1, 0, 0}};
  static FswAcsGeometry g;
  int i, k;
  base_config(c);
  c->initial_mode = FSW_ACS_MODE_INERTIAL;
  c->initial_actuation = FSW_ACS_ACT_THRUSTERS;
  memset(&g, 0, sizeof g);
  g.num_thr = 8;
  for (i = 0; i < 8; i++) {
    for (k = 0; k < 3; k++) {
      g.r_thr_B[i][k] = R(r[i][k]);
      g.gt_hat_B[i][k] = R(gt[i][k]);
    }
    g.F_max[i] = R(1.0);
  }
  if (fsw_acs_config_set_geometry(c, &g) != FSW_OK) return -1;
  c->mrp_fb.K = R(20.0);
  c->mrp_fb.P = R(200.0);
  for (k = 0; k < 3; k++) c->thr_map.control_axes_B[k][k] = R(1.0);
  c->thr_map.thr_force_sign = 1;
  c->thr_map.ang_err_thresh = R(0.0);
  c->thr_map.mode = FSW_THR_MAP_NNLS;
  c->pulser = pulser;
  c->pulse_rem.common.t_min = R(0.02);
  c->pulse_rem.common.init_off_pulse_on_time = R(2.0);
  c->pulse_schmitt.common.t_min = R(0.02);
  c->pulse_schmitt.level_on = R(0.75);
  c->pulse_schmitt.level_off = R(0.25);
  c->pulse_schmitt.common.init_off_pulse_on_time = R(2.0);
  return 0;
}

/* ---- what is counted ---------------------------------------------------- */
static FswAcsConfig g_cfg;
static FswAcsState g_st;  /* the replay */
static FswAcsState g_pre; /* the replay's state before the cycle */
static FswAcsState g_scr; /* scratch: each module counted alone */
static FswAcsSensorMsg g_sens;
static FswAcsCmdMsg g_cmd;
static FswAcsActuatorMsg g_act;
static FswAcsHealthMsg g_health;
static FswStatus g_status;

static void t_cycle(void *a)
{
  (void)a;
  g_status = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g_cmd, &g_act, &g_health);
}
#define W (&g_st.work)
#define O (&g_scr.work)
static void t_css(void *a) { (void)a; (void)fsw_css_sun_update(&g_scr.css, &g_cfg.css, &W->css_in, &O->css_out); }
static void t_sunsafe(void *a)
{
  (void)a;
  (void)fsw_guid_sunsafe_update(&g_scr.sunsafe, &g_cfg.sunsafe, &W->sunsafe_in, &O->sunsafe_out);
}
static void t_inertial(void *a) { (void)a; (void)fsw_guid_inertial_update(&g_scr.inertial, &g_scr.inertial_cfg, &O->inertial_out); }
static void t_track(void *a) { (void)a; (void)fsw_att_track_update(&g_scr.track, &g_cfg.track, &W->track_in, &O->track_out); }
static void t_mrp_fb(void *a) { (void)a; (void)fsw_mrp_fb_update(&g_scr.mrp_fb, &g_scr.mrp_cfg, &W->fb_in, &O->fb_out); }
static void t_lpf(void *a) { (void)a; (void)fsw_trq_lpf_update(&g_scr.lpf, &g_cfg.lpf, &W->lpf_in, &O->lpf_out); }
static void t_rw_map(void *a) { (void)a; (void)fsw_rw_map_update(&g_scr.rw_map, &g_cfg.rw_map, &W->map_in, &O->map_out); }
static void t_rw_null(void *a) { (void)a; (void)fsw_rw_null_update(&g_scr.rw_null, &g_cfg.rw_null, &W->null_in, &O->null_out); }
static void t_rw_sat(void *a) { (void)a; (void)fsw_rw_sat_update(&g_scr.rw_sat, &g_cfg.rw_sat, &W->sat_in, &O->sat_out); }
static void t_rw_volt(void *a) { (void)a; (void)fsw_rw_volt_update(&g_scr.rw_volt, &g_cfg.rw_volt, &W->volt_in, &O->volt_out); }
static void t_thr_map(void *a) { (void)a; (void)fsw_thr_map_update(&g_scr.thr_map, &g_cfg.thr_map, &W->thr_in, &O->thr_out); }
static void t_rem(void *a)
{
  (void)a;
  (void)fsw_thr_pulse_rem_update(&g_scr.pulse_rem, &g_cfg.pulse_rem, &W->rem_in, &O->rem_out);
}
static void t_schmitt(void *a)
{
  (void)a;
  (void)fsw_thr_pulse_schmitt_update(&g_scr.pulse_schmitt, &g_cfg.pulse_schmitt, &W->sch_in, &O->sch_out);
}

enum { I_CYCLE, I_CSS, I_SUNSAFE, I_INERTIAL, I_TRACK, I_MRP_FB, I_LPF, I_RW_MAP, I_RW_NULL, I_RW_SAT, I_RW_VOLT,
       I_THR_MAP, I_REM, I_SCHMITT, NUM_ITEMS };
static const char *const kItemName[NUM_ITEMS] = {
    "fsw_acs_cycle", "css_sun", "guid_sunsafe", "guid_inertial", "att_track", "mrp_fb", "trq_lpf",
    "rw_map", "rw_null", "rw_sat", "rw_volt", "thr_map", "thr_pulse_rem", "thr_pulse_schmitt"};
static const M4fCountFn kItemFn[NUM_ITEMS] = {t_cycle, t_css, t_sunsafe, t_inertial, t_track, t_mrp_fb, t_lpf,
                                               t_rw_map, t_rw_null, t_rw_sat, t_rw_volt, t_thr_map, t_rem,
                                               t_schmitt};
enum { G_SUN_WHEELS, G_INERTIAL_WHEELS, G_INERTIAL_REM, G_INERTIAL_SCHMITT, NUM_GROUPS };
static const char *const kGroupName[NUM_GROUPS] = {"SUN_SAFE, wheels", "INERTIAL, wheels",
                                                   "INERTIAL, thrusters (remainder)", "INERTIAL, thrusters (Schmitt)"};
#define MAX_SAMPLES 80u
static uint32_t g_samples[NUM_GROUPS][NUM_ITEMS][MAX_SAMPLES];
static uint32_t g_count[NUM_GROUPS][NUM_ITEMS];
static uint32_t g_bad_counts;

static void record(int group, int item)
{
  const uint32_t n = m4f_count(kItemFn[item], 0);
  if (n == UINT32_MAX) g_bad_counts++;
  if (g_count[group][item] < MAX_SAMPLES) g_samples[group][item][g_count[group][item]++] = n;
}

/* the modules the cycle ran, each counted alone */
static void record_modules(int group)
{
  static const int sun[] = {I_CSS, I_SUNSAFE, I_MRP_FB, I_LPF, I_RW_MAP, I_RW_NULL, I_RW_SAT, I_RW_VOLT, -1};
  static const int inw[] = {I_INERTIAL, I_TRACK, I_MRP_FB, I_LPF, I_RW_MAP, I_RW_NULL, I_RW_SAT, I_RW_VOLT, -1};
  static const int rem[] = {I_INERTIAL, I_TRACK, I_MRP_FB, I_THR_MAP, I_REM, -1};
  static const int sch[] = {I_INERTIAL, I_TRACK, I_MRP_FB, I_THR_MAP, I_SCHMITT, -1};
  static const int *const list[NUM_GROUPS] = {sun, inw, rem, sch};
  const int *p;
  for (p = list[group]; *p >= 0; ++p) {
    g_scr = g_pre;
    record(group, *p);
  }
}

int main(void)
{
  size_t k;
  int sc_prev = -1, g, i;
  uint32_t cycles = 0, status_equal = 0;
  if (m4f_counter_init() != 0) {
    printf("m4f_cycles: SysTick vernier failed (run under qemu-system-arm -icount shift=0)\n");
    return 1;
  }
  for (k = 0; k < NUM_GOLDEN; ++k) {
    const FswAcsGoldenCycle *c = &kGolden[k];
    int group;
    if (c->scenario != sc_prev) {
      const int ok = c->scenario == 0 ? wheel_config(&g_cfg)
                                      : thruster_config(&g_cfg, c->scenario == 1 ? FSW_ACS_PULSE_REMAINDER
                                                                                 : FSW_ACS_PULSE_SCHMITT);
      if (ok != 0 || fsw_acs_init(&g_st, &g_cfg, NULL) != FSW_OK) {
        printf("m4f_cycles: scenario %d: configuration refused\n", c->scenario);
        return 1;
      }
      sc_prev = c->scenario;
    }
    memset(&g_sens, 0, sizeof g_sens);
    g_sens.t_ns = c->t_ns;
    g_sens.att_valid = 1;
    for (i = 0; i < 3; i++) {
      g_sens.sigma_BN[i] = R(c->sigma[i]);
      g_sens.omega_BN_B[i] = R(c->omega[i]);
    }
    for (i = 0; i < 6; i++) g_sens.css[i] = R(c->css[i]);
    for (i = 0; i < 4; i++) g_sens.Omega[i] = R(c->Omega[i]);
    memset(&g_cmd, 0, sizeof g_cmd);
    g_cmd.mode = c->mode;
    g_cmd.actuation = g_cfg.initial_actuation;
    group = c->scenario == 0 ? (c->mode == FSW_ACS_MODE_SUN_SAFE ? G_SUN_WHEELS : G_INERTIAL_WHEELS)
                             : (c->scenario == 1 ? G_INERTIAL_REM : G_INERTIAL_SCHMITT);
    g_pre = g_st;
    record(group, I_CYCLE);
    record_modules(group);
    cycles++;
    if ((int)g_status == c->status) status_equal++;
  }
  printf("m4f_cycles: fsw_real %s, %lu cycles replayed, status equal to the recorded one in %lu, %lu failed counts\n",
         sizeof(fsw_real) == 4u ? "float" : "double", (unsigned long)cycles, (unsigned long)status_equal,
         (unsigned long)g_bad_counts);
  printf("| mode, actuation | item | n | min | median | max |\n| --- | --- | ---: | ---: | ---: | ---: |\n");
  for (g = 0; g < NUM_GROUPS; ++g) {
    for (i = 0; i < NUM_ITEMS; ++i) {
      const uint32_t n = g_count[g][i];
      if (n == 0u) continue;
      m4f_sort(g_samples[g][i], n);
      printf("| %s | %s | %lu | %lu | %lu | %lu |\n", kGroupName[g], kItemName[i], (unsigned long)n,
             (unsigned long)g_samples[g][i][0], (unsigned long)g_samples[g][i][(n - 1u) / 2u],
             (unsigned long)g_samples[g][i][n - 1u]);
    }
  }
  return 0;
}

/* Eva driver: thr_pulse_rem, thr_pulse_round, thr_pulse_schmitt
 * (docs/fsw/thr_pulse_*.md, docs/eva.md).
 * eva-include: thr_pulse_round_clamp.h thr_pulse_on_time.h
 * eva-sources: thr_pulse_rem.c thr_pulse_round.c thr_pulse_schmitt.c thr_pulse_common.c fsw_clock.c fsw_vec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/thr_pulse_rem.h"
#include "fsw/thr_pulse_round.h"
#include "fsw/thr_pulse_schmitt.h"

/* The thruster set every variant's check accepts. */
static void thrusters(int *num_thr, fsw_real F_max[FSW_MAX_THR])
{
  *num_thr = eva_int(1, FSW_MAX_THR);
  eva_positives(F_max, FSW_MAX_THR);
}

static void common(FswThrPulseCommon *c)
{
  thrusters(&c->num_thr, c->F_max);
  c->t_min = eva_positive();
  c->base_thrust_state = eva_int(0, 1);
  c->init_off_pulse_on_time = eva_nonneg();
}

/* Force commands and a time stamp. */
static uint64_t forces(fsw_real F[FSW_MAX_THR])
{
  eva_sensors(F, FSW_MAX_THR);
  return eva_u64();
}

static void rem(void)
{
  FswThrPulseRemConfig cfg;
  FswThrPulseRemState st;
  FswThrPulseRemIn in;
  FswThrPulseRemOut out;
  FswStatus s;
  int k;
  common(&cfg.common);
  EVA_ENTRY(rem_check, fsw_thr_pulse_rem_check(&cfg));
  s = fsw_thr_pulse_rem_init(&st, &cfg);
  EVA_ENTRY(rem_init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the remainders carried to a second call */
    in.t_ns = forces(in.F);
    s = fsw_thr_pulse_rem_update(&st, &cfg, &in, &out);
    EVA_ENTRY(rem_update, s);
  }
}

static void round_(void)
{
  FswThrPulseRoundConfig cfg;
  FswThrPulseRoundState st;
  FswThrPulseRoundIn in;
  FswThrPulseRoundOut out;
  FswStatus s;
  int k;
  thrusters(&cfg.num_thr, cfg.F_max);
  cfg.period = eva_positive();
  cfg.resolution = eva_positive();
  cfg.t_min = eva_real(0.0, cfg.period);
  cfg.carry_residual = eva_int(0, 1);
  EVA_ENTRY(round_check, fsw_thr_pulse_round_check(&cfg));
  s = fsw_thr_pulse_round_init(&st, &cfg);
  EVA_ENTRY(round_init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the residuals carried to a second call */
    in.t_ns = forces(in.F);
    s = fsw_thr_pulse_round_update(&st, &cfg, &in, &out);
    EVA_ENTRY(round_update, s);
  }
}

static void schmitt(void)
{
  FswThrPulseSchmittConfig cfg;
  FswThrPulseSchmittState st;
  FswThrPulseSchmittIn in;
  FswThrPulseSchmittOut out;
  FswStatus s;
  int k;
  common(&cfg.common);
  cfg.level_on = eva_real(EVA_TINY, 1.0);
  cfg.level_off = eva_real(0.0, cfg.level_on);
  EVA_ENTRY(schmitt_check, fsw_thr_pulse_schmitt_check(&cfg));
  s = fsw_thr_pulse_schmitt_init(&st, &cfg);
  EVA_ENTRY(schmitt_init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) { /* the hysteresis memory read by a second call */
    in.t_ns = forces(in.F);
    s = fsw_thr_pulse_schmitt_update(&st, &cfg, &in, &out);
    EVA_ENTRY(schmitt_update, s);
  }
}

static void run(void)
{
  rem();
  round_();
  schmitt();
}

EVA_MAINS

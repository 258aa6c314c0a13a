/* thr_momentum: thruster momentum management and dumping (see the header
 * and docs/fsw/thr_momentum.md). */
#include "fsw/thr_momentum.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

/* 1 when x is finite and lo <= x <= hi. */
static int in_range(fsw_real x, fsw_real lo, fsw_real hi)
{
  return isfinite(x) && x >= lo && x <= hi;
}

static uint32_t inc_sat(uint32_t n) { return n < UINT32_MAX ? n + 1u : n; }

/* Seconds from a to b (b >= a), from the integer difference. */
static fsw_real ns_to_s(uint64_t a, uint64_t b) { return fsw_clock_ns_to_s(b - a); }

FswStatus fsw_thr_momentum_check(const FswThrMomentumConfig *cfg)
{
  FswStatus s;
  fsw_real cycle; /* [N*m*s] impulse of one full-torque cycle */
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_rw_check_axes(cfg->gs_hat_B, cfg->num_rw, 1);
  if (s != FSW_OK) { return s; }
  if (cfg->num_thr < 1 || cfg->num_thr > FSW_MAX_THR) { return FSW_E_CAPACITY; }
  if (!fsw_rw_all_in_range(cfg->J_s, cfg->num_rw, FSW_R(0.0), FSW_RW_J_S_MAX)) { return FSW_E_CONFIG; }
  if (!in_range(cfg->L_dump, FSW_THR_MOM_L_MIN, FSW_THR_MOM_L_MAX)) { return FSW_E_CONFIG; }
  if (!in_range(cfg->dt_cycle, FSW_THR_MOM_T_MIN, FSW_THR_MOM_DT_MAX)) { return FSW_E_CONFIG; }
  if (!in_range(cfg->t_min_pulse, FSW_THR_MOM_T_MIN, FSW_THR_MOM_T_MAX)) { return FSW_E_CONFIG; }
  if (!in_range(cfg->t_pulse_max, cfg->t_min_pulse, FSW_THR_MOM_T_MAX)) { return FSW_E_CONFIG; }
  if (!(cfg->t_pulse_max <= FSW_THR_MOM_CYCLES_MAX * cfg->dt_cycle)) { return FSW_E_CONFIG; }
  if (!in_range(cfg->t_coast, FSW_R(0.0), FSW_THR_MOM_T_MAX)) { return FSW_E_CONFIG; }
  cycle = cfg->L_dump * cfg->dt_cycle;
  if (!in_range(cfg->h_upper, FSW_R(0.0), FSW_THR_MOM_H_MAX) || !(cfg->h_upper > FSW_R(0.0)) ||
      !(cfg->h_upper <= FSW_THR_MOM_CYCLES_MAX * cycle)) {
    return FSW_E_CONFIG; }
  if (!in_range(cfg->h_lower, FSW_R(0.0), cfg->h_upper) || !(cfg->h_lower < cfg->h_upper)) { return FSW_E_CONFIG; }
  /* the band must hold at least one minimum pulse, or no dump can start */
  if (!(cfg->h_upper - cfg->h_lower >= cfg->L_dump * cfg->t_min_pulse)) { return FSW_E_CONFIG; }
  if (!fsw_rw_all_in_range(cfg->F_max, cfg->num_thr, FSW_R(0.0), FSW_THR_MOM_F_MAX)) { return FSW_E_CONFIG; }
  if (!in_range(cfg->Isp, FSW_THR_MOM_ISP_MIN, FSW_THR_MOM_ISP_MAX)) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_thr_momentum_init(FswThrMomentumState *st, const FswThrMomentumConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_thr_momentum_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_thr_momentum_reset(st);
  return FSW_OK;
}

void fsw_thr_momentum_reset(FswThrMomentumState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  fsw_clock_reset(&st->clock);
  st->phase = FSW_THR_MOM_IDLE;
  st->phase_out = FSW_THR_MOM_IDLE;
  fsw_v3_zero(st->u_B);
  fsw_v3_zero(st->dH_B);
  st->I_rem = FSW_R(0.0);
  st->I_pulse = FSW_R(0.0);
  st->L_prev = FSW_R(0.0);
  st->t_start_ns = 0u;
  st->t_cmd_ns = 0u;
  st->dumps = 0u;
  st->aborts = 0u;
  st->pulses = 0u;
  st->t_dump = FSW_R(0.0);
  st->prop_dump = FSW_R(0.0);
  st->prop_total = FSW_R(0.0);
}

/* The report fields of the output from the state (after the state's last
 * accepted call); L_thr_B, h_w_B and h_norm are not touched. */
static void report(FswThrMomentumOut *out, const FswThrMomentumState *st)
{
  out->phase = st->phase_out;
  if (st->phase_out != FSW_THR_MOM_IDLE) { fsw_v3_scale(out->dH_rem_B, st->I_rem, st->u_B); }
  else { fsw_v3_zero(out->dH_rem_B); }
  fsw_v3_copy(out->dH_B, st->dH_B);
  out->dumps = st->dumps;
  out->aborts = st->aborts;
  out->pulses = st->pulses;
  out->t_dump = st->t_dump;
  out->prop_dump = st->prop_dump;
  out->prop_total = st->prop_total;
}

static void zero_out(FswThrMomentumOut *out)
{
  fsw_v3_zero(out->L_thr_B);
  out->phase = FSW_THR_MOM_IDLE;
  fsw_v3_zero(out->dH_rem_B);
  fsw_v3_zero(out->h_w_B);
  out->h_norm = FSW_R(0.0);
  out->dumps = 0u;
  out->t_dump = FSW_R(0.0);
  out->prop_dump = FSW_R(0.0);
  out->prop_total = FSW_R(0.0);
  fsw_v3_zero(out->dH_B);
  out->aborts = 0u;
  out->pulses = 0u;
}

static int input_ok(const FswThrMomentumConfig *cfg, const FswThrMomentumIn *in)
{
  int j;
  if (!fsw_rw_avail_valid(in->avail, cfg->num_rw)) { return 0; }
  if (!fsw_rw_avail_speed_ok(in->Omega, in->avail, cfg->num_rw)) { return 0; }
  for (j = 0; j < cfg->num_thr; j++) {
    if (!in_range(in->t_on_prev[j], FSW_R(0.0), FSW_THR_MOM_T_ON_MAX)) { return 0; } }
  if (in->enable > 1u || in->force_dump > 1u) { return 0; }
  return 1;
}

/* Start a pulse: its impulse is the remaining one, at most L_dump t_pulse_max. */
static void pulse_start(FswThrMomentumState *st, const FswThrMomentumConfig *cfg)
{
  const fsw_real I_max = cfg->L_dump * cfg->t_pulse_max;
  st->I_pulse = st->I_rem < I_max ? st->I_rem : I_max;
  st->pulses = inc_sat(st->pulses);
}

/* One PULSE cycle's command at t_ns: the torque that delivers a full
 * cycle's impulse, or the rest of the pulse, over the next dt_cycle.  The
 * impulse I_c is counted off the pulse and the dump now. */
static void pulse_command(FswThrMomentumState *st, const FswThrMomentumConfig *cfg, uint64_t t_ns,
                          fsw_real L_thr_B[3])
{
  const fsw_real full = cfg->L_dump * cfg->dt_cycle; /* [N*m*s] */
  const fsw_real I_c = st->I_pulse < full ? st->I_pulse : full;
  fsw_real L = I_c / cfg->dt_cycle;
  if (L > cfg->L_dump) { L = cfg->L_dump; } /* rounding of the quotient */
  fsw_v3_scale(L_thr_B, L, st->u_B);
  st->L_prev = L;
  st->t_cmd_ns = t_ns;
  st->I_rem = st->I_rem > I_c ? st->I_rem - I_c : FSW_R(0.0);
  st->I_pulse -= I_c;
  if (st->I_pulse <= FSW_THR_MOM_CYCLE_TOL * full) {
    st->I_pulse = FSW_R(0.0); /* pulse complete; a rounding crumb stays in I_rem */
    st->phase = FSW_THR_MOM_COAST;
  } else {
    st->phase = FSW_THR_MOM_PULSE;
  }
}

/* Start a dump from the wheel momentum h (|h| = hn > h_lower). */
static void dump_start(FswThrMomentumState *st, const FswThrMomentumConfig *cfg, const fsw_real h[3],
                       fsw_real hn, uint64_t t_ns)
{
  const fsw_real cap = FSW_R(2.0) * FSW_THR_MOM_CYCLES_MAX * cfg->L_dump * cfg->dt_cycle;
  const fsw_real dH = hn - cfg->h_lower; /* [N*m*s] |Delta_H| */
  fsw_v3_scale(st->u_B, -FSW_R(1.0) / hn, h);
  if (dH <= cap) {
    /* Delta_H = -h (1 - h_lower/|h|), written -h (|h| - h_lower)/|h|: the
     * difference of the norms is exact when they are close, where
     * 1 - h_lower/|h| would cancel */
    fsw_v3_scale(st->dH_B, -(dH / hn), h);
    st->I_rem = dH;
  } else {
    fsw_v3_scale(st->dH_B, cap, st->u_B);
    st->I_rem = cap;
  }
  st->t_start_ns = t_ns;
  st->pulses = 0u;
  st->t_dump = FSW_R(0.0);
  st->prop_dump = FSW_R(0.0);
}

FswStatus fsw_thr_momentum_update(FswThrMomentumState *st, const FswThrMomentumConfig *cfg,
                                  const FswThrMomentumIn *in, FswThrMomentumOut *out)
{
  FswStatus s;
  fsw_real dt;          /* [s] period since the previous accepted call */
  fsw_real h[3], hn;    /* [N*m*s] wheel momentum and its norm */
  fsw_real dm;          /* [kg] propellant reported by this call */
  fsw_real I_min;       /* [N*m*s] minimum pulse impulse */
  int i, out_phase;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { zero_out(out); } /* safe output */
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (!input_ok(cfg, in)) {
    report(out, st);
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  s = fsw_clock_dt(&st->clock, in->t_ns, &dt);
  if (s != FSW_OK) {
    report(out, st);
    return fsw_health_record(&st->health, s);
  }
  /* Inputs are valid and bounded: nothing below can fail or overflow, so
   * the state is advanced in place from here on. */
  if (st->clock.has_prev && st->L_prev > FSW_R(0.0) &&
      FSW_FABS(dt - cfg->dt_cycle) > FSW_THR_MOM_RATE_TOL * cfg->dt_cycle) {
    s = FSW_W_RATE; }

  fsw_rw_momentum(h, cfg->gs_hat_B, cfg->J_s, in->Omega, in->avail, cfg->num_rw);
  hn = fsw_v3_norm(h);

  /* propellant of the previous cycle's on-times, attributed to that cycle */
  if (st->clock.has_prev && st->phase_out != FSW_THR_MOM_IDLE) {
    dm = FSW_R(0.0);
    for (i = 0; i < cfg->num_thr; i++) { dm += cfg->F_max[i] * in->t_on_prev[i]; }
    dm /= cfg->Isp * FSW_THR_MOM_G0;
    st->prop_dump += dm;
    st->prop_total += dm;
  }

  I_min = cfg->L_dump * cfg->t_min_pulse;
  st->L_prev = FSW_R(0.0);
  out_phase = FSW_THR_MOM_IDLE;
  if (st->phase == FSW_THR_MOM_IDLE) {
    const int trigger = hn > cfg->h_upper || (in->force_dump && hn > cfg->h_lower);
    if (in->enable && trigger && hn - cfg->h_lower >= I_min) {
      dump_start(st, cfg, h, hn, in->t_ns);
      pulse_start(st, cfg);
      pulse_command(st, cfg, in->t_ns, out->L_thr_B);
      out_phase = FSW_THR_MOM_PULSE;
    }
  } else if (!in->enable) {
    st->phase = FSW_THR_MOM_IDLE; /* abort */
    st->aborts = inc_sat(st->aborts);
    st->t_dump = ns_to_s(st->t_start_ns, in->t_ns);
  } else if (st->phase == FSW_THR_MOM_PULSE) {
    pulse_command(st, cfg, in->t_ns, out->L_thr_B);
    out_phase = FSW_THR_MOM_PULSE;
  } else { /* COAST */
    const fsw_real t_wait = cfg->dt_cycle + cfg->t_coast - FSW_THR_MOM_CYCLE_TOL * cfg->dt_cycle;
    if (!(ns_to_s(st->t_cmd_ns, in->t_ns) >= t_wait)) {
      out_phase = FSW_THR_MOM_COAST;
    } else if (st->I_rem > FSW_R(0.0) && st->I_rem >= I_min) {
      pulse_start(st, cfg);
      pulse_command(st, cfg, in->t_ns, out->L_thr_B);
      out_phase = FSW_THR_MOM_PULSE;
    } else {
      st->phase = FSW_THR_MOM_IDLE; /* dump complete */
      st->dumps = inc_sat(st->dumps);
    }
  }
  if (out_phase != FSW_THR_MOM_IDLE || st->phase_out != FSW_THR_MOM_IDLE) {
    st->t_dump = ns_to_s(st->t_start_ns, in->t_ns); } /* active, or ended in this call */
  if (st->phase == FSW_THR_MOM_IDLE) { st->I_rem = FSW_R(0.0); }
  st->phase_out = out_phase;
  fsw_clock_commit(&st->clock, in->t_ns);

  report(out, st);
  fsw_v3_copy(out->h_w_B, h);
  out->h_norm = hn;
  return fsw_health_record(&st->health, s);
}

fsw_real fsw_thr_momentum_dump_interval(fsw_real h_upper, fsw_real h_lower, fsw_real L_dist)
{
  fsw_real T;
  if (!isfinite(h_upper) || !isfinite(h_lower) || !isfinite(L_dist)) { return FSW_R(0.0); }
  if (!(h_lower >= FSW_R(0.0)) || !(h_upper > h_lower) || L_dist == FSW_R(0.0)) { return FSW_R(0.0); }
  T = (h_upper - h_lower) / FSW_FABS(L_dist);
  return isfinite(T) ? T : FSW_R(0.0);
}

fsw_real fsw_thr_momentum_prop_per_dump(fsw_real dH, fsw_real lever_arm, fsw_real Isp)
{
  fsw_real m;
  if (!isfinite(dH) || !isfinite(lever_arm) || !isfinite(Isp)) { return FSW_R(0.0); }
  if (!(lever_arm > FSW_R(0.0)) || !(Isp > FSW_R(0.0))) { return FSW_R(0.0); }
  m = FSW_FABS(dH) / lever_arm / (Isp * FSW_THR_MOM_G0);
  return isfinite(m) ? m : FSW_R(0.0);
}

/* bdot: B-dot detumbling with magnetorquers (docs/fsw/bdot.md). */
#include "fsw/bdot.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

static int bdot_in_range(fsw_real x, fsw_real lo, fsw_real hi)
{
  return isfinite(x) && x >= lo && x <= hi;
}

FswStatus fsw_bdot_check(const FswBdotConfig *cfg)
{
  int i;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (cfg->variant != FSW_BDOT_DERIV && cfg->variant != FSW_BDOT_GYRO) { return FSW_E_CONFIG; }
  if (cfg->normalize != 0 && cfg->normalize != 1) { return FSW_E_CONFIG; }
  if (!bdot_in_range(cfg->k_bdot, FSW_R(0.0), FSW_BDOT_K_MAX) || !(cfg->k_bdot > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (!bdot_in_range(cfg->tau_f, FSW_R(0.0), FSW_BDOT_TAU_MAX)) { return FSW_E_CONFIG; }
  if (cfg->max_missed < 0 || cfg->max_missed > FSW_BDOT_MISSED_MAX) { return FSW_E_CONFIG; }
  for (i = 0; i < 3; i++) {
    if (!bdot_in_range(cfg->m_max_B[i], FSW_BDOT_M_MIN, FSW_BDOT_M_MAX)) { return FSW_E_CONFIG; } }
  if (!bdot_in_range(cfg->omega_done, FSW_R(0.0), FSW_BDOT_OMEGA_MAX) || !(cfg->omega_done > FSW_R(0.0))) {
    return FSW_E_CONFIG; }
  if (!bdot_in_range(cfg->omega_reenter, FSW_R(0.0), FSW_BDOT_OMEGA_MAX) ||
      !(cfg->omega_reenter > cfg->omega_done)) {
    return FSW_E_CONFIG; }
  if (!bdot_in_range(cfg->t_persist, FSW_R(0.0), FSW_BDOT_T_PERSIST_MAX)) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_bdot_init(FswBdotState *st, const FswBdotConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  fsw_bdot_reset(st); /* a rejected init leaves a cleared memory too */
  s = fsw_bdot_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  return FSW_OK;
}

void fsw_bdot_reset(FswBdotState *st)
{
  FswBdotMemory *m;
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  m = &st->mem;
  fsw_clock_reset(&m->clock);
  m->primed = 0;
  m->t_B_ns = 0u;
  fsw_v3_zero(m->B_prev);
  m->has_bdot = 0;
  fsw_v3_zero(m->Bdot_f);
  fsw_v3_zero(m->m_hold);
  m->scale_hold = FSW_R(0.0);
  m->missed = 0;
  m->below = 0;
  m->t_below = FSW_R(0.0);
  m->detumbled = 0u;
}

static void bdot_safe_output(FswBdotOut *out)
{
  fsw_v3_zero(out->m_B);
  fsw_v3_zero(out->Bdot_B);
  out->rate_est = FSW_R(0.0);
  out->rate_valid = 0u;
  out->detumbled = 0u;
  out->t_below = FSW_R(0.0);
  out->scale = FSW_R(0.0);
  out->held = 0u;
}

/* 1 if v is finite with every |v_i| <= lim. */
static int bdot_v3_within(const fsw_real v[3], fsw_real lim)
{
  int i;
  for (i = 0; i < 3; i++) {
    if (!isfinite(v[i]) || FSW_FABS(v[i]) > lim) { return 0; } }
  return 1;
}

/* m = -g Bdot, scaled by one factor so that |m_i| <= m_max_i; returns the
 * factor in (0, 1].  The scaled dipole is formed from the binding axis j
 * (the smallest m_max_i / |m_i|): m_i = (m_i / |m_j|) m_max_j, whose ratios
 * are at most m_max_i / m_max_j, so the direction is kept to rounding even
 * when the factor itself is tiny. */
static fsw_real bdot_dipole(fsw_real m[3], const FswBdotConfig *cfg, const fsw_real Bdot[3], fsw_real B2)
{
  const fsw_real g = cfg->normalize ? cfg->k_bdot / B2 : cfg->k_bdot;
  fsw_real scale = FSW_R(1.0), a;
  int i, j = -1;
  for (i = 0; i < 3; i++) {
    m[i] = -g * Bdot[i];
    if (FSW_FABS(m[i]) > cfg->m_max_B[i]) {
      const fsw_real s = cfg->m_max_B[i] / FSW_FABS(m[i]);
      if (j < 0 || s < scale) {
        scale = s;
        j = i;
      }
    }
  }
  if (j < 0) { return FSW_R(1.0); }
  a = FSW_FABS(m[j]);
  for (i = 0; i < 3; i++) {
    m[i] = (m[i] / a) * cfg->m_max_B[j];
    /* the product may round one ulp above the limit: clip that ulp */
    if (m[i] > cfg->m_max_B[i]) { m[i] = cfg->m_max_B[i]; }
    if (m[i] < -cfg->m_max_B[i]) { m[i] = -cfg->m_max_B[i]; }
  }
  return scale;
}

/* The detumble test on a cycle dt after the previous accepted one. */
static void bdot_detumble(FswBdotMemory *m, const FswBdotConfig *cfg, int rate_valid, fsw_real rate, fsw_real dt)
{
  if (!rate_valid) { /* no evidence this cycle: persistence restarts, latch kept */
    m->below = 0;
    m->t_below = FSW_R(0.0);
    return;
  }
  if (rate < cfg->omega_done) {
    m->t_below = m->below ? m->t_below + dt : FSW_R(0.0);
    if (m->t_below > FSW_BDOT_T_PERSIST_MAX) { m->t_below = FSW_BDOT_T_PERSIST_MAX; }
    m->below = 1;
    if (m->t_below >= cfg->t_persist) { m->detumbled = 1u; }
  } else {
    m->below = 0;
    m->t_below = FSW_R(0.0);
  }
  if (rate > cfg->omega_reenter) { m->detumbled = 0u; }
}

/* A missed sample: hold the last dipole within max_missed, then rods off. */
static void bdot_missed(FswBdotMemory *m, const FswBdotConfig *cfg, FswBdotOut *o)
{
  if (m->missed < cfg->max_missed) {
    m->missed++;
    fsw_v3_copy(o->m_B, m->m_hold);
    fsw_v3_copy(o->Bdot_B, m->Bdot_f);
    o->scale = m->scale_hold;
    o->held = 1u;
    return;
  }
  if (m->missed <= FSW_BDOT_MISSED_MAX) { m->missed++; }
  m->primed = 0;
  m->has_bdot = 0;
  fsw_v3_zero(m->Bdot_f);
  fsw_v3_zero(m->m_hold);
  m->scale_hold = FSW_R(0.0);
}

FswStatus fsw_bdot_update(FswBdotState *st, const FswBdotConfig *cfg,
                          const FswBdotIn *in, FswBdotOut *out)
{
  FswBdotMemory nx; /* candidate memory, committed on the accepted path */
  FswBdotOut o;
  FswStatus s;
  fsw_real dt, B2 = FSW_R(0.0), rate = FSW_R(0.0);
  int B_ok, w_ok, sample, rate_valid = 0;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { bdot_safe_output(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (in->B_valid > 1u || in->omega_valid > 1u) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  B_ok = in->B_valid == 1u;
  w_ok = in->omega_valid == 1u;
  if (B_ok) {
    if (!bdot_v3_within(in->B_B, FSW_BDOT_B_MAX)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
    B2 = fsw_v3_norm2(in->B_B);
    if (!(B2 >= FSW_BDOT_B_MIN * FSW_BDOT_B_MIN)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  }
  if (w_ok && !bdot_v3_within(in->omega_BN_B, FSW_BDOT_OMEGA_MAX)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  s = fsw_clock_dt(&st->mem.clock, in->t_ns, &dt); /* FSW_OK or FSW_E_TIME */
  if (s != FSW_OK) { return fsw_health_record(&st->health, s); }

  nx = st->mem;
  bdot_safe_output(&o);
  s = FSW_OK;
  sample = cfg->variant == FSW_BDOT_GYRO ? (B_ok && w_ok) : B_ok;
  if (!sample) {
    bdot_missed(&nx, cfg, &o);
    s = FSW_W_RATE;
  } else if (cfg->variant == FSW_BDOT_GYRO) {
    fsw_v3_cross(o.Bdot_B, in->B_B, in->omega_BN_B); /* dB_B/dt = B x omega */
    o.scale = bdot_dipole(o.m_B, cfg, o.Bdot_B, B2);
    nx.missed = 0;
  } else if (!nx.primed) { /* DERIV: the first valid sample only primes */
    nx.primed = 1;
    nx.has_bdot = 0;
    fsw_v3_zero(nx.Bdot_f);
    o.scale = FSW_R(1.0);
    nx.missed = 0;
  } else { /* DERIV: difference against the last valid sample */
    const fsw_real dtB = fsw_clock_ns_to_s(in->t_ns - nx.t_B_ns);
    fsw_real raw[3];
    int k;
    for (k = 0; k < 3; k++) { raw[k] = (in->B_B[k] - nx.B_prev[k]) / dtB; }
    if (nx.has_bdot) {
      const fsw_real beta = dtB / (cfg->tau_f + dtB);
      for (k = 0; k < 3; k++) { nx.Bdot_f[k] += beta * (raw[k] - nx.Bdot_f[k]); }
    } else {
      fsw_v3_copy(nx.Bdot_f, raw);
      nx.has_bdot = 1;
    }
    fsw_v3_copy(o.Bdot_B, nx.Bdot_f);
    o.scale = bdot_dipole(o.m_B, cfg, o.Bdot_B, B2);
    nx.missed = 0;
  }
  if (sample) {
    if (cfg->variant == FSW_BDOT_GYRO) { fsw_v3_copy(nx.Bdot_f, o.Bdot_B); }
    if (B_ok) {
      fsw_v3_copy(nx.B_prev, in->B_B);
      nx.t_B_ns = in->t_ns;
    }
    fsw_v3_copy(nx.m_hold, o.m_B);
    nx.scale_hold = o.scale;
    if (o.scale < FSW_R(1.0)) { s = FSW_W_SAT; }
  }
  /* rate estimate: the gyro when valid, else (DERIV) |Bdot_f| / |B| */
  if (w_ok) {
    rate = fsw_v3_norm(in->omega_BN_B);
    rate_valid = 1;
  } else if (cfg->variant == FSW_BDOT_DERIV && B_ok && nx.has_bdot) {
    rate = fsw_v3_norm(nx.Bdot_f) / FSW_SQRT(B2);
    rate_valid = 1;
  }
  /* in-range inputs cannot overflow (header ranges); kept as the contract's guard */
  if (!fsw_v3_is_finite(o.m_B) || !fsw_v3_is_finite(o.Bdot_B) || !isfinite(rate)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  bdot_detumble(&nx, cfg, rate_valid, rate, dt);
  fsw_clock_commit(&nx.clock, in->t_ns);

  o.rate_est = rate_valid ? rate : FSW_R(0.0);
  o.rate_valid = (uint8_t)rate_valid;
  o.detumbled = nx.detumbled;
  o.t_below = nx.t_below;
  st->mem = nx;
  *out = o;
  return fsw_health_record(&st->health, s);
}

fsw_real fsw_bdot_gain(fsw_real n_orbit, fsw_real J_min, fsw_real incl_mag)
{
  if (!isfinite(n_orbit) || !isfinite(J_min) || !isfinite(incl_mag)) { return FSW_R(0.0); }
  if (!(n_orbit > FSW_R(0.0)) || !(J_min > FSW_R(0.0))) { return FSW_R(0.0); }
  return FSW_R(2.0) * n_orbit * (FSW_R(1.0) + FSW_SIN(incl_mag)) * J_min;
}

fsw_real fsw_bdot_decay_time(fsw_real k, fsw_real J, fsw_real B_rms, int normalize)
{
  fsw_real k_eff;
  if (normalize != 0 && normalize != 1) { return FSW_R(0.0); }
  if (!isfinite(k) || !isfinite(J) || !(k > FSW_R(0.0)) || !(J > FSW_R(0.0))) { return FSW_R(0.0); }
  if (normalize) {
    k_eff = k;
  } else {
    if (!isfinite(B_rms) || !(B_rms > FSW_R(0.0))) { return FSW_R(0.0); }
    k_eff = k * B_rms * B_rms;
  }
  if (!(k_eff > FSW_R(0.0)) || !isfinite(k_eff)) { return FSW_R(0.0); }
  return FSW_R(1.5) * J / k_eff;
}

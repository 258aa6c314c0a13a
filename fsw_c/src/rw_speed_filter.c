/* rw_speed_filter: tachometer outlier rejection with hold, fail and recover. */
#include "fsw/rw_speed_filter.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_vec.h"
#include "fsw/rw_common.h"

FswStatus fsw_rw_speed_filter_check(const FswRwSpeedFilterConfig *cfg)
{
  int n, i;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  n = cfg->num_rw;
  if (n < 1 || n > FSW_MAX_RW || n > 64) { return FSW_E_CAPACITY; }
  if (!fsw_rw_all_positive(cfg->u_max, n) || !fsw_rw_all_positive(cfg->J_s, n)) { return FSW_E_CONFIG; }
  for (i = 0; i < n; i++) {
    if (!isfinite(cfg->noise[i]) || cfg->noise[i] < FSW_R(0.0)) { return FSW_E_CONFIG; } }
  if (cfg->k_reject < 1u || cfg->n_recover < 1u) { return FSW_E_CONFIG; }
  if (cfg->n_window > 0u) {
    for (i = 0; i < n; i++) {
      if (!isfinite(cfg->resid_tol[i]) || cfg->resid_tol[i] < FSW_R(0.0)) { return FSW_E_CONFIG; } } }
  return FSW_OK;
}

FswStatus fsw_rw_speed_filter_init(FswRwSpeedFilterState *st, const FswRwSpeedFilterConfig *cfg)
{
  FswStatus s;
  int i;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  for (i = 0; i < FSW_MAX_RW; i++) { st->rejections[i] = 0u; }
  s = fsw_rw_speed_filter_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_rw_speed_filter_reset(st);
  return FSW_OK;
}

void fsw_rw_speed_filter_reset(FswRwSpeedFilterState *st)
{
  int i;
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  for (i = 0; i < FSW_MAX_RW; i++) {
    st->Omega_good[i] = FSW_R(0.0);
    st->t_good_ns[i] = 0u;
    st->Omega_cand[i] = FSW_R(0.0);
    st->t_cand_ns[i] = 0u;
    st->reject_run[i] = 0u;
    st->recover_run[i] = 0u;
    st->has_good[i] = 0u;
    st->failed[i] = 0u;
    st->latched[i] = 0u;
    st->last_raw[i] = FSW_R(0.0);
    st->has_raw[i] = 0u;
    st->stale_run[i] = 0u;
    st->win_open[i] = 0u;
    st->win_Omega0[i] = FSW_R(0.0);
    st->win_exp[i] = FSW_R(0.0);
    st->win_count[i] = 0u;
  }
  fsw_clock_reset(&st->clock);
}

/* |x - ref| within what the motor torque allows since t_ref, plus noise. */
static int consistent(const FswRwSpeedFilterConfig *cfg, int i, fsw_real x, fsw_real ref,
                      uint64_t t_ns, uint64_t t_ref_ns)
{
  const fsw_real dt = fsw_clock_ns_to_s(t_ns - t_ref_ns);
  return FSW_FABS(x - ref) <= cfg->u_max[i] / cfg->J_s[i] * dt + cfg->noise[i];
}

static void safe_output(const FswRwSpeedFilterState *st, int n, FswRwSpeedFilterOut *out, int held)
{
  int i;
  fsw_rw_zero(out->Omega);
  for (i = 0; i < FSW_MAX_RW; i++) { out->avail[i] = (i < n) ? (uint8_t)FSW_UNAVAILABLE : (uint8_t)0u; }
  if (held) {
    for (i = 0; i < n; i++) { out->Omega[i] = st->has_good[i] ? st->Omega_good[i] : FSW_R(0.0); } }
  out->rejected = 0u;
  out->failed = 0u;
  out->latched = 0u;
}

/* The applied torques are read only by the torque test, and only when valid. */
static int torques_valid(const FswRwSpeedFilterConfig *cfg, const FswRwSpeedFilterIn *in, int n)
{
  int i;
  if (in->u_valid > 1u) { return 0; }
  if (cfg->n_window == 0u || in->u_valid == 0u) { return 1; }
  for (i = 0; i < n; i++) {
    if (!(FSW_FABS(in->u_applied[i]) <= FSW_R(2.0) * cfg->u_max[i])) { return 0; } } /* NaN fails too */
  return 1;
}

/* Stale test: a finite sample equal to the previous finite one bit for bit
 * extends the run; returns 1 when the run reaches n_stale.  Bit for bit,
 * not ==: a zero reading that flips its sign (-0.0 then +0.0) moved, and a
 * frozen tachometer repeats its bits (issue 39). */
static int stale(FswRwSpeedFilterState *st, const FswRwSpeedFilterConfig *cfg, int i, fsw_real x)
{
  if (!isfinite(x)) { return 0; } /* the outlier gate handles it; the run is kept */
  if (st->has_raw[i] && memcmp(&x, &st->last_raw[i], sizeof x) == 0) {
    if (st->stale_run[i] < cfg->n_stale) { st->stale_run[i]++; } /* counted up to the limit only */
  } else {
    st->stale_run[i] = 0u;
  }
  st->last_raw[i] = x;
  st->has_raw[i] = 1u;
  return cfg->n_stale > 0u && st->stale_run[i] >= cfg->n_stale;
}

/* Torque test, after the accept/reject step of this call.  `open_before`:
 * the window was running before this call (its interval then belongs to
 * it).  Returns 1 when a closing window's residual exceeds resid_tol. */
static int torque_inconsistent(FswRwSpeedFilterState *st, const FswRwSpeedFilterConfig *cfg,
                               const FswRwSpeedFilterIn *in, int i, int accepted, fsw_real dt)
{
  if (cfg->n_window == 0u) { return 0; }
  if (st->failed[i] || in->u_valid == 0u) { st->win_open[i] = 0u; } /* torque or speed unknown */
  if (st->win_open[i]) {
    st->win_exp[i] += in->u_applied[i] / cfg->J_s[i] * dt;
    if (st->win_count[i] < cfg->n_window) { st->win_count[i]++; } /* waits there for an accepted sample */
  }
  if (!accepted) { return 0; } /* the window waits for an accepted sample */
  if (st->win_open[i] && st->win_count[i] >= cfg->n_window) {
    const fsw_real r = (st->Omega_good[i] - st->win_Omega0[i]) - st->win_exp[i];
    if (!(FSW_FABS(r) <= cfg->resid_tol[i])) { return 1; }
    st->win_open[i] = 0u; /* closed clean: the next one opens here */
  }
  if (!st->win_open[i]) { /* (a failed wheel never gets here: it has no accepted sample) */
    st->win_open[i] = 1u;
    st->win_Omega0[i] = st->Omega_good[i];
    st->win_exp[i] = FSW_R(0.0);
    st->win_count[i] = 0u;
  }
  return 0;
}

FswStatus fsw_rw_speed_filter_update(FswRwSpeedFilterState *st, const FswRwSpeedFilterConfig *cfg,
                                     const FswRwSpeedFilterIn *in, FswRwSpeedFilterOut *out)
{
  int n, i;
  fsw_real dt = FSW_R(0.0);
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    if (out != NULL) { safe_output(st, FSW_MAX_RW, out, 0); }
    return FSW_E_NULL_ARG;
  }
  n = (cfg->num_rw < 0) ? 0 : (cfg->num_rw > FSW_MAX_RW ? FSW_MAX_RW : cfg->num_rw);
  safe_output(st, n, out, st->ready);
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (!fsw_rw_avail_valid(in->avail, n) || !torques_valid(cfg, in, n)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  {
    /* dt: the torque window's interval (0 on the first call); the outlier
     * gate measures from each wheel's own sample */
    const FswStatus s = fsw_clock_dt(&st->clock, in->t_ns, &dt); /* FSW_OK or FSW_E_TIME */
    if (s != FSW_OK) { return fsw_health_record(&st->health, s); }
  }

  for (i = 0; i < n; i++) {
    const fsw_real x = in->Omega_meas[i];
    /* beyond +-FSW_RW_OMEGA_MAX a finite sample is no speed: an outlier like NaN */
    const int plausible = FSW_FABS(x) <= FSW_RW_OMEGA_MAX;
    const uint64_t bit = (uint64_t)1u << i;
    int accepted = 0;
    if (st->latched[i]) {
      /* held until reset: no test, no recovery */
    } else if (!st->failed[i]) {
      if (plausible && (!st->has_good[i] ||
                     consistent(cfg, i, x, st->Omega_good[i], in->t_ns, st->t_good_ns[i]))) {
        st->Omega_good[i] = x;
        st->t_good_ns[i] = in->t_ns;
        st->has_good[i] = 1u;
        st->reject_run[i] = 0u;
        accepted = 1;
      } else {
        out->rejected |= bit;
        if (st->rejections[i] < UINT32_MAX) { st->rejections[i]++; }
        st->reject_run[i]++;
        if (st->reject_run[i] >= cfg->k_reject) {
          st->failed[i] = 1u;
          st->recover_run[i] = 0u;
        }
      }
    } else if (!plausible) {
      st->recover_run[i] = 0u;
    } else {
      if (st->recover_run[i] > 0u &&
          consistent(cfg, i, x, st->Omega_cand[i], in->t_ns, st->t_cand_ns[i]))
        st->recover_run[i]++;
      else {
        st->recover_run[i] = 1u; }
      st->Omega_cand[i] = x;
      st->t_cand_ns[i] = in->t_ns;
      if (st->recover_run[i] >= cfg->n_recover) {
        st->failed[i] = 0u;
        st->reject_run[i] = 0u;
        st->recover_run[i] = 0u;
        st->Omega_good[i] = x;
        st->t_good_ns[i] = in->t_ns;
        st->has_good[i] = 1u;
      }
    }
    if (!st->latched[i] &&
        (stale(st, cfg, i, x) || torque_inconsistent(st, cfg, in, i, accepted, dt))) {
      st->latched[i] = 1u;
      st->failed[i] = 1u;
      st->win_open[i] = 0u;
    }
    out->Omega[i] = st->Omega_good[i];
    if (st->failed[i]) { out->failed |= bit; }
    if (st->latched[i]) { out->latched |= bit; }
    out->avail[i] = (st->failed[i] || in->avail[i] != FSW_AVAILABLE) ? (uint8_t)FSW_UNAVAILABLE
                                                                     : (uint8_t)FSW_AVAILABLE;
  }
  fsw_clock_commit(&st->clock, in->t_ns);
  return fsw_health_record(&st->health, FSW_OK);
}

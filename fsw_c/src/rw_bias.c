/* rw_bias: wheel-speed bias with zero-crossing avoidance (the desired speeds
 * of rw_null).  Equations and method: rw_bias.h and docs/fsw/rw_bias.md. */
#include "fsw/rw_bias.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

/* Per-update working set: the facts about each wheel that every solver
 * needs, computed once from the input and the new hysteresis state.  The
 * arrays live in the state's scratch (FswRwBiasScratch), off the stack. */
typedef struct {
  int n;                         /* [-]     num_rw                              */
  const fsw_real *Om;            /* [rad/s] measured speeds                     */
  fsw_real keepout;              /* [rad/s] Omega_keepout (scale of the stop rule) */
  const uint8_t *avail;          /* [-]     mask                                */
  fsw_real *lo;                  /* [rad/s] (n) keep-out interval of the step   */
  fsw_real *hi;                  /*         delta_i = Omega_des_i - Omega_i     */
  fsw_real *b;                   /* [rad/s] (n) band edge each wheel must clear */
  signed char *s;                /* [-]     (n) side of each wheel, +-1         */
} BiasWork;

/* Omega_i if it is a speed rw_null accepts, else 0 (the safe value). */
static fsw_real held_speed(fsw_real om)
{
  return (FSW_FABS(om) <= FSW_RW_OMEGA_MAX) ? om : FSW_R(0.0);
}

static void write_safe(FswRwBiasOut *out, const FswRwBiasConfig *cfg, const FswRwBiasIn *in)
{
  int i, n = 0;
  fsw_rw_zero(out->Omega_des);
  for (i = 0; i < FSW_MAX_RW; i++) {
    out->in_band[i] = 0;
    out->unavoidable[i] = 0;
  }
  out->crossing_unavoidable = 0;
  out->nullity = 0;
  out->lambda_norm = FSW_R(0.0);
  if (cfg != NULL && in != NULL && cfg->num_rw > 0 && cfg->num_rw <= FSW_MAX_RW) { n = cfg->num_rw; }
  for (i = 0; i < n; i++) { out->Omega_des[i] = held_speed(in->Omega[i]); }
}

/* Orthonormal basis of null([Gs_a]) from the projector: pivoted Gram-Schmidt
 * over the columns of tau (each step takes the column with the largest
 * residual, lowest index on ties; its residual is orthogonalised twice and
 * normalised).  Rows beyond the nullity are 0. */
static void basis_compute(FswRwBiasState *st)
{
  const FswRwNullProj *p = &st->proj;
  const int n = p->num_rw;
  int k = p->num_avail - p->rank, j, m, c, pass;
  fsw_real r[FSW_MAX_RW];
  for (j = 0; j < FSW_MAX_RW; j++) { fsw_vn_zero(st->basis[j], FSW_MAX_RW); }
  if (k < 0) { k = 0; }
  st->nullity = 0;
  for (j = 0; j < k; j++) {
    int best = -1;
    fsw_real best_n2 = FSW_R(0.0), nr;
    for (c = 0; c < n; c++) {
      fsw_real n2 = p->tau[c][c]; /* |tau_c|^2 = tau_cc for a projector */
      if (p->avail[c] != FSW_AVAILABLE) { continue; }
      for (m = 0; m < j; m++) { n2 -= st->basis[m][c] * st->basis[m][c]; } /* b_m . tau_c = b_mc */
      if (n2 > best_n2) {
        best_n2 = n2;
        best = c;
      }
    }
    if (best < 0 || !(best_n2 > FSW_NULL_TOL)) { break; }
    for (c = 0; c < n; c++) { r[c] = p->tau[c][best]; } /* tau is symmetric */
    for (pass = 0; pass < 2; pass++) {
      for (m = 0; m < j; m++) {
        const fsw_real d = fsw_vn_dot(st->basis[m], r, n);
        for (c = 0; c < n; c++) { r[c] -= d * st->basis[m][c]; }
      } }
    nr = fsw_vn_norm(r, n);
    if (!(nr > FSW_R(0.0))) { break; }
    for (c = 0; c < n; c++) { st->basis[j][c] = r[c] / nr; }
    st->nullity = j + 1;
  }
}

FswStatus fsw_rw_bias_check(const FswRwBiasConfig *cfg)
{
  FswStatus s;
  int i;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  s = fsw_rw_check_axes(cfg->gs_hat_B, cfg->num_rw, 1);
  if (s != FSW_OK) { return s; }
  if (!isfinite(cfg->Omega_keepout) || !(cfg->Omega_keepout > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->Omega_hyst) || !(cfg->Omega_hyst >= FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (!(cfg->Omega_keepout + cfg->Omega_hyst <= FSW_R(0.5) * FSW_RW_OMEGA_MAX)) { return FSW_E_CONFIG; }
  for (i = 0; i < cfg->num_rw; i++) {
    const fsw_real a = FSW_FABS(cfg->Omega_bias[i]);
    if (!isfinite(a) || !(a > cfg->Omega_keepout) || a > FSW_RW_OMEGA_MAX) { return FSW_E_CONFIG; }
  }
  return FSW_OK;
}

FswStatus fsw_rw_bias_init(FswRwBiasState *st, const FswRwBiasConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_rw_bias_check(cfg);
  if (s != FSW_OK) { return s; }
  fsw_rw_proj_init(&st->proj, cfg->gs_hat_B, cfg->num_rw);
  basis_compute(st);
  st->ready = 1;
  fsw_rw_bias_reset(st);
  return FSW_OK;
}

void fsw_rw_bias_reset(FswRwBiasState *st)
{
  int i;
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  for (i = 0; i < FSW_MAX_RW; i++) { st->in_band[i] = 0; }
}

/* Number of available wheels whose step delta_i leaves them in their band. */
static int count_in_band(const BiasWork *w, const fsw_real *delta)
{
  int i, c = 0;
  for (i = 0; i < w->n; i++) {
    if (w->avail[i] == FSW_AVAILABLE && (fsw_real)w->s[i] * (w->Om[i] + delta[i]) < (FSW_R(1.0) - FSW_RW_BIAS_TOL) * w->b[i]) { c++; } }
  return c;
}

/* delta = sum_j lambda_j basis_j, then scaled by the largest alpha in [0, 1]
 * that keeps |Omega_i + alpha delta_i| <= FSW_RW_OMEGA_MAX (Omega itself is
 * within: alpha = 0 always fits). */
static void step_of(fsw_real *delta, const FswRwBiasState *st, const BiasWork *w, const fsw_real *lambda)
{
  int i, j;
  fsw_real alpha = FSW_R(1.0);
  fsw_vn_zero(delta, FSW_MAX_RW);
  for (j = 0; j < st->nullity; j++) {
    for (i = 0; i < w->n; i++) { delta[i] += lambda[j] * st->basis[j][i]; } }
  for (i = 0; i < w->n; i++) {
    fsw_real a = alpha;
    if (w->avail[i] != FSW_AVAILABLE) { continue; }
    if (delta[i] > FSW_R(0.0) && w->Om[i] + delta[i] > FSW_RW_OMEGA_MAX) {
      a = (FSW_RW_OMEGA_MAX - w->Om[i]) / delta[i];
    } else if (delta[i] < FSW_R(0.0) && w->Om[i] + delta[i] < -FSW_RW_OMEGA_MAX) {
      a = (-FSW_RW_OMEGA_MAX - w->Om[i]) / delta[i]; }
    if (a < alpha) { alpha = a; }
  }
  if (alpha < FSW_R(1.0)) { fsw_vn_scale(delta, alpha > FSW_R(0.0) ? alpha : FSW_R(0.0), delta, w->n); }
}

/* k = 1: every constraint is an interval of lambda. */
static void solve_k1(fsw_real *lambda, const FswRwBiasState *st, const BiasWork *w, fsw_real lam_u)
{
  const fsw_real *nv = st->basis[0];
  fsw_real Hlo = -FSW_RW_OMEGA_MAX * FSW_R(1e3), Hhi = FSW_RW_OMEGA_MAX * FSW_R(1e3); /* |lambda| <= |delta|: any bound above 2 OMEGA_MAX is inert */
  fsw_real Flo, Fhi, best = FSW_R(0.0), best_d = FSW_R(0.0);
  int i, e, best_c = -1;
  /* hard speed bounds (contain lambda = 0) */
  for (i = 0; i < w->n; i++) {
    fsw_real a, c;
    if (w->avail[i] != FSW_AVAILABLE || FSW_FABS(nv[i]) <= FSW_NULL_TOL) { continue; }
    a = (-FSW_RW_OMEGA_MAX - w->Om[i]) / nv[i];
    c = (FSW_RW_OMEGA_MAX - w->Om[i]) / nv[i];
    if (nv[i] < FSW_R(0.0)) {
      const fsw_real t = a;
      a = c;
      c = t;
    }
    if (a > Hlo) { Hlo = a; }
    if (c < Hhi) { Hhi = c; }
  }
  if (Hlo > FSW_R(0.0)) { Hlo = FSW_R(0.0); } /* rounding: 0 is admissible */
  if (Hhi < FSW_R(0.0)) { Hhi = FSW_R(0.0); }
  /* keep-out intervals */
  Flo = Hlo;
  Fhi = Hhi;
  for (i = 0; i < w->n; i++) {
    fsw_real a, c;
    if (w->avail[i] != FSW_AVAILABLE) { continue; }
    if (FSW_FABS(nv[i]) <= FSW_NULL_TOL) {
      if (w->lo[i] > FSW_R(0.0) || w->hi[i] < FSW_R(0.0)) { Fhi = Flo - FSW_R(1.0); } /* fixed in its band */
      continue;
    }
    a = w->lo[i] / nv[i];
    c = w->hi[i] / nv[i];
    if (nv[i] < FSW_R(0.0)) {
      const fsw_real t = a;
      a = c;
      c = t;
    }
    if (a > Flo) { Flo = a; }
    if (c < Fhi) { Fhi = c; }
  }
  if (Flo <= Fhi) {
    lambda[0] = lam_u < Flo ? Flo : (lam_u > Fhi ? Fhi : lam_u);
    return;
  }
  /* infeasible: among clamp(lam_u, H) and every interval end inside H, the
   * lambda with the fewest wheels in their band, then the closest to lam_u */
  for (e = -1; e < 2 * w->n; e++) {
    fsw_real cand, d, delta[FSW_MAX_RW];
    int cnt;
    if (e < 0) {
      cand = lam_u;
    } else {
      i = e / 2;
      if (w->avail[i] != FSW_AVAILABLE || FSW_FABS(nv[i]) <= FSW_NULL_TOL) { continue; }
      cand = ((e % 2) ? w->hi[i] : w->lo[i]) / nv[i];
    }
    cand = cand < Hlo ? Hlo : (cand > Hhi ? Hhi : cand);
    lambda[0] = cand;
    step_of(delta, st, w, lambda);
    cnt = count_in_band(w, delta);
    d = FSW_FABS(cand - lam_u);
    if (best_c < 0 || cnt < best_c || (cnt == best_c && d < best_d)) {
      best_c = cnt;
      best = cand;
      best_d = d;
    }
  }
  lambda[0] = best;
}

/* k > 1: Hildreth's dual coordinate ascent for the projection of lam_u onto
 * {lambda : lo_i <= a_i . lambda <= hi_i}, a_i = row i of N. */
static void solve_hildreth(fsw_real *x, const FswRwBiasState *st, const BiasWork *w, const fsw_real *lam_u)
{
  fsw_real mu[FSW_MAX_RW];
  const int k = st->nullity;
  const fsw_real stop = FSW_RW_BIAS_TOL * FSW_R(1e-3) * w->keepout;
  int sweep, i, j;
  fsw_vn_zero(mu, FSW_MAX_RW);
  fsw_vn_copy(x, lam_u, k);
  for (sweep = 0; sweep < FSW_RW_BIAS_MAX_SWEEPS; sweep++) {
    fsw_real moved = FSW_R(0.0);
    for (i = 0; i < w->n; i++) {
      fsw_real aa = FSW_R(0.0), t = FSW_R(0.0), m_new = FSW_R(0.0), dm;
      if (w->avail[i] != FSW_AVAILABLE) { continue; }
      for (j = 0; j < k; j++) {
        aa += st->basis[j][i] * st->basis[j][i];
        t += st->basis[j][i] * x[j];
      }
      if (!(aa > FSW_NULL_TOL)) { continue; }
      t -= mu[i] * aa; /* a_i . lambda without this constraint's own multiplier */
      if (t < w->lo[i]) {
        m_new = (w->lo[i] - t) / aa;
      } else if (t > w->hi[i]) {
        m_new = (w->hi[i] - t) / aa; }
      dm = m_new - mu[i];
      if (dm != FSW_R(0.0)) {
        for (j = 0; j < k; j++) { x[j] += dm * st->basis[j][i]; }
        mu[i] = m_new;
        if (FSW_FABS(dm) * FSW_SQRT(aa) > moved) { moved = FSW_FABS(dm) * FSW_SQRT(aa); }
      }
    }
    if (moved <= stop) { break; }
  }
}

FswStatus fsw_rw_bias_update(FswRwBiasState *st, const FswRwBiasConfig *cfg, const FswRwBiasIn *in,
                             FswRwBiasOut *out)
{
  BiasWork w;
  fsw_real *lam_u, *lambda, *delta;
  uint8_t band[FSW_MAX_RW];
  int n, i, j, any = 0;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { write_safe(out, cfg, in); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    return fsw_health_record(st != NULL ? &st->health : NULL, FSW_E_NULL_ARG); }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_rw;
  if (!fsw_rw_avail_valid(in->avail, n) || !fsw_rw_avail_speed_ok(in->Omega, in->avail, n)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }

  /* hysteresis state and the constraints of this call */
  lam_u = st->scratch.lam_u;
  lambda = st->scratch.lambda;
  delta = st->scratch.delta;
  w.lo = st->scratch.lo;
  w.hi = st->scratch.hi;
  w.b = st->scratch.b;
  w.s = st->scratch.s;
  w.n = n;
  w.Om = in->Omega;
  w.avail = in->avail;
  w.keepout = cfg->Omega_keepout;
  for (i = 0; i < n; i++) {
    const fsw_real om = in->Omega[i], a = FSW_FABS(om);
    band[i] = 0;
    w.lo[i] = w.hi[i] = FSW_R(0.0);
    w.b[i] = cfg->Omega_keepout;
    w.s[i] = 1;
    if (in->avail[i] != FSW_AVAILABLE) { continue; }
    if (a < cfg->Omega_keepout) {
      band[i] = 1;
    } else if (a > cfg->Omega_keepout + cfg->Omega_hyst) {
      band[i] = 0;
    } else {
      band[i] = st->in_band[i]; }
    if (band[i]) { w.b[i] = cfg->Omega_keepout + cfg->Omega_hyst; }
    w.s[i] = (signed char)((om > FSW_R(0.0) || (om == FSW_R(0.0) && cfg->Omega_bias[i] > FSW_R(0.0))) ? 1 : -1);
    if (w.s[i] > 0) {
      w.lo[i] = w.b[i] - om;
      w.hi[i] = FSW_RW_OMEGA_MAX - om;
    } else {
      w.lo[i] = -FSW_RW_OMEGA_MAX - om;
      w.hi[i] = -w.b[i] - om;
    }
  }

  if (fsw_rw_proj_refresh(&st->proj, in->avail)) { basis_compute(st); }

  /* unconstrained optimum in the null space */
  fsw_vn_zero(lam_u, FSW_MAX_RW);
  fsw_vn_zero(lambda, FSW_MAX_RW);
  for (j = 0; j < st->nullity; j++) {
    fsw_real sum = FSW_R(0.0);
    for (i = 0; i < n; i++) {
      if (in->avail[i] == FSW_AVAILABLE) { sum += st->basis[j][i] * (cfg->Omega_bias[i] - in->Omega[i]); } }
    lam_u[j] = sum;
  }
  if (st->nullity == 1) {
    solve_k1(lambda, st, &w, lam_u[0]);
    step_of(delta, st, &w, lambda);
  } else if (st->nullity > 1) {
    int c1, c2;
    solve_hildreth(lambda, st, &w, lam_u);
    step_of(delta, st, &w, lambda);
    c1 = count_in_band(&w, delta);
    if (c1 > 0) { /* not kept out: the unconstrained choice may leave fewer in the band */
      step_of(lambda, st, &w, lam_u); /* lambda is free now: holds that step */
      c2 = count_in_band(&w, lambda);
      if (c2 < c1) { fsw_vn_copy(delta, lambda, FSW_MAX_RW); }
    }
  } else {
    fsw_vn_zero(delta, FSW_MAX_RW);
  }

  for (i = 0; i < n; i++) {
    fsw_real v;
    if (in->avail[i] != FSW_AVAILABLE) {
      delta[i] = FSW_R(0.0);
      continue; /* Omega_des_i keeps its held value */
    }
    v = in->Omega[i] + delta[i];
    if (v > FSW_RW_OMEGA_MAX) { v = FSW_RW_OMEGA_MAX; } /* last rounding of the alpha step */
    if (v < -FSW_RW_OMEGA_MAX) { v = -FSW_RW_OMEGA_MAX; }
    out->Omega_des[i] = v;
    out->in_band[i] = band[i];
    if ((fsw_real)w.s[i] * v < (FSW_R(1.0) - FSW_RW_BIAS_TOL) * w.b[i]) {
      out->unavoidable[i] = 1;
      any = 1;
    }
  }
  for (i = 0; i < FSW_MAX_RW; i++) { st->in_band[i] = (i < n) ? band[i] : (uint8_t)0; }
  out->crossing_unavoidable = (uint8_t)any;
  out->nullity = st->nullity;
  out->lambda_norm = fsw_vn_norm(delta, n);
  return fsw_health_record(&st->health, any ? FSW_W_SAT : FSW_OK);
}

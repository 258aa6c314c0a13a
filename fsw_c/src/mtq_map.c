/* mtq_map: torque or dipole request -> magnetorquer rod commands. */
#include "fsw/mtq_map.h"

#include <stddef.h>

#include "fsw/fsw_vec.h"

/* Jacobi sweeps: a 3x3 converges (quadratically) in 4 to 6; the cap only
 * bounds the run time. */
#define MTQ_JACOBI_SWEEPS 12

FswStatus fsw_mtq_field(fsw_real b_hat[3], fsw_real *B_norm, const fsw_real B[3], uint8_t valid)
{
  fsw_real n;
  fsw_v3_zero(b_hat);
  *B_norm = FSW_R(0.0);
  if (valid > 1u) { return FSW_E_BAD_INPUT; }
  if (valid == 0u) { return FSW_W_SINGULAR; }
  if (!fsw_v3_is_finite(B)) { return FSW_E_BAD_INPUT; }
  n = fsw_v3_norm(B);
  if (!(n <= FSW_MTQ_B_MAX)) { return FSW_E_BAD_INPUT; }
  if (n < FSW_MTQ_B_MIN) { return FSW_W_SINGULAR; }
  fsw_v3_scale(b_hat, FSW_R(1.0) / n, B);
  *B_norm = n;
  return FSW_OK;
}

FswStatus fsw_mtq_map_check(const FswMtqMapConfig *cfg)
{
  int i;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (cfg->num_mtq < 1 || cfg->num_mtq > FSW_MAX_MTQ) { return FSW_E_CAPACITY; }
  for (i = 0; i < cfg->num_mtq; i++) {
    const fsw_real mm = cfg->m_max[i];
    if (!fsw_v3_is_finite(cfg->gt_hat_B[i])) { return FSW_E_CONFIG; }
    if (FSW_FABS(fsw_v3_norm(cfg->gt_hat_B[i]) - FSW_R(1.0)) > FSW_MTQ_UNIT_TOL) { return FSW_E_CONFIG; }
    if (!(mm >= FSW_MTQ_M_MAX_MIN && mm <= FSW_MTQ_M_MAX_MAX)) { return FSW_E_CONFIG; }
  }
  if (!(cfg->duty_max >= FSW_MTQ_DUTY_MIN && cfg->duty_max <= FSW_R(1.0))) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_mtq_map_init(FswMtqMapState *st, const FswMtqMapConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  st->ready = 0;
  fsw_health_clear(&st->health);
  s = fsw_mtq_map_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_mtq_map_reset(st);
  return FSW_OK;
}

void fsw_mtq_map_reset(FswMtqMapState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* no time-varying state */
}

static void mtq_safe_output(FswMtqMapOut *out)
{
  fsw_vn_zero(out->m_cmd, FSW_MAX_MTQ);
  fsw_vn_zero(out->duty, FSW_MAX_MTQ);
  fsw_v3_zero(out->m_ach_B);
  fsw_v3_zero(out->tau_ach_B);
  fsw_v3_zero(out->tau_par_B);
  out->scale = FSW_R(0.0);
  out->rank = 0;
}

/* Cyclic Jacobi in fixed order on the symmetric 3x3 a: on return a is
 * diagonal to working precision (its diagonal holds the eigenvalues) and
 * the columns of v are the eigenvectors.  An off-diagonal entry below
 * eps/100 of its two diagonal entries is set to 0 (it cannot change them). */
static void mtq_jacobi3(fsw_real a[3][3], fsw_real v[3][3])
{
  static const int P[3] = {0, 0, 1}, Q[3] = {1, 2, 2};
  int sweep, k, r;
  fsw_m33_identity(v);
  for (sweep = 0; sweep < MTQ_JACOBI_SWEEPS; sweep++) {
    int rotated = 0;
    for (k = 0; k < 3; k++) {
      const int p = P[k], q = Q[k];
      const fsw_real apq = a[p][q];
      fsw_real theta, t, c, s;
      if (apq == FSW_R(0.0)) { continue; }
      if (FSW_FABS(apq) <= FSW_REAL_EPS * FSW_R(0.01) * (FSW_FABS(a[p][p]) + FSW_FABS(a[q][q]))) {
        a[p][q] = a[q][p] = FSW_R(0.0);
        continue;
      }
      theta = (a[q][q] - a[p][p]) / (FSW_R(2.0) * apq);
      t = FSW_R(1.0) / (FSW_FABS(theta) + FSW_SQRT(theta * theta + FSW_R(1.0)));
      if (theta < FSW_R(0.0)) { t = -t; }
      c = FSW_R(1.0) / FSW_SQRT(t * t + FSW_R(1.0));
      s = t * c;
      for (r = 0; r < 3; r++) { /* columns p, q of a P */
        const fsw_real arp = a[r][p], arq = a[r][q];
        a[r][p] = c * arp - s * arq;
        a[r][q] = s * arp + c * arq;
      }
      for (r = 0; r < 3; r++) { /* rows p, q of P^T (a P) */
        const fsw_real apr = a[p][r], aqr = a[q][r];
        a[p][r] = c * apr - s * aqr;
        a[q][r] = s * apr + c * aqr;
      }
      a[p][q] = a[q][p] = FSW_R(0.0); /* zero by construction */
      for (r = 0; r < 3; r++) {
        const fsw_real vrp = v[r][p], vrq = v[r][q];
        v[r][p] = c * vrp - s * vrq;
        v[r][q] = s * vrp + c * vrq;
      }
      rotated = 1;
    }
    if (!rotated) { break; }
  }
}

/* The pseudo-inverse of G = [gt_hat of the available rods] (3 x n) as
 * G^+ = G^T (G G^T)^+: the eigenpairs of M = G G^T with eigenvalues above
 * FSW_RANK_TOL x the largest.  M is dimensionless (unit axes), trace =
 * number of available rods. */
typedef struct {
  fsw_real V[3][3];   /* [-] eigenvectors of M (columns) */
  fsw_real inv[3];    /* [-] 1/lambda_k for the kept eigenvalues, else 0 */
  int rank;           /* [-] kept eigenvalues, 0..3 */
} MtqPinv;

static void mtq_pinv_form(MtqPinv *p, const FswMtqMapConfig *cfg, const uint8_t *avail)
{
  fsw_real M[3][3];
  fsw_real lmax = FSW_R(0.0);
  int i, j, k;
  fsw_m33_zero(M);
  for (i = 0; i < cfg->num_mtq; i++) {
    if (avail[i] != FSW_AVAILABLE) { continue; }
    for (j = 0; j < 3; j++) {
      for (k = 0; k < 3; k++) { M[j][k] += cfg->gt_hat_B[i][j] * cfg->gt_hat_B[i][k]; } }
  }
  mtq_jacobi3(M, p->V);
  for (k = 0; k < 3; k++) {
    if (M[k][k] > lmax) { lmax = M[k][k]; } }
  p->rank = 0;
  for (k = 0; k < 3; k++) {
    if (lmax > FSW_R(0.0) && M[k][k] > FSW_RANK_TOL * lmax) {
      p->inv[k] = FSW_R(1.0) / M[k][k];
      p->rank++;
    } else {
      p->inv[k] = FSW_R(0.0);
    }
  }
}

/* c = G^+ m (every FSW_MAX_MTQ entry written; unavailable rods 0). */
static void mtq_pinv_apply(fsw_real c[FSW_MAX_MTQ], const MtqPinv *p, const FswMtqMapConfig *cfg,
                           const uint8_t *avail, const fsw_real m[3])
{
  fsw_real y[3] = {FSW_R(0.0), FSW_R(0.0), FSW_R(0.0)};
  int i, k;
  for (k = 0; k < 3; k++) {
    const fsw_real vk[3] = {p->V[0][k], p->V[1][k], p->V[2][k]};
    fsw_v3_axpy(y, y, p->inv[k] * fsw_v3_dot(vk, m), vk);
  }
  fsw_vn_zero(c, FSW_MAX_MTQ);
  for (i = 0; i < cfg->num_mtq; i++) {
    if (avail[i] == FSW_AVAILABLE) { c[i] = fsw_v3_dot(cfg->gt_hat_B[i], y); } }
}

/* m = G c over the available rods. */
static void mtq_dipole(fsw_real m[3], const FswMtqMapConfig *cfg, const uint8_t *avail,
                       const fsw_real c[FSW_MAX_MTQ])
{
  int i;
  fsw_v3_zero(m);
  for (i = 0; i < cfg->num_mtq; i++) {
    if (avail[i] == FSW_AVAILABLE) { fsw_v3_axpy(m, m, c[i], cfg->gt_hat_B[i]); } }
}

/* 1 when every entry of v is finite and within +-lim. */
static int mtq_v3_within(const fsw_real v[3], fsw_real lim)
{
  int k;
  for (k = 0; k < 3; k++) {
    if (!(FSW_FABS(v[k]) <= lim)) { return 0; } }
  return 1;
}

/* Scale c by the common factor that brings every |c_i| within
 * duty_max m_max_i; returns the factor (1 when none is beyond). */
static fsw_real mtq_saturate(fsw_real c[FSW_MAX_MTQ], const FswMtqMapConfig *cfg)
{
  fsw_real s = FSW_R(1.0);
  int i;
  for (i = 0; i < cfg->num_mtq; i++) {
    const fsw_real lim = cfg->duty_max * cfg->m_max[i];
    if (FSW_FABS(c[i]) > lim) {
      const fsw_real si = lim / FSW_FABS(c[i]);
      if (si < s) { s = si; }
    }
  }
  if (s < FSW_R(1.0)) {
    for (i = 0; i < cfg->num_mtq; i++) {
      const fsw_real lim = cfg->duty_max * cfg->m_max[i];
      c[i] *= s;
      /* the product can land one ulp above the limit: clamp it */
      if (c[i] > lim) { c[i] = lim; }
      if (c[i] < -lim) { c[i] = -lim; }
    }
  }
  return s;
}

FswStatus fsw_mtq_map_update(FswMtqMapState *st, const FswMtqMapConfig *cfg,
                             const FswMtqMapIn *in, FswMtqMapOut *out)
{
  MtqPinv pinv;
  fsw_real b_hat[3], Bn;  /* [-], [T] field direction and size */
  fsw_real m_B[3];        /* [A*m^2] dipole to deliver */
  fsw_real r[3];          /* [A*m^2] residual m_B - G c */
  fsw_real dc[FSW_MAX_MTQ];
  fsw_real c[FSW_MAX_MTQ]; /* [A*m^2] rod commands */
  fsw_real s;
  FswStatus fs, status;
  int i, n;

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { mtq_safe_output(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) { return FSW_E_NULL_ARG; }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  n = cfg->num_mtq;
  if (in->use_dipole > 1u) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  for (i = 0; i < n; i++) {
    if (in->avail[i] > 1u) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); } }
  if (in->use_dipole ? !mtq_v3_within(in->m_req_B, FSW_MTQ_M_REQ_MAX)
                     : !mtq_v3_within(in->tau_B, FSW_MTQ_TAU_REQ_MAX)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }
  fs = fsw_mtq_field(b_hat, &Bn, in->B_B, in->B_valid);
  if (fs != FSW_OK) { return fsw_health_record(&st->health, fs); } /* W_SINGULAR: rods off */

  if (in->use_dipole) {
    fsw_v3_copy(m_B, in->m_req_B);
  } else {
    /* m_B = (b x tau)/|B|; tau_par = (tau . b) b */
    fsw_v3_cross(m_B, b_hat, in->tau_B);
    fsw_v3_scale(m_B, FSW_R(1.0) / Bn, m_B);
    fsw_v3_scale(out->tau_par_B, fsw_v3_dot(in->tau_B, b_hat), b_hat);
  }

  /* c = G^+ m_B with one refinement step c += G^+ (m_B - G c) */
  mtq_pinv_form(&pinv, cfg, in->avail);
  mtq_pinv_apply(c, &pinv, cfg, in->avail, m_B);
  mtq_dipole(r, cfg, in->avail, c);
  fsw_v3_sub(r, m_B, r);
  mtq_pinv_apply(dc, &pinv, cfg, in->avail, r);
  fsw_vn_add(c, c, dc, FSW_MAX_MTQ);
  mtq_dipole(r, cfg, in->avail, c);
  fsw_v3_sub(r, m_B, r);
  status = fsw_v3_norm(r) > FSW_RESID_TOL * fsw_v3_norm(m_B) ? FSW_W_SINGULAR : FSW_OK;

  s = mtq_saturate(c, cfg);
  if (s < FSW_R(1.0) && status == FSW_OK) { status = FSW_W_SAT; }
  for (i = 0; i < n; i++) {
    /* |c_i| <= fl(duty_max m_max_i), but the quotient can round one ulp
     * above duty_max */
    const fsw_real d = FSW_FABS(c[i]) / cfg->m_max[i];
    out->duty[i] = d < cfg->duty_max ? d : cfg->duty_max;
  }
  fsw_vn_copy(out->m_cmd, c, n);
  mtq_dipole(out->m_ach_B, cfg, in->avail, c);
  fsw_v3_cross(out->tau_ach_B, out->m_ach_B, in->B_B);
  out->scale = s;
  out->rank = pinv.rank;
  /* accepted ranges keep everything finite; checked all the same */
  if (!fsw_vn_is_finite(out->m_cmd, n) || !fsw_v3_is_finite(out->tau_ach_B) ||
      !fsw_v3_is_finite(out->tau_par_B) || !isfinite(s)) {
    mtq_safe_output(out);
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  return fsw_health_record(&st->health, status);
}

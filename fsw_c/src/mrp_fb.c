/* mrp_fb: MRP feedback control law (docs/fsw/mrp_fb.md). */
#include "fsw/mrp_fb.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_vec.h"
#include "fsw/rw_common.h"
#include "fsw_vec_inline.h"
#include "fsw_status_inline.h"
#include "mrp_fb_internal.h"

/* Relative symmetry tolerance of the inertia: |I_jk - I_kj| <= tol * max|I|. */
#if FSW_USE_FLOAT
#define MRP_FB_SYM_TOL FSW_R(1e-6)
#else
#define MRP_FB_SYM_TOL FSW_R(1e-12)
#endif

static void write_safe(FswMrpFbOut *out)
{
  fsw_v3_zero(out->torque_B);
  fsw_v3_zero(out->int_torque_B);
}

/* Symmetric and positive definite by Sylvester's criterion (leading minors
 * > 0), with a scale-invariant symmetry test. */
static int inertia_ok(const fsw_real I[3][3])
{
  fsw_real max_abs = FSW_R(0.0);
  fsw_real m1, m2, m3;
  int j, k;
  if (!fsw_m33_is_finite(I)) { return 0; }
  for (j = 0; j < 3; j++) {
    for (k = 0; k < 3; k++) {
      if (FSW_FABS(I[j][k]) > max_abs) { max_abs = FSW_FABS(I[j][k]); } } }
  if (!(max_abs > FSW_R(0.0))) { return 0; }
  for (j = 0; j < 3; j++) {
    for (k = j + 1; k < 3; k++) {
      if (FSW_FABS(I[j][k] - I[k][j]) > MRP_FB_SYM_TOL * max_abs) { return 0; } } }
  m1 = I[0][0];
  m2 = I[0][0] * I[1][1] - I[0][1] * I[1][0];
  m3 = fsw_m33_det(I);
  return m1 > FSW_R(0.0) && m2 > FSW_R(0.0) && m3 > FSW_R(0.0);
}

FswStatus fsw_mrp_fb_check(const FswMrpFbConfig *cfg)
{
  int i;
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (!isfinite(cfg->K) || !(cfg->K > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->P) || !(cfg->P > FSW_R(0.0))) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->K_i)) { return FSW_E_CONFIG; }
  if (!isfinite(cfg->integral_limit) || cfg->integral_limit < FSW_R(0.0)) { return FSW_E_CONFIG; }
  if (cfg->control_law_type != FSW_MRP_FB_LAW_0 && cfg->control_law_type != FSW_MRP_FB_LAW_1) {
    return FSW_E_CONFIG;
  }
  if (!fsw_v3_is_finite(cfg->known_torque_B)) { return FSW_E_CONFIG; }
  if (!inertia_ok(cfg->I_B)) { return FSW_E_CONFIG; }
  if (cfg->num_rw < 0) { return FSW_E_CONFIG; }
  if (cfg->num_rw > FSW_MAX_RW) { return FSW_E_CAPACITY; }
  for (i = 0; i < cfg->num_rw; i++) {
    if (!fsw_v3_is_finite(cfg->gs_hat_B[i])) { return FSW_E_CONFIG; }
    if (!(FSW_FABS(fsw_v3_norm(cfg->gs_hat_B[i]) - FSW_R(1.0)) <= FSW_MRP_FB_UNIT_TOL)) {
      return FSW_E_CONFIG;
    }
    /* bounded like every wheel module's J_s (rw_common.h): with |Omega| <=
     * FSW_RW_OMEGA_MAX the wheel momentum J_s Omega stays finite */
    if (!((cfg->J_s[i] > FSW_R(0.0)) && (cfg->J_s[i] <= FSW_RW_J_S_MAX))) { return FSW_E_CONFIG; }
  }
  return FSW_OK;
}

FswStatus fsw_mrp_fb_init(FswMrpFbState *st, const FswMrpFbConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  (void)memset(st, 0, sizeof *st);
  fsw_health_clear(&st->health);
  s = fsw_mrp_fb_check(cfg);
  if (s != FSW_OK) { return s; }
  st->ready = 1;
  fsw_mrp_fb_reset(st);
  return FSW_OK;
}

void fsw_mrp_fb_reset(FswMrpFbState *st)
{
  FSW_ASSERT(st != NULL);
  if (st == NULL) { return; }
  fsw_clock_reset(&st->clock);
  fsw_v3_zero(st->int_sigma);
}

static int guid_is_finite(const FswAttGuid *g)
{
  return fsw_v3_is_finite(g->sigma_BR) && fsw_v3_is_finite(g->omega_BR_B) &&
         fsw_v3_is_finite(g->omega_RN_B) && fsw_v3_is_finite(g->omega_dot_RN_B);
}

static int wheels_ok(const FswMrpFbConfig *cfg, const FswMrpFbIn *in)
{
  int i;
  for (i = 0; i < cfg->num_rw; i++) {
    if (in->rw_avail[i] == FSW_AVAILABLE) {
      if (!isfinite(in->Omega[i])) { return 0; }
    } else if (in->rw_avail[i] != FSW_UNAVAILABLE) {
      return 0;
    }
  }
  return 1;
}

FswStatus fsw_mrp_fb_update(FswMrpFbState *st, const FswMrpFbConfig *cfg, const FswMrpFbIn *in,
                            FswMrpFbOut *out)
{
  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { write_safe(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    return fsw_health_record(st != NULL ? &st->health : NULL, FSW_E_NULL_ARG);
  }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (!guid_is_finite(&in->guid) || !wheels_ok(cfg, in)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  return fsw_mrp_fb_torque(st, cfg, &in->guid, in->t_ns, in->Omega, in->rw_avail, out);
}

FswStatus fsw_mrp_fb_torque(FswMrpFbState *st, const FswMrpFbConfig *cfg, const FswAttGuid *guid,
                            uint64_t t_ns, const fsw_real Omega[FSW_MAX_RW],
                            const uint8_t rw_avail[FSW_MAX_RW], FswMrpFbOut *out)
{
  const FswAttGuid *g = guid;
  fsw_real dt = FSW_R(0.0);  /* [s] */
  fsw_real int_sigma[3];     /* [N*m*s] candidate integral (committed at the end) */
  fsw_real omega_BN_B[3];    /* [rad/s] omega = omega_BR + omega_RN */
  fsw_real z[3];             /* [N*m*s] */
  fsw_real Ki_z[3];          /* [rad/s] K_i z */
  fsw_real P_Ki_z[3];        /* [N*m]   P K_i z */
  fsw_real h_B[3];           /* [N*m*s] H = [I] omega + wheel momenta */
  fsw_real v_B[3];           /* [rad/s] */
  fsw_real v_x_h_B[3];       /* [N*m] */
  fsw_real w_x_wr_B[3];      /* [rad/s^2] omega x omega_RN - omega_dot_RN */
  fsw_real I_term_B[3];      /* [N*m] */
  fsw_real tmp[3];
  fsw_real sum_B[3];
  int i;

  write_safe(out);
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  {
    const FswStatus s = fsw_clock_dt(&st->clock, t_ns, &dt); /* FSW_OK or FSW_E_TIME */
    if (s != FSW_OK) { return fsw_health_record(&st->health, s); }
  }

  /* 1. omega = omega_BR + omega_RN */
  fsw_v3_add(omega_BN_B, g->omega_BR_B, g->omega_RN_B);

  /* 2. integral term */
  fsw_v3_copy(int_sigma, st->int_sigma);
  fsw_v3_zero(z);
  if (cfg->K_i > FSW_R(0.0)) {
    fsw_v3_scale(tmp, cfg->K * dt, g->sigma_BR);
    fsw_v3_add(int_sigma, int_sigma, tmp);
    for (i = 0; i < 3; i++) {
      if (FSW_FABS(int_sigma[i]) > cfg->integral_limit) {
        int_sigma[i] = int_sigma[i] > FSW_R(0.0) ? cfg->integral_limit : -cfg->integral_limit;
      }
    }
    fsw_m33_mult_v3(tmp, cfg->I_B, g->omega_BR_B);
    fsw_v3_add(z, int_sigma, tmp);
  }

  /* 3. H = [I] omega + sum over available wheels of J_s (gs . omega + Omega) gs */
  fsw_m33_mult_v3(h_B, cfg->I_B, omega_BN_B);
  for (i = 0; i < cfg->num_rw; i++) {
    if (rw_avail[i] == FSW_AVAILABLE) {
      const fsw_real h_s = cfg->J_s[i] * (fsw_v3_dot(omega_BN_B, cfg->gs_hat_B[i]) + Omega[i]);
      fsw_v3_scale(tmp, h_s, cfg->gs_hat_B[i]);
      fsw_v3_add(h_B, h_B, tmp);
    }
  }

  /* 4. v */
  fsw_v3_scale(Ki_z, cfg->K_i, z);
  if (cfg->control_law_type == FSW_MRP_FB_LAW_0) {
    fsw_v3_add(v_B, g->omega_RN_B, Ki_z);
  } else {
    fsw_v3_copy(v_B, omega_BN_B);
  }

  /* 5. Lr = -(K sigma + P omega_BR + P K_i z - v x H + [I](omega x omega_RN - domega_RN) + L) */
  fsw_v3_scale(P_Ki_z, cfg->P, Ki_z);
  fsw_v3_scale(sum_B, cfg->K, g->sigma_BR);
  fsw_v3_scale(tmp, cfg->P, g->omega_BR_B);
  fsw_v3_add(sum_B, sum_B, tmp);
  fsw_v3_add(sum_B, sum_B, P_Ki_z);
  fsw_v3_cross(v_x_h_B, v_B, h_B);
  fsw_v3_sub(sum_B, sum_B, v_x_h_B);
  fsw_v3_cross(w_x_wr_B, omega_BN_B, g->omega_RN_B);
  fsw_v3_sub(w_x_wr_B, w_x_wr_B, g->omega_dot_RN_B);
  fsw_m33_mult_v3(I_term_B, cfg->I_B, w_x_wr_B);
  fsw_v3_add(sum_B, sum_B, I_term_B);
  fsw_v3_add(sum_B, sum_B, cfg->known_torque_B);

  /* finite but huge inputs can overflow: treat like non-finite input */
  if (!fsw_v3_is_finite(sum_B) || !fsw_v3_is_finite(P_Ki_z)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }

  /* 6. outputs; commit state */
  fsw_v3_scale(out->torque_B, FSW_R(-1.0), sum_B);
  fsw_v3_scale(out->int_torque_B, FSW_R(-1.0), P_Ki_z);
  fsw_v3_copy(st->int_sigma, int_sigma);
  fsw_clock_commit(&st->clock, t_ns);
  return fsw_health_record_ok_i(&st->health);
}

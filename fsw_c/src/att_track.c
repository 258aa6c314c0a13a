/* att_track: attitude tracking error (docs/fsw/att_track.md). */
#include "fsw/att_track.h"

#include <stddef.h>
#include <string.h>

#include "fsw/fsw_attitude.h"
#include "fsw/fsw_vec.h"

static void write_safe(FswAttTrackOut *out)
{
  fsw_v3_zero(out->sigma_BR);
  fsw_v3_zero(out->omega_BR_B);
  fsw_v3_zero(out->omega_RN_B);
  fsw_v3_zero(out->omega_dot_RN_B);
}

FswStatus fsw_att_track_check(const FswAttTrackConfig *cfg)
{
  FSW_ASSERT(cfg != NULL);
  if (cfg == NULL) { return FSW_E_NULL_ARG; }
  if (!fsw_v3_is_finite(cfg->sigma_R0R)) { return FSW_E_CONFIG; }
  if (!isfinite(fsw_v3_norm2(cfg->sigma_R0R))) { return FSW_E_CONFIG; }
  return FSW_OK;
}

FswStatus fsw_att_track_init(FswAttTrackState *st, const FswAttTrackConfig *cfg)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  (void)memset(st, 0, sizeof *st);
  fsw_health_clear(&st->health);
  s = fsw_att_track_check(cfg);
  if (s != FSW_OK) { return s; }
  /* -sigma_R0R is the exact inverse rotation; no shadow switch (Basilisk
   * parity: the sum is switched by addMRP). */
  fsw_v3_scale(st->sigma_RR0, FSW_R(-1.0), cfg->sigma_R0R);
  st->ready = 1;
  fsw_att_track_reset(st);
  return FSW_OK;
}

void fsw_att_track_reset(FswAttTrackState *st)
{
  FSW_ASSERT(st != NULL);
  (void)st; /* stateless */
}

static int in_is_finite(const FswAttTrackIn *in)
{
  return fsw_v3_is_finite(in->sigma_BN) && fsw_v3_is_finite(in->omega_BN_B) &&
         fsw_v3_is_finite(in->ref.sigma_RN) && fsw_v3_is_finite(in->ref.omega_RN_N) &&
         fsw_v3_is_finite(in->ref.omega_dot_RN_N) && isfinite(fsw_v3_norm2(in->sigma_BN)) &&
         isfinite(fsw_v3_norm2(in->ref.sigma_RN));
}

FswStatus fsw_att_track_update(FswAttTrackState *st, const FswAttTrackConfig *cfg,
                               const FswAttTrackIn *in, FswAttTrackOut *out)
{
  fsw_real sigma_RN_corr[3]; /* [-] corrected reference sigma_RN'  */
  fsw_real sigma_BR[3];      /* [-]                                 */
  fsw_real dcm_BN[3][3];     /* [-] [BN] = MRP2C(sigma_BN)          */
  fsw_real omega_RN_B[3];    /* [rad/s]                             */
  fsw_real omega_dot_RN_B[3];/* [rad/s^2]                           */
  fsw_real omega_BR_B[3];    /* [rad/s]                             */

  FSW_ASSERT(st != NULL && cfg != NULL && in != NULL && out != NULL);
  if (out != NULL) { write_safe(out); }
  if (st == NULL || cfg == NULL || in == NULL || out == NULL) {
    return fsw_health_record(st != NULL ? &st->health : NULL, FSW_E_NULL_ARG);
  }
  if (!st->ready) { return fsw_health_record(&st->health, FSW_E_NOT_INIT); }
  if (!in_is_finite(in)) { return fsw_health_record(&st->health, FSW_E_BAD_INPUT); }

  fsw_mrp_add(sigma_RN_corr, in->ref.sigma_RN, st->sigma_RR0);
  fsw_mrp_sub(sigma_BR, in->sigma_BN, sigma_RN_corr);
  fsw_mrp_to_dcm(dcm_BN, in->sigma_BN);
  fsw_m33_mult_v3(omega_RN_B, FSW_CM33(dcm_BN), in->ref.omega_RN_N);
  fsw_m33_mult_v3(omega_dot_RN_B, FSW_CM33(dcm_BN), in->ref.omega_dot_RN_N);

  fsw_v3_sub(omega_BR_B, in->omega_BN_B, omega_RN_B);
  /* finite but huge inputs can overflow: treat like non-finite input */
  if (!fsw_v3_is_finite(sigma_BR) || !fsw_v3_is_finite(omega_BR_B) ||
      !fsw_v3_is_finite(omega_RN_B) || !fsw_v3_is_finite(omega_dot_RN_B)) {
    return fsw_health_record(&st->health, FSW_E_BAD_INPUT);
  }
  fsw_v3_copy(out->sigma_BR, sigma_BR);
  fsw_v3_copy(out->omega_BR_B, omega_BR_B);
  fsw_v3_copy(out->omega_RN_B, omega_RN_B);
  fsw_v3_copy(out->omega_dot_RN_B, omega_dot_RN_B);
  return fsw_health_record(&st->health, FSW_OK);
}

/* rw_common: checks, cached null-space projector and scale-to-fit shared by
 * the reaction-wheel modules. */
#include "fsw/rw_common.h"

#include <math.h>
#include <stddef.h>

#include "fsw/fsw_linalg.h"
#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"

FswStatus fsw_rw_check_axes(const fsw_real gs_hat_B[FSW_MAX_RW][3], int num_rw, int min_rw)
{
  int i;
  if (num_rw < min_rw || num_rw > FSW_MAX_RW) { return FSW_E_CAPACITY; }
  for (i = 0; i < num_rw; i++) {
    if (!fsw_v3_is_finite(gs_hat_B[i])) { return FSW_E_CONFIG; }
    if (FSW_FABS(fsw_v3_norm(gs_hat_B[i]) - FSW_R(1.0)) > FSW_RW_UNIT_TOL) { return FSW_E_CONFIG; }
  }
  return FSW_OK;
}

int fsw_rw_all_positive(const fsw_real *v, int n)
{
  int i;
  for (i = 0; i < n; i++) {
    if (!isfinite(v[i]) || !(v[i] > FSW_R(0.0))) { return 0; } }
  return 1;
}

int fsw_rw_all_in_range(const fsw_real *v, int n, fsw_real lo, fsw_real hi)
{
  int i;
  for (i = 0; i < n; i++) {
    if (!isfinite(v[i]) || !(v[i] > FSW_R(0.0)) || v[i] < lo || v[i] > hi) { return 0; } }
  return 1;
}

int fsw_rw_avail_finite(const fsw_real *x, const uint8_t avail[FSW_MAX_RW], int n)
{
  int i;
  for (i = 0; i < n; i++) {
    if (avail[i] == FSW_AVAILABLE && !isfinite(x[i])) { return 0; } }
  return 1;
}

int fsw_rw_avail_speed_ok(const fsw_real *x, const uint8_t avail[FSW_MAX_RW], int n)
{
  int i;
  for (i = 0; i < n; i++) {
    if (avail[i] == FSW_AVAILABLE && !(FSW_FABS(x[i]) <= FSW_RW_OMEGA_MAX)) { return 0; } }
  return 1;
}

int fsw_rw_avail_valid(const uint8_t avail[FSW_MAX_RW], int n)
{
  int i;
  for (i = 0; i < n; i++) {
    if (avail[i] != FSW_AVAILABLE && avail[i] != FSW_UNAVAILABLE) { return 0; } }
  return 1;
}

void fsw_rw_zero(fsw_real u[FSW_MAX_RW]) { fsw_vn_zero(u, FSW_MAX_RW); }

void fsw_rw_momentum(fsw_real h_B[3], const fsw_real gs_hat_B[FSW_MAX_RW][3], const fsw_real *J_s,
                     const fsw_real *Omega, const uint8_t avail[FSW_MAX_RW], int n)
{
  int i;
  fsw_v3_zero(h_B);
  for (i = 0; i < n; i++) {
    if (avail[i] == FSW_AVAILABLE) { fsw_v3_axpy(h_B, h_B, J_s[i] * Omega[i], gs_hat_B[i]); } }
}

static void proj_compute(FswRwNullProj *p)
{
  int i;
  p->num_avail = 0;
  for (i = 0; i < p->num_rw; i++) {
    if (p->avail[i] == FSW_AVAILABLE) { p->num_avail++; } }
  /* G is finite (checked config) and num_rw in range: K2 cannot fail */
  (void)fsw_null_projector(p->tau, FSW_CM3N(p->G), p->num_rw, p->avail, &p->rank);
  /* No null space (e.g. three independent wheels): K2 leaves round-off of
   * order eps in tau; make it exactly 0 so the output is exactly the input. */
  if (p->rank >= p->num_avail) {
    for (i = 0; i < p->num_rw; i++) { fsw_vn_zero(p->tau[i], p->num_rw); } }
}

void fsw_rw_proj_init(FswRwNullProj *p, const fsw_real gs_hat_B[FSW_MAX_RW][3], int num_rw)
{
  int i, r;
  for (i = 0; i < FSW_MAX_EFF; i++) {
    for (r = 0; r < 3; r++) { p->G[r][i] = (i < num_rw) ? gs_hat_B[i][r] : FSW_R(0.0); }
    fsw_vn_zero(p->tau[i], FSW_MAX_EFF);
  }
  for (i = 0; i < FSW_MAX_RW; i++) { p->avail[i] = FSW_AVAILABLE; }
  p->num_rw = num_rw;
  proj_compute(p);
}

int fsw_rw_proj_refresh(FswRwNullProj *p, const uint8_t avail[FSW_MAX_RW])
{
  int i, changed = 0;
  for (i = 0; i < p->num_rw; i++) {
    uint8_t a = (avail == NULL) ? (uint8_t)FSW_AVAILABLE : avail[i];
    if (a != p->avail[i]) { changed = 1; }
    p->avail[i] = a;
  }
  if (changed) { proj_compute(p); }
  return changed;
}

fsw_real fsw_rw_add_scaled_to_fit(fsw_real *out, const fsw_real *u_c, const fsw_real *du,
                                  const fsw_real *u_max, int n)
{
  fsw_real kappa = FSW_R(1.0);
  int i;
  if (u_max != NULL) {
    for (i = 0; i < n; i++) {
      fsw_real step;
      if (FSW_FABS(u_c[i]) > u_max[i]) {
        kappa = FSW_R(0.0);
        break;
      }
      if (du[i] > FSW_R(0.0)) {
        step = (u_max[i] - u_c[i]) / du[i];
      } else if (du[i] < FSW_R(0.0)) {
        step = (-u_max[i] - u_c[i]) / du[i];
      } else {
        continue; }
      if (step < kappa) { kappa = step; }
    }
  }
  for (i = 0; i < n; i++) { out[i] = u_c[i] + kappa * du[i]; }
  if (u_max != NULL && kappa > FSW_R(0.0)) {
    for (i = 0; i < n; i++) {
      if (out[i] > u_max[i]) { out[i] = u_max[i]; }
      if (out[i] < -u_max[i]) { out[i] = -u_max[i]; }
    }
  }
  return kappa;
}

void fsw_rw_proj_apply(fsw_real *out, const FswRwNullProj *p, const fsw_real *d)
{
  fsw_real t[FSW_MAX_RW];
  int i, n = p->num_rw;
  for (i = 0; i < n; i++) { t[i] = fsw_vn_dot(p->tau[i], d, n); }
  for (i = 0; i < n; i++) { out[i] = fsw_vn_dot(p->tau[i], t, n); }
}

int fsw_rw_null_change_ok(const FswRwNullProj *p, const fsw_real *u, const fsw_real *u0, int n)
{
  fsw_real t[3] = {FSW_R(0.0), FSW_R(0.0), FSW_R(0.0)};
  fsw_real size = FSW_R(0.0);
  int i, k;
  for (i = 0; i < n; i++) {
    const fsw_real c = u[i] - u0[i];
    size += FSW_FABS(c);
    for (k = 0; k < 3; k++) { t[k] += p->G[k][i] * c; }
  }
  return fsw_v3_norm(t) <= FSW_NULL_TOL * size;
}


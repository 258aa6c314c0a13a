// Test helpers shared by the reaction-wheel module tests: geometries, an
// independent (plain C++, double) weighted minimum-norm solver, body torque,
// zero-initialised heap allocation (the bare-metal targets have a small
// stack, and the null-space states are ~11 KiB).
#ifndef KESTREL_RW_TEST_UTIL_H
#define KESTREL_RW_TEST_UTIL_H

#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

#include "fsw/fsw_config.h"
#include "kestrel_test_support.h"

namespace rwt {

// Zero-initialised object on the heap.
template <class T>
std::unique_ptr<T> make0()
{
  return std::unique_ptr<T>(new T());
}

// Wheel counts of the property tests (issue 4).
constexpr int kCounts[] = {3, 4, 6, 36};

// 4-wheel pyramid of the docs: g_i = (sx, sy, 1)/sqrt(3) with
// (sx, sy) = (+,+), (-,+), (-,-), (+,-).  [Gs][Gs]^T = (4/3) I, so the
// minimum-norm map is u = -(3/4) [Gs]^T Lr and null([Gs]) = (1,-1,1,-1)/2.
inline void pyramid4(double g[][3])
{
  const double s = 1.0 / std::sqrt(3.0);
  const double sx[4] = {1, -1, -1, 1}, sy[4] = {1, 1, -1, -1};
  for (int i = 0; i < 4; i++) {
    g[i][0] = sx[i] * s;
    g[i][1] = sy[i] * s;
    g[i][2] = s;
  }
}

inline void random_axes(kt::Rng& rng, int n, double g[][3])
{
  for (int i = 0; i < n; i++) rng.unit3(g[i]);
}

// n unit axes all in the plane orthogonal to a random normal (rank 2).
inline void coplanar_axes(kt::Rng& rng, int n, double g[][3])
{
  double nrm[3];
  rng.unit3(nrm);
  for (int i = 0; i < n; i++) {
    double v[3];
    double len;
    do {
      rng.unit3(v);
      double d = v[0] * nrm[0] + v[1] * nrm[1] + v[2] * nrm[2];
      for (int r = 0; r < 3; r++) v[r] -= d * nrm[r];
      len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (len < 0.1);
    for (int r = 0; r < 3; r++) g[i][r] = v[r] / len;
  }
}

// Copy double axes into a config's fsw_real array.
inline void set_axes(fsw_real dst[][3], const double src[][3], int n)
{
  for (int i = 0; i < n; i++)
    for (int r = 0; r < 3; r++) dst[i][r] = static_cast<fsw_real>(src[i][r]);
}

// Body-frame torque of wheel torques: t = [Gs] u (the body feels -t).
template <class R1, class R2>
void gs_times(double t[3], const R1 g[][3], const R2* u, int n)
{
  for (int r = 0; r < 3; r++) {
    double s = 0.0;
    for (int i = 0; i < n; i++) s += static_cast<double>(g[i][r]) * static_cast<double>(u[i]);
    t[r] = s;
  }
}

inline double norm3(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// Independent weighted minimum-norm solver (Lagrange multipliers, Gaussian
// elimination with partial pivoting): min sum u_i^2 W_i s.t.
// [C][Gs_a] u = -[C] Lr over the available wheels.  W == nullptr: W = 1.
// Returns false when the nc x nc system is singular (relative 1e-10).
template <class R>
bool ref_wmn(double* u, int nc, const double C[3][3], int n, const R g[][3], const double* W,
             const uint8_t* avail, const double Lr[3])
{
  double A[3][64], M[3][4];
  for (int i = 0; i < n; i++) u[i] = 0.0;
  for (int j = 0; j < nc; j++)
    for (int i = 0; i < n; i++) {
      bool ok = avail == nullptr || avail[i] == 0;
      A[j][i] = ok ? C[j][0] * double(g[i][0]) + C[j][1] * double(g[i][1]) + C[j][2] * double(g[i][2]) : 0.0;
    }
  double dmax = 0.0;
  for (int j = 0; j < nc; j++) {
    for (int k = 0; k < nc; k++) {
      double s = 0.0;
      for (int i = 0; i < n; i++) s += A[j][i] * A[k][i] / (W ? W[i] : 1.0);
      M[j][k] = s;
    }
    M[j][3] = -(C[j][0] * Lr[0] + C[j][1] * Lr[1] + C[j][2] * Lr[2]);
    dmax = std::fmax(dmax, M[j][j]);
  }
  if (!(dmax > 0.0)) return false;
  for (int c = 0; c < nc; c++) {
    int p = c;
    for (int r = c + 1; r < nc; r++)
      if (std::fabs(M[r][c]) > std::fabs(M[p][c])) p = r;
    if (std::fabs(M[p][c]) <= 1e-10 * dmax) return false;
    for (int k = 0; k < 4; k++) std::swap(M[c][k], M[p][k]);
    for (int r = 0; r < nc; r++) {
      if (r == c) continue;
      double f = M[r][c] / M[c][c];
      for (int k = 0; k < 4; k++) M[r][k] -= f * M[c][k];
    }
  }
  for (int i = 0; i < n; i++) {
    double s = 0.0;
    for (int j = 0; j < nc; j++) s += A[j][i] * M[j][3] / M[j][j];
    u[i] = s / (W ? W[i] : 1.0);
  }
  return true;
}

}  // namespace rwt

#endif  // KESTREL_RW_TEST_UTIL_H

// Test helpers shared by the guidance / control / sun-sensor tests: an
// independent reference for attitude maths written in plain C++ double
// (principal-rotation formulas, not the element-wise MRP2C of fsw_attitude.h), small
// 3-vector / 3x3 helpers and conversions between double and fsw_real.
// No Eigen, no <random> (the tests also run on bare metal with picolibc).
#ifndef KESTREL_GNC_TEST_REF_H
#define KESTREL_GNC_TEST_REF_H

#include <cmath>

#include "fsw/fsw_config.h"
#include "kestrel_test_support.h"

namespace gref {

constexpr double kPi = 3.14159265358979323846;

inline void to_real(fsw_real out[3], const double a[3])
{
  for (int i = 0; i < 3; i++) out[i] = static_cast<fsw_real>(a[i]);
}
inline void to_double(double out[3], const fsw_real a[3])
{
  for (int i = 0; i < 3; i++) out[i] = static_cast<double>(a[i]);
}
inline void set3(fsw_real out[3], double x, double y, double z)
{
  out[0] = static_cast<fsw_real>(x);
  out[1] = static_cast<fsw_real>(y);
  out[2] = static_cast<fsw_real>(z);
}
// x rounded to fsw_real and back: the exact value a module sees for literal x
inline double rr(double x) { return static_cast<double>(static_cast<fsw_real>(x)); }
inline double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const double a[3]) { return std::sqrt(dot(a, a)); }
inline void cross(double out[3], const double a[3], const double b[3])
{
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  for (int i = 0; i < 3; i++) out[i] = c[i];
}
inline void matvec(double out[3], const double A[3][3], const double v[3])
{
  double r[3];
  for (int i = 0; i < 3; i++) r[i] = A[i][0] * v[0] + A[i][1] * v[1] + A[i][2] * v[2];
  for (int i = 0; i < 3; i++) out[i] = r[i];
}
inline void matmul(double out[3][3], const double A[3][3], const double B[3][3])
{
  double r[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) r[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) out[i][j] = r[i][j];
}
inline void transpose(double out[3][3], const double A[3][3])
{
  double r[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) r[i][j] = A[j][i];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) out[i][j] = r[i][j];
}

// DCM of an MRP through its principal rotation (Schaub & Junkins 3.6):
// Phi = 4 atan|s|, e = s/|s|,
// [C] = cos(Phi) I + (1 - cos(Phi)) e e^T - sin(Phi) [e~]   (passive, v_B = [C] v_N)
inline void dcm_of_mrp(double C[3][3], const double s[3])
{
  const double n = norm(s);
  if (n == 0.0) {
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) C[i][j] = i == j ? 1.0 : 0.0;
    return;
  }
  const double e[3] = {s[0] / n, s[1] / n, s[2] / n};
  const double phi = 4.0 * std::atan(n);
  const double c = std::cos(phi), sn = std::sin(phi);
  const double E[3][3] = {{0, -e[2], e[1]}, {e[2], 0, -e[0]}, {-e[1], e[0], 0}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) C[i][j] = (i == j ? c : 0.0) + (1.0 - c) * e[i] * e[j] - sn * E[i][j];
}
#if FSW_USE_FLOAT
inline void dcm_of_mrp(double C[3][3], const fsw_real s[3])
{
  double d[3];
  to_double(d, s);
  dcm_of_mrp(C, d);
}
#endif

inline double max_abs_diff(const double A[3][3], const double B[3][3])
{
  double m = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) m = std::fmax(m, std::fabs(A[i][j] - B[i][j]));
  return m;
}

// MRP of a random rotation: uniform axis, angle uniform in [0, phi_max).
inline void random_mrp(kt::Rng& r, double s[3], double phi_max = 2.0 * kPi)
{
  double e[3];
  r.unit3(e);
  const double t = std::tan(r.uniform(0.0, phi_max) / 4.0);
  for (int i = 0; i < 3; i++) s[i] = t * e[i];
}

inline double nan() { return std::nan(""); }
inline double inf() { return HUGE_VAL; }

}  // namespace gref

#define EXPECT_V3_NEAR(want0, want1, want2, got, tol)                                         \
  do {                                                                                        \
    EXPECT_NEAR((want0), static_cast<double>((got)[0]), (tol));                               \
    EXPECT_NEAR((want1), static_cast<double>((got)[1]), (tol));                               \
    EXPECT_NEAR((want2), static_cast<double>((got)[2]), (tol));                               \
  } while (0)

#endif /* KESTREL_GNC_TEST_REF_H */

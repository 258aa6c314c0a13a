// magnetic_field: see sim/magnetic_field.h and docs/environment.md.
#include "sim/magnetic_field.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "validate_util.h"

namespace sim {

using Eigen::Vector3d;

namespace {

struct IgrfRow {
  int n, m;
  double g2020, h2020;  // [nT]     DGRF 2020.0
  double g2025, h2025;  // [nT]     IGRF 2025.0
  double g_sv, h_sv;    // [nT/yr]  secular variation 2025-2030
};

// IGRF-14 Gauss coefficients, Schmidt semi-normalised, n = 1..13 (IAGA
// V-MOD, igrf14coeffs: the DGRF 2020.0 and IGRF 2025.0 columns and the
// 2025-30 secular variation, which is zero beyond degree 8).
constexpr IgrfRow kIgrf14[] = {
    {1, 0, -29403.41, 0.0, -29350.0, 0.0, 12.6, 0.0},
    {1, 1, -1451.37, 4653.35, -1410.3, 4545.5, 10.0, -21.5},
    {2, 0, -2499.78, 0.0, -2556.2, 0.0, -11.2, 0.0},
    {2, 1, 2981.96, -2991.72, 2950.9, -3133.6, -5.3, -27.3},
    {2, 2, 1676.85, -734.62, 1648.7, -814.2, -8.3, -11.1},
    {3, 0, 1363.0, 0.0, 1360.9, 0.0, -1.5, 0.0},
    {3, 1, -2380.8, -81.96, -2404.2, -56.9, -4.4, 3.8},
    {3, 2, 1236.06, 241.8, 1243.8, 237.6, 0.4, -0.2},
    {3, 3, 525.6, -542.52, 453.4, -549.6, -15.6, -3.9},
    {4, 0, 902.82, 0.0, 894.6, 0.0, -1.7, 0.0},
    {4, 1, 809.47, 282.1, 799.6, 278.6, -2.3, -1.3},
    {4, 2, 86.18, -158.5, 55.8, -134.0, -5.8, 4.1},
    {4, 3, -309.47, 199.75, -281.1, 212.0, 5.4, 1.6},
    {4, 4, 47.44, -350.3, 12.0, -375.4, -6.8, -4.0},
    {5, 0, -234.42, 0.0, -232.9, 0.0, 0.6, 0.0},
    {5, 1, 363.26, 47.52, 369.0, 45.3, 1.3, -0.5},
    {5, 2, 187.86, 208.36, 187.2, 220.0, 0.0, 2.0},
    {5, 3, -140.73, -121.43, -138.7, -122.9, 0.7, 0.5},
    {5, 4, -151.16, 32.09, -141.9, 42.9, 2.2, 1.7},
    {5, 5, 13.98, 99.14, 20.9, 106.2, 1.0, 1.9},
    {6, 0, 65.97, 0.0, 64.3, 0.0, -0.2, 0.0},
    {6, 1, 65.56, -19.22, 63.8, -18.4, -0.3, 0.3},
    {6, 2, 72.96, 25.02, 76.7, 16.8, 0.8, -1.6},
    {6, 3, -121.57, 52.76, -115.7, 48.9, 1.1, -0.4},
    {6, 4, -36.06, -64.4, -40.9, -59.8, -0.8, 0.8},
    {6, 5, 13.6, 8.96, 14.9, 10.9, 0.4, 0.7},
    {6, 6, -64.8, 68.04, -60.8, 72.8, 0.9, 0.9},
    {7, 0, 80.54, 0.0, 79.6, 0.0, -0.1, 0.0},
    {7, 1, -76.63, -51.5, -76.9, -48.9, -0.1, 0.6},
    {7, 2, -8.23, -16.85, -8.8, -14.4, -0.1, 0.5},
    {7, 3, 56.45, 2.36, 59.3, -1.0, 0.5, -0.7},
    {7, 4, 15.8, 23.56, 15.8, 23.5, -0.1, 0.0},
    {7, 5, 6.3, -2.19, 2.5, -7.3, -0.8, -0.9},
    {7, 6, -7.21, -27.19, -11.2, -25.1, -0.8, 0.5},
    {7, 7, 9.77, -1.9, 14.3, -2.2, 0.9, -0.3},
    {8, 0, 23.66, 0.0, 23.1, 0.0, -0.1, 0.0},
    {8, 1, 9.74, 8.43, 10.9, 7.2, 0.2, -0.2},
    {8, 2, -17.49, -15.23, -17.5, -12.6, 0.0, 0.4},
    {8, 3, -0.49, 12.83, 2.0, 11.5, 0.4, -0.3},
    {8, 4, -21.07, -11.76, -21.8, -9.7, -0.1, 0.4},
    {8, 5, 15.28, 14.94, 16.9, 12.7, 0.3, -0.5},
    {8, 6, 13.65, 3.62, 14.9, 0.7, 0.1, -0.6},
    {8, 7, -16.59, -6.9, -16.8, -5.2, 0.0, 0.3},
    {8, 8, -0.34, 2.9, 1.0, 3.9, 0.3, 0.2},
    {9, 0, 5.03, 0.0, 4.7, 0.0, 0.0, 0.0},
    {9, 1, 8.36, -23.44, 8.0, -24.8, 0.0, 0.0},
    {9, 2, 2.84, 11.04, 3.0, 12.1, 0.0, 0.0},
    {9, 3, -1.48, 9.86, -0.2, 8.3, 0.0, 0.0},
    {9, 4, -1.14, -5.13, -2.5, -3.4, 0.0, 0.0},
    {9, 5, -13.22, -6.2, -13.1, -5.3, 0.0, 0.0},
    {9, 6, 1.08, 7.79, 2.4, 7.2, 0.0, 0.0},
    {9, 7, 8.82, 0.4, 8.6, -0.6, 0.0, 0.0},
    {9, 8, -9.23, -1.44, -8.7, 0.8, 0.0, 0.0},
    {9, 9, -11.86, 9.6, -12.8, 9.8, 0.0, 0.0},
    {10, 0, -1.84, 0.0, -1.3, 0.0, 0.0, 0.0},
    {10, 1, -6.25, 3.38, -6.4, 3.3, 0.0, 0.0},
    {10, 2, -0.11, -0.18, 0.2, 0.1, 0.0, 0.0},
    {10, 3, 1.66, 3.5, 2.0, 2.5, 0.0, 0.0},
    {10, 4, -0.86, 4.86, -1.0, 5.4, 0.0, 0.0},
    {10, 5, 0.65, -8.62, -0.5, -9.0, 0.0, 0.0},
    {10, 6, -0.88, -0.11, -0.9, 0.4, 0.0, 0.0},
    {10, 7, 1.88, -4.26, 1.5, -4.2, 0.0, 0.0},
    {10, 8, 1.44, -3.43, 0.9, -3.8, 0.0, 0.0},
    {10, 9, -2.38, -0.1, -2.6, 0.9, 0.0, 0.0},
    {10, 10, -3.84, -8.84, -3.9, -9.0, 0.0, 0.0},
    {11, 0, 2.96, 0.0, 3.0, 0.0, 0.0, 0.0},
    {11, 1, -1.36, -0.02, -1.4, 0.0, 0.0, 0.0},
    {11, 2, -2.51, 2.5, -2.5, 2.8, 0.0, 0.0},
    {11, 3, 2.31, -0.55, 2.4, -0.6, 0.0, 0.0},
    {11, 4, -0.85, -0.39, -0.6, 0.1, 0.0, 0.0},
    {11, 5, 0.28, 0.62, 0.0, 0.5, 0.0, 0.0},
    {11, 6, -0.66, -0.21, -0.6, -0.3, 0.0, 0.0},
    {11, 7, -0.07, -1.66, -0.1, -1.2, 0.0, 0.0},
    {11, 8, 1.44, -1.6, 1.1, -1.7, 0.0, 0.0},
    {11, 9, -0.59, -2.98, -1.0, -2.9, 0.0, 0.0},
    {11, 10, 0.18, -1.97, -0.1, -1.8, 0.0, 0.0},
    {11, 11, 3.09, -2.51, 2.6, -2.3, 0.0, 0.0},
    {12, 0, -2.0, 0.0, -2.0, 0.0, 0.0, 0.0},
    {12, 1, -0.13, -1.15, -0.1, -1.2, 0.0, 0.0},
    {12, 2, 0.43, 0.52, 0.4, 0.6, 0.0, 0.0},
    {12, 3, 1.28, 1.37, 1.2, 1.0, 0.0, 0.0},
    {12, 4, -1.14, -1.81, -1.2, -1.4, 0.0, 0.0},
    {12, 5, 0.71, 0.08, 0.6, 0.0, 0.0, 0.0},
    {12, 6, 0.31, 0.71, 0.5, 0.6, 0.0, 0.0},
    {12, 7, 0.49, -0.15, 0.5, -0.1, 0.0, 0.0},
    {12, 8, -0.26, 0.55, -0.1, 0.8, 0.0, 0.0},
    {12, 9, -0.47, 0.16, -0.5, 0.1, 0.0, 0.0},
    {12, 10, 0.09, -0.93, -0.2, -0.9, 0.0, 0.0},
    {12, 11, -1.13, -0.04, -1.2, 0.1, 0.0, 0.0},
    {12, 12, -0.33, 0.52, -0.7, 0.2, 0.0, 0.0},
    {13, 0, 0.08, 0.0, 0.2, 0.0, 0.0, 0.0},
    {13, 1, -0.93, -0.88, -0.9, -0.9, 0.0, 0.0},
    {13, 2, 0.53, 0.64, 0.6, 0.7, 0.0, 0.0},
    {13, 3, 0.72, 1.4, 0.7, 1.2, 0.0, 0.0},
    {13, 4, -0.3, -0.38, -0.2, -0.3, 0.0, 0.0},
    {13, 5, 0.75, -1.31, 0.5, -1.3, 0.0, 0.0},
    {13, 6, -0.01, -0.09, 0.1, -0.1, 0.0, 0.0},
    {13, 7, 0.76, 0.29, 0.7, 0.2, 0.0, 0.0},
    {13, 8, -0.05, -0.11, 0.0, -0.2, 0.0, 0.0},
    {13, 9, 0.37, 0.47, 0.3, 0.5, 0.0, 0.0},
    {13, 10, 0.13, 0.54, 0.2, 0.6, 0.0, 0.0},
    {13, 11, 0.45, -0.41, 0.4, -0.6, 0.0, 0.0},
    {13, 12, -0.46, -0.36, -0.5, -0.3, 0.0, 0.0},
    {13, 13, -0.4, -0.6, -0.4, -0.5, 0.0, 0.0},
};
constexpr int kIgrfRows = static_cast<int>(sizeof(kIgrf14) / sizeof(kIgrf14[0]));
static_assert(kIgrfRows == (kIgrfMaxDegree + 1) * (kIgrfMaxDegree + 2) / 2 - 1, "one row per (n, m)");

constexpr double kNanoTesla = 1e-9;  // [T / nT]

void require_year(const char* field, double year)
{
  detail::require_finite(field, year);
  if (year < kIgrfFirstYear || year > kIgrfLastYear) detail::fail(field, year, "must be in [2020, 2030]");
}

// Coefficient pair of a row at a decimal year.
void row_at(const IgrfRow& r, double year, double& g, double& h)
{
  if (year < 2025.0) {
    const double w = (year - 2020.0) / 5.0;
    g = r.g2020 + w * (r.g2025 - r.g2020);
    h = r.h2020 + w * (r.h2025 - r.h2020);
  } else {
    g = r.g2025 + r.g_sv * (year - 2025.0);
    h = r.h2025 + r.h_sv * (year - 2025.0);
  }
}

}  // namespace

double decimal_year(const J2000Days& d) { return 2000.0 + (d.value() + 0.5) / 365.25; }

MagneticDipole igrf14_dipole(double year)
{
  require_year("year", year);
  MagneticDipole d;
  double h10 = 0.0;
  row_at(kIgrf14[0], year, d.g10, h10);
  row_at(kIgrf14[1], year, d.g11, d.h11);
  d.g10 *= kNanoTesla;
  d.g11 *= kNanoTesla;
  d.h11 *= kNanoTesla;
  return d;
}

Vector3d dipole_field_E(const MagneticDipole& d, const Vector3d& r_E)
{
  const double r = r_E.norm();
  const Vector3d u = r_E / r;
  const Vector3d g(d.g11, d.h11, d.g10);
  const double k = kIgrfRadius / r;
  return (k * k * k) * (3.0 * g.dot(u) * u - g);
}

Igrf14::Igrf14(double year, int degree) : year_(year), degree_(degree)
{
  require_year("igrf.year", year);
  if (degree < 1 || degree > kIgrfMaxDegree) detail::fail("igrf.degree", degree, "must be in [1, 13]");
  for (const IgrfRow& r : kIgrf14) row_at(r, year, g_[r.n][r.m], h_[r.n][r.m]);
}

Vector3d Igrf14::field_E(const Vector3d& r_E) const
{
  constexpr int N = kIgrfMaxDegree + 1;
  const double r = r_E.norm();
  const double rho = std::hypot(r_E.x(), r_E.y());
  const double ct = r_E.z() / r;
  // On the axis the longitude is undefined; any one gives the same vector
  // there, and sin(theta) is kept off zero for the 1/sin(theta) of B_phi.
  const double st = std::max(rho / r, 1e-12);
  const double phi = std::atan2(r_E.y(), r_E.x());

  // Schmidt semi-normalised P_n^m(cos theta) and dP/dtheta by the standard recursions.
  double P[N][N] = {}, dP[N][N] = {};
  P[0][0] = 1.0;
  for (int n = 1; n <= degree_; ++n) {
    if (n == 1) {
      P[1][1] = st;
      dP[1][1] = ct;
    } else {
      const double k = std::sqrt((2.0 * n - 1.0) / (2.0 * n));
      P[n][n] = k * st * P[n - 1][n - 1];
      dP[n][n] = k * (ct * P[n - 1][n - 1] + st * dP[n - 1][n - 1]);
    }
    for (int m = 0; m < n; ++m) {
      const double a = 2.0 * n - 1.0;
      const double b = n >= 2 ? std::sqrt(double((n - 1) * (n - 1) - m * m)) : 0.0;
      const double c = std::sqrt(double(n * n - m * m));
      const double P2 = n >= 2 ? P[n - 2][m] : 0.0, dP2 = n >= 2 ? dP[n - 2][m] : 0.0;
      P[n][m] = (a * ct * P[n - 1][m] - b * P2) / c;
      dP[n][m] = (a * (ct * dP[n - 1][m] - st * P[n - 1][m]) - b * dP2) / c;
    }
  }

  double cm[N], sm[N];  // cos(m phi), sin(m phi)
  for (int m = 0; m <= degree_; ++m) {
    cm[m] = std::cos(m * phi);
    sm[m] = std::sin(m * phi);
  }

  double Br = 0.0, Bt = 0.0, Bp = 0.0;  // [nT] radial, southward (theta), eastward (phi)
  const double ar = kIgrfRadius / r;
  double arn = ar * ar;  // (a/r)^(n+2), starts at n = 0
  for (int n = 1; n <= degree_; ++n) {
    arn *= ar;
    double sr = 0.0, stt = 0.0, sp = 0.0;
    for (int m = 0; m <= n; ++m) {
      const double gc = g_[n][m] * cm[m] + h_[n][m] * sm[m];
      sr += gc * P[n][m];
      stt += gc * dP[n][m];
      sp += m * (g_[n][m] * sm[m] - h_[n][m] * cm[m]) * P[n][m];
    }
    Br += (n + 1) * arn * sr;
    Bt -= arn * stt;
    Bp += arn * sp;
  }
  Bp /= st;

  const double cp = std::cos(phi), sp = std::sin(phi);
  const Vector3d e_r(st * cp, st * sp, ct), e_t(ct * cp, ct * sp, -st), e_p(-sp, cp, 0.0);
  return kNanoTesla * (Br * e_r + Bt * e_t + Bp * e_p);
}

}  // namespace sim

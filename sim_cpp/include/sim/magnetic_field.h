// magnetic_field: the Earth's main magnetic field, IGRF-14 (IAGA Working
// Group V-MOD, 14th generation, released November 2024; coefficients as
// distributed by IAGA/NOAA NCEI), as a tilted dipole (degree 1) or as the
// spherical-harmonic model to degree 13, in the Earth-fixed frame E.
// Units: SI (tesla, metres; the coefficients are tabulated in nT).
// See docs/environment.md.
#ifndef SIM_MAGNETIC_FIELD_H
#define SIM_MAGNETIC_FIELD_H

#include <Eigen/Dense>

#include "sim/earth_time.h"

namespace sim {

constexpr double kIgrfRadius = 6371.2e3;  // [m] IGRF reference radius a
constexpr int kIgrfMaxDegree = 13;        // [-]
constexpr double kIgrfFirstYear = 2020.0;  // [yr] DGRF 2020 (first epoch tabulated here)
constexpr double kIgrfLastYear = 2030.0;   // [yr] end of the IGRF-14 secular-variation span

// Decimal year of an instant: 2000.0 + (d + 0.5) / 365.25, d days from
// J2000.0 (within 0.002 yr of the calendar fraction; the field changes by
// < 0.1 nT in that time).
double decimal_year(const J2000Days& d);

// Degree-1 Gauss coefficients (tilted dipole).
struct MagneticDipole {
  double g10 = 0.0;  // [T]
  double g11 = 0.0;  // [T]
  double h11 = 0.0;  // [T]
};

// IGRF-14 degree-1 coefficients at a decimal year in [2020, 2030]: linear
// between DGRF 2020 and IGRF 2025, then IGRF 2025 + secular variation
// (2025.0: g10 = -29350.0, g11 = -1410.3, h11 = 4545.5 nT; SV 12.6, 10.0,
// -21.5 nT/yr).  Throws std::invalid_argument ("year") outside.
MagneticDipole igrf14_dipole(double year);

// Field of the dipole at r_E (Earth-fixed position from the Earth's centre):
//   B_E = (a/|r|)^3 [3 (g.r_hat) r_hat - g],  g = (g11, h11, g10),  a = kIgrfRadius.
// |B| = B0 (a/r)^3 on the dipole's equator and 2 B0 (a/r)^3 at its poles,
// B0 = |g|.   [T]
Eigen::Vector3d dipole_field_E(const MagneticDipole& d, const Eigen::Vector3d& r_E);

// IGRF-14 to a chosen degree, coefficients fixed at one decimal year (set
// once, e.g. per run; the field changes by < 0.2 nT per day).  field_E()
// evaluates the geocentric spherical-harmonic synthesis with Schmidt
// semi-normalised associated Legendre functions; fixed-size storage, no heap.
class Igrf14 {
 public:
  // year in [kIgrfFirstYear, kIgrfLastYear], degree in [1, 13]; throws
  // std::invalid_argument naming "igrf.year" / "igrf.degree".
  explicit Igrf14(double year, int degree = kIgrfMaxDegree);

  // Main field at r_E (Earth-fixed, from the Earth's centre, |r_E| > 0).   [T]
  Eigen::Vector3d field_E(const Eigen::Vector3d& r_E) const;

  double year() const { return year_; }
  int degree() const { return degree_; }
  double g(int n, int m) const { return g_[n][m]; }  // [nT] at year()
  double h(int n, int m) const { return h_[n][m]; }  // [nT] at year()

 private:
  double year_;
  int degree_;
  double g_[kIgrfMaxDegree + 1][kIgrfMaxDegree + 1] = {};  // [nT]
  double h_[kIgrfMaxDegree + 1][kIgrfMaxDegree + 1] = {};  // [nT]
};

}  // namespace sim

#endif  // SIM_MAGNETIC_FIELD_H

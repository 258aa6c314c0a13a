// Sun position (docs/environment.md): the Almanac's low-precision series
// against Vallado's Example 5-1, Meeus' Example 25.a (an independent,
// more complete solar theory: agreement to the series' 0.01 deg), and the
// USNO instants of the 2000 equinox and solstice.
#include <cmath>

#include <gtest/gtest.h>

#include "sim/environment.h"
#include "sim/sun_almanac.h"

namespace {

using Eigen::Vector3d;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double ra_deg(const Vector3d& r)
{
  const double a = std::atan2(r.y(), r.x()) / kDeg;
  return a < 0.0 ? a + 360.0 : a;
}
double dec_deg(const Vector3d& r) { return std::asin(r.z() / r.norm()) / kDeg; }

// Vallado, Fundamentals of Astrodynamics and Applications (4th ed.),
// Example 5-1: 2006 Apr 2 0h UTC -> r = (0.9771945, 0.1924424, 0.0834308) AU
// (mean equator and equinox of date), printed to 1e-7 AU.  The full-precision
// evaluation of the same printed formula differs from it by 1.1e-6 AU in y
// (0.23 arcsec in direction, 3.8e-7 AU in distance), presumably because the
// example carries its intermediate angles rounded; hence 1.5e-6 AU per
// component and 1e-4 deg in direction, both far inside the series' 0.01 deg.
TEST(SunAlmanac, ValladoExample5_1)
{
  const Vector3d r = sim::sun_position_almanac(sim::days_since_j2000(sim::UtcEpoch{2006, 4, 2, 0})) / sim::kAU;
  const Vector3d printed(0.9771945, 0.1924424, 0.0834308);
  EXPECT_NEAR(r.x(), printed.x(), 1.5e-6);
  EXPECT_NEAR(r.y(), printed.y(), 1.5e-6);
  EXPECT_NEAR(r.z(), printed.z(), 1.5e-6);
  EXPECT_LT(std::acos(r.normalized().dot(printed.normalized())) / kDeg, 1e-4);
  EXPECT_NEAR(r.norm(), printed.norm(), 1e-6);
}

// Meeus, Astronomical Algorithms (2nd ed.), Example 25.a: 1992 Oct 13 0h TD,
// apparent alpha = 198.38083 deg, delta = -7.78507 deg, R = 0.99766 AU, from
// Meeus' own (different) solar theory with nutation and aberration.  The
// series is quoted to 0.01 deg: that is the tolerance.
TEST(SunAlmanac, MeeusExample25a)
{
  const Vector3d r = sim::sun_position_almanac(sim::days_since_j2000(sim::UtcEpoch{1992, 10, 13, 0}));
  EXPECT_NEAR(ra_deg(r), 198.38083, 0.01);
  EXPECT_NEAR(dec_deg(r), -7.78507, 0.01);
  EXPECT_NEAR(r.norm() / sim::kAU, 0.99766, 1e-5);
}

// USNO (Data Services, Earth's Seasons): 2000 March equinox 2000-03-20 07:35 UTC,
// June solstice 2000-06-21 01:48 UTC, to the minute.  At the equinox the Sun
// crosses the equator (declination 0, RA 0); at the solstice RA = 90 deg.
// Per minute of timing the Sun moves 0.0068 deg in declination at the
// equinox and 0.0007 deg in RA at the solstice, so 0.012 deg checks the series.
TEST(SunAlmanac, EquinoxAndSolstice2000)
{
  const Vector3d eq = sim::sun_position_almanac(sim::days_since_j2000(sim::UtcEpoch{2000, 3, 20, 7, 35}));
  EXPECT_NEAR(dec_deg(eq), 0.0, 0.012);
  EXPECT_NEAR(std::remainder(ra_deg(eq), 360.0), 0.0, 0.012 / std::cos(23.44 * kDeg));
  const Vector3d so = sim::sun_position_almanac(sim::days_since_j2000(sim::UtcEpoch{2000, 6, 21, 1, 48}));
  EXPECT_NEAR(ra_deg(so), 90.0, 0.012);
  EXPECT_NEAR(dec_deg(so), 23.439, 0.012);  // the obliquity of date
  // Distance bounds over a year: perihelion ~0.98329 AU (Jan), aphelion ~1.01671 AU (Jul).
  double rmin = 2.0, rmax = 0.0;
  for (int k = 0; k < 366; ++k) {
    const double r = sim::sun_position_almanac(sim::days_since_j2000(sim::UtcEpoch{2000, 1, 1, 0}, k * 86400.0)).norm() / sim::kAU;
    rmin = std::min(rmin, r);
    rmax = std::max(rmax, r);
  }
  EXPECT_NEAR(rmin, 1.0 - 0.01671, 2e-4);
  EXPECT_NEAR(rmax, 1.0 + 0.01671, 2e-4);
}

}  // namespace

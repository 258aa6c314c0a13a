// Earth time and rotation (docs/environment.md): calendar -> Julian date
// against Meeus' and Vallado's worked examples and an independent
// day-count formula, the split J2000 day count, GMST (IAU 1982) against
// IAU SOFA's published check value and Vallado's Example 3-5, the Earth
// rotation angle against SOFA's check value and its J2000.0 definition.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sim/earth_time.h"
#include "field_check.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kTwoPi = 6.283185307179586477;
constexpr double kDeg = kTwoPi / 360.0;

// Meeus, Astronomical Algorithms (2nd ed.), Chapter 7 examples and table;
// Vallado, Fundamentals of Astrodynamics and Applications, Example 3-4.
TEST(JulianDate, PublishedExamples)
{
  EXPECT_EQ(sim::julian_date(sim::UtcEpoch{2000, 1, 1, 12}), 2451545.0);
  EXPECT_EQ(sim::julian_date(sim::UtcEpoch{1999, 1, 1, 0}), 2451179.5);
  EXPECT_EQ(sim::julian_date(sim::UtcEpoch{1987, 1, 27, 0}), 2446822.5);
  EXPECT_EQ(sim::julian_date(sim::UtcEpoch{1987, 6, 19, 12}), 2446966.0);
  EXPECT_EQ(sim::julian_date(sim::UtcEpoch{1988, 1, 27, 0}), 2447187.5);
  EXPECT_EQ(sim::julian_date(sim::UtcEpoch{1988, 6, 19, 12}), 2447332.0);
  EXPECT_EQ(sim::julian_date(sim::UtcEpoch{1900, 1, 1, 0}), 2415020.5);
  // 1957 Oct 4.81 (Sputnik 1): 0.81 d = 19 h 26 min 24 s.
  EXPECT_NEAR(sim::julian_date(sim::UtcEpoch{1957, 10, 4, 19, 26, 24.0}), 2436116.31, 1e-8);
  // Vallado Ex. 3-4: 1996 Oct 26 14:20 UT -> 2450383.09722222 (printed to 1e-8 d).
  EXPECT_NEAR(sim::julian_date(sim::UtcEpoch{1996, 10, 26, 14, 20, 0.0}), 2450383.09722222, 1e-8);
}

// An independent day count: Vallado's Algorithm 14 (valid 1900 Mar - 2100 Feb),
// JD(0 h) = 367 y - INT(7 (y + INT((m + 9)/12)) / 4) + INT(275 m / 9) + d + 1721013.5,
// on the first, 28th and last day of every month, and consecutive days differ by one.
TEST(JulianDate, AgreesWithAnIndependentDayCount)
{
  static const int kLast[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  int n = 0;
  for (int y = 1901; y <= 2099; ++y) {
    for (int m = 1; m <= 12; ++m) {
      const int last = (m == 2 && y % 4 == 0) ? 29 : kLast[m - 1];  // 1901..2099: every 4th year
      for (int d : {1, 28, last}) {
        const double jd0 = 367.0 * y - std::floor(7.0 * (y + std::floor((m + 9) / 12.0)) / 4.0) +
                           std::floor(275.0 * m / 9.0) + d + 1721013.5;
        ASSERT_EQ(sim::julian_date(sim::UtcEpoch{y, m, d, 0}), jd0) << y << "-" << m << "-" << d;
        ++n;
      }
      // The day after the month's last day is the next month's first.
      const int ny = m == 12 ? y + 1 : y, nm = m == 12 ? 1 : m + 1;
      if (ny <= 2099) {
        ASSERT_EQ(sim::julian_day_number(ny, nm, 1) - sim::julian_day_number(y, m, last), 1);
      }
    }
  }
  EXPECT_EQ(n, 199 * 12 * 3);
}

TEST(J2000Days, SplitKeepsTheDayFraction)
{
  const sim::J2000Days j0 = sim::days_since_j2000(sim::UtcEpoch{2000, 1, 1, 12});
  EXPECT_EQ(j0.whole, 0.0);
  EXPECT_EQ(j0.frac, 0.0);
  // 2006-01-01 00:00 = MJD 53736.0 = JD 2453736.5: 2191.5 days.
  const sim::J2000Days j1 = sim::days_since_j2000(sim::UtcEpoch{2006, 1, 1, 0});
  EXPECT_EQ(j1.whole, 2191.0);
  EXPECT_EQ(j1.frac, 0.5);
  // Elapsed seconds carry into days: 2006-01-01 00:00 + 10 d 6 h = 2006-01-11 06:00.
  const sim::J2000Days j2 = sim::days_since_j2000(sim::UtcEpoch{2006, 1, 1, 0}, 10.25 * 86400.0);
  EXPECT_EQ(j2.whole, 2201.0);
  EXPECT_EQ(j2.frac, 0.75);
  // Negative offsets, before J2000.0: 1999-12-31 06:00 is -1.25 d.
  const sim::J2000Days j3 = sim::days_since_j2000(sim::UtcEpoch{2000, 1, 1, 12}, -1.25 * 86400.0);
  EXPECT_EQ(j3.whole, -2.0);
  EXPECT_EQ(j3.frac, 0.75);
  // Sub-millisecond steps survive 26 years from J2000.0 (the single double JD would not).
  const sim::J2000Days a = sim::days_since_j2000(sim::UtcEpoch{2026, 12, 5, 8, 0, 0.0});
  const sim::J2000Days b = sim::days_since_j2000(sim::UtcEpoch{2026, 12, 5, 8, 0, 0.0}, 1e-4);
  EXPECT_EQ(b.whole, a.whole);
  EXPECT_NEAR((b.frac - a.frac) * 86400.0, 1e-4, 2e-11);  // two ulps of frac
}

// IAU SOFA test suite (t_sofa_c.c): iauGmst82(2400000.5, 53736.0) = 1.754174981860675096 rad, to 1e-12.
TEST(Gmst, SofaCheckValue)
{
  const double g = sim::gmst_iau1982(sim::days_since_j2000(sim::UtcEpoch{2006, 1, 1, 0}));
  EXPECT_NEAR(g, 1.754174981860675096, 1e-12);
}

// Vallado Example 3-5: 1992 Aug 20 12:14 UT1 -> GMST = 152.578787810 deg
// (4th ed.; the 3rd ed. prints 152.578787886 deg).  Printed to 1e-9 deg; the
// two editions differ by 7.6e-8 deg, so 1e-7 deg holds whichever is right.
TEST(Gmst, ValladoExample3_5)
{
  const double g = sim::gmst_iau1982(sim::days_since_j2000(sim::UtcEpoch{1992, 8, 20, 12, 14, 0.0}));
  EXPECT_NEAR(g / kDeg, 152.578787810, 1e-7);
  // Rate: the mean sidereal rate, consistent with kOmegaEarth to its printed digits.
  const sim::UtcEpoch e = sim::UtcEpoch{2026, 12, 5, 8};
  const double g0 = sim::gmst_iau1982(sim::days_since_j2000(e, 0.0));
  const double g1 = sim::gmst_iau1982(sim::days_since_j2000(e, 1000.0));
  EXPECT_NEAR((g1 - g0) / 1000.0, sim::kOmegaEarth, 2e-11);
}

// IAU SOFA: iauEra00(2400000.5, 54388.0) = 0.4022837240028158102 rad, to 1e-12;
// MJD 54388.0 = 2007-10-15 00:00.  At J2000.0 the definition gives 0.7790572732640 turns.
TEST(EarthRotationAngle, SofaCheckValueAndDefinition)
{
  EXPECT_NEAR(sim::earth_rotation_angle(sim::days_since_j2000(sim::UtcEpoch{2007, 10, 15, 0})),
              0.4022837240028158102, 1e-12);
  EXPECT_NEAR(sim::earth_rotation_angle(sim::days_since_j2000(sim::UtcEpoch{2000, 1, 1, 12})),
              kTwoPi * 0.7790572732640, 1e-15);
  // At J2000.0 GMST (IAU 1982) and the ERA agree: 67310.54841 s / 86400 s = 0.77905727326... turns.
  EXPECT_NEAR(sim::gmst_iau1982(sim::days_since_j2000(sim::UtcEpoch{2000, 1, 1, 12})),
              kTwoPi * 67310.54841 / 86400.0, 1e-15);
}

TEST(EarthRotation, DcmIsTheRotationAboutZ)
{
  for (double th : {0.0, 0.3, 2.0, -1.0, 5.9}) {
    const Matrix3d E = sim::dcm_EN(th);
    EXPECT_NEAR((E * E.transpose() - Matrix3d::Identity()).norm(), 0.0, 1e-15);
    EXPECT_NEAR(E.determinant(), 1.0, 1e-15);
    // The Greenwich meridian, at angle th from N x, is E x; the pole stays.
    EXPECT_NEAR((E * Vector3d(std::cos(th), std::sin(th), 0.0) - Vector3d::UnitX()).norm(), 0.0, 1e-15);
    EXPECT_EQ(E * Vector3d::UnitZ(), Vector3d::UnitZ());
  }
}

TEST(UtcEpoch, RejectedFieldsAreNamed)
{
  EXPECT_NO_THROW(sim::validate(sim::UtcEpoch{2000, 2, 29, 0}));  // 2000 is a leap year
  EXPECT_NO_THROW(sim::validate(sim::UtcEpoch{2016, 12, 31, 23, 59, 60.5}));  // leap second
  const auto expect_field = [](const sim::UtcEpoch& e, const char* field) {
    simtest::expect_rejects_field([&] { sim::validate(e, "epoch"); }, field);
  };
  expect_field(sim::UtcEpoch{1900, 2, 29, 0}, "epoch.day");  // 1900 is not
  expect_field(sim::UtcEpoch{2023, 4, 31, 0}, "epoch.day");
  expect_field(sim::UtcEpoch{2023, 13, 1, 0}, "epoch.month");
  expect_field(sim::UtcEpoch{1899, 12, 31, 0}, "epoch.year");
  expect_field(sim::UtcEpoch{2023, 1, 1, 24}, "epoch.hour");
  expect_field(sim::UtcEpoch{2023, 1, 1, 0, 60}, "epoch.minute");
  expect_field(sim::UtcEpoch{2023, 1, 1, 0, 0, 61.0}, "epoch.second");
  expect_field(sim::UtcEpoch{2023, 1, 1, 0, 0, NAN}, "epoch.second");
  EXPECT_THROW(sim::days_since_j2000(sim::UtcEpoch{2023, 1, 1, 0}, NAN), std::invalid_argument);
}

}  // namespace

// earth_time: calendar epoch -> days from J2000.0, and the Earth's rotation
// angle about its axis (GMST, IAU 1982; Earth rotation angle, IERS 2003)
// with the inertial-to-Earth-fixed rotation built from it.  Units: SI
// except where a field says days.  Frames: N inertial, mean equator and
// equinox of date (z along the mean rotation axis); E Earth-fixed (x through
// the Greenwich meridian, z = N z).  See docs/environment.md.
//
// Time scales.  One clock only: the epoch is read as UTC and used for UT1
// (Earth rotation) and for TT/TDB (the Sun series) alike:
//   * UT1 - UTC (|.| <= 0.9 s, kept so by leap seconds) is neglected: the
//     rotation angle errs by up to 0.9 s x 15.04 "/s = 13.5 arcsec about z
//     (<= 420 m along the equator at the Earth's surface).
//   * TT - UTC (69.184 s since 2017) is neglected in the Sun series: the
//     Sun moves 0.0416 "/s along the ecliptic, i.e. <= 2.9 arcsec, well
//     inside the series' own 0.01 deg (36 arcsec).
//   * A leap second (second in [60, 61)) is counted as the first second of
//     the next day: days are 86,400 s long here.
#ifndef SIM_EARTH_TIME_H
#define SIM_EARTH_TIME_H

#include <Eigen/Dense>

namespace sim {

// Earth's nominal mean angular velocity (IERS Conventions 2010, Table 1.1;
// also WGS 84) about N z = E z.
constexpr double kOmegaEarth = 7.292115e-5;  // [rad/s]

// A UTC calendar instant, proleptic Gregorian calendar.
struct UtcEpoch {
  int year = 2000;      // [-] 1900 .. 2100 (the range the series here are quoted for)
  int month = 1;        // [-] 1 .. 12
  int day = 1;          // [-] 1 .. days in the month (leap years by the Gregorian rule)
  int hour = 12;        // [h] 0 .. 23
  int minute = 0;       // [min] 0 .. 59
  double second = 0.0;  // [s] [0, 61) (60.x: a leap second, see above)
};

// Throws std::invalid_argument naming `name.field` and the value.
void validate(const UtcEpoch& e, const char* name = "epoch");

// Days from J2000.0 (2000-01-01 12:00:00, read as UTC = UT1 = TT), kept in two
// parts so that the day fraction keeps full precision whatever the date:
// whole is an integer number of days, frac in [0, 1).
struct J2000Days {
  double whole = 0.0;  // [d] integral
  double frac = 0.0;   // [d] in [0, 1)
  double value() const { return whole + frac; }  // [d]
};

// Julian day number of a Gregorian date (the JD at 12:00 of that day),
// Fliegel & Van Flandern (1968), integer arithmetic.
long julian_day_number(int year, int month, int day);

// Julian date of the epoch [d] (one double: resolution ~40 us near 2.45e6 d;
// use days_since_j2000 where the day fraction matters).
double julian_date(const UtcEpoch& e);

// Epoch + t_s seconds as days from J2000.0 (t_s may be negative).  Validates e.
J2000Days days_since_j2000(const UtcEpoch& e, double t_s = 0.0);

// Greenwich mean sidereal time, IAU 1982 (Aoki et al. 1982):
//   GMST [s] = 67310.54841 + (876600 h + 8640184.812866 s) T + 0.093104 s T^2 - 6.2e-6 s T^3,
//   T = d / 36525 Julian centuries of UT1 from J2000.0.   [rad] in [0, 2 pi)
double gmst_iau1982(const J2000Days& d_ut1);

// Earth rotation angle, IERS Conventions 2003 (Capitaine et al. 2000):
//   ERA = 2 pi (0.7790572732640 + 1.00273781191135448 d).   [rad] in [0, 2 pi)
double earth_rotation_angle(const J2000Days& d_ut1);

// [EN] = R3(theta): components in E of a vector given in N, for the rotation
// angle theta about z (GMST for N = mean equator and equinox of date).
Eigen::Matrix3d dcm_EN(double theta);

}  // namespace sim

#endif  // SIM_EARTH_TIME_H

// earth_time: see sim/earth_time.h and docs/environment.md.
#include "sim/earth_time.h"

#include <cmath>
#include <string>

#include "sim/units.h"
#include "validate_util.h"

namespace sim {

namespace {

constexpr double kSecPerDay = 86400.0;
constexpr double kDaysPerCentury = 36525.0;
constexpr long kJdnJ2000 = 2451545;  // Julian day number of 2000-01-01 (JD 2451545.0 at 12:00)

bool leap_year(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int days_in_month(int y, int m)
{
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return (m == 2 && leap_year(y)) ? 29 : kDays[m - 1];
}

double fraction_of(double x) { return x - std::floor(x); }

}  // namespace

void validate(const UtcEpoch& e, const char* name)
{
  const std::string n(name);
  if (e.year < 1900 || e.year > 2100) detail::fail(n + ".year", e.year, "must be in [1900, 2100]");
  if (e.month < 1 || e.month > 12) detail::fail(n + ".month", e.month, "must be in [1, 12]");
  if (e.day < 1 || e.day > days_in_month(e.year, e.month))
    detail::fail(n + ".day", e.day, "must be in [1, days in the month]");
  if (e.hour < 0 || e.hour > 23) detail::fail(n + ".hour", e.hour, "must be in [0, 23]");
  if (e.minute < 0 || e.minute > 59) detail::fail(n + ".minute", e.minute, "must be in [0, 59]");
  if (!(e.second >= 0.0 && e.second < 61.0)) detail::fail(n + ".second", e.second, "must be in [0, 61)");
}

long julian_day_number(int year, int month, int day)
{
  const long y = year, m = month, d = day;
  const long a = (m - 14) / 12;  // -1 for January and February, else 0 (truncating division)
  return (1461 * (y + 4800 + a)) / 4 + (367 * (m - 2 - 12 * a)) / 12 -
         (3 * ((y + 4900 + a) / 100)) / 4 + d - 32075;
}

double julian_date(const UtcEpoch& e)
{
  validate(e);
  const double sod = 3600.0 * e.hour + 60.0 * e.minute + e.second;  // seconds of day
  return static_cast<double>(julian_day_number(e.year, e.month, e.day)) - 0.5 + sod / kSecPerDay;
}

J2000Days days_since_j2000(const UtcEpoch& e, double t_s)
{
  validate(e);
  detail::require_finite("t_s", t_s);
  // Seconds from the epoch's own noon, then whole days split off exactly.
  const double s = 3600.0 * (e.hour - 12) + 60.0 * e.minute + e.second + t_s;
  const double k = std::floor(s / kSecPerDay);
  J2000Days d;
  d.whole = static_cast<double>(julian_day_number(e.year, e.month, e.day) - kJdnJ2000) + k;
  d.frac = (s - k * kSecPerDay) / kSecPerDay;
  if (d.frac >= 1.0) {  // s/86400 rounded up to an integer
    d.frac -= 1.0;
    d.whole += 1.0;
  }
  return d;
}

double gmst_iau1982(const J2000Days& d)
{
  // 876600 h T = 86400 s x d: whole days add whole turns, so only the day
  // fraction of that term enters (as in IAU SOFA's iauGmst82).
  const double T = d.value() / kDaysPerCentury;
  const double s = 67310.54841 + T * (8640184.812866 + T * (0.093104 - 6.2e-6 * T));
  return 2.0 * kPi * fraction_of(s / kSecPerDay + d.frac);
}

double earth_rotation_angle(const J2000Days& d)
{
  // 1.00273781191135448 d = d + 0.00273781191135448 d; whole days are whole turns.
  const double turns = fraction_of(0.7790572732640 + 0.00273781191135448 * d.value() + d.frac);
  return 2.0 * kPi * turns;
}

Eigen::Matrix3d dcm_EN(double theta)
{
  const double c = std::cos(theta), s = std::sin(theta);
  Eigen::Matrix3d m;
  m << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
  return m;
}

}  // namespace sim

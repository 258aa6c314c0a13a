// earth_context: see sim/earth_context.h.
#include "sim/earth_context.h"

#include <cmath>
#include <string>

#include "sim/magnetic_field.h"
#include "sim/sun_almanac.h"
#include "validate_util.h"

namespace sim {

void validate(const EarthContextParams& p, const char* name)
{
  const std::string n(name);
  validate(p.epoch, (n + ".epoch").c_str());
  detail::require_non_negative(n + ".shadow_radius", p.shadow_radius);
}

EarthContext::EarthContext(const EarthContextParams& p) : p_(p)
{
  validate(p_);
  d0_ = days_since_j2000(p_.epoch, 0.0);
}

J2000Days EarthContext::days(double t_s) const
{
  // frac + t/86400 split into whole days again (floor keeps frac in [0, 1)).
  const double f = d0_.frac + t_s / 86400.0;
  const double k = std::floor(f);
  J2000Days d;
  d.whole = d0_.whole + k;
  d.frac = f - k;
  if (d.frac >= 1.0) {
    d.frac -= 1.0;
    d.whole += 1.0;
  }
  return d;
}

double EarthContext::gmst(double t_s) const { return gmst_iau1982(days(t_s)); }

Eigen::Matrix3d EarthContext::dcm_EN(double t_s) const { return sim::dcm_EN(gmst(t_s)); }

Eigen::Vector3d EarthContext::sun_position_N(double t_s) const { return sun_position_almanac(days(t_s)); }

double EarthContext::decimal_year() const { return sim::decimal_year(d0_); }

}  // namespace sim

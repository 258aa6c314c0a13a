// magnetorquer: see sim/magnetorquer.h and docs/environment.md.
#include "sim/magnetorquer.h"

#include <cmath>
#include <string>

#include "validate_util.h"

namespace sim {

namespace {
constexpr double kUnitTol = 1e-9;  // [-] on |axis| - 1
}

void validate(const MagnetorquerParams& p, const char* name)
{
  const std::string n(name);
  detail::require_finite(n + ".axis_B", p.axis_B);
  if (!(std::abs(p.axis_B.norm() - 1.0) <= kUnitTol)) detail::fail_vec(n + ".axis_B", p.axis_B, "must be a unit vector");
  detail::require_positive(n + ".m_max", p.m_max);
  detail::require_non_negative(n + ".m_remanent", p.m_remanent);
  if (!(p.m_remanent < p.m_max)) detail::fail(n + ".m_remanent", p.m_remanent, "must be < m_max");
  detail::require_non_negative(n + ".power_max", p.power_max);
}

Magnetorquer::Magnetorquer(const MagnetorquerParams& p, const char* name) : p_(p) { validate(p_, name); }

void Magnetorquer::command(double m_cmd)
{
  if (!std::isfinite(m_cmd) || m_cmd == 0.0) {
    m_ = p_.m_remanent * last_sign_;
    power_ = 0.0;
    saturated_ = false;
    return;
  }
  last_sign_ = m_cmd > 0.0 ? 1.0 : -1.0;
  saturated_ = std::abs(m_cmd) > p_.m_max;
  m_ = saturated_ ? last_sign_ * p_.m_max : m_cmd;
  const double f = m_ / p_.m_max;
  power_ = p_.power_max * f * f;
}

}  // namespace sim

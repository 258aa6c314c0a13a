// propellant: see sim/propellant.h.  docs/dynamics.md §2, §5.6.
#include "sim/propellant.h"

#include <algorithm>
#include <cmath>

#include "validate_util.h"

namespace sim {

using Eigen::Matrix3d;
using Eigen::Vector3d;

void validate(const TankParams& p, const std::string& name)
{
  detail::require_finite(name + ".r_TB_B", p.r_TB_B);
  detail::require_non_negative(name + ".m_p0", p.m_p0);
  detail::require_non_negative(name + ".R_T", p.R_T);
}

Matrix3d tank_inertia(const TankParams& p, double m_p)
{
  return (0.4 * m_p * p.R_T * p.R_T) * Matrix3d::Identity();
}

HubParams merge_tanks_into_hub(const HubParams& hub, const TankParams* tanks, int num_tanks,
                               const TankArray& m_p)
{
  if (num_tanks == 0) return hub;
  // Inertia about B of all parts, then shifted to the merged CoM (§2).
  double m = hub.m_h;
  Vector3d first_moment = hub.m_h * hub.r_BcB_B;
  Matrix3d I_B = hub.I_hBc_B + parallel_axis(hub.m_h, hub.r_BcB_B);
  for (int k = 0; k < num_tanks; ++k) {
    const TankParams& t = tanks[k];
    const double mk = std::max(m_p[static_cast<size_t>(k)], 0.0);
    m += mk;
    first_moment += mk * t.r_TB_B;
    I_B += tank_inertia(t, mk) + parallel_axis(mk, t.r_TB_B);
  }
  HubParams out;
  out.m_h = m;
  out.r_BcB_B = first_moment / m;
  out.I_hBc_B = I_B - parallel_axis(m, out.r_BcB_B);
  return out;
}

TankMerger::TankMerger(const HubParams& hub, const TankParams* tanks, int num_tanks)
    : hub_(hub), first_moment_h_(hub.m_h * hub.r_BcB_B), I_h_B_(hub.I_hBc_B + parallel_axis(hub.m_h, hub.r_BcB_B)),
      n_(num_tanks)
{
  for (int k = 0; k < num_tanks; ++k) {
    const auto uk = static_cast<size_t>(k);
    const TankParams& t = tanks[k];
    r_[uk] = t.r_TB_B;
    I_per_kg_B_[uk] = tank_inertia(t, 1.0) + parallel_axis(1.0, t.r_TB_B);
  }
}

HubParams TankMerger::merge(const TankArray& m_p) const
{
  if (n_ == 0) return hub_;
  double m = hub_.m_h;
  Vector3d first_moment = first_moment_h_;
  Matrix3d I_B = I_h_B_;
  for (int k = 0; k < n_; ++k) {
    const auto uk = static_cast<size_t>(k);
    const double mk = std::max(m_p[uk], 0.0);
    m += mk;
    first_moment += mk * r_[uk];
    I_B += mk * I_per_kg_B_[uk];
  }
  HubParams out;
  out.m_h = m;
  out.r_BcB_B = first_moment / m;
  out.I_hBc_B = I_B - parallel_axis(m, out.r_BcB_B);
  return out;
}

}  // namespace sim

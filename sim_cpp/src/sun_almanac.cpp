// sun_almanac: see sim/sun_almanac.h and docs/environment.md.
#include "sim/sun_almanac.h"

#include <cmath>

#include "sim/environment.h"  // kAU
#include "sim/units.h"

namespace sim {

Eigen::Vector3d sun_position_almanac(const J2000Days& d)
{
  const double T = d.value() / 36525.0;
  // Reduce the linear terms before converting: T ~ 0.3 gives ~1e4 deg.
  const double lambda_M = std::fmod(280.460 + 36000.771 * T, 360.0) * kRadPerDeg;
  const double M = std::fmod(357.5291092 + 35999.05034 * T, 360.0) * kRadPerDeg;
  const double lambda =
      lambda_M + (1.914666471 * std::sin(M) + 0.019994643 * std::sin(2.0 * M)) * kRadPerDeg;
  const double r_au = 1.000140612 - 0.016708617 * std::cos(M) - 0.000139589 * std::cos(2.0 * M);
  const double eps = (23.439291 - 0.0130042 * T) * kRadPerDeg;
  const double r = r_au * kAU;
  const double sl = std::sin(lambda);
  return Eigen::Vector3d(r * std::cos(lambda), r * std::cos(eps) * sl, r * std::sin(eps) * sl);
}

}  // namespace sim

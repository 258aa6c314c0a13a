// sun_almanac: the Sun's geocentric position from the Astronomical
// Almanac's low-precision formula (quoted there to 0.01 deg for 1950-2050),
// in the coefficients of Vallado, Fundamentals of Astrodynamics and
// Applications, Algorithm 29.  Frame N: mean equator and equinox of date.
// Units: SI.  See docs/environment.md.
#ifndef SIM_SUN_ALMANAC_H
#define SIM_SUN_ALMANAC_H

#include <Eigen/Dense>

#include "sim/earth_time.h"

namespace sim {

// With T = d / 36525 (d from J2000.0, UTC read as UT1 and TDB; angles in deg):
//   lambda_M = 280.460 + 36000.771 T                  mean longitude
//   M        = 357.5291092 + 35999.05034 T            mean anomaly
//   lambda   = lambda_M + 1.914666471 sin M + 0.019994643 sin 2M
//   r        = 1.000140612 - 0.016708617 cos M - 0.000139589 cos 2M   [AU]
//   eps      = 23.439291 - 0.0130042 T                obliquity of the ecliptic
//   r_N      = r kAU (cos lambda, cos eps sin lambda, sin eps sin lambda)   [m]
Eigen::Vector3d sun_position_almanac(const J2000Days& d);

}  // namespace sim

#endif  // SIM_SUN_ALMANAC_H

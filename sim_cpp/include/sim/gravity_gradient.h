// gravity_gradient: the gravity-gradient torque of a spherical (point-mass)
// central body on a rigid body, to first order in (body size / distance).
// Frames: B body.  Units: SI.  See docs/environment.md.
#ifndef SIM_GRAVITY_GRADIENT_H
#define SIM_GRAVITY_GRADIENT_H

#include <cmath>

#include <Eigen/Dense>

namespace sim {

// L_B = 3 mu / |R|^5  R_B x (I_B R_B)   [N m], about the mass centre, where
//   mu   [m^3/s^2] central body's gravity parameter (>= 0; 0 gives 0)
//   R_B  [m]       position of the mass centre relative to the central
//                  body, B components (non-zero; the sign of R does not matter)
//   I_B  [kg m^2]  inertia about the mass centre, B components (symmetric)
// Zero when R lies along a principal axis.  Neglected: the central body's
// oblateness (J2 changes the torque by O(J2 (R_E/R)^2) ~ 1e-3 relative in
// LEO) and terms of relative order (body size / |R|).
inline Eigen::Vector3d gravity_gradient_torque(double mu, const Eigen::Vector3d& R_B,
                                               const Eigen::Matrix3d& I_B)
{
  const double r2 = R_B.squaredNorm();
  const double r = std::sqrt(r2);
  return (3.0 * mu / (r2 * r2 * r)) * R_B.cross(I_B * R_B);
}

}  // namespace sim

#endif  // SIM_GRAVITY_GRADIENT_H

// attitude: MRP kinematics and small 3-vector helpers (spec plant-dynamics §0, §7.4).
// Named conversions only; Eigen's rotation helpers are not used because their
// direction convention differs from dcm_BN (v_B = dcm_BN * v_N).
#ifndef SIM_ATTITUDE_H
#define SIM_ATTITUDE_H

#include <cmath>

#include <Eigen/Dense>

namespace sim {

// [a~] with [a~] b = a x b.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a)
{
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(),
       a.z(), 0.0, -a.x(),
       -a.y(), a.x(), 0.0;
  return m;
}

// [BN](sigma_BN) = I + (8[s~]^2 - 4(1 - s^2)[s~]) / (1 + s^2)^2     (§7.4)
inline Eigen::Matrix3d dcm_BN_from_sigma(const Eigen::Vector3d& sigma_BN)
{
  const double s2 = sigma_BN.squaredNorm();
  const Eigen::Matrix3d s_tilde = skew(sigma_BN);
  const double den = (1.0 + s2) * (1.0 + s2);
  return Eigen::Matrix3d::Identity() +
         (8.0 * s_tilde * s_tilde - 4.0 * (1.0 - s2) * s_tilde) / den;
}

// [B(sigma)] = (1 - s^2) I + 2[s~] + 2 s s^T, so that sigma_dot = 1/4 [B] omega_BN_B.
inline Eigen::Matrix3d mrp_B_matrix(const Eigen::Vector3d& sigma_BN)
{
  const double s2 = sigma_BN.squaredNorm();
  return (1.0 - s2) * Eigen::Matrix3d::Identity() + 2.0 * skew(sigma_BN) +
         2.0 * sigma_BN * sigma_BN.transpose();
}

inline Eigen::Vector3d sigma_dot_from_omega(const Eigen::Vector3d& sigma_BN,
                                            const Eigen::Vector3d& omega_BN_B)
{
  return 0.25 * (mrp_B_matrix(sigma_BN) * omega_BN_B);
}

// Shadow set -sigma / |sigma|^2: the same attitude, other branch.
inline Eigen::Vector3d mrp_shadow(const Eigen::Vector3d& sigma_BN)
{
  return -sigma_BN / sigma_BN.squaredNorm();
}

// Rotation matrix exp([delta~]) (Rodrigues): rotates vectors by |delta| about delta.
inline Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& delta)
{
  const double angle = delta.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d k = skew(delta / angle);
  return Eigen::Matrix3d::Identity() + std::sin(angle) * k + (1.0 - std::cos(angle)) * k * k;
}

}  // namespace sim

#endif  // SIM_ATTITUDE_H

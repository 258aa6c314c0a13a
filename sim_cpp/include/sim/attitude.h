// attitude: MRP kinematics and small 3-vector helpers (docs/dynamics.md §0, §7.4).
// Named conversions only; Eigen's rotation helpers are not used because their
// direction convention differs from dcm_BN (v_B = dcm_BN * v_N).
#ifndef SIM_ATTITUDE_H
#define SIM_ATTITUDE_H

#include <algorithm>
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
// written out with [s~]^2 = s s^T - s^2 I (a hot path of the plant's derivative).
inline Eigen::Matrix3d dcm_BN_from_sigma(const Eigen::Vector3d& sigma_BN)
{
  const double x = sigma_BN.x(), y = sigma_BN.y(), z = sigma_BN.z();
  const double s2 = x * x + y * y + z * z;
  const double inv_den = 1.0 / ((1.0 + s2) * (1.0 + s2));
  const double a = 8.0 * inv_den;               // on [s~]^2
  const double b = 4.0 * (1.0 - s2) * inv_den;  // on -[s~]
  const double axy = a * x * y, axz = a * x * z, ayz = a * y * z;
  Eigen::Matrix3d m;
  m << 1.0 + a * (x * x - s2), axy + b * z, axz - b * y,
       axy - b * z, 1.0 + a * (y * y - s2), ayz + b * x,
       axz + b * y, ayz - b * x, 1.0 + a * (z * z - s2);
  return m;
}

// [B(sigma)] = (1 - s^2) I + 2[s~] + 2 s s^T, so that sigma_dot = 1/4 [B] omega_BN_B.
inline Eigen::Matrix3d mrp_B_matrix(const Eigen::Vector3d& sigma_BN)
{
  const double s2 = sigma_BN.squaredNorm();
  return (1.0 - s2) * Eigen::Matrix3d::Identity() + 2.0 * skew(sigma_BN) +
         2.0 * sigma_BN * sigma_BN.transpose();
}

// = 1/4 ((1 - s^2) omega + 2 s x omega + 2 s (s . omega)), the product written out.
inline Eigen::Vector3d sigma_dot_from_omega(const Eigen::Vector3d& sigma_BN,
                                            const Eigen::Vector3d& omega_BN_B)
{
  const double s2 = sigma_BN.squaredNorm();
  return 0.25 * ((1.0 - s2) * omega_BN_B + 2.0 * sigma_BN.cross(omega_BN_B) +
                 (2.0 * sigma_BN.dot(omega_BN_B)) * sigma_BN);
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

// Scalar-first quaternion (q0 >= 0) of a DCM, Shepperd's method.
inline Eigen::Vector4d quaternion_from_dcm(const Eigen::Matrix3d& C)
{
  const double tr = C.trace();
  const double b2[4] = {0.25 * (1.0 + tr), 0.25 * (1.0 + 2.0 * C(0, 0) - tr),
                        0.25 * (1.0 + 2.0 * C(1, 1) - tr), 0.25 * (1.0 + 2.0 * C(2, 2) - tr)};
  const int i = static_cast<int>(std::max_element(b2, b2 + 4) - b2);
  Eigen::Vector4d q;
  // Products from C = (q0^2 - qv.qv) I + 2 qv qv^T - 2 q0 [qv~] (Shepperd).
  const double p01 = 0.25 * (C(1, 2) - C(2, 1)), p02 = 0.25 * (C(2, 0) - C(0, 2));
  const double p03 = 0.25 * (C(0, 1) - C(1, 0)), p12 = 0.25 * (C(0, 1) + C(1, 0));
  const double p13 = 0.25 * (C(2, 0) + C(0, 2)), p23 = 0.25 * (C(1, 2) + C(2, 1));
  const double s = std::sqrt(b2[i]);
  switch (i) {
    case 0: q << s, p01 / s, p02 / s, p03 / s; break;
    case 1: q << p01 / s, s, p12 / s, p13 / s; break;
    case 2: q << p02 / s, p12 / s, s, p23 / s; break;
    default: q << p03 / s, p13 / s, p23 / s, s; break;
  }
  if (q(0) < 0.0) q = -q;
  return q / q.norm();
}

// MRP from a scalar-first quaternion with q0 >= 0: q_v / (1 + q0).
inline Eigen::Vector3d sigma_from_quaternion(const Eigen::Vector4d& q)
{
  return q.tail<3>() / (1.0 + q(0));
}

// Scalar-first quaternion of an MRP (|sigma| <= 1 gives q0 >= 0).
inline Eigen::Vector4d quaternion_from_sigma(const Eigen::Vector3d& s)
{
  const double s2 = s.squaredNorm();
  const double d = 1.0 + s2;
  return Eigen::Vector4d((1.0 - s2) / d, 2.0 * s(0) / d, 2.0 * s(1) / d, 2.0 * s(2) / d);
}

}  // namespace sim

#endif  // SIM_ATTITUDE_H

// Shared helpers for the sim_cpp tests: reference vehicles and independent
// (test-side) rotation maths.  Nothing here calls into the plant's attitude
// code, so tests that use it are independent checks of that code.
#ifndef SIM_TEST_UTIL_H
#define SIM_TEST_UTIL_H

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "sim/plant.h"
#include "sim/units.h"

namespace simtest {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Active rotation by angle phi about unit axis a (written out, not Eigen's AngleAxis).
inline Matrix3d rot(const Vector3d& a, double phi)
{
  Matrix3d k;
  k << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return Matrix3d::Identity() + std::sin(phi) * k + (1.0 - std::cos(phi)) * k * k;
}

// Principal rotation angle of a DCM: acos((trace - 1)/2), robust near 0.
inline double dcm_angle(const Matrix3d& R)
{
  const Vector3d v(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * v.norm(), 0.5 * (R.trace() - 1.0));
}

// MRP -> DCM from the quaternion route (independent of sim::dcm_BN_from_sigma):
// beta0 = (1 - s^2)/(1 + s^2), beta_v = 2 s/(1 + s^2); [BN] = rotation of
// frame N into B, i.e. the transpose of the active rotation by beta.
inline Matrix3d dcm_BN_via_quaternion(const Vector3d& s)
{
  const double s2 = s.squaredNorm();
  const double b0 = (1.0 - s2) / (1.0 + s2);
  const Vector3d b = 2.0 * s / (1.0 + s2);
  Matrix3d C;
  C << b0 * b0 + b(0) * b(0) - b(1) * b(1) - b(2) * b(2), 2 * (b(0) * b(1) + b0 * b(2)),
      2 * (b(0) * b(2) - b0 * b(1)), 2 * (b(0) * b(1) - b0 * b(2)),
      b0 * b0 - b(0) * b(0) + b(1) * b(1) - b(2) * b(2), 2 * (b(1) * b(2) + b0 * b(0)),
      2 * (b(0) * b(2) + b0 * b(1)), 2 * (b(1) * b(2) - b0 * b(0)),
      b0 * b0 - b(0) * b(0) - b(1) * b(1) + b(2) * b(2);
  return C;
}

// Seconds -> plant clock [ns] (tests written in seconds convert here).
inline int64_t ns(double seconds) { return std::llround(seconds * 1e9); }

inline double rel_err(const Vector3d& a, const Vector3d& b) { return (a - b).norm() / b.norm(); }
inline double rel_err(double a, double b) { return std::abs(a - b) / std::abs(b); }

// Basilisk's LEO test orbit (point C), Earth mu.
inline sim::InitialConditions leo_ic()
{
  sim::InitialConditions ic;
  ic.r_CN_N = Vector3d(-4020338.690396649, 7490566.741852513, 5248299.211589362);
  ic.v_CN_N = Vector3d(-5199.77710904224, -3436.681645356935, 1041.576797498721);
  ic.sigma_BN = Vector3d(0.1, 0.2, -0.3);
  ic.omega_BN_B = Vector3d(0.08, 0.01, -0.02);
  return ic;
}

// Hub of scenario S1 with products of inertia and an offset CoM so that B != C
// and no axis is principal.
inline sim::HubParams reference_hub()
{
  sim::HubParams h;
  h.m_h = 750.0;
  h.I_hBc_B << 900.0, 20.0, -15.0,
               20.0, 800.0, 10.0,
               -15.0, 10.0, 600.0;
  h.r_BcB_B = Vector3d(0.05, -0.03, 0.1);
  return h;
}

// Four wheels in the S1 pyramid (elevation 40 deg, azimuths 45..315 deg) at
// 100..400 RPM.  Imbalances are exaggerated (~70x the HR16 figures) so that
// jitter effects are far above round-off.  Wheel 3 has J_t != J_g (RW-9).
inline std::vector<sim::ReactionWheelParams> pyramid_wheels(sim::WheelModel model)
{
  std::vector<sim::ReactionWheelParams> ws;
  const double el = sim::rad_from_deg(40.0);
  const double az[4] = {45.0, 135.0, 225.0, 315.0};
  const double px[4] = {0.8, 0.8, -0.8, -0.8};
  const double py[4] = {0.8, -0.8, -0.8, 0.8};
  for (int i = 0; i < 4; ++i) {
    sim::ReactionWheelParams w;
    w.model = model;
    const double a = sim::rad_from_deg(az[i]);
    w.gs_hat_nom_B = Vector3d(std::cos(el) * std::cos(a), std::cos(el) * std::sin(a), std::sin(el));
    w.r_WB_B = Vector3d(px[i], py[i], 1.7907);
    w.m_w = 9.0;
    w.J_s = 0.0795775;
    w.U_s = 2.0e-4;
    w.U_d = 5.0e-5;
    w.Omega_0 = sim::rad_s_from_rpm(100.0 * (i + 1));
    ws.push_back(w);
  }
  ws[3].J_t = 0.045;
  ws[3].J_g = 0.035;
  return ws;
}

}  // namespace simtest

#endif  // SIM_TEST_UTIL_H

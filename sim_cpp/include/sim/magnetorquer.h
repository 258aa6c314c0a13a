// magnetorquer: a magnetic torque rod as a value model (dipole along a fixed
// axis, saturation, remanence, coil power) and the torque m x B.  Frame B
// body.  Units: SI (A m^2, T, W, N m).  See docs/environment.md.
#ifndef SIM_MAGNETORQUER_H
#define SIM_MAGNETORQUER_H

#include <Eigen/Dense>

#include "sim/state_io.h"

namespace sim {

struct MagnetorquerParams {
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitX();  // [-] unit dipole axis, B
  double m_max = 1.0;       // [A m^2] saturation dipole, > 0
  double m_remanent = 0.0;  // [A m^2] residual dipole once the coil is off, in [0, m_max)
  double power_max = 0.0;   // [W] coil power at |m| = m_max, >= 0
};

// Throws std::invalid_argument naming `name.field` and the value.
void validate(const MagnetorquerParams& p, const char* name = "mtq");

// Dipole along axis_B:
//   coil on  (command != 0): m = clamp(command, -m_max, m_max)   (saturated if clipped)
//   coil off (command == 0): m = m_remanent * sign(last non-zero command)
//                            (0 before any command)
// Coil power P = power_max (m_coil / m_max)^2 (resistive: current ~ dipole).
// A non-finite command is taken as 0 (coil off).
class Magnetorquer {
 public:
  explicit Magnetorquer(const MagnetorquerParams& p, const char* name = "mtq");  // validates
  void command(double m_cmd);  // [A m^2]

  double dipole() const { return m_; }                    // [A m^2] along the axis
  Eigen::Vector3d dipole_B() const { return m_ * p_.axis_B; }  // [A m^2] B
  double power() const { return power_; }                 // [W]
  bool saturated() const { return saturated_; }
  const MagnetorquerParams& params() const { return p_; }
  // Run state for a checkpoint (sim/state_io.h).
  void state_io(StateIO& io)
  {
    io.value("rod.m", m_);
    io.value("rod.power", power_);
    io.value("rod.last_sign", last_sign_);
    io.value("rod.saturated", saturated_);
  }

 private:
  MagnetorquerParams p_;
  double m_ = 0.0;
  double power_ = 0.0;
  double last_sign_ = 0.0;
  bool saturated_ = false;
};

// Torque of a magnetic dipole in a field: L_B = m_B x B_B   [N m].
inline Eigen::Vector3d magnetic_torque(const Eigen::Vector3d& m_B, const Eigen::Vector3d& B_B)
{
  return m_B.cross(B_B);
}

}  // namespace sim

#endif  // SIM_MAGNETORQUER_H

// spacecraft: rigid hub with reaction wheels, written at body point B
// (spec plant-dynamics §1-§3, §7, §8, §13).  Frames: N inertial, B body
// (origin at point B, NOT the mass centre C), Wi wheel i.  Units: SI.
//
// Two layers:
//   SpacecraftModel  validated parameters + derived wheel data; const, pure
//                    physics (mass properties, derivatives, energy/momentum).
//   Spacecraft       one run: the state, held (latched) inputs, friction mode
//                    flags and the MRP switch counter; step() = RK4 + switch.
//
// State vector layout (StateLayout, §1), n = number of wheels:
//   [0,3)   r_BN_N     [m]     position of B
//   [3,6)   v_BN_N     [m/s]   inertial velocity of B
//   [6,9)   sigma_BN   [-]     MRP attitude, |sigma| <= 1 after every step
//   [9,12)  omega_BN_B [rad/s] body rate
//   [12,12+n)     Omega_i [rad/s] wheel speeds relative to B about gs_hat_i
//   [12+n,12+2n)  theta_i [rad]   rotor angles (unwrapped).  Every wheel carries
//                 theta; only jitter wheels use it (a Balanced wheel ignores it).
// StateVector has a compile-time maximum size, so it never touches the heap.
#ifndef SIM_SPACECRAFT_H
#define SIM_SPACECRAFT_H

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "sim/reaction_wheel.h"

namespace sim {

constexpr int kMaxWheels = 16;                     // [-] capacity; state size 12 + 2*kMaxWheels
constexpr int kMaxStateDim = 12 + 2 * kMaxWheels;  // [-]

using StateVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxStateDim, 1>;
using WheelArray = std::array<double, kMaxWheels>;

struct StateLayout {
  static constexpr int r_BN_N = 0;
  static constexpr int v_BN_N = 3;
  static constexpr int sigma_BN = 6;
  static constexpr int omega_BN_B = 9;
  int num_rw = 0;
  int Omega(int i) const { return 12 + i; }
  int theta(int i) const { return 12 + num_rw + i; }
  int size() const { return 12 + 2 * num_rw; }
};

struct HubParams {
  double m_h = 0.0;                                       // [kg]     hub mass, > 0
  Eigen::Matrix3d I_hBc_B = Eigen::Matrix3d::Zero();      // [kg*m^2] hub inertia about its CoM Bc, SPD
  Eigen::Vector3d r_BcB_B = Eigen::Vector3d::Zero();      // [m]      hub CoM relative to B
};

struct SpacecraftParams {
  HubParams hub;  // Balanced/SimpleJitter wheels INSIDE, FullyCoupled wheels OUTSIDE (trap 2)
  std::vector<ReactionWheelParams> wheels;  // (num_rw <= kMaxWheels)
  double mu = 0.0;  // [m^3/s^2] point-mass gravity parameter, >= 0 (0: gravity off)
};

struct InitialConditions {  // given for the mass centre C (§1)
  Eigen::Vector3d r_CN_N = Eigen::Vector3d::Zero();      // [m]
  Eigen::Vector3d v_CN_N = Eigen::Vector3d::Zero();      // [m/s]
  Eigen::Vector3d sigma_BN = Eigen::Vector3d::Zero();    // [-]
  Eigen::Vector3d omega_BN_B = Eigen::Vector3d::Zero();  // [rad/s]
};

// Inputs held constant over a step (zero-order hold, §7.2).
struct HeldInputs {
  WheelArray u_s{};                                    // [N*m] (num_rw) motor torque after §4.3
  std::array<bool, kMaxWheels> stribeck{};             // [-]   (num_rw) friction mode flag S (§4.6)
  Eigen::Vector3d F_ext_B = Eigen::Vector3d::Zero();   // [N]   external force, B components
  Eigen::Vector3d L_ext_B = Eigen::Vector3d::Zero();   // [N*m] external torque about point B
};

struct MassProps {  // §2, about/relative to point B, B components
  double m_sc = 0.0;             // [kg]
  Eigen::Vector3d c_B;           // [m]        r_CB_B
  Eigen::Vector3d c_prime_B;     // [m/s]      B-frame derivative of c
  Eigen::Matrix3d I_sc_B;        // [kg*m^2]   inertia about B
  Eigen::Matrix3d I_sc_prime_B;  // [kg*m^2/s] B-frame derivative of I_sc_B
};

struct EnergyMomentum {  // §8
  Eigen::Vector3d r_CN_N, v_CN_N;  // [m], [m/s]
  Eigen::Vector3d H_C_B, H_C_N;    // [kg*m^2/s] rotational angular momentum about C
  Eigen::Vector3d H_orb_N;         // [kg*m^2/s] m_sc r_C x v_C
  double E_rot = 0.0;              // [J] rotational kinetic energy about C
  double E_orb = 0.0;              // [J] orbital energy of C
};

struct Accelerations {  // solved hub accelerations (§3)
  Eigen::Vector3d omega_dot_BN_B;  // [rad/s^2]
  Eigen::Vector3d r_ddot_BN_B;     // [m/s^2] inertial acceleration of B, B components
};

class SpacecraftModel {
 public:
  // Validates every field (std::invalid_argument names the field and value).
  explicit SpacecraftModel(SpacecraftParams params);

  const SpacecraftParams& params() const { return p_; }
  const ReactionWheelDerived& wheel_derived(int i) const { return derived_[static_cast<size_t>(i)]; }
  int num_rw() const { return layout_.num_rw; }
  const StateLayout& layout() const { return layout_; }

  // State at t0 from C-point initial conditions; Omega_i = Omega_0, theta_i = 0.
  StateVector initial_state(const InitialConditions& ic) const;

  MassProps mass_props(const StateVector& x) const;

  // Pure: x_dot = f(x, held).  Autonomous (t is accepted for rk4_step only).
  StateVector derivatives(double t, const StateVector& x, const HeldInputs& in,
                          Accelerations* acc = nullptr) const;

  EnergyMomentum energy_momentum(const StateVector& x) const;

  // --- hub override (added for thrusters/propellant, issue 7) -------------
  // Same physics with `hub` in place of params().hub.  The propulsion layer
  // (sim/vehicle.h) passes the hub merged with the rigid propellant tanks of
  // the current stage (§5.6: tanks are rigid bodies fixed in B, so merging
  // them into the hub is exact for §2 and §8).  `hub` is not re-validated.
  StateVector initial_state(const InitialConditions& ic, const HubParams& hub) const;
  MassProps mass_props(const StateVector& x, const HubParams& hub) const;
  StateVector derivatives(double t, const StateVector& x, const HeldInputs& in,
                          const HubParams& hub, Accelerations* acc = nullptr) const;
  EnergyMomentum energy_momentum(const StateVector& x, const HubParams& hub) const;

  // Friction torque tau_f (§4.4) of wheel i at state x and mode flag.
  double friction_torque(int i, const StateVector& x, bool stribeck) const;

 private:
  SpacecraftParams p_;
  std::vector<ReactionWheelDerived> derived_;
  StateLayout layout_;
};

enum class StepStatus { Ok, NonFiniteState };

class Spacecraft {
 public:
  Spacecraft(SpacecraftParams params, const InitialConditions& ic);

  const SpacecraftModel& model() const { return model_; }
  const StateVector& state() const { return x_; }
  void set_state(const StateVector& x);  // for tests and scenario restarts

  // §4.3 command latch using the current wheel speeds; u_cmd[i] for i < num_rw.
  void latch_commands(const WheelArray& u_cmd);
  // External test force/torque about B, held until changed.
  void set_external(const Eigen::Vector3d& F_ext_B, const Eigen::Vector3d& L_ext_B);

  // One RK4 step of dt [s]: Stribeck mode update at the step start (§4.6),
  // RK4 with held inputs (§7.1), MRP shadow switch after the step (§7.4).
  // A non-finite result is not committed; the run halts with that reason.
  StepStatus step(double dt);

  // Accessors (§13).
  Eigen::Vector3d r_BN_N() const { return x_.segment<3>(StateLayout::r_BN_N); }
  Eigen::Vector3d v_BN_N() const { return x_.segment<3>(StateLayout::v_BN_N); }
  Eigen::Vector3d sigma_BN() const { return x_.segment<3>(StateLayout::sigma_BN); }
  Eigen::Vector3d omega_BN_B() const { return x_.segment<3>(StateLayout::omega_BN_B); }
  double Omega(int i) const { return x_(model_.layout().Omega(i)); }
  double theta(int i) const { return x_(model_.layout().theta(i)); }
  MassProps mass_props() const { return model_.mass_props(x_); }
  EnergyMomentum energy_momentum() const { return model_.energy_momentum(x_); }
  double u_s(int i) const { return held_.u_s[static_cast<size_t>(i)]; }
  double tau_f(int i) const;
  bool stribeck_mode(int i) const { return held_.stribeck[static_cast<size_t>(i)]; }
  uint64_t mrp_switch_count() const { return switches_; }
  uint64_t steps_taken() const { return steps_; }
  StepStatus status() const { return status_; }
  const HeldInputs& held_inputs() const { return held_; }

 private:
  SpacecraftModel model_;
  StateVector x_;
  HeldInputs held_;
  WheelArray Omega_prev_{};  // [rad/s] wheel speeds at the previous step start (§4.6)
  bool first_step_ = true;
  uint64_t switches_ = 0;
  uint64_t steps_ = 0;
  StepStatus status_ = StepStatus::Ok;
};

}  // namespace sim

#endif  // SIM_SPACECRAFT_H

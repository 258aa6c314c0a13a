// spacecraft: the pure physics of a rigid hub with reaction wheels, written
// at body point B (docs/dynamics.md §1-§4, §8, §13).  Frames: N inertial,
// B body (origin at point B, NOT the mass centre C), Wi wheel i.  Units: SI.
//
// SpacecraftModel holds validated parameters and derived wheel data and
// evaluates mass properties, derivatives and energy/momentum for a given
// state, held inputs and hub.  The hub is always passed explicitly: the run
// (sim::Plant, sim/plant.h) passes the hub merged with the propellant of the
// current stage (§5.6), which is params().hub when there are no tanks.  The
// only mutable parts are the device parameters the Plant may change between
// steps (wheel limits and friction), each through a validating setter.
//
// State vector layout (StateLayout, §1), n = num_rw, m = num_tanks:
//   [0,3)   r_BN_N     [m]     position of B
//   [3,6)   v_BN_N     [m/s]   inertial velocity of B
//   [6,9)   sigma_BN   [-]     MRP attitude, |sigma| <= 1 after every step
//   [9,12)  omega_BN_B [rad/s] body rate
//   [12,12+n)        Omega_i [rad/s] wheel speeds relative to B about gs_hat_i
//   [12+n,12+2n)     theta_i [rad]   rotor angles (unwrapped).  Every wheel carries
//                    theta; only jitter wheels use it (a Balanced wheel ignores it).
//   [12+2n,12+2n+m)  m_p,k   [kg]    propellant per tank (derivative set by the Plant)
// Thruster factors kappa_j are NOT integrated states: the Plant advances them
// in closed form (docs/dynamics.md).  StateVector has a compile-time maximum
// size (sim/capacities.h), so it never touches the heap.
#ifndef SIM_SPACECRAFT_H
#define SIM_SPACECRAFT_H

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "sim/capacities.h"
#include "sim/reaction_wheel.h"
#include "sim/sin_cos.h"

namespace sim {

using StateVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxStateDim, 1>;

struct StateLayout {
  static constexpr int r_BN_N = 0;
  static constexpr int v_BN_N = 3;
  static constexpr int sigma_BN = 6;
  static constexpr int omega_BN_B = 9;
  int num_rw = 0;
  int num_tanks = 0;
  int Omega(int i) const { return kHubStateDim + i; }
  int theta(int i) const { return kHubStateDim + num_rw + i; }
  int m_p(int k) const { return kHubStateDim + 2 * num_rw + k; }
  int size() const { return kHubStateDim + 2 * num_rw + num_tanks; }
};

struct HubParams {
  double m_h = 0.0;                                       // [kg]     hub mass, > 0
  Eigen::Matrix3d I_hBc_B = Eigen::Matrix3d::Zero();      // [kg*m^2] hub inertia about its CoM Bc, SPD
  Eigen::Vector3d r_BcB_B = Eigen::Vector3d::Zero();      // [m]      hub CoM relative to B
};

// Parallel-axis term of a mass m at r from the reference point:
// m [r~][r~]^T = m ((r.r) I - r r^T), element by element as the Eigen
// expression m * ((r.r) * Identity - r * r^T) forms it (the same bits, and
// about 35 instructions fewer per call than the expression's product
// evaluation; the tank merge calls it in every derivative evaluation).
inline Eigen::Matrix3d parallel_axis(double m, const Eigen::Vector3d& r)
{
  const double s = r.squaredNorm();
  const double off = s * 0.0;  // the Identity's zeros times s (+0 for finite s)
  Eigen::Matrix3d P;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) P(i, j) = m * ((i == j ? s : off) - r(i) * r(j));
  return P;
}

struct SpacecraftParams {
  HubParams hub;  // Balanced/SimpleJitter wheels INSIDE, FullyCoupled wheels OUTSIDE (docs/dynamics.md §2)
  std::vector<ReactionWheelParams> wheels;  // (num_rw <= kMaxWheels)
  double mu = 0.0;  // [m^3/s^2] point-mass gravity parameter, >= 0 (0: gravity off)
  // Oblateness: the J2 term of the central body's gravity (sim::j2_acceleration,
  // N z = the body's rotation axis), at the mass centre.  0: off (default).
  double J2 = 0.0;    // [-] finite, >= 0; > 0 needs mu > 0 and R_J2 > 0
  double R_J2 = 0.0;  // [m] its reference (equatorial) radius
};

struct InitialConditions {  // given for the mass centre C (§1)
  Eigen::Vector3d r_CN_N = Eigen::Vector3d::Zero();      // [m]
  Eigen::Vector3d v_CN_N = Eigen::Vector3d::Zero();      // [m/s]
  Eigen::Vector3d sigma_BN = Eigen::Vector3d::Zero();    // [-]
  Eigen::Vector3d omega_BN_B = Eigen::Vector3d::Zero();  // [rad/s]
};

// Inputs held constant over a step (zero-order hold, §7.2).
struct WheelInputs {
  WheelArray u_s{};                         // [N*m] (num_rw) motor torque after §4.3
  std::array<bool, kMaxWheels> stribeck{};  // [-]   (num_rw) friction mode flag S (§4.6)
  std::array<bool, kMaxWheels> stuck{};     // [-]   (num_rw) rotor held at its speed: Omega' = 0
                                            //       (WheelHealth::Stuck; docs/dynamics.md)
};

// Total external force and torque on the hub at one derivative evaluation
// (the Plant: held test loads plus every force/torque effector).
struct ExternalLoads {
  Eigen::Vector3d F_ext_B = Eigen::Vector3d::Zero();  // [N]   external force, B components
  Eigen::Vector3d L_ext_B = Eigen::Vector3d::Zero();  // [N*m] external torque about point B
};

// Everything the Plant holds over a step besides the effectors' own inputs.
struct HeldInputs {
  WheelInputs wheels;
  ExternalLoads loads;  // test/caller loads set by Plant::set_external
};

struct MassProps {  // §2, about/relative to point B, B components
  double m_sc = 0.0;             // [kg]
  Eigen::Vector3d c_B;           // [m]        r_CB_B
  Eigen::Vector3d c_prime_B;     // [m/s]      B-frame derivative of c
  Eigen::Matrix3d I_sc_B;        // [kg*m^2]   inertia about B
  Eigen::Matrix3d I_sc_prime_B;  // [kg*m^2/s] B-frame derivative of I_sc_B
};

struct MassCentre {  // the first two members of MassProps
  double m_sc = 0.0;  // [kg]
  Eigen::Vector3d c_B = Eigen::Vector3d::Zero();  // [m] r_CB_B
};

// cos and sin of the rotor angles theta_i of one state: the entries of the
// jittering wheels (SimpleJitter, FullyCoupled); a Balanced wheel's is unset.
using RotorSinCos = std::array<SinCos, kMaxWheels>;

struct EnergyMomentum {  // §8
  Eigen::Vector3d r_CN_N, v_CN_N;  // [m], [m/s]
  Eigen::Vector3d H_C_B, H_C_N;    // [kg*m^2/s] rotational angular momentum about C
  Eigen::Vector3d H_orb_N;         // [kg*m^2/s] m_sc r_C x v_C
  double E_rot = 0.0;              // [J] rotational kinetic energy about C
  double E_orb = 0.0;              // [J] orbital energy of C (with the J2 potential when SpacecraftParams::J2 is set)
};

struct Accelerations {  // solved hub accelerations (§3)
  Eigen::Vector3d omega_dot_BN_B;  // [rad/s^2]
  Eigen::Vector3d r_ddot_BN_B;     // [m/s^2] inertial acceleration of B, B components
};

class SpacecraftModel {
 public:
  // Validates every field (std::invalid_argument names the field and value).
  // num_tanks only sizes the state layout (the tank masses are the Plant's).
  explicit SpacecraftModel(SpacecraftParams params, int num_tanks = 0);

  const SpacecraftParams& params() const { return p_; }
  const ReactionWheelDerived& wheel_derived(int i) const { return derived_[static_cast<size_t>(i)]; }
  int num_rw() const { return layout_.num_rw; }
  const StateLayout& layout() const { return layout_; }

  // State at t0 from C-point initial conditions with `hub` (§1);
  // Omega_i = Omega_0, theta_i = 0, tank entries 0 (filled by the Plant).
  StateVector initial_state(const InitialConditions& ic, const HubParams& hub) const;

  MassProps mass_props(const StateVector& x, const HubParams& hub) const;
  // m_sc and c_B alone, from the per-configuration constants (cheap).
  // `sc`: rotor_sin_cos(x, ...) when the caller has it, else null.
  MassCentre mass_centre(const StateVector& x, const HubParams& hub, const RotorSinCos* sc = nullptr) const;
  // A wheel jitters: the derivative and the mass centre need cos/sin theta.
  bool needs_rotor_angles() const { return any_rotor_angle_; }
  void rotor_sin_cos(const StateVector& x, RotorSinCos& out) const;

  // Pure: x_dot = f(x, wheel inputs, loads, hub).  Autonomous (t is accepted
  // for rk4_step only).  The tank entries of x_dot are 0; the Plant adds the
  // mass flows.
  // `sc`: rotor_sin_cos(x, ...) when the caller has it, else null.
  StateVector derivatives(double t, const StateVector& x, const WheelInputs& in,
                          const ExternalLoads& loads, const HubParams& hub,
                          Accelerations* acc = nullptr, const RotorSinCos* sc = nullptr) const;

  EnergyMomentum energy_momentum(const StateVector& x, const HubParams& hub) const;

  // Friction torque tau_f (§4.4) of wheel i at state x and mode flag.
  double friction_torque(int i, const StateVector& x, bool stribeck) const;

  // Device parameters changeable between steps (validated; std::invalid_argument
  // names "wheels[i].<field>").  They act from the next latch (u_max,
  // Omega_max) or the next derivative evaluation (friction).
  void set_wheel_u_max(int i, double u_max);          // [N*m]   <= 0: unlimited
  void set_wheel_Omega_max(int i, double Omega_max);  // [rad/s] <= 0: none
  void set_wheel_friction(int i, const WheelFrictionParams& f);

 private:
  void check_wheel_index(int i) const;
  void init_rotor_constants();

  SpacecraftParams p_;
  std::vector<ReactionWheelDerived> derived_;
  StateLayout layout_;

  // Per-configuration constants of the derivative (docs/dynamics.md,
  // "The derivative as computed"), set once by the constructor: the parts of
  // the mass properties that do not turn with the rotors, and per wheel the
  // scalars and B-frame vectors its rotor-angle-dependent terms are made of.
  struct RotorConstants {
    double md = 0.0;             // [kg*m]     m_w d (FullyCoupled; 0 otherwise)
    double inv_J = 0.0;          // [1/(kg*m^2)] 1 / J_bar
    double kA = 0.0;             // [1/m]      m_w d / J_bar
    double alpha = 0.0;          // [kg*m^2]   J_t - J_g - m_w d^2
    double rW_w2_0 = 0.0;        // [m]        r_W . w2_0
    double rW_w3_0 = 0.0;        // [m]        r_W . w3_0
    Eigen::Vector3d rW_x_w2_0;   // [m]        r_W x w2_0
    Eigen::Vector3d rW_x_w3_0;   // [m]        r_W x w3_0
  };
  std::vector<RotorConstants> rc_;
  double m_fc_ = 0.0;                                        // [kg]     sum of FC rotor masses
  Eigen::Vector3d first_moment_fc_ = Eigen::Vector3d::Zero();  // [kg*m]   sum m_w r_W (FC)
  Eigen::Matrix3d I_fc_const_B_ = Eigen::Matrix3d::Zero();     // [kg*m^2] FC inertia parts fixed in B
  Eigen::Matrix3d J_spin_B_ = Eigen::Matrix3d::Zero();         // [kg*m^2] sum J_s gs gs^T (Balanced/SimpleJitter)
  bool any_fc_ = false;
  bool any_rotor_angle_ = false;  // a SimpleJitter or FullyCoupled wheel: the derivative needs cos/sin theta
};

}  // namespace sim

#endif  // SIM_SPACECRAFT_H

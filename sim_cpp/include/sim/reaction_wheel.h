// reaction_wheel: wheel parameters, frame construction, command pipeline,
// friction and the back-substitution contributions of one wheel
// (docs/dynamics.md §4).  Frames: B (body), Wi (wheel i).  Units: SI.
//
// Models (§4.7):
//   Balanced      mass and full inertia INSIDE the hub values; motor reaction and
//                 gyroscopic torque only.
//   SimpleJitter  Balanced plus a pseudo-external force U_s Omega^2 w2 and torque
//                 r_WB x F + U_d Omega^2 w2.  Does NOT conserve momentum or energy.
//   FullyCoupled  separate rigid rotor (mass m_w, CoM offset d = U_s/m_w along w2,
//                 product of inertia J13 = U_d), NOT inside the hub values.
#ifndef SIM_REACTION_WHEEL_H
#define SIM_REACTION_WHEEL_H

#include <optional>
#include <string>

#include <Eigen/Dense>

namespace sim {

enum class WheelModel { Balanced, SimpleJitter, FullyCoupled };

const char* to_string(WheelModel m);

struct WheelFrictionParams {
  double tau_c = 0.0;      // [N*m]       Coulomb friction, >= 0
  double tau_st = 0.0;     // [N*m]       static (breakaway) friction, >= tau_c when Stribeck is on
  double c_v = 0.0;        // [N*m*s/rad] viscous coefficient, >= 0
  double beta_st = -1.0;   // [rad/s]     Stribeck speed; <= 0 disables Stribeck
  double omega_lc = 1e-4;  // [rad/s]     low-speed linearisation band, > 0
};

// Health of a wheel, set by the Plant between steps (faults/events).
enum class WheelHealth {
  Nominal,  // commands go through the §4.3 pipeline
  Off,      // motor unpowered: u_s forced to 0 at once and at every latch; friction still acts
  Stuck     // rotor held at its present speed relative to the hub (a speed-locked rotor): the
            // bearing carries whatever axial torque keeps Omega' = 0; motor and friction do not
            // act (u_s 0 as for Off); the rotor's spin momentum, imbalance and inertia remain
};

const char* to_string(WheelHealth h);

struct ReactionWheelParams {  // checked by validate(); u_max, Omega_max and friction settable on a Plant
  WheelModel model = WheelModel::Balanced;
  Eigen::Vector3d gs_hat_nom_B = Eigen::Vector3d::Zero();  // [-]   nominal spin axis, unit (what FSW believes)
  Eigen::Vector3d delta_mis_B = Eigen::Vector3d::Zero();   // [rad] spin-axis misalignment rotation vector
  Eigen::Vector3d r_WB_B = Eigen::Vector3d::Zero();        // [m]   wheel frame origin W (on the spin axis)
  double m_w = 0.0;               // [kg]       rotor mass (used by FullyCoupled only)
  double J_s = 0.0;               // [kg*m^2]   spin inertia (FC: about rotor CoM), > 0
  std::optional<double> J_t;      // [kg*m^2]   transverse inertia about w2; default J_s/2
  std::optional<double> J_g;      // [kg*m^2]   transverse inertia about w3; default J_s/2
  double U_s = 0.0;               // [kg*m]     static imbalance, >= 0
  double U_d = 0.0;               // [kg*m^2]   dynamic imbalance, >= 0
  double Omega_0 = 0.0;           // [rad/s]    initial wheel speed relative to B
  double u_max = 0.0;             // [N*m]      motor torque limit; <= 0: unlimited
  double u_min = 0.0;             // [N*m]      command dead-band, >= 0
  double Omega_max = 0.0;         // [rad/s]    speed limit for the command pipeline; <= 0: none
  double P_max = 0.0;             // [W]        motor power limit; <= 0: none
  WheelFrictionParams friction;
};

// Values derived once from the params (§4.2, §4.8) and echoed for tests (§13).
struct ReactionWheelDerived {
  Eigen::Vector3d gs_hat_B;   // [-]   true spin axis R(delta_mis) gs_hat_nom_B, renormalised
  Eigen::Vector3d w2_0_hat_B; // [-]   transverse axis at theta = 0
  Eigen::Vector3d w3_0_hat_B; // [-]   gs x w2 at theta = 0
  double J_t = 0.0;           // [kg*m^2]
  double J_g = 0.0;           // [kg*m^2]
  double d = 0.0;             // [m]      FC rotor CoM offset U_s / m_w (0 otherwise)
  double J13 = 0.0;           // [kg*m^2] FC product of inertia = U_d (0 otherwise)
  double J_bar = 0.0;         // [kg*m^2] spin inertia about the spin axis: J_s + m_w d^2 (FC), J_s otherwise
};

// Throw std::invalid_argument naming `name.field` and the offending value.
void validate(const ReactionWheelParams& p, const std::string& name = "wheel");
void validate(const WheelFrictionParams& f, const std::string& name = "friction");

// §4.2 frame construction.  Requires validate(p) to have passed.
ReactionWheelDerived derive(const ReactionWheelParams& p);

// Wheel axes at rotor angle theta (§4.2 step 3).
struct WheelAxes {
  Eigen::Vector3d gs_hat_B, w2_hat_B, w3_hat_B;
};
WheelAxes wheel_axes(const ReactionWheelDerived& dv, double theta);

// §4.3 command pipeline: saturation, dead-band, power limit, speed limit.
// Omega is the wheel speed at the latch time.  Returns the held motor torque u_s.
double command_pipeline(const ReactionWheelParams& p, double u_cmd, double Omega);

// §4.4 friction torque on the rotor, tau_f = -f(Omega), for mode flag
// stribeck (only honoured when beta_st > 0).
double friction_torque(const WheelFrictionParams& f, double Omega, bool stribeck);

// §4.6 Stribeck mode update, once per step at the step start.
// dOmega = Omega(step start) - Omega(previous step start) (0 on the first step).
// Returns true only while the wheel moves away from zero (sign(Omega) ==
// sign(dOmega), or either is zero): entered when also |Omega| < 0.1 omega_lc,
// kept while moving away, left as soon as the wheel slows down.
bool update_stribeck_mode(const WheelFrictionParams& f, bool mode, double Omega, double dOmega);

}  // namespace sim

#endif  // SIM_REACTION_WHEEL_H

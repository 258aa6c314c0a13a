// reaction_wheel: see sim/reaction_wheel.h.  docs/dynamics.md §4.
#include "sim/reaction_wheel.h"

#include <cmath>

#include "sim/attitude.h"
#include "sim/sin_cos.h"
#include "validate_util.h"

namespace sim {

namespace {
// Tolerance on |gs_hat_nom_B| - 1: axes are typed in with ~16 digits; a
// looser value would hide unit mistakes, a tighter one rejects rounding.
constexpr double kUnitAxisTol = 1e-9;
// §4.2: fall back to y-hat when the nominal axis is within ~0.57 deg of x-hat.
constexpr double kAxisParallelLimit = 0.01;
}  // namespace

const char* to_string(WheelModel m)
{
  switch (m) {
    case WheelModel::Balanced: return "Balanced";
    case WheelModel::SimpleJitter: return "SimpleJitter";
    case WheelModel::FullyCoupled: return "FullyCoupled";
  }
  return "?";
}

const char* to_string(WheelHealth h)
{
  switch (h) {
    case WheelHealth::Nominal: return "Nominal";
    case WheelHealth::Off: return "Off";
    case WheelHealth::Stuck: return "Stuck";
  }
  return "?";
}

void validate(const ReactionWheelParams& p, const std::string& name)
{
  using namespace detail;
  const int model = static_cast<int>(p.model);
  if (model < 0 || model > 2) fail(name + ".model", model, "must be Balanced, SimpleJitter or FullyCoupled");

  require_finite(name + ".gs_hat_nom_B", p.gs_hat_nom_B);
  if (std::abs(p.gs_hat_nom_B.norm() - 1.0) > kUnitAxisTol)
    fail_vec(name + ".gs_hat_nom_B", p.gs_hat_nom_B, "must be a unit vector");
  require_finite(name + ".delta_mis_B", p.delta_mis_B);
  require_finite(name + ".r_WB_B", p.r_WB_B);

  require_positive(name + ".J_s", p.J_s);
  if (p.J_t) require_positive(name + ".J_t", *p.J_t);
  if (p.J_g) require_positive(name + ".J_g", *p.J_g);
  require_non_negative(name + ".U_s", p.U_s);
  require_non_negative(name + ".U_d", p.U_d);
  require_non_negative(name + ".m_w", p.m_w);
  if (p.model == WheelModel::FullyCoupled) {
    if (!(p.m_w > 0.0)) fail(name + ".m_w", p.m_w, "must be > 0 for a FullyCoupled wheel");
    // [I_w]_W = [[J_s,0,J13],[0,J_t,0],[J13,0,J_g]] must be positive definite.
    const double J_g = p.J_g ? *p.J_g : 0.5 * p.J_s;
    if (!(p.U_d * p.U_d < p.J_s * J_g))
      fail(name + ".U_d", p.U_d, "rotor inertia not positive definite: need U_d^2 < J_s*J_g");
  }

  require_finite(name + ".Omega_0", p.Omega_0);
  require_finite(name + ".u_max", p.u_max);
  require_non_negative(name + ".u_min", p.u_min);
  require_finite(name + ".Omega_max", p.Omega_max);
  require_finite(name + ".P_max", p.P_max);

  validate(p.friction, name + ".friction");
}

void validate(const WheelFrictionParams& f, const std::string& name)
{
  using namespace detail;
  require_non_negative(name + ".tau_c", f.tau_c);
  require_non_negative(name + ".c_v", f.c_v);
  require_positive(name + ".omega_lc", f.omega_lc);
  require_finite(name + ".beta_st", f.beta_st);
  require_finite(name + ".tau_st", f.tau_st);
  if (f.beta_st > 0.0 && !(f.tau_st >= f.tau_c))
    fail(name + ".tau_st", f.tau_st, "must be >= tau_c when Stribeck is on (beta_st > 0)");
}

ReactionWheelDerived derive(const ReactionWheelParams& p)
{
  ReactionWheelDerived dv;
  const Eigen::Matrix3d R = rotation_from_vector(p.delta_mis_B);
  const Eigen::Vector3d g_nom = p.gs_hat_nom_B.normalized();

  Eigen::Vector3d w2_nom = g_nom.cross(Eigen::Vector3d::UnitX());
  if (w2_nom.norm() < kAxisParallelLimit) w2_nom = g_nom.cross(Eigen::Vector3d::UnitY());
  w2_nom.normalize();
  const Eigen::Vector3d w3_nom = g_nom.cross(w2_nom);

  dv.gs_hat_B = (R * g_nom).normalized();
  dv.w2_0_hat_B = R * w2_nom;
  dv.w3_0_hat_B = R * w3_nom;
  dv.J_t = p.J_t ? *p.J_t : 0.5 * p.J_s;
  dv.J_g = p.J_g ? *p.J_g : 0.5 * p.J_s;
  if (p.model == WheelModel::FullyCoupled) {
    dv.d = p.U_s / p.m_w;
    dv.J13 = p.U_d;
    dv.J_bar = p.J_s + p.m_w * dv.d * dv.d;
  } else {
    dv.J_bar = p.J_s;
  }
  return dv;
}

WheelAxes wheel_axes(const ReactionWheelDerived& dv, double theta)
{
  const SinCos sc = sin_cos(theta);
  const double c = sc.c;
  const double s = sc.s;
  WheelAxes ax;
  ax.gs_hat_B = dv.gs_hat_B;
  ax.w2_hat_B = c * dv.w2_0_hat_B + s * dv.w3_0_hat_B;
  ax.w3_hat_B = -s * dv.w2_0_hat_B + c * dv.w3_0_hat_B;
  return ax;
}

double command_pipeline(const ReactionWheelParams& p, double u_cmd, double Omega)
{
  double u = u_cmd;
  if (p.u_max > 0.0) {  // 1. saturation
    if (u > p.u_max) u = p.u_max;
    if (u < -p.u_max) u = -p.u_max;
  }
  if (std::abs(u) < p.u_min) u = 0.0;  // 2. dead-band
  if (p.P_max > 0.0 && std::abs(u * Omega) >= p.P_max)  // 3. power limit (Omega != 0 here)
    u = std::copysign(std::abs(p.P_max / Omega), u);
  if (p.Omega_max > 0.0 && std::abs(Omega) >= p.Omega_max && u * Omega >= 0.0)  // 4. speed limit
    u = 0.0;
  return u;
}

namespace {
// f_mode(Omega) of §4.4 with sgn(Omega) given explicitly.
double resisting_function(const WheelFrictionParams& f, double Omega, double sgn, bool stribeck)
{
  if (stribeck) {
    const double b = f.beta_st;
    const double sqrt_2e = std::sqrt(2.0 * std::exp(1.0));
    return sqrt_2e * (f.tau_st - f.tau_c) * std::exp(-Omega * Omega / (2.0 * b * b)) * Omega /
               (std::sqrt(2.0) * b) +
           f.tau_c * std::tanh(10.0 * Omega / b) + f.c_v * Omega;
  }
  return f.tau_c * sgn + f.c_v * Omega;
}
}  // namespace

double friction_torque(const WheelFrictionParams& f, double Omega, bool stribeck)
{
  const bool s = stribeck && f.beta_st > 0.0;
  double fr;
  if (std::abs(Omega) < f.omega_lc) {
    fr = resisting_function(f, f.omega_lc, 1.0, s) * Omega / f.omega_lc;
  } else {
    fr = resisting_function(f, Omega, Omega > 0.0 ? 1.0 : -1.0, s);
  }
  return -fr;
}

bool update_stribeck_mode(const WheelFrictionParams& f, bool mode, double Omega, double dOmega)
{
  if (!(f.beta_st > 0.0)) return false;
  // §4.6: the regime describes breakaway, i.e. a wheel whose speed moves AWAY
  // from zero: sign(Omega) == sign(dOmega), or either is zero (at rest, or the
  // first step).  It is entered near zero (|Omega| < 0.1 omega_lc) and kept
  // only while that holds.  A wheel still slowing down toward zero never
  // enters it: its friction stays the Coulomb/viscous law, so a coasting wheel
  // decays at the low-speed-band rate instead of the much weaker Stribeck one.
  const bool away = Omega == 0.0 || dOmega == 0.0 || ((Omega > 0.0) == (dOmega > 0.0));
  if (!away) return false;
  return mode || std::abs(Omega) < 0.1 * f.omega_lc;
}

}  // namespace sim

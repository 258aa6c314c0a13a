// spacecraft: see sim/spacecraft.h.  Spec plant-dynamics §1-§4, §8.
#include "sim/spacecraft.h"

#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "sim/attitude.h"
#include "validate_util.h"

namespace sim {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Relative asymmetry accepted in a typed-in inertia matrix.
constexpr double kSymmetryTol = 1e-12;

// Per-wheel kinematic quantities at one stage (§4.2, §4.8).  Only the fields
// the wheel's model needs are filled.
struct WheelStage {
  WheelAxes ax;
  Matrix3d Iw_B;        // [kg*m^2]   FC rotor inertia about W_c
  Matrix3d Iw_prime_B;  // [kg*m^2/s] its B-frame derivative
  Vector3d r_WcB_B;     // [m]        rotor CoM relative to B
  Vector3d r_WcB_B_prime;  // [m/s]   its B-frame derivative
};

using WheelStages = std::array<WheelStage, kMaxWheels>;

void fill_stages(const SpacecraftParams& p, const std::vector<ReactionWheelDerived>& dv,
                 const StateLayout& L, const StateVector& x, WheelStages& st)
{
  for (int i = 0; i < L.num_rw; ++i) {
    const auto ui = static_cast<size_t>(i);
    const ReactionWheelParams& w = p.wheels[ui];
    const ReactionWheelDerived& d = dv[ui];
    WheelStage& s = st[ui];
    if (w.model == WheelModel::Balanced) {
      s.ax.gs_hat_B = d.gs_hat_B;  // theta is not part of the Balanced physics
      continue;
    }
    s.ax = wheel_axes(d, x(L.theta(i)));
    if (w.model != WheelModel::FullyCoupled) continue;

    // [BW] diag-like inertias in closed form (W axes gs, w2, w3 orthonormal):
    // Iw_B = J_s gs gs^T + J_t w2 w2^T + J_g w3 w3^T + J13 (gs w3^T + w3 gs^T)
    // Iw'_B = Omega (-J13 (gs w2^T + w2 gs^T) + (J_t - J_g)(w2 w3^T + w3 w2^T))
    const double Omega = x(L.Omega(i));
    const Vector3d& gs = s.ax.gs_hat_B;
    const Vector3d& w2 = s.ax.w2_hat_B;
    const Vector3d& w3 = s.ax.w3_hat_B;
    const Vector3d a = w.J_s * gs + d.J13 * w3;  // Iw_B gs
    const Vector3d b = d.J_t * w2;               // Iw_B w2
    const Vector3d c = d.J13 * gs + d.J_g * w3;  // Iw_B w3
    s.Iw_B.noalias() = a * gs.transpose();
    s.Iw_B.noalias() += b * w2.transpose();
    s.Iw_B.noalias() += c * w3.transpose();
    const Vector3d p2 = Omega * (d.J_t - d.J_g) * w3 - Omega * d.J13 * gs;  // Iw'_B w2
    const Vector3d p3 = Omega * (d.J_t - d.J_g) * w2;                        // Iw'_B w3
    s.Iw_prime_B.noalias() = (-Omega * d.J13) * w2 * gs.transpose();
    s.Iw_prime_B.noalias() += p2 * w2.transpose();
    s.Iw_prime_B.noalias() += p3 * w3.transpose();
    s.r_WcB_B = w.r_WB_B + d.d * s.ax.w2_hat_B;
    s.r_WcB_B_prime = d.d * Omega * s.ax.w3_hat_B;
  }
}

// m [r~][r~]^T = m ((r.r) I - r r^T)
Matrix3d parallel_axis(double m, const Vector3d& r)
{
  return m * (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose());
}

MassProps mass_props_from_stages(const SpacecraftParams& p, const HubParams& h,
                                 const StateLayout& L, const WheelStages& st)
{
  MassProps mp;
  mp.m_sc = h.m_h;
  Vector3d first_moment = h.m_h * h.r_BcB_B;
  Vector3d first_moment_prime = Vector3d::Zero();
  mp.I_sc_B = h.I_hBc_B + parallel_axis(h.m_h, h.r_BcB_B);
  mp.I_sc_prime_B.setZero();
  for (int i = 0; i < L.num_rw; ++i) {
    const auto ui = static_cast<size_t>(i);
    const ReactionWheelParams& w = p.wheels[ui];
    if (w.model != WheelModel::FullyCoupled) continue;
    const WheelStage& s = st[ui];
    mp.m_sc += w.m_w;
    first_moment += w.m_w * s.r_WcB_B;
    first_moment_prime += w.m_w * s.r_WcB_B_prime;
    mp.I_sc_B += s.Iw_B + parallel_axis(w.m_w, s.r_WcB_B);
    // m ([r'~][r~]^T + [r~][r'~]^T) = m (2 (r.r') I - r r'^T - r' r^T)
    const Vector3d& r = s.r_WcB_B;
    const Vector3d& rp = s.r_WcB_B_prime;
    mp.I_sc_prime_B += s.Iw_prime_B;
    mp.I_sc_prime_B.diagonal().array() += 2.0 * w.m_w * r.dot(rp);
    mp.I_sc_prime_B.noalias() -= (w.m_w * r) * rp.transpose();
    mp.I_sc_prime_B.noalias() -= (w.m_w * rp) * r.transpose();
  }
  mp.c_B = first_moment / mp.m_sc;
  mp.c_prime_B = first_moment_prime / mp.m_sc;
  return mp;
}

}  // namespace

// ---------------------------------------------------------------- validation

SpacecraftModel::SpacecraftModel(SpacecraftParams params, int num_tanks) : p_(std::move(params))
{
  using namespace detail;
  const HubParams& h = p_.hub;
  require_positive("hub.m_h", h.m_h);
  require_finite("hub.r_BcB_B", h.r_BcB_B);
  if (!h.I_hBc_B.allFinite()) fail("hub.I_hBc_B", h.I_hBc_B.cwiseAbs().maxCoeff(), "must be finite");
  const double asym = (h.I_hBc_B - h.I_hBc_B.transpose()).cwiseAbs().maxCoeff();
  if (asym > kSymmetryTol * h.I_hBc_B.cwiseAbs().maxCoeff())
    fail("hub.I_hBc_B (max |I - I^T|)", asym, "must be symmetric");
  const Matrix3d I_sym = 0.5 * (h.I_hBc_B + h.I_hBc_B.transpose());
  const double min_eig = Eigen::SelfAdjointEigenSolver<Matrix3d>(I_sym).eigenvalues().minCoeff();
  if (!(min_eig > 0.0)) fail("hub.I_hBc_B (min eigenvalue)", min_eig, "must be positive definite");
  require_non_negative("mu", p_.mu);

  const size_t n = p_.wheels.size();
  if (n > static_cast<size_t>(kMaxWheels))
    fail("wheels.size()", static_cast<double>(n), "must be <= sim::kMaxWheels");
  Matrix3d I_less_spin = I_sym;  // hub must contain the Balanced/Simple wheels' J_s (§2, trap 2)
  for (size_t i = 0; i < n; ++i) {
    const ReactionWheelParams& w = p_.wheels[i];
    validate(w, "wheels[" + std::to_string(i) + "]");
    derived_.push_back(derive(w));
    if (w.model != WheelModel::FullyCoupled)
      I_less_spin -= w.J_s * derived_.back().gs_hat_B * derived_.back().gs_hat_B.transpose();
  }
  const double min_eig_less =
      Eigen::SelfAdjointEigenSolver<Matrix3d>(I_less_spin).eigenvalues().minCoeff();
  if (!(min_eig_less > 0.0))
    fail("hub.I_hBc_B - sum(J_s gs gs^T) (min eigenvalue)", min_eig_less,
         "hub inertia must include the spin inertia of Balanced/SimpleJitter wheels");
  if (num_tanks < 0 || num_tanks > kMaxTanks)
    fail("tanks.size()", num_tanks, "must be <= sim::kMaxTanks");
  layout_.num_rw = static_cast<int>(n);
  layout_.num_tanks = num_tanks;
}

void SpacecraftModel::check_wheel_index(int i) const
{
  if (i < 0 || i >= num_rw()) detail::fail("wheel index", i, "must be in [0, num_rw)");
}

void SpacecraftModel::set_wheel_u_max(int i, double u_max)
{
  check_wheel_index(i);
  detail::require_finite("wheels[" + std::to_string(i) + "].u_max", u_max);
  p_.wheels[static_cast<size_t>(i)].u_max = u_max;
}

void SpacecraftModel::set_wheel_Omega_max(int i, double Omega_max)
{
  check_wheel_index(i);
  detail::require_finite("wheels[" + std::to_string(i) + "].Omega_max", Omega_max);
  p_.wheels[static_cast<size_t>(i)].Omega_max = Omega_max;
}

void SpacecraftModel::set_wheel_friction(int i, const WheelFrictionParams& f)
{
  check_wheel_index(i);
  validate(f, "wheels[" + std::to_string(i) + "].friction");
  p_.wheels[static_cast<size_t>(i)].friction = f;
}

// -------------------------------------------------------------- initial state

StateVector SpacecraftModel::initial_state(const InitialConditions& ic, const HubParams& hub) const
{
  detail::require_finite("ic.r_CN_N", ic.r_CN_N);
  detail::require_finite("ic.v_CN_N", ic.v_CN_N);
  detail::require_finite("ic.sigma_BN", ic.sigma_BN);
  detail::require_finite("ic.omega_BN_B", ic.omega_BN_B);
  StateVector x(layout_.size());
  x.setZero();
  x.segment<3>(StateLayout::sigma_BN) = ic.sigma_BN;
  x.segment<3>(StateLayout::omega_BN_B) = ic.omega_BN_B;
  for (int i = 0; i < num_rw(); ++i) x(layout_.Omega(i)) = p_.wheels[static_cast<size_t>(i)].Omega_0;
  // r_B = r_C - [NB] c,  v_B = v_C - [NB](c' + omega x c)   (§1)
  const MassProps mp = mass_props(x, hub);
  const Matrix3d dcm_NB = dcm_BN_from_sigma(ic.sigma_BN).transpose();
  x.segment<3>(StateLayout::r_BN_N) = ic.r_CN_N - dcm_NB * mp.c_B;
  x.segment<3>(StateLayout::v_BN_N) =
      ic.v_CN_N - dcm_NB * (mp.c_prime_B + ic.omega_BN_B.cross(mp.c_B));
  return x;
}

MassProps SpacecraftModel::mass_props(const StateVector& x, const HubParams& hub) const
{
  WheelStages st;
  fill_stages(p_, derived_, layout_, x, st);
  return mass_props_from_stages(p_, hub, layout_, st);
}

double SpacecraftModel::friction_torque(int i, const StateVector& x, bool stribeck) const
{
  return sim::friction_torque(p_.wheels[static_cast<size_t>(i)].friction, x(layout_.Omega(i)),
                              stribeck);
}

// ---------------------------------------------------------------- derivatives

StateVector SpacecraftModel::derivatives(double /*t*/, const StateVector& x, const WheelInputs& in,
                                         const ExternalLoads& loads, const HubParams& hub,
                                         Accelerations* acc) const
{
  const int n = num_rw();
  const Vector3d v_BN_N = x.segment<3>(StateLayout::v_BN_N);
  const Vector3d sigma_BN = x.segment<3>(StateLayout::sigma_BN);
  const Vector3d omega = x.segment<3>(StateLayout::omega_BN_B);
  const Matrix3d dcm_BN = dcm_BN_from_sigma(sigma_BN);

  WheelStages st;
  fill_stages(p_, derived_, layout_, x, st);
  const MassProps mp = mass_props_from_stages(p_, hub, layout_, st);
  const double m = mp.m_sc;
  const Vector3d& c = mp.c_B;

  // Point-mass gravity at the system CoM (§3).
  Vector3d g_B = Vector3d::Zero();
  if (p_.mu > 0.0) {
    const Vector3d r_CN_N = x.segment<3>(StateLayout::r_BN_N) + dcm_BN.transpose() * c;
    const double r = r_CN_N.norm();
    g_B = dcm_BN * (-p_.mu / (r * r * r) * r_CN_N);
  }

  // Hub part (§3).
  Matrix3d A = m * Matrix3d::Identity();
  Matrix3d B = -m * skew(c);
  Matrix3d C = m * skew(c);
  Matrix3d D = mp.I_sc_B;
  Vector3d v_trans = loads.F_ext_B + m * g_B - 2.0 * m * omega.cross(mp.c_prime_B) -
                     m * omega.cross(omega.cross(c));
  Vector3d v_rot = loads.L_ext_B + c.cross(m * g_B) - omega.cross(mp.I_sc_B * omega) -
                   mp.I_sc_prime_B * omega;

  // Wheel contributions (§4.9); Omega_dot = a_Omega . r_ddot_B + b_Omega . omega_dot + c_Omega.
  std::array<Vector3d, kMaxWheels> a_Omega;
  std::array<Vector3d, kMaxWheels> b_Omega;
  WheelArray c_Omega;  // entries [0, n) written below
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    const ReactionWheelParams& w = p_.wheels[ui];
    const ReactionWheelDerived& dv = derived_[ui];
    const WheelStage& s = st[ui];
    const Vector3d& gs = s.ax.gs_hat_B;
    const double Omega = x(layout_.Omega(i));
    const bool stuck = in.stuck[ui];  // Omega' = 0: no substitution of the wheel equation
    const double u_tot = stuck ? 0.0 : in.u_s[ui] + sim::friction_torque(w.friction, Omega, in.stribeck[ui]);

    if (w.model != WheelModel::FullyCoupled) {
      if (stuck) {  // the rotor turns with the hub: all of J_s stays in D, no axial torque
        v_rot -= w.J_s * Omega * omega.cross(gs);
        a_Omega[ui].setZero();
        b_Omega[ui].setZero();
        c_Omega[ui] = 0.0;
      } else {
        D.noalias() -= (w.J_s * gs) * gs.transpose();
        v_rot -= gs * u_tot + w.J_s * Omega * omega.cross(gs);
        a_Omega[ui].setZero();
        b_Omega[ui] = -gs;
        c_Omega[ui] = u_tot / w.J_s;
      }
      if (w.model == WheelModel::SimpleJitter) {
        const double Omega2 = Omega * Omega;
        const Vector3d F_s = w.U_s * Omega2 * s.ax.w2_hat_B;
        v_trans += F_s;
        v_rot += w.r_WB_B.cross(F_s) + w.U_d * Omega2 * s.ax.w2_hat_B;
      }
      continue;
    }

    // FullyCoupled.
    const Vector3d& w2 = s.ax.w2_hat_B;
    const Vector3d& w3 = s.ax.w3_hat_B;
    const double mw = w.m_w;
    const double d = dv.d;
    const double J_bar = dv.J_bar;
    const double omega_s = gs.dot(omega);
    const double omega_2 = w2.dot(omega);
    const double omega_3 = w3.dot(omega);
    const Vector3d& r_W = w.r_WB_B;
    const Vector3d& r_Wc = s.r_WcB_B;

    const double md = mw * d;
    const Vector3d Iw_gs = w.J_s * gs + dv.J13 * w3;  // [Iw_B] gs (fill_stages)
    if (stuck) {  // the terms of the wheel equation's substitution all carry Omega': none
      a_Omega[ui].setZero();
      b_Omega[ui].setZero();
      c_Omega[ui] = 0.0;
      const double Omega2 = Omega * Omega;
      v_trans += md * Omega2 * w2;
      v_rot += md * Omega2 * r_Wc.cross(w2) + (Omega2 * dv.J13) * w2 -
               omega.cross(Omega * Iw_gs + mw * r_Wc.cross(s.r_WcB_B_prime));
      continue;
    }
    const double inv_J = 1.0 / J_bar;
    const double kA = md * inv_J;
    a_Omega[ui] = -kA * w3;
    b_Omega[ui] = -gs - inv_J * (dv.J13 * w3 + md * r_W.cross(w3));
    c_Omega[ui] = inv_J * (omega_2 * omega_3 * (dv.J_t - dv.J_g - md * d) - dv.J13 * omega_2 * omega_s -
                           md * w3.dot(omega.cross(omega.cross(r_W))) + u_tot + md * w3.dot(g_B));
    const Vector3d q = Iw_gs + md * r_Wc.cross(w3);

    // Outer products accumulated in place (noalias: no temporaries).
    A.noalias() -= (md * kA) * w3 * w3.transpose();  // (m_w d) w3 a_Omega^T
    B.noalias() += (md * w3) * b_Omega[ui].transpose();
    C.noalias() -= (kA * q) * w3.transpose();  // q a_Omega^T
    D.noalias() += q * b_Omega[ui].transpose();
    const double Omega2 = Omega * Omega;
    v_trans += md * (Omega2 * w2 - c_Omega[ui] * w3);
    v_rot += md * Omega2 * r_Wc.cross(w2) + (Omega2 * dv.J13) * w2 -
             omega.cross(Omega * Iw_gs + mw * r_Wc.cross(s.r_WcB_B_prime)) - c_Omega[ui] * q;
  }

  // Back-substitution solve (§3).  A is m I less a positive semi-definite
  // wheel part and D - C A^-1 B an inertia-like matrix (slightly
  // non-symmetric with FC terms: never Cholesky): both well conditioned, so
  // the 3x3 inverses by cofactors (Eigen's fixed-size path) are as accurate
  // as a pivoted LU and several times cheaper.
  const Matrix3d A_inv = A.inverse();
  Matrix3d Ainv_B;
  Ainv_B.noalias() = A_inv * B;
  const Vector3d Ainv_v = A_inv * v_trans;
  Matrix3d M = D;
  M.noalias() -= C * Ainv_B;
  const Vector3d omega_dot = M.inverse() * (v_rot - C * Ainv_v);
  const Vector3d r_ddot_B = Ainv_v - Ainv_B * omega_dot;

  StateVector xd(layout_.size());
  xd.segment<3>(StateLayout::r_BN_N) = v_BN_N;
  xd.segment<3>(StateLayout::v_BN_N) = dcm_BN.transpose() * r_ddot_B;
  xd.segment<3>(StateLayout::sigma_BN) = sigma_dot_from_omega(sigma_BN, omega);
  xd.segment<3>(StateLayout::omega_BN_B) = omega_dot;
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    xd(layout_.Omega(i)) = a_Omega[ui].dot(r_ddot_B) + b_Omega[ui].dot(omega_dot) + c_Omega[ui];
    xd(layout_.theta(i)) = x(layout_.Omega(i));
  }
  for (int k = 0; k < layout_.num_tanks; ++k) xd(layout_.m_p(k)) = 0.0;  // mass flows: the Plant's
  if (acc != nullptr) {
    acc->omega_dot_BN_B = omega_dot;
    acc->r_ddot_BN_B = r_ddot_B;
  }
  return xd;
}

// ----------------------------------------------------------- energy, momentum

EnergyMomentum SpacecraftModel::energy_momentum(const StateVector& x, const HubParams& hub) const
{
  WheelStages st;
  fill_stages(p_, derived_, layout_, x, st);
  const MassProps mp = mass_props_from_stages(p_, hub, layout_, st);
  const Vector3d sigma_BN = x.segment<3>(StateLayout::sigma_BN);
  const Vector3d omega = x.segment<3>(StateLayout::omega_BN_B);
  const Matrix3d dcm_NB = dcm_BN_from_sigma(sigma_BN).transpose();
  const HubParams& h = hub;
  const Vector3d c_dot = mp.c_prime_B + omega.cross(mp.c_B);

  EnergyMomentum em;
  em.r_CN_N = x.segment<3>(StateLayout::r_BN_N) + dcm_NB * mp.c_B;
  em.v_CN_N = x.segment<3>(StateLayout::v_BN_N) + dcm_NB * c_dot;
  const double r = em.r_CN_N.norm();
  em.E_orb = 0.5 * mp.m_sc * em.v_CN_N.squaredNorm() - (p_.mu > 0.0 ? p_.mu * mp.m_sc / r : 0.0);
  em.H_orb_N = mp.m_sc * em.r_CN_N.cross(em.v_CN_N);

  const Vector3d hub_vel = omega.cross(h.r_BcB_B);
  Vector3d H = h.I_hBc_B * omega + h.m_h * h.r_BcB_B.cross(hub_vel);
  double E = 0.5 * omega.dot(h.I_hBc_B * omega) + 0.5 * h.m_h * hub_vel.squaredNorm();
  for (int i = 0; i < num_rw(); ++i) {
    const auto ui = static_cast<size_t>(i);
    const ReactionWheelParams& w = p_.wheels[ui];
    const WheelStage& s = st[ui];
    const Vector3d& gs = s.ax.gs_hat_B;
    const double Omega = x(layout_.Omega(i));
    if (w.model != WheelModel::FullyCoupled) {
      H += w.J_s * Omega * gs;
      E += 0.5 * w.J_s * Omega * Omega + w.J_s * Omega * gs.dot(omega);
    } else {
      const Vector3d omega_W = omega + Omega * gs;
      const Vector3d r_Wc_dot = s.r_WcB_B_prime + omega.cross(s.r_WcB_B);
      H += s.Iw_B * omega_W + w.m_w * s.r_WcB_B.cross(r_Wc_dot);
      E += 0.5 * omega_W.dot(s.Iw_B * omega_W) + 0.5 * w.m_w * r_Wc_dot.squaredNorm();
    }
  }
  em.H_C_B = H - mp.m_sc * mp.c_B.cross(c_dot);
  em.E_rot = E - 0.5 * mp.m_sc * c_dot.squaredNorm();
  em.H_C_N = dcm_NB * em.H_C_B;
  return em;
}

}  // namespace sim

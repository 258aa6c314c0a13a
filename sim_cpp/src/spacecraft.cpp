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

    const double Omega = x(L.Omega(i));
    Matrix3d dcm_BW;
    dcm_BW.col(0) = s.ax.gs_hat_B;
    dcm_BW.col(1) = s.ax.w2_hat_B;
    dcm_BW.col(2) = s.ax.w3_hat_B;
    Matrix3d Iw_W;
    Iw_W << w.J_s, 0.0, d.J13,
            0.0, d.J_t, 0.0,
            d.J13, 0.0, d.J_g;
    Matrix3d Iw_prime_W;
    Iw_prime_W << 0.0, -d.J13, 0.0,
                  -d.J13, 0.0, d.J_t - d.J_g,
                  0.0, d.J_t - d.J_g, 0.0;
    Iw_prime_W *= Omega;
    s.Iw_B = dcm_BW * Iw_W * dcm_BW.transpose();
    s.Iw_prime_B = dcm_BW * Iw_prime_W * dcm_BW.transpose();
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
    const Matrix3d r_tilde = skew(s.r_WcB_B);
    const Matrix3d r_tilde_prime = skew(s.r_WcB_B_prime);
    mp.m_sc += w.m_w;
    first_moment += w.m_w * s.r_WcB_B;
    first_moment_prime += w.m_w * s.r_WcB_B_prime;
    mp.I_sc_B += s.Iw_B + parallel_axis(w.m_w, s.r_WcB_B);
    mp.I_sc_prime_B += s.Iw_prime_B + w.m_w * (r_tilde_prime * r_tilde.transpose() +
                                               r_tilde * r_tilde_prime.transpose());
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
    const double u_tot =
        in.u_s[ui] + sim::friction_torque(w.friction, Omega, in.stribeck[ui]);

    if (w.model != WheelModel::FullyCoupled) {
      D -= w.J_s * gs * gs.transpose();
      v_rot -= gs * u_tot + w.J_s * Omega * omega.cross(gs);
      a_Omega[ui].setZero();
      b_Omega[ui] = -gs;
      c_Omega[ui] = u_tot / w.J_s;
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

    a_Omega[ui] = -(mw * d / J_bar) * w3;
    b_Omega[ui] = -(1.0 / J_bar) * (J_bar * gs + dv.J13 * w3 + mw * d * r_W.cross(w3));
    c_Omega[ui] = (1.0 / J_bar) *
                  (omega_2 * omega_3 * (dv.J_t - dv.J_g - mw * d * d) -
                   dv.J13 * omega_2 * omega_s - mw * d * w3.dot(omega.cross(omega.cross(r_W))) +
                   u_tot + mw * d * w3.dot(g_B));
    const Vector3d Iw_gs = s.Iw_B * gs;
    const Vector3d q = Iw_gs + mw * d * r_Wc.cross(w3);

    A += (mw * d) * w3 * a_Omega[ui].transpose();
    B += (mw * d) * w3 * b_Omega[ui].transpose();
    C += q * a_Omega[ui].transpose();
    D += q * b_Omega[ui].transpose();
    v_trans += mw * d * (Omega * Omega * w2 - c_Omega[ui] * w3);
    v_rot += mw * d * Omega * Omega * r_Wc.cross(w2) - Omega * (s.Iw_prime_B * gs) -
             omega.cross(Omega * Iw_gs + mw * r_Wc.cross(s.r_WcB_B_prime)) - c_Omega[ui] * q;
  }

  // Back-substitution solve (§3): 3x3 LU with partial pivoting, never Cholesky
  // (FC terms make D - C A^-1 B slightly non-symmetric).
  const Eigen::PartialPivLU<Matrix3d> A_lu(A);
  const Matrix3d Ainv_B = A_lu.solve(B);
  const Vector3d Ainv_v = A_lu.solve(v_trans);
  const Matrix3d M = D - C * Ainv_B;
  const Vector3d omega_dot = Eigen::PartialPivLU<Matrix3d>(M).solve(v_rot - C * Ainv_v);
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

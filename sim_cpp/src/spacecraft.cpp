// spacecraft: see sim/spacecraft.h.  docs/dynamics.md §1-§4, §8.
#include "sim/spacecraft.h"

#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "sim/attitude.h"
#include "sim/environment.h"
#include "sim/sin_cos.h"
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

// cos and sin of the jittering wheels' rotor angles, in a loop of their own
// (sin_cos inlined here, not in the derivative's body: there it made the
// Balanced path, which needs none, 10 % slower).
#if defined(__GNUC__)
__attribute__((noinline))
#endif
void rotor_sin_cos(const SpacecraftParams& p, const StateLayout& L, const StateVector& x,
                   std::array<SinCos, kMaxWheels>& out)
{
  for (int i = 0; i < L.num_rw; ++i) {
    const auto ui = static_cast<size_t>(i);
    if (p.wheels[ui].model != WheelModel::Balanced) out[ui] = sin_cos(x(L.theta(i)));
  }
}

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

// Rank updates of 3x3 matrices written out (Eigen's outer-product
// assignment is an out-of-line loop, measurably slower here).
// M += a b^T + b a^T
inline void add_sym2(Matrix3d& M, const Vector3d& a, const Vector3d& b)
{
  const double xx = 2.0 * a.x() * b.x(), yy = 2.0 * a.y() * b.y(), zz = 2.0 * a.z() * b.z();
  const double xy = a.x() * b.y() + a.y() * b.x();
  const double xz = a.x() * b.z() + a.z() * b.x();
  const double yz = a.y() * b.z() + a.z() * b.y();
  M(0, 0) += xx; M(1, 1) += yy; M(2, 2) += zz;
  M(0, 1) += xy; M(1, 0) += xy;
  M(0, 2) += xz; M(2, 0) += xz;
  M(1, 2) += yz; M(2, 1) += yz;
}

// M += s a a^T
inline void add_sym1(Matrix3d& M, double s, const Vector3d& a)
{
  const Vector3d sa = s * a;
  const double xy = sa.x() * a.y(), xz = sa.x() * a.z(), yz = sa.y() * a.z();
  M(0, 0) += sa.x() * a.x(); M(1, 1) += sa.y() * a.y(); M(2, 2) += sa.z() * a.z();
  M(0, 1) += xy; M(1, 0) += xy;
  M(0, 2) += xz; M(2, 0) += xz;
  M(1, 2) += yz; M(2, 1) += yz;
}

// M += a b^T
inline void add_outer(Matrix3d& M, const Vector3d& a, const Vector3d& b)
{
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) M(row, col) += a(row) * b(col);
}

// Inverse of a symmetric 3x3 matrix by cofactors, from its lower triangle.
inline Matrix3d inverse_sym3(const Matrix3d& M)
{
  const double a = M(0, 0), b = M(1, 0), c = M(2, 0), d = M(1, 1), e = M(2, 1), f = M(2, 2);
  const double c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
  const double inv_det = 1.0 / (a * c00 + b * c01 + c * c02);
  const double i00 = c00 * inv_det, i01 = c01 * inv_det, i02 = c02 * inv_det;
  const double i11 = (a * f - c * c) * inv_det, i12 = (b * c - a * e) * inv_det, i22 = (a * d - b * b) * inv_det;
  Matrix3d R;
  R << i00, i01, i02, i01, i11, i12, i02, i12, i22;
  return R;
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
  require_non_negative("J2", p_.J2);
  require_non_negative("R_J2", p_.R_J2);
  if (p_.J2 > 0.0 && !(p_.mu > 0.0)) fail("J2", p_.J2, "needs gravity: mu > 0");
  if (p_.J2 > 0.0 && !(p_.R_J2 > 0.0)) fail("R_J2", p_.R_J2, "must be > 0 when J2 > 0");

  const size_t n = p_.wheels.size();
  if (n > static_cast<size_t>(kMaxWheels))
    fail("wheels.size()", static_cast<double>(n), "must be <= sim::kMaxWheels");
  Matrix3d I_less_spin = I_sym;  // hub must contain the Balanced/Simple wheels' J_s (docs/dynamics.md §2)
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
  init_rotor_constants();
}

void SpacecraftModel::init_rotor_constants()
{
  // docs/dynamics.md "The derivative as computed": with w2 w2^T + w3 w3^T =
  // I - gs gs^T, a fully-coupled rotor's [I_w] plus its parallel-axis term
  // m_w ((r.r) I - r r^T), r = r_W + d w2, is
  //   J_g I + (J_s - J_g) gs gs^T + m_w (|r_W|^2 + d^2) I - m_w r_W r_W^T     (fixed in B)
  //   + alpha w2 w2^T + J13 sym(gs, w3) + 2 m_w d (r_W.w2) I - m_w d sym(r_W, w2)
  // with alpha = J_t - J_g - m_w d^2 and sym(a, b) = a b^T + b a^T.
  rc_.assign(p_.wheels.size(), RotorConstants{});
  for (size_t i = 0; i < p_.wheels.size(); ++i) {
    const ReactionWheelParams& w = p_.wheels[i];
    const ReactionWheelDerived& dv = derived_[i];
    RotorConstants& k = rc_[i];
    const Vector3d& gs = dv.gs_hat_B;
    k.inv_J = 1.0 / dv.J_bar;
    if (w.model != WheelModel::Balanced) any_rotor_angle_ = true;
    if (w.model != WheelModel::FullyCoupled) {
      J_spin_B_.noalias() += (w.J_s * gs) * gs.transpose();
      continue;
    }
    any_fc_ = true;
    k.md = w.m_w * dv.d;
    k.kA = k.md * k.inv_J;
    k.alpha = dv.J_t - dv.J_g - k.md * dv.d;
    k.rW_w2_0 = w.r_WB_B.dot(dv.w2_0_hat_B);
    k.rW_w3_0 = w.r_WB_B.dot(dv.w3_0_hat_B);
    k.rW_x_w2_0 = w.r_WB_B.cross(dv.w2_0_hat_B);
    k.rW_x_w3_0 = w.r_WB_B.cross(dv.w3_0_hat_B);
    m_fc_ += w.m_w;
    first_moment_fc_ += w.m_w * w.r_WB_B;
    I_fc_const_B_.diagonal().array() += dv.J_g + w.m_w * (w.r_WB_B.squaredNorm() + dv.d * dv.d);
    I_fc_const_B_.noalias() += ((w.J_s - dv.J_g) * gs) * gs.transpose();
    I_fc_const_B_.noalias() -= (w.m_w * w.r_WB_B) * w.r_WB_B.transpose();
  }
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

void SpacecraftModel::rotor_sin_cos(const StateVector& x, RotorSinCos& out) const
{
  sim::rotor_sin_cos(p_, layout_, x, out);
}

MassCentre SpacecraftModel::mass_centre(const StateVector& x, const HubParams& hub, const RotorSinCos* sc) const
{
  // as in derivatives(): sum m_w r_Wc = sum m_w r_W + m_w d w2(theta)
  MassCentre mc;
  mc.m_sc = hub.m_h + m_fc_;
  Vector3d first_moment = hub.m_h * hub.r_BcB_B + first_moment_fc_;
  for (int i = 0; i < num_rw(); ++i) {
    const auto ui = static_cast<size_t>(i);
    if (p_.wheels[ui].model != WheelModel::FullyCoupled) continue;
    const ReactionWheelDerived& dv = derived_[ui];
    const SinCos th = sc ? (*sc)[ui] : sin_cos(x(layout_.theta(i)));
    first_moment += rc_[ui].md * (th.c * dv.w2_0_hat_B + th.s * dv.w3_0_hat_B);
  }
  mc.c_B = first_moment / mc.m_sc;
  return mc;
}

double SpacecraftModel::friction_torque(int i, const StateVector& x, bool stribeck) const
{
  return sim::friction_torque(p_.wheels[static_cast<size_t>(i)].friction, x(layout_.Omega(i)),
                              stribeck);
}

// ---------------------------------------------------------------- derivatives

StateVector SpacecraftModel::derivatives(double /*t*/, const StateVector& x, const WheelInputs& in,
                                         const ExternalLoads& loads, const HubParams& hub,
                                         Accelerations* acc, const RotorSinCos* sc) const
{
  // docs/dynamics.md "The derivative as computed": the equations of §3 and
  // §4.9 with the rotor-angle-dependent inertia terms formed as vectors, the
  // parts fixed in B taken from init_rotor_constants, and the block system
  // written symmetric (B = C^T, D symmetric).
  const int n = num_rw();
  const Vector3d sigma_BN = x.segment<3>(StateLayout::sigma_BN);
  const Vector3d omega = x.segment<3>(StateLayout::omega_BN_B);
  const Matrix3d dcm_BN = dcm_BN_from_sigma(sigma_BN);

  // Pass 1: rotor axes and the rotor-angle-dependent mass properties.
  struct Rotor {
    Vector3d w2, w3;          // rotor axes (jitter wheels)
    double cth, sth;          // cos, sin theta
    double om_s, om_2, om_3;  // omega . gs, w2, w3 (FC)
    double rW_w3;             // r_W . w3 (FC)
  };
  std::array<Rotor, kMaxWheels> ro;
  RotorSinCos rotor_own;
  if (any_rotor_angle_ && !sc) sim::rotor_sin_cos(p_, layout_, x, rotor_own);
  const RotorSinCos& rotor_sc = sc ? *sc : rotor_own;
  const double m = hub.m_h + m_fc_;
  Vector3d first_moment = hub.m_h * hub.r_BcB_B + first_moment_fc_;
  Vector3d first_moment_prime = Vector3d::Zero();
  Matrix3d I_sc = hub.I_hBc_B + I_fc_const_B_;  // about B
  I_sc.diagonal().array() += hub.m_h * hub.r_BcB_B.squaredNorm();
  I_sc.noalias() -= (hub.m_h * hub.r_BcB_B) * hub.r_BcB_B.transpose();
  Vector3d I_prime_omega = Vector3d::Zero();  // [I_sc]' omega
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    const WheelModel model = p_.wheels[ui].model;
    if (model == WheelModel::Balanced) continue;
    const ReactionWheelDerived& dv = derived_[ui];
    Rotor& r = ro[ui];
    r.cth = rotor_sc[ui].c;
    r.sth = rotor_sc[ui].s;
    r.w2 = r.cth * dv.w2_0_hat_B + r.sth * dv.w3_0_hat_B;
    r.w3 = r.cth * dv.w3_0_hat_B - r.sth * dv.w2_0_hat_B;
    if (model != WheelModel::FullyCoupled) continue;
    const RotorConstants& k = rc_[ui];
    const Vector3d& gs = dv.gs_hat_B;
    const Vector3d& w2 = r.w2;
    const Vector3d& w3 = r.w3;
    const Vector3d& r_W = p_.wheels[ui].r_WB_B;
    const double Omega = x(layout_.Omega(i));
    const double J13 = dv.J13;
    r.om_s = gs.dot(omega);
    r.om_2 = w2.dot(omega);
    r.om_3 = w3.dot(omega);
    const double rW_w2 = r.cth * k.rW_w2_0 + r.sth * k.rW_w3_0;
    r.rW_w3 = r.cth * k.rW_w3_0 - r.sth * k.rW_w2_0;
    first_moment += k.md * w2;
    first_moment_prime += (k.md * Omega) * w3;
    // alpha w2 w2^T - m d sym(r_W, w2) = sym(w2, alpha/2 w2 - m d r_W)
    const Vector3d p2 = (0.5 * k.alpha) * w2 - k.md * r_W;
    const Vector3d p3 = J13 * w3;
    add_sym2(I_sc, w2, p2);
    add_sym2(I_sc, gs, p3);
    I_sc.diagonal().array() += 2.0 * k.md * rW_w2;
    // d/dt of those terms (w2' = Omega w3, w3' = -Omega w2), times omega
    I_prime_omega += Omega * (k.alpha * (r.om_2 * w3 + r.om_3 * w2) - J13 * (r.om_2 * gs + r.om_s * w2) +
                              (2.0 * k.md * r.rW_w3) * omega -
                              k.md * (r.om_3 * r_W + r_W.dot(omega) * w3));
  }
  const Vector3d c = first_moment / m;
  const Vector3d c_prime = first_moment_prime / m;

  // Point-mass gravity at the system CoM (§3), and J2 when set.
  Vector3d g_B = Vector3d::Zero();
  if (p_.mu > 0.0) {
    const Vector3d r_CN_N = x.segment<3>(StateLayout::r_BN_N) + dcm_BN.transpose() * c;
    const double r = r_CN_N.norm();
    if (p_.J2 == 0.0)
      g_B = dcm_BN * (-p_.mu / (r * r * r) * r_CN_N);
    else
      g_B = dcm_BN * (-p_.mu / (r * r * r) * r_CN_N + j2_acceleration(p_.mu, p_.J2, p_.R_J2, r_CN_N));
  }

  // Hub part (§3): [A C^T; C D] [r_ddot; omega_dot] = [v_trans; v_rot].
  Matrix3d A = m * Matrix3d::Identity();
  Matrix3d C = m * skew(c);
  Matrix3d D = I_sc - J_spin_B_;
  Vector3d v_trans = loads.F_ext_B + m * g_B - 2.0 * m * omega.cross(c_prime) - m * omega.cross(omega.cross(c));
  Vector3d v_rot = loads.L_ext_B + c.cross(m * g_B) - omega.cross(I_sc * omega) - I_prime_omega;

  // Pass 2, the wheel equations (§4.9):
  //   Omega_dot = -kA w3 . r_ddot - (q . omega_dot) / J_bar + c_Omega
  // with q = J_bar gs + J13 w3 + m d (r_W x w3) for a FC wheel (q = gs,
  // kA = 0 otherwise); substituted, they add -kA m d w3 w3^T to A,
  // -kA q w3^T to C and -q q^T / J_bar to D.
  std::array<Vector3d, kMaxWheels> q;
  WheelArray kA;
  WheelArray inv_J;
  WheelArray c_Omega;
  const double omega_sq = omega.squaredNorm();
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    const ReactionWheelParams& w = p_.wheels[ui];
    const ReactionWheelDerived& dv = derived_[ui];
    const RotorConstants& k = rc_[ui];
    const Rotor& r = ro[ui];
    const Vector3d& gs = dv.gs_hat_B;
    const double Omega = x(layout_.Omega(i));
    const bool stuck = in.stuck[ui];  // Omega' = 0: no substitution of the wheel equation
    const double u_tot = stuck ? 0.0 : in.u_s[ui] + sim::friction_torque(w.friction, Omega, in.stribeck[ui]);

    if (w.model != WheelModel::FullyCoupled) {
      v_rot -= (w.J_s * Omega) * omega.cross(gs);
      if (stuck) {  // the rotor turns with the hub: all of J_s stays in D, no axial torque
        add_sym1(D, w.J_s, gs);
        q[ui].setZero();
        kA[ui] = 0.0;
        inv_J[ui] = 0.0;
        c_Omega[ui] = 0.0;
      } else {
        v_rot -= u_tot * gs;
        q[ui] = gs;
        kA[ui] = 0.0;
        inv_J[ui] = 1.0;
        c_Omega[ui] = u_tot * k.inv_J;
      }
      if (w.model == WheelModel::SimpleJitter) {
        const double Omega2 = Omega * Omega;
        const Vector3d F_s = (w.U_s * Omega2) * r.w2;
        v_trans += F_s;
        v_rot += w.r_WB_B.cross(F_s) + (w.U_d * Omega2) * r.w2;
      }
      continue;
    }

    // FullyCoupled.
    const Vector3d& w2 = r.w2;
    const Vector3d& w3 = r.w3;
    const double md = k.md;
    const double J13 = dv.J13;
    const Vector3d rW_x_w3 = r.cth * k.rW_x_w3_0 - r.sth * k.rW_x_w2_0;
    const Vector3d rW_x_w2 = r.cth * k.rW_x_w2_0 + r.sth * k.rW_x_w3_0;
    const Vector3d qi = dv.J_bar * gs + J13 * w3 + md * rW_x_w3;
    // The rotor's relative-motion terms: Omega^2 (m d (r_Wc x w2) + J13 w2)
    // and -omega x (Omega q) (its momentum Omega [I_w] gs + m_w r_Wc x r_Wc').
    const double Omega2 = Omega * Omega;
    v_trans += (md * Omega2) * w2;
    v_rot += Omega2 * (md * rW_x_w2 + J13 * w2) - Omega * omega.cross(qi);
    if (stuck) {  // the terms of the wheel equation's substitution all carry Omega': none
      q[ui].setZero();
      kA[ui] = 0.0;
      inv_J[ui] = 0.0;
      c_Omega[ui] = 0.0;
      continue;
    }
    // w3 . (omega x (omega x r_W)) = om_3 (omega . r_W) - |omega|^2 (r_W . w3)
    const double w3_wwr = r.om_3 * w.r_WB_B.dot(omega) - omega_sq * r.rW_w3;
    const double cO = k.inv_J * (r.om_2 * r.om_3 * k.alpha - J13 * r.om_2 * r.om_s - md * w3_wwr + u_tot +
                                 md * w3.dot(g_B));
    add_sym1(A, -md * k.kA, w3);
    add_outer(C, -k.kA * qi, w3);
    add_sym1(D, -k.inv_J, qi);
    v_trans -= (cO * md) * w3;
    v_rot -= cO * qi;
    q[ui] = qi;
    kA[ui] = k.kA;
    inv_J[ui] = k.inv_J;
    c_Omega[ui] = cO;
  }

  // Back-substitution solve (§3).  A is m I less a positive semi-definite
  // wheel part and M = D - C A^-1 C^T the system's inertia about B less the
  // rotors' spin parts: both symmetric positive definite and well
  // conditioned, so the 3x3 inverses by cofactors are as accurate as a
  // pivoted LU and several times cheaper.
  // Without fully-coupled wheels A = m I exactly.
  Matrix3d Ainv_Ct;
  Vector3d Ainv_v;
  if (any_fc_) {
    const Matrix3d A_inv = inverse_sym3(A);
    Ainv_Ct.noalias() = A_inv * C.transpose();
    Ainv_v.noalias() = A_inv * v_trans;
  } else {
    Ainv_Ct = C.transpose() / m;
    Ainv_v = v_trans / m;
  }
  Matrix3d M = D;  // symmetric: its lower triangle is used
  M.noalias() -= C * Ainv_Ct;
  const Vector3d omega_dot = inverse_sym3(M) * (v_rot - C * Ainv_v);
  const Vector3d r_ddot_B = Ainv_v - Ainv_Ct * omega_dot;

  StateVector xd(layout_.size());
  xd.segment<3>(StateLayout::r_BN_N) = x.segment<3>(StateLayout::v_BN_N);
  xd.segment<3>(StateLayout::v_BN_N) = dcm_BN.transpose() * r_ddot_B;
  xd.segment<3>(StateLayout::sigma_BN) = sigma_dot_from_omega(sigma_BN, omega);
  xd.segment<3>(StateLayout::omega_BN_B) = omega_dot;
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    const double a_r = kA[ui] == 0.0 ? 0.0 : kA[ui] * ro[ui].w3.dot(r_ddot_B);
    xd(layout_.Omega(i)) = c_Omega[ui] - a_r - inv_J[ui] * q[ui].dot(omega_dot);
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
  if (p_.J2 != 0.0 && p_.mu > 0.0) em.E_orb += mp.m_sc * j2_potential(p_.mu, p_.J2, p_.R_J2, em.r_CN_N);
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

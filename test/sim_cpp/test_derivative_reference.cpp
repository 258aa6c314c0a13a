// The plant's derivative (SpacecraftModel::derivatives, arranged for speed:
// per-configuration constant inertia parts, the rotor terms as vectors, the
// symmetric block system of docs/dynamics.md "Derivative, as computed")
// against an independent, term-by-term implementation written here from
// docs/dynamics.md §2-§4.9 through the model's public API only: every wheel's
// [I_w] and its B-frame derivative formed as matrices, the mass properties
// summed term by term, the wheel equation substituted into the general
// A, B, C, D blocks and the system solved by pivoted LU.
//
// Random states of every wheel model (stuck and Stribeck flags included),
// with imbalances 1,000x an HR16's so that the fully-coupled terms are not
// lost in the hub's: the two agree to rounding (<= 1e-12 of each block's
// largest component, see gravity_floor; measured ~1e-14).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <Eigen/LU>

#include "sim/attitude.h"
#include "sim/spacecraft.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using sim::StateLayout;
using sim::StateVector;
using sim::WheelModel;

Matrix3d outer(const Vector3d& a, const Vector3d& b) { return a * b.transpose(); }
Matrix3d tilde(const Vector3d& a) { return sim::skew(a); }

// docs/dynamics.md §2-§4.9 term by term: returns x_dot.
StateVector reference_derivatives(const sim::SpacecraftModel& model, const StateVector& x,
                                  const sim::WheelInputs& in, const sim::ExternalLoads& loads,
                                  const sim::HubParams& hub)
{
  const StateLayout& L = model.layout();
  const sim::SpacecraftParams& p = model.params();
  const int n = L.num_rw;
  const Vector3d sigma = x.segment<3>(StateLayout::sigma_BN);
  const Vector3d omega = x.segment<3>(StateLayout::omega_BN_B);
  const Matrix3d BN = sim::dcm_BN_from_sigma(sigma);

  // Rotor frames, inertias and CoM offsets (§4.2, §4.8).
  std::vector<Vector3d> gs(n), w2(n), w3(n), r_c(n), r_c_prime(n);
  std::vector<Matrix3d> Iw(n), Iw_prime(n);
  double m = hub.m_h;
  Vector3d first = hub.m_h * hub.r_BcB_B;
  Vector3d first_prime = Vector3d::Zero();
  Matrix3d I = hub.I_hBc_B - hub.m_h * tilde(hub.r_BcB_B) * tilde(hub.r_BcB_B);
  Matrix3d I_prime = Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    const sim::ReactionWheelParams& w = p.wheels[ui];
    const sim::ReactionWheelDerived& dv = model.wheel_derived(i);
    const double th = x(L.theta(i));
    const double Om = x(L.Omega(i));
    gs[ui] = dv.gs_hat_B;
    w2[ui] = std::cos(th) * dv.w2_0_hat_B + std::sin(th) * dv.w3_0_hat_B;
    w3[ui] = gs[ui].cross(w2[ui]);
    if (w.model != WheelModel::FullyCoupled) continue;
    // [BW] [I_w]_W [BW]^T with [I_w]_W = [[J_s,0,J13],[0,J_t,0],[J13,0,J_g]]
    Matrix3d BW;
    BW.col(0) = gs[ui];
    BW.col(1) = w2[ui];
    BW.col(2) = w3[ui];
    Matrix3d IW;
    IW << w.J_s, 0.0, dv.J13, 0.0, dv.J_t, 0.0, dv.J13, 0.0, dv.J_g;
    Iw[ui] = BW * IW * BW.transpose();
    // d/dt [BW] = Omega [BW] [[0,0,0],[0,0,-1],[0,1,0]] (w2' = Omega w3, w3' = -Omega w2)
    Matrix3d Wdot;
    Wdot << 0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0;
    const Matrix3d BW_prime = Om * BW * Wdot;
    Iw_prime[ui] = BW_prime * IW * BW.transpose() + BW * IW * BW_prime.transpose();
    r_c[ui] = w.r_WB_B + dv.d * w2[ui];
    r_c_prime[ui] = dv.d * Om * w3[ui];
    m += w.m_w;
    first += w.m_w * r_c[ui];
    first_prime += w.m_w * r_c_prime[ui];
    I += Iw[ui] - w.m_w * tilde(r_c[ui]) * tilde(r_c[ui]);
    I_prime += Iw_prime[ui] - w.m_w * (tilde(r_c_prime[ui]) * tilde(r_c[ui]) + tilde(r_c[ui]) * tilde(r_c_prime[ui]));
  }
  const Vector3d c = first / m;
  const Vector3d c_prime = first_prime / m;

  Vector3d g_B = Vector3d::Zero();
  if (p.mu > 0.0) {
    const Vector3d r_C = x.segment<3>(StateLayout::r_BN_N) + BN.transpose() * c;
    g_B = BN * (-p.mu / std::pow(r_C.norm(), 3) * r_C);
  }

  // [A B; C D] [r_ddot; omega_dot] = [v_trans; v_rot], hub part (§3).
  Matrix3d A = m * Matrix3d::Identity();
  Matrix3d B = -m * tilde(c);
  Matrix3d C = m * tilde(c);
  Matrix3d D = I;
  Vector3d v_trans = loads.F_ext_B + m * g_B - 2.0 * m * omega.cross(c_prime) - m * omega.cross(omega.cross(c));
  Vector3d v_rot = loads.L_ext_B + c.cross(m * g_B) - omega.cross(I * omega) - I_prime * omega;

  // Omega_dot_i = a_i . r_ddot + b_i . omega_dot + c_i (§4.9).
  std::vector<Vector3d> a_O(n, Vector3d::Zero()), b_O(n, Vector3d::Zero());
  std::vector<double> c_O(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    const sim::ReactionWheelParams& w = p.wheels[ui];
    const sim::ReactionWheelDerived& dv = model.wheel_derived(i);
    const double Om = x(L.Omega(i));
    const bool stuck = in.stuck[ui];
    const double u = stuck ? 0.0 : in.u_s[ui] + model.friction_torque(i, x, in.stribeck[ui]);
    if (w.model != WheelModel::FullyCoupled) {
      // Balanced / SimpleJitter: J_s in the hub; the rotor adds J_s Omega gs.
      v_rot -= w.J_s * Om * omega.cross(gs[ui]);
      if (!stuck) {
        D -= w.J_s * outer(gs[ui], gs[ui]);
        v_rot -= u * gs[ui];
        b_O[ui] = -gs[ui];
        c_O[ui] = u / w.J_s;
      }
      if (w.model == WheelModel::SimpleJitter) {
        const Vector3d F = w.U_s * Om * Om * w2[ui];
        v_trans += F;
        v_rot += w.r_WB_B.cross(F) + w.U_d * Om * Om * w2[ui];
      }
      continue;
    }
    // Fully coupled: the rotor's momentum rate terms that do not carry
    // Omega' (its relative-motion terms), then the wheel equation
    // J_bar Omega' = u - J_bar gs.omega_dot - J13 w3.omega_dot - m d w3.(r_ddot + omega_dot x r_W) + ...
    const Vector3d h_rel = Om * (Iw[ui] * gs[ui]) + w.m_w * r_c[ui].cross(r_c_prime[ui]);
    const double md = w.m_w * dv.d;
    v_trans += md * Om * Om * w2[ui];
    v_rot += md * Om * Om * r_c[ui].cross(w2[ui]) + Om * Om * dv.J13 * w2[ui] - omega.cross(h_rel);
    if (stuck) continue;
    const double w_s = gs[ui].dot(omega);
    const double w_2 = w2[ui].dot(omega);
    const double w_3 = w3[ui].dot(omega);
    a_O[ui] = -md / dv.J_bar * w3[ui];
    b_O[ui] = -gs[ui] - (dv.J13 * w3[ui] + md * w.r_WB_B.cross(w3[ui])) / dv.J_bar;
    c_O[ui] = (w_2 * w_3 * (dv.J_t - dv.J_g - md * dv.d) - dv.J13 * w_2 * w_s -
               md * w3[ui].dot(omega.cross(omega.cross(w.r_WB_B))) + u + md * w3[ui].dot(g_B)) /
              dv.J_bar;
    // The Omega' terms of the translational and rotational equations.
    const Vector3d t_vec = md * w3[ui];                                   // m d w3 Omega'
    const Vector3d r_vec = Iw[ui] * gs[ui] + md * r_c[ui].cross(w3[ui]);  // ([I_w] gs + m d r_c x w3) Omega'
    A += t_vec * a_O[ui].transpose();
    B += t_vec * b_O[ui].transpose();
    C += r_vec * a_O[ui].transpose();
    D += r_vec * b_O[ui].transpose();
    v_trans -= c_O[ui] * t_vec;
    v_rot -= c_O[ui] * r_vec;
  }
  Eigen::Matrix<double, 6, 6> K;
  K << A, B, C, D;
  Eigen::Matrix<double, 6, 1> rhs;
  rhs << v_trans, v_rot;
  const Eigen::Matrix<double, 6, 1> acc = K.fullPivLu().solve(rhs);
  const Vector3d r_ddot = acc.head<3>();
  const Vector3d omega_dot = acc.tail<3>();

  StateVector xd(L.size());
  xd.setZero();
  xd.segment<3>(StateLayout::r_BN_N) = x.segment<3>(StateLayout::v_BN_N);
  xd.segment<3>(StateLayout::v_BN_N) = BN.transpose() * r_ddot;
  xd.segment<3>(StateLayout::sigma_BN) = sim::sigma_dot_from_omega(sigma, omega);
  xd.segment<3>(StateLayout::omega_BN_B) = omega_dot;
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    xd(L.Omega(i)) = a_O[ui].dot(r_ddot) + b_O[ui].dot(omega_dot) + c_O[ui];
    xd(L.theta(i)) = x(L.Omega(i));
  }
  return xd;
}

struct Case {
  sim::SpacecraftParams params;
  StateVector x;
  sim::WheelInputs in;
  sim::ExternalLoads loads;
};

// A random vehicle (n wheels of `models`) and state.
Case random_case(std::mt19937_64& rng, const std::vector<WheelModel>& models)
{
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const auto vec = [&](double s) { return Vector3d(s * U(rng), s * U(rng), s * U(rng)); };
  Case c;
  sim::SpacecraftParams& p = c.params;
  p.hub.m_h = 500.0 + 300.0 * U(rng);
  const Matrix3d R = sim::rotation_from_vector(vec(3.0));
  p.hub.I_hBc_B = R * Vector3d(900.0, 800.0, 600.0).asDiagonal() * R.transpose();
  p.hub.I_hBc_B = 0.5 * (p.hub.I_hBc_B + p.hub.I_hBc_B.transpose()).eval();
  p.hub.r_BcB_B = vec(0.2);
  p.mu = U(rng) > 0.0 ? 3.986004418e14 : 0.0;
  for (size_t i = 0; i < models.size(); ++i) {
    sim::ReactionWheelParams w;
    w.model = models[i];
    w.gs_hat_nom_B = vec(1.0).normalized();
    w.delta_mis_B = vec(0.01);
    w.r_WB_B = vec(1.5);
    w.m_w = 5.0 + 4.0 * U(rng);
    w.J_s = 0.08 + 0.05 * U(rng);
    if (U(rng) > 0.0) w.J_t = 0.05 + 0.02 * U(rng);
    if (U(rng) > 0.0) w.J_g = 0.04 + 0.02 * U(rng);
    w.U_s = 3e-3 * (1.5 + U(rng));  // 1,000x an HR16's
    w.U_d = 8e-4 * (1.5 + U(rng));
    w.friction.tau_c = 5e-4;
    w.friction.c_v = 1e-5;
    w.friction.beta_st = U(rng) > 0.0 ? 2.0 : 0.0;
    w.friction.tau_st = 1e-3;
    p.wheels.push_back(w);
    if (w.model != WheelModel::FullyCoupled)  // the hub contains the spin inertia
      p.hub.I_hBc_B += w.J_s * w.gs_hat_nom_B * w.gs_hat_nom_B.transpose();
  }
  const int n = static_cast<int>(models.size());
  StateLayout L;
  L.num_rw = n;
  c.x = StateVector(L.size());
  c.x.segment<3>(0) = Vector3d(7.0e6, 0.0, 0.0) + vec(1.0e6);
  c.x.segment<3>(3) = vec(7.5e3);
  c.x.segment<3>(6) = vec(0.55);
  c.x.segment<3>(9) = vec(0.05);
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<size_t>(i);
    c.x(L.Omega(i)) = 600.0 * U(rng);
    c.x(L.theta(i)) = 50.0 * U(rng);
    c.in.u_s[ui] = 0.2 * U(rng);
    c.in.stribeck[ui] = U(rng) > 0.0;
    c.in.stuck[ui] = U(rng) > 0.6;  // 20 %
  }
  c.loads.F_ext_B = vec(2.0);
  c.loads.L_ext_B = vec(0.5);
  return c;
}

double block_error(const StateVector& a, const StateVector& b, int start, int len, double floor = 1e-300)
{
  const double scale = std::max(b.segment(start, len).cwiseAbs().maxCoeff(), floor);
  return (a.segment(start, len) - b.segment(start, len)).cwiseAbs().maxCoeff() / scale;
}

// The hub equations are written about B, not the mass centre C: gravity's
// torque about B, c x m g, and the part of A^-1 v_trans that removes it
// cancel to the small torques that act about C.  The accelerations omega'
// and Omega' are therefore differences of terms of size m |c| |g| / I and
// carry their rounding: that is their floor of comparison (the hub's
// smallest principal inertia here is >= 600 kg m^2).
double gravity_floor(const sim::SpacecraftModel& model, const Case& c)
{
  if (!(c.params.mu > 0.0)) return 1e-300;
  const sim::MassProps mp = model.mass_props(c.x, c.params.hub);
  const double r = c.x.segment<3>(StateLayout::r_BN_N).norm();
  return mp.m_sc * mp.c_B.norm() * c.params.mu / (r * r) / 600.0;
}

void compare(const std::vector<WheelModel>& models, int cases, unsigned seed)
{
  std::mt19937_64 rng(seed);
  double worst = 0.0;
  for (int k = 0; k < cases; ++k) {
    const Case c = random_case(rng, models);
    const sim::SpacecraftModel model(c.params);
    const StateLayout& L = model.layout();
    const StateVector fast = model.derivatives(0.0, c.x, c.in, c.loads, c.params.hub);
    const StateVector ref = reference_derivatives(model, c.x, c.in, c.loads, c.params.hub);
    ASSERT_EQ(fast.size(), ref.size());
    const int n = L.num_rw;
    const double gf = gravity_floor(model, c);
    const double e = std::max({block_error(fast, ref, 0, 3), block_error(fast, ref, 3, 3),
                               block_error(fast, ref, 6, 3), block_error(fast, ref, 9, 3, gf),
                               n > 0 ? block_error(fast, ref, 12, n, gf) : 0.0,
                               n > 0 ? block_error(fast, ref, 12 + n, n) : 0.0});
    worst = std::max(worst, e);
    ASSERT_LE(e, 1e-12) << "case " << k;
  }
  testing::Test::RecordProperty("worst_relative_difference", std::to_string(worst));
  std::printf("worst relative difference over %d cases: %.2e\n", cases, worst);
}

TEST(DerivativeReference, HubOnly) { compare({}, 200, 1); }

TEST(DerivativeReference, FourFullyCoupled)
{
  compare({WheelModel::FullyCoupled, WheelModel::FullyCoupled, WheelModel::FullyCoupled,
           WheelModel::FullyCoupled},
          300, 2);
}

TEST(DerivativeReference, FourSimpleJitter)
{
  compare({WheelModel::SimpleJitter, WheelModel::SimpleJitter, WheelModel::SimpleJitter,
           WheelModel::SimpleJitter},
          300, 3);
}

TEST(DerivativeReference, FourBalanced)
{
  compare({WheelModel::Balanced, WheelModel::Balanced, WheelModel::Balanced, WheelModel::Balanced}, 300, 4);
}

TEST(DerivativeReference, MixedSixWheels)
{
  compare({WheelModel::FullyCoupled, WheelModel::Balanced, WheelModel::SimpleJitter, WheelModel::FullyCoupled,
           WheelModel::SimpleJitter, WheelModel::Balanced},
          300, 5);
}

// The cheap mass centre (per-configuration constants) is the mass
// properties' m_sc and c_B, for every wheel model.
TEST(DerivativeReference, MassCentreIsTheMassPropertiesOne)
{
  std::mt19937_64 rng(7);
  for (int k = 0; k < 200; ++k) {
    const Case c = random_case(rng, {WheelModel::FullyCoupled, WheelModel::Balanced, WheelModel::SimpleJitter,
                                     WheelModel::FullyCoupled});
    const sim::SpacecraftModel model(c.params);
    const sim::MassProps mp = model.mass_props(c.x, c.params.hub);
    const sim::MassCentre mc = model.mass_centre(c.x, c.params.hub);
    EXPECT_NEAR(mc.m_sc, mp.m_sc, 1e-14 * mp.m_sc);
    EXPECT_LE((mc.c_B - mp.c_B).norm(), 1e-15 * (1.0 + mp.c_B.norm())) << "case " << k;
  }
}

// The reference itself is not the code under test copied: it must see a
// change of any physical term.  Dropping one wheel's imbalance from the model
// (U_s -> 0) moves the derivative far outside the tolerance.
TEST(DerivativeReference, ReferenceSeesAnImbalanceChange)
{
  std::mt19937_64 rng(6);
  Case c = random_case(rng, {WheelModel::FullyCoupled, WheelModel::FullyCoupled});
  c.in.stuck = {};
  const StateVector ref = reference_derivatives(sim::SpacecraftModel(c.params), c.x, c.in, c.loads, c.params.hub);
  c.params.wheels[0].U_s = 0.0;
  const sim::SpacecraftModel changed(c.params);
  const StateVector fast = changed.derivatives(0.0, c.x, c.in, c.loads, c.params.hub);
  EXPECT_GT(block_error(fast, ref, 9, 3), 1e-6);
}

}  // namespace

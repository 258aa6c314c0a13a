// mtq_map: torque or dipole request -> magnetorquer rod commands.
// Expected values: hand numbers, the cross-product identities, and an
// independent pseudo-inverse written here (normal equations solved by
// Gaussian elimination in double).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "fsw/mtq_map.h"
#include "kestrel_test_support.h"
#include "mtq_test_util.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
const fsw_real kInf = std::numeric_limits<fsw_real>::infinity();

using mtqt::cross;
using mtqt::dot;
using mtqt::norm;
using mtqt::to_d;
using rwt::make0;

// Solve the k x k system A x = b (k <= 3) by Gaussian elimination with
// partial pivoting.
void gauss(int k, double A[3][3], double b[3], double x[3])
{
  for (int c = 0; c < k; c++) {
    int p = c;
    for (int r = c + 1; r < k; r++)
      if (std::fabs(A[r][c]) > std::fabs(A[p][c])) p = r;
    for (int j = 0; j < k; j++) std::swap(A[c][j], A[p][j]);
    std::swap(b[c], b[p]);
    for (int r = c + 1; r < k; r++) {
      const double f = A[r][c] / A[c][c];
      for (int j = c; j < k; j++) A[r][j] -= f * A[c][j];
      b[r] -= f * b[c];
    }
  }
  for (int c = k - 1; c >= 0; c--) {
    double s = b[c];
    for (int j = c + 1; j < k; j++) s -= A[c][j] * x[j];
    x[c] = s / A[c][c];
  }
}

// Full row rank (3 independent rods among n): c = G^T (G G^T)^-1 m.
void ref_minnorm(int n, const double g[][3], const double m[3], double* c)
{
  double M[3][3] = {}, y[3], b[3] = {m[0], m[1], m[2]};
  for (int i = 0; i < n; i++)
    for (int r = 0; r < 3; r++)
      for (int s = 0; s < 3; s++) M[r][s] += g[i][r] * g[i][s];
  gauss(3, M, b, y);
  for (int i = 0; i < n; i++) c[i] = dot(g[i], y);
}

// Full column rank (n <= 3 independent rods): c = (G^T G)^-1 G^T m.
void ref_lsq(int n, const double g[][3], const double m[3], double* c)
{
  double N[3][3] = {}, b[3] = {};
  for (int i = 0; i < n; i++) {
    b[i] = dot(g[i], m);
    for (int j = 0; j < n; j++) N[i][j] = dot(g[i], g[j]);
  }
  gauss(n, N, b, c);
}

struct Fixture {
  std::unique_ptr<FswMtqMapConfig> cfg = make0<FswMtqMapConfig>();
  std::unique_ptr<FswMtqMapState> st = make0<FswMtqMapState>();
  std::unique_ptr<FswMtqMapIn> in = make0<FswMtqMapIn>();
  std::unique_ptr<FswMtqMapOut> out = make0<FswMtqMapOut>();

  void setup(const double g[][3], int n, double m_max = 0.2, double duty = 0.8)
  {
    cfg->num_mtq = n;
    for (int i = 0; i < n; i++) {
      for (int k = 0; k < 3; k++) cfg->gt_hat_B[i][k] = static_cast<fsw_real>(g[i][k]);
      cfg->m_max[i] = static_cast<fsw_real>(m_max);
    }
    cfg->duty_max = static_cast<fsw_real>(duty);
    in->B_valid = 1;
  }
  FswStatus init() { return fsw_mtq_map_init(st.get(), cfg.get()); }
  FswStatus update() { return fsw_mtq_map_update(st.get(), cfg.get(), in.get(), out.get()); }
  void set_B(double x, double y, double z)
  {
    in->B_B[0] = static_cast<fsw_real>(x);
    in->B_B[1] = static_cast<fsw_real>(y);
    in->B_B[2] = static_cast<fsw_real>(z);
  }
  void set_tau(const double t[3])
  {
    for (int k = 0; k < 3; k++) in->tau_B[k] = static_cast<fsw_real>(t[k]);
  }
  void garbage() { std::memset(out.get(), 0x5A, sizeof *out); }
  void expect_safe(const char* why) const
  {
    for (int i = 0; i < FSW_MAX_MTQ; i++) {
      EXPECT_EQ(out->m_cmd[i], 0.0) << why << " rod " << i;
      EXPECT_EQ(out->duty[i], 0.0) << why << " rod " << i;
    }
    for (int k = 0; k < 3; k++) {
      EXPECT_EQ(out->m_ach_B[k], 0.0) << why;
      EXPECT_EQ(out->tau_ach_B[k], 0.0) << why;
      EXPECT_EQ(out->tau_par_B[k], 0.0) << why;
    }
    EXPECT_EQ(out->scale, 0.0) << why;
    EXPECT_EQ(out->rank, 0) << why;
  }
};

const double kOrtho[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

std::unique_ptr<Fixture> ortho(double m_max = 0.2, double duty = 0.8)
{
  auto f = make0<Fixture>();
  f->setup(kOrtho, 3, m_max, duty);
  EXPECT_EQ(f->init(), FSW_OK);
  return f;
}

// A skewed set of four rods: three non-orthogonal ones and a diagonal.
void skewed4(double g[4][3])
{
  const double raw[4][3] = {{1, 0.2, 0}, {0.1, 1, -0.3}, {0.3, -0.2, 1}, {1, 1, 1}};
  for (int i = 0; i < 4; i++) {
    const double n = norm(raw[i]);
    for (int k = 0; k < 3; k++) g[i][k] = raw[i][k] / n;
  }
}

std::unique_ptr<Fixture> skewed(double m_max, double duty)
{
  double g[4][3];
  skewed4(g);
  auto f = make0<Fixture>();
  f->setup(g, 4, m_max, duty);
  EXPECT_EQ(f->init(), FSW_OK);
  return f;
}

// The minimum-norm dipole for tau in the field of the input: (B x tau)/|B|^2.
void ref_dipole(double mB[3], const FswMtqMapIn& in)
{
  double B[3], t[3];
  to_d(B, in.B_B);
  to_d(t, in.tau_B);
  cross(mB, B, t);
  for (int k = 0; k < 3; k++) mB[k] /= dot(B, B);
}

}  // namespace

// Verifies: REQ-MTQMAP-001
TEST(MtqMapConfig, RejectsBadConfigurationsTableDriven)
{
  struct Row {
    const char* why;
    void (*spoil)(FswMtqMapConfig*);
    FswStatus want;
  };
  static const Row rows[] = {
      {"no rods", [](FswMtqMapConfig* c) { c->num_mtq = 0; }, FSW_E_CAPACITY},
      {"negative count", [](FswMtqMapConfig* c) { c->num_mtq = -1; }, FSW_E_CAPACITY},
      {"too many rods", [](FswMtqMapConfig* c) { c->num_mtq = FSW_MAX_MTQ + 1; }, FSW_E_CAPACITY},
      {"axis not unit", [](FswMtqMapConfig* c) { c->gt_hat_B[1][1] = FSW_R(0.99); }, FSW_E_CONFIG},
      {"axis zero", [](FswMtqMapConfig* c) { c->gt_hat_B[2][2] = 0; }, FSW_E_CONFIG},
      {"axis NaN", [](FswMtqMapConfig* c) { c->gt_hat_B[0][1] = kNaN; }, FSW_E_CONFIG},
      {"m_max zero", [](FswMtqMapConfig* c) { c->m_max[1] = 0; }, FSW_E_CONFIG},
      {"m_max negative", [](FswMtqMapConfig* c) { c->m_max[2] = FSW_R(-0.2); }, FSW_E_CONFIG},
      {"m_max NaN", [](FswMtqMapConfig* c) { c->m_max[0] = kNaN; }, FSW_E_CONFIG},
      {"m_max Inf", [](FswMtqMapConfig* c) { c->m_max[0] = kInf; }, FSW_E_CONFIG},
      {"m_max below range", [](FswMtqMapConfig* c) { c->m_max[0] = FSW_R(1e-7); }, FSW_E_CONFIG},
      {"m_max above range", [](FswMtqMapConfig* c) { c->m_max[0] = FSW_R(2e4); }, FSW_E_CONFIG},
      {"duty_max zero", [](FswMtqMapConfig* c) { c->duty_max = 0; }, FSW_E_CONFIG},
      {"duty_max negative", [](FswMtqMapConfig* c) { c->duty_max = FSW_R(-0.5); }, FSW_E_CONFIG},
      // fuzz finding (2026-12-05): a subnormal duty_max made every limit 0
      {"duty_max subnormal", [](FswMtqMapConfig* c) { c->duty_max = std::numeric_limits<fsw_real>::denorm_min(); },
       FSW_E_CONFIG},
      {"duty_max below 1e-3", [](FswMtqMapConfig* c) { c->duty_max = FSW_R(0.9e-3); }, FSW_E_CONFIG},
      {"duty_max above 1", [](FswMtqMapConfig* c) { c->duty_max = FSW_R(1.01); }, FSW_E_CONFIG},
      {"duty_max NaN", [](FswMtqMapConfig* c) { c->duty_max = kNaN; }, FSW_E_CONFIG},
  };
  for (const Row& row : rows) {
    auto f = ortho();
    row.spoil(f->cfg.get());
    EXPECT_EQ(fsw_mtq_map_check(f->cfg.get()), row.want) << row.why;
    EXPECT_EQ(f->init(), row.want) << row.why;
    EXPECT_EQ(f->st->ready, 0) << row.why;
    f->in->tau_B[0] = FSW_R(1e-6);
    f->set_B(0, 3e-5, 4e-5);
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_NOT_INIT) << row.why;
    f->expect_safe(row.why);
  }
  // the edges are accepted: duty_max = 1, m_max at both ends, all capacity
  auto f = ortho(1e4, 1.0);
  EXPECT_EQ(fsw_mtq_map_check(f->cfg.get()), FSW_OK);
  f->cfg->m_max[0] = FSW_R(1e-6);
  EXPECT_EQ(fsw_mtq_map_check(f->cfg.get()), FSW_OK);
  f->cfg->duty_max = FSW_R(1e-3);
  EXPECT_EQ(fsw_mtq_map_check(f->cfg.get()), FSW_OK);
  f->cfg->num_mtq = FSW_MAX_MTQ;
  for (int i = 3; i < FSW_MAX_MTQ; i++) {
    f->cfg->gt_hat_B[i][i % 3] = FSW_R(1.0);
    f->cfg->m_max[i] = FSW_R(0.1);
  }
  EXPECT_EQ(fsw_mtq_map_check(f->cfg.get()), FSW_OK);
}

// Orthogonal rods, B = (0, 3, 4) 1e-5 T (|B| = 5e-5 T), tau = (1e-6, 0, 0)
// N*m, perpendicular to B.  B x tau = (0, 4e-11, -3e-11), |B|^2 = 2.5e-9:
// m = (0, 0.016, -0.012) A*m^2, and m x B = (0.016*4e-5 + 0.012*3e-5, 0, 0)
// = tau.  Rods = m; limit 0.8 * 0.2 = 0.16, so no saturation;
// duty = (0, 0.08, 0.06).
// Verifies: REQ-MTQMAP-002
TEST(MtqMapNominal, OrthogonalRodsHandNumbers)
{
  auto f = ortho();
  f->set_B(3e-5 * 0, 3e-5, 4e-5);
  const double tau[3] = {1e-6, 0, 0};
  f->set_tau(tau);
  f->garbage();
  ASSERT_EQ(f->update(), FSW_OK);
  const double want[3] = {0, 0.016, -0.012};
  const double tol = kt::tol(1e-15, 1e-8);
  for (int i = 0; i < 3; i++) {
    EXPECT_NEAR(f->out->m_cmd[i], want[i], tol) << i;
    EXPECT_NEAR(f->out->m_ach_B[i], want[i], tol) << i;
    EXPECT_NEAR(f->out->duty[i], std::fabs(want[i]) / 0.2, tol * 5) << i;
    EXPECT_NEAR(f->out->tau_ach_B[i], tau[i], kt::tol(1e-18, 1e-12)) << i;
    EXPECT_NEAR(f->out->tau_par_B[i], 0.0, kt::tol(1e-22, 1e-13)) << i;
  }
  for (int i = 3; i < FSW_MAX_MTQ; i++) EXPECT_EQ(f->out->m_cmd[i], 0.0);
  EXPECT_EQ(f->out->scale, 1.0);
  EXPECT_EQ(f->out->rank, 3);
  EXPECT_EQ(f->st->health.calls, 1u);
}

// A request with a part along B: the dipole delivers exactly the
// perpendicular part (m x B = tau - (tau.B) B/|B|^2) and reports the
// parallel part.  Random requests and fields, relative 1e-12 (double).
// Verifies: REQ-MTQMAP-002
TEST(MtqMapNominal, DeliversThePerpendicularPartAndReportsTheParallel)
{
  auto f = ortho(1e4, 1.0);
  kt::Rng rng(3801);
  double worst = 0.0, worst_par = 0.0;
  for (int trial = 0; trial < 500; trial++) {
    double b[3], t[3];
    rng.unit3(b);
    rng.unit3(t);
    const double Bmag = rng.uniform(1e-5, 6e-5), tmag = rng.uniform(1e-7, 1e-3);
    f->set_B(b[0] * Bmag, b[1] * Bmag, b[2] * Bmag);
    for (double& x : t) x *= tmag;
    f->set_tau(t);
    ASSERT_EQ(f->update(), FSW_OK) << trial;
    double B[3], tau_in[3];
    to_d(B, f->in->B_B);
    to_d(tau_in, f->in->tau_B);
    const double s = dot(tau_in, B) / dot(B, B);
    double par[3], perp[3], m[3], mxB[3];
    for (int k = 0; k < 3; k++) {
      par[k] = s * B[k];
      perp[k] = tau_in[k] - par[k];
    }
    to_d(m, f->out->m_ach_B);
    cross(mxB, m, B);
    double e[3], ep[3], tach[3];
    to_d(tach, f->out->tau_ach_B);
    for (int k = 0; k < 3; k++) {
      e[k] = mxB[k] - perp[k];
      ep[k] = double(f->out->tau_par_B[k]) - par[k];
      EXPECT_NEAR(tach[k], mxB[k], kt::tol(1e-15, 1e-6) * norm(m) * norm(B));  // tau_ach is m_ach x B
    }
    worst = std::fmax(worst, norm(e) / norm(tau_in));
    worst_par = std::fmax(worst_par, norm(ep) / norm(tau_in));
    // minimum-norm dipole: perpendicular to B
    EXPECT_LE(std::fabs(dot(m, B)), kt::tol(1e-12, 1e-5) * norm(m) * norm(B)) << trial;
  }
  EXPECT_LE(worst, kt::tol(1e-12, 1e-5));
  EXPECT_LE(worst_par, kt::tol(1e-12, 1e-5));
  std::printf("[ figures ] |m x B - tau_perp|/|tau| worst %.3g, |tau_par error|/|tau| worst %.3g (500 cases)\n",
              worst, worst_par);
}

// tau along B: no dipole, no torque, the whole request reported as parallel.
// Verifies: REQ-MTQMAP-002
TEST(MtqMapNominal, ParallelRequestGivesNoTorque)
{
  auto f = ortho();
  f->set_B(0, 3e-5, 4e-5);
  const double tau[3] = {0, 1.2e-6, 1.6e-6};  // 2e-6 * (0, 0.6, 0.8)
  f->set_tau(tau);
  ASSERT_EQ(f->update(), FSW_OK);
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(f->out->m_ach_B[k], 0.0, kt::tol(1e-12, 1e-5) * 2e-6 / 5e-5) << k;
    EXPECT_NEAR(f->out->tau_ach_B[k], 0.0, kt::tol(1e-12, 1e-5) * 2e-6) << k;
    EXPECT_NEAR(f->out->tau_par_B[k], tau[k], kt::tol(1e-20, 1e-12)) << k;
  }
}

// Skewed 4-rod set: the minimum-norm commands equal G^T (G G^T)^-1 m_B from
// the normal equations solved here.
// Verifies: REQ-MTQMAP-002
TEST(MtqMapNominal, SkewedFourRodsMatchAnIndependentPseudoInverse)
{
  auto f = skewed(1e4, 1.0);
  kt::Rng rng(3802);
  double worst = 0.0;
  for (int trial = 0; trial < 200; trial++) {
    double m[3];
    rng.unit3(m);
    const double mag = rng.uniform(0.01, 10.0);
    f->in->use_dipole = 1;
    for (int k = 0; k < 3; k++) f->in->m_req_B[k] = static_cast<fsw_real>(m[k] * mag);
    f->set_B(1e-5, -2e-5, 3e-5);
    ASSERT_EQ(f->update(), FSW_OK) << trial;
    double md[3], c[4], gd[4][3];
    to_d(md, f->in->m_req_B);
    for (int i = 0; i < 4; i++) to_d(gd[i], f->cfg->gt_hat_B[i]);
    ref_minnorm(4, gd, md, c);
    double e = 0.0, cn = 0.0;
    for (int i = 0; i < 4; i++) {
      e += (f->out->m_cmd[i] - c[i]) * (f->out->m_cmd[i] - c[i]);
      cn += c[i] * c[i];
    }
    worst = std::fmax(worst, std::sqrt(e / cn));
    EXPECT_EQ(f->out->rank, 3);
  }
  EXPECT_LE(worst, kt::tol(1e-13, 1e-5));
  std::printf("[ figures ] skewed 4 rods: |c - c_ref|/|c_ref| worst %.3g (200 cases)\n", worst);
  // torque mode: the commands solve G c = (B x tau)/|B|^2
  f->in->use_dipole = 0;
  const double tau[3] = {2e-6, -1e-6, 0.5e-6};
  f->set_tau(tau);
  ASSERT_EQ(f->update(), FSW_OK);
  double mB[3], c[4], gd[4][3];
  ref_dipole(mB, *f->in);
  for (int i = 0; i < 4; i++) to_d(gd[i], f->cfg->gt_hat_B[i]);
  ref_minnorm(4, gd, mB, c);
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f->out->m_cmd[i], c[i], kt::tol(1e-13, 1e-5) * norm(mB)) << i;
}

// Two rods span a plane (rank 2): G c is the projection of m_B on the plane,
// c = (G^T G)^-1 G^T m_B (least squares, here also the minimum norm).  When
// m_B lies in the plane it is delivered (OK); otherwise W_SINGULAR.
// Verifies: REQ-MTQMAP-003
TEST(MtqMapRankDeficient, TwoRodsGiveTheLeastSquaresDipole)
{
  const double s2 = std::sqrt(0.5);
  const double g[2][3] = {{1, 0, 0}, {s2, s2, 0}};
  auto f = make0<Fixture>();
  f->setup(g, 2, 1e4, 1.0);
  ASSERT_EQ(f->init(), FSW_OK);
  // B along z: every perpendicular dipole is in the rods' plane
  f->set_B(0, 0, 5e-5);
  const double tau[3] = {1e-6, 2e-6, 0};
  f->set_tau(tau);
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->rank, 2);
  double gd[2][3], mB[3], c[2];
  for (int i = 0; i < 2; i++) to_d(gd[i], f->cfg->gt_hat_B[i]);
  ref_dipole(mB, *f->in);
  ref_lsq(2, gd, mB, c);
  for (int i = 0; i < 2; i++) EXPECT_NEAR(f->out->m_cmd[i], c[i], kt::tol(1e-14, 1e-6) * norm(mB)) << i;
  for (int k = 0; k < 3; k++) EXPECT_NEAR(f->out->tau_ach_B[k], tau[k], kt::tol(1e-18, 1e-11)) << k;
  // B tilted: m_B has a z part the rods cannot make
  f->set_B(3e-5, 0, 4e-5);
  f->set_tau(tau);
  ASSERT_EQ(f->update(), FSW_W_SINGULAR);
  EXPECT_EQ(f->out->rank, 2);
  EXPECT_EQ(f->out->scale, 1.0);
  ref_dipole(mB, *f->in);
  ref_lsq(2, gd, mB, c);
  for (int i = 0; i < 2; i++) EXPECT_NEAR(f->out->m_cmd[i], c[i], kt::tol(1e-14, 1e-6) * norm(mB)) << i;
  EXPECT_NEAR(f->out->m_ach_B[0], mB[0], kt::tol(1e-14, 1e-6) * norm(mB));
  EXPECT_NEAR(f->out->m_ach_B[1], mB[1], kt::tol(1e-14, 1e-6) * norm(mB));
  EXPECT_EQ(f->out->m_ach_B[2], 0.0);
  EXPECT_EQ(f->st->health.singular, 1u);
  // one rod: the component of m_B along it
  f->cfg->num_mtq = 1;
  ASSERT_EQ(f->init(), FSW_OK);
  ASSERT_EQ(f->update(), FSW_W_SINGULAR);
  EXPECT_EQ(f->out->rank, 1);
  EXPECT_NEAR(f->out->m_cmd[0], mB[0], kt::tol(1e-14, 1e-6) * norm(mB));
  EXPECT_EQ(f->out->m_cmd[1], 0.0);
}

// Saturation: orthogonal rods, limit 0.5 * 0.2 = 0.1 A*m^2.  tau = (2.5e-5,
// 0, 0) gives m = (0, 0.4, -0.3); scale = 0.1/0.4 = 0.25, m_cmd = (0, 0.1,
// -0.075), duty = (0, 0.5, 0.375), torque 0.25 tau.
// Verifies: REQ-MTQMAP-004
TEST(MtqMapSaturation, CommonFactorHandNumbers)
{
  auto f = ortho(0.2, 0.5);
  f->set_B(0, 3e-5, 4e-5);
  const double tau[3] = {2.5e-5, 0, 0};
  f->set_tau(tau);
  ASSERT_EQ(f->update(), FSW_W_SAT);
  const double tol = kt::tol(1e-15, 1e-7);
  EXPECT_NEAR(f->out->scale, 0.25, tol);
  const double want[3] = {0, 0.1, -0.075}, duty[3] = {0, 0.5, 0.375};
  for (int i = 0; i < 3; i++) {
    EXPECT_NEAR(f->out->m_cmd[i], want[i], tol) << i;
    EXPECT_NEAR(f->out->duty[i], duty[i], tol * 5) << i;
    EXPECT_NEAR(f->out->tau_ach_B[i], 0.25 * tau[i], kt::tol(1e-18, 1e-11)) << i;
  }
  EXPECT_EQ(f->st->health.saturated, 1u);
}

// Saturation keeps the direction and each rod within duty_max m_max, on
// the skewed set with unequal limits (independent pseudo-inverse for the
// unsaturated dipole).
// Verifies: REQ-MTQMAP-004
TEST(MtqMapSaturation, DirectionKeptAndEveryRodWithinItsLimit)
{
  double g[4][3];
  skewed4(g);
  auto f = make0<Fixture>();
  f->setup(g, 4, 0.2, 0.7);
  f->cfg->m_max[1] = FSW_R(0.05);
  f->cfg->m_max[3] = FSW_R(1.0);
  ASSERT_EQ(f->init(), FSW_OK);
  kt::Rng rng(3803);
  int saturated = 0;
  double worst_angle = 0.0;
  for (int trial = 0; trial < 300; trial++) {
    double m[3];
    rng.unit3(m);
    const double mag = rng.uniform(0.005, 0.15);
    f->in->use_dipole = 1;
    for (int k = 0; k < 3; k++) f->in->m_req_B[k] = static_cast<fsw_real>(m[k] * mag);
    f->set_B(2e-5, 1e-5, -4e-5);
    const FswStatus s = f->update();
    ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT) << trial;
    double md[3], c[4], gd[4][3], ach[3];
    to_d(md, f->in->m_req_B);
    for (int i = 0; i < 4; i++) to_d(gd[i], f->cfg->gt_hat_B[i]);
    ref_minnorm(4, gd, md, c);
    double smax = 1.0;
    for (int i = 0; i < 4; i++) {
      // the limit as the module forms it, in the real type
      const double lim = double(static_cast<fsw_real>(f->cfg->duty_max * f->cfg->m_max[i]));
      EXPECT_LE(std::fabs(double(f->out->m_cmd[i])), lim) << trial << " rod " << i;
      EXPECT_LE(double(f->out->duty[i]), double(f->cfg->duty_max)) << trial;
      if (std::fabs(c[i]) > lim) smax = std::fmin(smax, lim / std::fabs(c[i]));
    }
    EXPECT_EQ(s == FSW_W_SAT, smax < 1.0) << trial;
    EXPECT_NEAR(f->out->scale, smax, kt::tol(1e-12, 1e-5)) << trial;
    for (int i = 0; i < 4; i++) EXPECT_NEAR(f->out->m_cmd[i], smax * c[i], kt::tol(1e-13, 1e-5) * mag) << i;
    to_d(ach, f->out->m_ach_B);
    double x[3];
    cross(x, ach, md);
    worst_angle = std::fmax(worst_angle, norm(x) / (norm(ach) * norm(md)));
    EXPECT_GE(dot(ach, md), 0.0);
    saturated += s == FSW_W_SAT;
  }
  EXPECT_GT(saturated, 50);
  EXPECT_LT(saturated, 290);
  EXPECT_LE(worst_angle, kt::tol(1e-13, 1e-5));
  std::printf("[ figures ] saturation: %d of 300 saturated, sin(angle m_ach, m_req) worst %.3g\n", saturated,
              worst_angle);
}

// Unavailable rods get exactly 0: the skewed set without rod 4 is the 3-rod
// set; the orthogonal set without rod 1 is rank 2.
// Verifies: REQ-MTQMAP-005
TEST(MtqMapAvailability, UnavailableRodsAreZero)
{
  auto f = skewed(1e4, 1.0);
  f->in->use_dipole = 1;
  f->in->m_req_B[0] = FSW_R(0.3);
  f->in->m_req_B[1] = FSW_R(-0.1);
  f->in->m_req_B[2] = FSW_R(0.2);
  f->set_B(1e-5, 2e-5, 3e-5);
  f->in->avail[3] = FSW_UNAVAILABLE;
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->m_cmd[3], 0.0);
  EXPECT_EQ(f->out->duty[3], 0.0);
  double md[3], c[3], gd[3][3];
  to_d(md, f->in->m_req_B);
  for (int i = 0; i < 3; i++) to_d(gd[i], f->cfg->gt_hat_B[i]);
  ref_lsq(3, gd, md, c);  // square: the exact solution
  for (int i = 0; i < 3; i++) EXPECT_NEAR(f->out->m_cmd[i], c[i], kt::tol(1e-14, 1e-6)) << i;

  auto o = ortho(1e4, 1.0);
  o->in->use_dipole = 1;
  for (int k = 0; k < 3; k++) o->in->m_req_B[k] = static_cast<fsw_real>(0.1 * (k + 1));
  o->set_B(1e-5, 2e-5, 3e-5);
  o->in->avail[0] = FSW_UNAVAILABLE;
  ASSERT_EQ(o->update(), FSW_W_SINGULAR);
  EXPECT_EQ(o->out->m_cmd[0], 0.0);
  EXPECT_EQ(o->out->rank, 2);
  EXPECT_NEAR(o->out->m_cmd[1], 0.2, kt::tol(1e-15, 1e-7));
  EXPECT_NEAR(o->out->m_cmd[2], 0.3, kt::tol(1e-15, 1e-7));
  // every rod unavailable: nothing commanded
  o->in->avail[1] = o->in->avail[2] = FSW_UNAVAILABLE;
  ASSERT_EQ(o->update(), FSW_W_SINGULAR);
  EXPECT_EQ(o->out->rank, 0);
  for (int i = 0; i < FSW_MAX_MTQ; i++) EXPECT_EQ(o->out->m_cmd[i], 0.0);
  // a zero request with no rods is delivered
  for (int k = 0; k < 3; k++) o->in->m_req_B[k] = 0;
  EXPECT_EQ(o->update(), FSW_OK);
}

// Dipole mode: m_req_B mapped directly; tau_par = 0; tau_ach = m x B.
// Verifies: REQ-MTQMAP-002
TEST(MtqMapNominal, DipoleModeMapsTheRequestDirectly)
{
  auto f = ortho();
  f->in->use_dipole = 1;
  f->in->m_req_B[0] = FSW_R(0.05);
  f->in->m_req_B[1] = FSW_R(-0.02);
  f->in->m_req_B[2] = FSW_R(0.1);
  f->in->tau_B[0] = kNaN;  // not read in dipole mode
  f->set_B(2e-5, 0, 0);
  ASSERT_EQ(f->update(), FSW_OK);
  for (int i = 0; i < 3; i++) EXPECT_NEAR(f->out->m_cmd[i], f->in->m_req_B[i], kt::tol(1e-16, 1e-8)) << i;
  // m x B = (0, 0.1 * 2e-5, 0.02 * 2e-5)
  EXPECT_NEAR(f->out->tau_ach_B[0], 0.0, 1e-20);
  EXPECT_NEAR(f->out->tau_ach_B[1], 2e-6, kt::tol(1e-20, 1e-12));
  EXPECT_NEAR(f->out->tau_ach_B[2], 4e-7, kt::tol(1e-20, 1e-12));
  for (int k = 0; k < 3; k++) EXPECT_EQ(f->out->tau_par_B[k], 0.0);
}

// No usable field: B_valid = 0 (B not read) or |B| below 1e-9 T -> rods off,
// W_SINGULAR.  1e-9 T itself is usable.
// Verifies: REQ-MTQMAP-005
TEST(MtqMapField, InvalidOrTinyFieldTurnsTheRodsOff)
{
  auto f = ortho();
  const double tau[3] = {1e-6, 0, 0};
  f->set_tau(tau);
  f->in->B_valid = 0;
  f->in->B_B[0] = kNaN;
  f->garbage();
  EXPECT_EQ(f->update(), FSW_W_SINGULAR);
  f->expect_safe("B_valid 0");
  f->in->B_valid = 1;
  f->set_B(0, 0, 0);
  f->garbage();
  EXPECT_EQ(f->update(), FSW_W_SINGULAR);
  f->expect_safe("B = 0");
  f->set_B(0, 0, 0.9e-9);
  f->garbage();
  EXPECT_EQ(f->update(), FSW_W_SINGULAR);
  f->expect_safe("|B| 0.9 nT");
  // |B| = 1e-9 T: usable; the dipole is large and saturates
  f->set_B(0, 0, 1e-9);
  EXPECT_EQ(f->update(), FSW_W_SAT);
  EXPECT_NEAR(f->out->m_cmd[1], 0.16, kt::tol(1e-15, 1e-7));  // (0,0,1) x (1,0,0) = (0,1,0)
  EXPECT_EQ(f->st->health.singular, 3u);
}

// Verifies: REQ-MTQMAP-006
TEST(MtqMapBadInput, SafeOutputAndNoStateChange)
{
  struct Row {
    const char* why;
    void (*spoil)(FswMtqMapIn*);
  };
  static const Row rows[] = {
      {"use_dipole 2", [](FswMtqMapIn* in) { in->use_dipole = 2; }},
      {"B_valid 2", [](FswMtqMapIn* in) { in->B_valid = 2; }},
      {"mask 2", [](FswMtqMapIn* in) { in->avail[2] = 2; }},
      {"tau NaN", [](FswMtqMapIn* in) { in->tau_B[1] = kNaN; }},
      {"tau Inf", [](FswMtqMapIn* in) { in->tau_B[0] = -kInf; }},
      {"tau beyond range", [](FswMtqMapIn* in) { in->tau_B[2] = FSW_R(2e6); }},
      {"m_req NaN (dipole mode)",
       [](FswMtqMapIn* in) {
         in->use_dipole = 1;
         in->m_req_B[0] = kNaN;
       }},
      {"m_req beyond range",
       [](FswMtqMapIn* in) {
         in->use_dipole = 1;
         in->m_req_B[2] = FSW_R(-2e9);
       }},
      {"B NaN", [](FswMtqMapIn* in) { in->B_B[1] = kNaN; }},
      {"B Inf", [](FswMtqMapIn* in) { in->B_B[2] = kInf; }},
      {"|B| above 1 T", [](FswMtqMapIn* in) { in->B_B[0] = FSW_R(1.5); }},
  };
  for (const Row& row : rows) {
    auto f = ortho();
    f->set_B(0, 3e-5, 4e-5);
    const double tau[3] = {1e-6, 0, 0};
    f->set_tau(tau);
    ASSERT_EQ(f->update(), FSW_OK);
    FswMtqMapState before, masked;
    std::memcpy(&before, f->st.get(), sizeof before);
    row.spoil(f->in.get());
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_BAD_INPUT) << row.why;
    f->expect_safe(row.why);
    EXPECT_EQ(f->st->health.bad_input, 1u) << row.why;
    EXPECT_EQ(f->st->ready, before.ready);
    std::memcpy(&masked, f->st.get(), sizeof masked);
    masked.health = before.health;
    EXPECT_EQ(std::memcmp(&masked, &before, sizeof before), 0) << row.why;
  }
  // the request not used is not read; a mask beyond num_mtq is not read
  auto f = ortho();
  f->set_B(0, 3e-5, 4e-5);
  f->in->m_req_B[0] = kNaN;
  f->in->avail[3 % FSW_MAX_MTQ] = 7;
  EXPECT_EQ(f->update(), FSW_MAX_MTQ > 3 ? FSW_OK : FSW_E_BAD_INPUT);
}

// Same input, same output bytes, also after reset; reset keeps ready and
// the health counters.
// Verifies: REQ-MTQMAP-007
TEST(MtqMapRepeatability, SameInputsGiveIdenticalOutputs)
{
  double g[4][3];
  skewed4(g);
  auto f = make0<Fixture>();
  f->setup(g, 4, 0.2, 0.6);
  ASSERT_EQ(f->init(), FSW_OK);
  const double tau[3] = {3e-6, -2e-6, 1e-6};
  f->set_tau(tau);
  f->set_B(1e-5, -3e-5, 2e-5);
  f->in->avail[1] = FSW_UNAVAILABLE;
  ASSERT_NE(f->update(), FSW_E_BAD_INPUT);
  auto first = make0<FswMtqMapOut>();
  std::memcpy(first.get(), f->out.get(), sizeof *first);
  fsw_mtq_map_reset(f->st.get());
  EXPECT_EQ(f->st->ready, 1);
  EXPECT_EQ(f->st->health.calls, 1u);
  f->garbage();
  ASSERT_NE(f->update(), FSW_E_BAD_INPUT);
  // field by field (the struct may have padding, which nobody writes)
  EXPECT_EQ(std::memcmp(first->m_cmd, f->out->m_cmd, sizeof first->m_cmd), 0);
  EXPECT_EQ(std::memcmp(first->duty, f->out->duty, sizeof first->duty), 0);
  EXPECT_EQ(std::memcmp(first->m_ach_B, f->out->m_ach_B, sizeof first->m_ach_B), 0);
  EXPECT_EQ(std::memcmp(first->tau_ach_B, f->out->tau_ach_B, sizeof first->tau_ach_B), 0);
  EXPECT_EQ(std::memcmp(first->tau_par_B, f->out->tau_par_B, sizeof first->tau_par_B), 0);
  EXPECT_EQ(std::memcmp(&first->scale, &f->out->scale, sizeof first->scale), 0);
  EXPECT_EQ(first->rank, f->out->rank);
}

// Verifies: REQ-GEN-007
TEST(MtqMapIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("mtq_map", fsw_mtq_map_check, fsw_mtq_map_init, fsw_mtq_map_reset, fsw_mtq_map_update);
}

// MC/DC of the saturation status (mtq_map.c, `scale < 1 && status == OK`):
// the request of MtqMapSaturation.CommonFactorHandNumbers (B = (0, 3e-5,
// 4e-5), tau = (2.5e-5, 0, 0): m_B = B x tau / |B|^2 = (0, 0.4, -0.3)) on
// two rods x and y (limit 0.5 * 0.2 = 0.1).  The rods cannot make the z part
// (W_SINGULAR); the least-squares commands (0, 0.4) are scaled by
// 0.1 / 0.4 = 0.25 to (0, 0.1), and the status stays W_SINGULAR (the scale
// tells the saturation).  With the third rod the same request is W_SAT.
// Verifies: REQ-MTQMAP-003, REQ-MTQMAP-004
TEST(MtqMapSaturation, McdcASingularRodSetThatSaturatesStaysSingular)
{
  const double tau[3] = {2.5e-5, 0, 0};
  const double tol = kt::tol(1e-15, 1e-7);
  auto f = make0<Fixture>();
  f->setup(kOrtho, 2, 0.2, 0.5);
  ASSERT_EQ(f->init(), FSW_OK);
  f->set_B(0, 3e-5, 4e-5);
  f->set_tau(tau);
  ASSERT_EQ(f->update(), FSW_W_SINGULAR);
  EXPECT_EQ(f->out->rank, 2);
  EXPECT_NEAR(f->out->scale, 0.25, tol);
  EXPECT_NEAR(f->out->m_cmd[0], 0.0, tol);
  EXPECT_NEAR(f->out->m_cmd[1], 0.1, tol);
  EXPECT_NEAR(f->out->duty[1], 0.5, tol * 5);
  // m_ach = (0, 0.1, 0); tau_ach = m_ach x B = (0.1 * 4e-5, 0, 0)
  EXPECT_NEAR(f->out->m_ach_B[1], 0.1, tol);
  EXPECT_EQ(f->out->m_ach_B[2], 0.0);
  EXPECT_NEAR(f->out->tau_ach_B[0], 4e-6, kt::tol(1e-18, 1e-11));
  EXPECT_EQ(f->st->health.singular, 1u);
  EXPECT_EQ(f->st->health.saturated, 0u);
  // the third rod spans m_B: the same saturation is W_SAT
  auto g = ortho(0.2, 0.5);
  g->set_B(0, 3e-5, 4e-5);
  g->set_tau(tau);
  EXPECT_EQ(g->update(), FSW_W_SAT);
  EXPECT_NEAR(g->out->scale, 0.25, tol);
}

// mrp_fb: MRP feedback control law (docs/fsw/mrp_fb.md).
// Expected values: a hand calculation for the pure P/K case, and otherwise an
// independent plain-C++ (double) evaluation of the equations of docs/fsw/mrp_fb.md written
// out component by component in this file (ref_lr below), never the
// module's own output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "fsw/mrp_fb.h"
#include "mrp_fb_internal.h"
#include "gnc_test_ref.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

const double kTol = kt::tol(1e-13, 2e-5);

// Independent evaluation of docs/fsw/mrp_fb.md, steps 1-6, in double.
struct RefIn {
  double sigma[3], wBR[3], wRN[3], dwRN[3];
  double I[3][3];
  double K, P, Ki, L[3];
  int law;
  int n_rw;
  double gs[4][3], Js[4], Omega[4];
  int avail[4];
};
struct RefOut {
  double Lr[3], Lint[3];
};

RefOut ref_lr(const RefIn& r, const double int_sigma[3])
{
  double w[3], z[3] = {0, 0, 0}, H[3], v[3];
  for (int i = 0; i < 3; i++) w[i] = r.wBR[i] + r.wRN[i];
  if (r.Ki > 0) {
    double Iw[3];
    gref::matvec(Iw, r.I, r.wBR);
    for (int i = 0; i < 3; i++) z[i] = int_sigma[i] + Iw[i];
  }
  gref::matvec(H, r.I, w);
  for (int k = 0; k < r.n_rw; k++) {
    if (r.avail[k] != 0) continue;
    const double hs = r.Js[k] * (gref::dot(r.gs[k], w) + r.Omega[k]);
    for (int i = 0; i < 3; i++) H[i] += hs * r.gs[k][i];
  }
  for (int i = 0; i < 3; i++) v[i] = r.law == 0 ? r.wRN[i] + r.Ki * z[i] : w[i];
  double vxH[3], wxwr[3], Iterm[3], a[3];
  gref::cross(vxH, v, H);
  gref::cross(wxwr, w, r.wRN);
  for (int i = 0; i < 3; i++) a[i] = wxwr[i] - r.dwRN[i];
  gref::matvec(Iterm, r.I, a);
  RefOut o;
  for (int i = 0; i < 3; i++) {
    o.Lr[i] = -(r.K * r.sigma[i] + r.P * r.wBR[i] + r.P * r.Ki * z[i] - vxH[i] + Iterm[i] + r.L[i]);
    o.Lint[i] = -r.P * r.Ki * z[i];
  }
  return o;
}

// Basilisk-like scenario (values of the mrpFeedback unit test style):
// I = diag(1000, 800, 800) with small products of inertia, four pyramid wheels.
RefIn scenario()
{
  RefIn r{};
  const double s[3] = {0.3, -0.5, 0.7}, wbr[3] = {0.010, -0.020, 0.015}, wrn[3] = {-0.02, -0.01, 0.005},
               dw[3] = {0.0002, 0.0003, 0.0001};
  for (int i = 0; i < 3; i++) {
    r.sigma[i] = s[i];
    r.wBR[i] = wbr[i];
    r.wRN[i] = wrn[i];
    r.dwRN[i] = dw[i];
    r.L[i] = 1.0;
  }
  const double I[3][3] = {{1000, 10, -5}, {10, 800, 2}, {-5, 2, 800}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) r.I[i][j] = I[i][j];
  r.K = 0.15;
  r.P = 150.0;
  r.Ki = 0.01;
  r.law = 0;
  r.n_rw = 4;
  const double c = 1.0 / std::sqrt(3.0);
  const double sx[4] = {1, -1, -1, 1}, sy[4] = {1, 1, -1, -1};
  for (int k = 0; k < 4; k++) {
    r.gs[k][0] = sx[k] * c;
    r.gs[k][1] = sy[k] * c;
    r.gs[k][2] = c;
    r.Js[k] = 0.1;
    r.avail[k] = 0;
  }
  const double Om[4] = {10.0, 25.0, 50.0, 100.0};
  for (int k = 0; k < 4; k++) r.Omega[k] = Om[k];
  return r;
}

void load(const RefIn& r, FswMrpFbConfig& cfg, FswMrpFbIn& in, double integral_limit)
{
  cfg = FswMrpFbConfig{};
  in = FswMrpFbIn{};
  cfg.K = static_cast<fsw_real>(r.K);
  cfg.P = static_cast<fsw_real>(r.P);
  cfg.K_i = static_cast<fsw_real>(r.Ki);
  cfg.integral_limit = static_cast<fsw_real>(integral_limit);
  cfg.control_law_type = r.law;
  gref::to_real(cfg.known_torque_B, r.L);
  for (int i = 0; i < 3; i++) gref::to_real(cfg.I_B[i], r.I[i]);
  cfg.num_rw = r.n_rw;
  for (int k = 0; k < r.n_rw; k++) {
    gref::to_real(cfg.gs_hat_B[k], r.gs[k]);
    cfg.J_s[k] = static_cast<fsw_real>(r.Js[k]);
    in.Omega[k] = static_cast<fsw_real>(r.Omega[k]);
    in.rw_avail[k] = static_cast<uint8_t>(r.avail[k]);
  }
  gref::to_real(in.guid.sigma_BR, r.sigma);
  gref::to_real(in.guid.omega_BR_B, r.wBR);
  gref::to_real(in.guid.omega_RN_B, r.wRN);
  gref::to_real(in.guid.omega_dot_RN_B, r.dwRN);
}

// the reference must see exactly the values the module sees (float build)
RefIn rounded(RefIn r)
{
  auto rd = [](double& x) { x = static_cast<double>(static_cast<fsw_real>(x)); };
  for (int i = 0; i < 3; i++) {
    rd(r.sigma[i]);
    rd(r.wBR[i]);
    rd(r.wRN[i]);
    rd(r.dwRN[i]);
    rd(r.L[i]);
    for (int j = 0; j < 3; j++) rd(r.I[i][j]);
  }
  rd(r.K);
  rd(r.P);
  rd(r.Ki);
  for (int k = 0; k < 4; k++) {
    rd(r.Js[k]);
    rd(r.Omega[k]);
    for (int i = 0; i < 3; i++) rd(r.gs[k][i]);
  }
  return r;
}

void expect_lr(const RefOut& want, const FswMrpFbOut& got, double tol)
{
  for (int i = 0; i < 3; i++) {
    const double scale = std::fmax(1.0, std::fabs(want.Lr[i]));
    EXPECT_NEAR(want.Lr[i], got.torque_B[i], tol * scale) << "Lr " << i;
    EXPECT_NEAR(want.Lint[i], got.int_torque_B[i], tol * std::fmax(1.0, std::fabs(want.Lint[i])))
        << "Lint " << i;
  }
}

class MrpFb : public ::testing::Test {
 protected:
  void SetUp() override { kestrel_assert_reset(); }
  void init(const RefIn& r, double limit)
  {
    load(r, cfg_, in_, limit);
    ASSERT_EQ(FSW_OK, fsw_mrp_fb_init(&st_, &cfg_));
  }
  FswStatus step(uint64_t t_ns)
  {
    in_.t_ns = t_ns;
    return fsw_mrp_fb_update(&st_, &cfg_, &in_, &out_);
  }
  FswMrpFbConfig cfg_{};
  FswMrpFbState st_{};
  FswMrpFbIn in_{};
  FswMrpFbOut out_{};
};

// Verifies: REQ-MRPFB-001
TEST_F(MrpFb, PureProportionalDerivativeHandCase)
{
  // omega_RN = 0, omega_dot_RN = 0, no wheels, K_i < 0 (z = 0): v = 0, so
  // Lr = -(K sigma + P omega_BR + L).  K = 0.15, P = 150,
  // sigma = (0.3, -0.5, 0.7), omega_BR = (0.01, -0.02, -0.03), L = (0.1, 0.2, 0.3):
  // K sigma = (0.045, -0.075, 0.105), P omega = (1.5, -3, -4.5)
  // Lr = -(1.645, -2.875, -4.095) = (-1.645, 2.875, 4.095).
  RefIn r = scenario();
  r.n_rw = 0;
  r.Ki = -1.0;
  const double wbr[3] = {0.01, -0.02, -0.03}, L[3] = {0.1, 0.2, 0.3};
  for (int i = 0; i < 3; i++) {
    r.wBR[i] = wbr[i];
    r.wRN[i] = 0.0;
    r.dwRN[i] = 0.0;
    r.L[i] = L[i];
  }
  init(r, 0.0);
  ASSERT_EQ(FSW_OK, step(0));
  EXPECT_V3_NEAR(-1.645, 2.875, 4.095, out_.torque_B, kt::tol(1e-13, 2e-6));
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.int_torque_B, 0.0);
}

// Verifies: REQ-MRPFB-001
TEST_F(MrpFb, FullLawMatchesIndependentEvaluation)
{
  // All terms active: integral (K_i = 0.01), wheels, reference motion, L.
  for (int law = 0; law < 2; law++) {
    SCOPED_TRACE(law);
    RefIn r = scenario();
    r.law = law;
    init(r, 20.0);
    const RefIn rr = rounded(r);
    const double zero[3] = {0, 0, 0};
    // first call: dt = 0, int_sigma stays 0
    ASSERT_EQ(FSW_OK, step(1000000000ull));
    expect_lr(ref_lr(rr, zero), out_, kTol);
    // second call 0.5 s later: int_sigma = K dt sigma = 0.075 sigma
    ASSERT_EQ(FSW_OK, step(1500000000ull));
    double is[3];
    for (int i = 0; i < 3; i++) is[i] = rr.K * 0.5 * rr.sigma[i];
    EXPECT_V3_NEAR(is[0], is[1], is[2], st_.int_sigma, kt::tol(1e-16, 1e-8));
    expect_lr(ref_lr(rr, is), out_, kTol);
    // third call 0.25 s later: accumulates
    ASSERT_EQ(FSW_OK, step(1750000000ull));
    for (int i = 0; i < 3; i++) is[i] += rr.K * 0.25 * rr.sigma[i];
    expect_lr(ref_lr(rr, is), out_, kTol);
  }
}

// Verifies: REQ-MRPFB-001
TEST_F(MrpFb, UnavailableWheelIsExcludedFromMomentum)
{
  RefIn r = scenario();
  r.avail[2] = 1;
  init(r, 20.0);
  in_.Omega[2] = static_cast<fsw_real>(gref::nan());  // ignored: wheel unavailable
  const double zero[3] = {0, 0, 0};
  ASSERT_EQ(FSW_OK, step(0));
  expect_lr(ref_lr(rounded(r), zero), out_, kTol);
  // same as a 3-wheel configuration without wheel 2
  RefIn r3 = scenario();
  r3.n_rw = 3;
  r3.gs[2][0] = r3.gs[3][0];
  r3.gs[2][1] = r3.gs[3][1];
  r3.gs[2][2] = r3.gs[3][2];
  r3.Omega[2] = r3.Omega[3];
  expect_lr(ref_lr(rounded(r3), zero), out_, kTol);
}

// Verifies: REQ-MRPFB-002
TEST_F(MrpFb, IntegralClampsPerComponentWithSign)
{
  // K = 1, dt = 1 s, sigma = (0.5, -0.5, 0.1), limit 0.2:
  // int_sigma = (0.5, -0.5, 0.1) -> clamped (0.2, -0.2, 0.1).  omega_BR = 0, so
  // z = int_sigma and the integral torque is -P K_i z = -10*0.01*z.
  RefIn r = scenario();
  r.K = 1.0;
  r.P = 10.0;
  r.n_rw = 0;
  const double s[3] = {0.5, -0.5, 0.1};
  for (int i = 0; i < 3; i++) {
    r.sigma[i] = s[i];
    r.wBR[i] = 0.0;
  }
  init(r, 0.2);
  ASSERT_EQ(FSW_OK, step(0));
  ASSERT_EQ(FSW_OK, step(1000000000ull));
  EXPECT_V3_NEAR(0.2, -0.2, 0.1, st_.int_sigma, kt::tol(1e-16, 1e-8));
  EXPECT_V3_NEAR(-0.02, 0.02, -0.01, out_.int_torque_B, kt::tol(1e-16, 1e-8));
  // further steps stay at the limit (no wind-up); component 3 reaches it too
  ASSERT_EQ(FSW_OK, step(2000000000ull));
  ASSERT_EQ(FSW_OK, step(3000000000ull));
  EXPECT_V3_NEAR(0.2, -0.2, 0.2, st_.int_sigma, kt::tol(1e-16, 1e-8));
  // a zero limit keeps the integral at zero
  init(r, 0.0);
  ASSERT_EQ(FSW_OK, step(0));
  ASSERT_EQ(FSW_OK, step(1000000000ull));
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, st_.int_sigma, 0.0);
}

// Verifies: REQ-MRPFB-002
TEST_F(MrpFb, NonPositiveKiLeavesIntegralUntouched)
{
  for (double ki : {0.0, -1.0}) {
    RefIn r = scenario();
    r.Ki = ki;
    init(r, 20.0);
    ASSERT_EQ(FSW_OK, step(0));
    ASSERT_EQ(FSW_OK, step(1000000000ull));
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, st_.int_sigma, 0.0);
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.int_torque_B, 0.0);
    const double zero[3] = {0, 0, 0};
    expect_lr(ref_lr(rounded(r), zero), out_, kTol);
  }
}

// Verifies: REQ-MRPFB-007
TEST_F(MrpFb, SmallErrorsTorqueOpposesError)
{
  // Pure P/K case (no reference motion, no integral): for random small
  // sigma alone sigma^T Lr = -K |sigma|^2 < 0; for omega_BR alone
  // omega^T Lr = -P |omega|^2 < 0 -- with law 1 and spinning wheels too,
  // because the gyroscopic term omega x H is perpendicular to omega.
  kt::Rng rng(0x5eed0003u);
  for (int trial = 0; trial < 200; trial++) {
    RefIn r = scenario();
    r.Ki = -1.0;
    r.law = trial % 2;
    r.n_rw = r.law == 1 ? 4 : 0;
    for (int i = 0; i < 3; i++) {
      r.wRN[i] = 0.0;
      r.dwRN[i] = 0.0;
      r.L[i] = 0.0;
    }
    double e[3];
    rng.unit3(e);
    const double a = rng.uniform(1e-4, 0.05);
    // sigma only
    for (int i = 0; i < 3; i++) {
      r.sigma[i] = a * e[i];
      r.wBR[i] = 0.0;
    }
    init(r, 0.0);
    ASSERT_EQ(FSW_OK, step(0));
    double Lr[3];
    gref::to_double(Lr, out_.torque_B);
    EXPECT_LT(gref::dot(r.sigma, Lr), 0.0) << trial;
    // omega only
    for (int i = 0; i < 3; i++) {
      r.sigma[i] = 0.0;
      r.wBR[i] = a * 0.1 * e[i];
    }
    init(r, 0.0);
    ASSERT_EQ(FSW_OK, step(0));
    gref::to_double(Lr, out_.torque_B);
    EXPECT_LT(gref::dot(r.wBR, Lr), 0.0) << trial;
  }
}

// Verifies: REQ-MRPFB-005
TEST_F(MrpFb, TimeMustIncrease)
{
  RefIn r = scenario();
  init(r, 20.0);
  ASSERT_EQ(FSW_OK, step(0));  // first call at t = 0 is legal
  ASSERT_EQ(FSW_OK, step(1000000000ull));
  double is[3];
  for (int i = 0; i < 3; i++) is[i] = st_.int_sigma[i];
  for (uint64_t t : {1000000000ull, 999999999ull, 0ull}) {
    EXPECT_EQ(FSW_E_TIME, step(t));
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.torque_B, 0.0);
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.int_torque_B, 0.0);
    EXPECT_V3_NEAR(is[0], is[1], is[2], st_.int_sigma, 0.0);  // no state advanced
    EXPECT_EQ(1000000000ull, st_.clock.t_prev_ns);
  }
  EXPECT_EQ(3u, st_.health.bad_time);
  // recovery: dt measured from the last accepted call (1 s), not the bad ones
  ASSERT_EQ(FSW_OK, step(2000000000ull));
  const RefIn rr = rounded(r);
  for (int i = 0; i < 3; i++) is[i] += rr.K * 1.0 * rr.sigma[i];
  EXPECT_V3_NEAR(is[0], is[1], is[2], st_.int_sigma, kt::tol(1e-16, 1e-8));
}

// Verifies: REQ-MRPFB-004
TEST_F(MrpFb, NonFiniteInputGivesZeroTorqueAndKeepsState)
{
  RefIn r = scenario();
  init(r, 20.0);
  ASSERT_EQ(FSW_OK, step(0));
  ASSERT_EQ(FSW_OK, step(1000000000ull));
  const FswMrpFbIn good = in_;
  double is[3];
  for (int i = 0; i < 3; i++) is[i] = st_.int_sigma[i];
  uint32_t n = 0;
  for (int f = 0; f < 4; f++) {
    for (int k = 0; k < 3; k++) {
      for (double v : {gref::nan(), gref::inf()}) {
        in_ = good;
        fsw_real* fld = f == 0 ? in_.guid.sigma_BR
                        : f == 1 ? in_.guid.omega_BR_B
                        : f == 2 ? in_.guid.omega_RN_B
                                 : in_.guid.omega_dot_RN_B;
        fld[k] = static_cast<fsw_real>(v);
        EXPECT_EQ(FSW_E_BAD_INPUT, step(2000000000ull));
        EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.torque_B, 0.0);
        n++;
      }
    }
  }
  // wheel speed of an available wheel; availability flag out of range
  in_ = good;
  in_.Omega[1] = static_cast<fsw_real>(gref::inf());
  EXPECT_EQ(FSW_E_BAD_INPUT, step(2000000000ull));
  in_ = good;
  in_.rw_avail[3] = 2;
  EXPECT_EQ(FSW_E_BAD_INPUT, step(2000000000ull));
  // finite but huge rate: omega x [I]omega overflows to Inf -> same safe output
  in_ = good;
  gref::set3(in_.guid.omega_BR_B, (kt::kFloat ? 1e30 : 1e200), 0.0, 0.0);
  gref::set3(in_.guid.omega_RN_B, 0.0, (kt::kFloat ? 1e30 : 1e200), 0.0);
  EXPECT_EQ(FSW_E_BAD_INPUT, step(2000000000ull));
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.torque_B, 0.0);
  n += 3;
  EXPECT_EQ(n, st_.health.bad_input);
  EXPECT_V3_NEAR(is[0], is[1], is[2], st_.int_sigma, 0.0);
  EXPECT_EQ(1000000000ull, st_.clock.t_prev_ns);
  // the next good call recovers
  in_ = good;
  EXPECT_EQ(FSW_OK, step(2000000000ull));
}

// Verifies: REQ-MRPFB-003
TEST_F(MrpFb, RejectsBadConfig)
{
  struct Case {
    const char* name;
    FswStatus want;
    void (*edit)(FswMrpFbConfig&);
  };
  const fsw_real kNan = static_cast<fsw_real>(gref::nan());
  (void)kNan;
  const Case cases[] = {
      {"K = 0", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.K = FSW_R(0.0); }},
      {"K < 0", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.K = FSW_R(-1.0); }},
      {"K nan", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.K = static_cast<fsw_real>(gref::nan()); }},
      {"P = 0", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.P = FSW_R(0.0); }},
      {"P inf", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.P = static_cast<fsw_real>(gref::inf()); }},
      {"K_i nan", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.K_i = static_cast<fsw_real>(gref::nan()); }},
      {"limit < 0", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.integral_limit = FSW_R(-1e-3); }},
      {"limit inf", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.integral_limit = static_cast<fsw_real>(gref::inf()); }},
      {"law 2", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.control_law_type = 2; }},
      {"law -1", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.control_law_type = -1; }},
      {"L nan", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.known_torque_B[1] = static_cast<fsw_real>(gref::nan()); }},
      {"I nan", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.I_B[2][2] = static_cast<fsw_real>(gref::nan()); }},
      {"I zero", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.I_B[0][0] = c.I_B[1][1] = c.I_B[2][2] = FSW_R(0.0); c.I_B[0][1] = c.I_B[1][0] = c.I_B[0][2] = c.I_B[2][0] = c.I_B[1][2] = c.I_B[2][1] = FSW_R(0.0); }},
      {"I not symmetric", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.I_B[0][1] = FSW_R(11.0); }},
      {"I not pos. def.", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.I_B[2][2] = FSW_R(-800.0); }},
      {"I indefinite minor", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.I_B[0][1] = c.I_B[1][0] = FSW_R(950.0); }},
      // m1 = 1000 > 0, m2 = 1000 * 800 - 950^2 = -102500 < 0, det = m2 * (-800)
      // = 8.2e7 > 0: only the second leading minor shows it is not positive
      // definite (issue 21)
      {"I second minor only", FSW_E_CONFIG, [](FswMrpFbConfig& c) {
         for (int j = 0; j < 3; j++)
           for (int k = 0; k < 3; k++) c.I_B[j][k] = FSW_R(0.0);
         c.I_B[0][0] = FSW_R(1000.0);
         c.I_B[1][1] = FSW_R(800.0);
         c.I_B[2][2] = FSW_R(-800.0);
         c.I_B[0][1] = c.I_B[1][0] = FSW_R(950.0);
       }},
      // m1 = -1000 < 0, m2 = (-1000)(-800) = 8e5 > 0, det = 8e5 * 800 > 0:
      // only the first leading minor shows it (issue 21)
      {"I first minor only", FSW_E_CONFIG, [](FswMrpFbConfig& c) {
         for (int j = 0; j < 3; j++)
           for (int k = 0; k < 3; k++) c.I_B[j][k] = FSW_R(0.0);
         c.I_B[0][0] = FSW_R(-1000.0);
         c.I_B[1][1] = FSW_R(-800.0);
         c.I_B[2][2] = FSW_R(800.0);
       }},
      // diag(1000, 800, 0): m1 = 1000 > 0, m2 = 8e5 > 0, det = 0 exactly (a
      // zero row): positive semi-definite, not definite; a zero principal
      // inertia is not a rigid body (issue 21, seed 9001)
      {"I semi-definite", FSW_E_CONFIG, [](FswMrpFbConfig& c) {
         for (int j = 0; j < 3; j++)
           for (int k = 0; k < 3; k++) c.I_B[j][k] = FSW_R(0.0);
         c.I_B[0][0] = FSW_R(1000.0);
         c.I_B[1][1] = FSW_R(800.0);
       }},
      {"num_rw < 0", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.num_rw = -1; }},
      {"num_rw > max", FSW_E_CAPACITY, [](FswMrpFbConfig& c) { c.num_rw = FSW_MAX_RW + 1; }},
      {"gs not unit", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.gs_hat_B[1][0] = FSW_R(0.6); }},
      {"gs zero", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.gs_hat_B[3][0] = c.gs_hat_B[3][1] = c.gs_hat_B[3][2] = FSW_R(0.0); }},
      {"gs nan", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.gs_hat_B[0][2] = static_cast<fsw_real>(gref::nan()); }},
      {"J_s = 0", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.J_s[2] = FSW_R(0.0); }},
      {"J_s nan", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.J_s[0] = static_cast<fsw_real>(gref::nan()); }},
      {"J_s inf", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.J_s[1] = std::numeric_limits<fsw_real>::infinity(); }},
      // issue 45 fuzzing: 1e307 kg m2 at 20 rad/s overflowed the momentum telemetry
      {"J_s 1e307", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.J_s[0] = static_cast<fsw_real>(1e307); }},
      {"J_s just above 1e4", FSW_E_CONFIG, [](FswMrpFbConfig& c) { c.J_s[3] = FSW_R(10000.01); }},
  };
  FswMrpFbConfig base{};
  FswMrpFbIn in{};
  load(scenario(), base, in, 20.0);
  ASSERT_EQ(FSW_OK, fsw_mrp_fb_check(&base));
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    FswMrpFbConfig cfg = base;
    k.edit(cfg);
    EXPECT_EQ(k.want, fsw_mrp_fb_check(&cfg));
    FswMrpFbState st{};
    EXPECT_EQ(k.want, fsw_mrp_fb_init(&st, &cfg));
    EXPECT_EQ(0, st.ready);
    out_.torque_B[0] = FSW_R(3.0);
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_mrp_fb_update(&st, &cfg, &in, &out_));
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.torque_B, 0.0);
  }
  // legal boundaries: K_i = 0, limit = 0, no wheels, wheel count at capacity
  FswMrpFbConfig ok = base;
  ok.K_i = FSW_R(0.0);
  ok.integral_limit = FSW_R(0.0);
  ok.num_rw = 0;
  EXPECT_EQ(FSW_OK, fsw_mrp_fb_check(&ok));
  ok.num_rw = FSW_MAX_RW;
  for (int k = 0; k < FSW_MAX_RW; k++) {
    gref::set3(ok.gs_hat_B[k], 0.0, 0.0, 1.0);
    ok.J_s[k] = FSW_R(0.05);
  }
  ok.J_s[FSW_MAX_RW - 1] = FSW_R(1e4); // the largest spin inertia, FSW_RW_J_S_MAX
  EXPECT_EQ(FSW_OK, fsw_mrp_fb_check(&ok));
}

// Verifies: REQ-MRPFB-006
TEST_F(MrpFb, ResetClearsIntegralAndTimingAndIsRepeatable)
{
  RefIn r = scenario();
  init(r, 20.0);
  const uint64_t times[] = {5000000000ull, 5100000000ull, 5200000000ull, 5350000000ull};
  FswMrpFbOut first[4];
  for (int k = 0; k < 4; k++) {
    ASSERT_EQ(FSW_OK, step(times[k]));
    first[k] = out_;
  }
  fsw_mrp_fb_reset(&st_);
  EXPECT_EQ(0, st_.clock.has_prev);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, st_.int_sigma, 0.0);
  EXPECT_EQ(1, st_.ready);
  EXPECT_EQ(4u, st_.health.calls);  // counters survive reset
  // after reset an earlier time stamp is legal again (first call)
  for (int k = 0; k < 4; k++) {
    ASSERT_EQ(FSW_OK, step(times[k]));
    for (int i = 0; i < 3; i++) {
      EXPECT_EQ(first[k].torque_B[i], out_.torque_B[i]);
      EXPECT_EQ(first[k].int_torque_B[i], out_.int_torque_B[i]);
    }
  }
}

// docs/fsw-conventions.md, "Reset and the output" says reset zeroes the output; the output belongs to
// the caller, so the project's reading (docs/fsw-conventions.md) is: the
// first update after reset writes its documented safe output on bad input,
// never what the caller's buffer held before the reset.
// Verifies: REQ-MRPFB-004, REQ-MRPFB-006
TEST_F(MrpFb, ResetThenBadInputGivesTheSafeOutputNotStaleValues)
{
  RefIn r = scenario();
  init(r, 20.0);
  ASSERT_EQ(FSW_OK, step(5000000000ull));
  ASSERT_EQ(FSW_OK, step(5100000000ull));
  ASSERT_TRUE(out_.torque_B[0] != 0 || out_.torque_B[1] != 0 || out_.torque_B[2] != 0);
  fsw_mrp_fb_reset(&st_);
  const fsw_real keep = in_.guid.sigma_BR[1];
  in_.guid.sigma_BR[1] = std::numeric_limits<fsw_real>::quiet_NaN();
  EXPECT_EQ(FSW_E_BAD_INPUT, step(100));
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.torque_B, 0.0);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.int_torque_B, 0.0);
  // nothing advanced: the next good call is still the first after reset
  // (an earlier stamp is legal) and equals a fresh module's first output
  in_.guid.sigma_BR[1] = keep;
  EXPECT_EQ(0, st_.clock.has_prev);
  ASSERT_EQ(FSW_OK, step(50));
  FswMrpFbState fresh{};
  FswMrpFbOut want{};
  ASSERT_EQ(FSW_OK, fsw_mrp_fb_init(&fresh, &cfg_));
  in_.t_ns = 50;
  ASSERT_EQ(FSW_OK, fsw_mrp_fb_update(&fresh, &cfg_, &in_, &want));
  for (int i = 0; i < 3; i++) {
    EXPECT_EQ(want.torque_B[i], out_.torque_B[i]);
    EXPECT_EQ(want.int_torque_B[i], out_.int_torque_B[i]);
  }
}

// Verifies: REQ-GEN-007
TEST_F(MrpFb, NullPointersAssert)
{
  RefIn r = scenario();
  init(r, 20.0);
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_mrp_fb_update(&st_, &cfg_, nullptr, &out_));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_mrp_fb_init(&st_, nullptr));
  EXPECT_EQ(2ul, kestrel_assert_count());
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.torque_B, 0.0);
}

}  // namespace

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(MrpFbNullIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("mrp_fb", fsw_mrp_fb_check, fsw_mrp_fb_init, fsw_mrp_fb_reset, fsw_mrp_fb_update);
}

// fsw_acs calls the law without the update's input checks (its guidance is
// a stage's finite output and its wheel flags and speeds are checked before
// any stage runs): for every input that passes them the output, the status
// and the state (integral, clock, health) are the update's, bit for bit,
// over a run of seeded guidance, both laws, the integral on, off and
// clamped, wheels dropping out (NaN speeds on them, not read), time stamps
// that do not advance and finite rates so large that Lr overflows.
// Verifies: REQ-MRPFB-001, REQ-MRPFB-004
TEST(MrpFbTorque, TorqueOfACheckedInputIsTheUpdate)
{
  kt::Rng rng(0x5eed0045u);
  int seen_ok = 0, seen_time = 0, seen_bad = 0, seen_clamp = 0;
  for (int run = 0; run < 12; run++) {
    RefIn r = scenario();
    r.law = run % 2;
    r.Ki = (run % 3 == 0) ? -1.0 : 0.01 * (1 + run);
    FswMrpFbConfig c{};
    FswMrpFbIn in{};
    load(r, c, in, (run % 4 == 1) ? 1e-3 : 20.0);
    FswMrpFbState st_u{}, st_t{};
    ASSERT_EQ(FSW_OK, fsw_mrp_fb_init(&st_u, &c));
    ASSERT_EQ(FSW_OK, fsw_mrp_fb_init(&st_t, &c));
    uint64_t t = 0;
    for (int k = 0; k < 400; k++) {
      for (int i = 0; i < 3; i++) {
        in.guid.sigma_BR[i] = static_cast<fsw_real>(rng.uniform(-1.0, 1.0));
        in.guid.omega_BR_B[i] = static_cast<fsw_real>(rng.uniform(-0.1, 0.1));
        in.guid.omega_RN_B[i] = static_cast<fsw_real>(rng.uniform(-0.01, 0.01));
        in.guid.omega_dot_RN_B[i] = static_cast<fsw_real>(rng.uniform(-1e-3, 1e-3));
      }
      for (int w = 0; w < c.num_rw; w++) {
        in.rw_avail[w] = (rng.uniform() < 0.2) ? FSW_UNAVAILABLE : FSW_AVAILABLE;
        in.Omega[w] = (in.rw_avail[w] == FSW_UNAVAILABLE && (k % 2) == 0)
                          ? static_cast<fsw_real>(gref::nan())
                          : static_cast<fsw_real>(rng.uniform(-300.0, 300.0));
      }
      if (k % 37 == 5) {  // finite but huge: Lr overflows
        in.guid.omega_BR_B[0] = static_cast<fsw_real>(kt::kFloat ? 1e30 : 1e200);
        in.guid.omega_RN_B[1] = static_cast<fsw_real>(kt::kFloat ? 1e30 : 1e200);
      }
      if (k % 29 != 7) t += 100000000ull;  // else the same stamp again: FSW_E_TIME
      if (k % 101 == 50) {
        fsw_mrp_fb_reset(&st_u);
        fsw_mrp_fb_reset(&st_t);
      }
      in.t_ns = t;
      FswMrpFbOut out_u{}, out_t{};
      const FswStatus su = fsw_mrp_fb_update(&st_u, &c, &in, &out_u);
      const FswStatus stq = fsw_mrp_fb_torque(&st_t, &c, &in.guid, in.t_ns, in.Omega, in.rw_avail, &out_t);
      ASSERT_EQ(su, stq) << run << " " << k;
      ASSERT_EQ(0, std::memcmp(&out_u, &out_t, sizeof out_u)) << run << " " << k;
      ASSERT_EQ(0, std::memcmp(&st_u, &st_t, sizeof st_u)) << run << " " << k;
      seen_ok += (su == FSW_OK);
      seen_time += (su == FSW_E_TIME);
      seen_bad += (su == FSW_E_BAD_INPUT);
      for (int i = 0; i < 3; i++) {
        seen_clamp += (r.Ki > 0 && std::fabs(static_cast<double>(st_u.int_sigma[i])) ==
                                       static_cast<double>(c.integral_limit));
      }
    }
  }
  EXPECT_GT(seen_ok, 3000);
  EXPECT_GT(seen_time, 50);
  EXPECT_GT(seen_bad, 50);
  EXPECT_GT(seen_clamp, 0);
  // a state that is not ready: FSW_E_NOT_INIT and the safe output, as the update
  RefIn r = scenario();
  FswMrpFbConfig c{};
  FswMrpFbIn in{};
  load(r, c, in, 20.0);
  FswMrpFbState idle{};
  FswMrpFbOut out{};
  out.torque_B[0] = FSW_R(1.0);
  EXPECT_EQ(FSW_E_NOT_INIT, fsw_mrp_fb_torque(&idle, &c, &in.guid, in.t_ns, in.Omega, in.rw_avail, &out));
  EXPECT_EQ(FSW_R(0.0), out.torque_B[0]);
  EXPECT_EQ(1u, idle.health.calls);
}

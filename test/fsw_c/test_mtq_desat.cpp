// mtq_desat: wheel momentum desaturation by magnetorquers (cross-product
// law).  Expected values: hand numbers, the identity (h x B) x B =
// (h.B) B - |B|^2 h, and a closed-loop integration written here (the wheel
// momentum changes by the magnetic torque mtq_map achieves).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "fsw/mtq_desat.h"
#include "fsw/mtq_map.h"
#include "kestrel_test_support.h"
#include "mtq_test_util.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
const fsw_real kInf = std::numeric_limits<fsw_real>::infinity();
const double kPi = 3.14159265358979323846;

using mtqt::cross;
using mtqt::dot;
using mtqt::norm;
using rwt::make0;

struct Fixture {
  std::unique_ptr<FswMtqDesatConfig> cfg = make0<FswMtqDesatConfig>();
  std::unique_ptr<FswMtqDesatState> st = make0<FswMtqDesatState>();
  std::unique_ptr<FswMtqDesatIn> in = make0<FswMtqDesatIn>();
  std::unique_ptr<FswMtqDesatOut> out = make0<FswMtqDesatOut>();

  // Three orthogonal wheels, J_s = 0.01 kg*m^2.
  void setup(double k = 0.01, double tau_max = 1.0)
  {
    cfg->num_rw = 3;
    for (int i = 0; i < 3; i++) {
      cfg->gs_hat_B[i][i] = FSW_R(1.0);
      cfg->J_s[i] = FSW_R(0.01);
    }
    cfg->k_desat = static_cast<fsw_real>(k);
    cfg->tau_max = static_cast<fsw_real>(tau_max);
    in->B_valid = 1;
  }
  FswStatus init() { return fsw_mtq_desat_init(st.get(), cfg.get()); }
  FswStatus update() { return fsw_mtq_desat_update(st.get(), cfg.get(), in.get(), out.get()); }
  void set_B(double x, double y, double z)
  {
    in->B_B[0] = static_cast<fsw_real>(x);
    in->B_B[1] = static_cast<fsw_real>(y);
    in->B_B[2] = static_cast<fsw_real>(z);
  }
  void garbage() { std::memset(out.get(), 0x5A, sizeof *out); }
  void expect_zero_request(const char* why) const
  {
    for (int k = 0; k < 3; k++) {
      EXPECT_EQ(out->tau_req_B[k], 0.0) << why;
      EXPECT_EQ(out->m_B[k], 0.0) << why;
    }
    EXPECT_EQ(out->scale, 0.0) << why;
  }
  void expect_safe(const char* why) const
  {
    expect_zero_request(why);
    for (int k = 0; k < 3; k++) {
      EXPECT_EQ(out->h_w_B[k], 0.0) << why;
      EXPECT_EQ(out->h_err_B[k], 0.0) << why;
    }
    EXPECT_EQ(out->h_err_norm, 0.0) << why;
  }
};

std::unique_ptr<Fixture> nominal(double k = 0.01, double tau_max = 1.0)
{
  auto f = make0<Fixture>();
  f->setup(k, tau_max);
  EXPECT_EQ(f->init(), FSW_OK);
  return f;
}

// The hand example: Omega = (100, -50, 20) rad/s -> h_w = (1, -0.5, 0.2) N*m*s,
// h_target = (0.1, 0, 0) -> h_err = (0.9, -0.5, 0.2); B = (0, 3, 4) 1e-5 T.
void hand_input(Fixture& f)
{
  f.in->Omega[0] = FSW_R(100.0);
  f.in->Omega[1] = FSW_R(-50.0);
  f.in->Omega[2] = FSW_R(20.0);
  f.cfg->h_target_B[0] = FSW_R(0.1);
  f.set_B(0, 3e-5, 4e-5);
}

}  // namespace

// Verifies: REQ-MTQDS-001
TEST(MtqDesatConfig, RejectsBadConfigurationsTableDriven)
{
  struct Row {
    const char* why;
    void (*spoil)(FswMtqDesatConfig*);
    FswStatus want;
  };
  static const Row rows[] = {
      {"no wheels", [](FswMtqDesatConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many wheels", [](FswMtqDesatConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"axis not unit", [](FswMtqDesatConfig* c) { c->gs_hat_B[0][0] = FSW_R(0.9); }, FSW_E_CONFIG},
      {"axis NaN", [](FswMtqDesatConfig* c) { c->gs_hat_B[2][1] = kNaN; }, FSW_E_CONFIG},
      {"J_s zero", [](FswMtqDesatConfig* c) { c->J_s[1] = 0; }, FSW_E_CONFIG},
      {"J_s negative", [](FswMtqDesatConfig* c) { c->J_s[1] = FSW_R(-0.01); }, FSW_E_CONFIG},
      {"J_s too large", [](FswMtqDesatConfig* c) { c->J_s[0] = FSW_R(2e4); }, FSW_E_CONFIG},
      {"J_s NaN", [](FswMtqDesatConfig* c) { c->J_s[2] = kNaN; }, FSW_E_CONFIG},
      {"k_desat zero", [](FswMtqDesatConfig* c) { c->k_desat = 0; }, FSW_E_CONFIG},
      {"k_desat negative", [](FswMtqDesatConfig* c) { c->k_desat = FSW_R(-1e-3); }, FSW_E_CONFIG},
      {"k_desat too large", [](FswMtqDesatConfig* c) { c->k_desat = FSW_R(2e3); }, FSW_E_CONFIG},
      {"k_desat Inf", [](FswMtqDesatConfig* c) { c->k_desat = kInf; }, FSW_E_CONFIG},
      {"h_target NaN", [](FswMtqDesatConfig* c) { c->h_target_B[1] = kNaN; }, FSW_E_CONFIG},
      {"h_target too large", [](FswMtqDesatConfig* c) { c->h_target_B[2] = FSW_R(-2e8); }, FSW_E_CONFIG},
      {"tau_max zero", [](FswMtqDesatConfig* c) { c->tau_max = 0; }, FSW_E_CONFIG},
      {"tau_max below range", [](FswMtqDesatConfig* c) { c->tau_max = FSW_R(1e-10); }, FSW_E_CONFIG},
      {"tau_max above range", [](FswMtqDesatConfig* c) { c->tau_max = FSW_R(2e4); }, FSW_E_CONFIG},
      {"tau_max NaN", [](FswMtqDesatConfig* c) { c->tau_max = kNaN; }, FSW_E_CONFIG},
      {"h_deadband negative", [](FswMtqDesatConfig* c) { c->h_deadband = FSW_R(-1e-3); }, FSW_E_CONFIG},
      {"h_deadband NaN", [](FswMtqDesatConfig* c) { c->h_deadband = kNaN; }, FSW_E_CONFIG},
      {"h_deadband too large", [](FswMtqDesatConfig* c) { c->h_deadband = FSW_R(2e8); }, FSW_E_CONFIG},
  };
  for (const Row& row : rows) {
    auto f = nominal();
    row.spoil(f->cfg.get());
    EXPECT_EQ(fsw_mtq_desat_check(f->cfg.get()), row.want) << row.why;
    EXPECT_EQ(f->init(), row.want) << row.why;
    EXPECT_EQ(f->st->ready, 0) << row.why;
    hand_input(*f);
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_NOT_INIT) << row.why;
    f->expect_safe(row.why);
  }
  auto f = nominal();
  f->cfg->h_deadband = 0;  // 0 is allowed
  EXPECT_EQ(fsw_mtq_desat_check(f->cfg.get()), FSW_OK);
}

// h_err = (0.9, -0.5, 0.2), b = (0, 0.6, 0.8): h.b = -0.14,
// h_perp = (0.9, -0.416, 0.312), tau = -0.01 h_perp = (-9e-3, 4.16e-3, -3.12e-3);
// h x B = (-2.6e-5, -3.6e-5, 2.7e-5), /|B|^2 (2.5e-9) x 0.01 = (-104, -144, 108) A*m^2.
// Verifies: REQ-MTQDS-002
TEST(MtqDesatNominal, ClosedFormHandNumbers)
{
  auto f = nominal();
  hand_input(*f);
  ASSERT_EQ(f->init(), FSW_OK);
  f->garbage();
  ASSERT_EQ(f->update(), FSW_OK);
  const double hw[3] = {1, -0.5, 0.2}, he[3] = {0.9, -0.5, 0.2};
  const double tau[3] = {-9e-3, 4.16e-3, -3.12e-3}, m[3] = {-104, -144, 108};
  const double r = kt::tol(1e-14, 1e-6);
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(f->out->h_w_B[k], hw[k], r) << k;
    EXPECT_NEAR(f->out->h_err_B[k], he[k], r) << k;
    EXPECT_NEAR(f->out->tau_req_B[k], tau[k], r * 1e-2) << k;
    EXPECT_NEAR(f->out->m_B[k], m[k], r * 200) << k;
  }
  EXPECT_NEAR(f->out->h_err_norm, std::sqrt(0.81 + 0.25 + 0.04), r);
  EXPECT_EQ(f->out->scale, 1.0);
  // m x B = tau_req, and tau_req is perpendicular to B
  double md[3], B[3], mxB[3], t[3];
  for (int k = 0; k < 3; k++) {
    md[k] = f->out->m_B[k];
    B[k] = f->in->B_B[k];
    t[k] = f->out->tau_req_B[k];
  }
  cross(mxB, md, B);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(mxB[k], t[k], kt::tol(1e-15, 1e-6) * norm(t)) << k;
  EXPECT_LE(std::fabs(dot(t, B)), kt::tol(1e-15, 1e-7) * norm(t) * norm(B));
}

// The law against its closed form for random momenta, fields and wheel sets
// (three to six wheels with random axes): m x B = -k h_err_perp to 1e-12.
// Verifies: REQ-MTQDS-002
TEST(MtqDesatNominal, CrossProductIdentityOnRandomCases)
{
  kt::Rng rng(3811);
  double worst = 0.0;
  for (int trial = 0; trial < 300; trial++) {
    auto f = make0<Fixture>();
    f->setup(rng.uniform(1e-4, 1e-2), 1e4);
    const int n = rng.uniform_int(3, 6 < FSW_MAX_RW ? 6 : FSW_MAX_RW);
    f->cfg->num_rw = n;
    for (int i = 0; i < n; i++) {
      double g[3];
      rng.unit3(g);
      for (int k = 0; k < 3; k++) f->cfg->gs_hat_B[i][k] = static_cast<fsw_real>(g[k]);
      f->cfg->J_s[i] = static_cast<fsw_real>(rng.uniform(0.005, 0.05));
      f->in->Omega[i] = static_cast<fsw_real>(rng.uniform(-600, 600));
      f->in->avail[i] = rng.uniform() < 0.2 ? FSW_UNAVAILABLE : FSW_AVAILABLE;
    }
    for (int k = 0; k < 3; k++) f->cfg->h_target_B[k] = static_cast<fsw_real>(rng.uniform(-1, 1));
    ASSERT_EQ(f->init(), FSW_OK);
    double b[3];
    rng.unit3(b);
    const double Bm = rng.uniform(1.5e-5, 6e-5);
    f->set_B(b[0] * Bm, b[1] * Bm, b[2] * Bm);
    ASSERT_EQ(f->update(), FSW_OK) << trial;
    // independent: h_w, h_err, h_perp and -k h_perp here
    double h[3] = {0, 0, 0}, B[3], mB[3], mxB[3], want[3];
    for (int i = 0; i < n; i++)
      if (f->in->avail[i] == FSW_AVAILABLE)
        for (int k = 0; k < 3; k++) h[k] += double(f->cfg->J_s[i]) * double(f->in->Omega[i]) * double(f->cfg->gs_hat_B[i][k]);
    for (int k = 0; k < 3; k++) {
      EXPECT_NEAR(f->out->h_w_B[k], h[k], kt::tol(1e-12, 1e-4)) << trial;
      h[k] -= double(f->cfg->h_target_B[k]);
      B[k] = f->in->B_B[k];
      mB[k] = f->out->m_B[k];
    }
    const double s = dot(h, B) / dot(B, B), k_d = f->cfg->k_desat;
    for (int k = 0; k < 3; k++) want[k] = -k_d * (h[k] - s * B[k]);
    cross(mxB, mB, B);
    double e = 0.0, e2 = 0.0;
    for (int k = 0; k < 3; k++) {
      e += (mxB[k] - want[k]) * (mxB[k] - want[k]);
      e2 += (double(f->out->tau_req_B[k]) - want[k]) * (double(f->out->tau_req_B[k]) - want[k]);
    }
    worst = std::fmax(worst, std::fmax(std::sqrt(e), std::sqrt(e2)) / (k_d * norm(h)));
  }
  EXPECT_LE(worst, kt::tol(1e-12, 1e-5));
  std::printf("[ figures ] |m x B + k h_perp| and |tau_req + k h_perp| / (k |h_err|) worst %.3g (300 cases)\n", worst);
}

// tau_max limits the magnitude, the direction stays: |tau| = 0.0103957...
// Verifies: REQ-MTQDS-003
TEST(MtqDesatNominal, TorqueLimitKeepsTheDirection)
{
  auto f = nominal(0.01, 0.005);
  hand_input(*f);
  ASSERT_EQ(f->init(), FSW_OK);
  ASSERT_EQ(f->update(), FSW_W_SAT);
  const double full = std::sqrt(9e-3 * 9e-3 + 4.16e-3 * 4.16e-3 + 3.12e-3 * 3.12e-3);
  const double s = 0.005 / full;
  const double tau[3] = {-9e-3, 4.16e-3, -3.12e-3}, m[3] = {-104, -144, 108};
  EXPECT_NEAR(f->out->scale, s, kt::tol(1e-14, 1e-6));
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(f->out->tau_req_B[k], s * tau[k], kt::tol(1e-16, 1e-8)) << k;
    EXPECT_NEAR(f->out->m_B[k], s * m[k], kt::tol(1e-11, 1e-3)) << k;
  }
  double t[3] = {f->out->tau_req_B[0], f->out->tau_req_B[1], f->out->tau_req_B[2]};
  EXPECT_NEAR(norm(t), 0.005, kt::tol(1e-16, 1e-9));
  EXPECT_EQ(f->st->health.saturated, 1u);
}

// Inside the deadband: no request, momentum still reported.
// Verifies: REQ-MTQDS-003
TEST(MtqDesatNominal, DeadbandGivesNoRequest)
{
  auto f = nominal();
  f->cfg->h_deadband = FSW_R(1.1);  // |h_err| = sqrt(1.1) = 1.0488
  hand_input(*f);
  ASSERT_EQ(f->init(), FSW_OK);
  f->garbage();
  ASSERT_EQ(f->update(), FSW_OK);
  f->expect_zero_request("deadband");
  EXPECT_NEAR(f->out->h_err_B[0], 0.9, kt::tol(1e-14, 1e-6));
  f->cfg->h_deadband = FSW_R(1.0);
  ASSERT_EQ(f->init(), FSW_OK);
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->scale, 1.0);
  EXPECT_NE(f->out->tau_req_B[0], 0.0);
}

// Unavailable wheels are not counted and their speeds not read.
// Verifies: REQ-MTQDS-002
TEST(MtqDesatNominal, UnavailableWheelNotCounted)
{
  auto f = nominal();
  hand_input(*f);
  f->in->avail[1] = FSW_UNAVAILABLE;
  f->in->Omega[1] = kNaN;
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_NEAR(f->out->h_w_B[0], 1.0, kt::tol(1e-14, 1e-6));
  EXPECT_EQ(f->out->h_w_B[1], 0.0);
  EXPECT_NEAR(f->out->h_w_B[2], 0.2, kt::tol(1e-14, 1e-6));
}

// No usable field: no request (W_SINGULAR); the momentum is still reported.
// Verifies: REQ-MTQDS-004
TEST(MtqDesatField, InvalidOrTinyFieldGivesNoRequest)
{
  for (int c = 0; c < 3; c++) {
    auto f = nominal();
    hand_input(*f);
    if (c == 0) {
      f->in->B_valid = 0;
      f->in->B_B[0] = kNaN;  // not read
    } else {
      f->set_B(0, 0, c == 1 ? 0.0 : 5e-10);
    }
    f->garbage();
    EXPECT_EQ(f->update(), FSW_W_SINGULAR) << c;
    f->expect_zero_request("no field");
    EXPECT_NEAR(f->out->h_err_B[1], -0.5, kt::tol(1e-14, 1e-6)) << c;
    EXPECT_NEAR(f->out->h_err_norm, std::sqrt(1.1), kt::tol(1e-14, 1e-6)) << c;
    EXPECT_EQ(f->st->health.singular, 1u);
  }
}

// Verifies: REQ-MTQDS-005
TEST(MtqDesatBadInput, SafeOutputAndNoStateChange)
{
  struct Row {
    const char* why;
    void (*spoil)(FswMtqDesatIn*);
  };
  static const Row rows[] = {
      {"mask 3", [](FswMtqDesatIn* in) { in->avail[0] = 3; }},
      {"B_valid 2", [](FswMtqDesatIn* in) { in->B_valid = 2; }},
      {"Omega NaN", [](FswMtqDesatIn* in) { in->Omega[2] = kNaN; }},
      {"Omega Inf", [](FswMtqDesatIn* in) { in->Omega[0] = -kInf; }},
      {"Omega beyond range", [](FswMtqDesatIn* in) { in->Omega[1] = FSW_R(2e4); }},
      {"B NaN", [](FswMtqDesatIn* in) { in->B_B[2] = kNaN; }},
      {"|B| above 1 T", [](FswMtqDesatIn* in) { in->B_B[1] = FSW_R(-3.0); }},
  };
  for (const Row& row : rows) {
    auto f = nominal();
    hand_input(*f);
    ASSERT_EQ(f->update(), FSW_OK);
    FswMtqDesatState before, masked;
    std::memcpy(&before, f->st.get(), sizeof before);
    row.spoil(f->in.get());
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_BAD_INPUT) << row.why;
    f->expect_safe(row.why);
    EXPECT_EQ(f->st->health.bad_input, 1u) << row.why;
    std::memcpy(&masked, f->st.get(), sizeof masked);
    masked.health = before.health;
    EXPECT_EQ(std::memcmp(&masked, &before, sizeof before), 0) << row.why;
  }
}

// Closed loop with a turning field.  The wheels hold the attitude and take
// up the achieved magnetic torque (the feedforward): dh/dt = tau_ach, with
// tau_ach from mtq_map (orthogonal rods, torque mode) fed tau_req_B.  The
// field turns on a cone of half-angle 60 deg about z at the orbit rate
// (T = 5400 s), the direction pattern of an inclined dipole seen from a
// fixed attitude.  |h_err| never grows (d|h|^2/dt = -2k |h_perp|^2), and
// over ten orbits it decays at the orbit-averaged rates: <I - b b^T> =
// diag(0.625, 0.625, 0.75), so |h_err| ends between exp(-k t) and
// exp(-0.625 k t) of its start (with margin for the ripple).
// Verifies: REQ-MTQDS-006
TEST(MtqDesatClosedLoop, RotatingFieldUnloadsEveryAxis)
{
  const double k = 1e-4, T = 5400.0, dt = 2.0, Bm = 3e-5, alpha = kPi / 3;
  auto d = nominal(k, 1.0);
  auto map = make0<FswMtqMapConfig>();
  auto mst = make0<FswMtqMapState>();
  auto min = make0<FswMtqMapIn>();
  auto mout = make0<FswMtqMapOut>();
  map->num_mtq = 3;
  for (int i = 0; i < 3; i++) {
    map->gt_hat_B[i][i] = FSW_R(1.0);
    map->m_max[i] = FSW_R(1e4);
  }
  map->duty_max = FSW_R(1.0);
  ASSERT_EQ(fsw_mtq_map_init(mst.get(), map.get()), FSW_OK);
  const double J = 0.01;
  double h[3] = {0.05, -0.03, 0.04};  // [N*m*s] wheel momentum, target 0
  const double h0 = norm(h);
  double prev = h0;
  int grew = 0;
  const int steps = static_cast<int>(10 * T / dt);
  for (int s = 0; s < steps; s++) {
    const double t = s * dt, w = 2 * kPi / T;
    for (int i = 0; i < 3; i++) d->in->Omega[i] = static_cast<fsw_real>(h[i] / J);
    d->set_B(Bm * std::sin(alpha) * std::cos(w * t), Bm * std::sin(alpha) * std::sin(w * t), Bm * std::cos(alpha));
    ASSERT_EQ(d->update(), FSW_OK) << s;
    for (int q = 0; q < 3; q++) {
      min->tau_B[q] = d->out->tau_req_B[q];
      min->B_B[q] = d->in->B_B[q];
    }
    min->B_valid = 1;
    ASSERT_EQ(fsw_mtq_map_update(mst.get(), map.get(), min.get(), mout.get()), FSW_OK) << s;
    for (int q = 0; q < 3; q++) h[q] += double(mout->tau_ach_B[q]) * dt;
    const double now = norm(h);
    if (now > prev * (1 + kt::tol(1e-12, 1e-5))) grew++;
    prev = now;
  }
  const double tt = steps * dt, ratio = norm(h) / h0;
  EXPECT_EQ(grew, 0);
  EXPECT_LT(ratio, 1.5 * std::exp(-0.625 * k * tt));
  EXPECT_GT(ratio, std::exp(-k * tt));
  EXPECT_LT(std::fabs(h[2]) / h0, 1.5 * std::exp(-0.75 * k * tt));
  std::printf("[ figures ] rotating field, k = 1e-4 1/s, 10 orbits: |h_err| %.4g -> %.4g (ratio %.4g; "
              "averaged bounds exp(-k t) = %.4g, exp(-0.625 k t) = %.4g)\n",
              h0, norm(h), ratio, std::exp(-k * tt), std::exp(-0.625 * k * tt));
}

// A fixed field: the part of h_err along B is never touched; the
// perpendicular part decays as (1 - k dt)^n (forward Euler of dh/dt = -k h_perp).
// Verifies: REQ-MTQDS-006
TEST(MtqDesatClosedLoop, FixedFieldLeavesTheParallelPartUntouched)
{
  const double k = 1e-3, dt = 1.0, J = 0.01;
  auto d = nominal(k, 1.0);
  d->set_B(1e-5, -2e-5, 2e-5);  // |B| = 3e-5, b = (1, -2, 2)/3
  const double b[3] = {1.0 / 3, -2.0 / 3, 2.0 / 3};
  double h[3] = {0.02, 0.05, -0.01};
  const double par0 = dot(h, b);
  double perp0[3];
  for (int q = 0; q < 3; q++) perp0[q] = h[q] - par0 * b[q];
  const int n = 2000;
  for (int s = 0; s < n; s++) {
    for (int i = 0; i < 3; i++) d->in->Omega[i] = static_cast<fsw_real>(h[i] / J);
    ASSERT_EQ(d->update(), FSW_OK);
    for (int q = 0; q < 3; q++) h[q] += double(d->out->tau_req_B[q]) * dt;
  }
  const double par = dot(h, b), decay = std::pow(1 - k * dt, n);
  EXPECT_NEAR(par, par0, kt::tol(1e-12, 1e-5) * norm(perp0));
  for (int q = 0; q < 3; q++) EXPECT_NEAR(h[q] - par * b[q], decay * perp0[q], kt::tol(1e-12, 1e-5) * norm(perp0)) << q;
  std::printf("[ figures ] fixed field, 2000 s at k = 1e-3: h.b %.6g -> %.6g, |h_perp| %.4g -> %.4g (expected %.4g)\n",
              par0, par, norm(perp0), std::sqrt(std::pow(norm(h), 2) - par * par), decay * norm(perp0));
}

// Verifies: REQ-MTQDS-007
TEST(MtqDesatRepeatability, SameInputsGiveIdenticalOutputs)
{
  auto f = nominal();
  hand_input(*f);
  ASSERT_EQ(f->update(), FSW_OK);
  auto first = make0<FswMtqDesatOut>();
  std::memcpy(first.get(), f->out.get(), sizeof *first);
  fsw_mtq_desat_reset(f->st.get());
  EXPECT_EQ(f->st->ready, 1);
  f->garbage();
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(std::memcmp(first.get(), f->out.get(), sizeof *first), 0);
  EXPECT_EQ(f->st->health.calls, 2u);
}

// Verifies: REQ-GEN-007
TEST(MtqDesatIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("mtq_desat", fsw_mtq_desat_check, fsw_mtq_desat_init, fsw_mtq_desat_reset,
                       fsw_mtq_desat_update);
}

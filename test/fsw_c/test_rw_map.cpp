// rw_map: minimum-norm and L2 power-optimal (docs/fsw/rw_map.md) wheel
// torque mapping.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/rw_common.h"
#include "fsw/rw_map.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_map_internal.h"
#include "rw_test_util.h"

namespace {

const double kI3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

struct Fixture {
  std::unique_ptr<FswRwMapConfig> cfg = rwt::make0<FswRwMapConfig>();
  std::unique_ptr<FswRwMapState> st = rwt::make0<FswRwMapState>();
  std::unique_ptr<FswRwMapIn> in = rwt::make0<FswRwMapIn>();
  std::unique_ptr<FswRwMapOut> out = rwt::make0<FswRwMapOut>();

  // all three body axes controlled, given wheel axes
  void setup(const double g[][3], int n, int mode = FSW_RW_MAP_MIN_NORM)
  {
    cfg->num_rw = n;
    rwt::set_axes(cfg->gs_hat_B, g, n);
    cfg->num_axes = 3;
    for (int j = 0; j < 3; j++)
      for (int r = 0; r < 3; r++) cfg->ctrl_axes_B[j][r] = static_cast<fsw_real>(kI3[j][r]);
    cfg->mode = mode;
    cfg->eps_P = FSW_RW_MAP_EPS_P_DEFAULT;
  }
  FswStatus init() { return fsw_rw_map_init(st.get(), cfg.get()); }
  FswStatus update() { return fsw_rw_map_update(st.get(), cfg.get(), in.get(), out.get()); }
  void set_Lr(double x, double y, double z)
  {
    in->Lr_B[0] = static_cast<fsw_real>(x);
    in->Lr_B[1] = static_cast<fsw_real>(y);
    in->Lr_B[2] = static_cast<fsw_real>(z);
  }
  void fill_out_with_garbage()
  {
    for (int i = 0; i < FSW_MAX_RW; i++) out->u_s[i] = static_cast<fsw_real>(123.0);
  }
};

Fixture pyramid(int mode = FSW_RW_MAP_MIN_NORM)
{
  double g[4][3];
  rwt::pyramid4(g);
  Fixture f;
  f.setup(g, 4, mode);
  EXPECT_EQ(f.init(), FSW_OK);
  return f;
}

void expect_all_zero(const FswRwMapOut& out)
{
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(out.u_s[i], 0.0) << "wheel " << i;
}

double rel_residual(const FswRwMapConfig& cfg, const fsw_real* u, const fsw_real* Lr)
{
  double t[3];
  rwt::gs_times(t, cfg.gs_hat_B, u, cfg.num_rw);
  double r[3], L[3];
  for (int k = 0; k < 3; k++) {
    L[k] = static_cast<double>(Lr[k]);
    r[k] = t[k] + L[k];  // [Gs] u = -Lr
  }
  return rwt::norm3(r) / rwt::norm3(L);
}

}  // namespace

// ---- configuration -------------------------------------------------------

// Verifies: REQ-RWMAP-001
TEST(RwMapConfig, RejectsBadConfigurationsTableDriven)
{
  struct Row {
    const char* why;
    void (*spoil)(FswRwMapConfig*);
    FswStatus want;
  };
  static const Row rows[] = {
      {"no wheels", [](FswRwMapConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"more wheels than FSW_MAX_RW", [](FswRwMapConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"spin axis not unit", [](FswRwMapConfig* c) { c->gs_hat_B[2][0] *= FSW_R(1.01); }, FSW_E_CONFIG},
      {"spin axis zero", [](FswRwMapConfig* c) { c->gs_hat_B[1][0] = c->gs_hat_B[1][1] = c->gs_hat_B[1][2] = 0; }, FSW_E_CONFIG},
      {"spin axis NaN", [](FswRwMapConfig* c) { c->gs_hat_B[3][2] = std::numeric_limits<fsw_real>::quiet_NaN(); }, FSW_E_CONFIG},
      {"negative axis count", [](FswRwMapConfig* c) { c->num_axes = -1; }, FSW_E_CONFIG},
      {"four control axes", [](FswRwMapConfig* c) { c->num_axes = 4; }, FSW_E_CONFIG},
      {"control axis not unit", [](FswRwMapConfig* c) { c->ctrl_axes_B[1][1] = FSW_R(2.0); }, FSW_E_CONFIG},
      {"control axes not orthogonal",
       [](FswRwMapConfig* c) {
         c->ctrl_axes_B[1][0] = FSW_R(0.6);
         c->ctrl_axes_B[1][1] = FSW_R(0.8);
       },
       FSW_E_CONFIG},
      {"control axis Inf", [](FswRwMapConfig* c) { c->ctrl_axes_B[0][0] = std::numeric_limits<fsw_real>::infinity(); }, FSW_E_CONFIG},
      {"unknown mode", [](FswRwMapConfig* c) { c->mode = 7; }, FSW_E_CONFIG},
      {"power mode, eps_P zero",
       [](FswRwMapConfig* c) {
         c->mode = FSW_RW_MAP_POWER;
         c->eps_P = 0;
       },
       FSW_E_CONFIG},
      {"power mode, eps_P negative",
       [](FswRwMapConfig* c) {
         c->mode = FSW_RW_MAP_POWER;
         c->eps_P = -1;
       },
       FSW_E_CONFIG},
      {"power mode, eps_P NaN",
       [](FswRwMapConfig* c) {
         c->mode = FSW_RW_MAP_POWER;
         c->eps_P = std::numeric_limits<fsw_real>::quiet_NaN();
       },
       FSW_E_CONFIG},
      {"power mode, eps_P above FSW_RW_MAP_EPS_P_MAX (issue 21)",
       [](FswRwMapConfig* c) {
         c->mode = FSW_RW_MAP_POWER;
         c->eps_P = 2 * FSW_RW_MAP_EPS_P_MAX;
       },
       FSW_E_CONFIG},
  };
  for (const Row& row : rows) {
    Fixture f = pyramid();
    row.spoil(f.cfg.get());
    EXPECT_EQ(fsw_rw_map_check(f.cfg.get()), row.want) << row.why;
    EXPECT_EQ(f.init(), row.want) << row.why;
    EXPECT_EQ(f.st->ready, 0) << row.why;
    f.set_Lr(0.1, 0.2, 0.3);
    f.fill_out_with_garbage();
    EXPECT_EQ(f.update(), FSW_E_NOT_INIT) << row.why;
    expect_all_zero(*f.out);
  }
}

// Verifies: REQ-RWMAP-001
TEST(RwMapConfig, AcceptsZeroAxesAndEpsIgnoredInMinNorm)
{
  Fixture f = pyramid();
  f.cfg->eps_P = 0;  // not used by MIN_NORM
  f.cfg->num_axes = 0;
  EXPECT_EQ(f.init(), FSW_OK);
  f.set_Lr(1, 2, 3);
  f.fill_out_with_garbage();
  EXPECT_EQ(f.update(), FSW_OK);  // nc = 0: all zeros (4, step 2)
  expect_all_zero(*f.out);
}

// Verifies: REQ-GEN-007
TEST(RwMapConfig, NullArgumentsAssertAndReturn)
{
  Fixture f = pyramid();
  kestrel_assert_reset();
  EXPECT_EQ(fsw_rw_map_check(nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_rw_map_init(nullptr, f.cfg.get()), FSW_E_NULL_ARG);
  f.fill_out_with_garbage();
  EXPECT_EQ(fsw_rw_map_update(f.st.get(), f.cfg.get(), nullptr, f.out.get()), FSW_E_NULL_ARG);
  expect_all_zero(*f.out);
  EXPECT_EQ(kestrel_assert_count(), 3u);
  kestrel_assert_reset();
}

// ---- nominal numbers -----------------------------------------------------

// Pyramid: [Gs][Gs]^T = (4/3) I, so u = -[Gs]^T (3/4) Lr.  With
// Lr = (0.03, -0.06, 0.12) and g_1 = (1,1,1)/sqrt(3):
//   u_1 = -(3/4)(0.03 - 0.06 + 0.12)/sqrt(3) = -0.0675/sqrt(3)
//   u_2 = -(3/4)(-0.03 - 0.06 + 0.12)/sqrt(3) = -0.0225/sqrt(3)
//   u_3 = -(3/4)(-0.03 + 0.06 + 0.12)/sqrt(3) = -0.1125/sqrt(3)
//   u_4 = -(3/4)(0.03 + 0.06 + 0.12)/sqrt(3) = -0.1575/sqrt(3)
// Verifies: REQ-RWMAP-002
TEST(RwMapNominal, PyramidMinimumNormClosedForm)
{
  Fixture f = pyramid();
  f.set_Lr(0.03, -0.06, 0.12);
  f.fill_out_with_garbage();
  ASSERT_EQ(f.update(), FSW_OK);
  const double s3 = std::sqrt(3.0);
  const double want[4] = {-0.0675 / s3, -0.0225 / s3, -0.1125 / s3, -0.1575 / s3};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f.out->u_s[i], want[i], kt::tol(1e-15, 1e-7)) << i;
  for (int i = 4; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->u_s[i], 0.0);
  EXPECT_EQ(f.st->health.calls, 1u);
}

// Two control axes (x, y): A = rows 1, 2 of [Gs], A A^T = (4/3) I_2, so
// u_i = -(3/4)(g_ix Lr_x + g_iy Lr_y); the z torque is not controlled.
// Lr = (0.4, 0.2, 9): u = -(3/4)/sqrt(3) * (0.6, -0.2, -0.6, 0.2).
// Verifies: REQ-RWMAP-002
TEST(RwMapNominal, PyramidTwoAxesLeavesZUncontrolled)
{
  Fixture f = pyramid();
  f.cfg->num_axes = 2;
  ASSERT_EQ(f.init(), FSW_OK);
  f.set_Lr(0.4, 0.2, 9.0);
  ASSERT_EQ(f.update(), FSW_OK);
  const double k = -0.75 / std::sqrt(3.0);
  const double want[4] = {0.6 * k, -0.2 * k, -0.6 * k, 0.2 * k};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f.out->u_s[i], want[i], kt::tol(1e-15, 1e-7)) << i;
}

// Wheel 4 unavailable: the remaining three axes are independent, so the
// solution is unique: u = -[Gs_a]^-1 Lr.  For Lr = (1, 0, 0) N*m:
// g1 - g2 = (2/sqrt3, 0, 0) gives u1 = -sqrt(3)/2, u2 = +sqrt(3)/2 and u3 = 0
// (check: -sqrt3/2 g1 + sqrt3/2 g2 = (-1, 0, 0) = -Lr).
// Verifies: REQ-RWMAP-004
TEST(RwMapNominal, UnavailableWheelGetsExactlyZero)
{
  Fixture f = pyramid();
  f.in->avail[3] = FSW_UNAVAILABLE;
  f.set_Lr(1, 0, 0);
  ASSERT_EQ(f.update(), FSW_OK);
  EXPECT_NEAR(f.out->u_s[0], -std::sqrt(3.0) / 2, kt::tol(1e-14, 1e-6));
  EXPECT_NEAR(f.out->u_s[1], std::sqrt(3.0) / 2, kt::tol(1e-14, 1e-6));
  EXPECT_NEAR(f.out->u_s[2], 0.0, kt::tol(1e-14, 1e-6));
  EXPECT_EQ(f.out->u_s[3], 0.0);
}

// Verifies: REQ-RWMAP-005
TEST(RwMapNominal, FewerAvailableThanAxesGivesZerosAndWarning)
{
  Fixture f = pyramid();
  f.in->avail[0] = f.in->avail[1] = FSW_UNAVAILABLE;
  f.set_Lr(0.1, 0.1, 0.1);
  f.fill_out_with_garbage();
  EXPECT_EQ(f.update(), FSW_W_SINGULAR);
  expect_all_zero(*f.out);
  EXPECT_EQ(f.st->health.singular, 1u);
}

// Three coplanar wheels (all axes in the x-y plane) cannot make a z torque.
// Basilisk's |det| > 1e-30 test lets nearly coplanar sets through with huge
// torques; K1's relative pivot test refuses them.
// Verifies: REQ-RWMAP-005
TEST(RwMapNominal, CoplanarAvailableSetGivesZerosAndWarning)
{
  const double c = std::cos(0.3), s = std::sin(0.3);
  const double g[3][3] = {{1, 0, 0}, {0, 1, 0}, {c, s, 0}};
  Fixture f;
  f.setup(g, 3);
  ASSERT_EQ(f.init(), FSW_OK);
  f.set_Lr(0.1, 0.2, 0.3);
  EXPECT_EQ(f.update(), FSW_W_SINGULAR);
  expect_all_zero(*f.out);
  // and the same set does fine with x, y control only
  f.cfg->num_axes = 2;
  ASSERT_EQ(f.init(), FSW_OK);
  EXPECT_EQ(f.update(), FSW_OK);
  double t[3];
  rwt::gs_times(t, f.cfg->gs_hat_B, f.out->u_s, 3);
  EXPECT_NEAR(t[0], -0.1, kt::tol(1e-14, 1e-6));
  EXPECT_NEAR(t[1], -0.2, kt::tol(1e-14, 1e-6));
  EXPECT_EQ(t[2], 0.0);  // z torque not controlled (bleeds): here it is 0
}

// Power mode, pyramid, speeds (100, 100, 100, 0) rad/s, eps_P = 1.  Weights
// W = (10001, 10001, 10001, 1).  Hand check via the independent solver and
// the defining properties: wheel 4 (stopped) takes most of the torque.
// Verifies: REQ-RWMAP-003
TEST(RwMapNominal, PowerOptimalPyramidFavoursSlowWheel)
{
  Fixture f = pyramid(FSW_RW_MAP_POWER);
  const double Om[4] = {100, 100, 100, 0};
  for (int i = 0; i < 4; i++) f.in->Omega[i] = static_cast<fsw_real>(Om[i]);
  f.set_Lr(0.03, -0.06, 0.12);
  ASSERT_EQ(f.update(), FSW_OK);
  double W[4], u[4];
  for (int i = 0; i < 4; i++) W[i] = Om[i] * Om[i] + 1.0;
  double Lr[3] = {0.03, -0.06, 0.12};
  ASSERT_TRUE(rwt::ref_wmn(u, 3, kI3, 4, f.cfg->gs_hat_B, W, nullptr, Lr));
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f.out->u_s[i], u[i], kt::tol(1e-12, 1e-5) * std::fabs(u[i])) << i;
  for (int i = 0; i < 3; i++) EXPECT_LT(std::fabs(f.out->u_s[i]), std::fabs(f.out->u_s[3]));
  EXPECT_LT(rel_residual(*f.cfg, f.out->u_s, f.in->Lr_B), kt::tol(1e-12, 1e-5));
}

// ---- bad input -----------------------------------------------------------

// Verifies: REQ-RWMAP-006
TEST(RwMapBadInput, NonFiniteOrBadMaskGivesZerosAndAdvancesNothing)
{
  struct Row {
    const char* why;
    void (*spoil)(FswRwMapIn*);
  };
  static const Row rows[] = {
      {"Lr NaN", [](FswRwMapIn* in) { in->Lr_B[1] = std::numeric_limits<fsw_real>::quiet_NaN(); }},
      {"Lr Inf", [](FswRwMapIn* in) { in->Lr_B[2] = -std::numeric_limits<fsw_real>::infinity(); }},
      {"Omega NaN", [](FswRwMapIn* in) { in->Omega[3] = std::numeric_limits<fsw_real>::quiet_NaN(); }},
      {"Omega Inf", [](FswRwMapIn* in) { in->Omega[0] = std::numeric_limits<fsw_real>::infinity(); }},
      {"mask value 2", [](FswRwMapIn* in) { in->avail[2] = 2; }},
  };
  for (const Row& row : rows) {
    Fixture f = pyramid(FSW_RW_MAP_POWER);
    f.set_Lr(0.1, 0.2, 0.3);
    row.spoil(f.in.get());
    f.fill_out_with_garbage();
    EXPECT_EQ(f.update(), FSW_E_BAD_INPUT) << row.why;
    expect_all_zero(*f.out);
    EXPECT_EQ(f.st->health.bad_input, 1u) << row.why;
  }
  // min-norm ignores Omega entirely
  Fixture f = pyramid();
  f.set_Lr(0.1, 0.2, 0.3);
  f.in->Omega[0] = std::numeric_limits<fsw_real>::quiet_NaN();
  EXPECT_EQ(f.update(), FSW_OK);
}

// Verifies: REQ-RWMAP-007
TEST(RwMapRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  Fixture f = pyramid(FSW_RW_MAP_POWER);
  fsw_real first[5][4];
  for (int pass = 0; pass < 2; pass++) {
    kt::Rng r(11);
    for (int k = 0; k < 5; k++) {
      f.set_Lr(r.normal(), r.normal(), r.normal());
      for (int i = 0; i < 4; i++) f.in->Omega[i] = static_cast<fsw_real>(r.uniform(-300, 300));
      ASSERT_EQ(f.update(), FSW_OK);
      for (int i = 0; i < 4; i++) {
        if (pass == 0)
          first[k][i] = f.out->u_s[i];
        else
          EXPECT_EQ(f.out->u_s[i], first[k][i]);
      }
    }
    fsw_rw_map_reset(f.st.get());
  }
}

// Verifies: REQ-RWMAP-007
TEST(RwMapRepeatability, MinNormKeptForTheMaskGivesWhatAFreshStateGives)
{
  // MIN_NORM keeps [C][Gs_a] and its factor for the last mask (rw_map.h).
  // A sequence of requests with masks that change, come back and include
  // a singular one, a bad call and a reset: every output must equal, bit for
  // bit, that of a state initialised just before the call.
  Fixture f = pyramid();
  Fixture g = pyramid();
  const uint8_t masks[][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 1, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 0},
                              {1, 1, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 0}};
  kt::Rng r(12);
  int ok = 0;
  for (int k = 0; k < 40; k++) {
    const uint8_t* m = masks[k % 10];
    for (int i = 0; i < 4; i++) f.in->avail[i] = g.in->avail[i] = m[i];
    f.set_Lr(r.normal(), r.normal(), r.normal());
    if (k % 7 == 3) f.in->Lr_B[1] = std::numeric_limits<fsw_real>::quiet_NaN();
    *g.in = *f.in;
    if (k == 23) fsw_rw_map_reset(f.st.get());
    ASSERT_EQ(g.init(), FSW_OK);
    const FswStatus sf = f.update(), sg = g.update();
    ASSERT_EQ(sf, sg) << "call " << k;
    for (int i = 0; i < FSW_MAX_RW; i++) ASSERT_EQ(f.out->u_s[i], g.out->u_s[i]) << "call " << k;
    if (sf == FSW_OK) ok++;
    if (m[0] && m[1]) EXPECT_EQ(sf, k % 7 == 3 ? FSW_E_BAD_INPUT : FSW_W_SINGULAR);  // 2 wheels, 3 axes
  }
  EXPECT_GT(ok, 20);
}

// ---- properties over seeded random geometries (3, 4, 6, 36 wheels) -------

class RwMapProperties : public ::testing::TestWithParam<int> {};

// Verifies: REQ-RWMAP-002
TEST_P(RwMapProperties, MinNormMatchesIndependentSolverAndTorqueConstraint)
{
  const int n = GetParam();
  kt::Rng rng(1000u + static_cast<uint64_t>(n));
  double g[FSW_MAX_RW][3];
  for (int trial = 0; trial < 20; trial++) {
    rwt::random_axes(rng, n, g);
    Fixture f;
    f.setup(g, n);
    ASSERT_EQ(f.init(), FSW_OK);
    double Lr[3] = {rng.normal(), rng.normal(), rng.normal()};
    f.set_Lr(Lr[0], Lr[1], Lr[2]);
    ASSERT_EQ(f.update(), FSW_OK);
    double u[FSW_MAX_RW];
    ASSERT_TRUE(rwt::ref_wmn(u, 3, kI3, n, f.cfg->gs_hat_B, nullptr, nullptr, Lr));
    double un = 0.0;
    for (int i = 0; i < n; i++) un = std::fmax(un, std::fabs(u[i]));
    for (int i = 0; i < n; i++) EXPECT_NEAR(f.out->u_s[i], u[i], kt::tol(1e-11, 1e-4) * un) << n << "/" << i;
    EXPECT_LT(rel_residual(*f.cfg, f.out->u_s, f.in->Lr_B), kt::tol(1e-12, 1e-5));
  }
}

// Verifies: REQ-RWMAP-003
TEST_P(RwMapProperties, PowerOptimalConstraintEqualSpeedsAndCost)
{
  const int n = GetParam();
  kt::Rng rng(2000u + static_cast<uint64_t>(n));
  double g[FSW_MAX_RW][3];
  int skipped = 0;
  for (int trial = 0; trial < 20; trial++) {
    rwt::random_axes(rng, n, g);
    Fixture p, m;
    p.setup(g, n, FSW_RW_MAP_POWER);
    m.setup(g, n, FSW_RW_MAP_MIN_NORM);
    p.cfg->eps_P = static_cast<fsw_real>(rng.uniform(0.01, 10.0));
    ASSERT_EQ(p.init(), FSW_OK);
    ASSERT_EQ(m.init(), FSW_OK);
    const double Lr[3] = {rng.normal(), rng.normal(), rng.normal()};
    p.set_Lr(Lr[0], Lr[1], Lr[2]);
    m.set_Lr(Lr[0], Lr[1], Lr[2]);
    // a wheel may fail (only where the rest can still act)
    if (n > 4 && trial % 3 == 0) p.in->avail[trial % n] = m.in->avail[trial % n] = FSW_UNAVAILABLE;
    for (int i = 0; i < n; i++) p.in->Omega[i] = static_cast<fsw_real>(rng.uniform(-400, 400));
    const FswStatus ps = p.update();
    // Single precision: the weights span up to 1e7 here and K1's float rank
    // tolerance (1e-5) can refuse a badly conditioned 3-wheel set.
    if (kt::kFloat && ps == FSW_W_SINGULAR) {
      skipped++;
      continue;
    }
    ASSERT_EQ(ps, FSW_OK);
    ASSERT_EQ(m.update(), FSW_OK);

    // (1) torque constraint to 1e-12 relative
    EXPECT_LT(rel_residual(*p.cfg, p.out->u_s, p.in->Lr_B), kt::tol(1e-12, 1e-5)) << n;
    // (2) weighted cost never above the minimum-norm solution's
    double cp = 0.0, cm = 0.0;
    for (int i = 0; i < n; i++) {
      const double w = double(p.in->Omega[i]) * double(p.in->Omega[i]) + double(p.cfg->eps_P);
      cp += w * double(p.out->u_s[i]) * double(p.out->u_s[i]);
      cm += w * double(m.out->u_s[i]) * double(m.out->u_s[i]);
    }
    EXPECT_LE(cp, cm * (1.0 + kt::tol(1e-12, 1e-5))) << n;
    // unavailable wheels stay exactly 0
    for (int i = 0; i < n; i++)
      if (p.in->avail[i]) EXPECT_EQ(p.out->u_s[i], 0.0);
    // (3) all |Omega| equal (random signs): equals min-norm to 1e-12
    const double w0 = rng.uniform(1, 500);
    for (int i = 0; i < n; i++) p.in->Omega[i] = static_cast<fsw_real>(rng.uniform() < 0.5 ? -w0 : w0);
    ASSERT_EQ(p.update(), FSW_OK);
    double un = 0.0;
    for (int i = 0; i < n; i++) un = std::fmax(un, std::fabs(double(m.out->u_s[i])));
    for (int i = 0; i < n; i++) EXPECT_NEAR(p.out->u_s[i], m.out->u_s[i], kt::tol(1e-12, 1e-5) * un) << n << "/" << i;
  }
  EXPECT_LE(skipped, 3);
}

INSTANTIATE_TEST_SUITE_P(Wheels, RwMapProperties, ::testing::ValuesIn(rwt::kCounts));

// ---- issue 13: the contract for every input -------------------------------

// Finding 2: three wheels in one plane to within ~1e-6.  Before the fix
// the third Cholesky pivot (6.8e-13) passed the 4.5e-13 floor and the map
// returned OK with a delivered torque far from the request; now the K1
// delivered-residual test rejects it: W_SINGULAR with u = 0 (both modes).
// Verifies: REQ-RWMAP-005
TEST(RwMapIssue13, NearlyCoplanarWheelsAreSingularNotOk)
{
  const double g[3][3] = {{0.0335, -0.0112, -0.99938},
                          {0.87451, -0.24484, -0.41866},
                          {-0.81849, 0.22940, 0.52674}};
  double gn[3][3];
  for (int i = 0; i < 3; i++) {
    const double n = rwt::norm3(g[i]);
    for (int r = 0; r < 3; r++) gn[i][r] = g[i][r] / n;
  }
  for (int mode : {FSW_RW_MAP_MIN_NORM, FSW_RW_MAP_POWER}) {
    Fixture f;
    f.setup(gn, 3, mode);
    ASSERT_EQ(f.init(), FSW_OK);
    f.set_Lr(0.966, 0.625, 0.267);
    f.fill_out_with_garbage();
    const FswStatus s = f.update();
    if (s == FSW_OK) {
      EXPECT_LE(rel_residual(*f.cfg, f.out->u_s, f.in->Lr_B), 10.0 * FSW_RESID_TOL) << mode;
    } else {
      EXPECT_EQ(FSW_W_SINGULAR, s) << mode;
      expect_all_zero(*f.out);
    }
  }
}

// Finding 2, seeded search: coplanar and duplicate-axis sets tilted out of
// their plane by 1e-8..1e-4.  OK always means a delivered torque within
// the residual tolerance; everything else is W_SINGULAR with u = 0.
// Verifies: REQ-RWMAP-005
TEST(RwMapIssue13, NearlyDeficientSetsNeverOkWithWrongTorque)
{
  kt::Rng rng(2013);
  for (int trial = 0; trial < 3000; trial++) {
    const int n = rng.uniform_int(3, 5);
    double g[5][3], nrm[3];
    rng.unit3(nrm);
    rwt::coplanar_axes(rng, n, g);
    if (trial % 3 == 0)
      for (int r = 0; r < 3; r++) g[1][r] = g[0][r];  // duplicate axis
    // tilt: the plane of coplanar_axes is unknown here, so add a small
    // random component and renormalise
    for (int i = 0; i < n; i++) {
      const double eps = std::pow(10.0, rng.uniform(-8, -4));
      for (int r = 0; r < 3; r++) g[i][r] += eps * nrm[r] * rng.uniform(-1, 1);
      const double len = rwt::norm3(g[i]);
      for (int r = 0; r < 3; r++) g[i][r] /= len;
    }
    const int mode = (trial % 2) ? FSW_RW_MAP_POWER : FSW_RW_MAP_MIN_NORM;
    Fixture f;
    f.setup(g, n, mode);
    ASSERT_EQ(f.init(), FSW_OK);
    f.set_Lr(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    for (int i = 0; i < n; i++) f.in->Omega[i] = static_cast<fsw_real>(rng.uniform(-300, 300));
    const FswStatus s = f.update();
    if (s == FSW_OK) {
      ASSERT_LE(rel_residual(*f.cfg, f.out->u_s, f.in->Lr_B), 10.0 * FSW_RESID_TOL)
          << "trial " << trial;
    } else {
      ASSERT_EQ(FSW_W_SINGULAR, s) << "trial " << trial;
      for (int i = 0; i < FSW_MAX_RW; i++) ASSERT_EQ(0, f.out->u_s[i]);
    }
  }
}

// Finding 7 (rw_map): Lr near the real's maximum on each axis gave -inf
// under OK in both modes; now bad input with u = 0.  A denormal eps_P
// (which made every POWER update a bad input) is refused by check.
// Verifies: REQ-RWMAP-006, REQ-RWMAP-001
TEST(RwMapIssue13, OverflowIsBadInputAndEpsPIsBounded)
{
  const double big = 0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  for (int mode : {FSW_RW_MAP_MIN_NORM, FSW_RW_MAP_POWER}) {
    Fixture f = pyramid(mode);
    f.set_Lr(big, big, big);
    f.fill_out_with_garbage();
    EXPECT_EQ(FSW_E_BAD_INPUT, f.update()) << mode;
    expect_all_zero(*f.out);
  }
  Fixture f = pyramid(FSW_RW_MAP_POWER);
  f.cfg->eps_P = std::numeric_limits<fsw_real>::denorm_min() * 8;
  EXPECT_EQ(FSW_E_CONFIG, fsw_rw_map_check(f.cfg.get()));
  f.cfg->eps_P = FSW_RW_MAP_EPS_P_MIN;
  ASSERT_EQ(FSW_OK, f.init());
  f.set_Lr(0.01, 0.02, 0.03);
  EXPECT_EQ(FSW_OK, f.update());  // wheel speeds 0: W = eps_P, finite
  EXPECT_LE(rel_residual(*f.cfg, f.out->u_s, f.in->Lr_B), kt::tol(1e-12, 1e-5));
}

// Found by fuzz_fsw_rw_map (2026-12-04, reproducer
// regressions/rw_map/h2-wheel-normal-to-the-axis): one available wheel of a
// pyramid, g = (-s, -s', c) with s and s' = sin 50 deg / sqrt 2 one ulp
// apart (as the fuzzer's rotated pyramid had them), and one control axis
// c = (-1, 1, 0) / sqrt 2 at 90 deg to it.  c . g = (s - s') / sqrt 2 =
// 7.9e-17, rounding noise: before the fix K1's scale-invariant
// test saw a full-rank 1 x 1 system and the map returned OK with u ~ 1e14
// N*m delivering a torque off by 30 %.  Now W_SINGULAR with u = 0 in both
// modes; and a wheel at 0.01 rad from 90 deg (c . g = sin 0.01, far above
// rounding) is still solved exactly: u = -(c . Lr) / (c . g).
// Verifies: REQ-RWMAP-005
TEST(RwMapIssue13, WheelNormalToTheOnlyAxisIsSingular)
{
  const double g[1][3] = {{-0.54167522041970195, -0.54167522041970184, 0.64278760968653925}};
  const double r2 = 1.0 / std::sqrt(2.0);
  // one wheel g1, one control axis c = (-1, 1, 0) / sqrt 2
  const auto one_wheel_one_axis = [r2](Fixture &f, const double (&g1)[1][3], int mode) {
    f.setup(g1, 1, mode);
    f.cfg->num_axes = 1;
    f.cfg->ctrl_axes_B[0][0] = static_cast<fsw_real>(-r2);
    f.cfg->ctrl_axes_B[0][1] = static_cast<fsw_real>(r2);
    f.cfg->ctrl_axes_B[0][2] = 0;
  };
  for (int mode : {FSW_RW_MAP_MIN_NORM, FSW_RW_MAP_POWER}) {
    Fixture f;
    one_wheel_one_axis(f, g, mode);
    ASSERT_EQ(f.init(), FSW_OK) << mode;
    f.in->Omega[0] = static_cast<fsw_real>(-300.6625);
    f.set_Lr(-5.9616249999999997, -6.0507499999999999, -5.9370624999999997);  // the fuzzer's request
    f.fill_out_with_garbage();
    EXPECT_EQ(f.update(), FSW_W_SINGULAR) << mode;
    expect_all_zero(*f.out);
  }
  // the same axis with the wheel tilted 0.01 rad towards it
  const double t = 0.01;
  double gt[1][3];
  for (int r = 0; r < 3; r++) gt[0][r] = std::cos(t) * g[0][r];
  gt[0][0] += std::sin(t) * -r2;
  gt[0][1] += std::sin(t) * r2;
  for (int mode : {FSW_RW_MAP_MIN_NORM, FSW_RW_MAP_POWER}) {
    Fixture f;
    one_wheel_one_axis(f, gt, mode);
    ASSERT_EQ(f.init(), FSW_OK) << mode;
    f.set_Lr(0.0, 0.01, 0.0);  // c . Lr = 0.01 / sqrt 2
    f.in->Omega[0] = static_cast<fsw_real>(100.0);
    ASSERT_EQ(f.update(), FSW_OK) << mode;
    const double expect = -(0.01 * r2) / std::sin(t);
    EXPECT_NEAR(f.out->u_s[0], expect, kt::tol(1e-13, 1e-4) * std::fabs(expect)) << mode;
  }
}

// Issue 42 (fuzz_fsw_rw_map, 2026-12-07): in POWER mode the weights
// 1/sqrt(Omega^2 + eps_P) scale the columns of [C][Gs_a] against each other
// without bound, so a wheel whose c . g is rounding noise could outweigh the
// wheels that reach the axis and carry the torque.  The finding's pyramid
// and control axis c = (1, 1, 0)/sqrt 2: wheels 0 and 2 reach it
// (c . g = +-0.766) and spin at +-1e15 rad/s (weight 1e-15), wheel 1 is
// exactly normal to it (c . g = 0) and wheel 3 normal up to rounding
// (c . g = -1.6e-16 in double) at rest (weight about 1).  Before, wheel 3
// took part of the request at about 1e13 N m and the torque was off by
// percents.  Now a wheel that reaches no control axis beyond rounding (its
// column of [C][Gs_a] below the floor) weighs nothing, and the two wheels
// that reach the axis share it: equal weights, so u_0 = -u_2 =
// b / (m_0^2 + m_2^2) m_0 with b = -c . Lr, independent of the weight
// (exact geometry in long double).  And the finding itself, with speeds
// whose squares overflow (weight 0): no wheel can deliver, W_SINGULAR.
// Verifies: REQ-RWMAP-005
TEST(RwMapIssue42, PowerWeightsNeverPutTheTorqueOnAWheelAtRoundingLevel)
{
  const double g[4][3] = {{0.54167522041970195, 0.54167522041970195, 0.64278760968653936},
                          {-0.54167522041970195, 0.54167522041970195, 0.64278760968653936},
                          {-0.54167522041970195, -0.54167522041970184, 0.64278760968653925},
                          {0.54167522041970184, -0.54167522041970206, 0.64278760968653936}};
  const double r2 = 0.70710678118654746;
  const auto setup = [&](Fixture &f) {
    f.setup(g, 4, FSW_RW_MAP_POWER);
    f.cfg->num_axes = 1;
    f.cfg->ctrl_axes_B[0][0] = static_cast<fsw_real>(r2);
    f.cfg->ctrl_axes_B[0][1] = static_cast<fsw_real>(r2);
    f.cfg->ctrl_axes_B[0][2] = 0;
    f.cfg->eps_P = 1;
    ASSERT_EQ(f.init(), FSW_OK);
    f.set_Lr(0.01, -0.02, 0.005);
  };
  {
    Fixture f;
    setup(f);
    const double speeds[4] = {1e15, -80.0, -1e15, -4e-5};
    for (int i = 0; i < 4; i++) f.in->Omega[i] = static_cast<fsw_real>(speeds[i]);
    f.fill_out_with_garbage();
    ASSERT_EQ(f.update(), FSW_OK);
    long double m[4], b = 0;
    for (int i = 0; i < 4; i++) {
      m[i] = 0;
      for (int k = 0; k < 3; k++)
        m[i] += static_cast<long double>(f.cfg->ctrl_axes_B[0][k]) * static_cast<long double>(f.cfg->gs_hat_B[i][k]);
    }
    for (int k = 0; k < 3; k++) b -= static_cast<long double>(f.cfg->ctrl_axes_B[0][k]) * static_cast<long double>(f.in->Lr_B[k]);
    const long double u0 = b * m[0] / (m[0] * m[0] + m[2] * m[2]), u2 = b * m[2] / (m[0] * m[0] + m[2] * m[2]);
    EXPECT_NEAR(f.out->u_s[0], static_cast<double>(u0), kt::tol(1e-12, 1e-5) * std::fabs(static_cast<double>(u0)));
    EXPECT_NEAR(f.out->u_s[2], static_cast<double>(u2), kt::tol(1e-12, 1e-5) * std::fabs(static_cast<double>(u2)));
    EXPECT_EQ(f.out->u_s[1], 0.0);
    EXPECT_EQ(f.out->u_s[3], 0.0);
    // the torque the wheels deliver about c with the exact geometry is the request
    long double got = 0;
    for (int i = 0; i < 4; i++) got += m[i] * static_cast<long double>(f.out->u_s[i]);
    EXPECT_NEAR(static_cast<double>(got), static_cast<double>(b), kt::tol(1e-12, 1e-5) * std::fabs(static_cast<double>(b)));
  }
  {
    Fixture f;
    setup(f);
    // the finding's speeds: the squares of wheels 0 and 2 overflow (weight 0)
    const fsw_real big = std::numeric_limits<fsw_real>::max();
    const fsw_real speeds[4] = {big, static_cast<fsw_real>(-80.0), -big, static_cast<fsw_real>(-4e-5)};
    for (int i = 0; i < 4; i++) f.in->Omega[i] = speeds[i];
    f.fill_out_with_garbage();
    EXPECT_EQ(f.update(), FSW_W_SINGULAR);
    expect_all_zero(*f.out);
  }
}

// The rule of the test above in closed form, and that it is POWER's only:
// one control axis c = x, wheel 0 at g = (1e-7, sqrt(1 - 1e-14), 0)
// (its column c . g = 1e-7, squared 1e-14: below the floor FSW_RANK_TOL,
// 1e-12 double and 1e-5 float), wheel 1 along x, both at rest, request
// b = -c . Lr = 2.  MIN_NORM keeps the small entry: u = b (1e-7, 1) / (1 + 1e-14).  POWER (equal weights) leaves
// wheel 0 out: u = (0, 2).
// Verifies: REQ-RWMAP-002, REQ-RWMAP-003
TEST(RwMapIssue42, AWheelBelowTheFloorWeighsNothingInPowerModeOnly)
{
  const double g[2][3] = {{1e-7, std::sqrt(1.0 - 1e-14), 0.0}, {1.0, 0.0, 0.0}};
  for (int mode : {FSW_RW_MAP_MIN_NORM, FSW_RW_MAP_POWER}) {
    Fixture f;
    f.setup(g, 2, mode);
    f.cfg->num_axes = 1;
    ASSERT_EQ(f.init(), FSW_OK) << mode;
    f.set_Lr(-2.0, 0.0, 0.0);
    f.fill_out_with_garbage();
    ASSERT_EQ(f.update(), FSW_OK) << mode;
    const double m0 = static_cast<double>(f.cfg->gs_hat_B[0][0]);  // c . g of wheel 0, exact
    if (mode == FSW_RW_MAP_MIN_NORM) {
      EXPECT_NEAR(f.out->u_s[0], 2.0 * m0 / (1.0 + m0 * m0), kt::tol(1e-15, 1e-6) * 2.0 * m0) << mode;
      EXPECT_NEAR(f.out->u_s[1], 2.0 / (1.0 + m0 * m0), kt::tol(1e-15, 1e-6)) << mode;
    } else {
      EXPECT_EQ(f.out->u_s[0], 0.0) << mode;
      EXPECT_NEAR(f.out->u_s[1], 2.0, kt::tol(1e-15, 1e-6)) << mode;
    }
  }
}

// The floor is taken wheel by wheel, not entry by entry: a wheel that
// reaches one axis keeps its small entry on the other.  Axes x and y,
// wheel 0 at g = (5e-7, sqrt(1 - 2.5e-13), 0) (5e-7 about x: below
// sqrt(FSW_RANK_TOL) in either real type), wheel 1 along x, both at rest,
// b = (1, 1): wheel 0 delivers y (u_0 = 1 / g_0y) and 5e-7 u_0 about x,
// which wheel 1 makes up.  The torque about both axes with the exact
// geometry is the request within 1e-12 (double), 1e-5 (float); dropping
// the small entry alone would leave 5e-7 of it undelivered.
// Verifies: REQ-RWMAP-003, REQ-RWMAP-005
TEST(RwMapIssue42, AWheelThatReachesOneAxisKeepsItsSmallEntryOnTheOther)
{
  const double g[2][3] = {{5e-7, std::sqrt(1.0 - 2.5e-13), 0.0}, {1.0, 0.0, 0.0}};
  Fixture f;
  f.setup(g, 2, FSW_RW_MAP_POWER);
  f.cfg->num_axes = 2;
  ASSERT_EQ(f.init(), FSW_OK);
  f.set_Lr(-1.0, -1.0, 0.0);
  f.fill_out_with_garbage();
  ASSERT_EQ(f.update(), FSW_OK);
  for (int j = 0; j < 2; j++) {
    long double got = 0;
    for (int i = 0; i < 2; i++) got += static_cast<long double>(f.cfg->gs_hat_B[i][j]) * static_cast<long double>(f.out->u_s[i]);
    EXPECT_NEAR(static_cast<double>(got), 1.0, kt::tol(1e-12, 1e-5)) << "axis " << j;
  }
  EXPECT_NEAR(f.out->u_s[0], 1.0 / static_cast<double>(f.cfg->gs_hat_B[0][1]), kt::tol(1e-12, 1e-5));
  EXPECT_NEAR(f.out->u_s[1], 1.0 - static_cast<double>(f.cfg->gs_hat_B[0][0]) * static_cast<double>(f.out->u_s[0]),
              kt::tol(1e-12, 1e-5));
}

// ---- issue 21: a single wheel is a legal configuration ----------------------

// One wheel g = (0.6, 0, 0.8) controlling the body z axis alone: A = [C][g]
// = [0.8] (1 x 1), b = -Lr_z, so u = -Lr_z / 0.8 in both modes (a square
// system has one solution; the power weighting only scales the column and is
// undone).  Lr = (5, 7, 0.04): u = -0.05.  Three axes from one wheel:
// fewer available wheels than axes -> W_SINGULAR with u = 0 (docs/fsw/rw_map.md).
// Verifies: REQ-RWMAP-002
TEST(RwMapIssue21, SingleWheelIsAcceptedAndSolvedExactly)
{
  const double g[1][3] = {{0.6, 0.0, 0.8}};
  for (int mode : {FSW_RW_MAP_MIN_NORM, FSW_RW_MAP_POWER}) {
    Fixture f;
    f.setup(g, 1, mode);
    f.cfg->num_axes = 1;
    for (int r = 0; r < 3; r++) f.cfg->ctrl_axes_B[0][r] = static_cast<fsw_real>(kI3[2][r]);
    EXPECT_EQ(fsw_rw_map_check(f.cfg.get()), FSW_OK) << mode;
    ASSERT_EQ(f.init(), FSW_OK) << mode;
    f.set_Lr(5.0, 7.0, 0.04);
    f.in->Omega[0] = static_cast<fsw_real>(300.0);
    f.fill_out_with_garbage();
    ASSERT_EQ(f.update(), FSW_OK) << mode;
    EXPECT_NEAR(f.out->u_s[0], -0.05, kt::tol(1e-16, 1e-8)) << mode;
    for (int i = 1; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->u_s[i], 0.0) << mode << " wheel " << i;
    f.cfg->num_axes = 3;
    for (int j = 0; j < 3; j++)
      for (int r = 0; r < 3; r++) f.cfg->ctrl_axes_B[j][r] = static_cast<fsw_real>(kI3[j][r]);
    ASSERT_EQ(f.init(), FSW_OK) << mode;
    f.fill_out_with_garbage();
    EXPECT_EQ(f.update(), FSW_W_SINGULAR) << mode;
    expect_all_zero(*f.out);
  }
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(RwMapIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("rw_map", fsw_rw_map_check, fsw_rw_map_init, fsw_rw_map_reset, fsw_rw_map_update);
}

// Issue 21: the overflow guard after the power weighting.  POWER, pyramid,
// wheels at rest, eps_P = 1e-9: every column is scaled by sqrt(y) =
// 1/sqrt(eps_P) = 31623, so K1 solves for x = u / 31623, which is finite,
// while u = -(3/4) [Gs]^T Lr for Lr = 0.9 max (1, 1, 1) has
// u_1 = -(3/4) sqrt(3) 0.9 max = -1.17 max: it overflows only when x is
// scaled back.  Bad input, u = 0 (the MIN_NORM row of
// OverflowIsBadInputAndEpsPIsBounded fails inside K1 instead).
// Verifies: REQ-RWMAP-006
TEST(RwMapIssue21, PowerWeightingThatOverflowsOnTheWayBackIsBadInput)
{
  const double big = 0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  Fixture f = pyramid(FSW_RW_MAP_POWER);
  f.cfg->eps_P = FSW_RW_MAP_EPS_P_MIN;
  ASSERT_EQ(FSW_OK, f.init());
  f.set_Lr(big, big, big);
  f.fill_out_with_garbage();
  EXPECT_EQ(FSW_E_BAD_INPUT, f.update());
  expect_all_zero(*f.out);
  EXPECT_EQ(1u, f.st->health.bad_input);
}

// fsw_acs calls the mapping without the update's checks of the wheels (its
// cycle checks the availability flags and speeds before any stage runs):
// for every input that passes them the output, the status, the scratch and
// the health record are the update's, bit for bit, in both modes, with two
// and three control axes and none, masks that change and come back, too
// few wheels, NaN speeds on unavailable wheels (not read), non-finite and
// huge requests.
// Verifies: REQ-RWMAP-001
TEST(RwMapTorques, TorquesOfACheckedInputAreTheUpdate)
{
  kt::Rng r(0x5eed0045u);
  int seen[4] = {0, 0, 0, 0};  // OK, W_SINGULAR, E_BAD_INPUT, other
  for (int set = 0; set < 6; set++) {
    Fixture f = pyramid(set % 2 == 0 ? FSW_RW_MAP_MIN_NORM : FSW_RW_MAP_POWER);
    Fixture g = pyramid(f.cfg->mode);
    const int nc = (set < 2) ? 3 : (set < 4 ? 2 : (set == 4 ? 3 : 0));
    f.cfg->num_axes = g.cfg->num_axes = nc;
    ASSERT_EQ(f.init(), FSW_OK);
    ASSERT_EQ(g.init(), FSW_OK);
    for (int k = 0; k < 600; k++) {
      for (int i = 0; i < 4; i++) {
        f.in->avail[i] = (r.uniform() < 0.25) ? FSW_UNAVAILABLE : FSW_AVAILABLE;
        f.in->Omega[i] = (f.in->avail[i] == FSW_UNAVAILABLE && (k % 2) == 0)
                             ? std::numeric_limits<fsw_real>::quiet_NaN()
                             : static_cast<fsw_real>(r.uniform(-600.0, 600.0));
      }
      const double scale = (k % 41 == 9) ? (kt::kFloat ? 1e37 : 1e306) : 1.0;
      f.set_Lr(r.normal() * scale, r.normal() * scale, r.normal() * scale);
      if (k % 53 == 11) f.in->Lr_B[2] = std::numeric_limits<fsw_real>::infinity();
      *g.in = *f.in;
      if (k % 97 == 40) {
        fsw_rw_map_reset(f.st.get());
        fsw_rw_map_reset(g.st.get());
      }
      const FswStatus su = f.update();
      const FswStatus st = fsw_rw_map_torques(g.st.get(), g.cfg.get(), g.in->Lr_B, g.in->Omega, g.in->avail, g.out.get());
      ASSERT_EQ(su, st) << set << " " << k;
      ASSERT_EQ(0, std::memcmp(f.out.get(), g.out.get(), sizeof(FswRwMapOut))) << set << " " << k;
      ASSERT_EQ(0, std::memcmp(f.st.get(), g.st.get(), sizeof(FswRwMapState))) << set << " " << k;
      seen[su == FSW_OK ? 0 : su == FSW_W_SINGULAR ? 1 : su == FSW_E_BAD_INPUT ? 2 : 3]++;
    }
  }
  EXPECT_GT(seen[0], 2000);
  EXPECT_GT(seen[1], 50);
  EXPECT_GT(seen[2], 50);
  EXPECT_EQ(0, seen[3]);
  // a state that is not ready: FSW_E_NOT_INIT and the safe output, as the update
  Fixture f = pyramid();
  auto idle = rwt::make0<FswRwMapState>();
  f.fill_out_with_garbage();
  EXPECT_EQ(FSW_E_NOT_INIT, fsw_rw_map_torques(idle.get(), f.cfg.get(), f.in->Lr_B, f.in->Omega, f.in->avail, f.out.get()));
  expect_all_zero(*f.out);
  EXPECT_EQ(1u, idle->health.calls);
}

// rw_bias: wheel-speed bias with zero-crossing avoidance.  Expected values:
// hand calculations on the 4-wheel pyramid (null vector n = (1,-1,1,-1)/2),
// an independent null-space projector built here (3x3 inverse), and a
// closed loop with rw_null and a wheel model written in the test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <limits>

#include "fsw/rw_bias.h"
#include "fsw/rw_null.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
const fsw_real kInf = std::numeric_limits<fsw_real>::infinity();

struct Fixture {
  std::unique_ptr<FswRwBiasConfig> cfg = rwt::make0<FswRwBiasConfig>();
  std::unique_ptr<FswRwBiasState> st = rwt::make0<FswRwBiasState>();
  std::unique_ptr<FswRwBiasIn> in = rwt::make0<FswRwBiasIn>();
  std::unique_ptr<FswRwBiasOut> out = rwt::make0<FswRwBiasOut>();

  void setup(const double g[][3], int n, double keep = 10.0, double hyst = 5.0)
  {
    cfg->num_rw = n;
    rwt::set_axes(cfg->gs_hat_B, g, n);
    cfg->Omega_keepout = static_cast<fsw_real>(keep);
    cfg->Omega_hyst = static_cast<fsw_real>(hyst);
    for (int i = 0; i < n; i++) cfg->Omega_bias[i] = static_cast<fsw_real>(i % 2 ? -100.0 : 100.0);
  }
  FswStatus init() { return fsw_rw_bias_init(st.get(), cfg.get()); }
  FswStatus update() { return fsw_rw_bias_update(st.get(), cfg.get(), in.get(), out.get()); }
  void speeds(std::initializer_list<double> om)
  {
    int i = 0;
    for (double w : om) in->Omega[i++] = static_cast<fsw_real>(w);
  }
  void garbage()
  {
    for (int i = 0; i < FSW_MAX_RW; i++) {
      out->Omega_des[i] = FSW_R(77.0);
      out->in_band[i] = out->unavoidable[i] = 9;
    }
    out->lambda_norm = FSW_R(5.0);
  }
};

std::unique_ptr<Fixture> pyramid(double keep = 10.0, double hyst = 5.0)
{
  double g[4][3];
  rwt::pyramid4(g);
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, keep, hyst);
  EXPECT_EQ(f->init(), FSW_OK);
  return f;
}

const double kTol = kt::tol(1e-12, 2e-4);

void expect_des(const Fixture& f, std::initializer_list<double> want, const char* why)
{
  int i = 0;
  for (double w : want) {
    EXPECT_NEAR(f.out->Omega_des[i], w, kTol * (1 + std::fabs(w))) << why << " wheel " << i;
    i++;
  }
  for (; i < FSW_MAX_RW; i++) EXPECT_EQ(f.out->Omega_des[i], 0.0) << why << " beyond num_rw " << i;
}

// |Gs (Omega_des - Omega)| over the available wheels, relative to |Omega| + |Omega_des - Omega|.
double momentum_change(const FswRwBiasConfig& c, const fsw_real* des, const fsw_real* om, const uint8_t* avail)
{
  double d[FSW_MAX_RW], t[3], a = 0, b = 0;
  for (int i = 0; i < c.num_rw; i++) {
    d[i] = avail[i] ? 0.0 : double(des[i]) - double(om[i]);
    a += avail[i] ? 0.0 : double(om[i]) * double(om[i]);
    b += d[i] * d[i];
  }
  rwt::gs_times(t, c.gs_hat_B, d, c.num_rw);
  return rwt::norm3(t) / (std::sqrt(a) + std::sqrt(b) + 1e-300);
}

// Independent null-space projection of x over the available wheels:
// x - G^T (G G^T)^-1 G x (G = [Gs_a], full rank 3 assumed).
void null_project(double* out, const FswRwBiasConfig& c, const uint8_t* avail, const double* x)
{
  const int n = c.num_rw;
  double M[3][3] = {}, y[3] = {}, z[3];
  for (int i = 0; i < n; i++) {
    if (avail[i]) continue;
    for (int r = 0; r < 3; r++) {
      y[r] += double(c.gs_hat_B[i][r]) * x[i];
      for (int s = 0; s < 3; s++) M[r][s] += double(c.gs_hat_B[i][r]) * double(c.gs_hat_B[i][s]);
    }
  }
  const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
  double I[3][3];
  for (int r = 0; r < 3; r++)
    for (int s = 0; s < 3; s++) {
      const int r1 = (s + 1) % 3, r2 = (s + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      I[r][s] = (M[r1][c1] * M[r2][c2] - M[r1][c2] * M[r2][c1]) / det;
    }
  for (int r = 0; r < 3; r++) z[r] = I[r][0] * y[0] + I[r][1] * y[1] + I[r][2] * y[2];
  for (int i = 0; i < n; i++) {
    out[i] = avail[i] ? 0.0 : x[i] - (double(c.gs_hat_B[i][0]) * z[0] + double(c.gs_hat_B[i][1]) * z[1] + double(c.gs_hat_B[i][2]) * z[2]);
  }
}

}  // namespace

// Verifies: REQ-RWBIAS-001
TEST(RwBiasConfig, RejectsBadConfigurationsTableDriven)
{
  struct Row {
    const char* why;
    void (*spoil)(FswRwBiasConfig*);
    FswStatus want;
  };
  static const Row rows[] = {
      {"no wheels", [](FswRwBiasConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many wheels", [](FswRwBiasConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"axis not unit", [](FswRwBiasConfig* c) { c->gs_hat_B[0][2] = FSW_R(0.9); }, FSW_E_CONFIG},
      {"axis NaN", [](FswRwBiasConfig* c) { c->gs_hat_B[1][1] = kNaN; }, FSW_E_CONFIG},
      {"keepout 0", [](FswRwBiasConfig* c) { c->Omega_keepout = 0; }, FSW_E_CONFIG},
      {"keepout negative", [](FswRwBiasConfig* c) { c->Omega_keepout = FSW_R(-1.0); }, FSW_E_CONFIG},
      {"keepout NaN", [](FswRwBiasConfig* c) { c->Omega_keepout = kNaN; }, FSW_E_CONFIG},
      {"hyst negative", [](FswRwBiasConfig* c) { c->Omega_hyst = FSW_R(-0.1); }, FSW_E_CONFIG},
      {"hyst Inf", [](FswRwBiasConfig* c) { c->Omega_hyst = kInf; }, FSW_E_CONFIG},
      {"band beyond half the speed range",
       [](FswRwBiasConfig* c) {
         c->Omega_keepout = FSW_R(4000.0);
         c->Omega_hyst = FSW_R(1001.0);
         for (int i = 0; i < 4; i++) c->Omega_bias[i] = FSW_R(6000.0);
       },
       FSW_E_CONFIG},
      {"bias inside the band", [](FswRwBiasConfig* c) { c->Omega_bias[2] = FSW_R(-9.0); }, FSW_E_CONFIG},
      {"bias at the band edge", [](FswRwBiasConfig* c) { c->Omega_bias[2] = FSW_R(10.0); }, FSW_E_CONFIG},
      {"bias beyond the speed range", [](FswRwBiasConfig* c) { c->Omega_bias[1] = FSW_R(2e4); }, FSW_E_CONFIG},
      {"bias NaN", [](FswRwBiasConfig* c) { c->Omega_bias[3] = kNaN; }, FSW_E_CONFIG},
  };
  for (const Row& row : rows) {
    auto f = pyramid();
    row.spoil(f->cfg.get());
    EXPECT_EQ(fsw_rw_bias_check(f->cfg.get()), row.want) << row.why;
    EXPECT_EQ(f->init(), row.want) << row.why;
    EXPECT_EQ(f->st->ready, 0);
    f->speeds({100, -100, 100, -100});
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_NOT_INIT) << row.why;
    if (row.want == FSW_E_CAPACITY)
      expect_des(*f, {0, 0, 0, 0}, row.why);  // no valid wheel count: all 0
    else
      expect_des(*f, {100, -100, 100, -100}, row.why);  // safe output: the current speeds
  }
  auto f = pyramid();
  f->cfg->Omega_hyst = 0;  // no hysteresis is allowed
  EXPECT_EQ(fsw_rw_bias_check(f->cfg.get()), FSW_OK);
}

// Pyramid, keepout 10, bias (100,-100,100,-100), Omega = (200,-100,150,-300):
// bias - Omega = (-100, 0, -50, 200), lambda_u = n.(bias - Omega) = -175,
// Omega_des = Omega - 175 n = (112.5, -12.5, 62.5, -212.5): every wheel out
// of its band on its own side, so this is the answer; |lambda| = 175.
// Verifies: REQ-RWBIAS-002
TEST(RwBiasNominal, PyramidUnconstrainedOptimumHandNumbers)
{
  auto f = pyramid();
  EXPECT_EQ(f->st->nullity, 1);
  const double nv[4] = {0.5, -0.5, 0.5, -0.5};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f->st->basis[0][i], nv[i], kt::tol(1e-15, 1e-7)) << i;
  f->speeds({200, -100, 150, -300});
  f->garbage();
  ASSERT_EQ(f->update(), FSW_OK);
  expect_des(*f, {112.5, -12.5, 62.5, -212.5}, "interior optimum");
  EXPECT_NEAR(f->out->lambda_norm, 175.0, kTol * 175);
  EXPECT_EQ(f->out->nullity, 1);
  EXPECT_EQ(f->out->crossing_unavoidable, 0);
  for (int i = 0; i < FSW_MAX_RW; i++) {
    EXPECT_EQ(f->out->in_band[i], 0);
    EXPECT_EQ(f->out->unavoidable[i], 0);
  }
}

// Same bias, Omega = (200,-100,50,-300): lambda_u = n.(-100,0,50,200) = -125
// would take wheel 3 from 50 to -12.5, through zero.  Wheel 3 (s = +1,
// n_3 = 1/2) requires 50 + lambda/2 >= 10, lambda >= -80 (the other wheels
// allow lambda >= -180, -380, -580), so lambda = -80:
// Omega_des = (160, -60, 10, -260), wheel 3 stops at the band edge.
// Verifies: REQ-RWBIAS-003
TEST(RwBiasNominal, CrossingStopsAtTheBandEdge)
{
  auto f = pyramid();
  f->speeds({200, -100, 50, -300});
  ASSERT_EQ(f->update(), FSW_OK);
  expect_des(*f, {160, -60, 10, -260}, "band edge");
  EXPECT_NEAR(f->out->lambda_norm, 80.0, kTol * 80);
}

// Wheel 1 at -3 rad/s (inside the band, negative side) with a positive bias:
// the unconstrained lambda_u = n.(103, 0, 0, 0) = 51.5 takes it to +22.75.
// It is in the band, so it must reach -(keepout + hyst) = -15 on its own
// side: -3 + lambda/2 <= -15, lambda <= -24 (others: lambda >= -180):
// lambda = -24, Omega_des = (-15, -88, 88, -88).
// Verifies: REQ-RWBIAS-003
TEST(RwBiasNominal, WheelNearZeroIsPushedOutOnItsOwnSide)
{
  auto f = pyramid();
  f->speeds({-3, -100, 100, -100});
  ASSERT_EQ(f->update(), FSW_OK);
  expect_des(*f, {-15, -88, 88, -88}, "pushed out");
  EXPECT_EQ(f->out->in_band[0], 1);
  EXPECT_EQ(f->st->in_band[0], 1);
  EXPECT_EQ(f->out->in_band[1], 0);
  // exactly 0: the side is the bias's (+): 0 + lambda/2 >= 15 -> lambda >= 30,
  // lambda_u = n.(100, 0, 0, 0) = 50 is admissible (others: lambda <= 180)
  f->speeds({0, -100, 100, -100});
  ASSERT_EQ(f->update(), FSW_OK);
  expect_des(*f, {25, -125, 125, -125}, "zero speed");
}

// Hysteresis on wheel 1 (keepout 10, hyst 5), bias (-100,-100,100,-100)
// pulls it through zero: the constraint 12 + lambda/2 >= b binds.
//   Omega_1 = 12: not in band (never entered)   b = 10: Omega_des_1 = 10
//   Omega_1 = 8:  in band                        b = 15: Omega_des_1 = 15
//   Omega_1 = 12: still in band (12 <= 15)       b = 15: Omega_des_1 = 15
//   Omega_1 = 16: leaves the band                b = 10: Omega_des_1 = 10
// Verifies: REQ-RWBIAS-003
TEST(RwBiasNominal, HysteresisOfTheBand)
{
  auto f = pyramid();
  f->cfg->Omega_bias[0] = FSW_R(-100.0);
  ASSERT_EQ(f->init(), FSW_OK);
  const double seq[4] = {12, 8, 12, 16};
  const double want_des[4] = {10, 15, 15, 10};
  const int want_band[4] = {0, 1, 1, 0};
  for (int k = 0; k < 4; k++) {
    f->speeds({seq[k], -100, 100, -100});
    ASSERT_EQ(f->update(), FSW_OK) << k;
    EXPECT_NEAR(f->out->Omega_des[0], want_des[k], kTol * 20) << k;
    EXPECT_EQ(f->out->in_band[0], want_band[k]) << k;
    // the null step: wheels 2..4 move by -/+ (Omega_des_1 - Omega_1)
    const double d = want_des[k] - seq[k];
    EXPECT_NEAR(f->out->Omega_des[1], -100 - d, kTol * 200) << k;
  }
  // reset forgets the band: 12 is then "not in band" again
  f->speeds({8, -100, 100, -100});
  ASSERT_EQ(f->update(), FSW_OK);
  fsw_rw_bias_reset(f->st.get());
  EXPECT_EQ(f->st->in_band[0], 0);
  f->speeds({12, -100, 100, -100});
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_NEAR(f->out->Omega_des[0], 10.0, kTol * 20);
}

// All four wheels at +5 (in band): wheels 1, 3 need lambda >= 20, wheels
// 2, 4 need lambda <= -20: no lambda keeps all out.  lambda_u = 0 (bias
// (100,100,100,100)); the fewest wheels in band is 2, at lambda = 20 or
// -20, equally far from lambda_u: the first found (wheel 1's bound, 20):
// Omega_des = (15, -5, 15, -5), wheels 2 and 4 flagged, FSW_W_SAT.
// Verifies: REQ-RWBIAS-004
TEST(RwBiasInfeasible, MomentumForcingACrossingIsFlagged)
{
  auto f = pyramid();
  for (int i = 0; i < 4; i++) f->cfg->Omega_bias[i] = FSW_R(100.0);
  ASSERT_EQ(f->init(), FSW_OK);
  f->speeds({5, 5, 5, 5});
  EXPECT_EQ(f->update(), FSW_W_SAT);
  expect_des(*f, {15, -5, 15, -5}, "infeasible");
  const int want[4] = {0, 1, 0, 1};
  for (int i = 0; i < 4; i++) {
    EXPECT_EQ(f->out->unavoidable[i], want[i]) << i;
    EXPECT_EQ(f->out->in_band[i], 1) << i;
  }
  EXPECT_EQ(f->out->crossing_unavoidable, 1);
  EXPECT_EQ(f->st->health.saturated, 1u);
  EXPECT_LT(momentum_change(*f->cfg, f->out->Omega_des, f->in->Omega, f->in->avail), kTol);
}

// k = 0 (wheel 4 unavailable: three independent wheels): no null motion,
// Omega_des = Omega; a wheel in its band is flagged.
// Verifies: REQ-RWBIAS-004
TEST(RwBiasInfeasible, NoNullSpaceHoldsTheSpeeds)
{
  auto f = pyramid();
  f->in->avail[3] = FSW_UNAVAILABLE;
  f->speeds({100, -100, 100, kNaN});  // the unavailable wheel's speed is not read
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->nullity, 0);
  expect_des(*f, {100, -100, 100, 0}, "k = 0");
  f->speeds({100, -4, 100, 55});
  EXPECT_EQ(f->update(), FSW_W_SAT);
  expect_des(*f, {100, -4, 100, 55}, "k = 0 in band");
  EXPECT_EQ(f->out->unavoidable[1], 1);
  EXPECT_EQ(f->out->unavoidable[3], 0);
}

// Only null-space moves: Gs_a Omega_des = Gs_a Omega to 1e-12 (relative),
// random geometries of 3, 4, 6 and 36 wheels, random masks and speeds; a
// wheel kept out never changes sign, and |Omega_des| <= FSW_RW_OMEGA_MAX.
class RwBiasProperties : public ::testing::TestWithParam<int> {};

// Verifies: REQ-RWBIAS-002, REQ-RWBIAS-003
TEST_P(RwBiasProperties, MomentumUnchangedAndNoSignChangeWhenKeptOut)
{
  const int n = GetParam();
  kt::Rng rng(4100u + static_cast<uint64_t>(n));
  double g[FSW_MAX_RW][3];
  auto f = rwt::make0<Fixture>();
  int ok = 0, sat = 0;
  for (int trial = 0; trial < 40; trial++) {
    rwt::random_axes(rng, n, g);
    f->setup(g, n, rng.uniform(1, 50), rng.uniform(0, 10));
    for (int i = 0; i < n; i++)
      f->cfg->Omega_bias[i] = static_cast<fsw_real>((rng.uniform() < 0.5 ? -1 : 1) * rng.uniform(60, 3000));
    ASSERT_EQ(f->init(), FSW_OK);
    for (int step = 0; step < 4; step++) {
      for (int i = 0; i < n; i++) {
        f->in->avail[i] = (trial % 3 == 2 && rng.uniform() < 0.2) ? FSW_UNAVAILABLE : FSW_AVAILABLE;
        f->in->Omega[i] = static_cast<fsw_real>(rng.uniform(-600, 600));
      }
      const FswStatus s = f->update();
      ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT) << s;
      (s == FSW_OK ? ok : sat)++;
      EXPECT_LT(momentum_change(*f->cfg, f->out->Omega_des, f->in->Omega, f->in->avail), kTol)
          << "n=" << n << " trial=" << trial;
      for (int i = 0; i < n; i++) {
        const double om = f->in->Omega[i], d = f->out->Omega_des[i];
        EXPECT_LE(std::fabs(d), double(FSW_RW_OMEGA_MAX));
        if (f->in->avail[i]) {
          EXPECT_EQ(d, om);
          continue;
        }
        if (!f->out->unavoidable[i] && om != 0) EXPECT_GT(d * om, 0.0) << "sign change, wheel " << i;
        if (s == FSW_OK) EXPECT_GE(std::fabs(d), (1 - FSW_RW_BIAS_TOL) * f->cfg->Omega_keepout) << i;
      }
    }
  }
  EXPECT_GT(ok, 0);
  RecordProperty("ok", ok);
  RecordProperty("w_sat", sat);
}

INSTANTIATE_TEST_SUITE_P(Wheels, RwBiasProperties, ::testing::ValuesIn(rwt::kCounts));

// Six wheels (k = 3): when every wheel can be kept out the result is the
// projection of the bias onto the admissible set: (a) equal to the
// unconstrained optimum (independent projector) when that is admissible;
// (b) otherwise no admissible point Omega + P x (random x, independent
// projector P) is closer to the bias.
// Verifies: REQ-RWBIAS-002
TEST(RwBiasSixWheels, NullityThreeOptimality)
{
  if (kt::kFloat) GTEST_SKIP() << "optimality compared in double";
  kt::Rng rng(606);
  double g[6][3];
  auto f = rwt::make0<Fixture>();
  int checked_a = 0, checked_b = 0;
  for (int trial = 0; trial < 60; trial++) {
    rwt::random_axes(rng, 6, g);
    f->setup(g, 6, 20, 5);
    for (int i = 0; i < 6; i++) f->cfg->Omega_bias[i] = static_cast<fsw_real>(rng.uniform() < 0.5 ? -300 : 300);
    ASSERT_EQ(f->init(), FSW_OK);
    ASSERT_EQ(f->st->nullity, 3);
    double om[6], x[6], p[6], ustar[6];
    for (int i = 0; i < 6; i++) {
      om[i] = rng.uniform(-500, 500);
      if (std::fabs(om[i]) < 40) om[i] = om[i] < 0 ? -40 : 40;  // start outside the bands
      f->in->Omega[i] = static_cast<fsw_real>(om[i]);
      x[i] = f->cfg->Omega_bias[i] - om[i];
    }
    const FswStatus s = f->update();
    ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT);
    if (s != FSW_OK) continue;  // Omega itself is admissible, so this cannot happen
    null_project(p, *f->cfg, f->in->avail, x);
    bool unconstrained_ok = true;
    double obj = 0;
    for (int i = 0; i < 6; i++) {
      ustar[i] = om[i] + p[i];
      unconstrained_ok = unconstrained_ok && ustar[i] * om[i] > 0 && std::fabs(ustar[i]) >= 20;
      obj += std::pow(double(f->out->Omega_des[i]) - f->cfg->Omega_bias[i], 2);
    }
    if (unconstrained_ok) {
      for (int i = 0; i < 6; i++) EXPECT_NEAR(f->out->Omega_des[i], ustar[i], 1e-9 * 300) << trial << " " << i;
      checked_a++;
      continue;
    }
    for (int sample = 0; sample < 400; sample++) {
      double y[6], py[6], o2 = 0;
      bool adm = true;
      const double scale = rng.uniform(0, 1.5);
      for (int i = 0; i < 6; i++) y[i] = scale * (rng.uniform() < 0.5 ? x[i] : rng.uniform(-400, 400));
      null_project(py, *f->cfg, f->in->avail, y);
      for (int i = 0; i < 6; i++) {
        const double v = om[i] + py[i];
        adm = adm && v * om[i] > 0 && std::fabs(v) >= 20;
        o2 += std::pow(v - f->cfg->Omega_bias[i], 2);
      }
      if (adm) EXPECT_LE(obj, o2 * (1 + 1e-6) + 1e-6) << trial << " sample " << sample;
    }
    checked_b++;
  }
  EXPECT_GT(checked_a, 0);
  EXPECT_GT(checked_b, 0);
  RecordProperty("unconstrained_cases", checked_a);
  RecordProperty("constrained_cases", checked_b);
}

// Closed loop: rw_bias feeds rw_null, which drives the wheels (J_s Omega' =
// u) while a secular body torque is absorbed by the wheels through the
// pyramid's minimum-norm map u_c = -(3/4) Gs^T L (L along g_1, slowly
// varying).  Without null motion wheel 1 crosses zero; with the stack no
// wheel changes sign for as long as rw_bias reports the set feasible (OK).
// Verifies: REQ-RWBIAS-007
TEST(RwBiasClosedLoop, StackWithRwNullKeepsWheelsFromCrossingZero)
{
  double g[4][3];
  rwt::pyramid4(g);
  auto b = pyramid(20.0, 5.0);
  auto nul = rwt::make0<FswRwNullConfig>();
  auto nst = rwt::make0<FswRwNullState>();
  auto nin = rwt::make0<FswRwNullIn>();
  auto nout = rwt::make0<FswRwNullOut>();
  nul->num_rw = 4;
  rwt::set_axes(nul->gs_hat_B, g, 4);
  nul->k_null = FSW_R(0.02);
  ASSERT_EQ(fsw_rw_null_init(nst.get(), nul.get()), FSW_OK);
  const double Js = 0.05, dt = 0.5, L0 = 0.05, Ls = 2e-4, T = 3000, P = 600;
  const double om0[4] = {50, -60, 70, -80};  // signs s_i g_i positively span R^3
  auto torque = [&](double t, double u[4]) {
    // periodic demand along g_1 (momentum swing L0 P/(2 pi)) and a secular part along x
    const double c = L0 * std::cos(6.283185307179586 * t / P);
    const double L[3] = {c * g[0][0] + Ls, c * g[0][1], c * g[0][2]};
    for (int i = 0; i < 4; i++) u[i] = -0.75 * (g[i][0] * L[0] + g[i][1] * L[1] + g[i][2] * L[2]);
  };
  // control run: no null motion
  double om[4], t_cross = -1;
  for (int i = 0; i < 4; i++) om[i] = om0[i];
  for (double t = 0; t < T && t_cross < 0; t += dt) {
    double u[4];
    torque(t, u);
    for (int i = 0; i < 4; i++) {
      om[i] += u[i] / Js * dt;
      if (om[i] * om0[i] <= 0) t_cross = t;
    }
  }
  ASSERT_GT(t_cross, 0) << "the control run must cross zero";
  // the stack
  for (int i = 0; i < 4; i++) om[i] = om0[i];
  double t_ok = 0, min_abs = 1e9;
  int singular = 0;
  double h0[3];
  rwt::gs_times(h0, g, om, 4);
  double hu[3] = {0, 0, 0};  // momentum the map put into the wheels (integral of Gs u_c)
  for (double t = 0; t < T; t += dt) {
    for (int i = 0; i < 4; i++) b->in->Omega[i] = static_cast<fsw_real>(om[i]);
    const FswStatus s = b->update();
    ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT);
    if (s != FSW_OK) break;
    double u[4];
    torque(t, u);
    for (int i = 0; i < 4; i++) {
      nin->u_s[i] = static_cast<fsw_real>(u[i]);
      nin->Omega[i] = static_cast<fsw_real>(om[i]);
      nin->Omega_des[i] = b->out->Omega_des[i];
    }
    // W_SINGULAR: a null step so small that the rounding of u_c + du is
    // above rw_null's null-space test; rw_null then applies u_c alone
    const FswStatus ns = fsw_rw_null_update(nst.get(), nul.get(), nin.get(), nout.get());
    ASSERT_TRUE(ns == FSW_OK || ns == FSW_W_SINGULAR) << ns;
    singular += ns == FSW_W_SINGULAR;
    double gu[3];
    rwt::gs_times(gu, g, u, 4);
    for (int k = 0; k < 3; k++) hu[k] += gu[k] * dt / Js;
    for (int i = 0; i < 4; i++) {
      om[i] += double(nout->u_s[i]) / Js * dt;
      ASSERT_GT(om[i] * om0[i], 0) << "wheel " << i << " crossed zero at t = " << t;
      min_abs = std::fmin(min_abs, std::fabs(om[i]));
    }
    t_ok = t;
  }
  // the null motion moved no momentum: Gs Omega = Gs Omega0 + integral of Gs u_c
  double h1[3];
  rwt::gs_times(h1, g, om, 4);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(h1[k], h0[k] + hu[k], kt::tol(1e-9, 1e-2) * (1 + std::fabs(h1[k])));
  EXPECT_GE(t_ok, T - 2 * dt) << "the set stays feasible over the whole run";
  RecordProperty("t_cross_without_bias_s", std::to_string(t_cross));
  RecordProperty("t_feasible_s", std::to_string(t_ok));
  RecordProperty("min_abs_speed", std::to_string(min_abs));
  std::printf("closed loop: control crosses at %.1f s; stack OK to %.1f s, min |Omega| %.3f rad/s, "
              "rw_null W_SINGULAR %d of %d\n", t_cross, t_ok, min_abs, singular, int(T / dt));
}

// Verifies: REQ-RWBIAS-005
TEST(RwBiasBadInput, SafeOutputIsTheCurrentSpeedsAndNothingChanges)
{
  struct Row {
    const char* why;
    void (*spoil)(FswRwBiasIn*);
  };
  static const Row rows[] = {
      {"Omega NaN", [](FswRwBiasIn* in) { in->Omega[2] = kNaN; }},
      {"Omega Inf", [](FswRwBiasIn* in) { in->Omega[0] = -kInf; }},
      {"Omega beyond the range", [](FswRwBiasIn* in) { in->Omega[0] = FSW_R(2e4); }},
      {"mask value 2", [](FswRwBiasIn* in) { in->avail[3] = 2; }},
  };
  for (const Row& row : rows) {
    auto f = pyramid();
    f->speeds({3, -100, 100, -100});  // wheel 1 enters the band ...
    ASSERT_EQ(f->update(), FSW_OK);
    const auto before = *f->st;
    f->speeds({50, -100, 100, -100});
    f->in->avail[1] = FSW_UNAVAILABLE;  // ... a mask change that must not be taken
    row.spoil(f->in.get());
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_BAD_INPUT) << row.why;
    for (int i = 0; i < 4; i++) {
      const double om = f->in->Omega[i];
      const double want = (std::isfinite(om) && std::fabs(om) <= FSW_RW_OMEGA_MAX) ? om : 0.0;
      EXPECT_EQ(f->out->Omega_des[i], want) << row.why << " " << i;
      EXPECT_EQ(f->out->in_band[i], 0);
      EXPECT_EQ(f->out->unavoidable[i], 0);
    }
    for (int i = 4; i < FSW_MAX_RW; i++) EXPECT_EQ(f->out->Omega_des[i], 0.0);
    EXPECT_EQ(f->out->lambda_norm, 0.0);
    EXPECT_EQ(f->st->health.bad_input, 1u);
    auto after = *f->st;
    after.health = before.health;
    EXPECT_EQ(0, std::memcmp(&before, &after, sizeof before)) << row.why;
  }
  // an unavailable wheel's bad speed is not read
  auto f = pyramid();
  f->in->avail[2] = FSW_UNAVAILABLE;
  f->speeds({100, -100, 3e30, -100});
  EXPECT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->Omega_des[2], 0.0);
}

// Verifies: REQ-RWBIAS-006
TEST(RwBiasRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  auto f = pyramid();
  fsw_real first[8][4];
  for (int pass = 0; pass < 2; pass++) {
    kt::Rng r(9);
    for (int k = 0; k < 8; k++) {
      for (int i = 0; i < 4; i++) {
        f->in->Omega[i] = static_cast<fsw_real>(r.uniform(-40, 40));
        f->in->avail[i] = (k == 5 && i == 1) ? FSW_UNAVAILABLE : FSW_AVAILABLE;
      }
      (void)f->update();
      for (int i = 0; i < 4; i++) {
        if (pass == 0)
          first[k][i] = f->out->Omega_des[i];
        else
          EXPECT_EQ(f->out->Omega_des[i], first[k][i]) << k << "/" << i;
      }
    }
    fsw_rw_bias_reset(f->st.get());
  }
}

// Verifies: REQ-GEN-007
TEST(RwBiasNullArgs, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("rw_bias", fsw_rw_bias_check, fsw_rw_bias_init, fsw_rw_bias_reset, fsw_rw_bias_update);
}

// MC/DC of the side of a wheel at rest (rw_bias.c, `om > 0 || (om == 0 &&
// bias > 0)`): wheel 1 at exactly 0 takes the side of its bias.  Pyramid,
// keepout 10, hyst 5, Omega = (0, -100, 100, -100).
//   bias_1 = -100: side -1, in band, b = 15: Omega_des_1 <= -15, i.e.
//   lambda/2 <= -15.  lambda_u = n.(bias - Omega) = (-100)/2 = -50 is
//   admissible (the others allow lambda >= -180): Omega_des = Omega - 50 n
//   = (-25, -75, 75, -75).
//   bias_1 = +100: side +1, lambda_u = +50: (25, -125, 125, -125) (as in
//   WheelNearZeroIsPushedOutOnItsOwnSide).
// Verifies: REQ-RWBIAS-003
TEST(RwBiasNominal, McdcWheelAtRestTakesTheSideOfItsNegativeBias)
{
  auto f = pyramid();
  f->cfg->Omega_bias[0] = FSW_R(-100.0);
  ASSERT_EQ(f->init(), FSW_OK);
  f->speeds({0, -100, 100, -100});
  ASSERT_EQ(f->update(), FSW_OK);
  expect_des(*f, {-25, -75, 75, -75}, "negative bias");
  EXPECT_EQ(f->out->in_band[0], 1);
  EXPECT_NEAR(f->out->lambda_norm, 50.0, kTol * 50);
  f->cfg->Omega_bias[0] = FSW_R(100.0);
  ASSERT_EQ(f->init(), FSW_OK);
  ASSERT_EQ(f->update(), FSW_OK);
  expect_des(*f, {25, -125, 125, -125}, "positive bias");
}

namespace {

// Five wheels: two along x, one along y, one along z, one along
// (1,1,1)/sqrt(3) that is unavailable.  The four available wheels have
// nullity 1, null vector n = (1, -1, 0, 0, 0)/sqrt(2) (sign immaterial):
// wheels 3 and 4 (y, z) lie outside the null motion (n_i = 0) and wheel 5
// is not available.  Keepout 10, hyst 5, bias (100, -100, 100, -100, 100).
std::unique_ptr<Fixture> xxyz_and_one_failed()
{
  const double s = 1.0 / std::sqrt(3.0);
  const double g[5][3] = {{1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {s, s, s}};
  auto f = rwt::make0<Fixture>();
  f->setup(g, 5);
  EXPECT_EQ(f->init(), FSW_OK);
  EXPECT_EQ(f->st->nullity, 2);
  f->in->avail[4] = FSW_UNAVAILABLE;
  return f;
}

}  // namespace

// MC/DC of the k = 1 solver's tests for a wheel outside the null motion
// and for an unavailable wheel (rw_bias.c solve_k1: the speed bounds, the
// keep-out intervals `lo > 0 || hi < 0`, the candidates of the infeasible
// case).  Wheels 1, 2 (x) at 50 and 30, r = 1/sqrt(2), the step is
// (lambda r, -lambda r, 0, 0, 0); bias_2 = 40 - 10 T (T =
// FSW_RW_BIAS_TOL), so lambda_u r = r^2 ((100 - 50) - (bias_2 - 30)) =
// 20 + 5 T.  Wheel 2 keeps out for 30 - lambda r >= 10, lambda r <= 20;
// it counts as kept out down to (1 - T) 10, lambda r <= 20 + 10 T.
// (a) y and z wheels at 200 and -300, out of their bands: they bound
//   nothing; the constraints are feasible and lambda is lambda_u clamped
//   to lambda r <= 20: Omega_des = (70, 10, 200, -300, held 123), FSW_OK.
// (b) y wheel at +5 (in band, its side +): it cannot move, so no lambda
//   keeps it out; lambda is the candidate with the fewest wheels in the
//   band, then the nearest to lambda_u: lambda_u itself (wheel 3 only:
//   wheel 2 at 10 - 5 T counts as out), Omega_des = (70 + 5 T, 10 - 5 T,
//   5, -300, 123), wheel 3 flagged, FSW_W_SAT.
// (c) z wheel at -5 (in band, its side -): as (b) with wheel 4 flagged.
// Verifies: REQ-RWBIAS-002, REQ-RWBIAS-003, REQ-RWBIAS-004
TEST(RwBiasInfeasible, McdcWheelsOutsideTheNullMotionAndAFailedWheel)
{
  const double T = FSW_RW_BIAS_TOL;
  const struct {
    const char* why;
    double om3, om4, step;
    FswStatus want;
    int flagged;
  } rows[] = {{"(a) out of band", 200, -300, 20, FSW_OK, -1},
              {"(b) y wheel in band, + side", 5, -300, 20 + 5 * T, FSW_W_SAT, 2},
              {"(c) z wheel in band, - side", 200, -5, 20 + 5 * T, FSW_W_SAT, 3}};
  for (const auto& r : rows) {
    auto f = xxyz_and_one_failed();
    f->cfg->Omega_bias[1] = static_cast<fsw_real>(40 - 10 * T);
    ASSERT_EQ(f->init(), FSW_OK);
    f->speeds({50, 30, r.om3, r.om4, 123});
    EXPECT_EQ(f->update(), r.want) << r.why;
    EXPECT_EQ(f->out->nullity, 1) << r.why;
    expect_des(*f, {50 + r.step, 30 - r.step, r.om3, r.om4, 123}, r.why);
    for (int i = 0; i < 5; i++) EXPECT_EQ(f->out->unavoidable[i], i == r.flagged ? 1 : 0) << r.why << " " << i;
    EXPECT_EQ(f->out->crossing_unavoidable, r.flagged >= 0 ? 1 : 0) << r.why;
    EXPECT_NEAR(f->out->lambda_norm, r.step * std::sqrt(2.0), kTol * 40) << r.why;
    EXPECT_LT(momentum_change(*f->cfg, f->out->Omega_des, f->in->Omega, f->in->avail), kTol) << r.why;
  }
}

// MC/DC of the speed limit of a step (rw_bias.c step_of, `delta > 0 &&
// Omega + delta > OMEGA_MAX` and its negative twin): three wheels along x
// (nullity 2: every step with d_1 + d_2 + d_3 = 0), y and z wheels at 200
// and -300 (outside the null motion, out of their bands).  The x wheels at
// 5 rad/s, all in their band on the + side (b = 15): keeping all three out
// needs a sum of at least 45, the momentum fixes it at 15, so at least one
// stays in the band whatever the step.  Bias (M, M, -M) with M =
// FSW_RW_OMEGA_MAX = 1e4: the unconstrained step is the projection of
// bias - Omega = (9995, 9995, -10005) on the null space, minus its mean
// 9985/3: (20000/3, 20000/3, -40000/3).  It would take wheel 3 to
// -13328.3, beyond -M: the step is scaled by alpha = (M + 5)/(40000/3) =
// 0.750375 to (5002.5, 5002.5, -10005) (wheels 1, 2 stay below M: their
// test is false), Omega_des = (5007.5, 5007.5, -10000): one wheel in the
// band (the fewest possible: the solver's own iterate, which cannot meet
// every constraint, leaves more), FSW_W_SAT, |delta| = 5002.5 sqrt(6).
// The mirror image (speeds -5, bias (-M, -M, M)) exercises the + limit.
// Verifies: REQ-RWBIAS-002, REQ-RWBIAS-004
TEST(RwBiasInfeasible, McdcAStepBeyondTheSpeedLimitIsScaledBackWhole)
{
  const double g[5][3] = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const double M = 1e4;
  for (int sign = 1; sign >= -1; sign -= 2) {
    auto f = rwt::make0<Fixture>();
    f->setup(g, 5);
    const double bias[5] = {sign * M, sign * M, -sign * M, 100, -100};
    for (int i = 0; i < 5; i++) f->cfg->Omega_bias[i] = static_cast<fsw_real>(bias[i]);
    ASSERT_EQ(f->init(), FSW_OK);
    EXPECT_EQ(f->st->nullity, 2);
    f->speeds({sign * 5.0, sign * 5.0, sign * 5.0, 200, -300});
    EXPECT_EQ(f->update(), FSW_W_SAT) << sign;
    expect_des(*f, {sign * 5007.5, sign * 5007.5, -sign * M, 200, -300}, sign > 0 ? "- limit" : "+ limit");
    for (int i = 0; i < 5; i++) EXPECT_EQ(f->out->unavoidable[i], i == 2 ? 1 : 0) << sign << " " << i;
    EXPECT_NEAR(f->out->lambda_norm, 5002.5 * std::sqrt(6.0), kTol * 2e4) << sign;
    EXPECT_LT(momentum_change(*f->cfg, f->out->Omega_des, f->in->Omega, f->in->avail), kTol) << sign;
  }
}

// rw_null_regen: regenerative power-optimal null motion (docs/fsw/rw_null_regen.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/rw_map.h"
#include "fsw/rw_null_regen.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();

struct Fixture {
  std::unique_ptr<FswRwNullRegenConfig> cfg = rwt::make0<FswRwNullRegenConfig>();
  std::unique_ptr<FswRwNullRegenState> st = rwt::make0<FswRwNullRegenState>();
  std::unique_ptr<FswRwNullRegenIn> in = rwt::make0<FswRwNullRegenIn>();
  std::unique_ptr<FswRwNullRegenOut> out = rwt::make0<FswRwNullRegenOut>();
  void setup(const double g[][3], int n, int mode, double kP = 1e-4, double umax = 0.1)
  {
    cfg->num_rw = n;
    rwt::set_axes(cfg->gs_hat_B, g, n);
    cfg->mode = mode;
    cfg->k_P = static_cast<fsw_real>(kP);
    for (int i = 0; i < n; i++) cfg->u_max[i] = static_cast<fsw_real>(umax);
  }
  FswStatus init() { return fsw_rw_null_regen_init(st.get(), cfg.get()); }
  FswStatus update() { return fsw_rw_null_regen_update(st.get(), cfg.get(), in.get(), out.get()); }
};

std::unique_ptr<Fixture> pyramid(int mode)
{
  double g[4][3];
  rwt::pyramid4(g);
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, mode);
  EXPECT_EQ(f->init(), FSW_OK);
  return f;
}

double dot(const fsw_real* a, const fsw_real* b, int n)
{
  double s = 0;
  for (int i = 0; i < n; i++) s += double(a[i]) * double(b[i]);
  return s;
}

double body_change(const FswRwNullRegenConfig& c, const fsw_real* u, const fsw_real* u0)
{
  double du[FSW_MAX_RW], t[3], a = 0, b = 0;
  for (int i = 0; i < c.num_rw; i++) {
    du[i] = double(u[i]) - double(u0[i]);
    a += double(u0[i]) * double(u0[i]);
    b += du[i] * du[i];
  }
  rwt::gs_times(t, c.gs_hat_B, du, c.num_rw);
  return rwt::norm3(t) / (std::sqrt(a) + std::sqrt(b) + 1e-300);
}

// Null vector of four axes in general position by cofactors:
// n_i = (-1)^i det(g_j, g_k, g_l) (the other three, in order).
void null4(double nv[4], const double g[4][3])
{
  for (int i = 0; i < 4; i++) {
    const double* c[3];
    int m = 0;
    for (int j = 0; j < 4; j++)
      if (j != i) c[m++] = g[j];
    const double det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                       c[1][0] * (c[0][1] * c[2][2] - c[0][2] * c[2][1]) +
                       c[2][0] * (c[0][1] * c[1][2] - c[0][2] * c[1][1]);
    nv[i] = (i % 2 ? -1.0 : 1.0) * det;
  }
}

}  // namespace

// Verifies: REQ-RWREGEN-001
TEST(RwNullRegenConfig, RejectsBadConfigurationsTableDriven)
{
  struct Row {
    const char* why;
    void (*spoil)(FswRwNullRegenConfig*);
    FswStatus want;
  };
  static const Row rows[] = {
      {"no wheels", [](FswRwNullRegenConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many wheels", [](FswRwNullRegenConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"axis not unit", [](FswRwNullRegenConfig* c) { c->gs_hat_B[2][2] = FSW_R(3.0); }, FSW_E_CONFIG},
      {"unknown mode", [](FswRwNullRegenConfig* c) { c->mode = 5; }, FSW_E_CONFIG},
      {"gradient gain zero", [](FswRwNullRegenConfig* c) { c->k_P = 0; }, FSW_E_CONFIG},
      {"gradient gain NaN", [](FswRwNullRegenConfig* c) { c->k_P = kNaN; }, FSW_E_CONFIG},
      {"limit zero", [](FswRwNullRegenConfig* c) { c->u_max[1] = 0; }, FSW_E_CONFIG},
      {"limit negative", [](FswRwNullRegenConfig* c) { c->u_max[3] = FSW_R(-1.0); }, FSW_E_CONFIG},
  };
  for (const Row& row : rows) {
    auto f = pyramid(FSW_RW_REGEN_GRADIENT);
    row.spoil(f->cfg.get());
    EXPECT_EQ(fsw_rw_null_regen_check(f->cfg.get()), row.want) << row.why;
    EXPECT_EQ(f->init(), row.want) << row.why;
    EXPECT_EQ(f->update(), FSW_E_NOT_INIT);
    for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(f->out->u_s[i], 0.0);
  }
  auto f = pyramid(FSW_RW_REGEN_OPTIMUM);
  f->cfg->k_P = 0;  // not used by OPTIMUM
  EXPECT_EQ(f->init(), FSW_OK);
}

// Gradient, pyramid (null vector n = (1,-1,1,-1)/2): Omega = (100,0,0,0),
// k_P = 1e-4, u0 = 0: d = -k_P Omega = (-0.01,0,0,0), n.d = -0.005,
// [tau] d = -0.005 n = (-0.0025, 0.0025, -0.0025, 0.0025); P = -0.25 W.
// Verifies: REQ-RWREGEN-002
TEST(RwNullRegenNominal, GradientPyramidHandNumbers)
{
  auto f = pyramid(FSW_RW_REGEN_GRADIENT);
  f->in->Omega[0] = FSW_R(100.0);
  ASSERT_EQ(f->update(), FSW_OK);
  const double want[4] = {-0.0025, 0.0025, -0.0025, 0.0025};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f->out->u_s[i], want[i], kt::tol(1e-17, 1e-9)) << i;
  EXPECT_NEAR(f->out->power, -0.25, kt::tol(1e-14, 1e-6));
}

// Optimum, pyramid, u_max = 0.1, u0 = min-norm map of Lr = (0.03,-0.06,0.12):
// u0 = -(0.0675, 0.0225, 0.1125, 0.1575)/sqrt3 (see test_rw_map).
// Omega = (100, 50, -30, 10): Omega.n = (100-50-30-10)/2 = 5 > 0 -> alpha_lo.
// Bounds alpha in [(-0.1 - u0_i)/n_i, (0.1 - u0_i)/n_i] (swapped for n_i < 0):
// wheel 3 (u0 = -0.0650, n = 1/2) binds: alpha = 2(-0.1 - u0_3) = -0.0701,
// so u_3 = -u_max exactly and P drops by 5 |alpha| = 0.3505 W.
// Verifies: REQ-RWREGEN-003
TEST(RwNullRegenNominal, OptimumPyramidHandNumbers)
{
  auto f = pyramid(FSW_RW_REGEN_OPTIMUM);
  const double s3 = std::sqrt(3.0);
  const double u0[4] = {-0.0675 / s3, -0.0225 / s3, -0.1125 / s3, -0.1575 / s3};
  const double Om[4] = {100, 50, -30, 10};
  for (int i = 0; i < 4; i++) {
    f->in->u_s[i] = static_cast<fsw_real>(u0[i]);
    f->in->Omega[i] = static_cast<fsw_real>(Om[i]);
  }
  ASSERT_EQ(f->update(), FSW_OK);
  const double alpha = 2.0 * (-0.1 - u0[2]);
  const double nv[4] = {0.5, -0.5, 0.5, -0.5};
  double P0 = 0;
  for (int i = 0; i < 4; i++) {
    EXPECT_NEAR(f->out->u_s[i], u0[i] + alpha * nv[i], kt::tol(1e-15, 1e-7)) << i;
    P0 += Om[i] * u0[i];
  }
  EXPECT_NEAR(f->out->u_s[2], -0.1, kt::tol(1e-16, 1e-8));
  EXPECT_NEAR(f->out->power, P0 + 5.0 * alpha, kt::tol(1e-13, 1e-5));
  // Omega orthogonal to n: any alpha is optimal, the rule picks alpha = 0
  const double Om0[4] = {100, 100, 100, 100};
  for (int i = 0; i < 4; i++) f->in->Omega[i] = static_cast<fsw_real>(Om0[i]);
  ASSERT_EQ(f->update(), FSW_OK);
  for (int i = 0; i < 4; i++) EXPECT_EQ(f->out->u_s[i], f->in->u_s[i]);
}

// u0 = (0.3, 0.3, 0, 0), u_max = 0.1: wheel 1 needs alpha <= -0.4, wheel 2
// needs alpha >= 0.4: empty interval -> u = u0 and FSW_W_SAT.
// Verifies: REQ-RWREGEN-003
TEST(RwNullRegenNominal, OptimumEmptyIntervalReturnsU0)
{
  auto f = pyramid(FSW_RW_REGEN_OPTIMUM);
  f->in->u_s[0] = f->in->u_s[1] = FSW_R(0.3);
  f->in->Omega[0] = FSW_R(10.0);
  EXPECT_EQ(f->update(), FSW_W_SAT);
  for (int i = 0; i < 4; i++) EXPECT_EQ(f->out->u_s[i], f->in->u_s[i]);
}

// Verifies: REQ-RWREGEN-003
TEST(RwNullRegenNominal, OptimumNullityZeroAndAboveOne)
{
  double g[6][3];
  kt::Rng rng(42);
  rwt::random_axes(rng, 6, g);
  auto f = rwt::make0<Fixture>();
  f->setup(g, 6, FSW_RW_REGEN_OPTIMUM);
  ASSERT_EQ(f->init(), FSW_OK);
  for (int i = 0; i < 6; i++) {
    f->in->u_s[i] = static_cast<fsw_real>(0.01 * (i - 2));
    f->in->Omega[i] = static_cast<fsw_real>(50.0 * i);
  }
  EXPECT_EQ(f->update(), FSW_E_UNSUPPORTED);  // nullity 3
  for (int i = 0; i < 6; i++) EXPECT_EQ(f->out->u_s[i], f->in->u_s[i]);
  for (int i = 3; i < 6; i++) f->in->avail[i] = FSW_UNAVAILABLE;  // nullity 0
  EXPECT_EQ(f->update(), FSW_OK);
  for (int i = 0; i < 6; i++) EXPECT_EQ(f->out->u_s[i], i < 3 ? f->in->u_s[i] : 0.0);
}

// Verifies: REQ-RWREGEN-005
TEST(RwNullRegenBadInput, NonFiniteOrBadMaskGivesZeros)
{
  for (int row = 0; row < 3; row++) {
    auto f = pyramid(FSW_RW_REGEN_GRADIENT);
    f->in->avail[0] = FSW_UNAVAILABLE;  // must not be taken
    if (row == 0) f->in->u_s[1] = kNaN;
    if (row == 1) f->in->Omega[2] = -std::numeric_limits<fsw_real>::infinity();
    if (row == 2) f->in->avail[3] = 3;
    for (int i = 0; i < FSW_MAX_RW; i++) f->out->u_s[i] = 5;
    EXPECT_EQ(f->update(), FSW_E_BAD_INPUT) << row;
    for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(f->out->u_s[i], 0.0);
    EXPECT_EQ(f->st->proj.num_avail, 4);
    EXPECT_EQ(f->st->health.bad_input, 1u);
  }
}

// Verifies: REQ-GEN-007
TEST(RwNullRegenBadInput, NullArgumentsAssertAndReturn)
{
  auto f = pyramid(FSW_RW_REGEN_GRADIENT);
  kestrel_assert_reset();
  EXPECT_EQ(fsw_rw_null_regen_check(nullptr), FSW_E_NULL_ARG);
  EXPECT_EQ(fsw_rw_null_regen_update(f->st.get(), f->cfg.get(), nullptr, f->out.get()), FSW_E_NULL_ARG);
  EXPECT_EQ(kestrel_assert_count(), 2u);
  kestrel_assert_reset();
}

// Verifies: REQ-RWREGEN-006
TEST(RwNullRegenRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  for (int mode = 0; mode < 2; mode++) {
    auto f = pyramid(mode);
    fsw_real first[5][4];
    for (int pass = 0; pass < 2; pass++) {
      kt::Rng r(9);
      for (int k = 0; k < 5; k++) {
        for (int i = 0; i < 4; i++) {
          f->in->u_s[i] = static_cast<fsw_real>(r.uniform(-0.05, 0.05));
          f->in->Omega[i] = static_cast<fsw_real>(r.uniform(-500, 500));
        }
        (void)f->update();
        for (int i = 0; i < 4; i++) {
          if (pass == 0)
            first[k][i] = f->out->u_s[i];
          else
            EXPECT_EQ(f->out->u_s[i], first[k][i]);
        }
      }
      fsw_rw_null_regen_reset(f->st.get());
    }
  }
}

// Properties with u0 from rw_map's minimum-norm solution inside the limits:
// body torque unchanged (1e-12), Omega^T u <= Omega^T u0, |u_i| <= u_max_i.
// OPTIMUM is exercised with exactly four available wheels (nullity 1) and
// checked against an independent optimum: the cofactor null vector and the
// interval end chosen by comparing the power at both ends.
class RwNullRegenProperties : public ::testing::TestWithParam<int> {};

// Verifies: REQ-RWREGEN-004
TEST_P(RwNullRegenProperties, BodyTorquePowerAndLimits)
{
  const int n = GetParam();
  kt::Rng rng(4000u + static_cast<uint64_t>(n));
  double g[FSW_MAX_RW][3];
  auto f = rwt::make0<Fixture>();
  auto mc = rwt::make0<FswRwMapConfig>();
  auto ms = rwt::make0<FswRwMapState>();
  auto mi = rwt::make0<FswRwMapIn>();
  auto mo = rwt::make0<FswRwMapOut>();
  for (int trial = 0; trial < 30; trial++) {
    const int mode = trial % 2;
    rwt::random_axes(rng, n, g);
    f->setup(g, n, mode, rng.uniform(1e-5, 1e-2), 0.0);
    for (int i = 0; i < n; i++) f->cfg->u_max[i] = static_cast<fsw_real>(rng.uniform(0.05, 0.2));
    ASSERT_EQ(f->init(), FSW_OK);
    mc->num_rw = n;
    rwt::set_axes(mc->gs_hat_B, g, n);
    mc->num_axes = 3;
    for (int j = 0; j < 3; j++)
      for (int r = 0; r < 3; r++) mc->ctrl_axes_B[j][r] = j == r ? FSW_R(1.0) : FSW_R(0.0);
    ASSERT_EQ(fsw_rw_map_init(ms.get(), mc.get()), FSW_OK);
    // availability: OPTIMUM keeps exactly 4 wheels (nullity 1) when n > 4
    int avail_idx[4] = {0, 1, 2, 3};
    for (int i = 0; i < n; i++) mi->avail[i] = FSW_AVAILABLE;
    if (mode == FSW_RW_REGEN_OPTIMUM && n > 4) {
      for (int i = 0; i < n; i++) mi->avail[i] = FSW_UNAVAILABLE;
      for (int k = 0; k < 4; k++) {
        int c;
        do c = rng.uniform_int(0, n - 1);
        while (mi->avail[c] == FSW_AVAILABLE);
        mi->avail[c] = FSW_AVAILABLE;
      }
      for (int i = 0, k = 0; i < n; i++)
        if (mi->avail[i] == FSW_AVAILABLE) avail_idx[k++] = i;
    }
    // u0: min-norm map of a torque scaled so that max |u0_i| = 0.5 u_min
    for (int r = 0; r < 3; r++) mi->Lr_B[r] = static_cast<fsw_real>(rng.normal());
    ASSERT_EQ(fsw_rw_map_update(ms.get(), mc.get(), mi.get(), mo.get()), FSW_OK);
    double umax_abs = 0;
    for (int i = 0; i < n; i++) umax_abs = std::fmax(umax_abs, std::fabs(double(mo->u_s[i])));
    const double sc = 0.5 * 0.05 / umax_abs;
    for (int i = 0; i < n; i++) {
      f->in->u_s[i] = static_cast<fsw_real>(double(mo->u_s[i]) * sc);
      f->in->Omega[i] = static_cast<fsw_real>(rng.uniform(-600, 600));
      f->in->avail[i] = mi->avail[i];
    }
    const FswStatus s = f->update();
    if (mode == FSW_RW_REGEN_OPTIMUM && n > 4) ASSERT_EQ(s, FSW_OK) << n;
    if (mode == FSW_RW_REGEN_OPTIMUM && n == 3) ASSERT_EQ(s, FSW_OK) << n;
    if (mode == FSW_RW_REGEN_OPTIMUM && n == 4) ASSERT_EQ(s, FSW_OK) << n;
    ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT) << s;

    EXPECT_LT(body_change(*f->cfg, f->out->u_s, f->in->u_s), kt::tol(1e-12, 1e-5)) << n << "/" << trial;
    const double P0 = dot(f->in->Omega, f->in->u_s, n);
    const double P = dot(f->in->Omega, f->out->u_s, n);
    EXPECT_LE(P, P0 + kt::tol(1e-12, 1e-5) * std::fabs(P0)) << n << "/" << trial;
    EXPECT_NEAR(f->out->power, P, kt::tol(1e-12, 1e-4) * (std::fabs(P) + 1e-3));
    for (int i = 0; i < n; i++) {
      EXPECT_LE(std::fabs(f->out->u_s[i]), f->cfg->u_max[i]);
      if (f->in->avail[i]) EXPECT_EQ(f->out->u_s[i], 0.0);
    }
    if (mode == FSW_RW_REGEN_OPTIMUM && n >= 4) {
      // independent optimum over the four available wheels
      double ga[4][3], nv[4], lo = -1e300, hi = 1e300;
      for (int k = 0; k < 4; k++)
        for (int r = 0; r < 3; r++) ga[k][r] = double(f->cfg->gs_hat_B[avail_idx[k]][r]);
      null4(nv, ga);
      double om_n = 0;
      for (int k = 0; k < 4; k++) {
        const int i = avail_idx[k];
        const double u0 = double(f->in->u_s[i]), um = double(f->cfg->u_max[i]);
        double a = (-um - u0) / nv[k], b = (um - u0) / nv[k];
        if (a > b) std::swap(a, b);
        lo = std::fmax(lo, a);
        hi = std::fmin(hi, b);
        om_n += double(f->in->Omega[i]) * nv[k];
      }
      ASSERT_LE(lo, hi);
      const double alpha = om_n > 0 ? lo : hi;  // P linear in alpha
      for (int k = 0; k < 4; k++) {
        const int i = avail_idx[k];
        EXPECT_NEAR(f->out->u_s[i], double(f->in->u_s[i]) + alpha * nv[k], kt::tol(1e-12, 1e-5))
            << n << "/" << trial << "/" << k;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Wheels, RwNullRegenProperties, ::testing::ValuesIn(rwt::kCounts));

// ---- issue 13: the contract for every input -------------------------------

// Finding 7 (rw_null_regen): gradient mode, k_P = 10, Omega ~ max gave NaN
// under W_SAT; now bad input with u = 0 and power = 0.  Optimum mode with
// u_max = max (power 1e306 W) is refused by check.
// Verifies: REQ-RWREGEN-005, REQ-RWREGEN-001
TEST(RwNullRegenIssue13, OverflowIsBadInputAndLimitsAreBounded)
{
  const double big = 0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  double g[4][3];
  rwt::pyramid4(g);
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, FSW_RW_REGEN_GRADIENT, 10.0);
  ASSERT_EQ(FSW_OK, f->init());
  for (int i = 0; i < 4; i++) f->in->Omega[i] = static_cast<fsw_real>(i == 0 ? big : 1.0);
  const FswRwNullProj proj_before = f->st->proj;
  EXPECT_EQ(FSW_E_BAD_INPUT, f->update());
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(0.0, f->out->u_s[i]);
  EXPECT_EQ(0.0, f->out->power);
  EXPECT_EQ(0, std::memcmp(&proj_before, &f->st->proj, sizeof proj_before));

  auto o = rwt::make0<Fixture>();
  o->setup(g, 4, FSW_RW_REGEN_OPTIMUM);
  o->cfg->u_max[2] = std::numeric_limits<fsw_real>::max();
  EXPECT_EQ(FSW_E_CONFIG, fsw_rw_null_regen_check(o->cfg.get()));
  o->cfg->u_max[2] = FSW_RW_U_MAX_MAX;
  EXPECT_EQ(FSW_OK, o->init());
}

// Fuzzing after the issue-13 fixes: gradient mode, the same round-off leak
// as rw_null's for a huge finite wheel speed (0.57 N*m of body torque at
// 1e100 rad/s): speeds beyond FSW_RW_OMEGA_MAX are bad input.
// Verifies: REQ-RWREGEN-005
TEST(RwNullRegenFuzzFinding, HugeFiniteSpeedIsBadInput)
{
  const double a = -0.57735026918962573;
  double g[4][3] = {{a, a, a}, {a, a, a}, {-0.68945749096291087, 0.2220286835304289, -0.68945749096291087}, {a, a, a}};
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, FSW_RW_REGEN_GRADIENT, 4e-4);
  for (int i = 0; i < 4; i++) f->cfg->u_max[i] = FSW_R(0.8);
  ASSERT_EQ(FSW_OK, f->init());
  const fsw_real om[4] = {FSW_R(100.0), FSW_R(-80.0), FSW_R(0.0), FSW_R(-40.0)};
  for (int i = 0; i < 4; i++) f->in->Omega[i] = om[i];
  ASSERT_EQ(FSW_OK, f->update());
  const FswRwNullProj proj_before = f->st->proj;
  for (const double w : {2e4, 1e30, 1e100}) {
    if (w > static_cast<double>(std::numeric_limits<fsw_real>::max())) continue;
    f->in->Omega[2] = static_cast<fsw_real>(w);
    EXPECT_EQ(FSW_E_BAD_INPUT, f->update()) << w;
    for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(0.0, f->out->u_s[i]);
    EXPECT_EQ(0, std::memcmp(&proj_before, &f->st->proj, sizeof proj_before));
  }
}

// Fuzzing after the issue-13 fixes: OPTIMUM with nullity > 1 returned
// FSW_E_UNSUPPORTED but kept the projector recomputed for the new mask (a
// state change on an error).  Now the projector is that of the last
// accepted call, byte for byte.
// Verifies: REQ-RWREGEN-003
TEST(RwNullRegenFuzzFinding, UnsupportedNullityLeavesTheProjectorUntouched)
{
  double g[6][3];
  kt::Rng rng(42);
  rwt::random_axes(rng, 6, g);
  auto f = rwt::make0<Fixture>();
  f->setup(g, 6, FSW_RW_REGEN_OPTIMUM);
  ASSERT_EQ(f->init(), FSW_OK);
  for (int i = 0; i < 6; i++) f->in->Omega[i] = static_cast<fsw_real>(50.0 * i);
  for (int i = 4; i < 6; i++) f->in->avail[i] = FSW_UNAVAILABLE;  // nullity 1
  ASSERT_EQ(f->update(), FSW_OK);
  const FswRwNullProj proj_before = f->st->proj;
  f->in->avail[4] = FSW_AVAILABLE;  // nullity 2: unsupported
  EXPECT_EQ(f->update(), FSW_E_UNSUPPORTED);
  EXPECT_EQ(0, std::memcmp(&proj_before, &f->st->proj, sizeof proj_before));
}


// Issue 21: gradient mode stopped by a limit reports W_SAT.  Pyramid,
// Omega = (100, 0, 0, 0), k_P = 1e-4: the full step is
// du = (-0.0025, 0.0025, -0.0025, 0.0025) (see GradientPyramidHandNumbers).
// u0 = (-0.099, 0, 0, 0), u_max = 0.1: wheel 1 reaches -u_max after
// kappa = (-0.1 + 0.099) / -0.0025 = 0.4 of the step (the others after 40),
// so u = u0 + 0.4 du = (-0.1, 0.001, -0.001, 0.001) and P = 100 * -0.1 = -10 W.
// A request already beyond its limit (u0_1 = 0.2) leaves no room: kappa = 0,
// u = u0, W_SAT.
// Verifies: REQ-RWREGEN-002
TEST(RwNullRegenIssue21, GradientStepCutByALimitIsWSat)
{
  auto f = pyramid(FSW_RW_REGEN_GRADIENT);
  f->in->Omega[0] = FSW_R(100.0);
  f->in->u_s[0] = static_cast<fsw_real>(-0.099);
  ASSERT_EQ(f->update(), FSW_W_SAT);
  const double want[4] = {-0.1, 0.001, -0.001, 0.001};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f->out->u_s[i], want[i], kt::tol(1e-15, 1e-7)) << i;
  EXPECT_NEAR(f->out->power, -10.0, kt::tol(1e-12, 1e-5));
  EXPECT_EQ(f->st->health.saturated, 1u);
  f->in->u_s[0] = FSW_R(0.2);
  ASSERT_EQ(f->update(), FSW_W_SAT);
  EXPECT_EQ(f->out->u_s[0], FSW_R(0.2));
  for (int i = 1; i < 4; i++) EXPECT_EQ(f->out->u_s[i], 0.0) << i;
  // the same request with room to move: the whole step, OK
  f->in->u_s[0] = FSW_R(0.0);
  EXPECT_EQ(f->update(), FSW_OK);
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(RwNullRegenIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("rw_null_regen", fsw_rw_null_regen_check, fsw_rw_null_regen_init, fsw_rw_null_regen_reset, fsw_rw_null_regen_update);
}

// Issue 21: rw_null's fuzz finding (StepThatIsNotNullIsDropped in
// test_rw_null.cpp) in gradient mode: wheels 1 and 2 are duplicates to
// 1e-16, which makes the cached projector ill-conditioned, and the step
// d = -k_P Omega = (0, 0, 0.128, 0) comes out of it with a body-torque
// component far above FSW_NULL_TOL of its size.  The step is dropped
// (u = u0, W_SINGULAR) rather than let through.  In either real type, and
// whatever the status: the body torque never moves by more than
// FSW_NULL_TOL-ish of the step (1e-4 x size, the rw_null bound).
// Verifies: REQ-RWREGEN-002
TEST(RwNullRegenIssue21, GradientStepThatIsNotNullIsDropped)
{
  const double g[4][3] = {{0.54167522041970195, 0.54167522041970195, 0.64278760968653936},
                          {0.54167522041970184, 0.54167522041970206, 0.64278760968653925},
                          {-0.54167522041970195, -0.54167522041970184, 0.64278760968653925},
                          {0.54167522041970184, -0.54167522041970206, 0.64278760968653936}};
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, FSW_RW_REGEN_GRADIENT, 0.002);
  const double umax[4] = {7.4, 0.2, 0.2, 0.2};
  for (int i = 0; i < 4; i++) f->cfg->u_max[i] = static_cast<fsw_real>(umax[i]);
  ASSERT_EQ(FSW_OK, f->init());
  f->in->Omega[2] = FSW_R(-64.0);
  const FswStatus s = f->update();
  ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT || s == FSW_W_SINGULAR) << s;
  if (sizeof(fsw_real) == 8) EXPECT_EQ(s, FSW_W_SINGULAR);
  double after[3] = {0, 0, 0}, size = 0.0;
  for (int i = 0; i < 4; i++) {
    size += std::fabs(static_cast<double>(f->out->u_s[i]));
    for (int k = 0; k < 3; k++) after[k] += g[i][k] * static_cast<double>(f->out->u_s[i]);
  }
  for (int k = 0; k < 3; k++) EXPECT_LE(std::fabs(after[k]), 1e-4 * size + 1e-30) << k;
  if (s == FSW_W_SINGULAR) {
    for (int i = 0; i < 4; i++) EXPECT_EQ(0.0, f->out->u_s[i]) << i;
    EXPECT_EQ(0.0, f->out->power);
  }
}

// Issue 21: a finite torque request whose power overflows.  Speeds are
// bounded (FSW_RW_OMEGA_MAX = 1e4 rad/s) but a request is only required to
// be finite: u0_1 = max/2 at Omega_1 = 1e4 gives Omega^T u = 5e3 max = inf,
// so the call is bad input with u = 0, power = 0.  (|u0_1| > u_max leaves
// the gradient step no room, u = u0 before the power.)
// Verifies: REQ-RWREGEN-005
TEST(RwNullRegenIssue21, OverflowingPowerIsBadInput)
{
  auto f = pyramid(FSW_RW_REGEN_GRADIENT);
  f->in->Omega[0] = FSW_RW_OMEGA_MAX;
  f->in->u_s[0] = std::numeric_limits<fsw_real>::max() / 2;
  EXPECT_EQ(FSW_E_BAD_INPUT, f->update());
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(0.0, f->out->u_s[i]) << i;
  EXPECT_EQ(0.0, f->out->power);
  f->in->u_s[0] = FSW_R(0.0);
  f->in->Omega[0] = FSW_R(100.0);
  EXPECT_EQ(FSW_OK, f->update());  // recovers (GradientPyramidHandNumbers)
  EXPECT_NEAR(f->out->power, -0.25, kt::tol(1e-14, 1e-6));
}

// Issue 21: OPTIMUM with a wheel outside the null motion.  Axes x, y, z and
// (x + y)/sqrt(2): the null vector is (1, 1, 0, -sqrt(2))/2, so wheel 3 (z)
// takes no part in it and no alpha can bring its u0_3 = 0.2 > u_max = 0.1
// back inside: W_SAT with u = u0.
// Verifies: REQ-RWREGEN-003
TEST(RwNullRegenIssue21, OptimumCannotFixAWheelOutsideTheNullSpace)
{
  const double h = 1.0 / std::sqrt(2.0);
  const double g[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {h, h, 0}};
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, FSW_RW_REGEN_OPTIMUM);
  ASSERT_EQ(FSW_OK, f->init());
  f->in->u_s[2] = FSW_R(0.2);
  f->in->Omega[0] = FSW_R(100.0);
  EXPECT_EQ(FSW_W_SAT, f->update());
  for (int i = 0; i < 4; i++) EXPECT_EQ(f->in->u_s[i], f->out->u_s[i]) << i;
}

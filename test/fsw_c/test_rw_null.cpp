// rw_null: wheel-speed null motion (docs/fsw/rw_null.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/rw_null.h"
#include "kestrel_test_support.h"
#include "null_args.h"
#include "rw_test_util.h"

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
const fsw_real kInf = std::numeric_limits<fsw_real>::infinity();

struct Fixture {
  std::unique_ptr<FswRwNullConfig> cfg = rwt::make0<FswRwNullConfig>();
  std::unique_ptr<FswRwNullState> st = rwt::make0<FswRwNullState>();
  std::unique_ptr<FswRwNullIn> in = rwt::make0<FswRwNullIn>();
  std::unique_ptr<FswRwNullOut> out = rwt::make0<FswRwNullOut>();

  void setup(const double g[][3], int n, double k = 0.01, int fit = 0, double umax = 0.1)
  {
    cfg->num_rw = n;
    rwt::set_axes(cfg->gs_hat_B, g, n);
    cfg->k_null = static_cast<fsw_real>(k);
    cfg->scale_to_fit = fit;
    for (int i = 0; i < n; i++) cfg->u_max[i] = static_cast<fsw_real>(umax);
  }
  FswStatus init() { return fsw_rw_null_init(st.get(), cfg.get()); }
  FswStatus update() { return fsw_rw_null_update(st.get(), cfg.get(), in.get(), out.get()); }
  void garbage()
  {
    for (int i = 0; i < FSW_MAX_RW; i++) out->u_s[i] = FSW_R(77.0);
  }
};

std::unique_ptr<Fixture> pyramid(int fit = 0)
{
  double g[4][3];
  rwt::pyramid4(g);
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, 0.01, fit);
  EXPECT_EQ(f->init(), FSW_OK);
  return f;
}

void expect_all_zero(const fsw_real* u)
{
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(u[i], 0.0) << "wheel " << i;
}

// |[Gs](u - u_c)| relative to |u_c| + |u - u_c| (the size of the terms).
double body_torque_change(const FswRwNullConfig& c, const fsw_real* u, const fsw_real* uc)
{
  double du[FSW_MAX_RW], t[3], a = 0, b = 0;
  for (int i = 0; i < c.num_rw; i++) {
    du[i] = double(u[i]) - double(uc[i]);
    a += double(uc[i]) * double(uc[i]);
    b += du[i] * du[i];
  }
  rwt::gs_times(t, c.gs_hat_B, du, c.num_rw);
  const double scale = std::sqrt(a) + std::sqrt(b);
  return scale > 0 ? rwt::norm3(t) / scale : rwt::norm3(t);
}

}  // namespace

// Verifies: REQ-RWNULL-001
TEST(RwNullConfig, RejectsBadConfigurationsTableDriven)
{
  struct Row {
    const char* why;
    void (*spoil)(FswRwNullConfig*);
    FswStatus want;
  };
  static const Row rows[] = {
      {"no wheels", [](FswRwNullConfig* c) { c->num_rw = 0; }, FSW_E_CAPACITY},
      {"too many wheels", [](FswRwNullConfig* c) { c->num_rw = FSW_MAX_RW + 1; }, FSW_E_CAPACITY},
      {"axis not unit", [](FswRwNullConfig* c) { c->gs_hat_B[0][2] = FSW_R(0.9); }, FSW_E_CONFIG},
      {"axis NaN", [](FswRwNullConfig* c) { c->gs_hat_B[1][1] = kNaN; }, FSW_E_CONFIG},
      {"gain zero", [](FswRwNullConfig* c) { c->k_null = 0; }, FSW_E_CONFIG},
      {"gain negative", [](FswRwNullConfig* c) { c->k_null = FSW_R(-0.1); }, FSW_E_CONFIG},
      {"gain Inf", [](FswRwNullConfig* c) { c->k_null = kInf; }, FSW_E_CONFIG},
      {"scale_to_fit flag 2", [](FswRwNullConfig* c) { c->scale_to_fit = 2; }, FSW_E_CONFIG},
      {"scale_to_fit with a zero limit",
       [](FswRwNullConfig* c) {
         c->scale_to_fit = 1;
         c->u_max[3] = 0;
       },
       FSW_E_CONFIG},
      {"scale_to_fit with a NaN limit",
       [](FswRwNullConfig* c) {
         c->scale_to_fit = 1;
         c->u_max[0] = kNaN;
       },
       FSW_E_CONFIG},
  };
  for (const Row& row : rows) {
    auto f = pyramid();
    row.spoil(f->cfg.get());
    EXPECT_EQ(fsw_rw_null_check(f->cfg.get()), row.want) << row.why;
    EXPECT_EQ(f->init(), row.want) << row.why;
    EXPECT_EQ(f->st->ready, 0);
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_NOT_INIT) << row.why;
    expect_all_zero(f->out->u_s);
  }
  // limits are not read without scale_to_fit
  auto f = pyramid();
  f->cfg->u_max[2] = 0;
  EXPECT_EQ(fsw_rw_null_check(f->cfg.get()), FSW_OK);
}

// Pyramid: null([Gs]) is spanned by n = (1,-1,1,-1)/2, so [tau] = n n^T.
// Omega = (100, 0, 0, 0) rad/s, Omega_des = 0, K = 0.01 N*m*s:
// d = (-1, 0, 0, 0) N*m, [tau] d = n (n.d) = -n/2 = (-1/4, 1/4, -1/4, 1/4).
// Verifies: REQ-RWNULL-002
TEST(RwNullNominal, PyramidDespinOneWheelHandNumbers)
{
  auto f = pyramid();
  f->in->Omega[0] = FSW_R(100.0);
  const double uc[4] = {0.01, -0.02, 0.03, 0.04};
  for (int i = 0; i < 4; i++) f->in->u_s[i] = static_cast<fsw_real>(uc[i]);
  f->garbage();
  ASSERT_EQ(f->update(), FSW_OK);
  const double du[4] = {-0.25, 0.25, -0.25, 0.25};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f->out->u_s[i], uc[i] + du[i], kt::tol(1e-15, 1e-7)) << i;
  for (int i = 4; i < FSW_MAX_RW; i++) EXPECT_EQ(f->out->u_s[i], 0.0);
  EXPECT_EQ(f->out->kappa, 1.0);
  EXPECT_EQ(f->st->proj.rank, 3);
}

// Omega_des shifts the target: Omega = Omega_des gives no null torque.
// Verifies: REQ-RWNULL-002
TEST(RwNullNominal, DesiredSpeedsReachedGiveNoNullTorque)
{
  auto f = pyramid();
  const double Om[4] = {150, -80, 20, 400};
  for (int i = 0; i < 4; i++) f->in->Omega[i] = f->in->Omega_des[i] = static_cast<fsw_real>(Om[i]);
  f->in->u_s[1] = FSW_R(0.05);
  ASSERT_EQ(f->update(), FSW_OK);
  for (int i = 0; i < 4; i++) EXPECT_EQ(f->out->u_s[i], i == 1 ? FSW_R(0.05) : 0.0);
}

// Three independent wheels: [tau] = 0, output = input (6.1 edge case).
// Verifies: REQ-RWNULL-002
TEST(RwNullNominal, ThreeIndependentWheelsPassInputThrough)
{
  const double g[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto f = rwt::make0<Fixture>();
  f->setup(g, 3);
  ASSERT_EQ(f->init(), FSW_OK);
  for (int i = 0; i < 3; i++) {
    f->in->u_s[i] = static_cast<fsw_real>(0.01 * (i + 1));
    f->in->Omega[i] = static_cast<fsw_real>(300.0 * (i + 1));
  }
  ASSERT_EQ(f->update(), FSW_OK);
  for (int i = 0; i < 3; i++) EXPECT_EQ(f->out->u_s[i], f->in->u_s[i]);
}

// Four wheels in the x-y plane (rank 2): the projector keeps the null torque
// out of the plane's torque.  Basilisk's singular 3x3 inverse returns zero,
// its [tau] becomes I and d is applied directly (docs/fsw/rw_null.md).
// g = (1,0,0), (0,1,0), (-1,0,0), (0,-1,0): null = span{(1,0,1,0), (0,1,0,1)}/sqrt2,
// d = (-1, 0, 0, 0) -> [tau] d = (-1/2, 0, -1/2, 0).
// Verifies: REQ-RWNULL-002
TEST(RwNullNominal, CoplanarSetHandNumbers)
{
  const double g[4][3] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  auto f = rwt::make0<Fixture>();
  f->setup(g, 4, 0.01);
  ASSERT_EQ(f->init(), FSW_OK);
  f->in->Omega[0] = FSW_R(100.0);
  ASSERT_EQ(f->update(), FSW_OK);
  const double want[4] = {-0.5, 0, -0.5, 0};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f->out->u_s[i], want[i], kt::tol(1e-15, 1e-7)) << i;
  EXPECT_EQ(f->st->proj.rank, 2);
}

// Availability: wheel 4 off -> three independent wheels -> no null torque,
// wheel 4 exactly 0 even if the input carried a torque; back on -> null
// torque again.  The projector follows the mask.
// Verifies: REQ-RWNULL-004
TEST(RwNullNominal, ProjectorRecomputedWhenAvailabilityChanges)
{
  auto f = pyramid();
  f->in->Omega[0] = FSW_R(100.0);
  f->in->u_s[3] = FSW_R(0.02);
  f->in->avail[3] = FSW_UNAVAILABLE;
  ASSERT_EQ(f->update(), FSW_OK);
  for (int i = 0; i < 4; i++) EXPECT_EQ(f->out->u_s[i], 0.0) << i;
  EXPECT_EQ(f->st->proj.num_avail, 3);
  f->in->avail[3] = FSW_AVAILABLE;
  f->in->u_s[3] = 0;
  ASSERT_EQ(f->update(), FSW_OK);
  EXPECT_NEAR(f->out->u_s[0], -0.25, kt::tol(1e-15, 1e-7));
  EXPECT_NEAR(f->out->u_s[3], 0.25, kt::tol(1e-15, 1e-7));
  EXPECT_EQ(f->st->proj.num_avail, 4);
}

// Scale to fit, u_max = 0.1: u_c = (0.05, 0, 0, 0), [tau] d = (-1/4, 1/4, -1/4, 1/4).
// Wheel 1: (-0.1 - 0.05)/(-0.25) = 0.6; wheels 2..4: 0.1/0.25 = 0.4 -> kappa = 0.4,
// u = (0.05 - 0.1, 0.1, -0.1, 0.1) = (-0.05, 0.1, -0.1, 0.1).
// Verifies: REQ-RWNULL-003
TEST(RwNullNominal, ScaleToFitHandNumbers)
{
  auto f = pyramid(1);
  f->in->Omega[0] = FSW_R(100.0);
  f->in->u_s[0] = FSW_R(0.05);
  EXPECT_EQ(f->update(), FSW_W_SAT);
  EXPECT_NEAR(f->out->kappa, 0.4, kt::tol(1e-15, 1e-7));
  const double want[4] = {-0.05, 0.1, -0.1, 0.1};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(f->out->u_s[i], want[i], kt::tol(1e-15, 1e-7)) << i;
  EXPECT_EQ(f->st->health.saturated, 1u);
  // u_c already beyond a limit: kappa = 0, u = u_c
  f->in->u_s[2] = FSW_R(-0.2);
  EXPECT_EQ(f->update(), FSW_W_SAT);
  EXPECT_EQ(f->out->kappa, 0.0);
  for (int i = 0; i < 4; i++) EXPECT_EQ(f->out->u_s[i], f->in->u_s[i]);
  // small null torque fits: kappa = 1, OK
  f->in->u_s[2] = 0;
  f->in->u_s[0] = 0;
  f->in->Omega[0] = FSW_R(1.0);
  EXPECT_EQ(f->update(), FSW_OK);
  EXPECT_EQ(f->out->kappa, 1.0);
}

// Verifies: REQ-RWNULL-005
TEST(RwNullBadInput, NonFiniteOrBadMaskGivesZerosAndKeepsProjector)
{
  struct Row {
    const char* why;
    void (*spoil)(FswRwNullIn*);
  };
  static const Row rows[] = {
      {"u_s NaN", [](FswRwNullIn* in) { in->u_s[2] = kNaN; }},
      {"Omega Inf (available wheel)", [](FswRwNullIn* in) { in->Omega[2] = kInf; }},
      {"Omega_des NaN", [](FswRwNullIn* in) { in->Omega_des[3] = kNaN; }},
      {"mask value 9", [](FswRwNullIn* in) { in->avail[0] = 9; }},
  };
  for (const Row& row : rows) {
    auto f = pyramid();
    f->in->avail[1] = FSW_UNAVAILABLE;  // a mask change that must not be taken
    f->in->Omega[0] = FSW_R(10.0);
    row.spoil(f->in.get());
    f->garbage();
    EXPECT_EQ(f->update(), FSW_E_BAD_INPUT) << row.why;
    expect_all_zero(f->out->u_s);
    EXPECT_EQ(f->st->health.bad_input, 1u);
    EXPECT_EQ(f->st->proj.avail[1], FSW_AVAILABLE) << row.why;
    EXPECT_EQ(f->st->proj.num_avail, 4) << row.why;
  }
  {
    // a failed tachometer on a wheel that is already unavailable is not read
    auto g = pyramid();
    g->in->avail[1] = FSW_UNAVAILABLE;
    g->in->Omega[0] = FSW_R(10.0);
    g->in->Omega[1] = kNaN;
    g->in->Omega_des[1] = kInf;
    EXPECT_EQ(g->update(), FSW_OK);
    for (int i = 0; i < 4; i++) EXPECT_TRUE(std::isfinite(g->out->u_s[i])) << i;
    EXPECT_EQ(g->out->u_s[1], 0.0);
  }
  auto f = pyramid();
  kestrel_assert_reset();
  EXPECT_EQ(fsw_rw_null_update(nullptr, f->cfg.get(), f->in.get(), f->out.get()), FSW_E_NULL_ARG);
  EXPECT_EQ(kestrel_assert_count(), 1u);
  kestrel_assert_reset();
}

// Verifies: REQ-RWNULL-006
TEST(RwNullRepeatability, SameInputsAfterResetGiveIdenticalOutputs)
{
  auto f = pyramid(1);
  fsw_real first[6][4];
  for (int pass = 0; pass < 2; pass++) {
    kt::Rng r(5);
    for (int k = 0; k < 6; k++) {
      for (int i = 0; i < 4; i++) {
        f->in->u_s[i] = static_cast<fsw_real>(r.uniform(-0.05, 0.05));
        f->in->Omega[i] = static_cast<fsw_real>(r.uniform(-500, 500));
        f->in->avail[i] = (k == 3 && i == 2) ? FSW_UNAVAILABLE : FSW_AVAILABLE;
      }
      (void)f->update();
      for (int i = 0; i < 4; i++) {
        if (pass == 0)
          first[k][i] = f->out->u_s[i];
        else
          EXPECT_EQ(f->out->u_s[i], first[k][i]) << k << "/" << i;
      }
    }
    fsw_rw_null_reset(f->st.get());
  }
}

// Property: [Gs] u = [Gs] u_c to 1e-12 for random inputs, random and
// coplanar geometries, random availability, with and without scale-to-fit;
// and |u_i| <= u_max_i whenever u_c is inside the limits.
class RwNullProperties : public ::testing::TestWithParam<int> {};

// Verifies: REQ-RWNULL-003
TEST_P(RwNullProperties, BodyTorqueUnchangedAndLimitsRespected)
{
  const int n = GetParam();
  kt::Rng rng(3000u + static_cast<uint64_t>(n));
  double g[FSW_MAX_RW][3];
  auto f = rwt::make0<Fixture>();
  for (int trial = 0; trial < 24; trial++) {
    const bool coplanar = trial % 4 == 1;
    const int fit = trial % 2;
    if (coplanar)
      rwt::coplanar_axes(rng, n, g);
    else
      rwt::random_axes(rng, n, g);
    f->setup(g, n, rng.uniform(1e-3, 1.0), fit, 0.0);
    for (int i = 0; i < n; i++) f->cfg->u_max[i] = static_cast<fsw_real>(rng.uniform(0.05, 0.2));
    ASSERT_EQ(f->init(), FSW_OK);
    for (int step = 0; step < 3; step++) {
      for (int i = 0; i < n; i++) {
        f->in->avail[i] = (trial % 3 == 2 && rng.uniform() < 0.2) ? FSW_UNAVAILABLE : FSW_AVAILABLE;
        // inside the limits, and 0 on unavailable wheels (rw_map's output)
        f->in->u_s[i] = f->in->avail[i] ? FSW_R(0.0) : static_cast<fsw_real>(rng.uniform(-0.9, 0.9)) * f->cfg->u_max[i];
        f->in->Omega[i] = static_cast<fsw_real>(rng.uniform(-600, 600));
        f->in->Omega_des[i] = static_cast<fsw_real>(rng.uniform(-100, 100));
      }
      const FswStatus s = f->update();
      ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT);
      EXPECT_LT(body_torque_change(*f->cfg, f->out->u_s, f->in->u_s), kt::tol(1e-12, 1e-5))
          << "n=" << n << " trial=" << trial << " coplanar=" << coplanar;
      for (int i = 0; i < n; i++) {
        if (f->in->avail[i]) EXPECT_EQ(f->out->u_s[i], 0.0);
        if (fit) EXPECT_LE(std::fabs(f->out->u_s[i]), f->cfg->u_max[i]);
      }
      if (!fit) EXPECT_EQ(f->out->kappa, 1.0);
      if (coplanar) EXPECT_LE(f->st->proj.rank, 2);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Wheels, RwNullProperties, ::testing::ValuesIn(rwt::kCounts));

// ---- issue 13: the contract for every input -------------------------------

// Finding 7 (rw_null): k_null ~ max is refused by check; a finite speed
// error that overflows (max - (-max)) gave NaN/inf under OK with kappa = 1:
// now bad input with u = 0, kappa = 0 and the projector untouched.
// Verifies: REQ-RWNULL-005, REQ-RWNULL-001
TEST(RwNullIssue13, OverflowIsBadInputAndGainIsBounded)
{
  const double big = 0.9 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  auto f = pyramid();
  f->cfg->k_null = static_cast<fsw_real>(big);
  EXPECT_EQ(FSW_E_CONFIG, fsw_rw_null_check(f->cfg.get()));
  f->cfg->k_null = FSW_R(0.01);
  ASSERT_EQ(FSW_OK, f->init());
  ASSERT_EQ(FSW_OK, f->update());  // all available: projector for the full set
  const FswRwNullProj proj_before = f->st->proj;
  f->in->avail[3] = FSW_UNAVAILABLE;
  f->in->Omega[0] = static_cast<fsw_real>(big);
  f->in->Omega_des[0] = static_cast<fsw_real>(-big);
  f->garbage();
  EXPECT_EQ(FSW_E_BAD_INPUT, f->update());
  expect_all_zero(f->out->u_s);
  EXPECT_EQ(0.0, f->out->kappa);
  EXPECT_EQ(0, std::memcmp(&proj_before, &f->st->proj, sizeof proj_before));
}

// Fuzzing after the issue-13 fixes: three wheels on one axis and a fourth
// alone; the fourth wheel's true null step is 0, so with a huge finite
// speed error its computed step is pure round-off (eps times the error),
// which scale-to-fit then turned into up to 0.117 N*m of body torque.
// Speeds beyond FSW_RW_OMEGA_MAX are bad input; at the bound the round-off
// is ~eps * k_null * 2e4, far below any torque that matters.
// Verifies: REQ-RWNULL-005
TEST(RwNullFuzzFinding, HugeFiniteSpeedErrorIsBadInputNotBodyTorque)
{
  auto f = pyramid();
  const double a = -0.57735026918962573;
  const double g[4][3] = {{a, a, a}, {a, a, a}, {-0.68945749096291087, 0.2220286835304289, -0.68945749096291087}, {a, a, a}};
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < 3; k++) f->cfg->gs_hat_B[i][k] = static_cast<fsw_real>(g[i][k]);
  f->cfg->k_null = FSW_R(0.02);
  f->cfg->scale_to_fit = 1;
  for (int i = 0; i < 4; i++) f->cfg->u_max[i] = FSW_R(0.2);
  ASSERT_EQ(FSW_OK, f->init());
  const fsw_real u0[4] = {FSW_R(0.05), FSW_R(-0.04), FSW_R(0.03), FSW_R(-0.02)};
  const fsw_real om[4] = {FSW_R(100.0), FSW_R(-80.0), FSW_R(60.0), FSW_R(-40.0)};
  for (int i = 0; i < 4; i++) {
    f->in->u_s[i] = u0[i];
    f->in->Omega[i] = om[i];
    f->in->Omega_des[i] = FSW_R(0.0);
  }
  const FswStatus s0 = f->update();
  ASSERT_TRUE(s0 == FSW_OK || s0 == FSW_W_SAT) << s0;
  const FswRwNullProj proj_before = f->st->proj;
  for (const double w : {2e4, 1e30, 1e100}) {
    if (w > static_cast<double>(std::numeric_limits<fsw_real>::max())) continue;
    f->in->Omega_des[2] = static_cast<fsw_real>(w);
    f->garbage();
    EXPECT_EQ(FSW_E_BAD_INPUT, f->update()) << w;
    expect_all_zero(f->out->u_s);
    EXPECT_EQ(0, std::memcmp(&proj_before, &f->st->proj, sizeof proj_before));
  }
  // at the bound the step is accepted and moves no body torque beyond round-off
  f->in->Omega_des[2] = FSW_RW_OMEGA_MAX;
  const FswStatus s = f->update();
  EXPECT_TRUE(s == FSW_OK || s == FSW_W_SAT) << s;
  for (int k = 0; k < 3; k++) {
    double before = 0.0, after = 0.0;
    for (int i = 0; i < 4; i++) {
      before += g[i][k] * static_cast<double>(u0[i]);
      after += g[i][k] * static_cast<double>(f->out->u_s[i]);
    }
    EXPECT_NEAR(after, before, sizeof(fsw_real) == 8 ? 1e-9 : 1e-3) << k;
  }
}

// Fuzzing after the speed bound: two axes equal to 1e-16 make the projector
// ill-conditioned and its null step moved the body torque by a third of its
// size.  A step that is not null to FSW_NULL_TOL is dropped (W_SINGULAR,
// u = u_c, kappa = 0); a well-conditioned set keeps its step.
// Verifies: REQ-RWNULL-002
TEST(RwNullFuzzFinding, StepThatIsNotNullIsDropped)
{
  auto f = pyramid();
  const double g[4][3] = {{0.54167522041970195, 0.54167522041970195, 0.64278760968653936},
                          {0.54167522041970184, 0.54167522041970206, 0.64278760968653925},
                          {-0.54167522041970195, -0.54167522041970184, 0.64278760968653925},
                          {0.54167522041970184, -0.54167522041970206, 0.64278760968653936}};
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < 3; k++) f->cfg->gs_hat_B[i][k] = static_cast<fsw_real>(g[i][k]);
  f->cfg->k_null = FSW_R(0.002);
  f->cfg->scale_to_fit = 1;
  const double umax[4] = {7.4, 0.2, 0.2, 0.2};
  for (int i = 0; i < 4; i++) f->cfg->u_max[i] = static_cast<fsw_real>(umax[i]);
  ASSERT_EQ(FSW_OK, f->init());
  // the fuzz case in plain numbers (double); in float the tiny values flush
  const double u0d[4] = {1.4349296274686128e-43, -1.1479437019748902e-43, 8.6095777648116778e-44,
                         -3.1115076389305709e-63};
  const double omd[4] = {2.8698592549372254e-40, -2.2958874039497803e-40, 1.7219155529623352e-40,
                         -1.1479437019748901e-40};
  const double desd[4] = {2.8698592549372254e-42, 2.8698592549372254e-42, 64.0, 0.0};
  fsw_real u0[4];
  for (int i = 0; i < 4; i++) {
    u0[i] = static_cast<fsw_real>(u0d[i]);
    f->in->u_s[i] = u0[i];
    f->in->Omega[i] = static_cast<fsw_real>(omd[i]);
    f->in->Omega_des[i] = static_cast<fsw_real>(desd[i]);
  }
  const FswStatus s = f->update();
  ASSERT_TRUE(s == FSW_OK || s == FSW_W_SAT || s == FSW_W_SINGULAR) << s;
  if (sizeof(fsw_real) == 8) EXPECT_EQ(s, FSW_W_SINGULAR);  // the case the fuzzer found
  double before[3] = {0, 0, 0}, after[3] = {0, 0, 0}, size = 0.0;
  for (int i = 0; i < 4; i++) {
    size += std::fabs(static_cast<double>(f->out->u_s[i] - u0[i]));
    for (int k = 0; k < 3; k++) {
      before[k] += g[i][k] * static_cast<double>(u0[i]);
      after[k] += g[i][k] * static_cast<double>(f->out->u_s[i]);
    }
  }
  for (int k = 0; k < 3; k++) EXPECT_LE(std::fabs(after[k] - before[k]), 1e-4 * size + 1e-30) << k;
  if (s == FSW_W_SINGULAR) {
    EXPECT_EQ(0.0, f->out->kappa);
    for (int i = 0; i < 4; i++) EXPECT_EQ(f->out->u_s[i], u0[i]);
  }
}


// Issue 21: rw_common's cached projector reports whether it recomputed.
// Pyramid, null vector n = (1, -1, 1, -1)/2: all available, tau = n n^T =
// (+-1/4); the same mask again -> 0 (nothing recomputed); wheel 3 off -> 1,
// three independent wheels: rank 3, nullity 0, tau exactly 0; all available
// again (NULL = all available) -> 1 and tau = n n^T back.
// Verifies: REQ-RWNULL-004
TEST(RwNullIssue21, ProjectorRefreshReportsAChangedMask)
{
  double gd[4][3];
  rwt::pyramid4(gd);
  fsw_real g[FSW_MAX_RW][3] = {};
  rwt::set_axes(g, gd, 4);
  auto p = rwt::make0<FswRwNullProj>();
  fsw_rw_proj_init(p.get(), g, 4);
  const double nv[4] = {0.5, -0.5, 0.5, -0.5};
  auto expect_tau = [&](bool null_space, const char* why) {
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++)
        EXPECT_NEAR(p->tau[i][j], null_space ? nv[i] * nv[j] : 0.0, kt::tol(1e-15, 1e-6))
            << why << " " << i << "," << j;
  };
  EXPECT_EQ(4, p->num_avail);
  EXPECT_EQ(3, p->rank);
  expect_tau(true, "all available");
  uint8_t avail[FSW_MAX_RW];
  for (int i = 0; i < FSW_MAX_RW; i++) avail[i] = FSW_AVAILABLE;
  EXPECT_EQ(0, fsw_rw_proj_refresh(p.get(), avail));
  EXPECT_EQ(0, fsw_rw_proj_refresh(p.get(), nullptr));
  avail[2] = FSW_UNAVAILABLE;
  EXPECT_EQ(1, fsw_rw_proj_refresh(p.get(), avail));
  EXPECT_EQ(3, p->num_avail);
  EXPECT_EQ(3, p->rank);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) EXPECT_EQ(0.0, p->tau[i][j]) << i << "," << j;
  EXPECT_EQ(0, fsw_rw_proj_refresh(p.get(), avail));
  EXPECT_EQ(1, fsw_rw_proj_refresh(p.get(), nullptr));
  EXPECT_EQ(4, p->num_avail);
  expect_tau(true, "available again");
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(RwNullIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("rw_null", fsw_rw_null_check, fsw_rw_null_init, fsw_rw_null_reset, fsw_rw_null_update);
}

// thr_map: thruster force mapping (docs/fsw/thr_map.md, both modes).
// Hand-computed cases, a config rejection table, bad input, repeatability,
// an independent double-precision re-implementation of the min-norm mode
// (explicit inverses instead of the library's Cholesky) and properties of
// the exact bounded mode over seeded random geometries.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <limits>

#include "fsw/thr_map.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

using R = fsw_real;
const double kTol = kt::tol(1e-12, 2e-5);

// --- configuration helpers ------------------------------------------------

void set3(R v[3], double x, double y, double z)
{
  v[0] = static_cast<R>(x);
  v[1] = static_cast<R>(y);
  v[2] = static_cast<R>(z);
}

FswThrMapConfig base_cfg()
{
  FswThrMapConfig c;
  std::memset(&c, 0, sizeof c);
  set3(c.control_axes_B[0], 1, 0, 0);
  set3(c.control_axes_B[1], 0, 1, 0);
  set3(c.control_axes_B[2], 0, 0, 1);
  c.thr_force_sign = 1;
  c.mode = FSW_THR_MAP_MIN_NORM;
  return c;
}

// Six thrusters whose torque arms (CoM at the origin) are +x,-x,+y,-y,+z,-z:
// thruster at (0,1,0) pushing +z has d = (0,1,0) x (0,0,1) = (1,0,0), etc.
FswThrMapConfig six_axis_cfg(double f_max = 1.0)
{
  FswThrMapConfig c = base_cfg();
  c.num_thr = 6;
  set3(c.r_thr_B[0], 0, 1, 0);  set3(c.gt_hat_B[0], 0, 0, 1);  // d = +x
  set3(c.r_thr_B[1], 0, -1, 0); set3(c.gt_hat_B[1], 0, 0, 1);  // d = -x
  set3(c.r_thr_B[2], 0, 0, 1);  set3(c.gt_hat_B[2], 1, 0, 0);  // d = +y
  set3(c.r_thr_B[3], 0, 0, -1); set3(c.gt_hat_B[3], 1, 0, 0);  // d = -y
  set3(c.r_thr_B[4], 1, 0, 0);  set3(c.gt_hat_B[4], 0, 1, 0);  // d = +z
  set3(c.r_thr_B[5], -1, 0, 0); set3(c.gt_hat_B[5], 0, 1, 0);  // d = -z
  for (int i = 0; i < 6; i++) c.F_max[i] = static_cast<R>(f_max);
  return c;
}

// Four DV thrusters pushing +z at (+-1, +-1, 0): d_i = (r_y, -r_x, 0).
FswThrMapConfig dv_cfg(int axes)
{
  FswThrMapConfig c = base_cfg();
  if (axes < 3) set3(c.control_axes_B[2], 0, 0, 0);
  c.num_thr = 4;
  const double xy[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  for (int i = 0; i < 4; i++) {
    set3(c.r_thr_B[i], xy[i][0], xy[i][1], 0);
    set3(c.gt_hat_B[i], 0, 0, 1);
    c.F_max[i] = 1;
  }
  c.thr_force_sign = -1;
  return c;
}

struct MapRun {
  FswThrMapState st;
  FswThrMapOut out;
  FswStatus s;
};

MapRun map_once(const FswThrMapConfig& c, double lx, double ly, double lz,
             double cx = 0, double cy = 0, double cz = 0)
{
  MapRun r;
  EXPECT_EQ(FSW_OK, fsw_thr_map_init(&r.st, &c));
  FswThrMapIn in{};
  set3(in.Lr_B, lx, ly, lz);
  set3(in.r_CoM_B, cx, cy, cz);
  r.s = fsw_thr_map_update(&r.st, &c, &in, &r.out);
  return r;
}

void expect_forces(const FswThrMapOut& o, std::initializer_list<double> want)
{
  int i = 0;
  for (double w : want) {
    EXPECT_NEAR(w, o.F[i], kTol * (1 + std::fabs(w))) << "thruster " << i;
    i++;
  }
  for (; i < FSW_MAX_THR; i++) EXPECT_EQ(0, o.F[i]) << "unused entry " << i;
}

// body torque [D]F of the output, with the CoM given
void body_torque(const FswThrMapConfig& c, const R* F, const double com[3], double out[3])
{
  out[0] = out[1] = out[2] = 0;
  for (int i = 0; i < c.num_thr; i++) {
    double r[3] = {c.r_thr_B[i][0] - com[0], c.r_thr_B[i][1] - com[1], c.r_thr_B[i][2] - com[2]};
    const R* g = c.gt_hat_B[i];
    double d[3] = {r[1] * g[2] - r[2] * g[1], r[2] * g[0] - r[0] * g[2], r[0] * g[1] - r[1] * g[0]};
    for (int k = 0; k < 3; k++) out[k] += d[k] * F[i];
  }
}

// --- config rejection -------------------------------------------------------

struct BadCfg {
  const char* why;
  void (*spoil)(FswThrMapConfig*);
  FswStatus want;
};

const BadCfg kBadConfigs[] = {
    {"zero thrusters", [](FswThrMapConfig* c) { c->num_thr = 0; }, FSW_E_CONFIG},
    {"negative count", [](FswThrMapConfig* c) { c->num_thr = -3; }, FSW_E_CONFIG},
    {"more than FSW_MAX_THR", [](FswThrMapConfig* c) { c->num_thr = FSW_MAX_THR + 1; }, FSW_E_CAPACITY},
    {"force sign 0", [](FswThrMapConfig* c) { c->thr_force_sign = 0; }, FSW_E_CONFIG},
    {"force sign 2", [](FswThrMapConfig* c) { c->thr_force_sign = 2; }, FSW_E_CONFIG},
    {"F_max zero", [](FswThrMapConfig* c) { c->F_max[2] = 0; }, FSW_E_CONFIG},
    {"F_max negative", [](FswThrMapConfig* c) { c->F_max[5] = -1; }, FSW_E_CONFIG},
    {"F_max NaN", [](FswThrMapConfig* c) { c->F_max[0] = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"location Inf", [](FswThrMapConfig* c) { c->r_thr_B[1][2] = std::numeric_limits<R>::infinity(); }, FSW_E_CONFIG},
    {"direction not unit", [](FswThrMapConfig* c) { set3(c->gt_hat_B[3], 2, 0, 0); }, FSW_E_CONFIG},
    {"direction zero", [](FswThrMapConfig* c) { set3(c->gt_hat_B[3], 0, 0, 0); }, FSW_E_CONFIG},
    {"no control axis", [](FswThrMapConfig* c) { std::memset(c->control_axes_B, 0, sizeof c->control_axes_B); }, FSW_E_CONFIG},
    {"control axis too short to normalise (1/|row| overflows)", [](FswThrMapConfig* c) {
       const R t = std::numeric_limits<R>::denorm_min();
       c->epsilon = 0;
       set3(c->control_axes_B[0], t, t, t); }, FSW_E_CONFIG},
    {"control axis NaN", [](FswThrMapConfig* c) { c->control_axes_B[1][0] = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"dependent control axes", [](FswThrMapConfig* c) { set3(c->control_axes_B[2], 1, 1, 0); }, FSW_E_SINGULAR},
    {"repeated control axis", [](FswThrMapConfig* c) { set3(c->control_axes_B[1], 2, 0, 0); }, FSW_E_SINGULAR},
    {"negative epsilon", [](FswThrMapConfig* c) { c->epsilon = -1e-3f; }, FSW_E_CONFIG},
    // issue 21: the NaN clause of each finite check
    {"epsilon NaN", [](FswThrMapConfig* c) { c->epsilon = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"direction NaN", [](FswThrMapConfig* c) { c->gt_hat_B[1][1] = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"negative angle threshold", [](FswThrMapConfig* c) { c->ang_err_thresh = -0.1f; }, FSW_E_CONFIG},
    {"angle threshold NaN", [](FswThrMapConfig* c) { c->ang_err_thresh = std::numeric_limits<R>::quiet_NaN(); }, FSW_E_CONFIG},
    {"use_2nd_loop 2", [](FswThrMapConfig* c) { c->use_2nd_loop = 2; }, FSW_E_CONFIG},
    {"unknown mode", [](FswThrMapConfig* c) { c->mode = 7; }, FSW_E_CONFIG},
    // issue 13: physical ranges, so that accepted configs cannot overflow
    {"location beyond FSW_THR_MAP_R_MAX", [](FswThrMapConfig* c) { set3(c->r_thr_B[0], 0, 1.5e30, -1.5e30); }, FSW_E_CONFIG},
    {"F_max beyond FSW_THR_MAP_F_MAX", [](FswThrMapConfig* c) { c->F_max[4] = static_cast<R>(1e30); }, FSW_E_CONFIG},
    {"control axis beyond FSW_THR_MAP_AXIS_MAX", [](FswThrMapConfig* c) { set3(c->control_axes_B[0], 1e30, 0, 0); }, FSW_E_CONFIG},
};

// Verifies: REQ-THRMAP-001
TEST(ThrMap, ConfigRejectionTable)
{
  {
    FswThrMapConfig good = six_axis_cfg();
    ASSERT_EQ(FSW_OK, fsw_thr_map_check(&good));
  }
  for (const BadCfg& row : kBadConfigs) {
    FswThrMapConfig c = six_axis_cfg();
    row.spoil(&c);
    EXPECT_EQ(row.want, fsw_thr_map_check(&c)) << row.why;
    FswThrMapState st;
    std::memset(&st, 0x5a, sizeof st);
    EXPECT_EQ(row.want, fsw_thr_map_init(&st, &c)) << row.why;
    EXPECT_EQ(0, st.ready) << row.why;
    // a refused state only ever gives the safe output
    FswThrMapIn in{};
    set3(in.Lr_B, 1, 2, 3);
    set3(in.r_CoM_B, 0, 0, 0);
    FswThrMapOut out;
    for (R& f : out.F) f = 9;
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_thr_map_update(&st, &c, &in, &out)) << row.why;
    for (R f : out.F) EXPECT_EQ(0, f) << row.why;
  }
}

// Verifies: REQ-THRMAP-002
TEST(ThrMap, AxesCountedUpToFirstShortRowAndNormalised)
{
  FswThrMapConfig c = six_axis_cfg();
  set3(c.control_axes_B[0], 0, 0, 4);    // normalised to +z
  set3(c.control_axes_B[1], 0, 0, 0);    // stops the count
  set3(c.control_axes_B[2], 1, 0, 0);    // ignored
  FswThrMapState st;
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  EXPECT_EQ(1, st.num_axes);
  EXPECT_EQ(1, st.C[0][2]);
  // epsilon is the counting threshold: a row of norm 1e-3 counts only if > eps
  c = six_axis_cfg();
  set3(c.control_axes_B[2], 0, 0, 1e-3);
  c.epsilon = static_cast<R>(5e-4);
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  EXPECT_EQ(3, st.num_axes);
  c.epsilon = static_cast<R>(2e-3);
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  EXPECT_EQ(2, st.num_axes);
}

// --- nominal cases, min-norm mode (hand calculations) ------------------------

// Verifies: REQ-THRMAP-003
TEST(ThrMap, SixThrusterMinNormAndShift)
{
  // D = [e_x, -e_x, e_y, -e_y, e_z, -e_z], D D^T = 2 I, so the first pass is
  // F = D^T L / 2 = (0.5, -0.5, -0.25, 0.25, 0.125, -0.125) for
  // L = (1, -0.5, 0.25); the shift adds 0.5 (pure couples: 1 in null(D)).
  MapRun r = map_once(six_axis_cfg(), 1, -0.5, 0.25);
  EXPECT_EQ(FSW_OK, r.s);
  expect_forces(r.out, {1.0, 0.0, 0.25, 0.75, 0.625, 0.375});
  EXPECT_EQ(0, r.st.ang_err);  // below the round-off floor of 8.5
}

// Verifies: REQ-THRMAP-003
TEST(ThrMap, SecondPassShiftAddsTorqueWhenNotPureCouples)
{
  // use_2nd_loop: S = {F_i > 0} = {0,2,3,4,5}; D_S D_S^T = diag(1,2,2),
  // Fbar = (1, -0.25, 0.25, 0.125, -0.125), shifted by +0.25:
  // (1.25, 0.5, 0.375, 0.125) on {0,3,4,5} and 0 on thrusters 1, 2.
  // Thruster 0 has no partner in S, so the shift adds 0.25 N*m about x:
  // the Basilisk weakness of docs/fsw/thr_map.md "Differences from Basilisk", kept for parity.
  FswThrMapConfig c = six_axis_cfg();
  c.use_2nd_loop = 1;
  MapRun r = map_once(c, 1, -0.5, 0.25);
  EXPECT_EQ(FSW_OK, r.s);
  expect_forces(r.out, {1.25, 0.0, 0.0, 0.5, 0.375, 0.125});
}

// Verifies: REQ-THRMAP-004
TEST(ThrMap, SaturationScalingKeepsDirection)
{
  // L = (4, 2, 0): first pass (2,-2,1,-1,0,0), shift +2 -> (4,0,3,1,2,2).
  // Saturated torque: sat(F) = (1,0,1,1,1,1) -> tau = (1, 0, 0); angle to
  // (4,2,0) is atan(0.5) = 0.4636 rad > 0, max |F|/F_max = 4 -> F / 4.
  MapRun r = map_once(six_axis_cfg(), 4, 2, 0);
  EXPECT_EQ(FSW_W_SAT, r.s);
  expect_forces(r.out, {1.0, 0.0, 0.75, 0.25, 0.5, 0.5});
  EXPECT_EQ(1u, r.st.health.saturated);
  EXPECT_NEAR(0.0, r.st.ang_err, kt::tol(1e-12, 1e-3));

  // Threshold above atan(0.5): no scaling, forces above F_max pass through.
  FswThrMapConfig c = six_axis_cfg();
  c.ang_err_thresh = static_cast<R>(0.5);
  r = map_once(c, 4, 2, 0);
  EXPECT_EQ(FSW_OK, r.s);
  expect_forces(r.out, {4.0, 0.0, 3.0, 1.0, 2.0, 2.0});
  EXPECT_NEAR(std::atan(0.5), r.st.ang_err, kt::tol(1e-12, 1e-5));
}

// Verifies: REQ-THRMAP-004
TEST(ThrMap, SaturatedButParallelIsNotScaled)
{
  // L = (4,0,0): F = (4,0,2,2,2,2); the saturated torque (1,0,0) is parallel
  // to L, so the angle is 0 and nothing is scaled (the pulser clips).
  MapRun r = map_once(six_axis_cfg(), 4, 0, 0);
  EXPECT_EQ(FSW_OK, r.s);
  expect_forces(r.out, {4.0, 0.0, 2.0, 2.0, 2.0, 2.0});
}

// Verifies: REQ-THRMAP-003
TEST(ThrMap, OffPulsingDvTwoAxes)
{
  // d = (1,-1,0), (1,1,0), (-1,1,0), (-1,-1,0); sum of F_max d = 0 so the
  // all-on offset is 0.  Lbar = (0.4, 0); [C][D][C][D]^T = 4 I:
  // first pass F = 0.1 (1, 1, -1, -1).  Second pass over S = {F_i < 0} =
  // {2, 3}: M = 2 I, Fbar = (-0.2, -0.2).  Throttling 2 and 3 by 0.2 N each
  // removes -0.2 (d2 + d3) = (0.4, 0, 0) from the all-on torque.
  MapRun r = map_once(dv_cfg(2), 0.4, 0, 0);
  EXPECT_EQ(FSW_OK, r.s);
  expect_forces(r.out, {0.0, 0.0, -0.2, -0.2});
}

// Verifies: REQ-THRMAP-003
TEST(ThrMap, OffPulsingOffsetRemovesAllOnTorque)
{
  // Thruster 0 stronger (F_max 2): the all-on torque is 1*d0 = (1,-1,0), so
  // Lbar = Lr - (1,-1,0) = (-1, 1) for Lr = 0.  First pass:
  // F = [C][D]^T Lbar / 4 = (-0.5, 0, 0.5, 0); S = {0}: one column for two
  // axes is rank deficient -> F = 0 and a singular warning.
  FswThrMapConfig c = dv_cfg(2);
  c.F_max[0] = 2;
  MapRun r = map_once(c, 0, 0, 0);
  EXPECT_EQ(FSW_W_SINGULAR, r.s);
  expect_forces(r.out, {0, 0, 0, 0});
  EXPECT_EQ(1u, r.st.health.singular);
}

// Verifies: REQ-THRMAP-005
TEST(ThrMap, RankDeficientGeometryGivesZeroAndWarning)
{
  // DV thrusters all along z give no torque about z: 3 control axes are
  // rank deficient.
  MapRun r = map_once(dv_cfg(3), 0.4, 0.1, 0.2);
  EXPECT_EQ(FSW_W_SINGULAR, r.s);
  expect_forces(r.out, {0, 0, 0, 0});
}

// Verifies: REQ-THRMAP-009
TEST(ThrMap, ZeroRequestGivesZeroForces)
{
  for (int mode : {FSW_THR_MAP_MIN_NORM, FSW_THR_MAP_NNLS}) {
    for (int second : {0, 1}) {
      FswThrMapConfig c = six_axis_cfg();
      c.mode = mode;
      c.use_2nd_loop = second;
      MapRun r = map_once(c, 0, 0, 0, 0.1, -0.2, 0.05);
      EXPECT_EQ(FSW_OK, r.s);
      expect_forces(r.out, {0, 0, 0, 0, 0, 0});
    }
  }
}

// Verifies: REQ-THRMAP-005
TEST(ThrMap, ScalingGeometryDoesNotChangeSingularity)
{
  // Basilisk tests det([C][D][C][D]^T) > eps with eps in m^6: a 1 mm-scale
  // spacecraft would be "singular".  K1's test is scale invariant: scaling
  // every location and the request by k leaves F unchanged and never
  // changes the decision.
  MapRun ref = map_once(six_axis_cfg(), 1, -0.5, 0.25);
  for (double k : {1e-4, 1e-3, 0.1, 10.0, 1e3}) {
    FswThrMapConfig c = six_axis_cfg();
    c.epsilon = static_cast<R>(5e-4);
    for (int i = 0; i < c.num_thr; i++)
      for (int j = 0; j < 3; j++) c.r_thr_B[i][j] = static_cast<R>(c.r_thr_B[i][j] * k);
    MapRun r = map_once(c, 1 * k, -0.5 * k, 0.25 * k);
    EXPECT_EQ(FSW_OK, r.s) << "scale " << k;
    for (int i = 0; i < 6; i++) EXPECT_NEAR(ref.out.F[i], r.out.F[i], kTol * 4) << "scale " << k;

    FswThrMapConfig d = dv_cfg(3);  // rank deficient at every scale
    for (int i = 0; i < d.num_thr; i++)
      for (int j = 0; j < 3; j++) d.r_thr_B[i][j] = static_cast<R>(d.r_thr_B[i][j] * k);
    EXPECT_EQ(FSW_W_SINGULAR, map_once(d, 0.4 * k, 0.1 * k, 0).s) << "scale " << k;
  }
}

// --- bad input, repeatability ----------------------------------------------

// Verifies: REQ-THRMAP-008
TEST(ThrMap, BadInputGivesSafeOutputAndCounts)
{
  FswThrMapConfig c = six_axis_cfg();
  FswThrMapState st;
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  const R nan = std::numeric_limits<R>::quiet_NaN();
  const R inf = std::numeric_limits<R>::infinity();
  FswThrMapIn ins[3]{};
  for (FswThrMapIn& in : ins) {
    set3(in.Lr_B, 1, 0, 0);
    set3(in.r_CoM_B, 0, 0, 0);
  }
  ins[0].Lr_B[1] = nan;
  ins[1].r_CoM_B[2] = inf;
  ins[2].Lr_B[0] = -inf;
  uint32_t n = 0;
  for (const FswThrMapIn& in : ins) {
    FswThrMapOut out;
    for (R& f : out.F) f = 3;
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_thr_map_update(&st, &c, &in, &out));
    for (R f : out.F) EXPECT_EQ(0, f);
    EXPECT_EQ(++n, st.health.bad_input);
    EXPECT_EQ(FSW_E_BAD_INPUT, st.health.last);
  }
  // NULL pointers: the assert hook fires and the call returns FSW_E_NULL_ARG
  kestrel_assert_reset();
  FswThrMapOut out;
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_thr_map_update(&st, &c, nullptr, &out));
  EXPECT_EQ(1u, kestrel_assert_count());
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_thr_map_init(nullptr, &c));
  EXPECT_EQ(2u, kestrel_assert_count());
  kestrel_assert_reset();
}

// Verifies: REQ-THRMAP-009
TEST(ThrMap, RepeatableAfterReset)
{
  for (int mode : {FSW_THR_MAP_MIN_NORM, FSW_THR_MAP_NNLS}) {
    FswThrMapConfig c = six_axis_cfg();
    c.mode = mode;
    FswThrMapState st;
    ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
    kt::Rng rng(11);
    FswThrMapIn in[5]{};
    FswThrMapOut first[5], again;
    for (int k = 0; k < 5; k++) {
      for (int j = 0; j < 3; j++) {
        in[k].Lr_B[j] = static_cast<R>(rng.uniform(-1.5, 1.5));
        in[k].r_CoM_B[j] = static_cast<R>(rng.uniform(-0.1, 0.1));
      }
      fsw_thr_map_update(&st, &c, &in[k], &first[k]);
    }
    fsw_thr_map_reset(&st);
    for (int k = 0; k < 5; k++) {
      fsw_thr_map_update(&st, &c, &in[k], &again);
      EXPECT_EQ(0, std::memcmp(&first[k], &again, sizeof again)) << "mode " << mode << " step " << k;
    }
  }
}

// --- independent re-implementation of the min-norm mode ---------------------

// Solve (A A^T) y = b for m <= 3 by explicit inverses (adjugate), then
// x = A^T y.  Returns false when the Gram matrix is (relatively) singular.
bool ref_minnorm(const double A[3][64], const double* b, int m, int n, double* x)
{
  for (int i = 0; i < n; i++) x[i] = 0;
  if (n < m) return false;
  double M[3][3] = {};
  for (int i = 0; i < m; i++)
    for (int j = 0; j < m; j++)
      for (int k = 0; k < n; k++) M[i][j] += A[i][k] * A[j][k];
  double dmax = 0;
  for (int i = 0; i < m; i++) dmax = std::fmax(dmax, M[i][i]);
  if (dmax == 0) return false;
  double y[3] = {};
  if (m == 1) {
    y[0] = b[0] / M[0][0];
  } else if (m == 2) {
    double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    if (det <= 1e-9 * dmax * dmax) return false;
    y[0] = (M[1][1] * b[0] - M[0][1] * b[1]) / det;
    y[1] = (-M[1][0] * b[0] + M[0][0] * b[1]) / det;
  } else {
    double C[3][3];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        C[i][j] = M[i1][j1] * M[i2][j2] - M[i1][j2] * M[i2][j1];  // adjugate
      }
    double det = M[0][0] * C[0][0] + M[0][1] * C[1][0] + M[0][2] * C[2][0];
    if (det <= 1e-9 * dmax * dmax * dmax) return false;
    for (int i = 0; i < 3; i++) y[i] = (C[i][0] * b[0] + C[i][1] * b[1] + C[i][2] * b[2]) / det;
  }
  for (int k = 0; k < n; k++)
    for (int i = 0; i < m; i++) x[k] += A[i][k] * y[i];
  return true;
}

// docs/fsw/thr_map.md (min-norm mode) written out directly in double.
void ref_map(const FswThrMapConfig& c, const double Lr_in[3], const double com[3], double* F)
{
  const int n = c.num_thr, sF = c.thr_force_sign;
  double C[3][3];
  int nc = 0;
  for (int j = 0; j < 3; j++) {
    double a[3] = {c.control_axes_B[j][0], c.control_axes_B[j][1], c.control_axes_B[j][2]};
    double nn = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(nn > c.epsilon)) break;
    for (int k = 0; k < 3; k++) C[j][k] = a[k] / nn;
    nc++;
  }
  double D[3][64], CD[3][64], Lr[3] = {Lr_in[0], Lr_in[1], Lr_in[2]};
  for (int i = 0; i < n; i++) {
    double r[3] = {c.r_thr_B[i][0] - com[0], c.r_thr_B[i][1] - com[1], c.r_thr_B[i][2] - com[2]};
    const R* g = c.gt_hat_B[i];
    D[0][i] = r[1] * g[2] - r[2] * g[1];
    D[1][i] = r[2] * g[0] - r[0] * g[2];
    D[2][i] = r[0] * g[1] - r[1] * g[0];
    if (sF < 0)
      for (int k = 0; k < 3; k++) Lr[k] -= c.F_max[i] * D[k][i];
  }
  double Lbar[3] = {};
  for (int j = 0; j < nc; j++) {
    for (int k = 0; k < 3; k++) Lbar[j] += C[j][k] * Lr[k];
    for (int i = 0; i < n; i++) CD[j][i] = C[j][0] * D[0][i] + C[j][1] * D[1][i] + C[j][2] * D[2][i];
  }
  auto shift = [](double* x, int len) {
    double mn = 0;
    for (int i = 0; i < len; i++) mn = std::fmin(mn, x[i]);
    for (int i = 0; i < len; i++) x[i] -= mn;
  };
  ref_minnorm(CD, Lbar, nc, n, F);
  if (sF > 0) shift(F, n);
  if (sF < 0 || c.use_2nd_loop) {
    double CDs[3][64], Fb[64];
    int idx[64], ns = 0;
    for (int i = 0; i < n; i++)
      if (sF * F[i] > 0) {
        for (int j = 0; j < nc; j++) CDs[j][ns] = CD[j][i];
        idx[ns++] = i;
      }
    ref_minnorm(CDs, Lbar, nc, ns, Fb);
    if (sF > 0) shift(Fb, ns);
    for (int i = 0; i < n; i++) F[i] = 0;
    for (int s = 0; s < ns; s++) F[idx[s]] = Fb[s];
  }
  // saturation scaling: angle between C^T Lbar and the saturated torque
  double ln = std::sqrt(Lbar[0] * Lbar[0] + Lbar[1] * Lbar[1] + Lbar[2] * Lbar[2]);
  if (ln > c.epsilon) {
    double Lb[3] = {}, tau[3] = {};
    for (int j = 0; j < nc; j++)
      for (int k = 0; k < 3; k++) Lb[k] += Lbar[j] * C[j][k];
    for (int i = 0; i < n; i++) {
      double f = std::fabs(F[i]) < c.F_max[i] ? F[i] : std::copysign(double(c.F_max[i]), F[i]);
      for (int k = 0; k < 3; k++) tau[k] += f * D[k][i];
    }
    double nl = std::sqrt(Lb[0] * Lb[0] + Lb[1] * Lb[1] + Lb[2] * Lb[2]);
    double nt = std::sqrt(tau[0] * tau[0] + tau[1] * tau[1] + tau[2] * tau[2]);
    double cth = (nl > 0 && nt > 0) ? (Lb[0] * tau[0] + Lb[1] * tau[1] + Lb[2] * tau[2]) / (nl * nt) : 0;
    double th = cth < 1 ? std::acos(std::fmax(-1.0, cth)) : 0;
    if (th < 1e-6) th = 0;
    if (th > c.ang_err_thresh) {
      double s = 0;
      for (int i = 0; i < n; i++) s = std::fmax(s, std::fabs(F[i]) / c.F_max[i]);
      if (s > 1)
        for (int i = 0; i < n; i++) F[i] /= s;
    }
  }
}

void random_geometry(kt::Rng& rng, FswThrMapConfig* c, int n)
{
  c->num_thr = n;
  for (int i = 0; i < n; i++) {
    double g[3];
    rng.unit3(g);
    set3(c->gt_hat_B[i], g[0], g[1], g[2]);
    set3(c->r_thr_B[i], rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
    c->F_max[i] = static_cast<R>(rng.uniform(0.5, 2.0));
  }
}

// nc random, well-separated axes (Gram determinant >= 0.05), not unit
// length: init normalises them.
void random_axes(kt::Rng& rng, FswThrMapConfig* c, int nc)
{
  double a[3][3], det;
  do {
    for (int j = 0; j < 3; j++) rng.unit3(a[j]);
    double g[3][3];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) g[i][j] = a[i][0] * a[j][0] + a[i][1] * a[j][1] + a[i][2] * a[j][2];
    det = nc == 1 ? 1.0
          : nc == 2 ? g[0][0] * g[1][1] - g[0][1] * g[1][0]
                    : g[0][0] * (g[1][1] * g[2][2] - g[1][2] * g[2][1]) -
                          g[0][1] * (g[1][0] * g[2][2] - g[1][2] * g[2][0]) +
                          g[0][2] * (g[1][0] * g[2][1] - g[1][1] * g[2][0]);
  } while (det < 0.05);
  std::memset(c->control_axes_B, 0, sizeof c->control_axes_B);
  for (int j = 0; j < nc; j++) set3(c->control_axes_B[j], a[j][0] * 2, a[j][1] * 2, a[j][2] * 2);
}

// Verifies: REQ-THRMAP-003
TEST(ThrMap, MinNormMatchesIndependentImplementation)
{
  kt::Rng rng(2024);
  int compared = 0;
  for (int trial = 0; trial < 300; trial++) {
    FswThrMapConfig c = base_cfg();
    const int n = rng.uniform_int(3, 12);
    random_geometry(rng, &c, n);
    random_axes(rng, &c, rng.uniform_int(1, 3));
    c.thr_force_sign = rng.uniform_int(0, 3) == 0 ? -1 : 1;
    c.use_2nd_loop = rng.uniform_int(0, 1);
    c.ang_err_thresh = static_cast<R>(rng.uniform_int(0, 1) ? 0.0 : 0.3);
    double Lr[3], com[3];
    for (int k = 0; k < 3; k++) {
      Lr[k] = rng.uniform(-2, 2);
      com[k] = rng.uniform(-0.2, 0.2);
    }
    MapRun r = map_once(c, Lr[0], Lr[1], Lr[2], com[0], com[1], com[2]);
    double F[64];
    ref_map(c, Lr, com, F);
    double scale = 1;
    for (int i = 0; i < n; i++) scale = std::fmax(scale, std::fabs(F[i]));
    for (int i = 0; i < n; i++)
      EXPECT_NEAR(F[i], r.out.F[i], kt::tol(1e-9, 2e-3) * scale) << "trial " << trial << " thr " << i;
    for (int i = n; i < FSW_MAX_THR; i++) EXPECT_EQ(0, r.out.F[i]);
    compared++;
  }
  EXPECT_EQ(300, compared);
}

// --- exact bounded mode (8.6) ------------------------------------------------

// Verifies: REQ-THRMAP-006
TEST(ThrMapNnls, SixThrusterFiresOneOfEachPair)
{
  // The minimum-norm non-negative solution of D F = (1,-0.5,0.25) with
  // D = [+-e_x, +-e_y, +-e_z] fires one thruster of each pair.
  FswThrMapConfig c = six_axis_cfg();
  c.mode = FSW_THR_MAP_NNLS;
  MapRun r = map_once(c, 1, -0.5, 0.25);
  EXPECT_EQ(FSW_OK, r.s);
  expect_forces(r.out, {1.0, 0.0, 0.0, 0.5, 0.25, 0.0});
}

// Verifies: REQ-THRMAP-006
TEST(ThrMapNnls, OutOfReachGivesLeastSquaresAndWarning)
{
  // 1 axis (z), F_max = 1: L = (0,0,3) can only be met up to 1 N*m by
  // thruster 4 alone; L = (0.5, 0, 3) on 3 axes: x met exactly, z capped.
  FswThrMapConfig c = six_axis_cfg();
  c.mode = FSW_THR_MAP_NNLS;
  MapRun r = map_once(c, 0.5, 0, 3);
  EXPECT_EQ(FSW_W_SAT, r.s);
  expect_forces(r.out, {0.5, 0.0, 0.0, 0.0, 1.0, 0.0});
  EXPECT_EQ(1u, r.st.health.saturated);
}

// Verifies: REQ-THRMAP-006
TEST(ThrMapNnls, CoMOffsetDefaultModeErrsExactModeDelivers)
{
  // With a CoM offset the six thrusters are no longer pure couples
  // (sum d_i = -c x (2,2,2) != 0): the default min-shift adds torque
  // (docs/fsw/thr_map.md, "Differences from Basilisk"); the exact mode delivers the request.
  const double com[3] = {0.1, -0.05, 0.08};
  const double L[3] = {0.3, -0.2, 0.1};
  FswThrMapConfig c = six_axis_cfg();
  MapRun def = map_once(c, L[0], L[1], L[2], com[0], com[1], com[2]);
  c.mode = FSW_THR_MAP_NNLS;
  MapRun ex = map_once(c, L[0], L[1], L[2], com[0], com[1], com[2]);
  EXPECT_EQ(FSW_OK, ex.s);
  double td[3], te[3];
  body_torque(c, def.out.F, com, td);
  body_torque(c, ex.out.F, com, te);
  double err_def = 0, err_ex = 0;
  for (int k = 0; k < 3; k++) {
    err_def = std::fmax(err_def, std::fabs(td[k] - L[k]));
    err_ex = std::fmax(err_ex, std::fabs(te[k] - L[k]));
  }
  EXPECT_GT(err_def, 1e-2);
  EXPECT_LT(err_ex, kt::tol(1e-12, 1e-5));
}

// KKT check of min |F|^2 s.t. A F = b, lo <= F <= hi: with the free set
// Phi = {lo < F < hi}, F_Phi = A_Phi^T lam for some lam, and a_i^T lam <= lo
// at the lower bound, >= hi at the upper bound.
void expect_kkt(const double A[3][64], int m, int n, const R* F, const double* lo,
                const double* hi, double ftol, const char* what)
{
  double M[3][3] = {}, rhs[3] = {};
  bool fr[64];
  for (int i = 0; i < n; i++) fr[i] = F[i] > lo[i] + ftol && F[i] < hi[i] - ftol;
  for (int j = 0; j < m; j++) {
    for (int k = 0; k < m; k++)
      for (int i = 0; i < n; i++)
        if (fr[i]) M[j][k] += A[j][i] * A[k][i];
    for (int i = 0; i < n; i++)
      if (fr[i]) rhs[j] += A[j][i] * F[i];
  }
  int nfree = 0;
  for (int i = 0; i < n; i++) nfree += fr[i] ? 1 : 0;
  if (nfree < m) return;  // degenerate: lam not unique, see the brute-force test
  // regularised normal equations, Gaussian elimination (tiny m)
  for (int j = 0; j < m; j++) M[j][j] += 1e-14 * (1 + M[j][j]);
  double lam[3] = {};
  for (int p = 0; p < m; p++)
    for (int q = p + 1; q < m; q++) {
      double f = M[q][p] / M[p][p];
      for (int k = p; k < m; k++) M[q][k] -= f * M[p][k];
      rhs[q] -= f * rhs[p];
    }
  for (int p = m - 1; p >= 0; p--) {
    double v = rhs[p];
    for (int k = p + 1; k < m; k++) v -= M[p][k] * lam[k];
    lam[p] = v / M[p][p];
  }
  for (int i = 0; i < n; i++) {
    double g = 0;
    for (int j = 0; j < m; j++) g += A[j][i] * lam[j];
    if (fr[i])
      EXPECT_NEAR(g, F[i], 50 * ftol) << what << " free thruster " << i;
    else if (F[i] <= lo[i] + ftol)
      EXPECT_LE(g, lo[i] + 50 * ftol) << what << " thruster at lower bound " << i;
    else
      EXPECT_GE(g, hi[i] - 50 * ftol) << what << " thruster at upper bound " << i;
  }
}

// Verifies: REQ-THRMAP-006
TEST(ThrMapNnls, DeliversEveryReachableRequestWithinLimits)
{
  // Property: whenever some F in [0, F_max] gives the request (built here as
  // D F0 for a random admissible F0), the exact mode delivers it on the
  // controlled axes, keeps 0 <= F <= F_max and is KKT-optimal (min |F|).
  kt::Rng rng(77);
  const double torque_tol = kt::tol(1e-9, 2e-3);
  double max_ratio = 0;
  for (int trial = 0; trial < 200; trial++) {
    FswThrMapConfig c = base_cfg();
    const int n = rng.uniform_int(4, FSW_MAX_THR < 36 ? FSW_MAX_THR : 36);
    random_geometry(rng, &c, n);
    const int nc = rng.uniform_int(1, 3);
    random_axes(rng, &c, nc);
    c.mode = FSW_THR_MAP_NNLS;
    c.thr_force_sign = (trial % 4 == 3) ? -1 : 1;
    double com[3] = {rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)};
    // a reachable request: actual forces F0 in [0, F_max] (some exactly 0)
    R F0[FSW_MAX_THR] = {};
    for (int i = 0; i < n; i++)
      F0[i] = rng.uniform_int(0, 3) == 0 ? 0 : static_cast<R>(rng.uniform(0, c.F_max[i]));
    double L[3];
    body_torque(c, F0, com, L);
    MapRun r = map_once(c, L[0], L[1], L[2], com[0], com[1], com[2]);
    ASSERT_EQ(FSW_OK, r.s) << "trial " << trial;
    EXPECT_LT(r.st.nnls_iter, 3 * n) << "converged within the budget";
    max_ratio = std::fmax(max_ratio, double(r.st.nnls_iter) / n);
    // actual thruster forces: on-pulsing F, off-pulsing F_max + F
    R act[FSW_MAX_THR] = {};
    for (int i = 0; i < n; i++) {
      act[i] = c.thr_force_sign > 0 ? r.out.F[i] : c.F_max[i] + r.out.F[i];
      EXPECT_GE(act[i], 0) << "trial " << trial;
      EXPECT_LE(act[i], c.F_max[i]) << "trial " << trial;
    }
    for (int i = n; i < FSW_MAX_THR; i++) EXPECT_EQ(0, r.out.F[i]);
    double T[3];
    body_torque(c, act, com, T);
    double lnorm = std::sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
    for (int j = 0; j < r.st.num_axes; j++) {
      double want = 0, got = 0;
      for (int k = 0; k < 3; k++) {
        want += r.st.C[j][k] * L[k];
        got += r.st.C[j][k] * T[k];
      }
      EXPECT_NEAR(want, got, torque_tol * (1 + lnorm)) << "trial " << trial << " axis " << j;
    }
    // optimality of the output F (deviation variable in off-pulsing)
    double A[3][64], lo[64], hi[64];
    for (int j = 0; j < r.st.num_axes; j++)
      for (int i = 0; i < n; i++) A[j][i] = r.st.work.CD[j][i];
    for (int i = 0; i < n; i++) {
      lo[i] = c.thr_force_sign > 0 ? 0 : -double(c.F_max[i]);
      hi[i] = c.thr_force_sign > 0 ? double(c.F_max[i]) : 0;
    }
    if (!kt::kFloat) {
      SCOPED_TRACE(testing::Message() << "trial " << trial << " iter " << r.st.nnls_iter << " n " << n << " nc " << r.st.num_axes << " sign " << c.thr_force_sign);
      expect_kkt(A, r.st.num_axes, n, r.out.F, lo, hi, 1e-9, "kkt");
    }
  }
  RecordProperty("max_iterations_per_thruster", std::to_string(max_ratio));
  std::printf("max NNLS iterations / thruster: %.2f\n", max_ratio);
}

// Verifies: REQ-THRMAP-006
TEST(ThrMapNnls, UnreachableRequestsStayWithinLimits)
{
  kt::Rng rng(5);
  for (int trial = 0; trial < 100; trial++) {
    FswThrMapConfig c = base_cfg();
    const int n = rng.uniform_int(2, 10);
    random_geometry(rng, &c, n);
    random_axes(rng, &c, rng.uniform_int(1, 3));
    c.mode = FSW_THR_MAP_NNLS;
    c.thr_force_sign = (trial % 3 == 2) ? -1 : 1;
    double L[3];
    rng.unit3(L);
    MapRun r = map_once(c, 50 * L[0], 50 * L[1], 50 * L[2]);
    EXPECT_TRUE(r.s == FSW_W_SAT || r.s == FSW_OK) << fsw_status_name(r.s);
    for (int i = 0; i < n; i++) {
      double act = c.thr_force_sign > 0 ? r.out.F[i] : c.F_max[i] + r.out.F[i];
      EXPECT_GE(act, 0);
      EXPECT_LE(act, c.F_max[i]);
    }
  }
}

// Brute force over every bound pattern (each thruster at its lower bound, at
// its upper bound or free; 3^n patterns): the best admissible minimum-norm
// candidate.  The library's result must be admissible and no larger.
// Verifies: REQ-THRMAP-006
TEST(ThrMapNnls, MinimumNormAgainstBruteForce)
{
  kt::Rng rng(31);
  for (int trial = 0; trial < 40; trial++) {
    FswThrMapConfig c = base_cfg();
    const int n = rng.uniform_int(3, 6);
    random_geometry(rng, &c, n);
    const int nc = rng.uniform_int(1, 3);
    random_axes(rng, &c, nc);
    c.mode = FSW_THR_MAP_NNLS;
    R F0[FSW_MAX_THR] = {};
    for (int i = 0; i < n; i++) F0[i] = static_cast<R>(rng.uniform(0, c.F_max[i]));
    const double com[3] = {0, 0, 0};
    double L[3];
    body_torque(c, F0, com, L);
    MapRun r = map_once(c, L[0], L[1], L[2]);
    ASSERT_EQ(FSW_OK, r.s);
    const int m = r.st.num_axes;
    double A[3][64], b[3] = {};
    for (int j = 0; j < m; j++) {
      for (int i = 0; i < n; i++) A[j][i] = r.st.work.CD[j][i];
      for (int k = 0; k < 3; k++) b[j] += r.st.C[j][k] * L[k];
    }
    double best = 1e300;
    int patterns = 1;
    for (int i = 0; i < n; i++) patterns *= 3;
    for (int p = 0; p < patterns; p++) {
      int code = p, idx[64], nf = 0;
      double F[64], rhs[3] = {b[0], b[1], b[2]}, As[3][64];
      for (int i = 0; i < n; i++, code /= 3) {
        if (code % 3 == 2) { idx[nf++] = i; continue; }
        F[i] = code % 3 == 0 ? 0.0 : double(c.F_max[i]);
        for (int j = 0; j < m; j++) rhs[j] -= A[j][i] * F[i];
      }
      for (int j = 0; j < m; j++)
        for (int q = 0; q < nf; q++) As[j][q] = A[j][idx[q]];
      double x[64];
      bool ok = ref_minnorm(As, rhs, m, nf, x);
      if (!ok && nf > 0) continue;
      for (int q = 0; q < nf; q++) F[idx[q]] = x[q];
      double res = 0, nrm = 0;
      bool inside = true;
      for (int i = 0; i < n; i++) {
        inside = inside && F[i] >= -1e-12 && F[i] <= c.F_max[i] + 1e-12;
        nrm += F[i] * F[i];
      }
      for (int j = 0; j < m; j++) {
        double v = -b[j];
        for (int i = 0; i < n; i++) v += A[j][i] * F[i];
        res = std::fmax(res, std::fabs(v));
      }
      if (inside && res < 1e-9 * (1 + std::fabs(b[0]) + std::fabs(b[1]) + std::fabs(b[2])))
        best = std::fmin(best, nrm);
    }
    ASSERT_LT(best, 1e300) << "trial " << trial << ": F0 itself is admissible";
    double got = 0;
    for (int i = 0; i < n; i++) got += double(r.out.F[i]) * r.out.F[i];
    EXPECT_LE(got, best * (1 + kt::tol(1e-9, 1e-4)) + kt::tol(1e-12, 1e-6)) << "trial " << trial;
  }
}

}  // namespace

// ---- issue 13: the contract for every input -------------------------------

// Finding 2 (thr_map part): torque arms of rank 2 (every force parallel to
// one unit u, so every d_i = (r_i - c) x u is orthogonal to u) with a request
// that has a component along u.  Before the fix K1 accepted some of these as
// OK (rounding-noise pivot just above the floor); now every one is
// W_SINGULAR with F = 0, and an OK is never returned.
// Verifies: REQ-THRMAP-005
TEST(ThrMapIssue13, RankTwoTorqueArmsAreNeverOk)
{
  kt::Rng rng(13);
  int singular = 0;
  for (int trial = 0; trial < 4000; trial++) {
    FswThrMapConfig c = base_cfg();
    c.num_thr = rng.uniform_int(3, 8);
    double u[3];
    rng.unit3(u);
    for (int i = 0; i < c.num_thr; i++) {
      const double sc = std::pow(10.0, rng.uniform(-3, 1));
      set3(c.r_thr_B[i], sc * rng.uniform(-1, 1), sc * rng.uniform(-1, 1), sc * rng.uniform(-1, 1));
      const double sg = rng.uniform() < 0.5 ? -1.0 : 1.0;
      set3(c.gt_hat_B[i], sg * u[0], sg * u[1], sg * u[2]);
      c.F_max[i] = 1;
    }
    MapRun r = map_once(c, u[0] + rng.uniform(-1, 1), u[1] + rng.uniform(-1, 1),
                        u[2] + rng.uniform(-1, 1));
    ASSERT_NE(FSW_OK, r.s) << "trial " << trial;
    if (r.s == FSW_W_SINGULAR) {
      singular++;
      for (int i = 0; i < FSW_MAX_THR; i++) ASSERT_EQ(0, r.out.F[i]) << "trial " << trial;
    }
  }
  EXPECT_GT(singular, 3000);
}

// Finding 6 (a): a finite request so large that the forces overflow is bad
// input with F = 0, in min-norm mode (also with a CoM offset, which gave
// NaN under W_SAT before).
// Verifies: REQ-THRMAP-008
TEST(ThrMapIssue13, OverflowingRequestIsBadInput)
{
  const double big = static_cast<double>(std::numeric_limits<R>::max());
  for (double rx : {0.0, -0.01}) {
    FswThrMapConfig c = base_cfg();
    set3(c.control_axes_B[1], 0, 0, 0);
    set3(c.control_axes_B[2], 0, 0, 0);
    c.num_thr = 1;
    set3(c.r_thr_B[0], rx, 0.5, 0);
    set3(c.gt_hat_B[0], 0, 0, 1);
    c.F_max[0] = 1;
    MapRun r = map_once(c, big * 0.99, 0, 0);
    EXPECT_EQ(FSW_E_BAD_INPUT, r.s) << "rx " << rx;
    for (int i = 0; i < FSW_MAX_THR; i++) EXPECT_EQ(0, r.out.F[i]);
    EXPECT_EQ(1u, r.st.health.bad_input);
    EXPECT_TRUE(std::isfinite(r.st.ang_err));
  }
}

// A short torque arm within the operating envelope (docs/eva.md, thr_map's
// envelope analysis): the six-axis set with every arm scaled to a, CoM at
// the origin.  [D][D]^T = 2 a^2 I, so for L = (Lx, Lx/2, 0) the first pass
// is F = (Lx/(2a), -Lx/(2a), Lx/(4a), -Lx/(4a), 0, 0), shifted by Lx/(2a)
// to (Lx/a, 0, 3Lx/(4a), Lx/(4a), Lx/(2a), Lx/(2a)); saturated, these give
// the torque F_max a (1, 0, 0), atan(0.5) away from L, so the scaling runs
// (as in SaturationScalingKeepsDirection).
// (a) a = 1e2/max: Lx/a = 10 max overflows in the solve's scaling back:
//     FSW_E_BAD_INPUT with F = 0, the angle error kept.
// (b) a = 1e6/max, F_max = 1e-6 (the envelope's least): every F_i is
//     finite (at most 1e-3 max), but |F_0| / F_max = 1e3 max overflows, so
//     the saturation factor is infinite and F / s = 0: zero forces with
//     FSW_W_SAT, and the angle between Lbar and the zero torque is
//     acos(0) = pi/2.  A safe output (no NaN or infinity leaves).
// Verifies: REQ-THRMAP-004, REQ-THRMAP-008
TEST(ThrMapEnvelope, ShortTorqueArmOverflowIsBadInputOrZeroForces)
{
  const double big = static_cast<double>(std::numeric_limits<R>::max());
  const double lx = 1e3;
  for (int which = 0; which < 2; which++) {
    const double a = (which == 0 ? 1e2 : 1e6) / big;
    FswThrMapConfig c = six_axis_cfg(which == 0 ? 1.0 : 1e-6);
    for (int i = 0; i < 6; i++)
      for (int k = 0; k < 3; k++) c.r_thr_B[i][k] = static_cast<R>(a * c.r_thr_B[i][k]);
    MapRun r = map_once(c, lx, 0.5 * lx, 0);
    if (which == 0) {
      EXPECT_EQ(FSW_E_BAD_INPUT, r.s);
      EXPECT_EQ(1u, r.st.health.bad_input);
      EXPECT_EQ(0, r.st.ang_err);
    } else {
      EXPECT_EQ(FSW_W_SAT, r.s);
      EXPECT_EQ(FSW_W_SAT, r.st.health.last);
      EXPECT_NEAR(std::acos(0.0), r.st.ang_err, kt::tol(1e-15, 1e-6));
    }
    for (int i = 0; i < FSW_MAX_THR; i++) EXPECT_EQ(0, r.out.F[i]) << "case " << which << " thruster " << i;
  }
}

// Finding 6 (b, c): the configs that overflowed (location 1.5e308, F_max
// 1e308) are now refused by check; a CoM beyond FSW_THR_MAP_R_MAX is bad
// input; the bounded mode is OK only when it delivers the request.
// Verifies: REQ-THRMAP-001, REQ-THRMAP-006, REQ-THRMAP-008
TEST(ThrMapIssue13, BoundedModeRangesAndDeliveredTorque)
{
  const double big = static_cast<double>(std::numeric_limits<R>::max()) / 1.2;
  FswThrMapConfig c = six_axis_cfg();
  c.mode = FSW_THR_MAP_NNLS;
  set3(c.r_thr_B[0], 0, big, -big);
  FswThrMapState st;
  EXPECT_EQ(FSW_E_CONFIG, fsw_thr_map_init(&st, &c));
  c = six_axis_cfg();
  c.mode = FSW_THR_MAP_NNLS;
  c.thr_force_sign = -1;
  c.F_max[4] = static_cast<R>(big);
  EXPECT_EQ(FSW_E_CONFIG, fsw_thr_map_init(&st, &c));
  c.F_max[4] = 1;
  MapRun r = map_once(c, 0.3, -0.2, 0.1, 2e3, 0, 0);  // CoM out of range
  EXPECT_EQ(FSW_E_BAD_INPUT, r.s);
  // rank-deficient (all arms about x and y) bounded mode: a z request is
  // out of reach -> least squares with W_SAT, never OK
  FswThrMapConfig d = base_cfg();
  d.mode = FSW_THR_MAP_NNLS;
  d.num_thr = 4;
  const double xy[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  for (int i = 0; i < 4; i++) {
    set3(d.r_thr_B[i], xy[i][0], xy[i][1], 0);
    set3(d.gt_hat_B[i], 0, 0, 1);
    d.F_max[i] = 1;
  }
  r = map_once(d, 0.1, 0.1, 0.5);
  EXPECT_EQ(FSW_W_SAT, r.s);
  for (int i = 0; i < FSW_MAX_THR; i++) EXPECT_TRUE(std::isfinite(r.out.F[i]));
  r = map_once(d, 0.1, -0.1, 0.0);  // in the range of [C][D]: delivered
  EXPECT_EQ(FSW_OK, r.s);
  double com[3] = {0, 0, 0}, t[3];
  body_torque(d, r.out.F, com, t);
  EXPECT_NEAR(0.1, t[0], kTol);
  EXPECT_NEAR(-0.1, t[1], kTol);
  EXPECT_NEAR(0.0, t[2], kTol);
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(ThrMapIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("thr_map", fsw_thr_map_check, fsw_thr_map_init, fsw_thr_map_reset, fsw_thr_map_update);
}

// Issue 21: a refused init clears the state (docs/fsw-conventions.md, "init
// calls check; on failure it clears the state, leaves st->ready = 0"): a
// state that was in use (ready, three counted axes, diagnostics and health
// counters set) keeps none of it after an init with a bad config, and the
// counted axes are 0, not a stale or default count.
// Verifies: REQ-THRMAP-001
TEST(ThrMapIssue21, RefusedInitClearsAUsedState)
{
  FswThrMapConfig c = six_axis_cfg();
  c.ang_err_thresh = static_cast<R>(0.5);
  MapRun r = map_once(c, 1, 0.5, 0);  // a used state: nc = 3, health counted
  ASSERT_EQ(1, r.st.ready);
  ASSERT_EQ(3, r.st.num_axes);
  ASSERT_EQ(1u, r.st.health.calls);
  FswThrMapConfig bad = c;
  bad.num_thr = 0;
  EXPECT_EQ(FSW_E_CONFIG, fsw_thr_map_init(&r.st, &bad));
  EXPECT_EQ(0, r.st.ready);
  EXPECT_EQ(0, r.st.num_axes);
  for (int j = 0; j < 3; j++)
    for (int k = 0; k < 3; k++) EXPECT_EQ(0, r.st.C[j][k]) << j << "," << k;
  EXPECT_EQ(0, r.st.ang_err);
  EXPECT_EQ(0, r.st.nnls_iter);
  EXPECT_EQ(0u, r.st.health.calls);
  // the same from a state never used: filled with a byte pattern first
  FswThrMapState st;
  std::memset(&st, 0x5A, sizeof st);
  EXPECT_EQ(FSW_E_CONFIG, fsw_thr_map_init(&st, &bad));
  EXPECT_EQ(0, st.ready);
  EXPECT_EQ(0, st.num_axes);
}

// Issue 21: the torque angle error of 8.5 is defined as 0 for a request at
// or below epsilon (docs/fsw/thr_map.md: "0 if |L̄| <= epsilon"): there is
// no direction to compare with.  In min-norm mode a zero request, and a
// request of norm 0.5 epsilon, leave ang_err = 0 (and the forces 0 for the
// zero request) -- also after a cycle whose angle error was atan(0.5), so
// the value is not a leftover.
// A state whose last cycle gave ang_err = atan(0.5) (the request l * (4, 2,
// 0) of SaturationScalingKeepsDirection on arms scaled by l, threshold 0.5
// above the angle: no scaling), with in/out ready for the next cycle.
namespace {
void start_at_atan_half(FswThrMapState& st, const FswThrMapConfig& c, FswThrMapIn& in, FswThrMapOut& out,
                        double l)
{
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  set3(in.r_CoM_B, 0, 0, 0);
  set3(in.Lr_B, 4 * l, 2 * l, 0);
  ASSERT_EQ(FSW_OK, fsw_thr_map_update(&st, &c, &in, &out));
  expect_forces(out, {4.0, 0.0, 3.0, 1.0, 2.0, 2.0});
  ASSERT_NEAR(std::atan(0.5), st.ang_err, kt::tol(1e-12, 1e-5));
}
}  // namespace

// Verifies: REQ-THRMAP-009
TEST(ThrMapIssue21, RequestAtOrBelowEpsilonHasNoAngleError)
{
  FswThrMapConfig c = six_axis_cfg();
  c.epsilon = static_cast<R>(1e-3);
  c.ang_err_thresh = static_cast<R>(0.5);
  FswThrMapState st;
  FswThrMapIn in{};
  FswThrMapOut out;
  start_at_atan_half(st, c, in, out, 1.0);
  if (HasFatalFailure()) return;
  set3(in.Lr_B, 0, 0, 0);
  EXPECT_EQ(FSW_OK, fsw_thr_map_update(&st, &c, &in, &out));
  EXPECT_EQ(0, st.ang_err);
  expect_forces(out, {0, 0, 0, 0, 0, 0});
  set3(in.Lr_B, 3e-4, 0, 4e-4);  // norm 5e-4 = epsilon / 2
  EXPECT_FALSE(fsw_status_is_error(fsw_thr_map_update(&st, &c, &in, &out)));
  EXPECT_EQ(0, st.ang_err);
}

// Mutation seed 31337 (thr_map.c:301): a cycle that fails after the mapper
// ran keeps the previous cycle's angle error ("an error changes no
// diagnostics").  Six-thruster geometry with the arms scaled by 1/4
// (thrusters at distance 0.25): [D][D]^T = 2 (1/4)^2 I = I/8.
// Cycle 1, L = (1, 0.5, 0): F = [D]^T L * 8 = (2,-2,1,-1,0,0), shifted by +2
// -> (4,0,3,1,2,2) as in SaturationScalingKeepsDirection; the saturated
// torque (1,0,1,1,1,1) -> (1/4)(1,0,0) makes atan(0.5) with L, below the
// threshold 0.5: ang_err = atan(0.5), no scaling.
// Cycle 2, L = (0.99 max, 0, 0): the first pass F_0 = 8 * L_x / 4 = 2 L_x
// overflows: FSW_E_BAD_INPUT, and ang_err must still be atan(0.5).
// Verifies: REQ-THRMAP-008
TEST(ThrMapSeed31337, ErrorAfterTheMapperKeepsThePreviousAngleError)
{
  FswThrMapConfig c = six_axis_cfg();
  for (int i = 0; i < 6; i++)
    for (int k = 0; k < 3; k++) c.r_thr_B[i][k] = static_cast<R>(0.25 * c.r_thr_B[i][k]);
  c.ang_err_thresh = static_cast<R>(0.5);
  FswThrMapState st;
  FswThrMapIn in{};
  FswThrMapOut out;
  start_at_atan_half(st, c, in, out, 0.25);
  if (HasFatalFailure()) return;
  set3(in.Lr_B, 0.99 * static_cast<double>(std::numeric_limits<R>::max()), 0, 0);
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_thr_map_update(&st, &c, &in, &out));
  for (int i = 0; i < FSW_MAX_THR; i++) EXPECT_EQ(0, out.F[i]);
  EXPECT_NEAR(std::atan(0.5), st.ang_err, kt::tol(1e-12, 1e-5));
  EXPECT_EQ(0, st.nnls_iter);  // min-norm mode: never written but by reset
}

// ---- issue 14: thrusters flagged unavailable --------------------------------

// The six-axis set plus a seventh thruster duplicating thruster 0 (arm +x),
// request L = (1, 0, 0) N*m.
//  NNLS (min ||F|| with [D]F = L, 0 <= F <= 2): F0 = F6 = 0.5; with thruster
//    0 unavailable its column is absent: F6 = 1, F0 = 0.
//  min-norm (8.3): the pseudo-inverse gives F0 = F6 = 1/3, F1 = -1/3, the
//    shift +1/3 (all thrusters): F0 = F6 = 2/3; with thruster 0 absent:
//    F6 = 1/2, F1 = -1/2, shifted: F6 = 1, F1 = 0 and the pure couples
//    2-3, 4-5 at 1/2 each.
// Both modes then deliver exactly L from the thrusters left (the torque is
// summed here from the arms +x, -x, +y, -y, +z, -z, +x).
// Verifies: REQ-THRMAP-007
TEST(ThrMapAvailability, AnUnavailableThrusterIsMappedAsAbsent)
{
  for (int mode : {FSW_THR_MAP_MIN_NORM, FSW_THR_MAP_NNLS}) {
    SCOPED_TRACE(mode);
    FswThrMapConfig c = six_axis_cfg(2.0);
    c.mode = mode;
    c.num_thr = 7;
    set3(c.r_thr_B[6], 0, 1, 0);
    set3(c.gt_hat_B[6], 0, 0, 1);
    c.F_max[6] = 2;
    FswThrMapState st;
    ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
    FswThrMapIn in{};
    set3(in.Lr_B, 1, 0, 0);
    FswThrMapOut out;
    ASSERT_EQ(FSW_OK, fsw_thr_map_update(&st, &c, &in, &out));
    const double both = mode == FSW_THR_MAP_NNLS ? 0.5 : 2.0 / 3.0;
    EXPECT_NEAR(both, out.F[0], kTol);
    EXPECT_NEAR(both, out.F[6], kTol);
    in.avail[0] = FSW_UNAVAILABLE;
    ASSERT_EQ(FSW_OK, fsw_thr_map_update(&st, &c, &in, &out));
    EXPECT_EQ(0, out.F[0]);
    EXPECT_NEAR(1.0, out.F[6], kTol);
    EXPECT_NEAR(0.0, out.F[1], kTol);
    const double tau[3] = {out.F[0] - out.F[1] + out.F[6], out.F[2] - out.F[3], out.F[4] - out.F[5]};
    EXPECT_NEAR(1.0, tau[0], kTol);
    EXPECT_NEAR(0.0, tau[1], kTol);
    EXPECT_NEAR(0.0, tau[2], kTol);
  }
}

// Off-pulsing DV set (dv_cfg, 3 control axes with the z row zero: 2 axes),
// thruster 0 flagged: it is commanded off (F = -F_max), its nominal torque is
// not counted, and the three left deliver the request about x and y:
// tau = sum_{i != 0} (F_max + F_i) d_i = L (the thrusters' own torque,
// computed here from the arms, not by the module).  Arms d = (r_y, -r_x):
// (1,-1), (1,1), (-1,1), (-1,-1); without thruster 0 the all-on torque is
// (-1, 1), so the others must change by T = L + (1, -1): F2 = (T_y - T_x)/2
// and F1 - F3 = (T_x + T_y)/2 with every F in [-1, 0].  L = (-0.2, 0.1, 0):
// T = (0.8, -0.9), F2 = -0.85, reachable.  (L = (0.2, -0.1) would need F2 =
// -1.15: out of reach with thruster 0 gone, FSW_W_SAT.)
// Verifies: REQ-THRMAP-007
TEST(ThrMapAvailability, OffPulsingUnavailableThrusterIsOffAndTheOthersDeliver)
{
  FswThrMapConfig c = dv_cfg(2);
  c.mode = FSW_THR_MAP_NNLS;
  FswThrMapState st;
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  FswThrMapIn in{};
  set3(in.Lr_B, 0.2, -0.1, 0);
  in.avail[0] = FSW_UNAVAILABLE;
  FswThrMapOut out;
  EXPECT_EQ(FSW_W_SAT, fsw_thr_map_update(&st, &c, &in, &out));
  set3(in.Lr_B, -0.2, 0.1, 0);
  ASSERT_EQ(FSW_OK, fsw_thr_map_update(&st, &c, &in, &out));
  EXPECT_NEAR(-0.85, out.F[2], kTol);
  EXPECT_EQ(-1, out.F[0]);
  double tau[2] = {0, 0};
  for (int i = 1; i < 4; i++) {
    EXPECT_LE(out.F[i], 0.0);
    EXPECT_GE(out.F[i], -1.0);
    const double d[2] = {c.r_thr_B[i][1], -c.r_thr_B[i][0]};  // (r x z)_xy = (r_y, -r_x)
    for (int k = 0; k < 2; k++) tau[k] += (1.0 + out.F[i]) * d[k];
  }
  EXPECT_NEAR(-0.2, tau[0], kTol);
  EXPECT_NEAR(0.1, tau[1], kTol);
}

// Verifies: REQ-THRMAP-008
TEST(ThrMapAvailability, AFlagOtherThanZeroOrOneIsBadInput)
{
  const FswThrMapConfig c = six_axis_cfg();
  FswThrMapState st;
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  FswThrMapIn in{};
  set3(in.Lr_B, 1, 0, 0);
  in.avail[5] = 2;
  FswThrMapOut out;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_thr_map_update(&st, &c, &in, &out));
  for (int i = 0; i < FSW_MAX_THR; i++) EXPECT_EQ(0, out.F[i]);
  in.avail[5] = 0;
  in.avail[6] = 7;  // beyond num_thr: not read
  EXPECT_EQ(FSW_OK, fsw_thr_map_update(&st, &c, &in, &out));
}

// Found by fuzz_fsw_thr_map (2026-12-03, with the flags): min-norm
// off-pulsing DV set with three control axes (no torque about z: rank 2,
// FSW_W_SINGULAR, F = 0) and thruster 0 flagged: F = 0 would be "full
// thrust" off-pulsing, so the flagged thruster keeps its off command -F_max
// under W_SINGULAR too; the others get 0.
// Verifies: REQ-THRMAP-007
TEST(ThrMapAvailability, RankDeficientOffPulsingKeepsTheFlaggedThrusterOff)
{
  FswThrMapConfig c = dv_cfg(3);
  FswThrMapState st;
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  FswThrMapIn in{};
  set3(in.Lr_B, 0.1, 0.2, 0.3);
  in.avail[0] = FSW_UNAVAILABLE;
  FswThrMapOut out;
  ASSERT_EQ(FSW_W_SINGULAR, fsw_thr_map_update(&st, &c, &in, &out));
  EXPECT_EQ(-1, out.F[0]);
  for (int i = 1; i < FSW_MAX_THR; i++) EXPECT_EQ(0, out.F[i]) << i;
}

// Issue 13, the blind spot rw_map had (b1d2eda): when every torque arm is
// normal to every control axis, or passes through the CoM, the entries of
// [C][D] are rounding noise of size ~1e-17 |r|; K1's scale-invariant test
// sees a full-rank matrix and solves with it.  The geometry is judged on its
// own scale: c . (r x g) / (|r| |g|), at most 1, must exceed the rounding
// level on some axis (FSW_RANK_TOL on the largest row's sum of squares),
// else W_SINGULAR with F = 0, in both modes.
// Verifies: REQ-THRMAP-005
TEST(ThrMapIssue13, TorqueArmsNormalToEveryAxisAreSingular)
{
  kt::Rng rng(1313);
  int noisy = 0;  // cases where the x torque arm computes to a non-zero value
  for (int trial = 0; trial < 400; trial++) {
    FswThrMapConfig c = base_cfg();
    set3(c.control_axes_B[1], 0, 0, 0);  // one control axis, x
    set3(c.control_axes_B[2], 0, 0, 0);
    c.num_thr = rng.uniform_int(1, 4);
    for (int i = 0; i < c.num_thr; i++) {
      double g[3] = {0, rng.uniform(-1, 1), rng.uniform(-1, 1)};
      const bool through_com = rng.uniform() < 0.3;
      if (through_com) g[0] = rng.uniform(-1, 1);
      const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      set3(c.gt_hat_B[i], g[0] / gn, g[1] / gn, g[2] / gn);
      const double s = rng.uniform(0.1, 3.0);
      const R* gh = c.gt_hat_B[i];
      // in the plane of x and g (arm normal to x), or along g (no arm)
      set3(c.r_thr_B[i], through_com ? s * gh[0] : rng.uniform(-2, 2), s * gh[1], s * gh[2]);
      const R* r = c.r_thr_B[i];
      if (r[1] * gh[2] - r[2] * gh[1] != 0) noisy++;
      c.F_max[i] = 1;
    }
    for (int mode : {FSW_THR_MAP_MIN_NORM, FSW_THR_MAP_NNLS}) {
      c.mode = mode;
      for (double lx : {0.5, 1e-12, 1e-20}) {
        MapRun r = map_once(c, lx, 0.1, -0.2);
        ASSERT_EQ(FSW_W_SINGULAR, r.s) << "trial " << trial << " mode " << mode << " Lx " << lx;
        for (int i = 0; i < FSW_MAX_THR; i++) ASSERT_EQ(0, r.out.F[i]) << "trial " << trial;
      }
      // control: one more thruster with a real arm about x (|d_x| / |r| =
      // 0.05, far above the floor in either real type) makes it solvable
      FswThrMapConfig d = c;
      const int k = d.num_thr++;
      set3(d.r_thr_B[k], 0, 1, 0);  // d = (0.05, 0, -0.9987)
      set3(d.gt_hat_B[k], std::sqrt(1 - 0.0025), 0, 0.05);
      d.F_max[k] = 1;
      MapRun r = map_once(d, 1e-3, 0, 0);
      EXPECT_NE(FSW_W_SINGULAR, r.s) << "trial " << trial << " mode " << mode;
    }
  }
  EXPECT_GT(noisy, 50);  // the test exercises the rounding-noise case
}

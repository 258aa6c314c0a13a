// css_sun: Sun heading from coarse sun sensors (docs/fsw/css_sun.md).
// Hand geometry: six sensors on the cube faces (+-x, +-y, +-z), where the
// lit normals are orthonormal and every estimate can be written down.
// Property checks use a 14-sensor head (6 faces + 8 cube corners) and seeded
// Sun directions: noiseless readings must give the Sun exactly; with bounded
// noise |dy_i| <= b the WLS error is exactly dx = (H^T W H)^-1 H^T W dy
// (because y = H s + dy for every lit sensor), so
//   |dx_j| <= b sum_i |P_ji|,  P = (H^T W H)^-1 H^T W,
// and the angle between x and the unit Sun s is at most atan(D / (1 - D)),
// D = |(b sum_i |P_ji|)_j|.  P is computed here independently (cofactor
// inverse), from the noisy readings the module saw.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "fsw/css_sun.h"
#include "css_sun_internal.h"
#include "fsw/fsw_vec.h"
#include "gnc_test_ref.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

const double kTol = kt::tol(1e-14, 2e-6);

// Cube faces: index 0..5 = +x, -x, +y, -y, +z, -z.
void cube_faces(FswCssSunConfig& c, double scale)
{
  c = FswCssSunConfig{};
  c.num_css = 6;
  const double n[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 6; i++) {
    gref::to_real(c.n_hat_B[i], n[i]);
    c.scale[i] = static_cast<fsw_real>(scale);
  }
  c.lit_threshold = FSW_R(0.1);
}

// 6 faces + 8 corners (+-1, +-1, +-1)/sqrt(3); scales differ per sensor.
void head14(FswCssSunConfig& c, double n_d[14][3], double scale_d[14])
{
  c = FswCssSunConfig{};
  c.num_css = 14;
  const double f[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  int k = 0;
  for (int i = 0; i < 6; i++, k++)
    for (int j = 0; j < 3; j++) n_d[k][j] = f[i][j];
  const double r3 = 1.0 / std::sqrt(3.0);
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      for (int sz = -1; sz <= 1; sz += 2, k++) {
        n_d[k][0] = sx * r3;
        n_d[k][1] = sy * r3;
        n_d[k][2] = sz * r3;
      }
  for (int i = 0; i < 14; i++) {
    scale_d[i] = 1.5 + 0.1 * i;  // [reading units] at normal incidence
    gref::to_real(c.n_hat_B[i], n_d[i]);
    // the module sees the fsw_real normals: use those in the reference
    gref::to_double(n_d[i], c.n_hat_B[i]);
    c.scale[i] = static_cast<fsw_real>(scale_d[i]);
    scale_d[i] = static_cast<double>(c.scale[i]);
  }
  c.lit_threshold = FSW_R(0.1);
}

// Ideal cosine-law readings for unit Sun s.
void readings(FswCssSunIn& in, const FswCssSunConfig& c, const double s[3])
{
  for (int i = 0; i < c.num_css; i++) {
    double n[3];
    gref::to_double(n, c.n_hat_B[i]);
    in.reading[i] = static_cast<fsw_real>(static_cast<double>(c.scale[i]) * std::fmax(0.0, gref::dot(n, s)));
  }
}

bool inv3(double out[3][3], const double A[3][3])
{
  const double c00 = A[1][1] * A[2][2] - A[1][2] * A[2][1];
  const double c01 = A[1][2] * A[2][0] - A[1][0] * A[2][2];
  const double c02 = A[1][0] * A[2][1] - A[1][1] * A[2][0];
  const double det = A[0][0] * c00 + A[0][1] * c01 + A[0][2] * c02;
  if (!(std::fabs(det) > 0.0)) return false;
  out[0][0] = c00 / det;
  out[1][0] = c01 / det;
  out[2][0] = c02 / det;
  out[0][1] = (A[0][2] * A[2][1] - A[0][1] * A[2][2]) / det;
  out[1][1] = (A[0][0] * A[2][2] - A[0][2] * A[2][0]) / det;
  out[2][1] = (A[0][1] * A[2][0] - A[0][0] * A[2][1]) / det;
  out[0][2] = (A[0][1] * A[1][2] - A[0][2] * A[1][1]) / det;
  out[1][2] = (A[0][2] * A[1][0] - A[0][0] * A[1][2]) / det;
  out[2][2] = (A[0][0] * A[1][1] - A[0][1] * A[1][0]) / det;
  return true;
}

double angle(const double a[3], const double b[3])
{
  double c[3];
  gref::cross(c, a, b);
  return std::atan2(gref::norm(c), gref::dot(a, b));
}

// Three sensors with coplanar normals x, y, (x+y)/sqrt(2), scale 1.
void coplanar_xy(FswCssSunConfig& c)
{
  c.num_css = 3;
  const double r2 = 1.0 / std::sqrt(2.0);
  gref::set3(c.n_hat_B[0], 1, 0, 0);
  gref::set3(c.n_hat_B[1], 0, 1, 0);
  gref::set3(c.n_hat_B[2], r2, r2, 0);
  for (int i = 0; i < 3; i++) c.scale[i] = FSW_R(1.0);
  c.lit_threshold = FSW_R(0.05);
}

class CssSun : public ::testing::Test {
 protected:
  void SetUp() override
  {
    kestrel_assert_reset();
    cube_faces(cfg_, 2.0);
    ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &cfg_));
  }
  FswStatus run() { return fsw_css_sun_update(&st_, &cfg_, &in_, &out_); }
  FswCssSunConfig cfg_{};
  FswCssSunState st_{};
  FswCssSunIn in_{};
  FswCssSunOut out_{};
};

// Verifies: REQ-CSS-001
TEST_F(CssSun, ThreeOrthogonalLitSensorsGiveExactSun)
{
  // s = (1,1,1)/sqrt(3): +x, +y, +z read 2/sqrt(3), y_i = 1/sqrt(3).
  // M = (1/sqrt(3)) I, c = (1/3)(1,1,1)  ->  x = sqrt(3)/3 (1,1,1) = s, |x| = 1.
  const double r3 = 1.0 / std::sqrt(3.0);
  const double s[3] = {r3, r3, r3};
  readings(in_, cfg_, s);
  ASSERT_EQ(FSW_OK, run());
  EXPECT_EQ(FSW_CSS_SUN_WLS, out_.mode);
  EXPECT_EQ(3, out_.num_lit);
  EXPECT_EQ(1, out_.sun_valid);
  EXPECT_V3_NEAR(r3, r3, r3, out_.sun_hat_B, kTol);
  EXPECT_NEAR(1.0, out_.sun_mag, kTol);
}

// Verifies: REQ-CSS-002
TEST_F(CssSun, TwoLitSensorsInPlaneSunIsExact)
{
  // s = (0.6, 0.8, 0): only +x (0.6) and +y (0.8) lit.  Two-sensor
  // minimum-norm: n_a = +y (brighter), n_b = +x, n_a.n_b = 0 ->
  // x = 0.8 y + 0.6 x = s; status warns that this is a fallback.
  const double s[3] = {0.6, 0.8, 0.0};
  readings(in_, cfg_, s);
  ASSERT_EQ(FSW_W_SINGULAR, run());
  EXPECT_EQ(FSW_CSS_SUN_TWO, out_.mode);
  EXPECT_EQ(2, out_.num_lit);
  EXPECT_V3_NEAR(0.6, 0.8, 0.0, out_.sun_hat_B, kTol);
  EXPECT_NEAR(1.0, out_.sun_mag, kTol);
  EXPECT_EQ(1u, st_.health.singular);
}

// Verifies: REQ-CSS-002
TEST_F(CssSun, TwoLitSensorsGiveInPlaneProjection)
{
  // s = (0.6, 0.6, sqrt(0.28)) with +z failed: +x, +y lit at 0.6 each.
  // x = 0.6 x + 0.6 y (the projection of s on span{x, y}), |x| = 0.6 sqrt(2),
  // heading (1,1,0)/sqrt(2): the out-of-plane part is lost (documented).
  const double s[3] = {0.6, 0.6, std::sqrt(0.28)};
  readings(in_, cfg_, s);
  in_.avail[4] = FSW_UNAVAILABLE;
  ASSERT_EQ(FSW_W_SINGULAR, run());
  EXPECT_EQ(FSW_CSS_SUN_TWO, out_.mode);
  const double r2 = 1.0 / std::sqrt(2.0);
  EXPECT_V3_NEAR(r2, r2, 0.0, out_.sun_hat_B, kTol);
  EXPECT_NEAR(0.6 * std::sqrt(2.0), out_.sun_mag, kTol);
}

// Verifies: REQ-CSS-002
TEST_F(CssSun, OneLitSensorGivesItsNormal)
{
  // s = (0.6, 0, 0.8) with +z failed: only +x lit (y = 0.6).
  const double s[3] = {0.6, 0.0, 0.8};
  readings(in_, cfg_, s);
  in_.avail[4] = FSW_UNAVAILABLE;
  in_.reading[4] = static_cast<fsw_real>(gref::nan());  // ignored: unavailable
  ASSERT_EQ(FSW_W_SINGULAR, run());
  EXPECT_EQ(FSW_CSS_SUN_ONE, out_.mode);
  EXPECT_EQ(1, out_.num_lit);
  EXPECT_EQ(1, out_.sun_valid);
  EXPECT_V3_NEAR(1.0, 0.0, 0.0, out_.sun_hat_B, 0.0);
  EXPECT_NEAR(0.6, out_.sun_mag, kTol);
}

// Verifies: REQ-CSS-003
TEST_F(CssSun, NoLitSensorNoHeading)
{
  // eclipse: all readings 0 (and one just at the threshold: not lit, strict >)
  in_.reading[2] = FSW_R(0.2);  // y = 0.2/2 = 0.1 = threshold
  ASSERT_EQ(FSW_W_SINGULAR, run());
  EXPECT_EQ(FSW_CSS_SUN_NONE, out_.mode);
  EXPECT_EQ(0, out_.num_lit);
  EXPECT_EQ(0, out_.sun_valid);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.sun_hat_B, 0.0);
  EXPECT_EQ(0.0, out_.sun_mag);
}

// Verifies: REQ-CSS-002
TEST_F(CssSun, CoplanarLitSensorsFallBackToTwo)
{
  // normals x, y, (x+y)/sqrt(2) are coplanar: M has rank 2, WLS refused.
  // s = (0.6, 0.8, 0): y = 0.6, 0.8, 1.4/sqrt(2) = 0.98995.  Brightest a = 2,
  // brightest non-parallel partner b = 1 (+y); x = projection of s on the
  // x-y plane = s (s lies in it).
  FswCssSunConfig c{};
  coplanar_xy(c);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &c));
  const double s[3] = {0.6, 0.8, 0.0};
  readings(in_, c, s);
  ASSERT_EQ(FSW_W_SINGULAR, fsw_css_sun_update(&st_, &c, &in_, &out_));
  EXPECT_EQ(FSW_CSS_SUN_TWO, out_.mode);
  EXPECT_EQ(3, out_.num_lit);
  EXPECT_V3_NEAR(0.6, 0.8, 0.0, out_.sun_hat_B, kt::tol(1e-14, 4e-6));
}

// Verifies: REQ-CSS-002
TEST_F(CssSun, ParallelLitSensorsFallBackToOne)
{
  // two sensors with the same normal (redundant pair) both lit: no 2-D
  // information, heading = the common normal; the brighter (lower index on a
  // tie) is reported.
  FswCssSunConfig c{};
  c.num_css = 2;
  gref::set3(c.n_hat_B[0], 0, 0, 1);
  gref::set3(c.n_hat_B[1], 0, 0, 1);
  c.scale[0] = c.scale[1] = FSW_R(1.0);
  c.lit_threshold = FSW_R(0.1);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &c));
  in_.reading[0] = FSW_R(0.5);
  in_.reading[1] = FSW_R(0.7);
  ASSERT_EQ(FSW_W_SINGULAR, fsw_css_sun_update(&st_, &c, &in_, &out_));
  EXPECT_EQ(FSW_CSS_SUN_ONE, out_.mode);
  EXPECT_EQ(2, out_.num_lit);
  EXPECT_V3_NEAR(0.0, 0.0, 1.0, out_.sun_hat_B, 0.0);
  EXPECT_NEAR(0.7, out_.sun_mag, kTol);
}

// Verifies: REQ-CSS-001
TEST_F(CssSun, NoiselessReadingsGiveExactSunOnSeededDirections)
{
  double n[14][3], sc[14];
  FswCssSunConfig c{};
  head14(c, n, sc);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &c));
  kt::Rng rng(0x5eed0004u);
  int n_wls = 0;
  const int kTrials = 500;
  for (int t = 0; t < kTrials; t++) {
    double s[3];
    rng.unit3(s);
    FswCssSunIn in{};
    readings(in, c, s);
    FswCssSunOut out{};
    const FswStatus st = fsw_css_sun_update(&st_, &c, &in, &out);
    if (out.mode != FSW_CSS_SUN_WLS) {
      EXPECT_EQ(FSW_W_SINGULAR, st);
      continue;
    }
    n_wls++;
    EXPECT_EQ(FSW_OK, st);
    EXPECT_V3_NEAR(s[0], s[1], s[2], out.sun_hat_B, kt::tol(1e-13, 2e-6));
    EXPECT_NEAR(1.0, out.sun_mag, kt::tol(1e-13, 2e-6));
  }
  // with 14 sensors at least 3 spanning sensors are lit almost everywhere
  EXPECT_GT(n_wls, kTrials * 95 / 100);
}

// Verifies: REQ-CSS-001
TEST_F(CssSun, NoisyReadingsStayWithinAnalyticBound)
{
  double n[14][3], sc[14];
  FswCssSunConfig c{};
  head14(c, n, sc);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &c));
  const double b = 0.01;  // [-] noise bound on each cosine, < lit_threshold
  kt::Rng rng(0x5eed0005u);
  int n_checked = 0;
  double worst_ratio = 0.0;
  for (int t = 0; t < 400; t++) {
    double s[3];
    rng.unit3(s);
    FswCssSunIn in{};
    for (int i = 0; i < 14; i++) {
      const double cosv = std::fmax(0.0, gref::dot(n[i], s));
      in.reading[i] = static_cast<fsw_real>(sc[i] * (cosv + b * rng.uniform(-1.0, 1.0)));
    }
    FswCssSunOut out{};
    fsw_css_sun_update(&st_, &c, &in, &out);
    // lit set and weights as the module defines them, from the noisy values
    double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    double y[14];
    bool lit[14];
    int n_lit = 0;
    for (int i = 0; i < 14; i++) {
      y[i] = static_cast<double>(in.reading[i]) / sc[i];
      lit[i] = y[i] > 0.1;
      if (!lit[i]) continue;
      n_lit++;
      EXPECT_GT(gref::dot(n[i], s), 0.0);  // lit => the cosine law is linear there
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) M[j][k] += y[i] * n[i][j] * n[i][k];
    }
    EXPECT_EQ(n_lit, out.num_lit);
    if (out.mode != FSW_CSS_SUN_WLS) continue;
    double Minv[3][3];
    ASSERT_TRUE(inv3(Minv, M));
    double B[3] = {0, 0, 0}, x_ref[3] = {0, 0, 0};
    for (int i = 0; i < 14; i++) {
      if (!lit[i]) continue;
      double Pcol[3];  // column i of P = M^-1 n_i w_i
      gref::matvec(Pcol, Minv, n[i]);
      for (int j = 0; j < 3; j++) {
        Pcol[j] *= y[i];
        B[j] += b * std::fabs(Pcol[j]);
        x_ref[j] += Pcol[j] * y[i];
      }
    }
    const double D = gref::norm(B);
    ASSERT_LT(D, 1.0);
    const double bound = std::atan(D / (1.0 - D)) + kt::tol(1e-12, 2e-5);
    double got[3];
    gref::to_double(got, out.sun_hat_B);
    const double err = angle(got, s);
    EXPECT_LE(err, bound) << "trial " << t;
    worst_ratio = std::fmax(worst_ratio, err / bound);
    // and the module's estimate is the WLS solution itself
    const double xn = gref::norm(x_ref);
    for (int j = 0; j < 3; j++) EXPECT_NEAR(x_ref[j] / xn, got[j], kt::tol(1e-12, 2e-5));
    n_checked++;
  }
  EXPECT_GT(n_checked, 380);
  EXPECT_GT(worst_ratio, 0.05);  // the bound is not vacuous
}

// Verifies: REQ-CSS-004
TEST_F(CssSun, RejectsBadConfig)
{
  struct Case {
    const char* name;
    FswStatus want;
    void (*edit)(FswCssSunConfig&);
  };
  const Case cases[] = {
      {"no sensors", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.num_css = 0; }},
      {"negative count", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.num_css = -2; }},
      {"too many", FSW_E_CAPACITY, [](FswCssSunConfig& c) { c.num_css = FSW_MAX_CSS + 1; }},
      {"normal not unit", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.n_hat_B[3][1] = FSW_R(-0.9); }},
      {"normal zero", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.n_hat_B[0][0] = FSW_R(0.0); }},
      {"normal nan", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.n_hat_B[5][2] = static_cast<fsw_real>(gref::nan()); }},
      {"scale 0", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.scale[1] = FSW_R(0.0); }},
      {"scale < 0", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.scale[1] = FSW_R(-2.0); }},
      {"scale inf", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.scale[4] = static_cast<fsw_real>(gref::inf()); }},
      {"threshold < 0", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.lit_threshold = FSW_R(-0.01); }},
      {"threshold 1", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.lit_threshold = FSW_R(1.0); }},
      {"threshold nan", FSW_E_CONFIG, [](FswCssSunConfig& c) { c.lit_threshold = static_cast<fsw_real>(gref::nan()); }},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    FswCssSunConfig c = cfg_;
    k.edit(c);
    EXPECT_EQ(k.want, fsw_css_sun_check(&c));
    FswCssSunState st{};
    EXPECT_EQ(k.want, fsw_css_sun_init(&st, &c));
    EXPECT_EQ(0, st.ready);
    out_.sun_valid = 1;
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_css_sun_update(&st, &c, &in_, &out_));
    EXPECT_EQ(0, out_.sun_valid);
  }
  FswCssSunConfig ok = cfg_;
  ok.lit_threshold = FSW_R(0.0);
  ok.num_css = 1;
  EXPECT_EQ(FSW_OK, fsw_css_sun_check(&ok));
}

// Verifies: REQ-CSS-005
TEST_F(CssSun, BadInputGivesSafeOutput)
{
  const double r3 = 1.0 / std::sqrt(3.0);
  const double s[3] = {r3, r3, r3};
  readings(in_, cfg_, s);
  const FswCssSunIn good = in_;
  for (double v : {gref::nan(), gref::inf(), -gref::inf()}) {
    in_ = good;
    in_.reading[3] = static_cast<fsw_real>(v);  // an unlit but available sensor
    out_.sun_valid = 1;
    EXPECT_EQ(FSW_E_BAD_INPUT, run());
    EXPECT_EQ(0, out_.sun_valid);
    EXPECT_EQ(FSW_CSS_SUN_NONE, out_.mode);
    EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.sun_hat_B, 0.0);
  }
  in_ = good;
  in_.avail[0] = 3;  // neither AVAILABLE nor UNAVAILABLE
  EXPECT_EQ(FSW_E_BAD_INPUT, run());
  // finite readings whose normal equations overflow
  in_ = good;
  in_.reading[0] = static_cast<fsw_real>(kt::kFloat ? 3e38 : 1.7e308);
  EXPECT_EQ(FSW_E_BAD_INPUT, run());
  EXPECT_EQ(0, out_.sun_valid);
  EXPECT_EQ(5u, st_.health.bad_input);
  in_ = good;
  EXPECT_EQ(FSW_OK, run());  // recovers
  EXPECT_EQ(1, out_.sun_valid);
}

// Verifies: REQ-GEN-007
TEST_F(CssSun, NullPointersAssert)
{
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_css_sun_update(&st_, &cfg_, nullptr, &out_));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_css_sun_check(nullptr));
  EXPECT_EQ(2ul, kestrel_assert_count());
}

// Verifies: REQ-CSS-007
TEST_F(CssSun, RepeatableAfterReset)
{
  double n[14][3], sc[14];
  FswCssSunConfig c{};
  head14(c, n, sc);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &c));
  kt::Rng rng(7);
  for (int i = 0; i < 14; i++) in_.reading[i] = static_cast<fsw_real>(rng.uniform(0.0, 1.5));
  FswCssSunOut a{}, b{};
  const FswStatus sa = fsw_css_sun_update(&st_, &c, &in_, &a);
  fsw_css_sun_reset(&st_);
  const FswStatus sb = fsw_css_sun_update(&st_, &c, &in_, &b);
  EXPECT_EQ(sa, sb);
  EXPECT_EQ(a.mode, b.mode);
  for (int i = 0; i < 3; i++) EXPECT_EQ(a.sun_hat_B[i], b.sun_hat_B[i]);
  EXPECT_EQ(a.sun_mag, b.sun_mag);
}

}  // namespace

// Finding 9 (issue 13): two lit sensors with subnormal readings (lit
// threshold 0) gave |sun_hat| = 1.00013 in two-sensor mode: the norm of a
// subnormal vector loses digits.  fsw_v3_normalize now pre-scales by a
// power of two, so sun_hat is a unit vector for any finite estimate.
// Verifies: REQ-CSS-006
TEST_F(CssSun, Issue13SubnormalReadingsStillGiveAUnitHeading)
{
  cfg_.lit_threshold = FSW_R(0.0);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &cfg_));
  const fsw_real tiny = std::numeric_limits<fsw_real>::denorm_min();
  for (int i = 0; i < 6; i++) in_.reading[i] = 0;
  in_.reading[0] = tiny * 1000;
  in_.reading[2] = tiny * 700;
  const FswStatus s = run();
  EXPECT_FALSE(fsw_status_is_error(s));
  if (out_.sun_valid) {
    EXPECT_NEAR(1.0, fsw_v3_norm(out_.sun_hat_B), kt::tol(1e-15, 1e-6));
    for (int k = 0; k < 3; k++) EXPECT_TRUE(std::isfinite(out_.sun_hat_B[k]));
  }
}

// Issue 21: a finite reading whose normalised value y = reading / scale
// overflows to -inf.  Scale 0.5, reading -max: y = -2 max = -inf, which is
// not lit (-inf <= threshold), so only the overflow check on y refuses it;
// without it the other sensors would give a heading from a corrupt input.
// (The +max reading of BadInputGivesSafeOutput is also caught later, by the
// overflow of the normal equations.)
// Verifies: REQ-CSS-005
TEST_F(CssSun, Issue21NegativeOverflowOfAReadingIsBadInput)
{
  cube_faces(cfg_, 0.5);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &cfg_));
  const double r3 = 1.0 / std::sqrt(3.0);
  const double s[3] = {r3, r3, r3};
  readings(in_, cfg_, s);
  EXPECT_EQ(FSW_OK, run());  // +x, +y, +z lit: the exact Sun
  EXPECT_EQ(1, out_.sun_valid);
  in_.reading[1] = -std::numeric_limits<fsw_real>::max();  // the unlit -x face
  EXPECT_EQ(FSW_E_BAD_INPUT, run());
  EXPECT_EQ(0, out_.sun_valid);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.sun_hat_B, 0.0);
  EXPECT_EQ(1u, st_.health.bad_input);
}

// Issue 21: every entry point with every pointer NULL in turn asserts once
// and returns FSW_E_NULL_ARG (null_args.h).
// Verifies: REQ-GEN-007
TEST(CssSunNullIssue21, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("css_sun", fsw_css_sun_check, fsw_css_sun_init, fsw_css_sun_reset, fsw_css_sun_update);
}

// Issue 21: an unavailable sensor never takes part, whatever the previous
// call saw.  Call 1: Sun along (1, 1, 1)/sqrt(3), +x, +y, +z lit (WLS).
// Call 2: only +x available: one lit sensor, so mode ONE with the +x normal
// (header: FSW_CSS_SUN_ONE), never a TWO built with a sensor that is
// unavailable now (its lit flag must be cleared on every call, not left from
// call 1).
// Verifies: REQ-CSS-005
TEST_F(CssSun, Issue21UnavailableSensorIsNeverAPartner)
{
  const double r3 = 1.0 / std::sqrt(3.0);
  const double s[3] = {r3, r3, r3};
  readings(in_, cfg_, s);
  ASSERT_EQ(FSW_OK, run());
  ASSERT_EQ(FSW_CSS_SUN_WLS, out_.mode);
  for (int i = 1; i < 6; i++) in_.avail[i] = FSW_UNAVAILABLE;
  EXPECT_EQ(FSW_W_SINGULAR, run());
  EXPECT_EQ(FSW_CSS_SUN_ONE, out_.mode);
  EXPECT_EQ(1, out_.num_lit);
  EXPECT_V3_NEAR(1.0, 0.0, 0.0, out_.sun_hat_B, 0.0);
}

// Issue 21: readings whose normal matrix M = sum y n n^T is finite but whose
// right-hand side c = sum y^2 n overflows: y = 1e200 (1e20 in float) gives
// M ~ 1e200 and y^2 = 1e400 = inf.  Bad input, safe output.
// Verifies: REQ-CSS-005
TEST_F(CssSun, Issue21OverflowOfTheRightHandSideIsBadInput)
{
  const double r3 = 1.0 / std::sqrt(3.0);
  const double s[3] = {r3, r3, r3};
  readings(in_, cfg_, s);
  in_.reading[0] = static_cast<fsw_real>(kt::kFloat ? 1e20 : 1e200);
  EXPECT_EQ(FSW_E_BAD_INPUT, run());
  EXPECT_EQ(0, out_.sun_valid);
  EXPECT_V3_NEAR(0.0, 0.0, 0.0, out_.sun_hat_B, 0.0);
}

// Issue 21: the normal matrix itself overflowing: two sensors with the same
// normal (+x) each reading 0.9 max at scale 1 put 1.8 max = inf into M_xx
// (the right-hand side overflows too).  Bad input.
// Verifies: REQ-CSS-005
TEST_F(CssSun, Issue21OverflowOfTheNormalMatrixIsBadInput)
{
  FswCssSunConfig c = cfg_;
  c.n_hat_B[1][0] = FSW_R(1.0);  // sensor 1 (was -x) now also +x
  for (int i = 0; i < 6; i++) c.scale[i] = FSW_R(1.0);
  FswCssSunState st{};
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st, &c));
  FswCssSunIn in{};
  in.reading[0] = in.reading[1] = static_cast<fsw_real>(0.9) * std::numeric_limits<fsw_real>::max();
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_css_sun_update(&st, &c, &in, &out_));
  EXPECT_EQ(0, out_.sun_valid);
}

// MC/DC of the partner search (css_sun.c, `b < 0 || y[i] > y[b]`): three
// coplanar lit sensors x, y, (x+y)/sqrt(2) (WLS refused), a = 2 the
// brightest; the partner is the brighter of sensors 0 and 1, whichever
// comes first.  The readings of the two candidates are inconsistent on
// purpose, so the heading tells which one was taken: with partner b the
// heading solves n_2.x = y_2 = 1.4/sqrt(2) (x_x + x_y = 1.4) and
// n_b.x = y_b only.
//   y = (0.8, 0.3, 1.4/sqrt(2)): sensor 1 is dimmer than sensor 0 (the
//   condition false for it), b = 0: x = (0.8, 0.6, 0), |x| = 1.
//   y = (0.3, 0.8, 1.4/sqrt(2)): sensor 1 is brighter, b = 1:
//   x = (0.6, 0.8, 0).
// (Taking the dimmer one would give (0.8, 0.3)/(0.3, 1.1) normalised.)
// Verifies: REQ-CSS-002
TEST_F(CssSun, McdcTheBrighterOfTwoPartnersIsTakenEitherOrder)
{
  FswCssSunConfig c{};
  coplanar_xy(c);
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_, &c));
  const double y2 = 1.4 / std::sqrt(2.0);
  const struct {
    double y0, y1, want[3];
  } rows[] = {{0.8, 0.3, {0.8, 0.6, 0.0}}, {0.3, 0.8, {0.6, 0.8, 0.0}}};
  for (const auto& r : rows) {
    in_.reading[0] = static_cast<fsw_real>(r.y0);
    in_.reading[1] = static_cast<fsw_real>(r.y1);
    in_.reading[2] = static_cast<fsw_real>(y2);
    ASSERT_EQ(FSW_W_SINGULAR, fsw_css_sun_update(&st_, &c, &in_, &out_)) << r.y0;
    EXPECT_EQ(FSW_CSS_SUN_TWO, out_.mode);
    EXPECT_EQ(3, out_.num_lit);
    EXPECT_V3_NEAR(r.want[0], r.want[1], r.want[2], out_.sun_hat_B, kt::tol(1e-14, 4e-6));
    EXPECT_NEAR(1.0, out_.sun_mag, kt::tol(1e-14, 4e-6)) << r.y0;
  }
}

// fsw_acs calls the estimate without the update's input checks (its cycle
// checks the same flags and readings first): for every input that passes
// them the output, the status and the health record are the update's, bit
// for bit, in each of the WLS, two-sensor, one-sensor and no-heading cases.
// Verifies: REQ-CSS-001, REQ-CSS-002, REQ-CSS-003
TEST_F(CssSun, EstimateOfACheckedInputIsTheUpdate)
{
  double n[14][3], sc[14];
  FswCssSunConfig c{};
  head14(c, n, sc);
  FswCssSunState st_u{}, st_e{};
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_u, &c));
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st_e, &c));
  kt::Rng rng(0x5eed0045u);
  int seen[4] = {0, 0, 0, 0};
  for (int t = 0; t < 4000; t++) {
    double s[3];
    rng.unit3(s);
    FswCssSunIn in{};
    readings(in, c, s);
    for (int i = 0; i < c.num_css; i++) {
      in.avail[i] = (rng.uniform(0.0, 1.0) < 0.4) ? FSW_UNAVAILABLE : FSW_AVAILABLE;
      if (in.avail[i] == FSW_UNAVAILABLE && (t % 3) == 0) {
        in.reading[i] = std::numeric_limits<fsw_real>::quiet_NaN();  // not read
      }
    }
    FswCssSunOut out_u{}, out_e{};
    const FswStatus su = fsw_css_sun_update(&st_u, &c, &in, &out_u);
    const FswStatus se = fsw_css_sun_estimate(&st_e, &c, in.reading, in.avail, &out_e);
    ASSERT_EQ(su, se) << t;
    ASSERT_EQ(0, std::memcmp(&out_u, &out_e, sizeof out_u)) << t;
    ASSERT_EQ(0, std::memcmp(&st_u, &st_e, sizeof st_u)) << t;
    seen[out_u.mode]++;
  }
  for (int m = 0; m < 4; m++) EXPECT_GT(seen[m], 0) << m;
  // a state that is not ready: FSW_E_NOT_INIT and the safe output, as the update
  FswCssSunState idle{};
  FswCssSunIn in{};
  FswCssSunOut out{};
  out.sun_valid = 1;
  EXPECT_EQ(FSW_E_NOT_INIT, fsw_css_sun_estimate(&idle, &c, in.reading, in.avail, &out));
  EXPECT_EQ(0, out.sun_valid);
  EXPECT_EQ(1u, idle.health.calls);
}

// The estimate tests the right-hand side c = sum y^2 n alone for overflow:
// c is finite only if the normal matrix M = sum y n n^T is.  Over seeded
// Sun directions, lit sets and one or two readings swept from 1e100 to the
// largest real (1e10 up in float), bad input exactly when this file's own
// accumulation of every entry of M and c, in the module's order and type,
// overflows: the verdict of testing M and c together.
// Verifies: REQ-CSS-005
TEST_F(CssSun, OverflowVerdictOfTheRightHandSideIsThatOfTheWholeSystem)
{
  double n[14][3], sc[14];
  FswCssSunConfig c{};
  head14(c, n, sc);
  FswCssSunState st{};
  ASSERT_EQ(FSW_OK, fsw_css_sun_init(&st, &c));
  kt::Rng rng(0x5eed0046u);
  const double lo = kt::kFloat ? 1e10 : 1e100;
  const double hi = static_cast<double>(std::numeric_limits<fsw_real>::max());
  int bad = 0, good = 0, m_only_ok = 0;
  for (int t = 0; t < 3000; t++) {
    double s[3];
    rng.unit3(s);
    FswCssSunIn in{};
    readings(in, c, s);
    for (int h = 0; h < 1 + (t % 2); h++) {
      const int i = rng.uniform_int(0, c.num_css - 1);
      in.reading[i] = static_cast<fsw_real>(std::exp(rng.uniform(std::log(lo), std::log(hi))));
    }
    fsw_real M[3][3] = {}, cc[3] = {};
    bool overflow_y = false;
    for (int i = 0; i < c.num_css; i++) {
      const fsw_real y = in.reading[i] / c.scale[i];
      if (!std::isfinite(y)) overflow_y = true;
      if (!(y > c.lit_threshold)) continue;
      for (int j = 0; j < 3; j++) {
        for (int k = 0; k < 3; k++) M[j][k] += y * c.n_hat_B[i][j] * c.n_hat_B[i][k];
        cc[j] += y * y * c.n_hat_B[i][j];
      }
    }
    bool m_finite = true, c_finite = true;
    for (int j = 0; j < 3; j++) {
      c_finite = c_finite && std::isfinite(cc[j]);
      for (int k = 0; k < 3; k++) m_finite = m_finite && std::isfinite(M[j][k]);
    }
    const bool want_bad = overflow_y || !m_finite || !c_finite;
    FswCssSunOut out{};
    const FswStatus got = fsw_css_sun_update(&st, &c, &in, &out);
    ASSERT_EQ(want_bad, got == FSW_E_BAD_INPUT) << t;
    bad += want_bad;
    good += !want_bad;
    m_only_ok += (m_finite && !c_finite);
  }
  EXPECT_GT(bad, 300);
  EXPECT_GT(good, 300);
  EXPECT_GT(m_only_ok, 100);  // M finite, c not: the right-hand side decides
}

// guid_orbit: orbit-referenced guidance.  Expected values: hand-built frames
// of a circular equatorial orbit, and an independent two-body propagation
// (RK4 written here) whose frames are differenced numerically.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "fsw/guid_orbit.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
const fsw_real kInf = std::numeric_limits<fsw_real>::infinity();
const double kMu = 3.986004418e14;  // [m^3/s^2] Earth
const double kPi = 3.14159265358979323846;

struct V3 {
  double x[3];
  double operator[](int i) const { return x[i]; }
};
V3 v3(double a, double b, double c) { return V3{{a, b, c}}; }
V3 add(V3 a, V3 b, double s = 1.0) { return v3(a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]); }
V3 scl(double s, V3 a) { return v3(s * a[0], s * a[1], s * a[2]); }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double nrm(V3 a) { return std::sqrt(dot(a, a)); }
V3 unit(V3 a) { return scl(1.0 / nrm(a), a); }
V3 cross(V3 a, V3 b)
{
  return v3(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

// Independent frame construction: rows R1, R2, R3 of [RN].
void ref_frame(double C[3][3], V3 r, V3 v, int variant)
{
  const V3 h = unit(cross(r, v));
  V3 R1, R2 = scl(-1, h), R3;
  if (variant == FSW_GUID_ORBIT_NADIR) {
    R3 = scl(-1, unit(r));
    R1 = cross(R2, R3);
  } else {
    R1 = unit(v);
    R3 = cross(R1, R2);
  }
  for (int k = 0; k < 3; k++) {
    C[0][k] = R1[k];
    C[1][k] = R2[k];
    C[2][k] = R3[k];
  }
}

// Independent MRP -> DCM (Schaub & Junkins 3.152).
void mrp2dcm(double C[3][3], const fsw_real s_in[3])
{
  const double s[3] = {double(s_in[0]), double(s_in[1]), double(s_in[2])};
  const double s2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2], d = (1 + s2) * (1 + s2);
  const double t[3][3] = {{0, -s[2], s[1]}, {s[2], 0, -s[0]}, {-s[1], s[0], 0}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double t2 = 0;
      for (int k = 0; k < 3; k++) t2 += t[i][k] * t[k][j];
      C[i][j] = (i == j ? 1.0 : 0.0) + (8 * t2 - 4 * (1 - s2) * t[i][j]) / d;
    }
}

// Two-body RK4 from (r, v) over time T with steps of at most dt.
void rk4(V3& r, V3& v, double T, double dt)
{
  const int n = std::max(1, int(std::ceil(std::fabs(T) / dt)));
  const double h = T / n;
  auto acc = [](V3 p) { const double q = nrm(p); return scl(-kMu / (q * q * q), p); };
  for (int i = 0; i < n; i++) {
    const V3 k1r = v, k1v = acc(r);
    const V3 k2r = add(v, k1v, h / 2), k2v = acc(add(r, k1r, h / 2));
    const V3 k3r = add(v, k2v, h / 2), k3v = acc(add(r, k2r, h / 2));
    const V3 k4r = add(v, k3v, h), k4v = acc(add(r, k3r, h));
    r = add(r, add(add(add(k1r, k2r, 2), k3r, 2), k4r), h / 6);  // k1 + 2 k2 + 2 k3 + k4
    v = add(v, add(add(add(k1v, k2v, 2), k3v, 2), k4v), h / 6);
  }
}

// Orbit state from classical elements (perifocal -> N by 3-1-3 rotation).
void from_elements(V3& r, V3& v, double a, double e, double inc, double raan, double argp, double nu)
{
  const double p = a * (1 - e * e), rr = p / (1 + e * std::cos(nu));
  const double rp[3] = {rr * std::cos(nu), rr * std::sin(nu), 0};
  const double vp[3] = {-std::sqrt(kMu / p) * std::sin(nu), std::sqrt(kMu / p) * (e + std::cos(nu)), 0};
  const double cO = std::cos(raan), sO = std::sin(raan), ci = std::cos(inc), si = std::sin(inc), cw = std::cos(argp),
               sw = std::sin(argp);
  const double Q[3][2] = {{cO * cw - sO * sw * ci, -cO * sw - sO * cw * ci},
                          {sO * cw + cO * sw * ci, -sO * sw + cO * cw * ci},
                          {sw * si, cw * si}};
  for (int k = 0; k < 3; k++) {
    r.x[k] = Q[k][0] * rp[0] + Q[k][1] * rp[1];
    v.x[k] = Q[k][0] * vp[0] + Q[k][1] * vp[1];
  }
}

struct Fixture {
  FswGuidOrbitConfig cfg{};
  FswGuidOrbitState st{};
  FswGuidOrbitIn in{};
  FswGuidOrbitOut out{};
  explicit Fixture(int variant = FSW_GUID_ORBIT_NADIR)
  {
    cfg.variant = variant;
    cfg.mu = static_cast<fsw_real>(kMu);
    in.valid = 1;
  }
  FswStatus init() { return fsw_guid_orbit_init(&st, &cfg); }
  FswStatus update() { return fsw_guid_orbit_update(&st, &cfg, &in, &out); }
  void set(V3 r, V3 v)
  {
    for (int k = 0; k < 3; k++) {
      in.r_N[k] = static_cast<fsw_real>(r[k]);
      in.v_N[k] = static_cast<fsw_real>(v[k]);
    }
  }
  void garbage()
  {
    for (int k = 0; k < 3; k++) out.sigma_RN[k] = out.omega_RN_N[k] = out.omega_dot_RN_N[k] = FSW_R(7.0);
  }
};

void expect_safe(const FswGuidOrbitOut& o)
{
  for (int k = 0; k < 3; k++) {
    EXPECT_EQ(o.sigma_RN[k], 0.0);
    EXPECT_EQ(o.omega_RN_N[k], 0.0);
    EXPECT_EQ(o.omega_dot_RN_N[k], 0.0);
  }
}

}  // namespace

// Verifies: REQ-GORB-001
TEST(GuidOrbitConfig, RejectsBadConfigurationsTableDriven)
{
  struct Row {
    const char* why;
    void (*spoil)(FswGuidOrbitConfig*);
  };
  static const Row rows[] = {
      {"variant 2", [](FswGuidOrbitConfig* c) { c->variant = 2; }},
      {"variant -1", [](FswGuidOrbitConfig* c) { c->variant = -1; }},
      {"sigma NaN", [](FswGuidOrbitConfig* c) { c->sigma_BdR[1] = kNaN; }},
      {"sigma Inf", [](FswGuidOrbitConfig* c) { c->sigma_BdR[2] = kInf; }},
      {"sigma norm overflows",
       [](FswGuidOrbitConfig* c) { c->sigma_BdR[0] = std::numeric_limits<fsw_real>::max(); }},
      {"mu 0", [](FswGuidOrbitConfig* c) { c->mu = 0; }},
      {"mu negative", [](FswGuidOrbitConfig* c) { c->mu = FSW_R(-1.0); }},
      {"mu NaN", [](FswGuidOrbitConfig* c) { c->mu = kNaN; }},
      {"mu beyond the maximum", [](FswGuidOrbitConfig* c) { c->mu = FSW_R(1e22); }},
  };
  for (const Row& row : rows) {
    Fixture f;
    row.spoil(&f.cfg);
    EXPECT_EQ(fsw_guid_orbit_check(&f.cfg), FSW_E_CONFIG) << row.why;
    EXPECT_EQ(f.init(), FSW_E_CONFIG) << row.why;
    EXPECT_EQ(f.st.ready, 0);
    f.set(v3(7e6, 0, 0), v3(0, 7.5e3, 0));
    f.garbage();
    EXPECT_EQ(f.update(), FSW_E_NOT_INIT) << row.why;
    expect_safe(f.out);
  }
  Fixture ok(FSW_GUID_ORBIT_VELOCITY);
  ok.cfg.sigma_BdR[0] = FSW_R(3.0);  // any magnitude (shadow-switched)
  EXPECT_EQ(fsw_guid_orbit_check(&ok.cfg), FSW_OK);
}

// Circular equatorial orbit, radius a, theta = n t:
// r = a (c, s, 0), v = n a (-s, c, 0), h along +z.  NADIR:
// R3 = -(c, s, 0), R2 = (0, 0, -1), R1 = R2 x R3 = (-s, c, 0) = v_hat.
// At theta = 0: [RN] = [[0,1,0],[0,0,-1],[-1,0,0]], trace 0, b0 = 1/2,
// b = ((C23-C32), (C31-C13), (C12-C21))/(4 b0) = (-1, -1, 1)/2,
// sigma = b/(1 + b0) = (-1/3, -1/3, 1/3).  omega = n z, omega_dot = 0.
// VELOCITY gives the same frame rows in another order: R1 = v_hat,
// R2 = -z, R3 = R1 x R2 = (-c, -s, 0) = -r_hat: the same DCM on a circle.
// Verifies: REQ-GORB-003
TEST(GuidOrbitNominal, CircularEquatorialHandValues)
{
  const double a = 7e6, n = std::sqrt(kMu / (a * a * a));
  for (int variant : {FSW_GUID_ORBIT_NADIR, FSW_GUID_ORBIT_VELOCITY}) {
    Fixture f(variant);
    ASSERT_EQ(f.init(), FSW_OK);
    f.set(v3(a, 0, 0), v3(0, n * a, 0));
    ASSERT_EQ(f.update(), FSW_OK);
    const double want[3] = {-1.0 / 3, -1.0 / 3, 1.0 / 3};
    for (int k = 0; k < 3; k++) {
      EXPECT_NEAR(f.out.sigma_RN[k], want[k], kt::tol(1e-15, 1e-6)) << variant << " " << k;
      EXPECT_NEAR(f.out.omega_RN_N[k], k == 2 ? n : 0.0, kt::tol(1e-18, 1e-9)) << variant << " " << k;
      EXPECT_NEAR(f.out.omega_dot_RN_N[k], 0.0, kt::tol(1e-21, 1e-12)) << variant << " " << k;
    }
    // at theta = 90 deg: R1 = (-1,0,0), R2 = (0,0,-1), R3 = (0,-1,0)
    f.set(v3(0, a, 0), v3(-n * a, 0, 0));
    ASSERT_EQ(f.update(), FSW_OK);
    double C[3][3];
    mrp2dcm(C, f.out.sigma_RN);
    const double W[3][3] = {{-1, 0, 0}, {0, 0, -1}, {0, -1, 0}};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) EXPECT_NEAR(C[i][j], W[i][j], kt::tol(1e-14, 1e-6)) << i << j;
    EXPECT_NEAR(f.out.omega_RN_N[2], n, kt::tol(1e-18, 1e-9));
  }
}

// Inclined eccentric orbit: omega and omega_dot against central differences
// of the frames of an RK4 propagation (independent of the module).
// Verifies: REQ-GORB-003
TEST(GuidOrbitNominal, EccentricInclinedRatesMatchFiniteDifferencesOfThePropagatedFrame)
{
  if (kt::kFloat) GTEST_SKIP() << "finite differences at 1e-7 need double";
  // [s] inner step (frame -> omega, truncation ~ h^2 omega^2/6 ~ 1e-9 relative)
  // and outer step (omega -> omega_dot)
  const double h = 0.05, ho = 0.5;
  for (int variant : {FSW_GUID_ORBIT_NADIR, FSW_GUID_ORBIT_VELOCITY}) {
    Fixture f(variant);
    ASSERT_EQ(f.init(), FSW_OK);
    for (double nu : {0.3, 1.4, 2.6, -2.0, -0.7}) {
      V3 r0, v0;
      from_elements(r0, v0, 9.0e6, 0.3, 51.6 * kPi / 180, 0.4, 1.1, nu);
      // omega by differences of the frame: [RN]' = -[w_R x][RN] => [w_R x] = -C' C^T
      auto omega_fd = [&](double t, double w[3]) {
        double Cp[3][3], Cm[3][3], C0[3][3];
        V3 rp = r0, vp = v0, rm = r0, vm = v0, rc = r0, vc = v0;
        rk4(rp, vp, t + h, 0.01);
        rk4(rm, vm, t - h, 0.01);
        rk4(rc, vc, t, 0.01);
        ref_frame(Cp, rp, vp, variant);
        ref_frame(Cm, rm, vm, variant);
        ref_frame(C0, rc, vc, variant);
        double Cd[3][3], M[3][3];
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++) Cd[i][j] = (Cp[i][j] - Cm[i][j]) / (2 * h);
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++) s += Cd[i][k] * C0[j][k];
            M[i][j] = -s;
          }
        const double wR[3] = {0.5 * (M[2][1] - M[1][2]), 0.5 * (M[0][2] - M[2][0]), 0.5 * (M[1][0] - M[0][1])};
        for (int k = 0; k < 3; k++) w[k] = C0[0][k] * wR[0] + C0[1][k] * wR[1] + C0[2][k] * wR[2];  // N comp.
      };
      double w0[3], wp[3], wm[3];
      omega_fd(0.0, w0);
      omega_fd(ho, wp);
      omega_fd(-ho, wm);
      f.set(r0, v0);
      ASSERT_EQ(f.update(), FSW_OK);
      const double wn = nrm(v3(w0[0], w0[1], w0[2]));
      double wdn = 0;
      for (int k = 0; k < 3; k++) wdn += std::pow((wp[k] - wm[k]) / (2 * ho), 2);
      wdn = std::sqrt(wdn);
      for (int k = 0; k < 3; k++) {
        EXPECT_NEAR(f.out.omega_RN_N[k], w0[k], 1e-7 * wn) << variant << " nu=" << nu << " k=" << k;
        EXPECT_NEAR(f.out.omega_dot_RN_N[k], (wp[k] - wm[k]) / (2 * ho), 1e-5 * wdn)
            << variant << " nu=" << nu << " k=" << k;
      }
      // the frame itself: sigma gives the independently built [RN]
      double C[3][3], W[3][3];
      mrp2dcm(C, f.out.sigma_RN);
      ref_frame(W, r0, v0, variant);
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) EXPECT_NEAR(C[i][j], W[i][j], 1e-13) << i << j;
    }
  }
}

// Frame properties over random orbits: [RN] orthonormal and right-handed,
// nadir axis R3 = -r_hat, velocity axis R1 = v_hat, R2 = -h_hat, and the
// rates along h_hat with the closed forms' magnitudes.
// Verifies: REQ-GORB-002
TEST(GuidOrbitProperties, FrameOrthonormalRightHandedAndAxesAsDefined)
{
  kt::Rng rng(77);
  for (int trial = 0; trial < 200; trial++) {
    const int variant = trial % 2;
    Fixture f(variant);
    ASSERT_EQ(f.init(), FSW_OK);
    V3 r, v;
    rng.unit3(r.x);
    rng.unit3(v.x);
    r = scl(rng.uniform(6.6e6, 4.2e7), r);
    v = scl(rng.uniform(1e3, 1.1e4), v);
    if (nrm(cross(unit(r), unit(v))) < 0.05) continue;
    f.set(r, v);
    ASSERT_EQ(f.update(), FSW_OK);
    double C[3][3];
    mrp2dcm(C, f.out.sigma_RN);
    const double tl = kt::tol(1e-13, 2e-5);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double s = 0;
        for (int k = 0; k < 3; k++) s += C[i][k] * C[j][k];
        EXPECT_NEAR(s, i == j ? 1.0 : 0.0, tl);
      }
    const V3 R1 = v3(C[0][0], C[0][1], C[0][2]), R2 = v3(C[1][0], C[1][1], C[1][2]), R3 = v3(C[2][0], C[2][1], C[2][2]);
    EXPECT_NEAR(dot(cross(R1, R2), R3), 1.0, tl);
    const V3 hh = unit(cross(r, v));
    for (int k = 0; k < 3; k++) {
      EXPECT_NEAR(R2[k], -hh[k], tl);
      if (variant == FSW_GUID_ORBIT_NADIR)
        EXPECT_NEAR(R3[k], -unit(r)[k], tl);
      else
        EXPECT_NEAR(R1[k], unit(v)[k], tl);
    }
    const double rr = nrm(r), vv = nrm(v), hn = nrm(cross(r, v));
    const double rate = variant == FSW_GUID_ORBIT_NADIR ? hn / (rr * rr) : kMu * hn / (rr * rr * rr * vv * vv);
    const double rv = dot(r, v) / (rr * rr);
    const double rated = variant == FSW_GUID_ORBIT_NADIR ? -2 * rv * rate : rv * (2 * kMu / (rr * vv * vv) - 3) * rate;
    for (int k = 0; k < 3; k++) {
      EXPECT_NEAR(f.out.omega_RN_N[k], rate * hh[k], kt::tol(1e-12, 1e-5) * rate);
      EXPECT_NEAR(f.out.omega_dot_RN_N[k], rated * hh[k], kt::tol(1e-12, 1e-4) * std::fabs(rated) + 1e-30);
    }
  }
}

// The fixed offset: Bd = R rotated by sigma_BdR; [BdN] = [BdR][RN], rates
// unchanged.  sigma_BdR = tan(90deg/4) z: Bd1 = R2, Bd2 = -R1, Bd3 = R3.
// Verifies: REQ-GORB-002
TEST(GuidOrbitNominal, OffsetIsApplied)
{
  const double a = 7e6, n = std::sqrt(kMu / (a * a * a));
  Fixture base, off;
  off.cfg.sigma_BdR[2] = static_cast<fsw_real>(std::tan(kPi / 8));
  ASSERT_EQ(base.init(), FSW_OK);
  ASSERT_EQ(off.init(), FSW_OK);
  V3 r, v;
  from_elements(r, v, a, 0.1, 0.5, 0.2, 0.3, 0.9);
  base.set(r, v);
  off.set(r, v);
  ASSERT_EQ(base.update(), FSW_OK);
  ASSERT_EQ(off.update(), FSW_OK);
  double Cr[3][3], Cb[3][3];
  mrp2dcm(Cr, base.out.sigma_RN);
  mrp2dcm(Cb, off.out.sigma_RN);
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(Cb[0][k], Cr[1][k], kt::tol(1e-14, 1e-6));
    EXPECT_NEAR(Cb[1][k], -Cr[0][k], kt::tol(1e-14, 1e-6));
    EXPECT_NEAR(Cb[2][k], Cr[2][k], kt::tol(1e-14, 1e-6));
    EXPECT_EQ(off.out.omega_RN_N[k], base.out.omega_RN_N[k]);
    EXPECT_EQ(off.out.omega_dot_RN_N[k], base.out.omega_dot_RN_N[k]);
  }
  (void)n;
  // an offset given as its shadow set is the same rotation
  Fixture sh;
  const double s = std::tan(kPi / 8);
  sh.cfg.sigma_BdR[2] = static_cast<fsw_real>(-1.0 / s);
  ASSERT_EQ(sh.init(), FSW_OK);
  sh.set(r, v);
  ASSERT_EQ(sh.update(), FSW_OK);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(sh.out.sigma_RN[k], off.out.sigma_RN[k], kt::tol(1e-14, 1e-6));
}

// Verifies: REQ-GORB-004
TEST(GuidOrbitBadInput, SafeOutputAndNothingChanges)
{
  struct Row {
    const char* why;
    void (*spoil)(FswGuidOrbitIn*);
  };
  static const Row rows[] = {
      {"not valid", [](FswGuidOrbitIn* in) { in->valid = 0; }},
      {"valid 2", [](FswGuidOrbitIn* in) { in->valid = 2; }},
      {"r NaN", [](FswGuidOrbitIn* in) { in->r_N[1] = kNaN; }},
      {"v Inf", [](FswGuidOrbitIn* in) { in->v_N[0] = kInf; }},
      {"r tiny", [](FswGuidOrbitIn* in) { in->r_N[0] = FSW_R(0.5); in->r_N[1] = in->r_N[2] = 0; }},
      {"r zero", [](FswGuidOrbitIn* in) { in->r_N[0] = in->r_N[1] = in->r_N[2] = 0; }},
      {"v zero", [](FswGuidOrbitIn* in) { in->v_N[0] = in->v_N[1] = in->v_N[2] = 0; }},
      {"r parallel to v", [](FswGuidOrbitIn* in) { for (int k = 0; k < 3; k++) in->v_N[k] = FSW_R(1e-3) * in->r_N[k]; }},
      {"r anti-parallel to v", [](FswGuidOrbitIn* in) { for (int k = 0; k < 3; k++) in->v_N[k] = FSW_R(-2e-3) * in->r_N[k]; }},
  };
  for (int variant : {FSW_GUID_ORBIT_NADIR, FSW_GUID_ORBIT_VELOCITY})
    for (const Row& row : rows) {
      Fixture f(variant);
      ASSERT_EQ(f.init(), FSW_OK);
      f.set(v3(7e6, 1e5, -2e5), v3(100, 7.5e3, 300));
      row.spoil(&f.in);
      const FswGuidOrbitState before = f.st;
      f.garbage();
      EXPECT_EQ(f.update(), FSW_E_BAD_INPUT) << row.why;
      expect_safe(f.out);
      EXPECT_EQ(f.st.health.bad_input, 1u) << row.why;
      FswGuidOrbitState after = f.st;
      after.health = before.health;
      EXPECT_EQ(0, std::memcmp(&before, &after, sizeof before)) << row.why;
    }
  // velocity variant: a finite speed so small that the rate overflows
  Fixture f(FSW_GUID_ORBIT_VELOCITY);
  ASSERT_EQ(f.init(), FSW_OK);
  const fsw_real tiny = std::numeric_limits<fsw_real>::denorm_min();
  f.in.r_N[0] = FSW_R(7e6);
  f.in.v_N[1] = tiny;
  EXPECT_EQ(f.update(), FSW_E_BAD_INPUT);
  expect_safe(f.out);
  // not initialised
  Fixture g;
  g.set(v3(7e6, 0, 0), v3(0, 7.5e3, 0));
  EXPECT_EQ(g.update(), FSW_E_NOT_INIT);
  expect_safe(g.out);
}

// Verifies: REQ-GORB-005
TEST(GuidOrbitRepeatability, SameInputSameOutputAcrossReset)
{
  Fixture f(FSW_GUID_ORBIT_VELOCITY);
  f.cfg.sigma_BdR[0] = FSW_R(0.2);
  ASSERT_EQ(f.init(), FSW_OK);
  V3 r, v;
  from_elements(r, v, 2.4e7, 0.7, 1.0, 2.0, 3.0, 0.5);
  f.set(r, v);
  ASSERT_EQ(f.update(), FSW_OK);
  const FswGuidOrbitOut first = f.out;
  fsw_guid_orbit_reset(&f.st);
  f.garbage();
  ASSERT_EQ(f.update(), FSW_OK);
  EXPECT_EQ(0, std::memcmp(&first, &f.out, sizeof first));
  EXPECT_EQ(f.st.health.calls, 2u);
}

// Verifies: REQ-GEN-007
TEST(GuidOrbitNullArgs, EveryNullArgumentAssertsAndReturns)
{
  kt::module_null_args("guid_orbit", fsw_guid_orbit_check, fsw_guid_orbit_init, fsw_guid_orbit_reset,
                       fsw_guid_orbit_update);
}

// MC/DC (docs/coverage.md): every component finite but the magnitude not:
// |r| or |v| = sqrt(3) * (largest real) overflows, and each alone is refused
// by its own condition (|r| >= R_MIN and finite / |v| finite).
// Verifies: REQ-GORB-004
TEST(GuidOrbitBadInput, FiniteComponentsWhoseMagnitudeOverflowsAreRefused)
{
  const fsw_real big = std::numeric_limits<fsw_real>::max();
  for (int which = 0; which < 2; which++) {
    Fixture f;
    ASSERT_EQ(f.init(), FSW_OK);
    f.set(v3(7e6, 1e5, -2e5), v3(100, 7.5e3, 300));
    fsw_real* p = which == 0 ? f.in.r_N : f.in.v_N;
    for (int k = 0; k < 3; k++) p[k] = big;
    f.garbage();
    EXPECT_EQ(f.update(), FSW_E_BAD_INPUT) << which;
    expect_safe(f.out);
    EXPECT_EQ(f.st.health.bad_input, 1u);
  }
}

// MC/DC (docs/coverage.md, guid_orbit's rate check): the rate finite but its
// derivative not.  Nadir frame, |r| = 7e6 m, a finite speed of about a third
// of the largest real at 45 deg to r: |omega| = sin(45) |v| / |r| is about
// 5e-8 of the largest real, finite; |omega_dot| = 2 |(r.v)/r^2| |omega| is
// of the order of (5e-8 largest)^2, which overflows in either real type.
// Refused as bad input, like any finite input whose rates overflow.
// Verifies: REQ-GORB-004
TEST(GuidOrbitBadInput, FiniteRateWhoseDerivativeOverflowsIsRefused)
{
  const fsw_real quarter = std::numeric_limits<fsw_real>::max() / 4;
  Fixture f(FSW_GUID_ORBIT_NADIR);
  ASSERT_EQ(f.init(), FSW_OK);
  f.set(v3(7e6, 0, 0), v3(0, 0, 0));
  f.in.v_N[0] = quarter;
  f.in.v_N[1] = quarter;
  f.garbage();
  EXPECT_EQ(f.update(), FSW_E_BAD_INPUT);
  expect_safe(f.out);
  EXPECT_EQ(f.st.health.bad_input, 1u);
  // the same geometry at an orbital speed is accepted: the overflow alone refuses
  Fixture g(FSW_GUID_ORBIT_NADIR);
  ASSERT_EQ(g.init(), FSW_OK);
  g.set(v3(7e6, 0, 0), v3(5e3, 5e3, 0));
  EXPECT_EQ(g.update(), FSW_OK);
}

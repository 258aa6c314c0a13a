// Faceted surface forces and the exponential atmosphere
// (docs/environment.md): SRP on a flat plate facing the Sun and at 45 deg,
// absorbed, specular and diffuse separately, worked by hand from the
// momentum of the light; drag on a plate and a cube against 1/2 rho C_D A v^2
// with the projected area; torque = r x F; the co-rotating wind; the
// density at every band boundary and its continuity; the ellipsoid height
// against an independent geodetic-height iteration.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sim/earth_time.h"
#include "sim/surface_forces.h"
#include "field_check.h"

namespace {

using Eigen::Vector3d;

constexpr double kP = 1361.0 / 299792458.0;  // [N/m^2] solar pressure at 1 AU

sim::Facet plate(double area, const Vector3d& n, double a, double s, double d)
{
  sim::Facet f;
  f.area = area;
  f.n_B = n;
  f.absorbed = a;
  f.specular = s;
  f.diffuse = d;
  return f;
}

sim::FacetSet one(const sim::Facet& f)
{
  sim::FacetSet s;
  s.facets[0] = f;
  s.count = 1;
  return s;
}

void expect_vec(const Vector3d& got, const Vector3d& want, double tol, const char* what)
{
  EXPECT_LT((got - want).norm(), tol) << what << ": got " << got.transpose() << " want " << want.transpose();
}

TEST(SolarPressure, ConstantIs1361WattsOverC)
{
  EXPECT_NEAR(sim::kSolarPressure1AU, 4.5398e-6, 5e-11);
}

// Plate of area A facing the Sun (n = s): the beam carries momentum flux P.
// Absorbed: all of it is taken, F = -P A s.  Specular: it comes back, F = -2 P A n.
// Diffuse (Lambert): taken, then re-emitted with mean momentum 2/3 of it along
// the normal, F = -P A (s + 2/3 n) = -5/3 P A s.
TEST(SolarPressure, PlateFacingTheSun)
{
  const double A = 2.0;
  const Vector3d s(0.0, 0.6, 0.8);
  for (double flux : {1.0, 0.25}) {
    const double P = kP * flux;
    expect_vec(sim::srp_load(one(plate(A, s, 1, 0, 0)), s, flux).F_B, -P * A * s, 1e-20, "absorbed");
    expect_vec(sim::srp_load(one(plate(A, s, 0, 1, 0)), s, flux).F_B, -2.0 * P * A * s, 1e-20, "specular");
    expect_vec(sim::srp_load(one(plate(A, s, 0, 0, 1)), s, flux).F_B, -5.0 / 3.0 * P * A * s, 1e-20, "diffuse");
  }
  // Facing away or edge-on: nothing.
  EXPECT_EQ(sim::srp_load(one(plate(A, -s, 1, 0, 0)), s, 1.0).F_B, Vector3d::Zero());
  EXPECT_EQ(sim::srp_load(one(plate(A, Vector3d(0.0, 0.8, -0.6), 1, 0, 0)), s, 1.0).F_B, Vector3d::Zero());
}

// Plate normal z, Sun at 45 deg in the x-z plane: s = (1, 0, 1)/sqrt 2, cos = 1/sqrt 2.
// The plate intercepts the beam over A cos: momentum per second P A cos along -s...
//   absorbed: F = -P A cos s                         = -P A (1/2, 0, 1/2)
//   specular: the normal momentum reverses: F = -2 P A cos^2 n = -P A (0, 0, 1)
//   diffuse : -P A cos (s + 2/3 n)                   = -P A (1/2, 0, 1/2 + sqrt 2/3)
// and a mix (0.2, 0.5, 0.3) is the weighted sum.
TEST(SolarPressure, PlateAt45Degrees)
{
  const double A = 3.0, PA = kP * A;
  const Vector3d n = Vector3d::UnitZ();
  const Vector3d s = Vector3d(1.0, 0.0, 1.0) / std::sqrt(2.0);
  const Vector3d Fa = -PA * Vector3d(0.5, 0.0, 0.5);
  const Vector3d Fs = -PA * Vector3d(0.0, 0.0, 1.0);
  const Vector3d Fd = -PA * Vector3d(0.5, 0.0, 0.5 + std::sqrt(2.0) / 3.0);
  expect_vec(sim::srp_load(one(plate(A, n, 1, 0, 0)), s, 1.0).F_B, Fa, 1e-20, "absorbed");
  expect_vec(sim::srp_load(one(plate(A, n, 0, 1, 0)), s, 1.0).F_B, Fs, 1e-20, "specular");
  expect_vec(sim::srp_load(one(plate(A, n, 0, 0, 1)), s, 1.0).F_B, Fd, 1e-20, "diffuse");
  expect_vec(sim::srp_load(one(plate(A, n, 0.2, 0.5, 0.3)), s, 1.0).F_B, 0.2 * Fa + 0.5 * Fs + 0.3 * Fd,
             1e-20, "mixed");
}

// Torque about the reference point is (r - r_ref) x F; two equal plates placed
// symmetrically about the reference give no torque.
TEST(SurfaceForces, TorqueIsLeverArmCrossForce)
{
  const Vector3d s = Vector3d(0.3, -0.4, 0.866).normalized();
  sim::Facet f = plate(1.5, Vector3d::UnitZ(), 0.3, 0.4, 0.3);
  f.r_B = Vector3d(1.0, 2.0, 0.5);
  f.C_D = 2.0;
  const Vector3d r_ref(0.1, 0.0, -0.2);
  const sim::SurfaceLoad srp = sim::srp_load(one(f), s, 1.0, r_ref);
  expect_vec(srp.L_B, (f.r_B - r_ref).cross(srp.F_B), 1e-20, "srp");
  EXPECT_GT(srp.L_B.norm(), 0.0);
  const Vector3d v(-7000.0, 300.0, 2500.0);
  const sim::SurfaceLoad drag = sim::drag_load(one(plate(1.5, -v.normalized(), 1, 0, 0)), v, 1e-12, r_ref);
  EXPECT_EQ(drag.F_B, Vector3d::Zero());  // facing backwards: in the wake
  sim::FacetSet two;
  two.count = 2;
  two.facets[0] = f;
  two.facets[1] = f;
  two.facets[0].r_B = r_ref + Vector3d(0.7, -0.2, 0.0);
  two.facets[1].r_B = r_ref - Vector3d(0.7, -0.2, 0.0);
  const sim::SurfaceLoad sym = sim::srp_load(two, s, 1.0, r_ref);
  EXPECT_LT(sym.L_B.norm(), 1e-22);
  expect_vec(sym.F_B, 2.0 * srp.F_B, 1e-20, "two plates");
  const sim::SurfaceLoad dr = sim::drag_load(one(f), Vector3d(0.0, 0.0, 7500.0), 2e-12, r_ref);
  expect_vec(dr.L_B, (f.r_B - r_ref).cross(dr.F_B), 1e-18, "drag");
}

// Drag: a plate facing the flow feels 1/2 rho C_D A v^2 against the velocity;
// at 60 deg incidence its projected area halves; a cube shows its projected
// area (A along a face normal, sqrt 2 A along a face diagonal).
TEST(Drag, PlateAndCubeAgainstTheFormula)
{
  const double rho = 3.725e-12, CD = 2.2, A = 0.8, v = 7660.0;
  const double q = 0.5 * rho * v * v;
  sim::Facet f = plate(A, Vector3d::UnitX(), 1, 0, 0);
  f.C_D = CD;
  expect_vec(sim::drag_load(one(f), Vector3d(v, 0.0, 0.0), rho).F_B, Vector3d(-q * CD * A, 0.0, 0.0), 1e-18,
             "facing");
  const Vector3d v60 = v * Vector3d(0.5, std::sqrt(3.0) / 2.0, 0.0);
  expect_vec(sim::drag_load(one(f), v60, rho).F_B, -0.5 * q * CD * A * v60 / v, 1e-18, "60 deg");
  sim::FacetSet cube;
  cube.count = 6;
  for (int k = 0; k < 6; ++k) {
    cube.facets[k] = plate(A, (k < 3 ? 1.0 : -1.0) * Vector3d::Unit(k % 3), 1, 0, 0);
    cube.facets[k].C_D = CD;
    cube.facets[k].r_B = 0.5 * cube.facets[k].n_B;
  }
  expect_vec(sim::drag_load(cube, Vector3d(0.0, -v, 0.0), rho).F_B, Vector3d(0.0, q * CD * A, 0.0), 1e-18,
             "cube face");
  const Vector3d vd = v * Vector3d(1.0, 1.0, 0.0) / std::sqrt(2.0);
  const sim::SurfaceLoad cd = sim::drag_load(cube, vd, rho);
  expect_vec(cd.F_B, -q * CD * std::sqrt(2.0) * A * vd / v, 1e-18, "cube diagonal");
  EXPECT_LT(cd.L_B.norm(), 1e-22);  // symmetric about the centre
  EXPECT_EQ(sim::drag_load(cube, Vector3d::Zero(), rho).F_B, Vector3d::Zero());
}

// At the equator r = R x, the air moves with omega R along y.
TEST(Drag, WindCoRotatesWithTheEarth)
{
  const double R = 6.778e6, w = 7.292115e-5;
  expect_vec(sim::wind_velocity_N(Vector3d(R, 0.0, 0.0), Vector3d(0.0, 7669.0, 0.0)),
             Vector3d(0.0, 7669.0 - w * R, 0.0), 1e-9, "equator");
  // Over the pole the air is still; along z nothing changes.
  expect_vec(sim::wind_velocity_N(Vector3d(0.0, 0.0, R), Vector3d(7669.0, 0.0, 0.0)),
             Vector3d(7669.0, 0.0, 0.0), 1e-12, "pole");
  const Vector3d r(3.0e6, -4.0e6, 4.5e6);
  expect_vec(sim::wind_velocity_N(r, Vector3d::Zero()), Vector3d(-w * 4.0e6, -w * 3.0e6, 0.0), 1e-9, "general");
}

// Vallado Table 8-4: base altitudes [km] and nominal densities [kg/m^3].
constexpr double kH0km[28] = {0,   25,  30,  40,  50,  60,  70,  80,  90,  100, 110, 120, 130, 140,
                              150, 180, 200, 250, 300, 350, 400, 450, 500, 600, 700, 800, 900, 1000};
constexpr double kRho0[28] = {1.225,     3.899e-2,  1.774e-2,  3.972e-3,  1.057e-3,  3.206e-4,  8.770e-5,
                              1.905e-5,  3.396e-6,  5.297e-7,  9.661e-8,  2.438e-8,  8.484e-9,  3.845e-9,
                              2.070e-9,  5.464e-10, 2.789e-10, 7.248e-11, 2.418e-11, 9.518e-12, 3.725e-12,
                              1.585e-12, 6.967e-13, 1.454e-13, 3.614e-14, 1.170e-14, 5.245e-15, 3.019e-15};

TEST(Atmosphere, NominalDensityAtEveryBandBase)
{
  const sim::ExponentialAtmosphere atm;
  for (int k = 0; k < 28; ++k) EXPECT_NEAR(sim::density(atm, kH0km[k] * 1e3), kRho0[k], 1e-14 * kRho0[k]) << kH0km[k];
  // Inside a band: 420 km in the 400 km band (H = 58.515 km); one scale height
  // above 500 km (H = 63.822 km) the density is rho0 / e.
  EXPECT_NEAR(sim::density(atm, 420e3), 3.725e-12 * std::exp(-20.0 / 58.515), 1e-26);
  EXPECT_NEAR(sim::density(atm, 563.822e3), 6.967e-13 / std::exp(1.0), 1e-27);
  // Beyond the table: the last band's law continues; below 0 the first band's.
  EXPECT_NEAR(sim::density(atm, 1500e3), 3.019e-15 * std::exp(-500.0 / 268.0), 1e-29);
  EXPECT_NEAR(sim::density(atm, -1e3), 1.225 * std::exp(1.0 / 7.249), 1e-12);
  // The scale factor multiplies.
  EXPECT_NEAR(sim::density(sim::ExponentialAtmosphere{2.5}, 420e3), 2.5 * sim::density(atm, 420e3), 1e-26);
}

// The table is not exactly continuous: the lower band's law reaches the next
// base altitude within -0.14 % (25 km) and within 1e-4 relative from 30 km
// up (worked by hand from the table: the largest, +0.008 %, at 110 km).
TEST(Atmosphere, ContinuityAtTheBandBoundaries)
{
  const sim::ExponentialAtmosphere atm;
  for (int k = 1; k < 28; ++k) {
    const double h = kH0km[k] * 1e3;
    const double jump = sim::density(atm, h - 1e-6) / sim::density(atm, h) - 1.0;
    EXPECT_LT(std::abs(jump), k == 1 ? 1.4e-3 : 1e-4) << kH0km[k] << " km: " << jump;
  }
  EXPECT_GT(sim::density(atm, 25e3 - 1e-6), 0.998 * 3.899e-2);
  EXPECT_LT(sim::density(atm, 25e3 - 1e-6), 3.899e-2);  // the 25 km step is upward (-0.136 %)
}

// Geodetic height by fixed-point iteration on the geodetic latitude
// (independent of the model's radial formula).
double geodetic_height(const Vector3d& r)
{
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double p = std::hypot(r.x(), r.y());
  double phi = std::atan2(r.z(), p * (1.0 - e2)), h = 0.0;
  for (int i = 0; i < 50; ++i) {
    const double N = a / std::sqrt(1.0 - e2 * std::sin(phi) * std::sin(phi));
    h = p / std::cos(phi) - N;
    phi = std::atan2(r.z(), p * (1.0 - e2 * N / (N + h)));
  }
  return h;
}

// Found: at most 0.07 m, 1.2 m, 2.2 m and 4.9 m at 0, 200, 400 and 1000 km.
TEST(Atmosphere, EllipsoidHeight)
{
  const double a = 6378137.0, b = a * (1.0 - 1.0 / 298.257223563);
  EXPECT_NEAR(sim::ellipsoid_height(Vector3d(a + 400e3, 0.0, 0.0)), 400e3, 1e-8);
  EXPECT_NEAR(sim::ellipsoid_height(Vector3d(0.0, 0.0, -(b + 400e3))), 400e3, 1e-8);
  for (double h : {0.0, 200e3, 400e3, 1000e3}) {
    double worst = 0.0;
    for (double lat_deg = -89.0; lat_deg <= 89.0; lat_deg += 1.0) {
      const double lat = lat_deg * 3.14159265358979323846 / 180.0;  // geocentric
      const Vector3d u(std::cos(lat) * std::cos(0.4), std::cos(lat) * std::sin(0.4), std::sin(lat));
      const Vector3d r = u * (a + h);  // any radius: compare the two heights there
      worst = std::max(worst, std::abs(sim::ellipsoid_height(r) - geodetic_height(r)));
    }
    // Radius and normal differ by at most ~f (where sin 2 phi = 1), so the
    // radial height exceeds the normal one by about h f^2 / 2 (5.6e-6 h).
    const double f = 1.0 / 298.257223563;
    EXPECT_LT(worst, 0.1 + h * f * f / 2.0) << h;
  }
}

TEST(SurfaceForces, RejectedFieldsAreNamed)
{
  sim::FacetSet s;
  s.count = 2;
  s.facets[0] = plate(1.0, Vector3d::UnitX(), 1, 0, 0);
  s.facets[1] = plate(1.0, Vector3d::UnitX(), 1, 0, 0);
  EXPECT_NO_THROW(sim::validate(s));
  const auto expect_field = [](const sim::FacetSet& bad, const char* field) {
    simtest::expect_rejects_field([&] { sim::validate(bad, "facets"); }, field);
  };
  sim::FacetSet b = s;
  b.facets[1].area = 0.0;
  expect_field(b, "facets[1].area");
  b = s;
  b.facets[1].n_B = Vector3d(1.0, 0.1, 0.0);
  expect_field(b, "facets[1].n_B");
  b = s;
  b.facets[0].specular = 0.5;
  expect_field(b, "facets[0].absorbed + specular + diffuse");
  b = s;
  b.facets[0].diffuse = -0.1;
  b.facets[0].absorbed = 1.1;
  expect_field(b, "facets[0].absorbed");
  b = s;
  b.facets[1].C_D = NAN;
  expect_field(b, "facets[1].C_D");
  b = s;
  b.count = sim::kMaxFacets + 1;
  expect_field(b, "facets.count");
  EXPECT_THROW(sim::validate(sim::ExponentialAtmosphere{-1.0}), std::invalid_argument);
}

}  // namespace

// surface_forces: see sim/surface_forces.h and docs/environment.md.
#include "sim/surface_forces.h"

#include <cmath>
#include <string>

#include "sim/earth_time.h"  // kOmegaEarth
#include "validate_util.h"

namespace sim {

using Eigen::Vector3d;

namespace {

constexpr double kUnitTol = 1e-9;  // [-] on |n| and on the sum of the optical fractions

struct Band {
  double h0;    // [m] base altitude
  double rho0;  // [kg/m^3] nominal density at h0
  double H;     // [m] scale height
};

// Vallado, Fundamentals of Astrodynamics and Applications, Table 8-4.
constexpr Band kBands[] = {
    {0.0e3, 1.225, 7.249e3},        {25.0e3, 3.899e-2, 6.349e3},   {30.0e3, 1.774e-2, 6.682e3},
    {40.0e3, 3.972e-3, 7.554e3},    {50.0e3, 1.057e-3, 8.382e3},   {60.0e3, 3.206e-4, 7.714e3},
    {70.0e3, 8.770e-5, 6.549e3},    {80.0e3, 1.905e-5, 5.799e3},   {90.0e3, 3.396e-6, 5.382e3},
    {100.0e3, 5.297e-7, 5.877e3},   {110.0e3, 9.661e-8, 7.263e3},  {120.0e3, 2.438e-8, 9.473e3},
    {130.0e3, 8.484e-9, 12.636e3},  {140.0e3, 3.845e-9, 16.149e3}, {150.0e3, 2.070e-9, 22.523e3},
    {180.0e3, 5.464e-10, 29.740e3}, {200.0e3, 2.789e-10, 37.105e3}, {250.0e3, 7.248e-11, 45.546e3},
    {300.0e3, 2.418e-11, 53.628e3}, {350.0e3, 9.518e-12, 53.298e3}, {400.0e3, 3.725e-12, 58.515e3},
    {450.0e3, 1.585e-12, 60.828e3}, {500.0e3, 6.967e-13, 63.822e3}, {600.0e3, 1.454e-13, 71.835e3},
    {700.0e3, 3.614e-14, 88.667e3}, {800.0e3, 1.170e-14, 124.64e3}, {900.0e3, 5.245e-15, 181.05e3},
    {1000.0e3, 3.019e-15, 268.00e3},
};
constexpr int kNumBands = static_cast<int>(sizeof(kBands) / sizeof(kBands[0]));

}  // namespace

void validate(const Facet& f, const char* name)
{
  const std::string n(name);
  detail::require_positive(n + ".area", f.area);
  detail::require_finite(n + ".n_B", f.n_B);
  if (!(std::abs(f.n_B.norm() - 1.0) <= kUnitTol)) detail::fail_vec(n + ".n_B", f.n_B, "must be a unit vector");
  detail::require_finite(n + ".r_B", f.r_B);
  const double fr[3] = {f.absorbed, f.specular, f.diffuse};
  const char* names[3] = {".absorbed", ".specular", ".diffuse"};
  for (int i = 0; i < 3; ++i) {
    detail::require_non_negative(n + names[i], fr[i]);
    if (fr[i] > 1.0) detail::fail(n + names[i], fr[i], "must be <= 1");
  }
  const double sum = f.absorbed + f.specular + f.diffuse;
  if (!(std::abs(sum - 1.0) <= kUnitTol))
    detail::fail(n + ".absorbed + specular + diffuse", sum, "must be 1");
  detail::require_non_negative(n + ".C_D", f.C_D);
}

void validate(const FacetSet& s, const char* name)
{
  const std::string n(name);
  if (s.count < 0 || s.count > kMaxFacets) detail::fail(n + ".count", s.count, "must be in [0, kMaxFacets]");
  for (int i = 0; i < s.count; ++i) validate(s.facets[i], (n + "[" + std::to_string(i) + "]").c_str());
}

SurfaceLoad srp_load(const FacetSet& s, const Vector3d& s_B, double flux_scale, const Vector3d& r_ref_B)
{
  SurfaceLoad out;
  const double P = kSolarPressure1AU * flux_scale;
  for (int i = 0; i < s.count; ++i) {
    const Facet& f = s.facets[i];
    const double c = f.n_B.dot(s_B);
    if (!(c > 0.0)) continue;  // facing away (or edge-on)
    const Vector3d F =
        (-P * f.area * c) * ((1.0 - f.specular) * s_B + (2.0 * (f.specular * c + f.diffuse / 3.0)) * f.n_B);
    out.F_B += F;
    out.L_B += (f.r_B - r_ref_B).cross(F);
  }
  return out;
}

SurfaceLoad drag_load(const FacetSet& s, const Vector3d& v_rel_B, double rho, const Vector3d& r_ref_B)
{
  SurfaceLoad out;
  const double v = v_rel_B.norm();
  if (!(v > 0.0) || rho == 0.0) return out;
  const Vector3d v_hat = v_rel_B / v;
  const double q = 0.5 * rho * v * v;  // dynamic pressure [Pa]
  for (int i = 0; i < s.count; ++i) {
    const Facet& f = s.facets[i];
    const double c = f.n_B.dot(v_hat);
    if (!(c > 0.0)) continue;  // in the wake
    const Vector3d F = (-q * f.C_D * f.area * c) * v_hat;
    out.F_B += F;
    out.L_B += (f.r_B - r_ref_B).cross(F);
  }
  return out;
}

Vector3d wind_velocity_N(const Vector3d& r_N, const Vector3d& v_N)
{
  return v_N - Vector3d(-kOmegaEarth * r_N.y(), kOmegaEarth * r_N.x(), 0.0);
}

double ellipsoid_height(const Vector3d& r_N)
{
  const double a = kWgs84A, b = kWgs84A * (1.0 - kWgs84F);
  const double r = r_N.norm();
  const double sin2 = (r_N.z() / r) * (r_N.z() / r);
  return r - a * b / std::sqrt(b * b * (1.0 - sin2) + a * a * sin2);
}

void validate(const ExponentialAtmosphere& a, const char* name)
{
  detail::require_non_negative(std::string(name) + ".scale", a.scale);
}

double density(const ExponentialAtmosphere& a, double h)
{
  int k = 0;
  while (k + 1 < kNumBands && h >= kBands[k + 1].h0) ++k;
  const Band& b = kBands[k];
  return a.scale * b.rho0 * std::exp(-(h - b.h0) / b.H);
}

}  // namespace sim

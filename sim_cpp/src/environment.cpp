// environment: see sim/environment.h.  docs/dynamics.md §0, §6, §9.3, §11.
#include "sim/environment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sim/units.h"
#include "validate_util.h"

namespace sim {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {
constexpr int kKeplerMaxIter = 60;  // Newton converges in < 10 for e < 0.99 or e > 1.01
constexpr double kKeplerTol = 1e-15;  // [rad] on the anomaly step
}  // namespace

CentralBody mars() { return CentralBody{kMuMars, kRadiusMars}; }
CentralBody earth() { return CentralBody{kMuEarth, kRadiusEarth}; }

void validate(const SunParams& p, const char* name)
{
  const std::string n(name);
  detail::require_finite(n + ".r_SunN_N0", p.r_SunN_N0);
  if (!(p.r_SunN_N0.norm() > 0.0)) detail::fail_vec(n + ".r_SunN_N0", p.r_SunN_N0, "must be non-zero");
  detail::require_finite(n + ".n", p.n);
}

void validate(const CentralBody& b, const char* name)
{
  const std::string n(name);
  detail::require_non_negative(n + ".mu", b.mu);
  detail::require_non_negative(n + ".radius", b.radius);
}

Vector3d point_mass_gravity(double mu, const Vector3d& r_N)
{
  if (mu == 0.0) return Vector3d::Zero();
  const double r = r_N.norm();
  return (-mu / (r * r * r)) * r_N;
}

Vector3d j2_acceleration(double mu, double J2, double R, const Vector3d& r_N)
{
  if (J2 == 0.0 || mu == 0.0) return Vector3d::Zero();
  const double r2 = r_N.squaredNorm();
  const double r = std::sqrt(r2);
  const double k = -1.5 * J2 * mu * R * R / (r2 * r2 * r);  // -(3/2) J2 mu R^2 / r^5
  const double q = 5.0 * r_N.z() * r_N.z() / r2;
  return Vector3d(k * r_N.x() * (1.0 - q), k * r_N.y() * (1.0 - q), k * r_N.z() * (3.0 - q));
}

double j2_potential(double mu, double J2, double R, const Vector3d& r_N)
{
  if (J2 == 0.0 || mu == 0.0) return 0.0;
  const double r2 = r_N.squaredNorm();
  const double r = std::sqrt(r2);
  return 0.5 * mu * J2 * R * R / (r2 * r) * (3.0 * r_N.z() * r_N.z() / r2 - 1.0);
}

Vector3d sun_position_N(const SunParams& p, double t)
{
  if (p.n == 0.0) return p.r_SunN_N0;
  const double c = std::cos(p.n * t), s = std::sin(p.n * t);
  const Vector3d& r = p.r_SunN_N0;
  return Vector3d(c * r.x() - s * r.y(), s * r.x() + c * r.y(), r.z());
}

Vector3d sun_direction_B(const Matrix3d& dcm_BN, const Vector3d& r_scN_N, const Vector3d& r_SunN_N)
{
  return dcm_BN * (r_SunN_N - r_scN_N).normalized();
}

double solar_flux_scale(const Vector3d& r_scN_N, const Vector3d& r_SunN_N)
{
  const double d = (r_SunN_N - r_scN_N).norm() / kAU;
  return 1.0 / (d * d);
}

double illumination_factor(const Vector3d& r_scN_N, const Vector3d& r_SunN_N, double R_body,
                           double R_sun)
{
  if (R_body <= 0.0) return 1.0;
  const Vector3d to_sun = r_SunN_N - r_scN_N;
  const Vector3d to_body = -r_scN_N;
  const double d_sun = to_sun.norm(), d_body = to_body.norm();
  if (d_body <= R_body) return 0.0;  // inside the body
  const double a = std::asin(std::min(1.0, R_sun / d_sun));  // apparent Sun radius
  const double b = std::asin(R_body / d_body);               // apparent body radius
  // Angular separation of the disk centres, by atan2 (acos of the cosine
  // loses sqrt(eps) near 0 and pi).
  const double c = std::atan2(to_sun.cross(to_body).norm(), to_sun.dot(to_body));
  if (c >= a + b) return 1.0;              // no overlap
  if (c <= b - a) return 0.0;              // total eclipse
  if (c <= a - b) return 1.0 - (b * b) / (a * a);  // annular
  // Partial overlap of two disks (flat-disk approximation, angles ~< 0.1 rad):
  // the lens a^2 al + b^2 be - c y, with y the half-chord and al, be its
  // half-angles seen from the Sun's and the body's disk centres.  Near a
  // contact (c -> a + b, or c -> b - a at the edge of the umbra) the small
  // factors of the triangle (a, b, c) are formed directly, so that y, the
  // chord's distances x1, x2 from the centres and the angles keep their
  // relative precision (acos of (c^2 + a^2 - b^2)/(2ac) near +-1 lost
  // sqrt(eps) ~ 1.5e-8 rad there, up to ~3e-4 of the factor).
  const double p1 = a + b - c;  // > 0: the disks overlap
  const double p2 = c + a - b;  // > 0: not total
  const double p3 = c + b - a;  // > 0: not annular
  const double p4 = a + b + c;
  const double y = std::sqrt(p1 * p2 * p3 * p4) / (2.0 * c);
  const double x1 = (p2 * p4 - p1 * p3) / (4.0 * c);  // (c^2 + a^2 - b^2) / (2c)
  const double x2 = (p3 * p4 - p1 * p2) / (4.0 * c);  // (c^2 + b^2 - a^2) / (2c)
  const double area = a * a * std::atan2(y, x1) + b * b * std::atan2(y, x2) - c * y;
  return std::clamp(1.0 - area / (kPi * a * a), 0.0, 1.0);
}

OrbitElements elements_from_rv(double mu, const Vector3d& r_N, const Vector3d& v_N)
{
  OrbitElements el;
  const double r = r_N.norm();
  el.energy = 0.5 * v_N.squaredNorm() - mu / r;
  el.h_N = r_N.cross(v_N);
  const Vector3d e_vec = v_N.cross(el.h_N) / mu - r_N / r;
  el.e = e_vec.norm();
  const double p = el.h_N.squaredNorm() / mu;  // semi-latus rectum
  el.r_p = p / (1.0 + el.e);
  el.a = el.energy == 0.0 ? std::numeric_limits<double>::infinity() : -mu / (2.0 * el.energy);
  el.r_a = el.e < 1.0 ? p / (1.0 - el.e) : std::numeric_limits<double>::infinity();
  return el;
}

OrbitState conic_state_from_periapsis(double mu, double r_p, double e, double t)
{
  if (!(mu > 0.0)) detail::fail("conic.mu", mu, "must be > 0");
  if (!(r_p > 0.0)) detail::fail("conic.r_p", r_p, "must be > 0");
  if (!(e >= 0.0) || e == 1.0) detail::fail("conic.e", e, "must be >= 0 and != 1 (no parabolas)");
  const double p = r_p * (1.0 + e);
  double nu;  // true anomaly
  if (e < 1.0) {
    const double a = r_p / (1.0 - e);
    const double M = std::sqrt(mu / (a * a * a)) * t;
    double E = e < 0.8 ? M : kPi * (M < 0 ? -1.0 : 1.0);
    for (int i = 0; i < kKeplerMaxIter; ++i) {
      const double dE = (E - e * std::sin(E) - M) / (1.0 - e * std::cos(E));
      E -= dE;
      if (std::abs(dE) < kKeplerTol) break;
    }
    nu = 2.0 * std::atan2(std::sqrt(1.0 + e) * std::sin(0.5 * E), std::sqrt(1.0 - e) * std::cos(0.5 * E));
  } else {
    const double a = r_p / (e - 1.0);  // |a|
    const double M = std::sqrt(mu / (a * a * a)) * t;
    double H = std::asinh(M / e);
    for (int i = 0; i < kKeplerMaxIter; ++i) {
      const double dH = (e * std::sinh(H) - H - M) / (e * std::cosh(H) - 1.0);
      H -= dH;
      if (std::abs(dH) < kKeplerTol * std::max(1.0, std::abs(H))) break;
    }
    nu = 2.0 * std::atan(std::sqrt((e + 1.0) / (e - 1.0)) * std::tanh(0.5 * H));
  }
  const double r = p / (1.0 + e * std::cos(nu));
  const double vf = std::sqrt(mu / p);
  OrbitState s;
  s.r_N = Vector3d(r * std::cos(nu), r * std::sin(nu), 0.0);
  s.v_N = Vector3d(-vf * std::sin(nu), vf * (e + std::cos(nu)), 0.0);
  return s;
}

}  // namespace sim

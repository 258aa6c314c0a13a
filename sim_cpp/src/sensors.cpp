// sensors: see sim/sensors.h.  docs/dynamics.md §9.
#include "sim/sensors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/attitude.h"
#include "sim/environment.h"
#include "validate_util.h"

namespace sim {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::Vector4d;

constexpr double kOrthoTol = 1e-9;     // [-] max |R R^T - I| of a typed-in DCM
constexpr double kUnitTol = 1e-9;      // [-] on |n_hat| - 1
constexpr double kKellyOff = 1e-10;    // [-] k_kelly at or below this disables Kelly (§9.3)

void require_dcm(const std::string& field, const Matrix3d& R)
{
  if (!R.allFinite()) detail::fail(field, R.cwiseAbs().maxCoeff(), "must be finite");
  const double err = (R * R.transpose() - Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (err > kOrthoTol) detail::fail(field + " (max |R R^T - I|)", err, "must be orthonormal");
  if (!(R.determinant() > 0.0)) detail::fail(field + " (det)", R.determinant(), "must be a rotation");
}

void require_period(const std::string& field, int64_t p)
{
  if (!(p > 0)) detail::fail(field, static_cast<double>(p), "must be > 0");
}

void require_name(const std::string& field, const std::string& n)
{
  if (n.empty()) detail::fail(field + ".size()", 0.0, "stream name must not be empty");
}

bool due(int64_t t_ns, int64_t period_ns) { return t_ns % period_ns == 0; }

void require_scale_error(const std::string& field, const Vector3d& e)
{
  detail::require_finite(field, e);
  if (!(e.minCoeff() > -1.0)) detail::fail(field + " (min)", e.minCoeff(), "must be > -1");
}

// Quantises each axis, then clips it at +-limit (limit > 0); true if any axis was clipped.
bool quantize_and_clip(Vector3d& v, double lsb, double limit)
{
  bool clipped = false;
  for (int i = 0; i < 3; ++i) {
    v(i) = quantize(v(i), lsb);
    if (limit > 0.0 && std::abs(v(i)) > limit) {
      v(i) = std::copysign(limit, v(i));
      clipped = true;
    }
  }
  return clipped;
}

double checked_noise_scale(const std::string& name, double k)
{
  if (!(k >= 0.0) || !std::isfinite(k)) detail::fail(name + ".noise_scale", k, "must be finite and >= 0");
  return k;
}

}  // namespace

void Gyro::set_noise_scale(double k) { k_noise_ = checked_noise_scale(p_.name, k); }
void StarTracker::set_noise_scale(double k) { k_noise_ = checked_noise_scale(p_.name, k); }
void CoarseSunSensor::set_noise_scale(double k) { k_noise_ = checked_noise_scale(p_.name, k); }
void Magnetometer::set_noise_scale(double k) { k_noise_ = checked_noise_scale(p_.name, k); }
void WheelTachometers::set_noise_scale(int i, double k)
{
  if (i < 0 || i >= p_.num_rw) throw std::out_of_range("tach(" + p_.name + ").noise_scale: no wheel " + std::to_string(i));
  k_noise_[static_cast<size_t>(i)] = checked_noise_scale(p_.name, k);
}

double quantize(double x, double lsb)
{
  if (!(lsb > 0.0)) return x;
  const double q = lsb * std::floor(std::abs(x) / lsb);
  return x < 0.0 ? -q : q;
}

// ------------------------------------------------------------------ gyro

Gyro::Gyro(GyroParams p, const SensorContext& ctx)
    : p_(std::move(p)), noise_(ctx.noise), rng_(ctx.run_seed, p_.name)
{
  using namespace detail;
  const std::string n = "gyro(" + p_.name + ")";
  require_name(n + ".name", p_.name);
  require_dcm(n + ".dcm_PB", p_.dcm_PB);
  require_period(n + ".period_ns", p_.period_ns);
  require_non_negative(n + ".sigma_ARW", p_.sigma_ARW);
  require_non_negative(n + ".sigma_RRW", p_.sigma_RRW);
  require_finite(n + ".b0", p_.b0);
  require_scale_error(n + ".scale_error", p_.scale_error);
  require_non_negative(n + ".lsb", p_.lsb);
  require_non_negative(n + ".omega_max", p_.omega_max);
}

bool Gyro::update(const SensorTruth& truth)
{
  if (!due(truth.t_ns, p_.period_ns)) return false;
  Vector3d w = p_.dcm_PB * truth.omega_BN_B;
  if (noise_) {
    const double dt_s = static_cast<double>(p_.period_ns) * 1e-9;
    const Vector3d eta = rng_.normal3();
    const Vector3d nu = rng_.normal3();
    w += b_ + p_.b0 + (k_noise_ * p_.sigma_ARW / std::sqrt(dt_s)) * eta;
    w = w.cwiseProduct(Vector3d::Ones() + p_.scale_error);
    b_ += (k_noise_ * p_.sigma_RRW * std::sqrt(dt_s)) * nu;
  }
  out_.saturated = quantize_and_clip(w, p_.lsb, p_.omega_max);
  out_.omega_PN_P = w;
  out_.t_ns = truth.t_ns;
  out_.valid = true;
  return true;
}

// ---------------------------------------------------------- star tracker

StarTracker::StarTracker(StarTrackerParams p, const SensorContext& ctx)
    : p_(std::move(p)), cos_exclusion_(std::cos(p_.sun_exclusion)), noise_(ctx.noise), rng_(ctx.run_seed, p_.name)
{
  using namespace detail;
  const std::string n = "star_tracker(" + p_.name + ")";
  require_name(n + ".name", p_.name);
  require_dcm(n + ".dcm_CB", p_.dcm_CB);
  require_period(n + ".period_ns", p_.period_ns);
  require_non_negative(n + ".sigma_cross", p_.sigma_cross);
  require_non_negative(n + ".sigma_bore", p_.sigma_bore);
  require_non_negative(n + ".sun_exclusion", p_.sun_exclusion);
}

bool StarTracker::update(const SensorTruth& truth)
{
  if (!due(truth.t_ns, p_.period_ns)) return false;
  const Matrix3d dcm_BN = dcm_BN_from_sigma(truth.sigma_BN);
  Matrix3d dcm_CN = p_.dcm_CB * dcm_BN;
  if (noise_) {
    const Vector3d eta = rng_.normal3();
    const double sx = k_noise_ * p_.sigma_cross, sb = k_noise_ * p_.sigma_bore;
    const Vector3d delta(sx * eta.x(), sx * eta.y(), sb * eta.z());
    dcm_CN = rotation_from_vector(-delta) * dcm_CN;
  }
  out_.q_CN = quaternion_from_dcm(dcm_CN);
  out_.sigma_CN = sigma_from_quaternion(out_.q_CN);
  out_.valid = true;
  if (p_.sun_exclusion > 0.0) {
    const Vector3d s_C = p_.dcm_CB * sun_direction_B(dcm_BN, truth.r_BN_N, truth.r_SunN_N);
    // angle(s_C, z_C) < sun_exclusion, compared as cosines (acos is decreasing;
    // they differ only within an ulp of the boundary, and >= keeps an exclusion
    // whose cosine rounds to 1 excluding the exactly-aligned Sun as acos did)
    if (std::clamp(s_C.z(), -1.0, 1.0) >= cos_exclusion_) out_.valid = false;
  }
  out_.t_ns = truth.t_ns;
  return true;
}

// ---------------------------------------------------- coarse sun sensors

CoarseSunSensor::CoarseSunSensor(CssParams p, const SensorContext& ctx)
    : p_(std::move(p)), cos_fov_(std::cos(p_.fov_half)), noise_(ctx.noise), rng_(ctx.run_seed, p_.name)
{
  using namespace detail;
  const std::string n = "css(" + p_.name + ")";
  require_name(n + ".name", p_.name);
  require_finite(n + ".n_hat_B", p_.n_hat_B);
  if (std::abs(p_.n_hat_B.norm() - 1.0) > kUnitTol) fail_vec(n + ".n_hat_B", p_.n_hat_B, "must be a unit vector");
  require_positive(n + ".fov_half", p_.fov_half);
  if (p_.fov_half > 0.5 * 3.14159265358979323846 + 1e-15)
    fail(n + ".fov_half", p_.fov_half, "must be <= pi/2");
  require_finite(n + ".k_kelly", p_.k_kelly);
  require_positive(n + ".scale", p_.scale);
  require_finite(n + ".bias", p_.bias);
  require_non_negative(n + ".sigma", p_.sigma);
  require_finite(n + ".albedo", p_.albedo);
  if (std::isnan(p_.y_min)) fail(n + ".y_min", p_.y_min, "must not be NaN");
  if (std::isnan(p_.y_max) || !(p_.y_max > p_.y_min)) fail(n + ".y_max", p_.y_max, "must be > y_min");
  require_period(n + ".period_ns", p_.period_ns);
}

SunGeometry sun_geometry(const SensorTruth& truth)
{
  SunGeometry g;
  g.s_B = sun_direction_B(dcm_BN_from_sigma(truth.sigma_BN), truth.r_BN_N, truth.r_SunN_N);
  g.flux = solar_flux_scale(truth.r_BN_N, truth.r_SunN_N) * truth.f_illum;
  return g;
}

bool CoarseSunSensor::update(const SensorTruth& truth)
{
  if (!due(truth.t_ns, p_.period_ns)) return false;
  return update(truth, sun_geometry(truth));
}

bool CoarseSunSensor::update(const SensorTruth& truth, const SunGeometry& sun)
{
  if (!due(truth.t_ns, p_.period_ns)) return false;
  const double cos_inc = p_.n_hat_B.dot(sun.s_B);
  double gamma = cos_inc >= cos_fov_ ? cos_inc : 0.0;
  if (p_.k_kelly > kKellyOff) gamma *= 1.0 - std::exp(-gamma * gamma / p_.k_kelly);
  gamma *= sun.flux;
  double signal = gamma + p_.albedo;
  if (noise_) signal += p_.bias + (k_noise_ * p_.sigma) * rng_.normal();
  out_.gamma = gamma;
  out_.y = std::clamp(p_.scale * signal, p_.y_min, p_.y_max);
  out_.t_ns = truth.t_ns;
  out_.valid = true;
  return true;
}

// -------------------------------------------------- wheel tachometers

WheelTachometers::WheelTachometers(TachParams p, const SensorContext& ctx)
    : p_(std::move(p)), noise_(ctx.noise), rng_(ctx.run_seed, p_.name)
{
  using namespace detail;
  const std::string n = "tach(" + p_.name + ")";
  require_name(n + ".name", p_.name);
  if (p_.num_rw < 0 || p_.num_rw > kMaxWheels)
    fail(n + ".num_rw", p_.num_rw, "must be in [0, kMaxWheels]");
  require_non_negative(n + ".sigma", p_.sigma);
  require_non_negative(n + ".lsb", p_.lsb);
  require_period(n + ".period_ns", p_.period_ns);
  k_noise_.fill(1.0);
}

bool WheelTachometers::update(const SensorTruth& truth)
{
  if (!due(truth.t_ns, p_.period_ns)) return false;
  for (int i = 0; i < p_.num_rw; ++i) {
    const auto ui = static_cast<size_t>(i);
    double w = truth.Omega[ui];
    if (noise_) w += p_.sigma * k_noise_[ui] * rng_.normal();  // sigma * 1.0: bit for bit the nominal
    out_.Omega[ui] = quantize(w, p_.lsb);
  }
  out_.t_ns = truth.t_ns;
  out_.valid = true;
  return true;
}

// ---------------------------------------------------------- magnetometer

Magnetometer::Magnetometer(MagnetometerParams p, const SensorContext& ctx)
    : p_(std::move(p)), noise_(ctx.noise), rng_(ctx.run_seed, p_.name)
{
  using namespace detail;
  const std::string n = "magnetometer(" + p_.name + ")";
  require_name(n + ".name", p_.name);
  require_dcm(n + ".dcm_SB", p_.dcm_SB);
  require_period(n + ".period_ns", p_.period_ns);
  require_non_negative(n + ".sigma", p_.sigma);
  require_finite(n + ".bias", p_.bias);
  require_scale_error(n + ".scale_error", p_.scale_error);
  require_non_negative(n + ".lsb", p_.lsb);
  require_non_negative(n + ".range", p_.range);
  if (!p_.interference_B.allFinite())
    fail(n + ".interference_B", p_.interference_B.cwiseAbs().maxCoeff(), "must be finite");
}

bool Magnetometer::update(int64_t t_ns, const Vector3d& B_B, const MagnetorquerArray& m)
{
  if (!due(t_ns, p_.period_ns)) return false;
  const Eigen::Map<const Eigen::Matrix<double, kMaxMagnetorquers, 1>> mv(m.data());
  Vector3d b = p_.dcm_SB * (B_B + p_.interference_B * mv);
  if (noise_) {
    const Vector3d eta = rng_.normal3();
    b = b.cwiseProduct(Vector3d::Ones() + p_.scale_error) + p_.bias + (k_noise_ * p_.sigma) * eta;
  }
  out_.saturated = quantize_and_clip(b, p_.lsb, p_.range);
  out_.B_S = b;
  out_.t_ns = t_ns;
  out_.valid = true;
  return true;
}

}  // namespace sim

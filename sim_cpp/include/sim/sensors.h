// sensors: gyro, star tracker, coarse sun sensors and wheel tachometers
// (docs/dynamics.md §9, §10, §13), and a magnetometer (docs/environment.md).
// Frames: N, B, P (gyro platform), C (star-tracker case, boresight = case z),
// S (magnetometer axes).  Units: SI; time tags are
// integer nanoseconds of the plant clock.
//
// Every sensor owns a random stream Rng(ctx.run_seed, params.name) and never
// seeds itself.  update(truth) samples when truth.t_ns is a multiple of the
// sensor's period (else the last output is held and false returned).  Draw
// order per sample is fixed and documented per sensor, so a stream does not
// depend on other sensors, validity or saturation.
//
// One switch: SensorContext::noise = false makes every sensor ideal: no
// random draws, no random-walk or constant biases, no gyro scale-factor
// error, no CSS bias.  What remains is the deterministic transfer: gyro
// quantisation and saturation, CSS cosine/FOV/Kelly/scale/albedo/limits,
// tachometer quantisation.  With those off too, outputs equal truth exactly.
#ifndef SIM_SENSORS_H
#define SIM_SENSORS_H

#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "sim/attitude.h"  // quaternion_from_dcm, sigma_from_quaternion
#include "sim/rng.h"
#include "sim/capacities.h"  // kMaxWheels, WheelArray, kMaxMagnetorquers

namespace sim {

struct SensorContext {
  uint64_t run_seed = 0;  // [-] Monte Carlo run seed
  bool noise = true;      // [-] false: all sensors ideal (see above)
};

// End-of-step truth the sensors read (§7.2 step 1).
struct SensorTruth {
  int64_t t_ns = 0;                                      // [ns] sample time
  Eigen::Vector3d sigma_BN = Eigen::Vector3d::Zero();    // [-]
  Eigen::Vector3d omega_BN_B = Eigen::Vector3d::Zero();  // [rad/s]
  Eigen::Vector3d r_BN_N = Eigen::Vector3d::Zero();      // [m] spacecraft position
  Eigen::Vector3d r_SunN_N = Eigen::Vector3d(149597870693.0, 0.0, 0.0);  // [m]
  double f_illum = 1.0;                                  // [-] eclipse factor in [0, 1]
  WheelArray Omega{};                                    // [rad/s] (num_rw) wheel speeds
};

// The Sun as every coarse sun sensor sees it at one sample: computed once
// per instant for the whole set (§9.3), the same values each sensor would
// compute from the truth.
struct SunGeometry {
  Eigen::Vector3d s_B = Eigen::Vector3d::Zero();  // [-] unit vector to the Sun, B
  double flux = 0.0;                              // [-] (1 AU / |r_Sun - r_B|)^2 f_illum
};
SunGeometry sun_geometry(const SensorTruth& truth);

// q(x) = sign(x) LSB floor(|x| / LSB) (§9.1); identity for lsb <= 0.
double quantize(double x, double lsb);

// ------------------------------------------------------------------ gyro

struct GyroParams {
  std::string name = "gyro";                               // stream name
  Eigen::Matrix3d dcm_PB = Eigen::Matrix3d::Identity();    // [-] platform from body
  int64_t period_ns = 10'000'000;                          // [ns] sample period, > 0
  double sigma_ARW = 0.0;   // [rad/sqrt(s)]   angle random walk
  double sigma_RRW = 0.0;   // [rad/s^(3/2)]   rate random walk (bias walk)
  Eigen::Vector3d b0 = Eigen::Vector3d::Zero();           // [rad/s] constant bias
  Eigen::Vector3d scale_error = Eigen::Vector3d::Zero();  // [-] diagonal; output *= 1 + e
  double lsb = 0.0;        // [rad/s] quantisation step; 0: off
  double omega_max = 0.0;  // [rad/s] saturation; 0: off
};

struct GyroOutput {
  int64_t t_ns = 0;                                      // [ns] time tag
  Eigen::Vector3d omega_PN_P = Eigen::Vector3d::Zero();  // [rad/s] measured rate
  bool valid = false;                                    // a sample exists
  bool saturated = false;                                // any axis clipped
};

// Per sample, with dt_s = period:  draws eta (3 normals) then nu (3 normals);
//   w = [PB] omega + b_k + b0 + sigma_ARW / sqrt(dt_s) eta
//   w = (1 + scale_error) .* w;  quantise;  saturate
//   b_{k+1} = b_k + sigma_RRW sqrt(dt_s) nu            (b_0 = 0)
class Gyro {
 public:
  Gyro(GyroParams p, const SensorContext& ctx);  // validates (std::invalid_argument)
  bool update(const SensorTruth& truth);
  const GyroOutput& output() const { return out_; }
  const Eigen::Vector3d& bias_walk() const { return b_; }  // b_k for the next sample [rad/s]
  const GyroParams& params() const { return p_; }
  // Multiplies the random-error 1-sigmas (a fault event's noise_scale):
  // finite, >= 0 (std::invalid_argument "<name>.noise_scale"); 1 nominal;
  // the draws per sample are unchanged, so the stream stays aligned.
  void set_noise_scale(double k);
  double noise_scale() const { return k_noise_; }

  // Run state for a checkpoint (sim/state_io.h); the parameters are the configuration's.
  void state_io(StateIO& io)
  {
    io.value("gyro.noise_scale", k_noise_);
    rng_.state_io(io);
    io.value("gyro.bias_walk", b_);
    io.value("gyro.output", out_);
  }

 private:
  GyroParams p_;
  bool noise_;
  double k_noise_ = 1.0;
  Rng rng_;
  Eigen::Vector3d b_ = Eigen::Vector3d::Zero();
  GyroOutput out_;
};

// ---------------------------------------------------------- star tracker

struct StarTrackerParams {
  std::string name = "st";
  Eigen::Matrix3d dcm_CB = Eigen::Matrix3d::Identity();  // [-] case from body
  int64_t period_ns = 250'000'000;                        // [ns] 4 Hz default
  double sigma_cross = 0.0;     // [rad] 1-sigma about case x and y
  double sigma_bore = 0.0;      // [rad] 1-sigma about case z (boresight)
  double sun_exclusion = 0.0;   // [rad] Sun-to-boresight angle below which output is invalid; 0: off
};

struct StarTrackerOutput {
  int64_t t_ns = 0;
  Eigen::Vector4d q_CN = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);  // [-] scalar first, q0 >= 0
  Eigen::Vector3d sigma_CN = Eigen::Vector3d::Zero();          // [-] MRP, |sigma| <= 1
  bool valid = false;
};

// Per sample: draws 3 normals (x, y, z);  delta = (sx n1, sx n2, sb n3) in C;
//   [CN]_meas = exp(-[delta~]) [CB][BN].
class StarTracker {
 public:
  StarTracker(StarTrackerParams p, const SensorContext& ctx);
  bool update(const SensorTruth& truth);
  const StarTrackerOutput& output() const { return out_; }
  const StarTrackerParams& params() const { return p_; }
  // Multiplies the random-error 1-sigmas (a fault event's noise_scale):
  // finite, >= 0 (std::invalid_argument "<name>.noise_scale"); 1 nominal;
  // the draws per sample are unchanged, so the stream stays aligned.
  void set_noise_scale(double k);
  double noise_scale() const { return k_noise_; }

  // Run state for a checkpoint (sim/state_io.h); the parameters are the configuration's.
  void state_io(StateIO& io)
  {
    io.value("star_tracker.noise_scale", k_noise_);
    rng_.state_io(io);
    io.value("star_tracker.output", out_);
  }

 private:
  StarTrackerParams p_;
  double cos_exclusion_;  // cos(sun_exclusion)
  bool noise_;
  double k_noise_ = 1.0;
  Rng rng_;
  StarTrackerOutput out_;
};

// quaternion_from_dcm / sigma_from_quaternion: see sim/attitude.h.

// ---------------------------------------------------- coarse sun sensors

struct CssParams {
  std::string name = "css";
  Eigen::Vector3d n_hat_B = Eigen::Vector3d::UnitZ();  // [-] unit normal, B
  double fov_half = 1.5707963267948966;  // [rad] half-angle, in (0, pi/2]
  double k_kelly = 0.0;     // [-] Kelly factor; <= 1e-10: off
  double scale = 1.0;       // [output units] s, > 0
  double bias = 0.0;        // [-] b, in units of gamma (cosine)
  double sigma = 0.0;       // [-] noise 1-sigma, in units of gamma
  double albedo = 0.0;      // [-] a, in units of gamma
  double y_min = 0.0;       // [output units] lower output limit
  double y_max = std::numeric_limits<double>::infinity();  // [output units] upper limit
  int64_t period_ns = 100'000'000;  // [ns]
};

struct CssOutput {
  int64_t t_ns = 0;
  double y = 0.0;      // [output units]
  double gamma = 0.0;  // [-] noise-free response before scale (for tests and logs)
  bool valid = false;
};

// Per sample: draws 1 normal.  §9.3:
//   s_B = [BN] unit(r_Sun - r_B); gamma = n.s if n.s >= cos(fov) else 0
//   gamma *= 1 - exp(-gamma^2 / k_kelly)  (if on)
//   gamma *= (1 AU / |r_Sun - r_B|)^2 f_illum
//   y = clamp(s (gamma + a + b + sigma eta), y_min, y_max)
class CoarseSunSensor {
 public:
  CoarseSunSensor(CssParams p, const SensorContext& ctx);
  bool update(const SensorTruth& truth);
  // The same with the instant's Sun geometry given (sun_geometry(truth)).
  bool update(const SensorTruth& truth, const SunGeometry& sun);
  const CssOutput& output() const { return out_; }
  const CssParams& params() const { return p_; }
  // Multiplies the random-error 1-sigmas (a fault event's noise_scale):
  // finite, >= 0 (std::invalid_argument "<name>.noise_scale"); 1 nominal;
  // the draws per sample are unchanged, so the stream stays aligned.
  void set_noise_scale(double k);
  double noise_scale() const { return k_noise_; }

  // Run state for a checkpoint (sim/state_io.h); the parameters are the configuration's.
  void state_io(StateIO& io)
  {
    io.value("css.noise_scale", k_noise_);
    rng_.state_io(io);
    io.value("css.output", out_);
  }

 private:
  CssParams p_;
  double cos_fov_;  // cos(fov_half)
  bool noise_;
  double k_noise_ = 1.0;
  Rng rng_;
  CssOutput out_;
};

// -------------------------------------------------- wheel tachometers

struct TachParams {
  std::string name = "tach";
  int num_rw = 0;                  // [-] wheels read, <= kMaxWheels
  double sigma = 0.0;              // [rad/s] white noise 1-sigma
  double lsb = 0.0;                // [rad/s] quantisation; 0: off
  int64_t period_ns = 100'000'000; // [ns]
};

struct TachOutput {
  int64_t t_ns = 0;
  WheelArray Omega{};  // [rad/s] (num_rw)
  bool valid = false;
};

// Per sample: draws num_rw normals, wheel 0 first.  Omega + sigma eta, quantised.
class WheelTachometers {
 public:
  WheelTachometers(TachParams p, const SensorContext& ctx);
  bool update(const SensorTruth& truth);
  const TachOutput& output() const { return out_; }
  // Multiplies wheel i's noise 1-sigma (a fault event's tach_noise_scale):
  // i in [0, num_rw) (std::out_of_range), k finite, >= 0
  // (std::invalid_argument "<name>.noise_scale"); 1 nominal; the draws are
  // unchanged, so the stream stays aligned.
  void set_noise_scale(int i, double k);
  double noise_scale(int i) const { return k_noise_.at(static_cast<size_t>(i)); }

  // Run state for a checkpoint (sim/state_io.h); the parameters are the configuration's.
  void state_io(StateIO& io)
  {
    rng_.state_io(io);
    io.value("tach.output", out_);
    io.value("tach.noise_scale", k_noise_);
  }

 private:
  TachParams p_;
  bool noise_;
  Rng rng_;
  TachOutput out_;
  WheelArray k_noise_;
};

// ---------------------------------------------------------- magnetometer

// Three-axis magnetometer (frame S, sensor axes).  The field it reads is the
// Earth's at the spacecraft plus the magnetorquers' own field at the sensor,
// interference_B * m (a linear map, tesla per A m^2 of each rod's dipole).
struct MagnetometerParams {
  std::string name = "mag";
  Eigen::Matrix3d dcm_SB = Eigen::Matrix3d::Identity();  // [-] sensor from body
  int64_t period_ns = 100'000'000;                        // [ns] sample period, > 0
  double sigma = 0.0;                                     // [T] white-noise 1-sigma per axis
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();         // [T] constant bias, S
  Eigen::Vector3d scale_error = Eigen::Vector3d::Zero();  // [-] diagonal; output *= 1 + e, each > -1
  double lsb = 0.0;    // [T] quantisation step; 0: off
  double range = 0.0;  // [T] per-axis saturation; 0: off
  Eigen::Matrix<double, 3, kMaxMagnetorquers> interference_B =
      Eigen::Matrix<double, 3, kMaxMagnetorquers>::Zero();  // [T/(A m^2)] column j: field at the sensor per unit dipole of rod j, B
};

struct MagnetometerOutput {
  int64_t t_ns = 0;                                 // [ns] time tag
  Eigen::Vector3d B_S = Eigen::Vector3d::Zero();    // [T] measured field, S
  bool valid = false;                               // a sample exists
  bool saturated = false;                           // any axis clipped
};

// Per sample: draws 3 normals (x, y, z).
//   b = [SB] (B_B + interference_B m)
//   b = (1 + scale_error) .* b + bias + sigma eta     (noise on; else b unchanged)
//   quantise; saturate at +-range
class Magnetometer {
 public:
  Magnetometer(MagnetometerParams p, const SensorContext& ctx);  // validates (std::invalid_argument)
  // B_B [T] the Earth's field at the spacecraft, B; m [A m^2] the rods' dipoles.
  bool update(int64_t t_ns, const Eigen::Vector3d& B_B, const MagnetorquerArray& m);
  const MagnetometerOutput& output() const { return out_; }
  const MagnetometerParams& params() const { return p_; }
  void set_noise_scale(double k);  // as the other sensors
  double noise_scale() const { return k_noise_; }

  // Run state for a checkpoint (sim/state_io.h); the parameters are the configuration's.
  void state_io(StateIO& io)
  {
    io.value("magnetometer.noise_scale", k_noise_);
    rng_.state_io(io);
    io.value("magnetometer.output", out_);
  }

 private:
  MagnetometerParams p_;
  bool noise_;
  double k_noise_ = 1.0;
  Rng rng_;
  MagnetometerOutput out_;
};

}  // namespace sim

#endif  // SIM_SENSORS_H

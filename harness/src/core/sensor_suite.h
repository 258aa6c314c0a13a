// sensor_suite: the plant-side sensor models of a run (coarse sun sensors,
// gyro, star tracker, wheel tachometers) and the mapping of their outputs
// (or truth, for a disabled sensor) onto the FSW's FswAcsSensorMsg.
#ifndef HARNESS_SENSOR_SUITE_H
#define HARNESS_SENSOR_SUITE_H

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/fsw_config.h"
#include "core/sun_source.h"
#include "harness/core/loop_messages.h"
#include "harness/core/scenario_types.h"
#include "sim/environment_effectors.h"
#include "sim/plant.h"
#include "sim/sensors.h"

namespace harness {

// The plant's sensor truth (sim::Plant::fill_sensor_truth) with the run's
// Sun, formed at most once a tick: the sampled models and the coarse sun
// sensors due at one tick read the same plant state (no task between them
// moves it).
class TickSensorTruth {
 public:
  // `sun`: the run's (it must outlive this object).
  TickSensorTruth(const sim::Plant& plant, const SunSource& sun) : plant_(plant), sun_(sun) {}
  // The truth at tick k: formed at the first call of the tick.
  const sim::SensorTruth& at(uint64_t k);
  const SunSource& sun() const { return sun_; }  // fixed, or the almanac Sun of the epoch with the Earth's shadow
  // A checkpoint (sim/state_io.h): the truth last formed, kept in the
  // file; a restored run forms it again at its next call.
  void state_io(sim::StateIO& io)
  {
    io.value("sensors.truth", truth_);
    formed_ = false;
  }

 private:
  const sim::Plant& plant_;
  const SunSource& sun_;
  sim::SensorTruth truth_;
  uint64_t tick_ = 0;    // the tick truth_ is of, when formed_
  bool formed_ = false;
};

class SensorSuite {
 public:
  // Each model on its own stream Rng(seed, name); one noise switch.  Throws
  // ScenarioError (at the sensor's key) when a model rejects its parameters.
  // The models sample the plant's own sensor truth (sim::Plant::fill_sensor_truth).
  // `sun`: the run's Sun (it must outlive the suite). `field`: the run's
  // magnetic effector (the field model and the rods the magnetometer reads;
  // null without environment.magnetic).
  SensorSuite(const Scenario& sc, const FswSetup& fsw, const sim::Plant& plant, const SunSource& sun,
              const sim::MagneticEffector* field = nullptr);

  bool has_css_models() const { return !css_.empty(); }
  bool has_sampled_models() const { return gyro_ || st_ || tach_; }
  bool has_magnetometer() const { return mag_ != nullptr; }

  // Every tick (with a magnetometer): when its period is due at tick k it
  // samples the field model at the position and attitude of B and the rods'
  // acting dipoles (its interference); `out` is the reading handed on, the
  // held sample with the magnetometer faults below applied.  With a field
  // period T (sensors.magnetometer.field_period > 0) the field in N is
  // evaluated at the samples at t = j T and, between them, extrapolated
  // linearly from the last two evaluations (held until there are two).
  void magnetometer(uint64_t k, MagnetometerMsg& out);

  // Every tick: the models whose own period is due at tick k sample truth;
  // `out` keeps the held outputs of the others.  False when none was due.
  bool sample(uint64_t k, SensorSampleMsg& out);
  // The coarse sun sensors at an FSW tick.
  void read_css(uint64_t k, CssMsg& out);
  // The FSW input: the held samples (gyro -> omega_BN_B, star tracker ->
  // sigma_BN + att_valid, tachometers -> Omega), CSS readings (or the ideal
  // cube-face readings), truth for a disabled sensor and for r_CoM_B.
  // With rods commanded by the FSW (fsw.magnetorquers), `mag` is the
  // magnetometer's message: its reading rotated into B is handed on as
  // B_B, valid when sampled within the last FSW period (a fresh sample).
  // With an orbit (environment.mu > 0) r_N, v_N are the truth (a GNSS
  // receiver's navigation solution taken as exact).
  void fsw_input(uint64_t t_ns, const TruthMsg& truth, const SensorSampleMsg& samples, const CssMsg& css,
                 const MagnetometerMsg* mag, FswAcsSensorMsg& msg) const;
  bool fsw_reads_magnetometer() const { return fsw_mag_; }

  // ---- faults set by scenario events (event_task.cpp, docs/events.md) -------
  // They change what fsw_input() hands the FSW, never the models' own
  // outputs (recorded samples, noise streams): a run whose events never
  // fire is bit-identical to one without events (the noise scales below,
  // 1 until an event sets them, act in the models).
  enum class Fault { None, Dropout, Frozen, Nan, Bias };
  // Gyro (which 0), star tracker (which 1) or CSS i (which 2): Dropout until
  // t_ns < until_ns; Frozen holds the model's last output (taken now).
  void set_gyro_fault(Fault f, uint64_t until_ns);
  void set_star_tracker_fault(Fault f, uint64_t until_ns);
  void set_css_fault(int i, Fault f, uint64_t until_ns);
  // Tachometer of wheel i: Nan, Frozen (last output, taken now), Bias [rad/s].
  void set_tach_fault(int i, Fault f, double bias);
  // The executive's availability flag for wheel i (FswAcsSensorMsg.rw_avail).
  void set_rw_commanded_unavailable(int i, bool unavailable);
  // The executive's flag for ACS thruster j, the FSW's index
  // (FswAcsSensorMsg.thr_avail).
  void set_thr_commanded_unavailable(int j, bool unavailable);
  // Random-error scale of the gyro, the star tracker or CSS i (the models'
  // set_noise_scale; 1 restores).  Unlike the faults above this changes the
  // model's own output, and so the recorded samples; the draws stay aligned
  // with the nominal stream.  No model (ideal sensor): nothing to scale.
  void set_gyro_noise_scale(double k);
  void set_star_tracker_noise_scale(double k);
  void set_css_noise_scale(int i, double k);
  void set_tach_noise_scale(int i, double k);  // wheel i's tachometer
  // Bias steps on what the FSW is given (events bias_x/y/z, bias; 0 clears):
  // the gyro's rate about body axis a [rad/s]; the star tracker's attitude,
  // turned by v about body axis a [rad] (a rotation of the measured body
  // frame); CSS i's reading [its units].
  void set_gyro_bias(int a, double v);
  void set_star_tracker_bias(int a, double v);
  void set_css_bias(int i, double v);
  // Magnetometer (events dropout, frozen, bias_x/y/z, noise_scale, restore):
  // unlike the faults above they act on the `magnetometer` message itself.
  // Dropout: valid 0 and NaN until t_ns < until_ns; Frozen: the message
  // handed on now is held; bias [T] added along sensor axis a (0 clears).
  void set_magnetometer_fault(Fault f, uint64_t until_ns);
  void set_magnetometer_bias(int a, double v);
  void set_magnetometer_noise_scale(double k);

  // For a checkpoint (sim/state_io.h): the faults, biases and held readings
  // set so far and every sensor model's state (noise streams, outputs).
  // Members fixed at setup are not in it; a member that changes during a
  // run must be.
  void state_io(sim::StateIO& io);

 private:
  struct SensorFault {
    Fault fault = Fault::None;
    uint64_t until_ns = 0;
  };
  SensorFault gyro_fault_, st_fault_;
  Eigen::Vector3d gyro_frozen_ = Eigen::Vector3d::Zero(), st_frozen_ = Eigen::Vector3d::Zero();
  uint8_t st_frozen_valid_ = 0;
  std::array<SensorFault, FSW_MAX_CSS> css_fault_{};
  std::array<double, FSW_MAX_CSS> css_frozen_{};
  std::array<Fault, kMaxRw> tach_fault_{};
  std::array<double, kMaxRw> tach_value_{};  // [rad/s] frozen reading or bias
  std::array<uint8_t, kMaxRw> rw_unavail_{};
  std::array<uint8_t, FSW_MAX_THR> thr_unavail_{};
  Eigen::Vector3d gyro_bias_ = Eigen::Vector3d::Zero(), st_bias_ = Eigen::Vector3d::Zero();  // [rad/s], [rad]
  std::array<double, FSW_MAX_CSS> css_bias_{};
  bool any_fault_ = false;  // a fault was ever set (the nominal path stays as it was)

  void apply_faults(uint64_t t_ns, FswAcsSensorMsg& msg) const;
  const sim::Plant& plant_;
  int n_rw_ = 0;
  int num_css_ = 0;
  TickSensorTruth truth_;  // what the models sample, and the run's Sun
  bool ideal_css_ = false;
  std::array<Eigen::Vector3d, kIdealCss> ideal_normals_{};
  uint64_t div_gyro_ = 1, div_st_ = 1, div_tach_ = 1;
  std::vector<sim::CoarseSunSensor> css_;
  std::unique_ptr<sim::Gyro> gyro_;
  std::unique_ptr<sim::StarTracker> st_;
  std::unique_ptr<sim::WheelTachometers> tach_;
  // magnetometer
  const sim::MagneticEffector* field_ = nullptr;
  std::unique_ptr<sim::Magnetometer> mag_;
  uint64_t tick_ns_ = 0, div_mag_ = 1;
  // sensors.magnetometer.field_period in ticks (0: the field at every
  // sample); the last two field evaluations [T, N] and their ticks
  uint64_t div_field_ = 0;
  Eigen::Vector3d field_prev_N_ = Eigen::Vector3d::Zero(), field_last_N_ = Eigen::Vector3d::Zero();
  uint64_t field_prev_k_ = 0, field_last_k_ = 0;
  int field_count_ = 0;  // evaluations so far, up to 2
  Eigen::Vector3d mag_field_N(uint64_t k, double t_s, const Eigen::Vector3d& r_N);
  SensorFault mag_fault_;
  MagnetometerMsg mag_frozen_{}, mag_last_{};  // held by a Frozen fault; the last handed on
  Eigen::Vector3d mag_bias_ = Eigen::Vector3d::Zero();  // [T] S
  bool fsw_mag_ = false;                                // the FSW reads the magnetometer
  Eigen::Matrix3d mag_dcm_SB_ = Eigen::Matrix3d::Identity();
  uint64_t fsw_period_ns_ = 0;
  bool orbit_ = false;                                  // r_N, v_N handed on
  void build_magnetometer(const Scenario& sc);
};

}  // namespace harness

#endif  // HARNESS_SENSOR_SUITE_H

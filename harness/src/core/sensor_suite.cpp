#include "core/sensor_suite.h"
#include "core/convert.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

#include "core/build_error.h"
#include "sim/attitude.h"

namespace harness {

void SensorSuite::state_io(sim::StateIO& io)
{
  io.value("sensors.gyro_fault", gyro_fault_);
  io.value("sensors.st_fault", st_fault_);
  io.value("sensors.gyro_frozen", gyro_frozen_);
  io.value("sensors.st_frozen", st_frozen_);
  io.value("sensors.st_frozen_valid", st_frozen_valid_);
  io.value("sensors.css_fault", css_fault_);
  io.value("sensors.css_frozen", css_frozen_);
  io.value("sensors.tach_fault", tach_fault_);
  io.value("sensors.tach_value", tach_value_);
  io.value("sensors.rw_unavailable", rw_unavail_);
  io.value("sensors.thr_unavailable", thr_unavail_);
  io.value("sensors.gyro_bias", gyro_bias_);
  io.value("sensors.st_bias", st_bias_);
  io.value("sensors.css_bias", css_bias_);
  io.value("sensors.any_fault", any_fault_);
  truth_.state_io(io);
  for (sim::CoarseSunSensor& c : css_) c.state_io(io);
  if (gyro_) gyro_->state_io(io);
  if (st_) st_->state_io(io);
  if (tach_) tach_->state_io(io);
  if (mag_) mag_->state_io(io);
  io.value("sensors.mag_fault", mag_fault_);
  io.value("sensors.mag_frozen", mag_frozen_);
  io.value("sensors.mag_last", mag_last_);
  io.value("sensors.mag_bias", mag_bias_);
  if (div_field_ > 0) {
    io.value("sensors.mag_field_prev_N", field_prev_N_);
    io.value("sensors.mag_field_last_N", field_last_N_);
    io.value("sensors.mag_field_prev_k", field_prev_k_);
    io.value("sensors.mag_field_last_k", field_last_k_);
    io.value("sensors.mag_field_count", field_count_);
  }
}

SensorSuite::SensorSuite(const Scenario& sc, const FswSetup& fsw, const sim::Plant& plant, const SunSource& sun,
                         const sim::MagneticEffector* field)
    : plant_(plant),
      n_rw_(static_cast<int>(sc.wheels.size())),
      num_css_(fsw.cfg.css.num_css),
      truth_(plant, sun),
      ideal_css_(fsw.ideal_css),
      ideal_normals_(fsw.ideal_normals),
      div_gyro_(sc.sensors.gyro.divisor),
      div_st_(sc.sensors.star_tracker.divisor),
      div_tach_(sc.sensors.tachometer.divisor),
      field_(field),
      tick_ns_(sc.tick_ns()),
      fsw_mag_(sc.fsw.mtq && sc.sensors.magnetometer.enabled),
      mag_dcm_SB_(sc.sensors.magnetometer.dcm_SB),
      fsw_period_ns_(sc.tick_ns() * sc.rates.fsw_divisor),
      orbit_(sc.environment.mu > 0.0)
{
  const int64_t tk = static_cast<int64_t>(sc.tick_ns());
  if (!ideal_css_) {
    const sim::SensorContext sctx{sc.seed, sc.sensors.noise && sc.sensors.css.noise_std > 0.0};
    for (size_t i = 0; i < sc.sensors.css.normals_B.size(); ++i) {
      sim::CssParams cp;
      cp.name = "css" + std::to_string(i);
      cp.n_hat_B = sc.sensors.css.normals_B[i];
      cp.fov_half = sc.sensors.css.fov;
      cp.scale = sc.sensors.css.scale;
      cp.sigma = sc.sensors.css.noise_std;
      cp.period_ns = tk;  // sampled at FSW ticks
      built_by_plant(sc, "sensors.css", [&] { css_.emplace_back(cp, sctx); });
    }
  }
  const sim::SensorContext sctx{sc.seed, sc.sensors.noise};
  built_by_plant(sc, "sensors.gyro", [&] {
    if (sc.sensors.gyro.enabled) {
      sim::GyroParams gp;
      gp.name = "gyro";
      gp.period_ns = static_cast<int64_t>(sc.sensors.gyro.divisor) * tk;
      gp.sigma_ARW = sc.sensors.gyro.arw;
      gp.sigma_RRW = sc.sensors.gyro.rrw;
      gp.lsb = sc.sensors.gyro.lsb;
      gyro_ = std::make_unique<sim::Gyro>(gp, sctx);
    }
  });
  built_by_plant(sc, "sensors.star_tracker", [&] {
    if (sc.sensors.star_tracker.enabled) {
      sim::StarTrackerParams sp;
      sp.name = "star_tracker";
      sp.period_ns = static_cast<int64_t>(sc.sensors.star_tracker.divisor) * tk;
      sp.sigma_cross = sc.sensors.star_tracker.sigma_cross;
      sp.sigma_bore = sc.sensors.star_tracker.sigma_bore;
      sp.sun_exclusion = sc.sensors.star_tracker.sun_exclusion;
      st_ = std::make_unique<sim::StarTracker>(sp, sctx);
    }
  });
  built_by_plant(sc, "sensors.tachometer", [&] {
    if (sc.sensors.tachometer.enabled && n_rw_ > 0) {
      sim::TachParams tp;
      tp.name = "tachometer";
      tp.num_rw = n_rw_;
      tp.period_ns = static_cast<int64_t>(sc.sensors.tachometer.divisor) * tk;
      tp.sigma = sc.sensors.tachometer.sigma;
      tp.lsb = sc.sensors.tachometer.lsb;
      tach_ = std::make_unique<sim::WheelTachometers>(tp, sctx);
    }
  });
  build_magnetometer(sc);
}

// sensors.magnetometer (period 0: the FSW period); needs the field (the
// scenario checks environment.magnetic).
void SensorSuite::build_magnetometer(const Scenario& sc)
{
  const MagnetometerSpec& g = sc.sensors.magnetometer;
  if (!g.enabled || !field_) return;
  const uint64_t p_ns = g.period > 0.0 ? static_cast<uint64_t>(std::llround(g.period * 1e9))
                                       : static_cast<uint64_t>(sc.rates.fsw_divisor) * tick_ns_;
  div_mag_ = std::max<uint64_t>(1, p_ns / tick_ns_);
  if (g.field_period > 0.0) div_field_ = static_cast<uint64_t>(std::llround(g.field_period * 1e9)) / tick_ns_;
  sim::MagnetometerParams mp;
  mp.name = "magnetometer";
  mp.dcm_SB = g.dcm_SB;
  mp.period_ns = static_cast<int64_t>(div_mag_ * tick_ns_);
  mp.sigma = g.sigma;
  mp.bias = g.bias;
  mp.scale_error = g.scale_error;
  mp.lsb = g.lsb;
  mp.range = g.range;
  const Eigen::Index n = std::min<Eigen::Index>(g.interference.cols(), sim::kMaxMagnetorquers);
  mp.interference_B.leftCols(n) = g.interference.leftCols(n);
  const sim::SensorContext sctx{sc.seed, sc.sensors.noise};
  built_by_plant(sc, "sensors.magnetometer", [&] { mag_ = std::make_unique<sim::Magnetometer>(mp, sctx); });
}

void SensorSuite::magnetometer(uint64_t k, MagnetometerMsg& out)
{
  const uint64_t t_ns = k * tick_ns_;
  if (k % div_mag_ == 0) {
    const sim::StateVector& x = plant_.state();
    const Eigen::Vector3d r_N = x.segment<3>(sim::StateLayout::r_BN_N);
    const Eigen::Vector3d B_B = sim::dcm_BN_from_sigma(x.segment<3>(sim::StateLayout::sigma_BN)) *
                                mag_field_N(k, static_cast<double>(t_ns) * 1e-9, r_N);
    sim::MagnetorquerArray m{};
    for (int i = 0; i < field_->num_rods(); ++i) m[static_cast<size_t>(i)] = field_->rod_dipole(i);
    if (mag_->update(static_cast<int64_t>(t_ns), B_B, m)) {
      const sim::MagnetometerOutput& o = mag_->output();
      put3(out.B_S, o.B_S + mag_bias_);
      out.t_ns = o.t_ns;
      out.valid = o.valid ? 1 : 0;
      out.saturated = o.saturated ? 1 : 0;
    }
  }
  if (mag_fault_.fault == Fault::Frozen) {
    out = mag_frozen_;
  } else if (mag_fault_.fault == Fault::Dropout && t_ns < mag_fault_.until_ns) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    put3(out.B_S, Eigen::Vector3d(nan, nan, nan));
    out.valid = 0;
  }
  mag_last_ = out;
}

// The field in N at a magnetometer sample (tick k, time t_s, position r_N):
// the model itself, or with a field period its evaluation at t = j T and
// the line through the last two evaluations between them.
Eigen::Vector3d SensorSuite::mag_field_N(uint64_t k, double t_s, const Eigen::Vector3d& r_N)
{
  if (div_field_ == 0) return field_->field_N(t_s, r_N);
  if (k % div_field_ == 0 || field_count_ == 0) {  // (a first sample off the grid: evaluated too)
    field_prev_N_ = field_last_N_;
    field_prev_k_ = field_last_k_;
    field_last_N_ = field_->field_N(t_s, r_N);
    field_last_k_ = k;
    field_count_ = std::min(field_count_ + 1, 2);
    return field_last_N_;
  }
  if (field_count_ < 2) return field_last_N_;
  const double s = static_cast<double>(k - field_last_k_) / static_cast<double>(field_last_k_ - field_prev_k_);
  return field_last_N_ + s * (field_last_N_ - field_prev_N_);
}

void SensorSuite::set_magnetometer_fault(Fault f, uint64_t until_ns)
{
  mag_fault_ = {f, until_ns};
  if (f == Fault::Frozen) mag_frozen_ = mag_last_;
}

void SensorSuite::set_magnetometer_bias(int a, double v) { mag_bias_(a) = v; }

void SensorSuite::set_magnetometer_noise_scale(double k)
{
  if (mag_) mag_->set_noise_scale(k);
}

const sim::SensorTruth& TickSensorTruth::at(uint64_t k)
{
  if (formed_ && tick_ == k) return truth_;
  formed_ = true;
  tick_ = k;
  if (!sun_.dated()) {
    plant_.fill_sensor_truth(truth_, sun_.position_N(0));
    return truth_;
  }
  const Eigen::Vector3d r_sun_N = sun_.position_N(plant_.t_ns());
  plant_.fill_sensor_truth(truth_, r_sun_N, sun_.illumination(plant_.r_BN_N(), r_sun_N));
  return truth_;
}

bool SensorSuite::sample(uint64_t k, SensorSampleMsg& out)
{
  const bool g = gyro_ && k % div_gyro_ == 0, a = st_ && k % div_st_ == 0, w = tach_ && k % div_tach_ == 0;
  if (!(g || a || w)) return false;
  const sim::SensorTruth& st = truth_.at(k);
  if (g && gyro_->update(st)) {
    const sim::GyroOutput& o = gyro_->output();
    put3(out.omega_PN_P, o.omega_PN_P);
    out.gyro_t_ns = o.t_ns;
    out.gyro_valid = o.valid ? 1 : 0;
  }
  if (a && st_->update(st)) {
    const sim::StarTrackerOutput& o = st_->output();
    put3(out.sigma_CN, o.sigma_CN);
    out.st_t_ns = o.t_ns;
    out.st_valid = o.valid ? 1 : 0;
  }
  if (w && tach_->update(st)) {
    const sim::TachOutput& o = tach_->output();
    for (int i = 0; i < n_rw_; ++i) out.Omega[i] = o.Omega[static_cast<size_t>(i)];
    out.tach_t_ns = o.t_ns;
    out.tach_valid = o.valid ? 1 : 0;
  }
  return true;
}

void SensorSuite::read_css(uint64_t k, CssMsg& out)
{
  const sim::SensorTruth& st = truth_.at(k);
  const sim::SunGeometry sun = sim::sun_geometry(st);  // once for the set
  for (size_t i = 0; i < css_.size(); ++i) {
    css_[i].update(st, sun);
    out.y[i] = css_[i].output().y;
  }
}

void SensorSuite::fsw_input(uint64_t t_ns, const TruthMsg& t, const SensorSampleMsg& sm, const CssMsg& css,
                            const MagnetometerMsg* mag, FswAcsSensorMsg& msg) const
{
  std::memset(&msg, 0, sizeof msg);
  msg.t_ns = t_ns;
  if (st_) {
    // sigma_BN = sigma_CN (case = body); no valid sample yet or Sun-excluded: att_valid 0
    copy3(msg.sigma_BN, sm.sigma_CN);
    msg.att_valid = sm.st_valid;
  } else {
    copy3(msg.sigma_BN, t.sigma_BN);
    msg.att_valid = 1;
  }
  if (gyro_) copy3(msg.omega_BN_B, sm.omega_PN_P);  // P = B
  else copy3(msg.omega_BN_B, t.omega_BN_B);
  if (ideal_css_) {
    // cube-face cosines, times the visible fraction of the Sun (1 without an epoch)
    const SunSource& sun = truth_.sun();
    const Eigen::Vector3d r_sun_N = sun.position_N(static_cast<int64_t>(t_ns));
    const Eigen::Vector3d d_B = sim::dcm_BN_from_sigma(ev(t.sigma_BN)) * (r_sun_N - ev(t.r_BN_N)).normalized();
    const double f = sun.illumination(ev(t.r_BN_N), r_sun_N);
    for (int i = 0; i < kIdealCss; ++i)
      msg.css[i] = static_cast<fsw_real>(f * std::max(0.0, ideal_normals_[static_cast<size_t>(i)].dot(d_B)));
  } else {
    for (int i = 0; i < num_css_; ++i) msg.css[i] = static_cast<fsw_real>(css.y[i]);
  }
  if (tach_) {
    for (int i = 0; i < n_rw_; ++i) msg.Omega[i] = static_cast<fsw_real>(sm.Omega[i]);
  } else {
    for (int i = 0; i < n_rw_; ++i) msg.Omega[i] = static_cast<fsw_real>(t.Omega[i]);
  }
  copy3(msg.r_CoM_B, t.r_CoM_B);
  if (orbit_) {
    copy3(msg.r_N, t.r_BN_N);
    copy3(msg.v_N, t.v_BN_N);
    msg.orbit_valid = 1;
  }
  if (fsw_mag_ && mag && mag->valid && mag->t_ns >= 0 &&
      static_cast<uint64_t>(mag->t_ns) + fsw_period_ns_ > t_ns) {
    put3(msg.B_B, mag_dcm_SB_.transpose() * ev(mag->B_S));
    msg.mag_valid = 1;
  }
  if (any_fault_) apply_faults(t_ns, msg);
}

void SensorSuite::apply_faults(uint64_t t_ns, FswAcsSensorMsg& msg) const
{
  const auto active = [t_ns](const SensorFault& f) {
    return f.fault == Fault::Frozen || (f.fault == Fault::Dropout && t_ns < f.until_ns);
  };
  if (active(gyro_fault_)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Eigen::Vector3d w = gyro_fault_.fault == Fault::Frozen ? gyro_frozen_ : Eigen::Vector3d(nan, nan, nan);
    for (int a = 0; a < 3; ++a) msg.omega_BN_B[a] = static_cast<fsw_real>(w(a));
  }
  if (active(st_fault_)) {
    if (st_fault_.fault == Fault::Frozen) {
      for (int a = 0; a < 3; ++a) msg.sigma_BN[a] = static_cast<fsw_real>(st_frozen_(a));
      msg.att_valid = st_frozen_valid_;
    } else {
      msg.att_valid = 0;
    }
  }
  for (int i = 0; i < num_css_; ++i) {
    const SensorFault& f = css_fault_[static_cast<size_t>(i)];
    if (!active(f)) continue;
    if (f.fault == Fault::Frozen) {
      msg.css[i] = static_cast<fsw_real>(css_frozen_[static_cast<size_t>(i)]);
    } else {
      msg.css[i] = 0;
      msg.css_avail[i] = 1;
    }
  }
  for (int i = 0; i < n_rw_; ++i) {
    const size_t u = static_cast<size_t>(i);
    switch (tach_fault_[u]) {
      case Fault::Nan: msg.Omega[i] = static_cast<fsw_real>(std::numeric_limits<double>::quiet_NaN()); break;
      case Fault::Frozen: msg.Omega[i] = static_cast<fsw_real>(tach_value_[u]); break;
      case Fault::Bias: msg.Omega[i] = static_cast<fsw_real>(static_cast<double>(msg.Omega[i]) + tach_value_[u]); break;
      default: break;
    }
    msg.rw_avail[i] = rw_unavail_[u];
  }
  for (size_t j = 0; j < thr_unavail_.size(); ++j) msg.thr_avail[j] = thr_unavail_[j];
  // bias steps, on top of what the faults above left
  for (int a = 0; a < 3; ++a)
    msg.omega_BN_B[a] = static_cast<fsw_real>(static_cast<double>(msg.omega_BN_B[a]) + gyro_bias_(a));
  if (st_bias_.squaredNorm() > 0.0 && msg.att_valid) {
    // the measured body frame turned by st_bias_: C_B'N = exp([delta~])^T C_BN
    Eigen::Vector3d s;
    for (int a = 0; a < 3; ++a) s(a) = static_cast<double>(msg.sigma_BN[a]);
    const Eigen::Matrix3d C = sim::rotation_from_vector(st_bias_).transpose() * sim::dcm_BN_from_sigma(s);
    const Eigen::Vector3d sb = sim::sigma_from_quaternion(sim::quaternion_from_dcm(C));
    for (int a = 0; a < 3; ++a) msg.sigma_BN[a] = static_cast<fsw_real>(sb(a));
  }
  for (int i = 0; i < num_css_; ++i)
    if (msg.css_avail[i] == 0)
      msg.css[i] = static_cast<fsw_real>(static_cast<double>(msg.css[i]) + css_bias_[static_cast<size_t>(i)]);
}

void SensorSuite::set_gyro_bias(int a, double v)
{
  any_fault_ = true;
  gyro_bias_(a) = v;
}

void SensorSuite::set_star_tracker_bias(int a, double v)
{
  any_fault_ = true;
  st_bias_(a) = v;
}

void SensorSuite::set_css_bias(int i, double v)
{
  any_fault_ = true;
  if (static_cast<size_t>(i) < css_bias_.size()) css_bias_[static_cast<size_t>(i)] = v;
}

void SensorSuite::set_gyro_fault(Fault f, uint64_t until_ns)
{
  any_fault_ = true;
  gyro_fault_ = {f, until_ns};
  if (f == Fault::Frozen && gyro_) gyro_frozen_ = gyro_->output().omega_PN_P;
}

void SensorSuite::set_star_tracker_fault(Fault f, uint64_t until_ns)
{
  any_fault_ = true;
  st_fault_ = {f, until_ns};
  if (f == Fault::Frozen && st_) {
    st_frozen_ = st_->output().sigma_CN;
    st_frozen_valid_ = st_->output().valid ? 1 : 0;
  }
}

void SensorSuite::set_css_fault(int i, Fault f, uint64_t until_ns)
{
  any_fault_ = true;
  const size_t u = static_cast<size_t>(i);
  css_fault_[u] = {f, until_ns};
  if (f == Fault::Frozen && u < css_.size()) css_frozen_[u] = css_[u].output().y;
}

void SensorSuite::set_tach_fault(int i, Fault f, double bias)
{
  any_fault_ = true;
  const size_t u = static_cast<size_t>(i);
  tach_fault_[u] = f;
  tach_value_[u] = bias;
  if (f == Fault::Frozen && tach_) tach_value_[u] = tach_->output().Omega[u];
}

void SensorSuite::set_gyro_noise_scale(double k)
{
  if (gyro_) gyro_->set_noise_scale(k);
}

void SensorSuite::set_star_tracker_noise_scale(double k)
{
  if (st_) st_->set_noise_scale(k);
}

void SensorSuite::set_css_noise_scale(int i, double k)
{
  const size_t u = static_cast<size_t>(i);
  if (u < css_.size()) css_[u].set_noise_scale(k);
}

void SensorSuite::set_tach_noise_scale(int i, double k)
{
  if (tach_) tach_->set_noise_scale(i, k);
}

void SensorSuite::set_rw_commanded_unavailable(int i, bool unavailable)
{
  any_fault_ = true;
  rw_unavail_[static_cast<size_t>(i)] = unavailable ? 1 : 0;
}

void SensorSuite::set_thr_commanded_unavailable(int j, bool unavailable)
{
  any_fault_ = true;
  if (static_cast<size_t>(j) < thr_unavail_.size()) thr_unavail_[static_cast<size_t>(j)] = unavailable ? 1 : 0;
}

}  // namespace harness

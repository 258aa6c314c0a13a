// sun_source.h: where a run's Sun is, for the sensors, sun-safe pointing and
// the metrics (the solar-pressure effector takes the same Sun from its own
// sim::EarthContext).
//   * No environment.epoch: the scenario's fixed environment.sun_position_N
//     in N, never eclipsed (deep space, or an orbit without a date).
//   * environment.epoch set (an Earth orbit): the geocentric almanac Sun of
//     the epoch plus plant time (sim/sun_almanac.h) and the Earth's umbra
//     and penumbra (sim::illumination_factor, shadowing sphere of radius
//     sim::kRadiusEarth).
// A run has one SunSource, shared by the sensors, the truth message and the
// metrics: the last position formed is kept with its time, so the tasks of
// one tick form the almanac Sun once (a pure function of t_ns: the same
// bits; nothing to save in a checkpoint).
// See docs/environment.md, "The Sun of a dated run".
#ifndef HARNESS_CORE_SUN_SOURCE_H
#define HARNESS_CORE_SUN_SOURCE_H

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "core/plant_builder.h"
#include "harness/core/scenario_types.h"
#include "sim/earth_context.h"
#include "sim/environment.h"

namespace harness {

class SunSource {
 public:
  // The context of the plant's environment effectors (earth_context).
  explicit SunSource(const Scenario& sc) : fixed_N_(sc.environment.sun_position_N), earth_(earth_context(sc)) {}
  bool dated() const { return earth_.has_value(); }
  // [m] the Sun's position in N at plant time t_ns
  Eigen::Vector3d position_N(int64_t t_ns) const
  {
    if (!earth_) return fixed_N_;
    if (t_ns != last_t_ns_ || !has_last_) {
      last_N_ = earth_->sun_position_N(1e-9 * static_cast<double>(t_ns));
      last_t_ns_ = t_ns;
      has_last_ = true;
    }
    return last_N_;
  }
  // [-] visible fraction of the solar disk from r_N [m] with the Sun at
  // r_sun_N: 1 without an epoch
  double illumination(const Eigen::Vector3d& r_N, const Eigen::Vector3d& r_sun_N) const
  {
    return earth_ ? sim::illumination_factor(r_N, r_sun_N, earth_->params().shadow_radius) : 1.0;
  }

 private:
  Eigen::Vector3d fixed_N_;
  std::optional<sim::EarthContext> earth_;
  mutable Eigen::Vector3d last_N_ = Eigen::Vector3d::Zero();  // [m] the last position formed
  mutable int64_t last_t_ns_ = 0;                              // [ns] its time
  mutable bool has_last_ = false;
};

}  // namespace harness

#endif  // HARNESS_CORE_SUN_SOURCE_H

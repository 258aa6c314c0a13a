// earth_context: the Earth-orbit context of a plant run: the UTC epoch of
// plant time t = 0, so that plant time maps to a date, and what the
// environment effectors (sim/environment_effectors.h) take from that date:
// the rotation N -> E (GMST), the Sun's position and the shadowing body.
// Frames: N inertial = mean equator and equinox of date, centred on the
// Earth (the plant's N when a context is used); E Earth-fixed.  Units: SI.
// See docs/environment.md, "In the plant".
//
// A plant without environment effectors has no context and behaves as
// before (deep space or a point-mass central body, sim/environment.h).
#ifndef SIM_EARTH_CONTEXT_H
#define SIM_EARTH_CONTEXT_H

#include <Eigen/Dense>

#include "sim/earth_time.h"
#include "sim/environment.h"

namespace sim {

struct EarthContextParams {
  UtcEpoch epoch;                       // [-] UTC instant of plant time t = 0
  double shadow_radius = kRadiusEarth;  // [m] radius of the shadowing sphere, >= 0 (0: no eclipses)
};

// Throws std::invalid_argument naming `name.field` and the value.
void validate(const EarthContextParams& p, const char* name = "earth");

class EarthContext {
 public:
  explicit EarthContext(const EarthContextParams& p);  // validates

  const EarthContextParams& params() const { return p_; }

  // Days from J2000.0 at plant time t_s [s] (epoch + t_s), the day fraction
  // at full precision (the epoch's whole days split off once).
  J2000Days days(double t_s) const;
  double gmst(double t_s) const;                 // [rad] GMST (IAU 1982) at t_s
  Eigen::Matrix3d dcm_EN(double t_s) const;      // [-] [EN] at t_s
  Eigen::Vector3d sun_position_N(double t_s) const;  // [m] geocentric Sun (almanac) at t_s
  double decimal_year() const;                   // [yr] of the epoch (for the IGRF coefficients)

 private:
  EarthContextParams p_;
  J2000Days d0_;  // [d] the epoch from J2000.0
};

}  // namespace sim

#endif  // SIM_EARTH_CONTEXT_H

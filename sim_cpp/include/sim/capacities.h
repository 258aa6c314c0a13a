// capacities: every fixed capacity of the plant, in one place.
//
// The plant never allocates inside a step (docs/dynamics.md §13): per-device arrays
// and the state vector have compile-time maximum sizes taken from here.  The
// capacities are chosen >= the flight software's, so that any configuration
// the FSW accepts can be simulated:
//   kMaxWheels    >= FSW_MAX_RW   (fsw_c/include/fsw/fsw_config.h, 36)
//   kMaxThrusters >= FSW_MAX_THR  (fsw_c/include/fsw/fsw_config.h, 36)
//   kMaxCss       >= FSW_MAX_CSS  (fsw_c/include/fsw/css_sun.h, 32)
// The plant library does not depend on the FSW, so the relation is checked
// where both are visible: test/sim_cpp/test_capacities.cpp static_asserts it
// (and an integrator that joins both, e.g. the harness, should do the same).
// Memory: the state vector holds at most kMaxStateDim doubles (704 B); one
// derivative evaluation keeps about 300 B of per-wheel data on the stack per
// wheel of capacity (~11 KiB at 36).
#ifndef SIM_CAPACITIES_H
#define SIM_CAPACITIES_H

#include <array>

namespace sim {

constexpr int kMaxWheels = 36;     // [-] reaction wheels (>= FSW_MAX_RW)
constexpr int kMaxThrusters = 36;  // [-] thrusters (>= FSW_MAX_THR)
constexpr int kMaxTanks = 4;       // [-] propellant tanks (the FSW has no tank capacity)
constexpr int kMaxCss = 32;        // [-] coarse sun sensors in one array (>= FSW_MAX_CSS)
constexpr int kMaxEffectors = 8;   // [-] force/torque effectors in a Plant, the thruster set included
constexpr int kMaxFacets = 64;     // [-] surface facets for radiation pressure and drag (sim/surface_forces.h)
constexpr int kMaxMagnetorquers = 6;  // [-] magnetorquers seen by one magnetometer (sim/sensors.h)

// State vector (sim/spacecraft.h StateLayout): hub 12, wheel speeds and angles, tank masses.
constexpr int kHubStateDim = 12;                                       // [-]
constexpr int kMaxStateDim = kHubStateDim + 2 * kMaxWheels + kMaxTanks;  // [-]

using WheelArray = std::array<double, kMaxWheels>;        // (num_rw)
using ThrusterArray = std::array<double, kMaxThrusters>;  // (num_thr)
using TankArray = std::array<double, kMaxTanks>;          // (num_tanks)
using MagnetorquerArray = std::array<double, kMaxMagnetorquers>;  // (magnetorquers)

}  // namespace sim

#endif  // SIM_CAPACITIES_H

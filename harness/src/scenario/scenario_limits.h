// scenario_limits: how many wheels, thrusters and coarse sun sensors a
// scenario may have -- the smaller of the flight software's and the plant's
// capacities, taken from their constants (the one place the harness's
// scenario schema names them).
//
// Private to the harness library.
#ifndef HARNESS_SRC_SCENARIO_LIMITS_H
#define HARNESS_SRC_SCENARIO_LIMITS_H

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "fsw/css_sun.h"     // FSW_MAX_CSS
#include "fsw/fsw_config.h"  // FSW_MAX_RW, FSW_MAX_THR
#include "sim/capacities.h"  // sim::kMaxWheels, kMaxThrusters, kMaxCss

namespace harness {

constexpr size_t kMaxScenarioWheels = static_cast<size_t>(std::min(FSW_MAX_RW, sim::kMaxWheels));       // [-]
constexpr size_t kMaxScenarioThrusters = static_cast<size_t>(std::min(FSW_MAX_THR, sim::kMaxThrusters));  // [-]
constexpr size_t kMaxScenarioCss = static_cast<size_t>(std::min(FSW_MAX_CSS, sim::kMaxCss));              // [-]
constexpr size_t kMaxScenarioEvents = 64;  // [-] events in a scenario (a fault campaign is a few)
constexpr size_t kMaxEventActions = 16;    // [-] actions of one event
constexpr uint64_t kMaxMcRuns = 10000000;  // [-] runs of one Monte Carlo campaign (also --runs)

}  // namespace harness

#endif  // HARNESS_SRC_SCENARIO_LIMITS_H

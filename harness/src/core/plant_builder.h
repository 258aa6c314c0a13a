// plant_builder: Scenario -> the plant of a run, and the main-engine burn
// schedule.
#ifndef HARNESS_PLANT_BUILDER_H
#define HARNESS_PLANT_BUILDER_H

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include <Eigen/Dense>

#include "harness/core/scenario_types.h"
#include "core/magnetorquer_drive.h"
#include "harness/core/vehicle_geometry.h"
#include "sim/environment_effectors.h"
#include "sim/plant.h"

namespace harness {

// The environment effectors of a run (owned by its plant), indexed by
// EnvSource; null where the scenario leaves that model off.
using EnvEffectors = std::array<const sim::SampledEnvironmentEffector*, kNumEnvSources>;

// The parts of a run's plant that commands and events act on (owned by its
// plant): the effector of the residual dipole and the rods (null when
// environment.magnetic is off), in PWM mode with rods the driver that
// switches them (else null), and the drag effector (null when
// environment.drag is off; the atmosphere events).
struct SettableParts {
  sim::MagneticEffector* effector = nullptr;
  MtqPwmDriver* pwm = nullptr;
  sim::DragEffector* drag = nullptr;
};

// Builds the plant (sim::Plant: hub, wheels and, with thrusters, the
// thruster set and the tanks, then the environment effectors the scenario
// enables); throws ScenarioError (at the key's line) when the plant rejects
// the configuration.  `env` (optional) receives the environment effectors,
// `mag` (optional) the magnetic parts.
std::unique_ptr<sim::Plant> build_plant(const Scenario& sc, EnvEffectors* env = nullptr, SettableParts* mag = nullptr);

// The Earth context of environment.epoch (the UTC of t = 0; the shadowing
// sphere of the Earth); nullopt when the scenario has no epoch.
std::optional<sim::EarthContext> earth_context(const Scenario& sc);

// Main-engine burn: the engine opens at the first thruster command instant
// at or after burn.start and closes at start + duration.
struct BurnSchedule {
  int engine = -1;        // plant index of the engine, -1 without a burn
  int64_t on_ns = 0;      // [ns]
  int64_t off_ns = 0;     // [ns]
  int64_t T_upd_ns = 0;   // [ns] thruster command period
  // On-time [s] of the engine for the command latched at the first command
  // instant at or after now_ns (0 outside the burn).
  double on_time(int64_t now_ns) const;
};
BurnSchedule burn_schedule(const Scenario& sc, const sim::Plant& plant);

}  // namespace harness

#endif  // HARNESS_PLANT_BUILDER_H

// fsw_config: Scenario -> FswAcsConfig (the FSW application's configuration,
// nominal values, not truth) and the map from a field fsw_acs_check rejects
// to the scenario key it comes from.
#ifndef HARNESS_FSW_CONFIG_H
#define HARNESS_FSW_CONFIG_H

#include <array>
#include <string>

#include <Eigen/Dense>

#include "harness/core/scenario_types.h"
#include "sim/spacecraft.h"

extern "C" {
#include "fsw/fsw_acs.h"
}

namespace harness {

// Without configured coarse sun sensors the FSW still needs a CSS set: six
// ideal sensors on the cube faces (readings max(0, n.s) computed exactly
// from truth, lit threshold 0).  For any Sun direction the lit faces span the
// directions where s has a component, so css_sun returns s exactly (3 lit:
// least squares on orthonormal normals; 2 or 1 lit: the documented
// fallbacks are exact for orthogonal normals).  This is the "ideal heading".
constexpr int kIdealCss = 6;
// guid_sunsafe: |s_B| above which the Sun heading counts as valid [-]
constexpr double kSunMinUnitMag = 0.1;

struct FswSetup {
  FswAcsConfig cfg{};
  int n_acs = 0;                                // ACS thrusters (FSW order)
  std::array<int, FSW_MAX_THR> acs_to_plant{};  // FSW thruster index -> plant thruster index
  bool ideal_css = false;                       // the six ideal cube-face sensors stand in
  std::array<Eigen::Vector3d, kIdealCss> ideal_normals{};
};

// Builds the configuration.  `nominal` are the plant's mass properties at t0
// (the FSW inertia about C when the scenario gives none).  Throws
// ScenarioError when fsw_acs_check rejects it, naming the scenario key of the
// bad field at its line.
FswSetup make_fsw_setup(const Scenario& sc, const sim::MassProps& nominal);

// The scenario key a field named by fsw_acs_check comes from ("fsw" when the
// field is not in the table).
std::string scenario_key_of_fsw_field(const std::string& field);

}  // namespace harness

#endif  // HARNESS_FSW_CONFIG_H

// build_error: a configuration problem found while building a run (by the
// plant, an FSW module or the harness), reported as a scenario problem at the
// line of the scenario key it comes from.
#ifndef HARNESS_BUILD_ERROR_H
#define HARNESS_BUILD_ERROR_H

#include <exception>
#include <string>

#include "harness/core/scenario_types.h"

namespace harness {

// A ScenarioError naming `key`, at the line of that key or of its nearest
// written parent.
ScenarioError config_error(const Scenario& sc, const std::string& key, const std::string& msg);

// Runs `make` (a plant constructor): an exception from the plant becomes a
// scenario error naming `key`.
template <class F>
void built_by_plant(const Scenario& sc, const char* key, F&& make)
{
  try {
    make();
  } catch (const std::exception& e) {
    throw config_error(sc, key, std::string("rejected by the plant: ") + e.what());
  }
}

}  // namespace harness

#endif  // HARNESS_BUILD_ERROR_H

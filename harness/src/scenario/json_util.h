// Private: nlohmann-json views of harness types.
#ifndef HARNESS_SRC_JSON_UTIL_H
#define HARNESS_SRC_JSON_UTIL_H

#include <nlohmann/json.hpp>

#include "harness/scenario/scenario.h"

namespace harness {
nlohmann::json scenario_to_json(const Scenario& sc);
}

#endif

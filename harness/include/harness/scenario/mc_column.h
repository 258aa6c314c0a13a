// mc_column: a named, unit-carrying column of a Monte Carlo campaign's table
// (the drawn values and the metrics; harness/mc/monte_carlo.h).  In the
// scenario room because the dispersions name their drawn columns there.
#ifndef HARNESS_SCENARIO_MC_COLUMN_H
#define HARNESS_SCENARIO_MC_COLUMN_H

#include <string>

namespace harness {

struct McColumn {
  std::string name;
  std::string unit;
  std::string what = "";
};

}  // namespace harness

#endif  // HARNESS_SCENARIO_MC_COLUMN_H

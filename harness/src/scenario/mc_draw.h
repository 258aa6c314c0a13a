// mc_draw: the random draws of a Monte Carlo campaign (docs/monte-carlo.md).
//
// Reproducible by construction: the numbers of run k come from counter-based
// streams keyed by (master seed, k, the dispersed key's path) only -- not by
// the thread, the MPI rank, the shard or the order the runs are done in; adding,
// removing or reordering dispersions does not change the draws of the others.  The
// generator (SplitMix64 on the key) and the distributions (Box-Muller,
// rejection for the truncated normal, inverse CDF for the cap) are written
// here rather than taken from <random>, whose distributions differ between
// standard libraries.
//
// Private to the harness library.
#ifndef HARNESS_SRC_MC_DRAW_H
#define HARNESS_SRC_MC_DRAW_H

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "harness/scenario/mc_column.h"
#include "harness/scenario/scenario.h"
#include "scenario/yaml_reader.h"

namespace harness {

namespace schema {
struct KeyDef;
KeyDef monte_carlo_key();  // the top-level `monte_carlo` key (read and written)
}  // namespace schema

// One random stream.
class McStream {
 public:
  // `key`: the dispersed key's normalised path (wheels[2].axis).
  McStream(uint64_t master, uint64_t run, const std::string& key);
  uint64_t next();
  double uniform();  // [0, 1), 53 bits
  double normal();   // N(0, 1), Box-Muller
 private:
  uint64_t s_;
};

// The seed of run k's own noise (sensor streams; Scenario::seed), below 2^53
// so every JSON reader holds it exactly.
uint64_t mc_run_seed(uint64_t master, uint64_t run);

// "wheels[*].axis" -> wheels[0].axis ... (one per element); `why` set when
// the key cannot be expanded.
std::vector<std::string> expand_dispersion_key(const Scenario& sc, const std::string& key, std::string& why);

// The dispersed keys checked against a read scenario (names, types, list
// elements, a key dispersed twice, choice values); problems go to ctx.
void check_monte_carlo(const Ctx& ctx, Scenario& sc);

// "" when `value` (a choice, as written) sets key `path` of sc, else why not.
std::string try_choice_value(Scenario& sc, const std::string& path, const std::string& value);

// The columns of the drawn values (summary table, scatter plots), e.g.
// "wheels[1].axis.angle_deg", "events[0].t".
std::vector<McColumn> drawn_columns(const Scenario& nominal);

// Run k of the campaign: the scenario with its draws applied (monte_carlo
// removed, seed = mc_run_seed), the drawn values by drawn_columns(), and
// "" or why the draw is not a valid spacecraft (the checks of a scenario
// file: set_parameter, then validate_scenario and check_run_configuration).
struct McDraw {
  Scenario sc;
  std::vector<double> drawn;
  std::string invalid;
};
// `check` false: the draws and each key's own checks only (no reload, no
// plant or FSW check): the sample-statistics tests.
McDraw draw_run(const Scenario& nominal, uint64_t master, uint64_t run, bool check = true);

}  // namespace harness

#endif  // HARNESS_SRC_MC_DRAW_H

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

// One dispersed key bound to the nominal scenario: its key definition, list
// element and nominal value resolved once, a choice's values decoded once.
struct McTarget {
  size_t dispersion = 0;                // index into McBinding::specs
  std::string path;                     // as expanded: "wheels[2].axis"
  std::string name;                     // normalised: the stream's key, the columns' prefix
  const schema::KeyDef* key = nullptr;  // null: the path names no key
  size_t index = 0;                     // the element of the key's list
  bool suffixed = false;                // written with the key's unit suffix
  ParameterValue nominal{0.0};
  std::vector<ParameterValue> choices;     // choice: each value as the key's type
  std::vector<std::string> choice_errors;  // choice: "" or why value v is not of that type
  std::string error;                    // non-empty: no value to disperse (each draw is invalid)
};

// The dispersions of a campaign bound to its nominal scenario, in the order
// of the draws (dispersion by dispersion, list element by list element).
struct McBinding {
  std::vector<DispersionSpec> specs;     // monte_carlo.dispersions
  std::vector<std::string> spec_errors;  // per dispersion: why its key does not expand, or ""
  std::vector<McTarget> targets;
  std::vector<McColumn> columns;         // the drawn values' columns (summary table, scatter
                                         // plots), e.g. "wheels[1].axis.angle_deg", "events[0].t"
};

// Binds what the keys name in `nominal`; problems stay in the binding (a
// target's error makes each draw invalid), as check_monte_carlo reports them.
McBinding bind_dispersions(const Scenario& nominal);

// The binding of a campaign: bind_dispersions after the checks of
// check_monte_carlo, which throw ScenarioError (file:line of the dispersion,
// key monte_carlo.dispersions[i].key).
McBinding bind_campaign(const Scenario& nominal);

// The dispersed keys checked against a read scenario (names, types, list
// elements, a key dispersed twice, choice values); problems go to ctx.
void check_monte_carlo(const Ctx& ctx, Scenario& sc);

// Run k of the campaign: the scenario with its draws applied (monte_carlo
// removed, seed = mc_run_seed), the drawn values by McBinding::columns, and
// "" or why the draw is not a valid spacecraft (the checks of a scenario
// file: the key's own checks, then validate_scenario and
// check_run_configuration).
struct McDraw {
  Scenario sc;
  std::vector<double> drawn;
  std::string invalid;
};
// `bound`: bind_dispersions(nominal) or bind_campaign(nominal).  `check`
// false: the draws and each key's own checks only (no reload, no plant or
// FSW check): the sample-statistics tests.
McDraw draw_run(const Scenario& nominal, const McBinding& bound, uint64_t master, uint64_t run, bool check = true);
// The same, binding `nominal` for this run alone.
McDraw draw_run(const Scenario& nominal, uint64_t master, uint64_t run, bool check = true);

// The checks of a scenario file on a valid draw (draw_run's `check`): the
// drawn scenario becomes its reloaded canonical form, exactly what its
// manifest gives `kestrel run`; then, with `plant_and_fsw`,
// check_run_configuration.  Problems go to d.invalid.  Without
// `plant_and_fsw`, the run's own construction (Run, the same builders in
// the same order) must make that check: it throws the ScenarioError the
// check would have reported first.
void check_drawn_scenario(McDraw& d, bool plant_and_fsw = true);

}  // namespace harness

#endif  // HARNESS_SRC_MC_DRAW_H

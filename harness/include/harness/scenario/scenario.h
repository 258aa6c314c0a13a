// scenario: the scenario schema, loaded from YAML (or from a run manifest,
// which is JSON and therefore YAML) and validated key by key.
//
// Every key is checked: an unknown key, a wrong type or a physically invalid
// value is reported as `FILE:LINE:COL: KEY: message`, all problems of a file
// are collected, and load_scenario() throws ScenarioError so no run starts.
// Values are stored SI; keys with the suffixes the schema lists (`_rpm`,
// `_deg`, `_deg_s`, `_arcsec`, `_g_cm`, `_g_cm2`) are converted on load.
// The schema is documented in docs/harness.md; the types it fills are
// harness/core/scenario_types.h (what a Run needs).
#ifndef HARNESS_SCENARIO_SCENARIO_H
#define HARNESS_SCENARIO_SCENARIO_H

#include <cstdint>
#include <limits>
#include <map>
#include <type_traits>
#include <utility>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Dense>

#include "harness/core/scenario_types.h"

namespace harness {

// "key.path=value" overrides applied before validation (`kestrel run --set`).
// Paths use dots; list elements are addressed by index (wheels.0.J_s).
struct Override {
  std::string path;
  std::string value;  // parsed as YAML (so lists `[1,2,3]` work)
};

// Loads and validates.  A file whose top level has `kestrel_manifest` is a
// run manifest: its `scenario` object is loaded.  Throws ScenarioError with
// every problem found (also for unreadable files and YAML syntax errors).
Scenario load_scenario(const std::string& path, const std::vector<Override>& overrides = {});
// The same from text (`file_name` is used in messages).
Scenario load_scenario_text(const std::string& text, const std::string& file_name,
                            const std::vector<Override>& overrides = {});
// The same for the writer's canonical text of a loaded scenario
// (scenario_to_json_text, e.g. a Monte Carlo draw): the same reading and
// checks of every key, without the bounds on the text's form that the
// writer's output meets by construction (one document, depth, aliases,
// bytes; its length is still checked) and without key_lines (empty).
Scenario load_canonical_scenario_text(const std::string& text, const std::string& file_name);
// load_canonical_scenario_text(scenario_to_json_text(sc), file_name), without
// the text: the reader is given the node tree that parsing the writer's
// text gives (yaml_of_json, scenario/yaml_reader.h), built from the
// writer's JSON; the same keys read, the same checks, the same Scenario.
Scenario reload_canonical_scenario(const Scenario& sc, const std::string& file_name);

// The fully resolved scenario as canonical JSON (SI keys only, every default
// filled in).  load_scenario_text() of this text gives the same Scenario.
std::string scenario_to_json_text(const Scenario& sc, int indent = 2);

// A JSON Schema (draft-07) of the scenario file, from the same key table, for
// editors (`kestrel schema`, docs/scenario-schema.md): keys, types, required
// keys.  Value ranges and cross-key rules are `kestrel validate`'s.
std::string scenario_json_schema_text(int indent = 2);

// Parses "a.b=c" into an Override; throws std::invalid_argument.
Override parse_override(const std::string& s);

// A typed value for set_parameter(): a number (also for integer keys), a
// flag, a word (strings and choices such as "sun_safe"), a 3-vector (also
// a diagonal inertia) or a 3x3 matrix (inertia).
struct ParameterValue {
  std::variant<double, long long, uint64_t, bool, std::string, Eigen::Vector3d, Eigen::Matrix3d> value;
  ParameterValue(double v) : value(v) {}
  ParameterValue(int v) : value(static_cast<long long>(v)) {}
  ParameterValue(long v) : value(static_cast<long long>(v)) {}
  ParameterValue(long long v) : value(v) {}
  ParameterValue(unsigned v) : value(static_cast<uint64_t>(v)) {}
  ParameterValue(unsigned long v) : value(static_cast<uint64_t>(v)) {}
  ParameterValue(unsigned long long v) : value(static_cast<uint64_t>(v)) {}
  ParameterValue(bool v) : value(v) {}
  ParameterValue(const char* v) : value(std::string(v)) {}
  ParameterValue(std::string v) : value(std::move(v)) {}
  template <class D>
  ParameterValue(const Eigen::MatrixBase<D>& m)
  {
    static_assert((D::RowsAtCompileTime == 3 && D::ColsAtCompileTime == 1) ||
                      (D::RowsAtCompileTime == 3 && D::ColsAtCompileTime == 3),
                  "a 3-vector or a 3x3 matrix");
    if constexpr (D::ColsAtCompileTime == 1) value = Eigen::Vector3d(m);
    else value = Eigen::Matrix3d(m);
  }
};

// Sets one key of a loaded scenario without YAML (Monte Carlo, Python):
// `path` as for --set ("fsw.mrp_fb.K", "wheels.2.Omega_0_rpm",
// "wheels[2].J_s"; a unit suffix converts as in a file).  The key's own
// definition checks the value (type, bounds, unit vector, inertia): on a
// problem it throws ScenarioError naming the key and leaves sc unchanged.
// Checks that involve other keys (duration a multiple of dt, u_min < u_max,
// burn names a main engine, ...) are validate_scenario()'s job.
void set_parameter(Scenario& sc, const std::string& path, const ParameterValue& value);
// The value of a settable key as set_parameter takes it (in the unit of the
// path's spelling: "wheels[0].Omega_0_rpm" in rpm).  Throws ScenarioError.
ParameterValue get_parameter(const Scenario& sc, const std::string& path);

// Every check of load_scenario() on a Scenario built or changed in code:
// its canonical form is reloaded (the manifest round trip).  Throws
// ScenarioError (issues name keys; no line numbers).
void validate_scenario(const Scenario& sc);

// The checks a run makes before its first step, without building the run:
// the plant (sim::Plant), the FSW configuration (fsw_acs_check and
// fsw_acs_init), the sensor models and the burn schedule -- the same
// functions Run calls, so `kestrel validate` accepts exactly what a run
// accepts.  No recorder, schedule or row storage is built: the cost does not
// depend on the duration.  Throws ScenarioError (at the key's line).
void check_run_configuration(const Scenario& sc);

// Every key path the schema knows, list elements as [i] (e.g.
// "wheels[i].Omega_0", alternative spellings as "wheels[i].Omega_0_rpm").
std::vector<std::string> scenario_key_paths();

}  // namespace harness

#endif  // HARNESS_SCENARIO_SCENARIO_H

// yaml_reader: a checked reader of YAML maps, independent of the scenario
// schema.  One MapReader per YAML map consumes the keys a caller knows and
// decodes each to a type (finite real, bounded integer, flag, string, one of
// a set of words, 3-vector, unit 3-vector, inertia matrix); whatever is left
// at finish() is an unknown key, reported with a did-you-mean hint.  Every
// problem becomes a ScenarioIssue `FILE:LINE:COL: KEY: message` collected
// in a Ctx, so all problems of a file are reported at once; a key given on
// the command line (`--set`) is named instead of a line.
//
// Private to the harness library (tested alone in test/harness/test_yaml_reader.cpp).
#ifndef HARNESS_SRC_YAML_READER_H
#define HARNESS_SRC_YAML_READER_H

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "harness/scenario/scenario.h"

namespace harness {

constexpr double kUnitTol = 1e-3;  // [-] tolerance on given unit vectors (renormalised)
constexpr double kSymTol = 1e-9;   // [-] relative inertia symmetry tolerance

// A check on a number: "" when valid, else the reason ("must be > 0 [kg]").
using NumberCheck = std::function<std::string(double)>;

// Where problems go.  `overridden` holds the dotted paths set on the command
// line: a problem under one of them names the `--set` instead of a line.
struct Ctx {
  std::string file;
  std::vector<ScenarioIssue>* issues = nullptr;
  std::set<std::string> overridden;

  void error(const YAML::Node& at, const std::string& key, const std::string& msg) const;
};

// "null", "scalar 'x'", "a list", "a map": what a node is, for messages.
std::string kind_name(const YAML::Node& n);
// A number for messages (10 significant digits).
std::string fmt(double v);
// "a.b" from "a" and "b"; just "b" at the top.
std::string join(const std::string& path, const std::string& key);
// Decoders that refuse non-scalars (and, for reals, empty scalars).
bool decode_double(const YAML::Node& n, double& out);
// A plain decimal literal (an optional sign, digits with at most one '.',
// at least one digit, an optional exponent e/E with optional sign and
// digits), read to a finite double: true and out set.  That value is the one
// yaml-cpp's stream conversion gives the same text in the "C" locale (its
// num_get collects these characters and hands them to strtod; from_chars
// rounds to nearest as strtod does), found without a stream: decode_double
// takes it first.  Anything else (.inf, .nan, spaces, hexadecimal, a value
// beyond the double range) is false and left to yaml-cpp.
bool plain_decimal_value(const std::string& s, double& out);
bool decode_int(const YAML::Node& n, long long& out);
// The known word nearest to `k` (edit distance < 3), or "".
std::string did_you_mean(const std::string& k, const std::vector<std::string>& known);

// Value checks shared by the YAML reader and the typed setter.  Each returns
// "" when valid, else the reason.
// |v| = 1 within kUnitTol; renormalises v (an already-normalised vector is
// left bit-for-bit alone so a manifest reloads to exactly the same values).
std::string check_unit_vector(Eigen::Vector3d& v);
// Symmetric, positive definite, triangle inequality of the principal moments.
std::string check_inertia(const Eigen::Matrix3d& m);

// ---- bounds on the text, checked before any node tree is built ---------------
// A scenario is a few kilobytes with a few hundred nodes, nested 5 deep; a run
// manifest a few times that.  Anything far beyond is refused with the place.
constexpr size_t kMaxYamlBytes = 1u << 20;   // [bytes] 1 MiB per file
constexpr size_t kMaxYamlDepth = 32;         // [-] nested maps and lists
constexpr size_t kMaxYamlNodes = 20000;      // [-] nodes after alias expansion
constexpr size_t kMaxYamlList = 1000;        // [-] entries of one list or map

// Checks `text` as one YAML document: size, no NUL or other control bytes
// (binary input), a single document, nesting depth, the size after alias
// expansion (alias bombs; an alias inside its own anchor is a cycle), list
// lengths.  Computed on the parser's events in time linear in the text,
// never expanding an alias.  Returns the problems (empty: fine); each names
// file:line:col.  YAML syntax errors are reported as such.
// A problem of the file as a whole (key "(file)"); line 0: no place in it.
ScenarioIssue file_issue(const std::string& file, int line, int col, const std::string& msg);

std::vector<ScenarioIssue> check_yaml_text(const std::string& text, const std::string& file);

// The node tree YAML::Load(j.dump(indent)) gives, built from j without the
// text: maps in j's key order, sequences, scalars holding the text the
// dump writes for a number or a boolean and the unescaped string of a
// string, null as a null node.  Only the marks differ (none: no line).
YAML::Node yaml_of_json(const nlohmann::json& j);
// yaml_of_json for a sequence of documents of one shape (a campaign's draws:
// the same keys, lists and nulls, a few numbers apart), the tree kept
// between them.  A document with the kept one's shape has the text of its
// changed scalars set in the kept tree, in place (a node's memory is never
// released before the tree's: a new node per draw would grow it); any other
// document builds the tree anew.  Either way the tree is yaml_of_json(j)'s
// (kind, scalar text, keys in order), valid until the next call.  Lookups
// of absent keys through a non-const node add empty entries to the kept
// tree that iteration and sizes skip; a reader doing the same lookups adds
// them once.  One per thread: not shared.
class KeptYamlTree {
 public:
  const YAML::Node& tree_of(nlohmann::json j);
  uint64_t built() const { return built_; }    // trees built anew
  uint64_t reused() const { return reused_; }  // documents set into the kept tree

 private:
  nlohmann::json json_;              // the document the tree holds
  std::optional<YAML::Node> tree_;   // replaced whole, never assigned (see tree_of)
  std::vector<YAML::Node> leaves_;   // the tree's scalar and null nodes, in the document's order
  bool kept_ = false;
  uint64_t built_ = 0, reused_ = 0;
};

// The text j.dump() writes for a scalar (a number, a boolean; others by
// dump() itself), without a serializer: a double by nlohmann's own shortest
// round-trip routine (the one its serializer calls), an integer in decimal.
std::string json_scalar_text(const nlohmann::json& j);

// Where every key sits in a document: dotted path (list indices as [i]) ->
// (line, column), 1-based.
void collect_key_lines(const YAML::Node& n, const std::string& path,
                       std::map<std::string, std::pair<int, int>>& out);

class MapReader {
 public:
  // `node` absent (present = false), null or not a map reads as an empty
  // map; not a map is reported.  Duplicate keys are reported here.
  MapReader(const Ctx& ctx, const YAML::Node& node, std::string path, bool present = true);

  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  const Ctx& ctx() const { return *ctx_; }
  // Keys merged in from another map (wheel_defaults) are named by where they
  // are written, e.g. wheel_defaults.model.
  std::string key_path(const std::string& key) const;
  void set_alias(const std::string& key, const std::string& origin) { alias_[key] = origin; }

  bool has(const std::string& key) const { return !synthetic_ && node_[key].IsDefined(); }
  // The value (undefined when absent); marks the key as known.
  YAML::Node get(const std::string& key);
  void mark_known(const std::string& key) { used_.insert(key); }

  // Where a problem of `key` with value `v` is reported: the value, or the
  // key itself when the value is empty (null).
  YAML::Node at(const std::string& key, const YAML::Node& v) const;
  void error_at(const std::string& key, const std::string& msg);
  // At the key itself (a problem of the whole value, e.g. a list of wheels).
  void error_at_key(const std::string& key, const std::string& msg);
  void error_self(const std::string& msg);
  void missing(const std::string& key, const std::string& what);

  // ---- scalars -------------------------------------------------------------
  // A finite real; `check` sees the value as written, the result is times `factor`.
  std::optional<double> real(const std::string& key, const NumberCheck& check = {}, double factor = 1.0);
  // A quantity accepted as `key` (SI) or as `key<suffix>` (factor to SI),
  // never both.  The check applies to the value as written.
  std::optional<double> quantity(const std::string& key, const std::string& suffix, double factor,
                                 const NumberCheck& check = {});
  std::optional<long long> integer(const std::string& key, long long lo, long long hi);
  std::optional<uint64_t> uinteger(const std::string& key);
  std::optional<bool> boolean(const std::string& key);
  std::optional<std::string> string(const std::string& key);
  // One of `options`; returns the index.
  std::optional<size_t> choice(const std::string& key, const std::vector<std::string>& options);

  // ---- vectors and matrices ------------------------------------------------
  std::optional<Eigen::Vector3d> vec3(const std::string& key, double factor = 1.0);
  std::optional<Eigen::Vector3d> vec3_of(const YAML::Node& v, const std::string& kp, double factor = 1.0);
  std::optional<Eigen::Vector3d> unit_vec3(const std::string& key);
  std::optional<Eigen::Vector3d> unit_of(const YAML::Node& v, const std::string& kp);
  // 3x3 as nested lists, or 3 numbers for a diagonal; checked by check_inertia().
  std::optional<Eigen::Matrix3d> inertia(const std::string& key);

  // Which spelling of a key with an alternative-unit suffix is given: the
  // plain key (false) or key<suffix> (true); both are marked known.  Both
  // given is reported and gives nullopt.
  std::optional<bool> spelling(const std::string& key, const std::string& suffix);

  // Every key not consumed is unknown (did-you-mean among the known ones).
  void finish(const std::set<std::string>& ignore = {});

  MapReader sub(const std::string& key);

 private:
  // Reports `key` as given without a value where `expected` was needed.
  std::nullopt_t empty_value(const std::string& key, const std::string& expected);
  static YAML::Node pick(const Ctx& ctx, const YAML::Node& node, const std::string& path, bool present);

  const Ctx* ctx_;
  YAML::Node node_;
  std::string path_;
  bool synthetic_ = false;
  std::set<std::string> used_;
  std::map<std::string, std::string> alias_;
};

}  // namespace harness

#endif  // HARNESS_SRC_YAML_READER_H

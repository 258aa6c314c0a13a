// scenario_monte_carlo.cpp: the `monte_carlo` section (docs/monte-carlo.md):
// runs, master seed, dispersions, pass/fail criteria, retention.  Read with
// the rest of the file; the dispersed keys are checked against the scenario
// once every section is read (check_monte_carlo).  A run ignores the
// section; `kestrel mc` uses it.
#include <cmath>
#include <limits>
#include <set>

#include "scenario/mc_draw.h"
#include "scenario/overrides.h"
#include "scenario/scenario_limits.h"
#include "scenario/scenario_schema.h"

namespace harness {

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr size_t kMaxDispersions = 200;   // [-] entries of monte_carlo.dispersions
constexpr size_t kMaxCriteria = 50;       // [-] entries of monte_carlo.criteria
constexpr size_t kMaxChoices = 100;       // [-] values of one choice
constexpr uint64_t kMaxRuns = kMaxMcRuns;  // [-] runs of one campaign (scenario_limits.h)
constexpr double kMaxAngleDeg = 180.0;    // [deg] a dispersion angle beyond is not a dispersion
// truncated_normal: the bounds must keep at least this probability of the
// untruncated normal, so rejection sampling needs ~1/p draws at most
// (1 % -> the chance that 10,000 draws all miss is e^-100).
constexpr double kMinTruncMass = 0.01;

const std::vector<std::string> kDistNames = {"normal",      "truncated_normal", "uniform",  "choice",
                                             "unit_vector", "normal_vector",    "attitude", "inertia"};
const std::vector<std::string> kStats = {"max", "min", "max_abs", "final", "mean", "rms", "error_count"};

// The keys each distribution takes (besides key and dist).
const std::vector<std::set<std::string>> kDistKeys = {
    {"mean", "std"},
    {"mean", "std", "min", "max"},
    {"min", "max", "half_width"},
    {"values", "weights"},
    {"angle_std", "angle_std_deg", "angle_max", "angle_max_deg"},
    {"std"},
    {"angle_std", "angle_std_deg", "angle_max", "angle_max_deg"},
    {"angle_std", "angle_std_deg", "principal_std_rel"},
};

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// Every key a distribution may take (besides key and dist), in the order
// they are checked.
const std::vector<std::string> kDistKeyOrder = {"mean",          "std",       "min",           "max",
                                                "half_width",    "values",    "weights",       "angle_std",
                                                "angle_std_deg", "angle_max", "angle_max_deg", "principal_std_rel"};
const std::set<std::string> kAllDistKeys(kDistKeyOrder.begin(), kDistKeyOrder.end());

// Required key k: false (and a "missing" problem) when absent.
bool need(MapReader& d, const char* k, const char* what)
{
  if (d.has(k)) return true;
  d.missing(k, what);
  return false;
}

// min < max, both required; false when one is missing.
bool read_bounds(MapReader& d, DispersionSpec& s, const char* min_what)
{
  const bool has_min = need(d, "min", min_what);
  const bool ok = need(d, "max", "upper bound, in the key's unit") && has_min;
  s.min = d.real("min");
  s.max = d.real("max");
  if (s.min && s.max && !(*s.min < *s.max)) d.error_at("max", "must be > min");
  return ok;
}

// normal, truncated_normal; false when a required key is missing or std is not > 0.
bool read_normal(MapReader& d, DispersionSpec& s)
{
  if (d.has("mean")) s.mean = d.real("mean");
  bool ok = need(d, "std", "standard deviation, in the key's unit");
  if (auto v = d.real("std", [](double x) { return x > 0.0 ? "" : "must be > 0"; })) s.std = *v;
  else ok = false;
  if (s.dist == DistKind::TruncatedNormal) ok = read_bounds(d, s, "lower bound, in the key's unit") && ok;
  return ok;
}

void read_uniform(MapReader& d, DispersionSpec& s)
{
  if (!d.has("half_width")) {
    read_bounds(d, s, "lower bound, in the key's unit (or half_width about the nominal value)");
    return;
  }
  s.half_width = d.real("half_width", [](double x) { return x > 0.0 ? "" : "must be > 0"; });
  if (d.has("min") || d.has("max")) d.error_at_key("half_width", "give half_width or min and max, not both");
}

void read_choice_weights(MapReader& d, DispersionSpec& s, size_t values)
{
  const YAML::Node w = d.get("weights");
  if (!w.IsDefined()) return;
  if (!w.IsSequence() || w.size() != values) {
    d.error_at("weights", "expected a list of " + std::to_string(values) + " weights (one per value)");
    return;
  }
  double sum = 0.0;
  for (size_t i = 0; i < w.size(); ++i) {
    double x = 0.0;
    if (!decode_double(w[i], x) || !std::isfinite(x) || x < 0.0) {
      d.ctx().error(w[i], d.key_path("weights") + "[" + std::to_string(i) + "]", "must be a number >= 0");
      continue;
    }
    s.weights.push_back(x);
    sum += x;
  }
  if (s.weights.size() == w.size() && !(sum > 0.0)) d.error_at("weights", "must not all be zero");
}

void read_choice(MapReader& d, DispersionSpec& s)
{
  const YAML::Node v = d.get("values");
  if (!v.IsDefined()) {
    d.missing("values", "a list of the values to choose from");
    return;
  }
  if (!v.IsSequence() || v.size() == 0 || v.size() > kMaxChoices) {
    d.error_at("values", "expected a list of 1 to " + std::to_string(kMaxChoices) + " values, got " + kind_name(v));
    return;
  }
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].IsScalar()) {
      d.ctx().error(v[i], d.key_path("values") + "[" + std::to_string(i) + "]", "expected a value, got " + kind_name(v[i]));
      continue;
    }
    s.values.push_back(v[i].Scalar());
  }
  read_choice_weights(d, s, v.size());
}

void read_normal_vector(MapReader& d, DispersionSpec& s)
{
  const YAML::Node v = d.get("std");
  if (!v.IsDefined()) {
    d.missing("std", "standard deviation per axis: one number or [x, y, z], in the key's unit");
    return;
  }
  double x = 0.0;
  if (v.IsScalar() && decode_double(v, x)) {
    s.std_vec = Eigen::Vector3d::Constant(x);
  } else if (auto vec = d.vec3_of(v, d.key_path("std"))) {
    s.std_vec = *vec;
  } else {
    return;
  }
  if (!(s.std_vec.minCoeff() >= 0.0 && s.std_vec.maxCoeff() > 0.0 && s.std_vec.allFinite()))
    d.error_at("std", "must be >= 0 on every axis and > 0 on one");
}

// unit_vector, attitude, inertia: the angles (and inertia's principal_std_rel).
void read_angles(MapReader& d, DispersionSpec& s)
{
  auto angle = [&](const char* k) -> std::optional<double> {
    if (!d.has(k) && !d.has(std::string(k) + "_deg")) return std::nullopt;
    return d.quantity(k, "_deg", kDeg, [](double) { return std::string(); });
  };
  s.angle_std = angle("angle_std");
  if (s.dist != DistKind::Inertia) s.angle_max = angle("angle_max");
  const bool both = s.angle_std && s.angle_max;
  if (both) d.error_at_key("angle_std", "give angle_std or angle_max, not both");
  for (const auto& [a, name] : {std::pair{s.angle_std, "angle_std"}, std::pair{s.angle_max, "angle_max"}})
    if (a && !(*a > 0.0 && *a <= kMaxAngleDeg * kDeg))
      d.error_at_key(d.has(name) ? name : std::string(name) + "_deg", "must be > 0 and at most 180 deg");
  if (s.dist == DistKind::Inertia) {
    if (d.has("principal_std_rel"))
      if (auto p = d.real("principal_std_rel", [](double x) { return x >= 0.0 && x <= 0.5 ? "" : "must be in [0, 0.5]"; }))
        s.principal_std_rel = *p;
    if (!s.angle_std && s.principal_std_rel == 0.0)
      d.error_self("an inertia dispersion needs angle_std(_deg) and/or principal_std_rel > 0");
  } else if (!s.angle_std && !s.angle_max) {
    d.missing("angle_std_deg", "the dispersion angle: angle_std(_deg) (normal per axis) or angle_max(_deg) (uniform)");
  }
}

// truncated_normal with its own mean: the bounds keep enough of the normal
// (about the nominal value: checked per key in check_monte_carlo).
void check_truncated_mass(MapReader& d, const DispersionSpec& s)
{
  if (!(s.min && s.max && *s.min < *s.max && s.std > 0.0 && s.mean)) return;
  const double p = normal_cdf((*s.max - *s.mean) / s.std) - normal_cdf((*s.min - *s.mean) / s.std);
  if (!(p >= kMinTruncMass))
    d.error_self("the bounds [" + fmt(*s.min) + ", " + fmt(*s.max) + "] keep only " + fmt(p) +
                 " of the normal distribution (at least 0.01 is needed): widen them or move the mean");
}

void read_dispersion(MapReader& d, MonteCarloSpec& mc)
{
  DispersionSpec s;
  s.line = d.node().Mark().line + 1;
  s.column = d.node().Mark().column + 1;
  const auto key = d.string("key");
  const auto dist = d.choice("dist", kDistNames);
  if (!key && !d.has("key")) d.missing("key", "the scenario key to disperse, e.g. spacecraft.inertia or wheels[*].axis");
  if (!dist && !d.has("dist")) d.missing("dist", "one of normal, truncated_normal, uniform, choice, unit_vector, "
                                                 "normal_vector, attitude, inertia");
  if (!key || !dist) {
    d.finish(kAllDistKeys);
    return;
  }
  s.key = *key;
  s.dist = static_cast<DistKind>(*dist);
  for (const std::string& k : kDistKeyOrder)
    if (d.has(k) && kDistKeys[*dist].count(k) == 0) {
      d.mark_known(k);
      d.error_at_key(k, "does not apply to dist " + kDistNames[*dist]);
    }
  bool ok = true;
  switch (s.dist) {
    case DistKind::Normal:
    case DistKind::TruncatedNormal: ok = read_normal(d, s); break;
    case DistKind::Uniform: read_uniform(d, s); break;
    case DistKind::Choice: read_choice(d, s); break;
    case DistKind::NormalVector: read_normal_vector(d, s); break;
    case DistKind::UnitVector:
    case DistKind::Attitude:
    case DistKind::Inertia: read_angles(d, s); break;
  }
  d.finish(kAllDistKeys);
  if (ok && s.dist == DistKind::TruncatedNormal) check_truncated_mass(d, s);
  mc.dispersions.push_back(s);
}

void read_criterion(MapReader& c, MonteCarloSpec& mc)
{
  CriterionSpec s;
  s.line = c.node().Mark().line + 1;
  s.column_no = c.node().Mark().column + 1;
  const auto name = c.string("name");
  const auto col = c.string("column");
  const auto stat = c.choice("stat", kStats);
  if (!col && !c.has("column")) c.missing("column", "a recorded column, quantity or prefix* (e.g. pointing_error_deg)");
  if (col) s.column = *col;
  if (stat) s.stat = kStats[*stat];
  s.name = name ? *name : "c" + std::to_string(mc.criteria.size() + 1);
  if (auto a = c.real("after", [](double x) { return x >= 0.0 ? "" : "must be >= 0 [s]"; })) s.after = *a;
  if (c.has("until")) s.until = c.real("until");
  if (s.until && !(*s.until >= s.after)) c.error_at("until", "must be >= after");
  if (c.has("below")) s.below = c.real("below");
  if (c.has("above")) s.above = c.real("above");
  if (!c.has("below") && !c.has("above")) c.missing("below", "the threshold: below: x (pass when the value < x) or above: x");
  if (c.has("below") && c.has("above")) c.error_at_key("above", "give below or above, not both");
  c.finish();
  for (const CriterionSpec& o : mc.criteria)
    if (o.name == s.name) c.error_at("name", "a criterion '" + s.name + "' is already defined");
  mc.criteria.push_back(s);
}

void read_mc(const schema::KeyDef&, MapReader& top, Scenario& sc, size_t)
{
  if (!top.has("monte_carlo")) return;
  MapReader r = top.sub("monte_carlo");
  MonteCarloSpec mc;
  mc.line = r.node().Mark().line + 1;
  if (auto n = r.uinteger("runs")) {
    if (*n < 1 || *n > kMaxRuns) r.error_at("runs", "must be in [1, " + std::to_string(kMaxRuns) + "]");
    mc.runs = *n;
  }
  if (auto s = r.uinteger("seed")) mc.seed = *s;
  const YAML::Node disp = r.get("dispersions");
  if (disp.IsDefined() && !disp.IsNull()) {
    if (!disp.IsSequence() || disp.size() > kMaxDispersions) {
      r.error_at("dispersions", "expected a list of at most " + std::to_string(kMaxDispersions) +
                                    " {key, dist, ...}, got " + kind_name(disp));
    } else {
      for (size_t i = 0; i < disp.size(); ++i) {
        MapReader d(r.ctx(), disp[i], r.key_path("dispersions") + "[" + std::to_string(i) + "]");
        read_dispersion(d, mc);
      }
    }
  }
  const YAML::Node crit = r.get("criteria");
  if (crit.IsDefined() && !crit.IsNull()) {
    if (!crit.IsSequence() || crit.size() > kMaxCriteria) {
      r.error_at("criteria", "expected a list of at most " + std::to_string(kMaxCriteria) +
                                 " {name, column, stat, after, below|above}, got " + kind_name(crit));
    } else {
      for (size_t i = 0; i < crit.size(); ++i) {
        MapReader c(r.ctx(), crit[i], r.key_path("criteria") + "[" + std::to_string(i) + "]");
        read_criterion(c, mc);
      }
    }
  }
  if (r.has("retention")) {
    MapReader t = r.sub("retention");
    RetentionSpec& k = mc.retention;
    if (auto v = t.integer("keep_first", 0, 1000000)) k.keep_first = static_cast<uint32_t>(*v);
    if (auto v = t.boolean("keep_failing")) k.keep_failing = *v;
    if (auto v = t.integer("max_failing", 0, 1000000)) k.max_failing = static_cast<uint32_t>(*v);
    if (auto v = t.integer("thin_samples", 2, 100000)) k.thin_samples = static_cast<uint32_t>(*v);
    t.finish();
  }
  r.finish();
  sc.monte_carlo = mc;
}

void write_mc(const schema::KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t)
{
  if (!sc.monte_carlo) return;
  const MonteCarloSpec& mc = *sc.monte_carlo;
  nlohmann::json o = {{"runs", mc.runs}, {"seed", mc.seed}};
  nlohmann::json d = nlohmann::json::array();
  for (const DispersionSpec& s : mc.dispersions) {
    nlohmann::json x = {{"key", s.key}, {"dist", kDistNames[static_cast<size_t>(s.dist)]}};
    switch (s.dist) {
      case DistKind::Normal:
      case DistKind::TruncatedNormal:
        if (s.mean) x["mean"] = *s.mean;
        x["std"] = s.std;
        if (s.dist == DistKind::TruncatedNormal) {
          x["min"] = *s.min;
          x["max"] = *s.max;
        }
        break;
      case DistKind::Uniform:
        if (s.half_width) x["half_width"] = *s.half_width;
        else {
          x["min"] = *s.min;
          x["max"] = *s.max;
        }
        break;
      case DistKind::Choice:
        x["values"] = s.values;  // as written: strings read back as the key's type
        if (!s.weights.empty()) x["weights"] = s.weights;
        break;
      case DistKind::NormalVector: x["std"] = {s.std_vec(0), s.std_vec(1), s.std_vec(2)}; break;
      case DistKind::UnitVector:
      case DistKind::Attitude:
      case DistKind::Inertia:
        if (s.angle_std) x["angle_std"] = *s.angle_std;
        if (s.angle_max) x["angle_max"] = *s.angle_max;
        if (s.dist == DistKind::Inertia && s.principal_std_rel > 0.0) x["principal_std_rel"] = s.principal_std_rel;
        break;
    }
    d.push_back(x);
  }
  o["dispersions"] = d;
  nlohmann::json c = nlohmann::json::array();
  for (const CriterionSpec& s : mc.criteria) {
    nlohmann::json x = {{"name", s.name}, {"column", s.column}, {"stat", s.stat}, {"after", s.after}};
    if (s.until) x["until"] = *s.until;
    if (s.below) x["below"] = *s.below;
    if (s.above) x["above"] = *s.above;
    c.push_back(x);
  }
  o["criteria"] = c;
  const RetentionSpec& r = mc.retention;
  o["retention"] = {{"keep_first", r.keep_first},
                    {"keep_failing", r.keep_failing},
                    {"max_failing", r.max_failing},
                    {"thin_samples", r.thin_samples}};
  j[k.name] = o;
}

// The schema type a distribution draws.
bool dist_fits(DistKind d, schema::Type t, const std::string& key_name)
{
  using schema::Type;
  switch (d) {
    case DistKind::Normal:
    case DistKind::TruncatedNormal:
    case DistKind::Uniform: return t == Type::Real || t == Type::Integer || t == Type::Unsigned;
    case DistKind::Choice:
      return t == Type::Real || t == Type::Integer || t == Type::Unsigned || t == Type::Bool || t == Type::String ||
             t == Type::Choice;
    case DistKind::UnitVector: return t == Type::UnitVec3;
    case DistKind::NormalVector: return t == Type::Vec3;
    case DistKind::Attitude: return t == Type::Vec3 && key_name.rfind("sigma_", 0) == 0;
    case DistKind::Inertia: return t == Type::Inertia;
  }
  return false;
}

const char* dist_needs(DistKind d)
{
  switch (d) {
    case DistKind::Normal:
    case DistKind::TruncatedNormal:
    case DistKind::Uniform: return "a number key";
    case DistKind::Choice: return "a single-value key";
    case DistKind::UnitVector: return "a unit-vector key (an axis or direction)";
    case DistKind::NormalVector: return "a 3-vector key";
    case DistKind::Attitude: return "an attitude (MRP) key such as spacecraft.initial.sigma_BN";
    case DistKind::Inertia: return "an inertia key";
  }
  return "";
}

}  // namespace

namespace schema {
namespace {
// The JSON Schema shape of the section: its keys, each distribution's own
// parameters, the criteria's statistics (docs/monte-carlo.md).
nlohmann::json mc_shape()
{
  using nlohmann::json;
  json dprops = {{"key", {{"type", "string"}}}, {"dist", {{"enum", kDistNames}}}};
  for (const std::string& k : kDistKeyOrder) dprops[k] = json::object();
  json dispersion = json_object_of(dprops, {"key", "dist"});
  for (size_t d = 0; d < kDistNames.size(); ++d) {  // a parameter of another distribution is refused
    std::vector<std::string> allowed = {"key", "dist"};
    allowed.insert(allowed.end(), kDistKeys[d].begin(), kDistKeys[d].end());
    dispersion["allOf"].push_back({{"if", {{"properties", {{"dist", {{"const", kDistNames[d]}}}}}}},
                                   {"then", {{"propertyNames", {{"enum", allowed}}}}}});
  }
  json criterion = json_object_of({{"name", {{"type", "string"}}},
                                   {"column", {{"type", "string"}}},
                                   {"stat", {{"enum", kStats}}},
                                   {"after", {{"type", "number"}, {"minimum", 0}}},
                                   {"until", {{"type", "number"}}},
                                   {"below", {{"type", "number"}}},
                                   {"above", {{"type", "number"}}}},
                                  {"column"});
  json one_threshold = json::array();
  one_threshold.push_back({{"required", json::array({"below"})}});
  one_threshold.push_back({{"required", json::array({"above"})}});
  criterion["oneOf"] = one_threshold;
  const auto count = [](long long lo) { return json{{"type", "integer"}, {"minimum", lo}, {"maximum", 1000000}}; };
  json retention = json_object_of({{"keep_first", count(0)},
                                   {"keep_failing", {{"type", "boolean"}}},
                                   {"max_failing", count(0)},
                                   {"thin_samples", {{"type", "integer"}, {"minimum", 2}, {"maximum", 100000}}}});
  return json_object_of({{"runs", {{"type", "integer"}, {"minimum", 1}, {"maximum", kMaxRuns}}},
                         {"seed", {{"type", "integer"}, {"minimum", 0}, {"maximum", std::numeric_limits<uint64_t>::max()}}},
                         {"dispersions", json_list_of(dispersion, 0, kMaxDispersions)},
                         {"criteria", json_list_of(criterion, 0, kMaxCriteria)},
                         {"retention", retention}});
}
}  // namespace

KeyDef monte_carlo_key()
{
  return custom("monte_carlo", read_mc, write_mc)
      .json_shape(mc_shape())
      .unit("a campaign: runs, seed, dispersions, criteria, retention (docs/monte-carlo.md)");
}
}  // namespace schema

std::vector<std::string> expand_dispersion_key(const Scenario& sc, const std::string& key, std::string& why)
{
  const size_t star = key.find("[*]");
  if (star == std::string::npos) return {key};
  if (key.find("[*]", star + 1) != std::string::npos) {
    why = "at most one [*] in a key";
    return {};
  }
  const KeyTarget t = resolve_path(split_path(key.substr(0, star)), list_sizes(sc));
  if (!t.error.empty() || t.key || !t.section || !t.section->list) {
    why = "[*] must follow a list (wheels, thrusters, events)";
    return {};
  }
  const size_t n = t.section->count ? t.section->count(sc) : 0;
  std::vector<std::string> out;
  for (size_t i = 0; i < n; ++i) out.push_back(key.substr(0, star) + "[" + std::to_string(i) + "]" + key.substr(star + 3));
  if (out.empty()) why = "the list is empty in this scenario";
  return out;
}

namespace {

// What is wrong with dispersing bound key t ("" when nothing); `seen`: the
// keys dispersed so far (without their unit suffix).
std::string target_problem(const McTarget& t, const DispersionSpec& s, std::set<std::string>& seen)
{
  static const std::set<std::string> kStructure = {"name",  "description", "seed",   "duration",
                                                   "rates", "monte_carlo", "outputs"};
  const std::vector<std::string> parts = split_path(t.path);
  if (!parts.empty() && kStructure.count(parts[0]))
    return "cannot be dispersed: it sets the run's structure (the time grid, the seeds, the outputs)";
  if (!t.error.empty()) return t.error;
  if (!dist_fits(s.dist, t.key->type, t.key->name))
    return "dist " + kDistNames[static_cast<size_t>(s.dist)] + " needs " + dist_needs(s.dist);
  const std::string& k = t.path;
  const std::string norm = normalise_path(split_path(t.suffixed ? k.substr(0, k.size() - t.key->suffix.size()) : k));
  if (!seen.insert(norm).second) return "dispersed twice (" + norm + ")";
  if (s.dist == DistKind::TruncatedNormal && !s.mean) {
    const ParameterValue& nominal = t.nominal;
    const double mean = std::holds_alternative<double>(nominal.value) ? std::get<double>(nominal.value)
                        : std::holds_alternative<long long>(nominal.value)
                            ? static_cast<double>(std::get<long long>(nominal.value))
                            : static_cast<double>(std::get<uint64_t>(nominal.value));
    const double p = normal_cdf((*s.max - mean) / s.std) - normal_cdf((*s.min - mean) / s.std);
    if (!(p >= kMinTruncMass))
      return "the bounds [" + fmt(*s.min) + ", " + fmt(*s.max) + "] about the nominal " + fmt(mean) + " keep only " +
             fmt(p) + " of the normal distribution (at least 0.01 is needed)";
  }
  return "";
}

// The first value of a choice that key t refuses (each set in turn on a copy
// of sc), or "".
std::string choice_problem(const McTarget& t, const DispersionSpec& s, const Scenario& sc)
{
  Scenario probe = sc;
  for (size_t v = 0; v < s.values.size(); ++v) {
    std::string bad = t.choice_errors[v];
    if (bad.empty()) bad = t.key->set(*t.key, probe, t.index, t.choices[v], t.suffixed);
    if (!bad.empty()) return "value " + std::to_string(v) + " ('" + s.values[v] + "'): " + bad;
  }
  return "";
}

// The problems of the binding of sc's dispersions, each at the line of its
// dispersion, key monte_carlo.dispersions[i].key.  A dispersion's keys are
// checked until one has a problem (a choice's values: each key).
void report_problems(const Ctx& ctx, const Scenario& sc, const McBinding& b)
{
  std::set<std::string> seen;
  size_t t = 0;  // b.targets: dispersion by dispersion
  for (size_t i = 0; i < b.specs.size(); ++i) {
    const DispersionSpec& s = b.specs[i];
    auto error = [&](const std::string& msg) {
      ScenarioIssue is;
      is.file = ctx.file;
      is.line = s.line;
      is.column = s.column;
      is.key = "monte_carlo.dispersions[" + std::to_string(i) + "].key";
      is.message = "'" + s.key + "': " + msg;
      ctx.issues->push_back(is);
    };
    if (!b.spec_errors[i].empty()) error(b.spec_errors[i]);
    bool stop = false;
    for (; t < b.targets.size() && b.targets[t].dispersion == i; ++t) {
      if (stop) continue;
      const std::string bad = target_problem(b.targets[t], s, seen);
      if (!bad.empty()) {
        error(bad);
        stop = true;
      } else if (s.dist == DistKind::Choice) {
        const std::string v = choice_problem(b.targets[t], s, sc);
        if (!v.empty()) error(v);
      }
    }
  }
}

}  // namespace

void check_monte_carlo(const Ctx& ctx, Scenario& sc)
{
  if (sc.monte_carlo) report_problems(ctx, sc, bind_dispersions(sc));
}

McBinding bind_campaign(const Scenario& nominal)
{
  McBinding b = bind_dispersions(nominal);
  std::vector<ScenarioIssue> issues;
  const Ctx ctx{nominal.source_file, &issues, {}};
  report_problems(ctx, nominal, b);
  if (!issues.empty()) throw ScenarioError(issues);
  return b;
}

}  // namespace harness

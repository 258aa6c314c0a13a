// scenario_schema: ONE definition per scenario key, from which reading
// (YAML), writing (the canonical manifest JSON), `--set` path resolution and
// the typed setter (set_parameter) all follow.
//
// A KeyDef holds the key's name, type, alternative-unit suffix, required
// text, bounds and the member of `Scenario` it maps to (an accessor lambda
// `[](auto& sc, size_t i) -> auto& { return sc.wheels[i].params.J_s; }`,
// used const by the writer and non-const by the readers).  A Section is a
// map of keys (or a list of such maps) with sub-sections; the tree of
// Sections is schema().  Each section's definition and its read function live
// together in scenario_<section>.cpp; the cross-field checks of a section
// follow its keys there, the whole-scenario checks are in scenario.cpp.
//
// Adding a key: one line in the section's table (plus the struct member in
// harness/scenario.h and its use in run.cpp).  Docs: docs/harness.md.
//
// Private to the harness library.
#ifndef HARNESS_SRC_SCENARIO_SCHEMA_H
#define HARNESS_SRC_SCENARIO_SCHEMA_H

#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "harness/scenario/scenario.h"
#include "scenario/yaml_reader.h"

namespace harness::schema {

constexpr uint32_t kMaxDivisor = 1000000;  // [ticks] sanity bound on rate divisors

enum class Type { Real, Integer, Unsigned, Bool, String, Choice, Vec3, UnitVec3, Inertia, Custom };

// ---- checks on a number as written -------------------------------------------
// `suffixed`: the value was written with the key's alternative-unit suffix.
using Check = std::function<std::string(double x, bool suffixed)>;
Check positive(const char* unit);
Check non_negative(const char* unit);

// ---- unit-aware bounds (docs/harness.md, "Input bounds") ---------------------------
// An angle key is read in radians, or in degrees with its _deg spelling; a
// value that is absurd in radians but plausible in degrees is pointed at the
// _deg spelling.  Rates likewise (rad/s, _deg_s, _rpm).
constexpr double kMaxMisalignmentDeg = 10.0;     // [deg] a tilt beyond is a different axis, not a misalignment
constexpr double kMaxBodyRateDegS = 180.0;       // [deg/s] |omega| of the body (half a turn per second)
constexpr double kMaxStarTrackerSigmaArcsec = 3600.0;  // [arcsec] 1-sigma noise: one degree
constexpr double kMaxWheelSpeedRpm = 20000.0;    // [rpm] wheel speed limit (flight wheels: <= 10000 rpm)
// x in [0, max_deg) as written: degrees when the key's _deg spelling is used, else radians.
Check angle_below(double max_deg);
// Vec3 in SI: every component within +-max_deg (as radians).
std::function<std::string(const Eigen::Vector3d&)> angles_within(double max_deg);
// Vec3 in SI: |v| <= max_deg_s (as rad/s).
std::function<std::string(const Eigen::Vector3d&)> rate_within(double max_deg_s);

struct KeyDef;
// Reads the key from `r` into sc (list element i); problems go to r's Ctx.
using ReadFn = std::function<void(const KeyDef&, MapReader&, Scenario&, size_t)>;
// Writes the key into the JSON object of its section (or nothing: optional key absent).
using WriteFn = std::function<void(const KeyDef&, nlohmann::json&, const Scenario&, size_t)>;
// Typed set: "" or the reason the value is refused (sc unchanged then).
using SetFn = std::function<std::string(const KeyDef&, Scenario&, size_t, const ParameterValue&, bool suffixed)>;

struct KeyDef {
  std::string name;
  Type type = Type::Real;
  std::string required;     // non-empty: required; the text of "required key missing (...)"
  std::string suffix;       // alternative spelling name+suffix ...
  double factor = 1.0;      // ... whose value times factor is SI
  Check check;              // Real: bounds on the value as written
  std::function<std::string(double& si)> post;  // Real: after conversion; may adjust; message verbatim
  std::function<std::string(const Eigen::Vector3d&)> check_vec;  // Vec3: message verbatim
  std::function<std::string(const std::string&)> check_str;      // String: message verbatim
  long long lo = 0, hi = 0;            // Integer bounds
  std::vector<std::string> options;    // Choice words
  std::string doc;                     // unit or a short description (for scenario_key_list)
  nlohmann::json shape;                // Custom: its JSON Schema (null: any value; scenario_json_schema.cpp)
  bool attitude = false;  // Vec3 MRP also given as a quaternion, Euler angles or axis-angle (attitude_key)
  ReadFn read;    // null: read by the section's own code (input-only keys such as hyperbola.*)
  WriteFn write;  // null: never written
  SetFn set;      // null: not settable with set_parameter

  // Fluent modifiers for the tables.
  KeyDef& req(std::string what) { required = std::move(what); return *this; }
  KeyDef& bounds(Check c) { check = std::move(c); return *this; }
  KeyDef& alt(std::string s, double f) { suffix = std::move(s); factor = f; return *this; }
  KeyDef& then(std::function<std::string(double&)> p) { post = std::move(p); return *this; }
  KeyDef& vcheck(std::function<std::string(const Eigen::Vector3d&)> c) { check_vec = std::move(c); return *this; }
  KeyDef& scheck(std::function<std::string(const std::string&)> c) { check_str = std::move(c); return *this; }
  KeyDef& unit(std::string u) { doc = std::move(u); return *this; }
  KeyDef& json_shape(nlohmann::json s) { shape = std::move(s); return *this; }
  // A Real whose 0 means "not given" (a bound > 0 applies when it is): 0 is
  // not written, so the manifest reloads to 0 rather than being refused.
  KeyDef& zero_unset();
};

struct Section {
  std::string name{};                // key in the parent map ("" at the top)
  std::vector<KeyDef> keys{};
  std::vector<Section> children{};
  bool list = false;                 // a list of maps (wheels, thrusters), addressed by index
  size_t capacity = 0;               // list: most elements accepted
  std::function<size_t(const Scenario&)> count{};  // list: elements in a Scenario
  std::function<bool(const Scenario&)> present{};  // optional map (tank, burn): written only when present
  bool input_only = false;           // read, never written (wheel_defaults, hyperbola)
  std::string note{};                // why a section cannot be set (input-only)

  const KeyDef* key(const std::string& name, bool& suffixed) const;
  const Section* child(const std::string& name) const;
  std::vector<std::string> known_names() const;  // keys, suffixed spellings, children
};

// The whole schema (top-level keys and every section).
const Section& schema();

// Each section, defined with its reader in scenario_<section>.cpp.
const Section& rates_section();
const Section& environment_section();
const Section& spacecraft_section();
const Section& wheel_section(bool defaults = false);  // "wheels" / "wheel_defaults"
const Section& thrusters_section();
const Section& tank_section(const std::string& name);  // "tank" / "rcs_tank"
const Section& burn_section();
const Section& sensors_section();
const Section& magnetorquers_section();       // scenario_magnetics.cpp
const Section& magnetorquer_drive_section();  // scenario_magnetics.cpp
Section magnetometer_section();               // scenario_magnetics.cpp (a child of sensors)
const Section& fsw_section();
const Section& outputs_section();
const Section& events_section();

void read_rates(MapReader r, Scenario& sc);
void read_environment(MapReader r, Scenario& sc);
void read_spacecraft(MapReader r, Scenario& sc);
void read_wheels(MapReader& top, Scenario& sc);
void read_thrusters(MapReader& top, Scenario& sc);
void read_tank(MapReader r, Scenario& sc, const std::string& name);
void read_burn(MapReader r, Scenario& sc);
void read_magnetorquers(MapReader& top, Scenario& sc);  // with magnetorquer_drive; after rates, environment, wheels, thrusters
void read_sensors(MapReader r, Scenario& sc);
void check_magnetometer(MapReader& m, const Scenario& sc);  // after its keys; the magnetorquers read
void read_fsw(MapReader r, Scenario& sc);
void read_outputs(MapReader r, Scenario& sc);
void read_events(MapReader& top, Scenario& sc);  // after every other section

// JSON Schema shapes for the custom keys' json_shape() (scenario_json_schema.cpp).
nlohmann::json json_vec3();  // 3 numbers
// A list of `item`s: between min_items and max_items (0: no bound).
nlohmann::json json_list_of(nlohmann::json item, size_t min_items = 0, size_t max_items = 0);
// An object of exactly these properties (no other key), `required` among them.
nlohmann::json json_object_of(nlohmann::json properties, std::vector<std::string> required = {});

// Reads every key of `s` (not its children) in table order.
void read_keys(MapReader& r, const Section& s, Scenario& sc, size_t i = 0);
// The JSON object of section `s` (list element i), children included.
nlohmann::json write_section(const Section& s, const Scenario& sc, size_t i = 0);

// ---- typed values ----------------------------------------------------------------
std::string describe(const ParameterValue& v);  // "true", "2.5", "'text'", "[1, 2, 3]" for messages
std::optional<double> as_number(const ParameterValue& v);

// ---- builders --------------------------------------------------------------------
// `field` is a generic lambda (auto& sc, size_t i) -> auto& naming the member.

template <class F>
KeyDef real(std::string name, F field)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::Real;
  d.read = [field](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    std::optional<double> v;
    if (k.suffix.empty()) {
      v = r.real(k.name, k.check ? NumberCheck([&k](double x) { return k.check(x, false); }) : NumberCheck());
    } else {
      const std::optional<bool> suffixed = r.spelling(k.name, k.suffix);
      if (!suffixed) return;
      const bool s = *suffixed;
      const NumberCheck c = k.check ? NumberCheck([&k, s](double x) { return k.check(x, s); }) : NumberCheck();
      v = s ? r.real(k.name + k.suffix, c, k.factor) : r.real(k.name, c);
    }
    if (v && k.post) {
      const std::string why = k.post(*v);
      if (!why.empty()) {
        r.error_at(k.name, why);
        return;
      }
    }
    if (v) field(sc, i) = *v;
    else if (!k.required.empty() && !r.has(k.name)) r.missing(k.name, k.required);
  };
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) {
    const auto& f = field(sc, i);
    if constexpr (std::is_same_v<std::decay_t<decltype(f)>, std::optional<double>>) {
      if (f) j[k.name] = *f;
    } else {
      j[k.name] = f;
    }
  };
  d.set = [field](const KeyDef& k, Scenario& sc, size_t i, const ParameterValue& pv, bool suffixed) -> std::string {
    const std::optional<double> x = as_number(pv);
    if (!x) return "expected a number, got " + describe(pv);
    if (!std::isfinite(*x)) return "must be finite, got " + describe(pv);
    if (k.check) {
      const std::string why = k.check(*x, suffixed);
      if (!why.empty()) return why + ", got " + describe(pv);
    }
    double si = suffixed ? *x * k.factor : *x;
    if (k.post) {
      const std::string why = k.post(si);
      if (!why.empty()) return why;
    }
    field(sc, i) = si;
    return "";
  };
  return d;
}

template <class F>
KeyDef integer(std::string name, long long lo, long long hi, F field)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::Integer;
  d.lo = lo;
  d.hi = hi;
  d.read = [field](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    using T = std::decay_t<decltype(field(sc, i))>;
    if (auto v = r.integer(k.name, k.lo, k.hi)) field(sc, i) = static_cast<T>(*v);
    else if (!k.required.empty() && !r.has(k.name)) r.missing(k.name, k.required);
  };
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) { j[k.name] = field(sc, i); };
  d.set = [field](const KeyDef& k, Scenario& sc, size_t i, const ParameterValue& pv, bool) -> std::string {
    using T = std::decay_t<decltype(field(sc, i))>;
    const std::optional<double> x = as_number(pv);
    if (!x || !(std::floor(*x) == *x)) return "expected an integer, got " + describe(pv);
    if (*x < static_cast<double>(k.lo) || *x > static_cast<double>(k.hi))
      return "must be in [" + std::to_string(k.lo) + ", " + std::to_string(k.hi) + "], got " + describe(pv);
    field(sc, i) = static_cast<T>(*x);
    return "";
  };
  return d;
}

// A non-negative 64-bit integer (the seed).
template <class F>
KeyDef unsigned64(std::string name, F field)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::Unsigned;
  d.read = [field](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    if (auto v = r.uinteger(k.name)) field(sc, i) = *v;
    else if (!k.required.empty() && !r.has(k.name)) r.missing(k.name, k.required);
  };
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) { j[k.name] = field(sc, i); };
  d.set = [field](const KeyDef&, Scenario& sc, size_t i, const ParameterValue& pv, bool) -> std::string {
    const auto& v = pv.value;
    if (std::holds_alternative<uint64_t>(v)) field(sc, i) = std::get<uint64_t>(v);
    else if (std::holds_alternative<long long>(v) && std::get<long long>(v) >= 0)
      field(sc, i) = static_cast<uint64_t>(std::get<long long>(v));
    else if (std::holds_alternative<double>(v) && std::get<double>(v) >= 0.0 &&
             std::get<double>(v) < 18446744073709551616.0 && std::floor(std::get<double>(v)) == std::get<double>(v))
      field(sc, i) = static_cast<uint64_t>(std::get<double>(v));
    else return "expected a non-negative integer, got " + describe(pv);
    return "";
  };
  return d;
}

template <class F>
KeyDef boolean(std::string name, F field)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::Bool;
  d.read = [field](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    if (auto v = r.boolean(k.name)) field(sc, i) = *v;
    else if (!k.required.empty() && !r.has(k.name)) r.missing(k.name, k.required);
  };
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) { j[k.name] = field(sc, i); };
  d.set = [field](const KeyDef&, Scenario& sc, size_t i, const ParameterValue& pv, bool) -> std::string {
    if (!std::holds_alternative<bool>(pv.value)) return "expected true or false, got " + describe(pv);
    field(sc, i) = std::get<bool>(pv.value);
    return "";
  };
  return d;
}

template <class F>
KeyDef string(std::string name, F field)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::String;
  d.read = [field](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    if (auto v = r.string(k.name)) {
      const std::string why = k.check_str ? k.check_str(*v) : std::string();
      if (!why.empty()) r.error_at(k.name, why + ", got '" + *v + "'");
      else field(sc, i) = *v;
    } else if (!k.required.empty() && !r.has(k.name)) {
      r.missing(k.name, k.required);
    }
  };
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) { j[k.name] = field(sc, i); };
  d.set = [field](const KeyDef& k, Scenario& sc, size_t i, const ParameterValue& pv, bool) -> std::string {
    if (!std::holds_alternative<std::string>(pv.value)) return "expected a string, got " + describe(pv);
    const std::string& s = std::get<std::string>(pv.value);
    const std::string why = k.check_str ? k.check_str(s) : std::string();
    if (!why.empty()) return why;
    field(sc, i) = s;
    return "";
  };
  return d;
}

// One of a set of words, stored as an enum: `options` pairs word and value.
template <class E, class F>
KeyDef choice(std::string name, std::vector<std::pair<std::string, E>> options, F field)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::Choice;
  for (const auto& o : options) d.options.push_back(o.first);
  d.read = [field, options](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    if (auto m = r.choice(k.name, k.options)) field(sc, i) = options[*m].second;
    else if (!k.required.empty() && !r.has(k.name)) r.missing(k.name, k.required);
  };
  d.write = [field, options](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) {
    for (const auto& o : options)
      if (o.second == field(sc, i)) j[k.name] = o.first;
  };
  d.set = [field, options](const KeyDef& k, Scenario& sc, size_t i, const ParameterValue& pv, bool) -> std::string {
    std::string all;
    for (size_t n = 0; n < k.options.size(); ++n) all += (n ? ", " : "") + k.options[n];
    if (std::holds_alternative<std::string>(pv.value))
      for (const auto& o : options)
        if (o.first == std::get<std::string>(pv.value)) {
          field(sc, i) = o.second;
          return "";
        }
    return "expected one of {" + all + "}, got " + describe(pv);
  };
  return d;
}

// A 3-vector; `unit`: must be a unit vector (renormalised).
template <class F>
KeyDef vec3(std::string name, F field, bool unit = false)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = unit ? Type::UnitVec3 : Type::Vec3;
  d.read = [field](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    std::optional<Eigen::Vector3d> v;
    std::string key = k.name;
    if (k.type == Type::UnitVec3) {
      v = r.unit_vec3(k.name);
    } else if (k.suffix.empty()) {
      v = r.vec3(k.name);
    } else {
      const std::optional<bool> suffixed = r.spelling(k.name, k.suffix);
      if (!suffixed) return;
      if (*suffixed) key = k.name + k.suffix;
      v = *suffixed ? r.vec3(key, k.factor) : r.vec3(key);
    }
    if (v && k.check_vec) {
      const std::string why = k.check_vec(*v);
      if (!why.empty()) {
        r.error_at(key, why);
        return;
      }
    }
    if (v) field(sc, i) = *v;
    else if (!k.required.empty() && !r.has(k.name)) r.missing(k.name, k.required);
  };
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) {
    const Eigen::Vector3d& v = field(sc, i);
    j[k.name] = nlohmann::json::array({v(0), v(1), v(2)});
  };
  d.set = [field](const KeyDef& k, Scenario& sc, size_t i, const ParameterValue& pv, bool suffixed) -> std::string {
    if (!std::holds_alternative<Eigen::Vector3d>(pv.value)) return "expected a 3-vector, got " + describe(pv);
    Eigen::Vector3d v = std::get<Eigen::Vector3d>(pv.value);
    if (!v.allFinite()) return "must be finite, got " + describe(pv);
    if (suffixed) v *= k.factor;
    if (k.type == Type::UnitVec3) {
      const std::string why = check_unit_vector(v);
      if (!why.empty()) return why;
    }
    if (k.check_vec) {
      const std::string why = k.check_vec(v);
      if (!why.empty()) return why;
    }
    field(sc, i) = v;
    return "";
  };
  return d;
}

// An inertia matrix (3 diagonal values or 3x3); the member is a Matrix3d or
// an optional one (absent: not written).
template <class F>
KeyDef inertia(std::string name, F field)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::Inertia;
  d.read = [field](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    if (auto v = r.inertia(k.name)) field(sc, i) = *v;
    else if (!k.required.empty() && !r.has(k.name)) r.missing(k.name, k.required);
  };
  d.write = [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t i) {
    const auto& f = field(sc, i);
    const Eigen::Matrix3d* m = nullptr;
    if constexpr (std::is_same_v<std::decay_t<decltype(f)>, std::optional<Eigen::Matrix3d>>) {
      if (!f) return;
      m = &*f;
    } else {
      m = &f;
    }
    nlohmann::json out = nlohmann::json::array();
    for (int row = 0; row < 3; ++row) out.push_back(nlohmann::json::array({(*m)(row, 0), (*m)(row, 1), (*m)(row, 2)}));
    j[k.name] = out;
  };
  d.set = [field](const KeyDef&, Scenario& sc, size_t i, const ParameterValue& pv, bool) -> std::string {
    Eigen::Matrix3d m;
    if (std::holds_alternative<Eigen::Matrix3d>(pv.value)) m = std::get<Eigen::Matrix3d>(pv.value);
    else if (std::holds_alternative<Eigen::Vector3d>(pv.value)) m = std::get<Eigen::Vector3d>(pv.value).asDiagonal();
    else return "expected 3 diagonal values or a 3x3 matrix, got " + describe(pv);
    const std::string why = check_inertia(m);
    if (!why.empty()) return why;
    field(sc, i) = m;
    return "";
  };
  return d;
}

// ---- attitude keys (scenario_attitude.cpp, docs/scenario-schema.md) --------------
// An MRP key sigma_XN (vec3) that is also accepted as
//   <name>_quaternion:     [q0, q1, q2, q3], scalar first, |q| = 1 within kUnitTol (renormalised)
//   <name>_euler_321_deg:  [yaw, pitch, roll] [deg], the 3-2-1 sequence (z, then y', then x'')
//   <name>_axis_angle:     {axis: [x, y, z] (any length > 0), angle_deg: a} [deg], |a| <= 360
// each the rotation from the second frame of the name to the first (sigma_BN:
// N to B), exactly one form given, converted once to the MRP with |sigma| <= 1
// (the shadow set for rotations beyond 180 deg) and stored through the key's
// own setter, so the run sees the MRP as if written.  Only the MRP is written.
KeyDef attitude_key(KeyDef mrp);
// The spellings of an attitude key: name, then the three alternative forms.
std::vector<std::string> attitude_spellings(const std::string& name);
// Which spelling of the attitude `name` a map gives (all marked known): its
// index in attitude_spellings(), -1 none, -2 more than one (reported).
int attitude_form_given(MapReader& r, const std::string& name);
// The MRP (|sigma| <= 1 for forms 1..3) of spelling `form` (0..3); problems reported.
std::optional<Eigen::Vector3d> read_attitude_form(MapReader& r, const std::string& name, int form);
// The JSON Schema of the alternative form `spelling` (one of attitude_spellings()[1..3]).
nlohmann::json attitude_form_json(const std::string& name, const std::string& spelling);

// A key the section reads and writes itself (lists of speeds or normals).
inline KeyDef custom(std::string name, ReadFn read, WriteFn write)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = Type::Custom;
  d.read = std::move(read);
  d.write = std::move(write);
  return d;
}

// A key read by the section's own code and never written (input-only).
inline KeyDef input_only(std::string name, Type type)
{
  KeyDef d;
  d.name = std::move(name);
  d.type = type;
  return d;
}

}  // namespace harness::schema

#endif  // HARNESS_SRC_SCENARIO_SCHEMA_H

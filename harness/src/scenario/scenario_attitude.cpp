// scenario_attitude.cpp: attitude keys (an MRP sigma_XN) given as a
// quaternion, 3-2-1 Euler angles or an axis and angle, converted once to
// the MRP the FSW and the plant use (scenario_schema.h, attitude_key).
#include <cmath>

#include "scenario/scenario_schema.h"
#include "sim/attitude.h"
#include "sim/units.h"

namespace harness::schema {

namespace {

constexpr double kMaxAxisAngleDeg = 360.0;  // [deg] |angle| of the axis-angle form

// The MRP of a scalar-first unit quaternion, on the branch |sigma| <= 1
// (q and -q are the same rotation: q0 >= 0 picks the short one).
Eigen::Vector3d mrp_of(Eigen::Vector4d q)
{
  if (q(0) < 0.0) q = -q;
  return sim::sigma_from_quaternion(q);
}

// Elementary frame rotation about axis a (0 x, 1 y, 2 z) by angle t [rad].
Eigen::Matrix3d frame_rotation(int a, double t)
{
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  m(a, a) = 1.0;
  m(b, b) = m(c, c) = std::cos(t);
  m(b, c) = std::sin(t);
  m(c, b) = -std::sin(t);
  return m;
}

std::optional<Eigen::Vector3d> read_quaternion(MapReader& r, const std::string& key)
{
  const YAML::Node v = r.get(key);
  Eigen::Vector4d q;
  bool ok = v.IsSequence() && v.size() == 4;
  for (size_t i = 0; ok && i < 4; ++i) ok = decode_double(v[i], q(static_cast<int>(i))) && std::isfinite(q(static_cast<int>(i)));
  if (!ok) {
    r.error_at(key, "expected 4 finite numbers [q0, q1, q2, q3] (scalar first), got " + kind_name(v));
    return std::nullopt;
  }
  const double n = q.norm();
  if (!(std::fabs(n - 1.0) <= kUnitTol)) {
    r.error_at(key, "a unit quaternion is needed (|q| = 1 within " + fmt(kUnitTol) + "), got |q| = " + fmt(n));
    return std::nullopt;
  }
  return mrp_of(q / n);
}

std::optional<Eigen::Vector3d> read_euler_321(MapReader& r, const std::string& key)
{
  const std::optional<Eigen::Vector3d> a = r.vec3(key, sim::kRadPerDeg);  // [yaw, pitch, roll] -> rad
  if (!a) return std::nullopt;
  const Eigen::Matrix3d C = frame_rotation(0, (*a)(2)) * frame_rotation(1, (*a)(1)) * frame_rotation(2, (*a)(0));
  return mrp_of(sim::quaternion_from_dcm(C));
}

std::optional<Eigen::Vector3d> read_axis_angle(MapReader& r, const std::string& key)
{
  const YAML::Node v = r.get(key);
  if (!v.IsMap()) {
    r.error_at(key, "expected a map {axis: [x, y, z], angle_deg: a}, got " + kind_name(v));
    return std::nullopt;
  }
  MapReader m = r.sub(key);
  const std::optional<Eigen::Vector3d> axis = m.vec3("axis");
  const std::optional<double> angle = m.real("angle_deg", [](double x) {
    return std::fabs(x) <= kMaxAxisAngleDeg ? std::string() : "must be within +-" + fmt(kMaxAxisAngleDeg) + " deg";
  });
  m.finish();
  if (!m.has("axis")) m.missing("axis", "the rotation axis, 3 numbers");
  if (!m.has("angle_deg")) m.missing("angle_deg", "the rotation angle [deg]");
  if (!axis || !angle) return std::nullopt;
  const double n = axis->norm();
  if (!(n > 0.0)) {
    m.error_at("axis", "the axis must not be zero");
    return std::nullopt;
  }
  const double h = 0.5 * *angle * sim::kRadPerDeg;
  Eigen::Vector4d q;
  q << std::cos(h), std::sin(h) * (*axis / n);
  return mrp_of(q);
}

}  // namespace

std::vector<std::string> attitude_spellings(const std::string& name)
{
  return {name, name + "_quaternion", name + "_euler_321_deg", name + "_axis_angle"};
}

nlohmann::json attitude_form_json(const std::string& name, const std::string& spelling)
{
  const std::vector<std::string> s = attitude_spellings(name);
  nlohmann::json j;
  if (spelling == s[1]) {
    j = {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 4}, {"maxItems", 4}};
    j["description"] = name + " as a unit quaternion [q0, q1, q2, q3], scalar first";
  } else if (spelling == s[2]) {
    j = json_vec3();
    j["description"] = name + " as 3-2-1 Euler angles [yaw, pitch, roll] [deg]";
  } else {
    j = json_object_of({{"axis", json_vec3()}, {"angle_deg", {{"type", "number"}}}}, {"axis", "angle_deg"});
    j["description"] = name + " as a rotation axis and angle [deg]";
  }
  j["description"] = j["description"].get<std::string>() + "; give one form of the attitude only";
  return j;
}

int attitude_form_given(MapReader& r, const std::string& name)
{
  const std::vector<std::string> forms = attitude_spellings(name);
  int given = -1;
  for (size_t f = 0; f < forms.size(); ++f) {
    r.mark_known(forms[f]);
    if (!r.has(forms[f])) continue;
    if (given >= 0) {
      r.error_at(forms[f], "give the attitude in one form only: " + forms[static_cast<size_t>(given)] + " is given too");
      return -2;
    }
    given = static_cast<int>(f);
  }
  return given;
}

std::optional<Eigen::Vector3d> read_attitude_form(MapReader& r, const std::string& name, int form)
{
  const std::string key = attitude_spellings(name).at(static_cast<size_t>(form));
  if (form == 1) return read_quaternion(r, key);
  if (form == 2) return read_euler_321(r, key);
  if (form == 3) return read_axis_angle(r, key);
  return r.vec3(key);
}

KeyDef attitude_key(KeyDef mrp)
{
  mrp.attitude = true;
  const ReadFn plain = mrp.read;
  mrp.read = [plain](const KeyDef& k, MapReader& r, Scenario& sc, size_t i) {
    const int form = attitude_form_given(r, k.name);
    if (form == -2) return;
    if (form <= 0) {  // the MRP itself (or nothing): the key's own reader
      plain(k, r, sc, i);
      return;
    }
    const std::optional<Eigen::Vector3d> sigma = read_attitude_form(r, k.name, form);
    if (!sigma) return;
    const std::string why = k.set(k, sc, i, ParameterValue(*sigma), false);
    if (!why.empty()) r.error_at(attitude_spellings(k.name)[static_cast<size_t>(form)], why);
  };
  return mrp;
}

}  // namespace harness::schema

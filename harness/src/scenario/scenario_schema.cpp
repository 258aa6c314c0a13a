// scenario_schema.cpp: the generic half of the key definitions (see
// scenario_schema.h): reading a section's keys, writing a section, the
// shared checks and value descriptions.
#include "scenario/scenario_schema.h"

#include <sstream>

#include "sim/units.h"

namespace harness::schema {

Check positive(const char* unit)
{
  return [unit](double x, bool) { return x > 0.0 ? std::string() : std::string("must be > 0 [") + unit + "]"; };
}

Check non_negative(const char* unit)
{
  return [unit](double x, bool) { return x >= 0.0 ? std::string() : std::string("must be >= 0 [") + unit + "]"; };
}

namespace {
constexpr double kRadPerDeg = sim::kRadPerDeg;
}  // namespace

Check angle_below(double max_deg)
{
  return [max_deg](double x, bool deg) {
    const double lim = deg ? max_deg : max_deg * kRadPerDeg;
    if (x >= 0.0 && x < lim) return std::string();
    std::string why = "must be in [0, " + fmt(max_deg) + " deg) = [0, " + fmt(max_deg * kRadPerDeg) + " rad)";
    if (!deg && x >= 0.0 && x < max_deg) why += "; a value in degrees? use the _deg spelling";
    return why;
  };
}

std::function<std::string(const Eigen::Vector3d&)> angles_within(double max_deg)
{
  return [max_deg](const Eigen::Vector3d& v) {
    if (v.cwiseAbs().maxCoeff() <= max_deg * kRadPerDeg) return std::string();
    return "every component must be within +-" + fmt(max_deg) + " deg = " + fmt(max_deg * kRadPerDeg) +
           " rad, got " + fmt(v.cwiseAbs().maxCoeff()) + " rad (a value in degrees? use the _deg spelling)";
  };
}

std::function<std::string(const Eigen::Vector3d&)> rate_within(double max_deg_s)
{
  return [max_deg_s](const Eigen::Vector3d& v) {
    if (v.norm() <= max_deg_s * kRadPerDeg) return std::string();
    return "|omega| must be at most " + fmt(max_deg_s) + " deg/s = " + fmt(max_deg_s * kRadPerDeg) + " rad/s, got " +
           fmt(v.norm()) + " rad/s = " + fmt(v.norm() / kRadPerDeg) + " deg/s (the key is in rad/s)";
  };
}

const KeyDef* Section::key(const std::string& n, bool& suffixed) const
{
  for (const KeyDef& k : keys) {
    if (k.name == n) {
      suffixed = false;
      return &k;
    }
    if (!k.suffix.empty() && k.name + k.suffix == n) {
      suffixed = true;
      return &k;
    }
  }
  return nullptr;
}

const Section* Section::child(const std::string& n) const
{
  for (const Section& c : children)
    if (c.name == n) return &c;
  return nullptr;
}

std::vector<std::string> Section::known_names() const
{
  std::vector<std::string> out;
  for (const KeyDef& k : keys) {
    out.push_back(k.name);
    if (!k.suffix.empty()) out.push_back(k.name + k.suffix);
    if (k.attitude)
      for (size_t f = 1; f < attitude_spellings(k.name).size(); ++f) out.push_back(attitude_spellings(k.name)[f]);
  }
  for (const Section& c : children) out.push_back(c.name);
  return out;
}

KeyDef& KeyDef::zero_unset()
{
  WriteFn plain = write;
  write = [plain](const KeyDef& d, nlohmann::json& j, const Scenario& sc, size_t i) {
    nlohmann::json one = nlohmann::json::object();
    plain(d, one, sc, i);
    const auto it = one.find(d.name);
    if (it == one.end() || (it->is_number() && it->get<double>() == 0.0)) return;
    j[d.name] = *it;
  };
  return *this;
}

void read_keys(MapReader& r, const Section& s, Scenario& sc, size_t i)
{
  for (const KeyDef& k : s.keys)
    if (k.read) k.read(k, r, sc, i);
}

nlohmann::json write_section(const Section& s, const Scenario& sc, size_t i)
{
  nlohmann::json j = nlohmann::json::object();
  for (const KeyDef& k : s.keys)
    if (k.write) k.write(k, j, sc, i);
  for (const Section& c : s.children) {
    if (c.input_only) continue;
    if (c.list) {
      if (c.present && !c.present(sc)) continue;  // an optional list (facets) absent
      nlohmann::json a = nlohmann::json::array();
      for (size_t n = 0; n < c.count(sc); ++n) a.push_back(write_section(c, sc, n));
      j[c.name] = a;
    } else if (!c.present || c.present(sc)) {
      j[c.name] = write_section(c, sc, i);
    }
  }
  return j;
}

std::optional<double> as_number(const ParameterValue& pv)
{
  const auto& v = pv.value;
  if (std::holds_alternative<double>(v)) return std::get<double>(v);
  if (std::holds_alternative<long long>(v)) return static_cast<double>(std::get<long long>(v));
  if (std::holds_alternative<uint64_t>(v)) return static_cast<double>(std::get<uint64_t>(v));
  return std::nullopt;
}

std::string describe(const ParameterValue& pv)
{
  const auto& v = pv.value;
  if (std::holds_alternative<double>(v)) return fmt(std::get<double>(v));
  if (std::holds_alternative<long long>(v)) return std::to_string(std::get<long long>(v));
  if (std::holds_alternative<uint64_t>(v)) return std::to_string(std::get<uint64_t>(v));
  if (std::holds_alternative<bool>(v)) return std::get<bool>(v) ? "true" : "false";
  if (std::holds_alternative<std::string>(v)) return "'" + std::get<std::string>(v) + "'";
  if (std::holds_alternative<Eigen::Vector3d>(v)) {
    const Eigen::Vector3d& x = std::get<Eigen::Vector3d>(v);
    return "[" + fmt(x(0)) + ", " + fmt(x(1)) + ", " + fmt(x(2)) + "]";
  }
  return "a 3x3 matrix";
}

}  // namespace harness::schema

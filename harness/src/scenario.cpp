// scenario.cpp: the scenario schema read from YAML (yaml_reader.h) after the
// `--set` overrides are applied (overrides.h).
#include "harness/scenario.h"

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "overrides.h"
#include "scenario_schema.h"
#include "yaml_reader.h"


namespace harness {

namespace schema {
namespace {

// ---- the top level --------------------------------------------------------------
bool is_plain_name(const std::string& v)
{
  bool ok = !v.empty();
  for (char c : v) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
  return ok;
}

schema::Section make_schema()
{
  using namespace schema;
  Section top{
      "",
      {
          string("name", [](auto& sc, size_t) -> auto& { return sc.name; })
              .req("scenario name")
              .scheck([](const std::string& v) {
                return is_plain_name(v) ? "" : "must be non-empty and use only letters, digits, '_' and '-'";
              }),
          string("description", [](auto& sc, size_t) -> auto& { return sc.description; }),
          unsigned64("seed", [](auto& sc, size_t) -> auto& { return sc.seed; })
              .req("random seed, a non-negative integer"),
          real("duration", [](auto& sc, size_t) -> auto& { return sc.duration; })
              .req("simulated time [s]").bounds(positive("s")).unit("s"),
      },
      {rates_section(), environment_section(), spacecraft_section(), wheel_section(true), wheel_section(),
       thrusters_section(), tank_section("tank"), tank_section("rcs_tank"), burn_section(), sensors_section(),
       fsw_section(), outputs_section()}};
  return top;
}
}  // namespace

const Section& schema()
{
  static const Section s = make_schema();
  return s;
}
}  // namespace schema

namespace {

constexpr uint64_t kMaxTicks = 100000000000ULL;  // [-] 1e11 ticks: refuse absurd runs

// The whole document: every section, then the checks across sections.
void read_scenario(const Ctx& ctx, const YAML::Node& root, Scenario& sc)
{
  using namespace schema;
  MapReader top(ctx, root, "");
  if (!root.IsDefined() || root.IsNull()) {
    ctx.error(root, "(top level)", "empty scenario file");
    return;
  }
  schema::read_keys(top, schema::schema(), sc);
  if (!top.has("rates")) top.missing("rates", "dt and rate divisors");
  read_rates(top.sub("rates"), sc);
  if (!top.has("spacecraft")) top.missing("spacecraft", "mass, inertia, com");
  read_environment(top.sub("environment"), sc);
  read_spacecraft(top.sub("spacecraft"), sc);
  read_wheels(top, sc);
  read_thrusters(top, sc);
  read_tank(top.sub("tank"), sc, "tank");
  read_tank(top.sub("rcs_tank"), sc, "rcs_tank");
  read_burn(top.sub("burn"), sc);
  read_sensors(top.sub("sensors"), sc);
  if (!top.has("fsw")) top.missing("fsw", "flight software gains and modes");
  read_fsw(top.sub("fsw"), sc);
  read_outputs(top.sub("outputs"), sc);
  top.finish();

  // ---- Cross-section checks (after every key is read) ----
  if (sc.duration > 0.0 && sc.rates.dt > 0.0) {
    const double n = sc.duration / sc.rates.dt;
    if (std::fabs(n - std::round(n)) > 1e-6 * std::max(1.0, n))
      top.error_at("duration", "must be a whole number of steps dt = " + fmt(sc.rates.dt) + " s");
    else if (std::round(n) > static_cast<double>(kMaxTicks))
      top.error_at("duration", "too many steps (" + fmt(n) + " > 1e11)");
  }
  // Sensor sample periods: absent, a sensor samples at the FSW rate.
  for (uint32_t* d : {&sc.sensors.gyro.divisor, &sc.sensors.star_tracker.divisor, &sc.sensors.tachometer.divisor})
    if (*d == 0) *d = sc.rates.fsw_divisor;
  if (sc.wheels.empty() && sc.thrusters.empty())
    ctx.error(root, "wheels", "the spacecraft needs wheels or thrusters");
  if (!sc.wheels.empty() && sc.wheels.size() < 3)
    ctx.error(root["wheels"], "wheels", "at least 3 wheels are needed for 3-axis control, got " +
                                          std::to_string(sc.wheels.size()));
  if (sc.fsw.mode == FswMode::SunSafe && sc.environment.sun_position_N.norm() == 0.0)
    ctx.error(root["environment"], "environment.sun_position_N", "sun_safe mode needs a Sun position");
  if (!sc.thrusters.empty() && !sc.tank)
    ctx.error(root["thrusters"], "tank", "thrusters need a propellant tank (key 'tank')");
  if (sc.rcs_tank && sc.thrusters.empty())
    ctx.error(root["rcs_tank"], "rcs_tank", "given but there are no thrusters");
  if (!sc.thrusters.empty()) {
    // The FSW's on-times cover one control period: thruster commands are
    // latched at the FSW rate.  Absent, thruster_divisor follows fsw_divisor.
    const YAML::Node rates = root["rates"];
    const bool given = rates.IsMap() && rates["thruster_divisor"].IsDefined();
    if (!given) sc.rates.thruster_divisor = sc.rates.fsw_divisor;
    else if (sc.rates.thruster_divisor != sc.rates.fsw_divisor)
      ctx.error(rates["thruster_divisor"], "rates.thruster_divisor",
                "must equal rates.fsw_divisor (" + std::to_string(sc.rates.fsw_divisor) +
                    ") with thrusters: the FSW's on-times cover one control period");
    bool acs = false;
    for (const ThrusterSpec& t : sc.thrusters) acs = acs || t.acs;
    if (acs && sc.fsw.thr_t_min * 1.0 >= sc.rates.dt * sc.rates.fsw_divisor)
      ctx.error(root["fsw"], "fsw.thr_pulse.t_min", "must be shorter than the FSW period");
  }
}

Scenario load_from_root(YAML::Node root, const std::string& file, const std::vector<Override>& overrides)
{
  std::vector<ScenarioIssue> issues;
  Ctx ctx{file, &issues, {}};
  if (root.IsMap() && root["kestrel_manifest"].IsDefined()) {
    YAML::Node s = root["scenario"];
    if (!s.IsDefined() || !s.IsMap()) {
      ctx.error(root, "scenario", "a manifest needs a 'scenario' map");
      throw ScenarioError(issues);
    }
    root = s;
  }
  for (const Override& o : overrides) {
    try {
      apply_override(ctx, root, o);
    } catch (const YAML::Exception& e) {  // safety net: never crash on an odd --set
      ScenarioIssue is;
      is.file = file;
      is.key = o.path;
      is.where = "--set " + o.path + "=" + o.value;
      is.message = std::string("cannot apply: ") + e.msg;
      issues.push_back(is);
    }
  }
  Scenario sc;
  sc.source_file = file;
  if (issues.empty()) {
    try {
      read_scenario(ctx, root, sc);
      collect_key_lines(root, "", sc.key_lines);
    } catch (const YAML::Exception& e) {  // safety net: never crash on odd input
      ScenarioIssue is;
      is.file = file;
      is.line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
      is.column = e.mark.column >= 0 ? e.mark.column + 1 : 0;
      is.key = "(file)";
      is.message = std::string("unreadable structure: ") + e.msg;
      issues.push_back(is);
    }
  }
  if (!issues.empty()) {
    // drop exact duplicates (a wheel_defaults problem shows once per wheel)
    std::vector<ScenarioIssue> uniq;
    for (const auto& is : issues) {
      bool dup = false;
      for (const auto& u : uniq) dup = dup || (u.line == is.line && u.column == is.column && u.message == is.message &&
                                               u.where == is.where && (u.line != 0 || u.key == is.key));
      if (!dup) uniq.push_back(is);
    }
    throw ScenarioError(uniq);
  }
  return sc;
}

ScenarioIssue file_issue(const std::string& file, int line, int col, const std::string& msg)
{
  ScenarioIssue is;
  is.file = file;
  is.line = line;
  is.column = col;
  is.key = "(file)";
  is.message = msg;
  return is;
}

}  // namespace

Scenario load_scenario_text(const std::string& text, const std::string& file_name,
                            const std::vector<Override>& overrides)
{
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ScenarioError({file_issue(file_name, e.mark.line + 1, e.mark.column + 1, "YAML syntax error: " + e.msg)});
  }
  return load_from_root(root, file_name, overrides);
}

Scenario load_scenario(const std::string& path, const std::vector<Override>& overrides)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError({file_issue(path, 0, 0, "cannot open the file")});
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw ScenarioError({file_issue(path, 0, 0, "cannot read the file")});
  return load_scenario_text(ss.str(), path, overrides);
}

Override parse_override(const std::string& s)
{
  const size_t eq = s.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--set expects key.path=value, got '" + s + "'");
  return Override{s.substr(0, eq), s.substr(eq + 1)};
}

}  // namespace harness

// scenario.cpp: the scenario schema read from YAML (yaml_reader.h) after the
// `--set` overrides are applied (overrides.h).
#include "harness/scenario/scenario.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "scenario/json_util.h"
#include "scenario/mc_draw.h"
#include "scenario/overrides.h"
#include "scenario/scenario_schema.h"
#include "scenario/yaml_reader.h"


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
          monte_carlo_key(),
      },
      {rates_section(), environment_section(), spacecraft_section(), wheel_section(true), wheel_section(),
       thrusters_section(), tank_section("tank"), tank_section("rcs_tank"), burn_section(),
       magnetorquers_section(), magnetorquer_drive_section(), sensors_section(),
       fsw_section(), outputs_section(), events_section()}};
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

// duration / dt is the number of steps N; duration and dt are decimal
// numbers, so their quotient carries about three roundings (each input and
// the division, <= 1.5 eps relative).  It must be within 64 eps * N of a
// whole number (a 40x margin; for the largest run, 1e11 steps, 0.0014 of a
// step): 100000.005 s with dt = 0.01 s (half a step off) or 1e-9 s (no step)
// are refused, 0.3 s with dt = 0.1 s is 3 steps.  N must also be a whole
// number of every rate group's period, so the last FSW cycle, recorded row
// and sensor sample fall on t = duration.
void check_duration(MapReader& top, const Scenario& sc)
{
  constexpr double kDurationRelTol = 64.0 * std::numeric_limits<double>::epsilon();  // [-]
  const double n = sc.duration / sc.rates.dt;
  const double whole = std::round(n);
  const std::string steps = "dt = " + fmt(sc.rates.dt) + " s";
  if (!(whole >= 1.0)) {
    top.error_at("duration", "shorter than one step " + steps);
    return;
  }
  if (whole > static_cast<double>(kMaxTicks)) {
    top.error_at("duration", "too many steps (" + fmt(n) + " > 1e11 steps of " + steps + ")");
    return;
  }
  if (std::fabs(n - whole) > kDurationRelTol * whole) {
    top.error_at("duration", "must be a whole number of steps " + steps + " (it is " + fmt(n) + " steps; e.g. " +
                                 fmt(std::floor(n) * sc.rates.dt) + " or " + fmt(std::ceil(n) * sc.rates.dt) + " s)");
    return;
  }
  const auto N = static_cast<uint64_t>(whole);
  struct Group {
    const char* key;
    uint32_t divisor;
    bool used;
  };
  const Group groups[] = {
      {"rates.fsw_divisor", sc.rates.fsw_divisor, true},
      {"rates.record_divisor", sc.rates.record_divisor, true},
      {"rates.thruster_divisor", sc.rates.thruster_divisor, !sc.thrusters.empty()},
      {"sensors.gyro.divisor", sc.sensors.gyro.divisor, sc.sensors.gyro.enabled},
      {"sensors.star_tracker.divisor", sc.sensors.star_tracker.divisor, sc.sensors.star_tracker.enabled},
      {"sensors.tachometer.divisor", sc.sensors.tachometer.divisor, sc.sensors.tachometer.enabled && !sc.wheels.empty()},
  };
  for (const Group& g : groups)
    if (g.used && g.divisor > 0 && N % g.divisor != 0) {  // the first one only: sensors follow the FSW
      top.error_at("duration", "must be a whole number of the period of " + std::string(g.key) + " (" +
                                   std::to_string(g.divisor) + " steps = " + fmt(g.divisor * sc.rates.dt) +
                                   " s): it is " + std::to_string(N) + " steps");
      return;
    }
}

// Actuators that can torque about every axis: the columns of A (3 x n, unit
// wheel axes or thruster torque directions) must span 3-D.  Relative to the
// strongest direction (largest singular value), the weakest must have at
// least kSpanRelTol of its authority: below that the FSW's mapping is
// singular or asks for torques 1000 times the nominal ones about that axis.
constexpr double kSpanRelTol = 1e-3;  // [-]

// "" when the columns span 3-D, else why not (with the axis left uncontrolled).
std::string span_problem(const Eigen::Matrix<double, 3, Eigen::Dynamic>& A)
{
  if (A.cols() == 0) return "there are none";
  // fewer than 3 columns (one or two ACS thrusters): zero columns added
  // leave the span unchanged and give the SVD its 3 singular values
  Eigen::MatrixXd A3 = Eigen::MatrixXd::Zero(3, std::max<Eigen::Index>(3, A.cols()));
  A3.leftCols(A.cols()) = A;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A3, Eigen::ComputeFullU);
  const Eigen::Vector3d s = svd.singularValues();
  if (!(s(0) > 0.0)) return "all are zero";
  if (s(2) >= kSpanRelTol * s(0)) return "";
  const int rank = s(1) >= kSpanRelTol * s(0) ? 2 : 1;
  Eigen::Vector3d u = svd.matrixU().col(2);
  for (int k = 0; k < 3; ++k)
    if (std::fabs(u(k)) < 1e-12) u(k) = 0.0;  // [0, 0, 1], not [5.6e-17, 0, 1]
  return std::string(rank == 1 ? "all lie along one line" : "all lie in one plane") +
         ", so no torque about [" + fmt(u(0)) + ", " + fmt(u(1)) + ", " + fmt(u(2)) +
         "] (weakest/strongest singular value " + fmt(s(2) / s(0)) + " < " + fmt(kSpanRelTol) + ")";
}

// The actuator set the FSW uses (fsw.actuation) must control three axes.
void check_actuator_span(MapReader& top, const Scenario& sc)
{
  if (sc.fsw.actuation == Actuation::Wheels && sc.wheels.size() >= 3) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> A(3, static_cast<Eigen::Index>(sc.wheels.size()));
    for (size_t i = 0; i < sc.wheels.size(); ++i)
      A.col(static_cast<Eigen::Index>(i)) = sc.wheels[i].params.gs_hat_nom_B;
    const std::string why = span_problem(A);
    if (!why.empty())
      top.error_at_key("wheels", "the wheel axes cannot control three axes (fsw.actuation is wheels): they " + why);
  }
  if (sc.fsw.actuation == Actuation::Thrusters) {
    // torque directions about the mass centre at t0 (hub and full tanks)
    double m = sc.spacecraft.mass;
    Eigen::Vector3d mc = sc.spacecraft.mass * sc.spacecraft.r_BcB_B;
    for (const std::optional<TankSpec>* t : {&sc.tank, &sc.rcs_tank})
      if (*t) {
        m += (*t)->mass;
        mc += (*t)->mass * (*t)->r_TB_B;
      }
    const Eigen::Vector3d c = m > 0.0 ? Eigen::Vector3d(mc / m) : sc.spacecraft.r_BcB_B;
    Eigen::Matrix<double, 3, Eigen::Dynamic> A(3, 0);
    for (const ThrusterSpec& t : sc.thrusters)
      if (t.acs) {
        A.conservativeResize(3, A.cols() + 1);
        A.col(A.cols() - 1) = (t.r_TjB_B - c).cross(t.t_hat_B);
      }
    if (A.cols() == 0) return;  // reported at fsw.actuation
    const std::string why = span_problem(A);
    if (!why.empty())
      top.error_at_key("thrusters", "the ACS thrusters' torque directions (r - r_CoM) x g cannot control three axes "
                                    "(fsw.actuation is thrusters): they " + why);
  }
}

// The whole document: every section, then the checks across sections.
void read_scenario(const Ctx& ctx, const YAML::Node& root, Scenario& sc)
{
  using namespace schema;
  MapReader top(ctx, root, "");
  if (root.IsDefined() && !root.IsNull() && !root.IsMap()) return;  // reported by MapReader: nothing to read
  if (!root.IsDefined() || root.IsNull()) {
    ScenarioIssue is;
    is.file = ctx.file;
    is.line = 1;
    is.column = 1;
    is.key = "(top level)";
    is.message = "empty scenario file (no keys)";
    ctx.issues->push_back(is);
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
  read_magnetorquers(top, sc);
  read_sensors(top.sub("sensors"), sc);
  if (!top.has("fsw")) top.missing("fsw", "flight software gains and modes");
  read_fsw(top.sub("fsw"), sc);
  read_outputs(top.sub("outputs"), sc);
  read_events(top, sc);
  top.finish();

  // ---- Cross-section checks (after every key is read) ----
  // Sensor sample periods: absent, a sensor samples at the FSW rate.
  for (uint32_t* d : {&sc.sensors.gyro.divisor, &sc.sensors.star_tracker.divisor, &sc.sensors.tachometer.divisor})
    if (*d == 0) *d = sc.rates.fsw_divisor;
  if (sc.duration > 0.0 && sc.rates.dt > 0.0) check_duration(top, sc);
  if (sc.wheels.empty() && sc.thrusters.empty())
    ctx.error(root, "wheels", "the spacecraft needs wheels or thrusters");
  if (!sc.wheels.empty() && sc.wheels.size() < 3)
    ctx.error(root["wheels"], "wheels", "at least 3 wheels are needed for 3-axis control, got " +
                                          std::to_string(sc.wheels.size()));
  if (sc.fsw.mode == FswMode::SunSafe && sc.environment.sun_position_N.norm() == 0.0)
    ctx.error(root["environment"], "environment.sun_position_N", "sun_safe mode needs a Sun position");
  for (EnvSource src : {EnvSource::SolarPressure, EnvSource::Drag})
    if (env_model(sc.environment, src).enabled && sc.spacecraft.facets.empty())
      ctx.error(root["environment"][env_source_name(src)], std::string("environment.") + env_source_name(src),
                "needs spacecraft.facets (the surfaces it acts on)");
  if (sc.fsw.mtq)  // the flight software writes the rods' commands
    for (size_t e = 0; e < sc.events.size(); ++e)
      for (size_t a = 0; a < sc.events[e].actions.size(); ++a)
        if (sc.events[e].actions[a].action == "dipole")
          ctx.error(root["events"][e], "events[" + std::to_string(e) + "].actions[" + std::to_string(a) + "]",
                    "'dipole' commands a rod, but the flight software commands them (fsw.magnetorquers.enabled)");
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
    const bool acs = sc.has_acs_thrusters();
    if (acs && sc.fsw.thr_t_min * 1.0 >= sc.rates.dt * sc.rates.fsw_divisor)
      ctx.error(root["fsw"], "fsw.thr_pulse.t_min", "must be shorter than the FSW period");
  }
  if (ctx.issues->empty()) check_actuator_span(top, sc);  // on a consistent scenario only
  if (ctx.issues->empty()) check_monte_carlo(ctx, sc);    // the dispersed keys, against the scenario read
}

// A manifest of a run with Python objects in the loop (written by the Python
// module, docs/python.md "Python in the loop"): the objects are not in it, so
// it cannot be rerun here.
void refuse_python_in_loop(Ctx& ctx, const YAML::Node& root)
{
  const YAML::Node p = root["python_in_loop"];
  if (!p.IsDefined()) return;
  YAML::Emitter what;
  what.SetMapFormat(YAML::Flow);
  what.SetSeqFormat(YAML::Flow);
  what << p;
  ctx.error(p, "python_in_loop",
            "this run had Python objects in the loop (" + std::string(what.c_str()) +
                "), which a manifest cannot hold: rerun it from Python with the same objects "
                "(kestrel.run(scenario, fsw=..., effectors=..., sensors=...); docs/python.md, \"Python in the loop\")");
  throw ScenarioError(*ctx.issues);
}

// A manifest's `from_checkpoint` ({path, fnv1a64: 16 hex digits, tick}):
// the run starts from that checkpoint (docs/checkpoint.md, "Branching a campaign").
std::optional<CheckpointRef> read_from_checkpoint(const Ctx& ctx, const YAML::Node& root)
{
  const YAML::Node f = root["from_checkpoint"];
  if (!f.IsDefined()) return std::nullopt;
  CheckpointRef ref;
  const YAML::Node path = f["path"], sum = f["fnv1a64"], tick = f["tick"];
  std::string hex = sum.IsScalar() ? sum.Scalar() : "";
  char* end = nullptr;
  if (hex.size() == 16) ref.fnv1a64 = std::strtoull(hex.c_str(), &end, 16);
  if (!f.IsMap() || !path.IsScalar() || path.Scalar().empty() || !tick.IsScalar() || hex.size() != 16 ||
      end != hex.c_str() + 16) {
    ctx.error(f, "from_checkpoint", "needs {path: the checkpoint file, fnv1a64: its checksum (16 hex digits), tick}");
    return std::nullopt;
  }
  ref.path = path.Scalar();
  try {
    ref.tick = tick.as<uint64_t>();
  } catch (const YAML::Exception&) {
    ctx.error(tick, "from_checkpoint.tick", "not a tick number");
  }
  return ref;
}

// A manifest's scenario map (its checkpoint, if any, to `from`), or the
// document itself.  Const lookups: an absent key is never added to the tree.
YAML::Node scenario_of_document(Ctx& ctx, const YAML::Node& document, std::optional<CheckpointRef>& from)
{
  if (!document.IsMap() || !document["kestrel_manifest"].IsDefined()) return document;
  refuse_python_in_loop(ctx, document);
  from = read_from_checkpoint(ctx, document);
  YAML::Node s = document["scenario"];
  if (!s.IsDefined() || !s.IsMap()) {
    ctx.error(document, "scenario", "a manifest needs a 'scenario' map");
    throw ScenarioError(*ctx.issues);
  }
  return s;
}

Scenario load_from_root(const YAML::Node& document, const std::string& file, const std::vector<Override>& overrides,
                        bool key_lines = true)
{
  std::vector<ScenarioIssue> issues;
  Ctx ctx{file, &issues, {}};
  std::optional<CheckpointRef> from;
  YAML::Node root = scenario_of_document(ctx, document, from);  // a new handle: the document's node is not rebound
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
  sc.from_checkpoint = from;
  if (issues.empty()) {
    try {
      read_scenario(ctx, root, sc);
      if (key_lines) collect_key_lines(root, "", sc.key_lines);
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
    // A problem inside a section the file does not have (a required key of
    // an absent map) has no node of its own: name the nearest written parent,
    // or the top of the file.
    std::map<std::string, std::pair<int, int>> lines;
    collect_key_lines(root, "", lines);
    for (ScenarioIssue& is : issues) {
      if (is.line > 0 || !is.where.empty()) continue;
      std::pair<int, int> at{1, 1};
      for (std::string k = is.key; !k.empty();) {
        const auto it = lines.find(k);
        if (it != lines.end()) {
          at = it->second;
          break;
        }
        const size_t cut = k.find_last_of(".[");
        if (cut == std::string::npos) break;
        k = k.substr(0, cut);
      }
      is.line = at.first;
      is.column = at.second;
    }
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

}  // namespace

Scenario load_scenario_text(const std::string& text, const std::string& file_name,
                            const std::vector<Override>& overrides)
{
  // Bounded first (size, binary bytes, one document, depth, aliases), on the
  // parser's events: the node tree below is built only for text that passed.
  std::vector<ScenarioIssue> bounds = check_yaml_text(text, file_name);
  if (!bounds.empty()) throw ScenarioError(bounds);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ScenarioError({file_issue(file_name, e.mark.line + 1, e.mark.column + 1, "YAML syntax error: " + e.msg)});
  }
  return load_from_root(root, file_name, overrides);
}

Scenario load_canonical_scenario_text(const std::string& text, const std::string& file_name)
{
  if (text.size() > kMaxYamlBytes)  // as load_scenario_text: a manifest of it would be refused
    throw ScenarioError({file_issue(file_name, 0, 0, "longer than " + std::to_string(kMaxYamlBytes) + " bytes")});
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ScenarioError({file_issue(file_name, e.mark.line + 1, e.mark.column + 1, "YAML syntax error: " + e.msg)});
  }
  return load_from_root(root, file_name, {}, false);
}

Scenario reload_canonical_scenario(const Scenario& sc, const std::string& file_name)
{
  nlohmann::json j = scenario_to_json(sc);
  if (j.dump(2).size() > kMaxYamlBytes)  // as load_canonical_scenario_text of the writer's text
    throw ScenarioError({file_issue(file_name, 0, 0, "longer than " + std::to_string(kMaxYamlBytes) + " bytes")});
  // A campaign's draws reload one after the other on each worker thread:
  // the tree of the last one, its changed scalars set, is this one's.
  thread_local KeptYamlTree kept;
  return load_from_root(kept.tree_of(std::move(j)), file_name, {}, false);
}

Scenario load_scenario(const std::string& path, const std::vector<Override>& overrides)
{
  // Only a regular file is read: a folder, a device (/dev/null, /dev/zero),
  // a FIFO or a socket is named for what it is (a FIFO would block).
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw ScenarioError({file_issue(path, 0, 0, "cannot open the file: no such file")});
  if (!fs::is_regular_file(st)) {
    const char* what = fs::is_directory(st)          ? "a directory"
                       : fs::is_character_file(st)  ? "a character device"
                       : fs::is_block_file(st)      ? "a block device"
                       : fs::is_fifo(st)            ? "a FIFO"
                       : fs::is_socket(st)          ? "a socket"
                                                    : "not a regular file";
    throw ScenarioError({file_issue(path, 0, 0, std::string("not a scenario file: ") + what)});
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError({file_issue(path, 0, 0, "cannot open the file")});
  // Read at most one byte more than accepted: a huge file is never read whole.
  std::string text(kMaxYamlBytes + 1, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw ScenarioError({file_issue(path, 0, 0, "cannot read the file")});
  text.resize(static_cast<size_t>(in.gcount()));
  if (text.size() > kMaxYamlBytes)
    throw ScenarioError({file_issue(path, 0, 0, "file too large (more than " + std::to_string(kMaxYamlBytes) +
                                                    " bytes): a scenario is a few kilobytes")});
  return load_scenario_text(text, path, overrides);
}

Override parse_override(const std::string& s)
{
  const size_t eq = s.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--set expects key.path=value, got '" + s + "'");
  return Override{s.substr(0, eq), s.substr(eq + 1)};
}

}  // namespace harness

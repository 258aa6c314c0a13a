// scenario_wheels.cpp: `wheels` (a list of sim::ReactionWheelParams) and
// `wheel_defaults` (any wheel key, for every wheel that does not set it).
#include <cmath>
#include <set>

#include "scenario/scenario_limits.h"
#include "scenario/scenario_schema.h"

#include "sim/units.h"

namespace harness::schema {

namespace {

Section make_wheel_section(const std::string& name, bool input_only)
{
  // the member of wheel i
#define KESTREL_WHEEL(member) [](auto& sc, size_t i) -> auto& { return sc.wheels[i].member; }
  Section s{
      name,
      {
          string("name", KESTREL_WHEEL(name)).unit("default rw<i+1>, unique"),
          choice<sim::WheelModel>("model",
                                  {{"balanced", sim::WheelModel::Balanced},
                                   {"simple_jitter", sim::WheelModel::SimpleJitter},
                                   {"fully_coupled", sim::WheelModel::FullyCoupled}},
                                  KESTREL_WHEEL(params.model))
              .req("balanced, simple_jitter or fully_coupled"),
          vec3("axis", KESTREL_WHEEL(params.gs_hat_nom_B), true).req("spin axis, unit vector in B"),
          vec3("position", KESTREL_WHEEL(params.r_WB_B)).unit("m"),
          real("J_s", KESTREL_WHEEL(params.J_s)).req("spin inertia [kg*m^2]").bounds(positive("kg*m^2")).unit("kg*m^2"),
          real("J_t", KESTREL_WHEEL(params.J_t)).bounds(positive("kg*m^2")).unit("kg*m^2"),
          real("J_g", KESTREL_WHEEL(params.J_g)).bounds(positive("kg*m^2")).unit("kg*m^2"),
          real("m_w", KESTREL_WHEEL(params.m_w)).bounds(non_negative("kg")).unit("kg"),
          real("U_s", KESTREL_WHEEL(params.U_s))
              .alt("_g_cm", sim::kKgMPerGCm).bounds(non_negative("kg*m or g*cm")).unit("kg*m"),
          real("U_d", KESTREL_WHEEL(params.U_d))
              .alt("_g_cm2", sim::kKgM2PerGCm2).bounds(non_negative("kg*m^2 or g*cm^2")).unit("kg*m^2"),
          real("Omega_0", KESTREL_WHEEL(params.Omega_0)).alt("_rpm", sim::kRadPerSecPerRpm).unit("rad/s"),
          real("Omega_max", KESTREL_WHEEL(params.Omega_max))
              .alt("_rpm", sim::kRadPerSecPerRpm)
              .bounds([](double x, bool rpm) {
                const double lim = rpm ? kMaxWheelSpeedRpm : kMaxWheelSpeedRpm * sim::kRadPerSecPerRpm;
                if (x >= 0.0 && x <= lim) return std::string();
                return "must be in [0, " + fmt(kMaxWheelSpeedRpm) + " rpm] = [0, " +
                       fmt(kMaxWheelSpeedRpm * sim::kRadPerSecPerRpm) + " rad/s]" +
                       (!rpm && x >= 0.0 && x <= kMaxWheelSpeedRpm ? "; a value in rpm? use Omega_max_rpm" : "");
              })
              .unit("rad/s"),
          real("u_max", KESTREL_WHEEL(params.u_max)).req("motor torque limit [N*m]").bounds(positive("N*m")).unit("N*m"),
          real("u_min", KESTREL_WHEEL(params.u_min)).bounds(non_negative("N*m")).unit("N*m"),
          real("P_max", KESTREL_WHEEL(params.P_max)).bounds(non_negative("W")).unit("W"),
          vec3("misalignment", KESTREL_WHEEL(params.delta_mis_B))
              .alt("_deg", sim::kRadPerDeg).vcheck(angles_within(kMaxMisalignmentDeg)).unit("rad"),
      },
      {Section{"friction",
               {
                   real("tau_c", KESTREL_WHEEL(params.friction.tau_c)).bounds(non_negative("N*m")).unit("N*m"),
                   real("tau_st", KESTREL_WHEEL(params.friction.tau_st)).bounds(non_negative("N*m")).unit("N*m"),
                   real("c_v", KESTREL_WHEEL(params.friction.c_v)).bounds(non_negative("N*m*s/rad")).unit("N*m*s/rad"),
                   real("beta_st", KESTREL_WHEEL(params.friction.beta_st)).unit("s/rad"),
                   real("omega_lc", KESTREL_WHEEL(params.friction.omega_lc))
                       .bounds(positive("rad/s")).unit("rad/s"),
               },
               {}}}};
#undef KESTREL_WHEEL
  s.list = !input_only;
  s.capacity = kMaxScenarioWheels;
  s.count = [](const Scenario& sc) { return sc.wheels.size(); };
  s.input_only = input_only;
  if (input_only) s.note = "applies when a file is read; set wheels.<i>.<key> instead";
  return s;
}

// One wheel from its own map, with keys missing there taken from `defaults`.
void read_wheel(const Ctx& ctx, const YAML::Node& node, const YAML::Node& defaults, size_t index, Scenario& sc)
{
  const Section& def = wheel_section();
  const std::string path = "wheels[" + std::to_string(index) + "]";
  sc.wheels.emplace_back();
  WheelSpec& w = sc.wheels.back();
  w.name = "rw" + std::to_string(index + 1);
  if (!node.IsMap()) {
    ctx.error(node, path, "expected a map of wheel keys, got " + kind_name(node));
    return;
  }
  // Merge: the wheel's own keys first, then defaults it does not override.
  std::set<std::string> from_defaults;
  if (defaults.IsDefined() && defaults.IsMap())
    for (auto it = defaults.begin(); it != defaults.end(); ++it) {
      const std::string k = it->first.as<std::string>("");
      if (!node[k].IsDefined()) from_defaults.insert(k);
    }
  // Nothing to merge into a map without a place in a text (a drawn
  // scenario's tree, yaml_of_json): the wheel's map is what the merged copy
  // would be (the same key and value nodes in order, no mark), without the
  // copy (its first insertion merges the document's node memory into it).
  const bool copy = !from_defaults.empty() || !node.Mark().is_null();
  YAML::Node merged(YAML::NodeType::Map);  // (a Node assigned to refers to the other's node: not reused)
  if (copy) {
    for (auto it = node.begin(); it != node.end(); ++it) merged[it->first] = it->second;
    for (auto it = defaults.begin(); it != defaults.end() && !from_defaults.empty(); ++it)
      if (from_defaults.count(it->first.as<std::string>(""))) merged[it->first] = it->second;
  }
  MapReader r(ctx, copy ? merged : node, path);
  for (const std::string& k : from_defaults) r.set_alias(k, "wheel_defaults");
  read_keys(r, def, sc, index);
  MapReader f = r.sub("friction");
  read_keys(f, *def.child("friction"), sc, index);
  f.finish();
  // Cross-field physics (reported on the wheel map).
  const sim::ReactionWheelParams& p = w.params;
  if (p.model == sim::WheelModel::FullyCoupled && !(p.m_w > 0.0))
    r.error_at(r.has("m_w") ? "m_w" : "model", "a fully_coupled wheel needs a rotor mass m_w > 0 [kg]");
  if (p.u_min > 0.0 && p.u_max > 0.0 && p.u_min >= p.u_max)
    r.error_at("u_min", "must be < u_max (" + fmt(p.u_max) + " N*m)");
  if (p.Omega_max > 0.0 && std::fabs(p.Omega_0) > p.Omega_max)
    r.error_at(r.has("Omega_0_rpm") ? "Omega_0_rpm" : "Omega_0",
               "initial speed exceeds Omega_max (" + fmt(p.Omega_max / sim::kRadPerSecPerRpm) + " rpm)");
  if (p.friction.beta_st > 0.0 && p.friction.tau_st < p.friction.tau_c)
    f.error_at("tau_st", "must be >= tau_c when Stribeck friction is on (beta_st > 0)");
  r.finish();
  // Let the plant's own validation have the last word (it names the field).
  try {
    sim::validate(p, path);
  } catch (const std::exception& e) {
    bool already = false;
    for (const auto& is : *ctx.issues) already = already || is.key.rfind(path, 0) == 0;
    if (!already) ctx.error(node, path, e.what());
  }
}

}  // namespace

const Section& wheel_section(bool defaults)
{
  static const Section wheels = make_wheel_section("wheels", false);
  static const Section wheel_defaults = make_wheel_section("wheel_defaults", true);
  return defaults ? wheel_defaults : wheels;
}

void read_wheels(MapReader& top, Scenario& sc)
{
  YAML::Node defaults = top.get("wheel_defaults");
  if (defaults.IsDefined() && !defaults.IsNull() && !defaults.IsMap()) {
    top.ctx().error(defaults, "wheel_defaults", "expected a map of wheel keys, got " + kind_name(defaults));
    defaults = YAML::Node();
  }
  YAML::Node list = top.get("wheels");
  if (!list.IsDefined() || list.IsNull()) {
    if (defaults.IsDefined() && defaults.IsMap() && defaults.size() > 0)
      top.ctx().error(defaults, "wheel_defaults", "given but there are no wheels");
    return;
  }
  if (!list.IsSequence()) {
    top.ctx().error(list, "wheels", "expected a list of wheels, got " + kind_name(list));
    return;
  }
  if (list.size() > kMaxScenarioWheels) {
    top.ctx().error(list, "wheels", "at most " + std::to_string(kMaxScenarioWheels) + " wheels, got " +
                                        std::to_string(list.size()));
    return;
  }
  for (size_t i = 0; i < list.size(); ++i) read_wheel(top.ctx(), list[i], defaults, i, sc);
  for (size_t i = 0; i < sc.wheels.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (sc.wheels[i].name == sc.wheels[j].name)
        top.ctx().error(list[i], "wheels[" + std::to_string(i) + "].name",
                        "duplicate wheel name '" + sc.wheels[i].name + "'");
}

}  // namespace harness::schema

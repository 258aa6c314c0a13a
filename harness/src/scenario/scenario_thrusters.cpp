// scenario_thrusters.cpp: `thrusters` (sim::ThrusterParams each), the
// propellant tanks `tank` and `rcs_tank`, and the main-engine `burn`.
#include "scenario/scenario_limits.h"
#include "scenario/scenario_schema.h"

#include "sim/units.h"

namespace harness::schema {

const Section& thrusters_section()
{
#define KESTREL_THR(member) [](auto& sc, size_t i) -> auto& { return sc.thrusters[i].member; }
  static const Section s = [] {
    Section t{"thrusters",
              {
                  string("name", KESTREL_THR(name)).unit("default thr<j+1>, unique"),
                  vec3("position", KESTREL_THR(r_TjB_B)).req("nozzle location in B [m]").unit("m"),
                  vec3("direction", KESTREL_THR(t_hat_B), true).req("unit thrust direction in B"),
                  real("F_max", KESTREL_THR(F_max)).req("thrust [N]").bounds(positive("N")).unit("N"),
                  real("Isp", KESTREL_THR(Isp)).req("specific impulse [s]").bounds(positive("s")).unit("s"),
                  real("T_min", KESTREL_THR(T_min)).bounds(non_negative("s")).unit("s"),
                  real("misalignment", KESTREL_THR(misalignment))
                      .alt("_deg", sim::kRadPerDeg)
                      .bounds(angle_below(kMaxMisalignmentDeg))
                      .unit("rad"),
                  choice<ThrTransient>("transient",
                                       {{"instant", ThrTransient::Instant}, {"first_order", ThrTransient::FirstOrder}},
                                       KESTREL_THR(transient)),
                  real("omega_on", KESTREL_THR(omega_on)).bounds(positive("rad/s")).unit("rad/s"),
                  real("omega_off", KESTREL_THR(omega_off)).bounds(positive("rad/s")).unit("rad/s"),
                  boolean("acs", KESTREL_THR(acs)),
              },
              {}};
    t.list = true;
    t.capacity = kMaxScenarioThrusters;
    t.count = [](const Scenario& sc) { return sc.thrusters.size(); };
    return t;
  }();
#undef KESTREL_THR
  return s;
}

void read_thrusters(MapReader& top, Scenario& sc)
{
  YAML::Node list = top.get("thrusters");
  if (!list.IsDefined() || list.IsNull()) return;
  if (!list.IsSequence()) {
    top.ctx().error(list, "thrusters", "expected a list of thrusters, got " + kind_name(list));
    return;
  }
  if (list.size() > kMaxScenarioThrusters) {
    top.ctx().error(list, "thrusters", "at most " + std::to_string(kMaxScenarioThrusters) + " thrusters, got " +
                                           std::to_string(list.size()));
    return;
  }
  for (size_t i = 0; i < list.size(); ++i) {
    MapReader r(top.ctx(), list[i], "thrusters[" + std::to_string(i) + "]");
    sc.thrusters.emplace_back();
    sc.thrusters.back().name = "thr" + std::to_string(i + 1);
    read_keys(r, thrusters_section(), sc, i);
    r.finish();
    for (size_t j = 0; j < i; ++j)
      if (sc.thrusters[j].name == sc.thrusters[i].name)
        r.error_at("name", "duplicate thruster name '" + sc.thrusters[i].name + "'");
  }
}

namespace {
Section make_tank_section(const std::string& name, std::optional<TankSpec> Scenario::*tank)
{
  Section s{name,
            {
                real("mass", [tank](auto& sc, size_t) -> auto& { return (sc.*tank)->mass; })
                    .req("initial propellant [kg]").bounds(non_negative("kg")).unit("kg"),
                vec3("position", [tank](auto& sc, size_t) -> auto& { return (sc.*tank)->r_TB_B; }).unit("m"),
            },
            {}};
  s.present = [tank](const Scenario& sc) { return (sc.*tank).has_value(); };
  return s;
}
}  // namespace

const Section& tank_section(const std::string& name)
{
  static const Section tank = make_tank_section("tank", &Scenario::tank);
  static const Section rcs_tank = make_tank_section("rcs_tank", &Scenario::rcs_tank);
  return name == "rcs_tank" ? rcs_tank : tank;
}

void read_tank(MapReader r, Scenario& sc, const std::string& name)
{
  if (!r.node().IsMap() || r.node().size() == 0) {
    r.finish();
    return;
  }
  (name == "rcs_tank" ? sc.rcs_tank : sc.tank).emplace();
  read_keys(r, tank_section(name), sc);
  r.finish();
}

const Section& burn_section()
{
  static const Section s = [] {
    Section b{"burn",
              {
                  string("thruster", [](auto& sc, size_t) -> auto& { return sc.burn->thruster; })
                      .req("name of the main engine (a thruster with acs: false)"),
                  real("start", [](auto& sc, size_t) -> auto& { return sc.burn->start; })
                      .req("ignition time [s]").bounds(non_negative("s")).unit("s"),
                  real("duration", [](auto& sc, size_t) -> auto& { return sc.burn->duration; })
                      .req("burn duration [s]").bounds(positive("s")).unit("s"),
              },
              {}};
    b.present = [](const Scenario& sc) { return sc.burn.has_value(); };
    return b;
  }();
  return s;
}

void read_burn(MapReader r, Scenario& sc)
{
  if (!r.node().IsMap() || r.node().size() == 0) {
    r.finish();
    return;
  }
  sc.burn.emplace();
  read_keys(r, burn_section(), sc);
  // The burn fires a main engine: a thruster of that name with acs: false.
  const YAML::Node& given = r.node();
  if (given["thruster"].IsDefined() && given["thruster"].IsScalar()) {
    const std::string& name = sc.burn->thruster;
    const ThrusterSpec* t = nullptr;
    for (const ThrusterSpec& x : sc.thrusters)
      if (x.name == name) t = &x;
    if (!t) r.error_at("thruster", "no thruster named '" + name + "' in 'thrusters'");
    else if (t->acs)
      r.error_at("thruster", "'" + name + "' is an ACS thruster (acs: true); the burn needs a main engine (acs: false)");
  }
  r.finish();
}

}  // namespace harness::schema

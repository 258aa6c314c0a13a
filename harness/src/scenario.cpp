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
#include "yaml_reader.h"

#include "sim/environment.h"
#include "sim/units.h"

namespace harness {

namespace {

constexpr double kRadPerArcsec = sim::kRadPerDeg / 3600.0;  // [rad / arcsec]
constexpr uint32_t kMaxDivisor = 1000000;  // [ticks] sanity bound on rate divisors
constexpr uint64_t kMaxTicks = 100000000000ULL;  // [-] 1e11 ticks: refuse absurd runs

// ---- checks ------------------------------------------------------------------
auto positive(const char* unit)
{
  return [unit](double x) { return x > 0.0 ? std::string() : std::string("must be > 0 [") + unit + "]"; };
}
auto non_negative(const char* unit)
{
  return [unit](double x) { return x >= 0.0 ? std::string() : std::string("must be >= 0 [") + unit + "]"; };
}

// ---- sections ----------------------------------------------------------------
void read_rates(MapReader r, Scenario& sc)
{
  if (auto v = r.real("dt", positive("s"))) {
    const double ns = *v * 1e9;
    const double rounded = std::round(ns);
    if (rounded < 1.0 || std::fabs(ns - rounded) > 1e-6 * std::max(1.0, rounded))
      r.error_at("dt", "must be a whole number of nanoseconds (>= 1 ns), got " + fmt(*v) + " s");
    else
      sc.rates.dt = rounded * 1e-9;
  } else if (!r.has("dt")) {
    r.missing("dt", "plant step [s]");
  }
  if (auto v = r.integer("fsw_divisor", 1, kMaxDivisor)) sc.rates.fsw_divisor = static_cast<uint32_t>(*v);
  if (auto v = r.integer("fsw_offset", 0, kMaxDivisor)) {
    if (*v >= sc.rates.fsw_divisor)
      r.error_at("fsw_offset", "must be < fsw_divisor (" + std::to_string(sc.rates.fsw_divisor) + ")");
    else
      sc.rates.fsw_offset = static_cast<uint32_t>(*v);
  }
  if (auto v = r.integer("record_divisor", 1, kMaxDivisor)) sc.rates.record_divisor = static_cast<uint32_t>(*v);
  if (auto v = r.integer("thruster_divisor", 1, kMaxDivisor)) sc.rates.thruster_divisor = static_cast<uint32_t>(*v);
  r.finish();
}

void read_spacecraft(MapReader r, Scenario& sc)
{
  SpacecraftSpec& s = sc.spacecraft;
  if (auto v = r.real("mass", positive("kg"))) s.mass = *v;
  else if (!r.has("mass")) r.missing("mass", "hub mass [kg]");
  if (auto v = r.inertia("inertia")) s.inertia = *v;
  else if (!r.has("inertia")) r.missing("inertia", "hub inertia about its CoM [kg*m^2]");
  if (auto v = r.vec3("com")) s.com = *v;
  MapReader ic = r.sub("initial");
  if (auto v = ic.vec3("sigma_BN")) {
    if (v->norm() > 1.0 + 1e-12) ic.error_at("sigma_BN", "MRP must have |sigma| <= 1 (use the shadow set)");
    else s.initial.sigma_BN = *v;
  }
  {
    const bool a = ic.has("omega_BN_B"), b = ic.has("omega_BN_B_deg_s");
    if (a && b) {
      ic.get("omega_BN_B");
      ic.get("omega_BN_B_deg_s");
      ic.error_at("omega_BN_B_deg_s", "give either 'omega_BN_B' or 'omega_BN_B_deg_s', not both");
    } else if (b) {
      if (auto v = ic.vec3("omega_BN_B_deg_s", sim::kRadPerDeg)) s.initial.omega_BN_B = *v;
    } else {
      ic.get("omega_BN_B_deg_s");
      if (auto v = ic.vec3("omega_BN_B")) s.initial.omega_BN_B = *v;
    }
  }
  if (auto v = ic.vec3("r_CN_N")) s.initial.r_CN_N = *v;
  if (auto v = ic.vec3("v_CN_N")) s.initial.v_CN_N = *v;
  if (ic.has("hyperbola")) {
    // Approach hyperbola (sim::conic_state_from_periapsis): perifocal frame = N
    // (x toward periapsis, z along the orbit normal).  Resolved into r_CN_N,
    // v_CN_N here (needs environment.mu, read before the spacecraft).
    MapReader h = ic.sub("hyperbola");
    const auto rp = h.real("periapsis_radius", positive("m"));
    if (!rp && !h.has("periapsis_radius")) h.missing("periapsis_radius", "periapsis radius [m]");
    const auto vinf = h.real("v_inf", positive("m/s"));
    if (!vinf && !h.has("v_inf")) h.missing("v_inf", "hyperbolic excess speed [m/s]");
    const auto tp = h.real("time_to_periapsis", non_negative("s"));
    if (!tp && !h.has("time_to_periapsis")) h.missing("time_to_periapsis", "time from the start to periapsis [s]");
    h.finish();
    if (ic.has("r_CN_N") || ic.has("v_CN_N"))
      ic.error_at("hyperbola", "give either 'hyperbola' or 'r_CN_N'/'v_CN_N', not both");
    else if (!(sc.environment.mu > 0.0))
      ic.error_at("hyperbola", "needs gravity: environment.mu > 0");
    else if (rp && vinf && tp) {
      const double e = sim::hyperbolic_eccentricity(sc.environment.mu, *rp, *vinf);
      const sim::OrbitState os = sim::conic_state_from_periapsis(sc.environment.mu, *rp, e, -*tp);
      if (!os.r_N.allFinite() || !os.v_N.allFinite())
        ic.error_at("hyperbola", "no finite state on this hyperbola (time_to_periapsis too large?)");
      s.initial.r_CN_N = os.r_N;
      s.initial.v_CN_N = os.v_N;
    }
  }
  ic.finish();
  r.finish();
}

void read_environment(MapReader r, Scenario& sc)
{
  if (auto v = r.real("mu", non_negative("m^3/s^2"))) sc.environment.mu = *v;
  if (auto v = r.vec3("sun_position_N")) sc.environment.sun_position_N = *v;
  r.finish();
}

// One wheel from its own map, with keys missing there taken from `defaults`.
WheelSpec read_wheel(const Ctx& ctx, const YAML::Node& node, const YAML::Node& defaults, size_t index)
{
  const std::string path = "wheels[" + std::to_string(index) + "]";
  WheelSpec w;
  w.name = "rw" + std::to_string(index + 1);
  if (!node.IsMap()) {
    ctx.error(node, path, "expected a map of wheel keys, got " + kind_name(node));
    return w;
  }
  // Merge: the wheel's own keys first, then defaults it does not override.
  YAML::Node merged(YAML::NodeType::Map);
  std::set<std::string> from_defaults;
  for (auto it = node.begin(); it != node.end(); ++it) merged[it->first] = it->second;
  if (defaults.IsDefined() && defaults.IsMap()) {
    for (auto it = defaults.begin(); it != defaults.end(); ++it) {
      const std::string k = it->first.as<std::string>("");
      if (!node[k].IsDefined()) {
        merged[it->first] = it->second;
        from_defaults.insert(k);
      }
    }
  }
  MapReader r(ctx, merged, path);
  for (const std::string& k : from_defaults) r.set_alias(k, "wheel_defaults");
  sim::ReactionWheelParams& p = w.params;
  if (auto v = r.string("name")) w.name = *v;
  if (auto m = r.choice("model", {"balanced", "simple_jitter", "fully_coupled"}))
    p.model = *m == 0 ? sim::WheelModel::Balanced
                      : (*m == 1 ? sim::WheelModel::SimpleJitter : sim::WheelModel::FullyCoupled);
  else if (!r.has("model")) r.missing("model", "balanced, simple_jitter or fully_coupled");
  if (auto v = r.unit_vec3("axis")) p.gs_hat_nom_B = *v;
  else if (!r.has("axis")) r.missing("axis", "spin axis, unit vector in B");
  if (auto v = r.vec3("position")) p.r_WB_B = *v;
  if (auto v = r.real("J_s", positive("kg*m^2"))) p.J_s = *v;
  else if (!r.has("J_s")) r.missing("J_s", "spin inertia [kg*m^2]");
  if (auto v = r.real("J_t", positive("kg*m^2"))) p.J_t = *v;
  if (auto v = r.real("J_g", positive("kg*m^2"))) p.J_g = *v;
  if (auto v = r.real("m_w", non_negative("kg"))) p.m_w = *v;
  if (auto v = r.quantity("U_s", "_g_cm", sim::kKgMPerGCm, non_negative("kg*m or g*cm"))) p.U_s = *v;
  if (auto v = r.quantity("U_d", "_g_cm2", sim::kKgM2PerGCm2, non_negative("kg*m^2 or g*cm^2"))) p.U_d = *v;
  if (auto v = r.quantity("Omega_0", "_rpm", sim::kRadPerSecPerRpm)) p.Omega_0 = *v;
  if (auto v = r.quantity("Omega_max", "_rpm", sim::kRadPerSecPerRpm, non_negative("rad/s or rpm")))
    p.Omega_max = *v;
  if (auto v = r.real("u_max", positive("N*m"))) p.u_max = *v;
  else if (!r.has("u_max")) r.missing("u_max", "motor torque limit [N*m]");
  if (auto v = r.real("u_min", non_negative("N*m"))) p.u_min = *v;
  if (auto v = r.real("P_max", non_negative("W"))) p.P_max = *v;
  if (r.has("misalignment") && r.has("misalignment_deg")) {
    r.get("misalignment");
    r.get("misalignment_deg");
    r.error_at("misalignment_deg", "give either 'misalignment' or 'misalignment_deg', not both");
  } else if (auto v = r.vec3("misalignment")) {
    p.delta_mis_B = *v;
  } else if (auto d = r.vec3("misalignment_deg", sim::kRadPerDeg)) {
    p.delta_mis_B = *d;
  }
  MapReader f = r.sub("friction");
  if (auto v = f.real("tau_c", non_negative("N*m"))) p.friction.tau_c = *v;
  if (auto v = f.real("tau_st", non_negative("N*m"))) p.friction.tau_st = *v;
  if (auto v = f.real("c_v", non_negative("N*m*s/rad"))) p.friction.c_v = *v;
  if (auto v = f.real("beta_st")) p.friction.beta_st = *v;
  if (auto v = f.real("omega_lc", positive("rad/s"))) p.friction.omega_lc = *v;
  f.finish();
  // Cross-field physics (reported on the wheel map).
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
  return w;
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
  if (list.size() > static_cast<size_t>(sim::kMaxWheels)) {
    top.ctx().error(list, "wheels", "at most " + std::to_string(sim::kMaxWheels) + " wheels, got " +
                                        std::to_string(list.size()));
    return;
  }
  for (size_t i = 0; i < list.size(); ++i) sc.wheels.push_back(read_wheel(top.ctx(), list[i], defaults, i));
  for (size_t i = 0; i < sc.wheels.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (sc.wheels[i].name == sc.wheels[j].name)
        top.ctx().error(list[i], "wheels[" + std::to_string(i) + "].name",
                        "duplicate wheel name '" + sc.wheels[i].name + "'");
}

void read_thrusters(MapReader& top, Scenario& sc)
{
  YAML::Node list = top.get("thrusters");
  if (!list.IsDefined() || list.IsNull()) return;
  if (!list.IsSequence()) {
    top.ctx().error(list, "thrusters", "expected a list of thrusters, got " + kind_name(list));
    return;
  }
  if (list.size() > 36) {
    top.ctx().error(list, "thrusters", "at most 36 thrusters, got " + std::to_string(list.size()));
    return;
  }
  for (size_t i = 0; i < list.size(); ++i) {
    MapReader r(top.ctx(), list[i], "thrusters[" + std::to_string(i) + "]");
    ThrusterSpec t;
    t.name = "thr" + std::to_string(i + 1);
    if (auto v = r.string("name")) t.name = *v;
    if (auto v = r.vec3("position")) t.r_B = *v;
    else if (!r.has("position")) r.missing("position", "nozzle location in B [m]");
    if (auto v = r.unit_vec3("direction")) t.dir_B = *v;
    else if (!r.has("direction")) r.missing("direction", "unit thrust direction in B");
    if (auto v = r.real("F_max", positive("N"))) t.F_max = *v;
    else if (!r.has("F_max")) r.missing("F_max", "thrust [N]");
    if (auto v = r.real("Isp", positive("s"))) t.Isp = *v;
    else if (!r.has("Isp")) r.missing("Isp", "specific impulse [s]");
    if (auto v = r.real("T_min", non_negative("s"))) t.T_min = *v;
    if (auto v = r.quantity("misalignment", "_deg", sim::kRadPerDeg, [](double x) {
          return x >= 0.0 && x < 90.0 ? std::string() : std::string("must be in [0, 90) deg");
        }))
      t.misalignment = *v;
    if (auto m = r.choice("transient", {"instant", "first_order"}))
      t.transient = *m == 0 ? ThrTransient::Instant : ThrTransient::FirstOrder;
    if (auto v = r.real("omega_on", positive("rad/s"))) t.omega_on = *v;
    if (auto v = r.real("omega_off", positive("rad/s"))) t.omega_off = *v;
    if (auto v = r.boolean("acs")) t.acs = *v;
    r.finish();
    for (const ThrusterSpec& o : sc.thrusters)
      if (o.name == t.name) r.error_at("name", "duplicate thruster name '" + t.name + "'");
    sc.thrusters.push_back(t);
  }
}

void read_tank(MapReader r, std::optional<TankSpec>& out)
{
  if (!r.node().IsMap() || r.node().size() == 0) {
    r.finish();
    return;
  }
  TankSpec t;
  if (auto v = r.real("mass", non_negative("kg"))) t.mass = *v;
  else if (!r.has("mass")) r.missing("mass", "initial propellant [kg]");
  if (auto v = r.vec3("position")) t.r_B = *v;
  r.finish();
  out = t;
}

void read_burn(MapReader r, Scenario& sc)
{
  if (!r.node().IsMap() || r.node().size() == 0) {
    r.finish();
    return;
  }
  BurnSpec b;
  if (auto v = r.string("thruster")) {
    b.thruster = *v;
    const ThrusterSpec* t = nullptr;
    for (const ThrusterSpec& x : sc.thrusters)
      if (x.name == *v) t = &x;
    if (!t) r.error_at("thruster", "no thruster named '" + *v + "' in 'thrusters'");
    else if (t->acs) r.error_at("thruster", "'" + *v + "' is an ACS thruster (acs: true); the burn needs a main engine (acs: false)");
  } else if (!r.has("thruster")) {
    r.missing("thruster", "name of the main engine (a thruster with acs: false)");
  }
  if (auto v = r.real("start", non_negative("s"))) b.start = *v;
  else if (!r.has("start")) r.missing("start", "ignition time [s]");
  if (auto v = r.real("duration", positive("s"))) b.duration = *v;
  else if (!r.has("duration")) r.missing("duration", "burn duration [s]");
  r.finish();
  sc.burn = b;
}

void read_sensors(MapReader r, Scenario& sc)
{
  MapReader css = r.sub("css");
  if (auto v = css.quantity("fov", "_deg", sim::kRadPerDeg, [&css](double x) {
        const double lim = css.has("fov_deg") ? 90.0 : 0.5 * sim::kPi;
        return x > 0.0 && x <= lim ? std::string() : std::string("half-angle must be in (0, 90 deg]");
      }))
    sc.sensors.css.fov = *v;
  if (auto v = css.real("scale", positive("-"))) sc.sensors.css.scale = *v;
  if (auto v = css.real("noise_std", non_negative("-"))) sc.sensors.css.noise_std = *v;
  YAML::Node normals = css.get("normals");
  if (normals.IsDefined()) {
    if (!normals.IsSequence()) {
      r.ctx().error(normals, css.key_path("normals"), "expected a list of unit 3-vectors, got " + kind_name(normals));
    } else {
      if (normals.size() > 32)
        r.ctx().error(normals, css.key_path("normals"), "at most 32 sensors (FSW_MAX_CSS), got " +
                                                            std::to_string(normals.size()));
      for (size_t i = 0; i < normals.size() && i < 32; ++i)
        if (auto n = css.unit_of(normals[i], css.key_path("normals") + "[" + std::to_string(i) + "]"))
          sc.sensors.css.normals_B.push_back(*n);
    }
  }
  css.finish();
  MapReader st = r.sub("star_tracker");
  if (auto v = st.boolean("enabled")) sc.sensors.star_tracker.enabled = *v;
  if (auto v = st.quantity("sigma_cross", "_arcsec", kRadPerArcsec, non_negative("rad or arcsec")))
    sc.sensors.star_tracker.sigma_cross = *v;
  if (auto v = st.quantity("sigma_bore", "_arcsec", kRadPerArcsec, non_negative("rad or arcsec")))
    sc.sensors.star_tracker.sigma_bore = *v;
  if (auto v = st.quantity("sun_exclusion", "_deg", sim::kRadPerDeg, [&st](double x) {
        const double lim = st.has("sun_exclusion_deg") ? 180.0 : sim::kPi;
        return x >= 0.0 && x < lim ? std::string() : std::string("must be in [0, 180 deg)");
      }))
    sc.sensors.star_tracker.sun_exclusion = *v;
  if (auto v = st.integer("divisor", 1, kMaxDivisor)) sc.sensors.star_tracker.divisor = static_cast<uint32_t>(*v);
  st.finish();
  MapReader g = r.sub("gyro");
  if (auto v = g.boolean("enabled")) sc.sensors.gyro.enabled = *v;
  if (auto v = g.real("arw", non_negative("rad/sqrt(s)"))) sc.sensors.gyro.arw = *v;
  if (auto v = g.real("rrw", non_negative("rad/s^(3/2)"))) sc.sensors.gyro.rrw = *v;
  if (auto v = g.real("lsb", non_negative("rad/s"))) sc.sensors.gyro.lsb = *v;
  if (auto v = g.integer("divisor", 1, kMaxDivisor)) sc.sensors.gyro.divisor = static_cast<uint32_t>(*v);
  g.finish();
  MapReader tc = r.sub("tachometer");
  if (auto v = tc.boolean("enabled")) sc.sensors.tachometer.enabled = *v;
  if (auto v = tc.quantity("sigma", "_rpm", sim::kRadPerSecPerRpm, non_negative("rad/s or rpm")))
    sc.sensors.tachometer.sigma = *v;
  if (auto v = tc.quantity("lsb", "_rpm", sim::kRadPerSecPerRpm, non_negative("rad/s or rpm")))
    sc.sensors.tachometer.lsb = *v;
  if (auto v = tc.integer("divisor", 1, kMaxDivisor)) sc.sensors.tachometer.divisor = static_cast<uint32_t>(*v);
  tc.finish();
  if (auto v = r.boolean("noise")) sc.sensors.noise = *v;
  r.finish();
}

void read_fsw(MapReader r, Scenario& sc)
{
  FswSpec& f = sc.fsw;
  if (auto m = r.choice("mode", {"inertial", "sun_safe"}))
    f.mode = *m == 0 ? FswMode::Inertial : FswMode::SunSafe;
  MapReader in = r.sub("inertial");
  if (auto v = in.vec3("sigma_R0N")) f.sigma_R0N = *v;
  in.finish();
  MapReader ss = r.sub("sun_safe");
  if (auto v = ss.unit_vec3("sun_axis_B")) f.sun_axis_B = *v;
  if (auto v = ss.quantity("small_angle", "_deg", sim::kRadPerDeg, [&ss](double x) {
        const double lim = ss.has("small_angle_deg") ? 90.0 : 0.5 * sim::kPi;
        return x >= 0.0 && x < lim ? std::string() : std::string("must be in [0, 90 deg)");
      }))
    f.sun_small_angle = *v;
  if (auto v = ss.vec3("omega_search_B")) f.omega_search_B = *v;
  if (auto v = ss.real("lit_threshold", [](double x) {
        return x >= 0.0 && x < 1.0 ? std::string() : std::string("must be in [0, 1)");
      }))
    f.css_lit_threshold = *v;
  ss.finish();
  MapReader mf = r.sub("mrp_fb");
  if (auto v = mf.real("K", positive("N*m"))) f.mrp_fb.K = *v;
  else if (!mf.has("K")) mf.missing("K", "attitude gain [N*m]");
  if (auto v = mf.real("P", positive("N*m*s"))) f.mrp_fb.P = *v;
  else if (!mf.has("P")) mf.missing("P", "rate gain [N*m*s]");
  if (auto v = mf.real("K_i")) f.mrp_fb.K_i = *v;
  if (auto v = mf.real("integral_limit", non_negative("N*m*s"))) f.mrp_fb.integral_limit = *v;
  if (auto v = mf.integer("control_law", 0, 1)) f.mrp_fb.control_law = static_cast<int>(*v);
  if (auto v = mf.inertia("inertia")) f.mrp_fb.inertia = *v;
  mf.finish();
  MapReader rm = r.sub("rw_map");
  if (auto m = rm.choice("mode", {"min_norm", "power"})) f.rw_map = *m == 0 ? RwMapMode::MinNorm : RwMapMode::Power;
  if (auto v = rm.real("eps_P", positive("rad^2/s^2"))) f.eps_P = *v;
  rm.finish();
  MapReader rn = r.sub("rw_null");
  if (auto v = rn.boolean("enabled")) f.rw_null = *v;
  if (auto v = rn.real("k_null", positive("N*m*s"))) f.k_null = *v;
  if (auto v = rn.boolean("scale_to_fit")) f.rw_null_scale_to_fit = *v;
  {
    const bool a = rn.has("Omega_des"), b = rn.has("Omega_des_rpm");
    const std::string key = b ? "Omega_des_rpm" : "Omega_des";
    const double factor = b ? sim::kRadPerSecPerRpm : 1.0;
    rn.get("Omega_des");
    rn.get("Omega_des_rpm");
    if (a && b) {
      rn.error_at("Omega_des_rpm", "give either 'Omega_des' or 'Omega_des_rpm', not both");
    } else if (a || b) {
      YAML::Node l = rn.node()[key];
      if (!l.IsSequence()) {
        rn.error_at(key, "expected a list with one speed per wheel, got " + kind_name(l));
      } else if (l.size() != sc.wheels.size()) {
        rn.error_at(key, "expected " + std::to_string(sc.wheels.size()) + " speeds (one per wheel), got " +
                             std::to_string(l.size()));
      } else {
        for (size_t i = 0; i < l.size(); ++i) {
          double x = 0.0;
          if (!decode_double(l[i], x) || !std::isfinite(x)) {
            r.ctx().error(l[i], rn.key_path(key) + "[" + std::to_string(i) + "]",
                          "expected a finite number, got " + kind_name(l[i]));
            break;
          }
          f.Omega_des.push_back(x * factor);
        }
      }
    }
  }
  if (f.rw_null && !(f.k_null > 0.0) && !rn.has("k_null")) rn.missing("k_null", "needed when rw_null is enabled");
  rn.finish();
  MapReader tp = r.sub("thr_pulse");
  if (auto m = tp.choice("mode", {"remainder", "schmitt"}))
    f.thr_pulse = *m == 0 ? ThrPulseMode::Remainder : ThrPulseMode::Schmitt;
  if (auto v = tp.real("t_min", positive("s"))) f.thr_t_min = *v;
  if (auto v = tp.real("level_on", [](double x) {
        return x > 0.0 && x <= 1.0 ? std::string() : std::string("must be in (0, 1]");
      }))
    f.thr_level_on = *v;
  if (auto v = tp.real("level_off", non_negative("-"))) f.thr_level_off = *v;
  if (f.thr_level_off >= f.thr_level_on) tp.error_at(tp.has("level_off") ? "level_off" : "level_on", "level_off must be < level_on");
  tp.finish();
  MapReader tm = r.sub("thr_map");
  if (auto m = tm.choice("mode", {"min_norm", "nnls"})) f.thr_map = *m == 0 ? ThrMapMode::MinNorm : ThrMapMode::Nnls;
  tm.finish();
  f.actuation = sc.wheels.empty() ? Actuation::Thrusters : Actuation::Wheels;
  if (auto m = r.choice("actuation", {"wheels", "thrusters"})) {
    f.actuation = *m == 0 ? Actuation::Wheels : Actuation::Thrusters;
    bool acs = false;
    for (const ThrusterSpec& t : sc.thrusters) acs = acs || t.acs;
    if (f.actuation == Actuation::Wheels && sc.wheels.empty()) r.error_at("actuation", "'wheels' needs wheels");
    if (f.actuation == Actuation::Thrusters && !acs)
      r.error_at("actuation", "'thrusters' needs ACS thrusters (thrusters with acs: true)");
  }
  if (!r.has("mrp_fb")) r.missing("mrp_fb", "control gains K and P");
  r.finish();
}

void read_outputs(MapReader r, Scenario& sc)
{
  if (auto v = r.boolean("hdf5")) sc.outputs.hdf5 = *v;
  if (auto v = r.boolean("csv")) sc.outputs.csv = *v;
  if (auto v = r.boolean("report_data")) sc.outputs.report_data = *v;
  r.finish();
}

void read_scenario(const Ctx& ctx, const YAML::Node& root, Scenario& sc)
{
  MapReader top(ctx, root, "");
  if (!root.IsDefined() || root.IsNull()) {
    ctx.error(root, "(top level)", "empty scenario file");
    return;
  }
  if (auto v = top.string("name")) {
    bool ok = !v->empty();
    for (char c : *v) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
    if (!ok) top.error_at("name", "must be non-empty and use only letters, digits, '_' and '-'");
    else sc.name = *v;
  } else if (!top.has("name")) {
    top.missing("name", "scenario name");
  }
  if (auto v = top.string("description")) sc.description = *v;
  if (auto v = top.uinteger("seed")) sc.seed = *v;
  else if (!top.has("seed")) top.missing("seed", "random seed, a non-negative integer");
  if (auto v = top.real("duration", positive("s"))) sc.duration = *v;
  else if (!top.has("duration")) top.missing("duration", "simulated time [s]");
  if (!top.has("rates")) top.missing("rates", "dt and rate divisors");
  read_rates(top.sub("rates"), sc);
  if (!top.has("spacecraft")) top.missing("spacecraft", "mass, inertia, com");
  read_environment(top.sub("environment"), sc);
  read_spacecraft(top.sub("spacecraft"), sc);
  read_wheels(top, sc);
  read_thrusters(top, sc);
  read_tank(top.sub("tank"), sc.tank);
  read_tank(top.sub("rcs_tank"), sc.rcs_tank);
  read_burn(top.sub("burn"), sc);
  read_sensors(top.sub("sensors"), sc);
  if (!top.has("fsw")) top.missing("fsw", "flight software gains and modes");
  read_fsw(top.sub("fsw"), sc);
  read_outputs(top.sub("outputs"), sc);
  top.finish();

  // Cross-section checks.
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
  for (const Override& o : overrides) apply_override(ctx, root, o);
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

std::string ScenarioIssue::str() const
{
  std::string s = file;
  if (!where.empty()) s += ": " + where;
  else if (line > 0) s += ":" + std::to_string(line) + ":" + std::to_string(column);
  return s + ": " + key + ": " + message;
}

namespace {
std::string join_issues(const std::vector<ScenarioIssue>& v)
{
  std::string s;
  for (const auto& is : v) s += (s.empty() ? "" : "\n") + is.str();
  return s;
}
}  // namespace

ScenarioError::ScenarioError(std::vector<ScenarioIssue> issues)
    : std::runtime_error(join_issues(issues)), issues_(std::move(issues))
{
}

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

uint64_t Scenario::tick_ns() const { return static_cast<uint64_t>(std::llround(rates.dt * 1e9)); }
uint64_t Scenario::num_ticks() const
{
  return static_cast<uint64_t>(std::llround(duration / rates.dt));
}

const char* to_string(FswMode m) { return m == FswMode::Inertial ? "inertial" : "sun_safe"; }
const char* to_string(RwMapMode m) { return m == RwMapMode::MinNorm ? "min_norm" : "power"; }
const char* to_string(ThrPulseMode m) { return m == ThrPulseMode::Remainder ? "remainder" : "schmitt"; }
const char* to_string(ThrTransient m) { return m == ThrTransient::Instant ? "instant" : "first_order"; }
const char* to_string(Actuation m) { return m == Actuation::Wheels ? "wheels" : "thrusters"; }
const char* to_string(ThrMapMode m) { return m == ThrMapMode::MinNorm ? "min_norm" : "nnls"; }
const char* wheel_model_key(sim::WheelModel m)
{
  switch (m) {
    case sim::WheelModel::Balanced: return "balanced";
    case sim::WheelModel::SimpleJitter: return "simple_jitter";
    case sim::WheelModel::FullyCoupled: return "fully_coupled";
  }
  return "balanced";
}

}  // namespace harness

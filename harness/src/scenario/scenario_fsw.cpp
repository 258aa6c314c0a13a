// scenario_fsw.cpp: `fsw` (mode, guidance, mrp_fb gains, wheel and thruster
// mapping, null motion, pulse modulation, actuation).
#include <cmath>

#include "scenario/scenario_schema.h"

#include "sim/units.h"

namespace harness::schema {

namespace {

#define KESTREL_FSW(member) [](auto& sc, size_t) -> auto& { return sc.fsw.member; }

// rw_null.Omega_des (or Omega_des_rpm): one desired speed per wheel.
KeyDef omega_des()
{
  KeyDef d = custom(
      "Omega_des",
      [](const KeyDef& k, MapReader& rn, Scenario& sc, size_t) {
        const std::optional<bool> suffixed = rn.spelling(k.name, k.suffix);
        if (!suffixed) return;
        const std::string key = *suffixed ? k.name + k.suffix : k.name;
        const double factor = *suffixed ? k.factor : 1.0;
        if (!rn.has(key)) return;
        const YAML::Node& node = rn.node();
        const YAML::Node l = node[key];
        if (!l.IsSequence()) {
          rn.error_at(key, "expected a list with one speed per wheel, got " + kind_name(l));
        } else if (l.size() != sc.wheels.size()) {
          rn.error_at(key, "expected " + std::to_string(sc.wheels.size()) + " speeds (one per wheel), got " +
                               std::to_string(l.size()));
        } else {
          for (size_t i = 0; i < l.size(); ++i) {
            double x = 0.0;
            if (!decode_double(l[i], x) || !std::isfinite(x)) {
              rn.ctx().error(l[i], rn.key_path(key) + "[" + std::to_string(i) + "]",
                             "expected a finite number, got " + kind_name(l[i]));
              break;
            }
            sc.fsw.Omega_des.push_back(x * factor);
          }
        }
      },
      [](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t) {
        if (!sc.fsw.Omega_des.empty()) j[k.name] = sc.fsw.Omega_des;
      });
  d.alt("_rpm", sim::kRadPerSecPerRpm).unit("rad/s");
  return d;
}

Check in_range_closed_open(double lo, double hi, const char* msg)
{
  return [lo, hi, msg](double x, bool) { return x >= lo && x < hi ? std::string() : std::string(msg); };
}

// fsw.sun_safe: the Sun-pointing guidance.
Section sun_safe_section()
{
  return Section{"sun_safe",
                 {
                     vec3("sun_axis_B", KESTREL_FSW(sun_axis_B), true),
                     real("small_angle", KESTREL_FSW(sun_small_angle))
                         .alt("_deg", sim::kRadPerDeg)
                         .bounds(angle_below(90.0))
                         .unit("rad"),
                     vec3("omega_search_B", KESTREL_FSW(omega_search_B))
                         .vcheck(rate_within(kMaxBodyRateDegS))
                         .unit("rad/s"),
                     real("lit_threshold", KESTREL_FSW(css_lit_threshold))
                         .bounds(in_range_closed_open(0.0, 1.0, "must be in [0, 1)")).unit("-"),
                 },
                 {}};
}

// fsw.mrp_fb: the attitude control law's gains.
Section mrp_fb_section()
{
  return Section{"mrp_fb",
                 {
                     real("K", KESTREL_FSW(mrp_fb.K)).req("attitude gain [N*m]").bounds(positive("N*m")).unit("N*m"),
                     real("P", KESTREL_FSW(mrp_fb.P)).req("rate gain [N*m*s]").bounds(positive("N*m*s")).unit("N*m*s"),
                     real("K_i", KESTREL_FSW(mrp_fb.K_i)).unit("1/(kg*m^2)"),
                     real("integral_limit", KESTREL_FSW(mrp_fb.integral_limit))
                         .bounds(non_negative("N*m*s")).unit("N*m*s"),
                     integer("control_law", 0, 1, KESTREL_FSW(mrp_fb.control_law)),
                     inertia("inertia", KESTREL_FSW(mrp_fb.inertia)).unit("kg*m^2"),
                 },
                 {}};
}

// fsw.rw_null: wheel null motion.
Section rw_null_section()
{
  return Section{"rw_null",
                 {
                     boolean("enabled", KESTREL_FSW(rw_null)),
                     [] {
                       KeyDef k = real("k_null", KESTREL_FSW(k_null)).bounds(positive("N*m*s")).unit("N*m*s");
                       // 0 (not given) is not written: the manifest then reloads to 0 too
                       WriteFn plain = k.write;
                       k.write = [plain](const KeyDef& d, nlohmann::json& j, const Scenario& sc, size_t i) {
                         if (sc.fsw.k_null > 0.0) plain(d, j, sc, i);
                       };
                       return k;
                     }(),
                     boolean("scale_to_fit", KESTREL_FSW(rw_null_scale_to_fit)),
                     omega_des(),
                 },
                 {}};
}

// fsw.speed_filter: the screening of the wheel tachometers.
Section speed_filter_section()
{
  return Section{"speed_filter",
                 {
                     boolean("enabled", KESTREL_FSW(speed_filter)),
                     real("noise", KESTREL_FSW(sf_noise))
                         .alt("_rpm", sim::kRadPerSecPerRpm)
                         .bounds(non_negative("rad/s"))
                         .unit("rad/s"),
                     integer("k_reject", 1, 1000000, KESTREL_FSW(sf_k_reject)),
                     integer("n_recover", 1, 1000000, KESTREL_FSW(sf_n_recover)),
                     integer("n_stale", 0, 1000000, KESTREL_FSW(sf_n_stale)),
                     integer("n_window", 0, 1000000, KESTREL_FSW(sf_n_window)),
                     real("resid_tol", KESTREL_FSW(sf_resid_tol))
                         .alt("_rpm", sim::kRadPerSecPerRpm)
                         .bounds(non_negative("rad/s"))
                         .unit("rad/s"),
                 },
                 {}};
}

// fsw.thr_pulse: thruster pulse modulation.
Section thr_pulse_section()
{
  return Section{"thr_pulse",
                 {
                     choice<ThrPulseMode>("mode",
                                          {{"remainder", ThrPulseMode::Remainder}, {"schmitt", ThrPulseMode::Schmitt}},
                                          KESTREL_FSW(thr_pulse)),
                     real("t_min", KESTREL_FSW(thr_t_min)).bounds(positive("s")).unit("s"),
                     real("level_on", KESTREL_FSW(thr_level_on))
                         .bounds([](double x, bool) {
                           return x > 0.0 && x <= 1.0 ? std::string() : std::string("must be in (0, 1]");
                         })
                         .unit("-"),
                     real("level_off", KESTREL_FSW(thr_level_off)).bounds(non_negative("-")).unit("-"),
                 },
                 {}};
}

}  // namespace

const Section& fsw_section()
{
  static const Section s{
      "fsw",
      {
          choice<FswMode>("mode", {{"inertial", FswMode::Inertial}, {"sun_safe", FswMode::SunSafe}}, KESTREL_FSW(mode)),
          choice<Actuation>("actuation", {{"wheels", Actuation::Wheels}, {"thrusters", Actuation::Thrusters}},
                            KESTREL_FSW(actuation)),
      },
      {
          Section{"inertial", {vec3("sigma_R0N", KESTREL_FSW(sigma_R0N)).unit("-")}, {}},
          sun_safe_section(),
          mrp_fb_section(),
          Section{"rw_map",
                  {
                      choice<RwMapMode>("mode", {{"min_norm", RwMapMode::MinNorm}, {"power", RwMapMode::Power}},
                                        KESTREL_FSW(rw_map)),
                      real("eps_P", KESTREL_FSW(eps_P)).bounds(positive("rad^2/s^2")).unit("rad^2/s^2"),
                  },
                  {}},
          rw_null_section(),
          speed_filter_section(),
          thr_pulse_section(),
          Section{"thr_map",
                  {choice<ThrMapMode>("mode", {{"min_norm", ThrMapMode::MinNorm}, {"nnls", ThrMapMode::Nnls}},
                                      KESTREL_FSW(thr_map))},
                  {}},
      }};
  return s;
}
#undef KESTREL_FSW

void read_fsw(MapReader r, Scenario& sc)
{
  const Section& def = fsw_section();
  FswSpec& f = sc.fsw;
  // Absent, the actuation follows the hardware: wheels if any, else thrusters.
  f.actuation = sc.wheels.empty() ? Actuation::Thrusters : Actuation::Wheels;
  read_keys(r, def, sc);
  for (const Section& c : def.children) {
    MapReader m = r.sub(c.name);
    read_keys(m, c, sc);
    // Cross-field checks of a sub-section.
    if (c.name == "rw_null" && f.rw_null && !(f.k_null > 0.0) && !m.has("k_null"))
      m.missing("k_null", "needed when rw_null is enabled");
    if (c.name == "speed_filter" && f.speed_filter) {
      // The filter screens a tachometer: there must be one, sampled every
      // FSW cycle; the stale test needs noise (an ideal reading of a coasting
      // wheel repeats legitimately), the torque test a tolerance.
      const TachSpec& t = sc.sensors.tachometer;
      if (sc.wheels.empty()) m.error_at("enabled", "the speed filter needs wheels");
      else if (!t.enabled) m.error_at("enabled", "the speed filter needs sensors.tachometer.enabled: true");
      else if (t.divisor != 0 && t.divisor != sc.rates.fsw_divisor)
        m.error_at("enabled", "the speed filter needs a tachometer sample every FSW cycle "
                              "(sensors.tachometer divisor = rates.fsw_divisor)");
      if (!m.has("noise") && !m.has("noise_rpm")) m.missing("noise", "outlier margin [rad/s], needed when enabled");
      if (f.sf_n_stale > 0 && !(sc.sensors.noise && t.sigma > 0.0))
        m.error_at("n_stale", "the stale test needs a noisy tachometer (sensors.noise: true, tachometer sigma > 0)");
      if (f.sf_n_window > 0 && !m.has("resid_tol") && !m.has("resid_tol_rpm"))
        m.missing("resid_tol", "torque-window tolerance [rad/s], needed when n_window > 0");
    }
    if (c.name == "thr_pulse" && f.thr_level_off >= f.thr_level_on)
      m.error_at(m.has("level_off") ? "level_off" : "level_on", "level_off must be < level_on");
    m.finish();
  }
  const YAML::Node& given = r.node();
  const YAML::Node a = given["actuation"];
  if (a.IsDefined() && a.IsScalar() && (a.Scalar() == "wheels" || a.Scalar() == "thrusters")) {
    bool acs = false;
    for (const ThrusterSpec& t : sc.thrusters) acs = acs || t.acs;
    if (f.actuation == Actuation::Wheels && sc.wheels.empty()) r.error_at("actuation", "'wheels' needs wheels");
    if (f.actuation == Actuation::Thrusters && !acs)
      r.error_at("actuation", "'thrusters' needs ACS thrusters (thrusters with acs: true)");
  }
  if (!r.has("mrp_fb")) r.missing("mrp_fb", "control gains K and P");
  r.finish();
}

}  // namespace harness::schema

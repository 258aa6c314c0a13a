// scenario_fsw.cpp: `fsw` (mode, guidance, mrp_fb gains, wheel and thruster
// mapping, null motion, pulse modulation, actuation).
#include <cmath>

#include "scenario/scenario_schema.h"

#include "sim/units.h"

namespace harness::schema {

namespace {

#define KESTREL_FSW(member) [](auto& sc, size_t) -> auto& { return sc.fsw.member; }

// A list of one speed per wheel (rw_null.Omega_des, rw_bias.Omega_bias; or
// with the suffix _rpm).
template <class F>
KeyDef wheel_speeds(const char* name, F field)
{
  KeyDef d = custom(
      name,
      [field](const KeyDef& k, MapReader& rn, Scenario& sc, size_t) {
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
            field(sc).push_back(x * factor);
          }
        }
      },
      [field](const KeyDef& k, nlohmann::json& j, const Scenario& sc, size_t) {
        const std::vector<double>& v = field(sc);
        if (!v.empty()) j[k.name] = v;
      });
  d.alt("_rpm", sim::kRadPerSecPerRpm).unit("rad/s").json_shape(json_list_of({{"type", "number"}}));
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
                     real("k_null", KESTREL_FSW(k_null)).bounds(positive("N*m*s")).unit("N*m*s").zero_unset(),
                     boolean("scale_to_fit", KESTREL_FSW(rw_null_scale_to_fit)),
                     wheel_speeds("Omega_des", [](auto& sc) -> auto& { return sc.fsw.Omega_des; }),
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

// fsw.magnetorquers: the rods commanded by the FSW.
Section fsw_magnetorquers_section()
{
  Section s{"magnetorquers",
                 {
                     boolean("enabled", KESTREL_FSW(mtq)),
                     real("duty_max", KESTREL_FSW(mtq_duty_max))
                         .bounds([](double x, bool) {
                           return x > 0.0 && x <= 1.0 ? std::string() : std::string("must be in (0, 1]");
                         })
                         .unit("-"),
                 },
                 {}};
  s.present = [](const Scenario& sc) { return !sc.magnetorquers.empty(); };  // with rods only
  return s;
}

// fsw.bdot: DETUMBLE's law and its exit.
Section bdot_section()
{
  Section s{"bdot",
                 {
                     choice<BdotLaw>("law", {{"derivative", BdotLaw::Derivative}, {"gyro", BdotLaw::Gyro}},
                                     KESTREL_FSW(bdot_law)),
                     real("k", KESTREL_FSW(bdot_k)).bounds(positive("-")).unit("A*m^2*s/T").zero_unset(),
                     boolean("normalize", KESTREL_FSW(bdot_normalize)),
                     real("filter_tau", KESTREL_FSW(bdot_tau_f)).bounds(non_negative("s")).unit("s"),
                     integer("max_missed", 0, 1000000, KESTREL_FSW(bdot_max_missed)),
                     vec3("m_max", KESTREL_FSW(bdot_m_max)).unit("A*m^2"),
                     real("omega_done", KESTREL_FSW(bdot_omega_done))
                         .alt("_deg", sim::kRadPerDeg)
                         .bounds(positive("rad/s"))
                         .unit("rad/s")
                         .zero_unset(),
                     real("omega_reenter", KESTREL_FSW(bdot_omega_reenter))
                         .alt("_deg", sim::kRadPerDeg)
                         .bounds(non_negative("rad/s"))
                         .unit("rad/s"),
                     real("t_persist", KESTREL_FSW(bdot_t_persist)).bounds(non_negative("s")).unit("s"),
                     choice<FswMode>("exit_mode",
                                     {{"none", FswMode::Detumble},
                                      {"inertial", FswMode::Inertial},
                                      {"sun_safe", FswMode::SunSafe},
                                      {"nadir", FswMode::Nadir}},
                                     KESTREL_FSW(detumble_exit)),
                 },
                 {}};
  s.present = [](const Scenario& sc) { return !sc.magnetorquers.empty(); };  // with rods only
  return s;
}

// fsw.momentum: who unloads the wheels, and how.
Section momentum_section()
{
  return Section{"momentum",
                 {
                     choice<MomentumPolicy>("policy",
                                            {{"none", MomentumPolicy::None},
                                             {"thrusters", MomentumPolicy::Thrusters},
                                             {"magnetorquers", MomentumPolicy::Magnetorquers}},
                                            KESTREL_FSW(policy)),
                     real("h_upper", KESTREL_FSW(mom_h_upper)).bounds(positive("N*m*s")).unit("N*m*s").zero_unset(),
                     real("h_lower", KESTREL_FSW(mom_h_lower)).bounds(non_negative("N*m*s")).unit("N*m*s"),
                     real("L_dump", KESTREL_FSW(mom_L_dump)).bounds(positive("N*m")).unit("N*m").zero_unset(),
                     real("t_pulse_max", KESTREL_FSW(mom_t_pulse_max)).bounds(positive("s")).unit("s"),
                     real("t_min_pulse", KESTREL_FSW(mom_t_min_pulse)).bounds(positive("s")).unit("s"),
                     real("t_coast", KESTREL_FSW(mom_t_coast)).bounds(non_negative("s")).unit("s"),
                     real("Isp", KESTREL_FSW(mom_Isp)).bounds(positive("s")).unit("s"),
                     real("k_desat", KESTREL_FSW(mom_k_desat)).bounds(positive("1/s")).unit("1/s").zero_unset(),
                     real("tau_max", KESTREL_FSW(mom_tau_max)).bounds(positive("N*m")).unit("N*m").zero_unset(),
                     real("h_deadband", KESTREL_FSW(mom_h_deadband)).bounds(non_negative("N*m*s")).unit("N*m*s"),
                 },
                 {}};
}

// fsw.nadir: the orbit frame NADIR follows.
Section nadir_section()
{
  return Section{"nadir",
                 {
                     choice<OrbitFrame>("frame", {{"nadir", OrbitFrame::Nadir}, {"velocity", OrbitFrame::Velocity}},
                                        KESTREL_FSW(orbit_frame)),
                     attitude_key(vec3("sigma_BdR", KESTREL_FSW(sigma_BdR)).unit("-")),
                 },
                 {}};
}

// fsw.rw_bias: wheel-speed bias with zero-crossing avoidance.
Section rw_bias_section()
{
  return Section{"rw_bias",
                 {
                     boolean("enabled", KESTREL_FSW(rw_bias)),
                     wheel_speeds("Omega_bias", [](auto& sc) -> auto& { return sc.fsw.Omega_bias; }),
                     real("keepout", KESTREL_FSW(bias_keepout))
                         .alt("_rpm", sim::kRadPerSecPerRpm)
                         .bounds(positive("rad/s"))
                         .unit("rad/s")
                         .zero_unset(),
                     real("hysteresis", KESTREL_FSW(bias_hyst))
                         .alt("_rpm", sim::kRadPerSecPerRpm)
                         .bounds(non_negative("rad/s"))
                         .unit("rad/s"),
                 },
                 {}};
}

}  // namespace

const Section& fsw_section()
{
  static const Section s{
      "fsw",
      {
          choice<FswMode>("mode",
                          {{"inertial", FswMode::Inertial},
                           {"sun_safe", FswMode::SunSafe},
                           {"detumble", FswMode::Detumble},
                           {"nadir", FswMode::Nadir}},
                          KESTREL_FSW(mode)),
          choice<Actuation>("actuation", {{"wheels", Actuation::Wheels}, {"thrusters", Actuation::Thrusters}},
                            KESTREL_FSW(actuation)),
      },
      {
          Section{"inertial", {attitude_key(vec3("sigma_R0N", KESTREL_FSW(sigma_R0N)).unit("-"))}, {}},
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
          fsw_magnetorquers_section(),
          bdot_section(),
          nadir_section(),
          momentum_section(),
          rw_bias_section(),
      }};
  return s;
}
#undef KESTREL_FSW

namespace {

// The rods, DETUMBLE, NADIR, the momentum policy and rw_bias against the
// hardware and the environment they need.
void check_momentum_keys(MapReader& r, const Scenario& sc)
{
  const FswSpec& f = sc.fsw;
  const bool rods_needed = f.mode == FswMode::Detumble || f.policy == MomentumPolicy::Magnetorquers;
  MapReader mq = r.sub("magnetorquers");
  if (f.mtq && sc.magnetorquers.empty()) mq.error_at("enabled", "needs magnetorquers (top-level key 'magnetorquers')");
  if (f.mtq && !sc.sensors.magnetometer.enabled)
    mq.error_at("enabled", "needs sensors.magnetometer.enabled: true (the field the rods act against)");
  if (rods_needed && !f.mtq)
    r.error_at(f.mode == FswMode::Detumble ? "mode" : "momentum",
               "needs the rods commanded by the FSW (fsw.magnetorquers.enabled: true)");
  MapReader b = r.sub("bdot");
  if (f.mtq && !(f.bdot_k > 0.0)) b.missing("k", "B-dot gain, needed with fsw.magnetorquers");
  if (f.mtq && !(f.bdot_omega_done > 0.0)) b.missing("omega_done", "detumble-complete rate, needed with fsw.magnetorquers");
  if (f.bdot_omega_reenter > 0.0 && f.bdot_omega_reenter <= f.bdot_omega_done)
    b.error_at("omega_reenter", "must be above omega_done");
  const bool nadir = f.mode == FswMode::Nadir || (f.mode == FswMode::Detumble && f.detumble_exit == FswMode::Nadir);
  if (nadir && !(sc.environment.mu > 0.0))
    r.error_at("mode", "nadir pointing needs an orbit (environment.mu > 0)");
  MapReader m = r.sub("momentum");
  if (f.policy == MomentumPolicy::Thrusters) {
    const bool acs = sc.has_acs_thrusters();
    if (sc.wheels.empty() || !acs) m.error_at("policy", "'thrusters' needs wheels and ACS thrusters");
    if (!(f.mom_h_upper > 0.0)) m.missing("h_upper", "dump threshold [N*m*s]");
    if (!(f.mom_L_dump > 0.0)) m.missing("L_dump", "dump torque [N*m]");
    if (f.mom_h_lower >= f.mom_h_upper) m.error_at("h_lower", "must be below h_upper");
    if (f.mom_t_min_pulse > f.mom_t_pulse_max) m.error_at("t_min_pulse", "must not exceed t_pulse_max");
  }
  if (f.policy == MomentumPolicy::Magnetorquers) {
    if (sc.wheels.empty()) m.error_at("policy", "'magnetorquers' needs wheels");
    if (!(f.mom_k_desat > 0.0)) m.missing("k_desat", "desaturation gain [1/s]");
    if (!(f.mom_tau_max > 0.0)) m.missing("tau_max", "magnetic torque limit [N*m]");
  }
  MapReader rb = r.sub("rw_bias");
  if (f.rw_bias) {
    if (!f.rw_null) rb.error_at("enabled", "rw_bias sets rw_null's desired speeds: needs fsw.rw_null.enabled: true");
    if (f.Omega_bias.size() != sc.wheels.size())
      rb.missing("Omega_bias", "one bias speed per wheel, needed when enabled");
    if (!(f.bias_keepout > 0.0)) rb.missing("keepout", "the keep-out band around zero speed [rad/s]");
  }
}

}  // namespace

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
    const bool acs = sc.has_acs_thrusters();
    if (f.actuation == Actuation::Wheels && sc.wheels.empty()) r.error_at("actuation", "'wheels' needs wheels");
    if (f.actuation == Actuation::Thrusters && !acs)
      r.error_at("actuation", "'thrusters' needs ACS thrusters (thrusters with acs: true)");
  }
  if (!r.has("mrp_fb")) r.missing("mrp_fb", "control gains K and P");
  check_momentum_keys(r, sc);
  r.finish();
}

}  // namespace harness::schema

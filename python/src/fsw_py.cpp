// kestrel.fsw: bindings of every FSW algorithm of fsw_c (docs/python.md,
// "Flight algorithms").  One generic wrapper (bind_algorithm, on the field
// tables of fsw_field.h): an algorithm's config fields are attributes (NumPy
// for arrays), check()/init() raise ConfigError naming the bad field,
// update(**inputs) returns (Status, outputs dict).  Each binding is a table
// of the C structs' fields.
#include "fsw_field.h"

#include <memory>

namespace kpy {

namespace {

template <class Cfg, class St, class In, class Out>
struct Algorithm {
  Cfg cfg{};
  St st{};
  // The configuration the last successful init() checked: the C update
  // trusts its config (counts index fixed arrays), so counts are frozen and
  // update() refuses to run on a configuration changed since.
  Cfg init_cfg{};
  bool inited = false;
};

template <class Cfg, class St, class In, class Out>
struct Spec {
  const char* name;
  const char* doc;
  FswStatus (*check)(const Cfg*);
  FswStatus (*init)(St*, const Cfg*);
  void (*reset)(St*);
  FswStatus (*update)(St*, const Cfg*, const In*, Out*);
  std::vector<Field<Cfg>> cfg;
  std::vector<Field<In>> in;
  std::vector<Field<Out>> out;
  std::vector<Field<St>> st;
};

template <class T>
std::string doc_list(const char* title, const std::vector<Field<T>>& fs)
{
  std::string s = std::string("\n\n") + title + ":";
  for (const Field<T>& f : fs) s += "\n    " + f.name + ": " + f.doc;
  return s;
}

template <class Cfg, class St, class In, class Out>
void bind_algorithm(py::module_& m, Spec<Cfg, St, In, Out> spec)
{
  using A = Algorithm<Cfg, St, In, Out>;
  auto sp = std::make_shared<const Spec<Cfg, St, In, Out>>(std::move(spec));
  const std::string doc = std::string(sp->doc) + doc_list("Config fields (attributes)", sp->cfg) +
                          doc_list("Inputs (update keywords)", sp->in) + doc_list("Outputs (update dict)", sp->out);
  auto cls = py::class_<A>(m, sp->name, doc.c_str());
  cls.def(py::init([sp](const py::kwargs& kw) {
            auto a = std::make_unique<A>();
            from_kwargs(a->cfg, sp->cfg, kw, "config field");
            return a;
          }),
          "A zeroed configuration; keyword arguments set config fields.");
  for (const Field<Cfg>& fr : sp->cfg) {
    const Field<Cfg>* f = &fr;
    cls.def_property(
        f->name.c_str(), [sp, f](A& a) { return get_field(a.cfg, *f); },
        [sp, f](A& a, const py::handle& v) { set_config(a.cfg, *f, v, a.inited, sp->name); }, f->doc);
  }
  // a refused configuration: ConfigError naming the field (`good`: the last accepted one, or null)
  auto refuse = [sp](A& a, FswStatus s, const char* what, const Cfg* good) {
    const std::string field = find_bad_field(a.cfg, sp->cfg, sp->check, good);
    raise_config_error(std::string(sp->name) + "." + what, s, field,
                       field.empty() ? " (the field's range: the module's page under docs/fsw/)" : "");
  };
  cls.def(
         "check",
         [sp, refuse](A& a) -> py::object {
           const FswStatus s = sp->check(&a.cfg);
           if (fsw_status_is_error(s)) refuse(a, s, "check", a.inited ? &a.init_cfg : nullptr);
           return status_obj(s);
         },
         "check(self) -> Status: the C check of the configuration; Status.OK, else ConfigError (a ValueError) "
         "with .status and .field (the bad field's name)")
      .def(
          "init",
          [sp, refuse](A& a) -> py::object {
            const FswStatus s = sp->init(&a.st, &a.cfg);
            if (fsw_status_is_error(s)) {
              const Cfg good = a.init_cfg;
              const bool had = a.inited;
              a.inited = false;  // the C state is not ready: counts may change again
              refuse(a, s, "init", had ? &good : nullptr);
            }
            a.inited = true;
            a.init_cfg = a.cfg;
            return status_obj(s);
          },
          "init(self) -> Status: check, then a fresh state (the configuration update() runs with; counts are "
          "fixed from here on).  ConfigError naming the field on a refused configuration (the module is then "
          "not initialised).")
      .def("reset", [sp](A& a) { sp->reset(&a.st); }, "reset(self) -> None: clear the dynamic state")
      .def(
          "update",
          [sp](A& a, const py::kwargs& kw) {
            if (a.inited) {
              const std::string changed = changed_fields(a.cfg, a.init_cfg, sp->cfg);
              if (!changed.empty())
                throw py::value_error(std::string(sp->name) + ".update: the configuration changed after init() (" +
                                      changed + "): call init() again (it checks the new one)");
            }
            In in{};
            from_kwargs(in, sp->in, kw, "input");
            Out out{};
            const FswStatus s = sp->update(&a.st, &a.cfg, &in, &out);
            return py::make_tuple(status_obj(s), to_dict(out, sp->out));
          },
          "update(self, **inputs) -> tuple[Status, dict[str, numpy.ndarray | float | int]]: one update with the "
          "inputs given by keyword (absent inputs are zero).  Before a successful init() the status is "
          "E_NOT_INIT; after a configuration change ValueError naming the changed fields until init() again.")
      .def_property_readonly("config", [sp](A& a) { return to_dict(a.cfg, sp->cfg); }, "every config field, as a dict")
      .def_property_readonly("state", [sp](A& a) { return to_dict(a.st, sp->st); }, "the state's fields, as a dict")
      .def_property_readonly("initialized", [](A& a) { return a.inited; }, "a successful init() holds")
      .def_property_readonly_static("inputs", [sp](const py::object&) {
        std::vector<std::string> v;
        for (const auto& f : sp->in) v.push_back(f.name);
        return v;
      })
      .def_property_readonly_static("outputs", [sp](const py::object&) {
        std::vector<std::string> v;
        for (const auto& f : sp->out) v.push_back(f.name);
        return v;
      });
}

// guid_inertial's update has no input struct: an empty one for the template
struct NoIn {
  int unused;
};
FswStatus guid_inertial_update(FswGuidInertialState* st, const FswGuidInertialConfig* cfg, const NoIn*,
                               FswGuidInertialOut* out)
{
  return fsw_guid_inertial_update(st, cfg, out);
}

}  // namespace

// ---- config tables (also nested in fsw_acs's config) ------------------------

std::vector<Field<FswMrpFbConfig>> mrp_fb_config()
{
  using C = FswMrpFbConfig;
  return {KPY_SCALAR(C, Kind::Real, K, "[N*m] attitude gain"), KPY_SCALAR(C, Kind::Real, P, "[N*m*s] rate gain"),
          KPY_SCALAR(C, Kind::Real, K_i, "[1/(kg*m^2)] integral gain; <= 0 disables"),
          KPY_SCALAR(C, Kind::Real, integral_limit, "[N*m*s] per-component bound on int_sigma"),
          KPY_SCALAR(C, Kind::Int, control_law_type, "0 or 1"),
          KPY_VEC(C, Kind::Real, known_torque_B, 3, false, "[N*m] known external torque"),
          KPY_MAT(C, I_B, 3, 3, false, "[kg*m^2] inertia about the CoM, B"),
          KPY_COUNT(C, num_rw, RW_CAP, "wheels in H, 0..MAX_RW"),
          KPY_RW_AXES(C),
          KPY_RW_VEC(C, J_s, "[kg*m^2] (num_rw) wheel spin inertias")};
}

std::vector<Field<FswRwMapConfig>> rw_map_config()
{
  using C = FswRwMapConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "1..MAX_RW"), KPY_RW_AXES(C),
          KPY_COUNT(C, num_axes, 3, "controlled axes 0..3"),
          KPY_MAT(C, ctrl_axes_B, 3, 3, true, "(num_axes, 3) control axes, rows"),
          KPY_SCALAR(C, Kind::Int, mode, "0 min-norm, 1 power"),
          KPY_SCALAR(C, Kind::Real, eps_P, "[rad^2/s^2] power mode")};
}

std::vector<Field<FswRwSatConfig>> rw_sat_config()
{
  using C = FswRwSatConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "1..MAX_RW"),
          KPY_RW_VEC(C, u_max, "[N*m] (num_rw) torque limits"),
          KPY_SCALAR(C, Kind::Int, mode, "0 scale, 1 clip")};
}

std::vector<Field<FswTrqLpfConfig>> trq_lpf_config()
{
  using C = FswTrqLpfConfig;
  return {KPY_SCALAR(C, Kind::Real, h, "[s] assumed call period"),
          KPY_SCALAR(C, Kind::Real, omega_c, "[rad/s] cut-off")};
}

std::vector<Field<FswAttTrackConfig>> att_track_config()
{
  using C = FswAttTrackConfig;
  return {KPY_VEC(C, Kind::Real, sigma_R0R, 3, false, "[-] nominal reference rel. the corrected one")};
}

std::vector<Field<FswBdotConfig>> bdot_config()
{
  using C = FswBdotConfig;
  return {KPY_SCALAR(C, Kind::Int, variant, "0 DERIV (magnetometer derivative), 1 GYRO"),
          KPY_SCALAR(C, Kind::Real, k_bdot, "gain, > 0"),
          KPY_SCALAR(C, Kind::Int, normalize, "0: g = k_bdot; 1: g = k_bdot / |B|^2"),
          KPY_SCALAR(C, Kind::Real, tau_f, "[s] derivative filter time constant (DERIV)"),
          KPY_SCALAR(C, Kind::Int, max_missed, "cycles a dipole is held over missed samples"),
          KPY_VEC(C, Kind::Real, m_max_B, 3, false, "[A*m^2] per-axis dipole limit"),
          KPY_SCALAR(C, Kind::Real, omega_done, "[rad/s] detumbled threshold"),
          KPY_SCALAR(C, Kind::Real, omega_reenter, "[rad/s] re-entry threshold, > omega_done"),
          KPY_SCALAR(C, Kind::Real, t_persist, "[s] time below omega_done before detumbled")};
}

std::vector<Field<FswCssSunConfig>> css_sun_config()
{
  using C = FswCssSunConfig;
  return {KPY_COUNT(C, num_css, FSW_MAX_CSS, "sensors, 1..MAX_CSS"),
          KPY_MAT(C, n_hat_B, FSW_MAX_CSS, 3, true, "(num_css, 3) unit normals, B"),
          KPY_VEC(C, Kind::Real, scale, FSW_MAX_CSS, true, "(num_css) reading at normal incidence, > 0"),
          KPY_SCALAR(C, Kind::Real, lit_threshold, "[-] a sensor is lit above it, [0, 1)")};
}

std::vector<Field<FswGuidInertialConfig>> guid_inertial_config()
{
  using C = FswGuidInertialConfig;
  return {KPY_VEC(C, Kind::Real, sigma_R0N, 3, false, "[-] commanded inertial attitude (MRP)")};
}

std::vector<Field<FswGuidOrbitConfig>> guid_orbit_config()
{
  using C = FswGuidOrbitConfig;
  return {KPY_SCALAR(C, Kind::Int, variant, "0 NADIR, 1 VELOCITY"),
          KPY_VEC(C, Kind::Real, sigma_BdR, 3, false, "[-] desired body attitude rel. the orbit frame"),
          KPY_SCALAR(C, Kind::Real, mu, "[m^3/s^2] gravitational parameter (VELOCITY)")};
}

std::vector<Field<FswGuidSunsafeConfig>> guid_sunsafe_config()
{
  using C = FswGuidSunsafeConfig;
  return {KPY_VEC(C, Kind::Real, s_cmd_B, 3, false, "[-] body axis to point at the Sun"),
          KPY_SCALAR(C, Kind::Real, min_unit_mag, "[-] smallest |sun_B| taken as a heading"),
          KPY_SCALAR(C, Kind::Real, small_angle, "[rad] below it the error is zero"),
          KPY_VEC(C, Kind::Real, omega_search_B, 3, false, "[rad/s] search rate without a heading"),
          KPY_SCALAR(C, Kind::Real, sun_axis_spin_rate, "[rad/s] spin about the Sun line")};
}

std::vector<Field<FswMtqDesatConfig>> mtq_desat_config()
{
  using C = FswMtqDesatConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "wheels, 1..MAX_RW"),
          KPY_RW_AXES(C),
          KPY_RW_VEC(C, J_s, "[kg*m^2] (num_rw) spin inertias"),
          KPY_SCALAR(C, Kind::Real, k_desat, "[1/s] momentum feedback gain"),
          KPY_VEC(C, Kind::Real, h_target_B, 3, false, "[N*m*s] target wheel momentum"),
          KPY_SCALAR(C, Kind::Real, tau_max, "[N*m] requested torque limit"),
          KPY_SCALAR(C, Kind::Real, h_deadband, "[N*m*s] no request below it")};
}

std::vector<Field<FswMtqMapConfig>> mtq_map_config()
{
  using C = FswMtqMapConfig;
  return {KPY_COUNT(C, num_mtq, FSW_MAX_MTQ, "rods, 1..MAX_MTQ"),
          KPY_MAT(C, gt_hat_B, FSW_MAX_MTQ, 3, true, "(num_mtq, 3) rod axes"),
          KPY_VEC(C, Kind::Real, m_max, FSW_MAX_MTQ, true, "[A*m^2] (num_mtq) dipole limits"),
          KPY_SCALAR(C, Kind::Real, duty_max, "[-] largest duty (sensing time-sharing)")};
}

std::vector<Field<FswRwBiasConfig>> rw_bias_config()
{
  using C = FswRwBiasConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "wheels, 4..MAX_RW"),
          KPY_RW_AXES(C),
          KPY_RW_VEC(C, Omega_bias, "[rad/s] (num_rw) preferred speeds"),
          KPY_SCALAR(C, Kind::Real, Omega_keepout, "[rad/s] keep-out band half-width about 0"),
          KPY_SCALAR(C, Kind::Real, Omega_hyst, "[rad/s] hysteresis of the band")};
}

std::vector<Field<FswRwNullConfig>> rw_null_config()
{
  using C = FswRwNullConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "wheels, 4..MAX_RW"),
          KPY_RW_AXES(C),
          KPY_SCALAR(C, Kind::Real, k_null, "[N*m*s] null-motion gain"),
          KPY_RW_VEC(C, u_max, "[N*m] (num_rw) torque limits (scale_to_fit)"),
          KPY_SCALAR(C, Kind::Int, scale_to_fit, "0/1: shrink the null torque to the limits")};
}

std::vector<Field<FswRwNullRegenConfig>> rw_null_regen_config()
{
  using C = FswRwNullRegenConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "wheels, 4..MAX_RW"),
          KPY_RW_AXES(C),
          KPY_SCALAR(C, Kind::Real, k_P, "[N*m*s] gain"),
          KPY_RW_VEC(C, u_max, "[N*m] (num_rw) torque limits"),
          KPY_SCALAR(C, Kind::Int, mode, "the law (docs/fsw/rw_null_regen.md)")};
}

std::vector<Field<FswRwSpeedFilterConfig>> rw_speed_filter_config()
{
  using C = FswRwSpeedFilterConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "wheels, 1..MAX_RW"),
          KPY_RW_VEC(C, u_max, "[N*m] (num_rw) torque limits"),
          KPY_RW_VEC(C, J_s, "[kg*m^2] (num_rw) spin inertias"),
          KPY_RW_VEC(C, noise, "[rad/s] (num_rw) tachometer noise"),
          KPY_SCALAR(C, Kind::U32, k_reject, "rejections in a row that fail a wheel"),
          KPY_SCALAR(C, Kind::U32, n_recover, "good samples that recover it"),
          KPY_SCALAR(C, Kind::U32, n_stale, "identical samples that fail it"),
          KPY_SCALAR(C, Kind::U32, n_window, "torque-consistency window (0 off)"),
          KPY_RW_VEC(C, resid_tol, "[rad/s] (num_rw) window residual tolerance")};
}

std::vector<Field<FswRwVoltConfig>> rw_volt_config()
{
  using C = FswRwVoltConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "wheels, 1..MAX_RW"),
          KPY_SCALAR(C, Kind::Real, V_min, "[V] smallest commanded |V| (dead zone)"),
          KPY_SCALAR(C, Kind::Real, V_max, "[V] largest |V|"),
          KPY_SCALAR(C, Kind::Real, K_V, "[V/(N*m)] volts per torque"),
          KPY_RW_VEC(C, u_max, "[N*m] (num_rw) torque limits"),
          KPY_RW_VEC(C, J_s, "[kg*m^2] (num_rw) spin inertias"),
          KPY_RW_VEC(C, Omega_dot_max, "[rad/s^2] (num_rw) rate gate"),
          KPY_SCALAR(C, Kind::Int, gate_rate, "0/1: the acceleration gate")};
}

std::vector<Field<FswThrMapConfig>> thr_map_config()
{
  using C = FswThrMapConfig;
  return {KPY_COUNT(C, num_thr, THR_CAP, "thrusters, 1..MAX_THR"),
          KPY_MAT(C, control_axes_B, 3, 3, true, "(axes, 3) control axes, rows (zero rows unused)"),
          KPY_MAT(C, r_thr_B, THR_CAP, 3, true, "[m] (num_thr, 3) locations"),
          KPY_MAT(C, gt_hat_B, THR_CAP, 3, true, "(num_thr, 3) force axes"),
          KPY_VEC(C, Kind::Real, F_max, THR_CAP, true, "[N] (num_thr) max thrust"),
          KPY_SCALAR(C, Kind::Int, thr_force_sign, "+1 on-pulsing, -1 off-pulsing"),
          KPY_SCALAR(C, Kind::Int, mode, "the mapping (docs/fsw/thr_map.md)"),
          KPY_SCALAR(C, Kind::Real, ang_err_thresh, "[rad] direction-error threshold"),
          KPY_SCALAR(C, Kind::Real, epsilon, "[-] rank tolerance")};
}

std::vector<Field<FswThrMomentumConfig>> thr_momentum_config()
{
  using C = FswThrMomentumConfig;
  return {KPY_COUNT(C, num_rw, RW_CAP, "wheels, 1..MAX_RW"),
          KPY_RW_AXES(C),
          KPY_RW_VEC(C, J_s, "[kg*m^2] (num_rw) spin inertias"),
          KPY_SCALAR(C, Kind::Real, h_upper, "[N*m*s] a dump starts above it"),
          KPY_SCALAR(C, Kind::Real, h_lower, "[N*m*s] a dump ends at it"),
          KPY_SCALAR(C, Kind::Real, L_dump, "[N*m] dump torque"),
          KPY_SCALAR(C, Kind::Real, t_pulse_max, "[s] longest pulse"),
          KPY_SCALAR(C, Kind::Real, t_min_pulse, "[s] shortest pulse"),
          KPY_SCALAR(C, Kind::Real, t_coast, "[s] coast between pulses"),
          KPY_SCALAR(C, Kind::Real, dt_cycle, "[s] control period"),
          KPY_COUNT(C, num_thr, THR_CAP, "thrusters, 1..MAX_THR"),
          KPY_VEC(C, Kind::Real, F_max, THR_CAP, true, "[N] (num_thr) max thrust"),
          KPY_SCALAR(C, Kind::Real, Isp, "[s] specific impulse")};
}

namespace {
// the pulse-width pulsers' shared part (common.*), named without the prefix
template <class C>
std::vector<Field<C>> pulse_common()
{
  return {KPY_COUNT_AS(C, "num_thr", common.num_thr, THR_CAP, "thrusters, 1..MAX_THR"),
          KPY_VEC_K(C, "F_max", Kind::Real, common.F_max, THR_CAP, true, "[N] (num_thr) max thrust"),
          KPY_SCALAR_AS(C, "t_min", Kind::Real, common.t_min, "[s] minimum on-time, > 0"),
          KPY_SCALAR_AS(C, "base_thrust_state", Kind::Int, common.base_thrust_state, "0 on-pulsing, 1 off-pulsing"),
          KPY_SCALAR_AS(C, "init_off_pulse_on_time", Kind::Real, common.init_off_pulse_on_time,
                        "[s] first-call on-time when off-pulsing")};
}
}  // namespace

std::vector<Field<FswThrPulseRemConfig>> thr_pulse_rem_config() { return pulse_common<FswThrPulseRemConfig>(); }

std::vector<Field<FswThrPulseSchmittConfig>> thr_pulse_schmitt_config()
{
  using C = FswThrPulseSchmittConfig;
  auto v = pulse_common<C>();
  append(v, {KPY_SCALAR(C, Kind::Real, level_on, "[-] duty level that switches on, <= 1"),
             KPY_SCALAR(C, Kind::Real, level_off, "[-] duty level that switches off, < level_on")});
  return v;
}

std::vector<Field<FswThrPulseRoundConfig>> thr_pulse_round_config()
{
  using C = FswThrPulseRoundConfig;
  return {KPY_COUNT(C, num_thr, THR_CAP, "thrusters, 1..MAX_THR"),
          KPY_VEC(C, Kind::Real, F_max, THR_CAP, true, "[N] (num_thr) max thrust"),
          KPY_SCALAR(C, Kind::Real, period, "[s] control period T"),
          KPY_SCALAR(C, Kind::Real, resolution, "[s] on-time resolution q"),
          KPY_SCALAR(C, Kind::Real, t_min, "[s] minimum on-time, 0..period"),
          KPY_SCALAR(C, Kind::Int, carry_residual, "0/1: carry the rounding error")};
}

namespace {
// every state: `ready` (the pulsers keep it in common)
template <class S>
std::vector<Field<S>> ready_only()
{
  return {KPY_SCALAR(S, Kind::Int, ready, "1 after a successful init")};
}
template <class S>
std::vector<Field<S>> ready_common()
{
  return {KPY_SCALAR_AS(S, "ready", Kind::Int, common.ready, "1 after a successful init")};
}
// the attitude guidance message FswAttGuid, as fields of a struct holding it in `guid`
template <class T>
std::vector<Field<T>> att_guid()
{
  return {KPY_VEC_AS(T, "sigma_BR", guid.sigma_BR, 3, "[-] attitude error"),
          KPY_VEC_AS(T, "omega_BR_B", guid.omega_BR_B, 3, "[rad/s] rate error"),
          KPY_VEC_AS(T, "omega_RN_B", guid.omega_RN_B, 3, "[rad/s] reference rate, B"),
          KPY_VEC_AS(T, "omega_dot_RN_B", guid.omega_dot_RN_B, 3, "[rad/s^2] reference acceleration, B")};
}
// the attitude reference FswAttRef
std::vector<Field<FswAttRef>> att_ref()
{
  using T = FswAttRef;
  return {KPY_VEC(T, Kind::Real, sigma_RN, 3, false, "[-] reference attitude"),
          KPY_VEC(T, Kind::Real, omega_RN_N, 3, false, "[rad/s] reference rate, N"),
          KPY_VEC(T, Kind::Real, omega_dot_RN_N, 3, false, "[rad/s^2] reference acceleration, N")};
}
// a per-thruster force input and on-time output of a pulser
template <class In>
std::vector<Field<In>> pulse_in()
{
  return {KPY_SCALAR(In, Kind::U64, t_ns, "[ns]"),
          KPY_VEC(In, Kind::Real, F, THR_CAP, true, "[N] (num_thr) force command")};
}
template <class Out>
std::vector<Field<Out>> pulse_out()
{
  return {KPY_VEC(Out, Kind::Real, t_on, THR_CAP, true, "[s] on-times (MAX_THR; 0 beyond num_thr)")};
}
}  // namespace

void bind_fsw(py::module_& m)
{
  m.attr("MAX_RW") = FSW_MAX_RW;
  m.attr("MAX_THR") = FSW_MAX_THR;
  m.attr("MAX_CSS") = FSW_MAX_CSS;
  m.attr("MAX_MTQ") = FSW_MAX_MTQ;
  m.attr("REAL_IS_FLOAT") = static_cast<bool>(FSW_USE_FLOAT);
  const std::pair<const char*, FswStatus> codes[] = {
      {"OK", FSW_OK},           {"W_SINGULAR", FSW_W_SINGULAR},   {"W_SAT", FSW_W_SAT},
      {"W_RATE", FSW_W_RATE},   {"E_NULL_ARG", FSW_E_NULL_ARG},   {"E_CONFIG", FSW_E_CONFIG},
      {"E_CAPACITY", FSW_E_CAPACITY}, {"E_SINGULAR", FSW_E_SINGULAR}, {"E_BAD_INPUT", FSW_E_BAD_INPUT},
      {"E_TIME", FSW_E_TIME},   {"E_UNSUPPORTED", FSW_E_UNSUPPORTED}, {"E_NOT_INIT", FSW_E_NOT_INIT}};
  py::list members;
  for (const auto& c : codes) members.append(py::make_tuple(c.first, static_cast<int>(c.second)));
  // Status: an IntEnum (equal to the C int; .name 'E_CONFIG'); OK, E_CONFIG, ... at module level too
  py::object status = py::module_::import("enum").attr("IntEnum")("Status", members, py::arg("module") = "kestrel.fsw");
  status.attr("__doc__") = "FswStatus of fsw_c: errors negative, warnings positive, OK zero";
  m.attr("Status") = status;
  for (const auto& c : codes) m.attr(c.first) = status(static_cast<int>(c.second));
  m.def("status_name", [](int s) { return std::string(fsw_status_name(static_cast<FswStatus>(s))); },
        "status_name(s: int) -> str: 'FSW_OK', 'FSW_E_CONFIG', ...");
  py::object config_error = py::module_::import("builtins").attr("type")(
      "ConfigError", py::make_tuple(py::module_::import("builtins").attr("ValueError")),
      py::dict(py::arg("__module__") = "kestrel.fsw",
               py::arg("__doc__") = "A configuration check() or init() refused: .status (Status) and .field (the "
                                    "bad field's name, or None when it could not be isolated)",
               py::arg("status") = py::none(), py::arg("field") = py::none()));
  m.attr("ConfigError") = config_error;

  {
    using I = FswMrpFbIn;
    using O = FswMrpFbOut;
    using S = FswMrpFbState;
    auto in = std::vector<Field<I>>{KPY_SCALAR(I, Kind::U64, t_ns, "[ns]")};
    append(in, att_guid<I>());
    append(in, {KPY_RW_SPEEDS(I),
                KPY_RW_MASK(I, rw_avail)});
    bind_algorithm(m, Spec<FswMrpFbConfig, S, I, O>{
        "MrpFb", "MRP feedback control law (docs/fsw/mrp_fb.md)", KPY_FNS(mrp_fb), mrp_fb_config(), in,
        {KPY_VEC(O, Kind::Real, torque_B, 3, false, "[N*m] Lr"),
         KPY_VEC(O, Kind::Real, int_torque_B, 3, false, "[N*m] integral part")},
        {KPY_SCALAR(S, Kind::Int, ready, ""), KPY_VEC(S, Kind::Real, int_sigma, 3, false, "[N*m*s]")}});
  }
  {
    using I = FswRwMapIn;
    using O = FswRwMapOut;
    bind_algorithm(m, Spec<FswRwMapConfig, FswRwMapState, I, O>{
        "RwMap", "Reaction-wheel torque mapping (docs/fsw/rw_map.md)", KPY_FNS(rw_map), rw_map_config(),
        {KPY_VEC(I, Kind::Real, Lr_B, 3, false, "[N*m] torque the wheels must apply to the body"),
         KPY_RW_SPEEDS(I),
         KPY_RW_MASK(I, avail)},
        {KPY_RW_VEC(O, u_s, "[N*m] motor torques (MAX_RW; 0 beyond num_rw)")},
        ready_only<FswRwMapState>()});
  }
  {
    using I = FswRwSatIn;
    using O = FswRwSatOut;
    bind_algorithm(m, Spec<FswRwSatConfig, FswRwSatState, I, O>{
        "RwSat", "Reaction-wheel torque saturation (fsw_c/include/fsw/rw_sat.h)", KPY_FNS(rw_sat), rw_sat_config(),
        {KPY_RW_VEC(I, u_s, "[N*m] (num_rw) commanded torques"),
         KPY_RW_MASK(I, avail)},
        {KPY_RW_VEC(O, u_s, "[N*m] limited torques")}, ready_only<FswRwSatState>()});
  }
  {
    using I = FswTrqLpfIn;
    using O = FswTrqLpfOut;
    using S = FswTrqLpfState;
    bind_algorithm(m, Spec<FswTrqLpfConfig, S, I, O>{
        "TrqLpf", "Control-torque low-pass filter, first-order Tustin (docs/fsw/trq_lpf.md)", KPY_FNS(trq_lpf), trq_lpf_config(),
        {KPY_VEC(I, Kind::Real, Lr_B, 3, false, "[N*m] control torque"), KPY_SCALAR(I, Kind::U64, t_ns, "[ns]")},
        {KPY_VEC(O, Kind::Real, LrF_B, 3, false, "[N*m] filtered torque")},
        {KPY_SCALAR(S, Kind::Int, ready, ""), KPY_VEC(S, Kind::Real, Lr_prev, 3, false, "[N*m]"),
         KPY_VEC(S, Kind::Real, LrF_prev, 3, false, "[N*m]")}});
  }
  {
    using I = FswAttTrackIn;
    using O = FswAttTrackOut;
    auto in = std::vector<Field<I>>{KPY_VEC(I, Kind::Real, sigma_BN, 3, false, "[-]"),
                                    KPY_VEC(I, Kind::Real, omega_BN_B, 3, false, "[rad/s]")};
    append(in, nest("ref", &I::ref, att_ref()));
    for (auto& f : in) f.name = f.name.substr(f.name.find('.') + 1);  // ref.sigma_RN -> sigma_RN
    bind_algorithm(m, Spec<FswAttTrackConfig, FswAttTrackState, I, O>{
        "AttTrack", "Attitude tracking error (docs/fsw/att_track.md)", KPY_FNS(att_track), att_track_config(), in,
        {KPY_VEC(O, Kind::Real, sigma_BR, 3, false, "[-]"), KPY_VEC(O, Kind::Real, omega_BR_B, 3, false, "[rad/s]"),
         KPY_VEC(O, Kind::Real, omega_RN_B, 3, false, "[rad/s]"),
         KPY_VEC(O, Kind::Real, omega_dot_RN_B, 3, false, "[rad/s^2]")},
        ready_only<FswAttTrackState>()});
  }
  {
    using I = FswBdotIn;
    using O = FswBdotOut;
    bind_algorithm(m, Spec<FswBdotConfig, FswBdotState, I, O>{
        "Bdot", "B-dot detumbling with magnetorquers (docs/fsw/bdot.md)", KPY_FNS(bdot), bdot_config(),
        {KPY_SCALAR(I, Kind::U64, t_ns, "[ns]"), KPY_VEC(I, Kind::Real, B_B, 3, false, "[T] measured field"),
         KPY_SCALAR(I, Kind::U8, B_valid, "1 valid sample"),
         KPY_VEC(I, Kind::Real, omega_BN_B, 3, false, "[rad/s] body rate"),
         KPY_SCALAR(I, Kind::U8, omega_valid, "1 valid rate")},
        {KPY_VEC(O, Kind::Real, m_B, 3, false, "[A*m^2] commanded dipole"),
         KPY_VEC(O, Kind::Real, Bdot_B, 3, false, "[T/s] Bdot used"),
         KPY_SCALAR(O, Kind::Real, rate_est, "[rad/s] rate of the detumble test"),
         KPY_SCALAR(O, Kind::U8, rate_valid, "1 when rate_est is a measurement"),
         KPY_SCALAR(O, Kind::U8, detumbled, "latched detumble flag"),
         KPY_SCALAR(O, Kind::Real, t_below, "[s] time below omega_done"),
         KPY_SCALAR(O, Kind::Real, scale, "[-] saturation factor"),
         KPY_SCALAR(O, Kind::U8, held, "1 when m_B is held over a missed sample")},
        ready_only<FswBdotState>()});
  }
  {
    using I = FswCssSunIn;
    using O = FswCssSunOut;
    bind_algorithm(m, Spec<FswCssSunConfig, FswCssSunState, I, O>{
        "CssSun", "Sun heading from coarse sun sensors, weighted least squares (docs/fsw/css_sun.md)",
        KPY_FNS(css_sun), css_sun_config(),
        {KPY_VEC(I, Kind::Real, reading, FSW_MAX_CSS, true, "(num_css) raw readings"),
         KPY_VEC(I, Kind::U8, avail, FSW_MAX_CSS, true, "(num_css) 0 available, 1 unavailable")},
        {KPY_VEC(O, Kind::Real, sun_hat_B, 3, false, "[-] unit Sun heading (0 when sun_valid = 0)"),
         KPY_SCALAR(O, Kind::Real, sun_mag, "[-] |x| before normalisation"),
         KPY_SCALAR(O, Kind::Int, sun_valid, "1 when sun_hat_B holds a heading"),
         KPY_SCALAR(O, Kind::Int, num_lit, "lit sensors"),
         KPY_SCALAR(O, Kind::Int, mode, "0 NONE, 1 ONE, 2 TWO, 3 WLS")},
        ready_only<FswCssSunState>()});
  }
  {
    auto out = att_ref();
    bind_algorithm(m, Spec<FswGuidInertialConfig, FswGuidInertialState, NoIn, FswAttRef>{
        "GuidInertial", "Inertial three-axis pointing guidance (docs/fsw/guid_inertial.md); update() takes no input",
        fsw_guid_inertial_check, fsw_guid_inertial_init, fsw_guid_inertial_reset, guid_inertial_update,
        guid_inertial_config(), {}, out, ready_only<FswGuidInertialState>()});
  }
  {
    using I = FswGuidOrbitIn;
    bind_algorithm(m, Spec<FswGuidOrbitConfig, FswGuidOrbitState, I, FswAttRef>{
        "GuidOrbit", "Orbit-referenced guidance, nadir or velocity pointing (docs/fsw/guid_orbit.md)",
        KPY_FNS(guid_orbit), guid_orbit_config(),
        {KPY_VEC(I, Kind::Real, r_N, 3, false, "[m] position, N"), KPY_VEC(I, Kind::Real, v_N, 3, false, "[m/s] velocity, N"),
         KPY_SCALAR(I, Kind::U8, valid, "1 valid orbit")},
        att_ref(), ready_only<FswGuidOrbitState>()});
  }
  {
    using I = FswGuidSunsafeIn;
    using O = FswGuidSunsafeOut;
    auto out = att_guid<O>();
    append(out, {KPY_SCALAR(O, Kind::Real, sun_angle_err, "[rad] angle between s_cmd and the Sun"),
                 KPY_SCALAR(O, Kind::Int, sun_valid, "1 when a Sun heading was used")});
    bind_algorithm(m, Spec<FswGuidSunsafeConfig, FswGuidSunsafeState, I, O>{
        "GuidSunsafe", "Sun-safe pointing guidance (docs/fsw/guid_sunsafe.md)", KPY_FNS(guid_sunsafe), guid_sunsafe_config(),
        {KPY_VEC(I, Kind::Real, sun_B, 3, false, "[-] Sun heading, B (0: none)"),
         KPY_VEC(I, Kind::Real, omega_BN_B, 3, false, "[rad/s] body rate")},
        out, ready_only<FswGuidSunsafeState>()});
  }
  {
    using I = FswMtqDesatIn;
    using O = FswMtqDesatOut;
    bind_algorithm(m, Spec<FswMtqDesatConfig, FswMtqDesatState, I, O>{
        "MtqDesat", "Wheel momentum unloading with magnetorquers (docs/fsw/mtq_desat.md)", KPY_FNS(mtq_desat), mtq_desat_config(),
        {KPY_RW_SPEEDS(I),
         KPY_RW_MASK(I, avail),
         KPY_VEC(I, Kind::Real, B_B, 3, false, "[T] field, B"), KPY_SCALAR(I, Kind::U8, B_valid, "1 valid field")},
        {KPY_VEC(O, Kind::Real, tau_req_B, 3, false, "[N*m] requested torque"),
         KPY_VEC(O, Kind::Real, m_B, 3, false, "[A*m^2] dipole"),
         KPY_VEC(O, Kind::Real, h_w_B, 3, false, "[N*m*s] wheel momentum"),
         KPY_VEC(O, Kind::Real, h_err_B, 3, false, "[N*m*s] h_w - h_target"),
         KPY_SCALAR(O, Kind::Real, h_err_norm, "[N*m*s]"), KPY_SCALAR(O, Kind::Real, scale, "[-]")},
        ready_only<FswMtqDesatState>()});
  }
  {
    using I = FswMtqMapIn;
    using O = FswMtqMapOut;
    bind_algorithm(m, Spec<FswMtqMapConfig, FswMtqMapState, I, O>{
        "MtqMap", "Magnetorquer mapping, torque or dipole to rod commands (docs/fsw/mtq_map.md)", KPY_FNS(mtq_map), mtq_map_config(),
        {KPY_VEC(I, Kind::Real, tau_B, 3, false, "[N*m] requested torque"),
         KPY_VEC(I, Kind::Real, m_req_B, 3, false, "[A*m^2] requested dipole (use_dipole = 1)"),
         KPY_SCALAR(I, Kind::U8, use_dipole, "1: map m_req_B, 0: map tau_B"),
         KPY_VEC(I, Kind::Real, B_B, 3, false, "[T] field, B"), KPY_SCALAR(I, Kind::U8, B_valid, "1 valid field"),
         KPY_VEC(I, Kind::U8, avail, FSW_MAX_MTQ, true, "(num_mtq) 0 available, 1 unavailable")},
        {KPY_VEC(O, Kind::Real, m_cmd, FSW_MAX_MTQ, true, "[A*m^2] rod dipoles"),
         KPY_VEC(O, Kind::Real, duty, FSW_MAX_MTQ, true, "[-] rod duties"),
         KPY_VEC(O, Kind::Real, m_ach_B, 3, false, "[A*m^2] achieved dipole"),
         KPY_VEC(O, Kind::Real, tau_ach_B, 3, false, "[N*m] achieved torque"),
         KPY_VEC(O, Kind::Real, tau_par_B, 3, false, "[N*m] unachievable part (along B)"),
         KPY_SCALAR(O, Kind::Real, scale, "[-]"), KPY_SCALAR(O, Kind::Int, rank, "rank of the rod set")},
        ready_only<FswMtqMapState>()});
  }
  {
    using I = FswRwBiasIn;
    using O = FswRwBiasOut;
    bind_algorithm(m, Spec<FswRwBiasConfig, FswRwBiasState, I, O>{
        "RwBias", "Wheel speed biasing away from zero crossings (docs/fsw/rw_bias.md)", KPY_FNS(rw_bias), rw_bias_config(),
        {KPY_RW_SPEEDS(I),
         KPY_RW_MASK(I, avail)},
        {KPY_RW_VEC(O, Omega_des, "[rad/s] desired speeds"),
         KPY_VEC(O, Kind::U8, in_band, RW_CAP, true, "in the keep-out band"),
         KPY_VEC(O, Kind::U8, unavoidable, RW_CAP, true, "crossing cannot be avoided"),
         KPY_SCALAR(O, Kind::U8, crossing_unavoidable, "any unavoidable"),
         KPY_SCALAR(O, Kind::Real, lambda_norm, "[rad/s] null-space step"),
         KPY_SCALAR(O, Kind::Int, nullity, "null-space dimension")},
        ready_only<FswRwBiasState>()});
  }
  {
    using I = FswRwNullIn;
    using O = FswRwNullOut;
    bind_algorithm(m, Spec<FswRwNullConfig, FswRwNullState, I, O>{
        "RwNull", "Reaction-wheel null motion toward desired speeds (docs/fsw/rw_null.md)", KPY_FNS(rw_null), rw_null_config(),
        {KPY_RW_VEC(I, u_s, "[N*m] (num_rw) mapped torques"),
         KPY_RW_SPEEDS(I),
         KPY_RW_VEC(I, Omega_des, "[rad/s] (num_rw) desired speeds"),
         KPY_RW_MASK(I, avail)},
        {KPY_RW_VEC(O, u_s, "[N*m] torques with the null motion"),
         KPY_SCALAR(O, Kind::Real, kappa, "[-] scale of the null torque")},
        ready_only<FswRwNullState>()});
  }
  {
    using I = FswRwNullRegenIn;
    using O = FswRwNullRegenOut;
    bind_algorithm(m, Spec<FswRwNullRegenConfig, FswRwNullRegenState, I, O>{
        "RwNullRegen", "Null motion for power (docs/fsw/rw_null_regen.md)", KPY_FNS(rw_null_regen), rw_null_regen_config(),
        {KPY_RW_VEC(I, u_s, "[N*m] (num_rw) mapped torques"),
         KPY_RW_SPEEDS(I),
         KPY_RW_MASK(I, avail)},
        {KPY_RW_VEC(O, u_s, "[N*m] torques with the null motion"),
         KPY_SCALAR(O, Kind::Real, power, "[W] mechanical power sum u Omega")},
        ready_only<FswRwNullRegenState>()});
  }
  {
    using I = FswRwSpeedFilterIn;
    using O = FswRwSpeedFilterOut;
    bind_algorithm(m, Spec<FswRwSpeedFilterConfig, FswRwSpeedFilterState, I, O>{
        "RwSpeedFilter", "Tachometer screening: outliers, NaN, stale and torque-inconsistent readings "
                         "(docs/fsw/rw_speed_filter.md)",
        KPY_FNS(rw_speed_filter),
        rw_speed_filter_config(),
        {KPY_RW_VEC(I, Omega_meas, "[rad/s] (num_rw) measured speeds"),
         KPY_RW_MASK(I, avail),
         KPY_SCALAR(I, Kind::U64, t_ns, "[ns]"),
         KPY_RW_VEC(I, u_applied, "[N*m] (num_rw) torques applied last cycle"),
         KPY_SCALAR(I, Kind::U8, u_valid, "1 when u_applied is known")},
        {KPY_RW_VEC(O, Omega, "[rad/s] screened speeds"),
         KPY_VEC(O, Kind::U8, avail, RW_CAP, true, "availability after screening"),
         KPY_SCALAR(O, Kind::U64, rejected, "bit i: wheel i's sample rejected"),
         KPY_SCALAR(O, Kind::U64, failed, "bit i: wheel i failed"),
         KPY_SCALAR(O, Kind::U64, latched, "bit i: wheel i failed for good")},
        ready_only<FswRwSpeedFilterState>()});
  }
  {
    using I = FswRwVoltIn;
    using O = FswRwVoltOut;
    bind_algorithm(m, Spec<FswRwVoltConfig, FswRwVoltState, I, O>{
        "RwVolt", "Wheel motor voltages from torques (docs/fsw/rw_volt.md)", KPY_FNS(rw_volt), rw_volt_config(),
        {KPY_RW_VEC(I, u_s, "[N*m] (num_rw) torques"),
         KPY_RW_SPEEDS(I),
         KPY_RW_MASK(I, avail),
         KPY_SCALAR(I, Kind::U64, t_ns, "[ns]"), KPY_SCALAR(I, Kind::Int, has_Omega, "1 when Omega is measured")},
        {KPY_RW_VEC(O, V, "[V] motor voltages"),
         KPY_SCALAR(O, Kind::U64, fault, "bit i: wheel i's rate gate tripped")},
        ready_only<FswRwVoltState>()});
  }
  {
    using I = FswThrMapIn;
    using O = FswThrMapOut;
    bind_algorithm(m, Spec<FswThrMapConfig, FswThrMapState, I, O>{
        "ThrMap", "Thruster force mapping, non-negative least squares (docs/fsw/thr_map.md)", KPY_FNS(thr_map), thr_map_config(),
        {KPY_VEC(I, Kind::Real, Lr_B, 3, false, "[N*m] requested torque"),
         KPY_VEC(I, Kind::Real, r_CoM_B, 3, false, "[m] centre of mass, B"),
         KPY_VEC(I, Kind::U8, avail, THR_CAP, true, "(num_thr) 0 available, 1 unavailable")},
        {KPY_VEC(O, Kind::Real, F, THR_CAP, true, "[N] thruster forces")}, ready_only<FswThrMapState>()});
  }
  {
    using I = FswThrMomentumIn;
    using O = FswThrMomentumOut;
    bind_algorithm(m, Spec<FswThrMomentumConfig, FswThrMomentumState, I, O>{
        "ThrMomentum", "Wheel momentum dumping with thrusters (docs/fsw/thr_momentum.md)", KPY_FNS(thr_momentum), thr_momentum_config(),
        {KPY_SCALAR(I, Kind::U64, t_ns, "[ns]"),
         KPY_RW_SPEEDS(I),
         KPY_RW_MASK(I, avail),
         KPY_VEC(I, Kind::Real, t_on_prev, THR_CAP, true, "[s] (num_thr) last cycle's on-times"),
         KPY_SCALAR(I, Kind::U8, enable, "1 dumping on"), KPY_SCALAR(I, Kind::U8, force_dump, "1 dump now")},
        {KPY_VEC(O, Kind::Real, L_thr_B, 3, false, "[N*m] torque request for the thrusters"),
         KPY_SCALAR(O, Kind::Int, phase, "0 IDLE, PULSE, COAST"),
         KPY_VEC(O, Kind::Real, dH_rem_B, 3, false, "[N*m*s] momentum not yet commanded"),
         KPY_VEC(O, Kind::Real, h_w_B, 3, false, "[N*m*s] wheel momentum"),
         KPY_SCALAR(O, Kind::Real, h_norm, "[N*m*s]"), KPY_SCALAR(O, Kind::U32, dumps, "dumps completed"),
         KPY_SCALAR(O, Kind::Real, t_dump, "[s]"), KPY_SCALAR(O, Kind::Real, prop_dump, "[kg]"),
         KPY_SCALAR(O, Kind::Real, prop_total, "[kg]"), KPY_VEC(O, Kind::Real, dH_B, 3, false, "[N*m*s]"),
         KPY_SCALAR(O, Kind::U32, aborts, ""), KPY_SCALAR(O, Kind::U32, pulses, "")},
        ready_only<FswThrMomentumState>()});
  }
  bind_algorithm(m, Spec<FswThrPulseRemConfig, FswThrPulseRemState, FswThrPulseRemIn, FswThrPulseRemOut>{
      "ThrPulseRem", "Thruster pulsing with remainder tracking (docs/fsw/thr_pulse_rem.md)", KPY_FNS(thr_pulse_rem), thr_pulse_rem_config(),
      pulse_in<FswThrPulseRemIn>(), pulse_out<FswThrPulseRemOut>(), ready_common<FswThrPulseRemState>()});
  bind_algorithm(m, Spec<FswThrPulseSchmittConfig, FswThrPulseSchmittState, FswThrPulseSchmittIn,
                         FswThrPulseSchmittOut>{
      "ThrPulseSchmitt", "Thruster pulsing with a Schmitt trigger (docs/fsw/thr_pulse_schmitt.md)",
      KPY_FNS(thr_pulse_schmitt), thr_pulse_schmitt_config(), pulse_in<FswThrPulseSchmittIn>(),
      pulse_out<FswThrPulseSchmittOut>(), ready_common<FswThrPulseSchmittState>()});
  bind_algorithm(m, Spec<FswThrPulseRoundConfig, FswThrPulseRoundState, FswThrPulseRoundIn, FswThrPulseRoundOut>{
      "ThrPulseRound", "Thruster pulsing by rounding (docs/fsw/thr_pulse_round.md)", KPY_FNS(thr_pulse_round), thr_pulse_round_config(),
      pulse_in<FswThrPulseRoundIn>(), pulse_out<FswThrPulseRoundOut>(), ready_common<FswThrPulseRoundState>()});

  bind_fsw_acs(m);
}

}  // namespace kpy

// kestrel.fsw.Acs: the flight application fsw_acs as a whole (docs/python.md,
// "Flight algorithms"): its configuration (every module config nested under
// its name, e.g. "mrp_fb.K"), the geometry helper, check/init/reset and one
// cycle: sensor message (+ command message) -> actuator and health messages.
#include "fsw_field.h"

#include <memory>

namespace kpy {

namespace {

struct Acs {
  FswAcsConfig cfg{};
  FswAcsState st{};
  FswAcsConfig init_cfg{};  // as Algorithm in fsw_py.cpp: counts frozen, edits refused until init()
  bool inited = false;
};

std::vector<Field<FswAcsConfig>> acs_config()
{
  using C = FswAcsConfig;
  std::vector<Field<C>> v = {
      KPY_SCALAR(C, Kind::Int, initial_mode, "AcsMode after init"),
      KPY_SCALAR(C, Kind::Int, initial_actuation, "AcsActuation after init"),
      KPY_SCALAR(C, Kind::Int, use_lpf, "0/1: low-pass filter Lr"),
      KPY_SCALAR(C, Kind::Int, has_wheels, "0/1"),
      KPY_SCALAR(C, Kind::Int, use_speed_filter, "0/1: screen the tachometers"),
      KPY_SCALAR(C, Kind::Int, use_null, "0/1: null motion toward Omega_des"),
      KPY_RW_VEC(C, Omega_des, "[rad/s] (num_rw) desired wheel speeds"),
      KPY_SCALAR(C, Kind::Int, use_volt, "0/1: also compute motor voltages"),
      KPY_SCALAR(C, Kind::Int, has_thrusters, "0/1"),
      KPY_SCALAR(C, Kind::Int, pulser, "0 remainder, 1 Schmitt"),
      KPY_SCALAR(C, Kind::Int, has_mtq, "0/1"),
      KPY_SCALAR(C, Kind::Int, detumble_exit_mode, "AcsMode once detumbled; -1 stay"),
      KPY_SCALAR(C, Kind::Int, has_orbit, "0/1"),
      KPY_SCALAR(C, Kind::Int, initial_policy, "AcsPolicy after init"),
      KPY_SCALAR(C, Kind::Int, use_thr_mom, "0/1: THRUSTERS policy available"),
      KPY_SCALAR(C, Kind::Int, use_mtq_desat, "0/1: MAGNETORQUERS policy available"),
      KPY_SCALAR(C, Kind::Int, use_bias, "0/1: rw_bias chooses the desired speeds")};
  append(v, nest("css", &C::css, css_sun_config()));
  append(v, nest("sunsafe", &C::sunsafe, guid_sunsafe_config()));
  append(v, nest("inertial", &C::inertial, guid_inertial_config()));
  append(v, nest("track", &C::track, att_track_config()));
  append(v, nest("mrp_fb", &C::mrp_fb, mrp_fb_config()));
  append(v, nest("lpf", &C::lpf, trq_lpf_config()));
  append(v, nest("speed_filter", &C::speed_filter, rw_speed_filter_config()));
  append(v, nest("rw_map", &C::rw_map, rw_map_config()));
  append(v, nest("rw_null", &C::rw_null, rw_null_config()));
  append(v, nest("rw_sat", &C::rw_sat, rw_sat_config()));
  append(v, nest("rw_volt", &C::rw_volt, rw_volt_config()));
  append(v, nest("thr_map", &C::thr_map, thr_map_config()));
  append(v, nest("pulse_rem", &C::pulse_rem, thr_pulse_rem_config()));
  append(v, nest("pulse_schmitt", &C::pulse_schmitt, thr_pulse_schmitt_config()));
  append(v, nest("mtq_map", &C::mtq_map, mtq_map_config()));
  append(v, nest("bdot", &C::bdot, bdot_config()));
  append(v, nest("orbit", &C::orbit, guid_orbit_config()));
  append(v, nest("thr_mom", &C::thr_mom, thr_momentum_config()));
  append(v, nest("mtq_desat", &C::mtq_desat, mtq_desat_config()));
  append(v, nest("rw_bias", &C::rw_bias, rw_bias_config()));
  return v;
}

std::vector<Field<FswAcsGeometry>> geometry_fields()
{
  using G = FswAcsGeometry;
  return {KPY_SCALAR(G, Kind::Int, num_rw, "0..MAX_RW"),
          KPY_MAT(G, gs_hat_B, FSW_MAX_RW, 3, true, "(num_rw, 3) spin axes"),
          KPY_RW_VEC(G, J_s, "[kg*m^2] (num_rw)"),
          KPY_RW_VEC(G, u_max, "[N*m] (num_rw)"),
          KPY_SCALAR(G, Kind::Int, num_thr, "0..MAX_THR"),
          KPY_MAT(G, r_thr_B, FSW_MAX_THR, 3, true, "[m] (num_thr, 3)"),
          KPY_MAT(G, gt_hat_B, FSW_MAX_THR, 3, true, "(num_thr, 3)"),
          KPY_VEC(G, Kind::Real, F_max, THR_CAP, true, "[N] (num_thr)"),
          KPY_SCALAR(G, Kind::Int, num_mtq, "0..MAX_MTQ"),
          KPY_MAT(G, mtq_axis_B, FSW_MAX_MTQ, 3, true, "(num_mtq, 3)"),
          KPY_VEC(G, Kind::Real, mtq_m_max, FSW_MAX_MTQ, true, "[A*m^2] (num_mtq)")};
}

}  // namespace

// (fsw_field.h: also the Python FSW's messages, loop_py.cpp)
std::vector<Field<FswAcsSensorMsg>> sensor_fields()
{
  using S = FswAcsSensorMsg;
  return {KPY_SCALAR(S, Kind::U64, t_ns, "[ns]"), KPY_VEC(S, Kind::Real, sigma_BN, 3, false, "[-] attitude"),
          KPY_SCALAR(S, Kind::U8, att_valid, "1 valid attitude"),
          KPY_VEC(S, Kind::Real, omega_BN_B, 3, false, "[rad/s] body rate"),
          KPY_VEC(S, Kind::Real, css, FSW_MAX_CSS, true, "CSS readings"),
          KPY_VEC(S, Kind::U8, css_avail, FSW_MAX_CSS, true, "0 available, 1 unavailable"),
          KPY_RW_VEC(S, Omega, "[rad/s] wheel speeds"),
          KPY_RW_MASK(S, rw_avail),
          KPY_VEC(S, Kind::Real, r_CoM_B, 3, false, "[m] centre of mass"),
          KPY_VEC(S, Kind::U8, thr_avail, THR_CAP, true, "0 available, 1 unavailable"),
          KPY_VEC(S, Kind::Real, B_B, 3, false, "[T] magnetic field"), KPY_SCALAR(S, Kind::U8, mag_valid, ""),
          KPY_VEC(S, Kind::Real, r_N, 3, false, "[m] position"), KPY_VEC(S, Kind::Real, v_N, 3, false, "[m/s]"),
          KPY_SCALAR(S, Kind::U8, orbit_valid, "")};
}

std::vector<Field<FswAcsCmdMsg>> cmd_fields()
{
  using M = FswAcsCmdMsg;
  return {KPY_SCALAR(M, Kind::Int, mode, "AcsMode requested (absent: the one last commanded)"),
          KPY_SCALAR(M, Kind::Int, actuation, "AcsActuation requested (absent: the one in force)"),
          KPY_SCALAR(M, Kind::U8, set_ref, "1: apply sigma_R0N"),
          KPY_VEC(M, Kind::Real, sigma_R0N, 3, false, "[-] inertial reference"),
          KPY_SCALAR(M, Kind::U8, set_gains, "1: apply K, P"), KPY_SCALAR(M, Kind::Real, K, "[N*m]"),
          KPY_SCALAR(M, Kind::Real, P, "[N*m*s]"), KPY_SCALAR(M, Kind::U8, set_policy, "1: apply policy"),
          KPY_SCALAR(M, Kind::Int, policy, "AcsPolicy")};
}

std::vector<Field<FswAcsActuatorMsg>> actuator_fields()
{
  using A = FswAcsActuatorMsg;
  return {KPY_VEC(A, Kind::Real, Lr_B, 3, false, "[N*m] control torque"),
          KPY_RW_VEC(A, u_s, "[N*m] wheel torques"),
          KPY_RW_VEC(A, V, "[V] wheel voltages"),
          KPY_VEC(A, Kind::Real, F, THR_CAP, true, "[N] thruster forces"),
          KPY_VEC(A, Kind::Real, t_on, THR_CAP, true, "[s] thruster on-times"),
          KPY_SCALAR(A, Kind::U8, wheels_active, ""), KPY_SCALAR(A, Kind::U8, thrusters_active, ""),
          KPY_VEC(A, Kind::Real, m_cmd, FSW_MAX_MTQ, true, "[A*m^2] rod dipoles"),
          KPY_SCALAR(A, Kind::U8, mtq_active, "")};
}

namespace {

std::vector<Field<FswAcsHealthMsg>> health_fields()
{
  using H = FswAcsHealthMsg;
  return {KPY_SCALAR(H, Kind::Int, status, "cycle status"), KPY_SCALAR(H, Kind::Int, mode, "AcsMode"),
          KPY_SCALAR(H, Kind::Int, actuation, ""), KPY_SCALAR(H, Kind::U8, safe_output, ""),
          KPY_SCALAR(H, Kind::U32, cycles, ""), KPY_SCALAR(H, Kind::U32, mode_changes, ""),
          KPY_VEC(H, Kind::Int, stage_status, FSW_ACS_NUM_STAGES, false, "status per stage (stage_name(i))"),
          KPY_VEC(H, Kind::Real, sigma_BR, 3, false, "[-]"), KPY_VEC(H, Kind::Real, omega_BR_B, 3, false, "[rad/s]"),
          KPY_SCALAR(H, Kind::Real, att_err_angle, "[rad]"), KPY_SCALAR(H, Kind::Real, sun_angle_err, "[rad]"),
          KPY_VEC(H, Kind::Real, sun_hat_B, 3, false, ""), KPY_SCALAR(H, Kind::U8, sun_valid, ""),
          KPY_SCALAR(H, Kind::U8, num_lit, ""), KPY_SCALAR(H, Kind::U64, rw_failed, "bit mask"),
          KPY_SCALAR(H, Kind::U64, rw_latched, "bit mask"), KPY_SCALAR(H, Kind::Int, policy, "AcsPolicy"),
          KPY_SCALAR(H, Kind::U8, detumbled, ""), KPY_SCALAR(H, Kind::U8, dump_phase, ""),
          KPY_VEC(H, Kind::Real, h_w_B, 3, false, "[N*m*s]"), KPY_SCALAR(H, Kind::Real, rate_est, "[rad/s]"),
          KPY_VEC(H, Kind::Real, tau_mtq_B, 3, false, "[N*m]"), KPY_SCALAR(H, Kind::U32, dumps, ""),
          KPY_SCALAR(H, Kind::Real, prop_used, "[kg]")};
}

void int_enum(py::module_& m, const char* name, std::vector<std::pair<const char*, int>> members)
{
  py::list l;
  for (const auto& p : members) l.append(py::make_tuple(p.first, p.second));
  m.attr(name) = py::module_::import("enum").attr("IntEnum")(name, l, py::arg("module") = "kestrel.fsw");
}

}  // namespace

void bind_fsw_acs(py::module_& m)
{
  int_enum(m, "AcsMode", {{"SUN_SAFE", FSW_ACS_MODE_SUN_SAFE}, {"INERTIAL", FSW_ACS_MODE_INERTIAL},
                          {"DETUMBLE", FSW_ACS_MODE_DETUMBLE}, {"NADIR", FSW_ACS_MODE_NADIR}});
  int_enum(m, "AcsActuation", {{"WHEELS", FSW_ACS_ACT_WHEELS}, {"THRUSTERS", FSW_ACS_ACT_THRUSTERS}});
  int_enum(m, "AcsPolicy", {{"NONE", FSW_ACS_MOM_NONE}, {"THRUSTERS", FSW_ACS_MOM_THRUSTERS},
                            {"MAGNETORQUERS", FSW_ACS_MOM_MAGNETORQUERS}});
  m.def("stage_name", [](int s) { return std::string(fsw_acs_stage_name(s)); },
        "stage_name(stage: int) -> str: the fsw_acs stage of health['stage_status'][stage], e.g. 'rw_map'");
  auto cf = std::make_shared<const std::vector<Field<FswAcsConfig>>>(acs_config());
  auto gf = std::make_shared<const std::vector<Field<FswAcsGeometry>>>(geometry_fields());
  auto sf = std::make_shared<const std::vector<Field<FswAcsSensorMsg>>>(sensor_fields());
  auto mf = std::make_shared<const std::vector<Field<FswAcsCmdMsg>>>(cmd_fields());
  auto af = std::make_shared<const std::vector<Field<FswAcsActuatorMsg>>>(actuator_fields());
  auto hf = std::make_shared<const std::vector<Field<FswAcsHealthMsg>>>(health_fields());
  auto config_field = [cf](const std::string& k) -> const Field<FswAcsConfig>& {
    const Field<FswAcsConfig>* f = find_field(*cf, k);
    if (f == nullptr) throw py::key_error("Acs: no config field '" + k + "' (Acs.fields lists them)");
    return *f;
  };
  auto refuse = [](const char* what, FswStatus s, const char* bad) {
    raise_config_error(std::string("Acs.") + what, s, bad == nullptr ? "" : bad, "");
  };
  py::class_<Acs>(m, "Acs",
                  "The flight application fsw_acs as a whole (docs/fsw/fsw_acs.md): one configuration holding every "
                  "module's, named 'module.field' (e.g. 'mrp_fb.K', 'rw_map.num_rw'; Acs.fields lists them), "
                  "set_geometry() for the actuator geometry, check()/init()/reset(), and cycle(): sensor message "
                  "(+ optional command message) -> (Status, actuator dict, health dict).")
      .def(py::init([cf](const py::kwargs& kw) {
             auto a = std::make_unique<Acs>();
             py::dict d;
             for (auto kv : kw) d[kv.first] = kv.second;
             from_kwargs(a->cfg, *cf, d, "config field");
             return a;
           }),
           "A zeroed configuration; keyword arguments set config fields (**{'mrp_fb.K': 0.5})")
      .def_static(
          "from_scenario",
          [](const PyScenario& s) {
            auto a = std::make_unique<Acs>();
            try {
              a->cfg = harness::fsw_acs_config_of(s.sc);
            } catch (const harness::ScenarioError& e) {
              throw py::value_error(e.what());
            }
            return a;
          },
          py::arg("scenario"),
          "from_scenario(scenario) -> Acs: the configuration a run of the scenario gives its C FSW "
          "(fsw_acs_config_of), not yet init()")
      .def_property_readonly_static("fields", [cf](const py::object&) {
        std::vector<std::string> v;
        for (const auto& f : *cf) v.push_back(f.name);
        return v;
      })
      .def("get", [config_field](Acs& a, const std::string& k) { return get_field(a.cfg, config_field(k)); },
           "get(self, name: str) -> float | int | numpy.ndarray: a config field")
      .def(
          "set", [config_field](Acs& a, const std::string& k, const py::handle& v) {
            set_config(a.cfg, config_field(k), v, a.inited, "Acs");
          },
          "set(self, name: str, value) -> None: a config field; counts are fixed after init()")
      .def(
          "set_geometry",
          [gf](Acs& a, const py::kwargs& kw) {
            FswAcsGeometry g{};
            from_kwargs(g, *gf, kw, "geometry field");
            FswAcsConfig next = a.cfg;
            const FswStatus s = fsw_acs_config_set_geometry(&next, &g);
            if (fsw_status_is_error(s))
              raise_config_error("Acs.set_geometry", s, g.num_rw < 0 || g.num_rw > FSW_MAX_RW ? "num_rw" : "num_thr", "");
            if (a.inited && (next.rw_map.num_rw != a.cfg.rw_map.num_rw || next.thr_map.num_thr != a.cfg.thr_map.num_thr))
              throw py::value_error("Acs.set_geometry: the counts are fixed after init(); make a new Acs");
            a.cfg = next;
          },
          "set_geometry(self, **geometry) -> None: fsw_acs_config_set_geometry (num_rw, gs_hat_B, J_s, u_max, "
          "num_thr, r_thr_B, gt_hat_B, F_max, num_mtq, mtq_axis_B, mtq_m_max) into every module config")
      .def_property_readonly("config", [cf](Acs& a) { return to_dict(a.cfg, *cf); }, "every config field, as a dict")
      .def(
          "check",
          [refuse](Acs& a) -> py::object {
            const char* bad = nullptr;
            const FswStatus s = fsw_acs_check(&a.cfg, &bad);
            if (fsw_status_is_error(s)) refuse("check", s, bad);
            return status_obj(s);
          },
          "check(self) -> Status: fsw_acs_check; ConfigError with .field = the C check's bad field")
      .def(
          "init",
          [refuse](Acs& a) -> py::object {
            const char* bad = nullptr;
            const FswStatus s = fsw_acs_init(&a.st, &a.cfg, &bad);
            a.inited = !fsw_status_is_error(s);
            if (!a.inited) refuse("init", s, bad);
            a.init_cfg = a.cfg;
            return status_obj(s);
          },
          "init(self) -> Status: check and init every module used; ConfigError naming the field")
      .def("reset", [](Acs& a) { fsw_acs_reset(&a.st, &a.cfg); }, "reset(self) -> None: back to the post-init mode")
      .def_property_readonly("initialized", [](Acs& a) { return a.inited; })
      .def(
          "cycle",
          [cf, sf, mf, af, hf](Acs& a, const py::object& cmd, const py::kwargs& kw) {
            if (a.inited) {
              const std::string changed = changed_fields(a.cfg, a.init_cfg, *cf);
              if (!changed.empty())
                throw py::value_error("Acs.cycle: the configuration changed after init() (" + changed +
                                      "): call init() again");
            }
            FswAcsSensorMsg sens{};
            from_kwargs(sens, *sf, kw, "sensor field");
            FswAcsCmdMsg c{};
            const bool has_cmd = !cmd.is_none();
            if (has_cmd) {
              c.mode = a.st.cmd_mode;  // absent: the mode last commanded (no change)
              c.actuation = a.st.actuation;
              from_kwargs(c, *mf, py::dict(cmd), "command field");
            }
            FswAcsActuatorMsg act{};
            FswAcsHealthMsg h{};
            const FswStatus s = fsw_acs_cycle(&a.st, &a.cfg, &sens, has_cmd ? &c : nullptr, &act, &h);
            return py::make_tuple(status_obj(s), to_dict(act, *af), to_dict(h, *hf));
          },
          py::arg("cmd") = py::none(),
          "cycle(self, cmd: dict | None = None, **sensors) -> tuple[Status, dict, dict]: one fsw_acs_cycle. "
          "Sensor message fields by keyword (t_ns, sigma_BN, att_valid, omega_BN_B, css, css_avail, Omega, "
          "rw_avail, r_CoM_B, thr_avail, B_B, mag_valid, r_N, v_N, orbit_valid; absent = 0); cmd: the command "
          "message (mode, actuation: absent keeps them; set_ref + sigma_R0N, set_gains + K, P, set_policy + "
          "policy).  Returns (status, actuator message, health message).");
}

}  // namespace kpy

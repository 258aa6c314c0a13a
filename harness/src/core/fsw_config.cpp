// fsw_config.cpp: the scenario's fsw/wheels/thrusters/sensors.css keys mapped
// onto FswAcsConfig.  fsw_real may be float: every value is converted here.
#include "core/fsw_config.h"
#include "core/convert.h"

#include <cmath>
#include <cstring>

#include "core/build_error.h"
#include "harness/core/vehicle_geometry.h"

namespace harness {

namespace {

fsw_real R(double x) { return static_cast<fsw_real>(x); }

// FswAcsConfig field (prefix, as fsw_acs_check names it) -> scenario key.
struct FieldKey {
  const char* field_prefix;
  const char* key;
};
constexpr FieldKey kFieldKeys[] = {
    {"css", "sensors.css"},           {"sunsafe", "fsw.sun_safe"},
    {"inertial", "fsw.inertial"},     {"track", "fsw.inertial"},
    {"mrp_fb", "fsw.mrp_fb"},         {"lpf", "fsw"},
    {"use_lpf", "fsw"},               {"rw_map", "fsw.rw_map"},
    {"rw_null", "fsw.rw_null"},       {"use_null", "fsw.rw_null"},
    {"Omega_des", "fsw.rw_null.Omega_des"}, {"rw_sat", "wheels"},
    {"speed_filter", "fsw.speed_filter"}, {"use_speed_filter", "fsw.speed_filter"},
    {"rw_volt", "wheels"},            {"has_wheels", "wheels"},
    {"thr_map", "thrusters"},         {"has_thrusters", "thrusters"},
    {"pulse", "fsw.thr_pulse"},       {"pulser", "fsw.thr_pulse"},
    {"initial_mode", "fsw.mode"},     {"initial_actuation", "fsw.actuation"},
    {"has_mtq", "fsw.magnetorquers"}, {"mtq_map", "fsw.magnetorquers"},
    {"bdot", "fsw.bdot"},             {"detumble_exit_mode", "fsw.bdot.exit_mode"},
    {"has_orbit", "fsw.nadir"},       {"orbit", "fsw.nadir"},
    {"initial_policy", "fsw.momentum.policy"}, {"use_thr_mom", "fsw.momentum"},
    {"thr_mom", "fsw.momentum"},      {"use_mtq_desat", "fsw.momentum"},
    {"mtq_desat", "fsw.momentum"},    {"use_bias", "fsw.rw_bias"},
    {"rw_bias", "fsw.rw_bias"},
};

}  // namespace

std::string scenario_key_of_fsw_field(const std::string& field)
{
  for (const FieldKey& fk : kFieldKeys)
    if (field.rfind(fk.field_prefix, 0) == 0) return fk.key;
  return "fsw";
}

namespace {

// The FSW inertia: the scenario's fsw.mrp_fb.inertia, else the plant's at t0
// moved from B to the mass centre C (parallel axis).
Eigen::Matrix3d fsw_inertia(const Scenario& sc, const sim::MassProps& mp)
{
  const Eigen::Vector3d c = mp.c_B;
  const Eigen::Matrix3d I_C =
      mp.I_sc_B - mp.m_sc * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return sc.fsw.mrp_fb.inertia ? *sc.fsw.mrp_fb.inertia : I_C;
}

// Coarse sun sensors: the scenario's, or the six ideal cube-face sensors.
void set_css(const Scenario& sc, FswSetup& out)
{
  FswAcsConfig& a = out.cfg;
  out.ideal_css = sc.sensors.css.normals_B.empty();
  if (out.ideal_css) {
    a.css.num_css = kIdealCss;
    for (int i = 0; i < kIdealCss; ++i) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n(i / 2) = (i % 2 == 0) ? 1.0 : -1.0;
      out.ideal_normals[static_cast<size_t>(i)] = n;
      put3(a.css.n_hat_B[i], n);
      a.css.scale[i] = R(1.0);
    }
    a.css.lit_threshold = R(0.0);
    return;
  }
  a.css.num_css = static_cast<int>(sc.sensors.css.normals_B.size());
  a.css.lit_threshold = R(sc.fsw.css_lit_threshold);
  for (size_t i = 0; i < sc.sensors.css.normals_B.size(); ++i) {
    put3(a.css.n_hat_B[i], sc.sensors.css.normals_B[i]);
    a.css.scale[i] = R(sc.sensors.css.scale);
  }
}

// Sun-safe and inertial pointing.
void set_guidance(const Scenario& sc, FswAcsConfig& a)
{
  put3(a.sunsafe.s_cmd_B, sc.fsw.sun_axis_B);
  a.sunsafe.min_unit_mag = R(kSunMinUnitMag);
  a.sunsafe.small_angle = R(sc.fsw.sun_small_angle);
  put3(a.sunsafe.omega_search_B, sc.fsw.omega_search_B);
  a.sunsafe.sun_axis_spin_rate = 0;
  put3(a.inertial.sigma_R0N, sc.fsw.sigma_R0N);
}

// The control law (its wheel set comes with the geometry).
void set_control(const Scenario& sc, const Eigen::Matrix3d& I_fsw, FswAcsConfig& a)
{
  FswMrpFbConfig& mf = a.mrp_fb;
  mf.K = R(sc.fsw.mrp_fb.K);
  mf.P = R(sc.fsw.mrp_fb.P);
  mf.K_i = R(sc.fsw.mrp_fb.K_i);
  mf.integral_limit = R(sc.fsw.mrp_fb.integral_limit);
  mf.control_law_type = sc.fsw.mrp_fb.control_law;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) mf.I_B[r][k] = R(I_fsw(r, k));
  a.use_lpf = 0;
}

// Actuator geometry, given once: vehicle_geometry() forms it, fsw_geometry()
// gives the FSW's view and fsw_acs_config_set_geometry() writes the module
// copies (and has_wheels / has_thrusters from the counts).  ACS thrusters
// (acs: true) only: the main engine follows the burn schedule.
void set_geometry(const Scenario& sc, FswSetup& out)
{
  const VehicleGeometry g = vehicle_geometry(sc);
  if (g.acs_to_plant.size() > static_cast<size_t>(FSW_MAX_THR))
    throw config_error(sc, "thrusters", "at most " + std::to_string(FSW_MAX_THR) + " ACS thrusters (FSW_MAX_THR)");
  out.n_acs = static_cast<int>(g.acs_to_plant.size());
  for (size_t i = 0; i < g.acs_to_plant.size(); ++i) out.acs_to_plant[i] = g.acs_to_plant[i];
  const FswAcsGeometry geo = fsw_geometry(sc, g);
  if (fsw_acs_config_set_geometry(&out.cfg, &geo) != FSW_OK)
    throw config_error(sc, geo.num_rw > FSW_MAX_RW ? "wheels" : "thrusters",
                       "more wheels or thrusters than the FSW holds");
}

// Wheel chain: rw_map -> [rw_null] -> rw_sat (limits = the wheels' u_max).
void set_wheel_chain(const Scenario& sc, FswAcsConfig& a)
{
  const int n_rw = static_cast<int>(sc.wheels.size());
  a.rw_map.num_axes = 3;
  for (int r = 0; r < 3; ++r) a.rw_map.ctrl_axes_B[r][r] = 1;
  a.rw_map.mode = sc.fsw.rw_map == RwMapMode::Power ? FSW_RW_MAP_POWER : FSW_RW_MAP_MIN_NORM;
  a.rw_map.eps_P = R(sc.fsw.eps_P);
  a.use_null = sc.fsw.rw_null ? 1 : 0;
  a.rw_null.k_null = R(sc.fsw.k_null);
  a.rw_null.scale_to_fit = sc.fsw.rw_null_scale_to_fit ? 1 : 0;
  a.rw_sat.mode = FSW_RW_SAT_SCALE;
  a.use_speed_filter = sc.fsw.speed_filter ? 1 : 0;
  a.speed_filter.k_reject = static_cast<uint32_t>(sc.fsw.sf_k_reject);
  a.speed_filter.n_recover = static_cast<uint32_t>(sc.fsw.sf_n_recover);
  a.speed_filter.n_stale = static_cast<uint32_t>(sc.fsw.sf_n_stale);
  a.speed_filter.n_window = static_cast<uint32_t>(sc.fsw.sf_n_window);
  for (int i = 0; i < n_rw; ++i) {
    a.speed_filter.noise[i] = R(sc.fsw.sf_noise);
    a.speed_filter.resid_tol[i] = R(sc.fsw.sf_resid_tol);
  }
  for (int i = 0; i < n_rw; ++i)
    a.Omega_des[i] = i < static_cast<int>(sc.fsw.Omega_des.size()) ? R(sc.fsw.Omega_des[static_cast<size_t>(i)]) : 0;
}

// Thruster chain: map -> pulser.
void set_thruster_chain(const Scenario& sc, FswAcsConfig& a)
{
  for (int k = 0; k < 3; ++k) a.thr_map.control_axes_B[k][k] = R(1.0);
  a.thr_map.thr_force_sign = 1;
  a.thr_map.ang_err_thresh = R(0.0);
  a.thr_map.epsilon = R(0.0);
  a.thr_map.use_2nd_loop = 0;
  a.thr_map.mode = sc.fsw.thr_map == ThrMapMode::Nnls ? FSW_THR_MAP_NNLS : FSW_THR_MAP_MIN_NORM;
  a.pulser = sc.fsw.thr_pulse == ThrPulseMode::Schmitt ? FSW_ACS_PULSE_SCHMITT : FSW_ACS_PULSE_REMAINDER;
  a.pulse_rem.common.t_min = R(sc.fsw.thr_t_min);
  a.pulse_rem.common.base_thrust_state = 0;
  a.pulse_rem.common.init_off_pulse_on_time = R(0.0);
  a.pulse_schmitt.common.t_min = R(sc.fsw.thr_t_min);
  a.pulse_schmitt.level_on = R(sc.fsw.thr_level_on);
  a.pulse_schmitt.level_off = R(sc.fsw.thr_level_off);
  a.pulse_schmitt.common.base_thrust_state = 0;
  a.pulse_schmitt.common.init_off_pulse_on_time = R(0.0);
}

int acs_mode(FswMode m)
{
  switch (m) {
    case FswMode::SunSafe: return FSW_ACS_MODE_SUN_SAFE;
    case FswMode::Detumble: return FSW_ACS_MODE_DETUMBLE;
    case FswMode::Nadir: return FSW_ACS_MODE_NADIR;
    default: return FSW_ACS_MODE_INERTIAL;
  }
}

// The rods (DETUMBLE's B-dot) and the orbit guidance (NADIR).
void set_magnetic_and_orbit(const Scenario& sc, FswAcsConfig& a)
{
  const FswSpec& f = sc.fsw;
  a.mtq_map.duty_max = R(f.mtq_duty_max);
  a.bdot.variant = f.bdot_law == BdotLaw::Gyro ? FSW_BDOT_GYRO : FSW_BDOT_DERIV;
  a.bdot.k_bdot = R(f.bdot_k);
  a.bdot.normalize = f.bdot_normalize ? 1 : 0;
  a.bdot.tau_f = R(f.bdot_tau_f);
  a.bdot.max_missed = f.bdot_max_missed;
  for (int k = 0; k < 3; ++k) {
    // absent: the largest dipole the rods can make along each body axis
    double m = f.bdot_m_max(k);
    if (!(m > 0.0))
      for (const MagnetorquerSpec& r : sc.magnetorquers) m += r.m_max * std::fabs(r.axis_B(k)) * f.mtq_duty_max;
    a.bdot.m_max_B[k] = R(m);
  }
  a.bdot.omega_done = R(f.bdot_omega_done);
  a.bdot.omega_reenter = R(f.bdot_omega_reenter > 0.0 ? f.bdot_omega_reenter : 2.0 * f.bdot_omega_done);
  a.bdot.t_persist = R(f.bdot_t_persist);
  a.detumble_exit_mode = f.detumble_exit == FswMode::Detumble ? -1 : acs_mode(f.detumble_exit);
  a.has_orbit = sc.environment.mu > 0.0 ? 1 : 0;
  a.orbit.variant = f.orbit_frame == OrbitFrame::Velocity ? FSW_GUID_ORBIT_VELOCITY : FSW_GUID_ORBIT_NADIR;
  put3(a.orbit.sigma_BdR, f.sigma_BdR);
  a.orbit.mu = R(sc.environment.mu);
}

// Momentum management (fsw.momentum) and the wheels' bias speeds (fsw.rw_bias).
void set_momentum(const Scenario& sc, fsw_real fsw_period, FswAcsConfig& a)
{
  const FswSpec& f = sc.fsw;
  a.initial_policy = f.policy == MomentumPolicy::Thrusters       ? FSW_ACS_MOM_THRUSTERS
                     : f.policy == MomentumPolicy::Magnetorquers ? FSW_ACS_MOM_MAGNETORQUERS
                                                                 : FSW_ACS_MOM_NONE;
  a.use_thr_mom = f.policy == MomentumPolicy::Thrusters ? 1 : 0;
  a.thr_mom.h_upper = R(f.mom_h_upper);
  a.thr_mom.h_lower = R(f.mom_h_lower);
  a.thr_mom.L_dump = R(f.mom_L_dump);
  a.thr_mom.t_pulse_max = R(f.mom_t_pulse_max);
  a.thr_mom.t_min_pulse = R(f.mom_t_min_pulse);
  a.thr_mom.t_coast = R(f.mom_t_coast);
  a.thr_mom.dt_cycle = fsw_period;
  a.thr_mom.Isp = R(f.mom_Isp);
  a.use_mtq_desat = f.policy == MomentumPolicy::Magnetorquers ? 1 : 0;
  a.mtq_desat.k_desat = R(f.mom_k_desat);
  a.mtq_desat.tau_max = R(f.mom_tau_max);
  a.mtq_desat.h_deadband = R(f.mom_h_deadband);
  a.use_bias = f.rw_bias ? 1 : 0;
  for (size_t i = 0; i < f.Omega_bias.size() && i < static_cast<size_t>(FSW_MAX_RW); ++i)
    a.rw_bias.Omega_bias[i] = R(f.Omega_bias[i]);
  a.rw_bias.Omega_keepout = R(f.bias_keepout);
  a.rw_bias.Omega_hyst = R(f.bias_hyst);
}

// fsw_acs_check; a rejection names the scenario key of the bad field.
void check_config(const Scenario& sc, const FswAcsConfig& a)
{
  const char* bad = nullptr;
  const FswStatus s = fsw_acs_check(&a, &bad);
  if (s == FSW_OK) return;
  const std::string field = bad ? bad : "(unknown)";
  throw config_error(sc, scenario_key_of_fsw_field(field),
                     std::string("rejected by fsw_acs_check: field '") + field + "': " + fsw_status_name(s));
}

}  // namespace

FswSetup make_fsw_setup(const Scenario& sc, const sim::MassProps& mp)
{
  FswSetup out;
  FswAcsConfig& a = out.cfg;
  std::memset(&a, 0, sizeof a);
  a.initial_mode = acs_mode(sc.fsw.mode);
  a.initial_actuation = sc.fsw.actuation == Actuation::Wheels ? FSW_ACS_ACT_WHEELS : FSW_ACS_ACT_THRUSTERS;
  set_css(sc, out);
  set_guidance(sc, a);
  set_control(sc, fsw_inertia(sc, mp), a);
  set_geometry(sc, out);
  if (a.has_wheels) set_wheel_chain(sc, a);
  if (a.has_thrusters) set_thruster_chain(sc, a);
  const fsw_real fsw_period = R(sc.rates.dt * sc.rates.fsw_divisor);
  set_magnetic_and_orbit(sc, a);
  set_momentum(sc, fsw_period, a);
  check_config(sc, a);
  return out;
}

}  // namespace harness

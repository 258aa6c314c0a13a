// run.cpp: the closed loop.  Glue is explicit code copying fields between
// plain structs; unit conversions happen here, named, at the boundary.
//
// The flight software is the application layer fsw_acs (fsw/fsw_acs.h): one
// fsw_acs_cycle() per control period, fed a FswAcsSensorMsg built from the
// plant, its FswAcsActuatorMsg applied to the plant (wheel torques latched,
// thruster on-times commanded), its FswAcsHealthMsg recorded.
#include "harness/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "harness/outputs.h"
#include "sim/attitude.h"
#include "sim/environment.h"
#include "sim/propellant.h"
#include "sim/sensors.h"
#include "sim/spacecraft.h"
#include "sim/units.h"
#include "sim/vehicle.h"

extern "C" {
#include "fsw/fsw_acs.h"
}

#ifndef KESTREL_VERSION
#define KESTREL_VERSION "0.0.0"
#endif

namespace harness {

const char* version() { return KESTREL_VERSION; }

namespace {

constexpr int kMaxRw = sim::kMaxWheels;
constexpr int kMaxThr = sim::kMaxThrusters;
constexpr double kRadToDeg = 180.0 / sim::kPi;
constexpr double kRpmPerRadS = 1.0 / sim::kRadPerSecPerRpm;
// guid_sunsafe: |s_B| above which the Sun heading counts as valid [-]
constexpr double kSunMinUnitMag = 0.1;
// Without configured coarse sun sensors the FSW still needs a CSS set: six
// ideal sensors on the cube faces (readings max(0, n.s) computed exactly
// from truth, lit threshold 0).  For any Sun direction the lit faces span the
// directions where s has a component, so css_sun returns s exactly (3 lit:
// least squares on orthonormal normals; 2 or 1 lit: the documented
// fallbacks are exact for orthogonal normals).  This is the "ideal heading".
constexpr int kIdealCss = 6;

// ---- harness messages (plain structs) ----------------------------------------
struct TruthMsg {
  double sigma_BN[3];       // [-]
  double omega_BN_B[3];     // [rad/s]
  double r_BN_N[3];         // [m]
  double v_BN_N[3];         // [m/s]
  double r_CN_N[3];         // [m]   mass centre
  double v_CN_N[3];         // [m/s] mass centre
  double c_B[3];            // [m]   mass centre relative to B
  double m_sc;              // [kg]  total mass
  double m_prop;            // [kg]  propellant left (all tanks)
  double Omega[kMaxRw];     // [rad/s] wheel speeds rel. B
  double u_s[kMaxRw];       // [N*m]   motor torque held by the plant
  double F_thr[kMaxThr];    // [N]     thrust magnitude of each thruster now
};
// Sampled outputs of the gyro, star tracker and wheel tachometers, held
// between samples (written by the every-tick sampling task).  Frames: the
// gyro platform P and the star-tracker case C coincide with B (dcm_PB =
// dcm_CB = I), so omega_PN_P = omega_BN_B and sigma_CN = sigma_BN as measured.
struct SensorSampleMsg {
  double omega_PN_P[3];    // [rad/s] gyro output
  int64_t gyro_t_ns;       // [ns] time tag of the gyro sample
  uint8_t gyro_valid;      // [-] 1 once the gyro has sampled
  double sigma_CN[3];      // [-] star-tracker attitude (MRP, |sigma| <= 1)
  int64_t st_t_ns;         // [ns] time tag of the star-tracker sample
  uint8_t st_valid;        // [-] 1 if the latest star-tracker sample is valid (sampled, not Sun-excluded)
  double Omega[kMaxRw];    // [rad/s] tachometer wheel speeds
  int64_t tach_t_ns;       // [ns]
  uint8_t tach_valid;      // [-]
};
struct CssMsg {
  double y[FSW_MAX_CSS];  // [reading units] (num_css) coarse-sun-sensor outputs
};
struct SunHeadingMsg {
  double sun_B[3];  // [-] unit Sun heading in B (FSW css_sun estimate); 0 when no valid heading
  int valid;        // [-] 1 if sun_B holds a heading
  int num_lit;      // [-] lit coarse sun sensors
};
struct ThrCmdMsg {
  double T_on[kMaxThr];  // [s] on-time requests sent to the plant (plant thruster order)
};
struct MetricsMsg {
  double pointing_error;  // [rad]
  double H_C_N[3];        // [kg*m^2/s]
  double E_rot;           // [J]
  double dv_ng;           // [m/s] |accumulated non-gravitational velocity change| of C
  double orbit_e;         // [-]   osculating eccentricity (mu > 0)
  double orbit_r_p;       // [m]   osculating periapsis radius (mu > 0)
  double orbit_energy;    // [J/kg] specific orbital energy (mu > 0)
};

// 3-vector copy across the FSW boundary (fsw_real may be float or double).
template <class Out, class In>
void copy3(Out* out, const In* in)
{
  for (int i = 0; i < 3; ++i) out[i] = static_cast<Out>(in[i]);
}
template <class Out>
void put3(Out* out, const Eigen::Vector3d& v)
{
  for (int i = 0; i < 3; ++i) out[i] = static_cast<Out>(v(i));
}

Eigen::Vector3d ev(const double* p) { return Eigen::Vector3d(p[0], p[1], p[2]); }
fsw_real R(double x) { return static_cast<fsw_real>(x); }

// Principal angle of B relative to R from two MRPs, via quaternions.
double principal_angle(const Eigen::Vector3d& sigma_BN, const Eigen::Vector3d& sigma_RN)
{
  const Eigen::Vector4d b = sim::quaternion_from_sigma(sigma_BN), r = sim::quaternion_from_sigma(sigma_RN);
  // q_BR = q_BN (x) q_RN^-1: scalar part and vector norm
  const double q0 = b(0) * r(0) + b.tail<3>().dot(r.tail<3>());
  const Eigen::Vector3d qv = r(0) * b.tail<3>() - b(0) * r.tail<3>() - b.tail<3>().cross(r.tail<3>());
  return 2.0 * std::atan2(qv.norm(), std::fabs(q0));
}

// Truth thrust axis of a thruster with a misalignment of `delta` [rad]: the
// nominal axis d tilted by delta about a = unit(d x x_B) (or unit(d x y_B)
// when d is within 25 deg of x_B): d' = cos(delta) d + sin(delta) (a x d).
// For d = +z_B this tilts toward +x_B.
Eigen::Vector3d misaligned_axis(const Eigen::Vector3d& d, double delta)
{
  if (delta == 0.0) return d;
  Eigen::Vector3d a = d.cross(Eigen::Vector3d::UnitX());
  if (a.norm() < 0.42) a = d.cross(Eigen::Vector3d::UnitY());
  a.normalize();
  return (std::cos(delta) * d + std::sin(delta) * a.cross(d)).normalized();
}

// The scenario key a fsw_acs_check bad_field comes from.
std::string scenario_key_of(const std::string& f)
{
  auto starts = [&f](const char* p) { return f.rfind(p, 0) == 0; };
  if (starts("css")) return "sensors.css";
  if (starts("sunsafe")) return "fsw.sun_safe";
  if (starts("inertial")) return "fsw.inertial";
  if (starts("track")) return "fsw.inertial";
  if (starts("mrp_fb")) return "fsw.mrp_fb";
  if (starts("lpf") || starts("use_lpf")) return "fsw";
  if (starts("rw_map")) return "fsw.rw_map";
  if (starts("rw_null") || starts("use_null")) return "fsw.rw_null";
  if (starts("Omega_des")) return "fsw.rw_null.Omega_des";
  if (starts("rw_sat") || starts("rw_volt") || starts("has_wheels")) return "wheels";
  if (starts("thr_map") || starts("has_thrusters")) return "thrusters";
  if (starts("pulse") || starts("pulser")) return "fsw.thr_pulse";
  if (starts("initial_mode")) return "fsw.mode";
  if (starts("initial_actuation")) return "fsw.actuation";
  return "fsw";
}

ScenarioError config_error(const Scenario& sc, const std::string& key, const std::string& msg)
{
  ScenarioIssue is;
  is.file = sc.source_file.empty() ? "(scenario)" : sc.source_file;
  is.key = key;
  is.message = msg;
  // name the line of the key, or of its nearest written parent
  for (std::string k = key; !k.empty();) {
    auto it = sc.key_lines.find(k);
    if (it != sc.key_lines.end()) {
      is.line = it->second.first;
      is.column = it->second.second;
      break;
    }
    const size_t cut = k.find_last_of(".[");
    if (cut == std::string::npos) break;
    k = k.substr(0, cut);
  }
  return ScenarioError({is});
}

// Runs `make` (plant construction): an exception from the plant becomes a
// scenario error naming `key`, with the line of that key.
template <class F>
void built_by_plant(const Scenario& sc, const char* key, F&& make)
{
  try {
    make();
  } catch (const std::exception& e) {
    throw config_error(sc, key, std::string("rejected by the plant: ") + e.what());
  }
}

}  // namespace

struct Run::Impl {
  Scenario sc;
  // the plant: a Spacecraft (hub + wheels) or, with thrusters, a Vehicle
  std::unique_ptr<sim::Spacecraft> craft;
  std::unique_ptr<sim::Vehicle> veh;
  Scheduler sched;
  DataFlow flow;
  Recorder rec{"telemetry"};
  uint64_t tick = 0;
  uint64_t n_ticks = 0;
  double dt = 0.0;
  int64_t dt_ns = 0;
  int n_rw = 0;
  int n_thr = 0;       // plant thrusters (scenario order)
  int n_acs = 0;       // ACS thrusters (FSW order)
  std::array<int, FSW_MAX_THR> acs_to_plant{};  // FSW thruster index -> plant index
  int engine = -1;     // plant index of the burn engine, -1 without a burn
  int64_t burn_on_ns = 0, burn_off_ns = 0;  // [ns] burn window (start, start + duration)
  int n_tanks = 0;
  std::string failure;
  sim::WheelArray u_held{};  // Vehicle: wheel commands latched (the plant keeps them privately)

  // FSW application
  FswAcsConfig acs_cfg{};
  FswAcsState acs_st{};
  FswAcsHealthMsg last_health{};
  std::vector<sim::CoarseSunSensor> css;
  std::unique_ptr<sim::Gyro> gyro;                 // when sensors.gyro.enabled
  std::unique_ptr<sim::StarTracker> st;            // when sensors.star_tracker.enabled
  std::unique_ptr<sim::WheelTachometers> tach;     // when sensors.tachometer.enabled and wheels
  bool ideal_css = false;
  std::array<Eigen::Vector3d, kIdealCss> ideal_normals;

  // non-gravitational velocity change of C (trapezoid on gravity), burn book-keeping
  bool have_prev = false;
  Eigen::Vector3d r_prev = Eigen::Vector3d::Zero(), v_prev = Eigen::Vector3d::Zero();
  Eigen::Vector3d dv_ng = Eigen::Vector3d::Zero();
  struct Snap {
    bool set = false;
    double t = 0.0, m = 0.0;
    std::array<double, sim::kMaxTanks> m_p{};
    Eigen::Vector3d dv_ng = Eigen::Vector3d::Zero(), r = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  } burn_start, burn_end;
  double max_err_burn = 0.0;  // [rad]

  // channels
  Channel<TruthMsg>* truth = nullptr;
  Channel<MetricsMsg>* metrics = nullptr;

  explicit Impl(const Scenario& s) : sc(s), sched(s.tick_ns()) {}

  const sim::StateVector& x() const { return veh ? veh->state().sc : craft->state(); }
  sim::MassProps mass_props() const { return veh ? veh->mass_props() : craft->mass_props(); }
  sim::EnergyMomentum energy_momentum() const { return veh ? veh->energy_momentum() : craft->energy_momentum(); }
  double Omega(int i) const { return veh ? veh->Omega(i) : craft->Omega(i); }
  double u_s(int i) const { return veh ? u_held[static_cast<size_t>(i)] : craft->u_s(i); }
  void latch_wheels(const sim::WheelArray& u)
  {
    if (veh) {
      u_held = u;
      veh->latch_wheel_commands(u);
    } else {
      craft->latch_commands(u);
    }
  }
  sim::StepStatus step() { return veh ? veh->step(dt_ns) : craft->step(dt); }
  double m_prop(int k) const { return veh ? veh->m_prop(k) : 0.0; }

  void snap(Snap& s, double t, const TruthMsg& tr)
  {
    s.set = true;
    s.t = t;
    s.m = tr.m_sc;
    for (int k = 0; k < n_tanks; ++k) s.m_p[static_cast<size_t>(k)] = m_prop(k);
    s.dv_ng = dv_ng;
    s.r = ev(tr.r_CN_N);
    s.v = ev(tr.v_CN_N);
  }
};

Run::Run(const Scenario& sc) : impl_(std::make_unique<Impl>(sc))
{
  Impl& m = *impl_;
  m.dt = sc.rates.dt;
  m.dt_ns = static_cast<int64_t>(sc.tick_ns());
  m.n_ticks = sc.num_ticks();
  m.n_rw = static_cast<int>(sc.wheels.size());
  m.n_thr = static_cast<int>(sc.thrusters.size());
  if (m.n_thr > kMaxThr)
    throw config_error(sc, "thrusters", "at most " + std::to_string(kMaxThr) + " thrusters in the plant");

  // ---- plant -----------------------------------------------------------------
  sim::SpacecraftParams params;
  params.hub.m_h = sc.spacecraft.mass;
  params.hub.I_hBc_B = sc.spacecraft.inertia;
  params.hub.r_BcB_B = sc.spacecraft.com;
  params.mu = sc.environment.mu;
  for (const WheelSpec& w : sc.wheels) params.wheels.push_back(w.params);
  sim::InitialConditions ic;
  ic.r_CN_N = sc.spacecraft.initial.r_CN_N;
  ic.v_CN_N = sc.spacecraft.initial.v_CN_N;
  ic.sigma_BN = sc.spacecraft.initial.sigma_BN;
  ic.omega_BN_B = sc.spacecraft.initial.omega_BN_B;
  if (m.n_thr == 0) {
    built_by_plant(sc, "spacecraft", [&] {
      m.craft = std::make_unique<sim::Spacecraft>(params, ic);
    });
  } else {
    sim::PropulsionParams prop;
    sim::TankParams tk;
    tk.r_TB_B = sc.tank->r_B;
    tk.m_p0 = sc.tank->mass;
    prop.tanks.push_back(tk);
    if (sc.rcs_tank) {
      sim::TankParams rt;
      rt.r_TB_B = sc.rcs_tank->r_B;
      rt.m_p0 = sc.rcs_tank->mass;
      prop.tanks.push_back(rt);
    }
    for (int j = 0; j < m.n_thr; ++j) {
      const ThrusterSpec& t = sc.thrusters[static_cast<size_t>(j)];
      sim::ThrusterParams p;
      p.r_TjB_B = t.r_B;
      p.t_hat_B = misaligned_axis(t.dir_B, t.misalignment);
      p.F_max = t.F_max;
      p.Isp = t.Isp;
      p.T_min = t.T_min;
      p.transient = t.transient == ThrTransient::Instant ? sim::ThrusterTransient::Instant
                                                         : sim::ThrusterTransient::FirstOrder;
      p.omega_on = t.omega_on;
      p.omega_off = t.omega_off;
      p.tank = (t.acs && sc.rcs_tank) ? 1 : 0;
      prop.thrusters.push_back(p);
      if (sc.burn && t.name == sc.burn->thruster) m.engine = j;
    }
    prop.command.T_upd_ns = static_cast<int64_t>(sc.rates.thruster_divisor) * m.dt_ns;
    built_by_plant(sc, "thrusters", [&] {
      m.veh = std::make_unique<sim::Vehicle>(params, prop, ic);
    });
    m.n_tanks = static_cast<int>(prop.tanks.size());
    if (sc.burn) {
      // the engine opens at the first command instant at or after start
      const int64_t T = prop.command.T_upd_ns;
      const int64_t start = static_cast<int64_t>(std::llround(sc.burn->start * 1e9));
      m.burn_on_ns = ((start + T - 1) / T) * T;
      m.burn_off_ns = start + static_cast<int64_t>(std::llround(sc.burn->duration * 1e9));
      if (m.burn_off_ns <= m.burn_on_ns) m.burn_off_ns = m.burn_on_ns;
    }
  }

  // ---- FSW application configuration (nominal values, not truth) -------------
  const sim::MassProps mp = m.mass_props();
  const Eigen::Vector3d c = mp.c_B;
  const Eigen::Matrix3d I_C =
      mp.I_sc_B - mp.m_sc * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  const Eigen::Matrix3d I_fsw = sc.fsw.mrp_fb.inertia ? *sc.fsw.mrp_fb.inertia : I_C;

  FswAcsConfig& a = m.acs_cfg;
  std::memset(&a, 0, sizeof a);
  a.initial_mode = sc.fsw.mode == FswMode::Inertial ? FSW_ACS_MODE_INERTIAL : FSW_ACS_MODE_SUN_SAFE;
  a.initial_actuation = sc.fsw.actuation == Actuation::Wheels ? FSW_ACS_ACT_WHEELS : FSW_ACS_ACT_THRUSTERS;
  // guidance
  m.ideal_css = sc.sensors.css.normals_B.empty();
  if (m.ideal_css) {
    a.css.num_css = kIdealCss;
    for (int i = 0; i < kIdealCss; ++i) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n(i / 2) = (i % 2 == 0) ? 1.0 : -1.0;
      m.ideal_normals[static_cast<size_t>(i)] = n;
      put3(a.css.n_hat_B[i], n);
      a.css.scale[i] = R(1.0);
    }
    a.css.lit_threshold = R(0.0);
  } else {
    a.css.num_css = static_cast<int>(sc.sensors.css.normals_B.size());
    a.css.lit_threshold = R(sc.fsw.css_lit_threshold);
    for (size_t i = 0; i < sc.sensors.css.normals_B.size(); ++i) {
      put3(a.css.n_hat_B[i], sc.sensors.css.normals_B[i]);
      a.css.scale[i] = R(sc.sensors.css.scale);
    }
  }
  put3(a.sunsafe.s_cmd_B, sc.fsw.sun_axis_B);
  a.sunsafe.min_unit_mag = R(kSunMinUnitMag);
  a.sunsafe.small_angle = R(sc.fsw.sun_small_angle);
  put3(a.sunsafe.omega_search_B, sc.fsw.omega_search_B);
  a.sunsafe.sun_axis_spin_rate = 0;
  put3(a.inertial.sigma_R0N, sc.fsw.sigma_R0N);
  // control
  FswMrpFbConfig& mf = a.mrp_fb;
  mf.K = R(sc.fsw.mrp_fb.K);
  mf.P = R(sc.fsw.mrp_fb.P);
  mf.K_i = R(sc.fsw.mrp_fb.K_i);
  mf.integral_limit = R(sc.fsw.mrp_fb.integral_limit);
  mf.control_law_type = sc.fsw.mrp_fb.control_law;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) mf.I_B[r][k] = R(I_fsw(r, k));
  a.use_lpf = 0;
  // actuator geometry, given once: fsw_acs_config_set_geometry() writes the
  // module copies (and has_wheels / has_thrusters from the counts)
  FswAcsGeometry geo;
  std::memset(&geo, 0, sizeof geo);
  geo.num_rw = m.n_rw;
  for (int i = 0; i < m.n_rw; ++i) {
    const sim::ReactionWheelParams& p = sc.wheels[static_cast<size_t>(i)].params;
    put3(geo.gs_hat_B[i], p.gs_hat_nom_B);
    geo.J_s[i] = R(p.J_s);
    geo.u_max[i] = R(p.u_max);
  }
  // thruster chain: the ACS thrusters (acs: true) only; the main engine is
  // commanded by the burn schedule, not by the FSW
  for (int j = 0; j < m.n_thr; ++j)
    if (sc.thrusters[static_cast<size_t>(j)].acs) {
      if (m.n_acs >= FSW_MAX_THR)
        throw config_error(sc, "thrusters", "at most " + std::to_string(FSW_MAX_THR) + " ACS thrusters (FSW_MAX_THR)");
      m.acs_to_plant[static_cast<size_t>(m.n_acs++)] = j;
    }
  geo.num_thr = m.n_acs;
  for (int i = 0; i < m.n_acs; ++i) {
    const ThrusterSpec& t = sc.thrusters[static_cast<size_t>(m.acs_to_plant[static_cast<size_t>(i)])];
    put3(geo.r_thr_B[i], t.r_B);
    put3(geo.gt_hat_B[i], t.dir_B);  // nominal axis: the misalignment is truth only
    geo.F_max[i] = R(t.F_max);
  }
  if (fsw_acs_config_set_geometry(&a, &geo) != FSW_OK)
    throw config_error(sc, "wheels", "wheel or thruster count above the FSW capacity");
  // wheel chain: rw_map -> [rw_null] -> rw_sat (limits = the wheels' u_max)
  if (a.has_wheels) {
    a.rw_map.num_axes = 3;
    for (int r = 0; r < 3; ++r) a.rw_map.ctrl_axes_B[r][r] = 1;
    a.rw_map.mode = sc.fsw.rw_map == RwMapMode::Power ? FSW_RW_MAP_POWER : FSW_RW_MAP_MIN_NORM;
    a.rw_map.eps_P = R(sc.fsw.eps_P);
    a.use_null = sc.fsw.rw_null ? 1 : 0;
    a.rw_null.k_null = R(sc.fsw.k_null);
    a.rw_null.scale_to_fit = sc.fsw.rw_null_scale_to_fit ? 1 : 0;
    a.rw_sat.mode = FSW_RW_SAT_SCALE;
    for (int i = 0; i < m.n_rw; ++i)
      a.Omega_des[i] = i < static_cast<int>(sc.fsw.Omega_des.size()) ? R(sc.fsw.Omega_des[static_cast<size_t>(i)]) : 0;
  }
  if (a.has_thrusters) {
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
  {
    const char* bad = nullptr;
    const FswStatus s = fsw_acs_init(&m.acs_st, &m.acs_cfg, &bad);
    if (s != FSW_OK) {
      const std::string field = bad ? bad : "(unknown)";
      throw config_error(sc, scenario_key_of(field),
                         std::string("rejected by fsw_acs_check: field '") + field + "': " + fsw_status_name(s));
    }
  }

  // Coarse sun sensors (plant side) when normals are configured.
  if (!m.ideal_css) {
    const sim::SensorContext sctx{sc.seed, sc.sensors.noise && sc.sensors.css.noise_std > 0.0};
    for (size_t i = 0; i < sc.sensors.css.normals_B.size(); ++i) {
      sim::CssParams cp;
      cp.name = "css" + std::to_string(i);
      cp.n_hat_B = sc.sensors.css.normals_B[i];
      cp.fov_half = sc.sensors.css.fov;
      cp.scale = sc.sensors.css.scale;
      cp.sigma = sc.sensors.css.noise_std;
      cp.period_ns = static_cast<int64_t>(sc.tick_ns());  // sampled at FSW ticks
      built_by_plant(sc, "sensors.css", [&] {
        m.css.emplace_back(cp, sctx);
      });
    }
  }

  // Gyro, star tracker, wheel tachometers (plant side), each on its own
  // stream Rng(seed, "gyro" | "star_tracker" | "tachometer"); one noise switch.
  {
    const sim::SensorContext sctx{sc.seed, sc.sensors.noise};
    const int64_t tk = static_cast<int64_t>(sc.tick_ns());
    built_by_plant(sc, "sensors.gyro", [&] {
      if (sc.sensors.gyro.enabled) {
        sim::GyroParams gp;
        gp.name = "gyro";
        gp.period_ns = static_cast<int64_t>(sc.sensors.gyro.divisor) * tk;
        gp.sigma_ARW = sc.sensors.gyro.arw;
        gp.sigma_RRW = sc.sensors.gyro.rrw;
        gp.lsb = sc.sensors.gyro.lsb;
        m.gyro = std::make_unique<sim::Gyro>(gp, sctx);
      }
    });
    built_by_plant(sc, "sensors.star_tracker", [&] {
      if (sc.sensors.star_tracker.enabled) {
        sim::StarTrackerParams sp;
        sp.name = "star_tracker";
        sp.period_ns = static_cast<int64_t>(sc.sensors.star_tracker.divisor) * tk;
        sp.sigma_cross = sc.sensors.star_tracker.sigma_cross;
        sp.sigma_bore = sc.sensors.star_tracker.sigma_bore;
        sp.sun_exclusion = sc.sensors.star_tracker.sun_exclusion;
        m.st = std::make_unique<sim::StarTracker>(sp, sctx);
      }
    });
    built_by_plant(sc, "sensors.tachometer", [&] {
      if (sc.sensors.tachometer.enabled && m.n_rw > 0) {
        sim::TachParams tp;
        tp.name = "tachometer";
        tp.num_rw = m.n_rw;
        tp.period_ns = static_cast<int64_t>(sc.sensors.tachometer.divisor) * tk;
        tp.sigma = sc.sensors.tachometer.sigma;
        tp.lsb = sc.sensors.tachometer.lsb;
        m.tach = std::make_unique<sim::WheelTachometers>(tp, sctx);
      }
    });
  }

  // ---- messages and data flow -------------------------------------------------
  DataFlow& f = m.flow;
  f.add_component("plant", m.veh ? "sim::Vehicle" : "sim::Spacecraft");
  f.add_component("sensors", "FSW input: sampled sensor outputs (truth where a sensor is disabled)");
  f.add_component("fsw_acs", "fsw_c application (fsw_acs_cycle)");
  f.add_component("actuators", "harness");
  auto& truth = f.add_message<TruthMsg>("truth");
  auto& sens = f.add_message<FswAcsSensorMsg>("fsw_sensors");
  auto& act = f.add_message<FswAcsActuatorMsg>("fsw_actuators");
  auto& health = f.add_message<FswAcsHealthMsg>("fsw_health");
  auto& metrics = f.add_message<MetricsMsg>("metrics");
  Channel<SunHeadingMsg>* sun = nullptr;
  if (sc.fsw.mode == FswMode::SunSafe) sun = &f.add_message<SunHeadingMsg>("sun_heading");
  Channel<ThrCmdMsg>* thr_cmd = m.n_thr > 0 ? &f.add_message<ThrCmdMsg>("thr_cmd") : nullptr;
  m.truth = &truth;
  m.metrics = &metrics;

  Impl* ip = &m;
  // truth: every tick
  {
    auto w = f.writer("plant", truth);
    m.sched.add_task("truth", RateGroup{"every_tick", 1, 0}, [ip, w](uint64_t k) {
      const Impl& s = *ip;
      const sim::StateVector& x = s.x();
      const sim::MassProps mp = s.mass_props();
      TruthMsg t{};
      for (int i = 0; i < 3; ++i) {
        t.r_BN_N[i] = x(sim::StateLayout::r_BN_N + i);
        t.v_BN_N[i] = x(sim::StateLayout::v_BN_N + i);
        t.sigma_BN[i] = x(sim::StateLayout::sigma_BN + i);
        t.omega_BN_B[i] = x(sim::StateLayout::omega_BN_B + i);
        t.c_B[i] = mp.c_B(i);
      }
      // mass centre: r_C = r_B + [NB] c, v_C = v_B + [NB](omega x c) (c' neglected, §5.6)
      const Eigen::Matrix3d NB = sim::dcm_BN_from_sigma(ev(t.sigma_BN)).transpose();
      const Eigen::Vector3d rC = ev(t.r_BN_N) + NB * mp.c_B;
      const Eigen::Vector3d vC = ev(t.v_BN_N) + NB * ev(t.omega_BN_B).cross(mp.c_B);
      for (int i = 0; i < 3; ++i) {
        t.r_CN_N[i] = rC(i);
        t.v_CN_N[i] = vC(i);
      }
      t.m_sc = mp.m_sc;
      for (int k2 = 0; k2 < s.n_tanks; ++k2) t.m_prop += s.m_prop(k2);
      for (int i = 0; i < s.n_rw; ++i) {
        t.Omega[i] = s.Omega(i);
        t.u_s[i] = s.u_s(i);
      }
      for (int j = 0; j < s.n_thr; ++j) t.F_thr[j] = s.veh->thruster_effect(j).F_B.norm();
      w.write(t, ip->sched.t_ns(k));
    });
  }
  // burn monitor (thruster runs): non-gravitational velocity change of C,
  // dv += (v_C(k+1) - v_C(k)) - dt/2 (g(r_C(k)) + g(r_C(k+1))), and the state at
  // the burn's start and end
  if (m.veh) {
    f.add_component("burn_monitor", "harness");
    auto rt = f.reader("burn_monitor", truth);
    const double mu = sc.environment.mu;
    m.sched.add_task("burn_monitor", RateGroup{"every_tick", 1, 0}, [ip, rt, mu](uint64_t k) {
      Impl& s = *ip;
      const TruthMsg& t = rt.read();
      const Eigen::Vector3d r = ev(t.r_CN_N), v = ev(t.v_CN_N);
      if (s.have_prev) {
        Eigen::Vector3d g = Eigen::Vector3d::Zero();
        if (mu > 0.0) g = 0.5 * (sim::point_mass_gravity(mu, s.r_prev) + sim::point_mass_gravity(mu, r));
        s.dv_ng += (v - s.v_prev) - s.dt * g;
      }
      s.have_prev = true;
      s.r_prev = r;
      s.v_prev = v;
      if (s.engine >= 0) {
        const int64_t t_ns = static_cast<int64_t>(s.sched.t_ns(k));
        const double tt = static_cast<double>(t_ns) * 1e-9;
        if (!s.burn_start.set && t_ns >= s.burn_on_ns) s.snap(s.burn_start, tt, t);
        // the engine is off (and its thrust decayed, 5 time constants) at burn_end
        if (s.burn_start.set && !s.burn_end.set && t_ns >= s.burn_off_ns && t.F_thr[s.engine] < 1e-3 * s.sc.thrusters[static_cast<size_t>(s.engine)].F_max)
          s.snap(s.burn_end, tt, t);
      }
    });
  }
  const RateGroup fsw_group{"fsw", sc.rates.fsw_divisor, sc.rates.fsw_offset};
  // sensor sampling (every tick): each model samples when its own period is
  // due (t_k a multiple of divisor * dt) and its output is held in between.
  const bool have_models = m.gyro || m.st || m.tach;
  Channel<SensorSampleMsg>* samples = have_models ? &f.add_message<SensorSampleMsg>("sensor_samples") : nullptr;
  if (have_models) {
    f.add_component("sample_sensors", "sim::Gyro, sim::StarTracker, sim::WheelTachometers");
    auto rt = f.reader("sample_sensors", truth);
    auto wsm = f.writer("sample_sensors", *samples);
    const Eigen::Vector3d r_sun = sc.environment.sun_position_N;
    const uint64_t dg = sc.sensors.gyro.divisor, ds = sc.sensors.star_tracker.divisor,
                   dw = sc.sensors.tachometer.divisor;
    m.sched.add_task("sample_sensors", RateGroup{"every_tick", 1, 0},
                     [ip, rt, wsm, r_sun, dg, ds, dw](uint64_t k) {
      Impl& s = *ip;
      const bool g = s.gyro && k % dg == 0, a = s.st && k % ds == 0, w = s.tach && k % dw == 0;
      if (!(g || a || w)) return;
      const TruthMsg& t = rt.read();
      sim::SensorTruth st;
      st.t_ns = static_cast<int64_t>(s.sched.t_ns(k));
      st.sigma_BN = ev(t.sigma_BN);
      st.omega_BN_B = ev(t.omega_BN_B);
      st.r_BN_N = ev(t.r_BN_N);
      st.r_SunN_N = r_sun;
      for (int i = 0; i < s.n_rw; ++i) st.Omega[static_cast<size_t>(i)] = t.Omega[i];
      SensorSampleMsg out = wsm.channel().value();
      if (g && s.gyro->update(st)) {
        const sim::GyroOutput& o = s.gyro->output();
        put3(out.omega_PN_P, o.omega_PN_P);
        out.gyro_t_ns = o.t_ns;
        out.gyro_valid = o.valid ? 1 : 0;
      }
      if (a && s.st->update(st)) {
        const sim::StarTrackerOutput& o = s.st->output();
        put3(out.sigma_CN, o.sigma_CN);
        out.st_t_ns = o.t_ns;
        out.st_valid = o.valid ? 1 : 0;
      }
      if (w && s.tach->update(st)) {
        const sim::TachOutput& o = s.tach->output();
        for (int i = 0; i < s.n_rw; ++i) out.Omega[i] = o.Omega[static_cast<size_t>(i)];
        out.tach_t_ns = o.t_ns;
        out.tach_valid = o.valid ? 1 : 0;
      }
      wsm.write(out, st.t_ns);
    });
  }
  // sensors: FswAcsSensorMsg from the held sensor samples (gyro -> omega_BN_B,
  // star tracker -> sigma_BN + att_valid, tachometers -> Omega), CSS readings;
  // a disabled sensor's quantity and r_CoM_B come from truth
  {
    auto rt = f.reader("sensors", truth);
    auto ws = f.writer("sensors", sens);
    Reader<SensorSampleMsg> rsm;
    if (samples) rsm = f.reader("sensors", *samples);
    Reader<CssMsg> rc;
    if (!m.ideal_css) {
      f.add_component("css", "sim::CoarseSunSensor");
      auto& css_msg = f.add_message<CssMsg>("css_readings");
      auto rtc = f.reader("css", truth);
      auto wc = f.writer("css", css_msg);
      rc = f.reader("sensors", css_msg);
      const Eigen::Vector3d r_sun = sc.environment.sun_position_N;
      m.sched.add_task("css", fsw_group, [ip, rtc, wc, r_sun](uint64_t k) {
        const TruthMsg& t = rtc.read();
        sim::SensorTruth st;
        st.t_ns = static_cast<int64_t>(ip->sched.t_ns(k));
        st.sigma_BN = ev(t.sigma_BN);
        st.omega_BN_B = ev(t.omega_BN_B);
        st.r_BN_N = ev(t.r_BN_N);
        st.r_SunN_N = r_sun;
        CssMsg cm{};
        for (size_t i = 0; i < ip->css.size(); ++i) {
          ip->css[i].update(st);
          cm.y[i] = ip->css[i].output().y;
        }
        wc.write(cm, ip->sched.t_ns(k));
      });
    }
    const Eigen::Vector3d r_sun = sc.environment.sun_position_N;
    m.sched.add_task("sensors", fsw_group, [ip, rt, ws, rc, rsm, r_sun](uint64_t k) {
      const Impl& s = *ip;
      const TruthMsg& t = rt.read();
      FswAcsSensorMsg msg;
      std::memset(&msg, 0, sizeof msg);
      msg.t_ns = s.sched.t_ns(k);
      if (s.st) {
        // sigma_BN = sigma_CN (case = body); no valid sample yet or Sun-excluded: att_valid 0
        const SensorSampleMsg& sm = rsm.read();
        copy3(msg.sigma_BN, sm.sigma_CN);
        msg.att_valid = sm.st_valid;
      } else {
        copy3(msg.sigma_BN, t.sigma_BN);
        msg.att_valid = 1;
      }
      if (s.gyro) copy3(msg.omega_BN_B, rsm.read().omega_PN_P);  // P = B
      else copy3(msg.omega_BN_B, t.omega_BN_B);
      if (s.ideal_css) {
        const Eigen::Vector3d d_B =
            sim::dcm_BN_from_sigma(ev(t.sigma_BN)) * (r_sun - ev(t.r_BN_N)).normalized();
        for (int i = 0; i < kIdealCss; ++i)
          msg.css[i] = R(std::max(0.0, s.ideal_normals[static_cast<size_t>(i)].dot(d_B)));
      } else {
        for (int i = 0; i < s.acs_cfg.css.num_css; ++i) msg.css[i] = R(rc.read().y[i]);
      }
      if (s.tach) {
        const SensorSampleMsg& sm = rsm.read();
        for (int i = 0; i < s.n_rw; ++i) msg.Omega[i] = R(sm.Omega[i]);
      } else {
        for (int i = 0; i < s.n_rw; ++i) msg.Omega[i] = R(t.Omega[i]);
      }
      copy3(msg.r_CoM_B, t.c_B);
      ws.write(msg, msg.t_ns);
    });
  }
  // the FSW application: one cycle per control period
  {
    auto rs = f.reader("fsw_acs", sens);
    auto wa = f.writer("fsw_acs", act);
    auto wh = f.writer("fsw_acs", health);
    Writer<SunHeadingMsg> wsun;
    if (sun) wsun = f.writer("fsw_acs", *sun);
    const bool has_sun = sun != nullptr;
    m.sched.add_task("fsw_acs", fsw_group, [ip, rs, wa, wh, wsun, has_sun](uint64_t k) {
      Impl& s = *ip;
      const uint64_t t_ns = s.sched.t_ns(k);
      FswAcsActuatorMsg out;
      fsw_acs_cycle(&s.acs_st, &s.acs_cfg, &rs.read(), nullptr, &out, &s.last_health);
      wa.write(out, t_ns);
      wh.write(s.last_health, t_ns);
      if (has_sun) {
        // the css_sun estimate the cycle used (published in the health message)
        SunHeadingMsg h{};
        copy3(h.sun_B, s.last_health.sun_hat_B);
        h.valid = s.last_health.sun_valid;
        h.num_lit = s.last_health.num_lit;
        wsun.write(h, t_ns);
      }
    });
  }
  // actuators: wheel torques latched (zero-order hold over the FSW period);
  // thruster on-times (ACS from the FSW, the engine from the burn schedule)
  // sent to the plant, latched at its next command instant
  {
    auto ra = f.reader("actuators", act);
    f.reader("plant", act);  // the plant holds the latched wheel torques
    Writer<ThrCmdMsg> wt;
    if (thr_cmd) {
      wt = f.writer("actuators", *thr_cmd);
      f.reader("plant", *thr_cmd);
    }
    m.sched.add_task("actuators", fsw_group, [ip, ra, wt](uint64_t k) {
      Impl& s = *ip;
      const FswAcsActuatorMsg& a = ra.read();
      sim::WheelArray u{};
      if (a.wheels_active)
        for (int i = 0; i < s.n_rw; ++i) u[static_cast<size_t>(i)] = static_cast<double>(a.u_s[i]);
      s.latch_wheels(u);
      if (s.n_thr > 0) {
        ThrCmdMsg c{};
        sim::ThrusterArray T{};
        if (a.thrusters_active)
          for (int i = 0; i < s.n_acs; ++i) {
            const int j = s.acs_to_plant[static_cast<size_t>(i)];
            T[static_cast<size_t>(j)] = static_cast<double>(a.t_on[i]);
          }
        if (s.engine >= 0) {
          const int64_t Tu = s.veh->model().propulsion().command.T_upd_ns;
          const int64_t now = static_cast<int64_t>(s.sched.t_ns(k));
          const int64_t t_L = ((now + Tu - 1) / Tu) * Tu;  // latch instant of this message
          if (t_L >= s.burn_on_ns && t_L < s.burn_off_ns)
            T[static_cast<size_t>(s.engine)] = static_cast<double>(std::min(Tu, s.burn_off_ns - t_L)) * 1e-9;
        }
        for (int j = 0; j < s.n_thr; ++j) c.T_on[j] = T[static_cast<size_t>(j)];
        s.veh->command_thrusters(T);
        wt.write(c, s.sched.t_ns(k));
      }
    });
  }
  // metrics + recorder
  const RateGroup rec_group{"record", sc.rates.record_divisor, 0};
  {
    f.add_component("metrics", "harness");
    auto rt = f.reader("metrics", truth);
    auto wm = f.writer("metrics", metrics);
    const bool inertial = sc.fsw.mode == FswMode::Inertial;
    const Eigen::Vector3d sigma_R0N = sc.fsw.sigma_R0N;
    const Eigen::Vector3d axis = sc.fsw.sun_axis_B;
    const Eigen::Vector3d r_sun = sc.environment.sun_position_N;
    const double mu = sc.environment.mu;
    m.sched.add_task("metrics", rec_group, [=](uint64_t k) {
      Impl& s = *ip;
      const TruthMsg& t = rt.read();
      MetricsMsg out{};
      const Eigen::Vector3d sigma = ev(t.sigma_BN);
      if (inertial) {
        out.pointing_error = principal_angle(sigma, sigma_R0N);  // guid_inertial: constant reference
      } else {
        const Eigen::Vector3d d_B = sim::dcm_BN_from_sigma(sigma) * (r_sun - ev(t.r_BN_N)).normalized();
        out.pointing_error = std::atan2(axis.cross(d_B).norm(), axis.dot(d_B));
      }
      const sim::EnergyMomentum em = s.energy_momentum();
      for (int i = 0; i < 3; ++i) out.H_C_N[i] = em.H_C_N(i);
      out.E_rot = em.E_rot;
      out.dv_ng = s.dv_ng.norm();
      if (mu > 0.0) {
        const sim::OrbitElements oe = sim::elements_from_rv(mu, ev(t.r_CN_N), ev(t.v_CN_N));
        out.orbit_e = oe.e;
        out.orbit_r_p = oe.r_p;
        out.orbit_energy = oe.energy;
      }
      if (s.burn_start.set && !s.burn_end.set) s.max_err_burn = std::max(s.max_err_burn, out.pointing_error);
      wm.write(out, s.sched.t_ns(k));
    });
  }
  {
    f.add_component("recorder", "harness");
    f.reader("recorder", truth);
    f.reader("recorder", metrics);
    f.reader("recorder", act);
    f.reader("recorder", health);
    const Scheduler* sch = &m.sched;
    m.rec.add_source({{"t", "s"}}, [ip, sch](double* o) {
      o[0] = static_cast<double>(sch->t_ns(ip->tick)) / 1e9;  // correctly rounded: 30 s is 30.0
    });
    m.rec.record<MetricsMsg>(metrics, {{"pointing_error_deg", "deg"}}, [](const MetricsMsg& x, double* o) {
      o[0] = x.pointing_error * kRadToDeg;
    });
    m.rec.record<TruthMsg>(truth,
                           {{"sigma_BN_x", "-"}, {"sigma_BN_y", "-"}, {"sigma_BN_z", "-"},
                            {"q_BN_0", "-"}, {"q_BN_1", "-"}, {"q_BN_2", "-"}, {"q_BN_3", "-"},
                            {"omega_BN_B_x", "rad/s"}, {"omega_BN_B_y", "rad/s"}, {"omega_BN_B_z", "rad/s"},
                            {"r_BN_N_x", "m"}, {"r_BN_N_y", "m"}, {"r_BN_N_z", "m"},
                            {"v_BN_N_x", "m/s"}, {"v_BN_N_y", "m/s"}, {"v_BN_N_z", "m/s"}},
                           [](const TruthMsg& x, double* o) {
                             const Eigen::Vector4d q = sim::quaternion_from_sigma(ev(x.sigma_BN));
                             for (int i = 0; i < 3; ++i) o[i] = x.sigma_BN[i];
                             for (int i = 0; i < 4; ++i) o[3 + i] = q(i);
                             for (int i = 0; i < 3; ++i) {
                               o[7 + i] = x.omega_BN_B[i];
                               o[10 + i] = x.r_BN_N[i];
                               o[13 + i] = x.v_BN_N[i];
                             }
                           });
    // what the FSW was given (FswAcsSensorMsg): the measured values next to truth
    {
      f.reader("recorder", sens);
      m.rec.record<FswAcsSensorMsg>(sens,
                                    {{"meas_sigma_BN_x", "-"}, {"meas_sigma_BN_y", "-"}, {"meas_sigma_BN_z", "-"},
                                     {"meas_att_valid", "-"},
                                     {"meas_omega_BN_B_x", "rad/s"}, {"meas_omega_BN_B_y", "rad/s"},
                                     {"meas_omega_BN_B_z", "rad/s"}},
                                    [](const FswAcsSensorMsg& x, double* o) {
                                      copy3(o, x.sigma_BN);
                                      o[3] = x.att_valid;
                                      copy3(o + 4, x.omega_BN_B);
                                    });
      const int nw = m.n_rw;
      if (nw > 0) {
        std::vector<Column> mc;
        for (int i = 0; i < nw; ++i) mc.push_back({"meas_wheel_speed_rpm_" + std::to_string(i), "rpm"});
        m.rec.record<FswAcsSensorMsg>(sens, mc, [nw](const FswAcsSensorMsg& x, double* o) {
          for (int i = 0; i < nw; ++i) o[i] = static_cast<double>(x.Omega[i]) * kRpmPerRadS;
        });
      }
    }
    const int n = m.n_rw;
    if (n > 0) {
      std::vector<Column> wc;
      for (int i = 0; i < n; ++i) wc.push_back({"wheel_speed_rpm_" + std::to_string(i), "rpm"});
      for (int i = 0; i < n; ++i) wc.push_back({"wheel_torque_" + std::to_string(i), "N*m"});
      m.rec.record<TruthMsg>(truth, wc, [n](const TruthMsg& x, double* o) {
        for (int i = 0; i < n; ++i) o[i] = x.Omega[i] * kRpmPerRadS;
        for (int i = 0; i < n; ++i) o[n + i] = x.u_s[i];
      });
      std::vector<Column> cc;
      for (int i = 0; i < n; ++i) cc.push_back({"wheel_cmd_" + std::to_string(i), "N*m"});
      m.rec.record<FswAcsActuatorMsg>(act, cc, [n](const FswAcsActuatorMsg& x, double* o) {
        for (int i = 0; i < n; ++i) o[i] = static_cast<double>(x.u_s[i]);
      });
    }
    const int nt = m.n_thr;
    if (nt > 0) {
      std::vector<Column> tc;
      for (int j = 0; j < nt; ++j) tc.push_back({"thruster_on_time_" + std::to_string(j), "s"});
      f.reader("recorder", *thr_cmd);
      m.rec.record<ThrCmdMsg>(*thr_cmd, tc, [nt](const ThrCmdMsg& x, double* o) {
        for (int j = 0; j < nt; ++j) o[j] = x.T_on[j];
      });
      std::vector<Column> fc;
      for (int j = 0; j < nt; ++j) fc.push_back({"thruster_force_" + std::to_string(j), "N"});
      fc.push_back({"propellant_kg", "kg"});
      fc.push_back({"mass_kg", "kg"});
      m.rec.record<TruthMsg>(truth, fc, [nt](const TruthMsg& x, double* o) {
        for (int j = 0; j < nt; ++j) o[j] = x.F_thr[j];
        o[nt] = x.m_prop;
        o[nt + 1] = x.m_sc;
      });
      m.rec.record<MetricsMsg>(metrics, {{"dv_nongrav", "m/s"}}, [](const MetricsMsg& x, double* o) { o[0] = x.dv_ng; });
    }
    if (sc.environment.mu > 0.0)
      m.rec.record<MetricsMsg>(metrics, {{"orbit_e", "-"}, {"orbit_r_p_km", "km"}, {"orbit_energy", "J/kg"}},
                               [](const MetricsMsg& x, double* o) {
                                 o[0] = x.orbit_e;
                                 o[1] = x.orbit_r_p * 1e-3;
                                 o[2] = x.orbit_energy;
                               });
    m.rec.record<FswAcsHealthMsg>(health,
                                  {{"sigma_BR_x", "-"}, {"sigma_BR_y", "-"}, {"sigma_BR_z", "-"},
                                   {"omega_BR_B_x", "rad/s"}, {"omega_BR_B_y", "rad/s"}, {"omega_BR_B_z", "rad/s"}},
                                  [](const FswAcsHealthMsg& g, double* o) {
                                    copy3(o, g.sigma_BR);
                                    copy3(o + 3, g.omega_BR_B);
                                  });
    m.rec.record<FswAcsActuatorMsg>(act, {{"Lr_B_x", "N*m"}, {"Lr_B_y", "N*m"}, {"Lr_B_z", "N*m"}},
                                    [](const FswAcsActuatorMsg& x, double* o) { copy3(o, x.Lr_B); });
    m.rec.record<MetricsMsg>(metrics,
                             {{"H_C_N_x", "kg*m^2/s"}, {"H_C_N_y", "kg*m^2/s"}, {"H_C_N_z", "kg*m^2/s"},
                              {"E_rot", "J"}},
                             [](const MetricsMsg& x, double* o) {
                               for (int i = 0; i < 3; ++i) o[i] = x.H_C_N[i];
                               o[3] = x.E_rot;
                             });
    {
      std::vector<Column> hc{{"fsw_status", "-"}, {"fsw_safe_output", "-"}};
      for (int i = 0; i < FSW_ACS_NUM_STAGES; ++i) hc.push_back({std::string("fsw_stage_") + fsw_acs_stage_name(i), "-"});
      m.rec.record<FswAcsHealthMsg>(health, hc, [](const FswAcsHealthMsg& h, double* o) {
        o[0] = static_cast<double>(h.status);
        o[1] = h.safe_output;
        for (int i = 0; i < FSW_ACS_NUM_STAGES; ++i) o[2 + i] = static_cast<double>(h.stage_status[i]);
      });
    }
    if (sun) {
      f.reader("recorder", *sun);
      m.rec.record<SunHeadingMsg>(*sun,
                                  {{"sun_B_x", "-"}, {"sun_B_y", "-"}, {"sun_B_z", "-"}, {"sun_valid", "-"},
                                   {"css_num_lit", "-"}},
                                  [](const SunHeadingMsg& h, double* o) {
                                    for (int i = 0; i < 3; ++i) o[i] = h.sun_B[i];
                                    o[3] = h.valid;
                                    o[4] = h.num_lit;
                                  });
    }
    Recorder* rec = &m.rec;
    m.sched.add_task("recorder", rec_group, [rec](uint64_t) { rec->sample(); });
    // rows: every due tick in [0, n_ticks] (the final tick is sampled too)
    m.rec.allocate(rec_group.count_due(m.n_ticks + 1));
  }
}

Run::~Run() = default;

bool Run::step_ticks(uint64_t n)
{
  Impl& m = *impl_;
  if (!m.failure.empty()) return false;
  for (uint64_t i = 0; i < n && m.tick <= m.n_ticks; ++i) {
    m.sched.run_tick(m.tick);
    if (m.rec.overflow() > 0) {
      m.failure = "recorder overflow at tick " + std::to_string(m.tick) + " (internal error)";
      return false;
    }
    if (m.tick < m.n_ticks) {
      if (m.step() != sim::StepStatus::Ok) {
        m.failure = "plant state became non-finite at t = " +
                    std::to_string(static_cast<double>(m.sched.t_ns(m.tick)) * 1e-9) + " s";
        ++m.tick;
        return false;
      }
    }
    ++m.tick;
  }
  return true;
}

bool Run::done() const { return impl_->tick > impl_->n_ticks || !impl_->failure.empty(); }
uint64_t Run::tick() const { return impl_->tick; }
uint64_t Run::total_ticks() const { return impl_->n_ticks + 1; }
const std::string& Run::failure() const { return impl_->failure; }
const Scenario& Run::scenario() const { return impl_->sc; }
const Recorder& Run::recorder() const { return impl_->rec; }
const DataFlow& Run::dataflow() const { return impl_->flow; }
const Scheduler& Run::scheduler() const { return impl_->sched; }

std::vector<std::array<double, 3>> Run::wheel_axes_B() const
{
  std::vector<std::array<double, 3>> out;
  for (const WheelSpec& w : impl_->sc.wheels)
    out.push_back({w.params.gs_hat_nom_B(0), w.params.gs_hat_nom_B(1), w.params.gs_hat_nom_B(2)});
  return out;
}

std::vector<std::string> Run::fsw_health_lines() const
{
  const Impl& m = *impl_;
  const FswAcsState& st = m.acs_st;
  const FswAcsHealthMsg& h = m.last_health;
  std::vector<std::string> out;
  {
    std::ostringstream os;
    os << "fsw_acs last cycle: status=" << fsw_status_name(h.status) << " safe_output=" << int(h.safe_output)
       << " mode=" << (h.mode == FSW_ACS_MODE_INERTIAL ? "inertial" : "sun_safe")
       << " actuation=" << (h.actuation == FSW_ACS_ACT_THRUSTERS ? "thrusters" : "wheels") << " cycles=" << h.cycles
       << " mode_changes=" << h.mode_changes;
    out.push_back(os.str());
    std::ostringstream ss;
    ss << "fsw_acs last cycle stages:";
    for (int i = 0; i < FSW_ACS_NUM_STAGES; ++i) ss << " " << fsw_acs_stage_name(i) << "=" << fsw_status_name(h.stage_status[i]);
    out.push_back(ss.str());
  }
  auto line = [&out](const char* name, const FswHealth& hh) {
    std::ostringstream os;
    os << name << ": calls=" << hh.calls << " bad_input=" << hh.bad_input << " bad_time=" << hh.bad_time
       << " saturated=" << hh.saturated << " singular=" << hh.singular << " other_error=" << hh.other_error
       << " last=" << fsw_status_name(hh.last);
    out.push_back(os.str());
  };
  line("fsw_acs", st.health);
  if (m.sc.fsw.mode == FswMode::Inertial) {
    line("guid_inertial", st.inertial.health);
    line("att_track", st.track.health);
  } else {
    line("css_sun", st.css.health);
    line("guid_sunsafe", st.sunsafe.health);
  }
  line("mrp_fb", st.mrp_fb.health);
  if (m.acs_cfg.has_wheels) {
    line("rw_map", st.rw_map.health);
    if (m.acs_cfg.use_null) line("rw_null", st.rw_null.health);
    line("rw_sat", st.rw_sat.health);
  }
  if (m.acs_cfg.has_thrusters) {
    line("thr_map", st.thr_map.health);
    if (m.acs_cfg.pulser == FSW_ACS_PULSE_REMAINDER) line("thr_pulse_rem", st.pulse_rem.common.health);
    else line("thr_pulse_schmitt", st.pulse_schmitt.common.health);
  }
  return out;
}

std::vector<SummaryItem> Run::summary() const
{
  const Impl& m = *impl_;
  std::vector<SummaryItem> out;
  const Recorder& r = m.rec;
  if (r.rows() > 0) {
    const auto err = r.column("pointing_error_deg");
    out.push_back({"final_pointing_error_deg", err.back(), "deg", "pointing error at the end of the run"});
  }
  if (!m.veh) return out;
  double used = 0.0;
  for (int k = 0; k < m.n_tanks; ++k)
    used += m.veh->model().propulsion().tanks[static_cast<size_t>(k)].m_p0 - m.m_prop(k);
  out.push_back({"propellant_used_kg", used, "kg", "all tanks, whole run"});
  const double mu = m.sc.environment.mu;
  if (m.engine >= 0 && m.burn_start.set) {
    const Impl::Snap& a = m.burn_start;
    const bool ended = m.burn_end.set;
    const Impl::Snap& b = ended ? m.burn_end : a;
    const ThrusterSpec& eng = m.sc.thrusters[static_cast<size_t>(m.engine)];
    out.push_back({"burn_start_s", a.t, "s", "engine open (first command instant at or after burn.start)"});
    out.push_back({"burn_end_s", ended ? b.t : std::numeric_limits<double>::quiet_NaN(), "s",
                   "engine closed and its thrust below 1e-3 F_max"});
    out.push_back({"burn_complete", ended ? 1.0 : 0.0, "-", "1 if the burn ended before the end of the run"});
    out.push_back({"max_pointing_error_burn_deg", m.max_err_burn * kRadToDeg, "deg",
                   "largest recorded pointing error between burn start and end"});
    if (ended) {
      const double m0 = a.m, m1 = b.m;
      // propellant of the engine's tank (tank 0); with rcs_tank the ACS
      // thrusters draw from tank 1, so tank 0 is the engine's alone
      const double dm_main = a.m_p[0] - b.m_p[0];
      const double dm_rcs = m.n_tanks > 1 ? a.m_p[1] - b.m_p[1] : 0.0;
      const double dv = (b.dv_ng - a.dv_ng).norm();
      const double ve = sim::kG0 * eng.Isp;
      const double dm_rocket = m0 * (1.0 - std::exp(-dv / ve));
      out.push_back({"mass_before_burn_kg", m0, "kg", "total mass at burn start"});
      out.push_back({"mass_after_burn_kg", m1, "kg", "total mass at burn end"});
      out.push_back({"propellant_engine_kg", dm_main, "kg", "tank 0 propellant used during the burn"});
      out.push_back({"propellant_rcs_burn_kg", dm_rcs, "kg", "rcs_tank propellant used during the burn"});
      out.push_back({"dv_nongrav_mps", dv, "m/s",
                     "|v_C(end) - v_C(start) - integral of gravity|: the delivered (sensed) delta-v"});
      out.push_back({"dv_rocket_mps", ve * std::log(m0 / (m0 - dm_main)), "m/s",
                     "g0 Isp ln(m0 / (m0 - engine propellant)): rocket equation"});
      out.push_back({"propellant_rocket_kg", dm_rocket, "kg", "m0 (1 - exp(-dv_nongrav / (g0 Isp)))"});
      out.push_back({"propellant_vs_rocket_rel", dm_main / dm_rocket - 1.0, "-",
                     "engine propellant / rocket-equation propellant - 1"});
    }
    if (mu > 0.0) {
      const sim::OrbitElements o0 = sim::elements_from_rv(mu, a.r, a.v);
      out.push_back({"orbit_before_e", o0.e, "-", "osculating eccentricity at burn start"});
      out.push_back({"orbit_before_r_p_km", o0.r_p * 1e-3, "km", "periapsis radius at burn start"});
    }
  }
  if (mu > 0.0) {
    const TruthMsg& t = m.truth->value();  // the last tick run
    const sim::OrbitElements o = sim::elements_from_rv(mu, ev(t.r_CN_N), ev(t.v_CN_N));
    out.push_back({"orbit_after_e", o.e, "-", "osculating eccentricity at the end of the run"});
    out.push_back({"orbit_after_r_p_km", o.r_p * 1e-3, "km", "periapsis radius"});
    out.push_back({"orbit_after_r_a_km", o.e < 1.0 ? o.r_a * 1e-3 : std::numeric_limits<double>::quiet_NaN(), "km",
                   "apoapsis radius (NaN: not captured)"});
    out.push_back({"orbit_after_period_h",
                   o.e < 1.0 ? 2.0 * sim::kPi * std::sqrt(o.a * o.a * o.a / mu) / 3600.0
                             : std::numeric_limits<double>::quiet_NaN(),
                   "h", "orbital period (NaN: not captured)"});
    out.push_back({"captured", o.e < 1.0 ? 1.0 : 0.0, "-", "1 if the orbit after the run is an ellipse"});
  }
  return out;
}

}  // namespace harness

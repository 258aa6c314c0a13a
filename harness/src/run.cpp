// run.cpp: the closed loop.  Glue is explicit code copying fields between
// plain structs; unit conversions happen here, named, at the boundary.
#include "harness/run.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

#include "harness/outputs.h"
#include "sim/attitude.h"
#include "sim/sensors.h"
#include "sim/spacecraft.h"
#include "sim/units.h"

extern "C" {
#include "fsw/att_track.h"
#include "fsw/css_sun.h"
#include "fsw/guid_inertial.h"
#include "fsw/guid_sunsafe.h"
#include "fsw/mrp_fb.h"
#include "fsw/rw_map.h"
#include "fsw/rw_null.h"
}

#ifndef KESTREL_VERSION
#define KESTREL_VERSION "0.0.0"
#endif

namespace harness {

const char* version() { return KESTREL_VERSION; }

namespace {

constexpr int kMaxRw = sim::kMaxWheels;
constexpr double kRadToDeg = 180.0 / sim::kPi;
constexpr double kRpmPerRadS = 1.0 / sim::kRadPerSecPerRpm;
// guid_sunsafe: |s_B| above which the Sun heading counts as valid [-]
constexpr double kSunMinUnitMag = 0.1;

// ---- harness messages (plain structs) ----------------------------------------
struct TruthMsg {
  double sigma_BN[3];       // [-]
  double omega_BN_B[3];     // [rad/s]
  double r_BN_N[3];         // [m]
  double v_BN_N[3];         // [m/s]
  double Omega[kMaxRw];     // [rad/s] wheel speeds rel. B
  double u_s[kMaxRw];       // [N*m]   motor torque held by the plant
};
struct NavAttMsg {
  double sigma_BN[3];    // [-]
  double omega_BN_B[3];  // [rad/s]
};
struct RwSpeedsMsg {
  double Omega[kMaxRw];  // [rad/s]
};
struct SunHeadingMsg {
  double sun_B[3];  // [-] unit Sun heading in B; 0 when no valid heading
  int valid;        // [-] 1 if sun_B holds a heading
  int num_lit;      // [-] lit coarse sun sensors (0 for the ideal heading)
};
struct CssMsg {
  double y[FSW_MAX_CSS];  // [reading units] (num_css) coarse-sun-sensor outputs
};
struct RwCmdMsg {
  double u_s[kMaxRw];  // [N*m] motor torque commands
};
struct MetricsMsg {
  double pointing_error;  // [rad]
  double H_C_N[3];        // [kg*m^2/s]
  double E_rot;           // [J]
};

// 3-vector copy across the FSW boundary (fsw_real may be float or double).
template <class Out, class In>
void copy3(Out* out, const In* in)
{
  for (int i = 0; i < 3; ++i) out[i] = static_cast<Out>(in[i]);
}

Eigen::Vector3d ev(const double* p) { return Eigen::Vector3d(p[0], p[1], p[2]); }

// Scalar-first quaternion from an MRP (|sigma| <= 1 gives beta_0 >= 0).
Eigen::Vector4d quat_from_mrp(const Eigen::Vector3d& s)
{
  const double s2 = s.squaredNorm();
  const double d = 1.0 + s2;
  return Eigen::Vector4d((1.0 - s2) / d, 2.0 * s(0) / d, 2.0 * s(1) / d, 2.0 * s(2) / d);
}

// Principal angle of B relative to R from two MRPs, via quaternions.
double principal_angle(const Eigen::Vector3d& sigma_BN, const Eigen::Vector3d& sigma_RN)
{
  const Eigen::Vector4d b = quat_from_mrp(sigma_BN), r = quat_from_mrp(sigma_RN);
  // q_BR = q_BN (x) q_RN^-1: scalar part and vector norm
  const double q0 = b(0) * r(0) + b.tail<3>().dot(r.tail<3>());
  const Eigen::Vector3d qv = r(0) * b.tail<3>() - b(0) * r.tail<3>() - b.tail<3>().cross(r.tail<3>());
  return 2.0 * std::atan2(qv.norm(), std::fabs(q0));
}

ScenarioError config_error(const Scenario& sc, const std::string& key, const std::string& msg)
{
  ScenarioIssue is;
  is.file = sc.source_file.empty() ? "(scenario)" : sc.source_file;
  is.key = key;
  is.message = msg;
  return ScenarioError({is});
}

}  // namespace

struct Run::Impl {
  Scenario sc;
  sim::SpacecraftParams params;
  std::unique_ptr<sim::Spacecraft> plant;
  Scheduler sched;
  DataFlow flow;
  Recorder rec{"telemetry"};
  uint64_t tick = 0;
  uint64_t n_ticks = 0;
  double dt = 0.0;
  int n_rw = 0;
  std::string failure;

  // FSW configs and states
  FswGuidInertialConfig gi_cfg{};
  FswGuidInertialState gi_st{};
  FswGuidSunsafeConfig gs_cfg{};
  FswGuidSunsafeState gs_st{};
  FswAttTrackConfig at_cfg{};
  FswAttTrackState at_st{};
  FswMrpFbConfig mf_cfg{};
  FswMrpFbState mf_st{};
  FswRwMapConfig rm_cfg{};
  FswRwMapState rm_st{};
  FswRwNullConfig rn_cfg{};
  FswRwNullState rn_st{};
  FswCssSunConfig cs_cfg{};
  FswCssSunState cs_st{};
  std::vector<sim::CoarseSunSensor> css;
  FswStatus last_mf = FSW_OK, last_rm = FSW_OK;

  // channels
  Channel<TruthMsg>* truth = nullptr;
  Channel<MetricsMsg>* metrics = nullptr;

  explicit Impl(const Scenario& s) : sc(s), sched(s.tick_ns()) {}
};

Run::Run(const Scenario& sc) : impl_(std::make_unique<Impl>(sc))
{
  Impl& m = *impl_;
  m.dt = sc.rates.dt;
  m.n_ticks = sc.num_ticks();
  m.n_rw = static_cast<int>(sc.wheels.size());
  if (!sc.thrusters.empty())
    throw config_error(sc, "thrusters",
                       "thrusters are not run yet: the harness does not wire the plant's thrusters "
                       "(sim::Vehicle) and the FSW thruster chain yet; remove the 'thrusters' list to run");

  // ---- plant -----------------------------------------------------------------
  m.params.hub.m_h = sc.spacecraft.mass;
  m.params.hub.I_hBc_B = sc.spacecraft.inertia;
  m.params.hub.r_BcB_B = sc.spacecraft.com;
  m.params.mu = sc.environment.mu;
  for (const WheelSpec& w : sc.wheels) m.params.wheels.push_back(w.params);
  sim::InitialConditions ic;
  ic.r_CN_N = sc.spacecraft.initial.r_CN_N;
  ic.v_CN_N = sc.spacecraft.initial.v_CN_N;
  ic.sigma_BN = sc.spacecraft.initial.sigma_BN;
  ic.omega_BN_B = sc.spacecraft.initial.omega_BN_B;
  try {
    m.plant = std::make_unique<sim::Spacecraft>(m.params, ic);
  } catch (const std::exception& e) {
    throw config_error(sc, "spacecraft", std::string("rejected by the plant: ") + e.what());
  }

  // ---- FSW configuration (nominal values, not truth) ---------------------------
  const sim::MassProps mp = m.plant->mass_props();
  const Eigen::Vector3d c = mp.c_B;
  const Eigen::Matrix3d I_C =
      mp.I_sc_B - mp.m_sc * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  const Eigen::Matrix3d I_fsw = sc.fsw.mrp_fb.inertia ? *sc.fsw.mrp_fb.inertia : I_C;

  copy3(m.gi_cfg.sigma_R0N, sc.fsw.sigma_R0N.data());
  copy3(m.gs_cfg.s_cmd_B, sc.fsw.sun_axis_B.data());
  m.gs_cfg.min_unit_mag = static_cast<fsw_real>(kSunMinUnitMag);
  m.gs_cfg.small_angle = static_cast<fsw_real>(sc.fsw.sun_small_angle);
  copy3(m.gs_cfg.omega_search_B, sc.fsw.omega_search_B.data());
  m.gs_cfg.sun_axis_spin_rate = 0;

  FswMrpFbConfig& mf = m.mf_cfg;
  mf.K = static_cast<fsw_real>(sc.fsw.mrp_fb.K);
  mf.P = static_cast<fsw_real>(sc.fsw.mrp_fb.P);
  mf.K_i = static_cast<fsw_real>(sc.fsw.mrp_fb.K_i);
  mf.integral_limit = static_cast<fsw_real>(sc.fsw.mrp_fb.integral_limit);
  mf.control_law_type = sc.fsw.mrp_fb.control_law;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) mf.I_B[r][k] = static_cast<fsw_real>(I_fsw(r, k));
  mf.num_rw = m.n_rw;
  m.rm_cfg.num_rw = m.n_rw;
  m.rm_cfg.num_axes = 3;
  for (int r = 0; r < 3; ++r) m.rm_cfg.ctrl_axes_B[r][r] = 1;
  m.rm_cfg.mode = sc.fsw.rw_map == RwMapMode::Power ? FSW_RW_MAP_POWER : FSW_RW_MAP_MIN_NORM;
  m.rm_cfg.eps_P = static_cast<fsw_real>(sc.fsw.eps_P);
  m.rn_cfg.num_rw = m.n_rw;
  m.rn_cfg.k_null = static_cast<fsw_real>(sc.fsw.k_null);
  m.rn_cfg.scale_to_fit = sc.fsw.rw_null_scale_to_fit ? 1 : 0;
  for (int i = 0; i < m.n_rw; ++i) {
    const sim::ReactionWheelParams& p = sc.wheels[static_cast<size_t>(i)].params;
    copy3(mf.gs_hat_B[i], p.gs_hat_nom_B.data());
    copy3(m.rm_cfg.gs_hat_B[i], p.gs_hat_nom_B.data());
    copy3(m.rn_cfg.gs_hat_B[i], p.gs_hat_nom_B.data());
    mf.J_s[i] = static_cast<fsw_real>(p.J_s);
    m.rn_cfg.u_max[i] = static_cast<fsw_real>(p.u_max);
  }
  auto check = [&sc](FswStatus s, const char* key, const char* module) {
    if (s != FSW_OK)
      throw config_error(sc, key, std::string("rejected by ") + module + ": " + fsw_status_name(s));
  };
  if (sc.fsw.mode == FswMode::Inertial) {
    check(fsw_guid_inertial_init(&m.gi_st, &m.gi_cfg), "fsw.inertial", "fsw_guid_inertial_init");
    check(fsw_att_track_init(&m.at_st, &m.at_cfg), "fsw", "fsw_att_track_init");
  } else {
    check(fsw_guid_sunsafe_init(&m.gs_st, &m.gs_cfg), "fsw.sun_safe", "fsw_guid_sunsafe_init");
  }
  // Coarse sun sensors (plant side) and css_sun (FSW) in sun-safe mode.
  const bool use_css = sc.fsw.mode == FswMode::SunSafe && !sc.sensors.css.normals_B.empty();
  if (use_css) {
    const sim::SensorContext sctx{sc.seed, sc.sensors.css.noise_std > 0.0};
    m.cs_cfg.num_css = static_cast<int>(sc.sensors.css.normals_B.size());
    m.cs_cfg.lit_threshold = static_cast<fsw_real>(sc.fsw.css_lit_threshold);
    for (size_t i = 0; i < sc.sensors.css.normals_B.size(); ++i) {
      sim::CssParams cp;
      cp.name = "css" + std::to_string(i);
      cp.n_hat_B = sc.sensors.css.normals_B[i];
      cp.fov_half = sc.sensors.css.fov;
      cp.scale = sc.sensors.css.scale;
      cp.sigma = sc.sensors.css.noise_std;
      cp.period_ns = static_cast<int64_t>(sc.tick_ns());  // sampled at FSW ticks
      try {
        m.css.emplace_back(cp, sctx);
      } catch (const std::exception& e) {
        throw config_error(sc, "sensors.css", std::string("rejected by the plant: ") + e.what());
      }
      copy3(m.cs_cfg.n_hat_B[i], sc.sensors.css.normals_B[i].data());
      m.cs_cfg.scale[i] = static_cast<fsw_real>(sc.sensors.css.scale);
    }
    check(fsw_css_sun_init(&m.cs_st, &m.cs_cfg), "sensors.css", "fsw_css_sun_init");
  }
  check(fsw_mrp_fb_init(&m.mf_st, &m.mf_cfg), "fsw.mrp_fb", "fsw_mrp_fb_init");
  check(fsw_rw_map_init(&m.rm_st, &m.rm_cfg), "fsw.rw_map", "fsw_rw_map_init");
  if (sc.fsw.rw_null) check(fsw_rw_null_init(&m.rn_st, &m.rn_cfg), "fsw.rw_null", "fsw_rw_null_init");

  // ---- messages and data flow -------------------------------------------------
  DataFlow& f = m.flow;
  f.add_component("plant", "sim::Spacecraft");
  f.add_component("sensors", "ideal truth sampling");
  auto& truth = f.add_message<TruthMsg>("truth");
  auto& nav = f.add_message<NavAttMsg>("nav_att");
  auto& speeds = f.add_message<RwSpeedsMsg>("rw_speeds");
  auto& att_guid = f.add_message<FswAttGuid>("att_guid");
  auto& cmd_torque = f.add_message<FswMrpFbOut>("cmd_torque");
  auto& rw_cmd = f.add_message<RwCmdMsg>("rw_cmd");
  auto& metrics = f.add_message<MetricsMsg>("metrics");
  m.truth = &truth;
  m.metrics = &metrics;
  Channel<FswAttRef>* att_ref = nullptr;
  Channel<SunHeadingMsg>* sun = nullptr;
  if (sc.fsw.mode == FswMode::Inertial) att_ref = &f.add_message<FswAttRef>("att_ref");
  else sun = &f.add_message<SunHeadingMsg>("sun_heading");
  Channel<RwCmdMsg>* rw_map_out = sc.fsw.rw_null ? &f.add_message<RwCmdMsg>("rw_map_torque") : &rw_cmd;

  Impl* ip = &m;
  // truth: every tick
  {
    auto w = f.writer("plant", truth);
    m.sched.add_task("truth", RateGroup{"every_tick", 1, 0}, [ip, w](uint64_t k) {
      const sim::Spacecraft& p = *ip->plant;
      const sim::StateVector& x = p.state();
      TruthMsg t{};
      for (int i = 0; i < 3; ++i) {
        t.r_BN_N[i] = x(sim::StateLayout::r_BN_N + i);
        t.v_BN_N[i] = x(sim::StateLayout::v_BN_N + i);
        t.sigma_BN[i] = x(sim::StateLayout::sigma_BN + i);
        t.omega_BN_B[i] = x(sim::StateLayout::omega_BN_B + i);
      }
      for (int i = 0; i < ip->n_rw; ++i) {
        t.Omega[i] = p.Omega(i);
        t.u_s[i] = p.u_s(i);
      }
      w.write(t, ip->sched.t_ns(k));
    });
  }
  const RateGroup fsw_group{"fsw", sc.rates.fsw_divisor, sc.rates.fsw_offset};
  // sensors (ideal): nav attitude, wheel speeds, Sun heading
  {
    auto rt = f.reader("sensors", truth);
    auto wn = f.writer("sensors", nav);
    auto ws = f.writer("sensors", speeds);
    Writer<SunHeadingMsg> wsun;
    if (sun && !use_css) wsun = f.writer("sensors", *sun);
    const Eigen::Vector3d r_sun = sc.environment.sun_position_N;
    const bool has_sun = sun != nullptr && !use_css;
    m.sched.add_task("sensors", fsw_group, [ip, rt, wn, ws, wsun, r_sun, has_sun](uint64_t k) {
      const TruthMsg& t = rt.read();
      const uint64_t t_ns = ip->sched.t_ns(k);
      NavAttMsg n{};
      std::memcpy(n.sigma_BN, t.sigma_BN, sizeof n.sigma_BN);
      std::memcpy(n.omega_BN_B, t.omega_BN_B, sizeof n.omega_BN_B);
      wn.write(n, t_ns);
      RwSpeedsMsg s{};
      std::memcpy(s.Omega, t.Omega, sizeof s.Omega);
      ws.write(s, t_ns);
      if (has_sun) {
        const Eigen::Vector3d d_N = (r_sun - ev(t.r_BN_N)).normalized();
        const Eigen::Vector3d d_B = sim::dcm_BN_from_sigma(ev(t.sigma_BN)) * d_N;
        SunHeadingMsg h{};
        for (int i = 0; i < 3; ++i) h.sun_B[i] = d_B(i);
        h.valid = 1;
        wsun.write(h, t_ns);
      }
    });
  }
  if (use_css) {
    f.add_component("css", "sim::CoarseSunSensor");
    f.add_component("css_sun", "fsw_c");
    auto& css_msg = f.add_message<CssMsg>("css_readings");
    auto rt = f.reader("css", truth);
    auto wc = f.writer("css", css_msg);
    auto rc = f.reader("css_sun", css_msg);
    auto ws = f.writer("css_sun", *sun);
    const Eigen::Vector3d r_sun = sc.environment.sun_position_N;
    m.sched.add_task("css", fsw_group, [ip, rt, wc, r_sun](uint64_t k) {
      const TruthMsg& t = rt.read();
      sim::SensorTruth st;
      st.t_ns = static_cast<int64_t>(ip->sched.t_ns(k));
      st.sigma_BN = ev(t.sigma_BN);
      st.omega_BN_B = ev(t.omega_BN_B);
      st.r_BN_N = ev(t.r_BN_N);
      st.r_SunN_N = r_sun;
      CssMsg c{};
      for (size_t i = 0; i < ip->css.size(); ++i) {
        ip->css[i].update(st);
        c.y[i] = ip->css[i].output().y;
      }
      wc.write(c, ip->sched.t_ns(k));
    });
    m.sched.add_task("css_sun", fsw_group, [ip, rc, ws](uint64_t k) {
      FswCssSunIn in{};
      for (int i = 0; i < ip->cs_cfg.num_css; ++i) in.reading[i] = static_cast<fsw_real>(rc.read().y[i]);
      FswCssSunOut out{};
      fsw_css_sun_update(&ip->cs_st, &ip->cs_cfg, &in, &out);
      SunHeadingMsg h{};
      copy3(h.sun_B, out.sun_hat_B);
      h.valid = out.sun_valid;
      h.num_lit = out.num_lit;
      ws.write(h, ip->sched.t_ns(k));
    });
  }
  // FSW chain
  {
    const std::string gname = sc.fsw.mode == FswMode::Inertial ? "guid_inertial" : "guid_sunsafe";
    f.add_component(gname, "fsw_c");
    Writer<FswAttRef> w_ref;
    Reader<SunHeadingMsg> r_sun;
    Reader<NavAttMsg> r_nav_g;
    Reader<FswAttRef> r_ref;
    Reader<NavAttMsg> r_nav_t;
    Writer<FswAttGuid> w_guid;
    if (att_ref) {
      w_ref = f.writer(gname, *att_ref);
      f.add_component("att_track", "fsw_c");
      r_nav_t = f.reader("att_track", nav);
      r_ref = f.reader("att_track", *att_ref);
      w_guid = f.writer("att_track", att_guid);
    } else {
      r_sun = f.reader(gname, *sun);
      r_nav_g = f.reader(gname, nav);
      w_guid = f.writer(gname, att_guid);
    }
    f.add_component("mrp_fb", "fsw_c");
    auto r_guid = f.reader("mrp_fb", att_guid);
    auto r_spd_mf = f.reader("mrp_fb", speeds);
    auto w_tq = f.writer("mrp_fb", cmd_torque);
    f.add_component("rw_map", "fsw_c");
    auto r_tq = f.reader("rw_map", cmd_torque);
    auto r_spd_rm = f.reader("rw_map", speeds);
    auto w_map = f.writer("rw_map", *rw_map_out);
    Reader<RwCmdMsg> r_map_null;
    Reader<RwSpeedsMsg> r_spd_null;
    Writer<RwCmdMsg> w_null;
    if (sc.fsw.rw_null) {
      f.add_component("rw_null", "fsw_c");
      r_map_null = f.reader("rw_null", *rw_map_out);
      r_spd_null = f.reader("rw_null", speeds);
      w_null = f.writer("rw_null", rw_cmd);
    }
    const bool inertial = att_ref != nullptr;
    const bool use_null = sc.fsw.rw_null;
    std::vector<double> Omega_des(static_cast<size_t>(m.n_rw), 0.0);
    for (size_t i = 0; i < sc.fsw.Omega_des.size() && i < Omega_des.size(); ++i) Omega_des[i] = sc.fsw.Omega_des[i];
    std::array<double, kMaxRw> om_des{};
    for (size_t i = 0; i < Omega_des.size(); ++i) om_des[i] = Omega_des[i];
    m.sched.add_task("fsw", fsw_group, [=](uint64_t k) {
      Impl& s = *ip;
      const uint64_t t_ns = s.sched.t_ns(k);
      FswAttGuid guid{};
      if (inertial) {
        FswAttRef ref{};
        fsw_guid_inertial_update(&s.gi_st, &s.gi_cfg, &ref);
        w_ref.write(ref, t_ns);
        FswAttTrackIn in{};
        copy3(in.sigma_BN, r_nav_t.read().sigma_BN);
        copy3(in.omega_BN_B, r_nav_t.read().omega_BN_B);
        in.ref = r_ref.read();
        fsw_att_track_update(&s.at_st, &s.at_cfg, &in, &guid);
      } else {
        FswGuidSunsafeIn in{};
        copy3(in.sun_B, r_sun.read().sun_B);
        copy3(in.omega_BN_B, r_nav_g.read().omega_BN_B);
        FswGuidSunsafeOut out{};
        fsw_guid_sunsafe_update(&s.gs_st, &s.gs_cfg, &in, &out);
        guid = out.guid;
      }
      w_guid.write(guid, t_ns);

      FswMrpFbIn mi{};
      mi.t_ns = t_ns;
      mi.guid = r_guid.read();
      for (int i = 0; i < s.n_rw; ++i) mi.Omega[i] = static_cast<fsw_real>(r_spd_mf.read().Omega[i]);
      FswMrpFbOut mo{};
      s.last_mf = fsw_mrp_fb_update(&s.mf_st, &s.mf_cfg, &mi, &mo);
      w_tq.write(mo, t_ns);

      FswRwMapIn ri{};
      for (int i = 0; i < 3; ++i) ri.Lr_B[i] = r_tq.read().torque_B[i];
      for (int i = 0; i < s.n_rw; ++i) ri.Omega[i] = static_cast<fsw_real>(r_spd_rm.read().Omega[i]);
      FswRwMapOut ro{};
      s.last_rm = fsw_rw_map_update(&s.rm_st, &s.rm_cfg, &ri, &ro);
      RwCmdMsg cmd{};
      for (int i = 0; i < s.n_rw; ++i) cmd.u_s[i] = static_cast<double>(ro.u_s[i]);
      w_map.write(cmd, t_ns);

      if (use_null) {
        FswRwNullIn ni{};
        for (int i = 0; i < s.n_rw; ++i) {
          ni.u_s[i] = static_cast<fsw_real>(r_map_null.read().u_s[i]);
          ni.Omega[i] = static_cast<fsw_real>(r_spd_null.read().Omega[i]);
          ni.Omega_des[i] = static_cast<fsw_real>(om_des[static_cast<size_t>(i)]);
        }
        FswRwNullOut no{};
        fsw_rw_null_update(&s.rn_st, &s.rn_cfg, &ni, &no);
        RwCmdMsg c2{};
        for (int i = 0; i < s.n_rw; ++i) c2.u_s[i] = static_cast<double>(no.u_s[i]);
        w_null.write(c2, t_ns);
      }
    });
  }
  // actuators: latch the wheel commands (zero-order hold over the FSW period)
  {
    auto r_cmd = f.reader("plant", rw_cmd);
    m.sched.add_task("actuators", fsw_group, [ip, r_cmd](uint64_t) {
      sim::WheelArray u{};
      for (int i = 0; i < ip->n_rw; ++i) u[static_cast<size_t>(i)] = r_cmd.read().u_s[i];
      ip->plant->latch_commands(u);
    });
  }
  // metrics + recorder
  const RateGroup rec_group{"record", sc.rates.record_divisor, 0};
  {
    f.add_component("metrics", "harness");
    auto rt = f.reader("metrics", truth);
    auto wm = f.writer("metrics", metrics);
    Reader<FswAttRef> rr;
    if (att_ref) rr = f.reader("metrics", *att_ref);
    const bool inertial = att_ref != nullptr;
    const Eigen::Vector3d sigma_R0N = sc.fsw.sigma_R0N;
    const Eigen::Vector3d axis = sc.fsw.sun_axis_B;
    const Eigen::Vector3d r_sun = sc.environment.sun_position_N;
    m.sched.add_task("metrics", rec_group, [=](uint64_t k) {
      const TruthMsg& t = rt.read();
      MetricsMsg out{};
      const Eigen::Vector3d sigma = ev(t.sigma_BN);
      if (inertial) {
        // before the first FSW call the reference message is still empty:
        // use the configured reference then
        Eigen::Vector3d sigma_RN = sigma_R0N;
        if (rr.write_count() > 0) sigma_RN = Eigen::Vector3d(rr.read().sigma_RN[0], rr.read().sigma_RN[1], rr.read().sigma_RN[2]);
        out.pointing_error = principal_angle(sigma, sigma_RN);
      } else {
        const Eigen::Vector3d d_B = sim::dcm_BN_from_sigma(sigma) * (r_sun - ev(t.r_BN_N)).normalized();
        out.pointing_error = std::atan2(axis.cross(d_B).norm(), axis.dot(d_B));
      }
      const sim::EnergyMomentum em = ip->plant->energy_momentum();
      for (int i = 0; i < 3; ++i) out.H_C_N[i] = em.H_C_N(i);
      out.E_rot = em.E_rot;
      wm.write(out, ip->sched.t_ns(k));
    });
  }
  {
    f.add_component("recorder", "harness");
    f.reader("recorder", truth);
    f.reader("recorder", metrics);
    f.reader("recorder", att_guid);
    f.reader("recorder", cmd_torque);
    f.reader("recorder", rw_cmd);
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
                             const Eigen::Vector4d q = quat_from_mrp(ev(x.sigma_BN));
                             for (int i = 0; i < 3; ++i) o[i] = x.sigma_BN[i];
                             for (int i = 0; i < 4; ++i) o[3 + i] = q(i);
                             for (int i = 0; i < 3; ++i) {
                               o[7 + i] = x.omega_BN_B[i];
                               o[10 + i] = x.r_BN_N[i];
                               o[13 + i] = x.v_BN_N[i];
                             }
                           });
    std::vector<Column> wc;
    for (int i = 0; i < m.n_rw; ++i) wc.push_back({"wheel_speed_rpm_" + std::to_string(i), "rpm"});
    for (int i = 0; i < m.n_rw; ++i) wc.push_back({"wheel_torque_" + std::to_string(i), "N*m"});
    const int n = m.n_rw;
    if (n > 0)
      m.rec.record<TruthMsg>(truth, wc, [n](const TruthMsg& x, double* o) {
        for (int i = 0; i < n; ++i) o[i] = x.Omega[i] * kRpmPerRadS;
        for (int i = 0; i < n; ++i) o[n + i] = x.u_s[i];
      });
    std::vector<Column> cc;
    for (int i = 0; i < m.n_rw; ++i) cc.push_back({"wheel_cmd_" + std::to_string(i), "N*m"});
    if (n > 0)
      m.rec.record<RwCmdMsg>(rw_cmd, cc, [n](const RwCmdMsg& x, double* o) {
        for (int i = 0; i < n; ++i) o[i] = x.u_s[i];
      });
    m.rec.record<FswAttGuid>(att_guid,
                             {{"sigma_BR_x", "-"}, {"sigma_BR_y", "-"}, {"sigma_BR_z", "-"},
                              {"omega_BR_B_x", "rad/s"}, {"omega_BR_B_y", "rad/s"}, {"omega_BR_B_z", "rad/s"}},
                             [](const FswAttGuid& g, double* o) {
                               copy3(o, g.sigma_BR);
                               copy3(o + 3, g.omega_BR_B);
                             });
    m.rec.record<FswMrpFbOut>(cmd_torque, {{"Lr_B_x", "N*m"}, {"Lr_B_y", "N*m"}, {"Lr_B_z", "N*m"}},
                              [](const FswMrpFbOut& x, double* o) { copy3(o, x.torque_B); });
    m.rec.record<MetricsMsg>(metrics,
                             {{"H_C_N_x", "kg*m^2/s"}, {"H_C_N_y", "kg*m^2/s"}, {"H_C_N_z", "kg*m^2/s"},
                              {"E_rot", "J"}},
                             [](const MetricsMsg& x, double* o) {
                               for (int i = 0; i < 3; ++i) o[i] = x.H_C_N[i];
                               o[3] = x.E_rot;
                             });
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
      if (m.plant->step(m.dt) != sim::StepStatus::Ok) {
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
  std::vector<std::string> out;
  auto line = [&out](const char* name, const FswHealth& h) {
    std::ostringstream os;
    os << name << ": calls=" << h.calls << " bad_input=" << h.bad_input << " bad_time=" << h.bad_time
       << " saturated=" << h.saturated << " singular=" << h.singular << " other_error=" << h.other_error
       << " last=" << fsw_status_name(h.last);
    out.push_back(os.str());
  };
  if (m.sc.fsw.mode == FswMode::Inertial) {
    line("guid_inertial", m.gi_st.health);
    line("att_track", m.at_st.health);
  } else {
    if (!m.css.empty()) line("css_sun", m.cs_st.health);
    line("guid_sunsafe", m.gs_st.health);
  }
  line("mrp_fb", m.mf_st.health);
  line("rw_map", m.rm_st.health);
  if (m.sc.fsw.rw_null) line("rw_null", m.rn_st.health);
  return out;
}

}  // namespace harness

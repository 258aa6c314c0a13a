// Reference configurations of the FSW application used by the fsw_acs
// tests, the golden-data generator and the benchmark:
//  * a 900/800/600 kg m^2 spacecraft with a 4-wheel pyramid and 6 CSS on
//    the cube faces (the paper's RW case), and
//  * the same spacecraft with the 8 RCS thrusters of Basilisk's
//    thrForceMapping tests (the paper's thruster case).
// Plus a small independent plant in plain C++ (rigid body + ideal wheels +
// thrusters as torque impulses) to close the loop in tests.
#ifndef KESTREL_ACS_FIXTURE_HPP
#define KESTREL_ACS_FIXTURE_HPP

#include <cmath>
#include <cstring>

#include "data/fsw_acs_golden.h"
#include "fsw/fsw_acs.h"

namespace acsfix {

constexpr double kPi = 3.14159265358979323846;
constexpr double kI[3] = {900.0, 800.0, 600.0};  // [kg m^2] principal inertia
constexpr double kJs = 0.1;                      // [kg m^2] wheel spin inertia
constexpr double kUmax = 0.2;                    // [N m]    wheel torque limit
constexpr double kPeriod = 0.5;                  // [s]      control period
constexpr uint64_t kPeriodNs = 500000000ull;

// 4-wheel pyramid: spin axes 40 deg above the x-y plane at azimuths 45+90k deg
inline void pyramid_axis(int i, double g[3])
{
  const double el = 40.0 * kPi / 180.0, az = (45.0 + 90.0 * i) * kPi / 180.0;
  g[0] = std::cos(el) * std::cos(az);
  g[1] = std::cos(el) * std::sin(az);
  g[2] = std::sin(el);
}

// Basilisk thrForceMapping test geometry (8 thrusters, on-pulsing)
constexpr double kThrR[8][3] = {{-0.86360, -0.82550, 1.79070}, {-0.82550, -0.86360, 1.79070},
                                {0.82550, 0.86360, 1.79070},   {0.86360, 0.82550, 1.79070},
                                {-0.86360, -0.82550, -1.79070}, {-0.82550, -0.86360, -1.79070},
                                {0.82550, 0.86360, -1.79070},  {0.86360, 0.82550, -1.79070}};
constexpr double kThrG[8][3] = {{1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {-1, 0, 0},
                                {-1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {1, 0, 0}};
constexpr double kFmax = 1.0;  // [N]

inline fsw_real R(double x) { return static_cast<fsw_real>(x); }

inline void base_config(FswAcsConfig& c)
{
  std::memset(&c, 0, sizeof c);
  c.initial_mode = FSW_ACS_MODE_SUN_SAFE;
  c.initial_actuation = FSW_ACS_ACT_WHEELS;
  // 6 CSS on the cube faces, unit scale
  c.css.num_css = 6;
  for (int i = 0; i < 6; i++) {
    c.css.n_hat_B[i][i / 2] = R(i % 2 == 0 ? 1.0 : -1.0);
    c.css.scale[i] = R(1.0);
  }
  // A lone lit sensor gives its normal as the heading, so sun-safe pointing
  // settles within asin(lit_threshold) of the Sun: 0.57 deg here.
  c.css.lit_threshold = R(0.01);
  // sun-safe: point +z at the Sun
  c.sunsafe.s_cmd_B[2] = R(1.0);
  c.sunsafe.min_unit_mag = R(0.1);
  c.sunsafe.small_angle = R(1e-4);
  c.sunsafe.omega_search_B[2] = R(0.005);
  // inertial target
  c.inertial.sigma_R0N[0] = R(0.1);
  c.inertial.sigma_R0N[1] = R(-0.05);
  c.inertial.sigma_R0N[2] = R(0.2);
  // control: omega_n = sqrt(K/(4 I)) = 0.02 rad/s at I = 900, zeta = P/sqrt(K I) = 1
  c.mrp_fb.K = R(1.44);
  c.mrp_fb.P = R(36.0);
  c.mrp_fb.K_i = R(-1.0);
  c.mrp_fb.integral_limit = R(0.0);
  for (int i = 0; i < 3; i++) c.mrp_fb.I_B[i][i] = R(kI[i]);
  c.lpf.h = R(kPeriod);
  c.lpf.omega_c = R(1.0);
}

// The 4-wheel pyramid as the application's geometry.
inline void wheel_geometry(FswAcsGeometry& g)
{
  std::memset(&g, 0, sizeof g);
  g.num_rw = 4;
  for (int i = 0; i < g.num_rw; i++) {
    double a[3];
    pyramid_axis(i, a);
    for (int k = 0; k < 3; k++) g.gs_hat_B[i][k] = R(a[k]);
    g.J_s[i] = R(kJs);
    g.u_max[i] = R(kUmax);
  }
}

// The 8 RCS thrusters as the application's geometry.
inline void thruster_geometry(FswAcsGeometry& g)
{
  std::memset(&g, 0, sizeof g);
  g.num_thr = 8;
  for (int i = 0; i < g.num_thr; i++) {
    for (int k = 0; k < 3; k++) {
      g.r_thr_B[i][k] = R(kThrR[i][k]);
      g.gt_hat_B[i][k] = R(kThrG[i][k]);
    }
    g.F_max[i] = R(kFmax);
  }
}

inline void wheel_config(FswAcsConfig& c)
{
  base_config(c);
  {
    FswAcsGeometry g;
    wheel_geometry(g);
    (void)fsw_acs_config_set_geometry(&c, &g);  // has_wheels, num_rw, axes, J_s, u_max
  }
  c.rw_map.num_axes = 3;
  for (int k = 0; k < 3; k++) c.rw_map.ctrl_axes_B[k][k] = R(1.0);
  c.rw_map.mode = FSW_RW_MAP_MIN_NORM;
  c.rw_map.eps_P = R(1.0);
  c.rw_null.k_null = R(0.002);
  c.rw_null.scale_to_fit = 1;
  c.rw_sat.mode = FSW_RW_SAT_SCALE;
  c.rw_volt.V_min = R(0.0);
  c.rw_volt.V_max = R(10.0);
  c.rw_volt.K_V = R(0.0);
}

inline void thruster_config(FswAcsConfig& c, int pulser = FSW_ACS_PULSE_REMAINDER)
{
  base_config(c);
  c.initial_mode = FSW_ACS_MODE_INERTIAL;
  c.initial_actuation = FSW_ACS_ACT_THRUSTERS;
  {
    FswAcsGeometry g;
    thruster_geometry(g);
    (void)fsw_acs_config_set_geometry(&c, &g);  // has_thrusters, num_thr, r, g, F_max
  }
  // Thrusters have ~9x the wheels' authority (1 N x 1.8 m): stiffer gains,
  // omega_n = sqrt(K/(4 I)) = 0.075 rad/s, zeta = P/sqrt(K I) = 1.5.  The
  // Schmitt trigger's dead band (no firing below level_on t_min) then maps to
  // an attitude dead band of 4 (0.75 t_min / T) F d / K = 0.6 deg.
  c.mrp_fb.K = R(20.0);
  c.mrp_fb.P = R(200.0);
  for (int k = 0; k < 3; k++) c.thr_map.control_axes_B[k][k] = R(1.0);
  c.thr_map.thr_force_sign = 1;
  c.thr_map.ang_err_thresh = R(0.0);
  c.thr_map.mode = FSW_THR_MAP_NNLS;
  c.pulser = pulser;
  c.pulse_rem.common.t_min = R(0.02);
  c.pulse_rem.common.init_off_pulse_on_time = R(2.0);
  c.pulse_schmitt.common.t_min = R(0.02);
  c.pulse_schmitt.level_on = R(0.75);
  c.pulse_schmitt.level_off = R(0.25);
  c.pulse_schmitt.common.init_off_pulse_on_time = R(2.0);
}

// ---- momentum management, magnetorquers, orbit (issue 38) --------------
// Three orthogonal rods, rotated 30 deg about z from the body axes (so the
// rod map is not the identity): rod 0 (c, s, 0), rod 1 (-s, c, 0), rod 2 z.
constexpr double kRodAz = 30.0 * kPi / 180.0;
constexpr double kRodMmax = 100.0;  // [A m^2] rod dipole at full drive
constexpr double kRodDuty = 0.8;    // [-]     duty_max
inline void rod_axis(int i, double a[3])
{
  const double c = std::cos(kRodAz), s = std::sin(kRodAz);
  a[0] = i == 0 ? c : (i == 1 ? -s : 0.0);
  a[1] = i == 0 ? s : (i == 1 ? c : 0.0);
  a[2] = i == 2 ? 1.0 : 0.0;
}
constexpr double kMu = 3.986004418e14;  // [m^3/s^2] Earth

// The 4-wheel pyramid, the 8 RCS thrusters and the 3 rods in one geometry.
inline void full_geometry(FswAcsGeometry& g)
{
  FswAcsGeometry t;
  wheel_geometry(g);
  thruster_geometry(t);
  g.num_thr = t.num_thr;
  std::memcpy(g.r_thr_B, t.r_thr_B, sizeof g.r_thr_B);
  std::memcpy(g.gt_hat_B, t.gt_hat_B, sizeof g.gt_hat_B);
  std::memcpy(g.F_max, t.F_max, sizeof g.F_max);
  g.num_mtq = 3;
  for (int i = 0; i < 3; i++) {
    double a[3];
    rod_axis(i, a);
    for (int k = 0; k < 3; k++) g.mtq_axis_B[i][k] = R(a[k]);
    g.mtq_m_max[i] = R(kRodMmax);
  }
}

// Wheels (actuation), thrusters, rods and orbit guidance all configured,
// every new module tuned but OFF (use_* = 0, policy NONE, SUN_SAFE): tests
// switch on what they exercise.
inline void full_config(FswAcsConfig& c)
{
  wheel_config(c);
  {
    FswAcsGeometry g;
    full_geometry(g);
    (void)fsw_acs_config_set_geometry(&c, &g);
  }
  for (int k = 0; k < 3; k++) c.thr_map.control_axes_B[k][k] = R(1.0);
  c.thr_map.thr_force_sign = 1;
  c.thr_map.mode = FSW_THR_MAP_NNLS;
  c.pulser = FSW_ACS_PULSE_REMAINDER;
  c.pulse_rem.common.t_min = R(0.02);
  c.pulse_schmitt.common.t_min = R(0.02);
  c.pulse_schmitt.level_on = R(0.75);
  c.pulse_schmitt.level_off = R(0.25);
  c.mtq_map.duty_max = R(kRodDuty);
  c.bdot.variant = FSW_BDOT_GYRO;
  c.bdot.k_bdot = R(1e6);
  c.bdot.normalize = 0;
  c.bdot.max_missed = 3;
  for (int k = 0; k < 3; k++) c.bdot.m_max_B[k] = R(1000.0);
  c.bdot.omega_done = R(0.01);
  c.bdot.omega_reenter = R(0.02);
  c.bdot.t_persist = R(1.0);
  c.detumble_exit_mode = FSW_ACS_MODE_SUN_SAFE;
  c.has_orbit = 1;
  c.orbit.variant = FSW_GUID_ORBIT_NADIR;
  c.orbit.mu = R(kMu);
  c.thr_mom.h_upper = R(4.0);
  c.thr_mom.h_lower = R(1.0);
  c.thr_mom.L_dump = R(0.2);
  c.thr_mom.t_pulse_max = R(5.0);
  c.thr_mom.t_min_pulse = R(0.5);
  c.thr_mom.t_coast = R(1.0);
  c.thr_mom.dt_cycle = R(kPeriod);
  c.thr_mom.Isp = R(200.0);
  c.mtq_desat.k_desat = R(1e-4);
  c.mtq_desat.tau_max = R(1.0);
  c.mtq_desat.h_deadband = R(0.0);
  for (int i = 0; i < 4; i++) c.rw_bias.Omega_bias[i] = R(i % 2 == 0 ? 50.0 : -50.0);
  c.rw_bias.Omega_keepout = R(5.0);
  c.rw_bias.Omega_hyst = R(1.0);
  c.initial_policy = FSW_ACS_MOM_NONE;
}

// ---- the canned sequences of the host/target equivalence test ----------
// scenario 0: wheels with null motion, filter and voltages; sun-safe from a
//             tumble, then inertial from cycle 40 on
// scenario 1: thrusters, remainder pulsing, inertial
// scenario 2: thrusters, Schmitt pulsing, inertial
constexpr int kGoldenScenarios = 3;
constexpr int kGoldenCycles[kGoldenScenarios] = {80, 40, 40};

inline void golden_config(int scenario, FswAcsConfig& c)
{
  if (scenario == 0) {
    wheel_config(c);
    c.use_null = 1;
    c.use_lpf = 1;
    c.use_volt = 1;
    c.Omega_des[0] = R(20.0);
  } else {
    thruster_config(c, scenario == 1 ? FSW_ACS_PULSE_REMAINDER : FSW_ACS_PULSE_SCHMITT);
  }
}
// The sensor message and the command of one recorded golden cycle
// (data/fsw_acs_golden.inc; test_fsw_acs_golden, test_fsw_acs_stages).
inline void golden_inputs(const FswAcsGoldenCycle& g, const FswAcsConfig& c, FswAcsSensorMsg& m, FswAcsCmdMsg& cmd)
{
  std::memset(&m, 0, sizeof m);
  m.t_ns = g.t_ns;
  m.att_valid = 1;
  for (int i = 0; i < 3; i++) {
    m.sigma_BN[i] = R(g.sigma[i]);
    m.omega_BN_B[i] = R(g.omega[i]);
  }
  for (int i = 0; i < 6; i++) m.css[i] = R(g.css[i]);
  for (int i = 0; i < 4; i++) m.Omega[i] = R(g.Omega[i]);
  std::memset(&cmd, 0, sizeof cmd);
  cmd.mode = g.mode;
  cmd.actuation = c.initial_actuation;
}
inline int golden_mode(int scenario, int cycle)
{
  return (scenario == 0 && cycle < 40) ? FSW_ACS_MODE_SUN_SAFE : FSW_ACS_MODE_INERTIAL;
}

// ---- a small independent plant (double precision) ------------------------
// Rigid body with principal inertia kI, ideal reaction wheels (J_s Omega_dot
// = u, body torque -sum u g) and thrusters applying F d_i for t_on of each
// control period.  Attitude as an MRP with shadow switching.
struct Plant {
  double sigma[3] = {0, 0, 0};
  double omega[3] = {0, 0, 0};
  double Omega[4] = {0, 0, 0, 0};
  double sun_N[3] = {1, 0, 0};

  static void cross(const double a[3], const double b[3], double c[3])
  {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
  }
  void dcm_BN(double C[3][3]) const
  {
    const double* s = sigma;
    const double q = s[0] * s[0] + s[1] * s[1] + s[2] * s[2], S = 1 - q, d = (1 + q) * (1 + q);
    const double T[3][3] = {{0, -s[2], s[1]}, {s[2], 0, -s[0]}, {-s[1], s[0], 0}};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double T2 = 0;
        for (int k = 0; k < 3; k++) T2 += T[i][k] * T[k][j];
        C[i][j] = (i == j ? 1.0 : 0.0) + (8 * T2 - 4 * S * T[i][j]) / d;
      }
  }
  // state derivative for body torque L_B and wheel torques u
  void deriv(const double x[10], const double L[3], const double u[4], double dx[10]) const
  {
    const double* s = x;
    const double* w = x + 3;
    const double q = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
    double sw = s[0] * w[0] + s[1] * w[1] + s[2] * w[2], sxw[3];
    cross(s, w, sxw);
    for (int i = 0; i < 3; i++) dx[i] = 0.25 * ((1 - q) * w[i] + 2 * sxw[i] + 2 * s[i] * sw);
    double H[3], tq[3] = {L[0], L[1], L[2]};
    for (int i = 0; i < 3; i++) H[i] = kI[i] * w[i];
    for (int k = 0; k < 4; k++) {
      double g[3];
      acsfix::pyramid_axis(k, g);
      for (int i = 0; i < 3; i++) {
        H[i] += kJs * x[6 + k] * g[i];
        tq[i] -= u[k] * g[i];
      }
    }
    double wxH[3];
    cross(w, H, wxH);
    for (int i = 0; i < 3; i++) dx[3 + i] = (tq[i] - wxH[i]) / kI[i];
    for (int k = 0; k < 4; k++) dx[6 + k] = u[k] / kJs;
  }
  void rk4(double dt, const double L[3], const double u[4])
  {
    double x[10], k1[10], k2[10], k3[10], k4[10], t[10];
    for (int i = 0; i < 3; i++) {
      x[i] = sigma[i];
      x[3 + i] = omega[i];
    }
    for (int k = 0; k < 4; k++) x[6 + k] = Omega[k];
    deriv(x, L, u, k1);
    for (int i = 0; i < 10; i++) t[i] = x[i] + 0.5 * dt * k1[i];
    deriv(t, L, u, k2);
    for (int i = 0; i < 10; i++) t[i] = x[i] + 0.5 * dt * k2[i];
    deriv(t, L, u, k3);
    for (int i = 0; i < 10; i++) t[i] = x[i] + dt * k3[i];
    deriv(t, L, u, k4);
    for (int i = 0; i < 10; i++) x[i] += dt / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    const double q = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if (q > 1)
      for (int i = 0; i < 3; i++) x[i] = -x[i] / q;
    for (int i = 0; i < 3; i++) {
      sigma[i] = x[i];
      omega[i] = x[3 + i];
    }
    for (int k = 0; k < 4; k++) Omega[k] = x[6 + k];
  }
  // Sensors for one cycle (perfect): CSS = max(0, n . s_B) on the cube faces.
  void sense(uint64_t t_ns, FswAcsSensorMsg& m) const
  {
    std::memset(&m, 0, sizeof m);
    m.t_ns = t_ns;
    m.att_valid = 1;
    double C[3][3], sB[3];
    dcm_BN(C);
    for (int i = 0; i < 3; i++) {
      sB[i] = C[i][0] * sun_N[0] + C[i][1] * sun_N[1] + C[i][2] * sun_N[2];
      m.sigma_BN[i] = R(sigma[i]);
      m.omega_BN_B[i] = R(omega[i]);
    }
    for (int i = 0; i < 6; i++) {
      const double c = (i % 2 == 0 ? 1.0 : -1.0) * sB[i / 2];
      m.css[i] = R(c > 0 ? c : 0.0);
    }
    for (int k = 0; k < 4; k++) m.Omega[k] = R(Omega[k]);
  }
  // Apply one control period of commands with n_sub RK4 sub-steps.
  void apply(const FswAcsActuatorMsg& a, int n_sub = 5)
  {
    const double h = kPeriod / n_sub;
    for (int s = 0; s < n_sub; s++) {
      double L[3] = {0, 0, 0}, u[4] = {0, 0, 0, 0};
      if (a.wheels_active)
        for (int k = 0; k < 4; k++) u[k] = a.u_s[k];
      if (a.thrusters_active) {
        const double t0 = s * h;
        for (int j = 0; j < 8; j++) {
          // on-time overlap with this sub-step [t0, t0 + h): average force
          double on = a.t_on[j] - t0;
          on = on < 0 ? 0 : (on > h ? h : on);
          double d[3];
          cross(kThrR[j], kThrG[j], d);
          for (int i = 0; i < 3; i++) L[i] += kFmax * (on / h) * d[i];
        }
      }
      rk4(h, L, u);
    }
  }
  double error_angle_to(const fsw_real sigma_RN[3]) const
  {
    // principal angle of B relative to R, through the DCMs
    Plant r;
    for (int i = 0; i < 3; i++) r.sigma[i] = sigma_RN[i];
    double CB[3][3], CR[3][3];
    dcm_BN(CB);
    r.dcm_BN(CR);
    double tr = 0;
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++) tr += CB[i][k] * CR[i][k];
    double c = 0.5 * (tr - 1);
    c = c > 1 ? 1 : (c < -1 ? -1 : c);
    return std::acos(c);
  }
};

}  // namespace acsfix

#endif

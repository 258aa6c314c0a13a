// The FSW application fsw_acs with the magnetorquers, the orbit guidance and
// the momentum management (issue 38): configuration (every new flag and
// cross-check rejected by name, the geometry copies), DETUMBLE (rod
// commands in closed form, the held dipole, the autonomous exit and the
// edge-triggered mode command), NADIR (the feedforward torque at rest on a
// circular orbit, bad orbit input), the MAGNETORQUERS and THRUSTERS
// policies (what the wheels are asked for, rod limits, a dump closed
// against the fixture's plant), the set_policy command, error cycles, and
// rw_bias feeding rw_null.  Expected values come from the closed forms
// written here in plain double arithmetic, not from the modules.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "acs_fixture.hpp"
#include "fsw/fsw_acs.h"
#include "kestrel_test_support.h"

namespace {

using acsfix::kPeriod;
using acsfix::kPeriodNs;
using acsfix::R;
const double kTol = kt::tol(1e-12, 2e-5);
const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();
constexpr double kG0 = 9.80665;

// Big structs: static storage, not the (small, on bare metal) test stack.
FswAcsConfig g_cfg;
FswAcsState g_st, g_st2;
FswAcsSensorMsg g_sens;
FswAcsCmdMsg g_cmd;
FswAcsActuatorMsg g_act, g_act2;
FswAcsHealthMsg g_h, g_h2;

void cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const double a[3]) { return std::sqrt(dot(a, a)); }

bool actuators_safe(const FswAcsActuatorMsg& a)
{
  for (int i = 0; i < 3; i++)
    if (a.Lr_B[i] != 0) return false;
  for (int i = 0; i < FSW_MAX_RW; i++)
    if (a.u_s[i] != 0 || a.V[i] != 0) return false;
  for (int i = 0; i < FSW_MAX_THR; i++)
    if (a.F[i] != 0 || a.t_on[i] != 0) return false;
  for (int i = 0; i < FSW_MAX_MTQ; i++)
    if (a.m_cmd[i] != 0) return false;
  return a.wheels_active == 0 && a.thrusters_active == 0 && a.mtq_active == 0;
}

// Body torque the wheel motor torques put on the body is -sum u_i g_i;
// rw_map solves [Gs] u = -Lw, so sum u_i g_i must equal -Lw.
void wheel_sum(const FswAcsActuatorMsg& a, double s[3])
{
  s[0] = s[1] = s[2] = 0;
  for (int i = 0; i < 4; i++) {
    double g[3];
    acsfix::pyramid_axis(i, g);
    for (int k = 0; k < 3; k++) s[k] += static_cast<double>(a.u_s[i]) * g[k];
  }
}

// Wheel momentum sum J_s Omega_i g_i of the pyramid (all available).
void wheel_h(const double Om[4], double h[3])
{
  h[0] = h[1] = h[2] = 0;
  for (int i = 0; i < 4; i++) {
    double g[3];
    acsfix::pyramid_axis(i, g);
    for (int k = 0; k < 3; k++) h[k] += acsfix::kJs * Om[i] * g[k];
  }
}

// Sensors: CSS lit on +x +y +z (sun along (1,1,1)), attitude valid at sigma.
void sensors(FswAcsSensorMsg& m, uint64_t t_ns, const double w[3], const double B[3], int mag_valid)
{
  std::memset(&m, 0, sizeof m);
  m.t_ns = t_ns;
  m.att_valid = 1;
  const double c = 1.0 / std::sqrt(3.0);
  m.css[0] = m.css[2] = m.css[4] = R(c);
  for (int k = 0; k < 3; k++) {
    m.omega_BN_B[k] = R(w[k]);
    m.B_B[k] = R(B != nullptr ? B[k] : 0.0);
  }
  m.mag_valid = static_cast<uint8_t>(mag_valid);
}

void set_speeds(FswAcsSensorMsg& m, const double Om[4])
{
  for (int i = 0; i < 4; i++) m.Omega[i] = R(Om[i]);
}

void init_ok(const FswAcsConfig& c, FswAcsState& st)
{
  const char* bad = nullptr;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&st, &c, &bad)) << (bad != nullptr ? bad : "");
}

/* ---- configuration ---- */

struct BadCfg {
  const char* why;
  void (*spoil)(FswAcsConfig&);
  const char* field;
  FswStatus want;
};

const BadCfg kBadConfigs[] = {
    {"has_mtq not boolean", [](FswAcsConfig& c) { c.has_mtq = 2; }, "has_mtq", FSW_E_CONFIG},
    {"has_orbit not boolean", [](FswAcsConfig& c) { c.has_orbit = 2; }, "has_orbit", FSW_E_CONFIG},
    {"DETUMBLE without rods",
     [](FswAcsConfig& c) { c.has_mtq = 0; c.initial_mode = FSW_ACS_MODE_DETUMBLE; }, "initial_mode", FSW_E_CONFIG},
    {"NADIR without orbit", [](FswAcsConfig& c) { c.has_orbit = 0; c.initial_mode = FSW_ACS_MODE_NADIR; },
     "initial_mode", FSW_E_CONFIG},
    {"rod duty_max zero", [](FswAcsConfig& c) { c.mtq_map.duty_max = 0; }, "mtq_map", FSW_E_CONFIG},
    {"rod count above capacity", [](FswAcsConfig& c) { c.mtq_map.num_mtq = FSW_MAX_MTQ + 1; }, "mtq_map",
     FSW_E_CAPACITY},
    {"bdot re-entry below done", [](FswAcsConfig& c) { c.bdot.omega_reenter = R(0.005); }, "bdot", FSW_E_CONFIG},
    {"exit to DETUMBLE", [](FswAcsConfig& c) { c.detumble_exit_mode = FSW_ACS_MODE_DETUMBLE; },
     "detumble_exit_mode", FSW_E_CONFIG},
    {"exit to NADIR without orbit",
     [](FswAcsConfig& c) { c.has_orbit = 0; c.detumble_exit_mode = FSW_ACS_MODE_NADIR; }, "detumble_exit_mode",
     FSW_E_CONFIG},
    {"exit to unknown mode", [](FswAcsConfig& c) { c.detumble_exit_mode = 7; }, "detumble_exit_mode", FSW_E_CONFIG},
    {"exit mode -2", [](FswAcsConfig& c) { c.detumble_exit_mode = -2; }, "detumble_exit_mode", FSW_E_CONFIG},
    {"orbit variant", [](FswAcsConfig& c) { c.orbit.variant = 5; }, "orbit", FSW_E_CONFIG},
    {"orbit mu zero", [](FswAcsConfig& c) { c.orbit.mu = 0; }, "orbit", FSW_E_CONFIG},
    {"use_thr_mom not boolean", [](FswAcsConfig& c) { c.use_thr_mom = 2; }, "use_thr_mom", FSW_E_CONFIG},
    {"thruster dumps without thrusters",
     [](FswAcsConfig& c) { c.use_thr_mom = 1; c.has_thrusters = 0; }, "use_thr_mom", FSW_E_CONFIG},
    {"thruster dumps with off-pulsing thrusters",
     [](FswAcsConfig& c) {
       c.use_thr_mom = 1;
       c.thr_map.thr_force_sign = -1;
       c.pulse_rem.common.base_thrust_state = 1;
     },
     "use_thr_mom", FSW_E_CONFIG},
    {"thr_mom Isp zero", [](FswAcsConfig& c) { c.use_thr_mom = 1; c.thr_mom.Isp = 0; }, "thr_mom", FSW_E_CONFIG},
    {"thr_mom axis copy differs",
     [](FswAcsConfig& c) { c.use_thr_mom = 1; c.thr_mom.gs_hat_B[1][0] = -c.thr_mom.gs_hat_B[1][0]; },
     "thr_mom.gs_hat_B", FSW_E_CONFIG},
    {"thr_mom J_s copy differs", [](FswAcsConfig& c) { c.use_thr_mom = 1; c.thr_mom.J_s[2] *= 2; }, "thr_mom.J_s",
     FSW_E_CONFIG},
    {"thr_mom thruster count",
     [](FswAcsConfig& c) { c.use_thr_mom = 1; c.thr_mom.num_thr = 7; }, "thr_mom.num_thr", FSW_E_CONFIG},
    {"use_mtq_desat not boolean", [](FswAcsConfig& c) { c.use_mtq_desat = 3; }, "use_mtq_desat", FSW_E_CONFIG},
    {"rod desaturation without rods",
     [](FswAcsConfig& c) { c.use_mtq_desat = 1; c.has_mtq = 0; c.detumble_exit_mode = -1; }, "use_mtq_desat",
     FSW_E_CONFIG},
    {"mtq_desat gain zero", [](FswAcsConfig& c) { c.use_mtq_desat = 1; c.mtq_desat.k_desat = 0; }, "mtq_desat",
     FSW_E_CONFIG},
    {"mtq_desat axis copy differs",
     [](FswAcsConfig& c) { c.use_mtq_desat = 1; c.mtq_desat.gs_hat_B[0][2] = -c.mtq_desat.gs_hat_B[0][2]; },
     "mtq_desat.gs_hat_B", FSW_E_CONFIG},
    {"mtq_desat J_s copy differs", [](FswAcsConfig& c) { c.use_mtq_desat = 1; c.mtq_desat.J_s[0] *= 3; },
     "mtq_desat.J_s", FSW_E_CONFIG},
    {"use_bias not boolean", [](FswAcsConfig& c) { c.use_bias = 2; }, "use_bias", FSW_E_CONFIG},
    {"bias without null motion", [](FswAcsConfig& c) { c.use_bias = 1; c.use_null = 0; }, "use_bias", FSW_E_CONFIG},
    {"bias keep-out zero",
     [](FswAcsConfig& c) { c.use_null = 1; c.use_bias = 1; c.rw_bias.Omega_keepout = 0; }, "rw_bias", FSW_E_CONFIG},
    {"bias axis copy differs",
     [](FswAcsConfig& c) { c.use_null = 1; c.use_bias = 1; c.rw_bias.gs_hat_B[3][1] = -c.rw_bias.gs_hat_B[3][1]; },
     "rw_bias.gs_hat_B", FSW_E_CONFIG},
    {"THRUSTERS policy not configured", [](FswAcsConfig& c) { c.initial_policy = FSW_ACS_MOM_THRUSTERS; },
     "initial_policy", FSW_E_CONFIG},
    {"MAGNETORQUERS policy not configured", [](FswAcsConfig& c) { c.initial_policy = FSW_ACS_MOM_MAGNETORQUERS; },
     "initial_policy", FSW_E_CONFIG},
    {"unknown policy", [](FswAcsConfig& c) { c.initial_policy = 3; }, "initial_policy", FSW_E_CONFIG},
};

// Verifies: REQ-ACS-001, REQ-ACS-002
TEST(FswAcsMomentumConfig, EveryNewFlagAndCrossCheckIsRejectedByName)
{
  for (const BadCfg& b : kBadConfigs) {
    acsfix::full_config(g_cfg);
    b.spoil(g_cfg);
    const char* field = nullptr;
    EXPECT_EQ(b.want, fsw_acs_check(&g_cfg, &field)) << b.why;
    ASSERT_NE(nullptr, field) << b.why;
    EXPECT_EQ(std::string(b.field), field) << b.why;
    EXPECT_EQ(b.want, fsw_acs_init(&g_st, &g_cfg, nullptr)) << b.why;
    EXPECT_EQ(0, g_st.ready) << b.why;
  }
}

// Verifies: REQ-ACS-002
TEST(FswAcsMomentumConfig, EverythingOnAndEveryModeIsAccepted)
{
  const int modes[] = {FSW_ACS_MODE_SUN_SAFE, FSW_ACS_MODE_INERTIAL, FSW_ACS_MODE_DETUMBLE, FSW_ACS_MODE_NADIR};
  const int exits[] = {-1, FSW_ACS_MODE_SUN_SAFE, FSW_ACS_MODE_INERTIAL, FSW_ACS_MODE_NADIR};
  for (int m : modes)
    for (int e : exits)
      for (int p = 0; p < 3; p++) {
        acsfix::full_config(g_cfg);
        g_cfg.use_null = g_cfg.use_bias = g_cfg.use_thr_mom = g_cfg.use_mtq_desat = 1;
        g_cfg.initial_mode = m;
        g_cfg.detumble_exit_mode = e;
        g_cfg.initial_policy = p;
        const char* bad = "x";
        EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &bad)) << m << " " << e << " " << p;
        EXPECT_EQ(nullptr, bad);
      }
  // without rods the exit mode is not read: any value is accepted
  acsfix::full_config(g_cfg);
  g_cfg.has_mtq = 0;
  g_cfg.detumble_exit_mode = 99;
  EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, nullptr));
}

// Verifies: REQ-ACS-003
TEST(FswAcsMomentumConfig, SetGeometryWritesTheRodAndWheelCopies)
{
  FswAcsGeometry g;
  acsfix::full_geometry(g);
  std::memset(&g_cfg, 0x5a, sizeof g_cfg);  // garbage beyond the counts must become 0
  ASSERT_EQ(FSW_OK, fsw_acs_config_set_geometry(&g_cfg, &g));
  EXPECT_EQ(1, g_cfg.has_mtq);
  EXPECT_EQ(3, g_cfg.mtq_map.num_mtq);
  for (int i = 0; i < FSW_MAX_MTQ; i++) {
    double a[3] = {0, 0, 0};
    if (i < 3) acsfix::rod_axis(i, a);
    for (int k = 0; k < 3; k++) EXPECT_EQ(R(a[k]), g_cfg.mtq_map.gt_hat_B[i][k]) << i;
    EXPECT_EQ(R(i < 3 ? acsfix::kRodMmax : 0.0), g_cfg.mtq_map.m_max[i]) << i;
  }
  EXPECT_EQ(4, g_cfg.thr_mom.num_rw);
  EXPECT_EQ(4, g_cfg.mtq_desat.num_rw);
  EXPECT_EQ(4, g_cfg.rw_bias.num_rw);
  EXPECT_EQ(8, g_cfg.thr_mom.num_thr);
  for (int i = 0; i < FSW_MAX_RW; i++) {
    double a[3] = {0, 0, 0};
    if (i < 4) acsfix::pyramid_axis(i, a);
    for (int k = 0; k < 3; k++) {
      EXPECT_EQ(R(a[k]), g_cfg.thr_mom.gs_hat_B[i][k]);
      EXPECT_EQ(R(a[k]), g_cfg.mtq_desat.gs_hat_B[i][k]);
      EXPECT_EQ(R(a[k]), g_cfg.rw_bias.gs_hat_B[i][k]);
    }
    EXPECT_EQ(R(i < 4 ? acsfix::kJs : 0.0), g_cfg.thr_mom.J_s[i]);
    EXPECT_EQ(R(i < 4 ? acsfix::kJs : 0.0), g_cfg.mtq_desat.J_s[i]);
  }
  for (int j = 0; j < FSW_MAX_THR; j++) EXPECT_EQ(R(j < 8 ? acsfix::kFmax : 0.0), g_cfg.thr_mom.F_max[j]);

  // no rods: has_mtq = 0; bad counts leave the config unchanged
  g.num_mtq = 0;
  ASSERT_EQ(FSW_OK, fsw_acs_config_set_geometry(&g_cfg, &g));
  EXPECT_EQ(0, g_cfg.has_mtq);
  EXPECT_EQ(0, g_cfg.mtq_map.num_mtq);
  EXPECT_EQ(R(0.0), g_cfg.mtq_map.m_max[0]);
  static FswAcsConfig before;
  before = g_cfg;
  g.num_mtq = FSW_MAX_MTQ + 1;
  EXPECT_EQ(FSW_E_CAPACITY, fsw_acs_config_set_geometry(&g_cfg, &g));
  g.num_mtq = -1;
  EXPECT_EQ(FSW_E_CONFIG, fsw_acs_config_set_geometry(&g_cfg, &g));
  EXPECT_EQ(0, std::memcmp(&before, &g_cfg, sizeof g_cfg));
}

/* ---- DETUMBLE ---- */

// The rods for a body dipole m, by hand: c_i = a_i . m (the rods are
// orthonormal, G^+ = G^T), one common factor to duty_max m_max, the torque
// (sum c_i a_i) x B.  Returns whether the factor was < 1.
bool rods_expect(const double m[3], const double B[3], double c[3], double tau[3])
{
  double s = 1.0;
  for (int i = 0; i < 3; i++) {
    double a[3];
    acsfix::rod_axis(i, a);
    c[i] = dot(a, m);
    const double lim = acsfix::kRodDuty * acsfix::kRodMmax;
    if (std::fabs(c[i]) > lim) s = std::fmin(s, lim / std::fabs(c[i]));
  }
  double mach[3] = {0, 0, 0};
  for (int i = 0; i < 3; i++) {
    double a[3];
    acsfix::rod_axis(i, a);
    c[i] *= s;
    for (int q = 0; q < 3; q++) mach[q] += c[i] * a[q];
  }
  cross(mach, B, tau);
  return s < 1.0;
}

// The rod commands of the gyro law, by hand: m = k (omega x B), bdot's
// per-B-axis limit (common factor), then the rods (rods_expect).
void detumble_expect(double k, const double w[3], const double B[3], double c[3], double tau[3])
{
  double m[3];
  cross(w, B, m);
  double s1 = 1.0;
  for (int i = 0; i < 3; i++) {
    m[i] *= k;
    if (std::fabs(m[i]) > 1000.0) s1 = std::fmin(s1, 1000.0 / std::fabs(m[i]));
  }
  for (int i = 0; i < 3; i++) m[i] *= s1;
  (void)rods_expect(m, B, c, tau);
}

// Verifies: REQ-ACS-009
TEST(FswAcsDetumble, RodCommandsAreTheGyroLawClosedForm)
{
  const double w[3] = {0.02, -0.01, 0.03}, B[3] = {2e-5, 1e-5, -3e-5};
  for (double k : {1e6, 1e9}) {  // 1e9: both bdot's and the rods' limits act
    acsfix::full_config(g_cfg);
    g_cfg.initial_mode = FSW_ACS_MODE_DETUMBLE;
    g_cfg.bdot.k_bdot = R(k);
    init_ok(g_cfg, g_st);
    sensors(g_sens, 0, w, B, 1);
    const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
    EXPECT_EQ(k > 1e7 ? FSW_W_SAT : FSW_OK, s);
    double c[3], tau[3];
    detumble_expect(k, w, B, c, tau);
    for (int i = 0; i < 3; i++) {
      EXPECT_NEAR(c[i], g_act.m_cmd[i], kTol * (1 + std::fabs(c[i]))) << k << " rod " << i;
      EXPECT_LE(std::fabs(g_act.m_cmd[i]), acsfix::kRodDuty * acsfix::kRodMmax * (1 + 1e-12));
      EXPECT_NEAR(tau[i], g_h.tau_mtq_B[i], kTol * 1e-3) << k;
    }
    for (int i = 3; i < FSW_MAX_MTQ; i++) EXPECT_EQ(R(0.0), g_act.m_cmd[i]);
    EXPECT_EQ(1, g_act.mtq_active);
    EXPECT_EQ(1, g_act.wheels_active);
    EXPECT_EQ(0, g_act.thrusters_active);
    for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(R(0.0), g_act.u_s[i]);
    for (int i = 0; i < 3; i++) EXPECT_EQ(R(0.0), g_act.Lr_B[i]);
    EXPECT_EQ(FSW_ACS_MODE_DETUMBLE, g_h.mode);
    EXPECT_NEAR(norm(w), g_h.rate_est, kTol);
    // energy: the torque removes rotational energy, omega . tau < 0
    EXPECT_LT(dot(w, tau), 0.0);
  }
}

// Verifies: REQ-ACS-009
TEST(FswAcsDetumble, AMissedSampleMapsTheHeldDipoleWithTheLastField)
{
  const double w[3] = {0.02, -0.01, 0.03}, B[3] = {2e-5, 1e-5, -3e-5}, B2[3] = {-4e-5, 2e-5, 1e-5};
  acsfix::full_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_DETUMBLE;
  init_ok(g_cfg, g_st);
  // no field sample yet: no dipole, rods off (commands 0)
  sensors(g_sens, 0, w, B, 0);
  fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
  EXPECT_EQ(0, g_h.safe_output);
  for (int i = 0; i < 3; i++) EXPECT_EQ(R(0.0), g_act.m_cmd[i]);
  sensors(g_sens, kPeriodNs, w, B, 1);
  ASSERT_EQ(FSW_OK, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  double c[3], tau[3];
  detumble_expect(1e6, w, B, c, tau);
  // missed sample with a different (stale, unread) B_B and rate: bdot holds
  // its dipole, the rods map it in the last valid field
  const double w2[3] = {0.05, 0.0, 0.0};
  sensors(g_sens, 2 * kPeriodNs, w2, B2, 0);
  EXPECT_EQ(FSW_W_RATE, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  for (int i = 0; i < 3; i++) {
    EXPECT_NEAR(c[i], g_act.m_cmd[i], kTol * (1 + std::fabs(c[i])));
    EXPECT_NEAR(tau[i], g_h.tau_mtq_B[i], kTol * 1e-3);
  }
  EXPECT_EQ(1, g_act.mtq_active);
  EXPECT_EQ(FSW_ACS_MODE_DETUMBLE, g_h.mode);
}

// Verifies: REQ-ACS-008
TEST(FswAcsDetumble, DetumbledExitsAndTheModeCommandIsEdgeTriggered)
{
  const double w[3] = {0.001, 0.0, -0.002}, B[3] = {2e-5, 1e-5, -3e-5};
  acsfix::full_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_DETUMBLE;
  init_ok(g_cfg, g_st);
  std::memset(&g_cmd, 0, sizeof g_cmd);
  g_cmd.mode = FSW_ACS_MODE_DETUMBLE;  // sent every cycle, like a link node
  g_cmd.actuation = FSW_ACS_ACT_WHEELS;
  // |omega| = 2.2 mrad/s < omega_done: t_below 0, 0.5, 1.0 s -> detumbled at
  // the third cycle (t_persist 1 s), which still flies DETUMBLE and reports
  // the exit mode for the next
  for (int k = 0; k < 3; k++) {
    sensors(g_sens, k * kPeriodNs, w, B, 1);
    ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g_cmd, &g_act, &g_h), 0);
    EXPECT_EQ(1, g_act.mtq_active) << k;
    EXPECT_EQ(k == 2 ? 1 : 0, g_h.detumbled) << k;
    EXPECT_EQ(k == 2 ? FSW_ACS_MODE_SUN_SAFE : FSW_ACS_MODE_DETUMBLE, g_h.mode) << k;
    EXPECT_EQ(k == 2 ? 1u : 0u, g_h.mode_changes) << k;
  }
  // the repeated DETUMBLE command does not undo the exit
  for (int k = 3; k < 6; k++) {
    sensors(g_sens, k * kPeriodNs, w, B, 1);
    ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g_cmd, &g_act, &g_h), 0);
    EXPECT_EQ(FSW_ACS_MODE_SUN_SAFE, g_h.mode) << k;
    EXPECT_EQ(0, g_act.mtq_active) << k;
    EXPECT_EQ(1, g_h.sun_valid) << k;
    EXPECT_EQ(1u, g_h.mode_changes) << k;
  }
  // a different command acts (SUN_SAFE: already flown, no transition) ...
  g_cmd.mode = FSW_ACS_MODE_SUN_SAFE;
  sensors(g_sens, 6 * kPeriodNs, w, B, 1);
  ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g_cmd, &g_act, &g_h), 0);
  EXPECT_EQ(FSW_ACS_MODE_SUN_SAFE, g_h.mode);
  EXPECT_EQ(1u, g_h.mode_changes);
  // ... and DETUMBLE again re-enters
  g_cmd.mode = FSW_ACS_MODE_DETUMBLE;
  sensors(g_sens, 7 * kPeriodNs, w, B, 1);
  ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g_cmd, &g_act, &g_h), 0);
  EXPECT_EQ(FSW_ACS_MODE_DETUMBLE, g_h.mode);
  EXPECT_EQ(2u, g_h.mode_changes);
  EXPECT_EQ(1, g_act.mtq_active);
  EXPECT_EQ(0, g_h.detumbled);  // a fresh persistence timer

  // exit mode -1: stays in DETUMBLE however long it is detumbled
  g_cfg.detumble_exit_mode = -1;
  init_ok(g_cfg, g_st);
  for (int k = 0; k < 8; k++) {
    sensors(g_sens, k * kPeriodNs, w, B, 1);
    ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h), 0);
  }
  EXPECT_EQ(1, g_h.detumbled);
  EXPECT_EQ(FSW_ACS_MODE_DETUMBLE, g_h.mode);
  EXPECT_EQ(0u, g_h.mode_changes);
}

/* ---- NADIR ---- */

// Circular equatorial orbit r = (a, 0, 0), v = (0, sqrt(mu/a), 0): the orbit
// frame's rows are R1 = y_N (along track), R2 = -z_N (-h), R3 = -x_N (nadir),
// so [RN] = [[0,1,0],[0,0,-1],[-1,0,0]], whose quaternion (Shepperd, q0 =
// sqrt(1 + tr)/2 = 1/2) is (1/2, -1/2, -1/2, 1/2) and MRP q/(1 + q0) =
// (-1/3, -1/3, 1/3).  omega_RN = h/r^2 = n z_N, in B (= R): (0, -n, 0).
constexpr double kA = 7.0e6;
void nadir_sensors(FswAcsSensorMsg& m, uint64_t t_ns, const double Om[4])
{
  const double n = std::sqrt(acsfix::kMu / kA) / kA;
  const double w[3] = {0.0, -n, 0.0};
  sensors(m, t_ns, w, nullptr, 0);
  m.sigma_BN[0] = m.sigma_BN[1] = R(-1.0 / 3.0);
  m.sigma_BN[2] = R(1.0 / 3.0);
  m.r_N[0] = R(kA);
  m.v_N[1] = R(std::sqrt(acsfix::kMu / kA));
  m.orbit_valid = 1;
  set_speeds(m, Om);
}

// Init in NADIR and one accepted cycle at rest in the orbit frame.
void nadir_first_cycle(const double Om[4])
{
  acsfix::full_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_NADIR;
  init_ok(g_cfg, g_st);
  nadir_sensors(g_sens, 0, Om);
  ASSERT_EQ(FSW_OK, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
}

// Verifies: REQ-ACS-010
TEST(FswAcsNadir, AtRestInTheOrbitFrameTheTorqueIsTheFeedforwardOnly)
{
  // the MRP above is [RN]: check it against the fixture's independent DCM
  {
    acsfix::Plant p;
    p.sigma[0] = p.sigma[1] = -1.0 / 3.0;
    p.sigma[2] = 1.0 / 3.0;
    double C[3][3];
    p.dcm_BN(C);
    const double RN[3][3] = {{0, 1, 0}, {0, 0, -1}, {-1, 0, 0}};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) ASSERT_NEAR(RN[i][j], C[i][j], 1e-15);
  }
  const double Om[4] = {30.0, -20.0, 10.0, 5.0};
  ASSERT_NO_FATAL_FAILURE(nadir_first_cycle(Om));
  // sigma_BR = 0, omega_BR = 0, circular (omega_dot_RN = 0), K_i off:
  //   Lr = -(-omega_RN x H + [I](omega x omega_RN)) = omega_RN x H,
  //   H = [I] omega + sum J_s (g . omega + Omega_i) g,   omega = omega_RN
  const double n = std::sqrt(acsfix::kMu / kA) / kA;
  const double w[3] = {0.0, -n, 0.0};
  double H[3];
  for (int k = 0; k < 3; k++) H[k] = acsfix::kI[k] * w[k];
  for (int i = 0; i < 4; i++) {
    double g[3];
    acsfix::pyramid_axis(i, g);
    const double hs = acsfix::kJs * (dot(g, w) + Om[i]);
    for (int k = 0; k < 3; k++) H[k] += hs * g[k];
  }
  double L[3];
  cross(w, H, L);
  ASSERT_GT(norm(L), 1e-4);  // not trivially zero: the wheels' momentum
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(0.0, g_h.sigma_BR[k], kt::tol(1e-14, 1e-6));
    EXPECT_NEAR(0.0, g_h.omega_BR_B[k], kt::tol(1e-17, 1e-9));
    EXPECT_NEAR(L[k], g_act.Lr_B[k], kt::tol(1e-12, 1e-7)) << k;
  }
  // and the wheels deliver it: sum u g = -Lr
  double s[3];
  wheel_sum(g_act, s);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(-L[k], s[k], kt::tol(1e-12, 1e-7));
  EXPECT_EQ(1, g_act.wheels_active);
  EXPECT_EQ(0, g_act.mtq_active);
  EXPECT_EQ(FSW_ACS_MODE_NADIR, g_h.mode);
}

// Verifies: REQ-ACS-010
TEST(FswAcsNadir, BadOrbitInputGivesTheSafeOutputAndNoStateChange)
{
  const double Om[4] = {30.0, -20.0, 10.0, 5.0};
  ASSERT_NO_FATAL_FAILURE(nadir_first_cycle(Om));
  g_st2 = g_st;
  struct Spoil {
    const char* why;
    void (*f)(FswAcsSensorMsg&);
  };
  const Spoil spoils[] = {
      {"orbit_valid 0", [](FswAcsSensorMsg& m) { m.orbit_valid = 0; }},
      {"orbit_valid 2", [](FswAcsSensorMsg& m) { m.orbit_valid = 2; }},
      {"NaN r", [](FswAcsSensorMsg& m) { m.r_N[1] = kNaN; }},
      {"inf v", [](FswAcsSensorMsg& m) { m.v_N[2] = std::numeric_limits<fsw_real>::infinity(); }},
      {"r parallel to v (guid_orbit)", [](FswAcsSensorMsg& m) { m.v_N[0] = R(7000.0), m.v_N[1] = 0; }},
      {"attitude invalid", [](FswAcsSensorMsg& m) { m.att_valid = 0; }},
  };
  for (const Spoil& sp : spoils) {
    nadir_sensors(g_sens, kPeriodNs, Om);
    sp.f(g_sens);
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)) << sp.why;
    EXPECT_TRUE(actuators_safe(g_act)) << sp.why;
    EXPECT_EQ(1, g_h.safe_output) << sp.why;
    EXPECT_EQ(1u, g_h.cycles) << sp.why;
    EXPECT_EQ(FSW_ACS_MODE_NADIR, g_h.mode) << sp.why;
    EXPECT_EQ(0, std::memcmp(&g_st.mrp_fb.int_sigma, &g_st2.mrp_fb.int_sigma, sizeof g_st.mrp_fb.int_sigma));
    EXPECT_EQ(g_st2.clock.t_prev_ns, g_st.clock.t_prev_ns) << sp.why;
  }
  // the good retry at the same time stamp is accepted
  nadir_sensors(g_sens, kPeriodNs, Om);
  EXPECT_EQ(FSW_OK, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
}

/* ---- MAGNETORQUERS policy ---- */

// What mtq_desat -> mtq_map give, by hand: h_err = h_w, tau_req = -k h_perp
// (|tau_req| <= tau_max = 1 here), m = (B x tau_req)/|B|^2, then the rods
// (rods_expect).
void desat_expect(double k, const double Om[4], const double B[3], double c[3], double tau[3], bool& saturated)
{
  double h[3], b[3], tr[3], m[3];
  wheel_h(Om, h);
  const double Bn = norm(B);
  for (int q = 0; q < 3; q++) b[q] = B[q] / Bn;
  const double hb = dot(h, b);
  for (int q = 0; q < 3; q++) tr[q] = -k * (h[q] - hb * b[q]);
  cross(B, tr, m);
  for (int q = 0; q < 3; q++) m[q] /= Bn * Bn;
  saturated = rods_expect(m, B, c, tau);
}

// Verifies: REQ-ACS-011
TEST(FswAcsMtqPolicy, TheWheelsAreAskedForLrMinusTheRodTorque)
{
  const double Om[4] = {100.0, -50.0, 30.0, -20.0}, B[3] = {2e-5, 1e-5, -3e-5};
  const double w[3] = {1e-4, -2e-4, 5e-5};
  for (double k : {1e-4, 1e-2}) {  // 1e-2: the rods saturate
    acsfix::full_config(g_cfg);
    g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
    g_cfg.use_mtq_desat = 1;
    g_cfg.initial_policy = FSW_ACS_MOM_MAGNETORQUERS;
    g_cfg.mtq_desat.k_desat = R(k);
    init_ok(g_cfg, g_st);
    sensors(g_sens, 0, w, B, 1);
    set_speeds(g_sens, Om);
    for (int q = 0; q < 3; q++) g_sens.sigma_BN[q] = g_cfg.inertial.sigma_R0N[q];
    const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
    double c[3], tau[3];
    bool sat = false;
    desat_expect(k, Om, B, c, tau, sat);
    EXPECT_EQ(k > 1e-3, sat);
    EXPECT_EQ(sat ? FSW_W_SAT : FSW_OK, s) << k;
    EXPECT_EQ(FSW_ACS_MOM_MAGNETORQUERS, g_h.policy);
    EXPECT_EQ(1, g_act.mtq_active);
    EXPECT_EQ(1, g_act.wheels_active);
    double Bt[3];
    for (int q = 0; q < 3; q++) Bt[q] = g_h.tau_mtq_B[q];
    for (int i = 0; i < 3; i++) {
      EXPECT_NEAR(c[i], g_act.m_cmd[i], kTol * (1 + std::fabs(c[i]))) << k << " rod " << i;
      EXPECT_LE(std::fabs(g_act.m_cmd[i]), acsfix::kRodDuty * acsfix::kRodMmax * (1 + 1e-12));
      EXPECT_NEAR(tau[i], g_h.tau_mtq_B[i], kTol * 1e-2) << k;
    }
    // the rod torque is perpendicular to B
    EXPECT_LE(std::fabs(dot(Bt, B)), kTol * norm(Bt) * norm(B));
    // and it reduces the wheel momentum: h . tau_ach < 0
    double h[3];
    wheel_h(Om, h);
    EXPECT_LT(dot(h, Bt), 0.0);
    // min-norm mapping of Lw = Lr - tau_ach: sum u g = -(Lr - tau_ach)
    double su[3];
    wheel_sum(g_act, su);
    for (int q = 0; q < 3; q++)
      EXPECT_NEAR(-(static_cast<double>(g_act.Lr_B[q]) - tau[q]), su[q], kt::tol(1e-12, 1e-7)) << k << " " << q;
    ASSERT_GT(norm(tau), 1e-5);  // the check above is not the bare -Lr one
  }
}

// Verifies: REQ-ACS-011
TEST(FswAcsMtqPolicy, WithoutAFieldSampleTheRodsAreOffAndTheWheelsGetLr)
{
  const double Om[4] = {100.0, -50.0, 30.0, -20.0}, B[3] = {2e-5, 1e-5, -3e-5};
  const double w[3] = {1e-4, -2e-4, 5e-5};
  acsfix::full_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  g_cfg.use_mtq_desat = 1;
  g_cfg.initial_policy = FSW_ACS_MOM_MAGNETORQUERS;
  init_ok(g_cfg, g_st);
  sensors(g_sens, 0, w, B, 0);
  g_sens.B_B[0] = kNaN;  // not read when mag_valid = 0
  set_speeds(g_sens, Om);
  for (int q = 0; q < 3; q++) g_sens.sigma_BN[q] = g_cfg.inertial.sigma_R0N[q];
  ASSERT_EQ(FSW_OK, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  for (int i = 0; i < FSW_MAX_MTQ; i++) EXPECT_EQ(R(0.0), g_act.m_cmd[i]);
  for (int q = 0; q < 3; q++) EXPECT_EQ(R(0.0), g_h.tau_mtq_B[q]);
  double su[3];
  wheel_sum(g_act, su);
  ASSERT_GT(std::fabs(g_act.Lr_B[0]), 1e-4);
  for (int q = 0; q < 3; q++) EXPECT_NEAR(-static_cast<double>(g_act.Lr_B[q]), su[q], kt::tol(1e-12, 1e-7));
  // a flagged-valid non-finite field is bad input
  g_sens.t_ns = kPeriodNs;
  g_sens.mag_valid = 1;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(actuators_safe(g_act));
}

/* ---- THRUSTERS policy ---- */

void thr_config(FswAcsConfig& c)
{
  acsfix::full_config(c);
  c.initial_mode = FSW_ACS_MODE_INERTIAL;
  c.use_thr_mom = 1;
  c.initial_policy = FSW_ACS_MOM_THRUSTERS;
}

// Omega with |h_w| = 5.86 N m s > h_upper = 4.
const double kDumpOm[4] = {60.0, -40.0, 20.0, 10.0};

void at_reference(FswAcsSensorMsg& m, const FswAcsConfig& c, uint64_t t, const double Om[4])
{
  const double w[3] = {0, 0, 0};
  sensors(m, t, w, nullptr, 0);
  set_speeds(m, Om);
  for (int q = 0; q < 3; q++) m.sigma_BN[q] = c.inertial.sigma_R0N[q];
}

// Verifies: REQ-ACS-011
TEST(FswAcsThrPolicy, AWheelMomentumAboveTheThresholdStartsADump)
{
  thr_config(g_cfg);
  init_ok(g_cfg, g_st);
  double h[3];
  wheel_h(kDumpOm, h);
  const double hn = norm(h);
  ASSERT_GT(hn, 4.0);
  // The pulser has no period in its first cycle (it commands nothing), so
  // that cycle starts no dump; the next one does.
  at_reference(g_sens, g_cfg, 0, kDumpOm);
  ASSERT_EQ(FSW_OK, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_EQ(FSW_THR_MOM_IDLE, g_h.dump_phase);
  EXPECT_EQ(0, g_act.thrusters_active);
  at_reference(g_sens, g_cfg, kPeriodNs, kDumpOm);
  ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h), 0);
  EXPECT_EQ(FSW_THR_MOM_PULSE, g_h.dump_phase);
  EXPECT_EQ(1, g_act.thrusters_active);
  EXPECT_EQ(1, g_act.wheels_active);
  // L_thr = -L_dump h/|h| (a full cycle's impulse of the first pulse)
  double L[3];
  for (int q = 0; q < 3; q++) L[q] = -0.2 * h[q] / hn;
  // forces: sum F_j (r_j x g_j) = L_thr; on-times F_j/F_max T (or carried)
  double LF[3] = {0, 0, 0}, Lt[3] = {0, 0, 0}, carried = 0;
  for (int j = 0; j < 8; j++) {
    double d[3];
    cross(acsfix::kThrR[j], acsfix::kThrG[j], d);
    const double F = g_act.F[j], ton = F / acsfix::kFmax * kPeriod;
    EXPECT_GE(F, 0.0);
    for (int q = 0; q < 3; q++) {
      LF[q] += F * d[q];
      Lt[q] += g_act.t_on[j] / kPeriod * acsfix::kFmax * d[q];
    }
    if (ton >= 0.02) {
      EXPECT_NEAR(ton, g_act.t_on[j], kt::tol(1e-12, 1e-6)) << j;
    } else {
      EXPECT_EQ(R(0.0), g_act.t_on[j]) << j;
      carried += F * norm(d);
    }
  }
  for (int q = 0; q < 3; q++) {
    EXPECT_NEAR(L[q], LF[q], kt::tol(1e-9, 1e-5)) << q;
    EXPECT_NEAR(L[q], Lt[q], carried + kt::tol(1e-9, 1e-5)) << q;
  }
  // the wheels are asked for Lr - L_thr: sum u g = -(Lr - L_thr)
  double su[3];
  wheel_sum(g_act, su);
  for (int q = 0; q < 3; q++)
    EXPECT_NEAR(-(static_cast<double>(g_act.Lr_B[q]) - L[q]), su[q], kt::tol(1e-12, 1e-6)) << q;
}

// Verifies: REQ-ACS-011
TEST(FswAcsThrPolicy, ADumpClosedAgainstThePlantEndsNearHLowerAndCountsItsPropellant)
{
  thr_config(g_cfg);
  init_ok(g_cfg, g_st);
  acsfix::Plant p;
  for (int q = 0; q < 3; q++) p.sigma[q] = g_cfg.inertial.sigma_R0N[q];
  for (int i = 0; i < 4; i++) p.Omega[i] = kDumpOm[i];
  double h0[3];
  wheel_h(kDumpOm, h0);
  double prop = 0, max_err = 0;
  int k = 0, pulses_cycles = 0;
  for (; k < 400; k++) {
    p.sense(k * kPeriodNs, g_sens);
    ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h), 0) << k;
    max_err = std::fmax(max_err, p.error_angle_to(g_cfg.inertial.sigma_R0N));
    if (g_h.dumps == 1) break;
    if (g_act.thrusters_active) {
      pulses_cycles++;
      for (int j = 0; j < 8; j++) prop += acsfix::kFmax * g_act.t_on[j] / (200.0 * kG0);
    }
    p.apply(g_act);
  }
  ASSERT_EQ(1u, g_h.dumps) << "no dump completed in " << k << " cycles";
  EXPECT_EQ(FSW_THR_MOM_IDLE, g_h.dump_phase);
  // |Delta_H| = |h0| - h_lower = 4.86 N m s at L_dump = 0.2 N m: 24.3 s of
  // pulses, i.e. 49 commanding cycles (the last a partial one) at least
  const double dH = norm(h0) - 1.0;
  EXPECT_GE(pulses_cycles, static_cast<int>(std::ceil(dH / (0.2 * kPeriod))) - 1);
  EXPECT_NEAR(prop, g_h.prop_used, 1e-9 + kt::tol(1e-12, 1e-5) * prop);
  // propellant bound: every thruster pair gives at most |r x g| <= 1.98 m of
  // lever, so the thrust impulse is at least dH / 1.98
  EXPECT_GT(prop, dH / (1.98 * 200.0 * kG0));
  // the wheels end near h_lower: what is left undelivered is below one
  // minimum pulse (L_dump t_min_pulse = 0.1 N m s), the pulser carries below
  // t_min (0.02 s x 1 N x 1.98 m per thruster)
  double hf[3];
  wheel_h(p.Omega, hf);
  std::printf("dump: %d cycles, %d thrusting, |h| %.4f -> %.4f N m s, prop %.6g kg, max error %.4g deg\n", k,
              pulses_cycles, norm(h0), norm(hf), prop, max_err * 180 / acsfix::kPi);
  // the dump never removes more than Delta_H (a pulser period longer than
  // the control period over-commanded every pulse's first cycle: 0.71 N m s
  // at the end before 2026-12-05), and leaves less than one minimum pulse
  // plus the pulser's carried remainders (< t_min F_max |r x g| = 0.04 each)
  EXPECT_GT(norm(hf), 1.0 - 0.01);
  EXPECT_LT(norm(hf), 1.0 + 0.1 + 8 * 0.02 * 1.98);
  // the wheels hold the attitude through the dump (0.52 deg with the stale
  // pulser period)
  EXPECT_LT(max_err, 0.2 * acsfix::kPi / 180);
}

/* ---- set_policy command ---- */

// Verifies: REQ-ACS-011
TEST(FswAcsPolicyCommand, SetPolicySwitchesAndBadValuesAreBadInput)
{
  acsfix::full_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  g_cfg.use_mtq_desat = 1;
  init_ok(g_cfg, g_st);
  const double Om[4] = {100.0, -50.0, 30.0, -20.0}, B[3] = {2e-5, 1e-5, -3e-5}, w[3] = {0, 0, 0};
  uint64_t t = 0;
  auto run = [&](int set, int pol) {
    sensors(g_sens, t, w, B, 1);
    set_speeds(g_sens, Om);
    for (int q = 0; q < 3; q++) g_sens.sigma_BN[q] = g_cfg.inertial.sigma_R0N[q];
    std::memset(&g_cmd, 0, sizeof g_cmd);
    g_cmd.mode = FSW_ACS_MODE_INERTIAL;
    g_cmd.actuation = FSW_ACS_ACT_WHEELS;
    g_cmd.set_policy = static_cast<uint8_t>(set);
    g_cmd.policy = pol;
    const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g_cmd, &g_act, &g_h);
    if (s >= 0) t += kPeriodNs;
    return s;
  };
  ASSERT_EQ(FSW_OK, run(0, 0));
  EXPECT_EQ(FSW_ACS_MOM_NONE, g_h.policy);
  EXPECT_EQ(0, g_act.mtq_active);
  ASSERT_GE(run(1, FSW_ACS_MOM_MAGNETORQUERS), 0);
  EXPECT_EQ(FSW_ACS_MOM_MAGNETORQUERS, g_h.policy);
  EXPECT_EQ(1, g_act.mtq_active);
  // the policy holds without set_policy
  ASSERT_GE(run(0, FSW_ACS_MOM_NONE), 0);
  EXPECT_EQ(FSW_ACS_MOM_MAGNETORQUERS, g_h.policy);
  // unconfigured, unknown, flag not 0/1: bad input, the policy unchanged
  const int bad[][2] = {{1, FSW_ACS_MOM_THRUSTERS}, {1, 3}, {1, -1}, {2, FSW_ACS_MOM_NONE}};
  for (const auto& b : bad) {
    EXPECT_EQ(FSW_E_BAD_INPUT, run(b[0], b[1])) << b[0] << " " << b[1];
    EXPECT_TRUE(actuators_safe(g_act));
    EXPECT_EQ(FSW_ACS_MOM_MAGNETORQUERS, g_h.policy);
  }
  // a good set_policy in a cycle that fails later does not stick
  sensors(g_sens, t, w, B, 1);
  g_sens.omega_BN_B[1] = kNaN;
  g_cmd.set_policy = 1;
  g_cmd.policy = FSW_ACS_MOM_NONE;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g_cmd, &g_act, &g_h));
  EXPECT_EQ(FSW_ACS_MOM_MAGNETORQUERS, g_h.policy);
  ASSERT_GE(run(1, FSW_ACS_MOM_NONE), 0);
  EXPECT_EQ(FSW_ACS_MOM_NONE, g_h.policy);
  EXPECT_EQ(0, g_act.mtq_active);
  // reset goes back to the configured policy
  fsw_acs_reset(&g_st, &g_cfg);
  EXPECT_EQ(FSW_ACS_MOM_NONE, g_st.policy);
}

/* ---- error cycles ---- */

// Wheels with null motion and bias, THRUSTERS policy: one wheel in its
// keep-out band (3 rad/s < 5), a dump running from the second cycle.
void err_config(FswAcsConfig& c)
{
  thr_config(c);
  c.use_null = 1;
  c.use_bias = 1;
}
const double kErrOm[4] = {60.0, -40.0, 20.0, 3.0};

// A run of n cycles; `bad_at` >= 0 inserts a failing cycle before the good
// one at that index (kind 0: NaN rate, caught before the stages; kind 1: a
// finite rate so large that mrp_fb's torque overflows, after rw_bias and
// thr_momentum have run).
void err_run(FswAcsState& st, FswAcsActuatorMsg& act, FswAcsHealthMsg& h, int n, int bad_at, int kind)
{
  init_ok(g_cfg, st);
  for (int k = 0; k < n; k++) {
    if (k == bad_at) {
      at_reference(g_sens, g_cfg, k * kPeriodNs, kErrOm);
      // kind 1: P omega = 36 x 1e307 (1e37 in float) overflows the real
      g_sens.omega_BN_B[0] = kind == 0 ? kNaN : R(kt::kFloat ? 1e37 : 1e307);
      static FswThrMomentumState tm;
      static uint8_t band[FSW_MAX_RW];
      static int policy, cmd_mode, mode;
      tm = st.thr_mom;
      std::memcpy(band, st.rw_bias.in_band, sizeof band);
      policy = st.policy, cmd_mode = st.cmd_mode, mode = st.mode;
      EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&st, &g_cfg, &g_sens, nullptr, &act, &h)) << kind;
      EXPECT_TRUE(actuators_safe(act));
      tm.health = st.thr_mom.health;
      EXPECT_EQ(0, std::memcmp(&tm, &st.thr_mom, sizeof tm)) << "thr_momentum advanced, kind " << kind;
      EXPECT_EQ(0, std::memcmp(band, st.rw_bias.in_band, sizeof band)) << "rw_bias advanced, kind " << kind;
      EXPECT_EQ(policy, st.policy);
      EXPECT_EQ(cmd_mode, st.cmd_mode);
      EXPECT_EQ(mode, st.mode);
    }
    at_reference(g_sens, g_cfg, k * kPeriodNs, kErrOm);
    ASSERT_GE(fsw_acs_cycle(&st, &g_cfg, &g_sens, nullptr, &act, &h), 0) << k;
  }
}

// Verifies: REQ-ACS-006
TEST(FswAcsMomentumErrors, AnErrorCycleAdvancesNoNewStateAndTheRetryEqualsACleanRun)
{
  err_config(g_cfg);
  err_run(g_st2, g_act2, g_h2, 6, -1, 0);
  EXPECT_EQ(FSW_THR_MOM_PULSE, g_h2.dump_phase);  // the dump is running
  EXPECT_EQ(1, g_st2.rw_bias.in_band[3]);          // and a wheel is in its band
  for (int kind = 0; kind < 2; kind++)
    for (int at : {1, 2, 4}) {
      err_run(g_st, g_act, g_h, 6, at, kind);
      EXPECT_EQ(0, std::memcmp(&g_act, &g_act2, sizeof g_act)) << kind << " at " << at;
      EXPECT_EQ(g_h2.cycles, g_h.cycles);
      static FswThrMomentumState a;
      a = g_st.thr_mom;
      a.health = g_st2.thr_mom.health;  // the failed call is counted
      EXPECT_EQ(0, std::memcmp(&a, &g_st2.thr_mom, sizeof a)) << kind << " at " << at;
      EXPECT_EQ(0, std::memcmp(g_st.rw_bias.in_band, g_st2.rw_bias.in_band, sizeof g_st.rw_bias.in_band));
      EXPECT_EQ(g_h2.prop_used, g_h.prop_used);
    }
}

// Verifies: REQ-ACS-006
TEST(FswAcsMomentumErrors, DetumbleErrorsRestoreBdotAndTheHeldField)
{
  const double w[3] = {0.02, -0.01, 0.03}, B[3] = {2e-5, 1e-5, -3e-5};
  acsfix::full_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_DETUMBLE;
  g_cfg.bdot.variant = FSW_BDOT_DERIV;  // memory of the last sample
  init_ok(g_cfg, g_st);
  sensors(g_sens, 0, w, B, 1);
  ASSERT_GE(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h), 0);
  static FswBdotState bd;
  bd = g_st.bdot;
  double Bh[3];
  for (int q = 0; q < 3; q++) Bh[q] = g_st.B_hold[q];
  // a field beyond bdot's 1 mT range (finite: the application passes it on)
  const double Bbig[3] = {2e-3, 0, 0};
  sensors(g_sens, kPeriodNs, w, Bbig, 1);
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(actuators_safe(g_act));
  bd.health = g_st.bdot.health;
  EXPECT_EQ(0, std::memcmp(&bd, &g_st.bdot, sizeof bd));
  for (int q = 0; q < 3; q++) EXPECT_EQ(R(Bh[q]), g_st.B_hold[q]);
  // NaN rate: rejected before any stage
  sensors(g_sens, kPeriodNs, w, B, 1);
  g_sens.omega_BN_B[2] = kNaN;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  bd.health = g_st.bdot.health;
  EXPECT_EQ(0, std::memcmp(&bd, &g_st.bdot, sizeof bd));
  EXPECT_EQ(1u, g_h.cycles);
}

/* ---- rw_bias -> rw_null ---- */

// Verifies: REQ-ACS-011
TEST(FswAcsBias, TheBiasSpeedsReachTheNullMotion)
{
  // The pyramid's null space is n = (1, -1, 1, -1)/2 (the azimuths cancel
  // pairwise).  Omega = 10 n 2 has no body momentum (Lr = 0 at rest on the
  // reference); the bias 50 (1,-1,1,-1) is in the null space, so rw_bias asks
  // for exactly the bias, and rw_null's u = -k_null (Omega - Omega_des)
  // (already in the null space, kappa = 1) = 0.002 x 40 (1, -1, 1, -1).
  const double Om[4] = {10.0, -10.0, 10.0, -10.0};
  for (int bias = 0; bias < 2; bias++) {
    acsfix::full_config(g_cfg);
    g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
    g_cfg.use_null = 1;
    g_cfg.use_bias = bias;
    init_ok(g_cfg, g_st);
    at_reference(g_sens, g_cfg, 0, Om);
    ASSERT_EQ(FSW_OK, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
    for (int i = 0; i < 4; i++) {
      const double sgn = i % 2 == 0 ? 1.0 : -1.0;
      const double des = bias ? 50.0 * sgn : 0.0;  // without bias: Omega_des = 0 (despin)
      EXPECT_NEAR(-0.002 * (Om[i] - des), g_act.u_s[i], kt::tol(1e-12, 1e-7)) << bias << " " << i;
    }
    if (bias) EXPECT_EQ(FSW_OK, g_h.stage_status[FSW_ACS_STAGE_RW_BIAS]);
  }
}

}  // namespace

namespace {

// MC/DC of the momentum cross-checks (docs/coverage.md): the single sides the
// table above leaves out.  A management set on a vehicle without wheels is
// refused by name even when its other actuator is present; an axis copy
// sized for fewer wheels is refused even when every axis it has matches;
// a controller without the wheel model (mrp_fb.num_rw 0) has no J_s to
// compare, so differing copies are accepted.
const BadCfg kMcdcConfigs[] = {
    {"thruster dumps without wheels", [](FswAcsConfig& c) { c.use_thr_mom = 1; c.has_wheels = 0; c.mrp_fb.num_rw = 0; c.initial_actuation = FSW_ACS_ACT_THRUSTERS; }, "use_thr_mom",
     FSW_E_CONFIG},
    {"rod desaturation without wheels", [](FswAcsConfig& c) { c.use_mtq_desat = 1; c.has_wheels = 0; c.mrp_fb.num_rw = 0; c.initial_actuation = FSW_ACS_ACT_THRUSTERS; },
     "use_mtq_desat", FSW_E_CONFIG},
    {"bias without wheels", [](FswAcsConfig& c) { c.use_null = 1; c.use_bias = 1; c.has_wheels = 0; c.mrp_fb.num_rw = 0; c.initial_actuation = FSW_ACS_ACT_THRUSTERS; }, "use_bias",
     FSW_E_CONFIG},
    {"thr_mom for three of four wheels", [](FswAcsConfig& c) { c.use_thr_mom = 1; c.thr_mom.num_rw = 3; },
     "thr_mom.gs_hat_B", FSW_E_CONFIG},
    {"mtq_desat for three of four wheels", [](FswAcsConfig& c) { c.use_mtq_desat = 1; c.mtq_desat.num_rw = 3; },
     "mtq_desat.gs_hat_B", FSW_E_CONFIG},
    {"rw_bias for three of four wheels",
     [](FswAcsConfig& c) { c.use_null = 1; c.use_bias = 1; c.rw_bias.num_rw = 3; }, "rw_bias.gs_hat_B", FSW_E_CONFIG},
};

}  // namespace

// Verifies: REQ-ACS-002
TEST(FswAcsMomentumConfig, McdcEachSideOfTheCrossChecksAlone)
{
  for (const BadCfg& b : kMcdcConfigs) {
    acsfix::full_config(g_cfg);
    b.spoil(g_cfg);
    const char* field = nullptr;
    const FswStatus s = fsw_acs_check(&g_cfg, &field);
    EXPECT_EQ(b.want, s) << b.why;
    EXPECT_STREQ(b.field, field) << b.why;
  }
  // no wheel model in the controller: the J_s copies are not compared
  for (int which = 0; which < 2; which++) {
    acsfix::full_config(g_cfg);
    g_cfg.mrp_fb.num_rw = 0;
    if (which == 0) {
      g_cfg.use_thr_mom = 1;
      g_cfg.thr_mom.J_s[2] *= 2;
    } else {
      g_cfg.use_mtq_desat = 1;
      g_cfg.mtq_desat.J_s[0] *= 3;
    }
    const char* field = nullptr;
    EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field)) << which << " " << (field != nullptr ? field : "");
  }
}

// MC/DC (docs/coverage.md): mag_valid is a 0/1 flag like orbit_valid; a 2
// is bad input of the cycle on its own (orbit_valid 1), the safe output,
// and the good retry at the same time stamp is accepted.
// Verifies: REQ-ACS-005
TEST(FswAcsNadir, McdcMagValidTwoAloneIsBadInput)
{
  const double Om[4] = {30.0, -20.0, 10.0, 5.0};
  ASSERT_NO_FATAL_FAILURE(nadir_first_cycle(Om));
  nadir_sensors(g_sens, kPeriodNs, Om);
  ASSERT_EQ(1u, g_sens.orbit_valid);
  g_sens.mag_valid = 2;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(actuators_safe(g_act));
  EXPECT_EQ(1, g_h.safe_output);
  g_sens.mag_valid = 1;
  EXPECT_EQ(FSW_OK, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
}

/* ---- MC/DC of the command's policy and actuation (docs/coverage.md) ---- */

namespace {

// One cycle at the reference with wheel speeds Om and body rate w (r_CoM
// as given), commanding mode INERTIAL, actuation `act`, and, when `set`,
// the policy `pol`.
FswStatus cmd_cycle(FswAcsState& st, FswAcsActuatorMsg& a, FswAcsHealthMsg& h, uint64_t t, const double Om[4],
                    const double w[3], int act, int set, int pol, fsw_real r_com = R(0.0))
{
  sensors(g_sens, t, w, nullptr, 0);
  set_speeds(g_sens, Om);
  for (int q = 0; q < 3; q++) {
    g_sens.sigma_BN[q] = g_cfg.inertial.sigma_R0N[q];
    g_sens.r_CoM_B[q] = r_com;
  }
  std::memset(&g_cmd, 0, sizeof g_cmd);
  g_cmd.mode = FSW_ACS_MODE_INERTIAL;
  g_cmd.actuation = act;
  g_cmd.set_policy = static_cast<uint8_t>(set);
  g_cmd.policy = pol;
  return fsw_acs_cycle(&st, &g_cfg, &g_sens, &g_cmd, &a, &h);
}

const double kRest[3] = {0, 0, 0};
// |h_w| = 0.586 N m s: below h_lower (1) and h_upper (4), no dump
const double kLowOm[4] = {6.0, -4.0, 2.0, 1.0};

}  // namespace

// fsw_acs.c input check `(actuation == THRUSTERS || policy == THRUSTERS) &&
// !finite(r_CoM)`: in the wheel actuation a non-finite centre of mass is
// bad input exactly when the THRUSTERS policy is requested (it maps the
// dumps); under the NONE policy it is not read.
// Verifies: REQ-ACS-005
TEST(FswAcsPolicyCommand, McdcNonFiniteCentreOfMassIsBadInputOnlyForThrusterDumps)
{
  thr_config(g_cfg);
  g_cfg.initial_policy = FSW_ACS_MOM_NONE;
  init_ok(g_cfg, g_st);
  ASSERT_EQ(FSW_OK, cmd_cycle(g_st, g_act, g_h, 0, kLowOm, kRest, FSW_ACS_ACT_WHEELS, 0, 0, kNaN));
  EXPECT_EQ(FSW_ACS_MOM_NONE, g_h.policy);
  EXPECT_EQ(1, g_act.wheels_active);
  EXPECT_EQ(FSW_E_BAD_INPUT, cmd_cycle(g_st, g_act, g_h, kPeriodNs, kLowOm, kRest, FSW_ACS_ACT_WHEELS, 1,
                                       FSW_ACS_MOM_THRUSTERS, kNaN));
  EXPECT_TRUE(actuators_safe(g_act));
  EXPECT_EQ(FSW_ACS_MOM_NONE, g_st.policy);
  // the same command with a finite centre of mass is taken
  ASSERT_GE(cmd_cycle(g_st, g_act, g_h, kPeriodNs, kLowOm, kRest, FSW_ACS_ACT_WHEELS, 1, FSW_ACS_MOM_THRUSTERS), 0);
  EXPECT_EQ(FSW_ACS_MOM_THRUSTERS, g_h.policy);
}

// fsw_acs.c transition `mode changed || actuation changed`: a command that
// keeps the mode and changes the actuation is a transition (counted once,
// the memory of the old actuation reset); repeating it is not.
// Verifies: REQ-ACS-007
TEST(FswAcsPolicyCommand, McdcAnActuationChangeAloneIsATransition)
{
  acsfix::full_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  init_ok(g_cfg, g_st);
  ASSERT_EQ(FSW_OK, cmd_cycle(g_st, g_act, g_h, 0, kLowOm, kRest, FSW_ACS_ACT_WHEELS, 0, 0));
  EXPECT_EQ(0u, g_h.mode_changes);
  const double w[3] = {0.01, 0, 0};
  ASSERT_GE(cmd_cycle(g_st, g_act, g_h, kPeriodNs, kLowOm, w, FSW_ACS_ACT_THRUSTERS, 0, 0), 0);
  EXPECT_EQ(1u, g_h.mode_changes);
  EXPECT_EQ(FSW_ACS_MODE_INERTIAL, g_h.mode);
  EXPECT_EQ(FSW_ACS_ACT_THRUSTERS, g_h.actuation);
  EXPECT_EQ(0, g_act.wheels_active);
  // the pulser was reset by the transition: its first cycle times no period
  // and commands nothing; the next one fires against the rate
  double ton = 0;
  for (int j = 0; j < 8; j++) ton += g_act.t_on[j];
  EXPECT_EQ(0.0, ton);
  ASSERT_GE(cmd_cycle(g_st, g_act, g_h, 2 * kPeriodNs, kLowOm, w, FSW_ACS_ACT_THRUSTERS, 0, 0), 0);
  EXPECT_EQ(1u, g_h.mode_changes);
  for (int j = 0; j < 8; j++) ton += g_act.t_on[j];
  EXPECT_GT(ton, 0.0);
}

// fsw_acs.c set_policy: `policy == THRUSTERS && actuation == WHEELS`
// restarts the pulser, whose clock went stale while the dumps were off:
// the first cycle of the THRUSTERS policy then times no pulser period and
// starts no dump even above h_upper; the next cycle does.  In the thruster
// actuation (the pulser runs every cycle) the same command restarts
// nothing: a twin run without it commands the same on-times, bit for bit.
// Verifies: REQ-ACS-011
TEST(FswAcsPolicyCommand, McdcThrustersPolicyRestartsAStalePulserOnlyInTheWheelActuation)
{
  thr_config(g_cfg);
  init_ok(g_cfg, g_st);
  uint64_t t = 0;
  for (int k = 0; k < 2; k++, t += kPeriodNs) {
    ASSERT_GE(cmd_cycle(g_st, g_act, g_h, t, kLowOm, kRest, FSW_ACS_ACT_WHEELS, 0, 0), 0) << k;
    EXPECT_EQ(FSW_THR_MOM_IDLE, g_h.dump_phase);
  }
  ASSERT_EQ(1, g_st.pulse_rem.common.clock.has_prev);
  // dumps off for two cycles: the pulser does not run, its clock goes stale
  ASSERT_GE(cmd_cycle(g_st, g_act, g_h, t, kLowOm, kRest, FSW_ACS_ACT_WHEELS, 1, FSW_ACS_MOM_NONE), 0);
  t += kPeriodNs;
  ASSERT_GE(cmd_cycle(g_st, g_act, g_h, t, kDumpOm, kRest, FSW_ACS_ACT_WHEELS, 0, 0), 0);
  t += kPeriodNs;
  EXPECT_EQ(FSW_THR_MOM_IDLE, g_h.dump_phase);
  ASSERT_EQ(1, g_st.pulse_rem.common.clock.has_prev);
  // back to THRUSTERS above h_upper: no dump in the first cycle, then one
  ASSERT_GE(cmd_cycle(g_st, g_act, g_h, t, kDumpOm, kRest, FSW_ACS_ACT_WHEELS, 1, FSW_ACS_MOM_THRUSTERS), 0);
  t += kPeriodNs;
  EXPECT_EQ(FSW_ACS_MOM_THRUSTERS, g_h.policy);
  EXPECT_EQ(FSW_THR_MOM_IDLE, g_h.dump_phase);
  EXPECT_EQ(0, g_act.thrusters_active);
  ASSERT_GE(cmd_cycle(g_st, g_act, g_h, t, kDumpOm, kRest, FSW_ACS_ACT_WHEELS, 0, 0), 0);
  EXPECT_EQ(FSW_THR_MOM_PULSE, g_h.dump_phase);
  EXPECT_EQ(1, g_act.thrusters_active);

  // thruster actuation, policy NONE, a body rate to fight: twins st, st2
  thr_config(g_cfg);
  g_cfg.initial_policy = FSW_ACS_MOM_NONE;
  g_cfg.initial_actuation = FSW_ACS_ACT_THRUSTERS;
  init_ok(g_cfg, g_st);
  init_ok(g_cfg, g_st2);
  const double w[3] = {0.01, -0.004, 0.002};
  double fired = 0;
  for (int k = 0; k < 5; k++) {
    const uint64_t tk = static_cast<uint64_t>(k) * kPeriodNs;
    const int set = k == 3 ? 1 : 0;
    ASSERT_GE(cmd_cycle(g_st, g_act, g_h, tk, kLowOm, w, FSW_ACS_ACT_THRUSTERS, 0, 0), 0) << k;
    ASSERT_GE(cmd_cycle(g_st2, g_act2, g_h2, tk, kLowOm, w, FSW_ACS_ACT_THRUSTERS, set, FSW_ACS_MOM_THRUSTERS), 0)
        << k;
    EXPECT_EQ(k >= 3 ? FSW_ACS_MOM_THRUSTERS : FSW_ACS_MOM_NONE, g_h2.policy) << k;
    for (int j = 0; j < 8; j++) {
      EXPECT_EQ(g_act.t_on[j], g_act2.t_on[j]) << k << " " << j;
      if (k == 3) fired += g_act2.t_on[j];
    }
  }
  EXPECT_GT(fired, 0.0);  // a restarted pulser would have commanded nothing
}

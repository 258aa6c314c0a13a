// The FSW application fsw_acs: configuration as a whole, nominal cycles with
// hand-computed numbers, bad input and recovery, mode transitions, and
// closed loops against the small independent plant of acs_fixture.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "acs_fixture.hpp"
#include "fsw/fsw_acs.h"
#include "fsw/fsw_attitude.h"
#include "kestrel_test_support.h"
#include "null_args.h"

namespace {

using acsfix::kPeriodNs;
const double kTol = kt::tol(1e-12, 2e-5);
const fsw_real kNaN = std::numeric_limits<fsw_real>::quiet_NaN();

// Big structs: static storage, not the (small, on bare metal) test stack.
FswAcsConfig g_cfg;
FswAcsState g_st, g_st2;
FswAcsSensorMsg g_sens;
FswAcsActuatorMsg g_act, g_act2;
FswAcsHealthMsg g_h, g_h2;

bool all_zero(const FswAcsActuatorMsg& a)
{
  for (int i = 0; i < 3; i++)
    if (a.Lr_B[i] != 0) return false;
  for (int i = 0; i < FSW_MAX_RW; i++)
    if (a.u_s[i] != 0 || a.V[i] != 0) return false;
  for (int i = 0; i < FSW_MAX_THR; i++)
    if (a.F[i] != 0 || a.t_on[i] != 0) return false;
  return a.wheels_active == 0 && a.thrusters_active == 0;
}

void sensors_at_rest(FswAcsSensorMsg& m, uint64_t t_ns)
{
  std::memset(&m, 0, sizeof m);
  m.t_ns = t_ns;
  m.att_valid = 1;
  // Sun along (1,1,1)/sqrt(3) in B: the +x, +y, +z sensors are lit
  const double c = 1.0 / std::sqrt(3.0);
  m.css[0] = acsfix::R(c);
  m.css[2] = acsfix::R(c);
  m.css[4] = acsfix::R(c);
}

/* ---- configuration ---- */

struct BadCfg {
  const char* why;
  void (*spoil)(FswAcsConfig&);
  const char* field;
  FswStatus want;
};

const BadCfg kBadConfigs[] = {
    {"unknown initial mode", [](FswAcsConfig& c) { c.initial_mode = 7; }, "initial_mode", FSW_E_CONFIG},
    {"no actuators", [](FswAcsConfig& c) { c.has_wheels = 0; c.mrp_fb.num_rw = 0; }, "has_wheels", FSW_E_CONFIG},
    {"thruster actuation without thrusters", [](FswAcsConfig& c) { c.initial_actuation = FSW_ACS_ACT_THRUSTERS; },
     "initial_actuation", FSW_E_CONFIG},
    {"bad CSS count", [](FswAcsConfig& c) { c.css.num_css = 0; }, "css", FSW_E_CONFIG},
    {"zero gain K", [](FswAcsConfig& c) { c.mrp_fb.K = 0; }, "mrp_fb", FSW_E_CONFIG},
    {"H wheels differ from mapped wheels", [](FswAcsConfig& c) { c.mrp_fb.num_rw = 3; }, "mrp_fb.num_rw", FSW_E_CONFIG},
    {"saturation wheel count", [](FswAcsConfig& c) { c.rw_sat.num_rw = 3; }, "rw_sat.num_rw", FSW_E_CONFIG},
    {"wheel count above capacity", [](FswAcsConfig& c) { c.rw_map.num_rw = FSW_MAX_RW + 1; }, "rw_map", FSW_E_CAPACITY},
    {"NaN desired speed", [](FswAcsConfig& c) { c.use_null = 1; c.Omega_des[2] = kNaN; }, "Omega_des", FSW_E_CONFIG},
    {"use_lpf not boolean", [](FswAcsConfig& c) { c.use_lpf = 2; }, "use_lpf", FSW_E_CONFIG},
    {"filter above Nyquist", [](FswAcsConfig& c) { c.use_lpf = 1; c.lpf.omega_c = acsfix::R(7.0); }, "lpf", FSW_E_CONFIG},
    // issue 21: every stage's check and every consistency check has a row
    {"has_wheels not boolean", [](FswAcsConfig& c) { c.has_wheels = 2; }, "has_wheels", FSW_E_CONFIG},
    {"has_thrusters not boolean", [](FswAcsConfig& c) { c.has_thrusters = 3; }, "has_thrusters", FSW_E_CONFIG},
    {"unknown initial actuation", [](FswAcsConfig& c) { c.initial_actuation = 9; }, "initial_actuation", FSW_E_CONFIG},
    {"wheel actuation without wheels", [](FswAcsConfig& c) { c.has_wheels = 0; c.has_thrusters = 1; },
     "initial_actuation", FSW_E_CONFIG},
    {"sun-safe command axis zero", [](FswAcsConfig& c) { c.sunsafe.s_cmd_B[2] = 0; }, "sunsafe", FSW_E_CONFIG},
    {"NaN inertial target", [](FswAcsConfig& c) { c.inertial.sigma_R0N[0] = kNaN; }, "inertial", FSW_E_CONFIG},
    {"NaN tracking offset", [](FswAcsConfig& c) { c.track.sigma_R0R[1] = kNaN; }, "track", FSW_E_CONFIG},
    {"saturation mode", [](FswAcsConfig& c) { c.rw_sat.mode = 7; }, "rw_sat", FSW_E_CONFIG},
    {"use_null not boolean", [](FswAcsConfig& c) { c.use_null = 2; }, "use_null", FSW_E_CONFIG},
    {"negative null gain", [](FswAcsConfig& c) { c.use_null = 1; c.rw_null.k_null = acsfix::R(-1.0); }, "rw_null", FSW_E_CONFIG},
    {"null-motion wheel count", [](FswAcsConfig& c) { c.use_null = 1; c.rw_null.num_rw = 3; }, "rw_null.num_rw", FSW_E_CONFIG},
    {"use_volt not boolean", [](FswAcsConfig& c) { c.use_volt = 2; }, "use_volt", FSW_E_CONFIG},
    {"voltage range empty", [](FswAcsConfig& c) { c.use_volt = 1; c.rw_volt.V_max = 0; }, "rw_volt", FSW_E_CONFIG},
    {"voltage wheel count", [](FswAcsConfig& c) { c.use_volt = 1; c.rw_volt.num_rw = 3; }, "rw_volt.num_rw", FSW_E_CONFIG},
    // issue 14: the speed filter in the chain
    {"use_speed_filter not boolean", [](FswAcsConfig& c) { c.use_speed_filter = 2; }, "use_speed_filter", FSW_E_CONFIG},
    {"speed filter k_reject zero", [](FswAcsConfig& c) { c.use_speed_filter = 1; c.speed_filter.n_recover = 3; },
     "speed_filter", FSW_E_CONFIG},
    {"speed filter wheel count",
     [](FswAcsConfig& c) { c.use_speed_filter = 1; c.speed_filter.k_reject = c.speed_filter.n_recover = 3; c.speed_filter.num_rw = 3; },
     "speed_filter.num_rw", FSW_E_CONFIG},
    {"speed filter J_s copy differs",
     [](FswAcsConfig& c) { c.use_speed_filter = 1; c.speed_filter.k_reject = c.speed_filter.n_recover = 3; c.speed_filter.J_s[1] *= 2; },
     "speed_filter.J_s", FSW_E_CONFIG},
    // issue 39: the filter refuses an applied torque above 2 of its u_max,
    // so a limit below rw_sat's (0.2 N m here) made every other cycle fail
    {"speed filter torque limit below the saturation limit (all wheels)",
     [](FswAcsConfig& c) {
       c.use_speed_filter = 1; c.speed_filter.k_reject = c.speed_filter.n_recover = 3; c.speed_filter.n_window = 2;
       for (int i = 0; i < 4; i++) c.speed_filter.u_max[i] = acsfix::R(2.8e-4);
     },
     "speed_filter.u_max", FSW_E_CONFIG},
    {"speed filter torque limit below the saturation limit (last wheel, by 1 %)",
     [](FswAcsConfig& c) {
       c.use_speed_filter = 1; c.speed_filter.k_reject = c.speed_filter.n_recover = 3;
       c.speed_filter.u_max[3] = acsfix::R(0.198);
     },
     "speed_filter.u_max", FSW_E_CONFIG},
    // issue 45 fuzzing: a spin inertia of 1e307 kg m2 was accepted and its
    // momentum at 20 rad/s overflowed the health message's h_w_B
    {"spin inertia above FSW_RW_J_S_MAX", [](FswAcsConfig& c) { c.mrp_fb.J_s[0] = acsfix::R(2e4); }, "mrp_fb",
     FSW_E_CONFIG},
    {"H wheels without a wheel chain",
     [](FswAcsConfig& c) { c.has_wheels = 0; c.has_thrusters = 1; c.initial_actuation = FSW_ACS_ACT_THRUSTERS; },
     "mrp_fb.num_rw", FSW_E_CONFIG},
};

// Verifies: REQ-ACS-001
TEST(FswAcsConfig, RejectsTheFirstBadFieldByName)
{
  for (const BadCfg& b : kBadConfigs) {
    acsfix::wheel_config(g_cfg);
    b.spoil(g_cfg);
    const char* field = nullptr;
    EXPECT_EQ(b.want, fsw_acs_check(&g_cfg, &field)) << b.why;
    ASSERT_NE(nullptr, field) << b.why;
    EXPECT_EQ(std::string(b.field), field) << b.why;
    // init refuses too and leaves a state that only gives the safe output
    EXPECT_EQ(b.want, fsw_acs_init(&g_st, &g_cfg, nullptr)) << b.why;
    sensors_at_rest(g_sens, 0);
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
    EXPECT_TRUE(all_zero(g_act));
    EXPECT_EQ(1, g_h.safe_output);
  }
}

// Verifies: REQ-ACS-001, REQ-ACS-002
TEST(FswAcsConfig, ThrusterChainConsistency)
{
  struct Row {
    const char* why;
    void (*spoil)(FswAcsConfig&);
    const char* field;
  };
  const Row rows[] = {
      {"off-pulsing pulser behind on-pulsing mapper", [](FswAcsConfig& c) { c.pulse_rem.common.base_thrust_state = 1; },
       "pulse_rem.base_thrust_state"},
      {"pulser thruster count", [](FswAcsConfig& c) { c.pulse_rem.common.num_thr = 7; }, "pulse_rem.num_thr"},
      {"pulser F_max differs from mapper", [](FswAcsConfig& c) { c.pulse_rem.common.F_max[3] = acsfix::R(2.0); }, "pulse_rem.F_max"},
      {"unknown pulser", [](FswAcsConfig& c) { c.pulser = 5; }, "pulser"},
      {"thruster mapping geometry", [](FswAcsConfig& c) { c.thr_map.F_max[0] = 0; }, "thr_map"},
      // issue 21: the same consistency rows for the Schmitt pulser, and each
      // pulser's own check; F_max differs in the last thruster (index n - 1)
      {"wheel actuation without wheels", [](FswAcsConfig& c) { c.initial_actuation = FSW_ACS_ACT_WHEELS; },
       "initial_actuation"},
      {"remainder pulser t_min zero", [](FswAcsConfig& c) { c.pulse_rem.common.t_min = 0; }, "pulse_rem"},
      {"Schmitt level above 1", [](FswAcsConfig& c) { c.pulser = FSW_ACS_PULSE_SCHMITT; c.pulse_schmitt.level_on = 2; },
       "pulse_schmitt"},
      {"Schmitt thruster count", [](FswAcsConfig& c) { c.pulser = FSW_ACS_PULSE_SCHMITT; c.pulse_schmitt.common.num_thr = 7; },
       "pulse_schmitt.num_thr"},
      {"off-pulsing Schmitt behind on-pulsing mapper",
       [](FswAcsConfig& c) { c.pulser = FSW_ACS_PULSE_SCHMITT; c.pulse_schmitt.common.base_thrust_state = 1; },
       "pulse_schmitt.base_thrust_state"},
      {"Schmitt F_max differs from mapper",
       [](FswAcsConfig& c) { c.pulser = FSW_ACS_PULSE_SCHMITT; c.pulse_schmitt.common.F_max[7] = acsfix::R(2.0); },
       "pulse_schmitt.F_max"},
      {"remainder F_max differs in the last thruster", [](FswAcsConfig& c) { c.pulse_rem.common.F_max[7] = acsfix::R(0.5); },
       "pulse_rem.F_max"},
  };
  for (const Row& r : rows) {
    acsfix::thruster_config(g_cfg);
    r.spoil(g_cfg);
    const char* field = nullptr;
    EXPECT_NE(FSW_OK, fsw_acs_check(&g_cfg, &field)) << r.why;
    ASSERT_NE(nullptr, field) << r.why;
    EXPECT_EQ(std::string(r.field), field) << r.why;
  }
  acsfix::thruster_config(g_cfg, FSW_ACS_PULSE_SCHMITT);
  const char* field = "x";
  EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field));
  EXPECT_EQ(nullptr, field);
  // entries beyond num_thr (8) are unused: a pulser's F_max there may differ
  // from the mapper's without making the chain inconsistent (issue 21)
  static_assert(FSW_MAX_THR > 8, "the thruster fixture fills 8 of FSW_MAX_THR");
  for (int pulser : {FSW_ACS_PULSE_REMAINDER, FSW_ACS_PULSE_SCHMITT}) {
    acsfix::thruster_config(g_cfg, pulser);
    g_cfg.pulse_rem.common.F_max[8] = acsfix::R(5.0);
    g_cfg.pulse_schmitt.common.F_max[8] = acsfix::R(5.0);
    EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field)) << pulser;
    EXPECT_EQ(nullptr, field) << pulser;
  }
}

/* ---- what the health message publishes ---- */

// Verifies: REQ-ACS-012
TEST(FswAcsHealth, StageNamesComeFromTheLibrary)
{
  const char* const want[FSW_ACS_NUM_STAGES] = {"css",     "guidance", "track",   "control",
                                                "lpf",     "rw_map",   "rw_null", "rw_sat",
                                                "rw_volt", "thr_map",  "thr_pulse",
                                                "bdot",    "mtq_desat", "mtq_map", "thr_momentum", "rw_bias"};
  for (int i = 0; i < FSW_ACS_NUM_STAGES; i++) EXPECT_EQ(std::string(want[i]), fsw_acs_stage_name(i)) << i;
  EXPECT_EQ(std::string("unknown"), fsw_acs_stage_name(-1));
  EXPECT_EQ(std::string("unknown"), fsw_acs_stage_name(FSW_ACS_NUM_STAGES));
}

// Verifies: REQ-ACS-012
TEST(FswAcsHealth, PublishesTheSunHeadingTheCycleUsed)
{
  // Sun along (1,1,1)/sqrt3 on the +x, +y, +z sensors: the heading is exact.
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 1000);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  EXPECT_EQ(1, g_h.sun_valid);
  EXPECT_EQ(3, g_h.num_lit);
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(1.0 / std::sqrt(3.0), double(g_h.sun_hat_B[k]), kTol) << k;
    EXPECT_EQ(g_st.work.css_out.sun_hat_B[k], g_h.sun_hat_B[k]) << k;  // the estimate used
  }
  // eclipse: no lit sensor, no heading
  sensors_at_rest(g_sens, 2000);
  for (int i = 0; i < 6; i++) g_sens.css[i] = 0;
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  EXPECT_EQ(0, g_h.sun_valid);
  for (int k = 0; k < 3; k++) EXPECT_EQ(0, g_h.sun_hat_B[k]) << k;
  // a rejected cycle publishes no heading
  sensors_at_rest(g_sens, 3000);
  g_sens.omega_BN_B[1] = kNaN;
  ASSERT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  for (int k = 0; k < 3; k++) EXPECT_EQ(0, g_h.sun_hat_B[k]) << k;
  // inertial pointing does not run the CSS: no heading either
  acsfix::thruster_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 1000);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  EXPECT_EQ(0, g_h.sun_valid);
  for (int k = 0; k < 3; k++) EXPECT_EQ(0, g_h.sun_hat_B[k]) << k;
}

/* ---- geometry given once ---- */

FswAcsGeometry g_geo;
FswAcsConfig g_cfg2;

// Verifies: REQ-ACS-003
TEST(FswAcsGeometry, WritesEveryCopyAndNothingElse)
{
  acsfix::wheel_geometry(g_geo);
  for (int i = 0; i < 4; i++) {  // distinct values, so a crossed copy shows
    g_geo.J_s[i] = acsfix::R(0.1 + 0.01 * i);
    g_geo.u_max[i] = acsfix::R(0.2 + 0.02 * i);
  }
  std::memset(&g_cfg, 0, sizeof g_cfg);
  for (int i = 0; i < FSW_MAX_RW; i++) g_cfg.rw_sat.u_max[i] = acsfix::R(9.0);  // stale, beyond n too
  g_cfg.rw_null.k_null = acsfix::R(5.0);                                        // not geometry
  g_cfg.pulse_rem.common.t_min = acsfix::R(0.3);                                // not geometry
  ASSERT_EQ(FSW_OK, fsw_acs_config_set_geometry(&g_cfg, &g_geo));
  EXPECT_EQ(1, g_cfg.has_wheels);
  EXPECT_EQ(0, g_cfg.has_thrusters);
  EXPECT_EQ(4, g_cfg.mrp_fb.num_rw);
  EXPECT_EQ(4, g_cfg.rw_map.num_rw);
  EXPECT_EQ(4, g_cfg.rw_null.num_rw);
  EXPECT_EQ(4, g_cfg.rw_sat.num_rw);
  EXPECT_EQ(4, g_cfg.rw_volt.num_rw);
  EXPECT_EQ(0, g_cfg.thr_map.num_thr);
  for (int i = 0; i < FSW_MAX_RW; i++) {
    const bool in = i < 4;
    for (int k = 0; k < 3; k++) {
      const fsw_real g = in ? g_geo.gs_hat_B[i][k] : acsfix::R(0.0);
      EXPECT_EQ(g, g_cfg.mrp_fb.gs_hat_B[i][k]) << i;
      EXPECT_EQ(g, g_cfg.rw_map.gs_hat_B[i][k]) << i;
      EXPECT_EQ(g, g_cfg.rw_null.gs_hat_B[i][k]) << i;
    }
    const fsw_real J = in ? g_geo.J_s[i] : acsfix::R(0.0), u = in ? g_geo.u_max[i] : acsfix::R(0.0);
    EXPECT_EQ(J, g_cfg.mrp_fb.J_s[i]) << i;
    EXPECT_EQ(J, g_cfg.rw_volt.J_s[i]) << i;
    EXPECT_EQ(u, g_cfg.rw_null.u_max[i]) << i;
    EXPECT_EQ(u, g_cfg.rw_sat.u_max[i]) << i;
    EXPECT_EQ(u, g_cfg.rw_volt.u_max[i]) << i;
  }
  EXPECT_EQ(acsfix::R(5.0), g_cfg.rw_null.k_null);
  EXPECT_EQ(acsfix::R(0.3), g_cfg.pulse_rem.common.t_min);

  acsfix::thruster_geometry(g_geo);
  g_geo.F_max[5] = acsfix::R(2.5);
  ASSERT_EQ(FSW_OK, fsw_acs_config_set_geometry(&g_cfg, &g_geo));
  EXPECT_EQ(0, g_cfg.has_wheels);  // the wheel copies follow the geometry: none
  EXPECT_EQ(0, g_cfg.mrp_fb.num_rw);
  EXPECT_EQ(0, g_cfg.rw_sat.u_max[0]);
  EXPECT_EQ(1, g_cfg.has_thrusters);
  EXPECT_EQ(8, g_cfg.thr_map.num_thr);
  EXPECT_EQ(8, g_cfg.pulse_rem.common.num_thr);
  EXPECT_EQ(8, g_cfg.pulse_schmitt.common.num_thr);
  for (int j = 0; j < FSW_MAX_THR; j++) {
    const bool in = j < 8;
    for (int k = 0; k < 3; k++) {
      EXPECT_EQ(in ? g_geo.r_thr_B[j][k] : acsfix::R(0.0), g_cfg.thr_map.r_thr_B[j][k]) << j;
      EXPECT_EQ(in ? g_geo.gt_hat_B[j][k] : acsfix::R(0.0), g_cfg.thr_map.gt_hat_B[j][k]) << j;
    }
    const fsw_real F = in ? g_geo.F_max[j] : acsfix::R(0.0);
    EXPECT_EQ(F, g_cfg.thr_map.F_max[j]) << j;
    EXPECT_EQ(F, g_cfg.pulse_rem.common.F_max[j]) << j;
    EXPECT_EQ(F, g_cfg.pulse_schmitt.common.F_max[j]) << j;
  }
}

// Verifies: REQ-ACS-003
TEST(FswAcsGeometry, BadCountsLeaveTheConfigUnchanged)
{
  acsfix::wheel_config(g_cfg);
  g_cfg2 = g_cfg;
  const struct {
    const char* why;
    int num_rw, num_thr;
    FswStatus want;
  } rows[] = {
      {"wheels above capacity", FSW_MAX_RW + 1, 0, FSW_E_CAPACITY},
      {"thrusters above capacity", 4, FSW_MAX_THR + 1, FSW_E_CAPACITY},
      {"negative wheel count", -1, 0, FSW_E_CONFIG},
      {"negative thruster count", 4, -2, FSW_E_CONFIG},
  };
  for (const auto& r : rows) {
    acsfix::wheel_geometry(g_geo);
    g_geo.num_rw = r.num_rw;
    g_geo.num_thr = r.num_thr;
    EXPECT_EQ(r.want, fsw_acs_config_set_geometry(&g_cfg, &g_geo)) << r.why;
    EXPECT_EQ(0, std::memcmp(&g_cfg, &g_cfg2, sizeof g_cfg)) << r.why;
  }
  kestrel_assert_reset();
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_acs_config_set_geometry(nullptr, &g_geo));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_acs_config_set_geometry(&g_cfg, nullptr));
  EXPECT_EQ(2ul, kestrel_assert_count());
  kestrel_assert_reset();
}

// Verifies: REQ-ACS-001, REQ-ACS-002
TEST(FswAcsConfig, SafetyNetCatchesCopiesFilledByHand)
{
  // Swapping two spin axes in one copy keeps every module's own check happy
  // (unit axes, same set) but breaks the geometry the modules share.
  struct Row {
    const char* why;
    void (*spoil)(FswAcsConfig&);
    const char* field;
  };
  const Row rows[] = {
      {"control law wheel axes", [](FswAcsConfig& c) {
         for (int k = 0; k < 3; k++) std::swap(c.mrp_fb.gs_hat_B[0][k], c.mrp_fb.gs_hat_B[1][k]);
       }, "mrp_fb.gs_hat_B"},
      {"null-motion wheel axes", [](FswAcsConfig& c) {
         c.use_null = 1;
         for (int k = 0; k < 3; k++) std::swap(c.rw_null.gs_hat_B[2][k], c.rw_null.gs_hat_B[3][k]);
       }, "rw_null.gs_hat_B"},
      {"voltage spin inertia", [](FswAcsConfig& c) {
         c.use_volt = 1;
         c.rw_volt.J_s[1] = acsfix::R(0.2);
       }, "rw_volt.J_s"},
  };
  for (const Row& r : rows) {
    acsfix::wheel_config(g_cfg);
    ASSERT_EQ(FSW_OK, fsw_acs_check(&g_cfg, nullptr)) << r.why;
    r.spoil(g_cfg);
    const char* field = nullptr;
    EXPECT_EQ(FSW_E_CONFIG, fsw_acs_check(&g_cfg, &field)) << r.why;
    ASSERT_NE(nullptr, field) << r.why;
    EXPECT_EQ(std::string(r.field), field) << r.why;
  }
}

/* ---- nominal cycles, numbers by hand ---- */

// Verifies: REQ-ACS-004
TEST(FswAcsCycle, SunSafeFromCssMatchesHandCalculation)
{
  // Sun along (1,1,1)/sqrt3 in B, command +z: theta = acos(1/sqrt3),
  // e = unit(s x z) = (1,-1,0)/sqrt2, sigma_BR = tan(theta/4) e; at rest
  // (omega = 0, Omega = 0) the control law reduces to Lr = -K sigma_BR.
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 1000);
  const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
  EXPECT_FALSE(fsw_status_is_error(s)) << fsw_status_name(s);
  const double th = std::acos(1.0 / std::sqrt(3.0)), t4 = std::tan(th / 4.0), r2 = std::sqrt(0.5);
  const double sigma[3] = {t4 * r2, -t4 * r2, 0.0};
  for (int i = 0; i < 3; i++) {
    EXPECT_NEAR(sigma[i], g_h.sigma_BR[i], kTol);
    EXPECT_NEAR(-1.44 * sigma[i], g_act.Lr_B[i], kTol);
  }
  EXPECT_NEAR(th, g_h.sun_angle_err, kTol * 10);
  EXPECT_NEAR(th, g_h.att_err_angle, kTol * 10);
  EXPECT_EQ(1, g_h.sun_valid);
  EXPECT_EQ(3, g_h.num_lit);
  EXPECT_EQ(FSW_ACS_MODE_SUN_SAFE, g_h.mode);
  // wheels: [Gs] u = -Lr unless the saturation stage scaled it; either way
  // the body torque -[Gs] u is parallel to Lr and |u_i| <= u_max
  double body[3] = {0, 0, 0};
  for (int k = 0; k < 4; k++) {
    double g[3];
    acsfix::pyramid_axis(k, g);
    EXPECT_LE(std::fabs(g_act.u_s[k]), acsfix::kUmax * (1 + kTol));
    for (int i = 0; i < 3; i++) body[i] -= g_act.u_s[k] * g[i];
  }
  const double Lr = std::sqrt(g_act.Lr_B[0] * g_act.Lr_B[0] + g_act.Lr_B[1] * g_act.Lr_B[1]);
  const double bn = std::sqrt(body[0] * body[0] + body[1] * body[1] + body[2] * body[2]);
  const double cosang = (body[0] * g_act.Lr_B[0] + body[1] * g_act.Lr_B[1] + body[2] * g_act.Lr_B[2]) / (Lr * bn);
  EXPECT_NEAR(1.0, cosang, kt::tol(1e-12, 1e-5));
  EXPECT_EQ(1, g_act.wheels_active);
  EXPECT_EQ(0, g_act.thrusters_active);
  for (int k = 4; k < FSW_MAX_RW; k++) EXPECT_EQ(0, g_act.u_s[k]);
}

// Verifies: REQ-ACS-004
TEST(FswAcsCycle, InertialAtRestGivesKSigmaRN)
{
  // sigma_BN = 0: sigma_BR = subMRP(0, sigma_RN) = -sigma_RN, so Lr = K sigma_RN.
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);  // time 0 is a legal first stamp
  const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
  EXPECT_FALSE(fsw_status_is_error(s));
  for (int i = 0; i < 3; i++) {
    EXPECT_NEAR(-g_cfg.inertial.sigma_R0N[i], g_h.sigma_BR[i], kTol);
    EXPECT_NEAR(1.44 * g_cfg.inertial.sigma_R0N[i], g_act.Lr_B[i], kTol);
  }
}

// Verifies: REQ-ACS-004
TEST(FswAcsCycle, SmallErrorsAreOpposedAndWheelsDeliverTheTorque)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  std::memset(g_cfg.inertial.sigma_R0N, 0, sizeof g_cfg.inertial.sigma_R0N);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  kt::Rng r(501);
  for (int k = 0; k < 100; k++) {
    fsw_acs_reset(&g_st, &g_cfg);
    sensors_at_rest(g_sens, 0);
    const bool rate_case = (k % 2 == 1);
    for (int i = 0; i < 3; i++) {
      const double v = r.uniform(-1, 1);
      if (rate_case) g_sens.omega_BN_B[i] = acsfix::R(1e-4 * v);
      else g_sens.sigma_BN[i] = acsfix::R(1e-3 * v);
    }
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
    const fsw_real* e = rate_case ? g_sens.omega_BN_B : g_sens.sigma_BN;
    EXPECT_LT(e[0] * g_act.Lr_B[0] + e[1] * g_act.Lr_B[1] + e[2] * g_act.Lr_B[2], 0.0) << k;
    // unsaturated: [Gs] u = -Lr
    double body[3] = {0, 0, 0};
    for (int w = 0; w < 4; w++) {
      double g[3];
      acsfix::pyramid_axis(w, g);
      for (int i = 0; i < 3; i++) body[i] += g_act.u_s[w] * g[i];
    }
    for (int i = 0; i < 3; i++) EXPECT_NEAR(-g_act.Lr_B[i], body[i], kt::tol(1e-15, 1e-8));
  }
}

// Verifies: REQ-ACS-015
TEST(FswAcsCycle, ThrusterOnTimesAreBoundedAndZeroRequestFiresNothing)
{
  acsfix::thruster_config(g_cfg);
  std::memcpy(g_cfg.inertial.sigma_R0N, (const fsw_real[3]){0, 0, 0}, sizeof(fsw_real) * 3);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  for (int c = 0; c < 5; c++) {  // exactly on target, at rest: no torque, no firing
    g_sens.t_ns = c * kPeriodNs;
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
    for (int j = 0; j < FSW_MAX_THR; j++) {
      EXPECT_EQ(0, g_act.t_on[j]);
      EXPECT_EQ(0, g_act.F[j]);
    }
  }
  kt::Rng r(502);
  const double T = acsfix::kPeriod;
  for (int c = 5; c < 60; c++) {
    g_sens.t_ns = c * kPeriodNs;
    for (int i = 0; i < 3; i++) g_sens.sigma_BN[i] = acsfix::R(0.02 * r.uniform(-1, 1));
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
    EXPECT_EQ(1, g_act.thrusters_active);
    for (int j = 0; j < 8; j++) {
      const double t = g_act.t_on[j];
      EXPECT_TRUE(t == 0 || (t >= 0.02 * (1 - 1e-6) && t <= 1.1 * T * (1 + 1e-6))) << t;
      EXPECT_GE(g_act.F[j], 0);
      EXPECT_LE(g_act.F[j], acsfix::kFmax * (1 + 1e-9));
    }
    for (int j = 8; j < FSW_MAX_THR; j++) EXPECT_EQ(0, g_act.t_on[j]);
  }
}

/* ---- bad input, time, recovery ---- */

// Verifies: REQ-ACS-005
TEST(FswAcsCycle, BadInputGivesSafeOutputAdvancesNothingAndRecovers)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  g_cfg.mrp_fb.K_i = acsfix::R(0.01);  // integral on: its memory must not move
  g_cfg.mrp_fb.integral_limit = acsfix::R(1.0);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st2, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  for (int c = 0; c < 3; c++) {
    g_sens.t_ns = c * kPeriodNs;
    fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
    fsw_acs_cycle(&g_st2, &g_cfg, &g_sens, nullptr, &g_act2, &g_h2);
  }
  const FswMrpFbState fb_before = g_st.mrp_fb;
  const uint64_t t_prev = g_st.clock.t_prev_ns;
  struct Spoil {
    const char* why;
    void (*f)(FswAcsSensorMsg&);
    FswStatus want;
  };
  const Spoil spoils[] = {
      {"NaN rate", [](FswAcsSensorMsg& m) { m.omega_BN_B[1] = kNaN; }, FSW_E_BAD_INPUT},
      {"Inf attitude", [](FswAcsSensorMsg& m) { m.sigma_BN[0] = std::numeric_limits<fsw_real>::infinity(); }, FSW_E_BAD_INPUT},
      {"attitude not valid in INERTIAL", [](FswAcsSensorMsg& m) { m.att_valid = 0; }, FSW_E_BAD_INPUT},
      {"NaN wheel speed", [](FswAcsSensorMsg& m) { m.Omega[3] = kNaN; }, FSW_E_BAD_INPUT},
      {"wheel speed beyond FSW_RW_OMEGA_MAX", [](FswAcsSensorMsg& m) { m.Omega[2] = acsfix::R(-10001.0); },
       FSW_E_BAD_INPUT},
      {"availability flag 7", [](FswAcsSensorMsg& m) { m.rw_avail[0] = 7; }, FSW_E_BAD_INPUT},
      {"repeated time stamp", [](FswAcsSensorMsg& m) { m.t_ns -= kPeriodNs; }, FSW_E_TIME},
      {"time going back", [](FswAcsSensorMsg& m) { m.t_ns -= 2 * kPeriodNs; }, FSW_E_TIME},
  };
  for (const Spoil& sp : spoils) {
    sensors_at_rest(g_sens, 3 * kPeriodNs);
    sp.f(g_sens);
    EXPECT_EQ(sp.want, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)) << sp.why;
    EXPECT_TRUE(all_zero(g_act)) << sp.why;
    EXPECT_EQ(1, g_h.safe_output) << sp.why;
    EXPECT_EQ(sp.want, g_h.status);
    EXPECT_EQ(0, std::memcmp(&fb_before, &g_st.mrp_fb, sizeof fb_before)) << sp.why;
    EXPECT_EQ(t_prev, g_st.clock.t_prev_ns);
  }
  EXPECT_EQ(6u, g_st.health.bad_input);
  EXPECT_EQ(2u, g_st.health.bad_time);
  // NaN in an UNAVAILABLE wheel's speed is not read: fine
  sensors_at_rest(g_sens, 3 * kPeriodNs);
  // the next good cycle recovers and equals a run that never saw bad input
  FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
  fsw_acs_cycle(&g_st2, &g_cfg, &g_sens, nullptr, &g_act2, &g_h2);
  EXPECT_FALSE(fsw_status_is_error(s));
  EXPECT_EQ(0, g_h.safe_output);
  EXPECT_EQ(0, std::memcmp(&g_act, &g_act2, sizeof g_act));
}

// cos of the angle between the wheels' body torque -[Gs]u and Lr
double wheel_torque_alignment(const FswAcsActuatorMsg& a)
{
  double body[3] = {0, 0, 0};
  for (int k = 0; k < 4; k++) {
    double g[3];
    acsfix::pyramid_axis(k, g);
    for (int i = 0; i < 3; i++) body[i] -= a.u_s[k] * g[i];
  }
  double bl = 0, bb = 0, ll = 0;
  for (int i = 0; i < 3; i++) {
    bl += body[i] * a.Lr_B[i];
    bb += body[i] * body[i];
    ll += static_cast<double>(a.Lr_B[i]) * a.Lr_B[i];
  }
  return bl / std::sqrt(bb * ll);
}

// Verifies: REQ-ACS-004, REQ-ACS-005
TEST(FswAcsCycle, UnavailableWheelGetsZeroAndItsNaNSpeedIsIgnored)
{
  // A failed tachometer on a wheel already out of service must not stop the
  // chain: every stage (map in both modes, null motion, saturation, voltage
  // with its speed loop) reads speeds of available wheels only.  The three
  // remaining wheels still deliver a torque along Lr (the pyramid minus one
  // wheel keeps full rank), and scaling saturation keeps the direction.
  for (int variant = 0; variant < 2; variant++) {
    acsfix::golden_config(0, g_cfg);  // null motion, filter and voltages on
    g_cfg.use_null = 0;               // null motion would add a (bodiless) torque; checked below
    if (variant == 1) g_cfg.rw_map.mode = FSW_RW_MAP_POWER;
    ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
    for (int c = 0; c < 4; c++) {  // past the voltage loop's two-call warm-up
      sensors_at_rest(g_sens, c * kPeriodNs);
      g_sens.Omega[0] = acsfix::R(10.0 + c);
      g_sens.rw_avail[2] = FSW_UNAVAILABLE;
      g_sens.Omega[2] = kNaN;
      const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
      EXPECT_FALSE(fsw_status_is_error(s)) << fsw_status_name(s) << " variant " << variant;
      EXPECT_EQ(0, g_h.safe_output);
      EXPECT_EQ(0, g_act.u_s[2]);
      EXPECT_EQ(0, g_act.V[2]);
      for (int k = 0; k < 4; k++) {
        EXPECT_TRUE(std::isfinite(g_act.u_s[k]));
        EXPECT_TRUE(std::isfinite(g_act.V[k]));
      }
      EXPECT_NEAR(1.0, wheel_torque_alignment(g_act), kt::tol(1e-12, 1e-5)) << "cycle " << c;
    }
    // the wheel returns with a good speed: no NaN leaks from its stored sample
    sensors_at_rest(g_sens, 4 * kPeriodNs);
    g_sens.Omega[2] = acsfix::R(5.0);
    EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
    for (int k = 0; k < 4; k++) EXPECT_TRUE(std::isfinite(g_act.V[k]));
    EXPECT_NEAR(1.0, wheel_torque_alignment(g_act), kt::tol(1e-12, 1e-5));
  }
  // with null motion on as well: still no safe output and all finite
  acsfix::golden_config(0, g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  for (int c = 0; c < 4; c++) {
    sensors_at_rest(g_sens, c * kPeriodNs);
    g_sens.rw_avail[2] = FSW_UNAVAILABLE;
    g_sens.Omega[2] = kNaN;
    EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
    EXPECT_EQ(0, g_act.u_s[2]);
    for (int k = 0; k < 4; k++) EXPECT_TRUE(std::isfinite(g_act.V[k]));
  }
}

// h = sum over the available wheels of J_s,i Omega_i gs_i (by hand, long double)
static void hand_momentum(const FswAcsConfig& c, const FswAcsSensorMsg& m, uint64_t failed, long double h[3])
{
  h[0] = h[1] = h[2] = 0;
  for (int i = 0; i < c.mrp_fb.num_rw; i++) {
    if (m.rw_avail[i] != FSW_AVAILABLE || ((failed >> i) & 1u) != 0) continue;
    for (int k = 0; k < 3; k++)
      h[k] += static_cast<long double>(c.mrp_fb.J_s[i]) * m.Omega[i] * c.mrp_fb.gs_hat_B[i][k];
  }
}

// Issue 45 fuzzing: the momentum telemetry overflowed for a huge spin inertia
// times a speed.  Speeds of available wheels are bounded by FSW_RW_OMEGA_MAX
// (1e4 rad/s): beyond it the cycle refuses its input, or with the speed
// filter that wheel's sample is an outlier (held, then the wheel fails);
// h_w_B stays finite and equals the hand sum over the wheels in use.
// Verifies: REQ-ACS-005
TEST(FswAcsCycle, WheelSpeedBeyondTheRangeIsBadInputOrTheFiltersOutlier)
{
  const fsw_real big = acsfix::R(1e30);
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(0, g_cfg.use_speed_filter);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  long double h[3];
  // at the bound: accepted, and the telemetry is the hand sum
  sensors_at_rest(g_sens, 0);
  g_sens.Omega[0] = acsfix::R(1e4);
  g_sens.Omega[1] = acsfix::R(-1e4);
  g_sens.Omega[3] = acsfix::R(250.0);
  EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  hand_momentum(g_cfg, g_sens, 0, h);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(static_cast<double>(h[k]), g_h.h_w_B[k], kt::tol(1e-12, 1e-5) * 1e3) << k;
  // just beyond on an available wheel: bad input, safe output
  sensors_at_rest(g_sens, kPeriodNs);
  g_sens.Omega[1] = acsfix::R(-10000.5);
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_EQ(1, g_h.safe_output);
  // a huge speed of an UNAVAILABLE wheel is not read
  g_sens.Omega[1] = big;
  g_sens.rw_avail[1] = FSW_UNAVAILABLE;
  EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  EXPECT_EQ(0, g_h.h_w_B[0]);
  EXPECT_EQ(0, g_h.h_w_B[1]);
  EXPECT_EQ(0, g_h.h_w_B[2]);

  // with the speed filter: wheel 0 reads 1e30 from the first cycle on; its
  // samples are rejected (no good sample: held at 0) and after k_reject = 3
  // the wheel fails; the cycle goes on with the other three
  acsfix::wheel_config(g_cfg);
  g_cfg.use_speed_filter = 1;
  g_cfg.speed_filter.k_reject = g_cfg.speed_filter.n_recover = 3;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  for (int c = 0; c < 4; c++) {
    sensors_at_rest(g_sens, c * kPeriodNs);
    g_sens.Omega[0] = big;
    g_sens.Omega[2] = acsfix::R(30.0);
    const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
    EXPECT_FALSE(fsw_status_is_error(s)) << fsw_status_name(s) << " cycle " << c;
    EXPECT_EQ(c >= 2 ? 1u : 0u, g_h.rw_failed & 1u) << "cycle " << c;
    hand_momentum(g_cfg, g_sens, 1u, h);  // wheel 0 contributes 0 (held at 0, then failed)
    for (int k = 0; k < 3; k++)
      EXPECT_NEAR(static_cast<double>(h[k]), g_h.h_w_B[k], kt::tol(1e-12, 1e-5)) << "cycle " << c << " axis " << k;
  }
}

// Verifies: REQ-ACS-005
TEST(FswAcsCycle, BadModeRequestIsRejected)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  FswAcsCmdMsg cmd = {FSW_ACS_MODE_SUN_SAFE, FSW_ACS_ACT_THRUSTERS};  // no thrusters configured
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h));
  cmd.mode = 9;
  cmd.actuation = FSW_ACS_ACT_WHEELS;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h));
  EXPECT_EQ(FSW_ACS_MODE_SUN_SAFE, g_st.mode);
  EXPECT_EQ(0u, g_st.mode_changes);
}

/* ---- modes ---- */

// Verifies: REQ-ACS-007
TEST(FswAcsModes, TransitionResetsIntegratorAndPulseMemory)
{
  acsfix::thruster_config(g_cfg);
  g_cfg.mrp_fb.K_i = acsfix::R(0.01);
  g_cfg.mrp_fb.integral_limit = acsfix::R(1.0);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  const fsw_real small[3] = {acsfix::R(1e-4), acsfix::R(-2e-4), acsfix::R(1e-4)};
  for (int c = 0; c < 10; c++) {
    g_sens.t_ns = c * kPeriodNs;
    for (int i = 0; i < 3; i++) g_sens.sigma_BN[i] = acsfix::R(g_cfg.inertial.sigma_R0N[i] + small[i]);
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  }
  double rem = 0, integ = 0;
  for (int j = 0; j < 8; j++) rem += std::fabs(g_st.pulse_rem.rem[j]);
  for (int i = 0; i < 3; i++) integ += std::fabs(g_st.mrp_fb.int_sigma[i]);
  ASSERT_GT(rem, 0.0) << "sub-minimum requests must have left remainders";
  ASSERT_GT(integ, 0.0);
  // request sun-safe (same actuation): memory of the old mode is cleared
  FswAcsCmdMsg cmd = {FSW_ACS_MODE_SUN_SAFE, FSW_ACS_ACT_THRUSTERS};
  g_sens.t_ns = 10 * kPeriodNs;
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h)));
  EXPECT_EQ(FSW_ACS_MODE_SUN_SAFE, g_h.mode);
  EXPECT_EQ(1u, g_h.mode_changes);
  for (int j = 0; j < 8; j++) {
    EXPECT_EQ(0, g_st.pulse_rem.rem[j]);  // first pulser call after reset: no remainder
    EXPECT_EQ(0, g_act.t_on[j]);          // on-pulsing first call: b * 2.0 s = 0
  }
  for (int i = 0; i < 3; i++) EXPECT_EQ(0, g_st.mrp_fb.int_sigma[i]);  // dt = 0 on the first call
  // the same request again is not a transition
  g_sens.t_ns = 11 * kPeriodNs;
  fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h);
  EXPECT_EQ(1u, g_h.mode_changes);
}

// Verifies: REQ-ACS-007
TEST(FswAcsModes, ResetRepeatsBitForBit)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.use_null = 1;
  g_cfg.use_lpf = 1;
  g_cfg.use_volt = 1;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  static FswAcsActuatorMsg first[20];
  for (int pass = 0; pass < 2; pass++) {
    fsw_acs_reset(&g_st, &g_cfg);
    acsfix::Plant p;
    p.omega[0] = 0.01;
    p.omega[2] = -0.004;
    p.Omega[1] = 50;
    for (int c = 0; c < 20; c++) {
      p.sense(c * kPeriodNs, g_sens);
      ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
      if (pass == 0) first[c] = g_act;
      else EXPECT_EQ(0, std::memcmp(&first[c], &g_act, sizeof g_act)) << "cycle " << c;
      p.apply(g_act);
    }
  }
}

/* ---- closed loops against the independent plant ---- */

double run_closed_loop(FswAcsConfig& cfg, acsfix::Plant& p, int cycles, FswAcsState& st)
{
  EXPECT_EQ(FSW_OK, fsw_acs_init(&st, &cfg, nullptr));
  for (int c = 0; c < cycles; c++) {
    p.sense(c * kPeriodNs, g_sens);
    const FswStatus s = fsw_acs_cycle(&st, &cfg, &g_sens, nullptr, &g_act, &g_h);
    EXPECT_FALSE(fsw_status_is_error(s)) << "cycle " << c << " " << fsw_status_name(s);
    p.apply(g_act);
  }
  return g_h.att_err_angle;
}

// Verifies: REQ-ACS-016
TEST(FswAcsClosedLoop, InertialPointingWithWheelsConverges)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  g_cfg.use_null = 1;
  acsfix::Plant p;  // starts at sigma_BN = 0: 51.6 deg from the target
  p.Omega[0] = 30;
  const double e0 = p.error_angle_to(g_cfg.inertial.sigma_R0N);
  EXPECT_NEAR(4 * std::atan(std::sqrt(0.01 + 0.0025 + 0.04)), e0, 1e-6);
  run_closed_loop(g_cfg, p, 3000, g_st);  // 1500 s
  EXPECT_LT(p.error_angle_to(g_cfg.inertial.sigma_R0N), 0.05 * acsfix::kPi / 180);  // < 0.05 deg
  for (int i = 0; i < 3; i++) EXPECT_LT(std::fabs(p.omega[i]), 1e-5);
}

// Verifies: REQ-ACS-016
TEST(FswAcsClosedLoop, SunSafeAcquiresTheSunFromATumble)
{
  acsfix::wheel_config(g_cfg);
  acsfix::Plant p;
  p.omega[0] = 0.01;
  p.omega[1] = -0.006;
  p.omega[2] = 0.008;
  p.sun_N[0] = 0.0;
  p.sun_N[1] = -1.0;  // sun along -y of N: initially on the -y face
  run_closed_loop(g_cfg, p, 3000, g_st);
  double C[3][3];
  p.dcm_BN(C);
  const double sz = C[2][0] * p.sun_N[0] + C[2][1] * p.sun_N[1] + C[2][2] * p.sun_N[2];  // z_B . s
  // +z within asin(lit_threshold) = 0.57 deg (+0.1 deg margin) of the Sun
  EXPECT_GT(sz, std::cos(std::asin(0.01) + 0.1 * acsfix::kPi / 180));
  EXPECT_EQ(1, g_h.sun_valid);
}

// Verifies: REQ-ACS-016
TEST(FswAcsClosedLoop, InertialPointingWithThrustersHoldsAndIsDeterministic)
{
  for (int pulser = 0; pulser < 2; pulser++) {
    acsfix::thruster_config(g_cfg, pulser);
    acsfix::Plant p, q;
    // start about 5.5 deg away from the target (sigma offset 0.012 on x)
    for (int i = 0; i < 3; i++) p.sigma[i] = q.sigma[i] = g_cfg.inertial.sigma_R0N[i] + (i == 0 ? 0.012 : 0.0);
    run_closed_loop(g_cfg, p, 1200, g_st);  // 600 s
    const double e = p.error_angle_to(g_cfg.inertial.sigma_R0N);
    // within the Schmitt dead band of 0.6 deg (see acs_fixture.hpp) + margin
    EXPECT_LT(e, 1.0 * acsfix::kPi / 180) << "pulser " << pulser;
    run_closed_loop(g_cfg, q, 1200, g_st2);
    for (int i = 0; i < 3; i++) {
      EXPECT_EQ(p.sigma[i], q.sigma[i]);
      EXPECT_EQ(p.omega[i], q.omega[i]);
    }
  }
}

}  // namespace

// ---- issue 13: an error cycle advances no state ---------------------------

namespace {
// The state with the health counters and the scratch of the stages set to
// those of `ref`: what must be byte-identical after an error cycle.
FswAcsState g_before, g_after;
void mask_health_and_scratch(FswAcsState& s, const FswAcsState& ref)
{
  s.health = ref.health;
  s.css.health = ref.css.health;
  s.sunsafe.health = ref.sunsafe.health;
  s.inertial.health = ref.inertial.health;
  s.track.health = ref.track.health;
  s.mrp_fb.health = ref.mrp_fb.health;
  s.lpf.health = ref.lpf.health;
  s.rw_map.health = ref.rw_map.health;
  s.rw_map.work = ref.rw_map.work;
  s.rw_null.health = ref.rw_null.health;
  s.rw_sat.health = ref.rw_sat.health;
  s.rw_volt.health = ref.rw_volt.health;
  s.speed_filter.health = ref.speed_filter.health;
  s.thr_map.health = ref.thr_map.health;
  s.thr_map.work = ref.thr_map.work;
  s.pulse_rem.common.health = ref.pulse_rem.common.health;
  s.pulse_schmitt.common.health = ref.pulse_schmitt.common.health;
  s.work = ref.work;
}
}  // namespace

// Finding 1 (a): reference wheel configuration, torque filter on, sun-safe;
// omega = (1e-3, 1e-3, 0) at t = 0, then a huge finite rate at t = 0.5 s.
// The second cycle is bad input (mrp_fb overflows) and before the fix the
// cycle count, the application's clock and the filter memory advanced, so a
// good retry at t = 0.5 s got E_TIME.  Now the state is byte-identical
// (health and scratch aside) and the retry equals a run without the glitch.
// Verifies: REQ-ACS-006
TEST(FswAcsCycle, Issue13ErrorCycleAdvancesNoStateAndRetryWorks)
{
  const double big = 0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_SUN_SAFE;
  g_cfg.use_lpf = 1;
  g_cfg.use_null = 1;
  g_cfg.use_volt = 1;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st2, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  g_sens.omega_BN_B[0] = acsfix::R(1e-3);
  g_sens.omega_BN_B[1] = acsfix::R(1e-3);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st2, &g_cfg, &g_sens, nullptr, &g_act2, &g_h2)));
  g_before = g_st;

  g_sens.t_ns = kPeriodNs;
  g_sens.omega_BN_B[0] = static_cast<fsw_real>(big);
  g_sens.omega_BN_B[1] = static_cast<fsw_real>(big);
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(all_zero(g_act));
  EXPECT_EQ(1, g_h.safe_output);
  EXPECT_EQ(1u, g_st.cycles);
  EXPECT_EQ(g_before.clock.t_prev_ns, g_st.clock.t_prev_ns);
  g_after = g_st;
  mask_health_and_scratch(g_after, g_before);
  EXPECT_EQ(0, std::memcmp(&g_before, &g_after, sizeof g_before));

  // good retry at the same time: accepted, identical to the clean twin
  g_sens.omega_BN_B[0] = acsfix::R(1e-3);
  g_sens.omega_BN_B[1] = acsfix::R(1e-3);
  const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
  fsw_acs_cycle(&g_st2, &g_cfg, &g_sens, nullptr, &g_act2, &g_h2);
  EXPECT_FALSE(fsw_status_is_error(s));
  EXPECT_EQ(0, std::memcmp(&g_act, &g_act2, sizeof g_act));
  EXPECT_EQ(2u, g_st.cycles);
  EXPECT_EQ(0, std::memcmp(g_st.lpf.LrF_prev, g_st2.lpf.LrF_prev, sizeof g_st.lpf.LrF_prev));
}

// Finding 1 (b): power-optimal mapping with a denormal eps_P made every
// cycle bad input while the clocks advanced; check now refuses the config.
// Verifies: REQ-ACS-001, REQ-RWMAP-001
TEST(FswAcsConfig, Issue13DenormalEpsPIsRefused)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.rw_map.mode = FSW_RW_MAP_POWER;
  g_cfg.rw_map.eps_P = std::numeric_limits<fsw_real>::denorm_min() * 8;
  const char* field = nullptr;
  EXPECT_EQ(FSW_E_CONFIG, fsw_acs_check(&g_cfg, &field));
  ASSERT_NE(nullptr, field);
  EXPECT_STREQ("rw_map", field);
}

// Issue 21: the error-cycle contract of Issue13ErrorCycleAdvancesNoState...
// for any configuration in g_cfg: at rest, one good cycle, then a huge
// finite rate about `axis` that overflows the control law -> BAD_INPUT,
// safe output, state as before (health and scratch aside); the retry equals
// a twin that never saw the bad cycle.
namespace {
void expect_error_cycle_advances_no_state(int axis, const char* why)
{
  const double big = 0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max());
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr)) << why;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st2, &g_cfg, nullptr)) << why;
  sensors_at_rest(g_sens, 0);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h))) << why;
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st2, &g_cfg, &g_sens, nullptr, &g_act2, &g_h2))) << why;
  g_before = g_st;
  g_sens.t_ns = kPeriodNs;
  g_sens.omega_BN_B[axis] = static_cast<fsw_real>(big);
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)) << why;
  EXPECT_TRUE(all_zero(g_act)) << why;
  EXPECT_EQ(1, g_h.safe_output) << why;
  g_after = g_st;
  mask_health_and_scratch(g_after, g_before);
  EXPECT_EQ(0, std::memcmp(&g_before, &g_after, sizeof g_before)) << why;
  sensors_at_rest(g_sens, kPeriodNs);
  EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h))) << why;
  fsw_acs_cycle(&g_st2, &g_cfg, &g_sens, nullptr, &g_act2, &g_h2);
  EXPECT_EQ(0, std::memcmp(&g_act, &g_act2, sizeof g_act)) << why;
}
}  // namespace

// Issue 21: with thrusters, for both pulsers (the snapshot of the mapper
// diagnostics and of the pulser's memory is put back).
// Verifies: REQ-ACS-006
TEST(FswAcsCycle, Issue21ThrusterErrorCycleAdvancesNoState)
{
  acsfix::thruster_config(g_cfg, FSW_ACS_PULSE_REMAINDER);
  expect_error_cycle_advances_no_state(0, "remainder pulser");
  acsfix::thruster_config(g_cfg, FSW_ACS_PULSE_SCHMITT);
  expect_error_cycle_advances_no_state(2, "Schmitt pulser");
}

// Issue 21: inputs the sun-safe and thruster paths read: a NaN reading of an
// available CSS in SUN_SAFE, a NaN centre of mass with thrusters.
// Verifies: REQ-ACS-005
TEST(FswAcsCycle, Issue21SunSafeAndThrusterInputsAreChecked)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  g_sens.css[2] = kNaN;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(all_zero(g_act));
  g_sens.css_avail[2] = FSW_UNAVAILABLE;  // an unavailable sensor's reading is not read
  EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  acsfix::thruster_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  g_sens.r_CoM_B[1] = kNaN;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(all_zero(g_act));
  g_sens.r_CoM_B[1] = 0;
  EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
}

// Issue 21: every pointer NULL in turn (cmd and bad_field may be NULL by
// contract): assert once, FSW_E_NULL_ARG; the cycle still writes the safe
// output and a zero health message wherever those pointers are valid.
// Verifies: REQ-GEN-007
TEST(FswAcsIssue21, EveryNullArgumentAssertsAndReturns)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  const char* field = nullptr;
  kt::each_null("fsw_acs_check", [&](const FswAcsConfig* c) { return fsw_acs_check(c, &field); }, &g_cfg);
  EXPECT_EQ(std::string("cfg"), field);
  kt::each_null("fsw_acs_init", [](FswAcsState* st, const FswAcsConfig* c) { return fsw_acs_init(st, c, nullptr); },
                &g_st2, &g_cfg);
  kt::each_null("fsw_acs_reset", fsw_acs_reset, &g_st, &g_cfg);
  kt::each_null("fsw_acs_config_set_geometry", fsw_acs_config_set_geometry, &g_cfg2, &g_geo);
  kt::each_null(
      "fsw_acs_cycle",
      [](FswAcsState* st, const FswAcsConfig* c, const FswAcsSensorMsg* sens, FswAcsActuatorMsg* act,
         FswAcsHealthMsg* h) {
        if (act != nullptr) act->u_s[0] = 9;
        if (h != nullptr) h->cycles = 9;
        const FswStatus s = fsw_acs_cycle(st, c, sens, nullptr, act, h);
        if (act != nullptr) EXPECT_TRUE(all_zero(*act));
        if (h != nullptr) EXPECT_EQ(0u, h->cycles);
        return s;
      },
      &g_st, &g_cfg, &g_sens, &g_act, &g_h);
  EXPECT_EQ(4u, g_st.health.bad_input);  // NULL_ARG is counted whenever the state was given
}

// Issue 21: the remaining request and bookkeeping paths of the cycle.
// Verifies: REQ-ACS-005
TEST(FswAcsIssue21, RequestsCountersAndResetOfANotReadyState)
{
  // wheels requested from a thruster-only configuration, an unknown
  // actuation, an availability flag 2 on a CSS in SUN_SAFE: bad input
  acsfix::thruster_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  FswAcsCmdMsg cmd = {FSW_ACS_MODE_INERTIAL, FSW_ACS_ACT_WHEELS};
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h));
  cmd.actuation = 7;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h));
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  g_sens.css_avail[4] = 2;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(all_zero(g_act));
  // the cycle and transition counters saturate instead of wrapping
  sensors_at_rest(g_sens, 0);
  g_st.cycles = UINT32_MAX;
  g_st.mode_changes = UINT32_MAX;
  cmd = {FSW_ACS_MODE_INERTIAL, FSW_ACS_ACT_WHEELS};  // a transition from SUN_SAFE
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h)));
  EXPECT_EQ(UINT32_MAX, g_st.cycles);
  EXPECT_EQ(UINT32_MAX, g_st.mode_changes);
  EXPECT_EQ(FSW_ACS_MODE_INERTIAL, g_st.mode);
  // reset of a state that init refused changes nothing
  g_cfg.mrp_fb.K = 0;
  ASSERT_EQ(FSW_E_CONFIG, fsw_acs_init(&g_st, &g_cfg, nullptr));
  g_before = g_st;
  kestrel_assert_reset();
  fsw_acs_reset(&g_st, &g_cfg);
  EXPECT_EQ(0ul, kestrel_assert_count());
  EXPECT_EQ(0, std::memcmp(&g_before, &g_st, sizeof g_st));
}

// Issue 21: a control law without wheel momentum (mrp_fb.num_rw = 0) in
// front of a wheel chain is legal (H_s omitted, docs/fsw/mrp_fb.md), and then the
// spin-axis and spin-inertia copies have nothing to agree with.
// Verifies: REQ-ACS-002
TEST(FswAcsIssue21, ControlLawWithoutWheelMomentumIsAccepted)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.mrp_fb.num_rw = 0;
  g_cfg.use_volt = 1;
  g_cfg.rw_volt.J_s[0] = acsfix::R(5.0);  // would differ from mrp_fb.J_s
  const char* field = "x";
  EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field));
  EXPECT_EQ(nullptr, field);
  EXPECT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
}

// Issue 21: the wheel error cycle without null motion and voltages (the
// snapshot paths for a chain with neither).
// Verifies: REQ-ACS-006
TEST(FswAcsCycle, Issue21WheelErrorCycleWithoutNullOrVoltages)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  ASSERT_EQ(0, g_cfg.use_null);
  ASSERT_EQ(0, g_cfg.use_volt);
  expect_error_cycle_advances_no_state(1, "wheels, no null motion, no voltages");
}

// Issue 21 (seed 9001): the geometry copies are compared over the configured
// wheels only.  Rows past num_rw are unused capacity (every stage reads its
// first num_rw rows), so copies that differ only there must be accepted; a
// difference in the last used row must still be refused.
// Verifies: REQ-ACS-001, REQ-ACS-002
TEST(FswAcsIssue21, GeometryCopiesAreComparedOverTheUsedWheelsOnly)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.use_null = 1;
  const int n = g_cfg.rw_map.num_rw;
  ASSERT_LT(n, FSW_MAX_RW);  // there is an unused row to spoil
  g_cfg.rw_null.gs_hat_B[n][0] = acsfix::R(1.0);
  g_cfg.mrp_fb.gs_hat_B[n][1] = acsfix::R(1.0);
  ASSERT_NE(g_cfg.rw_null.gs_hat_B[n][0], g_cfg.rw_map.gs_hat_B[n][0]);
  const char* field = "x";
  EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field));
  EXPECT_EQ(nullptr, field);
  // the same spoil one row up, in a used wheel: refused
  acsfix::wheel_config(g_cfg);
  g_cfg.use_null = 1;
  g_cfg.rw_null.gs_hat_B[n - 1][0] = -g_cfg.rw_null.gs_hat_B[n - 1][0];
  g_cfg.rw_null.gs_hat_B[n - 1][1] = -g_cfg.rw_null.gs_hat_B[n - 1][1];
  g_cfg.rw_null.gs_hat_B[n - 1][2] = -g_cfg.rw_null.gs_hat_B[n - 1][2];  // still a unit vector
  EXPECT_EQ(FSW_E_CONFIG, fsw_acs_check(&g_cfg, &field));
  EXPECT_EQ(std::string("rw_null.gs_hat_B"), field);
}

// Issue 21 (seed 9001): an error cycle puts back the transition counter too.
// One commanded transition (SUN_SAFE -> INERTIAL) counts 1; a following
// cycle that fails inside a stage (an angular rate of half the real's
// maximum overflows the control law) must leave mode and counter as they
// were, 1 and INERTIAL, and the next good cycle still counts no transition.
// Verifies: REQ-ACS-006
TEST(FswAcsCycle, Issue21ErrorCycleKeepsTheTransitionCount)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_ACS_MODE_SUN_SAFE, g_cfg.initial_mode);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  const FswAcsCmdMsg cmd = {FSW_ACS_MODE_INERTIAL, FSW_ACS_ACT_WHEELS};
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h)));
  ASSERT_EQ(1u, g_st.mode_changes);
  sensors_at_rest(g_sens, kPeriodNs);
  g_sens.omega_BN_B[1] = static_cast<fsw_real>(0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  ASSERT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h));
  EXPECT_EQ(1u, g_st.mode_changes);
  EXPECT_EQ(FSW_ACS_MODE_INERTIAL, g_st.mode);
  sensors_at_rest(g_sens, 2 * kPeriodNs);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &cmd, &g_act, &g_h)));
  EXPECT_EQ(1u, g_h.mode_changes);
}

// Issue 21: the actuator message carries the mapper's thruster forces
// (docs/fsw/fsw_acs.md: F[i] and t_on[i] with thruster actuation).  With the
// exact (NNLS) mapping and a request the eight thrusters can deliver, the
// forces in the message must give the published torque about the centre of
// mass: sum_i ((r_i - r_CoM) x g_i) F_i = Lr_B (docs/fsw/thr_map.md, 8.6),
// computed here from the fixture's geometry (kThrR, kThrG), with
// 0 <= F_i <= F_max.  The request: at rest, sigma_BN = (0.01, -0.005, 0.002)
// against sigma_R0N = 0 gives |Lr| ~ K |sigma| = 0.2 N m, well inside the
// ~1.8 N m authority per axis, so the mapper reports FSW_OK (delivered), not
// a warning.  Tolerance: the active-set solver stops at a relative residual
// of 1000 eps (K4_TOL) of the request, 1e-9 N m in double; float as the
// mapper's own property test (2e-3).
// Issue 14: the same with one thruster flagged unavailable (thr_avail):
// it gets no force and no on-time, and the seven left still deliver Lr.
// Verifies: REQ-ACS-015
TEST(FswAcsCycle, Issue21ThrusterForcesInTheMessageGiveTheRequestedTorque)
{
  for (int flagged : {-1, 2, 5})
  for (int pulser : {FSW_ACS_PULSE_REMAINDER, FSW_ACS_PULSE_SCHMITT}) {
    SCOPED_TRACE(flagged);
    acsfix::thruster_config(g_cfg, pulser);
    for (int i = 0; i < 3; i++) g_cfg.inertial.sigma_R0N[i] = 0;
    ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
    sensors_at_rest(g_sens, 0);
    if (flagged >= 0) g_sens.thr_avail[flagged] = FSW_UNAVAILABLE;
    g_sens.sigma_BN[0] = acsfix::R(0.01);
    g_sens.sigma_BN[1] = acsfix::R(-0.005);
    g_sens.sigma_BN[2] = acsfix::R(0.002);
    const double com[3] = {0.02, -0.01, 0.03};
    for (int i = 0; i < 3; i++) g_sens.r_CoM_B[i] = acsfix::R(com[i]);
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
    ASSERT_EQ(1, g_act.thrusters_active);
    EXPECT_EQ(FSW_OK, g_h.stage_status[FSW_ACS_STAGE_THR_MAP]) << "request not delivered";
    double Lr2 = 0;
    for (int i = 0; i < 3; i++) Lr2 += static_cast<double>(g_act.Lr_B[i]) * g_act.Lr_B[i];
    ASSERT_GT(std::sqrt(Lr2), 0.1);  // a real request (K |sigma| = 0.23 N m)
    double tau[3] = {0, 0, 0};
    for (int j = 0; j < 8; j++) {
      const double* g = acsfix::kThrG[j];
      const double r[3] = {acsfix::kThrR[j][0] - com[0], acsfix::kThrR[j][1] - com[1], acsfix::kThrR[j][2] - com[2]};
      const double d[3] = {r[1] * g[2] - r[2] * g[1], r[2] * g[0] - r[0] * g[2], r[0] * g[1] - r[1] * g[0]};
      for (int k = 0; k < 3; k++) tau[k] += d[k] * g_act.F[j];
      EXPECT_GE(g_act.F[j], 0) << j;
      EXPECT_LE(g_act.F[j], acsfix::kFmax * (1 + 1e-9)) << j;
    }
    for (int k = 0; k < 3; k++) EXPECT_NEAR(g_act.Lr_B[k], tau[k], kt::tol(1e-9, 2e-3)) << "axis " << k;
    for (int j = 8; j < FSW_MAX_THR; j++) EXPECT_EQ(0, g_act.F[j]) << j;
    if (flagged >= 0) {
      EXPECT_EQ(0, g_act.F[flagged]);
      EXPECT_EQ(0, g_act.t_on[flagged]);
    }
  }
}

// A thruster flag other than 0/1 is bad input of the cycle (safe output);
// beyond num_thr it is not read.
// Verifies: REQ-ACS-005
TEST(FswAcsCycle, ThrusterFlagsAreZeroOrOne)
{
  acsfix::thruster_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  g_sens.thr_avail[7] = 2;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_TRUE(all_zero(g_act));
  g_sens.thr_avail[7] = 0;
  g_sens.thr_avail[8] = 9;
  EXPECT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
}

// Issue 21: an error cycle puts the dynamic state back but every stage
// keeps its health counters (docs/fsw/fsw_acs.md, "keeping only the stages'
// health counters"; they count this cycle's statuses).  One good cycle, then
// a finite rate that overflows the control law: every stage that ran was
// called twice, so its counter of calls is 2 (the control law's bad input
// counted once), not the 1 of the snapshot taken before the bad cycle.
namespace {
void expect_stage_health_after_error_cycle(const char* why)
{
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr)) << why;
  sensors_at_rest(g_sens, 0);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h))) << why;
  sensors_at_rest(g_sens, kPeriodNs);
  g_sens.omega_BN_B[0] = static_cast<fsw_real>(0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  ASSERT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)) << why;
  EXPECT_EQ(2u, g_st.mrp_fb.health.calls) << why;
  EXPECT_EQ(1u, g_st.mrp_fb.health.bad_input) << why;
  if (g_cfg.use_lpf) {
    EXPECT_EQ(2u, g_st.lpf.health.calls) << why;
    EXPECT_EQ(0u, g_st.lpf.health.bad_input) << why;  // its own counters, not the control law's (seed 20261203)
  }
  if (g_cfg.has_wheels && g_cfg.use_volt) EXPECT_EQ(2u, g_st.rw_volt.health.calls) << why;
  if (g_cfg.initial_actuation == FSW_ACS_ACT_THRUSTERS) {
    if (g_cfg.pulser == FSW_ACS_PULSE_REMAINDER)
      EXPECT_EQ(2u, g_st.pulse_rem.common.health.calls) << why;
    else
      EXPECT_EQ(2u, g_st.pulse_schmitt.common.health.calls) << why;
  }
}
}  // namespace

// Verifies: REQ-ACS-006
TEST(FswAcsCycle, Issue21ErrorCycleKeepsEveryStagesHealthCounters)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.use_lpf = 1;
  g_cfg.use_volt = 1;
  expect_stage_health_after_error_cycle("wheels, filter, voltages");
  acsfix::thruster_config(g_cfg, FSW_ACS_PULSE_REMAINDER);
  g_cfg.use_lpf = 1;
  expect_stage_health_after_error_cycle("thrusters, filter, remainder pulser");
  acsfix::thruster_config(g_cfg, FSW_ACS_PULSE_SCHMITT);
  expect_stage_health_after_error_cycle("thrusters, Schmitt pulser");
}

// Mutation seed 31337 (fsw_acs.c:391): in inertial mode the health message
// carries the attitude-tracking stage's own status.  A finite attitude of
// half the real's maximum passes the cycle's finiteness check, but in the
// tracking stage [BN] = MRP2C(sigma_BN) has |sigma|^2 = Inf, so every entry
// is Inf / Inf = NaN and omega_RN_B = [BN] * 0 is NaN: the stage refuses it
// (FSW_E_BAD_INPUT), the guidance stage before it (independent of the
// sensors) is OK.  The message is zeroed at the start of every cycle, so a
// TRACK entry of FSW_E_BAD_INPUT can only come from the stage.
// Verifies: REQ-ACS-012
TEST(FswAcsCycle, Seed31337InertialHealthCarriesTheTrackingStatus)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  EXPECT_EQ(FSW_OK, g_h.stage_status[FSW_ACS_STAGE_TRACK]);
  sensors_at_rest(g_sens, kPeriodNs);
  g_sens.sigma_BN[0] = static_cast<fsw_real>(0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_EQ(FSW_E_BAD_INPUT, g_h.stage_status[FSW_ACS_STAGE_TRACK]);
  EXPECT_EQ(FSW_OK, g_h.stage_status[FSW_ACS_STAGE_GUIDANCE]);
  EXPECT_EQ(1u, g_st.track.health.bad_input);
  EXPECT_TRUE(all_zero(g_act));
}

// ---- issue 14: the speed filter in the chain ------------------------------

namespace {
void speed_filter_on(FswAcsConfig& c, uint32_t k_reject, uint32_t n_window)
{
  c.use_speed_filter = 1;
  c.speed_filter.k_reject = k_reject;
  c.speed_filter.n_recover = 3;
  c.speed_filter.n_window = n_window;
  for (int i = 0; i < 4; i++) {
    c.speed_filter.noise[i] = acsfix::R(1.0);
    c.speed_filter.resid_tol[i] = acsfix::R(1e-3);
  }
}
}  // namespace

// Without the filter a NaN speed of an available wheel is bad input (safe
// output); with it, it is that wheel's outlier: held, then after k_reject = 2
// cycles the wheel is failed, shows in rw_failed, gets 0 torque, and the
// three others deliver the requested torque.
// Verifies: REQ-ACS-014
TEST(FswAcsSpeedFilter, ANaNTachometerFailsItsWheelNotTheCycle)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  g_sens.sigma_BN[0] = acsfix::R(0.01);
  g_sens.Omega[1] = kNaN;
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));

  speed_filter_on(g_cfg, 2, 0);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  for (int c = 0; c < 4; c++) {
    sensors_at_rest(g_sens, c * kPeriodNs);
    g_sens.sigma_BN[0] = acsfix::R(0.01);
    for (int i = 0; i < 4; i++) g_sens.Omega[i] = acsfix::R(20.0 * i);
    if (c >= 1) g_sens.Omega[1] = kNaN;
    const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
    ASSERT_FALSE(fsw_status_is_error(s)) << c;
    EXPECT_EQ(0, g_h.safe_output);
    EXPECT_EQ(c >= 2 ? 2u : 0u, g_h.rw_failed) << c;
    EXPECT_EQ(0u, g_h.rw_latched);
    EXPECT_EQ(g_st.work.filt_out.Omega[1], acsfix::R(20.0)) << c;  // held, never NaN
    if (c >= 2) EXPECT_EQ(0, g_act.u_s[1]) << c;
    else EXPECT_NE(0, g_act.u_s[1]) << c;
    EXPECT_NEAR(1.0, wheel_torque_alignment(g_act), kt::tol(1e-12, 1e-5)) << c;
  }
}

// A tachometer frozen at 10 rad/s under an attitude error of 0.1 (MRP): the
// commanded torques move every wheel by far more than resid_tol = 1e-3 rad/s
// over a window of n_window = 3 cycles.  The window opens on the first
// cycle's sample (k = 0) and closes at k = 3: wheel 2 latched there, not
// before; the live wheels (speeds following their torque exactly) never.
// An error cycle at k = 2 leaves the torque of that interval unknown: the
// window restarts at the retry and the latch comes at k = 5.
// Verifies: REQ-ACS-014, REQ-ACS-006
TEST(FswAcsSpeedFilter, AFrozenTachometerUnderTorqueIsLatchedAndAnErrorCycleRestartsTheWindow)
{
  for (int with_error = 0; with_error < 2; with_error++) {
    acsfix::wheel_config(g_cfg);
    g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
    speed_filter_on(g_cfg, 3, 3);
    ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
    double Omega[4] = {0.0, 5.0, 10.0, 15.0};
    const double dt = 1e-9 * static_cast<double>(kPeriodNs);
    int latched_at = -1;
    for (int k = 0; k <= 7 && latched_at < 0; k++) {
      sensors_at_rest(g_sens, k * kPeriodNs);
      g_sens.sigma_BN[0] = acsfix::R(0.1);
      g_sens.sigma_BN[1] = acsfix::R(-0.05);
      for (int i = 0; i < 4; i++) g_sens.Omega[i] = acsfix::R(i == 2 ? 10.0 : Omega[i]);
      if (with_error && k == 2) {
        g_sens.omega_BN_B[0] = kNaN;
        ASSERT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
        EXPECT_EQ(0u, g_st.work.u_last_valid);
        g_sens.omega_BN_B[0] = acsfix::R(0.0);  // good retry at the same time
      }
      ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h))) << k;
      if (g_h.rw_latched != 0u) {
        latched_at = k;
        EXPECT_EQ(4u, g_h.rw_latched);
        EXPECT_EQ(4u, g_h.rw_failed);
        EXPECT_EQ(0, g_act.u_s[2]);
        EXPECT_NEAR(1.0, wheel_torque_alignment(g_act), kt::tol(1e-12, 1e-5));
      } else {
        EXPECT_GT(std::fabs(g_act.u_s[2]), 1e-3) << k;  // torqued: the frozen reading cannot hide
      }
      // the live wheels follow their torque (J_s from the geometry)
      for (int i = 0; i < 4; i++)
        if (i != 2) Omega[i] += g_act.u_s[i] / g_cfg.speed_filter.J_s[i] * dt;
    }
    EXPECT_EQ(with_error ? 5 : 3, latched_at);
  }
}

// The filter's state is put back on an error cycle like every stage's
// (health and the work area aside), and reset clears a latched wheel.
// Verifies: REQ-ACS-014, REQ-ACS-006
TEST(FswAcsSpeedFilter, ErrorCycleRestoresTheFilterAndResetClearsALatch)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  speed_filter_on(g_cfg, 2, 0);
  g_cfg.speed_filter.n_stale = 2;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  for (int k = 0; k < 3; k++) {  // wheel 0 reads 7.0 three times: latched by the stale test
    sensors_at_rest(g_sens, k * kPeriodNs);
    for (int i = 0; i < 4; i++) g_sens.Omega[i] = acsfix::R(i == 0 ? 7.0 : 1.0 + 0.01 * k);
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  }
  EXPECT_EQ(1u, g_h.rw_latched);
  g_before = g_st;
  sensors_at_rest(g_sens, 3 * kPeriodNs);
  g_sens.Omega[1] = acsfix::R(500.0);  // an outlier the filter counts ...
  // ... in a cycle that fails after the filter ran: the control law
  // overflows on a huge finite rate
  g_sens.omega_BN_B[2] = static_cast<fsw_real>(0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  ASSERT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_EQ(1u, g_h.rw_latched);  // the health message shows the filter as it stands
  g_after = g_st;
  mask_health_and_scratch(g_after, g_before);
  EXPECT_EQ(0, std::memcmp(&g_before, &g_after, sizeof g_before));
  fsw_acs_reset(&g_st, &g_cfg);
  sensors_at_rest(g_sens, 4 * kPeriodNs);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  EXPECT_EQ(0u, g_h.rw_latched);
  EXPECT_EQ(0u, g_h.rw_failed);
}

// ---- mutation seed 20261203: gaps its survivors showed ---------------------

// An off-pulsing thruster set (thr_map sign -1) needs off-pulsing pulsing
// (base_thrust_state 1): that pairing is accepted, the mismatch refused by
// name, for both pulsers (docs/fsw/fsw_acs.md, "Checking the whole").
// Verifies: REQ-ACS-001, REQ-ACS-002
TEST(FswAcsConfig, OffPulsingThrustersNeedOffPulsingPulsing)
{
  for (int pulser : {FSW_ACS_PULSE_REMAINDER, FSW_ACS_PULSE_SCHMITT}) {
    acsfix::thruster_config(g_cfg, pulser);
    g_cfg.thr_map.thr_force_sign = -1;
    g_cfg.pulse_rem.common.base_thrust_state = 1;
    g_cfg.pulse_schmitt.common.base_thrust_state = 1;
    const char* field = nullptr;
    EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field)) << (field ? field : "");
    g_cfg.pulse_rem.common.base_thrust_state = 0;
    g_cfg.pulse_schmitt.common.base_thrust_state = 0;
    EXPECT_EQ(FSW_E_CONFIG, fsw_acs_check(&g_cfg, &field));
    ASSERT_NE(nullptr, field);
    EXPECT_EQ(std::string(pulser == FSW_ACS_PULSE_REMAINDER ? "pulse_rem.base_thrust_state"
                                                            : "pulse_schmitt.base_thrust_state"),
              field);
  }
}

// With the speed filter on, the sensor message's own availability flags
// still reach every stage (the filter ORs them with its verdicts): a wheel
// flagged unavailable gets no torque, the three others deliver Lr, and the
// flag is not a filter failure.
// Verifies: REQ-ACS-014
TEST(FswAcsSpeedFilter, FlaggedWheelsStayUnavailableThroughTheFilter)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  speed_filter_on(g_cfg, 3, 0);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  for (int c = 0; c < 3; c++) {
    sensors_at_rest(g_sens, c * kPeriodNs);
    g_sens.sigma_BN[0] = acsfix::R(0.01);
    g_sens.sigma_BN[2] = acsfix::R(-0.02);
    g_sens.rw_avail[3] = FSW_UNAVAILABLE;
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
    EXPECT_EQ(0, g_act.u_s[3]) << c;
    EXPECT_NE(0, g_act.u_s[0]) << c;
    EXPECT_EQ(0u, g_h.rw_failed) << c;
    EXPECT_NEAR(1.0, wheel_torque_alignment(g_act), kt::tol(1e-12, 1e-5)) << c;
  }
}

// ---- issue 14: reference and gain commands ----------------------------------

namespace {
FswAcsCmdMsg inertial_cmd()
{
  FswAcsCmdMsg c{};
  c.mode = FSW_ACS_MODE_INERTIAL;
  c.actuation = FSW_ACS_ACT_WHEELS;
  return c;
}
}  // namespace

// At rest (sigma_BN = 0, omega = 0, wheels at 0) Lr = K sigma_RN
// (InertialAtRestGivesKSigmaRN).  A set_ref command makes the reference
// (0.1, -0.2, 0.05) from the cycle that receives it, held on the cycles
// after (no command); a set_gains command K = 2.88 (twice the fixture's
// 1.44) doubles Lr; reset brings back the configured reference and gains.
// Verifies: REQ-ACS-013
TEST(FswAcsCommands, ReferenceAndGainsAreSetHeldAndResetBack)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  const double K = g_cfg.mrp_fb.K, ref[3] = {0.1, -0.2, 0.05};
  FswAcsCmdMsg c = inertial_cmd();
  c.set_ref = 1;
  for (int i = 0; i < 3; i++) c.sigma_R0N[i] = acsfix::R(ref[i]);
  for (int k = 0; k < 3; k++) {
    sensors_at_rest(g_sens, k * kPeriodNs);
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, k == 0 ? &c : nullptr, &g_act, &g_h)));
    for (int i = 0; i < 3; i++) {
      EXPECT_NEAR(-ref[i], g_h.sigma_BR[i], kTol) << k;
      EXPECT_NEAR(K * ref[i], g_act.Lr_B[i], kt::tol(1e-12, 1e-6)) << k;
    }
  }
  EXPECT_EQ(0u, g_st.mode_changes);  // a set command is not a transition
  FswAcsCmdMsg g = inertial_cmd();
  g.set_gains = 1;
  g.K = acsfix::R(2.0 * K);
  g.P = g_cfg.mrp_fb.P;
  sensors_at_rest(g_sens, 3 * kPeriodNs);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &g, &g_act, &g_h)));
  for (int i = 0; i < 3; i++) EXPECT_NEAR(2.0 * K * ref[i], g_act.Lr_B[i], kt::tol(1e-12, 1e-6));
  fsw_acs_reset(&g_st, &g_cfg);
  sensors_at_rest(g_sens, 4 * kPeriodNs);
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  for (int i = 0; i < 3; i++) EXPECT_NEAR(K * g_cfg.inertial.sigma_R0N[i], g_act.Lr_B[i], kTol);
}

// A bad set command is bad input of its cycle (safe output) and applies
// nothing; so is a good one in a cycle that fails later (here the control
// law overflows on a huge finite rate): the reference stays the configured
// one on the next good cycle.
// Verifies: REQ-ACS-013
TEST(FswAcsCommands, BadOrFailedCommandsApplyNothing)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  const double K = g_cfg.mrp_fb.K;
  struct Bad {
    const char* why;
    void (*spoil)(FswAcsCmdMsg&);
  } bad[] = {
      {"set_ref 2", [](FswAcsCmdMsg& c) { c.set_ref = 2; }},
      {"set_gains 7", [](FswAcsCmdMsg& c) { c.set_gains = 7; }},
      {"NaN reference", [](FswAcsCmdMsg& c) { c.set_ref = 1; c.sigma_R0N[1] = kNaN; }},
      {"huge reference", [](FswAcsCmdMsg& c) {
         c.set_ref = 1;
         c.sigma_R0N[0] = std::numeric_limits<fsw_real>::max();
       }},
      {"K zero", [](FswAcsCmdMsg& c) { c.set_gains = 1; c.K = 0; c.P = 1; }},
      {"P negative", [](FswAcsCmdMsg& c) { c.set_gains = 1; c.K = 1; c.P = -1; }},
      {"P NaN", [](FswAcsCmdMsg& c) { c.set_gains = 1; c.K = 1; c.P = kNaN; }},
      {"K infinite", [](FswAcsCmdMsg& c) { c.set_gains = 1; c.K = std::numeric_limits<fsw_real>::infinity(); c.P = 1; }},
  };
  uint64_t t = 0;
  for (const Bad& b : bad) {
    FswAcsCmdMsg c = inertial_cmd();
    b.spoil(c);
    sensors_at_rest(g_sens, t);
    EXPECT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &c, &g_act, &g_h)) << b.why;
    EXPECT_TRUE(all_zero(g_act)) << b.why;
  }
  // a good command in a failing cycle
  FswAcsCmdMsg c = inertial_cmd();
  c.set_ref = 1;
  c.sigma_R0N[2] = acsfix::R(0.3);
  c.set_gains = 1;
  c.K = acsfix::R(5.0);
  c.P = acsfix::R(5.0);
  sensors_at_rest(g_sens, t);
  g_sens.omega_BN_B[0] = static_cast<fsw_real>(0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  ASSERT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, &c, &g_act, &g_h));
  sensors_at_rest(g_sens, t);  // retry at the same time, no command
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  for (int i = 0; i < 3; i++) EXPECT_NEAR(K * g_cfg.inertial.sigma_R0N[i], g_act.Lr_B[i], kTol);
}

// The speed filter with no wheels in the control law's H (mrp_fb.num_rw =
// 0: its J_s copy is then not compared) is a valid configuration.
// Verifies: REQ-ACS-002
TEST(FswAcsSpeedFilter, AcceptedWithoutWheelsInTheControlLaw)
{
  acsfix::wheel_config(g_cfg);
  speed_filter_on(g_cfg, 3, 0);
  g_cfg.mrp_fb.num_rw = 0;
  g_cfg.speed_filter.J_s[1] = acsfix::R(5.0);  // differs from the geometry: not compared without wheels in H
  const char* field = nullptr;
  EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field)) << (field ? field : "");
}

/* ---- momentum dumps by thrusters ---- */

// Wheels hold the attitude, the thrusters dump (policy THRUSTERS).  The
// pulsers take their period from their previous call; the application steps
// them in the cycles without a request, so the first cycle of the second
// pulse (after a coast) gets one period's on-time like every full cycle of
// the first, not the coast's.  Found by scenarios/s1_year_dumps.yaml: 3.41 s
// commanded at a 0.5 s period after a 60 s coast.  Ten quiet cycles at
// |h_w| = 1.1, then h_w = 1.45 N m s along +x_B (speeds a sign(g_x) on the
// pyramid: 4 J_s a cos 40 cos 45 = 1.45), h_lower 1 -> |dH| = 0.45 along -x;
// L_dump 0.05 N m, t_pulse_max 4 s (0.2 N m s, 8 cycles a pulse): pulses of
// 8, 8 and 2 cycles with 10 s coasts.  A -x torque comes from thrusters 2
// and 6 of the fixture (0-based 1 and 5: +-y thrust at z = +-1.7907 m, a
// pure couple), so a full cycle gives each L_dump T / (2 * 1.7907 * 1 N).
// Verifies: REQ-ACS-011, REQ-ACS-015
TEST(FswAcsMomentum, EveryPulseCycleGetsOnePeriodsOnTimeAfterACoast)
{
  acsfix::wheel_config(g_cfg);
  FswAcsGeometry g;
  acsfix::wheel_geometry(g);
  g.num_thr = 8;
  for (int i = 0; i < 8; i++) {
    for (int k = 0; k < 3; k++) {
      g.r_thr_B[i][k] = acsfix::R(acsfix::kThrR[i][k]);
      g.gt_hat_B[i][k] = acsfix::R(acsfix::kThrG[i][k]);
    }
    g.F_max[i] = acsfix::R(acsfix::kFmax);
  }
  ASSERT_EQ(FSW_OK, fsw_acs_config_set_geometry(&g_cfg, &g));
  for (int k = 0; k < 3; k++) g_cfg.thr_map.control_axes_B[k][k] = acsfix::R(1.0);
  g_cfg.thr_map.thr_force_sign = 1;
  g_cfg.thr_map.mode = FSW_THR_MAP_NNLS;
  g_cfg.pulser = FSW_ACS_PULSE_REMAINDER;
  g_cfg.pulse_rem.common.t_min = acsfix::R(0.002);
  g_cfg.pulse_rem.common.init_off_pulse_on_time = acsfix::R(0.3);  // would show if spent in a dump
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  std::memset(g_cfg.inertial.sigma_R0N, 0, sizeof g_cfg.inertial.sigma_R0N);
  g_cfg.initial_policy = FSW_ACS_MOM_THRUSTERS;
  g_cfg.use_thr_mom = 1;
  g_cfg.thr_mom.h_upper = acsfix::R(1.2);
  g_cfg.thr_mom.h_lower = acsfix::R(1.0);
  g_cfg.thr_mom.L_dump = acsfix::R(0.05);
  g_cfg.thr_mom.t_pulse_max = acsfix::R(4.0);
  g_cfg.thr_mom.t_min_pulse = acsfix::R(0.5);
  g_cfg.thr_mom.t_coast = acsfix::R(10.0);
  g_cfg.thr_mom.dt_cycle = acsfix::R(acsfix::kPeriod);
  g_cfg.thr_mom.Isp = acsfix::R(220.0);
  const char* bad = nullptr;
  ASSERT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &bad)) << (bad ? bad : "");
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));

  const double per_a = 4.0 * acsfix::kJs * std::cos(40.0 * acsfix::kPi / 180.0) * std::cos(acsfix::kPi / 4.0);
  const double t_full = 0.05 * acsfix::kPeriod / (2.0 * 1.79070 * acsfix::kFmax);
  sensors_at_rest(g_sens, 0);
  int pulse = 0, prev_phase = FSW_THR_MOM_IDLE, full_cycles = 0;
  for (int c = 0; c < 200 && g_h.dumps == 0; c++) {
    const double a = (c < 10 ? 1.1 : 1.45) / per_a;
    for (int w = 0; w < 4; w++) {
      double ax[3];
      acsfix::pyramid_axis(w, ax);
      g_sens.Omega[w] = acsfix::R(ax[0] > 0 ? a : -a);
    }
    g_sens.t_ns = (c + 1) * kPeriodNs;
    ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h))) << c;
    if (g_h.dump_phase == FSW_THR_MOM_PULSE && prev_phase != FSW_THR_MOM_PULSE) pulse++;
    for (int j = 0; j < 8; j++) {
      const bool couple = (j == 1 || j == 5);
      if (g_h.dump_phase == FSW_THR_MOM_PULSE && pulse < 3 && couple) {
        EXPECT_NEAR(g_act.t_on[j], t_full, kt::tol(1e-9, 1e-5)) << "cycle " << c << " pulse " << pulse;
      } else if (g_h.dump_phase != FSW_THR_MOM_PULSE || !couple) {
        EXPECT_EQ(0.0, g_act.t_on[j]) << "cycle " << c << " thruster " << j;  // nothing else fires
      }
    }
    if (g_h.dump_phase == FSW_THR_MOM_PULSE && pulse < 3) full_cycles++;
    prev_phase = g_h.dump_phase;
  }
  EXPECT_EQ(1u, g_h.dumps);
  EXPECT_EQ(3, pulse);
  EXPECT_EQ(16, full_cycles);
}

// ---- issue 39 finding 10: limits that work together, the rejected cycle's health

// The saturation limit may sit below the filter's motor limit (a derated
// wheel): accepted, and with large commands (attitude error 0.3, torques
// clipped at rw_sat's 0.1 N m) and the torque test on, every cycle is good:
// the applied torque (<= 0.1) is within the filter's 2 u_max = 0.4.  The
// live wheels follow their torque so the torque test has nothing to find.
// Verifies: REQ-ACS-002, REQ-ACS-014
TEST(FswAcsSpeedFilter, Issue39SaturationBelowTheFilterLimitRunsEveryCycle)
{
  acsfix::wheel_config(g_cfg);
  g_cfg.initial_mode = FSW_ACS_MODE_INERTIAL;
  speed_filter_on(g_cfg, 3, 2);
  for (int i = 0; i < 4; i++) g_cfg.rw_sat.u_max[i] = acsfix::R(0.1);
  const char* field = "x";
  ASSERT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field));
  EXPECT_EQ(nullptr, field);
  // equal limits are accepted too (what fsw_acs_config_set_geometry writes)
  for (int i = 0; i < 4; i++) g_cfg.rw_sat.u_max[i] = g_cfg.speed_filter.u_max[i];
  ASSERT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &field));
  for (int i = 0; i < 4; i++) g_cfg.rw_sat.u_max[i] = acsfix::R(0.1);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  double Omega[4] = {0.0, 5.0, 10.0, 15.0};
  const double dt = 1e-9 * static_cast<double>(kPeriodNs);
  int saturated = 0;
  for (int k = 0; k < 12; k++) {
    sensors_at_rest(g_sens, k * kPeriodNs);
    g_sens.sigma_BN[0] = acsfix::R(0.3);
    g_sens.sigma_BN[1] = acsfix::R(-0.2);
    for (int i = 0; i < 4; i++) g_sens.Omega[i] = acsfix::R(Omega[i]);
    const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h);
    ASSERT_FALSE(fsw_status_is_error(s)) << k << " " << fsw_status_name(s);
    EXPECT_EQ(0u, g_h.rw_failed) << k;
    double umax = 0;
    for (int i = 0; i < 4; i++) umax = std::max(umax, std::fabs(double(g_act.u_s[i])));
    EXPECT_LE(umax, 0.1 * (1 + 1e-6)) << k;
    if (umax > 0.1 * (1 - 1e-6)) saturated++;
    for (int i = 0; i < 4; i++) Omega[i] += g_act.u_s[i] / g_cfg.speed_filter.J_s[i] * dt;
  }
  EXPECT_EQ(12, saturated);  // the commands were at the limit throughout
}

// A rejected cycle's health message is the safe one (docs/fsw/fsw_acs.md:
// no Sun heading "on a rejected cycle (the whole message is the safe
// one)"), also when the cycle fails after the CSS stage ran: in SUN_SAFE
// with the Sun on (1,1,1)/sqrt3, a huge finite rate overflows the control
// law.  Before issue 39 the message still carried the heading, the lit
// count, the sun-safe error and the errors of the rejected cycle.  The
// stage statuses stay (they say which stage failed); the mode, counters and
// filter verdicts are those in force.
// Verifies: REQ-ACS-005, REQ-ACS-006, REQ-ACS-012
TEST(FswAcsHealth, Issue39ARejectedCycleAfterTheStagesRanCarriesTheSafeHealthMessage)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_ACS_MODE_SUN_SAFE, g_cfg.initial_mode);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 1000);
  for (int i = 0; i < 4; i++) g_sens.Omega[i] = acsfix::R(10.0 * (i + 1));
  ASSERT_FALSE(fsw_status_is_error(fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h)));
  ASSERT_EQ(1, g_h.sun_valid);  // a good cycle publishes the heading
  sensors_at_rest(g_sens, 2000);
  for (int i = 0; i < 4; i++) g_sens.Omega[i] = acsfix::R(10.0 * (i + 1));
  g_sens.omega_BN_B[2] = static_cast<fsw_real>(0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  ASSERT_EQ(FSW_E_BAD_INPUT, fsw_acs_cycle(&g_st, &g_cfg, &g_sens, nullptr, &g_act, &g_h));
  EXPECT_EQ(FSW_OK, g_h.stage_status[FSW_ACS_STAGE_CSS]);  // the CSS stage ran ...
  int failed_stages = 0;
  for (int i = 0; i < FSW_ACS_NUM_STAGES; i++) failed_stages += fsw_status_is_error(g_h.stage_status[i]) ? 1 : 0;
  EXPECT_GE(failed_stages, 1);  // ... and a stage is blamed
  EXPECT_EQ(FSW_E_BAD_INPUT, g_h.status);
  EXPECT_EQ(1, g_h.safe_output);
  EXPECT_EQ(0, g_h.sun_valid);
  EXPECT_EQ(0, g_h.num_lit);
  EXPECT_EQ(0, g_h.sun_angle_err);
  EXPECT_EQ(0, g_h.att_err_angle);
  EXPECT_EQ(0, g_h.rate_est);
  for (int k = 0; k < 3; k++) {
    EXPECT_EQ(0, g_h.sun_hat_B[k]) << k;
    EXPECT_EQ(0, g_h.sigma_BR[k]) << k;
    EXPECT_EQ(0, g_h.omega_BR_B[k]) << k;
    EXPECT_EQ(0, g_h.h_w_B[k]) << k;
    EXPECT_EQ(0, g_h.tau_mtq_B[k]) << k;
  }
  EXPECT_EQ(FSW_ACS_MODE_SUN_SAFE, g_h.mode);
  EXPECT_EQ(1u, g_h.cycles);
  EXPECT_EQ(1u, g_h.health.bad_input);
  EXPECT_TRUE(all_zero(g_act));
}

// ---- issue 45: every byte of the actuator message is written once --------

namespace {
// The fields of two actuator messages equal byte for byte (the padding is
// not compared: it carries no value).
bool same_fields(const FswAcsActuatorMsg& a, const FswAcsActuatorMsg& b)
{
  return std::memcmp(a.Lr_B, b.Lr_B, sizeof a.Lr_B) == 0 && std::memcmp(a.u_s, b.u_s, sizeof a.u_s) == 0 &&
         std::memcmp(a.V, b.V, sizeof a.V) == 0 && std::memcmp(a.F, b.F, sizeof a.F) == 0 &&
         std::memcmp(a.t_on, b.t_on, sizeof a.t_on) == 0 && std::memcmp(a.m_cmd, b.m_cmd, sizeof a.m_cmd) == 0 &&
         a.wheels_active == b.wheels_active && a.thrusters_active == b.thrusters_active &&
         a.mtq_active == b.mtq_active;
}

// The documented safe output, every field (the rods included) +0.0 / 0.
bool is_safe_output(const FswAcsActuatorMsg& a)
{
  FswAcsActuatorMsg z;
  std::memset(&z, 0, sizeof z);
  return same_fields(a, z);
}

// One cycle of g_st (into a message that held 0xA5 in every byte) and of
// g_st2, the same state, into a zeroed message: what each cycle writes
// must not depend on what the caller's buffer held.
FswStatus cycle_both(const FswAcsCmdMsg* cmd)
{
  std::memset(&g_act, 0xA5, sizeof g_act);
  std::memset(&g_act2, 0, sizeof g_act2);
  const FswStatus s = fsw_acs_cycle(&g_st, &g_cfg, &g_sens, cmd, &g_act, &g_h);
  const FswStatus s2 = fsw_acs_cycle(&g_st2, &g_cfg, &g_sens, cmd, &g_act2, &g_h2);
  EXPECT_EQ(s, s2);
  EXPECT_TRUE(same_fields(g_act, g_act2));
  return s;
}
}  // namespace

// A pointing cycle on wheels writes the torque request and the configured
// wheel torques over the stages and every other field once, before them;
// any other cycle starts from the whole safe output.  Each path, from a
// buffer of 0xA5 bytes (a finite non-zero double) and from a zeroed one:
// the same fields, and the safe output wherever the contract says so.
// Verifies: REQ-ACS-004, REQ-ACS-005
TEST(FswAcsCycle, Issue45EveryFieldIsWrittenWhateverTheBufferHeld)
{
  acsfix::wheel_config(g_cfg);
  ASSERT_EQ(FSW_ACS_MODE_SUN_SAFE, g_cfg.initial_mode);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st2, &g_cfg, nullptr));
  const int n = g_cfg.rw_map.num_rw;

  // a good sun-safe cycle on wheels: nothing beyond the wheels is left over
  sensors_at_rest(g_sens, 1000);
  for (int i = 0; i < n; i++) g_sens.Omega[i] = acsfix::R(10.0 * (i + 1));
  g_sens.omega_BN_B[0] = acsfix::R(0.01);
  ASSERT_FALSE(fsw_status_is_error(cycle_both(nullptr)));
  EXPECT_EQ(1, g_act.wheels_active);
  EXPECT_EQ(0, g_act.thrusters_active);
  EXPECT_EQ(0, g_act.mtq_active);
  double u2 = 0;
  for (int i = 0; i < n; i++) u2 += static_cast<double>(g_act.u_s[i]) * g_act.u_s[i];
  EXPECT_GT(u2, 0.0);  // torques were commanded
  for (int i = n; i < FSW_MAX_RW; i++) EXPECT_EQ(0, g_act.u_s[i]) << i;
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(0, g_act.V[i]) << i;  // use_volt = 0
  for (int i = 0; i < FSW_MAX_THR; i++) {
    EXPECT_EQ(0, g_act.F[i]) << i;
    EXPECT_EQ(0, g_act.t_on[i]) << i;
  }
  for (int i = 0; i < FSW_MAX_MTQ; i++) EXPECT_EQ(0, g_act.m_cmd[i]) << i;

  // refused before any stage ran (each check that returns early)
  sensors_at_rest(g_sens, 2000);
  g_sens.omega_BN_B[1] = kNaN;
  EXPECT_EQ(FSW_E_BAD_INPUT, cycle_both(nullptr));
  EXPECT_TRUE(is_safe_output(g_act));
  sensors_at_rest(g_sens, 1000);  // a repeated time stamp
  EXPECT_EQ(FSW_E_TIME, cycle_both(nullptr));
  EXPECT_TRUE(is_safe_output(g_act));
  FswAcsCmdMsg bad{};
  bad.mode = 9;
  sensors_at_rest(g_sens, 2000);
  EXPECT_EQ(FSW_E_BAD_INPUT, cycle_both(&bad));
  EXPECT_TRUE(is_safe_output(g_act));

  // an error of a stage after the stages ran (a rate so large that the
  // control torque overflows): the whole safe output again
  sensors_at_rest(g_sens, 2000);
  g_sens.omega_BN_B[2] = static_cast<fsw_real>(0.5 * static_cast<double>(std::numeric_limits<fsw_real>::max()));
  EXPECT_EQ(FSW_E_BAD_INPUT, cycle_both(nullptr));
  EXPECT_TRUE(is_safe_output(g_act));

  // a state that is not ready
  g_st.ready = 0;
  g_st2.ready = 0;
  sensors_at_rest(g_sens, 3000);
  EXPECT_EQ(FSW_E_NOT_INIT, cycle_both(nullptr));
  EXPECT_TRUE(is_safe_output(g_act));

  // thruster actuation: the safe output up front, the thrusters' fields over it
  acsfix::thruster_config(g_cfg);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st2, &g_cfg, nullptr));
  sensors_at_rest(g_sens, 0);
  g_sens.sigma_BN[0] = acsfix::R(0.01);
  ASSERT_FALSE(fsw_status_is_error(cycle_both(nullptr)));
  EXPECT_EQ(1, g_act.thrusters_active);
  EXPECT_EQ(0, g_act.wheels_active);
  for (int i = 0; i < FSW_MAX_RW; i++) EXPECT_EQ(0, g_act.u_s[i]) << i;
  for (int i = g_cfg.thr_map.num_thr; i < FSW_MAX_THR; i++) EXPECT_EQ(0, g_act.F[i]) << i;
}

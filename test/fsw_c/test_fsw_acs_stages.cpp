// fsw_acs built with stages left out (fsw_config.h, FSW_CFG_*): the typical
// selection of docs/flight-footprint.md, wheels with null motion, thrusters
// with remainder pulsing and thruster momentum dumps; no magnetorquers,
// orbit guidance, wheel bias, voltages, speed filter, torque filter or
// Schmitt pulser.  This executable compiles fsw_acs.c itself with that
// selection (test/fsw_c/CMakeLists.txt); its object comes before the
// library on the link line, so the modules are the library's and fsw_acs is
// this build's.
//  - a configuration asking for a stage left out is refused with
//    FSW_E_UNSUPPORTED and the flag's name; init leaves the state not ready
//    and a cycle then gives the safe output;
//  - the stages kept compute what the full build computes: the thruster
//    sequence of the golden record (recorded by the full build on the host)
//    replays bit for bit on the host.
// Built twice (test/fsw_c/CMakeLists.txt): test_fsw_acs_stages keeps
// thr_map's NNLS mode, which the golden record flies; test_fsw_acs_stages_nnls
// also leaves it out (FSW_CFG_THR_NNLS=0, the selection of the footprint
// figures) and compiles thr_map.c too: there thr_map and fsw_acs refuse the
// mode, the golden configuration is refused, and the minimum-norm mode maps
// a torque to the forces computed by hand.
#include <gtest/gtest.h>

#include <cstring>

#include "acs_fixture.hpp"
#include "data/fsw_acs_golden.h"
#include "fsw/thr_map.h"
#include "kestrel_test_support.h"

#if FSW_CFG_MTQ || FSW_CFG_MTQ_DESAT || FSW_CFG_ORBIT || FSW_CFG_RW_BIAS || FSW_CFG_RW_VOLT || \
    FSW_CFG_SPEED_FILTER || FSW_CFG_LPF || FSW_CFG_PULSE_SCHMITT || !FSW_CFG_RW_NULL || !FSW_CFG_THR_MOM
#error "test_fsw_acs_stages is built with the typical selection (test/fsw_c/CMakeLists.txt)"
#endif

namespace {

using acsfix::R;

const FswAcsGoldenCycle kGolden[] = {
#include "data/fsw_acs_golden.inc"
};

FswAcsConfig g_cfg;
FswAcsState g_st;

// Everything the selection flies: wheels with null motion and the THRUSTERS
// policy, thrusters with remainder pulsing; rods and orbit guidance off.
void typical_config(FswAcsConfig& c)
{
  acsfix::full_config(c);
  c.has_mtq = 0;
  c.has_orbit = 0;
  c.detumble_exit_mode = -1;
  c.use_null = 1;
  c.Omega_des[0] = R(20.0);
  c.use_thr_mom = 1;
  c.initial_policy = FSW_ACS_MOM_THRUSTERS;
#if !FSW_CFG_THR_NNLS
  c.thr_map.mode = FSW_THR_MAP_MIN_NORM;
#endif
}

struct LeftOut {
  const char* flag;
  void (*ask)(FswAcsConfig&);
};

const LeftOut kLeftOut[] = {
    {"has_mtq", [](FswAcsConfig& c) { c.has_mtq = 1; }},
    {"use_mtq_desat", [](FswAcsConfig& c) { c.use_mtq_desat = 1; }},
    {"has_orbit", [](FswAcsConfig& c) { c.has_orbit = 1; }},
    {"use_bias", [](FswAcsConfig& c) { c.use_bias = 1; }},
    {"use_volt", [](FswAcsConfig& c) { c.use_volt = 1; }},
    {"use_speed_filter", [](FswAcsConfig& c) { c.use_speed_filter = 1; }},
    {"use_lpf", [](FswAcsConfig& c) { c.use_lpf = 1; }},
    {"pulser", [](FswAcsConfig& c) { c.pulser = FSW_ACS_PULSE_SCHMITT; }},
#if !FSW_CFG_THR_NNLS
    {"thr_map.mode", [](FswAcsConfig& c) { c.thr_map.mode = FSW_THR_MAP_NNLS; }},
#endif
};

// The safe output: every command 0, nothing active.
bool is_safe_output(const FswAcsActuatorMsg& a)
{
  bool zero = a.wheels_active == 0u && a.thrusters_active == 0u && a.mtq_active == 0u;
  for (int k = 0; k < 3; k++) zero = zero && a.Lr_B[k] == 0;
  for (int i = 0; i < FSW_MAX_RW; i++) zero = zero && a.u_s[i] == 0 && a.V[i] == 0;
  for (int i = 0; i < FSW_MAX_THR; i++) zero = zero && a.F[i] == 0 && a.t_on[i] == 0;
  for (int i = 0; i < FSW_MAX_MTQ; i++) zero = zero && a.m_cmd[i] == 0;
  return zero;
}

// Verifies: REQ-ACS-018, REQ-ACS-001
TEST(FswAcsStages, TheTypicalSelectionAcceptsWhatItFlies)
{
  typical_config(g_cfg);
  const char* bad = "unset";
  EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, &bad));
  EXPECT_EQ(nullptr, bad);
  ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
  EXPECT_EQ(1, g_st.ready);
}

// Verifies: REQ-ACS-018, REQ-ACS-005
TEST(FswAcsStages, AStageLeftOutIsRefusedAndTheCycleGivesTheSafeOutput)
{
  for (const LeftOut& l : kLeftOut) {
    typical_config(g_cfg);
    l.ask(g_cfg);
    const char* bad = nullptr;
    EXPECT_EQ(FSW_E_UNSUPPORTED, fsw_acs_check(&g_cfg, &bad)) << l.flag;
    ASSERT_NE(nullptr, bad) << l.flag;
    EXPECT_STREQ(l.flag, bad);
    bad = nullptr;
    EXPECT_EQ(FSW_E_UNSUPPORTED, fsw_acs_init(&g_st, &g_cfg, &bad)) << l.flag;
    EXPECT_STREQ(l.flag, bad);
    EXPECT_EQ(0, g_st.ready) << l.flag;

    FswAcsSensorMsg m;
    std::memset(&m, 0, sizeof m);
    m.t_ns = 100000000u;
    m.att_valid = 1u;
    FswAcsActuatorMsg a;
    FswAcsHealthMsg h;
    std::memset(&a, 0x5a, sizeof a);
    EXPECT_EQ(FSW_E_NOT_INIT, fsw_acs_cycle(&g_st, &g_cfg, &m, nullptr, &a, &h)) << l.flag;
    EXPECT_TRUE(is_safe_output(a)) << l.flag;
    EXPECT_EQ(1u, h.safe_output) << l.flag;
    EXPECT_EQ(FSW_E_NOT_INIT, h.status) << l.flag;
  }
  // a pulser value outside the enumeration stays a configuration error
  typical_config(g_cfg);
  g_cfg.pulser = 7;
  const char* bad = nullptr;
  EXPECT_EQ(FSW_E_CONFIG, fsw_acs_check(&g_cfg, &bad));
  EXPECT_STREQ("pulser", bad);
  // without wheels the wheel-chain flags are not read (as in the full build)
  acsfix::thruster_config(g_cfg);
#if !FSW_CFG_THR_NNLS
  g_cfg.thr_map.mode = FSW_THR_MAP_MIN_NORM;
#endif
  g_cfg.use_volt = 1;
  g_cfg.use_speed_filter = 1;
  EXPECT_EQ(FSW_OK, fsw_acs_check(&g_cfg, nullptr));
}

// Verifies: REQ-ACS-018, REQ-GEN-009
TEST(FswAcsStages, TheStagesKeptGiveTheFullBuildsNumbers)
{
#if !FSW_CFG_THR_NNLS
  // the golden thruster scenario flies the NNLS mode this build left out
  acsfix::golden_config(1, g_cfg);
  const char* bad = nullptr;
  EXPECT_EQ(FSW_E_UNSUPPORTED, fsw_acs_init(&g_st, &g_cfg, &bad));
  EXPECT_STREQ("thr_map.mode", bad);
  EXPECT_EQ(0, g_st.ready);
  return;
#endif
  if (kt::kFloat) GTEST_SKIP() << "the golden sequence is recorded in double precision";
  size_t rows = 0, fired = 0;
  bool first = true;
  for (const FswAcsGoldenCycle& g : kGolden) {
    if (g.scenario != 1) continue;  // thrusters, remainder pulsing (0: torque filter, voltages; 2: Schmitt)
    if (first) {
      acsfix::golden_config(g.scenario, g_cfg);
      ASSERT_EQ(FSW_OK, fsw_acs_init(&g_st, &g_cfg, nullptr));
      first = false;
    }
    FswAcsSensorMsg m;
    FswAcsCmdMsg cmd;
    acsfix::golden_inputs(g, g_cfg, m, cmd);
    FswAcsActuatorMsg a;
    FswAcsHealthMsg h;
    EXPECT_EQ(g.status, static_cast<int>(fsw_acs_cycle(&g_st, &g_cfg, &m, &cmd, &a, &h))) << g.cycle;
    for (int i = 0; i < 3; i++) {
#if KESTREL_TEST_HOST
      EXPECT_EQ(g.Lr[i], a.Lr_B[i]) << "cycle " << g.cycle;
#else  // a target's libm may differ in the last bit (test_fsw_acs_golden's bound)
      EXPECT_NEAR(g.Lr[i], a.Lr_B[i], 1e-12 * (std::fabs(g.Lr[i]) > 1.0 ? std::fabs(g.Lr[i]) : 1.0));
#endif
    }
    for (int i = 0; i < 8; i++) {
#if KESTREL_TEST_HOST
      EXPECT_EQ(g.t_on[i], a.t_on[i]) << "cycle " << g.cycle;
#else
      EXPECT_NEAR(g.t_on[i], a.t_on[i], 1e-12 * (std::fabs(g.t_on[i]) > 1.0 ? std::fabs(g.t_on[i]) : 1.0));
#endif
      if (g.t_on[i] != 0) fired++;
    }
    rows++;
  }
  EXPECT_EQ(static_cast<size_t>(acsfix::kGoldenCycles[1]), rows);
  EXPECT_GT(fired, 10u);  // the sequence fires thrusters
}

#if !FSW_CFG_THR_NNLS
// Two couples about z (thrusters 0 and 1 push +z, 2 and 3 -z, arm 1 m):
// [C][D] = [1 1 -1 -1] for the one control axis z.  The minimum-norm
// solve of [C][D] F = 0.5 is F = 0.5/4 (1, 1, -1, -1), the shift of the
// on-pulsing mapping adds 0.125: F = (0.25, 0.25, 0, 0), all exact.
void couple_config(FswThrMapConfig& c)
{
  std::memset(&c, 0, sizeof c);
  c.control_axes_B[0][2] = R(1.0);
  c.num_thr = 4;
  const double x[4] = {1, -1, 1, -1}, y[4] = {1, -1, -1, 1};
  for (int i = 0; i < 4; i++) {
    c.r_thr_B[i][0] = R(x[i]);
    c.gt_hat_B[i][1] = R(y[i]);
    c.F_max[i] = R(1.0);
  }
  c.thr_force_sign = 1;
  c.ang_err_thresh = R(4.0);  // above pi: no scaling
  c.mode = FSW_THR_MAP_MIN_NORM;
}

// Verifies: REQ-ACS-018, REQ-ACS-005
TEST(FswAcsStages, ThrMapWithoutNnlsRefusesTheModeAndMapsMinimumNorm)
{
  static FswThrMapConfig c;
  static FswThrMapState st;
  couple_config(c);
  c.mode = FSW_THR_MAP_NNLS;
  EXPECT_EQ(FSW_E_UNSUPPORTED, fsw_thr_map_check(&c));
  std::memset(&st, 0x5a, sizeof st);
  EXPECT_EQ(FSW_E_UNSUPPORTED, fsw_thr_map_init(&st, &c));
  EXPECT_EQ(0, st.ready);
  c.mode = 2;  // outside the enumeration: still a configuration error
  EXPECT_EQ(FSW_E_CONFIG, fsw_thr_map_check(&c));

  c.mode = FSW_THR_MAP_MIN_NORM;
  ASSERT_EQ(FSW_OK, fsw_thr_map_init(&st, &c));
  FswThrMapIn in;
  std::memset(&in, 0, sizeof in);
  in.Lr_B[2] = R(0.5);
  FswThrMapOut out;
  ASSERT_EQ(FSW_OK, fsw_thr_map_update(&st, &c, &in, &out));
  const double want[4] = {0.25, 0.25, 0.0, 0.0};
  for (int i = 0; i < 4; i++) EXPECT_NEAR(want[i], out.F[i], 1e-6) << i;

  // a configuration changed to the mode after init: refused, safe output F = 0
  c.mode = FSW_THR_MAP_NNLS;
  std::memset(&out, 0x5a, sizeof out);
  EXPECT_EQ(FSW_E_UNSUPPORTED, fsw_thr_map_update(&st, &c, &in, &out));
  for (int i = 0; i < FSW_MAX_THR; i++) EXPECT_EQ(0, out.F[i]) << i;
}
#endif

}  // namespace

// fsw_acs_cycle: the reference configurations of the application tests
// (acs_fixture.hpp: wheels with null motion, filter and voltages; wheels with
// the power-optimal mapping; thrusters with remainder or Schmitt pulsing)
// with decoded gains, filter, mapping, pulser and geometry changes; a
// sequence of sensor messages (NaN/inf/huge rates, attitudes, CSS readings,
// wheel speeds, masks, time going backwards) and mode/actuation requests.
// Checks: the returned status is known and equals hlth->status; OK and
// warnings: finite commands, wheel torques within u_max and voltages within
// V_max, on-times within [0, 1.1 dt] (or the first-call value), cycles
// counted; errors: the safe output (all 0, nothing active) and the
// application state byte-identical to before the cycle apart from health
// counters and scratch (issue 13 finding 1).
// Issue 14 (gated on bit 2 of the first byte, so inputs from before decode
// as they did): the speed filter in the chain (its counts, margins and
// tolerances), thruster availability flags and the reference / gain set
// commands.  Checks: a flagged thruster gets no on-time; the filter's bits
// stay within the wheels and latched implies failed.
// Issue 38 (bit 3 of the first byte; bits 0-1 then pick the wheel mapping
// and the pulser): the full configuration of acs_fixture.hpp (wheels,
// thrusters, three rods, orbit guidance) with the new modules decoded (rods,
// bdot, DETUMBLE's exit mode, orbit guidance, thruster dumps, rod
// desaturation, wheel bias, the momentum policy, every mode as the initial
// one); the magnetometer, orbit and set_policy fields of the messages.
// Checks: no rod command unless mtq_active (and never without rods), rod
// commands within duty_max m_max and 0 beyond num_mtq, finite telemetry of
// the new paths, mode and policy in force always configured ones.
// Issue 39 (bit 4 of the first byte; four bytes right after it): the speed
// filter's own u_max scaled wheel by wheel against the geometry's (rw_sat
// keeps it), so limits that cannot work together are reached (fsw_acs_check
// must refuse a filter limit below the saturation limit).  Checks: the speed
// filter never refuses what the cycle hands it (its bad_input counter stays:
// an error there had no stage to blame); an error cycle's health message is
// the safe one (no Sun heading, no estimates).
#include "acs_fixture.hpp"
#include "fsw/fsw_acs.h"
#include "fuzz_input.h"

static void mask(FswAcsState &s)
{
  fuzz_mask_health(s);
  std::memset(&s.work, 0, sizeof s.work);
  std::memset(&s.rw_map.work, 0, sizeof s.rw_map.work);
  std::memset(&s.thr_map.work, 0, sizeof s.thr_map.work);
  fuzz_mask_health(s.css);
  fuzz_mask_health(s.sunsafe);
  fuzz_mask_health(s.inertial);
  fuzz_mask_health(s.track);
  fuzz_mask_health(s.mrp_fb);
  fuzz_mask_health(s.lpf);
  fuzz_mask_health(s.rw_map);
  fuzz_mask_health(s.rw_null);
  fuzz_mask_health(s.rw_sat);
  fuzz_mask_health(s.rw_volt);
  fuzz_mask_health(s.speed_filter);
  fuzz_mask_health(s.thr_map);
  fuzz_mask_common_health(s.pulse_rem);
  fuzz_mask_common_health(s.pulse_schmitt);
  fuzz_mask_health(s.bdot);
  fuzz_mask_health(s.mtq_map);
  fuzz_mask_health(s.mtq_desat);
  fuzz_mask_health(s.thr_mom);
  fuzz_mask_health(s.orbit);
  fuzz_mask_health(s.rw_bias);
  // rw_bias's projector and null basis are a cache of the availability mask
  // it was last called with (each call recomputes them when its mask
  // differs), not memory of the past: an error cycle may leave them for its
  // own mask, and the next call gives what it would have given.
  std::memset(&s.rw_bias.proj, 0, sizeof s.rw_bias.proj);
  std::memset(&s.rw_bias.basis, 0, sizeof s.rw_bias.basis);
  s.rw_bias.nullity = 0;
  // its scratch is the update's work area (FswRwBiasScratch), no state
  std::memset(&s.rw_bias.scratch, 0, sizeof s.rw_bias.scratch);
}

static bool act_safe(const FswAcsActuatorMsg &a, int)
{
  return fuzz_nonzero_from(a.Lr_B, 0, 3) < 0 && fuzz_nonzero_from(a.u_s, 0, FSW_MAX_RW) < 0 &&
         fuzz_nonzero_from(a.V, 0, FSW_MAX_RW) < 0 && fuzz_nonzero_from(a.F, 0, FSW_MAX_THR) < 0 &&
         fuzz_nonzero_from(a.t_on, 0, FSW_MAX_THR) < 0 && fuzz_nonzero_from(a.m_cmd, 0, FSW_MAX_MTQ) < 0 &&
         a.wheels_active == 0 && a.thrusters_active == 0 && a.mtq_active == 0;
}

// Issue 38: the full configuration with the new modules decoded.
static void decode_issue38(FuzzIn &in, FswAcsConfig &c, int variant)
{
  acsfix::full_config(c);
  c.rw_map.mode = variant & 1;
  c.pulser = (variant & 2) ? FSW_ACS_PULSE_SCHMITT : FSW_ACS_PULSE_REMAINDER;
  FswAcsGeometry g;
  acsfix::full_geometry(g);
  g.num_mtq = in.count(3, FSW_MAX_MTQ);
  for (int i = 0; i < fuzz_clamp_count(g.num_mtq, FSW_MAX_MTQ); i++) {
    double a[3] = {1, 0, 0};
    if (i < 3) acsfix::rod_axis(i, a);
    in.unit3(g.mtq_axis_B[i], a, i > 0 ? g.mtq_axis_B[i - 1] : nullptr);
    g.mtq_m_max[i] = static_cast<fsw_real>(in.real(acsfix::kRodMmax));
  }
  (void)fsw_acs_config_set_geometry(&c, &g);
  c.initial_mode = in.flag(variant);  // every mode as the initial one
  c.detumble_exit_mode = in.flag(FSW_ACS_MODE_SUN_SAFE);
  c.has_orbit = in.flag(1);
  c.use_null = in.flag(1);
  c.use_bias = in.flag(1);
  c.use_thr_mom = in.flag(1);
  c.use_mtq_desat = in.flag(1);
  c.initial_policy = in.flag(variant == 3 ? FSW_ACS_MOM_MAGNETORQUERS : FSW_ACS_MOM_THRUSTERS);
  c.use_lpf = in.flag(0);
  c.use_volt = in.flag(0);
  c.mtq_map.duty_max = static_cast<fsw_real>(in.real(c.mtq_map.duty_max));
  c.bdot.variant = in.flag(FSW_BDOT_GYRO);
  c.bdot.k_bdot = static_cast<fsw_real>(in.real(c.bdot.k_bdot));
  c.bdot.normalize = in.flag(0);
  c.bdot.tau_f = static_cast<fsw_real>(in.real(1.0));
  c.bdot.max_missed = static_cast<int>(in.u32(3));
  c.bdot.omega_done = static_cast<fsw_real>(in.real(c.bdot.omega_done));
  c.bdot.omega_reenter = static_cast<fsw_real>(in.real(c.bdot.omega_reenter));
  c.bdot.t_persist = static_cast<fsw_real>(in.real(c.bdot.t_persist));
  // the fuzzed wheel speeds (20, -16, 12, -8 rad/s) make |h_w| ~ 1 N m s
  c.thr_mom.h_upper = static_cast<fsw_real>(in.real(0.8));
  c.thr_mom.h_lower = static_cast<fsw_real>(in.real(0.2));
  c.thr_mom.L_dump = static_cast<fsw_real>(in.real(c.thr_mom.L_dump));
  c.thr_mom.t_pulse_max = static_cast<fsw_real>(in.real(c.thr_mom.t_pulse_max));
  c.thr_mom.t_min_pulse = static_cast<fsw_real>(in.real(c.thr_mom.t_min_pulse));
  c.thr_mom.t_coast = static_cast<fsw_real>(in.real(c.thr_mom.t_coast));
  c.thr_mom.Isp = static_cast<fsw_real>(in.real(c.thr_mom.Isp));
  c.mtq_desat.k_desat = static_cast<fsw_real>(in.real(c.mtq_desat.k_desat));
  c.mtq_desat.tau_max = static_cast<fsw_real>(in.real(c.mtq_desat.tau_max));
  c.mtq_desat.h_deadband = static_cast<fsw_real>(in.real(c.mtq_desat.h_deadband));
  c.mtq_desat.h_target_B[0] = static_cast<fsw_real>(in.real(0.0));
  c.rw_bias.Omega_bias[0] = static_cast<fsw_real>(in.real(c.rw_bias.Omega_bias[0]));
  c.rw_bias.Omega_keepout = static_cast<fsw_real>(in.real(c.rw_bias.Omega_keepout));
  c.rw_bias.Omega_hyst = static_cast<fsw_real>(in.real(c.rw_bias.Omega_hyst));
  c.orbit.variant = in.flag(FSW_GUID_ORBIT_NADIR);
  {
    const double z[3] = {0, 0, 0};
    in.reals(c.orbit.sigma_BdR, 3, z);
  }
  c.orbit.mu = static_cast<fsw_real>(in.real(acsfix::kMu));
  fuzz_trace_int("num_mtq", g.num_mtq);
  fuzz_trace_int("initial_mode", c.initial_mode);
  fuzz_trace_int("detumble_exit_mode", c.detumble_exit_mode);
  fuzz_trace_int("has_orbit", c.has_orbit);
  fuzz_trace_int("use_null", c.use_null);
  fuzz_trace_int("use_bias", c.use_bias);
  fuzz_trace_int("use_thr_mom", c.use_thr_mom);
  fuzz_trace_int("use_mtq_desat", c.use_mtq_desat);
  fuzz_trace_int("initial_policy", c.initial_policy);
  fuzz_trace("bdot k_bdot", &c.bdot.k_bdot, 1);
  fuzz_trace("thr_mom h_upper h_lower L_dump", &c.thr_mom.h_upper, 3);
}

// Decode the configuration: a reference config, then single fields.
// Issue 39: the speed filter's limit against the saturation limit.
static void scale_filter_limits(FswAcsConfig &c, const double f[4])
{
  for (int i = 0; i < 4 && i < c.speed_filter.num_rw && i < FSW_MAX_RW; i++)
    c.speed_filter.u_max[i] = static_cast<fsw_real>(c.speed_filter.u_max[i] * f[i]);
  fuzz_trace("speed_filter.u_max", c.speed_filter.u_max, c.speed_filter.num_rw < 4 ? c.speed_filter.num_rw : 4);
}

static void decode_config(FuzzIn &in, FswAcsConfig &c, bool &issue14, bool &issue38)
{
  const int v8 = in.u8();
  const int variant = v8 % 4;
  issue14 = (v8 & 4) != 0;
  issue38 = (v8 & 8) != 0;
  double sf_scale[4] = {1, 1, 1, 1};
  if (v8 & 16)
    for (double &f : sf_scale) f = in.real(1.0);
  if (issue38) {
    decode_issue38(in, c, variant);
    if (issue14) {
      c.use_speed_filter = in.flag(1);
      c.speed_filter.k_reject = in.u32(3);
      c.speed_filter.n_recover = in.u32(3);
    }
    scale_filter_limits(c, sf_scale);
    return;
  }
  if (variant <= 1) {
    acsfix::golden_config(0, c);  // wheels: null motion, filter, voltages
    c.rw_map.mode = variant;      // 1: power-optimal mapping
  } else {
    acsfix::thruster_config(c, variant == 2 ? FSW_ACS_PULSE_REMAINDER : FSW_ACS_PULSE_SCHMITT);
  }
  FswAcsGeometry g;
  if (variant <= 1) acsfix::wheel_geometry(g);
  else acsfix::thruster_geometry(g);
  for (int i = 0; i < g.num_rw; i++) {
    const double g0[3] = {g.gs_hat_B[i][0], g.gs_hat_B[i][1], g.gs_hat_B[i][2]};
    in.unit3(g.gs_hat_B[i], g0, i > 0 ? g.gs_hat_B[i - 1] : nullptr);
    g.J_s[i] = static_cast<fsw_real>(in.real(g.J_s[i]));
    g.u_max[i] = static_cast<fsw_real>(in.real(g.u_max[i]));
  }
  for (int i = 0; i < g.num_thr; i++) g.F_max[i] = static_cast<fsw_real>(in.real(g.F_max[i]));
  (void)fsw_acs_config_set_geometry(&c, &g);
  c.initial_mode = in.flag(c.initial_mode);
  c.initial_actuation = in.flag(c.initial_actuation);
  c.css.lit_threshold = static_cast<fsw_real>(in.real(c.css.lit_threshold));
  c.mrp_fb.K = static_cast<fsw_real>(in.real(c.mrp_fb.K));
  c.mrp_fb.P = static_cast<fsw_real>(in.real(c.mrp_fb.P));
  c.mrp_fb.K_i = static_cast<fsw_real>(in.real(c.mrp_fb.K_i));
  c.mrp_fb.integral_limit = static_cast<fsw_real>(in.real(c.mrp_fb.integral_limit));
  c.use_lpf = in.flag(c.use_lpf);
  c.lpf.h = static_cast<fsw_real>(in.real(c.lpf.h));
  c.lpf.omega_c = static_cast<fsw_real>(in.real(c.lpf.omega_c));
  c.rw_map.mode = in.flag(c.rw_map.mode);
  c.rw_map.eps_P = static_cast<fsw_real>(in.real(c.rw_map.eps_P));
  c.use_null = in.flag(c.use_null);
  c.rw_null.k_null = static_cast<fsw_real>(in.real(c.rw_null.k_null));
  c.Omega_des[0] = static_cast<fsw_real>(in.real(c.Omega_des[0]));
  c.use_volt = in.flag(c.use_volt);
  c.rw_volt.K_V = static_cast<fsw_real>(in.real(c.rw_volt.K_V));
  c.rw_volt.V_max = static_cast<fsw_real>(in.real(c.rw_volt.V_max));
  c.thr_map.mode = in.flag(c.thr_map.mode);
  c.pulser = in.flag(c.pulser);
  c.pulse_rem.common.t_min = static_cast<fsw_real>(in.real(c.pulse_rem.common.t_min));
  c.pulse_schmitt.common.t_min = static_cast<fsw_real>(in.real(c.pulse_schmitt.common.t_min));
  if (issue14) {
    c.use_speed_filter = in.flag(1);
    c.speed_filter.k_reject = in.u32(3);
    c.speed_filter.n_recover = in.u32(3);
    c.speed_filter.n_stale = in.u32(4);
    c.speed_filter.n_window = in.u32(5);
    for (int i = 0; i < c.speed_filter.num_rw && i < FSW_MAX_RW; i++) {
      c.speed_filter.noise[i] = static_cast<fsw_real>(in.real(1.0));
      c.speed_filter.resid_tol[i] = static_cast<fsw_real>(in.real(0.2));
    }
    fuzz_trace_int("use_speed_filter", c.use_speed_filter);
  }
  scale_filter_limits(c, sf_scale);
  fuzz_trace_int("variant", variant);
  for (int i = 0; i < g.num_rw; i++) fuzz_trace("gs_hat_B[i]", g.gs_hat_B[i], 3);
  fuzz_trace("J_s", g.J_s, g.num_rw);
  fuzz_trace("u_max", g.u_max, g.num_rw);
  fuzz_trace("F_max", g.F_max, g.num_thr);
  fuzz_trace("mrp_fb K P K_i integral_limit", &c.mrp_fb.K, 4);
  fuzz_trace("css.lit_threshold", &c.css.lit_threshold, 1);
  fuzz_trace_int("initial_mode", c.initial_mode);
  fuzz_trace_int("initial_actuation", c.initial_actuation);
  fuzz_trace_int("use_null", c.use_null);
  fuzz_trace("k_null", &c.rw_null.k_null, 1);
  fuzz_trace_int("use_volt", c.use_volt);
  fuzz_trace("rw_volt K_V", &c.rw_volt.K_V, 1);
  fuzz_trace_int("use_lpf", c.use_lpf);
  fuzz_trace("lpf h omega_c", &c.lpf.h, 2);
  fuzz_trace_int("rw_map.mode", c.rw_map.mode);
  fuzz_trace("eps_P", &c.rw_map.eps_P, 1);
}

static FswStatus init_checked(FswAcsState *st, const FswAcsConfig *c) { return fsw_acs_init(st, c, nullptr); }
static FswStatus check_checked(const FswAcsConfig *c) { return fsw_acs_check(c, nullptr); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  static FswAcsConfig cfg;
  bool issue14 = false, issue38 = false;
  decode_config(in, cfg, issue14, issue38);
  static FswAcsState st;
  FswAcsSensorMsg sens{};
  FswAcsCmdMsg cmd{};
  const FswAcsCmdMsg *cmdp = nullptr;
  FswAcsActuatorMsg act;
  FswAcsHealthMsg hlth;
  const auto step = [&]() {
    const int s = fuzz_call("fsw_acs_cycle", st, act,
                            {FSW_OK, FSW_W_SINGULAR, FSW_W_SAT, FSW_W_RATE, FSW_E_BAD_INPUT, FSW_E_TIME,
                             FSW_E_NOT_INIT},
                            [&] { return fsw_acs_cycle(&st, &cfg, &sens, cmdp, &act, &hlth); }, mask, act_safe);
    FUZZ_REQUIRE(hlth.status == s, "fsw_acs_cycle returned %d but hlth.status = %d", s, hlth.status);
    FUZZ_REQUIRE((s < 0) == (hlth.safe_output != 0), "fsw_acs_cycle: status %d with safe_output %d", s,
                 hlth.safe_output);
    if (s < 0)  // issue 39: the safe health message
      FUZZ_REQUIRE(hlth.sun_valid == 0 && hlth.num_lit == 0 && fuzz_nonzero_from(hlth.sun_hat_B, 0, 3) < 0 &&
                       fuzz_nonzero_from(hlth.sigma_BR, 0, 3) < 0 && fuzz_nonzero_from(hlth.omega_BR_B, 0, 3) < 0 &&
                       fuzz_nonzero_from(hlth.h_w_B, 0, 3) < 0 && fuzz_nonzero_from(hlth.tau_mtq_B, 0, 3) < 0 &&
                       hlth.att_err_angle == 0 && hlth.sun_angle_err == 0 && hlth.rate_est == 0 &&
                       hlth.prop_used == 0 && hlth.dumps == 0 && hlth.detumbled == 0,
                   "fsw_acs_cycle: error %d but the health message carries the cycle's estimates", s);
    return s;
  };
  if (!fuzz_init("fsw_acs", st, cfg, check_checked, init_checked, [](const FswAcsState &s) { return s.ready; }, step))
    return 0;
  uint64_t t = 0;
  for (int k = 0, steps = in.steps(6, 24); k < steps; k++) {
    if (in.op()) fsw_acs_reset(&st, &cfg);
    const double sig[3] = {0.1, 0.2, -0.1}, w[3] = {1e-3, 1e-3, 0}, sun[3] = {0.6, 0.0, 0.8}, z[3] = {0, 0, 0};
    sens.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, acsfix::kPeriodNs);
    in.reals(sens.sigma_BN, 3, sig);
    sens.att_valid = static_cast<uint8_t>(in.flag(1));
    in.reals(sens.omega_BN_B, 3, w);
    for (int i = 0; i < cfg.css.num_css; i++) {
      const fsw_real *nrm = cfg.css.n_hat_B[i];
      const double c = nrm[0] * sun[0] + nrm[1] * sun[1] + nrm[2] * sun[2];
      sens.css[i] = static_cast<fsw_real>(in.real(c > 0 ? c : 0.0));
    }
    in.avail_mask(sens.css_avail, cfg.css.num_css);
    fuzz_speeds(in, sens.Omega, cfg.mrp_fb.num_rw, 20.0);
    in.avail_mask(sens.rw_avail, cfg.mrp_fb.num_rw);
    in.reals(sens.r_CoM_B, 3, z);
    if (issue14) in.avail_mask(sens.thr_avail, cfg.has_thrusters ? cfg.thr_map.num_thr : 0);
    if (issue38) {
      const double B0[3] = {2e-5, 1e-5, -3e-5}, r0[3] = {7e6, 0, 0}, v0[3] = {0, 7546.05, 0};
      in.reals(sens.B_B, 3, B0);
      sens.mag_valid = static_cast<uint8_t>(in.flag(1));
      in.reals(sens.r_N, 3, r0);
      in.reals(sens.v_N, 3, v0);
      sens.orbit_valid = static_cast<uint8_t>(in.flag(1));
      fuzz_trace("B_B", sens.B_B, 3);
      fuzz_trace("r_N", sens.r_N, 3);
      fuzz_trace("v_N", sens.v_N, 3);
      fuzz_trace_int("mag_valid", sens.mag_valid);
      fuzz_trace_int("orbit_valid", sens.orbit_valid);
    }
    cmdp = nullptr;
    if (in.u8() >= 200) {
      cmd.mode = in.flag(cfg.initial_mode == 0 ? 1 : 0);
      cmd.actuation = in.flag(cfg.initial_actuation);
      if (issue14) {
        const double ref0[3] = {0.2, -0.1, 0.3};
        cmd.set_ref = static_cast<uint8_t>(in.flag(1));
        in.reals(cmd.sigma_R0N, 3, ref0);
        cmd.set_gains = static_cast<uint8_t>(in.flag(0));
        cmd.K = static_cast<fsw_real>(in.real(cfg.mrp_fb.K));
        cmd.P = static_cast<fsw_real>(in.real(cfg.mrp_fb.P));
      }
      if (issue38) {
        cmd.mode = in.flag(in.u8() % 4);
        cmd.set_policy = static_cast<uint8_t>(in.flag(1));
        cmd.policy = in.flag(in.u8() % 3);
        fuzz_trace_int("cmd.set_policy", cmd.set_policy);
        fuzz_trace_int("cmd.policy", cmd.policy);
      }
      cmdp = &cmd;
    }
    fuzz_trace_int("t_ns", static_cast<long long>(sens.t_ns));
    fuzz_trace("omega_BN_B", sens.omega_BN_B, 3);
    fuzz_trace("sigma_BN", sens.sigma_BN, 3);
    fuzz_trace("css", sens.css, cfg.css.num_css);
    fuzz_trace("Omega", sens.Omega, cfg.mrp_fb.num_rw);
    fuzz_trace("r_CoM_B", sens.r_CoM_B, 3);
    fuzz_trace_int("att_valid", sens.att_valid);
    if (cmdp != nullptr) fuzz_trace_int("cmd.mode", cmd.mode), fuzz_trace_int("cmd.actuation", cmd.actuation);
    const uint32_t cycles = st.cycles;
    const uint32_t sf_bad = st.speed_filter.health.bad_input;
    const int first = !st.clock.has_prev;
    const double dt = first ? 0.0 : static_cast<double>(sens.t_ns - st.clock.t_prev_ns) * 1e-9;
    const int s = step();
    // issue 39: the cycle validated the filter's inputs; a refusal there is
    // an error with no stage to blame (a filter limit below rw_sat's)
    FUZZ_REQUIRE(st.speed_filter.health.bad_input == sf_bad,
                 "fsw_acs_cycle: the speed filter refused its input (status %d): u_max %.17g against rw_sat's %.17g", s,
                 static_cast<double>(cfg.speed_filter.u_max[0]), static_cast<double>(cfg.rw_sat.u_max[0]));
    if (s < 0) {
      FUZZ_REQUIRE(hlth.cycles == cycles, "fsw_acs_cycle: error but cycles %u -> %u", cycles, hlth.cycles);
      continue;
    }
    // issue 38: the rods, the new telemetry, mode and policy
    FUZZ_REQUIRE(fuzz_finite(act.m_cmd, FSW_MAX_MTQ), "fsw_acs_cycle: non-finite rod command");
    FUZZ_REQUIRE(act.mtq_active || fuzz_nonzero_from(act.m_cmd, 0, FSW_MAX_MTQ) < 0,
                 "fsw_acs_cycle: a rod command without mtq_active");
    FUZZ_REQUIRE(cfg.has_mtq || act.mtq_active == 0, "fsw_acs_cycle: mtq_active without rods");
    if (cfg.has_mtq) {
      FUZZ_REQUIRE(fuzz_nonzero_from(act.m_cmd, cfg.mtq_map.num_mtq, FSW_MAX_MTQ) < 0,
                   "fsw_acs_cycle: a rod command beyond num_mtq");
      for (int i = 0; i < cfg.mtq_map.num_mtq; i++)
        FUZZ_REQUIRE(std::fabs(act.m_cmd[i]) <= cfg.mtq_map.duty_max * cfg.mtq_map.m_max[i] * (1 + 1e-6),
                     "fsw_acs_cycle: |m_cmd[%d]| = %.17g above duty_max m_max", i, act.m_cmd[i]);
    }
    FUZZ_REQUIRE(fuzz_finite(hlth.tau_mtq_B, 3) && fuzz_finite(hlth.h_w_B, 3) && std::isfinite(hlth.rate_est) &&
                     std::isfinite(hlth.prop_used) && hlth.prop_used >= 0,
                 "fsw_acs_cycle: non-finite telemetry of the momentum paths");
    FUZZ_REQUIRE(hlth.mode >= FSW_ACS_MODE_SUN_SAFE && hlth.mode <= FSW_ACS_MODE_NADIR &&
                     (hlth.mode != FSW_ACS_MODE_DETUMBLE || cfg.has_mtq) &&
                     (hlth.mode != FSW_ACS_MODE_NADIR || cfg.has_orbit),
                 "fsw_acs_cycle: mode %d not configured", hlth.mode);
    FUZZ_REQUIRE(hlth.policy == FSW_ACS_MOM_NONE || (hlth.policy == FSW_ACS_MOM_THRUSTERS && cfg.use_thr_mom) ||
                     (hlth.policy == FSW_ACS_MOM_MAGNETORQUERS && cfg.use_mtq_desat),
                 "fsw_acs_cycle: policy %d not configured", hlth.policy);
    FUZZ_REQUIRE(hlth.cycles == cycles + 1, "fsw_acs_cycle: accepted cycle not counted");
    FUZZ_REQUIRE(fuzz_finite(act.Lr_B, 3) && fuzz_finite(act.u_s, FSW_MAX_RW) && fuzz_finite(act.V, FSW_MAX_RW) &&
                     fuzz_finite(act.F, FSW_MAX_THR) && fuzz_finite(act.t_on, FSW_MAX_THR),
                 "fsw_acs_cycle: non-finite command under %s", fsw_status_name(static_cast<FswStatus>(s)));
    if (act.wheels_active) {
      for (int i = 0; i < cfg.rw_sat.num_rw; i++) {
        FUZZ_REQUIRE(std::fabs(act.u_s[i]) <= cfg.rw_sat.u_max[i], "fsw_acs_cycle: |u_s[%d]| = %.17g above u_max", i,
                     act.u_s[i]);
        FUZZ_REQUIRE(!cfg.use_volt || std::fabs(act.V[i]) <= cfg.rw_volt.V_max, "fsw_acs_cycle: |V[%d]| = %.17g", i,
                     act.V[i]);
      }
    }
    FUZZ_REQUIRE((hlth.rw_latched & ~hlth.rw_failed) == 0, "fsw_acs_cycle: a latched wheel not failed");
    FUZZ_REQUIRE(cfg.mrp_fb.num_rw >= 64 || (hlth.rw_failed >> cfg.rw_map.num_rw) == 0 || !cfg.has_wheels,
                 "fsw_acs_cycle: failed bits beyond the wheels");
    if (act.thrusters_active)
      for (int i = 0; i < cfg.thr_map.num_thr; i++)
        FUZZ_REQUIRE(sens.thr_avail[i] == 0 || act.t_on[i] == 0, "fsw_acs_cycle: flagged thruster %d fires %.17g s",
                     i, act.t_on[i]);
    if (act.thrusters_active) {
      const FswThrPulseCommon &pc =
          cfg.pulser == FSW_ACS_PULSE_SCHMITT ? cfg.pulse_schmitt.common : cfg.pulse_rem.common;
      const int pfirst = cfg.pulser == FSW_ACS_PULSE_SCHMITT ? !st.pulse_schmitt.common.clock.has_prev : 0;
      (void)pfirst;
      for (int i = 0; i < pc.num_thr; i++)
        FUZZ_REQUIRE(act.t_on[i] >= 0 && (act.t_on[i] <= 1.1 * dt * (1 + 1e-12) ||
                                          act.t_on[i] == pc.base_thrust_state * pc.init_off_pulse_on_time),
                     "fsw_acs_cycle: t_on[%d] = %.17g for a %.17g s cycle", i, act.t_on[i], dt);
    }
  }
  return 0;
}

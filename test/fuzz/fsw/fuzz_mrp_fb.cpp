// fsw_mrp_fb_update: gains, integral limit, law, known torque, inertia
// (element-wise: asymmetric and indefinite ones too), wheel axes and
// inertias; a sequence of guidance messages, wheel speeds, masks and time
// stamps.  OK: finite torque and integral torque, every |int_sigma_j| <=
// integral_limit; errors: zero torques and no state change (integral,
// clock).
#include "fsw/mrp_fb.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  const int variant = in.u8() % 2;  // 0: integral off (reference), 1: integral on
  FswMrpFbConfig cfg{};
  cfg.K = static_cast<fsw_real>(in.real(1.44));
  cfg.P = static_cast<fsw_real>(in.real(36.0));
  cfg.K_i = static_cast<fsw_real>(in.real(variant ? 1e-3 : -1.0));
  cfg.integral_limit = static_cast<fsw_real>(in.real(variant ? 0.5 : 0.0));
  cfg.control_law_type = in.flag(FSW_MRP_FB_LAW_0);
  const double L0[3] = {0, 0, 0}, I[3][3] = {{900, 0, 0}, {0, 800, 0}, {0, 0, 600}};
  in.reals(cfg.known_torque_B, 3, L0);
  for (int r = 0; r < 3; r++) in.reals(cfg.I_B[r], 3, I[r]);
  const int n = fuzz_wheel_axes(in, cfg.gs_hat_B, &cfg.num_rw);
  in.reals(cfg.J_s, n, nullptr, 0.1);
  fuzz_trace("K P K_i integral_limit", &cfg.K, 4);
  fuzz_trace("I_B", cfg.I_B[0], 9);
  static FswMrpFbState st;
  FswMrpFbIn x{};
  FswMrpFbOut out;
  const auto step = [&]() {
    return fuzz_call("mrp_fb", st, out, {FSW_OK, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_mrp_fb_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswMrpFbState>,
                     [](const FswMrpFbOut &o, int) {
                       return fuzz_nonzero_from(o.torque_B, 0, 3) < 0 && fuzz_nonzero_from(o.int_torque_B, 0, 3) < 0;
                     });
  };
  if (!fuzz_init("mrp_fb", st, cfg, fsw_mrp_fb_check, fsw_mrp_fb_init,
                 [](const FswMrpFbState &s) { return s.ready; }, step))
    return 0;
  uint64_t t = 0;
  for (int k = 0, steps = in.steps(8, 32); k < steps; k++) {
    if (in.op()) fsw_mrp_fb_reset(&st);
    const double s[3] = {0.3 - 0.01 * k, -0.1, 0.05}, w[3] = {1e-3, 2e-3, -1e-3}, wR[3] = {0, 0, 1e-3},
                 dw[3] = {0, 0, 0};
    in.reals(x.guid.sigma_BR, 3, s);
    in.reals(x.guid.omega_BR_B, 3, w);
    in.reals(x.guid.omega_RN_B, 3, wR);
    in.reals(x.guid.omega_dot_RN_B, 3, dw);
    fuzz_speeds(in, x.Omega, n, 100.0);
    in.avail_mask(x.rw_avail, n);
    x.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, 500000000ull);
    fuzz_trace("guid (sigma_BR omega_BR_B omega_RN_B omega_dot_RN_B)", x.guid.sigma_BR, 12);
    fuzz_trace("Omega", x.Omega, n);
    fuzz_trace_int("t_ns", static_cast<long long>(x.t_ns));
    if (step() < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.torque_B, 3) && fuzz_finite(out.int_torque_B, 3),
                 "mrp_fb: non-finite torque (%g %g %g) under OK", out.torque_B[0], out.torque_B[1], out.torque_B[2]);
    for (int j = 0; j < 3; j++)
      FUZZ_REQUIRE(std::fabs(st.int_sigma[j]) <= cfg.integral_limit, "mrp_fb: |int_sigma[%d]| = %.17g above %.17g", j,
                   st.int_sigma[j], cfg.integral_limit);
  }
  return 0;
}

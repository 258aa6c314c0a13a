// fsw_rw_null_update: wheel axes, k_null, scale_to_fit and limits; a
// sequence of mapped torques, speeds, desired speeds and masks (mask changes
// recompute the cached projector).  OK/W_SAT: finite torques, kappa in
// [0, 1] (1 under OK), 0 on unavailable wheels and beyond num_rw, body
// torque unchanged, within the limits when the input was; errors: u = 0 and
// no state change (the projector cache included).
#include "fsw/rw_null.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswRwNullConfig cfg{};
  cfg.scale_to_fit = in.flag(in.u8() % 2 == 0 ? 1 : 0);
  const int n = fuzz_wheel_axes(in, cfg.gs_hat_B, &cfg.num_rw);
  cfg.k_null = static_cast<fsw_real>(in.real(0.002));
  in.reals(cfg.u_max, n, nullptr, 0.2);
  fuzz_trace("k_null", &cfg.k_null, 1);
  fuzz_trace_int("scale_to_fit", cfg.scale_to_fit);
  fuzz_trace("u_max", cfg.u_max, n);
  static FswRwNullState st;
  FswRwNullIn x{};
  FswRwNullOut out;
  const auto step = [&]() {
    return fuzz_call("rw_null", st, out, {FSW_OK, FSW_W_SAT, FSW_W_SINGULAR, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_rw_null_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswRwNullState>,
                     [](const FswRwNullOut &o, int) { return fuzz_nonzero_from(o.u_s, 0, FSW_MAX_RW) < 0; });
  };
  if (!fuzz_init("rw_null", st, cfg, fsw_rw_null_check, fsw_rw_null_init,
                 [](const FswRwNullState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_rw_null_reset(&st);
    fuzz_speeds(in, x.u_s, n, 0.05);
    fuzz_speeds(in, x.Omega, n, 100.0);
    fuzz_speeds(in, x.Omega_des, n, 0.0);
    in.avail_mask(x.avail, n);
    fuzz_trace("u_s", x.u_s, n);
    fuzz_trace("Omega", x.Omega, n);
    fuzz_trace("Omega_des", x.Omega_des, n);
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.u_s, FSW_MAX_RW) && std::isfinite(out.kappa), "rw_null: non-finite output under %s (kappa %g)",
                 fsw_status_name(static_cast<FswStatus>(s)), out.kappa);
    FUZZ_REQUIRE(out.kappa >= 0 && out.kappa <= 1 && (s != FSW_OK || out.kappa == 1),
                 "rw_null: kappa %.17g under %s", out.kappa, fsw_status_name(static_cast<FswStatus>(s)));
    FUZZ_REQUIRE(fuzz_nonzero_from(out.u_s, n, FSW_MAX_RW) < 0, "rw_null: torque beyond num_rw");
    FUZZ_REQUIRE(fuzz_unavail_nonzero(out.u_s, x.avail, n) < 0, "rw_null: torque on an unavailable wheel");
    double diff, scale;
    fuzz_wheel_torque_diff(cfg.gs_hat_B, x.avail, n, out.u_s, x.u_s, &diff, &scale);
    FUZZ_REQUIRE(diff <= 1e-6 * scale + 1e-100, "rw_null: body torque changed by %.17g (scale %.17g)", diff, scale);
    if (cfg.scale_to_fit) {
      bool in_limits = true;
      for (int i = 0; i < n; i++) in_limits = in_limits && (x.avail[i] || std::fabs(x.u_s[i]) <= cfg.u_max[i]);
      for (int i = 0; i < n && in_limits; i++)
        FUZZ_REQUIRE(std::fabs(out.u_s[i]) <= cfg.u_max[i], "rw_null: |u[%d]| = %.17g above u_max", i, out.u_s[i]);
    }
  }
  return 0;
}

// fsw_rw_null_regen_update: wheel axes, mode, k_P and limits; a sequence of
// mapped torques, speeds and masks.  OK/W_SAT: finite torques and power,
// power = Omega^T u, 0 on unavailable wheels and beyond num_rw, body torque
// unchanged and, when u0 is within the limits, power not above that of u0
// and the output within the limits;
// E_UNSUPPORTED: u = u0 passed through; other errors: u = 0; every error
// leaves the state (projector cache included) unchanged.
#include "fsw/rw_null_regen.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswRwNullRegenConfig cfg{};
  cfg.mode = in.flag(in.u8() % 2);
  const int n = fuzz_wheel_axes(in, cfg.gs_hat_B, &cfg.num_rw);
  cfg.k_P = static_cast<fsw_real>(in.real(1e-4));
  in.reals(cfg.u_max, n, nullptr, 0.2);
  fuzz_trace("k_P", &cfg.k_P, 1);
  fuzz_trace("u_max", cfg.u_max, n);
  static FswRwNullRegenState st;
  FswRwNullRegenIn x{};
  FswRwNullRegenOut out;
  fsw_real u0[FSW_MAX_RW] = {0};
  const auto is_safe = [&](const FswRwNullRegenOut &o, int s) {
    if (s != FSW_E_UNSUPPORTED) return fuzz_nonzero_from(o.u_s, 0, FSW_MAX_RW) < 0;
    return std::memcmp(o.u_s, u0, sizeof u0) == 0;
  };
  const auto step = [&]() {
    return fuzz_call("rw_null_regen", st, out,
                     {FSW_OK, FSW_W_SAT, FSW_W_SINGULAR, FSW_E_UNSUPPORTED, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_rw_null_regen_update(&st, &cfg, &x, &out); },
                     fuzz_mask_health<FswRwNullRegenState>, is_safe);
  };
  if (!fuzz_init("rw_null_regen", st, cfg, fsw_rw_null_regen_check, fsw_rw_null_regen_init,
                 [](const FswRwNullRegenState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_rw_null_regen_reset(&st);
    fuzz_speeds(in, x.u_s, n, 0.05);
    fuzz_speeds(in, x.Omega, n, 100.0);
    in.avail_mask(x.avail, n);
    for (int i = 0; i < FSW_MAX_RW; i++) u0[i] = (i < n && x.avail[i] == 0) ? x.u_s[i] : 0;
    fuzz_trace("u_s", x.u_s, n);
    fuzz_trace("Omega", x.Omega, n);
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.u_s, FSW_MAX_RW) && std::isfinite(out.power),
                 "rw_null_regen: non-finite output under %s (power %g)", fsw_status_name(static_cast<FswStatus>(s)),
                 out.power);
    FUZZ_REQUIRE(fuzz_nonzero_from(out.u_s, n, FSW_MAX_RW) < 0, "rw_null_regen: torque beyond num_rw");
    FUZZ_REQUIRE(fuzz_unavail_nonzero(out.u_s, x.avail, n) < 0, "rw_null_regen: torque on an unavailable wheel");
    double diff, scale;
    fuzz_wheel_torque_diff(cfg.gs_hat_B, x.avail, n, out.u_s, x.u_s, &diff, &scale);
    FUZZ_REQUIRE(diff <= 1e-6 * scale + 1e-100, "rw_null_regen: body torque changed by %.17g (scale %.17g)", diff,
                 scale);
    long double p0 = 0, p1 = 0, ps = 0;
    bool in_limits = true;
    for (int i = 0; i < n; i++) {
      if (x.avail[i]) continue;
      p0 += static_cast<long double>(x.Omega[i]) * u0[i];
      p1 += static_cast<long double>(x.Omega[i]) * out.u_s[i];
      // in long double: |u0| + |u| of two near-DBL_MAX torques overflows double (0 * inf = NaN)
      ps += std::fabs(static_cast<long double>(x.Omega[i])) *
            (std::fabs(static_cast<long double>(u0[i])) + std::fabs(static_cast<long double>(out.u_s[i])));
      in_limits = in_limits && std::fabs(u0[i]) <= cfg.u_max[i];
    }
    FUZZ_REQUIRE(std::fabs(out.power - p1) <= 1e-9 * ps + 1e-300, "rw_null_regen: power %.17g, Omega^T u = %.17Lg",
                 out.power, p1);
    FUZZ_REQUIRE(!in_limits || p1 <= p0 + 1e-9 * ps + 1e-300, "rw_null_regen: power rose from %.17Lg to %.17Lg", p0, p1);
    for (int i = 0; i < n && in_limits; i++)
      FUZZ_REQUIRE(std::fabs(out.u_s[i]) <= cfg.u_max[i], "rw_null_regen: |u[%d]| = %.17g above u_max", i,
                   out.u_s[i]);
  }
  return 0;
}

// fsw_rw_bias_update: wheel axes, bias speeds, keep-out band and hysteresis;
// a sequence of speeds and masks (mask changes recompute the cached
// projector and null basis).  OK/W_SAT: finite desired speeds within
// +-FSW_RW_OMEGA_MAX, Gs_a Omega_des = Gs_a Omega (only null-space moves),
// unavailable wheels and entries beyond num_rw held, flags 0/1 and
// consistent; under OK no wheel with |Omega| >= keepout changes sign and
// every available wheel is out of its band.  Errors: the safe output
// (Omega_des = the held speeds) and no state change.
#include "fsw/rw_bias.h"
#include "fuzz_input.h"

static fsw_real held(fsw_real om) { return std::fabs(om) <= FSW_RW_OMEGA_MAX ? om : FSW_R(0.0); }
// same strict side of zero (a product would underflow for tiny speeds)
static bool same_side(double a, double b) { return (a > 0 && b > 0) || (a < 0 && b < 0); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswRwBiasConfig cfg{};
  const int n = fuzz_wheel_axes(in, cfg.gs_hat_B, &cfg.num_rw);
  cfg.Omega_keepout = static_cast<fsw_real>(in.real(20.0));
  cfg.Omega_hyst = static_cast<fsw_real>(in.real(5.0));
  for (int i = 0; i < n; i++) cfg.Omega_bias[i] = static_cast<fsw_real>(in.real((i % 2 ? -1.0 : 1.0) * 150.0));
  fuzz_trace("Omega_keepout", &cfg.Omega_keepout, 1);
  fuzz_trace("Omega_hyst", &cfg.Omega_hyst, 1);
  fuzz_trace("Omega_bias", cfg.Omega_bias, n);
  static FswRwBiasState st;
  FswRwBiasIn x{};
  FswRwBiasOut out;
  const int nv = (cfg.num_rw >= 1 && cfg.num_rw <= FSW_MAX_RW) ? cfg.num_rw : 0;
  const auto is_safe = [&](const FswRwBiasOut &o, int) {
    for (int i = 0; i < FSW_MAX_RW; i++) {
      const fsw_real want = i < nv ? held(x.Omega[i]) : FSW_R(0.0);
      if (!(o.Omega_des[i] == want) || o.in_band[i] != 0 || o.unavoidable[i] != 0) return false;
    }
    return o.crossing_unavoidable == 0 && o.lambda_norm == 0 && o.nullity == 0;
  };
  const auto step = [&]() {
    return fuzz_call("rw_bias", st, out, {FSW_OK, FSW_W_SAT, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_rw_bias_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswRwBiasState>,
                     is_safe);
  };
  if (!fuzz_init("rw_bias", st, cfg, fsw_rw_bias_check, fsw_rw_bias_init,
                 [](const FswRwBiasState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_rw_bias_reset(&st);
    fuzz_speeds(in, x.Omega, n, 100.0);
    in.avail_mask(x.avail, n);
    fuzz_trace("Omega", x.Omega, n);
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.Omega_des, FSW_MAX_RW) && std::isfinite(out.lambda_norm),
                 "rw_bias: non-finite output under %s", fsw_status_name(static_cast<FswStatus>(s)));
    FUZZ_REQUIRE(fuzz_nonzero_from(out.Omega_des, n, FSW_MAX_RW) < 0, "rw_bias: desired speed beyond num_rw");
    int any = 0;
    for (int i = 0; i < n; i++) {
      const double om = x.Omega[i], d = out.Omega_des[i];
      FUZZ_REQUIRE(std::fabs(d) <= FSW_RW_OMEGA_MAX, "rw_bias: |Omega_des[%d]| = %.17g beyond the range", i, d);
      FUZZ_REQUIRE(out.in_band[i] <= 1 && out.unavoidable[i] <= 1, "rw_bias: flag not 0/1 at %d", i);
      if (x.avail[i]) {
        FUZZ_REQUIRE(d == held(x.Omega[i]) && out.in_band[i] == 0 && out.unavoidable[i] == 0,
                     "rw_bias: unavailable wheel %d not held", i);
        continue;
      }
      any |= out.unavoidable[i];
      FUZZ_REQUIRE(out.in_band[i] || std::fabs(om) >= cfg.Omega_keepout, "rw_bias: wheel %d in the band but not flagged", i);
      if (s == FSW_OK) {
        FUZZ_REQUIRE(std::fabs(om) < cfg.Omega_keepout || same_side(d, om),
                     "rw_bias: wheel %d changes sign under OK (%.17g -> %.17g)", i, om, d);
        FUZZ_REQUIRE(std::fabs(d) >= (1 - FSW_RW_BIAS_TOL) * cfg.Omega_keepout && (om == 0 || same_side(d, om)),
                     "rw_bias: wheel %d left in its band / sent through zero under OK (%.17g -> %.17g)", i, om, d);
      }
    }
    FUZZ_REQUIRE(out.crossing_unavoidable == any && (s == FSW_W_SAT) == (any == 1),
                 "rw_bias: status %s and flags disagree", fsw_status_name(static_cast<FswStatus>(s)));
    double diff, scale;
    fuzz_wheel_torque_diff(cfg.gs_hat_B, x.avail, n, out.Omega_des, x.Omega, &diff, &scale);
    FUZZ_REQUIRE(diff <= (sizeof(fsw_real) == 8 ? 1e-9 : 1e-4) * scale + 1e-100,
                 "rw_bias: body momentum changed by %.17g (scale %.17g)", diff, scale);
  }
  return 0;
}

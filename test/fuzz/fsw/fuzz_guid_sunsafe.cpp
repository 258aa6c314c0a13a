// fsw_guid_sunsafe_update: commanded axis, validity threshold, dead band,
// search rate and spin rate; a sequence of Sun headings (any length,
// including 0, antiparallel and overflowing ones) and body rates.  OK:
// finite guidance, |sigma_BR| <= 1, omega_dot_RN = 0, sun_valid agrees with
// |s_B| > min_unit_mag, and for a valid heading the reported angle is the
// angle between s_cmd and s_B and sigma_BR turns by it (4 atan|sigma| =
// angle outside the dead band); errors: all 0.
#include "fsw/guid_sunsafe.h"
#include "fuzz_input.h"

// angle between a and b, in long double (no overflow for finite doubles)
static double angle(const fsw_real *a, const fsw_real *b)
{
  long double na = 0, nb = 0, d = 0, c[3];
  for (int k = 0; k < 3; k++) {
    na += static_cast<long double>(a[k]) * a[k];
    nb += static_cast<long double>(b[k]) * b[k];
    d += static_cast<long double>(a[k]) * b[k];
  }
  c[0] = static_cast<long double>(a[1]) * b[2] - static_cast<long double>(a[2]) * b[1];
  c[1] = static_cast<long double>(a[2]) * b[0] - static_cast<long double>(a[0]) * b[2];
  c[2] = static_cast<long double>(a[0]) * b[1] - static_cast<long double>(a[1]) * b[0];
  (void)na;
  (void)nb;
  return static_cast<double>(std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), d));
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswGuidSunsafeConfig cfg{};
  const double s0[3] = {0, 0, 1}, w0[3] = {0, 0, 0.005};
  in.reals(cfg.s_cmd_B, 3, s0);
  cfg.min_unit_mag = static_cast<fsw_real>(in.real(0.1));
  cfg.small_angle = static_cast<fsw_real>(in.real(1e-4));
  in.reals(cfg.omega_search_B, 3, w0);
  cfg.sun_axis_spin_rate = static_cast<fsw_real>(in.real(0.0));
  fuzz_trace("s_cmd_B", cfg.s_cmd_B, 3);
  fuzz_trace("min_unit_mag small_angle", &cfg.min_unit_mag, 2);
  static FswGuidSunsafeState st;
  FswGuidSunsafeIn x{};
  FswGuidSunsafeOut out;
  const auto is_safe = [](const FswGuidSunsafeOut &o, int) {
    const FswAttGuid &g = o.guid;
    return fuzz_nonzero_from(g.sigma_BR, 0, 3) < 0 && fuzz_nonzero_from(g.omega_BR_B, 0, 3) < 0 &&
           fuzz_nonzero_from(g.omega_RN_B, 0, 3) < 0 && fuzz_nonzero_from(g.omega_dot_RN_B, 0, 3) < 0 &&
           o.sun_angle_err == 0 && o.sun_valid == 0;
  };
  const auto step = [&]() {
    return fuzz_call("guid_sunsafe", st, out, {FSW_OK, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_guid_sunsafe_update(&st, &cfg, &x, &out); },
                     fuzz_mask_health<FswGuidSunsafeState>, is_safe);
  };
  if (!fuzz_init("guid_sunsafe", st, cfg, fsw_guid_sunsafe_check, fsw_guid_sunsafe_init,
                 [](const FswGuidSunsafeState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_guid_sunsafe_reset(&st);
    const double a = 0.7 * k, sun[3] = {0.6 * std::cos(a), 0.6 * std::sin(a), 0.8}, w[3] = {1e-3, -2e-3, 5e-4};
    in.reals(x.sun_B, 3, sun);
    in.reals(x.omega_BN_B, 3, w);
    fuzz_trace("sun_B", x.sun_B, 3);
    fuzz_trace("omega_BN_B", x.omega_BN_B, 3);
    if (step() < 0) continue;
    const FswAttGuid &g = out.guid;
    FUZZ_REQUIRE(fuzz_finite(g.sigma_BR, 3) && fuzz_finite(g.omega_BR_B, 3) && fuzz_finite(g.omega_RN_B, 3) &&
                     std::isfinite(out.sun_angle_err),
                 "guid_sunsafe: non-finite guidance under OK (sigma %g %g %g)", g.sigma_BR[0], g.sigma_BR[1],
                 g.sigma_BR[2]);
    FUZZ_REQUIRE(fuzz_nonzero_from(g.omega_dot_RN_B, 0, 3) < 0, "guid_sunsafe: omega_dot_RN_B not 0");
    const double sig = fuzz_norm3(g.sigma_BR);
    FUZZ_REQUIRE(sig <= 1.0 + 1e-12, "guid_sunsafe: |sigma_BR| = %.17g", sig);
    // valid iff |s_B| > min_unit_mag; within rounding of the threshold either answer is right
    const double sn = fuzz_norm3(x.sun_B), mu = cfg.min_unit_mag;
    const bool valid = std::fabs(sn - mu) <= 1e-12 * (sn > mu ? sn : mu) ? out.sun_valid != 0 : sn > mu;
    FUZZ_REQUIRE(out.sun_valid == (valid ? 1 : 0), "guid_sunsafe: sun_valid %d but |s_B| = %.17g", out.sun_valid,
                 fuzz_norm3(x.sun_B));
    if (!valid) continue;
    const double th = angle(cfg.s_cmd_B, x.sun_B);
    FUZZ_REQUIRE(std::fabs(out.sun_angle_err - th) <= 1e-6, "guid_sunsafe: angle error %.17g, true angle %.17g",
                 out.sun_angle_err, th);
    FUZZ_REQUIRE(th <= cfg.small_angle + 1e-6 || std::fabs(4.0 * std::atan(sig) - th) <= 1e-6,
                 "guid_sunsafe: sigma_BR turns by %.17g rad, the Sun is %.17g rad away", 4.0 * std::atan(sig), th);
  }
  return 0;
}

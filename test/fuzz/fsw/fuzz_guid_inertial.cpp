// fsw_guid_inertial_update (no runtime input): the commanded attitude of
// any magnitude; a sequence of calls and resets.  OK: sigma_RN finite,
// |sigma_RN| <= 1 and the same attitude as sigma_R0N (itself or its shadow
// set), rates 0; NOT_INIT: all 0.
#include "fsw/guid_inertial.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswGuidInertialConfig cfg{};
  const double s0[3] = {0.1, -0.05, 0.2};
  in.reals(cfg.sigma_R0N, 3, s0);
  fuzz_trace("sigma_R0N", cfg.sigma_R0N, 3);
  static FswGuidInertialState st;
  FswGuidInertialOut out;
  const auto is_safe = [](const FswGuidInertialOut &o, int) {
    return fuzz_nonzero_from(o.sigma_RN, 0, 3) < 0 && fuzz_nonzero_from(o.omega_RN_N, 0, 3) < 0 &&
           fuzz_nonzero_from(o.omega_dot_RN_N, 0, 3) < 0;
  };
  const auto step = [&]() {
    return fuzz_call("guid_inertial", st, out, {FSW_OK, FSW_E_NOT_INIT},
                     [&] { return fsw_guid_inertial_update(&st, &cfg, &out); },
                     fuzz_mask_health<FswGuidInertialState>, is_safe);
  };
  if (!fuzz_init("guid_inertial", st, cfg, fsw_guid_inertial_check, fsw_guid_inertial_init,
                 [](const FswGuidInertialState &s) { return s.ready; }, step))
    return 0;
  // the expected attitude: sigma or its shadow -sigma/|sigma|^2, in long double
  long double q = 0, e[3];
  for (int k = 0; k < 3; k++) q += static_cast<long double>(cfg.sigma_R0N[k]) * cfg.sigma_R0N[k];
  for (int k = 0; k < 3; k++) e[k] = q > 1 ? -cfg.sigma_R0N[k] / q : cfg.sigma_R0N[k];
  for (int k = 0, steps = in.steps(2, 8); k < steps; k++) {
    if (in.op()) fsw_guid_inertial_reset(&st);
    if (step() < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.sigma_RN, 3) && fuzz_norm3(out.sigma_RN) <= 1.0 + 1e-12,
                 "guid_inertial: sigma_RN (%g %g %g) not finite or above 1", out.sigma_RN[0], out.sigma_RN[1],
                 out.sigma_RN[2]);
    FUZZ_REQUIRE(fuzz_nonzero_from(out.omega_RN_N, 0, 3) < 0 && fuzz_nonzero_from(out.omega_dot_RN_N, 0, 3) < 0,
                 "guid_inertial: non-zero reference rates");
    // at |sigma| = 1 (within rounding) sigma and its shadow -sigma are the same attitude
    const long double sgn = (std::fabs(q - 1) <= 1e-12L && out.sigma_RN[0] * e[0] + out.sigma_RN[1] * e[1] +
                                                              out.sigma_RN[2] * e[2] < 0) ? -1 : 1;
    for (int j = 0; j < 3; j++)
      FUZZ_REQUIRE(std::fabs(out.sigma_RN[j] - sgn * e[j]) <= 1e-12L * (std::fabs(e[j]) + std::sqrt(q > 1 ? 1 / q : q)) + 1e-300L,
                   "guid_inertial: sigma_RN[%d] = %.17g, expected %.17Lg", j, out.sigma_RN[j], sgn * e[j]);
  }
  return 0;
}

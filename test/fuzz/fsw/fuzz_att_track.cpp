// fsw_att_track_update: the reference correction sigma_R0R; a sequence of
// navigation attitudes and rates and references (attitudes of any
// magnitude, huge rates).  OK: finite guidance with |sigma_BR| <= 1; errors
// (NaN/inf or overflowing inputs): all 0.
#include "fsw/att_track.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswAttTrackConfig cfg{};
  const double z[3] = {0, 0, 0};
  in.reals(cfg.sigma_R0R, 3, z);
  fuzz_trace("sigma_R0R", cfg.sigma_R0R, 3);
  static FswAttTrackState st;
  FswAttTrackIn x{};
  FswAttTrackOut out;
  const auto is_safe = [](const FswAttTrackOut &o, int) {
    return fuzz_nonzero_from(o.sigma_BR, 0, 3) < 0 && fuzz_nonzero_from(o.omega_BR_B, 0, 3) < 0 &&
           fuzz_nonzero_from(o.omega_RN_B, 0, 3) < 0 && fuzz_nonzero_from(o.omega_dot_RN_B, 0, 3) < 0;
  };
  const auto step = [&]() {
    return fuzz_call("att_track", st, out, {FSW_OK, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_att_track_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswAttTrackState>,
                     is_safe);
  };
  if (!fuzz_init("att_track", st, cfg, fsw_att_track_check, fsw_att_track_init,
                 [](const FswAttTrackState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_att_track_reset(&st);
    const double sBN[3] = {0.1 * k, -0.2, 0.3}, w[3] = {1e-3, -2e-3, 5e-4}, sRN[3] = {0.1, -0.05, 0.2},
                 wR[3] = {0, 0, 1e-3}, dwR[3] = {0, 0, 0};
    in.reals(x.sigma_BN, 3, sBN);
    in.reals(x.omega_BN_B, 3, w);
    in.reals(x.ref.sigma_RN, 3, sRN);
    in.reals(x.ref.omega_RN_N, 3, wR);
    in.reals(x.ref.omega_dot_RN_N, 3, dwR);
    fuzz_trace("sigma_BN", x.sigma_BN, 3);
    fuzz_trace("omega_BN_B", x.omega_BN_B, 3);
    fuzz_trace("ref (sigma_RN omega_RN_N omega_dot_RN_N)", x.ref.sigma_RN, 9);
    if (step() < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.sigma_BR, 3) && fuzz_finite(out.omega_BR_B, 3) && fuzz_finite(out.omega_RN_B, 3) &&
                     fuzz_finite(out.omega_dot_RN_B, 3),
                 "att_track: non-finite guidance under OK");
    FUZZ_REQUIRE(fuzz_norm3(out.sigma_BR) <= 1.0 + 1e-12, "att_track: |sigma_BR| = %.17g", fuzz_norm3(out.sigma_BR));
  }
  return 0;
}

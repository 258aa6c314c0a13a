// fsw_guid_orbit_update: variant, offset of any magnitude, mu; a sequence of
// positions, velocities and valid flags.  OK: |sigma| <= 1, finite rates
// along h_hat = r x v / |r x v|, and the frame's defining axis (nadir:
// R3 = -r_hat; velocity: R1 = v_hat) when there is no offset.  Errors: all
// zeros and no state change.
#include "fsw/guid_orbit.h"
#include "fsw/fsw_attitude.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswGuidOrbitConfig cfg{};
  cfg.variant = in.flag(in.u8() % 2);
  const double s0[3] = {0.0, 0.0, 0.0};
  if (in.u8() >= 128) in.reals(cfg.sigma_BdR, 3, s0, 0.2);
  cfg.mu = static_cast<fsw_real>(in.real(3.986004418e14));
  fuzz_trace_int("variant", cfg.variant);
  fuzz_trace("sigma_BdR", cfg.sigma_BdR, 3);
  fuzz_trace("mu", &cfg.mu, 1);
  const bool no_offset = cfg.sigma_BdR[0] == 0 && cfg.sigma_BdR[1] == 0 && cfg.sigma_BdR[2] == 0;
  static FswGuidOrbitState st;
  FswGuidOrbitIn x{};
  FswGuidOrbitOut out;
  const auto is_safe = [](const FswGuidOrbitOut &o, int) {
    return fuzz_nonzero_from(o.sigma_RN, 0, 3) < 0 && fuzz_nonzero_from(o.omega_RN_N, 0, 3) < 0 &&
           fuzz_nonzero_from(o.omega_dot_RN_N, 0, 3) < 0;
  };
  const auto step = [&]() {
    return fuzz_call("guid_orbit", st, out, {FSW_OK, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_guid_orbit_update(&st, &cfg, &x, &out); },
                     fuzz_mask_health<FswGuidOrbitState>, is_safe);
  };
  if (!fuzz_init("guid_orbit", st, cfg, fsw_guid_orbit_check, fsw_guid_orbit_init,
                 [](const FswGuidOrbitState &s) { return s.ready; }, step))
    return 0;
  const double r0[3] = {6.9e6, 1.2e6, -4e5}, v0[3] = {-1.1e3, 6.4e3, 3.9e3};
  for (int k = 0, steps = in.steps(3, 12); k < steps; k++) {
    if (in.op()) fsw_guid_orbit_reset(&st);
    in.reals(x.r_N, 3, r0);
    in.reals(x.v_N, 3, v0);
    x.valid = static_cast<uint8_t>(in.u8() >= 250 ? in.u8() : 1);
    fuzz_trace("r_N", x.r_N, 3);
    fuzz_trace("v_N", x.v_N, 3);
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.sigma_RN, 3) && fuzz_norm3(out.sigma_RN) <= 1.0 + 1e-6,
                 "guid_orbit: sigma not finite or above 1");
    FUZZ_REQUIRE(fuzz_finite(out.omega_RN_N, 3) && fuzz_finite(out.omega_dot_RN_N, 3), "guid_orbit: non-finite rates");
    // h_hat in long double
    long double r[3], v[3], h[3], rn = 0, vn = 0, hn = 0;
    for (int j = 0; j < 3; j++) {
      r[j] = x.r_N[j];
      v[j] = x.v_N[j];
    }
    for (int j = 0; j < 3; j++) {
      rn += r[j] * r[j];
      vn += v[j] * v[j];
    }
    rn = std::sqrt(rn);
    vn = std::sqrt(vn);
    for (int j = 0; j < 3; j++) {
      r[j] /= rn;
      v[j] /= vn;
    }
    h[0] = r[1] * v[2] - r[2] * v[1];
    h[1] = r[2] * v[0] - r[0] * v[2];
    h[2] = r[0] * v[1] - r[1] * v[0];
    for (int j = 0; j < 3; j++) hn += h[j] * h[j];
    hn = std::sqrt(hn);
    const double tol = sizeof(fsw_real) == 8 ? 1e-6 : 1e-1;
    // rates parallel to h_hat: |w - (w . h) h| small against |w|
    for (const fsw_real *w : {out.omega_RN_N, out.omega_dot_RN_N}) {
      long double d = 0, wn = 0, e = 0;
      for (int j = 0; j < 3; j++) d += w[j] * h[j] / hn;
      for (int j = 0; j < 3; j++) {
        const long double c = w[j] - d * h[j] / hn;
        e += c * c;
        wn += static_cast<long double>(w[j]) * w[j];
      }
      FUZZ_REQUIRE(std::sqrt(e) <= tol * std::sqrt(wn) + 1e-300L, "guid_orbit: rate not along h_hat");
    }
    long double d = 0;
    for (int j = 0; j < 3; j++) d += out.omega_RN_N[j] * h[j];
    FUZZ_REQUIRE(d >= 0, "guid_orbit: rate against h");
    if (no_offset) {
      fsw_real C[3][3];
      fsw_mrp_to_dcm(C, out.sigma_RN);
      for (int j = 0; j < 3; j++) {
        const long double want = cfg.variant == FSW_GUID_ORBIT_NADIR ? -r[j] : v[j];
        const fsw_real got = cfg.variant == FSW_GUID_ORBIT_NADIR ? C[2][j] : C[0][j];
        FUZZ_REQUIRE(std::fabs(got - want) <= tol, "guid_orbit: defining axis off (%d: %.17g vs %.17Lg)", j, got, want);
      }
    }
  }
  return 0;
}

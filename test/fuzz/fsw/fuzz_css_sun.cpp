// fsw_css_sun_update: sensor count, normals (exact unit normals in any
// direction, parallel and opposite ones), scales and lit threshold; a
// sequence of readings (nominally those of a Sun direction) and masks.
// OK/W_SINGULAR: a valid heading is a unit vector (|s| = 1 within 1e-9)
// and finite, an invalid one is 0 in mode NONE, OK means WLS and a
// fallback means W_SINGULAR, num_lit <= num_css; errors: the safe output
// (0, not valid, NONE, 0 lit, 0 magnitude).
#include "fsw/css_sun.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswCssSunConfig cfg{};
  cfg.num_css = in.count(6, FSW_MAX_CSS);
  const int n = fuzz_clamp_count(cfg.num_css, FSW_MAX_CSS);
  for (int i = 0; i < n; i++) {
    double nrm[3] = {0, 0, 0};
    nrm[(i / 2) % 3] = (i % 2) ? -1.0 : 1.0;
    if (i >= 6) nrm[(i / 2 + 1) % 3] = 0.5 * (i % 5 - 2);
    const double l = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (double &v : nrm) v /= l;
    in.unit3(cfg.n_hat_B[i], nrm, i > 0 ? cfg.n_hat_B[i - 1] : nullptr);
  }
  in.reals(cfg.scale, n, nullptr, 1.0);
  cfg.lit_threshold = static_cast<fsw_real>(in.real(0.01));
  fuzz_trace("scale", cfg.scale, n);
  fuzz_trace("lit_threshold", &cfg.lit_threshold, 1);
  static FswCssSunState st;
  FswCssSunIn x{};
  FswCssSunOut out;
  const auto is_safe = [](const FswCssSunOut &o, int) {
    return fuzz_nonzero_from(o.sun_hat_B, 0, 3) < 0 && o.sun_mag == 0 && o.sun_valid == 0 && o.num_lit == 0 &&
           o.mode == FSW_CSS_SUN_NONE;
  };
  const auto step = [&]() {
    return fuzz_call("css_sun", st, out, {FSW_OK, FSW_W_SINGULAR, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_css_sun_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswCssSunState>,
                     is_safe);
  };
  if (!fuzz_init("css_sun", st, cfg, fsw_css_sun_check, fsw_css_sun_init,
                 [](const FswCssSunState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_css_sun_reset(&st);
    const double a = 0.3 * k, sun[3] = {0.6 * std::cos(a), 0.6 * std::sin(a), 0.8};
    for (int i = 0; i < n; i++) {
      const double c = cfg.n_hat_B[i][0] * sun[0] + cfg.n_hat_B[i][1] * sun[1] + cfg.n_hat_B[i][2] * sun[2];
      x.reading[i] = static_cast<fsw_real>(in.real((c > 0 ? c : 0.0) * cfg.scale[i]));
    }
    in.avail_mask(x.avail, n);
    fuzz_trace("reading", x.reading, n);
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.sun_hat_B, 3) && std::isfinite(out.sun_mag), "css_sun: non-finite output under %s",
                 fsw_status_name(static_cast<FswStatus>(s)));
    FUZZ_REQUIRE(out.num_lit >= 0 && out.num_lit <= n, "css_sun: num_lit %d", out.num_lit);
    FUZZ_REQUIRE((s == FSW_OK) == (out.mode == FSW_CSS_SUN_WLS), "css_sun: status %s with mode %d",
                 fsw_status_name(static_cast<FswStatus>(s)), out.mode);
    if (out.sun_valid) {
      const double m = fuzz_norm3(out.sun_hat_B);
      FUZZ_REQUIRE(std::fabs(m - 1.0) <= 1e-9, "css_sun: |sun_hat_B| = %.17g in mode %d", m, out.mode);
      FUZZ_REQUIRE(out.mode != FSW_CSS_SUN_NONE && out.num_lit >= 1, "css_sun: valid heading in mode NONE");
    } else {
      FUZZ_REQUIRE(out.sun_valid == 0 && out.mode == FSW_CSS_SUN_NONE && fuzz_nonzero_from(out.sun_hat_B, 0, 3) < 0,
                   "css_sun: invalid heading not 0 in mode NONE (valid %d, mode %d)", out.sun_valid, out.mode);
    }
  }
  return 0;
}

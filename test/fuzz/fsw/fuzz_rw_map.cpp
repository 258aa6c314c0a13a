// fsw_rw_map_update: wheel count and spin axes (including exact unit axes
// that are coplanar, parallel or opposite), control axes, mode and eps_P; a
// sequence of torque requests, wheel speeds and masks.  OK: finite torques,
// 0 on unavailable wheels and beyond num_rw, and the wheels deliver the
// request: [C][Gs_a] u = -[C] Lr (residual within 1e-5 of |[C] Lr|); W_SINGULAR and
// errors: u = 0 (errors: no state change).
#include "fsw/rw_map.h"
#include "fuzz_input.h"

static void mask(FswRwMapState &s)
{
  fuzz_mask_health(s);
  std::memset(&s.work, 0, sizeof s.work);  // scratch of one update
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswRwMapConfig cfg{};
  cfg.mode = in.flag(in.u8() % 2);
  const int n = fuzz_wheel_axes(in, cfg.gs_hat_B, &cfg.num_rw);
  cfg.num_axes = in.count(3, 3);
  static const double I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int j = 0; j < 3; j++) in.unit3(cfg.ctrl_axes_B[j], I3[j], j > 0 ? cfg.ctrl_axes_B[j - 1] : nullptr);
  cfg.eps_P = static_cast<fsw_real>(in.real(1.0));
  fuzz_trace_int("num_axes", cfg.num_axes);
  fuzz_trace("ctrl_axes_B", cfg.ctrl_axes_B[0], 9);
  fuzz_trace("eps_P", &cfg.eps_P, 1);
  static FswRwMapState st;
  FswRwMapIn x{};
  FswRwMapOut out;
  const auto step = [&]() {
    return fuzz_call("rw_map", st, out, {FSW_OK, FSW_W_SINGULAR, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_rw_map_update(&st, &cfg, &x, &out); }, mask,
                     [](const FswRwMapOut &o, int) { return fuzz_nonzero_from(o.u_s, 0, FSW_MAX_RW) < 0; });
  };
  if (!fuzz_init("rw_map", st, cfg, fsw_rw_map_check, fsw_rw_map_init,
                 [](const FswRwMapState &s) { return s.ready; }, step))
    return 0;
  const double L0[3] = {0.01, -0.02, 0.005};
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_rw_map_reset(&st);
    in.reals(x.Lr_B, 3, L0);
    fuzz_speeds(in, x.Omega, n, 100.0);
    in.avail_mask(x.avail, n);
    fuzz_trace("Lr_B", x.Lr_B, 3);
    fuzz_trace("Omega", x.Omega, n);
    const int s = step();
    if (s < 0) continue;
    if (s == FSW_W_SINGULAR) {
      FUZZ_REQUIRE(fuzz_nonzero_from(out.u_s, 0, FSW_MAX_RW) < 0, "rw_map: W_SINGULAR with non-zero torques");
      continue;
    }
    FUZZ_REQUIRE(fuzz_finite(out.u_s, FSW_MAX_RW), "rw_map: non-finite torque under OK");
    FUZZ_REQUIRE(fuzz_nonzero_from(out.u_s, n, FSW_MAX_RW) < 0, "rw_map: torque beyond num_rw");
    FUZZ_REQUIRE(fuzz_unavail_nonzero(out.u_s, x.avail, n) < 0, "rw_map: torque on an unavailable wheel");
    // delivered torque along every control axis: c_j . (sum_a g_i u_i) = -c_j . Lr, within 1e-5 of |[C] Lr|
    // (plus round-off of the delivered terms, round-off of the FSW's own
    // projection c_j . Lr -- which cancels to ~1e-18 for a request nearly
    // normal to c_j -- and a physically-zero floor of 1e-100 N*m)
    long double req[3] = {0, 0, 0}, got[3] = {0, 0, 0}, scale = 0, rn = 0, req_terms[3] = {0, 0, 0};
    for (int j = 0; j < cfg.num_axes; j++) {
      for (int k3 = 0; k3 < 3; k3++) {
        req[j] -= static_cast<long double>(cfg.ctrl_axes_B[j][k3]) * x.Lr_B[k3];
        req_terms[j] += std::fabs(static_cast<long double>(cfg.ctrl_axes_B[j][k3]) * x.Lr_B[k3]);
      }
      for (int i = 0; i < n; i++) {
        if (x.avail[i]) continue;
        long double cg = 0;
        for (int k3 = 0; k3 < 3; k3++) cg += static_cast<long double>(cfg.ctrl_axes_B[j][k3]) * cfg.gs_hat_B[i][k3];
        got[j] += cg * out.u_s[i];
        scale += std::fabs(cg * out.u_s[i]);
      }
      rn += req[j] * req[j];
    }
    for (int j = 0; j < cfg.num_axes; j++) {
      const double err = static_cast<double>(std::fabs(got[j] - req[j]));
      FUZZ_REQUIRE(err <= 1e-5 * static_cast<double>(std::sqrt(rn)) + 1e-9 * static_cast<double>(scale) +
                              1e-12 * static_cast<double>(req_terms[j]) + 1e-100,
                   "rw_map: OK but axis %d gets torque %.17Lg instead of %.17Lg", j, got[j], req[j]);
    }
  }
  return 0;
}

// fsw_mtq_desat_update: wheel axes, inertias, gain, target momentum, torque
// limit, deadband; a sequence of speeds, masks and fields (valid or not,
// tiny, huge, non-finite).  OK/W_SAT/W_SINGULAR: finite outputs, h_w the
// momentum of the available wheels, h_err = h_w - h_target and its norm,
// |tau_req| <= tau_max, tau_req perpendicular to B and equal to m_B x B,
// the unlimited request -k h_err_perp scaled by scale (1 under OK, < 1
// under W_SAT), no request inside the deadband or without a usable field;
// errors: the safe output (every output 0) and no state change.
#include "fsw/mtq_desat.h"
#include "fsw/mtq_map.h"
#include "fuzz_input.h"

namespace {

long double ldot(const long double *a, const long double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

bool all_zero(const FswMtqDesatOut &o)
{
  return fuzz_nonzero_from(o.tau_req_B, 0, 3) < 0 && fuzz_nonzero_from(o.m_B, 0, 3) < 0 &&
         fuzz_nonzero_from(o.h_w_B, 0, 3) < 0 && fuzz_nonzero_from(o.h_err_B, 0, 3) < 0 && o.h_err_norm == 0 &&
         o.scale == 0;
}

void check(const FswMtqDesatConfig &cfg, const FswMtqDesatIn &x, const FswMtqDesatOut &out, int s)
{
  const int n = cfg.num_rw;
  const char *st = fsw_status_name(static_cast<FswStatus>(s));
  const long double eps = FSW_REAL_EPS;
  FUZZ_REQUIRE(fuzz_finite(out.tau_req_B, 3) && fuzz_finite(out.m_B, 3) && fuzz_finite(out.h_w_B, 3) &&
                   fuzz_finite(out.h_err_B, 3) && std::isfinite(out.h_err_norm) && std::isfinite(out.scale),
               "mtq_desat: non-finite output under %s", st);
  long double h[3] = {0, 0, 0}, sc = 0;
  int na = 0;
  for (int i = 0; i < n; i++) {
    if (x.avail[i]) continue;
    const long double w = static_cast<long double>(cfg.J_s[i]) * x.Omega[i];
    for (int k = 0; k < 3; k++) h[k] += w * cfg.gs_hat_B[i][k];
    sc += std::fabs(w);
    na++;
  }
  long double he[3], hs = 0;
  for (int k = 0; k < 3; k++) {
    // a recursive sum of na terms J_i Omega_i g_ik (two roundings each):
    // at most (na + 2) eps sum_i |J_i Omega_i| off (|g_ik| <= 1)
    FUZZ_REQUIRE(std::fabs(out.h_w_B[k] - h[k]) <= (na + 2) * eps * sc + 1e-300L,
                 "mtq_desat: h_w[%d] %.17g, expected %.17Lg", k, out.h_w_B[k], h[k]);
    FUZZ_REQUIRE(out.h_err_B[k] == out.h_w_B[k] - cfg.h_target_B[k], "mtq_desat: h_err[%d] not h_w - h_target", k);
    he[k] = out.h_err_B[k];
    hs += he[k] * he[k];
  }
  const long double hn = std::sqrt(hs);
  FUZZ_REQUIRE(std::fabs(out.h_err_norm - hn) <= 4 * eps * hn + 1e-300L, "mtq_desat: h_err_norm %.17g, |h_err| %.17Lg",
               out.h_err_norm, hn);
  const long double B[3] = {x.B_B[0], x.B_B[1], x.B_B[2]};
  const long double Bn = std::sqrt(ldot(B, B));
  const bool usable = x.B_valid == 1 && Bn >= FSW_MTQ_B_MIN;
  const bool zero_req = fuzz_nonzero_from(out.tau_req_B, 0, 3) < 0 && fuzz_nonzero_from(out.m_B, 0, 3) < 0;
  if (!usable) {
    FUZZ_REQUIRE(s == FSW_W_SINGULAR && zero_req && out.scale == 0, "mtq_desat: no usable field but %s", st);
    return;
  }
  FUZZ_REQUIRE(s != FSW_W_SINGULAR, "mtq_desat: W_SINGULAR with a usable field");
  if (out.h_err_norm <= cfg.h_deadband) {
    FUZZ_REQUIRE(s == FSW_OK && zero_req && out.scale == 0, "mtq_desat: request inside the deadband (%s)", st);
    return;
  }
  FUZZ_REQUIRE(out.scale > 0 && out.scale <= 1 && (s == FSW_W_SAT) == (out.scale < 1),
               "mtq_desat: scale %.17g under %s", out.scale, st);
  const long double t[3] = {out.tau_req_B[0], out.tau_req_B[1], out.tau_req_B[2]};
  const long double m[3] = {out.m_B[0], out.m_B[1], out.m_B[2]};
  const long double tn = std::sqrt(ldot(t, t)), k = cfg.k_desat;
  FUZZ_REQUIRE(tn <= cfg.tau_max * (1 + 4 * eps), "mtq_desat: |tau_req| = %.17Lg above tau_max %.17g", tn,
               cfg.tau_max);
  // the unlimited request -k h_perp, scaled
  const long double hb = ldot(he, B) / ldot(B, B);
  const long double mxB[3] = {m[1] * B[2] - m[2] * B[1], m[2] * B[0] - m[0] * B[2], m[0] * B[1] - m[1] * B[0]};
  const long double tol = 16 * eps * k * hn * out.scale + 1e-300L;
  for (int q = 0; q < 3; q++) {
    const long double want = -k * (he[q] - hb * B[q]) * out.scale;
    FUZZ_REQUIRE(std::fabs(t[q] - want) <= tol, "mtq_desat: tau_req[%d] = %.17Lg, expected %.17Lg", q, t[q], want);
    FUZZ_REQUIRE(std::fabs(mxB[q] - t[q]) <= tol, "mtq_desat: (m x B)[%d] = %.17Lg != tau_req %.17Lg", q, mxB[q],
                 t[q]);
  }
  FUZZ_REQUIRE(std::fabs(ldot(t, B)) <= tol * Bn, "mtq_desat: tau_req . B = %.17Lg not 0", ldot(t, B));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswMtqDesatConfig cfg{};
  const int n = fuzz_wheel_axes(in, cfg.gs_hat_B, &cfg.num_rw);
  in.reals(cfg.J_s, n, nullptr, 0.01);
  cfg.k_desat = static_cast<fsw_real>(in.real(1e-3));
  const double h0[3] = {0.01, 0.0, -0.02};
  in.reals(cfg.h_target_B, 3, h0);
  cfg.tau_max = static_cast<fsw_real>(in.real(1e-3));
  cfg.h_deadband = static_cast<fsw_real>(in.real(1e-3));
  fuzz_trace("J_s", cfg.J_s, n);
  fuzz_trace("k_desat", &cfg.k_desat, 1);
  fuzz_trace("h_target_B", cfg.h_target_B, 3);
  fuzz_trace("tau_max", &cfg.tau_max, 1);
  fuzz_trace("h_deadband", &cfg.h_deadband, 1);
  static FswMtqDesatState st;
  FswMtqDesatIn x{};
  FswMtqDesatOut out;
  const auto step = [&]() {
    return fuzz_call("mtq_desat", st, out, {FSW_OK, FSW_W_SAT, FSW_W_SINGULAR, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_mtq_desat_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswMtqDesatState>,
                     [](const FswMtqDesatOut &o, int) { return all_zero(o); });
  };
  x.B_valid = 1;
  x.B_B[2] = FSW_R(3e-5);
  if (!fuzz_init("mtq_desat", st, cfg, fsw_mtq_desat_check, fsw_mtq_desat_init,
                 [](const FswMtqDesatState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_mtq_desat_reset(&st);
    const double ph = 0.7 * k;
    const double B0[3] = {2.6e-5 * std::cos(ph), 2.6e-5 * std::sin(ph), 1.5e-5};
    fuzz_speeds(in, x.Omega, n, 100.0);
    in.avail_mask(x.avail, n);
    in.reals(x.B_B, 3, B0);
    x.B_valid = static_cast<uint8_t>(in.flag(1));
    fuzz_trace("Omega", x.Omega, n);
    fuzz_trace("B_B", x.B_B, 3);
    fuzz_trace_int("B_valid", x.B_valid);
    const int s = step();
    if (s < 0) continue;
    check(cfg, x, out, s);
  }
  return 0;
}

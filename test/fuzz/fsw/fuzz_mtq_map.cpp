// fsw_mtq_map_update: rod count, axes (exact unit axes in any direction,
// duplicate, opposite and nearly coplanar ones), m_max, duty_max; a
// sequence of torque or dipole requests (first byte: the nominal mode),
// fields (valid or not, tiny, huge, non-finite) and masks.
// OK/W_SAT/W_SINGULAR: finite outputs, |m_cmd_i| <= duty_max m_max_i,
// duty_i = |m_cmd_i|/m_max_i, 0 for unavailable rods and beyond num_mtq,
// scale in (0, 1] (1 under OK, < 1 under W_SAT), tau_ach = m_ach x B
// perpendicular to B, m_ach = G m_cmd, the request delivered (scaled) under
// OK and W_SAT, tau_par the part of tau along B, rods off when the field is
// unusable; errors: the safe output (every output 0) and no state change.
#include "fsw/mtq_map.h"
#include "fuzz_input.h"

namespace {

struct Ld3 {
  long double v[3];
};

Ld3 ld(const fsw_real *a) { return {{a[0], a[1], a[2]}}; }
long double ldot(const Ld3 &a, const Ld3 &b) { return a.v[0] * b.v[0] + a.v[1] * b.v[1] + a.v[2] * b.v[2]; }
long double lnorm(const Ld3 &a) { return std::sqrt(ldot(a, a)); }
Ld3 lcross(const Ld3 &a, const Ld3 &b)
{
  return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2], a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}

bool all_zero(const FswMtqMapOut &o)
{
  return fuzz_nonzero_from(o.m_cmd, 0, FSW_MAX_MTQ) < 0 && fuzz_nonzero_from(o.duty, 0, FSW_MAX_MTQ) < 0 &&
         fuzz_nonzero_from(o.m_ach_B, 0, 3) < 0 && fuzz_nonzero_from(o.tau_ach_B, 0, 3) < 0 &&
         fuzz_nonzero_from(o.tau_par_B, 0, 3) < 0 && o.scale == 0 && !std::signbit(o.scale) && o.rank == 0;
}

// Nominal rod i: x, y, z, then a diagonal set.
void rod_axis(int i, double g[3])
{
  if (i < 3) {
    g[0] = g[1] = g[2] = 0;
    g[i] = 1;
  } else {
    fuzz_pyramid_axis(i, g);
  }
}

void check(const FswMtqMapConfig &cfg, const FswMtqMapIn &x, const FswMtqMapOut &out, int s)
{
  const int n = cfg.num_mtq;
  const char *st = fsw_status_name(static_cast<FswStatus>(s));
  const long double eps = FSW_REAL_EPS;
  FUZZ_REQUIRE(fuzz_finite(out.m_cmd, FSW_MAX_MTQ) && fuzz_finite(out.duty, FSW_MAX_MTQ) &&
                   fuzz_finite(out.m_ach_B, 3) && fuzz_finite(out.tau_ach_B, 3) && fuzz_finite(out.tau_par_B, 3) &&
                   std::isfinite(out.scale),
               "mtq_map: non-finite output under %s", st);
  FUZZ_REQUIRE(fuzz_nonzero_from(out.m_cmd, n, FSW_MAX_MTQ) < 0 && fuzz_nonzero_from(out.duty, n, FSW_MAX_MTQ) < 0,
               "mtq_map: command beyond num_mtq");
  for (int i = 0; i < n; i++) {
    const double lim = static_cast<double>(cfg.duty_max) * cfg.m_max[i];
    FUZZ_REQUIRE(std::fabs(out.m_cmd[i]) <= lim, "mtq_map: |m_cmd[%d]| = %.17g above duty_max m_max = %.17g", i,
                 out.m_cmd[i], lim);
    const double d = std::fabs(out.m_cmd[i]) / cfg.m_max[i];
    FUZZ_REQUIRE(out.duty[i] <= cfg.duty_max && std::fabs(out.duty[i] - d) <= 2 * FSW_REAL_EPS * d,
                 "mtq_map: duty[%d] = %.17g for m_cmd %.17g", i, out.duty[i], out.m_cmd[i]);
    FUZZ_REQUIRE(x.avail[i] == 0 || (out.m_cmd[i] == 0 && out.duty[i] == 0), "mtq_map: unavailable rod %d on", i);
  }
  FUZZ_REQUIRE(out.rank >= 0 && out.rank <= 3, "mtq_map: rank %d", out.rank);
  // field usable?
  const Ld3 B = ld(x.B_B);
  const bool usable = x.B_valid == 1 && lnorm(B) >= FSW_MTQ_B_MIN;
  if (!usable) {
    FUZZ_REQUIRE(s == FSW_W_SINGULAR && all_zero(out), "mtq_map: no usable field but %s with rods not off", st);
    return;
  }
  FUZZ_REQUIRE(out.scale > 0 && out.scale <= 1, "mtq_map: scale %.17g under %s", out.scale, st);
  FUZZ_REQUIRE(s != FSW_OK || out.scale == 1, "mtq_map: OK with scale %.17g", out.scale);
  FUZZ_REQUIRE(s != FSW_W_SAT || out.scale < 1, "mtq_map: W_SAT with scale 1");
  // m_ach = G m_cmd
  Ld3 g = {{0, 0, 0}};
  long double gs = 0;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      g.v[k] += static_cast<long double>(cfg.gt_hat_B[i][k]) * out.m_cmd[i];
      gs += std::fabs(static_cast<long double>(out.m_cmd[i]));
    }
  const Ld3 ma = ld(out.m_ach_B);
  for (int k = 0; k < 3; k++)
    FUZZ_REQUIRE(std::fabs(ma.v[k] - g.v[k]) <= 8 * eps * gs + 1e-300L, "mtq_map: m_ach[%d] %.17Lg != G m_cmd %.17Lg",
                 k, ma.v[k], g.v[k]);
  // tau_ach = m_ach x B, perpendicular to B
  const Ld3 ta = ld(out.tau_ach_B), mxB = lcross(ma, B);
  const long double mb = lnorm(ma) * lnorm(B);
  for (int k = 0; k < 3; k++)
    FUZZ_REQUIRE(std::fabs(ta.v[k] - mxB.v[k]) <= 4 * eps * mb + 1e-300L, "mtq_map: tau_ach[%d] != m_ach x B", k);
  FUZZ_REQUIRE(std::fabs(ldot(ta, B)) <= 8 * eps * mb * lnorm(B) + 1e-300L,
               "mtq_map: tau_ach . B = %.17Lg not 0 (|m||B|^2 = %.17Lg)", ldot(ta, B), mb * lnorm(B));
  // the request, the parallel part and delivery
  Ld3 mref = ld(x.m_req_B), par = {{0, 0, 0}};
  long double slack = 0;  // rounding of the module's own m_B
  if (!x.use_dipole) {
    const Ld3 t = ld(x.tau_B);
    const long double b2 = ldot(B, B), tb = ldot(t, B);
    const Ld3 c = lcross(B, t);
    for (int k = 0; k < 3; k++) {
      mref.v[k] = c.v[k] / b2;
      par.v[k] = tb * B.v[k] / b2;
    }
    slack = 16 * eps * lnorm(t) / lnorm(B);
  }
  const Ld3 tp = ld(out.tau_par_B);
  // tau_B is not read in dipole mode; 1e-300: subnormal products
  const long double ptol = x.use_dipole ? 0 : 8 * eps * lnorm(ld(x.tau_B)) + 1e-300L;
  for (int k = 0; k < 3; k++)
    FUZZ_REQUIRE(std::fabs(tp.v[k] - par.v[k]) <= ptol,
                 "mtq_map: tau_par[%d] = %.17Lg, expected %.17Lg", k, tp.v[k], par.v[k]);
  if (s == FSW_OK || s == FSW_W_SAT) {
    long double e2 = 0;
    for (int k = 0; k < 3; k++) e2 += (ma.v[k] - out.scale * mref.v[k]) * (ma.v[k] - out.scale * mref.v[k]);
    const long double tol = out.scale * (2 * FSW_RESID_TOL * lnorm(mref) + slack) + 16 * eps * gs + 1e-300L;
    FUZZ_REQUIRE(std::sqrt(e2) <= tol, "mtq_map: %s but |m_ach - scale m_B| = %.17Lg > %.17Lg (|m_B| %.17Lg)", st,
                 std::sqrt(e2), tol, lnorm(mref));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  const uint8_t mode = in.u8() % 2;
  FswMtqMapConfig cfg{};
  cfg.num_mtq = in.count(3, FSW_MAX_MTQ);
  const int n = fuzz_clamp_count(cfg.num_mtq, FSW_MAX_MTQ);
  for (int i = 0; i < n; i++) {
    double g[3];
    rod_axis(i, g);
    in.unit3(cfg.gt_hat_B[i], g, i > 0 ? cfg.gt_hat_B[i - 1] : nullptr);
  }
  in.reals(cfg.m_max, n, nullptr, 0.2);
  cfg.duty_max = static_cast<fsw_real>(in.real(0.8));
  fuzz_trace_int("num_mtq", cfg.num_mtq);
  for (int i = 0; i < n; i++) fuzz_trace("gt_hat_B[i]", cfg.gt_hat_B[i], 3);
  fuzz_trace("m_max", cfg.m_max, n);
  fuzz_trace("duty_max", &cfg.duty_max, 1);
  static FswMtqMapState st;
  FswMtqMapIn x{};
  FswMtqMapOut out;
  const auto step = [&]() {
    return fuzz_call("mtq_map", st, out, {FSW_OK, FSW_W_SAT, FSW_W_SINGULAR, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_mtq_map_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswMtqMapState>,
                     [](const FswMtqMapOut &o, int) { return all_zero(o); });
  };
  x.B_valid = 1;
  x.B_B[2] = FSW_R(3e-5);
  if (!fuzz_init("mtq_map", st, cfg, fsw_mtq_map_check, fsw_mtq_map_init,
                 [](const FswMtqMapState &s) { return s.ready; }, step))
    return 0;
  const double tau0[3] = {1e-5, -2e-5, 5e-6}, m0[3] = {0.05, -0.1, 0.02};
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_mtq_map_reset(&st);
    const double ph = 0.7 * k;
    const double B0[3] = {2.6e-5 * std::cos(ph), 2.6e-5 * std::sin(ph), 1.5e-5};
    in.reals(x.tau_B, 3, tau0);
    in.reals(x.m_req_B, 3, m0);
    in.reals(x.B_B, 3, B0);
    x.use_dipole = static_cast<uint8_t>(in.flag(mode));
    x.B_valid = static_cast<uint8_t>(in.flag(1));
    in.avail_mask(x.avail, n);
    fuzz_trace("tau_B", x.tau_B, 3);
    fuzz_trace("m_req_B", x.m_req_B, 3);
    fuzz_trace("B_B", x.B_B, 3);
    fuzz_trace_int("use_dipole", x.use_dipole);
    fuzz_trace_int("B_valid", x.B_valid);
    const int s = step();
    if (s < 0) continue;
    check(cfg, x, out, s);
  }
  return 0;
}

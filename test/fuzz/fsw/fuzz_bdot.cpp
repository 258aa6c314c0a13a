// fsw_bdot_update: variant (first byte), gain, normalize, filter time
// constant, max_missed, per-axis limits, detumble thresholds; a sequence of
// field samples and body rates with their validity flags and time stamps.
// OK/W_SAT/W_RATE: finite outputs, |m_i| <= m_max_B[i], m antiparallel to
// the reported Bdot_B (the direction kept by saturation), and for a fresh
// (not held) dipole m = -scale g Bdot_B with g = k or k/|B|^2 computed here;
// W_SAT iff scale < 1; W_RATE iff the sample was missed, and then m = 0
// unless held; flags 0/1.  Errors: every output 0, no state change.
#include "fsw/bdot.h"
#include "fuzz_input.h"

static bool safe(const FswBdotOut &o, int)
{
  return fuzz_nonzero_from(o.m_B, 0, 3) < 0 && fuzz_nonzero_from(o.Bdot_B, 0, 3) < 0 && o.rate_est == 0 &&
         !std::signbit(o.rate_est) && o.rate_valid == 0 && o.detumbled == 0 && o.t_below == 0 &&
         !std::signbit(o.t_below) && o.scale == 0 && !std::signbit(o.scale) && o.held == 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswBdotConfig cfg{};
  const int variant = in.u8() % 2;
  cfg.variant = in.flag(variant);
  cfg.normalize = in.flag(variant);  // nominal: DERIV unnormalised, GYRO normalised
  cfg.k_bdot = static_cast<fsw_real>(in.real(cfg.normalize == 1 ? 2e-4 : 3e5));
  cfg.tau_f = static_cast<fsw_real>(in.real(2.0));
  cfg.max_missed = in.count(3, 10);
  const double mmax[3] = {0.2, 0.2, 0.1};
  in.reals(cfg.m_max_B, 3, mmax);
  cfg.omega_done = static_cast<fsw_real>(in.real(1e-3));
  cfg.omega_reenter = static_cast<fsw_real>(in.real(3e-3));
  cfg.t_persist = static_cast<fsw_real>(in.real(2.0));
  fuzz_trace_int("variant", cfg.variant);
  fuzz_trace_int("normalize", cfg.normalize);
  fuzz_trace("k tau_f", &cfg.k_bdot, 1);
  fuzz_trace("m_max_B", cfg.m_max_B, 3);
  static FswBdotState st;
  FswBdotIn x{};
  FswBdotOut out;
  const auto step = [&]() {
    return fuzz_call("bdot", st, out,
                     {FSW_OK, FSW_W_SAT, FSW_W_RATE, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_bdot_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswBdotState>, safe);
  };
  if (!fuzz_init("bdot", st, cfg, fsw_bdot_check, fsw_bdot_init, [](const FswBdotState &s) { return s.ready; },
                 step))
    return 0;
  const double eps = sizeof(fsw_real) == sizeof(float) ? 1e-5 : 1e-12;
  const long double tiny = sizeof(fsw_real) == sizeof(float) ? 1e-37L : 1e-300L;  // subnormal products
  uint64_t t = 0;
  const uint64_t period = 500000000ull;
  for (int k = 0, n = in.steps(12, 48); k < n; k++) {
    if (in.op()) fsw_bdot_reset(&st);
    const double a = 0.3 * k;
    const double B0[3] = {3e-5 * std::cos(a), 3e-5 * std::sin(a), 2e-5};
    const double w0[3] = {0.1 * std::sin(0.7 * k), -0.05, 0.08 / (1 + k)};
    in.reals(x.B_B, 3, B0);
    in.reals(x.omega_BN_B, 3, w0);
    x.B_valid = static_cast<uint8_t>(1 - in.avail());  // mostly 1, sometimes 0, rarely invalid
    x.omega_valid = static_cast<uint8_t>(1 - in.avail());
    x.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, period);
    fuzz_trace("B_B", x.B_B, 3);
    fuzz_trace("omega_BN_B", x.omega_BN_B, 3);
    fuzz_trace_int("B_valid", x.B_valid);
    fuzz_trace_int("omega_valid", x.omega_valid);
    fuzz_trace_int("t_ns", static_cast<long long>(x.t_ns));
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.m_B, 3) && fuzz_finite(out.Bdot_B, 3) && std::isfinite(out.rate_est) &&
                     std::isfinite(out.t_below) && std::isfinite(out.scale),
                 "bdot: non-finite output under %s", fsw_status_name(static_cast<FswStatus>(s)));
    FUZZ_REQUIRE(out.detumbled <= 1 && out.held <= 1 && out.rate_valid <= 1, "bdot: a flag is not 0/1");
    FUZZ_REQUIRE(out.rate_est >= 0 && out.t_below >= 0 && out.t_below <= FSW_BDOT_T_PERSIST_MAX,
                 "bdot: rate_est %g or t_below %g out of range", static_cast<double>(out.rate_est),
                 static_cast<double>(out.t_below));
    FUZZ_REQUIRE(out.scale >= 0 && out.scale <= 1, "bdot: scale %g", static_cast<double>(out.scale));
    for (int i = 0; i < 3; i++)
      FUZZ_REQUIRE(std::fabs(out.m_B[i]) <= cfg.m_max_B[i], "bdot: |m_%d| = %g beyond %g", i,
                   static_cast<double>(out.m_B[i]), static_cast<double>(cfg.m_max_B[i]));
    const bool sample = cfg.variant == FSW_BDOT_GYRO ? (x.B_valid == 1 && x.omega_valid == 1) : x.B_valid == 1;
    FUZZ_REQUIRE((s == FSW_W_RATE) == !sample, "bdot: %s but the sample was %s",
                 fsw_status_name(static_cast<FswStatus>(s)), sample ? "present" : "missed");
    if (s == FSW_W_RATE && !out.held)
      FUZZ_REQUIRE(fuzz_nonzero_from(out.m_B, 0, 3) < 0, "bdot: rods not off after max_missed");
    if (sample) {
      FUZZ_REQUIRE(out.held == 0, "bdot: held with a valid sample");
      FUZZ_REQUIRE((s == FSW_W_SAT) == (out.scale < 1) && out.scale > 0, "bdot: %s with scale %g",
                   fsw_status_name(static_cast<FswStatus>(s)), static_cast<double>(out.scale));
      // fresh dipole: m = -scale g Bdot_B (long double, g from this input)
      long double B2 = 0, emax = 0, e[3];
      for (int i = 0; i < 3; i++) B2 += static_cast<long double>(x.B_B[i]) * x.B_B[i];
      const long double g = cfg.normalize ? static_cast<long double>(cfg.k_bdot) / B2 : cfg.k_bdot;
      for (int i = 0; i < 3; i++) {
        e[i] = -static_cast<long double>(out.scale) * g * out.Bdot_B[i];
        emax = std::fmax(emax, std::fabs(e[i]));
      }
      for (int i = 0; i < 3; i++)
        FUZZ_REQUIRE(std::fabs(out.m_B[i] - e[i]) <= 8 * eps * emax + tiny, "bdot: m_%d = %g, law gives %Lg", i,
                     static_cast<double>(out.m_B[i]), e[i]);
    }
    // the direction: m antiparallel to Bdot_B (held dipoles too)
    long double c[3], dot = 0, nm = 0, nb = 0;
    const fsw_real *m = out.m_B, *b = out.Bdot_B;
    c[0] = static_cast<long double>(m[1]) * b[2] - static_cast<long double>(m[2]) * b[1];
    c[1] = static_cast<long double>(m[2]) * b[0] - static_cast<long double>(m[0]) * b[2];
    c[2] = static_cast<long double>(m[0]) * b[1] - static_cast<long double>(m[1]) * b[0];
    for (int i = 0; i < 3; i++) {
      dot += static_cast<long double>(m[i]) * b[i];
      nm += static_cast<long double>(m[i]) * m[i];
      nb += static_cast<long double>(b[i]) * b[i];
    }
    const long double cn = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), mb = std::sqrt(nm) * std::sqrt(nb);
    FUZZ_REQUIRE(dot <= 0 && cn <= 8 * eps * mb + tiny, "bdot: m not antiparallel to Bdot (m.Bdot %Lg, |m x Bdot| %Lg of %Lg)",
                 dot, cn, mb);
  }
  return 0;
}

// fsw_rw_speed_filter_update: limits, inertias, noise margins, k_reject and
// n_recover; a sequence of tachometer samples (with NaN/inf outliers, jumps),
// masks and time stamps.  OK: finite speeds, avail = In.avail OR failed, bits
// only of configured wheels, nothing beyond num_rw; errors: the held good
// speeds with every wheel unavailable and no state change.
// Issue 39: the stale test against a model of its own, kept here: with the
// torque test off, a wheel is newly latched exactly when its finite samples
// repeated bit for bit (memcmp, so -0.0 after +0.0 is no repeat) n_stale
// times in a row.  The decoder's special values include +0.0 and -0.0; the
// seeds signed-zero-* alternate them on wheel 0 (and repeat one sign).
#include <cstring>

#include "fsw/rw_common.h"
#include "fsw/rw_speed_filter.h"
#include "fuzz_input.h"

namespace {
// Bit-for-bit run of repeated finite samples per wheel, as documented.
struct StaleModel {
  fsw_real last[FSW_MAX_RW];
  bool has[FSW_MAX_RW];
  uint32_t run[FSW_MAX_RW];
  void clear()
  {
    for (int i = 0; i < FSW_MAX_RW; i++) has[i] = false, run[i] = 0, last[i] = 0;
  }
  void sample(int i, fsw_real x)
  {
    if (!std::isfinite(x)) return;
    run[i] = (has[i] && std::memcmp(&x, &last[i], sizeof x) == 0) ? run[i] + 1 : 0;
    last[i] = x;
    has[i] = true;
  }
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswRwSpeedFilterConfig cfg{};
  cfg.num_rw = in.count(4, FSW_MAX_RW);
  const int n = fuzz_clamp_count(cfg.num_rw, FSW_MAX_RW);
  in.reals(cfg.u_max, n, nullptr, 0.2);
  in.reals(cfg.J_s, n, nullptr, 0.1);
  in.reals(cfg.noise, n, nullptr, 0.5);
  cfg.k_reject = in.u32(3);
  cfg.n_recover = in.u32(2);
  // issue 14: the latched tests (stale, torque consistency), on now and then
  cfg.n_stale = in.u8() >= 128 ? in.u32(4) : 0u;
  cfg.n_window = in.u8() >= 128 ? in.u32(5) : 0u;
  in.reals(cfg.resid_tol, n, nullptr, 0.3);
  static FswRwSpeedFilterState st;
  FswRwSpeedFilterIn x{};
  FswRwSpeedFilterOut out;
  const auto is_safe = [&](const FswRwSpeedFilterOut &o, int) {
    for (int i = 0; i < FSW_MAX_RW; i++) {
      const fsw_real held = (i < n && st.ready && st.has_good[i]) ? st.Omega_good[i] : 0;
      if (o.Omega[i] != held || o.avail[i] != (i < n ? 1 : 0)) return false;
    }
    return o.rejected == 0 && o.failed == 0 && o.latched == 0;
  };
  const auto step = [&]() {
    return fuzz_call("rw_speed_filter", st, out, {FSW_OK, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_rw_speed_filter_update(&st, &cfg, &x, &out); },
                     fuzz_mask_health<FswRwSpeedFilterState>, is_safe);
  };
  if (!fuzz_init("rw_speed_filter", st, cfg, fsw_rw_speed_filter_check, fsw_rw_speed_filter_init,
                 [](const FswRwSpeedFilterState &s) { return s.ready; }, step))
    return 0;
  uint64_t t = 0, latched_before = 0;
  static StaleModel model;
  model.clear();
  for (int k = 0, steps = in.steps(12, 48); k < steps; k++) {
    if (in.op()) {
      fsw_rw_speed_filter_reset(&st);
      latched_before = 0;
      model.clear();
    }
    fuzz_speeds(in, x.Omega_meas, n, 100.0 + 0.1 * k);
    in.avail_mask(x.avail, n);
    // the torque applied since the previous call: near the limits, any value
    // now and then (beyond 2 u_max or non-finite is bad input); u_valid mostly
    // 1, sometimes 0, rarely neither
    for (int i = 0; i < n; i++) x.u_applied[i] = static_cast<fsw_real>(in.real(0.05));
    {
      const uint8_t v = in.u8();
      x.u_valid = static_cast<uint8_t>(v < 32 ? 0 : (v == 255 ? 2 : 1));
    }
    x.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, 100000000ull);
    fuzz_trace("Omega_meas", x.Omega_meas, n);
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.Omega, FSW_MAX_RW), "rw_speed_filter: non-finite speed under OK");
    FUZZ_REQUIRE(fuzz_nonzero_from(out.Omega, n, FSW_MAX_RW) < 0, "rw_speed_filter: speed beyond num_rw");
    // issue 45: a sample beyond +-FSW_RW_OMEGA_MAX is an outlier, never output
    for (int i = 0; i < n; i++)
      FUZZ_REQUIRE(std::fabs(out.Omega[i]) <= FSW_RW_OMEGA_MAX, "rw_speed_filter: |Omega[%d]| = %.17g beyond the range", i,
                   static_cast<double>(out.Omega[i]));
    for (int i = 0; i < FSW_MAX_RW; i++) {
      const int failed = i < 64 && ((out.failed >> i) & 1u);
      const uint8_t expect = (i < n) ? static_cast<uint8_t>(x.avail[i] | failed) : 0;
      FUZZ_REQUIRE(out.avail[i] == expect, "rw_speed_filter: avail[%d] = %d, In.avail OR failed = %d", i,
                   out.avail[i], expect);
    }
    FUZZ_REQUIRE(n >= 64 || ((out.failed | out.rejected | out.latched) >> n) == 0,
                 "rw_speed_filter: bits beyond num_rw");
    FUZZ_REQUIRE((out.latched & ~out.failed) == 0, "rw_speed_filter: a latched wheel that is not failed");
    FUZZ_REQUIRE((latched_before & ~out.latched) == 0, "rw_speed_filter: a latched wheel came back without reset");
    for (int i = 0; i < n && i < 64; i++) {
      if ((latched_before >> i) & 1u) continue;  // latched: no test runs
      model.sample(i, x.Omega_meas[i]);
      if (cfg.n_window != 0u) continue;  // the torque test may latch it too
      const bool want = cfg.n_stale > 0u && model.run[i] >= cfg.n_stale;
      FUZZ_REQUIRE(want == (((out.latched >> i) & 1u) != 0),
                   "rw_speed_filter: wheel %d latched %d after %u bit-identical repeats (n_stale %u, sample %.17g)", i,
                   static_cast<int>((out.latched >> i) & 1u), model.run[i], cfg.n_stale,
                   static_cast<double>(x.Omega_meas[i]));
    }
    latched_before = out.latched;
  }
  return 0;
}

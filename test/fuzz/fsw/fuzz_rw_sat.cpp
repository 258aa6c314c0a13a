// fsw_rw_sat_update: wheel count, limits and mode; a sequence of torque
// commands and availability masks.  OK/W_SAT: |u_i| <= u_max_i, unavailable
// wheels and entries beyond num_rw exactly 0, OK leaves the torques as
// commanded; errors: u = 0.
#include "fsw/rw_sat.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswRwSatConfig cfg{};
  cfg.mode = in.flag(in.u8() % 2);
  cfg.num_rw = in.count(4, FSW_MAX_RW);
  const int n = fuzz_clamp_count(cfg.num_rw, FSW_MAX_RW);
  in.reals(cfg.u_max, n, nullptr, 0.2);
  fuzz_trace("u_max", cfg.u_max, n);
  static FswRwSatState st;
  FswRwSatIn x{};
  FswRwSatOut out;
  const auto step = [&]() {
    return fuzz_call("rw_sat", st, out, {FSW_OK, FSW_W_SAT, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_rw_sat_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswRwSatState>,
                     [](const FswRwSatOut &o, int) { return fuzz_nonzero_from(o.u_s, 0, FSW_MAX_RW) < 0; });
  };
  if (!fuzz_init("rw_sat", st, cfg, fsw_rw_sat_check, fsw_rw_sat_init,
                 [](const FswRwSatState &s) { return s.ready; }, step))
    return 0;
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_rw_sat_reset(&st);
    fuzz_speeds(in, x.u_s, n, 0.15);
    in.avail_mask(x.avail, n);
    fuzz_trace("u_s", x.u_s, n);
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.u_s, FSW_MAX_RW), "rw_sat: non-finite torque under %d", s);
    FUZZ_REQUIRE(fuzz_nonzero_from(out.u_s, n, FSW_MAX_RW) < 0, "rw_sat: torque beyond num_rw");
    FUZZ_REQUIRE(fuzz_unavail_nonzero(out.u_s, x.avail, n) < 0, "rw_sat: torque on an unavailable wheel");
    for (int i = 0; i < n; i++) {
      FUZZ_REQUIRE(std::fabs(out.u_s[i]) <= cfg.u_max[i], "rw_sat: |u[%d]| = %.17g above u_max %.17g", i,
                   out.u_s[i], cfg.u_max[i]);
      FUZZ_REQUIRE(s != FSW_OK || x.avail[i] || out.u_s[i] == x.u_s[i], "rw_sat: OK but u[%d] changed", i);
    }
  }
  return 0;
}

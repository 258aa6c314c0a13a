// fsw_trq_lpf_update: config (h, omega_c) and a sequence of torques and time
// stamps.  OK/W_RATE: finite output and finite filter memory; errors: zero
// output, no state change.
#include "fsw/trq_lpf.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswTrqLpfConfig cfg;
  cfg.h = in.real(0.5);
  cfg.omega_c = in.real(4.0);
  fuzz_trace("h omega_c", &cfg.h, 2);
  static FswTrqLpfState st;
  FswTrqLpfIn x{};
  FswTrqLpfOut out;
  const auto step = [&]() {
    return fuzz_call("trq_lpf", st, out, {FSW_OK, FSW_W_RATE, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_trq_lpf_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswTrqLpfState>,
                     [](const FswTrqLpfOut &o, int) { return fuzz_nonzero_from(o.LrF_B, 0, 3) < 0; });
  };
  if (!fuzz_init("trq_lpf", st, cfg, fsw_trq_lpf_check, fsw_trq_lpf_init,
                 [](const FswTrqLpfState &s) { return s.ready; }, step))
    return 0;
  const double L0[3] = {0.1, -0.05, 0.02};
  const uint64_t period = static_cast<uint64_t>(std::isfinite(cfg.h) && cfg.h < 1e3 ? cfg.h * 1e9 : 5e8);
  uint64_t t = 0;
  for (int k = 0, n = in.steps(8, 32); k < n; k++) {
    if (in.op()) fsw_trq_lpf_reset(&st);
    in.reals(x.Lr_B, 3, L0);
    x.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, period);
    fuzz_trace("Lr_B", x.Lr_B, 3);
    fuzz_trace_int("t_ns", static_cast<long long>(x.t_ns));
    if (step() >= 0) {
      FUZZ_REQUIRE(fuzz_finite(out.LrF_B, 3), "trq_lpf: non-finite output (%g %g %g) under OK/warning",
                   out.LrF_B[0], out.LrF_B[1], out.LrF_B[2]);
      FUZZ_REQUIRE(fuzz_finite(st.LrF_prev, 3) && fuzz_finite(st.Lr_prev, 3),
                   "trq_lpf: non-finite filter memory after an accepted call");
    }
  }
  return 0;
}

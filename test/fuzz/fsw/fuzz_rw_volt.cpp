// fsw_rw_volt_update: voltage limits, speed-loop gain, limits, inertias and
// the optional outlier gate; a sequence of torques, speeds (with and without
// has_Omega), masks and time stamps.  OK/W_SAT: finite |V_i| <= V_max,
// unavailable wheels and entries beyond num_rw 0, fault bits (gate or
// overflowed correction) only of configured wheels; errors: V = 0, fault = 0 and no state change.
#include "fsw/rw_volt.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  const int variant = in.u8() % 2;  // 0: speed loop, 1: speed loop and outlier gate
  FswRwVoltConfig cfg{};
  cfg.num_rw = in.count(4, FSW_MAX_RW);
  const int n = fuzz_clamp_count(cfg.num_rw, FSW_MAX_RW);
  cfg.V_min = static_cast<fsw_real>(in.real(0.5));
  cfg.V_max = static_cast<fsw_real>(in.real(10.0));
  cfg.K_V = static_cast<fsw_real>(in.real(0.5));
  in.reals(cfg.u_max, n, nullptr, 0.2);
  in.reals(cfg.J_s, n, nullptr, 0.1);
  cfg.gate_rate = in.flag(variant);
  in.reals(cfg.Omega_dot_max, n, nullptr, 50.0);
  fuzz_trace("V_min V_max K_V", &cfg.V_min, 3);
  fuzz_trace("u_max", cfg.u_max, n);
  fuzz_trace("J_s", cfg.J_s, n);
  static FswRwVoltState st;
  FswRwVoltIn x{};
  FswRwVoltOut out;
  const auto step = [&]() {
    return fuzz_call("rw_volt", st, out, {FSW_OK, FSW_W_SAT, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_rw_volt_update(&st, &cfg, &x, &out); }, fuzz_mask_health<FswRwVoltState>,
                     [](const FswRwVoltOut &o, int) { return fuzz_nonzero_from(o.V, 0, FSW_MAX_RW) < 0 && o.fault == 0; });
  };
  if (!fuzz_init("rw_volt", st, cfg, fsw_rw_volt_check, fsw_rw_volt_init,
                 [](const FswRwVoltState &s) { return s.ready; }, step))
    return 0;
  uint64_t t = 0;
  for (int k = 0, steps = in.steps(8, 32); k < steps; k++) {
    if (in.op()) fsw_rw_volt_reset(&st);
    fuzz_speeds(in, x.u_s, n, 0.15);
    fuzz_speeds(in, x.Omega, n, 100.0 + k);
    x.has_Omega = in.flag(1);
    in.avail_mask(x.avail, n);
    x.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, 100000000ull);
    fuzz_trace("u_s", x.u_s, n);
    fuzz_trace("Omega", x.Omega, n);
    fuzz_trace_int("has_Omega", x.has_Omega);
    fuzz_trace_int("t_ns", static_cast<long long>(x.t_ns));
    const int s = step();
    if (s < 0) continue;
    FUZZ_REQUIRE(fuzz_finite(out.V, FSW_MAX_RW), "rw_volt: non-finite voltage under %s",
                 fsw_status_name(static_cast<FswStatus>(s)));
    FUZZ_REQUIRE(fuzz_nonzero_from(out.V, n, FSW_MAX_RW) < 0, "rw_volt: voltage beyond num_rw");
    FUZZ_REQUIRE(fuzz_unavail_nonzero(out.V, x.avail, n) < 0, "rw_volt: voltage on an unavailable wheel");
    for (int i = 0; i < n; i++)
      FUZZ_REQUIRE(std::fabs(out.V[i]) <= cfg.V_max, "rw_volt: |V[%d]| = %.17g above V_max", i, out.V[i]);
    FUZZ_REQUIRE(n >= 64 || (out.fault >> n) == 0, "rw_volt: fault bit beyond num_rw");
  }
  return 0;
}

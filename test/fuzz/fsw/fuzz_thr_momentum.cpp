// fsw_thr_momentum_update: wheel axes and inertias, thresholds, pulse
// torque and timing, thrusters and Isp; a sequence of wheel speeds, masks,
// reported on-times, enable/force flags and time stamps.  OK/W_RATE: finite
// outputs, a known phase, |L_thr| <= L_dump (to the rounding of a unit
// vector), L_thr = 0 unless PULSE, dH_rem = 0 in IDLE, |dH_rem| never
// grows during a dump and stays within |dH_B|, one dump at most 2e6 full
// cycles, counters and prop_total never decrease, prop_dump <= prop_total;
// errors: L_thr = 0, h_w = 0, the report of the last accepted call (zeros
// after reset and for NOT_INIT) and no state change.
#include "fsw/thr_momentum.h"
#include "fuzz_input.h"

namespace {

// The report fields of an output (what an error repeats).
struct Report {
  int phase = 0;
  fsw_real dH_rem_B[3] = {0, 0, 0}, dH_B[3] = {0, 0, 0};
  uint32_t dumps = 0, aborts = 0, pulses = 0;
  fsw_real t_dump = 0, prop_dump = 0, prop_total = 0;
};

Report report_of(const FswThrMomentumOut &o)
{
  Report r;
  r.phase = o.phase;
  for (int k = 0; k < 3; k++) {
    r.dH_rem_B[k] = o.dH_rem_B[k];
    r.dH_B[k] = o.dH_B[k];
  }
  r.dumps = o.dumps;
  r.aborts = o.aborts;
  r.pulses = o.pulses;
  r.t_dump = o.t_dump;
  r.prop_dump = o.prop_dump;
  r.prop_total = o.prop_total;
  return r;
}

bool same_report(const Report &a, const Report &b)
{
  // bitwise: the error path copies the values, it computes nothing
  return std::memcmp(a.dH_rem_B, b.dH_rem_B, sizeof a.dH_rem_B) == 0 &&
         std::memcmp(a.dH_B, b.dH_B, sizeof a.dH_B) == 0 && a.phase == b.phase && a.dumps == b.dumps &&
         a.aborts == b.aborts && a.pulses == b.pulses && std::memcmp(&a.t_dump, &b.t_dump, sizeof a.t_dump) == 0 &&
         std::memcmp(&a.prop_dump, &b.prop_dump, sizeof a.prop_dump) == 0 &&
         std::memcmp(&a.prop_total, &b.prop_total, sizeof a.prop_total) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  FswThrMomentumConfig cfg{};
  const int n = fuzz_wheel_axes(in, cfg.gs_hat_B, &cfg.num_rw);
  in.reals(cfg.J_s, n, nullptr, 0.05);
  // nominal: the speeds below give |h_w| ~ 2.5 N*m*s; Delta_H ~ 0.2 in
  // three pulses of 4 cycles with 2 coast cycles between them
  cfg.h_upper = static_cast<fsw_real>(in.real(2.45));
  cfg.h_lower = static_cast<fsw_real>(in.real(2.3));
  cfg.L_dump = static_cast<fsw_real>(in.real(0.2));
  cfg.t_pulse_max = static_cast<fsw_real>(in.real(0.5));
  cfg.t_min_pulse = static_cast<fsw_real>(in.real(0.125));
  cfg.t_coast = static_cast<fsw_real>(in.real(0.25));
  cfg.dt_cycle = static_cast<fsw_real>(in.real(0.125));
  cfg.num_thr = in.count(2, FSW_MAX_THR);
  const int m = fuzz_clamp_count(cfg.num_thr, FSW_MAX_THR);
  in.reals(cfg.F_max, m, nullptr, 1.0);
  cfg.Isp = static_cast<fsw_real>(in.real(200.0));
  fuzz_trace("J_s", cfg.J_s, n);
  fuzz_trace("h_upper h_lower L_dump t_pulse_max t_min_pulse t_coast dt_cycle", &cfg.h_upper, 7);
  fuzz_trace_int("num_thr", cfg.num_thr);
  fuzz_trace("F_max", cfg.F_max, m);
  fuzz_trace("Isp", &cfg.Isp, 1);

  static FswThrMomentumState st;
  FswThrMomentumIn x{};
  FswThrMomentumOut out;
  Report last;  // report of the last accepted call (zero after reset)
  bool rejected = false;
  const auto step = [&]() {
    return fuzz_call("thr_momentum", st, out, {FSW_OK, FSW_W_RATE, FSW_E_BAD_INPUT, FSW_E_TIME, FSW_E_NOT_INIT},
                     [&] { return fsw_thr_momentum_update(&st, &cfg, &x, &out); },
                     fuzz_mask_health<FswThrMomentumState>, [&](const FswThrMomentumOut &o, int s) {
                       if (fuzz_nonzero_from(o.L_thr_B, 0, 3) >= 0 || fuzz_nonzero_from(o.h_w_B, 0, 3) >= 0 ||
                           o.h_norm != 0 || std::signbit(o.h_norm))
                         return false;
                       const Report want = (s == FSW_E_NOT_INIT || rejected) ? Report() : last;
                       return same_report(report_of(o), want);
                     });
  };
  rejected = true;
  if (!fuzz_init("thr_momentum", st, cfg, fsw_thr_momentum_check, fsw_thr_momentum_init,
                 [](const FswThrMomentumState &s) { return s.ready; }, step))
    return 0;
  rejected = false;

  const double dt_nom = static_cast<double>(cfg.dt_cycle);
  const uint64_t period = dt_nom <= 1.0 ? static_cast<uint64_t>(dt_nom * 1e9) : 125000000u;
  const double L_dump = static_cast<double>(cfg.L_dump);
  const double cap = 2.0 * static_cast<double>(FSW_THR_MOM_CYCLES_MAX) * L_dump * dt_nom;
  bool have_prev = false;  // an accepted call since reset
  uint64_t t = 0;
  for (int k = 0, steps = in.steps(40, 64); k < steps; k++) {
    if (in.op()) {
      fsw_thr_momentum_reset(&st);
      last = Report();
      have_prev = false;
    }
    fuzz_speeds(in, x.Omega, n, 100.0);
    in.avail_mask(x.avail, n);
    in.reals(x.t_on_prev, m, nullptr, 0.05);
    x.enable = static_cast<uint8_t>(in.flag(1));
    x.force_dump = static_cast<uint8_t>(in.flag(0));
    x.t_ns = t = (k == 0) ? in.next_time(0, 0) : in.next_time(t, period);
    fuzz_trace("Omega", x.Omega, n);
    fuzz_trace("t_on_prev", x.t_on_prev, m);
    fuzz_trace_int("enable", x.enable);
    fuzz_trace_int("force_dump", x.force_dump);
    fuzz_trace_int("t_ns", static_cast<long long>(x.t_ns));
    const int s = step();
    if (s < 0) continue;
    fuzz_trace_int("phase", out.phase);
    fuzz_trace("L_thr_B", out.L_thr_B, 3);
    const char *sn = fsw_status_name(static_cast<FswStatus>(s));
    FUZZ_REQUIRE(fuzz_finite(out.L_thr_B, 3) && fuzz_finite(out.dH_rem_B, 3) && fuzz_finite(out.dH_B, 3) &&
                     fuzz_finite(out.h_w_B, 3) && std::isfinite(out.h_norm) && std::isfinite(out.t_dump) &&
                     std::isfinite(out.prop_dump) && std::isfinite(out.prop_total),
                 "thr_momentum: non-finite output under %s", sn);
    FUZZ_REQUIRE(out.phase == FSW_THR_MOM_IDLE || out.phase == FSW_THR_MOM_PULSE || out.phase == FSW_THR_MOM_COAST,
                 "thr_momentum: phase %d", out.phase);
    const double L = fuzz_norm3(out.L_thr_B);
    FUZZ_REQUIRE(L <= L_dump * (1.0 + 8.0 * static_cast<double>(FSW_REAL_EPS)),
                 "thr_momentum: |L_thr| = %.17g above L_dump %.17g", L, L_dump);
    FUZZ_REQUIRE(out.phase == FSW_THR_MOM_PULSE || fuzz_nonzero_from(out.L_thr_B, 0, 3) < 0,
                 "thr_momentum: torque %.17g outside PULSE (phase %d)", L, out.phase);
    FUZZ_REQUIRE(out.phase != FSW_THR_MOM_IDLE || fuzz_nonzero_from(out.dH_rem_B, 0, 3) < 0,
                 "thr_momentum: remaining impulse in IDLE");
    const double rem = fuzz_norm3(out.dH_rem_B), dH = fuzz_norm3(out.dH_B);
    FUZZ_REQUIRE(rem <= dH * (1.0 + 1e-5) + 1e-30, "thr_momentum: |dH_rem| %.17g above |dH| %.17g", rem, dH);
    FUZZ_REQUIRE(dH <= cap * (1.0 + 1e-5), "thr_momentum: |dH| %.17g above the cap %.17g", dH, cap);
    FUZZ_REQUIRE(out.h_norm >= 0 && out.t_dump >= 0 && out.prop_dump >= 0 && out.prop_dump <= out.prop_total,
                 "thr_momentum: h_norm %g t_dump %g prop_dump %g prop_total %g", static_cast<double>(out.h_norm),
                 static_cast<double>(out.t_dump), static_cast<double>(out.prop_dump),
                 static_cast<double>(out.prop_total));
    if (have_prev) {
      FUZZ_REQUIRE(out.prop_total >= last.prop_total, "thr_momentum: prop_total fell from %.17g to %.17g",
                   static_cast<double>(last.prop_total), static_cast<double>(out.prop_total));
      FUZZ_REQUIRE(out.dumps >= last.dumps && out.aborts >= last.aborts, "thr_momentum: a counter fell");
      FUZZ_REQUIRE(out.dumps + out.aborts <= last.dumps + last.aborts + 1u, "thr_momentum: two dumps ended at once");
      if (last.phase != FSW_THR_MOM_IDLE && out.phase != FSW_THR_MOM_IDLE) {
        // the same dump: frozen Delta_H, remaining never grows
        FUZZ_REQUIRE(std::memcmp(out.dH_B, last.dH_B, sizeof out.dH_B) == 0, "thr_momentum: Delta_H changed in a dump");
        FUZZ_REQUIRE(rem <= fuzz_norm3(last.dH_rem_B), "thr_momentum: |dH_rem| grew from %.17g to %.17g",
                     fuzz_norm3(last.dH_rem_B), rem);
        FUZZ_REQUIRE(out.pulses >= last.pulses && out.prop_dump >= last.prop_dump,
                     "thr_momentum: pulses or prop_dump fell in a dump");
      }
    }
    last = report_of(out);
    have_prev = true;
  }
  return 0;
}

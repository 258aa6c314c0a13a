// fsw_thr_map_update: control axes, thruster count, locations, force axes,
// limits, force sign, thresholds, second loop and mode; a sequence of torque
// requests and centre-of-mass locations.  OK/warnings: finite forces,
// nothing beyond num_thr; W_SINGULAR: F = 0; thrusters flagged unavailable
// (issue 14): commanded off (0, or -F_max off-pulsing) under every non-error
// status and left out of the delivered torque; NNLS: lo <= F <= hi and under OK
// the delivered torque [C][D] F equals [C] Lr (+ the all-on torque when
// off-pulsing); min-norm on-pulsing without the second loop: F >= 0 and
// under OK the torque error lies along the min-shift direction [C][D] 1;
// errors: F = 0 and no state change.
#include "fsw/thr_map.h"
#include "fuzz_input.h"

static void mask(FswThrMapState &s)
{
  fuzz_mask_health(s);
  std::memset(&s.work, 0, sizeof s.work);  // scratch of one update
}

// Basilisk thrForceMapping test geometry (8 thrusters)
static const double kR[8][3] = {{-0.86360, -0.82550, 1.79070}, {-0.82550, -0.86360, 1.79070},
                                {0.82550, 0.86360, 1.79070},   {0.86360, 0.82550, 1.79070},
                                {-0.86360, -0.82550, -1.79070}, {-0.82550, -0.86360, -1.79070},
                                {0.82550, 0.86360, -1.79070},  {0.86360, 0.82550, -1.79070}};
static const double kG[8][3] = {{1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {-1, 0, 0},
                                {-1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {1, 0, 0}};

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FuzzIn in(data, size);
  const int v8 = in.u8();
  const int variant = v8 % 4;            // mode x force sign
  const bool with_flags = (v8 & 4) != 0;  // issue 14: availability flags (inputs from before read none)
  FswThrMapConfig cfg{};
  cfg.mode = in.flag(variant & 1);
  cfg.thr_force_sign = in.flag((variant & 2) ? -1 : 1);
  static const double I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int j = 0; j < 3; j++) {
    if (in.u8() >= 240) in.reals(cfg.control_axes_B[j], 3, I3[j]);  // any row, also zero rows
    else in.unit3(cfg.control_axes_B[j], I3[j], j > 0 ? cfg.control_axes_B[j - 1] : nullptr);
  }
  cfg.num_thr = in.count(8, FSW_MAX_THR);
  const int n = fuzz_clamp_count(cfg.num_thr, FSW_MAX_THR);
  for (int i = 0; i < n; i++) {
    in.reals(cfg.r_thr_B[i], 3, kR[i % 8]);
    in.unit3(cfg.gt_hat_B[i], kG[i % 8], i > 0 ? cfg.gt_hat_B[i - 1] : nullptr);
    cfg.F_max[i] = static_cast<fsw_real>(in.real(1.0));
  }
  cfg.ang_err_thresh = static_cast<fsw_real>(in.real(0.0));
  cfg.epsilon = static_cast<fsw_real>(in.real(0.0));
  cfg.use_2nd_loop = in.flag(0);
  fuzz_trace_int("mode", cfg.mode);
  fuzz_trace_int("thr_force_sign", cfg.thr_force_sign);
  fuzz_trace("control_axes_B", cfg.control_axes_B[0], 9);
  for (int i = 0; i < n; i++) {
    fuzz_trace("r_thr_B[i]", cfg.r_thr_B[i], 3);
    fuzz_trace("gt_hat_B[i]", cfg.gt_hat_B[i], 3);
  }
  fuzz_trace("F_max", cfg.F_max, n);
  static FswThrMapState st;
  FswThrMapIn x{};
  FswThrMapOut out;
  const auto step = [&]() {
    return fuzz_call("thr_map", st, out, {FSW_OK, FSW_W_SAT, FSW_W_SINGULAR, FSW_E_BAD_INPUT, FSW_E_NOT_INIT},
                     [&] { return fsw_thr_map_update(&st, &cfg, &x, &out); }, mask,
                     [](const FswThrMapOut &o, int) { return fuzz_nonzero_from(o.F, 0, FSW_MAX_THR) < 0; });
  };
  if (!fuzz_init("thr_map", st, cfg, fsw_thr_map_check, fsw_thr_map_init,
                 [](const FswThrMapState &s) { return s.ready; }, step))
    return 0;
  const double L0[3] = {0.5, -0.3, 0.2}, c0[3] = {0, 0, 0};
  for (int k = 0, steps = in.steps(4, 16); k < steps; k++) {
    if (in.op()) fsw_thr_map_reset(&st);
    in.reals(x.Lr_B, 3, L0);
    in.reals(x.r_CoM_B, 3, c0);
    // issue 14: thrusters flagged unavailable (now and then a flag that is
    // neither 0 nor 1: bad input)
    const bool flags = with_flags && in.u8() >= 128;
    for (int i = 0; i < n; i++) {
      const int b = flags ? in.u8() : 128;
      x.avail[i] = static_cast<uint8_t>(b < 64 ? 1 : (b == 255 ? 2 : 0));
    }
    fuzz_trace("Lr_B", x.Lr_B, 3);
    fuzz_trace("r_CoM_B", x.r_CoM_B, 3);
    const int s = step();
    if (s < 0) continue;
    fuzz_trace("F", out.F, n);
    FUZZ_REQUIRE(fuzz_finite(out.F, FSW_MAX_THR), "thr_map: non-finite force under %s",
                 fsw_status_name(static_cast<FswStatus>(s)));
    FUZZ_REQUIRE(fuzz_nonzero_from(out.F, n, FSW_MAX_THR) < 0, "thr_map: force beyond num_thr");
    if (s == FSW_W_SINGULAR) {  // F = 0, but a flagged thruster keeps its off command (checked below)
      for (int i = 0; i < n; i++)
        FUZZ_REQUIRE(x.avail[i] != 0 || out.F[i] == 0, "thr_map: W_SINGULAR with F[%d] = %.17g", i, out.F[i]);
      FUZZ_REQUIRE(fuzz_nonzero_from(out.F, n, FSW_MAX_THR) < 0, "thr_map: W_SINGULAR with forces beyond num_thr");
    }
    const int sF = cfg.thr_force_sign;
    for (int i = 0; i < n; i++)  // an unavailable thruster is commanded off
      FUZZ_REQUIRE(x.avail[i] == 0 || out.F[i] == (sF > 0 ? 0 : -cfg.F_max[i]),
                   "thr_map: unavailable thruster %d has F = %.17g", i, out.F[i]);
    if (s == FSW_W_SINGULAR) continue;
    for (int i = 0; i < n; i++) {
      const double lo = sF > 0 ? 0.0 : -cfg.F_max[i], hi = sF > 0 ? cfg.F_max[i] : 0.0;
      FUZZ_REQUIRE(cfg.mode != FSW_THR_MAP_NNLS || (out.F[i] >= lo && out.F[i] <= hi),
                   "thr_map: NNLS F[%d] = %.17g outside [%g, %g]", i, out.F[i], lo, hi);
      FUZZ_REQUIRE(sF < 0 || out.F[i] >= 0, "thr_map: on-pulsing F[%d] = %.17g < 0", i, out.F[i]);
    }
    if (s != FSW_OK || (cfg.mode != FSW_THR_MAP_NNLS && (sF < 0 || cfg.use_2nd_loop))) continue;
    // delivered torque about each control axis (terms with F_i = 0 skipped: D may overflow)
    long double r[3] = {0, 0, 0}, v[3] = {0, 0, 0}, req[3] = {0, 0, 0}, scale = 0;
    for (int j = 0; j < st.num_axes; j++) {
      long double Lr[3];
      for (int k3 = 0; k3 < 3; k3++) Lr[k3] = x.Lr_B[k3];
      for (int i = 0; i < n; i++) {
        if (x.avail[i] != 0) continue;  // mapped as absent: no arm, not on
        const long double rel[3] = {static_cast<long double>(cfg.r_thr_B[i][0]) - x.r_CoM_B[0],
                                    static_cast<long double>(cfg.r_thr_B[i][1]) - x.r_CoM_B[1],
                                    static_cast<long double>(cfg.r_thr_B[i][2]) - x.r_CoM_B[2]};
        const fsw_real *g = cfg.gt_hat_B[i];
        const long double d[3] = {rel[1] * g[2] - rel[2] * g[1], rel[2] * g[0] - rel[0] * g[2],
                                  rel[0] * g[1] - rel[1] * g[0]};
        const long double cd = st.C[j][0] * d[0] + st.C[j][1] * d[1] + st.C[j][2] * d[2];
        if (sF < 0)
          for (int k3 = 0; k3 < 3; k3++) {
            Lr[k3] -= cfg.F_max[i] * d[k3];
            scale += std::fabs(cfg.F_max[i] * d[k3]);  // the all-on torque's round-off is in Lbar too
          }
        if (out.F[i] != 0) r[j] += cd * out.F[i];
        scale += std::fabs(cd * out.F[i]);
        v[j] += cd;
      }
      req[j] = st.C[j][0] * Lr[0] + st.C[j][1] * Lr[1] + st.C[j][2] * Lr[2];
      r[j] -= req[j];
      // the FSW's own projection c_j . Lr rounds relative to its terms, and
      // cancels to round-off for a request nearly normal to c_j
      for (int k3 = 0; k3 < 3; k3++) scale += std::fabs(st.C[j][k3] * Lr[k3]);
    }
    long double rn = 0, qn = 0, vv = 0, rv = 0;
    for (int j = 0; j < 3; j++) {
      rn += r[j] * r[j];
      qn += req[j] * req[j];
      vv += v[j] * v[j];
      rv += r[j] * v[j];
    }
    if (cfg.mode != FSW_THR_MAP_NNLS && vv > 0) rn -= rv * rv / vv;  // the min-shift is allowed
    const double err = static_cast<double>(std::sqrt(std::fabs(rn))), want = static_cast<double>(std::sqrt(qn));
    FUZZ_REQUIRE(err <= 1e-6 * want + 1e-9 * static_cast<double>(scale) + 1e-100,
                 "thr_map: OK but the torque error is %.17g for a request of %.17g", err, want);
  }
  return 0;
}

/* trq_lpf: control-torque low-pass filter (docs/fsw/trq_lpf.md, Basilisk
 * lowPassFilterTorqueCommand).  First-order Tustin filter with frequency
 * pre-warping, per axis:
 *   hw = 2 tan(omega_c h / 2); a0 = 2 + hw; a1 = 2 - hw; b0 = b1 = hw
 *   LrF = (b0 Lr + b1 Lr_prev + a1 LrF_prev) / a0
 * DC gain exactly 1; the first call after reset starts from LrF_prev = 0 and
 * Lr_prev = Lr (a deliberate soft start).  h is the assumed call period; a
 * measured period differing from h by more than 1 % gives FSW_W_RATE (the
 * output is still computed with h).  Frames: B.  Units: SI.
 * Safe output (bad input, bad time, not initialised): LrF = 0. */
#ifndef FSW_TRQ_LPF_H
#define FSW_TRQ_LPF_H

#include <stdint.h>

#include "fsw/fsw_clock.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Relative call-period mismatch above which FSW_W_RATE is returned. */
#define FSW_TRQ_LPF_RATE_TOL FSW_R(0.01)

typedef struct {
  fsw_real h;       /* [s]     assumed call period, > 0            */
  fsw_real omega_c; /* [rad/s] cut-off, > 0, with omega_c h < pi    */
} FswTrqLpfConfig;

typedef struct {
  int ready;
  fsw_real a0, a1, b0; /* [-] Tustin coefficients (b1 = b0), from init */
  fsw_real Lr_prev[3];  /* [N*m] previous input  */
  fsw_real LrF_prev[3]; /* [N*m] previous output */
  FswClock clock;       /* [-] previous accepted call (docs/fsw-conventions.md, "Timing") */
  FswHealth health;
} FswTrqLpfState;

typedef struct {
  fsw_real Lr_B[3]; /* [N*m] control torque */
  uint64_t t_ns;    /* [ns]  time stamp     */
} FswTrqLpfIn;

typedef struct {
  fsw_real LrF_B[3]; /* [N*m] filtered control torque */
} FswTrqLpfOut;

/* FSW_OK or FSW_E_CONFIG (h, omega_c non-finite, <= 0, omega_c h >= pi). */
FswStatus fsw_trq_lpf_check(const FswTrqLpfConfig *cfg);
FswStatus fsw_trq_lpf_init(FswTrqLpfState *st, const FswTrqLpfConfig *cfg);
void fsw_trq_lpf_reset(FswTrqLpfState *st);
/* FSW_OK (output finite); FSW_W_RATE (output valid and finite);
 * FSW_E_BAD_INPUT (non-finite Lr, or a finite Lr so large that the filter
 * overflows); FSW_E_TIME (t_ns <= previous); FSW_E_NOT_INIT.  Errors
 * advance no state (filter memory and clock are committed on success). */
FswStatus fsw_trq_lpf_update(FswTrqLpfState *st, const FswTrqLpfConfig *cfg,
                             const FswTrqLpfIn *in, FswTrqLpfOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_TRQ_LPF_H */

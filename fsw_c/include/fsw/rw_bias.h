/* rw_bias: wheel-speed bias management with zero-crossing avoidance.
 * Chooses the desired wheel speeds Omega_des that rw_null (its input
 * Omega_des) then drives the wheels toward through the null space of the
 * available wheels' [Gs_a], so the stack moves no body momentum:
 *   Omega_des = Omega + N lambda,  N (n x k) orthonormal basis of null([Gs_a]),
 *   k = n_avail - rank([Gs_a]);
 *   lambda minimises |Omega + N lambda - Omega_bias|^2 (over the available
 *   wheels), i.e. |lambda - lambda_u|^2 with lambda_u = N^T (Omega_bias - Omega),
 *   subject to, for every available wheel i with side s_i = sign(Omega_i)
 *   (sign(Omega_bias_i) when Omega_i = 0):
 *     b_i <= s_i Omega_des_i           (keep-out: never through zero)
 *     |Omega_des_i| <= FSW_RW_OMEGA_MAX (what rw_null accepts)
 *   with b_i = Omega_keepout, or Omega_keepout + Omega_hyst while the wheel
 *   is "in the band" (hysteresis state, see in_band).
 * k = 1: exact (each constraint is an interval of lambda; intersect, clamp
 * lambda_u).  k > 1: Hildreth's dual coordinate ascent (exact projection of
 * lambda_u onto the constraint polyhedron in the limit; at most
 * FSW_RW_BIAS_MAX_SWEEPS sweeps).  When no lambda keeps every wheel out of
 * its band (k = 0, or the momentum forces a crossing), lambda minimises the
 * number of wheels left in their band (k = 1 exactly; k > 1 best of a few
 * candidates), those wheels are flagged in `unavoidable` and the status is
 * FSW_W_SAT.  The speed bound is never given up.
 * Frames: B.  Units: SI.
 * Safe output (bad input, not initialised): Omega_des_i = Omega_i (the
 * current speeds, so rw_null adds no null torque) for every wheel i <
 * num_rw whose Omega_i is finite and within +-FSW_RW_OMEGA_MAX, else 0;
 * every flag 0, lambda_norm = 0 (all entries 0 when num_rw is outside
 * 1..FSW_MAX_RW). */
#ifndef FSW_RW_BIAS_H
#define FSW_RW_BIAS_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"
#include "fsw/rw_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Sweep budget of the k > 1 solver (each sweep visits every available wheel
 * once); it stops earlier when a sweep changes no multiplier by more than
 * FSW_RW_BIAS_TOL relative. */
#define FSW_RW_BIAS_MAX_SWEEPS 200
/* Relative tolerance of the keep-out test: a wheel counts as kept out when
 * s_i Omega_des_i >= (1 - FSW_RW_BIAS_TOL) b_i.  Far below the band: a wheel
 * that is kept out never changes sign. */
#if FSW_USE_FLOAT
#define FSW_RW_BIAS_TOL FSW_R(1e-4)
#else
#define FSW_RW_BIAS_TOL 1e-7
#endif

typedef struct {
  int num_rw;                       /* [-]     1..FSW_MAX_RW                        */
  fsw_real gs_hat_B[FSW_MAX_RW][3]; /* [-]     (num_rw) spin axes, unit, B          */
  fsw_real Omega_bias[FSW_MAX_RW];  /* [rad/s] (num_rw) preferred speeds, signed,
                                       Omega_keepout < |.| <= FSW_RW_OMEGA_MAX    */
  fsw_real Omega_keepout;           /* [rad/s] > 0: the band |Omega| < Omega_keepout */
  fsw_real Omega_hyst;              /* [rad/s] >= 0: a wheel in the band leaves it
                                       only above Omega_keepout + Omega_hyst;
                                       Omega_keepout + Omega_hyst <=
                                       FSW_RW_OMEGA_MAX / 2                       */
} FswRwBiasConfig;

/* Scratch of one update, kept off the stack (1.7 KiB at FSW_MAX_RW = 36):
 * private by convention, it carries nothing from one call to the next. */
typedef struct {
  fsw_real lo[FSW_MAX_RW], hi[FSW_MAX_RW]; /* keep-out interval of each step   */
  fsw_real b[FSW_MAX_RW];                  /* band edge each wheel must clear  */
  signed char s[FSW_MAX_RW];               /* side of each wheel, +-1          */
  fsw_real lam_u[FSW_MAX_RW], lambda[FSW_MAX_RW], delta[FSW_MAX_RW]; /* solver */
} FswRwBiasScratch;

typedef struct {
  int ready;                    /* [-] 1 after a successful init                  */
  FswRwNullProj proj;           /* [-] [Gs], projector and its mask (~11 KiB)     */
  fsw_real basis[FSW_MAX_RW][FSW_MAX_RW]; /* [-] rows 0..nullity-1: orthonormal
                                   basis of null([Gs_a]) (n entries each), derived
                                   from proj whenever the mask changes           */
  int nullity;                  /* [-] k = rows of basis in use                   */
  uint8_t in_band[FSW_MAX_RW];  /* [-] hysteresis state of each wheel (1 in band) */
  FswRwBiasScratch scratch;     /* [-] work area of update (no state)             */
  FswHealth health;             /* [-] call counters                              */
} FswRwBiasState;

typedef struct {
  fsw_real Omega[FSW_MAX_RW]; /* [rad/s] (num_rw) measured speeds rel. body      */
  uint8_t avail[FSW_MAX_RW];  /* [-]     (num_rw) 0 available, 1 unavailable     */
} FswRwBiasIn;

typedef struct {
  fsw_real Omega_des[FSW_MAX_RW]; /* [rad/s] (num_rw) desired speeds for rw_null;
                                     unavailable wheels: their Omega (0 if it is
                                     not finite or beyond FSW_RW_OMEGA_MAX); 0
                                     beyond num_rw                               */
  uint8_t in_band[FSW_MAX_RW];    /* [-] (num_rw) 1: wheel in its keep-out band
                                     (hysteresis state after this call)          */
  uint8_t unavoidable[FSW_MAX_RW]; /* [-] (num_rw) 1: Omega_des of this available
                                     wheel is inside its band (no admissible
                                     lambda keeps it out)                        */
  uint8_t crossing_unavoidable;   /* [-] 1 if any unavoidable flag is set        */
  int nullity;                    /* [-] k, dimension of the null space used      */
  fsw_real lambda_norm;           /* [rad/s] |lambda| = |Omega_des - Omega|       */
} FswRwBiasOut;

/* FSW_OK, FSW_E_CAPACITY (num_rw), FSW_E_CONFIG (axes, speeds, band). */
FswStatus fsw_rw_bias_check(const FswRwBiasConfig *cfg);
/* check, then the projector and null basis for "all available"; ready = 1. */
FswStatus fsw_rw_bias_init(FswRwBiasState *st, const FswRwBiasConfig *cfg);
/* Clears the hysteresis state (every wheel out of the band); keeps the
 * projector, the basis and the health counters. */
void fsw_rw_bias_reset(FswRwBiasState *st);
/* FSW_OK: every available wheel kept out of its band.  FSW_W_SAT: some
 * wheel cannot be kept out (flagged in unavoidable); the output is the
 * admissible choice with the fewest such wheels.  Both: Gs_a Omega_des =
 * Gs_a Omega to round-off, |Omega_des_i| <= FSW_RW_OMEGA_MAX, hysteresis
 * state updated.  FSW_E_BAD_INPUT (safe output, no state change): a mask
 * entry other than 0/1, or the Omega of an available wheel non-finite or
 * beyond +-FSW_RW_OMEGA_MAX.  FSW_E_NOT_INIT, FSW_E_NULL_ARG (safe output). */
FswStatus fsw_rw_bias_update(FswRwBiasState *st, const FswRwBiasConfig *cfg,
                             const FswRwBiasIn *in, FswRwBiasOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_BIAS_H */

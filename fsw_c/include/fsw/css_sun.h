/* css_sun: Sun heading from coarse sun sensors (CSS) by weighted least squares.
 * Designed in this library (docs/fsw/css_sun.md).
 *
 * Sensor model: sensor i with unit normal n_i (B) and scale k_i > 0 reads
 *   reading_i = k_i * max(0, n_i . s_hat) + noise,
 * so y_i = reading_i / k_i is the cosine of the Sun incidence angle.
 * Sensor i is LIT when it is available and y_i > lit_threshold.
 *
 * Estimate (mode FSW_CSS_SUN_WLS, needs >= 3 lit sensors that span 3-D):
 *   x = argmin sum_lit w_i (n_i . x - y_i)^2,  w_i = y_i (brighter = trusted)
 *     = M^-1 c,  M = sum w_i n_i n_i^T,  c = sum w_i y_i n_i,
 *   solved by a 3x3 Cholesky in fixed order; sun_hat_B = x/|x|.
 * Fallbacks (status FSW_W_SINGULAR, the output is still a unit vector):
 *   FSW_CSS_SUN_TWO: fewer than 3 lit sensors, or M nearly singular (a Cholesky
 *     pivot <= FSW_CSS_SUN_RANK_TOL * max diag, e.g. coplanar normals).  Take
 *     the brightest lit sensor a and the brightest other lit sensor b whose
 *     normal is not parallel to n_a (1 - (n_a.n_b)^2 > FSW_CSS_SUN_RANK_TOL);
 *     x = minimum-norm solution of n_a.x = y_a, n_b.x = y_b (the projection
 *     of the Sun vector on span{n_a, n_b}); sun_hat_B = x/|x|.
 *   FSW_CSS_SUN_ONE: one lit sensor (or all lit normals parallel):
 *     sun_hat_B = n_a of the brightest lit sensor.
 *   FSW_CSS_SUN_NONE: no lit sensor (eclipse, all failed): sun_hat_B = 0 and
 *     sun_valid = 0; guid_sunsafe then commands its search spin.
 * Ties between equally bright sensors: the lowest index wins.
 * Stateless.  Frames: B body.  Units: readings in sensor units, rest [-].
 * Safe output (bad input, init failed): sun_hat_B = 0, sun_valid = 0,
 * mode FSW_CSS_SUN_NONE, num_lit = 0, sun_mag = 0. */
#ifndef FSW_CSS_SUN_H
#define FSW_CSS_SUN_H

#include <stdint.h>

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Capacity: FSW_MAX_CSS (fsw/fsw_config.h, with every capacity). */

/* Relative pivot tolerance deciding that the lit geometry does not span 3-D
 * (WLS) or that two normals are parallel (TWO).  1e-4 means: normals within
 * about 0.01 rad of a common plane (or of each other) are treated as
 * degenerate, where noise would be amplified ~100x along the weak direction. */
#define FSW_CSS_SUN_RANK_TOL FSW_R(1e-4)

/* Unit-vector tolerance for the normals: | |n_i| - 1 | <= tol. */
#if FSW_USE_FLOAT
#define FSW_CSS_SUN_UNIT_TOL FSW_R(1e-6)
#else
#define FSW_CSS_SUN_UNIT_TOL FSW_R(1e-9)
#endif

typedef enum {
  FSW_CSS_SUN_NONE = 0, /* no lit sensor: no heading                        */
  FSW_CSS_SUN_ONE = 1,  /* heading = normal of the brightest lit sensor     */
  FSW_CSS_SUN_TWO = 2,  /* two-sensor minimum-norm (in-plane projection)     */
  FSW_CSS_SUN_WLS = 3   /* full weighted least squares over all lit sensors  */
} FswCssSunMode;

typedef struct {
  int num_css;                       /* [-] sensors, 1..FSW_MAX_CSS             */
  fsw_real n_hat_B[FSW_MAX_CSS][3];  /* [-] (num_css) unit normals, B           */
  fsw_real scale[FSW_MAX_CSS];       /* [reading units] (num_css) reading at
                                        normal incidence, finite, > 0          */
  fsw_real lit_threshold;            /* [-] y_i must exceed this to be lit;
                                        finite, 0 <= lit_threshold < 1; set it
                                        above the noise level (e.g. 0.1)       */
} FswCssSunConfig;

typedef struct {
  int ready;        /* [-] 1 after a successful init */
  FswHealth health; /* [-] call counters             */
} FswCssSunState;

typedef struct {
  fsw_real reading[FSW_MAX_CSS]; /* [reading units] (num_css) raw readings; read
                                    only for available sensors              */
  uint8_t avail[FSW_MAX_CSS];    /* [-] (num_css) FSW_AVAILABLE (0) or
                                    FSW_UNAVAILABLE (1); zero = all available */
} FswCssSunIn;

typedef struct {
  fsw_real sun_hat_B[3]; /* [-] unit Sun heading, B (0 when sun_valid = 0)      */
  fsw_real sun_mag;      /* [-] |x| before normalisation (~1 in WLS mode with
                            correct scales; y_a in ONE mode), telemetry        */
  int sun_valid;         /* [-] 1 if sun_hat_B holds a heading                  */
  int num_lit;           /* [-] lit sensors used for the decision               */
  FswCssSunMode mode;    /* [-] which estimate produced sun_hat_B               */
} FswCssSunOut;

/* FSW_OK; FSW_E_CONFIG (num_css < 1, non-finite value, non-unit normal,
 * scale <= 0, lit_threshold outside [0,1)); FSW_E_CAPACITY (num_css >
 * FSW_MAX_CSS); FSW_E_NULL_ARG. */
FswStatus fsw_css_sun_check(const FswCssSunConfig *cfg);
FswStatus fsw_css_sun_init(FswCssSunState *st, const FswCssSunConfig *cfg);
/* No dynamic state: kept for the uniform module shape. */
void fsw_css_sun_reset(FswCssSunState *st);
/* FSW_OK (WLS); FSW_W_SINGULAR (a fallback mode, see above); with the safe
 * output: FSW_E_BAD_INPUT (NaN/Inf reading of an available sensor, avail
 * entry not 0/1, readings so large that the sums overflow), FSW_E_NOT_INIT,
 * FSW_E_NULL_ARG. */
FswStatus fsw_css_sun_update(FswCssSunState *st, const FswCssSunConfig *cfg,
                             const FswCssSunIn *in, FswCssSunOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_CSS_SUN_H */

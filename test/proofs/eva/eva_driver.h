/* Shared helpers of the Frama-C Eva drivers (docs/eva.md).  Only Frama-C
 * reads these files; the build does not compile them.
 *
 * Each driver calls the check, init and update entries of its module and is
 * analysed twice (tools/eva_check.py):
 *   envelope  eva_main_envelope, Eva's default float model: configuration
 *             values in the ranges check accepts, bounded by the operating
 *             envelope below where the contract only says "finite"; inputs
 *             within the envelope.  Any NaN or infinity that an operation
 *             produces is an alarm.
 *   any       eva_main_any, -warn-special-float none: every finite value
 *             check accepts (up to the largest double), and every real
 *             sensor input finite of any size, NaN or +-infinity.  IEEE
 *             overflow to infinity is allowed; undefined behaviour (signed
 *             overflow, out-of-bounds access, a non-finite or out-of-range
 *             float-to-int conversion, uninitialised read) is an alarm. */
#ifndef EVA_DRIVER_H
#define EVA_DRIVER_H

#include <math.h>
#include <stdint.h>

#include "__fc_builtin.h"

#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#define EVA_MAX 1.7976931348623157e308   /* the largest double            */
#define EVA_TINY 4.9406564584124654e-324 /* the smallest positive double  */
#define EVA_SQ 1e153 /* a component bound whose three squares add up to a finite double */

/* The operating envelope (SI units): a magnitude of any quantity the
 * contract leaves unbounded is at most EVA_ENV, a positive one at least
 * EVA_ENV_MIN. */
#define EVA_ENV 1e6
#define EVA_ENV_MIN 1e-6

/* An assumption about the C library, added to Frama-C's own contract of
 * frexp (which leaves the exponent unbounded): for a finite non-zero double
 * x = r 2^e with 0.5 <= |r| < 1, so e lies in [-1073, 1024] (C11 7.12.6.4
 * and IEEE 754 binary64: 2^-1074 <= |x| < 2^1024). */
/*@ behavior eva_finite_nonzero:
      assumes \is_finite(x) && x != 0.0;
      ensures eva_frexp_exponent: -1073 <= *exp <= 1024;
*/
extern double frexp(double x, int *exp);

static int eva_any_mode; /* 0: envelope, 1: any */

/* A real in [lo, hi]. */
static fsw_real eva_real(fsw_real lo, fsw_real hi) { return Frama_C_double_interval(lo, hi); }

/* A finite real the contract leaves unbounded: |x| <= EVA_ENV, or any. */
static fsw_real eva_finite(void) { return eva_any_mode ? eva_real(-EVA_MAX, EVA_MAX) : eva_real(-EVA_ENV, EVA_ENV); }

/* A positive real the contract leaves unbounded above. */
static fsw_real eva_positive(void) { return eva_any_mode ? eva_real(EVA_TINY, EVA_MAX) : eva_real(EVA_ENV_MIN, EVA_ENV); }

/* A non-negative real the contract leaves unbounded above. */
static fsw_real eva_nonneg(void) { return eva_any_mode ? eva_real(0.0, EVA_MAX) : eva_real(0.0, EVA_ENV); }

/* The lower end of a positive real the contract leaves unbounded below:
 * EVA_ENV_MIN, or (any) the smallest positive double. */
static fsw_real eva_pos_min(void) { return eva_any_mode ? EVA_TINY : EVA_ENV_MIN; }

/* A positive real the contract bounds above by hi only. */
static fsw_real eva_positive_to(fsw_real hi) { return eva_real(eva_pos_min(), hi); }

static int eva_int(int lo, int hi) { return Frama_C_interval(lo, hi); }

/* A real sensor or command input: in the envelope, or (any) finite of any
 * size, NaN, +infinity or -infinity. */
static fsw_real eva_sensor(void)
{
  if (!eva_any_mode) return eva_real(-EVA_ENV, EVA_ENV);
  switch (eva_int(0, 3)) {
  case 0: return (fsw_real)NAN;
  case 1: return (fsw_real)INFINITY;
  case 2: return -(fsw_real)INFINITY;
  default: return eva_real(-EVA_MAX, EVA_MAX);
  }
}

/* Any time stamp. */
static uint64_t eva_u64(void) { return Frama_C_unsigned_long_long_interval(0u, UINT64_MAX); }

static void eva_sensors(fsw_real *v, int n)
{
  int i;
  /*@ loop unroll 64; */
  for (i = 0; i < n; i++) v[i] = eva_sensor();
}

static void eva_reals(fsw_real *v, int n, fsw_real lo, fsw_real hi)
{
  int i;
  /*@ loop unroll 64; */
  for (i = 0; i < n; i++) v[i] = eva_real(lo, hi);
}

/* n unit vectors as check accepts them within tol: each component in
 * [-(1 + tol), 1 + tol] (a superset of the unit vectors). */
static void eva_units(fsw_real (*v)[3], int n, fsw_real tol)
{
  int i;
  /*@ loop unroll 64; */
  for (i = 0; i < n; i++) eva_reals(v[i], 3, -(1.0 + tol), 1.0 + tol);
}

static void eva_positives(fsw_real *v, int n)
{
  int i;
  /*@ loop unroll 64; */
  for (i = 0; i < n; i++) v[i] = eva_positive();
}

static void eva_bytes(uint8_t *v, int n, int lo, int hi)
{
  int i;
  /*@ loop unroll 64; */
  for (i = 0; i < n; i++) v[i] = (uint8_t)eva_int(lo, hi);
}

/* Marks an entry as reached and shows its statuses in the log, where
 * tools/eva_check.py reads them ("entries reached"). */
#define EVA_ENTRY(name, status) Frama_C_show_each_eva_entry_##name((int)(status))

/* The two analyses of a driver whose body is run(). */
#define EVA_MAINS                              \
  void eva_main_envelope(void)                 \
  {                                            \
    eva_any_mode = 0;                          \
    run();                                     \
  }                                            \
  void eva_main_any(void)                      \
  {                                            \
    eva_any_mode = 1;                          \
    run();                                     \
  }

/* Every argument in the drivers is a valid pointer: the library's assertion
 * hook must be unreachable. */
void fsw_assert_failed(const char *file, int line)
{
  (void)file;
  (void)line;
  /*@ assert eva_assert_hook_unreachable: \false; */
}

#endif /* EVA_DRIVER_H */

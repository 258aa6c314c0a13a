/* fsw_status: status codes, health counters and the integrator's assert hook.
 * Errors are negative, warnings positive, FSW_OK is zero.  No module logs,
 * sets errno or keeps a global "last error": each returns a status and
 * counts it in the FswHealth of its own state struct. */
#ifndef FSW_STATUS_H
#define FSW_STATUS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  FSW_OK = 0,
  /* warnings: the output is valid but degraded */
  FSW_W_SINGULAR = 1, /* mapping rank deficient: zero output, documented   */
  FSW_W_SAT = 2,      /* a limit was applied to the output                  */
  FSW_W_RATE = 3,     /* measured call period differs from the configured   */
  /* errors: the module wrote its documented safe output */
  FSW_E_NULL_ARG = -1,    /* programmer error, also reported to FSW_ASSERT    */
  FSW_E_CONFIG = -2,      /* out-of-range or non-finite configuration value   */
  FSW_E_CAPACITY = -3,    /* a count exceeds an FSW_MAX_* capacity            */
  FSW_E_SINGULAR = -4,    /* geometry cannot produce the requested mapping    */
  FSW_E_BAD_INPUT = -5,   /* non-finite or out-of-range runtime input         */
  FSW_E_TIME = -6,        /* time stamp not after the previous one            */
  FSW_E_UNSUPPORTED = -7, /* valid request the library does not implement     */
  FSW_E_NOT_INIT = -8     /* update called on a state that init did not accept */
} FswStatus;

/* Alternative spelling of FSW_E_BAD_INPUT. */
#define FSW_E_INPUT FSW_E_BAD_INPUT

/* Health counters, one set per module state.  Counters saturate at
 * UINT32_MAX instead of wrapping.  `last` is the status of the latest call. */
typedef struct {
  uint32_t bad_input;   /* FSW_E_BAD_INPUT and FSW_E_NULL_ARG returns */
  uint32_t bad_time;    /* FSW_E_TIME returns                          */
  uint32_t saturated;   /* FSW_W_SAT returns                           */
  uint32_t singular;    /* FSW_W_SINGULAR and FSW_E_SINGULAR returns   */
  uint32_t rate;        /* FSW_W_RATE returns                          */
  uint32_t other_error; /* any other error status                      */
  uint32_t calls;       /* every recorded call                         */
  FswStatus last;       /* status of the latest recorded call          */
} FswHealth;

/* Zero every counter, last = FSW_OK. */
void fsw_health_clear(FswHealth *h);

/* Count status `s` in `h` and return `s` unchanged (for `return
 * fsw_health_record(&st->health, FSW_E_TIME);`).  A NULL `h` is ignored. */
FswStatus fsw_health_record(FswHealth *h, FswStatus s);

/* Short constant name of a status ("FSW_OK", ...); "FSW_UNKNOWN" otherwise. */
const char *fsw_status_name(FswStatus s);

/* Non-zero when `s` is an error (negative). */
int fsw_status_is_error(FswStatus s);

/* ---- Assert hook -----------------------------------------------------------
 * The library never aborts.  A violated precondition (a NULL pointer, a
 * programmer error) calls fsw_assert_failed(), which the INTEGRATOR defines:
 * abort in tests, enter safe mode or log and continue in flight.  If the
 * hook returns, the function that asserted returns FSW_E_NULL_ARG (or does
 * nothing for void functions).  Define FSW_ASSERT_DISABLE to compile the
 * checks out of the hook (the NULL checks and their status remain). */
void fsw_assert_failed(const char *file, int line);

#ifdef FSW_ASSERT_DISABLE
#define FSW_ASSERT(cond) ((void)0)
#else
#define FSW_ASSERT(cond)                                                       \
  do {                                                                         \
    if (!(cond)) fsw_assert_failed(__FILE__, __LINE__);                        \
  } while (0)
#endif

#ifdef __cplusplus
}
#endif

#endif /* FSW_STATUS_H */

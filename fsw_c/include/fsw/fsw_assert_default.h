/* fsw_assert_default: a ready-made fsw_assert_failed() (fsw_status.h) for
 * flight builds that have no assertion hook of their own.
 *
 * Link the optional library kestrel::fsw_assert_default (CMake) or
 * -lkestrel_fsw_assert (pkg-config kestrel-fsw-assert-default) next to the
 * flight library and the program links on the first try.  The hook does what
 * flight software can always afford: it counts the violated preconditions and
 * keeps the place of the last one, then returns, so the function that
 * asserted returns FSW_E_NULL_ARG (or does nothing for a void function) and
 * the error shows in the module's health counters.  No I/O, no heap, no
 * abort.  Poll fsw_assert_default_count() from telemetry or a test.
 *
 * A build that wants another behaviour (abort in tests, safe mode in flight)
 * defines its own fsw_assert_failed() and does not link this library.
 *
 * The counters are plain static variables: read them from the thread that
 * runs the flight software (the library is single-threaded). */
#ifndef FSW_ASSERT_DEFAULT_H
#define FSW_ASSERT_DEFAULT_H

#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Violated preconditions since start (or the last reset); saturates at the
 * largest unsigned long. */
unsigned long fsw_assert_default_count(void);

/* Where the last one was: *file (the source file the library was built
 * from, a static string) and *line; NULL and 0 before the first.  Either
 * pointer may be NULL. */
void fsw_assert_default_last(const char **file, int *line);

/* Count back to 0, no last place. */
void fsw_assert_default_reset(void);

#ifdef __cplusplus
}
#endif

#endif /* FSW_ASSERT_DEFAULT_H */

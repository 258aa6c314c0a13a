/* The tests' FSW assert probes, on the library's default hook
 * (fsw/fsw_assert_default.h, kestrel::fsw_assert_default): it counts the
 * failure, remembers where it happened and returns, so the library's own
 * NULL check returns FSW_E_NULL_ARG (which the tests verify).  Every FSW test
 * on every preset thus runs the hook a flight build gets by default.  A test
 * that does not expect an assertion checks kestrel_assert_count() == 0. */
#include "kestrel_test_support.h"

#include "fsw/fsw_assert_default.h"

#include <stddef.h>

unsigned long kestrel_assert_count(void) { return fsw_assert_default_count(); }

const char *kestrel_assert_last_file(void)
{
  const char *file = NULL;
  fsw_assert_default_last(&file, NULL);
  return file;
}

int kestrel_assert_last_line(void)
{
  int line = 0;
  fsw_assert_default_last(NULL, &line);
  return line;
}

void kestrel_assert_reset(void) { fsw_assert_default_reset(); }

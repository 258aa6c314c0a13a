/* The integrator's FSW assert hook, as the tests define it: count the
 * failure and remember where it happened, then return so the library's own
 * NULL check returns FSW_E_NULL_ARG (which the tests verify).  A test that
 * does not expect an assertion checks kestrel_assert_count() == 0. */
#include "kestrel_test_support.h"

#include <stddef.h>

static unsigned long g_count;
static const char *g_file;
static int g_line;

void fsw_assert_failed(const char *file, int line)
{
  g_count++;
  g_file = file;
  g_line = line;
}

unsigned long kestrel_assert_count(void) { return g_count; }
const char *kestrel_assert_last_file(void) { return g_file; }
int kestrel_assert_last_line(void) { return g_line; }
void kestrel_assert_reset(void)
{
  g_count = 0;
  g_file = NULL;
  g_line = 0;
}

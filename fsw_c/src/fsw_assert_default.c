/* The default assertion hook (fsw/fsw_assert_default.h): count, remember the
 * place, return. */
#include "fsw/fsw_assert_default.h"

#include <limits.h>
#include <stddef.h>

static unsigned long s_count;
static const char *s_file;
static int s_line;

void fsw_assert_failed(const char *file, int line)
{
  if (s_count < ULONG_MAX) { s_count++; }
  s_file = file;
  s_line = line;
}

unsigned long fsw_assert_default_count(void) { return s_count; }

void fsw_assert_default_last(const char **file, int *line)
{
  if (file != NULL) { *file = s_file; }
  if (line != NULL) { *line = s_line; }
}

void fsw_assert_default_reset(void)
{
  s_count = 0u;
  s_file = NULL;
  s_line = 0;
}

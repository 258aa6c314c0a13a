/* A flight program without its own fsw_assert_failed(): the default hook of
 * libkestrel_fsw_assert counts the violated precondition, keeps its place
 * and returns, so the call returns FSW_E_NULL_ARG. */
#include <stdio.h>
#include <string.h>

#include "fsw/fsw_assert_default.h"
#include "fsw/fsw_linalg.h"

int main(void)
{
  const fsw_real b[3] = {FSW_R(1.0), FSW_R(0.0), FSW_R(0.0)};
  const char *file = "unset";
  int line = -1;
  FswStatus s;

  fsw_assert_default_last(&file, &line);
  if (fsw_assert_default_count() != 0u || file != NULL || line != 0) {
    printf("before any violation: count %lu, last %s:%d (want 0, none)\n", fsw_assert_default_count(),
           file ? file : "(none)", line);
    return 1;
  }
  s = fsw_minnorm_solve(NULL, NULL, b, 1, 2); /* a programmer error: no output, no matrix */
  fsw_assert_default_last(&file, &line);
  printf("default hook: status %s, count %lu, last at %s:%d\n", fsw_status_name(s), fsw_assert_default_count(),
         file ? file : "(none)", line);
  if (s != FSW_E_NULL_ARG || fsw_assert_default_count() != 1u || file == NULL ||
      strstr(file, "fsw_linalg.c") == NULL || line <= 0)
    return 2;
  fsw_assert_default_reset();
  fsw_assert_default_last(&file, &line);
  return (fsw_assert_default_count() == 0u && file == NULL && line == 0) ? 0 : 3;
}

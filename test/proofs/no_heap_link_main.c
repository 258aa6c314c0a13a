/* Linked with the whole FSW archive and with malloc, calloc, realloc and free
 * wrapped (-Wl,--wrap=...) but no __wrap_* definitions: if any FSW object
 * referred to the heap, this program would not link.  Running it only
 * reports that the link succeeded. */
#include <stdio.h>

#include "fsw/fsw_status.h"

void fsw_assert_failed(const char *file, int line)
{
  (void)file;
  (void)line;
}

int main(void)
{
  /* Touch one symbol so the archive is certainly part of the image. */
  FswHealth h;
  fsw_health_clear(&h);
  puts("whole-archive link without heap: OK");
  return (int)h.calls;
}

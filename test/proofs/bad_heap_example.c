/* Deliberately bad "flight" code: it allocates and keeps mutable static data.
 * The symbol check must reject this archive (test with WILL_FAIL). */
#include <stdlib.h>

double *kestrel_bad_alloc(int n);

double *kestrel_bad_alloc(int n)
{
  static int calls; /* mutable static: forbidden in fsw_c */
  calls++;
  return (double *)malloc((size_t)(n + calls) * sizeof(double));
}

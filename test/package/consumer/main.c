/* Consumer of the installed package: uses the API and the version header. */
#include <math.h>
#include <stdio.h>

#include "fsw/fsw_linalg.h"
#include "fsw/fsw_version.h"

void fsw_assert_failed(const char *file, int line)
{
  (void)file;
  (void)line;
}

int main(void)
{
  fsw_real A[3][FSW_MAX_EFF] = {{FSW_R(1.0), FSW_R(1.0)}};
  const fsw_real b[3] = {FSW_R(2.0), FSW_R(0.0), FSW_R(0.0)};
  fsw_real x[FSW_MAX_EFF];
  FswStatus s = fsw_minnorm_solve(x, FSW_CM3N(A), b, 1, 2);
  printf("kestrel %s consumer: status %d, x = (%g, %g)\n", FSW_VERSION_STRING, (int)s,
         (double)x[0], (double)x[1]);
  /* minimum-norm split of 2 over [1 1] is (1, 1) */
  return (s == FSW_OK && fabs((double)x[0] - 1.0) < 1e-5 && fabs((double)x[1] - 1.0) < 1e-5) ? 0 : 1;
}

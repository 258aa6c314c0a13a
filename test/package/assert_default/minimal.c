/* The smallest flight program: it uses the library and nothing of the hook's
 * own API, so only the hook's --undefined mark brings it in, wherever the
 * hook library stands on the link line. */
#include "fsw/fsw_linalg.h"

int main(void)
{
  fsw_real A[3][FSW_MAX_EFF] = {{FSW_R(1.0), FSW_R(1.0)}};
  const fsw_real b[3] = {FSW_R(2.0), FSW_R(0.0), FSW_R(0.0)};
  fsw_real x[FSW_MAX_EFF];
  return fsw_minnorm_solve(x, FSW_CM3N(A), b, 1, 2) == FSW_OK ? 0 : 1;
}

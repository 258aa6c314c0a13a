// Links the generated one-header-per-TU objects (C99 and C++) and calls a
// function of each core header from C++: an undefined, C++-mangled symbol at
// link time would mean a header lost its extern "C".
#include <cstdio>

#include "fsw/fsw_attitude.h"
#include "fsw/fsw_linalg.h"
#include "fsw/fsw_status.h"
#include "fsw/fsw_vec.h"

extern "C" void fsw_assert_failed(const char*, int) {}

int main()
{
  fsw_real a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3];
  fsw_v3_cross(c, a, b);
  fsw_real C[3][3];
  fsw_mrp_to_dcm(C, c);
  FswHealth h;
  fsw_health_clear(&h);
  fsw_real x[FSW_MAX_EFF];
  fsw_real A[3][FSW_MAX_EFF] = {{1}};
  const fsw_real rhs[3] = {1, 0, 0};
  const FswStatus s = fsw_minnorm_solve(x, A, rhs, 1, 1);
  if (c[2] != 1 || s != FSW_OK || x[0] != 1) {
    std::puts("public headers: linkage check FAILED");
    return 1;
  }
  std::printf("%d public headers compile alone as C99 and C++; public headers: OK\n",
              KESTREL_N_HEADERS);
  return 0;
}

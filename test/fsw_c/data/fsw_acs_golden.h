/* One row of fsw_acs_golden.inc (written by test/fsw_c/gen_fsw_acs_golden.cpp):
 * a cycle's sensor inputs and the outputs recorded for them.  C and C++:
 * replayed by test_fsw_acs_golden and by the Cortex-M4F benchmark
 * bench/target/m4f_cycles.c. */
#ifndef KESTREL_FSW_ACS_GOLDEN_H
#define KESTREL_FSW_ACS_GOLDEN_H

#include <stdint.h>

typedef struct {
  int scenario, cycle, mode;
  uint64_t t_ns;
  double sigma[3], omega[3], css[6], Omega[4];
  int status;
  double Lr[3], u[4], V[4], t_on[8];
} FswAcsGoldenCycle;

#endif

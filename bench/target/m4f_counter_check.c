/* Self-check of the instruction counter (m4f_counter.c) on the hand-counted
 * loop m4f_count_loop: 2 n + 1 instructions for n = 1 .. 400 (every phase
 * of the 40-instruction SysTick tick at both ends, several times) and a few
 * long runs.  Prints the first 10 mismatches and a summary; exit status 1 on
 * any mismatch or when the counter does not run (no -icount).  Run by
 * bench/target/m4f_timing.sh --check (ctest m4f_instruction_counter). */
#include <stdint.h>
#include <stdio.h>

#include "m4f_counter.h"

int main(void)
{
  static const uint32_t long_n[] = {1000u, 4099u, 65536u, 1000003u};
  uint32_t n, checked = 0, bad = 0, naive_min = UINT32_MAX, naive_max = 0;
  size_t k;
  if (m4f_counter_init() != 0) {
    printf("m4f counter self-check: SysTick vernier failed (run under qemu-system-arm -icount shift=0)\n");
    return 1;
  }
  for (n = 1; n <= 400u + 4u; ++n) {
    const uint32_t want = 2u * (n <= 400u ? n : long_n[n - 401u]) + 1u;
    const uint32_t arg = n <= 400u ? n : long_n[n - 401u];
    const uint32_t got = m4f_count(m4f_count_loop, (void *)(uintptr_t)arg);
    checked++;
    if (got != want && ++bad <= 10u) {
      printf("m4f counter self-check: loop n = %lu: %lu instructions counted, %lu executed\n",
             (unsigned long)arg, (unsigned long)got, (unsigned long)want);
    }
  }
  /* the calibration routine itself, 40 times at whatever phase it falls */
  for (k = 0; k < 40u; ++k) {
    const uint32_t got = m4f_count(m4f_count_empty, 0);
    if (got < naive_min) naive_min = got;
    if (got > naive_max) naive_max = got;
  }
  checked++;
  if (naive_min != 1u || naive_max != 1u) bad++;
  printf("m4f counter self-check: %lu of %lu counts exact (m4f_count_loop n = 1..400, 1000, 4099, 65536, "
         "1000003; m4f_count_empty x 40: %lu..%lu)\n",
         (unsigned long)(checked - bad), (unsigned long)checked, (unsigned long)naive_min, (unsigned long)naive_max);
  return bad == 0u ? 0 : 1;
}

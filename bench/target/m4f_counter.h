/* Exact instruction counts on the Cortex-M4F under QEMU -icount shift=0
 * (docs/performance.md, "Flight cycle on the target").  Application code of
 * the timing benchmark, not flight code. */
#ifndef KESTREL_M4F_COUNTER_H
#define KESTREL_M4F_COUNTER_H

#include <stdint.h>

typedef void (*M4fCountFn)(void *arg);

/* Starts SysTick (CPU clock, no interrupt, reload 2^24 - 1) and calibrates
 * the fixed cost of a measurement against m4f_count_empty.  Returns 0, or
 * -1 when the counter does not run as expected (no -icount, no SysTick). */
int m4f_counter_init(void);

/* Instructions executed by fn(arg), from its first instruction to its
 * return inclusive; UINT32_MAX when the vernier failed. */
uint32_t m4f_count(M4fCountFn fn, void *arg);

/* Sorts v[0..n) in ascending order (insertion sort: a few hundred samples). */
void m4f_sort(uint32_t *v, uint32_t n);

/* The hand-countable routines (m4f_counter_asm.S): `bx lr`, 1 instruction;
 * `1: subs r0, r0, #1; bne 1b; bx lr` with r0 = n (n >= 1, passed as
 * (void *)(uintptr_t)n), 2 n + 1 instructions. */
void m4f_count_empty(void *unused);
void m4f_count_loop(void *n);

#endif

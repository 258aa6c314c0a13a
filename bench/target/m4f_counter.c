/* Exact instruction counts from SysTick under QEMU -icount shift=0.
 *
 * With -icount shift=0 QEMU's virtual clock advances 1 ns per executed
 * instruction, and SysTick with its CPU clock source (25 MHz on the
 * mps2-an386 board) decrements once per 40 ns: one tick per 40 instructions.
 * A plain read therefore has a granularity of 40 instructions.  The vernier
 * (m4f_counter_asm.S) recovers the phase of a read inside its tick: it reads
 * again every 41 instructions, so the phase moves by one instruction per
 * read, and the read at which two successive values differ by 2 ticks
 * tells where the first read sat.  A read's time in instructions is then
 * 40 ticks + phase, exact; a measurement is the difference of the times of
 * a vernier before and one after the call, minus the vernier's own length
 * (41 per read) and the fixed cost of the call sequence, which
 * m4f_counter_init calibrates on m4f_count_empty (1 instruction). */
#include "m4f_counter.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SYST_RELOAD 0x00FFFFFFu
#define TICK_INSNS 40u  /* instructions per SysTick tick: 25 MHz at 1 ns per instruction */
#define VERNIER_STEP 41u /* instructions between two vernier reads */

uint32_t m4f_vernier(uint32_t *first);

static uint32_t g_fixed; /* instructions of the measuring sequence itself */

/* time of a vernier's first read in instructions since the last reload */
static uint32_t read_time(uint32_t first, uint32_t j)
{
  return (SYST_RELOAD - first) * TICK_INSNS + (TICK_INSNS - j) % TICK_INSNS;
}

static uint32_t measure_raw(M4fCountFn fn, void *arg) __attribute__((noinline));
static uint32_t measure_raw(M4fCountFn fn, void *arg)
{
  uint32_t a = 0, b = 0, ja, jb;
  /* keep the whole measurement inside one reload period: measured calls
   * are far shorter than half of it (2^23 ticks, 3.4e8 instructions) */
  if (SYST_CVR < (SYST_RELOAD >> 1)) {
    SYST_CVR = 0u; /* any write clears it; the next tick reloads */
    while (SYST_CVR < (SYST_RELOAD >> 1)) {
    }
  }
  ja = m4f_vernier(&a);
  fn(arg);
  jb = m4f_vernier(&b);
  if (ja == 0u || jb == 0u) return UINT32_MAX;
  return read_time(b, jb) - read_time(a, ja) - VERNIER_STEP * ja;
}

int m4f_counter_init(void)
{
  uint32_t r;
  SYST_CSR = 0u;
  SYST_RVR = SYST_RELOAD;
  SYST_CVR = 0u;
  SYST_CSR = 5u; /* ENABLE | CLKSOURCE = processor clock, TICKINT = 0 */
  r = measure_raw(m4f_count_empty, 0);
  if (r == UINT32_MAX || r < 1u) return -1;
  g_fixed = r - 1u;
  return 0;
}

uint32_t m4f_count(M4fCountFn fn, void *arg)
{
  const uint32_t r = measure_raw(fn, arg);
  return r == UINT32_MAX ? r : r - g_fixed;
}

void m4f_sort(uint32_t *v, uint32_t n)
{
  uint32_t i, j;
  for (i = 1; i < n; ++i) {
    const uint32_t x = v[i];
    for (j = i; j > 0 && v[j - 1] > x; --j) v[j] = v[j - 1];
    v[j] = x;
  }
}

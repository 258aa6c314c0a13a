/* fsw_clock: the shared timing step of docs/fsw-conventions.md, "Timing". */
#include "fsw/fsw_clock.h"

#include <stddef.h>

FswStatus fsw_clock_dt(const FswClock *clk, uint64_t t_ns, fsw_real *dt)
{
  FSW_ASSERT(clk != NULL && dt != NULL);
  if (dt != NULL) { *dt = FSW_R(0.0); }
  if (clk == NULL || dt == NULL) { return FSW_E_NULL_ARG; }
  if (!clk->has_prev) { return FSW_OK; }
  if (t_ns <= clk->t_prev_ns) { return FSW_E_TIME; }
  /* docs/fsw-conventions.md, "Timing": dt = (real)(t_ns - t_prev_ns) * 1e-9 */
  *dt = fsw_clock_ns_to_s(t_ns - clk->t_prev_ns);
  return FSW_OK;
}

void fsw_clock_commit(FswClock *clk, uint64_t t_ns)
{
  FSW_ASSERT(clk != NULL);
  if (clk == NULL) { return; }
  clk->has_prev = 1;
  clk->t_prev_ns = t_ns;
}

void fsw_clock_reset(FswClock *clk)
{
  FSW_ASSERT(clk != NULL);
  if (clk == NULL) { return; }
  clk->has_prev = 0;
  clk->t_prev_ns = 0u;
}

fsw_real fsw_clock_ns_to_s(uint64_t d_ns)
{
#if FSW_USE_FLOAT
  /* Above 32 bits: shift right until 32 are left (the top one set), OR-ing
   * every bit shifted out into the lowest kept one.  Rounding the 32 bits to
   * float's 24 then decides as rounding all 64 would (that bit lies below
   * the rounding bit, and it is set exactly when the dropped part is not
   * zero), and the scaling by 2^k is exact. */
  uint64_t m = d_ns;
  uint32_t sticky = 0u;
  int k = 0;
  fsw_real f;
  while ((m >> 32) != 0u) {
    sticky |= (uint32_t)(m & 1u);
    m >>= 1;
    k++;
  }
  f = (fsw_real)((uint32_t)m | sticky);
  for (; k > 0; k--) { f *= FSW_R(2.0); }
  return f * FSW_R(1e-9);
#else
  return (fsw_real)d_ns * FSW_R(1e-9);
#endif
}

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
  *dt = (fsw_real)(t_ns - clk->t_prev_ns) * FSW_R(1e-9);
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

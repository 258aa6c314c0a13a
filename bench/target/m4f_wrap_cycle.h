/* The call of fsw_acs_cycle that a replay counts (docs/performance.md,
 * "Flight cycle on the target"): the program links with
 * -Wl,--wrap=fsw_acs_cycle, its __wrap_fsw_acs_cycle fills an M4fCycleCall
 * and counts m4f_run_real_cycle with m4f_count.  Application code of the
 * timing benchmark, not flight code. */
#ifndef KESTREL_M4F_WRAP_CYCLE_H
#define KESTREL_M4F_WRAP_CYCLE_H

#include "fsw/fsw_acs.h"

FswStatus __real_fsw_acs_cycle(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                               const FswAcsCmdMsg *cmd, FswAcsActuatorMsg *act, FswAcsHealthMsg *h);
FswStatus __wrap_fsw_acs_cycle(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                               const FswAcsCmdMsg *cmd, FswAcsActuatorMsg *act, FswAcsHealthMsg *h);

typedef struct {
  FswAcsState *st;
  const FswAcsConfig *cfg;
  const FswAcsSensorMsg *sens;
  const FswAcsCmdMsg *cmd;
  FswAcsActuatorMsg *act;
  FswAcsHealthMsg *h;
  FswStatus status;
} M4fCycleCall;

/* an M4fCountFn: the cycle itself, its status into the call */
static inline void m4f_run_real_cycle(void *p)
{
  M4fCycleCall *c = (M4fCycleCall *)p;
  c->status = __real_fsw_acs_cycle(c->st, c->cfg, c->sens, c->cmd, c->act, c->h);
}

#endif

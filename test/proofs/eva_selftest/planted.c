/* Planted faults for tools/eva_check.py --self-test: the check must refuse
 * this driver (an out-of-bounds write, an entry never reached) and the stale
 * record of alarms.txt here.
 * eva-sources: fsw_status.c */
#include "eva_driver.h"

static FswStatus planted_update(int i)
{
  int a[4];
  a[i] = 1; /* i may be 4: out of bounds */
  return a[i] == 1 ? FSW_OK : FSW_E_BAD_INPUT;
}

static void run(void)
{
  EVA_ENTRY(update, planted_update(eva_int(0, 4)));
  if (eva_int(0, 0) == 0) return;
  EVA_ENTRY(never, FSW_OK); /* dead: must be reported as never reached */
}

EVA_MAINS

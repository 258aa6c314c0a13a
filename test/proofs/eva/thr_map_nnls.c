/* Eva driver: thr_map in its bounded (NNLS) mode (docs/fsw/thr_map.md,
 * docs/eva.md); the minimum-norm mode is thr_map.c.
 * eva-sources: thr_map.c fsw_linalg.c fsw_vec.c fsw_status.c
 * eva-options: -eva-auto-loop-unroll 36 -eva-slevel 0 */
#include "thr_map_common.h"

static void run(void) { thr_map_run(FSW_THR_MAP_NNLS); }

EVA_MAINS

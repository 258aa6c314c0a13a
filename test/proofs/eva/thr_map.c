/* Eva driver: thr_map in its minimum-norm mode (docs/fsw/thr_map.md,
 * docs/eva.md); the bounded mode is thr_map_nnls.c.
 * eva-sources: thr_map.c fsw_linalg.c fsw_vec.c fsw_status.c */
#include "thr_map_common.h"

static void run(void) { thr_map_run(FSW_THR_MAP_MIN_NORM); }

EVA_MAINS

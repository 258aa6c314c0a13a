/* rw_map_internal: the torque mapping of fsw_rw_map_update for an input
 * already checked, for the application (fsw_acs), whose cycle checks the
 * wheels' availability flags and speeds before any stage runs.  Not a
 * public header. */
#ifndef FSW_RW_MAP_INTERNAL_H
#define FSW_RW_MAP_INTERNAL_H

#include "fsw/rw_map.h"

#ifdef __cplusplus
extern "C" {
#endif

/* fsw_rw_map_update without its argument checks and its checks of the
 * wheels, the input's members (FswRwMapIn's Lr_B, Omega and avail) read in
 * place from the caller's arrays: the same output, status, scratch and
 * health record for non-NULL arguments and an input whose num_rw flags are
 * each FSW_AVAILABLE or FSW_UNAVAILABLE and (POWER mode) whose available
 * wheels' speeds are finite; anything else is the caller's error (Omega is
 * read in POWER mode only).  A state that is not ready gives
 * FSW_E_NOT_INIT and a non-finite Lr_B FSW_E_BAD_INPUT, as
 * fsw_rw_map_update does. */
FswStatus fsw_rw_map_torques(FswRwMapState *st, const FswRwMapConfig *cfg, const fsw_real Lr_B[3],
                             const fsw_real Omega[FSW_MAX_RW], const uint8_t avail[FSW_MAX_RW],
                             FswRwMapOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_MAP_INTERNAL_H */

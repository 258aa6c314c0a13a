/* rw_sat_internal: the saturation of fsw_rw_sat_update for an input already
 * checked, for the application (fsw_acs), whose cycle checks the wheels'
 * availability flags before any stage runs and whose mapping gives finite
 * torques.  Not a public header. */
#ifndef FSW_RW_SAT_INTERNAL_H
#define FSW_RW_SAT_INTERNAL_H

#include "fsw/rw_sat.h"

#ifdef __cplusplus
extern "C" {
#endif

/* fsw_rw_sat_update without its argument checks and its checks of the
 * input: u_out gets what fsw_rw_sat_update's out->u_s gets (every entry, 0
 * beyond num_rw) and the status and health record are the same, for
 * non-NULL arguments, num_rw flags in avail each FSW_AVAILABLE or
 * FSW_UNAVAILABLE and finite u_in of the available wheels; anything else
 * is the caller's error.  A state that is not ready gives FSW_E_NOT_INIT,
 * as fsw_rw_sat_update does.  u_in and u_out may not overlap. */
FswStatus fsw_rw_sat_limit(FswRwSatState *st, const FswRwSatConfig *cfg, const fsw_real u_in[FSW_MAX_RW],
                           const uint8_t avail[FSW_MAX_RW], fsw_real u_out[FSW_MAX_RW]);

#ifdef __cplusplus
}
#endif

#endif /* FSW_RW_SAT_INTERNAL_H */

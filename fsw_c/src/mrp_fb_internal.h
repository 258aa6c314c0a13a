/* mrp_fb_internal: the control law of fsw_mrp_fb_update for an input
 * already checked, for the application (fsw_acs), whose cycle hands the
 * law a guidance message and wheel speeds that are finite by construction
 * and availability flags it has checked.  Not a public header. */
#ifndef FSW_MRP_FB_INTERNAL_H
#define FSW_MRP_FB_INTERNAL_H

#include "fsw/mrp_fb.h"

#ifdef __cplusplus
extern "C" {
#endif

/* fsw_mrp_fb_update without its argument and input checks, the input's
 * members (FswMrpFbIn's guid, t_ns, Omega and rw_avail) read in place from
 * the caller's objects: the same output, status, state and health record
 * for non-NULL arguments and an input that passes those checks (every
 * guidance component finite; each of the num_rw flags FSW_AVAILABLE or
 * FSW_UNAVAILABLE, the speed of every available wheel finite); anything
 * else is the caller's error.  A state that is not ready gives
 * FSW_E_NOT_INIT, and a time stamp that does not advance FSW_E_TIME, as
 * fsw_mrp_fb_update does. */
FswStatus fsw_mrp_fb_torque(FswMrpFbState *st, const FswMrpFbConfig *cfg, const FswAttGuid *guid,
                            uint64_t t_ns, const fsw_real Omega[FSW_MAX_RW],
                            const uint8_t rw_avail[FSW_MAX_RW], FswMrpFbOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_MRP_FB_INTERNAL_H */

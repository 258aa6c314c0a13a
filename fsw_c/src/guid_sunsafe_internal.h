/* guid_sunsafe_internal: the guidance of fsw_guid_sunsafe_update for an
 * input already checked, for the application (fsw_acs), whose cycle hands
 * it the Sun sensors' heading (finite by construction) and the body rate it
 * has checked.  Not a public header. */
#ifndef FSW_GUID_SUNSAFE_INTERNAL_H
#define FSW_GUID_SUNSAFE_INTERNAL_H

#include "fsw/guid_sunsafe.h"

#ifdef __cplusplus
extern "C" {
#endif

/* fsw_guid_sunsafe_update without its argument and input checks: the same
 * output, status and health record for non-NULL arguments and an input
 * that passes those checks (sun_B and omega_BN_B finite); anything else is
 * the caller's error.  A state that is not ready gives FSW_E_NOT_INIT, and
 * a rate output that overflows FSW_E_BAD_INPUT, as fsw_guid_sunsafe_update
 * does. */
FswStatus fsw_guid_sunsafe_point(FswGuidSunsafeState *st, const FswGuidSunsafeConfig *cfg,
                                 const FswGuidSunsafeIn *in, FswGuidSunsafeOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_GUID_SUNSAFE_INTERNAL_H */

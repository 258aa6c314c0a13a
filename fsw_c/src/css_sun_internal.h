/* css_sun_internal: the estimate of fsw_css_sun_update for an input already
 * checked, for the application (fsw_acs), whose cycle checks the same
 * readings and flags before any stage runs.  Not a public header. */
#ifndef FSW_CSS_SUN_INTERNAL_H
#define FSW_CSS_SUN_INTERNAL_H

#include "fsw/css_sun.h"

#ifdef __cplusplus
extern "C" {
#endif

/* fsw_css_sun_update without its argument and input checks, the input's
 * readings and flags (FswCssSunIn's reading and avail) read in place from
 * the caller's arrays: the same output, status and health record for
 * non-NULL arguments and an input that passes those checks (each of the
 * num_css flags FSW_AVAILABLE or FSW_UNAVAILABLE, every available reading
 * finite); anything else is the caller's error.  A state that is not ready
 * gives FSW_E_NOT_INIT as fsw_css_sun_update does. */
FswStatus fsw_css_sun_estimate(FswCssSunState *st, const FswCssSunConfig *cfg,
                               const fsw_real reading[FSW_MAX_CSS], const uint8_t avail[FSW_MAX_CSS],
                               FswCssSunOut *out);

#ifdef __cplusplus
}
#endif

#endif /* FSW_CSS_SUN_INTERNAL_H */

/* fsw_status_inline: the status test and the record of a good call of
 * fsw/fsw_status.h as static inline functions, for the modules of the flight
 * cycle.  Not a public header.  Each gives what the out-of-line function in
 * fsw_status.c gives for the same arguments; the call is gone.  The public
 * functions stay in fsw_status.c with the same names and signatures (the
 * library's API and ABI do not change). */
#ifndef FSW_STATUS_INLINE_H
#define FSW_STATUS_INLINE_H

#include <stdint.h>

#include "fsw/fsw_status.h"

/* fsw_status_is_error(s): 1 for an error (a negative code), 0 for FSW_OK
 * and the warnings. */
static inline int fsw_status_is_error_i(FswStatus s) { return (int)s < 0; }

/* fsw_health_record(h, FSW_OK) for a non-NULL h: the call counted
 * (saturating at UINT32_MAX without a branch: calls / UINT32_MAX is 1 only
 * for calls = UINT32_MAX) and FSW_OK the last status; no other counter
 * moves for FSW_OK. */
static inline FswStatus fsw_health_record_ok_i(FswHealth *h)
{
  h->calls += 1u - (h->calls / UINT32_MAX);
  h->last = FSW_OK;
  return FSW_OK;
}

#endif /* FSW_STATUS_INLINE_H */

/* fsw_status: health counters and status names. */
#include "fsw/fsw_status.h"
#include "fsw_status_inline.h"

#include <stddef.h>

static void bump(uint32_t *c)
{
  if (*c < UINT32_MAX) { (*c)++; }
}

void fsw_health_clear(FswHealth *h)
{
  FSW_ASSERT(h != NULL);
  if (h == NULL) { return; }
  h->bad_input = 0u;
  h->bad_time = 0u;
  h->saturated = 0u;
  h->singular = 0u;
  h->rate = 0u;
  h->other_error = 0u;
  h->calls = 0u;
  h->last = FSW_OK;
}

FswStatus fsw_health_record(FswHealth *h, FswStatus s)
{
  if (h == NULL) { return s; }
  bump(&h->calls);
  h->last = s;
  switch (s) {
  case FSW_OK: break;
  case FSW_W_SINGULAR:
  case FSW_E_SINGULAR: bump(&h->singular); break;
  case FSW_W_SAT: bump(&h->saturated); break;
  case FSW_W_RATE: bump(&h->rate); break;
  case FSW_E_NULL_ARG:
  case FSW_E_BAD_INPUT: bump(&h->bad_input); break;
  case FSW_E_TIME: bump(&h->bad_time); break;
  case FSW_E_CONFIG:
  case FSW_E_CAPACITY:
  case FSW_E_UNSUPPORTED:
  case FSW_E_NOT_INIT:
  default: bump(&h->other_error); break;
  }
  return s;
}

const char *fsw_status_name(FswStatus s)
{
  switch (s) {
  case FSW_OK: return "FSW_OK";
  case FSW_W_SINGULAR: return "FSW_W_SINGULAR";
  case FSW_W_SAT: return "FSW_W_SAT";
  case FSW_W_RATE: return "FSW_W_RATE";
  case FSW_E_NULL_ARG: return "FSW_E_NULL_ARG";
  case FSW_E_CONFIG: return "FSW_E_CONFIG";
  case FSW_E_CAPACITY: return "FSW_E_CAPACITY";
  case FSW_E_SINGULAR: return "FSW_E_SINGULAR";
  case FSW_E_BAD_INPUT: return "FSW_E_BAD_INPUT";
  case FSW_E_TIME: return "FSW_E_TIME";
  case FSW_E_UNSUPPORTED: return "FSW_E_UNSUPPORTED";
  case FSW_E_NOT_INIT: return "FSW_E_NOT_INIT";
  default: return "FSW_UNKNOWN";
  }
}

int fsw_status_is_error(FswStatus s) { return fsw_status_is_error_i(s); }

/* fsw_acs_save: the application's state as a byte image (fsw/fsw_acs_save.h). */
#include "fsw/fsw_acs_save.h"

#include <string.h>

static void ckp_put_u32(uint8_t *p, uint32_t v)
{
  p[0] = (uint8_t)(v & 0xFFu);
  p[1] = (uint8_t)((v >> 8) & 0xFFu);
  p[2] = (uint8_t)((v >> 16) & 0xFFu);
  p[3] = (uint8_t)((v >> 24) & 0xFFu);
}

static uint32_t ckp_get_u32(const uint8_t *p)
{
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static void put_tag(uint8_t *p)
{
  ckp_put_u32(p, FSW_ACS_SAVE_MAGIC);
  ckp_put_u32(&p[4], FSW_ACS_SAVE_VERSION);
  ckp_put_u32(&p[8], (uint32_t)sizeof(FswAcsState));
  ckp_put_u32(&p[12], (uint32_t)sizeof(fsw_real));
}

size_t fsw_acs_save_size(void) { return (size_t)FSW_ACS_SAVE_TAG_BYTES + sizeof(FswAcsState); }

FswStatus fsw_acs_save(const FswAcsState *st, uint8_t *buf, size_t cap, size_t *len)
{
  FSW_ASSERT((st != NULL) && (buf != NULL) && (len != NULL));
  if (len != NULL) { *len = 0u; }
  if ((st == NULL) || (buf == NULL) || (len == NULL)) { return FSW_E_NULL_ARG; }
  if (cap < fsw_acs_save_size()) { return FSW_E_CAPACITY; }
  put_tag(buf);
  (void)memcpy(&buf[FSW_ACS_SAVE_TAG_BYTES], st, sizeof(FswAcsState));
  *len = fsw_acs_save_size();
  return FSW_OK;
}

FswStatus fsw_acs_restore(FswAcsState *st, const uint8_t *buf, size_t len)
{
  uint8_t tag[FSW_ACS_SAVE_TAG_BYTES];
  size_t k;
  FSW_ASSERT((st != NULL) && (buf != NULL));
  if ((st == NULL) || (buf == NULL)) { return FSW_E_NULL_ARG; }
  if (len != fsw_acs_save_size()) { return FSW_E_BAD_INPUT; }
  put_tag(tag);
  for (k = 0u; k < FSW_ACS_SAVE_TAG_BYTES; k += 4u) {
    if (ckp_get_u32(&buf[k]) != ckp_get_u32(&tag[k])) { return FSW_E_BAD_INPUT; } }
  (void)memcpy(st, &buf[FSW_ACS_SAVE_TAG_BYTES], sizeof(FswAcsState));
  return FSW_OK;
}

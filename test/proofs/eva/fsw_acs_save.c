/* Eva driver: fsw_acs_save (fsw/fsw_acs_save.h, docs/eva.md): the byte
 * image of the application's state.  save: any state, any capacity from 0
 * to the buffer's size (the image plus 64 bytes); restore: any bytes, any
 * length from 0 to that size.  The two analyses are the same here (no
 * floating-point operation).
 * eva-sources: fsw_acs_save.c */
#include "eva_driver.h"

#include "fsw/fsw_acs_save.h"

#define EVA_SAVE_BUF (FSW_ACS_SAVE_TAG_BYTES + sizeof(FswAcsState) + 64u)

static void run(void)
{
  static FswAcsState st; /* the application's state: static, as a flight build holds it */
  static uint8_t buf[EVA_SAVE_BUF];
  size_t len, cap;
  EVA_ENTRY(save_size, fsw_acs_save_size() == FSW_ACS_SAVE_TAG_BYTES + sizeof(FswAcsState));
  Frama_C_make_unknown((char *)&st, sizeof st);
  cap = Frama_C_size_t_interval(0u, sizeof buf);
  EVA_ENTRY(save, fsw_acs_save(&st, buf, cap, &len));
  Frama_C_make_unknown((char *)buf, sizeof buf);
  len = Frama_C_size_t_interval(0u, sizeof buf);
  EVA_ENTRY(restore, fsw_acs_restore(&st, buf, len));
}

EVA_MAINS

/* fsw_acs_save: the application's state as a byte image, for a checkpoint
 * of a run (docs/checkpoint.md, "Flight software").
 *
 * The state FswAcsState is plain, fixed-size C data with no pointer, so its
 * image is its bytes.  A saved image starts with a 16-byte tag, four
 * little-endian uint32: the magic 0x5753464B ("KFSW"), the format version
 * FSW_ACS_SAVE_VERSION, sizeof(FswAcsState) and sizeof(fsw_real); then the
 * state's bytes.  Restore refuses an image whose tag differs (another
 * build, another precision, a changed state), so an image is read back only
 * by the same library build it was written by.
 *
 * No heap, no stdio; status returns:
 *   fsw_acs_save     FSW_OK; FSW_E_NULL_ARG; FSW_E_CAPACITY when cap <
 *                    fsw_acs_save_size() (*len = 0, buf unchanged)
 *   fsw_acs_restore  FSW_OK; FSW_E_NULL_ARG; FSW_E_BAD_INPUT when len or the
 *                    tag differs (the state is then unchanged)
 */
#ifndef FSW_ACS_SAVE_H
#define FSW_ACS_SAVE_H

#include <stddef.h>
#include <stdint.h>

#include "fsw/fsw_acs.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FSW_ACS_SAVE_MAGIC 0x5753464Bu /* "KFSW" little-endian */
#define FSW_ACS_SAVE_VERSION 2u /* 2: FswAcsWork without its own copies of the speeds and flags */
#define FSW_ACS_SAVE_TAG_BYTES 16u

/* Bytes of a saved image: the tag and sizeof(FswAcsState). */
size_t fsw_acs_save_size(void);
FswStatus fsw_acs_save(const FswAcsState *st, uint8_t *buf, size_t cap, size_t *len);
FswStatus fsw_acs_restore(FswAcsState *st, const uint8_t *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* FSW_ACS_SAVE_H */

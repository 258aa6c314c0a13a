/* fsw_link_sec: optional authentication of FSW link packets with a shared
 * key, after CCSDS Space Data Link Security (355.0-B): each packet, as
 * fsw_link encodes it (header, payload, CRC), is followed by a security
 * trailer
 *
 *   u32  security sequence number, big-endian: 1, 2, 3, ... per sender
 *   u8[16] MAC: HMAC-SHA-256 (FIPS 198-1, FIPS 180-4) of the packet and the
 *        sequence number, under the shared key, truncated to its first
 *        128 bits (RFC 4868 style truncation)
 *
 * The receiver accepts a packet only when the MAC verifies (compared in
 * constant time) and the sequence number is new: above the highest one
 * accepted, or within the 64 below it and not seen yet (the anti-replay
 * window of SDLS and IPsec).  Each end keeps its own sender count, so a
 * retransmitted packet goes out under a new number.  A sender stops at
 * 2^32 - 1 numbers (497 days at 100 packets/s): re-key before.
 *
 * Also here: SHA-256 and HMAC-SHA-256 themselves (known-answer tests: the
 * FIPS 180-2 examples and RFC 4231).
 *
 * C99, no heap, no mutable globals, no stdio; all state is the caller's. */
#ifndef FSW_LINK_SEC_H
#define FSW_LINK_SEC_H

#include <stddef.h>
#include <stdint.h>

#include "fsw/fsw_link.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FSW_SHA256_SIZE 32u
#define FSW_LINK_SEC_SEQ_SIZE 4u
#define FSW_LINK_SEC_MAC_SIZE 16u
#define FSW_LINK_SEC_TRAILER_SIZE (FSW_LINK_SEC_SEQ_SIZE + FSW_LINK_SEC_MAC_SIZE)
#define FSW_LINK_SEC_KEY_MIN 16u /* [B] shortest key accepted (128 bits) */
#define FSW_LINK_SEC_KEY_MAX 64u /* [B] longest (one SHA-256 block)      */
#define FSW_LINK_SEC_WINDOW 64u  /* [-] anti-replay window               */

typedef struct {
  uint32_t h[8];
  uint64_t bytes; /* message bytes so far */
  uint8_t block[64];
  size_t used;    /* bytes in block */
} FswSha256;

void fsw_sha256_init(FswSha256 *c);
void fsw_sha256_update(FswSha256 *c, const uint8_t *data, size_t n);
void fsw_sha256_final(FswSha256 *c, uint8_t out[FSW_SHA256_SIZE]);

/* HMAC-SHA-256 of the concatenation a || b (either may be empty, n = 0)
 * under a key of any length. */
void fsw_hmac_sha256(const uint8_t *key, size_t key_len, const uint8_t *a, size_t na, const uint8_t *b, size_t nb,
                     uint8_t out[FSW_SHA256_SIZE]);

typedef struct {
  uint8_t key[FSW_LINK_SEC_KEY_MAX];
  size_t key_len;
  uint32_t tx_seq;        /* [-] number of the next packet sent (from 1) */
  uint32_t rx_high;       /* [-] highest number accepted (0: none yet)   */
  uint64_t rx_window;     /* bit i: rx_high - i accepted                 */
  uint32_t rx_ok;         /* [-] packets accepted                        */
  uint32_t rx_auth_failed;/* [-] refused: no trailer, or MAC mismatch    */
  uint32_t rx_replayed;   /* [-] refused: number seen or older than the window */
} FswLinkSec;

/* FSW_OK, FSW_E_NULL_ARG, FSW_E_CONFIG (key length outside
 * FSW_LINK_SEC_KEY_MIN ... FSW_LINK_SEC_KEY_MAX). */
FswStatus fsw_link_sec_init(FswLinkSec *s, const uint8_t *key, size_t key_len);

/* out[0 .. n + FSW_LINK_SEC_TRAILER_SIZE) = pkt[0 .. n) and its trailer
 * (out and pkt must not overlap).  FSW_OK; FSW_E_NULL_ARG; FSW_E_BAD_INPUT
 * with FSW_LINK_E_SPACE (cap too small) or FSW_LINK_E_COUNT (the sender's
 * numbers are used up). */
FswStatus fsw_link_sec_protect(FswLinkSec *s, const uint8_t *pkt, size_t n, uint8_t *out, size_t cap,
                               size_t *out_len, FswLinkError *err);

/* buf[0 .. n): a packet and its trailer.  FSW_OK with *pkt_len = n -
 * FSW_LINK_SEC_TRAILER_SIZE (the packet, to fsw_link_parse); else
 * FSW_E_BAD_INPUT with FSW_LINK_E_AUTH or FSW_LINK_E_REPLAY (counted; the
 * window moves only for an accepted packet); FSW_E_NULL_ARG. */
FswStatus fsw_link_sec_verify(FswLinkSec *s, const uint8_t *buf, size_t n, size_t *pkt_len, FswLinkError *err);

#ifdef __cplusplus
}
#endif

#endif /* FSW_LINK_SEC_H */

/* Eva driver: fsw_link_sec, the link's authentication (fsw/fsw_link_sec.h,
 * docs/eva.md): SHA-256 over any bytes fed in two parts of any length,
 * HMAC-SHA-256 under any key of any length over any two parts, init with
 * any key and any key length, then protect any packet of any length into
 * any capacity and verify any bytes of any length, from any sender count,
 * highest number accepted and anti-replay window (a superset of the states
 * that init and earlier calls leave).  No state splitting (about 9 s of CPU
 * per analysis): the hash's byte loops are joined, which gives the index,
 * access and initialization alarms recorded in alarms.txt.
 * eva-options: -eva-slevel 0
 * eva-sources: fsw_link_sec.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/fsw_link_sec.h"

#define EVA_SEC_BUF (FSW_LINK_MAX_PACKET + FSW_LINK_SEC_TRAILER_SIZE + 16u)
#define EVA_KEY_BUF (2u * FSW_LINK_SEC_KEY_MAX) /* keys longer than one block are hashed first */

static size_t eva_len(size_t size) { return Frama_C_size_t_interval(0u, size); }

static void run(void)
{
  static uint8_t data[EVA_SEC_BUF];
  static uint8_t out[EVA_SEC_BUF];
  static uint8_t key[EVA_KEY_BUF];
  static FswLinkSec s;
  FswSha256 c;
  uint8_t mac[FSW_SHA256_SIZE];
  FswLinkError err;
  FswStatus st;
  size_t n, n1, len;
  Frama_C_make_unknown((char *)data, sizeof data);
  Frama_C_make_unknown((char *)key, sizeof key);
  fsw_sha256_init(&c);
  EVA_ENTRY(sha256_init, 0);
  n = eva_len(sizeof data);
  n1 = eva_len(n);
  fsw_sha256_update(&c, data, n1);
  fsw_sha256_update(&c, data + n1, n - n1);
  EVA_ENTRY(sha256_update, 0);
  fsw_sha256_final(&c, mac);
  EVA_ENTRY(sha256_final, 0);
  fsw_hmac_sha256(key, eva_len(sizeof key), data, n1, data + n1, n - n1, mac);
  EVA_ENTRY(hmac_sha256, 0);
  st = fsw_link_sec_init(&s, key, eva_len(sizeof key));
  EVA_ENTRY(init, st);
  if (st != FSW_OK) return;
  s.tx_seq = Frama_C_unsigned_int_interval(0u, UINT32_MAX);
  s.rx_high = Frama_C_unsigned_int_interval(0u, UINT32_MAX);
  s.rx_window = eva_u64();
  EVA_ENTRY(protect, fsw_link_sec_protect(&s, data, eva_len(FSW_LINK_MAX_PACKET), out, eva_len(sizeof out), &len, &err));
  EVA_ENTRY(verify, fsw_link_sec_verify(&s, data, eva_len(sizeof data), &len, &err));
}

EVA_MAINS

/* fsw_link_sec: SHA-256, HMAC-SHA-256 and the link's security trailer (see
 * fsw_link_sec.h). */
#include "fsw/fsw_link_sec.h"

#include <string.h>

static const uint32_t kK[64] = {
    0x428a2f98u, 0x71374491u, 0xb5c0fbcfu, 0xe9b5dba5u, 0x3956c25bu, 0x59f111f1u, 0x923f82a4u, 0xab1c5ed5u,
    0xd807aa98u, 0x12835b01u, 0x243185beu, 0x550c7dc3u, 0x72be5d74u, 0x80deb1feu, 0x9bdc06a7u, 0xc19bf174u,
    0xe49b69c1u, 0xefbe4786u, 0x0fc19dc6u, 0x240ca1ccu, 0x2de92c6fu, 0x4a7484aau, 0x5cb0a9dcu, 0x76f988dau,
    0x983e5152u, 0xa831c66du, 0xb00327c8u, 0xbf597fc7u, 0xc6e00bf3u, 0xd5a79147u, 0x06ca6351u, 0x14292967u,
    0x27b70a85u, 0x2e1b2138u, 0x4d2c6dfcu, 0x53380d13u, 0x650a7354u, 0x766a0abbu, 0x81c2c92eu, 0x92722c85u,
    0xa2bfe8a1u, 0xa81a664bu, 0xc24b8b70u, 0xc76c51a3u, 0xd192e819u, 0xd6990624u, 0xf40e3585u, 0x106aa070u,
    0x19a4c116u, 0x1e376c08u, 0x2748774cu, 0x34b0bcb5u, 0x391c0cb3u, 0x4ed8aa4au, 0x5b9cca4fu, 0x682e6ff3u,
    0x748f82eeu, 0x78a5636fu, 0x84c87814u, 0x8cc70208u, 0x90befffau, 0xa4506cebu, 0xbef9a3f7u, 0xc67178f2u};

static uint32_t rotr(uint32_t x, unsigned n) { return (x >> n) | (x << (32u - n)); }

static void compress(uint32_t h[8], const uint8_t b[64])
{
  uint32_t w[64], v[8];
  unsigned i;
  for (i = 0u; i < 16u; ++i) {
    w[i] = ((uint32_t)b[4u * i] << 24) | ((uint32_t)b[4u * i + 1u] << 16) | ((uint32_t)b[4u * i + 2u] << 8) |
           (uint32_t)b[4u * i + 3u]; }
  for (i = 16u; i < 64u; ++i) {
    const uint32_t s0 = rotr(w[i - 15u], 7u) ^ rotr(w[i - 15u], 18u) ^ (w[i - 15u] >> 3);
    const uint32_t s1 = rotr(w[i - 2u], 17u) ^ rotr(w[i - 2u], 19u) ^ (w[i - 2u] >> 10);
    w[i] = w[i - 16u] + s0 + w[i - 7u] + s1;
  }
  (void)memcpy(v, h, sizeof v);
  for (i = 0u; i < 64u; ++i) {
    const uint32_t t1 = v[7] + (rotr(v[4], 6u) ^ rotr(v[4], 11u) ^ rotr(v[4], 25u)) + ((v[4] & v[5]) ^ (~v[4] & v[6])) +
                        kK[i] + w[i];
    const uint32_t t2 = (rotr(v[0], 2u) ^ rotr(v[0], 13u) ^ rotr(v[0], 22u)) + ((v[0] & v[1]) ^ (v[0] & v[2]) ^ (v[1] & v[2]));
    v[7] = v[6];
    v[6] = v[5];
    v[5] = v[4];
    v[4] = v[3] + t1;
    v[3] = v[2];
    v[2] = v[1];
    v[1] = v[0];
    v[0] = t1 + t2;
  }
  for (i = 0u; i < 8u; ++i) { h[i] += v[i]; }
}

void fsw_sha256_init(FswSha256 *c)
{
  static const uint32_t h0[8] = {0x6a09e667u, 0xbb67ae85u, 0x3c6ef372u, 0xa54ff53au,
                                 0x510e527fu, 0x9b05688cu, 0x1f83d9abu, 0x5be0cd19u};
  if (c == NULL) { return; }
  (void)memcpy(c->h, h0, sizeof c->h);
  c->bytes = 0u;
  c->used = 0u;
}

void fsw_sha256_update(FswSha256 *c, const uint8_t *data, size_t n)
{
  size_t i;
  if (c == NULL || (data == NULL && n != 0u)) { return; }
  for (i = 0u; i < n; ++i) {
    c->block[c->used++] = data[i];
    if (c->used == 64u) {
      compress(c->h, c->block);
      c->used = 0u;
    }
  }
  c->bytes += (uint64_t)n;
}

void fsw_sha256_final(FswSha256 *c, uint8_t out[FSW_SHA256_SIZE])
{
  const uint64_t bits = c->bytes * 8u;
  unsigned i;
  c->block[c->used++] = 0x80u;
  if (c->used > 56u) {
    while (c->used < 64u) { c->block[c->used++] = 0u; }
    compress(c->h, c->block);
    c->used = 0u;
  }
  while (c->used < 56u) { c->block[c->used++] = 0u; }
  for (i = 0u; i < 8u; ++i) { c->block[56u + i] = (uint8_t)(bits >> (56u - 8u * i)); }
  compress(c->h, c->block);
  for (i = 0u; i < 8u; ++i) {
    out[4u * i] = (uint8_t)(c->h[i] >> 24);
    out[4u * i + 1u] = (uint8_t)(c->h[i] >> 16);
    out[4u * i + 2u] = (uint8_t)(c->h[i] >> 8);
    out[4u * i + 3u] = (uint8_t)c->h[i];
  }
}

void fsw_hmac_sha256(const uint8_t *key, size_t key_len, const uint8_t *a, size_t na, const uint8_t *b, size_t nb,
                     uint8_t out[FSW_SHA256_SIZE])
{
  uint8_t k[64], pad[64], inner[FSW_SHA256_SIZE];
  FswSha256 c;
  unsigned i;
  (void)memset(k, 0, sizeof k);
  if (key_len > 64u) { /* a key longer than a block is hashed first */
    fsw_sha256_init(&c);
    fsw_sha256_update(&c, key, key_len);
    fsw_sha256_final(&c, k);
  } else if (key_len > 0u) {
    (void)memcpy(k, key, key_len);
  }
  for (i = 0u; i < 64u; ++i) { pad[i] = (uint8_t)(k[i] ^ 0x36u); }
  fsw_sha256_init(&c);
  fsw_sha256_update(&c, pad, 64u);
  fsw_sha256_update(&c, a, na);
  fsw_sha256_update(&c, b, nb);
  fsw_sha256_final(&c, inner);
  for (i = 0u; i < 64u; ++i) { pad[i] = (uint8_t)(k[i] ^ 0x5cu); }
  fsw_sha256_init(&c);
  fsw_sha256_update(&c, pad, 64u);
  fsw_sha256_update(&c, inner, sizeof inner);
  fsw_sha256_final(&c, out);
}

static FswStatus sec_fail(FswLinkError *err, FswLinkError e)
{
  if (err != NULL) { *err = e; }
  return FSW_E_BAD_INPUT;
}

FswStatus fsw_link_sec_init(FswLinkSec *s, const uint8_t *key, size_t key_len)
{
  if (s == NULL || key == NULL) { return FSW_E_NULL_ARG; }
  if (key_len < FSW_LINK_SEC_KEY_MIN || key_len > FSW_LINK_SEC_KEY_MAX) { return FSW_E_CONFIG; }
  (void)memset(s, 0, sizeof *s);
  (void)memcpy(s->key, key, key_len);
  s->key_len = key_len;
  s->tx_seq = 1u;
  return FSW_OK;
}

static void put_seq(uint8_t *p, uint32_t v)
{
  p[0] = (uint8_t)(v >> 24);
  p[1] = (uint8_t)(v >> 16);
  p[2] = (uint8_t)(v >> 8);
  p[3] = (uint8_t)v;
}

FswStatus fsw_link_sec_protect(FswLinkSec *s, const uint8_t *pkt, size_t n, uint8_t *out, size_t cap,
                               size_t *out_len, FswLinkError *err)
{
  uint8_t mac[FSW_SHA256_SIZE];
  if (s == NULL || pkt == NULL || out == NULL || out_len == NULL) { return FSW_E_NULL_ARG; }
  if (cap < FSW_LINK_SEC_TRAILER_SIZE || n > cap - FSW_LINK_SEC_TRAILER_SIZE) { return sec_fail(err, FSW_LINK_E_SPACE); }
  if (s->tx_seq == 0u) { return sec_fail(err, FSW_LINK_E_COUNT); } /* wrapped: numbers used up */
  (void)memmove(out, pkt, n);
  put_seq(out + n, s->tx_seq);
  fsw_hmac_sha256(s->key, s->key_len, out, n + FSW_LINK_SEC_SEQ_SIZE, NULL, 0u, mac);
  (void)memcpy(out + n + FSW_LINK_SEC_SEQ_SIZE, mac, FSW_LINK_SEC_MAC_SIZE);
  *out_len = n + FSW_LINK_SEC_TRAILER_SIZE;
  s->tx_seq++;
  if (err != NULL) { *err = FSW_LINK_OK; }
  return FSW_OK;
}

FswStatus fsw_link_sec_verify(FswLinkSec *s, const uint8_t *buf, size_t n, size_t *pkt_len, FswLinkError *err)
{
  uint8_t mac[FSW_SHA256_SIZE], diff = 0u;
  uint32_t seq;
  size_t body, i;
  if (s == NULL || buf == NULL || pkt_len == NULL) { return FSW_E_NULL_ARG; }
  if (n < FSW_LINK_SEC_TRAILER_SIZE + FSW_LINK_HEADER_SIZE + FSW_LINK_CRC_SIZE) {
    s->rx_auth_failed++;
    return sec_fail(err, FSW_LINK_E_AUTH);
  }
  body = n - FSW_LINK_SEC_MAC_SIZE; /* packet and sequence number */
  fsw_hmac_sha256(s->key, s->key_len, buf, body, NULL, 0u, mac);
  for (i = 0u; i < FSW_LINK_SEC_MAC_SIZE; ++i) { diff = (uint8_t)(diff | (mac[i] ^ buf[body + i])); }
  if (diff != 0u) {
    s->rx_auth_failed++;
    return sec_fail(err, FSW_LINK_E_AUTH);
  }
  seq = ((uint32_t)buf[body - 4u] << 24) | ((uint32_t)buf[body - 3u] << 16) | ((uint32_t)buf[body - 2u] << 8) |
        (uint32_t)buf[body - 1u];
  if (seq == 0u) {
    s->rx_replayed++;
    return sec_fail(err, FSW_LINK_E_REPLAY);
  }
  if (seq > s->rx_high) {
    const uint32_t shift = seq - s->rx_high;
    s->rx_window = shift >= FSW_LINK_SEC_WINDOW ? 0u : s->rx_window << shift;
    s->rx_window |= 1u;
    s->rx_high = seq;
  } else {
    const uint32_t back = s->rx_high - seq;
    if (back >= FSW_LINK_SEC_WINDOW || ((s->rx_window >> back) & 1u) != 0u) {
      s->rx_replayed++;
      return sec_fail(err, FSW_LINK_E_REPLAY);
    }
    s->rx_window |= (uint64_t)1u << back;
  }
  s->rx_ok++;
  *pkt_len = n - FSW_LINK_SEC_TRAILER_SIZE;
  if (err != NULL) { *err = FSW_LINK_OK; }
  return FSW_OK;
}

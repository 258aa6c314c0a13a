/* fsw_link: CCSDS Space Packet codec of the FSW link (see fsw_link.h and
 * docs/icd.md). */
#include "fsw/fsw_link.h"

#include <string.h>

#define LINK_VERSION 0u
#define LINK_SEQ_FLAGS 3u /* unsegmented user data */

static FswStatus link_fail(FswLinkError *err, FswLinkError why)
{
  if (err != NULL) *err = why;
  return FSW_E_BAD_INPUT;
}

static FswStatus link_ok(FswLinkError *err)
{
  if (err != NULL) *err = FSW_LINK_OK;
  return FSW_OK;
}

uint16_t fsw_link_crc16(const uint8_t *data, size_t n, uint16_t crc)
{
  size_t i;
  int b;
  if (data == NULL) return crc;
  for (i = 0u; i < n; ++i) {
    crc = (uint16_t)(crc ^ (uint16_t)((uint16_t)data[i] << 8));
    for (b = 0; b < 8; ++b) {
      const uint32_t shifted = ((uint32_t)crc << 1) ^ (((uint32_t)crc & 0x8000u) != 0u ? 0x1021u : 0u);
      crc = (uint16_t)(shifted & 0xFFFFu);
    }
  }
  return crc;
}

/* ---- big-endian writer / reader over a bounded buffer ------------------- */

typedef struct {
  uint8_t *p;
  size_t n, cap;
} Writer;

typedef struct {
  const uint8_t *p;
  size_t n, len;
} Reader;

static void put_u8(Writer *w, uint32_t v)
{
  if (w->n < w->cap) w->p[w->n] = (uint8_t)(v & 0xFFu);
  w->n++;
}

static void put_u16(Writer *w, uint32_t v)
{
  put_u8(w, v >> 8);
  put_u8(w, v);
}

static void put_u32(Writer *w, uint32_t v)
{
  put_u16(w, v >> 16);
  put_u16(w, v);
}

static void put_u64(Writer *w, uint64_t v)
{
  put_u32(w, (uint32_t)(v >> 32));
  put_u32(w, (uint32_t)(v & 0xFFFFFFFFu));
}

static void put_real(Writer *w, fsw_real x)
{
  const double d = (double)x;
  uint64_t bits;
  memcpy(&bits, &d, sizeof bits);
  put_u64(w, bits);
}

static void put_reals(Writer *w, const fsw_real *x, size_t n)
{
  size_t i;
  for (i = 0u; i < n; ++i) put_real(w, x[i]);
}

static void put_flags(Writer *w, const uint8_t *f, size_t n)
{
  size_t i;
  for (i = 0u; i < n; ++i) put_u8(w, f[i]);
}

static uint32_t get_u8(Reader *r)
{
  uint32_t v = 0u;
  if (r->n < r->len) v = r->p[r->n];
  r->n++;
  return v;
}

static uint32_t get_u16(Reader *r)
{
  const uint32_t hi = get_u8(r);
  return (hi << 8) | get_u8(r);
}

static uint32_t get_u32(Reader *r)
{
  const uint32_t hi = get_u16(r);
  return (hi << 16) | get_u16(r);
}

static uint64_t get_u64(Reader *r)
{
  const uint64_t hi = get_u32(r);
  return (hi << 32) | get_u32(r);
}

static fsw_real get_real(Reader *r)
{
  const uint64_t bits = get_u64(r);
  double d;
  memcpy(&d, &bits, sizeof d);
  return (fsw_real)d;
}

static void get_reals(Reader *r, fsw_real *x, size_t n)
{
  size_t i;
  for (i = 0u; i < n; ++i) x[i] = get_real(r);
}

/* flags must be 0 or 1; returns 0 if any is not */
static int get_flags(Reader *r, uint8_t *f, size_t n)
{
  size_t i;
  int ok = 1;
  for (i = 0u; i < n; ++i) {
    const uint32_t v = get_u8(r);
    if (v > 1u) ok = 0;
    f[i] = (uint8_t)v;
  }
  return ok;
}

/* ---- packets ---------------------------------------------------------------- */

static void put_headers(Writer *w, uint32_t apid, uint32_t type, uint16_t seq, uint64_t t_ns, size_t payload)
{
  const size_t data_len = FSW_LINK_SECONDARY_SIZE + payload + FSW_LINK_CRC_SIZE;
  put_u16(w, (LINK_VERSION << 13) | (type << 12) | (1u << 11) | (apid & 0x7FFu));
  put_u16(w, (LINK_SEQ_FLAGS << 14) | ((uint32_t)seq % FSW_LINK_SEQ_MODULO));
  put_u16(w, (uint32_t)(data_len - 1u));
  put_u64(w, t_ns);
}

/* Appends the CRC and reports the size; the writer counted every byte it
 * was asked for, so an overflow shows as n > cap. */
static FswStatus finish_packet(Writer *w, size_t *len, FswLinkError *err)
{
  if (w->n + FSW_LINK_CRC_SIZE > w->cap) return link_fail(err, FSW_LINK_E_SPACE);
  put_u16(w, fsw_link_crc16(w->p, w->n, 0xFFFFu));
  *len = w->n;
  return link_ok(err);
}

static int begin_packet(Writer *w, uint8_t *buf, size_t cap, size_t payload)
{
  w->p = buf;
  w->n = 0u;
  w->cap = cap;
  return cap >= FSW_LINK_HEADER_SIZE + payload + FSW_LINK_CRC_SIZE;
}

FswStatus fsw_link_encode_sensor(const FswAcsSensorMsg *m, uint8_t num_rw, uint8_t num_css, uint16_t seq,
                                 uint8_t *buf, size_t cap, size_t *len, FswLinkError *err)
{
  Writer w;
  const size_t payload = FSW_LINK_SENSOR_PAYLOAD(num_rw, num_css);
  if (m == NULL || buf == NULL || len == NULL) return FSW_E_NULL_ARG;
  if (num_rw > FSW_MAX_RW || num_css > FSW_MAX_CSS) return link_fail(err, FSW_LINK_E_COUNT);
  if (!begin_packet(&w, buf, cap, payload)) return link_fail(err, FSW_LINK_E_SPACE);
  put_headers(&w, FSW_LINK_APID_SENSOR, 1u, seq, m->t_ns, payload);
  put_u8(&w, num_rw);
  put_u8(&w, num_css);
  put_u8(&w, m->att_valid != 0u ? 1u : 0u);
  put_u8(&w, 0u);
  put_reals(&w, m->sigma_BN, 3u);
  put_reals(&w, m->omega_BN_B, 3u);
  put_reals(&w, m->r_CoM_B, 3u);
  put_reals(&w, m->Omega, num_rw);
  put_flags(&w, m->rw_avail, num_rw);
  put_reals(&w, m->css, num_css);
  put_flags(&w, m->css_avail, num_css);
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_encode_cmd(const FswAcsCmdMsg *m, uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap,
                              size_t *len, FswLinkError *err)
{
  Writer w;
  if (m == NULL || buf == NULL || len == NULL) return FSW_E_NULL_ARG;
  if (m->mode < 0 || m->mode > 255 || m->actuation < 0 || m->actuation > 255) return link_fail(err, FSW_LINK_E_COUNT);
  if (!begin_packet(&w, buf, cap, FSW_LINK_CMD_PAYLOAD)) return link_fail(err, FSW_LINK_E_SPACE);
  put_headers(&w, FSW_LINK_APID_CMD, 1u, seq, t_ns, FSW_LINK_CMD_PAYLOAD);
  put_u8(&w, (uint32_t)m->mode);
  put_u8(&w, (uint32_t)m->actuation);
  put_u16(&w, 0u);
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_encode_actuator(const FswAcsActuatorMsg *m, uint8_t num_rw, uint8_t num_thr, uint64_t t_ns,
                                   uint16_t seq, uint8_t *buf, size_t cap, size_t *len, FswLinkError *err)
{
  Writer w;
  const size_t payload = FSW_LINK_ACTUATOR_PAYLOAD(num_rw, num_thr);
  if (m == NULL || buf == NULL || len == NULL) return FSW_E_NULL_ARG;
  if (num_rw > FSW_MAX_RW || num_thr > FSW_MAX_THR) return link_fail(err, FSW_LINK_E_COUNT);
  if (!begin_packet(&w, buf, cap, payload)) return link_fail(err, FSW_LINK_E_SPACE);
  put_headers(&w, FSW_LINK_APID_ACTUATOR, 0u, seq, t_ns, payload);
  put_u8(&w, num_rw);
  put_u8(&w, num_thr);
  put_u8(&w, m->wheels_active != 0u ? 1u : 0u);
  put_u8(&w, m->thrusters_active != 0u ? 1u : 0u);
  put_reals(&w, m->Lr_B, 3u);
  put_reals(&w, m->u_s, num_rw);
  put_reals(&w, m->V, num_rw);
  put_reals(&w, m->F, num_thr);
  put_reals(&w, m->t_on, num_thr);
  return finish_packet(&w, len, err);
}

static uint32_t status_bits(FswStatus s) { return (uint32_t)(uint16_t)(int16_t)s; }

static FswStatus status_of(uint32_t bits)
{
  const int16_t v = (int16_t)(uint16_t)bits;
  return (FswStatus)v;
}

FswStatus fsw_link_encode_health(const FswAcsHealthMsg *m, uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap,
                                 size_t *len, FswLinkError *err)
{
  Writer w;
  size_t i;
  if (m == NULL || buf == NULL || len == NULL) return FSW_E_NULL_ARG;
  if (m->mode < 0 || m->mode > 255 || m->actuation < 0 || m->actuation > 255) return link_fail(err, FSW_LINK_E_COUNT);
  if (!begin_packet(&w, buf, cap, FSW_LINK_HEALTH_PAYLOAD)) return link_fail(err, FSW_LINK_E_SPACE);
  put_headers(&w, FSW_LINK_APID_HEALTH, 0u, seq, t_ns, FSW_LINK_HEALTH_PAYLOAD);
  put_u16(&w, status_bits(m->status));
  put_u8(&w, (uint32_t)m->mode);
  put_u8(&w, (uint32_t)m->actuation);
  put_u8(&w, m->safe_output != 0u ? 1u : 0u);
  put_u8(&w, m->sun_valid != 0u ? 1u : 0u);
  put_u8(&w, m->num_lit);
  put_u8(&w, (uint32_t)FSW_ACS_NUM_STAGES);
  put_u32(&w, m->cycles);
  put_u32(&w, m->mode_changes);
  for (i = 0u; i < (size_t)FSW_ACS_NUM_STAGES; ++i) put_u16(&w, status_bits(m->stage_status[i]));
  put_reals(&w, m->sigma_BR, 3u);
  put_reals(&w, m->omega_BR_B, 3u);
  put_real(&w, m->att_err_angle);
  put_real(&w, m->sun_angle_err);
  put_reals(&w, m->sun_hat_B, 3u);
  put_u32(&w, m->health.bad_input);
  put_u32(&w, m->health.bad_time);
  put_u32(&w, m->health.saturated);
  put_u32(&w, m->health.singular);
  put_u32(&w, m->health.rate);
  put_u32(&w, m->health.other_error);
  put_u32(&w, m->health.calls);
  put_u16(&w, status_bits(m->health.last));
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_parse(const uint8_t *buf, size_t n, FswLinkPacket *p, FswLinkError *err)
{
  Reader r;
  uint32_t w0, w1, data_len;
  size_t total;
  uint16_t crc;
  if (buf == NULL || p == NULL) return FSW_E_NULL_ARG;
  if (n < FSW_LINK_HEADER_SIZE + FSW_LINK_CRC_SIZE) return link_fail(err, FSW_LINK_E_SHORT);
  r.p = buf;
  r.n = 0u;
  r.len = n;
  w0 = get_u16(&r);
  w1 = get_u16(&r);
  data_len = get_u16(&r) + 1u;
  if ((w0 >> 13) != LINK_VERSION || ((w0 >> 11) & 1u) != 1u || (w1 >> 14) != LINK_SEQ_FLAGS)
    return link_fail(err, FSW_LINK_E_HEADER);
  if (data_len < FSW_LINK_SECONDARY_SIZE + FSW_LINK_CRC_SIZE) return link_fail(err, FSW_LINK_E_HEADER);
  total = FSW_LINK_PRIMARY_SIZE + (size_t)data_len;
  if (total > n) return link_fail(err, FSW_LINK_E_SHORT);
  crc = fsw_link_crc16(buf, total - FSW_LINK_CRC_SIZE, 0xFFFFu);
  if (crc != (uint16_t)(((uint32_t)buf[total - 2u] << 8) | buf[total - 1u])) return link_fail(err, FSW_LINK_E_CRC);
  p->apid = (uint16_t)(w0 & 0x7FFu);
  p->type = (uint8_t)((w0 >> 12) & 1u);
  p->seq = (uint16_t)(w1 & 0x3FFFu);
  p->t_ns = get_u64(&r);
  p->payload = buf + FSW_LINK_HEADER_SIZE;
  p->payload_len = total - FSW_LINK_HEADER_SIZE - FSW_LINK_CRC_SIZE;
  p->packet_len = total;
  return link_ok(err);
}

static FswStatus expect(const FswLinkPacket *p, uint32_t apid, uint32_t type, Reader *r, FswLinkError *err)
{
  if (p->apid != apid || p->type != type) return link_fail(err, FSW_LINK_E_APID);
  r->p = p->payload;
  r->n = 0u;
  r->len = p->payload_len;
  return FSW_OK;
}

FswStatus fsw_link_decode_sensor(const FswLinkPacket *p, FswAcsSensorMsg *m, uint8_t *num_rw, uint8_t *num_css,
                                 FswLinkError *err)
{
  Reader r;
  FswAcsSensorMsg out;
  uint32_t nrw, ncss, att_valid;
  int ok;
  if (p == NULL || m == NULL || num_rw == NULL || num_css == NULL || p->payload == NULL) return FSW_E_NULL_ARG;
  if (expect(p, FSW_LINK_APID_SENSOR, 1u, &r, err) != FSW_OK) return FSW_E_BAD_INPUT;
  if (p->payload_len < FSW_LINK_SENSOR_PAYLOAD(0u, 0u)) return link_fail(err, FSW_LINK_E_LENGTH);
  nrw = get_u8(&r);
  ncss = get_u8(&r);
  if (nrw > FSW_MAX_RW || ncss > FSW_MAX_CSS) return link_fail(err, FSW_LINK_E_COUNT);
  if (p->payload_len != FSW_LINK_SENSOR_PAYLOAD(nrw, ncss)) return link_fail(err, FSW_LINK_E_LENGTH);
  memset(&out, 0, sizeof out);
  out.t_ns = p->t_ns;
  att_valid = get_u8(&r);
  ok = att_valid <= 1u && get_u8(&r) == 0u;
  out.att_valid = (uint8_t)att_valid;
  get_reals(&r, out.sigma_BN, 3u);
  get_reals(&r, out.omega_BN_B, 3u);
  get_reals(&r, out.r_CoM_B, 3u);
  get_reals(&r, out.Omega, nrw);
  ok = get_flags(&r, out.rw_avail, nrw) && ok;
  get_reals(&r, out.css, ncss);
  ok = get_flags(&r, out.css_avail, ncss) && ok;
  if (!ok) return link_fail(err, FSW_LINK_E_COUNT);
  memcpy(m, &out, sizeof out);
  *num_rw = (uint8_t)nrw;
  *num_css = (uint8_t)ncss;
  return link_ok(err);
}

FswStatus fsw_link_decode_cmd(const FswLinkPacket *p, FswAcsCmdMsg *m, FswLinkError *err)
{
  Reader r;
  uint32_t mode, act;
  if (p == NULL || m == NULL || p->payload == NULL) return FSW_E_NULL_ARG;
  if (expect(p, FSW_LINK_APID_CMD, 1u, &r, err) != FSW_OK) return FSW_E_BAD_INPUT;
  if (p->payload_len != FSW_LINK_CMD_PAYLOAD) return link_fail(err, FSW_LINK_E_LENGTH);
  mode = get_u8(&r);
  act = get_u8(&r);
  if (get_u16(&r) != 0u) return link_fail(err, FSW_LINK_E_COUNT);
  m->mode = (int)mode;
  m->actuation = (int)act;
  return link_ok(err);
}

FswStatus fsw_link_decode_actuator(const FswLinkPacket *p, FswAcsActuatorMsg *m, uint8_t *num_rw, uint8_t *num_thr,
                                   FswLinkError *err)
{
  Reader r;
  FswAcsActuatorMsg out;
  uint32_t nrw, nthr, wa, ta;
  if (p == NULL || m == NULL || num_rw == NULL || num_thr == NULL || p->payload == NULL) return FSW_E_NULL_ARG;
  if (expect(p, FSW_LINK_APID_ACTUATOR, 0u, &r, err) != FSW_OK) return FSW_E_BAD_INPUT;
  if (p->payload_len < FSW_LINK_ACTUATOR_PAYLOAD(0u, 0u)) return link_fail(err, FSW_LINK_E_LENGTH);
  nrw = get_u8(&r);
  nthr = get_u8(&r);
  if (nrw > FSW_MAX_RW || nthr > FSW_MAX_THR) return link_fail(err, FSW_LINK_E_COUNT);
  if (p->payload_len != FSW_LINK_ACTUATOR_PAYLOAD(nrw, nthr)) return link_fail(err, FSW_LINK_E_LENGTH);
  wa = get_u8(&r);
  ta = get_u8(&r);
  if (wa > 1u || ta > 1u) return link_fail(err, FSW_LINK_E_COUNT);
  memset(&out, 0, sizeof out);
  out.wheels_active = (uint8_t)wa;
  out.thrusters_active = (uint8_t)ta;
  get_reals(&r, out.Lr_B, 3u);
  get_reals(&r, out.u_s, nrw);
  get_reals(&r, out.V, nrw);
  get_reals(&r, out.F, nthr);
  get_reals(&r, out.t_on, nthr);
  memcpy(m, &out, sizeof out);
  *num_rw = (uint8_t)nrw;
  *num_thr = (uint8_t)nthr;
  return link_ok(err);
}

FswStatus fsw_link_decode_health(const FswLinkPacket *p, FswAcsHealthMsg *m, FswLinkError *err)
{
  Reader r;
  FswAcsHealthMsg out;
  uint32_t safe, sun_valid;
  size_t i;
  if (p == NULL || m == NULL || p->payload == NULL) return FSW_E_NULL_ARG;
  if (expect(p, FSW_LINK_APID_HEALTH, 0u, &r, err) != FSW_OK) return FSW_E_BAD_INPUT;
  if (p->payload_len != FSW_LINK_HEALTH_PAYLOAD) return link_fail(err, FSW_LINK_E_LENGTH);
  memset(&out, 0, sizeof out);
  out.status = status_of(get_u16(&r));
  out.mode = (int)get_u8(&r);
  out.actuation = (int)get_u8(&r);
  safe = get_u8(&r);
  sun_valid = get_u8(&r);
  out.num_lit = (uint8_t)get_u8(&r);
  if (safe > 1u || sun_valid > 1u || get_u8(&r) != (uint32_t)FSW_ACS_NUM_STAGES)
    return link_fail(err, FSW_LINK_E_COUNT);
  out.safe_output = (uint8_t)safe;
  out.sun_valid = (uint8_t)sun_valid;
  out.cycles = get_u32(&r);
  out.mode_changes = get_u32(&r);
  for (i = 0u; i < (size_t)FSW_ACS_NUM_STAGES; ++i) out.stage_status[i] = status_of(get_u16(&r));
  get_reals(&r, out.sigma_BR, 3u);
  get_reals(&r, out.omega_BR_B, 3u);
  out.att_err_angle = get_real(&r);
  out.sun_angle_err = get_real(&r);
  get_reals(&r, out.sun_hat_B, 3u);
  out.health.bad_input = get_u32(&r);
  out.health.bad_time = get_u32(&r);
  out.health.saturated = get_u32(&r);
  out.health.singular = get_u32(&r);
  out.health.rate = get_u32(&r);
  out.health.other_error = get_u32(&r);
  out.health.calls = get_u32(&r);
  out.health.last = status_of(get_u16(&r));
  memcpy(m, &out, sizeof out);
  return link_ok(err);
}

/* ---- byte streams ------------------------------------------------------- */

/* Byte i of the attached sync marker 1A CF FC 1D (no static tables). */
static uint8_t asm_byte(size_t i)
{
  return (uint8_t)((0x1ACFFC1Du >> (8u * (3u - (unsigned)i))) & 0xFFu);
}

FswStatus fsw_link_frame(const uint8_t *pkt, size_t n, uint8_t *out, size_t cap, size_t *len)
{
  size_t i;
  if (pkt == NULL || out == NULL || len == NULL) return FSW_E_NULL_ARG;
  if (cap < n + FSW_LINK_ASM_SIZE) return FSW_E_BAD_INPUT;
  memmove(out + FSW_LINK_ASM_SIZE, pkt, n);
  for (i = 0u; i < FSW_LINK_ASM_SIZE; ++i) out[i] = asm_byte(i);
  *len = n + FSW_LINK_ASM_SIZE;
  return FSW_OK;
}

void fsw_link_deframer_init(FswLinkDeframer *d)
{
  if (d != NULL) memset(d, 0, sizeof *d);
}

/* Drops the first byte of the buffer (a rejected marker start) and keeps
 * the rest for the hunt. */
static void deframer_slip(FswLinkDeframer *d)
{
  memmove(d->buf, d->buf + 1, d->have - 1u);
  d->have--;
}

size_t fsw_link_deframer_push(FswLinkDeframer *d, const uint8_t *bytes, size_t n, const uint8_t **pkt,
                              size_t *pkt_len)
{
  size_t used = 0u;
  if (pkt != NULL) *pkt = NULL;
  if (pkt_len != NULL) *pkt_len = 0u;
  if (d == NULL || bytes == NULL || pkt == NULL || pkt_len == NULL) return 0u;
  while (used < n || d->have > 0u) {
    /* 1. the marker: the buffer always holds a prefix of it, or more */
    size_t i;
    int matched = 1;
    for (i = 0u; i < d->have && i < FSW_LINK_ASM_SIZE; ++i) {
      if (d->buf[i] != asm_byte(i)) matched = 0;
    }
    if (!matched) {
      deframer_slip(d);
      d->sync_slips++;
      continue;
    }
    if (d->have < FSW_LINK_ASM_SIZE + FSW_LINK_PRIMARY_SIZE) {
      if (used == n) break;
      d->buf[d->have++] = bytes[used++];
      continue;
    }
    /* 2. the length from the primary header */
    {
      const uint8_t *h = d->buf + FSW_LINK_ASM_SIZE;
      const size_t total = FSW_LINK_PRIMARY_SIZE + (((size_t)h[4] << 8) | h[5]) + 1u;
      FswLinkPacket p;
      if (total > FSW_LINK_MAX_PACKET || total < FSW_LINK_HEADER_SIZE + FSW_LINK_CRC_SIZE) {
        d->rejected++;
        deframer_slip(d);
        continue;
      }
      if (d->have < FSW_LINK_ASM_SIZE + total) {
        const size_t want = FSW_LINK_ASM_SIZE + total - d->have;
        const size_t take = (n - used) < want ? (n - used) : want;
        if (take == 0u) break;
        memcpy(d->buf + d->have, bytes + used, take);
        d->have += take;
        used += take;
        continue;
      }
      /* 3. a whole candidate: header and CRC */
      if (fsw_link_parse(h, total, &p, NULL) != FSW_OK) {
        d->rejected++;
        deframer_slip(d);
        continue;
      }
      d->packets++;
      d->have = 0u;
      /* the packet stays in buf until the next call */
      *pkt = h;
      *pkt_len = total;
      return used;
    }
  }
  return used;
}

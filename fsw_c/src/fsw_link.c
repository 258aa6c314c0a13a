/* fsw_link: CCSDS Space Packet codec of the FSW link (see fsw_link.h and
 * docs/icd.md). */
#include "fsw/fsw_link.h"

#include <stddef.h>
#include <string.h>

#define LINK_VERSION 0u
#define LINK_SEQ_FLAGS 3u /* unsegmented user data */

static FswStatus link_fail(FswLinkError *err, FswLinkError why)
{
  if (err != NULL) { *err = why; }
  return FSW_E_BAD_INPUT;
}

static FswStatus link_ok(FswLinkError *err)
{
  if (err != NULL) { *err = FSW_LINK_OK; }
  return FSW_OK;
}

/* CRC-16/CCITT-FALSE (polynomial 0x1021, MSB first) a byte at a time:
 * entry v is the CRC register after shifting the byte v through a zero
 * register eight times (crc = crc << 1, xor 0x1021 when the bit out was 1),
 * so crc' = (crc << 8) ^ table[(crc >> 8) ^ byte]. 512 bytes of read-only
 * data; the tests compare it with the bit-by-bit definition. */
uint16_t fsw_link_crc16(const uint8_t *data, size_t n, uint16_t crc)
{
  static const uint16_t crc16_table[256] = {
    0x0000u, 0x1021u, 0x2042u, 0x3063u, 0x4084u, 0x50A5u, 0x60C6u, 0x70E7u,
    0x8108u, 0x9129u, 0xA14Au, 0xB16Bu, 0xC18Cu, 0xD1ADu, 0xE1CEu, 0xF1EFu,
    0x1231u, 0x0210u, 0x3273u, 0x2252u, 0x52B5u, 0x4294u, 0x72F7u, 0x62D6u,
    0x9339u, 0x8318u, 0xB37Bu, 0xA35Au, 0xD3BDu, 0xC39Cu, 0xF3FFu, 0xE3DEu,
    0x2462u, 0x3443u, 0x0420u, 0x1401u, 0x64E6u, 0x74C7u, 0x44A4u, 0x5485u,
    0xA56Au, 0xB54Bu, 0x8528u, 0x9509u, 0xE5EEu, 0xF5CFu, 0xC5ACu, 0xD58Du,
    0x3653u, 0x2672u, 0x1611u, 0x0630u, 0x76D7u, 0x66F6u, 0x5695u, 0x46B4u,
    0xB75Bu, 0xA77Au, 0x9719u, 0x8738u, 0xF7DFu, 0xE7FEu, 0xD79Du, 0xC7BCu,
    0x48C4u, 0x58E5u, 0x6886u, 0x78A7u, 0x0840u, 0x1861u, 0x2802u, 0x3823u,
    0xC9CCu, 0xD9EDu, 0xE98Eu, 0xF9AFu, 0x8948u, 0x9969u, 0xA90Au, 0xB92Bu,
    0x5AF5u, 0x4AD4u, 0x7AB7u, 0x6A96u, 0x1A71u, 0x0A50u, 0x3A33u, 0x2A12u,
    0xDBFDu, 0xCBDCu, 0xFBBFu, 0xEB9Eu, 0x9B79u, 0x8B58u, 0xBB3Bu, 0xAB1Au,
    0x6CA6u, 0x7C87u, 0x4CE4u, 0x5CC5u, 0x2C22u, 0x3C03u, 0x0C60u, 0x1C41u,
    0xEDAEu, 0xFD8Fu, 0xCDECu, 0xDDCDu, 0xAD2Au, 0xBD0Bu, 0x8D68u, 0x9D49u,
    0x7E97u, 0x6EB6u, 0x5ED5u, 0x4EF4u, 0x3E13u, 0x2E32u, 0x1E51u, 0x0E70u,
    0xFF9Fu, 0xEFBEu, 0xDFDDu, 0xCFFCu, 0xBF1Bu, 0xAF3Au, 0x9F59u, 0x8F78u,
    0x9188u, 0x81A9u, 0xB1CAu, 0xA1EBu, 0xD10Cu, 0xC12Du, 0xF14Eu, 0xE16Fu,
    0x1080u, 0x00A1u, 0x30C2u, 0x20E3u, 0x5004u, 0x4025u, 0x7046u, 0x6067u,
    0x83B9u, 0x9398u, 0xA3FBu, 0xB3DAu, 0xC33Du, 0xD31Cu, 0xE37Fu, 0xF35Eu,
    0x02B1u, 0x1290u, 0x22F3u, 0x32D2u, 0x4235u, 0x5214u, 0x6277u, 0x7256u,
    0xB5EAu, 0xA5CBu, 0x95A8u, 0x8589u, 0xF56Eu, 0xE54Fu, 0xD52Cu, 0xC50Du,
    0x34E2u, 0x24C3u, 0x14A0u, 0x0481u, 0x7466u, 0x6447u, 0x5424u, 0x4405u,
    0xA7DBu, 0xB7FAu, 0x8799u, 0x97B8u, 0xE75Fu, 0xF77Eu, 0xC71Du, 0xD73Cu,
    0x26D3u, 0x36F2u, 0x0691u, 0x16B0u, 0x6657u, 0x7676u, 0x4615u, 0x5634u,
    0xD94Cu, 0xC96Du, 0xF90Eu, 0xE92Fu, 0x99C8u, 0x89E9u, 0xB98Au, 0xA9ABu,
    0x5844u, 0x4865u, 0x7806u, 0x6827u, 0x18C0u, 0x08E1u, 0x3882u, 0x28A3u,
    0xCB7Du, 0xDB5Cu, 0xEB3Fu, 0xFB1Eu, 0x8BF9u, 0x9BD8u, 0xABBBu, 0xBB9Au,
    0x4A75u, 0x5A54u, 0x6A37u, 0x7A16u, 0x0AF1u, 0x1AD0u, 0x2AB3u, 0x3A92u,
    0xFD2Eu, 0xED0Fu, 0xDD6Cu, 0xCD4Du, 0xBDAAu, 0xAD8Bu, 0x9DE8u, 0x8DC9u,
    0x7C26u, 0x6C07u, 0x5C64u, 0x4C45u, 0x3CA2u, 0x2C83u, 0x1CE0u, 0x0CC1u,
    0xEF1Fu, 0xFF3Eu, 0xCF5Du, 0xDF7Cu, 0xAF9Bu, 0xBFBAu, 0x8FD9u, 0x9FF8u,
    0x6E17u, 0x7E36u, 0x4E55u, 0x5E74u, 0x2E93u, 0x3EB2u, 0x0ED1u, 0x1EF0u
  };
  uint16_t c = crc;
  size_t i;
  if (data == NULL) { return crc; }
  for (i = 0u; i < n; ++i) {
    const uint32_t idx = (((uint32_t)c >> 8) ^ (uint32_t)data[i]) & 0xFFu;
    c = (uint16_t)((((uint32_t)c << 8) ^ (uint32_t)crc16_table[idx]) & 0xFFFFu);
  }
  return c;
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
  if (w->n < w->cap) { w->p[w->n] = (uint8_t)(v & 0xFFu); }
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
  (void)memcpy(&bits, &d, sizeof bits);
  put_u64(w, bits);
}

static void put_reals(Writer *w, const fsw_real *x, size_t n)
{
  size_t i;
  for (i = 0u; i < n; ++i) { put_real(w, x[i]); }
}

static void put_flags(Writer *w, const uint8_t *f, size_t n)
{
  size_t i;
  for (i = 0u; i < n; ++i) { put_u8(w, f[i]); }
}

static uint32_t get_u8(Reader *r)
{
  uint32_t v = 0u;
  if (r->n < r->len) { v = r->p[r->n]; }
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
  (void)memcpy(&d, &bits, sizeof d);
  return (fsw_real)d;
}

static void get_reals(Reader *r, fsw_real *x, size_t n)
{
  size_t i;
  for (i = 0u; i < n; ++i) { x[i] = get_real(r); }
}

/* flags must be 0 or 1; returns 0 if any is not */
static int get_flags(Reader *r, uint8_t *f, size_t n)
{
  size_t i;
  int ok = 1;
  for (i = 0u; i < n; ++i) {
    const uint32_t v = get_u8(r);
    if (v > 1u) { ok = 0; }
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
  if (w->n + FSW_LINK_CRC_SIZE > w->cap) { return link_fail(err, FSW_LINK_E_SPACE); }
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
  if (m == NULL || buf == NULL || len == NULL) { return FSW_E_NULL_ARG; }
  if (num_rw > FSW_MAX_RW || num_css > FSW_MAX_CSS) { return link_fail(err, FSW_LINK_E_COUNT); }
  {
    size_t i; /* the thruster flags travel as bits: a flag other than 0/1 cannot */
    for (i = 0u; i < (size_t)FSW_MAX_THR; ++i) {
      if (m->thr_avail[i] > 1u) { return link_fail(err, FSW_LINK_E_COUNT); } }
  }
  if (!begin_packet(&w, buf, cap, payload)) { return link_fail(err, FSW_LINK_E_SPACE); }
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
  {
    uint64_t bits = 0u;
    size_t i;
    for (i = 0u; i < (size_t)FSW_MAX_THR; ++i) {
      if (m->thr_avail[i] != 0u) { bits |= (uint64_t)1u << i; } }
    put_u64(&w, bits);
  }
  put_reals(&w, m->B_B, 3u);
  put_reals(&w, m->r_N, 3u);
  put_reals(&w, m->v_N, 3u);
  put_u8(&w, m->mag_valid != 0u ? 1u : 0u);
  put_u8(&w, m->orbit_valid != 0u ? 1u : 0u);
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_encode_cmd(const FswAcsCmdMsg *m, uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap,
                              size_t *len, FswLinkError *err)
{
  Writer w;
  if (m == NULL || buf == NULL || len == NULL) { return FSW_E_NULL_ARG; }
  if (m->mode < 0 || m->mode > 255 || m->actuation < 0 || m->actuation > 255 || m->set_ref > 1u ||
      m->set_gains > 1u || m->set_policy > 1u || m->policy < 0 || m->policy > 255) {
    return link_fail(err, FSW_LINK_E_COUNT); }
  if (!begin_packet(&w, buf, cap, FSW_LINK_CMD_PAYLOAD)) { return link_fail(err, FSW_LINK_E_SPACE); }
  put_headers(&w, FSW_LINK_APID_CMD, 1u, seq, t_ns, FSW_LINK_CMD_PAYLOAD);
  put_u8(&w, (uint32_t)m->mode);
  put_u8(&w, (uint32_t)m->actuation);
  put_u8(&w, m->set_ref);
  put_u8(&w, m->set_gains);
  put_reals(&w, m->sigma_R0N, 3u);
  put_real(&w, m->K);
  put_real(&w, m->P);
  put_u8(&w, m->set_policy);
  put_u8(&w, (uint32_t)m->policy);
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_encode_actuator(const FswAcsActuatorMsg *m, uint8_t num_rw, uint8_t num_thr, uint8_t num_mtq,
                                   uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap, size_t *len,
                                   FswLinkError *err)
{
  Writer w;
  const size_t payload = FSW_LINK_ACTUATOR_PAYLOAD(num_rw, num_thr, num_mtq);
  if (m == NULL || buf == NULL || len == NULL) { return FSW_E_NULL_ARG; }
  if (num_rw > FSW_MAX_RW || num_thr > FSW_MAX_THR || num_mtq > FSW_MAX_MTQ) { return link_fail(err, FSW_LINK_E_COUNT); }
  if (!begin_packet(&w, buf, cap, payload)) { return link_fail(err, FSW_LINK_E_SPACE); }
  put_headers(&w, FSW_LINK_APID_ACTUATOR, 0u, seq, t_ns, payload);
  put_u8(&w, num_rw);
  put_u8(&w, num_thr);
  put_u8(&w, num_mtq);
  put_u8(&w, m->wheels_active != 0u ? 1u : 0u);
  put_u8(&w, m->thrusters_active != 0u ? 1u : 0u);
  put_u8(&w, m->mtq_active != 0u ? 1u : 0u);
  put_u16(&w, 0u);
  put_reals(&w, m->Lr_B, 3u);
  put_reals(&w, m->u_s, num_rw);
  put_reals(&w, m->V, num_rw);
  put_reals(&w, m->F, num_thr);
  put_reals(&w, m->t_on, num_thr);
  put_reals(&w, m->m_cmd, num_mtq);
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
  if (m == NULL || buf == NULL || len == NULL) { return FSW_E_NULL_ARG; }
  if (m->mode < 0 || m->mode > 255 || m->actuation < 0 || m->actuation > 255 || m->policy < 0 || m->policy > 255) {
    return link_fail(err, FSW_LINK_E_COUNT); }
  if (!begin_packet(&w, buf, cap, FSW_LINK_HEALTH_PAYLOAD)) { return link_fail(err, FSW_LINK_E_SPACE); }
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
  for (i = 0u; i < (size_t)FSW_ACS_NUM_STAGES; ++i) { put_u16(&w, status_bits(m->stage_status[i])); }
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
  put_u64(&w, m->rw_failed);
  put_u64(&w, m->rw_latched);
  put_u8(&w, (uint32_t)m->policy);
  put_u8(&w, m->detumbled != 0u ? 1u : 0u);
  put_u8(&w, m->dump_phase);
  put_u8(&w, 0u);
  put_u32(&w, m->dumps);
  put_reals(&w, m->h_w_B, 3u);
  put_real(&w, m->rate_est);
  put_reals(&w, m->tau_mtq_B, 3u);
  put_real(&w, m->prop_used);
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_parse(const uint8_t *buf, size_t n, FswLinkPacket *p, FswLinkError *err)
{
  Reader r;
  uint32_t w0, w1, data_len;
  size_t total;
  uint16_t crc;
  if (buf == NULL || p == NULL) { return FSW_E_NULL_ARG; }
  if (n < FSW_LINK_HEADER_SIZE + FSW_LINK_CRC_SIZE) { return link_fail(err, FSW_LINK_E_SHORT); }
  r.p = buf;
  r.n = 0u;
  r.len = n;
  w0 = get_u16(&r);
  w1 = get_u16(&r);
  data_len = get_u16(&r) + 1u;
  if ((w0 >> 13) != LINK_VERSION || ((w0 >> 11) & 1u) != 1u || (w1 >> 14) != LINK_SEQ_FLAGS) {
    return link_fail(err, FSW_LINK_E_HEADER); }
  if (data_len < FSW_LINK_SECONDARY_SIZE + FSW_LINK_CRC_SIZE) { return link_fail(err, FSW_LINK_E_HEADER); }
  total = FSW_LINK_PRIMARY_SIZE + (size_t)data_len;
  if (total > n) { return link_fail(err, FSW_LINK_E_SHORT); }
  crc = fsw_link_crc16(buf, total - FSW_LINK_CRC_SIZE, 0xFFFFu);
  if (crc != (uint16_t)(((uint32_t)buf[total - 2u] << 8) | buf[total - 1u])) { return link_fail(err, FSW_LINK_E_CRC); }
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
  if (p->apid != apid || p->type != type) { return link_fail(err, FSW_LINK_E_APID); }
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
  if (p == NULL || m == NULL || num_rw == NULL || num_css == NULL || p->payload == NULL) { return FSW_E_NULL_ARG; }
  if (expect(p, FSW_LINK_APID_SENSOR, 1u, &r, err) != FSW_OK) { return FSW_E_BAD_INPUT; }
  if (p->payload_len < FSW_LINK_SENSOR_PAYLOAD(0u, 0u)) { return link_fail(err, FSW_LINK_E_LENGTH); }
  nrw = get_u8(&r);
  ncss = get_u8(&r);
  if (nrw > FSW_MAX_RW || ncss > FSW_MAX_CSS) { return link_fail(err, FSW_LINK_E_COUNT); }
  if (p->payload_len != FSW_LINK_SENSOR_PAYLOAD(nrw, ncss)) { return link_fail(err, FSW_LINK_E_LENGTH); }
  (void)memset(&out, 0, sizeof out);
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
  {
    const uint64_t bits = get_u64(&r);
    size_t i;
    for (i = 0u; i < 64u; ++i) {
      const uint8_t b = (uint8_t)((bits >> i) & 1u);
      if (i < (size_t)FSW_MAX_THR) { out.thr_avail[i] = b; }
      else if (b != 0u) { ok = 0; } /* a thruster beyond the capacity */
    }
  }
  get_reals(&r, out.B_B, 3u);
  get_reals(&r, out.r_N, 3u);
  get_reals(&r, out.v_N, 3u);
  ok = get_flags(&r, &out.mag_valid, 1u) && ok;
  ok = get_flags(&r, &out.orbit_valid, 1u) && ok;
  if (!ok) { return link_fail(err, FSW_LINK_E_COUNT); }
  (void)memcpy(m, &out, sizeof out);
  *num_rw = (uint8_t)nrw;
  *num_css = (uint8_t)ncss;
  return link_ok(err);
}

FswStatus fsw_link_decode_cmd(const FswLinkPacket *p, FswAcsCmdMsg *m, FswLinkError *err)
{
  Reader r;
  uint32_t mode, act, set_ref, set_gains, set_policy;
  fsw_real sigma[3], K, P;
  if (p == NULL || m == NULL || p->payload == NULL) { return FSW_E_NULL_ARG; }
  if (expect(p, FSW_LINK_APID_CMD, 1u, &r, err) != FSW_OK) { return FSW_E_BAD_INPUT; }
  if (p->payload_len != FSW_LINK_CMD_PAYLOAD) { return link_fail(err, FSW_LINK_E_LENGTH); }
  mode = get_u8(&r);
  act = get_u8(&r);
  set_ref = get_u8(&r);
  set_gains = get_u8(&r);
  get_reals(&r, sigma, 3u);
  K = get_real(&r);
  P = get_real(&r);
  set_policy = get_u8(&r);
  if (set_ref > 1u || set_gains > 1u || set_policy > 1u) { return link_fail(err, FSW_LINK_E_COUNT); }
  m->mode = (int)mode;
  m->actuation = (int)act;
  m->set_ref = (uint8_t)set_ref;
  m->set_gains = (uint8_t)set_gains;
  (void)memcpy(m->sigma_R0N, sigma, sizeof sigma);
  m->K = K;
  m->P = P;
  m->set_policy = (uint8_t)set_policy;
  m->policy = (int)get_u8(&r);
  return link_ok(err);
}

FswStatus fsw_link_decode_actuator(const FswLinkPacket *p, FswAcsActuatorMsg *m, uint8_t *num_rw, uint8_t *num_thr,
                                   uint8_t *num_mtq, FswLinkError *err)
{
  Reader r;
  FswAcsActuatorMsg out;
  uint32_t nrw, nthr, nmtq, wa, ta, ma;
  if (p == NULL || m == NULL || num_rw == NULL || num_thr == NULL || num_mtq == NULL || p->payload == NULL) {
    return FSW_E_NULL_ARG; }
  if (expect(p, FSW_LINK_APID_ACTUATOR, 0u, &r, err) != FSW_OK) { return FSW_E_BAD_INPUT; }
  if (p->payload_len < FSW_LINK_ACTUATOR_PAYLOAD(0u, 0u, 0u)) { return link_fail(err, FSW_LINK_E_LENGTH); }
  /* the counts first (bytes 0..2): a version-1 packet has its flag
     wheels_active (0/1) at byte 2, so it fails on its length */
  nrw = get_u8(&r);
  nthr = get_u8(&r);
  nmtq = get_u8(&r);
  wa = get_u8(&r);
  ta = get_u8(&r);
  ma = get_u8(&r);
  if (nrw > FSW_MAX_RW || nthr > FSW_MAX_THR || nmtq > FSW_MAX_MTQ) { return link_fail(err, FSW_LINK_E_COUNT); }
  if (p->payload_len != FSW_LINK_ACTUATOR_PAYLOAD(nrw, nthr, nmtq)) { return link_fail(err, FSW_LINK_E_LENGTH); }
  if (wa > 1u || ta > 1u || ma > 1u || get_u16(&r) != 0u) { return link_fail(err, FSW_LINK_E_COUNT); }
  (void)memset(&out, 0, sizeof out);
  out.wheels_active = (uint8_t)wa;
  out.thrusters_active = (uint8_t)ta;
  out.mtq_active = (uint8_t)ma;
  get_reals(&r, out.Lr_B, 3u);
  get_reals(&r, out.u_s, nrw);
  get_reals(&r, out.V, nrw);
  get_reals(&r, out.F, nthr);
  get_reals(&r, out.t_on, nthr);
  get_reals(&r, out.m_cmd, nmtq);
  (void)memcpy(m, &out, sizeof out);
  *num_rw = (uint8_t)nrw;
  *num_thr = (uint8_t)nthr;
  *num_mtq = (uint8_t)nmtq;
  return link_ok(err);
}

FswStatus fsw_link_decode_health(const FswLinkPacket *p, FswAcsHealthMsg *m, FswLinkError *err)
{
  Reader r;
  FswAcsHealthMsg out;
  uint32_t safe, sun_valid, detumbled;
  size_t i;
  if (p == NULL || m == NULL || p->payload == NULL) { return FSW_E_NULL_ARG; }
  if (expect(p, FSW_LINK_APID_HEALTH, 0u, &r, err) != FSW_OK) { return FSW_E_BAD_INPUT; }
  if (p->payload_len != FSW_LINK_HEALTH_PAYLOAD) { return link_fail(err, FSW_LINK_E_LENGTH); }
  (void)memset(&out, 0, sizeof out);
  out.status = status_of(get_u16(&r));
  out.mode = (int)get_u8(&r);
  out.actuation = (int)get_u8(&r);
  safe = get_u8(&r);
  sun_valid = get_u8(&r);
  out.num_lit = (uint8_t)get_u8(&r);
  if (safe > 1u || sun_valid > 1u || get_u8(&r) != (uint32_t)FSW_ACS_NUM_STAGES) {
    return link_fail(err, FSW_LINK_E_COUNT); }
  out.safe_output = (uint8_t)safe;
  out.sun_valid = (uint8_t)sun_valid;
  out.cycles = get_u32(&r);
  out.mode_changes = get_u32(&r);
  for (i = 0u; i < (size_t)FSW_ACS_NUM_STAGES; ++i) { out.stage_status[i] = status_of(get_u16(&r)); }
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
  out.rw_failed = get_u64(&r);
  out.rw_latched = get_u64(&r);
  out.policy = (int)get_u8(&r);
  detumbled = get_u8(&r);
  out.dump_phase = (uint8_t)get_u8(&r);
  if (detumbled > 1u || get_u8(&r) != 0u) { return link_fail(err, FSW_LINK_E_COUNT); }
  out.detumbled = (uint8_t)detumbled;
  out.dumps = get_u32(&r);
  get_reals(&r, out.h_w_B, 3u);
  out.rate_est = get_real(&r);
  get_reals(&r, out.tau_mtq_B, 3u);
  out.prop_used = get_real(&r);
  (void)memcpy(m, &out, sizeof out);
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
  if (pkt == NULL || out == NULL || len == NULL) { return FSW_E_NULL_ARG; }
  if (cap < n + FSW_LINK_ASM_SIZE) { return FSW_E_BAD_INPUT; }
  (void)memmove(out + FSW_LINK_ASM_SIZE, pkt, n);
  for (i = 0u; i < FSW_LINK_ASM_SIZE; ++i) { out[i] = asm_byte(i); }
  *len = n + FSW_LINK_ASM_SIZE;
  return FSW_OK;
}

void fsw_link_deframer_init(FswLinkDeframer *d)
{
  if (d != NULL) { (void)memset(d, 0, sizeof *d); }
}

/* Drops the first byte of the buffer (a rejected marker start) and keeps
 * the rest for the hunt. */
static void deframer_slip(FswLinkDeframer *d)
{
  (void)memmove(d->buf, d->buf + 1, d->have - 1u);
  d->have--;
}

size_t fsw_link_deframer_push(FswLinkDeframer *d, const uint8_t *bytes, size_t n, const uint8_t **pkt,
                              size_t *pkt_len)
{
  size_t used = 0u;
  if (pkt != NULL) { *pkt = NULL; }
  if (pkt_len != NULL) { *pkt_len = 0u; }
  if (d == NULL || bytes == NULL || pkt == NULL || pkt_len == NULL) { return 0u; }
  while (used < n || d->have > 0u) {
    /* 1. the marker: the buffer always holds a prefix of it, or more */
    size_t i;
    int matched = 1;
    for (i = 0u; i < d->have && i < FSW_LINK_ASM_SIZE; ++i) {
      if (d->buf[i] != asm_byte(i)) { matched = 0; }
    }
    if (!matched) {
      deframer_slip(d);
      d->sync_slips++;
      continue;
    }
    if (d->have < FSW_LINK_ASM_SIZE + FSW_LINK_PRIMARY_SIZE) {
      if (used == n) { break; }
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
        if (take == 0u) { break; }
        (void)memcpy(d->buf + d->have, bytes + used, take);
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

/* ---- link status packet ------------------------------------------------- */

FswStatus fsw_link_encode_status(const FswLinkStatusMsg *m, uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap,
                                 size_t *len, FswLinkError *err)
{
  Writer w;
  if (m == NULL || buf == NULL || len == NULL) { return FSW_E_NULL_ARG; }
  if (!begin_packet(&w, buf, cap, FSW_LINK_STATUS_PAYLOAD)) { return link_fail(err, FSW_LINK_E_SPACE); }
  put_headers(&w, FSW_LINK_APID_LINK, 0u, seq, t_ns, FSW_LINK_STATUS_PAYLOAD);
  put_u32(&w, m->rx_packets);
  put_u32(&w, m->rx_crc);
  put_u32(&w, m->rx_rejected);
  put_u32(&w, m->rx_stale);
  put_u32(&w, m->missed);
  put_u32(&w, m->safe_entries);
  put_u32(&w, m->safe_cycles);
  put_u32(&w, m->recoveries);
  put_u32(&w, m->cycles);
  put_u16(&w, m->last_seq);
  put_u8(&w, m->link_safe != 0u ? 1u : 0u);
  put_u8(&w, FSW_LINK_ICD_VERSION);
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_decode_status(const FswLinkPacket *p, FswLinkStatusMsg *m, FswLinkError *err)
{
  Reader r;
  FswLinkStatusMsg out;
  uint32_t safe;
  if (p == NULL || m == NULL || p->payload == NULL) { return FSW_E_NULL_ARG; }
  if (expect(p, FSW_LINK_APID_LINK, 0u, &r, err) != FSW_OK) { return FSW_E_BAD_INPUT; }
  if (p->payload_len != FSW_LINK_STATUS_PAYLOAD) { return link_fail(err, FSW_LINK_E_LENGTH); }
  out.rx_packets = get_u32(&r);
  out.rx_crc = get_u32(&r);
  out.rx_rejected = get_u32(&r);
  out.rx_stale = get_u32(&r);
  out.missed = get_u32(&r);
  out.safe_entries = get_u32(&r);
  out.safe_cycles = get_u32(&r);
  out.recoveries = get_u32(&r);
  out.cycles = get_u32(&r);
  out.last_seq = (uint16_t)get_u16(&r);
  safe = get_u8(&r);
  out.icd_version = (uint8_t)get_u8(&r);
  if (out.icd_version != FSW_LINK_ICD_VERSION) { return link_fail(err, FSW_LINK_E_HEADER); }
  if (safe > 1u || out.last_seq >= FSW_LINK_SEQ_MODULO) { return link_fail(err, FSW_LINK_E_COUNT); }
  out.link_safe = (uint8_t)safe;
  (void)memcpy(m, &out, sizeof out);
  return link_ok(err);
}

/* ---- configuration image -------------------------------------------------- */

/* One entry per field of FswAcsConfig (nested module configs flattened),
 * in struct order; arrays at full capacity.  Encoder, decoder, size and
 * layout code all walk this table. */
typedef struct {
  size_t offset; /* of the first element */
  uint8_t real;  /* 1 fsw_real (f64 on the wire), 0 int (i32) */
  uint16_t count;
} CfgField;

#define CF_R(f, n) {offsetof(FswAcsConfig, f), 1u, (uint16_t)(n)}
#define CF_I(f) {offsetof(FswAcsConfig, f), 0u, 1u}
#define CF_PULSE_COMMON(p)                                                                                   \
  CF_I(p.common.num_thr), CF_R(p.common.F_max, FSW_MAX_THR), CF_R(p.common.t_min, 1),                        \
      CF_I(p.common.base_thrust_state), CF_R(p.common.init_off_pulse_on_time, 1)

static const CfgField kCfgFields[] = {
    CF_I(initial_mode), CF_I(initial_actuation),
    /* css */
    CF_I(css.num_css), CF_R(css.n_hat_B, 3 * FSW_MAX_CSS), CF_R(css.scale, FSW_MAX_CSS), CF_R(css.lit_threshold, 1),
    /* sunsafe, inertial, track */
    CF_R(sunsafe.s_cmd_B, 3), CF_R(sunsafe.min_unit_mag, 1), CF_R(sunsafe.small_angle, 1),
    CF_R(sunsafe.omega_search_B, 3), CF_R(sunsafe.sun_axis_spin_rate, 1), CF_R(inertial.sigma_R0N, 3),
    CF_R(track.sigma_R0R, 3),
    /* mrp_fb */
    CF_R(mrp_fb.K, 1), CF_R(mrp_fb.P, 1), CF_R(mrp_fb.K_i, 1), CF_R(mrp_fb.integral_limit, 1),
    CF_I(mrp_fb.control_law_type), CF_R(mrp_fb.known_torque_B, 3), CF_R(mrp_fb.I_B, 9), CF_I(mrp_fb.num_rw),
    CF_R(mrp_fb.gs_hat_B, 3 * FSW_MAX_RW), CF_R(mrp_fb.J_s, FSW_MAX_RW),
    /* lpf */
    CF_I(use_lpf), CF_R(lpf.h, 1), CF_R(lpf.omega_c, 1),
    /* wheel chain */
    CF_I(has_wheels), CF_I(rw_map.num_rw), CF_R(rw_map.gs_hat_B, 3 * FSW_MAX_RW), CF_I(rw_map.num_axes),
    CF_R(rw_map.ctrl_axes_B, 9), CF_I(rw_map.mode), CF_R(rw_map.eps_P, 1),
    CF_I(use_null), CF_I(rw_null.num_rw), CF_R(rw_null.gs_hat_B, 3 * FSW_MAX_RW), CF_R(rw_null.k_null, 1),
    CF_I(rw_null.scale_to_fit), CF_R(rw_null.u_max, FSW_MAX_RW), CF_R(Omega_des, FSW_MAX_RW),
    CF_I(rw_sat.num_rw), CF_R(rw_sat.u_max, FSW_MAX_RW), CF_I(rw_sat.mode),
    CF_I(use_volt), CF_I(rw_volt.num_rw), CF_R(rw_volt.V_min, 1), CF_R(rw_volt.V_max, 1), CF_R(rw_volt.K_V, 1),
    CF_R(rw_volt.u_max, FSW_MAX_RW), CF_R(rw_volt.J_s, FSW_MAX_RW), CF_I(rw_volt.gate_rate),
    CF_R(rw_volt.Omega_dot_max, FSW_MAX_RW),
    /* thruster chain */
    CF_I(has_thrusters), CF_R(thr_map.control_axes_B, 9), CF_I(thr_map.num_thr),
    CF_R(thr_map.r_thr_B, 3 * FSW_MAX_THR), CF_R(thr_map.gt_hat_B, 3 * FSW_MAX_THR), CF_R(thr_map.F_max, FSW_MAX_THR),
    CF_I(thr_map.thr_force_sign), CF_R(thr_map.ang_err_thresh, 1), CF_R(thr_map.epsilon, 1),
    CF_I(thr_map.use_2nd_loop), CF_I(thr_map.mode), CF_I(pulser),
    CF_PULSE_COMMON(pulse_rem),
    CF_PULSE_COMMON(pulse_schmitt), CF_R(pulse_schmitt.level_on, 1), CF_R(pulse_schmitt.level_off, 1),
    /* magnetorquers, DETUMBLE, NADIR (configuration image version 2) */
    CF_I(has_mtq), CF_I(mtq_map.num_mtq), CF_R(mtq_map.gt_hat_B, 3 * FSW_MAX_MTQ), CF_R(mtq_map.m_max, FSW_MAX_MTQ),
    CF_R(mtq_map.duty_max, 1), CF_I(bdot.variant), CF_R(bdot.k_bdot, 1), CF_I(bdot.normalize), CF_R(bdot.tau_f, 1),
    CF_I(bdot.max_missed), CF_R(bdot.m_max_B, 3), CF_R(bdot.omega_done, 1), CF_R(bdot.omega_reenter, 1),
    CF_R(bdot.t_persist, 1), CF_I(detumble_exit_mode), CF_I(has_orbit), CF_I(orbit.variant),
    CF_R(orbit.sigma_BdR, 3), CF_R(orbit.mu, 1),
    /* momentum management */
    CF_I(initial_policy), CF_I(use_thr_mom), CF_I(thr_mom.num_rw), CF_R(thr_mom.gs_hat_B, 3 * FSW_MAX_RW),
    CF_R(thr_mom.J_s, FSW_MAX_RW), CF_R(thr_mom.h_upper, 1), CF_R(thr_mom.h_lower, 1), CF_R(thr_mom.L_dump, 1),
    CF_R(thr_mom.t_pulse_max, 1), CF_R(thr_mom.t_min_pulse, 1), CF_R(thr_mom.t_coast, 1), CF_R(thr_mom.dt_cycle, 1),
    CF_I(thr_mom.num_thr), CF_R(thr_mom.F_max, FSW_MAX_THR), CF_R(thr_mom.Isp, 1), CF_I(use_mtq_desat),
    CF_I(mtq_desat.num_rw), CF_R(mtq_desat.gs_hat_B, 3 * FSW_MAX_RW), CF_R(mtq_desat.J_s, FSW_MAX_RW),
    CF_R(mtq_desat.k_desat, 1), CF_R(mtq_desat.h_target_B, 3), CF_R(mtq_desat.tau_max, 1),
    CF_R(mtq_desat.h_deadband, 1), CF_I(use_bias), CF_I(rw_bias.num_rw), CF_R(rw_bias.gs_hat_B, 3 * FSW_MAX_RW),
    CF_R(rw_bias.Omega_bias, FSW_MAX_RW), CF_R(rw_bias.Omega_keepout, 1), CF_R(rw_bias.Omega_hyst, 1)};

#define CFG_NUM_FIELDS (sizeof kCfgFields / sizeof kCfgFields[0])
#define CFG_MAGIC 0x4B434647u /* "KCFG" */

static size_t cfg_body_size(void)
{
  size_t i, n = 0u;
  for (i = 0u; i < CFG_NUM_FIELDS; ++i) { n += (size_t)kCfgFields[i].count * (kCfgFields[i].real != 0u ? 8u : 4u); }
  return n;
}

/* CRC-16 over (kind, count) of every entry: changes with the table. */
static uint16_t cfg_layout_code(void)
{
  size_t i;
  uint16_t crc = 0xFFFFu;
  for (i = 0u; i < CFG_NUM_FIELDS; ++i) {
    const uint8_t e[3] = {kCfgFields[i].real, (uint8_t)(kCfgFields[i].count >> 8),
                          (uint8_t)(kCfgFields[i].count & 0xFFu)};
    crc = fsw_link_crc16(e, sizeof e, crc);
  }
  return crc;
}

size_t fsw_link_config_size(void) { return FSW_LINK_CONFIG_HEADER + cfg_body_size() + FSW_LINK_CRC_SIZE; }

static void put_cfg_header(Writer *w)
{
  put_u32(w, CFG_MAGIC);
  put_u16(w, FSW_LINK_CONFIG_VERSION);
  put_u16(w, (uint32_t)CFG_NUM_FIELDS);
  put_u16(w, cfg_layout_code());
  put_u8(w, (uint32_t)FSW_MAX_RW);
  put_u8(w, (uint32_t)FSW_MAX_CSS);
  put_u8(w, (uint32_t)FSW_MAX_THR);
  put_u8(w, (uint32_t)FSW_MAX_MTQ);
  put_u16(w, 0u);
  put_u32(w, (uint32_t)cfg_body_size());
}

FswStatus fsw_link_config_encode(const FswAcsConfig *cfg, uint8_t *buf, size_t cap, size_t *len, FswLinkError *err)
{
  Writer w;
  size_t i, k;
  const unsigned char *base = (const unsigned char *)cfg;
  if (cfg == NULL || buf == NULL || len == NULL) { return FSW_E_NULL_ARG; }
  if (cap < fsw_link_config_size()) { return link_fail(err, FSW_LINK_E_SPACE); }
  w.p = buf;
  w.n = 0u;
  w.cap = cap;
  put_cfg_header(&w);
  for (i = 0u; i < CFG_NUM_FIELDS; ++i) {
    for (k = 0u; k < kCfgFields[i].count; ++k) {
      if (kCfgFields[i].real != 0u) {
        fsw_real x;
        memcpy(&x, base + kCfgFields[i].offset + k * sizeof x, sizeof x);
        put_real(&w, x);
      } else {
        int v;
        memcpy(&v, base + kCfgFields[i].offset + k * sizeof v, sizeof v);
        put_u32(&w, (uint32_t)(int32_t)v);
      }
    }
  }
  return finish_packet(&w, len, err);
}

FswStatus fsw_link_config_decode(const uint8_t *buf, size_t n, FswAcsConfig *cfg, FswLinkError *err)
{
  Writer ref;
  uint8_t hdr[FSW_LINK_CONFIG_HEADER];
  Reader r;
  size_t i, k;
  const size_t size = fsw_link_config_size();
  unsigned char *base = (unsigned char *)cfg;
  if (buf == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  if (n < FSW_LINK_CONFIG_HEADER) { return link_fail(err, FSW_LINK_E_SHORT); }
  /* the header this build writes, compared byte for byte */
  ref.p = hdr;
  ref.n = 0u;
  ref.cap = sizeof hdr;
  put_cfg_header(&ref);
  if (memcmp(buf, hdr, FSW_LINK_CONFIG_HEADER - 4u) != 0) { return link_fail(err, FSW_LINK_E_HEADER); }
  if (memcmp(buf + FSW_LINK_CONFIG_HEADER - 4u, hdr + FSW_LINK_CONFIG_HEADER - 4u, 4u) != 0 || n != size) {
    return link_fail(err, n < size ? FSW_LINK_E_SHORT : FSW_LINK_E_LENGTH); }
  if (fsw_link_crc16(buf, size - FSW_LINK_CRC_SIZE, 0xFFFFu) !=
      (uint16_t)(((uint32_t)buf[size - 2u] << 8) | buf[size - 1u])) {
    return link_fail(err, FSW_LINK_E_CRC); }
  r.p = buf + FSW_LINK_CONFIG_HEADER;
  r.n = 0u;
  r.len = size - FSW_LINK_CONFIG_HEADER - FSW_LINK_CRC_SIZE;
  (void)memset(cfg, 0, sizeof *cfg);
  for (i = 0u; i < CFG_NUM_FIELDS; ++i) {
    for (k = 0u; k < kCfgFields[i].count; ++k) {
      if (kCfgFields[i].real != 0u) {
        const fsw_real x = get_real(&r);
        memcpy(base + kCfgFields[i].offset + k * sizeof x, &x, sizeof x);
      } else {
        const int v = (int)(int32_t)get_u32(&r);
        memcpy(base + kCfgFields[i].offset + k * sizeof v, &v, sizeof v);
      }
    }
  }
  return link_ok(err);
}

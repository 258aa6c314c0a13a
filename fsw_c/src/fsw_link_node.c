/* fsw_link_node: the FSW end of the link (see fsw_link_node.h). */
#include "fsw/fsw_link_node.h"

#include <string.h>

#define HALF_SEQ (FSW_LINK_SEQ_MODULO / 2u)

FswStatus fsw_link_node_init(FswLinkNode *n, const FswAcsConfig *cfg, uint32_t max_missed, const char **bad_field)
{
  FswStatus s;
  if (bad_field != NULL) { *bad_field = NULL; }
  if (n == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  if (max_missed == 0u) {
    if (bad_field != NULL) { *bad_field = "max_missed"; }
    return FSW_E_CONFIG;
  }
  (void)memset(n, 0, sizeof *n);
  s = fsw_acs_init(&n->acs, cfg, bad_field);
  if (s != FSW_OK) { return s; }
  n->max_missed = max_missed;
  n->num_rw = (uint8_t)(cfg->has_wheels != 0 ? cfg->rw_map.num_rw : 0);
  n->num_thr = (uint8_t)(cfg->has_thrusters != 0 ? cfg->thr_map.num_thr : 0);
  n->num_mtq = (uint8_t)(cfg->has_mtq != 0 ? cfg->mtq_map.num_mtq : 0);
  return FSW_OK;
}

static uint16_t next_seq(FswLinkNode *n, int i)
{
  const uint16_t s = n->tx_seq[i];
  n->tx_seq[i] = (uint16_t)((s + 1u) % FSW_LINK_SEQ_MODULO);
  return s;
}

/* The encoders cannot fail here: the buffers hold the largest packet and the
 * counts come from a config fsw_acs_init accepted. */
static void put_actuator(FswLinkNode *n, int slot, uint64_t t_ns)
{
  (void)fsw_link_encode_actuator(&n->act, n->num_rw, n->num_thr, n->num_mtq, t_ns, next_seq(n, 0), n->out[slot],
                                 FSW_LINK_MAX_PACKET, &n->out_len[slot], NULL);
}

static void put_status(FswLinkNode *n, int slot, uint64_t t_ns)
{
  (void)fsw_link_encode_status(&n->link, t_ns, next_seq(n, 2), n->out[slot], FSW_LINK_MAX_PACKET,
                               &n->out_len[slot], NULL);
}

/* A packet that runs no cycle is answered by the link status alone, so
 * that the sender learns at once that it was processed. */
static int status_only(FswLinkNode *n)
{
  put_status(n, 0, n->last_t_ns);
  return 1;
}

/* The CRC a parsed packet ends with (it follows the payload). */
static uint16_t packet_crc(const FswLinkPacket *p)
{
  const uint8_t *c = p->payload + p->payload_len;
  return (uint16_t)(((uint32_t)c[0] << 8) | c[1]);
}

static int on_sensor(FswLinkNode *n, const FswAcsConfig *cfg, const FswLinkPacket *p)
{
  uint8_t nrw, ncss;
  if (fsw_link_decode_sensor(p, &n->sens, &nrw, &ncss, NULL) != FSW_OK) {
    n->link.rx_rejected++;
    return status_only(n);
  }
  if (n->have_last != 0u && n->have_replies != 0u && p->seq == n->link.last_seq && p->t_ns == n->last_t_ns &&
      packet_crc(p) == n->last_crc) {
    /* the same packet again (a retransmission: the sender lost a reply, or
     * the packet came twice): the last cycle's replies once more, no cycle */
    n->link.rx_stale++;
    n->resent++;
    (void)memcpy(n->out, n->last_out, sizeof n->out);
    (void)memcpy(n->out_len, n->last_out_len, sizeof n->out_len);
    return 3;
  }
  if (n->have_last != 0u) {
    const uint32_t ahead = ((uint32_t)p->seq + FSW_LINK_SEQ_MODULO - n->link.last_seq) % FSW_LINK_SEQ_MODULO;
    if (ahead == 0u || ahead >= HALF_SEQ || p->t_ns <= n->last_t_ns) {
      n->link.rx_stale++;
      return status_only(n);
    }
    n->link.missed += ahead - 1u;
  }
  n->have_last = 1u;
  n->link.last_seq = p->seq;
  n->last_t_ns = p->t_ns;
  n->consec_missed = 0u;
  if (n->link.link_safe != 0u) {
    n->link.link_safe = 0u;
    n->link.recoveries++;
  }
  (void)fsw_acs_cycle(&n->acs, cfg, &n->sens, n->have_cmd != 0u ? &n->cmd : NULL, &n->act, &n->hlth);
  n->link.cycles++;
  put_actuator(n, 0, p->t_ns);
  (void)fsw_link_encode_health(&n->hlth, p->t_ns, next_seq(n, 1), n->out[1], FSW_LINK_MAX_PACKET, &n->out_len[1],
                               NULL);
  put_status(n, 2, p->t_ns);
  n->last_crc = packet_crc(p);
  n->have_replies = 1u;
  (void)memcpy(n->last_out, n->out, sizeof n->out);
  (void)memcpy(n->last_out_len, n->out_len, sizeof n->out_len);
  return 3;
}

int fsw_link_node_receive(FswLinkNode *n, const FswAcsConfig *cfg, const uint8_t *buf, size_t len)
{
  FswLinkPacket p;
  FswLinkError why = FSW_LINK_OK;
  if (n == NULL || cfg == NULL || buf == NULL) { return 0; }
  n->link.rx_packets++;
  if (fsw_link_parse(buf, len, &p, &why) != FSW_OK) {
    if (why == FSW_LINK_E_CRC) {
      n->link.rx_crc++;
    } else {
      n->link.rx_rejected++; }
    return status_only(n);
  }
  if (p.apid == FSW_LINK_APID_SENSOR) { return on_sensor(n, cfg, &p); }
  if (fsw_link_decode_cmd(&p, &n->cmd, NULL) == FSW_OK) {
    n->have_cmd = 1u;
  } else {
    n->link.rx_rejected++; }
  return status_only(n);
}

int fsw_link_node_watchdog(FswLinkNode *n, uint64_t t_ns)
{
  if (n == NULL) { return 0; }
  n->link.missed++;
  n->consec_missed++;
  if (n->consec_missed < n->max_missed) { return 0; }
  n->have_replies = 0u; /* a retransmitted sensor packet is stale from now on */
  if (n->link.link_safe == 0u) {
    n->link.link_safe = 1u;
    n->link.safe_entries++;
  }
  (void)memset(&n->act, 0, sizeof n->act);
  n->link.safe_cycles++;
  put_actuator(n, 0, t_ns);
  put_status(n, 1, t_ns);
  return 2;
}

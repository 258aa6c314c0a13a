/* fsw_link_node: the FSW end of the link.  It owns an fsw_acs application
 * and turns received packets into replies, with the link supervision a
 * flight computer needs (docs/hwil.md, docs/icd.md):
 *
 *   sensor packet (0x101), accepted -> one fsw_acs_cycle, replies:
 *        actuator (0x181), health (0x182), link status (0x183), all with the
 *        sensor packet's t_ns;
 *   command packet (0x102)          -> kept, applied from the next cycle on;
 *                                      reply: link status;
 *   anything else or damaged        -> counted; reply: link status (so a
 *                                      sender knows at once that its packet
 *                                      was processed and not answered).
 *
 * A sensor packet is stale (counted, no cycle, link status only) when its sequence
 * count is not ahead of the last accepted one (modulo 16384: 1..8191 ahead)
 * or its t_ns is not later.  The last accepted packet itself again (same
 * sequence count, t_ns and CRC: a retransmission after a lost reply) is
 * counted stale too, runs no cycle, and is answered by the last cycle's
 * three replies once more, byte for byte (counted in `resent`); once the
 * node has gone link-safe it is plain stale.  A sequence gap of g counts g - 1 missed cycles.
 * The transport calls fsw_link_node_watchdog() once per control period in
 * which no sensor packet arrived: after max_missed consecutive missed
 * periods the node is link-safe and every watchdog call emits the safe
 * output of fsw_acs.h (all commands 0, nothing active) as an actuator packet
 * plus a link status packet; the next accepted sensor packet runs a normal
 * cycle and ends link-safe (a recovery).
 *
 * C99, no heap, no globals, no stdio; the reply packets live in the node. */
#ifndef FSW_LINK_NODE_H
#define FSW_LINK_NODE_H

#include <stddef.h>
#include <stdint.h>

#include "fsw/fsw_acs.h"
#include "fsw/fsw_link.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Capacity: FSW_LINK_NODE_MAX_REPLIES (fsw/fsw_config.h, with every capacity). */

typedef struct {
  FswAcsState acs;
  FswLinkStatusMsg link;     /* counters, sent in every link status packet */
  uint32_t max_missed;       /* consecutive missed periods before link-safe, >= 1 */
  uint32_t consec_missed;
  uint8_t have_last;         /* a sensor packet has been accepted */
  uint64_t last_t_ns;
  uint8_t have_cmd;
  FswAcsCmdMsg cmd;
  uint8_t num_rw, num_thr;   /* counts of the actuator packets (from the config) */
  uint8_t num_mtq;           /* rods in the actuator packets: 0 (FswAcsConfig has no rods yet) */
  uint16_t tx_seq[3];        /* per APID: actuator, health, link status */
  FswAcsSensorMsg sens;
  FswAcsActuatorMsg act;
  FswAcsHealthMsg hlth;
  uint8_t out[FSW_LINK_NODE_MAX_REPLIES][FSW_LINK_MAX_PACKET]; /* replies of the last call */
  size_t out_len[FSW_LINK_NODE_MAX_REPLIES];
  /* the last cycle's replies, answered again to a retransmitted sensor packet */
  uint8_t last_out[FSW_LINK_NODE_MAX_REPLIES][FSW_LINK_MAX_PACKET];
  size_t last_out_len[FSW_LINK_NODE_MAX_REPLIES];
  uint16_t last_crc;         /* CRC of the last accepted sensor packet */
  uint8_t have_replies;      /* last_out holds a cycle's replies (cleared on link-safe entry) */
  uint32_t resent;           /* [-] retransmitted sensor packets answered from last_out */
} FswLinkNode;

/* fsw_acs_init with cfg (kept by the caller, unchanged while the node runs)
 * and the counters cleared.  FSW_E_CONFIG (max_missed = 0, *bad_field =
 * "max_missed") or fsw_acs_init's status and bad field; FSW_E_NULL_ARG. */
FswStatus fsw_link_node_init(FswLinkNode *n, const FswAcsConfig *cfg, uint32_t max_missed, const char **bad_field);

/* One received packet (a datagram, or a deframed packet) buf[0..len).
 * Returns the number of reply packets now in n->out / n->out_len: 3 after a
 * cycle or a retransmission, 1 (the link status, stamped with the last accepted t_ns) for any
 * other packet; 0 for NULL arguments. */
int fsw_link_node_receive(FswLinkNode *n, const FswAcsConfig *cfg, const uint8_t *buf, size_t len);

/* A control period passed without a sensor packet; t_ns stamps the safe
 * output.  Returns the number of reply packets (0, or 2 while link-safe:
 * actuator and link status). */
int fsw_link_node_watchdog(FswLinkNode *n, uint64_t t_ns);

#ifdef __cplusplus
}
#endif

#endif /* FSW_LINK_NODE_H */

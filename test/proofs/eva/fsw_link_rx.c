/* Eva driver: the receiving side of the link (fsw/fsw_link.h, docs/icd.md,
 * docs/eva.md): any bytes of any length up to a buffer's size are parsed,
 * each decoder reads a packet that parsed, the deframer takes any byte
 * stream in two pushes and the configuration decoder any image.  No
 * arithmetic is made on the received reals: each is a copy of its 64 bits,
 * so the envelope analysis reports the non-finite ones (recorded).  Few
 * states kept apart (-eva-slevel 4; the parser's accepted and refused
 * packets by the split below) and loops unrolled up to 8 iterations only:
 * with the defaults each analysis took 53 to 74 s of CPU, this way about
 * 6 s; the joined loops of the configuration table give the copy alarms
 * recorded in alarms.txt, as in fsw_link_tx.
 * eva-options: -eva-slevel 4 -eva-auto-loop-unroll 8
 * eva-sources: fsw_link.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/fsw_link.h"

#define EVA_RX_BUF (FSW_LINK_ASM_SIZE + FSW_LINK_MAX_PACKET + 16u)
#define EVA_CFG_BUF 16384u /* above fsw_link_config_size() (13174 bytes at the default capacities) */

static void run(void)
{
  static uint8_t buf[EVA_RX_BUF];
  static FswLinkDeframer d;
  static FswAcsSensorMsg sens;
  static FswAcsCmdMsg cmd;
  static FswAcsActuatorMsg act;
  static FswAcsHealthMsg health;
  static FswLinkStatusMsg status;
  static FswAcsConfig cfg;
  static uint8_t img[EVA_CFG_BUF];
  FswLinkPacket p;
  FswLinkError err;
  FswStatus s;
  uint8_t n1, n2, n3;
  const uint8_t *pkt;
  size_t n, used, pkt_len;
  Frama_C_make_unknown((char *)buf, sizeof buf);
  n = Frama_C_size_t_interval(0u, sizeof buf);
  s = fsw_link_parse(buf, n, &p, &err);
  /*@ split s; */ /* the decoders read p only where it parsed */
  EVA_ENTRY(parse, s);
  if (s == FSW_OK) {
    EVA_ENTRY(decode_sensor, fsw_link_decode_sensor(&p, &sens, &n1, &n2, &err));
    EVA_ENTRY(decode_cmd, fsw_link_decode_cmd(&p, &cmd, &err));
    EVA_ENTRY(decode_actuator, fsw_link_decode_actuator(&p, &act, &n1, &n2, &n3, &err));
    EVA_ENTRY(decode_health, fsw_link_decode_health(&p, &health, &err));
    EVA_ENTRY(decode_status, fsw_link_decode_status(&p, &status, &err));
  }
  fsw_link_deframer_init(&d);
  EVA_ENTRY(deframer_init, 0);
  used = fsw_link_deframer_push(&d, buf, n, &pkt, &pkt_len);
  EVA_ENTRY(deframer_push, used <= n);
  Frama_C_make_unknown((char *)buf, sizeof buf);
  used = fsw_link_deframer_push(&d, buf, n, &pkt, &pkt_len);
  EVA_ENTRY(deframer_push, used <= n);
  Frama_C_make_unknown((char *)img, sizeof img);
  n = Frama_C_size_t_interval(0u, sizeof img);
  EVA_ENTRY(config_decode, fsw_link_config_decode(img, n, &cfg, &err));
}

EVA_MAINS

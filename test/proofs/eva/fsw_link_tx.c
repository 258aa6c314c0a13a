/* Eva driver: the sending side of the link (fsw/fsw_link.h, docs/icd.md,
 * docs/eva.md): each encoder writes any message (every byte unknown) with
 * any counts, sequence count and time stamp into a buffer of any capacity
 * from 0 to its size; the configuration encoder any configuration into any
 * capacity; the framer any packet of any length up to the largest packet
 * into any capacity; the CRC any bytes of any length.  No arithmetic is
 * made on the sent reals: each is a copy of its 64 bits, so the envelope
 * analysis reports the non-finite ones (recorded).  No state splitting and
 * loops unrolled up to 8 iterations only (the CRC's bit loop): with the
 * defaults the encoders alone take over 30 s of CPU; this way each analysis
 * takes about 4 s, and the joined loops of the writers and of the
 * configuration table give the access alarms recorded in alarms.txt.
 * eva-options: -eva-slevel 0 -eva-auto-loop-unroll 8
 * eva-sources: fsw_link.c fsw_status.c */
#include "eva_driver.h"

#include "fsw/fsw_link.h"

#define EVA_TX_BUF (FSW_LINK_ASM_SIZE + FSW_LINK_MAX_PACKET + 16u)
#define EVA_CFG_BUF 16384u /* above fsw_link_config_size() (13174 bytes at the default capacities) */

static size_t eva_cap(size_t size) { return Frama_C_size_t_interval(0u, size); }
static uint8_t eva_u8(void) { return (uint8_t)eva_int(0, 255); }
static uint16_t eva_u16(void) { return (uint16_t)eva_int(0, 65535); }

static void run(void)
{
  static uint8_t buf[EVA_TX_BUF];
  static uint8_t pkt[FSW_LINK_MAX_PACKET];
  static FswAcsSensorMsg sens;
  static FswAcsCmdMsg cmd;
  static FswAcsActuatorMsg act;
  static FswAcsHealthMsg health;
  static FswLinkStatusMsg status;
  static FswAcsConfig cfg;
  static uint8_t img[EVA_CFG_BUF];
  FswLinkError err;
  size_t len, n;
  Frama_C_make_unknown((char *)&sens, sizeof sens);
  Frama_C_make_unknown((char *)&cmd, sizeof cmd);
  Frama_C_make_unknown((char *)&act, sizeof act);
  Frama_C_make_unknown((char *)&health, sizeof health);
  Frama_C_make_unknown((char *)&status, sizeof status);
  Frama_C_make_unknown((char *)&cfg, sizeof cfg);
  EVA_ENTRY(encode_sensor, fsw_link_encode_sensor(&sens, eva_u8(), eva_u8(), eva_u16(), buf,
                                                   eva_cap(sizeof buf), &len, &err));
  EVA_ENTRY(encode_cmd, fsw_link_encode_cmd(&cmd, eva_u64(), eva_u16(), buf, eva_cap(sizeof buf), &len, &err));
  EVA_ENTRY(encode_actuator, fsw_link_encode_actuator(&act, eva_u8(), eva_u8(), eva_u8(), eva_u64(), eva_u16(),
                                                       buf, eva_cap(sizeof buf), &len, &err));
  EVA_ENTRY(encode_health, fsw_link_encode_health(&health, eva_u64(), eva_u16(), buf, eva_cap(sizeof buf), &len,
                                                   &err));
  EVA_ENTRY(encode_status, fsw_link_encode_status(&status, eva_u64(), eva_u16(), buf, eva_cap(sizeof buf), &len,
                                                   &err));
  EVA_ENTRY(config_size, fsw_link_config_size() > 0u);
  EVA_ENTRY(config_encode, fsw_link_config_encode(&cfg, img, eva_cap(sizeof img), &len, &err));
  Frama_C_make_unknown((char *)pkt, sizeof pkt);
  n = eva_cap(sizeof pkt);
  EVA_ENTRY(frame, fsw_link_frame(pkt, n, buf, eva_cap(sizeof buf), &len));
  EVA_ENTRY(crc16, fsw_link_crc16(pkt, n, (uint16_t)eva_int(0, 65535)));
}

EVA_MAINS

/* fsw_link: the wire codec between the FSW application and whatever feeds it
 * (the harness, a test bench): CCSDS Space Packets (CCSDS 133.0-B-2) with a
 * time secondary header, fixed big-endian payload layouts, a CRC-16 per
 * packet and, for byte streams, CCSDS attached sync markers.  The interface
 * control document is docs/icd.md (byte tables of every packet).
 *
 * Packet = primary header (6 bytes) | secondary header (8 bytes: the sample
 * time, uint64 ns, big-endian) | payload | CRC-16 (2 bytes, big-endian).
 * Primary header: version 0, type 1 (telecommand: to the FSW) or 0
 * (telemetry: from the FSW), secondary-header flag 1, APID (11 bits),
 * sequence flags 3 (unsegmented), sequence count (14 bits, per APID, mod
 * 16384), packet data length = bytes after the primary header - 1.  The CRC
 * is CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF, no
 * reflection, no final XOR; check value 0x29B1 for "123456789"), the CRC of
 * the CCSDS TC/TM frame standards, over every byte of the packet before it.
 * Reals travel as IEEE-754 binary64, big-endian, whatever fsw_real is.
 *
 * On a byte stream (serial) each packet is preceded by the attached sync
 * marker 1A CF FC 1D; the deframer hunts for it, takes the length from the
 * primary header, checks the CRC, and after any failure resumes its hunt one
 * byte after the rejected marker, so one corrupted packet costs one packet.
 *
 * C99, no heap, no globals, no stdio; every function is reentrant.  Decoders
 * never read past the given length and never write a message on failure. */
#ifndef FSW_LINK_H
#define FSW_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "fsw/fsw_acs.h"
#include "fsw/fsw_acs_msgs.h"
#include "fsw/fsw_config.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Application process identifiers (11 bits). */
#define FSW_LINK_APID_SENSOR 0x101u   /* to the FSW:   FswAcsSensorMsg (drives one cycle) */
#define FSW_LINK_APID_CMD 0x102u      /* to the FSW:   FswAcsCmdMsg                       */
#define FSW_LINK_APID_ACTUATOR 0x181u /* from the FSW: FswAcsActuatorMsg                  */
#define FSW_LINK_APID_HEALTH 0x182u   /* from the FSW: FswAcsHealthMsg                    */
#define FSW_LINK_APID_LINK 0x183u     /* from the FSW: FswLinkStatusMsg (link counters)   */

#define FSW_LINK_PRIMARY_SIZE 6u
#define FSW_LINK_SECONDARY_SIZE 8u
#define FSW_LINK_HEADER_SIZE (FSW_LINK_PRIMARY_SIZE + FSW_LINK_SECONDARY_SIZE)
#define FSW_LINK_CRC_SIZE 2u
#define FSW_LINK_ASM_SIZE 4u
#define FSW_LINK_SEQ_MODULO 16384u

/* ICD version: the layout of every packet of docs/icd.md.  Version 2
 * (2026-12-05) carries the magnetometer and orbit inputs, the momentum
 * policy command, the rod dipole outputs and the momentum telemetry; version
 * 1 had none of them.  It travels in the link status packet (payload byte
 * 39, reserved 0 in version 1) and a receiver rejects a status of another
 * version (FSW_LINK_E_HEADER); every other packet of version 1 differs in
 * payload size from its version-2 counterpart for any counts, so a version-1
 * peer's packets are rejected as FSW_LINK_E_LENGTH. */
#define FSW_LINK_ICD_VERSION 2u

/* Payload sizes [bytes] (docs/icd.md). */
#define FSW_LINK_SENSOR_PAYLOAD(num_rw, num_css) (158u + 9u * (size_t)(num_rw) + 9u * (size_t)(num_css))
#define FSW_LINK_CMD_PAYLOAD 46u
#define FSW_LINK_ACTUATOR_PAYLOAD(num_rw, num_thr, num_mtq)                                                  \
  (32u + 16u * (size_t)(num_rw) + 16u * (size_t)(num_thr) + 8u * (size_t)(num_mtq))
#define FSW_LINK_HEALTH_PAYLOAD (16u + 2u * (size_t)FSW_ACS_NUM_STAGES + 88u + 30u + 16u + 8u + 64u)
#define FSW_LINK_STATUS_PAYLOAD 40u

/* The largest packet any capacity allows (buffer size for a receiver): the
 * full sensor or actuator packet, or the health packet (larger than both
 * with small capacities); command and link status are smaller than health. */
#define FSW_LINK_MAX_(a, b) ((a) > (b) ? (a) : (b))
#define FSW_LINK_MAX_PAYLOAD                                                                                 \
  FSW_LINK_MAX_(FSW_LINK_MAX_(FSW_LINK_SENSOR_PAYLOAD(FSW_MAX_RW, FSW_MAX_CSS),                               \
                              FSW_LINK_ACTUATOR_PAYLOAD(FSW_MAX_RW, FSW_MAX_THR, FSW_MAX_MTQ)),               \
                FSW_LINK_HEALTH_PAYLOAD)
#define FSW_LINK_MAX_PACKET (FSW_LINK_HEADER_SIZE + FSW_LINK_CRC_SIZE + FSW_LINK_MAX_PAYLOAD)

/* Why a packet was rejected (the status is FSW_E_BAD_INPUT for all). */
typedef enum {
  FSW_LINK_OK = 0,
  FSW_LINK_E_SHORT = 1,   /* fewer bytes than a header and CRC, or than the length field says */
  FSW_LINK_E_HEADER = 2,  /* version, secondary-header flag or sequence flags not as above; a
                             link status of another FSW_LINK_ICD_VERSION                      */
  FSW_LINK_E_CRC = 3,     /* CRC mismatch                                                      */
  FSW_LINK_E_APID = 4,    /* not the APID (or packet type) the decoder expects                 */
  FSW_LINK_E_LENGTH = 5,  /* payload length does not match the counts it declares              */
  FSW_LINK_E_COUNT = 6,   /* a count beyond an FSW_MAX_* capacity, or a flag not 0/1           */
  FSW_LINK_E_SPACE = 7,   /* encoder: the output buffer is too small                           */
  FSW_LINK_E_AUTH = 8,    /* fsw_link_sec: no security trailer, or its MAC does not verify     */
  FSW_LINK_E_REPLAY = 9   /* fsw_link_sec: security sequence number already seen or too old    */
} FswLinkError;

/* A parsed packet: header fields and where its payload is (inside the
 * caller's buffer). */
typedef struct {
  uint16_t apid;
  uint8_t type;          /* 1 telecommand (to the FSW), 0 telemetry (from it) */
  uint16_t seq;          /* sequence count, 0..16383 */
  uint64_t t_ns;         /* secondary header: sample time [ns] */
  const uint8_t *payload;
  size_t payload_len;
  size_t packet_len;     /* bytes of the whole packet, CRC included */
} FswLinkPacket;

/* The FSW end's link counters (APID 0x183, sent after every health packet;
 * docs/icd.md).  Filled by fsw_link_node. */
typedef struct {
  uint32_t rx_packets;   /* [-] packets received (any, before checks)                  */
  uint32_t rx_crc;       /* [-] rejected: CRC mismatch                                  */
  uint32_t rx_rejected;  /* [-] rejected: short, header, APID, length or count         */
  uint32_t rx_stale;     /* [-] sensor packets rejected as duplicate, old or not later */
  uint32_t missed;       /* [-] control cycles without a sensor packet (gaps, watchdog) */
  uint32_t safe_entries; /* [-] entries into the link-safe output                       */
  uint32_t safe_cycles;  /* [-] safe actuator packets sent by the watchdog              */
  uint32_t recoveries;   /* [-] returns to normal cycles after link-safe               */
  uint32_t cycles;       /* [-] fsw_acs cycles run                                      */
  uint16_t last_seq;     /* [-] sequence count of the last accepted sensor packet       */
  uint8_t link_safe;     /* [-] 1 while the link-safe output is in force                */
  uint8_t icd_version;   /* [-] FSW_LINK_ICD_VERSION (the encoder writes its own)        */
} FswLinkStatusMsg;

/* CRC-16/CCITT-FALSE of n bytes, continuing from `crc` (0xFFFF to start). */
uint16_t fsw_link_crc16(const uint8_t *data, size_t n, uint16_t crc);

/* Encoders: one whole packet into buf[0..cap), its size in *len.  Returns
 * FSW_OK, FSW_E_NULL_ARG, or FSW_E_BAD_INPUT with *err = FSW_LINK_E_SPACE or
 * FSW_LINK_E_COUNT (counts beyond the capacities); err may be NULL. */
FswStatus fsw_link_encode_sensor(const FswAcsSensorMsg *m, uint8_t num_rw, uint8_t num_css, uint16_t seq,
                                 uint8_t *buf, size_t cap, size_t *len, FswLinkError *err);
FswStatus fsw_link_encode_cmd(const FswAcsCmdMsg *m, uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap,
                              size_t *len, FswLinkError *err);
FswStatus fsw_link_encode_actuator(const FswAcsActuatorMsg *m, uint8_t num_rw, uint8_t num_thr, uint8_t num_mtq,
                                   uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap, size_t *len,
                                   FswLinkError *err);
FswStatus fsw_link_encode_health(const FswAcsHealthMsg *m, uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap,
                                 size_t *len, FswLinkError *err);

FswStatus fsw_link_encode_status(const FswLinkStatusMsg *m, uint64_t t_ns, uint16_t seq, uint8_t *buf, size_t cap,
                                 size_t *len, FswLinkError *err);

/* Checks the primary header and the CRC of buf[0..n) (n may exceed the
 * packet: the length field decides) and fills *p.  FSW_OK or
 * FSW_E_BAD_INPUT with *err saying why; *p is written only on FSW_OK. */
FswStatus fsw_link_parse(const uint8_t *buf, size_t n, FswLinkPacket *p, FswLinkError *err);

/* Decoders of a parsed packet's payload.  The message (and the counts) are
 * written only on FSW_OK; fields beyond the counts are zeroed.  The sensor
 * decoder takes t_ns from the secondary header. */
FswStatus fsw_link_decode_sensor(const FswLinkPacket *p, FswAcsSensorMsg *m, uint8_t *num_rw, uint8_t *num_css,
                                 FswLinkError *err);
FswStatus fsw_link_decode_cmd(const FswLinkPacket *p, FswAcsCmdMsg *m, FswLinkError *err);
FswStatus fsw_link_decode_actuator(const FswLinkPacket *p, FswAcsActuatorMsg *m, uint8_t *num_rw, uint8_t *num_thr,
                                   uint8_t *num_mtq, FswLinkError *err);
FswStatus fsw_link_decode_health(const FswLinkPacket *p, FswAcsHealthMsg *m, FswLinkError *err);
FswStatus fsw_link_decode_status(const FswLinkPacket *p, FswLinkStatusMsg *m, FswLinkError *err);

/* ---- configuration image ------------------------------------------------- */

/* A serialised FswAcsConfig (docs/icd.md, "Configuration image"): a 20-byte
 * header (magic "KCFG", format version, field count, a layout code over the
 * field table, the capacities FSW_MAX_RW, FSW_MAX_CSS, FSW_MAX_THR,
 * FSW_MAX_MTQ, the body
 * length), the body (every field of one table, in order, arrays at full
 * capacity: int as i32, fsw_real as f64, big-endian) and a CRC-16 over all
 * bytes before it.  Encoder and decoder walk the same table, so they cannot
 * drift.  An image is accepted only by a build with the same table and
 * capacities.  The decoder does not judge values: fsw_acs_check() does. */
#define FSW_LINK_CONFIG_VERSION 2u
#define FSW_LINK_CONFIG_HEADER 20u

/* Size of an image in bytes (this build's table and capacities). */
size_t fsw_link_config_size(void);

/* FSW_OK, FSW_E_NULL_ARG, or FSW_E_BAD_INPUT with FSW_LINK_E_SPACE (cap too
 * small).  int fields travel as i32 (int is 32 bits on every supported
 * target). */
FswStatus fsw_link_config_encode(const FswAcsConfig *cfg, uint8_t *buf, size_t cap, size_t *len, FswLinkError *err);

/* Decodes an image of exactly n bytes.  FSW_OK, FSW_E_NULL_ARG, or
 * FSW_E_BAD_INPUT with FSW_LINK_E_SHORT (n shorter than the image),
 * FSW_LINK_E_HEADER (magic, version, field count, layout or capacities not
 * this build's), FSW_LINK_E_LENGTH (n or the body length not this build's
 * size) or FSW_LINK_E_CRC; *cfg is written only on FSW_OK. */
FswStatus fsw_link_config_decode(const uint8_t *buf, size_t n, FswAcsConfig *cfg, FswLinkError *err);

/* ---- byte streams ------------------------------------------------------- */

/* Writes the attached sync marker and the packet pkt[0..n) to out (n + 4
 * bytes).  FSW_OK, FSW_E_NULL_ARG, or FSW_E_BAD_INPUT when cap is short. */
FswStatus fsw_link_frame(const uint8_t *pkt, size_t n, uint8_t *out, size_t cap, size_t *len);

typedef struct {
  uint8_t buf[FSW_LINK_ASM_SIZE + FSW_LINK_MAX_PACKET]; /* marker + packet being assembled */
  size_t have;               /* bytes in buf */
  uint32_t packets;          /* packets delivered */
  uint32_t sync_slips;       /* bytes skipped while hunting for a marker */
  uint32_t rejected;         /* candidate packets rejected (header, length or CRC) */
} FswLinkDeframer;

void fsw_link_deframer_init(FswLinkDeframer *d);

/* Feeds bytes[0..n).  Consumes bytes until a whole valid packet is
 * assembled or the input is used up; returns the number consumed.  When a
 * packet is ready, *pkt points to it (inside d, valid until the next call)
 * with *pkt_len bytes; otherwise *pkt is NULL.  Call again with the
 * remaining bytes. */
size_t fsw_link_deframer_push(FswLinkDeframer *d, const uint8_t *bytes, size_t n, const uint8_t **pkt,
                              size_t *pkt_len);

#ifdef __cplusplus
}
#endif

#endif /* FSW_LINK_H */

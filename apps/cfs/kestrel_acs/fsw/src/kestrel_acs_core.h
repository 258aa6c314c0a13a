/* kestrel_acs_core: the logic of the KESTREL_ACS cFS application without cFE.
 *
 * The application (kestrel_acs_app.c) is a thin cFE layer: it receives
 * Software Bus messages, hands their bytes to the functions below, sends the
 * packets and events they produce, and registers the configuration table.
 * Everything that decides something lives here, in portable C99 under the
 * flight library's rules (no heap, no globals, no stdio, caller-owned state),
 * so the Kestrel test suite checks it without cFS (test/cfs/).
 *
 *   configuration table  -> kestrel_acs_core_table_check (validation),
 *                           kestrel_acs_core_configure (load: fsw_acs_init)
 *   ground command 0x18F0 -> kestrel_acs_core_ground_cmd (length-checked per
 *                           command code; applied at the next cycle)
 *   link packet 0x18F1    -> kestrel_acs_core_link: an ICD sensor packet runs
 *                           one fsw_acs_cycle and yields the actuator and
 *                           health packets; an ICD command packet becomes the
 *                           pending command
 *   housekeeping 0x18F2   -> kestrel_acs_core_hk (24-byte big-endian payload)
 *
 * Events are not sent from here (no cFE): each call appends what happened to
 * the core's small event list (id, type, two integers, one constant text)
 * and the application turns the list into cFE events.  docs/cfs.md is the
 * interface description. */
#ifndef KESTREL_ACS_CORE_H
#define KESTREL_ACS_CORE_H

#include <stddef.h>
#include <stdint.h>

#include "fsw/fsw_acs.h"
#include "fsw/fsw_link.h"
#include "fsw/fsw_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- configuration table ------------------------------------------------- */

/* Bytes reserved for a configuration image (fsw_link_config_size() of this
 * build must fit; 13174 with the default capacities).  The table (4 + this)
 * stays below cFE's default single-table limit of 16384 bytes. */
#define KESTREL_ACS_CONFIG_IMAGE_MAX 16000u

/* The cFE table "KESTREL_ACS.Config": a Kestrel configuration image
 * (fsw_link_config_encode format) and its length.  image_length is in the
 * table's native byte order (cFE tables are memory images); the image itself
 * is big-endian by its own definition. */
typedef struct {
  uint32_t image_length;                       /* [bytes] used bytes of image */
  uint8_t image[KESTREL_ACS_CONFIG_IMAGE_MAX]; /* [-] the configuration image   */
} KestrelAcsConfigTable;

/* ---- ground commands (message 0x18F0) ------------------------------------ */

#define KESTREL_ACS_NOOP_CC 0u
#define KESTREL_ACS_RESET_COUNTERS_CC 1u
#define KESTREL_ACS_SET_MODE_CC 2u
#define KESTREL_ACS_SET_ACTUATION_CC 3u
#define KESTREL_ACS_SET_REFERENCE_CC 4u
#define KESTREL_ACS_SET_GAINS_CC 5u
#define KESTREL_ACS_SET_MOMENTUM_POLICY_CC 6u
#define KESTREL_ACS_NUM_CC 7u

/* Payload lengths [bytes] after the 8-byte command header, big-endian fields:
 * SET_MODE/SET_ACTUATION/SET_MOMENTUM_POLICY: u8 value, u8 spare[3];
 * SET_REFERENCE: f64 sigma_R0N[3]; SET_GAINS: f64 K [N m], f64 P [N m s]. */
#define KESTREL_ACS_NOOP_LEN 0u
#define KESTREL_ACS_RESET_COUNTERS_LEN 0u
#define KESTREL_ACS_SET_MODE_LEN 4u
#define KESTREL_ACS_SET_ACTUATION_LEN 4u
#define KESTREL_ACS_SET_REFERENCE_LEN 24u
#define KESTREL_ACS_SET_GAINS_LEN 16u
#define KESTREL_ACS_SET_MOMENTUM_POLICY_LEN 4u

/* The link message (0x18F1) has one command code. */
#define KESTREL_ACS_LINK_CC 0u

/* ---- events -------------------------------------------------------------- */

typedef enum {
  KESTREL_ACS_EV_DEBUG = 0,
  KESTREL_ACS_EV_INFO = 1,
  KESTREL_ACS_EV_ERROR = 2,
  KESTREL_ACS_EV_CRITICAL = 3
} KestrelAcsEventType;

/* Event ids (the application's cFE event ids; texts in docs/cfs.md). */
#define KESTREL_ACS_EID_STARTUP 1u        /* INFO  application started                          */
#define KESTREL_ACS_EID_NOOP 2u           /* INFO  NOOP received                                */
#define KESTREL_ACS_EID_RESET 3u          /* INFO  counters reset                               */
#define KESTREL_ACS_EID_CMD_ACCEPTED 4u   /* INFO  a set command accepted: a = CC, b = value    */
#define KESTREL_ACS_EID_CMD_LEN 5u        /* ERROR wrong length: a = CC, b = length received    */
#define KESTREL_ACS_EID_CMD_CC 6u         /* ERROR unknown command code: a = CC                 */
#define KESTREL_ACS_EID_CMD_VALUE 7u      /* ERROR a value out of range: a = CC, text = field   */
#define KESTREL_ACS_EID_MID 8u            /* ERROR a message id the application does not take   */
#define KESTREL_ACS_EID_MODE 9u           /* INFO  mode in force changed: a = old, b = new      */
#define KESTREL_ACS_EID_CYCLE_ERR 10u     /* ERROR first error cycle of a run: a = status, text = stage */
#define KESTREL_ACS_EID_CYCLE_OK 11u      /* INFO  cycles good again: a = error cycles in the run */
#define KESTREL_ACS_EID_LINK_REJECT 12u   /* ERROR first refused link packet of a run: a = FswLinkError */
#define KESTREL_ACS_EID_TBL_OK 13u        /* INFO  configuration table accepted and in force    */
#define KESTREL_ACS_EID_TBL_BAD 14u       /* ERROR configuration table refused: text = field, a = status */
#define KESTREL_ACS_EID_TBL_ERR 15u       /* ERROR table services call failed (application)     */
#define KESTREL_ACS_EID_NO_CONFIG 16u     /* ERROR sensor packet with no configuration in force */
#define KESTREL_ACS_EID_INIT_ERR 17u      /* ERROR initialisation failed (application)          */

#define KESTREL_ACS_MAX_EVENTS 4

typedef struct {
  uint16_t id;      /* KESTREL_ACS_EID_*                          */
  uint8_t type;     /* KestrelAcsEventType                        */
  int32_t a, b;     /* numbers of the event (see the id)          */
  const char *text; /* a constant string (field or stage) or NULL */
} KestrelAcsEvent;

/* ---- housekeeping (message 0x08F0) --------------------------------------- */

#define KESTREL_ACS_HK_LEN 24u

/* ---- the core ------------------------------------------------------------ */

typedef struct {
  /* configuration in force and the FSW state */
  uint8_t config_loaded;        /* [-] 1: cfg is valid and acs initialised     */
  FswAcsConfig cfg;
  FswAcsConfig cfg_scratch;     /* [-] a table being checked               */
  FswAcsState acs;
  uint8_t num_rw, num_thr, num_mtq; /* [-] counts of the actuator packets     */
  /* the command applied with every cycle (the latest ICD command packet,
   * edited by ground commands), as the link node of kestrel-fsw keeps it */
  uint8_t have_cmd;
  FswAcsCmdMsg cmd;
  /* counters (housekeeping) */
  uint8_t command_count;        /* [-] ground commands accepted (wraps)        */
  uint8_t command_error_count;  /* [-] ground/link commands refused (wraps)    */
  uint32_t cycles;              /* [-] fsw_acs_cycle calls                     */
  uint32_t cycle_errors;        /* [-] cycles whose status was an error (< 0)      */
  uint32_t link_rejected;       /* [-] link packets refused by parse/decode    */
  uint32_t table_rejects;       /* [-] table validations refused               */
  FswStatus last_status;        /* [-] status of the last cycle                */
  /* event rate limiting */
  uint32_t err_run;             /* [-] consecutive error cycles                */
  uint8_t link_bad_run;         /* [-] a refused link packet was reported      */
  int last_mode;                /* [-] mode in force after the last cycle      */
  /* the last sensor packet that ran a cycle (a retransmission of it is
   * answered with the same replies, no cycle: kestrel-fsw's link node does so) */
  uint8_t have_last;
  uint16_t last_seq;
  uint64_t last_t_ns;
  uint16_t last_crc;
  uint32_t resent;              /* [-] retransmissions answered again          */
  /* link replies of the last sensor packet */
  uint16_t tx_seq[2];           /* [-] next sequence count: actuator, health  */
  FswAcsSensorMsg sens;
  FswAcsActuatorMsg act;
  FswAcsHealthMsg hlth;
  uint8_t act_pkt[FSW_LINK_MAX_PACKET];
  size_t act_len;
  uint8_t hlth_pkt[FSW_LINK_MAX_PACKET];
  size_t hlth_len;
  /* events of the last call */
  KestrelAcsEvent events[KESTREL_ACS_MAX_EVENTS];
  int num_events;
} KestrelAcsCore;

/* Everything zero: no configuration, counters 0. */
void kestrel_acs_core_init(KestrelAcsCore *c);

/* The table validation: the image length, fsw_link_config_decode (into the
 * caller's scratch config) and fsw_acs_check.  Returns FSW_OK or the failing
 * status; *bad_field names the refused field: "image_length" (0 or above the
 * table's room), "image" (decoder errors: "image: header", "image: length",
 * "image: CRC", "image: short") or fsw_acs_check's field.  Adds no event
 * and counts nothing (the table services may validate without loading):
 * kestrel_acs_core_table_refused() does that. */
FswStatus kestrel_acs_core_table_check(const KestrelAcsConfigTable *t, FswAcsConfig *scratch,
                                       const char **bad_field);

/* Counts a refused table and adds the KESTREL_ACS_EID_TBL_BAD event. */
void kestrel_acs_core_table_refused(KestrelAcsCore *c, FswStatus s, const char *bad_field);

/* A new table in force: check, decode, fsw_acs_init (the FSW state starts
 * afresh), counts from the config, pending command dropped.  On failure the
 * previous configuration stays in force and the refusal is counted and
 * reported; FSW_OK adds KESTREL_ACS_EID_TBL_OK. */
FswStatus kestrel_acs_core_configure(KestrelAcsCore *c, const KestrelAcsConfigTable *t);

/* A ground command: cc and its payload (the bytes after the command header).
 * Returns 1 when accepted (command_count + 1), 0 when refused
 * (command_error_count + 1, an ERROR event, nothing applied).  NOOP and
 * RESET_COUNTERS act at once; the set commands edit the pending command,
 * applied from the next cycle on. */
int kestrel_acs_core_ground_cmd(KestrelAcsCore *c, uint8_t cc, const uint8_t *payload, size_t len);

/* A link message (0x18F1): cc must be 0 and the payload one ICD packet.
 * Returns the number of reply packets now in act_pkt/hlth_pkt: 2 after a
 * sensor packet (a cycle ran: its status is last_status; or the packet was
 * the last one again, same sequence count, t_ns and CRC, a retransmission
 * after a lost reply: the same replies once more, no cycle, counted in
 * `resent`), 0 otherwise
 * (a command packet kept, or a refused packet counted in link_rejected, or
 * a wrong cc counted in command_error_count). */
int kestrel_acs_core_link(KestrelAcsCore *c, uint8_t cc, const uint8_t *payload, size_t len);

/* The housekeeping payload, KESTREL_ACS_HK_LEN bytes, big-endian:
 *   0 u8 command_count, 1 u8 command_error_count, 2 u8 mode in force,
 *   3 u8 config_loaded, 4 u32 cycles, 8 u32 cycle_errors,
 *   12 u32 link_rejected, 16 u32 last_status (as u32), 20 u32 table_rejects. */
void kestrel_acs_core_hk(const KestrelAcsCore *c, uint8_t out[KESTREL_ACS_HK_LEN]);

/* The payload length [bytes] a ground command code takes; -1 for an
 * unknown code. */
int kestrel_acs_core_cmd_len(uint8_t cc);

/* Clears the event list (the application calls it after sending them). */
void kestrel_acs_core_clear_events(KestrelAcsCore *c);

#ifdef __cplusplus
}
#endif

#endif /* KESTREL_ACS_CORE_H */

/* KESTREL_ACS message ids (cFS v1: message id = CCSDS stream id; topic ids
 * 0xF0..0xF2).  A mission whose topic ids clash changes them here (or
 * overrides this header) and tells the ground system and the harness. */
#ifndef KESTREL_ACS_MSGIDS_H
#define KESTREL_ACS_MSGIDS_H

/* commands (to the application) */
#define KESTREL_ACS_CMD_MID 0x18F0     /* ground commands, CC 0..6 (docs/cfs.md)          */
#define KESTREL_ACS_LINK_MID 0x18F1    /* CC 0: one Kestrel ICD packet (0x101 or 0x102)   */
#define KESTREL_ACS_SEND_HK_MID 0x18F2 /* housekeeping request (scheduler), no payload    */

/* telemetry (from the application) */
#define KESTREL_ACS_HK_TLM_MID 0x08F0       /* housekeeping, 24-byte payload              */
#define KESTREL_ACS_ACTUATOR_TLM_MID 0x08F1 /* the ICD actuator packet (APID 0x181)       */
#define KESTREL_ACS_HEALTH_TLM_MID 0x08F2   /* the ICD health packet (APID 0x182)         */

#endif /* KESTREL_ACS_MSGIDS_H */

/* KESTREL_ACS: the Kestrel attitude-control flight software as a cFS
 * application.  This file is the cFE layer only: Software Bus pipe, table
 * registration, events and telemetry.  The decisions live in the cFE-free
 * core (kestrel_acs_core.c), which the Kestrel test suite tests without
 * cFS.  Interface: docs/cfs.md of the Kestrel repository. */
#include <string.h>

#include "cfe.h"

#include "kestrel_acs_core.h"
#include "kestrel_acs_msgids.h"

#define KESTREL_ACS_PIPE_DEPTH 32
#define KESTREL_ACS_PIPE_NAME "KESTREL_ACS_PIPE"
#define KESTREL_ACS_TABLE_NAME "Config"
#define KESTREL_ACS_TABLE_FILE "/cf/kestrel_acs_cfg.tbl"
#define KESTREL_ACS_PERF_ID 91

/* telemetry messages: the cFE header, then the payload */
typedef struct {
  CFE_MSG_TelemetryHeader_t TelemetryHeader;
  uint8 Payload[KESTREL_ACS_HK_LEN];
} KESTREL_ACS_HkTlm_t;

typedef struct {
  CFE_MSG_TelemetryHeader_t TelemetryHeader;
  uint8 Packet[FSW_LINK_MAX_PACKET]; /* one Kestrel ICD packet */
} KESTREL_ACS_PacketTlm_t;

typedef struct {
  uint32 RunStatus;
  CFE_SB_PipeId_t CommandPipe;
  CFE_TBL_Handle_t TblHandle;
  CFE_ES_AppId_t AppId;
  KESTREL_ACS_HkTlm_t HkTlm;
  KESTREL_ACS_PacketTlm_t ActTlm;
  KESTREL_ACS_PacketTlm_t HealthTlm;
  FswAcsConfig ValidateScratch; /* the validation function's decode target */
  KestrelAcsCore Core;
} KESTREL_ACS_Data_t;

/* The application's data: one instance, as every cFS application keeps it
 * (the core is about 97 KB: not on the task stack). */
static KESTREL_ACS_Data_t KESTREL_ACS_Data;

void KESTREL_ACS_AppMain(void);

/* The library's assertion hook (fsw_status.h): a violated precondition is
 * logged and the library returns FSW_E_NULL_ARG, which the cycle status and
 * the housekeeping then show. */
void fsw_assert_failed(const char *file, int line)
{
  CFE_ES_WriteToSysLog("KESTREL_ACS: FSW assertion failed at %s:%d\n", file, line);
}

static const char *mode_name(int m)
{
  switch (m) {
  case FSW_ACS_MODE_SUN_SAFE: return "SUN_SAFE";
  case FSW_ACS_MODE_INERTIAL: return "INERTIAL";
  case FSW_ACS_MODE_DETUMBLE: return "DETUMBLE";
  case FSW_ACS_MODE_NADIR: return "NADIR";
  default: return "?";
  }
}

static const char *cc_name(int cc)
{
  static const char *const names[KESTREL_ACS_NUM_CC] = {"NOOP",         "RESET_COUNTERS", "SET_MODE",
                                                        "SET_ACTUATION", "SET_REFERENCE", "SET_GAINS",
                                                        "SET_MOMENTUM_POLICY"};
  return cc >= 0 && cc < (int)KESTREL_ACS_NUM_CC ? names[cc] : "?";
}

static uint16 evs_type(uint8_t t)
{
  switch (t) {
  case KESTREL_ACS_EV_DEBUG: return CFE_EVS_EventType_DEBUG;
  case KESTREL_ACS_EV_INFO: return CFE_EVS_EventType_INFORMATION;
  case KESTREL_ACS_EV_CRITICAL: return CFE_EVS_EventType_CRITICAL;
  default: return CFE_EVS_EventType_ERROR;
  }
}

/* The core's events as cFE events (texts: docs/cfs.md). */
static void KESTREL_ACS_SendEvents(void)
{
  KestrelAcsCore *c = &KESTREL_ACS_Data.Core;
  int i;
  for (i = 0; i < c->num_events; ++i) {
    const KestrelAcsEvent *e = &c->events[i];
    const uint16 id = e->id, ty = evs_type(e->type);
    const CFE_ES_AppId_t app = KESTREL_ACS_Data.AppId;
    const char *text = e->text != NULL ? e->text : "";
    switch (e->id) {
    case KESTREL_ACS_EID_NOOP:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: NOOP command");
      break;
    case KESTREL_ACS_EID_RESET:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: RESET_COUNTERS command");
      break;
    case KESTREL_ACS_EID_CMD_ACCEPTED:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: %s command accepted (value %ld), applied from the next cycle",
                                 cc_name((int)e->a), (long)e->b);
      break;
    case KESTREL_ACS_EID_CMD_LEN:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: command length refused: CC %ld, payload %ld bytes, expected %d",
                                 (long)e->a, (long)e->b, kestrel_acs_core_cmd_len((uint8_t)e->a));
      break;
    case KESTREL_ACS_EID_CMD_CC:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: invalid command code %ld", (long)e->a);
      break;
    case KESTREL_ACS_EID_CMD_VALUE:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: %s command refused: field '%s' out of range",
                                 cc_name((int)e->a), text);
      break;
    case KESTREL_ACS_EID_MODE:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: mode %s -> %s", mode_name((int)e->a),
                                 mode_name((int)e->b));
      break;
    case KESTREL_ACS_EID_CYCLE_ERR:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: cycle error %s (status %ld) in '%s', safe output sent",
                                 fsw_status_name((FswStatus)e->a), (long)e->a, text);
      break;
    case KESTREL_ACS_EID_CYCLE_OK:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: cycles good again after %ld error cycles", (long)e->a);
      break;
    case KESTREL_ACS_EID_LINK_REJECT:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: link packet refused (link error %ld)", (long)e->a);
      break;
    case KESTREL_ACS_EID_TBL_OK:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: config table accepted (%ld-byte image), mode %s",
                                 (long)e->b, mode_name((int)e->a));
      break;
    case KESTREL_ACS_EID_TBL_BAD:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: config table refused: field '%s' (status %ld)", text,
                                 (long)e->a);
      break;
    case KESTREL_ACS_EID_NO_CONFIG:
      CFE_EVS_SendEventWithAppID(id, ty, app,
                                 "KESTREL_ACS: no configuration in force: sensor packets get the safe output");
      break;
    default:
      CFE_EVS_SendEventWithAppID(id, ty, app, "KESTREL_ACS: event %u (%ld, %ld)", (unsigned)id, (long)e->a,
                                 (long)e->b);
      break;
    }
  }
  kestrel_acs_core_clear_events(c);
}

/* cFE table validation: decode + fsw_acs_check, the bad field in the event.
 * This cFE calls it from CFE_TBL_Load and, for a ground VALIDATE command,
 * from this application's CFE_TBL_Manage; the events name the application
 * explicitly so that a cFE validating from its own task reports them right. */
static int32 KESTREL_ACS_ValidateConfig(void *TblPtr)
{
  const char *field = NULL;
  const FswStatus s =
      kestrel_acs_core_table_check((const KestrelAcsConfigTable *)TblPtr, &KESTREL_ACS_Data.ValidateScratch, &field);
  if (s == FSW_OK) return CFE_SUCCESS;
  kestrel_acs_core_table_refused(&KESTREL_ACS_Data.Core, s, field);
  KESTREL_ACS_SendEvents();
  return (int32)-1;
}

/* Table management: a new (validated) table is put in force and the FSW
 * state starts afresh (fsw_acs_init). */
static void KESTREL_ACS_ManageTable(void)
{
  void *addr = NULL;
  CFE_Status_t st;
  CFE_TBL_Manage(KESTREL_ACS_Data.TblHandle);
  st = CFE_TBL_GetAddress(&addr, KESTREL_ACS_Data.TblHandle);
  if (st == CFE_TBL_INFO_UPDATED && addr != NULL) {
    (void)kestrel_acs_core_configure(&KESTREL_ACS_Data.Core, (const KestrelAcsConfigTable *)addr);
    KESTREL_ACS_SendEvents();
  }
  if (st == CFE_SUCCESS || st == CFE_TBL_INFO_UPDATED) CFE_TBL_ReleaseAddress(KESTREL_ACS_Data.TblHandle);
}

static void KESTREL_ACS_SendPacket(KESTREL_ACS_PacketTlm_t *t, const uint8_t *pkt, size_t len)
{
  memcpy(t->Packet, pkt, len);
  CFE_MSG_SetSize(CFE_MSG_PTR(t->TelemetryHeader), sizeof(t->TelemetryHeader) + len);
  CFE_SB_TimeStampMsg(CFE_MSG_PTR(t->TelemetryHeader));
  CFE_SB_TransmitMsg(CFE_MSG_PTR(t->TelemetryHeader), true);
}

static void KESTREL_ACS_SendHk(void)
{
  KESTREL_ACS_ManageTable();
  kestrel_acs_core_hk(&KESTREL_ACS_Data.Core, KESTREL_ACS_Data.HkTlm.Payload);
  CFE_SB_TimeStampMsg(CFE_MSG_PTR(KESTREL_ACS_Data.HkTlm.TelemetryHeader));
  CFE_SB_TransmitMsg(CFE_MSG_PTR(KESTREL_ACS_Data.HkTlm.TelemetryHeader), true);
}

static void KESTREL_ACS_ProcessMsg(const CFE_SB_Buffer_t *buf)
{
  CFE_SB_MsgId_t mid = CFE_SB_INVALID_MSG_ID;
  CFE_MSG_FcnCode_t cc = 0;
  CFE_MSG_Size_t size = 0;
  const uint8_t *bytes = (const uint8_t *)buf;
  const size_t hdr = sizeof(CFE_MSG_CommandHeader_t);
  size_t payload_len;
  KestrelAcsCore *c = &KESTREL_ACS_Data.Core;

  CFE_MSG_GetMsgId(&buf->Msg, &mid);
  CFE_MSG_GetSize(&buf->Msg, &size);
  CFE_MSG_GetFcnCode(&buf->Msg, &cc);
  payload_len = size >= hdr ? size - hdr : 0u;

  switch (CFE_SB_MsgIdToValue(mid)) {
  case KESTREL_ACS_LINK_MID:
    if (size < hdr) {
      (void)kestrel_acs_core_link(c, (uint8_t)cc, NULL, 0u);
    } else if (kestrel_acs_core_link(c, (uint8_t)cc, bytes + hdr, payload_len) == 2) {
      KESTREL_ACS_SendPacket(&KESTREL_ACS_Data.ActTlm, c->act_pkt, c->act_len);
      KESTREL_ACS_SendPacket(&KESTREL_ACS_Data.HealthTlm, c->hlth_pkt, c->hlth_len);
    }
    break;
  case KESTREL_ACS_CMD_MID:
    (void)kestrel_acs_core_ground_cmd(c, (uint8_t)cc, size >= hdr ? bytes + hdr : NULL,
                                      size >= hdr ? payload_len : (size_t)0xFFFFu);
    break;
  case KESTREL_ACS_SEND_HK_MID:
    if (size != hdr) {
      c->command_error_count++;
      CFE_EVS_SendEvent(KESTREL_ACS_EID_CMD_LEN, CFE_EVS_EventType_ERROR,
                        "KESTREL_ACS: housekeeping request length %lu refused, expected %lu", (unsigned long)size,
                        (unsigned long)hdr);
    } else {
      KESTREL_ACS_SendHk();
    }
    break;
  default:
    c->command_error_count++;
    CFE_EVS_SendEvent(KESTREL_ACS_EID_MID, CFE_EVS_EventType_ERROR, "KESTREL_ACS: invalid message id 0x%04X",
                      (unsigned int)CFE_SB_MsgIdToValue(mid));
    break;
  }
  KESTREL_ACS_SendEvents();
}

static CFE_Status_t KESTREL_ACS_Init(void)
{
  CFE_Status_t st;
  KESTREL_ACS_Data.RunStatus = CFE_ES_RunStatus_APP_RUN;
  kestrel_acs_core_init(&KESTREL_ACS_Data.Core);
  st = CFE_EVS_Register(NULL, 0, CFE_EVS_EventFilter_BINARY);
  if (st != CFE_SUCCESS) {
    CFE_ES_WriteToSysLog("KESTREL_ACS: CFE_EVS_Register failed, RC = 0x%08lX\n", (unsigned long)(uint32)st);
    return st;
  }
  CFE_ES_GetAppID(&KESTREL_ACS_Data.AppId);
  CFE_MSG_Init(CFE_MSG_PTR(KESTREL_ACS_Data.HkTlm.TelemetryHeader), CFE_SB_ValueToMsgId(KESTREL_ACS_HK_TLM_MID),
               sizeof(KESTREL_ACS_Data.HkTlm));
  CFE_MSG_Init(CFE_MSG_PTR(KESTREL_ACS_Data.ActTlm.TelemetryHeader),
               CFE_SB_ValueToMsgId(KESTREL_ACS_ACTUATOR_TLM_MID), sizeof(KESTREL_ACS_Data.ActTlm));
  CFE_MSG_Init(CFE_MSG_PTR(KESTREL_ACS_Data.HealthTlm.TelemetryHeader),
               CFE_SB_ValueToMsgId(KESTREL_ACS_HEALTH_TLM_MID), sizeof(KESTREL_ACS_Data.HealthTlm));

  st = CFE_SB_CreatePipe(&KESTREL_ACS_Data.CommandPipe, KESTREL_ACS_PIPE_DEPTH, KESTREL_ACS_PIPE_NAME);
  if (st == CFE_SUCCESS)
    st = CFE_SB_Subscribe(CFE_SB_ValueToMsgId(KESTREL_ACS_CMD_MID), KESTREL_ACS_Data.CommandPipe);
  if (st == CFE_SUCCESS)
    st = CFE_SB_Subscribe(CFE_SB_ValueToMsgId(KESTREL_ACS_LINK_MID), KESTREL_ACS_Data.CommandPipe);
  if (st == CFE_SUCCESS)
    st = CFE_SB_Subscribe(CFE_SB_ValueToMsgId(KESTREL_ACS_SEND_HK_MID), KESTREL_ACS_Data.CommandPipe);
  if (st != CFE_SUCCESS) {
    CFE_EVS_SendEvent(KESTREL_ACS_EID_INIT_ERR, CFE_EVS_EventType_ERROR,
                      "KESTREL_ACS: Software Bus pipe setup failed, RC = 0x%08lX", (unsigned long)(uint32)st);
    return st;
  }

  st = CFE_TBL_Register(&KESTREL_ACS_Data.TblHandle, KESTREL_ACS_TABLE_NAME, sizeof(KestrelAcsConfigTable),
                        CFE_TBL_OPT_DEFAULT, KESTREL_ACS_ValidateConfig);
  if (st != CFE_SUCCESS) {
    CFE_EVS_SendEvent(KESTREL_ACS_EID_TBL_ERR, CFE_EVS_EventType_ERROR,
                      "KESTREL_ACS: config table registration failed, RC = 0x%08lX", (unsigned long)(uint32)st);
    return st;
  }
  CFE_EVS_SendEvent(KESTREL_ACS_EID_STARTUP, CFE_EVS_EventType_INFORMATION,
                    "KESTREL_ACS: initialized (config image %lu bytes, table %s)",
                    (unsigned long)fsw_link_config_size(), KESTREL_ACS_TABLE_FILE);
  /* A refused default table is reported by the validation function; the
   * application then runs without a configuration (safe output) until a
   * good table is loaded. */
  st = CFE_TBL_Load(KESTREL_ACS_Data.TblHandle, CFE_TBL_SRC_FILE, KESTREL_ACS_TABLE_FILE);
  if (st != CFE_SUCCESS)
    CFE_EVS_SendEvent(KESTREL_ACS_EID_TBL_ERR, CFE_EVS_EventType_ERROR,
                      "KESTREL_ACS: config table load from %s failed, RC = 0x%08lX", KESTREL_ACS_TABLE_FILE,
                      (unsigned long)(uint32)st);
  KESTREL_ACS_ManageTable();
  return CFE_SUCCESS;
}

void KESTREL_ACS_AppMain(void)
{
  CFE_SB_Buffer_t *buf = NULL;
  CFE_Status_t st;
  CFE_ES_PerfLogEntry(KESTREL_ACS_PERF_ID);
  if (KESTREL_ACS_Init() != CFE_SUCCESS) KESTREL_ACS_Data.RunStatus = CFE_ES_RunStatus_APP_ERROR;
  while (CFE_ES_RunLoop(&KESTREL_ACS_Data.RunStatus) == true) {
    CFE_ES_PerfLogExit(KESTREL_ACS_PERF_ID);
    st = CFE_SB_ReceiveBuffer(&buf, KESTREL_ACS_Data.CommandPipe, CFE_SB_PEND_FOREVER);
    CFE_ES_PerfLogEntry(KESTREL_ACS_PERF_ID);
    if (st == CFE_SUCCESS && buf != NULL) {
      KESTREL_ACS_ProcessMsg(buf);
    } else {
      CFE_EVS_SendEvent(KESTREL_ACS_EID_INIT_ERR, CFE_EVS_EventType_ERROR,
                        "KESTREL_ACS: Software Bus receive failed, RC = 0x%08lX", (unsigned long)(uint32)st);
      KESTREL_ACS_Data.RunStatus = CFE_ES_RunStatus_APP_ERROR;
    }
  }
  CFE_ES_PerfLogExit(KESTREL_ACS_PERF_ID);
  CFE_ES_ExitApp(KESTREL_ACS_Data.RunStatus);
}

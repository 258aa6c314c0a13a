/* kestrel_acs_core: the cFE-free logic of KESTREL_ACS (see kestrel_acs_core.h). */
#include "kestrel_acs_core.h"

#include <math.h>
#include <string.h>

static void add_event(KestrelAcsCore *c, uint16_t id, KestrelAcsEventType type, int32_t a, int32_t b,
                      const char *text)
{
  KestrelAcsEvent *e;
  if (c->num_events >= KESTREL_ACS_MAX_EVENTS) return;
  e = &c->events[c->num_events++];
  e->id = id;
  e->type = (uint8_t)type;
  e->a = a;
  e->b = b;
  e->text = text;
}

void kestrel_acs_core_clear_events(KestrelAcsCore *c)
{
  if (c != NULL) c->num_events = 0;
}

void kestrel_acs_core_init(KestrelAcsCore *c)
{
  if (c == NULL) return;
  memset(c, 0, sizeof *c);
  c->last_status = FSW_OK;
}

/* ---- table -------------------------------------------------------------- */

static const char *image_error_name(FswLinkError e)
{
  switch (e) {
  case FSW_LINK_E_SHORT: return "image: short";
  case FSW_LINK_E_HEADER: return "image: header";
  case FSW_LINK_E_LENGTH: return "image: length";
  case FSW_LINK_E_CRC: return "image: CRC";
  default: return "image";
  }
}

FswStatus kestrel_acs_core_table_check(const KestrelAcsConfigTable *t, FswAcsConfig *scratch,
                                       const char **bad_field)
{
  FswLinkError why = FSW_LINK_OK;
  FswStatus s;
  const char *field = NULL;
  if (bad_field != NULL) *bad_field = NULL;
  if (t == NULL || scratch == NULL) return FSW_E_NULL_ARG;
  if (t->image_length == 0u || t->image_length > KESTREL_ACS_CONFIG_IMAGE_MAX) {
    if (bad_field != NULL) *bad_field = "image_length";
    return FSW_E_CONFIG;
  }
  s = fsw_link_config_decode(t->image, (size_t)t->image_length, scratch, &why);
  if (s != FSW_OK) {
    if (bad_field != NULL) *bad_field = image_error_name(why);
    return s;
  }
  s = fsw_acs_check(scratch, &field);
  if (s != FSW_OK && bad_field != NULL) *bad_field = field != NULL ? field : "config";
  return s;
}

void kestrel_acs_core_table_refused(KestrelAcsCore *c, FswStatus s, const char *bad_field)
{
  if (c == NULL) return;
  if (c->table_rejects < UINT32_MAX) c->table_rejects++;
  add_event(c, KESTREL_ACS_EID_TBL_BAD, KESTREL_ACS_EV_ERROR, (int32_t)s, 0,
            bad_field != NULL ? bad_field : "config");
}

FswStatus kestrel_acs_core_configure(KestrelAcsCore *c, const KestrelAcsConfigTable *t)
{
  const char *field = NULL;
  FswStatus s;
  if (c == NULL || t == NULL) return FSW_E_NULL_ARG;
  /* checked into the scratch config: a refused table leaves the one in force */
  s = kestrel_acs_core_table_check(t, &c->cfg_scratch, &field);
  if (s != FSW_OK) {
    kestrel_acs_core_table_refused(c, s, field);
    return s;
  }
  memcpy(&c->cfg, &c->cfg_scratch, sizeof c->cfg);
  s = fsw_acs_init(&c->acs, &c->cfg, &field);
  if (s != FSW_OK) { /* cannot happen after fsw_acs_check; reported anyway */
    c->config_loaded = 0u;
    kestrel_acs_core_table_refused(c, s, field);
    return s;
  }
  c->config_loaded = 1u;
  c->num_rw = (uint8_t)(c->cfg.has_wheels != 0 ? c->cfg.rw_map.num_rw : 0);
  c->num_thr = (uint8_t)(c->cfg.has_thrusters != 0 ? c->cfg.thr_map.num_thr : 0);
  c->num_mtq = (uint8_t)(c->cfg.has_mtq != 0 ? c->cfg.mtq_map.num_mtq : 0);
  c->have_cmd = 0u;
  c->have_last = 0u;
  c->err_run = 0u;
  c->last_mode = c->acs.mode;
  add_event(c, KESTREL_ACS_EID_TBL_OK, KESTREL_ACS_EV_INFO, c->acs.mode, (int32_t)t->image_length, NULL);
  return FSW_OK;
}

/* ---- ground commands ---------------------------------------------------- */

static const uint8_t kCmdLen[KESTREL_ACS_NUM_CC] = {
    KESTREL_ACS_NOOP_LEN,      KESTREL_ACS_RESET_COUNTERS_LEN, KESTREL_ACS_SET_MODE_LEN,
    KESTREL_ACS_SET_ACTUATION_LEN, KESTREL_ACS_SET_REFERENCE_LEN, KESTREL_ACS_SET_GAINS_LEN,
    KESTREL_ACS_SET_MOMENTUM_POLICY_LEN};

int kestrel_acs_core_cmd_len(uint8_t cc) { return cc < KESTREL_ACS_NUM_CC ? (int)kCmdLen[cc] : -1; }

static double get_f64(const uint8_t *p)
{
  uint64_t u = 0u;
  double d;
  int i;
  for (i = 0; i < 8; ++i) u = (u << 8) | p[i];
  memcpy(&d, &u, sizeof d);
  return d;
}

/* A real that fits fsw_real and is finite there. */
static int real_ok(double d) { return isfinite(d) && isfinite((fsw_real)d); }

/* The pending command, created from the state in force when there is none
 * (mode: the mode last commanded, so that it requests no change). */
static FswAcsCmdMsg *pending(KestrelAcsCore *c)
{
  if (c->have_cmd == 0u) {
    memset(&c->cmd, 0, sizeof c->cmd);
    c->cmd.mode = c->config_loaded != 0u ? c->acs.cmd_mode : 0;
    c->cmd.actuation = c->config_loaded != 0u ? c->acs.actuation : 0;
    c->cmd.policy = c->config_loaded != 0u ? c->acs.policy : 0;
    c->have_cmd = 1u;
  }
  return &c->cmd;
}

static int refuse(KestrelAcsCore *c, uint16_t id, int32_t a, int32_t b, const char *text)
{
  c->command_error_count++;
  add_event(c, id, KESTREL_ACS_EV_ERROR, a, b, text);
  return 0;
}

static int accept(KestrelAcsCore *c, uint8_t cc, int32_t value)
{
  c->command_count++;
  add_event(c, KESTREL_ACS_EID_CMD_ACCEPTED, KESTREL_ACS_EV_INFO, cc, value, NULL);
  return 1;
}

int kestrel_acs_core_ground_cmd(KestrelAcsCore *c, uint8_t cc, const uint8_t *payload, size_t len)
{
  if (c == NULL) return 0;
  if (cc >= KESTREL_ACS_NUM_CC) return refuse(c, KESTREL_ACS_EID_CMD_CC, cc, (int32_t)len, NULL);
  if (len != kCmdLen[cc] || (len > 0u && payload == NULL))
    return refuse(c, KESTREL_ACS_EID_CMD_LEN, cc, (int32_t)len, NULL);
  switch (cc) {
  case KESTREL_ACS_NOOP_CC:
    c->command_count++;
    add_event(c, KESTREL_ACS_EID_NOOP, KESTREL_ACS_EV_INFO, 0, 0, NULL);
    return 1;
  case KESTREL_ACS_RESET_COUNTERS_CC:
    c->command_count = 0u;
    c->command_error_count = 0u;
    c->cycles = 0u;
    c->cycle_errors = 0u;
    c->link_rejected = 0u;
    c->table_rejects = 0u;
    add_event(c, KESTREL_ACS_EID_RESET, KESTREL_ACS_EV_INFO, 0, 0, NULL);
    return 1;
  case KESTREL_ACS_SET_MODE_CC:
    if (payload[0] > (uint8_t)FSW_ACS_MODE_NADIR) return refuse(c, KESTREL_ACS_EID_CMD_VALUE, cc, payload[0], "mode");
    pending(c)->mode = payload[0];
    return accept(c, cc, payload[0]);
  case KESTREL_ACS_SET_ACTUATION_CC:
    if (payload[0] > (uint8_t)FSW_ACS_ACT_THRUSTERS)
      return refuse(c, KESTREL_ACS_EID_CMD_VALUE, cc, payload[0], "actuation");
    pending(c)->actuation = payload[0];
    return accept(c, cc, payload[0]);
  case KESTREL_ACS_SET_REFERENCE_CC: {
    double s[3];
    int i;
    FswAcsCmdMsg *m;
    for (i = 0; i < 3; ++i) {
      s[i] = get_f64(payload + 8 * i);
      if (!real_ok(s[i])) return refuse(c, KESTREL_ACS_EID_CMD_VALUE, cc, i, "sigma_R0N");
    }
    m = pending(c);
    for (i = 0; i < 3; ++i) m->sigma_R0N[i] = (fsw_real)s[i];
    m->set_ref = 1u;
    return accept(c, cc, 0);
  }
  case KESTREL_ACS_SET_GAINS_CC: {
    const double K = get_f64(payload), P = get_f64(payload + 8);
    FswAcsCmdMsg *m;
    if (!real_ok(K) || !(K > 0.0)) return refuse(c, KESTREL_ACS_EID_CMD_VALUE, cc, 0, "K");
    if (!real_ok(P) || !(P > 0.0)) return refuse(c, KESTREL_ACS_EID_CMD_VALUE, cc, 1, "P");
    m = pending(c);
    m->K = (fsw_real)K;
    m->P = (fsw_real)P;
    m->set_gains = 1u;
    return accept(c, cc, 0);
  }
  default: /* KESTREL_ACS_SET_MOMENTUM_POLICY_CC */
    if (payload[0] > (uint8_t)FSW_ACS_MOM_MAGNETORQUERS)
      return refuse(c, KESTREL_ACS_EID_CMD_VALUE, cc, payload[0], "policy");
    pending(c)->policy = payload[0];
    pending(c)->set_policy = 1u;
    return accept(c, cc, payload[0]);
  }
}

/* ---- link ----------------------------------------------------------------- */

static uint16_t next_seq(KestrelAcsCore *c, int i)
{
  const uint16_t s = c->tx_seq[i];
  c->tx_seq[i] = (uint16_t)((s + 1u) % FSW_LINK_SEQ_MODULO);
  return s;
}

static int link_refused(KestrelAcsCore *c, FswLinkError why)
{
  if (c->link_rejected < UINT32_MAX) c->link_rejected++;
  if (c->link_bad_run == 0u) {
    c->link_bad_run = 1u;
    add_event(c, KESTREL_ACS_EID_LINK_REJECT, KESTREL_ACS_EV_ERROR, (int32_t)why, 0, NULL);
  }
  return 0;
}

/* The first failing stage of an error cycle, for the event text. */
static const char *failed_stage(const FswAcsHealthMsg *h)
{
  int i;
  for (i = 0; i < FSW_ACS_NUM_STAGES; ++i)
    if (fsw_status_is_error(h->stage_status[i])) return fsw_acs_stage_name(i);
  return "input";
}

static int run_cycle(KestrelAcsCore *c, const FswLinkPacket *p)
{
  FswStatus s;
  s = fsw_acs_cycle(&c->acs, &c->cfg, &c->sens, c->have_cmd != 0u ? &c->cmd : NULL, &c->act, &c->hlth);
  if (c->cycles < UINT32_MAX) c->cycles++;
  if (fsw_status_is_error(s) && c->cycle_errors < UINT32_MAX) c->cycle_errors++;
  c->last_status = s;
  if (fsw_status_is_error(s)) {
    if (c->err_run == 0u) {
      if (c->config_loaded == 0u)
        add_event(c, KESTREL_ACS_EID_NO_CONFIG, KESTREL_ACS_EV_ERROR, (int32_t)s, 0, NULL);
      else
        add_event(c, KESTREL_ACS_EID_CYCLE_ERR, KESTREL_ACS_EV_ERROR, (int32_t)s, 0, failed_stage(&c->hlth));
    }
    if (c->err_run < UINT32_MAX) c->err_run++;
  } else {
    if (c->err_run != 0u)
      add_event(c, KESTREL_ACS_EID_CYCLE_OK, KESTREL_ACS_EV_INFO, (int32_t)c->err_run, 0, NULL);
    c->err_run = 0u;
  }
  if (c->config_loaded != 0u && c->acs.mode != c->last_mode) {
    add_event(c, KESTREL_ACS_EID_MODE, KESTREL_ACS_EV_INFO, c->last_mode, c->acs.mode, NULL);
    c->last_mode = c->acs.mode;
  }
  /* the encoders cannot fail: the buffers hold the largest packet and the
   * counts come from a configuration fsw_acs_init accepted */
  (void)fsw_link_encode_actuator(&c->act, c->num_rw, c->num_thr, c->num_mtq, p->t_ns, next_seq(c, 0), c->act_pkt,
                                 sizeof c->act_pkt, &c->act_len, NULL);
  (void)fsw_link_encode_health(&c->hlth, p->t_ns, next_seq(c, 1), c->hlth_pkt, sizeof c->hlth_pkt, &c->hlth_len,
                               NULL);
  return 2;
}

int kestrel_acs_core_link(KestrelAcsCore *c, uint8_t cc, const uint8_t *payload, size_t len)
{
  FswLinkPacket p;
  FswLinkError why = FSW_LINK_OK;
  uint8_t nrw, ncss;
  if (c == NULL) return 0;
  if (cc != KESTREL_ACS_LINK_CC) return refuse(c, KESTREL_ACS_EID_CMD_CC, cc, (int32_t)len, NULL);
  if (payload == NULL || fsw_link_parse(payload, len, &p, &why) != FSW_OK) return link_refused(c, why);
  if (p.packet_len != len) return link_refused(c, FSW_LINK_E_LENGTH);
  if (p.apid == FSW_LINK_APID_SENSOR) {
    const uint16_t crc = (uint16_t)(((uint32_t)payload[len - 2u] << 8) | payload[len - 1u]);
    if (fsw_link_decode_sensor(&p, &c->sens, &nrw, &ncss, &why) != FSW_OK) return link_refused(c, why);
    c->link_bad_run = 0u;
    if (c->have_last != 0u && p.seq == c->last_seq && p.t_ns == c->last_t_ns && crc == c->last_crc) {
      if (c->resent < UINT32_MAX) c->resent++;
      return 2;
    }
    c->have_last = 1u;
    c->last_seq = p.seq;
    c->last_t_ns = p.t_ns;
    c->last_crc = crc;
    return run_cycle(c, &p);
  }
  if (fsw_link_decode_cmd(&p, &c->cmd, &why) != FSW_OK) return link_refused(c, why);
  c->have_cmd = 1u;
  c->link_bad_run = 0u;
  return 0;
}

/* ---- housekeeping --------------------------------------------------------- */

static void put_u32(uint8_t *p, uint32_t v)
{
  p[0] = (uint8_t)(v >> 24);
  p[1] = (uint8_t)(v >> 16);
  p[2] = (uint8_t)(v >> 8);
  p[3] = (uint8_t)v;
}

void kestrel_acs_core_hk(const KestrelAcsCore *c, uint8_t out[KESTREL_ACS_HK_LEN])
{
  if (c == NULL || out == NULL) return;
  out[0] = c->command_count;
  out[1] = c->command_error_count;
  out[2] = (uint8_t)(c->config_loaded != 0u ? c->acs.mode : 0);
  out[3] = c->config_loaded;
  put_u32(out + 4, c->cycles);
  put_u32(out + 8, c->cycle_errors);
  put_u32(out + 12, c->link_rejected);
  put_u32(out + 16, (uint32_t)(int32_t)c->last_status);
  put_u32(out + 20, c->table_rejects);
}

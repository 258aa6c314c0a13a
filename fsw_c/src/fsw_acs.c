/* fsw_acs: the FSW application (one cycle per control period). */
#include "fsw/fsw_acs.h"

#include <float.h>
#include <stddef.h>
#include <string.h>

#include "fsw/fsw_attitude.h"
#include "fsw/fsw_vec.h"
#include "fsw_vec_inline.h"
#include "fsw_status_inline.h"
#include "css_sun_internal.h"
#include "guid_sunsafe_internal.h"
#include "mrp_fb_internal.h"
#include "rw_map_internal.h"
#include "rw_sat_internal.h"
#include "fsw/rw_common.h"

/* ---- stage names --------------------------------------------------------- */

/* A switch, not a table of pointers: a pointer table needs relocations and
 * lands in a writable section (.data.rel.ro) of position-independent
 * objects, which the no-globals proof rejects. */
const char *fsw_acs_stage_name(int stage)
{
  switch (stage) {
    case FSW_ACS_STAGE_CSS: return "css";
    case FSW_ACS_STAGE_GUIDANCE: return "guidance";
    case FSW_ACS_STAGE_TRACK: return "track";
    case FSW_ACS_STAGE_CONTROL: return "control";
    case FSW_ACS_STAGE_LPF: return "lpf";
    case FSW_ACS_STAGE_RW_MAP: return "rw_map";
    case FSW_ACS_STAGE_RW_NULL: return "rw_null";
    case FSW_ACS_STAGE_RW_SAT: return "rw_sat";
    case FSW_ACS_STAGE_RW_VOLT: return "rw_volt";
    case FSW_ACS_STAGE_THR_MAP: return "thr_map";
    case FSW_ACS_STAGE_THR_PULSE: return "thr_pulse";
    case FSW_ACS_STAGE_BDOT: return "bdot";
    case FSW_ACS_STAGE_MTQ_DESAT: return "mtq_desat";
    case FSW_ACS_STAGE_MTQ_MAP: return "mtq_map";
    case FSW_ACS_STAGE_THR_MOM: return "thr_momentum";
    case FSW_ACS_STAGE_RW_BIAS: return "rw_bias";
    default: return "unknown";
  }
}

/* ---- configuration ---------------------------------------------------- */

static FswStatus fail(const char **bad_field, const char *name, FswStatus s)
{
  if (bad_field != NULL) { *bad_field = name; }
  return s;
}

static int is_bool(int v) { return v == 0 || v == 1; }

/* ---- stages left out of the build (fsw_config.h, FSW_CFG_*) -------------- */

/* FSW_E_UNSUPPORTED, with the flag's name, for a configuration that asks
 * for a stage this build does not have; FSW_OK otherwise (the values of
 * the flags are checked afterwards). */
static FswStatus check_stages_built(const FswAcsConfig *cfg, const char **bad_field)
{
#if !FSW_CFG_MTQ
  if (cfg->has_mtq != 0) { return fail(bad_field, "has_mtq", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_MTQ_DESAT
  if (cfg->use_mtq_desat != 0) { return fail(bad_field, "use_mtq_desat", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_ORBIT
  if (cfg->has_orbit != 0) { return fail(bad_field, "has_orbit", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_THR_MOM
  if (cfg->use_thr_mom != 0) { return fail(bad_field, "use_thr_mom", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_RW_BIAS
  if (cfg->use_bias != 0) { return fail(bad_field, "use_bias", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_RW_NULL
  if (cfg->has_wheels != 0 && cfg->use_null != 0) { return fail(bad_field, "use_null", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_RW_VOLT
  if (cfg->has_wheels != 0 && cfg->use_volt != 0) { return fail(bad_field, "use_volt", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_SPEED_FILTER
  if (cfg->has_wheels != 0 && cfg->use_speed_filter != 0) {
    return fail(bad_field, "use_speed_filter", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_LPF
  if (cfg->use_lpf != 0) { return fail(bad_field, "use_lpf", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_PULSE_SCHMITT
  if (cfg->has_thrusters != 0 && cfg->pulser == FSW_ACS_PULSE_SCHMITT) {
    return fail(bad_field, "pulser", FSW_E_UNSUPPORTED); }
#endif
#if !FSW_CFG_THR_NNLS
  if (cfg->has_thrusters != 0 && cfg->thr_map.mode == FSW_THR_MAP_NNLS) {
    return fail(bad_field, "thr_map.mode", FSW_E_UNSUPPORTED); }
#endif
  (void)cfg;
  (void)bad_field;
  return FSW_OK;
}

/* ---- geometry ------------------------------------------------------------- */

/* dst[i] = src[i] for i < n, 0 up to cap. */
static void copy_n(fsw_real *dst, const fsw_real *src, int n, int cap)
{
  int i;
  for (i = 0; i < cap; i++) { dst[i] = (i < n) ? src[i] : FSW_R(0.0); }
}

static void copy_n3(fsw_real (*dst)[3], const fsw_real (*src)[3], int n, int cap)
{
  int i, k;
  for (i = 0; i < cap; i++) {
    for (k = 0; k < 3; k++) { dst[i][k] = (i < n) ? src[i][k] : FSW_R(0.0); } }
}

FswStatus fsw_acs_config_set_geometry(FswAcsConfig *cfg, const FswAcsGeometry *geo)
{
  int nw, nt, nm;
  FSW_ASSERT(cfg != NULL && geo != NULL);
  if (cfg == NULL || geo == NULL) { return FSW_E_NULL_ARG; }
  nw = geo->num_rw;
  nt = geo->num_thr;
  nm = geo->num_mtq;
  if (nw < 0 || nt < 0 || nm < 0) { return FSW_E_CONFIG; }
  if (nw > FSW_MAX_RW || nt > FSW_MAX_THR || nm > FSW_MAX_MTQ) { return FSW_E_CAPACITY; }

  /* wheels */
  cfg->has_wheels = (nw > 0) ? 1 : 0;
  cfg->mrp_fb.num_rw = nw;
  copy_n3(cfg->mrp_fb.gs_hat_B, geo->gs_hat_B, nw, FSW_MAX_RW);
  copy_n(cfg->mrp_fb.J_s, geo->J_s, nw, FSW_MAX_RW);
  cfg->rw_map.num_rw = nw;
  copy_n3(cfg->rw_map.gs_hat_B, geo->gs_hat_B, nw, FSW_MAX_RW);
  cfg->rw_null.num_rw = nw;
  copy_n3(cfg->rw_null.gs_hat_B, geo->gs_hat_B, nw, FSW_MAX_RW);
  copy_n(cfg->rw_null.u_max, geo->u_max, nw, FSW_MAX_RW);
  cfg->rw_sat.num_rw = nw;
  copy_n(cfg->rw_sat.u_max, geo->u_max, nw, FSW_MAX_RW);
  cfg->rw_volt.num_rw = nw;
  copy_n(cfg->rw_volt.u_max, geo->u_max, nw, FSW_MAX_RW);
  copy_n(cfg->rw_volt.J_s, geo->J_s, nw, FSW_MAX_RW);
  cfg->speed_filter.num_rw = nw;
  copy_n(cfg->speed_filter.u_max, geo->u_max, nw, FSW_MAX_RW);
  copy_n(cfg->speed_filter.J_s, geo->J_s, nw, FSW_MAX_RW);
  cfg->thr_mom.num_rw = nw;
  copy_n3(cfg->thr_mom.gs_hat_B, geo->gs_hat_B, nw, FSW_MAX_RW);
  copy_n(cfg->thr_mom.J_s, geo->J_s, nw, FSW_MAX_RW);
  cfg->mtq_desat.num_rw = nw;
  copy_n3(cfg->mtq_desat.gs_hat_B, geo->gs_hat_B, nw, FSW_MAX_RW);
  copy_n(cfg->mtq_desat.J_s, geo->J_s, nw, FSW_MAX_RW);
  cfg->rw_bias.num_rw = nw;
  copy_n3(cfg->rw_bias.gs_hat_B, geo->gs_hat_B, nw, FSW_MAX_RW);

  /* thrusters */
  cfg->has_thrusters = (nt > 0) ? 1 : 0;
  cfg->thr_map.num_thr = nt;
  copy_n3(cfg->thr_map.r_thr_B, geo->r_thr_B, nt, FSW_MAX_THR);
  copy_n3(cfg->thr_map.gt_hat_B, geo->gt_hat_B, nt, FSW_MAX_THR);
  copy_n(cfg->thr_map.F_max, geo->F_max, nt, FSW_MAX_THR);
  cfg->pulse_rem.common.num_thr = nt;
  copy_n(cfg->pulse_rem.common.F_max, geo->F_max, nt, FSW_MAX_THR);
  cfg->pulse_schmitt.common.num_thr = nt;
  copy_n(cfg->pulse_schmitt.common.F_max, geo->F_max, nt, FSW_MAX_THR);
  cfg->thr_mom.num_thr = nt;
  copy_n(cfg->thr_mom.F_max, geo->F_max, nt, FSW_MAX_THR);

  /* magnetorquer rods */
  cfg->has_mtq = (nm > 0) ? 1 : 0;
  cfg->mtq_map.num_mtq = nm;
  copy_n3(cfg->mtq_map.gt_hat_B, geo->mtq_axis_B, nm, FSW_MAX_MTQ);
  copy_n(cfg->mtq_map.m_max, geo->mtq_m_max, nm, FSW_MAX_MTQ);
  return FSW_OK;
}

/* 1 if `mode` is a mode this configuration can fly. */
static int mode_configured(const FswAcsConfig *cfg, int mode)
{
  switch (mode) {
    case FSW_ACS_MODE_SUN_SAFE:
    case FSW_ACS_MODE_INERTIAL: return 1;
    case FSW_ACS_MODE_DETUMBLE: return cfg->has_mtq == 1;
    case FSW_ACS_MODE_NADIR: return cfg->has_orbit == 1;
    default: return 0;
  }
}

/* 1 if `policy` is a momentum policy this configuration can fly. */
static int policy_configured(const FswAcsConfig *cfg, int policy)
{
  switch (policy) {
    case FSW_ACS_MOM_NONE: return 1;
    case FSW_ACS_MOM_THRUSTERS: return cfg->use_thr_mom == 1;
    case FSW_ACS_MOM_MAGNETORQUERS: return cfg->use_mtq_desat == 1;
    default: return 0;
  }
}

/* Safety net for configs filled by hand: the copies of physical geometry
 * (spin axes, spin inertias) must be bit-for-bit equal.  Torque limits are
 * not compared: a module may be given a derated limit on purpose. */

#if FSW_CFG_RW_VOLT || FSW_CFG_SPEED_FILTER || FSW_CFG_THR_MOM || FSW_CFG_MTQ_DESAT
/* 1 if the first n entries of a and b are equal. */
static int same_n(const fsw_real *a, const fsw_real *b, int n)
{
  int i;
  for (i = 0; i < n; i++) {
    if (a[i] != b[i]) { return 0; } }
  return 1;
}
#endif

static int same_n3(const fsw_real (*a)[3], const fsw_real (*b)[3], int n)
{
  int i, k;
  for (i = 0; i < n; i++) {
    for (k = 0; k < 3; k++) {
      if (a[i][k] != b[i][k]) { return 0; } } }
  return 1;
}

/* The magnetorquers, the orbit guidance and the momentum management. */
static FswStatus check_momentum(const FswAcsConfig *cfg, const char **bad_field)
{
  FswStatus s;
  const int n = cfg->rw_map.num_rw;
#if FSW_CFG_MTQ
  if (cfg->has_mtq) {
    if ((s = fsw_mtq_map_check(&cfg->mtq_map)) != FSW_OK) { return fail(bad_field, "mtq_map", s); }
    if ((s = fsw_bdot_check(&cfg->bdot)) != FSW_OK) { return fail(bad_field, "bdot", s); }
    if (cfg->detumble_exit_mode != -1 &&
        (cfg->detumble_exit_mode == FSW_ACS_MODE_DETUMBLE || !mode_configured(cfg, cfg->detumble_exit_mode))) {
      return fail(bad_field, "detumble_exit_mode", FSW_E_CONFIG); }
  }
#endif
#if FSW_CFG_ORBIT
  if (cfg->has_orbit && (s = fsw_guid_orbit_check(&cfg->orbit)) != FSW_OK) { return fail(bad_field, "orbit", s); }
#endif
  if (!is_bool(cfg->use_thr_mom)) { return fail(bad_field, "use_thr_mom", FSW_E_CONFIG); }
#if FSW_CFG_THR_MOM
  if (cfg->use_thr_mom) {
    if (!cfg->has_wheels || !cfg->has_thrusters) { return fail(bad_field, "use_thr_mom", FSW_E_CONFIG); }
    /* dumps fire on-pulsing thrusters from off: an off-pulsing set's pulser
     * keeps every thruster on between pulses (zero force = full thrust) */
    if (cfg->thr_map.thr_force_sign < 0) { return fail(bad_field, "use_thr_mom", FSW_E_CONFIG); }
    if ((s = fsw_thr_momentum_check(&cfg->thr_mom)) != FSW_OK) { return fail(bad_field, "thr_mom", s); }
    if (cfg->thr_mom.num_rw != n || !same_n3(cfg->thr_mom.gs_hat_B, cfg->rw_map.gs_hat_B, n)) {
      return fail(bad_field, "thr_mom.gs_hat_B", FSW_E_CONFIG); }
    if (cfg->mrp_fb.num_rw != 0 && !same_n(cfg->thr_mom.J_s, cfg->mrp_fb.J_s, n)) {
      return fail(bad_field, "thr_mom.J_s", FSW_E_CONFIG); }
    if (cfg->thr_mom.num_thr != cfg->thr_map.num_thr) { return fail(bad_field, "thr_mom.num_thr", FSW_E_CONFIG); }
  }
#endif
  if (!is_bool(cfg->use_mtq_desat)) { return fail(bad_field, "use_mtq_desat", FSW_E_CONFIG); }
#if FSW_CFG_MTQ_DESAT
  if (cfg->use_mtq_desat) {
    if (!cfg->has_wheels || !cfg->has_mtq) { return fail(bad_field, "use_mtq_desat", FSW_E_CONFIG); }
    if ((s = fsw_mtq_desat_check(&cfg->mtq_desat)) != FSW_OK) { return fail(bad_field, "mtq_desat", s); }
    if (cfg->mtq_desat.num_rw != n || !same_n3(cfg->mtq_desat.gs_hat_B, cfg->rw_map.gs_hat_B, n)) {
      return fail(bad_field, "mtq_desat.gs_hat_B", FSW_E_CONFIG); }
    if (cfg->mrp_fb.num_rw != 0 && !same_n(cfg->mtq_desat.J_s, cfg->mrp_fb.J_s, n)) {
      return fail(bad_field, "mtq_desat.J_s", FSW_E_CONFIG); }
  }
#endif
  if (!is_bool(cfg->use_bias)) { return fail(bad_field, "use_bias", FSW_E_CONFIG); }
#if FSW_CFG_RW_BIAS
  if (cfg->use_bias) {
    if (!cfg->has_wheels || cfg->use_null != 1) { return fail(bad_field, "use_bias", FSW_E_CONFIG); }
    if ((s = fsw_rw_bias_check(&cfg->rw_bias)) != FSW_OK) { return fail(bad_field, "rw_bias", s); }
    if (cfg->rw_bias.num_rw != n || !same_n3(cfg->rw_bias.gs_hat_B, cfg->rw_map.gs_hat_B, n)) {
      return fail(bad_field, "rw_bias.gs_hat_B", FSW_E_CONFIG); }
  }
#endif
#if !(FSW_CFG_THR_MOM || FSW_CFG_MTQ_DESAT || FSW_CFG_RW_BIAS)
  (void)n; /* the wheel count the momentum stages check */
#if !(FSW_CFG_MTQ || FSW_CFG_ORBIT)
  s = FSW_OK; /* the status of the magnetic and orbit checks */
  (void)s;
#endif
#endif
  if (!policy_configured(cfg, cfg->initial_policy)) { return fail(bad_field, "initial_policy", FSW_E_CONFIG); }
  return FSW_OK;
}

FswStatus fsw_acs_check(const FswAcsConfig *cfg, const char **bad_field)
{
  FswStatus s;
  int i;
  FSW_ASSERT(cfg != NULL);
  if (bad_field != NULL) { *bad_field = NULL; }
  s = (cfg == NULL) ? fail(bad_field, "cfg", FSW_E_NULL_ARG) : check_stages_built(cfg, bad_field);
  if (s != FSW_OK) { return s; }

  if (!is_bool(cfg->has_mtq)) { return fail(bad_field, "has_mtq", FSW_E_CONFIG); }
  if (!is_bool(cfg->has_orbit)) { return fail(bad_field, "has_orbit", FSW_E_CONFIG); }
  if (!mode_configured(cfg, cfg->initial_mode)) { return fail(bad_field, "initial_mode", FSW_E_CONFIG); }
  if (!is_bool(cfg->has_wheels)) { return fail(bad_field, "has_wheels", FSW_E_CONFIG); }
  if (!is_bool(cfg->has_thrusters)) { return fail(bad_field, "has_thrusters", FSW_E_CONFIG); }
  if (!cfg->has_wheels && !cfg->has_thrusters) { return fail(bad_field, "has_wheels", FSW_E_CONFIG); }
  if (cfg->initial_actuation == FSW_ACS_ACT_WHEELS) {
    if (!cfg->has_wheels) { return fail(bad_field, "initial_actuation", FSW_E_CONFIG); }
  } else if (cfg->initial_actuation == FSW_ACS_ACT_THRUSTERS) {
    if (!cfg->has_thrusters) { return fail(bad_field, "initial_actuation", FSW_E_CONFIG); }
  } else {
    return fail(bad_field, "initial_actuation", FSW_E_CONFIG);
  }

  if ((s = fsw_css_sun_check(&cfg->css)) != FSW_OK) { return fail(bad_field, "css", s); }
  if ((s = fsw_guid_sunsafe_check(&cfg->sunsafe)) != FSW_OK) { return fail(bad_field, "sunsafe", s); }
  if ((s = fsw_guid_inertial_check(&cfg->inertial)) != FSW_OK) { return fail(bad_field, "inertial", s); }
  if ((s = fsw_att_track_check(&cfg->track)) != FSW_OK) { return fail(bad_field, "track", s); }
  if ((s = fsw_mrp_fb_check(&cfg->mrp_fb)) != FSW_OK) { return fail(bad_field, "mrp_fb", s); }
  if (!is_bool(cfg->use_lpf)) { return fail(bad_field, "use_lpf", FSW_E_CONFIG); }
#if FSW_CFG_LPF
  if (cfg->use_lpf && (s = fsw_trq_lpf_check(&cfg->lpf)) != FSW_OK) { return fail(bad_field, "lpf", s); }
#endif

  if (cfg->has_wheels) {
    const int n = cfg->rw_map.num_rw;
    if ((s = fsw_rw_map_check(&cfg->rw_map)) != FSW_OK) { return fail(bad_field, "rw_map", s); }
    if (cfg->mrp_fb.num_rw != 0 && cfg->mrp_fb.num_rw != n) {
      return fail(bad_field, "mrp_fb.num_rw", FSW_E_CONFIG); }
    if (cfg->mrp_fb.num_rw != 0 &&
        !same_n3(cfg->mrp_fb.gs_hat_B, cfg->rw_map.gs_hat_B, n)) {
      return fail(bad_field, "mrp_fb.gs_hat_B", FSW_E_CONFIG); }
    if ((s = fsw_rw_sat_check(&cfg->rw_sat)) != FSW_OK) { return fail(bad_field, "rw_sat", s); }
    if (cfg->rw_sat.num_rw != n) { return fail(bad_field, "rw_sat.num_rw", FSW_E_CONFIG); }
    if (!is_bool(cfg->use_null)) { return fail(bad_field, "use_null", FSW_E_CONFIG); }
#if FSW_CFG_RW_NULL
    if (cfg->use_null) {
      if ((s = fsw_rw_null_check(&cfg->rw_null)) != FSW_OK) { return fail(bad_field, "rw_null", s); }
      if (cfg->rw_null.num_rw != n) { return fail(bad_field, "rw_null.num_rw", FSW_E_CONFIG); }
      if (!same_n3(cfg->rw_null.gs_hat_B, cfg->rw_map.gs_hat_B, n)) {
        return fail(bad_field, "rw_null.gs_hat_B", FSW_E_CONFIG); }
      if (!fsw_vn_is_finite(cfg->Omega_des, n)) { return fail(bad_field, "Omega_des", FSW_E_CONFIG); }
    }
#endif
    if (!is_bool(cfg->use_volt)) { return fail(bad_field, "use_volt", FSW_E_CONFIG); }
#if FSW_CFG_RW_VOLT
    if (cfg->use_volt) {
      if ((s = fsw_rw_volt_check(&cfg->rw_volt)) != FSW_OK) { return fail(bad_field, "rw_volt", s); }
      if (cfg->rw_volt.num_rw != n) { return fail(bad_field, "rw_volt.num_rw", FSW_E_CONFIG); }
      if (cfg->mrp_fb.num_rw != 0 && !same_n(cfg->rw_volt.J_s, cfg->mrp_fb.J_s, n)) {
        return fail(bad_field, "rw_volt.J_s", FSW_E_CONFIG); }
    }
#endif
    if (!is_bool(cfg->use_speed_filter)) { return fail(bad_field, "use_speed_filter", FSW_E_CONFIG); }
#if FSW_CFG_SPEED_FILTER
    if (cfg->use_speed_filter) {
      if ((s = fsw_rw_speed_filter_check(&cfg->speed_filter)) != FSW_OK) {
        return fail(bad_field, "speed_filter", s); }
      if (cfg->speed_filter.num_rw != n) { return fail(bad_field, "speed_filter.num_rw", FSW_E_CONFIG); }
      if (cfg->mrp_fb.num_rw != 0 && !same_n(cfg->speed_filter.J_s, cfg->mrp_fb.J_s, n)) {
        return fail(bad_field, "speed_filter.J_s", FSW_E_CONFIG); }
      /* the filter bounds a wheel's speed change by its u_max / J_s and
       * refuses a torque above 2 u_max: its limit must cover every torque
       * rw_sat can command (issue 39: 2.8e-4 against 0.2 N m made every
       * other cycle fail) */
      for (i = 0; i < n; i++) {
        if (!(cfg->speed_filter.u_max[i] >= cfg->rw_sat.u_max[i])) {
          return fail(bad_field, "speed_filter.u_max", FSW_E_CONFIG); } }
    }
#endif
  } else if (cfg->mrp_fb.num_rw != 0) {
    return fail(bad_field, "mrp_fb.num_rw", FSW_E_CONFIG); /* wheels in H but no wheel chain */
  }

  if ((s = check_momentum(cfg, bad_field)) != FSW_OK) { return s; }

  if (cfg->has_thrusters) {
    const int n = cfg->thr_map.num_thr;
    /* off-pulsing mapping (sign -1) needs off-pulsing pulsing (b = 1) and
     * vice versa; a mismatch silently inverts the control (docs/fsw/thr_pulse_rem.md). */
    const int b_want = (cfg->thr_map.thr_force_sign < 0) ? 1 : 0;
    const fsw_real *F_max;
    int num_thr, b;
    if ((s = fsw_thr_map_check(&cfg->thr_map)) != FSW_OK) { return fail(bad_field, "thr_map", s); }
    if (cfg->pulser == FSW_ACS_PULSE_REMAINDER) {
      if ((s = fsw_thr_pulse_rem_check(&cfg->pulse_rem)) != FSW_OK) {
        return fail(bad_field, "pulse_rem", s); }
      num_thr = cfg->pulse_rem.common.num_thr;
      F_max = cfg->pulse_rem.common.F_max;
      b = cfg->pulse_rem.common.base_thrust_state;
      if (num_thr != n) { return fail(bad_field, "pulse_rem.num_thr", FSW_E_CONFIG); }
      if (b != b_want) { return fail(bad_field, "pulse_rem.base_thrust_state", FSW_E_CONFIG); }
      for (i = 0; i < n; i++) {
        if (F_max[i] != cfg->thr_map.F_max[i]) { return fail(bad_field, "pulse_rem.F_max", FSW_E_CONFIG); } }
#if FSW_CFG_PULSE_SCHMITT
    } else if (cfg->pulser == FSW_ACS_PULSE_SCHMITT) {
      if ((s = fsw_thr_pulse_schmitt_check(&cfg->pulse_schmitt)) != FSW_OK) {
        return fail(bad_field, "pulse_schmitt", s); }
      num_thr = cfg->pulse_schmitt.common.num_thr;
      F_max = cfg->pulse_schmitt.common.F_max;
      b = cfg->pulse_schmitt.common.base_thrust_state;
      if (num_thr != n) { return fail(bad_field, "pulse_schmitt.num_thr", FSW_E_CONFIG); }
      if (b != b_want) { return fail(bad_field, "pulse_schmitt.base_thrust_state", FSW_E_CONFIG); }
      for (i = 0; i < n; i++) {
        if (F_max[i] != cfg->thr_map.F_max[i]) {
          return fail(bad_field, "pulse_schmitt.F_max", FSW_E_CONFIG); } }
#endif
    } else {
      return fail(bad_field, "pulser", FSW_E_CONFIG);
    }
  }
  return FSW_OK;
}

/* ---- init / reset ---------------------------------------------------- */

static void clear_state(FswAcsState *st)
{
  unsigned char *p = (unsigned char *)st;
  size_t k;
  for (k = 0; k < sizeof(*st); k++) { p[k] = 0u; }
}

/* Reset the stages whose memory must not survive a mode transition. */
static void reset_dynamic(FswAcsState *st, const FswAcsConfig *cfg)
{
#if FSW_CFG_MTQ
  if (cfg->has_mtq) { fsw_bdot_reset(&st->bdot); } /* a fresh derivative and persistence timer */
#endif
  fsw_mrp_fb_reset(&st->mrp_fb);
#if FSW_CFG_LPF
  if (cfg->use_lpf) { fsw_trq_lpf_reset(&st->lpf); }
#endif
#if FSW_CFG_RW_VOLT
  if (cfg->has_wheels && cfg->use_volt) { fsw_rw_volt_reset(&st->rw_volt); }
#endif
  if (cfg->has_thrusters) {
    fsw_thr_map_reset(&st->thr_map);
    if (cfg->pulser == FSW_ACS_PULSE_REMAINDER) {
      fsw_thr_pulse_rem_reset(&st->pulse_rem);
    } else {
#if FSW_CFG_PULSE_SCHMITT
      fsw_thr_pulse_schmitt_reset(&st->pulse_schmitt);
#endif
    }
  }
}

FswStatus fsw_acs_init(FswAcsState *st, const FswAcsConfig *cfg, const char **bad_field)
{
  FswStatus s;
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL) { return FSW_E_NULL_ARG; }
  clear_state(st);
  s = fsw_acs_check(cfg, bad_field);
  if (s != FSW_OK) { return s; }

#define ACS_INIT(call, name)                                                   \
  do {                                                                         \
    s = (call);                                                                \
    if (s != FSW_OK) {                                                         \
      clear_state(st);                                                         \
      return fail(bad_field, name, s);                                         \
    }                                                                          \
  } while (0)

  ACS_INIT(fsw_css_sun_init(&st->css, &cfg->css), "css");
  ACS_INIT(fsw_guid_sunsafe_init(&st->sunsafe, &cfg->sunsafe), "sunsafe");
  st->inertial_cfg = cfg->inertial;
  st->mrp_cfg = cfg->mrp_fb;
  ACS_INIT(fsw_guid_inertial_init(&st->inertial, &cfg->inertial), "inertial");
  ACS_INIT(fsw_att_track_init(&st->track, &cfg->track), "track");
  ACS_INIT(fsw_mrp_fb_init(&st->mrp_fb, &cfg->mrp_fb), "mrp_fb");
#if FSW_CFG_LPF
  if (cfg->use_lpf) { ACS_INIT(fsw_trq_lpf_init(&st->lpf, &cfg->lpf), "lpf"); }
#endif
  if (cfg->has_wheels) {
    ACS_INIT(fsw_rw_map_init(&st->rw_map, &cfg->rw_map), "rw_map");
#if FSW_CFG_RW_NULL
    if (cfg->use_null) {
      ACS_INIT(fsw_rw_null_init(&st->rw_null, &cfg->rw_null), "rw_null");
      /* desired speeds are configuration: copied into the stage input once */
      fsw_vn_copy(st->work.null_in.Omega_des, cfg->Omega_des, cfg->rw_null.num_rw);
    }
#endif
    ACS_INIT(fsw_rw_sat_init(&st->rw_sat, &cfg->rw_sat), "rw_sat");
#if FSW_CFG_RW_VOLT
    if (cfg->use_volt) { ACS_INIT(fsw_rw_volt_init(&st->rw_volt, &cfg->rw_volt), "rw_volt"); }
#endif
#if FSW_CFG_SPEED_FILTER
    if (cfg->use_speed_filter) {
      ACS_INIT(fsw_rw_speed_filter_init(&st->speed_filter, &cfg->speed_filter), "speed_filter"); }
#endif
  }
  if (cfg->has_thrusters) {
    ACS_INIT(fsw_thr_map_init(&st->thr_map, &cfg->thr_map), "thr_map");
    if (cfg->pulser == FSW_ACS_PULSE_REMAINDER) {
      ACS_INIT(fsw_thr_pulse_rem_init(&st->pulse_rem, &cfg->pulse_rem), "pulse_rem");
    } else {
#if FSW_CFG_PULSE_SCHMITT
      ACS_INIT(fsw_thr_pulse_schmitt_init(&st->pulse_schmitt, &cfg->pulse_schmitt), "pulse_schmitt");
#endif
    }
  }
#if FSW_CFG_MTQ
  if (cfg->has_mtq) {
    ACS_INIT(fsw_mtq_map_init(&st->mtq_map, &cfg->mtq_map), "mtq_map");
    ACS_INIT(fsw_bdot_init(&st->bdot, &cfg->bdot), "bdot");
  }
#endif
#if FSW_CFG_ORBIT
  if (cfg->has_orbit) { ACS_INIT(fsw_guid_orbit_init(&st->orbit, &cfg->orbit), "orbit"); }
#endif
#if FSW_CFG_THR_MOM
  if (cfg->use_thr_mom) { ACS_INIT(fsw_thr_momentum_init(&st->thr_mom, &cfg->thr_mom), "thr_mom"); }
#endif
#if FSW_CFG_MTQ_DESAT
  if (cfg->use_mtq_desat) { ACS_INIT(fsw_mtq_desat_init(&st->mtq_desat, &cfg->mtq_desat), "mtq_desat"); }
#endif
#if FSW_CFG_RW_BIAS
  if (cfg->use_bias) { ACS_INIT(fsw_rw_bias_init(&st->rw_bias, &cfg->rw_bias), "rw_bias"); }
#endif
#undef ACS_INIT
  fsw_health_clear(&st->health);
  st->ready = 1;
  fsw_acs_reset(st, cfg);
  return FSW_OK;
}

void fsw_acs_reset(FswAcsState *st, const FswAcsConfig *cfg)
{
  FSW_ASSERT(st != NULL && cfg != NULL);
  if (st == NULL || cfg == NULL || !st->ready) { return; }
  fsw_css_sun_reset(&st->css);
  fsw_guid_sunsafe_reset(&st->sunsafe);
  /* back to the configured reference and gains */
  st->mrp_cfg = cfg->mrp_fb;
  {
    const FswHealth hh = st->inertial.health;
    st->inertial_cfg = cfg->inertial;
    (void)fsw_guid_inertial_init(&st->inertial, &st->inertial_cfg); /* checked by fsw_acs_init */
    st->inertial.health = hh;
  }
  fsw_att_track_reset(&st->track);
  if (cfg->has_wheels) {
    fsw_rw_map_reset(&st->rw_map);
#if FSW_CFG_RW_NULL
    if (cfg->use_null) { fsw_rw_null_reset(&st->rw_null); }
#endif
    fsw_rw_sat_reset(&st->rw_sat);
#if FSW_CFG_SPEED_FILTER
    if (cfg->use_speed_filter) { fsw_rw_speed_filter_reset(&st->speed_filter); }
#endif
  }
#if FSW_CFG_MTQ
  if (cfg->has_mtq) {
    fsw_mtq_map_reset(&st->mtq_map);
    fsw_bdot_reset(&st->bdot);
    fsw_v3_zero(st->B_hold);
    st->B_hold_ok = 0u;
  }
#endif
#if FSW_CFG_ORBIT
  if (cfg->has_orbit) { fsw_guid_orbit_reset(&st->orbit); }
#endif
#if FSW_CFG_THR_MOM
  if (cfg->use_thr_mom) { fsw_thr_momentum_reset(&st->thr_mom); }
#endif
#if FSW_CFG_MTQ_DESAT
  if (cfg->use_mtq_desat) { fsw_mtq_desat_reset(&st->mtq_desat); }
#endif
#if FSW_CFG_RW_BIAS
  if (cfg->use_bias) { fsw_rw_bias_reset(&st->rw_bias); }
#endif
  fsw_vn_zero(st->work.t_on_last, FSW_MAX_THR);
  st->work.u_last_valid = 0u;
  reset_dynamic(st, cfg);
  st->policy = cfg->initial_policy;
  st->cmd_mode = cfg->initial_mode;
  st->mode = cfg->initial_mode;
  st->actuation = cfg->initial_actuation;
  fsw_clock_reset(&st->clock);
}

/* ---- cycle -------------------------------------------------------------- */

/* The safe output (fsw_acs.h): every command 0, no actuator active.  One
 * fill of the whole message, the padding included: each field's bytes are
 * those of a 0 (0.0 is all bits 0 in IEEE 754), the same as field by field. */
static void safe_output(FswAcsActuatorMsg *act) { (void)memset(act, 0, sizeof *act); }

/* The safe output but for Lr_B and the wheel torques u_s (every entry,
 * 0 beyond num_rw), which a pointing cycle with the wheels active writes in
 * every case (run_pointing and run_wheels): every other byte of the
 * message is written once, here, before the stages run. */
static void safe_output_but_wheel_torques(FswAcsActuatorMsg *act)
{
  unsigned char *p = (unsigned char *)act;
  const size_t from = (size_t)offsetof(FswAcsActuatorMsg, u_s) + sizeof act->u_s;
  (void)memset(&p[from], 0, sizeof *act - from);
}

/* The health message of a rejected cycle: all 0 but the stage statuses
 * (which stage failed); finish() then fills the status, the mode, the
 * counters and the filter verdicts, all as restored.  No estimate of the
 * rejected cycle (Sun heading, errors, momentum) is published. */
/* Bytes [from, to) of the message set to 0. */
static void zero_bytes(FswAcsHealthMsg *h, size_t from, size_t to)
{
  unsigned char *p = (unsigned char *)h;
  size_t k;
  for (k = from; k < to; k++) { p[k] = 0u; }
}

static void zero_health(FswAcsHealthMsg *h) { (void)memset(h, 0, sizeof *h); }

static void safe_health(FswAcsHealthMsg *h)
{
  const size_t a = offsetof(FswAcsHealthMsg, stage_status);
  zero_bytes(h, 0u, a);
  zero_bytes(h, a + sizeof(h->stage_status), sizeof(*h));
}

/* out[i] = in[i] for i < n (n >= 0: counts of a checked configuration).
 * The cycle's copies are between distinct objects (a message and the
 * work area, or two members of it), so one memcpy does them. */
static void u8_copy(uint8_t *out, const uint8_t *in, int n)
{
  (void)memcpy(out, in, (size_t)n);
}

static void r_copy(fsw_real *out, const fsw_real *in, int n)
{
  (void)memcpy(out, in, (size_t)n * sizeof *out);
}

/* The largest finite real: |x| <= ACS_REAL_MAX is isfinite(x). */
#if FSW_USE_FLOAT
#define ACS_REAL_MAX FLT_MAX
#else
#define ACS_REAL_MAX DBL_MAX
#endif

/* 1 if each of the n availability flags is FSW_AVAILABLE or
 * FSW_UNAVAILABLE and, when values_too, each entry flagged available is
 * within [-x_max, x_max] (not NaN; one pass: the cycle rejects either fault
 * alike).  x_max = ACS_REAL_MAX asks for a finite entry. */
static int avail_ok(const fsw_real *x, const uint8_t *avail, int n, int values_too, fsw_real x_max)
{
  int i;
  for (i = 0; i < n; i++) {
    if (avail[i] != FSW_AVAILABLE) {
      if (avail[i] != FSW_UNAVAILABLE) { return 0; }
    } else if ((values_too != 0) && !(FSW_FABS(x[i]) <= x_max)) {
      return 0;
    } else {
      /* available and within x_max, or the values not asked */
    }
  }
  return 1;
}

/* The wheel speeds and availability flags every stage uses: the speed
 * filter's screened ones, else the sensors' own (checked before any stage
 * runs).  Read in place, n = rw_map.num_rw entries. */
static const fsw_real *wheel_speeds(const FswAcsState *st, const FswAcsConfig *cfg,
                                    const FswAcsSensorMsg *sens)
{
  return (cfg->use_speed_filter != 0) ? st->work.filt_out.Omega : sens->Omega;
}

static const uint8_t *wheel_flags(const FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens)
{
  return (cfg->use_speed_filter != 0) ? st->work.filt_out.avail : sens->rw_avail;
}

/* First error wins; otherwise the first warning; otherwise OK. */
static FswStatus combine(FswStatus acc, FswStatus s)
{
  if (fsw_status_is_error_i(acc)) { return acc; }
  if (fsw_status_is_error_i(s)) { return s; }
  if (acc != FSW_OK) { return acc; }
  return s;
}

static FswStatus finish(FswAcsState *st, const FswAcsConfig *cfg, FswAcsHealthMsg *h, FswStatus s)
{
  /* the speed filter's verdicts as they stand (all 0 when it is not used:
   * init clears the whole state, so a ready state without the filter need
   * not be read) */
  const int nv = (st->ready && !cfg->use_speed_filter) ? 0 : FSW_MAX_RW;
  int i;
  h->rw_failed = 0u;
  h->rw_latched = 0u;
  for (i = 0; i < nv; i++) {
    if (st->speed_filter.failed[i]) { h->rw_failed |= (uint64_t)1u << i; }
    if (st->speed_filter.latched[i]) { h->rw_latched |= (uint64_t)1u << i; }
  }
  /* the record of an FSW_OK cycle inline, any other through the function */
  h->status = (s == FSW_OK) ? fsw_health_record_ok_i(&st->health) : fsw_health_record(&st->health, s);
  h->safe_output = (uint8_t)(fsw_status_is_error_i(s) ? 1 : 0);
  h->mode = st->mode;
  h->actuation = st->actuation;
  h->policy = st->policy;
  h->cycles = st->cycles;
  h->mode_changes = st->mode_changes;
  h->health = st->health;
  return s;
}

/* A cycle refused before any stage ran: the safe output, then finish(). */
static FswStatus reject(FswAcsState *st, const FswAcsConfig *cfg, FswAcsActuatorMsg *act,
                        FswAcsHealthMsg *h, FswStatus s)
{
  safe_output(act);
  return finish(st, cfg, h, s);
}

static FswStatus run_guidance(FswAcsState *st, const FswAcsConfig *cfg,
                              const FswAcsSensorMsg *sens, FswAcsHealthMsg *h, FswAttGuid *guid)
{
  FswAcsWork *w = &st->work;
  FswStatus acc = FSW_OK, s;
  if (st->mode == FSW_ACS_MODE_SUN_SAFE) {
    /* the readings and flags passed the cycle's checks (req_mode was
     * SUN_SAFE): the estimate without fsw_css_sun_update's same checks,
     * reading them in place */
    s = fsw_css_sun_estimate(&st->css, &cfg->css, sens->css, sens->css_avail, &w->css_out);
    h->stage_status[FSW_ACS_STAGE_CSS] = s;
    acc = combine(acc, s);
    if (w->css_out.sun_valid) {
      fsw_v3_copy(w->sunsafe_in.sun_B, w->css_out.sun_hat_B);
    } else {
      fsw_v3_zero(w->sunsafe_in.sun_B); /* no heading: search spin */
    }
    fsw_v3_copy(w->sunsafe_in.omega_BN_B, sens->omega_BN_B);
    /* its input is the estimate's heading (finite: a unit vector, a
     * sensor normal or 0) and the body rate checked above: the guidance
     * without fsw_guid_sunsafe_update's same checks */
    s = fsw_guid_sunsafe_point(&st->sunsafe, &cfg->sunsafe, &w->sunsafe_in, &w->sunsafe_out);
    h->stage_status[FSW_ACS_STAGE_GUIDANCE] = s;
    acc = combine(acc, s);
    *guid = w->sunsafe_out.guid;
    h->sun_angle_err = w->sunsafe_out.sun_angle_err;
    fsw_v3_copy(h->sun_hat_B, w->css_out.sun_hat_B);
    h->sun_valid = (uint8_t)(w->css_out.sun_valid ? 1 : 0);
    h->num_lit = (uint8_t)w->css_out.num_lit;
  } else {
    if (st->mode == FSW_ACS_MODE_NADIR) {
#if FSW_CFG_ORBIT
      fsw_v3_copy(w->orbit_in.r_N, sens->r_N);
      fsw_v3_copy(w->orbit_in.v_N, sens->v_N);
      w->orbit_in.valid = sens->orbit_valid;
      s = fsw_guid_orbit_update(&st->orbit, &cfg->orbit, &w->orbit_in, &w->orbit_out);
      w->track_in.ref = w->orbit_out;
#else
      s = FSW_E_UNSUPPORTED; /* not reached: fsw_acs_check rejects the stage */
#endif
    } else {
      s = fsw_guid_inertial_update(&st->inertial, &st->inertial_cfg, &w->inertial_out);
      w->track_in.ref = w->inertial_out;
    }
    h->stage_status[FSW_ACS_STAGE_GUIDANCE] = s;
    acc = combine(acc, s);
    fsw_v3_copy(w->track_in.sigma_BN, sens->sigma_BN);
    fsw_v3_copy(w->track_in.omega_BN_B, sens->omega_BN_B);
    s = fsw_att_track_update(&st->track, &cfg->track, &w->track_in, &w->track_out);
    h->stage_status[FSW_ACS_STAGE_TRACK] = s;
    acc = combine(acc, s);
    *guid = w->track_out;
  }
  return acc;
}

static FswStatus run_wheels(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                            const fsw_real Lr_B[3], FswAcsActuatorMsg *act, FswAcsHealthMsg *h)
{
  FswAcsWork *w = &st->work;
  const int n = cfg->rw_map.num_rw;
  const fsw_real *const Omega = wheel_speeds(st, cfg, sens);
  const uint8_t *const avail = wheel_flags(st, cfg, sens);
  FswStatus acc = FSW_OK, s;
  const fsw_real *u;

  /* the wheels' flags and speeds are the checked or screened ones: the
   * mapping without fsw_rw_map_update's same checks of them, reading its
   * input in place */
  s = fsw_rw_map_torques(&st->rw_map, &cfg->rw_map, Lr_B, Omega, avail, &w->map_out);
  h->stage_status[FSW_ACS_STAGE_RW_MAP] = s;
  acc = combine(acc, s);
  u = w->map_out.u_s;

#if FSW_CFG_RW_NULL
  if (cfg->use_null) {
    r_copy(w->null_in.u_s, u, n);
    r_copy(w->null_in.Omega, Omega, n);
    u8_copy(w->null_in.avail, avail, n);
    s = fsw_rw_null_update(&st->rw_null, &cfg->rw_null, &w->null_in, &w->null_out);
    h->stage_status[FSW_ACS_STAGE_RW_NULL] = s;
    acc = combine(acc, s);
    u = w->null_out.u_s;
  }
#endif

  if (u == w->map_out.u_s) {
    /* rw_map's torques are finite (it refuses a non-finite one, and its
     * errors give 0) and the flags checked or screened: the saturation
     * without fsw_rw_sat_update's checks of them */
    s = fsw_rw_sat_limit(&st->rw_sat, &cfg->rw_sat, u, avail, act->u_s);
  } else {
    r_copy(w->sat_in.u_s, u, n);
    u8_copy(w->sat_in.avail, avail, n);
    s = fsw_rw_sat_update(&st->rw_sat, &cfg->rw_sat, &w->sat_in, &w->sat_out);
    r_copy(act->u_s, w->sat_out.u_s, FSW_MAX_RW);
  }
  /* either way every entry of act->u_s: the torques, 0 beyond num_rw */
  h->stage_status[FSW_ACS_STAGE_RW_SAT] = s;
  acc = combine(acc, s);

#if FSW_CFG_RW_VOLT
  if (cfg->use_volt) {
    r_copy(w->volt_in.u_s, act->u_s, n);
    r_copy(w->volt_in.Omega, Omega, n);
    w->volt_in.has_Omega = 1;
    u8_copy(w->volt_in.avail, avail, n);
    w->volt_in.t_ns = sens->t_ns;
    s = fsw_rw_volt_update(&st->rw_volt, &cfg->rw_volt, &w->volt_in, &w->volt_out);
    h->stage_status[FSW_ACS_STAGE_RW_VOLT] = s;
    acc = combine(acc, s);
    r_copy(act->V, w->volt_out.V, n);
  }
#endif
  act->wheels_active = 1u;
  return acc;
}

/* The pulser: forces F into this cycle's on-times act->t_on. */
static FswStatus run_pulser(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                            const fsw_real *F, FswAcsActuatorMsg *act, FswAcsHealthMsg *h)
{
  FswAcsWork *w = &st->work;
  const int n = cfg->thr_map.num_thr;
  FswStatus s;
  int i;
  if (cfg->pulser == FSW_ACS_PULSE_REMAINDER) {
    w->rem_in.t_ns = sens->t_ns;
    r_copy(w->rem_in.F, F, n);
    s = fsw_thr_pulse_rem_update(&st->pulse_rem, &cfg->pulse_rem, &w->rem_in, &w->rem_out);
    r_copy(act->t_on, w->rem_out.t_on, n);
  } else {
#if FSW_CFG_PULSE_SCHMITT
    w->sch_in.t_ns = sens->t_ns;
    r_copy(w->sch_in.F, F, n);
    s = fsw_thr_pulse_schmitt_update(&st->pulse_schmitt, &cfg->pulse_schmitt, &w->sch_in,
                                     &w->sch_out);
    r_copy(act->t_on, w->sch_out.t_on, n);
#else
    s = FSW_E_UNSUPPORTED; /* not reached: fsw_acs_check rejects the stage */
#endif
  }
  h->stage_status[FSW_ACS_STAGE_THR_PULSE] = s;
  /* a flagged thruster stays off whatever its pulser remembers */
  for (i = 0; i < n; i++) {
    if (sens->thr_avail[i] != FSW_AVAILABLE) { act->t_on[i] = FSW_R(0.0); } }
  return s;
}

#if FSW_CFG_THR_MOM
/* 1 if the pulser has timed a period (it has run since its last reset). */
static int pulser_has_period(const FswAcsState *st, const FswAcsConfig *cfg)
{
  return (cfg->pulser == FSW_ACS_PULSE_REMAINDER) ? st->pulse_rem.common.clock.has_prev
                                                  : st->pulse_schmitt.common.clock.has_prev;
}
#endif

static FswStatus run_thrusters(FswAcsState *st, const FswAcsConfig *cfg,
                               const FswAcsSensorMsg *sens, const fsw_real Lr_B[3],
                               FswAcsActuatorMsg *act, FswAcsHealthMsg *h)
{
  FswAcsWork *w = &st->work;
  const int n = cfg->thr_map.num_thr;
  FswStatus acc = FSW_OK, s;

  fsw_v3_copy(w->thr_in.Lr_B, Lr_B);
  fsw_v3_copy(w->thr_in.r_CoM_B, sens->r_CoM_B);
  u8_copy(w->thr_in.avail, sens->thr_avail, n);
  s = fsw_thr_map_update(&st->thr_map, &cfg->thr_map, &w->thr_in, &w->thr_out);
  h->stage_status[FSW_ACS_STAGE_THR_MAP] = s;
  acc = combine(acc, s);
  r_copy(act->F, w->thr_out.F, n);
  acc = combine(acc, run_pulser(st, cfg, sens, w->thr_out.F, act, h));
  act->thrusters_active = 1u;
  return acc;
}

#if FSW_CFG_MTQ
/* DETUMBLE: B-dot's dipole through the rod map; no attitude control, the
 * wheels hold zero torque. */
static FswStatus run_detumble(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                              FswAcsActuatorMsg *act, FswAcsHealthMsg *h)
{
  FswAcsWork *w = &st->work;
  FswStatus acc = FSW_OK, s;
  w->bdot_in.t_ns = sens->t_ns;
  fsw_v3_copy(w->bdot_in.B_B, sens->B_B);
  w->bdot_in.B_valid = sens->mag_valid;
  fsw_v3_copy(w->bdot_in.omega_BN_B, sens->omega_BN_B);
  w->bdot_in.omega_valid = 1u;
  s = fsw_bdot_update(&st->bdot, &cfg->bdot, &w->bdot_in, &w->bdot_out);
  h->stage_status[FSW_ACS_STAGE_BDOT] = s;
  acc = combine(acc, s);
  h->detumbled = w->bdot_out.detumbled;
  h->rate_est = w->bdot_out.rate_est;

  if (sens->mag_valid) {
    fsw_v3_copy(st->B_hold, sens->B_B);
    st->B_hold_ok = 1u;
  }
  fsw_v3_zero(w->mtq_in.tau_B);
  fsw_v3_copy(w->mtq_in.m_req_B, w->bdot_out.m_B);
  w->mtq_in.use_dipole = 1u;
  fsw_v3_copy(w->mtq_in.B_B, st->B_hold); /* the field of the dipole's torque */
  w->mtq_in.B_valid = st->B_hold_ok;
  s = fsw_mtq_map_update(&st->mtq_map, &cfg->mtq_map, &w->mtq_in, &w->mtq_out);
  h->stage_status[FSW_ACS_STAGE_MTQ_MAP] = s;
  acc = combine(acc, s);
  r_copy(act->m_cmd, w->mtq_out.m_cmd, cfg->mtq_map.num_mtq);
  fsw_v3_copy(h->tau_mtq_B, w->mtq_out.tau_ach_B);
  act->mtq_active = 1u;
  if (cfg->has_wheels) { act->wheels_active = 1u; } /* u_s = 0: the wheels keep their momentum */
  return acc;
}
#endif

#if FSW_CFG_THR_MOM || FSW_CFG_MTQ_DESAT || FSW_CFG_RW_BIAS
/* Momentum management ahead of the wheel chain: the desired wheel speeds
 * (rw_bias), then the policy's external torque (thruster dump pulses or the
 * rods' torque), which the wheels absorb: Lw = Lr - L_ext holds the
 * attitude while the external torque unloads them. */
static FswStatus run_momentum(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                              const fsw_real Lr_B[3], fsw_real Lw_B[3], FswAcsActuatorMsg *act,
                              FswAcsHealthMsg *h)
{
  FswAcsWork *w = &st->work;
  const int n = cfg->rw_map.num_rw;
  const fsw_real *const Omega = wheel_speeds(st, cfg, sens);
  const uint8_t *const avail = wheel_flags(st, cfg, sens);
  FswStatus acc = FSW_OK, s;
  fsw_v3_copy(Lw_B, Lr_B);
#if FSW_CFG_RW_BIAS
  if (cfg->use_bias) {
    r_copy(w->bias_in.Omega, Omega, n);
    u8_copy(w->bias_in.avail, avail, n);
    s = fsw_rw_bias_update(&st->rw_bias, &cfg->rw_bias, &w->bias_in, &w->bias_out);
    h->stage_status[FSW_ACS_STAGE_RW_BIAS] = s;
    acc = combine(acc, s);
    r_copy(w->null_in.Omega_des, w->bias_out.Omega_des, n);
  }
#endif
  if (st->policy == FSW_ACS_MOM_THRUSTERS) {
#if FSW_CFG_THR_MOM
    /* The pulser turns a force into an on-time over the period since its
     * own last call, so it runs in every cycle of this policy (zero force
     * between pulses) and that period is the control period.  Its first
     * call after a reset (init, a transition, a policy change) has no
     * period and commands nothing: in that cycle thr_momentum runs with
     * enable = 0 (no dump starts; one in progress is aborted and the next
     * cycle starts afresh from the measured momentum), so that no dump
     * counts an impulse the thrusters did not give. */
    const int timed = pulser_has_period(st, cfg);
    w->mom_in.t_ns = sens->t_ns;
    r_copy(w->mom_in.Omega, Omega, n);
    u8_copy(w->mom_in.avail, avail, n);
    r_copy(w->mom_in.t_on_prev, w->t_on_last, FSW_MAX_THR);
    w->mom_in.enable = timed ? 1u : 0u;
    w->mom_in.force_dump = 0u;
    s = fsw_thr_momentum_update(&st->thr_mom, &cfg->thr_mom, &w->mom_in, &w->mom_out);
    h->stage_status[FSW_ACS_STAGE_THR_MOM] = s;
    acc = combine(acc, s);
    h->dump_phase = (uint8_t)w->mom_out.phase;
    h->dumps = w->mom_out.dumps;
    h->prop_used = w->mom_out.prop_total;
    if (w->mom_out.phase == FSW_THR_MOM_PULSE && fsw_v3_norm2(w->mom_out.L_thr_B) > FSW_R(0.0)) {
      acc = combine(acc, run_thrusters(st, cfg, sens, w->mom_out.L_thr_B, act, h));
      fsw_v3_sub(Lw_B, Lw_B, w->mom_out.L_thr_B);
    } else {
      int i;
      fsw_vn_zero(w->thr_out.F, FSW_MAX_THR);
      acc = combine(acc, run_pulser(st, cfg, sens, w->thr_out.F, act, h));
      for (i = 0; i < cfg->thr_map.num_thr; i++) {
        if (act->t_on[i] > FSW_R(0.0)) { act->thrusters_active = 1u; } } /* a carried remainder */
    }
#else
    acc = combine(acc, FSW_E_UNSUPPORTED); /* not reached: fsw_acs_check rejects the stage */
#endif
  } else if (st->policy == FSW_ACS_MOM_MAGNETORQUERS) {
#if FSW_CFG_MTQ_DESAT
    act->mtq_active = 1u; /* rods off unless a field sample lets them act */
    if (sens->mag_valid) {
      r_copy(w->desat_in.Omega, Omega, n);
      u8_copy(w->desat_in.avail, avail, n);
      fsw_v3_copy(w->desat_in.B_B, sens->B_B);
      w->desat_in.B_valid = 1u;
      s = fsw_mtq_desat_update(&st->mtq_desat, &cfg->mtq_desat, &w->desat_in, &w->desat_out);
      h->stage_status[FSW_ACS_STAGE_MTQ_DESAT] = s;
      acc = combine(acc, s);
      fsw_v3_copy(w->mtq_in.tau_B, w->desat_out.tau_req_B);
      fsw_v3_zero(w->mtq_in.m_req_B);
      w->mtq_in.use_dipole = 0u;
      fsw_v3_copy(w->mtq_in.B_B, sens->B_B);
      w->mtq_in.B_valid = 1u;
      s = fsw_mtq_map_update(&st->mtq_map, &cfg->mtq_map, &w->mtq_in, &w->mtq_out);
      h->stage_status[FSW_ACS_STAGE_MTQ_MAP] = s;
      acc = combine(acc, s);
      r_copy(act->m_cmd, w->mtq_out.m_cmd, cfg->mtq_map.num_mtq);
      fsw_v3_copy(h->tau_mtq_B, w->mtq_out.tau_ach_B);
      fsw_v3_sub(Lw_B, Lw_B, w->mtq_out.tau_ach_B);
    }
#else
    acc = combine(acc, FSW_E_UNSUPPORTED); /* not reached: fsw_acs_check rejects the stage */
#endif
  }
  return acc;
}
#endif

/* The set fields of a command: flags 0/1, a finite reference, gains finite
 * and > 0 (what fsw_guid_inertial_check and fsw_mrp_fb_check ask of them),
 * a policy this configuration can fly. */
static int set_command_ok(const FswAcsConfig *cfg, const FswAcsCmdMsg *cmd)
{
  if (cmd->set_ref > 1u || cmd->set_gains > 1u || cmd->set_policy > 1u) { return 0; }
  if (cmd->set_policy && !policy_configured(cfg, cmd->policy)) { return 0; }
  if (cmd->set_ref && (!fsw_v3_is_finite(cmd->sigma_R0N) || !isfinite(fsw_v3_norm2(cmd->sigma_R0N)))) { return 0; }
  if (cmd->set_gains &&
      (!isfinite(cmd->K) || !(cmd->K > FSW_R(0.0)) || !isfinite(cmd->P) || !(cmd->P > FSW_R(0.0)))) {
    return 0; }
  return 1;
}

/* Apply a checked command's set fields (after save_dynamic: an error cycle
 * puts the previous reference and gains back). */
static void apply_set_command(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsCmdMsg *cmd)
{
  if (cmd->set_ref) {
    const FswHealth hh = st->inertial.health;
    fsw_v3_copy(st->inertial_cfg.sigma_R0N, cmd->sigma_R0N);
    (void)fsw_guid_inertial_init(&st->inertial, &st->inertial_cfg); /* checked by set_command_ok */
    st->inertial.health = hh;
  }
  if (cmd->set_gains) {
    st->mrp_cfg.K = cmd->K;
    st->mrp_cfg.P = cmd->P;
  }
  if (cmd->set_policy && cmd->policy != st->policy) {
    st->policy = cmd->policy;
    /* the pulser's clock is stale when the dumps start to use it (in the
     * thruster actuation it runs every cycle: its clock is current) */
    if (cmd->policy == FSW_ACS_MOM_THRUSTERS && st->actuation == FSW_ACS_ACT_WHEELS) {
      if (cfg->pulser == FSW_ACS_PULSE_REMAINDER) {
        fsw_thr_pulse_rem_reset(&st->pulse_rem);
      } else {
#if FSW_CFG_PULSE_SCHMITT
        fsw_thr_pulse_schmitt_reset(&st->pulse_schmitt);
#endif
      }
    }
  }
}

/* The thrusters configured (0 without thrusters).  Entries of t_on_last
 * from this count on are 0 from init to the end (act->t_on is 0 beyond the
 * configured thrusters), so the snapshot, its restore and the record of the
 * last on-times copy the configured entries only. */
static int thr_count(const FswAcsConfig *cfg) { return cfg->has_thrusters ? cfg->thr_map.num_thr : 0; }

/* Snapshot of the dynamic state before the stages run (see FswAcsWork). */
static void save_dynamic(FswAcsState *st, const FswAcsConfig *cfg)
{
  FswAcsWork *w = &st->work;
  int i;
  w->saved.mode = st->mode;
  fsw_v3_copy(w->saved.sigma_R0N, st->inertial_cfg.sigma_R0N);
  w->saved.inertial = st->inertial;
  w->saved.K = st->mrp_cfg.K;
  w->saved.P = st->mrp_cfg.P;
  w->saved.actuation = st->actuation;
  w->saved.mode_changes = st->mode_changes;
  w->saved.policy = st->policy;
  w->saved.cmd_mode = st->cmd_mode;
  if (cfg->has_mtq) {
    w->saved.bdot = st->bdot;
    fsw_v3_copy(w->saved.B_hold, st->B_hold);
    w->saved.B_hold_ok = st->B_hold_ok;
  }
  if (cfg->has_orbit) { w->saved.orbit = st->orbit; }
  if (cfg->use_thr_mom) { w->saved.thr_mom = st->thr_mom; }
  if (cfg->use_bias) {
    for (i = 0; i < FSW_MAX_RW; i++) { w->saved.bias_in_band[i] = st->rw_bias.in_band[i]; } }
  w->saved.mrp_fb = st->mrp_fb;
  if (cfg->use_lpf) { w->saved.lpf = st->lpf; }
  if (cfg->has_wheels && cfg->use_volt) { w->saved.rw_volt = st->rw_volt; }
  if (cfg->has_wheels && cfg->use_null) {
    for (i = 0; i < FSW_MAX_RW; i++) { w->saved.null_avail[i] = st->rw_null.proj.avail[i]; } }
  if (cfg->has_wheels && cfg->use_speed_filter) { w->saved.speed_filter = st->speed_filter; }
  if (cfg->has_thrusters) {
    r_copy(w->saved.t_on_last, w->t_on_last, thr_count(cfg));
    w->saved.thr_ang_err = st->thr_map.ang_err;
    w->saved.thr_nnls_iter = st->thr_map.nnls_iter;
    if (cfg->pulser == FSW_ACS_PULSE_REMAINDER) {
      w->saved.pulse_rem = st->pulse_rem;
    } else {
      w->saved.pulse_schmitt = st->pulse_schmitt; }
  }
}

/* Put the snapshot back; every stage keeps its health counters (they count
 * this cycle's statuses). */
static void restore_dynamic(FswAcsState *st, const FswAcsConfig *cfg)
{
  FswAcsWork *w = &st->work;
  FswHealth hh;
  st->mode = w->saved.mode;
  st->actuation = w->saved.actuation;
  fsw_v3_copy(st->inertial_cfg.sigma_R0N, w->saved.sigma_R0N);
  hh = st->inertial.health;
  st->inertial = w->saved.inertial;
  st->inertial.health = hh;
  st->mrp_cfg.K = w->saved.K;
  st->mrp_cfg.P = w->saved.P;
  st->mode_changes = w->saved.mode_changes;
  st->policy = w->saved.policy;
  st->cmd_mode = w->saved.cmd_mode;
  r_copy(w->t_on_last, w->saved.t_on_last, thr_count(cfg));
  if (cfg->has_mtq) {
    hh = st->bdot.health;
    st->bdot = w->saved.bdot;
    st->bdot.health = hh;
    fsw_v3_copy(st->B_hold, w->saved.B_hold);
    st->B_hold_ok = w->saved.B_hold_ok;
  }
  if (cfg->has_orbit) {
    hh = st->orbit.health;
    st->orbit = w->saved.orbit;
    st->orbit.health = hh;
  }
  if (cfg->use_thr_mom) {
    hh = st->thr_mom.health;
    st->thr_mom = w->saved.thr_mom;
    st->thr_mom.health = hh;
  }
  if (cfg->use_bias) {
    int i;
    for (i = 0; i < FSW_MAX_RW; i++) { st->rw_bias.in_band[i] = w->saved.bias_in_band[i]; }
  }
  hh = st->mrp_fb.health;
  st->mrp_fb = w->saved.mrp_fb;
  st->mrp_fb.health = hh;
  if (cfg->use_lpf) {
    hh = st->lpf.health;
    st->lpf = w->saved.lpf;
    st->lpf.health = hh;
  }
  if (cfg->has_wheels && cfg->use_volt) {
    hh = st->rw_volt.health;
    st->rw_volt = w->saved.rw_volt;
    st->rw_volt.health = hh;
  }
  if (cfg->has_wheels && cfg->use_null) { (void)fsw_rw_proj_refresh(&st->rw_null.proj, w->saved.null_avail); }
  if (cfg->has_wheels && cfg->use_speed_filter) {
    hh = st->speed_filter.health;
    st->speed_filter = w->saved.speed_filter;
    st->speed_filter.health = hh;
  }
  if (cfg->has_thrusters) {
    st->thr_map.ang_err = w->saved.thr_ang_err;
    st->thr_map.nnls_iter = w->saved.thr_nnls_iter;
    if (cfg->pulser == FSW_ACS_PULSE_REMAINDER) {
      hh = st->pulse_rem.common.health;
      st->pulse_rem = w->saved.pulse_rem;
      st->pulse_rem.common.health = hh;
    } else {
      hh = st->pulse_schmitt.common.health;
      st->pulse_schmitt = w->saved.pulse_schmitt;
      st->pulse_schmitt.common.health = hh;
    }
  }
}

/* The pointing modes: guidance, control law, actuation.  The guidance is
 * written once, into the control law's input (w->fb_in.guid), and read
 * from there for the telemetry. */
static FswStatus run_pointing(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                              FswAcsActuatorMsg *act, FswAcsHealthMsg *h)
{
  FswAcsWork *w = &st->work;
  FswStatus acc = FSW_OK, s;
  const fsw_real *Lr;

  /* 3. Guidance and attitude error. */
  acc = combine(acc, run_guidance(st, cfg, sens, h, &w->fb_in.guid));

  /* 4. Control law.  The guidance is a stage's output (finite, or its
   * safe output 0; run_guidance wrote it into w->fb_in.guid) and the
   * wheels' flags and speeds are the checked or screened ones: the law
   * without fsw_mrp_fb_update's same checks, reading its input in place
   * (the wheels' arrays are read for mrp_fb's num_rw wheels, none without
   * wheels) */
  s = fsw_mrp_fb_torque(&st->mrp_fb, &st->mrp_cfg, &w->fb_in.guid, sens->t_ns, wheel_speeds(st, cfg, sens),
                        wheel_flags(st, cfg, sens), &w->fb_out);
  h->stage_status[FSW_ACS_STAGE_CONTROL] = s;
  acc = combine(acc, s);
  Lr = w->fb_out.torque_B;

#if FSW_CFG_LPF
  if (cfg->use_lpf) {
    fsw_v3_copy(w->lpf_in.Lr_B, Lr);
    w->lpf_in.t_ns = sens->t_ns;
    s = fsw_trq_lpf_update(&st->lpf, &cfg->lpf, &w->lpf_in, &w->lpf_out);
    h->stage_status[FSW_ACS_STAGE_LPF] = s;
    acc = combine(acc, s);
    Lr = w->lpf_out.LrF_B;
  }
#endif
  fsw_v3_copy(act->Lr_B, Lr);

  /* 5. Actuation chain (with wheels: momentum management first). */
  if (st->actuation == FSW_ACS_ACT_WHEELS) {
    fsw_real Lw[3];
#if FSW_CFG_THR_MOM || FSW_CFG_MTQ_DESAT || FSW_CFG_RW_BIAS
    acc = combine(acc, run_momentum(st, cfg, sens, Lr, Lw, act, h));
#else
    fsw_v3_copy(Lw, Lr); /* no momentum management in this build */
#endif
    acc = combine(acc, run_wheels(st, cfg, sens, Lw, act, h));
  } else {
    acc = combine(acc, run_thrusters(st, cfg, sens, Lr, act, h));
  }

  return acc;
}

FswStatus fsw_acs_cycle(FswAcsState *st, const FswAcsConfig *cfg, const FswAcsSensorMsg *sens,
                        const FswAcsCmdMsg *cmd, FswAcsActuatorMsg *act, FswAcsHealthMsg *h)
{
  FswAcsWork *w;
  FswStatus acc = FSW_OK;
  FswAttGuid guid;       /* DETUMBLE's: no attitude error */
  const FswAttGuid *g;   /* the guidance of the cycle, for the telemetry */
  int req_mode, req_act, req_policy, i;
  uint8_t u_known;

  FSW_ASSERT(st != NULL && cfg != NULL && sens != NULL && act != NULL && h != NULL);
  if (h != NULL) { zero_health(h); }
  if (st == NULL || cfg == NULL || sens == NULL || act == NULL || h == NULL) {
    if (act != NULL) { safe_output(act); }
    if (st != NULL) { (void)fsw_health_record(&st->health, FSW_E_NULL_ARG); }
    return FSW_E_NULL_ARG;
  }
  if (!st->ready) { return reject(st, cfg, act, h, FSW_E_NOT_INIT); }
  w = &st->work;
  /* Whether last call's wheel torque held until now; from here on, until
   * this cycle succeeds with wheels active, the next call cannot know. */
  u_known = w->u_last_valid;
  w->u_last_valid = 0u;

  /* 1. Everything that can be wrong with the inputs is checked before any
   *    stage runs, so a bad cycle advances no state at all. */
  /* A mode command acts when its mode differs from the last one commanded
   * (the FSW may have left that mode on its own: DETUMBLE's exit). */
  req_mode = (cmd != NULL && cmd->mode != st->cmd_mode) ? cmd->mode : st->mode;
  req_act = (cmd != NULL) ? cmd->actuation : st->actuation;
  req_policy = (cmd != NULL && cmd->set_policy == 1u) ? cmd->policy : st->policy;
  if (!mode_configured(cfg, req_mode)) { return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if (!((req_act == FSW_ACS_ACT_WHEELS && cfg->has_wheels) ||
        (req_act == FSW_ACS_ACT_THRUSTERS && cfg->has_thrusters))) {
    return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if (cmd != NULL && !set_command_ok(cfg, cmd)) { return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  /* fsw_clock_dt's test (the stages derive their own dt): a time stamp
   * not after the last accepted cycle's is FSW_E_TIME */
  if ((st->clock.has_prev != 0) && (sens->t_ns <= st->clock.t_prev_ns)) {
    return reject(st, cfg, act, h, FSW_E_TIME); }
  if (!fsw_v3_is_finite(sens->omega_BN_B)) { return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if ((req_mode == FSW_ACS_MODE_INERTIAL || req_mode == FSW_ACS_MODE_NADIR) &&
      (sens->att_valid != 1u || !fsw_v3_is_finite(sens->sigma_BN))) {
    return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if (sens->mag_valid > 1u || sens->orbit_valid > 1u) { return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if (cfg->has_mtq && sens->mag_valid && !fsw_v3_is_finite(sens->B_B)) { return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if (req_mode == FSW_ACS_MODE_NADIR &&
      (sens->orbit_valid != 1u || !fsw_v3_is_finite(sens->r_N) || !fsw_v3_is_finite(sens->v_N))) {
    return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if (req_mode == FSW_ACS_MODE_SUN_SAFE &&
      !avail_ok(sens->css, sens->css_avail, cfg->css.num_css, 1, ACS_REAL_MAX)) {
    return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  /* a speed beyond +-FSW_RW_OMEGA_MAX is no speed (the wheel momentum
   * telemetry J_s Omega stays finite); with the speed filter, a non-finite
   * or out-of-range speed is one wheel's fault (it fails that wheel), not
   * bad input of the cycle */
  if (cfg->has_wheels &&
      !avail_ok(sens->Omega, sens->rw_avail, cfg->rw_map.num_rw, !cfg->use_speed_filter, FSW_RW_OMEGA_MAX)) {
    return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if ((req_act == FSW_ACS_ACT_THRUSTERS || req_policy == FSW_ACS_MOM_THRUSTERS) &&
      !fsw_v3_is_finite(sens->r_CoM_B)) {
    return reject(st, cfg, act, h, FSW_E_BAD_INPUT); }
  if (cfg->has_thrusters) {
    for (i = 0; i < cfg->thr_map.num_thr; i++) {
      if (sens->thr_avail[i] > FSW_UNAVAILABLE) { return reject(st, cfg, act, h, FSW_E_BAD_INPUT); } } }

  /* 2. Mode transition: clear the memory that belongs to the old mode.
   *    From here on the stages advance their own state; an error status of
   *    the cycle puts the snapshot back (validate, compute, commit only on
   *    success). */
  save_dynamic(st, cfg);
  if (cmd != NULL) { apply_set_command(st, cfg, cmd); }
  if (cmd != NULL) { st->cmd_mode = cmd->mode; }
  if (req_mode != st->mode || req_act != st->actuation) {
    reset_dynamic(st, cfg);
    st->mode = req_mode;
    st->actuation = req_act;
    if (st->mode_changes < UINT32_MAX) { st->mode_changes++; }
  }
  /* The actuator message before the stages run: the safe output, but for
   * what this cycle's stages write in every case (an error cycle ends with
   * the whole safe output again). */
  if ((st->mode != FSW_ACS_MODE_DETUMBLE) && (st->actuation == FSW_ACS_ACT_WHEELS)) {
    safe_output_but_wheel_torques(act);
  } else {
    safe_output(act);
  }

  /* 2b. Wheel speeds and availability for every stage: screened by the
   *     speed filter (in either actuation; the torque it is told of is
   *     last cycle's, known only after a good cycle with wheels active). */
  if (cfg->has_wheels && cfg->use_speed_filter) {
#if FSW_CFG_SPEED_FILTER
    const int n = cfg->rw_map.num_rw;
    r_copy(w->filt_in.Omega_meas, sens->Omega, n);
    u8_copy(w->filt_in.avail, sens->rw_avail, n);
    w->filt_in.t_ns = sens->t_ns;
    r_copy(w->filt_in.u_applied, w->u_last, n);
    w->filt_in.u_valid = u_known;
    /* OK: its inputs were validated above */
    acc = combine(acc, fsw_rw_speed_filter_update(&st->speed_filter, &cfg->speed_filter, &w->filt_in, &w->filt_out));
#else
    (void)u_known; /* not reached: fsw_acs_check rejects the stage */
#endif
  } /* else: the sensors' speeds and flags, read in place (wheel_speeds) */

  if (cfg->has_wheels) /* telemetry: mrp_fb's wheel set, available wheels */ {
    fsw_rw_momentum(h->h_w_B, cfg->mrp_fb.gs_hat_B, cfg->mrp_fb.J_s, wheel_speeds(st, cfg, sens),
                    wheel_flags(st, cfg, sens), cfg->mrp_fb.num_rw); }
  if (st->mode == FSW_ACS_MODE_DETUMBLE) {
    /* 3-5 in DETUMBLE: B-dot alone. */
    fsw_v3_zero(guid.sigma_BR);
    fsw_v3_zero(guid.omega_BR_B);
    g = &guid;
#if FSW_CFG_MTQ
    acc = combine(acc, run_detumble(st, cfg, sens, act, h));
#else
    acc = combine(acc, FSW_E_UNSUPPORTED); /* not reached: fsw_acs_check rejects the stage */
#endif
  } else {
    acc = combine(acc, run_pointing(st, cfg, sens, act, h));
    g = &w->fb_in.guid;
  }

  /* 6. Telemetry and timing. */
  fsw_v3_copy(h->sigma_BR, g->sigma_BR);
  fsw_v3_copy(h->omega_BR_B, g->omega_BR_B);
  h->att_err_angle = fsw_mrp_angle(g->sigma_BR);
  if (fsw_status_is_error_i(acc)) {
    safe_output(act);
    restore_dynamic(st, cfg); /* no state advance on an error cycle */
    safe_health(h);
    return finish(st, cfg, h, acc);
  }
  fsw_clock_commit(&st->clock, sens->t_ns);
  if (st->cycles < UINT32_MAX) { st->cycles++; }
  if (act->wheels_active) { /* the configured wheels (act->u_s is 0 beyond them) */
    r_copy(w->u_last, act->u_s, cfg->rw_map.num_rw);
    w->u_last_valid = 1u;
  }
  if (act->thrusters_active) {
    r_copy(w->t_on_last, act->t_on, thr_count(cfg));
  } else if (cfg->has_thrusters != 0) {
    fsw_vn_zero(w->t_on_last, thr_count(cfg));
  } else {
    /* no thrusters: t_on_last has no entries */
  }
  /* DETUMBLE's exit: the next cycle flies the configured pointing mode */
  if (st->mode == FSW_ACS_MODE_DETUMBLE && h->detumbled && cfg->detumble_exit_mode >= 0) {
    reset_dynamic(st, cfg);
    st->mode = cfg->detumble_exit_mode;
    if (st->mode_changes < UINT32_MAX) { st->mode_changes++; }
  }
  return finish(st, cfg, h, acc);
}

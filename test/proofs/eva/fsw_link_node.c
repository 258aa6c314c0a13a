/* Eva driver: fsw_link_node, the FSW end of the link (fsw/fsw_link_node.h,
 * docs/hwil.md, docs/eva.md) with the application configuration of
 * acs_config.h: init with any max_missed (0 refused), then twice a received
 * packet and a watchdog call at any time stamp (the second round reads the
 * node's memory: last sequence count and time, the kept replies, the
 * missed-period count).  The received packet is any bytes of any length
 * from 0 to the buffer's size in both analyses: the decoded reals are copies
 * of received bits, any double, so the cycle's inputs are outside the
 * envelope by definition (an analysis of fsw_acs itself takes the cycle's
 * sensor inputs in the envelope).  One state per program point
 * (-eva-slevel 0) except in the functions named below: the cycle function
 * (its error returns and DETUMBLE's local guidance kept apart from the
 * pointing modes'), rw_map's update and minimum-norm solve (the number of
 * control axes), and the link functions that parse and decode, so that a
 * packet is read only where it parsed (as fsw_link_rx.c's split); loops of up
 * to 7 iterations unrolled (css_sun's loop over the 6 configured sensors
 * returns from inside).  About 24 s of CPU per analysis.
 * eva-options: -eva-slevel 0 -eva-min-loop-unroll 7 -eva-slevel-function fsw_acs_cycle:8,fsw_rw_map_update:30,fsw_minnorm_solve_factored:30,fsw_link_node_receive:8,on_sensor:8,fsw_link_parse:8,expect:4,fsw_link_decode_sensor:8,fsw_link_decode_cmd:8
 * eva-sources: fsw_link_node.c fsw_link.c fsw_acs.c att_track.c bdot.c css_sun.c fsw_attitude.c fsw_clock.c fsw_linalg.c fsw_status.c fsw_vec.c guid_inertial.c guid_orbit.c guid_sunsafe.c mrp_fb.c mtq_desat.c mtq_map.c rw_bias.c rw_common.c rw_map.c rw_null.c rw_sat.c rw_speed_filter.c rw_volt.c thr_map.c thr_momentum.c thr_pulse_common.c thr_pulse_rem.c thr_pulse_schmitt.c trq_lpf.c */
#include "acs_config.h"

#include "fsw/fsw_link.h"
#include "fsw/fsw_link_node.h"

#define EVA_NODE_BUF (FSW_LINK_MAX_PACKET + 16u)

static void run(void)
{
  static FswAcsConfig cfg;
  static FswLinkNode node;
  static uint8_t buf[EVA_NODE_BUF];
  const char *bad;
  FswStatus s;
  int k;
  eva_acs_config(&cfg);
  s = fsw_link_node_init(&node, &cfg, Frama_C_unsigned_int_interval(0u, UINT32_MAX), &bad);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) {
    Frama_C_make_unknown((char *)buf, sizeof buf);
    EVA_ENTRY(receive, fsw_link_node_receive(&node, &cfg, buf, Frama_C_size_t_interval(0u, sizeof buf)));
    EVA_ENTRY(watchdog, fsw_link_node_watchdog(&node, eva_u64()));
  }
}

EVA_MAINS

/* Eva driver: fsw_link_node, the FSW end of the link (fsw/fsw_link_node.h,
 * docs/hwil.md, docs/icd.md, docs/eva.md) with the application
 * configuration of acs_config.h: init with any max_missed (0 refused), then
 * twice a received packet and a watchdog call at any time stamp (the second
 * round reads the node's memory: last sequence count and time, the kept
 * command and replies, the missed-period count).
 *
 * The received packet:
 *   any       any bytes of any length from 0 to the buffer's size: every
 *             framing, CRC and decoder rejection, and every decoded real
 *             any double (a copy of received bits);
 *   envelope  a well-formed packet, as the sim side sends it
 *             (harness/src/link/remote_fsw.cpp): a sensor packet that
 *             fsw_link_encode_sensor makes of an envelope sensor message
 *             (eva_acs_sensors, the fsw_acs driver's, with the configured
 *             counts 4 and 6, the flags as the wire carries them, 0 or 1)
 *             or a command packet that fsw_link_encode_cmd makes of an
 *             envelope command (eva_acs_cmd, its set flags 0 or 1), any
 *             sequence count 0..16383, any time stamp: new, repeated
 *             (a retransmission), old or gapped packets.  The UDP security
 *             trailer (fsw_link_sec) is checked and removed by the transport
 *             before the node (docs/icd.md), so a packet carries none here.
 *
 * In the envelope analysis the two decoders the node calls are taken by
 * their contract below (-eva-use-spec, that analysis only): the message
 * decoded from such a packet is the message encoded, field by field
 * (fsw_link's round trip, bit for bit: test_fsw_link's
 * EveryPacketRoundTripsAtZeroAndFullCapacity and, for this domain through
 * the node, test_fsw_link_node's
 * TheApplicationGetsTheEncodedMessagesBitForBit; REQ-LINK-003).  Eva cannot
 * carry that through the codec itself: a real travels as its 64 bits,
 * big-endian, and the bit patterns of [-1e6, 1e6] are two unsigned ranges
 * (the positive and the negative reals), which Eva's intervals join into one
 * that holds the NaN and infinity patterns, so every decoded real would be
 * any double.  The decoders' own absence of run-time errors is the `any`
 * analysis's (here, in the node, for any bytes) and fsw_link_rx's; the
 * parser, the node's sequence and link-safe logic, the cycle and the reply
 * encoders are analysed in both.
 *
 * One state per program point (-eva-slevel 0) except in the functions named
 * below: the cycle function (its error returns and DETUMBLE's local guidance
 * kept apart from the pointing modes'), rw_map's update and minimum-norm
 * solve (the number of control axes), and the link functions that parse and
 * decode, so that a packet is read only where it parsed (as fsw_link_rx.c's
 * split); loops of up to 7 iterations unrolled (css_sun's loop over the 6
 * configured sensors returns from inside).  About 15 s of CPU per analysis.
 * eva-options: -eva-slevel 0 -eva-min-loop-unroll 7 -eva-slevel-function fsw_acs_cycle:8,fsw_rw_map_update:30,fsw_minnorm_solve_factored:30,fsw_link_node_receive:8,on_sensor:8,fsw_link_parse:8,expect:4,fsw_link_decode_sensor:8,fsw_link_decode_cmd:8
 * eva-options-envelope: -eva-use-spec fsw_link_decode_sensor,fsw_link_decode_cmd
 * eva-sources: fsw_link_node.c fsw_link.c fsw_acs.c att_track.c bdot.c css_sun.c fsw_attitude.c fsw_clock.c fsw_linalg.c fsw_status.c fsw_vec.c guid_inertial.c guid_orbit.c guid_sunsafe.c mrp_fb.c mtq_desat.c mtq_map.c rw_bias.c rw_common.c rw_map.c rw_null.c rw_sat.c rw_speed_filter.c rw_volt.c thr_map.c thr_momentum.c thr_pulse_common.c thr_pulse_rem.c thr_pulse_schmitt.c trq_lpf.c */
#include "acs_config.h"

#include "fsw/fsw_link.h"
#include "fsw/fsw_link_node.h"

#define EVA_NODE_BUF (FSW_LINK_MAX_PACKET + 16u)
#define EVA_NODE_RW 4u  /* acs_config.h's counts: what the sim side puts in a sensor packet */
#define EVA_NODE_CSS 6u

/* The messages of the envelope analysis's last encoded sensor and command
 * packets: what the decoders' contract returns. */
static FswAcsSensorMsg eva_node_sens;
static FswAcsCmdMsg eva_node_cmd;

/* The decoders' contract in the envelope analysis (eva_any_mode == 0; in
 * the `any` analysis Eva analyses their code, and this behaviour does not
 * apply): a packet the node hands them is one the driver encoded (the node
 * calls fsw_link_decode_sensor for a parsed packet of the sensor APID, and
 * fsw_link_decode_cmd for any other parsed packet, here a command packet),
 * and it decodes to the message encoded, every field (with the configured
 * counts, the entries beyond them are the encoded message's zeros). */
#define EVA_S(f) (\is_finite(m->f) && m->f == eva_node_sens.f)
#define EVA_S4(f, i) EVA_S(f[i]) && EVA_S(f[i + 1]) && EVA_S(f[i + 2]) && EVA_S(f[i + 3])
#define EVA_S12(f, i) EVA_S4(f, i) && EVA_S4(f, i + 4) && EVA_S4(f, i + 8)
#define EVA_B(f) m->f == eva_node_sens.f
#define EVA_B4(f, i) EVA_B(f[i]) && EVA_B(f[i + 1]) && EVA_B(f[i + 2]) && EVA_B(f[i + 3])
#define EVA_B12(f, i) EVA_B4(f, i) && EVA_B4(f, i + 4) && EVA_B4(f, i + 8)
#define EVA_C(f) (\is_finite(m->f) && m->f == eva_node_cmd.f)
/*@ assigns \result, *m, *num_rw, *num_css \from eva_node_sens;
    behavior eva_envelope:
      assumes eva_any_mode == 0;
      ensures \result == FSW_OK;
      ensures *num_rw == EVA_NODE_RW && *num_css == EVA_NODE_CSS;
      ensures m->t_ns == eva_node_sens.t_ns;
      ensures EVA_S(sigma_BN[0]) && EVA_S(sigma_BN[1]) && EVA_S(sigma_BN[2]);
      ensures EVA_S(omega_BN_B[0]) && EVA_S(omega_BN_B[1]) && EVA_S(omega_BN_B[2]);
      ensures EVA_S12(css, 0) && EVA_S12(css, 12) && EVA_S4(css, 24) && EVA_S4(css, 28);
      ensures EVA_S12(Omega, 0) && EVA_S12(Omega, 12) && EVA_S12(Omega, 24);
      ensures EVA_S(r_CoM_B[0]) && EVA_S(r_CoM_B[1]) && EVA_S(r_CoM_B[2]);
      ensures EVA_S(B_B[0]) && EVA_S(B_B[1]) && EVA_S(B_B[2]);
      ensures EVA_S(r_N[0]) && EVA_S(r_N[1]) && EVA_S(r_N[2]);
      ensures EVA_S(v_N[0]) && EVA_S(v_N[1]) && EVA_S(v_N[2]);
      ensures EVA_B(att_valid) && EVA_B(mag_valid) && EVA_B(orbit_valid);
      ensures EVA_B12(css_avail, 0) && EVA_B12(css_avail, 12) && EVA_B4(css_avail, 24) && EVA_B4(css_avail, 28);
      ensures EVA_B12(rw_avail, 0) && EVA_B12(rw_avail, 12) && EVA_B12(rw_avail, 24);
      ensures EVA_B12(thr_avail, 0) && EVA_B12(thr_avail, 12) && EVA_B12(thr_avail, 24);
*/
FswStatus fsw_link_decode_sensor(const FswLinkPacket *p, FswAcsSensorMsg *m, uint8_t *num_rw, uint8_t *num_css,
                                 FswLinkError *err);

/*@ assigns \result, *m \from eva_node_cmd;
    behavior eva_envelope:
      assumes eva_any_mode == 0;
      ensures \result == FSW_OK;
      ensures m->mode == eva_node_cmd.mode && m->actuation == eva_node_cmd.actuation;
      ensures m->set_ref == eva_node_cmd.set_ref && m->set_gains == eva_node_cmd.set_gains;
      ensures m->set_policy == eva_node_cmd.set_policy && m->policy == eva_node_cmd.policy;
      ensures EVA_C(sigma_R0N[0]) && EVA_C(sigma_R0N[1]) && EVA_C(sigma_R0N[2]);
      ensures EVA_C(K) && EVA_C(P);
*/
FswStatus fsw_link_decode_cmd(const FswLinkPacket *p, FswAcsCmdMsg *m, FswLinkError *err);

/* The sensor message as the wire carries it: the flags 0 or 1 (the encoder
 * sends a validity flag as 0/1 and the thruster flags as bits; a wheel or
 * sun sensor flag other than 0/1 makes the decoder refuse the packet), the
 * entries beyond the counts 0 (not sent; decoded as 0). */
static void eva_node_wire_sensors(FswAcsSensorMsg *m)
{
  int i;
  m->att_valid = (uint8_t)(m->att_valid != 0u);
  m->mag_valid = (uint8_t)(m->mag_valid != 0u);
  m->orbit_valid = (uint8_t)(m->orbit_valid != 0u);
  /*@ loop unroll 64; */
  for (i = 0; i < FSW_MAX_RW; i++) {
    m->rw_avail[i] = (uint8_t)(i < (int)EVA_NODE_RW && m->rw_avail[i] != 0u);
    if (i >= (int)EVA_NODE_RW) m->Omega[i] = 0.0;
  }
  /*@ loop unroll 64; */
  for (i = 0; i < FSW_MAX_CSS; i++) {
    m->css_avail[i] = (uint8_t)(i < (int)EVA_NODE_CSS && m->css_avail[i] != 0u);
    if (i >= (int)EVA_NODE_CSS) m->css[i] = 0.0;
  }
  /*@ loop unroll 64; */
  for (i = 0; i < FSW_MAX_THR; i++) m->thr_avail[i] = (uint8_t)(m->thr_avail[i] != 0u);
}

/* A well-formed packet of the envelope into buf[0..*len): a sensor or a
 * command packet, encoded by the library as the sim side does. */
static void eva_node_packet(uint8_t *buf, size_t cap, size_t *len)
{
  FswStatus s;
  const uint16_t seq = (uint16_t)eva_int(0, (int)FSW_LINK_SEQ_MODULO - 1);
  if (eva_int(0, 1) != 0) {
    eva_acs_sensors(&eva_node_sens);
    eva_node_wire_sensors(&eva_node_sens);
    s = fsw_link_encode_sensor(&eva_node_sens, EVA_NODE_RW, EVA_NODE_CSS, seq, buf, cap, len, NULL);
  } else {
    eva_acs_cmd(&eva_node_cmd);
    eva_node_cmd.set_ref = (uint8_t)(eva_node_cmd.set_ref != 0u);
    eva_node_cmd.set_gains = (uint8_t)(eva_node_cmd.set_gains != 0u);
    eva_node_cmd.set_policy = (uint8_t)(eva_node_cmd.set_policy != 0u);
    s = fsw_link_encode_cmd(&eva_node_cmd, eva_u64(), seq, buf, cap, len, NULL);
  }
  /*@ assert eva_node_well_formed: s == FSW_OK; */
}

static void run(void)
{
  static FswAcsConfig cfg;
  static FswLinkNode node;
  static uint8_t buf[EVA_NODE_BUF];
  const char *bad;
  FswStatus s;
  size_t len;
  int k;
  eva_acs_config(&cfg);
  s = fsw_link_node_init(&node, &cfg, Frama_C_unsigned_int_interval(0u, UINT32_MAX), &bad);
  EVA_ENTRY(init, s);
  if (s != FSW_OK) return;
  for (k = 0; k < 2; k++) {
    if (eva_any_mode) {
      Frama_C_make_unknown((char *)buf, sizeof buf);
      len = Frama_C_size_t_interval(0u, sizeof buf);
    } else {
      eva_node_packet(buf, sizeof buf, &len);
    }
    EVA_ENTRY(receive, fsw_link_node_receive(&node, &cfg, buf, len));
    EVA_ENTRY(watchdog, fsw_link_node_watchdog(&node, eva_u64()));
  }
}

EVA_MAINS

// cfs_link: the FSW link's cFS profile (--fsw cfs:HOST:PORT[:TLMPORT],
// docs/hwil.md "cFS"): the KESTREL_ACS application inside a NASA core Flight
// System, reached through cFS's own lab command and telemetry path.
// (--fsw cfs:HOST also works: PORT 1234, TLMPORT 1235.)
//
//   uplink    each ICD packet the harness sends (sensor 0x101, command
//             0x102) goes out whole as the payload of a cFS command,
//             message id 0x18F1 (KESTREL_ACS_LINK_MID), function code 0, in
//             a UDP datagram to ci_lab at HOST:PORT (default port 1234);
//   downlink  to_lab sends every message it is subscribed to as a UDP
//             datagram to TLMPORT (default 1235) on this machine; the
//             transport keeps the actuator (0x08F1) and health (0x08F2)
//             messages and hands on the ICD packet they carry (after the
//             16-byte cFS telemetry header); everything else to_lab sends
//             (housekeeping of every app, events) is counted and dropped.
//
// At link start it enables to_lab's output towards this machine's address
// (TO_LAB_OUTPUT_ENABLE, function code 6 on 0x1880), subscribes to_lab to
// 0x08F0..0x08F2 (TO_LAB_ADD_PKT, code 2) and asks KESTREL_ACS for its
// housekeeping (0x18F2) until it comes, within a bounded time; the
// housekeeping says whether a configuration table is loaded.
//
// The application sends no link status packet: a cycle ends with its
// health packet (LinkTransport::sends_link_status), and nothing is
// retransmitted (the application runs every sensor packet it receives).
#ifndef HARNESS_CFS_LINK_H
#define HARNESS_CFS_LINK_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "harness/link/remote_fsw.h"

namespace harness {

// A cFS command message: the 8-byte command header (stream id mid, sequence
// flags "unsegmented" with sequence count seq, length, function code cc,
// checksum: the XOR of every byte of the message is 0xFF, as cFE's
// CFE_MSG_GenerateChecksum makes it) followed by payload.
std::vector<uint8_t> cfs_command(uint16_t mid, uint8_t cc, uint16_t seq, const uint8_t* payload, size_t n);

// KESTREL_ACS's housekeeping (0x08F0), fields big-endian in the payload.
struct CfsAcsHk {
  uint8_t command_count = 0, command_error_count = 0, mode = 0, config_loaded = 0;
  uint32_t cycles = 0, cycle_errors = 0, link_rejected = 0, last_status = 0, table_rejects = 0;
};
// Decodes a whole 0x08F0 telemetry message; false when it is not one.
bool cfs_decode_hk(const uint8_t* msg, size_t n, CfsAcsHk& hk);

// "HOST[:PORT[:TLMPORT]]" (IPv4 HOST; ports by default 1234 and 1235, the
// lab apps').  Throws FswEndpointError naming the
// reason: bad spec, TLMPORT busy, or no housekeeping from KESTREL_ACS
// through to_lab within timeout_s, or an application without a valid
// configuration table.
std::unique_ptr<LinkTransport> open_cfs_transport(const std::string& spec, double timeout_s);

}  // namespace harness

#endif  // HARNESS_CFS_LINK_H

/* The flight codec's constants (fsw/fsw_link.h, fsw_config.h) against the
 * packet table's (icd/generated/kestrel_icd.h, written by tools/icd_gen.py
 * from icd/packets.yaml): APIDs, header and CRC sizes, the ICD version, the
 * capacities, and every packet's payload size for counts from none to the
 * capacities.  Prints each disagreement; exit 1 if any. */
#include <stdio.h>

#include "fsw/fsw_link.h"
#include "kestrel_icd.h"

static int bad = 0;

static void same(const char *what, unsigned long codec, unsigned long table)
{
  if (codec != table) {
    printf("%s: fsw_link %lu, packet table %lu\n", what, codec, table);
    bad = 1;
  }
}

int main(void)
{
  static const unsigned counts[] = {0u, 1u, 3u, 4u, 8u, 17u};
  const unsigned char check[] = "123456789";
  size_t a, b, c;
  same("ICD version", FSW_LINK_ICD_VERSION, KESTREL_ICD_VERSION);
  same("header size", FSW_LINK_HEADER_SIZE, KESTREL_ICD_HEADER_SIZE);
  same("CRC size", FSW_LINK_CRC_SIZE, KESTREL_ICD_CRC_SIZE);
  same("CRC check value", fsw_link_crc16(check, 9u, KESTREL_ICD_CRC_INIT), KESTREL_ICD_CRC_CHECK);
  same("FSW_MAX_RW", FSW_MAX_RW, KESTREL_ICD_FSW_MAX_RW);
  same("FSW_MAX_CSS", FSW_MAX_CSS, KESTREL_ICD_FSW_MAX_CSS);
  same("FSW_MAX_THR", FSW_MAX_THR, KESTREL_ICD_FSW_MAX_THR);
  same("FSW_MAX_MTQ", FSW_MAX_MTQ, KESTREL_ICD_FSW_MAX_MTQ);
  same("sensor APID", FSW_LINK_APID_SENSOR, KESTREL_ICD_SENSOR_APID);
  same("command APID", FSW_LINK_APID_CMD, KESTREL_ICD_COMMAND_APID);
  same("actuator APID", FSW_LINK_APID_ACTUATOR, KESTREL_ICD_ACTUATOR_APID);
  same("health APID", FSW_LINK_APID_HEALTH, KESTREL_ICD_HEALTH_APID);
  same("link status APID", FSW_LINK_APID_LINK, KESTREL_ICD_LINK_STATUS_APID);
  same("command payload", FSW_LINK_CMD_PAYLOAD, KESTREL_ICD_COMMAND_PAYLOAD);
  same("health payload", FSW_LINK_HEALTH_PAYLOAD, KESTREL_ICD_HEALTH_PAYLOAD);
  same("link status payload", FSW_LINK_STATUS_PAYLOAD, KESTREL_ICD_LINK_STATUS_PAYLOAD);
  for (a = 0u; a < sizeof counts / sizeof counts[0]; ++a)
    for (b = 0u; b < sizeof counts / sizeof counts[0]; ++b) {
      same("sensor payload", FSW_LINK_SENSOR_PAYLOAD(counts[a], counts[b]),
           KESTREL_ICD_SENSOR_PAYLOAD(counts[a], counts[b]));
      for (c = 0u; c < sizeof counts / sizeof counts[0]; ++c)
        same("actuator payload", FSW_LINK_ACTUATOR_PAYLOAD(counts[a], counts[b], counts[c]),
             KESTREL_ICD_ACTUATOR_PAYLOAD(counts[a], counts[b], counts[c]));
    }
  same("full sensor payload", FSW_LINK_SENSOR_PAYLOAD(FSW_MAX_RW, FSW_MAX_CSS),
       KESTREL_ICD_SENSOR_PAYLOAD(KESTREL_ICD_FSW_MAX_RW, KESTREL_ICD_FSW_MAX_CSS));
  same("full actuator payload", FSW_LINK_ACTUATOR_PAYLOAD(FSW_MAX_RW, FSW_MAX_THR, FSW_MAX_MTQ),
       KESTREL_ICD_ACTUATOR_PAYLOAD(KESTREL_ICD_FSW_MAX_RW, KESTREL_ICD_FSW_MAX_THR, KESTREL_ICD_FSW_MAX_MTQ));
  printf("%s\n", bad ? "fsw_link.h and the packet table disagree" : "fsw_link.h agrees with the packet table");
  return bad;
}

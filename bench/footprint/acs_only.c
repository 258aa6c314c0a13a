/* acs-only: the flight application fsw_acs without the FSW link, for the
 * footprint figures (bench/flight-footprint.sh).  The configuration is a
 * FswAcsConfig placed in flash by the integrator (here read from the address
 * the PIL program uses for its configuration image); the sensor and command
 * messages arrive in, and the actuator and health messages leave through,
 * mailboxes in RAM that another task or a DMA engine would fill.  No stdio,
 * no heap: what is left is the ACS chain, its maths and the C start-up. */
#include <stddef.h>
#include <stdint.h>

#include "fsw/fsw_acs.h"

#define CONFIG_ADDR 0x00380000u

void fsw_assert_failed(const char *file, int line);
void fsw_assert_failed(const char *file, int line)
{
  (void)file;
  (void)line;
}

typedef struct {
  volatile uint32_t ready;   /* set by the producer, cleared here */
  FswAcsSensorMsg sens;
  FswAcsCmdMsg cmd;
  uint32_t has_cmd;
} InBox;

typedef struct {
  volatile uint32_t seq;
  FswAcsActuatorMsg act;
  FswAcsHealthMsg hlth;
} OutBox;

static FswAcsConfig cfg;
static FswAcsState st;
static InBox in_box;
static OutBox out_box;
/* the mailboxes' addresses, as another task would see them */
volatile void *const kestrel_acs_mailboxes[2] = {&in_box, &out_box};

int main(void)
{
  const FswAcsConfig *image = (const FswAcsConfig *)CONFIG_ADDR;
  cfg = *image;
  if (fsw_acs_init(&st, &cfg, NULL) != FSW_OK) return 1;
  for (;;) {
    if (in_box.ready != 0u) {
      (void)fsw_acs_cycle(&st, &cfg, &in_box.sens, in_box.has_cmd != 0u ? &in_box.cmd : NULL, &out_box.act,
                          &out_box.hlth);
      in_box.ready = 0u;
      out_box.seq++;
    }
  }
}

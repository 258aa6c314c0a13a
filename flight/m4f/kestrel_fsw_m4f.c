/* kestrel-fsw-m4f: the flight application fsw_acs behind the FSW link on a
 * bare-metal Cortex-M4F (QEMU mps2-an386 or an MPS2 board), for
 * processor-in-the-loop runs (docs/pil.md).  Application code, not flight
 * library: C99, no heap, all storage static and fixed in size, bounded
 * stack (no recursion, no VLA).
 *
 *   - Link: CMSDK APB UART0 (0x40004000), 8N1 byte stream, packets framed by
 *     the attached sync marker and deframed by fsw_link_deframer (fsw_c/).
 *     RX by interrupt into a ring buffer (the main loop sleeps in WFI while
 *     there is nothing to do), TX polled.
 *   - Configuration: a configuration image (`kestrel fsw-config`, icd.md)
 *     read from flash at KESTREL_M4F_CONFIG_ADDR; the harness places it there
 *     with QEMU's generic loader, a bench would program it into flash with
 *     the code.  Decoded and checked (fsw_acs_check) before the link starts;
 *     a refused image ends the program with a message on the semihosting
 *     console and exit status 1.
 *   - Lockstep: every accepted sensor packet runs one fsw_acs_cycle and is
 *     answered by the actuator, health and link status packets
 *     (fsw_link_node); the host's packets pace the control loop.  No
 *     watchdog timer in this build (see docs/pil.md).
 * Output on the semihosting console (QEMU's stderr): one line when ready,
 * one line when the configuration is refused. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fsw/fsw_link.h"
#include "fsw/fsw_link_node.h"

#ifndef KESTREL_M4F_CONFIG_ADDR
#define KESTREL_M4F_CONFIG_ADDR 0x00380000u /* last 512 KiB of the 4 MiB code region */
#endif
#define CONFIG_REGION_SIZE 0x00080000u

/* CMSDK APB UART */
typedef struct {
  volatile uint32_t DATA;
  volatile uint32_t STATE;  /* bit0 TX full, bit1 RX full */
  volatile uint32_t CTRL;   /* bit0 TX en, bit1 RX en, bit3 RX irq */
  volatile uint32_t INTSTATUS;
  volatile uint32_t BAUDDIV;
} CmsdkUart;
#define UART0 ((CmsdkUart *)0x40004000u)
#define UART0_RX_IRQ 0u
#define UART_STATE_TXFULL 1u
#define UART_STATE_RXFULL 2u
#define PCLK_HZ 25000000u
#define LINK_BAUD 115200u

#define SCB_VTOR (*(volatile uint32_t *)0xE000ED08u)
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define NUM_VECTORS 48u

typedef void (*Vector)(void);
extern const Vector __interrupt_vector[]; /* picolibc's table: the 16 system exceptions */

/* The integrator's assert hook (fsw_c calls it, then returns its safe output). */
void fsw_assert_failed(const char *file, int line);
void fsw_assert_failed(const char *file, int line) { (void)fprintf(stderr, "kestrel-fsw-m4f: FSW assertion failed at %s:%d\n", file, line); }

static Vector g_vectors[NUM_VECTORS] __attribute__((aligned(256)));
#define RX_RING 1024u /* power of two; > one sensor packet with its marker (786 + 4 at most, ICD 2) */
static volatile uint8_t g_rx_ring[RX_RING];
static volatile uint32_t g_rx_head; /* written by the ISR only */
static volatile uint32_t g_rx_tail; /* written by the main loop only */
static volatile uint32_t g_rx_dropped;

static FswLinkNode g_node;
static FswAcsConfig g_cfg;
static FswLinkDeframer g_deframer;
static uint8_t g_tx[FSW_LINK_ASM_SIZE + FSW_LINK_MAX_PACKET];

void uart0_rx_isr(void);
void uart0_rx_isr(void)
{
  UART0->INTSTATUS = 2u; /* clear first: the interrupt is level-driven by RX full */
  while ((UART0->STATE & UART_STATE_RXFULL) != 0u) {
    const uint8_t b = (uint8_t)UART0->DATA;
    if (g_rx_head - g_rx_tail < RX_RING) {
      g_rx_ring[g_rx_head & (RX_RING - 1u)] = b;
      g_rx_head = g_rx_head + 1u;
    } else {
      g_rx_dropped = g_rx_dropped + 1u; /* the deframer resynchronises on the next marker */
    }
  }
}

static void uart_init(void)
{
  uint32_t i;
  for (i = 0; i < 16u; ++i) { g_vectors[i] = __interrupt_vector[i]; }
  for (i = 16u; i < NUM_VECTORS; ++i) { g_vectors[i] = __interrupt_vector[2]; } /* NMI handler: unexpected */
  g_vectors[16u + UART0_RX_IRQ] = uart0_rx_isr;
  SCB_VTOR = (uint32_t)(uintptr_t)g_vectors;
  __asm volatile("dsb\n\tisb" ::: "memory");
  UART0->BAUDDIV = PCLK_HZ / LINK_BAUD;
  UART0->CTRL = 0x1u | 0x2u | 0x8u; /* TX and RX enabled before the first write; RX interrupt */
  NVIC_ISER0 = 1u << UART0_RX_IRQ;
}

static void uart_write(const uint8_t *p, size_t n)
{
  size_t i;
  for (i = 0; i < n; ++i) {
    while ((UART0->STATE & UART_STATE_TXFULL) != 0u) {
    }
    UART0->DATA = p[i];
  }
}

static void send_replies(int count)
{
  int i;
  for (i = 0; i < count; ++i) {
    size_t len = 0;
    if (fsw_link_frame(g_node.out[i], g_node.out_len[i], g_tx, sizeof g_tx, &len) == FSW_OK) { uart_write(g_tx, len); }
  }
}

static uint32_t be32(const uint8_t *p)
{
  return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | (uint32_t)p[3];
}

static const char *image_error(FswLinkError e)
{
  switch (e) {
    case FSW_LINK_E_SHORT: return "truncated";
    case FSW_LINK_E_HEADER: return "not a configuration image of this build (magic, version, layout or capacities)";
    case FSW_LINK_E_CRC: return "CRC mismatch";
    case FSW_LINK_E_LENGTH: return "wrong length";
    default: return "no image (length out of range)";
  }
}

static int load_config(void)
{
  const uint8_t *img = (const uint8_t *)(uintptr_t)KESTREL_M4F_CONFIG_ADDR;
  /* header (20 bytes) + body + CRC (2); the length is bounded before use and
   * the decoder checks header, length and CRC */
  const uint32_t body = be32(img + 16);
  const size_t n = body <= CONFIG_REGION_SIZE - FSW_LINK_CONFIG_HEADER - 2u ? FSW_LINK_CONFIG_HEADER + body + 2u : 0u;
  FswLinkError why = FSW_LINK_OK;
  const char *bad = NULL;
  FswStatus s;
  if (n == 0u || fsw_link_config_decode(img, n, &g_cfg, &why) != FSW_OK) {
    (void)fprintf(stderr, "kestrel-fsw-m4f: configuration image at 0x%08lx refused: %s\n",
            (unsigned long)KESTREL_M4F_CONFIG_ADDR, image_error(why));
    return -1;
  }
  s = fsw_acs_check(&g_cfg, &bad);
  if (s == FSW_OK) { s = fsw_link_node_init(&g_node, &g_cfg, 3u, &bad); }
  if (s != FSW_OK) {
    (void)fprintf(stderr, "kestrel-fsw-m4f: configuration refused: %s (field %s)\n", fsw_status_name(s),
            bad != NULL ? bad : "?");
    return -1;
  }
  return 0;
}

int main(void)
{
  uint8_t chunk[64];
  uint32_t deframer_rejected = 0;
  if (load_config() != 0) { return 1; }
  fsw_link_deframer_init(&g_deframer);
  uart_init();
  fprintf(stderr, "kestrel-fsw-m4f: ready (UART0, %s)\n", sizeof(fsw_real) == 4u ? "float" : "double");
  for (;;) {
    size_t n = 0, used = 0;
    /* sleep until a byte arrives; WFI wakes on a pending interrupt even
     * with PRIMASK set, so no wake-up is lost between the test and WFI */
    __asm volatile("cpsid i" ::: "memory");
    if (g_rx_head == g_rx_tail) { __asm volatile("wfi" ::: "memory"); }
    __asm volatile("cpsie i" ::: "memory");
    while (n < sizeof chunk && g_rx_tail != g_rx_head) {
      chunk[n++] = g_rx_ring[g_rx_tail & (RX_RING - 1u)];
      g_rx_tail = g_rx_tail + 1u;
    }
    while (used < n) {
      const uint8_t *pkt = NULL;
      size_t plen = 0;
      used += fsw_link_deframer_push(&g_deframer, chunk + used, n - used, &pkt, &plen);
      if (pkt != NULL) { send_replies(fsw_link_node_receive(&g_node, &g_cfg, pkt, plen)); }
    }
    /* candidates the deframer rejected (header, length, CRC) count as CRC
     * rejections in the link status, as in kestrel-fsw */
    g_node.link.rx_crc += g_deframer.rejected - deframer_rejected;
    deframer_rejected = g_deframer.rejected;
  }
}

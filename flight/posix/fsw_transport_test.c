/* fsw_transport_test: the FSW link's POSIX transports, both ends in this
 * process.  Packets are real command packets (fsw_link_encode_cmd: 6 bytes
 * primary header, 8 secondary (t_ns), 46 payload, 2 CRC = 62 bytes, docs/
 * icd.md); what comes out must be byte for byte what went in.
 *
 *   stream (socket pair): two frames in one write come out as two packets
 *     without a second read; a frame cut into 1-byte writes comes out whole;
 *     3 junk bytes before a frame are skipped; a frame with a flipped CRC
 *     bit is rejected (deframer rejected = 1) and the next one delivered; a
 *     quiet stream times out after the timeout (>= 40 ms of a 50 ms wait,
 *     ms clock); a closed peer reads as FSW_TRANSPORT_CLOSED.
 *   serial (pty pair): "SLAVE:115200" opens raw; packets go both ways;
 *     a bad baud rate and a spec without a colon are refused with messages.
 *   UDP: bound "127.0.0.1:0" gets a port (desc); before anything arrives
 *     its send is a no-op; connected -> bound -> reply to the last sender ->
 *     connected; connected to a port nobody listens on times out. */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, ptsname */
#define _DEFAULT_SOURCE 1
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "transport/fsw_transport.h"

static int g_failures = 0;

#define CHECK(cond)                                                   \
  do {                                                                \
    if (!(cond)) {                                                    \
      fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++g_failures;                                                   \
    }                                                                 \
  } while (0)

static FswTransport g_a, g_b;

static size_t make_packet(uint8_t *buf, size_t cap, uint64_t t_ns, uint16_t seq)
{
  FswAcsCmdMsg cmd;
  size_t len = 0;
  memset(&cmd, 0, sizeof cmd);
  cmd.mode = 1u;
  CHECK(fsw_link_encode_cmd(&cmd, t_ns, seq, buf, cap, &len, NULL) == FSW_OK);
  return len;
}

/* Receives one packet from t within timeout_ms and compares it with want. */
static void expect_packet(FswTransport *t, const uint8_t *want, size_t n, int timeout_ms)
{
  const uint8_t *p = NULL;
  size_t len = 0;
  const int rc = fsw_transport_recv(t, &p, &len, timeout_ms);
  CHECK(rc == FSW_TRANSPORT_PACKET);
  CHECK(rc != FSW_TRANSPORT_PACKET || (len == n && memcmp(p, want, n) == 0));
}

static long long ms_now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static void test_stream(void)
{
  int sv[2];
  uint8_t p1[FSW_LINK_MAX_PACKET], p2[FSW_LINK_MAX_PACKET], f[2 * (FSW_LINK_ASM_SIZE + FSW_LINK_MAX_PACKET)];
  size_t n1, n2, l1 = 0, l2 = 0, i;
  const uint8_t *p = NULL;
  size_t len = 0;
  long long t0;
  CHECK(socketpair(AF_UNIX, SOCK_STREAM, 0, sv) == 0);
  fsw_transport_open_stream(&g_a, sv[0], "a");
  fsw_transport_open_stream(&g_b, sv[1], "b");
  CHECK(g_a.stream == 1 && g_a.is_socket == 1);
  n1 = make_packet(p1, sizeof p1, 1000u, 1u);
  n2 = make_packet(p2, sizeof p2, 2000u, 2u);
  CHECK(n1 == 62u);
  /* two frames in one write */
  CHECK(fsw_link_frame(p1, n1, f, sizeof f, &l1) == FSW_OK);
  CHECK(fsw_link_frame(p2, n2, f + l1, sizeof f - l1, &l2) == FSW_OK);
  CHECK(write(sv[0], f, l1 + l2) == (ssize_t)(l1 + l2));
  expect_packet(&g_b, p1, n1, 1000);
  CHECK(g_b.used < g_b.have); /* the second frame is still buffered */
  expect_packet(&g_b, p2, n2, 0);
  /* one byte at a time, after 3 junk bytes */
  CHECK(write(sv[0], "\x01\x02\x03", 3) == 3);
  for (i = 0; i < l1; ++i) CHECK(write(sv[0], f + i, 1) == 1);
  expect_packet(&g_b, p1, n1, 1000);
  /* a flipped CRC bit: rejected, the next frame delivered */
  f[l1 - 1] ^= 0x01u;
  CHECK(write(sv[0], f, l1 + l2) == (ssize_t)(l1 + l2));
  expect_packet(&g_b, p2, n2, 1000);
  CHECK(g_b.deframer.rejected == 1u);
  /* both ways through fsw_transport_send */
  CHECK(fsw_transport_send(&g_b, p1, n1) == 0);
  expect_packet(&g_a, p1, n1, 1000);
  /* quiet: a timeout after the wait */
  t0 = ms_now();
  CHECK(fsw_transport_recv(&g_b, &p, &len, 50) == FSW_TRANSPORT_TIMEOUT);
  CHECK(ms_now() - t0 >= 40);
  CHECK(p == NULL && len == 0u);
  /* the peer closes */
  fsw_transport_close(&g_a);
  CHECK(fsw_transport_recv(&g_b, &p, &len, 1000) == FSW_TRANSPORT_CLOSED);
  fsw_transport_close(&g_b);
  CHECK(g_b.fd == -1);
}

static void test_serial(void)
{
  char spec[160], err[256];
  uint8_t p1[FSW_LINK_MAX_PACKET];
  size_t n1 = make_packet(p1, sizeof p1, 3000u, 3u);
  const int m = posix_openpt(O_RDWR | O_NOCTTY);
  CHECK(m >= 0 && grantpt(m) == 0 && unlockpt(m) == 0);
  snprintf(spec, sizeof spec, "%s:115200", ptsname(m));
  CHECK(fsw_transport_open_serial(&g_a, spec, err, sizeof err) == 0);
  CHECK(strncmp(g_a.desc, "serial /dev/pts/", 16) == 0 && strstr(g_a.desc, " 115200 baud") != NULL);
  CHECK(g_a.stream == 1 && g_a.is_socket == 0);
  fsw_transport_open_stream(&g_b, m, "pty master");
  CHECK(fsw_transport_send(&g_a, p1, n1) == 0);
  expect_packet(&g_b, p1, n1, 1000);
  CHECK(fsw_transport_send(&g_b, p1, n1) == 0);
  expect_packet(&g_a, p1, n1, 1000);
  fsw_transport_close(&g_a);
  fsw_transport_close(&g_b);
  snprintf(spec, sizeof spec, "/dev/null:1234");
  CHECK(fsw_transport_open_serial(&g_a, spec, err, sizeof err) == -1);
  CHECK(strcmp(err, "unsupported baud rate '1234' (9600 ... 921600)") == 0);
  CHECK(fsw_transport_open_serial(&g_a, "/dev/null", err, sizeof err) == -1);
  CHECK(strcmp(err, "bad serial line '/dev/null' (expected DEVICE:BAUD)") == 0);
  CHECK(fsw_transport_open_serial(&g_a, "/dev/null:115200", err, sizeof err) == -1);
  CHECK(strncmp(err, "/dev/null is not a terminal: ", 29) == 0);
  CHECK(g_a.fd == -1);
}

static void test_udp(void)
{
  char err[256], spec[160];
  uint8_t p1[FSW_LINK_MAX_PACKET], p2[FSW_LINK_MAX_PACKET];
  const size_t n1 = make_packet(p1, sizeof p1, 4000u, 4u), n2 = make_packet(p2, sizeof p2, 5000u, 5u);
  const uint8_t *p = NULL;
  size_t len = 0;
  CHECK(fsw_transport_open_udp(&g_a, "127.0.0.1:0", err, sizeof err) == 0);
  CHECK(strncmp(g_a.desc, "udp 127.0.0.1:", 14) == 0 && strcmp(g_a.desc, "udp 127.0.0.1:0") != 0);
  CHECK(fsw_transport_send(&g_a, p1, n1) == 0); /* nobody to answer yet */
  snprintf(spec, sizeof spec, "%s", g_a.desc + 4);
  CHECK(fsw_transport_connect_udp(&g_b, spec, err, sizeof err) == 0);
  CHECK(g_b.connected == 1 && strncmp(g_b.desc, "udp 127.0.0.1:", 14) == 0);
  CHECK(fsw_transport_send(&g_b, p1, n1) == 0);
  expect_packet(&g_a, p1, n1, 1000);
  CHECK(fsw_transport_send(&g_a, p2, n2) == 0);
  expect_packet(&g_b, p2, n2, 1000);
  fsw_transport_close(&g_a);
  /* the port is closed now: the refusal is a lost packet, then a timeout */
  CHECK(fsw_transport_send(&g_b, p1, n1) == 0);
  CHECK(fsw_transport_recv(&g_b, &p, &len, 100) == FSW_TRANSPORT_TIMEOUT);
  fsw_transport_close(&g_b);
  CHECK(fsw_transport_connect_udp(&g_b, "127.0.0.1", err, sizeof err) == -1);
  CHECK(strcmp(err, "bad UDP address '127.0.0.1' (expected HOST:PORT)") == 0);
}

int main(void)
{
  test_stream();
  test_serial();
  test_udp();
  if (g_failures != 0) {
    fprintf(stderr, "fsw_transport_test: %d failure(s)\n", g_failures);
    return 1;
  }
  printf("fsw_transport_test: stream, serial and UDP transports pass\n");
  return 0;
}

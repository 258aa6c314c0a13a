/* fsw_transport: the byte-moving part of kestrel-fsw (POSIX: UDP sockets,
 * termios serial lines).  Everything the link means is in fsw_c/
 * (fsw_link, fsw_link_node); this file only moves packets. */
#ifndef KESTREL_FSW_TRANSPORT_H
#define KESTREL_FSW_TRANSPORT_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
  int fd;
  int serial;                       /* 1: byte stream with sync markers */
  unsigned char peer[128];          /* UDP: last sender (struct sockaddr_storage) */
  unsigned int peer_len;
  char desc[160];                   /* "udp 127.0.0.1:40123" / "serial /dev/pts/3 115200" */
} FswTransport;

/* "HOST:PORT" (port 0: any free port, printed in desc).  0 or -1 (message in err). */
int fsw_transport_open_udp(FswTransport *t, const char *spec, char *err, size_t err_len);
/* "DEVICE:BAUD" (raw mode, 8N1, no flow control). */
int fsw_transport_open_serial(FswTransport *t, const char *spec, char *err, size_t err_len);
/* Waits up to timeout_ms (-1: forever) for bytes.  Returns the number of
 * bytes read (a datagram, or what a serial line had), 0 on timeout, -1 on
 * error or interruption. */
long fsw_transport_recv(FswTransport *t, uint8_t *buf, size_t cap, int timeout_ms);
/* Sends one packet (serial: framed by the caller).  0 or -1. */
int fsw_transport_send(FswTransport *t, const uint8_t *buf, size_t n);
void fsw_transport_close(FswTransport *t);

#endif

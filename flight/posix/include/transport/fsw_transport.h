/* fsw_transport: moves FSW link packets over POSIX transports, for both ends
 * of the link: kestrel-fsw (flight/posix/kestrel_fsw.c) and the harness
 * (harness/src/link/remote_fsw.cpp wraps it).  Everything the link means is
 * in fsw_c/ (fsw_link, fsw_link_node); this module only opens, frames,
 * moves and closes.  C99 + POSIX, no heap: all state, buffers included, is
 * in the caller's FswTransport.
 *
 *   UDP, bound      "HOST:PORT" (PORT 0: any free port, shown in desc);
 *                   the FSW end.  Pinned to one peer: the one given by
 *                   fsw_transport_pin_peer, else the sender of the first
 *                   whole telecommand packet with a good CRC.  Datagrams
 *                   from any other address or port are counted (foreign)
 *                   and dropped, never delivered nor answered; nothing is
 *                   sent before the peer is known.
 *   UDP, connected  "HOST:PORT"; sends to it, receives from it (the harness
 *                   end; a refused datagram is a lost packet; the kernel
 *                   delivers nothing from any other address or port)
 *   serial          "DEVICE:BAUD": a terminal set raw, 8N1, no flow control
 *   unix socket     a stream socket connected to PATH (an emulator's UART)
 *   stream          a byte stream already open (a pty, a connected socket)
 *
 * Serial lines and streams carry each packet behind the attached sync
 * marker (fsw_link_frame) and are re-framed on receive (FswLinkDeframer):
 * fsw_transport_send and fsw_transport_recv move whole packets on every
 * kind.  A failed open leaves fd -1 and a message (without a "who" prefix)
 * in err. */
#ifndef KESTREL_FSW_TRANSPORT_H
#define KESTREL_FSW_TRANSPORT_H

#include <stddef.h>
#include <stdint.h>

#include "fsw/fsw_link.h"
#include "fsw/fsw_link_sec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* bytes one receive can take: a whole UDP datagram, or a read of a stream */
#define FSW_TRANSPORT_RX_SIZE 65536u

/* fsw_transport_recv's results */
#define FSW_TRANSPORT_PACKET 1   /* *pkt, *len: one whole packet */
#define FSW_TRANSPORT_TIMEOUT 0  /* no packet within the timeout */
#define FSW_TRANSPORT_ERROR (-1) /* errno says why (EINTR: a signal came) */
#define FSW_TRANSPORT_CLOSED (-2) /* the stream ended (hang-up, peer gone) */
#define FSW_TRANSPORT_REFUSED 2   /* a datagram failed authentication (dropped; t->sec counts why) */

typedef struct {
  int fd;
  int stream;                       /* 1: byte stream with sync markers */
  int is_socket;                    /* stream is a socket: no SIGPIPE on send */
  int connected;                    /* UDP connected to one peer */
  unsigned char peer[128];          /* bound UDP: the pinned peer (struct sockaddr_storage) */
  unsigned int peer_len;            /* 0: no peer pinned yet */
  unsigned long foreign;            /* bound UDP: datagrams dropped, not from the peer */
  FswLinkSec *sec;                  /* UDP: packet authentication (fsw_link_sec.h); NULL: none */
  FswLinkDeframer deframer;         /* stream: packets re-framed from the bytes */
  size_t have, used;                /* stream: bytes read into rx, bytes pushed */
  uint8_t rx[FSW_TRANSPORT_RX_SIZE];
  uint8_t tx[FSW_LINK_ASM_SIZE + FSW_LINK_MAX_PACKET + FSW_LINK_SEC_TRAILER_SIZE];
  char desc[160];                   /* "udp 127.0.0.1:40123" / "serial /dev/pts/3 115200 baud" */
} FswTransport;

/* 0 or -1 (message in err).  Bound: the FSW end; connected: the harness end. */
int fsw_transport_open_udp(FswTransport *t, const char *spec, char *err, size_t err_len);
int fsw_transport_connect_udp(FswTransport *t, const char *spec, char *err, size_t err_len);
/* Bound UDP: pins the peer to spec ("HOST:PORT", numeric port) before
 * anything is received.  0 or -1 (message in err). */
int fsw_transport_pin_peer(FswTransport *t, const char *spec, char *err, size_t err_len);
/* The pinned peer as "HOST:PORT" ("none": not pinned yet, -1). */
int fsw_transport_peer_text(const FswTransport *t, char *buf, size_t len);
/* UDP only: every packet sent gets sec's trailer, and every datagram
 * received must verify (else FSW_TRANSPORT_REFUSED; an unauthenticated
 * datagram pins no peer).  sec is the caller's, initialised with the key
 * (fsw_link_sec_init).  0, or -1 on a serial line or stream (message). */
int fsw_transport_set_key(FswTransport *t, FswLinkSec *sec, char *err, size_t err_len);
/* Reads a shared key from path: 32 ... 128 hexadecimal digits (16 ... 64
 * bytes), whitespace allowed, nothing else.  Refused (-1, message in err,
 * which never holds key material) when path is a symbolic link or not a
 * regular file, or is open to group or others (mode & 077). */
int fsw_transport_load_key(const char *path, uint8_t *key, size_t cap, size_t *len, char *err, size_t err_len);
/* "DEVICE:BAUD", BAUD one of 9600 ... 921600. */
int fsw_transport_open_serial(FswTransport *t, const char *spec, char *err, size_t err_len);
/* Connects a stream socket to the unix socket at path, described as desc.
 * 0; -1: no socket (message in err); FSW_TRANSPORT_NOT_LISTENING: nothing
 * accepts at path yet (errno says why; try again later). */
#define FSW_TRANSPORT_NOT_LISTENING (-2)
int fsw_transport_connect_unix(FswTransport *t, const char *path, const char *desc, char *err, size_t err_len);
/* Takes fd (a byte stream already open) with a description; never fails. */
void fsw_transport_open_stream(FswTransport *t, int fd, const char *desc);

/* Waits up to timeout_ms (-1: forever) for one whole packet; a stream's
 * bytes already read are re-framed first.  Returns one of
 * FSW_TRANSPORT_PACKET (*pkt points into t, valid until the next call),
 * FSW_TRANSPORT_TIMEOUT, FSW_TRANSPORT_ERROR, FSW_TRANSPORT_CLOSED,
 * FSW_TRANSPORT_REFUSED (with a key: one datagram failed authentication). */
int fsw_transport_recv(FswTransport *t, const uint8_t **pkt, size_t *len, int timeout_ms);
/* Sends one packet (framed on a stream).  Bound UDP before anything was
 * received, and a refused datagram on connected UDP: nothing, 0.  0 or -1
 * (errno). */
int fsw_transport_send(FswTransport *t, const uint8_t *pkt, size_t n);
void fsw_transport_close(FswTransport *t);

#ifdef __cplusplus
}
#endif

#endif

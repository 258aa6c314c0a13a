/* fsw_transport: POSIX UDP, serial and stream transports of the FSW link,
 * for kestrel-fsw and the harness (include/transport/fsw_transport.h). */
#define _DEFAULT_SOURCE 1 /* cfmakeraw, getaddrinfo, MSG_NOSIGNAL */
#include "transport/fsw_transport.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

/* Splits "A:B" at the last colon into a (copied) and b. */
static int split_spec(const char *spec, char *a, size_t a_len, const char **b)
{
  const char *colon = strrchr(spec, ':');
  size_t n;
  if (colon == NULL || colon == spec || colon[1] == '\0') { return -1; }
  n = (size_t)(colon - spec);
  if (n >= a_len) { return -1; }
  (void)memcpy(a, spec, n);
  a[n] = '\0';
  *b = colon + 1;
  return 0;
}

/* getaddrinfo of a UDP "HOST:PORT" (numeric port); what names it in err. */
static int resolve_udp(const char *spec, int flags, const char *what, struct addrinfo **res, char *err, size_t err_len)
{
  char host[128];
  const char *port;
  struct addrinfo hints;
  int rc;
  *res = NULL;
  if (split_spec(spec, host, sizeof host, &port) != 0) {
    (void)snprintf(err, err_len, "bad %s '%s' (expected HOST:PORT)", what, spec);
    return -1;
  }
  (void)memset(&hints, 0, sizeof hints);
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = flags | AI_NUMERICSERV;
  rc = getaddrinfo(host, port, &hints, res);
  if (rc != 0) {
    (void)snprintf(err, err_len, "cannot resolve '%s': %s", spec, gai_strerror(rc));
    *res = NULL;
    return -1;
  }
  return 0;
}

static void reset(FswTransport *t)
{
  t->fd = -1;
  t->stream = 0;
  t->is_socket = 0;
  t->connected = 0;
  t->peer_len = 0u;
  t->foreign = 0u;
  t->sec = NULL;
  t->have = 0u;
  t->used = 0u;
  t->desc[0] = '\0';
  fsw_link_deframer_init(&t->deframer);
}

/* A UDP socket bound (connect == 0) or connected to the address in spec. */
static int open_udp(FswTransport *t, const char *spec, int connect_to, char *err, size_t err_len)
{
  struct addrinfo *res = NULL;
  int rc;
  reset(t);
  if (resolve_udp(spec, connect_to ? 0 : AI_PASSIVE, "UDP address", &res, err, err_len) != 0) { return -1; }
  t->fd = socket(res->ai_family, SOCK_DGRAM, 0);
  rc = t->fd < 0 ? -1 : connect_to ? connect(t->fd, res->ai_addr, res->ai_addrlen) : bind(t->fd, res->ai_addr, res->ai_addrlen);
  if (rc != 0) {
    (void)snprintf(err, err_len, connect_to ? "cannot open UDP to %s: %s" : "cannot bind UDP %s: %s", spec, strerror(errno));
    freeaddrinfo(res);
    fsw_transport_close(t);
    return -1;
  }
  freeaddrinfo(res);
  t->connected = connect_to;
  return 0;
}

int fsw_transport_open_udp(FswTransport *t, const char *spec, char *err, size_t err_len)
{
  struct sockaddr_storage bound;
  socklen_t blen = sizeof bound;
  char hbuf[64], pbuf[16];
  if (open_udp(t, spec, 0, err, err_len) != 0) { return -1; }
  if (getsockname(t->fd, (struct sockaddr *)&bound, &blen) != 0 ||
      getnameinfo((struct sockaddr *)&bound, blen, hbuf, sizeof hbuf, pbuf, sizeof pbuf,
                  NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    (void)snprintf(err, err_len, "cannot read the bound address of %s", spec);
    fsw_transport_close(t);
    return -1;
  }
  (void)snprintf(t->desc, sizeof t->desc, "udp %s:%s", hbuf, pbuf);
  return 0;
}

int fsw_transport_pin_peer(FswTransport *t, const char *spec, char *err, size_t err_len)
{
  struct addrinfo *res = NULL;
  if (t->fd < 0 || t->stream || t->connected) {
    (void)snprintf(err, err_len, "a peer is pinned on a bound UDP socket only");
    return -1;
  }
  if (resolve_udp(spec, 0, "peer address", &res, err, err_len) != 0) { return -1; }
  if (res->ai_addrlen > sizeof t->peer) {
    freeaddrinfo(res);
    (void)snprintf(err, err_len, "peer address '%s' too long", spec);
    return -1;
  }
  (void)memcpy(t->peer, res->ai_addr, res->ai_addrlen);
  t->peer_len = (unsigned int)res->ai_addrlen;
  freeaddrinfo(res);
  return 0;
}

int fsw_transport_peer_text(const FswTransport *t, char *buf, size_t len)
{
  char h[64], p[16];
  if (t->peer_len == 0u || getnameinfo((const struct sockaddr *)t->peer, (socklen_t)t->peer_len, h, sizeof h, p,
                                       sizeof p, NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    (void)snprintf(buf, len, "none");
    return -1;
  }
  (void)snprintf(buf, len, "%s:%s", h, p);
  return 0;
}

int fsw_transport_connect_udp(FswTransport *t, const char *spec, char *err, size_t err_len)
{
  if (open_udp(t, spec, 1, err, err_len) != 0) { return -1; }
  (void)snprintf(t->desc, sizeof t->desc, "udp %s", spec);
  return 0;
}

static speed_t baud_of(long baud)
{
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return (speed_t)0;
  }
}

/* Raw, 8N1, no flow control, blocking reads of at least one byte. */
static int set_raw(int fd, speed_t sp)
{
  struct termios tio;
  if (tcgetattr(fd, &tio) != 0) { return -1; }
  cfmakeraw(&tio);
  tio.c_cflag |= (tcflag_t)(CLOCAL | CREAD);
  tio.c_cflag &= (tcflag_t)~(tcflag_t)(CSTOPB | CRTSCTS);
  tio.c_cc[VMIN] = 1;
  tio.c_cc[VTIME] = 0;
  if (cfsetispeed(&tio, sp) != 0 || cfsetospeed(&tio, sp) != 0 || tcsetattr(fd, TCSANOW, &tio) != 0) { return -2; }
  return 0;
}

int fsw_transport_open_serial(FswTransport *t, const char *spec, char *err, size_t err_len)
{
  char dev[128];
  const char *bs;
  char *end;
  long baud;
  speed_t sp;
  int rc, fd;
  reset(t);
  if (split_spec(spec, dev, sizeof dev, &bs) != 0) {
    (void)snprintf(err, err_len, "bad serial line '%s' (expected DEVICE:BAUD)", spec);
    return -1;
  }
  baud = strtol(bs, &end, 10);
  sp = baud_of(baud);
  if (*end != '\0' || sp == (speed_t)0) {
    (void)snprintf(err, err_len, "unsupported baud rate '%s' (9600 ... 921600)", bs);
    return -1;
  }
  fd = open(dev, O_RDWR | O_NOCTTY);
  if (fd < 0) {
    (void)snprintf(err, err_len, "cannot open %s: %s", dev, strerror(errno));
    return -1;
  }
  rc = set_raw(fd, sp);
  if (rc != 0) {
    snprintf(err, err_len, rc == -1 ? "%s is not a terminal: %s" : "cannot configure %s: %s", dev, strerror(errno));
    close(fd);
    return -1;
  }
  fsw_transport_open_stream(t, fd, "");
  (void)snprintf(t->desc, sizeof t->desc, "serial %s %ld baud", dev, baud);
  return 0;
}

void fsw_transport_open_stream(FswTransport *t, int fd, const char *desc)
{
  int type = 0;
  socklen_t tl = sizeof type;
  reset(t);
  t->fd = fd;
  t->stream = 1;
  t->is_socket = getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &tl) == 0;
  (void)snprintf(t->desc, sizeof t->desc, "%s", desc);
}

int fsw_transport_connect_unix(FswTransport *t, const char *path, const char *desc, char *err, size_t err_len)
{
  struct sockaddr_un a;
  int fd, type = SOCK_STREAM;
#ifdef SOCK_CLOEXEC
  type |= SOCK_CLOEXEC;
#endif
  reset(t);
  fd = socket(AF_UNIX, type, 0);
  if (fd < 0) {
    (void)snprintf(err, err_len, "socket: %s", strerror(errno));
    return -1;
  }
  (void)memset(&a, 0, sizeof a);
  a.sun_family = AF_UNIX;
  (void)snprintf(a.sun_path, sizeof a.sun_path, "%s", path);
  if (connect(fd, (const struct sockaddr *)&a, sizeof a) != 0) {
    const int e = errno;
    (void)snprintf(err, err_len, "cannot connect to %s: %s", path, strerror(e));
    close(fd);
    errno = e;
    return FSW_TRANSPORT_NOT_LISTENING;
  }
  fsw_transport_open_stream(t, fd, desc);
  return 0;
}

static long long now_ms(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Waits for fd to be readable until deadline (ms, now_ms(); -1: forever).
 * 1: readable, 0: deadline passed, -1: error (errno, EINTR included). */
static int wait_readable(int fd, long long deadline)
{
  struct pollfd p;
  int rc;
  long long left = deadline < 0 ? -1 : deadline - now_ms();
  if (deadline >= 0 && left < 0) { left = 0; }
  if (left > INT_MAX) { left = INT_MAX; }
  p.fd = fd;
  p.events = POLLIN;
  p.revents = 0;
  rc = poll(&p, 1, (int)left);
  return rc > 0 ? 1 : rc;
}

/* Same family, address and port (IPv4 or IPv6). */
static int same_address(const unsigned char *pinned, unsigned int plen, const struct sockaddr_storage *from,
                        socklen_t flen)
{
  struct sockaddr_storage a;
  if ((socklen_t)plen != flen) { return 0; }
  (void)memcpy(&a, pinned, plen);
  if (a.ss_family != from->ss_family) { return 0; }
  if (a.ss_family == AF_INET) {
    const struct sockaddr_in *x = (const struct sockaddr_in *)&a, *y = (const struct sockaddr_in *)from;
    return x->sin_port == y->sin_port && x->sin_addr.s_addr == y->sin_addr.s_addr;
  }
  if (a.ss_family == AF_INET6) {
    const struct sockaddr_in6 *x = (const struct sockaddr_in6 *)&a, *y = (const struct sockaddr_in6 *)from;
    return x->sin6_port == y->sin6_port && memcmp(&x->sin6_addr, &y->sin6_addr, sizeof x->sin6_addr) == 0;
  }
  return memcmp(&a, from, flen) == 0;
}

/* A whole packet with a good CRC addressed to the FSW (telecommand type). */
static int is_telecommand(const uint8_t *buf, size_t n)
{
  FswLinkPacket p;
  return fsw_link_parse(buf, n, &p, NULL) == FSW_OK && p.type == 1u;
}

static int recv_datagram(FswTransport *t, const uint8_t **pkt, size_t *len, long long deadline)
{
  for (;;) {
    struct sockaddr_storage from;
    socklen_t flen = sizeof from;
    size_t inner = 0u;
    ssize_t n;
    const int w = wait_readable(t->fd, deadline);
    if (w <= 0) { return w == 0 ? FSW_TRANSPORT_TIMEOUT : FSW_TRANSPORT_ERROR; }
    n = recvfrom(t->fd, t->rx, sizeof t->rx, 0, (struct sockaddr *)&from, &flen);
    if (n >= 0) {
      if (!t->connected) {
        if (t->peer_len != 0u && !same_address(t->peer, t->peer_len, &from, flen)) {
          t->foreign++; /* not the pinned peer: counted, dropped, never answered */
          continue;
        }
        if (t->sec != NULL && fsw_link_sec_verify(t->sec, t->rx, (size_t)n, &inner, NULL) != FSW_OK) {
          return FSW_TRANSPORT_REFUSED; } /* unauthenticated: dropped, pins nothing */
        if (t->sec != NULL) { n = (ssize_t)inner; }
        if (t->peer_len == 0u && is_telecommand(t->rx, (size_t)n)) { /* the first valid packet pins its sender */
          (void)memcpy(t->peer, &from, flen);
          t->peer_len = (unsigned int)flen;
        }
      } else if (t->sec != NULL) {
        if (fsw_link_sec_verify(t->sec, t->rx, (size_t)n, &inner, NULL) != FSW_OK) { return FSW_TRANSPORT_REFUSED; }
        n = (ssize_t)inner;
      }
      *pkt = t->rx;
      *len = (size_t)n;
      return FSW_TRANSPORT_PACKET;
    }
    if (!t->connected || errno != ECONNREFUSED) { return FSW_TRANSPORT_ERROR; }
    deadline = now_ms(); /* ICMP refusal seen: look once more, then report a timeout */
  }
}

static int recv_framed(FswTransport *t, const uint8_t **pkt, size_t *len, long long deadline)
{
  for (;;) {
    ssize_t n;
    int w;
    while (t->used < t->have) {
      *pkt = NULL;
      t->used += fsw_link_deframer_push(&t->deframer, t->rx + t->used, t->have - t->used, pkt, len);
      if (*pkt != NULL) { return FSW_TRANSPORT_PACKET; }
    }
    w = wait_readable(t->fd, deadline);
    if (w <= 0) { return w == 0 ? FSW_TRANSPORT_TIMEOUT : FSW_TRANSPORT_ERROR; }
    n = read(t->fd, t->rx, sizeof t->rx);
    if (n < 0) { return FSW_TRANSPORT_ERROR; }
    if (n == 0) { return FSW_TRANSPORT_CLOSED; }
    t->have = (size_t)n;
    t->used = 0u;
  }
}

int fsw_transport_recv(FswTransport *t, const uint8_t **pkt, size_t *len, int timeout_ms)
{
  const long long deadline = timeout_ms < 0 ? -1 : now_ms() + timeout_ms;
  *pkt = NULL;
  *len = 0u;
  return t->stream ? recv_framed(t, pkt, len, deadline) : recv_datagram(t, pkt, len, deadline);
}

static int write_all(FswTransport *t, const uint8_t *buf, size_t n)
{
  size_t done = 0;
  while (done < n) {
    /* a socket whose peer has gone must not raise SIGPIPE */
    const ssize_t w = t->is_socket ? send(t->fd, buf + done, n - done, MSG_NOSIGNAL) : write(t->fd, buf + done, n - done);
    if (w < 0) {
      if (errno == EINTR || errno == EAGAIN) { continue; }
      return -1;
    }
    done += (size_t)w;
  }
  return 0;
}

int fsw_transport_send(FswTransport *t, const uint8_t *pkt, size_t n)
{
  size_t len = 0;
  if (t->stream) {
    if (fsw_link_frame(pkt, n, t->tx, sizeof t->tx, &len) != FSW_OK) {
      errno = EMSGSIZE;
      return -1;
    }
    return write_all(t, t->tx, len);
  }
  if (t->sec != NULL) {
    if (fsw_link_sec_protect(t->sec, pkt, n, t->tx, sizeof t->tx, &len, NULL) != FSW_OK) {
      errno = EMSGSIZE;
      return -1;
    }
    pkt = t->tx;
    n = len;
  }
  if (t->connected) {
    (void)send(t->fd, pkt, n, 0); /* a refused datagram (no process on the port yet) is a lost packet */
    return 0;
  }
  if (t->peer_len == 0u) { return 0; } /* nobody to answer yet */
  return sendto(t->fd, pkt, n, 0, (const struct sockaddr *)t->peer, (socklen_t)t->peer_len) == (ssize_t)n ? 0 : -1;
}

int fsw_transport_set_key(FswTransport *t, FswLinkSec *sec, char *err, size_t err_len)
{
  if (t->fd < 0 || t->stream) {
    (void)snprintf(err, err_len, "packet authentication needs a UDP link (not a serial line or stream)");
    return -1;
  }
  t->sec = sec;
  return 0;
}

static int hex_digit(int c)
{
  if (c >= '0' && c <= '9') { return c - '0'; }
  if (c >= 'a' && c <= 'f') { return c - 'a' + 10; }
  if (c >= 'A' && c <= 'F') { return c - 'A' + 10; }
  return -1;
}

int fsw_transport_load_key(const char *path, uint8_t *key, size_t cap, size_t *len, char *err, size_t err_len)
{
  struct stat st;
  char text[2 * FSW_LINK_SEC_KEY_MAX + 64];
  size_t n, i, digits = 0u;
  int fd;
  *len = 0u;
  fd = open(path, O_RDONLY | O_NOFOLLOW);
  if (fd < 0) {
    (void)snprintf(err, err_len, "cannot open the key file %s: %s", path, strerror(errno));
    return -1;
  }
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    (void)snprintf(err, err_len, "the key file %s is not a regular file", path);
    close(fd);
    return -1;
  }
  if ((st.st_mode & 077) != 0) {
    (void)snprintf(err, err_len, "the key file %s is open to group or others (mode %04o): chmod 600 it", path,
             (unsigned)(st.st_mode & 07777));
    close(fd);
    return -1;
  }
  n = 0u;
  for (;;) {
    const ssize_t r = read(fd, text + n, sizeof text - n);
    if (r <= 0) { break; }
    n += (size_t)r;
    if (n == sizeof text) { break; }
  }
  close(fd);
  for (i = 0u; i < n; ++i) {
    const int h = hex_digit((unsigned char)text[i]);
    if (h < 0) {
      if (text[i] == ' ' || text[i] == '\n' || text[i] == '\r' || text[i] == '\t') { continue; }
      digits = 0u;
      break;
    }
    if (digits / 2u >= cap) {
      digits = 0u;
      break;
    }
    if (digits % 2u == 0u) {
      key[digits / 2u] = (uint8_t)(h << 4);
    } else {
      key[digits / 2u] = (uint8_t)(key[digits / 2u] | h); }
    ++digits;
  }
  (void)memset(text, 0, sizeof text);
  if (digits % 2u != 0u || digits / 2u < FSW_LINK_SEC_KEY_MIN || digits / 2u > FSW_LINK_SEC_KEY_MAX || n == sizeof text) {
    (void)snprintf(err, err_len, "the key file %s must hold %u to %u hexadecimal digits (a %u- to %u-byte key) and nothing else",
             path, 2u * FSW_LINK_SEC_KEY_MIN, 2u * FSW_LINK_SEC_KEY_MAX, FSW_LINK_SEC_KEY_MIN, FSW_LINK_SEC_KEY_MAX);
    (void)memset(key, 0, cap);
    return -1;
  }
  *len = digits / 2u;
  return 0;
}

void fsw_transport_close(FswTransport *t)
{
  if (t->fd >= 0) { close(t->fd); }
  t->fd = -1;
}

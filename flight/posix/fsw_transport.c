/* fsw_transport: POSIX UDP and serial transports of kestrel-fsw. */
#define _DEFAULT_SOURCE 1 /* cfmakeraw, getaddrinfo */
#include "fsw_transport.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

/* Splits "A:B" at the last colon into a (copied) and b. */
static int split_spec(const char *spec, char *a, size_t a_len, const char **b)
{
  const char *colon = strrchr(spec, ':');
  size_t n;
  if (colon == NULL || colon == spec || colon[1] == '\0') return -1;
  n = (size_t)(colon - spec);
  if (n >= a_len) return -1;
  memcpy(a, spec, n);
  a[n] = '\0';
  *b = colon + 1;
  return 0;
}

int fsw_transport_open_udp(FswTransport *t, const char *spec, char *err, size_t err_len)
{
  char host[128];
  const char *port;
  struct addrinfo hints, *res = NULL;
  struct sockaddr_storage bound;
  socklen_t blen = sizeof bound;
  char hbuf[64], pbuf[16];
  int rc;
  memset(t, 0, sizeof *t);
  t->fd = -1;
  if (split_spec(spec, host, sizeof host, &port) != 0) {
    snprintf(err, err_len, "bad UDP address '%s' (expected HOST:PORT)", spec);
    return -1;
  }
  memset(&hints, 0, sizeof hints);
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  rc = getaddrinfo(host, port, &hints, &res);
  if (rc != 0) {
    snprintf(err, err_len, "cannot resolve '%s': %s", spec, gai_strerror(rc));
    return -1;
  }
  t->fd = socket(res->ai_family, SOCK_DGRAM, 0);
  if (t->fd < 0 || bind(t->fd, res->ai_addr, res->ai_addrlen) != 0) {
    snprintf(err, err_len, "cannot bind UDP %s: %s", spec, strerror(errno));
    freeaddrinfo(res);
    fsw_transport_close(t);
    return -1;
  }
  freeaddrinfo(res);
  if (getsockname(t->fd, (struct sockaddr *)&bound, &blen) != 0 ||
      getnameinfo((struct sockaddr *)&bound, blen, hbuf, sizeof hbuf, pbuf, sizeof pbuf,
                  NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    snprintf(err, err_len, "cannot read the bound address of %s", spec);
    fsw_transport_close(t);
    return -1;
  }
  snprintf(t->desc, sizeof t->desc, "udp %s:%s", hbuf, pbuf);
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

int fsw_transport_open_serial(FswTransport *t, const char *spec, char *err, size_t err_len)
{
  char dev[128];
  const char *bs;
  char *end;
  long baud;
  speed_t sp;
  struct termios tio;
  memset(t, 0, sizeof *t);
  t->fd = -1;
  t->serial = 1;
  if (split_spec(spec, dev, sizeof dev, &bs) != 0) {
    snprintf(err, err_len, "bad serial line '%s' (expected DEVICE:BAUD)", spec);
    return -1;
  }
  baud = strtol(bs, &end, 10);
  sp = baud_of(baud);
  if (*end != '\0' || sp == (speed_t)0) {
    snprintf(err, err_len, "unsupported baud rate '%s' (9600 ... 921600)", bs);
    return -1;
  }
  t->fd = open(dev, O_RDWR | O_NOCTTY);
  if (t->fd < 0) {
    snprintf(err, err_len, "cannot open %s: %s", dev, strerror(errno));
    return -1;
  }
  if (tcgetattr(t->fd, &tio) != 0) {
    snprintf(err, err_len, "%s is not a terminal: %s", dev, strerror(errno));
    fsw_transport_close(t);
    return -1;
  }
  cfmakeraw(&tio);
  tio.c_cflag |= (tcflag_t)(CLOCAL | CREAD);
  tio.c_cflag &= (tcflag_t)~(tcflag_t)(CSTOPB | CRTSCTS);
  tio.c_cc[VMIN] = 1;
  tio.c_cc[VTIME] = 0;
  if (cfsetispeed(&tio, sp) != 0 || cfsetospeed(&tio, sp) != 0 || tcsetattr(t->fd, TCSANOW, &tio) != 0) {
    snprintf(err, err_len, "cannot configure %s: %s", dev, strerror(errno));
    fsw_transport_close(t);
    return -1;
  }
  snprintf(t->desc, sizeof t->desc, "serial %s %ld", dev, baud);
  return 0;
}

long fsw_transport_recv(FswTransport *t, uint8_t *buf, size_t cap, int timeout_ms)
{
  struct pollfd p;
  ssize_t n;
  int rc;
  p.fd = t->fd;
  p.events = POLLIN;
  p.revents = 0;
  rc = poll(&p, 1, timeout_ms);
  if (rc == 0) return 0;
  if (rc < 0) return -1;
  if (t->serial) {
    n = read(t->fd, buf, cap);
  } else {
    struct sockaddr_storage from;
    socklen_t flen = sizeof from;
    n = recvfrom(t->fd, buf, cap, 0, (struct sockaddr *)&from, &flen);
    if (n >= 0) {
      memcpy(t->peer, &from, flen);
      t->peer_len = (unsigned int)flen;
    }
  }
  if (n == 0 && t->serial) return -1; /* hang-up */
  return n < 0 ? -1 : (long)n;
}

int fsw_transport_send(FswTransport *t, const uint8_t *buf, size_t n)
{
  if (t->serial) {
    size_t done = 0;
    while (done < n) {
      const ssize_t w = write(t->fd, buf + done, n - done);
      if (w < 0) {
        if (errno == EINTR || errno == EAGAIN) continue;
        return -1;
      }
      done += (size_t)w;
    }
    return 0;
  }
  if (t->peer_len == 0u) return 0; /* nobody to answer yet */
  return sendto(t->fd, buf, n, 0, (const struct sockaddr *)t->peer, (socklen_t)t->peer_len) == (ssize_t)n ? 0 : -1;
}

void fsw_transport_close(FswTransport *t)
{
  if (t->fd >= 0) close(t->fd);
  t->fd = -1;
}

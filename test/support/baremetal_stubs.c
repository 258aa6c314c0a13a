/* File-system calls GoogleTest references but never needs on bare metal
 * (output goes to stdout through semihosting).  picolibc has no stat(),
 * mkdir() or getcwd() for its semihost OS layer; these report "not
 * supported" so GoogleTest's optional file features quietly stay off. */
#include <errno.h>
#include <stddef.h>
#include <sys/stat.h>

int stat(const char *path, struct stat *st);
int mkdir(const char *path, mode_t mode);
char *getcwd(char *buf, size_t size);

int stat(const char *path, struct stat *st)
{
  (void)path;
  (void)st;
  errno = ENOSYS;
  return -1;
}

int mkdir(const char *path, mode_t mode)
{
  (void)path;
  (void)mode;
  errno = ENOSYS;
  return -1;
}

char *getcwd(char *buf, size_t size)
{
  if (buf != NULL && size > 1u) {
    buf[0] = '/';
    buf[1] = '\0';
    return buf;
  }
  errno = ERANGE;
  return NULL;
}

/* A frame's file: written beside its path and renamed over it once whole,
 * so that a failed write (a full disk, a quota) leaves the file that was
 * there as it was. A path that exists and is not a regular file (a
 * device, a pipe, a link) is written in place, as renaming over it would
 * replace the node itself. */
#include "config.h"
#include "internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

FILE *msocl__frame_open(const char *path, char *tmp, size_t cap)
{
  static unsigned serial; /* names apart between threads, not secret */
  struct stat st;
  tmp[0] = '\0';
  if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
    FILE *f = fopen(path, "w");
    if (!f)
      msocl__fail(MSOCL_ERR_IO, "cannot create %s: %s", path,
                  strerror(errno));
    return f;
  }
  for (int tries = 0; tries < 100; tries++) {
    const unsigned k = __atomic_fetch_add(&serial, 1, __ATOMIC_RELAXED);
    if (snprintf(tmp, cap, "%s.%ld-%u.part", path, (long)getpid(), k) >=
        (int)cap) {
      tmp[0] = '\0';
      msocl__fail(MSOCL_ERR_IO, "cannot create %s: path too long", path);
      return NULL;
    }
    const int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd < 0 && errno == EEXIST)
      continue;
    FILE *f = fd < 0 ? NULL : fdopen(fd, "w");
    if (!f) {
      const int err = errno;
      if (fd >= 0) {
        close(fd);
        remove(tmp);
      }
      tmp[0] = '\0';
      msocl__fail(MSOCL_ERR_IO, "cannot create %s: %s", path, strerror(err));
    }
    return f;
  }
  tmp[0] = '\0';
  msocl__fail(MSOCL_ERR_IO, "cannot create %s: no free name beside it", path);
  return NULL;
}

int msocl__frame_close(FILE *f, const char *path, const char *tmp)
{
  int bad = ferror(f), err = errno;
  if (fclose(f) != 0 && !bad) {
    bad = 1;
    err = errno;
  }
  if (!bad && tmp[0] && rename(tmp, path) != 0) {
    bad = 1;
    err = errno;
  }
  if (bad && tmp[0])
    remove(tmp);
  if (bad)
    return msocl__fail(MSOCL_ERR_IO, "error writing %s: %s%s", path,
                       strerror(err),
                       tmp[0] ? " (the file there, if any, is as it was)"
                              : "");
  return MSOCL_OK;
}

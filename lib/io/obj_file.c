/* An OBJ file into memory, within a size limit: a path such as /dev/zero or
 * a pipe that never ends must fail at once, not fill the memory. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "internal.h"
#include "obj_parse.h"

/* Regular files and pipes (a shell's <(zcat mesh.obj.gz)) hold text;
 * devices, sockets and directories do not, or never end. */
static int check_kind(const char *path, const struct stat *st, size_t max) {
  if (S_ISDIR(st->st_mode))
    return msocl__fail(MSOCL_ERR_IO, "cannot read %s: %s", path,
                       strerror(EISDIR));
  if (!S_ISREG(st->st_mode) && !S_ISFIFO(st->st_mode))
    return msocl__fail(MSOCL_ERR_IO,
                       "cannot read %s: not a regular file or a pipe (a "
                       "device?)",
                       path);
  if (S_ISREG(st->st_mode) && (unsigned long long)st->st_size > max)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "cannot read %s: %lld bytes, more than the %zu an OBJ "
                       "file may have",
                       path, (long long)st->st_size, max);
  return MSOCL_OK;
}

/* Reads one byte past max, to tell a text of max bytes from a longer one;
 * a pipe has no size to ask for, so the buffer doubles up to there. */
static int read_all(FILE *f, const char *path, size_t first, size_t max,
                    char **text, size_t *len) {
  size_t limit = max + 1, cap = 0, n = 0, want, got;
  char *buf = NULL, *b;

  for (;;) {
    if (n == cap) {
      size_t c = !cap ? (first < limit ? first : limit)
                      : (cap > limit / 2 ? limit : 2 * cap);
      if (cap == limit) {
        free(buf);
        return msocl__fail(MSOCL_ERR_TOO_MANY,
                           "cannot read %s: more than the %zu bytes an OBJ "
                           "file may have",
                           path, max);
      }
      if (!(b = realloc(buf, c))) {
        free(buf);
        return msocl__fail(MSOCL_ERR_NO_MEMORY,
                           "cannot hold %s in memory (%zu bytes read)", path,
                           n);
      }
      buf = b;
      cap = c;
    }
    want = cap - n;
    n += got = fread(buf + n, 1, want, f);
    if (got < want) break; /* end of file or an error: fread says no more */
  }
  if (ferror(f)) {
    free(buf);
    return msocl__fail(MSOCL_ERR_IO, "cannot read %s: %s", path,
                       strerror(errno));
  }
  *text = buf;
  *len = n;
  return MSOCL_OK;
}

int msocl__obj_read_file(const char *path, size_t max, char **text,
                         size_t *len) {
  FILE *f = fopen(path, "rb");
  struct stat st;
  int rc;

  if (!f)
    return msocl__fail(MSOCL_ERR_IO, "cannot open %s: %s", path,
                       strerror(errno));
  if (fstat(fileno(f), &st))
    rc = msocl__fail(MSOCL_ERR_IO, "cannot read %s: %s", path,
                     strerror(errno));
  else if (!(rc = check_kind(path, &st, max)))
    /* A regular file's size is known: one allocation, if it stays put. */
    rc = read_all(f, path,
                  S_ISREG(st.st_mode) ? (size_t)st.st_size + 1 : 64 * 1024,
                  max, text, len);
  fclose(f);
  return rc;
}

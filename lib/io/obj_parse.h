/* The private Wavefront OBJ reader: vertex positions and triangles, each
 * with the line it came from so later checks can name it. */
#ifndef MSOCL_OBJ_PARSE_H
#define MSOCL_OBJ_PARSE_H

#include <stddef.h>

/* A face may have at most this many corners: more is a broken file, and
 * its fan would hang every triangle on one point. */
#define MSOCL__OBJ_MAX_CORNERS 65536

struct msocl__obj {
  int nv;     /* vertices */
  float *xyz; /* 3 nv */
  int *vline; /* nv: the line of each vertex */
  int nt;     /* triangles (faces fanned from their first corner) */
  int *tri;   /* 3 nt, 0-based, every index < nv and distinct */
  int *tline; /* nt: the line of each triangle's face */
  int lines;  /* lines read */
};

/* Reads len bytes of OBJ text (no NUL needed at the end). On failure the
 * message names the line and *o holds nothing to free. */
int msocl__obj_parse(struct msocl__obj *o, const char *text, size_t len);
void msocl__obj_free(struct msocl__obj *o);

/* The whole file at path in a malloc'd buffer of *len bytes (no NUL
 * added), if it is a regular file or a pipe of at most max bytes
 * (max < SIZE_MAX); else MSOCL_ERR_IO or MSOCL_ERR_TOO_MANY, the message
 * naming the path (obj_file.c). */
int msocl__obj_read_file(const char *path, size_t max, char **text,
                         size_t *len);

/* Tokens, locale-independent (obj_number.c). A number is
 * [+-] digits [. digits] [(e|E) [+-] digits], read into the nearest float
 * (rounded twice, through double): values that round to FLT_MAX are taken,
 * ones below half the smallest denormal become (signed) zero. NOT_FINITE
 * for the words inf and nan, TOO_LARGE for values that round to infinity.
 * An integer is [+-] digits, its size clamped just past INT_MAX. */
enum {
  MSOCL__NUM_OK = 0,
  MSOCL__NUM_BAD,
  MSOCL__NUM_NOT_FINITE,
  MSOCL__NUM_TOO_LARGE
};
#define MSOCL__INDEX_CLAMP 4294967296LL
int msocl__obj_number(const char *p, size_t len, float *out);
int msocl__obj_integer(const char *p, size_t len, long long *out);

#endif /* MSOCL_OBJ_PARSE_H */

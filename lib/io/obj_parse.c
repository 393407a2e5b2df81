/* Reads the `v` and `f` statements of Wavefront OBJ text line by line; every
 * other statement (vt, vn, o, g, s, usemtl, mtllib, l, ...) is skipped. */
#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "obj_parse.h"

/* The model's own limits: 3 floats a point and 3 ints a triangle must be
 * indexed by an int. */
#define MAX_VERTICES (INT_MAX / 3)
#define MAX_TRIANGLES (INT_MAX / 3)
/* Tokens quoted in messages are cut to this many bytes. */
#define QUOTE 40

struct reader {
  struct msocl__obj *o;
  const char *p, *eol; /* the rest of the current line */
  int line;
  size_t vcap, vlcap, tcap, tlcap;
  int *corner; /* the current face's corners, 0-based */
  size_t ccap;
};

/* Doubles an array until it holds `need` items (never more than max), so n
 * appends cost O(n) copies; sizes are checked before they can wrap. */
static int grow(void **a, size_t *cap, size_t need, size_t size, size_t max,
                const char *what, int line) {
  size_t c;
  void *p;

  if (need <= *cap) return MSOCL_OK;
  if (need > max)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "OBJ line %d: more than %zu %s", line, max, what);
  c = *cap ? *cap : 64;
  while (c < need) c = c > max / 2 ? max : 2 * c;
  if (c > SIZE_MAX / size || !(p = realloc(*a, c * size)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "OBJ line %d: cannot grow the %s to %zu", line, what, c);
  *a = p;
  *cap = c;
  return MSOCL_OK;
}

static int is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* The next blank-separated token of the line, or 0 at its end. */
static int token(struct reader *r, const char **t, size_t *len) {
  while (r->p < r->eol && is_blank(*r->p)) r->p++;
  if (r->p == r->eol) return 0;
  *t = r->p;
  while (r->p < r->eol && !is_blank(*r->p)) r->p++;
  *len = (size_t)(r->p - *t);
  return 1;
}

/* Quotes at most QUOTE bytes of a token, and says when it cut it. */
#define TOKEN_FMT "'%.*s'%s"
#define TOKEN_ARGS(t, len) \
  (int)((len) < QUOTE ? (len) : QUOTE), (t), (len) > QUOTE ? "..." : ""

static int vertex(struct reader *r) {
  struct msocl__obj *o = r->o;
  const char *t;
  size_t len;
  float xyz[3], x;
  int n = 0, rc;

  /* Past x y z: w, or the r g b some exporters add; checked, not kept. */
  while (token(r, &t, &len)) {
    if ((rc = msocl__obj_number(t, len, &x)) == MSOCL__NUM_BAD)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "OBJ line %d: " TOKEN_FMT " is not a number", r->line,
                         TOKEN_ARGS(t, len));
    if (rc == MSOCL__NUM_NOT_FINITE)
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "OBJ line %d: " TOKEN_FMT " is not a finite float",
                         r->line, TOKEN_ARGS(t, len));
    if (rc == MSOCL__NUM_TOO_LARGE)
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "OBJ line %d: " TOKEN_FMT " is too large for a float "
                         "(past %.9g it rounds to infinity)",
                         r->line, TOKEN_ARGS(t, len), (double)FLT_MAX);
    if (n < 3) xyz[n++] = x;
    else n = 4;
  }
  if (n < 3)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "OBJ line %d: vertex has %d coordinates, needs x y z",
                       r->line, n);
  if ((rc = grow((void **)&o->xyz, &r->vcap, (size_t)o->nv + 1,
                 3 * sizeof *o->xyz, MAX_VERTICES, "vertices", r->line)) ||
      (rc = grow((void **)&o->vline, &r->vlcap, (size_t)o->nv + 1,
                 sizeof *o->vline, MAX_VERTICES, "vertices", r->line)))
    return rc;
  memcpy(o->xyz + 3 * (size_t)o->nv, xyz, sizeof xyz);
  o->vline[o->nv++] = r->line;
  return MSOCL_OK;
}

/* A texture or normal index: an integer, its value unused. */
static int is_integer(const char *p, size_t len) {
  long long v;
  return msocl__obj_integer(p, len, &v) == MSOCL__NUM_OK;
}

/* Whether a corner has the form v, v/vt, v//vn or v/vt/vn; *vlen gets the
 * length of its v part. */
static int corner_form(const char *t, size_t len, size_t *vlen) {
  const char *end = t + len, *s1 = memchr(t, '/', len), *s2;

  if (!s1) {
    *vlen = len;
    return 1;
  }
  *vlen = (size_t)(s1 - t);
  s2 = memchr(s1 + 1, '/', (size_t)(end - s1 - 1));
  if (!s2) return is_integer(s1 + 1, (size_t)(end - s1 - 1));
  return (s2 == s1 + 1 || is_integer(s1 + 1, (size_t)(s2 - s1 - 1))) &&
         is_integer(s2 + 1, (size_t)(end - s2 - 1));
}

/* One corner, 0-based. A negative index counts back from the last vertex
 * read; a positive one may name a later vertex, so its upper bound is
 * checked at the end of the text. */
static int corner(struct reader *r, const char *t, size_t len, int *out) {
  size_t vlen;
  long long v;

  if (!corner_form(t, len, &vlen) ||
      msocl__obj_integer(t, vlen, &v) != MSOCL__NUM_OK)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "OBJ line %d: face corner " TOKEN_FMT
                       " is not v, v/vt, v//vn or v/vt/vn",
                       r->line, TOKEN_ARGS(t, len));
  if (v == 0)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "OBJ line %d: vertex index 0 (OBJ counts from 1)",
                       r->line);
  /* The index is quoted as written: its value is clamped when large. */
  if (v < 0 && -v > r->o->nv)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "OBJ line %d: vertex index " TOKEN_FMT " reaches "
                       "before the first vertex (%d read so far)",
                       r->line, TOKEN_ARGS(t, vlen), r->o->nv);
  if (v > MAX_VERTICES)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "OBJ line %d: vertex index " TOKEN_FMT " is too large "
                       "(a model holds at most %d points)",
                       r->line, TOKEN_ARGS(t, vlen), MAX_VERTICES);
  *out = v < 0 ? (int)(r->o->nv + v) : (int)(v - 1);
  return MSOCL_OK;
}

static int triangle(struct reader *r, int a, int b, int c) {
  struct msocl__obj *o = r->o;
  int rc;

  if (a == b || b == c || a == c)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "OBJ line %d: face uses vertex %d twice in one "
                       "triangle",
                       r->line, (a == b || a == c ? a : b) + 1);
  if ((rc = grow((void **)&o->tri, &r->tcap, (size_t)o->nt + 1,
                 3 * sizeof *o->tri, MAX_TRIANGLES, "triangles", r->line)) ||
      (rc = grow((void **)&o->tline, &r->tlcap, (size_t)o->nt + 1,
                 sizeof *o->tline, MAX_TRIANGLES, "triangles", r->line)))
    return rc;
  o->tri[3 * (size_t)o->nt] = a;
  o->tri[3 * (size_t)o->nt + 1] = b;
  o->tri[3 * (size_t)o->nt + 2] = c;
  o->tline[o->nt++] = r->line;
  return MSOCL_OK;
}

/* A polygon becomes a fan from its first corner: right for the convex
 * polygons exporters write. */
static int face(struct reader *r) {
  const char *t;
  size_t len;
  int n = 0, i, rc;

  while (token(r, &t, &len)) {
    if (n == MSOCL__OBJ_MAX_CORNERS)
      return msocl__fail(MSOCL_ERR_TOO_MANY,
                         "OBJ line %d: face has more than %d corners", r->line,
                         MSOCL__OBJ_MAX_CORNERS);
    if ((rc = grow((void **)&r->corner, &r->ccap, (size_t)n + 1,
                   sizeof *r->corner, MSOCL__OBJ_MAX_CORNERS, "face corners",
                   r->line)) ||
        (rc = corner(r, t, len, &r->corner[n])))
      return rc;
    n++;
  }
  if (n < 3)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "OBJ line %d: face has %d corners, needs at least 3",
                       r->line, n);
  for (i = 1; i + 1 < n; i++)
    if ((rc = triangle(r, r->corner[0], r->corner[i], r->corner[i + 1])))
      return rc;
  return MSOCL_OK;
}

/* One line, without its newline; '#' starts a comment anywhere on it. */
static int statement(struct reader *r, const char *p, const char *eol) {
  const char *hash = memchr(p, '#', (size_t)(eol - p)), *t;
  size_t len;

  r->p = p;
  r->eol = hash ? hash : eol;
  if (!token(r, &t, &len) || len != 1) return MSOCL_OK;
  if (*t == 'v') return vertex(r);
  if (*t == 'f') return face(r);
  return MSOCL_OK;
}

/* What can only be judged once every vertex is known. */
static int finish(const struct msocl__obj *o) {
  int t, c;

  for (t = 0; t < o->nt; t++)
    for (c = 0; c < 3; c++)
      if (o->tri[3 * (size_t)t + c] >= o->nv)
        return msocl__fail(MSOCL_ERR_BAD_INDEX,
                           "OBJ line %d: vertex index %d is out of range: the "
                           "text has %d vertices",
                           o->tline[t], o->tri[3 * (size_t)t + c] + 1, o->nv);
  if (o->nv == 0)
    return msocl__fail(MSOCL_ERR_EMPTY, "OBJ text has no vertices (%d lines)",
                       o->lines);
  if (o->nt == 0)
    return msocl__fail(MSOCL_ERR_EMPTY,
                       "OBJ text has %d vertices but no faces (%d lines)",
                       o->nv, o->lines);
  return MSOCL_OK;
}

/* A NUL byte is refused up front: no OBJ writer puts one in, and text
 * tools would stop there. */
static int no_nul(const char *text, size_t len) {
  const char *nul = len ? memchr(text, '\0', len) : NULL, *p;
  int line = 1;

  if (!nul) return MSOCL_OK;
  for (p = text; p < nul && line < INT_MAX; p++) line += *p == '\n';
  return msocl__fail(MSOCL_ERR_BAD_VALUE,
                     "OBJ line %d: NUL byte in the text (binary file?)", line);
}

int msocl__obj_parse(struct msocl__obj *o, const char *text, size_t len) {
  struct reader r;
  const char *p = text, *end = text + len, *eol;
  int rc;

  memset(o, 0, sizeof *o);
  memset(&r, 0, sizeof r);
  r.o = o;
  if ((rc = no_nul(text, len))) return rc;
  /* Editors on Windows start UTF-8 text with a byte-order mark; left in, it
   * would glue onto the first statement and hide it. */
  if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) p += 3;
  while (p < end && !rc) {
    eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    if (r.line == INT_MAX) {
      rc = msocl__fail(MSOCL_ERR_TOO_MANY, "OBJ text has more than %d lines",
                       INT_MAX);
      break;
    }
    r.line++;
    rc = statement(&r, p, eol);
    p = eol < end ? eol + 1 : end;
  }
  o->lines = r.line;
  free(r.corner);
  if (rc || (rc = finish(o))) msocl__obj_free(o);
  return rc;
}

void msocl__obj_free(struct msocl__obj *o) {
  free(o->xyz);
  free(o->vline);
  free(o->tri);
  free(o->tline);
  memset(o, 0, sizeof *o);
}

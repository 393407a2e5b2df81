/* Colliders of a model: planes, spheres and round tables, checked and
 * stored in the form the kernels use. */
#include <math.h>

#include "internal.h"

int msocl__collider_check(const msocl_model *m, const char *kind,
                          float friction)
{
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  if (!isfinite(friction))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "%s %d: friction %g is not finite",
                       kind, m->ncol, friction);
  if (friction < 0 || friction > 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s %d: friction %g is outside [0, 1]", kind, m->ncol,
                       friction);
  if (m->ncol >= MSOCL__MAX_COLLIDERS)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "%s: a model holds at most %d colliders", kind,
                       MSOCL__MAX_COLLIDERS);
  return MSOCL_OK;
}

int msocl_model_collider_count(const msocl_model *m)
{
  msocl__clear_error();
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  return m->ncol;
}

/* The checks planes, spheres and tables share: those of every kind, then
 * their vector. */
static int check_common(const msocl_model *m, const char *kind,
                        const float v[3], float friction) {
  MSOCL__TRY(msocl__collider_check(m, kind, friction));
  if (!v) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: vector is NULL", kind);
  if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "%s %d: vector (%g, %g, %g) is not finite", kind,
                       m->ncol, v[0], v[1], v[2]);
  return MSOCL_OK;
}

static void append(msocl_model *m, int kind, const float v[3], float w,
                   float friction) {
  struct msocl__collider *c = &m->col[m->ncol++];
  c->kind = kind;
  c->p[0] = v[0];
  c->p[1] = v[1];
  c->p[2] = v[2];
  c->p[3] = w;
  c->friction = friction;
}

/* Spheres and tables: a centre and a radius > 0. */
static int add_round(msocl_model *m, int kind, const char *name,
                     const float centre[3], float radius, float friction) {
  int rc;

  msocl__clear_error();
  if ((rc = check_common(m, name, centre, friction))) return rc;
  if (!isfinite(radius))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "%s %d: radius %g is not finite",
                       name, m->ncol, radius);
  if (!(radius > 0))
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "%s %d: radius %g must be > 0",
                       name, m->ncol, radius);
  append(m, kind, centre, radius, friction);
  return MSOCL_OK;
}

/* The kernels take a unit normal, so the signed distance is one dot
 * product; dividing offset by the same length keeps n.p >= offset. */
int msocl_model_add_plane(msocl_model *m, const float normal[3], float offset,
                          float friction) {
  double len;
  float unit[3], off;
  int c, rc;

  msocl__clear_error();
  if ((rc = check_common(m, "plane", normal, friction))) return rc;
  if (!isfinite(offset))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "plane %d: offset %g is not finite", m->ncol, offset);
  /* In double: a float's square of a tiny or huge normal under- or
   * overflows. */
  len = sqrt((double)normal[0] * normal[0] + (double)normal[1] * normal[1] +
             (double)normal[2] * normal[2]);
  if (len == 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "plane %d: normal is zero",
                       m->ncol);
  for (c = 0; c < 3; c++) unit[c] = (float)(normal[c] / len);
  off = (float)(offset / len);
  if (!isfinite(off))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "plane %d: offset %g / |normal| %g overflows a float",
                       m->ncol, offset, len);
  append(m, MSOCL__PLANE, unit, off, friction);
  return MSOCL_OK;
}

int msocl_model_add_sphere(msocl_model *m, const float centre[3], float radius,
                           float friction) {
  return add_round(m, MSOCL__SPHERE, "sphere", centre, radius, friction);
}

int msocl_model_add_table(msocl_model *m, const float top[3], float radius,
                          float friction) {
  return add_round(m, MSOCL__TABLE, "table", top, radius, friction);
}

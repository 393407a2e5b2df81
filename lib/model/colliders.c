/* Colliders of a model: planes, spheres and round tables, checked and
 * stored in the form the kernels use. The checks and the stored form are
 * also those of a collider added to a running simulation
 * (sim/sim_colliders_add.c). */
#include <math.h>

#include "internal.h"

int msocl__collider_friction(const char *kind, int id, float friction)
{
  if (!isfinite(friction))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "%s %d: friction %g is not finite",
                       kind, id, friction);
  if (friction < 0 || friction > 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s %d: friction %g is outside [0, 1]", kind, id,
                       friction);
  return MSOCL_OK;
}

int msocl__collider_check(const msocl_model *m, const char *kind,
                          float friction)
{
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  MSOCL__TRY(msocl__collider_friction(kind, m->ncol, friction));
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

/* The vector planes, spheres and tables take. */
static int check_vector(const char *kind, int id, const float v[3]) {
  if (!v) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: vector is NULL", kind);
  if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "%s %d: vector (%g, %g, %g) is not finite", kind, id,
                       v[0], v[1], v[2]);
  return MSOCL_OK;
}

int msocl__collider_extent(const char *kind, int id, const float *v, int n)
{
  for (int d = 0; d < n; d++)
    if (fabs(v[d]) > MSOCL__COORD_MAX)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "%s %d: |%g| exceeds %g, the bound of a coordinate",
                         kind, id, (double)v[d], MSOCL__COORD_MAX);
  return MSOCL_OK;
}

static void fill(struct msocl__collider *c, int kind, const float v[3],
                 float w, float friction) {
  *c = (struct msocl__collider){.kind = kind, .friction = friction};
  c->p[0] = v[0];
  c->p[1] = v[1];
  c->p[2] = v[2];
  c->p[3] = w;
}

int msocl__collider_round(int id, int kind, const float centre[3],
                          float radius, float friction,
                          struct msocl__collider *out) {
  const char *name = kind == MSOCL__SPHERE ? "sphere" : "table";
  MSOCL__TRY(check_vector(name, id, centre));
  if (!isfinite(radius))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "%s %d: radius %g is not finite",
                       name, id, radius);
  if (!(radius > 0))
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "%s %d: radius %g must be > 0",
                       name, id, radius);
  MSOCL__TRY(msocl__collider_extent(name, id, centre, 3));
  MSOCL__TRY(msocl__collider_extent(name, id, &radius, 1));
  fill(out, kind, centre, radius, friction);
  return MSOCL_OK;
}

/* The kernels take a unit normal, so the signed distance is one dot
 * product; dividing offset by the same length keeps n.p >= offset. */
int msocl__collider_plane(int id, const float normal[3], float offset,
                          float friction, struct msocl__collider *out) {
  double len;
  float unit[3], off;

  MSOCL__TRY(check_vector("plane", id, normal));
  if (!isfinite(offset))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "plane %d: offset %g is not finite", id, offset);
  /* In double: a float's square of a tiny or huge normal under- or
   * overflows. */
  len = sqrt((double)normal[0] * normal[0] + (double)normal[1] * normal[1] +
             (double)normal[2] * normal[2]);
  if (len == 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "plane %d: normal is zero", id);
  for (int c = 0; c < 3; c++) unit[c] = (float)(normal[c] / len);
  off = (float)(offset / len);
  if (!isfinite(off))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "plane %d: offset %g / |normal| %g overflows a float",
                       id, offset, len);
  MSOCL__TRY(msocl__collider_extent("plane", id, &off, 1));
  fill(out, MSOCL__PLANE, unit, off, friction);
  return MSOCL_OK;
}

/* The model's checks, then the collider's own into the next slot. */
static int add_round(msocl_model *m, int kind, const float centre[3],
                     float radius, float friction) {
  msocl__clear_error();
  MSOCL__TRY(msocl__collider_check(m, kind == MSOCL__SPHERE ? "sphere"
                                                           : "table",
                                   friction));
  MSOCL__TRY(msocl__collider_round(m->ncol, kind, centre, radius, friction,
                                   &m->col[m->ncol]));
  m->ncol++;
  return MSOCL_OK;
}

int msocl_model_add_plane(msocl_model *m, const float normal[3], float offset,
                          float friction) {
  msocl__clear_error();
  MSOCL__TRY(msocl__collider_check(m, "plane", friction));
  MSOCL__TRY(msocl__collider_plane(m->ncol, normal, offset, friction,
                                   &m->col[m->ncol]));
  m->ncol++;
  return MSOCL_OK;
}

int msocl_model_add_sphere(msocl_model *m, const float centre[3], float radius,
                           float friction) {
  return add_round(m, MSOCL__SPHERE, centre, radius, friction);
}

int msocl_model_add_table(msocl_model *m, const float top[3], float radius,
                          float friction) {
  return add_round(m, MSOCL__TABLE, top, radius, friction);
}

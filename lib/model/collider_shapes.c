/* Capsule and oriented-box colliders of a model (planes engine only):
 * checked, and stored in msocl__collider's p and x as the kernels read
 * them (kernels/planes.cl msocl_planes_gap); the same for one added to a
 * running simulation (sim/sim_colliders_add.c). */
#include <math.h>

#include "internal.h"

static int finite3(const float *v)
{
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

int msocl__collider_capsule(int id, const float a[3], const float b[3],
                            float radius, float friction,
                            struct msocl__collider *out)
{
  if (!a || !b)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "capsule %d: an end is NULL",
                       id);
  if (!finite3(a) || !finite3(b) || !isfinite(radius))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "capsule %d: an end or the radius %g is not finite",
                       id, radius);
  if (!(radius > 0))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "capsule %d: radius %g must be > 0", id, radius);
  MSOCL__TRY(msocl__collider_extent("capsule", id, a, 3));
  MSOCL__TRY(msocl__collider_extent("capsule", id, b, 3));
  MSOCL__TRY(msocl__collider_extent("capsule", id, &radius, 1));
  *out = (struct msocl__collider){.kind = MSOCL__CAPSULE, .friction = friction};
  for (int d = 0; d < 3; d++) {
    out->p[d] = a[d];
    out->x[d] = b[d];
  }
  out->p[3] = radius;
  return MSOCL_OK;
}

int msocl__collider_box(int id, const float centre[3], const float rotation[4],
                        const float half[3], float friction,
                        struct msocl__collider *out)
{
  if (!centre || !rotation || !half)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "box %d: a vector is NULL", id);
  if (!finite3(centre) || !finite3(rotation) || !isfinite(rotation[3]) ||
      !finite3(half))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "box %d: centre, rotation or half extents not finite",
                       id);
  for (int d = 0; d < 3; d++)
    if (!(half[d] > 0))
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "box %d: half extent %d is %g, must be > 0", id, d,
                         half[d]);
  MSOCL__TRY(msocl__collider_extent("box", id, centre, 3));
  MSOCL__TRY(msocl__collider_extent("box", id, half, 3));
  /* in double: a float's square of a tiny or huge quaternion under- or
   * overflows */
  double len = 0;
  for (int d = 0; d < 4; d++)
    len += (double)rotation[d] * rotation[d];
  len = sqrt(len);
  if (!(len > 0) || !isfinite(len))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "box %d: rotation quaternion has length %g", id, len);
  *out = (struct msocl__collider){.kind = MSOCL__BOX, .friction = friction};
  for (int d = 0; d < 3; d++) {
    out->p[d] = centre[d];
    out->x[4 + d] = half[d];
  }
  for (int d = 0; d < 4; d++)
    out->x[d] = (float)(rotation[d] / len);
  return MSOCL_OK;
}

int msocl_model_add_capsule(msocl_model *m, const float a[3], const float b[3],
                            float radius, float friction)
{
  msocl__clear_error();
  MSOCL__TRY(msocl__collider_check(m, "capsule", friction));
  MSOCL__TRY(msocl__collider_capsule(m->ncol, a, b, radius, friction,
                                     &m->col[m->ncol]));
  m->ncol++;
  return MSOCL_OK;
}

int msocl_model_add_box(msocl_model *m, const float centre[3],
                        const float rotation[4], const float half[3],
                        float friction)
{
  msocl__clear_error();
  MSOCL__TRY(msocl__collider_check(m, "box", friction));
  MSOCL__TRY(msocl__collider_box(m->ncol, centre, rotation, half, friction,
                                 &m->col[m->ncol]));
  m->ncol++;
  return MSOCL_OK;
}

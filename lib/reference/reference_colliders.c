/* Moving colliders on the host reference (msocl_sim_set_collider_pose's
 * twin): the same path over a call's steps (model/collider_pose.c, the
 * fractions (float)k / (float)n), and the response in double on the
 * velocity relative to the surface (reference_force.c); colliders added
 * and removed as msocl_sim_add_* and msocl_sim_remove_collider do (the
 * same slots; a removed one's kind 0 as added). */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <string.h>

void msocl__ref_colliders_init(msocl_reference *r)
{
  memcpy(r->col_add, r->col, sizeof r->col_add);
  for (int c = 0; c < r->ncol; c++)
    msocl__pose_home(&r->col[c], r->cpos[c], r->crot[c]);
}

/* Collider c's shape at pose (P, Q), or kind 0 while disabled. */
static void place(msocl_reference *r, int c, const float P[3],
                  const float Q[4])
{
  msocl__pose_shape(&r->col_add[c], P, Q, &r->col[c]);
  if (r->coff[c])
    r->col[c].kind = 0;
}

void msocl__ref_colliders(msocl_reference *r, int k, int n)
{
  if (!r->cpending)
    return;
  for (int c = 0; c < r->ncol; c++) {
    if (!r->cto[c])
      continue;
    if (k == n) {
      memcpy(r->cpos[c], r->cto_pos[c], sizeof r->cpos[c]);
      memcpy(r->crot[c], r->cto_rot[c], sizeof r->crot[c]);
      place(r, c, r->cpos[c], r->crot[c]);
      r->cmoving[c] = 0;
      r->cto[c] = 0;
      continue;
    }
    float P0[3], Q0[4], P1[3], Q1[4];
    const float f0 = (float)k / (float)n, f1 = (float)(k + 1) / (float)n;
    msocl__pose_lerp(r->cpos[c], r->crot[c], r->cto_pos[c], r->cto_rot[c],
                     f0, P0, Q0);
    msocl__pose_lerp(r->cpos[c], r->crot[c], r->cto_pos[c], r->cto_rot[c],
                     f1, P1, Q1);
    place(r, c, P0, Q0);
    double *m = r->cmove[c];
    r->cmoving[c] = (unsigned char)msocl__pose_motion(P0, Q0, P1, Q1, r->dt,
                                                      m, m + 3);
    for (int d = 0; d < 3; d++)
      m[6 + d] = P0[d];
  }
  if (k == n)
    r->cpending = 0;
}

void msocl__ref_surface(const msocl_reference *r, int c, const double *p,
                        double *u)
{
  u[0] = u[1] = u[2] = 0.0;
  if (!r->cmoving[c])
    return;
  const double *v = r->cmove[c], *w = v + 3, *o = v + 6;
  const double d[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
  u[0] = v[0] + w[1] * d[2] - w[2] * d[1];
  u[1] = v[1] + w[2] * d[0] - w[0] * d[2];
  u[2] = v[2] + w[0] * d[1] - w[1] * d[0];
}

static int check_id(const msocl_reference *r, int id, const char *call)
{
  if (id < 0 || id >= r->ncol)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "%s: collider id %d out of range [0, %d)", call, id,
                       r->ncol);
  if (!r->col_add[id].kind)
    return msocl__fail(MSOCL_ERR_BAD_INDEX, "%s: collider %d was removed",
                       call, id);
  return MSOCL_OK;
}

/* The slot the next collider takes: the first removed one's, else the
 * next id; then its friction checked. */
static int begin(msocl_reference *r, const char *kind, float friction,
                 int *slot)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  *slot = r->ncol;
  for (int c = r->ncol - 1; c >= 0; c--)
    if (!r->col_add[c].kind)
      *slot = c;
  if (*slot >= MSOCL__MAX_COLLIDERS)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "the reference holds %d analytic colliders, the most "
                       "it can", MSOCL__MAX_COLLIDERS);
  return msocl__collider_friction(kind, *slot, friction);
}

/* Collider c into the slot, at rest at its pose, enabled. */
static int insert(msocl_reference *r, int slot,
                  const struct msocl__collider *c, int *id)
{
  r->col_add[slot] = *c;
  msocl__pose_home(c, r->cpos[slot], r->crot[slot]);
  r->cto[slot] = r->coff[slot] = r->cmoving[slot] = 0;
  place(r, slot, r->cpos[slot], r->crot[slot]);
  if (slot >= r->ncol)
    r->ncol = slot + 1;
  if (id)
    *id = slot;
  return MSOCL_OK;
}

int msocl_reference_add_plane(msocl_reference *r, const float normal[3],
                              float offset, float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(r, "plane", friction, &slot));
  MSOCL__TRY(msocl__collider_plane(slot, normal, offset, friction, &c));
  return insert(r, slot, &c, id);
}

int msocl_reference_add_sphere(msocl_reference *r, const float centre[3],
                               float radius, float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(r, "sphere", friction, &slot));
  MSOCL__TRY(msocl__collider_round(slot, MSOCL__SPHERE, centre, radius,
                                   friction, &c));
  return insert(r, slot, &c, id);
}

int msocl_reference_add_table(msocl_reference *r, const float top[3],
                              float radius, float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(r, "table", friction, &slot));
  MSOCL__TRY(msocl__collider_round(slot, MSOCL__TABLE, top, radius, friction,
                                   &c));
  return insert(r, slot, &c, id);
}

int msocl_reference_add_capsule(msocl_reference *r, const float a[3],
                                const float b[3], float radius,
                                float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(r, "capsule", friction, &slot));
  MSOCL__TRY(msocl__collider_capsule(slot, a, b, radius, friction, &c));
  return insert(r, slot, &c, id);
}

int msocl_reference_add_box(msocl_reference *r, const float centre[3],
                            const float rotation[4], const float half[3],
                            float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(r, "box", friction, &slot));
  MSOCL__TRY(msocl__collider_box(slot, centre, rotation, half, friction, &c));
  return insert(r, slot, &c, id);
}

int msocl_reference_remove_collider(msocl_reference *r, int id)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  MSOCL__TRY(check_id(r, id, "msocl_reference_remove_collider"));
  memset(&r->col_add[id], 0, sizeof r->col_add[id]);
  memset(&r->col[id], 0, sizeof r->col[id]);
  r->cto[id] = r->coff[id] = r->cmoving[id] = 0;
  return MSOCL_OK;
}

int msocl_reference_set_collider_pose(msocl_reference *r, int id,
                                      const float position[3],
                                      const float rotation[4])
{
  static const char call[] = "msocl_reference_set_collider_pose";
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  MSOCL__TRY(check_id(r, id, call));
  MSOCL__TRY(msocl__pose_check(call, id, r->col_add[id].kind, position,
                               rotation));
  memcpy(r->cto_pos[id], position, sizeof r->cto_pos[id]);
  memcpy(r->cto_rot[id], rotation, sizeof r->cto_rot[id]);
  r->cto[id] = 1;
  r->cpending = 1;
  return MSOCL_OK;
}

int msocl_reference_enable_collider(msocl_reference *r, int id, int on)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  MSOCL__TRY(check_id(r, id, "msocl_reference_enable_collider"));
  r->coff[id] = !on;
  place(r, id, r->cpos[id], r->crot[id]);
  return MSOCL_OK;
}

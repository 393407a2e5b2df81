/* Moving colliders on the host reference (msocl_sim_set_collider_pose's
 * twin): the same path over a call's steps (model/collider_pose.c, the
 * fractions (float)k / (float)n), and the response in double on the
 * velocity relative to the surface (reference_force.c). */
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

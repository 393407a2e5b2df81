/* A collider's pose (position, quaternion xyzw) and what it gives: the
 * pose a collider is added at, its shape at another pose (moved rigidly,
 * turning about the pose position), the path between two poses and the
 * motion over a step. Shared by the simulation's moving colliders
 * (sim/sim_colliders.c) and the host reference's (reference/
 * reference_colliders.c), so both follow the one path msocl.h states. */
#include <math.h>
#include <string.h>

#include "internal.h"

void msocl__pose_home(const struct msocl__collider *a, float P[3],
                      float Q[4])
{
  Q[0] = Q[1] = Q[2] = 0.0f;
  Q[3] = 1.0f;
  for (int d = 0; d < 3; d++)
    P[d] = a->kind == MSOCL__PLANE ? a->p[3] * a->p[d]
           : a->kind == MSOCL__CAPSULE
               ? (float)(0.5 * ((double)a->p[d] + a->x[d]))
               : a->p[d];
  if (a->kind == MSOCL__BOX)
    memcpy(Q, a->x, 4 * sizeof *Q);
}

/* q / |q| in double. */
static void unit(const float q[4], double u[4])
{
  double len = 0;
  for (int d = 0; d < 4; d++)
    len += (double)q[d] * q[d];
  len = sqrt(len);
  for (int d = 0; d < 4; d++)
    u[d] = q[d] / len;
}

/* The rotation matrix of unit q = (x, y, z, w). */
static void matrix(const double q[4], double r[3][3])
{
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  r[0][0] = 1 - 2 * (y * y + z * z);
  r[0][1] = 2 * (x * y - z * w);
  r[0][2] = 2 * (x * z + y * w);
  r[1][0] = 2 * (x * y + z * w);
  r[1][1] = 1 - 2 * (x * x + z * z);
  r[1][2] = 2 * (y * z - x * w);
  r[2][0] = 2 * (x * z - y * w);
  r[2][1] = 2 * (y * z + x * w);
  r[2][2] = 1 - 2 * (x * x + y * y);
}

/* a conj(b) of quaternions (x, y, z, w), both made unit. */
static void qdiv(const float fa[4], const float fb[4], double o[4])
{
  double a[4], b[4];
  unit(fa, a);
  unit(fb, b);
  b[0] = -b[0];
  b[1] = -b[1];
  b[2] = -b[2];
  o[0] = a[3] * b[0] + b[3] * a[0] + a[1] * b[2] - a[2] * b[1];
  o[1] = a[3] * b[1] + b[3] * a[1] + a[2] * b[0] - a[0] * b[2];
  o[2] = a[3] * b[2] + b[3] * a[2] + a[0] * b[1] - a[1] * b[0];
  o[3] = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
}

void msocl__pose_shape(const struct msocl__collider *a, const float P[3],
                       const float Q[4], struct msocl__collider *out)
{
  *out = *a;
  float H[3], HQ[4];
  msocl__pose_home(a, H, HQ);
  /* the pose it was added at gives its values exactly */
  if (!memcmp(P, H, sizeof H) && !memcmp(Q, HQ, sizeof HQ))
    return;
  /* the turn from the added pose: R(Q) R(Q_add)^T = R(Q conj(Q_add)) */
  double rel[4], r[3][3];
  qdiv(Q, HQ, rel);
  matrix(rel, r);
  switch (a->kind) {
  case MSOCL__PLANE: {
    double n[3], off = 0;
    for (int i = 0; i < 3; i++) {
      n[i] = r[i][0] * a->p[0] + r[i][1] * a->p[1] + r[i][2] * a->p[2];
      off += n[i] * P[i];
    }
    for (int i = 0; i < 3; i++)
      out->p[i] = (float)n[i];
    out->p[3] = (float)off;
    break;
  }
  case MSOCL__CAPSULE: {
    const float *ends[2] = {a->p, a->x};
    float *to[2] = {out->p, out->x};
    for (int k = 0; k < 2; k++)
      for (int i = 0; i < 3; i++) {
        double d = P[i];
        for (int j = 0; j < 3; j++)
          d += r[i][j] * ((double)ends[k][j] - H[j]);
        to[k][i] = (float)d;
      }
    break;
  }
  default: /* sphere, table (a table turns about y: its shape stays), box */
    for (int i = 0; i < 3; i++)
      out->p[i] = P[i];
    if (a->kind == MSOCL__BOX) {
      double q[4];
      unit(Q, q);
      for (int i = 0; i < 4; i++)
        out->x[i] = (float)q[i];
    }
  }
}

void msocl__pose_lerp(const float a[3], const float qa[4], const float b[3],
                      const float qb[4], float f, float P[3], float Q[4])
{
  const double g = f;
  for (int d = 0; d < 3; d++)
    P[d] = (float)((1 - g) * a[d] + g * b[d]);
  if (f == 0.0f || f == 1.0f) {
    memcpy(Q, f == 0.0f ? qa : qb, 4 * sizeof *Q);
    return;
  }
  /* the ends as unit quaternions: a quaternion's scale (10 q is q) must
   * not weigh its end in the blend */
  double ua[4], ub[4], dot = 0, q[4], len = 0;
  unit(qa, ua);
  unit(qb, ub);
  for (int d = 0; d < 4; d++)
    dot += ua[d] * ub[d];
  const double sb = dot < 0 ? -g : g;
  for (int d = 0; d < 4; d++) {
    q[d] = (1 - g) * ua[d] + sb * ub[d];
    len += q[d] * q[d];
  }
  len = sqrt(len);
  for (int d = 0; d < 4; d++)
    Q[d] = (float)(q[d] / len);
}

int msocl__pose_motion(const float P0[3], const float Q0[4],
                       const float P1[3], const float Q1[4], double dt,
                       double v[3], double w[3])
{
  if (!memcmp(P0, P1, 3 * sizeof *P0) && !memcmp(Q0, Q1, 4 * sizeof *Q0)) {
    v[0] = v[1] = v[2] = w[0] = w[1] = w[2] = 0.0;
    return 0;
  }
  double dq[4];
  qdiv(Q1, Q0, dq);
  if (dq[3] < 0) /* the shorter way round */
    for (int d = 0; d < 4; d++)
      dq[d] = -dq[d];
  const double sn = sqrt(dq[0] * dq[0] + dq[1] * dq[1] + dq[2] * dq[2]);
  const double turn = sn > 0 ? 2 * atan2(sn, dq[3]) / (sn * dt) : 0;
  for (int d = 0; d < 3; d++) {
    v[d] = ((double)P1[d] - P0[d]) / dt;
    w[d] = dq[d] * turn;
  }
  return 1;
}

int msocl__pose_check(const char *call, int id, int kind,
                      const float position[3], const float rotation[4])
{
  if (!position || !rotation)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: %s is NULL", call,
                       position ? "rotation" : "position");
  for (int d = 0; d < 7; d++) {
    const float x = d < 3 ? position[d] : rotation[d - 3];
    if (!isfinite(x))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "%s: collider %d's %s %d is %g", call, id,
                         d < 3 ? "position coordinate" : "rotation component",
                         d < 3 ? d : d - 3, (double)x);
  }
  for (int d = 0; d < 3; d++)
    if (fabs(position[d]) > MSOCL__COORD_MAX)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "%s: collider %d's position coordinate %d, %g, "
                         "exceeds %g",
                         call, id, d, (double)position[d], MSOCL__COORD_MAX);
  double len = 0;
  for (int d = 0; d < 4; d++)
    len += (double)rotation[d] * rotation[d];
  len = sqrt(len);
  if (!(len > 0))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: collider %d's rotation quaternion is zero", call,
                       id);
  if (kind == MSOCL__TABLE &&
      (fabs(rotation[0]) > 1e-6 * len || fabs(rotation[2]) > 1e-6 * len))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: collider %d is a table, which turns only about "
                       "y (rotation x and z must be 0, not %g and %g)",
                       call, id, (double)rotation[0], (double)rotation[2]);
  return MSOCL_OK;
}

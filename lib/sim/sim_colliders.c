/* Colliders that move (msocl.h's "moving colliders"): each analytic
 * collider has a pose (position, unit quaternion xyzw) and moves rigidly
 * from the pose it was added at to the one set for the next stepping
 * call, along a path over its steps (motion.c): the position linearly,
 * the rotation by nlerp. Before each of those steps the planes kernels'
 * collider table gets the shape at the step's start and the surface's
 * velocity over the step (kernels/planes.cl MSOCL_PLANES_SURFACE), so the
 * response acts on the velocity relative to the collider. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Host tables in flight: each write of the table reads its own slot
 * (non-blocking), and a slot is reused only after the queue finished. */
#define RING 64

struct msocl__moving {
  int n;
  struct msocl__collider add[MSOCL__MAX_COLLIDERS]; /* as added */
  float add_pos[MSOCL__MAX_COLLIDERS][3], add_rot[MSOCL__MAX_COLLIDERS][4];
  float pos[MSOCL__MAX_COLLIDERS][3], rot[MSOCL__MAX_COLLIDERS][4];
  float to_pos[MSOCL__MAX_COLLIDERS][3], to_rot[MSOCL__MAX_COLLIDERS][4];
  unsigned char target[MSOCL__MAX_COLLIDERS], off[MSOCL__MAX_COLLIDERS];
  int pending;
  long long writes; /* tables written so far: the ring's position */
  float ring[RING][4 * MSOCL__COL_VALUES * MSOCL__MAX_COLLIDERS];
};

void msocl__colliders_free(msocl_sim *s)
{
  free(s->mov);
  s->mov = NULL;
}

static int refuse_engine(const msocl_sim *s, const char *call)
{
  if (s->nparts > 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: the simulation is split over %d devices; moving "
                       "or enabling colliders needs one device (each "
                       "device's table would have to follow the pose)",
                       call, s->nparts);
  if (!s->part[0]->planes)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s needs the planes engine (tuning.planes, GRID, "
                       "BUFFER, EDGES or IMAGE2D layout); this simulation "
                       "runs the float4 engine, whose colliders are static",
                       call);
  return MSOCL_OK;
}

/* The colliders as the engine holds them, read back at the first call:
 * kind, friction and p from the float4 table, x from pl_colx. */
static int moving(msocl_sim *s, const char *call, struct msocl__moving **out)
{
  MSOCL__TRY(refuse_engine(s, call));
  if (!s->mov) {
    msocl__engine *e = s->part[0];
    float packed[8 * MSOCL__MAX_COLLIDERS];
    if (e->ncol > 0)
      MSOCL__CL(clEnqueueReadBuffer(e->dev->queue, e->col, CL_TRUE, 0,
                                    8 * (size_t)e->ncol * sizeof(float),
                                    packed, 0, NULL, NULL));
    struct msocl__moving *m = calloc(1, sizeof *m);
    if (!m)
      return msocl__fail(MSOCL_ERR_NO_MEMORY, "moving colliders");
    m->n = e->ncol;
    for (int c = 0; c < m->n; c++) {
      struct msocl__collider *a = &m->add[c];
      a->kind = (int)packed[8 * c];
      a->friction = packed[8 * c + 1];
      memcpy(a->p, packed + 8 * c + 4, sizeof a->p);
      memcpy(a->x, e->pl_colx + 8 * c, sizeof a->x);
      float *P = m->add_pos[c], *Q = m->add_rot[c];
      Q[0] = Q[1] = Q[2] = 0.0f;
      Q[3] = 1.0f;
      for (int d = 0; d < 3; d++)
        P[d] = a->kind == MSOCL__PLANE ? a->p[3] * a->p[d]
               : a->kind == MSOCL__CAPSULE
                   ? (float)(0.5 * ((double)a->p[d] + a->x[d]))
                   : a->p[d];
      if (a->kind == MSOCL__BOX)
        memcpy(Q, a->x, 4 * sizeof *Q);
      memcpy(m->pos[c], P, 3 * sizeof *P);
      memcpy(m->rot[c], Q, 4 * sizeof *Q);
    }
    s->mov = m;
  }
  *out = s->mov;
  return MSOCL_OK;
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

/* a b of quaternions (x, y, z, w). */
static void qmul(const double a[4], const double b[4], double o[4])
{
  o[0] = a[3] * b[0] + b[3] * a[0] + a[1] * b[2] - a[2] * b[1];
  o[1] = a[3] * b[1] + b[3] * a[1] + a[2] * b[0] - a[0] * b[2];
  o[2] = a[3] * b[2] + b[3] * a[2] + a[0] * b[1] - a[1] * b[0];
  o[3] = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
}

/* Collider c's shape at pose (P, Q): its kernel values p and x. The pose
 * it was added at gives its values exactly (a static scene's table). */
static void posed(const struct msocl__moving *m, int c, const float P[3],
                  const float Q[4], float p[4], float x[8])
{
  const struct msocl__collider *a = &m->add[c];
  memcpy(p, a->p, 4 * sizeof *p);
  memcpy(x, a->x, 8 * sizeof *x);
  if (!memcmp(P, m->add_pos[c], 3 * sizeof *P) &&
      !memcmp(Q, m->add_rot[c], 4 * sizeof *Q))
    return;
  /* the turn from the added pose: R(Q) R(Q_add)^T = R(Q conj(Q_add)) */
  double q[4], q0[4], rel[4], r[3][3];
  unit(Q, q);
  unit(m->add_rot[c], q0);
  q0[0] = -q0[0];
  q0[1] = -q0[1];
  q0[2] = -q0[2];
  qmul(q, q0, rel);
  matrix(rel, r);
  switch (a->kind) {
  case MSOCL__PLANE: {
    double n[3], off = 0;
    for (int i = 0; i < 3; i++) {
      n[i] = r[i][0] * a->p[0] + r[i][1] * a->p[1] + r[i][2] * a->p[2];
      off += n[i] * P[i];
    }
    for (int i = 0; i < 3; i++)
      p[i] = (float)n[i];
    p[3] = (float)off;
    break;
  }
  case MSOCL__CAPSULE: {
    const float *ends[2] = {a->p, a->x};
    float *to[2] = {p, x};
    for (int k = 0; k < 2; k++)
      for (int i = 0; i < 3; i++) {
        double d = P[i];
        for (int j = 0; j < 3; j++)
          d += r[i][j] * ((double)ends[k][j] - m->add_pos[c][j]);
        to[k][i] = (float)d;
      }
    break;
  }
  default: /* sphere, table (a table turns about y: its shape stays), box */
    for (int i = 0; i < 3; i++)
      p[i] = P[i];
    if (a->kind == MSOCL__BOX)
      for (int i = 0; i < 4; i++)
        x[i] = (float)q[i];
  }
}

/* (1 - f) a + f b, exact at f = 0 and 1; the rotation by nlerp, b taken
 * in a's hemisphere, a and b themselves at the ends. */
static void lerp_pose(const float a[3], const float qa[4], const float b[3],
                      const float qb[4], float f, float P[3], float Q[4])
{
  const double g = f;
  for (int d = 0; d < 3; d++)
    P[d] = (float)((1 - g) * a[d] + g * b[d]);
  if (f == 0.0f || f == 1.0f) {
    memcpy(Q, f == 0.0f ? qa : qb, 4 * sizeof *Q);
    return;
  }
  double dot = 0, q[4], len = 0;
  for (int d = 0; d < 4; d++)
    dot += (double)qa[d] * qb[d];
  const double sb = dot < 0 ? -g : g;
  for (int d = 0; d < 4; d++) {
    q[d] = (1 - g) * qa[d] + sb * qb[d];
    len += q[d] * q[d];
  }
  len = sqrt(len);
  for (int d = 0; d < 4; d++)
    Q[d] = (float)(q[d] / len);
}

/* Collider c's row of the table (lane 0 of each of its float4s): its
 * shape at pose 0 and, when pose 1 differs, the surface's motion from
 * pose 0 to pose 1 over dt. */
static void row(const struct msocl__moving *m, int c, const float P0[3],
                const float Q0[4], const float P1[3], const float Q1[4],
                float dt, float *out)
{
  float v[MSOCL__COL_VALUES] = {0};
  if (!m->off[c]) {
    v[0] = (float)m->add[c].kind;
    v[1] = m->add[c].friction;
    posed(m, c, P0, Q0, v + 4, v + 8);
    if (P1 && (memcmp(P0, P1, 3 * sizeof *P0) ||
               memcmp(Q0, Q1, 4 * sizeof *Q0))) {
      double a[4], b[4], dq[4];
      unit(Q0, a);
      unit(Q1, b);
      a[0] = -a[0];
      a[1] = -a[1];
      a[2] = -a[2];
      qmul(b, a, dq);
      if (dq[3] < 0)
        for (int d = 0; d < 4; d++)
          dq[d] = -dq[d];
      const double sn = sqrt(dq[0] * dq[0] + dq[1] * dq[1] + dq[2] * dq[2]);
      const double turn = sn > 0 ? 2 * atan2(sn, dq[3]) / (sn * dt) : 0;
      v[2] = 1.0f;
      for (int d = 0; d < 3; d++) {
        v[16 + d] = (float)(((double)P1[d] - P0[d]) / dt);
        v[19 + d] = (float)(dq[d] * turn);
        v[22 + d] = P0[d];
      }
    }
  }
  for (int k = 0; k < MSOCL__COL_VALUES; k++)
    out[4 * k] = v[k];
}

/* The table with every collider at its path's point f0 (moving toward f1;
 * f1 < 0: at rest), queued into the planes' collider buffer. */
static int write_table(msocl_sim *s, float f0, float f1)
{
  struct msocl__moving *m = s->mov;
  msocl__engine *e = s->part[0];
  const int slot = (int)(m->writes % RING);
  if (m->writes > 0 && slot == 0)
    MSOCL__CL(clFinish(e->dev->queue)); /* the ring's slots are read */
  float *t = m->ring[slot];
  for (int c = 0; c < m->n; c++) {
    float *row_at = t + 4 * MSOCL__COL_VALUES * c;
    if (m->target[c] && f1 >= 0.0f) {
      float P0[3], Q0[4], P1[3], Q1[4];
      lerp_pose(m->pos[c], m->rot[c], m->to_pos[c], m->to_rot[c], f0, P0,
                Q0);
      lerp_pose(m->pos[c], m->rot[c], m->to_pos[c], m->to_rot[c], f1, P1,
                Q1);
      row(m, c, P0, Q0, P1, Q1, e->o.dt, row_at);
    } else
      row(m, c, m->pos[c], m->rot[c], NULL, NULL, e->o.dt, row_at);
  }
  m->writes++;
  const size_t bytes = 4 * MSOCL__COL_VALUES * (size_t)m->n * sizeof(float);
  if (bytes > 0)
    MSOCL__CL(clEnqueueWriteBuffer(e->dev->queue, e->pl_col, CL_FALSE, 0,
                                   bytes, t, 0, NULL, NULL));
  return MSOCL_OK;
}

int msocl__colliders_pending(const msocl_sim *s)
{
  return s->mov && s->mov->pending;
}

int msocl__colliders_place(msocl_sim *s, float f0, float f1)
{
  return write_table(s, f0, f1);
}

int msocl__colliders_done(msocl_sim *s)
{
  struct msocl__moving *m = s->mov;
  for (int c = 0; c < m->n; c++)
    if (m->target[c]) {
      memcpy(m->pos[c], m->to_pos[c], sizeof m->pos[c]);
      memcpy(m->rot[c], m->to_rot[c], sizeof m->rot[c]);
      m->target[c] = 0;
    }
  m->pending = 0;
  return write_table(s, 0.0f, -1.0f);
}

static int check_id(const msocl_sim *s, const struct msocl__moving *m,
                    int id, const char *call)
{
  (void)s;
  if (id < 0 || id >= m->n)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "%s: collider id %d out of range [0, %d) (ids count "
                       "the model's analytic colliders in the order added)",
                       call, id, m->n);
  return MSOCL_OK;
}

int msocl_sim_set_collider_pose(msocl_sim *s, int id, const float position[3],
                                const float rotation[4])
{
  static const char call[] = "msocl_sim_set_collider_pose";
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (!position || !rotation)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: %s is NULL", call,
                       position ? "rotation" : "position");
  struct msocl__moving *m;
  MSOCL__TRY(moving(s, call, &m));
  MSOCL__TRY(check_id(s, m, id, call));
  for (int d = 0; d < 7; d++) {
    const float x = d < 3 ? position[d] : rotation[d - 3];
    if (!isfinite(x))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "%s: collider %d's %s %d is %g", call, id,
                         d < 3 ? "position coordinate" : "rotation component",
                         d < 3 ? d : d - 3, (double)x);
  }
  double len = 0;
  for (int d = 0; d < 4; d++)
    len += (double)rotation[d] * rotation[d];
  len = sqrt(len);
  if (!(len > 0))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: collider %d's rotation quaternion is zero", call,
                       id);
  if (m->add[id].kind == MSOCL__TABLE &&
      (fabs(rotation[0]) > 1e-6 * len || fabs(rotation[2]) > 1e-6 * len))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: collider %d is a table, which turns only about "
                       "y (rotation x and z must be 0, not %g and %g)",
                       call, id, (double)rotation[0], (double)rotation[2]);
  memcpy(m->to_pos[id], position, sizeof m->to_pos[id]);
  memcpy(m->to_rot[id], rotation, sizeof m->to_rot[id]);
  m->target[id] = 1;
  m->pending = 1;
  return MSOCL_OK;
}

int msocl_sim_get_collider_pose(msocl_sim *s, int id, float position[3],
                                float rotation[4])
{
  static const char call[] = "msocl_sim_get_collider_pose";
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (!position || !rotation)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: %s is NULL", call,
                       position ? "rotation" : "position");
  struct msocl__moving *m;
  MSOCL__TRY(moving(s, call, &m));
  MSOCL__TRY(check_id(s, m, id, call));
  memcpy(position, m->pos[id], sizeof m->pos[id]);
  memcpy(rotation, m->rot[id], sizeof m->rot[id]);
  return MSOCL_OK;
}

int msocl_sim_enable_collider(msocl_sim *s, int id, int on)
{
  static const char call[] = "msocl_sim_enable_collider";
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  struct msocl__moving *m;
  MSOCL__TRY(moving(s, call, &m));
  MSOCL__TRY(check_id(s, m, id, call));
  m->off[id] = !on;
  return write_table(s, 0.0f, -1.0f);
}

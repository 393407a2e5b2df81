/* Colliders that move (msocl.h's "moving colliders"): each analytic
 * collider has a pose (position, unit quaternion xyzw) and moves rigidly
 * from the pose it was added at to the one set for the next stepping
 * call, along a path over its steps (motion.c): the position linearly,
 * the rotation by nlerp. Before each of those steps the planes kernels'
 * collider table gets the shape at the step's start and the surface's
 * velocity over the step (kernels/planes.cl MSOCL_PLANES_SURFACE), so the
 * response acts on the velocity relative to the collider. The pose math
 * is model/collider_pose.c's. Colliders added on the running simulation
 * (sim_colliders_add.c) take a removed collider's slot or the next one,
 * the engine's program rebuilt where it has no room for them
 * (msocl__engine_colliders). */
#include "config.h"
#include "sim.h"

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
                       "%s: the simulation is split over %d devices; "
                       "moving, enabling, adding or removing colliders "
                       "needs one device (each device's table would have "
                       "to follow the pose)",
                       call, s->nparts);
  return MSOCL_OK;
}

/* The colliders as the (first) engine holds them, read back at the first
 * call: kind, friction and p from the float4 table, x from pl_colx. A
 * split's engines hold the same, which only a query reads. */
static int loaded(msocl_sim *s, struct msocl__moving **out)
{
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
      msocl__pose_home(a, P, Q);
      memcpy(m->pos[c], P, 3 * sizeof *P);
      memcpy(m->rot[c], Q, 4 * sizeof *Q);
    }
    s->mov = m;
  }
  *out = s->mov;
  return MSOCL_OK;
}

static int moving(msocl_sim *s, const char *call, struct msocl__moving **out)
{
  MSOCL__TRY(refuse_engine(s, call));
  return loaded(s, out);
}

/* Collider c's row of the table (lane 0 of each of its float4s): its
 * shape at pose 0 and, when pose 1 differs, the surface's motion from
 * pose 0 to pose 1 over dt. */
static void row(const struct msocl__moving *m, int c, const float P0[3],
                const float Q0[4], const float P1[3], const float Q1[4],
                float dt, float *out)
{
  float v[MSOCL__COL_VALUES] = {0};
  if (!m->off[c] && m->add[c].kind) { /* kind 0: a removed collider */
    struct msocl__collider k;
    msocl__pose_shape(&m->add[c], P0, Q0, &k);
    v[0] = (float)k.kind;
    v[1] = k.friction;
    memcpy(v + 4, k.p, sizeof k.p);
    memcpy(v + 8, k.x, sizeof k.x);
    double lin[3], ang[3];
    if (P1 && msocl__pose_motion(P0, Q0, P1, Q1, dt, lin, ang)) {
      v[2] = 1.0f;
      for (int d = 0; d < 3; d++) {
        v[16 + d] = (float)lin[d];
        v[19 + d] = (float)ang[d];
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
  e->pl_col_moving = 0;
  for (int c = 0; c < m->n; c++) {
    float *row_at = t + 4 * MSOCL__COL_VALUES * c;
    if (m->target[c] && f1 >= 0.0f) {
      float P0[3], Q0[4], P1[3], Q1[4];
      msocl__pose_lerp(m->pos[c], m->rot[c], m->to_pos[c], m->to_rot[c], f0, P0,
                Q0);
      msocl__pose_lerp(m->pos[c], m->rot[c], m->to_pos[c], m->to_rot[c], f1, P1,
                Q1);
      row(m, c, P0, Q0, P1, Q1, e->o.dt, row_at);
    } else
      row(m, c, m->pos[c], m->rot[c], NULL, NULL, e->o.dt, row_at);
    /* the kernels' "moving" value: the sweep takes its twin without */
    e->pl_col_moving |= row_at[4 * 2] != 0.0f;
  }
  m->writes++;
  const size_t bytes = 4 * MSOCL__COL_VALUES * (size_t)m->n * sizeof(float);
  /* at rest (a call's end, an enable): blocking, so that no write reads
   * the ring once the call returned (the simulation may be destroyed) */
  if (bytes > 0)
    MSOCL__CL(clEnqueueWriteBuffer(e->dev->queue, e->pl_col,
                                   f1 < 0.0f ? CL_TRUE : CL_FALSE, 0, bytes,
                                   t, 0, NULL, NULL));
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

static int check_id(const struct msocl__moving *m, int id, const char *call)
{
  if (id < 0 || id >= m->n)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "%s: collider id %d out of range [0, %d) (ids count "
                       "the model's analytic colliders in the order added, "
                       "then those added to the simulation)",
                       call, id, m->n);
  if (!m->add[id].kind)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "%s: collider %d was removed "
                       "(msocl_sim_remove_collider)", call, id);
  return MSOCL_OK;
}

int msocl__colliders_slot(msocl_sim *s, const char *call, int *slot)
{
  struct msocl__moving *m;
  MSOCL__TRY(moving(s, call, &m));
  for (int c = 0; c < m->n; c++)
    if (!m->add[c].kind) {
      *slot = c;
      return MSOCL_OK;
    }
  if (m->n >= MSOCL__MAX_COLLIDERS)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "%s: the simulation holds %d analytic colliders, the "
                       "most it can (remove one first)",
                       call, MSOCL__MAX_COLLIDERS);
  *slot = m->n;
  return MSOCL_OK;
}

int msocl__colliders_insert(msocl_sim *s, int slot,
                            const struct msocl__collider *c)
{
  struct msocl__moving *m = s->mov;
  msocl__engine *e = s->part[0];
  const unsigned kind = 1u << c->kind;
  /* the program's table has room, and its kernels this kind, or a new
   * program for one more slot or kind */
  if (slot >= e->ncol || !(e->pl_kinds & kind))
    MSOCL__TRY(msocl__engine_colliders(e, slot >= e->ncol ? slot + 1 : e->ncol,
                                       e->pl_kinds | kind));
  m->add[slot] = *c;
  msocl__pose_home(c, m->pos[slot], m->rot[slot]);
  m->target[slot] = 0;
  m->off[slot] = 0;
  if (slot >= m->n)
    m->n = slot + 1;
  return write_table(s, 0.0f, -1.0f);
}

int msocl_sim_remove_collider(msocl_sim *s, int id)
{
  static const char call[] = "msocl_sim_remove_collider";
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  struct msocl__moving *m;
  MSOCL__TRY(moving(s, call, &m));
  MSOCL__TRY(check_id(m, id, call));
  memset(&m->add[id], 0, sizeof m->add[id]);
  m->target[id] = 0;
  m->off[id] = 0;
  return write_table(s, 0.0f, -1.0f);
}

int msocl_sim_set_collider_pose(msocl_sim *s, int id, const float position[3],
                                const float rotation[4])
{
  static const char call[] = "msocl_sim_set_collider_pose";
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  struct msocl__moving *m;
  MSOCL__TRY(moving(s, call, &m));
  MSOCL__TRY(check_id(m, id, call));
  MSOCL__TRY(msocl__pose_check(call, id, m->add[id].kind, position,
                               rotation));
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
  struct msocl__moving *m; /* a query: a split's poses too */
  MSOCL__TRY(loaded(s, &m));
  MSOCL__TRY(check_id(m, id, call));
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
  MSOCL__TRY(check_id(m, id, call));
  m->off[id] = !on;
  return write_table(s, 0.0f, -1.0f);
}

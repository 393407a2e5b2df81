/* Colliders added to and removed from a running simulation
 * (msocl_sim_add_*, msocl_sim_remove_collider): an added collider equals,
 * bitwise, the same collider in the model disabled until then and
 * enabled there (GRID's sweep, with wind, and its passes, BUFFER,
 * IMAGE2D, Verlet, RK4, implicit Euler); a capsule and a box added
 * mid-run and carried at 5 m/s through a hanging cloth leave no point
 * inside; a removed collider equals a disabled one, and an add after it
 * takes its slot without a rebuild; the reference given the same adds
 * agrees; bad input is refused. */
#include "scenes.h"
#include "expect.h"
#include "sim.h" /* whether a rebuild ran: the engine's kernels */

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt
#define ERR(call, code, text)                                                 \
  do {                                                                        \
    EXPECT(call, code);                                                       \
    SAYS(text);                                                               \
  } while (0)
/* the steps before the add, and after it */
#define BEFORE 30
#define AFTER 60

static const float ident[4] = {0.0f, 0.0f, 0.0f, 1.0f};

/* check_colliders_moving's curtain (n 16 runs GRID's symplectic Euler in
 * kernels/planes_rows.cl on a CPU, n 15 in the planes passes). */
static msocl_model *curtain(int n, float damping)
{
  return scene_curtain(n, damping);
}

/* The step: implicit Euler's stable dt is unbounded, so symplectic
 * Euler's. */
static float step_dt(const msocl_model *m, msocl_integrator in)
{
  float dt;
  OK(msocl_stable_dt(m, in == MSOCL_IMPLICIT_EULER ? MSOCL_SYMPLECTIC_EULER
                                                   : in, &dt));
  return dt;
}

static msocl_sim *make(const msocl_model *m, msocl_integrator in,
                       msocl_layout layout)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = step_dt(m, in);
  o.integrator = in;
  o.check_every = 0;
  o.tuning.layout = layout;
  msocl_sim *s = NULL;
  OK(msocl_sim_create(&s, rt, m, &o));
  return s;
}

/* The shapes, at z = -0.25 m behind the cloth, then carried at 5 m/s to
 * +0.35 m through it (check_colliders_moving's pass). */
enum { SPHERE, CAPSULE, BOX, PLANE, TABLE };
static const float R_SPHERE = 0.08f, R_CAPSULE = 0.04f;
static const float HALF[3] = {0.06f, 0.05f, 0.03f};
static const float START[3] = {0.0f, -0.3f, -0.25f};
#define SPEED 5.0f

static void capsule_ends(const float P[3], float a[3], float b[3])
{
  memcpy(a, P, 3 * sizeof *a);
  memcpy(b, P, 3 * sizeof *b);
  a[0] -= 0.1f;
  b[0] += 0.1f;
}

/* Shape `kind` into the model (s NULL) or the simulation; its id. */
static int add(msocl_model *m, msocl_sim *s, int kind)
{
  int id = -1;
  float a[3], b[3];
  capsule_ends(START, a, b);
  /* a plane below the cloth, a table beside it: they touch nothing */
  const float up[3] = {0.0f, 1.0f, 0.0f}, top[3] = {2.0f, -0.1f, 0.0f};
  switch (kind) {
  case SPHERE:
    if (m)
      OK(msocl_model_add_sphere(m, START, R_SPHERE, 0.3f));
    else
      OK(msocl_sim_add_sphere(s, START, R_SPHERE, 0.3f, &id));
    break;
  case CAPSULE:
    if (m)
      OK(msocl_model_add_capsule(m, a, b, R_CAPSULE, 0.3f));
    else
      OK(msocl_sim_add_capsule(s, a, b, R_CAPSULE, 0.3f, &id));
    break;
  case BOX:
    if (m)
      OK(msocl_model_add_box(m, START, ident, HALF, 0.3f));
    else
      OK(msocl_sim_add_box(s, START, ident, HALF, 0.3f, &id));
    break;
  case PLANE:
    if (m)
      OK(msocl_model_add_plane(m, up, -2.0f, 0.5f));
    else
      OK(msocl_sim_add_plane(s, up, -2.0f, 0.5f, &id));
    break;
  case TABLE:
    if (m)
      OK(msocl_model_add_table(m, top, 0.1f, 0.5f));
    else
      OK(msocl_sim_add_table(s, top, 0.1f, 0.5f, &id));
    break;
  }
  return id;
}

/* The pose at time t after the add: through the cloth, then at rest at
 * +0.35 m (farther, the cloth dragged along goes unstable). */
static void pose_at(double t, float P[3])
{
  memcpy(P, START, 3 * sizeof *P);
  P[2] = (float)(START[2] + SPEED * fmin(t, 0.6 / SPEED));
}


/* Steps both simulations `steps` more in calls of `sub`, collider id
 * carried along the pass from time t0 (id < 0: none moves). */
static void run_pair(msocl_sim *a, msocl_sim *b, int id, double dt,
                     int steps, int sub, double *t)
{
  for (int j = 0; j < steps; j += sub) {
    if (id >= 0) {
      float P[3];
      *t += sub * dt;
      pose_at(*t, P);
      OK(msocl_sim_set_collider_pose(a, id, P, ident));
      OK(msocl_sim_set_collider_pose(b, id, P, ident));
    }
    OK(msocl_sim_step(a, sub));
    OK(msocl_sim_step(b, sub));
  }
}

/* Whether a and b hold bitwise the same positions and velocities. */
static void same_state(msocl_sim *a, msocl_sim *b, int n, const char *what)
{
  float *x = malloc(12 * (size_t)n * sizeof *x);
  OK(msocl_sim_read_positions(a, x));
  OK(msocl_sim_read_velocities(a, x + 3 * n));
  OK(msocl_sim_read_positions(b, x + 6 * n));
  OK(msocl_sim_read_velocities(b, x + 9 * n));
  for (int i = 0; i < 6 * n; i++)
    ck_assert_msg(isfinite(x[i]), "%s: value %d not finite", what, i);
  ck_assert_msg(!memcmp(x, x + 6 * n, 6 * (size_t)n * sizeof *x),
                "%s: not bitwise (max |diff| %g)", what,
                scene_max_diff(x, x + 6 * n, 6 * n));
  free(x);
}

static const struct {
  int kind, n;
  msocl_integrator in;
  msocl_layout layout;
  float damping;
  int wind;
} pairs[] = {
    {SPHERE, 16, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 0.0f, 1}, /* rows */
    {SPHERE, 16, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 1e-3f, 0},
    {SPHERE, 15, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 1e-3f, 1},
    {SPHERE, 16, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_BUFFER, 1e-3f, 0},
    {SPHERE, 16, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_IMAGE2D, 1e-3f, 0},
    {SPHERE, 16, MSOCL_VERLET, MSOCL_LAYOUT_GRID, 1e-3f, 0},
    {SPHERE, 15, MSOCL_RK4, MSOCL_LAYOUT_BUFFER, 1e-3f, 0},
    {SPHERE, 15, MSOCL_IMPLICIT_EULER, MSOCL_LAYOUT_GRID, 1e-3f, 0},
    /* the sweep dropped for the planes passes, wind moved to its own */
    {CAPSULE, 16, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 0.0f, 0},
    {BOX, 16, MSOCL_EXPLICIT_EULER, MSOCL_LAYOUT_IMAGE2D, 1e-3f, 0},
    {PLANE, 16, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 0.0f, 1},
    {TABLE, 15, MSOCL_VERLET, MSOCL_LAYOUT_BUFFER, 1e-3f, 0},
};

/* a: no collider, the shape added after BEFORE steps; b: the shape in
 * the model, disabled until then; both given the same poses. */
START_TEST(add_equals_enable)
{
  const int kind = pairs[_i].kind, n = pairs[_i].n * pairs[_i].n;
  msocl_model *ma = curtain(pairs[_i].n, pairs[_i].damping),
              *mb = curtain(pairs[_i].n, pairs[_i].damping);
  add(mb, NULL, kind);
  msocl_sim *a = make(ma, pairs[_i].in, pairs[_i].layout),
            *b = make(mb, pairs[_i].in, pairs[_i].layout);
  OK(msocl_sim_enable_collider(b, 0, 0));
  if (pairs[_i].wind) {
    msocl_wind w;
    msocl_wind_init(&w);
    w.velocity[2] = 3.0f;
    OK(msocl_sim_set_wind(a, &w));
    OK(msocl_sim_set_wind(b, &w));
  }
  const float dt = step_dt(ma, pairs[_i].in);
  double t = 0;
  run_pair(a, b, -1, dt, BEFORE, 5, &t);
  same_state(a, b, n, "before the add");
  const msocl__engine *e = a->part[0];
  const int rows = e->pl_rows != NULL;
  if (pairs[_i].in == MSOCL_SYMPLECTIC_EULER &&
      pairs[_i].layout == MSOCL_LAYOUT_GRID)
    ck_assert_int_eq(rows, pairs[_i].n >= 16); /* the sweep, or passes */
  ck_assert_int_eq(add(NULL, a, kind), 0);
  OK(msocl_sim_enable_collider(b, 0, 1));
  /* the sweep stays: it collides with every kind */
  ck_assert_int_eq(e->pl_rows != NULL,
                   rows);
  run_pair(a, b, kind <= BOX ? 0 : -1, dt, AFTER, 3, &t);
  same_state(a, b, n, "after the add");
  printf("add_equals_enable %d: bitwise over %d steps (sweep %d)\n", _i,
         BEFORE + AFTER, e->pl_rows != NULL);
  msocl_sim_destroy(a);
  msocl_sim_destroy(b);
  msocl_model_destroy(ma);
  msocl_model_destroy(mb);
}
END_TEST

/* The test's own gap of the shape at P, in double: < 0 inside. */
static double gap(int kind, const float P[3], const float *p)
{
  double d[3];
  for (int k = 0; k < 3; k++)
    d[k] = (double)p[k] - P[k];
  if (kind == CAPSULE) {
    const double t = fmin(fmax(d[0], -0.1), 0.1);
    return sqrt((d[0] - t) * (d[0] - t) + d[1] * d[1] + d[2] * d[2]) -
           R_CAPSULE;
  }
  double g = -INFINITY;
  for (int k = 0; k < 3; k++)
    g = fmax(g, fabs(d[k]) - HALF[k]);
  return g;
}

/* check_colliders_moving's tolerance: a step's motion is 5 m/s * dt
 * (about 4 mm); the response leaves a point on the surface to first
 * order. */
#define TOL 1.5e-3
#define SUB 4

/* A capsule and a box added to a running cloth (GRID's sweep before
 * them, its passes after) and carried through it at 5 m/s. */
START_TEST(added_nothing_inside)
{
  const int kind = _i == 0 ? CAPSULE : BOX, side = 16, n = side * side;
  const msocl_integrator in = _i == 0 ? MSOCL_SYMPLECTIC_EULER : MSOCL_RK4;
  msocl_model *m = curtain(side, _i == 0 ? 0.0f : 1e-3f);
  msocl_sim *s = make(m, in, MSOCL_LAYOUT_GRID);
  float dt;
  OK(msocl_stable_dt(m, in, &dt));
  OK(msocl_sim_step(s, BEFORE));
  const int id = add(NULL, s, kind);
  float *p = malloc(3 * (size_t)n * sizeof *p);
  double worst = INFINITY, touched = INFINITY, t = 0;
  while (t < 0.6 / SPEED) {
    float P[3];
    t += SUB * dt;
    pose_at(t, P);
    OK(msocl_sim_set_collider_pose(s, id, P, ident));
    OK(msocl_sim_step(s, SUB));
    OK(msocl_sim_read_positions(s, p));
    for (int i = 0; i < n; i++) {
      const double g = gap(kind, P, p + 3 * i);
      ck_assert_msg(isfinite(g), "point %d not finite", i);
      worst = fmin(worst, g);
      touched = fmin(touched, fabs(g));
      ck_assert_msg(g >= -TOL, "kind %d: point %d %g m inside at t %g", kind,
                    i, -g, t);
    }
  }
  printf("added_nothing_inside %d: deepest %.3g m\n", _i, -worst);
  ck_assert_msg(touched < 5e-3, "the shape missed the cloth (%g)", touched);
  const float *low = p + 3 * ((side - 4) * side + side / 2);
  ck_assert_msg(low[2] > 0.02f, "cloth not pushed (z %g)", low[2]);
  free(p);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* a: a sphere pressing into the cloth in the model, removed after
 * BEFORE steps; b: the same, disabled there. Bitwise after; then a
 * sphere added to a at the same place takes id 0 again without a rebuild
 * (the same kernels), equal to b's enabled; a table into that slot
 * after another remove is rebuilt and still equal. */
START_TEST(remove_then_reuse)
{
  const int side = _i == 0 ? 16 : 15, n = side * side;
  const float at[3] = {0.0f, -0.3f, 0.06f};
  msocl_model *m = curtain(side, 1e-3f);
  OK(msocl_model_add_sphere(m, at, R_SPHERE, 0.3f));
  add(m, NULL, PLANE);
  msocl_sim *a = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID),
            *b = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID);
  const float dt = step_dt(m, MSOCL_SYMPLECTIC_EULER);
  double t = 0;
  run_pair(a, b, -1, dt, BEFORE, 5, &t);
  OK(msocl_sim_remove_collider(a, 0));
  OK(msocl_sim_enable_collider(b, 0, 0));
  EXPECT(msocl_sim_remove_collider(a, 0), MSOCL_ERR_BAD_INDEX);
  run_pair(a, b, -1, dt, AFTER, 5, &t);
  same_state(a, b, n, "after the remove");
  const msocl__engine *e = a->part[0];
  /* counted, not compared by kernel: a freed kernel's address is often
   * the next one's */
  const int built = e->pl_rebuilds;
  int id = -1;
  OK(msocl_sim_add_sphere(a, at, R_SPHERE, 0.3f, &id));
  ck_assert_int_eq(id, 0);
  ck_assert_msg(e->pl_rebuilds == built,
                "a removed slot's kind in the program: no rebuild");
  OK(msocl_sim_enable_collider(b, 0, 1));
  run_pair(a, b, -1, dt, AFTER, 5, &t);
  same_state(a, b, n, "after the add into the removed slot");
  /* another kind into a removed slot: rebuilt, still that slot */
  OK(msocl_sim_remove_collider(a, 0));
  OK(msocl_sim_enable_collider(b, 0, 0));
  const float top[3] = {2.0f, -0.1f, 0.0f};
  OK(msocl_sim_add_table(a, top, 0.1f, 0.5f, &id));
  ck_assert_int_eq(id, 0);
  ck_assert_msg(e->pl_rebuilds == built + 1,
                "a kind not built in: rebuilt");
  run_pair(a, b, -1, dt, AFTER, 5, &t);
  same_state(a, b, n, "after a table into the removed slot");
  msocl_sim_destroy(a);
  msocl_sim_destroy(b);
  msocl_model_destroy(m);
}
END_TEST

/* The capsule and the box added mid-run on the device and the host
 * reference: within check_colliders_moving's 0.1 mm of each other. */
START_TEST(vs_reference)
{
  const int kind = _i == 0 ? CAPSULE : BOX, side = 16, n = side * side;
  msocl_model *m = curtain(side, 1e-3f);
  add(m, NULL, PLANE); /* id 0: the add takes id 1 */
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  OK(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt));
  msocl_sim *s = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID);
  msocl_reference *r = NULL;
  OK(msocl_reference_create(&r, m, &o));
  OK(msocl_sim_step(s, BEFORE));
  OK(msocl_reference_step(r, BEFORE));
  float a[3], b[3];
  capsule_ends(START, a, b);
  int id = add(NULL, s, kind), rid = -1;
  if (kind == CAPSULE)
    OK(msocl_reference_add_capsule(r, a, b, R_CAPSULE, 0.3f, &rid));
  else
    OK(msocl_reference_add_box(r, START, ident, HALF, 0.3f, &rid));
  ck_assert_int_eq(id, 1);
  ck_assert_int_eq(rid, 1);
  float *p = malloc(6 * (size_t)n * sizeof *p), *q = p + 3 * n;
  double *qd = malloc(3 * (size_t)n * sizeof *qd), worst = 0, t = 0;
  while (t < 0.6 / SPEED) {
    float P[3];
    t += SUB * o.dt;
    pose_at(t, P);
    OK(msocl_sim_set_collider_pose(s, id, P, ident));
    OK(msocl_reference_set_collider_pose(r, rid, P, ident));
    OK(msocl_sim_step(s, SUB));
    OK(msocl_reference_step(r, SUB));
    OK(msocl_sim_read_positions(s, p));
    OK(msocl_reference_positions(r, qd));
    for (int i = 0; i < 3 * n; i++)
      q[i] = (float)qd[i];
    worst = fmax(worst, scene_max_diff(p, q, 3 * n));
  }
  /* removed from both at the pass's end: they keep agreeing (not for
   * long: the cloth it tangled diverges, float against double) */
  OK(msocl_sim_remove_collider(s, id));
  OK(msocl_reference_remove_collider(r, rid));
  EXPECT(msocl_reference_remove_collider(r, rid), MSOCL_ERR_BAD_INDEX);
  OK(msocl_sim_step(s, 2 * SUB));
  OK(msocl_reference_step(r, 2 * SUB));
  OK(msocl_sim_read_positions(s, p));
  OK(msocl_reference_positions(r, qd));
  for (int i = 0; i < 3 * n; i++)
    q[i] = (float)qd[i];
  worst = fmax(worst, scene_max_diff(p, q, 3 * n));
  printf("vs_reference %d: max |device - reference| %.3g m\n", _i, worst);
  ck_assert_msg(worst <= 1e-4, "device and reference differ by %g m", worst);
  free(p);
  free(qd);
  msocl_reference_destroy(r);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = curtain(16, 1e-3f);
  add(m, NULL, SPHERE);
  msocl_sim *s = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID);
  const float c[3] = {0.0f, 0.0f, 0.0f}, nan3[3] = {NAN, 0.0f, 0.0f},
              inf3[3] = {0.0f, INFINITY, 0.0f}, zero3[3] = {0, 0, 0},
              zero4[4] = {0, 0, 0, 0}, flat[3] = {0.1f, 0.0f, 0.1f};
  int id = 7;
  ERR(msocl_sim_add_sphere(NULL, c, 0.1f, 0.3f, &id), MSOCL_ERR_NULL_HANDLE,
      "sim is NULL");
  ERR(msocl_sim_add_sphere(s, nan3, 0.1f, 0.3f, &id), MSOCL_ERR_NOT_FINITE,
      "sphere 1");
  ERR(msocl_sim_add_sphere(s, c, INFINITY, 0.3f, &id), MSOCL_ERR_NOT_FINITE,
      "radius");
  ERR(msocl_sim_add_sphere(s, c, 0.0f, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "must be > 0");
  ERR(msocl_sim_add_table(s, c, -1.0f, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "table 1");
  ERR(msocl_sim_add_sphere(s, c, 0.1f, 1.5f, &id), MSOCL_ERR_BAD_VALUE,
      "outside [0, 1]");
  ERR(msocl_sim_add_sphere(s, c, 0.1f, NAN, &id), MSOCL_ERR_NOT_FINITE,
      "friction");
  ERR(msocl_sim_add_plane(s, zero3, 0.0f, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "normal is zero");
  ERR(msocl_sim_add_plane(s, inf3, 0.0f, 0.3f, &id), MSOCL_ERR_NOT_FINITE,
      "plane 1");
  ERR(msocl_sim_add_capsule(s, c, flat, 0.0f, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "capsule 1: radius");
  ERR(msocl_sim_add_capsule(s, c, nan3, 0.1f, 0.3f, &id),
      MSOCL_ERR_NOT_FINITE, "capsule 1");
  ERR(msocl_sim_add_capsule(s, NULL, c, 0.1f, 0.3f, &id),
      MSOCL_ERR_NULL_HANDLE, "an end is NULL");
  ERR(msocl_sim_add_box(s, c, ident, flat, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "half extent 1");
  ERR(msocl_sim_add_box(s, c, zero4, HALF, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "quaternion");
  ERR(msocl_sim_add_box(s, inf3, ident, HALF, 0.3f, &id),
      MSOCL_ERR_NOT_FINITE, "box 1");
  /* finite, past a coordinate's bound (a step's squares overflow) */
  const float huge3[3] = {0.0f, 1e30f, 0.0f};
  ERR(msocl_sim_add_sphere(s, huge3, 0.1f, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "sphere 1: |1e+30| exceeds");
  ERR(msocl_sim_add_sphere(s, c, 1e30f, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "exceeds");
  ERR(msocl_sim_add_capsule(s, c, huge3, 0.1f, 0.3f, &id),
      MSOCL_ERR_BAD_VALUE, "capsule 1");
  ERR(msocl_sim_add_box(s, c, ident, huge3, 0.3f, &id), MSOCL_ERR_BAD_VALUE,
      "box 1");
  ck_assert_int_eq(id, 7); /* untouched by a refused add */
  ERR(msocl_sim_enable_mesh_collider(s, 0, 1), MSOCL_ERR_BAD_INDEX,
      "mesh collider 0: the simulation has none");
  /* unknown and removed ids */
  ERR(msocl_sim_remove_collider(s, 1), MSOCL_ERR_BAD_INDEX, "out of range");
  ERR(msocl_sim_remove_collider(s, -1), MSOCL_ERR_BAD_INDEX, "out of range");
  OK(msocl_sim_remove_collider(s, 0));
  ERR(msocl_sim_remove_collider(s, 0), MSOCL_ERR_BAD_INDEX, "was removed");
  ERR(msocl_sim_enable_collider(s, 0, 1), MSOCL_ERR_BAD_INDEX, "was removed");
  ERR(msocl_sim_set_collider_pose(s, 0, c, ident), MSOCL_ERR_BAD_INDEX,
      "was removed");
  float P[3], Q[4];
  ERR(msocl_sim_get_collider_pose(s, 0, P, Q), MSOCL_ERR_BAD_INDEX,
      "was removed");
  /* the table fills: 16 in use, the 17th refused; ids 0, 1, .. 15 */
  for (int k = 0; k < MSOCL_MAX_COLLIDERS; k++) {
    const float at[3] = {3.0f + (float)k, 0.0f, 0.0f};
    OK(msocl_sim_add_sphere(s, at, 0.1f, 0.3f, &id));
    ck_assert_int_eq(id, k);
  }
  ERR(msocl_sim_add_sphere(s, c, 0.1f, 0.3f, &id), MSOCL_ERR_TOO_MANY,
      "the most it can");
  OK(msocl_sim_remove_collider(s, 5));
  const float up[3] = {0.0f, 1.0f, 0.0f};
  OK(msocl_sim_add_plane(s, up, -5.0f, 0.3f, &id));
  ck_assert_int_eq(id, 5);
  EXPECT(msocl_sim_add_sphere(s, c, 0.1f, 0.3f, NULL), MSOCL_ERR_TOO_MANY);
  OK(msocl_sim_step(s, 10)); /* still runs */
  msocl_sim_destroy(s);
  /* the reference's checks and full table */
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  OK(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt));
  msocl_reference *r = NULL;
  OK(msocl_reference_create(&r, m, &o));
  ERR(msocl_reference_add_box(r, c, zero4, HALF, 0.3f, &id),
      MSOCL_ERR_BAD_VALUE, "quaternion");
  ERR(msocl_reference_add_sphere(r, nan3, 0.1f, 0.3f, &id),
      MSOCL_ERR_NOT_FINITE, "sphere 1");
  for (int k = 1; k < MSOCL_MAX_COLLIDERS; k++)
    OK(msocl_reference_add_sphere(r, c, 0.1f, 0.3f, &id));
  ck_assert_int_eq(id, MSOCL_MAX_COLLIDERS - 1);
  EXPECT(msocl_reference_add_sphere(r, c, 0.1f, 0.3f, &id),
         MSOCL_ERR_TOO_MANY);
  msocl_reference_destroy(r);
  msocl_model_destroy(m);
}
END_TEST

/* A simulation split over two devices refuses adds and removes. */
START_TEST(split_refuses)
{
  char spec[64];
  if (scene_cpu_spec(spec, sizeof spec, 2) < 2) {
    puts("split_refuses: fewer than two CPU devices, skipped");
    return;
  }
  msocl_runtime *two = NULL;
  OK(msocl_runtime_create(&two, spec));
  msocl_model *m = curtain(16, 1e-3f);
  add(m, NULL, SPHERE);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  OK(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt));
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  o.tuning.ndevices = 2;
  msocl_sim *s = NULL;
  OK(msocl_sim_create(&s, two, m, &o));
  ERR(msocl_sim_add_sphere(s, START, 0.1f, 0.3f, NULL), MSOCL_ERR_BAD_VALUE,
      "split over 2 devices");
  ERR(msocl_sim_remove_collider(s, 0), MSOCL_ERR_BAD_VALUE,
      "split over 2 devices");
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(two);
}
END_TEST

int main(void)
{
  scene_require_device("check_colliders_add");
  Suite *su = suite_create("colliders_add");
  TCase *tc = tcase_create("colliders_add");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, add_equals_enable, 0,
                      (int)(sizeof pairs / sizeof pairs[0]));
  tcase_add_loop_test(tc, added_nothing_inside, 0, 2);
  tcase_add_loop_test(tc, remove_then_reuse, 0, 2);
  tcase_add_loop_test(tc, vs_reference, 0, 2);
  tcase_add_test(tc, bad_input);
  tcase_add_test(tc, split_refuses);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

/* Colliders that move (msocl_sim_set_collider_pose): a sphere, a capsule
 * and a box moving at 5 m/s (and a box turning) through a hanging cloth
 * leave no point inside them at the end of any call; a cloth resting on a
 * box carried sideways at friction 1 moves with it; a call of k steps
 * equals k one-step calls given the path's poses, bitwise; a disabled
 * sphere lets the cloth fall through; the host reference given the same
 * poses agrees; bad input is refused. */
#include "scenes.h"
#include "expect.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt
/* a call fails with code and a message containing text */
#define ERR(call, code, text)                                                 \
  do {                                                                        \
    EXPECT(call, code);                                                       \
    SAYS(text);                                                               \
  } while (0)
#define N 16 /* the hanging cloth's side */

static const float ident[4] = {0.0f, 0.0f, 0.0f, 1.0f};

/* scene_curtain's N x N cloth, with dashpots `damping` (0: GRID's
 * symplectic Euler then runs kernels/planes_rows.cl on a CPU). */
static msocl_model *curtain_damped(float damping)
{
  return scene_curtain(N, damping);
}

static msocl_model *curtain(void)
{
  return curtain_damped(1e-3f);
}

/* check: keep the blow-up check on (its default period), else off */
static msocl_sim *make_checked(const msocl_model *m, msocl_integrator in,
                               msocl_layout layout, int check)
{
  float dt;
  OK(msocl_stable_dt(m, in, &dt));
  return scene_sim(m, in, dt, layout, check ? -1 : 0);
}

static msocl_sim *make(const msocl_model *m, msocl_integrator in,
                       msocl_layout layout)
{
  return make_checked(m, in, layout, 0);
}

static float sim_dt(const msocl_model *m, msocl_integrator in)
{
  float dt;
  OK(msocl_stable_dt(m, in, &dt));
  return dt;
}

/* The test's own rotation of v by unit quaternion q, in double. */
static void rotate(const double q[4], const double v[3], double o[3])
{
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w),
                           2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z),
                           2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w),
                           1 - 2 * (x * x + y * y)}};
  for (int i = 0; i < 3; i++)
    o[i] = R[i][0] * v[0] + R[i][1] * v[1] + R[i][2] * v[2];
}

enum { SPHERE, CAPSULE, BOX, BOX_TURNING };

/* The moving shapes, each added at z = -0.25 m and carried to +0.35 m
 * at 5 m/s through the cloth at z = 0 (the turning box a quarter turn about
 * y, 16 rad/s); their sizes at the add-time pose. */
static const float R_SPHERE = 0.08f, R_CAPSULE = 0.04f;
static const float HALF[3] = {0.06f, 0.05f, 0.03f};
#define Z0 -0.25f
#define SPEED 5.0f

/* The pose at time t of the pass. */
static void pose_at(int kind, double t, float P[3], float Q[4])
{
  P[0] = 0.0f;
  P[1] = -0.3f;
  P[2] = (float)(Z0 + SPEED * t);
  memcpy(Q, ident, sizeof ident);
  if (kind == BOX_TURNING) {
    const double a = 1.5707963267949 * SPEED * t / 0.5; /* pi/2 a 0.5 m */
    Q[1] = (float)sin(0.5 * a);
    Q[3] = (float)cos(0.5 * a);
  }
}

static void add_shape(msocl_model *m, int kind)
{
  float P[3], Q[4];
  pose_at(kind, 0.0, P, Q);
  if (kind == SPHERE)
    OK(msocl_model_add_sphere(m, P, R_SPHERE, 0.3f));
  else if (kind == CAPSULE) {
    const float a[3] = {P[0] - 0.1f, P[1], P[2]},
                b[3] = {P[0] + 0.1f, P[1], P[2]};
    OK(msocl_model_add_capsule(m, a, b, R_CAPSULE, 0.3f));
  } else
    OK(msocl_model_add_box(m, P, Q, HALF, 0.3f));
}

/* The test's gap of the shape at pose (P, Q), in double: < 0 inside. */
static double gap(int kind, const float P[3], const float Q[4],
                  const float *p)
{
  double q[4], len = 0, d[3], l[3];
  for (int k = 0; k < 4; k++)
    len += (double)Q[k] * Q[k];
  for (int k = 0; k < 4; k++)
    q[k] = Q[k] / sqrt(len);
  for (int k = 0; k < 3; k++)
    d[k] = (double)p[k] - P[k];
  if (kind == SPHERE)
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - R_SPHERE;
  /* p in the shape's frame: R^T d */
  const double qc[4] = {-q[0], -q[1], -q[2], q[3]};
  rotate(qc, d, l);
  if (kind == CAPSULE) {
    const double t = fmin(fmax(l[0], -0.1), 0.1);
    return sqrt((l[0] - t) * (l[0] - t) + l[1] * l[1] + l[2] * l[2]) -
           R_CAPSULE;
  }
  double g = -INFINITY;
  for (int k = 0; k < 3; k++)
    g = fmax(g, fabs(l[k]) - HALF[k]);
  return g;
}

/* Calls of SUB steps a frame carry the shape through the cloth; after
 * every call no point is deeper than TOL in the shape at the pose it
 * reached, and the shape touched the cloth (some point within 5 mm). The
 * tolerance: a step's motion is 5 m/s * dt (about 4 mm), and the
 * response makes the relative motion leave a point on the surface to
 * first order; 1.5 mm allows the curvature and the turn (0.06 rad) over
 * a step. */
#define TOL 1.5e-3
#define SUB 4

static const struct {
  int kind;
  msocl_integrator in;
  msocl_layout layout;
  float damping;
} passes[] = {
    {SPHERE, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 0.0f}, /* rows */
    {SPHERE, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 1e-3f},
    {CAPSULE, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 1e-3f},
    {BOX, MSOCL_VERLET, MSOCL_LAYOUT_BUFFER, 1e-3f},
    {BOX_TURNING, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID, 1e-3f},
    {SPHERE, MSOCL_RK4, MSOCL_LAYOUT_GRID, 1e-3f}, /* planes_project */
    {BOX_TURNING, MSOCL_EXPLICIT_EULER, MSOCL_LAYOUT_IMAGE2D, 1e-3f},
};

START_TEST(nothing_inside)
{
  const int kind = passes[_i].kind;
  msocl_model *m = curtain_damped(passes[_i].damping);
  add_shape(m, kind);
  /* pass 1 with the blow-up check on: a moving call's steps in its
   * batches */
  msocl_sim *s = make_checked(m, passes[_i].in, passes[_i].layout, _i == 1);
  const double dt = sim_dt(m, passes[_i].in);
  const int n = N * N;
  float *p = malloc(3 * (size_t)n * sizeof *p);
  double worst = INFINITY, touched = INFINITY;
  int calls = 0;
  for (double t = 0.0; t < 0.6 / SPEED; calls++) {
    t += SUB * dt;
    float P[3], Q[4], P2[3], Q2[4];
    pose_at(kind, t, P, Q);
    OK(msocl_sim_set_collider_pose(s, 0, P, Q));
    OK(msocl_sim_step(s, SUB));
    OK(msocl_sim_get_collider_pose(s, 0, P2, Q2));
    ck_assert(!memcmp(P, P2, sizeof P) && !memcmp(Q, Q2, sizeof Q));
    OK(msocl_sim_read_positions(s, p));
    for (int i = 0; i < n; i++) {
      const double g = gap(kind, P, Q, p + 3 * i);
      ck_assert_msg(isfinite(g), "point %d not finite", i);
      worst = fmin(worst, g);
      touched = fmin(touched, fabs(g));
      ck_assert_msg(g >= -TOL,
                    "pass %d call %d: point %d %g m inside the shape", _i,
                    calls, i, -g);
    }
  }
  printf("pass %d: deepest %.3g m, %d calls\n", _i, -worst, calls);
  ck_assert_msg(touched < 5e-3, "pass %d: the shape missed the cloth (%g)",
                _i, touched);
  /* it pushed the cloth: its lower middle went along +z */
  const float *low = p + 3 * ((N - 4) * N + N / 2);
  ck_assert_msg(low[2] > 0.02f, "pass %d: cloth not pushed (z %g)", _i,
                low[2]);
  free(p);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* The passes of a capsule and the turning box against the host
 * reference given the same poses: within 0.1 mm at every call (float
 * against double; measured up to 2e-5 m, RK4's capsule). */
START_TEST(vs_reference)
{
  static const int kinds[2] = {CAPSULE, BOX_TURNING};
  static const msocl_integrator ins[2] = {MSOCL_SYMPLECTIC_EULER, MSOCL_RK4};
  const int kind = kinds[_i % 2];
  const msocl_integrator in = ins[_i / 2];
  msocl_model *m = curtain();
  add_shape(m, kind);
  msocl_sim *s = make(m, in, MSOCL_LAYOUT_GRID);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = sim_dt(m, in);
  o.integrator = in;
  msocl_reference *r = NULL;
  OK(msocl_reference_create(&r, m, &o));
  const int n = N * N;
  float *p = malloc(6 * (size_t)n * sizeof *p), *q = p + 3 * n;
  double *qd = malloc(3 * (size_t)n * sizeof *qd);
  double worst = 0, deepest = INFINITY;
  for (double t = 0.0; t < 0.6 / SPEED;) {
    t += SUB * o.dt;
    float P[3], Q[4];
    pose_at(kind, t, P, Q);
    OK(msocl_sim_set_collider_pose(s, 0, P, Q));
    OK(msocl_reference_set_collider_pose(r, 0, P, Q));
    OK(msocl_sim_step(s, SUB));
    OK(msocl_reference_step(r, SUB));
    OK(msocl_sim_read_positions(s, p));
    OK(msocl_reference_positions(r, qd));
    for (int i = 0; i < 3 * n; i++)
      q[i] = (float)qd[i];
    worst = fmax(worst, scene_max_diff(p, q, 3 * n));
    for (int i = 0; i < n; i++)
      deepest = fmin(deepest, gap(kind, P, Q, q + 3 * i));
  }
  printf("vs_reference %d: max |device - reference| %.3g m, reference "
         "deepest %.3g m\n", _i, worst, -deepest);
  ck_assert_msg(worst <= 1e-4, "device and reference differ by %g m", worst);
  free(p);
  free(qd);
  msocl_reference_destroy(r);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* GRID (planes_rows for symplectic Euler's sphere), BUFFER (on a CPU
 * planes_wide.cl's vectors) and IMAGE2D give bitwise the same pass of a
 * moving shape: the collision response (symplectic Euler, Verlet's
 * drift) and the projection (RK4's last stage, forward Euler). */
static const struct {
  int kind;
  msocl_integrator in;
  float damping;
} alike[] = {
    {SPHERE, MSOCL_SYMPLECTIC_EULER, 0.0f},
    {BOX_TURNING, MSOCL_SYMPLECTIC_EULER, 0.0f},
    {BOX_TURNING, MSOCL_VERLET, 1e-3f},
    {CAPSULE, MSOCL_RK4, 1e-3f},
    {BOX_TURNING, MSOCL_RK4, 1e-3f},
    {SPHERE, MSOCL_EXPLICIT_EULER, 1e-3f},
    {CAPSULE, MSOCL_EXPLICIT_EULER, 1e-3f},
};

START_TEST(layouts_bitwise)
{
  static const msocl_layout layouts[3] = {
      MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER, MSOCL_LAYOUT_IMAGE2D};
  const int kind = alike[_i].kind, n = N * N;
  msocl_model *m = curtain_damped(alike[_i].damping);
  add_shape(m, kind);
  const double dt = sim_dt(m, alike[_i].in);
  float *x = malloc(9 * (size_t)n * sizeof *x);
  for (int l = 0; l < 3; l++) {
    msocl_sim *s = make(m, alike[_i].in, layouts[l]);
    for (double t = 0.0; t < 0.6 / SPEED;) {
      t += SUB * dt;
      float P[3], Q[4];
      pose_at(kind, t, P, Q);
      OK(msocl_sim_set_collider_pose(s, 0, P, Q));
      OK(msocl_sim_step(s, SUB));
    }
    OK(msocl_sim_read_positions(s, x + 3 * (size_t)n * l));
    msocl_sim_destroy(s);
  }
  for (int l = 1; l < 3; l++)
    ck_assert_msg(!memcmp(x, x + 3 * (size_t)n * l, 3 * (size_t)n * sizeof *x),
                  "case %d: layout %d differs from GRID by %g", _i, l,
                  scene_max_diff(x, x + 3 * (size_t)n * l, 3 * n));
  printf("layouts_bitwise %d: GRID = BUFFER = IMAGE2D\n", _i);
  free(x);
  msocl_model_destroy(m);
}
END_TEST

/* A 0.3 m cloth lying on a box's top face (friction 1), the box then
 * carried along +x at 0.5 m/s: once 0.1 s passed the cloth's mean x
 * velocity is the box's within 1 % (the points touching it take the box's
 * tangential velocity each step; the others follow through the springs). */
START_TEST(carried_by_box)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 12;
  d.origin[0] = -0.15f; d.origin[1] = 0.005f; d.origin[2] = -0.15f;
  d.u[0] = 0.0f; d.u[1] = 0.0f; d.u[2] = 0.3f;
  d.v[0] = 0.3f; d.v[1] = 0.0f; d.v[2] = 0.0f;
  d.point_mass = 0.1f / 144.0f;
  d.k_stretch = 20.0f;
  d.k_shear = 4.0f;
  d.k_bend = 2.0f;
  d.damping = 1e-3f;
  msocl_model *m = NULL;
  OK(msocl_model_cloth_grid(&m, &d));
  const float c0[3] = {0.0f, -0.05f, 0.0f}, half[3] = {0.3f, 0.05f, 0.3f};
  OK(msocl_model_add_box(m, c0, ident, half, 1.0f));
  msocl_sim *s = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID);
  const double dt = sim_dt(m, MSOCL_SYMPLECTIC_EULER);
  const int frame = 10, settle = (int)(0.1 / dt / frame) + 1;
  OK(msocl_sim_step(s, settle * frame)); /* lands on it */
  const float speed = 0.5f;
  float *v = malloc(3 * 144 * sizeof *v);
  double t = 0.0;
  for (int f = 0; f < 3 * settle; f++) {
    t += frame * dt;
    const float P[3] = {(float)(speed * t), c0[1], c0[2]};
    OK(msocl_sim_set_collider_pose(s, 0, P, ident));
    OK(msocl_sim_step(s, frame));
    if (f < settle)
      continue;
    OK(msocl_sim_read_velocities(s, v));
    double mean = 0.0, my = 0.0;
    for (int i = 0; i < 144; i++) {
      mean += v[3 * i] / 144.0;
      my += v[3 * i + 1] / 144.0;
    }
    ck_assert_msg(fabs(mean - speed) <= 0.01 * speed,
                  "frame %d: mean x velocity %g, box %g", f, mean,
                  (double)speed);
    ck_assert_msg(fabs(my) < 0.05, "frame %d: mean y velocity %g", f, my);
  }
  free(v);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* The library's interpolation, as msocl.h states it: (1 - f) a + f b in
 * double, the rotation nlerp'd in double from the ends made unit, the
 * ends exact. */
static void lerp(const float a[3], const float qa[4], const float b[3],
                 const float qb[4], float f, float P[3], float Q[4])
{
  const double g = f;
  for (int k = 0; k < 3; k++)
    P[k] = (float)((1 - g) * a[k] + g * b[k]);
  if (f == 0.0f || f == 1.0f) {
    memcpy(Q, f == 0.0f ? qa : qb, 4 * sizeof *Q);
    return;
  }
  double dot = 0, q[4], len = 0, la = 0, lb = 0;
  for (int k = 0; k < 4; k++) {
    la += (double)qa[k] * qa[k];
    lb += (double)qb[k] * qb[k];
  }
  la = sqrt(la);
  lb = sqrt(lb);
  for (int k = 0; k < 4; k++)
    dot += qa[k] / la * (qb[k] / lb);
  for (int k = 0; k < 4; k++) {
    q[k] = (1 - g) * (qa[k] / la) + (dot < 0 ? -g : g) * (qb[k] / lb);
    len += q[k] * q[k];
  }
  for (int k = 0; k < 4; k++)
    Q[k] = (float)(q[k] / sqrt(len));
}

/* a and b's positions and velocities bitwise alike, after the box pushed
 * the cloth (so that they compare a contact); then both and m freed. */
static void same_and_pushed(msocl_sim *a, msocl_sim *b, msocl_model *m)
{
  const int n = N * N;
  float *x = malloc(12 * (size_t)n * sizeof *x);
  OK(msocl_sim_read_positions(a, x));
  OK(msocl_sim_read_positions(b, x + 3 * n));
  OK(msocl_sim_read_velocities(a, x + 6 * n));
  OK(msocl_sim_read_velocities(b, x + 9 * n));
  ck_assert_msg(!memcmp(x, x + 3 * n, 3 * (size_t)n * sizeof *x),
                "positions differ by %g", scene_max_diff(x, x + 3 * n, 3 * n));
  ck_assert_msg(!memcmp(x + 6 * n, x + 9 * n, 3 * (size_t)n * sizeof *x),
                "velocities differ by %g",
                scene_max_diff(x + 6 * n, x + 9 * n, 3 * n));
  double zmax = 0;
  for (int i = 0; i < n; i++)
    zmax = fmax(zmax, x[3 * i + 2]);
  ck_assert_msg(zmax > 0.01, "the box never met the cloth (z %g)", zmax);
  free(x);
  msocl_sim_destroy(a);
  msocl_sim_destroy(b);
  msocl_model_destroy(m);
}

/* Calls of K steps carrying a turning box equal K one-step calls given
 * the path's poses at j / K, bitwise (positions and velocities). */
START_TEST(calls_bitwise)
{
  enum { K = 7, CALLS = 6 };
  msocl_model *m = curtain();
  add_shape(m, BOX_TURNING);
  msocl_sim *a = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_BUFFER),
             *b = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_BUFFER);
  const double dt = sim_dt(m, MSOCL_SYMPLECTIC_EULER);
  /* the box first reaches the cloth: 0.2 m at 5 m/s */
  float P0[3], Q0[4];
  pose_at(BOX_TURNING, 0.0, P0, Q0);
  for (int c = 0; c < CALLS; c++) {
    float P1[3], Q1[4];
    pose_at(BOX_TURNING, 0.04 + (c + 1) * K * dt, P1, Q1);
    if (c == 0) { /* a jump to the cloth first, then the pass */
      OK(msocl_sim_set_collider_pose(a, 0, P1, Q1));
      OK(msocl_sim_set_collider_pose(b, 0, P1, Q1));
      OK(msocl_sim_step(a, 1));
      OK(msocl_sim_step(b, 1));
      memcpy(P0, P1, sizeof P0);
      memcpy(Q0, Q1, sizeof Q0);
      pose_at(BOX_TURNING, 0.04 + (c + 2) * K * dt, P1, Q1);
    }
    OK(msocl_sim_set_collider_pose(a, 0, P1, Q1));
    OK(msocl_sim_step(a, K));
    for (int j = 1; j <= K; j++) {
      float P[3], Q[4];
      lerp(P0, Q0, P1, Q1, (float)j / (float)K, P, Q);
      OK(msocl_sim_set_collider_pose(b, 0, P, Q));
      OK(msocl_sim_step(b, 1));
    }
    memcpy(P0, P1, sizeof P0);
    memcpy(Q0, Q1, sizeof Q0);
  }
  same_and_pushed(a, b, m);
}
END_TEST

/* A quaternion's scale is no weight: the turning box's poses given as q
 * and as 8 q (exact in float) move the cloth bitwise alike. (The blend
 * used to weigh each end by its length: a box given 10 q turned about
 * 82 degrees where q turns 45 in the first half of a call.) */
START_TEST(quaternion_scale)
{
  enum { K = 5, CALLS = 8 };
  msocl_model *m = curtain();
  add_shape(m, BOX_TURNING);
  msocl_sim *a = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_AUTO),
             *b = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_AUTO);
  const double dt = sim_dt(m, MSOCL_SYMPLECTIC_EULER);
  for (int c = 0; c < CALLS; c++) {
    float P[3], Q[4], Q8[4];
    /* a jump to the cloth (0.2 m at 5 m/s), then the pass */
    pose_at(BOX_TURNING, 0.04 + (c + 1) * K * dt, P, Q);
    for (int k = 0; k < 4; k++)
      Q8[k] = 8.0f * Q[k];
    OK(msocl_sim_set_collider_pose(a, 0, P, Q));
    OK(msocl_sim_set_collider_pose(b, 0, P, Q8));
    OK(msocl_sim_step(a, K));
    OK(msocl_sim_step(b, K));
  }
  same_and_pushed(a, b, m);
}
END_TEST

/* A cloth dropped onto a sphere drapes over it; with the sphere disabled
 * it falls through. */
START_TEST(enable_disable)
{
  for (int on = 1; on >= 0; on--) {
    msocl_model *m = scene_tablecloth(12);
    const float c[3] = {0.0f, -0.1f, 0.0f};
    OK(msocl_model_add_sphere(m, c, 0.1f, 0.5f));
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = scene_tablecloth_dt(12);
    o.check_every = 0;
    msocl_sim *s = NULL;
    OK(msocl_sim_create(&s, rt, m, &o));
    ck_assert_int_eq(msocl_model_collider_count(m), 2);
    /* the table (id 0) off: only the sphere (id 1) can hold the cloth */
    OK(msocl_sim_enable_collider(s, 0, 0));
    OK(msocl_sim_enable_collider(s, 1, on));
    OK(msocl_sim_step(s, (int)(0.4 / o.dt)));
    float p[3];
    const int mid = 6 * 12 + 6;
    OK(msocl_sim_read_list(s, 0, 1, &mid, p));
    const double r = sqrt((double)p[0] * p[0] + (p[1] + 0.1) * (p[1] + 0.1) +
                          (double)p[2] * p[2]);
    if (on) /* draped over it, not inside */
      ck_assert_msg(r > 0.1 - 1e-3 && p[1] > -0.15f,
                    "sphere on: point at %g from its centre, y %g", r, p[1]);
    else
      ck_assert_msg(p[1] < -0.3f, "sphere off: centre point at y %g", p[1]);
    msocl_sim_destroy(s);
    msocl_model_destroy(m);
  }
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = curtain();
  add_shape(m, SPHERE);
  const float top[3] = {0.0f, -1.0f, 0.0f};
  OK(msocl_model_add_table(m, top, 0.2f, 0.5f));
  ck_assert_int_eq(msocl_model_collider_count(m), 2);
  ck_assert_int_eq(msocl_model_collider_count(NULL), MSOCL_ERR_NULL_HANDLE);
  msocl_sim *s = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID);
  const float P[3] = {0.0f, -0.3f, -0.2f}, nan3[3] = {0.0f, NAN, 0.0f},
              inf4[4] = {0.0f, INFINITY, 0.0f, 1.0f},
              zero4[4] = {0.0f, 0.0f, 0.0f, 0.0f},
              tilt[4] = {0.1f, 0.0f, 0.0f, 0.995f},
              turn[4] = {0.0f, 0.3826834f, 0.0f, 0.9238795f};
  float out[4];
  ERR(msocl_sim_set_collider_pose(NULL, 0, P, ident), MSOCL_ERR_NULL_HANDLE,
      "sim is NULL");
  ERR(msocl_sim_set_collider_pose(s, 0, NULL, ident), MSOCL_ERR_NULL_HANDLE,
      "position is NULL");
  ERR(msocl_sim_set_collider_pose(s, 0, P, NULL), MSOCL_ERR_NULL_HANDLE,
      "rotation is NULL");
  ERR(msocl_sim_set_collider_pose(s, 2, P, ident), MSOCL_ERR_BAD_INDEX,
      "collider id 2 out of range [0, 2)");
  ERR(msocl_sim_set_collider_pose(s, -1, P, ident), MSOCL_ERR_BAD_INDEX,
      "collider id -1");
  ERR(msocl_sim_set_collider_pose(s, 0, nan3, ident), MSOCL_ERR_NOT_FINITE,
      "position coordinate 1 is nan");
  ERR(msocl_sim_set_collider_pose(s, 0, P, inf4), MSOCL_ERR_NOT_FINITE,
      "rotation component 1 is inf");
  const float huge3[3] = {0.0f, 0.0f, 1e30f};
  ERR(msocl_sim_set_collider_pose(s, 0, huge3, ident), MSOCL_ERR_BAD_VALUE,
      "position coordinate 2, 1e+30, exceeds");
  ERR(msocl_sim_set_collider_pose(s, 0, P, zero4), MSOCL_ERR_BAD_VALUE,
      "quaternion is zero");
  ERR(msocl_sim_set_collider_pose(s, 1, top, tilt), MSOCL_ERR_BAD_VALUE,
      "turns only about y");
  OK(msocl_sim_set_collider_pose(s, 1, top, turn));
  ERR(msocl_sim_enable_collider(NULL, 0, 1), MSOCL_ERR_NULL_HANDLE,
      "sim is NULL");
  ERR(msocl_sim_enable_collider(s, 5, 1), MSOCL_ERR_BAD_INDEX,
      "collider id 5");
  ERR(msocl_sim_get_collider_pose(s, 0, NULL, out), MSOCL_ERR_NULL_HANDLE,
      "position is NULL");
  /* the refused calls changed nothing: the sphere is where it was added */
  float pos[3];
  OK(msocl_sim_get_collider_pose(s, 0, pos, out));
  ck_assert(pos[2] == Z0 && out[3] == 1.0f);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A simulation split over two devices refuses moving colliders. */
START_TEST(split_refuses)
{
  char spec[64];
  if (scene_cpu_spec(spec, sizeof spec, 2) < 2)
    return; /* one device: nothing to split */
  msocl_runtime *two = NULL;
  OK(msocl_runtime_create(&two, spec));
  msocl_model *m = curtain();
  add_shape(m, SPHERE);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  OK(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt));
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  o.tuning.ndevices = 2;
  msocl_sim *s = NULL;
  OK(msocl_sim_create(&s, two, m, &o));
  const float P[3] = {0.0f, 0.0f, 0.0f};
  ERR(msocl_sim_set_collider_pose(s, 0, P, ident), MSOCL_ERR_BAD_VALUE,
      "split over 2 devices");
  /* a query answers: the sphere where the model put it */
  float pos[3], rot[4], home[3], q[4];
  pose_at(SPHERE, 0.0, home, q);
  OK(msocl_sim_get_collider_pose(s, 0, pos, rot));
  ck_assert(!memcmp(pos, home, sizeof pos) && rot[3] == 1.0f);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(two);
}
END_TEST

int main(void)
{
  scene_require_device("check_colliders_moving");
  Suite *su = suite_create("colliders_moving");
  TCase *tc = tcase_create("colliders_moving");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, nothing_inside, 0,
                      (int)(sizeof passes / sizeof passes[0]));
  tcase_add_loop_test(tc, vs_reference, 0, 4);
  tcase_add_loop_test(tc, layouts_bitwise, 0,
                      (int)(sizeof alike / sizeof alike[0]));
  tcase_add_test(tc, carried_by_box);
  tcase_add_test(tc, calls_bitwise);
  tcase_add_test(tc, quaternion_scale);
  tcase_add_test(tc, enable_disable);
  tcase_add_test(tc, bad_input);
  tcase_add_test(tc, split_refuses);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

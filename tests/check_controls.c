/* Live controls on a running simulation (msocl.h): gravity changed
 * between calls matches the host reference; pins given targets reach them
 * exactly at the end of each call, and a call of k steps equals k one-step
 * calls given the path's points, bitwise; GRID, BUFFER and IMAGE2D stay
 * bitwise one another with the controls on; the moving pins
 * match the reference; partial reads and writes touch only their points;
 * and every bad input is refused with a clear error. */
#include "scenes.h"
#include "expect.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt
#define N 12 /* the hanging cloth's side */

static msocl_integrator integrators[] = {MSOCL_SYMPLECTIC_EULER, MSOCL_VERLET,
                                         MSOCL_RK4, MSOCL_IMPLICIT_EULER};

static float dt_for(const msocl_model *m, msocl_integrator in)
{
  float dt = 0.0f;
  if (in == MSOCL_IMPLICIT_EULER)
    in = MSOCL_SYMPLECTIC_EULER;
  OK(msocl_safe_dt(m, in, &dt));
  return dt;
}

static msocl_sim *make(const msocl_model *m, msocl_integrator in,
                       msocl_layout layout)
{
  return scene_sim(m, in, dt_for(m, in), layout, 0);
}

static msocl_reference *make_ref(const msocl_model *m, msocl_integrator in)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt_for(m, in);
  o.integrator = in;
  msocl_reference *r = NULL;
  OK(msocl_reference_create(&r, m, &o));
  return r;
}

static double vs_ref(msocl_sim *s, msocl_reference *r, int n)
{
  float *p = malloc(3 * (size_t)n * sizeof *p);
  double *q = malloc(3 * (size_t)n * sizeof *q);
  OK(msocl_sim_read_positions(s, p));
  OK(msocl_reference_positions(r, q));
  double e = 0.0;
  for (int i = 0; i < 3 * n; i++)
    if (fabs(p[i] - q[i]) > e || !isfinite(p[i]))
      e = isfinite(p[i]) ? fabs(p[i] - q[i]) : INFINITY;
  free(p);
  free(q);
  return e;
}

/* Tolerance: 1e-4 of the 1 m cloth over 0.5 s, check_accuracy's. */
START_TEST(gravity_vs_reference)
{
  const msocl_integrator in = integrators[_i % 4];
  const msocl_layout lay = _i < 4 ? MSOCL_LAYOUT_GRID : MSOCL_LAYOUT_BUFFER;
  msocl_model *m = scene_hanging(N);
  msocl_sim *s = make(m, in, lay);
  msocl_reference *r = make_ref(m, in);
  const int steps = (int)(0.25f / dt_for(m, in));
  OK(msocl_sim_step(s, steps));
  OK(msocl_reference_step(r, steps));
  OK(msocl_sim_set_gravity(s, 4.0f, -2.0f, 3.0f));
  OK(msocl_reference_set_gravity(r, 4.0f, -2.0f, 3.0f));
  OK(msocl_sim_step(s, steps));
  OK(msocl_reference_step(r, steps));
  const double e = vs_ref(s, r, N * N);
  ck_assert_msg(e <= 1e-4, "integrator %d layout %d: %g m", (int)in,
                (int)lay, e);
  /* and the change did something: the cloth swung along +x */
  float p[3];
  OK(msocl_sim_read_list(s, 0, 1, (int[]){N * N - 1}, p));
  ck_assert_msg(p[0] > 1.05f, "corner x %g: gravity's x not felt", p[0]);
  msocl_reference_destroy(r);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Viscous damping and air resistance changed mid-run on both, from a
 * model without either (the simulation builds the terms then): within
 * the same 1e-4 m of the reference, and felt (the cloth swings less). */
START_TEST(damping_vs_reference)
{
  const msocl_integrator in = integrators[_i];
  msocl_model *m = scene_hanging(N);
  OK(msocl_model_set_viscous_damping(m, 0.0f));
  msocl_sim *s = make(m, in, MSOCL_LAYOUT_GRID),
             *free_ = make(m, in, MSOCL_LAYOUT_GRID);
  msocl_reference *r = make_ref(m, in);
  const int steps = (int)(0.25f / dt_for(m, in));
  OK(msocl_sim_step(s, steps));
  OK(msocl_reference_step(r, steps));
  OK(msocl_sim_set_viscous_damping(s, 0.05f));
  OK(msocl_reference_set_viscous_damping(r, 0.05f));
  OK(msocl_sim_set_air_resistance(s, 0.995f));
  OK(msocl_reference_set_air_resistance(r, 0.995f));
  OK(msocl_sim_step(s, steps));
  OK(msocl_reference_step(r, steps));
  const double e = vs_ref(s, r, N * N);
  ck_assert_msg(e <= 1e-4, "integrator %d: %g m", (int)in, e);
  OK(msocl_sim_step(free_, 2 * steps));
  float a[3], b[3];
  OK(msocl_sim_read_list(s, 0, 1, (int[]){N * N - 1}, a));
  OK(msocl_sim_read_list(free_, 0, 1, (int[]){N * N - 1}, b));
  ck_assert_msg(fabsf(a[1] - b[1]) > 1e-3f, "integrator %d: damping not felt",
                (int)in);
  EXPECT(msocl_reference_set_viscous_damping(r, -1.0f), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_reference_set_air_resistance(r, 0.0f), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_reference_set_air_resistance(r, NAN), MSOCL_ERR_NOT_FINITE);
  msocl_reference_destroy(r);
  msocl_sim_destroy(s);
  msocl_sim_destroy(free_);
  msocl_model_destroy(m);
}
END_TEST

/* The two pins carried along a circle, a call of `steps` steps a frame. */
static void frame_targets(int frame, float *t)
{
  const float a = 0.3f * (float)frame;
  t[0] = 0.2f * sinf(a);
  t[1] = 0.1f * (1.0f - cosf(a));
  t[2] = 0.15f * sinf(a);
  t[3] = 1.0f + t[0];
  t[4] = t[1];
  t[5] = -t[2];
}

START_TEST(pins_reach_targets)
{
  static const msocl_layout layouts[] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                                         MSOCL_LAYOUT_IMAGE2D};
  msocl_model *m = scene_hanging(N);
  msocl_sim *s = make(m, integrators[_i % 4], layouts[_i / 4]);
  for (int f = 1; f <= 6; f++) {
    float t[6], p[6];
    frame_targets(f, t);
    OK(msocl_sim_set_pin_targets(s, 2, NULL, t));
    OK(msocl_sim_step(s, 5));
    OK(msocl_sim_read_list(s, 0, 2, (int[]){0, N - 1}, p));
    ck_assert_msg(memcmp(p, t, sizeof t) == 0,
                  "frame %d: pin at (%.9g %.9g %.9g), target (%.9g %.9g %.9g)",
                  f, p[0], p[1], p[2], t[0], t[1], t[2]);
  }
  /* with no new targets they stay */
  float before[3], after[3];
  OK(msocl_sim_read_range(s, 0, 0, 1, before));
  OK(msocl_sim_step(s, 3));
  OK(msocl_sim_read_range(s, 0, 0, 1, after));
  ck_assert(memcmp(before, after, sizeof before) == 0);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A batch's call spends the targets as msocl_sim_step's does. */
START_TEST(batch_reaches_targets)
{
  msocl_model *m = scene_hanging(N);
  const msocl_model *ms[2] = {m, m};
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt_for(m, MSOCL_SYMPLECTIC_EULER);
  msocl_batch *b = NULL;
  OK(msocl_batch_create(&b, rt, 2, ms, &o));
  float t[6];
  frame_targets(2, t);
  for (int i = 0; i < 2; i++) {
    msocl_sim *s = NULL;
    OK(msocl_batch_sim(b, i, &s));
    OK(msocl_sim_set_pin_targets(s, 2, NULL, t));
  }
  OK(msocl_batch_step(b, 8));
  for (int i = 0; i < 2; i++) {
    msocl_sim *s = NULL;
    float p[6];
    OK(msocl_batch_sim(b, i, &s));
    OK(msocl_sim_read_list(s, 0, 2, (int[]){0, N - 1}, p));
    ck_assert_msg(memcmp(p, t, sizeof t) == 0, "sim %d: pin at %.9g", i,
                  p[0]);
  }
  msocl_batch_destroy(b);
  msocl_model_destroy(m);
}
END_TEST

/* A cloth numbered at random (point q is grid point (7 q) mod 64), which
 * the simulation renumbers: partial access and targets keep the model's
 * numbers. */
START_TEST(renumbered_model_numbers)
{
  enum { S = 8, P = S * S };
  msocl_model *m = NULL;
  OK(msocl_model_create(&m));
  float xyz[3 * P], mass[P];
  int at[P]; /* model number of grid point g */
  for (int q = 0; q < P; q++) {
    const int g = 7 * q % P;
    at[g] = q;
    xyz[3 * q] = (float)(g % S) / (S - 1);
    xyz[3 * q + 1] = -(float)(g / S) / (S - 1);
    xyz[3 * q + 2] = 0.0f;
    mass[q] = 1.0f / P;
  }
  OK(msocl_model_add_points(m, P, xyz, mass, NULL));
  int ij[4 * P], ns = 0;
  for (int g = 0; g < P; g++) {
    if (g % S < S - 1) {
      ij[2 * ns] = at[g];
      ij[2 * ns++ + 1] = at[g + 1];
    }
    if (g / S < S - 1) {
      ij[2 * ns] = at[g];
      ij[2 * ns++ + 1] = at[g + S];
    }
  }
  float k[4 * P];
  for (int q = 0; q < ns; q++)
    k[q] = 20.0f;
  OK(msocl_model_add_springs(m, ns, ij, k, NULL, NULL));
  OK(msocl_model_pin(m, at[0], 1));
  OK(msocl_model_pin(m, at[S - 1], 1));
  msocl_sim *s = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_BUFFER);
  int order[P], moved = 0;
  OK(msocl_sim_point_order(s, order));
  for (int q = 0; q < P; q++)
    moved |= order[q] != q;
  ck_assert_msg(moved, "the model was not renumbered");
  OK(msocl_sim_step(s, 10));
  float all[3 * P], part[9];
  OK(msocl_sim_read_positions(s, all));
  const int idx[3] = {5, 40, 41};
  OK(msocl_sim_read_list(s, 0, 3, idx, part));
  for (int q = 0; q < 3; q++)
    ck_assert(memcmp(part + 3 * q, all + 3 * idx[q], 3 * sizeof(float)) == 0);
  OK(msocl_sim_read_range(s, 0, 40, 2, part));
  ck_assert(memcmp(part, all + 120, 6 * sizeof(float)) == 0);
  const float w[3] = {0.5f, 0.25f, 0.125f};
  OK(msocl_sim_write_list(s, 0, 1, (int[]){41}, w));
  OK(msocl_sim_read_positions(s, all));
  ck_assert(memcmp(all + 123, w, sizeof w) == 0);
  const float t[6] = {0.1f, 0.2f, 0.0f, 0.9f, 0.2f, 0.1f};
  OK(msocl_sim_set_pin_targets(s, 2, (int[]){at[0], at[S - 1]}, t));
  OK(msocl_sim_step(s, 4));
  OK(msocl_sim_read_positions(s, all));
  ck_assert(memcmp(all + 3 * at[0], t, 3 * sizeof(float)) == 0);
  ck_assert(memcmp(all + 3 * at[S - 1], t + 3, 3 * sizeof(float)) == 0);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

static void read_all(msocl_sim *s, float *p, float *v)
{
  OK(msocl_sim_read_positions(s, p));
  OK(msocl_sim_read_velocities(s, v));
}

/* One call of k steps toward T against k calls of one step toward the
 * path's points (1 - f) S + f T, f = (float)j / (float)k: bitwise. */
START_TEST(k_steps_equal_k_single)
{
  const msocl_integrator in = integrators[_i];
  const int k = 7, n = N * N;
  msocl_model *m = scene_hanging(N);
  msocl_sim *a = make(m, in, MSOCL_LAYOUT_GRID),
            *b = make(m, in, MSOCL_LAYOUT_GRID);
  OK(msocl_sim_step(a, 20));
  OK(msocl_sim_step(b, 20));
  for (int f = 1; f <= 3; f++) {
    float S[6], T[6];
    OK(msocl_sim_read_list(b, 0, 2, (int[]){0, N - 1}, S));
    frame_targets(f, T);
    OK(msocl_sim_set_pin_targets(a, 2, NULL, T));
    OK(msocl_sim_step(a, k));
    for (int j = 1; j <= k; j++) {
      const float fr = (float)j / (float)k;
      float t[6];
      for (int q = 0; q < 6; q++)
        t[q] = (1.0f - fr) * S[q] + fr * T[q];
      OK(msocl_sim_set_pin_targets(b, 2, (int[]){0, N - 1}, t));
      OK(msocl_sim_step(b, 1));
    }
  }
  float *pa = malloc(12 * (size_t)n * sizeof(float));
  float *va = pa + 3 * n, *pb = va + 3 * n, *vb = pb + 3 * n;
  read_all(a, pa, va);
  read_all(b, pb, vb);
  ck_assert_msg(memcmp(pa, pb, 3 * (size_t)n * sizeof(float)) == 0,
                "integrator %d: positions differ by %g", (int)in,
                scene_max_diff(pa, pb, 3 * n));
  ck_assert_msg(memcmp(va, vb, 3 * (size_t)n * sizeof(float)) == 0,
                "integrator %d: velocities differ by %g", (int)in,
                scene_max_diff(va, vb, 3 * n));
  /* the pins' velocity is their motion a step */
  ck_assert_msg(fabsf(va[0]) > 0.0f, "pin velocity %g", va[0]);
  free(pa);
  msocl_sim_destroy(a);
  msocl_sim_destroy(b);
  msocl_model_destroy(m);
}
END_TEST

/* Everything at once in GRID, BUFFER and IMAGE2D: bitwise. */
static void run_all_controls(msocl_sim *s)
{
  OK(msocl_sim_step(s, 10));
  OK(msocl_sim_set_gravity(s, 1.0f, -9.0f, 0.5f));
  OK(msocl_sim_pin(s, 1, (int[]){N / 2}, 1));
  for (int f = 1; f <= 3; f++) {
    float t[9];
    frame_targets(f, t);
    t[6] = 0.5f;
    t[7] = 0.1f * (float)f;
    t[8] = 0.05f;
    OK(msocl_sim_set_pin_targets(s, 3, NULL, t));
    OK(msocl_sim_step(s, 6));
  }
  OK(msocl_sim_pin(s, 1, (int[]){N / 2}, 0));
  const float w[6] = {0.3f, -0.2f, 0.1f, 0.0f, 0.5f, 0.0f};
  OK(msocl_sim_write_list(s, 1, 2, (int[]){N * N - 1, N * N - 2}, w));
  OK(msocl_sim_step(s, 10));
}

START_TEST(layouts_bitwise)
{
  const int n = N * N;
  msocl_model *m = scene_hanging(N);
  const msocl_layout ls[3] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                              MSOCL_LAYOUT_IMAGE2D};
  float *p[3], *v[3];
  for (int l = 0; l < 3; l++) {
    msocl_sim *s = make(m, integrators[_i], ls[l]);
    run_all_controls(s);
    p[l] = malloc(3 * (size_t)n * sizeof(float));
    v[l] = malloc(3 * (size_t)n * sizeof(float));
    read_all(s, p[l], v[l]);
    msocl_sim_destroy(s);
  }
  for (int l = 1; l < 3; l++) {
    ck_assert_msg(memcmp(p[0], p[l], 3 * (size_t)n * sizeof(float)) == 0,
                  "layout %d positions differ by %g", l,
                  scene_max_diff(p[0], p[l], 3 * n));
    ck_assert_msg(memcmp(v[0], v[l], 3 * (size_t)n * sizeof(float)) == 0,
                  "layout %d velocities differ by %g", l,
                  scene_max_diff(v[0], v[l], 3 * n));
  }
  for (int l = 0; l < 3; l++) {
    free(p[l]);
    free(v[l]);
  }
  msocl_model_destroy(m);
}
END_TEST

/* Moving pins against the reference's, 1e-4 of the cloth. */
START_TEST(pins_vs_reference)
{
  const msocl_integrator in = integrators[_i];
  msocl_model *m = scene_hanging(N);
  msocl_sim *s = make(m, in, MSOCL_LAYOUT_GRID);
  msocl_reference *r = make_ref(m, in);
  OK(msocl_sim_pin(s, 1, (int[]){N / 2}, 1));
  OK(msocl_reference_pin(r, 1, (int[]){N / 2}, 1));
  for (int f = 1; f <= 5; f++) {
    float t[9];
    frame_targets(f, t);
    t[6] = 0.5f + 0.5f * t[0];
    t[7] = t[1];
    t[8] = 0.1f;
    OK(msocl_sim_set_pin_targets(s, 3, NULL, t));
    OK(msocl_reference_set_pin_targets(r, 3, NULL, t));
    OK(msocl_sim_step(s, 20));
    OK(msocl_reference_step(r, 20));
  }
  const double e = vs_ref(s, r, N * N);
  ck_assert_msg(e <= 1e-4, "integrator %d: %g m", (int)in, e);
  msocl_reference_destroy(r);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Partial writes change exactly their points; reads give them back. */
START_TEST(partial_round_trip)
{
  const int n = N * N;
  msocl_model *m = scene_hanging(N);
  msocl_sim *s = make(m, MSOCL_SYMPLECTIC_EULER,
                      _i ? MSOCL_LAYOUT_BUFFER : MSOCL_LAYOUT_GRID);
  OK(msocl_sim_step(s, 15));
  for (int vel = 0; vel < 2; vel++) {
    float *all0 = malloc(3 * (size_t)n * sizeof(float));
    float *all1 = malloc(3 * (size_t)n * sizeof(float));
    if (vel)
      OK(msocl_sim_read_velocities(s, all0));
    else
      OK(msocl_sim_read_positions(s, all0));
    float range[3 * 5], back[3 * 5];
    OK(msocl_sim_read_range(s, vel, 30, 5, range));
    ck_assert(memcmp(range, all0 + 90, sizeof range) == 0);
    for (int q = 0; q < 15; q++)
      range[q] += 0.25f;
    OK(msocl_sim_write_range(s, vel, 30, 5, range));
    const int idx[3] = {7, 100, 6};
    float list[9] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f};
    OK(msocl_sim_write_list(s, vel, 3, idx, list));
    OK(msocl_sim_read_range(s, vel, 30, 5, back));
    ck_assert(memcmp(range, back, sizeof range) == 0);
    OK(msocl_sim_read_list(s, vel, 3, idx, back));
    ck_assert(memcmp(list, back, sizeof list) == 0);
    if (vel)
      OK(msocl_sim_read_velocities(s, all1));
    else
      OK(msocl_sim_read_positions(s, all1));
    for (int i = 0; i < n; i++) {
      const int touched = (i >= 30 && i < 35) || i == 7 || i == 100 || i == 6;
      ck_assert_msg(touched || !memcmp(all0 + 3 * i, all1 + 3 * i,
                                       3 * sizeof(float)),
                    "point %d changed", i);
    }
    free(all0);
    free(all1);
  }
  /* the pins hold through a write of their positions */
  float p0[3] = {0.0f, 0.3f, 0.0f}, p1[3];
  OK(msocl_sim_write_range(s, 0, 0, 1, p0));
  OK(msocl_sim_step(s, 5));
  OK(msocl_sim_read_range(s, 0, 0, 1, p1));
  ck_assert(memcmp(p0, p1, sizeof p0) == 0);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Viscous damping and air resistance turned on while a simulation runs, though its model had neither (its kernels rebuilt with the
 * terms), equal bitwise a simulation whose model had both, set to none
 * until that step. _i: symplectic Euler on GRID (the sweep) and BUFFER,
 * Verlet, implicit Euler. */
START_TEST(terms_turned_on)
{
  enum { P = N * N };
  const msocl_integrator ins[4] = {MSOCL_SYMPLECTIC_EULER,
                                   MSOCL_SYMPLECTIC_EULER, MSOCL_VERLET,
                                   MSOCL_IMPLICIT_EULER};
  const msocl_layout lay = _i == 1 ? MSOCL_LAYOUT_BUFFER : MSOCL_LAYOUT_GRID;
  msocl_model *bare = scene_hanging(N), *with = scene_hanging(N);
  OK(msocl_model_set_viscous_damping(with, 0.5f));
  OK(msocl_model_set_air_resistance(with, 0.5f));
  /* one dt for all (the model's damping would change the safe one) */
  const float dt = dt_for(bare, ins[_i]);
  msocl_sim *a = scene_sim(bare, ins[_i], dt, lay, 0),
            *b = scene_sim(with, ins[_i], dt, lay, 0);
  OK(msocl_sim_set_viscous_damping(b, 0.0f));
  OK(msocl_sim_set_air_resistance(b, 1.0f));
  OK(msocl_sim_step(a, 30));
  OK(msocl_sim_step(b, 30));
  for (int q = 0; q < 2; q++) {
    msocl_sim *s = q ? b : a;
    OK(msocl_sim_set_viscous_damping(s, 0.05f));
    OK(msocl_sim_set_air_resistance(s, 0.999f));
  }
  OK(msocl_sim_step(a, 50));
  OK(msocl_sim_step(b, 50));
  float pa[3 * P], pb[3 * P], va[3 * P], vb[3 * P];
  OK(msocl_sim_read_positions(a, pa));
  OK(msocl_sim_read_positions(b, pb));
  OK(msocl_sim_read_velocities(a, va));
  OK(msocl_sim_read_velocities(b, vb));
  ck_assert_msg(memcmp(pa, pb, sizeof pa) == 0 &&
                    memcmp(va, vb, sizeof va) == 0,
                "case %d: positions differ by %g, velocities by %g", _i,
                scene_max_diff(pa, pb, 3 * P), scene_max_diff(va, vb, 3 * P));
  /* and the terms act: against no damping at all */
  msocl_sim *c = scene_sim(bare, ins[_i], dt, lay, 0);
  OK(msocl_sim_step(c, 80));
  float pc[3 * P];
  OK(msocl_sim_read_positions(c, pc));
  ck_assert_msg(scene_max_diff(pa, pc, 3 * P) > 1e-6,
                "case %d: damping changed nothing", _i);
  msocl_sim_destroy(a);
  msocl_sim_destroy(b);
  msocl_sim_destroy(c);
  msocl_model_destroy(bare);
  msocl_model_destroy(with);
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = scene_hanging(N);
  msocl_sim *s = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID);
  const float nan = NAN, inf = INFINITY;
  EXPECT(msocl_sim_set_gravity(s, 0.0f, nan, 0.0f), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_sim_set_gravity(s, inf, 0.0f, 0.0f), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_sim_set_gravity(NULL, 0.0f, 0.0f, 0.0f),
         MSOCL_ERR_NULL_HANDLE);
  /* the model's setters refuse while its simulation lives */
  EXPECT(msocl_model_set_gravity(m, 0.0f, -1.0f, 0.0f), MSOCL_ERR_INVALID_ARG);
  SAYS("msocl_sim_set_gravity");
  EXPECT(msocl_model_pin(m, 3, 1), MSOCL_ERR_INVALID_ARG);
  EXPECT(msocl_model_set_viscous_damping(m, 0.1f), MSOCL_ERR_INVALID_ARG);
  EXPECT(msocl_model_set_air_resistance(m, 0.9f), MSOCL_ERR_INVALID_ARG);
  EXPECT(msocl_sim_set_viscous_damping(s, -1.0f), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_sim_set_viscous_damping(s, nan), MSOCL_ERR_NOT_FINITE);
  /* finite values past the limits a step's floats hold, as the model's */
  EXPECT(msocl_sim_set_gravity(s, 0.0f, -1e35f, 0.0f), MSOCL_ERR_BAD_VALUE);
  SAYS("exceeds");
  EXPECT(msocl_sim_set_viscous_damping(s, 1e35f), MSOCL_ERR_BAD_VALUE);
  SAYS("force limit");
  float far[3 * N * N];
  for (int q = 0; q < 3 * N * N; q++)
    far[q] = q == 7 ? 1e38f : 0.0f;
  EXPECT(msocl_sim_set_accelerations(s, far), MSOCL_ERR_BAD_VALUE);
  SAYS("point 2");
  msocl_wind w;
  msocl_wind_init(&w);
  w.velocity[0] = 1e30f;
  EXPECT(msocl_sim_set_wind(s, &w), MSOCL_ERR_BAD_VALUE);
  SAYS("wind");
  /* targets */
  const float t[6] = {0.0f, 0.1f, 0.0f, 1.0f, 0.1f, 0.0f};
  float bad[6];
  memcpy(bad, t, sizeof t);
  bad[4] = nan;
  EXPECT(msocl_sim_set_pin_targets(s, 2, NULL, bad), MSOCL_ERR_NOT_FINITE);
  bad[4] = -inf;
  EXPECT(msocl_sim_set_pin_targets(s, 2, NULL, bad), MSOCL_ERR_NOT_FINITE);
  bad[4] = 1e20f;
  EXPECT(msocl_sim_set_pin_targets(s, 2, NULL, bad), MSOCL_ERR_BAD_VALUE);
  SAYS("target 1");
  bad[4] = nan;
  EXPECT(msocl_sim_set_pin_targets(s, 1, (int[]){5}, t), MSOCL_ERR_BAD_VALUE);
  SAYS("not pinned");
  EXPECT(msocl_sim_set_pin_targets(s, 1, (int[]){N * N}, t),
         MSOCL_ERR_BAD_INDEX);
  EXPECT(msocl_sim_set_pin_targets(s, 1, (int[]){-1}, t), MSOCL_ERR_BAD_INDEX);
  EXPECT(msocl_sim_set_pin_targets(s, 2, (int[]){0, 0}, t),
         MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_sim_set_pin_targets(s, 1, NULL, t), MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_sim_set_pin_targets(s, 2, NULL, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_sim_pin(s, 1, (int[]){N * N}, 1), MSOCL_ERR_BAD_INDEX);
  OK(msocl_sim_set_pin_targets(s, 2, NULL, t));
  EXPECT(msocl_sim_pin(s, 1, (int[]){0}, 0), MSOCL_ERR_BAD_VALUE);
  /* partial access */
  float p[6];
  EXPECT(msocl_sim_read_range(s, 0, N * N - 1, 2, p), MSOCL_ERR_BAD_INDEX);
  EXPECT(msocl_sim_read_range(s, 0, -1, 1, p), MSOCL_ERR_BAD_INDEX);
  EXPECT(msocl_sim_read_list(s, 0, 1, (int[]){N * N}, p), MSOCL_ERR_BAD_INDEX);
  EXPECT(msocl_sim_write_list(s, 1, 1, (int[]){3}, bad + 3),
         MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_sim_write_range(s, 0, 0, 2, bad), MSOCL_ERR_NOT_FINITE);
  bad[4] = 2e18f;
  EXPECT(msocl_sim_write_range(s, 0, 0, 2, bad), MSOCL_ERR_BAD_VALUE);
  SAYS("point 1");
  EXPECT(msocl_sim_write_list(s, 1, 2, (int[]){3, 9}, bad),
         MSOCL_ERR_BAD_VALUE);
  SAYS("point 9");
  EXPECT(msocl_sim_write_list(s, 0, 2, (int[]){4, 4}, t), MSOCL_ERR_BAD_VALUE);
  SAYS("point 4 listed twice");
  EXPECT(msocl_sim_read_list(s, 0, 1, NULL, p), MSOCL_ERR_NULL_HANDLE);
  msocl_sim_destroy(s);
  /* the model is free again once its simulation is gone */
  OK(msocl_model_set_gravity(m, 0.0f, -9.81f, 0.0f));
  /* a split refuses moving pins clearly */
  char spec[64];
  if (scene_cpu_spec(spec, sizeof spec, 2) >= 2) {
    msocl_runtime *two = NULL;
    OK(msocl_runtime_create(&two, spec));
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = dt_for(m, MSOCL_SYMPLECTIC_EULER);
    o.tuning.ndevices = 2;
    OK(msocl_sim_create(&s, two, m, &o));
    EXPECT(msocl_sim_set_pin_targets(s, 2, NULL, t), MSOCL_ERR_BAD_VALUE);
    SAYS("needs one device");
    msocl_sim_destroy(s);
    msocl_runtime_destroy(two);
  }
  msocl_model_destroy(m);
  /* a model made with no pin: runtime pins refused */
  m = scene_hanging(N);
  OK(msocl_model_pin(m, 0, 0));
  OK(msocl_model_pin(m, N - 1, 0));
  s = make(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_GRID);
  EXPECT(msocl_sim_pin(s, 1, (int[]){0}, 1), MSOCL_ERR_BAD_VALUE);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_controls");
  Suite *su = suite_create("controls");
  TCase *tc = tcase_create("controls");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, gravity_vs_reference, 0, 8);
  tcase_add_loop_test(tc, damping_vs_reference, 0, 4);
  tcase_add_loop_test(tc, pins_reach_targets, 0, 12);
  tcase_add_loop_test(tc, k_steps_equal_k_single, 0, 4);
  tcase_add_loop_test(tc, layouts_bitwise, 0, 4);
  tcase_add_loop_test(tc, pins_vs_reference, 0, 4);
  tcase_add_loop_test(tc, partial_round_trip, 0, 2);
  tcase_add_test(tc, batch_reaches_targets);
  tcase_add_test(tc, renumbered_model_numbers);
  tcase_add_loop_test(tc, terms_turned_on, 0, 4);
  tcase_add_test(tc, bad_input);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

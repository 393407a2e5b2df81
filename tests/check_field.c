/* A user's field of accelerations or forces per point: a uniform field on
 * a free plate against the analytic drift; a varying field on a hanging
 * cloth against the double reference (renumbered too); forces equal
 * accelerations times the mass; the layouts still bitwise; a field
 * cleared is none; pinned points stay; bad input refused. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

enum { N = 16, P = N * N };

static msocl_sim *sim_of(const msocl_model *m, msocl_layout layout,
                         msocl_integrator in, msocl_choice renumber)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-3f;
  o.integrator = in;
  o.tuning.layout = layout;
  o.tuning.renumber = renumber;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK, "%s",
                msocl_last_error());
  return s;
}

/* A field that varies from point to point, in N/kg or N. */
static void varying(float *f, float scale)
{
  for (int i = 0; i < P; i++) {
    f[3 * i] = scale * (float)sin(0.3 * i);
    f[3 * i + 1] = scale * 0.5f * (float)cos(0.7 * i);
    f[3 * i + 2] = scale * (float)(i % 5) / 5.0f;
  }
}

/* A free plate at rest without gravity in a uniform field a: symplectic
 * Euler gives v_n = n dt a (in the mean) and x_n = x_0 + dt^2 a n (n + 1)
 * / 2. */
START_TEST(uniform_drift)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = N;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_gravity(m, 0.0f, 0.0f, 0.0f), MSOCL_OK);
  float *x0 = malloc(3 * P * sizeof *x0), *x = malloc(3 * P * sizeof *x),
        *v = malloc(3 * P * sizeof *v), *a = malloc(3 * P * sizeof *a);
  const float g[3] = {1.0f, -2.0f, 0.5f};
  for (int i = 0; i < 3 * P; i++)
    a[i] = g[i % 3];
  msocl_sim *s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER,
                        MSOCL_AUTO);
  ck_assert_int_eq(msocl_sim_read_positions(s, x0), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_set_accelerations(s, a), MSOCL_OK);
  const int n = 100;
  ck_assert_int_eq(msocl_sim_step(s, n), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, x), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, v), MSOCL_OK);
  double mean[3] = {0.0, 0.0, 0.0}, ex = 0.0;
  for (int i = 0; i < 3 * P; i++) {
    const double vn = n * 1e-3 * g[i % 3];
    const double xn = x0[i] + 1e-6 * g[i % 3] * n * (n + 1) / 2.0;
    mean[i % 3] += (v[i] - vn) / P;
    ex = fmax(ex, fabs(x[i] - xn));
  }
  /* the springs' forces cancel in the mean velocity, but not point by
   * point: the moved positions round apart, and stiff springs feel it */
  const double ev = fabs(mean[0]) + fabs(mean[1]) + fabs(mean[2]);
  printf("uniform field: |mean v - n dt a| = %.3g m/s, max |x - analytic| = "
         "%.3g m\n", ev, ex);
  ck_assert_msg(ev <= 1e-5, "velocity off by %g m/s", ev);
  ck_assert_msg(ex <= 1e-5, "position off by %g m", ex);
  msocl_sim_destroy(s);
  free(x0);
  free(x);
  free(v);
  free(a);
  msocl_model_destroy(m);
}
END_TEST

/* A hanging cloth under a varying field, changed mid-run from
 * accelerations to forces, against the double reference; GRID and a
 * renumbered BUFFER (which maps the model's order to its own). */
START_TEST(hanging_vs_reference)
{
  const msocl_integrator ins[3] = {MSOCL_SYMPLECTIC_EULER, MSOCL_VERLET,
                                   MSOCL_RK4};
  msocl_model *m = scene_hanging(N);
  float *f0 = malloc(3 * P * sizeof *f0), *f1 = malloc(3 * P * sizeof *f1);
  varying(f0, 3.0f);
  varying(f1, -0.02f);
  float *p = malloc(3 * P * sizeof *p);
  double *ref = malloc(3 * P * sizeof *ref);
  for (int q = 0; q < 4; q++) {
    const msocl_integrator in = ins[q % 3];
    msocl_sim *s = q < 3 ? sim_of(m, MSOCL_LAYOUT_GRID, in, MSOCL_AUTO)
                         : sim_of(m, MSOCL_LAYOUT_BUFFER, in, MSOCL_ON);
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = 1e-3f;
    o.integrator = in;
    msocl_reference *r = NULL;
    ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_set_accelerations(s, f0), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_set_accelerations(r, f0), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 250), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_step(r, 250), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_set_forces(s, f1), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_set_forces(r, f1), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 250), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_step(r, 250), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_positions(r, ref), MSOCL_OK);
    double e = 0.0, moved = 0.0;
    for (int i = 0; i < 3 * P; i++) {
      e = fmax(e, fabs(p[i] - ref[i]));
      if (i % 3 == 2)
        moved = fmax(moved, fabs(ref[i]));
    }
    printf("field, integrator %d%s: max |device - reference| = %.3g m, "
           "moved %.3g m out of the plane\n",
           (int)in, q == 3 ? " (BUFFER, renumbered)" : "", e, moved);
    ck_assert_msg(e <= 1e-5, "integrator %d: %g m", (int)in, e);
    ck_assert_msg(moved > 0.05, "the field moved the cloth only %g m", moved);
    msocl_reference_destroy(r);
    msocl_sim_destroy(s);
  }
  free(p);
  free(ref);
  free(f0);
  free(f1);
  msocl_model_destroy(m);
}
END_TEST

static void positions_after(const msocl_model *m, msocl_layout layout,
                            const float *f, int forces, float *p)
{
  msocl_sim *s = sim_of(m, layout, MSOCL_SYMPLECTIC_EULER, MSOCL_AUTO);
  if (f)
    ck_assert_int_eq(forces ? msocl_sim_set_forces(s, f)
                            : msocl_sim_set_accelerations(s, f),
                     MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 200), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
  msocl_sim_destroy(s);
}

/* GRID, BUFFER and IMAGE2D keep one result with a field; a force of m a
 * is the acceleration a, to float rounding of the division. */
START_TEST(layouts_and_forces)
{
  msocl_model *m = scene_hanging(N);
  const msocl_layout ls[3] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                              MSOCL_LAYOUT_IMAGE2D};
  float *a = malloc(3 * P * sizeof *a), *f = malloc(3 * P * sizeof *f);
  varying(a, 2.0f);
  const float mass = 0.5f / (float)P; /* scene_hanging's 0.5 kg */
  for (int i = 0; i < 3 * P; i++)
    f[i] = a[i] * mass;
  float *p[4];
  for (int l = 0; l < 4; l++)
    p[l] = malloc(3 * P * sizeof *p[l]);
  for (int l = 0; l < 3; l++)
    positions_after(m, ls[l], a, 0, p[l]);
  for (int l = 1; l < 3; l++)
    ck_assert_msg(memcmp(p[0], p[l], 3 * P * sizeof(float)) == 0,
                  "layout %d differs from GRID (%g m)", (int)ls[l],
                  scene_max_diff(p[0], p[l], 3 * P));
  positions_after(m, MSOCL_LAYOUT_GRID, f, 1, p[3]);
  const double e = scene_max_diff(p[0], p[3], 3 * P);
  printf("forces m a against accelerations a: %.3g m\n", e);
  ck_assert_msg(e <= 1e-6, "forces differ by %g m", e);
  for (int l = 0; l < 4; l++)
    free(p[l]);
  free(a);
  free(f);
  msocl_model_destroy(m);
}
END_TEST

/* A field set and cleared is none, to the bit; pinned points stay put
 * whatever the field. */
START_TEST(cleared_and_pins)
{
  msocl_model *m = scene_hanging(N);
  float *a = malloc(3 * P * sizeof *a), *b = malloc(3 * P * sizeof *b),
        *f = malloc(3 * P * sizeof *f), *x0 = malloc(3 * P * sizeof *x0);
  positions_after(m, MSOCL_LAYOUT_GRID, NULL, 0, a);
  varying(f, 50.0f);
  msocl_sim *s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER,
                        MSOCL_AUTO);
  ck_assert_int_eq(msocl_sim_set_accelerations(s, f), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_set_accelerations(s, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 200), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, b), MSOCL_OK);
  ck_assert(memcmp(a, b, 3 * P * sizeof *a) == 0);
  msocl_sim_destroy(s);
  s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER, MSOCL_AUTO);
  ck_assert_int_eq(msocl_sim_read_positions(s, x0), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_set_accelerations(s, f), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, b), MSOCL_OK);
  const int pins[2] = {0, N - 1}; /* scene_hanging's */
  for (int q = 0; q < 2; q++)
    ck_assert(memcmp(x0 + 3 * pins[q], b + 3 * pins[q], 3 * sizeof(float)) ==
              0);
  ck_assert(memcmp(x0, b, 3 * P * sizeof *b) != 0);
  msocl_sim_destroy(s);
  free(a);
  free(b);
  free(f);
  free(x0);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = scene_hanging(N);
  float *f = calloc(3 * P, sizeof *f);
  ck_assert_int_eq(msocl_sim_set_accelerations(NULL, f),
                   MSOCL_ERR_NULL_HANDLE);
  msocl_sim *s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER,
                        MSOCL_AUTO);
  f[3 * 7 + 1] = NAN;
  ck_assert_int_eq(msocl_sim_set_accelerations(s, f), MSOCL_ERR_NOT_FINITE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "point 7"));
  f[3 * 7 + 1] = INFINITY;
  ck_assert_int_eq(msocl_sim_set_forces(s, f), MSOCL_ERR_NOT_FINITE);
  msocl_reference *r = NULL;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_set_forces(r, f), MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_reference_set_forces(NULL, f), MSOCL_ERR_NULL_HANDLE);
  msocl_reference_destroy(r);
  msocl_sim_destroy(s);
  f[3 * 7 + 1] = 0.0f;
  char spec[256];
  if (scene_cpu_spec(spec, sizeof spec, 2) >= 2) {
    msocl_runtime *two = NULL;
    ck_assert_int_eq(msocl_runtime_create(&two, spec), MSOCL_OK);
    msocl_sim_options_init(&o);
    o.tuning.ndevices = 2;
    ck_assert_int_eq(msocl_sim_create(&s, two, m, &o), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_set_forces(s, f), MSOCL_ERR_BAD_VALUE);
    ck_assert_ptr_nonnull(strstr(msocl_last_error(), "split"));
    msocl_sim_destroy(s);
    msocl_runtime_destroy(two);
  }
  free(f);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_field");
  Suite *su = suite_create("field");
  TCase *tc = tcase_create("field");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, uniform_drift);
  tcase_add_test(tc, hanging_vs_reference);
  tcase_add_test(tc, layouts_and_forces);
  tcase_add_test(tc, cleared_and_pins);
  tcase_add_test(tc, bad_input);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

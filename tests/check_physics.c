/* Analytic checks on the device: a mass on a spring oscillates with period
 * 2 pi sqrt(m/k); pinned points never move; nothing passes through a
 * plane, a sphere or the table top; bad input is refused. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

static msocl_sim *make_sim(const msocl_model *m, float dt)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "sim_create: %s", msocl_last_error());
  return s;
}

/* Point 1 (mass m) hangs on a spring (k, rest 1) from pinned point 0, no
 * gravity, displaced by 0.1 along x. Upward zero crossings of x - rest,
 * interpolated linearly, give the period. */
START_TEST(spring_period)
{
  const float m = 0.1f, k = 10.0f, dt = 1e-4f;
  const double expect = 2.0 * 3.14159265358979323846 * sqrt(m / k);
  msocl_model *mod = NULL;
  msocl_model_create(&mod);
  const float xyz[6] = {0, 0, 0, 1.1f, 0, 0}, mass[2] = {1.0f, m};
  const int ij[2] = {0, 1};
  const float rest = 1.0f;
  msocl_model_add_points(mod, 2, xyz, mass, NULL);
  msocl_model_add_springs(mod, 1, ij, &k, &rest, NULL);
  msocl_model_pin(mod, 0, 1);
  msocl_model_set_gravity(mod, 0, 0, 0);
  msocl_sim *s = make_sim(mod, dt);
  float p[6];
  double prev = 0.1, t = 0.0, first = -1.0, last = -1.0;
  int crossings = 0;
  for (int step = 0; step < (int)(3.5 * expect / dt); step++) {
    ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    t += dt;
    double x = p[3] - 1.0;
    if (prev < 0.0 && x >= 0.0) {
      double tc = t - dt * x / (x - prev);
      if (first < 0.0)
        first = tc;
      last = tc;
      crossings++;
    }
    prev = x;
  }
  ck_assert_int_ge(crossings, 3);
  double period = (last - first) / (crossings - 1);
  printf("spring period %.6f s, analytic 2 pi sqrt(m/k) = %.6f s (%.3f%%)\n",
         period, expect, 100.0 * fabs(period - expect) / expect);
  ck_assert_msg(fabs(period - expect) <= 0.01 * expect,
                "period %.6f s, expected %.6f s", period, expect);
  msocl_sim_destroy(s);
  msocl_model_destroy(mod);
}
END_TEST

START_TEST(pinned_never_move)
{
  msocl_model *m = scene_hanging(16);
  float *p0 = malloc(3 * 256 * sizeof(float)), *p = malloc(3 * 256 * sizeof(float));
  msocl_model_get_positions(m, p0);
  msocl_sim *s = make_sim(m, 1e-3f);
  for (int round = 0; round < 10; round++) {
    ck_assert_int_eq(msocl_sim_step(s, 50), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    ck_assert(memcmp(p, p0, 3 * sizeof(float)) == 0);
    ck_assert(memcmp(p + 3 * 15, p0 + 3 * 15, 3 * sizeof(float)) == 0);
    /* ...while the rest of the cloth does move */
    ck_assert_float_ne(p[3 * 255 + 1], p0[3 * 255 + 1]);
  }
  free(p0);
  free(p);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Worst value of gap() over all points, every `chunk` steps. */
static double worst_gap(msocl_sim *s, int n, int rounds, int chunk,
                        double (*gap)(const float *))
{
  float *p = malloc(3 * (size_t)n * sizeof(float));
  double worst = INFINITY;
  for (int r = 0; r < rounds; r++) {
    ck_assert_int_eq(msocl_sim_step(s, chunk), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    for (int i = 0; i < n; i++) {
      double g = gap(p + 3 * i);
      ck_assert_msg(isfinite(g), "point %d is not finite", i);
      if (g < worst)
        worst = g;
    }
  }
  free(p);
  return worst;
}

/* Allowed penetration: float rounding only (1e-5 of the 1 m cloth). */
#define GAP_TOL (-1e-5)

START_TEST(table_not_crossed)
{
  msocl_model *m = scene_tablecloth(32);
  msocl_sim *s = make_sim(m, scene_tablecloth_dt(32));
  double w = worst_gap(s, 32 * 32, 40, 25, scene_table_gap);
  ck_assert_msg(w >= GAP_TOL, "a point went %g into the table", -w);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

static double sphere_gap(const float *p)
{
  double dy = p[1] + 0.4;
  return sqrt((double)p[0] * p[0] + dy * dy + (double)p[2] * p[2]) - 0.3;
}

static double plane_gap(const float *p)
{
  return p[1] + 0.2; /* free space: y >= -0.2 */
}

/* A cloth thrown down at 30 m/s: 3 cm a step, more than its distance to the
 * colliders, which a position check after the move would miss. */
START_TEST(fast_cloth_sphere_and_plane)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 24;
  const float origin[3] = {-0.5f, 0.0f, -0.5f};
  memcpy(d.origin, origin, sizeof origin);
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  const float c[3] = {0.0f, -0.4f, 0.0f}, up[3] = {0.0f, 2.0f, 0.0f};
  ck_assert_int_eq(msocl_model_add_sphere(m, c, 0.3f, 0.0f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_plane(m, up, -0.4f, 0.5f), MSOCL_OK);
  msocl_sim *s = make_sim(m, 1e-3f);
  float *v = calloc(3 * 24 * 24, sizeof(float));
  for (int i = 0; i < 24 * 24; i++)
    v[3 * i + 1] = -30.0f;
  ck_assert_int_eq(msocl_sim_write_velocities(s, v), MSOCL_OK);
  double ws = worst_gap(s, 24 * 24, 1, 20, sphere_gap);
  double wp = worst_gap(s, 24 * 24, 1, 1, plane_gap);
  ck_assert_msg(ws >= GAP_TOL, "a point went %g into the sphere", -ws);
  ck_assert_msg(wp >= GAP_TOL, "a point went %g through the plane", -wp);
  ws = worst_gap(s, 24 * 24, 20, 25, sphere_gap);
  wp = worst_gap(s, 24 * 24, 1, 1, plane_gap);
  ck_assert_msg(ws >= GAP_TOL, "a point went %g into the sphere", -ws);
  ck_assert_msg(wp >= GAP_TOL, "a point went %g through the plane", -wp);
  free(v);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = scene_hanging(4);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(NULL, rt, m, &o), MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_create(&s, NULL, m, &o), MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_create(&s, rt, NULL, &o), MSOCL_ERR_NULL_HANDLE);
  o.dt = 0.0f;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_DT);
  o.dt = -1e-3f;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_DT);
  o.dt = NAN;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_NOT_FINITE);
  o.dt = 1e-3f;
  o.tuning.device = 7;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_INDEX);
  o.tuning.device = 0;
  o.tuning.layout = (msocl_layout)42;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.tuning.layout = MSOCL_LAYOUT_AUTO;
  ck_assert_ptr_null(s);
  msocl_model *empty = NULL;
  msocl_model_create(&empty);
  ck_assert_int_eq(msocl_sim_create(&s, rt, empty, &o), MSOCL_ERR_EMPTY);
  msocl_model_destroy(empty);

  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  float xyz[3 * 16] = {0};
  ck_assert_int_eq(msocl_sim_step(NULL, 1), MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_step(s, -1), MSOCL_ERR_BAD_COUNT);
  ck_assert_int_eq(msocl_sim_read_positions(s, NULL), MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_read_positions(NULL, xyz), MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_read_normals(NULL, xyz), MSOCL_ERR_NULL_HANDLE);
  xyz[7] = INFINITY;
  ck_assert_int_eq(msocl_sim_write_positions(s, xyz), MSOCL_ERR_NOT_FINITE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "point 2"));
  xyz[7] = NAN;
  ck_assert_int_eq(msocl_sim_write_velocities(s, xyz), MSOCL_ERR_NOT_FINITE);
  msocl_sim_destroy(s);
  msocl_sim_destroy(NULL);
  msocl_model_destroy(m);
}
END_TEST

/* A flat cloth in the x-z plane (u = x, v = z) has normals along
 * u x v = -y or +y depending on winding; all must agree and be unit. */
START_TEST(normals_of_flat_cloth)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 8;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  msocl_sim *s = make_sim(m, 1e-4f);
  float nrm[3 * 64];
  ck_assert_int_eq(msocl_sim_read_normals(s, nrm), MSOCL_OK);
  for (int i = 0; i < 64; i++) {
    ck_assert_float_eq_tol(fabsf(nrm[3 * i + 1]), 1.0f, 1e-6f);
    ck_assert_float_eq(nrm[3 * i + 1], nrm[1]);
  }
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A bumped 21 x 19 cloth (corners on 1 or 2 triangles, edges on 3, the
 * rest on 6; GRID's rows padded): every layout's normals, read from its
 * own planes, agree bit for bit and match the area-weighted normals
 * computed here in double. */
START_TEST(normals_every_layout)
{
  static const msocl_layout layouts[4] = {
      MSOCL_LAYOUT_IMAGE2D, MSOCL_LAYOUT_BUFFER, MSOCL_LAYOUT_GRID,
      MSOCL_LAYOUT_EDGES};
  enum { NX = 21, NY = 19, N = NX * NY };
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = NX;
  d.ny = NY;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  static float xyz[3 * N], nrm[4][3 * N];
  msocl_model_get_positions(m, xyz);
  for (int i = 0; i < N; i++)
    xyz[3 * i + 1] += 0.1f * sinf(7.0f * xyz[3 * i]) *
                      cosf(5.0f * xyz[3 * i + 2]);
  for (int k = 0; k < 4; k++) {
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = 1e-4f;
    o.tuning.layout = layouts[k];
    msocl_sim *s = NULL;
    ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_write_positions(s, xyz), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_normals(s, nrm[k]), MSOCL_OK);
    msocl_sim_destroy(s);
    ck_assert_msg(memcmp(nrm[k], nrm[0], sizeof nrm[0]) == 0,
                  "layout %d's normals differ from IMAGE2D's", (int)k);
  }
  const int *tri = NULL;
  int nt = 0;
  ck_assert_int_eq(msocl_model_triangles(m, &nt, &tri), MSOCL_OK);
  static double want[3 * N];
  memset(want, 0, sizeof want);
  for (int t = 0; t < nt; t++) {
    const float *a = xyz + 3 * tri[3 * t], *b = xyz + 3 * tri[3 * t + 1],
                *c = xyz + 3 * tri[3 * t + 2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                 v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                         u[0] * v[1] - u[1] * v[0]};
    for (int q = 0; q < 3; q++)
      for (int e = 0; e < 3; e++)
        want[3 * tri[3 * t + q] + e] += w[e];
  }
  for (int i = 0; i < N; i++) {
    const double *w = want + 3 * i;
    const double len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int e = 0; e < 3; e++)
      ck_assert_msg(fabs(nrm[0][3 * i + e] - w[e] / len) < 1e-5,
                    "point %d coordinate %d: %.9g, want %.9g", i, e,
                    (double)nrm[0][3 * i + e], w[e] / len);
  }
  msocl_model_destroy(m);
}
END_TEST

/* Air resistance as the second seed applies it: each step multiplies the
 * velocity by the factor, so a free point coasting without gravity has
 * v_n = v_0 f^n. */
START_TEST(air_resistance)
{
  msocl_model *m = NULL;
  msocl_model_create(&m);
  const float xyz[3] = {0, 0, 0}, mass = 1.0f;
  msocl_model_add_points(m, 1, xyz, &mass, NULL);
  msocl_model_set_gravity(m, 0, 0, 0);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, 0.99f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, 0.0f), MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, 1.5f), MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, NAN), MSOCL_ERR_NOT_FINITE);
  msocl_sim *s = make_sim(m, 1e-3f);
  const float v0[3] = {1.0f, 0.0f, 0.0f};
  ck_assert_int_eq(msocl_sim_write_velocities(s, v0), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
  float v[3];
  msocl_sim_read_velocities(s, v);
  ck_assert_float_eq_tol(v[0], powf(0.99f, 100.0f), 1e-5f);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_physics");
  Suite *su = suite_create("physics");
  TCase *tc = tcase_create("physics");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, spring_period);
  tcase_add_test(tc, pinned_never_move);
  tcase_add_test(tc, table_not_crossed);
  tcase_add_test(tc, fast_cloth_sphere_and_plane);
  tcase_add_test(tc, bad_input);
  tcase_add_test(tc, normals_of_flat_cloth);
  tcase_add_test(tc, normals_every_layout);
  tcase_add_test(tc, air_resistance);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

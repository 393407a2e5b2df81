/* Capsule and oriented-box colliders: a tablecloth falling onto each
 * leaves no point inside it at any checked step; the device against the
 * double reference; GRID, BUFFER and IMAGE2D bitwise with them; bad input
 * refused. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

enum { N = 24, CHUNK = 25, STEPS = 600 };

static const float cap_a[3] = {-0.3f, 0.0f, 0.05f},
                   cap_b[3] = {0.3f, 0.0f, -0.05f};
static const float cap_r = 0.03f;
/* 30 degrees about y, then 10 about x: the top face tilted */
static const float box_c[3] = {0.0f, 0.02f, 0.0f},
                   box_q[4] = {0.0868241f, 0.2578799f, -0.0225576f,
                               0.9617692f},
                   box_h[3] = {0.15f, 0.02f, 0.2f};

/* The test's own gaps, in double (not the library's formulas). */
static double capsule_gap(const float *p)
{
  double e[3], a[3], ee = 0, ae = 0;
  for (int c = 0; c < 3; c++) {
    e[c] = cap_b[c] - cap_a[c];
    a[c] = p[c] - cap_a[c];
    ee += e[c] * e[c];
    ae += a[c] * e[c];
  }
  double t = fmin(fmax(ae / ee, 0.0), 1.0), d = 0;
  for (int c = 0; c < 3; c++)
    d += (a[c] - t * e[c]) * (a[c] - t * e[c]);
  return sqrt(d) - cap_r;
}

/* max over the box's face planes of the distance outside them: < 0 inside */
static double box_gap(const float *p)
{
  double x = box_q[0], y = box_q[1], z = box_q[2], w = box_q[3];
  /* the rotation matrix's columns are the box's axes */
  double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w),
                     2 * (x * z + y * w)},
                    {2 * (x * y + z * w), 1 - 2 * (x * x + z * z),
                     2 * (y * z - x * w)},
                    {2 * (x * z - y * w), 2 * (y * z + x * w),
                     1 - 2 * (x * x + y * y)}};
  double g = -INFINITY;
  for (int a = 0; a < 3; a++) {
    double l = 0;
    for (int c = 0; c < 3; c++)
      l += R[c][a] * (p[c] - box_c[c]);
    g = fmax(g, fabs(l) - box_h[a]);
  }
  return g;
}

static msocl_model *scene(int kind)
{
  msocl_model *m = scene_tablecloth(N);
  ck_assert_ptr_nonnull(m);
  if (kind == 0)
    ck_assert_int_eq(msocl_model_add_capsule(m, cap_a, cap_b, cap_r, 0.5f),
                     MSOCL_OK);
  else
    ck_assert_int_eq(msocl_model_add_box(m, box_c, box_q, box_h, 1.0f),
                     MSOCL_OK);
  return m;
}

static msocl_sim_options options(msocl_layout layout)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = scene_tablecloth_dt(N);
  /* symplectic Euler: GRID then runs planes_rows.c where it applies */
  o.integrator = MSOCL_SYMPLECTIC_EULER;
  o.tuning.layout = layout;
  return o;
}

/* Every CHUNK steps: no point deeper than 1 mm (a third of the capsule's
 * radius, half the box's thinnest half extent) in the shape, and some
 * point within 2 mm of it (the cloth reached it). */
START_TEST(nothing_inside)
{
  for (int kind = 0; kind < 2; kind++) {
    msocl_model *m = scene(kind);
    msocl_sim_options o = options(MSOCL_LAYOUT_GRID);
    msocl_sim *s = NULL;
    ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK, "%s",
                  msocl_last_error());
    float *p = malloc(3 * N * N * sizeof *p);
    double deepest = INFINITY;
    for (int k = 0; k < STEPS / CHUNK; k++) {
      ck_assert_int_eq(msocl_sim_step(s, CHUNK), MSOCL_OK);
      ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
      for (int i = 0; i < N * N; i++) {
        double g = kind == 0 ? capsule_gap(p + 3 * i) : box_gap(p + 3 * i);
        deepest = fmin(deepest, g);
      }
    }
    printf("%s: deepest point %.3g m (outside > 0)\n",
           kind == 0 ? "capsule" : "box", deepest);
    ck_assert_msg(deepest >= -1e-3, "a point %.3g m inside", -deepest);
    ck_assert_msg(deepest <= 2e-3, "the cloth never reached it (%.3g m)",
                  deepest);
    free(p);
    msocl_sim_destroy(s);
    msocl_model_destroy(m);
  }
}
END_TEST

/* Device (GRID) against the double reference after 300 steps:
 * within 2e-3 m (the box: its edges switch the normal), the contacts' float rounding amplified by the drape. */
START_TEST(vs_reference)
{
  for (int kind = 0; kind < 2; kind++) {
    msocl_model *m = scene(kind);
    msocl_sim_options o = options(MSOCL_LAYOUT_GRID);
    msocl_sim *s = NULL;
    ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK, "%s",
                  msocl_last_error());
    msocl_reference *r = NULL;
    ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 300), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_step(r, 300), MSOCL_OK);
    float *p = malloc(3 * N * N * sizeof *p), *q = malloc(3 * N * N * sizeof *q);
    double *qd = malloc(3 * N * N * sizeof *qd);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_positions(r, qd), MSOCL_OK);
    for (int i = 0; i < 3 * N * N; i++)
      q[i] = (float)qd[i];
    free(qd);
    double d = scene_max_diff(p, q, 3 * N * N), g = INFINITY;
    for (int i = 0; i < N * N; i++)
      g = fmin(g, kind == 0 ? capsule_gap(q + 3 * i) : box_gap(q + 3 * i));
    printf("%s: max |device - reference| = %.3g m, reference deepest %.3g m\n",
           kind == 0 ? "capsule" : "box", d, g);
    ck_assert_msg(d <= 2e-3, "device and reference differ by %g m", d);
    ck_assert_msg(g <= 2e-3, "the reference's cloth never reached it");
    free(p);
    free(q);
    msocl_reference_destroy(r);
    msocl_sim_destroy(s);
    msocl_model_destroy(m);
  }
}
END_TEST

START_TEST(layouts_bitwise)
{
  const msocl_layout ls[3] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                              MSOCL_LAYOUT_IMAGE2D};
  for (int kind = 0; kind < 2; kind++) {
    msocl_model *m = scene(kind);
    float *p[3];
    for (int l = 0; l < 3; l++) {
      msocl_sim_options o = options(ls[l]);
      msocl_sim *s = NULL;
      ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK, "%s",
                    msocl_last_error());
      ck_assert_int_eq(msocl_sim_step(s, 200), MSOCL_OK);
      p[l] = malloc(3 * N * N * sizeof *p[l]);
      ck_assert_int_eq(msocl_sim_read_positions(s, p[l]), MSOCL_OK);
      msocl_sim_destroy(s);
    }
    for (int l = 1; l < 3; l++)
      ck_assert_msg(memcmp(p[0], p[l], 3 * N * N * sizeof(float)) == 0,
                    "kind %d: layout %d differs from GRID (%g m)", kind, l,
                    scene_max_diff(p[0], p[l], 3 * N * N));
    for (int l = 0; l < 3; l++)
      free(p[l]);
    msocl_model_destroy(m);
  }
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = scene_tablecloth(4);
  const float nan3[3] = {NAN, 0, 0}, inf3[3] = {0, INFINITY, 0},
              zero_q[4] = {0, 0, 0, 0}, nan_q[4] = {0, 0, 0, NAN},
              flat[3] = {0.1f, 0.0f, 0.1f}, neg[3] = {0.1f, 0.1f, -1.0f};
  ck_assert_int_eq(msocl_model_add_capsule(m, nan3, cap_b, 0.1f, 0.5f),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_model_add_capsule(m, cap_a, inf3, 0.1f, 0.5f),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_model_add_capsule(m, cap_a, cap_b, 0.0f, 0.5f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_capsule(m, cap_a, cap_b, -1.0f, 0.5f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_capsule(m, cap_a, cap_b, NAN, 0.5f),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_model_add_capsule(m, cap_a, cap_b, 0.1f, 2.0f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_capsule(m, NULL, cap_b, 0.1f, 0.5f),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_model_add_box(m, nan3, box_q, box_h, 0.5f),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_model_add_box(m, box_c, nan_q, box_h, 0.5f),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_model_add_box(m, box_c, zero_q, box_h, 0.5f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_box(m, box_c, box_q, flat, 0.5f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_box(m, box_c, box_q, neg, 0.5f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_box(m, box_c, box_q, inf3, 0.5f),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_model_add_box(NULL, box_c, box_q, box_h, 0.5f),
                   MSOCL_ERR_NULL_HANDLE);
  /* nothing was added: the model still builds as before */
  ck_assert_int_eq(msocl_model_validate(m), MSOCL_OK);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_colliders_live");
  Suite *su = suite_create("colliders_live");
  TCase *tc = tcase_create("colliders_live");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, nothing_inside);
  tcase_add_test(tc, vs_reference);
  tcase_add_test(tc, layouts_bitwise);
  tcase_add_test(tc, bad_input);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

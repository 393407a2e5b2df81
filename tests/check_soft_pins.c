/* Soft pins: a free plate held by soft pins offset from it swings as the
 * discrete oscillator symplectic Euler makes of it (computed here in
 * double); anchors moving over a call of k steps equal k one-step calls,
 * bitwise, and the double reference; a hanging cloth's soft-pinned corners
 * dragged along against the reference; the layouts bitwise; bad input
 * refused. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

enum { N = 16, P = N * N };

static msocl_sim *sim_in(const msocl_model *m, float dt, msocl_layout l)
{
  return scene_sim(m, MSOCL_SYMPLECTIC_EULER, dt, l, -1);
}

static msocl_sim *sim_of(const msocl_model *m, float dt)
{
  return sim_in(m, dt, MSOCL_LAYOUT_AUTO);
}

/* A free plate without gravity, every point soft-pinned d away from
 * where it rests: its springs stay at rest, and each point is the
 * oscillator v += dt w^2 (a - x), x += dt v. */
START_TEST(plate_oscillates)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = N;
  d.point_mass = 0.5f / P;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_gravity(m, 0.0f, 0.0f, 0.0f), MSOCL_OK);
  float *x0 = malloc(3 * P * sizeof *x0), *a = malloc(3 * P * sizeof *a),
        *x = malloc(3 * P * sizeof *x);
  int *idx = malloc(P * sizeof *idx);
  ck_assert_int_eq(msocl_model_get_positions(m, x0), MSOCL_OK);
  const float off = 0.01f, k = 2.0f, dt = 1e-3f;
  for (int i = 0; i < P; i++) {
    idx[i] = i;
    for (int c = 0; c < 3; c++)
      a[3 * i + c] = x0[3 * i + c] + (c == 0 ? off : 0.0f);
  }
  msocl_sim *s = sim_of(m, dt);
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, P, idx, a, k), MSOCL_OK);
  const int n = 100; /* w = 32 /s: about half a period */
  ck_assert_int_eq(msocl_sim_step(s, n), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, x), MSOCL_OK);
  /* the same scheme in double, for the displacement along x */
  const double w2 = k / (0.5 / P);
  double u = 0.0, v = 0.0;
  for (int q = 0; q < n; q++) {
    v += dt * w2 * (off - u);
    u += dt * v;
  }
  double e = 0.0;
  for (int i = 0; i < P; i++)
    e = fmax(e, fabs((x[3 * i] - x0[3 * i]) - u));
  printf("soft-pinned plate: x offset %.6f m, the oscillator's %.6f m, "
         "max difference %.3g m\n", x[0] - x0[0], u, e);
  ck_assert_msg(fabs(u) > 1e-3, "the oscillator hardly moved");
  ck_assert_msg(e <= 1e-6, "%g m from the oscillator", e);
  msocl_sim_destroy(s);
  free(x0);
  free(a);
  free(x);
  free(idx);
  msocl_model_destroy(m);
}
END_TEST

/* The hanging cloth's bottom corners soft-pinned and dragged sideways:
 * frames of k steps against k one-step calls (bitwise) and against the
 * reference. */
START_TEST(dragged_corners)
{
  msocl_model *m = scene_hanging(N);
  float x0[3 * P];
  ck_assert_int_eq(msocl_model_get_positions(m, x0), MSOCL_OK);
  const int idx[2] = {N * (N - 1), P - 1};
  const float dt = 1e-3f, k = 5.0f;
  enum { FRAMES = 6, K = 20 };
  float *p[2];
  for (int mode = 0; mode < 2; mode++) {
    msocl_sim *s = sim_of(m, dt);
    float a[6];
    for (int q = 0; q < 2; q++)
      memcpy(a + 3 * q, x0 + 3 * idx[q], 3 * sizeof(float));
    ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, k), MSOCL_OK);
    for (int f = 1; f <= FRAMES; f++) {
      if (mode == 0) { /* a frame of K steps, the anchors at its end */
        for (int q = 0; q < 2; q++)
          a[3 * q + 2] = x0[3 * idx[q] + 2] + 0.05f * (float)f;
        ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, k), MSOCL_OK);
        ck_assert_int_eq(msocl_sim_step(s, K), MSOCL_OK);
      } else { /* K one-step calls, each anchor at j / K of the frame */
        const float z0 = 0.05f * (float)(f - 1), z1 = 0.05f * (float)f;
        for (int j = 1; j <= K; j++) {
          const float t = (float)j / (float)K;
          for (int q = 0; q < 2; q++)
            a[3 * q + 2] = x0[3 * idx[q] + 2] + ((1.0f - t) * z0 + t * z1);
          ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, k),
                           MSOCL_OK);
          ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
        }
      }
    }
    p[mode] = malloc(3 * P * sizeof *p[mode]);
    ck_assert_int_eq(msocl_sim_read_positions(s, p[mode]), MSOCL_OK);
    msocl_sim_destroy(s);
  }
  /* the two paths differ in how each step's anchor is rounded: a frame's
   * (1 - f) from + f to against the test's own blend */
  const double e01 = scene_max_diff(p[0], p[1], 3 * P);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  msocl_reference *r = NULL;
  ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
  float a[6];
  for (int f = 0; f <= FRAMES; f++) {
    for (int q = 0; q < 2; q++) {
      memcpy(a + 3 * q, x0 + 3 * idx[q], 3 * sizeof(float));
      a[3 * q + 2] += 0.05f * (float)f;
    }
    ck_assert_int_eq(msocl_reference_set_soft_pins(r, 2, idx, a, k), MSOCL_OK);
    if (f > 0)
      ck_assert_int_eq(msocl_reference_step(r, K), MSOCL_OK);
  }
  double ref[3 * P], e = 0.0, moved = 0.0;
  ck_assert_int_eq(msocl_reference_positions(r, ref), MSOCL_OK);
  for (int i = 0; i < 3 * P; i++)
    e = fmax(e, fabs(p[0][i] - ref[i]));
  moved = ref[3 * idx[0] + 2] - x0[3 * idx[0] + 2];
  printf("dragged corners: frames against one-step calls %.3g m, against "
         "the reference %.3g m, a corner moved %.3g m\n", e01, e, moved);
  ck_assert_msg(e01 <= 1e-6, "frames and one-step calls differ by %g m", e01);
  ck_assert_msg(e <= 1e-5, "%g m from the reference", e);
  ck_assert_msg(moved > 0.01, "the corner moved only %g m", moved);
  msocl_reference_destroy(r);
  free(p[0]);
  free(p[1]);
  msocl_model_destroy(m);
}
END_TEST

/* GRID, BUFFER and IMAGE2D keep one result with soft pins. */
START_TEST(layouts_bitwise)
{
  msocl_model *m = scene_hanging(N);
  float x0[3 * P];
  ck_assert_int_eq(msocl_model_get_positions(m, x0), MSOCL_OK);
  const int idx[3] = {P - 1, N * (N - 1), P / 2};
  const msocl_layout ls[3] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                              MSOCL_LAYOUT_IMAGE2D};
  float *p[3];
  for (int l = 0; l < 3; l++) {
    msocl_sim *s = sim_in(m, 1e-3f, ls[l]);
    float a[9];
    for (int q = 0; q < 3; q++) {
      memcpy(a + 3 * q, x0 + 3 * idx[q], 3 * sizeof(float));
      a[3 * q] += 0.1f;
    }
    ck_assert_int_eq(msocl_sim_set_soft_pins(s, 3, idx, a, 3.0f), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 50), MSOCL_OK);
    for (int q = 0; q < 3; q++)
      a[3 * q + 2] += 0.2f;
    ck_assert_int_eq(msocl_sim_set_soft_pins(s, 3, idx, a, 3.0f), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 150), MSOCL_OK);
    p[l] = malloc(3 * P * sizeof *p[l]);
    ck_assert_int_eq(msocl_sim_read_positions(s, p[l]), MSOCL_OK);
    msocl_sim_destroy(s);
  }
  for (int l = 1; l < 3; l++)
    ck_assert_msg(memcmp(p[0], p[l], 3 * P * sizeof(float)) == 0,
                  "layout %d differs from GRID (%g m)", (int)ls[l],
                  scene_max_diff(p[0], p[l], 3 * P));
  ck_assert(memcmp(p[0], x0, sizeof x0) != 0);
  for (int l = 0; l < 3; l++)
    free(p[l]);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = scene_hanging(N);
  msocl_sim *s = sim_of(m, 1e-3f);
  float a[6] = {0, 0, 0, 1, 1, 1};
  int idx[2] = {5, 9};
  ck_assert_int_eq(msocl_sim_set_soft_pins(NULL, 2, idx, a, 1.0f),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, NULL, a, 1.0f),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, -1, idx, a, 1.0f),
                   MSOCL_ERR_BAD_COUNT);
  idx[1] = P;
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 1.0f),
                   MSOCL_ERR_BAD_INDEX);
  idx[1] = 5;
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 1.0f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "twice"));
  idx[1] = 0; /* scene_hanging pins it */
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 1.0f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "pinned"));
  idx[1] = 9;
  a[4] = NAN;
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 1.0f),
                   MSOCL_ERR_NOT_FINITE);
  a[4] = 1.0f;
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 0.0f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, INFINITY),
                   MSOCL_ERR_NOT_FINITE);
  /* k dt^2 / m = 1e7 x 1e-6 x 512 > 1 */
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 1e7f),
                   MSOCL_ERR_UNSTABLE);
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 1.0f), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_set_soft_pins(s, 0, NULL, NULL, 0.0f), MSOCL_OK);
  msocl_sim_destroy(s);
  char spec[256];
  if (scene_cpu_spec(spec, sizeof spec, 2) >= 2) {
    msocl_runtime *two = NULL;
    ck_assert_int_eq(msocl_runtime_create(&two, spec), MSOCL_OK);
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.tuning.ndevices = 2;
    ck_assert_int_eq(msocl_sim_create(&s, two, m, &o), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_set_soft_pins(s, 2, idx, a, 1.0f),
                     MSOCL_ERR_BAD_VALUE);
    ck_assert_ptr_nonnull(strstr(msocl_last_error(), "split"));
    /* clearing them is no soft pin: as set_wind(NULL) there */
    ck_assert_int_eq(msocl_sim_set_soft_pins(s, 0, NULL, NULL, 0.0f),
                     MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 10), MSOCL_OK);
    msocl_sim_destroy(s);
    msocl_runtime_destroy(two);
  }
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_soft_pins");
  Suite *su = suite_create("soft_pins");
  TCase *tc = tcase_create("soft_pins");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, plate_oscillates);
  tcase_add_test(tc, dragged_corners);
  tcase_add_test(tc, layouts_bitwise);
  tcase_add_test(tc, bad_input);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

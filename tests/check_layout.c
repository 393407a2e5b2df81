/* The gather layouts (IMAGE2D, BUFFER, GRID): bitwise-equal results,
 * degree limits, and what GRID needs. */
#include "engine/engine.h" /* msocl__pl_wide_mode */
#include "layout.h"        /* msocl__image_dims */
#include "scenes.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

/* Runs `steps` steps of a model on one layout; returns positions and
 * velocities (caller frees). */
static void run(const msocl_model *m, msocl_layout layout, float dt,
                int steps, float **pos, float **vel)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.tuning.layout = layout;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "sim_create: %s", msocl_last_error());
  msocl_layout got;
  ck_assert_int_eq(msocl_sim_layout(s, &got), MSOCL_OK);
  ck_assert_int_eq(got, layout);
  int n;
  msocl_sim_point_count(s, &n);
  ck_assert_int_eq(msocl_sim_step(s, steps), MSOCL_OK);
  *pos = malloc(3 * (size_t)n * sizeof(float));
  *vel = malloc(3 * (size_t)n * sizeof(float));
  ck_assert_int_eq(msocl_sim_read_positions(s, *pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, *vel), MSOCL_OK);
  msocl_sim_destroy(s);
}

/* IMAGE2D, BUFFER and GRID (the models here are cloth grids) after
 * `steps` steps: bit for bit the same positions and velocities. */
static void compare_layouts(const msocl_model *m, float dt, int steps)
{
  int n;
  msocl_model_point_count(m, &n);
  const size_t bytes = 3 * (size_t)n * sizeof(float);
  float *p[3], *v[3], *p0 = malloc(bytes);
  const msocl_layout lay[3] = {MSOCL_LAYOUT_BUFFER, MSOCL_LAYOUT_IMAGE2D,
                               MSOCL_LAYOUT_GRID};
  const char *names[3] = {"BUFFER", "IMAGE2D", "GRID"};
  msocl_model_get_positions(m, p0);
  for (int q = 0; q < 3; q++)
    run(m, lay[q], dt, steps, &p[q], &v[q]);
  /* The scene must actually have moved, or equality proves nothing. */
  ck_assert_double_gt(scene_max_diff(p0, p[0], 3 * n), 1e-3);
  for (int q = 1; q < 3; q++) {
    ck_assert_msg(memcmp(p[q], p[0], bytes) == 0,
                  "%s positions differ from BUFFER: max %g", names[q],
                  scene_max_diff(p[q], p[0], 3 * n));
    ck_assert_msg(memcmp(v[q], v[0], bytes) == 0,
                  "%s velocities differ from BUFFER: max %g", names[q],
                  scene_max_diff(v[q], v[0], 3 * n));
  }
  for (int q = 0; q < 3; q++) {
    free(p[q]);
    free(v[q]);
  }
  free(p0);
}

START_TEST(tablecloth_bitwise)
{
  msocl_model *m = scene_tablecloth(32);
  ck_assert_ptr_nonnull(m);
  compare_layouts(m, scene_tablecloth_dt(32), 500);
  msocl_model_destroy(m);
}
END_TEST

/* Dashpots, pins and a non-square point count (33 x 29) exercise the damping
 * slots and the texture's padding. */
START_TEST(damped_pinned_bitwise)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = 33;
  d.ny = 29;
  d.damping = 1e-3f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  msocl_model_pin(m, 0, 1);
  msocl_model_pin(m, 32, 1);
  const float c[3] = {0.5f, -0.4f, 0.5f};
  msocl_model_add_sphere(m, c, 0.3f, 0.0f);
  compare_layouts(m, 2e-4f, 500);
  msocl_model_destroy(m);
}
END_TEST

/* A star: one centre with 17 springs, more than the texture's 16 slots. */
START_TEST(degree_limit)
{
  msocl_model *m = NULL;
  msocl_model_create(&m);
  float xyz[3 * 18] = {0}, mass[18];
  int ij[2 * 17];
  for (int i = 0; i < 18; i++) {
    mass[i] = 1.0f;
    xyz[3 * i] = (float)i;
  }
  for (int s = 0; s < 17; s++) {
    ij[2 * s] = 0;
    ij[2 * s + 1] = s + 1;
  }
  ck_assert_int_eq(msocl_model_add_points(m, 18, xyz, mass, NULL), MSOCL_OK);
  float k[17];
  for (int s = 0; s < 17; s++)
    k[s] = 1.0f;
  ck_assert_int_eq(msocl_model_add_springs(m, 17, ij, k, NULL, NULL),
                   MSOCL_OK);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.layout = MSOCL_LAYOUT_IMAGE2D;
  msocl_sim *s = (msocl_sim *)&o; /* must be reset to NULL on failure */
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_DEGREE);
  ck_assert_ptr_null(s);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "point 0 has 17"));
  o.tuning.layout = MSOCL_LAYOUT_BUFFER;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 10), MSOCL_OK);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* GRID needs the grid the builder recorded: a cloth with a spring added
 * afterwards is refused; a general model too. */
START_TEST(grid_needs_a_cloth_grid)
{
  msocl_model *m = scene_tablecloth(8);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_layout l;
  msocl_sim_layout(s, &l);
  ck_assert_int_eq(l, MSOCL_LAYOUT_GRID);
  msocl_sim_destroy(s);
  const int ij[2] = {0, 63};
  const float k = 1.0f;
  ck_assert_int_eq(msocl_model_add_springs(m, 1, ij, &k, NULL, NULL), MSOCL_OK);
  s = (msocl_sim *)&o;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "GRID"));
  msocl_model_destroy(m);
  /* a point added: GRID would never step it */
  m = scene_tablecloth(8);
  const float xyz[3] = {0.0f, 0.5f, 0.0f}, mass = 0.01f;
  ck_assert_int_eq(msocl_model_add_points(m, 1, xyz, &mass, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "points"));
  o.tuning.layout = MSOCL_LAYOUT_AUTO;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_layout got;
  msocl_sim_layout(s, &got);
  ck_assert_int_eq(got, MSOCL_LAYOUT_BUFFER);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* BUFFER's wide kernels (with the float4 gather copy and the skip of
 * free slots) and its scalar ones give the same bits, whichever the CPU
 * takes by default: a solid (a hub that spills, 7 springs a surface point
 * in a table of 8 slots) and a damped cloth, every integrator, symplectic
 * Euler both as two passes and fused (AUTO's choice on a CPU's BUFFER). */
START_TEST(wide_equals_scalar)
{
  msocl_solid_desc sd;
  msocl_solid_desc_init(&sd);
  sd.subdivisions = 3;
  msocl_model *ms[2] = {NULL, NULL};
  ck_assert_int_eq(msocl_model_solid(&ms[0], &sd), MSOCL_OK);
  const float up[3] = {0.0f, 1.0f, 0.0f};
  msocl_model_add_plane(ms[0], up, -0.12f, 0.5f);
  msocl_cloth_desc cd;
  msocl_cloth_desc_init(&cd);
  cd.nx = 21;
  cd.ny = 17;
  cd.damping = 1e-3f;
  ck_assert_int_eq(msocl_model_cloth_grid(&ms[1], &cd), MSOCL_OK);
  msocl_model_pin(ms[1], 0, 1);
  for (int k = 0; k < 2; k++) {
    int n;
    msocl_model_point_count(ms[k], &n);
    const size_t bytes = 3 * (size_t)n * sizeof(float);
    float dt = 1e-4f;
    msocl_safe_dt(ms[k], MSOCL_SYMPLECTIC_EULER, &dt);
    /* in == -1: symplectic Euler's two passes */
    for (int in = -1; in <= MSOCL_IMPLICIT_EULER; in++) {
      float *p[2], *v[2];
      for (int q = 0; q < 2; q++) {
        msocl__pl_wide_mode(q ? -1 : 1);
        msocl_sim_options o;
        msocl_sim_options_init(&o);
        o.dt = 0.5f * dt;
        o.integrator = in < 0 ? MSOCL_SYMPLECTIC_EULER : (msocl_integrator)in;
        o.tuning.fused = in < 0 ? MSOCL_OFF : MSOCL_AUTO;
        o.tuning.layout = MSOCL_LAYOUT_BUFFER;
        msocl_sim *s = NULL;
        ck_assert_int_eq(msocl_sim_create(&s, rt, ms[k], &o), MSOCL_OK);
        ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
        p[q] = malloc(bytes);
        v[q] = malloc(bytes);
        msocl_sim_read_positions(s, p[q]);
        msocl_sim_read_velocities(s, v[q]);
        msocl_sim_destroy(s);
      }
      msocl__pl_wide_mode(0);
      ck_assert_msg(memcmp(p[0], p[1], bytes) == 0 &&
                        memcmp(v[0], v[1], bytes) == 0,
                    "model %d, integrator %d: wide and scalar differ by %g m",
                    k, in, scene_max_diff(p[0], p[1], 3 * n));
      for (int q = 0; q < 2; q++) {
        free(p[q]);
        free(v[q]);
      }
    }
    msocl_model_destroy(ms[k]);
  }
}
END_TEST

/* Every integrator sums the same slots in the same order on GRID. */
START_TEST(grid_every_integrator)
{
  msocl_model *m = scene_hanging(12);
  int n = 144;
  for (int in = MSOCL_SYMPLECTIC_EULER; in <= MSOCL_IMPLICIT_EULER; in++) {
    float *p[2];
    for (int q = 0; q < 2; q++) {
      msocl_sim_options o;
      msocl_sim_options_init(&o);
      o.dt = 1e-4f;
      o.integrator = (msocl_integrator)in;
      o.tuning.layout = q ? MSOCL_LAYOUT_GRID : MSOCL_LAYOUT_BUFFER;
      msocl_sim *s = NULL;
      ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
      ck_assert_int_eq(msocl_sim_step(s, 200), MSOCL_OK);
      p[q] = malloc(3 * (size_t)n * sizeof(float));
      msocl_sim_read_positions(s, p[q]);
      msocl_sim_destroy(s);
    }
    ck_assert_msg(memcmp(p[0], p[1], 3 * (size_t)n * sizeof(float)) == 0,
                  "integrator %d: GRID differs from BUFFER by %g", in,
                  scene_max_diff(p[0], p[1], 3 * n));
    free(p[0]);
    free(p[1]);
  }
  msocl_model_destroy(m);
}
END_TEST

/* The texture's W x H: near-square, at most W - 1 unused texels (no
 * power-of-two padding), within the device's limits (4W x 4H). */
START_TEST(texture_dims)
{
  int w, h;
  const int ns[] = {1, 5, 48 * 48, 1000, 1 << 20, 4095 * 4095};
  for (size_t q = 0; q < sizeof ns / sizeof ns[0]; q++) {
    ck_assert_int_eq(msocl__image_dims(ns[q], 65536, 65536, &w, &h), MSOCL_OK);
    ck_assert_int_ge((long long)w * h, ns[q]);
    ck_assert_int_lt((long long)w * h - ns[q], w);
    ck_assert_int_le(abs(w - h), 1 + ns[q] / w / 64);
  }
  ck_assert_int_eq(msocl__image_dims(48 * 48, 65536, 65536, &w, &h), MSOCL_OK);
  ck_assert_int_eq(w, 48); /* the paper padded 48 x 48 to 64 x 64 */
  ck_assert_int_eq(h, 48);
  /* a narrow device: W capped at max_w / 4, H grows */
  ck_assert_int_eq(msocl__image_dims(1000, 64, 8192, &w, &h), MSOCL_OK);
  ck_assert_int_eq(w, 16);
  ck_assert_int_eq(h, 63);
  ck_assert_int_eq(msocl__image_dims(1000, 64, 128, &w, &h),
                   MSOCL_ERR_IMAGE_SIZE);
}
END_TEST

/* The fused kernel does both passes at once: bitwise the two passes'
 * result, on one device and split over two; refused where a pass between
 * them is needed. */
START_TEST(fused_equals_two_passes)
{
  msocl_model *m = scene_tablecloth(24);
  float *p[3];
  int n = 576, parts = 1;
  msocl_runtime *two = NULL;
  if (msocl_runtime_create(&two, "0:0,0:1") == MSOCL_OK)
    parts = 2;
  for (int q = 0; q < 3; q++) {
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = scene_tablecloth_dt(24);
    o.tuning.fused = q > 0 ? MSOCL_ON : MSOCL_OFF;
    o.tuning.ndevices = q == 2 ? parts : 1;
    msocl_sim *s = NULL;
    ck_assert_int_eq(msocl_sim_create(&s, q == 2 && two ? two : rt, m, &o),
                     MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 500), MSOCL_OK);
    p[q] = malloc(3 * (size_t)n * sizeof(float));
    msocl_sim_read_positions(s, p[q]);
    msocl_sim_destroy(s);
  }
  ck_assert(memcmp(p[0], p[1], 3 * (size_t)n * sizeof(float)) == 0);
  ck_assert(memcmp(p[0], p[2], 3 * (size_t)n * sizeof(float)) == 0);
  for (int q = 0; q < 3; q++)
    free(p[q]);
  msocl_runtime_destroy(two);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.fused = MSOCL_ON;
  o.integrator = MSOCL_RK4;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.integrator = MSOCL_SYMPLECTIC_EULER;
  o.strain = MSOCL_STRAIN_VELOCITY;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  msocl_model_destroy(m);
}
END_TEST

/* AUTO: GRID for a cloth grid as the builder made it, BUFFER once a
 * spring is added to it. */
START_TEST(auto_layout)
{
  msocl_model *m = scene_tablecloth(8);
  for (int added = 0; added < 2; added++) {
    if (added) {
      const int ij[2] = {0, 63};
      const float k = 1.0f;
      ck_assert_int_eq(msocl_model_add_springs(m, 1, ij, &k, NULL, NULL),
                       MSOCL_OK);
    }
    msocl_sim *s = NULL;
    ck_assert_int_eq(msocl_sim_create(&s, rt, m, NULL), MSOCL_OK);
    msocl_layout l;
    ck_assert_int_eq(msocl_sim_layout(s, &l), MSOCL_OK);
    ck_assert_int_eq(l, added ? MSOCL_LAYOUT_BUFFER : MSOCL_LAYOUT_GRID);
    msocl_sim_destroy(s);
  }
  msocl_model_destroy(m);
}
END_TEST


int main(void)
{
  scene_require_device("check_layout");
  Suite *su = suite_create("layout");
  TCase *tc = tcase_create("layouts");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, tablecloth_bitwise);
  tcase_add_test(tc, damped_pinned_bitwise);
  tcase_add_test(tc, degree_limit);
  tcase_add_test(tc, auto_layout);
  tcase_add_test(tc, texture_dims);
  tcase_add_test(tc, fused_equals_two_passes);
  tcase_add_test(tc, grid_needs_a_cloth_grid);
  tcase_add_test(tc, grid_every_integrator);
  tcase_add_test(tc, wide_equals_scalar);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

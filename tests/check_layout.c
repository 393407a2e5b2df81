/* IMAGE2D and BUFFER layouts: bitwise-equal results, degree limits, and the
 * texture's shape. */
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
  o.layout = layout;
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

static void compare_layouts(const msocl_model *m, float dt, int steps)
{
  int n;
  msocl_model_point_count(m, &n);
  float *pi, *vi, *pb, *vb, *p0 = malloc(3 * (size_t)n * sizeof(float));
  msocl_model_get_positions(m, p0);
  run(m, MSOCL_LAYOUT_IMAGE2D, dt, steps, &pi, &vi);
  run(m, MSOCL_LAYOUT_BUFFER, dt, steps, &pb, &vb);
  /* The scene must actually have moved, or equality proves nothing. */
  ck_assert_double_gt(scene_max_diff(p0, pb, 3 * n), 1e-3);
  ck_assert_msg(memcmp(pi, pb, 3 * (size_t)n * sizeof(float)) == 0,
                "positions differ: max %g", scene_max_diff(pi, pb, 3 * n));
  ck_assert_msg(memcmp(vi, vb, 3 * (size_t)n * sizeof(float)) == 0,
                "velocities differ: max %g", scene_max_diff(vi, vb, 3 * n));
  free(p0); free(pi); free(vi); free(pb); free(vb);
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
  o.layout = MSOCL_LAYOUT_IMAGE2D;
  msocl_sim *s = (msocl_sim *)&o; /* must be reset to NULL on failure */
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_DEGREE);
  ck_assert_ptr_null(s);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "point 0 has 17"));
  o.layout = MSOCL_LAYOUT_BUFFER;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 10), MSOCL_OK);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(auto_is_buffer_on_cpu)
{
  msocl_model *m = scene_tablecloth(8);
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, NULL), MSOCL_OK);
  msocl_layout l;
  ck_assert_int_eq(msocl_sim_layout(s, &l), MSOCL_OK);
  ck_assert_int_eq(l, MSOCL_LAYOUT_BUFFER);
  msocl_sim_destroy(s);
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
  tcase_add_test(tc, auto_is_buffer_on_cpu);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

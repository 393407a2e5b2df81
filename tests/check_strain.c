/* Strain limiting on the tablecloth: without it a soft cloth draped over
 * the table stretches far past 10%; Provot's position correction and the
 * velocity correction of Vassilev et al. keep every spring within the
 * limit plus a stated tolerance; both agree with the host reference. */
#include "internal.h" /* the model's springs, to measure them */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static msocl_runtime *rt;
static const char *const names[] = {"none", "Provot", "velocity"};

static void setup(void)
{
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
}

static void teardown(void)
{
  msocl_runtime_destroy(rt);
  rt = NULL;
}

/* A 24 x 24 tablecloth ten times softer than scene_tablecloth's. */
static msocl_model *soft_tablecloth(void)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 24;
  const float origin[3] = {-0.5f, 0.05f, -0.5f}, u[3] = {0, 0, 1},
              v[3] = {1, 0, 0};
  for (int c = 0; c < 3; c++) {
    d.origin[c] = origin[c];
    d.u[c] = u[c];
    d.v[c] = v[c];
  }
  d.point_mass = 0.5f / (24 * 24);
  d.k_stretch = 5.0f;
  d.k_shear = d.k_bend = 1.0f;
  d.damping = 0.0f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  const float top[3] = {0, 0, 0};
  msocl_model_add_table(m, top, 0.35f, 0.3f);
  msocl_model_set_viscous_damping(m, 0.5f * d.point_mass);
  return m;
}

/* Largest (length / rest - 1) over every spring of the model. */
static double max_strain(const msocl_model *m, const float *p)
{
  double worst = -1.0;
  for (int s = 0; s < m->ns; s++) {
    const float *a = p + 3 * m->ij[2 * s], *b = p + 3 * m->ij[2 * s + 1];
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double st = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / m->rest[s] - 1.0;
    worst = st > worst ? st : worst;
  }
  return worst;
}

/* The limit is 10%; Jacobi sweeps (10 a step, the default) leave a
 * residue, so the stated tolerance is 2% on top (measured: 0.4% Provot,
 * 1.4% velocity). */
#define LIMIT 0.10
#define TOLERANCE 0.02

START_TEST(draped_within_limit)
{
  msocl_model *m = soft_tablecloth();
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 0.5f * dt;
  o.strain = (msocl_strain)_i;
  o.strain_limit = (float)LIMIT;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  /* 2 s: the cloth lands, drapes over the edge and hangs */
  int steps = (int)(2.0 / o.dt);
  int rc = msocl_sim_step(s, steps);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  float *p = malloc(3 * 24 * 24 * sizeof *p);
  msocl_sim_read_positions(s, p);
  double st = max_strain(m, p);
  printf("strain limiting %s: max strain %.4f after %d steps (%.2f s)\n",
         names[_i], st, steps, steps * (double)o.dt);
  if (_i == MSOCL_STRAIN_NONE)
    ck_assert_double_gt(st, 3 * LIMIT); /* the scene needs limiting */
  else
    ck_assert_double_le(st, LIMIT + TOLERANCE);
  free(p);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Device against reference with each correction, through first contact. */
START_TEST(matches_reference)
{
  msocl_model *m = soft_tablecloth();
  float dt;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 0.5f * dt;
  o.strain = (msocl_strain)_i;
  msocl_sim *s = NULL;
  msocl_reference *r = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 60), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_step(r, 60), MSOCL_OK);
  float p[3 * 24 * 24];
  double q[3 * 24 * 24], worst = 0.0;
  msocl_sim_read_positions(s, p);
  msocl_reference_positions(r, q);
  for (int i = 0; i < 3 * 24 * 24; i++)
    worst = fmax(worst, fabs(p[i] - q[i]));
  printf("strain limiting %s: max |device - reference| %.3g m\n", names[_i],
         worst);
  ck_assert_double_le(worst, 1e-5);
  msocl_sim_destroy(s);
  msocl_reference_destroy(r);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(bad_options)
{
  msocl_model *m = soft_tablecloth();
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  msocl_sim *s = NULL;
  o.strain = MSOCL_STRAIN_VELOCITY;
  o.integrator = MSOCL_RK4; /* its position update is not p + dt v' */
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.integrator = MSOCL_SYMPLECTIC_EULER;
  o.strain_limit = -0.1f;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.strain_limit = 0.1f;
  o.strain_iterations = 0;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_strain");
  Suite *su = suite_create("strain");
  TCase *tc = tcase_create("strain");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_loop_test(tc, draped_within_limit, 0, 3);
  tcase_add_loop_test(tc, matches_reference, 1, 3);
  tcase_add_test(tc, bad_options);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

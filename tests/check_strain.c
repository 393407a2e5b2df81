/* Strain limiting on the tablecloth: without it a soft cloth draped over
 * the table stretches far past 10%; Provot's position correction and the
 * velocity correction of Vassilev et al. keep every spring within the
 * limit plus a stated tolerance; both agree with the host reference; and
 * both stay stable with one sweep a step and near the stable step, with
 * every integrator they run with, where summed corrections blew up. */
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
 * residue, so the stated tolerance is 2% on top (measured: 0.55% Provot,
 * 0.59% velocity). */
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

/* Runs the device and the reference `steps` steps from model m with
 * options o; returns the largest position difference (m). layout: the
 * device run's. */
static double device_minus_reference(const msocl_model *m,
                                     const msocl_sim_options *o, int steps,
                                     msocl_layout *layout)
{
  msocl_sim *s = NULL;
  msocl_reference *r = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, o), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_create(&r, m, o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_layout(s, layout), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, steps), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_step(r, steps), MSOCL_OK);
  float *p = malloc(3 * (size_t)m->n * sizeof *p);
  double *q = malloc(3 * (size_t)m->n * sizeof *q), worst = 0.0;
  ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_positions(r, q), MSOCL_OK);
  for (int i = 0; i < 3 * m->n; i++)
    worst = fmax(worst, fabs(p[i] - q[i]));
  free(p);
  free(q);
  msocl_sim_destroy(s);
  msocl_reference_destroy(r);
  return worst;
}

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
  msocl_layout layout;
  double worst = device_minus_reference(m, &o, 60, &layout);
  printf("strain limiting %s: max |device - reference| %.3g m\n", names[_i],
         worst);
  ck_assert_double_le(worst, 1e-5);
  msocl_model_destroy(m);
}
END_TEST

/* Verlet takes Provot's correction between its drift and its kick, RK4
 * after its step: both as the reference does, on the hanging cloth (no
 * contact, so the two stay close for long), on GRID and on BUFFER. */
START_TEST(verlet_rk4_match_reference)
{
  msocl_model *m = scene_hanging(16);
  float dt;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 0.5f * dt;
  o.integrator = _i & 1 ? MSOCL_RK4 : MSOCL_VERLET;
  o.strain = MSOCL_STRAIN_PROVOT;
  o.strain_iterations = 3;
  o.tuning.layout = _i >> 1 ? MSOCL_LAYOUT_BUFFER : MSOCL_LAYOUT_GRID;
  msocl_layout layout;
  double worst = device_minus_reference(m, &o, 200, &layout);
  ck_assert_int_eq(layout, o.tuning.layout);
  printf("Provot with %s on %s, hanging cloth: max |device - reference| "
         "%.3g m\n",
         _i & 1 ? "RK4" : "Verlet", _i >> 1 ? "BUFFER" : "GRID", worst);
  ck_assert_double_le(worst, 1e-5);
  msocl_model_destroy(m);
}
END_TEST

/* Each point used to move by the sum of what its springs asked; where a
 * structural and a bend spring pull one way that overshoots, and the
 * velocities taking the overshoot up made it grow: with those sums 36 of
 * these 60 runs blew up within 200 steps (every one-sweep run; Verlet
 * with Provot at half the stable step; RK4 with Provot and ten sweeps on
 * the soft tablecloth). Now every run must stay stable (the blow-up check
 * runs every 100 steps) and limit: below 30% strain, and within 5% of
 * the limit with the default ten sweeps (measured at most 13.3%). _i:
 * scene (hanging cloth, soft tablecloth) and step (0.5 or 0.9 of
 * symplectic Euler's stable step). */
START_TEST(stable_with_few_sweeps)
{
  static const struct {
    msocl_strain strain;
    msocl_integrator integrator;
    const char *name;
  } cells[5] = {{MSOCL_STRAIN_PROVOT, MSOCL_SYMPLECTIC_EULER,
                 "Provot, symplectic"},
                {MSOCL_STRAIN_PROVOT, MSOCL_VERLET, "Provot, Verlet"},
                {MSOCL_STRAIN_PROVOT, MSOCL_RK4, "Provot, RK4"},
                {MSOCL_STRAIN_VELOCITY, MSOCL_SYMPLECTIC_EULER,
                 "velocity, symplectic"},
                {MSOCL_STRAIN_VELOCITY, MSOCL_IMPLICIT_EULER,
                 "velocity, implicit"}};
  static const int sweeps[3] = {1, 3, 10};
  msocl_model *m = _i & 1 ? soft_tablecloth() : scene_hanging(16);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  const float frac = _i & 2 ? 0.9f : 0.5f;
  float *p = malloc(3 * (size_t)m->n * sizeof *p);
  for (int c = -1; c < 5; c++)
    for (int w = 0; w < 3; w++) {
      if (c < 0 && w > 0)
        continue;
      msocl_sim_options o;
      msocl_sim_options_init(&o);
      o.dt = frac * dt;
      o.strain = c < 0 ? MSOCL_STRAIN_NONE : cells[c].strain;
      o.integrator = c < 0 ? MSOCL_SYMPLECTIC_EULER : cells[c].integrator;
      o.strain_iterations = sweeps[w];
      msocl_sim *s = NULL;
      ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
      int rc = MSOCL_OK;
      for (int k = 0; k < 3 && rc == MSOCL_OK; k++)
        rc = msocl_sim_step(s, 100);
      char what[128];
      snprintf(what, sizeof what, "%s, %.1f of the stable step, %s, %d sweeps",
               _i & 1 ? "soft tablecloth" : "hanging cloth", frac,
               c < 0 ? "no limit" : cells[c].name, sweeps[w]);
      ck_assert_msg(rc == MSOCL_OK, "%s: %s", what, msocl_last_error());
      ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
      double st = max_strain(m, p);
      printf("%s: max strain %.3f after 300 steps\n", what, st);
      ck_assert_msg(isfinite(st), "%s: strain %g", what, st);
      if (c < 0)
        ck_assert_msg(st > 3 * LIMIT, "%s: the scene needs no limit (%.3f)",
                      what, st);
      else
        ck_assert_msg(st < (w == 2 ? LIMIT + 0.05 : 0.3),
                      "%s: max strain %.3f", what, st);
      msocl_sim_destroy(s);
    }
  free(p);
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
  tcase_add_loop_test(tc, verlet_rk4_match_reference, 0, 4);
  tcase_add_loop_test(tc, stable_with_few_sweeps, 0, 4);
  tcase_add_test(tc, bad_options);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

/* Every integrator on the device: agreement with the double host
 * reference, and convergence order against a much finer double RK4. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static msocl_runtime *rt;
static const char *const names[] = {"symplectic Euler", "explicit Euler",
                                    "Verlet", "RK4", "implicit Euler"};

static void setup(void)
{
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
}

static void teardown(void)
{
  msocl_runtime_destroy(rt);
  rt = NULL;
}

/* Max |device - reference| over positions after `steps`. */
static double vs_reference(const msocl_model *m, const msocl_sim_options *o,
                           int steps)
{
  int n;
  msocl_model_point_count(m, &n);
  msocl_sim *s = NULL;
  msocl_reference *r = NULL;
  int rc = msocl_sim_create(&s, rt, m, o);
  ck_assert_msg(rc == MSOCL_OK, "sim_create: %s", msocl_last_error());
  ck_assert_int_eq(msocl_reference_create(&r, m, o), MSOCL_OK);
  rc = msocl_sim_step(s, steps);
  ck_assert_msg(rc == MSOCL_OK, "step: %s", msocl_last_error());
  ck_assert_int_eq(msocl_reference_step(r, steps), MSOCL_OK);
  float *p = malloc(3 * (size_t)n * sizeof *p);
  double *q = malloc(3 * (size_t)n * sizeof *q);
  msocl_sim_read_positions(s, p);
  msocl_reference_positions(r, q);
  /* the energies, summed on the device and on the host, agree too */
  msocl_energy es, er;
  ck_assert_int_eq(msocl_sim_energy(s, &es), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_energy(r, &er), MSOCL_OK);
  ck_assert_double_eq_tol(es.kinetic, er.kinetic, 1e-4 * fabs(er.total) + 1e-9);
  ck_assert_double_eq_tol(es.spring, er.spring, 1e-4 * fabs(er.total) + 1e-9);
  ck_assert_double_eq_tol(es.gravity, er.gravity, 1e-4 * fabs(er.total));
  double worst = 0.0;
  for (int i = 0; i < 3 * n; i++) {
    double d = fabs(p[i] - q[i]);
    worst = d > worst || isnan(d) ? d : worst;
  }
  free(p);
  free(q);
  msocl_sim_destroy(s);
  msocl_reference_destroy(r);
  return worst;
}

/* The hanging cloth with dashpots and viscous damping, 300 steps of
 * 0.1 ms: the stated tolerance is 1e-5 of the 1 m cloth for every
 * integrator (measured: below 1e-6). */
START_TEST(device_matches_reference)
{
  msocl_model *m = scene_hanging(12);
  msocl_model_set_viscous_damping(m, 1e-3f);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-4f;
  o.cg_tolerance = 1e-6f;
  int in = _i;
  o.integrator = (msocl_integrator)in;
  double e = vs_reference(m, &o, 300);
  printf("%s: max |device - reference| = %.3g m\n", names[in], e);
  ck_assert_msg(e <= 1e-5, "%s: %g", names[in], e);
  msocl_model_destroy(m);
}
END_TEST

/* The small smooth problem: a chain of 4 masses (0.1 kg, springs 100 N/m,
 * 0.1 m) hanging from a pinned point, released from horizontal, swinging
 * for 0.2 s; no contact, no damping. */
static msocl_model *chain(void)
{
  msocl_model *m = NULL;
  msocl_model_create(&m);
  float xyz[15], mass[5];
  int ij[8];
  float k[4], rest[4];
  for (int i = 0; i < 5; i++) {
    xyz[3 * i] = 0.1f * (float)i;
    xyz[3 * i + 1] = 0.0f;
    xyz[3 * i + 2] = 0.02f * (float)i; /* out of plane: a 3D motion */
    mass[i] = 0.1f;
  }
  for (int s = 0; s < 4; s++) {
    ij[2 * s] = s;
    ij[2 * s + 1] = s + 1;
    k[s] = 100.0f;
    rest[s] = 0.1f;
  }
  msocl_model_add_points(m, 5, xyz, mass, NULL);
  msocl_model_add_springs(m, 4, ij, k, rest, NULL);
  msocl_model_pin(m, 0, 1);
  return m;
}

#define T_END 0.2

/* RMS position error at T_END of the device run with step h against
 * `exact` (3 * 5 doubles). */
static double error_at(const msocl_model *m, msocl_integrator in, double h,
                       const double *exact)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = (float)h;
  o.integrator = in;
  o.cg_tolerance = 1e-7f;
  o.check_every = 0;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, (int)lround(T_END / h)), MSOCL_OK);
  float p[15];
  msocl_sim_read_positions(s, p);
  msocl_sim_destroy(s);
  double sum = 0.0;
  for (int i = 0; i < 15; i++)
    sum += (p[i] - exact[i]) * (p[i] - exact[i]);
  return sqrt(sum / 5.0);
}

START_TEST(convergence_order)
{
  /* expected order, and a step pair whose errors stand well above
   * single-precision round-off */
  const double order[5] = {1.0, 1.0, 2.0, 4.0, 1.0};
  const double h[5] = {5e-4, 2.5e-4, 1e-2, 4e-2, 5e-4};
  int in = _i;
  msocl_model *m = chain();
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.integrator = MSOCL_RK4;
  o.dt = 1e-5f;
  msocl_reference *fine = NULL;
  ck_assert_int_eq(msocl_reference_create(&fine, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_step(fine, (int)lround(T_END / 1e-5)),
                   MSOCL_OK);
  double exact[15];
  msocl_reference_positions(fine, exact);
  msocl_reference_destroy(fine);
  /* least-squares slope of log error against log h over h, h/2, h/4:
   * steadier than one ratio where the pair is not yet asymptotic */
  double e[3], sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int q = 0; q < 3; q++) {
    double hq = h[in] / (1 << q);
    e[q] = error_at(m, (msocl_integrator)in, hq, exact);
    double x = log(hq), y = log(e[q]);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
  }
  double p = (3 * sxy - sx * sy) / (3 * sxx - sx * sx);
  printf("%s: error %.3g, %.3g, %.3g m at h = %g, h/2, h/4: order %.2f\n",
         names[in], e[0], e[1], e[2], h[in], p);
  ck_assert_msg(fabs(p - order[in]) <= 0.3, "%s: order %.2f, expected %.0f",
                names[in], p, order[in]);
  msocl_model_destroy(m);
}
END_TEST

/* Implicit Euler whose CG cannot converge within its cap (2 iterations
 * at 10 ms on the hanging cloth): GRID, BUFFER (bit for bit GRID's) and
 * the host reference take every step with the solver's last iterate and
 * return MSOCL_ERR_NO_CONVERGENCE naming the tolerance, the iterations
 * and the residual; the same run with room to converge returns OK. */
static const msocl_layout capped_layouts[2] = {MSOCL_LAYOUT_GRID,
                                               MSOCL_LAYOUT_BUFFER};
static const char *const capped_names[2] = {"GRID", "BUFFER"};

static msocl_sim *capped(const msocl_model *m, msocl_sim_options *o,
                         msocl_layout lay, int cap)
{
  msocl_sim_options_init(o);
  o->dt = 1e-2f;
  o->integrator = MSOCL_IMPLICIT_EULER;
  o->tuning.layout = lay;
  o->cg_max_iterations = cap;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, o);
  ck_assert_msg(rc == MSOCL_OK, "sim_create: %s", msocl_last_error());
  msocl_layout got;
  ck_assert_int_eq(msocl_sim_layout(s, &got), MSOCL_OK);
  ck_assert_int_eq(got, lay);
  return s;
}

static void says(const char *text)
{
  ck_assert_msg(strstr(msocl_last_error(), text), "\"%s\" lacks \"%s\"",
                msocl_last_error(), text);
}

START_TEST(implicit_no_convergence)
{
  const msocl_layout lay = capped_layouts[_i];
  const char *name = capped_names[_i];
  msocl_model *m = scene_hanging(12);
  int n;
  msocl_model_point_count(m, &n);
  msocl_sim_options o;
  float *p0 = malloc(3 * (size_t)n * sizeof *p0),
        *p1 = malloc(3 * (size_t)n * sizeof *p1),
        *p2 = malloc(3 * (size_t)n * sizeof *p2);
  msocl_model_get_positions(m, p0);

  msocl_sim *s = capped(m, &o, lay, 2);
  int rc = msocl_sim_step(s, 5);
  ck_assert_msg(rc == MSOCL_ERR_NO_CONVERGENCE, "got %s: %s",
                msocl_err_name(rc), msocl_last_error());
  printf("%s: %s\n", name, msocl_last_error());
  says("tolerance 1e-05 in 5 of 5 steps");
  says("after 2 iterations, cap 2");
  says("relative residual ");
  int it;
  double res;
  ck_assert_int_eq(msocl_sim_solver_stats(s, &it, &res), MSOCL_OK);
  ck_assert_int_eq(it, 2);
  ck_assert_double_gt(res, 1e-5);
  /* every step taken, from the last iterate: as five calls of one step */
  long long steps;
  ck_assert_int_eq(msocl_sim_step_count(s, &steps), MSOCL_OK);
  ck_assert_int_eq(steps, 5);
  ck_assert_int_eq(msocl_sim_read_positions(s, p1), MSOCL_OK);
  ck_assert_double_gt(scene_max_diff(p0, p1, 3 * n), 1e-4);
  msocl_sim_destroy(s);
  s = capped(m, &o, lay, 2);
  for (int q = 0; q < 5; q++) {
    ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_ERR_NO_CONVERGENCE);
    says("in 1 of 1 steps");
  }
  ck_assert_int_eq(msocl_sim_read_positions(s, p2), MSOCL_OK);
  ck_assert(memcmp(p1, p2, 3 * (size_t)n * sizeof *p1) == 0);
  msocl_sim_destroy(s);
  if (lay == MSOCL_LAYOUT_BUFFER) { /* BUFFER's capped steps are GRID's */
    s = capped(m, &o, MSOCL_LAYOUT_GRID, 2);
    ck_assert_int_eq(msocl_sim_step(s, 5), MSOCL_ERR_NO_CONVERGENCE);
    ck_assert_int_eq(msocl_sim_read_positions(s, p2), MSOCL_OK);
    ck_assert_msg(memcmp(p1, p2, 3 * (size_t)n * sizeof *p1) == 0,
                  "BUFFER differs from GRID by %g",
                  scene_max_diff(p1, p2, 3 * n));
    msocl_sim_destroy(s);
    o.tuning.layout = lay; /* the reference below takes BUFFER's options */
  }

  /* the host reference: the same code, the same state within float's
   * round-off of two CG iterations */
  msocl_reference *r = NULL;
  ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
  rc = msocl_reference_step(r, 5);
  ck_assert_msg(rc == MSOCL_ERR_NO_CONVERGENCE, "reference: got %s: %s",
                msocl_err_name(rc), msocl_last_error());
  says("reference implicit Euler: CG stopped above the tolerance 1e-05 in 5 "
       "of 5 steps");
  says("after 2 iterations, cap 2");
  double *q = malloc(3 * (size_t)n * sizeof *q), worst = 0.0;
  msocl_reference_positions(r, q);
  for (int i = 0; i < 3 * n; i++)
    worst = fmax(worst, fabs(q[i] - p1[i]));
  printf("%s: capped CG, max |device - reference| = %.3g m\n",
         name, worst);
  ck_assert_double_le(worst, 1e-5);
  msocl_reference_destroy(r);
  free(q);

  /* room to converge: OK, and the message of the last failure stays */
  s = capped(m, &o, lay, 200);
  rc = msocl_sim_step(s, 5);
  ck_assert_msg(rc == MSOCL_OK, "got %s: %s", msocl_err_name(rc),
                msocl_last_error());
  ck_assert_int_eq(msocl_sim_solver_stats(s, &it, &res), MSOCL_OK);
  ck_assert_double_le(res, 1e-5);
  ck_assert_int_gt(it, 2);
  msocl_sim_destroy(s);
  free(p0);
  free(p1);
  free(p2);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_integrators");
  Suite *su = suite_create("integrators");
  TCase *tc = tcase_create("integrators");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_loop_test(tc, device_matches_reference, 0, 5);
  tcase_add_loop_test(tc, convergence_order, 0, 5);
  tcase_add_loop_test(tc, implicit_no_convergence, 0, 2);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

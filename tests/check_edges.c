/* The EDGES layout (a work-item per spring, float atomics into force
 * accumulators) against the BUFFER gather: the same physics, summed in a
 * different and scheduling-dependent order, so agreement within rounding
 * rather than bitwise. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define rt scene_rt

/* Max position difference EDGES vs BUFFER after `steps`; also compares
 * the energies the two compute (per-spring and per-point sums). */
static double edges_vs_buffer(const msocl_model *m, float dt, int steps)
{
  int n;
  msocl_model_point_count(m, &n);
  float *p[2];
  msocl_energy e[2];
  const msocl_layout lay[2] = {MSOCL_LAYOUT_EDGES, MSOCL_LAYOUT_BUFFER};
  for (int q = 0; q < 2; q++) {
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = dt;
    o.tuning.layout = lay[q];
    msocl_sim *s = NULL;
    int rc = msocl_sim_create(&s, rt, m, &o);
    ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
    rc = msocl_sim_step(s, steps);
    ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
    p[q] = malloc(3 * (size_t)n * sizeof(float));
    msocl_sim_read_positions(s, p[q]);
    ck_assert_int_eq(msocl_sim_energy(s, &e[q]), MSOCL_OK);
    msocl_sim_destroy(s);
  }
  ck_assert_double_eq_tol(e[0].spring, e[1].spring,
                          1e-3 * fabs(e[1].spring) + 1e-7);
  ck_assert_double_eq_tol(e[0].total, e[1].total, 1e-4 * fabs(e[1].total));
  double d = scene_max_diff(p[0], p[1], 3 * n);
  free(p[0]);
  free(p[1]);
  return d;
}

/* Stated tolerance: 1e-5 of the 1 m cloth after 1000 steps (1 s). */
START_TEST(hanging_cloth)
{
  msocl_model *m = scene_hanging(16);
  double d = edges_vs_buffer(m, 1e-3f, 1000);
  printf("hanging cloth, 1000 steps: max |EDGES - BUFFER| = %.3g m\n", d);
  ck_assert_double_le(d, 1e-5);
  msocl_model_destroy(m);
}
END_TEST

/* With contact, through first touch (as tests/check_accuracy): 1e-4. */
START_TEST(tablecloth)
{
  msocl_model *m = scene_tablecloth(24);
  double d = edges_vs_buffer(m, scene_tablecloth_dt(24), 300);
  printf("tablecloth, 300 steps: max |EDGES - BUFFER| = %.3g m\n", d);
  ck_assert_double_le(d, 1e-4);
  msocl_model_destroy(m);
}
END_TEST

/* Degree 24 (structural + face shear + bend lattice): more than the
 * texture holds, nothing special for a spring list. */
START_TEST(lattice_degree_24)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.nx = d.ny = d.nz = 5;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_lattice(&m, &d), MSOCL_OK);
  const float up[3] = {0, 1, 0};
  msocl_model_add_plane(m, up, 0.0f, 0.5f);
  int deg;
  msocl_model_max_degree(m, &deg);
  ck_assert_int_eq(deg, 24);
  /* 0.3 s: it falls 10 cm and lands (in free fall the springs stay at
   * rest length and both layouts agree trivially) */
  double diff = edges_vs_buffer(m, 1e-4f, 3000);
  printf("jello cube 5^3, 3000 steps: max |EDGES - BUFFER| = %.3g m\n", diff);
  ck_assert_double_le(diff, 1e-5);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(only_symplectic)
{
  msocl_model *m = scene_hanging(4);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.layout = MSOCL_LAYOUT_EDGES;
  msocl_sim *s = NULL;
  for (int in = MSOCL_EXPLICIT_EULER; in <= MSOCL_IMPLICIT_EULER; in++) {
    o.integrator = (msocl_integrator)in;
    ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  }
  o.integrator = MSOCL_SYMPLECTIC_EULER;
  o.strain = MSOCL_STRAIN_PROVOT;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  o.strain = MSOCL_STRAIN_NONE;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_layout l;
  msocl_sim_layout(s, &l);
  ck_assert_int_eq(l, MSOCL_LAYOUT_EDGES);
  float nrm[48];
  ck_assert_int_eq(msocl_sim_read_normals(s, nrm), MSOCL_OK);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_edges");
  Suite *su = suite_create("edges");
  TCase *tc = tcase_create("edges");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, hanging_cloth);
  tcase_add_test(tc, tablecloth);
  tcase_add_test(tc, lattice_degree_24);
  tcase_add_test(tc, only_symplectic);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

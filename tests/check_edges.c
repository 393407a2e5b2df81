/* The EDGES layout (a per-point gather over each
 * point's springs in BUFFER's slot order) against the BUFFER gather: the
 * same physics, within the tolerances below, and since the sums go in the
 * same fixed order, bitwise BUFFER's result - run after
 * run, on whichever device, and equal to BUFFER split over 2 and 3
 * devices (EDGES itself is refused there). */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* Positions and velocities after `steps` of one run on runtime `r`, over
 * `parts` devices. */
static void run(msocl_runtime *r, const msocl_model *m, msocl_layout lay,
                float dt, int steps, int device, int parts, float *pos,
                float *vel)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.tuning.layout = lay;
  o.tuning.device = device;
  o.tuning.ndevices = parts;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, r, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  rc = msocl_sim_step(s, steps);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  ck_assert_int_eq(msocl_sim_read_positions(s, pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, vel), MSOCL_OK);
  msocl_sim_destroy(s);
}

/* State buffers of a model: positions then velocities, 6n floats. */
static float *state(const msocl_model *m, size_t *bytes)
{
  int n;
  msocl_model_point_count(m, &n);
  *bytes = 3 * (size_t)n * sizeof(float);
  float *b = malloc(2 * *bytes);
  ck_assert_ptr_nonnull(b);
  return b;
}

static void same_bits(const float *a, const float *b, size_t bytes,
                      const char *what)
{
  const int n3 = (int)(bytes / sizeof(float));
  ck_assert_msg(memcmp(a, b, 2 * bytes) == 0,
                "%s: positions differ by %g, velocities by %g", what,
                scene_max_diff(a, b, n3), scene_max_diff(a + n3, b + n3, n3));
}

/* The three scenes above (damped hanging cloth, tablecloth in contact,
 * degree-24 lattice) and the soft ball, whose centre's 162 springs pass
 * the table's width (the per-point list past it): bitwise BUFFER's
 * positions and velocities. The old atomic scatter summed in another order
 * and missed by 1e-7..1e-6. */
START_TEST(bitwise_buffer)
{
  msocl_lattice_desc ld;
  msocl_lattice_desc_init(&ld);
  ld.nx = ld.ny = ld.nz = 5;
  msocl_solid_desc sd;
  msocl_solid_desc_init(&sd);
  msocl_model *m[4] = {scene_hanging(16), scene_tablecloth(24), NULL, NULL};
  ck_assert_int_eq(msocl_model_lattice(&m[2], &ld), MSOCL_OK);
  ck_assert_int_eq(msocl_model_solid(&m[3], &sd), MSOCL_OK);
  const float up[3] = {0, 1, 0};
  msocl_model_add_plane(m[2], up, 0.0f, 0.5f);
  msocl_model_add_plane(m[3], up, 0.0f, 0.5f);
  const float dt[4] = {1e-3f, scene_tablecloth_dt(24), 1e-4f, 1e-4f};
  const int steps[4] = {1000, 300, 3000, 4000}; /* the ball lands */
  const char *what[4] = {"hanging cloth", "tablecloth", "jello cube",
                         "soft ball"};
  for (int q = 0; q < 4; q++) {
    size_t bytes;
    float *e = state(m[q], &bytes), *b = state(m[q], &bytes);
    const int n3 = (int)(bytes / sizeof(float));
    run(rt, m[q], MSOCL_LAYOUT_EDGES, dt[q], steps[q], 0, 1, e, e + n3);
    run(rt, m[q], MSOCL_LAYOUT_BUFFER, dt[q], steps[q], 0, 1, b, b + n3);
    same_bits(e, b, bytes, what[q]);
    free(e);
    free(b);
    msocl_model_destroy(m[q]);
  }
}
END_TEST

/* Spring values in every entry (options.classes 0) rather than a byte
 * naming their class: the same bits. */
START_TEST(values)
{
  msocl_model *m = scene_hanging(16);
  size_t bytes;
  float *a = state(m, &bytes), *b = state(m, &bytes);
  const int n3 = (int)(bytes / sizeof(float));
  run(rt, m, MSOCL_LAYOUT_BUFFER, 1e-3f, 1000, 0, 1, b, b + n3);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-3f;
  o.tuning.layout = MSOCL_LAYOUT_EDGES;
  o.tuning.classes = MSOCL_OFF;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 1000), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, a), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, a + n3), MSOCL_OK);
  msocl_energy e;
  ck_assert_int_eq(msocl_sim_energy(s, &e), MSOCL_OK);
  ck_assert(e.spring > 0.0);
  msocl_sim_destroy(s);
  same_bits(a, b, bytes, "EDGES with values");
  free(a);
  free(b);
  msocl_model_destroy(m);
}
END_TEST

/* Two runs, bitwise the same. The old atomic scatter could pass this by
 * luck (2 cores, few conflicting adds at a time), so bitwise_buffer is
 * the case that shows the fixed order. */
START_TEST(repeatable)
{
  msocl_model *m = scene_tablecloth(48);
  size_t bytes;
  float *a = state(m, &bytes), *b = state(m, &bytes);
  const int n3 = (int)(bytes / sizeof(float));
  const float dt = scene_tablecloth_dt(48);
  run(rt, m, MSOCL_LAYOUT_EDGES, dt, 300, 0, 1, a, a + n3);
  run(rt, m, MSOCL_LAYOUT_EDGES, dt, 300, 0, 1, b, b + n3);
  same_bits(a, b, bytes, "EDGES run twice");
  free(a);
  free(b);
  msocl_model_destroy(m);
}
END_TEST

/* On each of up to three PoCL devices, bitwise one another and BUFFER
 * split over 2 and 3 devices (bitwise one device: check_multidevice);
 * EDGES asked to split is refused with a message naming BUFFER. */
START_TEST(devices)
{
  char spec[256];
  const int ndev = scene_cpu_spec(spec, sizeof spec, 3);
  if (ndev < 2) {
    printf("devices: SKIP: needs two CPU devices (POCL_DEVICES=\"pthread "
           "pthread pthread\"), found %d\n", ndev);
    return;
  }
  msocl_runtime *r = NULL;
  ck_assert_int_eq(msocl_runtime_create(&r, spec), MSOCL_OK);
  msocl_model *m = scene_tablecloth(24);
  size_t bytes;
  float *one = state(m, &bytes), *other = state(m, &bytes);
  const int n3 = (int)(bytes / sizeof(float));
  const float dt = scene_tablecloth_dt(24);
  run(r, m, MSOCL_LAYOUT_EDGES, dt, 300, 0, 1, one, one + n3);
  for (int d = 1; d < ndev; d++) {
    run(r, m, MSOCL_LAYOUT_EDGES, dt, 300, d, 1, other, other + n3);
    same_bits(one, other, bytes, "EDGES on another device");
  }
  for (int parts = 2; parts <= ndev; parts++) {
    run(r, m, MSOCL_LAYOUT_BUFFER, dt, 300, 0, parts, other, other + n3);
    same_bits(one, other, bytes, "EDGES against BUFFER split");
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.tuning.layout = MSOCL_LAYOUT_EDGES;
    o.tuning.ndevices = parts;
    msocl_sim *s = NULL;
    ck_assert_int_eq(msocl_sim_create(&s, r, m, &o), MSOCL_ERR_BAD_VALUE);
    ck_assert_ptr_null(s);
    ck_assert_msg(strstr(msocl_last_error(), "EDGES") &&
                      strstr(msocl_last_error(), "BUFFER"),
                  "%s", msocl_last_error());
  }
  printf("devices: EDGES on %d devices and BUFFER split over 2..%d: the "
         "same bits\n", ndev, ndev);
  free(one);
  free(other);
  msocl_model_destroy(m);
  msocl_runtime_destroy(r);
}
END_TEST

int main(void)
{
  /* three PoCL CPU devices for the devices case unless the caller chose
   * otherwise; set before the first OpenCL call */
  setenv("POCL_DEVICES", "pthread pthread pthread", 0);
  scene_require_device("check_edges");
  Suite *su = suite_create("edges");
  TCase *tc = tcase_create("edges");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, hanging_cloth);
  tcase_add_test(tc, tablecloth);
  tcase_add_test(tc, lattice_degree_24);
  tcase_add_test(tc, only_symplectic);
  tcase_add_test(tc, bitwise_buffer);
  tcase_add_test(tc, values);
  tcase_add_test(tc, repeatable);
  tcase_add_test(tc, devices);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

/* Wind on the model's triangles: the force on a flat plate against its
 * analytic value, face-on and at an angle; a hanging flag in changing
 * wind against the double reference; the layouts still bitwise with wind,
 * GRID's one-sweep kernel too;
 * wind cleared is no wind; bad input refused. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

enum { N = 16 };

/* A free flat n x n cloth, 1 m a side, in the x-z plane (normal along y),
 * no gravity: its springs at rest, so one step's momentum is the wind's. */
static msocl_model *plate(int n)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = n;
  d.point_mass = 0.5f / (float)(n * n);
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_gravity(m, 0.0f, 0.0f, 0.0f), MSOCL_OK);
  return m;
}

static msocl_sim *sim_of(const msocl_model *m, msocl_layout layout,
                         msocl_integrator in, float dt)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.integrator = in;
  o.tuning.layout = layout;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK, "%s",
                msocl_last_error());
  return s;
}

/* The plate's total momentum after one step in air at velocity u. */
static void momentum(const msocl_wind *w, double out[3])
{
  msocl_model *m = plate(N);
  msocl_sim *s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER, 1e-3f);
  ck_assert_int_eq(msocl_sim_set_wind(s, w), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
  float *v = malloc(3 * N * N * sizeof *v);
  ck_assert_int_eq(msocl_sim_read_velocities(s, v), MSOCL_OK);
  const double mass = 0.5 / (N * N);
  out[0] = out[1] = out[2] = 0.0;
  for (int i = 0; i < N * N; i++)
    for (int k = 0; k < 3; k++)
      out[k] += mass * v[3 * i + k];
  free(v);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}

/* Face-on, drag only: |F| = rho Cd A |u|^2 / 2 along u, lift 0 whatever
 * its coefficient. */
START_TEST(plate_face_on)
{
  msocl_wind w;
  msocl_wind_init(&w);
  w.velocity[1] = 4.0f;
  w.lift = 0.8f;
  double p[3];
  momentum(&w, p);
  const double f = 0.5 * 1.2 * 1.2 * 1.0 * 16.0, dt = 1e-3;
  printf("face-on plate: impulse (%.6g %.6g %.6g), analytic (0 %.6g 0)\n",
         p[0], p[1], p[2], f * dt);
  ck_assert_msg(fabs(p[1] - f * dt) <= 1e-4 * f * dt, "drag %g", p[1] / dt);
  ck_assert_msg(fabs(p[0]) + fabs(p[2]) <= 1e-6 * f * dt, "sideways");
}
END_TEST

/* At 60 degrees from the normal: drag rho Cd A |u|^2 |cos| / 2 along u,
 * lift rho Cl A |u|^2 cos sin / 2 across it, towards the normal. */
START_TEST(plate_at_an_angle)
{
  const double th = 60.0 * acos(-1.0) / 180.0, speed = 5.0, dt = 1e-3;
  msocl_wind w;
  msocl_wind_init(&w);
  w.velocity[0] = (float)(speed * sin(th));
  w.velocity[1] = (float)(speed * cos(th));
  w.drag = 1.0f;
  w.lift = 0.6f;
  double p[3];
  momentum(&w, p);
  const double q = 0.5 * 1.2 * speed * speed; /* dynamic pressure, A = 1 */
  const double drag = q * w.drag * cos(th), lift = q * w.lift * cos(th) * sin(th);
  /* u = (sin, cos, 0); across it, towards +y: (-cos, sin, 0) */
  const double fx = drag * sin(th) - lift * cos(th),
               fy = drag * cos(th) + lift * sin(th);
  printf("plate at 60 deg: impulse (%.6g %.6g %.6g), analytic (%.6g %.6g 0)\n",
         p[0], p[1], p[2], fx * dt, fy * dt);
  ck_assert_msg(fabs(p[0] - fx * dt) <= 1e-4 * q * dt, "x %g", p[0] / dt);
  ck_assert_msg(fabs(p[1] - fy * dt) <= 1e-4 * q * dt, "y %g", p[1] / dt);
  ck_assert_msg(fabs(p[2]) <= 1e-6 * q * dt, "z %g", p[2] / dt);
}
END_TEST

/* The hanging cloth in wind that turns and strengthens halfway, each
 * integrator, against the double reference: 1e-4 of the 1 m cloth, as
 * check_accuracy's hanging cloth without wind. */
START_TEST(flag_vs_reference)
{
  const msocl_integrator ins[3] = {MSOCL_SYMPLECTIC_EULER, MSOCL_VERLET,
                                   MSOCL_RK4};
  msocl_wind w[2];
  msocl_wind_init(&w[0]);
  msocl_wind_init(&w[1]);
  w[0].velocity[2] = 3.0f;
  w[0].lift = 0.5f;
  w[1].velocity[0] = 2.0f;
  w[1].velocity[2] = 6.0f;
  w[1].lift = 0.5f;
  msocl_model *m = scene_hanging(N);
  const float dt = 1e-3f;
  for (int q = 0; q < 3; q++) {
    msocl_sim *s = sim_of(m, MSOCL_LAYOUT_GRID, ins[q], dt);
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = dt;
    o.integrator = ins[q];
    msocl_reference *r = NULL;
    ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
    for (int g = 0; g < 2; g++) {
      ck_assert_int_eq(msocl_sim_set_wind(s, &w[g]), MSOCL_OK);
      ck_assert_int_eq(msocl_reference_set_wind(r, &w[g]), MSOCL_OK);
      ck_assert_int_eq(msocl_sim_step(s, 250), MSOCL_OK);
      ck_assert_int_eq(msocl_reference_step(r, 250), MSOCL_OK);
    }
    float *p = malloc(3 * N * N * sizeof *p);
    double *ref = malloc(3 * N * N * sizeof *ref);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    ck_assert_int_eq(msocl_reference_positions(r, ref), MSOCL_OK);
    double e = 0.0, blown = 0.0;
    for (int i = 0; i < 3 * N * N; i++) {
      e = fmax(e, fabs(p[i] - ref[i]));
      if (i % 3 == 2)
        blown = fmax(blown, ref[i]);
    }
    printf("flag, integrator %d: max |device - reference| = %.3g m, "
           "blown %.3g m downwind\n", (int)ins[q], e, blown);
    ck_assert_msg(e <= 1e-4, "integrator %d: %g m", (int)ins[q], e);
    ck_assert_msg(blown > 0.1, "the wind moved the flag only %g m", blown);
    free(p);
    free(ref);
    msocl_reference_destroy(r);
    msocl_sim_destroy(s);
  }
  msocl_model_destroy(m);
}
END_TEST

static void positions_after(const msocl_model *m, msocl_layout layout,
                            msocl_integrator in, const msocl_wind *w,
                            float *p)
{
  msocl_sim *s = sim_of(m, layout, in, 1e-3f);
  ck_assert_int_eq(msocl_sim_set_wind(s, w), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 200), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
  msocl_sim_destroy(s);
}

/* GRID, BUFFER and IMAGE2D keep one result with wind. */
START_TEST(layouts_bitwise)
{
  msocl_wind w;
  msocl_wind_init(&w);
  w.velocity[2] = 4.0f;
  w.lift = 0.5f;
  msocl_model *m = scene_hanging(N);
  const msocl_layout ls[3] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                              MSOCL_LAYOUT_IMAGE2D};
  const msocl_integrator ins[2] = {MSOCL_SYMPLECTIC_EULER, MSOCL_VERLET};
  float *p[3];
  for (int l = 0; l < 3; l++)
    p[l] = malloc(3 * N * N * sizeof *p[l]);
  for (int q = 0; q < 2; q++) {
    for (int l = 0; l < 3; l++)
      positions_after(m, ls[l], ins[q], &w, p[l]);
    for (int l = 1; l < 3; l++)
      ck_assert_msg(memcmp(p[0], p[l], 3 * N * N * sizeof(float)) == 0,
                    "layout %d differs from GRID, integrator %d (%g m)",
                    (int)ls[l], (int)ins[q], scene_max_diff(p[0], p[l], 3 * N * N));
  }
  for (int l = 0; l < 3; l++)
    free(p[l]);
  msocl_model_destroy(m);
}
END_TEST

/* A flag of 20 x 20 without dashpots (rows of more than one vector, and a
 * last one that overlaps): GRID's one-sweep kernel blows the wind as it
 * goes and must keep BUFFER's and IMAGE2D's bits and the reference's
 * path. */
START_TEST(sweep_bitwise)
{
  enum { M = 20 };
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = M;
  d.v[0] = 0.0f, d.v[1] = -1.0f, d.v[2] = 0.0f;
  d.point_mass = 0.5f / (float)(M * M);
  d.damping = 0.0f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  ck_assert_int_eq(msocl_model_pin(m, 0, 1), MSOCL_OK);
  ck_assert_int_eq(msocl_model_pin(m, M - 1, 1), MSOCL_OK);
  /* viscous damping (the sweep blows wind without dashpots; with them
   * wind's own passes run before it), enough that the flag does not
   * flutter: fluttering, it grows the float rounding with the wind's
   * last bits (at 2 point masses, 6.6e-6 to 4.1e-5 m from the reference
   * over 19-21 points a side and 3.9-4.1 m/s; at 30, 2.6e-7 to 4.4e-7) */
  ck_assert_int_eq(msocl_model_set_viscous_damping(m, 30.0f * d.point_mass),
                   MSOCL_OK);
  msocl_wind w;
  msocl_wind_init(&w);
  w.velocity[0] = 1.0f;
  w.velocity[2] = 4.0f;
  w.lift = 0.6f;
  const msocl_layout ls[3] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                              MSOCL_LAYOUT_IMAGE2D};
  float *p[3];
  for (int l = 0; l < 3; l++) {
    p[l] = malloc(3 * M * M * sizeof *p[l]);
    positions_after(m, ls[l], MSOCL_SYMPLECTIC_EULER, &w, p[l]);
  }
  for (int l = 1; l < 3; l++)
    ck_assert_msg(memcmp(p[0], p[l], 3 * M * M * sizeof(float)) == 0,
                  "layout %d differs from GRID's sweep (%g m)", (int)ls[l],
                  scene_max_diff(p[0], p[l], 3 * M * M));
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-3f;
  msocl_reference *r = NULL;
  ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_set_wind(r, &w), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_step(r, 200), MSOCL_OK);
  double *ref = malloc(3 * M * M * sizeof *ref), e = 0.0, moved = 0.0;
  ck_assert_int_eq(msocl_reference_positions(r, ref), MSOCL_OK);
  float *x0 = malloc(3 * M * M * sizeof *x0);
  ck_assert_int_eq(msocl_model_get_positions(m, x0), MSOCL_OK);
  for (int i = 0; i < 3 * M * M; i++) {
    e = fmax(e, fabs(p[0][i] - ref[i]));
    if (i % 3 == 2)
      moved = fmax(moved, ref[i] - x0[i]);
  }
  printf("flag in the sweep: max |device - reference| = %.3g m, "
         "blown %.3g m downwind\n", e, moved);
  ck_assert_msg(e <= 1e-5, "%g m from the reference", e);
  ck_assert_msg(moved > 1e-2, "the wind moved the flag only %g m", moved);
  msocl_reference_destroy(r);
  for (int l = 0; l < 3; l++)
    free(p[l]);
  free(ref);
  free(x0);
  msocl_model_destroy(m);
}
END_TEST

/* Wind set and then cleared is no wind, to the bit. */
START_TEST(cleared_is_none)
{
  msocl_model *m = scene_hanging(N);
  float *a = malloc(3 * N * N * sizeof *a), *b = malloc(3 * N * N * sizeof *b);
  msocl_sim *s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER, 1e-3f);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, a), MSOCL_OK);
  msocl_sim_destroy(s);
  msocl_wind w;
  msocl_wind_init(&w);
  w.velocity[2] = 4.0f;
  s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER, 1e-3f);
  ck_assert_int_eq(msocl_sim_set_wind(s, &w), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_set_wind(s, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, b), MSOCL_OK);
  ck_assert(memcmp(a, b, 3 * N * N * sizeof *a) == 0);
  msocl_sim_destroy(s);
  free(a);
  free(b);
  msocl_model_destroy(m);
}
END_TEST

/* A fan of 12 triangles round a hub, more than a point's slots hold:
 * the hub's sum takes the spill kernel; BUFFER and IMAGE2D agree to the
 * bit and both match the reference, as the grid does. */
START_TEST(fan_spills)
{
  enum { RIM = 12 };
  float xyz[3 * (RIM + 1)] = {0.0f}, mass[RIM + 1];
  int ij[4 * RIM], tri[3 * RIM];
  float k[2 * RIM], rest[2 * RIM];
  mass[0] = 0.01f;
  for (int q = 0; q < RIM; q++) {
    const double a = 2.0 * acos(-1.0) * q / RIM;
    xyz[3 * (q + 1)] = (float)(0.3 * cos(a));
    xyz[3 * (q + 1) + 1] = (float)(0.1 * sin(3 * a)); /* not flat */
    xyz[3 * (q + 1) + 2] = (float)(0.3 * sin(a));
    mass[q + 1] = 0.01f;
    const int next = 1 + (q + 1) % RIM;
    ij[4 * q] = 0, ij[4 * q + 1] = q + 1;
    ij[4 * q + 2] = q + 1, ij[4 * q + 3] = next;
    tri[3 * q] = 0, tri[3 * q + 1] = q + 1, tri[3 * q + 2] = next;
  }
  for (int q = 0; q < 2 * RIM; q++) {
    k[q] = 50.0f;
    rest[q] = 0.0f; /* from the positions */
  }
  for (int q = 0; q < RIM; q++) {
    const float *a = xyz + 3 * ij[4 * q + 2], *b = xyz + 3 * ij[4 * q + 3];
    rest[2 * q] = 0.3f;
    rest[2 * q + 1] = (float)sqrt((a[0] - b[0]) * (a[0] - b[0]) +
                                  (a[1] - b[1]) * (a[1] - b[1]) +
                                  (a[2] - b[2]) * (a[2] - b[2]));
  }
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_create(&m), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_points(m, RIM + 1, xyz, mass, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_springs(m, 2 * RIM, ij, k, rest, NULL),
                   MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_triangles(m, RIM, tri), MSOCL_OK);
  msocl_model_pin(m, 1, 1);
  msocl_wind w;
  msocl_wind_init(&w);
  w.velocity[0] = 2.0f;
  w.velocity[1] = 3.0f;
  w.lift = 0.7f;
  float p[2][3 * (RIM + 1)];
  const msocl_layout ls[2] = {MSOCL_LAYOUT_BUFFER, MSOCL_LAYOUT_IMAGE2D};
  for (int l = 0; l < 2; l++)
    positions_after(m, ls[l], MSOCL_SYMPLECTIC_EULER, &w, p[l]);
  ck_assert(memcmp(p[0], p[1], sizeof p[0]) == 0);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-3f;
  msocl_reference *r = NULL;
  ck_assert_int_eq(msocl_reference_create(&r, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_set_wind(r, &w), MSOCL_OK);
  ck_assert_int_eq(msocl_reference_step(r, 200), MSOCL_OK);
  double ref[3 * (RIM + 1)], e = 0.0, moved = 0.0;
  ck_assert_int_eq(msocl_reference_positions(r, ref), MSOCL_OK);
  for (int i = 0; i < 3 * (RIM + 1); i++) {
    e = fmax(e, fabs(p[0][i] - ref[i]));
    moved = fmax(moved, fabs(ref[i] - xyz[i]));
  }
  printf("fan of %d: max |device - reference| = %.3g m, moved %.3g m\n", RIM,
         e, moved);
  ck_assert_msg(e <= 1e-4, "%g m", e);
  ck_assert_msg(moved > 0.01, "the wind moved the fan only %g m", moved);
  msocl_reference_destroy(r);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(bad_input)
{
  msocl_model *m = scene_hanging(4);
  msocl_sim *s = sim_of(m, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER, 1e-3f);
  msocl_wind w;
  msocl_wind_init(&w);
  ck_assert_int_eq(msocl_sim_set_wind(NULL, &w), MSOCL_ERR_NULL_HANDLE);
  w.velocity[1] = NAN;
  ck_assert_int_eq(msocl_sim_set_wind(s, &w), MSOCL_ERR_NOT_FINITE);
  msocl_wind_init(&w);
  w.lift = INFINITY;
  ck_assert_int_eq(msocl_sim_set_wind(s, &w), MSOCL_ERR_NOT_FINITE);
  msocl_wind_init(&w);
  w.density = -1.0f;
  ck_assert_int_eq(msocl_sim_set_wind(s, &w), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "density"));
  msocl_wind_init(&w);
  w.drag = -0.1f;
  ck_assert_int_eq(msocl_sim_set_wind(s, &w), MSOCL_ERR_BAD_VALUE);
  msocl_sim_destroy(s);
  msocl_reference *r = NULL;
  ck_assert_int_eq(msocl_reference_create(&r, m, NULL), MSOCL_OK);
  w.drag = NAN;
  ck_assert_int_eq(msocl_reference_set_wind(r, &w), MSOCL_ERR_NOT_FINITE);
  msocl_reference_destroy(r);
  msocl_model_destroy(m);
  msocl_wind_init(&w);
  /* a chain: springs, no triangles */
  const float xyz[9] = {0, 0, 0, 0.1f, 0, 0, 0.2f, 0, 0}, mass[3] = {1, 1, 1};
  const int ij[4] = {0, 1, 1, 2};
  const float k[2] = {100, 100}, rest[2] = {0.1f, 0.1f};
  ck_assert_int_eq(msocl_model_create(&m), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_points(m, 3, xyz, mass, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_springs(m, 2, ij, k, rest, NULL), MSOCL_OK);
  s = sim_of(m, MSOCL_LAYOUT_BUFFER, MSOCL_SYMPLECTIC_EULER, 1e-3f);
  ck_assert_int_eq(msocl_sim_set_wind(s, &w), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "triangles"));
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Two CPU devices (POCL_DEVICES="pthread pthread"): refused on a split. */
START_TEST(split_refused)
{
  char spec[256];
  if (scene_cpu_spec(spec, sizeof spec, 2) < 2) {
    printf("split_refused: one CPU device only, not run\n");
    return;
  }
  msocl_runtime *two = NULL;
  ck_assert_int_eq(msocl_runtime_create(&two, spec), MSOCL_OK);
  msocl_model *m = scene_hanging(N);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-3f;
  o.tuning.ndevices = 2;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, two, m, &o) == MSOCL_OK, "%s",
                msocl_last_error());
  msocl_wind w;
  msocl_wind_init(&w);
  ck_assert_int_eq(msocl_sim_set_wind(s, &w), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "split"));
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(two);
}
END_TEST

int main(void)
{
  scene_require_device("check_wind");
  Suite *su = suite_create("wind");
  TCase *tc = tcase_create("wind");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, plate_face_on);
  tcase_add_test(tc, plate_at_an_angle);
  tcase_add_test(tc, flag_vs_reference);
  tcase_add_test(tc, layouts_bitwise);
  tcase_add_test(tc, sweep_bitwise);
  tcase_add_test(tc, cleared_is_none);
  tcase_add_test(tc, fan_spills);
  tcase_add_test(tc, bad_input);
  tcase_add_test(tc, split_refused);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

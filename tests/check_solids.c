/* Deformable solids on the device: a soft ball and a jello cube dropped on
 * the ground come to rest on it, above it, the ball keeping its volume;
 * the cube's 24 springs a point do not fit the IMAGE2D layout. */
#include "internal.h"
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define DT 1e-4f
/* 2.75 s simulated, checked every 0.05 s; then 0.25 s more, checked every
 * 0.01 s, to find the largest kinetic energy left ("at rest"). */
#define CHUNK 500
#define CHUNKS 55
#define REST_CHUNK 100
#define REST_CHUNKS 25
/* Allowed penetration: float rounding only. */
#define GAP_TOL (-1e-5)

static msocl_runtime *rt;

static void setup(void)
{
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
}

static void teardown(void)
{
  msocl_runtime_destroy(rt);
  rt = NULL;
}

static int make_sim(msocl_sim **s, const msocl_model *m, msocl_layout layout)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = DT;
  o.tuning.layout = layout;
  *s = NULL;
  return msocl_sim_create(s, rt, m, &o);
}

/* The ground, y >= 0, with friction. */
static void add_ground(msocl_model *m)
{
  const float up[3] = {0.0f, 1.0f, 0.0f};
  ck_assert_int_eq(msocl_model_add_plane(m, up, 0.0f, 0.5f), MSOCL_OK);
}

/* Divergence theorem over the outward triangles. */
static double volume(const float *p, int nt, const int *ijk)
{
  double v = 0.0;
  for (int t = 0; t < nt; t++) {
    const float *a = p + 3 * ijk[3 * t], *b = p + 3 * ijk[3 * t + 1],
                *c = p + 3 * ijk[3 * t + 2];
    v += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
         (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
         (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
  }
  return v / 6.0;
}

static double lowest(const float *p, int n)
{
  double y = INFINITY;
  for (int i = 0; i < n; i++) {
    ck_assert_msg(isfinite(p[3 * i]) && isfinite(p[3 * i + 1]) &&
                      isfinite(p[3 * i + 2]),
                  "point %d is not finite", i);
    if (p[3 * i + 1] < y)
      y = p[3 * i + 1];
  }
  return y;
}

/* Sum of m v^2 / 2 from the device's velocities and the model's masses. */
static double kinetic(msocl_sim *s, const msocl_model *m, int n)
{
  float *v = malloc(3 * (size_t)n * sizeof *v);
  double e = 0.0;
  ck_assert_int_eq(msocl_sim_read_velocities(s, v), MSOCL_OK);
  for (int i = 0; i < n; i++)
    e += 0.5 * m->mass[i] *
         ((double)v[3 * i] * v[3 * i] + (double)v[3 * i + 1] * v[3 * i + 1] +
          (double)v[3 * i + 2] * v[3 * i + 2]);
  free(v);
  return e;
}

struct outcome {
  double low;    /* lowest y seen at any check */
  double vmin;   /* smallest volume ratio seen at any check */
  double ratio;  /* final volume / initial volume */
  double energy; /* largest kinetic energy over the last 0.25 s, J */
};

/* Watches the ground and the volume while it falls, bounces and settles. */
static struct outcome drop(msocl_sim *s, const msocl_model *m)
{
  int n = m->n, nt;
  const int *ijk;
  float *p = malloc(3 * (size_t)n * sizeof *p);
  struct outcome o = {INFINITY, INFINITY, 0.0, 0.0};

  ck_assert_int_eq(msocl_model_triangles(m, &nt, &ijk), MSOCL_OK);
  double v0 = volume(m->pos, nt, ijk);
  for (int c = 0; c < CHUNKS + REST_CHUNKS; c++) {
    ck_assert_int_eq(msocl_sim_step(s, c < CHUNKS ? CHUNK : REST_CHUNK),
                     MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    double low = lowest(p, n), r = volume(p, nt, ijk) / v0;
    if (low < o.low)
      o.low = low;
    if (r < o.vmin)
      o.vmin = r;
    o.ratio = r;
    if (c >= CHUNKS) {
      double e = kinetic(s, m, n);
      if (e > o.energy)
        o.energy = e;
    }
  }
  free(p);
  return o;
}

/* The default soft ball (162 + 1 points, radius 0.1 m) falls 0.2 m onto
 * the ground. It bounces well: viscous damping of 4e-3 N s/m (a rate of
 * 3.2/s on a surface point) settles it within the 3 s. */
START_TEST(ball_comes_to_rest)
{
  msocl_solid_desc d;
  msocl_solid_desc_init(&d);
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_solid(&m, &d), MSOCL_OK);
  add_ground(m);
  ck_assert_int_eq(msocl_model_set_viscous_damping(m, 4e-3f), MSOCL_OK);
  msocl_sim *s = NULL;
  ck_assert_msg(make_sim(&s, m, MSOCL_LAYOUT_AUTO) == MSOCL_OK, "%s",
                msocl_last_error());
  struct outcome o = drop(s, m);
  printf("ball: lowest y %.3g m, volume ratio %.4f (min %.4f), "
         "kinetic energy at most %.3g J at rest\n", o.low, o.ratio, o.vmin,
         o.energy);
  ck_assert_msg(o.low >= GAP_TOL, "a point went %g m below the ground", -o.low);
  ck_assert_msg(o.ratio >= 0.9, "volume ratio %g", o.ratio);
  /* At rest: 2e-5 J, the whole 0.22 kg moving at 1.3 cm/s. */
  ck_assert_msg(o.energy < 2e-5, "kinetic energy %g J", o.energy);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* The default jello cube (8^3 points, structural + face shear + bend:
 * 24 springs an inner point) falls 0.1 m onto the ground; viscous damping
 * of 4e-3 N s/m (a rate of 2/s) calms its wobble. */
START_TEST(cube_comes_to_rest)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_lattice(&m, &d), MSOCL_OK);
  int degree = 0;
  ck_assert_int_eq(msocl_model_max_degree(m, &degree), MSOCL_OK);
  ck_assert_int_eq(degree, 24);
  add_ground(m);
  ck_assert_int_eq(msocl_model_set_viscous_damping(m, 4e-3f), MSOCL_OK);
  msocl_sim *s = NULL;
  msocl_device_info info;
  ck_assert_int_eq(msocl_runtime_device_info(rt, 0, &info), MSOCL_OK);
  /* 24 > the texture's 16 slots (or no images at all). */
  int rc = make_sim(&s, m, MSOCL_LAYOUT_IMAGE2D);
  ck_assert_int_eq(rc, info.image_support ? MSOCL_ERR_DEGREE
                                          : MSOCL_ERR_NO_IMAGES);
  ck_assert_ptr_null(s);
  ck_assert_msg(make_sim(&s, m, MSOCL_LAYOUT_BUFFER) == MSOCL_OK, "%s",
                msocl_last_error());
  struct outcome o = drop(s, m);
  printf("cube: lowest y %.3g m, volume ratio %.4f (min %.4f), "
         "kinetic energy at most %.3g J at rest\n", o.low, o.ratio, o.vmin,
         o.energy);
  ck_assert_msg(o.low >= GAP_TOL, "a point went %g m below the ground", -o.low);
  /* At rest: 2e-5 J, the whole 1 kg moving at 6 mm/s. */
  ck_assert_msg(o.energy < 2e-5, "kinetic energy %g J", o.energy);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_solids");
  Suite *su = suite_create("solids");
  /* One case each, so CK_RUN_CASE=ball (or cube) runs one alone. */
  TCase *tc = tcase_create("ball");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, ball_comes_to_rest);
  suite_add_tcase(su, tc);
  tc = tcase_create("cube");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, cube_comes_to_rest);
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  /* PoCL hangs in fork()ed children once the parent has used OpenCL. */
  srunner_set_fork_status(sr, CK_NOFORK);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}

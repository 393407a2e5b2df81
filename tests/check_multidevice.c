/* One model split over several devices (PoCL's pthread devices here):
 * bitwise the same positions and velocities as on one device, for every
 * gather layout and explicit integrator, with even and uneven splits and
 * splits narrower than a spring's reach. */
#include "internal.h" /* to take a device's image support away */
#include "scenes.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

static msocl_runtime *rt;
static int ndev;
static char spec[256];
static msocl_choice overlap = MSOCL_AUTO; /* tuning.overlap of the splits */

static void setup(void)
{
  ck_assert_int_eq(msocl_runtime_create(&rt, spec), MSOCL_OK);
}

static void teardown(void)
{
  msocl_runtime_destroy(rt);
  rt = NULL;
}

static const char *const inames[] = {"symplectic Euler", "explicit Euler",
                                     "Verlet", "RK4", "implicit Euler"};

/* Runs the model on `parts` devices with `weights` (NULL: equal); returns
 * positions and velocities. */
static void run(const msocl_model *m, msocl_integrator in, msocl_layout lay,
                float dt, int steps, int parts, const float *weights,
                float *pos, float *vel)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.integrator = in;
  o.tuning.layout = lay;
  o.tuning.ndevices = parts;
  o.check_every = 0;
  o.tuning.overlap = overlap;
  for (int d = 0; weights && d < parts; d++)
    o.tuning.weights[d] = weights[d];
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  rc = msocl_sim_step(s, steps);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  ck_assert_int_eq(msocl_sim_read_positions(s, pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, vel), MSOCL_OK);
  msocl_sim_destroy(s);
}

/* One device against `parts`, bitwise. */
static void same_bits(const msocl_model *m, msocl_integrator in,
                      msocl_layout lay, float dt, int steps, int parts,
                      const float *weights, const char *what)
{
  int n;
  msocl_model_point_count(m, &n);
  size_t bytes = 3 * (size_t)n * sizeof(float);
  float *p1 = malloc(bytes), *v1 = malloc(bytes), *pk = malloc(bytes),
        *vk = malloc(bytes), *p0 = malloc(bytes);
  msocl_model_get_positions(m, p0);
  run(m, in, lay, dt, steps, 1, NULL, p1, v1);
  run(m, in, lay, dt, steps, parts, weights, pk, vk);
  ck_assert_msg(scene_max_diff(p0, p1, 3 * n) > 1e-4, "%s: did not move",
                what);
  ck_assert_msg(memcmp(p1, pk, bytes) == 0 && memcmp(v1, vk, bytes) == 0,
                "%s, %s, %s, %d devices: positions differ by %g, velocities "
                "by %g",
                what, inames[in],
                lay == MSOCL_LAYOUT_IMAGE2D ? "IMAGE2D"
                : lay == MSOCL_LAYOUT_GRID  ? "GRID"
                                            : "BUFFER",
                parts,
                scene_max_diff(p1, pk, 3 * n), scene_max_diff(v1, vk, 3 * n));
  free(p1); free(v1); free(pk); free(vk); free(p0);
}

/* _i: integrator * 2 + layout */
START_TEST(tablecloth_500_steps)
{
  msocl_integrator in = (msocl_integrator)(_i / 2);
  msocl_layout lay = _i % 2 ? MSOCL_LAYOUT_BUFFER : MSOCL_LAYOUT_IMAGE2D;
  msocl_model *m = scene_tablecloth(24);
  /* forward Euler grows without damping: a short enough step keeps its
   * 500 steps finite */
  float dt = scene_tablecloth_dt(24) / (in == MSOCL_EXPLICIT_EULER ? 20 : 1);
  for (int parts = 2; parts <= ndev && parts <= 3; parts++)
    same_bits(m, in, lay, dt, 500, parts, NULL, "tablecloth");
  msocl_model_destroy(m);
}
END_TEST

/* Dashpots make every gather read the neighbours' velocities too. */
START_TEST(damped_hanging_cloth)
{
  msocl_integrator in = (msocl_integrator)(_i / 2);
  msocl_layout lay = _i % 2 ? MSOCL_LAYOUT_BUFFER : MSOCL_LAYOUT_IMAGE2D;
  msocl_model *m = scene_hanging(16);
  float dt = in == MSOCL_EXPLICIT_EULER ? 1e-4f : 1e-3f;
  for (int parts = 2; parts <= ndev && parts <= 3; parts++)
    same_bits(m, in, lay, dt, 500, parts, NULL, "damped hanging cloth");
  msocl_model_destroy(m);
}
END_TEST

/* Implicit Euler split: one CG over every device, the search direction's
 * halo exchanged between products, ranges in whole work-groups so the dot
 * products add up in one device's order - bitwise one device's result. */
START_TEST(implicit_split)
{
  msocl_model *m = scene_hanging(24); /* 576 points: 9 groups of 64 */
  for (int parts = 2; parts <= ndev && parts <= 3; parts++)
    same_bits(m, MSOCL_IMPLICIT_EULER, MSOCL_LAYOUT_BUFFER, 1e-3f, 100,
              parts, NULL, "implicit Euler, damped hanging cloth");
  const float w[2] = {1.0f, 3.0f};
  same_bits(m, MSOCL_IMPLICIT_EULER, MSOCL_LAYOUT_GRID, 1e-3f, 100, 2, w,
            "implicit Euler, GRID, weights 1:3");
  msocl_model_destroy(m);
  /* 64 points cannot go to two devices in whole work-groups */
  m = scene_tablecloth(8);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.integrator = MSOCL_IMPLICIT_EULER;
  o.tuning.ndevices = 2;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "work-groups of 64"));
  msocl_model_destroy(m);
}
END_TEST

/* tuning.overlap = MSOCL_OFF: every kernel, then every copy - bitwise the same
 * as boundary first, and reported as off. _i: the integrator. */
START_TEST(kernels_then_copies)
{
  msocl_integrator in = (msocl_integrator)_i;
  msocl_model *m = scene_hanging(in == MSOCL_IMPLICIT_EULER ? 24 : 16);
  float dt = in == MSOCL_EXPLICIT_EULER ? 1e-4f : 1e-3f;
  overlap = MSOCL_OFF;
  same_bits(m, in, MSOCL_LAYOUT_BUFFER, dt, 200, ndev < 3 ? ndev : 3, NULL,
            "kernels then copies, damped hanging cloth");
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.tuning.ndevices = 2;
  o.tuning.overlap = MSOCL_OFF;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 10), MSOCL_OK);
  msocl_split_info info;
  ck_assert_int_eq(msocl_sim_split_info(s, &info), MSOCL_OK);
  ck_assert_int_eq(info.overlap, 0);
  ck_assert_double_eq(info.boundary_points[0], 0.0);
  ck_assert_double_eq(info.hidden_copy_seconds[0], 0.0);
  ck_assert_double_gt(info.compute_seconds[0], 0.0);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  overlap = MSOCL_AUTO;
}
END_TEST

/* GRID recomputes neighbours from the grid: split, it still reads the
 * exchanged halo rows. */
START_TEST(grid_layout_split)
{
  msocl_model *m = scene_hanging(16);
  for (int parts = 2; parts <= ndev && parts <= 3; parts++)
    same_bits(m, MSOCL_RK4, MSOCL_LAYOUT_GRID, 1e-3f, 500, parts, NULL,
              "GRID, damped hanging cloth");
  msocl_model_destroy(m);
}
END_TEST

START_TEST(uneven_weights)
{
  msocl_model *m = scene_tablecloth(24);
  const float w2[2] = {1.0f, 3.0f}, w3[3] = {5.0f, 1.0f, 1.0f};
  same_bits(m, MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_BUFFER,
            scene_tablecloth_dt(24), 500, 2, w2, "weights 1:3");
  if (ndev >= 3)
    same_bits(m, MSOCL_RK4, MSOCL_LAYOUT_BUFFER, scene_tablecloth_dt(24),
              500, 3, w3, "weights 5:1:1");
  msocl_model_destroy(m);
}
END_TEST

/* A 16 x 6 cloth with bend springs reaches two rows (32 points) away; the
 * middle device gets about one row, so the outer devices' halos reach
 * across it into each other. */
START_TEST(narrower_than_halo)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = 16;
  d.ny = 6;
  d.damping = 1e-3f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  msocl_model_pin(m, 0, 1);
  msocl_model_pin(m, 15, 1);
  const float w[3] = {1.0f, 0.3f, 1.0f};
  if (ndev >= 3)
    same_bits(m, MSOCL_VERLET, MSOCL_LAYOUT_BUFFER, 2e-4f, 500, 3, w,
              "middle range narrower than the halo");
  else
    same_bits(m, MSOCL_VERLET, MSOCL_LAYOUT_BUFFER, 2e-4f, 500, 2, w,
              "uneven 1:0.3");
  msocl_model_destroy(m);
}
END_TEST

/* _i 0: BUFFER, 1: GRID (what AUTO takes for the cloth) */
START_TEST(split_report_and_normals)
{
  msocl_model *m = scene_tablecloth(24);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = scene_tablecloth_dt(24);
  o.tuning.layout = _i ? MSOCL_LAYOUT_GRID : MSOCL_LAYOUT_BUFFER;
  o.tuning.ndevices = -1;
  msocl_sim *s = NULL, *one = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  o.tuning.ndevices = 1;
  ck_assert_int_eq(msocl_sim_create(&one, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(one, 100), MSOCL_OK);
  msocl_split_info info;
  ck_assert_int_eq(msocl_sim_split_info(s, &info), MSOCL_OK);
  ck_assert_int_eq(info.parts, ndev);
  int total = 0;
  for (int d = 0; d < info.parts; d++) {
    ck_assert_int_eq(info.first[d], total);
    total += info.count[d];
    ck_assert_double_ge(info.halo_points[d], 24); /* a row at least */
    /* boundary first: a part's phases run first on the points others
     * read - on an evenly split grid, as many as its halo holds - and
     * there is an interior left for the copies to overlap */
    ck_assert_int_eq(info.overlap, 1);
    if (_i) /* GRID: its spans cut at rows */
      ck_assert_double_eq(info.boundary_points[d], info.halo_points[d]);
    else /* BUFFER: at work-groups of points */
      ck_assert_double_ge(info.boundary_points[d], info.halo_points[d]);
    ck_assert_double_lt(info.boundary_points[d], info.count[d]);
    printf("part %d: device %d, points [%d, %d), receives %.0f points a "
           "phase\n", d, info.device[d], info.first[d],
           info.first[d] + info.count[d], info.halo_points[d]);
  }
  ck_assert_int_eq(total, 24 * 24);
  /* every step sends each halo its positions, and its velocities too
   * where dashpots read them: one or two times 12 bytes a halo point */
  double halo = 0.0;
  for (int d = 0; d < info.parts; d++)
    halo += info.halo_points[d];
  if (!_i) {
    /* three floats a point, a plane each, the points exactly */
    const double per = info.bytes_per_step / (12.0 * halo);
    ck_assert_msg(per == 1.0 || per == 2.0, "%g x 12 bytes a halo point a "
                  "step", per);
  } else {
    /* three floats a point, over each slice's padded rows (24 + 4) */
    const double per = info.bytes_per_step / (12.0 * halo * 28.0 / 24.0);
    ck_assert_msg(fabs(per - 1.0) < 0.1 || fabs(per - 2.0) < 0.2,
                  "%g x 12 bytes a padded halo point a step (%g bytes, %g "
                  "halo points)",
                  per, info.bytes_per_step, halo);
  }
  for (int d = 0; d < info.parts; d++) {
    /* event profiling timed the copies; the host thread timed its waits */
    ck_assert_double_gt(info.copy_seconds[d], 0.0);
    ck_assert_double_gt(info.part_wait_seconds[d], 0.0);
    ck_assert_double_gt(info.part_exchange_seconds[d], 0.0);
    ck_assert_double_gt(info.compute_seconds[d], 0.0);
    /* the copies beside the interior are part of the copies */
    ck_assert_double_ge(info.hidden_copy_seconds[d], 0.0);
    ck_assert_double_le(info.hidden_copy_seconds[d], info.copy_seconds[d]);
    printf("part %d: device time %.4f s in kernels, %.3g s in copies "
           "(%.3g s of them beside the interior); host time %.4f s "
           "exchanging, %.4f s waiting\n",
           d, info.compute_seconds[d], info.copy_seconds[d],
           info.hidden_copy_seconds[d], info.part_exchange_seconds[d],
           info.part_wait_seconds[d]);
  }
  printf("%.0f bytes a step through the host; %.3f s exchanging, %.3f s "
         "waiting for devices over %lld steps\n",
         info.bytes_per_step, info.exchange_seconds, info.wait_seconds,
         info.steps);
  float a[3 * 576], b[3 * 576];
  ck_assert_int_eq(msocl_sim_read_normals(s, a), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_normals(one, b), MSOCL_OK);
  ck_assert(memcmp(a, b, sizeof a) == 0);
  msocl_energy ea, eb;
  msocl_sim_energy(s, &ea);
  msocl_sim_energy(one, &eb);
  ck_assert_double_eq_tol(ea.total, eb.total, 1e-5 * fabs(eb.total));
  msocl_sim_destroy(s);
  msocl_sim_destroy(one);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(refused)
{
  msocl_model *m = scene_tablecloth(8);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.ndevices = 2;
  msocl_sim *s = NULL;
  o.tuning.layout = MSOCL_LAYOUT_EDGES;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.tuning.layout = MSOCL_LAYOUT_BUFFER;
  o.strain = MSOCL_STRAIN_PROVOT;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.strain = MSOCL_STRAIN_NONE;
  o.tuning.ndevices = ndev + 1;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_INDEX);
  o.tuning.ndevices = 2;
  o.tuning.weights[0] = -1.0f;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.tuning.weights[0] = 1e6f;
  o.tuning.weights[1] = 1.0f; /* 64 points: the second device would get none */
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  msocl_runtime *twice = NULL;
  char dup[64];
  msocl_device_info info;
  msocl_runtime_device_info(rt, 0, &info);
  snprintf(dup, sizeof dup, "%d:%d,%d:%d", info.platform_index,
           info.device_index, info.platform_index, info.device_index);
  ck_assert_int_eq(msocl_runtime_create(&twice, dup), MSOCL_ERR_DUP_DEVICE);
  ck_assert_ptr_null(twice);
  msocl_model_destroy(m);
}
END_TEST

/* Devices without a feature the model needs: a split IMAGE2D model on a
 * runtime whose second device lacks images (PoCL's have them, so this
 * test takes the flag away) is refused, naming the device. */
START_TEST(device_without_images)
{
  msocl_model *m = scene_tablecloth(8);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.layout = MSOCL_LAYOUT_IMAGE2D;
  o.tuning.ndevices = 2;
  rt->dev[1].info.image_support = 0;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_NO_IMAGES);
  ck_assert_ptr_null(s);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), rt->dev[1].info.name));
  o.tuning.layout = MSOCL_LAYOUT_BUFFER; /* needs no images */
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Weights from a calibration run: positive, reported, within 20x of each
 * other on these two alike devices (a timed run that built kernels gave
 * one 2 800x the other's weight on a cold PoCL cache), and the split
 * still gives one device's bits. */
START_TEST(calibrated_weights)
{
  msocl_model *m = scene_tablecloth(24);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = scene_tablecloth_dt(24);
  o.tuning.ndevices = 2;
  o.tuning.calibrate_steps = 20;
  o.check_every = 0;
  msocl_sim *s = NULL, *one = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_split_info info;
  msocl_sim_split_info(s, &info);
  printf("calibrated weights %.3g : %.3g -> %d and %d points\n",
         info.weight[0], info.weight[1], info.count[0], info.count[1]);
  ck_assert(info.weight[0] > 0.0f && info.weight[1] > 0.0f);
  ck_assert_msg(info.weight[0] < 20.0f * info.weight[1] &&
                    info.weight[1] < 20.0f * info.weight[0],
                "alike devices weighed %g and %g", info.weight[0],
                info.weight[1]);
  ck_assert_int_eq(info.count[0] + info.count[1], 576);
  o.tuning.ndevices = 1;
  ck_assert_int_eq(msocl_sim_create(&one, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 200), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(one, 200), MSOCL_OK);
  float a[3 * 576], b[3 * 576];
  msocl_sim_read_positions(s, a);
  msocl_sim_read_positions(one, b);
  ck_assert(memcmp(a, b, sizeof a) == 0);
  msocl_sim_destroy(s);
  msocl_sim_destroy(one);
  o.tuning.calibrate_steps = -1;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  o.tuning.calibrate_steps = 0;
  o.tuning.ndevices = -2; /* neither a count nor MSOCL_ALL_DEVICES */
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "MSOCL_ALL_DEVICES"));
  msocl_model_destroy(m);
}
END_TEST

/* A blow-up across devices rolls every device back. */
START_TEST(unstable_rolls_back)
{
  msocl_model *m = scene_tablecloth(16);
  msocl_model_set_gravity(m, 0, 0, 0);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  float limit;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &limit);
  o.dt = 3.0f * limit;
  o.tuning.ndevices = 2;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  float p[3 * 256], q[3 * 256];
  msocl_model_get_positions(m, p);
  for (int i = 0; i < 3 * 256; i++)
    p[i] += 1e-3f * (float)((i * 7919) % 13 - 6) / 6.0f;
  ck_assert_int_eq(msocl_sim_write_positions(s, p), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 1000), MSOCL_ERR_UNSTABLE);
  ck_assert_int_eq(msocl_sim_read_positions(s, q), MSOCL_OK);
  ck_assert(memcmp(p, q, sizeof p) == 0);
  /* the exchange a step is what it was, rolled-back steps counted (it
   * used to grow with each rollback, the bytes over the rewound count) */
  msocl_split_info a, b;
  msocl_sim_split_info(s, &a);
  ck_assert_int_eq(msocl_sim_step(s, 1000), MSOCL_ERR_UNSTABLE);
  msocl_sim_split_info(s, &b);
  ck_assert_msg(a.bytes_per_step > 0 && b.bytes_per_step == a.bytes_per_step,
                "bytes a step %g, then %g", a.bytes_per_step,
                b.bytes_per_step);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* 64 small cloths spread over the devices, stepped by one call: each ends
 * bitwise where it ends alone on the first device; one with an unstable
 * step fails alone, named, while the others finish. */
START_TEST(batch_of_64)
{
  enum { COUNT = 64 };
  msocl_model *models[COUNT];
  for (int i = 0; i < COUNT; i++) {
    msocl_cloth_desc d;
    msocl_cloth_desc_init(&d);
    d.nx = 8;
    d.ny = 6 + i % 5;
    d.k_stretch = 500.0f + 10.0f * (float)i;
    ck_assert_int_eq(msocl_model_cloth_grid(&models[i], &d), MSOCL_OK);
    msocl_model_pin(models[i], 0, 1);
    msocl_model_pin(models[i], i % 8, 1);
  }
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 2e-4f;
  msocl_batch *b = NULL;
  ck_assert_int_eq(msocl_batch_create(&b, rt, COUNT,
                                      (const msocl_model *const *)models, &o),
                   MSOCL_OK);
  ck_assert_int_eq(msocl_batch_step(b, 300), MSOCL_OK);
  for (int i = 0; i < COUNT; i += 7) {
    msocl_sim *s = NULL, *alone = NULL;
    ck_assert_int_eq(msocl_batch_sim(b, i, &s), MSOCL_OK);
    msocl_device_info info;
    msocl_sim_device_info(s, &info);
    ck_assert_int_eq(msocl_sim_create(&alone, rt, models[i], &o), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(alone, 300), MSOCL_OK);
    float p[3 * 80], q[3 * 80];
    int n;
    msocl_sim_point_count(s, &n);
    msocl_sim_read_positions(s, p);
    msocl_sim_read_positions(alone, q);
    ck_assert(memcmp(p, q, 3 * (size_t)n * sizeof(float)) == 0);
    msocl_sim_destroy(alone);
  }
  msocl_batch_destroy(b);
  /* one unstable member */
  msocl_model_set_gravity(models[5], 0, 0, 0);
  msocl_model_destroy(models[9]);
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 8;
  d.k_stretch = 1e7f; /* far too stiff for dt = 2e-4 */
  msocl_model_cloth_grid(&models[9], &d);
  ck_assert_int_eq(msocl_batch_create(&b, rt, COUNT,
                                      (const msocl_model *const *)models, &o),
                   MSOCL_OK);
  ck_assert_int_eq(msocl_batch_step(b, 300), MSOCL_ERR_UNSTABLE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "batch simulation 9:"));
  msocl_sim *other = NULL;
  long long steps;
  msocl_batch_sim(b, 10, &other);
  msocl_sim_step_count(other, &steps);
  ck_assert_int_eq(steps, 300);
  msocl_batch_destroy(b);
  ck_assert_int_eq(msocl_batch_create(&b, rt, 0, NULL, &o),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_batch_create(&b, rt, 0,
                                      (const msocl_model *const *)models, &o),
                   MSOCL_ERR_BAD_COUNT);
  for (int i = 0; i < COUNT; i++)
    msocl_model_destroy(models[i]);
}
END_TEST

int main(void)
{
  /* three PoCL CPU devices unless the caller chose otherwise; must be set
   * before the first OpenCL call */
  setenv("POCL_DEVICES", "pthread pthread pthread", 0);
  scene_require_device("check_multidevice");
  ndev = scene_cpu_spec(spec, sizeof spec, 3);
  if (ndev < 2) {
    printf("check_multidevice: SKIP: needs two CPU devices (POCL_DEVICES="
           "\"pthread pthread\"), found %d\n", ndev);
    return 77;
  }
  printf("devices: %s\n", spec);
  Suite *su = suite_create("multidevice");
  TCase *tc = tcase_create("multidevice");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, tablecloth_500_steps, 0, 8);
  tcase_add_loop_test(tc, damped_hanging_cloth, 0, 8);
  tcase_add_loop_test(tc, kernels_then_copies, 0, 5);
  tcase_add_test(tc, uneven_weights);
  tcase_add_test(tc, grid_layout_split);
  tcase_add_test(tc, implicit_split);
  tcase_add_test(tc, narrower_than_halo);
  tcase_add_loop_test(tc, split_report_and_normals, 0, 2);
  tcase_add_test(tc, refused);
  tcase_add_test(tc, unstable_rolls_back);
  tcase_add_test(tc, batch_of_64);
  tcase_add_test(tc, device_without_images);
  tcase_add_test(tc, calibrated_weights);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

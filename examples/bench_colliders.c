/* msocl-bench colliders: what a collider costs. The tablecloth (a cloth
 * grid 5 cm above y = 0) with no collider, a floor plane, a sphere or the
 * round table - the sphere and table tops at y = 0, so the cloth lands on
 * them - per engine: GRID and BUFFER (both forced); and a capsule and a
 * box, at rest and moving (cap-mov, box-mov: a pose set before each call,
 * carried along x at 0.5 m/s, the box turning about y at 1 rad/s) beside
 * the same shapes at rest. The
 * scenes of an engine are timed in turn, --repeat rounds,
 * the fastest of each counting, so the ratios to "none" come from the same
 * moments of a noisy machine. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { ENGINES = 2, SCENES = 8 };
static const char *const engine_names[ENGINES] = {"grid", "buffer"};
static const char *const scene_names[SCENES] = {
    "none", "plane", "sphere", "table", "capsule", "box", "cap-mov", "box-mov"};

static msocl_model *build(int n, int scene)
{
  msocl_cloth_desc d;
  const float origin[3] = {-0.5f, TC_HEIGHT, -0.5f}, u[3] = {0, 0, 1},
              v[3] = {1, 0, 0};
  bench_cloth(&d, n, origin, u, v);
  msocl_model *m = NULL;
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK)
    return NULL;
  const float up[3] = {0.0f, 1.0f, 0.0f}, top[3] = {0.0f, 0.0f, 0.0f};
  const float centre[3] = {0.0f, -TC_RADIUS, 0.0f};
  int rc = msocl_model_set_viscous_damping(m, TC_VISCOUS_PER_MASS *
                                                  d.point_mass);
  if (rc == MSOCL_OK && scene == 1)
    rc = msocl_model_add_plane(m, up, 0.0f, TC_FRICTION);
  if (rc == MSOCL_OK && scene == 2)
    rc = msocl_model_add_sphere(m, centre, TC_RADIUS, TC_FRICTION);
  if (rc == MSOCL_OK && scene == 3)
    rc = msocl_model_add_table(m, top, TC_RADIUS, TC_FRICTION);
  /* a capsule along x and a box turned 30 degrees about y, their tops at
   * y = 0 */
  const float a[3] = {-0.3f, -TC_RADIUS, 0.0f}, b[3] = {0.3f, -TC_RADIUS, 0.0f};
  const float bc[3] = {0.0f, -0.05f, 0.0f}, q[4] = {0.0f, 0.258819f, 0.0f,
                                                    0.9659258f},
              h[3] = {TC_RADIUS, 0.05f, TC_RADIUS};
  if (rc == MSOCL_OK && (scene == 4 || scene == 6))
    rc = msocl_model_add_capsule(m, a, b, TC_RADIUS, TC_FRICTION);
  if (rc == MSOCL_OK && (scene == 5 || scene == 7))
    rc = msocl_model_add_box(m, bc, q, h, TC_FRICTION);
  if (rc != MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

/* The moving scenes' pose for the call that ends at time t. */
static int move(msocl_sim *s, int scene, double t)
{
  const float p[3] = {(float)(0.5 * t), scene == 6 ? -TC_RADIUS : -0.05f,
                      0.0f};
  const double a = 0.5235988 + 1.0 * t; /* 30 degrees, then 1 rad/s */
  const float ident[4] = {0.0f, 0.0f, 0.0f, 1.0f},
              q[4] = {0.0f, (float)sin(0.5 * a), 0.0f, (float)cos(0.5 * a)};
  return msocl_sim_set_collider_pose(s, 0, p, scene == 6 ? ident : q);
}

/* One engine on one grid: the scenes timed in turn. */
static int engine_rows(const struct bench_opts *o, msocl_runtime *rt,
                       FILE *csv, int n, int engine)
{
  const int steps = n > 128 ? o->big_steps : o->steps;
  msocl_sim *s[SCENES] = {0};
  double best[SCENES];
  int rc = MSOCL_OK;
  const int scenes = SCENES;
  for (int c = 0; c < scenes && rc == MSOCL_OK; c++) {
    msocl_model *m = build(n, c);
    msocl_sim_options so;
    msocl_sim_options_init(&so);
    so.dt = 1e-4f;
    so.tuning.layout = engine == 0 ? MSOCL_LAYOUT_GRID : MSOCL_LAYOUT_BUFFER;
    so.check_every = 0;
    rc = m ? msocl_sim_create(&s[c], rt, m, &so) : MSOCL_ERR_NO_MEMORY;
    msocl_model_destroy(m);
    if (rc == MSOCL_OK && c >= 6)
      rc = move(s[c], c, 1e-4);
    if (rc == MSOCL_OK)
      rc = msocl_sim_step(s[c], 1); /* warm-up */
    best[c] = INFINITY;
  }
  for (int rep = 0; rc == MSOCL_OK && rep < o->repeat; rep++)
    for (int c = 0; c < scenes && rc == MSOCL_OK; c++) {
      double t0 = bench_now();
      if (c >= 6)
        rc = move(s[c], c, 1e-4 * (1 + (rep + 1) * steps));
      if (rc == MSOCL_OK)
        rc = msocl_sim_step(s[c], steps);
      double t = bench_now() - t0;
      best[c] = t < best[c] ? t : best[c];
    }
  for (int c = 0; c < SCENES; c++)
    msocl_sim_destroy(s[c]);
  if (rc != MSOCL_OK) {
    printf("%4d^2 %-12s failed\n", n, engine_names[engine]);
    return bench_fail(engine_names[engine], rc);
  }
  for (int c = 0; c < scenes; c++) {
    struct bench_row r;
    bench_row_init(&r);
    bench_row_device(&r, rt);
    char label[32]; /* the CSV's layout column: engine+collider */
    snprintf(label, sizeof label, "%s+%s", engine_names[engine],
             scene_names[c]);
    r.layout = label;
    r.integrator = bench_integrator_names[0];
    r.math = "precise";
    r.grid = n;
    r.dt = 1e-4;
    r.steps = steps;
    r.seconds = best[c];
    r.status = "ok";
    bench_row_rates(&r);
    printf("%4d^2 %-12s %-7s %6d %8.3f %9.1f %10.4f %7.2fx", n,
           engine_names[engine], scene_names[c], steps, r.seconds,
           r.steps_per_s, r.vertex_steps_per_s / 1e9, best[c] / best[0]);
    if (c >= 6) /* the same shape at rest */
      printf("  %.2fx at rest", best[c] / best[c - 2]);
    printf("\n");
    bench_csv_row(csv, &r);
  }
  fflush(stdout);
  return 0;
}

int bench_colliders(const struct bench_opts *o, FILE *csv)
{
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  if (bench_open(o, &rt, &info))
    return 1;
  printf("msocl-bench colliders on %s [%s]: symplectic Euler, best of %d\n",
         info.name, info.platform_name, o->repeat);
  printf("%6s %-12s %-7s %6s %8s %9s %10s %8s\n", "size", "engine",
         "collider", "steps", "seconds", "steps/s", "Gpt-st/s", "time/none");
  int failed = 0;
  for (int g = 0; g < o->ngrids; g++)
    for (int e = 0; e < ENGINES; e++)
      failed |= engine_rows(o, rt, csv, o->grids[g], e);
  msocl_runtime_destroy(rt);
  return failed;
}

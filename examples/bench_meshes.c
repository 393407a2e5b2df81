/* msocl-bench meshes: the two meshes of issue 15 in BUFFER (forced) and
 * in what AUTO chooses, side by side: the soft ball (msocl_model_solid,
 * icosphere subdivisions from -g, default 6: 40 962 points) on the
 * ground, and a square cloth loaded from OBJ text (-g's second size,
 * default 256 points a side) dropped on the paper's round table. The
 * error column is the largest difference of the final positions from
 * BUFFER's: 0 where they agree bit for bit. */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { ENGINES = 2 };
static const char *const engine_names[ENGINES] = {"buffer", "auto"};

static msocl_model *ball(int subdivisions)
{
  msocl_solid_desc d;
  msocl_solid_desc_init(&d);
  d.subdivisions = subdivisions;
  msocl_model *m = NULL;
  const float up[3] = {0.0f, 1.0f, 0.0f};
  if (msocl_model_solid(&m, &d) != MSOCL_OK ||
      msocl_model_add_plane(m, up, 0.0f, 0.5f) != MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

/* An n x n cloth, 1 m a side, 5 cm over the table, as OBJ text: points,
 * then two triangles a quad; edge and bending springs. */
static msocl_model *obj_cloth(int n)
{
  const size_t cap = (size_t)n * n * 80 + 64;
  char *text = malloc(cap);
  if (!text)
    return NULL;
  size_t len = 0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      len += (size_t)snprintf(text + len, cap - len, "v %.6f 0.05 %.6f\n",
                              -0.5 + (double)i / (n - 1),
                              -0.5 + (double)j / (n - 1));
  for (int j = 0; j + 1 < n; j++)
    for (int i = 0; i + 1 < n; i++) {
      const int a = j * n + i + 1, b = a + 1, c = a + n, d = c + 1;
      len += (size_t)snprintf(text + len, cap - len,
                              "f %d %d %d\nf %d %d %d\n", a, c, b, b, c, d);
    }
  msocl_obj_desc od;
  msocl_obj_desc_init(&od);
  od.k_edge = 50.0f;
  od.k_bend = 5.0f;
  msocl_model *m = NULL;
  const float top[3] = {0.0f, 0.0f, 0.0f};
  int rc = msocl_model_from_obj_text(&m, text, len, &od);
  free(text);
  if (rc != MSOCL_OK || msocl_model_add_table(m, top, 0.35f, 0.3f) != MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

/* One engine's row; pos receives its final positions. Returns its steps
 * per second, 0 where it failed. */
static double run(const struct bench_opts *o, msocl_runtime *rt, FILE *csv,
                  const msocl_model *m, const char *scene, int size, int in,
                  int engine, const float *ref, float *pos, double ref_ips)
{
  struct bench_row r;
  bench_row_init(&r);
  bench_row_device(&r, rt);
  r.layout = engine_names[engine];
  r.integrator = bench_integrator_names[in];
  r.math = "precise";
  r.grid = size;
  int n = 0;
  msocl_model_point_count(m, &n);
  r.points = n;
  /* implicit Euler has no bound (+infinity): four times symplectic's */
  float dt = 1e-4f;
  msocl_safe_dt(m, (msocl_integrator)in, &dt);
  if (!isfinite(dt) && msocl_safe_dt(m, MSOCL_SYMPLECTIC_EULER, &dt) == MSOCL_OK)
    dt *= 4.0f;
  r.dt = dt;
  r.steps = o->steps;
  msocl_sim_options so;
  msocl_sim_options_init(&so);
  so.dt = dt;
  so.integrator = (msocl_integrator)in;
  so.tuning.layout = engine == 0 ? MSOCL_LAYOUT_BUFFER : MSOCL_LAYOUT_AUTO;
  so.check_every = 0;
  int rc = bench_time_sim(o, rt, m, &so, &r, pos, ref);
  r.status = rc == MSOCL_OK ? "ok" : "failed";
  if (rc != MSOCL_OK) {
    bench_fail(r.layout, rc);
    r.seconds = NAN;
  }
  bench_row_rates(&r);
  char ratio[16] = "-", err[16] = "-";
  if (ref_ips > 0 && r.steps_per_s > 0)
    snprintf(ratio, sizeof ratio, "%.2fx", r.steps_per_s / ref_ips);
  if (isfinite(r.error))
    snprintf(err, sizeof err, "%.1e", r.error);
  if (rc == MSOCL_OK)
    printf("%-6s %5d %7d %-10s %-14s %6lld %8.3f %9.1f %8s %8s\n", scene,
           size, n, r.integrator, r.layout, r.steps, r.seconds,
           r.steps_per_s, ratio, err);
  else
    printf("%-6s %5d %7d %-10s %-14s failed\n", scene, size, n,
           r.integrator, r.layout);
  fflush(stdout);
  bench_csv_row(csv, &r);
  return rc == MSOCL_OK ? r.steps_per_s : 0.0;
}

int bench_meshes(const struct bench_opts *o, FILE *csv)
{
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  if (bench_open(o, &rt, &info))
    return 1;
  printf("msocl-bench meshes on %s [%s]: %d steps, best of %d\n", info.name,
         info.platform_name, o->steps, o->repeat);
  printf("%-6s %5s %7s %-10s %-14s %6s %8s %9s %8s %8s\n", "scene", "size",
         "points", "integr.", "engine", "steps", "seconds", "steps/s",
         "/buffer", "vs buf");
  int failed = 0;
  for (int g = 0; g < 2 && g < o->ngrids; g++) {
    const int size = o->grids[g];
    const char *scene = g == 0 ? "ball" : "cloth";
    msocl_model *m = g == 0 ? ball(size) : obj_cloth(size);
    int n = 0;
    if (m)
      msocl_model_point_count(m, &n);
    float *ref = malloc(3 * (size_t)n * sizeof *ref),
          *pos = malloc(3 * (size_t)n * sizeof *pos);
    if (!m || !ref || !pos) {
      fprintf(stderr, "msocl-bench: the %s (%d): %s\n", scene, size,
              msocl_last_error());
      failed = 1;
    }
    for (int q = 0; m && ref && pos && q < o->nintegrators; q++) {
      const int in = o->integrators[q];
      double ref_ips = 0.0;
      for (int e = 0; e < ENGINES; e++) {
        double ips = run(o, rt, csv, m, scene, size, in, e,
                         ref_ips > 0 ? ref : NULL, e ? pos : ref, ref_ips);
        failed |= !(ips > 0);
        if (e == 0)
          ref_ips = ips;
      }
    }
    msocl_model_destroy(m);
    free(ref);
    free(pos);
  }
  msocl_runtime_destroy(rt);
  return failed;
}

/* msocl-bench lattice: the jello cube of the second seed, n x n x n points
 * (structural, face shear and bend springs with dashpots, on a floor),
 * per engine side by side in one run - BUFFER (the stored slots) and GRID
 * (its springs recomputed), both forced - for each integrator asked for.
 * The error column is the largest difference of GRID's final positions
 * from BUFFER's: 0 where the engines agree bit for bit. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { ENGINES = 2 };
static const char *const engine_names[ENGINES] = {"buffer", "grid"};

/* The library's cube, n points a side, resting just above the floor. */
static msocl_model *build(int n)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.nx = d.ny = d.nz = n;
  d.origin[0] = d.origin[2] = -0.5f * d.spacing * (float)(n - 1);
  d.origin[1] = 0.001f;
  msocl_model *m = NULL;
  const float up[3] = {0.0f, 1.0f, 0.0f};
  if (msocl_model_lattice(&m, &d) != MSOCL_OK ||
      msocl_model_add_plane(m, up, 0.0f, 0.5f) != MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

/* One engine: a row, printed and written; pos receives its final
 * positions. Returns its steps per second, 0 where it failed. */
static double run(const struct bench_opts *o, msocl_runtime *rt, FILE *csv,
                  const msocl_model *m, int n, int in, int engine,
                  const float *ref, float *pos, double ref_ips)
{
  struct bench_row r;
  bench_row_init(&r);
  bench_row_device(&r, rt);
  r.layout = engine_names[engine];
  r.integrator = bench_integrator_names[in];
  r.math = "precise";
  r.grid = n;
  r.points = (long long)n * n * n;
  r.dt = 1e-4;
  r.steps = o->steps;
  msocl_sim_options so;
  msocl_sim_options_init(&so);
  so.dt = (float)r.dt;
  so.integrator = (msocl_integrator)in;
  so.tuning.layout = engine ? MSOCL_LAYOUT_GRID : MSOCL_LAYOUT_BUFFER;
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
    printf("%3d^3 %-10s %-12s %6lld %8.3f %9.1f %10.4f %8s %8s\n", n,
           r.integrator, r.layout, r.steps, r.seconds, r.steps_per_s,
           r.vertex_steps_per_s / 1e9, ratio, err);
  else
    printf("%3d^3 %-10s %-12s failed\n", n, r.integrator, r.layout);
  fflush(stdout);
  bench_csv_row(csv, &r);
  return rc == MSOCL_OK ? r.steps_per_s : 0.0;
}

int bench_lattice(const struct bench_opts *o, FILE *csv)
{
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  if (bench_open(o, &rt, &info))
    return 1;
  printf("msocl-bench lattice on %s [%s]: %d steps, best of %d\n", info.name,
         info.platform_name, o->steps, o->repeat);
  printf("%5s %-10s %-12s %6s %8s %9s %10s %8s %8s\n", "size", "integr.",
         "engine", "steps", "seconds", "steps/s", "Gpt-st/s", "/buffer",
         "vs buf");
  int failed = 0;
  for (int g = 0; g < o->ngrids; g++) {
    const int n = o->grids[g];
    msocl_model *m = build(n);
    const size_t floats = 3 * (size_t)n * n * n;
    float *ref = malloc(floats * sizeof *ref), *pos = malloc(floats * sizeof *pos);
    if (!m || !ref || !pos) {
      fprintf(stderr, "msocl-bench: a %d^3 lattice: %s\n", n,
              msocl_last_error());
      failed = 1;
    }
    for (int q = 0; !failed && q < o->nintegrators; q++) {
      const int in = o->integrators[q];
      double ref_ips = 0.0;
      for (int e = 0; e < ENGINES; e++) {
        /* BUFFER first: the others are compared with its rate and result */
        double ips = run(o, rt, csv, m, n, in, e, ref_ips > 0 ? ref : NULL,
                         e ? pos : ref, ref_ips);
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

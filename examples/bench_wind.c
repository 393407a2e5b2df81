/* msocl-bench wind: a flag (an n x n cloth, 1 m a side, hanging from its
 * two top corners) with no wind, in a 5 m/s wind with lift, and under a
 * user's field of forces, side by side in each repeat, on the default
 * engine (AUTO: GRID); the ratios are wind's and the
 * field's cost a step. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>

static msocl_model *flag(int n)
{
  msocl_cloth_desc d;
  const float origin[3] = {0, 0, 0}, u[3] = {1, 0, 0}, v[3] = {0, -1, 0};
  bench_cloth(&d, n, origin, u, v);
  msocl_model *m = NULL;
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK ||
      msocl_model_pin(m, 0, 1) != MSOCL_OK ||
      msocl_model_pin(m, n - 1, 1) != MSOCL_OK ||
      msocl_model_set_viscous_damping(m, TC_VISCOUS_PER_MASS * d.point_mass) !=
          MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

enum { KINDS = 3 }; /* none, wind, field */

/* Each sim's best time of o->steps over o->repeat rounds, one after the
 * other in each round. */
static int time_all(const struct bench_opts *o, msocl_sim *const s[KINDS],
                    double best[KINDS])
{
  for (int w = 0; w < KINDS; w++)
    best[w] = INFINITY;
  for (int rep = 0; rep < o->repeat; rep++)
    for (int w = 0; w < KINDS; w++) {
      const double t0 = bench_now();
      const int rc = msocl_sim_step(s[w], o->steps);
      const double t = bench_now() - t0;
      if (rc != MSOCL_OK)
        return rc;
      best[w] = t < best[w] ? t : best[w];
    }
  return MSOCL_OK;
}

int bench_wind(const struct bench_opts *o, FILE *csv)
{
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  if (bench_open(o, &rt, &info))
    return 1;
  printf("msocl-bench wind on %s [%s]: %d steps, best of %d\n", info.name,
         info.platform_name, o->steps, o->repeat);
  printf("%5s %-8s %8s %9s %8s\n", "grid", "wind", "seconds", "steps/s",
         "/none");
  msocl_wind wind;
  msocl_wind_init(&wind);
  wind.velocity[2] = 5.0f;
  wind.lift = 0.5f;
  int failed = 0;
  for (int g = 0; !failed && g < o->ngrids; g++) {
    const int n = o->grids[g];
    msocl_model *m = flag(n);
    msocl_sim_options so;
    msocl_sim_options_init(&so);
    so.dt = 1e-4f;
    so.check_every = 0;
    so.tuning.sweep_steps = o->sweep_steps;
    msocl_sim *s[KINDS] = {NULL, NULL, NULL};
    int rc = m ? MSOCL_OK : MSOCL_ERR_BAD_VALUE;
    for (int w = 0; rc == MSOCL_OK && w < KINDS; w++)
      rc = msocl_sim_create(&s[w], rt, m, &so);
    if (rc == MSOCL_OK)
      rc = msocl_sim_set_wind(s[1], &wind);
    float *field = rc == MSOCL_OK ? malloc(3 * (size_t)n * n * sizeof *field)
                                  : NULL;
    if (rc == MSOCL_OK && !field)
      rc = MSOCL_ERR_NO_MEMORY;
    for (int i = 0; rc == MSOCL_OK && i < 3 * n * n; i++)
      field[i] = i % 3 == 2 ? 1e-3f * (float)(i % 7) / (float)(n * n) : 0.0f;
    if (rc == MSOCL_OK)
      rc = msocl_sim_set_forces(s[2], field);
    free(field);
    for (int w = 0; rc == MSOCL_OK && w < KINDS; w++)
      rc = msocl_sim_step(s[w], 1); /* warm-up */
    double best[KINDS];
    if (rc == MSOCL_OK)
      rc = time_all(o, s, best);
    if (rc != MSOCL_OK) {
      failed = bench_fail("wind", rc);
    } else {
      const char *kinds[KINDS] = {"none", "wind", "field"};
      for (int w = 0; w < KINDS; w++) {
        struct bench_row r;
        bench_row_init(&r);
        bench_row_device(&r, rt);
        r.layout = kinds[w];
        r.integrator = bench_integrator_names[0];
        r.math = "precise";
        r.grid = n;
        r.dt = so.dt;
        r.steps = o->steps;
        r.seconds = best[w];
        r.status = "ok";
        bench_row_rates(&r);
        printf("%5d %-8s %8.3f %9.1f %7.2fx\n", n, r.layout, r.seconds,
               r.steps_per_s, best[w] / best[0]);
        bench_csv_row(csv, &r);
      }
      fflush(stdout);
    }
    for (int w = 0; w < KINDS; w++)
      msocl_sim_destroy(s[w]);
    msocl_model_destroy(m);
  }
  msocl_runtime_destroy(rt);
  return failed;
}

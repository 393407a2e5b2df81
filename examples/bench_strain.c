/* msocl-bench strain: what strain limiting costs against how well it
 * limits. A soft tablecloth (ten times softer than the paper's: it
 * stretches 37% draped over the table unlimited) falls for -T seconds at
 * half symplectic Euler's stable step, unlimited and with each strain
 * limit at each sweep count asked for (--sweeps), with each integrator
 * asked for that the limit runs with. The error column is the largest
 * strain (length / rest - 1) of any spring at the end, for a 10% limit;
 * runs that blow up are marked unstable. The library picks the layout
 * (GRID). */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LIMIT 0.1f

/* The soft tablecloth of tests/check_strain at n x n points. */
static msocl_model *build(int n)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = n;
  const float origin[3] = {-0.5f, TC_HEIGHT, -0.5f}, u[3] = {0, 0, 1},
              v[3] = {1, 0, 0};
  for (int c = 0; c < 3; c++) {
    d.origin[c] = origin[c];
    d.u[c] = u[c];
    d.v[c] = v[c];
  }
  d.point_mass = TC_MASS / (float)(n * n);
  d.k_stretch = TC_K_STRETCH / 10.0f;
  d.k_shear = d.k_bend = TC_K_SHEAR / 10.0f;
  msocl_model *m = NULL;
  const float top[3] = {0.0f, 0.0f, 0.0f};
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK ||
      msocl_model_add_table(m, top, TC_RADIUS, TC_FRICTION) != MSOCL_OK ||
      msocl_model_set_viscous_damping(m, TC_VISCOUS_PER_MASS *
                                             d.point_mass) != MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

/* The largest strain over the cloth builder's springs (structural, shear
 * and bend between grid neighbours, resting at the spacing times 1, sqrt 2
 * and 2); NaN where a position is not finite. */
static double max_strain(const float *p, int n)
{
  static const int off[6][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}, {2, 0},
                                {0, 2}};
  const double h = 1.0 / (n - 1), rest[6] = {h, h, h * sqrt(2.0),
                                             h * sqrt(2.0), 2 * h, 2 * h};
  double worst = 0.0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      for (int s = 0; s < 6; s++) {
        const int i2 = i + off[s][0], j2 = j + off[s][1];
        if (i2 < 0 || i2 >= n || j2 < 0 || j2 >= n)
          continue;
        const float *a = p + 3 * (j * n + i), *b = p + 3 * (j2 * n + i2);
        double d2 = 0.0;
        for (int c = 0; c < 3; c++)
          d2 += ((double)b[c] - a[c]) * ((double)b[c] - a[c]);
        const double st = sqrt(d2) / rest[s] - 1.0;
        if (!isfinite(st))
          return NAN;
        worst = st > worst ? st : worst;
      }
  return worst;
}

static const char *const kind_names[3] = {"none", "provot", "velocity"};

/* Whether the library runs strain limit `kind` with integrator `in`: the
 * velocity kind needs symplectic or implicit Euler (whose position update
 * uses the new velocity); Provot's runs after any. */
static int runs(int kind, int in)
{
  if (kind == MSOCL_STRAIN_VELOCITY)
    return in == MSOCL_SYMPLECTIC_EULER || in == MSOCL_IMPLICIT_EULER;
  return 1;
}

/* One run: a row, printed and written. Returns 0 where it ran (stable or
 * not), 1 where the library failed otherwise. */
static int run(const struct bench_opts *o, msocl_runtime *rt, FILE *csv,
               const msocl_model *m, int n, float dt, int in, int kind,
               int sweeps, float *pos)
{
  struct bench_row r;
  bench_row_init(&r);
  bench_row_device(&r, rt);
  r.integrator = bench_integrator_names[in];
  r.math = "precise";
  r.grid = n;
  r.dt = dt;
  r.steps = (long long)ceil(o->sim_time / dt);
  r.strain = kind_names[kind];
  r.sweeps = kind ? sweeps : 0;
  msocl_sim_options so;
  msocl_sim_options_init(&so);
  so.dt = dt;
  so.integrator = (msocl_integrator)in;
  so.strain = (msocl_strain)kind;
  so.strain_limit = LIMIT;
  so.strain_iterations = kind ? sweeps : 1;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &so);
  if (rc == MSOCL_OK) {
    msocl_layout lay = MSOCL_LAYOUT_AUTO;
    msocl_sim_layout(s, &lay);
    r.layout = lay == MSOCL_LAYOUT_GRID ? "grid" : "buffer";
    rc = msocl_sim_step(s, 1); /* warm-up: PoCL builds kernels at first use */
  }
  r.seconds = INFINITY;
  /* each repeat from the start: the model's positions, at rest */
  for (int rep = 0; rc == MSOCL_OK && rep < o->repeat; rep++) {
    rc = msocl_model_get_positions(m, pos);
    if (rc == MSOCL_OK)
      rc = msocl_sim_write_positions(s, pos);
    memset(pos, 0, 3 * (size_t)n * n * sizeof *pos);
    if (rc == MSOCL_OK)
      rc = msocl_sim_write_velocities(s, pos);
    if (rc != MSOCL_OK)
      break;
    double t0 = bench_now();
    rc = msocl_sim_step(s, (int)r.steps);
    double t = bench_now() - t0;
    r.seconds = t < r.seconds ? t : r.seconds;
    if (rc == MSOCL_OK)
      rc = msocl_sim_read_positions(s, pos);
  }
  msocl_sim_destroy(s);
  if (rc == MSOCL_OK) {
    r.error = max_strain(pos, n);
    r.status = isfinite(r.error) ? "ok" : "nonfinite";
  } else {
    r.status = rc == MSOCL_ERR_UNSTABLE ? "unstable" : "failed";
    if (rc != MSOCL_ERR_UNSTABLE)
      bench_fail(r.integrator, rc);
    r.seconds = NAN;
  }
  bench_row_rates(&r);
  char sw[8] = "-", st[16] = "-", per[16] = "-";
  if (kind)
    snprintf(sw, sizeof sw, "%d", sweeps);
  if (isfinite(r.error))
    snprintf(st, sizeof st, "%.2f%%", 100.0 * r.error);
  if (isfinite(r.seconds))
    snprintf(per, sizeof per, "%.3f", r.seconds / (r.steps * r.dt));
  printf("%4d^2 %-10s %-8s %6s %-11s %6lld %10s %10s %s\n", n, r.integrator,
         r.strain, sw, r.layout, r.steps, per, st, r.status);
  fflush(stdout);
  bench_csv_row(csv, &r);
  return rc != MSOCL_OK && rc != MSOCL_ERR_UNSTABLE;
}

int bench_strain(const struct bench_opts *o, FILE *csv)
{
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  if (bench_open(o, &rt, &info))
    return 1;
  printf("msocl-bench strain on %s [%s]: soft tablecloth, %.2f s simulated "
         "at half the stable step, limit %.0f%%, best of %d\n",
         info.name, info.platform_name, o->sim_time, 100.0 * LIMIT,
         o->repeat);
  printf("%6s %-10s %-8s %6s %-11s %6s %10s %10s %s\n", "grid", "integr.",
         "limit", "sweeps", "layout", "steps", "s/sim-s", "strain",
         "status");
  int failed = 0;
  for (int g = 0; g < o->ngrids; g++) {
    const int n = o->grids[g];
    msocl_model *m = build(n);
    float *pos = malloc(3 * (size_t)n * n * sizeof *pos);
    float dt = 0.0f;
    if (!m || !pos ||
        msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt) != MSOCL_OK) {
      fprintf(stderr, "msocl-bench: a %d^2 cloth: %s\n", n,
              msocl_last_error());
      failed = 1;
    }
    dt *= 0.5f;
    for (int q = 0; !failed && q < o->nintegrators; q++) {
      const int in = o->integrators[q];
      for (int kind = 0; !failed && kind < 3; kind++) {
        if (!runs(kind, in))
          continue;
        for (int w = 0; !failed && w < (kind ? o->nsweeps : 1); w++)
          failed |= run(o, rt, csv, m, n, dt, in, kind, o->sweeps[w], pos);
      }
    }
    msocl_model_destroy(m);
    free(pos);
  }
  msocl_runtime_destroy(rt);
  return failed;
}

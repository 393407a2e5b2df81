/* precision: work-precision data. A cloth hanging from two corners (no
 * contact, dashpot damping) falls and swings for T seconds; every
 * integrator and math mode runs it over a sweep of time steps, and each
 * run's RMS position error at T against a double-precision RK4 reference
 * at a much smaller step is set against its wall time per simulated
 * second. Runs that blow up are kept, as "unstable" with error inf. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CLOTH_SIZE 1.0 /* m: errors are relative to it */
#define HANG_DAMPING 2e-3f /* dashpot on every spring, N s/m */
#define CHECK_EVERY 50
#define MIN_TIME 0.3 /* s: short runs repeat until this, the best counts */
#define MAX_REPS 10

msocl_model *bench_hanging_cloth(int n)
{
  msocl_cloth_desc d;
  const float origin[3] = {-0.5f, 0.0f, -0.5f}, u[3] = {1, 0, 0},
              v[3] = {0, 0, 1};
  bench_cloth(&d, n, origin, u, v);
  d.damping = HANG_DAMPING;
  msocl_model *m = NULL;
  int rc = msocl_model_cloth_grid(&m, &d);
  if (rc == MSOCL_OK)
    rc = msocl_model_pin(m, 0, 1);
  if (rc == MSOCL_OK)
    rc = msocl_model_pin(m, n - 1, 1);
  if (rc != MSOCL_OK) {
    bench_fail("building the hanging cloth", rc);
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

static double rms_error(const float *xyz, const double *ref, int n)
{
  double sum = 0.0;
  for (int i = 0; i < 3 * n; i++) {
    double d = (double)xyz[i] - ref[i];
    sum += d * d;
  }
  return sqrt(sum / n) / CLOTH_SIZE;
}

/* The reference: RK4 in double, `steps` steps of dt; *xyz gets the final
 * positions (3n doubles, the caller frees). */
static int reference(const msocl_model *m, float dt, long long steps, int n,
                     double **xyz, double *secs)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.integrator = MSOCL_RK4;
  msocl_reference *r = NULL;
  *xyz = malloc(3 * (size_t)n * sizeof **xyz);
  if (!*xyz)
    return MSOCL_ERR_NO_MEMORY;
  double t0 = bench_now();
  int rc = msocl_reference_create(&r, m, &o);
  for (long long done = 0; rc == MSOCL_OK && done < steps; done += 1 << 20)
    rc = msocl_reference_step(r, steps - done < 1 << 20 ? (int)(steps - done)
                                                        : 1 << 20);
  if (rc == MSOCL_OK)
    rc = msocl_reference_positions(r, *xyz);
  *secs = bench_now() - t0;
  msocl_reference_destroy(r);
  if (rc != MSOCL_OK) {
    free(*xyz);
    *xyz = NULL;
  }
  return rc;
}

struct run {
  const msocl_model *m;
  msocl_runtime *rt;
  const float *x0, *v0; /* initial state */
  const double *ref;
  int n;
};

/* One timed run: the state is reset, `steps` steps of dt; a short run
 * repeats and the fastest counts. r->steps holds the steps simulated. */
static int timed(const struct run *u, msocl_sim *s, int steps,
                 struct bench_row *r, float *xyz)
{
  double best = INFINITY, total = 0.0;
  int rc = MSOCL_OK;
  for (int rep = 0; rep < MAX_REPS && total < MIN_TIME; rep++) {
    long long before = 0, after = 0;
    rc = msocl_sim_write_positions(s, u->x0);
    if (rc == MSOCL_OK)
      rc = msocl_sim_write_velocities(s, u->v0);
    if (rc == MSOCL_OK)
      rc = msocl_sim_step_count(s, &before);
    if (rc != MSOCL_OK)
      return rc;
    double t0 = bench_now();
    rc = msocl_sim_step(s, steps);
    double t = bench_now() - t0;
    if (rc == MSOCL_ERR_UNSTABLE) {
      /* caught at the check after the failing batch; state restored to
       * the batch's start */
      msocl_sim_step_count(s, &after);
      long long done = after - before;
      r->steps = done + (steps - done < CHECK_EVERY ? steps - done
                                                    : CHECK_EVERY);
      r->seconds = t;
      r->error = INFINITY;
      r->status = "unstable";
      return MSOCL_OK;
    }
    if (rc != MSOCL_OK)
      return rc;
    best = t < best ? t : best;
    total += t;
  }
  r->steps = steps;
  r->seconds = best;
  rc = msocl_sim_read_positions(s, xyz);
  if (rc == MSOCL_OK) {
    r->error = rms_error(xyz, u->ref, u->n);
    r->status = isfinite(r->error) ? "ok" : "nonfinite";
  }
  return rc;
}

static const char *const layout_label[] = {"auto", "image2d", "buffer",
                                           "edges", "grid"};

int bench_precision(const struct bench_opts *o, FILE *csv)
{
  int g = o->grids[0];
  msocl_runtime *rt = NULL;
  msocl_model *m = bench_hanging_cloth(g);
  if (!m)
    return 1;
  int n = g * g, ndev = 0, rc;
  float *x0 = malloc(3 * (size_t)n * sizeof *x0);
  float *v0 = calloc(3 * (size_t)n, sizeof *v0);
  float *xyz = malloc(3 * (size_t)n * sizeof *xyz);
  double *ref = NULL, *ref2 = NULL;
  float stable = 0.0f;
  if (!x0 || !v0 || !xyz) {
    rc = MSOCL_ERR_NO_MEMORY;
    bench_fail("precision", rc);
    goto out;
  }
  msocl_model_get_positions(m, x0);
  if ((rc = msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &stable)) !=
      MSOCL_OK) {
    bench_fail("stable step", rc);
    goto out;
  }
  /* Steps are powers of two, so every dt and the simulated time are exact
   * in float: the largest dt0 = 2^-k at most `from` times the stable
   * step, so the explicit methods' failures show on the chart too. */
  double dt0 = ldexp(1.0, (int)floor(log2(o->from * stable)));
  long long n0 = (long long)ceil(o->sim_time / dt0 - 1e-9);
  if (n0 < 1)
    n0 = 1;
  double T = (double)n0 * dt0;
  printf("msocl-bench precision (libmsocl %s): %dx%d cloth (1 m, %.2g kg, "
         "springs %g/%g/%g N/m,\ndashpots %g N s/m) held at two corners, "
         "falling from flat for T = %g s, no contact;\nsymplectic stable "
         "step %.3g s (Gershgorin); dt from %.3g s halving %d times; blow-up "
         "check every %d steps\n",
         msocl_version_string(), g, g, (double)TC_MASS,
         (double)TC_K_STRETCH, (double)TC_K_SHEAR, (double)TC_K_BEND,
         (double)HANG_DAMPING, T, (double)stable, dt0, o->levels - 1,
         CHECK_EVERY);

  /* The reference, and the same at half its step to show it converged. */
  long long nref = n0 << (o->levels);
  double rsecs = 0.0, rsecs2 = 0.0;
  bench_progress(1, 2, "double RK4 reference, %lld steps", nref);
  rc = reference(m, (float)(dt0 / (double)(1LL << o->levels)), nref, n, &ref,
                 &rsecs);
  bench_progress(2, 2, "double RK4 reference, %lld steps", 2 * nref);
  if (rc == MSOCL_OK)
    rc = reference(m, (float)(dt0 / (double)(1LL << (o->levels + 1))),
                   2 * nref, n, &ref2, &rsecs2);
  bench_progress(0, 0, " ");
  if (rc != MSOCL_OK) {
    bench_fail("reference", rc);
    goto out;
  }
  double conv = 0.0;
  for (int i = 0; i < 3 * n; i++)
    conv += (ref[i] - ref2[i]) * (ref[i] - ref2[i]);
  conv = sqrt(conv / n) / CLOTH_SIZE;
  printf("reference: double RK4, dt %.3g s (%lld steps, %.1f s); against dt "
         "%.3g s: RMS difference %.2e (relative to 1 m)\n\n",
         dt0 / (double)(1LL << o->levels), nref, rsecs,
         dt0 / (double)(1LL << (o->levels + 1)), conv);
  struct bench_row rr;
  bench_row_init(&rr);
  snprintf(rr.device, sizeof rr.device, "host double reference");
  rr.layout = "host";
  rr.integrator = "rk4";
  rr.math = "double";
  rr.grid = g;
  rr.dt = dt0 / (double)(1LL << o->levels);
  rr.steps = nref;
  rr.seconds = rsecs;
  rr.error = conv;
  rr.status = "reference";
  bench_row_rates(&rr);
  bench_csv_row(csv, &rr);

  if ((rc = msocl_runtime_create(&rt, o->spec)) != MSOCL_OK) {
    bench_fail("choosing devices", rc);
    goto out;
  }
  msocl_runtime_device_count(rt, &ndev);
  struct run u = {m, rt, x0, v0, ref, n};
  int total = ndev * o->nlayouts * o->nintegrators * o->nmaths * o->levels;
  int done = 0;
  printf("%-24s %-8s %-10s %-7s %10s %7s %9s %9s %9s %5s %s\n", "device",
         "layout", "integrator", "math", "dt", "steps", "time s", "s/sim-s",
         "error", "order", "status");
  for (int d = 0; d < ndev; d++) {
    msocl_device_info info;
    msocl_runtime_device_info(rt, d, &info);
    for (int l = 0; l < o->nlayouts; l++)
      for (int it = 0; it < o->nintegrators; it++)
        for (int k = 0; k < o->nmaths; k++) {
          double prev = NAN;
          for (int lv = 0; lv < o->levels; lv++) {
            struct bench_row r;
            bench_row_init(&r);
            bench_device_label(r.device, sizeof r.device, &info);
            r.layout = layout_label[o->layouts[l]];
            r.integrator = bench_integrator_names[o->integrators[it]];
            r.math = o->maths[k] == MSOCL_MATH_RELAXED ? "relaxed" : "precise";
            r.grid = g;
            r.dt = dt0 / (double)(1LL << lv);
            long long steps = n0 << lv;
            bench_progress(++done, total, "%s %s dt=%.3g, %lld steps",
                           r.integrator, r.math, r.dt, steps);
            msocl_sim_options so;
            msocl_sim_options_init(&so);
            so.dt = (float)r.dt;
            so.tuning.layout = (msocl_layout)o->layouts[l];
            so.math = (msocl_math)o->maths[k];
            so.integrator = (msocl_integrator)o->integrators[it];
            so.tuning.device = d;
            so.check_every = CHECK_EVERY;
            msocl_sim *s = NULL;
            int e = steps > 1 << 30 ? MSOCL_ERR_TOO_MANY
                                    : msocl_sim_create(&s, rt, m, &so);
            if (e == MSOCL_OK)
              e = msocl_sim_step(s, 1); /* warm-up, then reset */
            if (e == MSOCL_ERR_UNSTABLE)
              e = MSOCL_OK; /* the timed run records it */
            if (e == MSOCL_OK)
              e = timed(&u, s, (int)steps, &r, xyz);
            int cg = 0;
            double res = 0.0;
            if (e == MSOCL_OK && so.integrator == MSOCL_IMPLICIT_EULER)
              msocl_sim_solver_stats(s, &cg, &res);
            msocl_sim_destroy(s);
            bench_progress(0, 0, " ");
            if (e != MSOCL_OK) {
              bench_fail(r.integrator, e);
              r.status = "failed";
              r.steps = steps;
            }
            bench_row_rates(&r);
            bench_csv_row(csv, &r);
            char order[16] = "", status[48];
            if (isfinite(prev) && isfinite(r.error) && r.error > 0)
              snprintf(order, sizeof order, "%.2f", log2(prev / r.error));
            prev = r.error;
            snprintf(status, sizeof status, "%s", r.status);
            if (cg > 0)
              snprintf(status, sizeof status, "%s (CG %d it)", r.status, cg);
            printf("%-24.24s %-8s %-10s %-7s %10.4g %7lld %9.4f %9.4f %9.3g "
                   "%5s %s\n",
                   r.device, r.layout, r.integrator, r.math, r.dt, r.steps,
                   r.seconds, r.seconds / ((double)r.steps * r.dt), r.error,
                   order, status);
            fflush(stdout);
          }
        }
  }
out:
  free(ref);
  free(ref2);
  free(x0);
  free(v0);
  free(xyz);
  msocl_model_destroy(m);
  msocl_runtime_destroy(rt);
  return rc == MSOCL_OK ? 0 : 1;
}

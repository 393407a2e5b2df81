/* verify: the test suite's checks of a device against the double host
 * reference, for a machine that cannot run `make check` (the GPU machine
 * has no Check): each scene runs on the device and in msocl_reference,
 * and the largest position difference must stay within the tolerance the
 * tests state for it. --save writes each check's final positions, so
 * that a run on another device (--against) is compared with them too:
 * two devices each within tol of the reference are within 2 tol of each
 * other. Exit status 1 when a check fails. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum scene { HANGING, TABLECLOTH };

struct check {
  enum scene scene;
  int n;
  msocl_layout layout;
  msocl_integrator integrator;
  msocl_math math;
  float dt; /* 0: the tablecloth's half stable step */
  int steps;
  double tol; /* m, as the test states it */
  const char *test;
};

/* The tests' tolerances: check_accuracy's 1e-4 after 1 s of the hanging
 * cloth at 1 ms, 1e-4 with contact after 300 steps, 1e-3 in relaxed
 * math; check_integrators' 1e-5 for every integrator after 300 steps of
 * 0.1 ms. */
static const struct check checks[] = {
#define LAYOUT(l)                                                             \
  {HANGING, 16, l, MSOCL_SYMPLECTIC_EULER, MSOCL_MATH_PRECISE, 1e-3f, 1000,   \
   1e-4, "check_accuracy"}
    LAYOUT(MSOCL_LAYOUT_AUTO), LAYOUT(MSOCL_LAYOUT_IMAGE2D),
    LAYOUT(MSOCL_LAYOUT_BUFFER), LAYOUT(MSOCL_LAYOUT_EDGES),
    LAYOUT(MSOCL_LAYOUT_GRID),
#undef LAYOUT
#define INTEGRATOR(l, i)                                                      \
  {HANGING, 12, l, i, MSOCL_MATH_PRECISE, 1e-4f, 300, 1e-5,                   \
   "check_integrators"}
    INTEGRATOR(MSOCL_LAYOUT_BUFFER, MSOCL_EXPLICIT_EULER),
    INTEGRATOR(MSOCL_LAYOUT_BUFFER, MSOCL_VERLET),
    INTEGRATOR(MSOCL_LAYOUT_BUFFER, MSOCL_RK4),
    INTEGRATOR(MSOCL_LAYOUT_BUFFER, MSOCL_IMPLICIT_EULER),
    INTEGRATOR(MSOCL_LAYOUT_GRID, MSOCL_EXPLICIT_EULER),
    INTEGRATOR(MSOCL_LAYOUT_GRID, MSOCL_VERLET),
    INTEGRATOR(MSOCL_LAYOUT_GRID, MSOCL_RK4),
    INTEGRATOR(MSOCL_LAYOUT_GRID, MSOCL_IMPLICIT_EULER),
#undef INTEGRATOR
    {TABLECLOTH, 24, MSOCL_LAYOUT_BUFFER, MSOCL_SYMPLECTIC_EULER,
     MSOCL_MATH_PRECISE, 0.0f, 300, 1e-4, "check_accuracy"},
    {TABLECLOTH, 24, MSOCL_LAYOUT_GRID, MSOCL_SYMPLECTIC_EULER,
     MSOCL_MATH_PRECISE, 0.0f, 300, 1e-4, "check_accuracy"},
    {HANGING, 16, MSOCL_LAYOUT_BUFFER, MSOCL_SYMPLECTIC_EULER,
     MSOCL_MATH_RELAXED, 1e-3f, 1000, 1e-3, "check_accuracy"},
};
enum { NCHECKS = sizeof checks / sizeof checks[0] };

static const char *const layout_name[] = {"auto", "image2d", "buffer",
                                          "edges", "grid"};

static void check_name(char *out, size_t size, const struct check *c,
                       int steps)
{
  snprintf(out, size, "%s%d-%s-%s-%s-%d",
           c->scene == HANGING ? "hanging" : "tablecloth", c->n,
           layout_name[c->layout], bench_integrator_names[c->integrator],
           c->math == MSOCL_MATH_PRECISE ? "precise" : "relaxed", steps);
}

/* FILE's line for `name` (a name, the float count, the floats in %a) into
 * out (count floats): 0, or -1 if it has none such. */
static int load_saved(const char *file, const char *name, float *out,
                      int count)
{
  FILE *f = fopen(file, "r");
  if (!f)
    return -1;
  char word[128];
  int k, found = -1;
  while (found < 0 && fscanf(f, "%127s %d", word, &k) == 2) {
    int match = !strcmp(word, name) && k == count;
    for (int i = 0; i < k; i++) {
      float v;
      if (fscanf(f, "%a", &v) != 1)
        break;
      if (match)
        out[i] = v;
      if (match && i == k - 1)
        found = 0;
    }
  }
  fclose(f);
  return found;
}

static void save(FILE *f, const char *name, const float *p, int count)
{
  fprintf(f, "%s %d", name, count);
  for (int i = 0; i < count; i++)
    fprintf(f, " %a", p[i]);
  fputc('\n', f);
}

/* One check: device and reference from the same model and options, the
 * largest difference into *diff and how far the reference moved into
 * *travel; positions left in p. */
static int run_check(msocl_runtime *rt, const struct check *c, int steps,
                     float *p, double *q, double *diff, double *travel,
                     float *dt_used)
{
  float dt = c->dt;
  msocl_model *m = c->scene == HANGING ? bench_hanging_cloth(c->n)
                                       : bench_tablecloth(c->n, &dt);
  if (!m)
    return MSOCL_ERR_BAD_VALUE;
  *dt_used = dt;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.integrator = c->integrator;
  o.math = c->math;
  o.cg_tolerance = 1e-6f;
  o.tuning.layout = c->layout;
  msocl_sim *s = NULL;
  msocl_reference *r = NULL;
  const int count = 3 * c->n * c->n;
  float *p0 = malloc((size_t)count * sizeof *p0);
  int rc = p0 ? msocl_model_get_positions(m, p0) : MSOCL_ERR_NO_MEMORY;
  if (rc == MSOCL_OK)
    rc = msocl_sim_create(&s, rt, m, &o);
  if (rc == MSOCL_OK)
    rc = msocl_reference_create(&r, m, &o);
  if (rc == MSOCL_OK)
    rc = msocl_sim_step(s, steps);
  if (rc == MSOCL_OK)
    rc = msocl_reference_step(r, steps);
  if (rc == MSOCL_OK)
    rc = msocl_sim_read_positions(s, p);
  if (rc == MSOCL_OK)
    rc = msocl_reference_positions(r, q);
  *diff = *travel = 0.0;
  for (int i = 0; rc == MSOCL_OK && i < count; i++) {
    const double d = fabs((double)p[i] - q[i]), t = fabs(q[i] - p0[i]);
    *diff = d > *diff || isnan(d) ? d : *diff;
    *travel = t > *travel ? t : *travel;
  }
  free(p0);
  msocl_reference_destroy(r);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  return rc;
}

int bench_verify(const struct bench_opts *o, FILE *csv)
{
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  if (bench_open(o, &rt, &info))
    return 1;
  char device[128];
  bench_device_label(device, sizeof device, &info);
  /* a file to compare with that cannot be read is an error, not a
   * column of "not saved" */
  FILE *in = o->against ? fopen(o->against, "r") : NULL;
  if (o->against && !in) {
    perror(o->against);
    msocl_runtime_destroy(rt);
    return 1;
  }
  if (in)
    fclose(in);
  FILE *out = NULL;
  if (o->save && !(out = fopen(o->save, "w"))) {
    perror(o->save);
    msocl_runtime_destroy(rt);
    return 1;
  }
  printf("msocl-bench verify: device %s against the double host reference "
         "(msocl_reference, the same integrator and dt), with the tests' "
         "tolerances%s%s\n",
         device, o->against ? "; and against the positions saved in " : "",
         o->against ? o->against : "");
  printf("%-44s %6s %12s %9s %6s %14s\n", "check", "steps", "|dev-ref| m",
         "tolerance", "result", "|dev-saved| m");
  int failed = 0, rc = MSOCL_OK;
  int big = 0; /* the largest check's floats */
  for (int k = 0; k < NCHECKS; k++)
    big = 3 * checks[k].n * checks[k].n > big ? 3 * checks[k].n * checks[k].n
                                              : big;
  float *p = malloc((size_t)big * sizeof *p),
        *w = malloc((size_t)big * sizeof *w);
  double *q = malloc((size_t)big * sizeof *q);
  for (int k = 0; k < NCHECKS && p && w && q; k++) {
    const struct check *c = &checks[k];
    /* --quick: a quarter of the steps, for the smoke test */
    const int steps = o->quick ? c->steps / 4 : c->steps;
    char name[96];
    check_name(name, sizeof name, c, steps);
    double diff = NAN, travel = 0.0;
    float dt = c->dt;
    rc = run_check(rt, c, steps, p, q, &diff, &travel, &dt);
    /* a reference that hardly moved would pass anything */
    const int ok = rc == MSOCL_OK && diff <= c->tol && travel >= 10 * c->tol;
    char vs[48] = "-";
    const int count = 3 * c->n * c->n;
    int vs_ok = 1;
    if (rc == MSOCL_OK && o->against) {
      if (load_saved(o->against, name, w, count) == 0) {
        const double d = bench_max_diff(p, w, (size_t)count);
        vs_ok = d <= 2 * c->tol;
        snprintf(vs, sizeof vs, "%.3g%s", d,
                 d == 0 ? " (bitwise)" : vs_ok ? "" : " FAIL");
      } else {
        snprintf(vs, sizeof vs, "not saved");
      }
    }
    if (rc == MSOCL_OK && out)
      save(out, name, p, count);
    failed += !ok || !vs_ok;
    if (rc != MSOCL_OK)
      printf("%-44s failed: %s (%s)\n", name, msocl_strerror(rc),
             msocl_last_error());
    else
      printf("%-44s %6d %12.3g %9.0e %6s %14s\n", name, steps, diff, c->tol,
             ok ? "pass" : "FAIL", vs);
    if (!ok && rc == MSOCL_OK && travel < 10 * c->tol)
      printf("  the reference moved only %.3g m\n", travel);
    struct bench_row r;
    bench_row_init(&r);
    snprintf(r.device, sizeof r.device, "%s", device);
    r.layout = layout_name[c->layout];
    r.integrator = bench_integrator_names[c->integrator];
    r.math = c->math == MSOCL_MATH_PRECISE ? "precise" : "relaxed";
    r.grid = c->n;
    r.dt = dt;
    r.steps = steps;
    r.error = diff;
    r.status = ok && vs_ok ? "pass" : "fail";
    bench_csv_row(csv, &r);
  }
  if (!p || !w || !q) {
    fprintf(stderr, "msocl-bench verify: out of memory\n");
    failed++;
  }
  free(p);
  free(w);
  free(q);
  if (out && fclose(out) != 0) {
    perror(o->save);
    failed++;
  }
  msocl_runtime_destroy(rt);
  printf("%s: %d of %d checks failed\n", failed ? "FAIL" : "pass", failed,
         NCHECKS);
  return failed ? 1 : 0;
}

/* The benchmark: the paper's Table 1 reproduced and extended, with a
 * roofline column (table1), work-precision data for every integrator and
 * math mode (precision), and the second seed's jello cube per engine
 * (lattice). A table on stdout, one CSV row per run.
 *
 *   msocl-bench [table1|precision|lattice|strain|colliders|meshes|wind|meshcollider|verify] [-d SPEC] [-g LIST] [-s STEPS]
 *               [-l LIST] [-i LIST] [-m LIST] [-T SECONDS] [--from X]
 *               [--levels N]
 *               [--max-grid N] [--big-steps N] [--repeat N] [--copy-mib N]
 *               [--sweep-steps N]
 *               [--quick]
 *               [--csv FILE]
 */
#include "bench.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *const bench_integrator_names[5] = {"symplectic", "explicit",
                                               "verlet", "rk4", "implicit"};

static int usage(FILE *f, int code)
{
  fprintf(f,
"usage: msocl-bench [table1|precision|lattice|strain|colliders|meshes|wind|\n"
"                   meshcollider|verify]\n"
"                   [options]\n"
"  table1     the paper's Table 1: tablecloth on a round table, serial C\n"
"             (Algorithm 1) against libmsocl per layout, with a roofline\n"
"             column from the device's measured copy bandwidth (default)\n"
"  precision  work-precision data: a cloth hanging from two corners, every\n"
"             integrator and math mode over a sweep of dt, error against a\n"
"             double-precision RK4 reference\n"
"  lattice    the jello cube, n^3 points: BUFFER and GRID side by side,\n"
"             GRID against BUFFER's speed and final positions (-g\n"
"             default 16,32,64; -i default symplectic)\n"
"  strain     strain limiting's cost against its result: a soft tablecloth\n"
"             draped for -T s (default 2) unlimited and with each limit at\n"
"             each sweep count; error = largest strain at the end (-g\n"
"             default 32,64; -i default symplectic)\n"
"  colliders  the tablecloth with no collider, a plane, a sphere, the\n"
"             table, a capsule or a box (at rest and moving), per\n"
"             engine (GRID, BUFFER), each against no collider (-g\n"
"             default 96,256; -s default 200)\n"
"  meshes     the soft ball (-g's first size: icosphere subdivisions,\n"
"             default 6) and an n x n cloth read as OBJ (the second,\n"
"             default 256): BUFFER, and AUTO against it\n"
"             (-s default 200; -i default symplectic)\n"
"  wind       a flag hanging from two corners with no wind and in a 5 m/s\n"
"             wind, side by side (-g default 128,256,512; -s default 200)\n"
"  meshcollider  a cloth hanging from its top edge alone, against a\n"
"             static 10 000-triangle sphere mesh and against it moving\n"
"             (new vertices every 10 steps, and every 60 Hz frame's 167),\n"
"             side by side (-g default 128,512; -s default 200)\n"
"  verify     the device against the double host reference with the\n"
"             tests' tolerances (every layout and integrator, contact,\n"
"             relaxed math), for a machine without the test suite; exit\n"
"             status 1 if a check fails\n"
"options:\n"
"  -d SPEC        device spec (MSOCL_DEVICE grammar; 'all' = every device)\n"
"  -g LIST        grid sizes, e.g. 48,64,96 (table1: default 48,64,96,128,\n"
"                 256,512,1024,2048; precision: one size, default 16)\n"
"  -s STEPS       steps per run (table1, default 2000; lattice, 200)\n"
"  --big-steps N  steps for grids above 128 (table1, default: -s)\n"
"  --repeat N     time each run N times back to back, the fastest counts\n"
"                 (table1 and lattice, default 1; for a noisy machine)\n"
"  --max-grid N   skip grids larger than N\n"
"  -l LIST        layouts: buffer,image2d,edges,grid (table1 default all\n"
"                 four; precision default buffer; edges: symplectic Euler\n"
"                 only)\n"
"  -i LIST        integrators: symplectic,explicit,verlet,rk4,implicit\n"
"                 (precision, default all)\n"
"  -m LIST        math modes: precise,relaxed (default precise for table1,\n"
"                 both for precision)\n"
"  -T SECONDS     simulated time (precision, default 0.5)\n"
"  --from X       largest dt: the power of two at or below X times the\n"
"                 symplectic stable step (precision, default 16)\n"
"  --levels N     dt values, halving from there (precision, default 11)\n"
"  --copy-mib N   copy-bandwidth buffer size in MiB (default 256)\n"
"  --sweeps LIST  strain: sweeps a step to try (default 1,2,3,5,10,20)\n"
"  --fused        table1: also each gather layout with symplectic Euler's\n"
"                 two passes as one kernel (layout name +fused)\n"
"  --values       table1: also BUFFER with a spring-class byte in every\n"
"                 slot (buffer-classes) and with (rest, k) in every slot\n"
"                 (buffer-values), whatever the library would choose\n"
"  --expert       table1: also the tablecloth as expert C (planes, padded\n"
"                 rows, one fused sweep, OpenMP; the yardstick of issue 15),\n"
"                 its speed against each layout's and whether their final\n"
"                 positions agree bit for bit\n"
"  --sweep-steps N  table1 and wind: GRID's sweep on a CPU runs N steps a\n"
"                 launch (1-8; default 0: the library times 4, 3, 2)\n"
"  --no-serial    table1: without the serial C rows (slow at 2048^2)\n"
"  --save FILE    verify: also write each check's final positions to FILE\n"
"  --against FILE verify: also compare them with FILE's, saved on another\n"
"                 device (within twice the reference tolerance)\n"
"  --quick        tiny sizes and few steps: a smoke test\n"
"  --csv FILE     also write one CSV row per run to FILE\n"
"  -h, --help     this text\n");
  return code;
}

static int parse_int(const char *s, int lo, int *out)
{
  char *end;
  long v = strtol(s, &end, 10);
  if (end == s || *end || v < lo || v > 1 << 30)
    return -1;
  *out = (int)v;
  return 0;
}

/* Comma-separated words, each the index of a name in names (n); or, with
 * names NULL, integers >= n (grid sizes, sweeps). */
static int parse_list(const char *s, const char *const *names, int n,
                      int *out, int max, int *count)
{
  *count = 0;
  while (*s) {
    size_t len = strcspn(s, ",");
    char word[32];
    if (len == 0 || len >= sizeof word || *count >= max)
      return -1;
    memcpy(word, s, len);
    word[len] = '\0';
    int v = -1;
    if (names) {
      for (int i = 0; i < n; i++)
        if (!strcmp(word, names[i]))
          v = i;
      if (v < 0)
        return -1;
    } else if (parse_int(word, n, &v)) {
      return -1;
    }
    out[(*count)++] = v;
    s += len + (s[len] == ',');
  }
  return *count > 0 ? 0 : -1;
}

static const char *const layout_names[] = {"auto", "image2d", "buffer",
                                          "edges", "grid"};
static const char *const math_names[] = {"precise", "relaxed"};

int main(int argc, char **argv)
{
  struct bench_opts o;
  memset(&o, 0, sizeof o);
  o.steps = 2000;
  o.big_steps = -1;
  o.repeat = 1;
  o.sim_time = 0.5;
  o.levels = 11;
  o.from = 16.0;
  o.copy_mib = 256;
  int mode = 0, have_l = 0, have_m = 0, have_t = 0, have_lv = 0;
  int have_s = 0, have_from = 0;
  for (int a = 1; a < argc; a++) {
    const char *w = argv[a], *v = a + 1 < argc ? argv[a + 1] : NULL;
    int bad = 0, takes = 1;
    if (!strcmp(w, "-h") || !strcmp(w, "--help")) {
      return usage(stdout, 0);
    } else if (!strcmp(w, "table1") && a == 1) {
      mode = 0, takes = 0;
    } else if (!strcmp(w, "precision") && a == 1) {
      mode = 1, takes = 0;
    } else if (!strcmp(w, "lattice") && a == 1) {
      mode = 2, takes = 0;
    } else if (!strcmp(w, "strain") && a == 1) {
      mode = 3, takes = 0;
    } else if (!strcmp(w, "colliders") && a == 1) {
      mode = 4, takes = 0;
    } else if (!strcmp(w, "meshes") && a == 1) {
      mode = 5, takes = 0;
    } else if (!strcmp(w, "wind") && a == 1) {
      mode = 6, takes = 0;
    } else if (!strcmp(w, "meshcollider") && a == 1) {
      mode = 7, takes = 0;
    } else if (!strcmp(w, "--fused")) {
      o.fused = 1, takes = 0;
    } else if (!strcmp(w, "--values")) {
      o.values = 1, takes = 0;
    } else if (!strcmp(w, "--expert")) {
      o.expert = 1, takes = 0;
    } else if (!strcmp(w, "verify") && a == 1) {
      mode = 8, takes = 0;
    } else if (!strcmp(w, "--no-serial")) {
      o.no_serial = 1, takes = 0;
    } else if (!strcmp(w, "--save")) {
      bad = !v, o.save = v;
    } else if (!strcmp(w, "--against")) {
      bad = !v, o.against = v;
    } else if (!strcmp(w, "--quick")) {
      o.quick = 1, takes = 0;
    } else if (!v) {
      bad = 1;
    } else if (!strcmp(w, "-d")) {
      o.spec = v;
    } else if (!strcmp(w, "--csv")) {
      o.csv = v;
    } else if (!strcmp(w, "-g")) {
      bad = parse_list(v, NULL, 3, o.grids, BENCH_MAX_LIST, &o.ngrids);
    } else if (!strcmp(w, "--sweeps")) {
      bad = parse_list(v, NULL, 1, o.sweeps, BENCH_MAX_LIST, &o.nsweeps);
      for (int i = 0; i < o.nsweeps; i++)
        bad |= o.sweeps[i] > 1000; /* the library's bound */
    } else if (!strcmp(w, "-s")) {
      bad = parse_int(v, 1, &o.steps), have_s = 1;
    } else if (!strcmp(w, "--big-steps")) {
      bad = parse_int(v, 1, &o.big_steps);
    } else if (!strcmp(w, "--sweep-steps")) {
      bad = parse_int(v, 0, &o.sweep_steps) ||
            o.sweep_steps > MSOCL_MAX_SWEEP_STEPS;
    } else if (!strcmp(w, "--repeat")) {
      bad = parse_int(v, 1, &o.repeat);
    } else if (!strcmp(w, "--max-grid")) {
      bad = parse_int(v, 2, &o.max_grid);
    } else if (!strcmp(w, "--levels")) {
      bad = parse_int(v, 1, &o.levels), have_lv = 1;
    } else if (!strcmp(w, "--copy-mib")) {
      bad = parse_int(v, 1, &o.copy_mib);
    } else if (!strcmp(w, "--from")) {
      char *end;
      o.from = strtod(v, &end);
      bad = end == v || *end || !(o.from > 0) || !isfinite(o.from);
      have_from = 1;
    } else if (!strcmp(w, "-T")) {
      char *end;
      o.sim_time = strtod(v, &end);
      bad = end == v || *end || !(o.sim_time > 0) || !isfinite(o.sim_time);
      have_t = 1;
    } else if (!strcmp(w, "-l")) {
      bad = parse_list(v, layout_names + 1, 4, o.layouts, 4, &o.nlayouts);
      for (int i = 0; i < o.nlayouts; i++)
        o.layouts[i] += 1; /* names start at IMAGE2D */
      have_l = 1;
    } else if (!strcmp(w, "-i")) {
      bad = parse_list(v, bench_integrator_names, 5, o.integrators, 5,
                       &o.nintegrators);
    } else if (!strcmp(w, "-m")) {
      bad = parse_list(v, math_names, 2, o.maths, 2, &o.nmaths);
      have_m = 1;
    } else {
      bad = 1;
    }
    if (bad) {
      fprintf(stderr, "msocl-bench: bad option or value: %s%s%s\n", w,
              takes && v ? " " : "", takes && v ? v : "");
      return usage(stderr, 2);
    }
    a += takes;
  }
  /* Defaults that depend on the mode and --quick. */
  if (!have_l) {
    o.nlayouts = mode == 0 ? 4 : 1;
    o.layouts[0] = MSOCL_LAYOUT_BUFFER;
    o.layouts[1] = MSOCL_LAYOUT_IMAGE2D;
    o.layouts[2] = MSOCL_LAYOUT_EDGES;
    o.layouts[3] = MSOCL_LAYOUT_GRID;
  }
  if (!have_m) {
    o.nmaths = mode == 0 ? 1 : 2;
    o.maths[0] = MSOCL_MATH_PRECISE;
    o.maths[1] = MSOCL_MATH_RELAXED;
  }
  if (o.nintegrators == 0) {
    o.nintegrators = mode == 1 ? 5 : 1;
    for (int i = 0; i < 5; i++)
      o.integrators[i] = i;
  }
  if (o.ngrids == 0) {
    static const int t1[] = {48, 64, 96, 128, 256, 512, 1024, 2048};
    static const int t1q[] = {16, 24}, lat[] = {16, 32, 64}, latq[] = {6};
    static const int str[] = {32, 64}, strq[] = {8};
    static const int col[] = {96, 256}, colq[] = {8};
    static const int msh[] = {6, 256}, mshq[] = {2, 16};
    static const int wnd[] = {128, 256, 512}, wndq[] = {16};
    static const int mco[] = {128, 512}, mcoq[] = {16};
    const int *g = mode == 1   ? NULL
                   : mode == 2 ? (o.quick ? latq : lat)
                   : mode == 3 ? (o.quick ? strq : str)
                   : mode == 4 ? (o.quick ? colq : col)
                   : mode == 5 ? (o.quick ? mshq : msh)
                   : mode == 6 ? (o.quick ? wndq : wnd)
                   : mode == 7 ? (o.quick ? mcoq : mco)
                   : o.quick   ? t1q
                               : t1;
    o.ngrids = mode == 1   ? 1
               : mode == 2 ? (o.quick ? 1 : 3)
               : mode == 3 ? (o.quick ? 1 : 2)
               : mode == 4 ? (o.quick ? 1 : 2)
               : mode == 5 ? 2
               : mode == 6 ? (o.quick ? 1 : 3)
               : mode == 7 ? (o.quick ? 1 : 2)
               : o.quick   ? 2
                           : 8;
    for (int i = 0; i < o.ngrids; i++)
      o.grids[i] = g ? g[i] : o.quick ? 8 : 16;
  }
  if (o.quick) {
    if (!have_s)
      o.steps = 50;
    if (!have_t)
      o.sim_time = 0.05;
    if (!have_lv)
      o.levels = 3;
    if (!have_from)
      o.from = 2.0;
    if (o.copy_mib > 16)
      o.copy_mib = 16;
  }
  if (mode == 2 && !have_s)
    o.steps = o.quick ? 5 : 200;
  if (mode >= 4 && !have_s)
    o.steps = o.quick ? 5 : 200;
  if (mode == 3 && !have_t)
    o.sim_time = o.quick ? 0.02 : 2.0;
  if (o.nsweeps == 0) {
    static const int sw[] = {1, 2, 3, 5, 10, 20};
    o.nsweeps = o.quick ? 2 : 6;
    for (int i = 0; i < o.nsweeps; i++)
      o.sweeps[i] = o.quick ? 1 + 2 * i : sw[i];
  }
  if (o.big_steps < 0)
    o.big_steps = o.steps;

  FILE *csv = NULL;
  if (o.csv && !(csv = fopen(o.csv, "w"))) {
    perror(o.csv);
    return 1;
  }
  if (csv)
    bench_csv_header(csv);
  int rc = mode == 0   ? bench_table1(&o, csv)
           : mode == 1 ? bench_precision(&o, csv)
           : mode == 2 ? bench_lattice(&o, csv)
           : mode == 3 ? bench_strain(&o, csv)
           : mode == 4 ? bench_colliders(&o, csv)
           : mode == 5 ? bench_meshes(&o, csv)
           : mode == 6 ? bench_wind(&o, csv)
           : mode == 7 ? bench_mesh_collider(&o, csv)
                       : bench_verify(&o, csv);
  if (csv && fclose(csv) != 0) {
    perror(o.csv);
    rc = 1;
  }
  return rc;
}

/* ------------------------------------------------------------ shared */

double bench_max_diff(const float *a, const float *b, size_t n)
{
  double d = 0.0;
  for (size_t i = 0; i < n; i++) {
    double e = fabs((double)a[i] - (double)b[i]);
    d = e > d || isnan(e) ? e : d;
  }
  return d;
}

int bench_time_sim(const struct bench_opts *o, msocl_runtime *rt,
                   const msocl_model *m, const msocl_sim_options *so,
                   struct bench_row *r, float *pos, const float *ref)
{
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, so);
  if (rc == MSOCL_OK)
    rc = msocl_sim_step(s, 1); /* warm-up */
  r->seconds = INFINITY;
  for (int rep = 0; rc == MSOCL_OK && rep < o->repeat; rep++) {
    double t0 = bench_now();
    rc = msocl_sim_step(s, o->steps);
    double t = bench_now() - t0;
    r->seconds = t < r->seconds ? t : r->seconds;
  }
  if (rc == MSOCL_OK)
    rc = msocl_sim_read_positions(s, pos);
  if (rc == MSOCL_OK && ref)
    r->error = bench_max_diff(pos, ref, 3 * (size_t)r->points);
  msocl_sim_destroy(s);
  return rc;
}

double bench_now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

double bench_cpu_now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void bench_progress(int i, int n, const char *fmt, ...)
{
  static int tty = -1;
  if (tty < 0)
    tty = isatty(STDERR_FILENO);
  if (!tty)
    return;
  if (i == 0) {
    fprintf(stderr, "\r%*s\r", 79, "");
    return;
  }
  char text[160];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  fprintf(stderr, "\r[%d/%d] %-66.66s", i, n, text);
  fflush(stderr);
}

void bench_cloth(msocl_cloth_desc *d, int n, const float origin[3],
                 const float u[3], const float v[3])
{
  msocl_cloth_desc_init(d);
  d->nx = d->ny = n;
  memcpy(d->origin, origin, sizeof d->origin);
  memcpy(d->u, u, sizeof d->u);
  memcpy(d->v, v, sizeof d->v);
  d->point_mass = TC_MASS / (float)(n * n);
  d->k_stretch = TC_K_STRETCH;
  d->k_shear = TC_K_SHEAR;
  d->k_bend = TC_K_BEND;
}

int bench_fail(const char *what, int rc)
{
  fprintf(stderr, "msocl-bench: %s: %s (%s)\n%s\n", what, msocl_strerror(rc),
          msocl_err_name(rc), msocl_last_error());
  return 1;
}

int bench_open(const struct bench_opts *o, msocl_runtime **rt,
               msocl_device_info *info)
{
  int rc = msocl_runtime_create(rt, o->spec);
  if (rc != MSOCL_OK)
    return bench_fail("runtime", rc);
  msocl_runtime_device_info(*rt, 0, info);
  return 0;
}

void bench_row_device(struct bench_row *r, msocl_runtime *rt)
{
  msocl_device_info info;
  msocl_runtime_device_info(rt, 0, &info);
  bench_device_label(r->device, sizeof r->device, &info);
}

void bench_row_init(struct bench_row *r)
{
  memset(r, 0, sizeof *r);
  r->layout = r->integrator = r->math = r->status = r->strain = "";
  r->dt = r->seconds = r->steps_per_s = r->vertex_steps_per_s = NAN;
  r->bytes_per_vertex_step = r->effective_gbps = r->copy_gbps = NAN;
  r->fraction = r->error = NAN;
}

void bench_row_rates(struct bench_row *r)
{
  if (r->seconds > 0 && r->steps > 0) {
    r->steps_per_s = (double)r->steps / r->seconds;
    r->vertex_steps_per_s =
        r->steps_per_s *
        (r->points > 0 ? (double)r->points : (double)r->grid * r->grid);
  }
  if (isfinite(r->bytes_per_vertex_step) && isfinite(r->vertex_steps_per_s))
    r->effective_gbps = r->bytes_per_vertex_step * r->vertex_steps_per_s / 1e9;
  if (isfinite(r->effective_gbps) && r->copy_gbps > 0)
    r->fraction = r->effective_gbps / r->copy_gbps;
}

void bench_device_label(char *out, size_t size, const msocl_device_info *d)
{
  snprintf(out, size, "%d:%d %s", d->platform_index, d->device_index,
           d->name);
  for (char *c = out; *c; c++)
    if (*c == ',' || *c == '"' || *c == '\n' || *c == '\r')
      *c = *c == ',' ? ';' : ' ';
}

void bench_csv_header(FILE *f)
{
  fputs("device,layout,integrator,math,grid,dt,steps,seconds,steps_per_s,"
        "vertex_steps_per_s,bytes_per_vertex_step,effective_GBps,copy_GBps,"
        "fraction_of_copy,error,status,strain,sweeps\n",
        f);
}

static void num(FILE *f, const char *fmt, double x)
{
  if (isinf(x))
    fputs(x > 0 ? ",inf" : ",-inf", f);
  else if (!isnan(x))
    fprintf(f, fmt, x);
  else
    fputc(',', f);
}

void bench_csv_row(FILE *f, const struct bench_row *r)
{
  if (!f)
    return;
  fprintf(f, "%s,%s,%s,%s,%d", r->device, r->layout, r->integrator, r->math,
          r->grid);
  num(f, ",%.9g", r->dt);
  fprintf(f, ",%lld", r->steps);
  num(f, ",%.6g", r->seconds);
  num(f, ",%.6g", r->steps_per_s);
  num(f, ",%.6g", r->vertex_steps_per_s);
  num(f, ",%.6g", r->bytes_per_vertex_step);
  num(f, ",%.6g", r->effective_gbps);
  num(f, ",%.6g", r->copy_gbps);
  num(f, ",%.4g", r->fraction);
  num(f, ",%.6g", r->error);
  fprintf(f, ",%s,%s,", r->status, r->strain);
  if (r->sweeps > 0)
    fprintf(f, "%d", r->sweeps);
  fputc('\n', f);
  fflush(f);
}

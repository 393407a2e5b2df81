/* table1: the paper's Table 1 (tablecloth on a round table, time for 2000
 * iterations) reproduced beside the paper's numbers and extended to larger
 * grids: serial C (Algorithm 1) against libmsocl per device, layout and
 * math mode, with a roofline column from the device's copy bandwidth. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Table 1 of Vassilev & Rousev: time for 2000 iterations (s) and
 * iterations per second, machines 1 and 2, CPU and GPU. */
static const struct {
  int grid;
  double t[4];
  int ips[4];
} paper[] = {
    {48, {4.39, 3.05, 1.68, 0.67}, {455, 656, 1190, 2985}},
    {64, {7.70, 5.53, 2.20, 0.67}, {260, 362, 909, 2985}},
    {96, {18.65, 12.30, 4.25, 0.67}, {107, 163, 470, 2985}},
    {128, {32.86, 21.87, 6.90, 0.67}, {61, 91, 290, 2985}},
};
static const char *const paper_cols[4] = {"CPU 1", "CPU 2", "GPU 1",
                                          "GPU 2"};

/* Bytes a vertex-step moves under this model, on every layout (each runs
 * its state in x, y, z planes): 12 B a state, 4 B inverse mass, 4 B pinned
 * flag, neighbour positions counted as cached (0) and the connectivity not
 * counted: the velocity pass moves 12 + 12 + 8 + 12, the position pass
 * 12 + 12 + 4 + 12 - the model the planes rows of earlier results used. */
#define BYTES_MODEL (44.0 + 40.0)

/* A row's variant of its layout: the two-pass step (BUFFER: classes or
 * values, as the library chooses), the one-kernel step (--fused), or
 * BUFFER with spring classes, and with values, forced (--values). */
enum { PLAIN, FUSED, CLASSES, VALUES, VARIANTS };

static const char *layout_name(int layout, int variant)
{
  if (variant == CLASSES)
    return "buffer-classes";
  if (variant == VALUES)
    return "buffer-values";
  if (variant == FUSED)
    return layout == MSOCL_LAYOUT_IMAGE2D ? "image2d+fused"
           : layout == MSOCL_LAYOUT_GRID  ? "grid+fused"
                                          : "buffer+fused";
  return layout == MSOCL_LAYOUT_IMAGE2D ? "image2d"
         : layout == MSOCL_LAYOUT_EDGES ? "edges"
         : layout == MSOCL_LAYOUT_GRID  ? "grid"
                                        : "buffer";
}

msocl_model *bench_tablecloth(int n, float *dt)
{
  msocl_cloth_desc d;
  /* u = z, v = x: the tablecloth example's cloth, normals up */
  const float origin[3] = {-0.5f, TC_HEIGHT, -0.5f}, u[3] = {0, 0, 1},
              v[3] = {1, 0, 0}, top[3] = {0, 0, 0};
  bench_cloth(&d, n, origin, u, v);
  msocl_model *m = NULL;
  int rc = msocl_model_cloth_grid(&m, &d);
  if (rc == MSOCL_OK)
    rc = msocl_model_add_table(m, top, TC_RADIUS, TC_FRICTION);
  if (rc == MSOCL_OK)
    rc = msocl_model_set_viscous_damping(m, TC_VISCOUS_PER_MASS * d.point_mass);
  if (rc == MSOCL_OK)
    rc = msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, dt);
  if (rc != MSOCL_OK) {
    bench_fail("building the tablecloth", rc);
    msocl_model_destroy(m);
    return NULL;
  }
  *dt *= 0.5f; /* half the stable step, as examples/tablecloth.c */
  return m;
}

/* Physical memory of the host in bytes, 0 if unknown. */
static double host_memory(void)
{
#ifdef _SC_PHYS_PAGES
  long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  if (pages > 0 && size > 0)
    return (double)pages * (double)size;
#endif
  return 0.0;
}

static double rms_diff(const float *a, const float *b, int n)
{
  double sum = 0.0;
  for (int i = 0; i < 3 * n; i++) {
    double d = (double)a[i] - b[i];
    sum += d * d;
  }
  return sqrt(sum / n);
}

struct result {
  int grid, steps;
  char engine[64];
  double ips, seconds;
  int ok;
};

struct ctx {
  const struct bench_opts *o;
  FILE *csv;
  msocl_runtime *rt;
  int ndev;
  msocl_device_info *info;
  double *copy;
  struct result *res;
  int nres, done, total;
  float *xyz;
  const float *expert_pos; /* --expert: its final positions, this grid */
  double expert_ips, expert_busy; /* ... its speed; cores busy, best run */
};

static void print_row(const struct bench_row *r, const char *engine,
                      double serial_ips)
{
  char t2000[32] = "-", speed[32] = "-", bytes[32] = "-", gbps[32] = "-",
       frac[32] = "-", err[32] = "-";
  if (r->steps_per_s > 0) {
    snprintf(t2000, sizeof t2000, "%.2f%s", 2000.0 / r->steps_per_s,
             r->steps == 2000 ? "" : "*");
    if (serial_ips > 0)
      snprintf(speed, sizeof speed, "%.2fx", r->steps_per_s / serial_ips);
  }
  if (isfinite(r->bytes_per_vertex_step))
    snprintf(bytes, sizeof bytes, "%.0f", r->bytes_per_vertex_step);
  if (isfinite(r->effective_gbps))
    snprintf(gbps, sizeof gbps, "%.2f", r->effective_gbps);
  if (isfinite(r->fraction))
    snprintf(frac, sizeof frac, "%.0f%%", 100.0 * r->fraction);
  if (isfinite(r->error))
    snprintf(err, sizeof err, "%.1e", r->error);
  if (strcmp(r->status, "ok"))
    printf("%4dx%-4d %-28s %s\n", r->grid, r->grid, engine, r->status);
  else
    printf("%4dx%-4d %-28s %6lld %8.3f %8.1f %9s %9s %6s %6s %6s %9s\n",
           r->grid, r->grid, engine, r->steps, r->seconds, r->steps_per_s,
           t2000, speed, bytes, gbps, frac, err);
  fflush(stdout);
}

static void keep(struct ctx *c, const struct bench_row *r, const char *engine)
{
  struct result *x = &c->res[c->nres++];
  x->grid = r->grid;
  x->steps = (int)r->steps;
  snprintf(x->engine, sizeof x->engine, "%s", engine);
  x->ok = !strcmp(r->status, "ok");
  x->ips = x->ok ? r->steps_per_s : 0.0;
  x->seconds = r->seconds;
}

/* A host engine (serial C, expert C): its CSV labels, state, step and
 * final positions. */
struct host {
  const char *device, *layout, *engine;
  void *state;
  void (*step)(void *state, int steps);
  const float *(*positions)(const void *state);
};

static void serial_step(void *s, int steps) { bench_serial_step(s, steps); }
static void expert_step(void *e, int steps) { bench_expert_step(e, steps); }
static const float *host_serial_pos(const void *s)
{
  return bench_serial_positions(s);
}
static const float *host_expert_pos(const void *e)
{
  return bench_expert_positions(e);
}

/* Times h->state (NULL: it failed to build, error rc) as run_device times
 * the library: one warm-up step, then the best of --repeat runs. *ips: its
 * iterations per second, 0 if it failed; *busy (busy not NULL): the
 * cores it kept busy in that run; ref: serial C's final positions for the error column, or
 * NULL. */
static void run_host(struct ctx *c, const struct host *h, int rc, int n,
                     float dt, int steps, const float *ref,
                     double serial_ips, double *ips, double *busy)
{
  struct bench_row r;
  bench_row_init(&r);
  snprintf(r.device, sizeof r.device, "%s", h->device);
  r.layout = h->layout;
  r.integrator = "symplectic";
  r.math = "precise";
  r.grid = n;
  r.dt = dt;
  r.steps = steps;
  bench_progress(++c->done, c->total, "%dx%d %s, %d steps", n, n, h->engine,
                 steps);
  if (rc != MSOCL_OK) {
    r.status = "failed";
    fprintf(stderr, "msocl-bench: %s %dx%d: %s\n", h->engine, n, n,
            msocl_strerror(rc));
  } else {
    h->step(h->state, 1); /* warm-up */
    r.seconds = INFINITY;
    for (int rep = 0; rep < c->o->repeat; rep++) {
      const double t0 = bench_now(), c0 = bench_cpu_now();
      h->step(h->state, steps);
      const double t = bench_now() - t0;
      if (busy && t < r.seconds)
        *busy = (bench_cpu_now() - c0) / t;
      r.seconds = t < r.seconds ? t : r.seconds;
    }
    r.status = "ok";
    if (ref)
      r.error = rms_diff(h->positions(h->state), ref, n * n);
    bench_row_rates(&r);
  }
  bench_progress(0, 0, " ");
  print_row(&r, h->engine, serial_ips);
  bench_csv_row(c->csv, &r);
  keep(c, &r, h->engine);
  *ips = r.steps_per_s > 0 ? r.steps_per_s : 0.0;
}

/* The serial baseline on grid n; *ips gets its iterations per second. */
static int run_serial(struct ctx *c, int n, float dt, int steps,
                      const float **pos, bench_serial **keep_s, double *ips)
{
  bench_serial *s = NULL;
  int rc = bench_serial_create(&s, n, dt);
  struct host h = {"host serial C", "springs", "serial C (Algorithm 1)", s,
                   serial_step, host_serial_pos};
  run_host(c, &h, rc, n, dt, steps, NULL, 0.0, ips, NULL);
  *pos = s ? bench_serial_positions(s) : NULL;
  *keep_s = s;
  return rc;
}

/* The expert C yardstick on grid n from the model's initial positions;
 * c->expert_pos and c->expert_ips get its result. */
static void run_expert(struct ctx *c, const msocl_model *m, int n, float dt,
                       int steps, const float *serial_pos, double serial_ips,
                       bench_expert **keep_e)
{
  bench_expert *e = NULL;
  int rc = c->xyz ? msocl_model_get_positions(m, c->xyz) : MSOCL_ERR_NO_MEMORY;
  if (rc == MSOCL_OK)
    rc = bench_expert_create(&e, n, dt, c->xyz);
  char engine[64];
  snprintf(engine, sizeof engine, "expert C (%d thread%s)",
           bench_expert_threads(), bench_expert_threads() > 1 ? "s" : "");
  struct host h = {"host expert C", "expert-planes", engine, e, expert_step,
                   host_expert_pos};
  run_host(c, &h, rc, n, dt, steps, serial_pos, serial_ips, &c->expert_ips,
           &c->expert_busy);
  c->expert_pos = e ? bench_expert_positions(e) : NULL;
  *keep_e = e;
}

/* Expert C against the library's run: their speeds, whether the final
 * positions agree bit for bit and, on a CPU device (busy > 0), the cores
 * each kept busy: where the library's kernels take the expert's CPU time,
 * the rest of the gap is its threads waiting between launches. */
static void print_expert(const struct ctx *c, const float *xyz, int n,
                         double ips, double gbps, double busy)
{
  double most = 0.0;
  int same = 1;
  for (int i = 0; i < 3 * n * n; i++) {
    double d = fabs((double)xyz[i] - c->expert_pos[i]);
    most = d > most || isnan(d) ? d : most;
    same &= !memcmp(&xyz[i], &c->expert_pos[i], sizeof xyz[i]);
  }
  char ratio[32] = "-";
  if (ips > 0 && c->expert_ips > 0)
    snprintf(ratio, sizeof ratio, "%.2fx", c->expert_ips / ips);
  printf("%9s   expert C vs this: bitwise: %s, max |diff| %.3g; expert C's "
         "speed over this: %s\n",
         "", same ? "yes" : "no", most, ratio);
  if (busy > 0 && c->expert_busy > 0)
    printf("%9s   cores busy (the process's CPU time over the wall time): "
           "expert C %.2f (OpenMP's waits spin), this %.2f\n",
           "", c->expert_busy, busy);
  /* issue 15's memory bound: 48 bytes a vertex-step (x, y, z of position
   * and velocity read and written) at the measured copy bandwidth */
  if (gbps > 0) {
    const double bound = gbps * 1e9 / (48.0 * n * n);
    printf("%9s   memory bound (48 B a vertex-step at %.2f GB/s) %.0f "
           "steps/s: expert C %.0f%%, this %.0f%%\n",
           "", gbps, bound, 100.0 * c->expert_ips / bound, 100.0 * ips / bound);
  }
}

static void run_device(struct ctx *c, const msocl_model *m, int n, float dt,
                       int steps, int dev, int layout, int variant,
                       int math, const float *serial_pos, double serial_ips)
{
  const msocl_device_info *info = &c->info[dev];
  const int fused = variant == FUSED;
  struct bench_row r;
  bench_row_init(&r);
  bench_device_label(r.device, sizeof r.device, info);
  r.layout = layout_name(layout, variant);
  r.integrator = "symplectic";
  r.math = math == MSOCL_MATH_RELAXED ? "relaxed" : "precise";
  r.grid = n;
  r.dt = dt;
  r.steps = steps;
  r.copy_gbps = c->copy[dev] > 0 ? c->copy[dev] : NAN;
  int slots = 0, ns = 0;
  msocl_model_max_degree(m, &slots);
  msocl_model_spring_count(m, &ns);
  r.bytes_per_vertex_step = BYTES_MODEL;
  char engine[64];
  snprintf(engine, sizeof engine, "%d:%d %s %s", info->platform_index,
           info->device_index, r.layout, r.math);
  bench_progress(++c->done, c->total, "%dx%d %s, %d steps", n, n, engine,
                 steps);
  /* Device memory: 4 state copies, a backup, inverse masses, normals, the
   * force accumulators and the connectivity, with room to spare. */
  double conn = layout == MSOCL_LAYOUT_IMAGE2D ? 256.0
                : layout == MSOCL_LAYOUT_EDGES ? 16.0 * ns / ((double)n * n)
                : layout == MSOCL_LAYOUT_GRID  ? 0.0
                                               : 12.0 * slots;
  double need = 1.5 * (double)n * n * (64 + 32 + 4 + 16 + 16 + conn);
  msocl_sim *s = NULL;
  int rc = MSOCL_OK, vs_expert = 0;
  double busy = 0.0; /* the best run's cores kept busy */
  int sweep = 0;     /* GRID's steps a launch */
  if (info->global_mem > 0 && need > (double)info->global_mem) {
    r.status = "skipped (device memory)";
  } else {
    msocl_sim_options so;
    msocl_sim_options_init(&so);
    so.dt = dt;
    so.tuning.layout = (msocl_layout)layout;
    so.math = (msocl_math)math;
    so.tuning.device = dev;
    so.check_every = 0;
    so.tuning.fused = fused ? MSOCL_ON : MSOCL_AUTO;
    so.tuning.sweep_steps = c->o->sweep_steps;
    so.tuning.classes = variant == CLASSES  ? MSOCL_ON
                        : variant == VALUES ? MSOCL_OFF
                                            : MSOCL_AUTO;
    rc = msocl_sim_create(&s, c->rt, m, &so);
    if (rc == MSOCL_OK)
      rc = msocl_sim_step(s, 1); /* warm-up */
    r.seconds = INFINITY;
    for (int rep = 0; rc == MSOCL_OK && rep < c->o->repeat; rep++) {
      const double t0 = bench_now(), c0 = bench_cpu_now();
      rc = msocl_sim_step(s, steps);
      const double t = bench_now() - t0;
      if (t < r.seconds)
        busy = (bench_cpu_now() - c0) / t;
      r.seconds = t < r.seconds ? t : r.seconds;
    }
    vs_expert = c->expert_pos && math == MSOCL_MATH_PRECISE &&
                variant != FUSED;
    if (rc == MSOCL_OK && (serial_pos || vs_expert) && c->xyz &&
        (rc = msocl_sim_read_positions(s, c->xyz)) == MSOCL_OK && serial_pos)
      r.error = rms_diff(c->xyz, serial_pos, n * n);
    r.status = rc == MSOCL_OK ? "ok" : "failed";
    if (rc != MSOCL_OK) {
      bench_progress(0, 0, " ");
      bench_fail(engine, rc);
      r.seconds = NAN;
    }
    bench_row_rates(&r);
    if (rc == MSOCL_OK && layout == MSOCL_LAYOUT_GRID)
      msocl_sim_sweep_steps(s, &sweep);
  }
  msocl_sim_destroy(s);
  bench_progress(0, 0, " ");
  print_row(&r, engine, serial_ips);
  if (vs_expert && r.status && !strcmp(r.status, "ok"))
    print_expert(c, c->xyz, n, r.steps_per_s, c->copy[dev],
                 info->type == MSOCL_DEVICE_CPU ? busy : 0.0);
  if (sweep > 1)
    printf("%9s   GRID's sweep: %d steps a launch%s\n", "", sweep,
           c->o->sweep_steps ? "" : " (timed on the first launches)");
  bench_csv_row(c->csv, &r);
  keep(c, &r, engine);
}

/* 1 where a layout runs in this variant: every layout plain, the gather
 * layouts fused with --fused, BUFFER's two forced variants with --values. */
static int wanted(const struct bench_opts *o, int layout, int variant)
{
  if (variant == FUSED)
    return o->fused && layout != MSOCL_LAYOUT_EDGES;
  if (variant == CLASSES || variant == VALUES)
    return o->values && layout == MSOCL_LAYOUT_BUFFER;
  return 1;
}

/* The paper's numbers beside ours, grid by grid. */
static void print_paper(const struct ctx *c)
{
  printf("\nBeside the paper's Table 1 (time for 2000 iterations, s / "
         "iterations per second;\n* = extrapolated from fewer steps):\n\n");
  printf("%-9s", "grid");
  for (int k = 0; k < 4; k++)
    printf(" %-13s", paper_cols[k]);
  printf("|");
  for (int e = 0; e < c->nres && c->res[e].grid == c->res[0].grid; e++)
    printf(" %-24.24s", c->res[e].engine);
  printf("\n");
  for (int e = 0; e < c->nres;) {
    int g = c->res[e].grid;
    printf("%4dx%-4d", g, g);
    int p = -1;
    for (int k = 0; k < 4; k++)
      if (paper[k].grid == g)
        p = k;
    for (int k = 0; k < 4; k++) {
      char cell[32] = "-";
      if (p >= 0)
        snprintf(cell, sizeof cell, "%.2f/%d", paper[p].t[k],
                 paper[p].ips[k]);
      printf(" %-13s", cell);
    }
    printf("|");
    for (; e < c->nres && c->res[e].grid == g; e++) {
      char cell[40] = "-";
      if (c->res[e].ok)
        snprintf(cell, sizeof cell, "%.2f%s/%.0f", 2000.0 / c->res[e].ips,
                 c->res[e].steps == 2000 ? "" : "*", c->res[e].ips);
      printf(" %-24s", cell);
    }
    printf("\n");
  }
}

int bench_table1(const struct bench_opts *o, FILE *csv)
{
  struct ctx c;
  memset(&c, 0, sizeof c);
  c.o = o;
  c.csv = csv;
  int rc = msocl_runtime_create(&c.rt, o->spec);
  if (rc != MSOCL_OK)
    return bench_fail("choosing devices", rc);
  msocl_runtime_device_count(c.rt, &c.ndev);
  int engines = 0;
  for (int l = 0; l < o->nlayouts; l++)
    for (int v = 0; v < VARIANTS; v++)
      engines += wanted(o, o->layouts[l], v);
  int per_grid = 1 + !!o->expert + c.ndev * engines * o->nmaths, ngrids = 0, big = 0;
  for (int g = 0; g < o->ngrids; g++)
    if (!o->max_grid || o->grids[g] <= o->max_grid)
      ngrids++;
  c.info = calloc((size_t)c.ndev, sizeof *c.info);
  c.copy = calloc((size_t)c.ndev, sizeof *c.copy);
  c.res = calloc((size_t)(ngrids * per_grid + 1), sizeof *c.res);
  if (!c.info || !c.copy || !c.res) {
    rc = MSOCL_ERR_NO_MEMORY;
    bench_fail("table1", rc);
    goto out;
  }
  c.total = ngrids * per_grid;
  printf("msocl-bench table1 (libmsocl %s): tablecloth on a round table, "
         "symplectic Euler at half the stable step, check_every 0;\none "
         "warm-up step, then the best of %d timed run%s of each engine\n",
         msocl_version_string(), o->repeat, o->repeat > 1 ? "s" : "");
  for (int d = 0; d < c.ndev; d++) {
    msocl_runtime_device_info(c.rt, d, &c.info[d]);
    bench_progress(1, 1, "copy bandwidth of device %d:%d",
                   c.info[d].platform_index, c.info[d].device_index);
    int e = bench_copy_gbps(&c.info[d], (size_t)o->copy_mib << 20,
                            &c.copy[d]);
    bench_progress(0, 0, " ");
    printf("device %d:%d %s [%s]: copy bandwidth ", c.info[d].platform_index,
           c.info[d].device_index, c.info[d].name, c.info[d].platform_name);
    if (e == 0)
      printf("%.2f GB/s (clEnqueueCopyBuffer, read + written bytes, best of "
             "5x4 copies of %d MiB)\n",
             c.copy[d], o->copy_mib);
    else
      printf("not measured (%s)\n", msocl_err_name(e));
  }
  printf("bytes per vertex-step, every layout (the state in x, y, z planes): "
         "velocity pass\nreads pos 12 + vel 12 + inv_mass and pin 8, "
         "neighbours cached (0), writes vel 12;\nposition pass reads pos + "
         "vel 24 + pin 4, writes pos 12: 84 (connectivity not counted).\n"
         "GB/s = bytes x vertex-steps/s; %%copy = GB/s over the copy "
         "bandwidth.\nGRID on a CPU device sweeps several steps a launch "
         "(--sweep-steps; its row says\nhow many), reading and writing the "
         "planes once for them: its %%copy (and the\nmemory bound's %%) "
         "may pass 100.\n\n");
  printf("%-9s %-28s %6s %8s %8s %9s %9s %6s %6s %6s %9s\n", "grid",
         "engine", "steps", "time s", "it/s", "s/2000it", "vs serial",
         "B/v-st", "GB/s", "%copy", "rms vs C");
  for (int g = 0; g < o->ngrids; g++) {
    int n = o->grids[g];
    if (o->max_grid && n > o->max_grid)
      continue;
    int steps = n > 128 ? o->big_steps : o->steps;
    big |= n > 128 && steps != o->steps;
    double host = host_memory();
    if (host > 0 && 1024.0 * n * n > 0.5 * host) {
      printf("%4dx%-4d skipped: about %.1f GB of host memory needed\n", n, n,
             1024.0 * n * n / 1e9);
      c.done += per_grid;
      continue;
    }
    float dt = 0.0f;
    msocl_model *m = bench_tablecloth(n, &dt);
    if (!m) {
      rc = 1;
      break;
    }
    free(c.xyz);
    c.xyz = malloc(3 * (size_t)n * n * sizeof *c.xyz);
    const float *spos = NULL;
    bench_serial *s = NULL;
    double sips = 0.0;
    if (!o->no_serial)
      run_serial(&c, n, dt, steps, &spos, &s, &sips);
    bench_expert *e = NULL;
    c.expert_pos = NULL;
    if (o->expert)
      run_expert(&c, m, n, dt, steps, spos, sips, &e);
    for (int d = 0; d < c.ndev; d++)
      for (int l = 0; l < o->nlayouts; l++)
        for (int v = 0; v < VARIANTS; v++)
          for (int k = 0; k < o->nmaths && wanted(o, o->layouts[l], v); k++)
            run_device(&c, m, n, dt, steps, d, o->layouts[l], v,
                       o->maths[k], spos, sips);
    bench_serial_destroy(s);
    bench_expert_destroy(e);
    msocl_model_destroy(m);
  }
  if (big)
    printf("(grids above 128 ran %d steps: * marks times extrapolated to "
           "2000)\n",
           o->big_steps);
  if (c.nres > 0)
    print_paper(&c);
out:
  free(c.xyz);
  free(c.res);
  free(c.copy);
  free(c.info);
  msocl_runtime_destroy(c.rt);
  return rc == MSOCL_OK ? 0 : 1;
}

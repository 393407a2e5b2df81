/* A body dropped onto the ground: the options, simulation loop and report
 * that the jello and solid examples share. */
#include "drop.h"

#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* At rest: no point moved faster than REST_SPEED (m/s) on average between
 * samples a tenth of REST_SECONDS apart over the last REST_SECONDS. From
 * positions, not velocities: velocity Verlet's end-of-step velocity holds
 * half a step of the force that the ground then cancels, so a body at rest
 * on the ground still shows kinetic energy under it. */
#define REST_SPEED 0.01
#define REST_SECONDS 0.1

#define OPTIONS ":n:t:d:a:T:i:l:o:Kh"

static int usage(const drop_options *d)
{
  return cli_help(
      "usage: %s [-n SIZE] [-t SECONDS] [-d DEVICE_SPEC] [-a AIR] [-T DT]\n"
      "  [-i symplectic|explicit|verlet|rk4|implicit]\n"
      "  [-l auto|image2d|buffer|edges|grid] [-K] [-o OUT.obj|OUT.ply]\n"
      "  -n  %s (%d to %d, default %d)\n"
      "  -t  simulated seconds, > 0 and <= 1e5 (default %g)\n"
      "  -d  OpenCL device spec, as MSOCL_DEVICE (default: that "
      "variable)\n"
      "  -a  air resistance: every velocity times AIR a step, (0, 1] "
      "(default %g)\n"
      "  -T  time step in seconds, 1e-7 to 0.1 (default: half the stable "
      "step)\n"
      "  -i  integrator (default symplectic)\n"
      "  -l  spring layout (default auto: the library's choice)\n"
      "  -K  keep the model's point numbering (default: the library "
      "renumbers\n      the points so spring neighbours sit close)\n"
      "  -o  final mesh, OBJ or PLY by extension (default %s)\n"
      "  -h, --help  this text\n",
      d->prog, d->size_help, d->size_min, d->size_max, d->size, d->seconds,
      (double)d->air, d->out);
}

int drop_parse(drop_options *d, int argc, char **argv, int *done)
{
  int opt, k, rc = 0;
  double x;
  *done = 0;
  if ((rc = cli_long_options(d->prog, OPTIONS, argc, argv, done)) || *done)
    return rc ? rc : usage(d);
  opterr = 0;
  while (!rc && (opt = getopt(argc, argv, OPTIONS)) != -1) {
    switch (opt) {
    case 'n':
      rc = cli_int(d->prog, opt, optarg, d->size_name, d->size_min,
                   d->size_max, &d->size);
      break;
    case 't':
      if (!(rc = cli_double(d->prog, opt, optarg, "simulated time", 0.0, 1,
                            1e5, &x)))
        d->seconds = x;
      break;
    case 'a':
      if (!(rc = cli_double(d->prog, opt, optarg, "air resistance", 0.0, 1,
                            1.0, &x)))
        d->air = (float)x;
      break;
    case 'T':
      if (!(rc = cli_double(d->prog, opt, optarg, "time step", 1e-7, 0, 0.1,
                            &x)))
        d->dt = (float)x;
      break;
    case 'd': d->spec = optarg; break;
    case 'o': d->out = optarg; break;
    case 'K': d->keep_numbering = 1; break;
    case 'i':
      if (!(rc = cli_pick(d->prog, opt, optarg, "integrator",
                          cli_integrators, 5, &k)))
        d->integrator = (msocl_integrator)k;
      break;
    case 'l':
      if (!(rc = cli_pick(d->prog, opt, optarg, "layout", cli_layouts, 5,
                          &k)))
        d->layout = (msocl_layout)k;
      break;
    case 'h': *done = 1; return usage(d);
    default: return cli_bad_option(d->prog, opt);
    }
  }
  if (!rc)
    rc = cli_no_operands(d->prog, optind, argc, argv);
  if (!rc)
    rc = cli_output(d->prog, d->out, &d->ply);
  return rc;
}

/* Half the largest stable step of symplectic Euler, for every integrator:
 * collisions are resolved once a step, so a larger step (RK4's, implicit
 * Euler's unbounded one) would let the body sink further into the ground
 * each step. Explicit Euler needs a far smaller one. msocl_stable_dt finds
 * none for it without viscous damping, but the springs' dashpots damp
 * every deformation mode: with dashpots c = beta k, a mode of frequency w
 * has lambda^2 + beta w^2 lambda + w^2 = 0, and |1 + h lambda|^2 =
 * 1 - h beta w^2 + h^2 w^2 <= 1 for h <= beta at any w (while underdamped;
 * the symplectic bound already holds h d <= 2 for the overdamped ones).
 * So explicit Euler takes half of d->dashpot_ratio. *why says which. */
static int choose_dt(const drop_options *d, const msocl_model *m, float *dt,
                     const char **why)
{
  float h = 0.0f;
  int rc = msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &h);
  *why = "half the stable step";
  if (rc == MSOCL_OK && d->integrator == MSOCL_EXPLICIT_EULER) {
    if (d->dashpot_ratio > 0.0f) {
      if (d->dashpot_ratio < h) {
        h = d->dashpot_ratio;
        *why = "half the dashpots' c/k";
      }
    } else {
      float own = 0.0f;
      if ((rc = msocl_stable_dt(m, d->integrator, &own)) == MSOCL_OK &&
          own < h)
        h = own;
    }
  }
  *dt = 0.5f * h;
  return rc;
}

/* Writes the points on the model's triangles (inner points of a lattice,
 * the centre of a solid are left out), renumbered, with their normals. */
static int write_mesh(const char *path, int ply, const msocl_model *m,
                      int n, const float *xyz, const float *nrm)
{
  int ntri = 0, used = 0;
  const int *tri = NULL;
  int rc = msocl_model_triangles(m, &ntri, &tri);
  if (rc != MSOCL_OK)
    return rc;
  int *map = malloc((size_t)n * sizeof *map);
  int *ijk = malloc(3 * (size_t)ntri * sizeof *ijk + 1);
  float *p = malloc(6 * (size_t)n * sizeof *p);
  if (!map || !ijk || !p) {
    rc = MSOCL_ERR_NO_MEMORY;
  } else {
    float *q = p + 3 * (size_t)n; /* the normals */
    for (int i = 0; i < n; i++)
      map[i] = -1;
    for (int t = 0; t < 3 * ntri; t++) {
      int i = tri[t];
      if (map[i] < 0) {
        memcpy(p + 3 * used, xyz + 3 * i, 3 * sizeof *p);
        memcpy(q + 3 * used, nrm + 3 * i, 3 * sizeof *q);
        map[i] = used++;
      }
      ijk[t] = map[i];
    }
    rc = cli_write_mesh(path, ply, used, p, q, ntri, ijk);
  }
  free(map);
  free(ijk);
  free(p);
  return rc;
}

/* The fastest point's speed, m/s, from its move since `prev` over `secs`;
 * copies xyz into prev. */
static double fastest(float *prev, const float *xyz, int n, double secs)
{
  double top = 0.0;
  for (int i = 0; i < 3 * n; i += 3) {
    double dx = xyz[i] - prev[i], dy = xyz[i + 1] - prev[i + 1],
           dz = xyz[i + 2] - prev[i + 2];
    double v = sqrt(dx * dx + dy * dy + dz * dz);
    if (v > top)
      top = v;
  }
  memcpy(prev, xyz, 3 * (size_t)n * sizeof *prev);
  return top / secs;
}

/* Steps `total` steps of o->dt: all but the first are timed (the first
 * pays the first kernel launches), the last `tail` in ten chunks, each
 * followed by a look at the positions. Fills *secs and *vmax (the fastest
 * point's speed over the tail). */
static int run(msocl_sim *s, const msocl_sim_options *o, long long total,
               long long tail, int n, float *xyz, float *prev, double *secs,
               double *vmax)
{
  long long chunk = tail >= 10 ? tail / 10 : 1;
  cli_progress p;
  *secs = *vmax = 0.0;
  cli_progress_start(&p, total - 1);
  int rc = msocl_sim_step(s, 1);
  if (rc == MSOCL_OK)
    rc = cli_step(s, &p, total - 1 - tail, 0, secs);
  if (rc == MSOCL_OK)
    rc = msocl_sim_read_positions(s, prev);
  for (long long done = 0; rc == MSOCL_OK && done < tail; done += chunk) {
    long long k = tail - done < chunk ? tail - done : chunk;
    if ((rc = cli_step(s, &p, k, 0, secs)) == MSOCL_OK &&
        (rc = msocl_sim_read_positions(s, xyz)) == MSOCL_OK) {
      double v = fastest(prev, xyz, n, k * (double)o->dt);
      if (v > *vmax)
        *vmax = v;
    }
  }
  cli_progress_end(&p);
  return rc;
}

/* The simulation proper: reports, fills xyz (3 n floats; prev and nrm are
 * scratch of the same size) and writes the mesh. */
static int simulate(const drop_options *d, msocl_runtime *rt,
                    const msocl_model *m, double mass, int n, float *xyz,
                    float *prev, float *nrm)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.integrator = d->integrator;
  o.tuning.layout = d->layout;
  o.tuning.renumber = d->keep_numbering ? MSOCL_OFF : MSOCL_AUTO;
  o.dt = d->dt;
  const char *why = "-T";
  int rc = d->dt > 0 ? MSOCL_OK : choose_dt(d, m, &o.dt, &why);
  if (rc != MSOCL_OK)
    return cli_fail(d->prog, "choosing the step", rc);
  long long total = llround(d->seconds / o.dt);
  if (total < 2)
    total = 2;
  long long tail = llround(REST_SECONDS / o.dt);
  if (tail > total - 1)
    tail = total - 1;

  msocl_sim *s = NULL;
  double t0 = cli_now();
  rc = msocl_sim_create(&s, rt, m, &o);
  double setup = cli_now() - t0;
  if (rc != MSOCL_OK)
    return cli_fail(d->prog, "setting up the simulation", rc);
  msocl_device_info info;
  msocl_layout layout;
  if ((rc = msocl_sim_device_info(s, &info)) != MSOCL_OK ||
      (rc = msocl_sim_layout(s, &layout)) != MSOCL_OK) {
    msocl_sim_destroy(s);
    return cli_fail(d->prog, "asking the simulation", rc);
  }
  printf("device: %s [%s]\nlayout: %s, integrator: %s\n", info.name,
         info.platform_name,
         (int)layout >= 0 && (int)layout < 5 ? cli_layouts[layout] : "other",
         cli_integrators[d->integrator]);
  printf("dt %.3g s (%s), air resistance %g a step (%.3g/s)\n"
         "%.3g s simulated: %lld steps (setup %.3f s)\n",
         (double)o.dt, why, (double)d->air,
         0.0 - log((double)d->air) / o.dt, total * (double)o.dt,
         total, setup);

  double secs = 0.0, vmax = 0.0;
  msocl_energy e;
  rc = run(s, &o, total, tail, n, xyz, prev, &secs, &vmax);
  if (rc == MSOCL_OK)
    rc = msocl_sim_energy(s, &e);
  if (rc == MSOCL_OK)
    rc = msocl_sim_read_normals(s, nrm);
  msocl_sim_destroy(s);
  if (rc != MSOCL_OK)
    return cli_fail(d->prog, "simulating", rc);

  double low = INFINITY;
  for (int i = 0; i < n; i++)
    if (xyz[3 * i + 1] < low)
      low = xyz[3 * i + 1];
  printf("%.3f s: %.1f steps/s, %.3g point-steps/s\n", secs,
         secs > 0 ? (total - 1) / secs : 0.0,
         secs > 0 ? (double)(total - 1) * n / secs : 0.0);
  printf("final kinetic energy %.3g J (the whole %.3g kg at %.3g cm/s)\n",
         e.kinetic, mass, 100 * sqrt(2 * e.kinetic / mass));
  printf("at rest: %s (fastest point %.3g cm/s over the last %.3g s; "
         "threshold %g cm/s)\n",
         vmax < REST_SPEED ? "yes" : "no", 100 * vmax, tail * (double)o.dt,
         100 * REST_SPEED);
  printf("lowest point %.3g mm above the plane\n", 1e3 * low);

  if ((rc = write_mesh(d->out, d->ply, m, n, xyz, nrm)) != MSOCL_OK)
    return cli_fail(d->prog, d->out, rc);
  printf("wrote %s\n", d->out);
  return 0;
}

int drop_run(const drop_options *d, msocl_model *m, double mass,
             float **xyz)
{
  const float up[3] = {0.0f, 1.0f, 0.0f};
  int n = 0, rc;
  *xyz = NULL;
  if ((rc = msocl_model_add_plane(m, up, 0.0f, 0.5f)) != MSOCL_OK)
    return cli_fail(d->prog, "adding the ground", rc);
  if ((rc = msocl_model_set_air_resistance(m, d->air)) != MSOCL_OK)
    return cli_fail(d->prog, "air resistance", rc);
  if ((rc = msocl_model_point_count(m, &n)) != MSOCL_OK)
    return cli_fail(d->prog, "counting points", rc);

  msocl_runtime *rt = NULL;
  if ((rc = msocl_runtime_create(&rt, d->spec)) != MSOCL_OK)
    return cli_fail(d->prog, "choosing a device", rc);
  float *p = malloc(3 * (size_t)n * sizeof *p);
  float *prev = malloc(3 * (size_t)n * sizeof *prev);
  float *nrm = malloc(3 * (size_t)n * sizeof *nrm);
  int status = p && prev && nrm
                   ? simulate(d, rt, m, mass, n, p, prev, nrm)
                   : cli_fail(d->prog, "positions", MSOCL_ERR_NO_MEMORY);
  free(prev);
  free(nrm);
  msocl_runtime_destroy(rt);
  if (status)
    free(p);
  else
    *xyz = p;
  return status;
}

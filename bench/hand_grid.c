/* The tablecloth built by hand from points and springs, as a user porting
 * from another library would, against the same cloth from
 * msocl_model_cloth_grid: steps a second under AUTO (and, for the
 * hand-built one, BUFFER forced: what AUTO gave it before it recognised
 * grids), and whether the hand-built AUTO run ends bit for bit where the
 * builder's does. Public API only, so it links against any build:
 *
 *   cc -std=c99 -O2 -Ilib bench/hand_grid.c -L.libs -lmsocl -lm \
 *      -Wl,-rpath,$PWD/.libs -o hand_grid
 *   ./hand_grid N steps reps
 *
 * Prints one line per model and layout: the layout chosen, the best of
 * `reps` timings of `steps` steps, in steps/s. Results:
 * docs/PERFORMANCE.md ("Grids built by hand"). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "msocl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void die(const char *what)
{
  fprintf(stderr, "hand_grid: %s: %s\n", what, msocl_last_error());
  exit(1);
}

/* The scene: tests/scenes.c's tablecloth (1 m, 0.5 kg, k 50/10/10, a
 * round table under it, light viscous damping). */
static void describe(msocl_cloth_desc *d, int n)
{
  msocl_cloth_desc_init(d);
  d->nx = d->ny = n;
  d->origin[0] = -0.5f;
  d->origin[1] = 0.05f;
  d->origin[2] = -0.5f;
  d->u[0] = 0.0f; d->u[1] = 0.0f; d->u[2] = 1.0f;
  d->v[0] = 1.0f; d->v[1] = 0.0f; d->v[2] = 0.0f;
  d->point_mass = 0.5f / (float)(n * n);
  d->k_stretch = 50.0f;
  d->k_shear = 10.0f;
  d->k_bend = 10.0f;
}

static void dress(msocl_model *m, int n)
{
  const float top[3] = {0.0f, 0.0f, 0.0f};
  if (msocl_model_add_table(m, top, 0.35f, 0.3f) ||
      msocl_model_set_viscous_damping(m, 0.25f / (float)(n * n)))
    die("scene");
}

/* By hand: the points row by row (the builder's positions, so both start
 * alike), then the springs kind by kind, each kind at its rest length
 * (the grid's spacing along it, computed once in double). */
static msocl_model *by_hand(const msocl_model *b, const msocl_cloth_desc *d)
{
  const int n = d->nx, np = n * n, most = 6 * np;
  float *xyz = malloc(3 * (size_t)np * sizeof *xyz);
  float *mass = malloc((size_t)np * sizeof *mass);
  int *ij = malloc(2 * (size_t)most * sizeof *ij), ns = 0;
  float *k = malloc((size_t)most * sizeof *k);
  float *rest = malloc((size_t)most * sizeof *rest);
  if (!xyz || !mass || !ij || !k || !rest)
    die("memory");
  if (msocl_model_get_positions(b, xyz))
    die("positions");
  for (int p = 0; p < np; p++)
    mass[p] = d->point_mass;
  double du[3], dv[3], len[4] = {0, 0, 0, 0};
  for (int c = 0; c < 3; c++) {
    du[c] = (double)d->u[c] / (n - 1);
    dv[c] = (double)d->v[c] / (n - 1);
    len[0] += du[c] * du[c];
    len[1] += dv[c] * dv[c];
    len[2] += (du[c] + dv[c]) * (du[c] + dv[c]);
    len[3] += (dv[c] - du[c]) * (dv[c] - du[c]);
  }
  float r[6];
  for (int q = 0; q < 4; q++)
    r[q] = (float)sqrt(len[q]);
  r[4] = (float)(2.0 * sqrt(len[0]));
  r[5] = (float)(2.0 * sqrt(len[1]));
#define ADD(p, q, kk, rr)                                                     \
  (ij[2 * ns] = (p), ij[2 * ns + 1] = (q), k[ns] = (kk), rest[ns++] = (rr))
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      if (i + 1 < n) ADD(j * n + i, j * n + i + 1, d->k_stretch, r[0]);
      if (j + 1 < n) ADD(j * n + i, (j + 1) * n + i, d->k_stretch, r[1]);
    }
  for (int j = 0; j + 1 < n; j++)
    for (int i = 0; i + 1 < n; i++) {
      ADD(j * n + i, (j + 1) * n + i + 1, d->k_shear, r[2]);
      ADD(j * n + i + 1, (j + 1) * n + i, d->k_shear, r[3]);
    }
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      if (i + 2 < n) ADD(j * n + i, j * n + i + 2, d->k_bend, r[4]);
      if (j + 2 < n) ADD(j * n + i, (j + 2) * n + i, d->k_bend, r[5]);
    }
#undef ADD
  msocl_model *m = NULL;
  if (msocl_model_create(&m) ||
      msocl_model_add_points(m, np, xyz, mass, NULL) ||
      msocl_model_add_springs(m, ns, ij, k, rest, NULL))
    die("hand-built model");
  free(xyz);
  free(mass);
  free(ij);
  free(k);
  free(rest);
  return m;
}

static const char *name(msocl_layout l)
{
  return l == MSOCL_LAYOUT_GRID ? "GRID" : l == MSOCL_LAYOUT_BUFFER ? "BUFFER"
       : l == MSOCL_LAYOUT_IMAGE2D ? "IMAGE2D" : "EDGES";
}

/* Best steps/s of `reps` runs of `steps` steps; final positions in out. */
static double timed(msocl_runtime *rt, const msocl_model *m, msocl_layout lay,
                    float dt, int steps, int reps, float *out,
                    msocl_layout *got)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.tuning.layout = lay;
  double best = 0.0;
  for (int r = 0; r < reps; r++) {
    msocl_sim *s = NULL;
    if (msocl_sim_create(&s, rt, m, &o) || msocl_sim_layout(s, got) ||
        msocl_sim_step(s, 5))
      die("sim");
    double t0 = now();
    if (msocl_sim_step(s, steps))
      die("step");
    double rate = steps / (now() - t0);
    best = rate > best ? rate : best;
    if (msocl_sim_read_positions(s, out))
      die("read");
    msocl_sim_destroy(s);
  }
  return best;
}

int main(int argc, char **argv)
{
  if (argc != 4) {
    fprintf(stderr, "usage: hand_grid N steps reps\n");
    return 2;
  }
  const int n = atoi(argv[1]), steps = atoi(argv[2]), reps = atoi(argv[3]);
  msocl_cloth_desc d;
  describe(&d, n);
  msocl_model *b = NULL;
  if (msocl_model_cloth_grid(&b, &d))
    die("cloth");
  msocl_model *h = by_hand(b, &d);
  dress(b, n);
  dress(h, n);
  float dt;
  if (msocl_safe_dt(b, MSOCL_SYMPLECTIC_EULER, &dt))
    die("safe_dt");
  msocl_runtime *rt = NULL;
  if (msocl_runtime_create(&rt, "cpu"))
    die("runtime");
  const size_t bytes = 3 * (size_t)n * n * sizeof(float);
  float *pb = malloc(bytes), *ph = malloc(bytes), *pf = malloc(bytes);
  msocl_layout lb, lh, lf;
  double rb = timed(rt, b, MSOCL_LAYOUT_AUTO, dt, steps, reps, pb, &lb);
  double rh = timed(rt, h, MSOCL_LAYOUT_AUTO, dt, steps, reps, ph, &lh);
  double rf = timed(rt, h, MSOCL_LAYOUT_BUFFER, dt, steps, reps, pf, &lf);
  printf("%dx%d builder AUTO %s %.1f steps/s\n", n, n, name(lb), rb);
  printf("%dx%d by-hand AUTO %s %.1f steps/s (%.2fx builder), %s the "
         "builder's positions\n", n, n, name(lh), rh, rh / rb,
         memcmp(pb, ph, bytes) ? "NOT bitwise" : "bitwise");
  printf("%dx%d by-hand BUFFER %s %.1f steps/s (%.2fx builder), %s\n", n, n,
         name(lf), rf, rf / rb,
         memcmp(pb, pf, bytes) ? "NOT bitwise" : "bitwise");
  msocl_runtime_destroy(rt);
  msocl_model_destroy(b);
  msocl_model_destroy(h);
  free(pb);
  free(ph);
  free(pf);
  return 0;
}

/* The planes (kernels/planes.cl): a model's steps, every integrator's
 * (implicit Euler's CG: planes_implicit.c), over x, y, z planes of
 * floats - GRID's padded rows, or BUFFER's, EDGES's and IMAGE2D's points
 * in index order, their neighbours found through the layout's own
 * connectivity - which PoCL's CPU device runs eight or sixteen points to
 * an instruction. The state lives in the planes (state.c moves it to
 * and from the host); whatever writes it calls msocl__planes_written. */
#include "config.h"
#include "planes.h"
#include "schedule.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TRY MSOCL__TRY
#define launch msocl__pl_launch

_Static_assert(PL_COUNT == sizeof ((msocl__engine *)0)->pl_k /
                               sizeof(cl_kernel),
               "msocl__engine.pl_k holds every planes kernel");
_Static_assert(PL_COUNT == sizeof ((msocl__engine *)0)->pl_ks /
                               sizeof(cl_kernel),
               "msocl__engine.pl_ks holds every twin");

static const char *const names[PL_COUNT] = {
    "msocl_planes_velocity", "msocl_planes_position", "msocl_planes_fused",
    "msocl_planes_drift",
    "msocl_planes_vkick",
    "msocl_planes_rk4_first", "msocl_planes_rk4_middle",
    "msocl_planes_rk4_last", "msocl_planes_strain", "msocl_planes_commit",
    "msocl_planes_strain_v", "msocl_planes_ie_rhs", "msocl_planes_ie_apply",
    "msocl_planes_cg_step", "msocl_planes_cg_direction",
    "msocl_planes_ie_finish", "msocl_sum_points", "msocl_planes_euler"};

/* Whether planes kernel q gathers over its springs (and so has a _spill
 * twin in a program built with a spill). */
static int gathers(int q)
{
  return q == PL_VELOCITY || q == PL_FUSED || q == PL_EULER || q == PL_KICK ||
         q == PL_RK4 || q == PL_RK4_MID || q == PL_RK4_LAST ||
         q == PL_STRAIN || q == PL_STRAIN_V || q == PL_IE_RHS ||
         q == PL_IE_APPLY;
}

/* The planes' shape for model m's grid: rows padded to whole work-groups
 * - of 64 points, or of 32, 16 or 8 for a narrow grid (a lattice's rows
 * are short), so that few padding points are computed - plus two points
 * each side; a lattice's layers padded by two rows each side, and two
 * padding layers at each end. In size_t: a skinny grid's plane can pass
 * INT_MAX floats. */
struct geometry {
  size_t group, wide, pitch, slab, plane;
};

static struct geometry geometry_in(int nx, int ny, int nz)
{
  struct geometry g;
  g.group = 64;
  while (g.group > 8 && (size_t)nx <= g.group / 2)
    g.group /= 2;
  g.wide = ((size_t)nx + g.group - 1) / g.group * g.group;
  g.pitch = g.wide + 4;
  g.slab = g.pitch * ((size_t)ny + 4);
  g.plane = g.slab * (nz > 0 ? (size_t)nz + 4 : 1);
  return g;
}

static struct geometry geometry_of(const msocl_model *m)
{
  return geometry_in(m->grid.nx, m->grid.ny, m->grid.nz);
}

/* BUFFER and IMAGE2D: the n points in one row of work-groups of 64, no
 * padding around them (no neighbour is read at an offset); `pitch`
 * carries n to the kernels, `slab` the stride of the planes' copy of
 * BUFFER's table. */
static struct geometry geometry_row(int n)
{
  struct geometry g;
  g.group = 64;
  g.wide = ((size_t)n + g.group - 1) / g.group * g.group;
  g.pitch = (size_t)n;
  g.slab = g.wide;
  g.plane = g.wide;
  return g;
}

static struct geometry geometry_engine(const msocl__engine *s)
{
  return s->lay.kind == MSOCL_LAYOUT_GRID
             ? geometry_in(s->lay.grid_nx, s->lay.grid_ny, s->lay.grid_nz)
             : geometry_row(s->n);
}

/* Planes (floats a padded point) each integrator and strain limit keeps:
 * p and v twice (12) and the inverse mass and pin (2); Verlet's
 * acceleration; RK4's or implicit Euler's stage states and sums; a
 * strain sweep's output, and Provot's second. */
static size_t planes_per_point(const msocl_sim_options *o)
{
  size_t n = 14;
  if (o->integrator == MSOCL_VERLET)
    n += 3;
  if (o->integrator == MSOCL_RK4 || o->integrator == MSOCL_IMPLICIT_EULER)
    n += 18;
  if (o->strain != MSOCL_STRAIN_NONE)
    n += 3;
  if (o->strain == MSOCL_STRAIN_PROVOT)
    n += 3;
  return n;
}

size_t msocl__planes_bytes(const msocl_model *m, const msocl_sim_options *o)
{
  return geometry_of(m).plane * planes_per_point(o) * sizeof(float);
}

/* Why a model's GRID cannot run in planes on points [lo, hi) of its n
 * (every integrator and strain limit can); NULL: it can. */
static const char *unfit(const msocl_model *m, int lo, int hi)
{
  (void)lo; /* a split's engines run the whole grid (exchange_slices.c) */
  (void)hi;
  /* the kernels index all three planes with an int */
  if (3 * geometry_of(m).plane > (size_t)INT_MAX)
    return "index at most 2^31 floats (the grid and its padding are too "
           "large)";
  return NULL;
}

/* AUTO's limit on the padding: where the planes hold more than this many
 * padded points a point, and more than LAVISH_BYTES, the padding would
 * multiply the memory (a skinny grid: 2 x 2 x n pads to 12 x 6 x n). */
#define LAVISH_FACTOR 4
#define LAVISH_BYTES ((size_t)64 << 20)

static int lavish(const msocl_model *m, const msocl_sim_options *o)
{
  return geometry_of(m).plane > LAVISH_FACTOR * (size_t)m->n &&
         msocl__planes_bytes(m, o) > LAVISH_BYTES;
}

int msocl__planes_would(const msocl_sim_options *o, const msocl_model *m,
                        int lo, int hi)
{
  return !unfit(m, lo, hi) && !lavish(m, o);
}

int msocl__planes_refused(const msocl_sim_options *o, const msocl_model *m,
                          int lo, int hi)
{
  const char *why =
      o->tuning.layout == MSOCL_LAYOUT_GRID ? unfit(m, lo, hi) : NULL;
  if (why)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "GRID's planes %s: a %d x %d x %d grid pads to %zu "
                       "floats a plane (use BUFFER)", why, m->grid.nx,
                       m->grid.ny, m->grid.nz, geometry_of(m).plane);
  return MSOCL_OK;
}

int msocl__planes_fit(const msocl__engine *s)
{
  /* GRID: msocl__planes_refused, before anything was allocated */
  if (s->lay.kind != MSOCL_LAYOUT_GRID &&
      3 * geometry_row(s->n).plane > (size_t)INT_MAX)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "the planes index at most 2^31 floats: %d points are "
                       "too many", s->n);
  return MSOCL_OK;
}

/* The twin that takes kernel k's arguments too: a planes kernel's _spill
 * twin, the sweep's still one (planes_rows.c), or NULL. */
static cl_kernel twin(const msocl__engine *s, cl_kernel k)
{
  if (k && k == s->pl_rows)
    return s->pl_rows_still;
  for (int q = 0; q < PL_COUNT; q++)
    if (s->pl_k[q] == k)
      return s->pl_ks[q];
  return NULL;
}

int msocl__pl_arg(msocl__engine *s, cl_kernel k, const char *name,
                  size_t size, const void *v)
{
  TRY(msocl__arg(s, k, name, size, v));
  cl_kernel t = twin(s, k);
  return t ? msocl__arg(s, t, name, size, v) : MSOCL_OK;
}

int msocl__pl_mem(msocl__engine *s, cl_kernel k, const char *name, cl_mem m)
{
  return msocl__pl_arg(s, k, name, sizeof m, &m);
}

int msocl__pl_named(msocl__engine *s, cl_kernel k,
                    const struct msocl__named *vals, int n)
{
  TRY(msocl__args_named(s, k, vals, n));
  cl_kernel t = twin(s, k);
  return t ? msocl__args_named(s, t, vals, n) : MSOCL_OK;
}

int msocl__pl_conn(msocl__engine *s, cl_kernel k)
{
  cl_kernel t = twin(s, k);
  if (t)
    TRY(msocl__layout_set_args(&s->pl_lay, s->dev, t));
  return msocl__layout_set_args(&s->pl_lay, s->dev, k);
}

/* Where point j sits in each plane (planes.cl's MSOCL_PLANES_AT). */
int msocl__pl_address(const msocl__engine *s, int j)
{
  if (s->lay.kind != MSOCL_LAYOUT_GRID)
    return j;
  const int nx = s->lay.grid_nx, ny = s->lay.grid_ny;
  const int x = j % nx, y = (j / nx) % ny, z = j / (nx * ny);
  const int a = (y + 2) * s->pl_pitch + x + 2;
  return s->lay.grid_nz > 0 ? a + (z + 2) * s->pl_slab : a;
}

int msocl__pl_shape(msocl__engine *s, cl_kernel k)
{
  const int nx = s->lay.kind == MSOCL_LAYOUT_GRID ? s->lay.grid_nx : s->n;
  const struct msocl__named shape[] = {{"nx", sizeof nx, &nx},
                                       {"pitch", sizeof(int), &s->pl_pitch},
                                       {"slab", sizeof(int), &s->pl_slab},
                                       {"plane", sizeof(int), &s->pl_plane}};
  return msocl__pl_named(s, k, shape, 4);
}

/* Planes kernel k's (and the sweep's) gravity, viscous damping and air
 * resistance, where it has them. */
static int forces(msocl__engine *s, cl_kernel k)
{
  const struct msocl__named f[] = {
      {"gravity", sizeof s->gravity, &s->gravity},
      {"viscous", sizeof(float), &s->viscous},
      {"air", sizeof(float), &s->air}};
  return msocl__pl_named(s, k, f, 3);
}

int msocl__pl_forces(msocl__engine *s)
{
  for (int q = 0; q < PL_COUNT; q++)
    TRY(forces(s, s->pl_k[q]));
  if (s->pl_rows_steps)
    TRY(forces(s, s->pl_rows_steps));
  return s->pl_rows ? forces(s, s->pl_rows) : MSOCL_OK;
}


/* The arguments that hold one value for the engine's life, by name, in
 * every planes kernel that has them: all but the planes that ping-pong
 * (set at each launch) and RK4's stage constant. */
int msocl__pl_fixed(msocl__engine *s, cl_kernel k)
{
  const struct msocl__named fixed[] = {
      {"aux", sizeof s->pl_aux, &s->pl_aux},
      {"dt", sizeof(float), &s->o.dt},
      {"col", sizeof s->pl_col, &s->pl_col},
      {"limit", sizeof(float), &s->o.strain_limit},
      {"n", sizeof(int), &s->n},
      {"sum_p", sizeof s->pl_sum[0], &s->pl_sum[0]},
      {"sum_v", sizeof s->pl_sum[1], &s->pl_sum[1]},
      {"acc", sizeof s->pl_a, &s->pl_a},
      {"acc_out", sizeof s->pl_a, &s->pl_a},
      {"p4", sizeof s->pl_p4, &s->pl_p4}};
  TRY(msocl__pl_named(s, k, fixed, (int)(sizeof fixed / sizeof fixed[0])));
  TRY(msocl__pl_shape(s, k));
  return forces(s, k);
}

static int fixed_args(msocl__engine *s)
{
  for (int q = 0; q < PL_COUNT; q++) {
    if (gathers(q))
      TRY(msocl__pl_conn(s, s->pl_k[q]));
    TRY(msocl__pl_fixed(s, s->pl_k[q]));
  }
  return MSOCL_OK;
}

/* The colliders for the planes kernels: s->col's values (8 a collider),
 * each at the start of a float4 of its own. Side by side, two values read
 * with the same arithmetic (a sphere's centre y and z) were paired by
 * -O3's SLP vectorizer into a <2 x float>, and PoCL then left the whole
 * kernel unvectorised (planes.cl's header says why). A moving collider's
 * values are rewritten before its steps (sim/sim_colliders.c). */
static int collider_table(msocl__engine *s)
{
  enum { VALUES = MSOCL__COL_VALUES * MSOCL__MAX_COLLIDERS };
  float packed[8 * MSOCL__MAX_COLLIDERS], spread[4 * VALUES] = {0};
  const size_t used = 8 * (size_t)s->ncol * sizeof(float);
  if (used > 0)
    MSOCL__CL(clEnqueueReadBuffer(s->dev->queue, s->col, CL_TRUE, 0, used,
                                  packed, 0, NULL, NULL));
  /* s->col's 8, then msocl__collider.x; no motion */
  for (int c = 0; c < s->ncol; c++)
    for (int k = 0; k < 8; k++) {
      spread[4 * (MSOCL__COL_VALUES * c + k)] = packed[8 * c + k];
      spread[4 * (MSOCL__COL_VALUES * c + 8 + k)] = s->pl_colx[8 * c + k];
    }
  int rc = MSOCL_OK;
  s->pl_col = msocl__buffer(s->dev, CL_MEM_READ_ONLY, sizeof spread, spread,
                            "colliders", &rc);
  return rc;
}

/* The spill's offsets, padded to the plane (a padding point spills
 * nothing), and the list of the points that spill, for the _spill
 * twins. */
static int spill_list(msocl__engine *s, size_t n, size_t P, int *nsp)
{
  int *off = malloc((P + 1) * sizeof *off), *list = malloc(n * sizeof *list);
  int rc = off && list ? MSOCL_OK
                       : msocl__fail(MSOCL_ERR_NO_MEMORY, "planes' spill");
  cl_int e = CL_SUCCESS;
  if (rc == MSOCL_OK)
    e = clEnqueueReadBuffer(s->dev->queue, s->lay.spill, CL_TRUE, 0,
                            (n + 1) * sizeof *off, off, 0, NULL, NULL);
  if (rc == MSOCL_OK && e != CL_SUCCESS)
    rc = msocl__fail(e, "reading the spill: %s", msocl_err_name(e));
  if (rc == MSOCL_OK) {
    for (size_t i = n + 1; i <= P; i++)
      off[i] = off[n];
    int nl = 0;
    for (size_t i = 0; i < n; i++)
      if (off[i + 1] > off[i])
        list[nl++] = (int)i;
    *nsp = off[n];
    s->pl_nspill = nl;
    s->pl_table[3] = msocl__buffer(s->dev, CL_MEM_READ_ONLY,
                                   (P + 1) * sizeof *off, off,
                                   "planes' spill", &rc);
    s->pl_list = msocl__buffer(s->dev, CL_MEM_READ_ONLY,
                               (size_t)nl * sizeof *list, list,
                               "planes' spill", &rc);
  }
  free(off);
  free(list);
  return rc;
}

/* BUFFER's slot table for the planes kernels: each slot `plane` entries
 * apart instead of n, the padding work-items' entries free slots (the
 * point itself, zeros), and (rest, k) pairs split into a plane of rests
 * and one of stiffnesses - eight or sixteen work-items read a slot with
 * contiguous vector loads, not gathers; the spill's entries follow the
 * table as they do in the layout's (pairs after both planes). */
static int padded_table(msocl__engine *s)
{
  s->pl_lay = s->lay;
  if (s->lay.kind != MSOCL_LAYOUT_BUFFER &&
      s->lay.kind != MSOCL_LAYOUT_EDGES)
    return MSOCL_OK;
  /* a model without springs still has one (free) slot, as layout.c's */
  const size_t n = (size_t)s->n,
               S = (size_t)(s->lay.slots > 0 ? s->lay.slots : 1),
               P = (size_t)s->pl_plane;
  int nsp = 0, rc = s->lay.spill ? spill_list(s, n, P, &nsp) : MSOCL_OK;
  const size_t sp = (size_t)nsp;
  /* bytes an entry: nbr; rk (classes: a byte, else rest and k); dashpots
   * where each slot has its own (values, damped) */
  const size_t size[3] = {sizeof(cl_int),
                          s->lay.classes ? 1 : 2 * sizeof(cl_float),
                          !s->lay.classes && s->damped ? sizeof(cl_float)
                                                       : 0};
  cl_mem from[3] = {s->lay.con, s->lay.rk, s->lay.damp};
  for (int q = 0; q < 3 && rc == MSOCL_OK; q++) {
    if (!size[q])
      continue;
    const size_t z = size[q];
    unsigned char *in = malloc((S * n + sp) * z),
                  *out = calloc(S * P + sp, z);
    if (!in || !out)
      rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "planes' slot table");
    cl_int e = CL_SUCCESS;
    if (rc == MSOCL_OK)
      e = clEnqueueReadBuffer(s->dev->queue, from[q], CL_TRUE, 0,
                              (S * n + sp) * z, in, 0, NULL, NULL);
    if (rc == MSOCL_OK && e != CL_SUCCESS)
      rc = msocl__fail(e, "reading the slot table: %s", msocl_err_name(e));
    for (size_t t = 0; rc == MSOCL_OK && t < S; t++) {
      if (q == 1 && !s->lay.classes) /* rests, then stiffnesses */
        for (size_t i = 0; i < n; i++) {
          memcpy(out + (t * P + i) * sizeof(float), in + (t * n + i) * z,
                 sizeof(float));
          memcpy(out + ((S + t) * P + i) * sizeof(float),
                 in + (t * n + i) * z + sizeof(float), sizeof(float));
        }
      else
        memcpy(out + t * P * z, in + t * n * z, n * z);
      for (size_t i = n; q == 0 && i < P; i++) /* free: the point itself */
        ((cl_int *)out)[t * P + i] = (cl_int)i;
    }
    if (rc == MSOCL_OK) {
      memcpy(out + S * P * z, in + S * n * z, sp * z);
      s->pl_table[q] = msocl__buffer(s->dev, CL_MEM_READ_ONLY,
                                     (S * P + sp) * z, out,
                                     "planes' slot table", &rc);
    }
    free(in);
    free(out);
  }
  if (rc != MSOCL_OK)
    return rc;
  s->pl_lay.con = s->pl_table[0];
  s->pl_lay.rk = s->pl_table[1];
  if (s->pl_table[2])
    s->pl_lay.damp = s->pl_table[2];
  if (s->pl_table[3])
    s->pl_lay.spill = s->pl_table[3];
  return MSOCL_OK;
}

/* Planes kernel q from prog, and its _spill twin where it has one (the
 * twin's last argument, the list of the points that spill, set). */
static int make_kernel(msocl__engine *s, cl_program prog, int q)
{
  const char *name = names[q];
  const unsigned bit = 1u << q;
  s->pl_wide &= ~bit;
  if (msocl__pl_wide_name(q) && msocl__pl_wide(s)) {
    name = msocl__pl_wide_name(q);
    s->pl_wide |= bit;
  }
  TRY(msocl__kernel_make(s->dev, prog, name, &s->pl_k[q]));
  if (s->pl_nspill == 0 || !gathers(q))
    return MSOCL_OK;
  char twin[64];
  snprintf(twin, sizeof twin, "%s_spill", names[q]);
  TRY(msocl__kernel_make(s->dev, prog, twin, &s->pl_ks[q]));
  return msocl__arg_mem(s, s->pl_ks[q], "spilled", s->pl_list);
}

/* Whether planes kernel q reads the collider table (its `col`). */
static int reads_colliders(int q)
{
  return q == PL_VELOCITY || q == PL_FUSED || q == PL_EULER || q == PL_KICK ||
         q == PL_RK4 || q == PL_RK4_MID || q == PL_RK4_LAST ||
         q == PL_STRAIN_V || q == PL_DRIFT || q == PL_IE_FINISH;
}

int msocl__planes_rebuild(msocl__engine *s, cl_program prog, int all)
{
  /* nothing queued may still need a kernel released here */
  MSOCL__CL(clFinish(s->dev->queue));
  s->pl_rebuilds++;
  for (int q = 0; q < PL_COUNT; q++) {
    if (!all && !reads_colliders(q))
      continue;
    msocl__kernel_free(s->dev, &s->pl_k[q]);
    msocl__kernel_free(s->dev, &s->pl_ks[q]);
    TRY(make_kernel(s, prog, q));
  }
  /* every fixed argument again: those of the kernels kept are unchanged;
   * the ping-pong ones are set at each launch */
  TRY(fixed_args(s));
  return msocl__pl_rows_rebuild(s, prog);
}

int msocl__planes_create(msocl__engine *s, cl_program prog)
{
  /* unfit() kept 3 planes within INT_MAX floats */
  const struct geometry g = geometry_engine(s);
  s->pl_group = g.group;
  s->pl_pitch = (int)g.pitch;
  s->pl_slab = (int)g.slab;
  s->pl_plane = (int)g.plane;
  s->pl_global[0] = g.wide;
  s->pl_global[1] = s->lay.grid_ny > 0 ? (size_t)s->lay.grid_ny : 1;
  s->pl_global[2] = s->lay.grid_nz > 0 ? (size_t)s->lay.grid_nz : 1;
  TRY(padded_table(s));
  for (int q = 0; q < PL_COUNT; q++)
    TRY(make_kernel(s, prog, q));
  /* and Verlet's acceleration, RK4's stage states and sums, Provot's
   * sweeps */
  cl_mem *bufs[14] = {&s->pl_p[0],  &s->pl_p[1],   &s->pl_v[0],
                      &s->pl_v[1],  &s->pl_aux,    &s->pl_a,
                      &s->pl_sp[0], &s->pl_sp[1],  &s->pl_sv[0],
                      &s->pl_sv[1], &s->pl_sum[0], &s->pl_sum[1],
                      &s->pl_s[0],  &s->pl_s[1]};
  for (int q = 0; q < 14; q++) {
    if ((q == 5 && s->o.integrator != MSOCL_VERLET) ||
        (q > 5 && q < 12 && s->o.integrator != MSOCL_RK4 &&
         s->o.integrator != MSOCL_IMPLICIT_EULER) ||
        (q >= 12 && s->o.strain == MSOCL_STRAIN_NONE) ||
        (q == 13 && s->o.strain != MSOCL_STRAIN_PROVOT))
      continue;
    /* the padding is read (and its terms discarded): zeros, not garbage */
    const size_t bytes =
        (q == 4 ? 2 : 3) * (size_t)s->pl_plane * sizeof(float);
    int rc = MSOCL_OK;
    *bufs[q] = msocl__buffer(s->dev, CL_MEM_READ_WRITE, bytes, NULL,
                             "planes", &rc);
    TRY(rc);
    const float zero = 0.0f;
    MSOCL__CL(clEnqueueFillBuffer(s->dev->queue, *bufs[q], &zero, sizeof zero,
                                  0, bytes, 0, NULL, NULL));
  }
  TRY(collider_table(s));
  TRY(msocl__pl_pack_create(s, prog));
  TRY(fixed_args(s));
  return msocl__pl_rows_create(s, prog);
}

/* A split engine's passes: the rows (a lattice's layers; BUFFER's and
 * IMAGE2D's work-groups) that hold its points, or those of the span a
 * boundary-first phase runs (sim_step.c run_span), into off and size.
 * The few points outside it this covers are computed from stale inputs
 * and never read: what others read of them arrives by the exchange, and
 * a row two spans share is computed twice alike (every pass a span runs
 * writes out of place, but Verlet's drift: exchange_plan.c cuts spans at
 * msocl__planes_unit). */
static void own_part(const msocl__engine *s, size_t off[3], size_t size[3])
{
  for (int d = 0; d < 3; d++) {
    off[d] = 0;
    size[d] = s->pl_global[d];
  }
  const int span = s->run_offset != s->offset || s->run_global != s->global;
  const size_t lo = span ? s->run_offset : (size_t)s->lo,
               hi = span ? s->run_offset + s->run_global : (size_t)s->hi;
  if (lo == 0 && hi == (size_t)s->n)
    return;
  const int grid = s->lay.kind == MSOCL_LAYOUT_GRID,
            dim = !grid ? 0 : s->lay.grid_nz > 0 ? 2 : 1;
  const size_t per = (size_t)msocl__planes_unit(s), a = lo / per,
               b = (hi - 1) / per + 1;
  off[dim] = !grid ? a * per : a;
  size[dim] = !grid ? (b - a) * per : b - a;
}

int msocl__planes_unit(const msocl__engine *s)
{
  if (s->lay.kind != MSOCL_LAYOUT_GRID)
    return (int)s->pl_group;
  return s->lay.grid_nz > 0 ? s->lay.grid_nx * s->lay.grid_ny
                            : s->lay.grid_nx;
}

/* A pass over the padded grid; CPU devices in work-groups of a row's
 * pl_group points (launch.c's reason). */
int msocl__pl_launch(msocl__engine *s, int k)
{
  size_t local[3] = {s->pl_group, 1, 1};
  const size_t *group = s->dev->info.type == MSOCL_DEVICE_CPU ? local : NULL;
  size_t off[3], size[3];
  own_part(s, off, size);
  if (s->pl_wide & (1u << k)) {
    /* MSOCL__WIDE_W points a work-item, and rows enough for
     * MSOCL__WIDE_GROUP work-items a group where the rows divide evenly:
     * PoCL's cost a work-group outweighed a narrow row's 1-4 work-items */
    size[0] /= MSOCL__WIDE_W;
    local[0] = s->pl_group / MSOCL__WIDE_W;
    size_t rows = MSOCL__WIDE_GROUP / local[0];
    while (rows > 1 && size[1] % rows != 0)
      rows--;
    local[1] = rows;
  }
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->pl_k[k], 3, off, size,
                                   group, 0, NULL, NULL));
  if (s->pl_ks[k]) {
    const size_t spilled = (size_t)s->pl_nspill;
    MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->pl_ks[k], 1, NULL,
                                     &spilled, NULL, 0, NULL, NULL));
  }
  return MSOCL_OK;
}

/* Sets planes kernel k's ping-pong arguments names[q] to bufs[q] (q < n). */
static int buffers(msocl__engine *s, int k, int n, const char *const *names,
                   const cl_mem *bufs)
{
  for (int q = 0; q < n; q++)
    TRY(msocl__pl_mem(s, s->pl_k[k], names[q], bufs[q]));
  return MSOCL_OK;
}

/* RK4's stage q: the stage states alternate
 * between two sets so no kernel writes what its neighbours read; the last
 * stage writes set w. */
static int rk4_stage(msocl__engine *s, int q, int r, int w)
{
  static const float cs[4] = {0.5f, 0.5f, 1.0f, 0.0f};
  const int k = q == 0 ? PL_RK4 : q == 3 ? PL_RK4_LAST : PL_RK4_MID;
  const int in = (q - 1) & 1, out = q & 1;
  const cl_mem y0[4] = {s->pl_p[r], s->pl_v[r], q ? s->pl_sp[in] : s->pl_p[r],
                        q ? s->pl_sv[in] : s->pl_v[r]};
  const cl_mem next[2] = {q == 3 ? s->pl_p[w] : s->pl_sp[out],
                          q == 3 ? s->pl_v[w] : s->pl_sv[out]};
  static const char *const in_names[4] = {"p0", "v0", "sp", "sv"},
                           *const out_names[2] = {"np", "nv"};
  TRY(buffers(s, k, 4, in_names, y0));
  TRY(buffers(s, k, 2, out_names, next));
  TRY(msocl__pl_arg(s, s->pl_k[k], "c", sizeof cs[q], &cs[q]));
  return launch(s, k);
}

/* Provot's sweeps on new positions p, then the commit that moves them
 * and the velocities v together (as strain.c's). */
static int provot(msocl__engine *s, cl_mem p, cl_mem v)
{
  cl_mem from = p;
  cl_kernel k = s->pl_k[PL_STRAIN];
  for (int it = 0; it < s->o.strain_iterations; it++) {
    const cl_mem to = s->pl_s[it & 1];
    TRY(msocl__pl_mem(s, k, "p", from));
    TRY(msocl__pl_mem(s, k, "p_out", to));
    TRY(launch(s, PL_STRAIN));
    from = to;
  }
  k = s->pl_k[PL_COMMIT];
  TRY(msocl__pl_mem(s, k, "p", p));
  TRY(msocl__pl_mem(s, k, "corrected", from));
  TRY(msocl__pl_mem(s, k, "v", v));
  return launch(s, PL_COMMIT);
}

/* The velocity kind's sweeps on the new velocities v at the positions p,
 * ping-ponging with Provot's first scratch set; the result ends in v. */
static int strain_velocity(msocl__engine *s, cl_mem p, cl_mem v)
{
  cl_kernel k = s->pl_k[PL_STRAIN_V];
  cl_mem from = v;
  TRY(msocl__pl_mem(s, k, "p", p));
  for (int it = 0; it < s->o.strain_iterations; it++) {
    const cl_mem to = from == v ? s->pl_s[0] : v;
    TRY(msocl__pl_mem(s, k, "v", from));
    TRY(msocl__pl_mem(s, k, "v_out", to));
    TRY(launch(s, PL_STRAIN_V));
    from = to;
  }
  if (from != v)
    MSOCL__CL(clEnqueueCopyBuffer(s->dev->queue, from, v, 0, 0,
                                  3 * (size_t)s->pl_plane * sizeof(float), 0,
                                  NULL, NULL));
  return MSOCL_OK;
}

/* Pass p (schedule.h) from plane set r = pl_set into set w. */
int msocl__planes_pass(msocl__engine *s, enum msocl__pass pass)
{
  const int r = s->pl_set, w = 1 - r;
  const cl_mem *p = s->pl_p, *v = s->pl_v;
  static const char *const step_names[4] = {"p", "v", "v_out", "p_out"};
  /* symplectic Euler's two passes, or fused, in one sweep (planes_rows.c) */
  if (s->pl_rows && (pass == MSOCL__P_VELOCITY || pass == MSOCL__P_FUSED))
    return msocl__pl_rows_step(s, r, w);
  if (s->pl_rows && pass == MSOCL__P_POSITION)
    return MSOCL_OK;
  switch (pass) {
  case MSOCL__P_VELOCITY: {
    const cl_mem vel[3] = {p[r], v[r], v[w]};
    TRY(buffers(s, PL_VELOCITY, 3, step_names, vel));
    TRY(msocl__pl_pack(s, p[r]));
    return launch(s, PL_VELOCITY);
  }
  case MSOCL__P_STRAIN_VEL: return strain_velocity(s, p[r], v[w]);
  case MSOCL__P_POSITION: {
    const cl_mem pos[3] = {p[r], v[w], p[w]};
    static const char *const pos_names[3] = {"p", "v", "p_out"};
    TRY(buffers(s, PL_POSITION, 3, pos_names, pos));
    return launch(s, PL_POSITION);
  }
  case MSOCL__P_FUSED:
  case MSOCL__P_EULER: {
    const int k = pass == MSOCL__P_FUSED ? PL_FUSED : PL_EULER;
    const cl_mem both[4] = {p[r], v[r], v[w], p[w]};
    TRY(buffers(s, k, 4, step_names, both));
    TRY(msocl__pl_pack(s, p[r]));
    return launch(s, k);
  }
  case MSOCL__P_DRIFT: {
    const cl_mem drift[3] = {p[r], v[r], p[w]};
    static const char *const drift_names[3] = {"p", "v", "p_out"};
    TRY(buffers(s, PL_DRIFT, 3, drift_names, drift));
    return launch(s, PL_DRIFT);
  }
  case MSOCL__P_KICK: {
    const cl_mem kick[3] = {p[w], v[r], v[w]};
    TRY(buffers(s, PL_KICK, 3, step_names, kick));
    TRY(msocl__pl_pack(s, p[w]));
    return launch(s, PL_KICK);
  }
  case MSOCL__P_RK4_0:
  case MSOCL__P_RK4_1:
  case MSOCL__P_RK4_2:
  case MSOCL__P_RK4_3:
    return rk4_stage(s, (int)(pass - MSOCL__P_RK4_0), r, w);
  case MSOCL__P_PROVOT: return provot(s, p[w], v[w]);
  case MSOCL__P_PROVOT_HALF: return provot(s, p[w], v[r]);
  case MSOCL__P_CG: break;
  }
  return msocl__fail(MSOCL_ERR_INVALID_ARG, "no planes pass %d", (int)pass);
}

/* Verlet's first acceleration, from the current set's state: the kick
 * with dt 0, its velocities into the other set, which every step writes
 * before it reads. */
static int first_acceleration(msocl__engine *s)
{
  const float zero = 0.0f;
  const int r = s->pl_set;
  cl_kernel k = s->pl_k[PL_KICK];
  TRY(msocl__pl_mem(s, k, "p", s->pl_p[r]));
  TRY(msocl__pl_mem(s, k, "v", s->pl_v[r]));
  TRY(msocl__pl_mem(s, k, "v_out", s->pl_v[1 - r]));
  TRY(msocl__pl_arg(s, k, "dt", sizeof zero, &zero));
  TRY(msocl__pl_pack(s, s->pl_p[r]));
  TRY(launch(s, PL_KICK));
  return msocl__pl_arg(s, k, "dt", sizeof(float), &s->o.dt);
}

/* The state lives in the planes; what it implies (Verlet's acceleration)
 * is computed again at the first step after anything wrote it. */
int msocl__planes_enter(msocl__engine *s)
{
  if (s->pl_valid)
    return MSOCL_OK;
  if (s->o.integrator == MSOCL_VERLET)
    TRY(first_acceleration(s));
  s->pl_valid = 1;
  return MSOCL_OK;
}

void msocl__planes_step_done(msocl__engine *s)
{
  s->pl_set = 1 - s->pl_set;
}

void msocl__planes_written(msocl__engine *s)
{
  s->pl_valid = 0;
}

void msocl__planes_release(msocl__engine *s)
{
  for (int q = 0; q < PL_COUNT; q++) {
    msocl__kernel_free(s->dev, &s->pl_k[q]);
    msocl__kernel_free(s->dev, &s->pl_ks[q]);
  }
  cl_mem m[14] = {s->pl_p[0],  s->pl_p[1],  s->pl_v[0],   s->pl_v[1],
                  s->pl_aux,   s->pl_a,     s->pl_sp[0],  s->pl_sp[1],
                  s->pl_sv[0], s->pl_sv[1], s->pl_sum[0], s->pl_sum[1],
                  s->pl_s[0],  s->pl_s[1]};
  for (int q = 0; q < 14; q++)
    if (m[q])
      clReleaseMemObject(m[q]);
  if (s->pl_col)
    clReleaseMemObject(s->pl_col);
  for (int q = 0; q < 4; q++)
    if (s->pl_table[q])
      clReleaseMemObject(s->pl_table[q]);
  if (s->pl_list)
    clReleaseMemObject(s->pl_list);
  msocl__pl_rows_release(s);
  msocl__pl_pack_release(s);
}

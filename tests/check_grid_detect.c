/* A cloth grid or lattice built by hand from points and springs (as a user
 * porting from another library would): AUTO gives it GRID when its springs
 * are exactly the builder's stencil, with one value a kind, in the
 * builder's order, and its result is then bitwise the builder's; anything
 * short of that keeps BUFFER. */
#include "internal.h" /* the builders' arrays, to copy and mutate */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

/* A model's arrays, copied out to be changed and rebuilt by hand. */
struct arrays {
  int n, ns;
  float *pos, *mass, *k, *rest, *damp; /* damp NULL: no dashpots */
  int *ij;
};

static void copy_out(const msocl_model *m, struct arrays *a)
{
  a->n = m->n;
  a->ns = m->ns;
  a->pos = malloc(3 * (size_t)m->n * sizeof *a->pos);
  a->mass = malloc((size_t)m->n * sizeof *a->mass);
  a->ij = malloc(2 * (size_t)m->ns * sizeof *a->ij + 2 * sizeof *a->ij);
  a->k = malloc(((size_t)m->ns + 1) * sizeof *a->k);
  a->rest = malloc(((size_t)m->ns + 1) * sizeof *a->rest);
  a->damp = m->damp ? malloc(((size_t)m->ns + 1) * sizeof *a->damp) : NULL;
  memcpy(a->pos, m->pos, 3 * (size_t)m->n * sizeof *a->pos);
  memcpy(a->mass, m->mass, (size_t)m->n * sizeof *a->mass);
  memcpy(a->ij, m->ij, 2 * (size_t)m->ns * sizeof *a->ij);
  memcpy(a->k, m->k, (size_t)m->ns * sizeof *a->k);
  memcpy(a->rest, m->rest, (size_t)m->ns * sizeof *a->rest);
  if (a->damp)
    memcpy(a->damp, m->damp, (size_t)m->ns * sizeof *a->damp);
}

static void free_arrays(struct arrays *a)
{
  free(a->pos);
  free(a->mass);
  free(a->ij);
  free(a->k);
  free(a->rest);
  free(a->damp);
}

/* Pins, gravity, damping of the air and colliders, the same on every model
 * of a comparison. */
static void dress(msocl_model *m, int nx)
{
  msocl_model_pin(m, 0, 1);
  msocl_model_pin(m, nx - 1, 1);
  const float c[3] = {0.5f, -0.105f, 0.5f}; /* touched after ~160 steps */
  msocl_model_add_sphere(m, c, 0.3f, 0.1f);
  msocl_model_set_viscous_damping(m, 1e-4f);
}

static msocl_model *from_arrays(const struct arrays *a, int nx)
{
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_create(&m), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_points(m, a->n, a->pos, a->mass, NULL),
                   MSOCL_OK);
  ck_assert_msg(msocl_model_add_springs(m, a->ns, a->ij, a->k, a->rest,
                                        a->damp) == MSOCL_OK,
                "add_springs: %s", msocl_last_error());
  dress(m, nx);
  return m;
}

/* A cloth as a user writes it: the points row by row, then the builder's
 * three loops (stretch, shear, bend), every spring of a kind at the
 * kind's rest length. The positions are the builder's, so the two start
 * from the same state. */
static msocl_model *hand_cloth(const msocl_model *b, const msocl_cloth_desc *d)
{
  const int nx = d->nx, ny = d->ny, most = 6 * nx * ny;
  struct arrays a = {nx * ny, 0, NULL, NULL, NULL, NULL, NULL, NULL};
  a.pos = malloc(3 * (size_t)a.n * sizeof *a.pos);
  a.mass = malloc((size_t)a.n * sizeof *a.mass);
  a.ij = malloc(2 * (size_t)most * sizeof *a.ij);
  a.k = malloc((size_t)most * sizeof *a.k);
  a.rest = malloc((size_t)most * sizeof *a.rest);
  a.damp = d->damping > 0 ? malloc((size_t)most * sizeof *a.damp) : NULL;
  ck_assert_int_eq(msocl_model_get_positions(b, a.pos), MSOCL_OK);
  for (int p = 0; p < a.n; p++)
    a.mass[p] = d->point_mass;
  const float *r = b->grid.rest; /* the builder's spacing for each kind */
#define ADD(p, q, kk, rr)                                                     \
  do {                                                                        \
    a.ij[2 * a.ns] = (p);                                                     \
    a.ij[2 * a.ns + 1] = (q);                                                 \
    a.k[a.ns] = (kk);                                                         \
    a.rest[a.ns] = (rr);                                                      \
    if (a.damp)                                                               \
      a.damp[a.ns] = d->damping;                                              \
    a.ns++;                                                                   \
  } while (0)
  for (int j = 0; d->k_stretch > 0 && j < ny; j++)
    for (int i = 0; i < nx; i++) {
      if (i + 1 < nx)
        ADD(j * nx + i, j * nx + i + 1, d->k_stretch, r[0]);
      if (j + 1 < ny)
        ADD((j + 1) * nx + i, j * nx + i, d->k_stretch, r[1]); /* either way */
    }
  for (int j = 0; d->k_shear > 0 && j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      ADD(j * nx + i, (j + 1) * nx + i + 1, d->k_shear, r[2]);
      ADD(j * nx + i + 1, (j + 1) * nx + i, d->k_shear, r[3]);
    }
  for (int j = 0; d->k_bend > 0 && j < ny; j++)
    for (int i = 0; i < nx; i++) {
      if (i + 2 < nx)
        ADD(j * nx + i, j * nx + i + 2, d->k_bend, r[4]);
      if (j + 2 < ny)
        ADD(j * nx + i, (j + 2) * nx + i, d->k_bend, r[5]);
    }
#undef ADD
  msocl_model *m = from_arrays(&a, nx);
  free_arrays(&a);
  return m;
}

/* Final positions and velocities after `steps` steps on `layout` (AUTO:
 * *got receives what it chose). */
static void run(const msocl_model *m, msocl_layout layout, int steps,
                float **pos, float **vel, msocl_layout *got)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 2e-4f;
  o.tuning.layout = layout;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK,
                "sim_create: %s", msocl_last_error());
  ck_assert_int_eq(msocl_sim_layout(s, got), MSOCL_OK);
  int n;
  msocl_sim_point_count(s, &n);
  ck_assert_int_eq(msocl_sim_step(s, steps), MSOCL_OK);
  *pos = malloc(3 * (size_t)n * sizeof(float));
  *vel = malloc(3 * (size_t)n * sizeof(float));
  ck_assert_int_eq(msocl_sim_read_positions(s, *pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, *vel), MSOCL_OK);
  msocl_sim_destroy(s);
}

/* a's AUTO run chose `want`, and ends bitwise where b's run on `lb` ends
 * (which must have moved). */
static void same_end(const msocl_model *a, msocl_layout want,
                     const msocl_model *b, msocl_layout lb, int steps,
                     const char *what)
{
  float *p[2], *v[2];
  msocl_layout got[2];
  run(a, MSOCL_LAYOUT_AUTO, steps, &p[0], &v[0], &got[0]);
  run(b, lb, steps, &p[1], &v[1], &got[1]);
  ck_assert_msg(got[0] == want, "%s: AUTO chose layout %d, not %d", what,
                (int)got[0], (int)want);
  const int n = a->n;
  const size_t bytes = 3 * (size_t)n * sizeof(float);
  ck_assert_double_gt(scene_max_diff(a->pos, p[0], 3 * n), 1e-4);
  ck_assert_msg(memcmp(p[0], p[1], bytes) == 0 && memcmp(v[0], v[1], bytes) == 0,
                "%s: positions differ by %g, velocities by %g", what,
                scene_max_diff(p[0], p[1], 3 * n),
                scene_max_diff(v[0], v[1], 3 * n));
  for (int q = 0; q < 2; q++) {
    free(p[q]);
    free(v[q]);
  }
}

static void cloth_desc(msocl_cloth_desc *d, int nx, int ny)
{
  msocl_cloth_desc_init(d);
  d->nx = nx;
  d->ny = ny;
  d->origin[1] = 0.2f;
}

/* Hand-built cloths of several shapes (2 x 2 up; a chain is no cloth) and
 * kinds: AUTO gives GRID, and the
 * state after the steps is bitwise that of the builder's cloth (GRID from
 * AUTO too); BUFFER forced on the hand-built one agrees bitwise. */
START_TEST(hand_cloth_gets_grid)
{
  static const struct {
    int nx, ny;
    float stretch, shear, bend, damping, skew;
  } c[] = {
      {20, 14, 1000, 100, 10, 1e-3f, 0.3f}, /* a parallelogram: unequal
                                               diagonals */
      {16, 16, 1000, 100, 10, 0, 0},     {33, 29, 1000, 100, 10, 1e-3f, 0},
      {2, 2, 1000, 100, 10, 0, 0},       {2, 7, 1000, 100, 10, 0, 0},
      {3, 40, 1000, 100, 10, 2e-3f, 0},  {12, 9, 1000, 0, 0, 0, 0},
      {12, 9, 1000, 0, 10, 1e-3f, 0},    {10, 11, 0, 300, 10, 0, 0},
  };
  for (size_t q = 0; q < sizeof c / sizeof c[0]; q++) {
    msocl_cloth_desc d;
    cloth_desc(&d, c[q].nx, c[q].ny);
    d.k_stretch = c[q].stretch;
    d.k_shear = c[q].shear;
    d.k_bend = c[q].bend;
    d.damping = c[q].damping;
    d.v[0] = c[q].skew;
    msocl_model *b = NULL;
    ck_assert_int_eq(msocl_model_cloth_grid(&b, &d), MSOCL_OK);
    msocl_model *h = hand_cloth(b, &d);
    dress(b, d.nx);
    char what[64];
    snprintf(what, sizeof what, "%d x %d cloth %zu", d.nx, d.ny, q);
    same_end(h, MSOCL_LAYOUT_GRID, b, MSOCL_LAYOUT_AUTO, 300, what);
    same_end(h, MSOCL_LAYOUT_GRID, h, MSOCL_LAYOUT_BUFFER, 300, what);
    msocl_model_destroy(h);
    msocl_model_destroy(b);
  }
}
END_TEST

/* GRID forced on a hand-built cloth is accepted (it was refused); on one
 * short of a spring still refused. */
START_TEST(hand_cloth_forced_grid)
{
  msocl_cloth_desc d;
  cloth_desc(&d, 9, 6);
  msocl_model *b = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&b, &d), MSOCL_OK);
  msocl_model *h = hand_cloth(b, &d);
  dress(b, d.nx);
  float *p[2], *v[2];
  msocl_layout got[2];
  run(h, MSOCL_LAYOUT_GRID, 200, &p[0], &v[0], &got[0]);
  run(b, MSOCL_LAYOUT_GRID, 200, &p[1], &v[1], &got[1]);
  ck_assert_int_eq(got[0], MSOCL_LAYOUT_GRID);
  ck_assert(memcmp(p[0], p[1], 3 * 54 * sizeof(float)) == 0);
  ck_assert(memcmp(v[0], v[1], 3 * 54 * sizeof(float)) == 0);
  for (int q = 0; q < 2; q++) {
    free(p[q]);
    free(v[q]);
  }
  struct arrays a;
  copy_out(h, &a);
  a.ns--;
  msocl_model *short1 = from_arrays(&a, d.nx);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, short1, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "by hand"));
  free_arrays(&a);
  msocl_model_destroy(short1);
  msocl_model_destroy(h);
  msocl_model_destroy(b);
}
END_TEST

/* Split over two devices, a hand-built cloth still runs GRID, bitwise one
 * device's run. */
START_TEST(hand_cloth_split)
{
  msocl_runtime *two = NULL;
  if (msocl_runtime_create(&two, "0:0,0:1") != MSOCL_OK)
    return; /* one device: nothing to split over */
  msocl_cloth_desc d;
  cloth_desc(&d, 14, 12);
  d.damping = 1e-3f;
  msocl_model *b = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&b, &d), MSOCL_OK);
  msocl_model *h = hand_cloth(b, &d);
  const size_t bytes = 3 * 14 * 12 * sizeof(float);
  float *p[2];
  for (int q = 0; q < 2; q++) {
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.dt = 2e-4f;
    o.tuning.ndevices = q ? 2 : 1;
    msocl_sim *s = NULL;
    ck_assert_int_eq(msocl_sim_create(&s, q ? two : rt, h, &o), MSOCL_OK);
    msocl_layout l;
    ck_assert_int_eq(msocl_sim_layout(s, &l), MSOCL_OK);
    ck_assert_int_eq(l, MSOCL_LAYOUT_GRID);
    ck_assert_int_eq(msocl_sim_step(s, 300), MSOCL_OK);
    p[q] = malloc(bytes);
    ck_assert_int_eq(msocl_sim_read_positions(s, p[q]), MSOCL_OK);
    msocl_sim_destroy(s);
  }
  ck_assert_msg(memcmp(p[0], p[1], bytes) == 0, "split differs by %g",
                scene_max_diff(p[0], p[1], 3 * 14 * 12));
  free(p[0]);
  free(p[1]);
  msocl_runtime_destroy(two);
  msocl_model_destroy(h);
  msocl_model_destroy(b);
}
END_TEST

/* Lattices (3-D, msocl_model_lattice's stencil) built by hand from the
 * builder's arrays: GRID, bitwise the builder's;
 * with one spring's k changed, BUFFER. */
START_TEST(hand_lattice_gets_grid)
{
  for (int q = 0; q < 3; q++) {
    msocl_lattice_desc d;
    msocl_lattice_desc_init(&d);
    d.nx = q == 2 ? 2 : 5;
    d.ny = 4;
    d.nz = q == 2 ? 3 : 6;
    d.origin[1] = 0.02f;
    if (q == 1) {
      d.k_shear_body = 40.0f;
      d.damping = 0.0f;
    }
    msocl_model *b = NULL;
    ck_assert_int_eq(msocl_model_lattice(&b, &d), MSOCL_OK);
    struct arrays a;
    copy_out(b, &a);
    msocl_model *h = from_arrays(&a, d.nx);
    dress(b, d.nx);
    char what[64];
    snprintf(what, sizeof what, "%d x %d x %d lattice", d.nx, d.ny, d.nz);
    same_end(h, MSOCL_LAYOUT_GRID, b, MSOCL_LAYOUT_AUTO, 300, what);
    same_end(h, MSOCL_LAYOUT_GRID, h, MSOCL_LAYOUT_BUFFER, 300, what);
    msocl_model_destroy(h);
    /* one face shear spring's k 1 ulp up: BUFFER */
    for (int s = 0; s < a.ns; s++)
      if (a.k[s] == d.k_shear_face) {
        a.k[s] = nextafterf(a.k[s], INFINITY);
        break;
      }
    h = from_arrays(&a, d.nx);
    same_end(h, MSOCL_LAYOUT_BUFFER, h, MSOCL_LAYOUT_BUFFER, 100, what);
    free_arrays(&a);
    msocl_model_destroy(h);
    msocl_model_destroy(b);
  }
}
END_TEST

/* Near misses of a 10 x 8 cloth: each keeps BUFFER under AUTO (its run is
 * then bitwise BUFFER's forced). */
enum {
  MISSING, STIFFER, LONGER, DAMPER, EXTRA, DOUBLED, FAR, REORDERED,
  SHUFFLED, COLUMNS, ZERO_K, MISSES
};
static const char *const miss_names[MISSES] = {
    "a spring missing", "one spring's k 1 ulp up", "one rest 1 ulp up",
    "one dashpot differs", "an extra spring (i+1, j+2)", "a spring doubled",
    "a spring out of the stencil", "springs in another order",
    "points shuffled", "points column by column", "a kind with k 0"};

static void miss(struct arrays *a, int kind, int nx, int ny)
{
  const int mid = a->ns / 2;
  switch (kind) {
  case MISSING:
    memmove(a->ij + 2 * mid, a->ij + 2 * mid + 2,
            2 * (size_t)(a->ns - mid - 1) * sizeof *a->ij);
    memmove(a->k + mid, a->k + mid + 1, (size_t)(a->ns - mid - 1) * 4);
    memmove(a->rest + mid, a->rest + mid + 1, (size_t)(a->ns - mid - 1) * 4);
    memmove(a->damp + mid, a->damp + mid + 1, (size_t)(a->ns - mid - 1) * 4);
    a->ns--;
    break;
  case STIFFER:
    a->k[mid] = nextafterf(a->k[mid], INFINITY);
    break;
  case LONGER:
    a->rest[mid] = nextafterf(a->rest[mid], INFINITY);
    break;
  case DAMPER:
    a->damp[mid] *= 2.0f;
    break;
  case EXTRA:
  case DOUBLED:
  case FAR: {
    const int s = a->ns++;
    a->ij[2 * s] = kind == DOUBLED ? a->ij[2 * mid] : 0;
    a->ij[2 * s + 1] = kind == DOUBLED ? a->ij[2 * mid + 1]
                       : kind == EXTRA ? 2 * nx + 1 : 3 * nx;
    a->k[s] = a->k[kind == DOUBLED ? mid : 0];
    a->rest[s] = a->rest[kind == DOUBLED ? mid : 0];
    a->damp[s] = a->damp[0];
    break;
  }
  case REORDERED: /* point by point: each point's springs to its right and up */
  case SHUFFLED:
  case COLUMNS: {
    int *num = malloc((size_t)a->n * sizeof *num);
    for (int p = 0; p < a->n; p++)
      num[p] = kind == COLUMNS ? (p % nx) * ny + p / nx
               : kind == SHUFFLED ? (int)(((long long)p * 37 + 11) % a->n)
                                  : p;
    if (kind == REORDERED) {
      /* sort springs by lower end: the order a point-by-point loop gives */
      for (int i = 1; i < a->ns; i++)
        for (int j = i; j > 0; j--) {
          int lo0 = a->ij[2 * j - 2] < a->ij[2 * j - 1] ? a->ij[2 * j - 2]
                                                          : a->ij[2 * j - 1];
          int lo1 = a->ij[2 * j] < a->ij[2 * j + 1] ? a->ij[2 * j]
                                                    : a->ij[2 * j + 1];
          if (lo0 <= lo1)
            break;
          int t0 = a->ij[2 * j - 2], t1 = a->ij[2 * j - 1];
          float k = a->k[j - 1], r = a->rest[j - 1], c = a->damp[j - 1];
          a->ij[2 * j - 2] = a->ij[2 * j];
          a->ij[2 * j - 1] = a->ij[2 * j + 1];
          a->k[j - 1] = a->k[j];
          a->rest[j - 1] = a->rest[j];
          a->damp[j - 1] = a->damp[j];
          a->ij[2 * j] = t0;
          a->ij[2 * j + 1] = t1;
          a->k[j] = k;
          a->rest[j] = r;
          a->damp[j] = c;
        }
    } else {
      float *pos = malloc(3 * (size_t)a->n * sizeof *pos);
      float *mass = malloc((size_t)a->n * sizeof *mass);
      for (int p = 0; p < a->n; p++) {
        memcpy(pos + 3 * num[p], a->pos + 3 * p, 3 * sizeof *pos);
        mass[num[p]] = a->mass[p];
      }
      memcpy(a->pos, pos, 3 * (size_t)a->n * sizeof *pos);
      memcpy(a->mass, mass, (size_t)a->n * sizeof *mass);
      for (int e = 0; e < 2 * a->ns; e++)
        a->ij[e] = num[a->ij[e]];
      free(pos);
      free(mass);
    }
    free(num);
    break;
  }
  case ZERO_K: /* the bend springs present, with k 0 (and dashpots) */
    for (int s = 0; s < a->ns; s++)
      if (a->k[s] == 10.0f)
        a->k[s] = 0.0f;
    break;
  }
}

START_TEST(near_misses_keep_buffer)
{
  const int nx = 10, ny = 8;
  msocl_cloth_desc d;
  cloth_desc(&d, nx, ny);
  d.damping = 1e-3f;
  msocl_model *b = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&b, &d), MSOCL_OK);
  for (int kind = 0; kind < MISSES; kind++) {
    struct arrays a;
    copy_out(b, &a);
    miss(&a, kind, nx, ny);
    msocl_model *h = from_arrays(&a, nx);
    same_end(h, MSOCL_LAYOUT_BUFFER, h, MSOCL_LAYOUT_BUFFER, 200,
             miss_names[kind]);
    free_arrays(&a);
    msocl_model_destroy(h);
  }
  msocl_model_destroy(b);
}
END_TEST

/* What GRID does not read, a hand-built grid may choose freely: a point
 * off the lattice (positions are state) still gets GRID, bitwise BUFFER's. */
START_TEST(point_off_the_lattice)
{
  msocl_cloth_desc d;
  cloth_desc(&d, 10, 8);
  msocl_model *b = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&b, &d), MSOCL_OK);
  struct arrays a;
  copy_out(b, &a);
  a.pos[3 * 45 + 1] += 0.03f;
  a.pos[3 * 45 + 0] -= 0.01f;
  msocl_model *h = from_arrays(&a, d.nx);
  same_end(h, MSOCL_LAYOUT_GRID, h, MSOCL_LAYOUT_BUFFER, 300, "moved point");
  free_arrays(&a);
  msocl_model_destroy(h);
  msocl_model_destroy(b);
}
END_TEST

/* A chain (1 x N) and a model with no springs are no grid GRID runs. */
START_TEST(chains_keep_buffer)
{
  enum { N = 12 };
  float xyz[3 * N] = {0}, mass[N], k[N], rest[N];
  int ij[2 * N];
  for (int i = 0; i < N; i++) {
    xyz[3 * i] = 0.1f * (float)i;
    mass[i] = 0.01f;
    k[i] = 100.0f;
    rest[i] = 0.1f;
    ij[2 * i] = i;
    ij[2 * i + 1] = i + 1;
  }
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_create(&m), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_points(m, N, xyz, mass, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_springs(m, N - 1, ij, k, rest, NULL),
                   MSOCL_OK);
  msocl_model_pin(m, 0, 1);
  same_end(m, MSOCL_LAYOUT_BUFFER, m, MSOCL_LAYOUT_BUFFER, 200, "chain");
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_grid_detect");
  Suite *su = suite_create("grid_detect");
  TCase *tc = tcase_create("hand-built grids");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, hand_cloth_gets_grid);
  tcase_add_test(tc, hand_cloth_forced_grid);
  tcase_add_test(tc, hand_cloth_split);
  tcase_add_test(tc, hand_lattice_gets_grid);
  tcase_add_test(tc, near_misses_keep_buffer);
  tcase_add_test(tc, point_off_the_lattice);
  tcase_add_test(tc, chains_keep_buffer);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

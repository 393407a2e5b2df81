/* Point numbering: reverse Cuthill-McKee on shuffled cloths, chains, a
 * hand-worked tree and split models; the renumbered model carries every
 * field and keeps each point's springs in their order. No OpenCL. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#include "expect.h"

/* ---------------------------------------------------------------- helpers */

/* A fixed shuffle of 0 .. n-1 (Fisher-Yates on a 64-bit LCG), the same on
 * every run and platform. */
static int *shuffled(int n, unsigned long long seed) {
  int *p = malloc(((size_t)n + 1) * sizeof *p);
  ck_assert_ptr_nonnull(p);
  for (int i = 0; i < n; i++) p[i] = i;
  for (int i = n - 1; i > 0; i--) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    int j = (int)((seed >> 33) % (unsigned long long)(i + 1)), t = p[i];
    p[i] = p[j];
    p[j] = t;
  }
  return p;
}

/* perm is a permutation of 0 .. n-1. */
static void check_bijection(const int *perm, int n) {
  unsigned char *seen = calloc((size_t)n + 1, 1);
  ck_assert_ptr_nonnull(seen);
  for (int k = 0; k < n; k++) {
    ck_assert_msg(perm[k] >= 0 && perm[k] < n, "perm[%d] = %d out of range", k,
                  perm[k]);
    ck_assert_msg(!seen[perm[k]], "perm[%d] = %d repeats", k, perm[k]);
    seen[perm[k]] = 1;
  }
  free(seen);
}

static int bandwidth(const msocl_model *m) {
  int bw = 0;
  for (int s = 0; s < m->ns; s++) {
    int d = abs(m->ij[2 * s] - m->ij[2 * s + 1]);
    if (d > bw) bw = d;
  }
  return bw;
}

static msocl_model *cloth(int nx, int ny, float damping) {
  msocl_cloth_desc d;
  msocl_model *m;
  msocl_cloth_desc_init(&d);
  d.nx = nx;
  d.ny = ny;
  d.damping = damping;
  OK(msocl_model_cloth_grid(&m, &d));
  return m;
}

/* m's points in the fixed shuffle of `seed`. */
static msocl_model *shuffle(const msocl_model *m, unsigned long long seed) {
  int *perm = shuffled(m->n, seed);
  msocl_model *p;
  OK(msocl__model_permuted(m, perm, &p));
  free(perm);
  return p;
}

/* n points on the x axis, mass 1. */
static msocl_model *points(int n) {
  msocl_model *m;
  float *xyz = calloc((size_t)n * 3, sizeof *xyz);
  float *mass = malloc(n * sizeof *mass);
  ck_assert(xyz && mass);
  for (int i = 0; i < n; i++) {
    xyz[3 * i] = (float)i;
    mass[i] = 1;
  }
  OK(msocl_model_create(&m));
  OK(msocl_model_add_points(m, n, xyz, mass, NULL));
  free(xyz);
  free(mass);
  return m;
}

/* Springs between the pairs ij[0..2n), stiffness 1, rest from positions. */
static void springs(msocl_model *m, int n, const int *ij) {
  float *k = malloc(n * sizeof *k);
  ck_assert_ptr_nonnull(k);
  for (int s = 0; s < n; s++) k[s] = 1;
  OK(msocl_model_add_springs(m, n, ij, k, NULL, NULL));
  free(k);
}

/* RCM's perm of m, checked a bijection; bandwidths out. */
static int *rcm(const msocl_model *m, int *bw_old, int *bw_new) {
  int *perm = malloc(((size_t)m->n + 1) * sizeof *perm);
  ck_assert_ptr_nonnull(perm);
  *bw_old = *bw_new = -1;
  OK(msocl__order_rcm(m, perm, bw_old, bw_new));
  check_bijection(perm, m->n);
  return perm;
}

/* RCM's bw_new is the bandwidth of the model it describes. */
static void check_bw_new(const msocl_model *m, const int *perm, int bw_new) {
  msocl_model *r;
  OK(msocl__model_permuted(m, perm, &r));
  ck_assert_int_eq(bandwidth(r), bw_new);
  msocl_model_destroy(r);
}

/* ------------------------------------------------------------------ cloth */

/* A shuffled 40 x 30 cloth: the bandwidth about n before, two rows' worth
 * after, as the row-major numbering has it (bend springs reach two rows:
 * 2 nx). RCM starts at a corner and may number across either side; this
 * cloth comes out at 2 ny + 2 = 62, the bound allows 2 nx + 2. */
START_TEST(cloth_shuffled) {
  const int nx = 40, ny = 30;
  msocl_model *m = cloth(nx, ny, 0), *s = shuffle(m, 12345);
  int bw_old, bw_new, *perm = rcm(s, &bw_old, &bw_new);

  printf("cloth %dx%d (%d points, %d springs): row-major bandwidth %d, "
         "shuffled %d, RCM %d\n",
         nx, ny, m->n, m->ns, bandwidth(m), bw_old, bw_new);
  ck_assert_int_eq(bandwidth(m), 2 * nx);
  ck_assert_int_eq(bw_old, bandwidth(s));
  ck_assert_msg(bw_old > 9 * m->n / 10, "shuffled bandwidth %d", bw_old);
  ck_assert_msg(bw_new <= 2 * nx + 2, "RCM bandwidth %d > %d", bw_new,
                2 * nx + 2);
  check_bw_new(s, perm, bw_new);
  free(perm);

  /* Stretch springs only: the fronts are anti-diagonals, at most
   * min(nx, ny) = 30 points, and RCM keeps within one front. */
  msocl_model *g;
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = nx;
  d.ny = ny;
  d.k_shear = d.k_bend = 0;
  OK(msocl_model_cloth_grid(&g, &d));
  msocl_model *gs = shuffle(g, 777);
  perm = rcm(gs, &bw_old, &bw_new);
  printf("stretch-only cloth %dx%d: row-major bandwidth %d, shuffled %d, "
         "RCM %d\n",
         nx, ny, bandwidth(g), bw_old, bw_new);
  ck_assert_int_eq(bandwidth(g), nx);
  ck_assert_msg(bw_new <= ny + 1, "RCM bandwidth %d > %d", bw_new, ny + 1);
  check_bw_new(gs, perm, bw_new);
  free(perm);
  msocl_model_destroy(gs);
  msocl_model_destroy(g);
  msocl_model_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Big enough that a quadratic step would not finish in Check's 4 s. */
START_TEST(cloth_large) {
  const int nx = 400, ny = 300;
  msocl_model *m = cloth(nx, ny, 0), *s = shuffle(m, 99);
  int bw_old, bw_new, *perm = rcm(s, &bw_old, &bw_new);

  printf("cloth %dx%d (%d points, %d springs): shuffled bandwidth %d, "
         "RCM %d\n",
         nx, ny, m->n, m->ns, bw_old, bw_new);
  ck_assert_msg(bw_new <= 2 * nx + 2, "RCM bandwidth %d", bw_new);
  free(perm);
  msocl_model_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* -------------------------------------------------------- the new model */

/* Everything follows the points: positions, masses, pins; spring ends and
 * triangle corners renumbered, coefficients in place; the rest copied. */
START_TEST(permuted_carries) {
  msocl_model *m = cloth(6, 5, 0.25f), *p;
  const float n[3] = {0, 1, 0}, c[3] = {0.5f, -1, 0.25f};
  int *perm = shuffled(m->n, 4242), *inv = malloc(m->n * sizeof *inv);

  ck_assert_ptr_nonnull(inv);
  OK(msocl_model_pin(m, 0, 1));
  OK(msocl_model_pin(m, 5, 1));
  OK(msocl_model_pin(m, 17, 1));
  OK(msocl_model_set_gravity(m, 0.5f, -3, 1));
  OK(msocl_model_set_viscous_damping(m, 0.125f));
  OK(msocl_model_set_air_resistance(m, 0.99f));
  OK(msocl_model_add_plane(m, n, -2, 0.5f));
  OK(msocl_model_add_sphere(m, c, 0.3f, 0.1f));
  ck_assert_ptr_nonnull(m->damp);
  ck_assert_int_eq(m->grid.nx, 6);

  OK(msocl__model_permuted(m, perm, &p));
  for (int k = 0; k < m->n; k++) inv[perm[k]] = k;
  ck_assert_int_eq(p->n, m->n);
  ck_assert_int_eq(p->ns, m->ns);
  ck_assert_int_eq(p->nt, m->nt);
  ck_assert_int_eq(p->cap, m->cap);
  ck_assert_int_eq(p->scap, m->scap);
  ck_assert_int_eq(p->tcap, m->tcap);
  for (int k = 0; k < m->n; k++) {
    ck_assert(memcmp(p->pos + 3 * k, m->pos + 3 * perm[k],
                     3 * sizeof *p->pos) == 0);
    ck_assert(p->mass[k] == m->mass[perm[k]]);
    ck_assert_int_eq(p->pinned[k], m->pinned[perm[k]]);
  }
  ck_assert_int_eq(p->pinned[inv[0]] + p->pinned[inv[5]] + p->pinned[inv[17]],
                   3);
  for (int s = 0; s < m->ns; s++) {
    int a = p->ij[2 * s], b = p->ij[2 * s + 1];
    ck_assert_int_eq(perm[a], m->ij[2 * s]);
    ck_assert_int_eq(perm[b], m->ij[2 * s + 1]);
    ck_assert(p->k[s] == m->k[s] && p->rest[s] == m->rest[s] &&
              p->damp[s] == m->damp[s]);
    /* The same ends, so the same length to the bit. */
    for (int q = 0; q < 3; q++) {
      const float *ma = m->pos + 3 * m->ij[2 * s],
                  *mb = m->pos + 3 * m->ij[2 * s + 1];
      ck_assert(p->pos[3 * a + q] - p->pos[3 * b + q] == ma[q] - mb[q]);
    }
  }
  for (int t = 0; t < 3 * m->nt; t++)
    ck_assert_int_eq(perm[p->tri[t]], m->tri[t]);
  ck_assert(memcmp(p->gravity, m->gravity, sizeof m->gravity) == 0);
  ck_assert(p->viscous == m->viscous && p->air == m->air);
  ck_assert_int_eq(p->ncol, 2);
  ck_assert(memcmp(p->col, m->col, sizeof m->col) == 0);
  ck_assert_int_eq(p->grid.nx, 0);
  ck_assert_int_eq(p->grid.ny, 0);
  ck_assert_int_eq(p->grid.ns, 0);
  OK(msocl_model_validate(p));
  /* The copy owns its arrays: it grows, and m is untouched by that. */
  {
    const float xyz[3] = {9, 9, 9}, mass = 1;
    const int ij[2] = {0, 30};
    const float k = 2;
    int first = -1;
    OK(msocl_model_add_points(p, 1, xyz, &mass, &first));
    ck_assert_int_eq(first, 30);
    OK(msocl_model_add_springs(p, 1, ij, &k, NULL, NULL));
    ck_assert_int_eq(m->n, 30);
    OK(msocl_model_validate(p));
  }
  msocl_model_destroy(p);

  /* The identity keeps the grid record, and everything else as it was. */
  for (int k = 0; k < m->n; k++) perm[k] = k;
  OK(msocl__model_permuted(m, perm, &p));
  ck_assert(memcmp(&p->grid, &m->grid, sizeof m->grid) == 0);
  ck_assert(memcmp(p->pos, m->pos, 3 * m->n * sizeof *m->pos) == 0);
  ck_assert(memcmp(p->ij, m->ij, 2 * m->ns * sizeof *m->ij) == 0);
  ck_assert(memcmp(p->tri, m->tri, 3 * m->nt * sizeof *m->tri) == 0);
  msocl_model_destroy(p);
  free(perm);
  free(inv);
  msocl_model_destroy(m);

  /* No dashpots in: none out. */
  m = cloth(4, 4, 0);
  ck_assert_ptr_null(m->damp);
  p = shuffle(m, 5);
  ck_assert_ptr_null(p->damp);
  msocl_model_destroy(p);
  msocl_model_destroy(m);
}
END_TEST

/* Every new point k sees old point perm[k]'s springs, in the same slots:
 * the sums that make its force run in the same order. */
START_TEST(permuted_slots) {
  msocl_model *m = cloth(7, 6, 0), *p;
  int *perm = shuffled(m->n, 31337);
  struct msocl__adjacency a, b;

  OK(msocl__model_permuted(m, perm, &p));
  OK(msocl__adjacency_build(m, &a));
  OK(msocl__adjacency_build(p, &b));
  ck_assert_int_eq(a.max_degree, b.max_degree);
  for (int k = 0; k < m->n; k++) {
    int o = perm[k], d = b.off[k + 1] - b.off[k];
    ck_assert_int_eq(d, a.off[o + 1] - a.off[o]);
    for (int s = 0; s < d; s++) {
      ck_assert_int_eq(b.spring[b.off[k] + s], a.spring[a.off[o] + s]);
      ck_assert_int_eq(perm[b.other[b.off[k] + s]], a.other[a.off[o] + s]);
    }
  }
  msocl__adjacency_free(&a);
  msocl__adjacency_free(&b);
  free(perm);
  msocl_model_destroy(p);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(permuted_rejected) {
  msocl_model *m = points(4), *p = (msocl_model *)&p;
  int dup[4] = {0, 1, 1, 3}, low[4] = {0, -1, 2, 3}, high[4] = {0, 1, 2, 4},
      good[4] = {3, 2, 1, 0};

  EXPECT(msocl__model_permuted(m, dup, &p), MSOCL_ERR_BAD_VALUE);
  SAYS("perm[2] = 1 repeats perm[1]");
  ck_assert_ptr_null(p);
  EXPECT(msocl__model_permuted(m, low, &p), MSOCL_ERR_BAD_VALUE);
  SAYS("perm[1] = -1");
  EXPECT(msocl__model_permuted(m, high, &p), MSOCL_ERR_BAD_VALUE);
  SAYS("perm[3] = 4");
  ck_assert_ptr_null(p);
  EXPECT(msocl__model_permuted(NULL, good, &p), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl__model_permuted(m, NULL, &p), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl__model_permuted(m, good, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl__order_rcm(NULL, good, NULL, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl__order_rcm(m, NULL, NULL, NULL), MSOCL_ERR_NULL_HANDLE);
  OK(msocl__model_permuted(m, good, &p));
  ck_assert(p->pos[0] == 3 && p->pos[9] == 0);
  msocl_model_destroy(p);
  msocl_model_destroy(m);
}
END_TEST

/* ---------------------------------------------------------------- graphs */

/* A tree worked by hand:
 *
 *   4 - 1 - 0 - 3 - 6      degrees: 0:3 1:3 2:1 3:2 4:1 5:1 6:1
 *       |   |
 *       5   2
 *
 * From 0 (the lowest point) the levels are {0} {1 2 3} {4 5 6}; the last
 * level's lowest degree, lowest number is 4, 4 levels deep from there, so
 * on from 6, the last level from 4; from 6 it is no deeper: 6 is the start.
 * Cuthill-McKee from 6: 6 3 0, then 0's new neighbours by degree: 2 (1)
 * before 1 (3), then 1's: 4 5. Reversed: 5 4 1 2 0 3 6. */
START_TEST(tree_by_hand) {
  msocl_model *m = points(7);
  const int ij[] = {0, 1, 0, 2, 0, 3, 1, 4, 1, 5, 3, 6};
  const int want[7] = {5, 4, 1, 2, 0, 3, 6};
  int bw_old, bw_new, *perm;

  springs(m, 6, ij);
  perm = rcm(m, &bw_old, &bw_new);
  for (int k = 0; k < 7; k++)
    ck_assert_msg(perm[k] == want[k], "perm[%d] = %d, want %d", k, perm[k],
                  want[k]);
  ck_assert_int_eq(bw_old, 4);
  ck_assert_int_eq(bw_new, 2);
  free(perm);
  msocl_model_destroy(m);
}
END_TEST

/* A shuffled path comes out a path again (bandwidth 1): that takes a start
 * at an end, which a start at the lowest point (inside) would miss. A
 * shuffled ring comes out with bandwidth 2. */
START_TEST(chain_and_ring) {
  const int n = 50;
  int *ij = malloc(2 * n * sizeof *ij), *sh = shuffled(n, 2024);
  msocl_model *m;
  int bw_old, bw_new, *perm;

  ck_assert_ptr_nonnull(ij);
  for (int ring = 0; ring < 2; ring++) {
    int ns = ring ? n : n - 1;
    for (int s = 0; s < ns; s++) {
      ij[2 * s] = sh[s];
      ij[2 * s + 1] = sh[(s + 1) % n];
    }
    m = points(n);
    springs(m, ns, ij);
    perm = rcm(m, &bw_old, &bw_new);
    printf("shuffled %s of %d: bandwidth %d, RCM %d\n",
           ring ? "ring" : "path", n, bw_old, bw_new);
    ck_assert_int_eq(bw_new, ring ? 2 : 1);
    ck_assert_int_eq(bw_old, bandwidth(m));
    ck_assert(bw_old > n / 2);
    check_bw_new(m, perm, bw_new);
    free(perm);
    msocl_model_destroy(m);
  }
  free(ij);
  free(sh);
}
END_TEST

/* A chain already banded (i to i+1 and i+2): RCM does no worse. */
START_TEST(banded_chain) {
  const int n = 30;
  int ij[4 * 30], ns = 0, bw_old, bw_new, *perm;
  msocl_model *m = points(n);

  for (int i = 0; i + 1 < n; i++) {
    ij[2 * ns] = i;
    ij[2 * ns++ + 1] = i + 1;
    if (i + 2 < n) {
      ij[2 * ns] = i;
      ij[2 * ns++ + 1] = i + 2;
    }
  }
  springs(m, ns, ij);
  perm = rcm(m, &bw_old, &bw_new);
  printf("banded chain of %d: bandwidth %d, RCM %d\n", n, bw_old, bw_new);
  ck_assert_int_eq(bw_old, 2);
  ck_assert_int_le(bw_new, bw_old);
  check_bw_new(m, perm, bw_new);
  free(perm);
  msocl_model_destroy(m);
}
END_TEST

/* Two components and three isolated points. Components go in order of
 * their lowest point, the whole then reversed: the isolated 10, 7, 6
 * first, then the component of 1, then that of 0, each in one range. */
START_TEST(components) {
  const int n = 12;
  /* A = {1 3 5 9}: a chain; B = {0 2 4 8 11}: a ring. */
  const int ij[] = {1, 5, 5, 9, 9, 3, 0, 4, 4, 8, 8, 2, 2, 11, 11, 0};
  const int a[] = {1, 3, 5, 9}, b[] = {0, 2, 4, 8, 11};
  msocl_model *m = points(n);
  int bw_old, bw_new, *perm, *again, inv[12];

  springs(m, 8, ij);
  perm = rcm(m, &bw_old, &bw_new);
  again = rcm(m, &bw_old, &bw_new);
  ck_assert(memcmp(perm, again, n * sizeof *perm) == 0);
  ck_assert_int_eq(perm[0], 10);
  ck_assert_int_eq(perm[1], 7);
  ck_assert_int_eq(perm[2], 6);
  for (int k = 0; k < n; k++) inv[perm[k]] = k;
  for (int i = 0; i < 4; i++)
    ck_assert_msg(inv[a[i]] >= 3 && inv[a[i]] < 7, "point %d at %d", a[i],
                  inv[a[i]]);
  for (int i = 0; i < 5; i++)
    ck_assert_msg(inv[b[i]] >= 7, "point %d at %d", b[i], inv[b[i]]);
  /* A chain stays a chain, a ring of 5 gets bandwidth 2. */
  ck_assert_int_eq(bw_new, 2);
  check_bw_new(m, perm, bw_new);
  free(again);
  free(perm);
  msocl_model_destroy(m);
}
END_TEST

/* No springs: every point alone, so the reversed identity, bandwidth 0. */
START_TEST(no_springs) {
  msocl_model *m = points(5), *p;
  int bw_old, bw_new, *perm = rcm(m, &bw_old, &bw_new);

  ck_assert_int_eq(bw_old, 0);
  ck_assert_int_eq(bw_new, 0);
  for (int k = 0; k < 5; k++) ck_assert_int_eq(perm[k], 4 - k);
  OK(msocl__model_permuted(m, perm, &p));
  ck_assert_int_eq(p->ns, 0);
  ck_assert(p->pos[0] == 4);
  msocl_model_destroy(p);
  free(perm);
  msocl_model_destroy(m);

  m = points(1);
  perm = rcm(m, &bw_old, &bw_new);
  ck_assert_int_eq(perm[0], 0);
  ck_assert_int_eq(bw_old, 0);
  ck_assert_int_eq(bw_new, 0);
  free(perm);
  msocl_model_destroy(m);
}
END_TEST

/* ------------------------------------------------------------------ main */

static Suite *order_suite(void) {
  Suite *s = suite_create("order");
  TCase *t;

  t = tcase_create("rcm");
  tcase_add_test(t, cloth_shuffled);
  tcase_add_test(t, cloth_large);
  tcase_add_test(t, tree_by_hand);
  tcase_add_test(t, chain_and_ring);
  tcase_add_test(t, banded_chain);
  tcase_add_test(t, components);
  tcase_add_test(t, no_springs);
  suite_add_tcase(s, t);

  t = tcase_create("permuted");
  tcase_add_test(t, permuted_carries);
  tcase_add_test(t, permuted_slots);
  tcase_add_test(t, permuted_rejected);
  suite_add_tcase(s, t);
  return s;
}

int main(void) {
  return expect_run(order_suite());
}

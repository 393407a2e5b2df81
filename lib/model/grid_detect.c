/* Recognises a cloth grid or lattice built by hand: a model whose springs
 * are exactly what msocl_model_cloth_grid or msocl_model_lattice would add
 * between its points, so that AUTO can give it the GRID layout. GRID
 * recomputes a point's neighbours from its number and takes one stiffness,
 * rest length and dashpot a kind; the check asks exactly that, and that
 * each point meets its springs in GRID's slot order, so GRID sums what
 * BUFFER sums, bit for bit (positions are state, which GRID never derives). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* GRID's neighbour tables (kernels/common.h): offsets in slot order, each
 * slot's kind (one stiffness) and rest-length index. */
struct stencil {
  int slots, kinds, rests, dims;
  const signed char *dx, *dy, *dz, *kind, *rest;
};

static const signed char cloth_dx[12] = {0, -1, 1, 0, -1, 1, -1, 1, 0, -2, 2, 0};
static const signed char cloth_dy[12] = {-1, 0, 0, 1, -1, -1, 1, 1, -2, 0, 0, 2};
static const signed char cloth_dz[12] = {0};
static const signed char cloth_kind[12] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
static const signed char cloth_rest[12] = {1, 0, 0, 1, 2, 3, 3, 2, 5, 4, 4, 5};

static const signed char lat_dx[32] = {
    0, 0, -1, 1, 0, 0,
    0, -1, 1, 0, -1, 1, 0, -1, -1, 1, 1, 0,
    -1, 1, -1, 1, -1, 1, -1, 1,
    0, 0, -2, 2, 0, 0};
static const signed char lat_dy[32] = {
    0, -1, 0, 0, 1, 0,
    -1, 0, 0, 1, -1, -1, -1, 1, 0, 1, 0, 1,
    -1, -1, 1, 1, -1, -1, 1, 1,
    0, -2, 0, 0, 2, 0};
static const signed char lat_dz[32] = {
    -1, 0, 0, 0, 0, 1,
    -1, -1, -1, -1, 0, 0, 1, 0, 1, 0, 1, 1,
    -1, -1, -1, -1, 1, 1, 1, 1,
    -2, 0, 0, 0, 0, 2};
static const signed char lat_kind[32] = {
    0, 0, 0, 0, 0, 0,
    1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
    2, 2, 2, 2, 2, 2, 2, 2,
    3, 3, 3, 3, 3, 3};

static const struct stencil cloth = {12, 3, 6, 2, cloth_dx, cloth_dy,
                                     cloth_dz, cloth_kind, cloth_rest};
static const struct stencil lattice = {32, 4, 4, 3, lat_dx, lat_dy, lat_dz,
                                       lat_kind, lat_kind};

/* Scratch of one detection: the slots each point has met, and the offset
 * (-2..2 each way) to slot table. */
struct scan {
  const msocl_model *m;
  const struct stencil *st;
  signed char lut[125];
  uint32_t *seen; /* n: bit s once the point met its slot-s spring */
  int damped;
  uint32_t damp; /* the one dashpot, as bits, when damped */
};

static uint32_t bits(float x) {
  uint32_t u;
  memcpy(&u, &x, sizeof u);
  return u;
}

/* The slot of offset (dx, dy, dz), or -1 where the stencil has none. */
static int slot_of(const struct scan *w, int dx, int dy, int dz) {
  if (dx < -2 || dx > 2 || dy < -2 || dy > 2 || dz < -2 || dz > 2) return -1;
  return w->lut[((dz + 2) * 5 + dy + 2) * 5 + dx + 2];
}

static void coords(int p, int nx, int ny, int c[3]) {
  int row = p / nx;
  c[0] = p - row * nx;
  c[2] = row / ny;
  c[1] = row - c[2] * ny;
}

/* Spring s's slot at its end `at` (the other end `to`), or -1. */
static int end_slot(const struct scan *w, int nx, int ny, int at, int to) {
  int a[3], b[3];
  coords(at, nx, ny, a);
  coords(to, nx, ny, b);
  return slot_of(w, b[0] - a[0], b[1] - a[1], b[2] - a[2]);
}

/* A point meets spring slot s: after every slot it met before, and once. */
static int meet(uint32_t *seen, int s) {
  if (*seen >> s) return 0;
  *seen |= (uint32_t)1 << s;
  return 1;
}

/* Point 0's neighbours q (in spring order) in the stencil, in slot order:
 * a wrong shape fails here in O(1), before the pass over the model. */
static int corner_fits(const struct scan *w, int nx, int ny, const int *q,
                       int nq) {
  uint32_t seen = 0;
  for (int a = 0; a < nq; a++) {
    int s = end_slot(w, nx, ny, 0, q[a]);
    if (s < 0 || !meet(&seen, s)) return 0;
  }
  return 1;
}

/* Whether m is the stencil's grid of nx x ny (x nz) points; fills g. */
static int check(struct scan *w, int nx, int ny, int nz, const int *q, int nq,
                 struct msocl__grid *g) {
  const msocl_model *m = w->m;
  const struct stencil *st = w->st;
  uint32_t k[4] = {0}, rest[6] = {0};
  int have_k[4] = {0}, have_rest[6] = {0};

  if (!corner_fits(w, nx, ny, q, nq)) return 0;
  memset(w->seen, 0, (size_t)m->n * sizeof *w->seen);
  for (int s = 0; s < m->ns; s++) {
    int a = m->ij[2 * s], b = m->ij[2 * s + 1], ca[3], cb[3];
    coords(a, nx, ny, ca);
    coords(b, nx, ny, cb);
    int dx = cb[0] - ca[0], dy = cb[1] - ca[1], dz = cb[2] - ca[2];
    int sa = slot_of(w, dx, dy, dz), sb = slot_of(w, -dx, -dy, -dz);
    if (sa < 0 || sb < 0) return 0;
    int kind = st->kind[sa], r = st->rest[sa];
    uint32_t kk = bits(m->k[s]), rr = bits(m->rest[s]);
    /* k 0 is a kind GRID leaves out: it would drop the spring's dashpot */
    if (m->k[s] == 0.0f || (have_k[kind] && kk != k[kind]) ||
        (have_rest[r] && rr != rest[r]))
      return 0;
    if (w->damped && bits(m->damp[s]) != w->damp) return 0;
    k[kind] = kk;
    rest[r] = rr;
    have_k[kind] = have_rest[r] = 1;
    if (!meet(&w->seen[a], sa) || !meet(&w->seen[b], sb)) return 0;
  }
  /* every neighbour of a kind present is there: none missing */
  for (int p = 0; p < m->n; p++) {
    int c[3];
    uint32_t want = 0;
    coords(p, nx, ny, c);
    for (int s = 0; s < st->slots; s++) {
      int x = c[0] + st->dx[s], y = c[1] + st->dy[s], z = c[2] + st->dz[s];
      if (have_k[st->kind[s]] && x >= 0 && x < nx && y >= 0 && y < ny &&
          z >= 0 && z < (nz > 0 ? nz : 1))
        want |= (uint32_t)1 << s;
    }
    if (w->seen[p] != want) return 0;
  }
  memset(g, 0, sizeof *g);
  g->nx = nx;
  g->ny = ny;
  g->nz = nz;
  g->ns = m->ns;
  for (int kind = 0; kind < st->kinds; kind++)
    if (have_k[kind]) memcpy(&g->k[kind], &k[kind], sizeof k[kind]);
  for (int r = 0; r < st->rests; r++)
    if (have_rest[r]) memcpy(&g->rest[r], &rest[r], sizeof rest[r]);
  if (w->damped) memcpy(&g->damp, &w->damp, sizeof w->damp);
  return 1;
}

/* Point 0's neighbours, at most `cap` (more: no grid); -1 past it. */
static int neighbours_of_0(const msocl_model *m, int *q, int cap) {
  int nq = 0;
  for (int s = 0; s < m->ns; s++)
    for (int e = 0; e < 2; e++)
      if (m->ij[2 * s + e] == 0) {
        if (nq == cap) return -1;
        q[nq++] = m->ij[2 * s + !e];
      }
  return nq;
}

/* Point 0 is a corner: each neighbour q sits at an offset of zeros, ones
 * and twos, q = dx + nx dy + nx ny dz. A cloth's nx is then q, q - 1 or
 * q / 2 of some neighbour; a lattice's nx ny is q, q - 1, q - nx,
 * q - nx - 1 or q / 2 of one with dz > 0. Candidates are few (at most 15
 * and 1500), each tried on point 0 first: a pass over the model only for
 * those that place its springs. */
static int from_one(int q, int i) {
  return i == 0 ? q : i == 1 ? q - 1 : q % 2 == 0 ? q / 2 : -1;
}

static int try_cloth(struct scan *w, const int *q, int nq,
                     struct msocl__grid *g) {
  const int n = w->m->n;
  for (int a = 0; a < nq; a++)
    for (int i = 0; i < 3; i++) {
      int nx = from_one(q[a], i);
      if (nx >= 2 && n % nx == 0 && n / nx >= 2 &&
          check(w, nx, n / nx, 0, q, nq, g))
        return 1;
    }
  return 0;
}

static int try_lattice(struct scan *w, const int *q, int nq,
                       struct msocl__grid *g) {
  const int n = w->m->n;
  for (int a = 0; a < nq; a++)
    for (int i = 0; i < 3; i++) {
      int nx = from_one(q[a], i);
      if (nx < 2 || n % nx != 0) continue;
      for (int b = 0; b < nq; b++)
        for (int j = 0; j < 5; j++) {
          int v = q[b], layer = j == 0 ? v : j == 1 ? v - 1 : j == 2 ? v - nx
                              : j == 3 ? v - nx - 1 : v % 2 == 0 ? v / 2 : -1;
          if (layer < 2 * nx || layer % nx != 0 || n % layer != 0 ||
              n / layer < 2)
            continue;
          if (check(w, nx, layer / nx, n / layer, q, nq, g)) return 1;
        }
    }
  return 0;
}

static int detect(struct scan *w, const struct stencil *st, const int *q,
                  int nq, struct msocl__grid *g) {
  w->st = st;
  memset(w->lut, -1, sizeof w->lut);
  for (int s = 0; s < st->slots; s++)
    w->lut[((st->dz[s] + 2) * 5 + st->dy[s] + 2) * 5 + st->dx[s] + 2] =
        (signed char)s;
  return st->dims == 2 ? try_cloth(w, q, nq, g) : try_lattice(w, q, nq, g);
}

int msocl__grid_detect(const msocl_model *m, struct msocl__grid *g) {
  /* a corner of a lattice has 10 neighbours, of a cloth 5 */
  int q[11], nq, found = 0;
  struct scan w;

  if (m->n < 4 || m->ns == 0 || (nq = neighbours_of_0(m, q, 10)) <= 0)
    return 0;
  memset(&w, 0, sizeof w);
  w.m = m;
  /* one dashpot for every spring, or none anywhere */
  for (int s = 0; m->damp && s < m->ns && !w.damped; s++)
    if (m->damp[s] != 0.0f) {
      w.damped = 1;
      w.damp = bits(m->damp[s]);
    }
  w.seen = malloc((size_t)m->n * sizeof *w.seen);
  if (!w.seen) return 0; /* BUFFER then, whose own allocation reports it */
  found = (nq <= 5 && detect(&w, &cloth, q, nq, g)) ||
          (m->n >= 8 && detect(&w, &lattice, q, nq, g));
  free(w.seen);
  return found;
}

int msocl__model_with_grid(const msocl_model *m, const struct msocl__grid *g,
                           msocl_model **out) {
  int *identity = malloc((m->n > 0 ? (size_t)m->n : 1) * sizeof *identity);
  int rc;

  *out = NULL;
  if (!identity)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "grid model: %d points", m->n);
  for (int i = 0; i < m->n; i++) identity[i] = i;
  rc = msocl__model_permuted(m, identity, out);
  free(identity);
  if (rc == MSOCL_OK) (*out)->grid = *g;
  return rc;
}

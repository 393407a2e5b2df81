/* Point numbering: reverse Cuthill-McKee by springs, and a model with its
 * points renumbered. Spring neighbours with nearby numbers let a model be
 * cut into contiguous index ranges with small halos (one range a device)
 * and keep each point's gathers close together in memory. */
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* -------------------------------------------------------------- bandwidth */

/* max |i - j| over the springs, the ends renumbered by inv (NULL: as they
 * are). */
static int bandwidth(const msocl_model *m, const int *inv) {
  int s, bw = 0;

  for (s = 0; s < m->ns; s++) {
    int a = m->ij[2 * s], b = m->ij[2 * s + 1], d;
    if (inv) {
      a = inv[a];
      b = inv[b];
    }
    d = a > b ? a - b : b - a;
    if (d > bw) bw = d;
  }
  return bw;
}

/* ---------------------------------------------------------------- search */

/* Scratch of one ordering; all of it O(n + ns) and iterative, since models
 * reach millions of points (no recursion to overflow the stack). */
struct rcm {
  struct msocl__adjacency a;
  int *q;      /* n: a level structure, breadth first */
  int *seen;   /* n: stamp of the last search that reached the point */
  int stamp;
  unsigned char *placed;   /* n: numbered already */
  unsigned long long *key; /* max_degree: (degree, number) to sort */
};

/* Springs, not distinct neighbours: a doubled spring counts twice, as it
 * does in a point's gather. */
static int degree(const struct rcm *w, int i) {
  return w->a.off[i + 1] - w->a.off[i];
}

/* The level structure rooted at r into q; returns r's eccentricity (the
 * number of levels less one) and the last level as q[*first .. *end). */
static int levels(struct rcm *w, int r, int *first, int *end) {
  int start = 0, stop = 1, tail = 1, ecc = 0, h, e;

  w->stamp++;
  w->q[0] = r;
  w->seen[r] = w->stamp;
  for (;;) {
    for (h = start; h < stop; h++) {
      int p = w->q[h];
      for (e = w->a.off[p]; e < w->a.off[p + 1]; e++) {
        int o = w->a.other[e];
        if (w->seen[o] != w->stamp) {
          w->seen[o] = w->stamp;
          w->q[tail++] = o;
        }
      }
    }
    if (tail == stop) break;
    start = stop;
    stop = tail;
    ecc++;
  }
  *first = start;
  *end = stop;
  return ecc;
}

/* Lowest degree in q[first .. end), ties to the lowest number, so the
 * choice does not hang on the order the search met the points in. */
static int lowest_degree(const struct rcm *w, int first, int end) {
  int h, best = w->q[first];

  for (h = first + 1; h < end; h++) {
    int p = w->q[h], dp = degree(w, p), db = degree(w, best);
    if (dp < db || (dp == db && p < best)) best = p;
  }
  return best;
}

/* George and Liu's pseudo-peripheral point: root a level structure at the
 * far end of the last one while that makes it deeper. The eccentricity
 * grows each round, so the rounds are bounded by the component's diameter
 * (a handful on meshes). As in their algorithm, the answer is the last
 * root tried: as deep as the one before it, and no nearer the middle. */
static int peripheral(struct rcm *w, int r) {
  int first, end, ecc = levels(w, r, &first, &end);

  for (;;) {
    int x = lowest_degree(w, first, end), e = levels(w, x, &first, &end);
    if (e <= ecc) return x;
    ecc = e;
  }
}

/* Short lists (a mesh point's 4 to 32 springs) sort faster by insertion
 * than through qsort's calls. */
static int key_cmp(const void *pa, const void *pb) {
  unsigned long long a = *(const unsigned long long *)pa,
                     b = *(const unsigned long long *)pb;
  return (a > b) - (a < b);
}

static void sort_keys(unsigned long long *key, int n) {
  int i, j;

  if (n > 32) {
    qsort(key, (size_t)n, sizeof *key, key_cmp);
    return;
  }
  for (i = 1; i < n; i++) {
    unsigned long long k = key[i];
    for (j = i; j > 0 && key[j - 1] > k; j--) key[j] = key[j - 1];
    key[j] = k;
  }
}

/* Cuthill-McKee over the component of s: breadth first from s, each
 * point's new neighbours appended by degree, then number. perm is the
 * queue; *count is its length so far. */
static void number_component(struct rcm *w, int s, int *perm, int *count) {
  int head = *count, e, i, nk;

  perm[(*count)++] = s;
  w->placed[s] = 1;
  while (head < *count) {
    int p = perm[head++];
    nk = 0;
    for (e = w->a.off[p]; e < w->a.off[p + 1]; e++) {
      int o = w->a.other[e];
      if (!w->placed[o]) {
        w->placed[o] = 1;
        w->key[nk++] = (unsigned long long)degree(w, o) << 32 | (unsigned)o;
      }
    }
    sort_keys(w->key, nk);
    for (i = 0; i < nk; i++) perm[(*count)++] = (int)(w->key[i] & 0xffffffffu);
  }
}

static void rcm_free(struct rcm *w) {
  msocl__adjacency_free(&w->a);
  free(w->q);
  free(w->seen);
  free(w->placed);
  free(w->key);
}

int msocl__order_rcm(const msocl_model *m, int *perm, int *bw_old,
                     int *bw_new) {
  struct rcm w;
  int i, count = 0, rc;
  size_t n1;

  memset(&w, 0, sizeof w);
  if (!m || !perm)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "order_rcm: NULL argument");
  if ((rc = msocl__adjacency_build(m, &w.a))) return rc;
  /* Only the neighbours are needed: give back the spring numbers' 2 ns
   * ints at once, the largest array here on a big model. */
  free(w.a.spring);
  w.a.spring = NULL;
  n1 = (size_t)m->n + 1; /* never 0 bytes: malloc(0) may answer NULL */
  w.q = malloc(n1 * sizeof *w.q);
  w.seen = calloc(n1, sizeof *w.seen);
  w.placed = calloc(n1, 1);
  w.key = malloc(((size_t)w.a.max_degree + 1) * sizeof *w.key);
  if (!w.q || !w.seen || !w.placed || !w.key) {
    rcm_free(&w);
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "order_rcm: cannot allocate the scratch of %d points",
                       m->n);
  }

  /* Components in order of their lowest point. An isolated point needs no
   * search (and spends no stamp). */
  for (i = 0; i < m->n; i++) {
    if (w.placed[i]) continue;
    if (degree(&w, i) == 0) {
      w.placed[i] = 1;
      perm[count++] = i;
    } else {
      number_component(&w, peripheral(&w, i), perm, &count);
    }
  }
  /* Reversed (George): the bandwidth stays, the profile (and with it the
   * fill of a banded factorisation) can only shrink. */
  for (i = 0; i < m->n / 2; i++) {
    int t = perm[i];
    perm[i] = perm[m->n - 1 - i];
    perm[m->n - 1 - i] = t;
  }

  if (bw_old) *bw_old = bandwidth(m, NULL);
  if (bw_new) {
    for (i = 0; i < m->n; i++) w.seen[perm[i]] = i; /* now the inverse */
    *bw_new = bandwidth(m, w.seen);
  }
  rcm_free(&w);
  return MSOCL_OK;
}

/* ------------------------------------------------------------- renumber */

/* inv[old] = new, checking that perm is a permutation of 0 .. n-1;
 * *identity says whether it is the identity. */
static int inverse(const int *perm, int n, int **out, int *identity) {
  int k, *inv = malloc(((size_t)n + 1) * sizeof *inv);

  *out = NULL;
  *identity = 1;
  if (!inv)
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "model_permuted: cannot allocate %d ints", n);
  for (k = 0; k < n; k++) inv[k] = -1;
  for (k = 0; k < n; k++) {
    int o = perm[k];
    if (o < 0 || o >= n) {
      free(inv);
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "model_permuted: perm[%d] = %d is out of range "
                         "[0, %d)",
                         k, o, n);
    }
    if (inv[o] >= 0) {
      int first = inv[o];
      free(inv);
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "model_permuted: perm[%d] = %d repeats perm[%d]", k,
                         o, first);
    }
    inv[o] = k;
    if (o != k) *identity = 0;
  }
  *out = inv;
  return MSOCL_OK;
}

/* count items of size bytes, or NULL for none (as an empty model holds);
 * sets *failed when the memory is not there. */
static void *room(size_t count, size_t size, int *failed) {
  void *p;

  if (count == 0) return NULL;
  if (!(p = malloc(count * size))) *failed = 1;
  return p;
}

int msocl__model_permuted(const msocl_model *m, const int *perm,
                          msocl_model **out) {
  msocl_model *p;
  int *inv, identity, failed = 0, k, s, c, rc;

  if (out) *out = NULL;
  if (!m || !perm || !out)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model_permuted: NULL argument");
  if ((rc = inverse(perm, m->n, &inv, &identity))) return rc;
  if ((rc = msocl_model_create(&p))) {
    free(inv);
    return rc;
  }

  /* A whole copy carries every scalar field, the colliders and the
   * capacities (so later adds grow the copy as they would the original);
   * the arrays, owned by m, are replaced before anything can fail. */
  *p = *m;
  p->pos = p->mass = p->k = p->rest = p->damp = NULL;
  p->pinned = NULL;
  p->ij = p->tri = NULL;
  p->live = NULL; /* the copy's simulations are its own */
  p->mesh = NULL; /* mesh colliders: the simulation reads the caller's */
  p->nmesh = 0;
  p->pos = room((size_t)m->cap * 3, sizeof *p->pos, &failed);
  p->mass = room((size_t)m->cap, sizeof *p->mass, &failed);
  p->pinned = room((size_t)m->cap, sizeof *p->pinned, &failed);
  p->ij = room((size_t)m->scap * 2, sizeof *p->ij, &failed);
  p->k = room((size_t)m->scap, sizeof *p->k, &failed);
  p->rest = room((size_t)m->scap, sizeof *p->rest, &failed);
  if (m->damp) p->damp = room((size_t)m->scap, sizeof *p->damp, &failed);
  p->tri = room((size_t)m->tcap * 3, sizeof *p->tri, &failed);
  if (failed) {
    msocl_model_destroy(p);
    free(inv);
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "model_permuted: cannot allocate a model of %d points, "
                       "%d springs, %d triangles",
                       m->n, m->ns, m->nt);
  }

  for (k = 0; k < m->n; k++) {
    int o = perm[k];
    for (c = 0; c < 3; c++) p->pos[3 * k + c] = m->pos[3 * o + c];
    p->mass[k] = m->mass[o];
    p->pinned[k] = m->pinned[o];
  }
  /* Springs stay in their order, so each point meets its springs in the
   * order it did and sums its forces bit for bit as before. */
  for (s = 0; s < 2 * m->ns; s++) p->ij[s] = inv[m->ij[s]];
  if (m->ns > 0) {
    memcpy(p->k, m->k, (size_t)m->ns * sizeof *p->k);
    memcpy(p->rest, m->rest, (size_t)m->ns * sizeof *p->rest);
    if (m->damp) memcpy(p->damp, m->damp, (size_t)m->ns * sizeof *p->damp);
  }
  for (s = 0; s < 3 * m->nt; s++) p->tri[s] = inv[m->tri[s]];
  /* The GRID layout finds neighbours from the numbers j * nx + i, which
   * only the identity keeps. */
  if (!identity) memset(&p->grid, 0, sizeof p->grid);
  free(inv);
  *out = p;
  return MSOCL_OK;
}

/* The edge and bending springs of a triangle mesh: sorting the three
 * half-edges of every triangle puts each edge's triangles side by side. */
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "mesh_edges.h"

/* The model holds at most this many springs (2 ints each, int-indexed). */
#define MAX_SPRINGS (INT_MAX / 2)

/* Edge (a < b) of a triangle whose third corner is opp. */
struct half {
  int a, b, opp;
};

static int cmp_int(int x, int y) { return (x > y) - (x < y); }

/* opp last, so equal edges sort the same way on every qsort. */
static int cmp_half(const void *x, const void *y) {
  const struct half *h = x, *k = y;
  int c = cmp_int(h->a, k->a);
  if (!c) c = cmp_int(h->b, k->b);
  return c ? c : cmp_int(h->opp, k->opp);
}

static int cmp_pair(const void *x, const void *y) {
  const int *p = x, *q = y;
  int c = cmp_int(p[0], q[0]);
  return c ? c : cmp_int(p[1], q[1]);
}

static void put_pair(int *ij, int a, int b) {
  ij[0] = a < b ? a : b;
  ij[1] = a < b ? b : a;
}

static struct half *halves(int nt, const int *tri) {
  size_t n = 3 * (size_t)nt, t;
  struct half *h;
  int c;

  if (n > SIZE_MAX / sizeof *h || !(h = malloc(n * sizeof *h))) return NULL;
  for (t = 0; t < (size_t)nt; t++)
    for (c = 0; c < 3; c++) {
      const int *k = tri + 3 * t;
      struct half *e = &h[3 * t + c];
      int pair[2];
      put_pair(pair, k[c], k[(c + 1) % 3]);
      e->a = pair[0];
      e->b = pair[1];
      e->opp = k[(c + 2) % 3];
    }
  qsort(h, n, sizeof *h, cmp_half);
  return h;
}

/* Sorts the candidate pairs at ij[2*nedges...], keeps each once and drops
 * those that are edges already (the edges lie sorted before them). */
static int unique_bends(int *ij, int nedges, int ncand) {
  int *c = ij + 2 * (size_t)nedges, i, n = 0;

  qsort(c, (size_t)ncand, 2 * sizeof *c, cmp_pair);
  for (i = 0; i < ncand; i++) {
    const int *p = c + 2 * (size_t)i;
    if (n > 0 && !cmp_pair(p, c + 2 * (size_t)(n - 1))) continue;
    if (nedges > 0 && bsearch(p, ij, (size_t)nedges, 2 * sizeof *ij, cmp_pair))
      continue;
    memmove(c + 2 * (size_t)n++, p, 2 * sizeof *p);
  }
  return n;
}

/* Runs of equal edges in the sorted halves: one edge a run, and a bend
 * candidate where exactly two triangles with distinct third corners meet.
 * With out NULL only counts; else edges go to out[0...], candidates after
 * the nedges edges. */
static void scan(const struct half *h, size_t n, int bends, int *out,
                 size_t nedges, size_t *ne, size_t *nc) {
  size_t i, j;

  *ne = *nc = 0;
  for (i = 0; i < n; i = j) {
    for (j = i + 1; j < n && h[j].a == h[i].a && h[j].b == h[i].b; j++) {}
    if (out) put_pair(out + 2 * *ne, h[i].a, h[i].b);
    ++*ne;
    if (bends && j - i == 2 && h[i].opp != h[i + 1].opp) {
      if (out) put_pair(out + 2 * (nedges + *nc), h[i].opp, h[i + 1].opp);
      ++*nc;
    }
  }
}

int msocl__mesh_springs(int nt, const int *tri, int bends, int **ij,
                        int *nedges, int *nbends) {
  size_t n = 3 * (size_t)nt, ne, nc;
  struct half *h = halves(nt, tri);
  int *out, nb;

  *ij = NULL;
  *nedges = *nbends = 0;
  if (!h)
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "cannot sort the edges of %d triangles", nt);
  /* Count first, so one allocation holds edges and bend candidates. */
  scan(h, n, bends, NULL, 0, &ne, &nc);
  if (ne > MAX_SPRINGS) {
    free(h);
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "the mesh has %zu edges, more than the %d springs a "
                       "model holds",
                       ne, MAX_SPRINGS);
  }
  if (ne + nc > SIZE_MAX / (2 * sizeof *out) ||
      !(out = malloc(2 * (ne + nc) * sizeof *out))) {
    free(h);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "cannot allocate %zu springs",
                       ne + nc);
  }
  scan(h, n, bends, out, ne, &ne, &nc);
  free(h);
  nb = unique_bends(out, (int)ne, (int)nc);
  if (ne + (size_t)nb > MAX_SPRINGS) {
    free(out);
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "the mesh has %zu edge and %d bending springs, more "
                       "than the %d a model holds",
                       ne, nb, MAX_SPRINGS);
  }
  *ij = out;
  *nedges = (int)ne;
  *nbends = nb;
  return MSOCL_OK;
}

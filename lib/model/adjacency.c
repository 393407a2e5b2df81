/* Per-point lists of springs (compressed rows), the common source of every
 * gather layout's connectivity. */
#include <stdlib.h>
#include <string.h>

#include "internal.h"

int msocl__adjacency_build(const msocl_model *m, struct msocl__adjacency *a) {
  int i, s, e;
  size_t slots;

  if (a) memset(a, 0, sizeof *a);
  if (!m || !a)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "adjacency: NULL argument");
  /* Never 0 bytes: malloc(0) may answer NULL, which would read as failure. */
  slots = 2 * (size_t)m->ns + 1;
  a->off = calloc((size_t)m->n + 1, sizeof *a->off);
  a->other = malloc(slots * sizeof *a->other);
  a->spring = malloc(slots * sizeof *a->spring);
  if (!a->off || !a->other || !a->spring) {
    msocl__adjacency_free(a);
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "cannot allocate the adjacency of %d points, %d springs",
                       m->n, m->ns);
  }
  a->n = m->n;

  /* Degrees into off[i + 1], then their prefix sums: off[i] = start of i. */
  for (e = 0; e < 2 * m->ns; e++) a->off[m->ij[e] + 1]++;
  for (i = 0; i < m->n; i++) {
    if (a->off[i + 1] > a->max_degree) a->max_degree = a->off[i + 1];
    a->off[i + 1] += a->off[i];
  }

  /* Springs in the order they were added, so slot order is spring order;
   * off[i] serves as point i's cursor and ends at the start of i + 1. */
  for (s = 0; s < m->ns; s++)
    for (e = 0; e < 2; e++) {
      int p = m->ij[2 * s + e], slot = a->off[p]++;
      a->other[slot] = m->ij[2 * s + !e];
      a->spring[slot] = s;
    }
  for (i = m->n; i > 0; i--) a->off[i] = a->off[i - 1];
  a->off[0] = 0;
  return MSOCL_OK;
}

void msocl__adjacency_free(struct msocl__adjacency *a) {
  if (!a) return;
  free(a->off);
  free(a->other);
  free(a->spring);
  memset(a, 0, sizeof *a);
}

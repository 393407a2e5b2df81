/* Soft pins on a running simulation: points pulled toward anchors by
 * springs (the engine's part: engine/soft_pins.c). Given again for the
 * same points in the same order, the anchors move there over the next
 * stepping call along straight lines, as pin targets do (motion.c);
 * otherwise they start where they are given. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct msocl__soft {
  int m;     /* points, in the model's numbers */
  int *idx;
  int moving; /* the anchors move over the next call */
};

void msocl__soft_pins_free(msocl_sim *s)
{
  if (s->soft)
    free(s->soft->idx);
  free(s->soft);
  s->soft = NULL;
}

int msocl__soft_pins_moving(const msocl_sim *s)
{
  return s->soft && s->soft->moving;
}

void msocl__soft_pins_place(msocl_sim *s, float f)
{
  msocl__soft_fraction(s->part[0], f);
  if (f == 1.0f)
    s->soft->moving = 0;
}

static int check(msocl_sim *s, int count, const int *idx, const float *xyz,
                 float stiffness)
{
  const char *what = "msocl_sim_set_soft_pins";
  if (count < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "%s: count %d is negative", what,
                       count);
  if (count > 0 && (!idx || !xyz))
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: %s is NULL", what,
                       idx ? "the anchors" : "the index list");
  if (count > 0 && !(isfinite(stiffness) && stiffness > 0.0f))
    return msocl__fail(isfinite(stiffness) ? MSOCL_ERR_BAD_VALUE
                                           : MSOCL_ERR_NOT_FINITE,
                       "%s: stiffness %g must be finite and > 0", what,
                       (double)stiffness);
  if (s->nparts > 1 && count > 0) /* clearing none is no soft pin */
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: soft pins do not run on a simulation split over "
                       "%d devices", what, s->nparts);
  MSOCL__TRY(msocl__check_triples(what, "anchor", xyz, count, NULL, 0,
                                  MSOCL__COORD_MAX));
  unsigned char *seen = calloc((size_t)s->n + 1, 1);
  if (!seen)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "soft pins");
  int rc = MSOCL_OK;
  for (int q = 0; rc == MSOCL_OK && q < count; q++) {
    int k = 0;
    if (idx[q] < 0 || idx[q] >= s->n)
      rc = msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "%s: index %d (entry %d) out of range [0, %d)", what,
                       idx[q], q, s->n);
    else if (seen[idx[q]])
      rc = msocl__fail(MSOCL_ERR_BAD_VALUE, "%s: point %d given twice", what,
                       idx[q]);
    else if ((rc = msocl__sim_index(s, idx[q], &k)) == MSOCL_OK &&
             s->pinned[k])
      rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: point %d is pinned (hard); free it with "
                       "msocl_sim_pin first", what, idx[q]);
    if (rc == MSOCL_OK)
      seen[idx[q]] = 1;
  }
  free(seen);
  return rc;
}

int msocl_sim_set_soft_pins(msocl_sim *s, int count, const int *idx,
                            const float *xyz, float stiffness)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  MSOCL__TRY(check(s, count, idx, xyz, stiffness));
  if (s->nparts > 1) /* none to clear: a split never had any */
    return MSOCL_OK;
  if (!s->soft && !(s->soft = calloc(1, sizeof *s->soft)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "soft pins");
  struct msocl__soft *c = s->soft;
  const int move = count > 0 && count == c->m &&
                   memcmp(idx, c->idx, (size_t)count * sizeof *idx) == 0;
  int *k = malloc(((size_t)count + 1) * sizeof *k);
  int *keep = malloc(((size_t)count + 1) * sizeof *keep);
  int rc = k && keep ? MSOCL_OK
                     : msocl__fail(MSOCL_ERR_NO_MEMORY, "soft pins");
  for (int q = 0; rc == MSOCL_OK && q < count; q++)
    rc = msocl__sim_index(s, idx[q], &k[q]);
  if (rc == MSOCL_OK)
    rc = msocl__soft_set(s->part[0], count, k, xyz, stiffness, move);
  free(k);
  if (rc != MSOCL_OK) {
    free(keep);
    return rc;
  }
  if (count > 0)
    memcpy(keep, idx, (size_t)count * sizeof *idx);
  free(c->idx);
  c->idx = keep;
  c->m = count;
  c->moving = move;
  return MSOCL_OK;
}

/* Soft pins in double, as engine/soft_pins.c: listed points pulled toward
 * anchors by springs, a velocity change dt k (anchor - x) / m before each
 * step; anchors given again for the same points move there over the next
 * call, from where they rest. */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int msocl_reference_set_soft_pins(msocl_reference *r, int count,
                                  const int *idx, const float *xyz,
                                  float stiffness)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  if (count < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "soft pins: count %d", count);
  if (count > 0 && (!idx || !xyz))
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "soft pins: a list is NULL");
  if (count > 0 && !(isfinite(stiffness) && stiffness > 0.0f))
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "soft pins: stiffness %g",
                       (double)stiffness);
  for (int q = 0; q < count; q++) {
    if (idx[q] < 0 || idx[q] >= r->n)
      return msocl__fail(MSOCL_ERR_BAD_INDEX, "soft pins: index %d", idx[q]);
    if (r->pinned[idx[q]])
      return msocl__fail(MSOCL_ERR_BAD_VALUE, "soft pins: point %d is pinned",
                         idx[q]);
  }
  MSOCL__TRY(msocl__check_triples("soft pins", "anchor", xyz, count, NULL, 0,
                                  MSOCL__COORD_MAX));
  const int move = count > 0 && count == r->soft_m &&
                   memcmp(idx, r->soft_idx, (size_t)count * sizeof *idx) == 0;
  int *keep = malloc(((size_t)count + 1) * sizeof *keep);
  double *from = malloc((3 * (size_t)count + 1) * sizeof *from),
         *to = malloc((3 * (size_t)count + 1) * sizeof *to);
  if (!keep || !from || !to) {
    free(keep);
    free(from);
    free(to);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "soft pins");
  }
  for (int q = 0; q < 3 * count; q++) {
    to[q] = xyz[q];
    from[q] = move ? r->soft_to[q] : xyz[q];
  }
  if (count > 0)
    memcpy(keep, idx, (size_t)count * sizeof *idx);
  free(r->soft_idx);
  free(r->soft_from);
  free(r->soft_to);
  r->soft_idx = keep;
  r->soft_from = from;
  r->soft_to = to;
  r->soft_m = count;
  r->soft_k = stiffness;
  r->soft_moving = move;
  return MSOCL_OK;
}

void msocl__ref_soft_pins(msocl_reference *r, int k, int n)
{
  /* the fraction as the engine computes it, in float */
  const double f = r->soft_moving && k < n ? (double)((float)k / (float)n)
                                           : 1.0;
  if (k == n) {
    r->soft_moving = 0;
    return;
  }
  for (int q = 0; q < r->soft_m; q++) {
    const int i = r->soft_idx[q];
    const double s = r->dt * r->soft_k * r->inv_mass[i];
    for (int e = 0; e < 3; e++) {
      const double anchor =
          (1 - f) * r->soft_from[3 * q + e] + f * r->soft_to[3 * q + e];
      r->vel[3 * i + e] += s * (anchor - r->pos[3 * i + e]);
    }
  }
}

void msocl__ref_soft_pins_free(msocl_reference *r)
{
  free(r->soft_idx);
  free(r->soft_from);
  free(r->soft_to);
}

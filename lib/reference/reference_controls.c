/* The host reference's live controls, as the simulation's (lib/sim/
 * sim_controls.c) in double: gravity, viscous damping and air
 * resistance, pins, and pins moved to targets along a straight path over
 * the next call's steps. */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int msocl_reference_set_gravity(msocl_reference *r, float gx, float gy,
                                float gz)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  const float g[3] = {gx, gy, gz};
  MSOCL__TRY(msocl__check_triples("msocl_reference_set_gravity", "vector",
                                  g, 1, NULL, 0, MSOCL__FORCE_MAX));
  r->gravity[0] = gx;
  r->gravity[1] = gy;
  r->gravity[2] = gz;
  r->acc_valid = 0; /* Verlet's a held the old gravity */
  return MSOCL_OK;
}

/* Viscous damping (air 0) or air resistance (air 1), as the simulation
 * checks them (sim_controls.c set_damping). */
static int set_damping(msocl_reference *r, int air, float value)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  MSOCL__TRY(msocl__check_damping(air, value));
  if (air)
    r->air = value;
  else {
    r->viscous = value;
    r->acc_valid = 0; /* Verlet's a held the old damping force */
  }
  return MSOCL_OK;
}

int msocl_reference_set_viscous_damping(msocl_reference *r, float c)
{
  return set_damping(r, 0, c);
}

int msocl_reference_set_air_resistance(msocl_reference *r, float factor)
{
  return set_damping(r, 1, factor);
}

static int check_indices(const msocl_reference *r, int count, const int *idx)
{
  if (count < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "count %d is negative", count);
  if (count > 0 && !idx)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "index list is NULL");
  for (int q = 0; q < count; q++)
    if (idx[q] < 0 || idx[q] >= r->n)
      return msocl__fail(MSOCL_ERR_BAD_INDEX,
                         "index %d (entry %d) out of range [0, %d)", idx[q], q,
                         r->n);
  return MSOCL_OK;
}

int msocl_reference_pin(msocl_reference *r, int count, const int *idx,
                        int pinned)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  MSOCL__TRY(check_indices(r, count, idx));
  for (int q = 0; q < count; q++)
    r->pinned[idx[q]] = pinned != 0;
  r->acc_valid = 0;
  return MSOCL_OK;
}

void msocl__ref_controls_free(msocl_reference *r)
{
  free(r->tidx);
  free(r->tstart);
  free(r->ttarget);
  r->tidx = NULL;
  r->tstart = r->ttarget = NULL;
  r->tm = 0;
}

int msocl_reference_set_pin_targets(msocl_reference *r, int count,
                                    const int *idx, const float *xyz)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  if (idx)
    MSOCL__TRY(check_indices(r, count, idx));
  else if (count < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "count %d is negative", count);
  if (count > 0 && !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "targets are NULL");
  int npins = 0;
  for (int i = 0; i < r->n; i++)
    npins += r->pinned[i];
  if (!idx && count != npins)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "%d targets for all %d pinned points", count, npins);
  MSOCL__TRY(msocl__check_triples("msocl_reference_set_pin_targets",
                                  "target", xyz, count, NULL, 0,
                                  MSOCL__COORD_MAX));
  int *ix = malloc(((size_t)count + 1) * sizeof *ix);
  double *st = malloc((3 * (size_t)count + 1) * sizeof *st),
         *tg = malloc((3 * (size_t)count + 1) * sizeof *tg);
  if (!ix || !st || !tg) {
    free(ix);
    free(st);
    free(tg);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "pin targets");
  }
  for (int q = 0, next = 0; q < count; q++) {
    if (idx)
      ix[q] = idx[q];
    else {
      while (!r->pinned[next])
        next++;
      ix[q] = next++;
    }
    int rc = r->pinned[ix[q]]
                 ? MSOCL_OK
                 : msocl__fail(MSOCL_ERR_BAD_VALUE, "point %d is not pinned",
                               ix[q]);
    for (int t = 0; rc == MSOCL_OK && t < q; t++)
      if (ix[t] == ix[q])
        rc = msocl__fail(MSOCL_ERR_BAD_VALUE, "point %d given twice", ix[q]);
    if (rc != MSOCL_OK) {
      free(ix);
      free(st);
      free(tg);
      return rc;
    }
    for (int e = 0; e < 3; e++)
      tg[3 * q + e] = xyz[3 * q + e];
  }
  msocl__ref_controls_free(r);
  r->tidx = ix;
  r->tstart = st;
  r->ttarget = tg;
  r->tm = count;
  return MSOCL_OK;
}

/* Before step k of n: each moving pin at k / n of its path, with the
 * velocity to (k + 1) / n in a step; at k = n, at its target, keeping the
 * last step's velocity, and the targets are spent. */
void msocl__ref_pins(msocl_reference *r, int k, int n)
{
  for (int q = 0; q < r->tm; q++) {
    double *p = r->pos + 3 * r->tidx[q], *v = r->vel + 3 * r->tidx[q];
    const double *s = r->tstart + 3 * q, *t = r->ttarget + 3 * q;
    if (k == 0)
      memcpy(r->tstart + 3 * q, p, 3 * sizeof(double));
    const double fp = (double)k / n, f0 = (double)(k < n ? k : n - 1) / n,
                 f1 = (double)(k < n ? k + 1 : n) / n;
    for (int e = 0; e < 3; e++) {
      const double x0 = (1 - f0) * s[e] + f0 * t[e],
                   x1 = (1 - f1) * s[e] + f1 * t[e];
      p[e] = (1 - fp) * s[e] + fp * t[e];
      v[e] = (x1 - x0) / r->dt;
    }
  }
  if (k == n && r->tm > 0) /* Verlet's a is kept, as the kernels keep it */
    msocl__ref_controls_free(r);
}

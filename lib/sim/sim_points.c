/* Partial state access: the positions or velocities of an index range or
 * list of points, read or written without moving the whole state between
 * host and device (each run of consecutive points one copy a plane) and
 * without touching any other point. A write, like
 * msocl_sim_write_positions, keeps the pins and counts as a write for the
 * blow-up check. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The simulation's numbers of points idx[0..count) (idx NULL: first on). */
static int numbers(msocl_sim *s, int first, int count, const int *idx,
                   int *k)
{
  for (int q = 0; q < count; q++)
    MSOCL__TRY(msocl__sim_index(s, idx ? idx[q] : first + q, &k[q]));
  return MSOCL_OK;
}

/* Reads (or writes) the simulation's points k[0..count) of engine e's
 * current state into (from) xyz, a copy for each run of consecutive
 * points; reads only those of the engine's own range. */
static int copy_runs(msocl__engine *e, int velocities, int write,
                     const int *k, int count, float *xyz)
{
  for (int q = 0; q < count;) {
    int r = q + 1;
    while (r < count && k[r] == k[r - 1] + 1 &&
           (write || k[r] < e->hi))
      r++;
    if (!write && (k[q] < e->lo || k[q] >= e->hi)) {
      q++;
      continue;
    }
    const int lo = k[q], hi = k[r - 1] + 1;
    MSOCL__TRY(write ? msocl__state_write(e, velocities, lo, hi, xyz + 3 * q)
                     : msocl__state_read(e, velocities, lo, hi, xyz + 3 * q));
    q = r;
  }
  return MSOCL_OK;
}

/* A write's list names a point once: which of two values would win is
 * the copy order's, not the caller's (pin targets and soft pins refuse
 * the same). */
static int once_each(const msocl_sim *s, int count, const int *idx)
{
  unsigned char *seen = calloc((size_t)s->n, 1);
  if (!seen)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "write of %d points", count);
  int rc = MSOCL_OK;
  for (int q = 0; rc == MSOCL_OK && q < count; q++)
    if (seen[idx[q]]++)
      rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "write: point %d listed twice (entry %d)", idx[q], q);
  free(seen);
  return rc;
}

static int points_io(msocl_sim *s, int velocities, int write, int list,
                  int first, int count, const int *idx, float *out,
                  const float *in)
{
  msocl__clear_error();
  const char *what = write ? "write" : "read";
  if (!s || (count > 0 && !(write ? (const void *)in : (void *)out)))
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: %s is NULL", what,
                       s ? "the array" : "sim");
  if (count < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "%s: count %d is negative", what,
                       count);
  if (count > 0 && list && !idx)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: index list is NULL",
                       what);
  if (!list && (first < 0 || first > s->n - count))
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "%s: range [%d, %d + %d) is not within [0, %d)", what,
                       first, first, count, s->n);
  for (int q = 0; list && q < count; q++)
    if (idx[q] < 0 || idx[q] >= s->n)
      return msocl__fail(MSOCL_ERR_BAD_INDEX,
                         "%s: index %d (entry %d) out of range [0, %d)", what,
                         idx[q], q, s->n);
  if (write)
    MSOCL__TRY(msocl__check_triples(what, "point", in, count, idx, first,
                                    MSOCL__COORD_MAX));
  if (count == 0)
    return MSOCL_OK;
  if (write && list)
    MSOCL__TRY(once_each(s, count, idx));
  int *k = malloc((size_t)count * sizeof *k);
  float *xyz = malloc(3 * (size_t)count * sizeof *xyz);
  int rc = k && xyz ? numbers(s, first, count, idx, k)
                    : msocl__fail(MSOCL_ERR_NO_MEMORY, "%s of %d points",
                                  what, count);
  if (rc == MSOCL_OK && write) {
    rc = msocl__check_write(s);
    memcpy(xyz, in, 3 * (size_t)count * sizeof *xyz);
  }
  for (int d = 0; rc == MSOCL_OK && d < s->nparts; d++) {
    msocl__engine *e = s->part[d];
    rc = copy_runs(e, velocities, write, k, count, xyz);
    if (rc == MSOCL_OK && write)
      msocl__planes_written(e);
  }
  if (rc == MSOCL_OK && !write)
    memcpy(out, xyz, 3 * (size_t)count * sizeof *xyz);
  free(k);
  free(xyz);
  return rc;
}

int msocl_sim_read_range(msocl_sim *s, int velocities, int first, int count,
                         float *xyz)
{
  return points_io(s, velocities, 0, 0, first, count, NULL, xyz, NULL);
}

int msocl_sim_write_range(msocl_sim *s, int velocities, int first, int count,
                          const float *xyz)
{
  return points_io(s, velocities, 1, 0, first, count, NULL, NULL, xyz);
}

int msocl_sim_read_list(msocl_sim *s, int velocities, int count,
                        const int *idx, float *xyz)
{
  return points_io(s, velocities, 0, 1, 0, count, idx, xyz, NULL);
}

int msocl_sim_write_list(msocl_sim *s, int velocities, int count,
                         const int *idx, const float *xyz)
{
  return points_io(s, velocities, 1, 1, 0, count, idx, NULL, xyz);
}

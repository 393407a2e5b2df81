/* A user's field on a running simulation: an acceleration or a force per
 * point, in the model's order (the engine's part: engine/field.c). */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdlib.h>

static int set(msocl_sim *s, const float *xyz, int forces)
{
  const char *what = forces ? "msocl_sim_set_forces" : "msocl_sim_set_accelerations";
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: sim is NULL", what);
  if (!xyz)
    return msocl__field_set(s->part[0], NULL, forces);
  if (s->nparts > 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "%s: a point field does not run on a simulation "
                       "split over %d devices",
                       what, s->nparts);
  MSOCL__TRY(msocl__check_triples(what, "point", xyz, s->n, NULL, 0,
                                  MSOCL__FORCE_MAX));
  if (!s->perm)
    return msocl__field_set(s->part[0], xyz, forces);
  float *own = malloc(3 * (size_t)s->n * sizeof *own);
  if (!own)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "%s: its copy", what);
  for (int k = 0; k < s->n; k++)
    for (int c = 0; c < 3; c++)
      own[3 * k + c] = xyz[3 * s->perm[k] + c];
  const int rc = msocl__field_set(s->part[0], own, forces);
  free(own);
  return rc;
}

int msocl_sim_set_accelerations(msocl_sim *s, const float *xyz)
{
  return set(s, xyz, 0);
}

int msocl_sim_set_forces(msocl_sim *s, const float *xyz)
{
  return set(s, xyz, 1);
}

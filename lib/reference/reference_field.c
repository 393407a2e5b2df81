/* A user's field in double, as engine/field.c: an acceleration per point
 * (a force divided by the point's mass) added to each free point's
 * velocity as dt a before the step. */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <stdlib.h>

static int set(msocl_reference *r, const float *xyz, int forces)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  if (!xyz) {
    free(r->field);
    r->field = NULL;
    return MSOCL_OK;
  }
  MSOCL__TRY(msocl__check_triples(forces ? "msocl_reference_set_forces"
                                         : "msocl_reference_set_accelerations",
                                  "point", xyz, r->n, NULL, 0,
                                  MSOCL__FORCE_MAX));
  if (!r->field && !(r->field = malloc(3 * (size_t)r->n * sizeof *r->field)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "the reference's field");
  for (int i = 0; i < 3 * r->n; i++)
    r->field[i] = forces ? xyz[i] * r->inv_mass[i / 3] : xyz[i];
  return MSOCL_OK;
}

int msocl_reference_set_accelerations(msocl_reference *r, const float *xyz)
{
  return set(r, xyz, 0);
}

int msocl_reference_set_forces(msocl_reference *r, const float *xyz)
{
  return set(r, xyz, 1);
}

void msocl__ref_field(msocl_reference *r)
{
  if (!r->field)
    return;
  for (int i = 0; i < r->n; i++)
    if (!r->pinned[i])
      for (int k = 0; k < 3; k++)
        r->vel[3 * i + k] += r->dt * r->field[3 * i + k];
}

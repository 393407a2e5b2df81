/* Wind on a running simulation (the engine's part: engine/wind.c). */
#include "config.h"
#include "sim.h"

int msocl_sim_set_wind(msocl_sim *s, const msocl_wind *w)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (!w)
    return msocl__wind_set(s->part[0], NULL, 0.0f, 0.0f);
  double kd, kl;
  MSOCL__TRY(msocl__wind_check(w, &kd, &kl));
  if (s->nparts > 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "wind does not run on a simulation split over %d "
                       "devices (a triangle's corners may lie in two parts)",
                       s->nparts);
  return msocl__wind_set(s->part[0], w->velocity, (float)kd, (float)kl);
}

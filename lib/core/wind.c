/* Wind's parameters: the defaults, and the checks both the simulation and
 * the reference make before taking them. */
#include "config.h"
#include "internal.h"

#include <math.h>

void msocl_wind_init(msocl_wind *w)
{
  if (!w)
    return;
  w->velocity[0] = w->velocity[1] = w->velocity[2] = 0.0f;
  w->density = 1.2f;
  w->drag = 1.2f;
  w->lift = 0.0f;
}

int msocl__wind_check(const msocl_wind *w, double *kd, double *kl)
{
  const float v[6] = {w->velocity[0], w->velocity[1], w->velocity[2],
                      w->density,     w->drag,        w->lift};
  for (int q = 0; q < 6; q++)
    if (!isfinite(v[q]))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "wind: %s is %g", q < 3 ? "a velocity component"
                         : q == 3 ? "the density" : q == 4 ? "drag" : "lift",
                         (double)v[q]);
  /* the force grows as the speed squared: that square within the limit */
  for (int q = 0; q < 3; q++)
    if (fabs(w->velocity[q]) > sqrt(MSOCL__FORCE_MAX))
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "wind: velocity component %g exceeds %g, whose "
                         "square is the force limit",
                         (double)w->velocity[q], sqrt(MSOCL__FORCE_MAX));
  if (w->density < 0 || w->drag < 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "wind: density %g and drag %g must be >= 0",
                       (double)w->density, (double)w->drag);
  *kd = 0.5 * w->density * w->drag;
  *kl = 0.5 * w->density * w->lift;
  return MSOCL_OK;
}

/* Wind in double, as kernels/wind.cl: each triangle's drag and lift from
 * the air's velocity relative to its corners' mean, a third to each
 * corner, as a velocity change before the step. */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <stdlib.h>

int msocl_reference_set_wind(msocl_reference *r, const msocl_wind *w)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  if (!w) {
    r->wind_on = 0;
    return MSOCL_OK;
  }
  MSOCL__TRY(msocl__wind_check(w, &r->wind_kd, &r->wind_kl));
  if (r->nt == 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "wind pushes on triangles, and the model has none");
  for (int e = 0; e < 3; e++)
    r->wind_air[e] = w->velocity[e];
  r->wind_on = 1;
  return MSOCL_OK;
}

void msocl__ref_wind(msocl_reference *r)
{
  if (!r->wind_on)
    return;
  double *f = r->tmp; /* 3n scratch the step's passes overwrite */
  for (int i = 0; i < 3 * r->n; i++)
    f[i] = 0.0;
  for (int t = 0; t < r->nt; t++) {
    const int *c = r->tri + 3 * t;
    const double *p0 = r->pos + 3 * c[0], *p1 = r->pos + 3 * c[1],
                 *p2 = r->pos + 3 * c[2];
    double e1[3], e2[3], u[3];
    for (int k = 0; k < 3; k++) {
      e1[k] = p1[k] - p0[k];
      e2[k] = p2[k] - p0[k];
      u[k] = r->wind_air[k] - (r->vel[3 * c[0] + k] + r->vel[3 * c[1] + k] +
                               r->vel[3 * c[2] + k]) / 3.0;
    }
    const double nrm[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                           e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
    /* with N = e1 x e2 = 2 A n: F = (kd |N.u| / 2 - l N.u) u + l |u|^2 N,
     * l = kl (N.u) / (2 |N| |u|), as the kernels */
    const double nn = msocl__dot3(nrm, nrm), uu = msocl__dot3(u, u);
    if (!(nn > 0) || !(uu > 0))
      continue;
    const double nu = msocl__dot3(nrm, u);
    const double l = 0.5 * r->wind_kl * nu / sqrt(nn * uu);
    const double a = 0.5 * r->wind_kd * fabs(nu) - l * nu, b = l * uu;
    for (int k = 0; k < 3; k++) {
      const double fk = (a * u[k] + b * nrm[k]) / 3.0;
      for (int q = 0; q < 3; q++)
        f[3 * c[q] + k] += fk;
    }
  }
  for (int i = 0; i < r->n; i++)
    if (!r->pinned[i])
      for (int k = 0; k < 3; k++)
        r->vel[3 * i + k] += r->dt * r->inv_mass[i] * f[3 * i + k];
}

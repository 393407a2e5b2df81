/* The capsule's and the oriented box's gap in double, formula for formula
 * as msocl_planes_gap (kernels/planes.cl). */
#include "config.h"
#include "reference_state.h"

#include <math.h>

double msocl__ref_capsule_gap(const struct msocl__collider *k, const double *p,
                              double *n)
{
  double e[3], a[3], d[3];
  for (int c = 0; c < 3; c++) {
    e[c] = (double)k->x[c] - k->p[c];
    a[c] = p[c] - k->p[c];
  }
  double ee = msocl__dot3(e, e);
  double t = ee > 0 ? msocl__dot3(a, e) / ee : 0.0;
  t = fmin(fmax(t, 0.0), 1.0);
  for (int c = 0; c < 3; c++)
    d[c] = a[c] - t * e[c];
  double len = sqrt(msocl__dot3(d, d));
  if (len > 0)
    for (int c = 0; c < 3; c++)
      n[c] = d[c] / len;
  return len - k->p[3];
}

/* v turned by the unit quaternion u = (x, y, z), w. */
static void qrot(const double *u, double w, const double *v, double *o)
{
  double c[3] = {u[1] * v[2] - u[2] * v[1] + w * v[0],
                 u[2] * v[0] - u[0] * v[2] + w * v[1],
                 u[0] * v[1] - u[1] * v[0] + w * v[2]};
  o[0] = v[0] + 2 * (u[1] * c[2] - u[2] * c[1]);
  o[1] = v[1] + 2 * (u[2] * c[0] - u[0] * c[2]);
  o[2] = v[2] + 2 * (u[0] * c[1] - u[1] * c[0]);
}

double msocl__ref_box_gap(const struct msocl__collider *k, const double *p,
                          double *n)
{
  const double u[3] = {k->x[0], k->x[1], k->x[2]},
               inv[3] = {-u[0], -u[1], -u[2]}, w = k->x[3];
  double r[3] = {p[0] - k->p[0], p[1] - k->p[1], p[2] - k->p[2]}, l[3],
         d[3], o[3], m[3] = {0, 0, 0};
  qrot(inv, w, r, l);
  for (int c = 0; c < 3; c++) {
    d[c] = fabs(l[c]) - k->x[4 + c];
    o[c] = fmax(d[c], 0.0);
  }
  double olen = sqrt(msocl__dot3(o, o)), g;
  if (olen > 0) {
    for (int c = 0; c < 3; c++)
      m[c] = (l[c] < 0 ? -1 : 1) * o[c] / olen;
    g = olen;
  } else {
    int a = d[0] >= d[1] && d[0] >= d[2] ? 0 : d[1] >= d[2] ? 1 : 2;
    m[a] = l[a] < 0 ? -1 : 1;
    g = d[a];
  }
  qrot(u, w, m, n);
  return g;
}

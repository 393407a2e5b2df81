/* The host reference's per-point physics, shared by its explicit and
 * implicit steps: spring and dashpot forces, collision response and
 * projection, formula for formula as kernels/planes.h. */
#include "config.h"
#include "reference_state.h"

#include <math.h>

/* msocl_planes_gap() and the response of msocl_planes_collide()
 * (kernels/planes.cl). */
static double gap(const struct msocl__collider *k, const double *p, double *n)
{
  n[0] = 0.0; n[1] = 1.0; n[2] = 0.0;
  if (k->kind == 0) /* disabled */
    return INFINITY;
  if (k->kind == MSOCL__PLANE) {
    for (int d = 0; d < 3; d++)
      n[d] = k->p[d];
    return n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - k->p[3];
  }
  if (k->kind == MSOCL__SPHERE) {
    double d[3] = {p[0] - k->p[0], p[1] - k->p[1], p[2] - k->p[2]};
    double len = sqrt(msocl__dot3(d, d));
    if (len > 0)
      for (int e = 0; e < 3; e++)
        n[e] = d[e] / len;
    return len - k->p[3];
  }
  if (k->kind == MSOCL__CAPSULE)
    return msocl__ref_capsule_gap(k, p, n);
  if (k->kind == MSOCL__BOX)
    return msocl__ref_box_gap(k, p, n);
  double dx = p[0] - k->p[0], dz = p[2] - k->p[2];
  double rr = sqrt(dx * dx + dz * dz), gside = rr - k->p[3],
         gtop = p[1] - k->p[1];
  if (gtop >= gside || !(rr > 0))
    return gtop;
  n[0] = dx / rr;
  n[1] = 0.0;
  n[2] = dz / rr;
  return gside;
}

void msocl__ref_collide(const msocl_reference *r, const double *p, double *v,
                        double fscale)
{
  for (int c = 0; c < r->ncol; c++) {
    /* on the velocity relative to a moving collider's surface */
    double u[3], w[3];
    msocl__ref_surface(r, c, p, u);
    for (int e = 0; e < 3; e++)
      w[e] = v[e] - u[e];
    double n[3], g = gap(&r->col[c], p, n), vn = msocl__dot3(w, n),
                 lim = -g / r->dt, fr = fscale * r->col[c].friction;
    if (vn < lim) {
      for (int e = 0; e < 3; e++)
        w[e] += (lim - vn) * n[e];
      for (int e = 0; e < 3; e++)
        v[e] = w[e] - fr * (w[e] - lim * n[e]) + u[e];
    }
  }
}

/* msocl_planes_project() of kernels/planes.cl; a moving collider's gap at the step's
 * end is its gap at p - dt u, to first order (kernels/planes.cl). */
void msocl__ref_project(const msocl_reference *r, double *p, double *v)
{
  for (int c = 0; c < r->ncol; c++) {
    double u[3], q[3];
    msocl__ref_surface(r, c, p, u);
    for (int e = 0; e < 3; e++)
      q[e] = p[e] - r->dt * u[e];
    double n[3], g = gap(&r->col[c], q, n);
    if (g < 0) {
      for (int e = 0; e < 3; e++)
        p[e] -= g * n[e];
      double w[3];
      for (int e = 0; e < 3; e++)
        w[e] = v[e] - u[e];
      double vn = msocl__dot3(w, n);
      if (vn < 0) {
        for (int e = 0; e < 3; e++)
          w[e] -= vn * n[e];
        for (int e = 0; e < 3; e++)
          v[e] = w[e] - r->col[c].friction * w[e] + u[e];
      }
    }
  }
}

/* Internal and viscous force on point i at state (pos, vel). */
void msocl__ref_force(const msocl_reference *r, const double *pos,
                      const double *vel, int i, double *f)
{
  const double *p = pos + 3 * i, *v = vel + 3 * i;
  f[0] = f[1] = f[2] = 0.0;
  for (int t = r->adj.off[i]; t < r->adj.off[i + 1]; t++) {
    int j = r->adj.other[t], sp = r->adj.spring[t];
    const double *q = pos + 3 * j, *vq = vel + 3 * j;
    double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    double len2 = msocl__dot3(d, d), len = sqrt(len2);
    if (!(len > 0))
      continue;
    double s = r->k[sp] * (len - r->rest[sp]) / len;
    double dv[3] = {vq[0] - v[0], vq[1] - v[1], vq[2] - v[2]};
    double c = r->damp[sp] * msocl__dot3(dv, d) / len2;
    for (int e = 0; e < 3; e++)
      f[e] += (s + c) * d[e];
  }
  for (int e = 0; e < 3; e++)
    f[e] -= r->viscous * v[e];
}

/* The device step, redone on the host in double precision: the yardstick
 * that tests and benchmarks measure the kernels' accuracy against. It
 * follows kernels/step.cl formula for formula. */
#include "config.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct msocl_reference {
  int n;
  double dt;
  double *pos, *vel, *vnew, *inv_mass;
  unsigned char *pinned;
  double gravity[3], viscous;
  int ncol;
  struct msocl__collider col[MSOCL__MAX_COLLIDERS];
  struct msocl__adjacency adj;
  const double *k, *rest, *damp; /* per spring, owned below */
  double *spring_data;
};

static double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* msocl_respond() of step.cl. */
static void respond(double *v, double g, const double *n, double friction,
                    double dt)
{
  double vn = dot3(v, n), lim = -g / dt;
  if (vn < lim) {
    for (int c = 0; c < 3; c++)
      v[c] += (lim - vn) * n[c];
    for (int c = 0; c < 3; c++)
      v[c] -= friction * (v[c] - lim * n[c]);
  }
}

static void collide(const msocl_reference *r, const double *p, double *v)
{
  for (int c = 0; c < r->ncol; c++) {
    const struct msocl__collider *k = &r->col[c];
    double n[3] = {0, 1, 0}, g;
    if (k->kind == MSOCL__PLANE) {
      for (int d = 0; d < 3; d++)
        n[d] = k->p[d];
      g = dot3(n, p) - k->p[3];
    } else if (k->kind == MSOCL__SPHERE) {
      double d[3] = {p[0] - k->p[0], p[1] - k->p[1], p[2] - k->p[2]};
      double len = sqrt(dot3(d, d));
      if (len > 0)
        for (int e = 0; e < 3; e++)
          n[e] = d[e] / len;
      g = len - k->p[3];
    } else {
      double dx = p[0] - k->p[0], dz = p[2] - k->p[2];
      double rr = sqrt(dx * dx + dz * dz);
      double gside = rr - k->p[3], gtop = p[1] - k->p[1];
      if (gtop >= gside || !(rr > 0)) {
        g = gtop;
      } else {
        g = gside;
        n[0] = dx / rr;
        n[1] = 0;
        n[2] = dz / rr;
      }
    }
    respond(v, g, n, k->friction, r->dt);
  }
}

static void velocity_pass(msocl_reference *r)
{
  for (int i = 0; i < r->n; i++) {
    double *vo = r->vnew + 3 * i;
    if (r->pinned[i]) {
      vo[0] = vo[1] = vo[2] = 0;
      continue;
    }
    const double *p = r->pos + 3 * i, *v = r->vel + 3 * i;
    double f[3] = {0, 0, 0};
    for (int t = r->adj.off[i]; t < r->adj.off[i + 1]; t++) {
      int j = r->adj.other[t], sp = r->adj.spring[t];
      const double *q = r->pos + 3 * j, *vq = r->vel + 3 * j;
      double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      double len2 = dot3(d, d), len = sqrt(len2);
      if (!(len > 0))
        continue;
      double s = r->k[sp] * (len - r->rest[sp]) / len;
      double dv[3] = {vq[0] - v[0], vq[1] - v[1], vq[2] - v[2]};
      double c = r->damp ? r->damp[sp] * dot3(dv, d) / len2 : 0.0;
      for (int e = 0; e < 3; e++)
        f[e] += (s + c) * d[e];
    }
    for (int e = 0; e < 3; e++)
      vo[e] = v[e] + r->dt * ((f[e] - r->viscous * v[e]) * r->inv_mass[i] +
                              r->gravity[e]);
    collide(r, p, vo);
  }
}

static void position_pass(msocl_reference *r)
{
  for (int i = 0; i < r->n; i++)
    if (!r->pinned[i])
      for (int e = 0; e < 3; e++)
        r->pos[3 * i + e] += r->dt * r->vnew[3 * i + e];
  double *t = r->vel;
  r->vel = r->vnew;
  r->vnew = t;
}

int msocl_reference_create(msocl_reference **out, const msocl_model *m,
                           double dt)
{
  msocl__clear_error();
  if (!out)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference out-pointer is NULL");
  *out = NULL;
  int rc = msocl_model_validate(m);
  if (rc != MSOCL_OK)
    return rc;
  if (!isfinite(dt))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "time step dt is %g", dt);
  if (!(dt > 0))
    return msocl__fail(MSOCL_ERR_BAD_DT, "time step dt = %g must be > 0", dt);
  msocl_reference *r = calloc(1, sizeof *r);
  if (!r)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "reference");
  const size_t n = (size_t)m->n, ns = (size_t)m->ns;
  r->n = m->n;
  r->dt = dt;
  r->pos = malloc(3 * n * sizeof(double));
  r->vel = calloc(3 * n, sizeof(double));
  r->vnew = calloc(3 * n, sizeof(double));
  r->inv_mass = malloc(n * sizeof(double));
  r->pinned = malloc(n);
  r->spring_data = malloc((3 * ns + 1) * sizeof(double));
  if (!r->pos || !r->vel || !r->vnew || !r->inv_mass || !r->pinned ||
      !r->spring_data) {
    msocl_reference_destroy(r);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "reference state");
  }
  rc = msocl__adjacency_build(m, &r->adj);
  if (rc != MSOCL_OK) {
    msocl_reference_destroy(r);
    return rc;
  }
  for (size_t i = 0; i < 3 * n; i++)
    r->pos[i] = m->pos[i];
  for (size_t i = 0; i < n; i++)
    r->inv_mass[i] = 1.0 / m->mass[i];
  memcpy(r->pinned, m->pinned, n);
  double *k = r->spring_data, *rest = k + ns, *damp = rest + ns;
  for (size_t s = 0; s < ns; s++) {
    k[s] = m->k[s];
    rest[s] = m->rest[s];
    damp[s] = m->damp ? m->damp[s] : 0.0;
  }
  r->k = k;
  r->rest = rest;
  r->damp = m->damp ? damp : NULL;
  for (int e = 0; e < 3; e++)
    r->gravity[e] = m->gravity[e];
  r->viscous = m->viscous;
  r->ncol = m->ncol;
  memcpy(r->col, m->col, sizeof r->col);
  *out = r;
  return MSOCL_OK;
}

void msocl_reference_destroy(msocl_reference *r)
{
  if (!r)
    return;
  msocl__adjacency_free(&r->adj);
  free(r->pos);
  free(r->vel);
  free(r->vnew);
  free(r->inv_mass);
  free(r->pinned);
  free(r->spring_data);
  free(r);
}

int msocl_reference_step(msocl_reference *r, int n)
{
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  if (n < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "step count %d is negative", n);
  for (int k = 0; k < n; k++) {
    velocity_pass(r);
    position_pass(r);
  }
  return MSOCL_OK;
}

int msocl_reference_positions(const msocl_reference *r, double *xyz)
{
  if (!r || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference or array is NULL");
  memcpy(xyz, r->pos, 3 * (size_t)r->n * sizeof(double));
  return MSOCL_OK;
}

int msocl_reference_velocities(const msocl_reference *r, double *xyz)
{
  if (!r || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference or array is NULL");
  memcpy(xyz, r->vel, 3 * (size_t)r->n * sizeof(double));
  return MSOCL_OK;
}

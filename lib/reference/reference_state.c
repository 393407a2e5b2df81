/* Creating the host reference from a model, and reading its state. */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int msocl_reference_create(msocl_reference **out, const msocl_model *m,
                           const msocl_sim_options *opts)
{
  msocl__clear_error();
  if (!out)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference out-pointer is NULL");
  *out = NULL;
  int rc = msocl_model_validate(m);
  if (rc != MSOCL_OK)
    return rc;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  if (opts)
    o = *opts;
  /* the simulation's checks of the physics it shares */
  MSOCL__TRY(msocl__check_physics(&o));
  msocl_reference *r = calloc(1, sizeof *r);
  if (!r)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "reference");
  const size_t n = (size_t)m->n, ns = (size_t)m->ns, n3 = 3 * n;
  r->o = o;
  r->n = m->n;
  r->dt = o.dt;
  double **vecs[] = {&r->pos,        &r->vel,        &r->pnew,  &r->vnew,
                     &r->a,          &r->acc,        &r->tmp,   &r->sum_p,
                     &r->sum_v,      &r->stage_p[0], &r->stage_p[1],
                     &r->stage_v[0], &r->stage_v[1]};
  int ok = 1;
  for (size_t q = 0; q < sizeof vecs / sizeof vecs[0]; q++)
    ok &= (*vecs[q] = calloc(n3, sizeof(double))) != NULL;
  r->inv_mass = malloc(n * sizeof(double));
  r->mass = malloc(n * sizeof(double));
  r->pinned = malloc(n);
  r->k = malloc((ns + 1) * sizeof(double));
  r->rest = malloc((ns + 1) * sizeof(double));
  r->damp = malloc((ns + 1) * sizeof(double));
  if (!ok || !r->inv_mass || !r->mass || !r->pinned || !r->k || !r->rest ||
      !r->damp) {
    msocl_reference_destroy(r);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "reference state");
  }
  rc = msocl__adjacency_build(m, &r->adj);
  if (rc != MSOCL_OK) {
    msocl_reference_destroy(r);
    return rc;
  }
  for (size_t i = 0; i < n3; i++)
    r->pos[i] = m->pos[i];
  for (size_t i = 0; i < n; i++) {
    r->mass[i] = m->mass[i];
    r->inv_mass[i] = 1.0 / m->mass[i];
  }
  memcpy(r->pinned, m->pinned, n);
  for (size_t s = 0; s < ns; s++) {
    r->k[s] = m->k[s];
    r->rest[s] = m->rest[s];
    r->damp[s] = m->damp ? m->damp[s] : 0.0;
  }
  for (int e = 0; e < 3; e++)
    r->gravity[e] = m->gravity[e];
  r->viscous = m->viscous;
  r->air = m->air;
  r->ncol = m->ncol;
  memcpy(r->col, m->col, sizeof r->col);
  msocl__ref_colliders_init(r);
  r->nt = m->nt;
  r->tri = malloc((3 * (size_t)m->nt + 1) * sizeof *r->tri);
  if (!r->tri) {
    msocl_reference_destroy(r);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "reference triangles");
  }
  if (m->nt > 0) /* a model without triangles has no array */
    memcpy(r->tri, m->tri, 3 * (size_t)m->nt * sizeof *r->tri);
  *out = r;
  return MSOCL_OK;
}

void msocl_reference_destroy(msocl_reference *r)
{
  if (!r)
    return;
  msocl__adjacency_free(&r->adj);
  double *vecs[] = {r->pos,        r->vel,        r->pnew,       r->vnew,
                    r->a,          r->acc,        r->tmp,        r->sum_p,
                    r->sum_v,      r->stage_p[0], r->stage_p[1], r->stage_v[0],
                    r->stage_v[1], r->inv_mass,   r->mass,       r->k,
                    r->rest,       r->damp,       r->field};
  for (size_t q = 0; q < sizeof vecs / sizeof vecs[0]; q++)
    free(vecs[q]);
  free(r->pinned);
  free(r->tri);
  msocl__ref_controls_free(r);
  msocl__ref_soft_pins_free(r);
  free(r);
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

/* As kernels/energy.cl: each spring's k (l - r)^2 / 2, kinetic m v^2 / 2,
 * gravitational -m g.p. */
int msocl_reference_energy(const msocl_reference *r, msocl_energy *e)
{
  if (!r || !e)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference or out is NULL");
  e->kinetic = e->spring = e->gravity = 0.0;
  for (int i = 0; i < r->n; i++) {
    const double *p = r->pos + 3 * i, *v = r->vel + 3 * i;
    e->kinetic += 0.5 * r->mass[i] * msocl__dot3(v, v);
    e->gravity -= r->mass[i] * msocl__dot3(r->gravity, p);
    for (int t = r->adj.off[i]; t < r->adj.off[i + 1]; t++) {
      const double *q = r->pos + 3 * r->adj.other[t];
      double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      double s = sqrt(msocl__dot3(d, d)) - r->rest[r->adj.spring[t]];
      e->spring += 0.25 * r->k[r->adj.spring[t]] * s * s;
    }
  }
  e->total = e->kinetic + e->spring + e->gravity;
  return MSOCL_OK;
}

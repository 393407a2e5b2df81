/* Mesh colliders on a running simulation (the engine's part:
 * engine/mesh_collider.c): each acts after every step of every call while
 * enabled, moving over a call toward the vertices set for it (motion.c
 * runs such a call step by step). */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int msocl__meshes_create(msocl_sim *s, const msocl_model *m)
{
  if (m->nmesh == 0)
    return MSOCL_OK;
  if (s->nparts > 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "mesh colliders need one device (this simulation is "
                       "split over %d)", s->nparts);
  s->mesh = calloc((size_t)m->nmesh, sizeof *s->mesh);
  s->mesh_on = malloc((size_t)m->nmesh);
  if (!s->mesh || !s->mesh_on)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "mesh colliders");
  s->nmesh = m->nmesh;
  for (int c = 0; c < m->nmesh; c++) {
    s->mesh_on[c] = 1;
    MSOCL__TRY(msocl__mesh_create(s->part[0], &m->mesh[c], &s->mesh[c]));
  }
  return MSOCL_OK;
}

void msocl__meshes_free(msocl_sim *s)
{
  for (int c = 0; c < s->nmesh; c++)
    msocl__mesh_free(s->mesh[c]);
  free(s->mesh);
  free(s->mesh_on);
}

/* Any collider: an enabled one acts, a disabled one may still move. */
int msocl__meshes_active(const msocl_sim *s)
{
  return s->nmesh > 0;
}

int msocl__meshes_begin(msocl_sim *s, int n)
{
  for (int c = 0; c < s->nmesh; c++)
    MSOCL__TRY(msocl__mesh_begin(s->part[0], s->mesh[c], n));
  return MSOCL_OK;
}

int msocl__meshes_step(msocl_sim *s, float f0, float f1)
{
  for (int c = 0; c < s->nmesh; c++)
    if (s->mesh_on[c])
      MSOCL__TRY(msocl__mesh_pass(s->part[0], s->mesh[c], f0, f1));
  return MSOCL_OK;
}

int msocl__meshes_end(msocl_sim *s)
{
  int rc = MSOCL_OK;
  for (int c = 0; c < s->nmesh; c++) { /* each ends its call, even on error */
    const int e = msocl__mesh_end(s->part[0], s->mesh[c]);
    rc = rc == MSOCL_OK ? e : rc;
  }
  return rc;
}

static int known(const msocl_sim *s, int id)
{
  if (s->nmesh == 0)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "mesh collider %d: the simulation has none (its "
                       "model added no mesh collider)",
                       id);
  if (id < 0 || id >= s->nmesh)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "mesh collider %d: the simulation has %d (ids 0 to "
                       "%d)",
                       id, s->nmesh, s->nmesh - 1);
  return MSOCL_OK;
}

int msocl_sim_set_mesh_collider_vertices(msocl_sim *s, int id,
                                         const float *verts)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  MSOCL__TRY(known(s, id));
  if (!verts)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "mesh collider %d: verts is NULL", id);
  const int nv = msocl__mesh_nv(s->mesh[id]);
  char what[48];
  snprintf(what, sizeof what, "mesh collider %d", id);
  MSOCL__TRY(msocl__check_triples(what, "vertex", verts, nv, NULL, 0,
                                  MSOCL__COORD_MAX));
  msocl__mesh_vertices(s->mesh[id], verts);
  return MSOCL_OK;
}

int msocl_sim_enable_mesh_collider(msocl_sim *s, int id, int on)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  MSOCL__TRY(known(s, id));
  s->mesh_on[id] = on != 0;
  return MSOCL_OK;
}

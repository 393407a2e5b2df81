/* Triangle-mesh colliders on a model: a copy of the caller's vertices and
 * triangles, checked, with a thickness and a friction (from an OBJ file:
 * io/mesh_collider_obj.c). The simulation (sim/sim_mesh.c,
 * engine/mesh_collider.c) keeps its own moving copy. */
#include "internal.h"
#include "mesh_area.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void msocl__mesh_colliders_free(msocl_model *m)
{
  for (int c = 0; c < m->nmesh; c++) {
    free(m->mesh[c].verts);
    free(m->mesh[c].tris);
  }
  free(m->mesh);
  m->mesh = NULL;
  m->nmesh = 0;
}

static int check(const msocl_model *m, const float *verts, int nverts,
                 const int *tris, int ntris, float thickness, float friction)
{
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "mesh collider: model is NULL");
  if (!verts || !tris)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "mesh collider: %s is NULL", verts ? "tris" : "verts");
  if (nverts < 3 || ntris < 1)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "mesh collider: %d vertices and %d triangles (at "
                       "least 3 and 1)", nverts, ntris);
  if (nverts > (1 << 26) || ntris > (1 << 26))
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "mesh collider: %d vertices, %d triangles (at most "
                       "%d each)", nverts, ntris, 1 << 26);
  if (!isfinite(thickness) || !(thickness > 0))
    return msocl__fail(isfinite(thickness) ? MSOCL_ERR_BAD_VALUE
                                           : MSOCL_ERR_NOT_FINITE,
                       "mesh collider: thickness %g must be finite and > 0",
                       (double)thickness);
  if (!isfinite(friction) || friction < 0 || friction > 1)
    return msocl__fail(isfinite(friction) ? MSOCL_ERR_BAD_VALUE
                                          : MSOCL_ERR_NOT_FINITE,
                       "mesh collider: friction %g is outside [0, 1]",
                       (double)friction);
  MSOCL__TRY(msocl__check_triples("mesh collider", "vertex", verts, nverts,
                                  NULL, 0, MSOCL__COORD_MAX));
  int real = 0;
  for (int t = 0; t < ntris; t++) {
    const int *k = tris + 3 * (size_t)t;
    for (int c = 0; c < 3; c++)
      if (k[c] < 0 || k[c] >= nverts)
        return msocl__fail(MSOCL_ERR_BAD_INDEX,
                           "mesh collider: triangle %d's corner %d is "
                           "vertex %d, outside [0, %d)", t, c, k[c], nverts);
    real += k[0] != k[1] && k[1] != k[2] && k[0] != k[2] &&
            msocl__tri_has_area(verts, k);
  }
  if (real == 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "mesh collider: all %d triangles are degenerate "
                       "(no area)", ntris);
  return MSOCL_OK;
}

int msocl_model_add_mesh_collider(msocl_model *m, const float *verts,
                                  int nverts, const int *tris, int ntris,
                                  float thickness, float friction)
{
  msocl__clear_error();
  MSOCL__TRY(check(m, verts, nverts, tris, ntris, thickness, friction));
  MSOCL__TRY(msocl__live_refuse(m, "msocl_model_add_mesh_collider",
                                "msocl_sim_set_mesh_collider_vertices or "
                                "msocl_sim_enable_mesh_collider"));
  if (m->nmesh >= MSOCL_MAX_MESH_COLLIDERS)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "mesh collider: the model has %d already (at most %d)",
                       m->nmesh, MSOCL_MAX_MESH_COLLIDERS);
  struct msocl__mesh_collider c = {nverts, ntris, NULL, NULL, thickness,
                                   friction};
  c.verts = malloc(3 * (size_t)nverts * sizeof *c.verts);
  c.tris = malloc(3 * (size_t)ntris * sizeof *c.tris);
  struct msocl__mesh_collider *grown =
      realloc(m->mesh, ((size_t)m->nmesh + 1) * sizeof *grown);
  if (grown)
    m->mesh = grown;
  if (!c.verts || !c.tris || !grown) {
    free(c.verts);
    free(c.tris);
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "mesh collider of %d vertices and %d triangles",
                       nverts, ntris);
  }
  memcpy(c.verts, verts, 3 * (size_t)nverts * sizeof *c.verts);
  memcpy(c.tris, tris, 3 * (size_t)ntris * sizeof *c.tris);
  m->mesh[m->nmesh++] = c;
  return MSOCL_OK;
}

/* The one test of whether a mesh collider's triangle counts, shared by the
 * model's check (lib/model/mesh_collider.c) and the engine's copy
 * (lib/engine/mesh_collider.c), so the engine keeps exactly the triangles
 * the check found and never one the check would call degenerate. */
#ifndef MSOCL_MESH_AREA_H
#define MSOCL_MESH_AREA_H

/* Whether triangle t (3 corner indices into v, 3 floats a vertex) has an
 * area float coordinates can see: relative to its edges, since the
 * kernels' normal is a float cross product of them, which a sliver with
 * a merely non-zero area in double turns into noise. */
static inline int msocl__tri_has_area(const float *v, const int *t)
{
  double e1[3], e2[3];
  for (int k = 0; k < 3; k++) {
    e1[k] = (double)v[3 * t[1] + k] - v[3 * t[0] + k];
    e2[k] = (double)v[3 * t[2] + k] - v[3 * t[0] + k];
  }
  const double nx = e1[1] * e2[2] - e1[2] * e2[1],
               ny = e1[2] * e2[0] - e1[0] * e2[2],
               nz = e1[0] * e2[1] - e1[1] * e2[0];
  const double n2 = nx * nx + ny * ny + nz * nz;
  const double l2 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2] +
                    e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  return n2 > 1e-12 * l2 * l2 && n2 > 0;
}

#endif

/* Vertex normals on the device: each point sums the area-weighted normals
 * of the triangles around it (a CSR list of the two other corners of
 * each, as where they sit in a plane) and normalises, from the positions'
 * planes into three floats a point. Points on no triangle get (0, 0, 0). */
#include "planes.h"

/* Run over the planes' range, as the steps: point
 * i = (z ny + y) nx + x of an nx-wide grid (BUFFER: nx = n, one row) at a
 * in a plane, ny the range's second size - no division a point. */
__kernel void msocl_normals(__global const float *p,
                            __global const int *tri_off,
                            __global const int2 *tri_ab,
                            __global float *normal, int n, int nx, int pitch,
                            int slab, int plane)
{
  MSOCL_PLANES_XYZ;
  const int i = (z * (int)get_global_size(1) + y) * nx + x;
  if (x >= nx || i >= n)
    return;
  (void)pitch; (void)slab;
  __global const float *py = p + plane, *pz = py + plane;
  const int a = MSOCL_PLANES_AT(x, y, z);
  const float qx = p[a], qy = py[a], qz = pz[a];
  float sx = 0.0f, sy = 0.0f, sz = 0.0f;
  for (int t = tri_off[i]; t < tri_off[i + 1]; t++) {
    const int2 bc = tri_ab[t];
    const float ux = p[bc.x] - qx, uy = py[bc.x] - qy, uz = pz[bc.x] - qz;
    const float vx = p[bc.y] - qx, vy = py[bc.y] - qy, vz = pz[bc.y] - qz;
    sx += uy * vz - uz * vy;
    sy += uz * vx - ux * vz;
    sz += ux * vy - uy * vx;
  }
  const float len = sqrt(sx * sx + sy * sy + sz * sz);
  const int on = len > 0.0f;
  normal[3 * i] = on ? sx / len : 0.0f;
  normal[3 * i + 1] = on ? sy / len : 0.0f;
  normal[3 * i + 2] = on ? sz / len : 0.0f;
}

/* Vertex normals on the device: each point sums the area-weighted normals
 * of the triangles around it (a CSR list of the two other corners of each)
 * and normalises. Points on no triangle get (0, 0, 0). */
#include "common.h"

__kernel void msocl_normals(__global const float4 *pos,
                            __global const int *tri_off,
                            __global const int2 *tri_ab,
                            __global float4 *normal, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float3 p = pos[i].xyz;
  float3 acc = (float3)(0.0f);
  for (int t = tri_off[i]; t < tri_off[i + 1]; t++) {
    int2 ab = tri_ab[t];
    acc += cross(pos[ab.x].xyz - p, pos[ab.y].xyz - p);
  }
  float len = length(acc);
  normal[i] = len > 0.0f ? (float4)(acc / len, 0.0f) : (float4)(0.0f);
}

/* A user's field of external accelerations (lib/engine/field.c): before
 * each step, each point's velocity gains dt times its acceleration, a
 * pinned point nothing. acc holds three planes laid out as the state's,
 * their padding zero. */
#include "planes.h"
#if defined(MSOCL_PLANES)

__kernel void msocl_field_kick(__global float *v, __global const float *aux,
                               __global const float *acc, float dt, int nx,
                               int pitch, int slab, int plane, int n)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)nx; (void)slab; (void)n;
  const float s = MSOCL_PLANES_PINNED(aux[plane + a]) ? 0.0f : dt;
  v[a] += s * acc[a];
  v[plane + a] = fma(s, acc[plane + a], v[plane + a]);
  v[2 * plane + a] += acc[2 * plane + a] * s;
}

#endif

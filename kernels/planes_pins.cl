/* Pins moving toward targets (lib/sim/sim_controls.c), in planes: pin i
 * of m, at at[i] in each plane, placed at its path's point fp and given
 * the velocity that moves it from the path's point f0 to f1 in a step
 * (the springs' dashpots feel it), the path running from start (copied
 * from p first when `capture`) to target as (1 - f) start + f target,
 * which is start at f = 0 and target at f = 1 exactly. */
#include "common.h"
#if defined(MSOCL_PLANES)
__kernel void msocl_planes_pins(__global float *p, __global float *v,
                                __global const int *at,
                                __global float *start,
                                __global const float *target, int m,
                                int plane, float fp, float f0, float f1,
                                float dt, int capture)
{
  const int i = get_global_id(0);
  if (i >= m)
    return;
  const int a = at[i];
  for (int q = 0; q < 3; q++) {
    const float s = capture ? p[q * plane + a] : start[3 * i + q];
    if (capture)
      start[3 * i + q] = s;
    const float t = target[3 * i + q];
    const float x0 = (1.0f - f0) * s + f0 * t, x1 = (1.0f - f1) * s + f1 * t;
    p[q * plane + a] = (1.0f - fp) * s + fp * t;
    v[q * plane + a] = MSOCL_DIV(x1 - x0, dt);
  }
}
#endif

/* Soft pins (lib/engine/soft_pins.c), before each step: pin i of m, at
 * at[i] in each plane, is pulled toward its anchor (1 - f) from + f to by
 * a spring of stiffness k, as the velocity change dt k (anchor - p) / m
 * (dtk = dt k; aux holds the inverse masses). */
#if defined(MSOCL_PLANES)
__kernel void msocl_soft_pins(__global const float *p, __global float *v,
                              __global const float *aux,
                              __global const int *at,
                              __global const float *from,
                              __global const float *to, int m, int plane,
                              float f, float dtk)
{
  const int i = get_global_id(0);
  if (i >= m)
    return;
  const int a = at[i];
  const float s = dtk * aux[a];
  for (int q = 0; q < 3; q++) {
    const float anchor = (1.0f - f) * from[3 * i + q] + f * to[3 * i + q];
    v[q * plane + a] += s * (anchor - p[q * plane + a]);
  }
}
#endif

/* Wind on the model's triangles in the planes engine (lib/engine/wind.c):
 * before each step, each triangle's aerodynamic force from the air's
 * velocity relative to the triangle's (its corners' mean), a third of it
 * to each corner, as a velocity change dt f / m. The model follows
 * NvCloth's: drag along the relative wind, proportional to |cos| of the
 * angle between it and the normal, lift across it, to cos sin; both to
 * the area and the relative speed squared. One kernel a triangle (no loop
 * inside, so PoCL vectorises it), one a point summing its corners in the
 * order the triangles were added, so every layout gets the same bits;
 * planes_rows.cl takes the same arithmetic (wind.h) into its sweep. */
#include "planes.h"
#include "wind.h"

#if defined(MSOCL_PLANES)

#define MSOCL_WIND_SEL1(c, a, b) ((c) ? (a) : (b))

/* MSOCL_WIND_FORCE for the corners at tx, ty, tz of the planes (q floats a
 * plane). */
static inline void msocl_wind_third(__global const float *p,
                                    __global const float *v, int q, int tx,
                                    int ty, int tz, float4 air, float4 coef,
                                    float *fx, float *fy, float *fz)
{
  MSOCL_WIND_FORCE(float, MSOCL_WIND_SEL1, w_, p[ty] - p[tx],
                   p[q + ty] - p[q + tx], p[2 * q + ty] - p[2 * q + tx],
                   p[tz] - p[tx], p[q + tz] - p[q + tx],
                   p[2 * q + tz] - p[2 * q + tx], v[tx] + v[ty] + v[tz],
                   v[q + tx] + v[q + ty] + v[q + tz],
                   v[2 * q + tx] + v[2 * q + ty] + v[2 * q + tz], air, coef,
                   gx, gy, gz);
  *fx = gx;
  *fy = gy;
  *fz = gz;
}

/* A third of the force on triangle k (its corners at tri[k],
 * tri[ntri + k], tri[2 ntri + k] of the planes: ints, as an int4 would
 * keep PoCL from vectorising), into plane `c` of `third` at triangle
 * index k (three planes of `ntri` floats). */
__kernel void msocl_wind_triangles(__global const float *p,
                                   __global const float *v,
                                   __global const int *tri,
                                   __global float *third, float4 air,
                                   float4 coef, int plane, int ntri,
                                   int nreal)
{
  /* past nreal, triangles with every corner at 0 up to ntri, whose
   * force is selected away (the padding they read holds anything): no
   * branch */
  const int k = get_global_id(0);
  const bool real = k < nreal;
  float fx, fy, fz;
  msocl_wind_third(p, v, plane, tri[k], tri[ntri + k], tri[2 * ntri + k],
                   air, coef, &fx, &fy, &fz);
  third[k] = real ? fx : 0.0f;
  third[ntri + k] = real ? fy : 0.0f;
  third[2 * ntri + k] = real ? fz : 0.0f;
}

/* The corners' sum f into the point's velocity at a: dt f / m, nothing
 * for a pinned point. */
static inline void msocl_wind_kick(__global float *v, __global const float *aux,
                                   int a, int plane, float dt, float fx,
                                   float fy, float fz)
{
  const float s = MSOCL_PLANES_PINNED(aux[plane + a]) ? 0.0f : dt * aux[a];
  v[a] += s * fx;
  v[plane + a] += s * fy;
  v[2 * plane + a] += s * fz;
}

/* Each point's corners into its velocity, in place: dt times the inverse
 * mass, nothing for a pinned point. Corner slot c of the point at a is
 * triangle slot[c plane + a] (a zero-force one past the last where the
 * point has fewer, and for the planes' padding), in triangle order; the
 * loop's fixed length unrolls, and nothing is conditional, so PoCL
 * vectorises it. */
#define MSOCL_WIND_SLOTS 8
__kernel void msocl_wind_points(__global float *v, __global const float *aux,
                                __global const int *slot,
                                __global const float *third, float dt,
                                int ntri, int nx, int pitch, int slab,
                                int plane, int n)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)nx; (void)slab; (void)n;
  float fx = 0.0f, fy = 0.0f, fz = 0.0f;
#pragma unroll
  for (int c = 0; c < MSOCL_WIND_SLOTS; c++) {
    const int k = slot[c * plane + a];
    fx += third[k];
    fy += third[ntri + k];
    fz += third[2 * ntri + k];
  }
  msocl_wind_kick(v, aux, a, plane, dt, fx, fy, fz);
}

/* Points on more triangles than the slots (listed: point i at a): their
 * whole sum from tri_off's CSR (corner c is triangle corner[c]), the
 * slots having given them nothing. */
__kernel void msocl_wind_spill(__global float *v, __global const float *aux,
                               __global const int *tri_off,
                               __global const int *corner,
                               __global const float *third,
                               __global const int *list, float dt, int ntri,
                               int plane, int nspill)
{
  const int q = get_global_id(0);
  if (q >= nspill)
    return;
  const int i = list[2 * q], a = list[2 * q + 1];
  float fx = 0.0f, fy = 0.0f, fz = 0.0f;
  for (int c = tri_off[i]; c < tri_off[i + 1]; c++) {
    const int k = corner[c];
    fx += third[k];
    fy += third[ntri + k];
    fz += third[2 * ntri + k];
  }
  msocl_wind_kick(v, aux, a, plane, dt, fx, fy, fz);
}

#if defined(MSOCL_LAYOUT_GRID) && !defined(MSOCL_GRID_3D)
/* The cloth builder's triangles on GRID (lib/engine/wind.c checks the
 * model has them): quad (x, y) holds A = (p, p+1, p+nx+1) and
 * B = (p, p+nx+1, p+nx); work-item (x, y, 0) writes A's third into
 * planes 0-2 of `cell` at a, (x, y, 1) B's into planes 3-5 (zero past the
 * last quad; the padding stays zero). Fixed offsets: no corner table, no
 * gather; one triangle a work-item, as two alike would be paired into a
 * vector and PoCL would leave the kernel scalar. */
__kernel void msocl_wind_quads(__global const float *p,
                               __global const float *v,
                               __global float *cell, float4 air, float4 coef,
                               int nx, int ny, int pitch, int slab, int plane)
{
  const int x = get_global_id(0), y = get_global_id(1);
  const bool b = get_global_id(2) == 1;
  const int a = MSOCL_PLANES_AT(x, y, 0);
  (void)slab;
  const bool real = x + 1 < nx && y + 1 < ny;
  float fx, fy, fz;
  msocl_wind_third(p, v, plane, a, b ? a + pitch + 1 : a + 1,
                   b ? a + pitch : a + pitch + 1, air, coef, &fx, &fy, &fz);
  const int o = b ? 3 * plane + a : a;
  cell[o] = real ? fx : 0.0f;
  cell[plane + o] = real ? fy : 0.0f;
  cell[2 * plane + o] = real ? fz : 0.0f;
}

/* Each point's six triangles in triangle order - A and B of the quad
 * below-left, B of the one below, A of the one left, A and B of its own
 * - into its velocity, as msocl_wind_points sums them. */
__kernel void msocl_wind_quad_points(__global float *v,
                                     __global const float *aux,
                                     __global const float *cell, float dt,
                                     int nx, int pitch, int slab, int plane,
                                     int n)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)nx; (void)slab; (void)n;
  const int below = a - pitch;
  float fx = 0.0f, fy = 0.0f, fz = 0.0f;
#define MSOCL_WIND_ADD(k)                                                     \
  fx += cell[k];                                                              \
  fy += cell[plane + (k)];                                                    \
  fz += cell[2 * plane + (k)]
  MSOCL_WIND_ADD(below - 1);
  MSOCL_WIND_ADD(3 * plane + below - 1);
  MSOCL_WIND_ADD(3 * plane + below);
  MSOCL_WIND_ADD(a - 1);
  MSOCL_WIND_ADD(a);
  MSOCL_WIND_ADD(3 * plane + a);
#undef MSOCL_WIND_ADD
  msocl_wind_kick(v, aux, a, plane, dt, fx, fy, fz);
}
#endif

#endif

/* Symplectic Euler's velocity pass (and both passes fused) on BUFFER's
 * table, MSOCL_ROWS_W points a work-item in explicit vectors
 * (lib/engine/planes.c takes them on a CPU device, one engine, no capsule
 * or box, precise math).
 *
 * Why: PoCL vectorises a kernel across work-items only when its
 * per-work-item code is all scalar; for AVX2 (PoCL's target on this
 * project's AMD machines) LLVM's SLP vectorizer pairs the gather's x and
 * z differences into <2 x float> first, so msocl_planes_velocity ran one
 * point at a time, below serial C. Here every value is a vector of points
 * and the neighbours' coordinates are gathered lane by lane, so nothing is
 * left for SLP to pair. Same per-point arithmetic and slot order as
 * msocl_planes_kick: bitwise its result (tests/check_planes.c). A point
 * with springs past the table gets a partial sum here, which the kernel's
 * _spill twin (msocl_planes_velocity_spill / _fused_spill, launched after)
 * overwrites. */
#include "rows.h"
#if defined(MSOCL_PLANES) && !defined(MSOCL_LAYOUT_GRID) && \
    !defined(MSOCL_LAYOUT_IMAGE2D)

/* q at the lanes' indices j */
static inline msocl_rows_f msocl_wide_gather(__global const float *q,
                                             const int *j)
{
  float t[MSOCL_ROWS_W];
#pragma unroll
  for (int u = 0; u < MSOCL_ROWS_W; u++)
    t[u] = q[j[u]];
  return MSOCL_ROWS_LOAD(t);
}

/* The new velocities of points x0 .. x0 + W - 1 (msocl_planes_kick's),
 * their positions in *px.., and whether each is pinned. */
static inline void msocl_wide_kick(MSOCL_CONN, __global const float *p,
                                   __global const float *v,
                                   __global const float *aux, int slab,
                                   int plane, float4 gravity, float viscous,
                                   float air, float dt,
                                   __constant const float *cf, int x0,
                                   msocl_rows_f *px, msocl_rows_f *py,
                                   msocl_rows_f *pz, msocl_rows_f *vx_out,
                                   msocl_rows_f *vy_out,
                                   msocl_rows_f *vz_out, msocl_rows_m *held)
{
  __global const float *py_ = p + plane, *pz_ = py_ + plane;
  __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
  const msocl_rows_f qx = MSOCL_ROWS_LOAD(p + x0),
                     qy = MSOCL_ROWS_LOAD(py_ + x0),
                     qz = MSOCL_ROWS_LOAD(pz_ + x0);
  const msocl_rows_f ux = MSOCL_ROWS_LOAD(v + x0),
                     uy = MSOCL_ROWS_LOAD(vy_ + x0),
                     uz = MSOCL_ROWS_LOAD(vz_ + x0);
  const msocl_rows_m self = MSOCL_ROWS_LANES + x0;
  msocl_rows_f fx = 0.0f, fy = 0.0f, fz = 0.0f;
  /* one slot at a time: unrolled, every slot's 16 lanes stayed live and
   * were spilled to a stack frame of kilobytes */
#pragma unroll 1
  for (int s = 0; s < MSOCL_TABLE_SLOTS; s++) {
    const int at = s * slab + x0;
    int j[MSOCL_ROWS_W];
#pragma unroll
    for (int u = 0; u < MSOCL_ROWS_W; u++)
      j[u] = nbr[at + u];
    const msocl_rows_m jv = MSOCL_ROWS_LOAD(j);
#ifdef MSOCL_CLASSES
    float r[MSOCL_ROWS_W], k[MSOCL_ROWS_W], c[MSOCL_ROWS_W];
#pragma unroll
    for (int u = 0; u < MSOCL_ROWS_W; u++) {
      __global const float *w = (__global const float *)dmp + 4 * rk[at + u];
      r[u] = w[0];
      k[u] = w[1];
      c[u] = w[2];
    }
    const msocl_rows_f rest = MSOCL_ROWS_LOAD(r), kk = MSOCL_ROWS_LOAD(k);
#ifdef MSOCL_DAMPING
    const msocl_rows_f cc = MSOCL_ROWS_LOAD(c);
#endif
#else
    __global const float *w = (__global const float *)rk;
    const msocl_rows_f rest = MSOCL_ROWS_LOAD(w + at),
                       kk = MSOCL_ROWS_LOAD(w + MSOCL_SLOTS * slab + at);
#ifdef MSOCL_DAMPING
    const msocl_rows_f cc = MSOCL_ROWS_LOAD(dmp + at);
#endif
#endif
    const msocl_rows_m there = jv != self;
    const msocl_rows_f dx = msocl_wide_gather(p, j) - qx,
                       dy = msocl_wide_gather(py_, j) - qy,
                       dz = msocl_wide_gather(pz_, j) - qz;
    const msocl_rows_f len2 = dx * dx + dy * dy + dz * dz;
    const msocl_rows_f len = MSOCL_SQRT(len2);
    const msocl_rows_f t = kk * MSOCL_DIV(len - rest, len);
    const msocl_rows_m on = there & (len > 0.0f);
    fx += MSOCL_ROWS_SEL(on, t * dx, 0.0f);
    fy += MSOCL_ROWS_SEL(on, t * dy, 0.0f);
    fz += MSOCL_ROWS_SEL(on, t * dz, 0.0f);
#ifdef MSOCL_DAMPING
    const msocl_rows_f wx = msocl_wide_gather(v, j) - ux,
                       wy = msocl_wide_gather(vy_, j) - uy,
                       wz = msocl_wide_gather(vz_, j) - uz;
    const msocl_rows_f h = cc * MSOCL_DIV(wx * dx + wy * dy + wz * dz, len2);
    const msocl_rows_m onh = there & (len2 > 0.0f);
    fx += MSOCL_ROWS_SEL(onh, h * dx, 0.0f);
    fy += MSOCL_ROWS_SEL(onh, h * dy, 0.0f);
    fz += MSOCL_ROWS_SEL(onh, h * dz, 0.0f);
#endif
  }
  msocl_rows_f vx, vy, vz;
  msocl_rows_velocity(fx, fy, fz, ux, uy, uz, MSOCL_ROWS_LOAD(aux + x0), qx,
                      qy, qz, gravity, viscous, air, dt, cf, &vx, &vy, &vz);
#ifdef MSOCL_PINS
  *held = MSOCL_ROWS_LOAD(aux + plane + x0) != 0.0f;
#else
  *held = (msocl_rows_m)(0);
#endif
  *vx_out = MSOCL_ROWS_SEL(*held, 0.0f, vx);
  *vy_out = MSOCL_ROWS_SEL(*held, 0.0f, vy);
  *vz_out = MSOCL_ROWS_SEL(*held, 0.0f, vz);
  *px = qx;
  *py = qy;
  *pz = qz;
}

/* v's W values at q, or those of them below n (the row's padding keeps
 * its zeros) */
static inline void msocl_wide_store(msocl_rows_f v, __global float *q,
                                    int x0, int n)
{
  if (x0 + MSOCL_ROWS_W <= n) {
    MSOCL_ROWS_STORE(v, q + x0);
    return;
  }
  const float *t = (const float *)&v;
  for (int u = 0; x0 + u < n && u < MSOCL_ROWS_W; u++)
    q[x0 + u] = t[u];
}

#define MSOCL_WIDE_KICK                                                       \
  const int x0 = get_global_id(0) * MSOCL_ROWS_W;                            \
  msocl_rows_f px, py, pz, vx, vy, vz;                                       \
  msocl_rows_m held;                                                         \
  msocl_wide_kick(MSOCL_CONN_ARGS, p, v, aux, slab, plane, gravity, viscous, \
                  air, dt, (__constant const float *)col, x0, &px, &py,      \
                  &pz, &vx, &vy, &vz, &held);                                \
  msocl_wide_store(vx, v_out, x0, pitch);                                    \
  msocl_wide_store(vy, v_out + plane, x0, pitch);                            \
  msocl_wide_store(vz, v_out + 2 * plane, x0, pitch)

__kernel void msocl_planes_wide_velocity(MSOCL_CONN, __global const float *p,
                                         __global const float *v,
                                         __global float *v_out,
                                         MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_KICK;
}

__kernel void msocl_planes_wide_fused(MSOCL_CONN, __global const float *p,
                                      __global const float *v,
                                      __global float *v_out,
                                      __global float *p_out,
                                      MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_KICK;
  msocl_wide_store(MSOCL_ROWS_SEL(held, px, px + dt * vx), p_out, x0, pitch);
  msocl_wide_store(MSOCL_ROWS_SEL(held, py, py + dt * vy), p_out + plane, x0,
                   pitch);
  msocl_wide_store(MSOCL_ROWS_SEL(held, pz, pz + dt * vz), p_out + 2 * plane,
                   x0, pitch);
}

#endif

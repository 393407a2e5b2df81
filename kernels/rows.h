/* The explicit vectors of points that planes_rows.cl's sweep and
 * planes_wide.cl's kernels work in, and their collision response. */
#ifndef MSOCL_ROWS_H
#define MSOCL_ROWS_H

#include "planes.h"

/* float16 values passed to functions (builtins included) where the
 * target lacks AVX-512: clang notes an ABI change a call, hundreds a
 * build, on the terminal of every program that builds the kernels; every
 * call is inlined, so no ABI is crossed */
#if defined(__clang__) && defined(__x86_64__)
#pragma clang diagnostic ignored "-Wpsabi"
#endif

/* The vector of points this sweep works in, and planes_wide.cl's kernels
 * (BUFFER's table) too. */
#if defined(MSOCL_PLANES) && !defined(MSOCL_LAYOUT_IMAGE2D)
#define MSOCL_ROWS 1 /* the vectors below exist in this program */
#ifndef MSOCL_ROWS_W
#define MSOCL_ROWS_W 16
#endif
#if MSOCL_ROWS_W == 16
typedef float16 msocl_rows_f;
typedef int16 msocl_rows_m;
#define MSOCL_ROWS_LANES                                                      \
  ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#define MSOCL_ROWS_LOAD(q) vload16(0, (q))
#else
typedef float8 msocl_rows_f;
typedef int8 msocl_rows_m;
#define MSOCL_ROWS_LANES ((int8)(0, 1, 2, 3, 4, 5, 6, 7))
#define MSOCL_ROWS_LOAD(q) vload8(0, (q))
#endif

/* A store of a vector at any float's address: one unaligned vector store,
 * where PoCL writes vstore16 as three (16, 16 and 32 bytes, two extracts) */
typedef msocl_rows_f msocl_rows_any __attribute__((aligned(4)));
#define MSOCL_ROWS_STORE(v, q) (*(__global msocl_rows_any *)(q) = (v))

/* c ? a : b per lane */
#define MSOCL_ROWS_SEL(c, a, b)                                               \
  select((msocl_rows_f)(b), (msocl_rows_f)(a), (msocl_rows_m)(c))

/* msocl_planes_gap for collider c, lane by lane: the gap, and the unit
 * gradient in *nx_out.. */
static inline msocl_rows_f msocl_rows_gap(msocl_rows_f px, msocl_rows_f py,
                                          msocl_rows_f pz,
                                          __constant const float *cf, int c,
                                          msocl_rows_f *nx_out,
                                          msocl_rows_f *ny_out,
                                          msocl_rows_f *nz_out)
{
#define cv(k) MSOCL_PLANES_COL(cf, c, k)
  const int kind = (int)cv(0);
  msocl_rows_f g = INFINITY, nx = 0.0f, ny = 1.0f, nz = 0.0f;
#ifdef MSOCL_PLANE
  if (kind == MSOCL_PLANE_KIND) {
    nx = cv(4);
    ny = cv(5);
    nz = cv(6);
    g = MSOCL_DOT3(cv(4), cv(5), cv(6), px, py, pz) - cv(7);
  }
#endif
#ifdef MSOCL_SPHERE
  if (kind == MSOCL_SPHERE_KIND) {
    const msocl_rows_f dx = px - cv(4), dy = py - cv(5), dz = pz - cv(6);
    const msocl_rows_f len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
    const msocl_rows_m out = len > 0.0f;
    nx = MSOCL_ROWS_SEL(out, MSOCL_DIV(dx, len), 0.0f);
    ny = MSOCL_ROWS_SEL(out, MSOCL_DIV(dy, len), 1.0f);
    nz = MSOCL_ROWS_SEL(out, MSOCL_DIV(dz, len), 0.0f);
    g = len - cv(7);
  }
#endif
#ifdef MSOCL_TABLE
  if (kind == MSOCL_TABLE_KIND) {
    const msocl_rows_f dx = px - cv(4), dz = pz - cv(6);
    const msocl_rows_f rr = MSOCL_SQRT(dx * dx + dz * dz);
    const msocl_rows_f gside = rr - cv(7), gtop = py - cv(5);
    const msocl_rows_m top = (gtop >= gside) | !(rr > 0.0f);
    nx = MSOCL_ROWS_SEL(top, 0.0f, MSOCL_DIV(dx, rr));
    ny = MSOCL_ROWS_SEL(top, 1.0f, 0.0f);
    nz = MSOCL_ROWS_SEL(top, 0.0f, MSOCL_DIV(dz, rr));
    g = MSOCL_ROWS_SEL(top, gtop, gside);
  }
#endif
#ifdef MSOCL_CAPSULE
  /* msocl_planes_gap's capsule, lane by lane */
  if (kind == MSOCL_CAPSULE_KIND) {
    const float ex = cv(8) - cv(4), ey = cv(9) - cv(5), ez = cv(10) - cv(6);
    const msocl_rows_f ax = px - cv(4), ay = py - cv(5), az = pz - cv(6);
    const float ee = MSOCL_DOT3(ex, ey, ez, ex, ey, ez);
    msocl_rows_f t = ee > 0.0f ? MSOCL_DIV(MSOCL_DOT3(ax, ay, az, ex, ey, ez),
                                           (msocl_rows_f)ee)
                               : (msocl_rows_f)0.0f;
    t = fmin(fmax(t, 0.0f), 1.0f);
    const msocl_rows_f dx = ax - t * ex, dy = ay - t * ey, dz = az - t * ez;
    const msocl_rows_f len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
    const msocl_rows_m out = len > 0.0f;
    nx = MSOCL_ROWS_SEL(out, dx / len, 0.0f);
    ny = MSOCL_ROWS_SEL(out, dy / len, 1.0f);
    nz = MSOCL_ROWS_SEL(out, dz / len, 0.0f);
    g = len - cv(7);
  }
#endif
#ifdef MSOCL_BOX
  /* msocl_planes_gap's box, lane by lane (the same operations: no SLP
   * pairing to avoid in vectors, but the bits must be the scalar's) */
  if (kind == MSOCL_BOX_KIND) {
    const float qx = cv(8), qy = cv(9), qz = cv(10), qw = cv(11);
    const float r00 = 1.0f - 2.0f * (qy * qy + qz * qz),
                r01 = 2.0f * (qx * qy - qz * qw),
                r02 = 2.0f * (qx * qz + qy * qw);
    const float r10 = 2.0f * (qx * qy + qz * qw),
                r11 = 1.0f - 2.0f * (qx * qx + qz * qz),
                r12 = 2.0f * (qy * qz - qx * qw);
    const float r20 = 2.0f * (qx * qz - qy * qw),
                r21 = 2.0f * (qy * qz + qx * qw),
                r22 = 1.0f - 2.0f * (qx * qx + qy * qy);
    const msocl_rows_f ex = px - cv(4), ey = py - cv(5), ez = pz - cv(6);
    const msocl_rows_f lx = r00 * ex + r10 * ey + r20 * ez;
    const msocl_rows_f ly = fma((msocl_rows_f)r01, ex,
                                fma((msocl_rows_f)r11, ey, r21 * ez));
    const msocl_rows_f lz = fma((msocl_rows_f)r22, ez, r02 * ex) + r12 * ey;
    const float hx = cv(12), hy = cv(13), hz = cv(14);
    const msocl_rows_f dx = fabs(lx) - hx, dy = fmax(ly, -ly) - hy,
                       dz = fabs(lz) - hz;
    const msocl_rows_f ox = fmax(dx, 0.0f),
                       oy = MSOCL_ROWS_SEL(dy > 0.0f, dy, 0.0f),
                       oz = 0.5f * (dz + fabs(dz));
    const msocl_rows_f olen = MSOCL_SQRT(MSOCL_DOT3(ox, oy, oz, ox, oy, oz));
    const msocl_rows_m outside = olen > 0.0f;
    const msocl_rows_m xm = (dx >= dy) & (dx >= dz),
                       ym = ~xm & (dy >= dz);
    const msocl_rows_f sx = MSOCL_ROWS_SEL(lx < 0.0f, -1.0f, 1.0f),
                       sy = copysign((msocl_rows_f)1.0f, ly),
                       sz = MSOCL_ROWS_SEL(lz < 0.0f, -1.0f, 1.0f);
    const msocl_rows_f inv = MSOCL_ROWS_SEL(outside, 1.0f / olen, 0.0f);
    const msocl_rows_f mx = MSOCL_ROWS_SEL(
        outside, sx * ox * inv, MSOCL_ROWS_SEL(xm, sx, 0.0f));
    const msocl_rows_f my = MSOCL_ROWS_SEL(
        outside, fma(sy * oy, inv, 0.0f), MSOCL_ROWS_SEL(ym, sy, 0.0f));
    const msocl_rows_f mz = MSOCL_ROWS_SEL(
        outside, sz * oz / olen, MSOCL_ROWS_SEL(~xm & ~ym, sz, 0.0f));
    g = MSOCL_ROWS_SEL(outside, olen,
                       MSOCL_ROWS_SEL(xm, dx, MSOCL_ROWS_SEL(ym, dy, dz)));
    nx = r00 * mx + r01 * my + r02 * mz;
    ny = fma((msocl_rows_f)r10, mx, fma((msocl_rows_f)r11, my, r12 * mz));
    nz = fma((msocl_rows_f)r22, mz, r20 * mx) + r21 * my;
  }
#endif
  (void)kind;
#undef cv
  *nx_out = nx;
  *ny_out = ny;
  *nz_out = nz;
  return g;
}

/* msocl_planes_collide's response for collider c, lane by lane, its
 * friction times fscale; `still` (a constant where it is inlined) when
 * the host knows no collider moves this step: the same bits, without the
 * motion's terms and branches. */
static inline __attribute__((always_inline)) void
msocl_rows_collide(msocl_rows_f px, msocl_rows_f py, msocl_rows_f pz,
                   msocl_rows_f *vx_io, msocl_rows_f *vy_io,
                   msocl_rows_f *vz_io, float dt, __constant const float *cf,
                   int c, int still, float fscale)
{
  msocl_rows_f nx, ny, nz;
  const msocl_rows_f g = msocl_rows_gap(px, py, pz, cf, c, &nx, &ny, &nz);
#define cv(k) MSOCL_PLANES_COL(cf, c, k)
  const float fr = fscale * cv(1);
  /* on the velocity relative to a moving collider's surface */
  MSOCL_PLANES_SURFACE(msocl_rows_f, cv, px, py, pz);
  const bool moving = !still && cv(2) != 0.0f;
#undef cv
  const msocl_rows_f vx = *vx_io, vy = *vy_io, vz = *vz_io;
  const msocl_rows_f ox = moving ? vx - ux : vx, oy = moving ? vy - uy : vy,
                     oz = moving ? vz - uz : vz;
  const msocl_rows_f vn = MSOCL_DOT3(ox, oy, oz, nx, ny, nz);
  const msocl_rows_f lim = MSOCL_DIV(-g, dt);
  msocl_rows_f hx = ox + (lim - vn) * nx, hy = oy + (lim - vn) * ny,
               hz = oz + (lim - vn) * nz;
  hx = hx - fr * (hx - lim * nx);
  hy = hy - fr * (hy - lim * ny);
  hz = hz - fr * (hz - lim * nz);
  if (moving) {
    hx = hx + ux;
    hy = hy + uy;
    hz = hz + uz;
  }
  const msocl_rows_m hit = vn < lim;
  *vx_io = MSOCL_ROWS_SEL(hit, hx, vx);
  *vy_io = MSOCL_ROWS_SEL(hit, hy, vy);
  *vz_io = MSOCL_ROWS_SEL(hit, hz, vz);
}

/* A vector of points' new velocity from their spring force f, velocity
 * u and inverse masses im: viscous damping, gravity, air resistance and
 * the colliders at their positions q - msocl_planes_kick's arithmetic,
 * so the bits are its. */
static inline __attribute__((always_inline)) void msocl_rows_velocity(
    msocl_rows_f fx, msocl_rows_f fy, msocl_rows_f fz, msocl_rows_f ux,
    msocl_rows_f uy, msocl_rows_f uz, msocl_rows_f im, msocl_rows_f qx,
    msocl_rows_f qy, msocl_rows_f qz, float4 gravity, float viscous,
    float air, float dt, __constant const float *cf, int still,
    msocl_rows_f *vx_out, msocl_rows_f *vy_out, msocl_rows_f *vz_out)
{
#ifdef MSOCL_VISCOUS
  fx = fx - viscous * ux;
  fy = fy - viscous * uy;
  fz = fz - viscous * uz;
#endif
  (void)viscous;
  msocl_rows_f vx = ux + dt * (fx * im + gravity.x);
  msocl_rows_f vy = uy + dt * (fy * im + gravity.y);
  msocl_rows_f vz = uz + dt * (fz * im + gravity.z);
#ifdef MSOCL_AIR
  vx = air * vx;
  vy = air * vy;
  vz = air * vz;
#endif
  (void)air;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++)
    msocl_rows_collide(qx, qy, qz, &vx, &vy, &vz, dt, cf, c, still, 1.0f);
  (void)cf;
  *vx_out = vx;
  *vy_out = vy;
  *vz_out = vz;
}
#endif
#endif

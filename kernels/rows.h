/* The explicit vectors of points that planes_rows.cl's sweep and
 * planes_wide.cl's kernels work in, and their collision response. */
#ifndef MSOCL_ROWS_H
#define MSOCL_ROWS_H

#include "planes.h"

/* The vector of points this sweep works in, and planes_wide.cl's kernels
 * (BUFFER's table) too. */
#if defined(MSOCL_PLANES) &&                                                 \
    ((defined(MSOCL_LAYOUT_GRID) && !defined(MSOCL_GRID_3D)) ||               \
     (!defined(MSOCL_LAYOUT_GRID) && !defined(MSOCL_LAYOUT_IMAGE2D)))
#ifndef MSOCL_ROWS_W
#define MSOCL_ROWS_W 16
#endif
#if MSOCL_ROWS_W == 16
typedef float16 msocl_rows_f;
typedef int16 msocl_rows_m;
#define MSOCL_ROWS_LANES                                                      \
  ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#define MSOCL_ROWS_LOAD(q) vload16(0, (q))
#define MSOCL_ROWS_STORE(v, q) vstore16((v), 0, (q))
#else
typedef float8 msocl_rows_f;
typedef int8 msocl_rows_m;
#define MSOCL_ROWS_LANES ((int8)(0, 1, 2, 3, 4, 5, 6, 7))
#define MSOCL_ROWS_LOAD(q) vload8(0, (q))
#define MSOCL_ROWS_STORE(v, q) vstore8((v), 0, (q))
#endif

/* c ? a : b per lane */
#define MSOCL_ROWS_SEL(c, a, b)                                               \
  select((msocl_rows_f)(b), (msocl_rows_f)(a), (msocl_rows_m)(c))

/* msocl_planes_gap and msocl_planes_collide's response for collider c,
 * lane by lane. */
static inline void msocl_rows_collide(msocl_rows_f px, msocl_rows_f py,
                               msocl_rows_f pz, msocl_rows_f *vx_io,
                               msocl_rows_f *vy_io, msocl_rows_f *vz_io,
                               float dt, __constant const float *cf, int c)
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
  (void)kind;
  const float fr = 1.0f * cv(1);
  /* on the velocity relative to a moving collider's surface */
  MSOCL_PLANES_SURFACE(msocl_rows_f, cv, px, py, pz);
  const bool moving = cv(2) != 0.0f;
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
static inline void msocl_rows_velocity(
    msocl_rows_f fx, msocl_rows_f fy, msocl_rows_f fz, msocl_rows_f ux,
    msocl_rows_f uy, msocl_rows_f uz, msocl_rows_f im, msocl_rows_f qx,
    msocl_rows_f qy, msocl_rows_f qz, float4 gravity, float viscous,
    float air, float dt, __constant const float *cf, msocl_rows_f *vx_out,
    msocl_rows_f *vy_out, msocl_rows_f *vz_out)
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
    msocl_rows_collide(qx, qy, qz, &vx, &vy, &vz, dt, cf, c);
  (void)cf;
  *vx_out = vx;
  *vy_out = vy;
  *vz_out = vz;
}
#endif
#endif

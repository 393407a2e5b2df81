/* The gathering step kernels on BUFFER's table - symplectic Euler's
 * velocity pass (and both passes fused), Verlet's kick, RK4's three
 * stage kernels and forward Euler - MSOCL_ROWS_W points a work-item in
 * explicit vectors (lib/engine/planes.c takes them on a CPU device, one
 * engine, precise math).
 *
 * Why: PoCL vectorises a kernel across work-items only when its
 * per-work-item code is all scalar and its cost model agrees; for AVX2
 * (PoCL's target on this project's AMD machines) LLVM's SLP vectorizer
 * pairs the slots' or the x and z components' arithmetic into short
 * vectors first, and the gathers are dear, so the planes.cl kernels ran
 * one point at a time, below serial C (docs/PERFORMANCE.md). Here every
 * value is a vector of points and the neighbours' coordinates are
 * gathered lane by lane, so nothing is left for SLP to pair. Same
 * per-point arithmetic and slot order as planes.cl's kernels: bitwise
 * their results (tests/check_planes.c). A point with springs past the
 * table gets a partial sum here, which the kernel's _spill twin (launched
 * after) overwrites; RK4's sums, which the twin reads, are left alone for
 * it. */
#include "wide.h"

#ifdef MSOCL_ROWS
/* The new velocities of points x0 .. x0 + W - 1 (msocl_planes_kick's),
 * their positions in *px.., and whether each is pinned. */
static MSOCL_WIDE_INLINE void
msocl_wide_kick(MSOCL_CONN, __global const float4 *p4,
                __global const float *p, __global const float *v,
                __global const float *aux, int slab, int plane, float4 gravity,
                float viscous, float air, float dt, __constant const float *cf,
                int pitch, int x0, int y, int z, int a, msocl_rows_f *px,
                msocl_rows_f *py, msocl_rows_f *pz, msocl_rows_f *vx_out,
                msocl_rows_f *vy_out, msocl_rows_f *vz_out, msocl_rows_m *held)
{
  msocl_rows_f q[3], u[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, p4, p, v, pitch, slab, plane, x0, y, z,
                   q, u, f);
  *px = q[0];
  *py = q[1];
  *pz = q[2];
  msocl_rows_f vx, vy, vz;
  msocl_rows_velocity(f[0], f[1], f[2], u[0], u[1], u[2],
                      MSOCL_ROWS_LOAD(aux + a), q[0], q[1], q[2], gravity,
                      viscous, air, dt, cf, 0, &vx, &vy, &vz);
  *held = msocl_wide_pinned(aux, plane, a);
  *vx_out = MSOCL_ROWS_SEL(*held, 0.0f, vx);
  *vy_out = MSOCL_ROWS_SEL(*held, 0.0f, vy);
  *vz_out = MSOCL_ROWS_SEL(*held, 0.0f, vz);
}

#define MSOCL_WIDE_KICK                                                       \
  MSOCL_WIDE_AT;                                                             \
  msocl_rows_f px, py, pz, vx, vy, vz;                                       \
  msocl_rows_m held;                                                         \
  msocl_wide_kick(MSOCL_CONN_ARGS, MSOCL_P4_ARG, p, v, aux, slab, plane,    \
                  gravity, viscous, air, dt, (__constant const float *)col,  \
                  pitch, x0, y, z, a, &px, &py, &pz, &vx, &vy, &vz, &held);  \
  MSOCL_WIDE_PUT(vx, v_out);                                                 \
  MSOCL_WIDE_PUT(vy, v_out + plane);                                         \
  MSOCL_WIDE_PUT(vz, v_out + 2 * plane)

__kernel void msocl_planes_wide_velocity(MSOCL_CONN MSOCL_P4,
                                         __global const float *p,
                                         __global const float *v,
                                         __global float *v_out,
                                         MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_KICK;
}

__kernel void msocl_planes_wide_fused(MSOCL_CONN MSOCL_P4,
                                      __global const float *p,
                                      __global const float *v,
                                      __global float *v_out,
                                      __global float *p_out, MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_KICK;
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, px, px + dt * vx), p_out);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, py, py + dt * vy), p_out + plane);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, pz, pz + dt * vz), p_out + 2 * plane);
}

/* Velocity Verlet's kick on BUFFER's table (msocl_planes_vkick's
 * arithmetic): a' = a(p', v+), v' = v+ + dt/2 a', a' kept. */
__kernel void msocl_planes_wide_vkick(MSOCL_CONN MSOCL_P4,
                                      __global const float *p,
                                      __global const float *v,
                                      __global float *v_out,
                                      __global float *acc_out,
                                      MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], u[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, MSOCL_P4_ARG, p, v, pitch, slab, plane, x0,
                   y, z, q, u, f);
  const msocl_rows_f fx = msocl_wide_viscous(f[0], u[0], viscous),
                     fy = msocl_wide_viscous(f[1], u[1], viscous),
                     fz = msocl_wide_viscous(f[2], u[2], viscous);
  const msocl_rows_f im = MSOCL_ROWS_LOAD(aux + a);
  const float h = 0.5f * dt;
  const msocl_rows_f ax = fx * im + gravity.x, ay = fy * im + gravity.y,
                     az = fz * im + gravity.z;
  msocl_rows_f vx = u[0] + h * ax, vy = u[1] + h * ay, vz = u[2] + h * az;
#ifdef MSOCL_AIR
  vx = air * vx;
  vy = air * vy;
  vz = air * vz;
#endif
  (void)air; (void)col; (void)q;
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, vx), v_out);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, vy), v_out + plane);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, vz), v_out + 2 * plane);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, ax), acc_out);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, ay), acc_out + plane);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, az), acc_out + 2 * plane);
}

/* Which of the points x0 .. x0 + W - 1 have all their springs in the
 * table: a point that spills is finished by the _spill twin, which reads
 * the RK4 sums this kernel would otherwise have updated already. */
static MSOCL_WIDE_INLINE msocl_rows_m
msocl_wide_whole(MSOCL_CONN, int x0, int n)
{
#ifdef MSOCL_SPILL
  int w[MSOCL_ROWS_W];
#pragma unroll
  for (int u = 0; u < MSOCL_ROWS_W; u++) {
    const int x = min(x0 + u, n - 1);
    w[u] = -(int)(spill[x + 1] == spill[x]);
  }
  return MSOCL_ROWS_LOAD(w);
#else
  (void)x0; (void)n;
  return (msocl_rows_m)(-1);
#endif
}

/* RK4's first (mode 0) and middle (1) stages on BUFFER's table
 * (msocl_planes_rk4's arithmetic): the stage's derivative at (sp, sv)
 * added to the sums, and the next stage state p0 + c dt k. */
static MSOCL_WIDE_INLINE void
msocl_wide_rk4(MSOCL_CONN, __global const float *p0, __global const float *v0,
               __global const float *sp, __global const float *sv,
               __global float *sum_p, __global float *sum_v,
               __global float *np, __global float *nv,
               __global const float *aux, int pitch, int slab, int plane,
               float4 gravity, float viscous, float dt, float c,
               const int mode)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], k[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, 0, sp, sv, pitch, slab, plane, x0, y, z,
                   q, k, f);
  const msocl_rows_f im = MSOCL_ROWS_LOAD(aux + a);
  const float g[3] = {gravity.x, gravity.y, gravity.z};
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
  const msocl_rows_m whole = msocl_wide_whole(MSOCL_CONN_ARGS, x0, pitch);
  const float h = c * dt;
#pragma unroll
  for (int d = 0; d < 3; d++) {
    const int o = d * plane + a;
    const msocl_rows_f kv = msocl_wide_viscous(f[d], k[d], viscous) * im + g[d];
    const msocl_rows_f kp = k[d];
    msocl_rows_f s_p = kp, s_v = kv;
    if (mode != 0) {
      const msocl_rows_f old_p = MSOCL_ROWS_LOAD(sum_p + o),
                         old_v = MSOCL_ROWS_LOAD(sum_v + o);
      s_p = MSOCL_ROWS_SEL(whole, old_p + 2.0f * kp, old_p);
      s_v = MSOCL_ROWS_SEL(whole, old_v + 2.0f * kv, old_v);
    }
    MSOCL_WIDE_PUT(s_p, sum_p + d * plane);
    MSOCL_WIDE_PUT(s_v, sum_v + d * plane);
    const msocl_rows_f start = MSOCL_ROWS_LOAD(p0 + o);
    MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, start, start + h * kp),
                   np + d * plane);
    MSOCL_WIDE_PUT(
        MSOCL_ROWS_SEL(held, 0.0f, MSOCL_ROWS_LOAD(v0 + o) + h * kv),
        nv + d * plane);
  }
  (void)q;
}

#define MSOCL_WIDE_RK4(mode)                                                  \
  msocl_wide_rk4(MSOCL_CONN_ARGS, p0, v0, sp, sv, sum_p, sum_v, np, nv, aux, \
                 pitch, slab, plane, gravity, viscous, dt, c, mode);         \
  (void)air; (void)col

/* the parameter list without its parentheses (expanded first) */
#define MSOCL_WIDE_PARAMS(list) MSOCL_PLANES_UNPAREN list

__kernel void msocl_planes_wide_rk4_first(
    MSOCL_WIDE_PARAMS(MSOCL_PLANES_RK4_ARGS))
{
  MSOCL_WIDE_RK4(0);
}

__kernel void msocl_planes_wide_rk4_middle(
    MSOCL_WIDE_PARAMS(MSOCL_PLANES_RK4_ARGS))
{
  MSOCL_WIDE_RK4(1);
}

/* msocl_planes_project for every collider, lane by lane: a point found
 * inside goes back to the surface and loses its inward speed. */
static MSOCL_WIDE_INLINE void
msocl_wide_project(msocl_rows_f *px, msocl_rows_f *py, msocl_rows_f *pz,
                   msocl_rows_f *vx, msocl_rows_f *vy, msocl_rows_f *vz,
                   float dt, __constant const float *cf)
{
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++) {
#define cv(k) MSOCL_PLANES_COL(cf, c, k)
    MSOCL_PLANES_SURFACE(msocl_rows_f, cv, *px, *py, *pz);
    const bool moving = cv(2) != 0.0f;
    const float fr = cv(1);
#undef cv
    const msocl_rows_f ex = moving ? *px - dt * ux : *px,
                       ey = moving ? *py - dt * uy : *py,
                       ez = moving ? *pz - dt * uz : *pz;
    msocl_rows_f nx, ny, nz;
    const msocl_rows_f g = msocl_rows_gap(ex, ey, ez, cf, c, &nx, &ny, &nz);
    const msocl_rows_m in = g < 0.0f;
    const msocl_rows_f qx = *px - g * nx, qy = *py - g * ny,
                       qz = *pz - g * nz;
    const msocl_rows_f ox = moving ? *vx - ux : *vx,
                       oy = moving ? *vy - uy : *vy,
                       oz = moving ? *vz - uz : *vz;
    const msocl_rows_f vn = MSOCL_DOT3(ox, oy, oz, nx, ny, nz);
    const msocl_rows_m back = in & (vn < 0.0f);
    msocl_rows_f wx = ox - vn * nx, wy = oy - vn * ny, wz = oz - vn * nz;
    wx = wx - fr * wx;
    wy = wy - fr * wy;
    wz = wz - fr * wz;
    if (moving) {
      wx = wx + ux;
      wy = wy + uy;
      wz = wz + uz;
    }
    *px = MSOCL_ROWS_SEL(in, qx, *px);
    *py = MSOCL_ROWS_SEL(in, qy, *py);
    *pz = MSOCL_ROWS_SEL(in, qz, *pz);
    *vx = MSOCL_ROWS_SEL(back, wx, *vx);
    *vy = MSOCL_ROWS_SEL(back, wy, *vy);
    *vz = MSOCL_ROWS_SEL(back, wz, *vz);
  }
  (void)cf;
}

/* RK4's last stage (msocl_planes_rk4's mode 2): the step's end from the
 * sums and this stage's derivative, air resistance, and the projection
 * out of the colliders. */
__kernel void msocl_planes_wide_rk4_last(
    MSOCL_WIDE_PARAMS(MSOCL_PLANES_RK4_ARGS))
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], k[3], f[3], e[3], w[3];
  msocl_wide_force(MSOCL_CONN_ARGS, 0, sp, sv, pitch, slab, plane, x0, y, z,
                   q, k, f);
  const msocl_rows_f im = MSOCL_ROWS_LOAD(aux + a);
  const float g[3] = {gravity.x, gravity.y, gravity.z};
  const float h = dt / 6.0f;
#pragma unroll
  for (int d = 0; d < 3; d++) {
    const int o = d * plane + a;
    const msocl_rows_f kv =
        msocl_wide_viscous(f[d], k[d], viscous) * im + g[d];
    e[d] = MSOCL_ROWS_LOAD(p0 + o) +
           h * (MSOCL_ROWS_LOAD(sum_p + o) + k[d]);
    w[d] = MSOCL_ROWS_LOAD(v0 + o) + h * (MSOCL_ROWS_LOAD(sum_v + o) + kv);
#ifdef MSOCL_AIR
    w[d] = air * w[d];
#endif
  }
  (void)air; (void)c; (void)q;
  msocl_wide_project(&e[0], &e[1], &e[2], &w[0], &w[1], &w[2], dt,
                     (__constant const float *)col);
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
#pragma unroll
  for (int d = 0; d < 3; d++) {
    MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, MSOCL_ROWS_LOAD(p0 + d * plane + a),
                                    e[d]), np + d * plane);
    MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, w[d]), nv + d * plane);
  }
}

/* Forward Euler (msocl_planes_euler's arithmetic): p' = p + dt v,
 * v' = v + dt a(p, v), air resistance, the projection out of the
 * colliders; pinned points stay. */
__kernel void msocl_planes_wide_euler(MSOCL_CONN MSOCL_P4,
                                      __global const float *p,
                                      __global const float *v,
                                      __global float *v_out,
                                      __global float *p_out, MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], u[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, MSOCL_P4_ARG, p, v, pitch, slab, plane, x0,
                   y, z, q, u, f);
  const msocl_rows_f im = MSOCL_ROWS_LOAD(aux + a);
  const float g[3] = {gravity.x, gravity.y, gravity.z};
  msocl_rows_f e[3], w[3];
#pragma unroll
  for (int d = 0; d < 3; d++) {
    e[d] = q[d] + dt * u[d];
    w[d] = u[d] + dt * (msocl_wide_viscous(f[d], u[d], viscous) * im + g[d]);
#ifdef MSOCL_AIR
    w[d] = air * w[d];
#endif
  }
  (void)air;
  msocl_wide_project(&e[0], &e[1], &e[2], &w[0], &w[1], &w[2], dt,
                     (__constant const float *)col);
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
#pragma unroll
  for (int d = 0; d < 3; d++) {
    MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, q[d], e[d]), p_out + d * plane);
    MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, w[d]), v_out + d * plane);
  }
}

#endif

/* Verlet's drift (msocl_planes_drift's arithmetic), pointwise, so on a
 * cloth grid's padded rows too: v+ = v + dt/2 a with the collision
 * response, in place, and p' = p + dt v+; only points x < nx stored. */
#ifdef MSOCL_ROWS
__kernel void msocl_planes_wide_drift(__global const float *p,
                                      __global float *v,
                                      __global const float *acc,
                                      __global float *p_out,
                                      __global const float *aux, int nx,
                                      int pitch, int slab, int plane,
                                      float dt, __constant float4 *col)
{
  const int x0 = get_global_id(0) * MSOCL_ROWS_W, y = get_global_id(1),
            z = get_global_id(2);
  const int a = MSOCL_PLANES_AT(x0, y, z);
  (void)slab; (void)y; (void)z; /* BUFFER's address is x0 alone */
  const float h = 0.5f * dt;
  msocl_rows_f q[3], u[3];
#pragma unroll
  for (int d = 0; d < 3; d++) {
    q[d] = MSOCL_ROWS_LOAD(p + d * plane + a);
    u[d] = MSOCL_ROWS_LOAD(v + d * plane + a) +
           h * MSOCL_ROWS_LOAD(acc + d * plane + a);
  }
  __constant const float *cf = (__constant const float *)col;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++)
    msocl_rows_collide(q[0], q[1], q[2], &u[0], &u[1], &u[2], dt, cf, c, 0,
                       1.0f);
  (void)cf;
#ifdef MSOCL_PINS
  const msocl_rows_m held = MSOCL_ROWS_LOAD(aux + plane + a) != 0.0f;
#else
  const msocl_rows_m held = (msocl_rows_m)(0);
#endif
  (void)aux;
  /* the row's first point at x0 = 0 */
  const int row = a - x0;
#pragma unroll
  for (int d = 0; d < 3; d++) {
    msocl_wide_store(MSOCL_ROWS_SEL(held, q[d], q[d] + dt * u[d]),
                     p_out + d * plane + row, x0, nx);
    msocl_wide_store(MSOCL_ROWS_SEL(held, 0.0f, u[d]), v + d * plane + row,
                     x0, nx);
  }
}
#endif

#if defined(MSOCL_GATHER4) && MSOCL_ROWS_W == 16
/* The positions' float4 copy that the force kernels gather (wide.h's
 * p4), 16 points a work-item over the planes' range: the gather's
 * transpose backwards, q[c]'s block b is point 4b + c. */
__kernel void msocl_planes_pack4(__global const float *p,
                                 __global float4 *p4, int plane)
{
  const int a = get_global_id(0) * 16;
  const float16 x = vload16(0, p + a), y = vload16(0, p + plane + a),
                z = vload16(0, p + 2 * plane + a), o = 0.0f;
  const float16 t0 = __builtin_shufflevector(x, y, 0, 16, 1, 17, 4, 20, 5, 21,
                                             8, 24, 9, 25, 12, 28, 13, 29),
                t1 = __builtin_shufflevector(x, y, 2, 18, 3, 19, 6, 22, 7, 23,
                                             10, 26, 11, 27, 14, 30, 15, 31),
                t2 = __builtin_shufflevector(z, o, 0, 16, 1, 17, 4, 20, 5, 21,
                                             8, 24, 9, 25, 12, 28, 13, 29),
                t3 = __builtin_shufflevector(z, o, 2, 18, 3, 19, 6, 22, 7, 23,
                                             10, 26, 11, 27, 14, 30, 15, 31);
  float16 q[4];
  q[0] = __builtin_shufflevector(t0, t2, 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24,
                                 25, 12, 13, 28, 29);
  q[1] = __builtin_shufflevector(t0, t2, 2, 3, 18, 19, 6, 7, 22, 23, 10, 11,
                                 26, 27, 14, 15, 30, 31);
  q[2] = __builtin_shufflevector(t1, t3, 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24,
                                 25, 12, 13, 28, 29);
  q[3] = __builtin_shufflevector(t1, t3, 2, 3, 18, 19, 6, 7, 22, 23, 10, 11,
                                 26, 27, 14, 15, 30, 31);
#pragma unroll
  for (int c = 0; c < 4; c++) {
    p4[a + c] = q[c].s0123;
    p4[a + 4 + c] = q[c].s4567;
    p4[a + 8 + c] = q[c].s89ab;
    p4[a + 12 + c] = q[c].scdef;
  }
}
#endif

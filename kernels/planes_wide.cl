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
#include "rows.h"

#ifdef MSOCL_ROWS
/* Every helper inlined: a float16 passed by value to a call left in the
 * kernel goes through the stack on AVX2 (and a shared helper, called from
 * several kernels, was left a call). */
#define MSOCL_WIDE_INLINE inline __attribute__((always_inline))

/* v's W values at q, or those of them below n (the row's padding keeps
 * its zeros) */
static MSOCL_WIDE_INLINE void
msocl_wide_store(msocl_rows_f v, __global float *q, int x0, int n)
{
  if (x0 + MSOCL_ROWS_W <= n) {
    MSOCL_ROWS_STORE(v, q + x0);
    return;
  }
  const float *t = (const float *)&v;
  for (int u = 0; x0 + u < n && u < MSOCL_ROWS_W; u++)
    q[x0 + u] = t[u];
}

#endif
#ifdef MSOCL_ROWS

/* The work-item's 16 points x0 .. x0 + W - 1 of row y of layer z
 * (BUFFER: of the points in index order) at a in the planes, the row's
 * first point at row; a result stored for those below the row's end. */
#define MSOCL_WIDE_AT                                                         \
  const int x0 = get_global_id(0) * MSOCL_ROWS_W, y = get_global_id(1),      \
            z = get_global_id(2);                                            \
  const int a = MSOCL_PLANES_AT(x0, y, z), row = a - x0;                     \
  (void)y; (void)z
#define MSOCL_WIDE_PUT(val, q)                                                \
  msocl_wide_store((val), (q) + row, x0, MSOCL_PLANES_NX)

#ifndef MSOCL_LAYOUT_GRID
/* q at the lanes' indices j */
static MSOCL_WIDE_INLINE msocl_rows_f
msocl_wide_gather(__global const float *q, const int *j)
{
  float t[MSOCL_ROWS_W];
#pragma unroll
  for (int u = 0; u < MSOCL_ROWS_W; u++)
    t[u] = q[j[u]];
  return MSOCL_ROWS_LOAD(t);
}
#endif

/* The slot loop of the W points x0.. of row y at a: MSOCL_WIDE_SLOTS
 * { MSOCL_WIDE_SLOT; ... } declares, slot by slot, `there` (the spring
 * exists: msocl_planes_neighbor's answer), `rest`, `kk` and `cc`, and
 * MSOCL_WIDE_NB(q) reads plane q at the neighbours. GRID: each neighbour
 * a fixed offset away, one vector load; BUFFER: the table's, gathered
 * lane by lane, one slot at a time (unrolled, every slot's 16 lanes
 * stayed live and were spilled to a stack frame of kilobytes). */
#ifdef MSOCL_LAYOUT_GRID
#ifdef MSOCL_GRID_3D
/* a lattice's neighbour: its layer, and whether that is one */
#define MSOCL_WIDE_DZ(s) (msocl_grid_dz[s] * slab)
#define MSOCL_WIDE_IN_Z(s)                                                    \
  (z + msocl_grid_dz[s] >= 0 && z + msocl_grid_dz[s] < grid_nz)
#else
#define MSOCL_WIDE_DZ(s) 0
#define MSOCL_WIDE_IN_Z(s) true
#endif
#define MSOCL_WIDE_SLOTS                                                      \
  (void)slab; (void)z;                                                       \
  _Pragma("unroll") for (int s = 0; s < MSOCL_TABLE_SLOTS; s++)              \
    if (!MSOCL_PLANES_SKIP(s))
#define MSOCL_WIDE_SLOT                                                       \
  const int b_ =                                                             \
      a + MSOCL_WIDE_DZ(s) + msocl_grid_dy[s] * pitch + msocl_grid_dx[s];    \
  const int ny_ = y + msocl_grid_dy[s];                                      \
  const float k_ = MSOCL_GRID_K(s);                                          \
  const msocl_rows_m nx_ = MSOCL_ROWS_LANES + (x0 + msocl_grid_dx[s]);       \
  const msocl_rows_m there =                                                 \
      (nx_ >= 0) & (nx_ < grid_nx) &                                         \
      (msocl_rows_m)(-(int)(ny_ >= 0 && ny_ < grid_ny && MSOCL_WIDE_IN_Z(s) && \
                            k_ != 0.0f));                                    \
  const msocl_rows_f rest = (msocl_rows_f)MSOCL_GRID_R(s),                   \
                     kk = (msocl_rows_f)k_, cc = (msocl_rows_f)MSOCL_GRID_C; \
  (void)kk; (void)cc
#define MSOCL_WIDE_NB(q) MSOCL_ROWS_LOAD((q) + b_)
#else
#define MSOCL_WIDE_SLOTS                                                      \
  (void)pitch; (void)z;                                                      \
  _Pragma("unroll 1") for (int s = 0; s < MSOCL_TABLE_SLOTS; s++)
#define MSOCL_WIDE_SLOT                                                       \
  int j_[MSOCL_ROWS_W];                                                      \
  msocl_rows_f rest, kk, cc;                                                 \
  const msocl_rows_m there =                                                 \
      msocl_wide_slot(MSOCL_CONN_ARGS, s, slab, x0, j_, &rest, &kk, &cc)
#define MSOCL_WIDE_NB(q) msocl_wide_gather((q), j_)

/* Slot s of the W points from x0 in BUFFER's table: their neighbours in
 * j, the springs' values, and whether each has one (a free slot holds the
 * point itself) */
static MSOCL_WIDE_INLINE msocl_rows_m
msocl_wide_slot(MSOCL_CONN, int s, int slab, int x0, int *j,
                msocl_rows_f *rest, msocl_rows_f *kk, msocl_rows_f *cc)
{
  const int at = s * slab + x0;
#pragma unroll
  for (int u = 0; u < MSOCL_ROWS_W; u++)
    j[u] = nbr[at + u];
  *cc = 0.0f;
#ifdef MSOCL_CLASSES
  float r[MSOCL_ROWS_W], k[MSOCL_ROWS_W], c[MSOCL_ROWS_W];
#pragma unroll
  for (int u = 0; u < MSOCL_ROWS_W; u++) {
    __global const float *w = (__global const float *)dmp + 4 * rk[at + u];
    r[u] = w[0];
    k[u] = w[1];
    c[u] = w[2];
  }
  *rest = MSOCL_ROWS_LOAD(r);
  *kk = MSOCL_ROWS_LOAD(k);
  *cc = MSOCL_ROWS_LOAD(c);
#else
  __global const float *w = (__global const float *)rk;
  *rest = MSOCL_ROWS_LOAD(w + at);
  *kk = MSOCL_ROWS_LOAD(w + MSOCL_SLOTS * slab + at);
#ifdef MSOCL_DAMPING
  *cc = MSOCL_ROWS_LOAD(dmp + at);
#endif
#endif
  return MSOCL_ROWS_LOAD(j) != MSOCL_ROWS_LANES + x0;
}
#endif

/* One slot's spring and dashpot on the points at q (velocities u), from
 * their neighbours at n (velocities w) where `there`: msocl_planes_pull's
 * terms, added to f. */
static MSOCL_WIDE_INLINE void
msocl_wide_pull(msocl_rows_f nx, msocl_rows_f ny, msocl_rows_f nz,
                msocl_rows_f wx0, msocl_rows_f wy0, msocl_rows_f wz0,
                msocl_rows_f qx, msocl_rows_f qy, msocl_rows_f qz,
                msocl_rows_f ux, msocl_rows_f uy, msocl_rows_f uz,
                msocl_rows_m there, msocl_rows_f rest, msocl_rows_f kk,
                msocl_rows_f cc, msocl_rows_f *fx, msocl_rows_f *fy,
                msocl_rows_f *fz)
{
  const msocl_rows_f dx = nx - qx, dy = ny - qy, dz = nz - qz;
  const msocl_rows_f len2 = dx * dx + dy * dy + dz * dz;
  const msocl_rows_f len = MSOCL_SQRT(len2);
  const msocl_rows_f t = kk * MSOCL_DIV(len - rest, len);
  const msocl_rows_m on = there & (len > 0.0f);
  *fx += MSOCL_ROWS_SEL(on, t * dx, 0.0f);
  *fy += MSOCL_ROWS_SEL(on, t * dy, 0.0f);
  *fz += MSOCL_ROWS_SEL(on, t * dz, 0.0f);
#ifdef MSOCL_DAMPING
  const msocl_rows_f wx = wx0 - ux, wy = wy0 - uy, wz = wz0 - uz;
  const msocl_rows_f h = cc * MSOCL_DIV(wx * dx + wy * dy + wz * dz, len2);
  const msocl_rows_m onh = there & (len2 > 0.0f);
  *fx += MSOCL_ROWS_SEL(onh, h * dx, 0.0f);
  *fy += MSOCL_ROWS_SEL(onh, h * dy, 0.0f);
  *fz += MSOCL_ROWS_SEL(onh, h * dz, 0.0f);
#else
  (void)wx0; (void)wy0; (void)wz0; (void)ux; (void)uy; (void)uz; (void)cc;
#endif
}

/* The spring and dashpot force f on the points x0 .. x0 + W - 1 of row
 * y at positions p and velocities v, slot by slot (msocl_planes_force's
 * sums, before viscous damping), and the points' own positions q and
 * velocities u. GRID: each neighbour a fixed offset away, one vector load;
 * BUFFER: the table's, gathered lane by lane. */
static MSOCL_WIDE_INLINE void
msocl_wide_force(MSOCL_CONN, __global const float *p, __global const float *v,
                 int pitch, int slab, int plane, int x0, int y, int z,
                 msocl_rows_f q_out[3], msocl_rows_f u_out[3],
                 msocl_rows_f f_out[3])
{
  const int a = MSOCL_PLANES_AT(x0, y, z);
  __global const float *py_ = p + plane, *pz_ = py_ + plane;
  __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
  const msocl_rows_f qx = MSOCL_ROWS_LOAD(p + a),
                     qy = MSOCL_ROWS_LOAD(py_ + a),
                     qz = MSOCL_ROWS_LOAD(pz_ + a);
  const msocl_rows_f ux = MSOCL_ROWS_LOAD(v + a),
                     uy = MSOCL_ROWS_LOAD(vy_ + a),
                     uz = MSOCL_ROWS_LOAD(vz_ + a);
  msocl_rows_f fx = 0.0f, fy = 0.0f, fz = 0.0f;
  msocl_rows_f wx = 0.0f, wy = 0.0f, wz = 0.0f;
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
#ifdef MSOCL_DAMPING
    wx = MSOCL_WIDE_NB(v);
    wy = MSOCL_WIDE_NB(vy_);
    wz = MSOCL_WIDE_NB(vz_);
#endif
    msocl_wide_pull(MSOCL_WIDE_NB(p), MSOCL_WIDE_NB(py_), MSOCL_WIDE_NB(pz_),
                    wx, wy, wz, qx, qy, qz, ux, uy, uz, there, rest, kk, cc,
                    &fx, &fy, &fz);
  }
  q_out[0] = qx;
  q_out[1] = qy;
  q_out[2] = qz;
  u_out[0] = ux;
  u_out[1] = uy;
  u_out[2] = uz;
  f_out[0] = fx;
  f_out[1] = fy;
  f_out[2] = fz;
}

/* Whether each of the W points at a is pinned */
static MSOCL_WIDE_INLINE msocl_rows_m
msocl_wide_pinned(__global const float *aux, int plane, int a)
{
#ifdef MSOCL_PINS
  return MSOCL_ROWS_LOAD(aux + plane + a) != 0.0f;
#else
  (void)aux; (void)plane; (void)a;
  return (msocl_rows_m)(0);
#endif
}

/* The new velocities of points x0 .. x0 + W - 1 (msocl_planes_kick's),
 * their positions in *px.., and whether each is pinned. */
static MSOCL_WIDE_INLINE void
msocl_wide_kick(MSOCL_CONN, __global const float *p, __global const float *v,
                __global const float *aux, int slab, int plane, float4 gravity,
                float viscous, float air, float dt, __constant const float *cf,
                int pitch, int x0, int y, int z, int a, msocl_rows_f *px,
                msocl_rows_f *py, msocl_rows_f *pz, msocl_rows_f *vx_out,
                msocl_rows_f *vy_out, msocl_rows_f *vz_out, msocl_rows_m *held)
{
  msocl_rows_f q[3], u[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, p, v, pitch, slab, plane, x0, y, z, q,
                   u, f);
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

/* msocl_planes_force's viscous damping on a spring force */
static MSOCL_WIDE_INLINE msocl_rows_f
msocl_wide_viscous(msocl_rows_f f, msocl_rows_f u, float viscous)
{
#ifdef MSOCL_VISCOUS
  return f - viscous * u;
#else
  (void)u; (void)viscous;
  return f;
#endif
}

#define MSOCL_WIDE_KICK                                                       \
  MSOCL_WIDE_AT;                                                             \
  msocl_rows_f px, py, pz, vx, vy, vz;                                       \
  msocl_rows_m held;                                                         \
  msocl_wide_kick(MSOCL_CONN_ARGS, p, v, aux, slab, plane, gravity, viscous, \
                  air, dt, (__constant const float *)col, pitch, x0, y, z, a,\
                  &px, &py, &pz, &vx, &vy, &vz, &held);                      \
  MSOCL_WIDE_PUT(vx, v_out);                                                 \
  MSOCL_WIDE_PUT(vy, v_out + plane);                                         \
  MSOCL_WIDE_PUT(vz, v_out + 2 * plane)

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
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, px, px + dt * vx), p_out);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, py, py + dt * vy), p_out + plane);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, pz, pz + dt * vz), p_out + 2 * plane);
}

/* Velocity Verlet's kick on BUFFER's table (msocl_planes_vkick's
 * arithmetic): a' = a(p', v+), v' = v+ + dt/2 a', a' kept. */
__kernel void msocl_planes_wide_vkick(MSOCL_CONN, __global const float *p,
                                      __global const float *v,
                                      __global float *v_out,
                                      __global float *acc_out,
                                      MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], u[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, p, v, pitch, slab, plane, x0, y, z, q,
                   u, f);
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
  msocl_wide_force(MSOCL_CONN_ARGS, sp, sv, pitch, slab, plane, x0, y, z, q,
                   k, f);
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
  msocl_wide_force(MSOCL_CONN_ARGS, sp, sv, pitch, slab, plane, x0, y, z, q,
                   k, f);
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
__kernel void msocl_planes_wide_euler(MSOCL_CONN, __global const float *p,
                                      __global const float *v,
                                      __global float *v_out,
                                      __global float *p_out,
                                      MSOCL_PLANES_ARGS)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], u[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, p, v, pitch, slab, plane, x0, y, z, q,
                   u, f);
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

/* A strain sweep's sums d and weight w into the move d / w where w > 0
 * (msocl_planes_strain's and msocl_planes_strain_v's ends) */
static MSOCL_WIDE_INLINE msocl_rows_f msocl_wide_share(msocl_rows_f d,
                                                       msocl_rows_f w)
{
  return MSOCL_ROWS_SEL(w > 0.0f, MSOCL_DIV(d, w), d);
}

/* A slot's spring vectors d from the points at q[0..2] to their
 * neighbours in the planes at p, and their lengths */
#define MSOCL_WIDE_EDGE(p, q)                                                 \
  const msocl_rows_f dx = MSOCL_WIDE_NB(p) - (q)[0],                         \
                     dy = MSOCL_WIDE_NB((p) + plane) - (q)[1],               \
                     dz = MSOCL_WIDE_NB((p) + 2 * plane) - (q)[2];           \
  const msocl_rows_f len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz))

/* A strain sweep's slot: its ask t (dx, dy, dz) and weight `ask` added
 * to d[0..3] where `on` */
static MSOCL_WIDE_INLINE void
msocl_wide_ask(msocl_rows_m on, msocl_rows_f t, msocl_rows_f ask,
               msocl_rows_f dx, msocl_rows_f dy, msocl_rows_f dz,
               msocl_rows_f *d)
{
  d[0] += MSOCL_ROWS_SEL(on, t * dx, 0.0f);
  d[1] += MSOCL_ROWS_SEL(on, t * dy, 0.0f);
  d[2] += MSOCL_ROWS_SEL(on, t * dz, 0.0f);
  d[3] += MSOCL_ROWS_SEL(on, ask, 0.0f);
}

/* The W values of planes q, q + plane and q + 2 plane at a */
static MSOCL_WIDE_INLINE void msocl_wide_load3(__global const float *q,
                                               int plane, int a,
                                               msocl_rows_f *out)
{
  out[0] = MSOCL_ROWS_LOAD(q + a);
  out[1] = MSOCL_ROWS_LOAD(q + plane + a);
  out[2] = MSOCL_ROWS_LOAD(q + 2 * plane + a);
}

/* Whether each of the neighbours at MSOCL_WIDE_NB is pinned: its share
 * of a spring's correction is all of it then, else half */
#ifdef MSOCL_PINS
#define MSOCL_WIDE_NB_SHARE                                                   \
  MSOCL_ROWS_SEL(MSOCL_WIDE_NB(aux + plane) != 0.0f, 1.0f, 0.5f)
#else
#define MSOCL_WIDE_NB_SHARE ((msocl_rows_f)0.5f)
#endif

/* Provot's sweep (msocl_planes_strain's arithmetic and slot order): each
 * point moved by the weighted average of what its over-long springs
 * ask. */
__kernel void msocl_planes_wide_strain(MSOCL_CONN, __global const float *p,
                                       __global float *p_out,
                                       __global const float *aux, int pitch,
                                       int slab, int plane, float limit)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  msocl_wide_load3(p, plane, a, q);
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
    MSOCL_WIDE_EDGE(p, q);
    const msocl_rows_f over = len - (1.0f + limit) * rest;
    const msocl_rows_f ask = MSOCL_WIDE_NB_SHARE * over;
    const msocl_rows_f t = ask * MSOCL_DIV(ask, len);
    msocl_wide_ask(there & (over > 0.0f), t, ask, dx, dy, dz, d);
  }
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
#pragma unroll
  for (int c = 0; c < 3; c++)
    MSOCL_WIDE_PUT(
        MSOCL_ROWS_SEL(held, q[c], q[c] + msocl_wide_share(d[c], d[3])),
        p_out + c * plane);
}

/* The velocity kind's sweep (msocl_planes_strain_v's arithmetic and slot
 * order), then the collision response again without friction. */
__kernel void msocl_planes_wide_strain_v(
    MSOCL_CONN, __global const float *p, __global const float *v,
    __global float *v_out, __global const float *aux, int pitch, int slab,
    int plane, float limit, float dt, __constant float4 *col)
{
  MSOCL_WIDE_AT;
  __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
  msocl_rows_f q[3], u[3], d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  msocl_wide_load3(p, plane, a, q);
  msocl_wide_load3(v, plane, a, u);
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
    MSOCL_WIDE_EDGE(p, q);
    const msocl_rows_f allowed = MSOCL_DIV((1.0f + limit) * rest - len, dt);
    const msocl_rows_f excess =
        MSOCL_DIV(MSOCL_DOT3(MSOCL_WIDE_NB(v) - u[0], MSOCL_WIDE_NB(vy_) - u[1],
                             MSOCL_WIDE_NB(vz_) - u[2], dx, dy, dz),
                  len) -
        allowed;
    const msocl_rows_f ask = MSOCL_WIDE_NB_SHARE * excess;
    const msocl_rows_f t = ask * MSOCL_DIV(ask, len);
    msocl_wide_ask(there & (len > 0.0f) & (excess > 0.0f), t, ask, dx, dy,
                   dz, d);
  }
  msocl_rows_f wx = u[0] + msocl_wide_share(d[0], d[3]),
               wy = u[1] + msocl_wide_share(d[1], d[3]),
               wz = u[2] + msocl_wide_share(d[2], d[3]);
  __constant const float *cf = (__constant const float *)col;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++)
    msocl_rows_collide(q[0], q[1], q[2], &wx, &wy, &wz, dt, cf, c, 0, 0.0f);
  (void)cf;
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, wx), v_out);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, wy), v_out + plane);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, wz), v_out + 2 * plane);
}

/* Implicit Euler's spring Jacobian J e for the springs to neighbours
 * d = (dx, dy, dz) away, added to *j.. where `on` (msocl_planes_jacobian's
 * arithmetic, lane by lane). */
static MSOCL_WIDE_INLINE void
msocl_wide_jacobian(msocl_rows_f dx, msocl_rows_f dy, msocl_rows_f dz,
                    msocl_rows_f rest, msocl_rows_f k, msocl_rows_f ex,
                    msocl_rows_f ey, msocl_rows_f ez, msocl_rows_m on,
                    msocl_rows_f *jx, msocl_rows_f *jy, msocl_rows_f *jz)
{
  const msocl_rows_f len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
  const msocl_rows_f ux = dx / len, uy = dy / len, uz = dz / len;
  const msocl_rows_f t = fmax(0.0f, 1.0f - MSOCL_DIV(rest, len));
  const msocl_rows_f s = MSOCL_DOT3(ux, uy, uz, ex, ey, ez);
  const msocl_rows_f ax = s * ux, ay = s * uy, az = s * uz;
  const msocl_rows_m live = on & (len > 0.0f);
  *jx += MSOCL_ROWS_SEL(live, k * (ax + t * (ex - ax)), 0.0f);
  *jy += MSOCL_ROWS_SEL(live, k * (ay + t * (ey - ay)), 0.0f);
  *jz += MSOCL_ROWS_SEL(live, k * (az + t * (ez - az)), 0.0f);
}

/* A CG kernel's term of a dot product, at the points' indices */
#define MSOCL_WIDE_DOT(val)                                                   \
  msocl_wide_store((val),                                                    \
                   dots + (z * (int)get_global_size(1) + y) * MSOCL_PLANES_NX, \
                   x0, MSOCL_PLANES_NX)

/* Implicit Euler's right-hand side (msocl_planes_ie_rhs's arithmetic):
 * b = dt (f + dt K v); x = 0, r = d = b; dots: b.b */
__kernel void msocl_planes_wide_ie_rhs(
    MSOCL_CONN, __global const float *p, __global const float *v,
    __global float *x_out, __global float *r_out, __global float *d_out,
    __global float *dots, __global const float *aux, int pitch, int slab,
    int plane, float4 gravity, float viscous, float dt)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], u[3], f[3];
  msocl_wide_force(MSOCL_CONN_ARGS, p, v, pitch, slab, plane, x0, y, z, q,
                   u, f);
  __global const float *py_ = p + plane, *pz_ = py_ + plane;
  __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
  msocl_rows_f kx = 0.0f, ky = 0.0f, kz = 0.0f;
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
    msocl_wide_jacobian(MSOCL_WIDE_NB(p) - q[0], MSOCL_WIDE_NB(py_) - q[1],
                        MSOCL_WIDE_NB(pz_) - q[2], rest, kk,
                        MSOCL_WIDE_NB(v) - u[0], MSOCL_WIDE_NB(vy_) - u[1],
                        MSOCL_WIDE_NB(vz_) - u[2], there, &kx, &ky, &kz);
  }
  const msocl_rows_f m = 1.0f / MSOCL_ROWS_LOAD(aux + a);
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
  const msocl_rows_f fx = msocl_wide_viscous(f[0], u[0], viscous),
                     fy = msocl_wide_viscous(f[1], u[1], viscous),
                     fz = msocl_wide_viscous(f[2], u[2], viscous);
  const msocl_rows_f
      bx = MSOCL_ROWS_SEL(held, 0.0f, dt * (fx + m * gravity.x + dt * kx)),
      by = MSOCL_ROWS_SEL(held, 0.0f, dt * (fy + m * gravity.y + dt * ky)),
      bz = MSOCL_ROWS_SEL(held, 0.0f, dt * (fz + m * gravity.z + dt * kz));
  const msocl_rows_f zero = 0.0f;
  MSOCL_WIDE_PUT(zero, x_out);
  MSOCL_WIDE_PUT(zero, x_out + plane);
  MSOCL_WIDE_PUT(zero, x_out + 2 * plane);
  MSOCL_WIDE_PUT(bx, r_out);
  MSOCL_WIDE_PUT(by, r_out + plane);
  MSOCL_WIDE_PUT(bz, r_out + 2 * plane);
  MSOCL_WIDE_PUT(bx, d_out);
  MSOCL_WIDE_PUT(by, d_out + plane);
  MSOCL_WIDE_PUT(bz, d_out + 2 * plane);
  MSOCL_WIDE_DOT(MSOCL_DOT3(bx, by, bz, bx, by, bz));
}

/* The conjugate gradients' product (msocl_planes_ie_apply's arithmetic
 * and slot order): ap = A d; dots: d.Ad */
__kernel void msocl_planes_wide_ie_apply(
    MSOCL_CONN, __global const float *p, __global const float *d,
    __global float *ap, __global float *dots, __global const float *aux,
    int pitch, int slab, int plane, float viscous, float dt)
{
  MSOCL_WIDE_AT;
  __global const float *py_ = p + plane, *pz_ = py_ + plane;
  __global const float *dy_ = d + plane, *dz_ = dy_ + plane;
  const msocl_rows_f qx = MSOCL_ROWS_LOAD(p + a), qy = MSOCL_ROWS_LOAD(py_ + a),
                     qz = MSOCL_ROWS_LOAD(pz_ + a);
  const msocl_rows_f ix = MSOCL_ROWS_LOAD(d + a), iy = MSOCL_ROWS_LOAD(dy_ + a),
                     iz = MSOCL_ROWS_LOAD(dz_ + a);
  msocl_rows_f kx = 0.0f, ky = 0.0f, kz = 0.0f;
  msocl_rows_f cx = 0.0f, cy = 0.0f, cz = 0.0f;
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
    const msocl_rows_f ux = MSOCL_WIDE_NB(p) - qx, uy = MSOCL_WIDE_NB(py_) - qy,
                       uz = MSOCL_WIDE_NB(pz_) - qz;
    const msocl_rows_f ex = MSOCL_WIDE_NB(d) - ix, ey = MSOCL_WIDE_NB(dy_) - iy,
                       ez = MSOCL_WIDE_NB(dz_) - iz;
    msocl_wide_jacobian(ux, uy, uz, rest, kk, ex, ey, ez, there, &kx, &ky,
                        &kz);
#ifdef MSOCL_DAMPING
    const msocl_rows_f len2 = MSOCL_DOT3(ux, uy, uz, ux, uy, uz);
    const msocl_rows_f h =
        cc * MSOCL_DIV(MSOCL_DOT3(ux, uy, uz, ex, ey, ez), len2);
    const msocl_rows_m live = there & (len2 > 0.0f);
    cx += MSOCL_ROWS_SEL(live, h * ux, 0.0f);
    cy += MSOCL_ROWS_SEL(live, h * uy, 0.0f);
    cz += MSOCL_ROWS_SEL(live, h * uz, 0.0f);
#endif
  }
  const msocl_rows_f m = 1.0f / MSOCL_ROWS_LOAD(aux + a);
#ifdef MSOCL_VISCOUS
  const msocl_rows_f mv = m + dt * viscous;
#else
  const msocl_rows_f mv = m;
#endif
  (void)viscous;
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
  const msocl_rows_f
      yx = MSOCL_ROWS_SEL(held, ix, mv * ix - dt * cx - (dt * dt) * kx),
      yy = MSOCL_ROWS_SEL(held, iy, mv * iy - dt * cy - (dt * dt) * ky),
      yz = MSOCL_ROWS_SEL(held, iz, mv * iz - dt * cz - (dt * dt) * kz);
  MSOCL_WIDE_PUT(yx, ap);
  MSOCL_WIDE_PUT(yy, ap + plane);
  MSOCL_WIDE_PUT(yz, ap + 2 * plane);
  MSOCL_WIDE_DOT(MSOCL_DOT3(ix, iy, iz, yx, yy, yz));
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

/* The planes kernels: symplectic Euler's two passes (or fused), explicit
 * Euler, velocity Verlet's and RK4's stages and both strain limits'
 * sweeps (planes.h says how the planes are laid out, and why). */
#include "planes.h"

#if defined(MSOCL_PLANES)
MSOCL_PLANES_GATHER(msocl_planes_velocity,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, MSOCL_PLANES_ARG_NAMES))
{
  MSOCL_PLANES_KICK;
  if (MSOCL_PLANES_LIVE) {
    MSOCL_PLANES_STORE_V;
  }
}

/* Both passes in one kernel (tuning.fused): the point
 * moves by its new velocity at once; others read only the old p. */
MSOCL_PLANES_GATHER(msocl_planes_fused,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global float *p_out, MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, p_out,
                     MSOCL_PLANES_ARG_NAMES))
{
  MSOCL_PLANES_KICK;
  if (MSOCL_PLANES_LIVE) {
    __global const float *py_ = p + plane, *pz_ = py_ + plane;
    __global float *qy = p_out + plane, *qz = qy + plane;
    const float cx = p[a], cy = py_[a], cz = pz_[a];
    MSOCL_PLANES_STORE_V;
    p_out[a] = pinned ? cx : cx + dt * vx;
    qy[a] = pinned ? cy : cy + dt * vy;
    qz[a] = pinned ? cz : cz + dt * vz;
  }
}

__kernel void msocl_planes_position(__global const float *p,
                                    __global const float *v,
                                    __global float *p_out,
                                    __global const float *aux, int nx,
                                    int pitch, int slab, int plane, float dt)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (x < nx) {
    /* three statements, not a loop: an inner loop would stop the
     * vectorizer (it takes the innermost loop, over the work-items) */
    __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
    __global const float *py_ = p + plane, *pz_ = py_ + plane;
    __global float *oy = p_out + plane, *oz = oy + plane;
    const float cx = p[a], cy = py_[a], cz = pz_[a];
    p_out[a] = pinned ? cx : cx + dt * v[a];
    oy[a] = pinned ? cy : cy + dt * vy_[a];
    oz[a] = pinned ? cz : cz + dt * vz_[a];
  }
}

/* Velocity Verlet in planes.
 * Drift: v+ = v + dt/2 a with the collision response on it, in place (no
 * other point reads it here), and p' = p + dt v+. */
__kernel void msocl_planes_drift(__global const float *p, __global float *v,
                                 __global const float *acc,
                                 __global float *p_out,
                                 __global const float *aux, int nx,
                                 int pitch, int slab, int plane, float dt,
                                 __constant float4 *col)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  const float h = 0.5f * dt;
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a];
  float vx = v[a] + h * acc[a], vy = v[plane + a] + h * acc[plane + a],
        vz = v[2 * plane + a] + h * acc[2 * plane + a];
  msocl_planes_collide(px, py, pz, &vx, &vy, &vz, dt, col, 1.0f);
  if (x < nx) {
    p_out[a] = pinned ? px : px + dt * vx;
    p_out[plane + a] = pinned ? py : py + dt * vy;
    p_out[2 * plane + a] = pinned ? pz : pz + dt * vz;
    v[a] = pinned ? 0.0f : vx;
    v[plane + a] = pinned ? 0.0f : vy;
    v[2 * plane + a] = pinned ? 0.0f : vz;
  }
}

/* Kick: a' = a(p', v+), v' = v+ + dt/2 a'; a' kept for the next drift. */
MSOCL_PLANES_GATHER(msocl_planes_vkick,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global float *acc_out, MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, acc_out,
                     MSOCL_PLANES_ARG_NAMES))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, p, v, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a], h = 0.5f * dt;
  const float ax = fx * im + gravity.x, ay = fy * im + gravity.y,
              az = fz * im + gravity.z;
  float vx = v[a] + h * ax, vy = v[plane + a] + h * ay,
        vz = v[2 * plane + a] + h * az;
  msocl_planes_air(air, &vx, &vy, &vz);
  (void)col;
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (MSOCL_PLANES_LIVE) {
    v_out[a] = pinned ? 0.0f : vx;
    v_out[plane + a] = pinned ? 0.0f : vy;
    v_out[2 * plane + a] = pinned ? 0.0f : vz;
    acc_out[a] = pinned ? 0.0f : ax;
    acc_out[plane + a] = pinned ? 0.0f : ay;
    acc_out[2 * plane + a] = pinned ? 0.0f : az;
  }
}

/* Projection out of the colliders (explicit methods: a point found inside a
 * collider at the end of the step goes back to its surface and loses its
 * inward speed). A moving collider's table holds its shape at the step's
 * start: its gap at the step's end is the gap at p - dt u, to first order,
 * and the response acts on the velocity relative to its surface. */
static MSOCL_PLANES_INLINE void msocl_planes_project(float *px, float *py, float *pz, float *vx,
                                 float *vy, float *vz, float dt,
                                 __constant float4 *col)
{
  __constant const float *cf = (__constant const float *)col;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++) {
#define cv(k) MSOCL_PLANES_COL(cf, c, k)
    MSOCL_PLANES_SURFACE(float, cv, *px, *py, *pz);
    const bool moving = cv(2) != 0.0f;
#undef cv
    const float ex = moving ? *px - dt * ux : *px,
                ey = moving ? *py - dt * uy : *py,
                ez = moving ? *pz - dt * uz : *pz;
    float nx, ny, nz;
    const float g = msocl_planes_gap(ex, ey, ez, cf, c, &nx, &ny, &nz);
    const bool in = g < 0.0f;
    const float qx = *px - g * nx, qy = *py - g * ny, qz = *pz - g * nz;
    const float ox = moving ? *vx - ux : *vx, oy = moving ? *vy - uy : *vy,
                oz = moving ? *vz - uz : *vz;
    const float vn = MSOCL_DOT3(ox, oy, oz, nx, ny, nz);
    const bool back = in && vn < 0.0f;
    float wx = ox - vn * nx, wy = oy - vn * ny, wz = oz - vn * nz;
    const float fr = MSOCL_PLANES_COL(cf, c, 1);
    wx = wx - fr * wx;
    wy = wy - fr * wy;
    wz = wz - fr * wz;
    wx = moving ? wx + ux : wx;
    wy = moving ? wy + uy : wy;
    wz = moving ? wz + uz : wz;
    *px = in ? qx : *px;
    *py = in ? qy : *py;
    *pz = in ? qz : *pz;
    *vx = back ? wx : *vx;
    *vy = back ? wy : *vy;
    *vz = back ? wz : *vz;
  }
  (void)cf;
}

/* Forward Euler in planes: p' = p + dt v, v' = v + dt
 * a(p, v), times air, projected out of the colliders; pinned points
 * stay. */
MSOCL_PLANES_GATHER(msocl_planes_euler,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global float *p_out, MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, p_out,
                     MSOCL_PLANES_ARG_NAMES))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, p, v, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a];
  const int ay = plane + a, az = 2 * plane + a;
  float px = p[a] + dt * v[a], py = p[ay] + dt * v[ay],
        pz = p[az] + dt * v[az];
  float vx = v[a] + dt * (fx * im + gravity.x),
        vy = v[ay] + dt * (fy * im + gravity.y),
        vz = v[az] + dt * (fz * im + gravity.z);
  msocl_planes_air(air, &vx, &vy, &vz);
  msocl_planes_project(&px, &py, &pz, &vx, &vy, &vz, dt, col);
  const bool pinned = MSOCL_PLANES_PINNED(aux[ay]);
  if (MSOCL_PLANES_LIVE) {
    p_out[a] = pinned ? p[a] : px;
    p_out[ay] = pinned ? p[ay] : py;
    p_out[az] = pinned ? p[az] : pz;
    v_out[a] = pinned ? 0.0f : vx;
    v_out[ay] = pinned ? 0.0f : vy;
    v_out[az] = pinned ? 0.0f : vz;
  }
}

/* One RK4 stage in planes; mode a constant in each of
 * the three kernels below, so its branches fold away. */
static MSOCL_PLANES_INLINE void msocl_planes_rk4(MSOCL_CONN, const int pass, const int x,
                             const int y, const int z,
                             __global const float *p0,
                             __global const float *v0,
                             __global const float *sp,
                             __global const float *sv, __global float *sum_p,
                             __global float *sum_v, __global float *np,
                             __global float *nv, __global const float *aux,
                             int pitch, int slab, int plane, float4 gravity,
                             float viscous, float air, float dt,
                             __constant float4 *col, float c, const int mode)
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, sp, sv, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a];
  const float kv[3] = {fx * im + gravity.x, fy * im + gravity.y,
                       fz * im + gravity.z};
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  float p[3], v[3];
  if (mode == 2) {
    const float h = dt / 6.0f;
#pragma unroll
    for (int q = 0; q < 3; q++) {
      p[q] = p0[q * plane + a] + h * (sum_p[q * plane + a] + sv[q * plane + a]);
      v[q] = v0[q * plane + a] + h * (sum_v[q * plane + a] + kv[q]);
#ifdef MSOCL_AIR
      v[q] = air * v[q];
#endif
    }
    msocl_planes_project(&p[0], &p[1], &p[2], &v[0], &v[1], &v[2], dt,
                         col);
  } else {
    const float h = c * dt;
#pragma unroll
    for (int q = 0; q < 3; q++) {
      const float kp = sv[q * plane + a];
      const float sp_ = mode == 0 ? kp : sum_p[q * plane + a] + 2.0f * kp;
      const float sv_ = mode == 0 ? kv[q] : sum_v[q * plane + a] + 2.0f * kv[q];
      if (MSOCL_PLANES_LIVE) {
        sum_p[q * plane + a] = sp_;
        sum_v[q * plane + a] = sv_;
      }
      p[q] = p0[q * plane + a] + h * kp;
      v[q] = v0[q * plane + a] + h * kv[q];
    }
  }
  (void)air;
  (void)col;
  if (MSOCL_PLANES_LIVE) {
#pragma unroll
    for (int q = 0; q < 3; q++) {
      np[q * plane + a] = pinned ? p0[q * plane + a] : p[q];
      nv[q * plane + a] = pinned ? 0.0f : v[q];
    }
  }
}

#define MSOCL_PLANES_RK4_NAMES                                                \
  (MSOCL_CONN_ARGS, p0, v0, sp, sv, sum_p, sum_v, np, nv,                    \
   MSOCL_PLANES_ARG_NAMES, c)
#define MSOCL_PLANES_RK4_CALL(mode)                                           \
  msocl_planes_rk4(MSOCL_CONN_ARGS, pass, x, y, z, p0, v0, sp, sv, sum_p,    \
                   sum_v, np, nv, aux, pitch, slab, plane, gravity, viscous, \
                   air, dt, col, c, mode)

MSOCL_PLANES_GATHER(msocl_planes_rk4_first, MSOCL_PLANES_RK4_ARGS,
                    MSOCL_PLANES_RK4_NAMES)
{
  MSOCL_PLANES_RK4_CALL(0);
}

MSOCL_PLANES_GATHER(msocl_planes_rk4_middle, MSOCL_PLANES_RK4_ARGS,
                    MSOCL_PLANES_RK4_NAMES)
{
  MSOCL_PLANES_RK4_CALL(1);
}

MSOCL_PLANES_GATHER(msocl_planes_rk4_last, MSOCL_PLANES_RK4_ARGS,
                    MSOCL_PLANES_RK4_NAMES)
{
  MSOCL_PLANES_RK4_CALL(2);
}

/* Provot's strain limiting in planes: a Jacobi
 * sweep from p into p_out, each point moved by the size-weighted average
 * of what its over-long springs ask (half the excess, a pinned
 * neighbour's spring all of it); pinned points stay. (In
 * float4 a missing neighbour is the point itself, whose zero length asks
 * nothing; here `there` masks it.) */
/* One slot's ask in Provot's sweep on the point at q[0..2], added to
 * d[0..3] (the move and the weight) where the spring is over its limit. */
static MSOCL_PLANES_INLINE void msocl_planes_provot(__global const float *p,
                                __global const float *aux, int plane,
                                float limit, const float *q, int b,
                                bool there, float rest, float *d)
{
  const float dx = p[b] - q[0], dy = p[plane + b] - q[1],
              dz = p[2 * plane + b] - q[2];
  const float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
  const float over = len - (1.0f + limit) * rest;
  const float ask = (MSOCL_PLANES_PINNED(aux[plane + b]) ? 1.0f : 0.5f) *
                    over;
  const float t = ask * MSOCL_DIV(ask, len);
  const bool on = there && over > 0.0f;
  d[0] += on ? t * dx : 0.0f;
  d[1] += on ? t * dy : 0.0f;
  d[2] += on ? t * dz : 0.0f;
  d[3] += on ? ask : 0.0f;
}

MSOCL_PLANES_GATHER(msocl_planes_strain,
                    (MSOCL_CONN, __global const float *p,
                     __global float *p_out, __global const float *aux,
                     int pitch, int slab, int plane, float limit),
                    (MSOCL_CONN_ARGS, p, p_out, aux, pitch, slab, plane,
                     limit))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a];
  const float q[3] = {px, py, pz};
  float d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_PLANES_SLOTS(pass); s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    (void)kk; (void)cc;
    msocl_planes_provot(p, aux, plane, limit, q, b, there, rest, d);
  }
#ifdef MSOCL_SPILL
  MSOCL_PLANES_SPILLS {
    MSOCL_PLANES_SPILL_NEIGHBOR(o);
    (void)kk; (void)cc;
    msocl_planes_provot(p, aux, plane, limit, q, b, there, rest, d);
  }
#endif
  float dpx = d[0], dpy = d[1], dpz = d[2];
  const float weight = d[3];
  if (weight > 0.0f) {
    dpx = MSOCL_DIV(dpx, weight);
    dpy = MSOCL_DIV(dpy, weight);
    dpz = MSOCL_DIV(dpz, weight);
  }
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (MSOCL_PLANES_LIVE) {
    p_out[a] = pinned ? px : px + dpx;
    p_out[plane + a] = pinned ? py : py + dpy;
    p_out[2 * plane + a] = pinned ? pz : pz + dpz;
  }
}

/* And its end: v += (corrected - p) / dt, then p
 * takes the corrected position. */
__kernel void msocl_planes_commit(__global float *p,
                                  __global const float *corrected,
                                  __global float *v, int nx, int pitch,
                                  int slab, int plane, float dt)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  if (x < nx) {
    const float cx = corrected[a], cy = corrected[plane + a],
                cz = corrected[2 * plane + a];
    v[a] = v[a] + MSOCL_DIV(cx - p[a], dt);
    v[plane + a] = v[plane + a] + MSOCL_DIV(cy - p[plane + a], dt);
    v[2 * plane + a] = v[2 * plane + a] + MSOCL_DIV(cz - p[2 * plane + a], dt);
    p[a] = cx;
    p[plane + a] = cy;
    p[2 * plane + a] = cz;
  }
}

/* The velocity kind in planes: a Jacobi sweep
 * from v into v_out at the step's starting positions p, each point's
 * velocity changed by the size-weighted average of what its springs ask
 * (the relative speed along a spring beyond what brings it to the limit
 * within the step: half of it, a pinned neighbour's spring all of it),
 * then the collision response again without friction. */
/* One slot's ask in the velocity kind's sweep on the point whose position
 * and velocity are q[0..5], added to d[0..3] (the change and the weight)
 * where the spring would pass its limit. */
static MSOCL_PLANES_INLINE void msocl_planes_vassilev(__global const float *p,
                                  __global const float *v,
                                  __global const float *aux, int plane,
                                  float limit, float dt, const float *q,
                                  int b, bool there, float rest, float *d)
{
  const float dx = p[b] - q[0], dy = p[plane + b] - q[1],
              dz = p[2 * plane + b] - q[2];
  const float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
  const float allowed = MSOCL_DIV((1.0f + limit) * rest - len, dt);
  const float excess =
      MSOCL_DIV(MSOCL_DOT3(v[b] - q[3], v[plane + b] - q[4],
                           v[2 * plane + b] - q[5], dx, dy, dz),
                len) -
      allowed;
  const float ask =
      (MSOCL_PLANES_PINNED(aux[plane + b]) ? 1.0f : 0.5f) * excess;
  const float t = ask * MSOCL_DIV(ask, len);
  const bool on = there && len > 0.0f && excess > 0.0f;
  d[0] += on ? t * dx : 0.0f;
  d[1] += on ? t * dy : 0.0f;
  d[2] += on ? t * dz : 0.0f;
  d[3] += on ? ask : 0.0f;
}

MSOCL_PLANES_GATHER(msocl_planes_strain_v,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global const float *aux, int pitch, int slab,
                     int plane, float limit, float dt,
                     __constant float4 *col),
                    (MSOCL_CONN_ARGS, p, v, v_out, aux, pitch, slab, plane,
                     limit, dt, col))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a];
  const float vx = v[a], vy = v[plane + a], vz = v[2 * plane + a];
  const float q[6] = {px, py, pz, vx, vy, vz};
  float d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_PLANES_SLOTS(pass); s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    (void)kk; (void)cc;
    msocl_planes_vassilev(p, v, aux, plane, limit, dt, q, b, there, rest, d);
  }
#ifdef MSOCL_SPILL
  MSOCL_PLANES_SPILLS {
    MSOCL_PLANES_SPILL_NEIGHBOR(o);
    (void)kk; (void)cc;
    msocl_planes_vassilev(p, v, aux, plane, limit, dt, q, b, there, rest, d);
  }
#endif
  float dvx = d[0], dvy = d[1], dvz = d[2];
  const float weight = d[3];
  if (weight > 0.0f) {
    dvx = MSOCL_DIV(dvx, weight);
    dvy = MSOCL_DIV(dvy, weight);
    dvz = MSOCL_DIV(dvz, weight);
  }
  float wx = vx + dvx, wy = vy + dvy, wz = vz + dvz;
  msocl_planes_collide(px, py, pz, &wx, &wy, &wz, dt, col, 0.0f);
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (MSOCL_PLANES_LIVE) {
    v_out[a] = pinned ? 0.0f : wx;
    v_out[plane + a] = pinned ? 0.0f : wy;
    v_out[2 * plane + a] = pinned ? 0.0f : wz;
  }
}

#endif

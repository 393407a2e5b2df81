/* Backward Euler in the Baraff-Witkin form (Large steps in cloth
 * simulation, 1998): one linearised step
 *   (M - dt D - dt^2 K) dv = dt (f(p, v) + dt K v),  v' = v + dv,
 *   p' = p + dt v'
 * solved by conjugate gradients (lib/engine/cg.c) without forming the
 * matrix: each product is a gather over the point's springs with the
 * spring Jacobian
 *   J = k (u u^T + max(0, 1 - r/l) (I - u u^T))
 * (the clamp keeps J positive semi-definite for compressed springs, so the
 * system stays symmetric positive definite), D from the dashpots (c u u^T)
 * and viscous damping. Pinned points have dv = 0: identity rows, zero
 * right-hand side. A planes work-group is a row's stretch, not 64
 * consecutive points, so each kernel writes its point's term of a dot
 * product to dots[i] (i its index) and msocl_sum_points adds them in
 * work-groups of 64 in index order: the same partials, host sums, alphas
 * and betas on every layout and split. */
#include "planes.h"

#define MSOCL_CG_GROUP 64

/* Sums v over the work-group into partial[group].x. */
static void msocl_group_sum(float v, __local float *part,
                            __global float4 *partial)
{
  int l = get_local_id(0);
  part[l] = v;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int w = MSOCL_CG_GROUP / 2; w > 0; w >>= 1) {
    if (l < w)
      part[l] += part[l + w];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0)
    partial[get_group_id(0)] = (float4)(part[0], 0.0f, 0.0f, 0.0f);
}

/* dots[i] in groups of 64 into partial[group].x (any device). */
__kernel __attribute__((reqd_work_group_size(MSOCL_CG_GROUP, 1, 1)))
void msocl_sum_points(__global const float *dots, __global float4 *partial,
                      int n)
{
  __local float part[MSOCL_CG_GROUP];
  const int i = get_global_id(0);
  msocl_group_sum(i < n ? dots[i] : 0.0f, part, partial);
}

#if defined(MSOCL_PLANES)

/* The point's float4 index, (z ny + y) nx + x. */
#define MSOCL_PLANES_INDEX(nx) ((z * (int)get_global_size(1) + y) * (nx) + x)

/* J e for the spring from the point to a neighbour d = (dx, dy, dz) away,
 * added to *j.. where `on`. */
static MSOCL_PLANES_INLINE void msocl_planes_jacobian(float dx, float dy, float dz, float rest,
                                  float k, float ex, float ey, float ez,
                                  bool on, float *jx, float *jy, float *jz)
{
  const float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
  const float ux = dx / len, uy = dy / len, uz = dz / len;
  const float t = fmax(0.0f, 1.0f - MSOCL_DIV(rest, len));
  const float s = MSOCL_DOT3(ux, uy, uz, ex, ey, ez);
  const float ax = s * ux, ay = s * uy, az = s * uz;
  const bool live = on && len > 0.0f;
  *jx += live ? k * (ax + t * (ex - ax)) : 0.0f;
  *jy += live ? k * (ay + t * (ey - ay)) : 0.0f;
  *jz += live ? k * (az + t * (ez - az)) : 0.0f;
}

/* One slot's J (v_b - v_a) for the point at a, added to k[0..2]. */
static MSOCL_PLANES_INLINE void msocl_planes_stiff(__global const float *p,
                               __global const float *v, int plane, int a,
                               int b, bool there, float rest, float kk,
                               float *k)
{
  __global const float *py_ = p + plane, *pz_ = py_ + plane;
  __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
  msocl_planes_jacobian(p[b] - p[a], py_[b] - py_[a], pz_[b] - pz_[a], rest,
                        kk, v[b] - v[a], vy_[b] - vy_[a], vz_[b] - vz_[a],
                        there, &k[0], &k[1], &k[2]);
}

/* b = dt (f + dt K v); x = 0, r = d = b; dots: b.b */
MSOCL_PLANES_GATHER(msocl_planes_ie_rhs,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *x_out,
                     __global float *r_out, __global float *d_out,
                     __global float *dots, __global const float *aux,
                     int pitch, int slab, int plane, float4 gravity,
                     float viscous, float dt),
                    (MSOCL_CONN_ARGS, p, v, x_out, r_out, d_out, dots, aux,
                     pitch, slab, plane, gravity, viscous, dt))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, p, v, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  float k[3] = {0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_PLANES_SLOTS(pass); s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    (void)cc;
    msocl_planes_stiff(p, v, plane, a, b, there, rest, kk, k);
  }
#ifdef MSOCL_SPILL
  MSOCL_PLANES_SPILLS {
    MSOCL_PLANES_SPILL_NEIGHBOR(o);
    (void)cc;
    msocl_planes_stiff(p, v, plane, a, b, there, rest, kk, k);
  }
#endif
  const float kx = k[0], ky = k[1], kz = k[2];
  const float m = 1.0f / aux[a];
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  const float bx = pinned ? 0.0f : dt * (fx + m * gravity.x + dt * kx);
  const float by = pinned ? 0.0f : dt * (fy + m * gravity.y + dt * ky);
  const float bz = pinned ? 0.0f : dt * (fz + m * gravity.z + dt * kz);
  if (MSOCL_PLANES_LIVE) {
    x_out[a] = x_out[plane + a] = x_out[2 * plane + a] = 0.0f;
    r_out[a] = d_out[a] = bx;
    r_out[plane + a] = d_out[plane + a] = by;
    r_out[2 * plane + a] = d_out[2 * plane + a] = bz;
    dots[MSOCL_PLANES_INDEX(MSOCL_PLANES_NX)] = MSOCL_DOT3(bx, by, bz, bx, by, bz);
  }
}

/* One slot's part of A d for the point whose position and direction are
 * q[0..5]: J (d_b - d_a) added to k[0..2], the dashpot's
 * c u u^T (d_b - d_a) to c[0..2]. */
static MSOCL_PLANES_INLINE void msocl_planes_product(__global const float *p,
                                 __global const float *d, int plane,
                                 const float *q, int b, bool there,
                                 float rest, float kk, float cc, float *k,
                                 float *c)
{
  const float qx = p[b] - q[0], qy = p[plane + b] - q[1],
              qz = p[2 * plane + b] - q[2];
  const float ex = d[b] - q[3], ey = d[plane + b] - q[4],
              ez = d[2 * plane + b] - q[5];
  msocl_planes_jacobian(qx, qy, qz, rest, kk, ex, ey, ez, there, &k[0],
                        &k[1], &k[2]);
#ifdef MSOCL_DAMPING
  const float len2 = MSOCL_DOT3(qx, qy, qz, qx, qy, qz);
  const float u = cc * MSOCL_DIV(MSOCL_DOT3(qx, qy, qz, ex, ey, ez), len2);
  const bool live = there && len2 > 0.0f;
  c[0] += live ? u * qx : 0.0f;
  c[1] += live ? u * qy : 0.0f;
  c[2] += live ? u * qz : 0.0f;
#endif
  (void)cc; (void)c; /* the dashpots' */
}

/* ap = A d; dots: d.Ad */
MSOCL_PLANES_GATHER(msocl_planes_ie_apply,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *d, __global float *ap,
                     __global float *dots, __global const float *aux,
                     int pitch, int slab, int plane, float viscous,
                     float dt),
                    (MSOCL_CONN_ARGS, p, d, ap, dots, aux, pitch, slab,
                     plane, viscous, dt))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  const float ix = d[a], iy = d[plane + a], iz = d[2 * plane + a];
  const float q[6] = {p[a], p[plane + a], p[2 * plane + a], ix, iy, iz};
  float k[3] = {0.0f, 0.0f, 0.0f}, c[3] = {0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_PLANES_SLOTS(pass); s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    msocl_planes_product(p, d, plane, q, b, there, rest, kk, cc, k, c);
  }
#ifdef MSOCL_SPILL
  MSOCL_PLANES_SPILLS {
    MSOCL_PLANES_SPILL_NEIGHBOR(o);
    msocl_planes_product(p, d, plane, q, b, there, rest, kk, cc, k, c);
  }
#endif
  const float kx = k[0], ky = k[1], kz = k[2], cx = c[0], cy = c[1],
              cz = c[2];
  const float m = 1.0f / aux[a];
#ifdef MSOCL_VISCOUS
  const float mv = m + dt * viscous;
#else
  const float mv = m;
#endif
  (void)viscous;
  (void)cx; (void)cy; (void)cz; /* the dashpots' */
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  const float yx = pinned ? ix : mv * ix - dt * cx - (dt * dt) * kx;
  const float yy = pinned ? iy : mv * iy - dt * cy - (dt * dt) * ky;
  const float yz = pinned ? iz : mv * iz - dt * cz - (dt * dt) * kz;
  if (MSOCL_PLANES_LIVE) {
    ap[a] = yx;
    ap[plane + a] = yy;
    ap[2 * plane + a] = yz;
    dots[MSOCL_PLANES_INDEX(MSOCL_PLANES_NX)] = MSOCL_DOT3(ix, iy, iz, yx, yy, yz);
  }
}

/* x += alpha d; r -= alpha ap; dots: r.r */
__kernel void msocl_planes_cg_step(__global float *xs, __global float *r,
                                   __global const float *d,
                                   __global const float *ap,
                                   __global float *dots, int nx, int pitch,
                                   int slab, int plane, float alpha)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  if (x >= nx)
    return;
  const int ay = plane + a, az = 2 * plane + a;
  xs[a] = xs[a] + alpha * d[a];
  xs[ay] = xs[ay] + alpha * d[ay];
  xs[az] = xs[az] + alpha * d[az];
  const float rx = r[a] - alpha * ap[a], ry = r[ay] - alpha * ap[ay],
              rz = r[az] - alpha * ap[az];
  r[a] = rx;
  r[ay] = ry;
  r[az] = rz;
  dots[MSOCL_PLANES_INDEX(nx)] = MSOCL_DOT3(rx, ry, rz, rx, ry, rz);
}

/* d = r + beta d */
__kernel void msocl_planes_cg_direction(__global float *d,
                                        __global const float *r, int nx,
                                        int pitch, int slab, int plane,
                                        float beta)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  if (x >= nx)
    return;
  const int ay = plane + a, az = 2 * plane + a;
  d[a] = r[a] + beta * d[a];
  d[ay] = r[ay] + beta * d[ay];
  d[az] = r[az] + beta * d[az];
}

/* v' = v + dv (times air), the collision response on
 * it; pinned points 0. */
__kernel void msocl_planes_ie_finish(__global const float *p,
                                     __global const float *v,
                                     __global const float *dv,
                                     __global float *v_out,
                                     __global const float *aux, int nx,
                                     int pitch, int slab, int plane,
                                     float air, float dt,
                                     __constant float4 *col)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  const int ay = plane + a, az = 2 * plane + a;
  float vx = v[a] + dv[a], vy = v[ay] + dv[ay], vz = v[az] + dv[az];
  msocl_planes_air(air, &vx, &vy, &vz);
  msocl_planes_collide(p[a], p[ay], p[az], &vx, &vy, &vz, dt, col, 1.0f);
  const bool pinned = MSOCL_PLANES_PINNED(aux[ay]);
  if (x < nx) {
    v_out[a] = pinned ? 0.0f : vx;
    v_out[ay] = pinned ? 0.0f : vy;
    v_out[az] = pinned ? 0.0f : vz;
  }
}

#endif

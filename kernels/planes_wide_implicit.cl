/* Implicit Euler's gathering kernels in explicit vectors (wide.h): the
 * right-hand side and the conjugate gradients' product, the scalar
 * kernels' arithmetic and slot order (planes_implicit.cl), bitwise them
 * (tests/check_planes.c): PoCL left those scalar on its AVX2 target
 * (docs/PERFORMANCE.md). */
#include "planes.h"
#include "wide.h"

#ifdef MSOCL_ROWS
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
  msocl_wide_force(MSOCL_CONN_ARGS, 0, p, v, pitch, slab, plane, x0, y, z, q,
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

/* The EDGES layout - the second seed's per-spring pass, without its float
 * atomics: a work-item per spring computes the spring's (and dashpot's)
 * force as a coefficient of the spring's length vector, once for both
 * ends; a per-point pass then sums t (q - p) over the point's springs in
 * BUFFER's slot order (a table the host builds) and integrates. The
 * coefficient is even in the spring's direction and q - p is odd, so each
 * end's term is bitwise what BUFFER's gather computes there, added in the
 * same order: the result is BUFFER's, bit for bit, run after run. Needs
 * common.cl and step.cl before it (the library builds it with the BUFFER
 * macros and no slots, and MSOCL_CLASSES where the springs' values fit 256
 * classes). */

/* Coefficients per spring: t[s] = k (l - r) / l, u[s] = c (dv . d) / l^2,
 * in msocl_force's scalar arithmetic lane by lane; 0 where the spring has
 * no length, as BUFFER's select adds zeros there. Eight springs a
 * work-item, so that the square roots and divisions take one SIMD
 * instruction for eight (PoCL does not vectorise across work-items here);
 * the host pads the lists to a multiple of 8 with springs of no length. */
#define MSOCL_GATHER8(buf, j, c)                                              \
  (float8)(buf[j.s0].c, buf[j.s1].c, buf[j.s2].c, buf[j.s3].c, buf[j.s4].c,  \
           buf[j.s5].c, buf[j.s6].c, buf[j.s7].c)

__kernel void msocl_edges_force(__global const int2 *ij, MSOCL_RK,
                                __global const float4 *pos,
                                __global const float4 *vel,
                                __global float *t_out,
                                __global float *u_out, int groups)
{
  int g = get_global_id(0);
  if (g >= groups)
    return;
  int16 e = vload16(g, (__global const int *)ij);
  int8 a = e.even, b = e.odd;
#ifdef MSOCL_CLASSES
  /* a byte a spring naming its (rest, k, dashpot) */
  const uchar8 q = vload8(g, rk);
  const float4 v0 = dmp[q.s0], v1 = dmp[q.s1], v2 = dmp[q.s2],
               v3 = dmp[q.s3], v4 = dmp[q.s4], v5 = dmp[q.s5],
               v6 = dmp[q.s6], v7 = dmp[q.s7];
  const float8 rest = (float8)(v0.x, v1.x, v2.x, v3.x, v4.x, v5.x, v6.x, v7.x);
  const float8 k = (float8)(v0.y, v1.y, v2.y, v3.y, v4.y, v5.y, v6.y, v7.y);
#ifdef MSOCL_DAMPING
  const float8 cd = (float8)(v0.z, v1.z, v2.z, v3.z, v4.z, v5.z, v6.z, v7.z);
#endif
#else
  const float16 c = vload16(g, (__global const float *)rk);
  const float8 rest = c.even, k = c.odd;
#ifdef MSOCL_DAMPING
  const float8 cd = vload8(g, dmp);
#endif
#endif
  float8 dx = MSOCL_GATHER8(pos, b, x) - MSOCL_GATHER8(pos, a, x);
  float8 dy = MSOCL_GATHER8(pos, b, y) - MSOCL_GATHER8(pos, a, y);
  float8 dz = MSOCL_GATHER8(pos, b, z) - MSOCL_GATHER8(pos, a, z);
  float8 len2 = dx * dx + dy * dy + dz * dz, len = MSOCL_SQRT(len2);
  float8 t = k * MSOCL_DIV(len - rest, len);
  vstore8(select((float8)(0.0f), t, len > 0.0f), g, t_out);
#ifdef MSOCL_DAMPING
  float8 wx = MSOCL_GATHER8(vel, b, x) - MSOCL_GATHER8(vel, a, x);
  float8 wy = MSOCL_GATHER8(vel, b, y) - MSOCL_GATHER8(vel, a, y);
  float8 wz = MSOCL_GATHER8(vel, b, z) - MSOCL_GATHER8(vel, a, z);
  float8 u = cd * MSOCL_DIV(wx * dx + wy * dy + wz * dz, len2);
  vstore8(select((float8)(0.0f), u, len2 > 0.0f), g, u_out);
#endif
  (void)vel; (void)u_out;
}

/* Eight points a work-item, a lane each: slot s of points 8b .. 8b + 7 is
 * tab[16 (b width + s) + l] (other end) and [... + 8 + l] (spring), the
 * points' first `width` springs in slot order, padded with the point
 * itself and a spring of no length (adding +0, as BUFFER's free slots
 * do). Each lane sums its own point's terms in order, fx += sx as
 * msocl_force adds them, spring then dashpot; springs past the table
 * (off[i] + width .. off[i + 1] of the CSR list inc, a hub's) follow one
 * at a time. Then each point kicks and moves by its new velocity at once,
 * as msocl_fused does: other points read only pos, so this is the two
 * passes' result in one. */

/* x, y, z of the eight points from p on */
#define MSOCL_ROW8(p, x8, y8, z8)                                             \
  do {                                                                        \
    const float16 lo_ = vload16(0, (__global const float *)(p));             \
    const float16 hi_ = vload16(0, (__global const float *)(p) + 16);        \
    x8 = (float8)(lo_.s048c, hi_.s048c);                                      \
    y8 = (float8)(lo_.s159d, hi_.s159d);                                      \
    z8 = (float8)(lo_.s26ae, hi_.s26ae);                                      \
  } while (0)
#define MSOCL_COEF8(buf, j)                                                   \
  (float8)(buf[j.s0], buf[j.s1], buf[j.s2], buf[j.s3], buf[j.s4], buf[j.s5],  \
           buf[j.s6], buf[j.s7])

__kernel void msocl_edges_velocity(__global const int *tab,
                                   __global const uchar *run, int width,
                                   __global const int *off,
                                   __global const int2 *inc,
                                   __global const float *tc,
                                   __global const float *uc,
                                   __global const float4 *pos,
                                   __global const float4 *vel,
                                   __global float4 *pos_out,
                                   __global float4 *vel_out,
                                   __global const float *inv_mass,
                                   float4 gravity, float viscous, float air,
                                   float dt, __constant float4 *col,
                                   int ncol, int n)
{
  const int b = get_global_id(0), i0 = 8 * b;
  if (i0 >= n)
    return;
  /* run: in every slot the eight other ends are consecutive points (a
   * grid's rows; the block's own points all < n), read with two vector
   * loads, not eight */
  const uchar r = run[b];
  float8 px, py, pz;
  if (r) {
    MSOCL_ROW8(pos + i0, px, py, pz);
  } else {
    const int8 me = min(i0 + (int8)(0, 1, 2, 3, 4, 5, 6, 7), n - 1);
    px = MSOCL_GATHER8(pos, me, x);
    py = MSOCL_GATHER8(pos, me, y);
    pz = MSOCL_GATHER8(pos, me, z);
  }
  float8 fx = 0.0f, fy = 0.0f, fz = 0.0f;
  for (int s = 0; s < width; s++) {
    const int16 e = vload16(b * width + s, tab);
    const int8 j = e.lo, sp = e.hi;
    float8 qx, qy, qz;
    if (r) {
      MSOCL_ROW8(pos + j.s0, qx, qy, qz);
    } else {
      qx = MSOCL_GATHER8(pos, j, x);
      qy = MSOCL_GATHER8(pos, j, y);
      qz = MSOCL_GATHER8(pos, j, z);
    }
    const float8 t = MSOCL_COEF8(tc, sp);
    const float8 dx = qx - px, dy = qy - py, dz = qz - pz;
    const float8 sx = t * dx, sy = t * dy, sz = t * dz;
    fx += sx; fy += sy; fz += sz;
#ifdef MSOCL_DAMPING
    const float8 u = MSOCL_COEF8(uc, sp);
    const float8 hx = u * dx, hy = u * dy, hz = u * dz;
    fx += hx; fy += hy; fz += hz;
#endif
  }
  float ax[8], ay[8], az[8];
  vstore8(fx, 0, ax);
  vstore8(fy, 0, ay);
  vstore8(fz, 0, az);
  for (int l = 0; l < 8 && i0 + l < n; l++) {
    const int i = i0 + l;
    const float4 p4 = pos[i];
    if (MSOCL_PINNED(p4)) {
      vel_out[i] = (float4)(0.0f);
      pos_out[i] = p4;
      continue;
    }
    float x = ax[l], y = ay[l], z = az[l];
    for (int o = off[i] + width; o < off[i + 1]; o++) {
      const int2 e = inc[o];
      const float4 q = pos[e.x];
      const float dx = q.x - p4.x, dy = q.y - p4.y, dz = q.z - p4.z;
      const float t = tc[e.y];
      const float sx = t * dx, sy = t * dy, sz = t * dz;
      x += sx; y += sy; z += sz;
#ifdef MSOCL_DAMPING
      const float u = uc[e.y];
      const float hx = u * dx, hy = u * dy, hz = u * dz;
      x += hx; y += hy; z += hz;
#endif
    }
    float3 f = (float3)(x, y, z), v = vel[i].xyz;
#ifdef MSOCL_VISCOUS
    f -= viscous * v;
#endif
    v = msocl_kick(p4.xyz, v, f, inv_mass[i], gravity, air, dt, col, ncol);
    vel_out[i] = (float4)(v, 0.0f);
    pos_out[i] = (float4)(p4.xyz + dt * v, p4.w);
  }
  (void)uc; (void)viscous;
}
#undef MSOCL_GATHER8
#undef MSOCL_COEF8
#undef MSOCL_ROW8

/* Spring energy k (l - r)^2 / 2 per spring, summed per work-group of 64
 * into partial[group].y (the per-point energies come from msocl_energy). */
__kernel __attribute__((reqd_work_group_size(64, 1, 1)))
void msocl_edges_energy(__global const int2 *ij, MSOCL_RK,
                        __global const float4 *pos,
                        __global float4 *partial, int ns)
{
  __local float part[64];
  int s = get_global_id(0), l = get_local_id(0);
  float e = 0.0f;
  if (s < ns) {
    int2 q = ij[s];
    float3 d = pos[q.y].xyz - pos[q.x].xyz;
#ifdef MSOCL_CLASSES
    const float4 v = dmp[rk[s]];
    const float rest = v.x, k = v.y;
#else
    const float rest = rk[s].x, k = rk[s].y;
    (void)dmp;
#endif
    float stretch = MSOCL_SQRT(dot(d, d)) - rest;
    e = 0.5f * k * stretch * stretch;
  }
  part[l] = e;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int w = 32; w > 0; w >>= 1) {
    if (l < w)
      part[l] += part[l + w];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0)
    partial[get_group_id(0)] = (float4)(0.0f, part[0], 0.0f, 0.0f);
}

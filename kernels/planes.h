/* The steps: symplectic Euler's two passes (or fused), explicit Euler,
 * velocity Verlet's and RK4's stages, both strain limits' sweeps and the
 * collision response, on every layout, over state held as separate x, y,
 * z planes of floats - a grid's or lattice's rows padded by two points on
 * every side, other models' points in index order: the helpers every
 * planes kernel file shares (the kernels: planes.cl).
 *
 * Why: PoCL's CPU device vectorises across work-items only when a kernel's
 * per-work-item code is all scalar (its loop vectorizer takes no vector-
 * typed instruction), and it builds the work-item loop after -O3 has
 * already paired the x and y of a float4 into <2 x float>. In planes every
 * value is a scalar, the planes sit a run-time `plane` apart (so nothing
 * pairs them), and a neighbour at (dx, dy) is at a fixed offset from the
 * point - within the padding at the grid's edge - so eight or sixteen
 * work-items read it with one vector load, not a gather.
 *
 * Every layout sums a point's springs slot by slot in the same order, so
 * that layouts and device splits agree bitwise (tests/check_planes.c,
 * check_multidevice.c). The state lives in the planes; the host reads
 * and writes slices of them (lib/engine/state.c).
 *
 * Point (x, y) sits at (y + 2) * pitch + x + 2 of each plane; p holds the
 * x, y, z planes `plane` floats apart (v likewise); aux holds the inverse
 * masses, then the pin flags; col the colliders, a float4 a value
 * (MSOCL_PLANES_COL). MSOCL_NCOL: the model's colliders, known
 * when the program is built so that their loop unrolls (a loop of run-time
 * length inside would stop the vectorizer); MSOCL_GRID_KINDS: a bit for
 * each kind of spring the model has. */
#ifndef MSOCL_PLANES_H
#define MSOCL_PLANES_H

#include "common.h"

#if defined(MSOCL_PLANES)

/* The work-item's point (x, y, z) and where it sits in a plane (GRID): a
 * lattice's layers are `slab` floats apart, each padded by two rows, and
 * two padding layers lie at each end; a cloth has one layer (z 0).
 * BUFFER and IMAGE2D: point x of one unpadded row (y and z 0), `pitch`
 * its n points; the row is padded to whole work-groups (BUFFER: `slab`
 * the planes' length, the stride of their copy of the slot table). MSOCL_PLANES_NX:
 * the row's points in a gathering kernel, past which a work-item is
 * padding and stores nothing. */
#define MSOCL_PLANES_XYZ                                                      \
  const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2); \
  (void)y; (void)z /* a cloth's address leaves z out, BUFFER's both */
#if defined(MSOCL_LAYOUT_GRID) && defined(MSOCL_GRID_3D)
#define MSOCL_PLANES_AT(x, y, z) (((z) + 2) * slab + ((y) + 2) * pitch + (x) + 2)
#elif defined(MSOCL_LAYOUT_GRID)
#define MSOCL_PLANES_AT(x, y, z) (((y) + 2) * pitch + (x) + 2)
#else
#define MSOCL_PLANES_AT(x, y, z) (x)
#endif
#ifdef MSOCL_LAYOUT_GRID
#define MSOCL_PLANES_NX grid_nx
#else
#define MSOCL_PLANES_NX pitch
#endif

/* For the helpers a gather calls once a slot (and again for the spill):
 * a call left in the kernel, or -O3's pairing of two values inside it
 * into a <2 x float>, would stop PoCL vectorising the kernel. */
#define MSOCL_PLANES_INLINE inline __attribute__((always_inline))

/* dot(a, b) of float3 as the other kernels compute it: (x + y) + z. */
#define MSOCL_DOT3(ax, ay, az, bx, by, bz) ((ax) * (bx) + (ay) * (by) + (az) * (bz))

/* Whether aux's pinned value w marks a pinned point */
#ifdef MSOCL_PINS
#define MSOCL_PLANES_PINNED(w) ((w) != 0.0f)
#else
#define MSOCL_PLANES_PINNED(w) false
#endif

/* Value k of collider c (0: kind, 1: friction, 2: 1 while it moves,
 * 4-7: its parameters (msocl_planes_gap), 8-15: a capsule's or box's
 * msocl__collider.x, 16-18: its pose's velocity, 19-21: its angular
 * velocity, 22-24: its pose position) in the planes' collider table
 * (lib/engine/planes.c, lib/sim/sim_colliders.c), where each value has a
 * float4 to itself: adjacent ones would be loaded as a pair into a
 * <2 x float>, which stops PoCL vectorising the kernel. */
#define MSOCL_PLANES_COL(cf, c, k) ((cf)[4 * (32 * (c) + (k))])

/* The surface velocity of moving collider c at p: u = v + w x (p - c),
 * declared as ux, uy, uz of type T (cv(k) reads value k). Each component
 * in its own shape: three alike would be paired by -O3's SLP vectorizer
 * and PoCL would leave the kernel scalar. */
#define MSOCL_PLANES_SURFACE(T, cv, px, py, pz)                               \
  const T rx_ = (px) - cv(22), ry_ = (py) - cv(23), rz_ = (pz) - cv(24);      \
  const T ux = cv(16) + (cv(20) * rz_ - cv(21) * ry_);                        \
  const T uy = fma((T)cv(21), rx_, -(cv(19) * rz_)) + cv(17);                 \
  const T uz = cv(18) - (cv(20) * rx_ - cv(19) * ry_)

/* Collider c's gap g at the point (>= 0 outside; convex), and its unit
 * gradient in *nx.. */
static MSOCL_PLANES_INLINE float msocl_planes_gap(float px, float py, float pz,
                              __constant const float *col, int c, float *nx,
                              float *ny, float *nz)
{
#define cf(k) MSOCL_PLANES_COL(col, c, k)
  const int kind = (int)cf(0);
  float g = INFINITY;
  *nx = 0.0f;
  *ny = 1.0f;
  *nz = 0.0f;
#ifdef MSOCL_PLANE
  if (kind == MSOCL_PLANE_KIND) {
    *nx = cf(4);
    *ny = cf(5);
    *nz = cf(6);
    g = MSOCL_DOT3(cf(4), cf(5), cf(6), px, py, pz) - cf(7);
  }
#endif
#ifdef MSOCL_SPHERE
  if (kind == MSOCL_SPHERE_KIND) {
    float dx = px - cf(4), dy = py - cf(5), dz = pz - cf(6);
    float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
    bool out = len > 0.0f;
    *nx = out ? dx / len : 0.0f;
    *ny = out ? dy / len : 1.0f;
    *nz = out ? dz / len : 0.0f;
    g = len - cf(7);
  }
#endif
#ifdef MSOCL_TABLE
  if (kind == MSOCL_TABLE_KIND) {
    float dx = px - cf(4), dz = pz - cf(6);
    float rr = MSOCL_SQRT(dx * dx + dz * dz);
    float gside = rr - cf(7), gtop = py - cf(5);
    bool top = gtop >= gside || !(rr > 0.0f);
    *nx = top ? 0.0f : dx / rr;
    *ny = top ? 1.0f : 0.0f;
    *nz = top ? 0.0f : dz / rr;
    g = top ? gtop : gside;
  }
#endif
#ifdef MSOCL_CAPSULE
  /* the closest point of segment a-b, then a sphere's gap from it */
  if (kind == MSOCL_CAPSULE_KIND) {
    const float ex = cf(8) - cf(4), ey = cf(9) - cf(5), ez = cf(10) - cf(6);
    const float ax = px - cf(4), ay = py - cf(5), az = pz - cf(6);
    const float ee = MSOCL_DOT3(ex, ey, ez, ex, ey, ez);
    float t = ee > 0.0f ? MSOCL_DIV(MSOCL_DOT3(ax, ay, az, ex, ey, ez), ee)
                        : 0.0f;
    t = fmin(fmax(t, 0.0f), 1.0f);
    const float dx = ax - t * ex, dy = ay - t * ey, dz = az - t * ez;
    const float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
    const bool out = len > 0.0f;
    *nx = out ? dx / len : 0.0f;
    *ny = out ? dy / len : 1.0f;
    *nz = out ? dz / len : 0.0f;
    g = len - cf(7);
  }
#endif
#ifdef MSOCL_BOX
  /* p in the box's frame (q = (x, y, z, w) unit), the signed distance to
   * the box of half extents h there, its gradient rotated back */
  if (kind == MSOCL_BOX_KIND) {
    /* The rotation's matrix R (q = (x, y, z, w) unit); p in the box's
     * frame, l = R^T (p - centre); the signed distance to the box of half
     * extents h there, and its gradient m, rotated back (R m). Each of
     * the three components is written in its own shape: three alike
     * would be paired into a vector by -O3's SLP vectorizer, and PoCL
     * then leaves the whole kernel scalar. */
    const float qx = cf(8), qy = cf(9), qz = cf(10), qw = cf(11);
    const float r00 = 1.0f - 2.0f * (qy * qy + qz * qz),
                r01 = 2.0f * (qx * qy - qz * qw),
                r02 = 2.0f * (qx * qz + qy * qw);
    const float r10 = 2.0f * (qx * qy + qz * qw),
                r11 = 1.0f - 2.0f * (qx * qx + qz * qz),
                r12 = 2.0f * (qy * qz - qx * qw);
    const float r20 = 2.0f * (qx * qz - qy * qw),
                r21 = 2.0f * (qy * qz + qx * qw),
                r22 = 1.0f - 2.0f * (qx * qx + qy * qy);
    const float ex = px - cf(4), ey = py - cf(5), ez = pz - cf(6);
    const float lx = r00 * ex + r10 * ey + r20 * ez;
    const float ly = fma(r01, ex, fma(r11, ey, r21 * ez));
    const float lz = fma(r22, ez, r02 * ex) + r12 * ey;
    const float hx = cf(12), hy = cf(13), hz = cf(14);
    /* |l| - h: fabs, a max and the sign bit cleared */
    const float dx = fabs(lx) - hx, dy = fmax(ly, -ly) - hy,
                dz = as_float(as_uint(lz) & 0x7fffffffu) - hz;
    const float ox = fmax(dx, 0.0f), oy = dy > 0.0f ? dy : 0.0f,
                oz = 0.5f * (dz + fabs(dz));
    const float olen = MSOCL_SQRT(MSOCL_DOT3(ox, oy, oz, ox, oy, oz));
    const bool outside = olen > 0.0f;
    const bool xm = dx >= dy && dx >= dz, ym = !xm && dy >= dz;
    const float sx = lx < 0.0f ? -1.0f : 1.0f, sy = copysign(1.0f, ly),
                sz = 1.0f - 2.0f * (float)(lz < 0.0f);
    const float inv = outside ? 1.0f / olen : 0.0f;
    const float mx = outside ? sx * ox * inv : xm ? sx : 0.0f;
    const float my = outside ? fma(sy * oy, inv, 0.0f) : ym ? sy : 0.0f;
    const float mz = outside ? sz * oz / olen : (!xm && !ym) ? sz : 0.0f;
    g = outside ? olen : xm ? dx : ym ? dy : dz;
    *nx = r00 * mx + r01 * my + r02 * mz;
    *ny = fma(r10, mx, fma(r11, my, r12 * mz));
    *nz = fma(r22, mz, r20 * mx) + r21 * my;
  }
#endif
#undef cf
  (void)kind; /* no collider kind compiled in */
  (void)col; (void)c;
  return g;
}

/* Slot s of the point (x, y, z) at a: where its neighbour sits in the
 * planes (*b), the spring's rest length, stiffness and dashpot, and
 * whether the spring exists; a missing one's terms are masked by every
 * user (they replace the exact zeros its float4 twin adds). GRID: the
 * neighbour a fixed offset away, past the grid's edge (or of a kind with
 * k 0) reading the padding or another row; BUFFER and IMAGE2D: the other
 * end that the table holds, a free slot the point itself (a padding
 * work-item reads no slot: the table holds n points a slot). */
static MSOCL_PLANES_INLINE bool msocl_planes_neighbor(MSOCL_CONN, int s, int x, int y, int z,
                                  int a, int pitch, int slab, int *b,
                                  float *rest, float *k, float *c)
{
#if defined(MSOCL_LAYOUT_GRID)
  const int qx = x + msocl_grid_dx[s], qy = y + msocl_grid_dy[s];
  *rest = MSOCL_GRID_R(s);
  *k = MSOCL_GRID_K(s);
  *c = MSOCL_GRID_C;
#ifdef MSOCL_GRID_3D
  const int qz = z + msocl_grid_dz[s];
  *b = a + msocl_grid_dz[s] * slab + msocl_grid_dy[s] * pitch +
       msocl_grid_dx[s];
  return qx >= 0 && qx < grid_nx && qy >= 0 && qy < grid_ny && qz >= 0 &&
         qz < grid_nz && *k != 0.0f;
#else
  (void)z;
  (void)slab;
  *b = a + msocl_grid_dy[s] * pitch + msocl_grid_dx[s];
  return qx >= 0 && qx < grid_nx && qy >= 0 && qy < grid_ny && *k != 0.0f;
#endif
#else
  /* point i = x of n = pitch, at a = i in the planes */
  int j = x;
  float r = 0.0f, kk = 0.0f, cc = 0.0f;
  (void)y; (void)z; (void)a; (void)slab;
#if defined(MSOCL_LAYOUT_IMAGE2D)
  if (x < pitch) { /* a padding work-item reads no texel */
    /* the entry, and the dashpot in its group's texel */
    const sampler_t smp =
        CLK_NORMALIZED_COORDS_FALSE | CLK_ADDRESS_NONE | CLK_FILTER_NEAREST;
    const int tx = x % tex_w, ty = x / tex_w;
    const float4 e = read_imagef(con, smp, (int2)(tx + (s & 3) * tex_w,
                                                  ty + (s >> 2) * tex_h));
    const bool on = e.x >= 0.0f;
    j = on ? (int)e.y * tex_w + (int)e.x : x;
    r = on ? e.z : 0.0f;
    kk = on ? e.w : 0.0f;
#ifdef MSOCL_DAMPING
    const float4 c4 = read_imagef(dmp, smp, (int2)(tx + (s >> 2) * tex_w, ty));
    const int q = s & 3;
    cc = q == 0 ? c4.x : q == 1 ? c4.y : q == 2 ? c4.z : c4.w;
#endif
  }
#else
  /* BUFFER's table as planes.c copies it for the planes: slot s of point
   * i at s * slab + i (slab: the plane's length, so a padding work-item
   * reads a free slot), the rests in the first half of rk's floats and
   * the stiffnesses in the second, each read as a vector by eight or
   * sixteen work-items. The test keeps each slot's reads in a block of
   * their own: straight-line, -O3 pairs two slots' differences into a
   * <2 x float>, which stops PoCL vectorising across work-items. */
  if (x < slab) {
    const int at = s * slab + x;
    j = nbr[at];
#ifdef MSOCL_CLASSES
    __global const float *v = (__global const float *)dmp + 4 * rk[at];
    r = v[0];
    kk = v[1];
    cc = v[2];
#else
    __global const float *v = (__global const float *)rk;
    r = v[at];
    kk = v[MSOCL_SLOTS * slab + at];
#ifdef MSOCL_DAMPING
    cc = dmp[at];
#endif
#endif
  }
#endif
  *b = j;
  *rest = r;
  *k = kk;
  *c = cc;
  return j != x;
#endif
}

/* Whether slot s is of a kind the model leaves out (GRID, where BUFFER
 * would have no slot for it either): skipped when the program is built. */
#ifdef MSOCL_LAYOUT_GRID
#define MSOCL_PLANES_SKIP(s) (!((MSOCL_GRID_KINDS >> msocl_grid_kind[s]) & 1))
#else
#define MSOCL_PLANES_SKIP(s) false
#endif

/* The slots a gathering kernel's pass reads: the rows store only points
 * that do not spill (MSOCL_PLANES_LIVE), whose slots past MSOCL_ROW_SLOTS
 * are free, and a free slot's + 0 leaves a sum begun at +0 as it is. */
#define MSOCL_PLANES_SLOTS(pass) ((pass) ? MSOCL_TABLE_SLOTS : MSOCL_ROW_SLOTS)

/* Slot s of the point (x, y, z) at a, declared as the gathering loops
 * use it: b, rest, kk, cc and there. */
#define MSOCL_PLANES_NEIGHBOR(s)                                              \
  int b;                                                                     \
  float rest, kk, cc;                                                        \
  const bool there = msocl_planes_neighbor(MSOCL_CONN_ARGS, s, x, y, z, a,   \
                                           pitch, slab, &b, &rest, &kk, &cc)

#ifdef MSOCL_SPILL
/* BUFFER's springs past the table, as planes.c copies them after it:
 * entry o's other end and values. */
static MSOCL_PLANES_INLINE void msocl_planes_spill_slot(MSOCL_CONN, int o, int slab, int *b,
                                    float *rest, float *k, float *c)
{
  const int at = MSOCL_SLOTS * slab + o;
  *b = nbr[at];
#ifdef MSOCL_CLASSES
  __global const float *v = (__global const float *)dmp + 4 * rk[at];
  *rest = v[0];
  *k = v[1];
  *c = v[2];
#else
  __global const float *v =
      (__global const float *)rk + 2 * (MSOCL_SLOTS * slab + o);
  *rest = v[0];
  *k = v[1];
#ifdef MSOCL_DAMPING
  *c = dmp[at];
#else
  *c = 0.0f;
#endif
#endif
}

/* A gathering kernel runs twice: over the rows (pass 0), storing nothing
 * for a point with springs past the table, and over just those points
 * (pass 1, the kernel's _spill twin), their springs past the table
 * summed after the table's one at a time, in the order a table long
 * enough for all would sum them (the force gathers: in
 * MSOCL_SPILL_SEQ's order). A loop of run-time length in the first
 * would stop PoCL vectorising it; `pass` is a constant in each, so the
 * loop below folds away in the first. */
#define MSOCL_PLANES_SPILLS                                                   \
  for (int o = pass ? spill[x] : 0, o_end = pass ? spill[x + 1] : 0;        \
       o < o_end; o++)
#define MSOCL_PLANES_SPILL_NEIGHBOR(o)                                        \
  int b;                                                                     \
  float rest, kk, cc;                                                        \
  const bool there = true;                                                   \
  msocl_planes_spill_slot(MSOCL_CONN_ARGS, o, slab, &b, &rest, &kk, &cc)
#define MSOCL_PLANES_LIVE                                                     \
  (pass || (x < MSOCL_PLANES_NX && spill[x + 1] == spill[x]))
#define MSOCL_PLANES_SPILL_TWIN(name, params, args)                           \
  __kernel void name##_spill(MSOCL_PLANES_UNPAREN params,                    \
                             __global const int *spilled)                    \
  {                                                                          \
    name##_at(1, spilled[get_global_id(0)], 0, 0, MSOCL_PLANES_UNPAREN args); \
  }
#else
/* whether the work-item's point stores its result */
#define MSOCL_PLANES_LIVE (x < MSOCL_PLANES_NX)
#define MSOCL_PLANES_SPILL_TWIN(name, params, args)
#endif

/* A gathering kernel `name` with parameters `params` (their names:
 * `args`): its body, name##_at, is written once for both passes and
 * follows the macro. */
#define MSOCL_PLANES_UNPAREN(...) __VA_ARGS__
#define MSOCL_PLANES_GATHER(name, params, args)                               \
  static MSOCL_PLANES_INLINE void name##_at(                                 \
      const int pass, const int x, const int y, const int z,                 \
      MSOCL_PLANES_UNPAREN params);                                          \
  __kernel void name(MSOCL_PLANES_UNPAREN params)                            \
  {                                                                          \
    MSOCL_PLANES_XYZ;                                                        \
    name##_at(0, x, y, z, MSOCL_PLANES_UNPAREN args);                        \
  }                                                                          \
  MSOCL_PLANES_SPILL_TWIN(name, params, args)                                \
  static MSOCL_PLANES_INLINE void name##_at(                                 \
      const int pass, const int x, const int y, const int z,                 \
      MSOCL_PLANES_UNPAREN params)

/* One slot's part of the force on the point whose position and
 * velocity are q[0..5]: the spring's and its dashpot's pull from the
 * neighbour at b, added to f[0..2] where the spring exists. */
static MSOCL_PLANES_INLINE void msocl_planes_pull(__global const float *p,
                              __global const float *v, int plane,
                              const float *q, int b, bool there, float rest,
                              float kk, float cc, float *f)
{
  const float dx = p[b] - q[0], dy = p[plane + b] - q[1],
              dz = p[2 * plane + b] - q[2];
  const float len2 = dx * dx + dy * dy + dz * dz;
  const float len = MSOCL_SQRT(len2);
  const float t = kk * MSOCL_DIV(len - rest, len);
  const bool on = there && len > 0.0f;
  f[0] += on ? t * dx : 0.0f;
  f[1] += on ? t * dy : 0.0f;
  f[2] += on ? t * dz : 0.0f;
#ifdef MSOCL_DAMPING
  const float wx = v[b] - q[3], wy = v[plane + b] - q[4],
              wz = v[2 * plane + b] - q[5];
  const float u = cc * MSOCL_DIV(wx * dx + wy * dy + wz * dz, len2);
  const bool onh = there && len2 > 0.0f;
  f[0] += onh ? u * dx : 0.0f;
  f[1] += onh ? u * dy : 0.0f;
  f[2] += onh ? u * dz : 0.0f;
#endif
  (void)v; (void)cc; /* read by dashpots */
}

#ifdef MSOCL_SPILL
/* A point's springs from the MSOCL_SPILL_SEQ-th on (a hub's) are summed
 * in eight running sums, spring 64 + 8 m + u into sum u, which are then
 * added in order; the springs before it one after another in their order.
 * The order is the same for every table width, so a point's force is
 * bitwise the same however much of it spills. */
#define MSOCL_SPILL_SEQ 64

/* Eight of the spill's springs from entry o (entries past `end` repeat
 * the last): msocl_planes_pull's spring terms in t[0..2] and dashpot
 * terms in t[3..5] (zero without dashpots), as float8 (square root and
 * division round as one at a time). */
static MSOCL_PLANES_INLINE void
msocl_planes_spill8(MSOCL_CONN, __global const float *p,
                    __global const float *v, int plane, int slab,
                    const float *q, int o, int end, float8 *t)
{
  float r[8], k[8], c[8], nx[8], ny[8], nz[8];
#ifdef MSOCL_DAMPING
  float wx[8], wy[8], wz[8];
#endif
  (void)c; (void)v; /* read by dashpots */
  int bs[8];
#ifndef MSOCL_CLASSES
  if (o + 8 <= end) { /* the table's entries as vectors */
    const int at = MSOCL_SLOTS * slab + o;
    vstore8(vload8(0, nbr + at), 0, bs);
    const float16 w = vload16(0, (__global const float *)rk + 2 * at);
    vstore8(w.even, 0, r);
    vstore8(w.odd, 0, k);
#ifdef MSOCL_DAMPING
    vstore8(vload8(0, dmp + at), 0, c);
#endif
  } else
#endif
#pragma unroll
    for (int u = 0; u < 8; u++)
      msocl_planes_spill_slot(MSOCL_CONN_ARGS, min(o + u, end - 1), slab,
                              &bs[u], &r[u], &k[u], &c[u]);
#pragma unroll
  for (int u = 0; u < 8; u++) {
    const int b = bs[u];
    nx[u] = p[b];
    ny[u] = p[plane + b];
    nz[u] = p[2 * plane + b];
#ifdef MSOCL_DAMPING
    wx[u] = v[b];
    wy[u] = v[plane + b];
    wz[u] = v[2 * plane + b];
#endif
  }
  const float8 dx = vload8(0, nx) - q[0], dy = vload8(0, ny) - q[1],
               dz = vload8(0, nz) - q[2];
  const float8 len2 = dx * dx + dy * dy + dz * dz;
  const float8 len = MSOCL_SQRT(len2);
  const float8 tt = vload8(0, k) * MSOCL_DIV(len - vload8(0, r), len);
  const int8 on = len > 0.0f;
  t[0] = select((float8)(0.0f), tt * dx, on);
  t[1] = select((float8)(0.0f), tt * dy, on);
  t[2] = select((float8)(0.0f), tt * dz, on);
#ifdef MSOCL_DAMPING
  const float8 ux = vload8(0, wx) - q[3], uy = vload8(0, wy) - q[4],
               uz = vload8(0, wz) - q[5];
  const float8 h =
      vload8(0, c) * MSOCL_DIV(ux * dx + uy * dy + uz * dz, len2);
  const int8 onh = len2 > 0.0f;
  t[3] = select((float8)(0.0f), h * dx, onh);
  t[4] = select((float8)(0.0f), h * dy, onh);
  t[5] = select((float8)(0.0f), h * dz, onh);
#else
  t[3] = t[4] = t[5] = 0.0f;
#endif
}

/* msocl_planes_pull of the spill's springs o .. o_end - 1 (the point's
 * springs from MSOCL_SLOTS on), summed into f in MSOCL_SPILL_SEQ's
 * order, eight springs' terms at a time. A hub (a solid's centre: 40 955
 * springs in the ball of `msocl-bench meshes`) ran them scalar, one
 * addition after another, in one work-item while the device's other
 * threads waited. */
static MSOCL_PLANES_INLINE void
msocl_planes_spill_pull(MSOCL_CONN, __global const float *p,
                        __global const float *v, int plane, int slab,
                        const float *q, int o, int o_end, float *f)
{
  const int seq = min(o_end, o + max(MSOCL_SPILL_SEQ - MSOCL_SLOTS, 0));
  float8 t[6];
  float l[6][8];
  for (; o < seq; o += 8) {
    msocl_planes_spill8(MSOCL_CONN_ARGS, p, v, plane, slab, q, o, seq, t);
#pragma unroll
    for (int c = 0; c < 6; c++)
      vstore8(t[c], 0, l[c]);
    for (int u = 0; u < 8 && o + u < seq; u++) {
      f[0] += l[0][u];
      f[1] += l[1][u];
      f[2] += l[2][u];
#ifdef MSOCL_DAMPING
      f[0] += l[3][u];
      f[1] += l[4][u];
      f[2] += l[5][u];
#endif
    }
  }
  if (seq >= o_end)
    return;
  float8 sum[3] = {0.0f, 0.0f, 0.0f};
  for (o = seq; o < o_end; o += 8) {
    msocl_planes_spill8(MSOCL_CONN_ARGS, p, v, plane, slab, q, o, o_end, t);
    const int8 in = (int8)(0, 1, 2, 3, 4, 5, 6, 7) + o < o_end;
#pragma unroll
    for (int c = 0; c < 3; c++) {
      sum[c] += select((float8)(0.0f), t[c], in);
#ifdef MSOCL_DAMPING
      sum[c] += select((float8)(0.0f), t[3 + c], in);
#endif
    }
  }
#pragma unroll
  for (int c = 0; c < 3; c++) {
    vstore8(sum[c], 0, l[c]);
    for (int u = 0; u < 8; u++)
      f[c] += l[c][u];
  }
}
#endif

/* Internal force at the point at a = (x, y, z): each spring k (len -
 * rest) / len d (Hooke, eq. 2 of the paper; a zero-length spring exerts
 * nothing rather than NaN) and each dashpot c dot(vq - vp, d) / len^2 d,
 * slot by slot, viscous damping included
 * (pass: MSOCL_PLANES_SPILLS). */
static MSOCL_PLANES_INLINE void msocl_planes_force(MSOCL_CONN, const int pass,
                               __global const float *p,
                               __global const float *v, int pitch, int slab,
                               int plane, float viscous, int x, int y, int z,
                               int a, float *fx_out, float *fy_out,
                               float *fz_out)
{
  const float vx = v[a], vy = v[plane + a], vz = v[2 * plane + a];
  const float q[6] = {p[a], p[plane + a], p[2 * plane + a], vx, vy, vz};
  float f[3] = {0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_PLANES_SLOTS(pass); s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    msocl_planes_pull(p, v, plane, q, b, there, rest, kk, cc, f);
  }
#ifdef MSOCL_SPILL
  if (pass)
    msocl_planes_spill_pull(MSOCL_CONN_ARGS, p, v, plane, slab, q, spill[x],
                            spill[x + 1], f);
#endif
  (void)pass;
  float fx = f[0], fy = f[1], fz = f[2];
#ifdef MSOCL_VISCOUS
  fx = fx - viscous * vx;
  fy = fy - viscous * vy;
  fz = fz - viscous * vz;
#endif
  (void)viscous;
  (void)vx; (void)vy; (void)vz; /* read by dashpots and viscous damping */
  *fx_out = fx;
  *fy_out = fy;
  *fz_out = fz;
}

/* Collision response by changing velocity (the paper's way): g is convex
 * and >= 0 outside, so raising n.v to at least -g/dt keeps p + dt v
 * outside; friction scales away that fraction of the tangential velocity
 * on contact. Branches as selects. */
static MSOCL_PLANES_INLINE void msocl_planes_collide(float px, float py, float pz, float *vx_io,
                                 float *vy_io, float *vz_io, float dt,
                                 __constant float4 *col, float fscale)
{
  float vx = *vx_io, vy = *vy_io, vz = *vz_io;
  __constant const float *cf = (__constant const float *)col;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++) {
    float nx, ny, nz;
    const float g = msocl_planes_gap(px, py, pz, cf, c, &nx, &ny, &nz);
    /* on the velocity relative to a moving collider's surface (a static
     * one's, selected, is v itself) */
#define cv(k) MSOCL_PLANES_COL(cf, c, k)
    MSOCL_PLANES_SURFACE(float, cv, px, py, pz);
    const bool moving = cv(2) != 0.0f;
#undef cv
    const float ox = moving ? vx - ux : vx, oy = moving ? vy - uy : vy,
                oz = moving ? vz - uz : vz;
    const float fr = fscale * MSOCL_PLANES_COL(cf, c, 1);
    const float vn = MSOCL_DOT3(ox, oy, oz, nx, ny, nz);
    const float lim = MSOCL_DIV(-g, dt);
    float hx = ox + (lim - vn) * nx, hy = oy + (lim - vn) * ny,
          hz = oz + (lim - vn) * nz;
    hx = hx - fr * (hx - lim * nx);
    hy = hy - fr * (hy - lim * ny);
    hz = hz - fr * (hz - lim * nz);
    hx = moving ? hx + ux : hx;
    hy = moving ? hy + uy : hy;
    hz = moving ? hz + uz : hz;
    const bool hit = vn < lim;
    vx = hit ? hx : vx;
    vy = hit ? hy : vy;
    vz = hit ? hz : vz;
  }
  (void)cf;
  *vx_io = vx;
  *vy_io = vy;
  *vz_io = vz;
}

/* Air resistance (MSOCL_AIR): the velocity times `air`. */
static MSOCL_PLANES_INLINE void msocl_planes_air(float air, float *vx, float *vy, float *vz)
{
#ifdef MSOCL_AIR
  *vx = air * *vx;
  *vy = air * *vy;
  *vz = air * *vz;
#endif
  (void)air; (void)vx; (void)vy; (void)vz;
}

/* The velocity pass for the point at a = (x, y, z): its new velocity in
 * *vx.., and whether it is pinned. */
static MSOCL_PLANES_INLINE void msocl_planes_kick(MSOCL_CONN, const int pass,
                              __global const float *p,
                              __global const float *v,
                              __global const float *aux, int pitch, int slab,
                              int plane, float4 gravity, float viscous,
                              float air, float dt, __constant float4 *col,
                              int x, int y, int z, int a, float *vx_out,
                              float *vy_out, float *vz_out, bool *pinned)
{
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, p, v, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a];
  float vx = v[a] + dt * (fx * im + gravity.x);
  float vy = v[plane + a] + dt * (fy * im + gravity.y);
  float vz = v[2 * plane + a] + dt * (fz * im + gravity.z);
  msocl_planes_air(air, &vx, &vy, &vz);
  msocl_planes_collide(p[a], p[plane + a], p[2 * plane + a], &vx, &vy, &vz,
                       dt, col, 1.0f);
  *pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  *vx_out = *pinned ? 0.0f : vx;
  *vy_out = *pinned ? 0.0f : vy;
  *vz_out = *pinned ? 0.0f : vz;
}

/* The planes' ping-pong arguments after the connectivity, then the fixed
 * ones; both kernels below take them in this order. */
#define MSOCL_PLANES_ARGS                                                     \
  __global const float *aux, int pitch, int slab, int plane,                 \
      float4 gravity, float viscous, float air, float dt,                    \
      __constant float4 *col
#define MSOCL_PLANES_ARG_NAMES                                                \
  aux, pitch, slab, plane, gravity, viscous, air, dt, col

/* An RK4 stage kernel's parameters (planes.cl's and planes_wide.cl's):
 * the step's start, the stage state read, the sums, the next state. */
#define MSOCL_PLANES_RK4_ARGS                                                 \
  (MSOCL_CONN, __global const float *p0, __global const float *v0,           \
   __global const float *sp, __global const float *sv,                       \
   __global float *sum_p, __global float *sum_v, __global float *np,         \
   __global float *nv, MSOCL_PLANES_ARGS, float c)

/* Both kernels' point (x, y, z), at a, and its new velocity; then the
 * store of that velocity. */
#define MSOCL_PLANES_KICK                                                     \
  const int a = MSOCL_PLANES_AT(x, y, z);                                    \
  float vx, vy, vz;                                                          \
  bool pinned;                                                               \
  msocl_planes_kick(MSOCL_CONN_ARGS, pass, p, v, aux, pitch, slab, plane,    \
                    gravity, viscous, air, dt, col, x, y, z, a, &vx, &vy,    \
                    &vz, &pinned)
#define MSOCL_PLANES_STORE_V                                                  \
  v_out[a] = vx;                                                             \
  v_out[plane + a] = vy;                                                     \
  v_out[2 * plane + a] = vz

#endif
#endif

/* The explicit vectors' helpers of the wide kernels (planes_wide.cl,
 * planes_wide_strain.cl, planes_wide_implicit.cl): a work-item's W
 * points, their stores, the slot loop over their springs, and the spring
 * force every gathering kernel sums. */
#ifndef MSOCL_WIDE_H
#define MSOCL_WIDE_H

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

/* BUFFER on a CPU (-DMSOCL_GATHER4): the positions also as a float4 a
 * point (p4, packed before each pass that gathers them), so that a
 * neighbour is one 16-byte load where the planes take three scalar loads
 * and three inserts (planes_pack.c). The force kernels that read it take
 * it as their argument p4 (MSOCL_P4); the others pass 0. */
#ifdef MSOCL_GATHER4
#define MSOCL_P4 , __global const float4 *p4
#define MSOCL_P4_ARG p4
#else
#define MSOCL_P4
#define MSOCL_P4_ARG 0
#endif

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

/* The float4s p4[j] as three vectors: four points a 16-lane vector, then
 * a 4x4 transpose in each 128-bit block (lane c of block b comes out as
 * point 4b + c when vector c holds points c, c + 4, c + 8, c + 12). */
static MSOCL_WIDE_INLINE void
msocl_wide_gather4(__global const float4 *p4, const int *j, msocl_rows_f *x,
                   msocl_rows_f *y, msocl_rows_f *z)
{
#if MSOCL_ROWS_W == 16
  float16 a[4];
#pragma unroll
  for (int c = 0; c < 4; c++)
    a[c] = (float16)(p4[j[c]], p4[j[c + 4]], p4[j[c + 8]], p4[j[c + 12]]);
  const float16 t0 = __builtin_shufflevector(a[0], a[1], 0, 16, 1, 17, 4, 20,
                                             5, 21, 8, 24, 9, 25, 12, 28, 13,
                                             29),
                t1 = __builtin_shufflevector(a[0], a[1], 2, 18, 3, 19, 6, 22,
                                             7, 23, 10, 26, 11, 27, 14, 30,
                                             15, 31),
                t2 = __builtin_shufflevector(a[2], a[3], 0, 16, 1, 17, 4, 20,
                                             5, 21, 8, 24, 9, 25, 12, 28, 13,
                                             29),
                t3 = __builtin_shufflevector(a[2], a[3], 2, 18, 3, 19, 6, 22,
                                             7, 23, 10, 26, 11, 27, 14, 30,
                                             15, 31);
  *x = __builtin_shufflevector(t0, t2, 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24,
                               25, 12, 13, 28, 29);
  *y = __builtin_shufflevector(t0, t2, 2, 3, 18, 19, 6, 7, 22, 23, 10, 11,
                               26, 27, 14, 15, 30, 31);
  *z = __builtin_shufflevector(t1, t3, 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24,
                               25, 12, 13, 28, 29);
#else
  float tx[MSOCL_ROWS_W], ty[MSOCL_ROWS_W], tz[MSOCL_ROWS_W];
#pragma unroll
  for (int u = 0; u < MSOCL_ROWS_W; u++) {
    const float4 w = p4[j[u]];
    tx[u] = w.x;
    ty[u] = w.y;
    tz[u] = w.z;
  }
  *x = MSOCL_ROWS_LOAD(tx);
  *y = MSOCL_ROWS_LOAD(ty);
  *z = MSOCL_ROWS_LOAD(tz);
#endif
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
/* The slots unrolled where a vector's values fit the registers: a
 * cloth's 12, or a lattice's 32 with AVX-512's 32 registers; a lattice's
 * unrolled on AVX2 (16) spilled, 15 000 stack references a kernel */
#if defined(MSOCL_GRID_3D) && defined(__x86_64__) && !defined(__AVX512F__)
#define MSOCL_WIDE_UNROLL _Pragma("unroll 1")
#else
#define MSOCL_WIDE_UNROLL _Pragma("unroll")
#endif
#define MSOCL_WIDE_SLOTS                                                      \
  (void)slab; (void)z;                                                       \
  MSOCL_WIDE_UNROLL for (int s = 0; s < MSOCL_TABLE_SLOTS; s++)              \
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
#define MSOCL_WIDE_SKIP_FREE
#define MSOCL_WIDE_NB_P(p4, px, py, pz, nx, ny, nz)                           \
  (void)(p4);                                                                \
  nx = MSOCL_WIDE_NB(px);                                                    \
  ny = MSOCL_WIDE_NB(py);                                                    \
  nz = MSOCL_WIDE_NB(pz)
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
/* A slot past MSOCL_ROW_SLOTS that no lane fills is skipped: its + 0
 * terms leave a sum begun at +0 as it is (such a sum is never -0). */
#define MSOCL_WIDE_SKIP_FREE                                                  \
  if (s >= MSOCL_ROW_SLOTS && !any(there))                                   \
  continue
/* the neighbours' positions, from p4 where a kernel has it */
#define MSOCL_WIDE_NB_P(p4, px, py, pz, nx, ny, nz)                           \
  if (p4) {                                                                  \
    msocl_wide_gather4((p4), j_, &(nx), &(ny), &(nz));                       \
  } else {                                                                   \
    nx = MSOCL_WIDE_NB(px);                                                  \
    ny = MSOCL_WIDE_NB(py);                                                  \
    nz = MSOCL_WIDE_NB(pz);                                                  \
  }

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
 * BUFFER: the table's, gathered lane by lane, or a float4 a neighbour
 * from p4 where the kernel has it. */
static MSOCL_WIDE_INLINE void
msocl_wide_force(MSOCL_CONN, __global const float4 *p4,
                 __global const float *p, __global const float *v,
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
    MSOCL_WIDE_SKIP_FREE;
#ifdef MSOCL_DAMPING
    wx = MSOCL_WIDE_NB(v);
    wy = MSOCL_WIDE_NB(vy_);
    wz = MSOCL_WIDE_NB(vz_);
#endif
    msocl_rows_f nx, ny, nz;
    MSOCL_WIDE_NB_P(p4, p, py_, pz_, nx, ny, nz);
    msocl_wide_pull(nx, ny, nz, wx, wy, wz, qx, qy, qz, ux, uy, uz, there,
                    rest, kk, cc, &fx, &fy, &fz);
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
#endif

#endif

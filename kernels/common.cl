/* What every kernel file shares: math mode, collider kinds, and access
 * to a point's springs, whichever layout holds them.
 * The library compiles it first, followed by the other kernel files, as one
 * program; its -D options name only what the model uses:
 *   MSOCL_LAYOUT_IMAGE2D | MSOCL_LAYOUT_BUFFER | MSOCL_LAYOUT_GRID
 *                          where the springs live
 *   MSOCL_SLOTS=n          slots per point (BUFFER)
 *   MSOCL_CLASSES          BUFFER: a class byte per slot (rk) naming a
 *                          (rest, k, dashpot) float4 (dmp), not values
 *   MSOCL_DAMPING          per-spring dashpots (a slot table of coefficients)
 *   MSOCL_VISCOUS          viscous damping -c v
 *   MSOCL_AIR              air resistance: velocity times a factor a step
 *   MSOCL_PINS             pinned points
 *   MSOCL_PLANE, MSOCL_SPHERE, MSOCL_TABLE   collider kinds present
 *   MSOCL_RELAXED          native functions (with -cl-fast-relaxed-math)
 * The steps run on planes (planes.cl); the float4 state the host reads
 * and writes (pos.w = 1 marks a pinned point) feeds the energy and the
 * normals. */

/* Precise mode forbids fused multiply-add so every layout, and every device
 * split, sums in exactly the same arithmetic (bitwise-equal results). */
#ifndef MSOCL_RELAXED
#pragma OPENCL FP_CONTRACT OFF
#define MSOCL_SQRT(x) sqrt(x)
#define MSOCL_DIV(a, b) ((a) / (b))
#else
#define MSOCL_SQRT(x) native_sqrt(x)
#define MSOCL_DIV(a, b) native_divide((a), (b))
#endif

#define MSOCL_PLANE_KIND 1
#define MSOCL_SPHERE_KIND 2
#define MSOCL_TABLE_KIND 3
#define MSOCL_CAPSULE_KIND 4 /* planes.cl only */
#define MSOCL_BOX_KIND 5

/* BUFFER's per-slot values, or class bytes and the classes' values */
#ifdef MSOCL_CLASSES
#define MSOCL_RK __global const uchar *rk, __global const float4 *dmp
#else
#define MSOCL_RK __global const float2 *rk, __global const float *dmp
#endif

/* Connectivity parameters of every gathering kernel, and the same names to
 * pass them on. */
#if defined(MSOCL_LAYOUT_IMAGE2D)
#define MSOCL_MAX_SLOTS 16
#define MSOCL_CONN                                                            \
  __read_only image2d_t con, int tex_w, int tex_h, __read_only image2d_t dmp
#define MSOCL_CONN_ARGS con, tex_w, tex_h, dmp
#elif defined(MSOCL_LAYOUT_GRID) && defined(MSOCL_GRID_3D)
#define MSOCL_MAX_SLOTS 32
#define MSOCL_CONN                                                            \
  int grid_nx, int grid_ny, int grid_nz, float4 grid_k, float8 grid_rest
#define MSOCL_CONN_ARGS grid_nx, grid_ny, grid_nz, grid_k, grid_rest
/* A lattice's 32 neighbours in the order msocl_model_lattice adds their
 * springs (so in BUFFER's slot order: each set loops the points in index
 * order, so a point meets first the springs of the points before it):
 * 6 structural, 12 face shear, 8 body shear, 6 bend. kind: 0 structural,
 * 1 face shear, 2 body shear, 3 bend - grid_k's stiffness and grid_rest's
 * rest length; grid_rest.s4 is the dashpot. */
__constant int msocl_grid_dx[32] = {
    0, 0, -1, 1, 0, 0,
    0, -1, 1, 0, -1, 1, 0, -1, -1, 1, 1, 0,
    -1, 1, -1, 1, -1, 1, -1, 1,
    0, 0, -2, 2, 0, 0};
__constant int msocl_grid_dy[32] = {
    0, -1, 0, 0, 1, 0,
    -1, 0, 0, 1, -1, -1, -1, 1, 0, 1, 0, 1,
    -1, -1, 1, 1, -1, -1, 1, 1,
    0, -2, 0, 0, 2, 0};
__constant int msocl_grid_dz[32] = {
    -1, 0, 0, 0, 0, 1,
    -1, -1, -1, -1, 0, 0, 1, 0, 1, 0, 1, 1,
    -1, -1, -1, -1, 1, 1, 1, 1,
    -2, 0, 0, 0, 0, 2};
__constant int msocl_grid_kind[32] = {
    0, 0, 0, 0, 0, 0,
    1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
    2, 2, 2, 2, 2, 2, 2, 2,
    3, 3, 3, 3, 3, 3};
/* slot s's stiffness and rest length, and the dashpot (as the cloth's
 * below) */
#define MSOCL_GRID_K(s)                                                       \
  (msocl_grid_kind[s] == 0 ? grid_k.x : msocl_grid_kind[s] == 1 ? grid_k.y   \
   : msocl_grid_kind[s] == 2 ? grid_k.z : grid_k.w)
#define MSOCL_GRID_R(s)                                                       \
  (msocl_grid_kind[s] == 0 ? grid_rest.s0                                    \
   : msocl_grid_kind[s] == 1 ? grid_rest.s1                                  \
   : msocl_grid_kind[s] == 2 ? grid_rest.s2 : grid_rest.s3)
#define MSOCL_GRID_C grid_rest.s4
#elif defined(MSOCL_LAYOUT_GRID)
#define MSOCL_MAX_SLOTS 12
#define MSOCL_CONN int grid_nx, int grid_ny, float4 grid_k, float8 grid_rest
#define MSOCL_CONN_ARGS grid_nx, grid_ny, grid_k, grid_rest
/* A cloth grid's 12 neighbours in the order msocl_model_cloth_grid adds
 * their springs (so in BUFFER's slot order): stretch below, left, right,
 * above; shear below-left, below-right, above-left, above-right; bend two
 * below, left, right, above. kind: 0 stretch, 1 shear, 2 bend; rest: index
 * into grid_rest. */
__constant int msocl_grid_dx[12] = {0, -1, 1, 0, -1, 1, -1, 1, 0, -2, 2, 0};
__constant int msocl_grid_dy[12] = {-1, 0, 0, 1, -1, -1, 1, 1, -2, 0, 0, 2};
__constant int msocl_grid_kind[12] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
__constant int msocl_grid_rest[12] = {1, 0, 0, 1, 2, 3, 3, 2, 5, 4, 4, 5};
/* slot s's stiffness and rest length, and the dashpot */
#define MSOCL_GRID_K(s)                                                       \
  (msocl_grid_kind[s] == 0 ? grid_k.x : msocl_grid_kind[s] == 1 ? grid_k.y   \
                                                              : grid_k.z)
#define MSOCL_GRID_R(s)                                                       \
  (msocl_grid_rest[s] == 0 ? grid_rest.s0                                    \
   : msocl_grid_rest[s] == 1 ? grid_rest.s1                                  \
   : msocl_grid_rest[s] == 2 ? grid_rest.s2                                  \
   : msocl_grid_rest[s] == 3 ? grid_rest.s3                                  \
   : msocl_grid_rest[s] == 4 ? grid_rest.s4 : grid_rest.s5)
#define MSOCL_GRID_C grid_k.w
#elif defined(MSOCL_SPILL)
/* BUFFER with a spill: MSOCL_SLOTS slots a point in the table, the rest of
 * a point's springs (only a few points have more) listed after the table,
 * point i's from spill[i] to spill[i + 1]; MSOCL_DEGREE: the most any
 * point has. */
#define MSOCL_MAX_SLOTS MSOCL_DEGREE
#define MSOCL_CONN __global const int *nbr, MSOCL_RK, __global const int *spill
#define MSOCL_CONN_ARGS nbr, rk, dmp, spill
#else
#define MSOCL_MAX_SLOTS MSOCL_SLOTS
#define MSOCL_CONN __global const int *nbr, MSOCL_RK
#define MSOCL_CONN_ARGS nbr, rk, dmp
#endif
/* The slots msocl_slot4 takes four at a time (BUFFER: the table's). */
#if defined(MSOCL_LAYOUT_IMAGE2D) || defined(MSOCL_LAYOUT_GRID)
#define MSOCL_TABLE_SLOTS MSOCL_MAX_SLOTS
#else
#define MSOCL_TABLE_SLOTS MSOCL_SLOTS
#endif

#if !defined(MSOCL_LAYOUT_IMAGE2D) && !defined(MSOCL_LAYOUT_GRID)
/* BUFFER: rest length, stiffness and dashpot of table entry `at` (the
 * class's values are the very floats a slot would hold). */
static void msocl_values(MSOCL_RK, int at, float *rest, float *k, float *c)
{
#ifdef MSOCL_CLASSES
  float4 v = dmp[rk[at]];
  *rest = v.x;
  *k = v.y;
  *c = v.z;
#else
  float2 e = rk[at];
  *rest = e.x;
  *k = e.y;
#ifdef MSOCL_DAMPING
  *c = dmp[at];
#else
  *c = 0.0f;
#endif
#endif
}
#endif

/* Slots s0 .. s0 + 3 of point i (s0 a multiple of 4, unrolled) as
 * vectors: the other ends j, rest lengths, stiffnesses and dashpot
 * coefficients. The texture is the paper's: 16 tiles of W x H, slot s in
 * tile (s % 4, s / 4), entry (x, y of the other end, rest, k), -1 = end;
 * dashpots in a (4W) x H image, four slots a texel. BUFFER is slot-major:
 * slot s of point i at s * n + i. A free slot, a slot past the last, and
 * GRID's missing neighbour (grid edge, or a kind the model leaves out) are
 * a spring to the point itself with rest, k and c 0 (layout.c), which
 * adds exact zeros wherever it is summed. */
static void msocl_slot4(MSOCL_CONN, int i, int s0, int n, int4 *j,
                        float4 *rest, float4 *k, float4 *c)
{
#if defined(MSOCL_LAYOUT_GRID) && defined(MSOCL_GRID_3D)
  /* the point's (x, y, z) found once; a group of four may mix kinds */
  int x = i % grid_nx, t = i / grid_nx, y = t % grid_ny, z = t / grid_ny;
  int4 qx = x + vload4(0, msocl_grid_dx + s0);
  int4 qy = y + vload4(0, msocl_grid_dy + s0);
  int4 qz = z + vload4(0, msocl_grid_dz + s0);
  int4 kind = vload4(0, msocl_grid_kind + s0);
  float4 kk = select(select(select((float4)(grid_k.w), (float4)(grid_k.z),
                                   kind == 2),
                            (float4)(grid_k.y), kind == 1),
                     (float4)(grid_k.x), kind == 0);
  *rest = select(select(select((float4)(grid_rest.s3), (float4)(grid_rest.s2),
                               kind == 2),
                        (float4)(grid_rest.s1), kind == 1),
                 (float4)(grid_rest.s0), kind == 0);
  int4 there = (qx >= 0) & (qx < grid_nx) & (qy >= 0) & (qy < grid_ny) &
               (qz >= 0) & (qz < grid_nz) & (kk != 0.0f);
  *j = select((int4)(i), (qz * grid_ny + qy) * grid_nx + qx, there);
  *k = select((float4)(0.0f), kk, there);
  *c = select((float4)(0.0f), (float4)(MSOCL_GRID_C), there);
  (void)n;
#elif defined(MSOCL_LAYOUT_GRID)
  /* each group of four neighbours is of one kind (stretch, shear, bend) */
  int x = i % grid_nx, y = i / grid_nx, kind = msocl_grid_kind[s0];
  int4 dx = vload4(0, msocl_grid_dx + s0), dy = vload4(0, msocl_grid_dy + s0);
  int4 ri = vload4(0, msocl_grid_rest + s0);
  int4 qx = x + dx, qy = y + dy;
  float kk = kind == 0 ? grid_k.x : kind == 1 ? grid_k.y : grid_k.z;
  int4 there = (qx >= 0) & (qx < grid_nx) & (qy >= 0) & (qy < grid_ny) &
               (int4)(kk != 0.0f ? -1 : 0);
  float r[4];
#pragma unroll
  for (int q = 0; q < 4; q++) {
    int e = q == 0 ? ri.x : q == 1 ? ri.y : q == 2 ? ri.z : ri.w;
    r[q] = e == 0 ? grid_rest.s0 : e == 1 ? grid_rest.s1
         : e == 2 ? grid_rest.s2 : e == 3 ? grid_rest.s3
         : e == 4 ? grid_rest.s4 : grid_rest.s5;
  }
  *j = select((int4)(i), qy * grid_nx + qx, there);
  *rest = (float4)(r[0], r[1], r[2], r[3]);
  *k = select((float4)(0.0f), (float4)(kk), there);
  *c = select((float4)(0.0f), (float4)(grid_k.w), there);
  (void)n;
#elif defined(MSOCL_LAYOUT_IMAGE2D)
  /* the group's four dashpots share one texel: one read for them, not
   * four (a free slot's is 0, and its spring to the point itself adds
   * zeros whatever c is) */
  const sampler_t smp =
      CLK_NORMALIZED_COORDS_FALSE | CLK_ADDRESS_NONE | CLK_FILTER_NEAREST;
  int x = i % tex_w, y = i / tex_w;
  int jq[4];
  float rq[4], kq[4];
#pragma unroll
  for (int q = 0; q < 4; q++) {
    float4 e = read_imagef(con, smp, (int2)(x + q * tex_w,
                                            y + (s0 >> 2) * tex_h));
    bool on = e.x >= 0.0f;
    jq[q] = on ? (int)e.y * tex_w + (int)e.x : i;
    rq[q] = on ? e.z : 0.0f;
    kq[q] = on ? e.w : 0.0f;
  }
  *j = (int4)(jq[0], jq[1], jq[2], jq[3]);
  *rest = (float4)(rq[0], rq[1], rq[2], rq[3]);
  *k = (float4)(kq[0], kq[1], kq[2], kq[3]);
#ifdef MSOCL_DAMPING
  *c = read_imagef(dmp, smp, (int2)(x + (s0 >> 2) * tex_w, y));
#else
  *c = (float4)(0.0f);
#endif
  (void)n;
#else
  int jq[4];
  float rq[4], kq[4], cq[4];
#pragma unroll
  for (int q = 0; q < 4; q++) {
    jq[q] = i;
    rq[q] = kq[q] = cq[q] = 0.0f;
    if (s0 + q < MSOCL_TABLE_SLOTS) {
      const int at = (s0 + q) * n + i;
      jq[q] = nbr[at];
      msocl_values(rk, dmp, at, &rq[q], &kq[q], &cq[q]);
    }
  }
  *j = (int4)(jq[0], jq[1], jq[2], jq[3]);
  *rest = (float4)(rq[0], rq[1], rq[2], rq[3]);
  *k = (float4)(kq[0], kq[1], kq[2], kq[3]);
  *c = (float4)(cq[0], cq[1], cq[2], cq[3]);
#endif
}

/* buf at the four points j, less o: their x, y and z differences, each a
 * vector of four (the gathers' transpose). */
static void msocl_diff4(__global const float4 *buf, int4 j, float4 o,
                        float4 *dx, float4 *dy, float4 *dz)
{
  float4 a = buf[j.x], b = buf[j.y], e = buf[j.z], g = buf[j.w];
  *dx = (float4)(a.x, b.x, e.x, g.x) - o.x;
  *dy = (float4)(a.y, b.y, e.y, g.y) - o.y;
  *dz = (float4)(a.z, b.z, e.z, g.z) - o.z;
}

/* What every kernel file shares: math mode, access to a point's springs
 * (whichever layout holds them), spring forces and collision response.
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
 *   MSOCL_PINS             pinned points (pos.w != 0)
 *   MSOCL_PLANE, MSOCL_SPHERE, MSOCL_TABLE   collider kinds present
 *   MSOCL_RELAXED          native functions (with -cl-fast-relaxed-math)
 * State is float4 (xyz, w): pos.w = 1 marks a pinned point. */

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

#ifdef MSOCL_PINS
#define MSOCL_PINNED(p4) ((p4).w != 0.0f)
#else
#define MSOCL_PINNED(p4) 0
#endif

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
/* The slots msocl_force takes four at a time (BUFFER: the table's). */
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

/* Slot s of point i: the other end *j, rest length, stiffness and dashpot
 * coefficient; returns 0 past the last spring (GRID: never). The texture is
 * the paper's: 16 tiles of W x H, slot s in tile (s % 4, s / 4), entry
 * (x, y of the other end, rest, k), -1 = end; dashpots in a (4W) x H image,
 * four slots a texel. BUFFER is slot-major: slot s of point i at s * n + i;
 * a free slot holds, like GRID's missing neighbour, a spring to the point
 * itself with rest, k and c 0 (layout.c; a model has no such spring), which
 * adds exact zeros wherever it is summed. */
static int msocl_slot(MSOCL_CONN, int i, int s, int n, int *j, float *rest,
                      float *k, float *c)
{
#if defined(MSOCL_LAYOUT_GRID) && defined(MSOCL_GRID_3D)
  /* as the cloth's below, in three dimensions */
  int x = i % grid_nx, t = i / grid_nx, y = t % grid_ny, z = t / grid_ny;
  int qx = x + msocl_grid_dx[s], qy = y + msocl_grid_dy[s],
      qz = z + msocl_grid_dz[s];
  float kk = MSOCL_GRID_K(s);
  bool there = qx >= 0 && qx < grid_nx && qy >= 0 && qy < grid_ny &&
               qz >= 0 && qz < grid_nz && kk != 0.0f;
  *j = there ? (qz * grid_ny + qy) * grid_nx + qx : i;
  *rest = MSOCL_GRID_R(s);
  *k = there ? kk : 0.0f;
  *c = there ? MSOCL_GRID_C : 0.0f;
  (void)n;
  return 1;
#elif defined(MSOCL_LAYOUT_GRID)
  /* A missing neighbour (grid edge, or a kind the cloth leaves out) is a
   * spring to the point itself with k = 0: it adds exact zeros, and the
   * loop keeps a fixed trip count. */
  int x = i % grid_nx, y = i / grid_nx;
  int qx = x + msocl_grid_dx[s], qy = y + msocl_grid_dy[s];
  int kind = msocl_grid_kind[s];
  float kk = kind == 0 ? grid_k.x : kind == 1 ? grid_k.y : grid_k.z;
  bool there = qx >= 0 && qx < grid_nx && qy >= 0 && qy < grid_ny &&
               kk != 0.0f;
  int ri = msocl_grid_rest[s];
  float r = ri == 0 ? grid_rest.s0 : ri == 1 ? grid_rest.s1
          : ri == 2 ? grid_rest.s2 : ri == 3 ? grid_rest.s3
          : ri == 4 ? grid_rest.s4 : grid_rest.s5;
  *j = there ? qy * grid_nx + qx : i;
  *rest = r;
  *k = there ? kk : 0.0f;
  *c = there ? grid_k.w : 0.0f;
  (void)n;
  return 1;
#elif defined(MSOCL_LAYOUT_IMAGE2D)
  const sampler_t smp =
      CLK_NORMALIZED_COORDS_FALSE | CLK_ADDRESS_NONE | CLK_FILTER_NEAREST;
  int x = i % tex_w, y = i / tex_w;
  float4 e = read_imagef(con, smp, (int2)(x + (s & 3) * tex_w,
                                          y + (s >> 2) * tex_h));
  if (e.x < 0.0f)
    return 0;
  *j = (int)e.y * tex_w + (int)e.x;
  *rest = e.z;
  *k = e.w;
#ifdef MSOCL_DAMPING
  float4 c4 = read_imagef(dmp, smp, (int2)(x + (s >> 2) * tex_w, y));
  int q = s & 3;
  *c = q == 0 ? c4.x : q == 1 ? c4.y : q == 2 ? c4.z : c4.w;
#else
  *c = 0.0f;
#endif
  return 1;
#else
  int at = s * n + i;
#ifdef MSOCL_SPILL
  if (s >= MSOCL_SLOTS) {
    int o = spill[i] + (s - MSOCL_SLOTS);
    if (o >= spill[i + 1])
      return 0;
    at = MSOCL_SLOTS * n + o;
  }
#endif
  *j = nbr[at];
  msocl_values(rk, dmp, at, rest, k, c);
  return *j != i;
#endif
}

/* Slots s0 .. s0 + 3 of point i (s0 a multiple of 4, unrolled) as
 * vectors; a slot past the last is the point itself with zeros. */
static void msocl_slot4(MSOCL_CONN, int i, int s0, int n, int4 *j,
                        float4 *rest, float4 *k, float4 *c)
{
#if defined(MSOCL_LAYOUT_GRID) && defined(MSOCL_GRID_3D)
  /* msocl_slot's arithmetic on four lanes at once, the point's (x, y, z)
   * found once; a group of four may mix kinds */
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
  /* msocl_slot's arithmetic on four lanes at once. Each group of four
   * neighbours is of one kind (stretch, shear, bend). */
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
  /* msocl_slot's reads, but the group's four dashpots share one texel:
   * one read for them, not four (a free slot's is 0, and its spring to
   * the point itself adds zeros whatever c is) */
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
    if (s0 + q < MSOCL_TABLE_SLOTS)
      msocl_slot(MSOCL_CONN_ARGS, i, s0 + q, n, &jq[q], &rq[q], &kq[q],
                 &cq[q]);
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

/* Internal and viscous force on point i (not gravity): the gather over its
 * springs, in slot order - each spring k (len - rest) / len d (Hooke, eq. 2
 * of the paper; a zero-length spring exerts nothing rather than NaN) and
 * each dashpot c dot(vq - vp, d) / len^2 d, four slots at a time, so that their square roots and divisions, which bounded this loop
 * on a CPU (PoCL runs it one work-item at a time: docs/PERFORMANCE.md),
 * take one SIMD instruction for four springs. Each lane does the scalar
 * arithmetic, and the sums still go slot after slot: bitwise the one-slot
 * loop's result (and serial C's). */
static float3 msocl_force(MSOCL_CONN, __global const float4 *pos,
                          __global const float4 *vel, int i, int n,
                          float viscous)
{
  float4 p = pos[i], v = vel[i];
  float fx = 0.0f, fy = 0.0f, fz = 0.0f;
  /* unrolled for a mesh's few slots; a wide table (tuning.buffer_slots)
   * would only bloat the code */
#if MSOCL_TABLE_SLOTS <= 64
#pragma unroll
#endif
  for (int s0 = 0; s0 < MSOCL_TABLE_SLOTS; s0 += 4) {
    int4 j;
    float4 rest, k, c;
    msocl_slot4(MSOCL_CONN_ARGS, i, s0, n, &j, &rest, &k, &c);
    float4 dx, dy, dz;
    msocl_diff4(pos, j, p, &dx, &dy, &dz);
    /* dot(d, d) = (x x + y y) + z z */
    float4 len2 = dx * dx + dy * dy + dz * dz;
    float4 len = MSOCL_SQRT(len2);
    float4 t = k * MSOCL_DIV(len - rest, len);
    int4 on = len > 0.0f;
    float4 sx = select((float4)(0.0f), t * dx, on);
    float4 sy = select((float4)(0.0f), t * dy, on);
    float4 sz = select((float4)(0.0f), t * dz, on);
#ifdef MSOCL_DAMPING
    float4 wx, wy, wz;
    msocl_diff4(vel, j, v, &wx, &wy, &wz);
    float4 u = c * MSOCL_DIV(wx * dx + wy * dy + wz * dz, len2);
    on = len2 > 0.0f;
    float4 hx = select((float4)(0.0f), u * dx, on);
    float4 hy = select((float4)(0.0f), u * dy, on);
    float4 hz = select((float4)(0.0f), u * dz, on);
#define MSOCL_ADD(q)                                                          \
  fx += sx.q; fy += sy.q; fz += sz.q;                                         \
  fx += hx.q; fy += hy.q; fz += hz.q
#else
#define MSOCL_ADD(q) fx += sx.q; fy += sy.q; fz += sz.q
#endif
    /* slot by slot; past the last slot, nothing (not even its zeros) */
    MSOCL_ADD(x);
    if (s0 + 1 < MSOCL_TABLE_SLOTS) {
      MSOCL_ADD(y);
    }
    if (s0 + 2 < MSOCL_TABLE_SLOTS) {
      MSOCL_ADD(z);
    }
    if (s0 + 3 < MSOCL_TABLE_SLOTS) {
      MSOCL_ADD(w);
    }
#undef MSOCL_ADD
    (void)c;
  }
#ifdef MSOCL_SPILL
  /* the springs past the table, one at a time in one lane's arithmetic:
   * the same sums, in the same order, as a table long enough for all */
  for (int o = spill[i]; o < spill[i + 1]; o++) {
    const int at = MSOCL_SLOTS * n + o;
    float rest, k, c;
    msocl_values(rk, dmp, at, &rest, &k, &c);
    const float4 q = pos[nbr[at]];
    float dx = q.x - p.x, dy = q.y - p.y, dz = q.z - p.z;
    float len2 = dx * dx + dy * dy + dz * dz, len = MSOCL_SQRT(len2);
    float t = k * MSOCL_DIV(len - rest, len);
    /* adding the zero too, as a lane does: -0 + 0 is +0 */
    fx += len > 0.0f ? t * dx : 0.0f;
    fy += len > 0.0f ? t * dy : 0.0f;
    fz += len > 0.0f ? t * dz : 0.0f;
#ifdef MSOCL_DAMPING
    const float4 w = vel[nbr[at]] - v;
    float u = c * MSOCL_DIV(w.x * dx + w.y * dy + w.z * dz, len2);
    fx += len2 > 0.0f ? u * dx : 0.0f;
    fy += len2 > 0.0f ? u * dy : 0.0f;
    fz += len2 > 0.0f ? u * dz : 0.0f;
#endif
  }
#endif
  float3 f = (float3)(fx, fy, fz);
#ifdef MSOCL_VISCOUS
  f -= viscous * v.xyz;
#endif
  (void)v; (void)viscous;
  return f;
}

/* Collision response by changing velocity (the paper's way). g is a convex
 * function that is >= 0 outside the collider, n its unit gradient. Because
 * g is convex, g(p + dt v) >= g(p) + dt n.v, so raising n.v to at least
 * -g/dt keeps the new position outside. Friction scales away that fraction
 * of the tangential velocity on contact. */
static float3 msocl_respond(float3 v, float g, float3 n, float friction,
                            float dt)
{
  float vn = dot(v, n);
  float lim = MSOCL_DIV(-g, dt);
  if (vn < lim) {
    v = v + (lim - vn) * n;
    v = v - friction * (v - lim * n);
  }
  return v;
}

/* The collider's g (>= 0 outside) and unit gradient n at p. */
static float msocl_collider_gap(float3 p, float4 head, float4 prm, float3 *n)
{
  int kind = (int)head.x;
#ifdef MSOCL_PLANE
  if (kind == MSOCL_PLANE_KIND) {
    *n = prm.xyz;
    return dot(prm.xyz, p) - prm.w;
  }
#endif
#ifdef MSOCL_SPHERE
  if (kind == MSOCL_SPHERE_KIND) {
    float3 d = p - prm.xyz;
    float len = MSOCL_SQRT(dot(d, d));
    *n = len > 0.0f ? d / len : (float3)(0.0f, 1.0f, 0.0f);
    return len - prm.w;
  }
#endif
#ifdef MSOCL_TABLE
  if (kind == MSOCL_TABLE_KIND) {
    /* max(radial distance - R, height above top): convex, zero on the
     * table's surface. */
    float dx = p.x - prm.x, dz = p.z - prm.z;
    float rr = MSOCL_SQRT(dx * dx + dz * dz);
    float gside = rr - prm.w, gtop = p.y - prm.y;
    if (gtop >= gside || !(rr > 0.0f)) {
      *n = (float3)(0.0f, 1.0f, 0.0f);
      return gtop;
    }
    *n = (float3)(dx / rr, 0.0f, dz / rr);
    return gside;
  }
#endif
  (void)kind; (void)p; (void)prm;
  *n = (float3)(0.0f, 1.0f, 0.0f);
  return INFINITY;
}

/* Velocity response for a point at p about to move by dt * v; friction
 * scaled by fscale (0 when a velocity is corrected again within a step:
 * friction acts once a step). */
static float3 msocl_collide(float3 p, float3 v, float dt,
                            __constant float4 *col, int ncol, float fscale)
{
  for (int c = 0; c < ncol; c++) {
    float3 n;
    float g = msocl_collider_gap(p, col[2 * c], col[2 * c + 1], &n);
    v = msocl_respond(v, g, n, fscale * col[2 * c].y, dt);
  }
  return v;
}

/* For integrators whose position update does not use the velocity the
 * response sees (explicit Euler, RK4): a point found inside a collider
 * after the step is put back on its surface and loses its inward normal
 * velocity (friction as above). */
static void msocl_project(float3 *p, float3 *v, __constant float4 *col,
                          int ncol)
{
  for (int c = 0; c < ncol; c++) {
    float3 n;
    float g = msocl_collider_gap(*p, col[2 * c], col[2 * c + 1], &n);
    if (g < 0.0f) {
      *p = *p - g * n;
      float vn = dot(*v, n);
      if (vn < 0.0f) {
        *v = *v - vn * n;
        *v = *v - col[2 * c].y * *v;
      }
    }
  }
}

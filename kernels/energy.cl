/* Energy of the state, summed on the device: each work-group of 64 points
 * writes one partial (kinetic, spring, gravitational, 0); the host adds the
 * partials in double (group 0 starts at the launch's global offset). A
 * spring's energy k (l - r)^2 / 2 is split between
 * its two ends, as each end's gather sees it. */
#include "common.h"

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

#define MSOCL_ENERGY_GROUP 64

__kernel __attribute__((reqd_work_group_size(MSOCL_ENERGY_GROUP, 1, 1)))
void msocl_energy(MSOCL_CONN, __global const float4 *pos,
                  __global const float4 *vel,
                  __global const float *inv_mass, float4 gravity,
                  __global float4 *partial, int n, int end)
{
  __local float4 part[MSOCL_ENERGY_GROUP];
  int i = get_global_id(0), l = get_local_id(0);
  float4 e = (float4)(0.0f);
  if (i < end) { /* end: the last point of this device's range, + 1 */
    float3 p = pos[i].xyz, v = vel[i].xyz;
    float m = 1.0f / inv_mass[i];
    e.x = 0.5f * m * dot(v, v);
    /* four slots at a time (a free slot, the
     * point itself with k 0, adds an exact 0): one slot at a time this
     * loop cost five velocity passes on PoCL */
#if MSOCL_TABLE_SLOTS <= 64
#pragma unroll
#endif
    for (int s0 = 0; s0 < MSOCL_TABLE_SLOTS; s0 += 4) {
      int4 j;
      float4 rest, k, c;
      msocl_slot4(MSOCL_CONN_ARGS, i, s0, n, &j, &rest, &k, &c);
      float4 dx, dy, dz;
      msocl_diff4(pos, j, (float4)(p, 0.0f), &dx, &dy, &dz);
      float4 stretch = MSOCL_SQRT(dx * dx + dy * dy + dz * dz) - rest;
      float4 t = 0.25f * k * stretch * stretch;
      e.y += t.x;
      if (s0 + 1 < MSOCL_TABLE_SLOTS)
        e.y += t.y;
      if (s0 + 2 < MSOCL_TABLE_SLOTS)
        e.y += t.z;
      if (s0 + 3 < MSOCL_TABLE_SLOTS)
        e.y += t.w;
      (void)c;
    }
#ifdef MSOCL_SPILL
    for (int o = spill[i]; o < spill[i + 1]; o++) {
      const int at = MSOCL_SLOTS * n + o;
      float rest, k, c;
      msocl_values(rk, dmp, at, &rest, &k, &c);
      float3 d = pos[nbr[at]].xyz - p;
      float stretch = MSOCL_SQRT(dot(d, d)) - rest;
      e.y += 0.25f * k * stretch * stretch;
    }
#endif
    e.z = -m * dot(gravity.xyz, p);
  }
  part[l] = e;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int w = MSOCL_ENERGY_GROUP / 2; w > 0; w >>= 1) {
    if (l < w)
      part[l] += part[l + w];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0)
    partial[get_group_id(0)] = part[0];
}

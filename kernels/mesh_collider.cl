/* Triangle-mesh colliders in the planes engine (lib/engine/mesh_collider.c):
 * after each step, each point is kept `thickness` from the mesh, and out
 * of a closed one. The mesh's vertices move linearly from va (the call's
 * start) to vb (its end); this step runs from fraction f0 to f1 of that
 * motion. Each call places the grid's triangles once (cur: their corners
 * at both ends and a sphere that bounds them all the way), and each step
 * places between the ends only the triangles its points come near. A
 * uniform grid over the call's swept bounds lists, per cell, the
 * triangles whose swept bounds (grown by the reach) touch it, so a point
 * looks only at its own cell (a grid culled to where the cloth will be
 * leaves a point outside it, within the mesh's bounds, all triangles). */
#include "planes.h"
#if defined(MSOCL_PLANES)

/* The closest point to p on triangle abc as barycentric weights (wa, wb,
 * wc) in *w, and the feature it lies on: 0 inside, 1 2 4 edges ab bc ca,
 * 8 16 32 corners a b c (Ericson, Real-Time Collision Detection 5.1.5). */
static inline int msocl_mesh_closest(float3 p, float3 a, float3 b, float3 c,
                                     float3 *w)
{
  const float3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) {
    *w = (float3)(1.0f, 0.0f, 0.0f);
    return 8;
  }
  const float3 bp = p - b;
  const float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) {
    *w = (float3)(0.0f, 1.0f, 0.0f);
    return 16;
  }
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float t = d1 / (d1 - d3);
    *w = (float3)(1.0f - t, t, 0.0f);
    return 1;
  }
  const float3 cp = p - c;
  const float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) {
    *w = (float3)(0.0f, 0.0f, 1.0f);
    return 32;
  }
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float t = d2 / (d2 - d6);
    *w = (float3)(1.0f - t, 0.0f, t);
    return 4;
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    *w = (float3)(0.0f, 1.0f - t, t);
    return 2;
  }
  const float s = 1.0f / (va + vb + vc);
  *w = (float3)(va * s, vb * s, vc * s);
  return 0;
}

/* Vertex k of a mesh whose vertices lie in three planes of nv floats. */
static inline float3 msocl_mesh_vertex(__global const float *m, int k, int nv)
{
  return (float3)(m[k], m[nv + k], m[2 * nv + k]);
}

/* a to b at fraction f: a triangle's corners, wherever placed */
#define MSOCL_MESH_LERP(a, b, f) ((a) + ((b) - (a)) * (f))

/* Triangle t over the call, as msocl_mesh_place writes it into cur (q[0
 * .. 7]): its corners at the call's start (q[0 .. 2]) and end (q[3 .. 5]),
 * and a sphere that holds it at every fraction of the motion between:
 * about the centroid at the start (q[6].xyz) moved by a fraction of its
 * motion (q[7].xyz), a radius (q[6].w) past both ends' (a corner's
 * offset from the centroid moves linearly, so its length is largest at
 * an end), grown for the roundings of the centroid placed. */
static inline void msocl_mesh_ends(__global const float *va,
                                   __global const float *vb,
                                   __global const int *tri, int t, int nv,
                                   int nt, float4 *q)
{
  const int k[3] = {tri[t], tri[nt + t], tri[2 * nt + t]};
  float r2 = 0.0f;
  for (int e = 0; e < 2; e++) {
    __global const float *v = e ? vb : va;
    const float3 A = msocl_mesh_vertex(v, k[0], nv),
                 B = msocl_mesh_vertex(v, k[1], nv),
                 C = msocl_mesh_vertex(v, k[2], nv);
    const float3 m = (A + B + C) / 3.0f;
    r2 = fmax(r2, fmax(dot(A - m, A - m),
                       fmax(dot(B - m, B - m), dot(C - m, C - m))));
    q[3 * e] = (float4)(A, 0.0f);
    q[3 * e + 1] = (float4)(B, 0.0f);
    q[3 * e + 2] = (float4)(C, 0.0f);
    q[6 + e] = (float4)(m, 0.0f);
  }
  const float3 big = fmax(fabs(q[6].xyz), fabs(q[7].xyz));
  q[6].w = sqrt(r2) * 1.0001f + 1e-6f * (big.x + big.y + big.z);
  q[7].xyz -= q[6].xyz;
}

/* One mesh collider on every point of the planes state: p and v (this
 * step's end, changed in place), pp (its start), aux (pins: left alone).
 * tri: three planes of nt corner indices; rim: each triangle's features on
 * the open mesh's boundary (msocl_mesh_closest's bits); the grid: cells
 * gx * gy * gz of size 1 / origin.w from origin.xyz, cell c's triangles
 * cell_tri[cell_start[c] .. cell_start[c + 1]). prm: (f0, f1, thickness,
 * friction); orient: +1 or -1 for a closed mesh (the side its normals
 * point to is outside), 0 for an open one (a point stays on the side of
 * the triangle it was on at the step's start). */
static inline void msocl_mesh_point(
    __global float *p, __global float *v, __global const float *pp,
    __global const float *aux, __global const float *va,
    __global const float *vb, __global const int *tri,
    __global const int *rim, __global const int *cell_start,
    __global const int *cell_tri, float4 origin, int gx, int gy, int gz,
    float4 prm, float orient, float dt, int nv, int nt, int plane,
    __global const float4 *cur, float reach2, __global int *esc, int cell,
    int a)
{
  if (cell == -1)
    return;
  const float3 P = (float3)(p[a], p[plane + a], p[2 * plane + a]);
  const float f0 = prm.x, f1 = prm.y, thick = prm.z;
  float best = reach2; /* farther than the reach: no contact */
  float root = sqrt(best);
  int bt = -1, bfeat = 0;
  float3 bw = (float3)(0.0f), A1 = bw, B1 = bw, C1 = bw;
  /* outside the culled grid (cell -2): every triangle, placed here */
  const bool all = cell < 0;
  if (all)
    *esc = 1; /* for the host: the next calls' grids not culled */
  const int q0 = all ? 0 : cell_start[cell], q1 = all ? nt : cell_start[cell + 1];
  for (int q = q0; q < q1; q++) {
    const int t = all ? q : cell_tri[q];
    __global const float4 *ct = cur + 8 * t;
    float4 g[8];
    if (all)
      msocl_mesh_ends(va, vb, tri, t, nv, nt, g);
    const float4 s0 = all ? g[6] : ct[6], s1 = all ? g[7] : ct[7];
    /* the distances to its bounding sphere and to its plane bound the
     * distance to the triangle: most triangles end there (the sphere's
     * |P - m| - r >= root squared, with no root taken a triangle) */
    const float3 e = P - (s0.xyz + s1.xyz * f1);
    const float out = s0.w + root;
    if (dot(e, e) >= out * out)
      continue;
    const float3 A = all ? MSOCL_MESH_LERP(g[0].xyz, g[3].xyz, f1)
                         : MSOCL_MESH_LERP(ct[0].xyz, ct[3].xyz, f1),
                 B = all ? MSOCL_MESH_LERP(g[1].xyz, g[4].xyz, f1)
                         : MSOCL_MESH_LERP(ct[1].xyz, ct[4].xyz, f1),
                 C = all ? MSOCL_MESH_LERP(g[2].xyz, g[5].xyz, f1)
                         : MSOCL_MESH_LERP(ct[2].xyz, ct[5].xyz, f1);
    const float3 c = cross(B - A, C - A); /* not unit: no root */
    const float h = dot(P - A, c);
    if (h * h > best * dot(c, c))
      continue;
    float3 w;
    const int feat = msocl_mesh_closest(P, A, B, C, &w);
    const float3 d = P - (w.x * A + w.y * B + w.z * C);
    const float d2 = dot(d, d);
    if (d2 < best) {
      best = d2;
      root = sqrt(d2);
      bt = t;
      bw = w;
      bfeat = feat;
      A1 = A;
      B1 = B;
      C1 = C;
    }
  }
  if (bt < 0)
    return;
  const int i0 = tri[bt], i1 = tri[nt + bt], i2 = tri[2 * nt + bt];
  const float3 A0 = msocl_mesh_vertex(va, i0, nv),
               B0 = msocl_mesh_vertex(va, i1, nv),
               C0 = msocl_mesh_vertex(va, i2, nv);
  const float3 DA = msocl_mesh_vertex(vb, i0, nv) - A0,
               DB = msocl_mesh_vertex(vb, i1, nv) - B0,
               DC = msocl_mesh_vertex(vb, i2, nv) - C0;
  const float3 n1 = normalize(cross(B1 - A1, C1 - A1));
  /* the side the point belongs on */
  float side = orient;
  if (orient == 0.0f) {
    const float3 As = A0 + f0 * DA, Bs = B0 + f0 * DB, Cs = C0 + f0 * DC;
    const float3 PP = (float3)(pp[a], pp[plane + a], pp[2 * plane + a]);
    side = dot(PP - As, cross(Bs - As, Cs - As)) >= 0.0f ? 1.0f : -1.0f;
  }
  const float3 c1 = bw.x * A1 + bw.y * B1 + bw.z * C1;
  const float3 D = P - c1;
  const float dist = root; /* sqrt(best) */
  const bool behind = dot(D, n1) * side < 0.0f;
  /* behind an open mesh's boundary the point went round its rim, not
   * through it: kept off the rim like a point in front */
  const bool through = behind && (orient != 0.0f || (rim[bt] & bfeat) == 0);
  if (!through && dist >= thick)
    return;
  const float tiny = 1e-6f * thick;
  float3 nrm = dist > tiny ? D / dist : side * n1;
  if (through)
    nrm = dist > tiny ? -nrm : side * n1;
  /* the mesh's velocity at the contact over this step */
  const float3 u =
      (f1 - f0) / dt * (bw.x * DA + bw.y * DB + bw.z * DC);
  const float3 V = (float3)(v[a], v[plane + a], v[2 * plane + a]);
  const float3 rel = V - u;
  const float vn = dot(rel, nrm);
  const float3 vt = rel - vn * nrm;
  const float3 Vn = u + fmax(vn, 0.0f) * nrm + (1.0f - prm.w) * vt;
  /* the step moved the point by dt v: friction takes back its share of
   * the tangential part too, or a point held still by friction would
   * move without velocity, a step that is unstable near the stable dt */
  const float3 Pn = c1 + thick * nrm - (dt * prm.w) * vt;
  p[a] = Pn.x;
  p[plane + a] = Pn.y;
  p[2 * plane + a] = Pn.z;
  v[a] = Vn.x;
  v[plane + a] = Vn.y;
  v[2 * plane + a] = Vn.z;
}

/* Each triangle over the call into cur (msocl_mesh_ends), work-item i
 * taking live[i] where nlive >= 0 (the grid's triangles), else i; those
 * past the count do nothing. */
__kernel void msocl_mesh_place(__global const float *va,
                               __global const float *vb,
                               __global const int *tri, __global float4 *cur,
                               int nv, int nt, __global const int *live,
                               int nlive)
{
  const int i = get_global_id(0);
  if (i >= (nlive >= 0 ? nlive : nt))
    return;
  const int t = nlive >= 0 ? live[i] : i;
  float4 q[8];
  msocl_mesh_ends(va, vb, tri, t, nv, nt, q);
  for (int j = 0; j < 8; j++)
    cur[8 * t + j] = q[j];
}

/* Point a's cell, -1 where it has no triangles (or is pinned, or outside
 * the grid and, where the grid is culled, outside the mesh's bounds box
 * [lo, hi], or NaN: every comparison false), -2 outside a culled grid
 * inside that box (the point searches every triangle); the roundings of
 * the grid's build (msocl_mesh_span), without a branch. */
static inline int msocl_mesh_cell_of(__global const float *p,
                                     __global const float *aux,
                                     __global const int *cell_start,
                                     float4 origin, int gx, int gy, int gz,
                                     int plane, float4 lo, float4 hi,
                                     int culled, int a)
{
  const float w = origin.w;
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a];
  const float fx = floor((px - origin.x) * w),
              fy = floor((py - origin.y) * w),
              fz = floor((pz - origin.z) * w);
  const bool free = !MSOCL_PLANES_PINNED(aux[plane + a]);
  const bool in = fx >= 0.0f && fy >= 0.0f && fz >= 0.0f && fx < (float)gx &&
                  fy < (float)gy && fz < (float)gz && free;
  const bool box = culled && px >= lo.x && py >= lo.y && pz >= lo.z &&
                   px <= hi.x && py <= hi.y && pz <= hi.z && free;
  const int c = in ? ((int)fz * gy + (int)fy) * gx + (int)fx : 0;
  const bool any = cell_start[c + 1] > cell_start[c];
  return in && any ? c : box && !in ? -2 : -1;
}

/* The cells of the n (at most 8) points from a into cell[], as
 * msocl_mesh_cell_of finds each (its tests in float8, the same roundings),
 * or false where none of the 8 is near the grid: a chunk far from the
 * grid costs a few vector tests, a near one no scalar floor. */
static inline bool msocl_mesh_cells8(__global const float *p,
                                     __global const float *aux,
                                     __global const int *cell_start,
                                     float4 origin, int gx, int gy, int gz,
                                     int plane, float4 lo, float4 hi,
                                     int culled, int a, int n, int *cell)
{
  const float w = origin.w;
  const float8 px = vload8(0, p + a), py = vload8(0, p + plane + a),
               pz = vload8(0, p + 2 * plane + a);
  /* floor(u) >= 0 and < g just where u is: no floor, and for u >= 0 the
   * conversion truncates as floor does */
  const float8 fx = (px - origin.x) * w, fy = (py - origin.y) * w,
               fz = (pz - origin.z) * w;
  const int8 in = fx >= 0.0f & fy >= 0.0f & fz >= 0.0f & fx < (float)gx &
                  fy < (float)gy & fz < (float)gz;
  const int8 box = px >= lo.x & py >= lo.y & pz >= lo.z & px <= hi.x &
                   py <= hi.y & pz <= hi.z & (int8)(culled ? -1 : 0);
  if (!any(in | box))
    return false;
  const int8 c = select((int8)(0), (convert_int8(fz) * gy +
                                    convert_int8(fy)) * gx + convert_int8(fx),
                        in);
  int ci[8], ini[8], boxi[8];
  vstore8(c, 0, ci);
  vstore8(in, 0, ini);
  vstore8(box, 0, boxi);
  for (int i = 0; i < n; i++) {
    const bool free = !MSOCL_PLANES_PINNED(aux[plane + a + i]);
    const bool has = ini[i] && cell_start[ci[i] + 1] > cell_start[ci[i]];
    cell[i] = free && has ? ci[i] : free && boxi[i] && !ini[i] ? -2 : -1;
  }
  return true;
}

#define MSOCL_MESH_PARAMS                                                     \
  __global float *p, __global float *v, __global const float *pp,             \
      __global const float *aux, __global const float *va,                    \
      __global const float *vb, __global const int *tri,                      \
      __global const int *rim, __global const int *cell_start,                \
      __global const int *cell_tri, float4 origin, int gx, int gy, int gz,    \
      float4 prm, float orient, float dt, int nv, int nt, int nx, int pitch,  \
      int slab, int plane, __global const float4 *cur, float reach2,          \
      int culled, float4 lo, float4 hi, __global int *esc, int rows_y,        \
      int runs
#define MSOCL_MESH_ARGS(c, a)                                                 \
  p, v, pp, aux, va, vb, tri, rim, cell_start, cell_tri, origin, gx, gy, gz,  \
      prm, orient, dt, nv, nt, plane, cur, reach2, esc, c, a

/* A work-item a point (GPUs). */
__kernel void msocl_mesh_collide(MSOCL_MESH_PARAMS)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab; (void)rows_y; (void)runs;
  if (x < nx)
    msocl_mesh_point(MSOCL_MESH_ARGS(
        msocl_mesh_cell_of(p, aux, cell_start, origin, gx, gy, gz, plane, lo,
                           hi, culled, a),
        a));
}

/* CPU devices: the runs of MSOCL_MESH_RUN points of each row (`runs` in
 * all, row by row), work-item b of B taking runs b, b + B, ... (a contact
 * spans few rows: interleaved, the cores share it); 8 points at a time
 * are tested in vectors, and only the points of a chunk near the grid
 * find their cells and search (the search cannot be vectorised, and a
 * work-item costs more to schedule than most runs take). A row's padding
 * holds the 8 floats past its last chunk's start. */
#define MSOCL_MESH_RUN 256
__kernel void msocl_mesh_collide_rows(MSOCL_MESH_PARAMS)
{
  const int row_runs = (nx + MSOCL_MESH_RUN - 1) / MSOCL_MESH_RUN;
  (void)slab;
  for (int r = get_global_id(0); r < runs; r += get_global_size(0)) {
    const int row = r / row_runs, y = row % rows_y, z = row / rows_y;
    const int x0 = (r - row * row_runs) * MSOCL_MESH_RUN;
    const int x1 = min(nx, x0 + MSOCL_MESH_RUN);
    (void)y; (void)z;
    for (int x8 = x0; x8 < x1; x8 += 8) {
      const int n = min(x1 - x8, 8);
      int cell[8];
      if (!msocl_mesh_cells8(p, aux, cell_start, origin, gx, gy, gz, plane,
                             lo, hi, culled, MSOCL_PLANES_AT(x8, y, z), n,
                             cell))
        continue;
      for (int x = x8; x < x8 + n; x++) {
        const int a = MSOCL_PLANES_AT(x, y, z);
        msocl_mesh_point(MSOCL_MESH_ARGS(cell[x - x8], a));
      }
    }
  }
}

/* Before a call that moves the mesh: the free points' bounds and their
 * largest squared move since the last such call (prev: their positions
 * then, updated), a run of MSOCL_MESH_RUN points of a row a work-item,
 * into out (8 floats a work-item: low xyz, the move, high xyz,
 * and the first's last: whether a point searched every triangle since,
 * esc, then cleared); the host takes the whole from these. */
__kernel void msocl_mesh_bounds(__global const float *p,
                                __global float *prev,
                                __global const float *aux,
                                __global float4 *out, int nx, int pitch,
                                int slab, int plane, __global int *esc)
{
  const int y = get_global_id(1), z = get_global_id(2);
  const int x0 = get_global_id(0) * MSOCL_MESH_RUN;
  const int x1 = min(nx, x0 + MSOCL_MESH_RUN);
  (void)y; (void)z; (void)slab;
  float4 lo = (float4)(INFINITY, INFINITY, INFINITY, 0.0f);
  float4 hi = (float4)(-INFINITY, -INFINITY, -INFINITY, 0.0f);
  for (int x = x0; x < x1; x++) {
    const int a = MSOCL_PLANES_AT(x, y, z);
    if (MSOCL_PLANES_PINNED(aux[plane + a]))
      continue;
    const float4 P = (float4)(p[a], p[plane + a], p[2 * plane + a], 0.0f);
    const float3 M = P.xyz - (float3)(prev[a], prev[plane + a],
                                      prev[2 * plane + a]);
    prev[a] = P.x;
    prev[plane + a] = P.y;
    prev[2 * plane + a] = P.z;
    lo = fmin(lo, P);
    hi = fmax(hi, P);
    lo.w = fmax(lo.w, dot(M, M));
  }
  const int o = (z * (int)get_global_size(1) + y) * (int)get_global_size(0) +
                (int)get_global_id(0);
  if (o == 0) {
    hi.w = (float)*esc;
    *esc = 0;
  }
  out[2 * o] = lo;
  out[2 * o + 1] = hi;
}

/* The grid, built on the device each call that moves the mesh
 * (mesh_collider.c picks origin, cell size and dims): count the cells
 * each triangle's swept bounds cover, an exclusive scan of the counts,
 * fill, and each cell's list sorted by triangle, so that the lists are
 * the host reference build's whatever order the atomics ran in. */

/* The cells lo[c] .. hi[c] that triangle t's bounds over the call (its
 * corners at va and vb, grown by reach) cover, clamped to the grid, and
 * whether they miss the grid (a grid culled to the cloth's reach leaves
 * such a triangle out): the same float operations as the host's build. */
static inline bool msocl_mesh_span(__global const float *va,
                                   __global const float *vb,
                                   __global const int *tri, int t, int nv,
                                   int nt, float4 origin, int4 g, float reach,
                                   int4 *lo, int4 *hi)
{
  const int k0 = tri[t], k1 = tri[nt + t], k2 = tri[2 * nt + t];
  float mn[3], mx[3];
  for (int c = 0; c < 3; c++) {
    const float x0 = va[c * nv + k0], x1 = va[c * nv + k1],
                x2 = va[c * nv + k2], y0 = vb[c * nv + k0],
                y1 = vb[c * nv + k1], y2 = vb[c * nv + k2];
    mn[c] = fmin(fmin(fmin(x0, x1), fmin(x2, y0)), fmin(y1, y2));
    mx[c] = fmax(fmax(fmax(x0, x1), fmax(x2, y0)), fmax(y1, y2));
  }
  const float3 o = origin.xyz;
  const float3 top3 = convert_float3(g.xyz);
  /* clamped to [-1, g] in float first, so that the ints are in range */
  const float3 a = clamp(floor(((float3)(mn[0], mn[1], mn[2]) - reach - o) *
                               origin.w), -1.0f, top3),
               b = clamp(floor(((float3)(mx[0], mx[1], mx[2]) + reach - o) *
                               origin.w), -1.0f, top3);
  const int4 ia = (int4)(convert_int3(a), 0), ib = (int4)(convert_int3(b), 0);
  const int4 top = (int4)(g.xyz - 1, 0); /* w: unused, kept in range */
  *lo = clamp(ia, (int4)(0), top);
  *hi = clamp(ib, (int4)(0), top);
  return ia.x > top.x || ia.y > top.y || ia.z > top.z || ib.x < 0 ||
         ib.y < 0 || ib.z < 0;
}

/* Per triangle: count[c] + 1 for each cell c it covers. This kernel, the
 * fill and the sort take `run` items a work-item (CPUs: a work-item costs
 * more to schedule than an item takes; GPUs: 1). */
__kernel void msocl_mesh_count(__global const float *va,
                               __global const float *vb,
                               __global const int *tri,
                               volatile __global int *count, float4 origin,
                               int4 g, float reach, int nv, int nt,
                               int run)
{
  const int t0 = get_global_id(0) * run, t1 = min(nt, t0 + run);
  for (int t = t0; t < t1; t++) {
    int4 lo, hi;
    if (msocl_mesh_span(va, vb, tri, t, nv, nt, origin, g, reach, &lo, &hi))
      continue;
    for (int z = lo.z; z <= hi.z; z++)
      for (int y = lo.y; y <= hi.y; y++)
        for (int x = lo.x; x <= hi.x; x++)
          atomic_inc(&count[(z * g.y + y) * g.x + x]);
  }
}

/* Per triangle: itself into each cell it covers, at start[c] plus the
 * cell's count so far (count zeroed again before). The triangles run in
 * reverse so that, where a device runs the atomics in order, a list the
 * sort left unsorted shows in the tests. */
__kernel void msocl_mesh_fill(__global const float *va,
                              __global const float *vb,
                              __global const int *tri,
                              volatile __global int *count,
                              __global const int *start,
                              __global int *list, float4 origin, int4 g,
                              float reach, int nv, int nt, int run)
{
  const int u0 = get_global_id(0) * run, u1 = min(nt, u0 + run);
  for (int u = u0; u < u1; u++) {
    const int t = nt - 1 - u;
    int4 lo, hi;
    if (msocl_mesh_span(va, vb, tri, t, nv, nt, origin, g, reach, &lo, &hi))
      continue;
    for (int z = lo.z; z <= hi.z; z++)
      for (int y = lo.y; y <= hi.y; y++)
        for (int x = lo.x; x <= hi.x; x++) {
          const int c = (z * g.y + y) * g.x + x;
          list[start[c] + atomic_inc(&count[c])] = t;
        }
  }
}

/* The scan, first: sums[i] = the counts of cells [i chunk, (i + 1)
 * chunk) (a work-item a chunk, those past the cells idle). */
__kernel void msocl_mesh_scan_sums(__global const int *count,
                                   __global int *sums, int n, int chunk)
{
  const int i = get_global_id(0), j0 = i * chunk;
  if (j0 >= n)
    return;
  const int j1 = min(n, j0 + chunk);
  int s = 0;
  for (int j = j0; j < j1; j++)
    s += count[j];
  sums[i] = s;
}

/* Then one work-item: the m chunks' sums scanned exclusively in place. */
__kernel void msocl_mesh_scan_top(__global int *sums, int m)
{
  if (get_global_id(0) != 0)
    return;
  int run = 0;
  for (int i = 0; i < m; i++) {
    const int s = sums[i];
    sums[i] = run;
    run += s;
  }
}

/* Then per chunk: start[j] = the counts before cell j, and start[n] the
 * total. */
__kernel void msocl_mesh_scan_out(__global const int *count,
                                  __global const int *sums,
                                  __global int *start, int n, int chunk)
{
  const int i = get_global_id(0), j0 = i * chunk;
  if (j0 >= n)
    return;
  const int j1 = min(n, j0 + chunk);
  int run = sums[i];
  for (int j = j0; j < j1; j++) {
    start[j] = run;
    run += count[j];
  }
  if (j1 == n)
    start[n] = run;
}

/* Heap sort's sift down of l[root] within l[0 .. n). */
static inline void msocl_mesh_sift(__global int *l, int root, int n)
{
  for (;;) {
    int c = 2 * root + 1;
    if (c >= n)
      return;
    if (c + 1 < n && l[c + 1] > l[c])
      c++;
    if (l[root] >= l[c])
      return;
    const int t = l[root];
    l[root] = l[c];
    l[c] = t;
    root = c;
  }
}

/* A cell's list of n in ascending triangle order (insertion sort for the
 * short lists most cells have, heap sort past that). */
static inline void msocl_mesh_sort_cell(__global int *l, int n)
{
  if (n <= 32) {
    for (int i = 1; i < n; i++) {
      const int t = l[i];
      int j = i;
      for (; j > 0 && l[j - 1] > t; j--)
        l[j] = l[j - 1];
      l[j] = t;
    }
    return;
  }
  for (int i = n / 2 - 1; i >= 0; i--)
    msocl_mesh_sift(l, i, n);
  for (int e = n - 1; e > 0; e--) {
    const int t = l[0];
    l[0] = l[e];
    l[e] = t;
    msocl_mesh_sift(l, 0, e);
  }
}

/* Per cell: its list sorted. */
__kernel void msocl_mesh_sort(__global const int *start, __global int *list,
                              int ncell, int run)
{
  const int c0 = get_global_id(0) * run, c1 = min(ncell, c0 + run);
  for (int c = c0; c < c1; c++)
    msocl_mesh_sort_cell(list + start[c], start[c + 1] - start[c]);
}

#endif

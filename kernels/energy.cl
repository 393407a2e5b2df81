/* Energy of the state in planes, summed on the device: each run of 64
 * points (in the model's order, whatever the layout pads) writes one
 * partial (kinetic, spring, gravitational, 0); the host adds the partials
 * in double. A spring's
 * energy k (l - r)^2 / 2 is split between its two ends, as each end's
 * gather sees it; a missing slot adds nothing, so every layout sums the
 * same terms in the same order. */
#include "planes.h"
#include "wide.h"
#if defined(MSOCL_PLANES)

#define MSOCL_ENERGY_GROUP 64

/* The part of the point (x, y, z) at a: kinetic, spring and
 * gravitational energy, into e[0 .. 2]. Scalars only: a vector type stops
 * PoCL vectorising the kernel across its work-items. */
static MSOCL_PLANES_INLINE void msocl_energy_point(
    MSOCL_CONN, __global const float *p, __global const float *v,
    __global const float *aux, float4 gravity, int pitch, int slab, int plane,
    int x, int y, int z, int a, float *e)
{
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a],
              vx = v[a], vy = v[plane + a], vz = v[2 * plane + a];
  const float m = 1.0f / aux[a];
  float es = 0.0f;
#pragma unroll
  for (int s = 0; s < MSOCL_TABLE_SLOTS; s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    const float dx = p[b] - px, dy = p[plane + b] - py,
                dz = p[2 * plane + b] - pz;
    const float stretch = MSOCL_SQRT(dx * dx + dy * dy + dz * dz) - rest;
    es += there ? 0.25f * kk * stretch * stretch : 0.0f;
    (void)cc;
  }
#ifdef MSOCL_SPILL
  for (int o = spill[x]; o < spill[x + 1]; o++) {
    int b;
    float rest, kk, cc;
    msocl_planes_spill_slot(MSOCL_CONN_ARGS, o, slab, &b, &rest, &kk, &cc);
    const float dx = p[b] - px, dy = p[plane + b] - py,
                dz = p[2 * plane + b] - pz;
    const float stretch = MSOCL_SQRT(dx * dx + dy * dy + dz * dz) - rest;
    es += 0.25f * kk * stretch * stretch;
    (void)cc;
  }
#endif
  e[0] = 0.5f * m * MSOCL_DOT3(vx, vy, vz, vx, vy, vz);
  e[1] = es;
  e[2] = -m * MSOCL_DOT3(gravity.x, gravity.y, gravity.z, px, py, pz);
}

/* Each point's part, over the planes' range as their passes run, into
 * three planes of `stride` floats in the model's order (point i = (z ny +
 * y) nx + x): no barrier, so that PoCL vectorises it. */
__kernel void msocl_energy_points(MSOCL_CONN, __global const float *p,
                                  __global const float *v,
                                  __global const float *aux, float4 gravity,
                                  __global float *parts, int pitch, int slab,
                                  int plane, int stride)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
#ifdef MSOCL_LAYOUT_GRID
  const int i = (z * (int)get_global_size(1) + y) * grid_nx + x;
#else
  const int i = x;
#endif
  float e[3];
  msocl_energy_point(MSOCL_CONN_ARGS, p, v, aux, gravity, pitch, slab, plane,
                     x, y, z, a, e);
  if (x < MSOCL_PLANES_NX) {
    parts[i] = e[0];
    parts[stride + i] = e[1];
    parts[2 * stride + i] = e[2];
  }
}

#if defined(MSOCL_ROWS) && !defined(MSOCL_LAYOUT_GRID)
/* msocl_energy_points on BUFFER's table in explicit vectors, sixteen
 * points a work-item (on a CPU device, where PoCL leaves a table's gathers
 * scalar): the same arithmetic lane by lane, a spilling point's springs
 * past the table added after the table's, in order. */
__kernel void msocl_energy_points_wide(MSOCL_CONN, __global const float *p,
                                       __global const float *v,
                                       __global const float *aux,
                                       float4 gravity, __global float *parts,
                                       int pitch, int slab, int plane,
                                       int stride)
{
  MSOCL_WIDE_AT;
  const msocl_rows_f px = MSOCL_ROWS_LOAD(p + a),
                     py = MSOCL_ROWS_LOAD(p + plane + a),
                     pz = MSOCL_ROWS_LOAD(p + 2 * plane + a),
                     vx = MSOCL_ROWS_LOAD(v + a),
                     vy = MSOCL_ROWS_LOAD(v + plane + a),
                     vz = MSOCL_ROWS_LOAD(v + 2 * plane + a);
  const msocl_rows_f m = 1.0f / MSOCL_ROWS_LOAD(aux + a);
  msocl_rows_f es = 0.0f;
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
    const msocl_rows_f dx = MSOCL_WIDE_NB(p) - px,
                       dy = MSOCL_WIDE_NB(p + plane) - py,
                       dz = MSOCL_WIDE_NB(p + 2 * plane) - pz;
    const msocl_rows_f stretch =
        MSOCL_SQRT(dx * dx + dy * dy + dz * dz) - rest;
    es += MSOCL_ROWS_SEL(there, 0.25f * kk * stretch * stretch, 0.0f);
    (void)cc;
  }
#ifdef MSOCL_SPILL
  float t[MSOCL_ROWS_W];
  *(msocl_rows_any *)t = es;
  for (int u = 0; u < MSOCL_ROWS_W && x0 + u < MSOCL_PLANES_NX; u++) {
    const int x = x0 + u;
    for (int o = spill[x]; o < spill[x + 1]; o++) {
      int b;
      float rest, kk, cc;
      msocl_planes_spill_slot(MSOCL_CONN_ARGS, o, slab, &b, &rest, &kk, &cc);
      const float *q = (const float *)&px;
      const float *qy = (const float *)&py, *qz = (const float *)&pz;
      const float dx = p[b] - q[u], dy = p[plane + b] - qy[u],
                  dz = p[2 * plane + b] - qz[u];
      const float stretch = MSOCL_SQRT(dx * dx + dy * dy + dz * dz) - rest;
      t[u] += 0.25f * kk * stretch * stretch;
      (void)cc;
    }
  }
  es = MSOCL_ROWS_LOAD(t);
#endif
  const msocl_rows_f ek = 0.5f * m * (vx * vx + vy * vy + vz * vz),
                     eg = -m * (gravity.x * px + gravity.y * py +
                                gravity.z * pz);
  msocl_wide_store(ek, parts, x0, MSOCL_PLANES_NX);
  msocl_wide_store(es, parts + stride, x0, MSOCL_PLANES_NX);
  msocl_wide_store(eg, parts + 2 * stride, x0, MSOCL_PLANES_NX);
  (void)row;
}
#endif

/* The points' parts summed in runs of 64 (in the model's order, whatever
 * the layout pads), run g from point first + 64 g, one after another into
 * partial (four floats a run: kinetic, spring, gravity, 0): a work-item a
 * run, no barrier. */
__kernel void msocl_energy(__global const float *parts,
                           __global float *partial, int stride, int first,
                           int end, int runs)
{
  const int g = get_global_id(0);
  if (g >= runs)
    return;
  float e[3] = {0.0f, 0.0f, 0.0f};
  /* end: the last point of this device's range, + 1 */
  for (int j = 0; j < MSOCL_ENERGY_GROUP; j++) {
    const int i = first + MSOCL_ENERGY_GROUP * g + j;
    for (int c = 0; c < 3; c++)
      e[c] += i < end ? parts[c * stride + i] : 0.0f;
  }
  for (int c = 0; c < 3; c++)
    partial[4 * g + c] = e[c];
  partial[4 * g + 3] = 0.0f;
}

#endif

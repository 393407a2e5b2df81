/* Energy of the state, summed on the device: each work-group of 64 points
 * writes one partial (kinetic, spring, gravitational, 0); the host adds the
 * partials in double (group 0 starts at the launch's global offset). A
 * spring's energy k (l - r)^2 / 2 is split between
 * its two ends, as each end's gather sees it. */

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

/* The EDGES layout - the second seed's way: one work-item per spring
 * computes its force and adds it to both end points' force accumulators
 * with atomics; a per-point pass then integrates (symplectic Euler, like
 * msocl_velocity) and clears the accumulator for the next step. Summation
 * order depends on scheduling, so results agree with the gather layouts
 * within rounding, not bitwise. Needs common.cl and step.cl before it (the
 * library builds it with the BUFFER macros and no slots). */

/* Float add by compare-and-swap on the 32-bit word: OpenCL 1.2 has no
 * float atomics. */
static void msocl_atomic_add(volatile __global float *at, float v)
{
  union {
    unsigned int u;
    float f;
  } old, sum;
  do {
    old.f = *at;
    sum.f = old.f + v;
  } while (atomic_cmpxchg((volatile __global unsigned int *)at, old.u,
                          sum.u) != old.u);
}

__kernel void msocl_edges_force(__global const int2 *ij,
                                __global const float2 *rk,
                                __global const float *dmp,
                                __global const float4 *pos,
                                __global const float4 *vel,
                                __global float *force, int ns)
{
  int s = get_global_id(0);
  if (s >= ns)
    return;
  int2 e = ij[s];
  float2 c = rk[s];
  float3 p = pos[e.x].xyz, q = pos[e.y].xyz;
  float3 f = msocl_spring(p, q, c.x, c.y); /* on e.x; -f on e.y */
#ifdef MSOCL_DAMPING
  f += msocl_dashpot(p, q, vel[e.x].xyz, vel[e.y].xyz, dmp[s]);
#endif
  (void)vel; (void)dmp;
  for (int a = 0; a < 3; a++) {
    float fa = a == 0 ? f.x : a == 1 ? f.y : f.z;
    msocl_atomic_add(force + 4 * e.x + a, fa);
    msocl_atomic_add(force + 4 * e.y + a, -fa);
  }
}

__kernel void msocl_edges_velocity(__global const float4 *pos,
                                   __global const float4 *vel,
                                   __global float4 *vel_out,
                                   __global float4 *force,
                                   __global const float *inv_mass,
                                   float4 gravity, float viscous, float air,
                                   float dt, __constant float4 *col,
                                   int ncol, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float3 f = force[i].xyz;
  force[i] = (float4)(0.0f); /* cleared for the next step's springs */
  float4 p4 = pos[i];
  if (MSOCL_PINNED(p4)) {
    vel_out[i] = (float4)(0.0f);
    return;
  }
  float3 v = vel[i].xyz;
#ifdef MSOCL_VISCOUS
  f -= viscous * v;
#endif
  (void)viscous;
  v = msocl_kick(p4.xyz, v, f, inv_mass[i], gravity, air, dt, col, ncol);
  vel_out[i] = (float4)(v, 0.0f);
}

/* Spring energy k (l - r)^2 / 2 per spring, summed per work-group of 64
 * into partial[group].y (the per-point energies come from msocl_energy). */
__kernel __attribute__((reqd_work_group_size(64, 1, 1)))
void msocl_edges_energy(__global const int2 *ij, __global const float2 *rk,
                        __global const float4 *pos,
                        __global float4 *partial, int ns)
{
  __local float part[64];
  int s = get_global_id(0), l = get_local_id(0);
  float e = 0.0f;
  if (s < ns) {
    int2 q = ij[s];
    float3 d = pos[q.y].xyz - pos[q.x].xyz;
    float stretch = MSOCL_SQRT(dot(d, d)) - rk[s].x;
    e = 0.5f * rk[s].y * stretch * stretch;
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

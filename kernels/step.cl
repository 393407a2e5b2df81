/* The paper's two passes of one symplectic Euler step (eq. 3): the velocity
 * pass gathers each point's springs, adds external forces, integrates
 * velocity and answers collisions; the position pass moves the points.
 * Needs common.cl before it. */

/* Symplectic Euler's new velocity of a free point from its force f
 * (springs and viscous damping): gravity, air resistance, collisions. */
static float3 msocl_kick(float3 p, float3 v, float3 f, float inv_m,
                         float4 gravity, float air, float dt,
                         __constant float4 *col, int ncol)
{
  v = v + dt * (f * inv_m + gravity.xyz);
#ifdef MSOCL_AIR
  v = air * v;
#endif
  (void)air;
  return msocl_collide(p, v, dt, col, ncol, 1.0f);
}

__kernel void msocl_velocity(MSOCL_CONN, __global const float4 *pos,
                             __global const float4 *vel,
                             __global float4 *vel_out,
                             __global const float *inv_mass, float4 gravity,
                             float viscous, float air, float dt,
                             __constant float4 *col, int ncol, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 p4 = pos[i];
  if (MSOCL_PINNED(p4)) {
    vel_out[i] = (float4)(0.0f);
    return;
  }
  float3 f = msocl_force(MSOCL_CONN_ARGS, pos, vel, i, n, viscous);
  float3 v = msocl_kick(p4.xyz, vel[i].xyz, f, inv_mass[i], gravity, air, dt,
                        col, ncol);
  vel_out[i] = (float4)(v, 0.0f);
}

__kernel void msocl_position(__global const float4 *pos,
                             __global const float4 *vel,
                             __global float4 *pos_out, float dt, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 p = pos[i];
  if (MSOCL_PINNED(p)) {
    pos_out[i] = p;
    return;
  }
  pos_out[i] = (float4)(p.xyz + dt * vel[i].xyz, p.w);
}

/* Both passes in one kernel (tuning.fused): the velocity pass, then the
 * point moves by the new velocity at once. Other points read only the old
 * positions (pos, not pos_out), so this is exactly the two passes' result -
 * with one launch and one read of the state instead of two. */
__kernel void msocl_fused(MSOCL_CONN, __global const float4 *pos,
                          __global const float4 *vel,
                          __global float4 *pos_out, __global float4 *vel_out,
                          __global const float *inv_mass, float4 gravity,
                          float viscous, float air, float dt,
                          __constant float4 *col, int ncol, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 p4 = pos[i];
  if (MSOCL_PINNED(p4)) {
    vel_out[i] = (float4)(0.0f);
    pos_out[i] = p4;
    return;
  }
  float3 f = msocl_force(MSOCL_CONN_ARGS, pos, vel, i, n, viscous);
  float3 v = msocl_kick(p4.xyz, vel[i].xyz, f, inv_mass[i], gravity, air, dt,
                        col, ncol);
  vel_out[i] = (float4)(v, 0.0f);
  pos_out[i] = (float4)(p4.xyz + dt * v, p4.w);
}

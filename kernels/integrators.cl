/* The other explicit integrators, on the same force gather (common.cl):
 * explicit Euler, velocity Verlet (kick-drift-kick) and classic RK4.
 * Pinned points keep their position and zero velocity throughout. */

/* Acceleration of point i at (pos, vel): forces / m + gravity. */
static float3 msocl_accel_at(MSOCL_CONN, __global const float4 *pos,
                             __global const float4 *vel,
                             __global const float *inv_mass, float4 gravity,
                             float viscous, int i, int n)
{
  float3 f = msocl_force(MSOCL_CONN_ARGS, pos, vel, i, n, viscous);
  return f * inv_mass[i] + gravity.xyz;
}

/* Forward Euler in one pass: p' = p + dt v, v' = v + dt a(p, v). */
__kernel void msocl_euler(MSOCL_CONN, __global const float4 *pos,
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
    pos_out[i] = p4;
    vel_out[i] = (float4)(0.0f);
    return;
  }
  float3 a = msocl_accel_at(MSOCL_CONN_ARGS, pos, vel, inv_mass, gravity,
                            viscous, i, n);
  float3 v0 = vel[i].xyz;
  float3 p = p4.xyz + dt * v0;
  float3 v = v0 + dt * a;
#ifdef MSOCL_AIR
  v = air * v;
#endif
  (void)air;
  msocl_project(&p, &v, col, ncol);
  pos_out[i] = (float4)(p, p4.w);
  vel_out[i] = (float4)(v, 0.0f);
}

/* The acceleration at the current state, for Verlet's first kick. */
__kernel void msocl_accel(MSOCL_CONN, __global const float4 *pos,
                          __global const float4 *vel,
                          __global float4 *acc_out,
                          __global const float *inv_mass, float4 gravity,
                          float viscous, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float3 a = MSOCL_PINNED(pos[i])
                 ? (float3)(0.0f)
                 : msocl_accel_at(MSOCL_CONN_ARGS, pos, vel, inv_mass,
                                  gravity, viscous, i, n);
  acc_out[i] = (float4)(a, 0.0f);
}

/* Verlet, first half: v+ = v + dt/2 a, with the collision response on v+
 * (it is the velocity the drift uses), then p' = p + dt v+. v+ replaces v
 * in place: no other point reads it here. */
__kernel void msocl_verlet_drift(__global const float4 *pos,
                                 __global float4 *vel,
                                 __global const float4 *acc,
                                 __global float4 *pos_out, float dt,
                                 __constant float4 *col, int ncol, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 p4 = pos[i];
  if (MSOCL_PINNED(p4)) {
    pos_out[i] = p4;
    vel[i] = (float4)(0.0f);
    return;
  }
  float3 v = vel[i].xyz + (0.5f * dt) * acc[i].xyz;
  v = msocl_collide(p4.xyz, v, dt, col, ncol, 1.0f);
  pos_out[i] = (float4)(p4.xyz + dt * v, p4.w);
  vel[i] = (float4)(v, 0.0f);
}

/* Verlet, second half: a' = a(p', v+), v' = v+ + dt/2 a'; a' is kept for
 * the next step's first kick. */
__kernel void msocl_verlet_kick(MSOCL_CONN, __global const float4 *pos,
                                __global const float4 *vel,
                                __global float4 *vel_out,
                                __global float4 *acc_out,
                                __global const float *inv_mass,
                                float4 gravity, float viscous, float air,
                                float dt, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  if (MSOCL_PINNED(pos[i])) {
    vel_out[i] = (float4)(0.0f);
    acc_out[i] = (float4)(0.0f);
    return;
  }
  float3 a = msocl_accel_at(MSOCL_CONN_ARGS, pos, vel, inv_mass, gravity,
                            viscous, i, n);
  float3 v = vel[i].xyz + (0.5f * dt) * a;
#ifdef MSOCL_AIR
  v = air * v;
#endif
  (void)air;
  vel_out[i] = (float4)(v, 0.0f);
  acc_out[i] = (float4)(a, 0.0f);
}

/* One RK4 stage. The stage state (sp, sv) gives the derivative
 * k = (sv, a(sp, sv)); mode 0 starts the sum with k, mode 1 adds 2k, and
 * both write the next stage state y0 + c dt k to (np, nv); mode 2 ends the
 * step: y' = y0 + dt/6 (sum + k) into (np, nv). */
__kernel void msocl_rk4_stage(MSOCL_CONN, __global const float4 *p0,
                              __global const float4 *v0,
                              __global const float4 *sp,
                              __global const float4 *sv,
                              __global float4 *sum_p, __global float4 *sum_v,
                              __global float4 *np, __global float4 *nv,
                              __global const float *inv_mass, float4 gravity,
                              float viscous, float air, float c, float dt,
                              int mode, __constant float4 *col, int ncol,
                              int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 y0 = p0[i];
  if (MSOCL_PINNED(y0)) {
    np[i] = y0;
    nv[i] = (float4)(0.0f);
    return;
  }
  float3 kp = sv[i].xyz;
  float3 kv = msocl_accel_at(MSOCL_CONN_ARGS, sp, sv, inv_mass, gravity,
                             viscous, i, n);
  if (mode == 2) {
    float3 p = y0.xyz + (dt / 6.0f) * (sum_p[i].xyz + kp);
    float3 v = v0[i].xyz + (dt / 6.0f) * (sum_v[i].xyz + kv);
#ifdef MSOCL_AIR
    v = air * v;
#endif
    msocl_project(&p, &v, col, ncol);
    np[i] = (float4)(p, y0.w);
    nv[i] = (float4)(v, 0.0f);
    return;
  }
  if (mode == 0) {
    sum_p[i] = (float4)(kp, 0.0f);
    sum_v[i] = (float4)(kv, 0.0f);
  } else {
    sum_p[i] = (float4)(sum_p[i].xyz + 2.0f * kp, 0.0f);
    sum_v[i] = (float4)(sum_v[i].xyz + 2.0f * kv, 0.0f);
  }
  (void)air;
  np[i] = (float4)(y0.xyz + (c * dt) * kp, y0.w);
  nv[i] = (float4)(v0[i].xyz + (c * dt) * kv, 0.0f);
}

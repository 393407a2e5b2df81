/* Backward Euler in the Baraff-Witkin form (Large steps in cloth
 * simulation, 1998): one linearised step
 *   (M - dt D - dt^2 K) dv = dt (f(p, v) + dt K v),  v' = v + dv,
 *   p' = p + dt v'
 * solved by conjugate gradients without forming the matrix: each product
 * is a gather over the point's springs with the spring Jacobian
 *   J = k (u u^T + max(0, 1 - r/l) (I - u u^T))
 * (the clamp keeps J positive semi-definite for compressed springs, so the
 * system stays symmetric positive definite), D from the dashpots (c u u^T)
 * and viscous damping. Pinned points have dv = 0: identity rows, zero
 * right-hand side. Dot products: work-group reduction into partials that
 * the host adds in double. Needs common.cl before it. */

#define MSOCL_CG_GROUP 64

/* J (x_j - x_i) for a spring from p to q, and c u u^T (y_j - y_i). */
static float3 msocl_jacobian(float3 p, float3 q, float rest, float k,
                             float3 dx)
{
  float3 d = q - p;
  float len = MSOCL_SQRT(dot(d, d));
  if (!(len > 0.0f))
    return (float3)(0.0f);
  float3 u = d / len;
  float t = fmax(0.0f, 1.0f - MSOCL_DIV(rest, len));
  float3 along = dot(u, dx) * u;
  return k * (along + t * (dx - along));
}

#ifdef MSOCL_DAMPING
static float3 msocl_damp_jacobian(float3 p, float3 q, float c, float3 dx)
{
  float3 d = q - p;
  float len2 = dot(d, d);
  if (!(len2 > 0.0f))
    return (float3)(0.0f);
  return (c * MSOCL_DIV(dot(d, dx), len2)) * d;
}
#endif

/* Sums v over the work-group into partial[group].x. */
static void msocl_group_sum(float v, __local float *part,
                            __global float4 *partial)
{
  int l = get_local_id(0);
  part[l] = v;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int w = MSOCL_CG_GROUP / 2; w > 0; w >>= 1) {
    if (l < w)
      part[l] += part[l + w];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0)
    partial[get_group_id(0)] = (float4)(part[0], 0.0f, 0.0f, 0.0f);
}

/* b = dt (f + dt K v); x = 0, r = p = b; partial: r.r */
__kernel __attribute__((reqd_work_group_size(MSOCL_CG_GROUP, 1, 1)))
void msocl_ie_rhs(MSOCL_CONN, __global const float4 *pos,
                  __global const float4 *vel, __global float4 *x,
                  __global float4 *r, __global float4 *p,
                  __global const float *inv_mass, float4 gravity,
                  float viscous, float dt, __global float4 *partial, int n)
{
  __local float part[MSOCL_CG_GROUP];
  int i = get_global_id(0);
  float3 b = (float3)(0.0f);
  bool live = i < n;
  if (live)
    live = !MSOCL_PINNED(pos[i]);
  if (live) {
    float3 pi = pos[i].xyz, vi = vel[i].xyz, kv = (float3)(0.0f);
    float m = 1.0f / inv_mass[i];
    float3 f = msocl_force(MSOCL_CONN_ARGS, pos, vel, i, n, viscous);
    for (int s = 0; s < MSOCL_MAX_SLOTS; s++) {
      int j;
      float rest, k, c;
      if (!msocl_slot(MSOCL_CONN_ARGS, i, s, n, &j, &rest, &k, &c))
        break;
      kv += msocl_jacobian(pi, pos[j].xyz, rest, k, vel[j].xyz - vi);
    }
    b = dt * (f + m * gravity.xyz + dt * kv);
  }
  if (i < n) {
    x[i] = (float4)(0.0f);
    r[i] = (float4)(b, 0.0f);
    p[i] = (float4)(b, 0.0f);
  }
  msocl_group_sum(dot(b, b), part, partial);
}

/* ap = A p; partial: p.Ap */
__kernel __attribute__((reqd_work_group_size(MSOCL_CG_GROUP, 1, 1)))
void msocl_ie_apply(MSOCL_CONN, __global const float4 *pos,
                    __global const float4 *p, __global float4 *ap,
                    __global const float *inv_mass, float viscous, float dt,
                    __global float4 *partial, int n)
{
  __local float part[MSOCL_CG_GROUP];
  int i = get_global_id(0);
  float3 y = (float3)(0.0f), pi = (float3)(0.0f);
  if (i < n) {
    pi = p[i].xyz;
    if (MSOCL_PINNED(pos[i])) {
      y = pi;
    } else {
      float3 xi = pos[i].xyz, kx = (float3)(0.0f), dx = (float3)(0.0f);
      for (int s = 0; s < MSOCL_MAX_SLOTS; s++) {
        int j;
        float rest, k, c;
        if (!msocl_slot(MSOCL_CONN_ARGS, i, s, n, &j, &rest, &k, &c))
          break;
        float3 q = pos[j].xyz, dp = p[j].xyz - pi;
        kx += msocl_jacobian(xi, q, rest, k, dp);
#ifdef MSOCL_DAMPING
        dx += msocl_damp_jacobian(xi, q, c, dp);
#endif
      }
      float m = 1.0f / inv_mass[i];
#ifdef MSOCL_VISCOUS
      y = (m + dt * viscous) * pi - dt * dx - (dt * dt) * kx;
#else
      y = m * pi - dt * dx - (dt * dt) * kx;
#endif
      (void)viscous;
    }
    ap[i] = (float4)(y, 0.0f);
  }
  msocl_group_sum(dot(pi, y), part, partial);
}

/* x += alpha p; r -= alpha ap; partial: r.r */
__kernel __attribute__((reqd_work_group_size(MSOCL_CG_GROUP, 1, 1)))
void msocl_cg_step(__global float4 *x, __global float4 *r,
                   __global const float4 *p, __global const float4 *ap,
                   float alpha, __global float4 *partial, int n)
{
  __local float part[MSOCL_CG_GROUP];
  int i = get_global_id(0);
  float rr = 0.0f;
  if (i < n) {
    x[i] = (float4)(x[i].xyz + alpha * p[i].xyz, 0.0f);
    float3 ri = r[i].xyz - alpha * ap[i].xyz;
    r[i] = (float4)(ri, 0.0f);
    rr = dot(ri, ri);
  }
  msocl_group_sum(rr, part, partial);
}

/* p = r + beta p */
__kernel void msocl_cg_direction(__global float4 *p, __global const float4 *r,
                                 float beta, int n)
{
  int i = get_global_id(0);
  if (i < n)
    p[i] = (float4)(r[i].xyz + beta * p[i].xyz, 0.0f);
}

/* v' = v + dv (times air), then the collision response on v' - the
 * velocity the position pass (msocl_position) moves the point by. */
__kernel void msocl_ie_finish(__global const float4 *pos,
                              __global const float4 *vel,
                              __global const float4 *dv,
                              __global float4 *vel_out, float air, float dt,
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
  float3 v = vel[i].xyz + dv[i].xyz;
#ifdef MSOCL_AIR
  v = air * v;
#endif
  (void)air;
  v = msocl_collide(p4.xyz, v, dt, col, ncol, 1.0f);
  vel_out[i] = (float4)(v, 0.0f);
}

/* The two passes of one symplectic Euler step (Vassilev & Rousev, eq. 3):
 * the velocity pass gathers each point's springs, adds external forces,
 * integrates velocity and answers collisions; the position pass moves the
 * points. The host builds this file with -D options naming only what the
 * model uses:
 *   MSOCL_LAYOUT_IMAGE2D | MSOCL_LAYOUT_BUFFER   where the springs live
 *   MSOCL_SLOTS=n          slots per point (BUFFER)
 *   MSOCL_DAMPING          per-spring dashpots (a slot table of coefficients)
 *   MSOCL_VISCOUS          viscous damping -c v
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

/* Force on point p from a spring to q of rest length r and stiffness k
 * (Hooke, eq. 2 of the paper with the sign that pulls a stretched spring
 * together). A zero-length spring exerts nothing rather than NaN. */
static float3 msocl_spring(float3 p, float3 q, float rest, float k)
{
  float3 d = q - p;
  float len = MSOCL_SQRT(dot(d, d));
  if (len > 0.0f)
    return (k * MSOCL_DIV(len - rest, len)) * d;
  return (float3)(0.0f);
}

#ifdef MSOCL_DAMPING
/* Dashpot along the spring: c times the closing speed, along the spring. */
static float3 msocl_dashpot(float3 p, float3 q, float3 vp, float3 vq, float c)
{
  float3 d = q - p;
  float len2 = dot(d, d);
  if (len2 > 0.0f)
    return (c * MSOCL_DIV(dot(vq - vp, d), len2)) * d;
  return (float3)(0.0f);
}
#endif

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

static float3 msocl_collide(float3 p, float3 v, float dt,
                            __constant float4 *col, int ncol)
{
  for (int c = 0; c < ncol; c++) {
    float4 head = col[2 * c];     /* kind, friction */
    float4 prm = col[2 * c + 1];  /* shape parameters */
    int kind = (int)head.x;
    float g;
    float3 n;
#ifdef MSOCL_PLANE
    if (kind == MSOCL_PLANE_KIND) {
      n = prm.xyz;
      g = dot(n, p) - prm.w;
      v = msocl_respond(v, g, n, head.y, dt);
    }
#endif
#ifdef MSOCL_SPHERE
    if (kind == MSOCL_SPHERE_KIND) {
      float3 d = p - prm.xyz;
      float len = MSOCL_SQRT(dot(d, d));
      n = len > 0.0f ? d / len : (float3)(0.0f, 1.0f, 0.0f);
      g = len - prm.w;
      v = msocl_respond(v, g, n, head.y, dt);
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
        g = gtop;
        n = (float3)(0.0f, 1.0f, 0.0f);
      } else {
        g = gside;
        n = (float3)(dx / rr, 0.0f, dz / rr);
      }
      v = msocl_respond(v, g, n, head.y, dt);
    }
#endif
    (void)kind; (void)g; (void)n; (void)prm; (void)head;
  }
  return v;
}

#ifdef MSOCL_LAYOUT_IMAGE2D
#define MSOCL_CONNECTIVITY                                                    \
  __read_only image2d_t con, int tex_w, int tex_h, __read_only image2d_t dmp
#else
#define MSOCL_CONNECTIVITY                                                    \
  __global const int *nbr, __global const float2 *rk, __global const float *dmp
#endif

__kernel void msocl_velocity(MSOCL_CONNECTIVITY,
                             __global const float4 *pos,
                             __global const float4 *vel,
                             __global float4 *vel_out,
                             __global const float *inv_mass,
                             float4 gravity, float viscous, float dt,
                             __constant float4 *col, int ncol, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 p4 = pos[i];
#ifdef MSOCL_PINS
  if (p4.w != 0.0f) {
    vel_out[i] = (float4)(0.0f);
    return;
  }
#endif
  float3 p = p4.xyz;
  float3 v = vel[i].xyz;
  float3 f = (float3)(0.0f);

#ifdef MSOCL_LAYOUT_IMAGE2D
  const sampler_t smp =
      CLK_NORMALIZED_COORDS_FALSE | CLK_ADDRESS_NONE | CLK_FILTER_NEAREST;
  int x = i % tex_w, y = i / tex_w;
  for (int s = 0; s < 16; s++) {
    int2 at = (int2)(x + (s & 3) * tex_w, y + (s >> 2) * tex_h);
    float4 e = read_imagef(con, smp, at);  /* other end x, y; rest; k */
    if (e.x < 0.0f)
      break;
    int j = (int)e.y * tex_w + (int)e.x;
    float3 q = pos[j].xyz;
    f += msocl_spring(p, q, e.z, e.w);
#ifdef MSOCL_DAMPING
    /* dashpots: a (4W) x H image, four slots a texel */
    float4 c4 = read_imagef(dmp, smp, (int2)(x + (s >> 2) * tex_w, y));
    float c = (s & 3) == 0 ? c4.x : (s & 3) == 1 ? c4.y : (s & 3) == 2 ? c4.z : c4.w;
    f += msocl_dashpot(p, q, v, vel[j].xyz, c);
#endif
  }
#else
  for (int s = 0; s < MSOCL_SLOTS; s++) {
    int j = nbr[s * n + i];
    if (j < 0)
      break;
    float2 e = rk[s * n + i];  /* rest, k */
    float3 q = pos[j].xyz;
    f += msocl_spring(p, q, e.x, e.y);
#ifdef MSOCL_DAMPING
    f += msocl_dashpot(p, q, v, vel[j].xyz, dmp[s * n + i]);
#endif
  }
#endif

#ifdef MSOCL_VISCOUS
  f -= viscous * v;
#endif
  v = v + dt * (f * inv_mass[i] + gravity.xyz);
  v = msocl_collide(p, v, dt, col, ncol);
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
#ifdef MSOCL_PINS
  if (p.w != 0.0f) {
    pos_out[i] = p;
    return;
  }
#endif
  pos_out[i] = (float4)(p.xyz + dt * vel[i].xyz, p.w);
}

/* The steps: symplectic Euler's two passes (or fused), explicit Euler,
 * velocity Verlet's and RK4's stages, both strain limits' sweeps and the
 * collision response, on every layout, over state held as separate x, y,
 * z planes of floats - a grid's or lattice's rows padded by two points on
 * every side, other models' points in index order. Needs common.cl
 * before it.
 *
 * Why: PoCL's CPU device vectorises across work-items only when a kernel's
 * per-work-item code is all scalar (its loop vectorizer takes no vector-
 * typed instruction), and it builds the work-item loop after -O3 has
 * already paired the x and y of a float4 into <2 x float>. In planes every
 * value is a scalar, the planes sit a run-time `plane` apart (so nothing
 * pairs them), and a neighbour at (dx, dy) is at a fixed offset from the
 * point - within the padding at the grid's edge - so eight or sixteen
 * work-items read it with one vector load, not a gather.
 *
 * Every layout sums a point's springs slot by slot in the same order, so
 * that layouts and device splits agree bitwise (tests/check_planes.c,
 * check_multidevice.c). The state stays in the planes between calls
 * (lib/engine/planes.c): msocl_planes_pack copies it in after the engine's
 * float4 buffers were written, msocl_planes_unpack back before they are
 * read.
 *
 * Point (x, y) sits at (y + 2) * pitch + x + 2 of each plane; p holds the
 * x, y, z planes `plane` floats apart (v likewise); aux holds the inverse
 * masses, then pos.w (pinned); col the colliders, a float4 a value
 * (MSOCL_PLANES_COL). MSOCL_NCOL: the model's colliders, known
 * when the program is built so that their loop unrolls (a loop of run-time
 * length inside would stop the vectorizer); MSOCL_GRID_KINDS: a bit for
 * each kind of spring the model has. */
#if defined(MSOCL_PLANES)

/* The work-item's point (x, y, z) and where it sits in a plane (GRID): a
 * lattice's layers are `slab` floats apart, each padded by two rows, and
 * two padding layers lie at each end; a cloth has one layer (z 0).
 * BUFFER and IMAGE2D: point x of one unpadded row (y and z 0), `pitch`
 * its n points; the row is padded to whole work-groups (BUFFER: `slab`
 * the planes' length, the stride of their copy of the slot table). MSOCL_PLANES_NX:
 * the row's points in a gathering kernel, past which a work-item is
 * padding and stores nothing. */
#define MSOCL_PLANES_XYZ                                                      \
  const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2); \
  (void)y; (void)z /* a cloth's address leaves z out, BUFFER's both */
#if defined(MSOCL_LAYOUT_GRID) && defined(MSOCL_GRID_3D)
#define MSOCL_PLANES_AT(x, y, z) (((z) + 2) * slab + ((y) + 2) * pitch + (x) + 2)
#elif defined(MSOCL_LAYOUT_GRID)
#define MSOCL_PLANES_AT(x, y, z) (((y) + 2) * pitch + (x) + 2)
#else
#define MSOCL_PLANES_AT(x, y, z) (x)
#endif
#ifdef MSOCL_LAYOUT_GRID
#define MSOCL_PLANES_NX grid_nx
#else
#define MSOCL_PLANES_NX pitch
#endif

/* For the helpers a gather calls once a slot (and again for the spill):
 * a call left in the kernel, or -O3's pairing of two values inside it
 * into a <2 x float>, would stop PoCL vectorising the kernel. */
#define MSOCL_PLANES_INLINE inline __attribute__((always_inline))

/* dot(a, b) of float3 as the other kernels compute it: (x + y) + z. */
#define MSOCL_DOT3(ax, ay, az, bx, by, bz) ((ax) * (bx) + (ay) * (by) + (az) * (bz))

/* Whether aux's pinned value w marks a pinned point */
#ifdef MSOCL_PINS
#define MSOCL_PLANES_PINNED(w) ((w) != 0.0f)
#else
#define MSOCL_PLANES_PINNED(w) false
#endif

/* Value k of collider c (0: kind, 1: friction, 2: 1 while it moves,
 * 4-7: its parameters (msocl_planes_gap), 8-15: a capsule's or box's
 * msocl__collider.x, 16-18: its pose's velocity, 19-21: its angular
 * velocity, 22-24: its pose position) in the planes' collider table
 * (lib/engine/planes.c, lib/sim/sim_colliders.c), where each value has a
 * float4 to itself: adjacent ones would be loaded as a pair into a
 * <2 x float>, which stops PoCL vectorising the kernel. */
#define MSOCL_PLANES_COL(cf, c, k) ((cf)[4 * (32 * (c) + (k))])

/* The surface velocity of moving collider c at p: u = v + w x (p - c),
 * declared as ux, uy, uz of type T (cv(k) reads value k). Each component
 * in its own shape: three alike would be paired by -O3's SLP vectorizer
 * and PoCL would leave the kernel scalar. */
#define MSOCL_PLANES_SURFACE(T, cv, px, py, pz)                               \
  const T rx_ = (px) - cv(22), ry_ = (py) - cv(23), rz_ = (pz) - cv(24);      \
  const T ux = cv(16) + (cv(20) * rz_ - cv(21) * ry_);                        \
  const T uy = fma((T)cv(21), rx_, -(cv(19) * rz_)) + cv(17);                 \
  const T uz = cv(18) - (cv(20) * rx_ - cv(19) * ry_)

/* Collider c's gap g at the point (>= 0 outside; convex), and its unit
 * gradient in *nx.. */
static MSOCL_PLANES_INLINE float msocl_planes_gap(float px, float py, float pz,
                              __constant const float *col, int c, float *nx,
                              float *ny, float *nz)
{
#define cf(k) MSOCL_PLANES_COL(col, c, k)
  const int kind = (int)cf(0);
  float g = INFINITY;
  *nx = 0.0f;
  *ny = 1.0f;
  *nz = 0.0f;
#ifdef MSOCL_PLANE
  if (kind == MSOCL_PLANE_KIND) {
    *nx = cf(4);
    *ny = cf(5);
    *nz = cf(6);
    g = MSOCL_DOT3(cf(4), cf(5), cf(6), px, py, pz) - cf(7);
  }
#endif
#ifdef MSOCL_SPHERE
  if (kind == MSOCL_SPHERE_KIND) {
    float dx = px - cf(4), dy = py - cf(5), dz = pz - cf(6);
    float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
    bool out = len > 0.0f;
    *nx = out ? dx / len : 0.0f;
    *ny = out ? dy / len : 1.0f;
    *nz = out ? dz / len : 0.0f;
    g = len - cf(7);
  }
#endif
#ifdef MSOCL_TABLE
  if (kind == MSOCL_TABLE_KIND) {
    float dx = px - cf(4), dz = pz - cf(6);
    float rr = MSOCL_SQRT(dx * dx + dz * dz);
    float gside = rr - cf(7), gtop = py - cf(5);
    bool top = gtop >= gside || !(rr > 0.0f);
    *nx = top ? 0.0f : dx / rr;
    *ny = top ? 1.0f : 0.0f;
    *nz = top ? 0.0f : dz / rr;
    g = top ? gtop : gside;
  }
#endif
#ifdef MSOCL_CAPSULE
  /* the closest point of segment a-b, then a sphere's gap from it */
  if (kind == MSOCL_CAPSULE_KIND) {
    const float ex = cf(8) - cf(4), ey = cf(9) - cf(5), ez = cf(10) - cf(6);
    const float ax = px - cf(4), ay = py - cf(5), az = pz - cf(6);
    const float ee = MSOCL_DOT3(ex, ey, ez, ex, ey, ez);
    float t = ee > 0.0f ? MSOCL_DIV(MSOCL_DOT3(ax, ay, az, ex, ey, ez), ee)
                        : 0.0f;
    t = fmin(fmax(t, 0.0f), 1.0f);
    const float dx = ax - t * ex, dy = ay - t * ey, dz = az - t * ez;
    const float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
    const bool out = len > 0.0f;
    *nx = out ? dx / len : 0.0f;
    *ny = out ? dy / len : 1.0f;
    *nz = out ? dz / len : 0.0f;
    g = len - cf(7);
  }
#endif
#ifdef MSOCL_BOX
  /* p in the box's frame (q = (x, y, z, w) unit), the signed distance to
   * the box of half extents h there, its gradient rotated back */
  if (kind == MSOCL_BOX_KIND) {
    /* The rotation's matrix R (q = (x, y, z, w) unit); p in the box's
     * frame, l = R^T (p - centre); the signed distance to the box of half
     * extents h there, and its gradient m, rotated back (R m). Each of
     * the three components is written in its own shape: three alike
     * would be paired into a vector by -O3's SLP vectorizer, and PoCL
     * then leaves the whole kernel scalar. */
    const float qx = cf(8), qy = cf(9), qz = cf(10), qw = cf(11);
    const float r00 = 1.0f - 2.0f * (qy * qy + qz * qz),
                r01 = 2.0f * (qx * qy - qz * qw),
                r02 = 2.0f * (qx * qz + qy * qw);
    const float r10 = 2.0f * (qx * qy + qz * qw),
                r11 = 1.0f - 2.0f * (qx * qx + qz * qz),
                r12 = 2.0f * (qy * qz - qx * qw);
    const float r20 = 2.0f * (qx * qz - qy * qw),
                r21 = 2.0f * (qy * qz + qx * qw),
                r22 = 1.0f - 2.0f * (qx * qx + qy * qy);
    const float ex = px - cf(4), ey = py - cf(5), ez = pz - cf(6);
    const float lx = r00 * ex + r10 * ey + r20 * ez;
    const float ly = fma(r01, ex, fma(r11, ey, r21 * ez));
    const float lz = fma(r22, ez, r02 * ex) + r12 * ey;
    const float hx = cf(12), hy = cf(13), hz = cf(14);
    /* |l| - h: fabs, a max and the sign bit cleared */
    const float dx = fabs(lx) - hx, dy = fmax(ly, -ly) - hy,
                dz = as_float(as_uint(lz) & 0x7fffffffu) - hz;
    const float ox = fmax(dx, 0.0f), oy = dy > 0.0f ? dy : 0.0f,
                oz = 0.5f * (dz + fabs(dz));
    const float olen = MSOCL_SQRT(MSOCL_DOT3(ox, oy, oz, ox, oy, oz));
    const bool outside = olen > 0.0f;
    const bool xm = dx >= dy && dx >= dz, ym = !xm && dy >= dz;
    const float sx = lx < 0.0f ? -1.0f : 1.0f, sy = copysign(1.0f, ly),
                sz = 1.0f - 2.0f * (float)(lz < 0.0f);
    const float inv = outside ? 1.0f / olen : 0.0f;
    const float mx = outside ? sx * ox * inv : xm ? sx : 0.0f;
    const float my = outside ? fma(sy * oy, inv, 0.0f) : ym ? sy : 0.0f;
    const float mz = outside ? sz * oz / olen : (!xm && !ym) ? sz : 0.0f;
    g = outside ? olen : xm ? dx : ym ? dy : dz;
    *nx = r00 * mx + r01 * my + r02 * mz;
    *ny = fma(r10, mx, fma(r11, my, r12 * mz));
    *nz = fma(r22, mz, r20 * mx) + r21 * my;
  }
#endif
#undef cf
  (void)kind; /* no collider kind compiled in */
  (void)col; (void)c;
  return g;
}

/* Slot s of the point (x, y, z) at a: where its neighbour sits in the
 * planes (*b), the spring's rest length, stiffness and dashpot, and
 * whether the spring exists; a missing one's terms are masked by every
 * user (they replace the exact zeros its float4 twin adds). GRID: the
 * neighbour a fixed offset away, past the grid's edge (or of a kind with
 * k 0) reading the padding or another row; BUFFER and IMAGE2D: the other
 * end that the table holds (common.cl's msocl_slot4), a free slot the point itself (a padding
 * work-item reads no slot: the table holds n points a slot). */
static MSOCL_PLANES_INLINE bool msocl_planes_neighbor(MSOCL_CONN, int s, int x, int y, int z,
                                  int a, int pitch, int slab, int *b,
                                  float *rest, float *k, float *c)
{
#if defined(MSOCL_LAYOUT_GRID)
  const int qx = x + msocl_grid_dx[s], qy = y + msocl_grid_dy[s];
  *rest = MSOCL_GRID_R(s);
  *k = MSOCL_GRID_K(s);
  *c = MSOCL_GRID_C;
#ifdef MSOCL_GRID_3D
  const int qz = z + msocl_grid_dz[s];
  *b = a + msocl_grid_dz[s] * slab + msocl_grid_dy[s] * pitch +
       msocl_grid_dx[s];
  return qx >= 0 && qx < grid_nx && qy >= 0 && qy < grid_ny && qz >= 0 &&
         qz < grid_nz && *k != 0.0f;
#else
  (void)z;
  (void)slab;
  *b = a + msocl_grid_dy[s] * pitch + msocl_grid_dx[s];
  return qx >= 0 && qx < grid_nx && qy >= 0 && qy < grid_ny && *k != 0.0f;
#endif
#else
  /* point i = x of n = pitch, at a = i in the planes */
  int j = x;
  float r = 0.0f, kk = 0.0f, cc = 0.0f;
  (void)y; (void)z; (void)a; (void)slab;
#if defined(MSOCL_LAYOUT_IMAGE2D)
  if (x < pitch) { /* a padding work-item reads no texel */
    /* the entry, and the dashpot in its group's texel */
    const sampler_t smp =
        CLK_NORMALIZED_COORDS_FALSE | CLK_ADDRESS_NONE | CLK_FILTER_NEAREST;
    const int tx = x % tex_w, ty = x / tex_w;
    const float4 e = read_imagef(con, smp, (int2)(tx + (s & 3) * tex_w,
                                                  ty + (s >> 2) * tex_h));
    const bool on = e.x >= 0.0f;
    j = on ? (int)e.y * tex_w + (int)e.x : x;
    r = on ? e.z : 0.0f;
    kk = on ? e.w : 0.0f;
#ifdef MSOCL_DAMPING
    const float4 c4 = read_imagef(dmp, smp, (int2)(tx + (s >> 2) * tex_w, ty));
    const int q = s & 3;
    cc = q == 0 ? c4.x : q == 1 ? c4.y : q == 2 ? c4.z : c4.w;
#endif
  }
#else
  /* BUFFER's table as planes.c copies it for the planes: slot s of point
   * i at s * slab + i (slab: the plane's length, so a padding work-item
   * reads a free slot), the rests in the first half of rk's floats and
   * the stiffnesses in the second, each read as a vector by eight or
   * sixteen work-items. The test keeps each slot's reads in a block of
   * their own: straight-line, -O3 pairs two slots' differences into a
   * <2 x float>, which stops PoCL vectorising across work-items. */
  {
    const int at = s * slab + x;
    j = nbr[at];
#ifdef MSOCL_CLASSES
    __global const float *v = (__global const float *)dmp + 4 * rk[at];
    r = v[0];
    kk = v[1];
    cc = v[2];
#else
    __global const float *v = (__global const float *)rk;
    r = v[at];
    kk = v[MSOCL_SLOTS * slab + at];
#ifdef MSOCL_DAMPING
    cc = dmp[at];
#endif
#endif
  }
#endif
  *b = j;
  *rest = r;
  *k = kk;
  *c = cc;
  return j != x;
#endif
}

/* Whether slot s is of a kind the model leaves out (GRID, where BUFFER
 * would have no slot for it either): skipped when the program is built. */
#ifdef MSOCL_LAYOUT_GRID
#define MSOCL_PLANES_SKIP(s) (!((MSOCL_GRID_KINDS >> msocl_grid_kind[s]) & 1))
#else
#define MSOCL_PLANES_SKIP(s) false
#endif

/* Slot s of the point (x, y, z) at a, declared as the gathering loops
 * use it: b, rest, kk, cc and there. */
#define MSOCL_PLANES_NEIGHBOR(s)                                              \
  int b;                                                                     \
  float rest, kk, cc;                                                        \
  const bool there = msocl_planes_neighbor(MSOCL_CONN_ARGS, s, x, y, z, a,   \
                                           pitch, slab, &b, &rest, &kk, &cc)

#ifdef MSOCL_SPILL
/* BUFFER's springs past the table, as planes.c copies them after it:
 * entry o's other end and values. */
static MSOCL_PLANES_INLINE void msocl_planes_spill_slot(MSOCL_CONN, int o, int slab, int *b,
                                    float *rest, float *k, float *c)
{
  const int at = MSOCL_SLOTS * slab + o;
  *b = nbr[at];
#ifdef MSOCL_CLASSES
  __global const float *v = (__global const float *)dmp + 4 * rk[at];
  *rest = v[0];
  *k = v[1];
  *c = v[2];
#else
  __global const float *v =
      (__global const float *)rk + 2 * (MSOCL_SLOTS * slab + o);
  *rest = v[0];
  *k = v[1];
#ifdef MSOCL_DAMPING
  *c = dmp[at];
#else
  *c = 0.0f;
#endif
#endif
}

/* A gathering kernel runs twice: over the rows (pass 0), storing nothing
 * for a point with springs past the table, and over just those points
 * (pass 1, the kernel's _spill twin), their springs past the table
 * summed after the table's one at a time, in the order a table long
 * enough for all would sum them. A loop of run-time length in the first would stop PoCL
 * vectorising it; `pass` is a constant in each, so the loop below
 * folds away in the first. */
#define MSOCL_PLANES_SPILLS                                                   \
  for (int o = pass ? spill[x] : 0, o_end = pass ? spill[x + 1] : 0;        \
       o < o_end; o++)
#define MSOCL_PLANES_SPILL_NEIGHBOR(o)                                        \
  int b;                                                                     \
  float rest, kk, cc;                                                        \
  const bool there = true;                                                   \
  msocl_planes_spill_slot(MSOCL_CONN_ARGS, o, slab, &b, &rest, &kk, &cc)
#define MSOCL_PLANES_LIVE                                                     \
  (pass || (x < MSOCL_PLANES_NX && spill[x + 1] == spill[x]))
#define MSOCL_PLANES_SPILL_TWIN(name, params, args)                           \
  __kernel void name##_spill(MSOCL_PLANES_UNPAREN params,                    \
                             __global const int *spilled)                    \
  {                                                                          \
    name##_at(1, spilled[get_global_id(0)], 0, 0, MSOCL_PLANES_UNPAREN args); \
  }
#else
/* whether the work-item's point stores its result */
#define MSOCL_PLANES_LIVE (x < MSOCL_PLANES_NX)
#define MSOCL_PLANES_SPILL_TWIN(name, params, args)
#endif

/* A gathering kernel `name` with parameters `params` (their names:
 * `args`): its body, name##_at, is written once for both passes and
 * follows the macro. */
#define MSOCL_PLANES_UNPAREN(...) __VA_ARGS__
#define MSOCL_PLANES_GATHER(name, params, args)                               \
  static void name##_at(const int pass, const int x, const int y,            \
                        const int z, MSOCL_PLANES_UNPAREN params);           \
  __kernel void name(MSOCL_PLANES_UNPAREN params)                            \
  {                                                                          \
    MSOCL_PLANES_XYZ;                                                        \
    name##_at(0, x, y, z, MSOCL_PLANES_UNPAREN args);                        \
  }                                                                          \
  MSOCL_PLANES_SPILL_TWIN(name, params, args)                                \
  static void name##_at(const int pass, const int x, const int y,            \
                        const int z, MSOCL_PLANES_UNPAREN params)

/* One slot's part of the force on the point whose position and
 * velocity are q[0..5]: the spring's and its dashpot's pull from the
 * neighbour at b, added to f[0..2] where the spring exists. */
static MSOCL_PLANES_INLINE void msocl_planes_pull(__global const float *p,
                              __global const float *v, int plane,
                              const float *q, int b, bool there, float rest,
                              float kk, float cc, float *f)
{
  const float dx = p[b] - q[0], dy = p[plane + b] - q[1],
              dz = p[2 * plane + b] - q[2];
  const float len2 = dx * dx + dy * dy + dz * dz;
  const float len = MSOCL_SQRT(len2);
  const float t = kk * MSOCL_DIV(len - rest, len);
  const bool on = there && len > 0.0f;
  f[0] += on ? t * dx : 0.0f;
  f[1] += on ? t * dy : 0.0f;
  f[2] += on ? t * dz : 0.0f;
#ifdef MSOCL_DAMPING
  const float wx = v[b] - q[3], wy = v[plane + b] - q[4],
              wz = v[2 * plane + b] - q[5];
  const float u = cc * MSOCL_DIV(wx * dx + wy * dy + wz * dz, len2);
  const bool onh = there && len2 > 0.0f;
  f[0] += onh ? u * dx : 0.0f;
  f[1] += onh ? u * dy : 0.0f;
  f[2] += onh ? u * dz : 0.0f;
#endif
  (void)v; (void)cc; /* read by dashpots */
}

/* Internal force at the point at a = (x, y, z): each spring k (len -
 * rest) / len d (Hooke, eq. 2 of the paper; a zero-length spring exerts
 * nothing rather than NaN) and each dashpot c dot(vq - vp, d) / len^2 d,
 * slot by slot, viscous damping included
 * (pass: MSOCL_PLANES_SPILLS). */
static MSOCL_PLANES_INLINE void msocl_planes_force(MSOCL_CONN, const int pass,
                               __global const float *p,
                               __global const float *v, int pitch, int slab,
                               int plane, float viscous, int x, int y, int z,
                               int a, float *fx_out, float *fy_out,
                               float *fz_out)
{
  const float vx = v[a], vy = v[plane + a], vz = v[2 * plane + a];
  const float q[6] = {p[a], p[plane + a], p[2 * plane + a], vx, vy, vz};
  float f[3] = {0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_TABLE_SLOTS; s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    msocl_planes_pull(p, v, plane, q, b, there, rest, kk, cc, f);
  }
#ifdef MSOCL_SPILL
  MSOCL_PLANES_SPILLS {
    MSOCL_PLANES_SPILL_NEIGHBOR(o);
    msocl_planes_pull(p, v, plane, q, b, there, rest, kk, cc, f);
  }
#endif
  (void)pass;
  float fx = f[0], fy = f[1], fz = f[2];
#ifdef MSOCL_VISCOUS
  fx = fx - viscous * vx;
  fy = fy - viscous * vy;
  fz = fz - viscous * vz;
#endif
  (void)viscous;
  (void)vx; (void)vy; (void)vz; /* read by dashpots and viscous damping */
  *fx_out = fx;
  *fy_out = fy;
  *fz_out = fz;
}

/* Collision response by changing velocity (the paper's way): g is convex
 * and >= 0 outside, so raising n.v to at least -g/dt keeps p + dt v
 * outside; friction scales away that fraction of the tangential velocity
 * on contact. Branches as selects. */
static MSOCL_PLANES_INLINE void msocl_planes_collide(float px, float py, float pz, float *vx_io,
                                 float *vy_io, float *vz_io, float dt,
                                 __constant float4 *col, float fscale)
{
  float vx = *vx_io, vy = *vy_io, vz = *vz_io;
  __constant const float *cf = (__constant const float *)col;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++) {
    float nx, ny, nz;
    const float g = msocl_planes_gap(px, py, pz, cf, c, &nx, &ny, &nz);
    /* on the velocity relative to a moving collider's surface (a static
     * one's, selected, is v itself) */
#define cv(k) MSOCL_PLANES_COL(cf, c, k)
    MSOCL_PLANES_SURFACE(float, cv, px, py, pz);
    const bool moving = cv(2) != 0.0f;
#undef cv
    const float ox = moving ? vx - ux : vx, oy = moving ? vy - uy : vy,
                oz = moving ? vz - uz : vz;
    const float fr = fscale * MSOCL_PLANES_COL(cf, c, 1);
    const float vn = MSOCL_DOT3(ox, oy, oz, nx, ny, nz);
    const float lim = MSOCL_DIV(-g, dt);
    float hx = ox + (lim - vn) * nx, hy = oy + (lim - vn) * ny,
          hz = oz + (lim - vn) * nz;
    hx = hx - fr * (hx - lim * nx);
    hy = hy - fr * (hy - lim * ny);
    hz = hz - fr * (hz - lim * nz);
    hx = moving ? hx + ux : hx;
    hy = moving ? hy + uy : hy;
    hz = moving ? hz + uz : hz;
    const bool hit = vn < lim;
    vx = hit ? hx : vx;
    vy = hit ? hy : vy;
    vz = hit ? hz : vz;
  }
  (void)cf;
  *vx_io = vx;
  *vy_io = vy;
  *vz_io = vz;
}

/* Air resistance (MSOCL_AIR): the velocity times `air`. */
static MSOCL_PLANES_INLINE void msocl_planes_air(float air, float *vx, float *vy, float *vz)
{
#ifdef MSOCL_AIR
  *vx = air * *vx;
  *vy = air * *vy;
  *vz = air * *vz;
#endif
  (void)air; (void)vx; (void)vy; (void)vz;
}

/* The velocity pass for the point at a = (x, y, z): its new velocity in
 * *vx.., and whether it is pinned. */
static MSOCL_PLANES_INLINE void msocl_planes_kick(MSOCL_CONN, const int pass,
                              __global const float *p,
                              __global const float *v,
                              __global const float *aux, int pitch, int slab,
                              int plane, float4 gravity, float viscous,
                              float air, float dt, __constant float4 *col,
                              int x, int y, int z, int a, float *vx_out,
                              float *vy_out, float *vz_out, bool *pinned)
{
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, p, v, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a];
  float vx = v[a] + dt * (fx * im + gravity.x);
  float vy = v[plane + a] + dt * (fy * im + gravity.y);
  float vz = v[2 * plane + a] + dt * (fz * im + gravity.z);
  msocl_planes_air(air, &vx, &vy, &vz);
  msocl_planes_collide(p[a], p[plane + a], p[2 * plane + a], &vx, &vy, &vz,
                       dt, col, 1.0f);
  *pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  *vx_out = *pinned ? 0.0f : vx;
  *vy_out = *pinned ? 0.0f : vy;
  *vz_out = *pinned ? 0.0f : vz;
}

/* The planes' ping-pong arguments after the connectivity, then the fixed
 * ones; both kernels below take them in this order. */
#define MSOCL_PLANES_ARGS                                                     \
  __global const float *aux, int pitch, int slab, int plane,                 \
      float4 gravity, float viscous, float air, float dt,                    \
      __constant float4 *col
#define MSOCL_PLANES_ARG_NAMES                                                \
  aux, pitch, slab, plane, gravity, viscous, air, dt, col

/* Both kernels' point (x, y, z), at a, and its new velocity; then the
 * store of that velocity. */
#define MSOCL_PLANES_KICK                                                     \
  const int a = MSOCL_PLANES_AT(x, y, z);                                    \
  float vx, vy, vz;                                                          \
  bool pinned;                                                               \
  msocl_planes_kick(MSOCL_CONN_ARGS, pass, p, v, aux, pitch, slab, plane,    \
                    gravity, viscous, air, dt, col, x, y, z, a, &vx, &vy,    \
                    &vz, &pinned)
#define MSOCL_PLANES_STORE_V                                                  \
  v_out[a] = vx;                                                             \
  v_out[plane + a] = vy;                                                     \
  v_out[2 * plane + a] = vz

MSOCL_PLANES_GATHER(msocl_planes_velocity,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, MSOCL_PLANES_ARG_NAMES))
{
  MSOCL_PLANES_KICK;
  if (MSOCL_PLANES_LIVE) {
    MSOCL_PLANES_STORE_V;
  }
}

/* Both passes in one kernel (tuning.fused): the point
 * moves by its new velocity at once; others read only the old p. */
MSOCL_PLANES_GATHER(msocl_planes_fused,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global float *p_out, MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, p_out,
                     MSOCL_PLANES_ARG_NAMES))
{
  MSOCL_PLANES_KICK;
  if (MSOCL_PLANES_LIVE) {
    __global const float *py_ = p + plane, *pz_ = py_ + plane;
    __global float *qy = p_out + plane, *qz = qy + plane;
    const float cx = p[a], cy = py_[a], cz = pz_[a];
    MSOCL_PLANES_STORE_V;
    p_out[a] = pinned ? cx : cx + dt * vx;
    qy[a] = pinned ? cy : cy + dt * vy;
    qz[a] = pinned ? cz : cz + dt * vz;
  }
}

__kernel void msocl_planes_position(__global const float *p,
                                    __global const float *v,
                                    __global float *p_out,
                                    __global const float *aux, int nx,
                                    int pitch, int slab, int plane, float dt)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (x < nx) {
    /* three statements, not a loop: an inner loop would stop the
     * vectorizer (it takes the innermost loop, over the work-items) */
    __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
    __global const float *py_ = p + plane, *pz_ = py_ + plane;
    __global float *oy = p_out + plane, *oz = oy + plane;
    const float cx = p[a], cy = py_[a], cz = pz_[a];
    p_out[a] = pinned ? cx : cx + dt * v[a];
    oy[a] = pinned ? cy : cy + dt * vy_[a];
    oz[a] = pinned ? cz : cz + dt * vz_[a];
  }
}

/* Velocity Verlet in planes.
 * Drift: v+ = v + dt/2 a with the collision response on it, in place (no
 * other point reads it here), and p' = p + dt v+. */
__kernel void msocl_planes_drift(__global const float *p, __global float *v,
                                 __global const float *acc,
                                 __global float *p_out,
                                 __global const float *aux, int nx,
                                 int pitch, int slab, int plane, float dt,
                                 __constant float4 *col)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  const float h = 0.5f * dt;
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a];
  float vx = v[a] + h * acc[a], vy = v[plane + a] + h * acc[plane + a],
        vz = v[2 * plane + a] + h * acc[2 * plane + a];
  msocl_planes_collide(px, py, pz, &vx, &vy, &vz, dt, col, 1.0f);
  if (x < nx) {
    p_out[a] = pinned ? px : px + dt * vx;
    p_out[plane + a] = pinned ? py : py + dt * vy;
    p_out[2 * plane + a] = pinned ? pz : pz + dt * vz;
    v[a] = pinned ? 0.0f : vx;
    v[plane + a] = pinned ? 0.0f : vy;
    v[2 * plane + a] = pinned ? 0.0f : vz;
  }
}

/* Kick: a' = a(p', v+), v' = v+ + dt/2 a'; a' kept for the next drift. */
MSOCL_PLANES_GATHER(msocl_planes_vkick,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global float *acc_out, MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, acc_out,
                     MSOCL_PLANES_ARG_NAMES))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, p, v, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a], h = 0.5f * dt;
  const float ax = fx * im + gravity.x, ay = fy * im + gravity.y,
              az = fz * im + gravity.z;
  float vx = v[a] + h * ax, vy = v[plane + a] + h * ay,
        vz = v[2 * plane + a] + h * az;
  msocl_planes_air(air, &vx, &vy, &vz);
  (void)col;
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (MSOCL_PLANES_LIVE) {
    v_out[a] = pinned ? 0.0f : vx;
    v_out[plane + a] = pinned ? 0.0f : vy;
    v_out[2 * plane + a] = pinned ? 0.0f : vz;
    acc_out[a] = pinned ? 0.0f : ax;
    acc_out[plane + a] = pinned ? 0.0f : ay;
    acc_out[2 * plane + a] = pinned ? 0.0f : az;
  }
}

/* Projection out of the colliders (explicit methods: a point found inside a
 * collider at the end of the step goes back to its surface and loses its
 * inward speed). A moving collider's table holds its shape at the step's
 * start: its gap at the step's end is the gap at p - dt u, to first order,
 * and the response acts on the velocity relative to its surface. */
static MSOCL_PLANES_INLINE void msocl_planes_project(float *px, float *py, float *pz, float *vx,
                                 float *vy, float *vz, float dt,
                                 __constant float4 *col)
{
  __constant const float *cf = (__constant const float *)col;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++) {
#define cv(k) MSOCL_PLANES_COL(cf, c, k)
    MSOCL_PLANES_SURFACE(float, cv, *px, *py, *pz);
    const bool moving = cv(2) != 0.0f;
#undef cv
    const float ex = moving ? *px - dt * ux : *px,
                ey = moving ? *py - dt * uy : *py,
                ez = moving ? *pz - dt * uz : *pz;
    float nx, ny, nz;
    const float g = msocl_planes_gap(ex, ey, ez, cf, c, &nx, &ny, &nz);
    const bool in = g < 0.0f;
    const float qx = *px - g * nx, qy = *py - g * ny, qz = *pz - g * nz;
    const float ox = moving ? *vx - ux : *vx, oy = moving ? *vy - uy : *vy,
                oz = moving ? *vz - uz : *vz;
    const float vn = MSOCL_DOT3(ox, oy, oz, nx, ny, nz);
    const bool back = in && vn < 0.0f;
    float wx = ox - vn * nx, wy = oy - vn * ny, wz = oz - vn * nz;
    const float fr = MSOCL_PLANES_COL(cf, c, 1);
    wx = wx - fr * wx;
    wy = wy - fr * wy;
    wz = wz - fr * wz;
    wx = moving ? wx + ux : wx;
    wy = moving ? wy + uy : wy;
    wz = moving ? wz + uz : wz;
    *px = in ? qx : *px;
    *py = in ? qy : *py;
    *pz = in ? qz : *pz;
    *vx = back ? wx : *vx;
    *vy = back ? wy : *vy;
    *vz = back ? wz : *vz;
  }
  (void)cf;
}

/* Forward Euler in planes: p' = p + dt v, v' = v + dt
 * a(p, v), times air, projected out of the colliders; pinned points
 * stay. */
MSOCL_PLANES_GATHER(msocl_planes_euler,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global float *p_out, MSOCL_PLANES_ARGS),
                    (MSOCL_CONN_ARGS, p, v, v_out, p_out,
                     MSOCL_PLANES_ARG_NAMES))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, p, v, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a];
  const int ay = plane + a, az = 2 * plane + a;
  float px = p[a] + dt * v[a], py = p[ay] + dt * v[ay],
        pz = p[az] + dt * v[az];
  float vx = v[a] + dt * (fx * im + gravity.x),
        vy = v[ay] + dt * (fy * im + gravity.y),
        vz = v[az] + dt * (fz * im + gravity.z);
  msocl_planes_air(air, &vx, &vy, &vz);
  msocl_planes_project(&px, &py, &pz, &vx, &vy, &vz, dt, col);
  const bool pinned = MSOCL_PLANES_PINNED(aux[ay]);
  if (MSOCL_PLANES_LIVE) {
    p_out[a] = pinned ? p[a] : px;
    p_out[ay] = pinned ? p[ay] : py;
    p_out[az] = pinned ? p[az] : pz;
    v_out[a] = pinned ? 0.0f : vx;
    v_out[ay] = pinned ? 0.0f : vy;
    v_out[az] = pinned ? 0.0f : vz;
  }
}

/* One RK4 stage in planes; mode a constant in each of
 * the three kernels below, so its branches fold away. */
static MSOCL_PLANES_INLINE void msocl_planes_rk4(MSOCL_CONN, const int pass, const int x,
                             const int y, const int z,
                             __global const float *p0,
                             __global const float *v0,
                             __global const float *sp,
                             __global const float *sv, __global float *sum_p,
                             __global float *sum_v, __global float *np,
                             __global float *nv, __global const float *aux,
                             int pitch, int slab, int plane, float4 gravity,
                             float viscous, float air, float dt,
                             __constant float4 *col, float c, const int mode)
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  float fx, fy, fz;
  msocl_planes_force(MSOCL_CONN_ARGS, pass, sp, sv, pitch, slab, plane,
                     viscous, x, y, z, a, &fx, &fy, &fz);
  const float im = aux[a];
  const float kv[3] = {fx * im + gravity.x, fy * im + gravity.y,
                       fz * im + gravity.z};
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  float p[3], v[3];
  if (mode == 2) {
    const float h = dt / 6.0f;
#pragma unroll
    for (int q = 0; q < 3; q++) {
      p[q] = p0[q * plane + a] + h * (sum_p[q * plane + a] + sv[q * plane + a]);
      v[q] = v0[q * plane + a] + h * (sum_v[q * plane + a] + kv[q]);
#ifdef MSOCL_AIR
      v[q] = air * v[q];
#endif
    }
    msocl_planes_project(&p[0], &p[1], &p[2], &v[0], &v[1], &v[2], dt,
                         col);
  } else {
    const float h = c * dt;
#pragma unroll
    for (int q = 0; q < 3; q++) {
      const float kp = sv[q * plane + a];
      const float sp_ = mode == 0 ? kp : sum_p[q * plane + a] + 2.0f * kp;
      const float sv_ = mode == 0 ? kv[q] : sum_v[q * plane + a] + 2.0f * kv[q];
      if (MSOCL_PLANES_LIVE) {
        sum_p[q * plane + a] = sp_;
        sum_v[q * plane + a] = sv_;
      }
      p[q] = p0[q * plane + a] + h * kp;
      v[q] = v0[q * plane + a] + h * kv[q];
    }
  }
  (void)air;
  (void)col;
  if (MSOCL_PLANES_LIVE) {
#pragma unroll
    for (int q = 0; q < 3; q++) {
      np[q * plane + a] = pinned ? p0[q * plane + a] : p[q];
      nv[q * plane + a] = pinned ? 0.0f : v[q];
    }
  }
}

#define MSOCL_PLANES_RK4_ARGS                                                 \
  (MSOCL_CONN, __global const float *p0, __global const float *v0,           \
   __global const float *sp, __global const float *sv,                       \
   __global float *sum_p, __global float *sum_v, __global float *np,         \
   __global float *nv, MSOCL_PLANES_ARGS, float c)
#define MSOCL_PLANES_RK4_NAMES                                                \
  (MSOCL_CONN_ARGS, p0, v0, sp, sv, sum_p, sum_v, np, nv,                    \
   MSOCL_PLANES_ARG_NAMES, c)
#define MSOCL_PLANES_RK4_CALL(mode)                                           \
  msocl_planes_rk4(MSOCL_CONN_ARGS, pass, x, y, z, p0, v0, sp, sv, sum_p,    \
                   sum_v, np, nv, aux, pitch, slab, plane, gravity, viscous, \
                   air, dt, col, c, mode)

MSOCL_PLANES_GATHER(msocl_planes_rk4_first, MSOCL_PLANES_RK4_ARGS,
                    MSOCL_PLANES_RK4_NAMES)
{
  MSOCL_PLANES_RK4_CALL(0);
}

MSOCL_PLANES_GATHER(msocl_planes_rk4_middle, MSOCL_PLANES_RK4_ARGS,
                    MSOCL_PLANES_RK4_NAMES)
{
  MSOCL_PLANES_RK4_CALL(1);
}

MSOCL_PLANES_GATHER(msocl_planes_rk4_last, MSOCL_PLANES_RK4_ARGS,
                    MSOCL_PLANES_RK4_NAMES)
{
  MSOCL_PLANES_RK4_CALL(2);
}

/* Provot's strain limiting in planes: a Jacobi
 * sweep from p into p_out, each point moved by the size-weighted average
 * of what its over-long springs ask (half the excess, a pinned
 * neighbour's spring all of it); pinned points stay. (In
 * float4 a missing neighbour is the point itself, whose zero length asks
 * nothing; here `there` masks it.) */
/* One slot's ask in Provot's sweep on the point at q[0..2], added to
 * d[0..3] (the move and the weight) where the spring is over its limit. */
static MSOCL_PLANES_INLINE void msocl_planes_provot(__global const float *p,
                                __global const float *aux, int plane,
                                float limit, const float *q, int b,
                                bool there, float rest, float *d)
{
  const float dx = p[b] - q[0], dy = p[plane + b] - q[1],
              dz = p[2 * plane + b] - q[2];
  const float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
  const float over = len - (1.0f + limit) * rest;
  const float ask = (MSOCL_PLANES_PINNED(aux[plane + b]) ? 1.0f : 0.5f) *
                    over;
  const float t = ask * MSOCL_DIV(ask, len);
  const bool on = there && over > 0.0f;
  d[0] += on ? t * dx : 0.0f;
  d[1] += on ? t * dy : 0.0f;
  d[2] += on ? t * dz : 0.0f;
  d[3] += on ? ask : 0.0f;
}

MSOCL_PLANES_GATHER(msocl_planes_strain,
                    (MSOCL_CONN, __global const float *p,
                     __global float *p_out, __global const float *aux,
                     int pitch, int slab, int plane, float limit),
                    (MSOCL_CONN_ARGS, p, p_out, aux, pitch, slab, plane,
                     limit))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a];
  const float q[3] = {px, py, pz};
  float d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_TABLE_SLOTS; s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    (void)kk; (void)cc;
    msocl_planes_provot(p, aux, plane, limit, q, b, there, rest, d);
  }
#ifdef MSOCL_SPILL
  MSOCL_PLANES_SPILLS {
    MSOCL_PLANES_SPILL_NEIGHBOR(o);
    (void)kk; (void)cc;
    msocl_planes_provot(p, aux, plane, limit, q, b, there, rest, d);
  }
#endif
  float dpx = d[0], dpy = d[1], dpz = d[2];
  const float weight = d[3];
  if (weight > 0.0f) {
    dpx = MSOCL_DIV(dpx, weight);
    dpy = MSOCL_DIV(dpy, weight);
    dpz = MSOCL_DIV(dpz, weight);
  }
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (MSOCL_PLANES_LIVE) {
    p_out[a] = pinned ? px : px + dpx;
    p_out[plane + a] = pinned ? py : py + dpy;
    p_out[2 * plane + a] = pinned ? pz : pz + dpz;
  }
}

/* And its end: v += (corrected - p) / dt, then p
 * takes the corrected position. */
__kernel void msocl_planes_commit(__global float *p,
                                  __global const float *corrected,
                                  __global float *v, int nx, int pitch,
                                  int slab, int plane, float dt)
{
  MSOCL_PLANES_XYZ;
  const int a = MSOCL_PLANES_AT(x, y, z);
  (void)slab;
  if (x < nx) {
    const float cx = corrected[a], cy = corrected[plane + a],
                cz = corrected[2 * plane + a];
    v[a] = v[a] + MSOCL_DIV(cx - p[a], dt);
    v[plane + a] = v[plane + a] + MSOCL_DIV(cy - p[plane + a], dt);
    v[2 * plane + a] = v[2 * plane + a] + MSOCL_DIV(cz - p[2 * plane + a], dt);
    p[a] = cx;
    p[plane + a] = cy;
    p[2 * plane + a] = cz;
  }
}

/* The velocity kind in planes: a Jacobi sweep
 * from v into v_out at the step's starting positions p, each point's
 * velocity changed by the size-weighted average of what its springs ask
 * (the relative speed along a spring beyond what brings it to the limit
 * within the step: half of it, a pinned neighbour's spring all of it),
 * then the collision response again without friction. */
/* One slot's ask in the velocity kind's sweep on the point whose position
 * and velocity are q[0..5], added to d[0..3] (the change and the weight)
 * where the spring would pass its limit. */
static MSOCL_PLANES_INLINE void msocl_planes_vassilev(__global const float *p,
                                  __global const float *v,
                                  __global const float *aux, int plane,
                                  float limit, float dt, const float *q,
                                  int b, bool there, float rest, float *d)
{
  const float dx = p[b] - q[0], dy = p[plane + b] - q[1],
              dz = p[2 * plane + b] - q[2];
  const float len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz));
  const float allowed = MSOCL_DIV((1.0f + limit) * rest - len, dt);
  const float excess =
      MSOCL_DIV(MSOCL_DOT3(v[b] - q[3], v[plane + b] - q[4],
                           v[2 * plane + b] - q[5], dx, dy, dz),
                len) -
      allowed;
  const float ask =
      (MSOCL_PLANES_PINNED(aux[plane + b]) ? 1.0f : 0.5f) * excess;
  const float t = ask * MSOCL_DIV(ask, len);
  const bool on = there && len > 0.0f && excess > 0.0f;
  d[0] += on ? t * dx : 0.0f;
  d[1] += on ? t * dy : 0.0f;
  d[2] += on ? t * dz : 0.0f;
  d[3] += on ? ask : 0.0f;
}

MSOCL_PLANES_GATHER(msocl_planes_strain_v,
                    (MSOCL_CONN, __global const float *p,
                     __global const float *v, __global float *v_out,
                     __global const float *aux, int pitch, int slab,
                     int plane, float limit, float dt,
                     __constant float4 *col),
                    (MSOCL_CONN_ARGS, p, v, v_out, aux, pitch, slab, plane,
                     limit, dt, col))
{
  const int a = MSOCL_PLANES_AT(x, y, z);
  const float px = p[a], py = p[plane + a], pz = p[2 * plane + a];
  const float vx = v[a], vy = v[plane + a], vz = v[2 * plane + a];
  const float q[6] = {px, py, pz, vx, vy, vz};
  float d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
#pragma unroll
  for (int s = 0; s < MSOCL_TABLE_SLOTS; s++) {
    if (MSOCL_PLANES_SKIP(s))
      continue;
    MSOCL_PLANES_NEIGHBOR(s);
    (void)kk; (void)cc;
    msocl_planes_vassilev(p, v, aux, plane, limit, dt, q, b, there, rest, d);
  }
#ifdef MSOCL_SPILL
  MSOCL_PLANES_SPILLS {
    MSOCL_PLANES_SPILL_NEIGHBOR(o);
    (void)kk; (void)cc;
    msocl_planes_vassilev(p, v, aux, plane, limit, dt, q, b, there, rest, d);
  }
#endif
  float dvx = d[0], dvy = d[1], dvz = d[2];
  const float weight = d[3];
  if (weight > 0.0f) {
    dvx = MSOCL_DIV(dvx, weight);
    dvy = MSOCL_DIV(dvy, weight);
    dvz = MSOCL_DIV(dvz, weight);
  }
  float wx = vx + dvx, wy = vy + dvy, wz = vz + dvz;
  msocl_planes_collide(px, py, pz, &wx, &wy, &wz, dt, col, 0.0f);
  const bool pinned = MSOCL_PLANES_PINNED(aux[plane + a]);
  if (MSOCL_PLANES_LIVE) {
    v_out[a] = pinned ? 0.0f : wx;
    v_out[plane + a] = pinned ? 0.0f : wy;
    v_out[2 * plane + a] = pinned ? 0.0f : wz;
  }
}

/* The copy kernels run over the planes' range too: point
 * i = (z ny + y) nx + x of an nx-wide grid (n points; ny the range's
 * second size), at a in a plane - no division a point. */
#define MSOCL_PLANES_POINT                                                    \
  MSOCL_PLANES_XYZ;                                                          \
  const int i = (z * (int)get_global_size(1) + y) * nx + x;                  \
  const int a = MSOCL_PLANES_AT(x, y, z);                                    \
  (void)slab;                                                                \
  if (x >= nx || i >= n)                                                     \
    return

/* The engine's float4 state into planes. */
__kernel void msocl_planes_pack(__global const float4 *pos,
                                __global const float4 *vel,
                                __global const float *inv_mass,
                                __global float *p, __global float *v,
                                __global float *aux, int nx, int pitch,
                                int slab, int plane, int n)
{
  MSOCL_PLANES_POINT;
  const float4 q = pos[i], w = vel[i];
  p[a] = q.x;
  p[plane + a] = q.y;
  p[2 * plane + a] = q.z;
  v[a] = w.x;
  v[plane + a] = w.y;
  v[2 * plane + a] = w.z;
  aux[a] = inv_mass[i];
  aux[plane + a] = q.w;
}

/* And back: pos.w as packed; vel.w 0, as the velocity pass writes it. */
__kernel void msocl_planes_unpack(__global const float *p,
                                  __global const float *v,
                                  __global const float *aux,
                                  __global float4 *pos, __global float4 *vel,
                                  int nx, int pitch, int slab, int plane, int n)
{
  MSOCL_PLANES_POINT;
  pos[i] = (float4)(p[a], p[plane + a], p[2 * plane + a], aux[plane + a]);
  vel[i] = (float4)(v[a], v[plane + a], v[2 * plane + a], 0.0f);
}

#endif

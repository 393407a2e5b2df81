/* Symplectic Euler on a cloth grid in planes, one sweep a step, each
 * spring computed once (lib/engine/planes_rows.c takes it where it applies: a
 * CPU device, no strain limit, rows at least MSOCL_ROWS_W
 * points wide). It keeps planes.h's layout: point (x, y) at
 * (y + 2) * pitch + x + 2 of each plane, aux the inverse masses then
 * pos.w, col a float4 a collider value.
 *
 * Why: the planes kernels compute each spring at both of its ends, two
 * square roots and two divisions a spring, and the dividers bound the
 * step on a CPU. Here a work-item sweeps a block of rows in explicit
 * vectors of MSOCL_ROWS_W points: for each row it writes the terms of
 * every point's six forward springs (right, above, above-left,
 * above-right, bend right, bend above) into a ring of three rows in
 * `ring`, then sums each point's twelve slots from the ring - a
 * backward spring is a forward one negated, bit for bit, as its d is -d
 * and its length the same - and moves the point, both passes at once as
 * in msocl_planes_fused: its velocity in place (no other point reads
 * it) or, with wind or dashpots, which read the neighbours' velocities
 * before the step, into the other plane set; its position into the
 * other plane set.
 *
 * The position planes' padding holds NaN (engine/planes_rows.c): a missing
 * neighbour's length is NaN, `len > 0` fails and its term is the zero
 * msocl_planes_force adds for it, with no edge test a slot. Same slot
 * order and arithmetic as msocl_planes_kick, so the result is bitwise
 * GRID's (tests/check_planes.c). msocl_planes_rows_steps runs several
 * steps a launch, each a few rows behind the one before (temporal
 * blocking): one launch's wait and pass over the planes for several. */
#include "rows.h"
#include "wind.h"

#if defined(MSOCL_PLANES) && defined(MSOCL_LAYOUT_GRID) && \
    !defined(MSOCL_GRID_3D)

/* Terms of one ring row: six forward springs' x, y, z terms, then wind's
 * on the quad's two triangles (A, B as wind.cl's msocl_wind_quads), then
 * with dashpots the six springs' dashpot terms (term 8 + f: summed apart,
 * as msocl_planes_pull adds a slot's spring and dashpot one after the
 * other),
 * each `ring_w` floats (a padded row's columns); engine/planes_rows.c
 * sizes the ring by the same count */
#define MSOCL_ROWS_DASH 8
#ifdef MSOCL_DAMPING
#define MSOCL_ROWS_TERMS 42
#else
#define MSOCL_ROWS_TERMS 24
#endif

/* The forward springs: offset in a plane, kind and rest index (as
 * common.h's slots 2, 3, 6, 7, 10, 11). */
#define MSOCL_ROWS_OFF(f, pitch)                                              \
  ((f) == 0 ? 1 : (f) == 1 ? (pitch) : (f) == 2 ? (pitch) - 1                \
   : (f) == 3 ? (pitch) + 1 : (f) == 4 ? 2 : 2 * (pitch))
/* ... as a row above (0, 1 or 2) and a column offset */
#define MSOCL_ROWS_DY(f) ((f) == 0 || (f) == 4 ? 0 : (f) == 5 ? 2 : 1)
#define MSOCL_ROWS_DX(f)                                                      \
  ((f) == 0 || (f) == 3 ? 1 : (f) == 2 ? -1 : (f) == 4 ? 2 : 0)
#define MSOCL_ROWS_KIND(f) ((f) < 2 ? 0 : (f) < 4 ? 1 : 2)
#define MSOCL_ROWS_REST(f)                                                    \
  ((f) == 0 ? grid_rest.s0 : (f) == 1 ? grid_rest.s1                         \
   : (f) == 2 ? grid_rest.s3 : (f) == 3 ? grid_rest.s2                       \
   : (f) == 4 ? grid_rest.s4 : grid_rest.s5)
#define MSOCL_ROWS_K(f)                                                       \
  (MSOCL_ROWS_KIND(f) == 0 ? grid_k.x : MSOCL_ROWS_KIND(f) == 1 ? grid_k.y   \
                                                               : grid_k.z)
#define MSOCL_ROWS_HAS(f) ((MSOCL_GRID_KINDS >> MSOCL_ROWS_KIND(f)) & 1)

/* Wind on the quads at row y's padded columns c.. into ring row t
 * (terms 6 and 7: A and B), from the velocities before the step in rows
 * v0 (y) and v1 (y + 1), planes `ps` floats apart, and the quads' edges
 * (msocl_rows_springs_at's ex..ez: right, above, -, above-right), as
 * msocl_wind_quads computes them: zero where the quad is not the
 * model's (its padding corners hold NaN). */
static inline __attribute__((always_inline)) void
msocl_rows_wind(MSOCL_CONN, __global const float *v0,
                __global const float *v1, int ps, int y, int c,
                const msocl_rows_f *ex, const msocl_rows_f *ey,
                const msocl_rows_f *ez, float4 air, float4 coef,
                __global float *t, int ring_w)
{
  const int q = ps;
  const msocl_rows_m x = MSOCL_ROWS_LANES + (c - 2);
  /* select reads a lane's sign bit: the row's test as -1 or 0 */
  const int row_real = -(int)(y >= 0 && y + 1 < grid_ny);
  const msocl_rows_m real = (x >= 0) & (x + 1 < grid_nx) & row_real;
  /* the quad's corners (y, c), (y, c+1), (y+1, c+1) (A) and (y, c),
   * (y+1, c+1), (y+1, c) (B) */
  __global const float *a = v0 + c, *r = a + 1, *u = v1 + c + 1,
                       *l = v1 + c;
#define V(o) MSOCL_ROWS_LOAD(o)
  const msocl_rows_f v0x = V(a), v0y = V(q + a), v0z = V(2 * q + a);
  const msocl_rows_f vux = V(u), vuy = V(q + u), vuz = V(2 * q + u);
  MSOCL_WIND_FORCE(msocl_rows_f, MSOCL_ROWS_SEL, wa_, ex[0], ey[0], ez[0],
                   ex[3], ey[3], ez[3], v0x + V(r) + vux,
                   v0y + V(q + r) + vuy, v0z + V(2 * q + r) + vuz, air,
                   coef, ax, ay, az);
  __global float *o = t + 3 * 6 * ring_w + c;
  MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(real, ax, 0.0f), o);
  MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(real, ay, 0.0f), o + ring_w);
  MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(real, az, 0.0f), o + 2 * ring_w);
  MSOCL_WIND_FORCE(msocl_rows_f, MSOCL_ROWS_SEL, wb_, ex[3], ey[3], ez[3],
                   ex[1], ey[1], ez[1], v0x + vux + V(l),
                   v0y + vuy + V(q + l), v0z + vuz + V(2 * q + l), air,
                   coef, bx, by, bz);
#undef V
  o += 3 * ring_w;
  MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(real, bx, 0.0f), o);
  MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(real, by, 0.0f), o + ring_w);
  MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(real, bz, 0.0f), o + 2 * ring_w);
}

/* Row y's forward spring terms at the padded columns c..c + W - 1 into
 * ring row t: msocl_planes_pull's `on ? t * d : 0`, and with dashpots its
 * `onh ? u * d : 0` from the velocities before the step (a backward one
 * negates exactly: w and d both flip, w . d and len2 stay). Positions and
 * velocities of rows y, y + 1, y + 2 at p0.., v0.. (column 0 is x = -2;
 * msocl_rows_row sweeps 0..nx + 2), planes `ps` floats apart. */
static inline __attribute__((always_inline)) void
msocl_rows_springs_at(MSOCL_CONN, __global const float *p0,
                      __global const float *p1, __global const float *p2,
                      __global const float *v0, __global const float *v1,
                      __global const float *v2, int ps, int y,
                      __global float *t, int ring_w, float4 air,
                      float4 coef, const int wind, const int c)
{
#ifdef MSOCL_DAMPING
  const float cc = MSOCL_GRID_C;
#endif
  (void)v2;
  const msocl_rows_f px = MSOCL_ROWS_LOAD(p0 + c),
                     py = MSOCL_ROWS_LOAD(p0 + ps + c),
                     pz = MSOCL_ROWS_LOAD(p0 + 2 * ps + c);
#ifdef MSOCL_DAMPING
  const msocl_rows_f vx = MSOCL_ROWS_LOAD(v0 + c),
                     vy = MSOCL_ROWS_LOAD(v0 + ps + c),
                     vz = MSOCL_ROWS_LOAD(v0 + 2 * ps + c);
#endif
  /* wind's quad edges: springs 0, 3 and 1's (right, above-right,
   * above), the same bits as loading them again */
  msocl_rows_f ex[4], ey[4], ez[4];
#pragma unroll
  for (int f = 0; f < 6; f++) {
    const bool edge = wind && f < 4 && f != 2;
    if (!MSOCL_ROWS_HAS(f) && !edge)
      continue;
    const int o_ = c + MSOCL_ROWS_DX(f);
    __global const float *o = (MSOCL_ROWS_DY(f) == 0   ? p0
                               : MSOCL_ROWS_DY(f) == 1 ? p1
                                                       : p2) + o_;
    const float kk = MSOCL_ROWS_K(f), rest = MSOCL_ROWS_REST(f);
    const msocl_rows_f dx = MSOCL_ROWS_LOAD(o) - px,
                       dy = MSOCL_ROWS_LOAD(o + ps) - py,
                       dz = MSOCL_ROWS_LOAD(o + 2 * ps) - pz;
    if (edge) {
      ex[f] = dx;
      ey[f] = dy;
      ez[f] = dz;
    }
    if (!MSOCL_ROWS_HAS(f))
      continue;
    const msocl_rows_f len2 = dx * dx + dy * dy + dz * dz;
    const msocl_rows_f len = MSOCL_SQRT(len2);
    const msocl_rows_f k = kk * MSOCL_DIV(len - rest, len);
    const msocl_rows_m on = len > 0.0f;
    __global float *q = t + 3 * f * ring_w + c;
    MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(on, k * dx, 0.0f), q);
    MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(on, k * dy, 0.0f), q + ring_w);
    MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(on, k * dz, 0.0f), q + 2 * ring_w);
#ifdef MSOCL_DAMPING
    __global const float *b = (MSOCL_ROWS_DY(f) == 0   ? v0
                               : MSOCL_ROWS_DY(f) == 1 ? v1
                                                       : v2) + o_;
    const msocl_rows_f wx = MSOCL_ROWS_LOAD(b) - vx,
                       wy = MSOCL_ROWS_LOAD(b + ps) - vy,
                       wz = MSOCL_ROWS_LOAD(b + 2 * ps) - vz;
    const msocl_rows_f u =
        cc * MSOCL_DIV(wx * dx + wy * dy + wz * dz, len2);
    const msocl_rows_m onh = len2 > 0.0f;
    __global float *h = t + 3 * (MSOCL_ROWS_DASH + f) * ring_w + c;
    MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(onh, u * dx, 0.0f), h);
    MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(onh, u * dy, 0.0f), h + ring_w);
    MSOCL_ROWS_STORE(MSOCL_ROWS_SEL(onh, u * dz, 0.0f), h + 2 * ring_w);
#endif
  }
  if (wind)
    msocl_rows_wind(MSOCL_CONN_ARGS, v0, v1, ps, y, c, ex, ey, ez, air,
                    coef, t, ring_w);
}

/* Term q of forward spring f in ring row r at padded column c */
#define MSOCL_ROWS_T(r, f, q, c)                                              \
  MSOCL_ROWS_LOAD((r) + (3 * (f) + (q)) * ring_w + (c))

/* One slot: forward spring f's term in ring row r at column c, forward
 * (+) or backward (-), then its dashpot's, as msocl_planes_pull adds them */
#ifdef MSOCL_DAMPING
#define MSOCL_ROWS_ADD(sg, r, f, c)                                           \
  g += sg MSOCL_ROWS_T(r, f, q, c);                                           \
  g += sg MSOCL_ROWS_T(r, MSOCL_ROWS_DASH + (f), q, c)
#else
#define MSOCL_ROWS_ADD(sg, r, f, c) g += sg MSOCL_ROWS_T(r, f, q, c)
#endif

/* One component of a point's force: its twelve slots in common.h's order
 * from ring rows r0, r1, r2 (rows y - 2, y - 1, y) at column c; kinds the
 * model leaves out add nothing, as in msocl_planes_force. */
static inline __attribute__((always_inline)) msocl_rows_f
msocl_rows_sum(__global const float *r0,
                                   __global const float *r1,
                                   __global const float *r2, int q, int c,
                                   int ring_w)
{
  msocl_rows_f g = 0.0f;
  if (MSOCL_ROWS_HAS(0)) {
    MSOCL_ROWS_ADD(-, r1, 1, c);
    MSOCL_ROWS_ADD(-, r2, 0, c - 1);
    MSOCL_ROWS_ADD(+, r2, 0, c);
    MSOCL_ROWS_ADD(+, r2, 1, c);
  }
  if (MSOCL_ROWS_HAS(2)) {
    MSOCL_ROWS_ADD(-, r1, 3, c - 1);
    MSOCL_ROWS_ADD(-, r1, 2, c + 1);
    MSOCL_ROWS_ADD(+, r2, 2, c);
    MSOCL_ROWS_ADD(+, r2, 3, c);
  }
  if (MSOCL_ROWS_HAS(4)) {
    MSOCL_ROWS_ADD(-, r0, 5, c);
    MSOCL_ROWS_ADD(-, r2, 4, c - 2);
    MSOCL_ROWS_ADD(+, r2, 4, c);
    MSOCL_ROWS_ADD(+, r2, 5, c);
  }
  return g;
}

/* The kick and drift (msocl_planes_fused) of a row's points at padded
 * columns c..c + W - 1 from ring rows r0, r1, r2: positions and
 * velocities read from rows pr, vr (column 0 is x = -2; planes `ps`
 * floats apart), written to rows pw, vw (`pso` apart), the inverse masses
 * and pins from row ar (`plane` apart); vw may be vr without wind or
 * dashpots (only the point reads its own velocity). The `last` vector
 * ends at the row's last point, over points the one before it has
 * updated: its velocities tx.. are read before the row's first. */
static inline __attribute__((always_inline)) void
msocl_rows_kick_at(MSOCL_CONN, __global const float *pr,
                   __global const float *vr, int ps, __global float *pw,
                   __global float *vw, int pso, __global const float *ar,
                   int plane, float4 gravity, float viscous, float air,
                   float dt, __constant const float *cf,
                   __global const float *r0, __global const float *r1,
                   __global const float *r2, int ring_w, int wind,
                   int still, const bool last, const int c,
                   msocl_rows_f tx, msocl_rows_f ty, msocl_rows_f tz)
{
  const msocl_rows_f fx0 = msocl_rows_sum(r0, r1, r2, 0, c, ring_w),
                     fy0 = msocl_rows_sum(r0, r1, r2, 1, c, ring_w),
                     fz0 = msocl_rows_sum(r0, r1, r2, 2, c, ring_w);
  msocl_rows_f ux = last ? tx : MSOCL_ROWS_LOAD(vr + c),
               uy = last ? ty : MSOCL_ROWS_LOAD(vr + ps + c),
               uz = last ? tz : MSOCL_ROWS_LOAD(vr + 2 * ps + c);
  const msocl_rows_f im = MSOCL_ROWS_LOAD(ar + c);
  if (wind) {
    /* the six triangles' thirds in triangle order, then the velocity
     * change, as msocl_wind_quad_points and msocl_wind_kick */
    msocl_rows_f wx = 0.0f, wy = 0.0f, wz = 0.0f;
#define W(r, f, cc)                                                           \
  wx += MSOCL_ROWS_T(r, f, 0, cc);                                            \
  wy += MSOCL_ROWS_T(r, f, 1, cc);                                            \
  wz += MSOCL_ROWS_T(r, f, 2, cc)
    W(r1, 6, c - 1);
    W(r1, 7, c - 1);
    W(r1, 7, c);
    W(r2, 6, c - 1);
    W(r2, 6, c);
    W(r2, 7, c);
#undef W
#ifdef MSOCL_PINS
    const msocl_rows_m held = MSOCL_ROWS_LOAD(ar + plane + c) != 0.0f;
    const msocl_rows_f s = MSOCL_ROWS_SEL(held, 0.0f, dt * im);
#else
    const msocl_rows_f s = dt * im;
#endif
    ux += s * wx;
    uy += s * wy;
    uz += s * wz;
  }
  const msocl_rows_f px = MSOCL_ROWS_LOAD(pr + c),
                     py = MSOCL_ROWS_LOAD(pr + ps + c),
                     pz = MSOCL_ROWS_LOAD(pr + 2 * ps + c);
  msocl_rows_f vx, vy, vz;
  msocl_rows_velocity(fx0, fy0, fz0, ux, uy, uz, im, px, py, pz, gravity,
                      viscous, air, dt, cf, still, &vx, &vy, &vz);
  msocl_rows_f qx = px + dt * vx, qy = py + dt * vy, qz = pz + dt * vz;
#ifdef MSOCL_PINS
  const msocl_rows_m pinned = MSOCL_ROWS_LOAD(ar + plane + c) != 0.0f;
  vx = MSOCL_ROWS_SEL(pinned, 0.0f, vx);
  vy = MSOCL_ROWS_SEL(pinned, 0.0f, vy);
  vz = MSOCL_ROWS_SEL(pinned, 0.0f, vz);
  qx = MSOCL_ROWS_SEL(pinned, px, qx);
  qy = MSOCL_ROWS_SEL(pinned, py, qy);
  qz = MSOCL_ROWS_SEL(pinned, pz, qz);
#endif
  MSOCL_ROWS_STORE(vx, vw + c);
  MSOCL_ROWS_STORE(vy, vw + pso + c);
  MSOCL_ROWS_STORE(vz, vw + 2 * pso + c);
  MSOCL_ROWS_STORE(qx, pw + c);
  MSOCL_ROWS_STORE(qy, pw + pso + c);
  MSOCL_ROWS_STORE(qz, pw + 2 * pso + c);
}

/* Row y: its springs' terms (msocl_rows_springs_at, wind's quads where
 * `blow`) and, where `kick`, its points' kick (msocl_rows_kick_at), in
 * one column loop, each kick a vector behind the terms it reads (columns
 * up to its own): one loop's additions and stores run while the other's
 * square roots and divisions wait on the divider. The last vectors of
 * both move back to end at the row's end, over columns done (the same
 * terms again; velocities read before), so no load passes the planes. */
static inline __attribute__((always_inline)) void
msocl_rows_row(MSOCL_CONN, __global const float *p0,
               __global const float *p1, __global const float *p2,
               __global const float *v0, __global const float *v1,
               __global const float *v2, int ps, int y, __global float *t,
               int ring_w, float4 wind_air, float4 wind_coef, const int blow,
               const bool kick, __global float *pw, __global float *vw,
               int pso, __global const float *ar, int plane, float4 gravity,
               float viscous, float air, float dt,
               __constant const float *cf, __global const float *r0,
               __global const float *r1, int wind, int still)
{
  const int cols = grid_nx + 3, tail = grid_nx - MSOCL_ROWS_W + 2;
  const int tt = kick ? tail : 0;
  const msocl_rows_f tx = MSOCL_ROWS_LOAD(v0 + tt),
                     ty = MSOCL_ROWS_LOAD(v0 + ps + tt),
                     tz = MSOCL_ROWS_LOAD(v0 + 2 * ps + tt);
  int x0 = kick ? 2 : grid_nx + 2;
#define MSOCL_ROWS_KICK_AT(xc)                                                \
  msocl_rows_kick_at(MSOCL_CONN_ARGS, p0, v0, ps, pw, vw, pso, ar, plane,     \
                     gravity, viscous, air, dt, cf, r0, r1, t, ring_w, wind,  \
                     still, (xc) >= tail, min((xc), tail), tx, ty, tz)
  for (int c0 = 0; c0 < cols; c0 += MSOCL_ROWS_W) {
    const int c = min(c0, cols - MSOCL_ROWS_W);
    msocl_rows_springs_at(MSOCL_CONN_ARGS, p0, p1, p2, v0, v1, v2, ps, y, t,
                          ring_w, wind_air, wind_coef, blow, c);
    if (x0 < grid_nx + 2 && min(x0, tail) <= c) {
      MSOCL_ROWS_KICK_AT(x0);
      x0 += MSOCL_ROWS_W;
    }
  }
  for (; x0 < grid_nx + 2; x0 += MSOCL_ROWS_W)
    MSOCL_ROWS_KICK_AT(x0);
#undef MSOCL_ROWS_KICK_AT
}

#define MSOCL_ROWS_PARAMS                                                     \
  MSOCL_CONN, __global const float *p, __global const float *v,               \
      __global float *p_out, __global const float *aux, int pitch, int plane, \
      float4 gravity, float viscous, float air, float dt,                     \
      __constant float4 *col, __global float *ring, int ring_w,               \
      __global float *v_out, float4 wind_air, float4 wind_coef, int wind
#define MSOCL_ROWS_ARGS                                                       \
  MSOCL_CONN_ARGS, p, v, p_out, aux, pitch, plane, gravity, viscous, air, dt, \
      col, ring, ring_w, v_out, wind_air, wind_coef, wind

/* A sweeping work-item's ring row width rw - a build constant where the
 * host gives one, so that the ring's term rows sit at fixed offsets from
 * three pointers, not a pointer each that spills - its block of rows
 * [y0, y1) (work-item b of nb), and a ring row's floats `one`. */
#ifdef MSOCL_ROWS_RING_W
#define MSOCL_ROWS_RW MSOCL_ROWS_RING_W
#else
#define MSOCL_ROWS_RW ring_w
#endif
#define MSOCL_ROWS_BLOCK                                                      \
  const int rw = MSOCL_ROWS_RW;                                               \
  const int b = get_global_id(0), nb = get_global_size(0);                    \
  const int y0 = (int)((long)grid_ny * b / nb),                               \
            y1 = (int)((long)grid_ny * (b + 1) / nb);                         \
  const size_t one = (size_t)MSOCL_ROWS_TERMS * rw;                           \
  (void)ring_w

/* One step, work-item b of B sweeping rows [ny b / B, ny (b + 1) / B)
 * with its own ring of three rows: the two rows below the block first,
 * for its first rows' backward springs. */
static inline __attribute__((always_inline)) void
msocl_rows_step(MSOCL_ROWS_PARAMS, int still)
{
  MSOCL_ROWS_BLOCK;
  __global float *mine = ring + (size_t)b * 3 * one;
  __constant const float *cf = (__constant const float *)col;
  for (int y = y0 - 2; y < y1; y++) {
    /* the windless loop apart, specialised */
    __global float *t = mine + (size_t)((y + 3) % 3) * one;
    const int row = (y + 2) * pitch;
    __global const float *pr = p + row, *vr = v + row;
#define MSOCL_ROWS_ROW(blow)                                                  \
  msocl_rows_row(MSOCL_CONN_ARGS, pr, pr + pitch, pr + 2 * pitch, vr,         \
                 vr + pitch, vr + 2 * pitch, plane, y, t, rw, wind_air,       \
                 wind_coef, blow, y >= y0, p_out + row, v_out + row, plane,   \
                 aux + row, plane, gravity, viscous, air, dt, cf,             \
                 mine + (size_t)((y + 1) % 3) * one,                          \
                 mine + (size_t)((y + 2) % 3) * one, wind, still)
    if (wind && y >= y0 - 1)
      MSOCL_ROWS_ROW(1);
    else
      MSOCL_ROWS_ROW(0);
#undef MSOCL_ROWS_ROW
  }
}

__kernel void msocl_planes_rows(MSOCL_ROWS_PARAMS)
{
  msocl_rows_step(MSOCL_ROWS_ARGS, 0);
}

/* The same step when the host knows that no collider moves in it (the
 * table's motion flags all 0): the colliders' motion compiled out of the
 * kick, which then spills less, the same bits. */
__kernel void msocl_planes_rows_still(MSOCL_ROWS_PARAMS)
{
  msocl_rows_step(MSOCL_ROWS_ARGS, 1);
}

/* Steps a launch of msocl_planes_rows_steps at most (planes_rows.c's
 * ROWS_STEPS, msocl.h's MSOCL_MAX_SWEEP_STEPS) */
#define MSOCL_ROWS_STEPS 8

/* Row r of a middle state in its ring `m` (three rows, then one of NaN
 * for rows off the grid), each `slot` floats: positions then velocities,
 * planes `pitch` floats apart. */
static inline __global float *msocl_rows_mid(__global float *m, int r,
                                             int slot, int ny)
{
  return m + (size_t)(r < 0 || r >= ny ? 3 : r % 3) * slot;
}

/* `steps` steps (at most MSOCL_ROWS_STEPS) in one launch, with colliders
 * at rest (engine/planes_rows.c): work-item b moves rows [y0, y1) by
 * `steps` steps. Step j runs two rows behind step j - 1 and covers
 * 2 (steps - 1 - j) rows more on each side than the block, recomputed as
 * the neighbouring blocks compute them; each step but the last writes
 * its rows into a ring of three in `mid`, which the next reads. The same
 * arithmetic in the same order as one launch a step, so the same bits,
 * with fewer launches and passes over the planes. */
__kernel void msocl_planes_rows_steps(MSOCL_ROWS_PARAMS, __global float *mid,
                                      int steps)
{
  MSOCL_ROWS_BLOCK;
  const int slot = 6 * pitch, vs = 3 * pitch;
  /* a block's rings of terms and middle states, a step each */
  __global float *rings = ring + (size_t)b * MSOCL_ROWS_STEPS * 3 * one;
  __global float *mids =
      mid + (size_t)b * (MSOCL_ROWS_STEPS * (4 * slot + MSOCL_ROWS_W)) +
      MSOCL_ROWS_W;
  __constant const float *cf = (__constant const float *)col;
  const int last = 2 * (steps - 1);
  for (int y = max(y0 - last, 0) - 2; y < y1 + last; y++) {
    for (int j = 0; j < steps; j++) {
      /* step j's row z and the rows it kicks, [k0, k1) */
      const int z = y - 2 * j, h = last - 2 * j;
      const int k0 = max(y0 - h, 0), k1 = min(y1 + h, grid_ny);
      if (z < k0 - 2 || z >= k1)
        continue;
      __global float *ts = rings + (size_t)j * 3 * one;
      __global float *t = ts + (size_t)((z + 3) % 3) * one;
      /* its input: the planes, or the ring step j - 1 writes */
      __global float *mi =
          mids + (size_t)max(j - 1, 0) * (4 * slot + MSOCL_ROWS_W);
      const int row = (z + 2) * pitch, in = j == 0 ? plane : pitch;
      __global const float
          *p0 = j == 0 ? p + row : msocl_rows_mid(mi, z, slot, grid_ny),
          *p1 = j == 0 ? p0 + pitch : msocl_rows_mid(mi, z + 1, slot, grid_ny),
          *p2 = j == 0 ? p0 + 2 * pitch
                       : msocl_rows_mid(mi, z + 2, slot, grid_ny);
      __global const float *v0 = j == 0 ? v + row : p0 + vs,
                           *v1 = j == 0 ? v0 + pitch : p1 + vs,
                           *v2 = j == 0 ? v0 + 2 * pitch : p2 + vs;
      /* its output: the planes, or its own ring */
      __global float *mo = mids + (size_t)min(j, MSOCL_ROWS_STEPS - 1) *
                                      (4 * slot + MSOCL_ROWS_W);
      __global float *pw =
          j == steps - 1 ? p_out + row : msocl_rows_mid(mo, z, slot, grid_ny);
      __global float *vw = j == steps - 1 ? v_out + row : pw + vs;
#define MSOCL_ROWS_ROW(blow)                                                  \
  msocl_rows_row(MSOCL_CONN_ARGS, p0, p1, p2, v0, v1, v2, in, z, t, rw,       \
                 wind_air, wind_coef, blow, z >= k0, pw, vw,                  \
                 j == steps - 1 ? plane : pitch, aux + row, plane, gravity,   \
                 viscous, air, dt, cf, ts + (size_t)((z + 1) % 3) * one,      \
                 ts + (size_t)((z + 2) % 3) * one, wind, 1)
      if (wind && z >= k0 - 1)
        MSOCL_ROWS_ROW(1);
      else
        MSOCL_ROWS_ROW(0);
#undef MSOCL_ROWS_ROW
    }
  }
}

#endif

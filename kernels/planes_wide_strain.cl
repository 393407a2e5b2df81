/* The strain limits' sweeps in explicit vectors (wide.h), the scalar
 * sweeps' arithmetic and slot order (planes.cl's msocl_planes_strain and
 * msocl_planes_strain_v), bitwise them (tests/check_planes.c): PoCL left
 * those scalar on its AVX2 target (docs/PERFORMANCE.md). */
#include "wide.h"

#ifdef MSOCL_ROWS
/* A strain sweep's sums d and weight w into the move d / w where w > 0
 * (msocl_planes_strain's and msocl_planes_strain_v's ends) */
static MSOCL_WIDE_INLINE msocl_rows_f msocl_wide_share(msocl_rows_f d,
                                                       msocl_rows_f w)
{
  return MSOCL_ROWS_SEL(w > 0.0f, MSOCL_DIV(d, w), d);
}

/* A slot's spring vectors d from the points at q[0..2] to their
 * neighbours in the planes at p, and their lengths */
#define MSOCL_WIDE_EDGE(p, q)                                                 \
  const msocl_rows_f dx = MSOCL_WIDE_NB(p) - (q)[0],                         \
                     dy = MSOCL_WIDE_NB((p) + plane) - (q)[1],               \
                     dz = MSOCL_WIDE_NB((p) + 2 * plane) - (q)[2];           \
  const msocl_rows_f len = MSOCL_SQRT(MSOCL_DOT3(dx, dy, dz, dx, dy, dz))

/* A strain sweep's slot: its ask t (dx, dy, dz) and weight `ask` added
 * to d[0..3] where `on` */
static MSOCL_WIDE_INLINE void
msocl_wide_ask(msocl_rows_m on, msocl_rows_f t, msocl_rows_f ask,
               msocl_rows_f dx, msocl_rows_f dy, msocl_rows_f dz,
               msocl_rows_f *d)
{
  d[0] += MSOCL_ROWS_SEL(on, t * dx, 0.0f);
  d[1] += MSOCL_ROWS_SEL(on, t * dy, 0.0f);
  d[2] += MSOCL_ROWS_SEL(on, t * dz, 0.0f);
  d[3] += MSOCL_ROWS_SEL(on, ask, 0.0f);
}

/* The W values of planes q, q + plane and q + 2 plane at a */
static MSOCL_WIDE_INLINE void msocl_wide_load3(__global const float *q,
                                               int plane, int a,
                                               msocl_rows_f *out)
{
  out[0] = MSOCL_ROWS_LOAD(q + a);
  out[1] = MSOCL_ROWS_LOAD(q + plane + a);
  out[2] = MSOCL_ROWS_LOAD(q + 2 * plane + a);
}

/* Whether each of the neighbours at MSOCL_WIDE_NB is pinned: its share
 * of a spring's correction is all of it then, else half */
#ifdef MSOCL_PINS
#define MSOCL_WIDE_NB_SHARE                                                   \
  MSOCL_ROWS_SEL(MSOCL_WIDE_NB(aux + plane) != 0.0f, 1.0f, 0.5f)
#else
#define MSOCL_WIDE_NB_SHARE ((msocl_rows_f)0.5f)
#endif

/* Provot's sweep (msocl_planes_strain's arithmetic and slot order): each
 * point moved by the weighted average of what its over-long springs
 * ask. */
__kernel void msocl_planes_wide_strain(MSOCL_CONN, __global const float *p,
                                       __global float *p_out,
                                       __global const float *aux, int pitch,
                                       int slab, int plane, float limit)
{
  MSOCL_WIDE_AT;
  msocl_rows_f q[3], d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  msocl_wide_load3(p, plane, a, q);
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
    MSOCL_WIDE_EDGE(p, q);
    const msocl_rows_f over = len - (1.0f + limit) * rest;
    const msocl_rows_f ask = MSOCL_WIDE_NB_SHARE * over;
    const msocl_rows_f t = ask * MSOCL_DIV(ask, len);
    msocl_wide_ask(there & (over > 0.0f), t, ask, dx, dy, dz, d);
  }
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
#pragma unroll
  for (int c = 0; c < 3; c++)
    MSOCL_WIDE_PUT(
        MSOCL_ROWS_SEL(held, q[c], q[c] + msocl_wide_share(d[c], d[3])),
        p_out + c * plane);
}

/* The velocity kind's sweep (msocl_planes_strain_v's arithmetic and slot
 * order), then the collision response again without friction. */
__kernel void msocl_planes_wide_strain_v(
    MSOCL_CONN, __global const float *p, __global const float *v,
    __global float *v_out, __global const float *aux, int pitch, int slab,
    int plane, float limit, float dt, __constant float4 *col)
{
  MSOCL_WIDE_AT;
  __global const float *vy_ = v + plane, *vz_ = vy_ + plane;
  msocl_rows_f q[3], u[3], d[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  msocl_wide_load3(p, plane, a, q);
  msocl_wide_load3(v, plane, a, u);
  MSOCL_WIDE_SLOTS {
    MSOCL_WIDE_SLOT;
    MSOCL_WIDE_EDGE(p, q);
    const msocl_rows_f allowed = MSOCL_DIV((1.0f + limit) * rest - len, dt);
    const msocl_rows_f excess =
        MSOCL_DIV(MSOCL_DOT3(MSOCL_WIDE_NB(v) - u[0], MSOCL_WIDE_NB(vy_) - u[1],
                             MSOCL_WIDE_NB(vz_) - u[2], dx, dy, dz),
                  len) -
        allowed;
    const msocl_rows_f ask = MSOCL_WIDE_NB_SHARE * excess;
    const msocl_rows_f t = ask * MSOCL_DIV(ask, len);
    msocl_wide_ask(there & (len > 0.0f) & (excess > 0.0f), t, ask, dx, dy,
                   dz, d);
  }
  msocl_rows_f wx = u[0] + msocl_wide_share(d[0], d[3]),
               wy = u[1] + msocl_wide_share(d[1], d[3]),
               wz = u[2] + msocl_wide_share(d[2], d[3]);
  __constant const float *cf = (__constant const float *)col;
#pragma unroll
  for (int c = 0; c < MSOCL_NCOL; c++)
    msocl_rows_collide(q[0], q[1], q[2], &wx, &wy, &wz, dt, cf, c, 0, 0.0f);
  (void)cf;
  const msocl_rows_m held = msocl_wide_pinned(aux, plane, a);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, wx), v_out);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, wy), v_out + plane);
  MSOCL_WIDE_PUT(MSOCL_ROWS_SEL(held, 0.0f, wz), v_out + 2 * plane);
}
#endif

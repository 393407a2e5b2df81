/* The tablecloth as an expert would write it in C for a CPU: the yardstick
 * of issue 15. Struct of arrays (x, y, z planes of floats for position and
 * velocity), every row padded by two points on each side so that the 12
 * neighbours of the GRID layout sit at fixed offsets, symplectic Euler's
 * two passes fused into one sweep over the rows, OpenMP over blocks of
 * rows, the inner loop over a row written for the vectorizer, and each
 * spring's length and force computed once for both of its ends.
 *
 * Same arithmetic, slot order and collision response per point as GRID
 * (kernels/planes.cl) in PRECISE math, so with no contraction of
 * a * b + c into FMAs its result is bitwise libmsocl's. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* One build of the row sweep per vector width, chosen when the program
 * starts, so that a distributed binary needs no -march=native. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    defined(__gnu_linux__)
#define EXPERT_CLONES \
  __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define EXPERT_CLONES
#endif

/* the 12 slots unrolled before the vectorizer sees the loop over a row */
#if defined(__GNUC__) && !defined(__clang__)
#define EXPERT_UNROLL _Pragma("GCC unroll 12")
#else
#define EXPERT_UNROLL
#endif

#if defined(_OPENMP)
#define EXPERT_SIMD _Pragma("omp simd")
#else
#define EXPERT_SIMD
#endif

struct bench_expert {
  int n, pitch;         /* points a row; floats a padded row */
  size_t plane;         /* floats a plane: n + 4 padded rows */
  float dt, inv_mass, viscous;
  float rest[3];        /* stretch, shear, bend */
  float *p, *v;         /* x, y, z planes, `plane` floats apart */
  float *xyz;           /* positions in the model's order */
  int threads;          /* blocks of rows a step */
  float *terms;         /* each thread's ring of spring terms */
};

/* A point's six forward springs (right, above, above-left, above-right,
 * bend right, bend above: slots 2, 3, 6, 7, 10, 11) and their x, y, z
 * force terms, each a padded row of `pitch` floats; a ring of three rows
 * a thread. */
enum { FWD = 6, RING = 3 };
static const int fwd_slot[FWD] = {2, 3, 6, 7, 10, 11};

/* The 12 slots of kernels/common.h's cloth grid, in its order: stretch
 * below, left, right, above; shear below-left, below-right, above-left,
 * above-right; bend two below, left, right, above. */
static const int slot_dx[12] = {0, -1, 1, 0, -1, 1, -1, 1, 0, -2, 2, 0};
static const int slot_dy[12] = {-1, 0, 0, 1, -1, -1, 1, 1, -2, 0, 0, 2};
static const int slot_kind[12] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};

static size_t at(const bench_expert *e, int x, int y)
{
  return (size_t)(y + 2) * e->pitch + x + 2;
}

int bench_expert_create(bench_expert **out, int n, float dt,
                        const float *xyz)
{
  *out = NULL;
  if (n < 3)
    return MSOCL_ERR_BAD_COUNT;
  bench_expert *e = calloc(1, sizeof *e);
  if (!e)
    return MSOCL_ERR_NO_MEMORY;
  e->n = n;
  /* rows start 64-byte aligned; the forward springs of x = n read x + 2
   * past the padding of two */
  e->pitch = (n + 5 + 15) / 16 * 16;
  e->plane = (size_t)(n + 4) * e->pitch;
  e->dt = dt;
  float m = TC_MASS / (float)(n * n);
  e->inv_mass = 1.0f / m;
  e->viscous = TC_VISCOUS_PER_MASS * m;
  bench_tc_rests(n, e->rest);
  size_t bytes = 3 * e->plane * sizeof(float);
  void *p = NULL, *v = NULL;
  if (posix_memalign(&p, 64, bytes) == 0)
    e->p = p;
  if (posix_memalign(&v, 64, bytes) == 0)
    e->v = v;
  e->xyz = malloc(3 * (size_t)n * n * sizeof *e->xyz);
  e->threads = bench_expert_threads();
  void *t = NULL;
  if (posix_memalign(&t, 64, (size_t)e->threads * RING * FWD * 3 *
                                 e->pitch * sizeof(float)) == 0)
    e->terms = t;
  if (!e->p || !e->v || !e->xyz || !e->terms) {
    bench_expert_destroy(e);
    return MSOCL_ERR_NO_MEMORY;
  }
  /* The padding holds NaN positions: a missing neighbour's length is NaN,
   * `len > 0` fails, and its terms become the zeros the kernels add, with
   * no edge test in the loop. */
  for (size_t i = 0; i < 3 * e->plane; i++)
    e->p[i] = NAN;
  memset(e->v, 0, bytes);
  for (int y = 0; y < n; y++)
    for (int x = 0; x < n; x++)
      for (int c = 0; c < 3; c++)
        e->p[c * e->plane + at(e, x, y)] = xyz[3 * ((size_t)y * n + x) + c];
  *out = e;
  return MSOCL_OK;
}

void bench_expert_destroy(bench_expert *e)
{
  if (!e)
    return;
  free(e->p);
  free(e->v);
  free(e->xyz);
  free(e->terms);
  free(e);
}

/* Row y's forward spring terms, x from -2 to n, into ring row `row`:
 * msocl_planes_force's `on ? t * d : 0` for each. A spring's other end sees
 * d negated, the same length and t, so its term is this one negated, bit
 * for bit: each spring's square root and division are done once. */
EXPERT_CLONES
static void spring_row(const bench_expert *e, float *restrict row, int y)
{
  const size_t pl = e->plane, a0 = at(e, -2, y);
  const float *restrict px_ = e->p, *restrict py_ = px_ + pl,
              *restrict pz_ = py_ + pl;
  const float k[3] = {TC_K_STRETCH, TC_K_SHEAR, TC_K_BEND};
  const int len_row = e->n + 3, pitch = e->pitch;
  for (int f = 0; f < FWD; f++) {
    const int s = fwd_slot[f], off = slot_dy[s] * pitch + slot_dx[s];
    const float kk = k[slot_kind[s]], rest = e->rest[slot_kind[s]];
    float *restrict tx = row + 3 * f * pitch, *restrict ty = tx + pitch,
                    *restrict tz = ty + pitch;
    EXPERT_SIMD
    for (int i = 0; i < len_row; i++) {
      const size_t a = a0 + i, b = a + off;
      const float dx = px_[b] - px_[a], dy = py_[b] - py_[a],
                  dz = pz_[b] - pz_[a];
      const float len = sqrtf(dx * dx + dy * dy + dz * dz);
      const float t = kk * ((len - rest) / len);
      const int on = len > 0.0f;
      tx[i] = on ? t * dx : 0.0f;
      ty[i] = on ? t * dy : 0.0f;
      tz[i] = on ? t * dz : 0.0f;
    }
  }
}

/* Term c of forward spring f of ring row r at x (r's column 0 is x = -2). */
#define TERM(r, f, c, x) ((r)[(3 * (f) + (c)) * pitch + (x) + 2])

/* The velocity pass of one row (msocl_planes_kick): the 12 slots' terms
 * summed in slot order from the ring (rows y - 2, y - 1, y), viscous
 * damping, gravity, the table's response as selects; v is updated in
 * place, as only the point itself reads its velocity. */
EXPERT_CLONES
static void kick_row(const bench_expert *e, const float *restrict r0,
                     const float *restrict r1, const float *restrict r2,
                     int y)
{
  const size_t pl = e->plane, a0 = at(e, 0, y);
  const float *restrict px_ = e->p, *restrict py_ = px_ + pl,
              *restrict pz_ = py_ + pl;
  float *restrict vx_ = e->v, *restrict vy_ = vx_ + pl,
        *restrict vz_ = vy_ + pl;
  const float dt = e->dt, im = e->inv_mass, c = e->viscous;
  const int n = e->n, pitch = e->pitch;
  EXPERT_SIMD
  for (int x = 0; x < n; x++) {
    const size_t a = a0 + x;
    const float px = px_[a], py = py_[a], pz = pz_[a];
    const float vx = vx_[a], vy = vy_[a], vz = vz_[a];
    float f3[3];
    EXPERT_UNROLL
    for (int q = 0; q < 3; q++) {
      /* slots 0..11; r2 is row y, r1 y - 1, r0 y - 2; forward index f:
       * 0 right, 1 above, 2 above-left, 3 above-right, 4 bend right,
       * 5 bend above */
      float g = 0.0f;
      g += -TERM(r1, 1, q, x);
      g += -TERM(r2, 0, q, x - 1);
      g += TERM(r2, 0, q, x);
      g += TERM(r2, 1, q, x);
      g += -TERM(r1, 3, q, x - 1);
      g += -TERM(r1, 2, q, x + 1);
      g += TERM(r2, 2, q, x);
      g += TERM(r2, 3, q, x);
      g += -TERM(r0, 5, q, x);
      g += -TERM(r2, 4, q, x - 2);
      g += TERM(r2, 4, q, x);
      g += TERM(r2, 5, q, x);
      f3[q] = g;
    }
    float fx = f3[0], fy = f3[1], fz = f3[2];
    fx = fx - c * vx;
    fy = fy - c * vy;
    fz = fz - c * vz;
    float ux = vx + dt * (fx * im + 0.0f);
    float uy = vy + dt * (fy * im + TC_GRAVITY);
    float uz = vz + dt * (fz * im + 0.0f);
    /* the table at the origin (msocl_planes_gap, msocl_respond) */
    const float rx = px - 0.0f, rz = pz - 0.0f;
    const float rr = sqrtf(rx * rx + rz * rz);
    const float gside = rr - TC_RADIUS, gtop = py - 0.0f;
    const int top = gtop >= gside || !(rr > 0.0f);
    const float nx = top ? 0.0f : rx / rr, ny = top ? 1.0f : 0.0f,
                nz = top ? 0.0f : rz / rr, g = top ? gtop : gside;
    const float fr = 1.0f * TC_FRICTION;
    const float vn = ux * nx + uy * ny + uz * nz;
    const float lim = -g / dt;
    float hx = ux + (lim - vn) * nx, hy = uy + (lim - vn) * ny,
          hz = uz + (lim - vn) * nz;
    hx = hx - fr * (hx - lim * nx);
    hy = hy - fr * (hy - lim * ny);
    hz = hz - fr * (hz - lim * nz);
    const int hit = vn < lim;
    vx_[a] = hit ? hx : ux;
    vy_[a] = hit ? hy : uy;
    vz_[a] = hit ? hz : uz;
  }
}

/* The position pass of one row, by its new velocity. */
EXPERT_CLONES
static void drift_row(const bench_expert *e, int y)
{
  const size_t pl = e->plane, a0 = at(e, 0, y);
  float *restrict p = e->p;
  const float *restrict v = e->v;
  const float dt = e->dt;
  const int n = e->n;
  for (int c = 0; c < 3; c++) {
    float *restrict q = p + c * pl + a0;
    const float *restrict w = v + c * pl + a0;
    EXPERT_SIMD
    for (int x = 0; x < n; x++)
      q[x] = q[x] + dt * w[x];
  }
}

/* Rows r0..r1-1 of one step. Row y's old positions are read by the
 * spring terms of rows y - 2..y and by its own kick, all done once row y
 * has kicked, so it moves at once; but the first two and last two rows of
 * a block are also read by the neighbouring blocks' spring terms, and move
 * only after every block has kicked (the caller's barrier, then
 * drift_edges). */
static void sweep_block(const bench_expert *e, int id, int r0, int r1)
{
  const size_t size = (size_t)FWD * 3 * e->pitch;
  float *ring = e->terms + (size_t)id * RING * size;
#define RING_ROW(y) (ring + (size_t)(((y) + RING) % RING) * size)
  /* the rows below the block: its first rows' backward springs */
  spring_row(e, RING_ROW(r0 - 2), r0 - 2);
  spring_row(e, RING_ROW(r0 - 1), r0 - 1);
  for (int y = r0; y < r1; y++) {
    spring_row(e, RING_ROW(y), y);
    kick_row(e, RING_ROW(y - 2), RING_ROW(y - 1), RING_ROW(y), y);
    if (y >= r0 + 2 && y < r1 - 2)
      drift_row(e, y);
  }
}

static void drift_edges(const bench_expert *e, int r0, int r1)
{
  for (int y = r0; y < r1; y++)
    if (y < r0 + 2 || y >= r1 - 2)
      drift_row(e, y);
}

void bench_expert_step(bench_expert *e, int steps)
{
#ifdef _OPENMP
#pragma omp parallel num_threads(e->threads)
  {
    const int nt = omp_get_num_threads(), id = omp_get_thread_num();
    const int r0 = (int)((long long)e->n * id / nt),
              r1 = (int)((long long)e->n * (id + 1) / nt);
    for (int t = 0; t < steps; t++) {
      sweep_block(e, id, r0, r1);
#pragma omp barrier
      drift_edges(e, r0, r1);
#pragma omp barrier
    }
  }
#else
  for (int t = 0; t < steps; t++) {
    sweep_block(e, 0, 0, e->n);
    drift_edges(e, 0, e->n);
  }
#endif
}

const float *bench_expert_positions(const bench_expert *e)
{
  const int n = e->n;
  for (int y = 0; y < n; y++)
    for (int x = 0; x < n; x++)
      for (int c = 0; c < 3; c++)
        e->xyz[3 * ((size_t)y * n + x) + c] = e->p[c * e->plane + at(e, x, y)];
  return e->xyz;
}

int bench_expert_threads(void)
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

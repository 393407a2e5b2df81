/* The tablecloth as an expert would write it in C for a CPU: the yardstick
 * of issue 15. Struct of arrays (x, y, z planes of floats for position and
 * velocity), every row padded by two points on each side so that the 12
 * neighbours of the GRID layout sit at fixed offsets, symplectic Euler's
 * two passes fused into one sweep over the rows, OpenMP over blocks of
 * rows, the inner loop over a row written for the vectorizer.
 *
 * Same arithmetic, slot order and collision response per point as GRID in
 * planes (kernels/planes.cl) in PRECISE math, so with no contraction of
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
};

/* The 12 slots of kernels/common.cl's cloth grid, in its order: stretch
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
  /* rows start 64-byte aligned */
  e->pitch = (n + 4 + 15) / 16 * 16;
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
  if (!e->p || !e->v || !e->xyz) {
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
  free(e);
}

/* The velocity pass of one row (msocl_planes_kick): spring forces slot by
 * slot, viscous damping, gravity, the table's response as selects; v is
 * updated in place, as only the point itself reads its velocity. */
EXPERT_CLONES
static void kick_row(const bench_expert *e, int y)
{
  const size_t pl = e->plane, a0 = at(e, 0, y);
  const float *restrict px_ = e->p, *restrict py_ = px_ + pl,
              *restrict pz_ = py_ + pl;
  float *restrict vx_ = e->v, *restrict vy_ = vx_ + pl,
        *restrict vz_ = vy_ + pl;
  const float dt = e->dt, im = e->inv_mass, c = e->viscous;
  const float k[3] = {TC_K_STRETCH, TC_K_SHEAR, TC_K_BEND};
  int off[12];
  float kk[12], rest[12];
  for (int s = 0; s < 12; s++) {
    off[s] = slot_dy[s] * e->pitch + slot_dx[s];
    kk[s] = k[slot_kind[s]];
    rest[s] = e->rest[slot_kind[s]];
  }
  const int n = e->n;
  EXPERT_SIMD
  for (int x = 0; x < n; x++) {
    const size_t a = a0 + x;
    const float px = px_[a], py = py_[a], pz = pz_[a];
    const float vx = vx_[a], vy = vy_[a], vz = vz_[a];
    float fx = 0.0f, fy = 0.0f, fz = 0.0f;
    EXPERT_UNROLL
    for (int s = 0; s < 12; s++) {
      const size_t b = a + off[s];
      const float dx = px_[b] - px, dy = py_[b] - py, dz = pz_[b] - pz;
      const float len = sqrtf(dx * dx + dy * dy + dz * dz);
      const float t = kk[s] * ((len - rest[s]) / len);
      const int on = len > 0.0f;
      fx += on ? t * dx : 0.0f;
      fy += on ? t * dy : 0.0f;
      fz += on ? t * dz : 0.0f;
    }
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

/* Rows r0..r1-1 of one step: row y's old positions are read by rows y-2..
 * y+2, so it moves two rows behind the kicks; a block's first two and last
 * two rows are also read by its neighbours' blocks, and move only after
 * every block has kicked (the caller's barrier, then drift_edges). */
static void sweep_block(const bench_expert *e, int r0, int r1)
{
  for (int y = r0; y < r1; y++) {
    kick_row(e, y);
    if (y - 2 >= r0 + 2 && y - 2 < r1 - 2)
      drift_row(e, y - 2);
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
#pragma omp parallel
  {
    const int nt = omp_get_num_threads(), id = omp_get_thread_num();
    const int r0 = (int)((long long)e->n * id / nt),
              r1 = (int)((long long)e->n * (id + 1) / nt);
    for (int t = 0; t < steps; t++) {
      sweep_block(e, r0, r1);
#pragma omp barrier
      drift_edges(e, r0, r1);
#pragma omp barrier
    }
  }
#else
  for (int t = 0; t < steps; t++) {
    sweep_block(e, 0, e->n);
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

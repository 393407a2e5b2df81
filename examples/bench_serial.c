/* The paper's Algorithm 1, the CPU baseline of its Table 1, as plain serial
 * C: a loop over the springs adds each spring's force to both of its ends,
 * then a loop over the points adds gravity and viscous damping, updates the
 * velocity, answers the table by changing the velocity, and moves the
 * point. Same scene, springs, arithmetic order per point and collision
 * response as the library's kernels (kernels/planes.h), single precision. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct spring {
  int i, j;
  float rest, k;
};

struct bench_serial {
  int n; /* points */
  float dt, inv_mass, viscous;
  float *pos, *vel, *force; /* 3 floats a point */
  struct spring *sp;
  int ns;
};

/* Every spring of a kind rests at the grid's spacing for that kind (as
 * lib/model/model_cloth.c does): h for stretch, h sqrt 2 for shear, 2h for
 * bend. */
static void push(bench_serial *s, int i, int j, float k, float rest)
{
  struct spring *e = &s->sp[s->ns++];
  e->i = i;
  e->j = j;
  e->rest = rest;
  e->k = k;
}

void bench_tc_rests(int n, float rest[3])
{
  const double h = 1.0 / (n - 1);
  rest[0] = (float)h;
  rest[1] = (float)sqrt(2.0 * h * h);
  rest[2] = (float)(2 * h);
}

/* The grid of lib/model/model_cloth.c: point (i, j) at origin + i/(n-1) z +
 * j/(n-1) x, stretch, shear and bend springs. */
static void build(bench_serial *s, int n)
{
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double a = (double)i / (n - 1), b = (double)j / (n - 1);
      float *p = s->pos + 3 * (j * n + i);
      p[0] = (float)(-0.5 + b);
      p[1] = TC_HEIGHT;
      p[2] = (float)(-0.5 + a);
    }
  float rest[3];
  bench_tc_rests(n, rest);
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      if (i + 1 < n) push(s, j * n + i, j * n + i + 1, TC_K_STRETCH, rest[0]);
      if (j + 1 < n) push(s, j * n + i, (j + 1) * n + i, TC_K_STRETCH, rest[0]);
    }
  for (int j = 0; j + 1 < n; j++)
    for (int i = 0; i + 1 < n; i++) {
      push(s, j * n + i, (j + 1) * n + i + 1, TC_K_SHEAR, rest[1]);
      push(s, j * n + i + 1, (j + 1) * n + i, TC_K_SHEAR, rest[1]);
    }
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      if (i + 2 < n) push(s, j * n + i, j * n + i + 2, TC_K_BEND, rest[2]);
      if (j + 2 < n) push(s, j * n + i, (j + 2) * n + i, TC_K_BEND, rest[2]);
    }
}

int bench_serial_create(bench_serial **out, int n, float dt)
{
  *out = NULL;
  if (n < 3)
    return MSOCL_ERR_BAD_COUNT;
  bench_serial *s = calloc(1, sizeof *s);
  if (!s)
    return MSOCL_ERR_NO_MEMORY;
  size_t np = (size_t)n * n;
  size_t most = 6 * np; /* 2 stretch + 2 shear + 2 bend a point at most */
  s->n = n * n;
  s->dt = dt;
  float m = TC_MASS / (float)s->n;
  s->inv_mass = 1.0f / m;
  s->viscous = TC_VISCOUS_PER_MASS * m;
  s->pos = malloc(3 * np * sizeof *s->pos);
  s->vel = calloc(3 * np, sizeof *s->vel);
  s->force = malloc(3 * np * sizeof *s->force);
  s->sp = malloc(most * sizeof *s->sp);
  if (!s->pos || !s->vel || !s->force || !s->sp) {
    bench_serial_destroy(s);
    return MSOCL_ERR_NO_MEMORY;
  }
  build(s, n);
  *out = s;
  return MSOCL_OK;
}

void bench_serial_destroy(bench_serial *s)
{
  if (!s)
    return;
  free(s->pos);
  free(s->vel);
  free(s->force);
  free(s->sp);
  free(s);
}

const float *bench_serial_positions(const bench_serial *s)
{
  return s->pos;
}

/* msocl_respond() with the table's gap and normal: raise the normal
 * velocity to at least -gap/dt, then friction scales away that fraction of
 * the tangential velocity. */
static void respond(const float *p, float *v, float dt)
{
  float dx = p[0], dz = p[2];
  float rr = sqrtf(dx * dx + dz * dz);
  float gside = rr - TC_RADIUS, gtop = p[1], g, n[3] = {0.0f, 1.0f, 0.0f};
  if (gtop >= gside || !(rr > 0.0f)) {
    g = gtop;
  } else {
    n[0] = dx / rr;
    n[1] = 0.0f;
    n[2] = dz / rr;
    g = gside;
  }
  float vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  float lim = -g / dt;
  if (vn < lim) {
    for (int c = 0; c < 3; c++)
      v[c] = v[c] + (lim - vn) * n[c];
    for (int c = 0; c < 3; c++)
      v[c] = v[c] - TC_FRICTION * (v[c] - lim * n[c]);
  }
}

void bench_serial_step(bench_serial *s, int steps)
{
  const float dt = s->dt, im = s->inv_mass, c = s->viscous;
  float *restrict p = s->pos, *restrict v = s->vel, *restrict f = s->force;
  for (int t = 0; t < steps; t++) {
    memset(f, 0, 3 * (size_t)s->n * sizeof *f);
    /* For each spring: internal forces, added to both ends. */
    for (int e = 0; e < s->ns; e++) {
      const struct spring *sp = &s->sp[e];
      float *pi = p + 3 * sp->i, *pj = p + 3 * sp->j;
      float d0 = pj[0] - pi[0], d1 = pj[1] - pi[1], d2 = pj[2] - pi[2];
      float len = sqrtf(d0 * d0 + d1 * d1 + d2 * d2);
      if (!(len > 0.0f))
        continue;
      float k = sp->k * ((len - sp->rest) / len);
      float *fi = f + 3 * sp->i, *fj = f + 3 * sp->j;
      fi[0] += k * d0; fi[1] += k * d1; fi[2] += k * d2;
      fj[0] -= k * d0; fj[1] -= k * d1; fj[2] -= k * d2;
    }
    /* For each mass point: external forces, velocity, collision response
     * (modifies the velocity), new position. */
    for (int i = 0; i < s->n; i++) {
      float *fi = f + 3 * i, *vi = v + 3 * i, *pi = p + 3 * i;
      const float g[3] = {0.0f, TC_GRAVITY, 0.0f};
      for (int a = 0; a < 3; a++)
        vi[a] = vi[a] + dt * ((fi[a] - c * vi[a]) * im + g[a]);
      respond(pi, vi, dt);
      for (int a = 0; a < 3; a++)
        pi[a] = pi[a] + dt * vi[a];
    }
  }
}

/* Wind in the planes engine (kernels/wind.cl): the triangles' corners as
 * plane addresses, each point's corners in triangle order, and the pass
 * that runs before each step while the wind blows. */
#include "config.h"
#include "planes.h"

#include <stdlib.h>
#include <string.h>

#define TRY MSOCL__TRY

/* Whether the model's triangles are the cloth builder's on GRID, in its
 * order (model_cloth.c add_triangles): then kernels/wind.cl's quad kernels
 * read the corners at fixed offsets. */
static int quads(const msocl__engine *s, const msocl_model *m)
{
  if (s->lay.kind != MSOCL_LAYOUT_GRID || s->lay.grid_nz > 0)
    return 0;
  const int nx = s->lay.grid_nx, ny = s->lay.grid_ny;
  if (m->nt != 2 * (nx - 1) * (ny - 1))
    return 0;
  const int *c = m->tri;
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++, c += 6) {
      const int p = j * nx + i;
      const int want[6] = {p, p + 1, p + nx + 1, p, p + nx + 1, p + nx};
      for (int k = 0; k < 6; k++)
        if (c[k] != want[k])
          return 0;
    }
  return 1;
}

int msocl__wind_create(msocl__engine *s, const msocl_model *m, cl_program prog)
{
  if (m->nt == 0)
    return MSOCL_OK;
  s->wind_host = malloc(3 * (size_t)m->nt * sizeof *s->wind_host);
  if (!s->wind_host)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "wind's triangles");
  memcpy(s->wind_host, m->tri, 3 * (size_t)m->nt * sizeof *s->wind_host);
  s->wind_ntri = m->nt;
  const char *names[5] = {"msocl_wind_triangles", "msocl_wind_points",
                          "msocl_wind_spill", "msocl_wind_quads",
                          "msocl_wind_quad_points"};
  s->wind_quads = quads(s, m);
  for (int q = s->wind_quads ? 3 : 0; q < (s->wind_quads ? 5 : 3); q++)
    TRY(msocl__kernel_make(s->dev, prog, names[q], &s->wind_k[q]));
  return MSOCL_OK;
}

/* The wind kernels' arguments that stay (by name, where each has them):
 * the planes' shape, the tables, nt triangles (whole 64s) of which
 * wind_ntri are the model's, nspill points listed for the spill kernel. */
static int fixed_args(msocl__engine *s, int nt, int nspill)
{
  const struct msocl__named fixed[] = {
      {"aux", sizeof s->pl_aux, &s->pl_aux},
      {"dt", sizeof(float), &s->o.dt},
      {"n", sizeof(int), &s->n},
      {"ny", sizeof(int), &s->lay.grid_ny},
      {"third", sizeof s->wind_third, &s->wind_third},
      {"cell", sizeof s->wind_third, &s->wind_third},
      {"tri", sizeof s->wind_tri, &s->wind_tri},
      {"slot", sizeof s->wind_slot, &s->wind_slot},
      {"tri_off", sizeof s->tri_off, &s->tri_off},
      {"corner", sizeof s->wind_corner, &s->wind_corner},
      {"list", sizeof s->wind_list, &s->wind_list},
      {"ntri", sizeof nt, &nt},
      {"nreal", sizeof(int), &s->wind_ntri},
      {"nspill", sizeof nspill, &nspill}};
  for (int q = 0; q < 5; q++)
    if (s->wind_k[q]) {
      TRY(msocl__args_named(s, s->wind_k[q], fixed,
                            (int)(sizeof fixed / sizeof fixed[0])));
      TRY(msocl__pl_shape(s, s->wind_k[q]));
    }
  return MSOCL_OK;
}

/* The corners as addresses (a zero-force triangle, all corners at 0, at
 * index wind_ntri and after it up to a whole 64), each point's triangles
 * in its slots (in triangle order, as state.c fills tri_off's CSR), the
 * points with more listed for the spill kernel, and the fixed arguments;
 * once, at the first wind. */
/* The quads' planes (zero, so the padding adds nothing) and the quad
 * kernels' fixed arguments. */
static int quad_buffers(msocl__engine *s)
{
  int rc = MSOCL_OK;
  const size_t bytes = 6 * (size_t)s->pl_plane * sizeof(float);
  s->wind_third = msocl__buffer(s->dev, CL_MEM_READ_WRITE, bytes, NULL,
                                "wind's quads", &rc);
  TRY(rc);
  const float zero = 0.0f;
  MSOCL__CL(clEnqueueFillBuffer(s->dev->queue, s->wind_third, &zero,
                                sizeof zero, 0, bytes, 0, NULL, NULL));
  return fixed_args(s, 0, 0);
}

enum { SLOTS = 8 };
static int buffers(msocl__engine *s)
{
  if (s->wind_quads)
    return quad_buffers(s);
  const int n = s->n, nt = (s->wind_ntri / 64 + 1) * 64, zero = s->wind_ntri;
  const size_t P = (size_t)s->pl_plane;
  int *tri = calloc(3 * (size_t)nt, sizeof *tri);
  int *off = calloc((size_t)n + 1, sizeof *off), *fill = calloc((size_t)n, sizeof *fill),
      *corner = malloc(3 * (size_t)nt * sizeof *corner),
      *slot = malloc(SLOTS * P * sizeof *slot), *list = malloc(2 * (size_t)n * sizeof *list);
  int rc = MSOCL_OK;
  if (!tri || !off || !fill || !corner || !slot || !list)
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "wind's tables");
  for (int t = 0; rc == MSOCL_OK && t < s->wind_ntri; t++) {
    const int *c = s->wind_host + 3 * t;
    for (int k = 0; k < 3; k++) {
      tri[k * nt + t] = msocl__pl_address(s, c[k]);
      off[c[k] + 1]++;
    }
  }
  for (int i = 0; rc == MSOCL_OK && i < n; i++)
    off[i + 1] += off[i];
  for (int t = 0; rc == MSOCL_OK && t < s->wind_ntri; t++)
    for (int k = 0; k < 3; k++) {
      const int a = s->wind_host[3 * t + k];
      corner[off[a] + fill[a]++] = t;
    }
  int nspill = 0;
  for (size_t q = 0; rc == MSOCL_OK && q < SLOTS * P; q++)
    slot[q] = zero;
  for (int i = 0; rc == MSOCL_OK && i < n; i++) {
    const int a = msocl__pl_address(s, i), count = off[i + 1] - off[i];
    if (count > SLOTS) {
      list[2 * nspill] = i;
      list[2 * nspill++ + 1] = a;
      continue;
    }
    for (int c = 0; c < count; c++)
      slot[(size_t)c * P + (size_t)a] = corner[off[i] + c];
  }
  if (rc == MSOCL_OK) {
    s->wind_tri = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                                3 * (size_t)nt * sizeof *tri, tri, "wind",
                                &rc);
    s->wind_slot = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                                 SLOTS * P * sizeof *slot, slot, "wind", &rc);
    s->wind_third = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                                  3 * (size_t)nt * sizeof(float), NULL, "wind",
                                  &rc);
    if (nspill > 0) {
      s->wind_corner = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                                     3 * (size_t)nt * sizeof *corner, corner,
                                     "wind", &rc);
      s->wind_list = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                                   2 * (size_t)nspill * sizeof *list, list,
                                   "wind", &rc);
    }
  }
  s->wind_nspill = nspill;
  free(tri);
  free(off);
  free(fill);
  free(corner);
  free(slot);
  free(list);
  TRY(rc);
  return fixed_args(s, nt, nspill);
}

int msocl__wind_set(msocl__engine *s, const float air[3], float kd, float kl)
{
  if (!air) {
    s->wind_on = 0;
    return s->pl_rows ? msocl__pl_rows_wind(s, NULL, 0.0f, 0.0f) : MSOCL_OK;
  }
  if (s->wind_ntri == 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "wind pushes on triangles, and the model has none "
                       "(msocl_model_add_triangles)");
  /* kept for a rebuild for added colliders (planes.c), which sets it again */
  for (int d = 0; d < 3; d++)
    s->wind_air[d] = air[d];
  s->wind_kd = kd;
  s->wind_kl = kl;
  if (s->wind_quads && s->pl_rows && !s->damped) {
    /* the one-sweep kernel blows it on the quads as it goes; dashpots
     * read the neighbours' velocities after the wind's kick, which the
     * sweep has not made yet, so with them wind's own passes run first */
    s->wind_on = 1;
    return msocl__pl_rows_wind(s, air, kd, kl);
  }
  if (!s->wind_third)
    TRY(buffers(s));
  const cl_float4 a = {{air[0], air[1], air[2], 0.0f}},
                  c = {{kd, kl, 0.0f, 0.0f}};
  cl_kernel k = s->wind_k[s->wind_quads ? 3 : 0];
  TRY(msocl__arg(s, k, "air", sizeof a, &a));
  TRY(msocl__arg(s, k, "coef", sizeof c, &c));
  s->wind_on = 1;
  return MSOCL_OK;
}

int msocl__wind_pass(msocl__engine *s)
{
  if (!s->wind_on || s->pl_rows_wind)
    return MSOCL_OK;
  const int set = s->pl_set;
  const size_t local[3] = {s->pl_group, 1, 1};
  const size_t *group = s->dev->info.type == MSOCL_DEVICE_CPU ? local : NULL;
  if (s->wind_quads) {
    cl_kernel q = s->wind_k[3];
    TRY(msocl__arg_mem(s, q, "p", s->pl_p[set]));
    TRY(msocl__arg_mem(s, q, "v", s->pl_v[set]));
    const size_t two[3] = {s->pl_global[0], s->pl_global[1], 2}; /* A, B */
    MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, q, 3, NULL, two, group,
                                     0, NULL, NULL));
    q = s->wind_k[4];
    TRY(msocl__arg_mem(s, q, "v", s->pl_v[set]));
    MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, q, 3, NULL, s->pl_global,
                                     group, 0, NULL, NULL));
    return MSOCL_OK;
  }
  cl_kernel k = s->wind_k[0];
  TRY(msocl__arg_mem(s, k, "p", s->pl_p[set]));
  TRY(msocl__arg_mem(s, k, "v", s->pl_v[set]));
  const size_t tris = ((size_t)s->wind_ntri / 64 + 1) * 64; /* buffers' */
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 1, NULL, &tris, NULL, 0,
                                   NULL, NULL));
  k = s->wind_k[1];
  TRY(msocl__arg_mem(s, k, "v", s->pl_v[set]));
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 3, NULL, s->pl_global,
                                   group, 0, NULL, NULL));
  if (s->wind_nspill == 0)
    return MSOCL_OK;
  k = s->wind_k[2];
  TRY(msocl__arg_mem(s, k, "v", s->pl_v[set]));
  const size_t spill = ((size_t)s->wind_nspill + 63) / 64 * 64;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 1, NULL, &spill, NULL, 0,
                                   NULL, NULL));
  return MSOCL_OK;
}

void msocl__wind_release(msocl__engine *s)
{
  for (int q = 0; q < 5; q++)
    msocl__kernel_free(s->dev, &s->wind_k[q]);
  cl_mem b[5] = {s->wind_tri, s->wind_corner, s->wind_third, s->wind_slot,
                 s->wind_list};
  for (int q = 0; q < 5; q++)
    if (b[q])
      clReleaseMemObject(b[q]);
  free(s->wind_host);
}

/* The engine's state between host and device: points of the engine's
 * numbering, three floats a point on the host, straight from and into
 * the planes (a slice of each plane over the points; a write reads the
 * slices first and keeps their padding, which the sweep fills with NaN
 * in the positions' planes). */
#include "config.h"
#include "planes.h"

#include <stdlib.h>
#include <string.h>

static cl_mem current(const msocl__engine *s, int velocities)
{
  return velocities ? s->pl_v[s->pl_set] : s->pl_p[s->pl_set];
}

/* Points [lo, hi)'s coordinates from t, the three planes' slices over
 * them (`floats` apart, the first point at 0), into out; or, out NULL,
 * from in into t: a run of points consecutive in a plane at a time (a
 * grid's row). */
static void interleave(const msocl__engine *s, int lo, int hi, float *t,
                       size_t floats, float *out, const float *in)
{
  const int grid = s->lay.kind == MSOCL_LAYOUT_GRID;
  const size_t first = (size_t)msocl__pl_address(s, lo);
  for (int i = lo; i < hi;) {
    const int nx = grid ? s->lay.grid_nx : hi, x = grid ? i % nx : 0;
    const int end = hi - i < nx - x ? hi : i + (nx - x);
    const size_t a = (size_t)msocl__pl_address(s, i) - first;
    for (int c = 0; c < 3; c++) {
      float *q = t + c * floats + a;
      const size_t at = 3 * (size_t)(i - lo) + (size_t)c;
      if (out)
        for (int j = 0; j < end - i; j++)
          out[at + 3 * (size_t)j] = q[j];
      else
        for (int j = 0; j < end - i; j++)
          q[j] = in[at + 3 * (size_t)j];
    }
    i = end;
  }
}

/* Points [lo, hi) of plane set b: each plane's slice into the engine's
 * host scratch (*t, `floats` a plane), or out of it. */
static int slices(msocl__engine *s, cl_mem b, int write, int lo, int hi,
                  float **t, size_t *floats)
{
  size_t off[3], len;
  msocl__exchange_slices(s, lo, hi, off, &len);
  *floats = len / sizeof(float);
  if (3 * *floats > s->host_cap) {
    float *grown = realloc(s->host, 3 * len);
    if (!grown)
      return msocl__fail(MSOCL_ERR_NO_MEMORY, "state of %d points",
                         hi - lo);
    s->host = grown;
    s->host_cap = 3 * *floats;
  }
  *t = s->host;
  for (int c = 0; c < 3; c++)
    MSOCL__CL(write ? clEnqueueWriteBuffer(s->dev->queue, b, CL_FALSE,
                                           off[c], len, *t + c * *floats, 0,
                                           NULL, NULL)
                    : clEnqueueReadBuffer(s->dev->queue, b, CL_FALSE, off[c],
                                          len, *t + c * *floats, 0, NULL,
                                          NULL));
  MSOCL__CL(clFinish(s->dev->queue));
  return MSOCL_OK;
}

int msocl__state_read(msocl__engine *s, int velocities, int lo, int hi,
                      float *xyz)
{
  if (lo >= hi)
    return MSOCL_OK;
  float *t;
  size_t floats;
  MSOCL__TRY(slices(s, current(s, velocities), 0, lo, hi, &t, &floats));
  interleave(s, lo, hi, t, floats, xyz, NULL);
  return MSOCL_OK;
}

int msocl__state_write(msocl__engine *s, int velocities, int lo, int hi,
                       const float *xyz)
{
  if (lo >= hi)
    return MSOCL_OK;
  /* the slices read first: their padding stays as it is */
  const cl_mem b = current(s, velocities);
  float *t;
  size_t floats;
  MSOCL__TRY(slices(s, b, 0, lo, hi, &t, &floats));
  interleave(s, lo, hi, t, floats, NULL, xyz);
  return slices(s, b, 1, lo, hi, &t, &floats);
}

int msocl__state_pin(msocl__engine *s, int k, int pinned)
{
  /* static: the write needs no wait, however many points a call pins */
  static const float flag[2] = {0.0f, 1.0f};
  const size_t at = (size_t)s->pl_plane + (size_t)msocl__pl_address(s, k);
  MSOCL__CL(clEnqueueWriteBuffer(s->dev->queue, s->pl_aux, CL_FALSE,
                                 at * sizeof *flag, sizeof *flag,
                                 &flag[pinned != 0], 0, NULL, NULL));
  return MSOCL_OK;
}

/* The normals' lists: each triangle (a, b, c) lists (b, c) at a, (c, a)
 * at b, (a, b) at c - the same winding at every corner - as where b and
 * c sit in a plane; a point's list starts at tri_off (wind's spill reads
 * that too). */
static int normals_lists(msocl__engine *s, const msocl_model *m)
{
  const size_t n = (size_t)m->n;
  int *off = calloc(n + 1, sizeof *off), *fill = calloc(n, sizeof *fill);
  cl_int *bc = malloc((size_t)(2 * 3 * m->nt + 2) * sizeof *bc);
  int rc = off && fill && bc ? MSOCL_OK
                             : msocl__fail(MSOCL_ERR_NO_MEMORY,
                                           "the normals' triangle lists");
  for (int t = 0; rc == MSOCL_OK && t < 3 * m->nt; t++)
    off[m->tri[t] + 1]++;
  for (size_t i = 0; rc == MSOCL_OK && i < n; i++)
    off[i + 1] += off[i];
  for (int t = 0; rc == MSOCL_OK && t < m->nt; t++)
    for (int k = 0; k < 3; k++) {
      const int a = m->tri[3 * t + k], at = off[a] + fill[a]++;
      bc[2 * at] = msocl__pl_address(s, m->tri[3 * t + (k + 1) % 3]);
      bc[2 * at + 1] = msocl__pl_address(s, m->tri[3 * t + (k + 2) % 3]);
    }
  if (rc == MSOCL_OK) {
    s->tri_off = msocl__buffer(s->dev, CL_MEM_READ_ONLY, (n + 1) * sizeof *off,
                               off, "the normals' lists", &rc);
    s->tri_ab = msocl__buffer(s->dev, CL_MEM_READ_ONLY,
                              (size_t)(2 * 3 * m->nt + 2) * sizeof *bc, bc,
                              "the normals' lists", &rc);
    s->normal = msocl__buffer(s->dev, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float),
                              NULL, "the normals", &rc);
  }
  free(off);
  free(fill);
  free(bc);
  return rc;
}

int msocl__state_init(msocl__engine *s, const msocl_model *m)
{
  MSOCL__TRY(normals_lists(s, m));
  const size_t plane = (size_t)s->pl_plane;
  float *aux = calloc(2 * plane, sizeof *aux);
  if (!aux)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "the points' masses and pins");
  for (int i = 0; i < m->n; i++) {
    const size_t a = (size_t)msocl__pl_address(s, i);
    aux[a] = s->inv_host[i];
    aux[plane + a] = m->pinned[i] ? 1.0f : 0.0f;
  }
  cl_int e = clEnqueueWriteBuffer(s->dev->queue, s->pl_aux, CL_TRUE, 0,
                                  2 * plane * sizeof *aux, aux, 0, NULL,
                                  NULL);
  free(aux);
  if (e != CL_SUCCESS)
    return msocl__fail(e, "clEnqueueWriteBuffer: %s", msocl_err_name(e));
  return msocl__state_write(s, 0, 0, m->n, m->pos);
}

int msocl__state_backup(msocl__engine *s, int to_backup)
{
  const size_t bytes = 3 * (size_t)s->pl_plane * sizeof(float);
  const cl_mem st[2] = {current(s, 0), current(s, 1)},
               bk[2] = {s->backup_p, s->backup_v};
  for (int k = 0; k < 2; k++)
    MSOCL__CL(clEnqueueCopyBuffer(s->dev->queue, to_backup ? st[k] : bk[k],
                                  to_backup ? bk[k] : st[k], 0, 0, bytes, 0,
                                  NULL, NULL));
  if (!to_backup)
    msocl__planes_written(s);
  return MSOCL_OK;
}

int msocl__state_normals(msocl__engine *s, float *xyz)
{
  cl_kernel k = s->k[MSOCL__K_NORMALS];
  MSOCL__TRY(msocl__arg_mem(s, k, "p", current(s, 0)));
  MSOCL__TRY(msocl__pl_shape(s, k));
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 3, NULL, s->pl_global,
                                   NULL, 0, NULL, NULL));
  MSOCL__CL(clEnqueueReadBuffer(s->dev->queue, s->normal, CL_TRUE, 0,
                                3 * (size_t)s->n * sizeof(float), xyz, 0,
                                NULL, NULL));
  return MSOCL_OK;
}

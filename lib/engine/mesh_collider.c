/* A mesh collider's device copy (kernels/mesh_collider.cl): its vertices
 * at the call's start and end as planes, its triangles with their rims,
 * and the uniform grid over the call's swept bounds, built once per call
 * that moves it, and then only where the cloth will likely be (build):
 * the host picks origin, cell size and dims from the call's bounds and
 * the cloth's (a pass over the triangles' corners), the device counts
 * each triangle's cells, scans the counts, fills and sorts each cell's
 * list (one small read of the total between); each step only runs the
 * per-point pass, which interpolates the vertices itself. On CPU devices
 * the host's counting sort builds the same lists instead (faster there);
 * tests choose either, or check one against the other
 * (msocl__mesh_host_grid). */
#include "config.h"
#include "mesh_area.h"
#include "planes.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TRY MSOCL__TRY
/* CPUs: the search's work-items a compute unit (runs interleaved) */
#define ITEMS_PER_UNIT 8

static int host_grid = -1; /* tests: msocl__mesh_host_grid */
static int cull_mode = -1;  /* tests: msocl__mesh_cull */
static int per_point = 0;   /* tests: msocl__mesh_per_point */

void msocl__mesh_host_grid(int mode)
{
  host_grid = mode;
}

void msocl__mesh_cull(int mode)
{
  cull_mode = mode;
}

void msocl__mesh_per_point(int on)
{
  per_point = on;
}

struct msocl__mesh_dev {
  int nv, nt;            /* vertices; triangles with an area */
  float *at[2];          /* host: start and end, 3 nv interleaved */
  int *tri;              /* host: 3 nt corners */
  int moving, built;     /* end differs from start; a grid exists */
  int a;                 /* at[a], vert[a]: the start */
  int rows;              /* the kernel runs a row a work-item (CPUs) */
  float thick, friction, orient;
  cl_mem vert[2];        /* 3 planes of nv floats each */
  cl_mem dtri, drim, start, list;
  size_t start_cap, list_cap; /* ints the grid's buffers hold */
  cl_mem live;           /* the host build's triangles in the grid */
  size_t live_cap;
  int nlive;             /* ... how many, or -1: every triangle placed */
  cl_kernel bounds;      /* the cloth's bounds and move a run of points */
  cl_mem dbounds, esc;   /* its output; whether a point left the grid */
  cl_mem prev;           /* the points at the last call's start */
  float *hbounds;
  int full;              /* calls left to build the whole grid */
  int cull;              /* tests: msocl__mesh_cull's mode */
  int pending, n;        /* a grid to build at the first pass; steps */
  cl_event read;         /* ... once the cloth's bounds are read */
  size_t runs[3];        /* msocl_mesh_bounds' work-items */
  size_t items;          /* CPUs: the search's work-items */
  int culled;            /* the grid is culled to a call's cloth */
  cl_float4 lo, hi;      /* every triangle's swept bounds, with the reach */
  /* host staging for the writes, kept until the next call's (a call
   * ends with the queue finished), so the writes need not block */
  float *hvert, *hbox, *hvbox; /* the build's: triangles', vertices' bounds */
  int *hstart, *hlist, *hlive;
  size_t hstart_cap, hlist_cap, hlive_cap;
  struct msocl__device *dev; /* its kernels' */
  cl_kernel k, place;    /* the pass; the triangles over a call */
  cl_kernel count, scan_sums, scan_top, scan_out, fill, sort; /* the grid */
  cl_mem dcount, sums;   /* per cell; per chunk of cells */
  size_t count_cap, sums_cap;
  int host;              /* tests: msocl__mesh_host_grid's mode */
  cl_mem cur;            /* ... over the call: 8 float4s a triangle */
  int placed;            /* cur holds this call's (or a static mesh's) */
  cl_float4 origin;      /* the grid: origin, 1 / cell size */
  int g[3];
};

static int cmp_u64(const void *x, const void *y)
{
  const uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
  return (a > b) - (a < b);
}

static uint64_t edge_key(int i, int j)
{
  const uint32_t lo = (uint32_t)(i < j ? i : j), hi = (uint32_t)(i < j ? j : i);
  return (uint64_t)lo << 32 | hi;
}

/* Is edge (i, j) on one triangle only? keys: every edge's key, sorted. */
static int on_rim(const uint64_t *keys, size_t n, int i, int j)
{
  const uint64_t k = edge_key(i, j);
  size_t lo = 0, hi = n;
  while (lo < hi) { /* the first key >= k */
    const size_t mid = (lo + hi) / 2;
    if (keys[mid] < k)
      lo = mid + 1;
    else
      hi = mid;
  }
  return !(lo + 1 < n && keys[lo + 1] == k);
}

/* The rims of an open mesh (bits of msocl_mesh_closest's features on an
 * edge of one triangle, or a corner on such an edge); closed: every edge
 * on two triangles, then orient is the side its normals point to by the
 * sign of its volume. */
static int topology(struct msocl__mesh_dev *d, int *rim)
{
  const size_t ne = 3 * (size_t)d->nt;
  uint64_t *keys = malloc(ne * sizeof *keys);
  unsigned char *corner = calloc((size_t)d->nv, 1);
  if (!keys || !corner) {
    free(keys);
    free(corner);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "mesh collider's edges");
  }
  for (int t = 0; t < d->nt; t++)
    for (int c = 0; c < 3; c++)
      keys[3 * t + c] = edge_key(d->tri[3 * t + c], d->tri[3 * t + (c + 1) % 3]);
  qsort(keys, ne, sizeof *keys, cmp_u64);
  int open = 0;
  for (int t = 0; t < d->nt; t++) {
    const int *k = d->tri + 3 * t;
    rim[t] = 0;
    for (int c = 0; c < 3; c++)
      if (on_rim(keys, ne, k[c], k[(c + 1) % 3])) {
        rim[t] |= 1 << c; /* ab 1, bc 2, ca 4 */
        corner[k[c]] = corner[k[(c + 1) % 3]] = 1;
        open = 1;
      }
  }
  for (int t = 0; t < d->nt; t++)
    for (int c = 0; c < 3; c++)
      if (corner[d->tri[3 * t + c]])
        rim[t] |= 8 << c;
  double vol = 0;
  for (int t = 0; !open && t < d->nt; t++) {
    const float *a = d->at[0] + 3 * d->tri[3 * t],
                *b = d->at[0] + 3 * d->tri[3 * t + 1],
                *c = d->at[0] + 3 * d->tri[3 * t + 2];
    vol += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
           (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
           (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
  }
  d->orient = open ? 0.0f : vol >= 0 ? 1.0f : -1.0f;
  free(keys);
  free(corner);
  return MSOCL_OK;
}

/* Vertices as three planes, for the device. */
static void to_planes(const struct msocl__mesh_dev *d, const float *xyz,
                      float *pl)
{
  for (int i = 0; i < d->nv; i++)
    for (int c = 0; c < 3; c++)
      pl[(size_t)c * d->nv + i] = xyz[3 * i + c];
}

static int upload(msocl__engine *s, struct msocl__mesh_dev *d, int which)
{
  to_planes(d, d->at[which], d->hvert);
  MSOCL__CL(clEnqueueWriteBuffer(s->dev->queue, d->vert[which], CL_FALSE, 0,
                                 3 * (size_t)d->nv * sizeof *d->hvert,
                                 d->hvert, 0, NULL, NULL));
  return MSOCL_OK;
}

int msocl__mesh_create(msocl__engine *s, const struct msocl__mesh_collider *c,
                       struct msocl__mesh_dev **out)
{
  struct msocl__mesh_dev *d = calloc(1, sizeof *d);
  if (!d)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "mesh collider");
  *out = d;
  d->dev = s->dev;
  d->nv = c->nv;
  d->thick = c->thickness;
  d->host = host_grid;
  d->cull = cull_mode;
  d->friction = c->friction;
  const size_t nv3 = 3 * (size_t)c->nv;
  d->at[0] = malloc(nv3 * sizeof(float));
  d->at[1] = malloc(nv3 * sizeof(float));
  d->hvert = malloc(nv3 * sizeof(float));
  d->hvbox = malloc(2 * nv3 * sizeof(float));
  d->hbox = malloc(6 * (size_t)c->nt * sizeof(float));
  d->tri = malloc(3 * (size_t)c->nt * sizeof *d->tri);
  int *rim = malloc((size_t)c->nt * sizeof *rim);
  int *planes = malloc(3 * (size_t)c->nt * sizeof *planes);
  int rc = MSOCL_OK;
  if (!d->at[0] || !d->at[1] || !d->hvert || !d->hvbox || !d->hbox ||
      !d->tri || !rim || !planes)
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "mesh collider");
  if (rc == MSOCL_OK) {
    memcpy(d->at[0], c->verts, nv3 * sizeof(float));
    memcpy(d->at[1], c->verts, nv3 * sizeof(float));
    for (int t = 0; t < c->nt; t++) {
      const int *k = c->tris + 3 * t;
      if (k[0] != k[1] && k[1] != k[2] && k[0] != k[2] &&
          msocl__tri_has_area(c->verts, k)) {
        memcpy(d->tri + 3 * d->nt, k, 3 * sizeof *k);
        d->nt++;
      }
    }
    rc = topology(d, rim);
  }
  for (int t = 0; rc == MSOCL_OK && t < d->nt; t++)
    for (int q = 0; q < 3; q++)
      planes[(size_t)q * d->nt + t] = d->tri[3 * t + q];
  if (rc == MSOCL_OK) {
    d->dtri = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                            3 * (size_t)d->nt * sizeof(int), planes,
                            "a mesh collider's triangles", &rc);
    d->drim = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                            (size_t)d->nt * sizeof(int), rim,
                            "a mesh collider's rims", &rc);
    d->vert[0] = msocl__buffer(s->dev, CL_MEM_READ_WRITE, nv3 * sizeof(float),
                               NULL, "a mesh collider's vertices", &rc);
    d->vert[1] = msocl__buffer(s->dev, CL_MEM_READ_WRITE, nv3 * sizeof(float),
                               NULL, "a mesh collider's vertices", &rc);
  }
  free(rim);
  free(planes);
  if (rc == MSOCL_OK) /* one staging area: each write finished in turn */
    rc = upload(s, d, 0);
  if (rc == MSOCL_OK && clFinish(s->dev->queue) != CL_SUCCESS)
    rc = msocl__fail(MSOCL_ERR_INVALID_ARG, "mesh collider's vertices");
  if (rc == MSOCL_OK)
    rc = upload(s, d, 1);
  if (rc == MSOCL_OK && clFinish(s->dev->queue) != CL_SUCCESS)
    rc = msocl__fail(MSOCL_ERR_INVALID_ARG, "mesh collider's vertices");
  TRY(rc);
  d->rows = s->dev->info.type == MSOCL_DEVICE_CPU && !per_point;
  const char *name = d->rows ? "msocl_mesh_collide_rows" : "msocl_mesh_collide";
  TRY(msocl__kernel_make(s->dev, s->prog, name, &d->k));
  TRY(msocl__kernel_make(s->dev, s->prog, "msocl_mesh_place", &d->place));
  int rc2 = MSOCL_OK;
  d->cur = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                         32 * (size_t)d->nt * sizeof(float), NULL,
                         "a mesh collider's placed triangles", &rc2);
  TRY(rc2);
  TRY(msocl__arg_mem(s, d->place, "tri", d->dtri));
  TRY(msocl__arg_mem(s, d->place, "cur", d->cur));
  TRY(msocl__arg_int(s, d->place, "nv", d->nv));
  TRY(msocl__arg_int(s, d->place, "nt", d->nt));
  TRY(msocl__arg_mem(s, d->place, "live", d->dtri)); /* a list to come */
  TRY(msocl__arg_int(s, d->place, "nlive", -1));
  d->nlive = -1;
  TRY(msocl__arg_mem(s, d->k, "cur", d->cur));
  const cl_int zero = 0;
  d->esc = msocl__buffer(s->dev, CL_MEM_READ_WRITE, sizeof zero, &zero,
                         "a mesh collider's flag", &rc2);
  TRY(rc2);
  TRY(msocl__arg_mem(s, d->k, "esc", d->esc));
  { /* CPUs: work-items a compute unit, each taking every B-th run */
    const cl_uint units = s->dev->info.compute_units;
    const int runs = (int)(((s->pl_global[0] + 255) / 256) *
                           s->pl_global[1] * s->pl_global[2]);
    d->items = ITEMS_PER_UNIT * (size_t)(units ? units : 1);
    if (d->items > (size_t)runs)
      d->items = (size_t)runs;
    TRY(msocl__arg_int(s, d->k, "rows_y", (int)s->pl_global[1]));
    TRY(msocl__arg_int(s, d->k, "runs", runs));
  }
  TRY(msocl__kernel_make(s->dev, s->prog, "msocl_mesh_bounds", &d->bounds));
  TRY(msocl__arg_mem(s, d->bounds, "aux", s->pl_aux));
  TRY(msocl__pl_shape(s, d->bounds));
  d->runs[0] = (s->pl_global[0] + 255) / 256;
  d->runs[1] = s->pl_global[1];
  d->runs[2] = s->pl_global[2];
  const size_t runs = d->runs[0] * d->runs[1] * d->runs[2];
  d->hbounds = malloc(8 * runs * sizeof *d->hbounds);
  if (!d->hbounds)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "mesh collider");
  d->dbounds = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                             8 * runs * sizeof *d->hbounds, NULL,
                             "the cloth's bounds", &rc2);
  TRY(rc2);
  TRY(msocl__arg_mem(s, d->bounds, "esc", d->esc));
  d->prev = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                          3 * (size_t)s->pl_plane * sizeof(float), NULL,
                          "the previous positions", &rc2);
  TRY(rc2);
  const cl_float nil = 0;
  MSOCL__CL(clEnqueueFillBuffer(s->dev->queue, d->prev, &nil, sizeof nil, 0,
                                3 * (size_t)s->pl_plane * sizeof nil, 0, NULL,
                                NULL));
  TRY(msocl__arg_mem(s, d->bounds, "prev", d->prev));
  cl_kernel *grid[6] = {&d->count, &d->scan_sums, &d->scan_top,
                        &d->scan_out, &d->fill, &d->sort};
  static const char *const gname[6] = {
      "msocl_mesh_count", "msocl_mesh_scan_sums", "msocl_mesh_scan_top",
      "msocl_mesh_scan_out", "msocl_mesh_fill", "msocl_mesh_sort"};
  for (int q = 0; q < 6; q++) {
    TRY(msocl__kernel_make(s->dev, s->prog, gname[q], grid[q]));
  }
  TRY(msocl__arg_mem(s, d->k, "aux", s->pl_aux));
  TRY(msocl__arg_mem(s, d->k, "tri", d->dtri));
  TRY(msocl__arg_mem(s, d->k, "rim", d->drim));
  TRY(msocl__arg_float(s, d->k, "orient", d->orient));
  TRY(msocl__arg_float(s, d->k, "dt", s->o.dt));
  TRY(msocl__arg_int(s, d->k, "nv", d->nv));
  TRY(msocl__arg_int(s, d->k, "nt", d->nt));
  return msocl__pl_shape(s, d->k);
}

int msocl__mesh_nv(const struct msocl__mesh_dev *d)
{
  return d->nv;
}

void msocl__mesh_vertices(struct msocl__mesh_dev *d, const float *verts)
{
  memcpy(d->at[1 - d->a], verts, 3 * (size_t)d->nv * sizeof(float));
  d->moving = 1;
}

/* A buffer of at least `need` ints, grown by half again when short. */
static int room(msocl__engine *s, cl_mem *b, size_t *cap, size_t need)
{
  if (*b && *cap >= need)
    return MSOCL_OK;
  if (*b)
    clReleaseMemObject(*b);
  *cap = need + need / 2 + 64;
  int rc = MSOCL_OK;
  *b = msocl__buffer(s->dev, CL_MEM_READ_WRITE, *cap * sizeof(int), NULL,
                     "a mesh collider's grid", &rc);
  return rc;
}

/* A host array of at least `need` ints. */
static int grow(int **a, size_t *cap, size_t need)
{
  if (*a && *cap >= need)
    return MSOCL_OK;
  free(*a);
  *cap = need + need / 2 + 64;
  *a = malloc(*cap * sizeof **a);
  if (!*a) {
    *cap = 0;
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "mesh collider's grid");
  }
  return MSOCL_OK;
}

/* floor(x) clamped to [-1, g] (g a cell count, far below 2^23): x
 * clamped first so that the int conversion is exact (floorf is a libm
 * call without SSE4.1). */
static inline int floor_in(float x, float g)
{
  x = x < -2.0f ? -2.0f : x > g + 1.0f ? g + 1.0f : x;
  const int i = (int)x; /* toward zero */
  const int f = i - (x < (float)i);
  return f < -1 ? -1 : f > (int)g ? (int)g : f;
}

/* The cells a bound [lo, hi] covers along axis c, clamped to the grid,
 * and whether it misses the grid (msocl_mesh_span's float operations). */
static inline int span(const struct msocl__mesh_dev *d, int c, float lo,
                       float hi, int *a, int *b)
{
  const float o = d->origin.s[c], w = d->origin.s[3], g = (float)d->g[c];
  const int ia = floor_in((lo - o) * w, g), ib = floor_in((hi - o) * w, g);
  *a = ia < 0 ? 0 : ia >= d->g[c] ? d->g[c] - 1 : ia;
  *b = ib < 0 ? 0 : ib >= d->g[c] ? d->g[c] - 1 : ib;
  return ia >= d->g[c] || ib < 0;
}

/* Whether triangle t misses the grid: span's answer without its floors
 * (a floor is negative just where its argument is, and at least g just
 * where its argument is). */
static int misses(const struct msocl__mesh_dev *d, const float *box, int t)
{
  const float *b = box + 6 * t, w = d->origin.s[3];
  int out = 0;
  for (int c = 0; c < 3; c++)
    out |= ((b[3 + c] - d->origin.s[c]) * w < 0.0f) |
           ((b[c] - d->origin.s[c]) * w >= (float)d->g[c]);
  return out;
}

/* Triangle t's cells a[] .. b[], or 0 where it misses the grid. */
static int spans(const struct msocl__mesh_dev *d, const float *box, int t,
                 int *a, int *b)
{
  int out = 0;
  for (int c = 0; c < 3; c++)
    out |= span(d, c, box[6 * t + c], box[6 * t + 3 + c], &a[c], &b[c]);
  return !out;
}

/* The reference build on the host, a counting sort over the triangles'
 * bounds box (6 floats each), into hstart and hlist (*total entries);
 * the triangles in the grid into hlive (d->nlive). Each cell's count
 * goes to its own entry, summed into the cell's end, and the fill walks
 * the triangles backwards, each taking the slot below its cells' ends:
 * every end becomes its cell's start, the triangles in order, and no
 * second array of ends to copy. */
static int host_lists(struct msocl__mesh_dev *d, const float *box,
                      size_t *total)
{
  const size_t ncell = (size_t)d->g[0] * d->g[1] * d->g[2];
  *total = 0;
  TRY(grow(&d->hstart, &d->hstart_cap, ncell + 1));
  TRY(grow(&d->hlive, &d->hlive_cap, (size_t)d->nt));
  int *start = d->hstart;
  memset(start, 0, (ncell + 1) * sizeof *start);
  const size_t gx = (size_t)d->g[0], gxy = gx * (size_t)d->g[1];
  int a[3], b[3];
  d->nlive = 0;
  for (int t = 0; t < d->nt; t++) {
    if (misses(d, box, t))
      continue;
    spans(d, box, t, a, b);
    d->hlive[d->nlive++] = t;
    for (int z = a[2]; z <= b[2]; z++)
      for (int y = a[1]; y <= b[1]; y++)
        for (int x = a[0]; x <= b[0]; x++)
          start[(size_t)z * gxy + (size_t)y * gx + (size_t)x]++;
  }
  for (size_t q = 1; q < ncell; q++)
    start[q] += start[q - 1];
  const size_t sum = ncell ? (size_t)start[ncell - 1] : 0;
  start[ncell] = (int)sum;
  TRY(grow(&d->hlist, &d->hlist_cap, sum + 1));
  int *list = d->hlist;
  for (int i = d->nlive - 1; i >= 0; i--) {
    const int t = d->hlive[i];
    spans(d, box, t, a, b);
    for (int z = a[2]; z <= b[2]; z++)
      for (int y = a[1]; y <= b[1]; y++)
        for (int x = a[0]; x <= b[0]; x++)
          list[--start[(size_t)z * gxy + (size_t)y * gx + (size_t)x]] = t;
  }
  *total = sum;
  return MSOCL_OK;
}

/* The host's lists, uploaded. */
static int build_host(msocl__engine *s, struct msocl__mesh_dev *d,
                      const float *box)
{
  const size_t ncell = (size_t)d->g[0] * d->g[1] * d->g[2];
  size_t total;
  int rc = host_lists(d, box, &total);
  const int *start = d->hstart, *list = d->hlist;
  if (rc == MSOCL_OK)
    rc = room(s, &d->start, &d->start_cap, ncell + 1);
  if (rc == MSOCL_OK)
    rc = room(s, &d->list, &d->list_cap, total + 1);
  cl_int e = CL_SUCCESS;
  if (rc == MSOCL_OK)
    e = clEnqueueWriteBuffer(s->dev->queue, d->start, CL_FALSE, 0,
                             (ncell + 1) * sizeof *start, start, 0, NULL, NULL);
  if (rc == MSOCL_OK && e == CL_SUCCESS)
    e = clEnqueueWriteBuffer(s->dev->queue, d->list, CL_FALSE, 0,
                             (total + 1) * sizeof *list, list, 0, NULL, NULL);
  if (rc == MSOCL_OK && e == CL_SUCCESS)
    rc = room(s, &d->live, &d->live_cap, (size_t)d->nlive + 1);
  if (rc == MSOCL_OK && e == CL_SUCCESS && d->nlive > 0)
    e = clEnqueueWriteBuffer(s->dev->queue, d->live, CL_FALSE, 0,
                             (size_t)d->nlive * sizeof *d->hlive, d->hlive, 0,
                             NULL, NULL);
  if (rc == MSOCL_OK && e != CL_SUCCESS)
    rc = msocl__fail(e, "mesh collider's grid: %s", msocl_err_name(e));
  return rc;
}

/* Kernel k over n items, `run` a work-item (its argument "run", where
 * it has one). */
static int launch(msocl__engine *s, cl_kernel k, size_t n, int run)
{
  if (n == 0)
    return MSOCL_OK;
  if (msocl__kernel_has(s->dev, k, "run"))
    TRY(msocl__arg_int(s, k, "run", run));
  const size_t items = (n + run - 1) / run;
  /* runs: a group each, spread over the cores */
  const size_t global = run > 1 ? items : (items + 63) / 64 * 64, one = 1;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 1, NULL, &global,
                                   run > 1 ? &one : NULL, 0, NULL, NULL));
  return MSOCL_OK;
}

/* The per-triangle kernels' common arguments: the call's start and end
 * vertices, the triangles, the counts, the grid. */
static int span_args(msocl__engine *s, struct msocl__mesh_dev *d,
                     cl_kernel k, float reach)
{
  const cl_int4 g = {{d->g[0], d->g[1], d->g[2], 0}};
  const cl_mem vb = d->vert[d->moving ? 1 - d->a : d->a];
  const struct msocl__named args[] = {
      {"va", sizeof(cl_mem), &d->vert[d->a]},
      {"vb", sizeof vb, &vb},
      {"tri", sizeof d->dtri, &d->dtri},
      {"count", sizeof d->dcount, &d->dcount},
      {"origin", sizeof d->origin, &d->origin},
      {"g", sizeof g, &g},
      {"reach", sizeof reach, &reach},
      {"nv", sizeof d->nv, &d->nv},
      {"nt", sizeof d->nt, &d->nt}};
  for (size_t q = 0; q < sizeof args / sizeof args[0]; q++)
    TRY(msocl__arg(s, k, args[q].name, args[q].size, args[q].v));
  return MSOCL_OK;
}

/* The build on the device: counts, their scan into start, the total read
 * back to size the list, the fill, each cell's list sorted. */
static int build_dev(msocl__engine *s, struct msocl__mesh_dev *d, float reach)
{
  const size_t ncell = (size_t)d->g[0] * d->g[1] * d->g[2];
  /* chunks of about sqrt(cells): the top level runs on one work-item */
  int chunk = (int)ceil(sqrt((double)ncell));
  chunk = chunk < 64 ? 64 : chunk;
  const size_t nchunk = (ncell + chunk - 1) / chunk;
  TRY(room(s, &d->dcount, &d->count_cap, ncell));
  TRY(room(s, &d->sums, &d->sums_cap, nchunk));
  TRY(room(s, &d->start, &d->start_cap, ncell + 1));
  const cl_int zero = 0;
  cl_command_queue q = s->dev->queue;
  MSOCL__CL(clEnqueueFillBuffer(q, d->dcount, &zero, sizeof zero, 0,
                                ncell * sizeof zero, 0, NULL, NULL));
  TRY(span_args(s, d, d->count, reach));
  const int run = d->rows ? 256 : 1; /* items a work-item */
  TRY(launch(s, d->count, (size_t)d->nt, run));
  TRY(msocl__arg_mem(s, d->scan_sums, "count", d->dcount));
  TRY(msocl__arg_mem(s, d->scan_sums, "sums", d->sums));
  TRY(msocl__arg_int(s, d->scan_sums, "n", (int)ncell));
  TRY(msocl__arg_int(s, d->scan_sums, "chunk", chunk));
  TRY(launch(s, d->scan_sums, nchunk, 1));
  TRY(msocl__arg_mem(s, d->scan_top, "sums", d->sums));
  TRY(msocl__arg_int(s, d->scan_top, "m", (int)nchunk));
  const size_t one = 1;
  MSOCL__CL(clEnqueueNDRangeKernel(q, d->scan_top, 1, NULL, &one, NULL, 0,
                                   NULL, NULL));
  TRY(msocl__arg_mem(s, d->scan_out, "count", d->dcount));
  TRY(msocl__arg_mem(s, d->scan_out, "sums", d->sums));
  TRY(msocl__arg_mem(s, d->scan_out, "start", d->start));
  TRY(msocl__arg_int(s, d->scan_out, "n", (int)ncell));
  TRY(msocl__arg_int(s, d->scan_out, "chunk", chunk));
  TRY(launch(s, d->scan_out, nchunk, 1));
  cl_int total = 0;
  MSOCL__CL(clEnqueueReadBuffer(q, d->start, CL_TRUE,
                                ncell * sizeof total, sizeof total, &total, 0,
                                NULL, NULL));
  TRY(room(s, &d->list, &d->list_cap, (size_t)total + 1));
  MSOCL__CL(clEnqueueFillBuffer(q, d->dcount, &zero, sizeof zero, 0,
                                ncell * sizeof zero, 0, NULL, NULL));
  TRY(span_args(s, d, d->fill, reach));
  TRY(msocl__arg_mem(s, d->fill, "start", d->start));
  TRY(msocl__arg_mem(s, d->fill, "list", d->list));
  TRY(launch(s, d->fill, (size_t)d->nt, run));
  TRY(msocl__arg_mem(s, d->sort, "start", d->start));
  TRY(msocl__arg_mem(s, d->sort, "list", d->list));
  TRY(msocl__arg_int(s, d->sort, "ncell", (int)ncell));
  return launch(s, d->sort, ncell, run);
}

/* Tests: the device's lists read back against the host's, bitwise. */
static int verify(msocl__engine *s, struct msocl__mesh_dev *d,
                  const float *box)
{
  const size_t ncell = (size_t)d->g[0] * d->g[1] * d->g[2];
  size_t total;
  TRY(host_lists(d, box, &total));
  int *got = malloc((ncell + 1 + total) * sizeof *got);
  if (!got)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "mesh collider's grid check");
  cl_int e = clEnqueueReadBuffer(s->dev->queue, d->start, CL_TRUE, 0,
                                 (ncell + 1) * sizeof *got, got, 0, NULL,
                                 NULL);
  if (e == CL_SUCCESS && total > 0)
    e = clEnqueueReadBuffer(s->dev->queue, d->list, CL_TRUE, 0,
                            total * sizeof *got, got + ncell + 1, 0, NULL,
                            NULL);
  int rc = e == CL_SUCCESS ? MSOCL_OK
                           : msocl__fail(e, "mesh collider's grid check: %s",
                                         msocl_err_name(e));
  for (size_t q = 0; rc == MSOCL_OK && q <= ncell; q++)
    if (got[q] != d->hstart[q])
      rc = msocl__fail(MSOCL_ERR_INVALID_ARG,
                       "device grid: cell %zu starts at %d, host's at %d", q,
                       got[q], d->hstart[q]);
  for (size_t q = 0; rc == MSOCL_OK && q < total; q++)
    if (got[ncell + 1 + q] != d->hlist[q])
      rc = msocl__fail(MSOCL_ERR_INVALID_ARG,
                       "device grid: entry %zu is triangle %d, host's %d", q,
                       got[ncell + 1 + q], d->hlist[q]);
  free(got);
  return rc;
}

/* A triangle's bounds along axis c from its corners' (vb: each vertex's
 * low and high a coordinate). */
static inline void tri_axis(const float *vb, const int *k, int c, float *lo,
                            float *hi)
{
  const float *x = vb + 2 * (3 * k[0] + c), *y = vb + 2 * (3 * k[1] + c),
              *z = vb + 2 * (3 * k[2] + c);
  const float l = x[0] < y[0] ? x[0] : y[0], h = x[1] > y[1] ? x[1] : y[1];
  *lo = l < z[0] ? l : z[0];
  *hi = h > z[1] ? h : z[1];
}

/* Each triangle's bounds over the call, from start to end, grown by the
 * reach: the thickness and the mesh's largest motion a step. A point held
 * at the thickness that crosses a triangle within one step ends up at
 * most its motion less the thickness behind it, so it is seen while the
 * cloth moves less than twice the thickness a step (beside the mesh's own
 * motion). The grid spans those bounds, or where `near` (6 floats) is
 * given, only their part inside it, and holds just the triangles whose
 * bounds reach into it: every triangle a point in the grid can touch,
 * since a point in cell c lies in a triangle's bounds only if the
 * triangle's cells (the same monotone float operations) include c; a
 * point outside the grid but inside every triangle's bounds box (lo, hi)
 * searches all triangles, and one outside that box is out of every
 * triangle's reach. So `near` decides the speed, never what is seen. */
static int build(msocl__engine *s, struct msocl__mesh_dev *d, float step,
                 const float *near)
{
  const float *p0 = d->at[d->a], *p1 = d->at[1 - d->a];
  const float reach = (d->thick + step) * 1.001f;
  /* on a CPU device the host is the same cores, and its counting sort
   * beat the device build's passes (docs/PERFORMANCE.md) */
  const int mode = d->host >= 0 ? d->host : d->rows ? 1 : 0;
  float *box = mode ? d->hbox : NULL, *vb = d->hvbox;
  for (int i = 0; i < 3 * d->nv; i++) { /* each vertex's, start to end */
    vb[2 * i] = p0[i] < p1[i] ? p0[i] : p1[i];
    vb[2 * i + 1] = p0[i] > p1[i] ? p0[i] : p1[i];
  }
  /* each axis in its own scalars, the box stored once: a box assembled
   * in memory and copied out stalled on its stores (most of the loop) */
  float lx = INFINITY, ly = INFINITY, lz = INFINITY, hx = -INFINITY,
        hy = -INFINITY, hz = -INFINITY;
  double size = 0;
  for (int t = 0; t < d->nt; t++) {
    const int *k = d->tri + 3 * t;
    float l0, l1, l2, h0, h1, h2;
    tri_axis(vb, k, 0, &l0, &h0);
    tri_axis(vb, k, 1, &l1, &h1);
    tri_axis(vb, k, 2, &l2, &h2);
    size += (double)(h0 - l0);
    size += (double)(h1 - l1);
    size += (double)(h2 - l2);
    l0 -= reach, l1 -= reach, l2 -= reach;
    h0 += reach, h1 += reach, h2 += reach;
    /* (not fminf: a libm call a bound here; the bounds are finite) */
    lx = l0 < lx ? l0 : lx;
    ly = l1 < ly ? l1 : ly;
    lz = l2 < lz ? l2 : lz;
    hx = h0 > hx ? h0 : hx;
    hy = h1 > hy ? h1 : hy;
    hz = h2 > hz ? h2 : hz;
    if (box) {
      float *o = box + 6 * t;
      o[0] = l0, o[1] = l1, o[2] = l2, o[3] = h0, o[4] = h1, o[5] = h2;
    }
  }
  float lo[3] = {lx, ly, lz}, hi[3] = {hx, hy, hz};
  for (int c = 0; c < 3; c++) {
    d->lo.s[c] = lo[c];
    d->hi.s[c] = hi[c];
    if (near) {
      lo[c] = fmaxf(lo[c], near[c]);
      hi[c] = fmaxf(fminf(hi[c], near[3 + c]), lo[c]);
    }
  }
  d->lo.s[3] = d->hi.s[3] = 0.0f;
  /* cells about as wide as a triangle's swept bounds, or the reach if
   * that is more: a point near the surface then looks at the triangles
   * within about reach plus two cells of it; at most 16 cells a triangle
   * (or 2^16), 2^22 in all */
  double h = 1.5 * fmax(size / 3.0 / d->nt, (double)reach);
  double most = fmax(16.0 * d->nt, 65536.0);
  most = fmin(most, 4194304.0);
  for (;;) {
    double cells = 1;
    for (int c = 0; c < 3; c++)
      cells *= floor((double)(hi[c] - lo[c]) / h) + 1;
    if (cells <= most)
      break;
    h *= 1.1 * cbrt(cells / most);
  }
  for (int c = 0; c < 3; c++) {
    d->origin.s[c] = lo[c];
    d->g[c] = (int)floor((double)(hi[c] - lo[c]) / h) + 1;
  }
  d->origin.s[3] = (float)(1.0 / h);
  int rc = mode == 1 ? build_host(s, d, box) : build_dev(s, d, reach);
  if (rc == MSOCL_OK && mode == 2)
    rc = verify(s, d, box);
  TRY(rc);
  d->built = 1;
  d->culled = near != NULL;
  /* the host build places only its grid's triangles */
  if (mode != 1)
    d->nlive = -1;
  TRY(msocl__arg_mem(s, d->place, "live", mode == 1 ? d->live : d->dtri));
  TRY(msocl__arg_int(s, d->place, "nlive", d->nlive));
  TRY(msocl__arg_float(s, d->k, "reach2", reach * reach));
  TRY(msocl__arg(s, d->k, "lo", sizeof d->lo, &d->lo));
  TRY(msocl__arg(s, d->k, "hi", sizeof d->hi, &d->hi));
  TRY(msocl__arg_int(s, d->k, "culled", d->culled));
  TRY(msocl__arg_mem(s, d->k, "cell_start", d->start));
  TRY(msocl__arg_mem(s, d->k, "cell_tri", d->list));
  TRY(msocl__arg(s, d->k, "origin", sizeof d->origin, &d->origin));
  TRY(msocl__arg_int(s, d->k, "gx", d->g[0]));
  TRY(msocl__arg_int(s, d->k, "gy", d->g[1]));
  return msocl__arg_int(s, d->k, "gz", d->g[2]);
}

/* A queued read of the cloth's bounds, waited for and let go. */
static void drop_read(struct msocl__mesh_dev *d)
{
  if (d->read) {
    clWaitForEvents(1, &d->read);
    clReleaseEvent(d->read);
    d->read = NULL;
  }
}

/* The cloth's free points' bounds now and move since, queued for the host
 * at a moving call's end (or the next one's start, where none is), read at
 * the next moving call's first pass. */
static int cloth_bounds(msocl__engine *s, struct msocl__mesh_dev *d)
{
  drop_read(d); /* a failed call's */
  const int set = s->pl_set;
  TRY(msocl__arg_mem(s, d->bounds, "p", s->pl_p[set]));
  TRY(msocl__arg_mem(s, d->bounds, "out", d->dbounds));
  const size_t one[3] = {1, 1, 1};
  cl_command_queue q = s->dev->queue;
  MSOCL__CL(clEnqueueNDRangeKernel(q, d->bounds, 3, NULL, d->runs, one, 0,
                                   NULL, NULL));
  const size_t items = d->runs[0] * d->runs[1] * d->runs[2];
  MSOCL__CL(clEnqueueReadBuffer(q, d->dbounds, CL_FALSE, 0,
                                8 * items * sizeof *d->hbounds, d->hbounds, 0,
                                NULL, &d->read));
  return MSOCL_OK;
}

/* The box the cloth's free points will likely stay in over the call's n
 * steps (6 floats): their bounds at its start, grown by twice the most a
 * point moved over the last call (a vibrating point's speed would
 * overstate it), gravity's fall, the mesh's own travel and two reaches
 * (a push off the mesh moves a point by up to its reach and the
 * thickness); and whether a point left the last grid. Only the speed of
 * the pass depends on it (build). */
static int cloth_reach(msocl__engine *s, struct msocl__mesh_dev *d, int n,
                       float step, float *near, int *escaped)
{
  const cl_int e = clWaitForEvents(1, &d->read);
  clReleaseEvent(d->read);
  d->read = NULL;
  if (e != CL_SUCCESS)
    return msocl__fail(e, "mesh collider's cloth bounds: %s",
                       msocl_err_name(e));
  const size_t items = d->runs[0] * d->runs[1] * d->runs[2];
  float m2 = 0;
  *escaped = d->hbounds[7] != 0.0f;
  for (int c = 0; c < 3; c++) {
    near[c] = INFINITY;
    near[3 + c] = -INFINITY;
  }
  for (size_t i = 0; i < items; i++) {
    const float *b = d->hbounds + 8 * i;
    for (int c = 0; c < 3; c++) {
      near[c] = fminf(near[c], b[c]);
      near[3 + c] = fmaxf(near[3 + c], b[4 + c]);
    }
    m2 = fmaxf(m2, b[3]);
  }
  const double t = (double)n * s->o.dt;
  const double g = sqrt((double)s->gravity.s[0] * s->gravity.s[0] +
                        (double)s->gravity.s[1] * s->gravity.s[1] +
                        (double)s->gravity.s[2] * s->gravity.s[2]);
  const double reach = (double)d->thick + step;
  const float grow = d->cull == 1 ? 0.0f
                                   : (float)(2.0 * sqrt((double)m2) +
                                             g * t * t + (double)n * step +
                                             2.0 * reach);
  for (int c = 0; c < 3; c++) {
    near[c] -= grow;
    near[3 + c] += grow;
  }
  return MSOCL_OK;
}

/* The call's largest vertex motion a step. */
static float motion(const struct msocl__mesh_dev *d, int n)
{
  const float *p0 = d->at[d->a], *p1 = d->at[1 - d->a];
  double st = 0;
  for (int i = 0; i < d->nv; i++) {
    double l2 = 0;
    for (int c = 0; c < 3; c++) {
      const double e = (double)p1[3 * i + c] - p0[3 * i + c];
      l2 += e * e;
    }
    st = fmax(st, l2);
  }
  return (float)(sqrt(st) / (n > 0 ? n : 1));
}

/* A moving mesh's grid is built again each call, tight around the call's
 * swept bounds (slack for later calls would grow every point's search
 * more than it saves), at the first step's pass, so that the host builds
 * while the device runs the step; a static mesh's once, here. */
int msocl__mesh_begin(msocl__engine *s, struct msocl__mesh_dev *d, int n)
{
  /* the staging areas are free once the queue is (a failed call may
   * have left it running) */
  if (d->moving || !d->built || d->culled)
    MSOCL__CL(clFinish(s->dev->queue));
  if (d->moving)
    TRY(upload(s, d, 1 - d->a));
  if (d->moving) {
    /* the bounds the last moving call queued at its end, else now */
    if (!d->read)
      TRY(cloth_bounds(s, d));
    d->n = n;
    d->pending = 1;
    d->placed = 0; /* a static call before it placed the resting mesh */
  } else {
    drop_read(d); /* stale by the next moving call */
    if (!d->built || d->culled) /* once while it stays: whole */
      TRY(build(s, d, 0.0f, NULL));
  }
  const cl_mem a = d->vert[d->a], b = d->vert[d->moving ? 1 - d->a : d->a];
  TRY(msocl__arg_mem(s, d->place, "va", a));
  TRY(msocl__arg_mem(s, d->place, "vb", b));
  TRY(msocl__arg_mem(s, d->k, "va", a));
  return msocl__arg_mem(s, d->k, "vb", b);
}

int msocl__mesh_pass(msocl__engine *s, struct msocl__mesh_dev *d, float f0,
                     float f1)
{
  if (d->pending) { /* the step's queued: the device starts it */
    MSOCL__CL(clFlush(s->dev->queue));
    d->pending = 0;
    const float step = motion(d, d->n);
    float near[6];
    int escaped = 0;
    TRY(cloth_reach(s, d, d->n, step, near, &escaped));
    /* the first call (no move since a call before it to grow the box
     * by), and a few after a point left the grid (a slow search), build
     * the whole grid */
    if (escaped && d->cull < 0)
      d->full = 8;
    const int whole = !d->built || d->full > 0 || d->cull == 0;
    d->full -= d->full > 0;
    TRY(build(s, d, step, whole ? NULL : near));
  }
  /* the triangles over the call, once a call (a static mesh's once) */
  if (!d->placed) {
    const int m = d->nlive >= 0 ? d->nlive : d->nt;
    /* groups of 64 whatever the count: PoCL builds its code again for
     * each work-group size it picks, and it picks the count */
    const size_t tris = ((size_t)m + 63) / 64 * 64, group = 64;
    if (m > 0)
      MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, d->place, 1, NULL,
                                       &tris, &group, 0, NULL, NULL));
    d->placed = 1;
  }
  const int set = s->pl_set;
  TRY(msocl__arg_mem(s, d->k, "p", s->pl_p[set]));
  TRY(msocl__arg_mem(s, d->k, "v", s->pl_v[set]));
  TRY(msocl__arg_mem(s, d->k, "pp", s->pl_p[1 - set]));
  const cl_float4 prm = {{f0, f1, d->thick, d->friction}};
  TRY(msocl__arg(s, d->k, "prm", sizeof prm, &prm));
  if (d->rows) { /* a group a work-item, spread over cores */
    const size_t one = 1;
    MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, d->k, 1, NULL,
                                     &d->items, &one, 0, NULL, NULL));
    return MSOCL_OK;
  }
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, d->k, 3, NULL, s->pl_global,
                                   NULL, 0, NULL, NULL));
  return MSOCL_OK;
}

int msocl__mesh_end(msocl__engine *s, struct msocl__mesh_dev *d)
{
  if (d->pending) { /* disabled through a call that moved it: no grid */
    drop_read(d);
    d->pending = d->built = 0;
  }
  if (!d->moving)
    return MSOCL_OK;
  d->a = 1 - d->a;
  d->placed = 0;
  /* the host's copies agree again, for a later partial move */
  memcpy(d->at[1 - d->a], d->at[d->a], 3 * (size_t)d->nv * sizeof(float));
  d->moving = 0;
  /* the cloth's bounds for the next call, read as this one finishes:
   * that call builds its grid without waiting for the device (positions
   * written between the calls leave them stale: a slower grid, never a
   * missed contact) */
  return cloth_bounds(s, d);
}

void msocl__mesh_free(struct msocl__mesh_dev *d)
{
  if (!d)
    return;
  drop_read(d);
  cl_kernel *k[9] = {&d->k,        &d->place,    &d->count,
                     &d->scan_sums, &d->scan_top, &d->scan_out,
                     &d->fill,      &d->sort,     &d->bounds};
  for (int q = 0; q < 9; q++)
    msocl__kernel_free(d->dev, k[q]);
  cl_mem b[13] = {d->vert[0], d->vert[1], d->dtri, d->drim, d->start,
                  d->list, d->cur, d->dcount, d->sums, d->live,
                  d->dbounds, d->esc, d->prev};
  for (int q = 0; q < 13; q++)
    if (b[q])
      clReleaseMemObject(b[q]);
  free(d->at[0]);
  free(d->at[1]);
  free(d->hvert);
  free(d->hvbox);
  free(d->hbox);
  free(d->hstart);
  free(d->hlist);
  free(d->hlive);
  free(d->hbounds);
  free(d->tri);
  free(d);
}

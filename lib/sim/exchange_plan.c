/* The plan of a split simulation's halo exchange: where each slice sits
 * in the host staging areas, and, boundary first, each engine's range cut
 * into the spans others read and the interior, with the device buffers
 * and second queue its copies go through. */
#include "config.h"
#include "sim.h"

#include <stdlib.h>

/* Engine d's range as spans: first the union of the slices others read,
 * merged and in order, then the gaps between them (the interior). */
static void plan_spans(msocl_sim *s, int d)
{
  struct msocl__exchange *x = &s->x;
  const int lo = s->halo[d][d][0], hi = s->halo[d][d][1];
  /* the planes run whole rows: a row cut between two spans would run
   * twice, and Verlet's drift is in place */
  const int unit = msocl__planes_unit(s->part[d]);
  int iv[MSOCL__MAX_PARTS][2], n = 0;
  for (int r = 0; r < s->nparts; r++) {
    const int *h = s->halo[r][d];
    if (r == d || h[0] >= h[1])
      continue;
    int a = h[0] / unit * unit, b = (h[1] + unit - 1) / unit * unit;
    a = a > lo ? a : lo;
    b = b < hi ? b : hi;
    if (a >= b)
      continue;
    int q = n++; /* insertion by start */
    for (; q > 0 && iv[q - 1][0] > a; q--) {
      iv[q][0] = iv[q - 1][0];
      iv[q][1] = iv[q - 1][1];
    }
    iv[q][0] = a;
    iv[q][1] = b;
  }
  int nb = 0;
  for (int q = 0; q < n; q++) {
    if (nb > 0 && iv[q][0] <= x->span[d][nb - 1][1]) {
      if (iv[q][1] > x->span[d][nb - 1][1])
        x->span[d][nb - 1][1] = iv[q][1];
      continue;
    }
    x->span[d][nb][0] = iv[q][0];
    x->span[d][nb][1] = iv[q][1];
    nb++;
  }
  int ns = nb, at = lo;
  for (int q = 0; q <= nb; q++) {
    int end = q < nb ? x->span[d][q][0] : hi;
    if (at < end) {
      x->span[d][ns][0] = at;
      x->span[d][ns][1] = end;
      ns++;
    }
    if (q < nb)
      at = x->span[d][q][1];
  }
  x->nbound[d] = nb;
  x->nspan[d] = ns;
}

/* Engine d's second queue, and its send and receive buffers. */
static int plan_copies(msocl_sim *s, int d, size_t bytes)
{
  struct msocl__exchange *x = &s->x;
  struct msocl__device *dev = s->part[d]->dev;
  cl_int err;
  x->xq[d] = clCreateCommandQueue(dev->ctx, dev->id,
                                  CL_QUEUE_PROFILING_ENABLE, &err);
  if (err != CL_SUCCESS)
    return msocl__fail(err, "the copy queue on %s: %s (%d)", dev->info.name,
                       msocl_err_name(err), (int)err);
  for (int k = 0; k < MSOCL__X_SLOTS; k++) {
    cl_mem *b[2] = {&x->send[d][k], &x->recv[d][k]};
    for (int q = 0; q < 2; q++) {
      int rc = MSOCL_OK;
      *b[q] = msocl__buffer(dev, CL_MEM_READ_WRITE, bytes, NULL, "halo",
                            &rc);
      MSOCL__TRY(rc);
    }
  }
  return MSOCL_OK;
}

int msocl__exchange_plan(msocl_sim *s)
{
  struct msocl__exchange *x = &s->x;
  /* one slice an ordered pair: a middle device's two neighbours read
   * opposite ends of its range, not all that lies between */
  x->packed = 0;
  for (int d = 0; d < s->nparts; d++)
    for (int e = 0; e < s->nparts; e++) {
      const int *h = s->halo[d][e];
      x->base[d][e] = x->packed;
      if (d != e && h[0] < h[1]) {
        size_t off[MSOCL__X_SLICES], len;
        const int nc = msocl__exchange_slices(s->part[e], h[0], h[1], off,
                                              &len);
        x->packed += (size_t)nc * len;
      }
    }
  /* whole float4s, so that every area stays aligned for them */
  const size_t one = ((x->packed > 0 ? x->packed : 1) + sizeof(cl_float4) -
                      1) & ~(sizeof(cl_float4) - 1);
  /* Pinned (page-locked) host memory makes a GPU's transfers direct
   * rather than staged through the driver's own bounce buffer; it belongs
   * to one context, so a GPU's. CPU devices read host memory in place. */
  int gpu = -1;
  for (int d = 0; d < s->nparts && gpu < 0; d++)
    if (s->part[d]->dev->info.type == MSOCL_DEVICE_GPU)
      gpu = d;
  const size_t all = 2 * MSOCL__X_SLOTS * one;
  if (gpu >= 0) {
    cl_int err;
    struct msocl__device *dev = s->part[gpu]->dev;
    x->pinned = clCreateBuffer(dev->ctx, CL_MEM_ALLOC_HOST_PTR, all, NULL,
                               &err);
    if (err == CL_SUCCESS) {
      x->map_queue = dev->queue;
      x->host = clEnqueueMapBuffer(dev->queue, x->pinned, CL_TRUE,
                                   CL_MAP_READ | CL_MAP_WRITE, 0, all, 0,
                                   NULL, NULL, &err);
    }
    if (err != CL_SUCCESS)
      msocl__exchange_free(s); /* fall back to ordinary memory */
  }
  if (!x->host && !(x->host = x->heap = malloc(all)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "exchange staging (%zu bytes)",
                       all);
  for (int p = 0; p < 2; p++)
    for (int k = 0; k < MSOCL__X_SLOTS; k++)
      x->area[p][k] = (unsigned char *)x->host +
                      (size_t)(p * MSOCL__X_SLOTS + k) * one;
  /* Boundary first runs a phase once a span. */
  x->overlap = s->o.tuning.overlap != MSOCL_OFF;
  for (int d = 0; x->overlap && d < s->nparts; d++) {
    plan_spans(s, d);
    int rc = plan_copies(s, d, one);
    if (rc != MSOCL_OK)
      return rc;
  }
  return MSOCL_OK;
}

void msocl__exchange_free(msocl_sim *s)
{
  struct msocl__exchange *x = &s->x;
  for (int d = 0; d < MSOCL__MAX_PARTS; d++) {
    cl_event *ev[2] = {x->wev[d], x->rev[d]};
    int *nev[2] = {&x->nwev[d], &x->nrev[d]};
    for (int q = 0; q < 2; q++) {
      for (int i = 0; i < *nev[q]; i++)
        clReleaseEvent(ev[q][i]);
      *nev[q] = 0;
    }
    for (int i = 0; i < x->nmark[d]; i++) {
      struct msocl__mark *m = &x->mark[d][i];
      for (int q = 0; q < 2; q++)
        if (m->ev[q])
          clReleaseEvent(m->ev[q]);
      for (int r = 0; r < m->ncopy; r++)
        clReleaseEvent(m->copy[r]);
      m->ncopy = 0;
    }
    x->nmark[d] = 0;
    if (x->xq[d]) {
      clFinish(x->xq[d]);
      clReleaseCommandQueue(x->xq[d]);
      x->xq[d] = NULL;
    }
    for (int k = 0; k < MSOCL__X_SLOTS; k++) {
      cl_mem *b[2] = {&x->send[d][k], &x->recv[d][k]};
      for (int q = 0; q < 2; q++)
        if (*b[q]) {
          clReleaseMemObject(*b[q]);
          *b[q] = NULL;
        }
    }
  }
  if (x->pinned) {
    if (x->host) {
      clEnqueueUnmapMemObject(x->map_queue, x->pinned, x->host, 0, NULL,
                              NULL);
      clFinish(x->map_queue);
    }
    clReleaseMemObject(x->pinned);
  }
  free(x->heap);
  x->pinned = NULL;
  x->host = x->heap = NULL;
}

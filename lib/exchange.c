/* Halo exchange between the engines of a split simulation, through host
 * memory: devices may sit in different contexts and platforms, where no
 * device-to-device copy exists. Each engine reads the slice of its points
 * that each other engine needs (gather); each engine then writes its halos
 * from those slices (scatter). The staging areas alternate
 * between two sets, so one exchange's writes may still be in flight on
 * one device while the next exchange's reads fill the other set. */
#include "config.h"
#include "sim.h"

#include <stdlib.h>
#include <string.h>

/* Seconds from profiling stamp `from` of finished command a to stamp `to`
 * of b (0 where the driver gives none). */
static double stamps(cl_event a, cl_profiling_info from, cl_event b,
                     cl_profiling_info to)
{
  cl_ulong t0 = 0, t1 = 0;
  if (clGetEventProfilingInfo(a, from, sizeof t0, &t0, NULL) != CL_SUCCESS ||
      clGetEventProfilingInfo(b, to, sizeof t1, &t1, NULL) != CL_SUCCESS ||
      t1 < t0)
    return 0.0;
  return 1e-9 * (double)(t1 - t0);
}

/* Device time of a finished command. */
static double event_seconds(cl_event ev)
{
  return stamps(ev, CL_PROFILING_COMMAND_START, ev, CL_PROFILING_COMMAND_END);
}

double msocl__event_span(cl_event a, cl_event b)
{
  return stamps(a, CL_PROFILING_COMMAND_END, b, CL_PROFILING_COMMAND_END);
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
      if (d != e && h[0] < h[1])
        x->packed += h[1] - h[0];
    }
  size_t one = (size_t)(x->packed > 0 ? x->packed : 1) * sizeof(cl_float4);
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
      x->area[p][k] = (cl_float4 *)((char *)x->host +
                                    (size_t)(p * MSOCL__X_SLOTS + k) * one);
  return MSOCL_OK;
}

void msocl__exchange_free(msocl_sim *s)
{
  struct msocl__exchange *x = &s->x;
  for (int d = 0; d < MSOCL__MAX_PARTS; d++) {
    for (int i = 0; i < x->nwev[d]; i++)
      clReleaseEvent(x->wev[d][i]);
    x->nwev[d] = 0;
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

int msocl__exchange_gather(msocl_sim *s, int d, unsigned mask)
{
  struct msocl__exchange *x = &s->x;
  msocl__engine *e = s->part[d];
  cl_event ev[MSOCL__X_SLOTS * MSOCL__MAX_PARTS];
  int k = 0, nev = 0;
  for (unsigned bit = 1; bit <= MSOCL__X_LAST; bit <<= 1) {
    if (!(mask & bit))
      continue;
    if (k == MSOCL__X_SLOTS)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "a phase exchanges more than %d buffers",
                         MSOCL__X_SLOTS);
    cl_float4 *area = x->area[x->parity][k];
    /* the slice of d's points each other engine r reads */
    for (int r = 0; r < s->nparts; r++) {
      const int *h = s->halo[r][d];
      if (r == d || h[0] >= h[1])
        continue;
      MSOCL__CL(clEnqueueReadBuffer(
          e->dev->queue, msocl__exchange_buffer(e, bit), CL_FALSE,
          (size_t)h[0] * sizeof(cl_float4),
          (size_t)(h[1] - h[0]) * sizeof(cl_float4), area + x->base[r][d], 0,
          NULL, &ev[nev++]));
    }
    /* what this engine receives into its own buffer, bound now: the
     * buffer a bit names changes when the step's ping-pong swaps */
    x->pend[d][k].buf = msocl__exchange_buffer(e, bit);
    x->pend[d][k].area = area;
    k++;
  }
  x->npend[d] = k;
  cl_int err = nev > 0 ? clWaitForEvents((cl_uint)nev, ev) : CL_SUCCESS;
  for (int i = 0; i < nev; i++) {
    x->stat[d].copy_seconds += event_seconds(ev[i]);
    clReleaseEvent(ev[i]);
  }
  MSOCL__CL(err);
  return MSOCL_OK;
}

int msocl__exchange_scatter(msocl_sim *s, int d)
{
  struct msocl__exchange *x = &s->x;
  msocl__engine *dst = s->part[d];
  for (int k = 0; k < x->npend[d]; k++) {
    const struct msocl__pending *p = &x->pend[d][k];
    for (int e = 0; e < s->nparts; e++) {
      const int *h = s->halo[d][e];
      if (e == d || h[0] >= h[1])
        continue;
      const size_t len = (size_t)(h[1] - h[0]) * sizeof(cl_float4);
      /* its time is read once the queue is done (settle) */
      MSOCL__CL(clEnqueueWriteBuffer(dst->dev->queue, p->buf, CL_FALSE,
                                     (size_t)h[0] * sizeof(cl_float4), len,
                                     p->area + x->base[d][e], 0, NULL,
                                     &x->wev[d][x->nwev[d]++]));
      x->stat[d].bytes += (double)len;
    }
  }
  x->npend[d] = 0;
  return MSOCL_OK;
}

void msocl__exchange_settle(msocl_sim *s, int d)
{
  struct msocl__exchange *x = &s->x;
  for (int i = 0; i < x->nwev[d]; i++) {
    x->stat[d].copy_seconds += event_seconds(x->wev[d][i]);
    clReleaseEvent(x->wev[d][i]);
  }
  x->nwev[d] = 0;
}

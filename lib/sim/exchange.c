/* Halo exchange between the engines of a split simulation, through host
 * memory: devices may sit in different contexts and platforms, where no
 * device-to-device copy exists. Each engine reads the slice of its points
 * that each other engine needs (gather, or send without waiting); each
 * engine then writes its halos from those slices (scatter). The staging
 * areas alternate between two sets, so one exchange's writes may still be
 * in flight on one device while the next exchange's reads fill the other
 * set. A slice of a buffer is three copies, one a plane
 * (exchange_slices.c). */
#include "config.h"
#include "sim.h"

#include <string.h>

/* Device stamp `what` of a finished command (0 where none is given). */
static cl_ulong stamp(cl_event ev, cl_profiling_info what)
{
  cl_ulong t = 0;
  if (clGetEventProfilingInfo(ev, what, sizeof t, &t, NULL) != CL_SUCCESS)
    return 0;
  return t;
}

/* Seconds from profiling stamp `from` of finished command a to stamp `to`
 * of b (0 where the driver gives none). */
static double stamps(cl_event a, cl_profiling_info from, cl_event b,
                     cl_profiling_info to)
{
  cl_ulong t0 = stamp(a, from), t1 = stamp(b, to);
  return t0 > 0 && t1 > t0 ? 1e-9 * (double)(t1 - t0) : 0.0;
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

/* The exchange slots of `mask`'s buffers, in bit order: *n of them. */
static int slots(unsigned mask, unsigned *bit, int *n)
{
  *n = 0;
  for (unsigned b = 1; b <= MSOCL__X_LAST; b <<= 1) {
    if (!(mask & b))
      continue;
    if (*n == MSOCL__X_SLOTS)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "a phase exchanges more than %d buffers",
                         MSOCL__X_SLOTS);
    bit[(*n)++] = b;
  }
  return MSOCL_OK;
}

/* Books and releases finished copies. */
static void book(msocl_sim *s, int d, cl_event *ev, int n)
{
  for (int i = 0; i < n; i++) {
    s->x.stat[d].copy_seconds += event_seconds(ev[i]);
    clReleaseEvent(ev[i]);
  }
}

int msocl__exchange_gather(msocl_sim *s, int d, unsigned mask)
{
  struct msocl__exchange *x = &s->x;
  msocl__engine *e = s->part[d];
  cl_event ev[MSOCL__X_COPIES];
  unsigned bit[MSOCL__X_SLOTS];
  int nk, nev = 0, rc = slots(mask, bit, &nk);
  if (rc != MSOCL_OK)
    return rc;
  for (int k = 0; k < nk; k++) {
    unsigned char *area = x->area[x->parity][k];
    cl_mem buf = msocl__planes_exchange_buffer(e, bit[k]);
    /* the slices of d's points each other engine r reads */
    for (int r = 0; r < s->nparts; r++) {
      const int *h = s->halo[r][d];
      if (r == d || h[0] >= h[1])
        continue;
      size_t off[MSOCL__X_SLICES], len;
      const int nc = msocl__exchange_slices(e, h[0], h[1], off, &len);
      for (int c = 0; c < nc; c++) {
        cl_int err = clEnqueueReadBuffer(
            e->dev->queue, buf, CL_FALSE, off[c], len,
            area + x->base[r][d] + (size_t)c * len, 0, NULL, &ev[nev]);
        if (err != CL_SUCCESS) {
          clWaitForEvents((cl_uint)nev, ev);
          book(s, d, ev, nev);
          MSOCL__CL(err);
        }
        nev++;
      }
    }
    /* what this engine receives into its own buffer, bound now: the
     * buffer a bit names changes when the step's ping-pong swaps */
    x->pend[d][k].buf = buf;
    x->pend[d][k].area = area;
  }
  x->npend[d] = nk;
  cl_int err = nev > 0 ? clWaitForEvents((cl_uint)nev, ev) : CL_SUCCESS;
  book(s, d, ev, nev);
  MSOCL__CL(err);
  return MSOCL_OK;
}

/* Boundary first: the slices are copied on the device into `send` behind
 * the phases queued so far, and read from there on the copy queue, so
 * the kernels queued next (the interior) overwrite nothing being read. */
int msocl__exchange_send(msocl_sim *s, int d, unsigned mask)
{
  struct msocl__exchange *x = &s->x;
  msocl__engine *e = s->part[d];
  cl_command_queue q = e->dev->queue;
  unsigned bit[MSOCL__X_SLOTS];
  int nk, rc = slots(mask, bit, &nk);
  if (rc != MSOCL_OK)
    return rc;
  for (int k = 0; k < nk; k++) {
    cl_mem buf = msocl__planes_exchange_buffer(e, bit[k]);
    for (int r = 0; r < s->nparts; r++) {
      const int *h = s->halo[r][d];
      if (r == d || h[0] >= h[1])
        continue;
      size_t off[MSOCL__X_SLICES], len;
      const int nc = msocl__exchange_slices(e, h[0], h[1], off, &len);
      for (int c = 0; c < nc; c++)
        MSOCL__CL(clEnqueueCopyBuffer(q, buf, x->send[d][k], off[c],
                                      x->base[r][d] + (size_t)c * len, len,
                                      0, NULL, NULL));
    }
    x->pend[d][k].buf = buf;
    x->pend[d][k].area = x->area[x->parity][k];
  }
  x->npend[d] = nk;
  cl_event ready;
  MSOCL__CL(clEnqueueMarkerWithWaitList(q, 0, NULL, &ready));
  cl_int err = clFlush(q);
  for (int k = 0; err == CL_SUCCESS && k < nk; k++)
    for (int r = 0; err == CL_SUCCESS && r < s->nparts; r++) {
      const int *h = s->halo[r][d];
      if (r == d || h[0] >= h[1])
        continue;
      /* the slices lie one after another: one read */
      size_t off[MSOCL__X_SLICES], len;
      const int nc = msocl__exchange_slices(e, h[0], h[1], off, &len);
      const size_t at = x->base[r][d];
      err = clEnqueueReadBuffer(x->xq[d], x->send[d][k], CL_FALSE, at,
                                (size_t)nc * len, x->area[x->parity][k] + at,
                                1, &ready, &x->rev[d][x->nrev[d]++]);
      if (err != CL_SUCCESS)
        x->nrev[d]--;
    }
  clReleaseEvent(ready);
  if (err == CL_SUCCESS)
    err = clFlush(x->xq[d]);
  MSOCL__CL(err);
  return MSOCL_OK;
}

int msocl__exchange_wait(msocl_sim *s, int d, struct msocl__mark *m)
{
  struct msocl__exchange *x = &s->x;
  const int n = x->nrev[d];
  cl_int err = n > 0 ? clWaitForEvents((cl_uint)n, x->rev[d]) : CL_SUCCESS;
  if (m && err == CL_SUCCESS) {
    for (int i = 0; i < n; i++)
      m->copy[m->ncopy++] = x->rev[d][i];
  } else {
    book(s, d, x->rev[d], n);
  }
  x->nrev[d] = 0;
  MSOCL__CL(err);
  return MSOCL_OK;
}

/* Boundary first, a write goes into `recv` on the copy queue (while the
 * device may still run the last interior), then into the halo on the
 * device's queue once written; otherwise straight into the halo. */
int msocl__exchange_scatter(msocl_sim *s, int d)
{
  struct msocl__exchange *x = &s->x;
  msocl__engine *dst = s->part[d];
  msocl__exchange_settle(s, d);
  /* boundary first: the last job's interior may still run beside these */
  struct msocl__mark *m = x->overlap && x->nmark[d] > 0
                              ? &x->mark[d][x->nmark[d] - 1]
                              : NULL;
  for (int k = 0; k < x->npend[d]; k++) {
    const struct msocl__pending *p = &x->pend[d][k];
    for (int e = 0; e < s->nparts; e++) {
      const int *h = s->halo[d][e];
      if (e == d || h[0] >= h[1])
        continue;
      size_t off[MSOCL__X_SLICES], len;
      const int nc = msocl__exchange_slices(dst, h[0], h[1], off, &len);
      for (int c = 0; c < nc; c++) {
        const size_t to = off[c], at = x->base[d][e] + (size_t)c * len;
        cl_event *w = &x->wev[d][x->nwev[d]];
        /* its time is booked once it is done (settle) */
        if (!x->overlap) {
          MSOCL__CL(clEnqueueWriteBuffer(dst->dev->queue, p->buf, CL_FALSE,
                                         to, len, p->area + at, 0, NULL, w));
          x->nwev[d]++;
        } else {
          MSOCL__CL(clEnqueueWriteBuffer(x->xq[d], x->recv[d][k], CL_FALSE,
                                         at, len, p->area + at, 0, NULL, w));
          MSOCL__CL(clEnqueueCopyBuffer(dst->dev->queue, x->recv[d][k],
                                        p->buf, at, to, len, 1, w, NULL));
          if (m) /* booked with the mark, not settled */
            m->copy[m->ncopy++] = *w;
          else
            x->nwev[d]++;
        }
        x->stat[d].bytes += (double)len;
      }
    }
  }
  x->npend[d] = 0;
  if (x->overlap)
    MSOCL__CL(clFlush(x->xq[d]));
  return MSOCL_OK;
}

void msocl__exchange_settle(msocl_sim *s, int d)
{
  struct msocl__exchange *x = &s->x;
  if (x->nwev[d] > 0)
    clWaitForEvents((cl_uint)x->nwev[d], x->wev[d]);
  book(s, d, x->wev[d], x->nwev[d]);
  x->nwev[d] = 0;
}

void msocl__exchange_marks(msocl_sim *s, int d, int keep)
{
  struct msocl__exchange *x = &s->x;
  const int n = x->nmark[d] - keep;
  for (int i = 0; i < n; i++) {
    struct msocl__mark *m = &x->mark[d][i];
    cl_ulong end = 0;
    if (m->ev[1] && clWaitForEvents(1, &m->ev[1]) == CL_SUCCESS) {
      x->stat[d].compute_seconds += msocl__event_span(m->ev[0], m->ev[1]);
      end = stamp(m->ev[1], CL_PROFILING_COMMAND_END);
    }
    /* each copy's time before the interior's end ran beside it */
    if (m->ncopy > 0 && clWaitForEvents((cl_uint)m->ncopy, m->copy) !=
                            CL_SUCCESS)
      end = 0;
    for (int r = 0; r < m->ncopy; r++) {
      cl_ulong a = stamp(m->copy[r], CL_PROFILING_COMMAND_START),
               b = stamp(m->copy[r], CL_PROFILING_COMMAND_END);
      if (b > end)
        b = end;
      if (b > a)
        x->stat[d].hidden_seconds += 1e-9 * (double)(b - a);
    }
    book(s, d, m->copy, m->ncopy);
    m->ncopy = 0;
    for (int q = 0; q < 2; q++)
      if (m->ev[q])
        clReleaseEvent(m->ev[q]);
  }
  for (int i = 0; n > 0 && i < keep; i++)
    x->mark[d][i] = x->mark[d][n + i];
  if (n > 0)
    x->nmark[d] = keep;
}

/* Stepping a simulation: every engine runs each phase of a step on its own
 * points, then the points other engines read cross over through host
 * memory; every check_every steps the blow-up check. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <string.h>
#include <time.h>

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int finish_all(msocl_sim *s)
{
  double t0 = now();
  /* flush every queue first: a queue starts its work when flushed, so
   * finishing them one by one would run the devices one after another */
  for (int d = 0; s->nparts > 1 && d < s->nparts; d++)
    MSOCL__CL(clFlush(s->part[d]->dev->queue));
  for (int d = 0; d < s->nparts; d++)
    MSOCL__CL(clFinish(s->part[d]->dev->queue));
  s->wait_seconds += now() - t0;
  return MSOCL_OK;
}

/* Moves the buffers named in `mask`: each engine's halo spans from their
 * owners, through host staging (devices may sit in different contexts and
 * platforms). Reads wait; the writes are queued ahead of the next phase's
 * kernels on each in-order queue. */
static int exchange(msocl_sim *s, unsigned mask)
{
  if (s->nparts < 2 || mask == 0)
    return MSOCL_OK;
  int rc = finish_all(s); /* kernels done, last exchange's writes too */
  if (rc != MSOCL_OK)
    return rc;
  double t0 = now();
  int slot = 0;
  for (unsigned bit = 1; bit <= MSOCL__X_CG_P && rc == MSOCL_OK; bit <<= 1) {
    if (!(mask & bit))
      continue;
    if (slot == 2) { /* both staging arrays in flight: let writes drain */
      if ((rc = finish_all(s)) != MSOCL_OK)
        break;
      slot = 0;
    }
    cl_float4 *host = s->xfer[slot++];
    /* every span any engine needs, read once from its owner */
    for (int e = 0; e < s->nparts; e++) {
      int lo = s->n, hi = 0;
      for (int d = 0; d < s->nparts; d++)
        if (d != e && s->halo[d][e][0] < s->halo[d][e][1]) {
          lo = s->halo[d][e][0] < lo ? s->halo[d][e][0] : lo;
          hi = s->halo[d][e][1] > hi ? s->halo[d][e][1] : hi;
        }
      if (lo >= hi)
        continue;
      size_t off = (size_t)lo * sizeof(cl_float4),
             len = (size_t)(hi - lo) * sizeof(cl_float4);
      msocl__engine *src = s->part[e];
      MSOCL__CL(clEnqueueReadBuffer(src->dev->queue,
                                    msocl__exchange_buffer(src, bit), CL_TRUE,
                                    off, len, host + lo, 0, NULL, NULL));
    }
    for (int d = 0; d < s->nparts; d++)
      for (int e = 0; e < s->nparts; e++) {
        const int *h = s->halo[d][e];
        if (d == e || h[0] >= h[1])
          continue;
        size_t off = (size_t)h[0] * sizeof(cl_float4),
               len = (size_t)(h[1] - h[0]) * sizeof(cl_float4);
        msocl__engine *dst = s->part[d];
        MSOCL__CL(clEnqueueWriteBuffer(dst->dev->queue,
                                       msocl__exchange_buffer(dst, bit),
                                       CL_FALSE, off, len, host + h[0], 0,
                                       NULL, NULL));
        s->bytes_exchanged += (double)len;
      }
  }
  s->exchange_seconds += now() - t0;
  return rc;
}

static int exchange_cg(void *ctx)
{
  return exchange((msocl_sim *)ctx, MSOCL__X_CG_P);
}

/* `n` whole steps on every engine, phase by phase. */
static int steps(msocl_sim *s, int n)
{
  const int phases = msocl__phase_count(s->part[0]);
  const int split_cg = s->nparts > 1 &&
                       s->o.integrator == MSOCL_IMPLICIT_EULER;
  for (int q = 0; q < n; q++) {
    for (int ph = 0; ph < phases; ph++) {
      unsigned mask = 0;
      if (ph == 0 && split_cg) { /* one CG over every engine */
        int rc = msocl__implicit_cg(s->part, s->nparts, exchange_cg, s);
        if (rc != MSOCL_OK)
          return rc;
        continue;
      }
      for (int d = 0; d < s->nparts; d++) {
        int rc = msocl__phase(s->part[d], ph, &mask);
        if (rc != MSOCL_OK)
          return rc;
      }
      int rc = exchange(s, mask);
      if (rc != MSOCL_OK)
        return rc;
    }
    for (int d = 0; d < s->nparts; d++) {
      msocl__step_done(s->part[d]);
      if ((q + 1) % 64 == 0)
        MSOCL__CL(clFlush(s->part[d]->dev->queue));
    }
    s->steps++;
  }
  return MSOCL_OK;
}

/* Energy of the whole state: each engine sums its own points. */
int msocl__sim_energy(msocl_sim *s, msocl_energy *e)
{
  memset(e, 0, sizeof *e);
  for (int d = 0; d < s->nparts; d++) {
    msocl_energy p;
    int rc = msocl__energy(s->part[d], &p);
    if (rc != MSOCL_OK)
      return rc;
    e->kinetic += p.kinetic;
    e->spring += p.spring;
    e->gravity += p.gravity;
  }
  e->total = e->kinetic + e->spring + e->gravity;
  return MSOCL_OK;
}

/* The blow-up check's baseline: energy at the start, and a scale for the
 * scene - its kinetic and spring energy plus the work gravity could do
 * across its extent - so a scene starting at rest has a finite bound. */
static int baseline(msocl_sim *s)
{
  msocl_energy e;
  int rc = msocl__sim_energy(s, &e);
  if (rc != MSOCL_OK)
    return rc;
  const cl_float4 *g = &s->part[0]->gravity;
  double gn = sqrt((double)g->s[0] * g->s[0] + (double)g->s[1] * g->s[1] +
                   (double)g->s[2] * g->s[2]);
  s->e0 = e.total;
  s->escale = e.kinetic + e.spring + s->total_mass * gn * s->extent;
  s->e0_valid = 1;
  return MSOCL_OK;
}

/* Saves (to_backup) or restores each engine's whole state. */
static int backup(msocl_sim *s, int to_backup)
{
  for (int d = 0; d < s->nparts; d++) {
    msocl__engine *e = s->part[d];
    const size_t bytes = 4 * (size_t)e->n * sizeof(float);
    cl_mem st[2] = {e->pos[e->r], e->vel[e->r]}, bk[2] = {e->backup_p,
                                                          e->backup_v};
    for (int k = 0; k < 2; k++)
      MSOCL__CL(clEnqueueCopyBuffer(e->dev->queue, to_backup ? st[k] : bk[k],
                                    to_backup ? bk[k] : st[k], 0, 0, bytes,
                                    0, NULL, NULL));
    if (!to_backup)
      e->acc_valid = 0;
  }
  return MSOCL_OK;
}

/* A checked batch, in two halves so that many simulations can run theirs
 * at once: begin saves the state and queues the steps; end checks the
 * energy and, past the bound, restores the saved state. */
int msocl__batch_begin(msocl_sim *s, int batch, long long *first)
{
  int rc = s->e0_valid ? MSOCL_OK : baseline(s);
  *first = s->steps;
  if (rc == MSOCL_OK)
    rc = backup(s, 1);
  return rc == MSOCL_OK ? steps(s, batch) : rc;
}

int msocl__batch_end(msocl_sim *s, long long first)
{
  msocl_energy e;
  int rc = msocl__sim_energy(s, &e);
  if (rc != MSOCL_OK)
    return rc;
  double bound = s->e0 + s->o.energy_factor * s->escale;
  if (isfinite(e.total) && e.total <= bound)
    return MSOCL_OK;
  long long last = s->steps;
  rc = backup(s, 0);
  s->steps = first;
  if (rc == MSOCL_OK)
    rc = finish_all(s);
  if (rc != MSOCL_OK)
    return rc;
  return msocl__fail(
      MSOCL_ERR_UNSTABLE,
      "blew up between steps %lld and %lld (dt = %g): total energy %g J "
      "against %g J at the start (bound %g J); state restored to step %lld; "
      "msocl_stable_dt() gives a safe step",
      first, last, (double)s->o.dt, e.total, s->e0, bound, first);
}

int msocl__sim_steps(msocl_sim *s, int n)
{
  return steps(s, n);
}

int msocl__sim_finish(msocl_sim *s)
{
  return finish_all(s);
}

int msocl_sim_step(msocl_sim *s, int n)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (n < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "step count %d is negative", n);
  int rc = MSOCL_OK;
  if (s->o.check_every <= 0)
    rc = steps(s, n);
  for (int done = 0; s->o.check_every > 0 && rc == MSOCL_OK && done < n;) {
    int batch = n - done < s->o.check_every ? n - done : s->o.check_every;
    long long first;
    rc = msocl__batch_begin(s, batch, &first);
    if (rc == MSOCL_OK)
      rc = msocl__batch_end(s, first);
    done += batch;
  }
  return rc == MSOCL_OK ? finish_all(s) : rc;
}

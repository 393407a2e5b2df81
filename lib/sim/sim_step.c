/* Stepping a simulation: every engine runs each phase of a step on its own
 * points, then the points other engines read cross over through host
 * memory; every check_every steps (counted across calls) the blow-up
 * check. */
#include "config.h"
#include "schedule.h"
#include "sim.h"

#include <math.h>
#include <string.h>


/* Waits for engine d's queues: its kernels, and the copies into and out
 * of its halos (whose device time is then booked). */
static int finish(msocl_sim *s, int d)
{
  double t0 = msocl__seconds();
  MSOCL__CL(clFinish(s->part[d]->dev->queue));
  if (s->nparts > 1 && s->x.xq[d])
    MSOCL__CL(clFinish(s->x.xq[d]));
  s->x.stat[d].wait_seconds += msocl__seconds() - t0;
  if (s->nparts > 1) {
    msocl__exchange_settle(s, d);
    msocl__exchange_marks(s, d, 0);
  }
  return MSOCL_OK;
}

static int finish_all(msocl_sim *s)
{
  /* flush every queue first: a queue starts its work when flushed, so
   * finishing them one by one would run the devices one after another */
  for (int d = 0; s->nparts > 1 && d < s->nparts; d++)
    MSOCL__CL(clFlush(s->part[d]->dev->queue));
  for (int d = 0; d < s->nparts; d++) {
    int rc = finish(s, d);
    if (rc != MSOCL_OK)
      return rc;
  }
  return MSOCL_OK;
}

/* Gather (after the queue finished) or scatter, timed on the host. */
static int gather(msocl_sim *s, int d, unsigned mask)
{
  double t0 = msocl__seconds();
  int rc = msocl__exchange_gather(s, d, mask);
  s->x.stat[d].host_seconds += msocl__seconds() - t0;
  return rc;
}

static int scatter(msocl_sim *s, int d)
{
  double t0 = msocl__seconds();
  int rc = msocl__exchange_scatter(s, d);
  s->x.stat[d].host_seconds += msocl__seconds() - t0;
  return rc;
}

/* The implicit solver's exchange of the CG direction, from the caller's
 * thread between the solver's products: every engine finished, every
 * slice read, every halo write queued ahead of the next product. */
static int exchange_cg(void *ctx)
{
  msocl_sim *s = ctx;
  int rc = finish_all(s);
  for (int d = 0; rc == MSOCL_OK && d < s->nparts; d++)
    rc = gather(s, d, MSOCL__X_CG_P);
  for (int d = 0; rc == MSOCL_OK && d < s->nparts; d++)
    rc = scatter(s, d);
  s->x.parity ^= 1;
  return rc;
}

/* One job of a split step, on engine d's own host thread: the writes
 * the last exchange left for it, then phases from `ph` until one leaves
 * data that others read, and that data read for them. */
struct job {
  msocl_sim *s;
  int ph;       /* first phase; < 0: only the pending writes */
  int end;      /* out: the phase after the last one run */
  unsigned mask; /* out: what the last one left for the others */
};

/* Phases [from, to) over span sp of the engine's range (NULL: all). */
static int run_span(msocl__engine *e, const int *sp, int from, int to)
{
  int rc = MSOCL_OK;
  if (sp) {
    e->run_offset = (size_t)sp[0];
    e->run_global = (size_t)(sp[1] - sp[0]);
  }
  for (int ph = from; rc == MSOCL_OK && ph < to; ph++) {
    unsigned mask;
    rc = msocl__phase(e, ph, &mask);
  }
  e->run_offset = e->offset;
  e->run_global = e->global;
  return rc;
}

/* Boundary first: the phases over the spans others read, their slices
 * sent, then the phases over the interior - the device may still be at
 * the interior when the job ends. Only a phase's first kernel reads other
 * points, so every point's result is the one a whole-range launch gives. */
static int boundary_first(msocl_sim *s, int d, int from, int to,
                          unsigned mask)
{
  struct msocl__exchange *x = &s->x;
  msocl__engine *e = s->part[d];
  int rc = MSOCL_OK;
  for (int q = 0; rc == MSOCL_OK && q < x->nbound[d]; q++)
    rc = run_span(e, x->span[d][q], from, to);
  if (rc == MSOCL_OK)
    rc = msocl__exchange_send(s, d, mask);
  for (int q = x->nbound[d]; rc == MSOCL_OK && q < x->nspan[d]; q++)
    rc = run_span(e, x->span[d][q], from, to);
  return rc;
}

static int job(void *ctx, int d)
{
  struct job *j = ctx;
  msocl_sim *s = j->s;
  struct msocl__exchange *x = &s->x;
  msocl__engine *e = s->part[d];
  const int phases = msocl__phase_count(e);
  const int ph = j->ph < 0 ? phases : j->ph;
  const int ahead = x->overlap; /* boundary first */
  unsigned mask = 0;
  int end = ph;
  while (end < phases && mask == 0)
    mask = msocl__phase_mask(e, end++);
  int rc = scatter(s, d);
  /* markers around the phases: their device time, from profiling, read
   * once the device is done with them */
  if (x->nmark[d] == MSOCL__MARKS)
    msocl__exchange_marks(s, d, 1);
  struct msocl__mark *m = &x->mark[d][x->nmark[d]];
  cl_event *mark = m->ev;
  mark[0] = mark[1] = NULL;
  m->ncopy = 0;
  if (rc == MSOCL_OK && ph < end &&
      clEnqueueMarkerWithWaitList(e->dev->queue, 0, NULL, &mark[0]) ==
          CL_SUCCESS)
    x->nmark[d]++;
  if (rc == MSOCL_OK)
    rc = ahead && mask ? boundary_first(s, d, ph, end, mask)
                       : run_span(e, NULL, ph, end);
  if (mark[0] &&
      clEnqueueMarkerWithWaitList(e->dev->queue, 0, NULL, &mark[1]) !=
          CL_SUCCESS)
    mark[1] = NULL;
  if (rc == MSOCL_OK && ahead) {
    /* only the reads are waited for; the rest queues on */
    double t0 = msocl__seconds();
    cl_int err = clFlush(e->dev->queue);
    if (err != CL_SUCCESS)
      rc = msocl__fail(err, "clFlush failed: %s (%d)", msocl_err_name(err),
                       (int)err);
    if (rc == MSOCL_OK) /* the reads go with the markers, if any */
      rc = msocl__exchange_wait(s, d, mark[1] ? m : NULL);
    x->stat[d].wait_seconds += msocl__seconds() - t0;
  } else if (rc == MSOCL_OK) {
    rc = finish(s, d);
    if (rc == MSOCL_OK && mask)
      rc = gather(s, d, mask); /* before the swap: bits name buffers by r */
  }
  if (rc == MSOCL_OK && j->ph >= 0 && end == phases)
    msocl__step_done(e);
  if (d == 0) {
    j->end = end;
    j->mask = mask;
  }
  return rc;
}

/* `n` whole steps of a split simulation, each engine on its own thread. */
static int split_steps(msocl_sim *s, int n)
{
  const struct msocl__schedule *t = msocl__schedule_of(&s->part[0]->o);
  struct job j = {s, 0, 0, 0};
  /* planes: the state into them, halos and all, unless they hold it */
  for (int d = 0; d < s->nparts; d++) {
    int rc = msocl__planes_enter(s->part[d]);
    if (rc != MSOCL_OK)
      return rc;
  }
  for (int q = 0; q < n; q++) {
    for (int ph = 0; ph < t->nphases;) {
      if (t->phase[ph].pass[0] == MSOCL__P_CG) {
        /* one CG over every engine, driven from this thread (a split
         * runs no strain sweeps: the CG is the whole phase) */
        j.ph = -1;
        int rc = msocl__workers_run(s->workers, job, &j);
        if (rc == MSOCL_OK)
          rc = msocl__implicit_cg(s->part, s->nparts, exchange_cg, s);
        if (rc != MSOCL_OK)
          return rc;
        ph++;
        continue;
      }
      j.ph = ph;
      int rc = msocl__workers_run(s->workers, job, &j);
      if (rc != MSOCL_OK)
        return rc;
      ph = j.end;
      if (j.mask)
        s->x.parity ^= 1;
    }
    s->steps++;
    s->x.steps_run++;
  }
  /* the last exchange's writes, so the halos match the state at rest */
  j.ph = -1;
  return msocl__workers_run(s->workers, job, &j);
}

/* `n` whole steps, phase by phase; one engine needs no exchange, and its
 * steps are queued without waiting. */
static int steps(msocl_sim *s, int n)
{
  if (s->nparts > 1)
    return split_steps(s, n);
  if (msocl__motion_moving(s))
    return msocl__motion_steps(s, n);
  /* msocl__integrate flushes the queue every 64 steps */
  int rc = msocl__integrate(s->part[0], n);
  if (rc == MSOCL_OK)
    s->steps += n;
  return rc;
}

/* A checked batch, in two halves so that many simulations can run theirs
 * at once: begin saves the state (where a stretch of check_every steps
 * starts, or where writes left a new one) and queues the steps; end, once
 * the stretch is whole, checks the energy and, past the bound, restores
 * the saved state. The count runs across calls and writes, so one step a
 * call (a frame loop) pays for the check every check_every steps, not
 * every call, and a loop that writes more often is checked all the same. */
int msocl__batch_room(const msocl_sim *s)
{
  return s->o.check_every - s->since_check;
}

int msocl__batch_begin(msocl_sim *s, int batch)
{
  int rc = MSOCL_OK;
  const int save = (s->since_check == 0 || s->moved) && !s->blown;
  if (!s->e0_valid || s->moved)
    rc = msocl__check_baseline(s);
  if (rc == MSOCL_OK && save) {
    s->check_first = s->steps;
    rc = msocl__check_backup(s, 1);
  }
  if (rc == MSOCL_OK)
    rc = steps(s, batch);
  if (rc == MSOCL_OK)
    s->since_check += batch;
  return rc;
}

int msocl__batch_end(msocl_sim *s)
{
  if (s->since_check < s->o.check_every)
    return MSOCL_OK;
  s->since_check = 0;
  const long long first = s->check_first;
  msocl_energy e = {0};
  if (!s->blown) {
    int rc = msocl__sim_energy(s, &e);
    if (rc != MSOCL_OK)
      return rc;
    if (isfinite(e.total) && e.total <= msocl__check_bound(s))
      return MSOCL_OK;
  }
  const int at_write = s->blown;
  const long long last = at_write ? s->blown_step : s->steps;
  const double total = at_write ? s->blown_total : e.total;
  s->blown = 0;
  int rc = msocl__check_backup(s, 0);
  s->steps = first;
  if (rc == MSOCL_OK)
    rc = finish_all(s);
  if (rc != MSOCL_OK)
    return rc;
  return msocl__fail(
      MSOCL_ERR_UNSTABLE,
      "blew up between steps %lld and %lld (dt = %g): total energy %g J%s "
      "against %g J at the start%s (bound %g J); state restored to step "
      "%lld; msocl_safe_dt() gives a step that holds in every state "
      "(docs/STABILITY.md)",
      first, last, (double)s->o.dt, total,
      at_write ? " where it was written" : "", s->e0,
      s->wrote ? " with the writes' work" : "", msocl__check_bound(s), first);
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
  msocl__motion_call(s, n);
  if (s->o.check_every <= 0)
    rc = steps(s, n);
  for (int done = 0; s->o.check_every > 0 && rc == MSOCL_OK && done < n;) {
    const int room = msocl__batch_room(s);
    const int batch = n - done < room ? n - done : room;
    rc = msocl__batch_begin(s, batch);
    if (rc == MSOCL_OK)
      rc = msocl__batch_end(s);
    done += batch;
  }
  return msocl__cg_report(s, rc == MSOCL_OK ? finish_all(s) : rc, n);
}

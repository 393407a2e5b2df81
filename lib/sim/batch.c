/* Batches: many independent simulations over a runtime's devices, stepped
 * together - every simulation's commands are queued before any is waited
 * for, so the devices work at once. */
#include "config.h"
#include "sim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct msocl_batch {
  int count;
  msocl_sim **sims;
  int *bad; /* a simulation that failed this call */
};

int msocl_batch_create(msocl_batch **out, msocl_runtime *rt, int count,
                       const msocl_model *const *models,
                       const msocl_sim_options *opts)
{
  msocl__clear_error();
  if (!out)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "batch out-pointer is NULL");
  *out = NULL;
  if (!rt || !models)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       rt ? "models" : "runtime");
  if (count <= 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "batch of %d simulations", count);
  msocl_batch *b = calloc(1, sizeof *b);
  if (!b || !(b->sims = calloc((size_t)count, sizeof *b->sims)) ||
      !(b->bad = calloc((size_t)count, sizeof *b->bad))) {
    msocl_batch_destroy(b);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "batch of %d", count);
  }
  b->count = count;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  if (opts)
    o = *opts;
  o.tuning.ndevices = 1;
  for (int i = 0; i < count; i++) {
    o.tuning.device = i % rt->ndev;
    int rc = models[i] ? msocl_sim_create(&b->sims[i], rt, models[i], &o)
                       : msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
    if (rc != MSOCL_OK) {
      char msg[512];
      snprintf(msg, sizeof msg, "%s", msocl_last_error());
      msocl_batch_destroy(b);
      return msocl__fail(rc, "batch simulation %d: %s", i, msg);
    }
  }
  *out = b;
  return MSOCL_OK;
}

void msocl_batch_destroy(msocl_batch *b)
{
  if (!b)
    return;
  for (int i = 0; b->sims && i < b->count; i++)
    msocl_sim_destroy(b->sims[i]);
  free(b->sims);
  free(b->bad);
  free(b);
}

/* Keeps the first failure's code, naming the simulation. */
static int note(int rc, int i, int *first_rc, char *msg, size_t cap)
{
  if (rc != MSOCL_OK && *first_rc == MSOCL_OK) {
    *first_rc = rc;
    snprintf(msg, cap, "batch simulation %d: %s", i, msocl_last_error());
  }
  return rc;
}

int msocl_batch_step(msocl_batch *b, int n)
{
  msocl__clear_error();
  if (!b)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "batch is NULL");
  if (n < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "step count %d is negative", n);
  int first_rc = MSOCL_OK;
  char msg[1024] = "";
  memset(b->bad, 0, (size_t)b->count * sizeof *b->bad);
  const int every = b->sims[0]->o.check_every;
  for (int i = 0; i < b->count; i++) /* the call's pin targets */
    msocl__motion_call(b->sims[i], n);
  for (int done = 0; done < n;) {
    /* up to the first check due (the simulations' counts can differ: a
     * restore after a blow-up starts one's count again) */
    int batch = n - done;
    for (int i = 0; every > 0 && i < b->count; i++)
      if (!b->bad[i] && msocl__batch_room(b->sims[i]) < batch)
        batch = msocl__batch_room(b->sims[i]);
    for (int i = 0; i < b->count; i++) /* queue everyone's steps */
      if (!b->bad[i])
        b->bad[i] = note(every > 0 ? msocl__batch_begin(b->sims[i], batch)
                                   : msocl__sim_steps(b->sims[i], batch),
                         i, &first_rc, msg, sizeof msg) != MSOCL_OK;
    for (int i = 0; i < b->count; i++) /* then check (or wait for) them */
      if (!b->bad[i])
        b->bad[i] = note(every > 0 ? msocl__batch_end(b->sims[i])
                                   : msocl__sim_finish(b->sims[i]),
                         i, &first_rc, msg, sizeof msg) != MSOCL_OK;
    done += batch;
  }
  for (int i = 0; i < b->count; i++)
    if (!b->bad[i])
      b->bad[i] = note(msocl__sim_finish(b->sims[i]), i, &first_rc, msg,
                       sizeof msg) != MSOCL_OK;
  for (int i = 0; i < b->count; i++) { /* implicit Euler's missed CGs */
    int rc = msocl__cg_report(b->sims[i], b->bad[i] ? first_rc : MSOCL_OK, n);
    if (!b->bad[i])
      note(rc, i, &first_rc, msg, sizeof msg);
  }
  return first_rc == MSOCL_OK ? MSOCL_OK : msocl__fail(first_rc, "%s", msg);
}

int msocl_batch_count(const msocl_batch *b, int *count)
{
  if (!b || !count)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "batch or out-pointer is NULL");
  *count = b->count;
  return MSOCL_OK;
}

int msocl_batch_sim(msocl_batch *b, int i, msocl_sim **s)
{
  if (!b || !s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "batch or out-pointer is NULL");
  if (i < 0 || i >= b->count)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "simulation %d out of range [0, %d)", i, b->count);
  *s = b->sims[i];
  return MSOCL_OK;
}

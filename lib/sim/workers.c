/* A small pool of host threads, one per device of a split simulation.
 * Some OpenCL drivers do a command's work in the thread that enqueues or
 * waits for it (PoCL's 'basic' device), and a blocking call on one device
 * stalls the thread that would feed the next: one thread per device lets
 * every device work at once whatever its driver does. Job i runs on
 * thread i; job 0 runs on the caller, which saves a hand-off. */
#include "config.h"
#include "sim.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct msocl__workers {
  int n;
  pthread_t th[MSOCL__MAX_DEVICES];
  int started; /* threads 1 .. started-1 exist */
  pthread_mutex_t mu;
  pthread_cond_t go, done;
  unsigned long gen; /* bumped for every job */
  int remaining;     /* threads still on the current job */
  int stop;
  int (*fn)(void *ctx, int i);
  void *ctx;
  int rc[MSOCL__MAX_DEVICES];
  char msg[MSOCL__MAX_DEVICES][512]; /* a failed job's message: the
                                        last-error text is per thread */
};

static void run_one(struct msocl__workers *w, int i)
{
  w->rc[i] = w->fn(w->ctx, i);
  if (w->rc[i] != MSOCL_OK)
    snprintf(w->msg[i], sizeof w->msg[i], "%s", msocl_last_error());
}

struct start {
  struct msocl__workers *w;
  int i;
};

static void *loop(void *arg)
{
  struct start st = *(struct start *)arg;
  free(arg);
  struct msocl__workers *w = st.w;
  unsigned long seen = 0;
  pthread_mutex_lock(&w->mu);
  for (;;) {
    while (!w->stop && w->gen == seen)
      pthread_cond_wait(&w->go, &w->mu);
    if (w->stop)
      break;
    seen = w->gen;
    pthread_mutex_unlock(&w->mu);
    run_one(w, st.i);
    pthread_mutex_lock(&w->mu);
    if (--w->remaining == 0)
      pthread_cond_signal(&w->done);
  }
  pthread_mutex_unlock(&w->mu);
  return NULL;
}

void msocl__workers_destroy(struct msocl__workers *w)
{
  if (!w)
    return;
  pthread_mutex_lock(&w->mu);
  w->stop = 1;
  pthread_cond_broadcast(&w->go);
  pthread_mutex_unlock(&w->mu);
  for (int i = 1; i < w->started; i++)
    pthread_join(w->th[i], NULL);
  pthread_cond_destroy(&w->go);
  pthread_cond_destroy(&w->done);
  pthread_mutex_destroy(&w->mu);
  free(w);
}

int msocl__workers_create(struct msocl__workers **out, int n)
{
  *out = NULL;
  if (n < 1 || n > MSOCL__MAX_DEVICES)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "%d worker threads", n);
  struct msocl__workers *w = calloc(1, sizeof *w);
  if (!w)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "worker threads");
  w->n = n;
  w->started = 1;
  pthread_mutex_init(&w->mu, NULL);
  pthread_cond_init(&w->go, NULL);
  pthread_cond_init(&w->done, NULL);
  for (int i = 1; i < n; i++) {
    struct start *st = malloc(sizeof *st);
    if (st) {
      st->w = w;
      st->i = i;
    }
    int e = st ? pthread_create(&w->th[i], NULL, loop, st) : -1;
    if (e != 0) {
      free(st);
      msocl__workers_destroy(w);
      return msocl__fail(MSOCL_ERR_NO_MEMORY,
                         "could not start worker thread %d of %d", i, n);
    }
    w->started = i + 1;
  }
  *out = w;
  return MSOCL_OK;
}

int msocl__workers_run(struct msocl__workers *w, int (*fn)(void *ctx, int i),
                       void *ctx)
{
  pthread_mutex_lock(&w->mu);
  w->fn = fn;
  w->ctx = ctx;
  w->remaining = w->n - 1;
  w->gen++;
  pthread_cond_broadcast(&w->go);
  pthread_mutex_unlock(&w->mu);
  run_one(w, 0);
  pthread_mutex_lock(&w->mu);
  while (w->remaining > 0)
    pthread_cond_wait(&w->done, &w->mu);
  pthread_mutex_unlock(&w->mu);
  for (int i = 0; i < w->n; i++)
    if (w->rc[i] != MSOCL_OK)
      return msocl__fail(w->rc[i], "device part %d: %s", i, w->msg[i]);
  return MSOCL_OK;
}

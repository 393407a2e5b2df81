/* The conjugate gradients of an implicit Euler step, run on the host over
 * the engines' operations (schedule.h), on one engine or
 * over a split: each dot product's partials are added up here in double,
 * engine by engine in point order, so a split sums as one engine does. */
#include "config.h"
#include "schedule.h"

#include <math.h>

#define TRY MSOCL__TRY

static const struct msocl__cg_ops *const ops = &msocl__planes_cg;

enum { RHS, APPLY, STEP };

/* Queues product `which` (STEP: given alpha) on every engine, then sums
 * their partials in order. */
static int reduce_all(msocl__engine *const *e, int parts, int which,
                      float alpha, double *sum)
{
  *sum = 0.0;
  for (int d = 0; d < parts; d++) {
    TRY(which == RHS     ? ops->rhs(e[d])
        : which == APPLY ? ops->apply(e[d])
                         : ops->step(e[d], alpha));
  }
  for (int d = 0; d < parts; d++)
    TRY(ops->collect(e[d], sum));
  return MSOCL_OK;
}

/* The worst miss is the largest residual, NaN above all. */
static void cg_note(msocl__engine *s, int converged)
{
  if (converged)
    return;
  if (s->cg_missed++ == 0 ||
      (!isnan(s->cg_worst_residual) &&
       (isnan(s->cg_residual) || s->cg_residual > s->cg_worst_residual))) {
    s->cg_worst_residual = s->cg_residual;
    s->cg_worst_iterations = s->cg_iterations;
  }
}

/* The CG of one step over `parts` engines; between products, `exchange`
 * brings every engine the halo of the search direction p. */
int msocl__implicit_cg(msocl__engine *const *e, int parts,
                       int (*exchange)(void *ctx), void *ctx)
{
  double bb, rr, pap, rr_new;
  TRY(reduce_all(e, parts, RHS, 0.0f, &bb));
  if (exchange)
    TRY(exchange(ctx));
  rr = bb;
  const msocl_sim_options *o = &e[0]->o;
  const double goal = (double)o->cg_tolerance * (double)o->cg_tolerance * bb;
  int it = 0;
  while (rr > goal && it < o->cg_max_iterations) {
    TRY(reduce_all(e, parts, APPLY, 0.0f, &pap));
    if (!(pap > 0.0))
      break; /* p = 0 or a non-SPD round-off: x is as good as it gets */
    TRY(reduce_all(e, parts, STEP, (float)(rr / pap), &rr_new));
    for (int d = 0; d < parts; d++)
      TRY(ops->direction(e[d], (float)(rr_new / rr)));
    if (exchange)
      TRY(exchange(ctx));
    rr = rr_new;
    it++;
  }
  for (int d = 0; d < parts; d++) {
    msocl__engine *s = e[d];
    s->cg_iterations = it;
    s->cg_residual = bb > 0.0 ? sqrt(rr / bb) : 0.0;
    cg_note(s, rr <= goal); /* NaN: not converged */
    TRY(ops->finish(s));
  }
  return MSOCL_OK;
}

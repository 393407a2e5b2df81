/* Implicit (backward) Euler, Baraff-Witkin form: builds the right-hand
 * side, runs conjugate gradients on the device (matrix-free products,
 * work-group reductions added up here in double), then moves the points.
 * The kernels and the system are described in kernels/implicit.cl. */
#include "config.h"
#include "sim.h"

#include <math.h>

static const size_t group = 64;

/* Queues kernel k over the engine's points in work-groups of 64 (the
 * points past n, in the last group, do nothing). */
static int launch64(msocl__engine *s, int k)
{
  const size_t global = 64 * s->groups;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[k], 1, &s->offset,
                                   &global, &group, 0, NULL, NULL));
  return MSOCL_OK;
}

#define TRY MSOCL__TRY

int msocl__implicit_setup(msocl__engine *s)
{
  const cl_uint c = s->nconn;
  const float dt = s->o.dt;
  cl_mem x = s->stage_p[0], r = s->stage_p[1], p = s->stage_v[0],
         ap = s->stage_v[1];
  cl_kernel k = s->k[MSOCL__K_IE_RHS];
  TRY(msocl__arg_mem(k, c + 2, x));
  TRY(msocl__arg_mem(k, c + 3, r));
  TRY(msocl__arg_mem(k, c + 4, p));
  TRY(msocl__arg_mem(k, c + 5, s->inv_mass));
  MSOCL__CL(clSetKernelArg(k, c + 6, sizeof s->gravity, &s->gravity));
  TRY(msocl__arg_float(k, c + 7, s->viscous));
  TRY(msocl__arg_float(k, c + 8, dt));
  TRY(msocl__arg_mem(k, c + 9, s->partial));
  TRY(msocl__arg_int(k, c + 10, s->n));
  k = s->k[MSOCL__K_IE_APPLY];
  TRY(msocl__arg_mem(k, c + 1, p));
  TRY(msocl__arg_mem(k, c + 2, ap));
  TRY(msocl__arg_mem(k, c + 3, s->inv_mass));
  TRY(msocl__arg_float(k, c + 4, s->viscous));
  TRY(msocl__arg_float(k, c + 5, dt));
  TRY(msocl__arg_mem(k, c + 6, s->partial));
  TRY(msocl__arg_int(k, c + 7, s->n));
  k = s->k[MSOCL__K_CG_STEP];
  TRY(msocl__arg_mem(k, 0, x));
  TRY(msocl__arg_mem(k, 1, r));
  TRY(msocl__arg_mem(k, 2, p));
  TRY(msocl__arg_mem(k, 3, ap));
  TRY(msocl__arg_mem(k, 5, s->partial));
  TRY(msocl__arg_int(k, 6, s->n));
  k = s->k[MSOCL__K_CG_DIR];
  TRY(msocl__arg_mem(k, 0, p));
  TRY(msocl__arg_mem(k, 1, r));
  TRY(msocl__arg_int(k, 3, s->n));
  k = s->k[MSOCL__K_IE_FINISH];
  TRY(msocl__arg_mem(k, 2, x));
  TRY(msocl__arg_float(k, 4, s->air));
  TRY(msocl__arg_float(k, 5, dt));
  TRY(msocl__arg_mem(k, 6, s->col));
  TRY(msocl__arg_int(k, 7, s->ncol));
  TRY(msocl__arg_int(k, 8, s->n));
  return MSOCL_OK;
}

/* Runs kernel k on every engine, then sums their partials in order. */
static int reduce_all(msocl__engine *const *e, int parts, int k, double *sum)
{
  *sum = 0.0;
  for (int d = 0; d < parts; d++)
    TRY(launch64(e[d], k));
  for (int d = 0; d < parts; d++)
    TRY(msocl__implicit_collect(e[d], sum));
  return MSOCL_OK;
}

static int set_float_all(msocl__engine *const *e, int parts, int k,
                         cl_uint arg, float v)
{
  for (int d = 0; d < parts; d++)
    TRY(msocl__arg_float(e[d]->k[k], arg, v));
  return MSOCL_OK;
}

/* The CG of one step over `parts` engines; between products, `exchange`
 * brings every engine the halo of the search direction p. */
int msocl__implicit_cg(msocl__engine *const *e, int parts,
                       int (*exchange)(void *ctx), void *ctx)
{
  for (int d = 0; d < parts; d++) {
    const cl_uint c = e[d]->nconn;
    const int r = e[d]->r;
    TRY(msocl__arg_mem(e[d]->k[MSOCL__K_IE_RHS], c, e[d]->pos[r]));
    TRY(msocl__arg_mem(e[d]->k[MSOCL__K_IE_RHS], c + 1, e[d]->vel[r]));
    TRY(msocl__arg_mem(e[d]->k[MSOCL__K_IE_APPLY], c, e[d]->pos[r]));
  }
  double bb, rr, pap, rr_new;
  TRY(reduce_all(e, parts, MSOCL__K_IE_RHS, &bb));
  if (exchange)
    TRY(exchange(ctx));
  rr = bb;
  const msocl_sim_options *o = &e[0]->o;
  const double goal = (double)o->cg_tolerance * (double)o->cg_tolerance * bb;
  int it = 0;
  while (rr > goal && it < o->cg_max_iterations) {
    TRY(reduce_all(e, parts, MSOCL__K_IE_APPLY, &pap));
    if (!(pap > 0.0))
      break; /* p = 0 or a non-SPD round-off: x is as good as it gets */
    TRY(set_float_all(e, parts, MSOCL__K_CG_STEP, 4, (float)(rr / pap)));
    TRY(reduce_all(e, parts, MSOCL__K_CG_STEP, &rr_new));
    TRY(set_float_all(e, parts, MSOCL__K_CG_DIR, 2, (float)(rr_new / rr)));
    for (int d = 0; d < parts; d++)
      TRY(msocl__launch(e[d], MSOCL__K_CG_DIR));
    if (exchange)
      TRY(exchange(ctx));
    rr = rr_new;
    it++;
  }
  for (int d = 0; d < parts; d++) {
    msocl__engine *s = e[d];
    const int r = s->r, w = 1 - r;
    s->cg_iterations = it;
    s->cg_residual = bb > 0.0 ? sqrt(rr / bb) : 0.0;
    msocl__cg_note(s, rr <= goal); /* NaN: not converged */
    cl_kernel k = s->k[MSOCL__K_IE_FINISH];
    TRY(msocl__arg_mem(k, 0, s->pos[r]));
    TRY(msocl__arg_mem(k, 1, s->vel[r]));
    TRY(msocl__arg_mem(k, 3, s->vel[w]));
    TRY(msocl__launch(s, MSOCL__K_IE_FINISH));
  }
  return MSOCL_OK;
}

/* The worst miss is the largest residual, NaN above all. */
void msocl__cg_note(msocl__engine *s, int converged)
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

/* Every step is taken even when its CG missed: the state then holds the
 * solver's last iterate, and the code says so once, for the whole call. */
int msocl__cg_report(msocl_sim *s, int rc, int n)
{
  const msocl__engine *e = s->part[0];
  const int missed = e->cg_missed, it = e->cg_worst_iterations;
  const double res = e->cg_worst_residual;
  for (int d = 0; d < s->nparts; d++)
    s->part[d]->cg_missed = 0;
  if (rc != MSOCL_OK || missed == 0)
    return rc;
  return msocl__fail(
      MSOCL_ERR_NO_CONVERGENCE,
      "implicit Euler: CG stopped above the tolerance %g in %d of %d steps "
      "(worst: relative residual %g after %d iterations, cap %d); the steps "
      "were taken with the solver's last iterate",
      (double)s->o.cg_tolerance, missed, n, res, it, s->o.cg_max_iterations);
}

/* Writes the new velocity to vel[1 - r]; the caller's position pass moves
 * the points. */
int msocl__implicit_velocity(msocl__engine *s)
{
  return msocl__implicit_cg(&s, 1, NULL, NULL);
}

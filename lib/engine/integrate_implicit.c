/* Implicit (backward) Euler, Baraff-Witkin form, on the float4 engine:
 * the operations the host's CG (cg.c) runs - the right-hand side, matrix-free products and work-group
 * reductions, then the new velocities. The kernels and the system are
 * described in kernels/implicit.cl. */
#include "config.h"
#include "schedule.h"

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

/* The float4 engine's CG operations (schedule.h), over its range. */
static int rhs(msocl__engine *s)
{
  const int r = s->r;
  TRY(msocl__set_mem(s, MSOCL__K_IE_RHS, "pos", s->pos[r]));
  TRY(msocl__set_mem(s, MSOCL__K_IE_RHS, "vel", s->vel[r]));
  TRY(msocl__set_mem(s, MSOCL__K_IE_APPLY, "pos", s->pos[r]));
  return launch64(s, MSOCL__K_IE_RHS);
}

static int apply(msocl__engine *s)
{
  return launch64(s, MSOCL__K_IE_APPLY);
}

static int step(msocl__engine *s, float alpha)
{
  TRY(msocl__set_float(s, MSOCL__K_CG_STEP, "alpha", alpha));
  return launch64(s, MSOCL__K_CG_STEP);
}

static int direction(msocl__engine *s, float beta)
{
  TRY(msocl__set_float(s, MSOCL__K_CG_DIR, "beta", beta));
  return msocl__launch(s, MSOCL__K_CG_DIR);
}

static int finish(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  TRY(msocl__set_mem(s, MSOCL__K_IE_FINISH, "pos", s->pos[r]));
  TRY(msocl__set_mem(s, MSOCL__K_IE_FINISH, "vel", s->vel[r]));
  TRY(msocl__set_mem(s, MSOCL__K_IE_FINISH, "vel_out", s->vel[w]));
  return msocl__launch(s, MSOCL__K_IE_FINISH);
}

const struct msocl__cg_ops msocl__float4_cg = {
    rhs, apply, step, direction, msocl__implicit_collect, finish};

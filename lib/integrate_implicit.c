/* Implicit (backward) Euler, Baraff-Witkin form, on the float4 engine:
 * the kernels' fixed arguments and the operations the host's CG (cg.c)
 * runs - the right-hand side, matrix-free products and work-group
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

/* The float4 engine's CG operations (schedule.h), over its range. */
static int rhs(msocl__engine *s)
{
  const cl_uint c = s->nconn;
  const int r = s->r;
  TRY(msocl__arg_mem(s->k[MSOCL__K_IE_RHS], c, s->pos[r]));
  TRY(msocl__arg_mem(s->k[MSOCL__K_IE_RHS], c + 1, s->vel[r]));
  TRY(msocl__arg_mem(s->k[MSOCL__K_IE_APPLY], c, s->pos[r]));
  return launch64(s, MSOCL__K_IE_RHS);
}

static int apply(msocl__engine *s)
{
  return launch64(s, MSOCL__K_IE_APPLY);
}

static int step(msocl__engine *s, float alpha)
{
  TRY(msocl__arg_float(s->k[MSOCL__K_CG_STEP], 4, alpha));
  return launch64(s, MSOCL__K_CG_STEP);
}

static int direction(msocl__engine *s, float beta)
{
  TRY(msocl__arg_float(s->k[MSOCL__K_CG_DIR], 2, beta));
  return msocl__launch(s, MSOCL__K_CG_DIR);
}

static int finish(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  cl_kernel k = s->k[MSOCL__K_IE_FINISH];
  TRY(msocl__arg_mem(k, 0, s->pos[r]));
  TRY(msocl__arg_mem(k, 1, s->vel[r]));
  TRY(msocl__arg_mem(k, 3, s->vel[w]));
  return msocl__launch(s, MSOCL__K_IE_FINISH);
}

const struct msocl__cg_ops msocl__float4_cg = {
    rhs, apply, step, direction, msocl__implicit_collect, finish};

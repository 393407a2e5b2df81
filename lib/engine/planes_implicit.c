/* Implicit Euler in planes (kernels/planes_implicit.cl): the right-hand
 * side, the conjugate gradients' products and the new velocities over
 * the planes, for the host's CG (cg.c). Every dot product is summed by
 * msocl_sum_points from the points' terms in float4 order, so the partials
 * the host adds, and the step, are bitwise float4's. The search state:
 * x, r in RK4's stage positions, d, Ad in its stage velocities, the
 * points' terms in its first sum. */
#include "config.h"
#include "planes.h"
#include "schedule.h"

#define TRY MSOCL__TRY

/* The search state's buffers, by the names the kernels give them, in
 * the implicit kernels that have them (planes.c sets the rest). */
int msocl__pl_implicit_args(msocl__engine *s)
{
  const cl_mem x = s->pl_sp[0], r = s->pl_sp[1], d = s->pl_sv[0],
               ap = s->pl_sv[1], dots = s->pl_sum[0];
  const struct msocl__named state[] = {
      {"x_out", sizeof x, &x},   {"r_out", sizeof r, &r},
      {"d_out", sizeof d, &d},   {"xs", sizeof x, &x},
      {"r", sizeof r, &r},       {"d", sizeof d, &d},
      {"ap", sizeof ap, &ap},    {"dv", sizeof x, &x},
      {"dots", sizeof dots, &dots},
      {"partial", sizeof s->partial, &s->partial}};
  const int k[6] = {PL_IE_RHS,  PL_IE_APPLY,  PL_CG_STEP,
                    PL_CG_DIR,  PL_IE_FINISH, PL_SUM};
  for (int q = 0; q < 6; q++)
    TRY(msocl__pl_named(s, s->pl_k[k[q]], state,
                        (int)(sizeof state / sizeof state[0])));
  return MSOCL_OK;
}

/* Kernel k over the planes, then the terms of the engine's own points
 * (a split's start at multiples of 64) summed as float4's work-groups of
 * 64 would, for the CG to collect. */
static int reduce(msocl__engine *s, int k)
{
  TRY(msocl__pl_launch(s, k));
  const size_t group = 64, global = 64 * s->groups, from = (size_t)s->lo;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->pl_k[PL_SUM], 1, &from,
                                   &global, &group, 0, NULL, NULL));
  return MSOCL_OK;
}

static int set_float(msocl__engine *s, int k, const char *name, float v)
{
  return msocl__pl_arg(s, s->pl_k[k], name, sizeof v, &v);
}

/* The CG's operations (schedule.h) from plane set r = pl_set into v[w]. */
static int rhs(msocl__engine *s)
{
  const int r = s->pl_set;
  TRY(msocl__pl_mem(s, s->pl_k[PL_IE_RHS], "p", s->pl_p[r]));
  TRY(msocl__pl_mem(s, s->pl_k[PL_IE_RHS], "v", s->pl_v[r]));
  TRY(msocl__pl_mem(s, s->pl_k[PL_IE_APPLY], "p", s->pl_p[r]));
  return reduce(s, PL_IE_RHS);
}

static int apply(msocl__engine *s)
{
  return reduce(s, PL_IE_APPLY);
}

static int step(msocl__engine *s, float alpha)
{
  TRY(set_float(s, PL_CG_STEP, "alpha", alpha));
  return reduce(s, PL_CG_STEP);
}

static int direction(msocl__engine *s, float beta)
{
  TRY(set_float(s, PL_CG_DIR, "beta", beta));
  return msocl__pl_launch(s, PL_CG_DIR);
}

static int finish(msocl__engine *s)
{
  const int r = s->pl_set, w = 1 - r;
  cl_kernel k = s->pl_k[PL_IE_FINISH];
  TRY(msocl__pl_mem(s, k, "p", s->pl_p[r]));
  TRY(msocl__pl_mem(s, k, "v", s->pl_v[r]));
  TRY(msocl__pl_mem(s, k, "v_out", s->pl_v[w]));
  return msocl__pl_launch(s, PL_IE_FINISH);
}

const struct msocl__cg_ops msocl__planes_cg = {
    rhs, apply, step, direction, msocl__implicit_collect, finish};

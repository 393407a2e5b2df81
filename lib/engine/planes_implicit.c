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

int msocl__pl_implicit_args(msocl__engine *s)
{
  cl_mem x = s->pl_sp[0], r = s->pl_sp[1], d = s->pl_sv[0], ap = s->pl_sv[1],
         dots = s->pl_sum[0];
  const float dt = s->o.dt;
  cl_uint c;
  /* rhs: connectivity, p, v, x, r, d, dots, aux, shape, gravity, viscous,
   * dt */
  cl_kernel k = s->pl_k[PL_IE_RHS];
  TRY(msocl__pl_conn(s, k, &c));
  const cl_mem rhs[4] = {x, r, d, dots};
  for (cl_uint q = 0; q < 4; q++)
    TRY(msocl__pl_arg(s, k, c + 2 + q, sizeof rhs[q], &rhs[q]));
  TRY(msocl__pl_arg(s, k, c + 6, sizeof s->pl_aux, &s->pl_aux));
  TRY(msocl__pl_shape(s, k, c + 7, 0));
  TRY(msocl__pl_arg(s, k, c + 10, sizeof s->gravity, &s->gravity));
  TRY(msocl__pl_arg(s, k, c + 11, sizeof(float), &s->viscous));
  TRY(msocl__pl_arg(s, k, c + 12, sizeof(float), &dt));
  /* apply: connectivity, p, d, ap, dots, aux, shape, viscous, dt */
  k = s->pl_k[PL_IE_APPLY];
  TRY(msocl__pl_conn(s, k, &c));
  const cl_mem apply[3] = {d, ap, dots};
  for (cl_uint q = 0; q < 3; q++)
    TRY(msocl__pl_arg(s, k, c + 1 + q, sizeof apply[q], &apply[q]));
  TRY(msocl__pl_arg(s, k, c + 4, sizeof s->pl_aux, &s->pl_aux));
  TRY(msocl__pl_shape(s, k, c + 5, 0));
  TRY(msocl__pl_arg(s, k, c + 8, sizeof(float), &s->viscous));
  TRY(msocl__pl_arg(s, k, c + 9, sizeof(float), &dt));
  /* CG step: x, r, d, ap, dots, nx and shape, alpha */
  k = s->pl_k[PL_CG_STEP];
  const cl_mem step[5] = {x, r, d, ap, dots};
  for (cl_uint q = 0; q < 5; q++)
    TRY(msocl__pl_arg(s, k, q, sizeof step[q], &step[q]));
  TRY(msocl__pl_shape(s, k, 5, 1));
  /* direction: d, r, nx and shape, beta */
  k = s->pl_k[PL_CG_DIR];
  TRY(msocl__pl_arg(s, k, 0, sizeof d, &d));
  TRY(msocl__pl_arg(s, k, 1, sizeof r, &r));
  TRY(msocl__pl_shape(s, k, 2, 1));
  /* finish: p, v, dv, v_out, aux, nx and shape, air, dt, col */
  k = s->pl_k[PL_IE_FINISH];
  TRY(msocl__pl_arg(s, k, 2, sizeof x, &x));
  TRY(msocl__pl_arg(s, k, 4, sizeof s->pl_aux, &s->pl_aux));
  TRY(msocl__pl_shape(s, k, 5, 1));
  TRY(msocl__pl_arg(s, k, 9, sizeof(float), &s->air));
  TRY(msocl__pl_arg(s, k, 10, sizeof(float), &dt));
  TRY(msocl__pl_arg(s, k, 11, sizeof s->pl_col, &s->pl_col));
  /* the sums: dots, partial, n */
  k = s->pl_k[PL_SUM];
  TRY(msocl__pl_arg(s, k, 0, sizeof dots, &dots));
  TRY(msocl__pl_arg(s, k, 1, sizeof s->partial, &s->partial));
  return msocl__pl_arg(s, k, 2, sizeof(int), &s->n);
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

static int set_float(msocl__engine *s, int k, cl_uint i, float v)
{
  return msocl__pl_arg(s, s->pl_k[k], i, sizeof v, &v);
}

/* The CG's operations (schedule.h) from plane set r = pl_set into v[w]. */
static int rhs(msocl__engine *s)
{
  const cl_uint c = s->pl_conn;
  const int r = s->pl_set;
  TRY(msocl__pl_arg(s, s->pl_k[PL_IE_RHS], c, sizeof s->pl_p[r], &s->pl_p[r]));
  TRY(msocl__pl_arg(s, s->pl_k[PL_IE_RHS], c + 1, sizeof s->pl_v[r],
                    &s->pl_v[r]));
  TRY(msocl__pl_arg(s, s->pl_k[PL_IE_APPLY], c, sizeof s->pl_p[r],
                    &s->pl_p[r]));
  return reduce(s, PL_IE_RHS);
}

static int apply(msocl__engine *s)
{
  return reduce(s, PL_IE_APPLY);
}

static int step(msocl__engine *s, float alpha)
{
  TRY(set_float(s, PL_CG_STEP, 9, alpha));
  return reduce(s, PL_CG_STEP);
}

static int direction(msocl__engine *s, float beta)
{
  TRY(set_float(s, PL_CG_DIR, 6, beta));
  return msocl__pl_launch(s, PL_CG_DIR);
}

static int finish(msocl__engine *s)
{
  const int r = s->pl_set, w = 1 - r;
  cl_kernel k = s->pl_k[PL_IE_FINISH];
  TRY(msocl__pl_arg(s, k, 0, sizeof s->pl_p[r], &s->pl_p[r]));
  TRY(msocl__pl_arg(s, k, 1, sizeof s->pl_v[r], &s->pl_v[r]));
  TRY(msocl__pl_arg(s, k, 3, sizeof s->pl_v[w], &s->pl_v[w]));
  return msocl__pl_launch(s, PL_IE_FINISH);
}

const struct msocl__cg_ops msocl__planes_cg = {
    rhs, apply, step, direction, msocl__implicit_collect, finish};

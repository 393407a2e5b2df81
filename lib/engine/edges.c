/* The EDGES layout's passes (kernels/edges.cl): the per-spring pass writes
 * each spring's force coefficients once, the per-point pass sums them over
 * the point's springs in a fixed order (the layout's table and list),
 * kicks and moves the point: a step in two launches.
 * No atomics: the sum's order is BUFFER's, so is its result. */
#include "config.h"
#include "engine.h"

#define TRY MSOCL__TRY

int msocl__edges_buffers(msocl__engine *s)
{
  const size_t ns = 8 * (size_t)s->lay.nblocks;
  s->edge_work = ((size_t)s->lay.nblocks + 63) / 64 * 64;
  s->edge_points = ((size_t)(s->n + 7) / 8 + 63) / 64 * 64;
  s->edge_global = ((size_t)s->lay.nsprings + 63) / 64 * 64;
  if (s->edge_global == 0)
    s->edge_global = 64;
  s->edge_groups = s->edge_global / 64;
  for (int q = 0; q < 2; q++) {
    /* the dashpots' coefficients only where there are dashpots */
    size_t bytes = (q == 0 || s->damped ? ns : 1) * sizeof(float);
    cl_int e;
    s->edge_coef[q] =
        clCreateBuffer(s->dev->ctx, CL_MEM_READ_WRITE, bytes, NULL, &e);
    if (e != CL_SUCCESS)
      return msocl__fail(e, "clCreateBuffer(%zu bytes) on %s: %s", bytes,
                         s->dev->info.name, msocl_err_name(e));
  }
  return MSOCL_OK;
}

int msocl__edges_setup(msocl__engine *s)
{
  cl_kernel k = s->k[MSOCL__K_EDGES_FORCE];
  TRY(msocl__arg_mem(k, 0, s->lay.con));
  TRY(msocl__arg_mem(k, 1, s->lay.rk));
  TRY(msocl__arg_mem(k, 2, s->lay.damp));
  TRY(msocl__arg_mem(k, 5, s->edge_coef[0]));
  TRY(msocl__arg_mem(k, 6, s->edge_coef[1]));
  TRY(msocl__arg_int(k, 7, s->lay.nblocks));
  k = s->k[MSOCL__K_EDGES_VEL];
  TRY(msocl__arg_mem(k, 0, s->lay.tab));
  TRY(msocl__arg_mem(k, 1, s->lay.run));
  TRY(msocl__arg_int(k, 2, s->lay.width));
  TRY(msocl__arg_mem(k, 3, s->lay.inc_off));
  TRY(msocl__arg_mem(k, 4, s->lay.inc));
  TRY(msocl__arg_mem(k, 5, s->edge_coef[0]));
  TRY(msocl__arg_mem(k, 6, s->edge_coef[1]));
  TRY(msocl__arg_mem(k, 11, s->inv_mass));
  MSOCL__CL(clSetKernelArg(k, 12, sizeof s->gravity, &s->gravity));
  TRY(msocl__arg_float(k, 13, s->viscous));
  TRY(msocl__arg_float(k, 14, s->air));
  TRY(msocl__arg_float(k, 15, s->o.dt));
  TRY(msocl__arg_mem(k, 16, s->col));
  TRY(msocl__arg_int(k, 17, s->ncol));
  TRY(msocl__arg_int(k, 18, s->n));
  k = s->k[MSOCL__K_EDGES_ENERGY];
  TRY(msocl__arg_mem(k, 0, s->lay.con));
  TRY(msocl__arg_mem(k, 1, s->lay.rk));
  TRY(msocl__arg_mem(k, 2, s->lay.damp));
  TRY(msocl__arg_mem(k, 4, s->partial));
  return msocl__arg_int(k, 5, s->lay.nsprings);
}

int msocl__edges_velocity(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  cl_kernel f = s->k[MSOCL__K_EDGES_FORCE];
  TRY(msocl__arg_mem(f, 3, s->pos[r]));
  TRY(msocl__arg_mem(f, 4, s->vel[r]));
  /* groups of 64 on a CPU, as msocl__launch chooses for points */
  const size_t cpu = 64;
  MSOCL__CL(clEnqueueNDRangeKernel(
      s->dev->queue, f, 1, NULL, &s->edge_work,
      s->dev->info.type == MSOCL_DEVICE_CPU ? &cpu : NULL, 0, NULL, NULL));
  cl_kernel k = s->k[MSOCL__K_EDGES_VEL];
  TRY(msocl__arg_mem(k, 7, s->pos[r]));
  TRY(msocl__arg_mem(k, 8, s->vel[r]));
  TRY(msocl__arg_mem(k, 9, s->pos[w]));
  TRY(msocl__arg_mem(k, 10, s->vel[w]));
  /* eight points a work-item */
  MSOCL__CL(clEnqueueNDRangeKernel(
      s->dev->queue, k, 1, NULL, &s->edge_points,
      s->dev->info.type == MSOCL_DEVICE_CPU ? &cpu : NULL, 0, NULL, NULL));
  return MSOCL_OK;
}

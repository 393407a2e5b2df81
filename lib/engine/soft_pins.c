/* Soft pins in the planes engine (kernels/planes_pins.cl msocl_soft_pins):
 * listed points pulled toward anchors by springs of one stiffness, as a
 * velocity change before each step (first order, as wind and fields).
 * Anchors move from `from` to `to` over a moving call (the fraction set
 * before each of its steps) and rest at `to` otherwise. */
#include "config.h"
#include "engine.h"

#include <math.h>
#include <stdlib.h>

#define TRY MSOCL__TRY

static int buffers(msocl__engine *s, int m)
{
  if (!s->soft_k) {
    cl_program prog;
    MSOCL__CL(clGetKernelInfo(s->pl_k[0], CL_KERNEL_PROGRAM, sizeof prog,
                              &prog, NULL));
    TRY(msocl__kernel_make(s->dev, prog, "msocl_soft_pins", &s->soft_k));
  }
  if (m <= s->soft_cap)
    return MSOCL_OK;
  cl_mem *b[3] = {&s->soft_at, &s->soft_from, &s->soft_to};
  const size_t bytes[3] = {(size_t)m * sizeof(cl_int),
                           3 * (size_t)m * sizeof(float),
                           3 * (size_t)m * sizeof(float)};
  s->soft_cap = 0;
  for (int q = 0; q < 3; q++) {
    if (*b[q])
      clReleaseMemObject(*b[q]);
    int rc = MSOCL_OK;
    *b[q] = msocl__buffer(s->dev, CL_MEM_READ_WRITE, bytes[q], NULL,
                          "soft pins", &rc);
    TRY(rc);
  }
  s->soft_cap = m;
  return MSOCL_OK;
}

/* The largest inverse mass of the engine's points k[0..m), from the host
 * copy the engine keeps: masses never change, and a device read here
 * would cost O(n) every frame that moves the anchors. */
static double largest_inverse_mass(const msocl__engine *s, const int *k, int m)
{
  double w = 0.0;
  for (int q = 0; q < m; q++)
    w = s->inv_host[k[q]] > w ? s->inv_host[k[q]] : w;
  return w;
}

int msocl__soft_set(msocl__engine *s, int m, const int *k, const float *xyz,
                    float stiffness, int move)
{
  if (m == 0) {
    s->soft_m = 0;
    return MSOCL_OK;
  }
  const double w = largest_inverse_mass(s, k, m);
  /* alone, the point and its anchor are an oscillator of w^2 = k / m:
   * a first-order kick holds while dt w stays well inside 2 */
  const double h2 = (double)s->o.dt * s->o.dt * stiffness * w;
  if (h2 > 1.0)
    return msocl__fail(MSOCL_ERR_UNSTABLE,
                       "soft pins: stiffness %g N/m on a point of %g kg "
                       "oscillates at dt w = %.3g, unstable at dt %g s "
                       "(keep k dt^2 / m below 1: k <= %g N/m)",
                       (double)stiffness, 1.0 / w, sqrt(h2), (double)s->o.dt,
                       1.0 / ((double)s->o.dt * s->o.dt * w));
  TRY(buffers(s, m));
  int *at = malloc((size_t)m * sizeof *at);
  if (!at)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "soft pins");
  for (int q = 0; q < m; q++)
    at[q] = msocl__pl_address(s, k[q]);
  cl_command_queue qu = s->dev->queue;
  const size_t b3 = 3 * (size_t)m * sizeof(float);
  /* a move keeps the old anchors (where they rest: `to`) as the start */
  cl_int e = move ? clEnqueueCopyBuffer(qu, s->soft_to, s->soft_from, 0, 0, b3,
                                        0, NULL, NULL)
                  : clEnqueueWriteBuffer(qu, s->soft_from, CL_FALSE, 0, b3,
                                         xyz, 0, NULL, NULL);
  if (e == CL_SUCCESS)
    e = clEnqueueWriteBuffer(qu, s->soft_to, CL_FALSE, 0, b3, xyz, 0, NULL,
                             NULL);
  if (e == CL_SUCCESS)
    e = clEnqueueWriteBuffer(qu, s->soft_at, CL_TRUE, 0,
                             (size_t)m * sizeof *at, at, 0, NULL, NULL);
  free(at);
  if (e != CL_SUCCESS)
    return msocl__fail(e, "writing soft pins: %s", msocl_err_name(e));
  cl_kernel kk = s->soft_k;
  TRY(msocl__arg_mem(s, kk, "aux", s->pl_aux));
  TRY(msocl__arg_mem(s, kk, "at", s->soft_at));
  TRY(msocl__arg_mem(s, kk, "from", s->soft_from));
  TRY(msocl__arg_mem(s, kk, "to", s->soft_to));
  TRY(msocl__arg_int(s, kk, "m", m));
  TRY(msocl__arg_int(s, kk, "plane", s->pl_plane));
  TRY(msocl__arg_float(s, kk, "dtk", s->o.dt * stiffness));
  s->soft_m = m;
  s->soft_f = move ? 0.0f : 1.0f;
  return MSOCL_OK;
}

void msocl__soft_fraction(msocl__engine *s, float f)
{
  s->soft_f = f;
}

int msocl__soft_pass(msocl__engine *s)
{
  if (s->soft_m == 0)
    return MSOCL_OK;
  cl_kernel k = s->soft_k;
  TRY(msocl__arg_mem(s, k, "p", s->pl_p[s->pl_set]));
  TRY(msocl__arg_mem(s, k, "v", s->pl_v[s->pl_set]));
  TRY(msocl__arg_float(s, k, "f", s->soft_f));
  /* groups of 64: PoCL builds its code again for each work-group size */
  const size_t global = ((size_t)s->soft_m + 63) / 64 * 64, group = 64;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 1, NULL, &global,
                                   &group, 0, NULL, NULL));
  return MSOCL_OK;
}

void msocl__soft_release(msocl__engine *s)
{
  msocl__kernel_free(s->dev, &s->soft_k);
  cl_mem b[3] = {s->soft_at, s->soft_from, s->soft_to};
  for (int q = 0; q < 3; q++)
    if (b[q])
      clReleaseMemObject(b[q]);
}

/* A user's field of external accelerations in the planes engine
 * (kernels/field.cl): three planes laid out as the state's, their padding
 * zero, added to the velocities as dt a before each step while it is set.
 * First order, as wind is: the step's forces see the velocity with it. */
#include "config.h"
#include "planes.h"

#include <stdlib.h>

#define TRY MSOCL__TRY

int msocl__field_create(msocl__engine *s, cl_program prog)
{
  return msocl__kernel_make(s->dev, prog, "msocl_field_kick", &s->field_k);
}

/* The field's planes from xyz; forces divided by the masses, which the
 * engine keeps only as inverse masses in its aux plane. */
static int fill(msocl__engine *s, const float *xyz, int forces, float *acc)
{
  const size_t P = (size_t)s->pl_plane;
  float *inv = NULL;
  if (forces) {
    TRY(msocl__planes_enter(s)); /* packs the inverse masses into aux */
    inv = malloc(P * sizeof *inv);
    if (!inv)
      return msocl__fail(MSOCL_ERR_NO_MEMORY, "the field's masses");
    cl_int e = clEnqueueReadBuffer(s->dev->queue, s->pl_aux, CL_TRUE, 0,
                                   P * sizeof *inv, inv, 0, NULL, NULL);
    if (e != CL_SUCCESS) {
      free(inv);
      return msocl__fail(e, "reading the inverse masses: %s",
                         msocl_err_name(e));
    }
  }
  for (int j = 0; j < s->n; j++) {
    const size_t a = (size_t)msocl__pl_address(s, j);
    const float w = inv ? inv[a] : 1.0f;
    for (int c = 0; c < 3; c++)
      acc[(size_t)c * P + a] = w * xyz[3 * (size_t)j + c];
  }
  free(inv);
  return MSOCL_OK;
}

int msocl__field_set(msocl__engine *s, const float *xyz, int forces)
{
  if (!xyz) {
    s->field_on = 0;
    return MSOCL_OK;
  }
  const size_t bytes = 3 * (size_t)s->pl_plane * sizeof(float);
  float *acc = calloc(1, bytes);
  if (!acc)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "the field's planes");
  int rc = fill(s, xyz, forces, acc);
  if (!s->field_acc)
    s->field_acc = msocl__buffer(s->dev, CL_MEM_READ_ONLY, bytes, NULL,
                                 "the field", &rc);
  if (rc == MSOCL_OK) {
    const cl_int e = clEnqueueWriteBuffer(s->dev->queue, s->field_acc,
                                          CL_TRUE, 0, bytes, acc, 0, NULL,
                                          NULL);
    if (e != CL_SUCCESS)
      rc = msocl__fail(e, "writing the field: %s", msocl_err_name(e));
  }
  free(acc);
  TRY(rc);
  cl_kernel k = s->field_k;
  TRY(msocl__arg_mem(s, k, "acc", s->field_acc));
  TRY(msocl__arg_mem(s, k, "aux", s->pl_aux));
  TRY(msocl__arg_float(s, k, "dt", s->o.dt));
  TRY(msocl__arg_int(s, k, "n", s->n));
  TRY(msocl__pl_shape(s, k));
  s->field_on = 1;
  return MSOCL_OK;
}

int msocl__field_pass(msocl__engine *s)
{
  if (!s->field_on)
    return MSOCL_OK;
  TRY(msocl__arg_mem(s, s->field_k, "v", s->pl_v[s->pl_set]));
  const size_t local[3] = {s->pl_group, 1, 1};
  const size_t *group = s->dev->info.type == MSOCL_DEVICE_CPU ? local : NULL;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->field_k, 3, NULL,
                                   s->pl_global, group, 0, NULL, NULL));
  return MSOCL_OK;
}

void msocl__field_release(msocl__engine *s)
{
  msocl__kernel_free(s->dev, &s->field_k);
  if (s->field_acc)
    clReleaseMemObject(s->field_acc);
}

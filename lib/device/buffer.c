/* Device buffers: one place that creates them and says which failed. */
#include "internal.h"

cl_mem msocl__buffer(struct msocl__device *dev, cl_mem_flags flags,
                     size_t bytes, const void *host, const char *what, int *rc)
{
  if (*rc != MSOCL_OK)
    return NULL;
  cl_int e;
  const cl_mem_flags copy = host ? CL_MEM_COPY_HOST_PTR : 0;
  cl_mem b = clCreateBuffer(dev->ctx, flags | copy, bytes, (void *)host, &e);
  if (e == CL_SUCCESS)
    return b;
  *rc = msocl__fail(e, "clCreateBuffer(%zu bytes of %s) on %s: %s", bytes,
                    what, dev->info.name, msocl_err_name(e));
  return NULL;
}

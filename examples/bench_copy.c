/* The roofline's ceiling: a device's copy bandwidth, measured with
 * clEnqueueCopyBuffer between two device buffers on a context of our own
 * (the library's device numbering: platform P, device D of all types). */
#define CL_TARGET_OPENCL_VERSION 120
#include "bench.h"

#include <CL/cl.h>
#include <stdlib.h>

#define COPY_BATCHES 5 /* timed batches; the best one counts */
#define COPY_REPS 4    /* copies a batch */

static cl_device_id find_device(int pi, int di, cl_int *e)
{
  cl_uint np = 0, nd = 0;
  cl_platform_id *plats = NULL;
  cl_device_id *devs = NULL, id = NULL;
  if ((*e = clGetPlatformIDs(0, NULL, &np)) != CL_SUCCESS || pi < 0 ||
      (cl_uint)pi >= np)
    goto out;
  if (!(plats = malloc(np * sizeof *plats))) {
    *e = CL_OUT_OF_HOST_MEMORY;
    goto out;
  }
  if ((*e = clGetPlatformIDs(np, plats, NULL)) != CL_SUCCESS ||
      (*e = clGetDeviceIDs(plats[pi], CL_DEVICE_TYPE_ALL, 0, NULL, &nd)) !=
          CL_SUCCESS ||
      di < 0 || (cl_uint)di >= nd)
    goto out;
  if (!(devs = malloc(nd * sizeof *devs))) {
    *e = CL_OUT_OF_HOST_MEMORY;
    goto out;
  }
  if ((*e = clGetDeviceIDs(plats[pi], CL_DEVICE_TYPE_ALL, nd, devs, NULL)) ==
      CL_SUCCESS)
    id = devs[di];
out:
  if (!id && *e == CL_SUCCESS)
    *e = CL_DEVICE_NOT_FOUND;
  free(plats);
  free(devs);
  return id;
}

int bench_copy_gbps(const msocl_device_info *info, size_t max_bytes,
                    double *gbps)
{
  cl_int e = CL_SUCCESS;
  cl_context ctx = NULL;
  cl_command_queue q = NULL;
  cl_mem a = NULL, b = NULL;
  *gbps = 0.0;
  cl_device_id id = find_device(info->platform_index, info->device_index, &e);
  if (!id)
    return e;
  /* Two buffers within a quarter of the device's memory and its largest
   * allocation. */
  cl_ulong max_alloc = 0;
  clGetDeviceInfo(id, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof max_alloc,
                  &max_alloc, NULL);
  size_t bytes = max_bytes;
  if (max_alloc > 0 && bytes > max_alloc)
    bytes = (size_t)max_alloc;
  if (info->global_mem > 0 && bytes > info->global_mem / 8)
    bytes = (size_t)(info->global_mem / 8);
  bytes &= ~(size_t)4095;
  if (bytes == 0)
    return CL_INVALID_BUFFER_SIZE;
  ctx = clCreateContext(NULL, 1, &id, NULL, NULL, &e);
  if (e == CL_SUCCESS)
    q = clCreateCommandQueue(ctx, id, 0, &e);
  if (e == CL_SUCCESS)
    a = clCreateBuffer(ctx, CL_MEM_READ_WRITE, bytes, NULL, &e);
  if (e == CL_SUCCESS)
    b = clCreateBuffer(ctx, CL_MEM_READ_WRITE, bytes, NULL, &e);
  const unsigned char zero = 0;
  /* Touch both buffers (first-use page faults), then one untimed copy. */
  if (e == CL_SUCCESS)
    e = clEnqueueFillBuffer(q, a, &zero, 1, 0, bytes, 0, NULL, NULL);
  if (e == CL_SUCCESS)
    e = clEnqueueFillBuffer(q, b, &zero, 1, 0, bytes, 0, NULL, NULL);
  if (e == CL_SUCCESS)
    e = clEnqueueCopyBuffer(q, a, b, 0, 0, bytes, 0, NULL, NULL);
  if (e == CL_SUCCESS)
    e = clFinish(q);
  double best = 0.0;
  for (int t = 0; e == CL_SUCCESS && t < COPY_BATCHES; t++) {
    double t0 = bench_now();
    for (int r = 0; e == CL_SUCCESS && r < COPY_REPS; r++)
      e = clEnqueueCopyBuffer(q, r & 1 ? b : a, r & 1 ? a : b, 0, 0, bytes,
                              0, NULL, NULL);
    if (e == CL_SUCCESS)
      e = clFinish(q);
    double secs = bench_now() - t0;
    /* read + written bytes */
    double rate = secs > 0 ? 2.0 * (double)bytes * COPY_REPS / secs : 0.0;
    if (rate > best)
      best = rate;
  }
  if (e == CL_SUCCESS)
    *gbps = best / 1e9;
  if (b)
    clReleaseMemObject(b);
  if (a)
    clReleaseMemObject(a);
  if (q)
    clReleaseCommandQueue(q);
  if (ctx)
    clReleaseContext(ctx);
  return e;
}

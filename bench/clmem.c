/* LD_PRELOAD shim for bench/state_io.c: counts the bytes of the OpenCL
 * buffers a process holds (clCreateBuffer less clReleaseMemObject) and
 * answers clmem_now(). */
#define _GNU_SOURCE /* RTLD_NEXT */
#define CL_TARGET_OPENCL_VERSION 300
#include <CL/cl.h>
#include <dlfcn.h>
#include <stddef.h>

enum { MAX_LIVE = 1 << 16 };
static struct {
  cl_mem m;
  size_t bytes;
} live[MAX_LIVE];
static int nlive;
static size_t held;

cl_mem clCreateBuffer(cl_context c, cl_mem_flags f, size_t size, void *host,
                      cl_int *err)
{
  cl_mem (*real)(cl_context, cl_mem_flags, size_t, void *, cl_int *);
  *(void **)&real = dlsym(RTLD_NEXT, "clCreateBuffer");
  cl_mem m = real(c, f, size, host, err);
  if (m && nlive < MAX_LIVE) {
    live[nlive].m = m;
    live[nlive++].bytes = size;
    held += size;
  }
  return m;
}

cl_int clReleaseMemObject(cl_mem m)
{
  cl_int (*real)(cl_mem);
  *(void **)&real = dlsym(RTLD_NEXT, "clReleaseMemObject");
  for (int q = 0; q < nlive; q++)
    if (live[q].m == m) {
      held -= live[q].bytes;
      live[q] = live[--nlive];
      break;
    }
  return real(m);
}

size_t clmem_now(void) { return held; }

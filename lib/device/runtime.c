/* A runtime: one OpenCL context and in-order, profiling command queue on
 * each device a spec (or MSOCL_DEVICE) chooses. Threads may share it: the
 * queues are OpenCL's (thread-safe) and the program cache has a lock. */
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* The public device list carries only (P, D), so find the CL ids again. */
static int find_ids(struct msocl__device *dev, const cl_platform_id *plats,
                    cl_uint np) {
  const msocl_device_info *in = &dev->info;
  cl_device_id *ids;
  cl_uint nd = 0;
  cl_int e;

  if ((cl_uint)in->platform_index >= np)
    return msocl__fail(MSOCL_ERR_NO_DEVICE, "platform %d is gone",
                       in->platform_index);
  dev->platform = plats[in->platform_index];
  MSOCL__CL(clGetDeviceIDs(dev->platform, CL_DEVICE_TYPE_ALL, 0, NULL, &nd));
  if ((cl_uint)in->device_index >= nd)
    return msocl__fail(MSOCL_ERR_NO_DEVICE, "device %d:%d (%s) is gone",
                       in->platform_index, in->device_index, in->name);
  if (!(ids = malloc(nd * sizeof *ids)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "out of memory");
  e = clGetDeviceIDs(dev->platform, CL_DEVICE_TYPE_ALL, nd, ids, NULL);
  if (e == CL_SUCCESS) dev->id = ids[in->device_index];
  free(ids);
  if (e != CL_SUCCESS)
    return msocl__fail(e, "clGetDeviceIDs on platform %d failed: %s (%d)",
                       in->platform_index, msocl_err_name(e), (int)e);
  return MSOCL_OK;
}

static int open_device(struct msocl__device *dev, const cl_platform_id *plats,
                       cl_uint np) {
  cl_context_properties props[3];
  cl_int e;
  int rc;

  if (pthread_mutex_init(&dev->programs_lock, NULL) != 0)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "program cache lock");
  if (pthread_mutex_init(&dev->names_lock, NULL) != 0) {
    pthread_mutex_destroy(&dev->programs_lock);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "kernel names lock");
  }
  dev->lock_made = 1;
  if ((rc = find_ids(dev, plats, np)) != MSOCL_OK) return rc;
  props[0] = CL_CONTEXT_PLATFORM;
  props[1] = (cl_context_properties)dev->platform;
  props[2] = 0;
  dev->ctx = clCreateContext(props, 1, &dev->id, NULL, NULL, &e);
  if (e != CL_SUCCESS)
    return msocl__fail(e, "clCreateContext on device %d:%d (%s) failed: "
                          "%s (%d)", dev->info.platform_index,
                       dev->info.device_index, dev->info.name,
                       msocl_err_name(e), (int)e);
  /* Profiling costs little and lets the benchmarks time kernels alone. */
  dev->queue = clCreateCommandQueue(dev->ctx, dev->id,
                                    CL_QUEUE_PROFILING_ENABLE, &e);
  if (e != CL_SUCCESS)
    return msocl__fail(e, "clCreateCommandQueue on device %d:%d (%s) "
                          "failed: %s (%d)", dev->info.platform_index,
                       dev->info.device_index, dev->info.name,
                       msocl_err_name(e), (int)e);
  return MSOCL_OK;
}

static void release_devices(msocl_runtime *rt) {
  int i;
  for (i = 0; i < rt->ndev; i++) {
    if (rt->dev[i].queue) clReleaseCommandQueue(rt->dev[i].queue);
    if (rt->dev[i].ctx) clReleaseContext(rt->dev[i].ctx);
    if (rt->dev[i].lock_made) {
      msocl__kernel_names_free(&rt->dev[i]);
      pthread_mutex_destroy(&rt->dev[i].programs_lock);
      pthread_mutex_destroy(&rt->dev[i].names_lock);
    }
  }
}

static int open_all(msocl_runtime *rt, const msocl_device_info *list,
                    const int *chosen, int nchosen) {
  cl_platform_id *plats;
  cl_uint np = 0;
  cl_int e;
  int rc = MSOCL_OK;

  MSOCL__CL(clGetPlatformIDs(0, NULL, &np));
  if (np == 0)
    return msocl__fail(MSOCL_ERR_NO_PLATFORM, "the OpenCL platforms are gone");
  if (!(plats = malloc(np * sizeof *plats)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "out of memory");
  if ((e = clGetPlatformIDs(np, plats, NULL)) != CL_SUCCESS)
    rc = msocl__fail(e, "clGetPlatformIDs failed: %s (%d)",
                     msocl_err_name(e), (int)e);
  /* ndev counts a half-opened device too, so that it is released. */
  for (rt->ndev = 0; rc == MSOCL_OK && rt->ndev < nchosen; rt->ndev++) {
    rt->dev[rt->ndev].info = list[chosen[rt->ndev]];
    rc = open_device(&rt->dev[rt->ndev], plats, np);
  }
  free(plats);
  return rc;
}

int msocl_runtime_create(msocl_runtime **rt, const char *spec) {
  msocl_device_info *list = NULL;
  int chosen[MSOCL__MAX_DEVICES];
  int from_env = spec == NULL, n = 0, nchosen = 0, rc;
  msocl_runtime *r;

  msocl__clear_error();
  if (!rt)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "msocl_runtime_create: rt is NULL");
  *rt = NULL;
  if (from_env) spec = getenv("MSOCL_DEVICE");
  if ((rc = msocl_device_list(&list, &n)) != MSOCL_OK) return rc;
  rc = msocl_device_select(spec, list, n, chosen, MSOCL__MAX_DEVICES,
                           &nchosen);
  if (rc != MSOCL_OK) {
    free(list);
    /* A user who never typed a spec must learn where it came from. */
    if (from_env && spec)
      return msocl__fail(rc, "MSOCL_DEVICE='%s': %s", spec,
                         msocl_last_error());
    return rc;
  }
  if (!(r = calloc(1, sizeof *r))) {
    free(list);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "out of memory");
  }
  rc = open_all(r, list, chosen, nchosen);
  free(list);
  if (rc != MSOCL_OK) {
    release_devices(r);
    free(r);
    return rc;
  }
  *rt = r;
  return MSOCL_OK;
}

void msocl_runtime_destroy(msocl_runtime *rt) {
  int i;
  if (!rt) return;
  /* Programs first: they belong to the contexts released below. */
  for (i = 0; i < rt->ndev; i++) msocl__program_cache_free(&rt->dev[i]);
  release_devices(rt);
  free(rt);
}

int msocl_runtime_device_count(const msocl_runtime *rt, int *n) {
  msocl__clear_error();
  if (!rt || !n)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "msocl_runtime_device_count: %s is NULL",
                       rt ? "n" : "rt");
  *n = rt->ndev;
  return MSOCL_OK;
}

int msocl_runtime_device_info(const msocl_runtime *rt, int i,
                              msocl_device_info *info) {
  msocl__clear_error();
  if (!rt || !info)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "msocl_runtime_device_info: %s is NULL",
                       rt ? "info" : "rt");
  if (i < 0 || i >= rt->ndev)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "device index %d out of range: the runtime has %d "
                       "device%s",
                       i, rt->ndev, rt->ndev == 1 ? "" : "s");
  *info = rt->dev[i].info;
  return MSOCL_OK;
}

/* Enumerates OpenCL platforms and devices and reads the facts the library
 * needs about each (type, memory, image limits, fp64). */
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* From cl_ext.h, which the ICD loader returns when it finds no platform. */
#define PLATFORM_NOT_FOUND_KHR (-1001)

#define NO_PLATFORM_HINT                                                      \
  "no OpenCL platform or device found (for a CPU device install PoCL: "      \
  "apt-get install pocl-opencl-icd)"

/* Copies a string property into out, truncated to cap and trimmed: some
 * drivers pad device names with spaces. A property too long for a fixed
 * buffer makes clGet*Info fail, so ask for the size first. */
static int get_string(cl_platform_id p, cl_device_id d, cl_uint param,
                      char *out, size_t cap) {
  size_t size = 0, n;
  char *buf, *s;
  cl_int e;

  out[0] = '\0';
  e = d ? clGetDeviceInfo(d, param, 0, NULL, &size)
        : clGetPlatformInfo(p, param, 0, NULL, &size);
  if (e != CL_SUCCESS)
    return msocl__fail(e, "clGet%sInfo(0x%x) failed: %s (%d)",
                       d ? "Device" : "Platform", (unsigned)param,
                       msocl_err_name(e), (int)e);
  if (!(buf = calloc(size + 1, 1)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "out of memory (%zu bytes)",
                       size + 1);
  e = d ? clGetDeviceInfo(d, param, size, buf, NULL)
        : clGetPlatformInfo(p, param, size, buf, NULL);
  if (e != CL_SUCCESS) {
    free(buf);
    return msocl__fail(e, "clGet%sInfo(0x%x) failed: %s (%d)",
                       d ? "Device" : "Platform", (unsigned)param,
                       msocl_err_name(e), (int)e);
  }
  for (s = buf; *s == ' ' || *s == '\t'; s++) {
  }
  n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\n'))
    n--;
  if (n >= cap) n = cap - 1;
  memcpy(out, s, n);
  out[n] = '\0';
  free(buf);
  return MSOCL_OK;
}

/* fp64 is optional before OpenCL 3.0's query; 1.1 devices advertise it
 * only as the cl_khr_fp64 extension. */
static int has_fp64(cl_device_id d) {
  cl_device_fp_config fp = 0;
  size_t size = 0;
  char *ext;
  int yes;

  if (clGetDeviceInfo(d, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof fp, &fp, NULL) ==
          CL_SUCCESS &&
      fp != 0)
    return 1;
  if (clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, 0, NULL, &size) != CL_SUCCESS ||
      !(ext = calloc(size + 1, 1)))
    return 0;
  yes = clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, size, ext, NULL) ==
            CL_SUCCESS &&
        strstr(ext, "cl_khr_fp64") != NULL;
  free(ext);
  return yes;
}

int msocl__device_query(cl_platform_id p, cl_device_id d,
                        msocl_device_info *info) {
  cl_device_type type;
  cl_uint units;
  cl_ulong mem;
  cl_bool images;
  int rc;

  if ((rc = get_string(p, NULL, CL_PLATFORM_NAME, info->platform_name,
                       sizeof info->platform_name)) != MSOCL_OK ||
      (rc = get_string(p, d, CL_DEVICE_NAME, info->name,
                       sizeof info->name)) != MSOCL_OK ||
      (rc = get_string(p, d, CL_DEVICE_VERSION, info->version,
                       sizeof info->version)) != MSOCL_OK)
    return rc;
  MSOCL__CL(clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof type, &type, NULL));
  MSOCL__CL(clGetDeviceInfo(d, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof units,
                            &units, NULL));
  MSOCL__CL(clGetDeviceInfo(d, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem,
                            NULL));
  MSOCL__CL(clGetDeviceInfo(d, CL_DEVICE_IMAGE_SUPPORT, sizeof images,
                            &images, NULL));
  /* A device may also carry CL_DEVICE_TYPE_DEFAULT: keep the kind only. */
  if (type & CL_DEVICE_TYPE_GPU) info->type = MSOCL_DEVICE_GPU;
  else if (type & CL_DEVICE_TYPE_CPU) info->type = MSOCL_DEVICE_CPU;
  else if (type & CL_DEVICE_TYPE_ACCELERATOR)
    info->type = MSOCL_DEVICE_ACCELERATOR;
  else info->type = MSOCL_DEVICE_OTHER;
  info->compute_units = units;
  info->global_mem = mem;
  cl_ulong cache = 0;
  if (clGetDeviceInfo(d, CL_DEVICE_GLOBAL_MEM_CACHE_SIZE, sizeof cache,
                      &cache, NULL) != CL_SUCCESS)
    cache = 0; /* not given: no cache assumed */
  info->cache = cache;
  info->image_support = images != CL_FALSE;
  info->image2d_max_width = info->image2d_max_height = 0;
  if (info->image_support) {
    MSOCL__CL(clGetDeviceInfo(d, CL_DEVICE_IMAGE2D_MAX_WIDTH,
                              sizeof info->image2d_max_width,
                              &info->image2d_max_width, NULL));
    MSOCL__CL(clGetDeviceInfo(d, CL_DEVICE_IMAGE2D_MAX_HEIGHT,
                              sizeof info->image2d_max_height,
                              &info->image2d_max_height, NULL));
  }
  info->fp64 = has_fp64(d);
  return MSOCL_OK;
}

/* Appends platform p's devices to *list; a platform without any adds none. */
static int add_platform(cl_platform_id p, int pi, msocl_device_info **list,
                        int *count) {
  cl_uint nd = 0, i;
  cl_device_id *ids;
  msocl_device_info *grown;
  cl_int e = clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, NULL, &nd);
  int rc = MSOCL_OK;

  if (e == CL_DEVICE_NOT_FOUND || (e == CL_SUCCESS && nd == 0))
    return MSOCL_OK;
  MSOCL__CL(e);
  if (!(ids = malloc(nd * sizeof *ids)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "out of memory");
  if (!(grown = realloc(*list, (size_t)(*count + (int)nd) * sizeof **list))) {
    free(ids);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "out of memory");
  }
  *list = grown;
  e = clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, ids, NULL);
  if (e != CL_SUCCESS)
    rc = msocl__fail(e, "clGetDeviceIDs on platform %d failed: %s (%d)", pi,
                     msocl_err_name(e), (int)e);
  for (i = 0; rc == MSOCL_OK && i < nd; i++) {
    msocl_device_info *info = &grown[*count];
    memset(info, 0, sizeof *info);
    info->platform_index = pi;
    info->device_index = (int)i;
    if ((rc = msocl__device_query(p, ids[i], info)) == MSOCL_OK) ++*count;
  }
  free(ids);
  return rc;
}

static int list_platforms(cl_platform_id **ids, cl_uint *n) {
  cl_int e = clGetPlatformIDs(0, NULL, n);
  /* The ICD loader's way of saying "none" is no failure of the call. */
  if (e == PLATFORM_NOT_FOUND_KHR || (e == CL_SUCCESS && *n == 0))
    return msocl__fail(MSOCL_ERR_NO_PLATFORM, NO_PLATFORM_HINT);
  MSOCL__CL(e);
  if (!(*ids = malloc(*n * sizeof **ids)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "out of memory");
  if ((e = clGetPlatformIDs(*n, *ids, NULL)) != CL_SUCCESS) {
    free(*ids);
    *ids = NULL;
    return msocl__fail(e, "clGetPlatformIDs failed: %s (%d)",
                       msocl_err_name(e), (int)e);
  }
  return MSOCL_OK;
}

int msocl_device_list(msocl_device_info **list, int *count) {
  cl_platform_id *ids = NULL;
  cl_uint np = 0, i;
  int rc;

  msocl__clear_error();
  if (!list || !count)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "msocl_device_list: %s is NULL",
                       list ? "count" : "list");
  *list = NULL;
  *count = 0;
  if ((rc = list_platforms(&ids, &np)) != MSOCL_OK) return rc;
  for (i = 0; i < np && rc == MSOCL_OK; i++)
    rc = add_platform(ids[i], (int)i, list, count);
  free(ids);
  if (rc == MSOCL_OK && *count == 0)
    rc = msocl__fail(MSOCL_ERR_NO_PLATFORM, NO_PLATFORM_HINT);
  if (rc != MSOCL_OK) {
    free(*list);
    *list = NULL;
    *count = 0;
  }
  return rc;
}

/* Kernels made here remember their arguments' names, read once from the
 * program (program.c builds with -cl-kernel-arg-info), so that a caller
 * sets an argument by the name kernels/ gives it and never counts to it:
 * a signature that gains an argument cannot shift the others. */
#include "config.h"
#include "internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NAME_MAX_LEN 32

struct msocl__kernel_names {
  cl_kernel k;
  cl_uint n;
  char kernel[64];
  char (*arg)[NAME_MAX_LEN];
  struct msocl__kernel_names *next;
};

static int read_names(struct msocl__kernel_names *e, const char *name)
{
  snprintf(e->kernel, sizeof e->kernel, "%s", name);
  MSOCL__CL(clGetKernelInfo(e->k, CL_KERNEL_NUM_ARGS, sizeof e->n, &e->n,
                            NULL));
  e->arg = calloc(e->n ? e->n : 1, sizeof *e->arg);
  if (!e->arg)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "argument names of %s", name);
  for (cl_uint i = 0; i < e->n; i++) {
    size_t len = 0;
    cl_int err = clGetKernelArgInfo(e->k, i, CL_KERNEL_ARG_NAME,
                                    sizeof e->arg[i], e->arg[i], &len);
    if (err != CL_SUCCESS)
      return msocl__fail(err, "argument %u of %s has no name (%s): the "
                              "program needs -cl-kernel-arg-info",
                         i, name, msocl_err_name(err));
  }
  return MSOCL_OK;
}

int msocl__kernel_make(struct msocl__device *dev, cl_program prog,
                       const char *name, cl_kernel *out)
{
  cl_int err;
  *out = NULL;
  struct msocl__kernel_names *e = calloc(1, sizeof *e);
  if (!e)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "kernel %s", name);
  e->k = clCreateKernel(prog, name, &err);
  if (err != CL_SUCCESS) {
    free(e);
    return msocl__fail(err, "clCreateKernel(%s): %s", name,
                       msocl_err_name(err));
  }
  int rc = read_names(e, name);
  if (rc != MSOCL_OK) {
    clReleaseKernel(e->k);
    free(e->arg);
    free(e);
    return rc;
  }
  pthread_mutex_lock(&dev->names_lock);
  e->next = dev->names;
  dev->names = e;
  pthread_mutex_unlock(&dev->names_lock);
  *out = e->k;
  return MSOCL_OK;
}

void msocl__kernel_free(struct msocl__device *dev, cl_kernel *k)
{
  if (!*k)
    return;
  pthread_mutex_lock(&dev->names_lock);
  for (struct msocl__kernel_names **p = &dev->names; *p; p = &(*p)->next)
    if ((*p)->k == *k) {
      struct msocl__kernel_names *e = *p;
      *p = e->next;
      free(e->arg);
      free(e);
      break;
    }
  pthread_mutex_unlock(&dev->names_lock);
  clReleaseKernel(*k);
  *k = NULL;
}

/* Index of k's argument `name` into *i; -1: k has none of that name, -2:
 * k was not made by msocl__kernel_make. k's entry moves to the list's
 * head: a step sets arguments of a few kernels out of dozens, again and
 * again. */
static int find(struct msocl__device *dev, cl_kernel k, const char *name,
                cl_uint *i, const char **kernel)
{
  int found = -2;
  pthread_mutex_lock(&dev->names_lock);
  for (struct msocl__kernel_names **p = &dev->names; *p; p = &(*p)->next)
    if ((*p)->k == k) {
      struct msocl__kernel_names *e = *p;
      *p = e->next;
      e->next = dev->names;
      dev->names = e;
      found = -1;
      *kernel = e->kernel;
      for (cl_uint a = 0; a < e->n; a++)
        if (strcmp(e->arg[a], name) == 0) {
          *i = a;
          found = 0;
          break;
        }
      break;
    }
  pthread_mutex_unlock(&dev->names_lock);
  return found;
}

int msocl__kernel_has(struct msocl__device *dev, cl_kernel k,
                      const char *name)
{
  cl_uint i;
  const char *kernel;
  return find(dev, k, name, &i, &kernel) == 0;
}

int msocl__kernel_arg(struct msocl__device *dev, cl_kernel k,
                      const char *name, size_t size, const void *v)
{
  cl_uint i = 0;
  const char *kernel = "?";
  const int found = find(dev, k, name, &i, &kernel);
  if (found == -2)
    return msocl__fail(MSOCL_ERR_INVALID_ARG,
                       "argument %s of a kernel not made by name", name);
  if (found == -1)
    return msocl__fail(MSOCL_ERR_INVALID_ARG, "kernel %s has no argument %s",
                       kernel, name);
  MSOCL__CL(clSetKernelArg(k, i, size, v));
  return MSOCL_OK;
}

void msocl__kernel_names_free(struct msocl__device *dev)
{
  struct msocl__kernel_names *e = dev->names;
  while (e) {
    struct msocl__kernel_names *next = e->next;
    free(e->arg);
    free(e);
    e = next;
  }
  dev->names = NULL;
}

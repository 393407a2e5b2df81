/* Kernel arguments by name (the device's kernel_names.c reads the names
 * from the program): one argument, or every argument of a kernel that a
 * table of named values names. */
#include "config.h"
#include "engine.h"

int msocl__arg(msocl__engine *s, cl_kernel k, const char *name, size_t size,
               const void *v)
{
  return msocl__kernel_arg(s->dev, k, name, size, v);
}

int msocl__arg_mem(msocl__engine *s, cl_kernel k, const char *name, cl_mem m)
{
  return msocl__kernel_arg(s->dev, k, name, sizeof m, &m);
}

int msocl__arg_float(msocl__engine *s, cl_kernel k, const char *name, float f)
{
  return msocl__kernel_arg(s->dev, k, name, sizeof f, &f);
}

int msocl__arg_int(msocl__engine *s, cl_kernel k, const char *name, int v)
{
  return msocl__kernel_arg(s->dev, k, name, sizeof v, &v);
}

int msocl__args_named(msocl__engine *s, cl_kernel k,
                      const struct msocl__named *vals, int n)
{
  for (int q = 0; q < n; q++)
    if (msocl__kernel_has(s->dev, k, vals[q].name))
      MSOCL__TRY(msocl__kernel_arg(s->dev, k, vals[q].name, vals[q].size,
                                   vals[q].v));
  return MSOCL_OK;
}

/* The values the engine's own kernels' (s->k) arguments hold for its
 * whole life: everything but the state buffers. */
int msocl__set_fixed(msocl__engine *s)
{
  const struct msocl__named fixed[] = {
      {"gravity", sizeof s->gravity, &s->gravity},
      {"n", sizeof s->n, &s->n},
      {"end", sizeof s->hi, &s->hi},
      {"partial", sizeof s->partial, &s->partial},
      {"tri_off", sizeof s->tri_off, &s->tri_off},
      {"tri_ab", sizeof s->tri_ab, &s->tri_ab},
      {"normal", sizeof s->normal, &s->normal},
  };
  for (int k = 0; k < MSOCL__K_COUNT; k++)
    if (s->k[k])
      MSOCL__TRY(msocl__args_named(s, s->k[k], fixed,
                                   (int)(sizeof fixed / sizeof fixed[0])));
  return MSOCL_OK;
}

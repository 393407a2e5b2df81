/* The float4 kernels' arguments by name: each kernel's signature as in
 * kernels/, so that a caller names the argument it sets and never counts
 * to it. CONN stands for the layout's connectivity arguments, the
 * engine's nconn of them (msocl__layout_set_args sets those). */
#include "config.h"
#include "engine.h"

#include <string.h>

#define CONN ""

static const char *const normals[] = {"pos", "tri_off", "tri_ab", "normal",
                                      "n", NULL};
static const char *const energy[] = {CONN,      "pos", "vel", "inv_mass",
                                     "gravity", "partial", "n", "end",
                                     NULL};

static const char *const *const signature[MSOCL__K_COUNT] = {
    [MSOCL__K_NORMALS] = normals,
    [MSOCL__K_ENERGY] = energy,
};

int msocl__set(msocl__engine *s, int k, const char *name, size_t size,
               const void *v)
{
  cl_uint i = 0;
  for (const char *const *a = signature[k]; a && *a; a++) {
    if (**a == '\0') {
      i += s->nconn;
    } else if (strcmp(*a, name) == 0) {
      MSOCL__CL(clSetKernelArg(s->k[k], i, size, v));
      return MSOCL_OK;
    } else {
      i++;
    }
  }
  return msocl__fail(MSOCL_ERR_INVALID_ARG, "kernel %d has no argument %s",
                     k, name);
}

int msocl__set_mem(msocl__engine *s, int k, const char *name, cl_mem m)
{
  return msocl__set(s, k, name, sizeof m, &m);
}

int msocl__set_float(msocl__engine *s, int k, const char *name, float f)
{
  return msocl__set(s, k, name, sizeof f, &f);
}

int msocl__set_int(msocl__engine *s, int k, const char *name, int v)
{
  return msocl__set(s, k, name, sizeof v, &v);
}

/* The values an argument of a given name holds in every float4 kernel
 * that has it, for the engine's whole life: everything but the state
 * buffers. */
int msocl__set_fixed(msocl__engine *s)
{
  const struct {
    const char *name;
    size_t size;
    const void *v;
  } fixed[] = {
      {"inv_mass", sizeof s->inv_mass, &s->inv_mass},
      {"gravity", sizeof s->gravity, &s->gravity},
      {"viscous", sizeof s->viscous, &s->viscous},
      {"n", sizeof s->n, &s->n},
      {"end", sizeof s->hi, &s->hi},
      {"partial", sizeof s->partial, &s->partial},
      {"tri_off", sizeof s->tri_off, &s->tri_off},
      {"tri_ab", sizeof s->tri_ab, &s->tri_ab},
      {"normal", sizeof s->normal, &s->normal},
  };
  for (int k = 0; k < MSOCL__K_COUNT; k++) {
    if (!s->k[k] || !signature[k])
      continue;
    for (const char *const *a = signature[k]; *a; a++)
      for (size_t f = 0; f < sizeof fixed / sizeof fixed[0]; f++)
        if (strcmp(*a, fixed[f].name) == 0) {
          int rc = msocl__set(s, k, *a, fixed[f].size, fixed[f].v);
          if (rc != MSOCL_OK)
            return rc;
        }
  }
  return MSOCL_OK;
}

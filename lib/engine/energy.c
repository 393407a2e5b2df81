/* Kinetic, spring and gravitational energy of a simulation's state, read
 * from the planes, summed on the device in runs of 64 points and
 * finished on the host in double. */
#include "config.h"
#include "engine.h"
#include "planes.h"

#include <math.h>

/* The floats a plane of the points' parts: every point of the model (the
 * whole planes run), and every point the sums read. */
int msocl__energy_stride(const msocl__engine *s)
{
  const size_t read = s->offset + 64 * s->groups;
  return (int)(read > (size_t)s->n ? read : (size_t)s->n);
}

/* Whether the points' parts take energy.cl's wide kernel: where the
 * other passes take theirs (planes.c), on BUFFER's or EDGES's table. */
static int wide(const msocl__engine *s)
{
  return (s->pl_wide & (1u << PL_VELOCITY)) &&
         s->lay.kind != MSOCL_LAYOUT_GRID && s->pl_group % MSOCL__WIDE_W == 0;
}

/* The energy kernels' arguments that hold for the engine's life: the
 * planes' connectivity and shape, the parts' planes (the state's buffers
 * are set each time); the wide kernel made from prog where it applies. */
int msocl__energy_args(msocl__engine *s, cl_program prog)
{
  msocl__kernel_free(s->dev, &s->k[MSOCL__K_ENERGY_WIDE]);
  if (wide(s))
    MSOCL__TRY(msocl__kernel_make(s->dev, prog, "msocl_energy_points_wide",
                                  &s->k[MSOCL__K_ENERGY_WIDE]));
  const int stride = msocl__energy_stride(s), first = (int)s->offset,
            runs = (int)s->groups;
  const struct msocl__named fixed[] = {
      {"aux", sizeof s->pl_aux, &s->pl_aux},
      {"pitch", sizeof(int), &s->pl_pitch},
      {"slab", sizeof(int), &s->pl_slab},
      {"plane", sizeof(int), &s->pl_plane},
      {"parts", sizeof s->parts, &s->parts},
      {"stride", sizeof stride, &stride},
      {"first", sizeof first, &first},
      {"runs", sizeof runs, &runs}};
  const int nf = (int)(sizeof fixed / sizeof fixed[0]);
  for (int q = MSOCL__K_ENERGY; q <= MSOCL__K_ENERGY_WIDE; q++) {
    cl_kernel k = s->k[q];
    if (!k)
      continue;
    if (q != MSOCL__K_ENERGY)
      MSOCL__TRY(msocl__layout_set_args(&s->pl_lay, s->dev, k));
    MSOCL__TRY(msocl__args_named(s, k, fixed, nf));
  }
  return MSOCL_OK;
}

int msocl__energy(msocl__engine *s, msocl_energy *e)
{
  const int w = s->k[MSOCL__K_ENERGY_WIDE] != NULL;
  cl_kernel k = s->k[w ? MSOCL__K_ENERGY_WIDE : MSOCL__K_ENERGY_POINTS];
  /* the state in planes (where the steps leave it), not copied out */
  int rc = msocl__planes_enter(s);
  if (rc == MSOCL_OK)
    rc = msocl__arg_mem(s, k, "p", s->pl_p[s->pl_set]);
  if (rc == MSOCL_OK)
    rc = msocl__arg_mem(s, k, "v", s->pl_v[s->pl_set]);
  if (rc != MSOCL_OK)
    return rc;
  /* each point's part over the planes as their passes run (the whole
   * planes: a split's others are dropped; wide: MSOCL__WIDE_W points a
   * work-item),
   * then sums in the model's order */
  const size_t per = w ? MSOCL__WIDE_W : 1;
  size_t group[3] = {s->pl_group / per, 1, 1},
         size[3] = {s->pl_global[0] / per, s->pl_global[1], s->pl_global[2]};
  MSOCL__CL(clEnqueueNDRangeKernel(
      s->dev->queue, k, 3, NULL, size,
      s->dev->info.type == MSOCL_DEVICE_CPU ? group : NULL, 0, NULL, NULL));
  const size_t runs = (s->groups + 63) / 64 * 64;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[MSOCL__K_ENERGY], 1,
                                   NULL, &runs, NULL, 0, NULL, NULL));
  MSOCL__CL(clEnqueueReadBuffer(s->dev->queue, s->partial, CL_TRUE, 0,
                                s->groups * sizeof(cl_float4),
                                s->partial_host, 0, NULL, NULL));
  e->kinetic = e->spring = e->gravity = 0.0;
  for (size_t g = 0; g < s->groups; g++) {
    e->kinetic += s->partial_host[g].s[0];
    e->spring += s->partial_host[g].s[1];
    e->gravity += s->partial_host[g].s[2];
  }
  e->total = e->kinetic + e->spring + e->gravity;
  return MSOCL_OK;
}

/* Launching an engine's kernels, the helpers every engine file uses; and
 * reading back the work-group partials of a reduction. */
#include "config.h"
#include "engine.h"

/* Work-group size of a launch over `global` points. Left to choose (NULL),
 * PoCL's CPU device takes the largest group that still gives each core one:
 * 3 groups of 3072 at 96x96 on 2 cores, so one core idles a third of the
 * time (and a core slowed by other jobs cannot hand work over). Groups of
 * 64 share out evenly and cost nothing measurable at 512x512. GPUs keep
 * their driver's choice (not measured). */
static const size_t *group(const msocl__engine *s, size_t global)
{
  static const size_t cpu = 64;
  return s->dev->info.type == MSOCL_DEVICE_CPU && global % cpu == 0 ? &cpu
                                                                     : NULL;
}

int msocl__launch(msocl__engine *s, int k)
{
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[k], 1, &s->run_offset,
                                   &s->run_global, group(s, s->run_global), 0,
                                   NULL, NULL));
  return MSOCL_OK;
}

/* Over the engine's whole range, whatever span the phase runs on. */
int msocl__launch_range(msocl__engine *s, int k)
{
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[k], 1, &s->offset,
                                   &s->global, group(s, s->global), 0, NULL,
                                   NULL));
  return MSOCL_OK;
}

int msocl__launch_all(msocl__engine *s, int k)
{
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[k], 1, NULL,
                                   &s->full_global, group(s, s->full_global),
                                   0, NULL, NULL));
  return MSOCL_OK;
}

/* Adds the engine's partials, group by group, to *sum: split over devices
 * whose ranges start at multiples of 64, the additions come in the same
 * order as on one device, and so do the bits of the sum. */
int msocl__implicit_collect(msocl__engine *s, double *sum)
{
  MSOCL__CL(clEnqueueReadBuffer(s->dev->queue, s->partial, CL_TRUE, 0,
                                s->groups * sizeof(cl_float4),
                                s->partial_host, 0, NULL, NULL));
  for (size_t g = 0; g < s->groups; g++)
    *sum += s->partial_host[g].s[0];
  return MSOCL_OK;
}

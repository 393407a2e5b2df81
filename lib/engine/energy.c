/* Kinetic, spring and gravitational energy of a simulation's state, summed
 * on the device by work-group reduction and finished on the host in
 * double. */
#include "config.h"
#include "engine.h"

#include <math.h>

int msocl__energy(msocl__engine *s, msocl_energy *e)
{
  cl_kernel k = s->k[MSOCL__K_ENERGY];
  int rc = msocl__planes_current(s);
  if (rc == MSOCL_OK)
    rc = msocl__arg_mem(s, k, "pos", s->pos[s->r]);
  if (rc == MSOCL_OK)
    rc = msocl__arg_mem(s, k, "vel", s->vel[s->r]);
  if (rc != MSOCL_OK)
    return rc;
  const size_t local = 64, global = 64 * s->groups;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 1, &s->offset, &global,
                                   &local, 0, NULL, NULL));
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

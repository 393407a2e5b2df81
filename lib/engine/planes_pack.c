/* BUFFER's and EDGES's force kernels on a CPU gather each neighbour's
 * position as one float4 from a copy of the positions packed before the
 * pass, where the planes take three scalar loads and three inserts: the
 * copy costs 16 bytes a point and a pass over the positions a step. */
#include "planes.h"

int msocl__pl_pack_create(msocl__engine *s, cl_program prog)
{
  if (!msocl__pl_gather4(s) || s->pl_pack)
    return MSOCL_OK;
  int rc = MSOCL_OK;
  s->pl_p4 = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                           (size_t)s->pl_plane * sizeof(cl_float4), NULL,
                           "the positions' gather copy", &rc);
  MSOCL__TRY(rc);
  MSOCL__TRY(msocl__kernel_make(s->dev, prog, "msocl_planes_pack4",
                                &s->pl_pack));
  MSOCL__TRY(msocl__arg_mem(s, s->pl_pack, "p4", s->pl_p4));
  return msocl__arg_int(s, s->pl_pack, "plane", s->pl_plane);
}

int msocl__pl_pack(msocl__engine *s, cl_mem p)
{
  if (!s->pl_pack)
    return MSOCL_OK;
  MSOCL__TRY(msocl__arg_mem(s, s->pl_pack, "p", p));
  const size_t all = (size_t)s->pl_plane / MSOCL__WIDE_W,
               group = s->pl_group / MSOCL__WIDE_W;
  MSOCL__CL(clEnqueueNDRangeKernel(
      s->dev->queue, s->pl_pack, 1, NULL, &all,
      s->dev->info.type == MSOCL_DEVICE_CPU ? &group : NULL, 0, NULL, NULL));
  return MSOCL_OK;
}

void msocl__pl_pack_release(msocl__engine *s)
{
  msocl__kernel_free(s->dev, &s->pl_pack);
  if (s->pl_p4)
    clReleaseMemObject(s->pl_p4);
  s->pl_p4 = NULL;
}

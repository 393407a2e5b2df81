/* Stepping a simulation and moving its state between host and device. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <string.h>

/* Steps per batch between flushes: enough to keep the device fed without
 * piling thousands of commands into the queue. */
#define MSOCL__FLUSH_EVERY 64

int msocl_sim_step(msocl_sim *s, int n)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (n < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "step count %d is negative", n);
  cl_command_queue q = s->dev->queue;
  for (int k = 0; k < n; k++) {
    MSOCL__CL(clEnqueueNDRangeKernel(q, s->kvel[s->r], 1, NULL, &s->global,
                                     NULL, 0, NULL, NULL));
    MSOCL__CL(clEnqueueNDRangeKernel(q, s->kpos[s->r], 1, NULL, &s->global,
                                     NULL, 0, NULL, NULL));
    s->r = 1 - s->r;
    if ((k + 1) % MSOCL__FLUSH_EVERY == 0)
      MSOCL__CL(clFlush(q));
  }
  MSOCL__CL(clFinish(q));
  return MSOCL_OK;
}

static int read_xyz(msocl_sim *s, cl_mem b, float *xyz)
{
  msocl__clear_error();
  if (!s || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       s ? "output array" : "sim");
  MSOCL__CL(clEnqueueReadBuffer(s->dev->queue, b, CL_TRUE, 0,
                                4 * (size_t)s->n * sizeof(float), s->stage,
                                0, NULL, NULL));
  for (int i = 0; i < s->n; i++)
    memcpy(xyz + 3 * i, s->stage + 4 * i, 3 * sizeof(float));
  return MSOCL_OK;
}

/* Writes xyz into the current copy; w carries the pin flag for positions
 * and is 0 for velocities. */
static int write_xyz(msocl_sim *s, cl_mem b, const float *xyz, int is_pos)
{
  msocl__clear_error();
  if (!s || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       s ? "input array" : "sim");
  for (int i = 0; i < 3 * s->n; i++)
    if (!isfinite(xyz[i]))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "point %d: coordinate %d is %g", i / 3, i % 3,
                         xyz[i]);
  for (int i = 0; i < s->n; i++) {
    memcpy(s->stage + 4 * i, xyz + 3 * i, 3 * sizeof(float));
    s->stage[4 * i + 3] = is_pos && s->pinned[i] ? 1.0f : 0.0f;
  }
  MSOCL__CL(clEnqueueWriteBuffer(s->dev->queue, b, CL_TRUE, 0,
                                 4 * (size_t)s->n * sizeof(float), s->stage,
                                 0, NULL, NULL));
  return MSOCL_OK;
}

int msocl_sim_read_positions(msocl_sim *s, float *xyz)
{
  return read_xyz(s, s ? s->pos[s->r] : NULL, xyz);
}

int msocl_sim_write_positions(msocl_sim *s, const float *xyz)
{
  return write_xyz(s, s ? s->pos[s->r] : NULL, xyz, 1);
}

int msocl_sim_read_velocities(msocl_sim *s, float *xyz)
{
  return read_xyz(s, s ? s->vel[s->r] : NULL, xyz);
}

int msocl_sim_write_velocities(msocl_sim *s, const float *xyz)
{
  return write_xyz(s, s ? s->vel[s->r] : NULL, xyz, 0);
}

int msocl_sim_read_normals(msocl_sim *s, float *xyz)
{
  msocl__clear_error();
  if (!s || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       s ? "output array" : "sim");
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->knorm[s->r], 1, NULL,
                                   &s->global, NULL, 0, NULL, NULL));
  return read_xyz(s, s->normal, xyz);
}

int msocl_sim_point_count(const msocl_sim *s, int *n)
{
  if (!s || !n)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  *n = s->n;
  return MSOCL_OK;
}

int msocl_sim_layout(const msocl_sim *s, msocl_layout *layout)
{
  if (!s || !layout)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  *layout = s->lay.kind;
  return MSOCL_OK;
}

int msocl_sim_device_info(const msocl_sim *s, msocl_device_info *info)
{
  if (!s || !info)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  *info = s->dev->info;
  return MSOCL_OK;
}

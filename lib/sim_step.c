/* Stepping a simulation and moving its state between host and device. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <string.h>

/* The blow-up check's baseline: energy at the start, and a scale for the
 * scene - its kinetic and spring energy plus the work gravity could do
 * across its extent - so a scene starting at rest has a finite bound. */
static int baseline(msocl_sim *s)
{
  msocl_energy e;
  int rc = msocl__energy(s, &e);
  if (rc != MSOCL_OK)
    return rc;
  double g = sqrt((double)s->gravity.s[0] * s->gravity.s[0] +
                  (double)s->gravity.s[1] * s->gravity.s[1] +
                  (double)s->gravity.s[2] * s->gravity.s[2]);
  s->e0 = e.total;
  s->escale = e.kinetic + e.spring + s->total_mass * g * s->extent;
  s->e0_valid = 1;
  return MSOCL_OK;
}

static int copy_state(msocl_sim *s, cl_mem from_p, cl_mem from_v, cl_mem to_p,
                      cl_mem to_v)
{
  const size_t bytes = 4 * (size_t)s->n * sizeof(float);
  MSOCL__CL(clEnqueueCopyBuffer(s->dev->queue, from_p, to_p, 0, 0, bytes, 0,
                                NULL, NULL));
  MSOCL__CL(clEnqueueCopyBuffer(s->dev->queue, from_v, to_v, 0, 0, bytes, 0,
                                NULL, NULL));
  return MSOCL_OK;
}

/* Runs `n` steps in batches of check_every, each followed by the check;
 * a failed check restores the state saved before its batch. */
static int checked_steps(msocl_sim *s, int n)
{
  int rc = s->e0_valid ? MSOCL_OK : baseline(s);
  for (int done = 0; rc == MSOCL_OK && done < n;) {
    int batch = n - done < s->o.check_every ? n - done : s->o.check_every;
    long long first = s->steps;
    rc = copy_state(s, s->pos[s->r], s->vel[s->r], s->backup_p, s->backup_v);
    if (rc == MSOCL_OK)
      rc = msocl__integrate(s, batch);
    msocl_energy e;
    if (rc == MSOCL_OK)
      rc = msocl__energy(s, &e);
    if (rc != MSOCL_OK)
      return rc;
    double bound = s->e0 + s->o.energy_factor * s->escale;
    if (!isfinite(e.total) || e.total > bound) {
      rc = copy_state(s, s->backup_p, s->backup_v, s->pos[s->r],
                      s->vel[s->r]);
      s->steps = first;
      s->acc_valid = 0;
      if (rc == MSOCL_OK)
        MSOCL__CL(clFinish(s->dev->queue));
      return msocl__fail(
          MSOCL_ERR_UNSTABLE,
          "blew up between steps %lld and %lld (dt = %g): total energy %g J "
          "against %g J at the start (bound %g J); state restored to step "
          "%lld; msocl_stable_dt() gives a safe step",
          first, first + batch, (double)s->o.dt, e.total, s->e0, bound,
          first);
    }
    done += batch;
  }
  return rc;
}

int msocl_sim_step(msocl_sim *s, int n)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (n < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "step count %d is negative", n);
  int rc = s->o.check_every > 0 ? checked_steps(s, n) : msocl__integrate(s, n);
  if (rc != MSOCL_OK)
    return rc;
  MSOCL__CL(clFinish(s->dev->queue));
  return MSOCL_OK;
}

int msocl_sim_step_count(const msocl_sim *s, long long *steps)
{
  if (!s || !steps)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  *steps = s->steps;
  return MSOCL_OK;
}

int msocl_sim_solver_stats(const msocl_sim *s, int *iterations,
                           double *residual)
{
  if (!s || !iterations || !residual)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  *iterations = s->cg_iterations;
  *residual = s->cg_residual;
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
  /* A new state: new baseline energy, new Verlet acceleration. */
  s->e0_valid = 0;
  s->acc_valid = 0;
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
  int rc = msocl__arg_mem(s->k[MSOCL__K_NORMALS], 0, s->pos[s->r]);
  if (rc == MSOCL_OK)
    rc = msocl__launch(s, MSOCL__K_NORMALS);
  return rc == MSOCL_OK ? read_xyz(s, s->normal, xyz) : rc;
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

/* Moving a simulation's state between host and devices, and what it
 * reports about itself. With several devices each one's own range is read,
 * and writes go to every device (each holds the whole state). */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <string.h>

/* Staged points (the simulation's numbering) to the caller's xyz (the
 * model's numbering). */
static void unstage(const msocl_sim *s, float *xyz)
{
  for (int i = 0; i < s->n; i++)
    memcpy(xyz + 3 * (s->perm ? s->perm[i] : i), s->stage + 3 * i,
           3 * sizeof(float));
}

/* Every engine's own range into s->stage. */
static int read_stage(msocl_sim *s, int velocities)
{
  for (int d = 0; d < s->nparts; d++) {
    msocl__engine *e = s->part[d];
    MSOCL__TRY(msocl__state_read(e, velocities, e->lo, e->hi,
                                 s->stage + 3 * (size_t)e->lo));
  }
  return MSOCL_OK;
}

static int read_state(msocl_sim *s, int velocities, float *xyz)
{
  msocl__clear_error();
  if (!s || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       s ? "output array" : "sim");
  MSOCL__TRY(read_stage(s, velocities));
  unstage(s, xyz);
  return MSOCL_OK;
}

/* The whole state into every engine's current plane set (the pins stay
 * in their own plane). */
static int write_state(msocl_sim *s, int velocities, const float *xyz)
{
  msocl__clear_error();
  if (!s || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       s ? "input array" : "sim");
  /* a speed within the coordinates' bound too: dt v stays one */
  MSOCL__TRY(msocl__check_triples(velocities ? "msocl_sim_write_velocities"
                                             : "msocl_sim_write_positions",
                                  "point", xyz, s->n, NULL, 0,
                                  MSOCL__COORD_MAX));
  int rc = msocl__check_write(s); /* the blow-up check's part */
  if (rc != MSOCL_OK)
    return rc;
  for (int i = 0; i < s->n; i++)
    memcpy(s->stage + 3 * i, xyz + 3 * (s->perm ? s->perm[i] : i),
           3 * sizeof(float));
  for (int d = 0; d < s->nparts; d++) {
    MSOCL__TRY(msocl__state_write(s->part[d], velocities, 0, s->n, s->stage));
    msocl__planes_written(s->part[d]);
  }
  return MSOCL_OK;
}

int msocl_sim_read_positions(msocl_sim *s, float *xyz)
{
  return read_state(s, 0, xyz);
}

int msocl_sim_write_positions(msocl_sim *s, const float *xyz)
{
  return write_state(s, 0, xyz);
}

int msocl_sim_read_velocities(msocl_sim *s, float *xyz)
{
  return read_state(s, 1, xyz);
}

int msocl_sim_write_velocities(msocl_sim *s, const float *xyz)
{
  return write_state(s, 1, xyz);
}

/* On the first device; split over several, it first receives the other
 * ranges' positions (normals follow triangles, not springs). */
int msocl_sim_read_normals(msocl_sim *s, float *xyz)
{
  msocl__clear_error();
  if (!s || !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       s ? "output array" : "sim");
  msocl__engine *e = s->part[0];
  if (s->nparts > 1) {
    MSOCL__TRY(read_stage(s, 0));
    for (int d = 1; d < s->nparts; d++)
      MSOCL__TRY(msocl__state_write(e, 0, s->part[d]->lo, s->part[d]->hi,
                                    s->stage + 3 * (size_t)s->part[d]->lo));
  }
  MSOCL__TRY(msocl__state_normals(e, s->stage));
  unstage(s, xyz);
  return MSOCL_OK;
}

int msocl_sim_energy(msocl_sim *s, msocl_energy *e)
{
  msocl__clear_error();
  if (!s || !e)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  return msocl__sim_energy(s, e);
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
  *layout = s->part[0]->lay.kind;
  return MSOCL_OK;
}

int msocl_sim_sweep_steps(const msocl_sim *s, int *steps)
{
  if (!s || !steps)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  const msocl__engine *e = s->part[0];
  *steps = s->nparts == 1 && e->pl_rows_steps ? e->pl_steps_k : 1;
  return MSOCL_OK;
}

int msocl_sim_connectivity(const msocl_sim *s, int *slots, int *classes)
{
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (slots)
    *slots = s->part[0]->lay.slots;
  if (classes)
    *classes = s->part[0]->lay.classes;
  return MSOCL_OK;
}


int msocl_sim_device_info(const msocl_sim *s, msocl_device_info *info)
{
  if (!s || !info)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  *info = s->part[0]->dev->info;
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
  *iterations = s->part[0]->cg_iterations;
  *residual = s->part[0]->cg_residual;
  return MSOCL_OK;
}

int msocl_sim_split_info(const msocl_sim *s, msocl_split_info *info)
{
  if (!s || !info)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or out-pointer is NULL");
  memset(info, 0, sizeof *info);
  info->parts = s->nparts;
  for (int d = 0; d < s->nparts && d < MSOCL_MAX_DEVICES; d++)
    info->weight[d] = s->o.tuning.weights[d];
  for (int d = 0; d < s->nparts; d++) {
    info->device[d] = s->o.tuning.device + d;
    info->first[d] = s->part[d]->lo;
    info->count[d] = s->part[d]->hi - s->part[d]->lo;
    for (int e = 0; e < s->nparts; e++)
      if (e != d && s->halo[d][e][0] < s->halo[d][e][1])
        info->halo_points[d] += s->halo[d][e][1] - s->halo[d][e][0];
  }
  info->steps = s->steps;
  info->overlap = s->x.overlap;
  double bytes = 0.0;
  for (int d = 0; d < s->nparts; d++) {
    const struct msocl__xstat *st = &s->x.stat[d];
    bytes += st->bytes;
    info->copy_seconds[d] = st->copy_seconds;
    info->compute_seconds[d] = st->compute_seconds;
    info->part_exchange_seconds[d] = st->host_seconds;
    info->part_wait_seconds[d] = st->wait_seconds;
    info->hidden_copy_seconds[d] = st->hidden_seconds;
    for (int q = 0; s->x.overlap && q < s->x.nbound[d]; q++)
      info->boundary_points[d] += s->x.span[d][q][1] - s->x.span[d][q][0];
    /* the parts work at once: the slowest one is the critical path */
    if (st->host_seconds > info->exchange_seconds)
      info->exchange_seconds = st->host_seconds;
    if (st->wait_seconds > info->wait_seconds)
      info->wait_seconds = st->wait_seconds;
  }
  info->bytes_per_step =
      s->x.steps_run > 0 ? bytes / (double)s->x.steps_run : 0.0;
  return MSOCL_OK;
}

int msocl_sim_point_order(const msocl_sim *s, int *order)
{
  if (!s || !order)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim or order array is NULL");
  for (int i = 0; i < s->n; i++)
    order[i] = s->perm ? s->perm[i] : i;
  return MSOCL_OK;
}

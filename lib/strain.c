/* Strain limiting sweeps (kernels/strain.cl): Vassilev et al.'s velocity
 * correction between the velocity and position passes, Provot's position
 * correction after the step. Each sweep is a Jacobi pass from one buffer
 * into another. */
#include "config.h"
#include "sim.h"

#define TRY MSOCL__TRY

int msocl__strain_setup(msocl__engine *s)
{
  const cl_uint c = s->nconn;
  cl_kernel k;
  if ((k = s->k[MSOCL__K_STRAIN_VEL])) {
    TRY(msocl__arg_float(k, c + 3, s->o.strain_limit));
    TRY(msocl__arg_float(k, c + 4, s->o.dt));
    TRY(msocl__arg_mem(k, c + 5, s->col));
    TRY(msocl__arg_int(k, c + 6, s->ncol));
    TRY(msocl__arg_int(k, c + 7, s->n));
  }
  if ((k = s->k[MSOCL__K_STRAIN_POS])) {
    TRY(msocl__arg_float(k, c + 2, s->o.strain_limit));
    TRY(msocl__arg_int(k, c + 3, s->n));
  }
  if ((k = s->k[MSOCL__K_STRAIN_COMMIT])) {
    TRY(msocl__arg_float(k, 3, s->o.dt));
    TRY(msocl__arg_int(k, 4, s->n));
  }
  return MSOCL_OK;
}

/* Sweeps kernel `kind` from `from` (read from arg c+in, written to arg
 * c+out), ping-ponging with `to`; returns the buffer holding the result. */
static int sweeps(msocl__engine *s, int kind, cl_uint in, cl_uint out,
                  cl_mem from, cl_mem to, cl_mem *result)
{
  cl_kernel k = s->k[kind];
  for (int it = 0; it < s->o.strain_iterations; it++) {
    TRY(msocl__arg_mem(k, s->nconn + in, from));
    TRY(msocl__arg_mem(k, s->nconn + out, to));
    TRY(msocl__launch(s, kind));
    cl_mem t = from;
    from = to;
    to = t;
  }
  *result = from;
  return MSOCL_OK;
}

/* On the new velocities vel[1 - r], before the position pass. */
int msocl__strain_velocity(msocl__engine *s)
{
  cl_mem target = s->vel[1 - s->r], result;
  TRY(msocl__arg_mem(s->k[MSOCL__K_STRAIN_VEL], s->nconn, s->pos[s->r]));
  TRY(sweeps(s, MSOCL__K_STRAIN_VEL, 1, 2, target, s->stage_v[0], &result));
  if (result != target)
    MSOCL__CL(clEnqueueCopyBuffer(s->dev->queue, result, target, 0, 0,
                                  4 * (size_t)s->n * sizeof(float), 0, NULL,
                                  NULL));
  return MSOCL_OK;
}

/* On the new positions pos[1 - r], after the step (Verlet: after its
 * drift): the sweeps read them and alternate between the stage buffers,
 * leaving them as they were, then the commit moves points and the
 * velocities vel (vel[1 - r]; Verlet's half-step vel[r]) together. */
int msocl__strain_position(msocl__engine *s, cl_mem vel)
{
  const int w = 1 - s->r;
  cl_kernel k = s->k[MSOCL__K_STRAIN_POS];
  cl_mem result = s->pos[w];
  for (int it = 0; it < s->o.strain_iterations; it++) {
    TRY(msocl__arg_mem(k, s->nconn, result));
    TRY(msocl__arg_mem(k, s->nconn + 1, s->stage_p[it & 1]));
    TRY(msocl__launch(s, MSOCL__K_STRAIN_POS));
    result = s->stage_p[it & 1];
  }
  k = s->k[MSOCL__K_STRAIN_COMMIT];
  TRY(msocl__arg_mem(k, 0, s->pos[w]));
  TRY(msocl__arg_mem(k, 1, result));
  TRY(msocl__arg_mem(k, 2, vel));
  return msocl__launch(s, MSOCL__K_STRAIN_COMMIT);
}

/* Strain limiting sweeps (kernels/strain.cl): Vassilev et al.'s velocity
 * correction between the velocity and position passes, Provot's position
 * correction after the step. Each sweep is a Jacobi pass from one buffer
 * into another. */
#include "config.h"
#include "engine.h"

#define TRY MSOCL__TRY

/* Sweeps kernel `kind` from `from` (read from argument `in`, written to
 * `out`), ping-ponging with `to`; returns the buffer holding the result. */
static int sweeps(msocl__engine *s, int kind, const char *in,
                  const char *out, cl_mem from, cl_mem to, cl_mem *result)
{
  for (int it = 0; it < s->o.strain_iterations; it++) {
    TRY(msocl__set_mem(s, kind, in, from));
    TRY(msocl__set_mem(s, kind, out, to));
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
  TRY(msocl__set_mem(s, MSOCL__K_STRAIN_VEL, "pos", s->pos[s->r]));
  TRY(sweeps(s, MSOCL__K_STRAIN_VEL, "vel", "vel_out", target, s->stage_v[0],
             &result));
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
  cl_mem result = s->pos[w];
  for (int it = 0; it < s->o.strain_iterations; it++) {
    TRY(msocl__set_mem(s, MSOCL__K_STRAIN_POS, "pos", result));
    TRY(msocl__set_mem(s, MSOCL__K_STRAIN_POS, "pos_out", s->stage_p[it & 1]));
    TRY(msocl__launch(s, MSOCL__K_STRAIN_POS));
    result = s->stage_p[it & 1];
  }
  TRY(msocl__set_mem(s, MSOCL__K_STRAIN_COMMIT, "pos", s->pos[w]));
  TRY(msocl__set_mem(s, MSOCL__K_STRAIN_COMMIT, "corrected", result));
  TRY(msocl__set_mem(s, MSOCL__K_STRAIN_COMMIT, "vel", vel));
  return msocl__launch(s, MSOCL__K_STRAIN_COMMIT);
}

/* The simulation options' defaults: every layer that makes a simulation or
 * checks options against them (the reference, too) starts from these. */
#include "config.h"
#include "internal.h"

#include <math.h>
#include <string.h>

void msocl_sim_options_init(msocl_sim_options *o)
{
  if (!o)
    return;
  memset(o, 0, sizeof *o); /* the tuning: all MSOCL_AUTO */
  o->dt = 1e-3f;
  o->math = MSOCL_MATH_PRECISE;
  o->integrator = MSOCL_SYMPLECTIC_EULER;
  o->strain = MSOCL_STRAIN_NONE;
  o->strain_limit = 0.1f;
  o->strain_iterations = 10;
  o->cg_tolerance = 1e-5f;
  o->cg_max_iterations = 200;
  o->check_every = 100;
  /* Near its stability limit a symplectic method's energy swings by up to
   * 1 / (1 - h w / 2) (10x at 0.9 of the limit) without being unstable;
   * a blow-up grows exponentially and passes 100x within a few checks. */
  o->energy_factor = 100.0f;
}

/* The options' physics (what the reference runs too), as msocl.h bounds
 * them; the simulation adds its tuning's and devices' checks. */
int msocl__check_physics(const msocl_sim_options *o)
{
  if (!isfinite(o->dt))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "time step dt is %g", o->dt);
  if (!(o->dt > 0.0f))
    return msocl__fail(MSOCL_ERR_BAD_DT, "time step dt = %g must be > 0",
                       o->dt);
  if (o->math != MSOCL_MATH_PRECISE && o->math != MSOCL_MATH_RELAXED)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown math mode %d",
                       (int)o->math);
  if (o->integrator < MSOCL_SYMPLECTIC_EULER ||
      o->integrator > MSOCL_IMPLICIT_EULER)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown integrator %d",
                       (int)o->integrator);
  if (o->strain < MSOCL_STRAIN_NONE || o->strain > MSOCL_STRAIN_VELOCITY)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown strain limiting %d",
                       (int)o->strain);
  if (!(o->strain_limit >= 0.0f) || !isfinite(o->strain_limit) ||
      o->strain_iterations < 1 || o->strain_iterations > 1000)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "strain limit %g must be >= 0 and iterations %d in "
                       "[1, 1000]",
                       o->strain_limit, o->strain_iterations);
  if (!(o->cg_tolerance > 0.0f) || !isfinite(o->cg_tolerance) ||
      o->cg_max_iterations < 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "CG tolerance %g must be > 0 and iterations %d >= 1",
                       o->cg_tolerance, o->cg_max_iterations);
  if (o->check_every < 0 || !(o->energy_factor > 0.0f) ||
      !isfinite(o->energy_factor))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "check_every %d must be >= 0 and energy_factor %g > 0",
                       o->check_every, o->energy_factor);
  return MSOCL_OK;
}

/* The simulation options' defaults: every layer that makes a simulation or
 * checks options against them (the reference, too) starts from these. */
#include "config.h"
#include "internal.h"

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

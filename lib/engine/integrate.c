/* The float4 kernels' fixed arguments, and Verlet's first acceleration
 * from the float4 state the host wrote (the passes: planes.c). */
#include "config.h"
#include "schedule.h"

#define TRY MSOCL__TRY

/* Fixed arguments: everything but the state buffers, by name
 * (kernel_args.c). */
int msocl__integrate_setup(msocl__engine *s)
{
  return msocl__set_fixed(s);
}

/* The acceleration covers the whole range before any drift: its dashpots
 * read the velocities that drift changes in place, so a drift run span by
 * span must not precede it anywhere. */
int msocl__verlet_accel(msocl__engine *s)
{
  if (s->acc_valid)
    return MSOCL_OK;
  TRY(msocl__set_mem(s, MSOCL__K_ACCEL, "pos", s->pos[s->r]));
  TRY(msocl__set_mem(s, MSOCL__K_ACCEL, "vel", s->vel[s->r]));
  TRY(msocl__launch_range(s, MSOCL__K_ACCEL));
  s->acc_valid = 1;
  return MSOCL_OK;
}

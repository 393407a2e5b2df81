/* The float4 engine's passes (schedule.h), over the state buffers of a
 * simulation (implicit Euler's CG: integrate_implicit.c), and its kernels'
 * fixed arguments (the gathering kernels': kernel_args.c). */
#include "config.h"
#include "schedule.h"

#define TRY MSOCL__TRY

/* Fixed arguments: everything but the state buffers that ping-pong, by
 * name (kernel_args.c). */
int msocl__integrate_setup(msocl__engine *s)
{
  return msocl__set_fixed(s);
}

/* The position pass of the symplectic and implicit steps: pos[w] from
 * pos[r] and the new velocity vel[w]. */
static int position_pass(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  TRY(msocl__set_mem(s, MSOCL__K_POSITION, "pos", s->pos[r]));
  TRY(msocl__set_mem(s, MSOCL__K_POSITION, "vel", s->vel[w]));
  TRY(msocl__set_mem(s, MSOCL__K_POSITION, "pos_out", s->pos[w]));
  return msocl__launch(s, MSOCL__K_POSITION);
}

/* The velocity pass of the paper's two. */
static int symplectic_velocity(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  TRY(msocl__set_mem(s, MSOCL__K_VELOCITY, "pos", s->pos[r]));
  TRY(msocl__set_mem(s, MSOCL__K_VELOCITY, "vel", s->vel[r]));
  TRY(msocl__set_mem(s, MSOCL__K_VELOCITY, "vel_out", s->vel[w]));
  return msocl__launch(s, MSOCL__K_VELOCITY);
}

/* A one-pass step, kernel k (fused symplectic or explicit Euler), from
 * state r into w. */
static int one_pass(msocl__engine *s, int k)
{
  const int r = s->r, w = 1 - r;
  TRY(msocl__set_mem(s, k, "pos", s->pos[r]));
  TRY(msocl__set_mem(s, k, "vel", s->vel[r]));
  TRY(msocl__set_mem(s, k, "pos_out", s->pos[w]));
  TRY(msocl__set_mem(s, k, "vel_out", s->vel[w]));
  return msocl__launch(s, k);
}

/* Verlet, kick-drift-kick. Drift: turns vel[r] into the half-step velocity
 * in place and writes pos[w] (first computing the acceleration, when the
 * state is new). Kick: gathers at (pos[w], v+), writes vel[w] and the
 * acceleration the next step starts from. The acceleration covers the
 * whole range before any drift: its dashpots read the velocities that
 * drift changes in place, so a drift run span by span must not precede
 * it anywhere. */
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

static int verlet_drift(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  TRY(msocl__verlet_accel(s));
  TRY(msocl__set_mem(s, MSOCL__K_DRIFT, "pos", s->pos[r]));
  TRY(msocl__set_mem(s, MSOCL__K_DRIFT, "vel", s->vel[r]));
  TRY(msocl__set_mem(s, MSOCL__K_DRIFT, "pos_out", s->pos[w]));
  return msocl__launch(s, MSOCL__K_DRIFT);
}

static int verlet_kick(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  TRY(msocl__set_mem(s, MSOCL__K_KICK, "pos", s->pos[w]));
  TRY(msocl__set_mem(s, MSOCL__K_KICK, "vel", s->vel[r]));
  TRY(msocl__set_mem(s, MSOCL__K_KICK, "vel_out", s->vel[w]));
  return msocl__launch(s, MSOCL__K_KICK);
}

/* RK4 stage q: the stage states alternate between two buffer pairs so no
 * kernel writes what its neighbours read; the last writes pos[w], vel[w]. */
static int rk4_stage(msocl__engine *s, int q)
{
  const int r = s->r, w = 1 - r, k = MSOCL__K_RK4;
  const float cs[4] = {0.5f, 0.5f, 1.0f, 0.0f};
  const int modes[4] = {0, 1, 1, 2};
  const int in = (q - 1) & 1, out = q & 1;
  TRY(msocl__set_mem(s, k, "p0", s->pos[r]));
  TRY(msocl__set_mem(s, k, "v0", s->vel[r]));
  TRY(msocl__set_mem(s, k, "sp", q == 0 ? s->pos[r] : s->stage_p[in]));
  TRY(msocl__set_mem(s, k, "sv", q == 0 ? s->vel[r] : s->stage_v[in]));
  TRY(msocl__set_mem(s, k, "np", q == 3 ? s->pos[w] : s->stage_p[out]));
  TRY(msocl__set_mem(s, k, "nv", q == 3 ? s->vel[w] : s->stage_v[out]));
  TRY(msocl__set_float(s, k, "c", cs[q]));
  TRY(msocl__set_int(s, k, "mode", modes[q]));
  return msocl__launch(s, k);
}

/* Within a phase only the first pass reads other points (a gather); the
 * rest read their own point's results, so a phase may run span by span
 * (the one exception, Verlet's first acceleration, covers the whole range
 * itself). */
int msocl__float4_pass(msocl__engine *s, enum msocl__pass p)
{
  switch (p) {
  case MSOCL__P_VELOCITY: return symplectic_velocity(s);
  case MSOCL__P_STRAIN_VEL: return msocl__strain_velocity(s);
  case MSOCL__P_POSITION: return position_pass(s);
  case MSOCL__P_FUSED: return one_pass(s, MSOCL__K_FUSED);
  case MSOCL__P_EULER: return one_pass(s, MSOCL__K_EULER);
  case MSOCL__P_DRIFT: return verlet_drift(s);
  case MSOCL__P_KICK: return verlet_kick(s);
  case MSOCL__P_RK4_0:
  case MSOCL__P_RK4_1:
  case MSOCL__P_RK4_2:
  case MSOCL__P_RK4_3: return rk4_stage(s, (int)(p - MSOCL__P_RK4_0));
  case MSOCL__P_PROVOT: return msocl__strain_position(s, s->vel[1 - s->r]);
  case MSOCL__P_PROVOT_HALF: return msocl__strain_position(s, s->vel[s->r]);
  case MSOCL__P_CG: break;
  }
  return msocl__fail(MSOCL_ERR_INVALID_ARG, "no float4 pass %d", (int)p);
}

cl_mem msocl__exchange_buffer(const msocl__engine *s, unsigned bit)
{
  if (s->planes)
    return msocl__planes_exchange_buffer(s, bit);
  switch (bit) {
  case MSOCL__X_POS_W: return s->pos[1 - s->r];
  case MSOCL__X_VEL_W: return s->vel[1 - s->r];
  case MSOCL__X_VEL_R: return s->vel[s->r];
  case MSOCL__X_STAGE0: return s->stage_p[0];
  case MSOCL__X_STAGE1: return s->stage_p[1];
  case MSOCL__X_STAGEV0: return s->stage_v[0];
  case MSOCL__X_STAGEV1: return s->stage_v[1];
  case MSOCL__X_CG_P: return s->stage_v[0];
  }
  return NULL;
}

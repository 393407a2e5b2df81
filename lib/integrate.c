/* The float4 engine's passes (schedule.h), over the state buffers of a
 * simulation (implicit Euler's CG: integrate_implicit.c), and its kernels'
 * fixed arguments (the gathering kernels': kernel_args.c). */
#include "config.h"
#include "schedule.h"

static int arg_vec(cl_kernel k, cl_uint i, const cl_float4 *v)
{
  MSOCL__CL(clSetKernelArg(k, i, sizeof *v, v));
  return MSOCL_OK;
}

/* Sets buffers args[0..n) from argument `first` on. */
static int mems(cl_kernel k, cl_uint first, int n, const cl_mem *args)
{
  for (int q = 0; q < n; q++) {
    int rc = msocl__arg_mem(k, first + (cl_uint)q, args[q]);
    if (rc != MSOCL_OK)
      return rc;
  }
  return MSOCL_OK;
}

#define TRY MSOCL__TRY

/* The tail the point passes that end a symplectic or explicit Euler step
 * share: inverse masses, gravity, viscous damping, air, dt, colliders, n. */
static int point_pass_args(msocl__engine *s, cl_kernel k, cl_uint a)
{
  TRY(msocl__arg_mem(k, a, s->inv_mass));
  TRY(arg_vec(k, a + 1, &s->gravity));
  TRY(msocl__arg_float(k, a + 2, s->viscous));
  TRY(msocl__arg_float(k, a + 3, s->air));
  TRY(msocl__arg_float(k, a + 4, s->o.dt));
  TRY(msocl__arg_mem(k, a + 5, s->col));
  TRY(msocl__arg_int(k, a + 6, s->ncol));
  return msocl__arg_int(k, a + 7, s->n);
}

/* Fixed arguments: everything but the state buffers that ping-pong; the
 * float4 kernels' by name (kernel_args.c), the EDGES kernels' here. */
int msocl__integrate_setup(msocl__engine *s)
{
  cl_kernel k;
  TRY(msocl__set_fixed(s));
  if ((k = s->k[MSOCL__K_EDGES_FORCE])) {
    TRY(msocl__arg_mem(k, 0, s->lay.con));
    TRY(msocl__arg_mem(k, 1, s->lay.rk));
    TRY(msocl__arg_mem(k, 2, s->lay.damp));
    TRY(msocl__arg_mem(k, 5, s->force));
    TRY(msocl__arg_int(k, 6, s->lay.nsprings));
  }
  if ((k = s->k[MSOCL__K_EDGES_VEL])) {
    TRY(msocl__arg_mem(k, 3, s->force));
    TRY(point_pass_args(s, k, 4));
  }
  if ((k = s->k[MSOCL__K_EDGES_ENERGY])) {
    TRY(msocl__arg_mem(k, 0, s->lay.con));
    TRY(msocl__arg_mem(k, 1, s->lay.rk));
    TRY(msocl__arg_mem(k, 3, s->partial));
    TRY(msocl__arg_int(k, 4, s->lay.nsprings));
  }
  return MSOCL_OK;
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

/* EDGES: the per-spring pass scatters forces, then the per-point pass
 * integrates and clears them. */
static int edges_velocity(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  cl_kernel f = s->k[MSOCL__K_EDGES_FORCE];
  TRY(msocl__arg_mem(f, 3, s->pos[r]));
  TRY(msocl__arg_mem(f, 4, s->vel[r]));
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, f, 1, NULL,
                                   &s->edge_global, NULL, 0, NULL, NULL));
  cl_mem v[3] = {s->pos[r], s->vel[r], s->vel[w]};
  TRY(mems(s->k[MSOCL__K_EDGES_VEL], 0, 3, v));
  return msocl__launch(s, MSOCL__K_EDGES_VEL);
}

/* The velocity pass of the paper's two (EDGES: scatter, then integrate). */
static int symplectic_velocity(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  if (s->lay.kind == MSOCL_LAYOUT_EDGES)
    return edges_velocity(s);
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

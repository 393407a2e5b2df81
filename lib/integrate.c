/* The float4 engine's passes (schedule.h), over the state buffers of a
 * simulation, and its kernels' fixed arguments (implicit Euler's CG:
 * integrate_implicit.c). */
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

/* Fixed arguments: everything but the state buffers that ping-pong. The
 * argument orders are those of the kernels in kernels/. */
int msocl__integrate_setup(msocl__engine *s)
{
  const cl_uint c = s->nconn;
  const float dt = s->o.dt;
  cl_kernel k;
  if ((k = s->k[MSOCL__K_VELOCITY]))
    TRY(point_pass_args(s, k, c + 3));
  if ((k = s->k[MSOCL__K_FUSED]))
    TRY(point_pass_args(s, k, c + 4));
  if ((k = s->k[MSOCL__K_POSITION])) {
    TRY(msocl__arg_float(k, 3, dt));
    TRY(msocl__arg_int(k, 4, s->n));
  }
  if ((k = s->k[MSOCL__K_NORMALS])) {
    TRY(msocl__arg_mem(k, 1, s->tri_off));
    TRY(msocl__arg_mem(k, 2, s->tri_ab));
    TRY(msocl__arg_mem(k, 3, s->normal));
    TRY(msocl__arg_int(k, 4, s->n));
  }
  if ((k = s->k[MSOCL__K_EULER]))
    TRY(point_pass_args(s, k, c + 4));
  if ((k = s->k[MSOCL__K_ACCEL])) {
    TRY(msocl__arg_mem(k, c + 2, s->acc));
    TRY(msocl__arg_mem(k, c + 3, s->inv_mass));
    TRY(arg_vec(k, c + 4, &s->gravity));
    TRY(msocl__arg_float(k, c + 5, s->viscous));
    TRY(msocl__arg_int(k, c + 6, s->n));
  }
  if ((k = s->k[MSOCL__K_DRIFT])) {
    TRY(msocl__arg_mem(k, 2, s->acc));
    TRY(msocl__arg_float(k, 4, dt));
    TRY(msocl__arg_mem(k, 5, s->col));
    TRY(msocl__arg_int(k, 6, s->ncol));
    TRY(msocl__arg_int(k, 7, s->n));
  }
  if ((k = s->k[MSOCL__K_KICK])) {
    TRY(msocl__arg_mem(k, c + 3, s->acc));
    TRY(msocl__arg_mem(k, c + 4, s->inv_mass));
    TRY(arg_vec(k, c + 5, &s->gravity));
    TRY(msocl__arg_float(k, c + 6, s->viscous));
    TRY(msocl__arg_float(k, c + 7, s->air));
    TRY(msocl__arg_float(k, c + 8, dt));
    TRY(msocl__arg_int(k, c + 9, s->n));
  }
  if ((k = s->k[MSOCL__K_RK4])) {
    TRY(msocl__arg_mem(k, c + 4, s->sum_p));
    TRY(msocl__arg_mem(k, c + 5, s->sum_v));
    TRY(msocl__arg_mem(k, c + 8, s->inv_mass));
    TRY(arg_vec(k, c + 9, &s->gravity));
    TRY(msocl__arg_float(k, c + 10, s->viscous));
    TRY(msocl__arg_float(k, c + 11, s->air));
    TRY(msocl__arg_float(k, c + 13, dt));
    TRY(msocl__arg_mem(k, c + 15, s->col));
    TRY(msocl__arg_int(k, c + 16, s->ncol));
    TRY(msocl__arg_int(k, c + 17, s->n));
  }
  if ((k = s->k[MSOCL__K_ENERGY])) {
    TRY(msocl__arg_mem(k, c + 2, s->inv_mass));
    TRY(arg_vec(k, c + 3, &s->gravity));
    TRY(msocl__arg_mem(k, c + 4, s->partial));
    TRY(msocl__arg_int(k, c + 5, s->n));
    TRY(msocl__arg_int(k, c + 6, s->hi));
  }
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
  if (s->o.integrator == MSOCL_IMPLICIT_EULER)
    TRY(msocl__implicit_setup(s));
  return msocl__strain_setup(s);
}

/* The position pass of the symplectic and implicit steps: pos[w] from
 * pos[r] and the new velocity vel[w]. */
static int position_pass(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  cl_mem p[3] = {s->pos[r], s->vel[w], s->pos[w]};
  TRY(mems(s->k[MSOCL__K_POSITION], 0, 3, p));
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
  cl_mem v[3] = {s->pos[r], s->vel[r], s->vel[w]};
  TRY(mems(s->k[MSOCL__K_VELOCITY], s->nconn, 3, v));
  return msocl__launch(s, MSOCL__K_VELOCITY);
}

/* Both symplectic passes in one kernel. */
static int fused_pass(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  cl_mem a[4] = {s->pos[r], s->vel[r], s->pos[w], s->vel[w]};
  TRY(mems(s->k[MSOCL__K_FUSED], s->nconn, 4, a));
  return msocl__launch(s, MSOCL__K_FUSED);
}

static int explicit_euler(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  cl_mem a[4] = {s->pos[r], s->vel[r], s->pos[w], s->vel[w]};
  TRY(mems(s->k[MSOCL__K_EULER], s->nconn, 4, a));
  return msocl__launch(s, MSOCL__K_EULER);
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
  cl_mem a[2] = {s->pos[s->r], s->vel[s->r]};
  TRY(mems(s->k[MSOCL__K_ACCEL], s->nconn, 2, a));
  TRY(msocl__launch_range(s, MSOCL__K_ACCEL));
  s->acc_valid = 1;
  return MSOCL_OK;
}

static int verlet_drift(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  TRY(msocl__verlet_accel(s));
  cl_mem d[2] = {s->pos[r], s->vel[r]};
  TRY(mems(s->k[MSOCL__K_DRIFT], 0, 2, d));
  TRY(msocl__arg_mem(s->k[MSOCL__K_DRIFT], 3, s->pos[w]));
  return msocl__launch(s, MSOCL__K_DRIFT);
}

static int verlet_kick(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  cl_mem k[3] = {s->pos[w], s->vel[r], s->vel[w]};
  TRY(mems(s->k[MSOCL__K_KICK], s->nconn, 3, k));
  return msocl__launch(s, MSOCL__K_KICK);
}

/* RK4 stage q: the stage states alternate between two buffer pairs so no
 * kernel writes what its neighbours read; the last writes pos[w], vel[w]. */
static int rk4_stage(msocl__engine *s, int q)
{
  const cl_uint c = s->nconn;
  const int r = s->r, w = 1 - r;
  cl_kernel k = s->k[MSOCL__K_RK4];
  const float cs[4] = {0.5f, 0.5f, 1.0f, 0.0f};
  const int modes[4] = {0, 1, 1, 2};
  cl_mem sp = q == 0 ? s->pos[r] : s->stage_p[(q - 1) & 1];
  cl_mem sv = q == 0 ? s->vel[r] : s->stage_v[(q - 1) & 1];
  cl_mem np = q == 3 ? s->pos[w] : s->stage_p[q & 1];
  cl_mem nv = q == 3 ? s->vel[w] : s->stage_v[q & 1];
  cl_mem y0[2] = {s->pos[r], s->vel[r]}, a[2] = {sp, sv}, b[2] = {np, nv};
  TRY(mems(k, c, 2, y0));
  TRY(mems(k, c + 2, 2, a));
  TRY(mems(k, c + 6, 2, b));
  TRY(msocl__arg_float(k, c + 12, cs[q]));
  TRY(msocl__arg_int(k, c + 14, modes[q]));
  return msocl__launch(s, MSOCL__K_RK4);
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
  case MSOCL__P_FUSED: return fused_pass(s);
  case MSOCL__P_EULER: return explicit_euler(s);
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

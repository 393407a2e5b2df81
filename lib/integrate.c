/* The schedule of kernels each explicit integrator runs per step, over the
 * state buffers of a simulation (implicit Euler: integrate_implicit.c). */
#include "config.h"
#include "sim.h"

int msocl__arg_mem(cl_kernel k, cl_uint i, cl_mem m)
{
  MSOCL__CL(clSetKernelArg(k, i, sizeof m, &m));
  return MSOCL_OK;
}

int msocl__arg_float(cl_kernel k, cl_uint i, float f)
{
  MSOCL__CL(clSetKernelArg(k, i, sizeof f, &f));
  return MSOCL_OK;
}

int msocl__arg_int(cl_kernel k, cl_uint i, int v)
{
  MSOCL__CL(clSetKernelArg(k, i, sizeof v, &v));
  return MSOCL_OK;
}

static int arg_vec(cl_kernel k, cl_uint i, const cl_float4 *v)
{
  MSOCL__CL(clSetKernelArg(k, i, sizeof *v, v));
  return MSOCL_OK;
}

/* Work-group size of a launch over `global` points. Left to choose (NULL),
 * PoCL's CPU device takes the largest group that still gives each core one:
 * 3 groups of 3072 at 96x96 on 2 cores, so one core idles a third of the
 * time (and a core slowed by other jobs cannot hand work over). Groups of
 * 64 share out evenly and cost nothing measurable at 512x512. GPUs keep
 * their driver's choice (not measured). */
static const size_t *group(const msocl__engine *s, size_t global)
{
  static const size_t cpu = 64;
  return s->dev->info.type == MSOCL_DEVICE_CPU && global % cpu == 0 ? &cpu
                                                                     : NULL;
}

int msocl__launch(msocl__engine *s, int k)
{
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[k], 1, &s->run_offset,
                                   &s->run_global, group(s, s->run_global), 0,
                                   NULL, NULL));
  return MSOCL_OK;
}

/* Over the engine's whole range, whatever span the phase runs on. */
static int launch_range(msocl__engine *s, int k)
{
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[k], 1, &s->offset,
                                   &s->global, group(s, s->global), 0, NULL,
                                   NULL));
  return MSOCL_OK;
}

int msocl__launch_all(msocl__engine *s, int k)
{
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, s->k[k], 1, NULL,
                                   &s->full_global, group(s, s->full_global),
                                   0, NULL, NULL));
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
  if (s->lay.kind == MSOCL_LAYOUT_EDGES)
    TRY(msocl__edges_setup(s));
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

/* The velocity pass of the paper's two (EDGES: the whole step),
 * with the velocity strain correction after it when asked for. */
static int symplectic_velocity(msocl__engine *s)
{
  const int r = s->r, w = 1 - r;
  if (s->lay.kind == MSOCL_LAYOUT_EDGES)
    return msocl__edges_velocity(s);
  cl_mem v[3] = {s->pos[r], s->vel[r], s->vel[w]};
  TRY(mems(s->k[MSOCL__K_VELOCITY], s->nconn, 3, v));
  TRY(msocl__launch(s, MSOCL__K_VELOCITY));
  if (s->o.strain == MSOCL_STRAIN_VELOCITY)
    TRY(msocl__strain_velocity(s));
  return MSOCL_OK;
}

static int implicit_velocity(msocl__engine *s)
{
  TRY(msocl__implicit_velocity(s));
  if (s->o.strain == MSOCL_STRAIN_VELOCITY)
    TRY(msocl__strain_velocity(s));
  return MSOCL_OK;
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
  TRY(launch_range(s, MSOCL__K_ACCEL));
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

int msocl__phase_count(const msocl__engine *s)
{
  switch (s->o.integrator) {
  case MSOCL_SYMPLECTIC_EULER:
    return s->o.fused || s->lay.kind == MSOCL_LAYOUT_EDGES ? 1 : 2;
  case MSOCL_EXPLICIT_EULER: return 1;
  case MSOCL_VERLET: return 2;
  case MSOCL_RK4: return 4;
  case MSOCL_IMPLICIT_EULER: return 2;
  }
  return 0;
}

/* What the other engines must receive after each phase: the positions
 * every gather reads, and the velocities too when dashpots read them
 * (implicit Euler's right-hand side reads neighbours' velocities, K v,
 * even without). */
unsigned msocl__phase_mask(const msocl__engine *s, int phase)
{
  const unsigned vel_w = s->damped ? MSOCL__X_VEL_W : 0;
  if (s->o.fused || s->lay.kind == MSOCL_LAYOUT_EDGES)
    return MSOCL__X_POS_W | vel_w;
  switch (s->o.integrator) {
  case MSOCL_SYMPLECTIC_EULER:
    return phase == 0 ? 0 : MSOCL__X_POS_W | vel_w;
  case MSOCL_IMPLICIT_EULER:
    return phase == 0 ? 0 : MSOCL__X_POS_W | MSOCL__X_VEL_W;
  case MSOCL_EXPLICIT_EULER:
    return MSOCL__X_POS_W | vel_w;
  case MSOCL_VERLET:
    return phase == 0 ? MSOCL__X_POS_W | (s->damped ? MSOCL__X_VEL_R : 0)
                      : vel_w;
  case MSOCL_RK4:
    if (phase == 3)
      return MSOCL__X_POS_W | vel_w;
    if (phase & 1)
      return MSOCL__X_STAGE1 | (s->damped ? MSOCL__X_STAGEV1 : 0);
    return MSOCL__X_STAGE0 | (s->damped ? MSOCL__X_STAGEV0 : 0);
  }
  return 0;
}

/* Within a phase, only the first kernel reads other points (a gather);
 * the rest read their own point's results, so a phase may run span by
 * span (the one exception, Verlet's first acceleration, covers the whole
 * range itself). */
int msocl__phase(msocl__engine *s, int phase, unsigned *exchange)
{
  const int last = phase == msocl__phase_count(s) - 1;
  *exchange = msocl__phase_mask(s, phase);
  if (s->o.fused) { /* both passes in one kernel */
    const int r = s->r, w = 1 - r;
    cl_mem a[4] = {s->pos[r], s->vel[r], s->pos[w], s->vel[w]};
    TRY(mems(s->k[MSOCL__K_FUSED], s->nconn, 4, a));
    TRY(msocl__launch(s, MSOCL__K_FUSED));
    if (s->o.strain == MSOCL_STRAIN_PROVOT)
      TRY(msocl__strain_position(s, s->vel[1 - s->r]));
    return MSOCL_OK;
  }
  switch (s->o.integrator) {
  case MSOCL_SYMPLECTIC_EULER:
  case MSOCL_IMPLICIT_EULER:
    if (phase == 0)
      TRY(s->o.integrator == MSOCL_IMPLICIT_EULER ? implicit_velocity(s)
                                                  : symplectic_velocity(s));
    else
      TRY(position_pass(s));
    break;
  case MSOCL_EXPLICIT_EULER:
    TRY(explicit_euler(s));
    break;
  case MSOCL_VERLET:
    if (phase == 1)
      return verlet_kick(s);
    TRY(verlet_drift(s));
    /* Provot's correction between drift and kick, on v+: the kick then
     * keeps the corrected positions' acceleration for the next step. After
     * the kick, the next drift used the acceleration of positions the
     * correction had moved, and a hanging cloth blew up at half the
     * stable step. */
    if (s->o.strain == MSOCL_STRAIN_PROVOT)
      TRY(msocl__strain_position(s, s->vel[s->r]));
    return MSOCL_OK;
  case MSOCL_RK4:
    TRY(rk4_stage(s, phase));
    break;
  }
  if (last && s->o.strain == MSOCL_STRAIN_PROVOT)
    TRY(msocl__strain_position(s, s->vel[1 - s->r]));
  return MSOCL_OK;
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

void msocl__step_done(msocl__engine *s)
{
  s->r = 1 - s->r;
}

int msocl__integrate(msocl__engine *s, int n)
{
  if (s->planes)
    return msocl__planes_steps(s, n);
  const int phases = msocl__phase_count(s);
  for (int q = 0; q < n; q++) {
    for (int ph = 0; ph < phases; ph++) {
      unsigned x;
      TRY(msocl__phase(s, ph, &x));
    }
    msocl__step_done(s);
    if ((q + 1) % 64 == 0)
      MSOCL__CL(clFlush(s->dev->queue));
  }
  return MSOCL_OK;
}

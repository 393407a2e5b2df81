/* Symplectic Euler on a cloth grid in planes in one sweep a step, each
 * spring computed once (kernels/planes_rows.cl), where it applies: a CPU
 * device, a cloth (not a lattice), no strain limit or Provot's (whose
 * sweeps follow the step's two passes, so the sweep's end), rows of at
 * least one vector. Elsewhere planes.c's passes run. Where nothing acts
 * between steps (no collider moving, no field, soft pins or wind of
 * wind.c's own), up to ROWS_STEPS steps run in one launch
 * (sweep_steps.c says how many). */
#include "config.h"
#include "planes.h"
#include "schedule.h"

#include <math.h>

#define ROWS_W MSOCL__WIDE_W
/* steps a launch at most, rings of terms and middle states a block
 * (MSOCL_ROWS_STEPS) */
#define ROWS_STEPS MSOCL_MAX_SWEEP_STEPS

/* Work-items a CPU compute unit: blocks of rows, each sweeping two rows
 * more than its own, handed to the device's threads as they come free. */
#define BLOCKS_PER_UNIT 2

static int applies(const msocl__engine *s)
{
  /* its blocks sweep the whole grid: a split's engine runs the two
   * passes over its own rows instead */
  return s->dev->info.type == MSOCL_DEVICE_CPU &&
         s->lo == 0 && s->hi == s->n &&
         s->lay.grid_nz == 0 && s->lay.grid_nx >= ROWS_W &&
         s->o.integrator == MSOCL_SYMPLECTIC_EULER &&
         s->o.strain != MSOCL_STRAIN_VELOCITY;
}

/* A ring row's width: a padded row's columns -2..nx in whole vectors,
 * 64 k + 16 floats, so that widths share programs (the kernel takes it as
 * a constant) and term rows, 64 bytes off a multiple of 256, fall in every
 * L1 set. */
static int ring_width(const msocl__engine *s)
{
  return (s->lay.grid_nx + 3 + 47) / 64 * 64 + ROWS_W;
}

int msocl__pl_rows_ring_w(const msocl__engine *s)
{
  return s->dev->info.type == MSOCL_DEVICE_CPU &&
                 s->lay.kind == MSOCL_LAYOUT_GRID && s->lay.grid_nz == 0
             ? ring_width(s)
             : 0;
}

/* A sweep kernel's arguments that hold for the engine's life. */
static int fixed_args(msocl__engine *s, cl_kernel k, int ring_w)
{
  const struct msocl__named fixed[] = {
      {"aux", sizeof s->pl_aux, &s->pl_aux},
      {"pitch", sizeof(int), &s->pl_pitch},
      {"plane", sizeof(int), &s->pl_plane},
      {"gravity", sizeof s->gravity, &s->gravity},
      {"viscous", sizeof(float), &s->viscous},
      {"air", sizeof(float), &s->air},
      {"dt", sizeof(float), &s->o.dt},
      {"col", sizeof s->pl_col, &s->pl_col},
      {"ring", sizeof s->pl_ring, &s->pl_ring},
      {"ring_w", sizeof ring_w, &ring_w}};
  MSOCL__TRY(msocl__layout_set_args(&s->lay, s->dev, k));
  for (size_t q = 0; q < sizeof fixed / sizeof fixed[0]; q++)
    MSOCL__TRY(msocl__arg(s, k, fixed[q].name, fixed[q].size, fixed[q].v));
  return MSOCL_OK;
}

/* The sweep's kernels from prog, their arguments set, their wind off. */
static int sweep_kernel(msocl__engine *s, cl_program prog)
{
  MSOCL__TRY(msocl__kernel_make(s->dev, prog, "msocl_planes_rows",
                                &s->pl_rows));
  MSOCL__TRY(msocl__kernel_make(s->dev, prog, "msocl_planes_rows_still",
                                &s->pl_rows_still));
  const int ring_w = ring_width(s);
  for (int q = 0; q < 2; q++)
    MSOCL__TRY(fixed_args(s, q ? s->pl_rows_still : s->pl_rows, ring_w));
  MSOCL__TRY(msocl__kernel_make(s->dev, prog, "msocl_planes_rows_steps",
                                &s->pl_rows_steps));
  MSOCL__TRY(fixed_args(s, s->pl_rows_steps, ring_w));
  MSOCL__TRY(msocl__arg_mem(s, s->pl_rows_steps, "mid", s->pl_mid));
  return msocl__pl_rows_wind(s, NULL, 0.0f, 0.0f);
}

int msocl__pl_rows_rebuild(msocl__engine *s, cl_program prog)
{
  if (!s->pl_rows)
    return MSOCL_OK;
  msocl__kernel_free(s->dev, &s->pl_rows);
  msocl__kernel_free(s->dev, &s->pl_rows_still);
  msocl__kernel_free(s->dev, &s->pl_rows_steps);
  if (applies(s))
    return sweep_kernel(s, prog);
  /* a capsule or box: the other planes kernels from now on */
  clReleaseMemObject(s->pl_ring);
  s->pl_ring = NULL;
  if (s->pl_mid)
    clReleaseMemObject(s->pl_mid);
  s->pl_mid = NULL;
  s->pl_rows_wind = 0;
  return MSOCL_OK;
}

int msocl__pl_rows_create(msocl__engine *s, cl_program prog)
{
  if (!applies(s))
    return MSOCL_OK;
  size_t blocks = BLOCKS_PER_UNIT * (size_t)(s->dev->info.compute_units
                                                 ? s->dev->info.compute_units
                                                 : 1);
  if (blocks > (size_t)s->lay.grid_ny)
    blocks = (size_t)s->lay.grid_ny;
  s->pl_blocks = blocks;
  msocl__sweep_steps_init(s);
  /* several steps a launch: a block a unit, as a block's first steps
   * sweep rows of its neighbours' too */
  s->pl_steps_blocks = (blocks + BLOCKS_PER_UNIT - 1) / BLOCKS_PER_UNIT;
  const size_t rings = s->pl_steps_blocks * ROWS_STEPS > blocks
                           ? s->pl_steps_blocks * ROWS_STEPS
                           : blocks;
  /* a ring row: 24 terms (springs' 18, wind's 6), with dashpots 18 more
   * (the kernel's MSOCL_ROWS_TERMS), of ring_width columns */
  const int ring_w = ring_width(s);
  const size_t terms = s->damped ? 42 : 24;
  /* a ring a block, or a step a block */
  const size_t bytes = rings * 3 * terms * (size_t)ring_w * sizeof(float);
  int rc = MSOCL_OK;
  s->pl_ring = msocl__buffer(s->dev, CL_MEM_READ_WRITE, bytes, NULL, "rings",
                             &rc);
  /* NaN in the positions' padding: the kernel's missing neighbours (the
   * other planes kernels test the grid's edges and ignore it) */
  const float nan = NAN;
  /* the middle states of several steps a launch: four rows of six planes
   * a step a block (the kernel's msocl_rows_mid), NaN where the kernel
   * never writes */
  const size_t mid = s->pl_steps_blocks * ROWS_STEPS *
                         (4 * 6 * (size_t)s->pl_pitch + ROWS_W) +
                     ROWS_W;
  s->pl_mid = msocl__buffer(s->dev, CL_MEM_READ_WRITE, mid * sizeof(float),
                            NULL, "middle rows", &rc);
  MSOCL__TRY(rc);
  MSOCL__CL(clEnqueueFillBuffer(s->dev->queue, s->pl_mid, &nan, sizeof nan,
                                0, mid * sizeof(float), 0, NULL, NULL));
  for (int q = 0; q < 2; q++)
    MSOCL__CL(clEnqueueFillBuffer(s->dev->queue, s->pl_p[q], &nan, sizeof nan,
                                  0, 3 * (size_t)s->pl_plane * sizeof(float),
                                  0, NULL, NULL));
  return sweep_kernel(s, prog);
}

int msocl__pl_rows_wind(msocl__engine *s, const float air[3], float kd,
                        float kl)
{
  const cl_float4 w = {{air ? air[0] : 0.0f, air ? air[1] : 0.0f,
                        air ? air[2] : 0.0f, 0.0f}},
                  c = {{kd, kl, 0.0f, 0.0f}};
  const int on = air != NULL;
  for (int q = 0; q < 3; q++) {
    cl_kernel k = q == 2 ? s->pl_rows_steps : q ? s->pl_rows_still : s->pl_rows;
    MSOCL__TRY(msocl__arg(s, k, "wind_air", sizeof w, &w));
    MSOCL__TRY(msocl__arg(s, k, "wind_coef", sizeof c, &c));
    MSOCL__TRY(msocl__arg_int(s, k, "wind", on));
  }
  s->pl_rows_wind = on;
  return MSOCL_OK;
}

/* Sweep kernel k from plane set r into set w (its velocities into set
 * out), over `blocks` work-items of one. */
static int sweep(msocl__engine *s, cl_kernel k, int r, int w, int out,
                 size_t blocks)
{
  MSOCL__TRY(msocl__arg_mem(s, k, "p", s->pl_p[r]));
  MSOCL__TRY(msocl__arg_mem(s, k, "v", s->pl_v[r]));
  MSOCL__TRY(msocl__arg_mem(s, k, "p_out", s->pl_p[w]));
  MSOCL__TRY(msocl__arg_mem(s, k, "v_out", s->pl_v[out]));
  const size_t one = 1;
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 1, NULL, &blocks, &one,
                                   0, NULL, NULL));
  return MSOCL_OK;
}

int msocl__pl_rows_step(msocl__engine *s, int r, int w)
{
  /* without wind or dashpots the velocities move in place; with them,
   * into set w, as they read the neighbours' velocities before the step */
  const int out = s->pl_rows_wind || s->damped ? w : r;
  cl_kernel k = s->pl_col_moving ? s->pl_rows : s->pl_rows_still;
  MSOCL__TRY(sweep(s, k, r, w, out, s->pl_blocks));
  if (out == r) {
    /* moved in place: set w's velocities are now that buffer */
    const cl_mem t = s->pl_v[r];
    s->pl_v[r] = s->pl_v[w];
    s->pl_v[w] = t;
  }
  return MSOCL_OK;
}

int msocl__pl_rows_steps(msocl__engine *s, int n, int *done)
{
  *done = 0;
  /* wind the sweep does not blow (wind.c's kernels) runs between steps */
  if (n < 2 || !s->pl_rows_steps || s->pl_col_moving ||
      (s->wind_on && !s->pl_rows_wind) || s->field_on || s->soft_m != 0 ||
      s->o.strain != MSOCL_STRAIN_NONE)
    return MSOCL_OK;
  int start, end;
  const int r = s->pl_set, w = 1 - r,
            k = msocl__sweep_next(s, n, &start, &end);
  if (k < 2)
    return MSOCL_OK;
  MSOCL__TRY(msocl__arg_int(s, s->pl_rows_steps, "steps", k));
  if (start) {
    MSOCL__CL(clFinish(s->dev->queue));
    s->pl_trial_t0 = msocl__seconds();
  }
  MSOCL__TRY(sweep(s, s->pl_rows_steps, r, w, w, s->pl_steps_blocks));
  if (end) {
    MSOCL__CL(clFinish(s->dev->queue));
    msocl__sweep_took(s, msocl__seconds() - s->pl_trial_t0);
  }
  *done = k;
  return MSOCL_OK;
}

void msocl__pl_rows_release(msocl__engine *s)
{
  msocl__kernel_free(s->dev, &s->pl_rows);
  msocl__kernel_free(s->dev, &s->pl_rows_still);
  msocl__kernel_free(s->dev, &s->pl_rows_steps);
  if (s->pl_ring)
    clReleaseMemObject(s->pl_ring);
  if (s->pl_mid)
    clReleaseMemObject(s->pl_mid);
}

/* GRID in planes (options.planes, kernels/planes.cl): a cloth grid's
 * symplectic Euler steps over x, y, z planes of padded rows, which PoCL's
 * CPU device runs eight or sixteen points to an instruction. The engine's
 * float4 buffers stay the state everything else reads and writes: a call's
 * steps copy it into the planes, step there, and copy it back. */
#include "config.h"
#include "sim.h"

enum { PL_VELOCITY, PL_POSITION, PL_PACK, PL_UNPACK, PL_FUSED, PL_COUNT };

static const char *const names[PL_COUNT] = {
    "msocl_planes_velocity", "msocl_planes_position", "msocl_planes_pack",
    "msocl_planes_unpack", "msocl_planes_fused"};

/* Why the engine cannot run in planes; NULL: it can. */
static const char *unfit(const msocl__engine *s)
{
  if (s->lay.kind != MSOCL_LAYOUT_GRID)
    return "needs the GRID layout";
  if (s->o.integrator != MSOCL_SYMPLECTIC_EULER)
    return "runs symplectic Euler only";
  if (s->o.strain != MSOCL_STRAIN_NONE)
    return "runs without strain limiting only";
  if (s->lo != 0 || s->hi != s->n)
    return "runs a whole model on one device (not a split)";
  return NULL;
}

int msocl__planes_choose(msocl__engine *s)
{
  const char *why = unfit(s);
  if (s->o.planes == 1 && why)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "planes %s", why);
  /* auto: CPU devices, where it is measured faster (docs/PERFORMANCE.md);
   * a GPU gathers float4 as well, and is not measured */
  s->planes = !why && (s->o.planes == 1 ||
                       (s->o.planes == -1 &&
                        s->dev->info.type == MSOCL_DEVICE_CPU));
  return MSOCL_OK;
}

static int arg(cl_kernel k, cl_uint i, size_t size, const void *v)
{
  MSOCL__CL(clSetKernelArg(k, i, size, v));
  return MSOCL_OK;
}

#define TRY MSOCL__TRY

/* The arguments that never change: all but the planes that ping-pong. */
static int fixed_args(msocl__engine *s)
{
  cl_kernel k = NULL;
  /* velocity (connectivity, p, v, v_out, then these), and fused (with
   * p_out before them) */
  for (int q = 0; q < 2; q++) {
    k = s->pl_k[q ? PL_FUSED : PL_VELOCITY];
    cl_uint a;
    TRY(msocl__layout_set_args(&s->lay, k, &a));
    s->pl_conn = a;
    a += 3 + (cl_uint)q;
    TRY(arg(k, a, sizeof s->pl_aux, &s->pl_aux));
    TRY(arg(k, a + 1, sizeof(int), &s->pl_pitch));
    TRY(arg(k, a + 2, sizeof(int), &s->pl_plane));
    TRY(arg(k, a + 3, sizeof s->gravity, &s->gravity));
    TRY(arg(k, a + 4, sizeof(float), &s->viscous));
    TRY(arg(k, a + 5, sizeof(float), &s->air));
    TRY(arg(k, a + 6, sizeof(float), &s->o.dt));
    TRY(arg(k, a + 7, sizeof s->col, &s->col));
  }
  k = s->pl_k[PL_POSITION];
  TRY(arg(k, 3, sizeof s->pl_aux, &s->pl_aux));
  TRY(arg(k, 4, sizeof(int), &s->lay.grid_nx));
  TRY(arg(k, 5, sizeof(int), &s->pl_pitch));
  TRY(arg(k, 6, sizeof(int), &s->pl_plane));
  TRY(arg(k, 7, sizeof(float), &s->o.dt));
  /* pack (pos, vel, inv_mass, p, v, aux, ints); unpack (p, v, aux, pos,
   * vel, ints) */
  const cl_uint ints[2] = {6, 5}, aux_at[2] = {5, 2};
  for (int q = 0; q < 2; q++) {
    k = s->pl_k[PL_PACK + q];
    TRY(arg(k, ints[q], sizeof(int), &s->lay.grid_nx));
    TRY(arg(k, ints[q] + 1, sizeof(int), &s->pl_pitch));
    TRY(arg(k, ints[q] + 2, sizeof(int), &s->pl_plane));
    TRY(arg(k, ints[q] + 3, sizeof(int), &s->n));
    TRY(arg(k, aux_at[q], sizeof s->pl_aux, &s->pl_aux));
  }
  k = s->pl_k[PL_PACK];
  return arg(k, 2, sizeof s->inv_mass, &s->inv_mass);
}

int msocl__planes_create(msocl__engine *s, cl_program prog)
{
  if (!s->planes)
    return MSOCL_OK;
  /* rows padded to whole work-groups of 64, plus two points each side */
  const size_t wide = ((size_t)s->lay.grid_nx + 63) / 64 * 64;
  s->pl_pitch = (int)wide + 4;
  s->pl_plane = s->pl_pitch * (s->lay.grid_ny + 4);
  s->pl_global[0] = wide;
  s->pl_global[1] = (size_t)s->lay.grid_ny;
  for (int q = 0; q < PL_COUNT; q++) {
    cl_int e;
    s->pl_k[q] = clCreateKernel(prog, names[q], &e);
    if (e != CL_SUCCESS)
      return msocl__fail(e, "clCreateKernel(%s): %s", names[q],
                         msocl_err_name(e));
  }
  cl_mem *bufs[5] = {&s->pl_p[0], &s->pl_p[1], &s->pl_v[0], &s->pl_v[1],
                     &s->pl_aux};
  for (int q = 0; q < 5; q++) {
    /* the padding is read (and its terms discarded): zeros, not garbage */
    const size_t bytes =
        (q < 4 ? 3 : 2) * (size_t)s->pl_plane * sizeof(float);
    cl_int e;
    *bufs[q] = clCreateBuffer(s->dev->ctx, CL_MEM_READ_WRITE, bytes, NULL,
                              &e);
    if (e != CL_SUCCESS)
      return msocl__fail(e, "clCreateBuffer(%zu bytes of planes): %s", bytes,
                         msocl_err_name(e));
    const float zero = 0.0f;
    MSOCL__CL(clEnqueueFillBuffer(s->dev->queue, *bufs[q], &zero, sizeof zero,
                                  0, bytes, 0, NULL, NULL));
  }
  return fixed_args(s);
}

/* pack (to_planes) or unpack planes set `set` and the current state. */
static int copy(msocl__engine *s, int set, int to_planes)
{
  cl_kernel k = s->pl_k[to_planes ? PL_PACK : PL_UNPACK];
  cl_mem f4[2] = {s->pos[s->r], s->vel[s->r]},
         pl[2] = {s->pl_p[set], s->pl_v[set]};
  for (int q = 0; q < 2; q++) {
    TRY(arg(k, (cl_uint)(to_planes ? q : 3 + q), sizeof f4[q], &f4[q]));
    TRY(arg(k, (cl_uint)(to_planes ? 3 + q : q), sizeof pl[q], &pl[q]));
  }
  MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, k, 1, NULL, &s->full_global,
                                   NULL, 0, NULL, NULL));
  return MSOCL_OK;
}

int msocl__planes_steps(msocl__engine *s, int n)
{
  if (n <= 0)
    return MSOCL_OK;
  const size_t local[2] = {64, 1};
  const size_t *group = s->dev->info.type == MSOCL_DEVICE_CPU ? local : NULL;
  TRY(copy(s, 0, 1));
  const cl_uint a = s->pl_conn;
  for (int q = 0; q < n; q++) {
    const int r = q & 1, w = 1 - r;
    if (s->o.fused) {
      cl_kernel kf = s->pl_k[PL_FUSED];
      TRY(arg(kf, a, sizeof s->pl_p[r], &s->pl_p[r]));
      TRY(arg(kf, a + 1, sizeof s->pl_v[r], &s->pl_v[r]));
      TRY(arg(kf, a + 2, sizeof s->pl_v[w], &s->pl_v[w]));
      TRY(arg(kf, a + 3, sizeof s->pl_p[w], &s->pl_p[w]));
      MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, kf, 2, NULL,
                                       s->pl_global, group, 0, NULL, NULL));
    } else {
      cl_kernel kv = s->pl_k[PL_VELOCITY], kp = s->pl_k[PL_POSITION];
      TRY(arg(kv, a, sizeof s->pl_p[r], &s->pl_p[r]));
      TRY(arg(kv, a + 1, sizeof s->pl_v[r], &s->pl_v[r]));
      TRY(arg(kv, a + 2, sizeof s->pl_v[w], &s->pl_v[w]));
      MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, kv, 2, NULL,
                                       s->pl_global, group, 0, NULL, NULL));
      TRY(arg(kp, 0, sizeof s->pl_p[r], &s->pl_p[r]));
      TRY(arg(kp, 1, sizeof s->pl_v[w], &s->pl_v[w]));
      TRY(arg(kp, 2, sizeof s->pl_p[w], &s->pl_p[w]));
      MSOCL__CL(clEnqueueNDRangeKernel(s->dev->queue, kp, 2, NULL,
                                       s->pl_global, group, 0, NULL, NULL));
    }
    if ((q + 1) % 64 == 0)
      MSOCL__CL(clFlush(s->dev->queue));
  }
  return copy(s, n & 1, 0);
}

void msocl__planes_release(msocl__engine *s)
{
  for (int q = 0; q < PL_COUNT; q++)
    if (s->pl_k[q])
      clReleaseKernel(s->pl_k[q]);
  cl_mem m[5] = {s->pl_p[0], s->pl_p[1], s->pl_v[0], s->pl_v[1], s->pl_aux};
  for (int q = 0; q < 5; q++)
    if (m[q])
      clReleaseMemObject(m[q]);
}

/* A model on one device: state buffers, the two passes per step with
 * ping-pong buffers, and reading and writing of the state. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


void msocl_sim_options_init(msocl_sim_options *o)
{
  if (!o)
    return;
  memset(o, 0, sizeof *o);
  o->dt = 1e-3f;
  o->layout = MSOCL_LAYOUT_AUTO;
  o->math = MSOCL_MATH_PRECISE;
  o->device = 0;
}

/* -D options for just the features this model uses. */
static int build_options(const msocl_sim *s, const msocl_model *m,
                         msocl_math math, char *buf, size_t cap)
{
  int any_pin = 0, damped = 0, kinds[4] = {0};
  for (int i = 0; i < m->n; i++)
    any_pin |= m->pinned[i];
  for (int i = 0; m->damp && i < m->ns; i++)
    damped |= m->damp[i] != 0.0f;
  for (int c = 0; c < m->ncol; c++)
    kinds[m->col[c].kind] = 1;
  cl_device_fp_config fp = 0;
  clGetDeviceInfo(s->dev->id, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp, &fp,
                  NULL);
  int len = snprintf(
      buf, cap, "%s -DMSOCL_SLOTS=%d%s%s%s%s%s%s%s",
      s->lay.kind == MSOCL_LAYOUT_IMAGE2D ? "-DMSOCL_LAYOUT_IMAGE2D"
                                          : "-DMSOCL_LAYOUT_BUFFER",
      s->lay.slots > 0 ? s->lay.slots : 1, damped ? " -DMSOCL_DAMPING" : "",
      m->viscous != 0.0f ? " -DMSOCL_VISCOUS" : "",
      any_pin ? " -DMSOCL_PINS" : "",
      kinds[MSOCL__PLANE] ? " -DMSOCL_PLANE" : "",
      kinds[MSOCL__SPHERE] ? " -DMSOCL_SPHERE" : "",
      kinds[MSOCL__TABLE] ? " -DMSOCL_TABLE" : "",
      math == MSOCL_MATH_RELAXED
          ? " -DMSOCL_RELAXED -cl-fast-relaxed-math"
          /* GPUs may round single divide and sqrt loosely unless asked. */
          : (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT)
                ? " -cl-fp32-correctly-rounded-divide-sqrt"
                : "");
  if (len < 0 || (size_t)len >= cap)
    return msocl__fail(MSOCL_ERR_INVALID_ARG, "build options too long");
  return MSOCL_OK;
}

static cl_mem buffer(msocl_sim *s, cl_mem_flags flags, size_t bytes,
                     void *host, int *rc)
{
  if (*rc != MSOCL_OK)
    return NULL;
  cl_int e;
  cl_mem b = clCreateBuffer(s->dev->ctx, flags | (host ? CL_MEM_COPY_HOST_PTR
                                                       : 0),
                            bytes, host, &e);
  if (e != CL_SUCCESS)
    *rc = msocl__fail(e, "clCreateBuffer(%zu bytes) on %s: %s", bytes,
                      s->dev->info.name, msocl_err_name(e));
  return b;
}

/* State, masses, colliders and the normals' triangle lists. */
static int make_buffers(msocl_sim *s, const msocl_model *m)
{
  const size_t n = (size_t)m->n;
  int rc = MSOCL_OK;
  float *inv = malloc(n * sizeof *inv);
  float col[2 * 4 * MSOCL__MAX_COLLIDERS + 4] = {0};
  int *off = calloc(n + 1, sizeof *off);
  int *ab = malloc((size_t)(2 * 3 * m->nt + 2) * sizeof *ab);
  if (!inv || !off || !ab) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation staging");
    goto out;
  }
  for (size_t i = 0; i < n; i++) {
    s->stage[4 * i] = m->pos[3 * i];
    s->stage[4 * i + 1] = m->pos[3 * i + 1];
    s->stage[4 * i + 2] = m->pos[3 * i + 2];
    s->stage[4 * i + 3] = m->pinned[i] ? 1.0f : 0.0f;
    inv[i] = 1.0f / m->mass[i];
  }
  for (int c = 0; c < m->ncol; c++) {
    col[8 * c] = (float)m->col[c].kind;
    col[8 * c + 1] = m->col[c].friction;
    memcpy(col + 8 * c + 4, m->col[c].p, 4 * sizeof(float));
  }
  /* Each triangle (a, b, c) lists (b, c) at a, (c, a) at b, (a, b) at c:
   * the same winding at every corner. */
  for (int t = 0; t < m->nt; t++)
    for (int k = 0; k < 3; k++)
      off[m->tri[3 * t + k] + 1]++;
  for (size_t i = 0; i < n; i++)
    off[i + 1] += off[i];
  int *fill = calloc(n, sizeof *fill);
  if (!fill) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation staging");
    goto out;
  }
  for (int t = 0; t < m->nt; t++)
    for (int k = 0; k < 3; k++) {
      int a = m->tri[3 * t + k];
      int at = off[a] + fill[a]++;
      ab[2 * at] = m->tri[3 * t + (k + 1) % 3];
      ab[2 * at + 1] = m->tri[3 * t + (k + 2) % 3];
    }
  free(fill);

  const size_t state = 4 * n * sizeof(float);
  for (int k = 0; k < 2; k++) {
    s->pos[k] = buffer(s, CL_MEM_READ_WRITE, state, s->stage, &rc);
    s->vel[k] = buffer(s, CL_MEM_READ_WRITE, state, NULL, &rc);
  }
  s->inv_mass = buffer(s, CL_MEM_READ_ONLY, n * sizeof *inv, inv, &rc);
  s->col = buffer(s, CL_MEM_READ_ONLY, sizeof col, col, &rc);
  s->normal = buffer(s, CL_MEM_WRITE_ONLY, state, NULL, &rc);
  s->tri_off = buffer(s, CL_MEM_READ_ONLY, (n + 1) * sizeof *off, off, &rc);
  s->tri_ab = buffer(s, CL_MEM_READ_ONLY,
                     (size_t)(2 * 3 * m->nt + 2) * sizeof *ab, ab, &rc);
  if (rc == MSOCL_OK) {
    /* Velocities start at zero: a pattern fill, no host transfer. */
    float zero = 0.0f;
    for (int k = 0; k < 2 && rc == MSOCL_OK; k++) {
      cl_int e = clEnqueueFillBuffer(s->dev->queue, s->vel[k], &zero,
                                     sizeof zero, 0, state, 0, NULL, NULL);
      if (e != CL_SUCCESS)
        rc = msocl__fail(e, "clEnqueueFillBuffer: %s", msocl_err_name(e));
    }
  }
out:
  free(inv);
  free(off);
  free(ab);
  return rc;
}

static int make_kernels(msocl_sim *s, const msocl_model *m, cl_program prog)
{
  const char *names[3] = {"msocl_velocity", "msocl_position",
                          "msocl_normals"};
  for (int r = 0; r < 2; r++) {
    cl_kernel *k[3] = {&s->kvel[r], &s->kpos[r], &s->knorm[r]};
    for (int q = 0; q < 3; q++) {
      cl_int e;
      *k[q] = clCreateKernel(prog, names[q], &e);
      if (e != CL_SUCCESS)
        return msocl__fail(e, "clCreateKernel(%s): %s", names[q],
                           msocl_err_name(e));
    }
    const int w = 1 - r;
    cl_float4 g = {{m->gravity[0], m->gravity[1], m->gravity[2], 0.0f}};
    cl_uint a;
    int rc = msocl__layout_set_args(&s->lay, s->kvel[r], &a);
    if (rc != MSOCL_OK)
      return rc;
    cl_kernel kv = s->kvel[r], kp = s->kpos[r], kn = s->knorm[r];
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(cl_mem), &s->pos[r]));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(cl_mem), &s->vel[r]));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(cl_mem), &s->vel[w]));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(cl_mem), &s->inv_mass));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof g, &g));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(float), &m->viscous));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(float), &s->dt));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(cl_mem), &s->col));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(int), &m->ncol));
    MSOCL__CL(clSetKernelArg(kv, a++, sizeof(int), &s->n));
    MSOCL__CL(clSetKernelArg(kp, 0, sizeof(cl_mem), &s->pos[r]));
    MSOCL__CL(clSetKernelArg(kp, 1, sizeof(cl_mem), &s->vel[w]));
    MSOCL__CL(clSetKernelArg(kp, 2, sizeof(cl_mem), &s->pos[w]));
    MSOCL__CL(clSetKernelArg(kp, 3, sizeof(float), &s->dt));
    MSOCL__CL(clSetKernelArg(kp, 4, sizeof(int), &s->n));
    MSOCL__CL(clSetKernelArg(kn, 0, sizeof(cl_mem), &s->pos[r]));
    MSOCL__CL(clSetKernelArg(kn, 1, sizeof(cl_mem), &s->tri_off));
    MSOCL__CL(clSetKernelArg(kn, 2, sizeof(cl_mem), &s->tri_ab));
    MSOCL__CL(clSetKernelArg(kn, 3, sizeof(cl_mem), &s->normal));
    MSOCL__CL(clSetKernelArg(kn, 4, sizeof(int), &s->n));
  }
  return MSOCL_OK;
}

static int check_options(const msocl_runtime *rt, const msocl_sim_options *o)
{
  if (!isfinite(o->dt))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "time step dt is %g", o->dt);
  if (!(o->dt > 0.0f))
    return msocl__fail(MSOCL_ERR_BAD_DT, "time step dt = %g must be > 0",
                       o->dt);
  if (o->layout < MSOCL_LAYOUT_AUTO || o->layout > MSOCL_LAYOUT_BUFFER)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown layout %d",
                       (int)o->layout);
  if (o->math != MSOCL_MATH_PRECISE && o->math != MSOCL_MATH_RELAXED)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown math mode %d",
                       (int)o->math);
  if (o->device < 0 || o->device >= rt->ndev)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "device %d out of range: the runtime holds %d",
                       o->device, rt->ndev);
  return MSOCL_OK;
}

int msocl_sim_create(msocl_sim **out, msocl_runtime *rt, const msocl_model *m,
                     const msocl_sim_options *opts)
{
  msocl__clear_error();
  if (!out)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim out-pointer is NULL");
  *out = NULL;
  if (!rt || !m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       rt ? "model" : "runtime");
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  if (opts)
    o = *opts;
  int rc = check_options(rt, &o);
  if (rc == MSOCL_OK)
    rc = msocl_model_validate(m);
  if (rc != MSOCL_OK)
    return rc;

  msocl_sim *s = calloc(1, sizeof *s);
  struct msocl__adjacency adj;
  memset(&adj, 0, sizeof adj);
  if (!s)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation");
  s->dev = (struct msocl__device *)&rt->dev[o.device];
  s->n = m->n;
  s->dt = o.dt;
  s->global = ((size_t)m->n + 63) / 64 * 64;
  s->pinned = malloc((size_t)m->n);
  s->stage = malloc(4 * (size_t)m->n * sizeof(float));
  if (!s->pinned || !s->stage) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation");
    goto fail;
  }
  memcpy(s->pinned, m->pinned, (size_t)m->n);
  rc = msocl__adjacency_build(m, &adj);
  if (rc == MSOCL_OK)
    rc = msocl__layout_create(s->dev, m, &adj, o.layout, &s->lay);
  if (rc == MSOCL_OK)
    rc = make_buffers(s, m);
  char opt[512];
  cl_program prog = NULL;
  if (rc == MSOCL_OK)
    rc = build_options(s, m, o.math, opt, sizeof opt);
  if (rc == MSOCL_OK)
    rc = msocl__program_get(s->dev, opt, &prog);
  if (rc == MSOCL_OK)
    rc = make_kernels(s, m, prog);
  if (rc == MSOCL_OK) {
    cl_int e = clFinish(s->dev->queue);
    if (e != CL_SUCCESS)
      rc = msocl__fail(e, "clFinish: %s", msocl_err_name(e));
  }
  msocl__adjacency_free(&adj);
  if (rc == MSOCL_OK) {
    *out = s;
    return MSOCL_OK;
  }
fail:
  msocl_sim_destroy(s);
  return rc;
}

void msocl_sim_destroy(msocl_sim *s)
{
  if (!s)
    return;
  if (s->dev && s->dev->queue)
    clFinish(s->dev->queue);
  for (int r = 0; r < 2; r++) {
    cl_kernel k[3] = {s->kvel[r], s->kpos[r], s->knorm[r]};
    for (int q = 0; q < 3; q++)
      if (k[q])
        clReleaseKernel(k[q]);
  }
  cl_mem mems[] = {s->pos[0], s->pos[1], s->vel[0], s->vel[1], s->inv_mass,
                   s->col, s->normal, s->tri_off, s->tri_ab};
  for (size_t q = 0; q < sizeof mems / sizeof mems[0]; q++)
    if (mems[q])
      clReleaseMemObject(mems[q]);
  msocl__layout_release(&s->lay);
  free(s->pinned);
  free(s->stage);
  free(s);
}

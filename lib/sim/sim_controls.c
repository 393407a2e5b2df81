/* Controls on a running simulation (msocl.h's "live controls"): gravity,
 * viscous damping and air resistance, applied from the next step; pins
 * set and cleared; and pins moved to targets that they reach at the end of
 * the next stepping call, along a straight path over its steps (kernels/
 * planes_pins.cl, before each step and once after the last). */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct msocl__controls {
  int *inverse; /* model index -> the simulation's (NULL: the same) */
  /* what the kernels were built with (engine.c leaves out a zero
   * viscosity, an air factor of 1 and pins when the model has none) */
  int viscous_built, air_built, pins_built;
  int m;        /* pins given targets for the next call (0: none) */
  int *at_host; /* their model indices, to refuse unpinning them */
  cl_kernel pins;
  cl_mem at, start, target;
  struct msocl__device *dev; /* the pins kernel's */
  int cap;      /* pins the buffers hold */
};

void msocl__controls_free(msocl_sim *s)
{
  struct msocl__controls *c = s->ctl;
  if (!c)
    return;
  if (c->pins)
    msocl__kernel_free(c->dev, &c->pins);
  cl_mem b[3] = {c->at, c->start, c->target};
  for (int q = 0; q < 3; q++)
    if (b[q])
      clReleaseMemObject(b[q]);
  free(c->inverse);
  free(c->at_host);
  free(c);
  s->ctl = NULL;
}

/* The simulation's controls, made at the first call, while the engines
 * still hold what they were built with. */
static int controls(msocl_sim *s, struct msocl__controls **out)
{
  if (!s->ctl) {
    struct msocl__controls *c = calloc(1, sizeof *c);
    if (!c)
      return msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation controls");
    const msocl__engine *e = s->part[0];
    c->viscous_built = e->viscous != 0.0f;
    c->air_built = e->air != 1.0f;
    for (int i = 0; i < s->n; i++)
      c->pins_built |= s->pinned[i];
    if (s->perm) {
      c->inverse = malloc((size_t)s->n * sizeof *c->inverse);
      if (!c->inverse) {
        free(c);
        return msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation controls");
      }
      for (int k = 0; k < s->n; k++)
        c->inverse[s->perm[k]] = k;
    }
    s->ctl = c;
  }
  *out = s->ctl;
  return MSOCL_OK;
}

int msocl__sim_index(msocl_sim *s, int i, int *k)
{
  struct msocl__controls *c;
  MSOCL__TRY(controls(s, &c));
  *k = c->inverse ? c->inverse[i] : i;
  return MSOCL_OK;
}

/* The engines' kernels take the changed gravity, viscosity or air factor;
 * Verlet's stored acceleration held the old forces, so it is computed
 * again at the next step. */
static int apply(msocl_sim *s)
{
  for (int d = 0; d < s->nparts; d++) {
    msocl__engine *e = s->part[d];
    if (e->o.integrator == MSOCL_VERLET)
      msocl__planes_written(e);
    MSOCL__TRY(msocl__set_fixed(e));
    MSOCL__TRY(msocl__planes_forces(e));
  }
  return MSOCL_OK;
}

int msocl_sim_set_gravity(msocl_sim *s, float gx, float gy, float gz)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  const float g[3] = {gx, gy, gz};
  MSOCL__TRY(msocl__check_triples("msocl_sim_set_gravity", "vector", g, 1,
                                  NULL, 0, MSOCL__FORCE_MAX));
  /* gravity's potential is part of the blow-up check's energy: the change
   * moves its baseline as a write does */
  MSOCL__TRY(msocl__check_write(s));
  for (int d = 0; d < s->nparts; d++) {
    cl_float4 *g = &s->part[d]->gravity;
    g->s[0] = gx;
    g->s[1] = gy;
    g->s[2] = gz;
    g->s[3] = 0.0f;
  }
  return apply(s);
}

/* A damping value changed: refused where the kernels were built without
 * that term (off at creation) and the new value would need it. */
static int set_damping(msocl_sim *s, int air, float value)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  MSOCL__TRY(msocl__check_damping(air, value));
  /* as the model's check: the force at the model's extent a second */
  const double ext1 = s->extent > 1.0 ? s->extent : 1.0;
  if (!air && (double)value * ext1 > MSOCL__FORCE_MAX)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "viscous damping %g x speed %g (the model's extent a "
                       "second) exceeds the force limit %g",
                       (double)value, ext1, MSOCL__FORCE_MAX);
  struct msocl__controls *c;
  MSOCL__TRY(controls(s, &c));
  const int off = air ? value == 1.0f : value == 0.0f;
  int *built = air ? &c->air_built : &c->viscous_built;
  if (!*built && !off) {
    for (int d = 0; d < s->nparts; d++)
      MSOCL__TRY(msocl__engine_terms(s->part[d], !air, air));
    *built = 1;
  }
  for (int d = 0; d < s->nparts; d++)
    *(air ? &s->part[d]->air : &s->part[d]->viscous) = value;
  return apply(s);
}

int msocl_sim_set_viscous_damping(msocl_sim *s, float c)
{
  return set_damping(s, 0, c);
}

int msocl_sim_set_air_resistance(msocl_sim *s, float factor)
{
  return set_damping(s, 1, factor);
}

/* Checks count and the model indices idx[0..count). */
static int check_indices(const msocl_sim *s, int count, const int *idx,
                         const char *what)
{
  if (count < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "%s: count %d is negative", what,
                       count);
  if (count > 0 && !idx)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: index list is NULL",
                       what);
  for (int q = 0; q < count; q++)
    if (idx[q] < 0 || idx[q] >= s->n)
      return msocl__fail(MSOCL_ERR_BAD_INDEX,
                         "%s: index %d (entry %d) out of range [0, %d)", what,
                         idx[q], q, s->n);
  return MSOCL_OK;
}

int msocl_sim_pin(msocl_sim *s, int count, const int *idx, int pinned)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  MSOCL__TRY(check_indices(s, count, idx, "msocl_sim_pin"));
  struct msocl__controls *c;
  MSOCL__TRY(controls(s, &c));
  if (!c->pins_built && count > 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "msocl_sim_pin: the simulation was created with no "
                       "pinned point, so its kernels leave pins out; pin at "
                       "least one point of the model before msocl_sim_create");
  for (int q = 0; !pinned && q < count; q++)
    for (int t = 0; t < c->m; t++)
      if (c->at_host[t] == idx[q])
        return msocl__fail(MSOCL_ERR_BAD_VALUE,
                           "msocl_sim_pin: point %d has a target for the "
                           "next call and cannot be unpinned before it",
                           idx[q]);
  for (int d = 0; d < s->nparts; d++) {
    msocl__engine *e = s->part[d];
    for (int q = 0; q < count; q++) {
      int k;
      MSOCL__TRY(msocl__sim_index(s, idx[q], &k));
      MSOCL__TRY(msocl__state_pin(e, k, pinned));
    }
    msocl__planes_written(e);
  }
  for (int q = 0; q < count; q++) {
    int k;
    MSOCL__TRY(msocl__sim_index(s, idx[q], &k));
    s->pinned[k] = pinned != 0;
  }
  return MSOCL_OK;
}

/* Buffers for m pins, the kernel at first use. */
static int pin_buffers(msocl__engine *e, struct msocl__controls *c, int m)
{
  if (!c->pins) {
    cl_program prog;
    MSOCL__CL(clGetKernelInfo(e->pl_k[0], CL_KERNEL_PROGRAM, sizeof prog,
                              &prog, NULL));
    MSOCL__TRY(msocl__kernel_make(e->dev, prog, "msocl_planes_pins",
                                  &c->pins));
    c->dev = e->dev;
  }
  if (m <= c->cap)
    return MSOCL_OK;
  cl_mem *b[3] = {&c->at, &c->start, &c->target};
  const size_t bytes[3] = {(size_t)m * sizeof(cl_int),
                           3 * (size_t)m * sizeof(float),
                           3 * (size_t)m * sizeof(float)};
  for (int q = 0; q < 3; q++) {
    if (*b[q])
      clReleaseMemObject(*b[q]);
    int rc = MSOCL_OK;
    *b[q] = msocl__buffer(e->dev, CL_MEM_READ_WRITE, bytes[q], NULL,
                          "pin targets", &rc);
    if (rc != MSOCL_OK) {
      c->cap = 0;
      return rc;
    }
  }
  int *h = realloc(c->at_host, (size_t)m * sizeof *h);
  if (!h)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "pin targets");
  c->at_host = h;
  c->cap = m;
  return MSOCL_OK;
}

int msocl_sim_set_pin_targets(msocl_sim *s, int count, const int *idx,
                              const float *xyz)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  if (count < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "msocl_sim_set_pin_targets: count %d is negative",
                       count);
  if (count > 0 && !xyz)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "msocl_sim_set_pin_targets: targets are NULL");
  if (idx)
    MSOCL__TRY(check_indices(s, count, idx, "msocl_sim_set_pin_targets"));
  msocl__engine *e = s->part[0];
  if (s->nparts > 1)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "msocl_sim_set_pin_targets needs one device; this "
                       "simulation is split over %d", s->nparts);
  struct msocl__controls *c;
  MSOCL__TRY(controls(s, &c));
  int npins = 0;
  for (int k = 0; k < s->n; k++)
    npins += s->pinned[k];
  if (!idx && count != npins)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "msocl_sim_set_pin_targets: %d targets for all %d "
                       "pinned points",
                       count, npins);
  MSOCL__TRY(msocl__check_triples("msocl_sim_set_pin_targets", "target",
                                  xyz, count, NULL, 0, MSOCL__COORD_MAX));
  int *model = malloc(((size_t)count + 1) * sizeof *model),
      *at = malloc(((size_t)count + 1) * sizeof *at);
  unsigned char *seen = calloc((size_t)s->n, 1);
  int rc = model && at && seen ? MSOCL_OK
                               : msocl__fail(MSOCL_ERR_NO_MEMORY,
                                             "pin targets");
  for (int q = 0, next = 0; rc == MSOCL_OK && q < count; q++) {
    if (idx)
      model[q] = idx[q];
    else { /* the pinned points in the model's order */
      int k;
      for (;; next++) {
        rc = msocl__sim_index(s, next, &k);
        if (rc != MSOCL_OK || s->pinned[k])
          break;
      }
      model[q] = next++;
    }
    int k = 0;
    if (rc == MSOCL_OK)
      rc = msocl__sim_index(s, model[q], &k);
    if (rc == MSOCL_OK && !s->pinned[k])
      rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "msocl_sim_set_pin_targets: point %d is not pinned "
                       "(msocl_sim_pin)",
                       model[q]);
    if (rc == MSOCL_OK && seen[model[q]])
      rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "msocl_sim_set_pin_targets: point %d given twice",
                       model[q]);
    if (rc == MSOCL_OK) {
      seen[model[q]] = 1;
      at[q] = msocl__pl_address(e, k);
    }
  }
  free(seen);
  if (rc == MSOCL_OK && count > 0)
    rc = pin_buffers(e, c, count);
  if (rc == MSOCL_OK && count > 0) {
    cl_int err = clEnqueueWriteBuffer(e->dev->queue, c->at, CL_FALSE, 0,
                                      (size_t)count * sizeof(cl_int), at, 0,
                                      NULL, NULL);
    if (err == CL_SUCCESS)
      err = clEnqueueWriteBuffer(e->dev->queue, c->target, CL_TRUE, 0,
                                 3 * (size_t)count * sizeof(float), xyz, 0,
                                 NULL, NULL);
    if (err != CL_SUCCESS)
      rc = msocl__fail(err, "writing pin targets: %s", msocl_err_name(err));
  }
  if (rc == MSOCL_OK) {
    if (count > 0)
      memcpy(c->at_host, model, (size_t)count * sizeof *model);
    c->m = count;
  }
  free(model);
  free(at);
  return rc;
}

int msocl__pins_pending(const msocl_sim *s)
{
  return s->ctl && s->ctl->m > 0;
}

void msocl__pins_done(msocl_sim *s)
{
  s->ctl->m = 0;
}

/* The pins at their path's point fp, moving from f0 to f1 in a step. */
static int place(msocl__engine *e, struct msocl__controls *c, float fp,
                 float f0, float f1, int capture)
{
  cl_kernel k = c->pins;
  const cl_mem p = e->pl_p[e->pl_set], v = e->pl_v[e->pl_set];
  const struct msocl__named args[] = {
      {"p", sizeof p, &p},          {"v", sizeof v, &v},
      {"at", sizeof c->at, &c->at}, {"start", sizeof c->start, &c->start},
      {"target", sizeof c->target, &c->target},
      {"m", sizeof c->m, &c->m},    {"plane", sizeof(int), &e->pl_plane},
      {"fp", sizeof fp, &fp},       {"f0", sizeof f0, &f0},
      {"f1", sizeof f1, &f1},       {"dt", sizeof(float), &e->o.dt},
      {"capture", sizeof capture, &capture}};
  for (size_t q = 0; q < sizeof args / sizeof args[0]; q++)
    MSOCL__TRY(msocl__arg(e, k, args[q].name, args[q].size, args[q].v));
  /* groups of 64 whatever the count: PoCL builds its code again for each
   * work-group size it picks, and it picks the count */
  const size_t global = ((size_t)c->m + 63) / 64 * 64, group = 64;
  MSOCL__CL(clEnqueueNDRangeKernel(e->dev->queue, k, 1, NULL, &global,
                                   &group, 0, NULL, NULL));
  return MSOCL_OK;
}

int msocl__pins_place(msocl_sim *s, float fp, float f0, float f1,
                      int capture)
{
  return place(s->part[0], s->ctl, fp, f0, f1, capture);
}

/* A model on one device: the state the host reads and writes, the
 * program built for the model's features, and the planes engine that
 * steps it (planes.c). */
#include "config.h"
#include "planes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The model's features the -D options name, beside its colliders. */
enum { OPT_PINS = 1, OPT_DAMPING = 2, OPT_VISCOUS = 4, OPT_AIR = 8 };

static void model_options(msocl__engine *s, const msocl_model *m)
{
  int any_pin = 0, damped = 0;
  for (int i = 0; i < m->n; i++)
    any_pin |= m->pinned[i];
  for (int i = 0; m->damp && i < m->ns; i++)
    damped |= m->damp[i] != 0.0f;
  s->opt_model = (any_pin ? OPT_PINS : 0u) | (damped ? OPT_DAMPING : 0u) |
                 (m->viscous != 0.0f ? OPT_VISCOUS : 0u) |
                 (m->air != 1.0f ? OPT_AIR : 0u);
  /* the kinds of spring the model leaves out compiled out (a lattice's
   * body shear, by default: 8 of its 32 neighbours) */
  s->opt_grid_kinds = 0;
  for (int q = 0; q < 4; q++)
    s->opt_grid_kinds |= (m->grid.k[q] != 0.0f) << q;
  s->pl_kinds = 0;
  for (int c = 0; c < m->ncol; c++)
    s->pl_kinds |= 1u << m->col[c].kind;
}

/* -D options for just the features the model uses, with ncol colliders
 * of the kinds in `kinds` (1 << kind each). */
static int build_options(const msocl__engine *s, int ncol, unsigned kinds,
                         char *buf, size_t cap)
{
  const unsigned f = s->opt_model;
  cl_device_fp_config fp = 0;
  clGetDeviceInfo(s->dev->id, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp, &fp,
                  NULL);
  /* the planes' kernels, with the colliders' loop unrolled */
  char planes[112], dense[32];
  /* BUFFER's rows skip the slots past the most a non-spilling point has */
  snprintf(dense, sizeof dense, " -DMSOCL_DENSE=%d", s->lay.dense);
  const int ring_w = msocl__pl_rows_ring_w(s);
  int at = snprintf(planes, sizeof planes,
                    " -DMSOCL_PLANES -DMSOCL_NCOL=%d -DMSOCL_GRID_KINDS=%d",
                    ncol, s->opt_grid_kinds);
  if (ring_w > 0)
    snprintf(planes + at, sizeof planes - (size_t)at,
             " -DMSOCL_ROWS_RING_W=%d", ring_w);
#define KIND(k) (kinds & (1u << (k)))
  /* EDGES holds BUFFER's table (layout.c) */
  int len = snprintf(
      buf, cap,
      "%s -DMSOCL_SLOTS=%d -DMSOCL_DEGREE=%d%s%s%s%s%s%s%s%s%s%s%s%s%s%s%s",
      s->lay.kind == MSOCL_LAYOUT_IMAGE2D ? "-DMSOCL_LAYOUT_IMAGE2D"
      : s->lay.kind == MSOCL_LAYOUT_GRID
          ? (s->lay.grid_nz > 0 ? "-DMSOCL_LAYOUT_GRID -DMSOCL_GRID_3D"
                                : "-DMSOCL_LAYOUT_GRID")
                                          : "-DMSOCL_LAYOUT_BUFFER",
      s->lay.slots > 0 ? s->lay.slots : 1,
      s->lay.degree, s->lay.spill ? " -DMSOCL_SPILL" : "",
      s->lay.classes ? " -DMSOCL_CLASSES" : "",
      f & OPT_DAMPING ? " -DMSOCL_DAMPING" : "",
      f & OPT_VISCOUS ? " -DMSOCL_VISCOUS" : "",
      f & OPT_AIR ? " -DMSOCL_AIR" : "",
      f & OPT_PINS ? " -DMSOCL_PINS" : "",
      KIND(MSOCL__PLANE) ? " -DMSOCL_PLANE" : "",
      KIND(MSOCL__SPHERE) ? " -DMSOCL_SPHERE" : "",
      KIND(MSOCL__TABLE) ? " -DMSOCL_TABLE" : "",
      KIND(MSOCL__CAPSULE) ? " -DMSOCL_CAPSULE" : "",
      KIND(MSOCL__BOX) ? " -DMSOCL_BOX" : "",
      msocl__pl_gather4(s) ? " -DMSOCL_GATHER4" : "",
      s->lay.kind == MSOCL_LAYOUT_BUFFER || s->lay.kind == MSOCL_LAYOUT_EDGES
          ? dense : "",
      planes,
      s->o.math == MSOCL_MATH_RELAXED
          ? " -DMSOCL_RELAXED -cl-fast-relaxed-math"
          /* GPUs may round single divide and sqrt loosely unless asked. */
          : (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT)
                ? " -cl-fp32-correctly-rounded-divide-sqrt"
                : "");
#undef KIND
  if (len < 0 || (size_t)len >= cap)
    return msocl__fail(MSOCL_ERR_INVALID_ARG, "build options too long");
  return MSOCL_OK;
}

/* Whether AUTO's fused is symplectic Euler's one-kernel step here: on a
 * CPU's BUFFER table, one engine (a split keeps every engine's schedule
 * alike), where it ran 1.0-1.4x the two passes (docs/PERFORMANCE.md). */
static int fused_by_default(const msocl__engine *s)
{
  return s->o.tuning.fused == MSOCL_AUTO &&
         s->lay.kind == MSOCL_LAYOUT_BUFFER &&
         s->dev->info.type == MSOCL_DEVICE_CPU &&
         s->o.integrator == MSOCL_SYMPLECTIC_EULER &&
         s->o.strain != MSOCL_STRAIN_VELOCITY && s->lo == 0 && s->hi == s->n;
}

/* Masses, colliders and the reductions' buffers (the state and the
 * normals' lists: state.c, once the planes exist). */
static int make_buffers(msocl__engine *s, const msocl_model *m)
{
  const size_t n = (size_t)m->n;
  int rc = MSOCL_OK;
  float *inv = malloc(n * sizeof *inv);
  float col[2 * 4 * MSOCL__MAX_COLLIDERS + 4] = {0};
  if (!inv) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation staging");
    goto out;
  }
  for (size_t i = 0; i < n; i++)
    inv[i] = 1.0f / m->mass[i];
  for (int c = 0; c < m->ncol; c++) {
    col[8 * c] = (float)m->col[c].kind;
    col[8 * c + 1] = m->col[c].friction;
    memcpy(col + 8 * c + 4, m->col[c].p, 4 * sizeof(float));
    memcpy(s->pl_colx + 8 * c, m->col[c].x, sizeof m->col[c].x);
  }
  s->col = msocl__buffer(s->dev, CL_MEM_READ_ONLY, sizeof col, col,
                         "colliders", &rc);
  s->partial = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                             s->groups * sizeof(cl_float4), NULL,
                             "partial sums", &rc);
  s->parts = msocl__buffer(s->dev, CL_MEM_READ_WRITE,
                           3 * (size_t)msocl__energy_stride(s) * sizeof(float),
                           NULL, "energy parts", &rc);
out:
  s->inv_host = inv; /* soft pins' stiffness check reads it */
  return rc;
}

/* The blow-up check's copy of the state, planes as the state's. */
static int backups(msocl__engine *s)
{
  int rc = MSOCL_OK;
  const size_t bytes = 3 * (size_t)s->pl_plane * sizeof(float);
  if (s->o.check_every > 0) {
    s->backup_p = msocl__buffer(s->dev, CL_MEM_READ_WRITE, bytes, NULL,
                                "the check's positions", &rc);
    s->backup_v = msocl__buffer(s->dev, CL_MEM_READ_WRITE, bytes, NULL,
                                "the check's velocities", &rc);
  }
  return rc;
}

/* Kernels by enum index (the energy's wide twin is made by
 * msocl__energy_args, where it applies). */
static const char *const kernel_names[MSOCL__K_ENERGY_WIDE] = {
    "msocl_normals", "msocl_energy", "msocl_energy_points"};

/* Creates the engine's own kernels: the normals and the energy's two. */
static int make_kernels(msocl__engine *s, cl_program prog)
{
  for (int q = 0; q < MSOCL__K_ENERGY_WIDE; q++)
    MSOCL__TRY(msocl__kernel_make(s->dev, prog, kernel_names[q], &s->k[q]));
  return MSOCL_OK;
}

int msocl__engine_create(msocl__engine **out, struct msocl__device *dev,
                         const msocl_model *m, const msocl_sim_options *o,
                         int lo, int hi)
{
  *out = NULL;
  msocl__engine *s = calloc(1, sizeof *s);
  struct msocl__adjacency adj;
  memset(&adj, 0, sizeof adj);
  if (!s)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation");
  int rc = MSOCL_OK;
  s->dev = dev;
  s->o = *o;
  s->n = m->n;
  s->lo = lo;
  s->hi = hi;
  s->full_global = ((size_t)m->n + 63) / 64 * 64;
  if (lo == 0 && hi == m->n) {
    s->offset = 0;
    s->global = s->full_global;
  } else {
    /* exactly its points: the kernels' bound is n, not hi */
    s->offset = (size_t)lo;
    s->global = (size_t)(hi - lo);
  }
  s->run_offset = s->offset;
  s->run_global = s->global;
  s->groups = ((size_t)(hi - lo) + 63) / 64;
  s->gravity.s[0] = m->gravity[0];
  s->gravity.s[1] = m->gravity[1];
  s->gravity.s[2] = m->gravity[2];
  s->gravity.s[3] = 0.0f;
  s->viscous = m->viscous;
  s->air = m->air;
  s->ncol = m->ncol;
  rc = msocl__planes_refused(o, m, lo, hi);
  if (rc != MSOCL_OK)
    goto fail;
  for (int i = 0; m->damp && i < m->ns && !s->damped; i++)
    s->damped = m->damp[i] != 0.0f;
  s->partial_host =
      malloc((s->full_global / 64 + 1) * sizeof *s->partial_host);
  if (!s->partial_host) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation");
    goto fail;
  }
  rc = msocl__adjacency_build(m, &adj);
  /* AUTO takes GRID only where its padded planes fit */
  msocl_layout kind = o->tuning.layout;
  if (kind == MSOCL_LAYOUT_AUTO)
    kind = msocl__layout_auto(&dev->info, m,
                              msocl__planes_would(o, m, lo, hi));
  if (rc == MSOCL_OK)
    rc = msocl__layout_create(s->dev, m, &adj, kind, o->tuning.buffer_slots,
                              o->tuning.classes, &s->lay);
  if (rc == MSOCL_OK && fused_by_default(s))
    s->o.tuning.fused = MSOCL_ON;
  if (rc == MSOCL_OK)
    rc = msocl__planes_fit(s);
  if (rc == MSOCL_OK)
    rc = make_buffers(s, m);
  char opt[512];
  cl_program prog = NULL;
  if (rc == MSOCL_OK) {
    model_options(s, m);
    rc = build_options(s, m->ncol, s->pl_kinds, opt, sizeof opt);
  }
  if (rc == MSOCL_OK)
    rc = msocl__program_get(s->dev, opt, &prog);
  s->prog = prog;
  if (rc == MSOCL_OK)
    rc = make_kernels(s, prog);
  if (rc == MSOCL_OK)
    rc = msocl__planes_create(s, prog);
  if (rc == MSOCL_OK)
    rc = backups(s);
  if (rc == MSOCL_OK)
    rc = msocl__state_init(s, m);
  if (rc == MSOCL_OK)
    rc = msocl__energy_args(s, prog);
  if (rc == MSOCL_OK)
    rc = msocl__wind_create(s, m, prog);
  if (rc == MSOCL_OK)
    rc = msocl__field_create(s, prog);
  if (rc == MSOCL_OK && s->o.integrator == MSOCL_IMPLICIT_EULER)
    rc = msocl__pl_implicit_args(s); /* planes_implicit.c's kernels */
  if (rc == MSOCL_OK)
    rc = msocl__set_fixed(s);
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
  msocl__engine_destroy(s);
  return rc;
}

void msocl__engine_destroy(msocl__engine *s)
{
  if (!s)
    return;
  if (s->dev && s->dev->queue)
    clFinish(s->dev->queue);
  for (int q = 0; q < MSOCL__K_COUNT; q++)
    msocl__kernel_free(s->dev, &s->k[q]);
  cl_mem mems[] = {s->col,      s->normal,   s->tri_ab,  s->tri_off,
                   s->backup_p, s->backup_v, s->partial, s->parts};
  for (size_t q = 0; q < sizeof mems / sizeof mems[0]; q++)
    if (mems[q])
      clReleaseMemObject(mems[q]);
  msocl__planes_release(s);
  msocl__wind_release(s);
  msocl__field_release(s);
  msocl__soft_release(s);
  msocl__layout_release(&s->lay);
  free(s->partial_host);
  free(s->host);
  free(s->inv_host);
  free(s);
}

int msocl__planes_forces(msocl__engine *s)
{
  return msocl__pl_forces(s);
}

/* After msocl__planes_rebuild: the arguments its re-created kernels take
 * from the implicit solver and wind (set here, above both files). */
static int rebound(msocl__engine *s)
{
  if (s->o.integrator == MSOCL_IMPLICIT_EULER)
    MSOCL__TRY(msocl__pl_implicit_args(s));
  /* wind blows in the sweep or in its own passes, whichever now runs */
  return s->wind_on ? msocl__wind_set(s, s->wind_air, s->wind_kd, s->wind_kl)
                    : MSOCL_OK;
}

int msocl__engine_colliders(msocl__engine *s, int ncol, unsigned kinds)
{
  char opt[512];
  cl_program prog;
  MSOCL__TRY(build_options(s, ncol, kinds, opt, sizeof opt));
  MSOCL__TRY(msocl__program_get(s->dev, opt, &prog));
  s->ncol = ncol;
  s->pl_kinds = kinds;
  MSOCL__TRY(msocl__planes_rebuild(s, prog, 0));
  return rebound(s);
}

int msocl__engine_terms(msocl__engine *s, int viscous, int air)
{
  const unsigned want = s->opt_model | (viscous ? OPT_VISCOUS : 0u) |
                        (air ? OPT_AIR : 0u);
  if (want == s->opt_model)
    return MSOCL_OK;
  char opt[512];
  cl_program prog;
  const unsigned was = s->opt_model;
  s->opt_model = want;
  int rc = build_options(s, s->ncol, s->pl_kinds, opt, sizeof opt);
  if (rc == MSOCL_OK)
    rc = msocl__program_get(s->dev, opt, &prog);
  if (rc != MSOCL_OK) {
    s->opt_model = was;
    return rc;
  }
  /* the energy's kernel too: it reads the springs */
  MSOCL__CL(clFinish(s->dev->queue));
  for (int q = 0; q < MSOCL__K_COUNT; q++)
    msocl__kernel_free(s->dev, &s->k[q]);
  MSOCL__TRY(make_kernels(s, prog));
  MSOCL__TRY(msocl__energy_args(s, prog));
  MSOCL__TRY(msocl__set_fixed(s));
  MSOCL__TRY(msocl__planes_rebuild(s, prog, 1));
  return rebound(s);
}

/* The float4 kernels' arguments by name: each kernel's signature as in
 * kernels/, so that a caller names the argument it sets and never counts
 * to it. CONN stands for the layout's connectivity arguments, the
 * engine's nconn of them (msocl__layout_set_args sets those). The EDGES
 * kernels keep their own argument code (integrate.c). */
#include "config.h"
#include "engine.h"

#include <string.h>

#define CONN ""

/* the tail the point passes share */
#define POINT_TAIL                                                            \
  "inv_mass", "gravity", "viscous", "air", "dt", "col", "ncol", "n"

static const char *const velocity[] = {CONN, "pos", "vel", "vel_out",
                                       POINT_TAIL, NULL};
static const char *const position[] = {"pos", "vel", "pos_out", "dt", "n",
                                       NULL};
static const char *const normals[] = {"pos", "tri_off", "tri_ab", "normal",
                                      "n", NULL};
static const char *const euler[] = {CONN,      "pos",     "vel", "pos_out",
                                    "vel_out", POINT_TAIL, NULL};
static const char *const accel[] = {CONN,       "pos",      "vel",
                                    "acc_out",  "inv_mass", "gravity",
                                    "viscous",  "n",        NULL};
static const char *const drift[] = {"pos", "vel",  "acc", "pos_out", "dt",
                                    "col", "ncol", "n",   NULL};
static const char *const kick[] = {CONN,      "pos",      "vel",
                                   "vel_out", "acc_out",  "inv_mass",
                                   "gravity", "viscous",  "air",
                                   "dt",      "n",        NULL};
static const char *const rk4[] = {
    CONN,      "p0",      "v0",  "sp", "sv",   "sum_p", "sum_v",
    "np",      "nv",      "inv_mass",  "gravity", "viscous", "air",
    "c",       "dt",      "mode", "col", "ncol", "n",    NULL};
static const char *const energy[] = {CONN,      "pos", "vel", "inv_mass",
                                     "gravity", "partial", "n", "end",
                                     NULL};
static const char *const ie_rhs[] = {
    CONN,      "pos",     "vel", "x",  "r",       "p", "inv_mass",
    "gravity", "viscous", "dt",  "partial", "n", NULL};
static const char *const ie_apply[] = {CONN,      "pos", "p",       "ap",
                                       "inv_mass", "viscous", "dt",
                                       "partial",  "n",   NULL};
static const char *const cg_step[] = {"x",     "r",       "p", "ap",
                                      "alpha", "partial", "n", NULL};
static const char *const cg_direction[] = {"p", "r", "beta", "n", NULL};
static const char *const ie_finish[] = {"pos", "vel", "dv",   "vel_out", "air",
                                        "dt",  "col", "ncol", "n",       NULL};
static const char *const strain_velocity[] = {
    CONN, "pos", "vel", "vel_out", "limit", "dt", "col", "ncol", "n", NULL};
static const char *const strain_position[] = {CONN,    "pos", "pos_out",
                                              "limit", "n",   NULL};
static const char *const strain_commit[] = {"pos", "corrected", "vel", "dt",
                                            "n",   NULL};

static const char *const *const signature[MSOCL__K_COUNT] = {
    [MSOCL__K_VELOCITY] = velocity,
    [MSOCL__K_POSITION] = position,
    [MSOCL__K_NORMALS] = normals,
    [MSOCL__K_EULER] = euler,
    [MSOCL__K_ACCEL] = accel,
    [MSOCL__K_DRIFT] = drift,
    [MSOCL__K_KICK] = kick,
    [MSOCL__K_RK4] = rk4,
    [MSOCL__K_ENERGY] = energy,
    [MSOCL__K_IE_RHS] = ie_rhs,
    [MSOCL__K_IE_APPLY] = ie_apply,
    [MSOCL__K_CG_STEP] = cg_step,
    [MSOCL__K_CG_DIR] = cg_direction,
    [MSOCL__K_IE_FINISH] = ie_finish,
    [MSOCL__K_STRAIN_VEL] = strain_velocity,
    [MSOCL__K_STRAIN_POS] = strain_position,
    [MSOCL__K_STRAIN_COMMIT] = strain_commit,
    [MSOCL__K_FUSED] = euler, /* the same arguments as explicit Euler's */
};

int msocl__set(msocl__engine *s, int k, const char *name, size_t size,
               const void *v)
{
  cl_uint i = 0;
  for (const char *const *a = signature[k]; a && *a; a++) {
    if (**a == '\0') {
      i += s->nconn;
    } else if (strcmp(*a, name) == 0) {
      MSOCL__CL(clSetKernelArg(s->k[k], i, size, v));
      return MSOCL_OK;
    } else {
      i++;
    }
  }
  return msocl__fail(MSOCL_ERR_INVALID_ARG, "kernel %d has no argument %s",
                     k, name);
}

int msocl__set_mem(msocl__engine *s, int k, const char *name, cl_mem m)
{
  return msocl__set(s, k, name, sizeof m, &m);
}

int msocl__set_float(msocl__engine *s, int k, const char *name, float f)
{
  return msocl__set(s, k, name, sizeof f, &f);
}

int msocl__set_int(msocl__engine *s, int k, const char *name, int v)
{
  return msocl__set(s, k, name, sizeof v, &v);
}

/* The values an argument of a given name holds in every float4 kernel
 * that has it, for the engine's whole life: everything but the state
 * buffers that ping-pong (pos, vel, ...) and the per-launch values (c,
 * mode, alpha, beta). The CG's search state: x (also the velocity change
 * dv) and r in the stage positions, p and Ap in the stage velocities. */
int msocl__set_fixed(msocl__engine *s)
{
  const struct {
    const char *name;
    size_t size;
    const void *v;
  } fixed[] = {
      {"inv_mass", sizeof s->inv_mass, &s->inv_mass},
      {"gravity", sizeof s->gravity, &s->gravity},
      {"viscous", sizeof s->viscous, &s->viscous},
      {"air", sizeof s->air, &s->air},
      {"dt", sizeof s->o.dt, &s->o.dt},
      {"col", sizeof s->col, &s->col},
      {"ncol", sizeof s->ncol, &s->ncol},
      {"n", sizeof s->n, &s->n},
      {"end", sizeof s->hi, &s->hi},
      {"acc", sizeof s->acc, &s->acc},
      {"acc_out", sizeof s->acc, &s->acc},
      {"sum_p", sizeof s->sum_p, &s->sum_p},
      {"sum_v", sizeof s->sum_v, &s->sum_v},
      {"partial", sizeof s->partial, &s->partial},
      {"tri_off", sizeof s->tri_off, &s->tri_off},
      {"tri_ab", sizeof s->tri_ab, &s->tri_ab},
      {"normal", sizeof s->normal, &s->normal},
      {"limit", sizeof s->o.strain_limit, &s->o.strain_limit},
      {"x", sizeof(cl_mem), &s->stage_p[0]},
      {"dv", sizeof(cl_mem), &s->stage_p[0]},
      {"r", sizeof(cl_mem), &s->stage_p[1]},
      {"p", sizeof(cl_mem), &s->stage_v[0]},
      {"ap", sizeof(cl_mem), &s->stage_v[1]},
  };
  for (int k = 0; k < MSOCL__K_COUNT; k++) {
    if (!s->k[k] || !signature[k])
      continue;
    for (const char *const *a = signature[k]; *a; a++)
      for (size_t f = 0; f < sizeof fixed / sizeof fixed[0]; f++)
        if (strcmp(*a, fixed[f].name) == 0) {
          int rc = msocl__set(s, k, *a, fixed[f].size, fixed[f].v);
          if (rc != MSOCL_OK)
            return rc;
        }
  }
  return MSOCL_OK;
}

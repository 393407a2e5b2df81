/* What planes.c shares with planes_implicit.c: the planes kernels' slots
 * in msocl__engine.pl_k, and launching and arguing them. */
#ifndef MSOCL_PLANES_H
#define MSOCL_PLANES_H

#include "engine.h"

/* Points a work-item of the explicit-vector kernels (planes_wide.cl,
 * planes_rows.cl, energy.cl: kernels/rows.h's MSOCL_ROWS_W), and their
 * work-items a CPU work-group where the rows allow (planes.c's launch) */
#define MSOCL__WIDE_W 16
#define MSOCL__WIDE_GROUP 16

enum {
  PL_VELOCITY, PL_POSITION, PL_FUSED, PL_DRIFT, PL_KICK,
  PL_RK4, PL_RK4_MID, PL_RK4_LAST, PL_STRAIN, PL_COMMIT,
  PL_STRAIN_V, PL_IE_RHS, PL_IE_APPLY, PL_CG_STEP, PL_CG_DIR, PL_IE_FINISH,
  PL_SUM, PL_EULER, PL_COUNT
};

/* Planes kernel k's argument `name` (and its _spill twin's, if any):
 * size bytes at v, or a buffer; named: each of vals[0..n) it has. */
int msocl__pl_arg(msocl__engine *s, cl_kernel k, const char *name,
                  size_t size, const void *v);
int msocl__pl_mem(msocl__engine *s, cl_kernel k, const char *name, cl_mem m);
int msocl__pl_named(msocl__engine *s, cl_kernel k,
                    const struct msocl__named *vals, int n);
/* Kernel k's connectivity arguments (and its twin's). */
int msocl__pl_conn(msocl__engine *s, cl_kernel k);
/* The planes' shape, where k has them: nx, pitch, slab, plane. */
int msocl__pl_shape(msocl__engine *s, cl_kernel k);
/* Every argument of k that holds one value for the engine's life (the
 * shape, aux, dt, the colliders, the forces, ...), where k has it. */
int msocl__pl_fixed(msocl__engine *s, cl_kernel k);
/* Kernel k over the padded grid (then its twin over the points that
 * spill). */
int msocl__pl_launch(msocl__engine *s, int k);

/* planes_wide.c: whether the planes kernels take their twins in explicit
 * vectors, kernel q's twin (NULL: none), and whether the force kernels
 * gather the positions from a float4 copy (-DMSOCL_GATHER4: BUFFER's and
 * EDGES's tables on a CPU). */
int msocl__pl_wide(const msocl__engine *s);
const char *msocl__pl_wide_name(int q);
int msocl__pl_gather4(const msocl__engine *s);
/* planes_pack.c: that copy and its kernel, where it applies (create);
 * the copy of positions p, before a pass that gathers them (pack). */
int msocl__pl_pack_create(msocl__engine *s, cl_program prog);
int msocl__pl_pack(msocl__engine *s, cl_mem p);
void msocl__pl_pack_release(msocl__engine *s);

/* planes_implicit.c: its kernels' fixed arguments (its CG operations:
 * schedule.h). */
int msocl__pl_implicit_args(msocl__engine *s);
/* Every planes kernel's gravity, viscous damping and air arguments again
 * (planes.c), the sweep's too. */
int msocl__pl_forces(msocl__engine *s);


/* planes_rows.c: symplectic Euler in one sweep a step with each spring
 * computed once, where it applies (s->pl_rows then set), and its step
 * from plane set r to w. */
int msocl__pl_rows_create(msocl__engine *s, cl_program prog);
/* The sweep's kernel again from prog (a rebuild for new colliders), its
 * arguments set and its wind off; released instead (with its rings)
 * where it no longer applies. */
int msocl__pl_rows_rebuild(msocl__engine *s, cl_program prog);
int msocl__pl_rows_step(msocl__engine *s, int r, int w);
/* Wind on the cloth builder's triangles inside the sweep (air NULL:
 * none), kd and kl as msocl__wind_set's. */
int msocl__pl_rows_wind(msocl__engine *s, const float air[3], float kd,
                        float kl);
void msocl__pl_rows_release(msocl__engine *s);
/* The columns of the sweep's ring rows on a CPU cloth grid (a build
 * option there, -DMSOCL_ROWS_RING_W), 0 where it does not run. */
int msocl__pl_rows_ring_w(const msocl__engine *s);

/* sweep_steps.c: steps a launch of GRID's sweep. From the tuning, before
 * the first launch: */
void msocl__sweep_steps_init(msocl__engine *s);
/* Steps the next launch runs of the n due (< 2: none); *start and *end
 * where it begins and ends a candidate's trial, whose time from before
 * the first launch to after the last msocl__sweep_took takes. */
int msocl__sweep_next(msocl__engine *s, int n, int *start, int *end);
void msocl__sweep_took(msocl__engine *s, double seconds);

#endif

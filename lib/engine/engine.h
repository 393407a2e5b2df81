/* An engine: a whole copy of the model on one device, advancing the points
 * of its own range. Shared by the files that set it up (engine.c), step it
 * (schedule.c, planes*.c, cg.c) and
 * measure it (energy.c); the simulation (sim.h) joins engines. */
#ifndef MSOCL_ENGINE_H
#define MSOCL_ENGINE_H

#include "layout.h"

/* Kernels the library's program holds; the enum indexes msocl__engine.k. */
/* Beside the planes' kernels (planes.h): the normals and the energy. */
enum {
  MSOCL__K_NORMALS, MSOCL__K_ENERGY, MSOCL__K_ENERGY_POINTS,
  MSOCL__K_ENERGY_WIDE, /* made by msocl__energy_args where it applies */
  MSOCL__K_COUNT
};

/* Steps a launch that GRID's sweep times where tuning.sweep_steps is AUTO
 * (sweep_steps.c) */
#define MSOCL__SWEEP_CANDIDATES 3

typedef struct msocl__engine msocl__engine;

struct msocl__engine {
  struct msocl__device *dev;
  msocl_sim_options o;
  int n;
  struct msocl__layout lay;
  cl_mem col, normal, tri_ab, tri_off;
  cl_mem backup_p, backup_v; /* last state that passed the blow-up check,
                                planes as pl_p and pl_v */
  cl_mem partial;         /* one float4 per work-group of reductions */
  cl_mem parts;           /* the energy's per point, three planes */
  cl_kernel k[MSOCL__K_COUNT];
  int damped;             /* dashpots: gathers read neighbours' velocities */
  int lo, hi;             /* the points this engine advances */
  size_t offset, global;  /* its launches: from lo, (hi - lo) work-items
                             (one engine: 0 and n rounded up to 64) */
  size_t run_offset, run_global; /* what msocl__launch covers now: the
                             above, or one span of it while a split job
                             runs its boundary first */
  size_t groups;          /* reductions: work-groups of 64 over [lo, hi) */
  size_t full_global;     /* n rounded up to 64 */
  int cg_iterations;
  double cg_residual;
  /* steps since the last msocl__cg_report whose CG stopped above the
   * tolerance, and the worst of them */
  int cg_missed, cg_worst_iterations;
  double cg_worst_residual;
  cl_float4 gravity;
  float viscous, air;
  int ncol;
  cl_float4 *partial_host;
  float *host;            /* state.c's slices of the planes */
  size_t host_cap;        /* ... its floats */
  float *inv_host; /* the points' inverse masses, in the engine's order */
  /* the engine's state (planes.c, kernels/planes.cl): x, y, z planes of
   * floats, rows padded on GRID, kept there between calls */
  int pl_valid;           /* what the planes' state implies is computed
                             (Verlet's acceleration) */
  int pl_set;             /* the plane set that holds it */
  cl_mem pl_p[2], pl_v[2], pl_aux; /* ping-pong like pos and vel */
  cl_mem pl_a;            /* Verlet: the acceleration */
  cl_mem pl_sp[2], pl_sv[2], pl_sum[2]; /* RK4: stage states, sums */
  cl_mem pl_s[2];         /* strain sweeps (velocity: pl_s[0]) */
  cl_mem pl_col;          /* the colliders, a float4 a value (planes.c) */
  int pl_col_moving;      /* a collider in the table as last written moves
                             (sim_colliders.c): the sweep's still twin not */
  float pl_colx[8 * MSOCL__MAX_COLLIDERS]; /* their msocl__collider.x */
  unsigned pl_kinds;      /* the collider kinds compiled in, 1 << kind */
  int pl_rebuilds;        /* programs taken after creation: what a test
                             asks (a freed kernel's address comes back) */
  unsigned opt_model;     /* the model's -D options beside its colliders
                             (engine.c), kept for a rebuild */
  int opt_grid_kinds;
  struct msocl__layout pl_lay; /* the planes kernels' connectivity: lay,
                             BUFFER's table copied with a plane's stride */
  cl_mem pl_table[4];     /* that copy's nbr, rk, dashpots, spill (owned) */
  cl_mem pl_list;         /* BUFFER with a spill: the points that spill */
  int pl_nspill;          /* ... and how many */
  cl_kernel pl_ks[18];    /* the gathering kernels' _spill twins */
  cl_kernel pl_k[18];     /* planes.c's kernels (planes.h) */
  int pl_pitch, pl_slab, pl_plane; /* floats a row, a layer, a plane */
  size_t pl_global[3];    /* the passes' range: rows padded to a group */
  size_t pl_group;        /* a work-group's points (CPU devices) */
  /* symplectic Euler in one sweep a step (planes_rows.c), where it applies */
  unsigned pl_wide;       /* 1 << q: planes kernel q is planes_wide.cl's
                             (planes.c) */
  cl_mem pl_p4;           /* BUFFER on a CPU: the positions a float4 a
                             point, for the force's gathers (planes_pack.c) */
  cl_kernel pl_pack;      /* ... and the kernel that writes them */
  cl_kernel pl_rows, pl_rows_still; /* and with colliders at rest */
  cl_kernel pl_rows_steps; /* several steps a launch (planes_rows.c) */
  cl_mem pl_ring;         /* its work-items' rings of spring terms */
  cl_mem pl_mid;          /* its middle states' rows */
  size_t pl_blocks;       /* its work-items: blocks of rows */
  size_t pl_steps_blocks; /* and pl_rows_steps' */
  /* its steps a launch, or 0 while each candidate is timed: trials begun
   * (the first launch counts one), launches left in the running one,
   * launches outside trials, when the running one began, each
   * candidate's best seconds a step (sweep_steps.c) */
  int pl_steps_k, pl_trials, pl_trial_left, pl_untimed;
  double pl_trial_t0, pl_trial_s[MSOCL__SWEEP_CANDIDATES];
  int pl_rows_wind;       /* it blows wind on the quads (wind.c) */
  /* wind on the triangles (wind.c, kernels/wind.cl) */
  int wind_on, wind_ntri, wind_nspill;
  int wind_quads;         /* the cloth builder's triangles on GRID */
  float wind_air[3], wind_kd, wind_kl; /* as last set (a rebuild's) */
  int *wind_host;         /* the model's triangles, 3 a triangle */
  cl_kernel wind_k[5];    /* a triangle's force; a point's sum; the sum of
                             a point on more triangles than the slots; the
                             quads' forces and a point's sum of them */
  cl_mem wind_tri, wind_slot, wind_third, wind_corner, wind_list;
  /* a user's acceleration field (field.c, kernels/field.cl) */
  int field_on;
  cl_kernel field_k;
  cl_mem field_acc;       /* three planes, laid out as the state's */
  /* soft pins (soft_pins.c, kernels/planes_pins.cl) */
  int soft_m, soft_cap;
  float soft_f;           /* the anchors' place from `from` to `to` */
  cl_kernel soft_k;
  cl_mem soft_at, soft_from, soft_to;
  cl_program prog;        /* the library's program (the device's cache
                             owns it, and any rebuilt for colliders added
                             later): mesh colliders' kernels */
};

/* What a phase of a step leaves that other engines' next phase reads. */
enum {
  MSOCL__X_POS_W = 1, MSOCL__X_VEL_W = 2, MSOCL__X_VEL_R = 4,
  MSOCL__X_STAGE0 = 8, MSOCL__X_STAGE1 = 16, /* RK4 stage positions */
  MSOCL__X_STAGEV0 = 32, MSOCL__X_STAGEV1 = 64, /* and velocities */
  MSOCL__X_CG_P = 128,                          /* implicit: CG direction */
  MSOCL__X_LAST = MSOCL__X_CG_P
};
/* The most buffers one phase exchanges (positions and velocities). */
#define MSOCL__X_SLOTS 2

/* One engine for the whole model on `dev`, advancing points [lo, hi). */
int msocl__engine_create(msocl__engine **out, struct msocl__device *dev,
                         const msocl_model *m, const msocl_sim_options *o,
                         int lo, int hi);
void msocl__engine_destroy(msocl__engine *e);
/* A step is a few phases (schedule.c's table); after each, the buffers in
 * the returned mask must reach the other engines before the next phase
 * reads them. */
int msocl__phase_count(const msocl__engine *s);
int msocl__phase(msocl__engine *s, int phase, unsigned *exchange);
/* That mask, without queuing anything. */
unsigned msocl__phase_mask(const msocl__engine *s, int phase);
/* The planes (planes.c). would: whether model m's grid, over points
 * [lo, hi), fits GRID's padded planes (what AUTO weighs); refused:
 * MSOCL_ERR_BAD_VALUE, before anything is allocated, where GRID is forced
 * on a grid whose planes the kernels' int indices cannot address; fit:
 * the same for the engine's chosen layout; create: its buffers and
 * kernels, from the program built with -DMSOCL_PLANES; release: frees
 * them. Its passes: schedule.h. */
int msocl__planes_would(const msocl_sim_options *o, const msocl_model *m,
                        int lo, int hi);
int msocl__planes_refused(const msocl_sim_options *o, const msocl_model *m,
                          int lo, int hi);
int msocl__planes_fit(const msocl__engine *s);
/* Device bytes the planes of model m's grid take under options o
 * (msocl.h's formula). */
size_t msocl__planes_bytes(const msocl_model *m, const msocl_sim_options *o);
int msocl__planes_create(msocl__engine *s, cl_program prog);
/* enter: before a run of steps, computes what the state implies
 * (Verlet's acceleration) unless it is; step_done: ends a step, from one
 * plane set into the other; written: after anything wrote the state. */
int msocl__planes_enter(msocl__engine *s);
void msocl__planes_step_done(msocl__engine *s);
void msocl__planes_written(msocl__engine *s);
/* The state between host and planes (state.c), the engine's points
 * [lo, hi), 3 floats a point: read, write (positions or velocities; the
 * caller says msocl__planes_written where the state changed); a point's
 * pin flag; init: the model's positions, masses and pins after
 * msocl__planes_create; backup: the current state into the blow-up
 * check's copy, or back; normals: every point's, from the positions. */
int msocl__state_read(msocl__engine *s, int velocities, int lo, int hi,
                      float *xyz);
int msocl__state_write(msocl__engine *s, int velocities, int lo, int hi,
                       const float *xyz);
int msocl__state_pin(msocl__engine *s, int k, int pinned);
int msocl__state_init(msocl__engine *s, const msocl_model *m);
int msocl__state_backup(msocl__engine *s, int to_backup);
int msocl__state_normals(msocl__engine *s, float *xyz);
void msocl__planes_release(msocl__engine *s);
/* The planes kernels' gravity, viscous damping and air resistance
 * arguments again, from s->gravity, viscous and air (a live change). */
int msocl__planes_forces(msocl__engine *s);
/* Colliders added to a running engine (engine.c): the program
 * built for ncol colliders of the kinds in `kinds` (1 << kind each), and
 * the kernels that read the collider table re-created from it, their
 * arguments set again (msocl__planes_rebuild, planes.c; planes_rows.c's
 * sweep, dropped once a capsule or box is compiled in); the state and
 * every other kernel stay. */
int msocl__engine_colliders(msocl__engine *s, int ncol, unsigned kinds);
/* Viscous damping or air resistance turned on in a running engine
 * whose kernels were built without the term: the program with it, every
 * planes kernel re-created (the gathers, the sweep and implicit Euler's
 * read it); the state stays. */
int msocl__engine_terms(msocl__engine *s, int viscous, int air);
/* all: every planes kernel, else those that read the collider table */
int msocl__planes_rebuild(msocl__engine *s, cl_program prog, int all);
/* Ends a step: swaps the ping-pong buffers (or plane sets). */
void msocl__step_done(msocl__engine *s);
/* exchange_slices.c: the planes' buffer an exchange bit names, at this
 * point of the step; and where points [a, b) lie in such a buffer: n
 * slices (returned: 3, one a plane), each *len bytes at off[c]. */
cl_mem msocl__planes_exchange_buffer(const msocl__engine *s, unsigned bit);
int msocl__exchange_slices(const msocl__engine *s, int a, int b,
                           size_t off[3], size_t *len);
/* Enqueues `n` whole steps on one engine (no wait, no exchange). */
int msocl__integrate(msocl__engine *s, int n);
/* Wind (wind.c): create: its kernels, where the model has triangles; set: air at air[3] with kd = rho Cd / 2 and
 * kl = rho Cl / 2 from the next step (air NULL: none); pass: its velocity
 * change, before a step's phases; release: frees it. */
int msocl__wind_create(msocl__engine *s, const msocl_model *m, cl_program prog);
int msocl__wind_set(msocl__engine *s, const float air[3], float kd, float kl);
int msocl__wind_pass(msocl__engine *s);
void msocl__wind_release(msocl__engine *s);
/* Where the engine's point j sits in each plane (planes.c; planes.cl's
 * MSOCL_PLANES_AT). */
int msocl__pl_address(const msocl__engine *s, int j);
/* The points a planes pass runs in one piece (a row, a lattice's layer,
 * a work-group): a split's spans are cut at its multiples. */
int msocl__planes_unit(const msocl__engine *s);
/* Soft pins (soft_pins.c): set: the engine's points k[0..m) pulled by
 * springs of `stiffness` toward anchors xyz (3 m floats), from the next
 * step; `move`: the anchors move there over the next moving call from
 * where they rest (fraction: before each of its steps), else they start
 * there; m 0: none. pass: their velocity change, before a step's phases;
 * release: frees them. */
int msocl__soft_set(msocl__engine *s, int m, const int *k, const float *xyz,
                    float stiffness, int move);
void msocl__soft_fraction(msocl__engine *s, float f);
int msocl__soft_pass(msocl__engine *s);
void msocl__soft_release(msocl__engine *s);
/* A user's field (field.c): create: its kernel; set: xyz (3 floats a point, the engine's order) as accelerations
 * or, `forces`, as forces divided by the points' masses, from the next
 * step (xyz NULL: none); pass: its velocity change, before a step's
 * phases; release: frees it. */
int msocl__field_create(msocl__engine *s, cl_program prog);
int msocl__field_set(msocl__engine *s, const float *xyz, int forces);
int msocl__field_pass(msocl__engine *s);
void msocl__field_release(msocl__engine *s);
/* Mesh colliders (mesh_collider.c, kernels/mesh_collider.cl): create: collider c's device copy on the engine; vertices: the
 * positions it reaches at the end of the next call (3 nv floats); begin:
 * before a call of n steps, its end vertices uploaded and its grid built
 * if it moves or has none; pass: its push after a step that ran from
 * fraction f0 to f1 of the call's motion; end: after the call, its end is
 * the next call's start. */
struct msocl__mesh_collider;
struct msocl__mesh_dev;
int msocl__mesh_create(msocl__engine *s, const struct msocl__mesh_collider *c,
                       struct msocl__mesh_dev **out);
void msocl__mesh_vertices(struct msocl__mesh_dev *d, const float *verts);
int msocl__mesh_nv(const struct msocl__mesh_dev *d);
int msocl__mesh_begin(msocl__engine *s, struct msocl__mesh_dev *d, int n);
int msocl__mesh_pass(msocl__engine *s, struct msocl__mesh_dev *d, float f0,
                     float f1);
int msocl__mesh_end(msocl__engine *s, struct msocl__mesh_dev *d);
void msocl__mesh_free(struct msocl__mesh_dev *d);
/* Tests only: mesh colliders created from now on build their grid on the
 * device (mode 0), on the host (1: the reference), on the device checked
 * against the host's lists, failing the call that builds it where they
 * differ (2), or (-1, the default) on the host for CPU devices and on the
 * device for others. */
void msocl__mesh_host_grid(int mode);
/* Tests only: simulations created from now on run BUFFER and EDGES in
 * the wide kernels wherever those apply (1), never (-1), or (0, the
 * default) where the CPU has no gathers PoCL vectorises with
 * (planes_wide.c). */
void msocl__pl_wide_mode(int mode);
/* Tests only: a moving mesh's grid, for colliders created from now on,
 * never culled to the cloth (0), culled every call to the cloth's box as
 * it stands (1: the search outside the grid does the rest), or (-1) as
 * the library chooses. */
void msocl__mesh_cull(int mode);
/* Tests only: mesh colliders created from now on search with the GPUs'
 * kernel, a work-item a point, on CPU devices too (1), or not (0). */
void msocl__mesh_per_point(int on);
/* Energy of the engine's points (waits for the device). */
int msocl__energy_stride(const msocl__engine *s);
int msocl__energy_args(msocl__engine *s, cl_program prog);
int msocl__energy(msocl__engine *s, msocl_energy *e);
/* Kernel k's argument that kernels/ names `name` (kernel_args.c; k made
 * by msocl__kernel_make): to size bytes at v, a buffer, a float, an int. */
int msocl__arg(msocl__engine *s, cl_kernel k, const char *name, size_t size,
               const void *v);
int msocl__arg_mem(msocl__engine *s, cl_kernel k, const char *name, cl_mem m);
int msocl__arg_float(msocl__engine *s, cl_kernel k, const char *name,
                     float f);
int msocl__arg_int(msocl__engine *s, cl_kernel k, const char *name, int v);
/* A value by name; args_named sets each of k's arguments that one of
 * vals[0..n) names (the others are not k's). */
struct msocl__named {
  const char *name;
  size_t size;
  const void *v;
};
int msocl__args_named(msocl__engine *s, cl_kernel k,
                      const struct msocl__named *vals, int n);
/* Sets every argument of the engine's own kernels (s->k: normals,
 * energy) that holds a value fixed for the engine's life (n, ...). */
int msocl__set_fixed(msocl__engine *s);
/* Implicit Euler: the new velocities of one step's CG (cg.c) over
 * `parts` engines, into the other plane set, where
 * exchange(ctx) spreads the CG direction's halo between products. */
int msocl__implicit_cg(msocl__engine *const *e, int parts,
                       int (*exchange)(void *ctx), void *ctx);
/* Adds the engine's reduction partials (s->partial), in group order, to
 * *sum (launch.c). */
int msocl__implicit_collect(msocl__engine *s, double *sum);
/* Enqueues kernel k (launch.c) over the engine's current span
 * (run_offset, run_global); _range: over its whole range (offset, global);
 * _all: over every point. */
int msocl__launch(msocl__engine *s, int k);
int msocl__launch_range(msocl__engine *s, int k);
int msocl__launch_all(msocl__engine *s, int k);

#endif

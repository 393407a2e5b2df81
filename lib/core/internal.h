/* Private structures and msocl__ helpers shared by the library's modules. */
#ifndef MSOCL_INTERNAL_H
#define MSOCL_INTERNAL_H

#define CL_TARGET_OPENCL_VERSION 120
#ifdef __APPLE__
#include <OpenCL/opencl.h>
#else
#include <CL/cl.h>
#endif

#include "msocl.h"

#define MSOCL__MAX_DEVICES MSOCL_MAX_DEVICES
#define MSOCL__MAX_COLLIDERS 16
/* Values a collider in the planes kernels' table, a float4 each
 * (kernels/planes.cl MSOCL_PLANES_COL). */
#define MSOCL__COL_VALUES 32
/* The paper's connectivity texture holds 16 springs per point. */
#define MSOCL__IMAGE_SLOTS 16

/* Records a detailed message for msocl_last_error() and returns `code`. */
int msocl__fail(int code, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Called on entry of public calls; the thread's last-error message is
 * kept until the next failure replaces it (as errno), so this does
 * nothing. */
void msocl__clear_error(void);

/* A monotonic clock in seconds (core/clock.c). */
double msocl__seconds(void);

/* Returns from the enclosing function with the OpenCL status if a CL call
 * failed, naming the call. */
#define MSOCL__CL(call)                                                       \
  do {                                                                        \
    cl_int msocl__e = (call);                                                 \
    if (msocl__e != CL_SUCCESS)                                               \
      return msocl__fail(msocl__e, "%s failed: %s (%d)", #call,               \
                         msocl_err_name(msocl__e), (int)msocl__e);            \
  } while (0)

/* Returns a failing library call's status from the calling function. */
#define MSOCL__TRY(call)                                                      \
  do {                                                                        \
    int msocl__rc = (call);                                                   \
    if (msocl__rc != MSOCL_OK)                                                \
      return msocl__rc;                                                       \
  } while (0)

/* The limits of msocl.h that keep a step's float arithmetic finite: a
 * coordinate (and a speed) within MSOCL__COORD_MAX keeps squared
 * distances, 3 (2 x 1e18)^2, below FLT_MAX; forces and accelerations (SI
 * units) stop at MSOCL__FORCE_MAX, a factor 3e8 below FLT_MAX, room for
 * sums and the step's products. Compared in double, as the floats they
 * are. */
#define MSOCL__COORD_MAX ((double)1e18f)
#define MSOCL__FORCE_MAX ((double)1e30f)
/* n triples xyz, each component finite (MSOCL_ERR_NOT_FINITE) and within
 * max (MSOCL_ERR_BAD_VALUE); messages "<what>: <item> <i>: ...", i being
 * idx[q] for triple q, or first + q without idx (core/limits.c). */
int msocl__check_triples(const char *what, const char *item, const float *xyz,
                         int n, const int *idx, int first, double max);
/* Viscous damping (air 0: finite, >= 0) or air resistance (air 1: in
 * (0, 1]), for the model, the simulation and the reference alike. */
int msocl__check_damping(int air, float value);

/* An msocl_sim_options' physics: dt, math, integrator, strain limiting,
 * CG and the blow-up check's settings (core/options.c), for the
 * simulation and the reference alike. */
int msocl__check_physics(const msocl_sim_options *o);

/* Checks wind's parameters (finite; density and drag >= 0) and gives
 * kd = rho Cd / 2 and kl = rho Cl / 2 (core/wind.c). */
int msocl__wind_check(const msocl_wind *w, double *kd, double *kl);

/* ------------------------------------------------------------------ model */

enum { MSOCL__PLANE = 1, MSOCL__SPHERE = 2, MSOCL__TABLE = 3,
       MSOCL__CAPSULE = 4, MSOCL__BOX = 5 };

/* One collider: kind, then p = (normal xyz, offset) for a plane,
 * (centre xyz, radius) for a sphere, (top centre xyz, radius) for a table. */
struct msocl__collider {
  int kind;
  float p[4];
  float friction;
  /* capsule: p = (end a, radius), x = end b; box: p = (centre, 0),
   * x = (unit quaternion xyzw, half extents xyz) */
  float x[8];
};

/* The checks every collider kind's builder makes (model/colliders.c):
 * the model, its friction in [0, 1], room for one more. */
int msocl__collider_check(const msocl_model *m, const char *kind,
                          float friction);
/* The rest of each kind's checks (colliders.c, collider_shapes.c), for a
 * model's collider or one added to a running simulation: friction in
 * [0, 1]; then a kind's values, stored into *out as the kernels read
 * them (kind MSOCL__SPHERE or MSOCL__TABLE for round), messages naming
 * collider id. */
int msocl__collider_friction(const char *kind, int id, float friction);
/* n of a collider's coordinates or sizes, each within MSOCL__COORD_MAX. */
int msocl__collider_extent(const char *kind, int id, const float *v, int n);
int msocl__collider_plane(int id, const float normal[3], float offset,
                          float friction, struct msocl__collider *out);
int msocl__collider_round(int id, int kind, const float centre[3],
                          float radius, float friction,
                          struct msocl__collider *out);
int msocl__collider_capsule(int id, const float a[3], const float b[3],
                            float radius, float friction,
                            struct msocl__collider *out);
int msocl__collider_box(int id, const float centre[3], const float rotation[4],
                        const float half[3], float friction,
                        struct msocl__collider *out);

/* Collider poses (model/collider_pose.c; msocl.h "moving colliders"):
 * the pose a collider a is added at; its shape moved rigidly to pose
 * (P, Q); the path's pose at f from (a, qa) to (b, qb); the motion from
 * pose 0 to 1 over dt, velocity v and angular velocity w (0: they are
 * the same pose, v and w zero); the checks of a pose given for collider
 * id of that kind. */
void msocl__pose_home(const struct msocl__collider *a, float P[3],
                      float Q[4]);
void msocl__pose_shape(const struct msocl__collider *a, const float P[3],
                       const float Q[4], struct msocl__collider *out);
void msocl__pose_lerp(const float a[3], const float qa[4], const float b[3],
                      const float qb[4], float f, float P[3], float Q[4]);
int msocl__pose_motion(const float P0[3], const float Q0[4],
                       const float P1[3], const float Q1[4], double dt,
                       double v[3], double w[3]);
int msocl__pose_check(const char *call, int id, int kind,
                      const float position[3], const float rotation[4]);

/* The simulations made from a model and not yet destroyed, in a block
 * shared by the model and those simulations and freed with the last of
 * them (either may go first), so that the model's setters can refuse a
 * change that would not reach them (lib/model/live.c). */
struct msocl__live;
/* Called by msocl_sim_create (0 or an error) and msocl_sim_destroy. */
int msocl__live_join(const msocl_model *m, struct msocl__live **out);
void msocl__live_leave(struct msocl__live *l);
void msocl__live_drop(msocl_model *m); /* msocl_model_destroy's part */
/* MSOCL_ERR_INVALID_ARG naming `what` and the msocl_sim_ call to use when
 * m has live simulations; else MSOCL_OK. */
int msocl__live_refuse(const msocl_model *m, const char *what,
                       const char *instead);

/* A triangle-mesh collider (model/mesh_collider.c): its vertices and
 * triangles, copied when added; the simulation moves its own copy. */
struct msocl__mesh_collider {
  int nv, nt;
  float *verts; /* 3 nv */
  int *tris;    /* 3 nt */
  float thickness, friction;
};

struct msocl_model {
  struct msocl__live *live; /* NULL until a simulation is made from it */
  int n, cap;            /* points */
  float *pos;            /* 3n */
  float *mass;           /* n */
  unsigned char *pinned; /* n, 0/1 */
  int ns, scap;          /* springs */
  int *ij;               /* 2 ns */
  float *k, *rest, *damp; /* ns each */
  int nt, tcap;          /* triangles (normals only) */
  int *tri;              /* 3 nt */
  float gravity[3];
  float viscous;
  float air; /* velocity factor a step, (0, 1] */
  int ncol;
  struct msocl__collider col[MSOCL__MAX_COLLIDERS];
  int nmesh;             /* mesh colliders, ids 0 .. nmesh - 1 */
  struct msocl__mesh_collider *mesh;
  /* Set by msocl_model_cloth_grid (nz 0) and msocl_model_lattice (nz >=
   * 2): the grid the GRID layout recomputes neighbours from; valid while
   * no springs or points were added since (msocl__grid_intact); or by
   * msocl__grid_detect for one built by hand. */
  struct msocl__grid {
    int nx, ny, nz, ns;
    float k[4];    /* cloth: stretch, shear, bend; lattice: structural,
                      face shear, body shear, bend (0: absent) */
    float rest[6]; /* cloth: stretch along u, v; shear u+v, v-u; bend u, v;
                      lattice: one a kind, as k */
    float damp;
  } grid;
};

/* Frees m's mesh colliders (msocl_model_destroy's part). */
void msocl__mesh_colliders_free(msocl_model *m);

/* Per-point adjacency in slot order: slot s of point i is spring
 * adj[off[i] + s], the other end other[off[i] + s]. Springs appear in the
 * order they were added, so every layout sums them the same way. */
struct msocl__adjacency {
  int n, max_degree;
  int *off;   /* n + 1 */
  int *other; /* 2 ns */
  int *spring; /* 2 ns */
};
int msocl__adjacency_build(const msocl_model *m, struct msocl__adjacency *a);

/* 1 when m is still the cloth grid or lattice its builder recorded (no
 * springs or points added since), so GRID can recompute its springs. */
int msocl__grid_intact(const msocl_model *m);
/* 1 when m, built by hand, is a cloth grid or lattice exactly as the
 * builder would have made it for GRID (grid_detect.c): every spring of
 * the builder's stencil between its points, numbered row by row, with one
 * stiffness and rest length a kind and one dashpot, each point meeting its
 * springs in GRID's slot order; g then receives the builder's record. */
int msocl__grid_detect(const msocl_model *m, struct msocl__grid *g);
/* A copy of m carrying the grid record g. */
int msocl__model_with_grid(const msocl_model *m, const struct msocl__grid *g,
                           msocl_model **out);
void msocl__adjacency_free(struct msocl__adjacency *a);

/* Point numbering (order.c), so that a model splits into contiguous index
 * ranges with small halos and gathers stay local. */

/* Reverse Cuthill-McKee numbering of m's points by springs: perm[k] is the
 * old number of new point k. Each connected component is numbered in turn
 * (components in order of their lowest old point number), each started
 * from a pseudo-peripheral point (George-Liu: repeat BFS from the farthest,
 * lowest-degree point of the last level while the eccentricity grows),
 * neighbours visited by increasing degree, ties by old number, and the
 * whole order then reversed. Deterministic. Isolated points are their own
 * components. *bw_old and *bw_new receive the bandwidth max |i - j| over
 * springs before and after (0 with no springs; either may be NULL). perm
 * has m->n ints. */
int msocl__order_rcm(const msocl_model *m, int *perm, int *bw_old, int *bw_new);

/* A new model equal to m with its points renumbered: new point k is old
 * point perm[k] (positions, masses, pins). Springs keep their order and
 * coefficients with renumbered ends - so every point meets its springs in the
 * same order as before and sums forces in the same order (bitwise equal
 * results); triangles likewise keep their order with renumbered corners.
 * Gravity, viscous/air damping and colliders are copied. The cloth-grid
 * record (m->grid) is cleared (nx = ny = ns = 0) unless perm is the
 * identity, since the GRID layout derives neighbours from the numbering.
 * perm must be a permutation of 0..n-1 (checked: MSOCL_ERR_BAD_VALUE). */
int msocl__model_permuted(const msocl_model *m, const int *perm,
                          msocl_model **out);

/* ---------------------------------------------------------------- runtime */

struct msocl__program; /* cache entry, program.c */
struct msocl__kernel_names; /* a kernel's argument names, kernel_names.c */

#include <pthread.h>

struct msocl__device {
  cl_platform_id platform;
  cl_device_id id;
  msocl_device_info info;
  cl_context ctx;
  cl_command_queue queue;
  /* Threads creating simulations on one runtime share the cache: the lock
   * is held from lookup to insertion, so a program is built once. */
  pthread_mutex_t programs_lock;
  int lock_made;
  struct msocl__program *programs;
  /* the kernels made by name (kernel_names.c), under their own lock */
  pthread_mutex_t names_lock;
  struct msocl__kernel_names *names;
};

struct msocl_runtime {
  int ndev;
  struct msocl__device dev[MSOCL__MAX_DEVICES];
};

/* Queries the facts of one device into info (indices left as given). */
int msocl__device_query(cl_platform_id p, cl_device_id d,
                        msocl_device_info *info);

/* Builds (or finds in the device's cache) the library's program with the
 * given -D options. The returned program is owned by the cache. */
int msocl__program_get(struct msocl__device *dev, const char *options,
                       cl_program *out);
void msocl__program_cache_free(struct msocl__device *dev);
/* Programs in the device's cache (the tests count them). */
int msocl__program_cache_size(struct msocl__device *dev);

/* A buffer on dev (buffer.c), filled from host where host is not NULL;
 * nothing where *rc already holds an error, so a run of them needs one
 * check; on failure *rc names `what`, the size and the device. */
cl_mem msocl__buffer(struct msocl__device *dev, cl_mem_flags flags,
                     size_t bytes, const void *host, const char *what,
                     int *rc);

/* Kernels by name (kernel_names.c). make: kernel `name` of prog, its
 * arguments' names remembered; free: forgets and releases it (NULL: no-op)
 * and sets *k NULL; arg: sets k's argument `name` (MSOCL_ERR_INVALID_ARG
 * where k has none: a typo fails, it never sets another); has: whether k
 * has one of that name; names_free: at the device's end. */
int msocl__kernel_make(struct msocl__device *dev, cl_program prog,
                       const char *name, cl_kernel *out);
void msocl__kernel_free(struct msocl__device *dev, cl_kernel *k);
int msocl__kernel_arg(struct msocl__device *dev, cl_kernel k,
                      const char *name, size_t size, const void *v);
int msocl__kernel_has(struct msocl__device *dev, cl_kernel k,
                      const char *name);
void msocl__kernel_names_free(struct msocl__device *dev);

/* Builders' argument checks (builder_check.c): every one of n floats
 * finite; a coefficient >= 0. Messages name the builder and the field. */
int msocl__check_finite(const char *builder, const char *what,
                        const float *x, int n);
int msocl__check_coef(const char *builder, const char *what, float x);

/* Frame writers (export*.c): the argument checks they share (normals may
 * be NULL); opening a file beside the path (its name into tmp, cap
 * bytes; NULL and the error recorded on failure), and closing it, renamed
 * over the path once whole, with the system's reason for any write error
 * (io/frame_file.c). */
int msocl__frame_check(const char *path, int npoints, const float *xyz,
                       const float *normals, int ntriangles, const int *ijk);
#include <stdio.h>
FILE *msocl__frame_open(const char *path, char *tmp, size_t cap);
int msocl__frame_close(FILE *f, const char *path, const char *tmp);

/* Embedded kernel sources (generated from the kernels folder at build time). */
struct msocl__kernel_source {
  const char *name;
  const char *text;
};
extern const struct msocl__kernel_source msocl__kernel_sources[];
extern const int msocl__kernel_source_count;

#endif /* MSOCL_INTERNAL_H */

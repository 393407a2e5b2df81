/* libmsocl — mass-spring deformable models as OpenCL kernels.
 *
 * The only public header. Every function returns an int status (MSOCL_OK = 0,
 * negative on error) and writes results through out-parameters; the detailed
 * message of the last failure on this thread is msocl_last_error().
 */
#ifndef MSOCL_H
#define MSOCL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(MSOCL_BUILDING) && defined(__GNUC__)
#define MSOCL_EXTERN __attribute__((visibility("default")))
#else
#define MSOCL_EXTERN
#endif

/* ---------------------------------------------------------------- errors */

/* Library codes start at -2000: OpenCL's own codes (0 to about -72, and the
 * Khronos extensions' -1000 to -1100 range) pass through unchanged. */
#define MSOCL_ERRNO_MAP(XX)                                                   \
  XX(INVALID_ARG, -2000, "invalid argument")                                  \
  XX(NO_MEMORY, -2001, "out of host memory")                                  \
  XX(NULL_HANDLE, -2002, "NULL handle or pointer")                            \
  XX(BAD_COUNT, -2003, "count must be positive")                              \
  XX(NOT_FINITE, -2004, "value is NaN or infinite")                           \
  XX(BAD_INDEX, -2005, "index out of range")                            \
  XX(SELF_SPRING, -2006, "spring connects a point to itself")                 \
  XX(BAD_MASS, -2007, "mass must be positive")                                \
  XX(BAD_DT, -2008, "time step must be positive")                             \
  XX(BAD_VALUE, -2009, "parameter out of range")                              \
  XX(DEGREE, -2010, "point has more springs than the layout holds")           \
  XX(NO_PLATFORM, -2011, "no OpenCL platform or device found")                \
  XX(NO_DEVICE, -2012, "device spec matches no OpenCL device")                \
  XX(BAD_SPEC, -2013, "malformed device spec")                                \
  XX(DUP_DEVICE, -2014, "device spec names the same device twice")            \
  XX(NO_IMAGES, -2015, "device has no image support")                         \
  XX(IMAGE_SIZE, -2016, "model exceeds the device's image limits")            \
  XX(KERNEL_SOURCE, -2017, "kernel source not found")                         \
  XX(BUILD, -2018, "kernel build failed")                                     \
  XX(UNSTABLE, -2019, "simulation became unstable")                           \
  XX(IO, -2020, "file input/output failed")                                   \
  XX(TOO_MANY, -2021, "too many items")                                       \
  XX(EMPTY, -2022, "model has no points")                                     \
  XX(NO_CONVERGENCE, -2023, "implicit solver did not converge")

typedef enum {
  MSOCL_OK = 0,
#define MSOCL__ERR_ENUM(name, code, msg) MSOCL_ERR_##name = (code),
  MSOCL_ERRNO_MAP(MSOCL__ERR_ENUM)
#undef MSOCL__ERR_ENUM
  MSOCL_ERR__LAST = -2999
} msocl_status;

/* Short text for a status (library or OpenCL code). Never NULL. */
MSOCL_EXTERN const char *msocl_strerror(int status);
/* Symbolic name: "MSOCL_ERR_BAD_MASS", "CL_OUT_OF_RESOURCES", ... */
MSOCL_EXTERN const char *msocl_err_name(int status);
/* Detailed message of the last failing call on this thread (names the
 * offending value, or carries the compiler's build log); "" if none. */
MSOCL_EXTERN const char *msocl_last_error(void);

MSOCL_EXTERN const char *msocl_version_string(void);
/* major * 10000 + minor * 100 + patch */
MSOCL_EXTERN int msocl_version(void);

/* --------------------------------------------------------------- devices */

typedef enum {
  MSOCL_DEVICE_CPU = 1,
  MSOCL_DEVICE_GPU = 2,
  MSOCL_DEVICE_ACCELERATOR = 4,
  MSOCL_DEVICE_OTHER = 8
} msocl_device_type;

typedef struct {
  int platform_index; /* P of "P:D" */
  int device_index;   /* D of "P:D" */
  char platform_name[128];
  char name[128];
  char version[128];
  msocl_device_type type;
  unsigned compute_units;
  unsigned long long global_mem; /* bytes */
  int image_support;
  size_t image2d_max_width, image2d_max_height;
  int fp64;
  unsigned long long cache; /* global memory cache, bytes (0: none given) */
} msocl_device_info;

/* Every device of every platform, in (P, D) order. Free with free(). */
MSOCL_EXTERN int msocl_device_list(msocl_device_info **list, int *count);

/* Applies a device spec (grammar in README.md; NULL or "" = the first GPU,
 * else the first CPU) to a list of devices: writes into `chosen` the
 * indices (into `devs`) of the chosen ones, in spec order. Pure: no OpenCL
 * call. */
MSOCL_EXTERN int msocl_device_select(const char *spec,
                                     const msocl_device_info *devs, int ndevs,
                                     int *chosen, int max_chosen,
                                     int *nchosen);

typedef struct msocl_runtime msocl_runtime;

/* Opens a context and an in-order queue on each chosen device. spec NULL:
 * the MSOCL_DEVICE environment variable.
 * Threads: a runtime may be shared by threads - each may create, step,
 * read and destroy simulations on it at once (their commands share the
 * device's queue, so they take turns on the device); one simulation (or
 * batch) must not be used by two threads at once, and the runtime must
 * outlive its simulations. */
MSOCL_EXTERN int msocl_runtime_create(msocl_runtime **rt, const char *spec);
MSOCL_EXTERN void msocl_runtime_destroy(msocl_runtime *rt);
MSOCL_EXTERN int msocl_runtime_device_count(const msocl_runtime *rt, int *n);
MSOCL_EXTERN int msocl_runtime_device_info(const msocl_runtime *rt, int i,
                                           msocl_device_info *info);

/* ----------------------------------------------------------------- model */

typedef struct msocl_model msocl_model;

MSOCL_EXTERN int msocl_model_create(msocl_model **m);
MSOCL_EXTERN void msocl_model_destroy(msocl_model *m);

/* Appends n points (xyz: 3n floats, mass: n floats > 0); *first (may be
 * NULL) receives the index of the first new point. Limits that keep a
 * step finite in float: each coordinate within +-1e18 (squared distances
 * stay finite), mass in [FLT_MIN, 1/FLT_MIN] (1/m a normal float);
 * msocl_model_validate adds the combinations below (MSOCL_ERR_BAD_VALUE
 * or MSOCL_ERR_BAD_MASS, the point named). */
MSOCL_EXTERN int msocl_model_add_points(msocl_model *m, int n,
                                        const float *xyz, const float *mass,
                                        int *first);
/* Appends n springs between points ij[2s], ij[2s+1]. stiffness: n floats
 * >= 0. rest: NULL, or n floats where a negative value means "the current
 * distance". damping: NULL (none) or n floats >= 0, a dashpot along the
 * spring. Forces (SI units) are limited to 1e30: stiffness times the
 * larger of 1 m, the rest length and the current distance (and damping
 * times that as a speed a second) at most 1e30, else MSOCL_ERR_BAD_VALUE
 * naming the spring. msocl_model_validate (and so msocl_sim_create and
 * the builders) takes the model's extent (its bounding box's diagonal) as
 * the length instead where it is longer, and refuses a free point whose
 * springs and dashpots at that length, and viscous damping at the extent
 * a second, accelerate it past 1e30 m/s^2 (sum of (k + c) L over its
 * springs, / mass), or whose weight m |g| passes 1e30. */
MSOCL_EXTERN int msocl_model_add_springs(msocl_model *m, int n, const int *ij,
                                         const float *stiffness,
                                         const float *rest,
                                         const float *damping);
/* Triangles (3n indices) are used only to compute vertex normals. */
MSOCL_EXTERN int msocl_model_add_triangles(msocl_model *m, int n,
                                           const int *ijk);
MSOCL_EXTERN int msocl_model_pin(msocl_model *m, int point, int pinned);
MSOCL_EXTERN int msocl_model_set_gravity(msocl_model *m, float gx, float gy,
                                         float gz);
/* Viscous damping force -c * v on every point, c >= 0. */
MSOCL_EXTERN int msocl_model_set_viscous_damping(msocl_model *m, float c);
/* Air resistance as the second seed does it: every step multiplies each
 * velocity by `factor` in (0, 1] (1: none). */
MSOCL_EXTERN int msocl_model_set_air_resistance(msocl_model *m, float factor);

/* Colliders push points out by changing velocity (friction in [0, 1] scales
 * away that fraction of the tangential velocity on contact). */
/* Half-space n.p >= offset is free space (n need not be unit). */
MSOCL_EXTERN int msocl_model_add_plane(msocl_model *m, const float normal[3],
                                       float offset, float friction);
MSOCL_EXTERN int msocl_model_add_sphere(msocl_model *m, const float centre[3],
                                        float radius, float friction);
/* A round table: solid vertical cylinder (axis along y) whose top disc has
 * the given centre and radius; it reaches down without end. */
MSOCL_EXTERN int msocl_model_add_table(msocl_model *m, const float top[3],
                                       float radius, float friction);
/* A capsule: the points within `radius` > 0 of segment a-b. An oriented
 * box: half extents (all > 0) along the axes of the frame at `centre`
 * turned by the quaternion rotation = (x, y, z, w), normalised here. */
MSOCL_EXTERN int msocl_model_add_capsule(msocl_model *m, const float a[3],
                                         const float b[3], float radius,
                                         float friction);
MSOCL_EXTERN int msocl_model_add_box(msocl_model *m, const float centre[3],
                                     const float rotation[4],
                                     const float half[3], float friction);
/* A triangle-mesh collider, closed or open: nverts vertices (3 floats
 * each) and ntris triangles (3 vertex indices each), copied. Points are
 * kept `thickness` > 0 from its surface (and, for a closed mesh, out of
 * it); friction in [0, 1] as the others. Its id is its number among the
 * model's mesh colliders (0, 1, ... in the order added; apart from the
 * analytic colliders). Checked: NULL, a non-finite vertex, an index out
 * of range, only degenerate triangles. Needs one device (a split:
 * msocl_sim_create returns MSOCL_ERR_BAD_VALUE). _obj reads the
 * mesh from a Wavefront OBJ file (faces fanned into triangles). */
#define MSOCL_MAX_MESH_COLLIDERS 16
MSOCL_EXTERN int msocl_model_add_mesh_collider(msocl_model *m,
                                               const float *verts, int nverts,
                                               const int *tris, int ntris,
                                               float thickness,
                                               float friction);
MSOCL_EXTERN int msocl_model_add_mesh_collider_obj(msocl_model *m,
                                                   const char *path,
                                                   float thickness,
                                                   float friction);

/* The model's analytic colliders (planes, spheres, tables, capsules,
 * boxes): collider id k is the k-th added, whatever its kind; the ids
 * msocl_sim_set_collider_pose and msocl_sim_enable_collider take (and
 * msocl_sim_add_* gives those added later). (Mesh colliders are numbered
 * apart, by their own calls.) A count, or MSOCL_ERR_NULL_HANDLE. */
MSOCL_EXTERN int msocl_model_collider_count(const msocl_model *m);

MSOCL_EXTERN int msocl_model_point_count(const msocl_model *m, int *n);
MSOCL_EXTERN int msocl_model_spring_count(const msocl_model *m, int *n);
/* The largest number of springs at any one point. */
MSOCL_EXTERN int msocl_model_max_degree(const msocl_model *m, int *degree);
MSOCL_EXTERN int msocl_model_get_positions(const msocl_model *m, float *xyz);
/* Checks the whole model (also done by msocl_sim_create). */
MSOCL_EXTERN int msocl_model_validate(const msocl_model *m);

/* A cloth of nx * ny points: point (i, j), index j * nx + i, sits at
 * origin + i/(nx-1) * u + j/(ny-1) * v. A stiffness of 0 leaves that spring
 * type out. Two triangles per quad are added for normals. */
typedef struct {
  int nx, ny;
  float origin[3], u[3], v[3];
  float point_mass;
  float k_stretch, k_shear, k_bend;
  float damping; /* dashpot coefficient on every spring, >= 0 */
} msocl_cloth_desc;

MSOCL_EXTERN void msocl_cloth_desc_init(msocl_cloth_desc *d);
MSOCL_EXTERN int msocl_model_cloth_grid(msocl_model **m,
                                        const msocl_cloth_desc *d);

/* A 3D lattice ("jello cube") of nx * ny * nz points, index
 * (k * ny + j) * nx + i at origin + spacing * (i, j, k). Spring sets, each
 * left out when its stiffness is 0: structural (6 axis neighbours), face
 * shear (12 face diagonals), body shear (8 body diagonals), bend (6 axis
 * neighbours two apart). Structural + face shear + bend: degree 24.
 * Each set's springs rest at the lattice's spacing times 1, sqrt 2,
 * sqrt 3 and 2 (computed in double), and the GRID layout can recompute
 * them from the points' positions in the lattice. */
typedef struct {
  int nx, ny, nz;
  float origin[3];
  float spacing;
  float point_mass;
  float k_structural, k_shear_face, k_shear_body, k_bend;
  float damping; /* dashpot coefficient on every spring, >= 0 */
} msocl_lattice_desc;

MSOCL_EXTERN void msocl_lattice_desc_init(msocl_lattice_desc *d);
MSOCL_EXTERN int msocl_model_lattice(msocl_model **m,
                                     const msocl_lattice_desc *d);

/* A deformable solid (Vassilev & Spanlang): surface springs along the edges
 * of a closed triangle mesh plus "support" springs from every surface point
 * to a centre mass point (the last point of the model), which moves with
 * the body. msocl_model_solid builds it on an icosphere of the given
 * subdivision level (0: 12 points, 1: 42, 2: 162, ...) scaled to an
 * ellipsoid of semi-axes `radii`. */
typedef struct {
  int subdivisions;
  float centre[3];
  float radii[3];
  float surface_mass; /* spread evenly over the surface points */
  float centre_mass;
  float k_surface, k_support;
  float damping;
} msocl_solid_desc;

MSOCL_EXTERN void msocl_solid_desc_init(msocl_solid_desc *d);
MSOCL_EXTERN int msocl_model_solid(msocl_model **m, const msocl_solid_desc *d);
/* The same from a user's closed mesh (centre = the points' centroid;
 * subdivisions, centre and radii of d are ignored). */
MSOCL_EXTERN int msocl_model_solid_from_mesh(msocl_model **m, int npoints,
                                             const float *xyz, int ntri,
                                             const int *ijk,
                                             const msocl_solid_desc *d);

/* Triangle meshes from Wavefront OBJ: springs along the edges, optional
 * bending springs across each edge shared by two triangles (between the
 * two opposite corners), point masses from area x density. */
typedef struct {
  float density;  /* kg per square metre of surface, > 0 */
  float k_edge;   /* stiffness of edge springs, > 0 */
  float k_bend;   /* 0: no bending springs */
  float damping;
} msocl_obj_desc;

MSOCL_EXTERN void msocl_obj_desc_init(msocl_obj_desc *d);
/* Reads a regular file or a pipe of at most MSOCL_OBJ_MAX_FILE_BYTES (1 GiB;
 * MSOCL_ERR_TOO_MANY past it, found before reading for a regular file);
 * a directory or device (/dev/zero) fails with MSOCL_ERR_IO before any
 * read. A leading UTF-8 byte-order mark is skipped. */
#define MSOCL_OBJ_MAX_FILE_BYTES ((size_t)1 << 30)
MSOCL_EXTERN int msocl_model_from_obj(msocl_model **m, const char *path,
                                      const msocl_obj_desc *d);
/* The same from text in memory (len bytes, need not be NUL-terminated). */
MSOCL_EXTERN int msocl_model_from_obj_text(msocl_model **m, const char *text,
                                           size_t len,
                                           const msocl_obj_desc *d);

/* ------------------------------------------------------------ simulation */

typedef enum {
  MSOCL_LAYOUT_AUTO = 0, /* GRID for a cloth grid as built, else BUFFER */
  MSOCL_LAYOUT_IMAGE2D,  /* the paper's connectivity texture, 16 slots */
  MSOCL_LAYOUT_BUFFER,   /* slot-major buffers, max-degree slots */
  MSOCL_LAYOUT_EDGES,    /* seed 2's spring list, gathered per point in
                            BUFFER's order, no atomics: bitwise BUFFER
                            (symplectic Euler only, one device) */
  MSOCL_LAYOUT_GRID      /* no stored springs: a cloth from
                            msocl_model_cloth_grid (or a lattice from
                            msocl_model_lattice) recomputes its 12 (32)
                            neighbours from its grid position */
} msocl_layout;

typedef enum {
  MSOCL_MATH_PRECISE = 0, /* IEEE single precision, no contraction */
  MSOCL_MATH_RELAXED      /* -cl-fast-relaxed-math, native functions */
} msocl_math;

typedef enum {
  MSOCL_SYMPLECTIC_EULER = 0, /* the paper's eq. 3: v += dt a, p += dt v */
  MSOCL_EXPLICIT_EULER,       /* forward Euler: p += dt v_old */
  MSOCL_VERLET,               /* velocity Verlet (kick-drift-kick) */
  MSOCL_RK4,                  /* classic Runge-Kutta, 4 force evaluations */
  MSOCL_IMPLICIT_EULER        /* Baraff-Witkin backward Euler, CG on device */
} msocl_integrator;

typedef enum {
  MSOCL_STRAIN_NONE = 0,
  MSOCL_STRAIN_PROVOT,  /* Provot 1995: move end points back (positions) */
  MSOCL_STRAIN_VELOCITY /* Vassilev et al. 2001: stop stretching velocity */
} msocl_strain;

/* The most devices one runtime holds and one simulation is split over. */
#define MSOCL_MAX_DEVICES 16
/* tuning.ndevices: every device the runtime holds from tuning.device on. */
#define MSOCL_ALL_DEVICES (-1)

/* An engine choice. AUTO (0) lets the library decide; ON and OFF force. */
typedef enum {
  MSOCL_AUTO = 0,
  MSOCL_ON = 1,
  MSOCL_OFF = 2
} msocl_choice;

/* How and where the steps run, never what they compute: every choice
 * gives bitwise the same result (EDGES and another device: the same to
 * float rounding), only faster or slower. All zero - as
 * msocl_sim_options_init leaves it - lets the library choose everything.
 * fused forced ON where it cannot apply is MSOCL_ERR_BAD_VALUE. The state
 * is always x, y, z planes of floats (docs/API.md: their memory).
 * Each field in full, and the measurements behind AUTO: docs/API.md. */
typedef struct {
  msocl_layout layout;
  int device;   /* first device: index into the runtime's devices */
  /* Split the model into contiguous ranges of points, one a device from
   * `device` on: 0 or 1 device, or MSOCL_ALL_DEVICES (another negative
   * count: MSOCL_ERR_BAD_VALUE). */
  int ndevices;
  float weights[MSOCL_MAX_DEVICES]; /* each device's share; all 0: equal */
  /* > 0 and all weights 0: weigh the devices by their speed on this
   * model, timed over this many steps on each device alone (after the
   * same steps untimed, which build and warm up). */
  int calibrate_steps;
  /* Symplectic Euler's two passes as one kernel: one launch and one read
   * of the state a step instead of two (gather layouts, no velocity
   * strain limiting). AUTO: on for BUFFER on a CPU device, one device
   * (faster there); off elsewhere, as it is not faster everywhere. */
  msocl_choice fused;
  /* Number the points by reverse Cuthill-McKee, so that neighbours are
   * close in memory and split halos narrow; reads and writes keep the
   * model's numbering. AUTO and ON: where it narrows the springs' reach,
   * but not for a cloth grid or lattice, numbered best as built. */
  msocl_choice renumber;
  /* BUFFER: slots a point in the slot table (at most 64), the rest of a
   * point's springs in a list after it. 0: every spring in the table (up
   * to 64) unless a few points (a solid's centre) have far more than the
   * rest. */
  int buffer_slots;
  /* Split: each phase runs first on the points other devices read, so
   * that their copies overlap the kernels on the rest. AUTO: on. */
  msocl_choice overlap;
  /* BUFFER: a slot holds its spring's (rest, k, dashpot) class as a byte
   * when there are at most 256 classes (ON: whenever they fit), 5 bytes
   * instead of 12 or 16. AUTO: when the table of values would not fit in
   * half the device's cache, where the step is bound by memory bandwidth. */
  msocl_choice classes;
  /* GRID on a CPU device: steps its sweep runs in one launch, 1 to
   * MSOCL_MAX_SWEEP_STEPS (1: a launch a step). More read and write the
   * state fewer times but recompute more rows at the blocks' edges and
   * keep more in cache; the best count depends on the CPU's caches. 0:
   * 4, 3 and 2 each timed over the first long calls, the fastest kept
   * (msocl_sim_sweep_steps says which; docs/API.md). */
  int sweep_steps;
} msocl_tuning;

/* tuning.sweep_steps at most */
#define MSOCL_MAX_SWEEP_STEPS 8

/* What the simulation computes. msocl_sim_options_init gives each field
 * its default (the tuning all AUTO); then set dt. */
typedef struct {
  float dt;           /* seconds, > 0 */
  /* RELAXED trades accuracy for speed, so it is never chosen for you. */
  msocl_math math;
  msocl_integrator integrator;
  msocl_strain strain;
  float strain_limit;    /* allowed elongation over rest length (0.1 = 10%) */
  int strain_iterations; /* correction sweeps a step */
  float cg_tolerance;    /* implicit Euler: relative residual to reach */
  int cg_max_iterations;
  /* Blow-up check every check_every steps (0: off, for benchmarks),
   * counted across calls: a non-finite state, or total energy above its
   * start by more than energy_factor times the scene's energy scale,
   * returns MSOCL_ERR_UNSTABLE with the last good state restored
   * (docs/API.md). */
  int check_every;
  float energy_factor;
  msocl_tuning tuning;
} msocl_sim_options;

MSOCL_EXTERN void msocl_sim_options_init(msocl_sim_options *o);

typedef struct msocl_sim msocl_sim;

/* Copies the model to the device; the model may be destroyed afterwards. */
MSOCL_EXTERN int msocl_sim_create(msocl_sim **s, msocl_runtime *rt,
                                  const msocl_model *m,
                                  const msocl_sim_options *o);
MSOCL_EXTERN void msocl_sim_destroy(msocl_sim *s);
/* n steps of the integrator in the options; returns when done.
 * Implicit Euler: every step is taken; when a step's CG stopped above
 * cg_tolerance (at cg_max_iterations, or on a breakdown), the call still
 * returns after all n steps, with the state they reached (the unconverged
 * steps' velocities kept), but returns MSOCL_ERR_NO_CONVERGENCE; the
 * message gives how many steps missed, the worst residual, its
 * iterations and the tolerance. Treat that code as success to accept
 * such steps. MSOCL_ERR_UNSTABLE from the blow-up check takes precedence. */
MSOCL_EXTERN int msocl_sim_step(msocl_sim *s, int n);
MSOCL_EXTERN int msocl_sim_point_count(const msocl_sim *s, int *n);
MSOCL_EXTERN int msocl_sim_layout(const msocl_sim *s, msocl_layout *layout);
/* Steps a launch of GRID's sweep (tuning.sweep_steps): 1 where every step
 * is a launch (no sweep: another layout or device, a split); 0 while
 * AUTO still times the candidates. */
MSOCL_EXTERN int msocl_sim_sweep_steps(const msocl_sim *s, int *steps);
/* How the layout holds the springs: slots a point in its table (BUFFER,
 * IMAGE2D, and EDGES, which keeps BUFFER's table beside its spring list
 * for the planes engine's gathers; GRID: the 12 implicit neighbours) and
 * BUFFER's spring classes (0: the values in every slot). Either may be
 * NULL. */
MSOCL_EXTERN int msocl_sim_connectivity(const msocl_sim *s, int *slots,
                                        int *classes);
MSOCL_EXTERN int msocl_sim_device_info(const msocl_sim *s,
                                       msocl_device_info *info);
/* 3 floats per point. */
MSOCL_EXTERN int msocl_sim_read_positions(msocl_sim *s, float *xyz);
MSOCL_EXTERN int msocl_sim_write_positions(msocl_sim *s, const float *xyz);
MSOCL_EXTERN int msocl_sim_read_velocities(msocl_sim *s, float *xyz);
MSOCL_EXTERN int msocl_sim_write_velocities(msocl_sim *s, const float *xyz);
/* Unit normals from the model's triangles, computed on the device; a
 * point on no triangle (a lattice's or a solid's inside, every point of a
 * model without triangles) gets (0, 0, 0), not a direction. */
MSOCL_EXTERN int msocl_sim_read_normals(msocl_sim *s, float *xyz);

/* Wind: air moving at `velocity` pushes on the model's triangles, each
 * getting drag along the air's velocity relative to it and lift across
 * it (NvCloth's model; docs/API.md has the formula), a third to each
 * corner, before each step. Defaults (msocl_wind_init): still air of
 * density 1.2 kg/m^3, drag 1.2 (a flat plate face-on), lift 0. */
typedef struct {
  float velocity[3]; /* m/s */
  float density;     /* kg/m^3, >= 0 */
  float drag;        /* drag coefficient, >= 0 */
  float lift;        /* lift coefficient */
} msocl_wind;
MSOCL_EXTERN void msocl_wind_init(msocl_wind *w);
/* From the next step, until set again; NULL: no wind. Needs triangles and
 * one device (else MSOCL_ERR_BAD_VALUE). */
MSOCL_EXTERN int msocl_sim_set_wind(msocl_sim *s, const msocl_wind *w);
/* A user's field: xyz holds 3 floats a point in the model's order, an
 * acceleration (m/s^2) or a force (N, divided by the point's mass), added
 * to each free point's velocity as dt a before each step from the next
 * one (first order, as wind), until set again; NULL: none. One device
 * (else MSOCL_ERR_BAD_VALUE); a non-finite value:
 * MSOCL_ERR_NOT_FINITE. */
MSOCL_EXTERN int msocl_sim_set_accelerations(msocl_sim *s, const float *xyz);
MSOCL_EXTERN int msocl_sim_set_forces(msocl_sim *s, const float *xyz);
/* Live controls, applied from the next step (docs/API.md, "Live
 * controls"). The model's own setters (msocl_model_set_gravity, _pin, ...)
 * return MSOCL_ERR_INVALID_ARG while a simulation made from the model
 * lives: it copied the model and would not see them. Gravity in any
 * direction; viscous damping c >= 0 and air resistance in (0, 1]: a term
 * the model had off when the simulation was created is built into the
 * kernels at the first call that turns it on (a program build, ~0.1 s
 * with PoCL's cache warm). Every live call holds its values to the
 * model's limits (msocl_model_add_points, msocl_model_validate):
 * positions, targets, anchors, poses, sizes and speeds within +-1e18,
 * gravity, accelerations and forces within 1e30, viscous damping times
 * the model's extent within 1e30, wind's speed within 1e15 (its square
 * within 1e30); past them MSOCL_ERR_BAD_VALUE, NaN or Inf
 * MSOCL_ERR_NOT_FINITE, the entry named. */
MSOCL_EXTERN int msocl_sim_set_gravity(msocl_sim *s, float gx, float gy,
                                       float gz);
MSOCL_EXTERN int msocl_sim_set_viscous_damping(msocl_sim *s, float c);
MSOCL_EXTERN int msocl_sim_set_air_resistance(msocl_sim *s, float factor);
/* Pins (pinned != 0) or frees the model's points idx[0..count); the
 * simulation must have been created with at least one pinned point. */
MSOCL_EXTERN int msocl_sim_pin(msocl_sim *s, int count, const int *idx,
                               int pinned);
/* Targets xyz (3 count floats) for pinned points idx[0..count) (idx NULL:
 * every pinned point, in index order, count their number), reached
 * exactly at the end of the next msocl_sim_step(s, n): before step j the
 * pin sits at (1 - f) start + f target, f = (float)j / (float)n, with
 * the velocity of its motion over the step, so springs and dashpots feel
 * it. k one-step calls given those points as targets give bitwise the
 * steps of one k-step call. One device only (MSOCL_ERR_BAD_VALUE on a
 * split); a point not pinned or given twice: MSOCL_ERR_BAD_VALUE. */
MSOCL_EXTERN int msocl_sim_set_pin_targets(msocl_sim *s, int count,
                                           const int *idx, const float *xyz);
/* Soft pins: free points idx[0..count) pulled toward anchors xyz (3 count
 * floats) by springs of `stiffness` N/m (zero rest length), a velocity
 * change dt k (anchor - x) / m before each step (first order, as wind);
 * given again for the same points in the same order, the anchors move
 * from where they rest to the new ones over the next msocl_sim_step, along
 * straight lines as pin targets do; otherwise they start there. count 0
 * clears them. A hard-pinned point, an index out of range or given twice,
 * a non-finite anchor or stiffness: an error; a stiffness whose
 * oscillation would be unstable at the simulation's dt (k dt^2 / m > 1):
 * MSOCL_ERR_UNSTABLE. Planes engine on one device. */
MSOCL_EXTERN int msocl_sim_set_soft_pins(msocl_sim *s, int count,
                                         const int *idx, const float *xyz,
                                         float stiffness);
/* Moving colliders. Each analytic collider (id: msocl_model_collider_count)
 * has a pose, a position and a quaternion (x, y, z, w; not zero,
 * normalised where used), that starts where it was added: a plane's
 * position is the point offset * normal, a sphere's its centre, a table's
 * its top centre, a capsule's the midpoint of its ends, a box's its
 * centre; the rotation is a box's quaternion, identity for the others.
 * The shape moves rigidly with its pose, turning about the pose position.
 * The pose set is
 * reached at the end of the next msocl_sim_step(s, n): before step j the
 * collider is at (1 - f) start + f end (in double), f = (float)j /
 * (float)n, the rotation by nlerp (normalised linear blend in double of the
 * ends made unit, end taken in the start's hemisphere), exact at both ends, moving toward the
 * pose at (j + 1) / n; the collision response acts on the
 * velocity relative to the surface's u = v + w x (p - c) over the step
 * (friction on the relative tangential part: a point resting on a moving
 * box at friction 1 moves with it). k one-step calls given the poses at
 * j / k equal one k-step call, bitwise. A table turns only about y
 * (MSOCL_ERR_BAD_VALUE otherwise). One device only: MSOCL_ERR_BAD_VALUE
 * on a split simulation.
 * Unknown id: MSOCL_ERR_BAD_INDEX; NaN/Inf: MSOCL_ERR_NOT_FINITE; a zero
 * quaternion: MSOCL_ERR_BAD_VALUE. get: the pose reached so far (the
 * rotation as set). */
MSOCL_EXTERN int msocl_sim_set_collider_pose(msocl_sim *s, int id,
                                             const float position[3],
                                             const float rotation[4]);
MSOCL_EXTERN int msocl_sim_get_collider_pose(msocl_sim *s, int id,
                                             float position[3],
                                             float rotation[4]);
/* A disabled collider (on 0) has no effect from the next step until
 * enabled again. Same engine limits as the poses. */
MSOCL_EXTERN int msocl_sim_enable_collider(msocl_sim *s, int id, int on);
/* Analytic colliders added to and removed from a running simulation.
 * add: as msocl_model_add_plane, _sphere, _table, _capsule and _box (the
 * same arguments and checks: NaN/Inf MSOCL_ERR_NOT_FINITE; a zero normal
 * or quaternion, a radius or half extent <= 0, friction outside [0, 1]
 * MSOCL_ERR_BAD_VALUE), the new collider's id into *id (id may be NULL);
 * it starts at rest at the pose it was given, enabled, from the next
 * step, and takes poses, enable and remove as the model's do. Ids: the
 * lowest removed id is taken again, else the next after the highest in
 * use (the model's are 0 .. msocl_model_collider_count - 1), so a
 * removed id may name a later collider. At most MSOCL_MAX_COLLIDERS in
 * use at once (MSOCL_ERR_TOO_MANY). remove: the collider has no effect
 * from the next step and its id is unknown (MSOCL_ERR_BAD_INDEX) until
 * an add takes it. An add whose kind the simulation's kernels were not
 * built for, or that needs a slot they lack, builds the program again
 * (once per set of kinds and count, cached: docs/API.md gives the time)
 * and keeps the whole state; one into a removed slot of a kind built in
 * only writes the table. Same engine limits as the poses
 * (MSOCL_ERR_BAD_VALUE on a split simulation). */
#define MSOCL_MAX_COLLIDERS 16
MSOCL_EXTERN int msocl_sim_add_plane(msocl_sim *s, const float normal[3],
                                     float offset, float friction, int *id);
MSOCL_EXTERN int msocl_sim_add_sphere(msocl_sim *s, const float centre[3],
                                      float radius, float friction, int *id);
MSOCL_EXTERN int msocl_sim_add_table(msocl_sim *s, const float top[3],
                                     float radius, float friction, int *id);
MSOCL_EXTERN int msocl_sim_add_capsule(msocl_sim *s, const float a[3],
                                       const float b[3], float radius,
                                       float friction, int *id);
MSOCL_EXTERN int msocl_sim_add_box(msocl_sim *s, const float centre[3],
                                   const float rotation[4],
                                   const float half[3], float friction,
                                   int *id);
MSOCL_EXTERN int msocl_sim_remove_collider(msocl_sim *s, int id);
/* Mesh collider `id` (its number among the model's mesh colliders):
 * the positions verts (3 floats a vertex, as many as it was added with)
 * its vertices reach at the end of the next msocl_sim_step(s, n), moving
 * linearly over its n steps (an animated body); the points it touches
 * take on its velocity there. enable: on (!= 0) or off from the next
 * step. An unknown id, a non-finite vertex: MSOCL_ERR_BAD_INDEX,
 * MSOCL_ERR_NOT_FINITE. */
MSOCL_EXTERN int msocl_sim_set_mesh_collider_vertices(msocl_sim *s, int id,
                                                      const float *verts);
MSOCL_EXTERN int msocl_sim_enable_mesh_collider(msocl_sim *s, int id, int on);
/* Partial state access: 3 floats a point, of positions (velocities 0) or
 * velocities (1), for points first..first+count-1 or idx[0..count);
 * other points and the rest of the state are untouched (writes keep the
 * pins and count as writes for the blow-up check). A write's list names
 * each point once (MSOCL_ERR_BAD_VALUE); a value is finite
 * (MSOCL_ERR_NOT_FINITE) and within msocl_model_add_points' 1e18
 * (MSOCL_ERR_BAD_VALUE), a velocity too. */
MSOCL_EXTERN int msocl_sim_read_range(msocl_sim *s, int velocities,
                                      int first, int count, float *xyz);
MSOCL_EXTERN int msocl_sim_write_range(msocl_sim *s, int velocities,
                                       int first, int count,
                                       const float *xyz);
MSOCL_EXTERN int msocl_sim_read_list(msocl_sim *s, int velocities, int count,
                                     const int *idx, float *xyz);
MSOCL_EXTERN int msocl_sim_write_list(msocl_sim *s, int velocities,
                                      int count, const int *idx,
                                      const float *xyz);

typedef struct {
  /* joules; gravity: -sum m g . p, zero at the origin (for gravity along
   * -y, m |g| y: relative to y = 0) */
  double kinetic, spring, gravity;
  double total;
} msocl_energy;

/* Energy of the current state, summed on the device. */
MSOCL_EXTERN int msocl_sim_energy(msocl_sim *s, msocl_energy *e);
/* Implicit Euler: CG iterations and relative residual of the last step. */
MSOCL_EXTERN int msocl_sim_solver_stats(const msocl_sim *s, int *iterations,
                                        double *residual);
/* Steps taken since creation. */
MSOCL_EXTERN int msocl_sim_step_count(const msocl_sim *s, long long *steps);

/* How a simulation is split over devices, and what the split costs. */
typedef struct {
  int parts;                             /* devices the model runs on */
  int device[MSOCL_MAX_DEVICES];         /* each part's index in the runtime */
  int first[MSOCL_MAX_DEVICES];          /* the points each part advances */
  int count[MSOCL_MAX_DEVICES];
  float weight[MSOCL_MAX_DEVICES];       /* its share (given or calibrated) */
  double halo_points[MSOCL_MAX_DEVICES]; /* points each part receives a step */
  double bytes_per_step; /* exchanged through the host, each way */
  /* Each part has a host thread of its own; per part: host time reading
   * the slices others read and queuing writes into its halo, host time
   * waiting for its device, and from event profiling its device's time
   * in those copies and in the kernels of its steps. */
  double part_exchange_seconds[MSOCL_MAX_DEVICES];
  double part_wait_seconds[MSOCL_MAX_DEVICES];
  double copy_seconds[MSOCL_MAX_DEVICES], compute_seconds[MSOCL_MAX_DEVICES];
  /* Boundary first (tuning.overlap): the points of each part that others
   * read, which its phases run on before the rest; 0 when off. */
  int overlap;
  double boundary_points[MSOCL_MAX_DEVICES];
  /* of each part's copy time, the device time of its copies (reads of
   * its boundary, writes of its halo) that ran while its interior's
   * kernels still did (from the same stamps) */
  double hidden_copy_seconds[MSOCL_MAX_DEVICES];
  double exchange_seconds;     /* the largest part_exchange_seconds */
  double wait_seconds;         /* the largest part_wait_seconds */
  long long steps;
} msocl_split_info;

MSOCL_EXTERN int msocl_sim_split_info(const msocl_sim *s,
                                      msocl_split_info *info);
/* The simulation's own numbering, which split_info's ranges count in:
 * order[k] is the model's number of the simulation's point k (n ints;
 * the identity unless the points were renumbered). */
MSOCL_EXTERN int msocl_sim_point_order(const msocl_sim *s, int *order);

/* The largest stable time step of the model under an integrator, from a
 * Gershgorin bound on the highest eigenfrequency (see lib/model/stable_dt.c):
 * symplectic Euler and Verlet h w < 2, RK4 h w <= 2 sqrt 2 (both less with
 * damping), explicit Euler needs damping (MSOCL_ERR_UNSTABLE without),
 * implicit Euler: +infinity. msocl_stable_dt bounds the model's own
 * positions, msocl_stable_dt_at those given (3n floats: a simulation's
 * state); either holds near that state only, since a stretched spring
 * stiffens sideways: a hanging cloth soon needs a shorter step.
 * msocl_safe_dt bounds every state the springs can reach (each at its
 * stiffest), less a margin for symplectic Euler and Verlet, whose long
 * undamped runs gain energy near their limit: the step to run at
 * (docs/STABILITY.md). MSOCL_ERR_BAD_COUNT when nothing bounds the step
 * (no stiffness, no damping); MSOCL_ERR_BAD_VALUE from the first two when
 * a spring of positive rest length joins coincident points. */
MSOCL_EXTERN int msocl_stable_dt(const msocl_model *m,
                                 msocl_integrator integrator, float *dt);
MSOCL_EXTERN int msocl_stable_dt_at(const msocl_model *m, const float *xyz,
                                    msocl_integrator integrator, float *dt);
MSOCL_EXTERN int msocl_safe_dt(const msocl_model *m,
                               msocl_integrator integrator, float *dt);

/* --------------------------------------------------------------- batches */

/* Many independent simulations (say 64 small cloths) spread over the
 * runtime's devices, stepped together: each device works through its
 * share while the others work through theirs. */
typedef struct msocl_batch msocl_batch;

/* count models, each with options o (dt, integrator, tuning.layout, ...;
 * o's tuning.device and tuning.ndevices are ignored: simulation i goes to
 * device i mod devices). */
MSOCL_EXTERN int msocl_batch_create(msocl_batch **b, msocl_runtime *rt,
                                    int count,
                                    const msocl_model *const *models,
                                    const msocl_sim_options *o);
MSOCL_EXTERN void msocl_batch_destroy(msocl_batch *b);
/* n steps of every simulation; on a blow-up, the others still finish
 * their steps and the first error is returned (its message names the
 * simulation). */
MSOCL_EXTERN int msocl_batch_step(msocl_batch *b, int n);
MSOCL_EXTERN int msocl_batch_count(const msocl_batch *b, int *count);
/* Simulation i, to read or write its state (owned by the batch). */
MSOCL_EXTERN int msocl_batch_sim(msocl_batch *b, int i, msocl_sim **s);

/* ------------------------------------------------------------- reference */

/* The same model and step on the host in double precision: the yardstick
 * for accuracy. */
typedef struct msocl_reference msocl_reference;

/* Uses o's dt, integrator, strain limiting and CG settings (NULL: the
 * defaults of msocl_sim_options_init); the step runs in double. */
MSOCL_EXTERN int msocl_reference_create(msocl_reference **r,
                                        const msocl_model *m,
                                        const msocl_sim_options *o);
MSOCL_EXTERN void msocl_reference_destroy(msocl_reference *r);
/* Implicit Euler: MSOCL_ERR_NO_CONVERGENCE as msocl_sim_step. */
MSOCL_EXTERN int msocl_reference_step(msocl_reference *r, int n);
MSOCL_EXTERN int msocl_reference_positions(const msocl_reference *r,
                                           double *xyz);
MSOCL_EXTERN int msocl_reference_velocities(const msocl_reference *r,
                                            double *xyz);
MSOCL_EXTERN int msocl_reference_energy(const msocl_reference *r,
                                        msocl_energy *e);
/* As msocl_sim_set_wind, in double. */
MSOCL_EXTERN int msocl_reference_set_wind(msocl_reference *r,
                                          const msocl_wind *w);
/* As msocl_sim_set_soft_pins, in double. */
MSOCL_EXTERN int msocl_reference_set_soft_pins(msocl_reference *r,
                                               int count, const int *idx,
                                               const float *xyz,
                                               float stiffness);
/* As msocl_sim_set_accelerations and msocl_sim_set_forces, in double. */
MSOCL_EXTERN int msocl_reference_set_accelerations(msocl_reference *r,
                                                   const float *xyz);
MSOCL_EXTERN int msocl_reference_set_forces(msocl_reference *r,
                                            const float *xyz);
/* The simulation's live controls on the reference (msocl_sim_set_gravity,
 * _set_viscous_damping, _set_air_resistance, msocl_sim_pin,
 * msocl_sim_set_pin_targets), in double. */
MSOCL_EXTERN int msocl_reference_set_gravity(msocl_reference *r, float gx,
                                             float gy, float gz);
MSOCL_EXTERN int msocl_reference_set_viscous_damping(msocl_reference *r,
                                                     float c);
MSOCL_EXTERN int msocl_reference_set_air_resistance(msocl_reference *r,
                                                    float factor);
MSOCL_EXTERN int msocl_reference_pin(msocl_reference *r, int count,
                                     const int *idx, int pinned);
MSOCL_EXTERN int msocl_reference_set_pin_targets(msocl_reference *r,
                                                 int count, const int *idx,
                                                 const float *xyz);
/* msocl_sim_set_collider_pose and msocl_sim_enable_collider on the
 * reference: the same path (poses interpolated in the same floats) and
 * the response on the relative velocity, in double. */
MSOCL_EXTERN int msocl_reference_set_collider_pose(msocl_reference *r, int id,
                                                   const float position[3],
                                                   const float rotation[4]);
MSOCL_EXTERN int msocl_reference_enable_collider(msocl_reference *r, int id,
                                                 int on);
/* msocl_sim_add_* and msocl_sim_remove_collider on the reference: the
 * same checks and ids. */
MSOCL_EXTERN int msocl_reference_add_plane(msocl_reference *r,
                                           const float normal[3],
                                           float offset, float friction,
                                           int *id);
MSOCL_EXTERN int msocl_reference_add_sphere(msocl_reference *r,
                                            const float centre[3],
                                            float radius, float friction,
                                            int *id);
MSOCL_EXTERN int msocl_reference_add_table(msocl_reference *r,
                                           const float top[3], float radius,
                                           float friction, int *id);
MSOCL_EXTERN int msocl_reference_add_capsule(msocl_reference *r,
                                             const float a[3],
                                             const float b[3], float radius,
                                             float friction, int *id);
MSOCL_EXTERN int msocl_reference_add_box(msocl_reference *r,
                                         const float centre[3],
                                         const float rotation[4],
                                         const float half[3], float friction,
                                         int *id);
MSOCL_EXTERN int msocl_reference_remove_collider(msocl_reference *r, int id);

/* ---------------------------------------------------------------- export */

/* Writes points and triangles as Wavefront OBJ (with normals when given).
 * Both writers refuse what no reader takes back (a non-finite value, a
 * triangle naming a point twice: MSOCL_ERR_NOT_FINITE, _BAD_VALUE), and
 * write beside the path, renamed over it once whole: a failed write
 * (MSOCL_ERR_IO) leaves the file that was there as it was. */
MSOCL_EXTERN int msocl_write_obj(const char *path, int npoints,
                                 const float *xyz, const float *normals,
                                 int ntriangles, const int *ijk);
/* Writes points and triangles as ASCII PLY (normals when given). */
MSOCL_EXTERN int msocl_write_ply(const char *path, int npoints,
                                 const float *xyz, const float *normals,
                                 int ntriangles, const int *ijk);
/* The model's triangles (count and 3n indices, owned by the model). */
MSOCL_EXTERN int msocl_model_triangles(const msocl_model *m, int *n,
                                       const int **ijk);

#ifdef __cplusplus
}
#endif
#endif /* MSOCL_H */

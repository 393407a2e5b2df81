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
  XX(EMPTY, -2022, "model has no points")

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
  int type; /* msocl_device_type */
  unsigned compute_units;
  unsigned long long global_mem; /* bytes */
  int image_support;
  size_t image2d_max_width, image2d_max_height;
  int fp64;
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
 * the MSOCL_DEVICE environment variable. */
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
 * NULL) receives the index of the first new point. */
MSOCL_EXTERN int msocl_model_add_points(msocl_model *m, int n,
                                        const float *xyz, const float *mass,
                                        int *first);
/* Appends n springs between points ij[2s], ij[2s+1]. stiffness: n floats
 * >= 0. rest: NULL, or n floats where a negative value means "the current
 * distance". damping: NULL (none) or n floats >= 0, a dashpot along the
 * spring. */
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

/* ------------------------------------------------------------ simulation */

typedef enum {
  MSOCL_LAYOUT_AUTO = 0, /* the faster on the device: BUFFER on CPUs */
  MSOCL_LAYOUT_IMAGE2D,  /* the paper's connectivity texture, 16 slots */
  MSOCL_LAYOUT_BUFFER    /* slot-major buffers, max-degree slots */
} msocl_layout;

typedef enum {
  MSOCL_MATH_PRECISE = 0, /* IEEE single precision, no contraction */
  MSOCL_MATH_RELAXED      /* -cl-fast-relaxed-math, native functions */
} msocl_math;

typedef struct {
  float dt;           /* seconds, > 0 */
  msocl_layout layout;
  msocl_math math;
  int device;         /* index into the runtime's devices */
} msocl_sim_options;

MSOCL_EXTERN void msocl_sim_options_init(msocl_sim_options *o);

typedef struct msocl_sim msocl_sim;

/* Copies the model to the device; the model may be destroyed afterwards. */
MSOCL_EXTERN int msocl_sim_create(msocl_sim **s, msocl_runtime *rt,
                                  const msocl_model *m,
                                  const msocl_sim_options *o);
MSOCL_EXTERN void msocl_sim_destroy(msocl_sim *s);
/* n steps of symplectic Euler (two passes each); returns when done. */
MSOCL_EXTERN int msocl_sim_step(msocl_sim *s, int n);
MSOCL_EXTERN int msocl_sim_point_count(const msocl_sim *s, int *n);
MSOCL_EXTERN int msocl_sim_layout(const msocl_sim *s, msocl_layout *layout);
MSOCL_EXTERN int msocl_sim_device_info(const msocl_sim *s,
                                       msocl_device_info *info);
/* 3 floats per point. */
MSOCL_EXTERN int msocl_sim_read_positions(msocl_sim *s, float *xyz);
MSOCL_EXTERN int msocl_sim_write_positions(msocl_sim *s, const float *xyz);
MSOCL_EXTERN int msocl_sim_read_velocities(msocl_sim *s, float *xyz);
MSOCL_EXTERN int msocl_sim_write_velocities(msocl_sim *s, const float *xyz);
/* Unit normals from the model's triangles, computed on the device. */
MSOCL_EXTERN int msocl_sim_read_normals(msocl_sim *s, float *xyz);

/* ------------------------------------------------------------- reference */

/* The same model and step on the host in double precision: the yardstick
 * for accuracy. */
typedef struct msocl_reference msocl_reference;

MSOCL_EXTERN int msocl_reference_create(msocl_reference **r,
                                        const msocl_model *m, double dt);
MSOCL_EXTERN void msocl_reference_destroy(msocl_reference *r);
MSOCL_EXTERN int msocl_reference_step(msocl_reference *r, int n);
MSOCL_EXTERN int msocl_reference_positions(const msocl_reference *r,
                                           double *xyz);
MSOCL_EXTERN int msocl_reference_velocities(const msocl_reference *r,
                                            double *xyz);

/* ---------------------------------------------------------------- export */

/* Writes points and triangles as Wavefront OBJ (with normals when given). */
MSOCL_EXTERN int msocl_write_obj(const char *path, int npoints,
                                 const float *xyz, const float *normals,
                                 int ntriangles, const int *ijk);
/* The model's triangles (count and 3n indices, owned by the model). */
MSOCL_EXTERN int msocl_model_triangles(const msocl_model *m, int *n,
                                       const int **ijk);

#ifdef __cplusplus
}
#endif
#endif /* MSOCL_H */

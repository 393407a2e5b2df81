#ifndef MSOCL_COMMON_H
#define MSOCL_COMMON_H

/* What every kernel file shares: math mode, collider kinds, and the
 * connectivity arguments of a point's springs, whichever layout holds
 * them. Each .cl file includes the headers it needs; the library joins the
 * headers and then the .cl files into one program (its #include lines
 * dropped: Makefile.am's KERNEL_FILES order), built with -D options that
 * name only what the model uses:
 *   MSOCL_LAYOUT_IMAGE2D | MSOCL_LAYOUT_BUFFER | MSOCL_LAYOUT_GRID
 *                          where the springs live
 *   MSOCL_SLOTS=n          slots per point (BUFFER)
 *   MSOCL_CLASSES          BUFFER: a class byte per slot (rk) naming a
 *                          (rest, k, dashpot) float4 (dmp), not values
 *   MSOCL_DAMPING          per-spring dashpots (a slot table of coefficients)
 *   MSOCL_VISCOUS          viscous damping -c v
 *   MSOCL_AIR              air resistance: velocity times a factor a step
 *   MSOCL_PINS             pinned points
 *   MSOCL_PLANE, MSOCL_SPHERE, MSOCL_TABLE   collider kinds present
 *   MSOCL_RELAXED          native functions (with -cl-fast-relaxed-math)
 * The steps, the energy and the normals run on the state's planes
 * (planes.cl, energy.cl, normals.cl). */

/* Precise mode forbids fused multiply-add so every layout, and every device
 * split, sums in exactly the same arithmetic (bitwise-equal results). */
#ifndef MSOCL_RELAXED
#pragma OPENCL FP_CONTRACT OFF
#define MSOCL_SQRT(x) sqrt(x)
#define MSOCL_DIV(a, b) ((a) / (b))
#else
#define MSOCL_SQRT(x) native_sqrt(x)
#define MSOCL_DIV(a, b) native_divide((a), (b))
#endif

#define MSOCL_PLANE_KIND 1
#define MSOCL_SPHERE_KIND 2
#define MSOCL_TABLE_KIND 3
#define MSOCL_CAPSULE_KIND 4 /* the planes kernels only */
#define MSOCL_BOX_KIND 5

/* BUFFER's per-slot values, or class bytes and the classes' values */
#ifdef MSOCL_CLASSES
#define MSOCL_RK __global const uchar *rk, __global const float4 *dmp
#else
#define MSOCL_RK __global const float2 *rk, __global const float *dmp
#endif

/* Connectivity parameters of every gathering kernel, and the same names to
 * pass them on. */
#if defined(MSOCL_LAYOUT_IMAGE2D)
#define MSOCL_MAX_SLOTS 16
#define MSOCL_CONN                                                            \
  __read_only image2d_t con, int tex_w, int tex_h, __read_only image2d_t dmp
#define MSOCL_CONN_ARGS con, tex_w, tex_h, dmp
#elif defined(MSOCL_LAYOUT_GRID) && defined(MSOCL_GRID_3D)
#define MSOCL_MAX_SLOTS 32
#define MSOCL_CONN                                                            \
  int grid_nx, int grid_ny, int grid_nz, float4 grid_k, float8 grid_rest
#define MSOCL_CONN_ARGS grid_nx, grid_ny, grid_nz, grid_k, grid_rest
/* A lattice's 32 neighbours in the order msocl_model_lattice adds their
 * springs (so in BUFFER's slot order: each set loops the points in index
 * order, so a point meets first the springs of the points before it):
 * 6 structural, 12 face shear, 8 body shear, 6 bend. kind: 0 structural,
 * 1 face shear, 2 body shear, 3 bend - grid_k's stiffness and grid_rest's
 * rest length; grid_rest.s4 is the dashpot. */
__constant int msocl_grid_dx[32] = {
    0, 0, -1, 1, 0, 0,
    0, -1, 1, 0, -1, 1, 0, -1, -1, 1, 1, 0,
    -1, 1, -1, 1, -1, 1, -1, 1,
    0, 0, -2, 2, 0, 0};
__constant int msocl_grid_dy[32] = {
    0, -1, 0, 0, 1, 0,
    -1, 0, 0, 1, -1, -1, -1, 1, 0, 1, 0, 1,
    -1, -1, 1, 1, -1, -1, 1, 1,
    0, -2, 0, 0, 2, 0};
__constant int msocl_grid_dz[32] = {
    -1, 0, 0, 0, 0, 1,
    -1, -1, -1, -1, 0, 0, 1, 0, 1, 0, 1, 1,
    -1, -1, -1, -1, 1, 1, 1, 1,
    -2, 0, 0, 0, 0, 2};
__constant int msocl_grid_kind[32] = {
    0, 0, 0, 0, 0, 0,
    1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
    2, 2, 2, 2, 2, 2, 2, 2,
    3, 3, 3, 3, 3, 3};
/* slot s's stiffness and rest length, and the dashpot (as the cloth's
 * below) */
#define MSOCL_GRID_K(s)                                                       \
  (msocl_grid_kind[s] == 0 ? grid_k.x : msocl_grid_kind[s] == 1 ? grid_k.y   \
   : msocl_grid_kind[s] == 2 ? grid_k.z : grid_k.w)
#define MSOCL_GRID_R(s)                                                       \
  (msocl_grid_kind[s] == 0 ? grid_rest.s0                                    \
   : msocl_grid_kind[s] == 1 ? grid_rest.s1                                  \
   : msocl_grid_kind[s] == 2 ? grid_rest.s2 : grid_rest.s3)
#define MSOCL_GRID_C grid_rest.s4
#elif defined(MSOCL_LAYOUT_GRID)
#define MSOCL_MAX_SLOTS 12
#define MSOCL_CONN int grid_nx, int grid_ny, float4 grid_k, float8 grid_rest
#define MSOCL_CONN_ARGS grid_nx, grid_ny, grid_k, grid_rest
/* A cloth grid's 12 neighbours in the order msocl_model_cloth_grid adds
 * their springs (so in BUFFER's slot order): stretch below, left, right,
 * above; shear below-left, below-right, above-left, above-right; bend two
 * below, left, right, above. kind: 0 stretch, 1 shear, 2 bend; rest: index
 * into grid_rest. */
__constant int msocl_grid_dx[12] = {0, -1, 1, 0, -1, 1, -1, 1, 0, -2, 2, 0};
__constant int msocl_grid_dy[12] = {-1, 0, 0, 1, -1, -1, 1, 1, -2, 0, 0, 2};
__constant int msocl_grid_kind[12] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
__constant int msocl_grid_rest[12] = {1, 0, 0, 1, 2, 3, 3, 2, 5, 4, 4, 5};
/* slot s's stiffness and rest length, and the dashpot */
#define MSOCL_GRID_K(s)                                                       \
  (msocl_grid_kind[s] == 0 ? grid_k.x : msocl_grid_kind[s] == 1 ? grid_k.y   \
                                                              : grid_k.z)
#define MSOCL_GRID_R(s)                                                       \
  (msocl_grid_rest[s] == 0 ? grid_rest.s0                                    \
   : msocl_grid_rest[s] == 1 ? grid_rest.s1                                  \
   : msocl_grid_rest[s] == 2 ? grid_rest.s2                                  \
   : msocl_grid_rest[s] == 3 ? grid_rest.s3                                  \
   : msocl_grid_rest[s] == 4 ? grid_rest.s4 : grid_rest.s5)
#define MSOCL_GRID_C grid_k.w
#elif defined(MSOCL_SPILL)
/* BUFFER with a spill: MSOCL_SLOTS slots a point in the table, the rest of
 * a point's springs (only a few points have more) listed after the table,
 * point i's from spill[i] to spill[i + 1]; MSOCL_DEGREE: the most any
 * point has. */
#define MSOCL_MAX_SLOTS MSOCL_DEGREE
#define MSOCL_CONN __global const int *nbr, MSOCL_RK, __global const int *spill
#define MSOCL_CONN_ARGS nbr, rk, dmp, spill
#else
#define MSOCL_MAX_SLOTS MSOCL_SLOTS
#define MSOCL_CONN __global const int *nbr, MSOCL_RK
#define MSOCL_CONN_ARGS nbr, rk, dmp
#endif
/* The slots a gather reads from the table (BUFFER: the table's, the
 * rest spill). */
#if defined(MSOCL_LAYOUT_IMAGE2D) || defined(MSOCL_LAYOUT_GRID)
#define MSOCL_TABLE_SLOTS MSOCL_MAX_SLOTS
#else
#define MSOCL_TABLE_SLOTS MSOCL_SLOTS
#endif
/* The slots a gather reads for a point that does not spill: BUFFER's
 * MSOCL_DENSE, the most such a point has (the table's width is rounded
 * up, and a spilling point fills it). */
#ifdef MSOCL_DENSE
#define MSOCL_ROW_SLOTS MSOCL_DENSE
#else
#define MSOCL_ROW_SLOTS MSOCL_TABLE_SLOTS
#endif

#endif

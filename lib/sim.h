/* The simulation handle, shared by the files that set it up (sim.c), step
 * it (sim_step.c, integrate*.c, strain.c) and measure it (energy.c). */
#ifndef MSOCL_SIM_H
#define MSOCL_SIM_H

#include "layout.h"

/* Kernels the library's program holds; the enum indexes msocl_sim.k. */
enum {
  MSOCL__K_VELOCITY, MSOCL__K_POSITION, MSOCL__K_NORMALS, MSOCL__K_EULER,
  MSOCL__K_ACCEL, MSOCL__K_DRIFT, MSOCL__K_KICK, MSOCL__K_RK4,
  MSOCL__K_ENERGY, MSOCL__K_IE_RHS, MSOCL__K_IE_APPLY, MSOCL__K_CG_STEP,
  MSOCL__K_CG_DIR, MSOCL__K_IE_FINISH, MSOCL__K_STRAIN_VEL,
  MSOCL__K_STRAIN_POS, MSOCL__K_STRAIN_COMMIT, MSOCL__K_EDGES_FORCE,
  MSOCL__K_EDGES_VEL, MSOCL__K_EDGES_ENERGY, MSOCL__K_COUNT
};

struct msocl_sim {
  struct msocl__device *dev;
  msocl_sim_options o;
  int n;
  cl_uint nconn;          /* connectivity arguments before the others */
  struct msocl__layout lay;
  cl_mem pos[2], vel[2];  /* ping-pong: [r] is current */
  cl_mem inv_mass, col, normal, tri_off, tri_ab;
  cl_mem acc;             /* Verlet: a at the current state */
  cl_mem stage_p[2], stage_v[2], sum_p, sum_v; /* RK4 stages; CG vectors */
  cl_mem backup_p, backup_v; /* last state that passed the blow-up check */
  cl_mem partial;         /* one float4 per work-group of reductions */
  cl_mem force;           /* EDGES: float4 force accumulators */
  size_t edge_global, edge_groups; /* EDGES: springs rounded up to 64 */
  cl_kernel k[MSOCL__K_COUNT];
  int r;
  int acc_valid;          /* acc matches the current state */
  size_t global, groups;
  long long steps;
  int e0_valid;           /* baseline energy of the blow-up check */
  double e0, escale;      /* start energy and the scene's energy scale */
  double total_mass, extent;
  int cg_iterations;
  double cg_residual;
  cl_float4 gravity;
  float viscous, air;
  int ncol;
  unsigned char *pinned;  /* host copy: writes keep pos.w */
  float *stage;           /* 4n floats for transfers */
  cl_float4 *partial_host;
};

/* Sets the kernels' fixed arguments, once. */
int msocl__integrate_setup(msocl_sim *s);
/* Enqueues `n` steps of the chosen integrator (no wait). */
int msocl__integrate(msocl_sim *s, int n);
/* Energy of the current state (waits for the device). */
int msocl__energy(msocl_sim *s, msocl_energy *e);
/* Sets argument i of kernel k to a buffer, a float, an int. */
int msocl__arg_mem(cl_kernel k, cl_uint i, cl_mem m);
int msocl__arg_float(cl_kernel k, cl_uint i, float f);
int msocl__arg_int(cl_kernel k, cl_uint i, int v);
/* Implicit Euler (integrate_implicit.c): fixed arguments; the new
 * velocity into vel[1 - r]. */
int msocl__implicit_setup(msocl_sim *s);
int msocl__implicit_velocity(msocl_sim *s);
/* Strain limiting (strain.c): fixed arguments; the velocity correction on
 * vel[1 - r]; Provot's position correction on pos[1 - r]. */
int msocl__strain_setup(msocl_sim *s);
int msocl__strain_velocity(msocl_sim *s);
int msocl__strain_position(msocl_sim *s);
/* Enqueues kernel k over all points (global = n rounded up to 64). */
int msocl__launch(msocl_sim *s, int k);

#endif

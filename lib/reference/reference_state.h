/* The host reference's state, shared by its files (reference*.c). */
#ifndef MSOCL_REFERENCE_STATE_H
#define MSOCL_REFERENCE_STATE_H

#include "internal.h"

struct msocl_reference {
  msocl_sim_options o;
  int n;
  double dt;
  double *pos, *vel, *pnew, *vnew; /* 3n each; swapped every step */
  double *a, *acc, *tmp;           /* scratch; acc: Verlet's a */
  double *sum_p, *sum_v, *stage_p[2], *stage_v[2]; /* RK4; CG vectors */
  double *inv_mass, *mass;
  unsigned char *pinned;
  double gravity[3], viscous, air;
  int ncol;
  struct msocl__collider col[MSOCL__MAX_COLLIDERS];
  struct msocl__adjacency adj;
  double *k, *rest, *damp; /* per spring */
  int acc_valid;
  int cg_iterations;
  double cg_residual;
  int cg_missed, cg_worst_iterations; /* as the engine's (sim.h) */
  double cg_worst_residual;
  int nt, *tri;            /* the model's triangles, 3 a triangle */
  int wind_on;             /* reference_wind.c */
  double wind_air[3], wind_kd, wind_kl;
  double *field;           /* accelerations, 3n, or NULL (reference_field.c) */
  /* soft pins (reference_soft_pins.c) */
  int soft_m, soft_moving, *soft_idx;
  double soft_k, *soft_from, *soft_to;
  /* pins moving to targets in the next call (reference_controls.c) */
  int tm;
  int *tidx;
  double *tstart, *ttarget;
  /* colliders moving to poses in the next call (reference_colliders.c):
   * as added, their poses, targets, the disabled, and a moving one's
   * motion over the step (v, w, the pose position) */
  struct msocl__collider col_add[MSOCL__MAX_COLLIDERS];
  float cpos[MSOCL__MAX_COLLIDERS][3], crot[MSOCL__MAX_COLLIDERS][4];
  float cto_pos[MSOCL__MAX_COLLIDERS][3], cto_rot[MSOCL__MAX_COLLIDERS][4];
  unsigned char cto[MSOCL__MAX_COLLIDERS], coff[MSOCL__MAX_COLLIDERS];
  unsigned char cmoving[MSOCL__MAX_COLLIDERS];
  double cmove[MSOCL__MAX_COLLIDERS][9];
  int cpending;
};

/* reference_colliders.c: the colliders as added, at their home poses; the
 * colliders before step k of a call's n (and at its end, k = n); the
 * surface velocity u of collider c at p (0 when it does not move). */
void msocl__ref_colliders_init(msocl_reference *r);
void msocl__ref_colliders(msocl_reference *r, int k, int n);
void msocl__ref_surface(const msocl_reference *r, int c, const double *p,
                        double *u);

/* reference_controls.c: the moving pins before step k of a call's n (and
 * at its end, k = n); frees their lists. */
void msocl__ref_pins(msocl_reference *r, int k, int n);
void msocl__ref_controls_free(msocl_reference *r);

static inline double msocl__dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* reference_force.c: internal and viscous force on point i; collisions. */
void msocl__ref_force(const msocl_reference *r, const double *pos,
                      const double *vel, int i, double *f);
/* A capsule's and a box's gap at p and unit gradient n
 * (reference_shapes.c; kernels/planes.cl msocl_planes_gap). */
double msocl__ref_capsule_gap(const struct msocl__collider *k, const double *p,
                              double *n);
double msocl__ref_box_gap(const struct msocl__collider *k, const double *p,
                          double *n);
void msocl__ref_collide(const msocl_reference *r, const double *p, double *v,
                        double fscale);
/* Pushes p out of the colliders it is inside, with v's normal part. */
void msocl__ref_project(const msocl_reference *r, double *p, double *v);
/* Backward Euler's new velocities into r->vnew (reference_implicit.c). */
void msocl__ref_implicit_velocity(msocl_reference *r);
/* Wind's velocity change before a step (reference_wind.c). */
void msocl__ref_wind(msocl_reference *r);
/* The user's field's velocity change before a step (reference_field.c). */
void msocl__ref_field(msocl_reference *r);
/* Soft pins' velocity change before step k of a call's n (k = n: the
 * call's end), and their lists freed (reference_soft_pins.c). */
void msocl__ref_soft_pins(msocl_reference *r, int k, int n);
void msocl__ref_soft_pins_free(msocl_reference *r);
/* As msocl__cg_report, for msocl_reference_step. */
int msocl__ref_cg_report(msocl_reference *r, int rc, int n);

#endif

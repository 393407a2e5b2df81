/* Each integrator's step, described once (schedule.c): its phases, the
 * passes each phase runs, and what other engines must receive after it.
 * The planes (planes.c) run each pass; the one-engine loop and the split runtime (sim_step.c) walk the
 * table. The host reference (reference.c) keeps its own schedule: it is
 * the oracle, and must not share this one. */
#ifndef MSOCL_SCHEDULE_H
#define MSOCL_SCHEDULE_H

#include "engine.h"

/* What a pass does, on the state [r] of the step into [w]. */
enum msocl__pass {
  MSOCL__P_VELOCITY,   /* symplectic Euler's new velocities (EDGES:
                          scatter, then integrate) */
  MSOCL__P_CG,         /* implicit Euler's new velocities: the host's CG
                          over every engine (cg.c) */
  MSOCL__P_STRAIN_VEL, /* velocity strain sweeps on the new velocities */
  MSOCL__P_POSITION,   /* new positions from the new velocities */
  MSOCL__P_FUSED,      /* both symplectic passes in one */
  MSOCL__P_EULER,      /* explicit Euler, one pass */
  MSOCL__P_DRIFT,      /* Verlet: the half-step velocity in place, the new
                          positions */
  MSOCL__P_KICK,       /* Verlet: the new velocities, the acceleration */
  MSOCL__P_RK4_0,      /* RK4's stages 0..3, in order */
  MSOCL__P_RK4_1,
  MSOCL__P_RK4_2,
  MSOCL__P_RK4_3,
  MSOCL__P_PROVOT,     /* Provot's sweeps on the new positions, taken up
                          by the new velocities */
  MSOCL__P_PROVOT_HALF /* the same, taken up by Verlet's half-step ones */
};

/* The most passes a phase runs, and phases a step has. */
#define MSOCL__MAX_PASSES 2
#define MSOCL__MAX_PHASES 4

/* A phase: its passes, in order - only the first reads other points (a
 * gather), so a phase may run span by span - and after it the exchange
 * bits (MSOCL__X_*) other engines need: `mask` always, `damped` too when
 * dashpots read neighbours' velocities. */
struct msocl__phase_desc {
  int npasses;
  enum msocl__pass pass[MSOCL__MAX_PASSES];
  unsigned mask, damped;
};

struct msocl__schedule {
  int nphases;
  struct msocl__phase_desc phase[MSOCL__MAX_PHASES];
};

/* The schedule that options o run (integrator, strain limit, fused). */
const struct msocl__schedule *msocl__schedule_of(const msocl_sim_options *o);

/* Each engine's pass p on its current state in the planes (planes.c).
 * MSOCL__P_CG is the walker's own. */
int msocl__planes_pass(msocl__engine *s, enum msocl__pass p);
/* Up to n steps as one launch where planes_rows.c's sweep can (no
 * collider moving, no wind it does not blow, no field, soft pins or
 * strain limit, n >= 2): from the current plane set into the other,
 * which then holds the state *done steps on; *done = 0 where it cannot. */
int msocl__pl_rows_steps(msocl__engine *s, int n, int *done);

/* The CG's operations on one engine (planes_implicit.c). rhs, apply, step (given alpha): queue the
 * kernel and the partials of its dot product, added up by collect;
 * direction (given beta): the new search direction; finish: the new
 * velocities from the solution. */
struct msocl__cg_ops {
  int (*rhs)(msocl__engine *s);
  int (*apply)(msocl__engine *s);
  int (*step)(msocl__engine *s, float alpha);
  int (*direction)(msocl__engine *s, float beta);
  int (*collect)(msocl__engine *s, double *sum);
  int (*finish)(msocl__engine *s);
};
extern const struct msocl__cg_ops msocl__planes_cg;

#endif

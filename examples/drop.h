/* The shared part of the jello and solid examples: a body dropped onto the
 * ground (the plane y = 0) - options, run, report, output mesh. */
#ifndef DROP_H
#define DROP_H

#include <msocl.h>

typedef struct {
  const char *prog;            /* program name, for messages */
  const char *size_help;       /* what -n means, for the usage text */
  const char *size_name;       /* and in a message: "-n 0: NAME must be" */
  int size, size_min, size_max; /* -n */
  double seconds;              /* -t: simulated time */
  const char *spec;            /* -d: device spec (NULL: MSOCL_DEVICE) */
  const char *out;             /* -o: .obj or .ply */
  int ply;                     /* out is PLY (by its name) */
  float air;                   /* -a: velocity factor a step, (0, 1] */
  float dt;                    /* -T: time step (0: half the stable one) */
  /* The smallest damping / stiffness of the model's springs (s; 0: no
   * dashpots): what bounds explicit Euler's step. */
  float dashpot_ratio;
  msocl_integrator integrator; /* -i */
  msocl_layout layout;         /* -l */
  int keep_numbering;          /* -K: no renumbering (to compare) */
} drop_options;

/* Reads argv over the defaults already in *d and checks that d->out can
 * be written. Returns 0, or the exit status: 0 after the usage for -h
 * (*done set), 2 after a message naming the bad option. */
int drop_parse(drop_options *d, int argc, char **argv, int *done);

/* Adds the ground and air resistance to m, simulates d->seconds with half
 * the stable step, prints steps per second, the final kinetic energy,
 * whether the body (total mass `mass`, kg) came to rest and its lowest
 * point's height, and writes the model's triangles and the points on
 * them to d->out. *xyz receives the final positions of all points (free()
 * it). Returns 0, or 1 after printing the error. */
int drop_run(const drop_options *d, msocl_model *m, double mass,
             float **xyz);

#endif /* DROP_H */

/* The simulation handle, shared by sim.c (setup) and sim_step.c (stepping
 * and state transfers). */
#ifndef MSOCL_SIM_H
#define MSOCL_SIM_H

#include "layout.h"

struct msocl_sim {
  struct msocl__device *dev;
  int n;
  float dt;
  struct msocl__layout lay;
  cl_mem pos[2], vel[2];  /* ping-pong: [r] is current */
  cl_mem inv_mass, col, normal, tri_off, tri_ab;
  cl_kernel kvel[2], kpos[2], knorm[2]; /* [r]: reads the r copies */
  int r;
  size_t global;
  unsigned char *pinned;  /* host copy: writes keep pos.w */
  float *stage;           /* 4n floats for transfers */
};

#endif

/* The second seed's scene (Withers): a jello cube - a lattice of points with
 * structural, face shear and bend springs - falls onto the ground and
 * settles. Prints steps per second, the final kinetic energy, whether it
 * came to rest and its lowest point, and writes the final surface mesh.
 *
 *   msocl-jello [-n SIZE] [-t SECONDS] [-d DEVICE_SPEC] [-a AIR] [-T DT]
 *               [-i symplectic|verlet|rk4|implicit|explicit]
 *               [-l auto|buffer|image2d|edges|grid] [-K]
 *               [-o OUT.obj|OUT.ply]
 */
#include "drop.h"

#include "cli.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
  /* Air resistance 0.999 a step, the seed's kind of damping. The springs'
   * dashpots alone (-a 1) bring the cube only just under the rest
   * threshold in 3 s (its fastest point at 0.97 cm/s); 0.999 a step - a
   * decay rate of 1.05/s at the default step, too weak to slow the 0.1 m
   * fall visibly - leaves 0.28 cm/s. The factor is a step's: a smaller
   * step (-T, or explicit Euler's) damps more per second. */
  drop_options d = {.prog = "msocl-jello",
                    .size_help = "points along each edge",
                    .size_name = "points along an edge",
                    .size = 8, .size_min = 2, .size_max = 64, .seconds = 3.0,
                    .out = "jello.obj", .air = 0.999f};
  int done, rc = drop_parse(&d, argc, argv, &done);
  if (rc || done)
    return rc;

  /* The library's cube (2 cm spacing, 2 g points, 10 cm above the ground;
   * see msocl_lattice_desc_init), SIZE points a side. Structural + face
   * shear + bend springs give an inner point 24 springs: more than the
   * connectivity texture's 16 slots. AUTO runs the lattice as a GRID
   * where its padded planes fit, else as BUFFER. */
  msocl_lattice_desc ld;
  msocl_lattice_desc_init(&ld);
  ld.nx = ld.ny = ld.nz = d.size;
  ld.origin[0] = ld.origin[2] = -0.5f * ld.spacing * (float)(d.size - 1);
  /* The same dashpot on every spring: the stiffest set has the least c/k. */
  float kmax = ld.k_structural > ld.k_shear_face ? ld.k_structural
                                                 : ld.k_shear_face;
  d.dashpot_ratio = ld.damping / (kmax > ld.k_bend ? kmax : ld.k_bend);
  msocl_model *m = NULL;
  if ((rc = msocl_model_lattice(&m, &ld)) != MSOCL_OK)
    return cli_fail(d.prog, "building the cube", rc);
  int n = 0, springs = 0, degree = 0;
  if ((rc = msocl_model_point_count(m, &n)) != MSOCL_OK ||
      (rc = msocl_model_spring_count(m, &springs)) != MSOCL_OK ||
      (rc = msocl_model_max_degree(m, &degree)) != MSOCL_OK) {
    msocl_model_destroy(m);
    return cli_fail(d.prog, "counting the cube", rc);
  }
  printf("jello cube %dx%dx%d: %d points, %d springs, up to %d a point\n",
         d.size, d.size, d.size, n, springs, degree);

  float *xyz = NULL;
  rc = drop_run(&d, m, (double)n * ld.point_mass, &xyz);
  free(xyz);
  msocl_model_destroy(m);
  return rc;
}

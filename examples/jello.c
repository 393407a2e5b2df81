/* The second seed's scene (Withers): a jello cube - a lattice of points with
 * structural, face shear and bend springs - falls onto the ground and
 * settles. Prints steps per second, the final kinetic energy, whether it
 * came to rest and its lowest point, and writes the final surface mesh.
 *
 *   jello [-n SIZE] [-t SECONDS] [-d DEVICE_SPEC] [-a AIR]
 *         [-i symplectic|verlet|rk4|implicit|explicit]
 *         [-l auto|buffer|image2d] [-o OUT.obj|OUT.ply]
 */
#include "drop.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
  /* Air resistance 0.999 a step: the springs' dashpots calm the cube's
   * wobble, but nothing else slows the body as a whole - it bounces and
   * rocks on the ground for seconds. 0.999 a step is a decay rate of
   * about 5/s at the default step, which brings it to rest within 3 s
   * without visibly slowing its fall. */
  drop_options d = {"jello", "points along each edge", 8, 2, 100, 3.0,
                    NULL, "jello.obj", 0.999f, MSOCL_SYMPLECTIC_EULER,
                    MSOCL_LAYOUT_AUTO};
  int rc = drop_parse(&d, argc, argv);
  if (rc)
    return rc;

  /* The library's cube (2 cm spacing, 2 g points, 10 cm above the ground;
   * see msocl_lattice_desc_init), SIZE points a side. Structural + face
   * shear + bend springs give an inner point 24 springs: more than the
   * connectivity texture's 16 slots, so AUTO picks the BUFFER layout. */
  msocl_lattice_desc ld;
  msocl_lattice_desc_init(&ld);
  ld.nx = ld.ny = ld.nz = d.size;
  ld.origin[0] = ld.origin[2] = -0.5f * ld.spacing * (float)(d.size - 1);
  msocl_model *m = NULL;
  if ((rc = msocl_model_lattice(&m, &ld)) != MSOCL_OK)
    return drop_fail(d.prog, "building the cube", rc);
  int n = 0, springs = 0, degree = 0;
  if ((rc = msocl_model_point_count(m, &n)) != MSOCL_OK ||
      (rc = msocl_model_spring_count(m, &springs)) != MSOCL_OK ||
      (rc = msocl_model_max_degree(m, &degree)) != MSOCL_OK) {
    msocl_model_destroy(m);
    return drop_fail(d.prog, "counting the cube", rc);
  }
  printf("jello cube %dx%dx%d: %d points, %d springs, up to %d a point\n",
         d.size, d.size, d.size, n, springs, degree);

  float *xyz = NULL;
  rc = drop_run(&d, m, (double)n * ld.point_mass, &xyz);
  free(xyz);
  msocl_model_destroy(m);
  return rc;
}

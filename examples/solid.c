/* A soft ball (Vassilev & Spanlang's deformable solid: springs along the
 * edges of an icosphere plus support springs from every surface point to a
 * centre point) dropped onto the ground. Prints steps per second, the final
 * kinetic energy, whether it came to rest, and how much of its volume it
 * kept; writes the final surface mesh.
 *
 *   msocl-solid [-n SUBDIVISIONS] [-t SECONDS] [-d DEVICE_SPEC] [-a AIR]
 *               [-T DT] [-i symplectic|verlet|rk4|implicit|explicit]
 *               [-l auto|buffer|image2d|edges] [-K] [-o OUT.obj|OUT.ply]
 */
#include "drop.h"

#include "cli.h"

#include <stdio.h>
#include <stdlib.h>

/* Volume inside outward-wound triangles, by the divergence theorem: the
 * sum of the signed tetrahedra from the origin. */
static double volume(const float *p, int nt, const int *ijk)
{
  double v = 0.0;
  for (int t = 0; t < nt; t++) {
    const float *a = p + 3 * ijk[3 * t], *b = p + 3 * ijk[3 * t + 1],
                *c = p + 3 * ijk[3 * t + 2];
    v += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
         (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
         (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
  }
  return v / 6.0;
}

int main(int argc, char **argv)
{
  /* Air resistance 0.998 a step (a decay rate of 3.3/s at the default
   * step, as the viscous damping of tests/check_solids): the ball bounces
   * longer than the cube, its dashpots damping its deformation but not its
   * bounce as a whole. After 3 s, without it (-a 1) its fastest point still
   * moves at 26 cm/s, at 0.999 a step at 2.6 cm/s, at 0.998 at 0.26 cm/s:
   * at rest. */
  drop_options d = {.prog = "msocl-solid", .size_name = "subdivisions",
                    .size_help = "icosphere subdivisions, 0: 12 surface "
                                 "points, 1: 42,\n      2: 162, ...",
                    .size = 2, .size_min = 0, .size_max = 7, .seconds = 3.0,
                    .out = "ball.obj", .air = 0.998f};
  int done, rc = drop_parse(&d, argc, argv, &done);
  if (rc || done)
    return rc;

  /* The library's ball: radius 0.1 m, 0.2 kg over the surface and 20 g at
   * the centre, dropped from 0.2 m above the ground
   * (msocl_solid_desc_init). */
  msocl_solid_desc sd;
  msocl_solid_desc_init(&sd);
  sd.subdivisions = d.size;
  d.dashpot_ratio = sd.damping / (sd.k_surface > sd.k_support
                                       ? sd.k_surface
                                       : sd.k_support);
  msocl_model *m = NULL;
  if ((rc = msocl_model_solid(&m, &sd)) != MSOCL_OK)
    return cli_fail(d.prog, "building the ball", rc);
  int n = 0, springs = 0, ntri = 0;
  const int *tri = NULL;
  float *start = NULL, *xyz = NULL;
  if ((rc = msocl_model_point_count(m, &n)) == MSOCL_OK &&
      !(start = malloc(3 * (size_t)n * sizeof *start)))
    rc = MSOCL_ERR_NO_MEMORY;
  if (rc != MSOCL_OK ||
      (rc = msocl_model_spring_count(m, &springs)) != MSOCL_OK ||
      (rc = msocl_model_triangles(m, &ntri, &tri)) != MSOCL_OK ||
      (rc = msocl_model_get_positions(m, start)) != MSOCL_OK) {
    free(start);
    msocl_model_destroy(m);
    return cli_fail(d.prog, "reading the ball", rc);
  }
  printf("soft ball: %d surface points + centre, %d springs, %d triangles\n",
         n - 1, springs, ntri);

  rc = drop_run(&d, m, (double)sd.surface_mass + sd.centre_mass, &xyz);
  /* (Asked again: the run added the ground to the model.) */
  if (rc == 0 && (rc = msocl_model_triangles(m, &ntri, &tri)) != MSOCL_OK)
    rc = cli_fail(d.prog, "reading the ball", rc);
  else if (rc == 0) {
    /* The centre (the last point) is on no triangle: the surface alone
     * bounds the volume. */
    double v0 = volume(start, ntri, tri), v1 = volume(xyz, ntri, tri);
    printf("volume %.4g l of %.4g l: ratio %.4f\n", 1e3 * v1, 1e3 * v0,
           v1 / v0);
  }
  free(start);
  free(xyz);
  msocl_model_destroy(m);
  return rc;
}

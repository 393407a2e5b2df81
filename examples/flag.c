/* A flag in gusty wind: an n x n cloth, 1.5 m by 1 m, its left edge tied
 * to a pole at its top and bottom corners, in wind that gusts and veers
 * (msocl_sim_set_wind between frames). Writes one OBJ a frame.
 *
 *   msocl-flag [-n GRID] [-t SECONDS] [-F FRAMES] [-d DEVICE_SPEC]
 *              [-o DIR]   (-h: all of them)
 */
#include "cli.h"

#include <msocl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PROG "msocl-flag"

static const char usage[] =
    "usage: " PROG " [-n GRID] [-t SECONDS] [-F FRAMES] [-d DEVICE_SPEC]\n"
    "  [-o DIR]\n"
    "A flag on a pole in wind that gusts between 3 and 9 m/s and veers by\n"
    "up to 25 degrees; writes DIR/flag-NNNN.obj, one a frame.\n"
    "  -n  points along the flag's height, 4 to 512 (default 32; 1.5 n\n"
    "      along its length)\n"
    "  -t  simulated seconds, > 0 to 600 (default 4)\n"
    "  -F  frames a second written, 1 to 240 (default 12)\n"
    "  -d  OpenCL device spec, as MSOCL_DEVICE (default: that variable)\n"
    "  -o  folder for the frames, made if missing (default flag-frames)\n"
    "  -h, --help  this text\n";

/* The flag in the x-y plane, its left edge (x = 0) at the pole, top
 * corner 2 m up; stiff along its threads, soft in shear and bending. */
static msocl_model *build(int n, int *nu)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = *nu = n * 3 / 2;
  d.ny = n;
  const float origin[3] = {0.0f, 2.0f, 0.0f}, u[3] = {1.5f, 0, 0},
              v[3] = {0, -1.0f, 0};
  memcpy(d.origin, origin, sizeof origin);
  memcpy(d.u, u, sizeof u);
  memcpy(d.v, v, sizeof v);
  d.point_mass = 0.2f / (float)(d.nx * d.ny); /* 130 g/m^2 cotton */
  d.k_stretch = 400.0f;
  d.k_shear = 40.0f;
  d.k_bend = 4.0f;
  d.damping = 0.02f;
  msocl_model *m = NULL;
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK ||
      msocl_model_pin(m, 0, 1) != MSOCL_OK ||
      msocl_model_pin(m, d.nx * (d.ny - 1), 1) != MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

/* The wind at time t: 3 to 9 m/s along +x, veering about the y axis;
 * two incommensurate sines so the gusts never repeat. */
static void gust(double t, msocl_wind *w)
{
  const double speed = 6.0 + 2.0 * sin(2.1 * t) + 1.0 * sin(5.3 * t + 1.0);
  const double turn = 0.44 * sin(0.7 * t) * sin(1.9 * t + 0.5);
  msocl_wind_init(w);
  w->velocity[0] = (float)(speed * cos(turn));
  w->velocity[2] = (float)(speed * sin(turn));
  w->lift = 0.6f;
}

int main(int argc, char **argv)
{
  struct cli_frames a = {32, 512, 12, 4.0, NULL, "flag-frames"};
  int done = 0, rc = cli_frames_parse(PROG, usage, argc, argv, &a, &done);
  if (rc || done)
    return rc;
  int nu = 0;
  msocl_model *m = build(a.n, &nu);
  if (!m)
    return cli_fail(PROG, "building the flag", MSOCL_ERR_BAD_VALUE);
  float dt = 0.0f;
  int per_frame = 0;
  msocl_runtime *rt = NULL;
  msocl_sim *s = NULL;
  if (cli_frames_sim(PROG, m, &a, &rt, &s, &per_frame, &dt))
    return 1;
  const int n = nu * a.n, frames = (int)ceil(a.seconds * a.fps);
  int ntri = 0;
  const int *tri = NULL;
  float *xyz = malloc(3 * (size_t)n * sizeof *xyz);
  msocl_model_triangles(m, &ntri, &tri);
  if (!xyz)
    return cli_fail(PROG, "frames", MSOCL_ERR_NO_MEMORY);
  double t = 0.0, t0 = cli_now();
  for (int f = 0; rc == MSOCL_OK && f <= frames; f++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/flag-%0*d.obj", a.dir,
             cli_frame_digits(frames), f);
    rc = msocl_sim_read_positions(s, xyz);
    if (rc == MSOCL_OK)
      rc = msocl_write_obj(path, n, xyz, NULL, ntri, tri);
    msocl_wind w;
    gust(t, &w);
    if (rc == MSOCL_OK && f < frames)
      rc = msocl_sim_set_wind(s, &w);
    if (rc == MSOCL_OK && f < frames)
      rc = msocl_sim_step(s, per_frame);
    t += per_frame * (double)dt;
  }
  if (rc != MSOCL_OK)
    return cli_fail(PROG, "the run", rc);
  printf("%d x %d flag, %d frames of %d steps (dt %.3g s) in %.2f s; "
         "%s/flag-*.obj\n", nu, a.n, frames + 1, per_frame, (double)dt,
         cli_now() - t0, a.dir);
  free(xyz);
  msocl_sim_destroy(s);
  msocl_runtime_destroy(rt);
  msocl_model_destroy(m);
  return 0;
}

/* A cape on a walking character: a body of capsules (torso, legs that
 * swing) and a sphere (head) walks a circle; the cape's top edge is pinned
 * to its shoulders by targets that follow them, and the cape collides with
 * the moving body and drags in still air. Each frame sets the colliders'
 * poses and the pins' targets for its end and steps to it. Writes the
 * cape and the body as OBJ, one of each a frame.
 *
 *   msocl-character [-n GRID] [-t SECONDS] [-F FRAMES] [-d DEVICE_SPEC]
 *                   [-o DIR]   (-h: all of them)
 */
#include "cli.h"

#include <msocl.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

#define PROG "msocl-character"

static const char usage[] =
    "usage: " PROG " [-n GRID] [-t SECONDS] [-F FRAMES] [-d DEVICE_SPEC]\n"
    "  [-o DIR]\n"
    "A cape pinned to the shoulders of a character of capsules walking a\n"
    "circle at 1 m/s; writes DIR/cape-NNNN.obj and DIR/body-NNNN.obj, one\n"
    "of each a frame.\n"
    "  -n  points across the cape, 4 to 256 (default 20; 2 n down it)\n"
    "  -t  simulated seconds, > 0 to 600 (default 6)\n"
    "  -F  frames a second written, 1 to 240 (default 12)\n"
    "  -d  OpenCL device spec, as MSOCL_DEVICE (default: that variable)\n"
    "  -o  folder for the frames, made if missing (default\n"
    "      character-frames)\n"
    "  -h, --help  this text\n";

/* The walk: a circle of radius R at SPEED, a stride (two steps) every
 * STRIDE seconds, the legs swinging SWING radians either way. */
#define R 1.2
#define SPEED 1.0
#define STRIDE 1.1
#define SWING 0.45

/* The body in its own frame (z forward, y up, on the ground at 0): the
 * torso's axis, the head, the hips and feet, the cape's top edge. */
static const double torso[2][3] = {{0, 0.98, 0}, {0, 1.42, 0}}, torso_r = 0.15;
static const double head[3] = {0, 1.66, 0}, head_r = 0.11;
static const double hip_y = 0.92, foot_y = 0.1, leg_x = 0.09, leg_r = 0.065;
static const double cape_y = 1.44, cape_z = -0.19, cape_w = 0.44,
                    cape_h = 0.9;

/* The body at time t: where its frame stands and its heading, and each
 * leg's swing. */
struct pose {
  double at[3], yaw, swing[2];
};

static void pose_at(double t, struct pose *p)
{
  const double th = SPEED / R * t;
  p->at[0] = R * cos(th);
  p->at[1] = 0.0;
  p->at[2] = R * sin(th);
  p->yaw = -th; /* local +z along the walk's tangent */
  const double s = SWING * sin(2.0 * PI * t / STRIDE);
  p->swing[0] = s;
  p->swing[1] = -s;
}

/* World point of local point l, the leg `leg` (-1: none) swung about its
 * hip. */
static void world(const struct pose *p, int leg, const double l[3],
                  float out[3])
{
  double x = l[0], y = l[1], z = l[2];
  if (leg >= 0) {
    const double a = p->swing[leg], dy = y - hip_y;
    const double ny = hip_y + dy * cos(a) - z * sin(a);
    z = dy * sin(a) + z * cos(a);
    y = ny;
  }
  const double c = cos(p->yaw), s = sin(p->yaw);
  out[0] = (float)(p->at[0] + c * x + s * z);
  out[1] = (float)(p->at[1] + y);
  out[2] = (float)(p->at[2] - s * x + c * z);
}

/* The turn of the body and of a leg as a quaternion (x, y, z, w): the
 * heading about y after the swing about x. */
static void turn(const struct pose *p, int leg, float q[4])
{
  const double h = p->yaw / 2, a = leg >= 0 ? p->swing[leg] / 2 : 0.0;
  /* q_yaw * q_swing, q_yaw = (0, sin h, 0, cos h), q_swing = (sin a, 0,
   * 0, cos a) */
  q[0] = (float)(cos(h) * sin(a));
  q[1] = (float)(sin(h) * cos(a));
  q[2] = (float)(-sin(h) * sin(a));
  q[3] = (float)(cos(h) * cos(a));
}

static void leg_ends(int leg, double a[3], double b[3])
{
  const double x = leg ? leg_x : -leg_x;
  a[0] = b[0] = x;
  a[1] = hip_y;
  b[1] = foot_y;
  a[2] = b[2] = 0.0;
}

/* Collider ids in the order added: torso, head, the two legs. */
enum { TORSO, HEAD, LEG0, NBODY = 4 };

static int add_body(msocl_model *m, const struct pose *p)
{
  float a[3], b[3];
  world(p, -1, torso[0], a);
  world(p, -1, torso[1], b);
  int rc = msocl_model_add_capsule(m, a, b, (float)torso_r, 0.3f);
  world(p, -1, head, a);
  if (rc == MSOCL_OK)
    rc = msocl_model_add_sphere(m, a, (float)head_r, 0.3f);
  for (int leg = 0; rc == MSOCL_OK && leg < 2; leg++) {
    double la[3], lb[3];
    leg_ends(leg, la, lb);
    world(p, leg, la, a);
    world(p, leg, lb, b);
    rc = msocl_model_add_capsule(m, a, b, (float)leg_r, 0.3f);
  }
  return rc;
}

/* The colliders' poses at p (each one's position: a capsule's middle, the
 * sphere's centre) for the end of the next call. */
static int move_body(msocl_sim *s, const struct pose *p)
{
  float at[3], q[4];
  const double mid[3] = {0, (torso[0][1] + torso[1][1]) / 2, 0};
  world(p, -1, mid, at);
  turn(p, -1, q);
  int rc = msocl_sim_set_collider_pose(s, TORSO, at, q);
  world(p, -1, head, at);
  if (rc == MSOCL_OK)
    rc = msocl_sim_set_collider_pose(s, HEAD, at, q);
  for (int leg = 0; rc == MSOCL_OK && leg < 2; leg++) {
    double la[3], lb[3];
    leg_ends(leg, la, lb);
    const double lm[3] = {la[0], (la[1] + lb[1]) / 2, 0};
    world(p, leg, lm, at);
    turn(p, leg, q);
    rc = msocl_sim_set_collider_pose(s, LEG0 + leg, at, q);
  }
  return rc;
}

/* The cape's top edge (its first row of nx points) at p, into xyz. */
static void shoulders(const struct pose *p, int nx, float *xyz)
{
  for (int i = 0; i < nx; i++) {
    const double l[3] = {cape_w * (0.5 - (double)i / (nx - 1)), cape_y,
                         cape_z};
    world(p, -1, l, xyz + 3 * i);
  }
}

/* The cape hanging behind the body at t = 0, its top row pinned. */
static msocl_model *build(int n, int *nx, int *ny, const struct pose *p)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = *nx = n;
  d.ny = *ny = 2 * n;
  const double top[3] = {cape_w / 2, cape_y, cape_z},
               right[3] = {-cape_w / 2, cape_y, cape_z},
               down[3] = {cape_w / 2, cape_y - cape_h, cape_z};
  float o[3], r[3], dn[3];
  world(p, -1, top, o);
  world(p, -1, right, r);
  world(p, -1, down, dn);
  for (int k = 0; k < 3; k++) {
    d.origin[k] = o[k];
    d.u[k] = r[k] - o[k];
    d.v[k] = dn[k] - o[k];
  }
  d.point_mass = 0.12f / (float)(d.nx * d.ny); /* 0.12 kg, a light cape */
  d.k_stretch = 300.0f;
  d.k_shear = 30.0f;
  d.k_bend = 1.0f;
  d.damping = 0.02f;
  msocl_model *m = NULL;
  int rc = msocl_model_cloth_grid(&m, &d);
  for (int i = 0; rc == MSOCL_OK && i < d.nx; i++)
    rc = msocl_model_pin(m, i, 1);
  if (rc == MSOCL_OK)
    rc = add_body(m, p);
  if (rc != MSOCL_OK) {
    msocl_model_destroy(m);
    return NULL;
  }
  return m;
}

/* The body as triangles for the renderer: each capsule a tube with round
 * ends, the head a sphere, as OBJ. */
#define AROUND 12
#define RINGS 5 /* a round end's rings, pole excluded */

static void capsule_obj(FILE *f, int *base, const float a[3],
                        const float b[3], double r)
{
  double ax[3], len = 0, u[3], v[3];
  for (int k = 0; k < 3; k++) {
    ax[k] = b[k] - a[k];
    len += ax[k] * ax[k];
  }
  len = sqrt(len);
  for (int k = 0; k < 3; k++)
    ax[k] = len > 0 ? ax[k] / len : (k == 1);
  /* u, v: across the axis */
  const double h[3] = {fabs(ax[0]) < 0.9 ? 1.0 : 0.0, fabs(ax[0]) < 0.9 ? 0.0 : 1.0, 0.0};
  u[0] = ax[1] * h[2] - ax[2] * h[1];
  u[1] = ax[2] * h[0] - ax[0] * h[2];
  u[2] = ax[0] * h[1] - ax[1] * h[0];
  const double un = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int k = 0; k < 3; k++)
    u[k] /= un;
  v[0] = ax[1] * u[2] - ax[2] * u[1];
  v[1] = ax[2] * u[0] - ax[0] * u[2];
  v[2] = ax[0] * u[1] - ax[1] * u[0];
  /* poles, then 2 RINGS rings of AROUND points from a's end to b's: a
   * hemisphere's RINGS latitudes from its equator up to one step short of
   * its pole, alike at both ends; a sphere's (a = b, whose equators
   * would meet) spread evenly between its poles */
  fprintf(f, "v %.5f %.5f %.5f\n", a[0] - r * ax[0], a[1] - r * ax[1],
          a[2] - r * ax[2]);
  fprintf(f, "v %.5f %.5f %.5f\n", b[0] + r * ax[0], b[1] + r * ax[1],
          b[2] + r * ax[2]);
  for (int ring = 0; ring < 2 * RINGS; ring++) {
    const int far = ring >= RINGS;
    const double al = len == 0 ? -PI / 2 + PI * (ring + 1) / (2 * RINGS + 1)
                      : far  ? PI / 2 * (ring - RINGS) / RINGS
                             : -PI / 2 * (RINGS - 1 - ring) / RINGS;
    const double along = (far ? len : 0.0) + r * sin(al), rad = r * cos(al);
    for (int k = 0; k < AROUND; k++) {
      const double phi = 2 * PI * k / AROUND;
      double p[3];
      for (int c = 0; c < 3; c++)
        p[c] = a[c] + along * ax[c] + rad * (cos(phi) * u[c] + sin(phi) * v[c]);
      fprintf(f, "v %.5f %.5f %.5f\n", p[0], p[1], p[2]);
    }
  }
  const int pa = *base + 1, pb = *base + 2, r0 = *base + 3;
  for (int k = 0; k < AROUND; k++) {
    const int k1 = (k + 1) % AROUND, last = r0 + (2 * RINGS - 1) * AROUND;
    fprintf(f, "f %d %d %d\n", pa, r0 + k1, r0 + k);
    fprintf(f, "f %d %d %d\n", pb, last + k, last + k1);
    for (int ring = 0; ring + 1 < 2 * RINGS; ring++) {
      const int q = r0 + ring * AROUND;
      fprintf(f, "f %d %d %d %d\n", q + k, q + k1, q + AROUND + k1,
              q + AROUND + k);
    }
  }
  *base += 2 + 2 * RINGS * AROUND;
}

static int body_obj(const char *path, const struct pose *p)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return 1;
  int base = 0;
  float a[3], b[3];
  world(p, -1, torso[0], a);
  world(p, -1, torso[1], b);
  capsule_obj(f, &base, a, b, torso_r);
  world(p, -1, head, a);
  capsule_obj(f, &base, a, a, head_r);
  for (int leg = 0; leg < 2; leg++) {
    double la[3], lb[3];
    leg_ends(leg, la, lb);
    world(p, leg, la, a);
    world(p, leg, lb, b);
    capsule_obj(f, &base, a, b, leg_r);
  }
  return fclose(f) != 0;
}

int main(int argc, char **argv)
{
  struct cli_frames a = {20, 256, 12, 6.0, NULL, "character-frames"};
  int done = 0, rc = cli_frames_parse(PROG, usage, argc, argv, &a, &done);
  if (rc || done)
    return rc;
  struct pose p;
  pose_at(0.0, &p);
  int nx = 0, ny = 0;
  msocl_model *m = build(a.n, &nx, &ny, &p);
  if (!m)
    return cli_fail(PROG, "building the scene", MSOCL_ERR_BAD_VALUE);
  float dt = 0.0f;
  int per_frame = 0;
  msocl_runtime *rt = NULL;
  msocl_sim *s = NULL;
  if (cli_frames_sim(PROG, m, &a, &rt, &s, &per_frame, &dt))
    return 1;
  /* still air: the cape drags as it moves through it */
  msocl_wind w;
  msocl_wind_init(&w);
  w.lift = 0.3f;
  if ((rc = msocl_sim_set_wind(s, &w)) != MSOCL_OK)
    return cli_fail(PROG, "air drag", rc);
  const int n = nx * ny, frames = (int)ceil(a.seconds * a.fps);
  int ntri = 0;
  const int *tri = NULL;
  msocl_model_triangles(m, &ntri, &tri);
  float *xyz = malloc(3 * (size_t)n * sizeof *xyz),
        *edge = malloc(3 * (size_t)nx * sizeof *edge);
  if (!xyz || !edge)
    return cli_fail(PROG, "frames", MSOCL_ERR_NO_MEMORY);
  const double t0 = cli_now();
  for (int f = 0; rc == MSOCL_OK && f <= frames; f++) {
    char path[4096];
    const int w = cli_frame_digits(frames);
    snprintf(path, sizeof path, "%s/cape-%0*d.obj", a.dir, w, f);
    rc = msocl_sim_read_positions(s, xyz);
    if (rc == MSOCL_OK)
      rc = msocl_write_obj(path, n, xyz, NULL, ntri, tri);
    snprintf(path, sizeof path, "%s/body-%0*d.obj", a.dir, w, f);
    if (rc == MSOCL_OK && body_obj(path, &p)) { /* a run's failure: 1 */
      fprintf(stderr, "%s: writing %s: %s\n", PROG, path, strerror(errno));
      return 1;
    }
    if (f == frames)
      break;
    /* where the body is at the end of the next frame: colliders and
     * shoulders move there over the frame's steps */
    pose_at((f + 1) / (double)a.fps, &p);
    shoulders(&p, nx, edge);
    if (rc == MSOCL_OK)
      rc = move_body(s, &p);
    if (rc == MSOCL_OK)
      rc = msocl_sim_set_pin_targets(s, nx, NULL, edge);
    if (rc == MSOCL_OK)
      rc = msocl_sim_step(s, per_frame);
  }
  if (rc != MSOCL_OK)
    return cli_fail(PROG, "the run", rc);
  printf("%d x %d cape on a walking body, %d frames of %d steps (dt %.3g s) "
         "in %.2f s; %s/cape-*.obj, %s/body-*.obj\n",
         nx, ny, frames + 1, per_frame, (double)dt, cli_now() - t0, a.dir,
         a.dir);
  free(xyz);
  free(edge);
  msocl_sim_destroy(s);
  msocl_runtime_destroy(rt);
  msocl_model_destroy(m);
  return 0;
}

/* Triangle-mesh colliders: an icosphere and a box read from an OBJ file
 * swept at 5 m/s through a hanging cloth leave no point inside them nor
 * nearer than the thickness (less a stated tolerance) after any call; a
 * static icosphere holds a dropped cloth where the analytic sphere of the
 * same radius does; an open sheet keeps points on their side; bad input
 * refused. Distances are computed here in double from the exact mesh. */
#include "engine/engine.h" /* msocl__mesh_host_grid, msocl__mesh_cull */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define rt scene_rt

/* Points after a call may sit this fraction of the thickness nearer than
 * it: the float rounding of the push and of the interpolated vertices. */
#define TOL 0.02

enum { N = 24, SUB = 4 };
static const double THICK = 0.01;

/* A cloth of N x N points, 1 m a side, hanging in the x-y plane (z = 0)
 * from its pinned top edge (y = 0), and its simulation at the stable dt. */
static msocl_model *hanging(void)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = N;
  d.origin[0] = -0.5f;
  d.u[0] = 1.0f;
  d.v[1] = -1.0f;
  d.v[2] = 0.0f;
  d.point_mass = 0.3f / (N * N);
  d.damping = 2e-3f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  for (int i = 0; i < N; i++)
    ck_assert_int_eq(msocl_model_pin(m, i, 1), MSOCL_OK);
  return m;
}

static msocl_sim *sim_of(const msocl_model *m, float *dt)
{
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, dt), MSOCL_OK);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = *dt;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK, "%s",
                msocl_last_error());
  return s;
}

/* Closest point to p on triangle abc, in double (Ericson 5.1.5). */
static void closest(const double p[3], const double a[3], const double b[3],
                    const double c[3], double q[3])
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; k++) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
#define DOT(u, w) ((u)[0] * (w)[0] + (u)[1] * (w)[1] + (u)[2] * (w)[2])
  const double d1 = DOT(ab, ap), d2 = DOT(ac, ap), d3 = DOT(ab, bp),
               d4 = DOT(ac, bp), d5 = DOT(ab, cp), d6 = DOT(ac, cp);
  double u = 0, w = 0; /* q = a + u ab + w ac */
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6,
               va = d3 * d6 - d5 * d4;
  if (d1 <= 0 && d2 <= 0) {
  } else if (d3 >= 0 && d4 <= d3) {
    u = 1;
  } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    u = d1 / (d1 - d3);
  } else if (d6 >= 0 && d5 <= d6) {
    w = 1;
  } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    w = d2 / (d2 - d6);
  } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    u = 1 - w;
  } else {
    const double den = 1 / (va + vb + vc);
    u = vb * den;
    w = vc * den;
  }
  for (int k = 0; k < 3; k++)
    q[k] = a[k] + u * ab[k] + w * ac[k];
}

/* Signed distance from p to a closed convex mesh wound outward: negative
 * inside (every face's plane has p behind it). */
static double convex_sdf(const double p[3], const float *v, const int *t,
                         int nt)
{
  double best = INFINITY, plane = -INFINITY;
  for (int k = 0; k < nt; k++) {
    double a[3], b[3], c[3], q[3], e1[3], e2[3], n[3];
    for (int i = 0; i < 3; i++) {
      a[i] = v[3 * t[3 * k] + i];
      b[i] = v[3 * t[3 * k + 1] + i];
      c[i] = v[3 * t[3 * k + 2] + i];
      e1[i] = b[i] - a[i];
      e2[i] = c[i] - a[i];
    }
    closest(p, a, b, c, q);
    const double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) +
                          (p[1] - q[1]) * (p[1] - q[1]) +
                          (p[2] - q[2]) * (p[2] - q[2]));
    best = fmin(best, d);
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double ln = sqrt(DOT(n, n));
    const double h = ((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] +
                      (p[2] - a[2]) * n[2]) / ln;
    plane = fmax(plane, h);
  }
  return plane < 0 ? plane : best;
}

/* The mesh's vertices moved by dz along z. */
static void shifted(const float *v, int nv, double dz, float *out)
{
  for (int i = 0; i < nv; i++) {
    out[3 * i] = v[3 * i];
    out[3 * i + 1] = v[3 * i + 1];
    out[3 * i + 2] = (float)(v[3 * i + 2] + dz);
  }
}

/* Sweeps mesh 0 of m (vertices v, triangles t, convex and wound outward)
 * along +z at `speed` for `travel` metres, SUB steps a call, checking
 * after every call that no free point is inside it or nearer than the
 * thickness less TOL of it. Returns the least gap seen over the
 * thickness, and how many points touched it. */
static double sweep(msocl_model *m, const float *v, int nv, const int *t,
                    int nt, double speed, double travel, int *touched)
{
  float dt;
  msocl_sim *s = sim_of(m, &dt);
  const int calls = (int)ceil(travel / (speed * dt * SUB));
  float *now = malloc(3 * (size_t)nv * sizeof *now);
  float *p = malloc(3 * N * N * sizeof *p);
  double least = INFINITY;
  *touched = 0;
  for (int c = 1; c <= calls; c++) {
    const double dz = speed * dt * SUB * c;
    shifted(v, nv, dz, now);
    ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, now),
                     MSOCL_OK);
    ck_assert_msg(msocl_sim_step(s, SUB) == MSOCL_OK, "%s",
                  msocl_last_error());
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    for (int i = N; i < N * N; i++) {
      const double q[3] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
      const double g = convex_sdf(q, now, t, nt) / THICK;
      ck_assert_msg(g >= 1.0 - TOL,
                    "call %d (mesh at dz %.4f m): point %d at (%g, %g, %g) "
                    "is %.4f thicknesses from the mesh", c, dz, i, q[0],
                    q[1], q[2], g);
      least = fmin(least, g);
      *touched += g < 1.0 + TOL && c == calls;
    }
  }
  free(now);
  free(p);
  msocl_sim_destroy(s);
  return least;
}

START_TEST(icosphere_through_cloth)
{
  float *v;
  int *t, nt;
  const double c[3] = {0.0, -0.55, -0.3};
  const int nv = scene_icosphere(3, 0.2, c, &v, &t, &nt);
  msocl_model *m = hanging();
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, nv, t, nt,
                                                 (float)THICK, 0.3f),
                   MSOCL_OK);
  int touched;
  const double least = sweep(m, v, nv, t, nt, 5.0, 0.5, &touched);
  ck_assert_msg(touched > 20, "only %d points against the sphere", touched);
  printf("icosphere at 5 m/s: least gap %.4f thicknesses, %d touching\n",
         least, touched);
  msocl_model_destroy(m);
  free(v);
  free(t);
}
END_TEST

/* A box of half extents (0.25, 0.2, 0.05) about (0, -0.5, -0.2), written
 * as an OBJ of quads, its faces wound inward (the collider finds which
 * side is out from the sign of the volume). */
START_TEST(obj_box_through_cloth)
{
  static const float v[8 * 3] = {-0.25f, -0.7f, -0.25f, 0.25f, -0.7f, -0.25f,
                                 0.25f,  -0.3f, -0.25f, -0.25f, -0.3f, -0.25f,
                                 -0.25f, -0.7f, -0.15f, 0.25f, -0.7f, -0.15f,
                                 0.25f,  -0.3f, -0.15f, -0.25f, -0.3f, -0.15f};
  static const int quad[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                 {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};
  char path[] = "/tmp/check_mesh_collider_XXXXXX";
  const int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  FILE *f = fdopen(fd, "w");
  fprintf(f, "# a box\n");
  for (int i = 0; i < 8; i++)
    fprintf(f, "v %.9g %.9g %.9g\n", v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  for (int q = 0; q < 6; q++)
    fprintf(f, "f %d %d %d %d\n", quad[q][0] + 1, quad[q][1] + 1,
            quad[q][2] + 1, quad[q][3] + 1);
  fclose(f);
  msocl_model *m = hanging();
  ck_assert_msg(msocl_model_add_mesh_collider_obj(m, path, (float)THICK,
                                                  0.5f) == MSOCL_OK,
                "%s", msocl_last_error());
  unlink(path);
  /* the same triangles, fanned as the reader does, wound outward for the
   * test's signed distance */
  int t[12 * 3];
  for (int q = 0; q < 6; q++) {
    const int a = quad[q][0], b = quad[q][1], c = quad[q][2], d = quad[q][3];
    const int two[6] = {a, c, b, a, d, c};
    memcpy(t + 6 * q, two, sizeof two);
  }
  int touched;
  const double least = sweep(m, v, 8, t, 12, 5.0, 0.45, &touched);
  ck_assert_msg(touched > 20, "only %d points against the box", touched);
  printf("OBJ box at 5 m/s: least gap %.4f thicknesses, %d touching\n", least,
         touched);
  msocl_model_destroy(m);
}
END_TEST

/* A free cloth of 16 x 16 points, 0.8 m a side, level at y = 0.32, onto
 * a sphere of radius 0.3 about the origin: the icosphere of circumradius
 * R with thickness h against the analytic sphere of radius R + h, both
 * without friction, for 0.25 s. */
static void drop(const msocl_model *base, float dt, int steps, float *p)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, rt, base, &o) == MSOCL_OK, "%s",
                msocl_last_error());
  ck_assert_msg(msocl_sim_step(s, steps) == MSOCL_OK, "%s",
                msocl_last_error());
  ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
  msocl_sim_destroy(s);
}

static msocl_model *sheet(void)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 16;
  d.origin[0] = -0.4f;
  d.origin[1] = 0.32f;
  d.origin[2] = -0.4f;
  d.u[0] = 0.8f;
  d.v[2] = 0.8f;
  d.point_mass = 0.2f / 256;
  d.damping = 2e-3f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  return m;
}

START_TEST(icosphere_like_sphere)
{
  const double R = 0.3, h = 0.01, c[3] = {0, 0, 0};
  float *v;
  int *t, nt;
  const int nv = scene_icosphere(4, R, c, &v, &t, &nt);
  msocl_model *a = sheet(), *b = sheet();
  ck_assert_int_eq(msocl_model_add_mesh_collider(a, v, nv, t, nt, (float)h,
                                                 0.0f), MSOCL_OK);
  const float centre[3] = {0, 0, 0};
  ck_assert_int_eq(msocl_model_add_sphere(b, centre, (float)(R + h), 0.0f),
                   MSOCL_OK);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(a, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  const int steps = (int)(0.25 / dt);
  float pa[3 * 256], pb[3 * 256];
  drop(a, dt, steps, pa);
  drop(b, dt, steps, pb);
  /* level 4's faces sag below the circumsphere by at most
   * R (1 - cos 3 deg) < 0.42 mm: resting points sit that much lower */
  const double sag = R * (1 - cos(3.0 * 3.14159265358979 / 180));
  double worst = 0, held = 0, rmin_a = INFINITY, rmin_b = INFINITY;
  int nheld = 0;
  for (int i = 0; i < 256; i++) {
    double ra = 0, rb = 0, d = 0;
    for (int k = 0; k < 3; k++) {
      ra += (double)pa[3 * i + k] * pa[3 * i + k];
      rb += (double)pb[3 * i + k] * pb[3 * i + k];
      d += ((double)pa[3 * i + k] - pb[3 * i + k]) *
           ((double)pa[3 * i + k] - pb[3 * i + k]);
    }
    rmin_a = fmin(rmin_a, sqrt(ra));
    rmin_b = fmin(rmin_b, sqrt(rb));
    worst = fmax(worst, sqrt(d));
    if (sqrt(rb) < R + h + 1e-3) { /* resting on the analytic sphere */
      held = fmax(held, sqrt(d));
      nheld++;
    }
  }
  printf("icosphere vs sphere after %d steps: max |dp| %.5f m (%d resting "
         "points: %.5f m), least radius %.5f vs %.5f m (sag %.5f)\n", steps,
         worst, nheld, held, rmin_a, rmin_b, sag);
  ck_assert_msg(rmin_b > R + h - 1e-4, "sphere: %g", rmin_b);
  ck_assert_msg(rmin_a > R + h - sag - 1e-4 && rmin_a < R + h + 1e-3,
                "icosphere: least radius %g", rmin_a);
  /* the facets' 0.4 mm sag, and their edges' tangential kicks, change
   * the drape a little: the points resting on the sphere stay within
   * 4 mm, the swinging rest within 1 cm, of the analytic run (measured:
   * 2.1 and 6.7 mm) */
  ck_assert_msg(nheld > 8 && held < 4e-3,
                "%d resting points up to %g m from the sphere's", nheld, held);
  ck_assert_msg(worst < 1e-2, "icosphere and sphere %g m apart", worst);
  msocl_model_destroy(a);
  msocl_model_destroy(b);
  free(v);
  free(t);
}
END_TEST

/* An open mesh: a flat square sheet 0.6 m across, at z = -0.2, swept
 * along +z through the hanging cloth: every free point over the sheet
 * (away from its rim, round which points may pass) stays on the side it
 * started, the thickness in front of it. */
START_TEST(open_sheet_keeps_side)
{
  const float v[4 * 3] = {-0.3f, -0.8f, -0.2f, 0.3f, -0.8f, -0.2f,
                          0.3f,  -0.2f, -0.2f, -0.3f, -0.2f, -0.2f};
  const int t[2 * 3] = {0, 1, 2, 0, 2, 3};
  msocl_model *m = hanging();
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 4, t, 2, (float)THICK,
                                                 0.5f), MSOCL_OK);
  float dt;
  msocl_sim *s = sim_of(m, &dt);
  const double speed = 5.0;
  const int calls = (int)ceil(0.4 / (speed * dt * SUB));
  float now[12], p[3 * N * N];
  int over = 0;
  /* each point's last check: in front of the sheet, over its inside */
  unsigned char front[N * N], inside[N * N];
  memset(front, 1, sizeof front);
  memset(inside, 0, sizeof inside);
  for (int c = 1; c <= calls; c++) {
    const double dz = speed * dt * SUB * c;
    shifted(v, 4, dz, now);
    ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, now),
                     MSOCL_OK);
    ck_assert_msg(msocl_sim_step(s, SUB) == MSOCL_OK, "%s",
                  msocl_last_error());
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    for (int i = N; i < N * N; i++) {
      const double x = p[3 * i], y = p[3 * i + 1], z = p[3 * i + 2];
      /* (2 thicknesses in from the rim: a point may go round it) */
      const int in = fabs(x) < 0.28 && y > -0.78 && y < -0.22;
      if (in && inside[i] && front[i]) {
        ck_assert_msg(z >= -0.2 + dz + THICK * (1 - TOL),
                      "call %d: point %d at (%g, %g, %g) passed the sheet "
                      "at z %g", c, i, x, y, z, -0.2 + dz);
        over += c == calls;
      }
      inside[i] = (unsigned char)in;
      front[i] = z > -0.2 + dz;
    }
  }
  ck_assert_int_gt(over, 50);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A static mesh acts on every step too; disabled, it does not; in
 * BUFFER (points in index order) as in GRID. */
/* m under gravity over a floor mesh at y = -0.6 (2 m a side, normal +y,
 * friction 1) `thick` thick, simulated in `layout` at the stable dt. */
static msocl_sim *over_floor(msocl_model *m, float thick,
                             msocl_layout layout, float *dt)
{
  const float v[4 * 3] = {-1, -0.6f, -1, 1, -0.6f, -1, 1, -0.6f, 1, -1, -0.6f, 1};
  const int t[2 * 3] = {0, 2, 1, 0, 3, 2};
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 4, t, 2, thick, 1.0f),
                   MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_gravity(m, 0, -9.81f, 0), MSOCL_OK);
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, dt), MSOCL_OK);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = *dt;
  o.tuning.layout = layout;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, rt, m, &o) == MSOCL_OK, "%s",
                msocl_last_error());
  return s;
}

static void floor_run(msocl_layout layout)
{
  msocl_model *m = sheet();
  float dt;
  msocl_sim *s = over_floor(m, 0.02f, layout, &dt);
  /* the sheet falls 0.92 m onto the floor mesh at y = -0.6 */
  float p[3 * 256];
  for (int c = 0; c < 60; c++)
    ck_assert_int_eq(msocl_sim_step(s, (int)(0.01 / dt) + 1), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
  for (int i = 0; i < 256; i++)
    ck_assert_msg(fabs(p[3 * i + 1] - (-0.58)) < 2e-3, "point %d at y %g", i,
                  p[3 * i + 1]);
  ck_assert_int_eq(msocl_sim_enable_mesh_collider(s, 0, 0), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, (int)(0.2 / dt)), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
  ck_assert_msg(p[1] < -0.7, "disabled, the floor still held: y %g", p[1]);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}

START_TEST(static_and_disabled)
{
  floor_run(MSOCL_LAYOUT_GRID);
}
END_TEST

START_TEST(static_in_buffer)
{
  floor_run(MSOCL_LAYOUT_BUFFER);
}
END_TEST

/* A jello cube (8^3 points, layers and rows: the CPU search's runs over
 * z and y) dropped onto the floor mesh bounces on it, held a thickness
 * above it after every call, GRID as BUFFER, bitwise. */
static void lattice_drop(msocl_layout layout, float *p)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.origin[0] = d.origin[2] = -0.07f;
  d.origin[1] = -0.55f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_lattice(&m, &d), MSOCL_OK);
  float dt;
  msocl_sim *s = over_floor(m, (float)THICK, layout, &dt);
  int touched = 0;
  for (int c = 0; c < 30; c++) {
    ck_assert_int_eq(msocl_sim_step(s, (int)(0.01 / dt) + 1), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    for (int i = 0; i < 512; i++) {
      const double y = p[3 * i + 1], floor = -0.6 + THICK;
      ck_assert_msg(y >= floor - TOL * THICK, "call %d: point %d at y %g",
                    c, i, y);
      touched += y < floor + TOL * THICK;
    }
  }
  ck_assert_int_gt(touched, 64); /* the bottom layer, more than once */
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}

START_TEST(lattice_on_floor)
{
  float g[3 * 512], b[3 * 512];
  lattice_drop(MSOCL_LAYOUT_GRID, g);
  lattice_drop(MSOCL_LAYOUT_BUFFER, b);
  ck_assert_msg(memcmp(g, b, sizeof g) == 0, "GRID and BUFFER differ");
}
END_TEST

/* The icosphere of `level` swept through the hanging cloth at `speed`
 * for `calls` calls, every call's positions into out (calls * 3 N N). */
static void swept_run(int level, double speed, int calls, float *out)
{
  float *v, *now;
  int *t, nt;
  const double c[3] = {0.0, -0.55, -0.3};
  const int nv = scene_icosphere(level, 0.2, c, &v, &t, &nt);
  msocl_model *m = hanging();
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, nv, t, nt,
                                                 (float)THICK, 0.3f),
                   MSOCL_OK);
  float dt;
  msocl_sim *s = sim_of(m, &dt);
  now = malloc(3 * (size_t)nv * sizeof *now);
  for (int k = 1; k <= calls; k++) {
    shifted(v, nv, speed * dt * SUB * k, now);
    ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, now),
                     MSOCL_OK);
    ck_assert_msg(msocl_sim_step(s, SUB) == MSOCL_OK, "%s",
                  msocl_last_error());
    ck_assert_int_eq(
        msocl_sim_read_positions(s, out + (size_t)(k - 1) * 3 * N * N),
        MSOCL_OK);
  }
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  free(now);
  free(v);
  free(t);
}

/* The grid built on the device holds the host's reference lists (mode 2
 * fails a call where they differ) and gives bitwise the host build's
 * cloth, call after call of a moving mesh: at 5 m/s, and a
 * finer sphere at 40 m/s, whose long reach puts dozens of triangles in a
 * cell (the device's sort past its short lists). */
START_TEST(device_grid_is_host_grid)
{
  static const struct { int level; double speed; int calls; } run[2] = {
      {3, 5.0, 60}, {4, 40.0, 12}};
  for (int r = 0; r < 2; r++) {
    const size_t n = (size_t)run[r].calls * 3 * N * N;
    float *host = malloc(n * sizeof *host), *dev = malloc(n * sizeof *dev);
    msocl__mesh_host_grid(1);
    swept_run(run[r].level, run[r].speed, run[r].calls, host);
    msocl__mesh_host_grid(2);
    swept_run(run[r].level, run[r].speed, run[r].calls, dev);
    msocl__mesh_host_grid(-1);
    size_t moved = 0;
    for (size_t q = 0; q < n; q++) {
      ck_assert_msg(memcmp(host + q, dev + q, sizeof *host) == 0,
                    "run %d: call %zu, point %zu, axis %zu: host grid %.9g, "
                    "device grid %.9g", r, q / (3 * N * N) + 1,
                    q % (3 * N * N) / 3, q % 3, host[q], dev[q]);
      moved += q >= n - 3 * N * N && q % 3 == 2 && fabsf(dev[q]) > 1e-3f;
    }
    /* the sphere reached the cloth: some points pushed off z = 0 */
    ck_assert_msg(moved > 20, "run %d: only %zu points pushed", r, moved);
    free(host);
    free(dev);
  }
}
END_TEST

/* The GPUs' search, a work-item a point finding its own cell, gives
 * bitwise the CPUs' (runs of points tested 8 at a time), on a moving
 * culled grid and on a static one. */
START_TEST(per_point_is_rows)
{
  const int calls = 60;
  const size_t n = (size_t)calls * 3 * N * N;
  float *rows = malloc(n * sizeof *rows), *each = malloc(n * sizeof *each);
  swept_run(3, 5.0, calls, rows);
  msocl__mesh_per_point(1);
  swept_run(3, 5.0, calls, each);
  msocl__mesh_per_point(0);
  size_t moved = 0;
  for (size_t q = 0; q < n; q++) {
    ck_assert_msg(memcmp(rows + q, each + q, sizeof *rows) == 0,
                  "call %zu, point %zu, axis %zu: runs %.9g, per point %.9g",
                  q / (3 * N * N) + 1, q % (3 * N * N) / 3, q % 3, rows[q],
                  each[q]);
    moved += q >= n - 3 * N * N && q % 3 == 2 && fabsf(rows[q]) > 1e-3f;
  }
  ck_assert_msg(moved > 20, "only %zu points pushed", moved);
  float g[3 * 512], b[3 * 512];
  lattice_drop(MSOCL_LAYOUT_GRID, g);
  msocl__mesh_per_point(1);
  lattice_drop(MSOCL_LAYOUT_GRID, b);
  msocl__mesh_per_point(0);
  ck_assert_msg(memcmp(g, b, sizeof g) == 0, "the lattice differs");
  free(rows);
  free(each);
}
END_TEST

/* The sheet thrown down at 3 m/s onto a floor mesh 2 m across at y = 0
 * (most of it outside the sheet's bounds, all of it below them) that
 * moves 1 mm a call along x, for `calls` calls of SUB steps; each call's
 * lowest free point into low, the positions at the end into p. */
static void thrown(int cull, int calls, float *low, float *p)
{
  const float v[4 * 3] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
  const int t[2 * 3] = {0, 2, 1, 0, 3, 2}; /* normal +y */
  msocl_model *m = sheet();
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 4, t, 2, (float)THICK,
                                                 0.5f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_gravity(m, 0, -9.81f, 0), MSOCL_OK);
  msocl__mesh_cull(cull);
  float dt;
  msocl_sim *s = sim_of(m, &dt);
  msocl__mesh_cull(-1);
  float vel[3 * 256];
  for (int i = 0; i < 256; i++)
    vel[3 * i] = 0, vel[3 * i + 1] = -3.0f, vel[3 * i + 2] = 0;
  ck_assert_int_eq(msocl_sim_write_velocities(s, vel), MSOCL_OK);
  float now[12];
  for (int c = 1; c <= calls; c++) {
    shifted(v, 4, 0.0, now);
    for (int k = 0; k < 4; k++)
      now[3 * k] += 1e-3f * (float)c;
    ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, now),
                     MSOCL_OK);
    ck_assert_msg(msocl_sim_step(s, SUB) == MSOCL_OK, "%s",
                  msocl_last_error());
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    low[c - 1] = INFINITY;
    for (int i = 0; i < 256; i++)
      low[c - 1] = fminf(low[c - 1], p[3 * i + 1]);
  }
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}

/* A moving mesh's grid culled to the cloth's box at each call's start
 * (the hardest the library may cull) misses nothing: the thrown sheet
 * reaches the floor within a call, its points leaving that box, and
 * stops on it a thickness up, as with the grid never culled. */
START_TEST(culled_grid_misses_nothing)
{
  enum { CALLS = 80 };
  float low[2][CALLS], p[2][3 * 256];
  thrown(1, CALLS, low[0], p[0]);
  thrown(0, CALLS, low[1], p[1]);
  for (int c = 0; c < CALLS; c++)
    ck_assert_msg(low[0][c] >= THICK * (1 - TOL),
                  "culled: call %d, a point at y %g, through the floor", c + 1,
                  (double)low[0][c]);
  double worst = 0;
  int resting = 0;
  for (int i = 0; i < 256; i++) {
    worst = fmax(worst, fabs((double)p[0][3 * i + 1] - p[1][3 * i + 1]));
    resting += fabs(p[0][3 * i + 1] - THICK) < 2e-3;
  }
  ck_assert_msg(resting > 200, "only %d points resting on the floor", resting);
  ck_assert_msg(worst < 1e-4, "culled and unculled grids %g m apart", worst);
  ck_assert_msg(low[0][0] > 0.1, "the sheet started on the floor: %g",
                (double)low[0][0]);
  printf("culled grid: %d of 256 points resting, %.3g m from the unculled "
         "run's\n", resting, worst);
}
END_TEST

START_TEST(bad_input)
{
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const int t[3] = {0, 1, 2}, far[3] = {0, 1, 3}, flat[3] = {0, 1, 1};
  msocl_model *m = sheet();
  ck_assert_int_eq(msocl_model_add_mesh_collider(NULL, v, 3, t, 1, 0.01f, 0),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, NULL, 3, t, 1, 0.01f, 0),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, NULL, 1, 0.01f, 0),
                   MSOCL_ERR_NULL_HANDLE);
  float nan[9];
  memcpy(nan, v, sizeof v);
  nan[4] = NAN;
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, nan, 3, t, 1, 0.01f, 0),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "vertex 1"));
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, far, 1, 0.01f, 0),
                   MSOCL_ERR_BAD_INDEX);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "vertex 3"));
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, flat, 1, 0.01f, 0),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, t, 1, 0.0f, 0),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, t, 1, INFINITY, 0),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, t, 1, 0.01f, 1.5f),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_model_add_mesh_collider_obj(m, NULL, 0.01f, 0),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_model_add_mesh_collider_obj(
                       m, "/nonexistent/mesh.obj", 0.01f, 0),
                   MSOCL_ERR_IO);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, t, 1, 0.01f, 0),
                   MSOCL_OK);
  /* a split refused at create */
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-4f;
  msocl_sim *s = NULL;
  char spec[64];
  if (scene_cpu_spec(spec, sizeof spec, 2) >= 2) {
    msocl_runtime *two = NULL;
    ck_assert_int_eq(msocl_runtime_create(&two, spec), MSOCL_OK);
    o.tuning.ndevices = 2;
    ck_assert_int_eq(msocl_sim_create(&s, two, m, &o), MSOCL_ERR_BAD_VALUE);
    ck_assert_ptr_null(s);
    ck_assert_ptr_nonnull(strstr(msocl_last_error(), "split"));
    o.tuning.ndevices = 0;
    msocl_runtime_destroy(two);
  }
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 3, t, 1, 0.01f, 0),
                   MSOCL_ERR_INVALID_ARG);
  ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 1, v),
                   MSOCL_ERR_BAD_INDEX);
  ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, -1, v),
                   MSOCL_ERR_BAD_INDEX);
  ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, NULL),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(NULL, 0, v),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, nan),
                   MSOCL_ERR_NOT_FINITE);
  float huge[sizeof v / sizeof v[0]];
  memcpy(huge, v, sizeof v);
  huge[4] = 1e30f;
  ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, huge),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "vertex 1"));
  ck_assert_int_eq(msocl_sim_enable_mesh_collider(s, 2, 1),
                   MSOCL_ERR_BAD_INDEX);
  ck_assert_int_eq(msocl_sim_enable_mesh_collider(NULL, 0, 1),
                   MSOCL_ERR_NULL_HANDLE);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A closed cube mesh (top face at y = -0.05) lifted 5 cm over one call,
 * its first move after calls that left it still, carries the 16 x 16
 * cloth resting on it: every point over the top face ends at least the
 * thickness, less TOL of it, above the face. (That call used to collide
 * with the resting cube's triangles: the points ended up to 3 cm inside.) */
static void cube(float *v, float cy)
{
  for (int i = 0; i < 8; i++) {
    v[3 * i] = 0.5f + 0.2f * (i & 1 ? 1.0f : -1.0f);
    v[3 * i + 1] = cy + 0.2f * (i & 2 ? 1.0f : -1.0f);
    v[3 * i + 2] = 0.5f + 0.2f * (i & 4 ? 1.0f : -1.0f);
  }
}

START_TEST(first_move_carries)
{
  /* outward: x (0-1), y (0-2), z (0-4) each low or high */
  static const int t[36] = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5,
                            0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3,
                            0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 16;
  msocl_model *m = NULL;
  float v[24];
  cube(v, -0.25f);
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_mesh_collider(m, v, 8, t, 12,
                                                 (float)THICK, 0.5f),
                   MSOCL_OK);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 5e-4f;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 1000), MSOCL_OK);
  cube(v, -0.20f);
  ck_assert_int_eq(msocl_sim_set_mesh_collider_vertices(s, 0, v), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
  float x[3 * 256];
  ck_assert_int_eq(msocl_sim_read_positions(s, x), MSOCL_OK);
  int over = 0;
  for (int i = 0; i < 256; i++)
    if (fabsf(x[3 * i] - 0.5f) < 0.15f && fabsf(x[3 * i + 2] - 0.5f) < 0.15f) {
      over++;
      ck_assert_msg(x[3 * i + 1] >= (1.0 - TOL) * THICK,
                    "point %d at y = %g, under the lifted top face's %g",
                    i, x[3 * i + 1], THICK);
    }
  ck_assert_int_ge(over, 16);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_mesh_collider");
  Suite *su = suite_create("mesh_collider");
  TCase *tc = tcase_create("mesh_collider");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, bad_input);
  tcase_add_test(tc, icosphere_through_cloth);
  tcase_add_test(tc, obj_box_through_cloth);
  tcase_add_test(tc, icosphere_like_sphere);
  tcase_add_test(tc, open_sheet_keeps_side);
  tcase_add_test(tc, static_and_disabled);
  tcase_add_test(tc, static_in_buffer);
  tcase_add_test(tc, lattice_on_floor);
  tcase_add_test(tc, per_point_is_rows);
  tcase_add_test(tc, device_grid_is_host_grid);
  tcase_add_test(tc, culled_grid_misses_nothing);
  tcase_add_test(tc, first_move_carries);
  suite_add_tcase(su, tc);
  return scene_run(su);
}

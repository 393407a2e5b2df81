/* The lattice and solid builders and the PLY writer: counts against hand
 * formulas, rest lengths, degrees, outward closed surfaces, rejected input,
 * files read back. No OpenCL. */
#include <check.h>
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <sys/resource.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "internal.h"

#include "expect.h"

static const double SQRT2 = 1.41421356237309505, SQRT3 = 1.73205080756887729;

/* ------------------------------------------------------------- geometry */

static double dist(const msocl_model *m, int i, int j) {
  double s = 0;
  for (int c = 0; c < 3; c++) {
    double d = (double)m->pos[3 * i + c] - m->pos[3 * j + c];
    s += d * d;
  }
  return sqrt(s);
}

/* (b - a) x (c - a) of triangle t. */
static void tri_normal(const msocl_model *m, int t, double n[3]) {
  const float *a = m->pos + 3 * m->tri[3 * t], *b = m->pos + 3 * m->tri[3 * t + 1],
              *c = m->pos + 3 * m->tri[3 * t + 2];
  double u[3], v[3];
  for (int k = 0; k < 3; k++) {
    u[k] = (double)b[k] - a[k];
    v[k] = (double)c[k] - a[k];
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
}

/* Every triangle's normal points away from `centre` (from the triangle's
 * centroid). */
static void check_outward(const msocl_model *m, const double centre[3]) {
  for (int t = 0; t < m->nt; t++) {
    double n[3], dot = 0;
    tri_normal(m, t, n);
    for (int c = 0; c < 3; c++) {
      double g = ((double)m->pos[3 * m->tri[3 * t] + c] +
                  m->pos[3 * m->tri[3 * t + 1] + c] +
                  m->pos[3 * m->tri[3 * t + 2] + c]) / 3.0;
      dot += n[c] * (g - centre[c]);
    }
    ck_assert_msg(dot > 0, "triangle %d (%d %d %d) faces inward", t,
                  m->tri[3 * t], m->tri[3 * t + 1], m->tri[3 * t + 2]);
  }
}

/* Closed and consistently wound: every directed edge once, and its
 * reverse once (an n^2 table; the meshes here are small). */
static void check_closed(const msocl_model *m) {
  int n = m->n;
  unsigned char *used = calloc((size_t)n * n, 1);
  ck_assert_ptr_nonnull(used);
  for (int i = 0; i < 3 * m->nt; i++) {
    int a = m->tri[i], b = m->tri[i % 3 == 2 ? i - 2 : i + 1];
    ck_assert_msg(!used[(size_t)a * n + b], "edge %d -> %d used twice", a, b);
    used[(size_t)a * n + b] = 1;
  }
  for (int i = 0; i < 3 * m->nt; i++) {
    int a = m->tri[i], b = m->tri[i % 3 == 2 ? i - 2 : i + 1];
    ck_assert_msg(used[(size_t)b * n + a], "edge %d -> %d has no twin", a, b);
  }
  free(used);
}

/* Divergence theorem: V = 1/6 sum a . (b x c) over outward triangles. */
static double volume(const msocl_model *m) {
  double v = 0;
  for (int t = 0; t < m->nt; t++) {
    const float *a = m->pos + 3 * m->tri[3 * t],
                *b = m->pos + 3 * m->tri[3 * t + 1],
                *c = m->pos + 3 * m->tri[3 * t + 2];
    v += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
         (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
         (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
  }
  return v / 6.0;
}

static int max_degree(const msocl_model *m) {
  int d = -1;
  OK(msocl_model_max_degree(m, &d));
  return d;
}

/* Gershgorin's bound on the fastest mode, max_i sqrt(sum_j 4 k_ij / m_i). */
static double omega_bound(const msocl_model *m) {
  double *sum = calloc((size_t)m->n, sizeof *sum), w2 = 0;
  ck_assert_ptr_nonnull(sum);
  for (int s = 0; s < m->ns; s++) {
    sum[m->ij[2 * s]] += 4.0 * m->k[s];
    sum[m->ij[2 * s + 1]] += 4.0 * m->k[s];
  }
  for (int i = 0; i < m->n; i++)
    if (sum[i] / m->mass[i] > w2) w2 = sum[i] / m->mass[i];
  free(sum);
  return sqrt(w2);
}

/* --------------------------------------------------------------- lattice */

static msocl_lattice_desc lattice(int nx, int ny, int nz) {
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.nx = nx;
  d.ny = ny;
  d.nz = nz;
  return d;
}

START_TEST(lattice_defaults) {
  msocl_lattice_desc d;
  msocl_model *m;
  double lo = INFINITY, hi = -INFINITY;

  memset(&d, 0x55, sizeof d);
  msocl_lattice_desc_init(&d);
  msocl_lattice_desc_init(NULL);
  ck_assert_int_eq(d.nx, 8);
  ck_assert_int_eq(d.ny, 8);
  ck_assert_int_eq(d.nz, 8);
  NEAR(d.spacing, 0.02, 1e-9);
  NEAR(d.point_mass, 0.002, 1e-9);
  NEAR(d.k_shear_body, 0, 0);
  ck_assert(d.k_structural > d.k_shear_face && d.k_shear_face > d.k_bend &&
            d.k_bend > 0 && d.damping > 0);

  OK(msocl_model_lattice(&m, &d));
  ck_assert_int_eq(m->n, 512);
  ck_assert_int_eq(max_degree(m), 24);
  for (int i = 0; i < m->n; i++) {
    if (m->pos[3 * i + 1] < lo) lo = m->pos[3 * i + 1];
    if (m->pos[3 * i + 1] > hi) hi = m->pos[3 * i + 1];
  }
  NEAR(lo, 0.1, 1e-6); /* bottom 10 cm above y = 0 */
  NEAR(hi - lo, 0.14, 1e-6);
  NEAR(m->pos[0] + m->pos[3 * 511], 0, 1e-6); /* centred on x = 0 */
  NEAR(m->pos[2] + m->pos[3 * 511 + 2], 0, 1e-6); /* and z = 0 */
  /* Stable at dt = 1e-4 s with room to spare. */
  ck_assert_msg(1e-4 * omega_bound(m) < 0.5, "dt w = %g", 1e-4 * omega_bound(m));
  OK(msocl_model_validate(m));
  msocl_model_destroy(m);
}
END_TEST

START_TEST(lattice_rejected) {
  msocl_lattice_desc d = lattice(3, 3, 3);
  msocl_model *m = (msocl_model *)&d; /* must come back NULL */

  EXPECT(msocl_model_lattice(NULL, &d), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_lattice(&m, NULL), MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_eq(m, NULL);

#define REJECT(field, value, code)                                             \
  do {                                                                         \
    d = lattice(3, 3, 3);                                                      \
    d.field = (value);                                                         \
    m = (msocl_model *)&d;                                                     \
    EXPECT(msocl_model_lattice(&m, &d), code);                                 \
    ck_assert_ptr_eq(m, NULL);                                                 \
  } while (0)
  REJECT(nx, 1, MSOCL_ERR_BAD_COUNT);
  REJECT(ny, 0, MSOCL_ERR_BAD_COUNT);
  REJECT(nz, -4, MSOCL_ERR_BAD_COUNT);
  REJECT(nx, INT_MAX, MSOCL_ERR_TOO_MANY);
  d = lattice(INT_MAX, INT_MAX, INT_MAX); /* no long long overflow either */
  EXPECT(msocl_model_lattice(&m, &d), MSOCL_ERR_TOO_MANY);
  d = lattice(600, 600, 600); /* 2.16e8 points fit, 2.6e9 springs not */
  EXPECT(msocl_model_lattice(&m, &d), MSOCL_ERR_TOO_MANY);
  REJECT(origin[2], NAN, MSOCL_ERR_NOT_FINITE);
  SAYS("origin[2]");
  REJECT(spacing, INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(point_mass, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(k_structural, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(k_shear_face, INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(k_shear_body, -INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(k_bend, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(damping, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(spacing, 0, MSOCL_ERR_BAD_VALUE);
  REJECT(spacing, -0.01f, MSOCL_ERR_BAD_VALUE);
  SAYS("spacing");
  REJECT(point_mass, 0, MSOCL_ERR_BAD_MASS);
  REJECT(point_mass, -1, MSOCL_ERR_BAD_MASS);
  REJECT(k_structural, -1, MSOCL_ERR_BAD_VALUE);
  SAYS("k_structural -1");
  REJECT(k_shear_face, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(k_shear_body, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(k_bend, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(damping, -1, MSOCL_ERR_BAD_VALUE);
  /* Corners past the coordinate limit of msocl.h (1e18), or a float's
   * range: the model's own point check, at the first point past 1e18. */
  REJECT(spacing, 3e38f, MSOCL_ERR_BAD_VALUE);
  REJECT(spacing, 1e18f, MSOCL_ERR_BAD_VALUE);
  SAYS("point 2: |x| = 2e+18 exceeds 1e+18");
#undef REJECT
}
END_TEST

/* Hand counts of each set in an nx x ny x nz lattice:
 *   structural = (nx-1) ny nz + nx (ny-1) nz + nx ny (nz-1)
 *   face shear = 2 [(nx-1)(ny-1) nz + (nx-1) ny (nz-1) + nx (ny-1)(nz-1)]
 *   body shear = 4 (nx-1)(ny-1)(nz-1)
 *   bend       = (nx-2) ny nz + nx (ny-2) nz + nx ny (nz-2)
 *   triangles  = 4 [(nx-1)(ny-1) + (nx-1)(nz-1) + (ny-1)(nz-1)] */
START_TEST(lattice_counts) {
  static const int sizes[][3] = {{2, 2, 2}, {3, 3, 3}, {3, 4, 5}, {5, 4, 3},
                                 {2, 3, 6}};
  for (int g = 0; g < (int)(sizeof sizes / sizeof sizes[0]); g++)
    for (int sets = 0; sets < 16; sets++) {
      int x = sizes[g][0], y = sizes[g][1], z = sizes[g][2], want = 0;
      msocl_lattice_desc d = lattice(x, y, z);
      msocl_model *m;

      if (sets & 1)
        want += (x - 1) * y * z + x * (y - 1) * z + x * y * (z - 1);
      else
        d.k_structural = 0;
      if (sets & 2)
        want += 2 * ((x - 1) * (y - 1) * z + (x - 1) * y * (z - 1) +
                     x * (y - 1) * (z - 1));
      else
        d.k_shear_face = 0;
      if (sets & 4)
        want += 4 * (x - 1) * (y - 1) * (z - 1);
      d.k_shear_body = sets & 4 ? 30.0f : 0.0f; /* 0 by default */
      if (sets & 8)
        want += (x - 2) * y * z + x * (y - 2) * z + x * y * (z - 2);
      else
        d.k_bend = 0;
      OK(msocl_model_lattice(&m, &d));
      ck_assert_int_eq(m->n, x * y * z);
      ck_assert_msg(m->ns == want, "%dx%dx%d sets %d: %d springs, want %d", x,
                    y, z, sets, m->ns, want);
      ck_assert_int_eq(m->nt, 4 * ((x - 1) * (y - 1) + (x - 1) * (z - 1) +
                                   (y - 1) * (z - 1)));
      OK(msocl_model_validate(m));
      msocl_model_destroy(m);
    }
}
END_TEST

/* Lowest lattice corner (componentwise) of a spring's two ends: the point
 * whose k, j, i loops emit it. */
static int low_corner(int a, int b, int nx, int ny) {
  int ia = a % nx, ja = a / nx % ny, ka = a / (nx * ny);
  int ib = b % nx, jb = b / nx % ny, kb = b / (nx * ny);
  int i = ia < ib ? ia : ib, j = ja < jb ? ja : jb, k = ka < kb ? ka : kb;
  return (k * ny + j) * nx + i;
}

/* The sets come in order (structural, face shear, body shear, bend), each
 * with its stiffness and rest length (spacing times 1, sqrt 2, sqrt 3, 2)
 * and in point order; points at origin + spacing (i, j, k). */
START_TEST(lattice_order_and_rest) {
  msocl_lattice_desc d = lattice(3, 4, 5);
  msocl_model *m;
  const double h = 0.25, rest[4] = {1, SQRT2, SQRT3, 2};
  int count[4] = {0, 0, 0, 0};

  d.spacing = (float)h;
  d.origin[0] = -1;
  d.origin[1] = 2;
  d.origin[2] = 0.5f;
  d.k_structural = 1; /* the stiffness names the set */
  d.k_shear_face = 2;
  d.k_shear_body = 3;
  d.k_bend = 4;
  d.damping = 0.125f;
  OK(msocl_model_lattice(&m, &d));
  for (int s = 0; s < m->ns; s++) {
    int set = (int)m->k[s] - 1, a = m->ij[2 * s], b = m->ij[2 * s + 1];
    ck_assert(set >= 0 && set < 4);
    NEAR(m->rest[s], h * rest[set], 1e-6);
    NEAR(dist(m, a, b), h * rest[set], 1e-6);
    NEAR(m->damp[s], 0.125, 0);
    if (s > 0) {
      ck_assert_msg(m->k[s] >= m->k[s - 1], "spring %d: set out of order", s);
      if (m->k[s] == m->k[s - 1])
        ck_assert_msg(low_corner(a, b, 3, 4) >=
                          low_corner(m->ij[2 * s - 2], m->ij[2 * s - 1], 3, 4),
                      "spring %d: out of point order", s);
    }
    count[set]++;
  }
  ck_assert_int_eq(count[0], 2 * 4 * 5 + 3 * 3 * 5 + 3 * 4 * 4);
  ck_assert_int_eq(count[1], 2 * (2 * 3 * 5 + 2 * 4 * 4 + 3 * 3 * 4));
  ck_assert_int_eq(count[2], 4 * 2 * 3 * 4);
  ck_assert_int_eq(count[3], 1 * 4 * 5 + 3 * 2 * 5 + 3 * 4 * 3);
  /* The first structural springs: point 0 to +x, +y, +z. */
  ck_assert_int_eq(m->ij[0], 0);
  ck_assert_int_eq(m->ij[1], 1);
  ck_assert_int_eq(m->ij[3], 3);
  ck_assert_int_eq(m->ij[5], 12);

  for (int k = 0; k < 5; k++)
    for (int j = 0; j < 4; j++)
      for (int i = 0; i < 3; i++) {
        const float *p = m->pos + 3 * ((k * 4 + j) * 3 + i);
        NEAR(p[0], -1 + i * h, 1e-6);
        NEAR(p[1], 2 + j * h, 1e-6);
        NEAR(p[2], 0.5 + k * h, 1e-6);
        NEAR(m->mass[(k * 4 + j) * 3 + i], d.point_mass, 0);
      }
  msocl_model_destroy(m);

  d.damping = 0; /* no dashpots at all */
  OK(msocl_model_lattice(&m, &d));
  ck_assert_ptr_eq(m->damp, NULL);
  msocl_model_destroy(m);
  d.k_structural = d.k_shear_face = d.k_shear_body = d.k_bend = 0;
  OK(msocl_model_lattice(&m, &d));
  ck_assert_int_eq(m->ns, 0);
  ck_assert_int_eq(m->nt, 4 * (2 * 3 + 2 * 4 + 3 * 4));
  msocl_model_destroy(m);
}
END_TEST

/* Degree of an inner point: 6 structural, 12 face shear, 8 body shear,
 * 6 bend. */
START_TEST(lattice_degree) {
  msocl_lattice_desc d = lattice(5, 5, 5);
  msocl_model *m;

  OK(msocl_model_lattice(&m, &d)); /* the defaults' sets */
  ck_assert_int_eq(max_degree(m), 24);
  msocl_model_destroy(m);
  d.k_shear_body = 10;
  OK(msocl_model_lattice(&m, &d));
  ck_assert_int_eq(max_degree(m), 32);
  msocl_model_destroy(m);
  d.k_shear_face = d.k_shear_body = d.k_bend = 0;
  OK(msocl_model_lattice(&m, &d));
  ck_assert_int_eq(max_degree(m), 6);
  msocl_model_destroy(m);
  d.k_structural = 0;
  d.k_shear_face = 1;
  OK(msocl_model_lattice(&m, &d));
  ck_assert_int_eq(max_degree(m), 12);
  msocl_model_destroy(m);
  d.k_shear_face = 0;
  d.k_shear_body = 1;
  OK(msocl_model_lattice(&m, &d));
  ck_assert_int_eq(max_degree(m), 8);
  msocl_model_destroy(m);
}
END_TEST

/* The surface: only boundary points, every normal outward, closed, and
 * enclosing the box's volume. */
START_TEST(lattice_surface) {
  static const int sizes[][3] = {{2, 2, 2}, {3, 4, 5}, {6, 2, 3}};
  for (int g = 0; g < 3; g++) {
    int x = sizes[g][0], y = sizes[g][1], z = sizes[g][2];
    msocl_lattice_desc d = lattice(x, y, z);
    msocl_model *m;
    double centre[3];

    d.spacing = 0.5f;
    OK(msocl_model_lattice(&m, &d));
    ck_assert_int_eq(m->nt, 4 * ((x - 1) * (y - 1) + (x - 1) * (z - 1) +
                                 (y - 1) * (z - 1)));
    for (int t = 0; t < 3 * m->nt; t++) {
      int p = m->tri[t], i = p % x, j = p / x % y, k = p / (x * y);
      ck_assert(i == 0 || i == x - 1 || j == 0 || j == y - 1 || k == 0 ||
                k == z - 1);
    }
    for (int c = 0; c < 3; c++)
      centre[c] = d.origin[c] + 0.5 * d.spacing * (sizes[g][c] - 1);
    check_outward(m, centre);
    check_closed(m);
    NEAR(volume(m), 0.125 * (x - 1) * (y - 1) * (z - 1), 1e-5);
    /* Each square's two triangles face the same way (unit area 0.25). */
    for (int t = 0; t < m->nt; t++) {
      double n[3];
      tri_normal(m, t, n);
      NEAR(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 0.25, 1e-6);
    }
    msocl_model_destroy(m);
  }
}
END_TEST

/* ----------------------------------------------------------------- solid */

static msocl_solid_desc solid(int s) {
  msocl_solid_desc d;
  msocl_solid_desc_init(&d);
  d.subdivisions = s;
  return d;
}

START_TEST(solid_defaults) {
  msocl_solid_desc d;
  msocl_model *m;

  memset(&d, 0x55, sizeof d);
  msocl_solid_desc_init(&d);
  msocl_solid_desc_init(NULL);
  ck_assert_int_eq(d.subdivisions, 2);
  for (int c = 0; c < 3; c++) NEAR(d.radii[c], 0.1, 1e-8);
  NEAR(d.centre[0], 0, 0);
  NEAR(d.centre[1], 0.3, 1e-7);
  NEAR(d.centre[2], 0, 0);
  NEAR(d.surface_mass, 0.2, 1e-7);
  NEAR(d.centre_mass, 0.02, 1e-8);
  ck_assert(d.k_surface > d.k_support && d.k_support > 0 && d.damping > 0);

  OK(msocl_model_solid(&m, &d));
  ck_assert_int_eq(m->n, 163);
  ck_assert_int_eq(m->ns, 480 + 162);
  ck_assert_int_eq(m->nt, 320);
  ck_assert_int_eq(max_degree(m), 162); /* the centre */
  ck_assert_msg(1e-4 * omega_bound(m) < 0.5, "dt w = %g", 1e-4 * omega_bound(m));
  OK(msocl_model_validate(m));
  msocl_model_destroy(m);
}
END_TEST

START_TEST(solid_rejected) {
  msocl_solid_desc d = solid(1);
  msocl_model *m = (msocl_model *)&d;

  EXPECT(msocl_model_solid(NULL, &d), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_solid(&m, NULL), MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_eq(m, NULL);
#define REJECT(field, value, code)                                             \
  do {                                                                         \
    d = solid(1);                                                              \
    d.field = (value);                                                         \
    m = (msocl_model *)&d;                                                     \
    EXPECT(msocl_model_solid(&m, &d), code);                                   \
    ck_assert_ptr_eq(m, NULL);                                                 \
  } while (0)
  REJECT(subdivisions, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(subdivisions, 8, MSOCL_ERR_BAD_VALUE);
  SAYS("8 subdivisions");
  REJECT(subdivisions, INT_MAX, MSOCL_ERR_BAD_VALUE);
  REJECT(centre[1], NAN, MSOCL_ERR_NOT_FINITE);
  SAYS("centre[1]");
  REJECT(radii[2], INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(radii[0], 0, MSOCL_ERR_BAD_VALUE);
  REJECT(radii[1], -0.1f, MSOCL_ERR_BAD_VALUE);
  SAYS("radii[1]");
  REJECT(surface_mass, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(centre_mass, INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(k_surface, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(k_support, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(damping, INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(surface_mass, 0, MSOCL_ERR_BAD_MASS);
  REJECT(centre_mass, -1, MSOCL_ERR_BAD_MASS);
  REJECT(k_surface, -1, MSOCL_ERR_BAD_VALUE);
  SAYS("k_surface -1");
  REJECT(k_support, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(damping, -1, MSOCL_ERR_BAD_VALUE);
#undef REJECT
}
END_TEST

/* Icosphere of level s: 10 * 4^s + 2 surface points (+ the centre, last),
 * 30 * 4^s edges (the surface springs, first), one support spring per
 * surface point (then), 20 * 4^s triangles; every surface point on the
 * ellipsoid, every edge once, the surface closed and outward. */
START_TEST(solid_icosphere) {
  for (int s = 0; s <= 4; s++) {
    msocl_solid_desc d = solid(s);
    msocl_model *m;
    int four = 1 << 2 * s, np = 10 * four + 2, edges = 30 * four;
    const double c[3] = {1, -2, 0.5};

    for (int k = 0; k < 3; k++) d.centre[k] = (float)c[k];
    d.radii[0] = d.radii[1] = d.radii[2] = 0.5f;
    d.k_surface = 7;
    d.k_support = 5;
    OK(msocl_model_solid(&m, &d));
    ck_assert_int_eq(m->n, np + 1);
    ck_assert_int_eq(m->ns, edges + np);
    ck_assert_int_eq(m->nt, 20 * four);
    for (int i = 0; i < np; i++) {
      double r = 0;
      for (int k = 0; k < 3; k++)
        r += (m->pos[3 * i + k] - c[k]) * (m->pos[3 * i + k] - c[k]);
      NEAR(sqrt(r), 0.5, 1e-6);
      NEAR(m->mass[i], d.surface_mass / np, 1e-9);
    }
    for (int k = 0; k < 3; k++) NEAR(m->pos[3 * np + k], c[k], 0);
    NEAR(m->mass[np], d.centre_mass, 0);
    for (int i = 0; i < edges; i++) {
      NEAR(m->k[i], 7, 0);
      ck_assert(m->ij[2 * i] < np && m->ij[2 * i + 1] < np);
      ck_assert(m->ij[2 * i] < m->ij[2 * i + 1]);
    }
    for (int i = 0; i < np; i++) {
      NEAR(m->k[edges + i], 5, 0);
      ck_assert_int_eq(m->ij[2 * (edges + i)], i);
      ck_assert_int_eq(m->ij[2 * (edges + i) + 1], np);
      NEAR(m->rest[edges + i], 0.5, 1e-6);
    }
    check_closed(m); /* implies every edge once, as springs: */
    ck_assert_int_eq(3 * m->nt / 2, edges);
    check_outward(m, c);
    /* Surface springs link only triangle neighbours, so no duplicates:
     * every point has degree 5 or 6 on the surface, plus its support. */
    int *deg = calloc((size_t)np + 1, sizeof *deg);
    for (int i = 0; i < 2 * edges; i++) deg[m->ij[i]]++;
    for (int i = 0; i < np; i++) ck_assert(deg[i] == 5 || deg[i] == 6);
    free(deg);
    double v = volume(m), ball = 4.0 / 3 * 3.14159265358979 * 0.125;
    ck_assert(v > 0 && v < ball);
    if (s == 4) NEAR(v / ball, 1, 0.01);
    OK(msocl_model_validate(m));
    msocl_model_destroy(m);
  }
}
END_TEST

/* The finest level, and an ellipsoid. */
START_TEST(solid_ellipsoid_and_finest) {
  msocl_solid_desc d = solid(7);
  msocl_model *m;

  d.radii[0] = 0.1f;
  d.radii[1] = 0.2f;
  d.radii[2] = 0.3f;
  OK(msocl_model_solid(&m, &d));
  ck_assert_int_eq(m->n, 10 * 16384 + 2 + 1);
  ck_assert_int_eq(m->ns, 30 * 16384 + 10 * 16384 + 2);
  for (int i = 0; i < m->n - 1; i++) {
    double e = 0;
    for (int k = 0; k < 3; k++) {
      double u = (m->pos[3 * i + k] - d.centre[k]) / d.radii[k];
      e += u * u;
    }
    NEAR(e, 1, 1e-5);
  }
  NEAR(volume(m) / (4.0 / 3 * 3.14159265358979 * 0.1 * 0.2 * 0.3), 1, 1e-4);
  msocl_model_destroy(m);
}
END_TEST

/* Spring sets left out at stiffness 0; dashpots only when damping > 0. */
START_TEST(solid_sets) {
  msocl_solid_desc d = solid(1);
  msocl_model *m;

  d.k_support = 0;
  OK(msocl_model_solid(&m, &d));
  ck_assert_int_eq(m->ns, 120);
  ck_assert_int_eq(max_degree(m), 6);
  msocl_model_destroy(m);
  d.k_support = 3;
  d.k_surface = 0;
  d.damping = 0;
  OK(msocl_model_solid(&m, &d));
  ck_assert_int_eq(m->ns, 42);
  ck_assert_int_eq(m->ij[0], 0);
  ck_assert_int_eq(m->ij[1], 42);
  NEAR(m->k[41], 3, 0);
  ck_assert_ptr_eq(m->damp, NULL);
  msocl_model_destroy(m);
  d.k_support = 0;
  OK(msocl_model_solid(&m, &d));
  ck_assert_int_eq(m->ns, 0);
  ck_assert_int_eq(m->n, 43);
  msocl_model_destroy(m);
}
END_TEST

/* A unit cube, 12 outward triangles. */
static const float cube_xyz[24] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                   0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
static const int cube_tri[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7,
                                 0, 1, 5, 0, 5, 4, 3, 6, 2, 3, 7, 6,
                                 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
/* A tetrahedron, outward. */
static const float tet_xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const int tet_tri[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

START_TEST(solid_from_mesh) {
  msocl_solid_desc d = solid(0);
  msocl_model *m;

  d.k_surface = 7;
  d.k_support = 5;
  OK(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tet_tri, &d));
  ck_assert_int_eq(m->n, 5);
  ck_assert_int_eq(m->ns, 6 + 4);
  ck_assert_int_eq(m->nt, 4);
  ck_assert(memcmp(m->tri, tet_tri, sizeof tet_tri) == 0);
  for (int k = 0; k < 3; k++) NEAR(m->pos[12 + k], 0.25, 1e-7);
  NEAR(m->mass[0], d.surface_mass / 4, 1e-9);
  NEAR(m->mass[4], d.centre_mass, 0);
  for (int s = 6; s < 10; s++) {
    ck_assert_int_eq(m->ij[2 * s + 1], 4);
    NEAR(m->k[s], 5, 0);
  }
  const double tc[3] = {0.25, 0.25, 0.25};
  check_outward(m, tc);
  check_closed(m);
  NEAR(volume(m), 1.0 / 6, 1e-7);
  msocl_model_destroy(m);

  OK(msocl_model_solid_from_mesh(&m, 8, cube_xyz, 12, cube_tri, &d));
  ck_assert_int_eq(m->n, 9);
  ck_assert_int_eq(m->ns, 18 + 8);
  ck_assert_int_eq(max_degree(m), 8);
  const double cc[3] = {0.5, 0.5, 0.5};
  for (int k = 0; k < 3; k++) NEAR(m->pos[24 + k], 0.5, 1e-7);
  for (int s = 18; s < 26; s++) NEAR(m->rest[s], sqrt(0.75), 1e-6);
  for (int s = 0; s < 18; s++) {
    double r = m->rest[s];
    ck_assert(fabs(r - 1) < 1e-6 || fabs(r - SQRT2) < 1e-6);
  }
  check_outward(m, cc);
  check_closed(m);
  NEAR(volume(m), 1, 1e-6);
  OK(msocl_model_validate(m));
  msocl_model_destroy(m);
}
END_TEST

START_TEST(solid_from_mesh_rejected) {
  msocl_solid_desc d = solid(0);
  msocl_model *m = (msocl_model *)&d;
  int tri[36];
  float xyz[24];

  EXPECT(msocl_model_solid_from_mesh(NULL, 4, tet_xyz, 4, tet_tri, &d),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_solid_from_mesh(&m, 4, NULL, 4, tet_tri, &d),
         MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_eq(m, NULL);
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, NULL, &d),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tet_tri, NULL),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_solid_from_mesh(&m, 3, tet_xyz, 4, tet_tri, &d),
         MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 3, tet_tri, &d),
         MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_solid_from_mesh(&m, -1, tet_xyz, 4, tet_tri, &d),
         MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_solid_from_mesh(&m, INT_MAX, tet_xyz, 4, tet_tri, &d),
         MSOCL_ERR_TOO_MANY);
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, INT_MAX, tet_tri, &d),
         MSOCL_ERR_TOO_MANY);

  /* An open mesh: the cube less its last triangle. */
  EXPECT(msocl_model_solid_from_mesh(&m, 8, cube_xyz, 11, cube_tri, &d),
         MSOCL_ERR_BAD_VALUE);
  SAYS("not closed");
  ck_assert_msg(strstr(msocl_last_error(), "edge (1, 6)") ||
                    strstr(msocl_last_error(), "edge (5, 6)") ||
                    strstr(msocl_last_error(), "edge (1, 5)"),
                "\"%s\" names none of the open edges", msocl_last_error());
  ck_assert_ptr_eq(m, NULL);
  /* A triangle twice: three triangles on its edges. */
  memcpy(tri, tet_tri, sizeof tet_tri);
  memcpy(tri + 12, tet_tri, 3 * sizeof *tri);
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 5, tri, &d),
         MSOCL_ERR_BAD_VALUE);
  SAYS("3 triangles");
  /* One triangle flipped: closed but not consistently wound. */
  memcpy(tri, tet_tri, sizeof tet_tri);
  tri[1] = 1;
  tri[2] = 2;
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tri, &d),
         MSOCL_ERR_BAD_VALUE);
  SAYS("consistently wound");
  /* Indices, corners, coordinates. */
  memcpy(tri, tet_tri, sizeof tet_tri);
  tri[7] = 4;
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tri, &d),
         MSOCL_ERR_BAD_INDEX);
  SAYS("triangle 2");
  tri[7] = -1;
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tri, &d),
         MSOCL_ERR_BAD_INDEX);
  tri[7] = tri[6];
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tri, &d),
         MSOCL_ERR_BAD_VALUE);
  SAYS("not distinct");
  memcpy(xyz, tet_xyz, sizeof tet_xyz);
  xyz[5] = NAN;
  EXPECT(msocl_model_solid_from_mesh(&m, 4, xyz, 4, tet_tri, &d),
         MSOCL_ERR_NOT_FINITE);
  SAYS("point 1");
  /* The material fields are checked; the shape fields ignored. */
  d.surface_mass = 0;
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tet_tri, &d),
         MSOCL_ERR_BAD_MASS);
  d = solid(0);
  d.k_support = -2;
  EXPECT(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tet_tri, &d),
         MSOCL_ERR_BAD_VALUE);
  d = solid(0);
  d.subdivisions = 99;
  d.radii[0] = -1;
  d.centre[0] = NAN;
  OK(msocl_model_solid_from_mesh(&m, 4, tet_xyz, 4, tet_tri, &d));
  msocl_model_destroy(m);
}
END_TEST

/* ------------------------------------------------------------------- PLY */

static char tmp_path[4096];

static void tmp_setup(void) {
  const char *dir = getenv("TMPDIR");
  snprintf(tmp_path, sizeof tmp_path, "%s/msocl-ply-XXXXXX",
           dir && *dir ? dir : "/tmp");
  int fd = mkstemp(tmp_path);
  ck_assert_int_ge(fd, 0);
  close(fd);
}

static void tmp_teardown(void) { unlink(tmp_path); }

/* The whole file as one string. */
static char *slurp(const char *path) {
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  char *buf = malloc(1 << 16);
  size_t n = fread(buf, 1, (1 << 16) - 1, f);
  buf[n] = 0;
  fclose(f);
  return buf;
}

START_TEST(ply_roundtrip) {
  static const char head[] =
      "ply\nformat ascii 1.0\ncomment libmsocl frame\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\n";
  static const char tail[] = "element face 4\n"
                             "property list uchar int vertex_indices\n"
                             "end_header\n";
  const float xyz[12] = {0, 0, 0, 1.5f, 0, 0, 0, -2.25f, 0, 0, 0, 0.1f};
  const float nrm[12] = {0, 1, 0, 1, 0, 0, 0, 0, 1, -1, 0, 0};
  char *text, *body;
  float x, y, z, nx, ny, nz;
  int a, b, c, k, n;

  OK(msocl_write_ply(tmp_path, 4, xyz, NULL, 4, tet_tri));
  text = slurp(tmp_path);
  ck_assert_msg(strncmp(text, head, strlen(head)) == 0, "header:\n%s", text);
  ck_assert(strncmp(text + strlen(head), tail, strlen(tail)) == 0);
  body = text + strlen(head) + strlen(tail);
  for (int i = 0; i < 4; i++) {
    ck_assert_int_eq(sscanf(body, "%f %f %f%n", &x, &y, &z, &n), 3);
    ck_assert(x == xyz[3 * i] && y == xyz[3 * i + 1] && z == xyz[3 * i + 2]);
    body += n;
    ck_assert(*body++ == '\n');
  }
  for (int t = 0; t < 4; t++) {
    ck_assert_int_eq(sscanf(body, "%d %d %d %d%n", &k, &a, &b, &c, &n), 4);
    ck_assert_int_eq(k, 3);
    ck_assert(a == tet_tri[3 * t] && b == tet_tri[3 * t + 1] &&
              c == tet_tri[3 * t + 2]);
    body += n;
    ck_assert(*body++ == '\n');
  }
  ck_assert(*body == 0);
  free(text);

  OK(msocl_write_ply(tmp_path, 4, xyz, nrm, 4, tet_tri));
  text = slurp(tmp_path);
  ck_assert(strncmp(text, head, strlen(head)) == 0);
  body = text + strlen(head);
  static const char normals[] =
      "property float nx\nproperty float ny\nproperty float nz\n";
  ck_assert(strncmp(body, normals, strlen(normals)) == 0);
  body += strlen(normals);
  ck_assert(strncmp(body, tail, strlen(tail)) == 0);
  body += strlen(tail);
  for (int i = 0; i < 4; i++) {
    ck_assert_int_eq(
        sscanf(body, "%f %f %f %f %f %f%n", &x, &y, &z, &nx, &ny, &nz, &n), 6);
    ck_assert(x == xyz[3 * i] && nx == nrm[3 * i] && ny == nrm[3 * i + 1] &&
              nz == nrm[3 * i + 2]);
    body += n + 1;
  }
  free(text);

  /* Points only: an empty face element. */
  OK(msocl_write_ply(tmp_path, 4, xyz, NULL, 0, NULL));
  text = slurp(tmp_path);
  ck_assert_ptr_nonnull(strstr(text, "element face 0\n"));
  free(text);
}
END_TEST

/* A model's surface, as a user would write it. */
START_TEST(ply_of_model) {
  msocl_solid_desc d = solid(1);
  msocl_model *m;
  const int *ijk;
  int nt, np, faces = 0;
  float *xyz;
  char line[256];

  OK(msocl_model_solid(&m, &d));
  OK(msocl_model_point_count(m, &np));
  OK(msocl_model_triangles(m, &nt, &ijk));
  xyz = malloc(3 * (size_t)np * sizeof *xyz);
  OK(msocl_model_get_positions(m, xyz));
  OK(msocl_write_ply(tmp_path, np, xyz, NULL, nt, ijk));
  FILE *f = fopen(tmp_path, "r");
  int header = 1, vertices = 0, nv = -1, nf = -1;
  while (fgets(line, sizeof line, f)) {
    if (header) {
      sscanf(line, "element vertex %d", &nv);
      sscanf(line, "element face %d", &nf);
      if (strcmp(line, "end_header\n") == 0) header = 0;
    } else if (vertices < nv) {
      vertices++;
    } else {
      ck_assert(line[0] == '3' && line[1] == ' ');
      faces++;
    }
  }
  fclose(f);
  ck_assert_int_eq(nv, 43);
  ck_assert_int_eq(vertices, 43);
  ck_assert_int_eq(nf, 80);
  ck_assert_int_eq(faces, 80);
  free(xyz);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(ply_rejected) {
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  int tri[3] = {0, 1, 2};

  EXPECT(msocl_write_ply(NULL, 3, xyz, NULL, 1, tri), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_write_ply(tmp_path, 3, NULL, NULL, 1, tri),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_write_ply(tmp_path, 3, xyz, NULL, 1, NULL),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_write_ply(tmp_path, 0, xyz, NULL, 1, tri), MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_write_ply(tmp_path, 3, xyz, NULL, -1, tri),
         MSOCL_ERR_BAD_COUNT);
  tri[2] = 3;
  EXPECT(msocl_write_ply(tmp_path, 3, xyz, NULL, 1, tri), MSOCL_ERR_BAD_INDEX);
  SAYS("index 3");
  tri[2] = -1;
  EXPECT(msocl_write_ply(tmp_path, 3, xyz, NULL, 1, tri), MSOCL_ERR_BAD_INDEX);
  tri[2] = 2;
  const int twice[3] = {0, 2, 0};
  EXPECT(msocl_write_ply(tmp_path, 3, xyz, NULL, 1, twice),
         MSOCL_ERR_BAD_VALUE);
  SAYS("triangle 0 names point 0 twice");
  EXPECT(msocl_write_obj(tmp_path, 3, xyz, NULL, 1, twice),
         MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_write_ply("/nonexistent-msocl-dir/a.ply", 3, xyz, NULL, 1, tri),
         MSOCL_ERR_IO);
  SAYS("/nonexistent-msocl-dir/a.ply");
  SAYS(strerror(ENOENT));
  /* A full device: the write fails (at the latest when the file closes). */
  if (access("/dev/full", W_OK) == 0) {
    EXPECT(msocl_write_ply("/dev/full", 3, xyz, NULL, 1, tri), MSOCL_ERR_IO);
    SAYS("/dev/full");
    SAYS(strerror(ENOSPC));
  }
}
END_TEST

/* A write that fails part way (here the file-size limit, as a full disk
 * would) leaves the file that was there as it was, and nothing beside it:
 * frames are written beside the path and renamed over it once whole (a
 * failed rewrite used to leave 16 KiB of a 140 KiB file, cut mid-line). */
START_TEST(failed_write_keeps_file) {
  enum { P = 400 };
  float xyz[3 * P];
  int tri[3 * (P - 2)];
  for (int i = 0; i < 3 * P; i++)
    xyz[i] = 0.001f * (float)i;
  for (int t = 0; t < P - 2; t++) {
    tri[3 * t] = t;
    tri[3 * t + 1] = t + 1;
    tri[3 * t + 2] = t + 2;
  }
  OK(msocl_write_obj(tmp_path, 3, xyz, NULL, 1, tri));
  char *before = slurp(tmp_path);
  struct rlimit old, low;
  ck_assert_int_eq(getrlimit(RLIMIT_FSIZE, &old), 0);
  low = old;
  low.rlim_cur = 2048; /* the soft limit alone: it can be raised again */
  signal(SIGXFSZ, SIG_IGN); /* the write fails with EFBIG instead */
  ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &low), 0);
  const int obj = msocl_write_obj(tmp_path, P, xyz, NULL, P - 2, tri);
  const int ply = msocl_write_ply(tmp_path, P, xyz, NULL, P - 2, tri);
  ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &old), 0);
  ck_assert_int_eq(obj, MSOCL_ERR_IO);
  ck_assert_int_eq(ply, MSOCL_ERR_IO);
  SAYS("as it was");
  char *after = slurp(tmp_path);
  ck_assert_str_eq(after, before);
  /* no part-written file left beside it */
  const char *slash = strrchr(tmp_path, '/');
  char dir[4096];
  snprintf(dir, sizeof dir, "%.*s", (int)(slash - tmp_path), tmp_path);
  DIR *d = opendir(dir);
  ck_assert_ptr_nonnull(d);
  const size_t len = strlen(slash + 1);
  for (struct dirent *e; (e = readdir(d));)
    ck_assert_msg(strncmp(e->d_name, slash + 1, len) != 0 ||
                      e->d_name[len] == '\0',
                  "left behind: %s", e->d_name);
  closedir(d);
  free(before);
  free(after);
}
END_TEST

/* A blown-up state is refused by both writers, in points or in normals,
 * and the file left as it was: written, it would say "nan", which no
 * reader (the library's own OBJ reader included) takes back. */
START_TEST(frame_not_finite) {
  static const char blown[] = "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n";
  float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  float nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const int tri[3] = {0, 1, 2};
  msocl_obj_desc d;
  msocl_model *m = NULL;
  char *text;

  msocl_obj_desc_init(&d);
  EXPECT(msocl_model_from_obj_text(&m, blown, strlen(blown), &d),
         MSOCL_ERR_NOT_FINITE);
  xyz[3] = NAN;
  EXPECT(msocl_write_obj(tmp_path, 3, xyz, NULL, 1, tri),
         MSOCL_ERR_NOT_FINITE);
  SAYS(tmp_path);
  SAYS("point 1: coordinate 0 is nan");
  EXPECT(msocl_write_ply(tmp_path, 3, xyz, NULL, 1, tri),
         MSOCL_ERR_NOT_FINITE);
  SAYS("point 1: coordinate 0 is nan");
  xyz[3] = 1;
  nrm[8] = -INFINITY;
  EXPECT(msocl_write_obj(tmp_path, 3, xyz, nrm, 1, tri),
         MSOCL_ERR_NOT_FINITE);
  SAYS("point 2: normal 2 is -inf");
  EXPECT(msocl_write_ply(tmp_path, 3, xyz, nrm, 1, tri),
         MSOCL_ERR_NOT_FINITE);
  SAYS("point 2: normal 2 is -inf");
  text = slurp(tmp_path);
  ck_assert_str_eq(text, "");
  free(text);
  OK(msocl_write_obj(tmp_path, 3, xyz, NULL, 1, tri));
}
END_TEST

/* ------------------------------------------------------------------ main */

static Suite *builders_suite(void) {
  Suite *s = suite_create("builders");
  TCase *t;

  t = tcase_create("lattice");
  tcase_add_test(t, lattice_defaults);
  tcase_add_test(t, lattice_rejected);
  tcase_add_test(t, lattice_counts);
  tcase_add_test(t, lattice_order_and_rest);
  tcase_add_test(t, lattice_degree);
  tcase_add_test(t, lattice_surface);
  suite_add_tcase(s, t);

  t = tcase_create("solid");
  tcase_set_timeout(t, 30);
  tcase_add_test(t, solid_defaults);
  tcase_add_test(t, solid_rejected);
  tcase_add_test(t, solid_icosphere);
  tcase_add_test(t, solid_ellipsoid_and_finest);
  tcase_add_test(t, solid_sets);
  tcase_add_test(t, solid_from_mesh);
  tcase_add_test(t, solid_from_mesh_rejected);
  suite_add_tcase(s, t);

  t = tcase_create("ply");
  tcase_add_checked_fixture(t, tmp_setup, tmp_teardown);
  tcase_add_test(t, ply_roundtrip);
  tcase_add_test(t, ply_of_model);
  tcase_add_test(t, ply_rejected);
  tcase_add_test(t, frame_not_finite);
  tcase_add_test(t, failed_write_keeps_file);
  suite_add_tcase(s, t);
  return s;
}

int main(void) {
  return expect_run(builders_suite());
}

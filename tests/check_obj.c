/* Wavefront OBJ meshes: counts, masses and springs of valid files, every
 * broken form with its code and line, numbers, and the file variant. No
 * OpenCL. */
#include <check.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <locale.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "internal.h"
#include "obj_parse.h"

#include "expect.h"

#define PI 3.14159265358979323846

static const char triangle[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
/* A 2 x 2 square in z = 0, one quad: the fan (1 2 3), (1 3 4). */
static const char square[] = "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n";
static const char cube[] =
    "# cube of side 2: 8 vertices, 6 quads\n"
    "o cube\n"
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "vn 0 0 -1\ns off\nusemtl grey\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

static msocl_model *m;

static void teardown(void) {
  msocl_model_destroy(m);
  m = NULL;
}

static int load(const char *text, const msocl_obj_desc *d) {
  msocl_obj_desc def;
  msocl_obj_desc_init(&def);
  msocl_model_destroy(m);
  m = NULL;
  return msocl_model_from_obj_text(&m, text, strlen(text), d ? d : &def);
}

static void expect_counts(int points, int springs, int triangles) {
  ck_assert_int_eq(m->n, points);
  ck_assert_int_eq(m->ns, springs);
  ck_assert_int_eq(m->nt, triangles);
  OK(msocl_model_validate(m));
}

static void expect_triangle(int t, int a, int b, int c) {
  ck_assert_int_eq(m->tri[3 * t], a);
  ck_assert_int_eq(m->tri[3 * t + 1], b);
  ck_assert_int_eq(m->tri[3 * t + 2], c);
}

/* Index of spring (i, j) in either order, or -1. */
static int find_spring(int i, int j) {
  int s;
  for (s = 0; s < m->ns; s++)
    if ((m->ij[2 * s] == i && m->ij[2 * s + 1] == j) ||
        (m->ij[2 * s] == j && m->ij[2 * s + 1] == i))
      return s;
  return -1;
}

static double mass_sum(void) {
  double sum = 0;
  int i;
  for (i = 0; i < m->n; i++) sum += m->mass[i];
  return sum;
}

/* ------------------------------------------------------------ the desc */

START_TEST(desc_defaults_and_checks) {
  msocl_obj_desc d;
  msocl_model *keep = (msocl_model *)&d; /* must be overwritten with NULL */

  msocl_obj_desc_init(NULL);
  msocl_obj_desc_init(&d);
  NEAR(d.density, 0.1f, 0);
  NEAR(d.k_edge, 100, 0);
  NEAR(d.k_bend, 0, 0);
  NEAR(d.damping, 0, 0);
  EXPECT(msocl_model_from_obj_text(NULL, triangle, 5, &d),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_from_obj_text(&keep, NULL, 5, &d), MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_null(keep);
  EXPECT(msocl_model_from_obj_text(&m, triangle, 5, NULL),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_from_obj(NULL, "x.obj", &d), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_from_obj(&m, NULL, &d), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_from_obj(&m, "x.obj", NULL), MSOCL_ERR_NULL_HANDLE);

  d.density = 0;
  EXPECT(load(triangle, &d), MSOCL_ERR_BAD_MASS);
  d.density = -1;
  EXPECT(load(triangle, &d), MSOCL_ERR_BAD_MASS);
  d.density = NAN;
  EXPECT(load(triangle, &d), MSOCL_ERR_NOT_FINITE);
  msocl_obj_desc_init(&d);
  d.k_edge = 0;
  EXPECT(load(triangle, &d), MSOCL_ERR_BAD_VALUE);
  SAYS("k_edge");
  d.k_edge = INFINITY;
  EXPECT(load(triangle, &d), MSOCL_ERR_NOT_FINITE);
  msocl_obj_desc_init(&d);
  d.k_bend = -1;
  EXPECT(load(triangle, &d), MSOCL_ERR_BAD_VALUE);
  SAYS("k_bend");
  msocl_obj_desc_init(&d);
  d.damping = -0.5f;
  EXPECT(load(triangle, &d), MSOCL_ERR_BAD_VALUE);
  SAYS("damping");
  d.damping = NAN;
  EXPECT(load(triangle, &d), MSOCL_ERR_NOT_FINITE);
  ck_assert_ptr_null(m);
}
END_TEST

/* --------------------------------------------------------- valid files */

START_TEST(single_triangle) {
  float xyz[9];
  int s;

  OK(load(triangle, NULL));
  expect_counts(3, 3, 1);
  expect_triangle(0, 0, 1, 2);
  OK(msocl_model_get_positions(m, xyz));
  NEAR(xyz[3], 1, 0);
  NEAR(xyz[7], 1, 0);
  for (s = 0; s < 3; s++) {
    NEAR(m->mass[s], 0.1 * 0.5 / 3, 1e-9);
    NEAR(m->k[s], 100, 0);
  }
  NEAR(m->rest[find_spring(0, 1)], 1, 1e-7);
  NEAR(m->rest[find_spring(0, 2)], 1, 1e-7);
  NEAR(m->rest[find_spring(1, 2)], sqrt(2), 1e-6);
  ck_assert_ptr_null(m->damp);
}
END_TEST

START_TEST(quad_is_two_triangles) {
  OK(load(square, NULL));
  expect_counts(4, 5, 2);
  expect_triangle(0, 0, 1, 2);
  expect_triangle(1, 0, 2, 3);
  ck_assert_int_ge(find_spring(0, 2), 0); /* the fan's diagonal */
  ck_assert_int_lt(find_spring(1, 3), 0);
  /* Area 4: corners 0 and 2 touch both triangles (area 2 each). */
  NEAR(mass_sum(), 0.1 * 4, 1e-6);
  NEAR(m->mass[0], 0.1 * 4 / 3, 1e-7);
  NEAR(m->mass[1], 0.1 * 2 / 3, 1e-7);
}
END_TEST

/* Vertices on no face are common (left over from editing): they get the
 * mass of an average vertex and no springs. */
START_TEST(unreferenced_vertex) {
  OK(load("v 9 9 9\nv 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 2 3 4 5\n", NULL));
  expect_counts(5, 5, 2);
  NEAR(m->mass[0], 0.1 * (4.0 / 2) / 3, 1e-7);
  ck_assert_int_lt(find_spring(0, 1), 0);
  NEAR(mass_sum() - m->mass[0], 0.1 * 4, 1e-6);
}
END_TEST

START_TEST(cube_edges_and_masses) {
  msocl_obj_desc d;
  int s;

  msocl_obj_desc_init(&d);
  d.density = 2.5f;
  d.damping = 0.25f;
  OK(load(cube, &d));
  expect_counts(8, 18, 12);
  NEAR(mass_sum(), 2.5 * 24, 1e-4);
  ck_assert_ptr_nonnull(m->damp);
  for (s = 0; s < m->ns; s++) {
    ck_assert_int_lt(m->ij[2 * s], m->ij[2 * s + 1]);
    NEAR(m->damp[s], 0.25f, 0);
    /* Sides of length 2 or face diagonals of 2 sqrt 2. */
    ck_assert(fabs(m->rest[s] - 2) < 1e-6 || fabs(m->rest[s] - sqrt(8)) < 1e-6);
  }
}
END_TEST

START_TEST(negative_and_forward_indices) {
  OK(load("v 0 0 0\nv 2 0 0\nv 2 2 0\nf -3 -2 -1\nv 0 2 0\nf -4 -2 -1\n",
          NULL));
  expect_counts(4, 5, 2);
  expect_triangle(0, 0, 1, 2);
  expect_triangle(1, 0, 2, 3);
  /* A positive index may name a vertex that comes later. */
  OK(load("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", NULL));
  expect_counts(3, 3, 1);
}
END_TEST

START_TEST(index_forms_and_extras) {
  OK(load("mtllib a.mtl\n"
          "v 0 0 0 1\n"           /* w */
          "v 2 0 0\n"
          "v 2 2 0\n"
          "v 0 2 0 1 0.5 0.25\n"  /* colours some exporters add */
          "vt 0 0\nvt 1 0\nvn 0 0 1\nvp 0.5\n"
          "g side\ns 1\nusemtl red\n"
          "f 1/1 2/2 3/1\n"
          "f 1//1 3//1 4//1\n"
          "f 1/1/1 2/2/1 4/-1/-1\n"
          "l 1 2\np 1\n",
          NULL));
  expect_counts(4, 6, 3);
  expect_triangle(0, 0, 1, 2);
  expect_triangle(1, 0, 2, 3);
  expect_triangle(2, 0, 1, 3);
}
END_TEST

START_TEST(crlf_comments_blanks) {
  OK(load("# a comment\r\n\r\n   \r\n\tv 0 0 0\r\nv  2\t0 0 # trailing\r\n"
          "v 0 2 0\r\nf 1 2 3\r\n#last line, no newline",
          NULL));
  expect_counts(3, 3, 1);
  NEAR(m->pos[3], 2, 0);
  /* Lines still count right after CRLF. */
  EXPECT(load("v 0 0 0\r\nv 1 0 0\r\n\r\nv 0 y 0\r\n", NULL),
         MSOCL_ERR_BAD_VALUE);
  SAYS("line 4:");
}
END_TEST

/* Two models with the same points, springs and triangles, bit for bit. */
static void expect_same_model(const msocl_model *a, const msocl_model *b) {
  ck_assert_int_eq(a->n, b->n);
  ck_assert_int_eq(a->ns, b->ns);
  ck_assert_int_eq(a->nt, b->nt);
  ck_assert(memcmp(a->pos, b->pos, 3 * (size_t)a->n * sizeof *a->pos) == 0);
  ck_assert(memcmp(a->mass, b->mass, (size_t)a->n * sizeof *a->mass) == 0);
  ck_assert(memcmp(a->ij, b->ij, 2 * (size_t)a->ns * sizeof *a->ij) == 0);
  ck_assert(memcmp(a->rest, b->rest, (size_t)a->ns * sizeof *a->rest) == 0);
  ck_assert(memcmp(a->tri, b->tri, 3 * (size_t)a->nt * sizeof *a->tri) == 0);
}

#define BOM "\xEF\xBB\xBF"

/* A UTF-8 byte-order mark before the first statement is skipped, not
 * glued onto it: the square's first vertex stays. */
START_TEST(byte_order_mark) {
  msocl_model *plain;

  OK(load(square, NULL));
  plain = m;
  m = NULL;
  OK(load(BOM "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n", NULL));
  expect_same_model(m, plain);
  msocl_model_destroy(plain);
  /* Lines are counted as without it. */
  EXPECT(load(BOM "v 0 0\n", NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("line 1:");
  EXPECT(load(BOM, NULL), MSOCL_ERR_EMPTY);
  /* Only at the start: elsewhere it is not a statement OBJ knows. */
  EXPECT(load("v 0 0 0\n" BOM "v 2 0 0\nv 2 2 0\nf 1 2 3\n", NULL),
         MSOCL_ERR_BAD_INDEX);
}
END_TEST

START_TEST(polygon_fan) {
  char text[64 * 1024];
  int n = 1000, i, len = 0;

  for (i = 0; i < n; i++)
    len += snprintf(text + len, sizeof text - (size_t)len, "v %.9g %.9g 0\n",
                    cos(2 * PI * i / n), sin(2 * PI * i / n));
  len += snprintf(text + len, sizeof text - (size_t)len, "f");
  for (i = 0; i < n; i++)
    len += snprintf(text + len, sizeof text - (size_t)len, " %d", i + 1);
  ck_assert_int_lt(len, (int)sizeof text - 1);
  OK(load(text, NULL));
  /* The rim, plus a diagonal from the first corner to each but its
   * neighbours. */
  expect_counts(n, n + n - 3, n - 2);
  NEAR(mass_sum(), 0.1 * n / 2 * sin(2 * PI / n), 1e-6);
}
END_TEST

/* The springs by brute force over triangle pairs: edges (each counted
 * once), then pairs across edges shared by exactly two triangles. */
static int third(const int *t, int a, int b) {
  int c;
  for (c = 0; c < 3; c++)
    if (t[c] != a && t[c] != b) return t[c];
  return -1;
}

static int has(const int *t, int v) {
  return t[0] == v || t[1] == v || t[2] == v;
}

static int is_edge(int p, int q) {
  int u;
  for (u = 0; u < m->nt; u++)
    if (has(m->tri + 3 * u, p) && has(m->tri + 3 * u, q)) return 1;
  return 0;
}

/* For small meshes (k_edge 100, k_bend 5): O(T^2). */
static void expect_brute_force_springs(void) {
  int want[512][2], nwant = 0, edges = 0, bends = 0, t, u, c, s, w;

  for (s = 0; s < m->ns; s++) /* each spring once */
    ck_assert_int_eq(find_spring(m->ij[2 * s], m->ij[2 * s + 1]), s);
  for (t = 0; t < m->nt; t++)
    for (c = 0; c < 3; c++) {
      const int *k = m->tri + 3 * t;
      int a = k[c], b = k[(c + 1) % 3], first = -1, n = 0, other = -1, p, q;
      for (u = 0; u < m->nt; u++)
        if (has(m->tri + 3 * u, a) && has(m->tri + 3 * u, b)) {
          if (first < 0) first = u;
          else other = u;
          n++;
        }
      if (first != t) continue; /* the edge's first triangle counts it */
      edges++;
      s = find_spring(a, b);
      ck_assert_int_ge(s, 0);
      NEAR(m->k[s], 100, 0);
      if (n != 2) continue;
      p = third(k, a, b);
      q = third(m->tri + 3 * other, a, b);
      if (p == q || is_edge(p, q)) continue;
      for (w = 0; w < nwant; w++)
        if ((want[w][0] == p && want[w][1] == q) ||
            (want[w][0] == q && want[w][1] == p))
          break;
      if (w < nwant) continue;
      ck_assert_int_lt(nwant, 512);
      want[nwant][0] = p;
      want[nwant++][1] = q;
      s = find_spring(p, q);
      ck_assert_int_ge(s, 0);
      NEAR(m->k[s], 5, 0);
    }
  for (s = 0; s < m->ns; s++) bends += m->k[s] == 5;
  ck_assert_int_eq(bends, nwant);
  ck_assert_int_eq(m->ns - bends, edges);
  /* Edges come first, bends after them. */
  for (s = 0; s < m->ns; s++) NEAR(m->k[s], s < edges ? 100 : 5, 0);
}

/* ----------------------------------------------------- bending springs */

START_TEST(bending_springs) {
  msocl_obj_desc d;
  int s;

  msocl_obj_desc_init(&d);
  d.k_bend = 5;
  OK(load(square, &d));
  expect_counts(4, 6, 2);
  s = find_spring(1, 3); /* across the diagonal 0-2 */
  ck_assert_int_eq(s, 5);
  NEAR(m->k[s], 5, 0);
  NEAR(m->rest[s], sqrt(8), 1e-6);
  for (s = 0; s < 5; s++) NEAR(m->k[s], 100, 0);

  /* A tetrahedron: the corners across each edge are joined by an edge. */
  OK(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
          "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n",
          &d));
  expect_counts(4, 6, 4);
  /* The same triangle twice: both opposite corners are one point. */
  OK(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 3 2 1\n", &d));
  expect_counts(3, 3, 2);
  /* Three triangles on one edge: no bend across it. */
  OK(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
          "f 1 2 3\nf 2 1 4\nf 1 2 5\n",
          &d));
  expect_counts(5, 7, 3);
  expect_brute_force_springs();
  /* Cube: every bend found by the brute force, none twice. */
  OK(load(cube, &d));
  expect_brute_force_springs();
  ck_assert_int_gt(m->ns, 18 + 6);
}
END_TEST

/* A bumpy 6 x 6 grid of quads, fanned, against the brute force. */
START_TEST(bending_grid) {
  char text[8192];
  msocl_obj_desc d;
  int i, j, n = 7, len = 0;

  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      len += snprintf(text + len, sizeof text - (size_t)len, "v %d %d %g\n", i,
                      j, 0.1 * ((i * 7 + j * 3) % 5));
  for (j = 0; j + 1 < n; j++)
    for (i = 0; i + 1 < n; i++) {
      int a = j * n + i + 1;
      /* Alternate fan corners, so the diagonals alternate too. */
      if ((i + j) % 2)
        len += snprintf(text + len, sizeof text - (size_t)len,
                        "f %d %d %d %d\n", a + 1, a + n + 1, a + n, a);
      else
        len += snprintf(text + len, sizeof text - (size_t)len,
                        "f %d %d %d %d\n", a, a + 1, a + n + 1, a + n);
    }
  ck_assert_int_lt(len, (int)sizeof text - 1);
  msocl_obj_desc_init(&d);
  d.k_bend = 5;
  OK(load(text, &d));
  ck_assert_int_eq(m->nt, 2 * (n - 1) * (n - 1));
  expect_brute_force_springs();
  ck_assert_int_gt(m->ns, 3 * (n - 1) * (n - 1) + 2 * (n - 1));
}
END_TEST

/* ----------------------------------------------------------- rejections */

struct broken {
  const char *text;
  int code;
  int line;
};

static const struct broken broken[] = {
    {"", MSOCL_ERR_EMPTY, 0},
    {"# nothing here\n\n   \n", MSOCL_ERR_EMPTY, 0},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n", MSOCL_ERR_EMPTY, 0},
    {"v 0 0 0\nv 1 2 x\n", MSOCL_ERR_BAD_VALUE, 2},
    {"v 1 2\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v 0 0 0\n\nv 1e999 0 0\n", MSOCL_ERR_NOT_FINITE, 3},
    {"v 0 -1e39 0\n", MSOCL_ERR_NOT_FINITE, 1},
    {"v nan 0 0\n", MSOCL_ERR_NOT_FINITE, 1},
    {"v 0 0 NaN(1)\n", MSOCL_ERR_NOT_FINITE, 1},
    {"v inf 0 0\n", MSOCL_ERR_NOT_FINITE, 1},
    {"v 0 -Infinity 0\n", MSOCL_ERR_NOT_FINITE, 1},
    {"v 0 0 0 1e400\n", MSOCL_ERR_NOT_FINITE, 1},
    {"v 1.2.3 0 0\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v 1e 0 0\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v 1e+ 0 0\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v . 0 0\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v - 0 0\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v 0x10 0 0\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v 1,5 0 0\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v 0 0 0 w\n", MSOCL_ERR_BAD_VALUE, 1},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", MSOCL_ERR_BAD_INDEX, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", MSOCL_ERR_BAD_INDEX, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", MSOCL_ERR_BAD_INDEX, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 99999999999999999999 1 2\n",
     MSOCL_ERR_BAD_INDEX, 4},
    {"f 1 2 3\n", MSOCL_ERR_BAD_INDEX, 1},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\n# x\nf 1 2\n", MSOCL_ERR_BAD_VALUE, 5},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 1\n", MSOCL_ERR_BAD_VALUE,
     5},
    {"v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 0.1 0.2 0.3\nv 0.3 0.6 0.9\nf 1 2 3\n", MSOCL_ERR_BAD_VALUE,
     4},
    {"v 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/ 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1///1 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf /1 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1.0 2 3\n", MSOCL_ERR_BAD_VALUE, 4},
    /* An edge longer than a float holds (its rest length). */
    {"v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n", MSOCL_ERR_NOT_FINITE, 4},
    /* Masses below a float's smallest: named by the vertex's line. */
    {"v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\n", MSOCL_ERR_BAD_MASS, 1},
};

START_TEST(broken_forms) {
  const struct broken *b = &broken[_i];
  char line[32];
  msocl_model *keep = (msocl_model *)&line;

  EXPECT(msocl_model_from_obj_text(&keep, b->text, strlen(b->text),
                                   &(msocl_obj_desc){0.1f, 100, 1, 0}),
         b->code);
  ck_assert_ptr_null(keep);
  if (b->line > 0) {
    snprintf(line, sizeof line, "line %d:", b->line);
    SAYS(line);
  }
}
END_TEST

START_TEST(mass_overflow_and_nul) {
  msocl_obj_desc d;
  static const char nul[] = "v 0 0 0\nv 1\0 0 0\nv 0 1 0\nf 1 2 3\n";

  msocl_obj_desc_init(&d);
  d.density = 1e30f;
  EXPECT(load("v 0 0 0\nv 1e5 0 0\nv 0 1e5 0\nf 1 2 3\n", &d),
         MSOCL_ERR_NOT_FINITE);
  SAYS("line 1:");
  SAYS("vertex 1");
  ck_assert_ptr_null(m);
  EXPECT(msocl_model_from_obj_text(&m, nul, sizeof nul - 1, &d),
         MSOCL_ERR_BAD_VALUE);
  SAYS("line 2:");
  SAYS("NUL");
  /* Only len bytes count: the text need not end in NUL. */
  msocl_obj_desc_init(&d);
  OK(msocl_model_from_obj_text(&m, triangle, sizeof triangle - 2, &d));
  expect_counts(3, 3, 1);
}
END_TEST

/* Repeats `piece` n times after `head` (malloc'd). */
static char *repeat(const char *head, const char *piece, int n) {
  size_t lh = strlen(head), lp = strlen(piece), i;
  char *s = malloc(lh + lp * (size_t)n + 1);
  ck_assert_ptr_nonnull(s);
  memcpy(s, head, lh);
  for (i = 0; i < (size_t)n; i++) memcpy(s + lh + i * lp, piece, lp);
  s[lh + lp * (size_t)n] = '\0';
  return s;
}

START_TEST(huge_faces_and_long_lines) {
  char *s = repeat("v 0 0 0\nv 1 0 0\nv 0 1 0\nf", " 1", 1000000);
  EXPECT(load(s, NULL), MSOCL_ERR_TOO_MANY);
  SAYS("line 4:");
  free(s);
  s = repeat("v 0 0 0\nf", " 1", MSOCL__OBJ_MAX_CORNERS + 1);
  EXPECT(load(s, NULL), MSOCL_ERR_TOO_MANY);
  free(s);
  /* A megabyte comment, then a broken line: nothing is cut. */
  s = repeat("#", "comment ", 128 * 1024);
  s = realloc(s, strlen(s) + 64);
  strcat(s, "\nv 0 0\n");
  EXPECT(load(s, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("line 2:");
  free(s);
  /* A number of 100000 digits: 1 followed by zeros, scaled back to 1. */
  s = repeat("v 1", "0", 100000);
  s = realloc(s, strlen(s) + 64);
  strcat(s, "e-100000 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n");
  OK(load(s, NULL));
  NEAR(m->pos[0], 1, 0);
  free(s);
  /* So many leading zeros after the point that an exponent must undo. */
  s = repeat("v 0.", "0", 100000);
  s = realloc(s, strlen(s) + 64);
  strcat(s, "25e100000 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  OK(load(s, NULL));
  NEAR(m->pos[0], 0.25, 0);
  free(s);
}
END_TEST

/* -------------------------------------------------------------- numbers */

static float number(const char *text) {
  float x = -12345;
  ck_assert_msg(msocl__obj_number(text, strlen(text), &x) == MSOCL__NUM_OK,
                "'%s' should be a number", text);
  return x;
}

START_TEST(numbers) {
  static const char *const bad[] = {"", "+", "-", ".", "e5", "1e", "1e+",
                                    "1..2", "1.2.3", "0x1p3", "1f", "1 ",
                                    "--1", "1e5.0", "١"};
  float x;
  size_t i;

  NEAR(number("0"), 0, 0);
  NEAR(number("-0.5"), -0.5, 0);
  NEAR(number("+.5"), 0.5, 0);
  NEAR(number("5."), 5, 0);
  NEAR(number("1E+2"), 100, 0);
  NEAR(number("2.5e-3"), 2.5e-3f, 0);
  NEAR(number("007"), 7, 0);
  NEAR(number("3.4028234e38"), FLT_MAX, 0);
  NEAR(number("1e-50"), 0, 0);
  NEAR(number("1e-99999999999999999999999"), 0, 0);
  NEAR(number("0e99999999999999999999999"), 0, 0);
  NEAR(number("123456789012345678901234567890e-29"), 1.23456789f, 0);
  for (i = 0; i < sizeof bad / sizeof bad[0]; i++)
    ck_assert_msg(msocl__obj_number(bad[i], strlen(bad[i]), &x) ==
                      MSOCL__NUM_BAD,
                  "'%s' should not be a number", bad[i]);
  ck_assert_int_eq(msocl__obj_number("3.5e38", 6, &x), MSOCL__NUM_TOO_LARGE);
  ck_assert_int_eq(msocl__obj_number("1e99999999999999999999", 22, &x),
                   MSOCL__NUM_TOO_LARGE);
  ck_assert_int_eq(msocl__obj_number("-INF", 4, &x), MSOCL__NUM_NOT_FINITE);
  ck_assert_int_eq(msocl__obj_number("info", 4, &x), MSOCL__NUM_BAD);
}
END_TEST

/* The edges of float: what rounds to FLT_MAX is taken (FLT_MAX printed
 * with 8 digits is above it), what rounds to infinity refused; denormals
 * are kept, values below half the smallest become zero with their sign. */
START_TEST(numbers_near_limits) {
  static const char *const too_large[] = {"3.4028236e38", "-3.4028236e38",
                                          "3.40282357e38", "1e39"};
  float x;
  size_t i;

  ck_assert(number("3.4028235e38") == FLT_MAX);
  ck_assert(number("-3.4028235e38") == -FLT_MAX);
  ck_assert(number("3.40282356e38") == FLT_MAX);
  for (i = 0; i < sizeof too_large / sizeof too_large[0]; i++)
    ck_assert_msg(msocl__obj_number(too_large[i], strlen(too_large[i]), &x) ==
                      MSOCL__NUM_TOO_LARGE,
                  "'%s' should be too large", too_large[i]);
  /* The tie between FLT_MAX and 2^128 goes to even: infinity. */
  ck_assert_int_eq(
      msocl__obj_number("340282356779733661637539395458142568448", 39, &x),
      MSOCL__NUM_TOO_LARGE);
  ck_assert(number("1.17549435e-38") == FLT_MIN);
  ck_assert(number("1.1754942e-38") == nextafterf(FLT_MIN, 0));
  ck_assert(number("1.4e-45") == nextafterf(0, 1));
  ck_assert(number("-1e-45") == -nextafterf(0, 1));
  ck_assert(number("7.1e-46") == nextafterf(0, 1));
  x = number("1e-46");
  ck_assert(x == 0 && !signbit(x));
  x = number("-1e-46");
  ck_assert(x == 0 && signbit(x));
  x = number("-0");
  ck_assert(x == 0 && signbit(x));
  /* A vertex at FLT_MAX reads as a float and is then refused by the
   * model's range (squared distances would overflow), not as a number;
   * a too large one says so. */
  EXPECT(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 3.4028235e38 -3.4028235E+38 0\n"
              "f 1 2 3\n",
              NULL),
         MSOCL_ERR_BAD_VALUE);
  SAYS("point 3: |x| = 3.40282e+38 exceeds 1e+18");
  EXPECT(load("v 0 0 0\nv 0 3.4028236e38 0\n", NULL), MSOCL_ERR_NOT_FINITE);
  SAYS("line 2: '3.4028236e38' is too large for a float");
  EXPECT(load("v 0 0 0\nv 0 -inf 0\n", NULL), MSOCL_ERR_NOT_FINITE);
  SAYS("line 2: '-inf' is not a finite float");
}
END_TEST

/* A huge index is quoted as written, not as its clamped value. */
START_TEST(huge_index_messages) {
  EXPECT(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 100000000000000000000000\n",
              NULL),
         MSOCL_ERR_BAD_INDEX);
  SAYS("line 4: vertex index '100000000000000000000000' is too large");
  EXPECT(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -99999999999999999999/1\n",
              NULL),
         MSOCL_ERR_BAD_INDEX);
  SAYS("vertex index '-99999999999999999999' reaches before the first");
}
END_TEST

/* Every float printed with 9 digits reads back to itself: the parser
 * rounds correctly away from ties, whatever the exponent. */
START_TEST(numbers_round_trip) {
  unsigned seed = 12345;
  char text[64];
  int i;

  for (i = 0; i < 200000; i++) {
    unsigned bits;
    float f, g = 0;
    seed = seed * 1103515245u + 12345u;
    bits = seed ^ (seed >> 13) * 2654435761u;
    memcpy(&f, &bits, sizeof f);
    if (!isfinite(f)) continue;
    snprintf(text, sizeof text, "%.9g", f);
    ck_assert_int_eq(msocl__obj_number(text, strlen(text), &g), 0);
    ck_assert_msg(memcmp(&f, &g, sizeof f) == 0 || (f == 0 && g == 0),
                  "'%s' read as %.9g", text, g);
  }
}
END_TEST

/* strtod would read "0.5" as 0 under a locale with a decimal comma. */
START_TEST(locale_independent) {
  static const char *const names[] = {"de_DE.UTF-8", "de_DE", "fr_FR.UTF-8",
                                      "ru_RU.UTF-8"};
  size_t i;

  for (i = 0; i < sizeof names / sizeof names[0]; i++)
    if (setlocale(LC_NUMERIC, names[i])) break;
  OK(load("v 0 0 0\nv 0.5 0 0\nv 0 0.5 0\nf 1 2 3\n", NULL));
  NEAR(m->pos[3], 0.5, 0);
  setlocale(LC_NUMERIC, "C");
}
END_TEST

/* ---------------------------------------------------------------- files */

static char dir[256];

static void make_dir(void) {
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/check_obj.XXXXXX", tmp && *tmp ? tmp : "/tmp");
  ck_assert_ptr_nonnull(mkdtemp(dir));
}

static void remove_dir(void) {
  char path[512];
  snprintf(path, sizeof path, "%s/mesh.obj", dir);
  remove(path);
  snprintf(path, sizeof path, "%s/pipe.obj", dir);
  remove(path);
  rmdir(dir);
  teardown();
}

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  ck_assert_int_eq(fputs(text, f) >= 0, 1);
  ck_assert_int_eq(fclose(f), 0);
}

START_TEST(from_file) {
  char path[512];
  msocl_obj_desc d;
  msocl_model *plain;

  msocl_obj_desc_init(&d);
  snprintf(path, sizeof path, "%s/mesh.obj", dir);
  write_file(path, cube);
  OK(msocl_model_from_obj(&m, path, &d));
  expect_counts(8, 18, 12);
  msocl_model_destroy(m);
  m = NULL;

  write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n");
  EXPECT(msocl_model_from_obj(&m, path, &d), MSOCL_ERR_BAD_INDEX);
  ck_assert_ptr_null(m);
  ck_assert_msg(strncmp(msocl_last_error(), path, strlen(path)) == 0,
                "\"%s\" does not start with the path", msocl_last_error());
  SAYS("line 4:");

  /* The same mesh with a byte-order mark loads the same. */
  write_file(path, BOM "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  OK(msocl_model_from_obj(&m, path, &d));
  write_file(path, triangle);
  OK(msocl_model_from_obj(&plain, path, &d));
  expect_same_model(m, plain);
  msocl_model_destroy(plain);
  msocl_model_destroy(m);
  m = NULL;

  /* An empty file. */
  write_file(path, "");
  EXPECT(msocl_model_from_obj(&m, path, &d), MSOCL_ERR_EMPTY);
  SAYS(path);
}
END_TEST

START_TEST(unreadable_file) {
  char path[512];
  msocl_obj_desc d;
  msocl_model *keep = (msocl_model *)path;

  msocl_obj_desc_init(&d);
  snprintf(path, sizeof path, "%s/missing.obj", dir);
  EXPECT(msocl_model_from_obj(&keep, path, &d), MSOCL_ERR_IO);
  ck_assert_ptr_null(keep);
  SAYS(path);
  SAYS(strerror(ENOENT));
  /* A directory opens, then fails to read. */
  EXPECT(msocl_model_from_obj(&m, dir, &d), MSOCL_ERR_IO);
  SAYS(dir);
  SAYS(strerror(EISDIR));
  /* The desc is checked before the file is read. */
  d.density = -1;
  EXPECT(msocl_model_from_obj(&m, path, &d), MSOCL_ERR_BAD_MASS);
}
END_TEST

/* A child writes text into the FIFO at path (the reader's open waits for
 * it) and exits; reap it with wait_child. */
static pid_t feed_fifo(const char *path, const char *text) {
  pid_t pid = fork();

  ck_assert_int_ge(pid, 0);
  if (pid == 0) {
    FILE *f;
    signal(SIGPIPE, SIG_IGN); /* the reader may stop before the end */
    if ((f = fopen(path, "wb"))) {
      fputs(text, f);
      fclose(f);
    }
    _exit(0);
  }
  return pid;
}

static void wait_child(pid_t pid) {
  int status;
  ck_assert_int_eq(waitpid(pid, &status, 0), pid);
}

/* Only regular files and pipes are read, and at most
 * MSOCL_OBJ_MAX_FILE_BYTES of them: /dev/zero used to be read until the
 * memory ran out. */
START_TEST(file_kinds_and_size) {
  char path[512], *text;
  size_t len, n = strlen(cube);
  msocl_obj_desc d;
  pid_t pid;

  msocl_obj_desc_init(&d);
  EXPECT(msocl_model_from_obj(&m, "/dev/zero", &d), MSOCL_ERR_IO);
  SAYS("/dev/zero: not a regular file or a pipe");
  /* A regular file is judged by its size before it is read (this one is
   * sparse: no disk space). */
  snprintf(path, sizeof path, "%s/mesh.obj", dir);
  write_file(path, "");
  ck_assert_int_eq(truncate(path, (off_t)MSOCL_OBJ_MAX_FILE_BYTES + 1), 0);
  EXPECT(msocl_model_from_obj(&m, path, &d), MSOCL_ERR_TOO_MANY);
  SAYS(path);
  SAYS("1073741825 bytes, more than the 1073741824");
  /* The limit itself is allowed, one byte more is not. */
  write_file(path, cube);
  OK(msocl__obj_read_file(path, n, &text, &len));
  ck_assert(len == n && memcmp(text, cube, n) == 0);
  free(text);
  EXPECT(msocl__obj_read_file(path, n - 1, &text, &len), MSOCL_ERR_TOO_MANY);

  /* A pipe has no size: it loads, and fails once past the limit. */
  snprintf(path, sizeof path, "%s/pipe.obj", dir);
  ck_assert_int_eq(mkfifo(path, 0600), 0);
  pid = feed_fifo(path, cube);
  OK(msocl_model_from_obj(&m, path, &d));
  wait_child(pid);
  expect_counts(8, 18, 12);
  pid = feed_fifo(path, cube);
  OK(msocl__obj_read_file(path, n, &text, &len));
  wait_child(pid);
  ck_assert(len == n && memcmp(text, cube, n) == 0);
  free(text);
  pid = feed_fifo(path, cube);
  EXPECT(msocl__obj_read_file(path, n - 1, &text, &len), MSOCL_ERR_TOO_MANY);
  wait_child(pid);
  SAYS("pipe.obj: more than the");
}
END_TEST

/* ----------------------------------------------------------------- main */

static Suite *obj_suite(void) {
  Suite *s = suite_create("obj");
  TCase *t;

  t = tcase_create("valid");
  tcase_add_checked_fixture(t, NULL, teardown);
  tcase_add_test(t, desc_defaults_and_checks);
  tcase_add_test(t, single_triangle);
  tcase_add_test(t, quad_is_two_triangles);
  tcase_add_test(t, unreferenced_vertex);
  tcase_add_test(t, cube_edges_and_masses);
  tcase_add_test(t, negative_and_forward_indices);
  tcase_add_test(t, index_forms_and_extras);
  tcase_add_test(t, crlf_comments_blanks);
  tcase_add_test(t, byte_order_mark);
  tcase_add_test(t, polygon_fan);
  tcase_add_test(t, bending_springs);
  tcase_add_test(t, bending_grid);
  suite_add_tcase(s, t);

  t = tcase_create("broken");
  tcase_add_checked_fixture(t, NULL, teardown);
  tcase_add_loop_test(t, broken_forms, 0,
                      (int)(sizeof broken / sizeof broken[0]));
  tcase_add_test(t, mass_overflow_and_nul);
  tcase_add_test(t, huge_faces_and_long_lines);
  tcase_add_test(t, huge_index_messages);
  tcase_set_timeout(t, 60);
  suite_add_tcase(s, t);

  t = tcase_create("numbers");
  tcase_add_checked_fixture(t, NULL, teardown);
  tcase_add_test(t, numbers);
  tcase_add_test(t, numbers_near_limits);
  tcase_add_test(t, numbers_round_trip);
  tcase_add_test(t, locale_independent);
  suite_add_tcase(s, t);

  t = tcase_create("files");
  tcase_add_checked_fixture(t, make_dir, remove_dir);
  tcase_add_test(t, from_file);
  tcase_add_test(t, unreadable_file);
  tcase_add_test(t, file_kinds_and_size);
  suite_add_tcase(s, t);
  return s;
}

int main(void) {
  return expect_run(obj_suite());
}

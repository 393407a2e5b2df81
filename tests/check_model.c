/* The host-side model: every input rule with its code, atomic adds, rest
 * lengths, colliders, adjacency order and the cloth builder. No OpenCL. */
#include <check.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#include "expect.h"

/* The fixture: a unit square of 4 points, mass 1, no springs. */
static msocl_model *m;
static const float square[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static const float ones[8] = {1, 1, 1, 1, 1, 1, 1, 1};

static void setup(void) {
  OK(msocl_model_create(&m));
  OK(msocl_model_add_points(m, 4, square, ones, NULL));
}

static void teardown(void) {
  msocl_model_destroy(m);
  m = NULL;
}

static int points(const msocl_model *mm) {
  int n = -1;
  OK(msocl_model_point_count(mm, &n));
  return n;
}

static int springs(const msocl_model *mm) {
  int n = -1;
  OK(msocl_model_spring_count(mm, &n));
  return n;
}

static int degree(const msocl_model *mm) {
  int d = -1;
  OK(msocl_model_max_degree(mm, &d));
  return d;
}

/* ---------------------------------------------------------------- points */

START_TEST(create_and_defaults) {
  msocl_model *e;
  EXPECT(msocl_model_create(NULL), MSOCL_ERR_NULL_HANDLE);
  msocl_model_destroy(NULL);
  OK(msocl_model_create(&e));
  ck_assert_int_eq(points(e), 0);
  ck_assert_int_eq(springs(e), 0);
  ck_assert_int_eq(degree(e), 0);
  NEAR(e->gravity[0], 0, 0);
  NEAR(e->gravity[1], -9.81f, 0);
  NEAR(e->gravity[2], 0, 0);
  NEAR(e->viscous, 0, 0);
  ck_assert_int_eq(e->ncol, 0);
  EXPECT(msocl_model_validate(e), MSOCL_ERR_EMPTY);
  msocl_model_destroy(e);
}
END_TEST

START_TEST(points_rejected) {
  float xyz[9] = {0, 0, 0, 1, 2, 3, 4, 5, 6}, mass[3] = {1, 1, 1};
  int first = -1;

  EXPECT(msocl_model_add_points(NULL, 3, xyz, mass, NULL),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_points(m, 3, NULL, mass, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_points(m, 3, xyz, NULL, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_points(m, 0, xyz, mass, NULL), MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_add_points(m, -2, xyz, mass, NULL), MSOCL_ERR_BAD_COUNT);
  /* Counts are checked before the arrays are read. */
  EXPECT(msocl_model_add_points(m, INT_MAX, xyz, mass, NULL),
         MSOCL_ERR_TOO_MANY);
  EXPECT(msocl_model_add_points(m, INT_MAX / 3 - 3, xyz, mass, NULL),
         MSOCL_ERR_TOO_MANY);

  xyz[7] = NAN;
  EXPECT(msocl_model_add_points(m, 3, xyz, mass, &first), MSOCL_ERR_NOT_FINITE);
  SAYS("point 2: y = nan");
  xyz[7] = INFINITY;
  EXPECT(msocl_model_add_points(m, 3, xyz, mass, NULL), MSOCL_ERR_NOT_FINITE);
  xyz[7] = 5;
  xyz[0] = -INFINITY;
  EXPECT(msocl_model_add_points(m, 3, xyz, mass, NULL), MSOCL_ERR_NOT_FINITE);
  SAYS("point 0");
  xyz[0] = 0;
  mass[1] = NAN;
  EXPECT(msocl_model_add_points(m, 3, xyz, mass, NULL), MSOCL_ERR_NOT_FINITE);
  mass[1] = INFINITY;
  EXPECT(msocl_model_add_points(m, 3, xyz, mass, NULL), MSOCL_ERR_NOT_FINITE);
  mass[1] = 0;
  EXPECT(msocl_model_add_points(m, 3, xyz, mass, NULL), MSOCL_ERR_BAD_MASS);
  SAYS("point 1: mass 0");
  mass[1] = -1;
  EXPECT(msocl_model_add_points(m, 3, xyz, mass, NULL), MSOCL_ERR_BAD_MASS);
  SAYS("point 1: mass -1");

  /* Nothing of a failed add is kept. */
  ck_assert_int_eq(first, -1);
  ck_assert_int_eq(points(m), 4);
  mass[1] = 2;
  OK(msocl_model_add_points(m, 3, xyz, mass, &first));
  ck_assert_int_eq(first, 4);
  ck_assert_int_eq(points(m), 7);
  /* The success keeps the last failure's message, as errno. */
  ck_assert_str_eq(msocl_last_error(), "point 1: mass -1 must be > 0");
}
END_TEST

/* The last failure's message stays through later successes, of any call,
 * until the next failure replaces it. */
START_TEST(last_error_kept) {
  float p[3] = {0, 0, 0}, mass = 0;
  msocl_model *e = NULL;

  EXPECT(msocl_model_add_points(m, 1, p, &mass, NULL), MSOCL_ERR_BAD_MASS);
  SAYS("point 0: mass 0");
  mass = 1;
  OK(msocl_model_add_points(m, 1, p, &mass, NULL));
  OK(msocl_model_validate(m));
  OK(msocl_model_create(&e));
  msocl_model_destroy(e);
  ck_assert_int_eq(points(m), 5);
  ck_assert_str_eq(msocl_last_error(), "point 0: mass 0 must be > 0");
  EXPECT(msocl_model_pin(m, 9, 1), MSOCL_ERR_BAD_INDEX);
  ck_assert_str_eq(msocl_last_error(),
                   "pin: point index 9 out of range [0, 5)");
}
END_TEST

/* The limits of msocl.h at msocl_model_add_points: coordinates within
 * +-1e18, masses in [FLT_MIN, 1/FLT_MIN]; the bounds themselves pass. */
START_TEST(points_limits) {
  float xyz[6] = {0, 0, 0, 1, 1, 1}, mass[2] = {1, 1};

  mass[1] = 1e-39f; /* the issue's: 1/m overflows, energy went NaN */
  EXPECT(msocl_model_add_points(m, 2, xyz, mass, NULL), MSOCL_ERR_BAD_MASS);
  SAYS("point 1: mass 1e-39 is outside [FLT_MIN, 1/FLT_MIN]");
  mass[1] = 1e-45f;
  EXPECT(msocl_model_add_points(m, 2, xyz, mass, NULL), MSOCL_ERR_BAD_MASS);
  SAYS("point 1: mass 1.4013e-45");
  mass[1] = nextafterf(FLT_MIN, 0);
  EXPECT(msocl_model_add_points(m, 2, xyz, mass, NULL), MSOCL_ERR_BAD_MASS);
  mass[1] = nextafterf(1 / FLT_MIN, INFINITY);
  EXPECT(msocl_model_add_points(m, 2, xyz, mass, NULL), MSOCL_ERR_BAD_MASS);
  SAYS("point 1");
  mass[1] = 1;
  xyz[4] = nextafterf(1e18f, INFINITY);
  EXPECT(msocl_model_add_points(m, 2, xyz, mass, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("point 1: |y| = 1e+18 exceeds 1e+18");
  xyz[4] = -3e38f;
  EXPECT(msocl_model_add_points(m, 2, xyz, mass, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("point 1: |y| = 3e+38");
  ck_assert_int_eq(points(m), 4);

  mass[0] = FLT_MIN;
  mass[1] = 1 / FLT_MIN;
  xyz[4] = 1e18f;
  xyz[2] = -1e18f;
  OK(msocl_model_add_points(m, 2, xyz, mass, NULL));
  ck_assert_int_eq(points(m), 6);
  OK(msocl_model_set_gravity(m, 0, 0, 0)); /* a weight of 1/FLT_MIN g */
  OK(msocl_model_validate(m));
}
END_TEST

START_TEST(points_grow_and_read_back) {
  float p[3], *out;
  int i, first;

  /* One at a time, through several doublings of the capacity. */
  for (i = 0; i < 1000; i++) {
    float mass = 1.0f + (float)i;
    p[0] = (float)i;
    p[1] = -(float)i;
    p[2] = 0.5f * (float)i;
    OK(msocl_model_add_points(m, 1, p, &mass, &first));
    ck_assert_int_eq(first, 4 + i);
  }
  ck_assert_int_eq(points(m), 1004);
  out = malloc(1004 * 3 * sizeof *out);
  ck_assert_ptr_ne(out, NULL);
  OK(msocl_model_get_positions(m, out));
  ck_assert(memcmp(out, square, sizeof square) == 0);
  for (i = 0; i < 1000; i++) {
    NEAR(out[12 + 3 * i], i, 0);
    NEAR(out[13 + 3 * i], -i, 0);
    NEAR(out[14 + 3 * i], 0.5 * i, 0);
    NEAR(m->mass[4 + i], 1 + i, 0);
    ck_assert_int_eq(m->pinned[4 + i], 0);
  }
  free(out);
  OK(msocl_model_validate(m));
}
END_TEST

/* --------------------------------------------------------------- springs */

START_TEST(springs_rejected) {
  int ij[4] = {0, 1, 1, 2};
  float k[2] = {10, 10}, rest[2] = {-1, -1}, damp[2] = {0, 0};

  EXPECT(msocl_model_add_springs(NULL, 2, ij, k, NULL, NULL),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_springs(m, 2, NULL, k, NULL, NULL),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_springs(m, 2, ij, NULL, NULL, NULL),
         MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_springs(m, 0, ij, k, NULL, NULL), MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_add_springs(m, -1, ij, k, NULL, NULL),
         MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_add_springs(m, INT_MAX, ij, k, NULL, NULL),
         MSOCL_ERR_TOO_MANY);

  ij[3] = 4;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL), MSOCL_ERR_BAD_INDEX);
  SAYS("spring 1: point index 4 out of range [0, 4)");
  ij[3] = -1;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL), MSOCL_ERR_BAD_INDEX);
  SAYS("spring 1: point index -1 out of range [0, 4)");
  ij[3] = 412;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL), MSOCL_ERR_BAD_INDEX);
  SAYS("412");
  ij[3] = 1;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL),
         MSOCL_ERR_SELF_SPRING);
  SAYS("spring 1");
  ij[3] = 2;

  k[1] = -1;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 1: stiffness -1");
  k[1] = NAN;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL),
         MSOCL_ERR_NOT_FINITE);
  k[1] = INFINITY;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL),
         MSOCL_ERR_NOT_FINITE);
  k[1] = 10;
  damp[1] = -0.5f;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, damp), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 1: damping -0.5");
  damp[1] = INFINITY;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, damp),
         MSOCL_ERR_NOT_FINITE);
  damp[1] = 0;
  rest[0] = NAN;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, rest, damp),
         MSOCL_ERR_NOT_FINITE);
  rest[0] = -INFINITY;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, rest, damp),
         MSOCL_ERR_NOT_FINITE);
  rest[0] = -1;

  ck_assert_int_eq(springs(m), 0);
  ck_assert_int_eq(degree(m), 0);
  OK(msocl_model_add_springs(m, 2, ij, k, rest, damp));
  ck_assert_int_eq(springs(m), 2);
  ck_assert_int_eq(degree(m), 2);
}
END_TEST

/* A failed add after good ones keeps those and nothing of its own. */
START_TEST(springs_failed_add_is_atomic) {
  int ij[6] = {0, 1, 1, 2, 2, 3};
  float k[3] = {1, 2, 3};

  OK(msocl_model_add_springs(m, 1, ij, k, NULL, NULL));
  ij[5] = 9;
  EXPECT(msocl_model_add_springs(m, 3, ij, k, NULL, NULL), MSOCL_ERR_BAD_INDEX);
  SAYS("spring 2: point index 9 out of range [0, 4)");
  ck_assert_int_eq(springs(m), 1);
  ck_assert_int_eq(degree(m), 1);
  ck_assert_int_eq(m->ij[0], 0);
  ck_assert_int_eq(m->ij[1], 1);
  NEAR(m->k[0], 1, 0);
  OK(msocl_model_validate(m));
}
END_TEST

START_TEST(springs_rest_and_order) {
  /* Given rest, negative rest and no rest: the latter two get the current
   * distance, computed in double. */
  int ij[8] = {0, 1, 0, 2, 3, 1, 2, 3};
  float k[4] = {1, 2, 3, 4}, rest[4] = {0.25f, -1, -0.0f, 0};
  int s;

  OK(msocl_model_add_springs(m, 4, ij, k, rest, NULL));
  NEAR(m->rest[0], 0.25, 0);
  NEAR(m->rest[1], (float)sqrt(2.0), 0);
  NEAR(m->rest[2], 0, 0); /* -0 is not negative */
  NEAR(m->rest[3], 0, 0);
  OK(msocl_model_add_springs(m, 4, ij, k, NULL, NULL));
  NEAR(m->rest[4], 1, 0);
  NEAR(m->rest[5], (float)sqrt(2.0), 0);
  NEAR(m->rest[6], (float)sqrt(2.0), 0);
  NEAR(m->rest[7], 1, 0);
  for (s = 0; s < 8; s++) {
    ck_assert_int_eq(m->ij[2 * s], ij[2 * (s % 4)]);
    ck_assert_int_eq(m->ij[2 * s + 1], ij[2 * (s % 4) + 1]);
    NEAR(m->k[s], k[s % 4], 0);
  }
  ck_assert_int_eq(springs(m), 8);
  ck_assert_ptr_eq(m->damp, NULL);
}
END_TEST

/* Points far enough apart for their distance to overflow a float no
 * longer get in; at the coordinate limit the distance is still finite. */
START_TEST(springs_rest_overflow) {
  float far[6] = {-3e38f, 0, 0, 3e38f, 0, 0};
  int ij[2] = {4, 5};
  float k = 1;

  EXPECT(msocl_model_add_points(m, 2, far, ones, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("point 0: |x| = 3e+38");
  far[0] = -1e18f;
  far[3] = 1e18f;
  OK(msocl_model_add_points(m, 2, far, ones, NULL));
  OK(msocl_model_add_springs(m, 1, ij, &k, NULL, NULL));
  NEAR(m->rest[0], 2e18f, 0);
  OK(msocl_model_validate(m));
}
END_TEST

/* The limits of msocl.h at msocl_model_add_springs: stiffness, and
 * damping, times the larger of 1 m, the rest length and the distance at
 * most 1e30; the bound itself passes. */
START_TEST(springs_limits) {
  int ij[4] = {0, 1, 0, 2}; /* 1 m, then the diagonal */
  float k[2] = {10, 10}, rest[2] = {-1, -1}, damp[2] = {0, 0};

  k[1] = FLT_MAX; /* the issue's: k L overflows */
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 1: stiffness 3.40282e+38 x length 1.41421");
  k[1] = 1e30f; /* x sqrt 2 */
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 1: stiffness 1e+30");
  k[1] = 10;
  k[0] = nextafterf(1e30f, INFINITY);
  EXPECT(msocl_model_add_springs(m, 2, ij, k, NULL, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 0: stiffness");
  k[0] = 1e29f;
  rest[0] = 20; /* the rest length, when longer than the distance */
  EXPECT(msocl_model_add_springs(m, 2, ij, k, rest, NULL), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 0: stiffness 1e+29 x length 20");
  rest[0] = -1;
  damp[1] = 1e30f;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, rest, damp),
         MSOCL_ERR_BAD_VALUE);
  SAYS("spring 1: damping 1e+30 x speed 1.41421");
  damp[1] = 0;
  damp[0] = 1e31f; /* a unit spring is held to 1 m */
  rest[0] = 0;
  EXPECT(msocl_model_add_springs(m, 2, ij, k, rest, damp),
         MSOCL_ERR_BAD_VALUE);
  SAYS("spring 0: damping 1e+31 x speed 1");
  ck_assert_int_eq(springs(m), 0);

  /* At the limit: 1e30 x 1 m (a short rest length counts as 1 m too). */
  k[0] = 1e30f;
  damp[0] = 1e30f;
  rest[0] = 0.5f;
  k[1] = 1e30f / 1.5f;
  damp[1] = 7e29f;
  OK(msocl_model_add_springs(m, 2, ij, k, rest, damp));
  ck_assert_int_eq(springs(m), 2);
}
END_TEST

/* Models without dashpots carry no damping array; the first damped spring
 * brings one, zero for the springs before it. */
START_TEST(springs_damping_storage) {
  int ij[4] = {0, 1, 2, 3};
  float k[2] = {1, 1}, zero[2] = {0, 0}, damp[2] = {0.5f, 0};

  OK(msocl_model_add_springs(m, 2, ij, k, NULL, zero));
  ck_assert_ptr_eq(m->damp, NULL);
  OK(msocl_model_add_springs(m, 2, ij, k, NULL, damp));
  ck_assert_ptr_ne(m->damp, NULL);
  OK(msocl_model_add_springs(m, 2, ij, k, NULL, NULL));
  NEAR(m->damp[0], 0, 0);
  NEAR(m->damp[1], 0, 0);
  NEAR(m->damp[2], 0.5, 0);
  NEAR(m->damp[3], 0, 0);
  NEAR(m->damp[4], 0, 0);
  NEAR(m->damp[5], 0, 0);
  OK(msocl_model_validate(m));
}
END_TEST

START_TEST(springs_max_degree) {
  /* A star on point 2, one more spring elsewhere, a duplicate counted twice. */
  int ij[10] = {2, 0, 1, 2, 2, 3, 0, 1, 3, 2};
  float k[5] = {1, 1, 1, 1, 1};

  OK(msocl_model_add_springs(m, 5, ij, k, NULL, NULL));
  ck_assert_int_eq(degree(m), 4);
}
END_TEST

/* ------------------------------------------------------------- triangles */

START_TEST(triangles) {
  int t[6] = {0, 1, 2, 0, 2, 3}, n = -1;
  const int *got = NULL;

  EXPECT(msocl_model_add_triangles(NULL, 2, t), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_triangles(m, 2, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_triangles(m, 0, t), MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_add_triangles(m, -5, t), MSOCL_ERR_BAD_COUNT);
  EXPECT(msocl_model_add_triangles(m, INT_MAX, t), MSOCL_ERR_TOO_MANY);
  t[4] = 4;
  EXPECT(msocl_model_add_triangles(m, 2, t), MSOCL_ERR_BAD_INDEX);
  SAYS("triangle 1: point index 4 out of range [0, 4)");
  t[4] = -1;
  EXPECT(msocl_model_add_triangles(m, 2, t), MSOCL_ERR_BAD_INDEX);
  t[4] = 0;
  EXPECT(msocl_model_add_triangles(m, 2, t), MSOCL_ERR_BAD_VALUE);
  SAYS("triangle 1");
  t[4] = 3;
  EXPECT(msocl_model_add_triangles(m, 2, t), MSOCL_ERR_BAD_VALUE);
  t[4] = 2;

  OK(msocl_model_triangles(m, &n, &got));
  ck_assert_int_eq(n, 0);
  OK(msocl_model_add_triangles(m, 2, t));
  OK(msocl_model_add_triangles(m, 1, t));
  OK(msocl_model_triangles(m, &n, &got));
  ck_assert_int_eq(n, 3);
  ck_assert(memcmp(got, t, sizeof t) == 0);
  ck_assert(memcmp(got + 6, t, 3 * sizeof *t) == 0);
  EXPECT(msocl_model_triangles(NULL, &n, &got), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_triangles(m, NULL, &got), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_triangles(m, &n, NULL), MSOCL_ERR_NULL_HANDLE);
}
END_TEST

/* ------------------------------------------------------------ parameters */

START_TEST(pins) {
  EXPECT(msocl_model_pin(NULL, 0, 1), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_pin(m, 4, 1), MSOCL_ERR_BAD_INDEX);
  SAYS("point index 4 out of range [0, 4)");
  EXPECT(msocl_model_pin(m, -1, 1), MSOCL_ERR_BAD_INDEX);
  SAYS("-1");
  OK(msocl_model_pin(m, 3, 7));
  ck_assert_int_eq(m->pinned[3], 1);
  ck_assert_int_eq(m->pinned[0], 0);
  OK(msocl_model_pin(m, 3, 0));
  ck_assert_int_eq(m->pinned[3], 0);
}
END_TEST

START_TEST(gravity_and_viscous) {
  EXPECT(msocl_model_set_gravity(NULL, 0, 0, 0), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_set_gravity(m, NAN, 0, 0), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_model_set_gravity(m, 0, INFINITY, 0), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_model_set_gravity(m, 0, 0, -INFINITY), MSOCL_ERR_NOT_FINITE);
  NEAR(m->gravity[1], -9.81f, 0);
  OK(msocl_model_set_gravity(m, 1, 2, 3));
  NEAR(m->gravity[0], 1, 0);
  NEAR(m->gravity[1], 2, 0);
  NEAR(m->gravity[2], 3, 0);

  EXPECT(msocl_model_set_viscous_damping(NULL, 1), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_set_viscous_damping(m, -0.1f), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_model_set_viscous_damping(m, NAN), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_model_set_viscous_damping(m, INFINITY), MSOCL_ERR_NOT_FINITE);
  NEAR(m->viscous, 0, 0);
  OK(msocl_model_set_viscous_damping(m, 0.25f));
  NEAR(m->viscous, 0.25, 0);
  OK(msocl_model_validate(m));
}
END_TEST

/* --------------------------------------------------------------- queries */

START_TEST(queries_null) {
  int n;
  float xyz[12];

  EXPECT(msocl_model_point_count(NULL, &n), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_point_count(m, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_spring_count(NULL, &n), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_spring_count(m, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_max_degree(NULL, &n), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_max_degree(m, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_get_positions(NULL, xyz), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_get_positions(m, NULL), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_validate(NULL), MSOCL_ERR_NULL_HANDLE);
}
END_TEST

/* validate re-checks what the adds checked, whatever wrote the struct. */
START_TEST(validate_rechecks) {
  int ij[2] = {0, 1};
  float k = 1, n[3] = {0, 1, 0};

  OK(msocl_model_add_springs(m, 1, ij, &k, NULL, NULL));
  OK(msocl_model_add_plane(m, n, 0, 0.5f));
  OK(msocl_model_validate(m));
  m->pos[5] = NAN;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_NOT_FINITE);
  SAYS("point 1");
  m->pos[5] = 0;
  m->rest[0] = INFINITY;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_NOT_FINITE);
  m->rest[0] = 1;
  m->gravity[2] = NAN;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_NOT_FINITE);
  m->gravity[2] = 0;
  m->col[0].p[3] = INFINITY;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_NOT_FINITE);
  m->col[0].p[3] = 0;
  m->mass[2] = 0;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_BAD_MASS);
  m->mass[2] = 1e-39f;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_BAD_MASS);
  SAYS("point 2: mass 1e-39");
  m->mass[2] = 1;
  m->pos[7] = 2e18f;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_BAD_VALUE);
  SAYS("point 2: |y| = 2e+18");
  m->pos[7] = 1;
  m->k[0] = FLT_MAX;
  EXPECT(msocl_model_validate(m), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 0: stiffness 3.40282e+38");
  m->k[0] = 1;
  OK(msocl_model_validate(m));
}
END_TEST

/* Two points 1 m apart on one spring, no gravity: the combinations
 * msocl_model_validate checks, each refused past its limit and accepted
 * at it. */
static msocl_model *pair(float mass1, float k, float c) {
  const float xyz[6] = {0, 0, 0, 1, 0, 0};
  float mass[2] = {1, mass1};
  const int ij[2] = {0, 1};
  msocl_model *p = NULL;
  OK(msocl_model_create(&p));
  OK(msocl_model_add_points(p, 2, xyz, mass, NULL));
  OK(msocl_model_add_springs(p, 1, ij, &k, NULL, &c));
  OK(msocl_model_set_gravity(p, 0, 0, 0));
  return p;
}

START_TEST(validate_limits) {
  msocl_model *p;
  const float far[3] = {1e6f, 0, 0};

  /* a light point on a spring: k L / m */
  p = pair(2e-38f, 10, 0);
  EXPECT(msocl_model_validate(p), MSOCL_ERR_BAD_VALUE);
  SAYS("point 1: its springs and damping at the model's extent 1 give its "
       "mass 2e-38 an acceleration of 5e+38");
  OK(msocl_model_pin(p, 1, 1)); /* a pinned point's 1/m is never used */
  OK(msocl_model_validate(p));
  msocl_model_destroy(p);
  p = pair(9e-31f, 1, 0);
  EXPECT(msocl_model_validate(p), MSOCL_ERR_BAD_VALUE);
  SAYS("point 1:");
  msocl_model_destroy(p);
  p = pair(1e-30f, 1, 0); /* 1 / 1e-30 */
  OK(msocl_model_validate(p));
  msocl_model_destroy(p);
  /* dashpots count as k does */
  p = pair(1e-30f, 0.5f, 0.6f);
  EXPECT(msocl_model_validate(p), MSOCL_ERR_BAD_VALUE);
  SAYS("point 1:");
  msocl_model_destroy(p);
  p = pair(1e-30f, 0.5f, 0.5f);
  OK(msocl_model_validate(p));

  /* the model's extent stretches every spring: 1e25 x 1e6 */
  msocl_model_destroy(p);
  p = pair(1, 1e25f, 0);
  OK(msocl_model_validate(p));
  OK(msocl_model_add_points(p, 1, far, ones, NULL));
  EXPECT(msocl_model_validate(p), MSOCL_ERR_BAD_VALUE);
  SAYS("spring 0: stiffness 1e+25 x length 1e+06");
  msocl_model_destroy(p);
  p = pair(1, 1e24f, 0);
  OK(msocl_model_add_points(p, 1, far, ones, NULL));
  OK(msocl_model_validate(p));
  msocl_model_destroy(p);
  /* viscous damping at the extent a second */
  p = pair(1, 1, 0);
  OK(msocl_model_add_points(p, 1, far, ones, NULL));
  OK(msocl_model_set_viscous_damping(p, 1e24f));
  OK(msocl_model_validate(p));
  OK(msocl_model_set_viscous_damping(p, 2e24f));
  EXPECT(msocl_model_validate(p), MSOCL_ERR_BAD_VALUE);
  SAYS("viscous damping 2e+24");
  msocl_model_destroy(p);

  /* weight m |g| */
  p = pair(1e29f, 1, 0);
  OK(msocl_model_validate(p));
  OK(msocl_model_set_gravity(p, 0, -20, 0));
  EXPECT(msocl_model_validate(p), MSOCL_ERR_BAD_VALUE);
  SAYS("point 1: weight 1e+29 x 20");
  msocl_model_destroy(p);
}
END_TEST

/* ------------------------------------------------------------- colliders */

START_TEST(colliders_rejected) {
  float n[3] = {0, 0, 0}, c[3] = {0, 1, 0};

  EXPECT(msocl_model_add_plane(NULL, c, 0, 0), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_plane(m, NULL, 0, 0), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_plane(m, n, 0, 0), MSOCL_ERR_BAD_VALUE);
  SAYS("normal is zero");
  n[1] = NAN;
  EXPECT(msocl_model_add_plane(m, n, 0, 0), MSOCL_ERR_NOT_FINITE);
  n[1] = 1;
  EXPECT(msocl_model_add_plane(m, n, INFINITY, 0), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_model_add_plane(m, n, 0, -0.1f), MSOCL_ERR_BAD_VALUE);
  SAYS("friction -0.1");
  EXPECT(msocl_model_add_plane(m, n, 0, 1.1f), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_model_add_plane(m, n, 0, NAN), MSOCL_ERR_NOT_FINITE);

  EXPECT(msocl_model_add_sphere(NULL, c, 1, 0), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_sphere(m, NULL, 1, 0), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_sphere(m, c, 0, 0), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_model_add_sphere(m, c, -1, 0), MSOCL_ERR_BAD_VALUE);
  SAYS("radius -1");
  EXPECT(msocl_model_add_sphere(m, c, NAN, 0), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_model_add_sphere(m, c, INFINITY, 0), MSOCL_ERR_NOT_FINITE);
  EXPECT(msocl_model_add_sphere(m, c, 1, 2), MSOCL_ERR_BAD_VALUE);
  c[0] = -INFINITY;
  EXPECT(msocl_model_add_sphere(m, c, 1, 0), MSOCL_ERR_NOT_FINITE);
  c[0] = 0;

  EXPECT(msocl_model_add_table(NULL, c, 1, 0), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_table(m, NULL, 1, 0), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_add_table(m, c, 0, 0), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_model_add_table(m, c, -2, 0), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_model_add_table(m, c, 1, -1), MSOCL_ERR_BAD_VALUE);
  EXPECT(msocl_model_add_table(m, c, 1, INFINITY), MSOCL_ERR_NOT_FINITE);
  ck_assert_int_eq(m->ncol, 0);
}
END_TEST

START_TEST(colliders_stored) {
  float n[3] = {0, 2, 0}, tilted[3] = {3, 0, 4}, c[3] = {1, 2, 3};

  /* n.p >= offset is kept: both scale by 1 / |n|. */
  OK(msocl_model_add_plane(m, n, 1, 0));
  OK(msocl_model_add_plane(m, tilted, -10, 1));
  OK(msocl_model_add_sphere(m, c, 0.5f, 0.25f));
  OK(msocl_model_add_table(m, c, 0.75f, 1));
  ck_assert_int_eq(m->ncol, 4);
  ck_assert_int_eq(m->col[0].kind, MSOCL__PLANE);
  NEAR(m->col[0].p[0], 0, 0);
  NEAR(m->col[0].p[1], 1, 0);
  NEAR(m->col[0].p[2], 0, 0);
  NEAR(m->col[0].p[3], 0.5, 0);
  NEAR(m->col[0].friction, 0, 0);
  NEAR(m->col[1].p[0], 0.6, 1e-7);
  NEAR(m->col[1].p[2], 0.8, 1e-7);
  NEAR(m->col[1].p[3], -2, 1e-7);
  NEAR(m->col[1].friction, 1, 0);
  ck_assert_int_eq(m->col[2].kind, MSOCL__SPHERE);
  NEAR(m->col[2].p[0], 1, 0);
  NEAR(m->col[2].p[1], 2, 0);
  NEAR(m->col[2].p[2], 3, 0);
  NEAR(m->col[2].p[3], 0.5, 0);
  NEAR(m->col[2].friction, 0.25, 0);
  ck_assert_int_eq(m->col[3].kind, MSOCL__TABLE);
  NEAR(m->col[3].p[3], 0.75, 0);
  OK(msocl_model_validate(m));
}
END_TEST

START_TEST(colliders_too_many) {
  float n[3] = {0, 1, 0};
  int i;

  for (i = 0; i < MSOCL__MAX_COLLIDERS; i++)
    OK(i % 3 == 0   ? msocl_model_add_plane(m, n, (float)i, 0)
       : i % 3 == 1 ? msocl_model_add_sphere(m, n, 1, 0)
                    : msocl_model_add_table(m, n, 1, 0));
  EXPECT(msocl_model_add_plane(m, n, 0, 0), MSOCL_ERR_TOO_MANY);
  EXPECT(msocl_model_add_sphere(m, n, 1, 0), MSOCL_ERR_TOO_MANY);
  EXPECT(msocl_model_add_table(m, n, 1, 0), MSOCL_ERR_TOO_MANY);
  ck_assert_int_eq(m->ncol, MSOCL__MAX_COLLIDERS);
}
END_TEST

/* ------------------------------------------------------------- adjacency */

START_TEST(adjacency_order) {
  /* Springs deliberately not sorted by point: slot order must still be
   * spring order, each spring in both ends' lists. */
  int ij[10] = {2, 0, 1, 2, 0, 1, 3, 2, 0, 3};
  float k[5] = {1, 1, 1, 1, 1};
  static const int off[5] = {0, 3, 5, 8, 10};
  static const int other[10] = {2, 1, 3, 2, 0, 0, 1, 3, 2, 0};
  static const int spring[10] = {0, 2, 4, 1, 2, 0, 1, 3, 3, 4};
  struct msocl__adjacency a;
  int i;

  OK(msocl_model_add_springs(m, 5, ij, k, NULL, NULL));
  OK(msocl__adjacency_build(m, &a));
  ck_assert_int_eq(a.n, 4);
  ck_assert_int_eq(a.max_degree, 3);
  for (i = 0; i < 5; i++) ck_assert_int_eq(a.off[i], off[i]);
  for (i = 0; i < 10; i++) {
    ck_assert_int_eq(a.other[i], other[i]);
    ck_assert_int_eq(a.spring[i], spring[i]);
  }
  msocl__adjacency_free(&a);
  ck_assert_ptr_eq(a.off, NULL);
  msocl__adjacency_free(&a); /* twice is harmless */
}
END_TEST

START_TEST(adjacency_edges) {
  struct msocl__adjacency a;
  int i;

  OK(msocl__adjacency_build(m, &a)); /* no springs */
  ck_assert_int_eq(a.max_degree, 0);
  for (i = 0; i <= 4; i++) ck_assert_int_eq(a.off[i], 0);
  msocl__adjacency_free(&a);
  EXPECT(msocl__adjacency_build(NULL, &a), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl__adjacency_build(m, NULL), MSOCL_ERR_NULL_HANDLE);
  msocl__adjacency_free(NULL);
}
END_TEST

/* ----------------------------------------------------------------- cloth */

static msocl_cloth_desc cloth(int nx, int ny) {
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = nx;
  d.ny = ny;
  return d;
}

START_TEST(cloth_defaults) {
  msocl_cloth_desc d;
  msocl_model *c;
  int n;
  float xyz[3 * 32 * 32];

  memset(&d, 0x55, sizeof d);
  msocl_cloth_desc_init(&d);
  msocl_cloth_desc_init(NULL);
  ck_assert_int_eq(d.nx, 32);
  ck_assert_int_eq(d.ny, 32);
  NEAR(d.origin[0] + d.origin[1] + d.origin[2], 0, 0);
  NEAR(d.u[0], 1, 0);
  NEAR(d.u[1] + d.u[2], 0, 0);
  NEAR(d.v[2], 1, 0);
  NEAR(d.v[0] + d.v[1], 0, 0);
  NEAR(d.point_mass, 0.01, 1e-9);
  ck_assert(d.k_stretch > d.k_shear && d.k_shear > d.k_bend && d.k_bend > 0);
  NEAR(d.damping, 0, 0);

  OK(msocl_model_cloth_grid(&c, &d));
  ck_assert_int_eq(points(c), 32 * 32);
  OK(msocl_model_get_positions(c, xyz));
  for (n = 0; n < 32 * 32; n++) NEAR(xyz[3 * n + 1], 0, 0); /* horizontal */
  OK(msocl_model_validate(c));
  msocl_model_destroy(c);
}
END_TEST

START_TEST(cloth_rejected) {
  msocl_cloth_desc d = cloth(4, 4);
  msocl_model *c = (msocl_model *)&d; /* must come back NULL */

  EXPECT(msocl_model_cloth_grid(NULL, &d), MSOCL_ERR_NULL_HANDLE);
  EXPECT(msocl_model_cloth_grid(&c, NULL), MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_eq(c, NULL);

#define REJECT(field, value, code)                                             \
  do {                                                                         \
    d = cloth(4, 4);                                                           \
    d.field = (value);                                                         \
    c = (msocl_model *)&d;                                                     \
    EXPECT(msocl_model_cloth_grid(&c, &d), code);                              \
    ck_assert_ptr_eq(c, NULL);                                                 \
  } while (0)
  REJECT(nx, 1, MSOCL_ERR_BAD_COUNT);
  REJECT(ny, 1, MSOCL_ERR_BAD_COUNT);
  REJECT(nx, 0, MSOCL_ERR_BAD_COUNT);
  REJECT(ny, -3, MSOCL_ERR_BAD_COUNT);
  REJECT(nx, INT_MAX, MSOCL_ERR_TOO_MANY); /* INT_MAX x 4 points */
  d = cloth(17321, 17321); /* 3e8 points fit an int index, 1.8e9 springs not */
  EXPECT(msocl_model_cloth_grid(&c, &d), MSOCL_ERR_TOO_MANY);
  REJECT(origin[1], NAN, MSOCL_ERR_NOT_FINITE);
  SAYS("origin[1]");
  REJECT(u[0], INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(v[2], -INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(point_mass, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(k_bend, INFINITY, MSOCL_ERR_NOT_FINITE);
  REJECT(damping, NAN, MSOCL_ERR_NOT_FINITE);
  REJECT(point_mass, 0, MSOCL_ERR_BAD_MASS);
  REJECT(point_mass, -0.01f, MSOCL_ERR_BAD_MASS);
  REJECT(k_stretch, -1, MSOCL_ERR_BAD_VALUE);
  SAYS("k_stretch -1");
  REJECT(k_shear, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(k_bend, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(damping, -1, MSOCL_ERR_BAD_VALUE);
  REJECT(u[0], 0, MSOCL_ERR_BAD_VALUE); /* u = 0 */
  REJECT(v[2], 0, MSOCL_ERR_BAD_VALUE); /* v = 0 */
#undef REJECT
}
END_TEST

START_TEST(cloth_parallel_axes) {
  msocl_cloth_desc d = cloth(3, 3);
  msocl_model *c;

  d.v[0] = -2;
  d.v[2] = 0; /* v = (-2, 0, 0) against u = (1, 0, 0) */
  EXPECT(msocl_model_cloth_grid(&c, &d), MSOCL_ERR_BAD_VALUE);
  SAYS("parallel");
  d.v[0] = 2;
  d.v[2] = 1; /* skewed but spanning: fine */
  OK(msocl_model_cloth_grid(&c, &d));
  msocl_model_destroy(c);
}
END_TEST

/* Every spring-type combination on a few small grids, against hand counts. */
START_TEST(cloth_counts) {
  static const int grids[][2] = {{2, 2}, {3, 3}, {4, 5},
                                 {5, 4}, {2, 6}, {7, 3}};
  int g, types;

  for (g = 0; g < (int)(sizeof grids / sizeof grids[0]); g++)
    for (types = 0; types < 8; types++) {
      int nx = grids[g][0], ny = grids[g][1], want = 0, n, nt;
      const int *ijk;
      msocl_cloth_desc d = cloth(nx, ny);
      msocl_model *c;

      if (types & 1)
        want += (nx - 1) * ny + nx * (ny - 1);
      else
        d.k_stretch = 0;
      if (types & 2)
        want += 2 * (nx - 1) * (ny - 1);
      else
        d.k_shear = 0;
      if (types & 4)
        want += (nx - 2) * ny + nx * (ny - 2);
      else
        d.k_bend = 0;
      OK(msocl_model_cloth_grid(&c, &d));
      ck_assert_int_eq(points(c), nx * ny);
      ck_assert_msg(springs(c) == want, "%dx%d types %d: %d springs, want %d",
                    nx, ny, types, springs(c), want);
      OK(msocl_model_triangles(c, &nt, &ijk));
      ck_assert_int_eq(nt, 2 * (nx - 1) * (ny - 1));
      for (n = 0; n < 3 * nt; n++) ck_assert(ijk[n] >= 0 && ijk[n] < nx * ny);
      OK(msocl_model_validate(c));
      msocl_model_destroy(c);
    }
}
END_TEST

/* Springs in the documented order, with rest lengths of the flat grid:
 * spacing hx = 1, hy = 0.25. */
START_TEST(cloth_order_and_rest) {
  msocl_cloth_desc d = cloth(4, 5);
  msocl_model *c;
  int s, i, j, nx = 4, ny = 5;
  double hx = 1, hy = 0.25, diag = sqrt(hx * hx + hy * hy);

  d.u[0] = 3;
  d.origin[0] = -1;
  d.origin[1] = 2;
  d.origin[2] = 0.5f;
  OK(msocl_model_cloth_grid(&c, &d));
  s = 0;
  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++) {
      if (i + 1 < nx) {
        ck_assert_int_eq(c->ij[2 * s], j * nx + i);
        ck_assert_int_eq(c->ij[2 * s + 1], j * nx + i + 1);
        NEAR(c->k[s], d.k_stretch, 0);
        NEAR(c->rest[s++], hx, 1e-6);
      }
      if (j + 1 < ny) {
        ck_assert_int_eq(c->ij[2 * s + 1], (j + 1) * nx + i);
        NEAR(c->rest[s++], hy, 1e-6);
      }
    }
  for (j = 0; j + 1 < ny; j++)
    for (i = 0; i + 1 < nx; i++) {
      ck_assert_int_eq(c->ij[2 * s], j * nx + i);
      ck_assert_int_eq(c->ij[2 * s + 1], (j + 1) * nx + i + 1);
      NEAR(c->k[s], d.k_shear, 0);
      NEAR(c->rest[s++], diag, 1e-6);
      ck_assert_int_eq(c->ij[2 * s], j * nx + i + 1);
      ck_assert_int_eq(c->ij[2 * s + 1], (j + 1) * nx + i);
      NEAR(c->rest[s++], diag, 1e-6);
    }
  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++) {
      if (i + 2 < nx) {
        ck_assert_int_eq(c->ij[2 * s + 1], j * nx + i + 2);
        NEAR(c->k[s], d.k_bend, 0);
        NEAR(c->rest[s++], 2 * hx, 1e-6);
      }
      if (j + 2 < ny) {
        ck_assert_int_eq(c->ij[2 * s + 1], (j + 2) * nx + i);
        NEAR(c->rest[s++], 2 * hy, 1e-6);
      }
    }
  ck_assert_int_eq(s, springs(c));
  ck_assert_ptr_eq(c->damp, NULL); /* damping 0: no dashpots */

  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++) {
      const float *p = c->pos + 3 * (j * nx + i);
      NEAR(p[0], -1 + i * hx, 1e-6);
      NEAR(p[1], 2, 0);
      NEAR(p[2], 0.5 + j * hy, 1e-6);
      NEAR(c->mass[j * nx + i], d.point_mass, 0);
    }
  msocl_model_destroy(c);
}
END_TEST

START_TEST(cloth_degree_damping_winding) {
  msocl_cloth_desc d = cloth(5, 5);
  msocl_model *c;
  int t, s, n;
  const int *ijk;

  d.damping = 0.125f;
  OK(msocl_model_cloth_grid(&c, &d));
  ck_assert_int_eq(degree(c), 12); /* the paper's cloth: 12 neighbours */
  ck_assert_ptr_ne(c->damp, NULL);
  for (s = 0; s < springs(c); s++) NEAR(c->damp[s], 0.125, 0);

  /* Every triangle's normal points along u x v = (0, -1, 0). */
  OK(msocl_model_triangles(c, &n, &ijk));
  for (t = 0; t < n; t++) {
    const float *a = c->pos + 3 * ijk[3 * t], *b = c->pos + 3 * ijk[3 * t + 1],
                *e = c->pos + 3 * ijk[3 * t + 2];
    double ab[3], ae[3], ny;
    int k;
    for (k = 0; k < 3; k++) {
      ab[k] = (double)b[k] - a[k];
      ae[k] = (double)e[k] - a[k];
    }
    ny = ab[2] * ae[0] - ab[0] * ae[2];
    ck_assert_msg(ny < 0, "triangle %d wound the other way", t);
  }
  msocl_model_destroy(c);

  d = cloth(4, 4);
  OK(msocl_model_cloth_grid(&c, &d));
  ck_assert_int_eq(degree(c), 10);
  msocl_model_destroy(c);

  d.k_stretch = d.k_shear = d.k_bend = 0; /* no springs at all is allowed */
  OK(msocl_model_cloth_grid(&c, &d));
  ck_assert_int_eq(springs(c), 0);
  ck_assert_int_eq(degree(c), 0);
  msocl_model_destroy(c);
}
END_TEST

/* ------------------------------------------------------------------ main */

static Suite *model_suite(void) {
  Suite *s = suite_create("model");
  TCase *t;

  t = tcase_create("points");
  tcase_add_checked_fixture(t, setup, teardown);
  tcase_add_test(t, create_and_defaults);
  tcase_add_test(t, points_rejected);
  tcase_add_test(t, points_grow_and_read_back);
  tcase_add_test(t, last_error_kept);
  tcase_add_test(t, points_limits);
  suite_add_tcase(s, t);

  t = tcase_create("springs");
  tcase_add_checked_fixture(t, setup, teardown);
  tcase_add_test(t, springs_rejected);
  tcase_add_test(t, springs_failed_add_is_atomic);
  tcase_add_test(t, springs_rest_and_order);
  tcase_add_test(t, springs_rest_overflow);
  tcase_add_test(t, springs_limits);
  tcase_add_test(t, springs_damping_storage);
  tcase_add_test(t, springs_max_degree);
  suite_add_tcase(s, t);

  t = tcase_create("other");
  tcase_add_checked_fixture(t, setup, teardown);
  tcase_add_test(t, triangles);
  tcase_add_test(t, pins);
  tcase_add_test(t, gravity_and_viscous);
  tcase_add_test(t, queries_null);
  tcase_add_test(t, validate_rechecks);
  tcase_add_test(t, validate_limits);
  suite_add_tcase(s, t);

  t = tcase_create("colliders");
  tcase_add_checked_fixture(t, setup, teardown);
  tcase_add_test(t, colliders_rejected);
  tcase_add_test(t, colliders_stored);
  tcase_add_test(t, colliders_too_many);
  suite_add_tcase(s, t);

  t = tcase_create("adjacency");
  tcase_add_checked_fixture(t, setup, teardown);
  tcase_add_test(t, adjacency_order);
  tcase_add_test(t, adjacency_edges);
  suite_add_tcase(s, t);

  t = tcase_create("cloth");
  tcase_add_test(t, cloth_defaults);
  tcase_add_test(t, cloth_rejected);
  tcase_add_test(t, cloth_parallel_axes);
  tcase_add_test(t, cloth_counts);
  tcase_add_test(t, cloth_order_and_rest);
  tcase_add_test(t, cloth_degree_damping_winding);
  suite_add_tcase(s, t);
  return s;
}

int main(void) {
  return expect_run(model_suite());
}

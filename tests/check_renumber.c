/* A simulation numbers a general model's points by reverse Cuthill-McKee:
 * results in the model's numbering are bitwise those of the model's own
 * numbering (every point meets its springs in the same order), and a
 * split over devices then has narrow halos. The tablecloth, shuffled, is
 * a model whose given numbering is as bad as it gets. */
#include "internal.h" /* msocl__model_permuted: to shuffle a model */
#include "scenes.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N 24
#define STEPS 300

static msocl_runtime *rt;
static int ndev;

static char spec[256];

static void setup(void)
{
  ck_assert_int_eq(msocl_runtime_create(&rt, spec), MSOCL_OK);
  ck_assert_int_eq(msocl_runtime_device_count(rt, &ndev), MSOCL_OK);
}

static void teardown(void)
{
  msocl_runtime_destroy(rt);
  rt = NULL;
}

/* The tablecloth with its points in a fixed pseudo-random order. */
static msocl_model *shuffled_tablecloth(void)
{
  msocl_model *grid = scene_tablecloth(N), *m = NULL;
  int perm[N * N];
  for (int i = 0; i < N * N; i++)
    perm[i] = i;
  unsigned x = 12345u;
  for (int i = N * N - 1; i > 0; i--) {
    x = x * 1103515245u + 12345u;
    int j = (int)((x >> 8) % (unsigned)(i + 1)), t = perm[i];
    perm[i] = perm[j];
    perm[j] = t;
  }
  ck_assert_int_eq(msocl__model_permuted(grid, perm, &m), MSOCL_OK);
  msocl_model_destroy(grid);
  return m;
}

struct result {
  float pos[3 * N * N], vel[3 * N * N], nrm[3 * N * N];
  int order[N * N];
  msocl_split_info split;
};

static void run(const msocl_model *m, int renumber, int parts,
                msocl_integrator in, struct result *r)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  /* forward Euler grows without damping: a shorter step keeps it finite */
  o.dt = scene_tablecloth_dt(N) / (in == MSOCL_EXPLICIT_EULER ? 20 : 1);
  o.tuning.renumber = renumber ? MSOCL_ON : MSOCL_OFF;
  o.tuning.ndevices = parts;
  o.integrator = in;
  o.tuning.layout = MSOCL_LAYOUT_BUFFER;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  rc = msocl_sim_step(s, STEPS);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  ck_assert_int_eq(msocl_sim_read_positions(s, r->pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, r->vel), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_normals(s, r->nrm), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_point_order(s, r->order), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_split_info(s, &r->split), MSOCL_OK);
  msocl_sim_destroy(s);
}

static int is_identity(const int *order)
{
  for (int i = 0; i < N * N; i++)
    if (order[i] != i)
      return 0;
  return 1;
}

static void same_bits(const struct result *a, const struct result *b,
                      const char *what)
{
  ck_assert_msg(memcmp(a->pos, b->pos, sizeof a->pos) == 0 &&
                    memcmp(a->vel, b->vel, sizeof a->vel) == 0,
                "%s: positions differ by %g, velocities by %g", what,
                scene_max_diff(a->pos, b->pos, 3 * N * N),
                scene_max_diff(a->vel, b->vel, 3 * N * N));
  /* a point meets its triangles in the same order too */
  ck_assert_msg(memcmp(a->nrm, b->nrm, sizeof a->nrm) == 0,
                "%s: normals differ by %g", what,
                scene_max_diff(a->nrm, b->nrm, 3 * N * N));
}

static struct result given, renumbered, split_given, split_renumbered;

/* _i: the integrator */
START_TEST(renumbered_is_bitwise_the_given_numbering)
{
  msocl_integrator in = (msocl_integrator)_i;
  msocl_model *m = shuffled_tablecloth();
  run(m, 0, 1, in, &given);
  run(m, 1, 1, in, &renumbered);
  ck_assert(is_identity(given.order));
  ck_assert(!is_identity(renumbered.order));
  /* the order is a permutation */
  unsigned char seen[N * N] = {0};
  for (int i = 0; i < N * N; i++) {
    ck_assert(renumbered.order[i] >= 0 && renumbered.order[i] < N * N);
    ck_assert(!seen[renumbered.order[i]]);
    seen[renumbered.order[i]] = 1;
  }
  same_bits(&given, &renumbered, "one device");
  /* the cloth moved: the comparison is not between two resting states */
  float p0[3 * N * N];
  msocl_model_get_positions(m, p0);
  ck_assert(scene_max_diff(p0, given.pos, 3 * N * N) > 1e-4);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(split_halos_narrow)
{
  if (ndev < 2) {
    printf("split_halos_narrow: one CPU device only; not split\n");
    return;
  }
  msocl_model *m = shuffled_tablecloth();
  run(m, 0, 1, MSOCL_SYMPLECTIC_EULER, &given);
  run(m, 0, 2, MSOCL_SYMPLECTIC_EULER, &split_given);
  run(m, 1, 2, MSOCL_SYMPLECTIC_EULER, &split_renumbered);
  same_bits(&given, &split_given, "split, given numbering");
  same_bits(&given, &split_renumbered, "split, renumbered");
  double h0 = split_given.split.halo_points[0] +
              split_given.split.halo_points[1],
         h1 = split_renumbered.split.halo_points[0] +
              split_renumbered.split.halo_points[1];
  printf("shuffled %dx%d tablecloth over 2 devices: halo %.0f points as "
         "given, %.0f renumbered\n", N, N, h0, h1);
  /* shuffled, each half reaches nearly the whole other half; renumbered,
   * a band a few rows wide (bend springs reach two rows, and RCM's
   * levels run diagonally: 4 * 2 * N is generous) */
  ck_assert(h0 > 0.8 * N * N);
  ck_assert(h1 <= 8 * N);
  msocl_model_destroy(m);
}
END_TEST

/* Writes and reads use the model's numbering, whatever the simulation's. */
START_TEST(state_round_trip)
{
  msocl_model *m = shuffled_tablecloth();
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = scene_tablecloth_dt(N);
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_point_order(s, given.order), MSOCL_OK);
  ck_assert(!is_identity(given.order));
  for (int i = 0; i < 3 * N * N; i++) {
    given.pos[i] = (float)i;          /* point i's own values */
    given.vel[i] = -0.5f * (float)i;
  }
  ck_assert_int_eq(msocl_sim_write_positions(s, given.pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_write_velocities(s, given.vel), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_positions(s, renumbered.pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, renumbered.vel), MSOCL_OK);
  ck_assert(memcmp(given.pos, renumbered.pos, sizeof given.pos) == 0);
  ck_assert(memcmp(given.vel, renumbered.vel, sizeof given.vel) == 0);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(grid_and_option)
{
  /* a cloth grid keeps its numbering: banded, and GRID needs it */
  msocl_model *grid = scene_tablecloth(N);
  run(grid, 1, 1, MSOCL_SYMPLECTIC_EULER, &given);
  ck_assert(is_identity(given.order));
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  ck_assert_int_eq(o.tuning.renumber, MSOCL_AUTO);
  o.dt = scene_tablecloth_dt(N);
  o.tuning.renumber = (msocl_choice)3;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, grid, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  ck_assert_int_eq(msocl_sim_point_order(NULL, given.order),
                   MSOCL_ERR_NULL_HANDLE);
  msocl_model_destroy(grid);
}
END_TEST

int main(void)
{
  scene_require_device("check_renumber");
  if (scene_cpu_spec(spec, sizeof spec, 2) == 0) {
    printf("check_renumber: SKIP: no CPU device\n");
    return 77;
  }
  Suite *su = suite_create("renumber");
  TCase *tc = tcase_create("renumber");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 300);
  /* implicit Euler's CG sums dot products in point order: renumbering
   * changes its rounding, so it is left out of the bitwise comparison */
  tcase_add_loop_test(tc, renumbered_is_bitwise_the_given_numbering,
                      MSOCL_SYMPLECTIC_EULER, MSOCL_RK4 + 1);
  tcase_add_test(tc, split_halos_narrow);
  tcase_add_test(tc, state_round_trip);
  tcase_add_test(tc, grid_and_option);
  suite_add_tcase(su, tc);
  return scene_run(su);
}
